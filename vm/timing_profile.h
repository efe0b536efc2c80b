// Timing profiles: per-processor execution times as data, each figure with its source.
//
// A profile gives, for one processor (the ProcessorModel::timing_key(): "5/02B", "5/02C",
// "5/03", "5/04", "5/05"), the true and false execution time of every instruction (plus a
// per-word time for file instructions), the per-scan housekeeping time, and the I/O scan time
// per module. Every figure names a source from the profile's `sources` table, and each source
// says whether it is an estimate. Official SLC 5/03–5/05 execution times are not in softslc's
// sources, so the shipped profiles (vm/profiles/*.json, compiled into the binary) are marked as
// estimates except where a document exists (the 5/02 I/O scan times of the 1747-PT1 manual).
//
// The documented M0/M1 access times are not part of a profile: they are the manuals' own table
// (instructions/mfile_access_time.h) and are always applied exactly.
//
// A user profile (`--timing FILE`) names its processor and overrides any subset of the
// built-in figures for it; everything it does not give keeps the built-in value.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "instructions/instruction_table.h"
#include "vm/virtual_time.h"

namespace softslc {

struct TimingSource {
  bool estimate = true;
  std::string citation;
};

// One figure and where it comes from.
struct TimedFigure {
  Nanoseconds ns = 0;
  std::string source;  // key into TimingProfile::sources
};

// The figures of one value of an instruction's first operand, where the manual prints a row per
// value: SVC's channel select (1763-RM001B p. 344: channel 0 94.1 us, channel 1 87.0 us, both 203.1 us).
struct OperandTiming {
  std::int64_t value = 0;
  Nanoseconds true_ns = 0;
  Nanoseconds false_ns = 0;
};

// A "false-to-true transition" row (1762-RM001C p. 21-3 Table 21.1): the instruction's time on the scan
// where its rung goes false to true, instead of the steady-state true time, plus a time per word. `variant`
// is the code of the instruction's first keyword operand the row is for (MSG: READ 0, WRITE 1), -1 for all.
struct TransitionTiming {
  int variant = -1;
  Nanoseconds true_ns = 0;
  Nanoseconds per_word_ns = 0;
};

struct InstructionTiming {
  Nanoseconds true_ns = 0;      // rung-in true
  Nanoseconds false_ns = 0;     // rung-in false
  Nanoseconds per_word_ns = 0;  // added per word for file instructions (COP, FLL, BSL, ...), true only
  std::string source;
  // Rows that replace true_ns/false_ns when the first operand is that literal ("by_operand").
  std::vector<OperandTiming> by_operand;
  // "transition": the false-to-true rows, by keyword variant (none: the transition costs the true time).
  std::vector<TransitionTiming> transitions;

  const TransitionTiming* transition(int variant) const {
    for (const auto& t : transitions)
      if (t.variant == variant || t.variant < 0) return &t;
    return nullptr;
  }

  // The true (or false) figure for an instance whose first operand is the literal `first`.
  Nanoseconds for_operand(std::int64_t first, bool rung_in) const {
    for (const auto& v : by_operand)
      if (v.value == first) return rung_in ? v.true_ns : v.false_ns;
    return rung_in ? true_ns : false_ns;
  }
};

struct ModuleScanTiming {
  TimedFigure input;
  TimedFigure output;
};

struct TimingProfile {
  std::string processor;  // timing key
  std::string name;
  std::map<std::string, TimingSource> sources;
  TimedFigure housekeeping;
  TimedFigure input_scan_base;
  TimedFigure default_module;          // I/O scan time of a module not listed, per scan direction
  TimedFigure default_per_image_word;  // ... plus this per image word
  std::map<std::string, ModuleScanTiming> modules;  // by catalog
  std::array<InstructionTiming, kInstructionCount> instructions{};

  const InstructionTiming& instruction(Opcode op) const { return instructions[static_cast<std::size_t>(op)]; }
  bool is_estimate(const std::string& source) const;
  // I/O scan cost of one module in a chassis slot (0 when it has no image in that direction).
  Nanoseconds input_scan(const std::string& catalog, int words) const;
  Nanoseconds output_scan(const std::string& catalog, int words) const;
};

class TimingProfileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The built-in profile for a timing key; nullopt for processors without one.
std::optional<TimingProfile> builtin_timing_profile(std::string_view timing_key);
// The timing keys of the built-in profiles, in order.
std::vector<std::string> builtin_timing_profile_keys();

// Applies a user profile (parsed JSON) on top of the built-in profile of the processor it names.
// Throws TimingProfileError with the JSON path of the first problem.
TimingProfile load_timing_profile(const nlohmann::json& user);
// Reads and applies a user profile file; errors name the file.
TimingProfile load_timing_profile_file(const std::string& path);

}  // namespace softslc
