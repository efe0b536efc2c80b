#include "modules/scanport/drive.h"

#include <algorithm>
#include <limits>

namespace softslc::scanport {

std::int64_t type_minimum(DataType t) {
  const auto& i = info(t);
  if (!i.is_signed) return 0;
  return i.size == 8 ? std::numeric_limits<std::int64_t>::min() : -(std::int64_t{1} << (8 * i.size - 1));
}

std::int64_t type_maximum(DataType t) {
  const auto& i = info(t);
  if (t == DataType::kBoolean) return 1;
  if (i.size == 8) return std::numeric_limits<std::int64_t>::max();
  return i.is_signed ? (std::int64_t{1} << (8 * i.size - 1)) - 1 : (std::int64_t{1} << (8 * i.size)) - 1;
}

// ---------------------------------------------------------------------------------------------
// validate()

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& message) {
  throw DriveDescriptionError(path + ": " + message);
}

std::string param_path(std::size_t index, const char* field) {
  return "parameters[" + std::to_string(index) + "]" + (field[0] ? std::string(".") + field : "");
}

void check_text(const std::string& text, int width, bool allow_empty, const std::string& path) {
  if (!allow_empty && text.empty()) fail(path, "must not be empty");
  if (static_cast<int>(text.size()) > width)
    fail(path, "\"" + text + "\" is longer than " + std::to_string(width) + " characters");
  for (char c : text)
    if (c < 0x20 || c > 0x7E) fail(path, "only printable ASCII characters fit the SCANport text fields");
}

void check_parameter_number(int n, int count, bool allow_zero, const std::string& path) {
  if ((n == 0 && allow_zero) || (n >= 1 && n <= count)) return;
  fail(path, std::to_string(n) + " is not a parameter number (1-" + std::to_string(count) + ")" +
                 (allow_zero ? " or 0" : ""));
}

void check_bits(const int* bits, int count, const std::string_view* names, const std::string& path) {
  std::uint32_t used = 0;
  for (int i = 0; i < count; ++i) {
    int b = bits[i];
    if (b == -1) continue;
    std::string p = path + "." + std::string(names[i]);
    if (b < 0 || b > 15) fail(p, "expected a bit number 0-15");
    if (used & (1u << b)) fail(p, "bit " + std::to_string(b) + " is already used by another function");
    used |= 1u << b;
  }
}

}  // namespace

void validate(const DriveDescription& d) {
  check_text(d.product.text, kProductTextChars, true, "product.text");
  if (d.product.software_versions.empty())
    fail("product.software_versions", "a product has at least one microprocessor (page B-22)");
  if (d.product.software_versions.size() > 0xFFFF) fail("product.software_versions", "too many microprocessors");

  for (const auto& f : d.optional_features) {
    bool known = false;
    for (const auto& s : kServices) known |= s.feature && f == s.feature;
    for (const auto& c : kClasses) known |= c.feature && f == c.feature;
    if (!known) fail("optional_services", "unknown optional service \"" + f + "\"");
  }
  for (int k = 0; k < kObjectKindCount; ++k)
    if (d.response_padding[k] < 1 || d.response_padding[k] > 64)
      fail("response_padding." + std::string(kObjectKindNames[k]), "expected a granule of 1-64 bytes");
  if (d.message_processing < 0 || d.message_processing > 10 * kNsPerS)
    fail("message_processing_us", "expected 0-10000000 microseconds");

  check_bits(d.command_bits.data(), kCommandFunctionCount, kCommandFunctionNames, "logic_command_bits");
  check_bits(d.status_bits.data(), kStatusFunctionCount, kStatusFunctionNames, "logic_status_bits");

  const auto& s = d.speed;
  if (s.reference_full_scale < 1) fail("speed_response.reference_full_scale", "expected 1-65535");
  if (s.update_period < kNsPerUs || s.update_period > 100 * kNsPerMs)
    fail("speed_response.update_period_us", "expected 1-100000 microseconds");
  if (s.time_constant < s.update_period)
    fail("speed_response.time_constant_us", "must be at least update_period_us (a stable first-order step)");
  if (s.time_constant / s.update_period > 65536)
    fail("speed_response.time_constant_us", "must be at most 65536 update periods (fixed-point resolution)");
  if (s.at_speed_band > s.reference_full_scale)
    fail("speed_response.at_speed_band", "must not exceed reference_full_scale");

  if (d.parameters.empty()) fail("parameters", "a drive has at least one parameter");
  if (d.parameters.size() > static_cast<std::size_t>(kMaxParameters))
    fail("parameters", "at most " + std::to_string(kMaxParameters) + " parameters");
  const int count = static_cast<int>(d.parameters.size());

  for (std::size_t i = 0; i < d.parameters.size(); ++i) {
    const auto& p = d.parameters[i];
    if (p.number != static_cast<int>(i) + 1)
      fail(param_path(i, "number"), "expected " + std::to_string(i + 1) + " (parameters are listed in order from 1)");
    check_text(p.name, kNameChars, false, param_path(i, "name"));
    check_text(p.units, kUnitsChars, true, param_path(i, "units"));
    if (!find_data_type(static_cast<int>(p.type))) fail(param_path(i, "data_type"), "expected a data type code 1-8");
    if (p.descriptor & ~kDescriptorDefinedBits)
      fail(param_path(i, "descriptor"), "only bits 1-6 are defined (bit 0 \"should always be 0\")");
    const std::int64_t lo = type_minimum(p.type), hi = type_maximum(p.type);
    auto in_type = [&](std::int64_t v, const char* field) {
      if (v < lo || v > hi)
        fail(param_path(i, field), std::to_string(v) + " does not fit data type " +
                                       std::to_string(static_cast<int>(p.type)) + " (" + std::to_string(lo) + ".." +
                                       std::to_string(hi) + ")");
    };
    in_type(p.minimum, "min");
    in_type(p.maximum, "max");
    if (p.minimum > p.maximum)
      fail(param_path(i, "max"), std::to_string(p.maximum) + " is below min " + std::to_string(p.minimum));
    auto in_range = [&](std::int64_t v, const char* field) {
      if (v < p.minimum) fail(param_path(i, field), std::to_string(v) + " is below min " + std::to_string(p.minimum));
      if (v > p.maximum) fail(param_path(i, field), std::to_string(v) + " is above max " + std::to_string(p.maximum));
    };
    in_range(p.default_value, "default");
    in_range(p.value, "value");
    const auto& sc = p.scaling;
    if (sc.multiplier == 0) fail(param_path(i, "scaling.multiplier"), "must not be 0");
    if (sc.divisor == 0) fail(param_path(i, "scaling.divisor"), "must not be 0");
    if (sc.base == 0) fail(param_path(i, "scaling.base"), "must not be 0");
    if (sc.precision > 9) fail(param_path(i, "scaling.precision"), "expected 0-9 decimal places");
    check_parameter_number(sc.multiplier_link, count, true, param_path(i, "scaling.multiplier_link"));
    check_parameter_number(sc.divisor_link, count, true, param_path(i, "scaling.divisor_link"));
    check_parameter_number(sc.base_link, count, true, param_path(i, "scaling.base_link"));
    check_parameter_number(sc.offset_link, count, true, param_path(i, "scaling.offset_link"));
    if (p.has(descriptor::kEnum) != !p.enums.empty())
      fail(param_path(i, "enums"), p.enums.empty() ? "descriptor has \"enum\" but no enum strings are given"
                                                   : "enum strings need \"enum\" in the descriptor");
    if (p.enums.size() > 256) fail(param_path(i, "enums"), "at most 256 strings (the attribute word is below 256)");
    for (std::size_t e = 0; e < p.enums.size(); ++e)
      check_text(p.enums[e], kEnumChars, true, param_path(i, "enums") + "[" + std::to_string(e) + "]");
    for (auto [link, field] : {std::pair{p.link, "link"}, std::pair{p.default_link, "default_link"}}) {
      check_parameter_number(link, count, true, param_path(i, field));
      if (link == p.number) fail(param_path(i, field), "a parameter cannot be linked to itself");
    }
  }

  for (int r = 0; r < kRoleCount; ++r) {
    std::string path = "roles." + std::string(kRoleNames[r]);
    check_parameter_number(d.roles[r], count, true, path);
    if (d.roles[r] != 0 && static_cast<Role>(r) != Role::kMaximumFrequency &&
        !d.parameters[static_cast<std::size_t>(d.roles[r] - 1)].has(descriptor::kReadOnly))
      fail(path, "parameter " + std::to_string(d.roles[r]) + " is written by the drive, so it must be read_only");
  }
  for (int i = 0; i < kDatalinkWords; ++i) {
    check_parameter_number(d.data_in[i], count, true, "datalinks.data_in[" + std::to_string(i) + "]");
    check_parameter_number(d.data_out[i], count, true, "datalinks.data_out[" + std::to_string(i) + "]");
  }
}

// ---------------------------------------------------------------------------------------------
// Drive

Drive::Drive(DriveDescription description) : desc_(std::move(description)) {
  validate(desc_);
  for (const auto& p : desc_.parameters) {
    ram_.push_back(p.value);
    storage_.push_back(p.value);
    ram_links_.push_back(p.link);
    stored_links_.push_back(p.link);
  }
  next_update_ = desc_.speed.update_period;
  refresh_roles();
}

bool Drive::supports(Service s) const {
  const char* f = info(s).feature;
  return !f ||
         std::find(desc_.optional_features.begin(), desc_.optional_features.end(), f) != desc_.optional_features.end();
}

bool Drive::supports(ObjectClass c) const {
  const char* f = info(c).feature;
  return !f ||
         std::find(desc_.optional_features.begin(), desc_.optional_features.end(), f) != desc_.optional_features.end();
}

const ParameterSpec* Drive::parameter(std::int64_t number) const {
  if (number < 1 || number > parameter_count()) return nullptr;
  return &spec(static_cast<int>(number));
}

std::int64_t Drive::value(int number) const { return ram_[static_cast<std::size_t>(number - 1)]; }
std::uint16_t Drive::link(int number) const { return ram_links_[static_cast<std::size_t>(number - 1)]; }
std::int64_t Drive::stored_value(int number) const { return storage_[static_cast<std::size_t>(number - 1)]; }
std::uint16_t Drive::stored_link(int number) const { return stored_links_[static_cast<std::size_t>(number - 1)]; }

ErrorCode Drive::write_value(std::int64_t number, std::int64_t v) {
  const ParameterSpec* p = parameter(number);
  if (!p) return ErrorCode::kInstanceNotSupported;
  // The order is read-only, then state, then range: a value cannot make a read-only parameter
  // writable, and "cannot perform this request while ... running" holds whatever the value.
  if (p->has(descriptor::kReadOnly)) return ErrorCode::kServiceFailed;
  if (p->stopped_only && running()) return ErrorCode::kDeviceConflict;
  if (v < p->minimum || v > p->maximum) return ErrorCode::kValueOutOfRange;
  ram_[static_cast<std::size_t>(number - 1)] = v;
  ++ram_version_;
  refresh_roles();
  return ErrorCode::kNone;
}

ErrorCode Drive::write_link(std::int64_t number, std::int64_t source) {
  if (!parameter(number)) return ErrorCode::kInstanceNotSupported;
  if (source != 0 && (!parameter(source) || source == number)) return ErrorCode::kValueOutOfRange;
  ram_links_[static_cast<std::size_t>(number - 1)] = static_cast<std::uint16_t>(source);
  return ErrorCode::kNone;
}

std::optional<std::string> Drive::enum_string(int number, std::int64_t index) const {
  const auto& e = spec(number).enums;
  if (index < 0 || index >= static_cast<std::int64_t>(e.size())) return std::nullopt;
  std::string s = e[static_cast<std::size_t>(index)];
  s.resize(kEnumChars, ' ');
  return s;
}

ScalingFactors Drive::scaling_factors(int number) const {
  const auto& p = spec(number);
  const auto& sc = p.scaling;
  ScalingFactors f{sc.multiplier, sc.divisor, sc.base, sc.offset, sc.precision};
  if (p.has(descriptor::kScalingLinks)) {
    if (sc.multiplier_link) f.multiplier = value(sc.multiplier_link);
    if (sc.divisor_link) f.divisor = value(sc.divisor_link);
    if (sc.base_link) f.base = value(sc.base_link);
    if (sc.offset_link) f.offset = value(sc.offset_link);
  }
  return f;
}

std::optional<Rational> Drive::display_value(int number) const {
  return scanport::display_value(scaling_factors(number), value(number),
                                 spec(number).has(descriptor::kExtendedPrecision));
}

std::optional<std::string> Drive::display_text(int number) const {
  return scanport::display_text(scaling_factors(number), value(number),
                                spec(number).has(descriptor::kExtendedPrecision));
}

ErrorCode Drive::save() {
  for (int n = 1; n <= parameter_count(); ++n)
    if (stored(n)) storage_[static_cast<std::size_t>(n - 1)] = value(n);
  stored_links_ = ram_links_;
  return ErrorCode::kNone;
}

ErrorCode Drive::restore() {
  if (running()) return ErrorCode::kDeviceConflict;
  for (int n = 1; n <= parameter_count(); ++n)
    if (stored(n)) ram_[static_cast<std::size_t>(n - 1)] = stored_value(n);
  ++ram_version_;
  ram_links_ = stored_links_;
  refresh_roles();
  return ErrorCode::kNone;
}

ErrorCode Drive::reset_to_defaults() {
  // Figure B.9: "set all parameter values in the SCANport device's EEPROM and RAM to the
  // factory default values".
  if (running()) return ErrorCode::kDeviceConflict;
  for (int n = 1; n <= parameter_count(); ++n) {
    const auto i = static_cast<std::size_t>(n - 1);
    if (stored(n)) ram_[i] = storage_[i] = spec(n).default_value;
    ram_links_[i] = stored_links_[i] = spec(n).default_link;
  }
  ++ram_version_;
  refresh_roles();
  return ErrorCode::kNone;
}

void Drive::power_cycle() {
  for (int n = 1; n <= parameter_count(); ++n)
    if (stored(n)) ram_[static_cast<std::size_t>(n - 1)] = stored_value(n);
  ++ram_version_;
  ram_links_ = stored_links_;
  command_ = 0;
  reference_ = 0;
  run_latch_ = false;
  forward_ = true;
  faulted_ = false;
  speed_q_ = 0;
  refresh_roles();
}

// ---------------------------------------------------------------------------------------------
// Logic and plant

bool Drive::command_has(std::uint16_t word, CommandFunction f) const {
  int b = bit(f);
  return b >= 0 && (word >> b) & 1;
}

void Drive::set_logic_command(std::uint16_t word) {
  const std::uint16_t old = command_;
  command_ = word;
  auto rising = [&](CommandFunction f) { return command_has(word, f) && !command_has(old, f); };
  if (rising(CommandFunction::kClearFaults)) faulted_ = false;
  const bool fwd = command_has(word, CommandFunction::kForward);
  const bool rev = command_has(word, CommandFunction::kReverse);
  if (fwd != rev) forward_ = fwd;
  if (command_has(word, CommandFunction::kStop))
    run_latch_ = false;
  else if (rising(CommandFunction::kStart) && !faulted_)
    run_latch_ = true;
  refresh_roles();
}

void Drive::set_reference(std::uint16_t word) {
  reference_ = word;
  refresh_roles();
}

void Drive::fault(std::uint16_t code) {
  faulted_ = true;
  run_latch_ = false;
  last_fault_ = code;
  refresh_roles();
}

std::int64_t Drive::target_q() const {
  if (!run_latch_) return 0;
  // A reference above full scale asks for no more than full speed.
  const std::int64_t ref = std::min<std::int64_t>(reference_, desc_.speed.reference_full_scale);
  return (forward_ ? ref : -ref) * 65536;
}

void Drive::step() {
  const std::int64_t target = target_q();
  const std::int64_t delta = (target - speed_q_) * desc_.speed.update_period / desc_.speed.time_constant;
  // Truncation would leave the speed a fraction of a count short of the target for ever; once
  // the step rounds to nothing the remaining error is below one count, so the speed lands on it.
  speed_q_ = delta == 0 ? target : speed_q_ + delta;
}

void Drive::advance_to(VirtualTime t) {
  if (t < now_)
    throw TimeWentBackwards("drive asked to go from " + std::to_string(now_) + " ns back to " + std::to_string(t) +
                            " ns");
  const Nanoseconds h = desc_.speed.update_period;
  while (next_update_ <= t) {
    if (speed_q_ == target_q()) {
      // Settled: every remaining update up to t would leave the state as it is.
      next_update_ = (t / h + 1) * h;
      break;
    }
    step();
    next_update_ += h;
  }
  now_ = t;
  refresh_roles();
}

std::uint16_t Drive::feedback() const {
  const std::int64_t mag = speed_q_ < 0 ? -speed_q_ : speed_q_;
  return static_cast<std::uint16_t>(std::min<std::int64_t>((mag + 32768) >> 16, 0xFFFF));
}

std::uint16_t Drive::logic_status() const {
  const std::int64_t target = target_q();
  const bool accelerating = speed_q_ != target && ((target > 0 && speed_q_ >= 0 && speed_q_ < target) ||
                                                   (target < 0 && speed_q_ <= 0 && speed_q_ > target));
  const bool decelerating = speed_q_ != target && !accelerating;
  const std::int64_t error = (target - speed_q_) < 0 ? speed_q_ - target : target - speed_q_;
  const bool state[kStatusFunctionCount] = {
      /* kEnabled */ !faulted_,
      /* kRunning */ running(),
      /* kCommandForward */ forward_,
      /* kRotatingForward */ speed_q_ > 0 || (speed_q_ == 0 && forward_),
      /* kAccelerating */ accelerating,
      /* kDecelerating */ decelerating,
      /* kFaulted */ faulted_,
      /* kAtSpeed */ run_latch_ && error <= std::int64_t{desc_.speed.at_speed_band} * 65536,
  };
  static_assert(std::size(state) == kStatusFunctionCount);
  std::uint16_t word = 0;
  for (int f = 0; f < kStatusFunctionCount; ++f)
    if (state[f] && desc_.status_bits[f] >= 0) word |= static_cast<std::uint16_t>(1u << desc_.status_bits[f]);
  return word;
}

void Drive::set_role(Role r, std::int64_t v) {
  const int n = desc_.roles[static_cast<int>(r)];
  if (n == 0) return;
  const auto& p = spec(n);
  std::int64_t& held = ram_[static_cast<std::size_t>(n - 1)];
  const std::int64_t clamped = std::clamp(v, p.minimum, p.maximum);
  if (held != clamped) ++ram_version_;
  held = clamped;
}

void Drive::refresh_roles() {
  // Frequencies go through display values, so the output parameter may use other units or
  // precision than the maximum-frequency parameter (Hz vs 0.01 Hz).
  auto frequency = [&](std::uint16_t counts, Role r, FrequencyMemo& memo) {
    const int out = desc_.roles[static_cast<int>(r)];
    if (out == 0) return;
    if (memo.valid && memo.counts == counts && memo.version == ram_version_) return set_role(r, memo.value);
    const auto fs = desc_.speed.reference_full_scale;
    const std::int64_t c = std::min<std::int64_t>(counts, fs);
    const int maxp = desc_.roles[static_cast<int>(Role::kMaximumFrequency)];
    std::optional<std::int64_t> v;
    if (maxp != 0) {
      std::int64_t num = 0, den = 0;
      auto top = display_value(maxp);
      // c / fs x top, exactly; a product that overflows leaves the parameter at 0.
      if (top && !__builtin_mul_overflow(c, top->numerator, &num) &&
          !__builtin_mul_overflow(std::int64_t{fs}, top->denominator, &den))
        if (auto shown = make_rational(num, den))
          v = internal_from_display(scaling_factors(out), *shown, spec(out).has(descriptor::kExtendedPrecision));
    } else {
      v = c * spec(out).maximum / fs;
    }
    // Remembered for the values it was computed from, before set_role may change one.
    memo = {true, counts, ram_version_, v.value_or(0)};
    set_role(r, memo.value);
  };
  frequency(feedback(), Role::kOutputFrequency, frequency_memo_[0]);
  frequency(reference_, Role::kFrequencyCommand, frequency_memo_[1]);
  set_role(Role::kDriveStatus, logic_status());
  set_role(Role::kLastFault, last_fault_);
}

// ---------------------------------------------------------------------------------------------
// Datalinks

std::optional<std::int64_t> Drive::value_from_word(int number, std::uint16_t word) const {
  const auto& t = info(spec(number).type);
  if (t.size > 2) return std::nullopt;
  if (!t.is_signed) return word;
  return static_cast<std::int16_t>(word);
}

ErrorCode Drive::write_datalink(int index, std::uint16_t word) {
  if (index < 0 || index >= kDatalinkWords || desc_.data_in[index] == 0) return ErrorCode::kServiceNotSupported;
  const std::int64_t target = value(desc_.data_in[index]);
  if (target == 0) return ErrorCode::kNone;
  if (!parameter(target)) return ErrorCode::kInstanceNotSupported;
  auto v = value_from_word(static_cast<int>(target), word);
  if (!v) return ErrorCode::kAttributeNotSupported;
  return write_value(target, *v);
}

std::uint16_t Drive::read_datalink(int index) const {
  if (index < 0 || index >= kDatalinkWords || desc_.data_out[index] == 0) return 0;
  const std::int64_t source = value(desc_.data_out[index]);
  if (!parameter(source)) return 0;
  return static_cast<std::uint16_t>(value(static_cast<int>(source)));
}

}  // namespace softslc::scanport
