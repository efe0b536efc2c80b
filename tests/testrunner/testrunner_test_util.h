// Helpers for the test-runner tests: a sandbox directory holding the small programs of
// tests/testrunner/data/ and the test files a test writes, and ways to run them.
//
// Sandbox::run(text) loads `text` as the test file "t.test" beside the programs and runs its tests
// in order on the calling thread, returning exactly what `softslc test` would print for them
// without host times (or the diagnostics, when the file has errors), so tests can compare whole
// outputs. Sandbox::command(options) runs the real command on sandbox paths and strips the
// sandbox directory from its output so expectations do not depend on where it was created.
//
// data/lamp.slc (a 5/03, inputs in slot 1, outputs in slot 2):
//   rung 0  XIC SWITCH (I:1/0) OTE LAMP (O:2/0)
//   rung 1  XIC I:1/1 TON T4:0 0.01 50 0          0.5 s on-delay
//   rung 2  XIC T4:0/DN OTE DELAYED (O:2/1)
//   rung 3  XIC I:1/2 ADD N7:0 N7:1 N7:2          overflow -> S:5/0 -> fault 0020h at END
//   rung 4  XIC I:1/3 OTL LATCH (B3:0/1)
//   rung 5  XIC I:1/4 OTU LATCH
//   rung 6  XIC I:1/5 CTU C5:0 100 0
//   DATA N7:0 = 10 20 0 0, N11:0 = 000E 000F 0010 FFFF, F8:0 = 0.1 2.5
// data/other.slc: XIC I:1/0 OTE GREEN (O:2/5).
//
// Timing: the runtime's default scan-time model is being refined (per-processor profiles), so the
// sandbox runs every test with FixedScanTimeModel: each instruction 1 us whatever its rung state,
// module I/O free, 1 ms housekeeping. A scan of lamp.slc (14 instructions) is then exactly
// 1.014 ms, and the virtual times in expected failure messages follow from that alone.
#pragma once

#include <gtest/gtest.h>
#include <stdlib.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tools/testrunner/executor.h"
#include "tools/testrunner/runner.h"
#include "tools/testrunner/test_loader.h"
#include "vm/scan_time_model.h"

namespace softslc::testing::test {

class FixedScanTimeModel : public ScanTimeModel {
 public:
  std::string_view name() const override { return "fixed (tests)"; }
  Nanoseconds instruction_cost(Opcode, bool) const override { return microseconds(1); }
  Nanoseconds input_scan_cost(const Module&) const override { return 0; }
  Nanoseconds output_scan_cost(const Module&) const override { return 0; }
  Nanoseconds housekeeping_cost() const override { return milliseconds(1); }
};

inline RuntimeOptions fixed_timing() {
  RuntimeOptions o;
  o.time_model = std::make_shared<FixedScanTimeModel>();
  return o;
}

inline std::filesystem::path data_dir() { return std::filesystem::path(SOFTSLC_SOURCE_DIR) / "tests/testrunner/data"; }

inline std::string read_text(const std::filesystem::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

inline void write_text(const std::filesystem::path& p, const std::string& text) {
  if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
  std::ofstream f(p, std::ios::binary);
  f << text;
}

inline std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (auto at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) s.replace(at, from.size(), to);
  return s;
}

// Removes the host milliseconds of PASS lines (" (12 ms)"), the only part of the output that
// varies between runs. (No std::regex: GCC 12 warns inside <regex> under the sanitizers.)
inline std::string strip_host_ms(const std::string& s) {
  std::string out;
  std::size_t at = 0;
  for (;;) {
    const auto open = s.find(" (", at);
    if (open == std::string::npos) break;
    std::size_t i = open + 2;
    while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) ++i;
    if (i > open + 2 && s.compare(i, 5, " ms)\n") == 0) {
      out.append(s, at, open - at);
      at = i + 4;  // keep the newline
    } else {
      out.append(s, at, open + 2 - at);
      at = open + 2;
    }
  }
  return out + s.substr(at);
}

class Sandbox {
 public:
  Sandbox() {
    std::string tmpl = (std::filesystem::temp_directory_path() / "softslc-testrunner-XXXXXX").string();
    if (!::mkdtemp(tmpl.data())) throw std::runtime_error("mkdtemp failed");
    dir_ = tmpl;
    for (const char* name : {"lamp.slc", "other.slc"}) std::filesystem::copy_file(data_dir() / name, dir_ / name);
  }
  ~Sandbox() {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  Sandbox(const Sandbox&) = delete;
  Sandbox& operator=(const Sandbox&) = delete;

  const std::filesystem::path& dir() const { return dir_; }

  std::filesystem::path write(const std::string& name, const std::string& text) {
    write_text(dir_ / name, text);
    return dir_ / name;
  }

  TestFileLoad load(const std::string& text) {
    ProgramCache cache;
    return load_test_text(text, "t.test", dir_, cache);
  }

  // The rendered diagnostics of `text` as t.test (empty when it loads cleanly).
  std::string diagnostics(const std::string& text) { return load(text).render(); }

  // What `softslc test` prints for t.test, without host times (diagnostics if it has errors).
  std::string run(const std::string& text) {
    ProgramCache cache;
    TestFileLoad f = load_test_text(text, "t.test", dir_, cache);
    if (!f.ok()) return f.render();
    std::string out;
    for (const auto& t : f.file.tests)
      out += format_result("t.test", t.name, run_test(t, "t.test", fixed_timing()), 0, false);
    return out;
  }

  struct Command {
    int rc = 0;
    std::string out, err;
  };

  // Runs the command on paths relative to the sandbox.
  Command command(RunOptions o) {
    for (auto& p : o.paths) p = (dir_ / p).string();
    if (!o.junit.empty()) o.junit = (dir_ / o.junit).string();
    if (!o.runtime.time_model) o.runtime = fixed_timing();
    std::ostringstream out, err;
    Command c;
    c.rc = run_tests(o, out, err);
    c.out = strip(out.str());
    c.err = strip(err.str());
    return c;
  }

  std::string strip(const std::string& s) const { return replace_all(s, dir_.string() + "/", ""); }

 private:
  std::filesystem::path dir_;
};

}  // namespace softslc::testing::test
