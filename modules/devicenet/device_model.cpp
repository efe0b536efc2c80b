#include "modules/devicenet/device_model.h"

#include <algorithm>
#include <set>

namespace softslc::devicenet {

namespace detail {
struct BuiltinDeviceText {
  const char* name;
  const char* json;
};
extern const BuiltinDeviceText kBuiltinDevices[];
extern const std::size_t kBuiltinDeviceCount;
}  // namespace detail

using nlohmann::json;

std::string_view to_string(IoType t) {
  switch (t) {
    case IoType::Strobe: return "strobe";
    case IoType::Poll: return "poll";
    case IoType::Cos: return "cos";
    case IoType::Cyclic: return "cyclic";
  }
  return "?";
}

std::optional<IoType> parse_io_type(std::string_view text) {
  for (IoType t : kIoTypes)
    if (to_string(t) == text) return t;
  return std::nullopt;
}

std::uint16_t connection_instance(IoType t) {
  switch (t) {
    case IoType::Poll: return 2;
    case IoType::Strobe: return 3;
    case IoType::Cos:
    case IoType::Cyclic: return 4;
  }
  return 0;
}

int DeviceModel::input_size() const {
  int n = 0;
  for (const auto& s : io)
    if (s.supported) n = std::max(n, s.produce);
  return n;
}

int DeviceModel::output_size() const {
  int n = 0;
  for (const auto& s : io)
    if (s.supported) n = std::max(n, s.consume);
  return n;
}

namespace {

constexpr std::int64_t kMaxIoBytes = 255;

// Reads an integer-typed value of `type` at `path`.
std::int64_t typed_integer(const json& v, const std::string& path, CipType type) {
  if (type == CipType::Bool && v.is_boolean()) return v.get<bool>() ? 1 : 0;
  return integer_at(v, path, cip_type_min(type), cip_type_max(type));
}

CipType read_type(const ObjectReader& r, bool integers_only) {
  const std::string name = r.string("type");
  const auto t = parse_cip_type(name);
  if (!t) throw ConfigError(r.path("type"), "unknown CIP type \"" + name + "\"");
  if (integers_only && !cip_type_integer(*t))
    throw ConfigError(r.path("type"), "expected an integer type (BOOL, SINT, INT, DINT, USINT, UINT, UDINT, BYTE, WORD, DWORD)");
  return *t;
}

IoPoint read_point(const json& v, const std::string& path, int image_size, const char* image) {
  const ObjectReader r(v, path, {"name", "byte", "bit"});
  IoPoint p;
  p.name = r.string("name");
  if (p.name.empty()) throw ConfigError(r.path("name"), "must not be empty");
  p.byte = static_cast<int>(r.integer("byte", 0, kMaxIoBytes - 1));
  p.bit = static_cast<int>(r.integer("bit", 0, 7));
  if (p.byte >= image_size)
    throw ConfigError(r.path("byte"), std::string("byte ") + std::to_string(p.byte) + " is outside the " + image +
                                          " image of " + std::to_string(image_size) + " bytes");
  return p;
}

AttributeDef read_attribute(const json& v, const std::string& path) {
  const ObjectReader r(v, path, {"id", "name", "type", "value", "settable", "min", "max"});
  AttributeDef a;
  a.id = static_cast<std::uint8_t>(r.integer("id", 1, 255));
  a.name = r.optional_string("name");
  a.type = read_type(r, false);
  a.settable = r.boolean("settable", false);
  const json* value = r.find("value");
  if (value == nullptr) throw ConfigError(r.path("value"), "required");
  if (a.type == CipType::ShortString) {
    if (!value->is_string()) throw ConfigError(r.path("value"), "expected a string, got " + describe(*value));
    a.text = value->get<std::string>();
    if (a.text.size() > 255) throw ConfigError(r.path("value"), "a SHORT_STRING holds at most 255 characters");
  } else if (a.type == CipType::Bytes) {
    if (!value->is_array()) throw ConfigError(r.path("value"), "expected an array of bytes, got " + describe(*value));
    for (std::size_t i = 0; i < value->size(); ++i)
      a.bytes.push_back(static_cast<std::uint8_t>(integer_at((*value)[i], element_path(r.path("value"), i), 0, 255)));
  } else {
    a.value = typed_integer(*value, r.path("value"), a.type);
    a.min = r.optional_integer("min", cip_type_min(a.type), cip_type_max(a.type));
    a.max = r.optional_integer("max", cip_type_min(a.type), cip_type_max(a.type));
    if (a.min && a.max && *a.min > *a.max) throw ConfigError(r.path("min"), "min is greater than max");
    if ((a.min && a.value < *a.min) || (a.max && a.value > *a.max))
      throw ConfigError(r.path("value"), "value is outside [min, max]");
  }
  if (!cip_type_integer(a.type) && (r.has("min") || r.has("max")))
    throw ConfigError(r.path(r.has("min") ? "min" : "max"), "min/max apply to integer types only");
  return a;
}

ObjectDef read_object(const json& v, const std::string& path) {
  const ObjectReader r(v, path, {"class", "name", "revision", "instances"});
  ObjectDef o;
  o.class_id = static_cast<std::uint8_t>(r.integer("class", 1, 255));
  for (std::uint8_t builtin : {cip_class::kIdentity, cip_class::kDeviceNet, cip_class::kAssembly,
                               cip_class::kConnection, cip_class::kParameter})
    if (o.class_id == builtin)
      throw ConfigError(r.path("class"), "class " + std::to_string(o.class_id) +
                                             " is a built-in object of every simulated device");
  o.name = r.optional_string("name");
  o.revision = static_cast<std::uint16_t>(r.optional_integer("revision", 1, 65535).value_or(1));
  std::set<std::uint16_t> seen;
  r.array("instances", [&](const json& iv, const std::string& ipath) {
    const ObjectReader ir(iv, ipath, {"instance", "attributes"});
    InstanceDef inst;
    inst.instance = static_cast<std::uint16_t>(ir.integer("instance", 1, 65535));
    if (!seen.insert(inst.instance).second) throw ConfigError(ir.path("instance"), "duplicate instance");
    std::set<std::uint8_t> ids;
    ir.array("attributes", [&](const json& av, const std::string& apath) {
      inst.attributes.push_back(read_attribute(av, apath));
      if (!ids.insert(inst.attributes.back().id).second)
        throw ConfigError(child_path(apath, "id"), "duplicate attribute id");
    });
    std::sort(inst.attributes.begin(), inst.attributes.end(),
              [](const AttributeDef& a, const AttributeDef& b) { return a.id < b.id; });
    o.instances.push_back(std::move(inst));
  });
  std::sort(o.instances.begin(), o.instances.end(),
            [](const InstanceDef& a, const InstanceDef& b) { return a.instance < b.instance; });
  return o;
}

ParameterDef read_parameter(const json& v, const std::string& path) {
  const ObjectReader r(v, path, {"number", "name", "type", "value", "default", "min", "max", "units", "help", "read_only"});
  ParameterDef p;
  p.number = static_cast<std::uint16_t>(r.integer("number", 1, 65535));
  p.name = r.string("name");
  if (p.name.size() > 255) throw ConfigError(r.path("name"), "a parameter name holds at most 255 characters");
  p.type = read_type(r, true);
  const std::int64_t lo = cip_type_min(p.type), hi = cip_type_max(p.type);
  p.min = r.optional_integer("min", lo, hi).value_or(lo);
  p.max = r.optional_integer("max", lo, hi).value_or(hi);
  if (p.min > p.max) throw ConfigError(r.path("min"), "min is greater than max");
  const json* d = r.find("default");
  if (d == nullptr) throw ConfigError(r.path("default"), "required");
  p.default_value = typed_integer(*d, r.path("default"), p.type);
  if (p.default_value < p.min || p.default_value > p.max)
    throw ConfigError(r.path("default"), "default is outside [min, max]");
  p.value = p.default_value;
  if (const json* val = r.find("value")) {
    p.value = typed_integer(*val, r.path("value"), p.type);
    if (p.value < p.min || p.value > p.max) throw ConfigError(r.path("value"), "value is outside [min, max]");
  }
  p.units = r.optional_string("units");
  p.help = r.optional_string("help");
  if (p.units.size() > 255 || p.help.size() > 255)
    throw ConfigError(r.path(p.units.size() > 255 ? "units" : "help"), "at most 255 characters");
  p.read_only = r.boolean("read_only", false);
  return p;
}

}  // namespace

DeviceModel parse_device_model(const json& doc, const std::string& path) {
  const ObjectReader r(doc, path,
                       {"name", "description", "identity", "timing", "io", "inputs", "outputs", "fault_action",
                        "idle_action", "assemblies", "parameters", "objects"});
  DeviceModel m;
  m.name = r.string("name");
  if (m.name.empty()) throw ConfigError(r.path("name"), "must not be empty");
  m.description = r.optional_string("description");

  const json* id = r.object("identity");
  if (id == nullptr) throw ConfigError(r.path("identity"), "required");
  {
    const ObjectReader ir(*id, r.path("identity"),
                          {"vendor", "device_type", "product_code", "major", "minor", "serial", "product_name"});
    m.identity.vendor = static_cast<std::uint16_t>(ir.integer("vendor", 0, 65535));
    m.identity.device_type = static_cast<std::uint16_t>(ir.integer("device_type", 0, 65535));
    m.identity.product_code = static_cast<std::uint16_t>(ir.integer("product_code", 0, 65535));
    m.identity.major = static_cast<std::uint8_t>(ir.integer("major", 1, 127));
    m.identity.minor = static_cast<std::uint8_t>(ir.integer("minor", 1, 255));
    m.identity.serial = static_cast<std::uint32_t>(ir.optional_integer("serial", 0, 0xFFFFFFFF).value_or(0));
    m.identity.product_name = ir.string("product_name");
    if (m.identity.product_name.size() > 32)
      throw ConfigError(ir.path("product_name"), "a product name holds at most 32 characters");
  }

  m.io_response_time = microseconds(100);
  m.explicit_response_time = microseconds(1000);
  if (const json* t = r.object("timing")) {
    const ObjectReader tr(*t, r.path("timing"), {"io_response_us", "explicit_response_us"});
    m.io_response_time = microseconds(tr.optional_integer("io_response_us", 0, 1'000'000).value_or(100));
    m.explicit_response_time = microseconds(tr.optional_integer("explicit_response_us", 0, 1'000'000).value_or(1000));
  }

  const json* io = r.object("io");
  if (io == nullptr) throw ConfigError(r.path("io"), "required");
  {
    const ObjectReader ior(*io, r.path("io"), {"strobe", "poll", "cos", "cyclic"});
    for (IoType t : kIoTypes) {
      const json* c = ior.object(to_string(t));
      if (c == nullptr) continue;
      const bool strobe = t == IoType::Strobe;
      const ObjectReader cr(*c, ior.path(to_string(t)), {"produce", "consume"});
      IoSupport& s = m.io[static_cast<std::size_t>(t)];
      s.supported = true;
      // A bit-strobe response carries at most 8 bytes (DeviceNet limits strobe data to one frame);
      // what a strobed device consumes is its one bit of the strobe message: consume 0 or 1.
      s.produce = static_cast<int>(cr.integer("produce", 0, strobe ? 8 : kMaxIoBytes));
      s.consume = static_cast<int>(cr.optional_integer("consume", 0, strobe ? 1 : kMaxIoBytes).value_or(0));
    }
    if (m.support(IoType::Cos).supported && m.support(IoType::Cyclic).supported &&
        (m.support(IoType::Cos).produce != m.support(IoType::Cyclic).produce ||
         m.support(IoType::Cos).consume != m.support(IoType::Cyclic).consume))
      throw ConfigError(ior.path("cyclic"),
                        "COS and cyclic share Connection instance 4 and must have the same sizes");
  }

  const int in_size = m.input_size(), out_size = m.output_size();
  std::set<std::string> names;
  r.array("inputs", [&](const json& v, const std::string& p) {
    m.inputs.push_back(read_point(v, p, in_size, "input"));
    if (!names.insert(m.inputs.back().name).second) throw ConfigError(child_path(p, "name"), "duplicate point name");
  });
  names.clear();
  r.array("outputs", [&](const json& v, const std::string& p) {
    m.outputs.push_back(read_point(v, p, out_size, "output"));
    if (!names.insert(m.outputs.back().name).second) throw ConfigError(child_path(p, "name"), "duplicate point name");
  });
  m.fault_action = r.choice("fault_action", {"clear", "hold"}, "clear") == "hold" ? OutputAction::Hold : OutputAction::Clear;
  m.idle_action = r.choice("idle_action", {"clear", "hold"}, "clear") == "hold" ? OutputAction::Hold : OutputAction::Clear;

  std::set<std::uint16_t> assemblies;
  r.array("assemblies", [&](const json& v, const std::string& p) {
    const ObjectReader ar(v, p, {"instance", "kind"});
    AssemblyDef a;
    a.instance = static_cast<std::uint16_t>(ar.integer("instance", 1, 65535));
    a.kind = ar.choice("kind", {"input", "output"}) == "input" ? AssemblyDef::Kind::Input : AssemblyDef::Kind::Output;
    if (!assemblies.insert(a.instance).second) throw ConfigError(ar.path("instance"), "duplicate assembly instance");
    m.assemblies.push_back(a);
  });
  std::set<std::uint16_t> numbers;
  r.array("parameters", [&](const json& v, const std::string& p) {
    m.parameters.push_back(read_parameter(v, p));
    if (!numbers.insert(m.parameters.back().number).second)
      throw ConfigError(child_path(p, "number"), "duplicate parameter number");
  });
  std::sort(m.parameters.begin(), m.parameters.end(),
            [](const ParameterDef& a, const ParameterDef& b) { return a.number < b.number; });
  std::set<std::uint8_t> classes;
  r.array("objects", [&](const json& v, const std::string& p) {
    m.objects.push_back(read_object(v, p));
    if (!classes.insert(m.objects.back().class_id).second) throw ConfigError(child_path(p, "class"), "duplicate class");
  });
  return m;
}

DeviceModel parse_device_model_text(std::string_view json_text, std::string_view source) {
  return parse_device_model(parse_json_text(json_text, source));
}

std::vector<std::string> builtin_device_names() {
  std::vector<std::string> names;
  for (std::size_t i = 0; i < detail::kBuiltinDeviceCount; ++i) names.emplace_back(detail::kBuiltinDevices[i].name);
  return names;
}

std::string_view builtin_device_json(std::string_view name) {
  for (std::size_t i = 0; i < detail::kBuiltinDeviceCount; ++i)
    if (name == detail::kBuiltinDevices[i].name) return detail::kBuiltinDevices[i].json;
  std::string known;
  for (const auto& n : builtin_device_names()) known += (known.empty() ? "" : ", ") + n;
  throw ConfigError("", "no built-in device model \"" + std::string(name) + "\" (built in: " + known + ")");
}

DeviceModel builtin_device_model(std::string_view name) {
  return parse_device_model_text(builtin_device_json(name), std::string("built-in device ") + std::string(name));
}

}  // namespace softslc::devicenet
