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
//   v := the rung's contact bits gathered into one small integer (one load, shift and OR each)
//   elapsed += cost[v]          the exact sum of every instruction's true/false charge
//   count   += instructions     every instruction of a contact network always executes
//   for each coil j: its rung-in is bit v of the coil's truth table; apply OTE/OTL/OTU
//
// The truth tables and cost tables are not written by hand per pattern: they are produced by
// running the rung's own ops through the same rung-condition rules the interpreter uses (SOR,
// BST/NXB/BND, and each op's rule from fused_rule(), which is checked against the instruction
// table's rows) for every value of v, with the interpreter's cost table. Rungs with the same op
// sequence share one "shape" (its tables), so memory grows with the number of distinct rung
// shapes, not with the program.
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
// The bytecode is unchanged: the fused form is a side table the Interpreter builds once, at
// construction, from the CompiledProgram and its cost table (which depends on the timing model).
#pragma once

#include <cstdint>
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
};

FusedRule fused_rule(Opcode op);

class FusedProgram {
 public:
  // Contacts per fused rung: the cost table has 2^kMaxContacts entries per shape.
  static constexpr unsigned kMaxContacts = 8;
  // Coils per fused rung.
  static constexpr unsigned kMaxCoils = 16;

  // `cost` is the interpreter's table, indexed op * 2 + rung-in.
  FusedProgram(const CompiledProgram& program, const std::vector<Nanoseconds>& cost);

  // The run that starts at rung `rung` of program file `file`, or -1.
  std::int32_t run_at(int file, std::uint32_t rung) const {
    const std::uint32_t first = file_first_rung_[static_cast<std::size_t>(file) & 0xFF];
    return run_of_rung_[first + rung];
  }

  // Executes run `run` whose first rung's SOR the caller has already executed (rung-in true).
  // Adds the scan time to `elapsed` and the instructions executed to `count`; returns the code
  // offset where the general path continues (the SOR of the next rung, the file's EOF, or the
  // SOR of a rung at which `limit`, the watchdog or an interrupt point, was reached).
  std::uint32_t execute(std::int32_t run, std::uint16_t* w, Nanoseconds& elapsed, std::uint64_t& count,
                        Nanoseconds limit) const;

  std::size_t runs() const { return runs_.size(); }
  std::size_t fused_rungs() const { return fused_rungs_; }
  std::size_t shapes() const { return shapes_.size(); }

 private:
  struct Shape {
    std::uint8_t contacts = 0;
    std::uint8_t coils = 0;
    std::uint16_t instructions = 0;  // instruction-table instructions in the rung
    std::uint32_t cost_at = 0;       // first of 2^contacts entries in costs_
    std::uint32_t truth_at = 0;      // first of coils * 4 words in truth_ (256-bit table per coil)
  };
  struct Run {
    std::uint32_t first = 0;  // index in stream_ of the first rung record
    std::uint32_t last = 0;   // one past the last rung record
    std::uint32_t next = 0;   // code offset after the run
    std::uint32_t first_rung = 0;  // index in sor_ of the first rung
  };
  static constexpr std::uint32_t kShapeMask = 0x00FFFFFF;

  class Builder;

  // Rung records, back to back: the shape index with the contact count in bits 31-24, one bit
  // operand word per contact, one bit operand word per coil with the coil's FusedRule in the
  // mode bits (31-28).
  std::vector<std::uint32_t> stream_;
  std::vector<std::uint32_t> sor_;  // per fused rung, in stream order: the code offset of its SOR
  std::vector<Shape> shapes_;
  std::vector<Nanoseconds> costs_;
  std::vector<std::uint64_t> truth_;
  std::vector<Run> runs_;
  std::vector<std::int32_t> run_of_rung_;         // per rung of every file (in file order): its run or -1
  std::vector<std::uint32_t> file_first_rung_;    // file number -> index of its rung 0 in run_of_rung_
  std::size_t fused_rungs_ = 0;
};

}  // namespace softslc
