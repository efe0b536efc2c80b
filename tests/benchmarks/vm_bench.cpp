// Interpreter speed: ns per executed instruction on a generated bit-logic program, and the VM
// against a hand-written native C++ version of the same program.
//
// The generated program has one rung per index i:
//
//   SOR XIC a(i) XIO b(i) BST XIC c(i) NXB XIC d(i) BND OTE e(i) EOR
//
// with a, b, c input bits in B10, d a feedback bit among the outputs and e(i) the rung's own
// output bit in B11.. (see the address functions below). That is five instruction-table
// instructions per rung (plus the BST/NXB/BND structure).
//
// The native version is what a ladder-to-C++ compiler would emit for the same rungs: each rung's
// word indices and masks are fixed before the scan (here in a table built once, which costs what
// immediate operands in straight-line code cost), and the scan evaluates
// `out[e] = in[a] && !in[b] && (in[c] || out[d])` rung after rung. BM_VmVsNative runs both on
// identical data in the same iteration and reports vm_ns / native_ns as `ratio`.
//
// The VM is measured through Interpreter::program_scan directly (no I/O scan or housekeeping),
// with a watchdog that never fires.
#include <benchmark/benchmark.h>

#include <chrono>
#include <ctime>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "parser/loader.h"
#include "vm/compiler.h"
#include "vm/coverage.h"
#include "vm/interpreter.h"

namespace softslc {
namespace {

constexpr int kInBits = 4096;     // B10: 256 words
constexpr int kOutBits = 3 * 4096;  // B11-B13

int a_of(int i) { return (i * 7) % kInBits; }
int b_of(int i) { return (i * 13 + 5) % kInBits; }
int c_of(int i) { return (i * 31 + 11) % kInBits; }
int d_of(int i) { return (i * 17 + 3) % kOutBits; }
int e_of(int i) { return i % kOutBits; }

std::string in_bit(int n) { return "B10:" + std::to_string(n / 16) + "/" + std::to_string(n % 16); }
std::string out_bit(int n) {
  return "B" + std::to_string(11 + n / 4096) + ":" + std::to_string((n % 4096) / 16) + "/" + std::to_string(n % 16);
}

std::string generate_ladder(int rungs) {
  std::string s = "START 1747-L532\nLADDER 2\n";
  for (int i = 0; i < rungs; ++i)
    s += "SOR XIC " + in_bit(a_of(i)) + " XIO " + in_bit(b_of(i)) + " BST XIC " + in_bit(c_of(i)) + " NXB XIC " +
         out_bit(d_of(i)) + " BND OTE " + out_bit(e_of(i)) + " EOR\n";
  // Size every file fully (reading only, so the outputs stay the generated rungs' own).
  s += "SOR XIC B10:255/15 XIC B11:255/15 XIC B12:255/15 XIC B13:255/15 OTE B3:0/0 EOR\n";
  return s;
}

std::uint16_t input_pattern(int w) { return static_cast<std::uint16_t>(0x5A5Au ^ (w * 0x9E37u)); }

struct NoChassis final : ChassisAccess {
  MAccess read_m(int, MFile, int, std::uint16_t&) override { return MAccess::NoSuchWord; }
  MAccess write_m(int, MFile, int, std::uint16_t) override { return MAccess::NoSuchWord; }
  void immediate_input(int, int, int, std::uint16_t) override {}
  void immediate_output(int, int, int, std::uint16_t) override {}
};

// A compiled generated program with its data table, ready to scan.
struct VmFixture {
  CompiledProgram program;
  std::unique_ptr<DataTable> table;
  NoChassis chassis;
  DefaultScanTimeModel model;
  std::unique_ptr<Interpreter> interp;

  explicit VmFixture(int rungs) {
    LoadResult lr = load_program(generate_ladder(rungs), "bench.slc");
    if (!lr.ok()) throw std::runtime_error(lr.render_diagnostics());
    CompileResult cr = compile(*lr.program);
    if (!cr.ok()) throw std::runtime_error(cr.render());
    program = std::move(*cr.program);
    table = std::make_unique<DataTable>(program.layout, program.initial_words);
    const std::uint32_t b10 = program.layout->files[10].base;
    for (int w = 0; w < kInBits / 16; ++w) table->set_word(b10 + static_cast<std::uint32_t>(w), input_pattern(w));
    interp = std::make_unique<Interpreter>(program, *table, chassis, model);
  }
  ProgramScanResult scan() { return interp->program_scan(0, 0, false, INT64_MAX); }
};

// The hand-written native version: fixed word indices and masks per rung.
struct NativeRung {
  std::uint32_t a, b, c, d, e;
  std::uint16_t ma, mb, mc, md, me;
};

struct NativeFixture {
  std::vector<std::uint16_t> in = std::vector<std::uint16_t>(kInBits / 16);
  std::vector<std::uint16_t> out = std::vector<std::uint16_t>(kOutBits / 16);
  std::vector<NativeRung> rungs;

  explicit NativeFixture(int n) {
    for (int w = 0; w < kInBits / 16; ++w) in[static_cast<std::size_t>(w)] = input_pattern(w);
    auto word = [](int bit) { return static_cast<std::uint32_t>(bit / 16); };
    auto mask = [](int bit) { return static_cast<std::uint16_t>(1u << (bit % 16)); };
    for (int i = 0; i < n; ++i)
      rungs.push_back({word(a_of(i)), word(b_of(i)), word(c_of(i)), word(d_of(i)), word(e_of(i)), mask(a_of(i)),
                       mask(b_of(i)), mask(c_of(i)), mask(d_of(i)), mask(e_of(i))});
  }
  // Not inlined, so a profiler sees the native scan as one function, like the VM's program_scan.
  [[gnu::noinline]] void scan() {
    const std::uint16_t* const i = in.data();
    std::uint16_t* const o = out.data();
    for (const NativeRung& r : rungs) {
      const bool on = (i[r.a] & r.ma) && !(i[r.b] & r.mb) && ((i[r.c] & r.mc) || (o[r.d] & r.md));
      o[r.e] = static_cast<std::uint16_t>(on ? (o[r.e] | r.me) : (o[r.e] & ~r.me));
    }
  }
};

void BM_VmProgramScan(benchmark::State& state) {
  VmFixture vm(static_cast<int>(state.range(0)));
  std::uint64_t instructions = 0;
  for (auto _ : state) {
    ProgramScanResult r = vm.scan();
    instructions += r.instructions;
    benchmark::DoNotOptimize(r);
  }
  state.counters["instr/scan"] = static_cast<double>(instructions) / static_cast<double>(state.iterations());
  // Printed in seconds per instruction with an SI prefix (e.g. "3.1n" = 3.1 ns).
  state.counters["s/instr"] =
      benchmark::Counter(static_cast<double>(instructions), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_VmProgramScan)->Arg(1000)->Arg(10000)->Unit(benchmark::kMicrosecond);

// The same scan with ladder coverage recorded (softslc test --coverage): every instruction goes
// through the general switch and is reported to the recorder.
void BM_VmProgramScanWithCoverage(benchmark::State& state) {
  VmFixture vm(static_cast<int>(state.range(0)));
  CoverageRecorder recorder(vm.program);
  vm.interp->set_coverage(&recorder);
  std::uint64_t instructions = 0;
  for (auto _ : state) {
    ProgramScanResult r = vm.scan();
    instructions += r.instructions;
    benchmark::DoNotOptimize(r);
  }
  state.counters["s/instr"] =
      benchmark::Counter(static_cast<double>(instructions), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_VmProgramScanWithCoverage)->Arg(1000)->Unit(benchmark::kMicrosecond);

void BM_NativeScan(benchmark::State& state) {
  NativeFixture native(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    native.scan();
    benchmark::ClobberMemory();
  }
  state.counters["s/rung"] = benchmark::Counter(static_cast<double>(state.range(0)),
                                                benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_NativeScan)->Arg(1000)->Arg(10000)->Unit(benchmark::kMicrosecond);

// This thread's CPU time: the machine the figures come from is shared, and wall-clock time
// would charge either side for other processes' time slices.
std::chrono::nanoseconds thread_cpu_now() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return std::chrono::seconds(ts.tv_sec) + std::chrono::nanoseconds(ts.tv_nsec);
}

void BM_VmVsNative(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  VmFixture vm(n);
  NativeFixture native(n);
  // Both versions must compute the same outputs from the same inputs.
  vm.scan();
  native.scan();
  const std::uint32_t b11 = vm.program.layout->files[11].base;
  for (std::size_t w = 0; w < native.out.size(); ++w)
    if (vm.table->word(b11 + static_cast<std::uint32_t>(w)) != native.out[w]) {
      state.SkipWithError("VM and native outputs differ");
      return;
    }
  std::chrono::nanoseconds vm_time{0}, native_time{0};
  for (auto _ : state) {
    const auto t0 = thread_cpu_now();
    benchmark::DoNotOptimize(vm.scan());
    const auto t1 = thread_cpu_now();
    native.scan();
    benchmark::ClobberMemory();
    const auto t2 = thread_cpu_now();
    vm_time += t1 - t0;
    native_time += t2 - t1;
  }
  const double iters = static_cast<double>(state.iterations());
  state.counters["vm_us"] = static_cast<double>(vm_time.count()) / iters / 1e3;
  state.counters["native_us"] = static_cast<double>(native_time.count()) / iters / 1e3;
  state.counters["ratio"] = static_cast<double>(vm_time.count()) / static_cast<double>(std::max<std::int64_t>(native_time.count(), 1));
}
BENCHMARK(BM_VmVsNative)->Arg(1000)->Arg(10000)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace softslc

BENCHMARK_MAIN();
