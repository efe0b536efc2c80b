// Bus timing: how long DeviceNet messages occupy the CAN bus, in integer nanoseconds.
//
// DeviceNet runs on CAN 2.0A (11-bit identifiers) at 125, 250 or 500 kbit/s, so one bit lasts
// exactly 8000, 4000 or 2000 ns and every duration below is an exact integer. A data frame with n
// data bytes (0...8) has 47 + 8n nominal bits (start of frame, identifier, control, CRC, ACK, end
// of frame and the 3-bit interframe space) plus worst-case bit stuffing of floor((34 + 8n - 1) / 4)
// bits (Tindell and Burns' bound). We always charge the worst case: it keeps timing independent of
// the data values, so a change of an input bit never changes when later events happen.
//
// Messages longer than one frame are fragmented as DeviceNet does:
//   I/O messages:      each fragment carries a fragmentation byte and up to 7 data bytes; no acks.
//   explicit messages: each frame carries the message header byte; a message whose header + body
//                      exceed 8 bytes is sent as fragments of header, fragmentation byte and up to 6
//                      body bytes, and the receiver answers every fragment with a 3-byte ack frame.
// The body of an explicit request is service, class, instance (1 byte, 2 when above 255),
// attribute (absent when 0, chapter 8 p.96) and data; a response body is service and data.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "vm/virtual_time.h"

namespace softslc::devicenet {

// The three DeviceNet data rates (the 1747-SDN's factory default is 125K, appendix D p.140).
enum class Baud : std::uint8_t { k125 = 0, k250 = 1, k500 = 2 };
std::string_view to_string(Baud b);                          // "125K", "250K", "500K"
std::optional<Baud> parse_baud(std::string_view text);       // accepts exactly those spellings
constexpr Nanoseconds bit_time(Baud b) {
  return b == Baud::k125 ? 8000 : b == Baud::k250 ? 4000 : 2000;
}

// Bits on the wire for one CAN data frame carrying `data_bytes` (0...8) bytes, stuffing included.
constexpr int can_frame_bits(int data_bytes) { return 47 + 8 * data_bytes + (34 + 8 * data_bytes - 1) / 4; }
constexpr Nanoseconds frame_time(Baud b, int data_bytes) { return can_frame_bits(data_bytes) * bit_time(b); }

// An I/O message of `bytes` bytes (0 = the zero-length idle message), fragmented when above 8.
Nanoseconds io_message_time(Baud b, int bytes);
// One explicit message whose body (service onwards) is `body_bytes` long, with its fragment acks.
Nanoseconds explicit_message_time(Baud b, int body_bytes);
// Body length of an explicit request: service + class + instance + optional attribute + data.
constexpr int explicit_request_body(int instance, int attribute, int data_bytes) {
  return 1 + 1 + (instance > 255 ? 2 : 1) + (attribute != 0 ? 1 : 0) + data_bytes;
}

}  // namespace softslc::devicenet
