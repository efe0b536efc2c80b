// Fused rungs: whole rungs of bit logic executed as straight-line bit operations.
//
// Design. The general dispatch loop (vm/interpreter.cpp) pays, per instruction, a dispatch on the
// op byte, an operand-mode test, a cost-table load and add, and an instruction-count increment;
// for bit logic that is most of the work (docs/performance.md, "Where an instruction's time
// goes"). A FusedProgram removes those costs for rungs that are pure contact networks: every
// instruction of the rung is a direct-bit contact (XIC, XIO) or a direct-bit coil (OTE, OTL,
// OTU) and the rest is branch structure (BST, NXB, BND). Such a rung is a boolean function of at
// most kMaxContacts contact bits, so it runs as
//
//   v := the rung's contact bits gathered into one small integer (bit k = contact k)
//   elapsed += cost[v]          the exact sum of every instruction's true/false charge
//   count   += instructions     every instruction of a contact network always executes
//   for each coil j: its rung-in is on[j][v] (0 or 0xFFFF); apply OTE/OTL/OTU to its bit
//
// The cost and rung-in tables are not written by hand per pattern: they are produced by running
// the rung's own ops through the same rung-condition rules the interpreter uses (SOR,
// BST/NXB/BND, and each op's rule from fused_rule(), which is checked against the instruction
// table's rows) for every value of v, with the interpreter's cost table. Rungs with the same op
// sequence share one "shape" (its tables), so memory grows with the number of distinct rung
// shapes, not with the program.
//
// Speed (docs/performance.md, "Fused rungs"). Each rung is a record of pre-decoded operands: a
// contact's word index and bit number, a coil's word index and mask, so nothing is decoded from
// the 32-bit bit operand at run time. Records of one shape all have one layout, and consecutive
// rungs of one shape form a segment executed by one kernel, a template instance for the shape's
// contact count, index width and (for the commonest case, one coil) the coil's rule: inside a
// segment the gather is straight-line code with constant offsets and the only per-rung branches
// are the watchdog test and the loop. Word indices are 16 bits when the data table has at most
// 65,536 words, else 32, so the bench rung's record is 16 bytes (it was 24) and the records of a
// 10,000-rung program stay in the L2 cache beside its data table.
//
// Word rungs. The commonest non-bit rungs are fused the same way: a network of contacts and
// integer compares (EQU NEQ LES LEQ GRT GEQ on direct words or immediates), optional coils, and
// after them one action on direct words: TON TOF RTO, CTU CTD, RES, MOV, ADD, SUB, COP or CLR
// (only branch structure, more actions ("Several actions" below) and a JSR or RET may follow it).
// A compare is a contact whose bit is
// computed (bit k of v for contacts, then one bit per compare); the action is one more "coil" of
// the truth table, so its rung-in and every instruction's charge still come from running the
// rung's ops for every v. The
// action runs through the interpreter's own semantics (vm/word_ops.h) with pre-decoded word
// indices (a read operand is a word index or an immediate; there is no operand-mode test), in code
// instantiated per action and per small contact/compare count. Word rungs alternate shapes (TON,
// then CTU, then MOV ...), so consecutive word rungs of any shapes form one segment whose records
// each begin with their rung kernel's number and shape's index, and one direct-threaded loop in
// execute() runs them: each kernel ends with its own jump to the next record's kernel (no call,
// `switch` or end test per rung; the segment ends with an end record whose kernel leaves the loop,
// and a kernel for fixed counts steps over a record of constant size). Because a timer is its
// rung's last instruction (only BNDs may follow it), the virtual time it sees (a timer's 10 ms
// tick) is the rung's start plus the rung's whole charge, exactly the general path's. A timer
// element with a negative PRE or ACC (fault 0034h) is noticed before the rung writes anything; the
// run then returns that rung's SOR marked kRunsGeneral and the general path executes the rung and
// raises the fault. LBL, SBR and INT are no-ops (charged, counted) in either kind of rung. Floats,
// longs, indexed, indirect and M-file operands, and LIM/MEQ/MUL/DIV/... leave the rung to the
// general path. (A timer's steps are functions in vm/word_ops.h, not lambdas capturing its words:
// GCC built those closures on the stack on every call of the word-rung loop.)
//
// A contact network next to a word rung of its run (the rung before or after it has a compare, an
// action or a transfer) is built as a word rung too, with a word-rung record and its own shape
// (the same tables), so the word-rung loop runs it with a jump instead of leaving for a segment
// and a kernel call of its own; a stretch of contact networks keeps its one-shape segments.
//
// Several actions (session 19). A word rung may hold several actions, each in a branch leg or in
// series, after every condition and coil of the rung (only branch structure, further actions and
// a transfer follow the first action): the five unconditional MOVs of `BST MOV NXB MOV ... BND`
// that keep a DII's configuration in S:46-S:50, or a COP beside a counter. Each action is one more
// output of the truth table, and the actions run in program order, each reading its words when it
// runs, so an action sees what an earlier one wrote, as on the general path. Such a rung holds no
// timer (a timer reads the clock at its own instruction and must see every charge before it, and
// an earlier action could make its preset negative after the 0034h test): it stays general. Its
// record holds a step word before each action's operands, naming that action's step kernel, one per
// action of the actions' list (kActions in vm/fused.cpp, the same list and the same run_action code
// as the single-action kernels), and a last step word ending the rung; the word-rung loop jumps
// from step to step as from rung to rung.
//
// Transfers (issue 20). A word rung may end in a JSR or RET (followed by nothing but BNDs), after
// its action if it has one (COP NXB JSR: a file copy and a subroutine call in parallel legs). The
// transfer is one more output of the truth table; when its rung-in is true the run stops there and
// returns it to the interpreter's run_routine, which takes the JSR (its nesting check, fault 0030h,
// and its call frame) or the RET exactly as the general path's handler would, with the rung's
// charge and instruction count already added. A JSR returns to the next rung's SOR (after the
// rung's closing BNDs, which cost and count nothing and whose rung condition the SOR replaces),
// and the rung after a transfer starts a segment and a run of its own, the rest of the run it is
// in, so the run entered there is found (an untaken transfer does not end its run). A timer may not
// precede a transfer: it must see the scan time of the whole rung, which includes the JSR's charge.
// COP is fused when the compiler resolved both spans (flag B: no fault is possible); the copy is
// word_ops::copy_direct, the handler's code, and its per-word charge is added with the rung's.
//
// Calls (issue 20). A taken JSR need not leave the run either: when the subroutine's first rung
// starts a fused run (and the JSR's code offset is that rung's SOR), the run checks the nesting
// limit (calls.room, the frames run_routine has left), notes the call (return offset, calling file,
// the JSR's rung number, and the run that starts at the return: the FusedCall) and, unless the
// watchdog or an interrupt point is reached at the subroutine's first SOR, continues there. A taken
// RET with a call of the run outstanding returns into the run after the JSR's rung the same way
// (after the same check at that SOR); when the run it enters starts with word rungs, the
// word-rung loop goes straight on to their records. Every other case stops the run where the
// general path would act: the nesting limit (the JSR is returned, and run_routine raises
// 0030h), a subroutine or a return rung that is not fused (the run stops at its SOR, or at the
// file's EOF), a rung handed back (kRunsGeneral), or the watchdog. The calls still outstanding then are returned in
// FusedCalls, and run_routine pushes their frames (a fused run holds no branch and no false MCR
// zone, so the frames are the JSR handler's). The mixed program's scan thus runs as one call of
// execute() instead of one per JSR and return. A fused JSR's record carries the call's targets
// (kCallWords), filled in once every file's runs are known.
//
// Exactness. Gathering every contact before any coil writes is only correct when no contact
// reads a bit that a coil earlier in the same rung writes; such rungs are left to the general
// path. A run of consecutive fused rungs is executed in one call; before each rung after the
// first it checks the interpreter's rung-start limit (the watchdog, or sooner a timed interrupt
// that is due: vm/interrupts.cpp) and, when the scan time has reached it, returns that rung's SOR
// so the general path raises fault 0022h or runs the interrupt exactly where it would have. The interpreter enters a
// run only when no coverage recorder is attached and the rung is not inside a false MCR zone
// (fused rungs hold no MCR, so the zone cannot change inside a run); in every other case the
// general path runs, instruction by instruction, as before. Results, scan time and instruction
// counts are identical either way (tests/vm/fused_test.cpp compares the two on random programs).
//
// A compare reading a word that an earlier coil of the rung writes would likewise need the new
// value; such rungs stay general too.
//
// The bytecode is unchanged: the fused form is a side table the Interpreter builds once, at
// construction, from the CompiledProgram and its cost table (which depends on the timing model).
#pragma once

#include <cstdint>
#include <type_traits>
#include <vector>

#include "vm/bytecode.h"
#include "vm/virtual_time.h"

namespace softslc {

// What a fused rung does with an instruction-table op. Only ops whose whole effect is "read one
// bit into the rung condition" or "act on one bit with the rung condition" qualify.
enum class FusedRule : std::uint8_t {
  None,          // not fusable: the rung takes the general path
  Contact,       // rung := rung and bit
  OpenContact,   // rung := rung and not bit
  Energize,      // bit := rung
  Latch,         // if rung: bit := 1
  Unlatch,       // if rung: bit := 0
  NoOp,          // LBL, SBR, INT: charged and counted, nothing else
  Compare,       // rung := rung and (a op b), integer, a and b direct words or immediates
  Action,        // one action on direct words (vm/word_ops.h), after every condition and coil
  Transfer,      // JSR or RET, the rung's last instruction: a true rung-in hands control to run_routine
};

namespace word_ops {
class TickClock;
struct TimerExecution;
}

// What a fused kernel needs of the scan beyond the data table: timers read the tick count at
// scan_start + their scan time; counters and timers behave differently on the first pass. During a
// probe (Runtime::probe_and_repeat) `timers` collects every TON, TOF and RTO execution, as the
// interpreter's timer handler does; it is null otherwise.
struct FusedScan {
  VirtualTime scan_start = 0;
  bool first_pass = false;
  std::vector<word_ops::TimerExecution>* timers = nullptr;
};

FusedRule fused_rule(Opcode op);

// A subroutine call a run took itself and that had not returned when the run stopped (vm/fused.h,
// "Calls"): the interpreter pushes a call frame for it, as its JSR handler would have.
// No member initializers: run_routine holds a FusedCalls on its stack for every routine it runs,
// and zeroing its sixteen calls cost about a hundred instructions a scan; a call is written whole
// (execute's `calls.call[depth++] = {...}`) before it is read, and only call[0, depth) is read.
struct FusedCall {
  std::uint32_t ret;        // code offset of the SOR (or EOF) after the JSR's rung
  std::uint32_t file;       // the calling file
  std::uint32_t rung;       // the JSR's rung number
  std::int32_t ret_run;     // the run starting at ret, or -1
  std::uint32_t ret_words;  // FusedProgram's: that run's first word-rung record, or kNoWordEntry
};
static_assert(std::is_trivially_default_constructible_v<FusedCall>);
// The call state a run shares with the interpreter's run_routine.
struct FusedCalls {
  static constexpr unsigned kCapacity = 16;  // at least kMaxCallDepth (vm/interpreter.cpp checks)
  std::uint32_t file = 0;  // in: the program file the run starts in; out: the file where it stopped
  unsigned room = 0;       // in: calls allowed before the nesting limit (fault 0030h)
  unsigned depth = 0;      // out: calls outstanding, oldest first in call[0, depth)
  FusedCall call[kCapacity];
};

class FusedProgram {
 public:
  // Contacts per fused rung: the cost table has 2^kMaxContacts entries per shape.
  static constexpr unsigned kMaxContacts = 8;
  // Coils per fused rung.
  static constexpr unsigned kMaxCoils = 16;

  // `cost` is the interpreter's table, indexed op * 2 + rung-in.
  // `per_word` is the interpreter's per-word charge by opcode (COP).
  FusedProgram(const CompiledProgram& program, const std::vector<Nanoseconds>& cost, const Nanoseconds* per_word);

  // The run that starts at rung `rung` of program file `file`, or -1.
  std::int32_t run_at(int file, std::uint32_t rung) const {
    const std::uint32_t first = file_first_rung_[static_cast<std::size_t>(file) & 0xFF];
    return run_of_rung_[first + rung];
  }

  // Set in execute()'s result when the rung at the returned SOR must run on the general path
  // (it would fault): the caller must not enter a fused run there.
  static constexpr std::uint32_t kRunsGeneral = 0x80000000u;
  // Set in execute()'s result when the run stopped at a taken JSR or RET: `next` is that
  // instruction's code offset and `rung` its rung number; its charge and count are added.
  static constexpr std::uint32_t kTransfer = 0x40000000u;
  static constexpr std::uint32_t kOffsetMask = 0x3FFFFFFFu;

  // Where the general path continues after a run (two 32-bit halves, returned in one register).
  struct Exit {
    std::uint32_t next = 0;  // a code offset, with kRunsGeneral or kTransfer
    std::uint32_t rung = 0;  // with kTransfer: the rung number of the JSR or RET
  };

  // Executes run `run` whose first rung's SOR the caller has already executed (rung-in true).
  // Adds the scan time to `elapsed` and the instructions executed to `count`; returns the code
  // offset where the general path continues (the SOR of the next rung, the file's EOF, or the
  // SOR of a rung at which `limit`, the watchdog or an interrupt point, was reached, or, with
  // kRunsGeneral, of a rung the general path must execute, or with kTransfer a taken JSR or RET).
  // A taken JSR whose subroutine starts with a fused run, with `calls.room` left, is entered
  // without returning (its call is added to `calls`), and a taken RET with a call outstanding
  // returns into the run after that JSR's rung; `calls.file` follows.
  Exit execute(std::int32_t run, std::uint16_t* w, Nanoseconds& elapsed, std::uint64_t& count,
                        Nanoseconds limit, const FusedScan& scan, FusedCalls& calls) const;

  std::size_t runs() const { return runs_.size(); }
  std::size_t fused_rungs() const { return fused_rungs_; }
  std::size_t shapes() const { return shapes_.size(); }
  std::size_t segments() const { return segments_.size(); }
  // The word rungs whose rung-ins fit Shape::on_bits.
  static constexpr unsigned kSmallConditions = 3;
  static constexpr unsigned kSmallOutputs = 4;
  // Fused rungs with a compare or an action (word rungs).
  std::size_t word_rungs() const { return word_rungs_; }
  // Contact networks built as word rungs, beside a word rung of their run (run in the word-rung loop).
  std::size_t word_form_rungs() const { return word_form_rungs_; }
  // Fused word rungs holding several actions ("Several actions").
  std::size_t several_action_rungs() const { return several_action_rungs_; }
  // Fused rungs ending in a JSR or RET.
  std::size_t transfer_rungs() const { return transfer_rungs_; }
  // Fused JSRs whose subroutine starts with a fused run (a run enters it itself).
  std::size_t linked_calls() const { return linked_calls_; }
  bool wide_indices() const { return wide_; }

 private:
  // One shape: a distinct op sequence, with its tables. Rungs of one shape have records of one
  // size and layout, so a kernel specialised for the contact count and coil kind walks them.
  // 128 bytes, so a word rung finds its shape from the index in its record with one shift (the
  // mixed 1k scan: 86,242 -> 83,590 instructions with the lazy SOR lookup in execute()).
  struct alignas(128) Shape {
    std::uint8_t contacts = 0;
    std::uint8_t compares = 0;        // word rungs: compares, after the contacts in v
    std::uint8_t coils = 0;
    bool word = false;                // a word rung: records in wrecords_, run by execute()'s word-rung loop
    Op action = Op::SOR;              // word rungs: the action, or SOR for none
    bool transfer = false;            // word rungs: ends in a JSR or RET (kTransfer)
    bool call = false;                // ... in a JSR, whose record carries the call's targets
    std::uint8_t action_flags = 0;    // its header flags (a timer's time base)
    std::uint16_t action_aux = 0;     // its header aux (RES: the element's FileType)
    std::uint16_t instructions = 0;  // instruction-table instructions in the rung
    std::uint16_t stride = 0;        // record size, in 16-bit units
    std::uint8_t kernel = 0;         // index into the kernel table, or (word rungs) the word-rung loop's rung kernel
    std::uint32_t cost_at = 0;       // first of 2^contacts entries in costs_
    std::uint32_t on_at = 0;         // first of coils * 2^contacts entries in on_
    std::uint32_t rules_at = 0;      // first of coils entries in rules_, then (word rungs) compares Op bytes
    // Word rungs of at most kSmallConditions conditions and kSmallOutputs outputs (every
    // fixed-count kernel's): bit output * 8 + v is that output's rung-in, the on_ table as bits
    // here, so the kernel finds a rung-in with a shift of a word the shape holds instead of a
    // load through `on` (a load the rung's branches waited for).
    std::uint32_t on_bits = 0;
    // ... and their charges, costs_'s entries for the shape (word rungs of at most
    // kSmallConditions conditions): read at a fixed place in the shape, not through `cost`.
    Nanoseconds small_cost[1u << kSmallConditions] = {};
    // The same three tables as pointers, set once every shape is built, so a word rung loads one
    // pointer per table instead of the vector's start and the offset.
    const Nanoseconds* cost = nullptr;
    const std::uint16_t* on = nullptr;
    const std::uint8_t* rules = nullptr;
  };
  // Consecutive rungs of one run that share a shape, or consecutive word rungs: executed by one
  // kernel call.
  struct Segment {
    std::uint32_t rec = 0;         // index in records_ (wrecords_ for word rungs) of the first rung's record
    std::uint32_t rungs = 0;       // rungs in the segment
    std::uint32_t shape = 0;       // or kWordSegment
    std::uint32_t first_rung = 0;  // index in sor_ of the first rung
    // Word segments: the segment's end record (kEndOfSegment) in wrecords_, and the instructions of all its rungs
    // (added once when the segment completes; a segment that stops early counts its rungs then).
    std::uint32_t rec_end = 0;
    std::uint32_t instructions = 0;
  };
  struct Run {
    std::uint32_t first = 0;  // index in segments_ of the first segment
    std::uint32_t last = 0;   // one past the last segment
    std::uint32_t next = 0;   // code offset after the run
  };
  // Runs `segment`'s rungs from its first: returns how many completed, stopping early after the
  // rung at which `t` reached `limit`. N contacts, word indices of 32 bits when Wide (else 16),
  // and Coil 0 for any number of coils or the FusedRule kind of the rung's single coil (1 OTE,
  // 2 OTL, 3 OTU).
  template <unsigned N, bool Wide, unsigned Coil>
  static std::uint32_t run_segment(const FusedProgram& p, const Segment& segment, std::uint16_t* w, Nanoseconds& t,
                                   Nanoseconds limit, const FusedScan& scan);
  // A fused JSR's record ends in its call words, then the transfer's code offset and rung number:
  // the subroutine's file, the run at its first rung (or -1), the return offset (the next rung's
  // SOR, or EOF), the run that starts there (or -1), and for each of the two runs the index in
  // wrecords_ of its first record when it starts with word rungs, else kNoWordEntry (so a taken
  // call or return jumps to the next record's kernel without first loading the run and its
  // segment: those loads were on the path to the jump).
  static constexpr unsigned kCallWords = 6;
  static constexpr std::uint32_t kNoWordEntry = 0xFFFFFFFFu;
  // word_rung's results.
  enum WordRungResult : unsigned { kRungDone = 0, kRungGeneral = 1, kRungTransfer = 2 };
  template <Op A, unsigned NC, unsigned NM, unsigned NK, bool Transfer>
  static unsigned word_rung(const FusedProgram& p, const Shape& sh, const std::uint32_t* rec, std::uint16_t* w,
                        Nanoseconds& t, const FusedScan& scan, word_ops::TickClock& ticks);
  // Action A (vm/word_ops.h) on its recorded operands `act`, with its rung-in, its header's flags
  // (a timer's time base) and aux (RES: the element's FileType; COP: its words), at scan time t
  // (COP adds its per-word charge). The one place a fused rung's action is done: word_rung's
  // single action and each step of a rung of several actions run it.
  template <Op A>
  static void run_action(const FusedProgram& p, const std::uint32_t* act, std::uint16_t* w, Nanoseconds& t,
                         const FusedScan& scan, word_ops::TickClock& ticks, bool rung, std::uint8_t flags,
                         std::uint16_t aux);
  // The conditions and coils of a rung of several actions (any counts): gathers v, adds the
  // rung's charge and applies the coils; returns the record's first step word.
  static const std::uint32_t* multi_head(const Shape& sh, const std::uint32_t* rec, std::uint16_t* w, Nanoseconds& t,
                                         unsigned& v);
  // The largest Shape::kernel of a word rung of one action (the word-rung loop's last rung kernel
  // of that kind), and the kernel number of the one-word record that ends every word segment (the
  // loop's exit).
  static constexpr unsigned kLastWordKernel = 215;
  static constexpr unsigned kEndOfSegment = kLastWordKernel + 1;
  // A rung of several actions ("Several actions" above): its record's kernel, then in its record
  // one step word per action (the step's kernel, kFirstStep + the action's index in the actions'
  // list, in the low byte; the action header's aux above kStepAuxShift) before that action's
  // operands, and a last step word whose kernel ends the rung (kStepsEnd, or with a transfer
  // kStepsEndTransfer).
  static constexpr unsigned kMultiRung = kEndOfSegment + 1;
  static constexpr unsigned kFirstStep = kMultiRung + 1;
  static constexpr unsigned kStepsEnd = kFirstStep + 12;
  static constexpr unsigned kStepsEndTransfer = kStepsEnd + 1;
  static constexpr unsigned kStepAuxShift = 16;
  // A word-rung record's first word: its kernel number in the low byte, its shape's index above.
  static constexpr unsigned kShapeShift = 8;
  static constexpr std::uint32_t kKernelMask = 0xFF;
  // Shapes a program may have while its word rungs are fused (the index's 24 bits).
  static constexpr std::uint32_t kMaxWordShapes = 1u << (32 - kShapeShift);
  // Segment::shape of a segment of word rungs (each record names its shape).
  static constexpr std::uint32_t kWordSegment = 0xFFFFFFFFu;
  using Kernel = std::uint32_t (*)(const FusedProgram&, const Segment&, std::uint16_t*, Nanoseconds&, Nanoseconds,
                                   const FusedScan&);
  static const Kernel kKernels[];

  class Builder;

  // Rung records, back to back in program order, each a fixed layout per shape (16-bit units;
  // k = 1, or 2 when the data table has more than 65,536 words):
  //   contacts * k     each contact's word index (pre-decoded from its bit operand)
  //   (contacts+1)/2   each contact's bit number, one byte each
  //   coils * (k + 1)  each coil's word index and bit mask
  // The bench rung (four contacts, one coil) is 16 bytes.
  std::vector<std::uint16_t> records_;
  // Word-rung records, 32-bit units: the rung's kernel number and its shape's index (kShapeShift),
  // each contact's and coil's word index and bit number (index << 8 | bit, not the bytecode's
  // BIT operand, so the kernel decodes it in one shift), two read operands per compare, then the action's table operands other than
  // literals and time bases (COP: its two file operands' word indices and its length as an
  // immediate), in instruction-box order, then for a JSR its call words (kCallWords), then for a
  // transfer its code offset and rung number.
  // A read operand is a word index, or an immediate with bit 31 set and its value in bits 0-30
  // (kImmediate). Each word segment's records are followed by one word, kEndOfSegment.
  std::vector<std::uint32_t> wrecords_;
  std::uint32_t s0_ = 0, s2_ = 0, s5_ = 0, s24_ = 0;  // S:0, S:2, S:5 and S:24 word indices
  Nanoseconds cop_per_word_ = 0;                       // COP's per-word charge
  bool wide_ = false;
  std::vector<std::uint32_t> sor_;  // per fused rung, in record order: the code offset of its SOR
  std::vector<Shape> shapes_;
  std::vector<Nanoseconds> costs_;
  std::vector<std::uint16_t> on_;    // per shape, coil and contact value: the coil's rung-in, 0 or 0xFFFF
  std::vector<std::uint8_t> rules_;  // per shape and coil: its FusedRule
  std::vector<Segment> segments_;
  std::vector<Run> runs_;
  std::vector<std::int32_t> run_of_rung_;         // per rung of every file (in file order): its run or -1
  std::vector<std::uint32_t> file_first_rung_;    // file number -> index of its rung 0 in run_of_rung_
  std::size_t fused_rungs_ = 0;
  std::size_t word_rungs_ = 0;
  std::size_t word_form_rungs_ = 0;
  std::size_t transfer_rungs_ = 0;
  std::size_t several_action_rungs_ = 0;
  std::size_t linked_calls_ = 0;
};

}  // namespace softslc
