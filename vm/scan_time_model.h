// The scan-time model: how much virtual time each part of a scan takes.
//
// Virtual time advances by a scan's *predicted* duration, never by how long the host took. This
// interface is the seam where the real timing model (per-processor instruction times, M0/M1
// access times from the 1747-SN and 1203-SM1 tables) will plug in later. The runtime asks the
// model once, at construction, for a cost per opcode and rung state and keeps the answers in a
// flat table, so the interpreter pays one table load and one add per executed instruction and
// never makes a virtual call on the hot path.
//
// DefaultScanTimeModel is a documented placeholder, not a measurement (facts §4: no SLC 5/03+
// execution times are available): see docs/semantics.md "Default scan-cost model". It charges
// nothing per file-instruction word and nothing for M0/M1 accesses; the timing-profile model
// (vm/timing_profile.h) is where those figures belong.
#pragma once

#include <string_view>

#include "instructions/instruction_table.h"
#include "vm/virtual_time.h"

namespace softslc {

class Module;

class ScanTimeModel {
 public:
  virtual ~ScanTimeModel() = default;
  virtual std::string_view name() const = 0;
  // Cost of one execution of `op` whose rung-in is `rung_in` (true/false execution times).
  virtual Nanoseconds instruction_cost(Opcode op, bool rung_in) const = 0;
  // Cost of moving one module's image in the input and output scans. Asked once per module when
  // the runtime is created (a module's catalog number and image size never change), not per scan.
  virtual Nanoseconds input_scan_cost(const Module& m) const = 0;
  virtual Nanoseconds output_scan_cost(const Module& m) const = 0;
  // Fixed per-scan overhead (housekeeping, communications, scan bookkeeping).
  virtual Nanoseconds housekeeping_cost() const = 0;
  // Extra cost per word a file instruction (COP, FLL, BSL, BSR, FFU, ...) moves, rung true.
  // Called once per opcode at construction, like instruction_cost.
  virtual Nanoseconds per_word_cost(Opcode) const { return 0; }
  // Cost of `op` whose first operand is the literal `first`, where the figures differ by its value
  // (SVC's channel select). Asked at construction for each value the instruction can take.
  virtual Nanoseconds literal_operand_cost(Opcode op, std::int64_t /*first*/, bool rung_in) const {
    return instruction_cost(op, rung_in);
  }
  // Cost of an immediate M0/M1 access of `words` words under the access-time row `row`
  // (1747-SN appendix B, 1203-SM1 appendix A). Asked at each M-file access: a virtual call, but
  // only on the M-file path.
  virtual Nanoseconds mfile_access_cost(MFileAccess /*row*/, int /*words*/) const { return 0; }
  // What `op` costs beyond its steady-state true time on the scan where its rung goes false to true,
  // for the instructions whose manuals print a "false-to-true transition" figure (the MicroLogix MSG,
  // 1762-RM001C p. 21-3 Table 21.1): the transition figure less the true one, and a time per word the
  // instruction moves. `variant` is the code of the instance's first keyword operand (READ 0, WRITE 1:
  // keyword_code), whose rows may differ. Asked once per opcode and variant at construction.
  struct TransitionCost {
    Nanoseconds ns = 0;
    Nanoseconds per_word_ns = 0;
  };
  virtual TransitionCost transition_cost(Opcode /*op*/, int /*variant*/) const { return {}; }
};

// Placeholder costs, chosen to be plausible for an SLC 5/03 and easy to reason about in tests:
//   input instructions (XIC, compares, OSR, ...)    1 us, true or false
//   output instructions                              2 us true, 1 us false
//   input scan / output scan per module              20 us + 5 us per image word
//   housekeeping                                     1 ms per scan
class DefaultScanTimeModel : public ScanTimeModel {
 public:
  static constexpr Nanoseconds kInputInstruction = microseconds(1);
  static constexpr Nanoseconds kOutputTrue = microseconds(2);
  static constexpr Nanoseconds kOutputFalse = microseconds(1);
  static constexpr Nanoseconds kModuleBase = microseconds(20);
  static constexpr Nanoseconds kPerImageWord = microseconds(5);
  static constexpr Nanoseconds kHousekeeping = milliseconds(1);

  std::string_view name() const override { return "default placeholder"; }
  Nanoseconds instruction_cost(Opcode op, bool rung_in) const override;
  Nanoseconds input_scan_cost(const Module& m) const override;
  Nanoseconds output_scan_cost(const Module& m) const override;
  Nanoseconds housekeeping_cost() const override { return kHousekeeping; }
};

}  // namespace softslc
