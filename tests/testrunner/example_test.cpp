// The shipped example's tests (examples/ladder/seal_in/seal_in.test) pass, through the same
// entry point `softslc test` uses, and with the runtime's own scan-time model.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sstream>

#include "tools/testrunner/test_command.h"

namespace softslc::testing {
namespace {

TEST(Example, SealInTestsPass) {
  const std::string dir = std::string(SOFTSLC_SOURCE_DIR) + "/examples/ladder/seal_in";
  std::ostringstream out, err;
  TestCommandOptions options;
  options.paths = {dir};
  const int rc = run_test_command(options, out, err);
  EXPECT_EQ(err.str(), "");
  EXPECT_EQ(rc, 0) << out.str();
  EXPECT_THAT(out.str(), ::testing::Not(::testing::HasSubstr("FAIL")));
  // The last line is "N passed, 0 failed" with N > 0.
  const std::string text = out.str();
  const auto last = text.rfind('\n', text.size() - 2);
  const std::string summary = text.substr(last + 1);
  EXPECT_EQ(summary.substr(summary.find(' ')), " passed, 0 failed\n") << text;
  EXPECT_GT(std::stoi(summary), 0) << text;
}

}  // namespace
}  // namespace softslc::testing
