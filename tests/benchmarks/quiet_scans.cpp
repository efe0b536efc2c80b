// How much of each shipped example's simulated time is idle: for every example with its bench
// (loaded as sim_bench loads it), the share of scans after which no data word outside the status
// file has changed, over 20 s of virtual time, and the status words that changed from scan to
// scan. It times nothing (so it is not a Google Benchmark); it measures how far skipping scans
// that repeat the one before could take the simulation speed (docs/performance.md, "Simulation
// speed of the shipped examples"). Deterministic: the same tree prints the same lines.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "tools/controller/controller.h"

namespace softslc {
namespace {

namespace fs = std::filesystem;

constexpr int kStatusFile = 2;

// Every word of every data file but the status file, in file order.
std::vector<std::uint16_t> words_outside_status(const Controller& plc) {
  std::vector<std::uint16_t> all;
  for (int f = 0; f < 256; ++f) {
    const auto info = plc.file_info(f);
    if (!info || f == kStatusFile || info->words() == 0) continue;
    const auto at = all.size();
    all.resize(at + info->words());
    plc.read_file_words(f, 0, std::span<std::uint16_t>(all).subspan(at));
  }
  return all;
}

std::vector<std::uint16_t> status_words(const Controller& plc) {
  std::vector<std::uint16_t> s(plc.file_info(kStatusFile)->words());
  plc.read_file_words(kStatusFile, 0, s);
  return s;
}

void measure(const fs::path& program, const fs::path& root) {
  fs::path bench = program;
  bench.replace_extension(".bench");
  const std::string name = fs::relative(program, root).string();
  try {
    Controller plc = Controller::load(program, fs::exists(bench) ? std::optional<fs::path>(bench) : std::nullopt);
    auto data = words_outside_status(plc);
    auto status = status_words(plc);
    std::uint64_t scans = 0, quiet = 0;
    std::map<std::size_t, std::uint64_t> status_changes;  // word -> scans that changed it
    while (plc.now() < milliseconds(20'000) && !plc.fault()) {
      plc.scan(1);
      ++scans;
      auto d = words_outside_status(plc);
      auto s = status_words(plc);
      quiet += d == data;
      for (std::size_t w = 0; w < s.size(); ++w) status_changes[w] += s[w] != status[w];
      data = std::move(d);
      status = std::move(s);
    }
    std::printf("%-52s %7llu scans  %5.1f%% quiet ", name.c_str(), static_cast<unsigned long long>(scans),
                scans ? 100.0 * static_cast<double>(quiet) / static_cast<double>(scans) : 0.0);
    for (const auto& [w, n] : status_changes)
      if (n) std::printf(" S:%zu %5.1f%%", w, 100.0 * static_cast<double>(n) / static_cast<double>(scans));
    std::printf("%s\n", plc.fault() ? "  (faulted)" : "");
  } catch (const std::exception& e) {
    std::printf("%-52s %s\n", name.c_str(), e.what());
  }
}

}  // namespace
}  // namespace softslc

int main() {
  namespace fs = std::filesystem;
  const fs::path root = fs::path(SOFTSLC_SOURCE_DIR) / "examples" / "ladder";
  std::vector<fs::path> programs;
  for (const auto& e : fs::recursive_directory_iterator(root))
    if (e.is_regular_file() && e.path().extension() == ".slc") programs.push_back(e.path());
  std::sort(programs.begin(), programs.end());
  std::printf("%-52s %13s  %-12s  status words changed (share of scans)\n", "example", "", "quiet scans");
  for (const auto& p : programs) softslc::measure(p, root);
  return 0;
}
