// Ladder coverage: what the program scans of a test run exercised, rung by rung.
//
// softslc measures coverage of the ladder itself, in the terms a controls engineer reviews a
// program in:
//   - rungs executed (scanned with the processor in Run or Test);
//   - rungs seen both true and false: an output instruction of the rung was executed with its
//     rung condition true, and one with it false (a rung with no input instruction, which can
//     only be true, counts once seen true);
//   - input instructions (XIC, XIO, compares, OSR: the instruction table's Input role) that
//     decided their rung segment both ways — condition coverage in the MC/DC spirit: an input
//     decides when the rung condition reaching it was true and every later input of its segment
//     was true, so its own value was the segment's outcome. A segment is the run of inputs
//     between two structure points: the start of the rung, a branch start, a next-leg or branch
//     end, or an output instruction. (Inputs before a branch are judged on their own segment;
//     the legs after them are not taken into account — an approximation, documented.)
//   - output instructions never energized (never executed with their rung condition true);
//   - subroutine files never called (no JSR to them with its rung true).
//
// Recording. The interpreter, when a CoverageRecorder is attached, leaves its bit-logic fast path
// and reports every instruction from its general switch (Interpreter::set_coverage): the code
// offset, the op, the rung condition before and after. Nothing is recorded, and nothing costs,
// without a recorder. Results are flags per code offset, so runs of the same compiled program
// (tests, power cycles, snapshots) merge by OR (merge()), in any order, giving the same report.
//
// Reporting. build_coverage_report() walks the compiled program rung by rung and names every
// instruction with the source's text and line (the compiler emits instructions in source order,
// depth first through branch legs).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "parser/program.h"
#include "vm/bytecode.h"

namespace softslc {

namespace coverage {
inline constexpr std::uint8_t kExecuted = 1;        // the instruction was executed
inline constexpr std::uint8_t kRungInTrue = 2;      // ... with its rung condition true
inline constexpr std::uint8_t kRungInFalse = 4;     // ... with its rung condition false
inline constexpr std::uint8_t kDecidedTrue = 8;     // an input that decided its segment true
inline constexpr std::uint8_t kDecidedFalse = 16;   // ... and false
inline constexpr std::uint8_t kCalled = 32;         // a file's first word: the file was called
}  // namespace coverage

class CoverageRecorder {
 public:
  explicit CoverageRecorder(const CompiledProgram& program);

  // One executed instruction at code offset `at`: the rung condition before and after it.
  void record(std::uint32_t at, Op op, bool rung_in, bool rung_out);
  // A subroutine file entered (JSR with its rung true).
  void called(int file);

  const std::vector<std::uint8_t>& flags() const { return flags_; }
  // ORs another run's flags in (same compiled program).
  void merge(const std::vector<std::uint8_t>& other);

 private:
  void close_segment();

  struct Pending {
    std::uint32_t at;
    bool rung_in;
    bool value;  // the rung condition after the input (its own value when rung_in is true)
  };
  const CompiledProgram& program_;
  std::vector<std::uint8_t> flags_;
  std::vector<Pending> segment_;
};

// The coverage of one program: totals per program file, and every uncovered item.
struct CoverageItem {
  int file = 2;
  int rung = 0;          // rung number in its file
  int instruction = -1;  // index of the instruction in its rung (from 0); -1 for a rung or file
  std::uint32_t line = 0;
  std::string text;      // "XIC START_PB", "rung 3", "file 3 SUBR"
  std::string problem;   // "never executed", "never decided its rung false", ...
};

struct FileCoverage {
  int file = 2;
  std::string name;
  bool called = true;    // subroutines: called at least once (file 2 always counts as called)
  int rungs = 0;
  int rungs_executed = 0;
  int rungs_both_ways = 0;
  int conditions = 0;            // input instructions
  int conditions_both_ways = 0;  // decided their segment true and false
  int outputs = 0;
  int outputs_energized = 0;
};

struct CoverageReport {
  std::string program;  // the program's name as shown
  std::vector<FileCoverage> files;
  std::vector<CoverageItem> uncovered;  // in file, rung, instruction order
  FileCoverage total() const;
};

CoverageReport build_coverage_report(const Program& source, const CompiledProgram& compiled,
                                     const std::vector<std::uint8_t>& flags, std::string program_name);

}  // namespace softslc
