// Scanner: the 1747-SDN DeviceNet scanner's protocol logic, independent of the SLC backplane.
//
// The scanner is the master of one simulated Network. It keeps the module's tables exactly as the
// SLC sees them (tables.h): the 32-word discrete input image whose word 0 is the module status
// register, the M1 file (input data, status tables, response block), and the stores the processor
// writes (the 32-word output image whose word 0 is the command register, the M0 file). The module
// wrapper moves words in and out at the points of the SLC scan; everything else happens on the
// network's Timeline in virtual time.
//
// Port state. The DeviceNet port runs only when nothing stops it: not flushed (E9), halted (97),
// commanded to fault (81) or disable (90), rebooting, without network power (92), bus-off or at the
// wrong data rate (91). Starting the port runs the Duplicate MAC ID check (two requests one second
// apart, 2 s): a node answering at the scanner's address fails it (70, status bit 12) until the
// port is restarted; no node at all to acknowledge means code 79 and a retry every second.
//
// Scan cycle. While running, a cycle starts, in order: connection timeouts (a connection silent
// for 4 x its expected packet rate fails with 72), connection attempts for unconnected nodes, one
// AutoScan probe, then the I/O: the bit-strobe request (8 bytes of output bits in Run, zero-length
// in Idle) and the strobe responses in node order; then, in node order, each polled node due this
// cycle (foreground every cycle, background once every background_poll_ratio cycles): the poll
// command (its tx bytes in Run, zero-length in Idle), the device's response time and its
// response. Outputs are sampled once, when the cycle starts. The scan ends when the last response
// arrives: the scan counter (M1:211) counts it and queued explicit requests go out. The next cycle
// starts one interscan delay after the last poll request, "the time the module waits between the
// last poll message request and the start of the next scan cycle" (glossary), or when the scan ends
// if that is later. COS and cyclic connections run beside the cycle: the device produces on every
// input change and every EPR (heartbeat or rate), the scanner sends its COS outputs when they
// change at a cycle start and every EPR.
//
// Connecting a node takes the explicit exchanges a real scanner makes (allocate, identity, the
// produced/consumed size of every configured connection, set EPR) and ends in one of: connected;
// 78 (no device answered; 72 if it had been connected before); 83 (error responses: owned by another
// master, or a configured connection the device lacks); 73 (electronic key mismatch); 77 (size
// mismatch: autoverify failure table and status bit 8). A failed node is retried every second.
// Each of these sets the node's device failure bit (status bit 6) and clears its active bit; a
// failed node's mapped inputs are cleared to 0. A connected node whose data has the wrong length
// fails with 85 and is reconnected (so a lasting size change becomes 77); one that produces
// zero-length data is idle (device idle table; code 86 in Run) and its inputs hold. The first good
// data after connecting sets the active bit and clears the failure bit.
//
// Run/Idle follows command bit 0 at each cycle: Idle keeps the connections, sends zero-length
// outputs (devices apply their idle action) and still maps inputs. Stopping the port (fault,
// disable, halt, flush, reboot, bus-off, power) maps nothing further, and each device's own
// watchdog expires 4 x EPR after the last message it received, applying its fault action if it
// was in Run.
//
// Explicit Message Program Control (appendix E) is in the second half of this header; AutoScan in
// autoscan.h. Every decision the manual leaves open is listed in docs/1747-sdn.md.
#pragma once

#include <array>
#include <bit>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "modules/devicenet/autoscan.h"
#include "modules/devicenet/network.h"
#include "modules/devicenet/scanlist.h"
#include "modules/devicenet/tables.h"
#include "modules/devicenet/transaction.h"

namespace softslc::devicenet {

// The chapter 7 numeric codes (status_codes.def).
enum class SdnCode : std::uint8_t {
#define SDN_CODE(value, name, scope, modelled, text) name = value,
#include "modules/devicenet/status_codes.def"
#undef SDN_CODE
};
std::string_view sdn_code_text(int code);  // "" for 0...63 and unlisted codes
bool sdn_code_is_node_code(int code);

// Protocol timings the manual does not give; each is a documented model decision.
namespace timing {
inline constexpr Nanoseconds kDuplicateMacCheck = 2 * kNsPerS;  // two Duplicate MAC ID requests, 1 s apart
inline constexpr Nanoseconds kInitRetry = kNsPerS;              // retry after no node acknowledged (79)
inline constexpr Nanoseconds kReconnectInterval = kNsPerS;      // retry a failed node
inline constexpr Nanoseconds kExplicitTimeout = 500 * kNsPerMs; // one explicit request attempt
inline constexpr int kExplicitRetries = 2;                      // attempts = 1 + retries
inline constexpr Nanoseconds kRebootTime = 2 * kNsPerS;         // firmware start-up after a reboot command
inline constexpr int kTimeoutMultiplier = 4;                    // CIP inactivity watchdog = 4 x EPR
}  // namespace timing

inline constexpr int kMaxQueuedTransactions = 10;  // "A maximum of ten ... can be queued" (p.149)

class Scanner : public NetworkObserver {
 public:
  // Takes the configuration from nonvolatile memory and powers up at the network's current time.
  // Throws ConfigError for scanner-level settings it cannot run with. The network must outlive the
  // scanner; the destructor withdraws the scanner's pending events (device watchdogs included).
  Scanner(Network& network, ScannerConfig config);
  ~Scanner() override;
  Scanner(const Scanner&) = delete;
  Scanner& operator=(const Scanner&) = delete;

  // ---- configuration ----------------------------------------------------------------------------
  const ScannerConfig& config() const { return config_; }
  // Problems of the current scanlist; their nodes show code 71 and are not scanned.
  const std::vector<ScanlistIssue>& scanlist_issues() const { return issues_; }
  // A configuration download (RSNetWorx): replaces the configuration and restarts the port.
  void download(ScannerConfig config);
  // Power cycle: RAM (tables, queues, counters) cleared, configuration kept, port restarted.
  void power_cycle();
  Nanoseconds interscan_delay() const { return config_.interscan_delay; }

  // ---- the SLC side --------------------------------------------------------------------------------
  // Input image I:s.0...31 (word 0 = module status register).
  std::array<std::uint16_t, layout::kImageWords> input_image() const;
  // Output image O:s.0...(n-1), n <= 32 (word 0 = command register). Acts on the command at once.
  void write_output_image(std::span<const std::uint16_t> image);
  std::uint16_t status_register() const;
  std::uint16_t command_register() const { return command_word_; }
  // Immediate M-file access; false when `word` is outside the 395-word file.
  bool read_m(MFile f, int word, std::uint16_t& value) const;
  bool write_m(MFile f, int word, std::uint16_t value);
  // Acts on the request block in M0:224...255. The wrapper calls it once per M0 transfer that wrote
  // any of those words (a COP of the 32 words is one transfer).
  void process_request_block();
  // Writes a 32-word request block to M0:224...255 and processes it.
  void submit_request_block(std::span<const std::uint16_t, 32> block);

  // ---- status -------------------------------------------------------------------------------------
  // M1:210: high byte node address, low byte status code.
  std::uint16_t node_status_word() const;
  int status_code() const { return node_status_word() & 0xFF; }
  int status_node() const { return node_status_word() >> 8; }
  std::uint16_t scan_counter() const { return scan_counter_; }
  bool active(int node) const;
  bool idle(int node) const;
  bool failed(int node) const;
  bool autoverify_failed(int node) const;
  // The node's own code (71, 72, 73, 77, 78, 83, 85, 86), or 0.
  int node_code(int node) const;
  bool port_running() const { return port_ == Port::Running; }
  bool connected(int node) const;
  // AutoScan: whether it is probing now, and the nodes it rejected since enabled.
  bool autoscan_active() const;
  std::vector<int> autoscan_rejected() const;

  // ---- explicit messaging, typed (the DEM port and tests) ----------------------------------------
  enum class Accept : std::uint8_t { Queued, Ignored, Dropped };
  // Handles one request block as process_request_block() does, without touching M0.
  Accept handle_request(const RequestBlock& request);
  bool txid_in_use(std::uint8_t txid) const { return txns_.count(txid) != 0; }
  std::size_t transactions_in_use() const { return txns_.size(); }
  std::size_t responses_queued() const { return responses_.size(); }
  // The response at the head of the queue (what M1:224...255 shows).
  std::optional<ResponseBlock> head_response() const;
  // The final response of transaction `txid` if it has completed (not a status report).
  std::optional<ResponseBlock> completed_response(std::uint8_t txid) const;
  // Removes transaction `txid` and every queued response carrying it (command 4).
  void delete_transaction(std::uint8_t txid);

  // ---- determinism ------------------------------------------------------------------------------
  // When enabled, every state change is appended as one line "<ns> <event>" (for golden traces).
  void set_tracing(bool on) { tracing_ = on; }
  const std::vector<std::string>& trace() const { return trace_; }

  // NetworkObserver
  void on_input_changed(int node) override;
  void on_bus_changed() override;

 private:
  enum class Port : std::uint8_t { Down, Initializing, DuplicateFailed, Running };
  enum class Phase : std::uint8_t { Unlisted, Illegal, Waiting, Establishing, Connected };

  struct NodeState {
    Phase phase = Phase::Unlisted;
    int entry = -1;  // index into config_.scanlist
    int code = 0;    // 71, 72, 73, 77, 78, 83, 85 (86 is derived)
    bool active = false, failed = false, autoverify = false, idle = false;
    bool ever_connected = false, attempted = false;
    VirtualTime retry_at = 0;
    std::array<VirtualTime, 4> last_rx{};
    VirtualTime last_tx = 0;
    std::uint64_t epoch = 0;        // bumped whenever a connection starts or ends; tags periodic events
    std::uint64_t connections = 0;  // counts connections made; a device watchdog fires only if no
                                    // new connection was made since it was armed
    Bytes last_cos_out;
    bool cos_sent = false;
    std::deque<std::uint8_t> explicit_queue;
    std::optional<std::uint8_t> explicit_in_flight;
  };

  struct Transaction {
    RequestBlock request;
    bool done = false;
    int attempts = 0;
  };

  // Command handling and port control.
  void apply_command(std::uint16_t word);
  bool port_wanted() const;
  void reconcile();
  void start_port();
  void stop_port(bool involuntary);
  void finish_init(std::uint64_t gen);
  void reset_ram();
  void release_nodes();
  void rebuild_nodes();
  void refresh_listed();
  // Calls f(n) for every node n in `mask`, lowest first (node order).
  template <class F>
  static void for_each_node(std::uint64_t mask, F&& f) {
    for (; mask != 0; mask &= mask - 1) f(std::countr_zero(mask));
  }
  // Calls f(n) for every listed node (in the scanlist, or marked illegal), lowest first: every
  // other node is as NodeState{} leaves it and takes part in nothing.
  template <class F>
  void for_listed(F&& f) const {
    for_each_node(listed_, std::forward<F>(f));
  }

  // The scan cycle.
  void cycle(std::uint64_t gen);
  void end_of_scan(std::uint64_t gen);
  void begin_connect(int node);
  void finish_connect(int node);
  void receive(int node, IoType t);
  void deliver(int node, IoType t, std::span<const std::uint8_t> data);
  void fail_node(int node, int code, bool autoverify);
  void schedule_watchdog(int node);
  void schedule_periodic(int node, IoType t);
  bool in_run() const { return (command_word_ & bit(CommandBit::Run)) != 0 && !command_error_; }
  bool node_scanned(int node) const;
  const ScanlistEntry& entry(int node) const;

  // Mapping between device data and the tables.
  void map_inputs(int node, IoType t, std::span<const std::uint8_t> data);
  void clear_inputs(int node);
  Bytes sample_outputs(int node, IoType t) const;
  void set_table_bit(const TableRef& at, int offset, bool value);

  // Explicit messaging.
  void complete(std::uint8_t txid, ResponseBlock response);
  void complete_status(std::uint8_t txid, TxnStatus status);
  void attempt(int node, std::uint8_t txid, std::uint64_t gen);
  void send_explicit(VirtualTime& cursor, std::uint64_t gen);
  void status_report(std::uint8_t txid, TxnStatus status, std::uint8_t service, std::uint8_t mac);
  CipReply local_request(const CipRequest& request);
  void fail_all_explicit(TxnStatus status);

  // AutoScan.
  void autoscan_probe(std::uint64_t gen);
  void finish_probe(int node, std::uint64_t gen);
  void set_autoscan(bool enabled);

  // Events. at() schedules on the network's timeline under this scanner's owner tag; at_running()
  // also drops the work if the port has stopped (or restarted) since it was scheduled. Templates
  // (defined in scanner.cpp, their only user) so that `fn` lands in the timeline's callback as it
  // is, without a std::function around it.
  template <class F>
  void at(VirtualTime t, F&& fn);
  template <class F>
  void at_running(VirtualTime t, std::uint64_t gen, F&& fn);
  VirtualTime now() const { return net_.now(); }
  void flush_();
  void reboot();
  Nanoseconds connect_time(const SimDevice& d, const ScanlistEntry* e) const;
  void trace(const std::string& what);
  int lowest_node_problem(int& node) const;

  Network& net_;
  ScannerConfig config_;
  std::vector<ScanlistIssue> issues_;
  std::array<NodeState, kNodeCount> nodes_{};
  std::uint64_t listed_ = 0;  // bit n: nodes_[n].phase != Unlisted (kept by release/rebuild_nodes, finish_probe)

  std::array<std::uint16_t, layout::kImageWords> din_{};   // discrete inputs (word 0 unused)
  std::array<std::uint16_t, layout::kImageWords> dout_{};  // discrete outputs (word 0 = command)
  std::array<std::uint16_t, layout::kMFileWords> m0_{};
  std::array<std::uint16_t, layout::kDataWords> m1_{};
  std::uint16_t scan_counter_ = 0;

  std::uint16_t command_word_ = 0;
  bool command_error_ = false;
  bool flushed_ = false;
  bool rebooting_ = false;

  Port port_ = Port::Down;
  bool transmit_failed_ = false;
  int init_remaining_ = 0;
  std::uint64_t generation_ = 1;  // bumped whenever the port stops; tags cycle events
  int background_count_ = 0;

  std::map<std::uint8_t, Transaction> txns_;
  struct QueuedResponse {
    ResponseBlock block;
    bool report = false;  // a status report (commands 2, 5...255) rather than a transaction's answer
  };
  std::deque<QueuedResponse> responses_;

  int probe_next_ = autoscan::kFirstNode;
  bool probe_busy_ = false;
  std::array<bool, kNodeCount> autoscan_rejected_{};

  SimDevice self_;  // the scanner's own Identity and DeviceNet objects
  bool tracing_ = false;
  std::vector<std::string> trace_;
};

}  // namespace softslc::devicenet
