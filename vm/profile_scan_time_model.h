// The scan-time model that drives virtual time from a timing profile and the manuals' M0/M1
// access-time table.
//
// Instruction true/false times, per-word times, housekeeping and I/O scan times come from a
// TimingProfile (vm/timing_profile.h; estimates unless their source says otherwise); each M0/M1
// access is charged exactly the documented time for the processor (instructions/
// mfile_access_time.h). The runtime asks once per opcode at construction, so the interpreter's
// hot path stays a table load and an add; only M-file accesses call back into the model.
#pragma once

#include <array>
#include <memory>
#include <string>

#include "instructions/processor.h"
#include "vm/scan_time_model.h"
#include "vm/timing_profile.h"

namespace softslc {

class ProfileScanTimeModel final : public ScanTimeModel {
 public:
  ProfileScanTimeModel(TimingProfile profile, std::string timing_key);

  std::string_view name() const override { return profile_.name; }
  Nanoseconds instruction_cost(Opcode op, bool rung_in) const override;
  Nanoseconds input_scan_cost(const Module& m) const override;
  Nanoseconds output_scan_cost(const Module& m) const override;
  // The per-scan overhead: housekeeping plus the fixed part of the input scan (1747-PT1 p. D-5
  // gives the 5/02 input scan as a base plus a time per module).
  Nanoseconds housekeeping_cost() const override { return profile_.housekeeping.ns + profile_.input_scan_base.ns; }
  Nanoseconds per_word_cost(Opcode op) const override { return profile_.instruction(op).per_word_ns; }
  Nanoseconds literal_operand_cost(Opcode op, std::int64_t first, bool rung_in) const override {
    return profile_.instruction(op).for_operand(first, rung_in);
  }
  Nanoseconds mfile_access_cost(MFileAccess row, int words) const override;
  TransitionCost transition_cost(Opcode op, int variant) const override {
    const InstructionTiming& t = profile_.instruction(op);
    const TransitionTiming* x = t.transition(variant);
    return x ? TransitionCost{x->true_ns - t.true_ns, x->per_word_ns} : TransitionCost{};
  }

  const TimingProfile& profile() const { return profile_; }

 private:
  TimingProfile profile_;
  std::string timing_key_;
  // Every row of the access-time table is linear in the words moved (a time per access or word,
  // or a base plus a time per word), so each MFileAccess class is kept as the cost of one word and
  // of each further word, taken from mfile_access_us at construction: an SN or SM1 program charges
  // an M-file access many times a scan, and the table lookup compares processor names.
  struct MFileCost {
    Nanoseconds first_word = 0;
    Nanoseconds next_word = 0;
  };
  std::array<MFileCost, static_cast<std::size_t>(MFileAccess::OtherM) + 1> mfile_costs_{};
};

// The model for a processor: its built-in profile (or `user`, when it names the same
// processor), else the documented placeholder for processors without a profile (5/01, fixed
// controllers, MicroLogix).
std::shared_ptr<const ScanTimeModel> make_scan_time_model(const ProcessorModel& processor,
                                                          const TimingProfile* user = nullptr);

}  // namespace softslc
