// The interpreter: executes the program scan of a CompiledProgram against a DataTable.
//
// Design. One function, Interpreter::program_scan, holds the dispatch loop: a plain `switch` on
// the op byte of each header word, one case per Op (the compiler warns, via -Wswitch, if an
// instruction-table opcode has no case). The loop's state lives in locals: the program counter,
// the rung condition, the branch stack, the call stack and the scan time so far. Direct operands
// are data-table word indices, so a bit instruction is a load, a shift and an AND; nothing on
// that path allocates, calls through a pointer or looks anything up. Long handlers (timers,
// math, file instructions) are ordinary member functions called directly, kept out of line.
//
// Fast path. In front of the general switch sits a small switch over the ops most ladder is made
// of (XIC, XIO, OTE with direct bits; BST, NXB, BND). It keeps only the program counter, the rung
// condition, the scan time and the branch-stack index live, so the compiler holds them in
// registers; anything else drops to the general switch, whose cases implement every op
// (including these, for run-time-resolved operands). Measured with tests/benchmarks/vm_bench:
// the general switch alone kept the rung condition in memory and ran about 6 ns per bit
// instruction; with the fast path about 2.4 ns (docs/bytecode.md, "Performance"). After a
// general-switch op the next op is dispatched there directly unless the fast path runs it (and
// always with coverage), so a TON or MOV is not switched on twice.
//
// Fused rungs. Runs of contact-network rungs, and of contacts and compares ending in TON/TOF/RTO, CTU/CTD,
// RES, MOV, ADD or SUB on direct words, are handed at their first SOR to a FusedProgram (vm/fused.h, built
// once), which runs them as gathered bits, table lookups and the handlers' own word code (vm/word_ops.h) with
// the same results, scan time and counts; a rung it hands back runs here unfused. Coverage keeps the general path.
//
// Run-time addresses (indexed, indirect, M0/M1) go through resolve(), the one checked path: it
// either yields an index inside the data table (or a module word) or records a major fault
// (0029h/002Ah/xx55h) and yields a harmless scratch location. Instructions with such operands
// carry the DYN flag and the loop checks for a recorded fault after them, so a faulting
// instruction never writes outside the table and the scan stops at that rung.
//
// Virtual time. Each executed instruction adds its cost (from the ScanTimeModel, tabulated once)
// to the scan time. Timers read the 10 ms tick count at the current virtual time
// (scan start + scan time so far); every rung start compares the scan time with limit_, which is
// the watchdog (S:3 high byte) or, sooner, the next selectable timed interrupt (vm/interrupts.cpp:
// interrupt routines run recursively through run_routine from a rung start), so an endless JMP
// loop ends in fault 0022h after the watchdog's worth of virtual time.
//
// Invariants: the branch stack and call stack are fixed arrays bounded by kMaxBranchDepth and
// the processor's nesting limit (checked before every push); the program counter only takes
// values the compiler produced (headers, jump targets, file starts).
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "vm/ascii.h"
#include "vm/bytecode.h"
#include "vm/data_table.h"
#include "vm/faults.h"
#include "vm/ml_data_log.h"
#include "vm/ml_pto.h"
#include "vm/ml_hsc.h"
#include "vm/module.h"
#include "vm/scan_time_model.h"

namespace softslc {

namespace word_ops {
struct TimerExecution;
}

// What the interpreter needs from the chassis mid-scan: M0/M1 immediate access and the
// immediate I/O instructions. The runtime implements it; it is only reached from M-file
// operands and IIM/IOM, never from the bit-logic path.
struct MessageInstruction;

class ChassisAccess {
 public:
  virtual ~ChassisAccess() = default;
  virtual MAccess read_m(int slot, MFile f, int word, std::uint16_t& value) = 0;
  virtual MAccess write_m(int slot, MFile f, int word, std::uint16_t value) = 0;
  // read_m of words word .. word + out.size() - 1 in order, stopping at the first that is refused:
  // `done` is how many were read. One call instead of one per word (the runtime finds the module
  // once); the default reads them one by one.
  virtual MAccess read_m_block(int slot, MFile f, int word, std::span<std::uint16_t> out, std::size_t& done) {
    for (done = 0; done < out.size(); ++done) {
      const MAccess a = read_m(slot, f, word + static_cast<int>(done), out[done]);
      if (a != MAccess::Ok) return a;
    }
    return MAccess::Ok;
  }
  // The module's reason for refusing an access (Module::m_refusal); empty when it gives none.
  virtual std::string m_refusal(int /*slot*/, MFile, int /*word*/, bool /*write*/) const { return {}; }
  // IIM: copy `count` input words of `slot` from word `first` into the I file under `mask`.
  virtual void immediate_input(int slot, int first, int count, std::uint16_t mask) = 0;
  // IOM: send `count` O-file words of `slot` from word `first` to the module under `mask`.
  virtual void immediate_output(int slot, int first, int count, std::uint16_t mask) = 0;
  // REF at virtual time `at`: an output scan, the communications servicing of every channel, then an
  // input scan, in the middle of the program scan. Returns the virtual time the two scans took. The
  // default does nothing and takes no time (no chassis).
  virtual Nanoseconds io_refresh(VirtualTime /*at*/) { return 0; }
  // A specialty-module instruction (BTR, BTW, DEM) addressed to the module in `slot`. The default
  // faults: there is no module to execute it.
  virtual void module_instruction(int slot, ModuleInstructionContext& ctx);
  // Whether `slot` holds a discrete input card (the DII's S:47, RM 11-18); the default
  // has no chassis.
  virtual bool discrete_input_card(int /*slot*/) const { return false; }
  // The ISR for the module in `slot` completed, or an RPI reset its request (RM 11-27 step 3).
  virtual void interrupt_serviced(int /*slot*/) {}
  // MSG and SVC (vm/message_network.h): a MSG rung starts a message (its EN was 0), a MSG's TO bit
  // aborts the one in progress, SVC services the channels in `channels` (bit 0 channel 0, bit 1
  // channel 1) at virtual time `at`. The defaults do nothing: no network.
  virtual void message_start(const MessageInstruction& /*m*/) {}
  virtual void message_abort(std::uint32_t /*block*/) {}
  virtual void service_communications(std::uint16_t /*channels*/, VirtualTime /*at*/) {}
};

struct ProgramScanResult {
  bool faulted = false;
  FaultInfo fault;
  Nanoseconds elapsed = 0;         // scan time at the end of the program scan
  std::uint64_t instructions = 0;  // instruction-table instructions executed
  int last_file = 2;
  int last_rung = -1;
  // A true SUS stopped the scan (S:7 and S:8 written): the processor enters Suspend Idle.
  bool suspended = false;
  // The scan time at which the watchdog count last restarted (0, or the end of the last REF):
  // the runtime measures its end-of-scan watchdog check from here (RM B-19).
  Nanoseconds watchdog_from = 0;
};

// The selectable timed interrupt as the interpreter keeps it between scans (RM 11-8 to 11-16).
// S:30/S:31 (or the MicroLogix STI function file) are the program's view; this is the timer.
struct StiTimer {
  int file = 0;                  // the STI program file, 0 = not running
  Nanoseconds period = 0;        // time between expiries
  Nanoseconds next_period = 0;   // a changed setpoint, applied at the next expiry (RM 11-12)
  VirtualTime due = 0;           // the next expiry, when file != 0
  std::uint16_t setpoint = 0;    // the S:30 (or .SPM) value the period was made from
  std::uint64_t runs = 0;        // STI routine executions since the runtime was created

  bool operator==(const StiTimer&) const = default;
};

// The discrete input interrupt as the interpreter keeps it (RM 11-18 .. 11-26): the
// configuration last applied from S:46-S:50 (at the end of a scan, a DII routine's exit, entry to
// Run) and what the last interrupt did. S:2/11-13, S:51 and S:52 are the program's view.
struct DiiState {
  int file = 0;                 // S:46 applied; 0 = off
  int slot = 0;                 // S:47
  std::uint16_t mask = 0;       // S:48 bits 0-7
  std::uint16_t compare = 0;    // S:49 bits 0-7
  int preset = 0;               // S:50
  std::uint16_t return_mask = 0;  // S:51 for the pending interrupt
  VirtualTime requested_at = 0;   // the input transition that generated the pending interrupt
  Nanoseconds last_latency = 0;   // from that transition to the routine's first rung
  std::uint64_t runs = 0;         // DII routine executions since the runtime was created
  // S:46-S:50 as last applied with a DII configured (file != 0): applying the same words again
  // changes nothing, so apply_dii_config skips them (docs/performance.md, session 19).
  std::uint16_t applied[5] = {};
};

// A MicroLogix event interrupt as the interpreter keeps it: an EII:n (event input interrupt) or an
// HSC:n (high-speed counter interrupt) function-file element, whose first words are PFN, ER and the
// bit word with UIX/UIE/UIL/UIP/ED at the STI's positions (eii::, hsc:: in parser/address.h). What
// waits is counted here: "1 active and ... up to 2 pending" before the lost bit (1763-RM001C p. 275).
struct EventInterrupt {
  bool counter = false;          // HSC:n, else EII:n
  int number = 0;                // n
  std::uint32_t element = 0;     // data-table index of the element's first word (PFN)
  int priority = 0;              // vm/interrupts.cpp, 1762-RM001C p. 18-4
  int queued = 0;                // events waiting to run, 0-2
  std::uint64_t runs = 0;        // routine executions since the runtime was created
};

// Maximum call depth the interpreter's call stack holds (the processor's limit is at most 8).
inline constexpr int kMaxCallDepth = 16;

class ModuleCall;
class CoverageRecorder;
class AsciiPort;
class FusedProgram;

class Interpreter {
 public:
  Interpreter(const CompiledProgram& program, DataTable& table, ChassisAccess& chassis, const ScanTimeModel& model);

  // Runs the main program file once. `scan_start`: virtual time the scan began; `elapsed`: scan
  // time already used before the program scan (input scan); `first_pass`: the first scan after
  // entering Run/Test; `watchdog`: the scan time at which fault 0022h is raised.
  ProgramScanResult program_scan(VirtualTime scan_start, Nanoseconds elapsed, bool first_pass, Nanoseconds watchdog);

  // Attaches a coverage recorder (nullptr detaches). While one is attached the interpreter leaves
  // its bit-logic fast path and reports every instruction (vm/coverage.h); without one nothing
  // is recorded and the fast path is unchanged.
  void set_coverage(CoverageRecorder* recorder) { coverage_ = recorder; }

  // Channel 0 in User mode (vm/ascii_channel.h), or nullptr: the channel instructions (ABL ACB AHL
  // ARD ARL AWA AWT) then end with ER and error code 04h (not in User mode).
  void set_ascii_port(AsciiPort* port) { ascii_port_ = port; }

  // Fused rungs (vm/fused.h) are on by default; off, every rung takes the general path. The
  // result is the same either way; tests compare the two.
  void set_fusion(bool on) { fusion_ = on; }

  // The MicroLogix data log queues (DLG; vm/ml_data_log.h).
  DataLogs& data_logs() { return data_logs_; }
  const DataLogs& data_logs() const { return data_logs_; }
  std::uint16_t* words() { return w_; }

  // ---- Interrupts (docs/semantics.md "Program control and interrupts") ----
  // At the end of a program scan (and, with `entering_run`, before the first scan in Run): reads
  // S:30/S:31/S:2/10 and starts, changes or stops the STI timer as RM 11-12 says. Returns false
  // with fault() set (0023h, 0024h) when the configuration is invalid.
  bool configure_sti(VirtualTime now, bool entering_run);
  // Runs every STI that is due by scan time `elapsed` of the scan that started at `scan_start`
  // (expiries during the output scan and housekeeping). Returns the new scan time; a fault in
  // the routine is reported in the result like a program-scan fault.
  ProgramScanResult service_interrupts_between(VirtualTime scan_start, Nanoseconds elapsed, Nanoseconds watchdog);
  // Leaving Run/Test: the STI timer stops and S:2/0, S:2/2 are cleared (RM 11-12, 11-13); so do the
  // DII (S:2/11, S:2/13) and the I/O interrupt requests.
  void stop_interrupts();
  // At the end of a program scan (and with `entering_run` before the first one): applies
  // S:46-S:50 (RM 11-24). Returns false with last_fault() set (0042h, 0043h) when they are invalid.
  bool configure_dii(bool entering_run);
  // A field input word of the card in `slot` changed at `at` (between scans, in Run): counts towards
  // the DII preset and, at the preset, makes the DII pending (it runs at the next rung start).
  void dii_input(int slot, int word, std::uint16_t before, std::uint16_t after, VirtualTime at);
  // The module in `slot` requests its I/O interrupt (between scans, in Run; RM 11-27).
  void io_interrupt_request(int slot);
  // The MicroLogix event input interrupts: the embedded input word I:0.0 (slot 0, word 0) changed at
  // the terminals (between scans, in Run). Each EII whose EIE is set and whose IS bit saw its edge
  // (ES) gets an event; the routine runs at the next rung start (docs/semantics.md "The EII function file").
  void event_input(int slot, int word, std::uint16_t before, std::uint16_t after);
  // The EII:n or HSC:n interrupt (nullptr when the processor has none), for tests and tools.
  const EventInterrupt* event_interrupt(bool counter, int number) const;
  const DiiState& dii() const { return dii_; }
  std::uint64_t isr_runs() const { return isr_runs_; }
  // Interrupt routines (STI, DII, I/O event, EII, HSC) and fault routines run since the runtime was
  // created: a probe that ran one is not repeated (docs/semantics.md "Repeated scans").
  std::uint64_t routine_runs() const { return routine_runs_; }
  // How many times a module instruction asked the time of its execution
  // (ModuleInstructionContext::now): a repeated scan cannot stand for such an instruction past an
  // event (docs/semantics.md "Repeated scans").
  std::uint64_t module_time_reads() const { return module_time_reads_; }
  // How many times an event between scans changed a data-table word through the interpreter (an
  // EII whose IS names no input sets ED and ER at an input edge): the repeats across events stop
  // there, as they do for a field process's write (docs/semantics.md "Repeated scans").
  std::uint64_t between_scan_writes() const { return between_scan_writes_; }
  // The earliest pid::Outcome::same_until of the PIDs executed since the last reset: repeated
  // scans end before it (docs/semantics.md "Repeated scans").
  VirtualTime pid_same_until() const { return pid_same_until_; }
  void reset_pid_same_until() { pid_same_until_ = std::numeric_limits<VirtualTime>::max(); }
  // While set, every TON, TOF and RTO execution is appended to `v` (a probe's record: repeats across
  // timer ticks, docs/semantics.md "Timers accumulating across ticks"); nullptr stops it.
  void record_timer_executions(std::vector<word_ops::TimerExecution>* v) { timer_executions_ = v; }
  const StiTimer& sti() const { return sti_; }
  // The MicroLogix high-speed counters (vm/ml_hsc.h); no counters on a processor without them.
  MicroLogixHsc& hsc() { return hsc_; }
  const MicroLogixHsc& hsc() const { return hsc_; }
  // Nothing can run or become due between scans and at the next rung starts but an STI expiry at
  // its known time (sti().due): no STI expiry waiting, no DII or ISR, no EII or HSC interrupt
  // queued, no HSC pulses arriving, no PTO running (an ASCII port acts in its events). One of the
  // conditions under which the runtime may skip scans that repeat the last one (docs/semantics.md
  // "Repeated scans").
  bool nothing_pending_between_scans() const;
  // The fault configure_sti raised.
  const FaultInfo& last_fault() const { return fault_; }

  // The cost table (ns) indexed by op * 2 + rung-in.
  const std::vector<Nanoseconds>& costs() const { return cost_; }
  // Per-word charges of the file instructions, by opcode (ScanTimeModel::per_word_cost).
  const Nanoseconds* per_word_costs() const { return per_word_.data(); }

  // Resolves a run-time operand for tools (Runtime::get/set of indexed/indirect addresses).
  // Returns false with `message` when it would leave the data table.
  bool resolve_for_tool(const DynOperand& d, Location& out, std::string& message);

 private:
  struct Ref {
    std::uint32_t word = 0;  // data-table index (or M-file word when mfile)
    int bit = -1;
    int file = -1;
    bool mfile = false;
    int slot = 0;
    MFile which = MFile::M0;
  };
  struct Span {
    std::uint32_t base = 0;  // first data-table word (or first M-file word)
    std::uint32_t count = 0;
    bool mfile = false;
    MFileAccess row = MFileAccess::OtherM;
    int slot = 0;
    MFile which = MFile::M0;
    ValueType vtype = ValueType::Int16;
    std::uint32_t wpe = 1;
  };

  // Fault recording: the first fault of a scan wins.
  [[gnu::noinline, gnu::cold]] void raise(std::uint16_t code, std::string message);
  // "module refused (no such word)", plus the module's reason when it gives one.
  [[gnu::noinline, gnu::cold]] std::string refused(MAccess a, int slot, MFile f, int word, bool write) const;

  // An M0/M1 operand's Ref (slot, file, word, bit), for resolve and resolve_common.
  static void mfile_ref(const DynOperand& d, Ref& out);
  // The checked run-time resolver. Returns false (and raises) when the address leaves the table.
  bool resolve(const DynOperand& d, Ref& out);
  bool resolve_common(const DynOperand& d, Ref& out, std::uint16_t& code, std::string& message);

  // Operand access. The fast cases are inline in the .cpp; the *_slow functions take the DYN path.
  bool rd_bit(std::uint32_t o);
  void wr_bit(std::uint32_t o, bool v);
  [[gnu::noinline, gnu::cold]] bool rd_bit_slow(std::uint32_t o);
  [[gnu::noinline, gnu::cold]] void wr_bit_slow(std::uint32_t o, bool v);
  // Direct words and immediates inline; every other mode through the out-of-line *_slow.
  std::int64_t rd_int(std::uint32_t o) {
    if (bc::mode_of(o) == bc::kWord) [[likely]] return static_cast<std::int16_t>(w_[bc::payload_of(o)]);
    if (bc::mode_of(o) == bc::kImm) return bc::imm_of(o);
    return rd_int_slow(o);
  }
  [[gnu::noinline]] std::int64_t rd_int_slow(std::uint32_t o);
  float rd_flt(std::uint32_t o);
  std::uint16_t rd_word(std::uint32_t o);
  void wr_word(std::uint32_t o, std::uint16_t v) {
    if (bc::mode_of(o) == bc::kWord) [[likely]] w_[bc::payload_of(o)] = v;
    else wr_word_slow(o, v);
  }
  [[gnu::noinline]] void wr_word_slow(std::uint32_t o, std::uint16_t v);
  ValueType dest_type(std::uint32_t o) const;
  std::uint16_t* element(std::uint32_t o);
  // Stores an integer-domain result with the S:2/14 overflow rule; returns the value stored.
  std::int64_t st_int(std::uint32_t o, std::int64_t v, bool& overflow);
  // Stores raw bits (logical instructions): truncation to the destination width, no overflow.
  std::int64_t st_bits(std::uint32_t o, std::int64_t v);
  // Stores a float-domain result (float destination, or rounding/saturating into an integer).
  double st_flt(std::uint32_t o, float v, bool& overflow);
  void set_flags(bool c, bool v, bool z, bool s);
  bool file_span(std::uint32_t o, std::uint32_t elements, Span& out, std::string_view what);
  std::uint16_t span_get(const Span& s, std::uint32_t i);
  // span_get's fault for word i of an M-file span that the module refused.
  [[gnu::noinline, gnu::cold]] void m_read_refused(const Span& s, std::uint32_t i, MAccess a);
  void span_set(const Span& s, std::uint32_t i, std::uint16_t v);

  // Instruction handlers that are too long to inline in the dispatch loop. They are kept out of
  // line on purpose: inlined, they made the compiler spill the loop's hot registers.
#define SOFTSLC_HANDLER [[gnu::noinline]]
  SOFTSLC_HANDLER bool timer(Op op, const std::uint32_t* o, std::uint32_t h, bool rung, Nanoseconds now_in_scan);
  SOFTSLC_HANDLER void counter(Op op, const std::uint32_t* o, bool rung);
  SOFTSLC_HANDLER void reset(const std::uint32_t* o, std::uint32_t h);
  SOFTSLC_HANDLER bool compare(Op op, const std::uint32_t* o, std::uint32_t h);
  SOFTSLC_HANDLER void math(Op op, const std::uint32_t* o, std::uint32_t h);
  SOFTSLC_HANDLER void unary(Op op, const std::uint32_t* o, std::uint32_t h);
  SOFTSLC_HANDLER void logical(Op op, const std::uint32_t* o);
  // Issue 15: DDV; SQR, ABS and the float functions (LN ... RAD, XPY); SCL and SCP; TOD, FRD, DCD, ENC.
  SOFTSLC_HANDLER void double_divide(const std::uint32_t* o);
  SOFTSLC_HANDLER void function(Op op, const std::uint32_t* o, std::uint32_t h);
  SOFTSLC_HANDLER void scale(Op op, const std::uint32_t* o, std::uint32_t h);
  SOFTSLC_HANDLER void convert(Op op, const std::uint32_t* o);
  SOFTSLC_HANDLER void compute(const std::uint32_t* o);
  SOFTSLC_HANDLER void move(Op op, const std::uint32_t* o, std::uint32_t h);
  SOFTSLC_HANDLER void copy_file(const std::uint32_t* o, std::uint32_t h);
  SOFTSLC_HANDLER void copy_words(const std::uint32_t* o);
  SOFTSLC_HANDLER void swap_bytes(const std::uint32_t* o);
  SOFTSLC_HANDLER void free_running_clock(Op op, const std::uint32_t* o, Nanoseconds now_in_scan);
  SOFTSLC_HANDLER void message(Op op, const std::uint32_t* o, bool rung, Nanoseconds now_in_scan);
  SOFTSLC_HANDLER void micrologix_message(const std::uint32_t* o, bool rung, Nanoseconds now_in_scan);
  SOFTSLC_HANDLER void fill_file(const std::uint32_t* o, std::uint32_t h);
  SOFTSLC_HANDLER void bit_shift(Op op, const std::uint32_t* o, bool rung);
  SOFTSLC_HANDLER void sequencer(Op op, const std::uint32_t* o, bool rung);
  SOFTSLC_HANDLER void stack(Op op, const std::uint32_t* o, bool rung);
  // BTR, BTW, DEM: resolves the operands and hands the instruction to the module in the slot the
  // compiler recorded in the header's aux field (ChassisAccess::module_instruction).
  SOFTSLC_HANDLER void module_instruction(Op op, const std::uint32_t* o, std::uint32_t h, bool rung,
                                          Nanoseconds now_in_scan);
  // PID (1747-RM001G ch. 9): the control block's 23 words go to pid::execute (vm/pid.h); an invalid
  // parameter is major fault 0036h. Returns false when it faulted.
  SOFTSLC_HANDLER bool pid(const std::uint32_t* o, bool rung, Nanoseconds now_in_scan);
  // ASCII and strings (1747-RM001G ch. 10; vm/ascii.h, vm/ascii_channel.h). The string instructions
  // run on every true scan; a length outside 0-82 sets S:5/15. ASR returns the rung.
  SOFTSLC_HANDLER void string_instruction(Op op, const std::uint32_t* o);
  SOFTSLC_HANDLER bool string_compare(const std::uint32_t* o);
  // The channel instructions: EN follows the rung, a false-to-true rung queues the instruction on
  // the ASCII port, EM is set when the instruction is scanned with DN or ER set.
  SOFTSLC_HANDLER void channel_instruction(Op op, const std::uint32_t* o, bool rung, Nanoseconds now_in_scan);
  SOFTSLC_HANDLER void ascii_clear(const std::uint32_t* o, Nanoseconds now_in_scan);
  // Reads (or writes) the ST element operand `o`; false (S:5/15 set for a bad length) when unusable.
  bool read_string(std::uint32_t o, ascii::Text& out, const char* what);
  bool string_words(std::uint32_t o, std::uint16_t*& words, const char* what);
  void ascii_error();
  // STS: S:31/S:30 (or the STI function file) := file/time, enable, restart the timer from now.
  SOFTSLC_HANDLER void sti_start(const std::uint32_t* o, Nanoseconds now_in_scan);
  // The MicroLogix STS (time only): STI:0.SPM := time, TIE := 1, the timer restarts from now; time 0
  // stops the STI and clears TIE.
  SOFTSLC_HANDLER void function_file_sti_start(const std::uint32_t* o, Nanoseconds now_in_scan);
  // HSL and RAC on the MicroLogix high-speed counters (vm/ml_hsc.h).
  SOFTSLC_HANDLER void high_speed_counter(Op op, const std::uint32_t* o, Nanoseconds now_in_scan);
  // IID, IIE, RPI (RM 11-33, B-43) on S:25-S:28; FBC, DDT (RM 7-18 .. 7-22).
  SOFTSLC_HANDLER void io_interrupt_control(Op op, const std::uint32_t* o, Nanoseconds now_in_scan);
  SOFTSLC_HANDLER void bit_compare(Op op, const std::uint32_t* o, bool rung);

  // The dispatch loop: runs program file `file` from its first rung until it ends (END, EOF, TND,
  // or RET at its own level) or faults. Interrupt routines run through it recursively from a
  // rung start. Returns false on a fault (fault_ located) or a SUS (suspended_).
  bool run_routine(int file, Nanoseconds& elapsed, int max_depth);
  // Per-pass state for a program scan or a between-scans interrupt pass, and its result.
  void begin_pass(VirtualTime scan_start, Nanoseconds watchdog);
  ProgramScanResult pass_result(bool ok, Nanoseconds elapsed) const;
  // Rung-start hook, reached only when the scan time has passed limit_: raises the watchdog fault,
  // or takes the STI expiries due by now and runs the STI routine when it may run.
  [[gnu::noinline, gnu::cold]] bool at_limit(Nanoseconds& elapsed);
  bool service_interrupts(Nanoseconds& elapsed);
  bool run_sti(Nanoseconds& elapsed);
  // The MicroLogix EII and HSC interrupts (vm/interrupts.cpp): set up once by the constructor, in
  // priority order, highest first.
  void locate_event_interrupts();
  // Entering Run: nothing waits or runs; AS sets an EII's EIE [U]. Leaving Run: nothing waits.
  void reset_event_interrupts(bool entering_run);
  // An event of `e`: one more waits (UIP), or the lost bit UIL when two already wait.
  void queue_event(EventInterrupt& e, int events);
  // The HSC events of the last counter update (vm/ml_hsc.h) become HSC interrupts.
  void collect_counter_events();
  // The element's PFN when it names a subroutine file; otherwise sets ED and ER 1 and returns 0.
  int event_program(EventInterrupt& e);
  bool event_runnable(const EventInterrupt& e) const;
  bool run_event(EventInterrupt& e, Nanoseconds& elapsed);
  // the DII and the I/O event interrupt, and the priorities of RM 11-30 (an interrupt
  // runs only inside a routine of lower priority: fault routine > DII > STI > ISR > main program).
  bool sti_runnable() const;
  bool dii_runnable() const;
  int runnable_isr_slot() const;  // the lowest requesting slot that may run now, 0 = none
  bool run_dii(Nanoseconds& elapsed);
  bool run_isr(int slot, Nanoseconds& elapsed);
  // chassis_.discrete_input_card(slot), 1 <= slot <= 30, asked once per slot (dii_card_).
  bool discrete_input_card(int slot);
  bool apply_dii_config();
  bool io_enabled(int slot) const;
  // Forgets slot's request and answers its module (RPI, leaving Run).
  void drop_io_request(int slot);
  void set_io_pending(int slot, bool on);
  // Runs `file` as an interrupt routine of `priority`, charged as a true JSR and RET, with S:0,
  // S:13, S:14 and S:24 saved and restored (STI, DII, ISR).
  bool run_interrupt_routine(int file, int priority, Nanoseconds& elapsed);
  void sti_expire();
  // Where the STI's pending/enabled/executing bits live (set once by the constructor): S:2/0-2 on
  // the SLC, STI:0's UIP/UIE/UIX on a MicroLogix with the STI function file.
  void locate_sti_bits();
  // configure_sti for the MicroLogix STI function file (STI:0 .PFN .SPM /TIE /AS, ED and .ER).
  bool configure_function_file_sti(VirtualTime now, bool entering_run);
  // STI:0.PFN when it names a subroutine file; otherwise sets ED and ER 1 and raises fault 0023h.
  int function_file_sti_program(const char* when);
  // limit_ := the scan time of the next thing a rung start must look at (watchdog, STI expiry).
  void update_limit(Nanoseconds elapsed);
  Nanoseconds sti_period(std::int64_t setpoint) const;
  // A fault raised in a routine: runs the user fault routine (S:29) once. True when the fault
  // was recoverable and the routine cleared S:1/13, so the scan goes on.
  bool user_fault_routine(Nanoseconds& elapsed);
  // Saved and restored around an interrupt or fault routine (PT1 30-3; RM B-5, B-43).
  struct SavedStatus {
    std::uint16_t s0, s13, s14, s24;
  };
  SavedStatus save_status() const;
  void restore_status(const SavedStatus& s);
  friend class ModuleCall;

  // Virtual time spent on the slow paths (M0/M1 accesses, file-instruction words); folded into
  // the scan time after the instruction.
  void charge_m(MFileAccess row, int words) { extra_ns_ += model_.mfile_access_cost(row, words); }
  std::uint32_t message_words(std::uint32_t data, std::uint16_t elements) const;
  void charge_words(Op op, std::uint32_t words) {
    extra_ns_ += per_word_[static_cast<std::size_t>(op)] * static_cast<Nanoseconds>(words);
  }
  // The rung went false to true at `op` (ScanTimeModel::transition_cost): its transition figure less the
  // true one already charged, and its words; `variant` is its first keyword operand's code.
  void charge_transition(Op op, int variant, std::uint32_t words) {
    const auto& t = transition_[static_cast<std::size_t>(op)][static_cast<std::size_t>(variant < 0 ? 0 : variant > 3 ? 3 : variant)];
    extra_ns_ += t.ns + t.per_word_ns * static_cast<Nanoseconds>(words);
  }

  const CompiledProgram& prog_;
  DataTable& table_;
  ChassisAccess& chassis_;
  const ScanTimeModel& model_;
  std::array<Nanoseconds, kInstructionCount> per_word_{};
  // By opcode and keyword variant (0-3): ScanTimeModel::transition_cost.
  std::array<std::array<ScanTimeModel::TransitionCost, 4>, kInstructionCount> transition_{};
  // By SVC channel select (1-3) and rung state: the select's own figure less SVC's table cost.
  std::array<std::array<Nanoseconds, 2>, 4> svc_select_extra_{};
  Nanoseconds extra_ns_ = 0;
  std::uint16_t* w_;
  // The MicroLogix pulse train outputs (PTO/PTOX function file), scanned by the PTO/PTOX handler.
  PulseTrainOutputs pulse_trains_;
  // The MicroLogix data log queues (DLG, DLS0:q), in battery-backed memory outside the data table.
  DataLogs data_logs_;
  const std::uint32_t* code_;
  std::vector<Nanoseconds> cost_;
  std::array<std::uint8_t, kOpCount> countable_{};
  int max_depth_;
  std::uint32_t s0_, s2_, s5_, s13_, s14_, s24_;
  // Interrupt status words (the status file always has S:0-S:35); S:36 is absent (-1) on the
  // processors whose status file stops before it.
  std::uint32_t s1_, s6_, s7_, s8_, s29_, s30_, s31_;
  std::int64_t s36_ = -1;
  CoverageRecorder* coverage_ = nullptr;
  AsciiPort* ascii_port_ = nullptr;
  // Whole rungs of direct-bit logic, built once from the program and the cost table.
  std::shared_ptr<const FusedProgram> fused_;
  bool fusion_ = true;

  // Per-scan state used by the handlers.
  VirtualTime scan_start_ = 0;
  bool first_pass_ = false;
  bool faulted_ = false;
  std::uint64_t count_ = 0;  // instructions executed this scan
  FaultInfo fault_;
  // Forgets the fault of the last pass. fault_ is written only after raise(), which gives it a
  // code, so a pass that raised nothing leaves nothing to reset (resetting its string at every
  // pass and configure step was a cost on every scan: docs/performance.md).
  void clear_fault() {
    faulted_ = false;
    if (fault_.code != 0) fault_ = {};
  }
  // The fault has been located (file, rung) and offered to the user fault routine; outer
  // routines only pass it on.
  bool fault_located_ = false;
  bool suspended_ = false;
  // Rung starts look at interrupts and the watchdog only when the scan time reaches limit_.
  Nanoseconds limit_ = 0;
  Nanoseconds watchdog_ = 0;       // the scan time at which fault 0022h is raised
  Nanoseconds watchdog_span_ = 0;  // S:3 high byte in ns (REF restarts the count from here)
  Nanoseconds watchdog_from_ = 0;
  int interrupt_level_ = 0;        // 0 in the main program; > 0 inside an STI or fault routine
  bool in_fault_routine_ = false;
  bool sti_ms_units_ = false;      // S:2/10 latched on entry to Run (RM 11-13)
  StiTimer sti_;
  MicroLogixHsc hsc_;
  // The STI's program view (locate_sti_bits): the word holding its pending, enabled and executing
  // bits, and on a MicroLogix the STI function file's first word (-1 on the SLC).
  std::uint32_t sti_bits_ = 0;
  std::uint16_t sti_pending_ = 0, sti_enabled_ = 0, sti_executing_ = 0;
  std::int64_t sti_file_word_ = -1;
  int sti_queued_ = 0;             // MicroLogix: expiries waiting to run, at most 2 (1763-RM001C p. 270)
  std::array<EventInterrupt, eii::kMaxElements + 6> events_{};  // EII:n and HSC:n, highest priority first
  int event_count_ = 0;
  int events_queued_ = 0;          // the sum of events_[].queued: rung starts look while it is not 0
  // The priority of the routine running now (kPriority* in vm/interrupts.cpp).
  int priority_ = 0;
  DiiState dii_;
  bool dii_supported_ = false;     // the status file has S:46-S:52 (SLC 5/03-5/05)
  // The chassis' answers to discrete_input_card, per slot (bit n: slot n), asked once each: the
  // DII's configuration is applied at every end of scan (RM 11-24), and the answer depends only on
  // the chassis, which does not change while the runtime exists.
  std::uint32_t dii_card_asked_ = 0;
  std::uint32_t dii_card_ = 0;
  bool io_supported_ = false;      // the processor has the I/O event interrupt (SLC 5/02-5/05)
  bool indirect_bit_runs_on_ = false;  // MicroLogix: N7:0/[N10:0] past bit 15 counts on into N7:1 ...
  bool any_isr_ = false;               // some slot has an ISR file (isr_file_, fixed at construction)
  std::uint32_t s25_ = 0, s27_ = 0, s32_ = 0, s46_ = 0;
  std::array<int, 31> isr_file_{};        // per slot, OPTION ISR (0 = none)
  std::array<bool, 31> io_requested_{};   // a module's request not yet serviced
  int io_requests_ = 0;                   // how many of io_requested_ are set
  std::uint64_t isr_runs_ = 0;
  std::uint64_t routine_runs_ = 0;  // interrupt and fault routine runs (routine_runs)
  std::uint64_t module_time_reads_ = 0;
  std::uint64_t between_scan_writes_ = 0;
  VirtualTime pid_same_until_ = std::numeric_limits<VirtualTime>::max();
  std::vector<word_ops::TimerExecution>* timer_executions_ = nullptr;
  int last_file_ = 2;
  int last_rung_ = -1;
  std::array<std::uint16_t, 64> scratch_{};  // where a faulting operand's access lands
#undef SOFTSLC_HANDLER
};

}  // namespace softslc
