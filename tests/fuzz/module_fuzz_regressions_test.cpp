// Replays every input the module fuzzers found (tests/fuzz/regressions/<target>/) through the
// properties the fuzz targets check (module_properties.h), so each fixed bug stays fixed.
#include <gtest/gtest.h>

#include <filesystem>

#include "module_properties.h"
#include "regression_inputs.h"

namespace softslc {
namespace {

using fuzz::read_bytes;
using fuzz::regression_inputs;

TEST(ModuleFuzzRegressions, Benches) {
  for (const auto& f : regression_inputs("bench")) EXPECT_EQ(fuzz::check_bench_property(read_bytes(f)), "") << f;
}

TEST(ModuleFuzzRegressions, ScanportMessages) {
  for (const auto& f : regression_inputs("scanport_message")) EXPECT_EQ(fuzz::check_scanport_message_property(read_bytes(f)), "") << f;
}

TEST(ModuleFuzzRegressions, TransactionBlocks) {
  for (const auto& f : regression_inputs("transaction")) EXPECT_EQ(fuzz::check_transaction_property(read_bytes(f)), "") << f;
}

TEST(ModuleFuzzRegressions, DemControlBlocks) {
  const auto files = regression_inputs("dem");
  EXPECT_FALSE(files.empty());
  for (const auto& f : files) EXPECT_EQ(fuzz::check_dem_property(read_bytes(f)), "") << f;
}

// The seeds tools/fuzz.sh starts from hold too: every example bench.
TEST(ModuleFuzzSeeds, ExampleBenchesHoldTheBenchProperty) {
  int n = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(std::filesystem::path(SOFTSLC_SOURCE_DIR) / "examples"))
    if (e.path().extension() == ".bench") {
      EXPECT_EQ(fuzz::check_bench_property(read_bytes(e.path())), "") << e.path();
      ++n;
    }
  EXPECT_GT(n, 0);
}

}  // namespace
}  // namespace softslc
