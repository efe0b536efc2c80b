#include "modules/devicenet/scanner.h"

#include <algorithm>
#include <bit>

namespace softslc::devicenet {

// ---- code tables --------------------------------------------------------------------------------

namespace {

enum class Scope : std::uint8_t { Module, Node };
struct CodeRow {
  int value;
  Scope scope;
  std::string_view text;
};
constexpr CodeRow kCodes[] = {
#define SDN_CODE(value, name, scope, modelled, text) {value, Scope::scope, text},
#include "modules/devicenet/status_codes.def"
#undef SDN_CODE
};

struct BitRow {
  int bit;
  std::string_view text;
};
constexpr BitRow kStatusBits[] = {
#define STATUS_BIT(bit, name, text) {bit, text},
#include "modules/devicenet/registers.def"
#undef STATUS_BIT
};
constexpr BitRow kCommandBits[] = {
#define COMMAND_BIT(bit, name, text) {bit, text},
#include "modules/devicenet/registers.def"
#undef COMMAND_BIT
};

// The scanner's own identity, answered at its address (Identity and DeviceNet objects). Device type
// 12 is the CIP communications adapter; revision 8.2 is firmware 8.002 (appendix C, p.129); the
// product code and serial number are invented.
DeviceModel scanner_model() {
  DeviceModel m;
  m.name = "1747-SDN";
  m.identity = Identity{1, 12, 19, 8, 2, 1747001, "1747-SDN Scanner Module"};
  return m;
}

// One explicit request/response exchange: the request's frames, the device's answer time, the
// response's frames.
Nanoseconds exchange(Baud b, int request_body, Nanoseconds answer, int response_body) {
  return explicit_message_time(b, request_body) + answer + explicit_message_time(b, response_body);
}

}  // namespace

std::string_view sdn_code_text(int code) {
  for (const auto& r : kCodes)
    if (r.value == code) return r.text;
  return "";
}

bool sdn_code_is_node_code(int code) {
  for (const auto& r : kCodes)
    if (r.value == code) return r.scope == Scope::Node;
  return false;
}

std::string_view status_bit_meaning(int b) {
  for (const auto& r : kStatusBits)
    if (r.bit == b) return r.text;
  return "";
}

std::string_view command_bit_meaning(int b) {
  for (const auto& r : kCommandBits)
    if (r.bit == b) return r.text;
  return "";
}

// ---- construction and configuration ------------------------------------------------------------------

Scanner::Scanner(Network& network, ScannerConfig config)
    : net_(network), config_(std::move(config)), self_(scanner_model()) {
  validate_scanner_settings(config_);
  self_.set_address(config_.node_address, config_.baud);
  net_.set_observer(this);
  rebuild_nodes();
  trace("power on");
  reconcile();
}

Scanner::~Scanner() {
  net_.timeline().cancel_owner(reinterpret_cast<Timeline::Owner>(this));
  net_.set_observer(nullptr);
}

void Scanner::download(ScannerConfig config) {
  validate_scanner_settings(config);
  if (port_ != Port::Down) stop_port(false);
  config_ = std::move(config);
  self_.set_address(config_.node_address, config_.baud);
  rebuild_nodes();
  trace("configuration downloaded");
  reconcile();
}

void Scanner::power_cycle() {
  if (port_ != Port::Down) stop_port(false);
  flushed_ = false;
  rebooting_ = false;
  command_error_ = false;
  command_word_ = 0;
  reset_ram();
  trace("power cycle");
  reconcile();
}

void Scanner::reset_ram() {
  din_.fill(0);
  dout_.fill(0);
  m0_.fill(0);
  m1_.fill(0);
  scan_counter_ = 0;
  txns_.clear();
  responses_.clear();
  probe_next_ = autoscan::kFirstNode;
  probe_busy_ = false;
  autoscan_rejected_.fill(false);
  rebuild_nodes();
}

void Scanner::release_nodes() {
  // Runs while config_.scanlist still holds the entries the node states point at.
  for (int n = 0; n < kNodeCount; ++n) {
    NodeState& s = nodes_[static_cast<std::size_t>(n)];
    if (s.phase == Phase::Connected) schedule_watchdog(n);
    // Requests still waiting for this node can no longer be sent to it.
    const std::deque<std::uint8_t> waiting = s.explicit_queue;
    s.explicit_queue.clear();
    for (std::uint8_t txid : waiting) complete_status(txid, TxnStatus::NotInScanlist);
    const std::uint64_t epoch = s.epoch + 1;  // orphans the old connection's periodic events
    const std::uint64_t connections = s.connections;
    const std::optional<std::uint8_t> in_flight = s.explicit_in_flight;
    s = NodeState{};
    s.epoch = epoch;
    s.connections = connections;
    s.explicit_in_flight = in_flight;  // its attempt events still complete it
  }
  listed_ = 0;
}

void Scanner::rebuild_nodes() {
  release_nodes();
  issues_ = validate_scanlist(config_);
  for (std::size_t i = 0; i < config_.scanlist.size(); ++i) {
    const int n = config_.scanlist[i].node;
    if (n < 0 || n >= kNodeCount) continue;
    NodeState& s = nodes_[static_cast<std::size_t>(n)];
    if (s.phase == Phase::Unlisted) {
      s.phase = Phase::Waiting;
      s.entry = static_cast<int>(i);
    }
  }
  for (const ScanlistIssue& issue : issues_) {
    if (issue.node < 0 || issue.node >= kNodeCount) continue;
    NodeState& s = nodes_[static_cast<std::size_t>(issue.node)];
    s.phase = Phase::Illegal;
    s.code = static_cast<int>(SdnCode::IllegalScanlistData);
  }
  refresh_listed();
}

void Scanner::refresh_listed() {
  listed_ = 0;
  for (int n = 0; n < kNodeCount; ++n)
    if (nodes_[static_cast<std::size_t>(n)].phase != Phase::Unlisted) listed_ |= std::uint64_t{1} << n;
}

const ScanlistEntry& Scanner::entry(int node) const {
  return config_.scanlist[static_cast<std::size_t>(nodes_[static_cast<std::size_t>(node)].entry)];
}

// ---- events -----------------------------------------------------------------------------------------

template <class F>
void Scanner::at(VirtualTime t, F&& fn) {
  net_.timeline().schedule_at(t, [fn = std::forward<F>(fn)](VirtualTime) mutable { fn(); },
                              reinterpret_cast<Timeline::Owner>(this));
}

template <class F>
void Scanner::at_running(VirtualTime t, std::uint64_t gen, F&& fn) {
  net_.timeline().schedule_at(
      t,
      [this, gen, fn = std::forward<F>(fn)](VirtualTime) mutable {
        if (gen == generation_ && port_ == Port::Running) fn();
      },
      reinterpret_cast<Timeline::Owner>(this));
}

void Scanner::trace(const std::string& what) {
  if (tracing_) trace_.push_back(std::to_string(now()) + " " + what);
}

// ---- the command register and the port -----------------------------------------------------------

void Scanner::write_output_image(std::span<const std::uint16_t> image) {
  if (image.empty()) return;
  const std::size_t n = std::min(image.size(), dout_.size());
  if (n > 1) std::copy(image.begin() + 1, image.begin() + static_cast<std::ptrdiff_t>(n), dout_.begin() + 1);
  apply_command(image[0]);
}

void Scanner::apply_command(std::uint16_t word) {
  const std::uint16_t before = command_word_;
  const bool was_error = command_error_;
  command_word_ = word;
  const std::uint16_t flush = bit(CommandBit::Flush);
  // Reserved bits must be 0 (p.139), and the flush procedure needs bit 2 alone: "If other bits in
  // the module command word are set, then the module will generate an error" (p.140).
  const bool bad = (word & ~kDefinedCommandBits) != 0 || ((word & flush) != 0 && word != flush);
  command_error_ = bad;
  if (bad) {
    if (!was_error) trace("command error " + std::to_string(word));
    reconcile();
    return;
  }
  if (word != before || was_error) trace("command " + std::to_string(word));
  if (word == flush) {
    if (!flushed_) flush_();
    reconcile();
    return;
  }
  const std::uint16_t reboot_bit = bit(CommandBit::Reboot);
  if ((word & reboot_bit) != 0 && ((before & reboot_bit) == 0 || was_error) && !flushed_) reboot();
  reconcile();
}

void Scanner::flush_() {
  if (port_ != Port::Down) stop_port(false);
  flushed_ = true;
  config_ = ScannerConfig{};  // node 63, 125K, no scanlist, AutoScan off (p.140)
  self_.set_address(config_.node_address, config_.baud);
  reset_ram();
  trace("flushed to factory defaults");
}

void Scanner::reboot() {
  if (port_ != Port::Down) stop_port(false);
  rebooting_ = true;
  reset_ram();
  trace("reboot");
  at(now() + timing::kRebootTime, [this] {
    rebooting_ = false;
    trace("reboot complete");
    reconcile();
  });
}

bool Scanner::port_wanted() const {
  const std::uint16_t stops = bit(CommandBit::FaultNetwork) | bit(CommandBit::DisableNetwork) | bit(CommandBit::Halt);
  return !flushed_ && !rebooting_ && !command_error_ && (command_word_ & stops) == 0 && net_.network_power() &&
         !net_.bus_fault() && net_.baud() == config_.baud;
}

void Scanner::reconcile() {
  const bool want = port_wanted();
  if (!want && port_ != Port::Down) {
    const bool involuntary = !net_.network_power() || net_.bus_fault() || net_.baud() != config_.baud;
    stop_port(involuntary);
  } else if (want && port_ == Port::Down) {
    start_port();
  }
}

void Scanner::start_port() {
  port_ = Port::Initializing;
  transmit_failed_ = false;
  trace("port starting: duplicate MAC ID check");
  const std::uint64_t gen = generation_;
  at(now() + timing::kDuplicateMacCheck, [this, gen] { finish_init(gen); });
}

void Scanner::finish_init(std::uint64_t gen) {
  if (gen != generation_ || port_ != Port::Initializing) return;
  const int addr = config_.node_address;
  if (net_.address_answers(addr)) {
    port_ = Port::DuplicateFailed;
    trace("duplicate node address " + std::to_string(addr));
    return;
  }
  if (!net_.any_other_node(addr)) {
    // No other node acknowledges our frames: the module fails to transmit (79) and tries again.
    if (!transmit_failed_) trace("failed to transmit: no other node on the network");
    transmit_failed_ = true;
    at(now() + timing::kInitRetry, [this, gen] { finish_init(gen); });
    return;
  }
  port_ = Port::Running;
  transmit_failed_ = false;
  background_count_ = 0;
  init_remaining_ = 0;
  for (auto& s : nodes_)
    if (s.phase == Phase::Waiting) {
      s.retry_at = now();
      if (!s.attempted) ++init_remaining_;
    }
  trace("port running");
  at_running(now(), gen, [this, gen] { cycle(gen); });
}

void Scanner::stop_port(bool involuntary) {
  ++generation_;
  port_ = Port::Down;
  transmit_failed_ = false;
  probe_busy_ = false;
  init_remaining_ = 0;
  for (int n = 0; n < kNodeCount; ++n) {
    NodeState& s = nodes_[static_cast<std::size_t>(n)];
    if (s.phase == Phase::Unlisted || s.phase == Phase::Illegal) continue;
    const bool was_connected = s.phase == Phase::Connected;
    if (was_connected) schedule_watchdog(n);
    s.phase = Phase::Waiting;
    s.retry_at = 0;
    s.active = false;
    s.idle = false;
    s.explicit_queue.clear();
    s.explicit_in_flight.reset();
    if (involuntary) {
      // The scanner lost the network under its devices: the ones it was talking to have failed.
      if (was_connected) {
        s.failed = true;
        clear_inputs(n);
      }
    } else {
      s.failed = false;
      s.autoverify = false;
      s.code = 0;
      s.attempted = false;
      s.ever_connected = false;
    }
  }
  fail_all_explicit(TxnStatus::PortOffline);
  trace(involuntary ? "port down (network failure)" : "port down");
}

void Scanner::on_bus_changed() { reconcile(); }

// ---- the scan cycle ----------------------------------------------------------------------------------

bool Scanner::node_scanned(int node) const {
  return nodes_[static_cast<std::size_t>(node)].phase == Phase::Connected;
}

void Scanner::cycle(std::uint64_t gen) {
  const VirtualTime t0 = now();
  const Baud baud = config_.baud;

  // 1. Connection timeouts: no packet for 4 x EPR.
  for_listed([&](int n) {
    NodeState& s = nodes_[static_cast<std::size_t>(n)];
    if (s.phase != Phase::Connected) return;
    const ScanlistEntry& e = entry(n);
    for (IoType t : kIoTypes) {
      const ConnectionConfig& c = e.conn(t);
      if (c.enabled && t0 - s.last_rx[static_cast<std::size_t>(t)] >= timing::kTimeoutMultiplier * c.epr) {
        fail_node(n, static_cast<int>(SdnCode::DeviceStoppedCommunicating), false);
        break;
      }
    }
  });
  // 2. Connection attempts.
  for_listed([&](int n) {
    const NodeState& s = nodes_[static_cast<std::size_t>(n)];
    if (s.phase == Phase::Waiting && s.retry_at <= t0) begin_connect(n);
  });
  // 3. AutoScan.
  if (autoscan_active() && !probe_busy_) autoscan_probe(gen);

  // 4. I/O. Outputs are sampled now, for the whole cycle.
  const bool run = in_run();
  VirtualTime cursor = t0;
  std::optional<VirtualTime> last_request;

  std::uint64_t strobed = 0;
  for_listed([&](int n) {
    if (node_scanned(n) && entry(n).conn(IoType::Strobe).enabled) strobed |= std::uint64_t{1} << n;
  });
  if (strobed != 0) {
    // The bit-strobe request: 64 bits, bit n for node n (appendix A, p.118), so `on` is the
    // message itself; zero-length in Idle. Each strobed node gets its bit as one byte (Run) or
    // nothing (Idle).
    std::uint64_t on = 0;
    if (run)
      for_each_node(strobed, [&](int n) {
        if (entry(n).conn(IoType::Strobe).tx != 1) return;
        const Bytes out = sample_outputs(n, IoType::Strobe);
        if (!out.empty() && (out[0] & 1) != 0) on |= std::uint64_t{1} << n;
      });
    cursor += io_message_time(baud, run ? 8 : 0);
    const VirtualTime request_end = cursor;
    last_request = request_end;
    at_running(request_end, gen, [this, strobed, on, run] {
      for_each_node(strobed, [&](int n) {
        const std::uint8_t bit = (on >> n) & 1u;
        deliver(n, IoType::Strobe, run ? std::span<const std::uint8_t>(&bit, 1) : std::span<const std::uint8_t>());
      });
    });
    for_each_node(strobed, [&](int n) {
      const SimDevice* d = net_.device(n);
      const auto answer = d != nullptr ? d->produced_length(IoType::Strobe) : std::nullopt;
      if (!answer) return;
      cursor = std::max(cursor, request_end + d->model().io_response_time) + io_message_time(baud, *answer);
      at_running(cursor, gen, [this, n] { receive(n, IoType::Strobe); });
    });
  }

  const bool background_due = background_count_ % config_.background_poll_ratio == 0;
  background_count_ = (background_count_ + 1) % config_.background_poll_ratio;
  for_listed([&](int n) {
    if (!node_scanned(n)) return;
    const ConnectionConfig& c = entry(n).conn(IoType::Poll);
    if (!c.enabled || (c.background && !background_due)) return;
    Bytes out = run ? sample_outputs(n, IoType::Poll) : Bytes{};
    cursor += io_message_time(baud, static_cast<int>(out.size()));
    last_request = cursor;
    at_running(cursor, gen, [this, n, out = std::move(out)] { deliver(n, IoType::Poll, out); });
    const SimDevice* d = net_.device(n);
    const auto answer = d != nullptr ? d->produced_length(IoType::Poll) : std::nullopt;
    if (!answer) return;
    cursor += d->model().io_response_time + io_message_time(baud, *answer);
    at_running(cursor, gen, [this, n] { receive(n, IoType::Poll); });
  });

  // Change-of-state outputs go out when they change (and on every heartbeat, schedule_periodic).
  for_listed([&](int n) {
    if (!node_scanned(n) || !entry(n).conn(IoType::Cos).enabled) return;
    NodeState& s = nodes_[static_cast<std::size_t>(n)];
    Bytes out = run ? sample_outputs(n, IoType::Cos) : Bytes{};
    if (s.cos_sent && out == s.last_cos_out) return;
    s.last_cos_out = out;
    s.cos_sent = true;
    const VirtualTime t = t0 + io_message_time(baud, static_cast<int>(out.size()));
    at_running(t, gen, [this, n, out = std::move(out)] { deliver(n, IoType::Cos, out); });
  });

  const VirtualTime scan_end = cursor;
  at_running(scan_end, gen, [this, gen] { end_of_scan(gen); });
  VirtualTime next = last_request ? std::max(*last_request + config_.interscan_delay, scan_end)
                                  : t0 + config_.interscan_delay;
  if (next <= t0) next = t0 + config_.interscan_delay;
  at_running(next, gen, [this, gen] { cycle(gen); });
}

void Scanner::end_of_scan(std::uint64_t gen) {
  ++scan_counter_;  // a uint16_t: 65535 rolls over to 0 (p.136)
  VirtualTime cursor = now();
  send_explicit(cursor, gen);
}

Nanoseconds Scanner::connect_time(const SimDevice& d, const ScanlistEntry* e) const {
  const Baud b = config_.baud;
  const Nanoseconds answer = d.model().explicit_response_time;
  // Allocate_Master/Slave_Connection_Set: service, class, instance, allocation choice, master MAC.
  Nanoseconds t = exchange(b, 5, answer, 2);
  if (d.owned_elsewhere()) return exchange(b, 5, answer, 3);  // the error response
  // Get_Attributes_All of the Identity object: 14 bytes plus the product name string.
  t += exchange(b, 3, answer, 1 + 14 + 1 + static_cast<int>(d.identity().product_name.size()));
  for (IoType type : kIoTypes) {
    const bool wanted = e != nullptr ? e->conn(type).enabled : d.supports(type);
    if (!wanted) continue;
    t += exchange(b, 4, answer, 3);                                 // produced connection size
    if (type != IoType::Strobe) t += exchange(b, 4, answer, 3);      // consumed connection size
    if (e != nullptr) t += exchange(b, 6, answer, 1);               // set expected packet rate
  }
  return t;
}

void Scanner::begin_connect(int node) {
  NodeState& s = nodes_[static_cast<std::size_t>(node)];
  s.phase = Phase::Establishing;
  const SimDevice* d = net_.device(node);
  const Nanoseconds duration =
      d != nullptr && d->online() ? connect_time(*d, &entry(node)) : timing::kExplicitTimeout;
  at_running(now() + duration, generation_, [this, node] { finish_connect(node); });
}

void Scanner::finish_connect(int node) {
  NodeState& s = nodes_[static_cast<std::size_t>(node)];
  if (s.phase != Phase::Establishing) return;
  if (!s.attempted) {
    s.attempted = true;
    if (init_remaining_ > 0) --init_remaining_;
  }
  const ScanlistEntry& e = entry(node);
  SimDevice* d = net_.device(node);
  std::vector<IoType> types;
  for (IoType t : kIoTypes)
    if (e.conn(t).enabled) types.push_back(t);

  if (d == nullptr || !d->online()) {
    fail_node(node, static_cast<int>(s.ever_connected ? SdnCode::DeviceStoppedCommunicating : SdnCode::DeviceDoesNotExist),
              false);
    return;
  }
  if (d->owned_elsewhere()) {
    fail_node(node, static_cast<int>(SdnCode::ErrorResponses), false);
    return;
  }
  if (!e.key.matches(d->identity())) {
    fail_node(node, static_cast<int>(SdnCode::KeyMismatch), false);
    return;
  }
  for (IoType t : types)
    if (!d->supports(t)) {
      fail_node(node, static_cast<int>(SdnCode::ErrorResponses), false);
      return;
    }
  for (IoType t : types) {
    const ConnectionConfig& c = e.conn(t);
    if (d->produced_size(t) != c.rx || (t != IoType::Strobe && d->consumed_size(t) != c.tx)) {
      fail_node(node, static_cast<int>(SdnCode::SizeMismatch), true);
      return;
    }
  }
  if (d->allocate(types) != SimDevice::AllocateResult::Ok) {
    fail_node(node, static_cast<int>(SdnCode::ErrorResponses), false);
    return;
  }
  s.phase = Phase::Connected;
  s.code = 0;
  s.autoverify = false;
  s.idle = false;
  s.ever_connected = true;
  ++s.epoch;
  ++s.connections;
  s.last_rx.fill(now());
  s.last_tx = now();
  s.cos_sent = false;
  trace("node " + std::to_string(node) + " connected");
  for (IoType t : types)
    if (t == IoType::Cos || t == IoType::Cyclic) schedule_periodic(node, t);
}

void Scanner::fail_node(int node, int code, bool autoverify) {
  NodeState& s = nodes_[static_cast<std::size_t>(node)];
  const bool was_connected = s.phase == Phase::Connected;
  if (was_connected) schedule_watchdog(node);
  s.phase = Phase::Waiting;
  s.retry_at = now() + timing::kReconnectInterval;
  s.code = code;
  s.failed = true;
  s.autoverify = autoverify;
  s.active = false;
  s.idle = false;
  clear_inputs(node);
  trace("node " + std::to_string(node) + " failed, code " + std::to_string(code));
}

void Scanner::schedule_watchdog(int node) {
  NodeState& s = nodes_[static_cast<std::size_t>(node)];
  if (s.entry < 0 || static_cast<std::size_t>(s.entry) >= config_.scanlist.size()) return;
  Nanoseconds epr = 0;
  for (IoType t : kIoTypes) {
    const ConnectionConfig& c = entry(node).conn(t);
    if (c.enabled && (epr == 0 || c.epr < epr)) epr = c.epr;
  }
  ++s.epoch;  // ends the connection's periodic events
  const std::uint64_t connections = s.connections;
  const VirtualTime expiry = std::max(now(), s.last_tx + timing::kTimeoutMultiplier * epr);
  at(expiry, [this, node, connections] {
    if (nodes_[static_cast<std::size_t>(node)].connections != connections) return;  // reconnected meanwhile
    if (SimDevice* d = net_.device(node)) d->master_lost();
  });
}

void Scanner::schedule_periodic(int node, IoType t) {
  const std::uint64_t epoch = nodes_[static_cast<std::size_t>(node)].epoch;
  const std::uint64_t gen = generation_;
  at_running(now() + entry(node).conn(t).epr, gen, [this, node, t, epoch, gen] {
    NodeState& s = nodes_[static_cast<std::size_t>(node)];
    if (s.phase != Phase::Connected || s.epoch != epoch) return;
    const Baud baud = config_.baud;
    // The scanner's heartbeat (COS) or cyclic production.
    Bytes out = in_run() ? sample_outputs(node, t) : Bytes{};
    if (t == IoType::Cos) {
      s.last_cos_out = out;
      s.cos_sent = true;
    }
    const VirtualTime sent = now() + io_message_time(baud, static_cast<int>(out.size()));
    at_running(sent, gen, [this, node, t, epoch, out = std::move(out)] {
      if (nodes_[static_cast<std::size_t>(node)].epoch == epoch) deliver(node, t, out);
    });
    // The device's heartbeat or cyclic production.
    if (const SimDevice* d = net_.device(node)) {
      if (const auto answer = d->produced_length(t)) {
        const VirtualTime arrives = now() + d->model().io_response_time + io_message_time(baud, *answer);
        at_running(arrives, gen, [this, node, t, epoch] {
          if (nodes_[static_cast<std::size_t>(node)].epoch == epoch) receive(node, t);
        });
      }
    }
    schedule_periodic(node, t);
  });
}

void Scanner::on_input_changed(int node) {
  if (port_ != Port::Running || node < 0 || node >= kNodeCount || !node_scanned(node)) return;
  if (!entry(node).conn(IoType::Cos).enabled) return;
  const SimDevice* d = net_.device(node);
  if (d == nullptr) return;
  const auto answer = d->produced_length(IoType::Cos);
  if (!answer) return;
  const std::uint64_t epoch = nodes_[static_cast<std::size_t>(node)].epoch;
  const VirtualTime arrives = now() + d->model().io_response_time + io_message_time(config_.baud, *answer);
  at_running(arrives, generation_, [this, node, epoch] {
    if (nodes_[static_cast<std::size_t>(node)].epoch == epoch) receive(node, IoType::Cos);
  });
}

void Scanner::deliver(int node, IoType t, std::span<const std::uint8_t> data) {
  NodeState& s = nodes_[static_cast<std::size_t>(node)];
  if (s.phase != Phase::Connected) return;
  if (SimDevice* d = net_.device(node)) d->consume(t, data);
  s.last_tx = now();
}

void Scanner::receive(int node, IoType t) {
  NodeState& s = nodes_[static_cast<std::size_t>(node)];
  if (s.phase != Phase::Connected) return;
  const SimDevice* d = net_.device(node);
  // produce(t) without building it: the length, and the input image whose first bytes it carries
  // (bytes past the image are zeros, which map_inputs reads for bytes past the span).
  const auto length = d != nullptr ? d->produced_length(t) : std::nullopt;
  if (!length) return;  // silent: the connection timeout notices
  s.last_rx[static_cast<std::size_t>(t)] = now();
  if (*length == 0) {
    if (!s.idle) trace("node " + std::to_string(node) + " idle");
    s.idle = true;
    s.active = true;
    return;
  }
  if (*length != entry(node).conn(t).rx) {
    fail_node(node, static_cast<int>(SdnCode::RuntimeSizeError), false);
    return;
  }
  s.idle = false;
  if (!s.active) trace("node " + std::to_string(node) + " active");
  s.active = true;
  s.failed = false;
  s.code = 0;
  const Bytes& image = d->inputs();
  map_inputs(node, t, std::span<const std::uint8_t>(image).first(std::min(image.size(), static_cast<std::size_t>(*length))));
}

// ---- mapping ------------------------------------------------------------------------------------------

void Scanner::set_table_bit(const TableRef& at, int offset, bool value) {
  const int linear = at.word * 16 + at.bit + offset;
  const auto w = static_cast<std::size_t>(linear / 16);
  const auto mask = static_cast<std::uint16_t>(1u << (linear % 16));
  std::uint16_t* word = nullptr;
  if (at.area == TableRef::Area::MFile && w < m1_.size()) word = &m1_[w];
  if (at.area == TableRef::Area::Discrete && w >= 1 && w < din_.size()) word = &din_[w];
  if (word == nullptr) return;  // validate_scanlist keeps legal entries inside; defensive
  *word = static_cast<std::uint16_t>(value ? *word | mask : *word & ~mask);
}

namespace {

// Walks `bits` bits from bit position `a` on a side of ABits-bit units to bit position `b` on a side
// of BBits-bit units, in runs that stay within one unit on both sides: f(a unit, shift in it, b unit,
// shift in it, run length). A byte-aligned segment is one run per byte.
template <int ABits, int BBits, class F>
void for_each_run(int a, int b, int bits, F&& f) {
  for (int left = bits; left > 0;) {
    const int as = a % ABits, bs = b % BBits;
    const int k = std::min({left, ABits - as, BBits - bs});
    f(a / ABits, as, b / BBits, bs, k);
    a += k;
    b += k;
    left -= k;
  }
}

}  // namespace

// Every receive maps its data: in runs (for_each_run), as set_table_bit would set them one by one.
void Scanner::map_inputs(int node, IoType t, std::span<const std::uint8_t> data) {
  for (const MapSegment& s : entry(node).inputs) {
    if (s.connection != t) continue;
    for_each_run<8, 16>(s.device_byte * 8 + s.device_bit, s.table.word * 16 + s.table.bit, s.bits,
                        [&](int byte, int sb, int w, int db, int k) {
                          const unsigned ones = (1u << k) - 1;
                          const auto i = static_cast<std::size_t>(byte), j = static_cast<std::size_t>(w);
                          const unsigned v = i < data.size() ? (static_cast<unsigned>(data[i]) >> sb) & ones : 0;
                          std::uint16_t* word = nullptr;
                          if (s.table.area == TableRef::Area::MFile && j < m1_.size()) word = &m1_[j];
                          if (s.table.area == TableRef::Area::Discrete && j >= 1 && j < din_.size()) word = &din_[j];
                          if (word != nullptr) *word = static_cast<std::uint16_t>((*word & ~(ones << db)) | (v << db));
                        });
  }
}

void Scanner::clear_inputs(int node) {
  const int e = nodes_[static_cast<std::size_t>(node)].entry;
  if (e < 0 || static_cast<std::size_t>(e) >= config_.scanlist.size()) return;
  for (const MapSegment& s : entry(node).inputs)
    for (int b = 0; b < s.bits; ++b) set_table_bit(s.table, b, false);
}

// In runs, as map_inputs; bits outside M0's data area or the output image read 0.
Bytes Scanner::sample_outputs(int node, IoType t) const {
  const ConnectionConfig& c = entry(node).conn(t);
  Bytes out(static_cast<std::size_t>(c.tx), 0);
  for (const MapSegment& s : entry(node).outputs) {
    if (s.connection != t) continue;
    for_each_run<16, 8>(s.table.word * 16 + s.table.bit, s.device_byte * 8 + s.device_bit, s.bits,
                        [&](int w, int sb, int byte, int db, int k) {
                          const auto i = static_cast<std::size_t>(byte), j = static_cast<std::size_t>(w);
                          unsigned word = 0;
                          if (s.table.area == TableRef::Area::MFile) word = j < layout::kDataWords ? m0_[j] : 0;
                          else word = j >= 1 && j < dout_.size() ? dout_[j] : 0;
                          if (i < out.size())
                            out[i] = static_cast<std::uint8_t>(out[i] | (((word >> sb) & ((1u << k) - 1)) << db));
                        });
  }
  return out;
}

// ---- the SLC side ---------------------------------------------------------------------------------

std::array<std::uint16_t, layout::kImageWords> Scanner::input_image() const {
  auto image = din_;
  image[0] = status_register();
  return image;
}

std::uint16_t Scanner::status_register() const {
  std::uint16_t w = command_error_ ? 0 : static_cast<std::uint16_t>(command_word_ & kEchoedCommandBits);
  // Built every input scan. Only a listed node can be failed (release_nodes resets an unlisted one).
  bool any_failed = false, any_autoverify = false;
  for_listed([&](int n) {
    any_failed |= nodes_[static_cast<std::size_t>(n)].failed;
    any_autoverify |= nodes_[static_cast<std::size_t>(n)].autoverify;
  });
  if (any_failed) w |= bit(StatusBit::DeviceFailure);
  if (any_autoverify) w |= bit(StatusBit::AutoverifyFailure);
  const bool no_partner = (port_ == Port::Initializing && transmit_failed_) ||
                          (port_ == Port::Running && !net_.any_other_node(config_.node_address));
  if (!net_.network_power() || net_.bus_fault() || net_.baud() != config_.baud || no_partner)
    w |= bit(StatusBit::CommunicationFailure);
  if (port_ == Port::DuplicateFailed) w |= bit(StatusBit::DuplicateNode);
  if (!responses_.empty()) w |= bit(StatusBit::ResponseAvailable);
  return w;
}

bool Scanner::read_m(MFile f, int word, std::uint16_t& value) const {
  if (word < 0 || word >= layout::kMFileWords) return false;
  value = 0;
  if (f == MFile::M0) {
    value = m0_[static_cast<std::size_t>(word)];
    return true;
  }
  // Only a listed node can be active, idle, failed or autoverify-failed (release_nodes resets the others).
  auto node_table = [&](int base, auto&& has) {
    std::uint16_t v = 0;
    const int first = (word - base) * 16;
    for_each_node((listed_ >> first) & 0xFFFFu, [&](int b) {
      if (has(nodes_[static_cast<std::size_t>(first) + static_cast<std::size_t>(b)])) v = static_cast<std::uint16_t>(v | (1u << b));
    });
    return v;
  };
  using L = std::pair<int, int>;
  auto in = [&](L range) { return word >= range.first && word < range.first + range.second; };
  if (word < layout::kDataWords) value = m1_[static_cast<std::size_t>(word)];
  else if (in({layout::kActiveTable, 4})) value = node_table(layout::kActiveTable, [](const NodeState& s) { return s.active; });
  else if (word == layout::kNodeStatus) value = node_status_word();
  else if (word == layout::kScanCounter) value = scan_counter_;
  else if (in({layout::kIdleTable, 4})) value = node_table(layout::kIdleTable, [](const NodeState& s) { return s.idle; });
  else if (in({layout::kFailureTable, 4})) value = node_table(layout::kFailureTable, [](const NodeState& s) { return s.failed; });
  else if (in({layout::kAutoverifyTable, 4}))
    value = node_table(layout::kAutoverifyTable, [](const NodeState& s) { return s.autoverify; });
  else if (in({layout::kTransactionBlock, layout::kTransactionWords})) {
    if (!responses_.empty())
      value = encode_response(responses_.front().block)[static_cast<std::size_t>(word - layout::kTransactionBlock)];
  }
  return true;
}

bool Scanner::write_m(MFile f, int word, std::uint16_t value) {
  if (word < 0 || word >= layout::kMFileWords) return false;
  if (f == MFile::M0) m0_[static_cast<std::size_t>(word)] = value;
  // M1 is read/write (p.123): the data area keeps what the ladder writes until the next device
  // update; the module's status and response words are recomputed on every read.
  else if (word < layout::kDataWords) m1_[static_cast<std::size_t>(word)] = value;
  return true;
}

void Scanner::process_request_block() {
  std::array<std::uint16_t, 32> block{};
  std::copy_n(m0_.begin() + layout::kTransactionBlock, 32, block.begin());
  handle_request(decode_request(block));
}

void Scanner::submit_request_block(std::span<const std::uint16_t, 32> block) {
  std::copy(block.begin(), block.end(), m0_.begin() + layout::kTransactionBlock);
  process_request_block();
}

// ---- status -------------------------------------------------------------------------------------------

bool Scanner::active(int n) const { return n >= 0 && n < kNodeCount && nodes_[static_cast<std::size_t>(n)].active; }
bool Scanner::idle(int n) const { return n >= 0 && n < kNodeCount && nodes_[static_cast<std::size_t>(n)].idle; }
bool Scanner::failed(int n) const { return n >= 0 && n < kNodeCount && nodes_[static_cast<std::size_t>(n)].failed; }
bool Scanner::autoverify_failed(int n) const {
  return n >= 0 && n < kNodeCount && nodes_[static_cast<std::size_t>(n)].autoverify;
}
bool Scanner::connected(int n) const { return n >= 0 && n < kNodeCount && node_scanned(n); }

int Scanner::node_code(int n) const {
  if (n < 0 || n >= kNodeCount) return 0;
  const NodeState& s = nodes_[static_cast<std::size_t>(n)];
  if (s.phase == Phase::Illegal) return static_cast<int>(SdnCode::IllegalScanlistData);
  if (s.code != 0) return s.code;
  if (s.phase == Phase::Connected && s.idle && in_run()) return static_cast<int>(SdnCode::DeviceIdle);
  return 0;
}

int Scanner::lowest_node_problem(int& node) const {
  // An unlisted node has no code (release_nodes resets it), so the listed ones, lowest first.
  for (std::uint64_t m = listed_; m != 0; m &= m - 1)
    if (int code = node_code(std::countr_zero(m))) {
      node = std::countr_zero(m);
      return code;
    }
  return 0;
}

std::uint16_t Scanner::node_status_word() const {
  const int addr = config_.node_address;
  auto module = [addr](int code) { return static_cast<std::uint16_t>(addr << 8 | (code & 0xFF)); };
  const std::uint16_t cmd = command_error_ ? 0 : command_word_;
  // Module conditions first, most fundamental first; then the lowest node with a problem; then the
  // mode codes. docs/1747-sdn.md gives the reasoning for this order.
  if (flushed_) return module(static_cast<int>(SdnCode::Flushed));
  if (command_error_) return module(static_cast<int>(SdnCode::Faulted));
  if ((cmd & bit(CommandBit::Halt)) != 0) return module(static_cast<int>(SdnCode::Halted));
  if ((cmd & bit(CommandBit::FaultNetwork)) != 0) return module(static_cast<int>(SdnCode::Faulted));
  if ((cmd & bit(CommandBit::DisableNetwork)) != 0) return module(static_cast<int>(SdnCode::PortDisabled));
  if (rebooting_) return module(static_cast<int>(SdnCode::Initializing));
  if (!net_.network_power()) return module(static_cast<int>(SdnCode::NoNetworkPower));
  if (net_.bus_fault() || net_.baud() != config_.baud) return module(static_cast<int>(SdnCode::BusOff));
  if (port_ == Port::DuplicateFailed) return module(static_cast<int>(SdnCode::DuplicateNode));
  if (port_ != Port::Running)
    return module(static_cast<int>(transmit_failed_ ? SdnCode::TransmitFailed : SdnCode::Initializing));
  if (!net_.any_other_node(addr)) return module(static_cast<int>(SdnCode::TransmitFailed));
  int node = 0;
  if (const int code = lowest_node_problem(node)) return static_cast<std::uint16_t>(node << 8 | code);
  if (init_remaining_ > 0) return module(static_cast<int>(SdnCode::Initializing));
  if (config_.autoscan) return module(static_cast<int>(SdnCode::AutoScanActive));
  if (listed_ == 0) return module(static_cast<int>(SdnCode::NoTraffic));
  if (!in_run()) return module(static_cast<int>(SdnCode::Idle));
  return module(addr);
}

// ---- Explicit Message Program Control ---------------------------------------------------------------

Scanner::Accept Scanner::handle_request(const RequestBlock& r) {
  switch (r.command) {
    case static_cast<std::uint8_t>(TxnCommand::Ignore): return Accept::Ignored;
    case static_cast<std::uint8_t>(TxnCommand::Execute): break;
    case static_cast<std::uint8_t>(TxnCommand::GetStatus): {
      const auto it = txns_.find(r.txid);
      if (it == txns_.end()) {
        status_report(r.txid, TxnStatus::TxidUnknown, r.service, r.mac);
      } else if (!it->second.done) {
        status_report(r.txid, TxnStatus::InProgress, it->second.request.service, it->second.request.mac);
      } else {
        const auto done = completed_response(r.txid);
        status_report(r.txid, done ? static_cast<TxnStatus>(done->status) : TxnStatus::TxidUnknown,
                      it->second.request.service, it->second.request.mac);
      }
      return Accept::Queued;
    }
    case static_cast<std::uint8_t>(TxnCommand::ResetAll):
      txns_.clear();
      responses_.clear();
      for (auto& s : nodes_) {
        s.explicit_queue.clear();
        s.explicit_in_flight.reset();
      }
      trace("explicit: reset all");
      return Accept::Queued;
    case static_cast<std::uint8_t>(TxnCommand::Delete): delete_transaction(r.txid); return Accept::Queued;
    default: status_report(r.txid, TxnStatus::InvalidCommand, r.service, r.mac); return Accept::Queued;
  }

  // Execute. A zero TXID is outside 1...255 and could never be matched: ignored. "Requests with
  // transaction IDs that are in use are ignored by the module" and executes beyond the tenth "are
  // received and deleted" (p.149).
  if (r.txid == 0 || txns_.count(r.txid) != 0) return Accept::Ignored;
  if (txns_.size() >= static_cast<std::size_t>(kMaxQueuedTransactions)) {
    trace("explicit: txid " + std::to_string(r.txid) + " dropped, ten in use");
    return Accept::Dropped;
  }
  txns_[r.txid] = Transaction{r, false, 0};
  if (const auto bad = check_request(r)) {
    complete_status(r.txid, *bad);
    return Accept::Queued;
  }
  if (r.mac == config_.node_address) {
    // "If you enter in the local scanner's DeviceNet node address, the command is executed by the
    // local scanner" (p.95); it needs no network.
    const CipReply reply = local_request(to_cip_request(r));
    complete(r.txid, ResponseBlock{static_cast<std::uint8_t>(TxnStatus::Success), r.txid, 0,
                                   reply_service(r.service, reply), r.mac, reply_bytes(reply)});
    return Accept::Queued;
  }
  if (r.mac >= kNodeCount || nodes_[r.mac].phase == Phase::Unlisted || nodes_[r.mac].phase == Phase::Illegal) {
    complete_status(r.txid, TxnStatus::NotInScanlist);
    return Accept::Queued;
  }
  if (port_ != Port::Running) {
    complete_status(r.txid, TxnStatus::PortOffline);
    return Accept::Queued;
  }
  NodeState& s = nodes_[r.mac];
  if (s.phase != Phase::Connected) {
    const bool refused = s.code == static_cast<int>(SdnCode::KeyMismatch) ||
                         s.code == static_cast<int>(SdnCode::SizeMismatch) ||
                         s.code == static_cast<int>(SdnCode::ErrorResponses);
    complete_status(r.txid, refused ? TxnStatus::CouldNotConnect : TxnStatus::SlaveOffline);
    return Accept::Queued;
  }
  s.explicit_queue.push_back(r.txid);
  trace("explicit: txid " + std::to_string(r.txid) + " queued for node " + std::to_string(r.mac));
  return Accept::Queued;
}

void Scanner::status_report(std::uint8_t txid, TxnStatus status, std::uint8_t service, std::uint8_t mac) {
  // One report per TXID: a newer one replaces the older, so repeated commands cannot grow the queue.
  std::erase_if(responses_, [txid](const QueuedResponse& q) { return q.report && q.block.txid == txid; });
  responses_.push_back(QueuedResponse{ResponseBlock{static_cast<std::uint8_t>(status), txid, 0, service, mac, {}}, true});
}

void Scanner::complete(std::uint8_t txid, ResponseBlock response) {
  const auto it = txns_.find(txid);
  if (it == txns_.end() || it->second.done) return;
  it->second.done = true;
  response.txid = txid;
  trace("explicit: txid " + std::to_string(txid) + " status " + std::to_string(response.status));
  responses_.push_back(QueuedResponse{std::move(response), false});
}

void Scanner::complete_status(std::uint8_t txid, TxnStatus status) {
  const auto it = txns_.find(txid);
  if (it == txns_.end()) return;
  complete(txid, ResponseBlock{static_cast<std::uint8_t>(status), txid, 0, it->second.request.service,
                               it->second.request.mac, {}});
}

void Scanner::fail_all_explicit(TxnStatus status) {
  std::vector<std::uint8_t> open;
  for (const auto& [txid, t] : txns_)
    if (!t.done && t.request.mac != config_.node_address) open.push_back(txid);
  for (std::uint8_t txid : open) complete_status(txid, status);
}

void Scanner::delete_transaction(std::uint8_t txid) {
  txns_.erase(txid);
  std::erase_if(responses_, [txid](const QueuedResponse& q) { return q.block.txid == txid; });
  for (auto& s : nodes_) std::erase(s.explicit_queue, txid);
}

std::optional<ResponseBlock> Scanner::head_response() const {
  if (responses_.empty()) return std::nullopt;
  return responses_.front().block;
}

std::optional<ResponseBlock> Scanner::completed_response(std::uint8_t txid) const {
  for (const auto& q : responses_)
    if (!q.report && q.block.txid == txid) return q.block;
  return std::nullopt;
}

void Scanner::send_explicit(VirtualTime& cursor, std::uint64_t gen) {
  // Only a listed node has requests queued (handle_request queues for connected nodes; release_nodes
  // empties the queues of the nodes it unlists).
  for (std::uint64_t m = listed_; m != 0; m &= m - 1) {
    const int n = std::countr_zero(m);
    NodeState& s = nodes_[static_cast<std::size_t>(n)];
    if (s.explicit_in_flight || s.explicit_queue.empty()) continue;
    const std::uint8_t txid = s.explicit_queue.front();
    s.explicit_queue.pop_front();
    s.explicit_in_flight = txid;
    const RequestBlock& r = txns_.at(txid).request;
    cursor += explicit_message_time(config_.baud, explicit_request_body(r.instance, r.attribute, static_cast<int>(r.data.size())));
    at_running(cursor, gen, [this, n, txid, gen] { attempt(n, txid, gen); });
  }
}

void Scanner::attempt(int node, std::uint8_t txid, std::uint64_t gen) {
  NodeState& s = nodes_[static_cast<std::size_t>(node)];
  const auto it = txns_.find(txid);
  if (it == txns_.end() || it->second.done) {  // deleted or reset meanwhile
    if (s.explicit_in_flight == txid) s.explicit_in_flight.reset();
    return;
  }
  Transaction& t = it->second;
  ++t.attempts;
  SimDevice* d = net_.device(node);
  if (d != nullptr && d->answers_explicit()) {
    const RequestBlock request = t.request;
    const CipReply reply = d->handle(to_cip_request(request));
    Bytes data = reply_bytes(reply);
    const VirtualTime done = now() + d->model().explicit_response_time +
                             explicit_message_time(config_.baud, 1 + static_cast<int>(data.size()));
    at_running(done, gen, [this, node, txid, request, reply, data = std::move(data)] {
      NodeState& ns = nodes_[static_cast<std::size_t>(node)];
      if (ns.explicit_in_flight == txid) ns.explicit_in_flight.reset();
      // A slave's CIP error is a successful transaction carrying the error (p.150).
      ResponseBlock rb{static_cast<std::uint8_t>(TxnStatus::Success), txid, 0, reply_service(request.service, reply),
                       request.mac, data};
      if (data.size() > static_cast<std::size_t>(kMaxBodyBytes)) {
        rb.status = static_cast<std::uint8_t>(TxnStatus::ResponseTooLarge);
        rb.data.clear();
      }
      complete(txid, std::move(rb));
    });
    return;
  }
  // No answer: retry after the timeout; after the last retry the transaction fails (p.150).
  if (t.attempts <= timing::kExplicitRetries) {
    at_running(now() + timing::kExplicitTimeout, gen, [this, node, txid, gen] { attempt(node, txid, gen); });
  } else {
    at_running(now() + timing::kExplicitTimeout, gen, [this, node, txid] {
      NodeState& ns = nodes_[static_cast<std::size_t>(node)];
      if (ns.explicit_in_flight == txid) ns.explicit_in_flight.reset();
      complete_status(txid, TxnStatus::NoResponse);
    });
  }
}

CipReply Scanner::local_request(const CipRequest& r) {
  if (r.class_id != autoscan::kClass) return self_.handle(r);
  // The AutoScan settings object (assumed addressing, autoscan.h).
  if (r.instance == 0) {
    if (r.service != service::kGetAttributeSingle) return CipReply::error(CipStatus::ServiceNotSupported);
    if (r.body.size() != 1) return CipReply::error(r.body.empty() ? CipStatus::NotEnoughData : CipStatus::TooMuchData);
    if (r.body[0] == 1 || r.body[0] == 2) return CipReply::success(Bytes{1, 0});
    return CipReply::error(CipStatus::AttributeNotSupported);
  }
  if (r.instance != autoscan::kInstance) return CipReply::error(CipStatus::ObjectDoesNotExist);
  if (r.service == service::kGetAttributeSingle) {
    if (r.body.size() != 1) return CipReply::error(r.body.empty() ? CipStatus::NotEnoughData : CipStatus::TooMuchData);
    if (r.body[0] == autoscan::kEnableAttribute) return CipReply::success(Bytes{static_cast<std::uint8_t>(config_.autoscan)});
    if (r.body[0] == autoscan::kAllocationAttribute)
      return CipReply::success(Bytes{static_cast<std::uint8_t>(config_.autoscan_allocation)});
    return CipReply::error(CipStatus::AttributeNotSupported);
  }
  if (r.service != service::kSetAttributeSingle) return CipReply::error(CipStatus::ServiceNotSupported);
  if (r.body.empty()) return CipReply::error(CipStatus::NotEnoughData);
  const std::uint8_t a = r.body[0];
  if (a != autoscan::kEnableAttribute && a != autoscan::kAllocationAttribute)
    return CipReply::error(CipStatus::AttributeNotSupported);
  if (r.body.size() < 2) return CipReply::error(CipStatus::NotEnoughData);
  if (r.body.size() > 2) return CipReply::error(CipStatus::TooMuchData);
  const std::uint8_t v = r.body[1];
  // "Verify that the scanner is in Idle mode" before configuring AutoScan (p.104).
  if (in_run()) return CipReply::error(CipStatus::DeviceStateConflict);
  if (a == autoscan::kEnableAttribute) {
    if (v > 1) return CipReply::error(CipStatus::InvalidAttributeValue);
    set_autoscan(v == 1);
  } else {
    if (v < autoscan::kMinAllocation || v > autoscan::kMaxAllocation) return CipReply::error(CipStatus::InvalidAttributeValue);
    config_.autoscan_allocation = v;
  }
  return CipReply::success();
}

// ---- AutoScan -----------------------------------------------------------------------------------------

bool Scanner::autoscan_active() const { return config_.autoscan && port_ == Port::Running && !in_run(); }

std::vector<int> Scanner::autoscan_rejected() const {
  std::vector<int> out;
  for (int n = 0; n < kNodeCount; ++n)
    if (autoscan_rejected_[static_cast<std::size_t>(n)]) out.push_back(n);
  return out;
}

void Scanner::set_autoscan(bool enabled) {
  if (enabled == config_.autoscan) return;
  config_.autoscan = enabled;
  if (!enabled) {
    trace("autoscan disabled");
    return;
  }
  // "An AutoScan Disable mode to Enable mode transition will cause the scanner to erase the
  // existing scanlist and scan for all nodes" and "changes ... ISD from 10 ms to 4 ms" (p.113).
  config_.interscan_delay = autoscan::kInterscanDelay;
  release_nodes();
  config_.scanlist.clear();
  rebuild_nodes();
  probe_next_ = autoscan::kFirstNode;
  probe_busy_ = false;
  autoscan_rejected_.fill(false);
  trace("autoscan enabled, scanlist erased");
}

void Scanner::autoscan_probe(std::uint64_t gen) {
  const int span = autoscan::kLastNode - autoscan::kFirstNode + 1;
  for (int k = 0; k < span; ++k) {
    const int p = autoscan::kFirstNode + (probe_next_ - autoscan::kFirstNode + k) % span;
    if (p == config_.node_address || nodes_[static_cast<std::size_t>(p)].phase != Phase::Unlisted) continue;
    probe_next_ = autoscan::kFirstNode + (p - autoscan::kFirstNode + 1) % span;
    probe_busy_ = true;
    const SimDevice* d = net_.device(p);
    const Nanoseconds duration =
        d != nullptr && d->online() && !d->owned_elsewhere() ? connect_time(*d, nullptr) : timing::kExplicitTimeout;
    at_running(now() + duration, gen, [this, p, gen] { finish_probe(p, gen); });
    return;
  }
}

void Scanner::finish_probe(int node, std::uint64_t /*gen*/) {
  probe_busy_ = false;
  if (!autoscan_active() || nodes_[static_cast<std::size_t>(node)].phase != Phase::Unlisted) return;
  const SimDevice* d = net_.device(node);
  if (d == nullptr || !d->online() || d->owned_elsewhere()) return;
  std::array<IoSupport, 4> reported{};
  for (IoType t : kIoTypes)
    reported[static_cast<std::size_t>(t)] = IoSupport{d->supports(t), d->produced_size(t), d->consumed_size(t)};
  auto decision = autoscan::decide(node, config_.autoscan_allocation, d->identity(), reported);
  if (decision.verdict != autoscan::Verdict::Accepted) {
    if (!autoscan_rejected_[static_cast<std::size_t>(node)])
      trace("autoscan: node " + std::to_string(node) + " rejected");
    autoscan_rejected_[static_cast<std::size_t>(node)] = true;
    return;
  }
  config_.scanlist.push_back(std::move(*decision.entry));
  issues_ = validate_scanlist(config_);
  bool bad = false;
  for (const auto& i : issues_) bad = bad || i.node == node;
  if (bad) {
    config_.scanlist.pop_back();
    issues_ = validate_scanlist(config_);
    autoscan_rejected_[static_cast<std::size_t>(node)] = true;
    return;
  }
  NodeState& s = nodes_[static_cast<std::size_t>(node)];
  s.phase = Phase::Waiting;
  s.entry = static_cast<int>(config_.scanlist.size() - 1);
  listed_ |= std::uint64_t{1} << node;
  s.retry_at = now();
  autoscan_rejected_[static_cast<std::size_t>(node)] = false;
  trace("autoscan: node " + std::to_string(node) + " added");
}

}  // namespace softslc::devicenet
