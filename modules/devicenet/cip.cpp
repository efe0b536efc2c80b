#include "modules/devicenet/cip.h"

#include <array>

namespace softslc::devicenet {
namespace {

struct StatusRow {
  std::uint8_t code;
  std::string_view name;
};
constexpr StatusRow kStatusRows[] = {
#define CIP_STATUS(code, name, short_name, text) {code, short_name},
#include "modules/devicenet/cip_status.def"
#undef CIP_STATUS
};

struct TypeRow {
  std::string_view json;
  std::uint8_t code;
  int size;
  bool is_signed;
};
constexpr TypeRow kTypeRows[] = {
#define CIP_TYPE(name, json, code, size, is_signed) {json, code, size, is_signed},
#include "modules/devicenet/cip_types.def"
#undef CIP_TYPE
};

const TypeRow& row(CipType t) { return kTypeRows[static_cast<std::size_t>(t)]; }

}  // namespace

std::string_view cip_status_name(std::uint8_t code) {
  for (const auto& r : kStatusRows)
    if (r.code == code) return r.name;
  return "";
}

bool cip_status_listed(std::uint8_t code) {
  if (code == 0) return false;
  for (const auto& r : kStatusRows)
    if (r.code == code) return true;
  return false;
}

std::string_view to_string(CipType t) { return row(t).json; }

std::optional<CipType> parse_cip_type(std::string_view json_name) {
  for (std::size_t i = 0; i < std::size(kTypeRows); ++i)
    if (kTypeRows[i].json == json_name) return static_cast<CipType>(i);
  return std::nullopt;
}

std::uint8_t cip_type_code(CipType t) { return row(t).code; }
int cip_type_size(CipType t) { return row(t).size; }
bool cip_type_signed(CipType t) { return row(t).is_signed; }
bool cip_type_integer(CipType t) { return row(t).size > 0; }

std::int64_t cip_type_min(CipType t) {
  if (t == CipType::Bool) return 0;
  const int bits = 8 * row(t).size;
  return row(t).is_signed ? -(std::int64_t{1} << (bits - 1)) : 0;
}

std::int64_t cip_type_max(CipType t) {
  if (t == CipType::Bool) return 1;
  const int bits = 8 * row(t).size;
  return row(t).is_signed ? (std::int64_t{1} << (bits - 1)) - 1 : (std::int64_t{1} << bits) - 1;
}

std::uint8_t reply_service(std::uint8_t request_service, const CipReply& reply) {
  if (!reply.ok()) return service::kErrorResponse | service::kReplyBit;
  return static_cast<std::uint8_t>(request_service | service::kReplyBit);
}

Bytes reply_bytes(const CipReply& reply) {
  if (!reply.ok()) return Bytes{reply.general_status, reply.additional.value_or(0xFF)};
  return reply.data;
}

void put_le(Bytes& out, std::uint64_t value, int size) {
  for (int i = 0; i < size; ++i) out.push_back(static_cast<std::uint8_t>(value >> (8 * i)));
}

std::uint64_t get_le(std::span<const std::uint8_t> in, int size) {
  std::uint64_t v = 0;
  for (int i = 0; i < size; ++i) v |= std::uint64_t{in[static_cast<std::size_t>(i)]} << (8 * i);
  return v;
}

}  // namespace softslc::devicenet
