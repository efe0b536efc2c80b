// The inputs the fuzzers found and kept (tests/fuzz/regressions/<target>/), for the tests that
// replay them through the fuzz targets' properties.
#pragma once

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace softslc::fuzz {

// The files of one target's regression directory, in name order (none when it does not exist).
inline std::vector<std::filesystem::path> regression_inputs(const std::string& target) {
  std::vector<std::filesystem::path> files;
  auto dir = std::filesystem::path(SOFTSLC_SOURCE_DIR) / "tests/fuzz/regressions" / target;
  if (std::filesystem::exists(dir))
    for (const auto& e : std::filesystem::directory_iterator(dir))
      if (e.is_regular_file()) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

inline std::string read_bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace softslc::fuzz
