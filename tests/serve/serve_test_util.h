// Helpers shared by the serve tests: frames written out byte by byte, and a live controller on the
// shipped HMI example program.
#pragma once

#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <string>
#include <vector>

#include "server/eip.h"
#include "server/live.h"

namespace softslc::serve::testing {

using Bytes = std::vector<std::uint8_t>;

inline std::filesystem::path hmi_program() {
  return std::filesystem::path(SOFTSLC_SOURCE_DIR) / "examples/ladder/serve/hmi_panel.slc";
}

inline Bytes cat(std::initializer_list<Bytes> parts) {
  Bytes out;
  for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

inline Bytes le16(std::uint16_t v) { return {static_cast<std::uint8_t>(v & 0xFF), static_cast<std::uint8_t>(v >> 8)}; }
inline Bytes le32(std::uint32_t v) { return cat({le16(static_cast<std::uint16_t>(v & 0xFFFF)), le16(static_cast<std::uint16_t>(v >> 16))}); }

// The encapsulation header (CIP Vol. 2, 2-3): command, length, session, status, context, options.
inline Bytes header(std::uint16_t command, std::uint16_t length, std::uint32_t session) {
  return cat({le16(command), le16(length), le32(session), le32(0), {1, 2, 3, 4, 5, 6, 7, 8}, le32(0)});
}

// RegisterSession exactly as nodepccc 0.1.17 sends it (its connectReq buffer).
inline Bytes register_session_frame() {
  return {0x65, 0x00, 0x04, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x0a, 0x0b,
          0x0c, 0x0d, 0x0e, 0x0f, 0x0a, 0x0b, 0x00, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00};
}

// SendRRData carrying Execute PCCC (4Bh, path 20 67 24 01) with requestor ID 07 0000 01020304,
// the layout nodepccc sends (its EIP_CIP_Header and PCCC_Encapsulation_Header buffers).
inline Bytes execute_pccc_frame(std::uint32_t session, const Bytes& pccc) {
  const Bytes cip = cat({{0x4B, 0x02, 0x20, 0x67, 0x24, 0x01, 0x07, 0x00, 0x00, 0x01, 0x02, 0x03, 0x04}, pccc});
  const Bytes data = cat({le32(0), le16(10), le16(2), le16(0), le16(0), le16(0xB2), le16(static_cast<std::uint16_t>(cip.size())), cip});
  return cat({header(0x6F, static_cast<std::uint16_t>(data.size()), session), data});
}

// The PCCC reply inside a SendRRData reply to execute_pccc_frame: after the 24-byte header, the
// interface handle and timeout (6), the CPF (2 + 4 + 4), the CIP reply header (4) and the
// requestor ID (7) — offset 51, as nodepccc reads it.
inline Bytes pccc_reply_of(const Bytes& frame) {
  if (frame.size() < 51) return {};
  return Bytes(frame.begin() + 51, frame.end());
}

}  // namespace softslc::serve::testing
