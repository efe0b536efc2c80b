// Helpers for the module tests: a program (export text) plus a bench (bench text) -> a Runtime
// built through the same loader the CLI and the test runner use (modules/module_setup.h).
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>

#include "modules/module_setup.h"
#include "modules/sn/rio_scanner.h"
#include "parser/loader.h"
#include "vm/runtime.h"

namespace softslc::test {

inline std::string read_text(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw std::runtime_error("cannot read " + path);
  std::ostringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

inline std::string example_path(const std::string& name) {
  return std::string(SOFTSLC_SOURCE_DIR) + "/examples/ladder/1747-sn/" + name;
}

struct Bench {
  LoadResult load;
  ModuleSetup setup;
  std::unique_ptr<Runtime> rt;

  // Loads the program and bench; `allow_errors` builds the runtime even when the module setup
  // reports configuration errors (to reach the run-time faults).
  Bench(const std::string& program, const std::string& bench, bool allow_errors = false)
      : load(load_program(program, "test.slc")) {
    if (!load.ok()) throw std::runtime_error("program did not load:\n" + load.render_diagnostics());
    setup = bench.empty() ? setup_modules(*load.program, nullptr) : load_module_setup_text(*load.program, bench, "test.bench");
    if (!setup.ok() && !allow_errors)
      throw std::runtime_error("module setup failed:\n" + setup.render("test.slc", load.source));
    auto r = Runtime::create(*load.program, setup.options);
    if (!r.ok()) throw std::runtime_error("program did not compile:\n" + r.render_errors());
    rt = std::move(r.runtime);
  }
  static Bench example(const std::string& slc, const std::string& bench) {
    return Bench(read_text(example_path(slc)), read_text(example_path(bench)));
  }

  Runtime* operator->() { return rt.get(); }
  RioScanner& sn(int slot = 1) {
    auto* s = dynamic_cast<RioScanner*>(rt->module(slot));
    if (!s) throw std::runtime_error("no 1747-SN in slot " + std::to_string(slot));
    return *s;
  }
  std::int64_t i(std::string_view a) const { return rt->value(a).as_int(); }
  std::uint16_t u(std::string_view a) const { return static_cast<std::uint16_t>(rt->value(a).as_int()); }
  bool b(std::string_view a) const { return rt->value(a).as_bool(); }
  void set(std::string_view a, std::int64_t v) {
    auto st = rt->set(a, Value::of_int(v));
    if (!st) throw std::runtime_error(st.message);
  }
  void run() {
    auto st = rt->set_mode(Mode::Run);
    if (!st) throw std::runtime_error(st.message);
  }
  void inject(std::string_view device, std::string_view fault, std::vector<std::string> args = {}) {
    auto st = rt->inject(device, fault, std::move(args));
    if (!st) throw std::runtime_error(st.message);
  }
  std::uint16_t m1(int word, int slot = 1) { return sn(slot).m1().at(static_cast<std::size_t>(word)); }
  std::uint16_t m0(int word, int slot = 1) { return sn(slot).m0().at(static_cast<std::size_t>(word)); }
  std::uint16_t fault_code() const { return rt->fault() ? rt->fault()->code : 0; }
  // Runs scans until `pred` holds; fails the test (returns false) after `limit`.
  template <typename P>
  bool until(P pred, Nanoseconds limit) {
    return rt->run_until([&](const Runtime&) { return pred(); }, limit);
  }
};

}  // namespace softslc::test
