// Interrupts: the selectable timed interrupt (STI), STD/STE/STS, the user fault routine, and the
// MicroLogix EII and HSC interrupts.
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
//
// the discrete input interrupt (DII, RM 11-18 .. 11-26) and the I/O event-driven
// interrupt (ISR, RM 11-27 .. 11-35) reuse the same machinery: a request makes its routine runnable,
// update_limit brings limit_ down to "now", and the next rung start runs it through
// run_interrupt_routine. Priorities (RM 11-30 and the 5/03+ order): the fault routine, then the DII,
// the STI, the ISRs; a routine is interrupted only by one of higher priority. Field input changes
// and module requests reach the runtime between scans (events and tools), so a DII or ISR they make
// runnable starts at the first rung of the next scan: its latency is the rest of the scan in which
// the input changed, the input scan and the entry cost (docs/semantics.md).
//
// The MicroLogix 1100-1500 keep their STI in the STI:0 function file (1763-RM001C pp. 270-272):
// the same timer and the same rung-start servicing, with the program's view in STI:0 instead of
// the status file (locate_sti_bits: UIP, UIE, UIX for S:2/0-2), PFN/SPM/TIE read where the SLC
// reads S:30/S:31, up to two waiting expiries before the lost bit (sti_queued_), and rung starts
// that look while one waits so that a program's OTL of UIE runs it at the next rung.
//
// Their event input interrupts (EII:n) and high-speed counter interrupts (HSC:n) are EventInterrupts:
// function-file elements with the STI's UIX/UIE/UIL/UIP bits and its "1 active and 2 pending" rule,
// kept in one array in the priority order of 1762-RM001C p. 18-4 (all above the STI). An embedded
// input's edge (event_input, from the runtime when the terminal changes) or a counter's high preset or
// overflow (collect_counter_events, after each counter update) queues a run; rung starts look while
// one waits (update_limit), so it runs at the next rung start once its UIE is set.
#include <algorithm>
#include <array>
#include <cstring>
#include <string>

#include "vm/interpreter.h"

namespace softslc {

namespace {

// Interrupt priorities (RM 11-30: "an executing interrupt can only be interrupted by an interrupt
// having higher priority"; the 5/03+ order fault routine, DII, STI, ISR). The MicroLogix event
// interrupts lie between the STI and the fault routine (1762-RM001C p. 18-4), from
// kPriorityEventLowest up, in the order of kEventOrder.
constexpr int kPriorityIsr = 1;
constexpr int kPrioritySti = 2;
constexpr int kPriorityEventLowest = 3;
constexpr int kPriorityDii = 30;
constexpr int kPriorityFault = 40;

// The MicroLogix user interrupts, highest priority first: 1762-RM001C p. 18-4 lists the User Fault
// Routine, Event Interrupt 0, Event Interrupt 1, High-Speed Counter Interrupt 0, Event Interrupts 2
// and 3, High-Speed Counter Interrupt 1 (1500 only) and the STI. The 1400's EII:4-7 and HSC:2-5 are
// not in that list: softslc puts them after it, EIIs first [U]. {counter, number}.
struct EventSlot {
  bool counter;
  int number;
};
constexpr std::array<EventSlot, 14> kEventOrder{{{false, 0}, {false, 1}, {true, 0}, {false, 2}, {false, 3}, {true, 1},
                                                {false, 4}, {false, 5}, {false, 6}, {false, 7}, {true, 2}, {true, 3},
                                                {true, 4}, {true, 5}}};

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

bool Interpreter::sti_runnable() const {
  return priority_ < kPrioritySti && sti_.file != 0 && (w_[sti_bits_] & sti_pending_) && (w_[sti_bits_] & sti_enabled_);
}

void Interpreter::locate_sti_bits() {
  const FileLayout& f = prog_.layout->function_file(FunctionFile::STI);
  if (!f.present) {
    sti_bits_ = s2_;
    sti_pending_ = status::kStiPending;
    sti_enabled_ = status::kStiEnabled;
    sti_executing_ = status::kStiExecuting;
    return;
  }
  sti_file_word_ = f.base;
  sti_bits_ = f.base + sti::kBits;
  sti_pending_ = 1u << sti::kPendingBit;
  sti_enabled_ = 1u << sti::kEnableBit;
  sti_executing_ = 1u << sti::kExecutingBit;
}

bool Interpreter::dii_runnable() const {
  return priority_ < kPriorityDii && dii_.file != 0 && (w_[s2_] & status::kDiiPending) &&
         (w_[s2_] & status::kDiiEnabled);
}

bool Interpreter::io_enabled(int slot) const {
  const std::uint32_t word = s27_ + static_cast<std::uint32_t>(slot / 16);
  return (w_[word] >> (slot % 16)) & 1u;
}

void Interpreter::set_io_pending(int slot, bool on) {
  std::uint16_t& word = w_[s25_ + static_cast<std::uint32_t>(slot / 16)];
  const auto bit = static_cast<std::uint16_t>(1u << (slot % 16));
  word = static_cast<std::uint16_t>(on ? (word | bit) : (word & ~bit));
}

int Interpreter::runnable_isr_slot() const {
  if (io_requests_ == 0 || priority_ >= kPriorityIsr) return 0;
  // RM 11-30: requests seen together are served lowest slot first.
  for (int slot = 1; slot <= 30; ++slot)
    if (io_requested_[static_cast<std::size_t>(slot)] && io_enabled(slot)) return slot;
  return 0;
}

void Interpreter::update_limit(Nanoseconds elapsed) {
  Nanoseconds limit = watchdog_;
  if (sti_.file != 0) limit = std::min(limit, sti_runnable() ? elapsed : sti_.due - scan_start_);
  // MicroLogix: an expiry held back by a clear UIE runs at the first rung start after the program
  // sets UIE (1763-RM001C p. 270 "STI subroutine processing resumes"; 1762-RM001C p. 18-3: interrupts
  // are serviced at the start of a rung), so rung starts look while one waits.
  if (sti_file_word_ >= 0 && sti_queued_ > 0 && priority_ < kPrioritySti) limit = std::min(limit, elapsed);
  // So do they while an EII or HSC event waits (for its UIE, or a routine of higher priority to end).
  if (events_queued_ > 0)
    for (int i = 0; i < event_count_; ++i)
      if (events_[static_cast<std::size_t>(i)].queued > 0 && events_[static_cast<std::size_t>(i)].priority > priority_) {
        limit = std::min(limit, elapsed);
        break;
      }
  if (dii_runnable() || runnable_isr_slot() != 0) limit = std::min(limit, elapsed);
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
  if (sti_file_word_ >= 0) {
    // MicroLogix (1763-RM001C p. 270): "1 active and ... up to 2 pending user interrupt conditions
    // before it sets the lost bit"; UIP shows that one waits.
    std::uint16_t& bits = w_[sti_bits_];
    if (sti_queued_ >= 2) {
      bits = static_cast<std::uint16_t>(bits | (1u << sti::kLostBit));
    } else {
      ++sti_queued_;
      bits = static_cast<std::uint16_t>(bits | sti_pending_);
    }
    if (sti_.next_period > 0) {
      sti_.period = sti_.next_period;
      sti_.next_period = 0;
    }
    sti_.due += sti_.period;
    return;
  }
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
    // Highest priority first; after each routine look again: the timer may have expired, or a
    // lower-priority request become runnable, while it ran.
    if (dii_runnable()) {
      if (!run_dii(elapsed)) return false;
      continue;
    }
    // The MicroLogix EII and HSC interrupts, in their priority order, all above the STI.
    bool ran = false;
    for (int i = 0; events_queued_ > 0 && i < event_count_; ++i) {
      EventInterrupt& e = events_[static_cast<std::size_t>(i)];
      if (!event_runnable(e)) continue;
      if (!run_event(e, elapsed)) return false;
      ran = true;
      break;
    }
    if (ran) continue;
    if (sti_runnable()) {
      if (!run_sti(elapsed)) return false;
      continue;
    }
    if (const int slot = runnable_isr_slot(); slot != 0) {
      if (!run_isr(slot, elapsed)) return false;
      continue;
    }
    break;
  }
  update_limit(elapsed);
  return true;
}

bool Interpreter::run_interrupt_routine(int file, int priority, Nanoseconds& elapsed) {
  ++routine_runs_;
  const SavedStatus saved = save_status();
  elapsed += cost_[static_cast<std::size_t>(Op::JSR) * 2 + 1];  // entry, charged as a true JSR
  const int outer = priority_;
  priority_ = priority;
  ++interrupt_level_;
  update_limit(elapsed);
  // RM 6-4 (facts §4): 3 levels of subroutines from inside an STI, DII, event or fault routine.
  const bool ok = run_routine(file, elapsed, std::min(3, max_depth_));
  --interrupt_level_;
  priority_ = outer;
  if (!ok) return false;
  elapsed += cost_[static_cast<std::size_t>(Op::RET) * 2 + 1];  // exit, charged as a true RET
  restore_status(saved);
  return true;
}

bool Interpreter::run_sti(Nanoseconds& elapsed) {
  // RM 11-12/11-13: starting the routine resets the pending bit and sets the executing bit. On the
  // MicroLogix UIX is set while the routine runs (1763-RM001C p. 270) and UIP stays set while a
  // second expiry still waits.
  std::uint16_t pending_after = 0;
  if (sti_file_word_ >= 0 && --sti_queued_ > 0) pending_after = sti_pending_;
  w_[sti_bits_] = static_cast<std::uint16_t>((w_[sti_bits_] & ~sti_pending_) | pending_after | sti_executing_);
  if (!run_interrupt_routine(sti_.file, kPrioritySti, elapsed)) return false;
  w_[sti_bits_] = static_cast<std::uint16_t>(w_[sti_bits_] & ~sti_executing_);
  ++sti_.runs;
  return true;
}

// ---- The discrete input interrupt -------------------------------------------------------------------

bool Interpreter::run_dii(Nanoseconds& elapsed) {
  // RM B-56: the return mask is written just before the routine is entered. The pending bit gives
  // way to the executing bit as for the STI (S:2/11, S:2/13).
  w_[s46_ + 5] = dii_.return_mask;
  w_[s2_] = static_cast<std::uint16_t>((w_[s2_] & ~status::kDiiPending) | status::kDiiExecuting);
  const int file = dii_.file;
  dii_.last_latency = scan_start_ + elapsed + cost_[static_cast<std::size_t>(Op::JSR) * 2 + 1] - dii_.requested_at;
  if (!run_interrupt_routine(file, kPriorityDii, elapsed)) return false;
  w_[s2_] = static_cast<std::uint16_t>(w_[s2_] & ~status::kDiiExecuting);
  ++dii_.runs;
  // RM 11-24: S:46-S:50 are applied at each DII ISR exit (the routine may reconfigure the DII).
  return apply_dii_config();
}

bool Interpreter::discrete_input_card(int slot) {
  const std::uint32_t bit = 1u << slot;
  if (!(dii_card_asked_ & bit)) {
    dii_card_asked_ |= bit;
    if (chassis_.discrete_input_card(slot)) dii_card_ |= bit;
  }
  return (dii_card_ & bit) != 0;
}

bool Interpreter::apply_dii_config() {
  if (!dii_supported_) return true;
  // The words this DII was configured from: the checks below depend only on them, the program and
  // the chassis, so the result is the configuration already held. (Entering Run and stopping the
  // interrupts clear dii_.file, so the words are applied again then.)
  if (dii_.file != 0 && std::memcmp(dii_.applied, w_ + s46_, sizeof dii_.applied) == 0) return true;
  const int file = static_cast<std::int16_t>(w_[s46_]);
  if (file == 0) {
    // No DII: nothing waits (a pending one is dropped with it).
    dii_.file = 0;
    w_[s2_] = static_cast<std::uint16_t>(w_[s2_] & ~status::kDiiPending);
    return true;
  }
  if (file < 3 || file > 255 || !prog_.file(file)) {
    raise(fault::kInvalidDiiFile, "S:46 names DII file " + std::to_string(file) +
                                      ", which is not a subroutine file of this program (3-255, RM 11-18)");
    return false;
  }
  const int slot = static_cast<std::int16_t>(w_[s46_ + 1]);
  if (slot < 1 || slot > 30 || !discrete_input_card(slot)) {
    raise(fault::kInvalidDiiConfig, "S:47 names DII input slot " + std::to_string(slot) +
                                        ", which holds no discrete input card (1-30, RM 11-18)");
    return false;
  }
  const int preset = static_cast<std::int16_t>(w_[s46_ + 4]);
  if (preset < 0) {
    raise(fault::kInvalidDiiConfig,
          "S:50 DII preset " + std::to_string(preset) + " is outside 0-32767 (RM 11-24)");
    return false;
  }
  // RM 11-24: "Only bits 0 to 7 are used" of the mask and the compare value.
  dii_.file = file;
  dii_.slot = slot;
  dii_.mask = static_cast<std::uint16_t>(w_[s46_ + 2] & 0xFF);
  dii_.compare = static_cast<std::uint16_t>(w_[s46_ + 3] & 0xFF);
  dii_.preset = preset;
  std::memcpy(dii_.applied, w_ + s46_, sizeof dii_.applied);
  return true;
}

// Hot: run at every scan (vm/runtime.cpp, "The scan cycle", says why it is marked).
[[gnu::hot]] bool Interpreter::configure_dii(bool entering_run) {
  clear_fault();
  w_ = table_.words();
  if (!dii_supported_) return true;
  if (entering_run) {
    // Entering Run: nothing pending or executing, the accumulator from zero (softslc's reading of
    // the STI's rule, RM 11-12; docs/semantics.md).
    w_[s2_] = static_cast<std::uint16_t>(w_[s2_] & ~(status::kDiiPending | status::kDiiExecuting));
    w_[s46_ + 6] = 0;
    const std::uint64_t runs = dii_.runs;
    dii_ = DiiState{};
    dii_.runs = runs;
  }
  return apply_dii_config();
}

void Interpreter::dii_input(int slot, int word, std::uint16_t before, std::uint16_t after, VirtualTime at) {
  if (dii_.file == 0 || slot != dii_.slot || word != 0) return;
  w_ = table_.words();
  // RM 11-18/11-24: the first byte of the card under the mask is compared with the compare value;
  // the transition that makes the pattern match counts (a mask of 0 watches nothing).
  const unsigned mask = dii_.mask;
  const bool matched_before = ((before ^ dii_.compare) & mask) == 0;
  const bool matches = ((after ^ dii_.compare) & mask) == 0;
  if (mask == 0 || matched_before || !matches) return;
  // Every counted transition writes the table (S:52, or S:2/S:5/S:36): repeats across events stop.
  ++between_scan_writes_;
  const auto transitions = static_cast<std::uint16_t>((before ^ after) & mask);
  std::uint16_t& acc = w_[s46_ + 6];
  if (dii_.preset >= 2) {
    // Counter mode (RM 11-24, B-56): each match counts; at the preset the interrupt is generated
    // and the accumulator "immediately wraps around and begins counting again at zero" (RM 11-18).
    const int count = static_cast<std::int16_t>(acc) + 1;
    if (count < dii_.preset) {
      acc = static_cast<std::uint16_t>(count);
      return;
    }
    acc = 0;
  }
  // RM B-24: S:5/12 when the interrupt occurs while the routine executes, or while one is pending
  // or the DII is disabled. One already pending: this one is lost (S:36/8, as the STI's S:36/9).
  const std::uint16_t s2 = w_[s2_];
  if ((s2 & (status::kDiiExecuting | status::kDiiPending)) || !(s2 & status::kDiiEnabled))
    w_[s5_] = static_cast<std::uint16_t>(w_[s5_] | status::kDiiOverflow);
  if (s2 & status::kDiiPending) {
    if (s36_ >= 0) w_[s36_] = static_cast<std::uint16_t>(w_[s36_] | status::kDiiLost);
    return;
  }
  w_[s2_] = static_cast<std::uint16_t>(s2 | status::kDiiPending);
  dii_.return_mask = transitions;
  dii_.requested_at = at;
}

// ---- The I/O event-driven interrupt ---------------------------------------------------------------

void Interpreter::io_interrupt_request(int slot) {
  if (!io_supported_ || slot < 1 || slot > 30) return;
  const auto s = static_cast<std::size_t>(slot);
  if (isr_file_[s] == 0) {
    // No ISR number in the slot's configuration: nothing to run; the request is answered so the
    // module is not left waiting (docs/semantics.md).
    chassis_.interrupt_serviced(slot);
    return;
  }
  if (io_requested_[s]) return;  // a module requests again only once serviced (RM 11-27 step 3)
  w_ = table_.words();
  io_requested_[s] = true;
  ++io_requests_;
  // RM 11-31, B-43: the pending bit is set when the slot's enable bit is clear at the request.
  if (!io_enabled(slot)) set_io_pending(slot, true);
}

void Interpreter::drop_io_request(int slot) {
  io_requested_[static_cast<std::size_t>(slot)] = false;
  --io_requests_;
  chassis_.interrupt_serviced(slot);  // the module may request again
}

bool Interpreter::run_isr(int slot, Nanoseconds& elapsed) {
  const auto s = static_cast<std::size_t>(slot);
  io_requested_[s] = false;
  --io_requests_;
  set_io_pending(slot, false);
  // RM B-46: S:32 holds the slot of the executing ISR and is cleared when it completes.
  const std::uint16_t outer_slot = w_[s32_];
  w_[s32_] = static_cast<std::uint16_t>(slot);
  if (!run_interrupt_routine(isr_file_[s], kPriorityIsr, elapsed)) return false;
  w_[s32_] = outer_slot;
  ++isr_runs_;
  chassis_.interrupt_serviced(slot);  // RM 11-27 step 3: the module may interrupt again
  return true;
}

void Interpreter::io_interrupt_control(Op op, const std::uint32_t* o, Nanoseconds now_in_scan) {
  // Bit n of the slots operand is slot n (RM 11-31: S:25/S:27 bits 1-15 are slots 1-15, S:26/S:28
  // bits 0-14 slots 16-30).
  const auto slots = static_cast<std::uint32_t>(rd_int(o[0])) & 0x7FFFFFFEu;
  const auto lo = static_cast<std::uint16_t>(slots & 0xFFFF);
  const auto hi = static_cast<std::uint16_t>(slots >> 16);
  std::uint16_t* pending = w_ + s25_;
  std::uint16_t* enable = w_ + s27_;
  switch (op) {
    case Op::IID:  // RM 11-33's IID/IIE zone example
      enable[0] = static_cast<std::uint16_t>(enable[0] & ~lo);
      enable[1] = static_cast<std::uint16_t>(enable[1] & ~hi);
      break;
    case Op::IIE:  // RM 11-33: a pending ISR of these slots runs at once (the next rung start)
      enable[0] = static_cast<std::uint16_t>(enable[0] | lo);
      enable[1] = static_cast<std::uint16_t>(enable[1] | hi);
      // B-43: setting the enable bit clears the pending bit; the request itself stays to be served.
      pending[0] = static_cast<std::uint16_t>(pending[0] & ~lo);
      pending[1] = static_cast<std::uint16_t>(pending[1] & ~hi);
      update_limit(now_in_scan);
      break;
    case Op::RPI:  // RM B-43 (the RPI page was not reached): the pending bits of these slots reset; their requests are dropped
      pending[0] = static_cast<std::uint16_t>(pending[0] & ~lo);
      pending[1] = static_cast<std::uint16_t>(pending[1] & ~hi);
      for (int slot = 1; slot <= 30; ++slot) {
        const auto s = static_cast<std::size_t>(slot);
        if (((slots >> slot) & 1u) && io_requested_[s]) drop_io_request(slot);
      }
      break;
    default: break;
  }
}

[[gnu::hot]] bool Interpreter::configure_sti(VirtualTime now, bool entering_run) {
  clear_fault();
  w_ = table_.words();
  if (sti_file_word_ >= 0) return configure_function_file_sti(now, entering_run);
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
  if (file == 0 || setpoint == 0 || !prog_.processor.supports(Requirement::TimedInterrupt)) {
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
  reset_event_interrupts(false);
  sti_.file = 0;
  sti_.next_period = 0;
  sti_queued_ = 0;
  w_[sti_bits_] = static_cast<std::uint16_t>(w_[sti_bits_] & ~(sti_pending_ | sti_executing_));
  // the DII and the I/O interrupts stop too; a module's open request is answered.
  dii_.file = 0;
  if (dii_supported_)
    w_[s2_] = static_cast<std::uint16_t>(w_[s2_] & ~(status::kDiiPending | status::kDiiExecuting));
  for (int slot = 1; slot <= 30 && io_requests_ > 0; ++slot)
    if (io_requested_[static_cast<std::size_t>(slot)]) drop_io_request(slot);
  // RM B-46: S:32 is cleared on entry to Run; B-43: the pending bits go with the requests.
  if (io_supported_) {
    w_[s32_] = 0;
    w_[s25_] = 0;
    w_[s25_ + 1] = 0;
  }
}

[[gnu::hot]] ProgramScanResult Interpreter::service_interrupts_between(VirtualTime scan_start, Nanoseconds elapsed,
                                                          Nanoseconds watchdog) {
  // Nothing timing or waiting (most scans): update_limit would leave the limit at the watchdog and
  // nothing would run, so no pass is begun.
  if (sti_.file == 0 && sti_queued_ == 0 && events_queued_ == 0 && !dii_runnable() && runnable_isr_slot() == 0) {
    ProgramScanResult res;
    res.elapsed = elapsed;
    res.last_file = last_file_;
    res.last_rung = last_rung_;
    return res;
  }
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

// ---- The MicroLogix STI function file ----------------------------------------------------------------
// STI:0 (sti:: in parser/address.h) is the program's view; the timer is the SLC's (sti_, sti_expire,
// run_sti). Sources: 1763-RM001C pp. 270 and 272 (UIX, UIE, UIL, ED, SPM, error code 1) and p. 318 of
// 1766-RM001A; the rest is softslc's reading, marked [U] in docs/semantics.md "MicroLogix".

int Interpreter::function_file_sti_program(const char* when) {
  std::uint16_t* fn = w_ + sti_file_word_;
  const int file = fn[sti::kProgramFile];
  if (file >= 3 && file <= 255 && prog_.file(file)) {
    fn[sti::kBits] = static_cast<std::uint16_t>(fn[sti::kBits] & ~(1u << sti::kErrorBit));
    fn[sti::kErrorCode] = 0;
    return file;
  }
  // 1763-RM001C p. 270: error code 1, a recoverable controller fault; p. 272: ED tells the program
  // to look at ER. The fault code is the SLC's STI file fault [U].
  fn[sti::kBits] = static_cast<std::uint16_t>(fn[sti::kBits] | (1u << sti::kErrorBit));
  fn[sti::kErrorCode] = sti::kErrorInvalidFile;
  raise(fault::kInvalidStiFile, std::string(when) + ": STI:0.PFN " + std::to_string(file) +
                                    " is not a subroutine file of this program (3-255): STI error code 1, Invalid "
                                    "Program File Number (1763-RM001C p. 270)");
  return 0;
}

bool Interpreter::configure_function_file_sti(VirtualTime now, bool entering_run) {
  std::uint16_t* fn = w_ + sti_file_word_;
  std::uint16_t& bits = fn[sti::kBits];
  const auto timed_enable = static_cast<std::uint16_t>(1u << sti::kTimedEnableBit);
  if (entering_run) {
    // Nothing runs or waits on entry; AS sets TIE when the controller enters an executing mode
    // (the 2080-UM002 wording of the same bit [U]); SPM is loaded then (1763-RM001C p. 272).
    bits = static_cast<std::uint16_t>(bits & ~(sti_executing_ | sti_pending_));
    if ((bits >> sti::kAutoStartBit) & 1u) bits = static_cast<std::uint16_t>(bits | timed_enable);
    sti_queued_ = 0;
    sti_ = StiTimer{0, 0, 0, 0, 0, sti_.runs};
  }
  // TIE and SPM are read here, at the end of every scan: a program's change to either starts,
  // stops or re-times the STI as an S:30/S:31 change does on the SLC (RM 11-12) [U].
  const std::uint16_t setpoint = fn[sti::kSetPoint];
  if (!(bits & timed_enable) || setpoint == 0) {
    sti_.file = 0;
    sti_.next_period = 0;
    sti_queued_ = 0;
    bits = static_cast<std::uint16_t>(bits & ~sti_pending_);
    return true;
  }
  const int file = function_file_sti_program("entering Run or at the end of the scan");
  if (file == 0) return false;
  const Nanoseconds period = sti_period(setpoint);
  if (sti_.file == 0) {
    sti_.period = period;
    sti_.next_period = 0;
    sti_.due = now + period;
  } else {
    sti_.next_period = period != sti_.period ? period : 0;
  }
  sti_.file = file;
  sti_.setpoint = setpoint;
  return true;
}

void Interpreter::function_file_sti_start(const std::uint32_t* o, Nanoseconds now_in_scan) {
  if (sti_file_word_ < 0) {
    raise(fault::kUnsupportedInstruction, "STS with one operand needs the MicroLogix STI function file");
    return;
  }
  const auto time = static_cast<std::uint16_t>(bc::imm_of(o[0]));
  std::uint16_t* fn = w_ + sti_file_word_;
  std::uint16_t& bits = fn[sti::kBits];
  // 1763-RM001C p. 272: STS changes SPM. As the SLC STS does (RM 11-16), it restarts the timer and
  // drops what was pending; time 0 stops the STI [U].
  fn[sti::kSetPoint] = time;
  sti_queued_ = 0;
  bits = static_cast<std::uint16_t>(bits & ~sti_pending_);
  if (time == 0) {
    bits = static_cast<std::uint16_t>(bits & ~(1u << sti::kTimedEnableBit));
    sti_.file = 0;
    sti_.next_period = 0;
  } else {
    bits = static_cast<std::uint16_t>(bits | (1u << sti::kTimedEnableBit));
    const int file = function_file_sti_program("STS");
    if (file == 0) return;
    sti_.file = file;
    sti_.period = sti_period(time);
    sti_.next_period = 0;
    sti_.setpoint = time;
    sti_.due = scan_start_ + now_in_scan + sti_.period;
  }
  update_limit(now_in_scan);
}

// ---- The MicroLogix EII and HSC interrupts ---------------------------------------------------------------
// EII:n and HSC:n (eii::, hsc:: in parser/address.h) share the STI's program view: UIX, UIE, UIL, UIP
// and ED at the same bit positions of word 2, PFN in word 0, ER in word 1. Sources: 1763-RM001C p. 275
// and 1762-RM001C p. 18-19 (UIX, UIE, UIL, UIP: "1 active and ... up to 2 pending"), p. 18-3 (service
// points), p. 18-4 (priority); the rest is softslc's reading, marked [U] in docs/semantics.md
// "The EII function file" and "The HSC function file".

void Interpreter::locate_event_interrupts() {
  const FileLayout& inputs = prog_.layout->function_file(FunctionFile::EII);
  const FileLayout& counters = prog_.layout->function_file(FunctionFile::HSC);
  event_count_ = 0;
  for (std::size_t k = 0; k < kEventOrder.size(); ++k) {
    const EventSlot slot = kEventOrder[k];
    const FileLayout& f = slot.counter ? counters : inputs;
    if (!f.present || static_cast<std::uint32_t>(slot.number) >= f.elements) continue;
    EventInterrupt& e = events_[static_cast<std::size_t>(event_count_++)];
    e.counter = slot.counter;
    e.number = slot.number;
    e.element = f.base + static_cast<std::uint32_t>(slot.number) * f.words_per_element;
    e.priority = kPriorityEventLowest + static_cast<int>(kEventOrder.size() - k);
  }
}

bool Interpreter::nothing_pending_between_scans() const {
  // An EII fires only on an input edge, which a repeated scan cannot bring (inputs change through
  // tools between runs, or through module events, which bound the skip); one already queued vetoes.
  // A timing STI is allowed, the SLC's and the MicroLogix function file's alike: its expiries are at
  // known times (sti_.due), which the runtime bounds the repeats by, and a probe that moved the timer
  // (an expiry, an STS) is not repeated; a MicroLogix expiry waiting for UIE (sti_queued_) vetoes.
  // An HSC with no pulses arriving counts nothing (its loads by SP, HSL and RAC take the table's
  // values, the same in every repeat), and an idle PTO's scan follows the table alone. An ASCII
  // port acts between scans only in its events (Repeat::AsciiPort in the instruction table).
  // A configured DII with nothing pending is allowed (docs/semantics.md "A DII waiting for its input"):
  // it acts only on the card's input transitions, which reach it between scans in events (dii_input
  // counts its writes as between-scan writes, which stop the repeats), and its end-of-scan
  // configuration from S:46-S:50, table words the probe compares, changes nothing when they are the
  // ones it applied. A pending one runs at the next interrupt point.
  const bool no_dii_pending = dii_.file == 0 || (table_.words()[s2_] & status::kDiiPending) == 0;
  return sti_queued_ == 0 && no_dii_pending && !any_isr_ && events_queued_ == 0 && !hsc_.pulses_arriving() &&
         pulse_trains_.idle() && coverage_ == nullptr;
}

const EventInterrupt* Interpreter::event_interrupt(bool counter, int number) const {
  for (int i = 0; i < event_count_; ++i)
    if (events_[static_cast<std::size_t>(i)].counter == counter && events_[static_cast<std::size_t>(i)].number == number)
      return &events_[static_cast<std::size_t>(i)];
  return nullptr;
}

void Interpreter::reset_event_interrupts(bool entering_run) {
  events_queued_ = 0;
  for (int i = 0; i < event_count_; ++i) {
    EventInterrupt& e = events_[static_cast<std::size_t>(i)];
    e.queued = 0;
    std::uint16_t& bits = w_[e.element + eii::kBits];
    bits = static_cast<std::uint16_t>(bits & ~((1u << eii::kExecutingBit) | (1u << eii::kPendingBit)));
    if (!entering_run || e.counter) continue;
    // AS "automatically sets the Event User Interrupt Enable bit when the controller enters any
    // executing mode" (the 2080-UM002 wording of the same bit; taken as the EII's EIE [U]). An EII
    // that may fire must name its program file (error code 1, as the STI's, 1763-RM001C p. 270).
    if ((bits >> eii::kAutoStartBit) & 1u) bits = static_cast<std::uint16_t>(bits | (1u << eii::kEventEnableBit));
    if ((bits >> eii::kEventEnableBit) & 1u) (void)event_program(e);
  }
}

int Interpreter::event_program(EventInterrupt& e) {
  std::uint16_t* fn = w_ + e.element;
  const int file = fn[eii::kProgramFile];
  if (file >= 3 && file <= 255 && prog_.file(file)) return file;
  // Only a tool can make it so (PFN is read only and `check` refuses a bad DATA block): the
  // element's ED and ER 1 "Invalid Program File Number" (as the STI's, 1763-RM001C p. 270); the
  // controller does not fault and nothing runs [U].
  fn[eii::kBits] = static_cast<std::uint16_t>(fn[eii::kBits] | (1u << eii::kErrorBit));
  fn[eii::kErrorCode] = eii::kErrorInvalidFile;
  return 0;
}

void Interpreter::queue_event(EventInterrupt& e, int events) {
  std::uint16_t& bits = w_[e.element + eii::kBits];
  // 1763-RM001C p. 275: "1 active and ... up to 2 pending user interrupt conditions before it sets
  // the lost bit"; UIP shows that one waits (1762-RM001C p. 18-19).
  const int room = 2 - e.queued;
  const int taken = std::min(room, events);
  e.queued += taken;
  events_queued_ += taken;
  if (taken > 0) bits = static_cast<std::uint16_t>(bits | (1u << eii::kPendingBit));
  if (events > taken) bits = static_cast<std::uint16_t>(bits | (1u << eii::kLostBit));
}

void Interpreter::event_input(int slot, int word, std::uint16_t before, std::uint16_t after) {
  if (slot != 0 || word != 0 || before == after) return;
  w_ = table_.words();
  for (int i = 0; i < event_count_; ++i) {
    EventInterrupt& e = events_[static_cast<std::size_t>(i)];
    if (e.counter) continue;
    const std::uint16_t* fn = w_ + e.element;
    // EIE arms the EII [U]; IS names the input (validated by `check`; a tool's bad IS sets ED, ER 2).
    if (!((fn[eii::kBits] >> eii::kEventEnableBit) & 1u)) continue;
    const int input = static_cast<std::int16_t>(fn[eii::kInputSelect]);
    if (input < 0 || input > eii::kMaxInput) {
      const auto bits = static_cast<std::uint16_t>(fn[eii::kBits] | (1u << eii::kErrorBit));
      if (fn[eii::kBits] != bits || fn[eii::kErrorCode] != eii::kErrorInvalidInput) ++between_scan_writes_;
      w_[e.element + eii::kBits] = bits;
      w_[e.element + eii::kErrorCode] = eii::kErrorInvalidInput;
      continue;
    }
    const bool was = (before >> input) & 1u, is = (after >> input) & 1u;
    if (was == is) continue;
    // ES set: the rising edge; clear: the falling edge [U].
    const bool rising = (fn[eii::kBits] >> eii::kEdgeSelectBit) & 1u;
    if (is != rising) continue;
    if (event_program(e) == 0) continue;
    queue_event(e, 1);
  }
}

void Interpreter::collect_counter_events() {
  if (!hsc_.has_events()) return;
  for (int i = 0; i < event_count_; ++i) {
    EventInterrupt& e = events_[static_cast<std::size_t>(i)];
    if (!e.counter) continue;
    const MicroLogixHsc::Events ev = hsc_.take_events(e.number);
    if (ev.high == 0 && ev.overflow == 0) continue;
    std::uint16_t* fn = w_ + e.element;
    // A set mask bit lets its event interrupt [U]: RSLogix's default has HPM, LPM, UFM and OFM set
    // (0X000F), and so has TVZ_1100_REV02.RSS, whose LAD 11 "HSC0" runs on every high preset as its
    // annotations say. A counter whose PFN is 0 has no interrupt.
    const std::uint16_t masks = fn[hsc::kStatus];
    const std::int64_t high = (masks >> hsc::kHighMaskBit) & 1u ? ev.high : 0;
    const std::int64_t overflow = (masks >> hsc::kOverflowMaskBit) & 1u ? ev.overflow : 0;
    if (high + overflow == 0 || fn[hsc::kProgramFile] == 0) continue;
    if (event_program(e) == 0) continue;
    // HPI / OFI say which event interrupted; the other interrupt bits are cleared, as LPI and UFI are
    // "when the High Preset Interrupt executes" (1762-RM001C pp. 5-10, 5-13) [U: at the event].
    std::uint16_t& bits = fn[hsc::kBits];
    bits = static_cast<std::uint16_t>(bits & ~((1u << hsc::kLowInterruptBit) | (1u << hsc::kUnderflowInterruptBit) |
                                               (1u << hsc::kHighInterruptBit) | (1u << hsc::kOverflowInterruptBit)));
    if (high > 0) bits = static_cast<std::uint16_t>(bits | (1u << hsc::kHighInterruptBit));
    if (overflow > 0) bits = static_cast<std::uint16_t>(bits | (1u << hsc::kOverflowInterruptBit));
    queue_event(e, static_cast<int>(std::min<std::int64_t>(high + overflow, 3)));
  }
}

bool Interpreter::event_runnable(const EventInterrupt& e) const {
  return e.queued > 0 && priority_ < e.priority && ((w_[e.element + eii::kBits] >> eii::kEnableBit) & 1u);
}

bool Interpreter::run_event(EventInterrupt& e, Nanoseconds& elapsed) {
  --e.queued;
  --events_queued_;
  std::uint16_t& bits = w_[e.element + eii::kBits];
  const int file = event_program(e);
  if (file == 0) {
    // The PFN was made invalid (by a tool) while the event waited: ED and ER 1, nothing runs.
    events_queued_ -= e.queued;
    e.queued = 0;
    bits = static_cast<std::uint16_t>(bits & ~(1u << eii::kPendingBit));
    return true;
  }
  // UIX while the routine runs (1763-RM001C p. 275); UIP stays while another waits.
  if (e.queued == 0) bits = static_cast<std::uint16_t>(bits & ~(1u << eii::kPendingBit));
  bits = static_cast<std::uint16_t>(bits | (1u << eii::kExecutingBit));
  if (!run_interrupt_routine(file, e.priority, elapsed)) return false;
  w_[e.element + eii::kBits] = static_cast<std::uint16_t>(w_[e.element + eii::kBits] & ~(1u << eii::kExecutingBit));
  ++e.runs;
  return true;
}

// HSL (counter, high preset, low preset, output high source, output low source) and RAC (counter,
// source): vm/ml_hsc.h brings the counter up to now and loads it. A preset that breaks OVF >= HIP or
// UNF <= LOP sets the counter's ED and loads nothing [U].
void Interpreter::high_speed_counter(Op op, const std::uint32_t* o, Nanoseconds now_in_scan) {
  const int counter = static_cast<int>(bc::imm_of(o[0]));
  const std::int64_t now = scan_start_ + now_in_scan;
  if (op == Op::RAC) {
    hsc_.reset_accumulator(w_, counter, rd_int(o[1]), now);
  } else {
    (void)hsc_.load(w_, counter, rd_int(o[1]), rd_int(o[2]), static_cast<std::uint16_t>(rd_int(o[3])),
                    static_cast<std::uint16_t>(rd_int(o[4])), now);
  }
  // Bringing the counter up to now may have reached a preset: its interrupt runs at the next rung start.
  collect_counter_events();
  update_limit(now_in_scan);
}

bool Interpreter::user_fault_routine(Nanoseconds& elapsed) {
  if (in_fault_routine_ || suspended_) return false;
  const std::uint16_t code = fault_.code;
  if (non_user_fault(code)) return false;
  const int file = static_cast<std::int16_t>(w_[s29_]);
  if (file < 3 || file > 255 || !prog_.file(file)) return false;
  ++routine_runs_;
  // RM 11-2: the routine runs with the fault posted (S:6 code, S:1/13 set) for one pass.
  w_[s6_] = code;
  w_[s1_] = static_cast<std::uint16_t>(w_[s1_] | status::kMajorHalt);
  const FaultInfo original = fault_;
  const SavedStatus saved = save_status();
  clear_fault();
  fault_located_ = false;
  in_fault_routine_ = true;
  const int outer_priority = priority_;
  priority_ = kPriorityFault;
  ++interrupt_level_;
  // The routine gets a watchdog period of its own: after a watchdog fault it could not run a
  // rung otherwise (docs/semantics.md).
  const Nanoseconds watchdog = watchdog_;
  watchdog_ = elapsed + watchdog_span_;
  update_limit(elapsed);
  const bool ok = run_routine(file, elapsed, std::min(3, max_depth_));
  watchdog_ = watchdog;
  --interrupt_level_;
  priority_ = outer_priority;
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
