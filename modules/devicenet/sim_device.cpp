#include "modules/devicenet/sim_device.h"

#include <algorithm>

namespace softslc::devicenet {

std::string_view to_string(OutputState s) {
  switch (s) {
    case OutputState::NotConnected: return "not connected";
    case OutputState::Run: return "run";
    case OutputState::Idle: return "idle";
    case OutputState::Fault: return "fault";
  }
  return "?";
}

namespace {

Bytes encode_int(std::int64_t v, CipType t) {
  Bytes b;
  put_le(b, static_cast<std::uint64_t>(v), cip_type_size(t));
  return b;
}

std::int64_t decode_int(std::span<const std::uint8_t> in, CipType t) {
  const int size = cip_type_size(t);
  std::uint64_t u = get_le(in, size);
  if (cip_type_signed(t) && size < 8 && (u >> (8 * size - 1)) != 0) u |= ~std::uint64_t{0} << (8 * size);
  return static_cast<std::int64_t>(u);
}

Bytes short_string(std::string_view s) {
  // Sized up front: GCC 12 warns (falsely) about vector::insert of a char range here.
  Bytes b(s.size() + 1, 0);
  b[0] = static_cast<std::uint8_t>(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) b[i + 1] = static_cast<std::uint8_t>(s[i]);
  return b;
}

// Get_Attribute_Single needs exactly one body byte (the attribute).
std::optional<CipReply> check_get_single(const CipRequest& r) {
  if (r.body.empty()) return CipReply::error(CipStatus::NotEnoughData);
  if (r.body.size() > 1) return CipReply::error(CipStatus::TooMuchData);
  return std::nullopt;
}

// An integer value for Set_Attribute_Single: exact size, then range.
CipReply set_integer(std::span<const std::uint8_t> data, CipType t, std::int64_t lo, std::int64_t hi,
                     std::int64_t& target) {
  const auto size = static_cast<std::size_t>(cip_type_size(t));
  if (data.size() < size) return CipReply::error(CipStatus::NotEnoughData);
  if (data.size() > size) return CipReply::error(CipStatus::TooMuchData);
  const std::int64_t v = decode_int(data, t);
  if (v < lo || v > hi) return CipReply::error(CipStatus::InvalidAttributeValue);
  target = v;
  return CipReply::success();
}

// Class-level attributes every object answers: 1 revision, 2 max instance.
CipReply class_attributes(const CipRequest& r, std::uint16_t revision, std::uint16_t max_instance) {
  if (r.service == service::kSetAttributeSingle) {
    if (r.body.empty()) return CipReply::error(CipStatus::NotEnoughData);
    return r.body[0] == 1 || r.body[0] == 2 ? CipReply::error(CipStatus::AttributeNotSettable)
                                            : CipReply::error(CipStatus::AttributeNotSupported);
  }
  if (r.service != service::kGetAttributeSingle) return CipReply::error(CipStatus::ServiceNotSupported);
  if (auto e = check_get_single(r)) return *e;
  Bytes b;
  if (r.body[0] == 1) put_le(b, revision, 2);
  else if (r.body[0] == 2) put_le(b, max_instance, 2);
  else return CipReply::error(CipStatus::AttributeNotSupported);
  return CipReply::success(std::move(b));
}

}  // namespace

SimDevice::SimDevice(DeviceModel model) : model_(std::move(model)) {
  inputs_.assign(static_cast<std::size_t>(model_.input_size()), 0);
  outputs_.assign(static_cast<std::size_t>(model_.output_size()), 0);
  for (const auto& p : model_.parameters) parameter_values_.push_back(p.value);
  objects_ = model_.objects;
}

// ---- I/O -----------------------------------------------------------------------------------------

SimDevice::AllocateResult SimDevice::allocate(std::span<const IoType> types) {
  if (!online_) return AllocateResult::NoResponse;
  if (owned_elsewhere_) return AllocateResult::Refused;
  for (IoType t : types)
    if (!supports(t)) return AllocateResult::Refused;
  allocated_ = true;
  return AllocateResult::Ok;
}

int SimDevice::produced_size(IoType t) const {
  if (!supports(t)) return 0;
  return size_override_ ? *size_override_ : model_.support(t).produce;
}

int SimDevice::consumed_size(IoType t) const { return supports(t) ? model_.support(t).consume : 0; }

std::optional<Bytes> SimDevice::produce(IoType t) const {
  const std::optional<int> length = produced_length(t);  // silent, idle (0) or the input image's size
  if (!length) return std::nullopt;
  Bytes out(static_cast<std::size_t>(*length), 0);
  std::copy_n(inputs_.begin(), std::min(out.size(), inputs_.size()), out.begin());
  return out;
}

void SimDevice::consume(IoType t, std::span<const std::uint8_t> data) {
  if (!online_ || !allocated_ || !supports(t)) return;
  ++consumed_[static_cast<std::size_t>(t)];
  const bool consumes = t == IoType::Strobe ? !outputs_.empty() : consumed_size(t) > 0;
  if (data.empty()) {
    if (!consumes) return;
    if (output_state_ != OutputState::Idle) apply_action(model_.idle_action);
    output_state_ = OutputState::Idle;
    return;
  }
  if (t == IoType::Strobe) {
    if (!outputs_.empty()) outputs_[0] = static_cast<std::uint8_t>((outputs_[0] & ~1u) | (data[0] & 1u));
  } else {
    std::copy_n(data.begin(), std::min(data.size(), outputs_.size()), outputs_.begin());
  }
  output_state_ = OutputState::Run;
}

void SimDevice::master_lost() {
  if (!online_) return;
  allocated_ = false;
  if (output_state_ == OutputState::Run) apply_action(model_.fault_action);
  if (output_state_ != OutputState::NotConnected) output_state_ = OutputState::Fault;
}

void SimDevice::apply_action(OutputAction a) {
  if (a == OutputAction::Clear) std::fill(outputs_.begin(), outputs_.end(), 0);
}

void SimDevice::set_online(bool online) {
  if (online_ == online) return;
  online_ = online;
  if (!online) {
    allocated_ = false;
    std::fill(outputs_.begin(), outputs_.end(), 0);
    output_state_ = OutputState::NotConnected;
  }
}

// ---- field side ----------------------------------------------------------------------------------

bool SimDevice::set_input(std::string_view point, bool value) {
  for (const auto& p : model_.inputs) {
    if (p.name != point) continue;
    auto& byte = inputs_[static_cast<std::size_t>(p.byte)];
    const auto before = byte;
    byte = static_cast<std::uint8_t>(value ? byte | (1u << p.bit) : byte & ~(1u << p.bit));
    if (byte != before) notify_input();
    return true;
  }
  return false;
}

void SimDevice::set_input_byte(int byte, std::uint8_t value) {
  if (byte < 0 || static_cast<std::size_t>(byte) >= inputs_.size()) return;
  auto& b = inputs_[static_cast<std::size_t>(byte)];
  if (b == value) return;
  b = value;
  notify_input();
}

std::optional<bool> SimDevice::input(std::string_view point) const {
  for (const auto& p : model_.inputs)
    if (p.name == point) return ((inputs_[static_cast<std::size_t>(p.byte)] >> p.bit) & 1) != 0;
  return std::nullopt;
}

std::optional<bool> SimDevice::output(std::string_view point) const {
  for (const auto& p : model_.outputs)
    if (p.name == point) return ((outputs_[static_cast<std::size_t>(p.byte)] >> p.bit) & 1) != 0;
  return std::nullopt;
}

// ---- explicit messaging ----------------------------------------------------------------------------

CipReply SimDevice::handle(const CipRequest& r) {
  switch (r.class_id) {
    case cip_class::kIdentity: return identity_service(r);
    case cip_class::kDeviceNet: return devicenet_service(r);
    case cip_class::kAssembly: return assembly_service(r);
    case cip_class::kConnection: return connection_service(r);
    case cip_class::kParameter: return parameter_service(r);
    default:
      for (auto& o : objects_)
        if (o.class_id == r.class_id) return vendor_service(o, r);
      return CipReply::error(CipStatus::ObjectDoesNotExist);
  }
}

Bytes SimDevice::identity_attribute(std::uint8_t id) const {
  const Identity& ident = identity();
  Bytes b;
  switch (id) {
    case 1: put_le(b, ident.vendor, 2); break;
    case 2: put_le(b, ident.device_type, 2); break;
    case 3: put_le(b, ident.product_code, 2); break;
    case 4: b = {ident.major, ident.minor}; break;
    case 5: put_le(b, allocated_ ? 0x0001 : 0x0000, 2); break;  // bit 0: owned by a master
    case 6: put_le(b, ident.serial, 4); break;
    case 7: b = short_string(ident.product_name); break;
    default: break;
  }
  return b;
}

CipReply SimDevice::identity_service(const CipRequest& r) {
  if (r.instance == 0) return class_attributes(r, 1, 1);
  if (r.instance != 1) return CipReply::error(CipStatus::ObjectDoesNotExist);
  switch (r.service) {
    case service::kGetAttributeSingle: {
      if (auto e = check_get_single(r)) return *e;
      if (r.body[0] < 1 || r.body[0] > 7) return CipReply::error(CipStatus::AttributeNotSupported);
      return CipReply::success(identity_attribute(r.body[0]));
    }
    case service::kSetAttributeSingle:
      if (r.body.empty()) return CipReply::error(CipStatus::NotEnoughData);
      return r.body[0] >= 1 && r.body[0] <= 7 ? CipReply::error(CipStatus::AttributeNotSettable)
                                              : CipReply::error(CipStatus::AttributeNotSupported);
    case service::kGetAttributesAll: {
      if (!r.body.empty()) return CipReply::error(CipStatus::TooMuchData);
      Bytes all;
      for (std::uint8_t id = 1; id <= 7; ++id) {
        const Bytes a = identity_attribute(id);
        all.insert(all.end(), a.begin(), a.end());
      }
      return CipReply::success(std::move(all));
    }
    case service::kReset: {
      if (r.body.size() > 1) return CipReply::error(CipStatus::TooMuchData);
      if (!r.body.empty() && r.body[0] > 1) return CipReply::error(CipStatus::InvalidParameter);
      // The reply goes out before the device restarts: connections close, outputs de-energise, and
      // type 1 (return to factory defaults) also restores the parameter table.
      if (!r.body.empty() && r.body[0] == 1)
        for (std::size_t i = 0; i < parameter_values_.size(); ++i)
          parameter_values_[i] = model_.parameters[i].default_value;
      allocated_ = false;
      std::fill(outputs_.begin(), outputs_.end(), 0);
      output_state_ = OutputState::NotConnected;
      return CipReply::success();
    }
    default: return CipReply::error(CipStatus::ServiceNotSupported);
  }
}

CipReply SimDevice::devicenet_service(const CipRequest& r) {
  if (r.instance == 0) return class_attributes(r, 2, 1);
  if (r.instance != 1) return CipReply::error(CipStatus::ObjectDoesNotExist);
  if (r.service == service::kSetAttributeSingle) {
    if (r.body.empty()) return CipReply::error(CipStatus::NotEnoughData);
    // Address and data rate come from the device's switches in this simulation.
    return r.body[0] == 1 || r.body[0] == 2 ? CipReply::error(CipStatus::AttributeNotSettable)
                                            : CipReply::error(CipStatus::AttributeNotSupported);
  }
  if (r.service != service::kGetAttributeSingle) return CipReply::error(CipStatus::ServiceNotSupported);
  if (auto e = check_get_single(r)) return *e;
  if (r.body[0] == 1) return CipReply::success(Bytes{static_cast<std::uint8_t>(mac_)});
  if (r.body[0] == 2) return CipReply::success(Bytes{static_cast<std::uint8_t>(baud_)});
  return CipReply::error(CipStatus::AttributeNotSupported);
}

CipReply SimDevice::assembly_service(const CipRequest& r) {
  std::uint16_t max_instance = 0;
  for (const auto& a : model_.assemblies) max_instance = std::max(max_instance, a.instance);
  if (r.instance == 0) return class_attributes(r, 2, max_instance);
  const AssemblyDef* def = nullptr;
  for (const auto& a : model_.assemblies)
    if (a.instance == r.instance) def = &a;
  if (def == nullptr) return CipReply::error(CipStatus::ObjectDoesNotExist);
  const bool output = def->kind == AssemblyDef::Kind::Output;
  switch (r.service) {
    case service::kGetAttributeSingle:
      if (auto e = check_get_single(r)) return *e;
      if (r.body[0] != 3) return CipReply::error(CipStatus::AttributeNotSupported);
      return CipReply::success(output ? outputs_ : inputs_);
    case service::kGetAttributesAll:
      if (!r.body.empty()) return CipReply::error(CipStatus::TooMuchData);
      return CipReply::success(output ? outputs_ : inputs_);
    case service::kSetAttributeSingle: {
      if (r.body.empty()) return CipReply::error(CipStatus::NotEnoughData);
      if (r.body[0] != 3) return CipReply::error(CipStatus::AttributeNotSupported);
      if (!output) return CipReply::error(CipStatus::AttributeNotSettable);
      const std::size_t n = r.body.size() - 1;
      if (n < outputs_.size()) return CipReply::error(CipStatus::NotEnoughData);
      if (n > outputs_.size()) return CipReply::error(CipStatus::TooMuchData);
      // A Run I/O connection owns the outputs; writing them explicitly would fight the scanner.
      if (output_state_ == OutputState::Run) return CipReply::error(CipStatus::DeviceStateConflict);
      std::copy(r.body.begin() + 1, r.body.end(), outputs_.begin());
      return CipReply::success();
    }
    default: return CipReply::error(CipStatus::ServiceNotSupported);
  }
}

CipReply SimDevice::connection_service(const CipRequest& r) {
  if (r.instance == 0) return class_attributes(r, 1, 4);
  IoType type{};
  bool found = false;
  for (IoType t : kIoTypes)
    if (supports(t) && connection_instance(t) == r.instance) {
      type = t;
      found = true;
      break;
    }
  if (!found) return CipReply::error(CipStatus::ObjectDoesNotExist);
  auto& epr = epr_ms_[r.instance];
  if (r.service == service::kSetAttributeSingle) {
    if (r.body.empty()) return CipReply::error(CipStatus::NotEnoughData);
    const std::uint8_t a = r.body[0];
    if (a == 9) {
      std::int64_t v = 0;
      CipReply rep = set_integer(std::span(r.body).subspan(1), CipType::Uint, 0, 65535, v);
      if (rep.ok()) epr = static_cast<std::uint16_t>(v);
      return rep;
    }
    return a == 1 || a == 7 || a == 8 ? CipReply::error(CipStatus::AttributeNotSettable)
                                      : CipReply::error(CipStatus::AttributeNotSupported);
  }
  if (r.service != service::kGetAttributeSingle) return CipReply::error(CipStatus::ServiceNotSupported);
  if (auto e = check_get_single(r)) return *e;
  Bytes b;
  switch (r.body[0]) {
    case 1: b.push_back(allocated_ ? 3 : 1); break;  // 3 established, 1 configuring
    case 7: put_le(b, static_cast<std::uint64_t>(produced_size(type)), 2); break;
    case 8: put_le(b, static_cast<std::uint64_t>(consumed_size(type)), 2); break;
    case 9: put_le(b, epr, 2); break;
    default: return CipReply::error(CipStatus::AttributeNotSupported);
  }
  return CipReply::success(std::move(b));
}

CipReply SimDevice::parameter_service(const CipRequest& r) {
  const std::uint16_t max_instance = model_.parameters.empty() ? 0 : model_.parameters.back().number;
  if (r.instance == 0) return class_attributes(r, 1, max_instance);
  std::size_t index = model_.parameters.size();
  for (std::size_t i = 0; i < model_.parameters.size(); ++i)
    if (model_.parameters[i].number == r.instance) index = i;
  if (index == model_.parameters.size()) return CipReply::error(CipStatus::ObjectDoesNotExist);
  const ParameterDef& p = model_.parameters[index];
  if (r.service == service::kSetAttributeSingle) {
    if (r.body.empty()) return CipReply::error(CipStatus::NotEnoughData);
    const std::uint8_t a = r.body[0];
    if (a == 1) {
      if (p.read_only) return CipReply::error(CipStatus::AttributeNotSettable);
      return set_integer(std::span(r.body).subspan(1), p.type, p.min, p.max, parameter_values_[index]);
    }
    return a >= 2 && a <= 12 ? CipReply::error(CipStatus::AttributeNotSettable)
                             : CipReply::error(CipStatus::AttributeNotSupported);
  }
  if (r.service != service::kGetAttributeSingle) return CipReply::error(CipStatus::ServiceNotSupported);
  if (auto e = check_get_single(r)) return *e;
  switch (r.body[0]) {
    case 1: return CipReply::success(encode_int(parameter_values_[index], p.type));
    case 2: return CipReply::success(Bytes{0});
    case 3: return CipReply::success(Bytes{});
    case 4: {
      Bytes b;
      put_le(b, p.read_only ? 0x0010 : 0x0000, 2);
      return CipReply::success(std::move(b));
    }
    case 5: return CipReply::success(Bytes{cip_type_code(p.type)});
    case 6: return CipReply::success(Bytes{static_cast<std::uint8_t>(cip_type_size(p.type))});
    case 7: return CipReply::success(short_string(p.name));
    case 8: return CipReply::success(short_string(p.units));
    case 9: return CipReply::success(short_string(p.help));
    case 10: return CipReply::success(encode_int(p.min, p.type));
    case 11: return CipReply::success(encode_int(p.max, p.type));
    case 12: return CipReply::success(encode_int(p.default_value, p.type));
    default: return CipReply::error(CipStatus::AttributeNotSupported);
  }
}

CipReply SimDevice::vendor_service(ObjectDef& object, const CipRequest& r) {
  const std::uint16_t max_instance = object.instances.empty() ? 0 : object.instances.back().instance;
  if (r.instance == 0) return class_attributes(r, object.revision, max_instance);
  InstanceDef* inst = nullptr;
  for (auto& i : object.instances)
    if (i.instance == r.instance) inst = &i;
  if (inst == nullptr) return CipReply::error(CipStatus::ObjectDoesNotExist);
  auto value_of = [](const AttributeDef& a) {
    if (a.type == CipType::ShortString) return short_string(a.text);
    if (a.type == CipType::Bytes) return a.bytes;
    return encode_int(a.value, a.type);
  };
  auto find = [&](std::uint8_t id) -> AttributeDef* {
    for (auto& a : inst->attributes)
      if (a.id == id) return &a;
    return nullptr;
  };
  switch (r.service) {
    case service::kGetAttributeSingle: {
      if (auto e = check_get_single(r)) return *e;
      const AttributeDef* a = find(r.body[0]);
      if (a == nullptr) return CipReply::error(CipStatus::AttributeNotSupported);
      return CipReply::success(value_of(*a));
    }
    case service::kGetAttributesAll: {
      if (!r.body.empty()) return CipReply::error(CipStatus::TooMuchData);
      Bytes all;
      for (const auto& a : inst->attributes) {
        const Bytes v = value_of(a);
        all.insert(all.end(), v.begin(), v.end());
      }
      return CipReply::success(std::move(all));
    }
    case service::kSetAttributeSingle: {
      if (r.body.empty()) return CipReply::error(CipStatus::NotEnoughData);
      AttributeDef* a = find(r.body[0]);
      if (a == nullptr) return CipReply::error(CipStatus::AttributeNotSupported);
      if (!a->settable) return CipReply::error(CipStatus::AttributeNotSettable);
      const std::span<const std::uint8_t> data = std::span(r.body).subspan(1);
      if (a->type == CipType::ShortString) {
        if (data.empty()) return CipReply::error(CipStatus::NotEnoughData);
        const std::size_t len = data[0];
        if (data.size() - 1 < len) return CipReply::error(CipStatus::NotEnoughData);
        if (data.size() - 1 > len) return CipReply::error(CipStatus::TooMuchData);
        a->text.assign(data.begin() + 1, data.end());
        return CipReply::success();
      }
      if (a->type == CipType::Bytes) {
        if (data.size() < a->bytes.size()) return CipReply::error(CipStatus::NotEnoughData);
        if (data.size() > a->bytes.size()) return CipReply::error(CipStatus::TooMuchData);
        a->bytes.assign(data.begin(), data.end());
        return CipReply::success();
      }
      return set_integer(data, a->type, a->min.value_or(cip_type_min(a->type)), a->max.value_or(cip_type_max(a->type)),
                         a->value);
    }
    default: return CipReply::error(CipStatus::ServiceNotSupported);
  }
}

}  // namespace softslc::devicenet
