// The word-level semantics of the commonest non-bit instructions, shared by the interpreter's
// handlers (vm/interpreter.cpp) and the fused rung kernels (vm/fused.cpp).
//
// Design. A fused rung must do exactly what the general path does; the surest way is for both to
// run the same code. So what TON/TOF/RTO, CTU/CTD, RES, the integer compares, MOV, ADD/SUB and a
// COP whose spans the compiler resolved do
// to their words once their operands are resolved lives here, as inline functions of plain
// pointers and values: the interpreter's handlers resolve operands (element(), rd_int(), DYN
// faults) and call them; the fused kernels pass pre-resolved word pointers and call them with the
// op a template constant, so the `switch` folds away. Nothing here allocates, looks anything up
// or raises a fault: the faults these instructions can raise (a timer's negative PRE/ACC, a bad
// indexed address) are detected by the callers before anything is written. The longer ones are
// always inlined: in the fused word-rung loop (one function with a case per rung kind) the
// compiler otherwise called them, a measurable cost per rung.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

#include "vm/bytecode.h"
#include "vm/data_table.h"
#include "vm/virtual_time.h"

namespace softslc::word_ops {

// ---- S:0 arithmetic flags ----

inline constexpr std::uint16_t kArithFlags = 0x000F;  // S:0 C V Z S

// Writes C V Z S into S:0 (word s0); RM B-5: whenever V is set, the overflow trap S:5/0 (word s5)
// is set too.
[[gnu::always_inline]] inline void set_arith_flags(std::uint16_t* w, std::uint32_t s0, std::uint32_t s5, bool c,
                                                   bool v, bool z, bool s) {
  const auto f = static_cast<std::uint16_t>((c ? status::kCarry : 0) | (v ? status::kOverflow : 0) |
                                            (z ? status::kZero : 0) | (s ? status::kSign : 0));
  w[s0] = static_cast<std::uint16_t>((w[s0] & ~kArithFlags) | f);
  if (v) w[s5] |= status::kOverflowTrap;
}

// ---- Integer results ----

// ADD/SUB/MUL/DIV's store rule for an integer destination (16 or 32 bits): a result outside the
// destination's range sets `overflow` and, with S:2/14 set (`truncate`), keeps the low bits,
// otherwise clamps (PT1 20-5, ML B-10).
inline std::int64_t fit_integer(std::int64_t v, bool wide, bool truncate, bool& overflow) {
  const std::int64_t hi = wide ? INT32_MAX : INT16_MAX;
  const std::int64_t lo = wide ? INT32_MIN : INT16_MIN;
  if (v <= hi && v >= lo) return v;
  overflow = true;
  if (truncate)
    return wide ? static_cast<std::int64_t>(static_cast<std::int32_t>(static_cast<std::uint32_t>(v)))
                : static_cast<std::int64_t>(static_cast<std::int16_t>(static_cast<std::uint16_t>(v)));
  return v > hi ? hi : lo;
}

// MOV's rule: a value that does not fit the destination saturates and sets `overflow`, whatever
// S:2/14 says (PT1 20-5).
inline std::int64_t saturate(std::int64_t v, std::int64_t lo, std::int64_t hi, bool& overflow) {
  if (v <= hi && v >= lo) return v;
  overflow = true;
  return v > hi ? hi : lo;
}

// ADD's and SUB's carry: out of the destination width, the operands taken as unsigned (RM B-5).
inline bool add_carry(std::int64_t a, std::int64_t b, std::uint64_t width_mask) {
  return ((static_cast<std::uint64_t>(a) & width_mask) + (static_cast<std::uint64_t>(b) & width_mask)) > width_mask;
}
inline bool sub_carry(std::int64_t a, std::int64_t b, std::uint64_t width_mask) {
  return (static_cast<std::uint64_t>(a) & width_mask) < (static_cast<std::uint64_t>(b) & width_mask);
}

// The two-operand integer compares (EQU NEQ LES LEQ GRT GEQ) as a 3-bit mask of the orderings
// that make them true (bit 0 a < b, bit 1 a == b, bit 2 a > b), so a compare is a table bit.
constexpr unsigned compare_mask(Op op) {
  switch (op) {
    case Op::EQU: return 0b010;
    case Op::NEQ: return 0b101;
    case Op::LES: return 0b001;
    case Op::LEQ: return 0b011;
    case Op::GRT: return 0b100;
    case Op::GEQ: return 0b110;
    default: return 0;
  }
}
inline bool compare_by_mask(unsigned mask, std::int64_t a, std::int64_t b) {
  const unsigned order = static_cast<unsigned>((a > b) - (a < b) + 1);  // 0 <, 1 ==, 2 >
  return ((mask >> order) & 1u) != 0;
}
inline bool compare(Op op, std::int64_t a, std::int64_t b) { return compare_by_mask(compare_mask(op), a, b); }

// ---- Timers (RM 2-9, 2-10), counters (RM 2-14), RES (RM 2-16) ----

// A timer element with a negative PRE or ACC faults (0034h) before anything is written.
inline bool timer_negative(const std::uint16_t* t) {
  return static_cast<std::int16_t>(t[1]) < 0 || static_cast<std::int16_t>(t[2]) < 0;
}

// The tick count at virtual time `at` that a timer with header flags `flags` keeps: the low byte
// of the 10 ms count, or of the 1 ms count for a MicroLogix 0.001 s timer (flag B), so it stays
// exact with scans up to 255 ms (docs/semantics.md, "MicroLogix").
// Each branch divides by a constant, which compiles to a multiply; dividing by the unit chosen at
// run time compiled to a 64-bit idiv, tens of cycles on every timer rung (docs/performance.md).
inline std::uint8_t timer_tick(VirtualTime at, std::uint32_t flags) {
  return static_cast<std::uint8_t>((flags & bc::kFlagB) ? at / kNsPerMs : at / kTick);
}

// timer_tick for a run of rungs whose time only grows (vm/fused.cpp): each unit's count is kept
// with the interval of times it holds for, and divided again only when the time leaves it, so a
// timer rung pays two compares where timer_tick's multiply by the unit's inverse sat on its path.
class TickClock {
 public:
  std::uint8_t at(VirtualTime now, std::uint32_t flags) { return (flags & bc::kFlagB) ? ms_.at(now) : tick_.at(now); }

 private:
  template <VirtualTime Unit>
  struct Count {
    VirtualTime from = 1, to = 0;  // the count holds for times in [from, to); empty at first
    std::uint8_t low = 0;
    std::uint8_t at(VirtualTime now) {
      if (now >= to || now < from) [[unlikely]] {
        const VirtualTime q = now / Unit;
        from = q * Unit;
        to = from + Unit;
        low = static_cast<std::uint8_t>(q);
      }
      return low;
    }
  };
  Count<kTick> tick_;
  Count<kNsPerMs> ms_;
};

// The timer's steps, as functions of the control word and ACC held in locals (lambdas capturing
// them by reference made GCC build closure objects on the stack in the fused word-rung loop, a
// cost on every call of it; docs/performance.md).
namespace timer_steps {
// Restarts the 8-bit stamp at `now8`.
[[gnu::always_inline]] inline void restart(std::uint16_t& ctl, std::uint8_t now8) {
  ctl = static_cast<std::uint16_t>((ctl & ~bits::kStampMask) | now8);
}
// Whole time-base units since the stamp; the remainder of a 1.0 s unit stays in the stamp.
[[gnu::always_inline]] inline int advance(std::uint16_t& ctl, std::uint8_t now8, bool base1s) {
  const auto stamp = static_cast<std::uint8_t>(ctl & bits::kStampMask);
  const unsigned delta = static_cast<std::uint8_t>(now8 - stamp);
  const unsigned units = base1s ? delta / 100 : delta;
  const unsigned used = base1s ? units * 100 : delta;
  ctl = static_cast<std::uint16_t>((ctl & ~bits::kStampMask) | static_cast<std::uint8_t>(stamp + used));
  return static_cast<int>(units);
}
[[gnu::always_inline]] inline void set_done(std::uint16_t& ctl, bool done) {
  ctl = static_cast<std::uint16_t>(done ? ((ctl | bits::kDN) & ~bits::kTT) : ((ctl | bits::kTT) & ~bits::kDN));
}
// TON and RTO with a true rung: the stamp restarts when timing starts (or on the first pass),
// else ACC advances up to PRE; EN is set, and DN or TT from ACC against PRE.
[[gnu::always_inline]] inline void time_while_true(std::uint16_t& ctl, int& acc, int pre, bool first_pass,
                                                   std::uint8_t now8, bool base1s) {
  if (first_pass || !(ctl & bits::kEN))
    restart(ctl, now8);
  else if (acc < pre)
    acc = std::min<int>(pre, acc + advance(ctl, now8, base1s));
  ctl |= bits::kEN;
  set_done(ctl, acc >= pre);
}
}  // namespace timer_steps

// TON, TOF or RTO on element t (control word, PRE, ACC; neither negative) at tick `now8`.
// `base1s`: the 1.0 s time base (header flag A).
[[gnu::always_inline]] inline void timer(Op op, std::uint16_t* t, bool rung, bool first_pass, std::uint8_t now8,
                                        bool base1s) {
  using namespace timer_steps;
  const auto pre = static_cast<std::int16_t>(t[1]);
  int acc = static_cast<std::int16_t>(t[2]);
  std::uint16_t ctl = t[0];
  switch (op) {
    case Op::TON:
      // RM 2-9: EN follows the rung; TT while timing; DN at ACC >= PRE; a false rung resets all.
      if (!rung) {
        ctl &= static_cast<std::uint16_t>(~(bits::kEN | bits::kTT | bits::kDN));
        acc = 0;
        break;
      }
      // Starting to time, or the first scan after entering Run: RM 2-9 resets ACC on return
      // to Run with the rung true.
      if (first_pass) acc = 0;
      time_while_true(ctl, acc, pre, first_pass, now8, base1s);
      break;
    case Op::TOF:
      // RM 2-10: DN while the rung is true; after it goes false ACC counts, DN clears at PRE.
      if (first_pass && !rung) {
        ctl &= static_cast<std::uint16_t>(~(bits::kEN | bits::kTT | bits::kDN));
        acc = pre;
        break;
      }
      if (rung) {
        ctl = static_cast<std::uint16_t>((ctl | bits::kEN | bits::kDN) & ~bits::kTT);
        acc = 0;
        break;
      }
      if (ctl & bits::kEN) {
        ctl &= static_cast<std::uint16_t>(~bits::kEN);
        restart(ctl, now8);
        if (ctl & bits::kDN) ctl |= bits::kTT;
      } else if (ctl & bits::kTT) {
        acc = std::min<int>(pre, acc + advance(ctl, now8, base1s));
      }
      if ((ctl & bits::kTT) && acc >= pre) ctl &= static_cast<std::uint16_t>(~(bits::kTT | bits::kDN));
      break;
    case Op::RTO:
      // Like TON, but a false rung only clears EN and TT; ACC and DN hold until RES.
      if (!rung) {
        ctl &= static_cast<std::uint16_t>(~(bits::kEN | bits::kTT));
        break;
      }
      time_while_true(ctl, acc, pre, first_pass, now8, base1s);
      break;
    default: break;
  }
  t[0] = ctl;
  t[2] = static_cast<std::uint16_t>(acc);
}

// How an execution of timer() with these inputs uses `now8`: not at all, to restart the stamp, or to
// advance ACC by the units since the stamp. It follows timer()'s branches one for one (the
// TimerClockUse test in tests/vm/word_ops_test.cpp runs both on every combination of bits and checks
// that an execution said not to read the clock gives the same words at any tick, and one said to
// restart gives the stamp `now8` and leaves ACC). The repeats across ticks rest on it
// (Runtime::probe_and_repeat, docs/semantics.md "Timers accumulating across ticks").
enum class TimerClockUse : std::uint8_t { None, Restart, Advance };
inline TimerClockUse timer_clock_use(Op op, std::uint16_t ctl, int acc, int pre, bool rung, bool first_pass) {
  switch (op) {
    case Op::TON:
    case Op::RTO:
      if (!rung) return TimerClockUse::None;
      if (first_pass || !(ctl & bits::kEN)) return TimerClockUse::Restart;
      return acc < pre ? TimerClockUse::Advance : TimerClockUse::None;
    case Op::TOF:
      if (rung || first_pass) return TimerClockUse::None;
      if (ctl & bits::kEN) return TimerClockUse::Restart;
      return (ctl & bits::kTT) ? TimerClockUse::Advance : TimerClockUse::None;
    default: return TimerClockUse::None;
  }
}

// One execution of TON, TOF or RTO as a probe records it (Runtime::probe_and_repeat): the element's
// control word (its index in the table), the control word and ACC as the instruction found them, the
// rung, the header flags (kFlagA the 1.0 s base, kFlagB the 0.001 s base) and the virtual time at
// which it read the tick.
struct TimerExecution {
  VirtualTime at = 0;
  std::uint32_t word = 0;
  std::uint32_t flags = 0;
  std::uint16_t control = 0;
  std::int16_t acc = 0;
  std::int16_t pre = 0;
  Op op = Op::TON;
  bool rung = false;
};

// Records the execution of timer `op` on the element at word `word` of table `w`, before it runs.
[[gnu::noinline, gnu::cold]] inline void record_timer(std::vector<TimerExecution>& v, Op op, const std::uint16_t* w,
                                                      std::uint32_t word, bool rung, VirtualTime at,
                                                      std::uint32_t flags) {
  v.push_back({at, word, flags, w[word], static_cast<std::int16_t>(w[word + 2]), static_cast<std::int16_t>(w[word + 1]),
               op, rung});
}

// CTU or CTD on element c. RM 2-14: count on a false-to-true transition only (CU/CD remember the
// last rung state); on the first scan after entering Run the SLC has set CU/CD, so a true rung
// does not count.
[[gnu::always_inline]] inline void counter(Op op, std::uint16_t* c, bool rung, bool first_pass) {
  std::uint16_t ctl = c[0];
  int acc = static_cast<std::int16_t>(c[2]);
  const int pre = static_cast<std::int16_t>(c[1]);
  if (op == Op::CTU) {
    if (rung && !(ctl & bits::kCU) && !first_pass) {
      if (acc == 32767) {
        acc = -32768;
        // Wrapping up out of an underflowed count brings it back in range: UN clears.
        if (ctl & bits::kUN) ctl &= static_cast<std::uint16_t>(~bits::kUN);
        else ctl |= bits::kOV;
      } else {
        ++acc;
      }
    }
    ctl = static_cast<std::uint16_t>(rung ? (ctl | bits::kCU) : (ctl & ~bits::kCU));
  } else {
    if (rung && !(ctl & bits::kCD) && !first_pass) {
      if (acc == -32768) {
        acc = 32767;
        // RM 2-14: OV clears when a CTD brings the count back to <= +32767.
        if (ctl & bits::kOV) ctl &= static_cast<std::uint16_t>(~bits::kOV);
        else ctl |= bits::kUN;
      } else {
        --acc;
      }
    }
    ctl = static_cast<std::uint16_t>(rung ? (ctl | bits::kCD) : (ctl & ~bits::kCD));
  }
  ctl = static_cast<std::uint16_t>(acc >= pre ? (ctl | bits::kDN) : (ctl & ~bits::kDN));
  c[0] = ctl;
  c[2] = static_cast<std::uint16_t>(acc);
}

// RES on an element of file type `type` (the RES header's aux).
inline void reset(FileType type, std::uint16_t* e) {
  switch (type) {
    case FileType::Timer:
      e[0] &= static_cast<std::uint16_t>(~(bits::kEN | bits::kTT | bits::kDN));
      e[2] = 0;
      break;
    case FileType::Counter:
      e[0] &= static_cast<std::uint16_t>(~(bits::kCU | bits::kCD | bits::kDN | bits::kOV | bits::kUN));
      e[2] = 0;
      break;
    default:  // Control: every status bit and the error code clear; POS = 0; LEN stays.
      e[0] = 0;
      e[2] = 0;
      break;
  }
}

// ---- CLR into a 16-bit word ----

// The destination becomes 0; Z set, C, V and S clear (docs/semantics.md, "CLR: destination 0,
// flags Z only"). The interpreter's CLR on a direct word and the fused word rungs both run this.
[[gnu::always_inline]] inline void clear(std::uint16_t* w, std::uint32_t dest, std::uint32_t s0, std::uint32_t s5) {
  w[dest] = 0;
  set_arith_flags(w, s0, s5, false, false, true, false);
}

// ---- COP (RM 7-5) with both spans resolved by the compiler (bytecode.h, COP flag B) ----

// Moves `words` raw words from src to dst as one block (overlapping ranges behave as memmove:
// docs/semantics.md), then S:24 (word s24) holds the last offset used, length - 1 [U]. The
// per-word scan-time charge is the caller's.
[[gnu::always_inline]] inline void copy_direct(std::uint16_t* w, std::uint32_t src, std::uint32_t dst,
                                               std::uint32_t words, std::uint32_t s24, std::int32_t length) {
  std::memmove(w + dst, w + src, words * sizeof(std::uint16_t));
  w[s24] = static_cast<std::uint16_t>(std::max(length, 1) - 1);
}

}  // namespace softslc::word_ops
