// Shared helpers for the SCANport tests: run a message the way the manual's Figure B.3 program
// does, and compare word lists in the manual's hexadecimal spelling so a mismatch prints like
// the figure ("000e 000f 0000 0002 ...").
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "modules/scanport/drive.h"
#include "modules/scanport/drive_json.h"
#include "modules/scanport/messages.h"

namespace softslc::scanport::test {

using Words = std::vector<std::uint16_t>;

// "000e 000f 0000" - the figures' data-table spelling.
inline std::string hex(const Words& words) {
  std::string s;
  char buf[8];
  for (std::size_t i = 0; i < words.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%04x", static_cast<unsigned>(words[i]));
    s += (i ? " " : "") + std::string(buf);
  }
  return s;
}

// The first n words of a buffer.
inline Words first(const Words& w, std::size_t n) {
  return Words(w.begin(), w.begin() + static_cast<std::ptrdiff_t>(std::min(n, w.size())));
}

// The shipped 1305 drive, freshly powered up.
inline Drive drive_1305() { return Drive(builtin_drive("1305")); }

// Figure B.3: the program copies N10 into M0 buffer 0 (M0:e.000), sets Message Enable for
// channel 1 with MSG ID 0, waits for DONE, and copies the channel 1 response buffer M1:e.100
// into N11. N10 is a whole 100-word buffer whose unused words are 0; N11 is the whole response
// buffer as the module leaves it.
inline Words run_figure_b3(Drive* drive, const Words& n10) {
  std::array<std::uint16_t, kBufferWords> m0{};
  std::copy(n10.begin(), n10.end(), m0.begin());
  const Request request = decode_request(m0);
  const Response response = transact(drive, request);
  std::array<std::uint16_t, kBufferWords> m1{};
  m1.fill(0xDEAD);  // stale words from an earlier message must be cleared by write_response
  write_response(response, m1);
  return Words(m1.begin(), m1.end());
}

}  // namespace softslc::scanport::test
