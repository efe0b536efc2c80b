// Modbus RTU as a MicroLogix 1100/1400 channel 0 configured as a Modbus RTU slave answers it: the
// framing of the Modbus over Serial Line specification v1.02 (§2.5.1) around the PDU handling of
// server/modbus.h. Pure, without I/O: the server (server/server.h) feeds it the bytes it reads
// from the serial line and tells it when the line has been silent; it returns the frames to send.
//
// A frame is the slave address (1 byte), the PDU, and the CRC-16 (polynomial A001h reflected,
// initial value FFFFh, low byte first; §6.2.2). On a serial line frames are delimited by 3.5
// character times of silence (§2.5.1.1); a pseudo-terminal has no character timing, so a request
// ends where its function code's length rule says:
//   FC 1, 2, 3, 4, 5, 6        8 bytes (address, function, 2-byte address, 2-byte quantity/value, CRC)
//   FC 15, 16                  9 + the byte count in its 7th byte
//   any other function         at the silence (FC 8's data has no length; unknown functions)
// and the silence ends a frame a length rule cannot (and one cut short). Then:
//   - a bad CRC: the frame is dropped, no reply (§2.4.1: the slave does not answer), and every
//     byte until the next silence is dropped too, so the link resynchronises at a frame start;
//   - a frame for another slave: ignored, no reply;
//   - address 0 (broadcast, §2.2): the request is executed (writes happen), no reply;
//   - otherwise the reply frame: this slave's address, handle_pdu's reply PDU, the CRC.
// At most kRtuMaxFrame bytes are buffered (256, §2.5.1): a longer run of bytes is dropped as a
// bad frame, so garbage on the line costs a bounded buffer.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "server/modbus.h"

namespace softslc::modbus {

inline constexpr std::size_t kRtuMaxFrame = 256;  // address + 253-byte PDU + CRC
inline constexpr std::uint8_t kBroadcastAddress = 0;

// The Modbus CRC-16 of `bytes` (§6.2.2). On the wire the low byte goes first.
std::uint16_t crc16(std::span<const std::uint8_t> bytes);
// `bytes` with its CRC appended, low byte first.
std::vector<std::uint8_t> with_crc(std::vector<std::uint8_t> bytes);

// What the slave did with the bytes it was given.
struct RtuEvents {
  std::vector<std::vector<std::uint8_t>> replies;  // frames to send, in order
  std::vector<std::string> log;                    // frames dropped or ignored, and refusals (debug log)
};

class RtuSlave {
 public:
  RtuSlave(std::uint8_t address, Map map) : address_(address), map_(map) {}

  // Bytes that arrived on the line.
  RtuEvents receive(std::span<const std::uint8_t> bytes, pccc::Target& target);
  // The line has been silent for the inter-frame time: ends a frame without a length rule, drops a
  // frame cut short, ends dropping after a bad frame.
  RtuEvents silence(pccc::Target& target);
  // Whether silence() has anything to do (bytes buffered, or dropping until the line is quiet).
  bool waiting_for_silence() const { return dropping_ || !buffer_.empty(); }
  std::size_t buffered() const { return buffer_.size(); }
  const SlaveCounters& counters() const { return counters_; }
  // Input registers 30501-30532 as this slave answers them (server/modbus.h, CommParameters).
  CommParameters comm_parameters() const;
  std::uint8_t address() const { return address_; }

 private:
  // Cuts and handles the frames in the buffer; `silent`: the line went quiet after the last byte.
  void cut(bool silent, pccc::Target& target, RtuEvents& events);
  void frame(std::span<const std::uint8_t> frame, pccc::Target& target, RtuEvents& events);
  void drop(const std::string& why, bool silent, RtuEvents& events);

  std::uint8_t address_;
  Map map_;
  std::vector<std::uint8_t> buffer_;
  bool dropping_ = false;
  SlaveCounters counters_;
};

}  // namespace softslc::modbus
