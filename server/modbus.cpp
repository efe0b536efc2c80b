#include "server/modbus.h"

namespace softslc::modbus {

std::optional<Header> decode_header(std::span<const std::uint8_t> b, std::string* error) {
  if (b.size() < kHeaderSize) {
    if (error) *error = "MBAP header shorter than 7 bytes";
    return std::nullopt;
  }
  Header h;
  h.transaction = be16(b, 0);
  h.protocol = be16(b, 2);
  h.length = be16(b, 4);
  h.unit = b[6];
  if (h.protocol != 0) {
    if (error) *error = "MBAP protocol identifier " + std::to_string(h.protocol) + " is not Modbus (0)";
    return std::nullopt;
  }
  if (h.length < 2 || h.length > kMaxPdu + 1) {
    if (error) *error = "MBAP length " + std::to_string(h.length) + " outside 2-254";
    return std::nullopt;
  }
  return h;
}

std::optional<std::vector<std::uint8_t>> handle(std::span<const std::uint8_t> frame, const Map& map, pccc::Target& target,
                                                std::string* error, std::string* refusal, const CommParameters* comm) {
  const auto h = decode_header(frame, error);
  if (!h) return std::nullopt;
  if (frame.size() != kHeaderSize + h->length - 1u) {
    if (error) *error = "MBAP length " + std::to_string(h->length) + " disagrees with the frame's " +
                        std::to_string(frame.size()) + " bytes";
    return std::nullopt;
  }
  const auto pdu = handle_pdu(frame.subspan(kHeaderSize), map, target, refusal, comm);
  std::vector<std::uint8_t> out;
  out.reserve(kHeaderSize + pdu.size());
  put16(out, h->transaction);
  put16(out, 0);
  put16(out, static_cast<std::uint16_t>(pdu.size() + 1));
  out.push_back(h->unit);
  out.insert(out.end(), pdu.begin(), pdu.end());
  return out;
}

}  // namespace softslc::modbus
