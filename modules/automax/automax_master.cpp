// The AutoMax Remote I/O master: dual-port access rules (section 4.3), the drops' behaviour
// (sections 4.4, 4.6) and the update cycle in virtual time (sections 4.4, 4.5).
#include <algorithm>

#include "modules/automax/automax_network.h"
#include "parser/loader.h"

namespace softslc {

namespace {

std::string point_text(int area, int slot, int reg) {
  return "drop " + std::to_string(area) + " slot " + std::to_string(slot) + " register " + std::to_string(reg);
}

std::uint16_t& counter(std::array<std::uint16_t, kAutomaxImageWords>& image, int reg) {
  return image[static_cast<std::size_t>(automax_master_word(reg))];
}

}  // namespace

AutomaxMaster::AutomaxMaster(const SlotConfig& slot, std::shared_ptr<const AutomaxBench> bench,
                             std::shared_ptr<const SymbolNames> symbols)
    : Module(slot.slot, slot.catalog, slot.scan_in, slot.scan_out), bench_(std::move(bench)), symbols_(std::move(symbols)) {
  counter(image_, kDropNumberRegister) = 0;  // the master is drop 0
  counter(image_, kKeyswitchRegister) = static_cast<std::uint16_t>(bench_ ? bench_->keyswitch : 3);
  if (!bench_) return;
  for (const auto& spec : bench_->drops) {
    Drop d;
    d.spec = &spec;
    d.online = spec.online;
    d.noisy = spec.noisy;
    d.rails = spec.rails;
    d.known_rails = spec.rails;
    d.head_rails = spec.rails;
    drops_[static_cast<std::size_t>(spec.area)] = std::move(d);
  }
}

// ---- Power-up and the update cycle -----------------------------------------------------------------

void AutomaxMaster::attach(ModuleHost& host) {
  Module::attach(host);
  // The master powers up with the processor: its first event polls the drops, so what the
  // field looks like at that moment (a drop a test took off line) is what it finds.
  host.schedule_at(host.now(), [this](VirtualTime) { power_up(); });
}

// "At power up, the master will poll all of the slave drops to determine which drops are
// connected to the network" (section 4.4); then the update cycles start.
void AutomaxMaster::power_up() {
  for (int area = 1; area < kAutomaxAreas; ++area) poll_inactive(area);
  set_status();
  update_cycle();
}

// A poll of a drop not in the active list: one message; a drop that answers joins.
void AutomaxMaster::poll_inactive(int area) {
  count(kMessagesTransmitted);
  auto& d = drops_[static_cast<std::size_t>(area)];
  if (d && answers(*d)) {
    count(kMessagesReceived);
    join(*d);
  } else {
    count(kReceiveTimeouts);
  }
}

bool AutomaxMaster::answers(Drop& d) {
  if (cable_removed_ || !d.online || host()->now() < d.ready_at) return false;
  return true;
}

void AutomaxMaster::join(Drop& d) {
  d.active = true;
  // The head sends its rail configuration when it is first polled (sections 4.6.2, 4.6.3).
  d.known_rails = d.rails;
  read_rails(d);
}

// A 57C330 finds which ports have a rail "approximately every 20 milliseconds" (4.6.3): a rail
// found is undefined, a rail gone loses its definition.
void AutomaxMaster::read_rails(Drop& d) {
  for (int r = 0; r < static_cast<int>(d.rail_state.size()); ++r) {
    const bool connected = std::find(d.rails.begin(), d.rails.end(), r) != d.rails.end();
    Rail& st = d.rail_state[static_cast<std::size_t>(r)];
    if (!connected) st = Rail::None;
    else if (st == Rail::None) st = Rail::Undefined;
  }
  d.head_rails = d.rails;
  d.next_rail_read = host()->now() + kRailReadPeriod;
}

void AutomaxMaster::go_offline(Drop& d) {
  d.active = false;
  // Line inactive: a 57C330's rail definitions and a Shark rack's configuration are lost
  // (sections 4.6.3, 4.6.1).
  d.rail_state.fill(Rail::None);
  d.shark_configured = false;
}

Nanoseconds AutomaxMaster::drop_time(const Drop& d) const {
  throughput::AutomaxDrop t = throughput_drop(*d.spec);
  if (d.spec->kind == AutomaxDropKind::Head57C330) {
    // X output and Y input registers transferred: defined rails count on their side, rails
    // not yet defined on both (data goes both ways until it defines them).
    for (int r : d.head_rails) {
      const Rail s = d.rail_state[static_cast<std::size_t>(r)];
      t.outputs += s != Rail::Input;
      t.inputs += s != Rail::Output;
    }
  }
  if (d.spec->kind == AutomaxDropKind::Head57C328) t.rails = static_cast<int>(d.rails.size());
  return microseconds(throughput::automax_drop_time(t));
}

bool AutomaxMaster::poll(Drop& d, Nanoseconds& elapsed) {
  for (int attempt = 0; attempt <= kRetries; ++attempt) {
    count(kMessagesTransmitted);
    elapsed += drop_time(d);
    if (attempt > 0) ++d.retries;
    if (!answers(d)) {
      count(kReceiveTimeouts);
      continue;
    }
    ++d.messages;
    if (d.noisy > 0 && d.messages % static_cast<std::uint64_t>(d.noisy) == 0) {
      count(kCrcErrors);
      continue;
    }
    count(kMessagesReceived);
    exchange(d);
    return true;
  }
  go_offline(d);
  return false;
}

void AutomaxMaster::update_cycle() {
  Nanoseconds elapsed = 0;
  for (int area = 1; area < kAutomaxAreas; ++area) {
    auto& d = drops_[static_cast<std::size_t>(area)];
    if (d && d->active) poll(*d, elapsed);
  }
  // "After polling all active slave drops, the master then polls one inactive drop" (4.4).
  for (int tries = 0; tries < kAutomaxAreas - 1; ++tries) {
    const int area = next_inactive_;
    next_inactive_ = next_inactive_ % (kAutomaxAreas - 1) + 1;
    auto& d = drops_[static_cast<std::size_t>(area)];
    if (d && d->active) continue;
    poll_inactive(area);
    break;
  }
  elapsed += microseconds(throughput::kAutomaxInactivePoll);
  set_status();
  update_period_ = elapsed;
  ++cycles_;
  host()->schedule_at(host()->now() + elapsed, [this](VirtualTime) { update_cycle(); });
}

void AutomaxMaster::count(int reg) { ++counter(image_, reg); }

void AutomaxMaster::set_status() {
  std::uint16_t bits = 0;
  for (int area = 1; area < kAutomaxAreas; ++area)
    if (drops_[static_cast<std::size_t>(area)] && drops_[static_cast<std::size_t>(area)]->active)
      bits = static_cast<std::uint16_t>(bits | (1u << area));
  counter(image_, kStatusRegister) = bits;
}

bool AutomaxMaster::has_rail(const Drop& d, int rail) const {
  // The master controls access with the rail configuration the drop sent when it connected.
  return std::find(d.known_rails.begin(), d.known_rails.end(), rail) != d.known_rails.end();
}

// One successful message: the drop's inputs into the image, the image's outputs to the drop.
void AutomaxMaster::exchange(Drop& d) {
  const std::size_t base = static_cast<std::size_t>(d.spec->area) * kAutomaxAreaWords;
  auto img = [&](int offset) -> std::uint16_t& { return image_[base + static_cast<std::size_t>(offset)]; };
  auto in = [&](int offset) { img(offset) = d.field_in[static_cast<std::size_t>(offset)]; };
  auto out = [&](int offset) { d.field_out[static_cast<std::size_t>(offset)] = img(offset); };
  switch (d.spec->kind) {
    case AutomaxDropKind::Multibus:
      for (const auto& m : d.spec->modules)
        for (int r = 0; r < m.inputs + m.outputs; ++r) {
          const int o = m.slot * kAutomaxSlotRegisters + r;
          if (r < m.inputs) in(o);
          else out(o);
        }
      break;
    case AutomaxDropKind::Shark: {
      if (!d.spec->all_digital_shark()) {
        // The configuration word (slot 0 register 0) is taken once, when bit 15 is set; later
        // writes change nothing until a Stop-All or a reconnection (section 4.6.1).
        if (!d.shark_configured && (img(0) & 0x8000u)) {
          d.shark_configured = true;
          d.shark_config = img(0);
        }
        if (!d.shark_configured) break;  // no I/O until configured
      }
      for (const auto& m : d.spec->modules) {
        const bool digital_configured = d.spec->all_digital_shark() || ((d.shark_config >> m.slot) & 1u);
        const bool matches = digital_configured == m.digital;
        for (int r = 0; r < m.inputs; ++r) {
          const int o = m.slot * kAutomaxSlotRegisters + r;
          img(o) = matches ? d.field_in[static_cast<std::size_t>(o)] : 0;
        }
        if (matches)
          for (int r = 8; r < 8 + m.outputs; ++r) out(m.slot * kAutomaxSlotRegisters + r);
      }
      break;
    }
    case AutomaxDropKind::Head57C328:
      for (int rail : d.rails) {
        in(rail);
        out(rail + 4);
      }
      break;
    case AutomaxDropKind::Head57C330:
      if (host()->now() >= d.next_rail_read) read_rails(d);
      for (int rail : d.head_rails) {
        Rail& s = d.rail_state[static_cast<std::size_t>(rail)];
        if (s == Rail::Undefined) {
          // Non-zero data defines the rail: from the rail, an input; from the master, an output.
          if (d.field_in[static_cast<std::size_t>(rail)] != 0) s = Rail::Input;
          else if (img(rail) != 0) s = Rail::Output;
        }
        if (s == Rail::Input) in(rail);
        if (s == Rail::Output) out(rail);
      }
      break;
    case AutomaxDropKind::DriveHead:
      for (int port : d.rails) {
        const int o = port * kAutomaxSlotRegisters;
        out(o);
        out(o + 1);
        for (int r = 2; r < 4; ++r) {
          // A drive that stops answering: the head clears its input registers and keeps trying
          // (section 4.6.4); the drop stays on-line.
          if (d.port_online[static_cast<std::size_t>(port)]) in(o + r);
          else img(o + r) = 0;
        }
      }
      break;
  }
}

// ---- Dual-port access (section 4.3) -----------------------------------------------------------------

AutomaxMaster::Access AutomaxMaster::access(int word, std::string* why) const {
  // The reason is text for refusal() only: read_m and write_m ask on every M0 access of a scan
  // and pass no `why`, so nothing is formatted (or allocated) for them.
  auto say = [&](Access a, auto&& text) {
    if (why) *why = text();
    return a;
  };
  if (word < 0 || word >= kAutomaxImageWords)
    return say(Access::BusError, [&] { return std::string("beyond the dual-port image"); });
  const int area = word / kAutomaxAreaWords;
  const int slot = (word % kAutomaxAreaWords) / kAutomaxSlotRegisters;
  const int reg = word % kAutomaxSlotRegisters;
  if (area == 0)
    return say(Access::ReadOnly,
               [&] { return "drop 0 register " + std::to_string(word) + " (status, read only: section 4.2)"; });
  const auto& dp = drops_[static_cast<std::size_t>(area)];
  auto point = [&] { return point_text(area, slot, reg); };
  // The drops and their modules are the network's configuration (section 4.6): a drop that has
  // not answered yet still has its registers (decision, docs/automax.md).
  if (!dp)
    return say(Access::BusError,
               [&] { return point() + ": there is no drop " + std::to_string(area) + " on the network"; });
  const Drop& d = *dp;
  const AutomaxDropSpec& s = *d.spec;
  switch (s.kind) {
    case AutomaxDropKind::Multibus: {
      for (const auto& m : s.modules)
        if (m.slot == slot) {
          if (reg < m.inputs)
            return say(Access::ReadOnly, [&] { return point() + " (" + m.name + " input, read only)"; });
          if (reg < m.inputs + m.outputs) return say(Access::ReadWrite, [&] { return point(); });
          return say(Access::BusError, [&] {
            return point() + ": module " + m.name + " has " + std::to_string(m.inputs + m.outputs) + " registers";
          });
        }
      return say(Access::BusError, [&] { return point() + ": no module in slot " + std::to_string(slot); });
    }
    case AutomaxDropKind::Shark: {
      if (slot == 0 && reg == 0 && !s.all_digital_shark())
        return say(Access::ReadWrite, [&] { return point() + " (configuration word)"; });
      const AutomaxModuleSpec* m = nullptr;
      for (const auto& x : s.modules)
        if (x.slot == slot) m = &x;
      if (!m)
        return say(Access::BusError, [&] { return point() + ": no module in Shark slot " + std::to_string(slot); });
      if (reg < 8 && reg < m->inputs)
        return say(Access::ReadOnly, [&] { return point() + " (" + m->name + " input, read only)"; });
      if (reg >= 8 && reg < 16 && reg - 8 < m->outputs) return say(Access::ReadWrite, [&] { return point(); });
      // "in the case of a digital module in a mixed Shark rack, a bus error will NOT be reported"
      if (m->digital && !s.all_digital_shark())
        return say(Access::Ignored,
                   [&] { return point() + ": invalid register of digital module " + m->name + " in a mixed rack"; });
      return say(Access::BusError, [&] {
        return point() + (reg >= 16 ? ": Shark registers 16-32 are not accessible"
                                    : ": module " + m->name + " has no such register");
      });
    }
    case AutomaxDropKind::Head57C328: {
      // Registers 0-3 inputs, 4-7 outputs, one pair per rail; 8-31 not accessible. A head's
      // registers are the drop's, whatever the SLOT field (decision, docs/automax.md).
      if (reg >= 8)
        return say(Access::BusError, [&] { return point() + ": registers 8-31 of a 57C328 head are not accessible"; });
      if (!has_rail(d, reg % 4))
        return say(Access::BusError, [&] { return point() + ": no rail " + std::to_string(reg % 4) + " connected"; });
      return say(reg < 4 ? Access::ReadOnly : Access::ReadWrite,
                 [&] { return point() + (reg < 4 ? " (rail input, read only)" : ""); });
    }
    case AutomaxDropKind::Head57C330: {
      if (reg >= 16 || !has_rail(d, reg))
        return say(Access::BusError, [&] { return point() + ": no rail " + std::to_string(reg) + " connected"; });
      const Rail st = d.rail_state[static_cast<std::size_t>(reg)];
      return say(st == Rail::Input ? Access::ReadOnly : Access::ReadWrite,
                 [&] { return point() + (st == Rail::Input ? " (rail defined as input, read only)" : ""); });
    }
    case AutomaxDropKind::DriveHead: {
      if (std::find(d.rails.begin(), d.rails.end(), slot) == d.rails.end())
        return say(Access::BusError, [&] { return point() + ": no drive port " + std::to_string(slot); });
      if (reg >= 4) return say(Access::BusError, [&] { return point() + ": a drive port has registers 0-3"; });
      return say(reg < 2 ? Access::ReadWrite : Access::ReadOnly,
                 [&] { return point() + (reg >= 2 ? " (from the drive, read only)" : ""); });
    }
  }
  return say(Access::BusError, [&] { return point(); });
}

std::string AutomaxMaster::refusal(int word, bool write) const {
  std::string why;
  const Access a = access(word, &why);
  if (a == Access::BusError) return "bus error: " + why;
  if (a == Access::ReadOnly && write) return "write refused: " + why;
  return {};
}

// A Remote I/O Head's registers are the drop's whatever the SLOT field (decision,
// docs/automax.md): they are kept at slot 0 of its area.
int AutomaxMaster::storage_word(int word) const {
  const auto& d = drops_[static_cast<std::size_t>(word / kAutomaxAreaWords)];
  const bool head = d && (d->spec->kind == AutomaxDropKind::Head57C328 || d->spec->kind == AutomaxDropKind::Head57C330);
  return head ? word - word % kAutomaxAreaWords + word % kAutomaxSlotRegisters : word;
}

std::string AutomaxMaster::m_refusal(MFile f, int word, bool write) const {
  if (f != MFile::M0) return "the AutoMax master has no M1 file (its dual-port image is M0)";
  std::string why = refusal(word, write);
  if (why.empty() || !symbols_) return why;
  auto it = symbols_->find(word);
  return it == symbols_->end() ? why : it->second + ": " + why;
}

MAccess AutomaxMaster::read_m(MFile f, int word, std::uint16_t& value) {
  if (f != MFile::M0) return MAccess::NoSuchWord;
  const Access a = access(word, nullptr);
  if (a == Access::BusError) return MAccess::NoSuchWord;
  value = a == Access::Ignored ? 0 : image_[static_cast<std::size_t>(storage_word(word))];
  return MAccess::Ok;
}

MAccess AutomaxMaster::write_m(MFile f, int word, std::uint16_t value) {
  if (f != MFile::M0) return MAccess::NoSuchWord;
  const Access a = access(word, nullptr);
  if (a == Access::BusError) return MAccess::NoSuchWord;
  if (a == Access::ReadOnly) return MAccess::Forbidden;
  if (a == Access::ReadWrite) {
    std::uint16_t& stored = image_[static_cast<std::size_t>(storage_word(word))];
    if (stored != value) ++program_changes_;
    stored = value;
  }
  return MAccess::Ok;
}

// See the header: accepted, and either ignored or storing the value the image holds.
bool AutomaxMaster::m_write_changes_nothing(MFile f, int word, std::uint16_t value) const {
  if (f != MFile::M0) return false;
  const Access a = access(word, nullptr);
  if (a == Access::BusError || a == Access::ReadOnly) return false;
  return a == Access::Ignored || image_[static_cast<std::size_t>(storage_word(word))] == value;
}

// A Stop-All (the processor leaving Run) lets a mixed Shark rack take a new configuration word
// (section 4.6.1).
void AutomaxMaster::on_mode_change(Mode from, Mode to) {
  if (from == Mode::Run && to != Mode::Run)
    for (auto& d : drops_)
      if (d) d->shark_configured = false;
}

// ---- Devices -------------------------------------------------------------------------------------------

std::vector<std::string> AutomaxMaster::device_names() const {
  std::vector<std::string> names;
  if (bench_ && !bench_->name.empty()) names.push_back(bench_->name);
  for (const auto& d : drops_)
    if (d) names.push_back(d->spec->name);
  return names;
}

AutomaxMaster::Drop* AutomaxMaster::find_drop(std::string_view name) {
  for (auto& d : drops_)
    if (d && d->spec->name == name) return &*d;
  return nullptr;
}
const AutomaxMaster::Drop* AutomaxMaster::find_drop(std::string_view name) const {
  return const_cast<AutomaxMaster*>(this)->find_drop(name);
}

namespace {
std::optional<std::int64_t> arg_int(const DeviceFault& f, std::size_t i) {
  if (i >= f.args.size()) return std::nullopt;
  NumberValue v;
  if (!parse_number_text(f.args[i], v) || v.is_float) return std::nullopt;
  return v.integer;
}
}  // namespace

DeviceStatus AutomaxMaster::inject(const DeviceFault& f) {
  if (bench_ && f.device == bench_->name) {
    if (f.fault == "cable removed") cable_removed_ = true;
    else if (f.fault == "cable restored" || f.fault == "normal") cable_removed_ = false;
    else return DeviceStatus::refused("the master takes 'cable removed', 'cable restored', 'normal'");
    return DeviceStatus::done();
  }
  Drop* d = find_drop(f.device);
  if (!d) return {};
  const AutomaxDropSpec& s = *d->spec;
  const VirtualTime now = host() ? host()->now() : 0;
  auto reset = [&] {  // the drop disconnects and re-runs its power-up diagnostics
    d->ready_at = now + s.diagnostics;
    d->messages = 0;
    go_offline(*d);
  };
  if (f.fault == "offline") {
    d->online = false;
  } else if (f.fault == "online") {
    d->online = true;
  } else if (f.fault == "noisy") {
    auto n = arg_int(f, 0);
    if (f.args.size() == 1 && f.args[0] == "off") d->noisy = 0;
    else if (n && *n >= 0) d->noisy = static_cast<int>(*n);
    else return DeviceStatus::refused("noisy N (every N-th message in error) or noisy off");
  } else if (f.fault == "power cycle") {
    reset();
  } else if (f.fault == "input") {
    // input SLOT REGISTER VALUE: what the drop's input register reads in the field.
    auto slot = arg_int(f, 0), reg = arg_int(f, 1), value = arg_int(f, 2);
    if (!slot || !reg || !value || *slot < 0 || *slot >= kAutomaxSlots || *reg < 0 || *reg >= kAutomaxSlotRegisters)
      return DeviceStatus::refused("input SLOT REGISTER VALUE (slot 0-15, register 0-31)");
    const bool head = s.kind == AutomaxDropKind::Head57C328 || s.kind == AutomaxDropKind::Head57C330;
    d->field_in[static_cast<std::size_t>((head ? 0 : *slot) * kAutomaxSlotRegisters + *reg)] =
        static_cast<std::uint16_t>(*value);
  } else if (f.fault == "rail removed" || f.fault == "rail added") {
    auto rail = arg_int(f, 0);
    const bool head = s.kind == AutomaxDropKind::Head57C328 || s.kind == AutomaxDropKind::Head57C330;
    if (!head || !rail || *rail < 0 || *rail > (s.kind == AutomaxDropKind::Head57C330 ? 15 : 3))
      return DeviceStatus::refused("'rail added N' / 'rail removed N' are for Remote I/O Heads");
    auto it = std::find(d->rails.begin(), d->rails.end(), static_cast<int>(*rail));
    if (f.fault == "rail removed" && it != d->rails.end()) d->rails.erase(it);
    if (f.fault == "rail added" && it == d->rails.end()) {
      d->rails.push_back(static_cast<int>(*rail));
      std::sort(d->rails.begin(), d->rails.end());
    }
    // A 57C328 "will disconnect from the network, re-run the power-up diagnostics"; a 57C330
    // notices at its next rail read (about every 20 ms) and the master learns the new set when
    // the drop connects again.
    if (s.kind == AutomaxDropKind::Head57C328) reset();
  } else if (f.fault == "drive offline" || f.fault == "drive online") {
    auto port = arg_int(f, 0);
    if (s.kind != AutomaxDropKind::DriveHead || !port || *port < 0 || *port > 3)
      return DeviceStatus::refused("'drive offline PORT' / 'drive online PORT' are for a drive head (ports 0-3)");
    d->port_online[static_cast<std::size_t>(*port)] = f.fault == "drive online";
  } else if (f.fault == "normal") {
    d->online = s.online;
    d->noisy = s.noisy;
    d->port_online.fill(true);
  } else {
    return DeviceStatus::refused("a drop takes 'offline', 'online', 'noisy N', 'noisy off', 'power cycle', "
                                 "'input SLOT REGISTER VALUE', 'rail added N', 'rail removed N', "
                                 "'drive offline PORT', 'drive online PORT', 'normal'");
  }
  return DeviceStatus::done();
}

std::optional<std::vector<std::int64_t>> AutomaxMaster::observe(std::string_view device, std::string_view what) const {
  using V = std::vector<std::int64_t>;
  if (bench_ && device == bench_->name) {
    if (what == "update period") return V{update_period_};
    if (what == "cycles") return V{cycles_};
    if (what == "status") return V{image_[kStatusRegister]};
    if (what == "counters") {
      V v;
      for (int r = kMessagesReceived; r <= kMessagesTransmitted; ++r) v.push_back(image_[static_cast<std::size_t>(r)]);
      return v;
    }
    return std::nullopt;
  }
  const Drop* d = find_drop(device);
  if (!d) return std::nullopt;
  if (what == "active") return V{d->active ? 1 : 0};
  if (what == "retries") return V{static_cast<std::int64_t>(d->retries)};
  if (what == "configured") return V{d->shark_configured ? 1 : 0};
  if (what == "rails") {  // 57C330: 0 none, 1 undefined, 2 input, 3 output per rail 0-15
    V v;
    for (auto s : d->rail_state) v.push_back(static_cast<std::int64_t>(s));
    return v;
  }
  // The drop's 512 registers (index 32 * slot + register) as it last received them, and as its
  // inputs read in the field.
  if (what == "outputs" || what == "inputs") {
    const auto& regs = what == "outputs" ? d->field_out : d->field_in;
    return V(regs.begin(), regs.end());
  }
  return std::nullopt;
}

}  // namespace softslc
