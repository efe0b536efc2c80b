// Interrupts: the selectable timed interrupt (STI), STD/STE/STS and the user fault routine.
//
// Design. An interrupt routine is a program file run by the interpreter's own dispatch loop
// (Interpreter::run_routine), called recursively from a rung start of the routine it interrupts;
// the interrupted routine's locals (program counter, call and branch stacks, MCR state) simply
// wait on the C++ stack. Nothing is checked per instruction: every rung start already compares
// the scan time with the watchdog, and that compare now uses limit_, which is the watchdog or,
// sooner, the scan time of the next STI expiry (or "now" when a pending STI has just been enabled).
// With no STI armed limit_ is the watchdog and the hot path is what it was. Interrupts therefore
// start at rung boundaries, which is one of the points the SLC 5/03+ allows with S:33/8 clear
// (RM B-48: "at the start of each rung"); expiries during the I/O scan and housekeeping are run
// at the end of the scan cycle (Runtime::scan_once). Entry and exit are charged as a true JSR and
// a true RET of the processor's timing profile: that is the interrupt latency softslc models.
//
// State: the timer (StiTimer) lives here; the program's view is the status file: S:30 setpoint,
// S:31 file, S:2/0 pending, S:2/1 enabled, S:2/2 executing, S:5/10 overflow, S:36/9 lost
// (RM 11-12, 11-13). S:30/S:31 are read at the end of each scan (RM 11-12: a status-file change
// starts timing "from the end of the program scan in which the status registers were loaded");
// S:2/1 is read when the timer expires and when STE runs, which is the "takes effect upon the STI
// timer expiration or next end of scan" of RM 11-13.
#include <algorithm>
#include <string>

#include "vm/interpreter.h"

namespace softslc {

namespace {

bool slc_503_or_later(const ProcessorModel& p) {
  return p.family == ProcessorFamily::Slc503 || p.family == ProcessorFamily::Slc504 ||
         p.family == ProcessorFamily::Slc505;
}

// Recoverable user faults: the fault routine may clear them (RM 11-2, table 11.2). 0020h and 0034h
// are the manual's own example (RM 11-4); 0029h/002Ah (indirect or indexed address out of range)
// are softslc's reading of the same class (docs/semantics.md).
bool recoverable(std::uint16_t code) {
  return code == fault::kMinorErrorAtEnd || code == fault::kIndirectOutOfRange || code == fault::kIndexOutOfRange ||
         code == fault::kNegativeTimerValue;
}

// Faults that are not the user program's (a module's, softslc's own): the fault routine does not
// run for them (RM 11-2, table 11.2 "Non-User Fault").
bool non_user_fault(std::uint16_t code) { return code == fault::kUnsupportedInstruction || (code & 0xFF) == 0x55; }

}  // namespace

Interpreter::SavedStatus Interpreter::save_status() const { return {w_[s0_], w_[s13_], w_[s14_], w_[s24_]}; }

void Interpreter::restore_status(const SavedStatus& s) {
  // PT1 30-3 and RM B-5/B-43: the arithmetic flags, the math register and the index register
  // are put back when the interrupted program resumes.
  w_[s0_] = static_cast<std::uint16_t>((w_[s0_] & ~0x000Fu) | (s.s0 & 0x000Fu));
  w_[s13_] = s.s13;
  w_[s14_] = s.s14;
  w_[s24_] = s.s24;
}

Nanoseconds Interpreter::sti_period(std::int64_t setpoint) const {
  if (setpoint <= 0) return -1;
  const auto& p = prog_.processor;
  if (p.is_micrologix()) return setpoint * kNsPerMs;  // STI:0.SPM is in milliseconds
  if (!slc_503_or_later(p)) {
    // SLC 5/02: 1-255 in 10 ms units (RM 11-8, 11-12: "10 to 2550 ms").
    return setpoint <= 255 ? setpoint * 10 * kNsPerMs : -1;
  }
  // SLC 5/03 and later: 10 ms units, or 1 ms with S:2/10 (RM 11-12); at most 32,767 ms, and at
  // least 2 ms on the 5/03 (RM 11-8).
  const std::int64_t ms = sti_ms_units_ ? setpoint : setpoint * 10;
  if (ms > 32767) return -1;
  if (p.family == ProcessorFamily::Slc503 && ms < 2) return -1;
  return ms * kNsPerMs;
}

void Interpreter::update_limit(Nanoseconds elapsed) {
  Nanoseconds limit = watchdog_;
  if (sti_.file != 0) {
    const bool runnable = interrupt_level_ == 0 && (w_[s2_] & status::kStiPending) && (w_[s2_] & status::kStiEnabled);
    limit = std::min(limit, runnable ? elapsed : sti_.due - scan_start_);
  }
  limit_ = limit;
}

bool Interpreter::at_limit(Nanoseconds& elapsed) {
  if (elapsed >= watchdog_) {
    raise(fault::kWatchdog,
          "scan time reached the watchdog (S:3 high byte, " + std::to_string(watchdog_span_ / kTick) + " x 10 ms)");
    return false;
  }
  return service_interrupts(elapsed);
}

void Interpreter::sti_expire() {
  // RM 11-13: overflow S:5/10 when the timer expires while the routine runs or while an earlier
  // expiry still waits; S:36/9 (5/03+) when an expiry finds one pending: that interrupt is lost.
  if (w_[s2_] & status::kStiPending) {
    w_[s5_] = static_cast<std::uint16_t>(w_[s5_] | status::kStiOverflow);
    if (s36_ >= 0) w_[s36_] = static_cast<std::uint16_t>(w_[s36_] | status::kStiLost);
  } else if (w_[s2_] & status::kStiExecuting) {
    w_[s5_] = static_cast<std::uint16_t>(w_[s5_] | status::kStiOverflow);
  }
  w_[s2_] = static_cast<std::uint16_t>(w_[s2_] | status::kStiPending);
  // RM 11-12: a new setpoint takes effect once the previously configured STI has timed out. The
  // timer runs on from its own expiry, so the period does not drift with latency.
  if (sti_.next_period > 0) {
    sti_.period = sti_.next_period;
    sti_.next_period = 0;
  }
  sti_.due += sti_.period;
}

bool Interpreter::service_interrupts(Nanoseconds& elapsed) {
  for (;;) {
    const VirtualTime now = scan_start_ + elapsed;
    while (sti_.file != 0 && sti_.due <= now) sti_expire();
    if (interrupt_level_ == 0 && sti_.file != 0 && (w_[s2_] & status::kStiPending) &&
        (w_[s2_] & status::kStiEnabled)) {
      if (!run_sti(elapsed)) return false;
      continue;  // the timer may have expired again while the routine ran
    }
    break;
  }
  update_limit(elapsed);
  return true;
}

bool Interpreter::run_sti(Nanoseconds& elapsed) {
  // RM 11-12/11-13: starting the routine resets the pending bit and sets the executing bit.
  w_[s2_] = static_cast<std::uint16_t>((w_[s2_] & ~status::kStiPending) | status::kStiExecuting);
  const SavedStatus saved = save_status();
  elapsed += cost_[static_cast<std::size_t>(Op::JSR) * 2 + 1];  // entry, charged as a true JSR
  ++interrupt_level_;
  update_limit(elapsed);
  // RM 6-4 (facts §4): 3 levels of subroutines from inside an STI, DII, event or fault routine.
  const bool ok = run_routine(sti_.file, elapsed, std::min(3, max_depth_));
  --interrupt_level_;
  if (!ok) return false;
  elapsed += cost_[static_cast<std::size_t>(Op::RET) * 2 + 1];  // exit, charged as a true RET
  restore_status(saved);
  w_[s2_] = static_cast<std::uint16_t>(w_[s2_] & ~status::kStiExecuting);
  ++sti_.runs;
  return true;
}

bool Interpreter::configure_sti(VirtualTime now, bool entering_run) {
  faulted_ = false;
  fault_ = {};
  w_ = table_.words();
  if (entering_run) {
    // RM 11-12/11-13: pending and executing are cleared on entry to Run; S:2/10 is read on the
    // Program-to-Run transition; the timer starts from here.
    w_[s2_] = static_cast<std::uint16_t>(w_[s2_] & ~(status::kStiPending | status::kStiExecuting));
    sti_ms_units_ = slc_503_or_later(prog_.processor) && (w_[s2_] & status::kStiResolution);
    sti_ = StiTimer{0, 0, 0, 0, 0, sti_.runs};
  }
  const int file = static_cast<std::int16_t>(w_[s31_]);
  const int setpoint = static_cast<std::int16_t>(w_[s30_]);
  // S:30/S:31 are the STI's only on the processors that have the SLC's STI (RM 11-8: 5/02 and
  // later). The MicroLogix keep their STI in a function file; a saved MicroLogix status file can
  // hold other values there (an .RSS fixture has S:30 = 300, S:31 = 13), which must not arm it.
  if (!prog_.processor.supports(Requirement::TimedInterrupt) || file == 0 || setpoint == 0) {
    // RM 11-12: "A value of zero disables the STI function" (file or setpoint).
    sti_.file = 0;
    sti_.next_period = 0;
    return true;
  }
  if (file < 3 || file > 255 || !prog_.file(file)) {
    raise(fault::kInvalidStiFile, "S:31 names STI file " + std::to_string(file) +
                                      ", which is not a subroutine file of this program (3-255, RM 11-12)");
    return false;
  }
  const Nanoseconds period = sti_period(setpoint);
  if (period <= 0) {
    raise(fault::kInvalidStiSetpoint, "S:30 STI setpoint " + std::to_string(setpoint) + " is out of range for the " +
                                          prog_.processor.display_name + " (RM 11-8, 11-12)");
    return false;
  }
  if (sti_.file == 0) {
    sti_.period = period;
    sti_.next_period = 0;
    sti_.due = now + period;
  } else if (period != sti_.period) {
    sti_.next_period = period;
  } else {
    sti_.next_period = 0;
  }
  sti_.file = file;
  sti_.setpoint = static_cast<std::uint16_t>(setpoint);
  return true;
}

void Interpreter::stop_interrupts() {
  w_ = table_.words();
  sti_.file = 0;
  sti_.next_period = 0;
  w_[s2_] = static_cast<std::uint16_t>(w_[s2_] & ~(status::kStiPending | status::kStiExecuting));
}

ProgramScanResult Interpreter::service_interrupts_between(VirtualTime scan_start, Nanoseconds elapsed,
                                                          Nanoseconds watchdog) {
  begin_pass(scan_start, watchdog);
  update_limit(elapsed);
  bool ok = true;
  if (elapsed >= limit_ && elapsed < watchdog_) ok = service_interrupts(elapsed);
  return pass_result(ok, elapsed);
}

void Interpreter::sti_start(const std::uint32_t* o, Nanoseconds now_in_scan) {
  const int file = bc::imm_of(o[0]);
  const int time = bc::imm_of(o[1]);
  // RM 11-16: STS writes the file and setpoint, sets the enable bit, clears the pending bit and
  // restarts the timer at once; time 0 stops the STI.
  w_[s31_] = static_cast<std::uint16_t>(file);
  w_[s30_] = static_cast<std::uint16_t>(time);
  w_[s2_] = static_cast<std::uint16_t>((w_[s2_] | status::kStiEnabled) & ~status::kStiPending);
  if (time == 0) {
    sti_.file = 0;
  } else {
    const Nanoseconds period = sti_period(time);
    if (period <= 0) {
      raise(fault::kInvalidStiSetpoint, "STS time " + std::to_string(time) + " is out of range for the " +
                                            prog_.processor.display_name + " (RM 11-8, 11-16)");
      return;
    }
    sti_.file = file;
    sti_.period = period;
    sti_.next_period = 0;
    sti_.setpoint = static_cast<std::uint16_t>(time);
    sti_.due = scan_start_ + now_in_scan + period;
  }
  update_limit(now_in_scan);
}

bool Interpreter::user_fault_routine(Nanoseconds& elapsed) {
  if (in_fault_routine_ || suspended_) return false;
  const std::uint16_t code = fault_.code;
  if (non_user_fault(code)) return false;
  const int file = static_cast<std::int16_t>(w_[s29_]);
  if (file < 3 || file > 255 || !prog_.file(file)) return false;
  // RM 11-2: the routine runs with the fault posted (S:6 code, S:1/13 set) for one pass.
  w_[s6_] = code;
  w_[s1_] = static_cast<std::uint16_t>(w_[s1_] | status::kMajorHalt);
  const FaultInfo original = fault_;
  const SavedStatus saved = save_status();
  faulted_ = false;
  fault_ = {};
  fault_located_ = false;
  in_fault_routine_ = true;
  ++interrupt_level_;
  // The routine gets a watchdog period of its own: after a watchdog fault it could not run a
  // rung otherwise (docs/semantics.md).
  const Nanoseconds watchdog = watchdog_;
  watchdog_ = elapsed + watchdog_span_;
  update_limit(elapsed);
  const bool ok = run_routine(file, elapsed, std::min(3, max_depth_));
  watchdog_ = watchdog;
  --interrupt_level_;
  in_fault_routine_ = false;
  if (!ok) {
    // A fault inside the fault routine (or a SUS there) is the one that stands.
    fault_located_ = true;
    return false;
  }
  restore_status(saved);
  update_limit(elapsed);
  // RM 11-2 table 11.2: a recoverable fault is cleared when the routine clears S:1/13; a
  // non-recoverable one halts the processor whatever the routine did.
  if (recoverable(code) && !(w_[s1_] & status::kMajorHalt)) return true;
  faulted_ = true;
  fault_ = original;
  fault_located_ = true;
  return false;
}

}  // namespace softslc
