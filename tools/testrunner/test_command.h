// Entry point of `softslc test`: the options the command line parses, and the command itself.
//
// The CLI (tools/softslc/main.cpp) fills a TestCommandOptions with CLI11 and calls
// run_test_command(); everything else (discovery, parallel run, output, JUnit) lives in the
// runner library (runner.h), so the test suite exercises exactly what users run. Output goes to
// the given streams, never to std::cout directly, so tests can capture it.
//
// Exit codes (also in docs/testing.md): 0 all selected tests passed, 1 some test failed, 2 usage
// or input error (bad path, no test files, errors in a test file or its program, nothing matches
// --filter, the JUnit report could not be written).
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace softslc::testing {

struct TestCommandOptions {
  std::vector<std::string> paths;  // test files and directories (searched recursively for *.test)
  std::string filter;              // glob on test names; empty = all
  std::string junit;               // write a JUnit XML report here; empty = none
  bool list = false;               // list the selected tests, run nothing
  int jobs = 0;                    // parallel tests; 0 = one per hardware thread
  bool coverage = false;           // print ladder coverage
  std::string coverage_json;       // write ladder coverage as JSON here; empty = none
  std::string trace_dir;           // write a VCD per failing test here (docs/traces.md); empty = none
  bool trace_all = false;          // with trace_dir: every test's VCD
  std::string processor;           // CATALOG[:SERIES] of pasted-rung programs whose test file names none
};

int run_test_command(const TestCommandOptions& options, std::ostream& out, std::ostream& err);

}  // namespace softslc::testing
