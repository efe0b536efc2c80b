#include "modules/sdn/sdn_scanner.h"

#include <algorithm>
#include <array>

#include "parser/loader.h"

namespace softslc {

namespace dn = devicenet;

namespace {

dn::MFile library_file(MFile f) { return f == MFile::M0 ? dn::MFile::M0 : dn::MFile::M1; }

bool in_request_block(int word) {
  return word >= dn::layout::kTransactionBlock && word < dn::layout::kTransactionBlock + dn::layout::kTransactionWords;
}

std::optional<std::int64_t> integer_arg(const DeviceFault& f, std::size_t i, std::int64_t lo, std::int64_t hi) {
  if (i >= f.args.size()) return std::nullopt;
  NumberValue v;
  if (!parse_number_text(f.args[i], v) || v.is_float || v.integer < lo || v.integer > hi) return std::nullopt;
  return v.integer;
}

std::vector<std::int64_t> bytes_of(const dn::Bytes& b) { return {b.begin(), b.end()}; }

}  // namespace

SdnScanner::SdnScanner(const SlotConfig& slot, int m0_words, int m1_words, std::shared_ptr<const SdnBench> bench)
    : Module(slot.slot, slot.catalog, slot.scan_in, slot.scan_out),
      bench_(bench ? std::move(bench) : std::make_shared<const SdnBench>()),
      m0_words_(std::min(m0_words, dn::layout::kMFileWords)),
      m1_words_(std::min(m1_words, dn::layout::kMFileWords)) {
  network_ = std::make_unique<dn::Network>(bench_->network_baud);
  for (const auto& d : bench_->devices) network_->attach(d.address, d.model);
}

// The scanner withdraws its events from the network's timeline; the host's queue dies with the
// runtime that owns this module.
SdnScanner::~SdnScanner() = default;

// The module powers up when the runtime takes it: at time 0, or later after a power cycle (the
// processor's clock carries on), so the network's clock starts there and the scanner's start-up
// (the duplicate node check) runs from that moment.
void SdnScanner::attach(ModuleHost& host) {
  Module::attach(host);
  network_->advance_to(host.now());
  scanner_ = std::make_unique<dn::Scanner>(*network_, bench_->config);
  dem_ = std::make_unique<dn::dem::DemPort>(*scanner_);
  rearm();
}

// ---- Time ------------------------------------------------------------------------------------------------

void SdnScanner::sync(VirtualTime t) {
  if (t > network_->now()) network_->advance_to(t);
  rearm();
}

void SdnScanner::rearm() {
  const std::optional<VirtualTime> next = network_->next_event_time();
  if (next == wake_at_) return;
  if (wake_at_) host()->cancel_event(wake_id_);
  wake_at_.reset();
  if (!next) return;
  wake_at_ = std::max(*next, host()->now());
  wake_id_ = host()->schedule_at(*wake_at_, [this](VirtualTime t) { wake(t); });
}

void SdnScanner::wake(VirtualTime t) {
  wake_at_.reset();
  sync(t);
}

// See the header. The armed host event must stand for the network's next event (rearm keeps it so).
bool SdnScanner::passive() const {
  if (request_block_written_ || dem_->owner() || scanner_->transactions_in_use() != 0) return false;
  return network_->next_event_time().has_value() == wake_at_.has_value();
}

// ---- The backplane -------------------------------------------------------------------------------------------

void SdnScanner::input_scan(std::span<std::uint16_t> image) {
  sync(host()->now());
  const auto in = scanner_->input_image();
  std::copy_n(in.begin(), std::min(image.size(), in.size()), image.begin());
}

void SdnScanner::output_scan(std::span<const std::uint16_t> image) {
  sync(host()->now());
  scanner_->write_output_image(image.first(std::min<std::size_t>(image.size(), dn::layout::kImageWords)));
  rearm();
}

int SdnScanner::m_file_words(MFile f) const { return f == MFile::M0 ? m0_words_ : m1_words_; }

MAccess SdnScanner::read_m(MFile f, int word, std::uint16_t& value) {
  if (word < 0 || word >= m_file_words(f)) return MAccess::NoSuchWord;
  sync(host()->now());
  return scanner_->read_m(library_file(f), word, value) ? MAccess::Ok : MAccess::NoSuchWord;
}

MAccess SdnScanner::write_m(MFile f, int word, std::uint16_t value) {
  if (word < 0 || word >= m_file_words(f)) return MAccess::NoSuchWord;
  sync(host()->now());
  if (!m_write_changes_nothing(f, word, value)) ++program_changes_;
  if (!scanner_->write_m(library_file(f), word, value)) return MAccess::NoSuchWord;
  // The request block is acted on once per processor scan that wrote it, after the scan: a block
  // built word by word over several rungs, or copied by one COP, is one request.
  if (f == MFile::M0 && in_request_block(word) && !request_block_written_) {
    request_block_written_ = true;
    host()->schedule_at(host()->now(), [this](VirtualTime t) {
      sync(t);
      request_block_written_ = false;
      scanner_->process_request_block();
      rearm();
    });
  }
  rearm();
  return MAccess::Ok;
}

// See the header: M0 outside the request block, or M1's data area, already holding the value, or an
// M1 word outside the data area (the library ignores writes there).
bool SdnScanner::m_write_changes_nothing(MFile f, int word, std::uint16_t value) const {
  if (word < 0 || word >= m_file_words(f)) return false;
  if (f == MFile::M0 && in_request_block(word)) return false;
  if (f == MFile::M1 && word >= dn::layout::kDataWords) return true;
  std::uint16_t held = 0;
  return scanner_->read_m(library_file(f), word, held) && held == value;
}

// Leaving Run or Test drops the DEM in flight, as the processor resets its message instructions;
// the scanner itself sees the mode only through the command register (zeros outside Run: Idle).
void SdnScanner::on_mode_change(Mode from, Mode to) {
  const bool was_running = from == Mode::Run || from == Mode::Test;
  const bool running = to == Mode::Run || to == Mode::Test;
  if (was_running && !running) {
    sync(host()->now());
    dem_->abandon();
    rearm();
  }
}

// DEM slot, control block, length (docs/program-format.md): the control block is a Table operand of
// 70 words, read, stepped through the module's DEM port and written back.
void SdnScanner::execute(ModuleInstructionContext& ctx) {
  if (ctx.opcode() != Opcode::DEM) return Module::execute(ctx);
  const auto ops = ctx.operands();
  std::size_t cb_op = ops.size();
  for (std::size_t i = 0; i < ops.size(); ++i)
    if (ops[i].kind == ModuleOperand::Kind::Table) {
      cb_op = i;
      break;
    }
  if (cb_op == ops.size()) {
    ctx.fault(0x001F, "DEM needs an integer control block of 70 words");
    return;
  }
  std::array<std::uint16_t, dn::dem::kWords> cb{};
  if (!ctx.read_block(cb_op, 0, cb)) return;
  const auto before = cb;
  const std::uint32_t owner = ops[cb_op].word;
  // A DEM with no message in flight that starts none (a false rung, EN still set, or WS while
  // another block holds the slot) acts from its block, the rung and the slot alone: it neither
  // asks the time (so a probe may repeat across the network's events) nor advances the network.
  const bool timed = dem_->reads_network(owner, cb, ctx.rung_in());
  VirtualTime now = 0;
  if (timed) {
    now = ctx.now();
    const std::optional<VirtualTime> next = network_->next_event_time();
    if (next && *next <= now) ++program_changes_;  // the network moves mid-scan
    sync(now);
  }
  const auto slot_owner = dem_->owner();
  const auto abandoned = dem_->abandoned();
  dem_->on_rung(owner, cb, ctx.rung_in(), now);
  if (cb != before || dem_->owner() != slot_owner || dem_->abandoned() != abandoned) ++program_changes_;
  // Most scans change nothing in the block: one compare of the whole block then, not 70.
  if (cb != before)
    for (int k = 0; k < dn::dem::kWords; ++k) {
      const auto i = static_cast<std::size_t>(k);
      if (cb[i] != before[i] && !ctx.write(cb_op, static_cast<std::uint32_t>(k), cb[i])) return;
    }
  if (timed) rearm();
}

// ---- Bench devices --------------------------------------------------------------------------------------------

std::vector<std::string> SdnScanner::device_names() const {
  std::vector<std::string> out;
  if (!bench_->name.empty()) out.push_back(bench_->name);
  for (const auto& n : bench_->nodes) out.push_back(n.name);
  return out;
}

std::optional<int> SdnScanner::address_of(std::string_view device) const {
  for (const auto& n : bench_->nodes)
    if (n.name == device) return n.address;
  return std::nullopt;
}

DeviceStatus SdnScanner::inject(const DeviceFault& given) {
  const bool network = !bench_->name.empty() && given.device == bench_->name;
  const auto address = address_of(given.device);
  if (!network && !address) return {};
  // The test runner passes the switch words as arguments ("bus" {"off"}); the change words here
  // read as one phrase ("bus off", "duplicate off").
  DeviceFault fault = given;
  if (!fault.args.empty() && (fault.args[0] == "on" || fault.args[0] == "off")) {
    fault.fault += " " + fault.args[0];
    fault.args.erase(fault.args.begin());
  }
  sync(host()->now());
  DeviceStatus st = network ? inject_network(fault) : inject_node(*address, fault);
  rearm();
  return st;
}

DeviceStatus SdnScanner::inject_network(const DeviceFault& f) {
  const std::string& w = f.fault;
  if (w == "bus off" || w == "bus on") {
    network_->set_bus_fault(w == "bus off");
  } else if (w == "power off" || w == "power on") {
    network_->set_network_power(w == "power on");
  } else if (w == "duplicate" || w == "duplicate off") {
    const auto n = integer_arg(f, 0, 0, 63);
    if (!n) return DeviceStatus::refused("'" + w + "' needs the node address that is claimed twice (0-63)");
    network_->set_duplicate_claim(static_cast<int>(*n), w == "duplicate");
  } else if (w == "normal") {
    network_->set_bus_fault(false);
    network_->set_network_power(true);
    for (int n = 0; n < dn::kNodeCount; ++n) network_->set_duplicate_claim(n, false);
  } else {
    return DeviceStatus::refused("a DeviceNet network takes 'bus off', 'bus on', 'power off', 'power on', "
                                 "'duplicate N', 'duplicate off N' or 'normal', not '" + w + "'");
  }
  return DeviceStatus::done();
}

DeviceStatus SdnScanner::inject_node(int address, const DeviceFault& f) {
  dn::SimDevice* d = network_->device(address);
  if (!d) return DeviceStatus::refused(f.device + " is a scanlist entry with no device on the cable");
  const std::string& w = f.fault;
  if (w == "offline" || w == "online") {
    d->set_online(w == "online");
  } else if (w == "data size") {
    const auto n = integer_arg(f, 0, 0, 255);
    if (!n) return DeviceStatus::refused("'data size' needs the number of bytes the device produces (0-255)");
    d->set_produced_size_override(static_cast<int>(*n));
  } else if (w == "idle" || w == "producing") {
    d->set_producing_idle(w == "idle");
  } else if (w == "key mismatch" || w == "key match") {
    // Another product of the same vendor: the electronic key's product code no longer matches.
    std::optional<dn::Identity> id;
    if (w == "key mismatch") {
      id = d->model().identity;
      id->product_code = static_cast<std::uint16_t>(id->product_code + 1);
    }
    d->set_identity_override(id);
  } else if (w == "owned elsewhere" || w == "released") {
    d->set_owned_elsewhere(w == "owned elsewhere");
  } else if (w == "message timeout" || w == "responding") {
    d->set_explicit_silent(w == "message timeout");
  } else if (w.rfind("input", 0) == 0) {
    // "input start 1" (the test runner's spelling: lower-case point names join the change words) or
    // "input" POINT VALUE.
    std::string point = w.size() > 6 ? w.substr(6) : std::string();
    std::size_t vi = 0;
    if (point.empty() && !f.args.empty()) point = f.args[vi++];
    const auto v = integer_arg(f, vi, 0, 1);
    if (point.empty() || !v) return DeviceStatus::refused("'input' needs a point name and 0 or 1");
    if (!network_->set_input(address, point, *v != 0)) {
      std::string names;
      for (const auto& p : d->model().inputs) names += (names.empty() ? "" : ", ") + p.name;
      return DeviceStatus::refused(f.device + " has no input '" + point + "' (" + names + ")");
    }
  } else if (w == "normal") {
    d->set_online(true);
    d->set_produced_size_override(std::nullopt);
    d->set_producing_idle(false);
    d->set_identity_override(std::nullopt);
    d->set_owned_elsewhere(false);
    d->set_explicit_silent(false);
  } else {
    return DeviceStatus::refused("a DeviceNet node takes 'offline', 'online', 'data size N', 'idle', 'producing', "
                                 "'key mismatch', 'key match', 'owned elsewhere', 'released', 'message timeout', "
                                 "'responding', 'input POINT 0|1' or 'normal', not '" + w + "'");
  }
  return DeviceStatus::done();
}

std::optional<std::vector<std::int64_t>> SdnScanner::observe(std::string_view device, std::string_view what) const {
  if (!bench_->name.empty() && device == bench_->name) {
    if (what == "status code") return std::vector<std::int64_t>{scanner_->status_code()};
    if (what == "scan counter") return std::vector<std::int64_t>{scanner_->scan_counter()};
    if (what == "active") {
      std::vector<std::int64_t> out;
      for (int n = 0; n < dn::kNodeCount; ++n)
        if (scanner_->active(n)) out.push_back(n);
      return out;
    }
    return std::nullopt;
  }
  const auto address = address_of(device);
  if (!address) return std::nullopt;
  const dn::SimDevice* d = network_->device(*address);
  if (!d) return std::nullopt;
  if (what == "inputs") return bytes_of(d->inputs());
  if (what == "outputs") return bytes_of(d->outputs());
  if (what == "output state") return std::vector<std::int64_t>{static_cast<std::int64_t>(d->output_state())};
  if (auto v = d->output(what)) return std::vector<std::int64_t>{*v ? 1 : 0};
  if (auto v = d->input(what)) return std::vector<std::int64_t>{*v ? 1 : 0};
  return std::nullopt;
}

}  // namespace softslc
