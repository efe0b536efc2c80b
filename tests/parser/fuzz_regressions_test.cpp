// Replays every input the fuzzers found (tests/fuzz/regressions/<target>/) through the same
// properties the fuzz targets check, so each fixed bug stays fixed in the ordinary suite.
#include <gtest/gtest.h>

#include <filesystem>

#include "../fuzz/properties.h"
#include "../fuzz/regression_inputs.h"

namespace softslc {
namespace {

using fuzz::read_bytes;
using fuzz::regression_inputs;

TEST(FuzzRegressions, Addresses) {
  auto files = regression_inputs("address");
  EXPECT_FALSE(files.empty());
  for (const auto& f : files) EXPECT_EQ(fuzz::check_address_property(read_bytes(f)), "") << f;
}

TEST(FuzzRegressions, TestFiles) {
  for (const auto& f : regression_inputs("testfile")) EXPECT_EQ(fuzz::check_testfile_property(read_bytes(f)), "") << f;
}

TEST(FuzzRegressions, Programs) {
  for (const auto& f : regression_inputs("program")) EXPECT_EQ(fuzz::check_program_property(read_bytes(f)), "") << f;
}

}  // namespace
}  // namespace softslc
