// The online view's server side at scale (Google Benchmark; figures in docs/performance.md): on a
// generated program of N rungs (the shape of tests/serve/browser/make_big_program.js), the outline
// sent on connect (every rung laid out once for its height) and one periodic update for a page
// showing 12 rungs in the middle of the file (status, their layout with values and power flow).
#include <benchmark/benchmark.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "server/web.h"

namespace {

std::filesystem::path big_program(int rungs) {
  auto path = std::filesystem::temp_directory_path() / ("softslc_web_bench_" + std::to_string(rungs) + ".slc");
  std::ofstream out(path);
  out << "START 1747-L552\nSLOT 1 1746-IB16 SCAN_IN 1 SCAN_OUT 0\nSLOT 2 1746-OB16 SCAN_IN 0 SCAN_OUT 1\n"
         "PROJECT \"BIG\"\nLADDER 2 MAIN\n";
  for (int r = 0; r < rungs; ++r) {
    const int b = r % 200, t = r % 100;
    switch (r % 5) {
      case 0:
        out << "% Block " << r / 5 << ": a seal-in on B3:" << b << ". %\nSOR BST XIC I:1/" << r % 16 << " NXB XIC B3:" << b
            << "/0 BND XIO B3:" << b << "/1 OTE B3:" << b << "/0 EOR\n";
        break;
      case 1: out << "SOR XIC B3:" << b << "/0 TON T4:" << t << " 0.01 50 0 EOR\n"; break;
      case 2: out << "SOR GRT N7:" << b << " 10 OTE B3:" << b << "/2 EOR\n"; break;
      case 3: out << "SOR XIC T4:" << t << "/DN ADD N7:" << b << " 1 N7:" << b << " EOR\n"; break;
      default: out << "SOR XIC B3:" << b << "/2 CTU C5:" << t << " 1000 0 OTE O:2/" << r % 16 << " EOR\n"; break;
    }
  }
  return path;
}

void BM_WebOutline(benchmark::State& state) {
  const auto path = big_program(static_cast<int>(state.range(0)));
  softslc::serve::LiveController live(path, std::nullopt, {});
  std::size_t bytes = 0;
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores): Google Benchmark's loop variable
    softslc::serve::WebModel model(live, nullptr);
    bytes = model.program_message().size();
    benchmark::DoNotOptimize(bytes);
  }
  state.counters["message_bytes"] = static_cast<double>(bytes);
  std::filesystem::remove(path);
}
BENCHMARK(BM_WebOutline)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);

void BM_WebUpdate(benchmark::State& state) {
  const int rungs = static_cast<int>(state.range(0));
  const auto path = big_program(rungs);
  softslc::serve::LiveController live(path, std::nullopt, {});
  live.step(10);
  softslc::serve::WebModel model(live, nullptr);
  softslc::serve::WebWatch watch;
  model.handle(R"({"op":"view","file":2,"first":)" + std::to_string(rungs / 2) + R"(,"last":)" +
                   std::to_string(rungs / 2 + 11) + "}",
               watch);
  std::size_t bytes = 0;
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores): Google Benchmark's loop variable
    const std::string u = model.update(watch);
    bytes = u.size();
    benchmark::DoNotOptimize(bytes);
  }
  state.counters["message_bytes"] = static_cast<double>(bytes);
  std::filesystem::remove(path);
}
BENCHMARK(BM_WebUpdate)->Arg(1000)->Arg(10000)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
