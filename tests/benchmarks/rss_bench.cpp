// Reading and decoding the largest .RSS fixture (../shared/fixtures/rss, issue 14): the OLE2
// container, inflating its streams, decoding PROCESSOR, PROGRAM FILES, MEM DATABASE and DATA FILES
// into export text (rss::read_project), and the same followed by the loader and checker
// (load_program_bytes, what `softslc check X.RSS` does). Figures go to docs/performance.md.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "parser/loader.h"
#include "parser/rss/rss_reader.h"

namespace {

// The largest project by file size: the one whose decoding costs most.
std::filesystem::path largest_fixture() {
  std::filesystem::path best;
  std::uintmax_t best_size = 0;
  auto dir = std::filesystem::path(SOFTSLC_SHARED_DIR) / "fixtures" / "rss";
  if (!std::filesystem::exists(dir)) return best;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir))
    if (e.path().extension() == ".RSS" && e.file_size() > best_size) {
      best_size = e.file_size();
      best = e.path();
    }
  return best;
}

std::string slurp(const std::filesystem::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

void BM_RssReadProject(benchmark::State& state) {
  auto path = largest_fixture();
  if (path.empty()) {
    state.SkipWithError("no .RSS fixtures in ../shared/fixtures/rss");
    return;
  }
  std::string bytes = slurp(path);
  state.SetLabel(path.filename().string() + ", " + std::to_string(bytes.size()) + " bytes");
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores): Google Benchmark's loop variable
    auto r = softslc::rss::read_project(bytes, path.filename().string());
    if (!r.text) state.SkipWithError(r.error.c_str());
    benchmark::DoNotOptimize(r);
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * bytes.size()));
}
BENCHMARK(BM_RssReadProject)->Unit(benchmark::kMillisecond);

void BM_RssReadAndCheck(benchmark::State& state) {
  auto path = largest_fixture();
  if (path.empty()) {
    state.SkipWithError("no .RSS fixtures in ../shared/fixtures/rss");
    return;
  }
  std::string bytes = slurp(path);
  state.SetLabel(path.filename().string());
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores): Google Benchmark's loop variable
    auto r = softslc::load_program_bytes(bytes, path.filename().string());
    benchmark::DoNotOptimize(r);
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * bytes.size()));
}
BENCHMARK(BM_RssReadAndCheck)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
