#include "modules/devicenet/transaction.h"

#include <algorithm>

namespace softslc::devicenet {

namespace {
struct TextRow {
  std::uint8_t value;
  std::string_view text;
};
constexpr TextRow kCommands[] = {
#define TXN_COMMAND(value, name, text) {value, text},
#include "modules/devicenet/transaction_codes.def"
#undef TXN_COMMAND
};
constexpr TextRow kStatuses[] = {
#define TXN_STATUS(value, name, text) {value, text},
#include "modules/devicenet/transaction_codes.def"
#undef TXN_STATUS
};

std::uint8_t lo(std::uint16_t w) { return static_cast<std::uint8_t>(w & 0xFF); }
std::uint8_t hi(std::uint16_t w) { return static_cast<std::uint8_t>(w >> 8); }
std::uint16_t word(std::uint8_t high, std::uint8_t low) { return static_cast<std::uint16_t>(high << 8 | low); }

// Body byte k (0...57) of a block: word 3 + k/2, low byte first.
std::uint8_t body_byte(std::span<const std::uint16_t, 32> w, int k) {
  const std::uint16_t v = w[3 + static_cast<std::size_t>(k / 2)];
  return k % 2 == 0 ? lo(v) : hi(v);
}
void set_body_byte(Block& w, int k, std::uint8_t b) {
  std::uint16_t& v = w[3 + static_cast<std::size_t>(k / 2)];
  v = k % 2 == 0 ? word(hi(v), b) : word(b, lo(v));
}
}  // namespace

std::string_view txn_command_text(std::uint8_t command) {
  for (const auto& r : kCommands)
    if (r.value == command) return r.text;
  return "";
}

std::string_view txn_status_text(std::uint8_t status) {
  for (const auto& r : kStatuses)
    if (r.value == status) return r.text;
  return "";
}

RequestBlock decode_request(std::span<const std::uint16_t, 32> w) {
  RequestBlock r;
  r.command = lo(w[0]);
  r.txid = hi(w[0]);
  r.size = lo(w[1]);
  r.port = hi(w[1]);
  r.mac = lo(w[2]);
  r.service = hi(w[2]);
  r.class_id = lo(w[3]);
  r.instance = w[4];
  r.attribute = lo(w[5]);
  const int n = std::clamp(static_cast<int>(r.size) - kRequestPathBytes, 0, kMaxRequestDataBytes);
  r.data.resize(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) r.data[static_cast<std::size_t>(k)] = body_byte(w, kRequestPathBytes + k);
  return r;
}

Block encode_request(const RequestBlock& r) {
  Block w{};
  w[0] = word(r.txid, r.command);
  w[1] = word(r.port, r.size);
  w[2] = word(r.service, r.mac);
  w[3] = r.class_id;
  w[4] = r.instance;
  w[5] = r.attribute;
  const int n = std::min(static_cast<int>(r.data.size()), kMaxRequestDataBytes);
  for (int k = 0; k < n; ++k) set_body_byte(w, kRequestPathBytes + k, r.data[static_cast<std::size_t>(k)]);
  return w;
}

ResponseBlock decode_response(std::span<const std::uint16_t, 32> w) {
  ResponseBlock r;
  r.status = lo(w[0]);
  r.txid = hi(w[0]);
  r.port = hi(w[1]);
  r.mac = lo(w[2]);
  r.service = hi(w[2]);
  const int n = std::min(static_cast<int>(lo(w[1])), kMaxBodyBytes);
  r.data.resize(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) r.data[static_cast<std::size_t>(k)] = body_byte(w, k);
  return r;
}

Block encode_response(const ResponseBlock& r) {
  Block w{};
  const int n = std::min(static_cast<int>(r.data.size()), kMaxBodyBytes);
  w[0] = word(r.txid, r.status);
  w[1] = word(r.port, static_cast<std::uint8_t>(n));
  w[2] = word(r.service, r.mac);
  for (int k = 0; k < n; ++k) set_body_byte(w, k, r.data[static_cast<std::size_t>(k)]);
  return w;
}

std::optional<TxnStatus> check_request(const RequestBlock& r) {
  if (r.port != 0) return TxnStatus::InvalidPort;
  if (r.size < kRequestPathBytes || r.size > kMaxBodyBytes) return TxnStatus::InvalidSize;
  return std::nullopt;
}

CipRequest to_cip_request(const RequestBlock& r) {
  CipRequest c;
  c.service = r.service;
  c.class_id = r.class_id;
  c.instance = r.instance;
  // Built element by element: GCC 12 warns (falsely) about vector::insert of a range here.
  c.body.reserve(r.data.size() + 1);
  if (r.attribute != 0) c.body.push_back(r.attribute);
  for (std::uint8_t b : r.data) c.body.push_back(b);
  return c;
}

}  // namespace softslc::devicenet
