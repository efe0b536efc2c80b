// A simulated SCANport drive: parameter database, product identity, non-volatile storage, logic
// command/status, reference/feedback over virtual time, and datalinks.
//
// A drive is data. DriveDescription holds everything that differs between products (the
// parameter list with its attributes, which optional services exist, how replies are padded,
// what each logic bit means, how fast the speed follows the reference); drive_json.h loads one
// from JSON and drives/1305.json is compiled into the library. Drive is the running instance:
// it owns the RAM and non-volatile copies of the parameter values and links and the plant state,
// and exposes them through small operations that report SCANport error codes, so the message
// layer (messages.h) only decodes words and calls them, and the 1203-SM1 module wrapper can call
// the same operations for the I/O image (logic command, reference, datalinks).
//
// Invariants, checked when a Drive is built (validate()): parameters are numbered 1..n without
// gaps; every minimum <= default, value <= maximum fits the data type; every string fits its
// fixed field (name 16, units 4, enum 12, product text 16 characters); a parameter has enum
// strings exactly when its descriptor says so; links and role/datalink targets name existing
// parameters. After construction every RAM and non-volatile value stays within its parameter's
// minimum..maximum, whatever sequence of operations is applied.
//
// Time: the drive updates its plant every `update_period` of virtual time, at fixed instants
// k * update_period since power-up, in integer fixed-point arithmetic (speed in 1/65536 of a
// reference count). advance_to(t) runs every update up to t, so the state at a time never
// depends on how the caller split the advance, and two runs with the same calls are identical.
// The speed response is first order: each update moves the speed by
// (target - speed) * update_period / time_constant, the target being the reference when running
// and 0 when stopped. Commands take effect from the next update.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "modules/scanport/codes.h"
#include "modules/scanport/scaling.h"
#include "vm/virtual_time.h"

namespace softslc::scanport {

// ---------------------------------------------------------------------------------------------
// Parameter data types (Read Full Parameter attribute 5; the "Data Type Value" table on page
// B-12). Columns: enumerator, code, manual description, value size in bytes (attribute 6),
// signed. The manual shows only type 2's size (2 bytes, Figure B.8); the other sizes follow the
// names (short = 1 byte, double = 4, long = 8; a Boolean is one byte).
#define SOFTSLC_SCANPORT_DATA_TYPES(X)                          \
  X(kWord, 1, "16-bit word", 2, false)                          \
  X(kUnsigned16, 2, "16-bit unsigned integer", 2, false)        \
  X(kSigned16, 3, "16-bit signed integer", 2, true)             \
  X(kBoolean, 4, "Boolean", 1, false)                           \
  X(kShortInteger, 5, "Short integer", 1, true)                 \
  X(kDoubleInteger, 6, "Double integer", 4, true)               \
  X(kLongInteger, 7, "Long integer", 8, true)                   \
  X(kUnsignedShort, 8, "Unsigned short integer", 1, false)

enum class DataType : std::uint8_t {
#define SOFTSLC_X(name, code, text, size, is_signed) name = code,
  SOFTSLC_SCANPORT_DATA_TYPES(SOFTSLC_X)
#undef SOFTSLC_X
};

struct DataTypeInfo {
  DataType type;
  std::uint8_t code;
  std::string_view description;
  int size;
  bool is_signed;
};

inline constexpr DataTypeInfo kDataTypes[] = {
#define SOFTSLC_X(name, code, text, size, is_signed) {DataType::name, code, text, size, is_signed},
    SOFTSLC_SCANPORT_DATA_TYPES(SOFTSLC_X)
#undef SOFTSLC_X
};

constexpr const DataTypeInfo* find_data_type(int code) {
  for (const auto& t : kDataTypes)
    if (t.code == code) return &t;
  return nullptr;
}
constexpr const DataTypeInfo& info(DataType t) { return *find_data_type(static_cast<int>(t)); }
// The smallest and largest value a type can hold.
std::int64_t type_minimum(DataType t);
std::int64_t type_maximum(DataType t);

// ---------------------------------------------------------------------------------------------
// Descriptor bits (Read Full Parameter attribute 4; the descriptor table on page B-12).
// Columns: enumerator, bit, JSON name, the manual's definition. Bit 0 is "Not used. This bit
// should always be 0."; it has no row, so a description cannot set it.
#define SOFTSLC_SCANPORT_DESCRIPTOR_BITS(X)                                                      \
  X(kEnum, 1, "enum", "Supports ENUM strings.")                                                   \
  X(kScaling, 2, "scaling", "Supports scaling.")                                                  \
  X(kScalingLinks, 3, "scaling_links", "Supports scaling links.")                                 \
  X(kReadOnly, 4, "read_only", "Read only parameter.")                                            \
  X(kMonitor, 5, "monitor", "Monitor parameter (parameter is continuously updated by SCANport device).") \
  X(kExtendedPrecision, 6, "extended_precision", "Supports extended precision scaling.")

namespace descriptor {
#define SOFTSLC_X(name, bit, json, text) inline constexpr std::uint16_t name = 1u << bit;
SOFTSLC_SCANPORT_DESCRIPTOR_BITS(SOFTSLC_X)
#undef SOFTSLC_X
}  // namespace descriptor

struct DescriptorBitInfo {
  std::uint16_t mask;
  int bit;
  std::string_view json_name;
  std::string_view meaning;
};

inline constexpr DescriptorBitInfo kDescriptorBits[] = {
#define SOFTSLC_X(name, bit, json, text) {descriptor::name, bit, json, text},
    SOFTSLC_SCANPORT_DESCRIPTOR_BITS(SOFTSLC_X)
#undef SOFTSLC_X
};

inline constexpr std::uint16_t kDescriptorDefinedBits = [] {
  std::uint16_t m = 0;
  for (const auto& b : kDescriptorBits) m |= b.mask;
  return m;
}();

// ---------------------------------------------------------------------------------------------
// Logic command and status functions. The manual leaves their bit positions to each product
// ("Different SCANport devices may define different meanings for the bits in the Logic Command
// and Logic Status fields", chapter 3), so a description maps each function to a bit (or to
// none). Columns: enumerator, JSON name, meaning in the model.
#define SOFTSLC_SCANPORT_COMMAND_FUNCTIONS(X)                                                      \
  /* Level: while 1 the run latch is clear; wins over start. */                                     \
  X(kStop, "stop", "while set, the drive stops (clears the run latch); wins over start")            \
  /* Edge: a 0 -> 1 change sets the run latch unless stop is set or the drive is faulted. */        \
  X(kStart, "start", "rising edge starts the drive")                                                \
  /* Edge: a 0 -> 1 change clears a fault. */                                                       \
  X(kClearFaults, "clear_faults", "rising edge clears a fault")                                     \
  /* Level: forward alone selects forward; with reverse, or neither, keeps the direction. */        \
  X(kForward, "forward", "selects forward rotation")                                                \
  X(kReverse, "reverse", "selects reverse rotation")

enum class CommandFunction : std::uint8_t {
#define SOFTSLC_X(name, json, text) name,
  SOFTSLC_SCANPORT_COMMAND_FUNCTIONS(SOFTSLC_X)
#undef SOFTSLC_X
};
inline constexpr std::string_view kCommandFunctionNames[] = {
#define SOFTSLC_X(name, json, text) json,
    SOFTSLC_SCANPORT_COMMAND_FUNCTIONS(SOFTSLC_X)
#undef SOFTSLC_X
};
inline constexpr int kCommandFunctionCount = static_cast<int>(std::size(kCommandFunctionNames));

#define SOFTSLC_SCANPORT_STATUS_FUNCTIONS(X)                                                  \
  X(kEnabled, "enabled", "the drive is not faulted and can run")                               \
  X(kRunning, "running", "the run latch is set or the motor is still turning")                 \
  X(kCommandForward, "command_forward", "the commanded direction is forward")                  \
  X(kRotatingForward, "rotating_forward", "the motor turns forward (or is stopped, commanded forward)") \
  X(kAccelerating, "accelerating", "the speed magnitude is rising toward the target")          \
  X(kDecelerating, "decelerating", "the speed magnitude is falling toward the target")         \
  X(kFaulted, "faulted", "a fault is latched")                                                 \
  X(kAtSpeed, "at_speed", "running, and the speed is within at_speed_band of the reference")

enum class StatusFunction : std::uint8_t {
#define SOFTSLC_X(name, json, text) name,
  SOFTSLC_SCANPORT_STATUS_FUNCTIONS(SOFTSLC_X)
#undef SOFTSLC_X
};
inline constexpr std::string_view kStatusFunctionNames[] = {
#define SOFTSLC_X(name, json, text) json,
    SOFTSLC_SCANPORT_STATUS_FUNCTIONS(SOFTSLC_X)
#undef SOFTSLC_X
};
inline constexpr int kStatusFunctionCount = static_cast<int>(std::size(kStatusFunctionNames));

// ---------------------------------------------------------------------------------------------
// Parameters whose value the drive itself keeps current (they must be read-only). Columns:
// enumerator, JSON name, what the drive writes there at every update.
#define SOFTSLC_SCANPORT_ROLES(X)                                                                       \
  /* Not written: the display value the reference full scale stands for ("Maximum Freq"). */            \
  X(kMaximumFrequency, "maximum_frequency", "read: the display value of a full-scale reference")        \
  X(kOutputFrequency, "output_frequency", "|feedback| / full scale x maximum_frequency, in its units")   \
  X(kFrequencyCommand, "frequency_command", "reference / full scale x maximum_frequency, in its units") \
  X(kDriveStatus, "drive_status", "the logic status word")                                              \
  X(kLastFault, "last_fault", "the code passed to the last fault()")

enum class Role : std::uint8_t {
#define SOFTSLC_X(name, json, text) name,
  SOFTSLC_SCANPORT_ROLES(SOFTSLC_X)
#undef SOFTSLC_X
};
inline constexpr std::string_view kRoleNames[] = {
#define SOFTSLC_X(name, json, text) json,
    SOFTSLC_SCANPORT_ROLES(SOFTSLC_X)
#undef SOFTSLC_X
};
inline constexpr int kRoleCount = static_cast<int>(std::size(kRoleNames));

// Datalinks A1, A2, B1, B2, C1, C2, D1, D2 (chapter 4, "What Are Datalinks?").
inline constexpr int kDatalinkWords = 8;
inline constexpr std::string_view kDatalinkNames[kDatalinkWords] = {"A1", "A2", "B1", "B2",
                                                                    "C1", "C2", "D1", "D2"};

// Fixed string field widths (Figures B.6, B.8, B.12, B.14).
inline constexpr int kNameChars = 16;
inline constexpr int kUnitsChars = 4;
inline constexpr int kEnumChars = 12;
inline constexpr int kProductTextChars = 16;
// Parameter numbers share the 16-bit scattered entry word with the error flag (bit 15), so a
// database holds at most 0x7FFF parameters.
inline constexpr int kMaxParameters = 0x7FFF;

// ---------------------------------------------------------------------------------------------
// The description.

struct ParameterScaling {
  std::uint16_t multiplier = 1;  // attribute 13
  std::uint16_t divisor = 1;     // attribute 14
  std::uint16_t base = 1;        // attribute 15
  std::int16_t offset = 0;       // attribute 16
  // Attributes 17-20: the parameter whose value replaces the factor when descriptor bit 3
  // (scaling links) is set; 0 = use the fixed factor.
  std::uint16_t multiplier_link = 0;
  std::uint16_t divisor_link = 0;
  std::uint16_t base_link = 0;
  std::uint16_t offset_link = 0;
  std::uint8_t precision = 0;  // attribute 21, decimal places (0-9)
};

struct ParameterSpec {
  int number = 0;       // instance, 1..n
  std::string name;     // up to 16 characters; sent space-padded
  std::string units;    // up to 4 characters; sent space-padded
  DataType type = DataType::kUnsigned16;
  std::uint16_t descriptor = 0;
  std::int64_t minimum = 0;
  std::int64_t maximum = 0;
  std::int64_t default_value = 0;  // factory default (Reset to Default)
  std::int64_t value = 0;          // the value in non-volatile storage at first power-up
  ParameterScaling scaling;
  std::vector<std::string> enums;  // index = value (or bit number); up to 12 characters each
  std::uint16_t link = 0;          // class 0x99 link at first power-up; 0 = none
  std::uint16_t default_link = 0;  // link after Reset to Default
  bool stopped_only = false;       // writes while running fail with error 7
  std::string source;              // where the figures come from (documentation only)

  bool has(std::uint16_t descriptor_mask) const { return (descriptor & descriptor_mask) != 0; }
  int size() const { return info(type).size; }
};

struct ProductIdentity {
  std::uint16_t number = 0;                   // class 0x92 instance 0 attribute 0
  std::string text;                           // attribute 1, up to 16 characters
  std::uint16_t series = 1;                   // attribute 3, 1 = A, 2 = B, ...
  std::vector<std::uint16_t> software_versions;  // instance n attribute 1, n = 1..; 0x00CA = FRN 2.02
};

struct SpeedResponse {
  std::uint16_t reference_full_scale = 32767;  // reference/feedback word for maximum speed
  Nanoseconds time_constant = 500 * kNsPerMs;  // first-order time constant
  Nanoseconds update_period = 1 * kNsPerMs;    // plant update interval
  std::uint16_t at_speed_band = 164;           // |reference - feedback| for "at speed", counts
};

struct DriveDescription {
  std::string name;   // "1305"
  std::string title;  // free text
  ProductIdentity product;
  // Optional services and classes the device has, by JSON name (codes.h "feature" column).
  std::vector<std::string> optional_features;
  // Padding granule per ObjectKind: every reply to that object is padded with zero bytes to a
  // multiple of it (1 = no padding).
  std::array<int, kObjectKindCount> response_padding{1, 1, 1, 1, 1, 1};
  // Time the device takes to act on a message once it has received it (messages.h timing).
  Nanoseconds message_processing = 2 * kNsPerMs;
  std::array<int, kCommandFunctionCount> command_bits{};  // bit 0-15, or -1 = none
  std::array<int, kStatusFunctionCount> status_bits{};    // bit 0-15, or -1 = none
  SpeedResponse speed;
  std::array<int, kRoleCount> roles{};                  // parameter number, 0 = none
  std::array<int, kDatalinkWords> data_in{};            // "Data In A1-D2" parameter numbers, 0 = none
  std::array<int, kDatalinkWords> data_out{};           // "Data Out A1-D2"
  std::vector<ParameterSpec> parameters;                // parameters[i].number == i + 1

  DriveDescription() {
    command_bits.fill(-1);
    status_bits.fill(-1);
  }
};

// An inconsistent description. The message names the offending field the way the JSON spells
// it: "parameters[6].default: 70000 is above max 60000".
class DriveDescriptionError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws DriveDescriptionError at the first inconsistency (see the invariants above).
void validate(const DriveDescription& d);

// ---------------------------------------------------------------------------------------------
// The running drive.
class Drive {
 public:
  // Validates the description (throws DriveDescriptionError) and powers up: RAM values and
  // links from the description's "value" and "link" (the first non-volatile contents), stopped,
  // no fault, logic command and reference 0, at virtual time 0.
  explicit Drive(DriveDescription description);

  const DriveDescription& description() const { return desc_; }

  // Capabilities.
  bool supports(Service s) const;
  bool supports(ObjectClass c) const;
  int padding(ObjectKind k) const { return desc_.response_padding[static_cast<int>(k)]; }
  Nanoseconds message_processing_time() const { return desc_.message_processing; }
  const ProductIdentity& product() const { return desc_.product; }

  // Parameter database. Numbers outside 1..parameter_count() give nullptr / kInstanceNotSupported.
  int parameter_count() const { return static_cast<int>(desc_.parameters.size()); }
  const ParameterSpec* parameter(std::int64_t number) const;
  std::int64_t value(int number) const;  // precondition: parameter(number) != nullptr
  // A write from the outside (message, datalink): read-only -> kServiceFailed, a stopped_only
  // parameter while running -> kDeviceConflict, outside minimum..maximum -> kValueOutOfRange.
  ErrorCode write_value(std::int64_t number, std::int64_t value);
  std::uint16_t link(int number) const;  // precondition: parameter(number) != nullptr
  // 0 removes the link; otherwise an existing parameter other than `number` (else kValueOutOfRange).
  ErrorCode write_link(std::int64_t number, std::int64_t source);
  // The enum text for `index`, space-padded to 12 characters; nullopt when none.
  std::optional<std::string> enum_string(int number, std::int64_t index) const;
  // Scaling factors with scaling links resolved (descriptor bit 3).
  ScalingFactors scaling_factors(int number) const;
  std::optional<Rational> display_value(int number) const;
  std::optional<std::string> display_text(int number) const;

  // Non-volatile storage. Read-only parameters are never stored: their values are the drive's.
  ErrorCode save();               // storage <- RAM (values and links)
  ErrorCode restore();            // RAM <- storage; kDeviceConflict while running
  ErrorCode reset_to_defaults();  // RAM and storage <- defaults; kDeviceConflict while running
  std::int64_t stored_value(int number) const;
  std::uint16_t stored_link(int number) const;
  // Power lost and back: RAM <- storage, stopped, fault cleared, command and reference 0. The
  // clock keeps running (virtual time is the processor's).
  void power_cycle();

  // Logic command, reference, status, feedback (the I/O image words of one channel).
  void set_logic_command(std::uint16_t word);
  void set_reference(std::uint16_t word);
  std::uint16_t logic_command() const { return command_; }
  std::uint16_t reference() const { return reference_; }
  std::uint16_t logic_status() const;
  std::uint16_t feedback() const;
  // Running in the sense of error 7: the run latch is set or the motor still turns.
  bool running() const { return run_latch_ || speed_q_ != 0; }
  // The speed has reached its target: until a command, the reference or a fault changes, every
  // plant update leaves the drive as it is (advance_to skips them).
  bool settled() const { return speed_q_ == target_q(); }
  bool faulted() const { return faulted_; }
  // Latch a fault (e.g. the SCANport connection was lost while enabled): the drive stops and
  // the last_fault parameter, if any, takes `code`.
  void fault(std::uint16_t code);

  // Datalinks: word i (0 = A1 ... 7 = D2). A write goes to the parameter that Data In Xi names
  // (as write_value; kNone when Data In Xi is 0, kServiceNotSupported when the drive has no
  // such datalink, kAttributeNotSupported for a parameter wider than 16 bits); a read returns
  // the low 16 bits of the parameter Data Out Xi names, 0 when none.
  ErrorCode write_datalink(int index, std::uint16_t word);
  std::uint16_t read_datalink(int index) const;

  // Virtual time.
  VirtualTime now() const { return now_; }
  // Runs every plant update due at or before t. Throws TimeWentBackwards if t < now().
  void advance_to(VirtualTime t);

  // A 16-bit message/datalink word as a value of the parameter's type: sign-extended for signed
  // types, zero-extended otherwise; nullopt for parameters wider than 2 bytes.
  std::optional<std::int64_t> value_from_word(int number, std::uint16_t word) const;

 private:
  const ParameterSpec& spec(int number) const { return desc_.parameters[static_cast<std::size_t>(number - 1)]; }
  bool stored(int number) const { return !spec(number).has(descriptor::kReadOnly); }
  int bit(CommandFunction f) const { return desc_.command_bits[static_cast<int>(f)]; }
  bool command_has(std::uint16_t word, CommandFunction f) const;
  std::int64_t target_q() const;
  void step();
  void refresh_roles();
  void set_role(Role r, std::int64_t v);

  DriveDescription desc_;
  std::vector<std::int64_t> ram_;
  std::vector<std::int64_t> storage_;
  std::vector<std::uint16_t> ram_links_;
  std::vector<std::uint16_t> stored_links_;

  std::uint16_t command_ = 0;
  std::uint16_t reference_ = 0;
  bool run_latch_ = false;
  bool forward_ = true;
  bool faulted_ = false;
  std::uint16_t last_fault_ = 0;
  std::int64_t speed_q_ = 0;  // signed speed, reference counts x 65536

  VirtualTime now_ = 0;
  VirtualTime next_update_ = 0;  // the next k * update_period > every update already run

  // refresh_roles runs several times a scan (every command, reference and time step) and its
  // frequency roles cost exact rational arithmetic. Their value depends only on the counts given
  // and on parameter values (the maximum frequency, scaling links), so each frequency role keeps
  // its last answer with the counts and ram_version_ it was computed for. ram_version_ changes with
  // every change to a value in ram_.
  struct FrequencyMemo {
    bool valid = false;
    std::uint16_t counts = 0;
    std::uint64_t version = 0;
    std::int64_t value = 0;
  };
  std::uint64_t ram_version_ = 0;
  std::array<FrequencyMemo, 2> frequency_memo_{};
};

}  // namespace softslc::scanport
