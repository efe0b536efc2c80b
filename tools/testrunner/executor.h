// Running one test case: a fresh Runtime, the steps in order, the first failure reported.
//
// Every test gets its own Runtime built from its (shared, read-only) program, switched to its
// starting mode (Run unless the test's first step chose another) before the first step, so tests
// cannot see each other and may run on any thread in any order. A `restore` replaces the
// Runtime with a fresh one and replays the snapshot's steps into it; the runtime is
// deterministic, so the state is exactly the one the snapshot named, and a failure during the
// replay is reported at the replayed step with the snapshot named as context.
//
// The executor keeps what the Runtime cannot: virtual time and scan counts across power cycles
// (a power cycle builds a new Runtime; the test's clock and scan count carry on), the forces the
// test installed (they survive a power cycle, as on the SLC), and the virtual time and program
// scans of the most recent `scan`/`run` step, which `elapsed` and `scans` read.
//
// A test stops at its first failing step. Failures say where (file:line of the step, and the
// snapshot being replayed, if any), what was expected and what was found (the values of every
// operand of the condition), the virtual time and the scan number, and the active major fault if
// there is one. Nothing in a failure depends on the host: the same test fails with the same text
// on every machine and every --jobs setting.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "tools/testrunner/test_file.h"
#include "vm/runtime.h"
#include "vm/virtual_time.h"

namespace softslc::testing {

struct Failure {
  std::string file;
  Location loc;
  std::string step;                // the step as written
  std::string context;             // the snapshot being replayed, when there is one
  std::string expected;            // empty when `error` says what went wrong instead
  std::string actual;
  std::string error;               // a refused request or a read error
  std::vector<std::string> notes;  // further lines: differing elements, the active fault
  VirtualTime time = 0;
  std::uint64_t scan = 0;

  // "seal_in.test:9: expect MOTOR == 1" (JUnit's message attribute).
  std::string summary() const;
  // The lines printed under "FAIL name", each starting with `indent`.
  std::string render(const std::string& indent = "    ") const;
};

// Coverage flags (vm/coverage.h) per program, in the order the programs were first seen.
using ProgramCoverage = std::vector<std::pair<const LoadedProgram*, std::vector<std::uint8_t>>>;
// ORs `flags` into the entry of `program`, appending one when it has none.
void merge_coverage(ProgramCoverage& into, const LoadedProgram* program, const std::vector<std::uint8_t>& flags);

struct TestOutcome {
  std::optional<Failure> failure;
  // With coverage on: the coverage of each program the test ran.
  ProgramCoverage coverage;
  // With tracing on: the test's signal trace as VCD text (tools/trace/trace.h).
  std::string trace_vcd;
  VirtualTime virtual_time = 0;  // at the end of the test
  std::uint64_t scans = 0;       // program scans the test ran
  bool passed() const { return !failure.has_value(); }
};

// Runs one test of `file_name` (used in failure locations). Every Runtime the test creates
// (at the start, at each restore and power cycle) gets `options` (a scan-time model, a module
// factory); the default is the runtime's own. Never throws: an unexpected exception from the
// runtime becomes a failure at the step that raised it.
// With `record_coverage`, every Runtime records ladder coverage and the outcome carries it.
// With `record_trace`, every address the program's ladder names is traced over the test (from its
// start, or from the last `restore`, which replays the snapshot) and the outcome carries the VCD.
TestOutcome run_test(const TestCase& test, const std::string& file_name, const RuntimeOptions& options = {},
                     bool record_coverage = false, bool record_trace = false);

}  // namespace softslc::testing
