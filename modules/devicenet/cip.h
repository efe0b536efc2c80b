// CIP vocabulary shared by the simulated devices, the scanner and the DEM codec.
//
// DeviceNet explicit messages carry CIP requests: a service code, a path (class, instance) and a
// body whose first byte is the attribute number for the attribute services. The manual's DEM note
// (chapter 8, p.96) that "if the value of the Attribute is set to 0, the DeviceNet scanner does not
// transmit an Attribute byte" is why CipRequest keeps the attribute inside `body` rather than as a
// field: the server sees exactly the bytes the wire would carry.
//
// A DeviceNet server answers with service | 0x80 and the reply data, or with the Error Response
// service (0x94 on the wire) whose two data bytes are the general status and an additional code,
// 0xFF when there is none (appendix E, "Explicit Messaging Error Codes", p.151). CipReply models
// both; to_response_bytes() gives the bytes a response transaction block carries.
//
// The tables (general status codes, elementary data types) are X-macro .def files with one row
// per code, so names, numbers and descriptions live in exactly one place.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace softslc::devicenet {

using Bytes = std::vector<std::uint8_t>;

enum class CipStatus : std::uint8_t {
#define CIP_STATUS(code, name, short_name, text) name = code,
#include "modules/devicenet/cip_status.def"
#undef CIP_STATUS
};
// The manual's name for a general status ("Attribute not supported"), or "" when unlisted.
std::string_view cip_status_name(std::uint8_t code);
// Whether the manual's CIP Response Error Codes tables list `code` (success 0 is not an error).
bool cip_status_listed(std::uint8_t code);

enum class CipType : std::uint8_t {
#define CIP_TYPE(name, json, code, size, is_signed) name,
#include "modules/devicenet/cip_types.def"
#undef CIP_TYPE
};
std::string_view to_string(CipType t);
std::optional<CipType> parse_cip_type(std::string_view json_name);
std::uint8_t cip_type_code(CipType t);     // the CIP type code (0xC6 for USINT, ...); 0 for BYTES
int cip_type_size(CipType t);              // bytes; 0 = variable length
bool cip_type_signed(CipType t);
bool cip_type_integer(CipType t);          // fixed-size integer types (BOOL...DWORD)
// Range of values an integer type holds.
std::int64_t cip_type_min(CipType t);
std::int64_t cip_type_max(CipType t);

// Service codes the simulation implements (CIP Common Specification, appendix A).
namespace service {
inline constexpr std::uint8_t kGetAttributesAll = 0x01;
inline constexpr std::uint8_t kSetAttributesAll = 0x02;
inline constexpr std::uint8_t kReset = 0x05;
inline constexpr std::uint8_t kGetAttributeSingle = 0x0E;
inline constexpr std::uint8_t kSetAttributeSingle = 0x10;
inline constexpr std::uint8_t kErrorResponse = 0x14;   // DeviceNet Error Response (0x94 with the reply bit)
inline constexpr std::uint8_t kReplyBit = 0x80;
}  // namespace service

// Class codes of the objects every simulated device carries.
namespace cip_class {
inline constexpr std::uint8_t kIdentity = 0x01;
inline constexpr std::uint8_t kDeviceNet = 0x03;
inline constexpr std::uint8_t kAssembly = 0x04;
inline constexpr std::uint8_t kConnection = 0x05;
inline constexpr std::uint8_t kParameter = 0x0F;
}  // namespace cip_class

struct CipRequest {
  std::uint8_t service = 0;
  std::uint8_t class_id = 0;
  std::uint16_t instance = 0;
  Bytes body;  // attribute byte (when transmitted) followed by the service data
};

struct CipReply {
  std::uint8_t general_status = 0;  // 0 = success
  std::optional<std::uint8_t> additional;
  Bytes data;  // reply data on success

  bool ok() const { return general_status == 0; }
  static CipReply success(Bytes d = {}) { return CipReply{0, std::nullopt, std::move(d)}; }
  static CipReply error(CipStatus s, std::optional<std::uint8_t> extra = std::nullopt) {
    return CipReply{static_cast<std::uint8_t>(s), extra, {}};
  }
};

// The reply service code and data as a response block carries them: (request | 0x80, data) on
// success; (0x94, [general, additional or 0xFF]) on error.
std::uint8_t reply_service(std::uint8_t request_service, const CipReply& reply);
Bytes reply_bytes(const CipReply& reply);

// Little-endian encoding of CIP integers.
void put_le(Bytes& out, std::uint64_t value, int size);
std::uint64_t get_le(std::span<const std::uint8_t> in, int size);  // in.size() >= size

}  // namespace softslc::devicenet
