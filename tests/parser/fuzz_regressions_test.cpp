// Replays every input the fuzzers found (tests/fuzz/regressions/<target>/) through the same
// properties the fuzz targets check, so each fixed bug stays fixed in the ordinary suite.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "../fuzz/properties.h"

namespace softslc {
namespace {

std::vector<std::filesystem::path> inputs(const std::string& target) {
  std::vector<std::filesystem::path> files;
  auto dir = std::filesystem::path(SOFTSLC_SOURCE_DIR) / "tests/fuzz/regressions" / target;
  if (std::filesystem::exists(dir))
    for (const auto& e : std::filesystem::directory_iterator(dir))
      if (e.is_regular_file()) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

std::string read(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(FuzzRegressions, Addresses) {
  auto files = inputs("address");
  EXPECT_FALSE(files.empty());
  for (const auto& f : files) EXPECT_EQ(fuzz::check_address_property(read(f)), "") << f;
}

TEST(FuzzRegressions, TestFiles) {
  for (const auto& f : inputs("testfile")) EXPECT_EQ(fuzz::check_testfile_property(read(f)), "") << f;
}

TEST(FuzzRegressions, Programs) {
  for (const auto& f : inputs("program")) EXPECT_EQ(fuzz::check_program_property(read(f)), "") << f;
}

}  // namespace
}  // namespace softslc
