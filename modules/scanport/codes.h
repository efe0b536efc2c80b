// SCANport protocol vocabulary: services, object classes, error codes, object kinds.
//
// Each concept is one X-macro list, expanded here into its enum and its row table, so a code is
// written once with everything the library knows about it (name, manual page, whether a device
// may lack it, the longest request it can carry). Every value comes from the 1203-SM1 user
// manual ("SLC to SCANport Communications Module"): the service list of Figure B.1 / Figure 4.11, the classes used
// by the appendix B examples, and the error table on page B-29. Nothing outside these lists
// exists for the library: find_service / find_class return nullptr for any other word, which
// the message layer turns into the documented "not supported" errors.
#pragma once

#include <cstddef>
#include <cstdint>
#include <iterator>
#include <string_view>

namespace softslc::scanport {

// The longest request data the 1203-SM1 transmits, in bytes: "Up to a maximum of 96 bytes of
// message data is available" (Figure B.1), except for scattered messages, which "can continue on
// in this pattern for up to 47 parameters" of 4 bytes each (pages B-23, B-25).
inline constexpr int kMaxRequestBytes = 96;
inline constexpr int kMaxScatteredRequestBytes = 47 * 4;

// ---------------------------------------------------------------------------------------------
// Services (Figure B.1, "Service"). Columns: enumerator, code, manual name, page of the
// example, JSON name of the optional feature (nullptr = every device supports it; the manual
// marks the optional ones with footnote 1, "Not all SCANport devices support these services"),
// and the longest request data in bytes the 1203-SM1 transmits for it.
#define SOFTSLC_SCANPORT_SERVICES(X)                                                                       \
  /* Read every attribute of one parameter in one reply (53 bytes for a 16-bit parameter). */              \
  X(kGetAttributeAll, 0x01, "Read Parameter Full/All Info", "B-11", nullptr, kMaxRequestBytes)             \
  /* Set every parameter value, in RAM and non-volatile storage, to its factory default. */                \
  X(kResetToDefaults, 0x05, "Reset to Default", "B-15", "reset_to_defaults", kMaxRequestBytes)             \
  /* Read one attribute of one object instance. */                                                          \
  X(kGetAttributeSingle, 0x0E, "Get Attribute Single", "B-7", nullptr, kMaxRequestBytes)                   \
  /* Write one attribute of one object instance. */                                                         \
  X(kSetAttributeSingle, 0x10, "Set Attribute Single", "B-10", nullptr, kMaxRequestBytes)                  \
  /* Copy the non-volatile parameter values back into RAM. */                                              \
  X(kRestoreFromStorage, 0x15, "Restore from Storage", "B-16", "restore_from_storage", kMaxRequestBytes)   \
  /* Copy the RAM parameter values into non-volatile storage. */                                           \
  X(kSaveToStorage, 0x16, "Save to Storage", "B-17", "save_to_storage", kMaxRequestBytes)                  \
  /* Read the values of a list of (parameter, placeholder) pairs. */                                       \
  X(kGetAttributeScattered, 0x32, "Get Attribute Scattered", "B-23", nullptr, kMaxScatteredRequestBytes)  \
  /* Write the values of a list of (parameter, value) pairs. */                                            \
  X(kSetAttributeScattered, 0x34, "Set Attribute Scattered", "B-25", nullptr, kMaxScatteredRequestBytes)  \
  /* Read the 12-character text of one value (or bit) of an enumerated parameter. */                       \
  X(kReadEnumString, 0x4B, "Read Enum String", "B-18", "read_enum_string", kMaxRequestBytes)

enum class Service : std::uint16_t {
#define SOFTSLC_X(name, code, text, page, feature, max_bytes) name = code,
  SOFTSLC_SCANPORT_SERVICES(SOFTSLC_X)
#undef SOFTSLC_X
};

struct ServiceInfo {
  Service service;
  std::uint16_t code;
  std::string_view name;
  std::string_view page;
  const char* feature;  // JSON name when optional, else nullptr
  int max_request_bytes;
};

inline constexpr ServiceInfo kServices[] = {
#define SOFTSLC_X(name, code, text, page, feature, max_bytes) {Service::name, code, text, page, feature, max_bytes},
    SOFTSLC_SCANPORT_SERVICES(SOFTSLC_X)
#undef SOFTSLC_X
};

// One bit per row of kServices, for the classes' service sets below.
constexpr std::uint32_t service_bit(Service s) {
  for (std::size_t i = 0; i < std::size(kServices); ++i)
    if (kServices[i].service == s) return std::uint32_t{1} << i;
  return 0;
}

// The service word of every error response (Figure B.2: "If an error occurred, the service will
// be 0014H (20 decimal)").
inline constexpr std::uint16_t kErrorService = 0x0014;

// ---------------------------------------------------------------------------------------------
// Object classes the appendix B examples address. Columns: enumerator, code, manual name, JSON
// name of the optional feature (links are footnoted "Not all SCANport devices support these
// messages" on page B-4; the others every device has), and the services the class answers.
#define SOFTSLC_SP_S(name) service_bit(Service::name)
#define SOFTSLC_SCANPORT_CLASSES(X)                                                                       \
  /* The parameter database; instance = parameter number, instance 0 = the database itself. */           \
  X(kParameter, 0x0F, "Parameter Class", nullptr,                                                         \
    SOFTSLC_SP_S(kGetAttributeAll) | SOFTSLC_SP_S(kResetToDefaults) | SOFTSLC_SP_S(kGetAttributeSingle) | \
        SOFTSLC_SP_S(kSetAttributeSingle) | SOFTSLC_SP_S(kRestoreFromStorage) |                           \
        SOFTSLC_SP_S(kSaveToStorage) | SOFTSLC_SP_S(kReadEnumString))                                     \
  /* Product identity; instance 0 = product, instance n = microprocessor n's firmware. */                \
  X(kProduct, 0x92, "Internal A-B Vendor Specific Class (product)", nullptr,                              \
    SOFTSLC_SP_S(kGetAttributeSingle))                                                                    \
  /* Scattered access to many parameter values in one message; instance 0 only. */                      \
  X(kScattered, 0x93, "Internal A-B Vendor Specific Class (scattered)", nullptr,                          \
    SOFTSLC_SP_S(kGetAttributeScattered) | SOFTSLC_SP_S(kSetAttributeScattered))                          \
  /* Parameter links; instance = parameter number, attribute 0 = the linked parameter. */                \
  X(kParameterLink, 0x99, "Internal A-B Vendor Specific Class (links)", "parameter_links",                \
    SOFTSLC_SP_S(kGetAttributeSingle) | SOFTSLC_SP_S(kSetAttributeSingle))

enum class ObjectClass : std::uint16_t {
#define SOFTSLC_X(name, code, text, feature, services) name = code,
  SOFTSLC_SCANPORT_CLASSES(SOFTSLC_X)
#undef SOFTSLC_X
};

struct ClassInfo {
  ObjectClass object_class;
  std::uint16_t code;
  std::string_view name;
  const char* feature;
  std::uint32_t services;  // service_bit() of each service the class answers

  constexpr bool answers(Service s) const { return (services & service_bit(s)) != 0; }
};

inline constexpr ClassInfo kClasses[] = {
#define SOFTSLC_X(name, code, text, feature, services) {ObjectClass::name, code, text, feature, services},
    SOFTSLC_SCANPORT_CLASSES(SOFTSLC_X)
#undef SOFTSLC_X
};

// ---------------------------------------------------------------------------------------------
// Error codes (page B-29), carried in the first response data word after service 0x0014, and in
// the value word of a failed scattered entry. 0xFD and 0xFE are produced by the 1203-SM1 itself
// (it cannot transmit the message / the device never answered); the others by the device.
#define SOFTSLC_SCANPORT_ERRORS(X)                                                                           \
  X(kNone, 0x00, "No error occurred. The operation was successful.")                                         \
  X(kServiceFailed, 0x01, "The service failed. The SCANport device could not perform this request.")         \
  X(kServiceNotSupported, 0x02, "Service not supported.")                                                    \
  X(kClassNotSupported, 0x03, "Class not supported.")                                                        \
  X(kInstanceNotSupported, 0x04, "Instance not supported.")                                                  \
  X(kAttributeNotSupported, 0x05, "Attribute not supported.")                                                \
  X(kValueOutOfRange, 0x06, "Value out of range.")                                                           \
  X(kDeviceConflict, 0x07,                                                                                   \
    "SCANport device conflict - cannot perform this request while the SCANport device is in the current "   \
    "state (usually while the drive is running).")                                                          \
  X(kInvalidLength, 0xFD, "Invalid message length. The message is too long or too short to transmit.")       \
  X(kTimeout, 0xFE, "The message timed out before the response was given. Check the SCANport connection.")

enum class ErrorCode : std::uint16_t {
#define SOFTSLC_X(name, code, text) name = code,
  SOFTSLC_SCANPORT_ERRORS(SOFTSLC_X)
#undef SOFTSLC_X
};

struct ErrorInfo {
  ErrorCode error;
  std::uint16_t code;
  std::string_view meaning;
};

inline constexpr ErrorInfo kErrors[] = {
#define SOFTSLC_X(name, code, text) {ErrorCode::name, code, text},
    SOFTSLC_SCANPORT_ERRORS(SOFTSLC_X)
#undef SOFTSLC_X
};

// ---------------------------------------------------------------------------------------------
// The object a message addresses, as far as response padding is concerned. Devices differ in
// which replies they pad to a multiple of six bytes (Figure B.2 footnote): the appendix B
// examples pad the class-level parameter reply, the product replies and the link replies but
// not the per-parameter replies, while the manual says a 1336 PLUS pads every reply. A drive
// description therefore gives a padding granule per kind (DriveDescription::response_padding).
#define SOFTSLC_SCANPORT_OBJECT_KINDS(X)                                               \
  /* Class 0x0F instance 0: "Read Number of Parameters", reset/restore/save. */         \
  X(kParameterClass, "parameter_class")                                                 \
  /* Class 0x0F instance 1-n: one parameter's value, name, enum strings, ... */         \
  X(kParameter, "parameter")                                                            \
  /* Class 0x92. */                                                                     \
  X(kProduct, "product")                                                                \
  /* Class 0x93. */                                                                     \
  X(kScattered, "scattered")                                                            \
  /* Class 0x99. */                                                                     \
  X(kParameterLink, "parameter_link")                                                   \
  /* Any class the device does not have (its error reply). */                           \
  X(kOther, "other")

enum class ObjectKind : std::uint8_t {
#define SOFTSLC_X(name, json) name,
  SOFTSLC_SCANPORT_OBJECT_KINDS(SOFTSLC_X)
#undef SOFTSLC_X
};

inline constexpr std::string_view kObjectKindNames[] = {
#define SOFTSLC_X(name, json) json,
    SOFTSLC_SCANPORT_OBJECT_KINDS(SOFTSLC_X)
#undef SOFTSLC_X
};
inline constexpr int kObjectKindCount = static_cast<int>(std::size(kObjectKindNames));

// Lookups over the tables above; nullptr for a word that is not in the table.
constexpr const ServiceInfo* find_service(std::uint16_t code) {
  for (const auto& s : kServices)
    if (s.code == code) return &s;
  return nullptr;
}
constexpr const ClassInfo* find_class(std::uint16_t code) {
  for (const auto& c : kClasses)
    if (c.code == code) return &c;
  return nullptr;
}
constexpr const ErrorInfo* find_error(std::uint16_t code) {
  for (const auto& e : kErrors)
    if (e.code == code) return &e;
  return nullptr;
}
constexpr const ServiceInfo& info(Service s) { return *find_service(static_cast<std::uint16_t>(s)); }
constexpr const ClassInfo& info(ObjectClass c) { return *find_class(static_cast<std::uint16_t>(c)); }
constexpr std::string_view name_of(ObjectKind k) { return kObjectKindNames[static_cast<int>(k)]; }

}  // namespace softslc::scanport
