// Helpers for the 1747-SDN tests: programs and benches from examples/ladder/1747-sdn, loaded through
// the same setup the CLI and the test runner use (tests/modules/modules_test_util.h).
#pragma once

#include <string>

#include "../modules/modules_test_util.h"
#include "modules/sdn/sdn_scanner.h"

namespace softslc::test {

inline std::string sdn_example(const std::string& name) {
  return read_text(std::string(SOFTSLC_SOURCE_DIR) + "/examples/ladder/1747-sdn/" + name);
}
// Benches with description= files are read from their directory; these helpers load benches as text
// and suit the examples without device description files.
inline Bench sdn_bench(const std::string& stem) {
  return Bench(sdn_example(stem + ".slc"), sdn_example(stem + ".bench"));
}
inline SdnScanner& sdn(Bench& b, int slot) {
  auto* s = dynamic_cast<SdnScanner*>(b->module(slot));
  if (!s) throw std::runtime_error("no 1747-SDN in slot " + std::to_string(slot));
  return *s;
}
inline std::vector<std::int64_t> one(std::int64_t v) { return {v}; }

}  // namespace softslc::test
