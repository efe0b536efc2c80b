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

#include <algorithm>
#include <chrono>
#include <cstring>
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
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores): Google Benchmark's loop variable
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
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores): Google Benchmark's loop variable
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
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores): Google Benchmark's loop variable
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
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores): Google Benchmark's loop variable
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

// ---- A mixed program: timers, counters, compares, math, COP and JSR, beside its native twin ----
//
// Block i (element e = i % kMixedElements) is six rungs:
//
//   SOR XIC B10:e/0 TON T4:e 0.01 5 0 EOR           on-delay timer, 50 ms
//   SOR XIC T4:e/DN CTU C5:e 30000 0 EOR            count the timer's done edges
//   SOR XIC T4:e/DN RES T4:e EOR                    restart the timer when done
//   SOR GRT N20:e N7:e MOV N20:e N21:e EOR          compare, then move
//   SOR XIC B10:e/1 ADD N20:e N7:e N22:e EOR        math with S:0 flags
//   SOR XIC B10:e/2 BST COP #N20:e #N23:e 4 NXB JSR 3 BND EOR    file copy and a subroutine call
//
// and file 3 is `SBR XIC B10:0/3 OTE B11:0/0; ADD N7:0 1 N24:0; RET`. Each program scan runs 10 ms
// of virtual time after the previous one, so the timers time, finish and restart. The native twin
// is the same logic written directly in C++ over a copy of the same data table (the RM 2-9 timer
// with the 10 ms tick stamp, the RM 2-14 counter edge, ADD's S:0 flags, COP's S:24), checked
// equal to the VM's data table after the first scans.
constexpr int kMixedElements = 250;

std::string generate_mixed(int blocks) {
  std::string s = "START 1747-L532\nLADDER 2\n";
  for (int i = 0; i < blocks; ++i) {
    const std::string e = std::to_string(i % kMixedElements);
    s += "SOR XIC B10:" + e + "/0 TON T4:" + e + " 0.01 5 0 EOR\n";
    s += "SOR XIC T4:" + e + "/DN CTU C5:" + e + " 30000 0 EOR\n";
    s += "SOR XIC T4:" + e + "/DN RES T4:" + e + " EOR\n";
    s += "SOR GRT N20:" + e + " N7:" + e + " MOV N20:" + e + " N21:" + e + " EOR\n";
    s += "SOR XIC B10:" + e + "/1 ADD N20:" + e + " N7:" + e + " N22:" + e + " EOR\n";
    s += "SOR XIC B10:" + e + "/2 BST COP #N20:" + e + " #N23:" + e + " 4 NXB JSR 3 BND EOR\n";
  }
  // Size the files fully (B10, N7 and N20-N23 to 254 elements), reading only.
  s += "SOR XIC B10:253/15 EQU N7:253 N20:253 EQU N21:253 N22:253 XIC B11:0/15 OTE B3:0/0 EOR\n";
  s += "LADDER 3\nSOR SBR XIC B10:0/3 OTE B11:0/0 EOR\nSOR ADD N7:0 1 N24:0 EOR\nSOR RET EOR\n";
  return s;
}

struct MixedNative {
  std::vector<std::uint16_t> w;
  std::uint32_t b10 = 0, b11 = 0, t4 = 0, c5 = 0, n7 = 0, n20 = 0, n21 = 0, n22 = 0, n23 = 0, n24 = 0, s0 = 0, s24 = 0;
  int blocks = 0;

  void add(std::int32_t a, std::int32_t b, std::uint32_t dest) {
    std::int32_t r = a + b;
    bool v = false;
    if (r > 32767 || r < -32768) {
      v = true;
      r = r > 32767 ? 32767 : -32768;
    }
    const bool c = ((static_cast<std::uint32_t>(a) & 0xFFFF) + (static_cast<std::uint32_t>(b) & 0xFFFF)) > 0xFFFF;
    w[dest] = static_cast<std::uint16_t>(r);
    w[s0] = static_cast<std::uint16_t>((w[s0] & ~0xFu) | (c ? 1u : 0u) | (v ? 2u : 0u) | (r == 0 ? 4u : 0u) | (r < 0 ? 8u : 0u));
  }
  // File 3.
  [[gnu::noinline]] void sub(Nanoseconds& t) {
    const bool in = (w[b10] >> 3) & 1u;
    t += kIn + kIn + (in ? kOutTrue : kOutFalse) + kOutTrue + kOutTrue;  // SBR XIC OTE, ADD, RET
    w[b11] = static_cast<std::uint16_t>((w[b11] & ~1u) | (in ? 1u : 0u));
    add(static_cast<std::int16_t>(w[n7]), 1, n24);
  }
  // The scan time so far matters: a timer reads the tick count at its own virtual time. These
  // are the default model's charges (vm/scan_time_model.h), added as the VM adds them.
  static constexpr Nanoseconds kIn = DefaultScanTimeModel::kInputInstruction;
  static constexpr Nanoseconds kOutTrue = DefaultScanTimeModel::kOutputTrue;
  static constexpr Nanoseconds kOutFalse = DefaultScanTimeModel::kOutputFalse;
  static Nanoseconds out(bool rung) { return rung ? kOutTrue : kOutFalse; }

  [[gnu::noinline]] void scan(VirtualTime now) {
    Nanoseconds t = 0;
    for (int i = 0; i < blocks; ++i) {
      const auto e = static_cast<std::uint32_t>(i % kMixedElements);
      const std::uint16_t in = w[b10 + e];
      t += kIn + out(in & 1u);
      const auto now8 = static_cast<std::uint8_t>((now + t) / kTick);
      // TON, 0.01 s time base (RM 2-9).
      std::uint16_t* tm = &w[t4 + 3 * e];
      if (!(in & 1u)) {
        tm[0] &= static_cast<std::uint16_t>(~(bits::kEN | bits::kTT | bits::kDN));
        tm[2] = 0;
      } else {
        int acc = static_cast<std::int16_t>(tm[2]);
        const int pre = static_cast<std::int16_t>(tm[1]);
        if (!(tm[0] & bits::kEN)) {
          tm[0] = static_cast<std::uint16_t>((tm[0] & ~bits::kStampMask) | now8);
        } else if (acc < pre) {
          const auto stamp = static_cast<std::uint8_t>(tm[0] & bits::kStampMask);
          acc = std::min(pre, acc + static_cast<std::uint8_t>(now8 - stamp));
          tm[0] = static_cast<std::uint16_t>((tm[0] & ~bits::kStampMask) | now8);
        }
        tm[0] |= bits::kEN;
        tm[0] = static_cast<std::uint16_t>(acc >= pre ? ((tm[0] | bits::kDN) & ~bits::kTT) : ((tm[0] | bits::kTT) & ~bits::kDN));
        tm[2] = static_cast<std::uint16_t>(acc);
      }
      // CTU on the done bit's rising edge (RM 2-14).
      const bool dn = (tm[0] & bits::kDN) != 0;
      t += kIn + out(dn) + kIn + out(dn);  // the CTU rung and the RES rung
      std::uint16_t* c = &w[c5 + 3 * e];
      if (dn && !(c[0] & bits::kCU)) c[2] = static_cast<std::uint16_t>(static_cast<std::int16_t>(c[2]) + 1);
      c[0] = static_cast<std::uint16_t>(dn ? (c[0] | bits::kCU) : (c[0] & ~bits::kCU));
      c[0] = static_cast<std::uint16_t>(static_cast<std::int16_t>(c[2]) >= static_cast<std::int16_t>(c[1])
                                            ? (c[0] | bits::kDN)
                                            : (c[0] & ~bits::kDN));
      if (tm[0] & bits::kDN) {
        tm[0] &= static_cast<std::uint16_t>(~(bits::kEN | bits::kTT | bits::kDN));
        tm[2] = 0;
      }
      // GRT, then MOV (Z and S from the value, C and V cleared).
      const auto a = static_cast<std::int16_t>(w[n20 + e]);
      const auto b = static_cast<std::int16_t>(w[n7 + e]);
      t += kIn + out(a > b) + kIn + out(in & 2u) + kIn + out(in & 4u) + out(in & 4u);
      if (a > b) {
        w[n21 + e] = static_cast<std::uint16_t>(a);
        w[s0] = static_cast<std::uint16_t>((w[s0] & ~0xFu) | (a == 0 ? 4u : 0u) | (a < 0 ? 8u : 0u));
      }
      if (in & 2u) add(a, b, n22 + e);
      if (in & 4u) {
        std::memmove(&w[n23 + e], &w[n20 + e], 4 * sizeof(std::uint16_t));
        w[s24] = 3;
        sub(t);
      }
    }
  }
};

struct MixedFixture {
  CompiledProgram program;
  std::unique_ptr<DataTable> table;
  NoChassis chassis;
  DefaultScanTimeModel model;
  std::unique_ptr<Interpreter> interp;
  MixedNative native;
  VirtualTime now = 0;

  explicit MixedFixture(int blocks) {
    LoadResult lr = load_program(generate_mixed(blocks), "mixed.slc");
    if (!lr.ok()) throw std::runtime_error(lr.render_diagnostics());
    CompileResult cr = compile(*lr.program);
    if (!cr.ok()) throw std::runtime_error(cr.render());
    program = std::move(*cr.program);
    table = std::make_unique<DataTable>(program.layout, program.initial_words);
    const auto& f = program.layout->files;
    // Inputs and operands small enough that ADD never overflows (an overflow trap left set at
    // END is a major fault).
    for (std::uint32_t e = 0; e < 254; ++e) {
      table->set_word(f[10].base + e, input_pattern(static_cast<int>(e)));
      table->set_word(f[20].base + e, static_cast<std::uint16_t>(input_pattern(static_cast<int>(e) + 7) & 0x3FF));
      table->set_word(f[7].base + e, static_cast<std::uint16_t>(input_pattern(static_cast<int>(e) + 3) & 0x3FF));
    }
    interp = std::make_unique<Interpreter>(program, *table, chassis, model);
    native.w.assign(table->words(), table->words() + program.layout->total_words);
    native.b10 = f[10].base;
    native.b11 = f[11].base;
    native.t4 = f[4].base;
    native.c5 = f[5].base;
    native.n7 = f[7].base;
    native.n20 = f[20].base;
    native.n21 = f[21].base;
    native.n22 = f[22].base;
    native.n23 = f[23].base;
    native.n24 = f[24].base;
    native.s0 = program.layout->status_word(status::kArith);
    native.s24 = program.layout->status_word(status::kIndex);
    native.blocks = blocks;
  }
  ProgramScanResult vm_scan() { return interp->program_scan(now, 0, false, INT64_MAX); }
  void native_scan() { native.scan(now); }
  // The first word (outside the status file) where the two differ, or -1.
  std::int64_t first_difference() const {
    const std::uint32_t from = program.layout->files[3].base;
    for (std::uint32_t i = from; i < program.layout->total_words; ++i)
      if (table->word(i) != native.w[i]) return i;
    return -1;
  }
};

void BM_MixedVmVsNative(benchmark::State& state) {
  const int blocks = static_cast<int>(state.range(0)) / 6;
  MixedFixture fx(blocks);
  for (int k = 0; k < 20; ++k, fx.now += kTick) {
    const ProgramScanResult r = fx.vm_scan();
    fx.native_scan();
    const std::int64_t d = fx.first_difference();
    if (r.faulted || d >= 0) {
      state.SkipWithError(r.faulted ? r.fault.to_string().c_str()
                                    : ("VM and native differ at " + fx.program.layout->describe(static_cast<std::uint32_t>(d)) +
                                       " after scan " + std::to_string(k) + ": " + std::to_string(fx.table->word(static_cast<std::uint32_t>(d))) +
                                       " vs " + std::to_string(fx.native.w[static_cast<std::size_t>(d)]))
                                          .c_str());
      return;
    }
  }
  std::chrono::nanoseconds vm_time{0}, native_time{0};
  std::uint64_t instructions = 0;
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores): Google Benchmark's loop variable
    fx.now += kTick;
    const auto t0 = thread_cpu_now();
    const ProgramScanResult r = fx.vm_scan();
    const auto t1 = thread_cpu_now();
    fx.native_scan();
    benchmark::ClobberMemory();
    const auto t2 = thread_cpu_now();
    instructions += r.instructions;
    vm_time += t1 - t0;
    native_time += t2 - t1;
  }
  const double iters = static_cast<double>(state.iterations());
  state.counters["instr/scan"] = static_cast<double>(instructions) / iters;
  state.counters["vm_us"] = static_cast<double>(vm_time.count()) / iters / 1e3;
  state.counters["native_us"] = static_cast<double>(native_time.count()) / iters / 1e3;
  state.counters["ratio"] = static_cast<double>(vm_time.count()) / static_cast<double>(std::max<std::int64_t>(native_time.count(), 1));
}
BENCHMARK(BM_MixedVmVsNative)->Arg(1000)->Arg(10000)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace softslc

BENCHMARK_MAIN();
