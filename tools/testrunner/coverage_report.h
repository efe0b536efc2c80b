// `softslc test --coverage`: merging the ladder coverage of every test and reporting it.
//
// Each test returns the coverage flags of the programs it ran (executor.h); merge_coverage()
// ORs them per program, in the order the programs first appear in the run (so the report's order
// follows the test files, never thread timing), and builds one CoverageReport per program
// (vm/coverage.h). The text form is a summary table per program and the uncovered items as
// `PROGRAM:LINE: file F rung R instruction K TEXT: problem`; the JSON form (--coverage-json)
// carries the same numbers and items.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "tools/testrunner/executor.h"
#include "vm/coverage.h"

namespace softslc::testing {

class CoverageCollector {
 public:
  void add(const TestOutcome& outcome);
  // One report per program, in first-seen order. `error` collects programs that could not be
  // compiled again for the report (should not happen: they ran).
  std::vector<CoverageReport> reports(std::string& error) const;

 private:
  ProgramCoverage merged_;
};

std::string render_coverage_text(const std::vector<CoverageReport>& reports);
std::string render_coverage_json(const std::vector<CoverageReport>& reports);

}  // namespace softslc::testing
