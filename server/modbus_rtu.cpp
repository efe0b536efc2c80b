#include "server/modbus_rtu.h"

#include <algorithm>

namespace softslc::modbus {

namespace {

// The length of the request that starts the buffer, by its function code: 0 when the function has
// no length rule (the silence ends it), nullopt while too few bytes have arrived to tell.
std::optional<std::size_t> request_length(std::span<const std::uint8_t> b) {
  if (b.size() < 2) return std::nullopt;
  switch (b[1]) {
    case kReadCoils:
    case kReadDiscreteInputs:
    case kReadHoldingRegisters:
    case kReadInputRegisters:
    case kWriteSingleCoil:
    case kWriteSingleRegister:
      return 8;
    case kWriteMultipleCoils:
    case kWriteMultipleRegisters:
      if (b.size() < 7) return std::nullopt;
      return 9 + std::size_t{b[6]};
    default:
      return 0;
  }
}

bool crc_ok(std::span<const std::uint8_t> frame) {
  if (frame.size() < 4) return false;
  const std::uint16_t crc = crc16(frame.first(frame.size() - 2));
  return frame[frame.size() - 2] == (crc & 0xFF) && frame[frame.size() - 1] == (crc >> 8);
}

}  // namespace

std::uint16_t crc16(std::span<const std::uint8_t> bytes) {
  std::uint16_t crc = 0xFFFF;
  for (const std::uint8_t byte : bytes) {
    crc = static_cast<std::uint16_t>(crc ^ byte);
    for (int i = 0; i < 8; ++i) crc = (crc & 1u) ? static_cast<std::uint16_t>((crc >> 1) ^ 0xA001u) : static_cast<std::uint16_t>(crc >> 1);
  }
  return crc;
}

std::vector<std::uint8_t> with_crc(std::vector<std::uint8_t> bytes) {
  const std::uint16_t crc = crc16(bytes);
  bytes.push_back(static_cast<std::uint8_t>(crc & 0xFF));
  bytes.push_back(static_cast<std::uint8_t>(crc >> 8));
  return bytes;
}

CommParameters RtuSlave::comm_parameters() const { return modbus::comm_parameters(map_, address_, counters_); }

RtuEvents RtuSlave::receive(std::span<const std::uint8_t> bytes, pccc::Target& target) {
  RtuEvents events;
  // At most one byte past the largest frame is buffered at a time, so a flood of bytes is cut and
  // dropped in bounded pieces.
  while (!bytes.empty() && !dropping_) {
    const std::size_t n = std::min(bytes.size(), kRtuMaxFrame + 1 - buffer_.size());
    buffer_.insert(buffer_.end(), bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(n));
    bytes = bytes.subspan(n);
    cut(false, target, events);
  }
  return events;
}

RtuEvents RtuSlave::silence(pccc::Target& target) {
  RtuEvents events;
  if (dropping_) {
    dropping_ = false;
    buffer_.clear();
    return events;
  }
  cut(true, target, events);
  return events;
}

void RtuSlave::drop(const std::string& why, bool silent, RtuEvents& events) {
  ++counters_.link_errors;
  events.log.push_back("Modbus RTU: " + why + "; " + std::to_string(buffer_.size()) + " byte(s) dropped" +
                       (silent ? "" : ", and the rest until the line is silent"));
  buffer_.clear();
  dropping_ = !silent;
}

void RtuSlave::cut(bool silent, pccc::Target& target, RtuEvents& events) {
  while (!buffer_.empty()) {
    const auto length = request_length(buffer_);
    if (length && *length > 0) {
      if (*length > kRtuMaxFrame) return drop("a byte count past the 256-byte frame", silent, events);
      if (buffer_.size() < *length) {
        if (silent) return drop("a frame cut short (" + std::to_string(buffer_.size()) + " of " +
                                std::to_string(*length) + " bytes)", silent, events);
        return;
      }
      const std::span<const std::uint8_t> f(buffer_.data(), *length);
      if (!crc_ok(f)) return drop("bad CRC", silent, events);
      frame(f, target, events);
      buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(*length));
      continue;
    }
    if (buffer_.size() > kRtuMaxFrame) return drop("a frame longer than 256 bytes", silent, events);
    if (!silent) return;
    // No length rule (or too few bytes to tell): the silence ends the frame.
    if (!crc_ok(buffer_)) return drop(buffer_.size() < 4 ? "a frame shorter than 4 bytes" : "bad CRC", silent, events);
    frame(buffer_, target, events);
    buffer_.clear();
  }
}

void RtuSlave::frame(std::span<const std::uint8_t> f, pccc::Target& target, RtuEvents& events) {
  ++counters_.seen;
  const std::uint8_t to = f[0];
  if (to != address_ && to != kBroadcastAddress) {
    events.log.push_back("Modbus RTU: a frame for slave " + std::to_string(to) + " ignored");
    return;
  }
  const auto pdu = f.subspan(1, f.size() - 3);
  counters_.count_request(pdu[0]);
  std::string refusal;
  const CommParameters comm = comm_parameters();
  auto reply = handle_pdu(pdu, map_, target, &refusal, &comm);
  if (!refusal.empty()) events.log.push_back("Modbus RTU: " + refusal);
  if (to == kBroadcastAddress) return;  // §2.2: a broadcast request is never answered
  reply.insert(reply.begin(), address_);
  events.replies.push_back(with_crc(std::move(reply)));
  ++counters_.responded;
}

}  // namespace softslc::modbus
