// Modbus TCP as a MicroLogix 1100/1400 answers it when its channel is configured as a Modbus slave:
// a pure decoder and executor, without sockets, like server/pccc.h.
//
// The map, the function codes and the exception codes are the PDU handler's (vm/modbus_slave.h).
//
// A frame is the 7-byte MBAP header (transaction u16, protocol u16 = 0, length u16 = unit id +
// PDU bytes, unit id u8, all big-endian) and the PDU. A protocol id other than 0 or a length
// outside 2-254 (a PDU is at most 253 bytes) is not a Modbus frame: the connection closes. The
// unit id is echoed and not checked (a Modbus TCP server addressed directly is the unit).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "server/pccc.h"
#include "vm/modbus_slave.h"

namespace softslc::modbus {

inline constexpr std::uint16_t kPort = 502;
inline constexpr std::size_t kHeaderSize = 7;  // MBAP

struct Header {
  std::uint16_t transaction = 0;
  std::uint16_t protocol = 0;
  std::uint16_t length = 0;  // unit id + PDU
  std::uint8_t unit = 0;
};
// The MBAP header of the first 7 bytes; nullopt when fewer, or when it is not a Modbus TCP header
// (protocol id not 0, length outside 2-254) — `error` says which.
std::optional<Header> decode_header(std::span<const std::uint8_t> bytes, std::string* error = nullptr);

// Handles one whole frame (header and exactly length-1 PDU bytes) and returns the reply frame.
// nullopt: the frame is malformed (the connection closes, `error` says why). `refusal`, when
// given, receives why an exception was answered (for the log).
std::optional<std::vector<std::uint8_t>> handle(std::span<const std::uint8_t> frame, const Map& map,
                                                pccc::Target& target, std::string* error = nullptr,
                                                std::string* refusal = nullptr, const CommParameters* comm = nullptr);

}  // namespace softslc::modbus
