// Parse + check throughput on generated programs of 1k, 10k and 100k rungs.
//
// The generated rungs mix what real programs hold: contacts, nested branches with outputs in
// legs, timers, counters, math and moves over N/B/T/C files. Growth should be linear in the
// number of rungs; the benchmark reports rungs per second so the three sizes compare directly.
#include <benchmark/benchmark.h>

#include <string>

#include "tests/benchmarks/generated_rung.h"

#include "parser/loader.h"

namespace {

std::string generate_program(int rungs) {
  std::string s =
      "START 1747-L552\nSLOT 1 1746-IB16 SCAN_IN 1 SCAN_OUT 0\nSLOT 2 1746-OB16 SCAN_IN 0 SCAN_OUT 1\nLADDER 2\n";
  for (int i = 0; i < rungs; ++i) s += softslc::bench::generated_rung(i);
  return s;
}

void BM_ParseAndCheck(benchmark::State& state) {
  const int rungs = static_cast<int>(state.range(0));
  const std::string text = generate_program(rungs);
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores): Google Benchmark's loop variable
    auto r = softslc::load_program(text, "generated.slc");
    if (!r.ok()) state.SkipWithError("generated program did not load");
    benchmark::DoNotOptimize(r);
  }
  state.SetItemsProcessed(state.iterations() * rungs);
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(text.size()));
  state.counters["rungs"] = rungs;
}

BENCHMARK(BM_ParseAndCheck)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);

}  // namespace
