#include "tools/testrunner/runner.h"

#include <fnmatch.h>
#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <set>
#include <thread>

#include "vm/atomic_file.h"

#include "tools/testrunner/coverage_report.h"
#include "tools/testrunner/executor.h"
#include "tools/testrunner/junit.h"
#include "tools/testrunner/test_loader.h"

namespace softslc::testing {

namespace fs = std::filesystem;

std::vector<TestFileRef> discover_test_files(const std::vector<std::string>& paths, std::vector<std::string>& errors) {
  std::vector<TestFileRef> found;
  std::set<std::string> seen;  // canonical paths, so a file named twice runs once
  auto add = [&](const fs::path& path, const fs::path& display) {
    std::error_code ec;
    const auto key = fs::weakly_canonical(path, ec);
    if (!seen.insert(ec ? path.string() : key.string()).second) return;
    found.push_back({path, display.lexically_normal().generic_string()});
  };
  for (const auto& p : paths) {
    const fs::path given(p);
    std::error_code ec;
    const auto st = fs::status(given, ec);
    if (ec || !fs::exists(st)) {
      errors.push_back("no such file or directory: '" + p + "'");
      continue;
    }
    if (!fs::is_directory(st)) {
      add(given, given);  // a file named explicitly runs whatever its extension
      continue;
    }
    std::vector<fs::path> files;
    fs::recursive_directory_iterator it(given, ec), end;
    for (; !ec && it != end; it.increment(ec)) {
      std::error_code fe;
      if (it->is_regular_file(fe) && it->path().extension() == ".test")
        files.push_back(it->path().lexically_relative(given));
    }
    if (ec) errors.push_back("cannot read directory '" + p + "': " + ec.message());
    // Sorted by the generic spelling so the order is the same on every file system.
    std::sort(files.begin(), files.end(),
              [](const fs::path& a, const fs::path& b) { return a.generic_string() < b.generic_string(); });
    for (const auto& rel : files) add(given / rel, given / rel);
  }
  return found;
}

bool glob_match(std::string_view pattern, std::string_view text) {
  // The shell's own matcher, fnmatch(3): '*', '?' and [...] as in the shell. Flags 0: '/' and a
  // leading '.' are ordinary characters in a test name.
  return ::fnmatch(std::string(pattern).c_str(), std::string(text).c_str(), 0) == 0;
}

std::string trace_file_name(const std::string& test_file, const std::string& test_name) {
  std::string name = std::filesystem::path(test_file).stem().string() + "." + test_name;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '.') c = '_';
  return name + ".vcd";
}

namespace {

struct Selected {
  const TestFile* file;
  const TestCase* test;
};

struct Result {
  TestOutcome outcome;
  std::int64_t host_ns = 0;
};

Result run_one(const Selected& s, const RuntimeOptions& options, bool coverage, bool trace, bool trace_all) {
  const auto t0 = std::chrono::steady_clock::now();
  Result r;
  r.outcome = run_test(*s.test, s.file->name, options, coverage, trace);
  // Only failing tests' traces are kept unless all were asked for: a passing test's VCD is dropped
  // at once, so memory holds only what will be written.
  if (r.outcome.passed() && !trace_all) r.outcome.trace_vcd.clear();
  r.host_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace

std::string format_result(const std::string& file, const std::string& name, const TestOutcome& outcome,
                          std::int64_t host_ns, bool host_times) {
  if (!outcome.passed()) return "FAIL " + file + ": " + name + "\n" + outcome.failure->render("    ");
  std::string line = "PASS " + file + ": " + name;
  if (host_times) line += " (" + std::to_string(host_ns / 1'000'000) + " ms)";
  return line + "\n";
}

int run_tests(const RunOptions& options, std::ostream& out, std::ostream& err) {
  if (options.paths.empty()) {
    err << "error: no test files or directories given\n";
    return kUsageError;
  }
  if (options.jobs < 0) {
    err << "error: --jobs must be 1 or more (0 = one per core)\n";
    return kUsageError;
  }

  // ---- Discover ----
  std::vector<std::string> errors;
  const auto refs = discover_test_files(options.paths, errors);
  for (const auto& e : errors) err << "error: " << e << "\n";
  if (!errors.empty()) return kUsageError;
  if (refs.empty()) {
    err << "error: no *.test files found\n";
    return kUsageError;
  }

  // ---- Load ----
  ProgramCache cache;
  cache.set_default_pasted_processor(options.pasted_processor);
  std::vector<TestFileLoad> files;
  files.reserve(refs.size());
  std::size_t bad = 0;
  for (const auto& ref : refs) {
    files.push_back(load_test_file(ref.path, ref.display, cache));
    const auto& f = files.back();
    if (!f.ok()) ++bad;
    if (!f.ok() || f.diagnostics.warning_count() > 0) err << f.render();
  }
  if (bad > 0) {
    err << "error: " << bad << " test file" << (bad == 1 ? " has" : "s have") << " errors; no test was run\n";
    return kUsageError;
  }
  // A report written over an input (--junit t.test, --coverage-json lamp.slc) would destroy it:
  // refuse before running anything. Inputs: every test file and the programs and benches they
  // name (resolved as the loader resolved them, relative to the test file).
  for (const auto& [option, output] : {std::pair<const char*, const std::string&>{"--junit", options.junit},
                                       std::pair<const char*, const std::string&>{"--coverage-json", options.coverage_json}}) {
    if (output.empty()) continue;
    std::vector<std::filesystem::path> inputs;
    for (std::size_t i = 0; i < refs.size(); ++i) {
      inputs.push_back(refs[i].path);
      for (const auto& t : files[i].file.tests)
        for (const auto* rel : {&t.program_path, &t.bench_path})
          if (!rel->empty()) inputs.push_back(refs[i].path.parent_path() / *rel);
    }
    for (const auto& in : inputs) {
      std::error_code ec;
      if (std::filesystem::equivalent(output, in, ec) && !ec) {
        err << "error: " << option << " " << output << " is an input of this run (" << in.string()
            << "); refusing to overwrite it\n";
        return kUsageError;
      }
    }
  }

  // ---- Select ----
  std::vector<Selected> selected;
  for (const auto& f : files)
    for (const auto& t : f.file.tests)
      if (options.filter.empty() || glob_match(options.filter, t.name)) selected.push_back({&f.file, &t});
  if (selected.empty()) {
    err << (options.filter.empty() ? std::string("error: the test files contain no tests\n")
                                   : "error: no test matches --filter '" + options.filter + "'\n");
    return kUsageError;
  }
  if (options.list) {
    for (const auto& s : selected) out << s.file->name << ": " << s.test->name << "\n";
    return kAllPassed;
  }

  // ---- Run and report in order ----
  const std::size_t n = selected.size();
  const bool coverage = options.coverage || !options.coverage_json.empty();
  std::size_t jobs = options.jobs > 0 ? static_cast<std::size_t>(options.jobs)
                                      : std::max<std::size_t>(1, std::thread::hardware_concurrency());
  jobs = std::min(jobs, n);
  std::vector<std::optional<Result>> results(n);
  std::mutex mutex;
  std::condition_variable ready;
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t i = next++; i < n; i = next++) {
      Result r = run_one(selected[i], options.runtime, coverage, !options.trace_dir.empty(), options.trace_all);
      {
        std::lock_guard<std::mutex> lock(mutex);
        results[i] = std::move(r);
      }
      ready.notify_all();
    }
  };
  std::vector<std::thread> threads;
  if (jobs > 1)
    for (std::size_t j = 0; j < jobs; ++j) threads.emplace_back(worker);
  else
    worker();  // one job: run on this thread, which keeps stack traces and debuggers simple

  std::size_t passed = 0, failed = 0;
  bool output_error = false;
  std::set<std::string> trace_names;
  if (!options.trace_dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(options.trace_dir, ec);
    if (ec) {
      err << "error: --trace-dir " << options.trace_dir << ": " << ec.message() << "\n";
      output_error = true;
    }
  }
  std::vector<JUnitCase> report;
  CoverageCollector covered;
  for (std::size_t i = 0; i < n; ++i) {
    {
      std::unique_lock<std::mutex> lock(mutex);
      ready.wait(lock, [&] { return results[i].has_value(); });
    }
    const Result& r = *results[i];
    out << format_result(selected[i].file->name, selected[i].test->name, r.outcome, r.host_ns, options.host_times);
    out.flush();
    (r.outcome.passed() ? passed : failed) += 1;
    if (!r.outcome.trace_vcd.empty() && !output_error) {
      // Two tests whose names differ only in replaced characters get -2, -3, ... in file order.
      std::string name = trace_file_name(selected[i].file->name, selected[i].test->name);
      for (int k = 2; !trace_names.insert(name).second; ++k)
        name = trace_file_name(selected[i].file->name, selected[i].test->name + "-" + std::to_string(k));
      const auto path = std::filesystem::path(options.trace_dir) / name;
      if (auto e = write_file_atomically(path, r.outcome.trace_vcd); !e.empty()) {
        err << "error: cannot write the trace: " << e << "\n";
        output_error = true;
      }
    }
    covered.add(r.outcome);
    report.push_back({selected[i].file->name, selected[i].test->name, selected[i].test->loc.line, r.host_ns,
                      r.outcome.virtual_time, r.outcome.scans, r.outcome.failure});
  }
  for (auto& t : threads) t.join();
  if (coverage) {
    // The coverage report comes before the summary, which stays the run's last line.
    std::string error;
    const auto reports = covered.reports(error);
    out << render_coverage_text(reports);
    if (!error.empty()) err << "error: coverage: " << error;
    if (!options.coverage_json.empty())
      if (auto e = write_file_atomically(options.coverage_json, render_coverage_json(reports)); !e.empty()) {
        err << "error: cannot write the coverage report: " << e << "\n";
        output_error = true;
      }
  }
  out << passed << " passed, " << failed << " failed\n";
  out.flush();

  if (!options.junit.empty()) {
    if (auto e = write_file_atomically(options.junit, junit_document(report)); !e.empty()) {
      err << "error: cannot write the JUnit report: " << e << "\n";
      return kUsageError;
    }
  }
  if (output_error) return kUsageError;
  return failed > 0 ? kTestsFailed : kAllPassed;
}

}  // namespace softslc::testing
