// The test runner: find test files, load them, run the selected tests in parallel, report.
//
// A run has four phases, each finished before the next starts:
//   discover  every path is a test file, or a directory searched recursively for *.test files
//             (sorted by path, so the order never depends on the file system);
//   load      every file is parsed and checked against its programs (test_loader.h); any error
//             in any file stops the run before a single test executes, with gcc-style
//             diagnostics on the error stream and exit code 2;
//   run       the selected tests (--filter) execute on --jobs worker threads, each test in its
//             own Runtime; workers take tests in order from a shared counter and store results
//             by index;
//   report    results are printed strictly in file order then test order, as soon as every
//             earlier test has finished, never in completion order, then the line
//             "N passed, N failed", then the JUnit report if asked.
// Apart from the host milliseconds on PASS lines (which RunOptions::host_times can turn off) the
// output is byte-identical for any --jobs value and on every machine.
//
// Exit codes: 0 every selected test passed; 1 at least one failed; 2 usage or input problem
// (no such path, no test files, a test file or program with errors, no test selected, the JUnit
// report could not be written).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "instructions/processor.h"
#include "tools/testrunner/executor.h"

namespace softslc::testing {

enum ExitCode : int { kAllPassed = 0, kTestsFailed = 1, kUsageError = 2 };

struct RunOptions {
  std::vector<std::string> paths;  // test files and directories
  std::string filter;              // glob on test names ('*' and '?'); empty = all
  std::string junit;               // JUnit XML report path; empty = none
  bool list = false;               // print the selected tests instead of running them
  int jobs = 0;                    // worker threads; 0 = the host's hardware concurrency
  bool host_times = true;          // "(12 ms)" on PASS lines
  bool coverage = false;           // report ladder coverage (before the summary line)
  std::string coverage_json;       // also write it as JSON here (implies coverage); empty = none
  RuntimeOptions runtime;          // for every Runtime a test creates (tests fix the scan-time model)
  std::string trace_dir;           // write a VCD per failing test here; empty = none
  bool trace_all = false;          // with trace_dir: a VCD for every test, passed or not
  // The processor of pasted-rung programs whose test file names none (`--processor`).
  std::optional<ProcessorModel> pasted_processor;
};

struct TestFileRef {
  std::filesystem::path path;  // where to read it
  std::string display;         // how messages name it
};

// Expands `paths` into test files in run order. Appends a message to `errors` for each path that
// does not exist or cannot be read.
std::vector<TestFileRef> discover_test_files(const std::vector<std::string>& paths, std::vector<std::string>& errors);

// Glob match of a whole test name, by fnmatch(3): '*' matches any run of characters, '?' any one character,
// [...] one of a set.
bool glob_match(std::string_view pattern, std::string_view text);

// The lines printed for one test: "PASS FILE: NAME (12 ms)", or "FAIL FILE: NAME" and the
// failure (executor.h), each line ending in '\n'.
std::string format_result(const std::string& file, const std::string& name, const TestOutcome& outcome,
                          std::int64_t host_ns, bool host_times);

// The file name of a test's trace: the test file's stem and the test's name, every character other
// than a letter, digit, '-' or '.' replaced by '_', then ".vcd".
std::string trace_file_name(const std::string& test_file, const std::string& test_name);

// Runs the whole command: discovery, loading, running and reporting. Test results and the summary
// go to `out`, diagnostics and usage errors to `err`. Returns an ExitCode.
int run_tests(const RunOptions& options, std::ostream& out, std::ostream& err);

}  // namespace softslc::testing
