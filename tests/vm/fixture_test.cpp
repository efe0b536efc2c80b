// The real RSLogix 500 export (MicroLogix 1400, facts §1 SCLFILE) compiles and runs.
//
// Its file 5 copies I:1.0/0-5 into B13:1/0-5 and file 6 copies those into B31:n/15 and
// B51:n/15 (read from the export's rungs); file 3 runs 1.0 s timers from B32 bits.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "vm_test_util.h"

namespace softslc::test {
namespace {

std::unique_ptr<Runtime> load_fixture() {
  LoadResult lr = load_program_file(SOFTSLC_SHARED_DIR "/fixtures/rslogix500/59-BSGS.SLC");
  if (!lr.ok()) throw std::runtime_error(lr.render_diagnostics());
  RuntimeResult rr = Runtime::create(*lr.program);
  if (!rr.ok()) throw std::runtime_error(rr.render_errors());
  return std::move(rr.runtime);
}

TEST(Fixture, BsgsRunsWithoutFaultAndMapsInputs) {
  auto rt = load_fixture();
  ASSERT_TRUE(rt->set_mode(Mode::Run));
  rt->run_for(seconds(2));
  ASSERT_FALSE(rt->fault().has_value()) << rt->fault()->to_string();
  ASSERT_TRUE(rt->set("I:1.0/2", Value::bit(true)));
  rt->scan(2);
  EXPECT_TRUE(rt->value("B13:1/2").as_bool());
  EXPECT_TRUE(rt->value("B31:2/15").as_bool());
  EXPECT_TRUE(rt->value("B51:2/15").as_bool());
  EXPECT_FALSE(rt->value("B31:3/15").as_bool());
  EXPECT_EQ(rt->value("N7:0").as_int(), 60) << "initial data from the DATA block";
}

TEST(Fixture, BsgsOneSecondTimerFromTheExport) {
  // File 3 rung 2: XIC B32:0/15 BST TON T33:0 1.0 60 60 ...; B32:0 = -32768 sets bit 15, so the
  // timer runs from the first scan; entering Run with the rung true resets its ACC (RM 2-9).
  auto rt = load_fixture();
  ASSERT_TRUE(rt->set_mode(Mode::Run));
  rt->scan(1);
  EXPECT_EQ(rt->value("T33:0.ACC").as_int(), 0);
  rt->run_for(milliseconds(10500));
  EXPECT_EQ(rt->value("T33:0.ACC").as_int(), 10);
  EXPECT_FALSE(rt->fault().has_value());
}

}  // namespace
}  // namespace softslc::test
