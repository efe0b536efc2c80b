// The runtime: one simulated SLC 500 processor and its chassis, for tools and tests.
//
// A Runtime is built from a loaded Program. It compiles it, lays out the data table, puts a
// module in every configured slot (a specialty module from RuntimeOptions::module_factory, else
// generic discrete I/O), installs the program's forces, and starts in Program mode at virtual
// time 0. Nothing happens until the caller scans or runs it.
//
// The scan cycle is the SLC's, each phase a separate function, in this order:
//
//   input_scan()     every module's input image -> I file, then input forces
//   program_scan()   file 2 from rung 0 (subroutines by JSR) — Run and Test modes only
//   output_scan()    O file + output forces -> every module (zeros unless in Run)
//   housekeeping()   status words (S:1/15, S:3, S:4, S:22, S:23, S:35), statistics
//
// after which the virtual clock advances by the scan's predicted duration (ScanTimeModel) and
// the event queue runs every module event due by then. In Program and Faulted mode a scan is
// only the I/O and housekeeping phases, so time still passes and modules still run. Test mode
// is the SLC's "test single scan": each scan() call executes the program once with outputs
// disabled; run_for/run_until in Test mode only idle.
//
// A major fault (from the program scan, or the watchdog at the end of a scan) stops the program
// scan at once, sets S:1/13 and S:6, records file/rung/message (fault()), and puts the runtime in
// Faulted mode with its outputs de-energised. clear_fault() returns to Program mode.
//
// Determinism: the runtime reads no wall clock and iterates only ordered containers; the same
// program, inputs and calls give byte-identical data tables, times and fault records.
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "parser/program.h"
#include "vm/ascii_channel.h"
#include "vm/modbus_master.h"
#include "vm/bytecode.h"
#include "vm/compiler.h"
#include "vm/coverage.h"
#include "vm/data_table.h"
#include "vm/event_queue.h"
#include "vm/faults.h"
#include "vm/field_process.h"
#include "vm/interpreter.h"
#include "vm/message_network.h"
#include "vm/module.h"
#include "vm/scan_time_model.h"
#include "vm/virtual_time.h"

namespace softslc {

namespace word_ops {
struct TimerExecution;
}

// Creates the module for a slot; returning nullptr means "generic discrete I/O".
using ModuleFactory = std::function<std::unique_ptr<Module>(const SlotConfig&)>;

struct PeerController;

// The bench device that is channel 0's DF1 link (`device DF1 cable removed`, `expect device DF1 sent == 4`).
inline constexpr std::string_view kDf1DeviceName = "DF1";

struct RuntimeOptions {
  std::optional<ProcessorModel> processor;         // overrides the program's START line
  std::shared_ptr<const ScanTimeModel> time_model;  // default: DefaultScanTimeModel
  ModuleFactory module_factory;
  ModuleInstructionHook module_instruction;
  // Simulated plants wired to data-table words (vm/field_process.h), attached in this order once
  // the runtime exists; one that cannot resolve its words fails create() with its message.
  std::vector<FieldProcessFactory> field_processes;
  // Channel 0 in User (ASCII) mode with the device wired to it (vm/ascii_channel.h); empty: the
  // channel stays in System mode and the ASCII channel instructions end with ER.
  std::function<std::unique_ptr<AsciiChannel>()> ascii_channel;
  // Channel 0 of a MicroLogix 1100/1400 as a Modbus RTU master with its slaves (vm/modbus_master.h); empty:
  // channel 0 is no Modbus master and a Modbus MSG ends with 12h.
  std::function<std::unique_ptr<ModbusMaster>()> modbus_channel;
  // MSG (docs/semantics.md "MSG"): this controller's node on its network, and the other controllers
  // on it. With peers, the runtime created is the network's leader: it owns the peers, drives them in
  // lockstep with its own scans, and passes its mode changes on to them.
  int node = 1;
  // On Ethernet (SLC 5/05 channel 1) the controller is named by its IP address instead (A.B.C.D as a
  // number, A in the high byte; 0: none configured, the processor's default, so its MSGs end with D0h).
  std::uint32_t ip = 0;
  // The 1764-LRP's channel 1, its second serial port, on DH-485 (docs/semantics.md "The MicroLogix MSG
  // (1100-1500)", "Channel 1 of the 1500 LRP"): its node there (0: channel 1 is on no network, and its
  // MSGs reach nobody), and the network it is on: "" this controller's network (the one its channel 0
  // and the peers are on), any other name a second DH-485 network of the same virtual time whose
  // stations are the peers given that name (PeerController::network).
  int channel1_node = 0;
  std::string channel1_network;
  // Channel 0 in System mode as DF1 full-duplex (vm/df1_link.h; docs/semantics.md "DF1 full-duplex on
  // channel 0"): its settings, each one left unset the processor's default. Empty: channel 0 is not so
  // configured (an SLC 5/03-5/05's channel 0 MSG then ends with 12h; a MicroLogix's channel 0 is on DH-485).
  std::optional<Df1Options> channel0_df1;
  std::vector<PeerController> peers;
};

// Another controller on the leader's MSG network: its program, its options (modules, processor;
// their own peers are ignored), its name (how tests address it) and its node.
struct PeerController {
  std::string name;
  int node = 2;
  std::uint32_t ip = 0;  // on Ethernet, instead of the node
  // The network the peer is on: "" the leader's, a name one the leader's channel 1 names (a 1764-LRP's
  // second serial port, RuntimeOptions::channel1_network). Node numbers are unique per network.
  std::string network;
  // Joined point to point to the leader's DF1 channel 0 by the cable (a null-modem cable) instead of being on
  // the network: the peer's own channel 0 is DF1 full-duplex, configured by its options' channel0_df1 (unset:
  // its processor's defaults). The leader needs channel0_df1; one such peer at most.
  bool df1 = false;
  // On the leader's Modbus RTU line instead (docs/semantics.md "A MicroLogix as a Modbus RTU slave"): the peer's
  // channel 0 is a Modbus RTU slave at this address, baud rate and map, answering the leader's Modbus MSGs from
  // its own data table. The leader's channel 0 must be a Modbus RTU master (modbus_channel); the peer a
  // MicroLogix 1100 or 1400; its address unique on the line (the bench's modbus nodes included).
  std::optional<modbus::SlaveOptions> modbus;
  std::shared_ptr<const Program> program;
  std::shared_ptr<const RuntimeOptions> options;
};

// Success, or a message saying why a request was refused.
struct RuntimeStatus {
  bool ok = true;
  std::string message;
  explicit operator bool() const { return ok; }
  static RuntimeStatus failure(std::string m) { return {false, std::move(m)}; }
};

struct ScanStats {
  std::uint64_t scans = 0;        // program scans executed since the runtime was created
  Nanoseconds last = 0;           // duration of the last program scan (whole scan cycle)
  Nanoseconds max = 0;
  Nanoseconds total = 0;
  std::uint64_t instructions = 0;  // instructions executed, all scans
  std::uint64_t repeated = 0;      // of `scans`, those taken as repeats of the scan before, not executed
  Nanoseconds avg() const { return scans ? total / static_cast<Nanoseconds>(scans) : 0; }
  std::int64_t last_us() const { return last / kNsPerUs; }
  std::int64_t max_us() const { return max / kNsPerUs; }
  std::int64_t avg_us() const { return avg() / kNsPerUs; }
};

// A word counted alone (docs/semantics.md "Counted words carried across repeats"): a direct N or B word
// that the program's text reaches only through one ADD or SUB of a constant into itself, compares with
// constants, and CLR or MOV of a constant. Found by Runtime::create.
struct CountedWord {
  std::uint32_t word = 0;
  bool subtract = false;        // SUB W k W; else ADD W k W or ADD k W W
  bool constant_first = false;  // ADD k W W: the constant is source A (ADD's carry is symmetric)
  std::int64_t k = 0;           // the constant, non-zero
  std::vector<std::int64_t> resets;  // the constants of the CLR (0) and MOV c W that may write it
  struct Compare {
    Opcode op;
    std::array<std::int64_t, 3> operand;  // the constants; the word's own place is `at`
    std::size_t at;                        // which operand is the word
  };
  std::vector<Compare> compares;
};

class Runtime;

struct RuntimeResult {
  std::unique_ptr<Runtime> runtime;
  std::vector<CompileError> errors;
  bool ok() const { return runtime != nullptr; }
  std::string render_errors() const;
};

class Runtime final : private ModuleHost, private ChassisAccess {
 public:
  static RuntimeResult create(const Program& program, RuntimeOptions options = {});
  ~Runtime() override;
  Runtime(const Runtime&) = delete;
  Runtime& operator=(const Runtime&) = delete;

  // ---- Modes and faults ----
  Mode mode() const override { return mode_; }
  // Program, Run or Test. Entering Run/Test sets up a first pass (S:1/15) and zeroes S:4;
  // refused while a fault is active (clear_fault() first) and for Mode::Faulted.
  RuntimeStatus set_mode(Mode m);
  // Clears an active major fault: S:1/13 off, the fault record cleared, Program mode. S:6 keeps
  // its code (PT1 27-17: the processor does not clear it).
  void clear_fault();
  const std::optional<FaultInfo>& fault() const { return fault_; }

  // ---- MicroLogix data logging (docs/semantics.md "Data logging: DLG and the DLS file") ----
  // Retrieval as a communications read does it (1763-RM001C p. 442): the oldest record of data log
  // queue `queue` as its text (date, time, fields, the queue's delimiter), removed from the queue
  // (DLS0:q.RST decremented, DN cleared). nullopt when the queue is empty or not configured.
  std::optional<std::string> retrieve_data_log_record(int queue);
  // The records of a queue as text, oldest first, left in place; the configured queue numbers.
  std::vector<std::string> data_log_records(int queue) const;
  std::vector<int> data_log_queues() const;
  // Takes over the records of `other`'s queues (a power cycle: the data log memory is battery-backed,
  // 1763-RM001C p. 433). Both runtimes run the same program.
  void keep_data_logs_of(const Runtime& other);

  // ---- Running ----
  // Runs n scan cycles (in Test mode: n single scans). Stops early when a scan faults. Returns
  // the number of scans run.
  int scan(int n = 1);
  // Runs whole scans until at least `duration` of virtual time has passed. Returns scans run (a scan
  // taken as a repeat of the one before counts as run: docs/semantics.md "Repeated scans").
  std::int64_t run_for(Nanoseconds duration);
  // One step of run_for toward `end` (which must be later than now): one scan, or a probe and
  // the scans that repeat it, none starting at or after `end`. Returns the scans taken. For a
  // caller that looks at the runtime between steps (softslc run stops at a fault or a SUS, which
  // only an executed scan can bring, and saves its state file at checkpoints).
  std::int64_t advance_toward(VirtualTime end);
  // run_for may take scans that would repeat the last one without executing them (the default);
  // off, every scan executes. Results are the same either way (tests compare the two).
  void skip_repeated_scans(bool on) { skip_repeated_ = on; }
  // Runs whole scans until `pred` holds (checked before the first scan and after each) or
  // `limit` of virtual time has passed. Returns whether `pred` held.
  bool run_until(const std::function<bool(const Runtime&)>& pred, Nanoseconds limit);
  VirtualTime now() const override { return clock_.now(); }
  const ScanStats& stats() const { return stats_; }
  // the discrete input interrupt's applied configuration, runs and last latency, and
  // the I/O event interrupt routines run (for tests and tools).
  const DiiState& dii() const { return interp_->dii(); }
  const StiTimer& sti() const { return interp_->sti(); }
  std::uint64_t isr_runs() const { return interp_->isr_runs(); }

  // ---- Data ----
  // Writes a value. An I: address sets the simulated field input of the slot's module (seen
  // from the next input scan, as on the real processor); M0/M1 go to the module's accessor;
  // anything else writes the data table now (floats into integers round half to even).
  RuntimeStatus set(std::string_view address, Value v);
  RuntimeStatus set(const Address& address, Value v);
  // Reads a value: bits as Bit, integer words as Integer, F as Float.
  std::optional<Value> get(std::string_view address, std::string* error = nullptr) const;
  std::optional<Value> get(const Address& address, std::string* error = nullptr) const;
  // get() that throws std::invalid_argument for a bad address (tests, quick tools).
  Value value(std::string_view address) const;
  // The printable value: bits 0/1, integers signed decimal, floats %g.
  std::string format(std::string_view address) const;

  // ---- Forces (I and O bits) ----
  RuntimeStatus force(std::string_view address, bool on);
  RuntimeStatus unforce(std::string_view address);
  void clear_forces();
  void enable_forces(bool enabled);
  bool forces_enabled() const { return forces_enabled_; }

  // ---- Simulated field devices (the bench) ----
  // Injects a change into the named field device of whichever module owns it (see
  // DeviceFault: "offline", "cable removed", "data size", ...). Refused for an unknown device
  // or a change the device does not accept. Takes effect at the current virtual time.
  RuntimeStatus inject(std::string_view device, std::string_view fault, std::vector<std::string> args = {});
  // An observable value of a named field device ("outputs", "btw data", ...); nullopt when no
  // module owns the device or it has no such value.
  std::optional<std::vector<std::int64_t>> observe(std::string_view device, std::string_view what) const;
  // The built-in HSC0-HSC5 input devices of a MicroLogix (`device HSC0 pulses 1000`; vm/ml_hsc.h).
  int hsc_input_name(std::string_view device) const;
  RuntimeStatus inject_hsc_pulses(int counter, std::string_view change, const std::vector<std::string>& args);
  // Every named field device, in slot order.
  std::vector<std::string> devices() const;

  // ---- Ladder coverage (vm/coverage.h) ----
  // Starts recording which rungs and instructions the program scans exercise. Costs nothing
  // until called; from then on the interpreter reports every instruction.
  void enable_coverage();
  // The recorder, or nullptr when coverage is off.
  const CoverageRecorder* coverage() const { return coverage_.get(); }

  // ---- Scan observer (signal traces, tools/trace/) ----
  // Called at the end of every scan cycle, after the clock has advanced and the module events due
  // by then have run, so an observer sees the data table as the scan left it, stamped with now().
  // Sampling at scan boundaries keeps tracing out of the interpreter: with no observer the cost
  // is one test per scan. An empty function detaches.
  using ScanObserver = std::function<void(const Runtime&)>;
  void set_scan_observer(ScanObserver observer) { scan_observer_ = std::move(observer); }

  // ---- MSG network (vm/message_network.h) ----
  // This controller's node, and the peer named `name` on its network (nullptr when there is none).
  // A peer's data may be read and written at any time; its scans are driven by the leader.
  int node() const { return node_; }
  std::uint32_t ip() const { return ip_; }
  Runtime* peer(std::string_view name) const;
  std::vector<std::string> peer_names() const;

  // ---- Access for tools and tests ----
  Module* module(int slot) const;
  EventQueue& events() { return events_; }
  // Channel 0 in User mode, or nullptr.
  AsciiChannel* ascii_channel() const { return ascii_channel_.get(); }
  // Channel 0 as a Modbus RTU master, or nullptr.
  ModbusMaster* modbus_channel() const { return modbus_channel_.get(); }
  const CompiledProgram& compiled() const { return *program_; }
  DataTable& data() { return data_; }
  const DataTable& data() const { return data_; }
  const ScanTimeModel& time_model() const { return *model_; }

 private:
  Runtime(std::unique_ptr<CompiledProgram> program, RuntimeOptions options);

  // The scan cycle.
  void scan_once(bool single_scan_step);
  Nanoseconds input_scan();
  ProgramScanResult program_scan(VirtualTime scan_start, Nanoseconds elapsed);
  Nanoseconds output_scan();
  // Advances the RTC function file (when the processor has one) to virtual time `now`.
  void advance_rtc(VirtualTime now);
  // Brings S:4, the free-running clock, up to the processor's clock ticks at virtual time `at`
  // (the start of a program scan, executed or repeated).
  void advance_free_running_clock(VirtualTime at);
  // The housekeeping of an executed scan of `scan_time`: its status words and statistics (its cost,
  // model_->housekeeping_cost(), is counted by the caller).
  void housekeeping(Nanoseconds scan_time);
  // Repeated scans (docs/semantics.md "Repeated scans"): whether the next scan may be a probe, and
  // the probe: one scan executed with the data table saved before it; when it changed no word but
  // the runtime's own, the scans that would repeat it before `end` (and before anything else is
  // due) are taken without executing them. Returns the scans run and taken.
  bool probe_due();
  std::int64_t probe_and_repeat(VirtualTime end);
  // Repeated cycles (docs/semantics.md "Repeated cycles"): after a probe whose scan changed the table and
  // nothing else, the scan after it is executed too, and when the two left everything as the probe found
  // it, the pairs of scans that would repeat them are taken without executing them. `probe` is what the
  // probe recorded before its scan. Returns the scans run and taken after the probe's.
  struct ProbeStart;
  std::int64_t probe_cycle(VirtualTime end, const ProbeStart& probe);
  // What the repeats of one scan go by (repeat_scans): the probe's measures and bounds.
  struct RepeatBasis {
    VirtualTime start = 0;  // the probe's start: a timer that read the clock bounds the repeats to its tick
    Nanoseconds d = 0;      // the scan's length
    Nanoseconds scan_time = 0;  // what its housekeeping was given
    std::uint64_t per_scan = 0;  // instructions
    std::uint16_t s33_toggle = 0;  // S:33/9, when the scan toggled it
    bool timing = false;
    VirtualTime pid_until = 0;
    std::int64_t count_limit = 0;
    bool across_events = false;  // the repeats may go on across events that change nothing the program reads
    std::optional<VirtualTime> network_quiet;
    std::uint64_t routine_runs = 0, process_writes = 0, between_scan_writes = 0;
  };
  // The scans that repeat the one `b` describes, from the clock's time to `end`; returns how many were
  // taken. `remembered`: no probe preceded them (repeat_remembered), and none taken is no failure.
  std::int64_t repeat_scans(VirtualTime end, const RepeatBasis& b, bool remembered);
  // Remembered steady scans (docs/semantics.md): the repeats of a probe remembered in steady_, taken
  // without a probe when the table is the one it left; 0 when it does not stand for the next scan.
  std::int64_t repeat_remembered(VirtualTime end);
  // Every scanned module's input image, with the input forces, is the I file the table holds.
  bool inputs_as_scanned();
  // The network holds for this station what it held before the probe (MessageNetwork::holdings).
  bool network_kept();
  void probe_failed();
  void wait_longer_before_probing();  // the wait before the next probe doubles, up to 64 scans
  // Every scanned module says it is passive (Module::passive).
  bool modules_passive() const;
  // During a probe: notes a module the program reaches (its count before the first access).
  void reach(int slot);
  // After a probe, or after events between repeats: no module the probe reached has counted a
  // change, every M0/M1 word it read reads the same, every M0/M1 write it made would change
  // nothing, and every module's input image is the one its input scan gave.
  bool reached_modules_unchanged() const;
  bool probe_reads_the_same();
  // The scans from `t` (each `d` long) whose program scans would see the bits of S:4 the program
  // reads (clock_bits_read_) as S:4 shows them now; unbounded when it reads none.
  std::int64_t scans_before_the_clock_bits_change(VirtualTime t, Nanoseconds d) const;
  void enter_fault(const FaultInfo& f);
  void enter_suspend();
  void apply_input_forces(std::uint32_t first, std::uint32_t count);
  std::uint16_t forced_output(std::uint32_t i) const;
  void write_mode_bits();
  void notify_modes(Mode from, Mode to);

  // Address helpers for the tool API.
  std::optional<Location> resolve_tool_address(const Address& a, std::string& error) const;

  // ModuleHost.
  EventQueue::EventId schedule_at(VirtualTime at, EventQueue::Callback cb) override;
  bool cancel_event(EventQueue::EventId id) override;
  void raise_major_fault(std::uint16_t code, std::string message) override;
  // ChassisAccess.
  MAccess read_m(int slot, MFile f, int word, std::uint16_t& value) override;
  MAccess read_m_block(int slot, MFile f, int word, std::span<std::uint16_t> out, std::size_t& done) override;
  MAccess write_m(int slot, MFile f, int word, std::uint16_t value) override;
  std::string m_refusal(int slot, MFile f, int word, bool write) const override;
  void immediate_input(int slot, int first, int count, std::uint16_t mask) override;
  void immediate_output(int slot, int first, int count, std::uint16_t mask) override;
  Nanoseconds io_refresh(VirtualTime at) override;
  // the DII's and the I/O event interrupt's sources.
  void field_input_changed(int slot, int word, std::uint16_t before, std::uint16_t after) override;
  void request_io_interrupt(int slot) override;
  bool discrete_input_card(int slot) const override;
  void interrupt_serviced(int slot) override;
  void module_instruction(int slot, ModuleInstructionContext& ctx) override;
  void message_start(const MessageInstruction& m) override;
  void message_abort(std::uint32_t block) override;
  // Channel 0 of an SLC 5/03-5/05 that nothing configured is a DF1 full-duplex port at its defaults
  // (default_df1_port), attached when first used (a MSG on it, a `device DF1` line).
  bool default_df1_port() const;
  void attach_default_df1_port();
  void service_communications(std::uint16_t channels, VirtualTime at) override;
  MessageNetwork& network();
  std::string join_peers(const std::vector<PeerController>& peers, int channel1_node,
                         const std::string& channel1_network, const std::optional<Df1Options>& channel0_df1);
  std::string join_df1_peer(MessageNetwork& net, const PeerController& p, bool leader_df1, bool joined);
  std::string join_modbus_peer(MessageNetwork& net, const PeerController& p);

  std::unique_ptr<CompiledProgram> program_;
  std::shared_ptr<const ScanTimeModel> model_;
  DataTable data_;
  VirtualClock clock_;
  EventQueue events_{clock_};
  std::vector<std::unique_ptr<Module>> owned_modules_;
  // Field processes and the host they see (vm/field_process.h).
  class ProcessHost;
  std::unique_ptr<ProcessHost> process_host_;
  std::vector<std::unique_ptr<FieldProcess>> processes_;
  std::unique_ptr<AsciiChannel> ascii_channel_;
  std::unique_ptr<ModbusMaster> modbus_channel_;
  std::array<Module*, kMaxSlots> modules_{};
  // The modules in slot order with their image-transfer costs, for the input and output scans.
  struct ScannedModule {
    Module* module;
    Nanoseconds input_cost;
    Nanoseconds output_cost;
  };
  std::vector<ScannedModule> scanned_;
  std::unique_ptr<Interpreter> interp_;
  std::unique_ptr<CoverageRecorder> coverage_;
  ScanObserver scan_observer_;
  // MSG: the network this controller is on (its own when it is the leader or alone), its station.
  std::unique_ptr<MessageNetwork> own_network_;
  MessageNetwork* network_ = nullptr;
  std::size_t station_ = 0;
  int node_ = 1;
  std::uint32_t ip_ = 0;

  Mode mode_ = Mode::Program;
  bool first_pass_ = false;
  bool single_scan_pending_ = false;
  std::optional<FaultInfo> fault_;
  ScanStats stats_;
  std::int64_t s4_tick_ = 0;  // tick count when S:4 was last advanced
  // Repeated scans: the program allows them (every instruction and operand, set by create), tools
  // allow them, scans left before the next probe and the wait after a probe that found a change
  // (none for the first three failures in a row, then doubling to 64, so a busy program pays for a
  // probe at most every 64 scans: probe_failed), the table saved
  // before the probe, and the time from a scan's start to its program scan (for S:4).
  bool program_repeatable_ = false;
  // The bits of the free-running clock S:4 the program reads (every bit when it reads the word):
  // repeats end before the scan in which one of them would change.
  std::uint16_t clock_bits_read_ = 0;
  bool skip_repeated_ = true;
  // The finest time base of the program's timers (1 ms with a MicroLogix 0.001 s timer, else the
  // 10 ms tick): a timing timer changes nothing while its reads stay in the tick it is stamped with.
  Nanoseconds timer_tick_ns_ = kTick;
  // Timers accumulating across ticks (docs/semantics.md "Timers accumulating across ticks"): for each
  // word of the table, 1 at the control word of a timer element whose control word and ACC no
  // instruction but its own TON/TOF/RTO (and RES) can reach, bits EN, TT and DN and PRE read aside
  // (set by create); the probe's record of its timer executions; and the timers the repeats carry.
  std::vector<std::uint8_t> timer_private_;
  std::vector<word_ops::TimerExecution> timer_executions_;
  struct AccumulatingTimer {
    std::uint32_t word;      // the control word; ACC is word + 2
    VirtualTime read_at;     // when the probe's execution read the tick
    Nanoseconds unit;        // 10 ms, or 1 ms for the 0.001 s base
    std::int64_t stamp0;     // the tick the probe left the stamp at, unwrapped
    std::int64_t units_per_acc;  // ticks per ACC count: 100 for the 1.0 s base, else 1
    std::int32_t acc0;       // ACC after the probe
  };
  std::vector<AccumulatingTimer> accumulating_;
  // Sorts the probe's timer executions: fills accumulating_ with the timers that may accumulate across
  // ticks, sets their ACC and stamp in before_probe_ to the probe's, and returns whether any timer read
  // the clock otherwise, which bounds the repeats to the tick.
  // A cycle (probe_cycle) passes its two scans' executions with `second` the index of the first of the
  // second scan's and `d` the cycle's length: a timer is then carried when it ran once in each scan.
  bool sort_timer_executions(Nanoseconds d, std::size_t second = 0);
  // Writes the carried timers' ACC and stamp as `n` scans after the probe, each `d` long, leave them.
  void set_accumulated_timers(std::int64_t n, Nanoseconds d);
  // Counted words carried across repeats (docs/semantics.md "Counted words carried across repeats"):
  // the program's counted words (set by create, by word), and those a probe found counting, which the
  // repeats advance by their step.
  std::vector<CountedWord> counted_words_;
  struct CarriedCount {
    std::uint32_t word;
    std::int64_t after;  // the value the probe left
    std::int64_t step;   // per scan
  };
  std::vector<CarriedCount> counting_;
  // Finds the counted words the probe advanced by their step with nothing else moving them, sets them
  // in before_probe_ to the probe's value (carried_before_ keeps the saved one), fills counting_, and
  // returns how many scans after the probe may repeat before one would compare, flag or overflow
  // otherwise (the maximum of int64 when none is carried).
  std::int64_t sort_counted_words();
  // Writes the carried counted words as `n` scans after the probe leave them.
  void set_counted_words(std::int64_t n);
  std::uint32_t probe_wait_ = 0;
  std::uint32_t probe_backoff_ = 1;
  std::uint32_t probe_failures_ = 0;  // probes in a row that repeated nothing (probe_failed)
  static constexpr std::uint32_t kProbesBeforeBackoff = 4;
  std::vector<std::uint16_t> before_probe_;
  // The words of before_probe_ that sort_timer_executions replaced with a carried timer's (word, value as
  // saved), for a cycle that compares with the table as the probe found it; the network's holdings before
  // the probe and after a cycle (MessageNetwork::holdings); a cycle may be tried: no channel whose state
  // lies outside the table (ASCII, Modbus), no data log queue, no read of S:4 (set by create).
  std::vector<std::pair<std::uint32_t, std::uint16_t>> carried_before_;
  std::vector<std::uint64_t> net_before_probe_, net_after_cycle_;
  // The last probe that left nothing outside the table to follow (repeat_remembered): the table it left,
  // its repeats' basis, its input scan's time and the runtime's own status words (sorted indexes), which
  // the comparison leaves out. The MSG starts and aborts the scans made (their effect depends on the
  // network, not the table alone), counted so that a probe can tell it made none.
  struct SteadyScan {
    bool valid = false;
    std::vector<std::uint16_t> table;
    RepeatBasis basis;
    Nanoseconds input_scan_ns = 0;
    std::array<std::uint32_t, 6> runtime_words{};
  };
  SteadyScan steady_;
  std::uint64_t message_calls_ = 0;
  bool cycles_allowed_ = false;
  Nanoseconds input_scan_ns_ = 0;
  std::size_t events_at_last_scan_end_ = 0;  // events the last scan cycle ran at its end
  // What a probe did with the modules (docs/semantics.md "Repeated scans"): the modules it reached
  // through M0/M1 or an instruction, each with its Module::program_changes() before the first
  // access; the M0/M1 words it read and what it read, and those it wrote with the value; whether
  // a module it reached cannot say (no count); each
  // module's input image at its input scan (slot order, as scanned_); and the data-table words
  // field processes changed (ProcessHost::write_word), which an event between repeats must leave
  // alone.
  struct ReachedModule {
    Module* module;
    std::uint64_t changes;
  };
  struct MRead {
    int slot;
    MFile file;
    int word;
    std::uint16_t value;
  };
  bool probing_ = false;
  bool probe_unsteady_ = false;
  std::vector<ReachedModule> reached_;
  std::vector<MRead> m_reads_, m_writes_;
  std::vector<std::uint16_t> probe_inputs_;
  std::vector<std::uint16_t> inputs_scratch_;
  std::uint64_t process_writes_ = 0;
  std::int64_t rtc_second_ = 0;  // whole seconds of virtual time when the RTC was last advanced
  // A module fault raised while modules are being told of a mode change waits here until every
  // module has seen the change.
  bool notifying_ = false;
  std::optional<FaultInfo> pending_module_fault_;

  // Forces, per word of the I and O images: which bits are forced and to what.
  std::vector<std::uint16_t> in_force_mask_, in_force_value_;
  std::vector<std::uint16_t> out_force_mask_, out_force_value_;
  bool forces_enabled_ = true;
  // Some input (output) bit is forced and forces are enabled; kept by write_mode_bits().
  bool in_forces_live_ = false;
  bool out_forces_live_ = false;
  // What the output scan last delivered to each module (IOM merges into it).
  std::vector<std::uint16_t> out_sent_;
  std::vector<std::uint16_t> io_scratch_;
};

}  // namespace softslc
