// Simulation speed and load time.
//
// BM_Simulate/<example>: every shipped example program (examples/ladder/**/*.slc) with its bench
// file when one sits beside it, loaded through the public Controller API exactly as `softslc
// test` loads it, then run in virtual time. The counter `x_realtime` is virtual seconds per CPU
// second of this thread (the machine the figures come from is shared, so CPU time, not wall time).
// An example that faults in its first second of virtual time (the fault-injection examples do
// so on purpose) is reported as an error with its fault, not timed. Each example restarts from a
// fresh load (outside the timing) after 100 s of virtual time: a fast run simulates hours, and
// some examples count transfers in a 16-bit word that overflows (fault 0020h) long before that.
//
// BM_SimulateNetwork/<test file>: every shipped example's test file that puts its program on a MSG
// network with other controllers (`peer` lines, docs/testing.md), the program and its peers built
// as that file's first such test builds them (tools/testrunner/test_loader.h), then run in virtual
// time like BM_Simulate. `x_realtime` is virtual seconds of the whole network per CPU second, every
// controller's scans included. An MSG example alone (BM_Simulate) has nobody to talk to and, on
// Ethernet, no IP address: it measures the failure path; with its peers it runs what it was written
// for (docs/performance.md "Examples with their peers").
//
// BM_LoadProgram/<rungs>: parse + check + compile of a generated program from 1,000 to 1,000,000
// rungs (the mix of parse_bench.cpp: contacts, branches, TON, CTU, ADD, GEQ, MOV, OTL, OTE), split
// into program files of at most 50,000 rungs that file 2 calls with JSR (a file holds at most
// 65,535 rungs). `peak_MB` is the process's peak resident set after the load (getrusage), so run
// one size per process to read it: --benchmark_filter='BM_LoadProgram/1000000$'.
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <string>

#include "tests/benchmarks/generated_rung.h"
#include <vector>

#include "parser/loader.h"
#include "tools/testrunner/test_loader.h"
#include "tools/controller/controller.h"
#include "vm/compiler.h"

namespace softslc {
namespace {

namespace fs = std::filesystem;

// Runs the runtime `start` builds in slices of 100 ms of virtual time and reports virtual seconds per CPU
// second. `start` is called again (outside the timing) after 100 s of virtual time; it returns null
// after SkipWithError when what it builds does not build.
void run_in_slices(benchmark::State& state, const std::function<Runtime*()>& start) {
  constexpr Nanoseconds kSlice = milliseconds(100);
  constexpr Nanoseconds kRestartAfter = milliseconds(100'000);
  Runtime* rt = start();
  if (!rt) return;
  Nanoseconds simulated = 0;
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores): Google Benchmark's loop variable
    if (rt->now() >= kRestartAfter) {
      state.PauseTiming();
      rt = start();
      state.ResumeTiming();
      if (!rt) return;
    }
    const VirtualTime before = rt->now();
    rt->run_for(kSlice);
    if (rt->fault()) {
      state.SkipWithError(("faults: " + rt->fault()->to_string()).c_str());
      return;
    }
    simulated += rt->now() - before;
  }
  state.counters["x_realtime"] = benchmark::Counter(static_cast<double>(simulated) / 1e9, benchmark::Counter::kIsRate);
  state.counters["scan_us"] = static_cast<double>(rt->stats().avg()) / 1e3;
}

void BM_Simulate(benchmark::State& state, const fs::path& program, const std::optional<fs::path>& bench) {
  std::optional<Controller> plc;
  run_in_slices(state, [&]() -> Runtime* {
    try {
      plc.emplace(Controller::load(program, bench));
    } catch (const std::exception& e) {
      state.SkipWithError(e.what());
      return nullptr;
    }
    return &plc->runtime();
  });
}

void BM_SimulateNetwork(benchmark::State& state, const fs::path& test_file) {
  testing::ProgramCache cache;
  const testing::TestFileLoad load = testing::load_test_file(test_file, test_file.string(), cache);
  if (!load.ok()) {
    state.SkipWithError(load.render().substr(0, 500).c_str());
    return;
  }
  const auto with_peers = std::find_if(load.file.tests.begin(), load.file.tests.end(),
                                       [](const testing::TestCase& t) { return !t.peers.empty(); });
  if (with_peers == load.file.tests.end()) {
    state.SkipWithError("no test of this file has peers");
    return;
  }
  const std::shared_ptr<const testing::LoadedProgram> program = with_peers->program;
  std::unique_ptr<Runtime> rt;
  run_in_slices(state, [&]() -> Runtime* {
    RuntimeResult r = Runtime::create(program->program, program->modules);
    if (!r.ok() || !r.runtime->set_mode(Mode::Run)) {  // the leader takes its peers along
      state.SkipWithError("the network did not build");
      return nullptr;
    }
    rt = std::move(r.runtime);
    return rt.get();
  });
}

std::string generate_program(int rungs) {
  constexpr int kPerFile = 50'000;
  const int files = (rungs + kPerFile - 1) / kPerFile;
  std::string s =
      "START 1747-L552\nSLOT 1 1746-IB16 SCAN_IN 1 SCAN_OUT 0\nSLOT 2 1746-OB16 SCAN_IN 0 SCAN_OUT 1\nLADDER 2\n";
  if (files > 1)
    for (int f = 0; f < files; ++f) s += "SOR JSR " + std::to_string(10 + f) + " EOR\n";
  for (int i = 0; i < rungs; ++i) {
    if (files > 1 && i % kPerFile == 0) s += "LADDER " + std::to_string(10 + i / kPerFile) + "\nSOR SBR OTE B3:255/0 EOR\n";
    s += bench::generated_rung(i);
  }
  return s;
}

void BM_LoadProgram(benchmark::State& state) {
  const int rungs = static_cast<int>(state.range(0));
  const std::string text = generate_program(rungs);
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores): Google Benchmark's loop variable
    LoadResult lr = load_program(text, "generated.slc");
    if (!lr.ok()) {
      state.SkipWithError(lr.render_diagnostics().substr(0, 500).c_str());
      return;
    }
    CompileResult cr = compile(*lr.program);
    if (!cr.ok()) {
      state.SkipWithError(cr.render().substr(0, 500).c_str());
      return;
    }
    benchmark::DoNotOptimize(cr);
  }
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  state.counters["peak_MB"] = static_cast<double>(ru.ru_maxrss) / 1024.0;
  state.counters["rungs/s"] = benchmark::Counter(static_cast<double>(rungs), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["text_MB"] = static_cast<double>(text.size()) / 1e6;
}
BENCHMARK(BM_LoadProgram)->Arg(1'000)->Arg(10'000)->Arg(100'000)->Arg(1'000'000)->Unit(benchmark::kMillisecond);

// One benchmark per shipped example, in path order, and one per test file with peers.
void register_examples() {
  std::vector<fs::path> programs;
  std::vector<fs::path> test_files;
  const fs::path root = fs::path(SOFTSLC_SOURCE_DIR) / "examples" / "ladder";
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    if (!e.is_regular_file()) continue;
    if (e.path().extension() == ".slc") programs.push_back(e.path());
    if (e.path().extension() == ".test") test_files.push_back(e.path());
  }
  std::sort(programs.begin(), programs.end());
  std::sort(test_files.begin(), test_files.end());
  for (const auto& p : programs) {
    fs::path bench = p;
    bench.replace_extension(".bench");
    const std::optional<fs::path> b = fs::exists(bench) ? std::optional<fs::path>(bench) : std::nullopt;
    const std::string name = "BM_Simulate/" + fs::relative(p, root).string();
    benchmark::RegisterBenchmark(name.c_str(), [p, b](benchmark::State& st) { BM_Simulate(st, p, b); })
        ->Unit(benchmark::kMillisecond);
  }
  for (const auto& t : test_files) {
    // A test file with peers names them on a file-level `peer` line; the others are not registered.
    testing::ProgramCache cache;
    const testing::TestFileLoad load = testing::load_test_file(t, t.string(), cache);
    const bool has_peers = std::any_of(load.file.tests.begin(), load.file.tests.end(),
                                       [](const testing::TestCase& c) { return !c.peers.empty(); });
    if (!has_peers) continue;
    const std::string name = "BM_SimulateNetwork/" + fs::relative(t, root).string();
    benchmark::RegisterBenchmark(name.c_str(), [t](benchmark::State& st) { BM_SimulateNetwork(st, t); })
        ->Unit(benchmark::kMillisecond);
  }
}

}  // namespace
}  // namespace softslc

int main(int argc, char** argv) {
  // The analyzer sees RegisterBenchmark's `new` and no delete: the library keeps what it registers.
  softslc::register_examples();  // NOLINT(clang-analyzer-cplusplus.NewDeleteLeaks)
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
