// Device descriptions: what a simulated DeviceNet slave is, as data.
//
// A DeviceModel says everything the simulation needs to know about a kind of device and nothing
// about any one instance of it: its identity (the electronic key the scanner checks), which I/O
// connections it supports and how many bytes each produces and consumes, how fast it answers,
// its named input and output bits, what its outputs do when the master goes idle or away, and the
// CIP objects its explicit-message server exposes (assemblies, a parameter table, vendor objects).
// SimDevice (sim_device.h) is the running instance.
//
// Models are loaded from JSON (docs/1747-sdn.md, "Device descriptions") by a strict reader that
// names the path of any bad field. Three models ship compiled into the library from
// modules/devicenet/devices/*.json: "series-9000-photoeye", "redistation" and "ac-drive"; CMake
// turns each file into a raw string literal, so the binary needs no data files and the JSON in the
// repository is the single source of truth.
//
// Invariants after parsing: every size is 0...255 bytes; every named point lies inside the device's
// input or output image; parameter numbers, assembly instances, vendor classes, instances and
// attribute ids are unique and never collide with the built-in objects (Identity 1, DeviceNet 3,
// Assembly 4, Connection 5, Parameter 0x0F); every integer value fits its CIP type and lies in its
// [min, max] range.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "modules/devicenet/cip.h"
#include "modules/devicenet/json_reader.h"
#include "vm/virtual_time.h"

namespace softslc::devicenet {

// The four I/O connection types a 1747-SDN scanlist entry can use (chapter 1, p.16).
enum class IoType : std::uint8_t { Strobe = 0, Poll = 1, Cos = 2, Cyclic = 3 };
inline constexpr std::array<IoType, 4> kIoTypes = {IoType::Strobe, IoType::Poll, IoType::Cos, IoType::Cyclic};
std::string_view to_string(IoType t);  // "strobe", "poll", "cos", "cyclic"
std::optional<IoType> parse_io_type(std::string_view text);
// The Connection object (class 5) instance of the predefined master/slave set that carries a
// connection type: 2 poll, 3 bit-strobe, 4 change of state / cyclic (so COS and cyclic exclude
// each other on one device).
std::uint16_t connection_instance(IoType t);

struct IoSupport {
  bool supported = false;
  int produce = 0;  // bytes the device sends (scanner input, "rx")
  int consume = 0;  // bytes the device receives (scanner output, "tx"); strobe: 0, or 1 = its strobe bit
};

struct Identity {
  std::uint16_t vendor = 0;
  std::uint16_t device_type = 0;
  std::uint16_t product_code = 0;
  std::uint8_t major = 1;
  std::uint8_t minor = 1;
  std::uint32_t serial = 0;
  std::string product_name;
  bool operator==(const Identity&) const = default;
};

struct IoPoint {
  std::string name;
  int byte = 0;
  int bit = 0;
};

// What a device does with its outputs when the master goes to Idle (zero-length data) or stops
// talking to it (connection timeout): clear them to 0 or hold the last Run values.
enum class OutputAction : std::uint8_t { Clear, Hold };

struct AssemblyDef {
  enum class Kind : std::uint8_t { Input, Output };
  std::uint16_t instance = 0;
  Kind kind = Kind::Input;  // Input: attribute 3 is the input image; Output: the output image
};

struct ParameterDef {
  std::uint16_t number = 0;  // the Parameter object instance
  std::string name;
  CipType type = CipType::Uint;
  std::int64_t value = 0;  // initial value
  std::int64_t min = 0;
  std::int64_t max = 0;
  std::int64_t default_value = 0;
  std::string units;
  std::string help;
  bool read_only = false;
};

struct AttributeDef {
  std::uint8_t id = 0;
  std::string name;
  CipType type = CipType::Usint;
  std::int64_t value = 0;  // integer types
  std::string text;        // SHORT_STRING
  Bytes bytes;             // BYTES
  bool settable = false;
  std::optional<std::int64_t> min, max;  // integer types: accepted range on Set (defaults: the type's)
};

struct InstanceDef {
  std::uint16_t instance = 0;
  std::vector<AttributeDef> attributes;
};

struct ObjectDef {
  std::uint8_t class_id = 0;
  std::string name;
  std::uint16_t revision = 1;
  std::vector<InstanceDef> instances;
};

struct DeviceModel {
  std::string name;
  std::string description;
  Identity identity;
  std::array<IoSupport, 4> io{};  // indexed by IoType
  Nanoseconds io_response_time = 0;
  Nanoseconds explicit_response_time = 0;
  std::vector<IoPoint> inputs;
  std::vector<IoPoint> outputs;
  OutputAction fault_action = OutputAction::Clear;
  OutputAction idle_action = OutputAction::Clear;
  std::vector<AssemblyDef> assemblies;
  std::vector<ParameterDef> parameters;
  std::vector<ObjectDef> objects;

  const IoSupport& support(IoType t) const { return io[static_cast<std::size_t>(t)]; }
  // Image sizes: the largest produce (consume) size over the supported connections.
  int input_size() const;
  int output_size() const;
};

// Reads a device description. Throws ConfigError naming the offending path under `path`.
DeviceModel parse_device_model(const nlohmann::json& doc, const std::string& path = "");
DeviceModel parse_device_model_text(std::string_view json_text, std::string_view source = "device description");

// The models compiled into the library, by name, in a fixed order.
std::vector<std::string> builtin_device_names();
// Throws ConfigError (path "") for an unknown name.
DeviceModel builtin_device_model(std::string_view name);
// The JSON text a built-in model was compiled from.
std::string_view builtin_device_json(std::string_view name);

}  // namespace softslc::devicenet
