// Parse + check throughput on generated programs of 1k, 10k and 100k rungs.
//
// The generated rungs mix what real programs hold: contacts, nested branches with outputs in
// legs, timers, counters, math and moves over N/B/T/C files. Growth should be linear in the
// number of rungs; the benchmark reports rungs per second so the three sizes compare directly.
#include <benchmark/benchmark.h>

#include <string>

#include "parser/loader.h"

namespace {

std::string generate_program(int rungs) {
  std::string s =
      "START 1747-L552\nSLOT 1 1746-IB16 SCAN_IN 1 SCAN_OUT 0\nSLOT 2 1746-OB16 SCAN_IN 0 SCAN_OUT 1\nLADDER 2\n";
  for (int i = 0; i < rungs; ++i) {
    int e = i % 200;
    std::string n = std::to_string(e);
    switch (i % 5) {
      case 0:
        s += "SOR XIC I:1/" + std::to_string(i % 16) + " BST XIC B3:" + n + "/1 NXB XIO B3:" + n + "/2 BND OTE B3:" + n +
             "/3 EOR\n";
        break;
      case 1: s += "SOR XIC B3:" + n + "/3 TON T4:" + n + " 0.01 100 0 EOR\n"; break;
      case 2:
        s += "SOR XIC T4:" + n + "/DN BST CTU C5:" + n + " 10 0 NXB ADD N7:" + n + " 1 N7:" + n + " BND EOR\n";
        break;
      case 3: s += "SOR GEQ N7:" + n + " 100 BST MOV 0 N7:" + n + " NXB OTL B3:" + n + "/4 BND EOR\n"; break;
      case 4: s += "SOR XIC B3:" + n + "/4 XIO C5:" + n + "/DN OTE O:2/" + std::to_string(i % 16) + " EOR\n"; break;
    }
  }
  return s;
}

void BM_ParseAndCheck(benchmark::State& state) {
  const int rungs = static_cast<int>(state.range(0));
  const std::string text = generate_program(rungs);
  for (auto _ : state) {
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
