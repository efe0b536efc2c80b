// The C++ API (tools/controller/controller.h), and an example of a user's ladder test written
// with it: the seal-in example program, examples/ladder/seal_in/seal_in.slc, tested from
// GoogleTest instead of a .test file. Expected values follow from the ladder (rung 0: MOTOR =
// (START_PB or MOTOR) and not STOP_PB and not OL_TRIPPED; rung 1: a 1.00 s TON on OL_CONTACT;
// rung 2 latches OL_TRIPPED; rung 4 counts starts), not from running it.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tools/controller/controller.h"

namespace {

using ::testing::HasSubstr;
using softslc::Controller;
using softslc::ControllerError;

std::filesystem::path example(const char* name) {
  return std::filesystem::path(SOFTSLC_SOURCE_DIR) / "examples/ladder" / name;
}

class SealIn : public ::testing::Test {
 protected:
  Controller plc = Controller::load(example("seal_in/seal_in.slc"));
};

// ---- The user's view: a ladder test in C++ ----

TEST_F(SealIn, StartSealsTheMotorIn) {
  plc.scan();  // the first pass
  plc.set("START_PB", 1);
  plc.scan();
  EXPECT_TRUE(plc.get_bit("MOTOR"));
  plc.set("START_PB", 0);
  plc.scan(2);
  EXPECT_TRUE(plc.get_bit("MOTOR"));
  EXPECT_EQ(plc.get_int("C5:0.ACC"), 1);
}

TEST_F(SealIn, AHeldOverloadTripsAfterOneSecond) {
  plc.set("OL_CONTACT", 1);
  const auto start = plc.now();
  ASSERT_TRUE(plc.run_until([](const Controller& p) { return p.get_bit("OL_TRIPPED"); }, softslc::seconds(2)));
  // TON preset 100 x 0.01 s: done at 1.00 s, seen within the scan that follows.
  EXPECT_GE(plc.now() - start, softslc::seconds(1));
  EXPECT_LT(plc.now() - start, softslc::milliseconds(1010));
  plc.scan();
  EXPECT_TRUE(plc.get_bit("TRIP_LAMP"));
}

TEST_F(SealIn, ForcesActAsOnTheSlc) {
  plc.scan();
  plc.force("START_PB", true);  // an input force applies after the input scan
  plc.scan();
  EXPECT_TRUE(plc.get_bit("MOTOR"));
  plc.unforce("START_PB");
  plc.set("STOP_PB", 1);
  plc.scan();
  EXPECT_FALSE(plc.get_bit("MOTOR"));
}

TEST_F(SealIn, SnapshotsRestoreTheExactState) {
  plc.scan();
  plc.set("START_PB", 1);
  plc.scan();
  plc.set("START_PB", 0);
  plc.run_until([](const Controller& p) { return p.get_int("C5:0.ACC") == 1; }, softslc::seconds(1));
  const auto running = plc.snapshot();
  const auto t = plc.now();
  const auto scans = plc.scans();
  plc.set("STOP_PB", 1);
  plc.run_for(softslc::milliseconds(50));
  EXPECT_FALSE(plc.get_bit("MOTOR"));
  plc.restore(running);
  EXPECT_TRUE(plc.get_bit("MOTOR"));
  EXPECT_EQ(plc.now(), t);
  EXPECT_EQ(plc.scans(), scans);
  EXPECT_EQ(plc.get_int("C5:0.ACC"), 1);
  plc.restore(running);  // any number of times
  EXPECT_TRUE(plc.get_bit("MOTOR"));
}

// ---- Modes, faults and errors ----

TEST(ControllerApi, ALadderFaultIsStateNotAnError) {
  Controller plc = Controller::from_text(
      "START 1747-L532\nLADDER 2 MAIN\nSOR DIV N7:0 N7:1 N7:2 EOR\nDATA N7:0\n1 0 0\n");
  plc.scan();  // division by zero: S:5/0 overflow trap still set at END, fault 0020h
  ASSERT_TRUE(plc.fault().has_value());
  EXPECT_EQ(plc.fault()->code, 0x0020);
  EXPECT_EQ(plc.mode(), softslc::Mode::Faulted);
  plc.clear_fault();
  EXPECT_EQ(plc.mode(), softslc::Mode::Program);
  EXPECT_FALSE(plc.fault().has_value());
}

TEST(ControllerApi, ErrorsCarryTheReason) {
  try {
    Controller::from_text("START 1747-L532\nLADDER 2 MAIN\nSOR XIC N7:0 EOR\n", {}, "bad.slc");
    FAIL() << "a program with errors loaded";
  } catch (const ControllerError& e) {
    EXPECT_THAT(e.what(), HasSubstr("bad.slc:3:")) << e.what();
  }
  Controller plc = Controller::load(example("seal_in/seal_in.slc"));
  EXPECT_THROW(plc.get("N99:0"), ControllerError);
  EXPECT_THROW(plc.set("MOTOR", 2), ControllerError);
  EXPECT_THROW(plc.force("N7:0", true), ControllerError);
  EXPECT_THROW(plc.inject("NOBODY", "offline"), ControllerError);
  EXPECT_THROW(plc.observe("NOBODY", "inputs"), ControllerError);
  EXPECT_THROW(Controller::load("/nonexistent/x.slc"), ControllerError);
}

// Issue 17: the API wrote I:1/0 for I:1/32 (the shift wrapped), nothing for O:2/16, -31073 for
// 99999 and 2 for 1.5; it now refuses what `run --set` and test files refuse, with the reason.
TEST(ControllerApi, OneAddressRuleAndOneValueRule) {
  Controller plc = Controller::load(example("seal_in/seal_in.slc"));
  try {
    plc.set("I:1/32", 1);
    FAIL() << "I:1/32 was written";
  } catch (const ControllerError& e) {
    EXPECT_THAT(e.what(), HasSubstr("bit number 32 is out of range 0-15")) << e.what();
  }
  EXPECT_THROW(plc.set("O:2/16", 1), ControllerError);
  EXPECT_THROW(plc.set("T4:0.ACC", 99999), ControllerError);
  EXPECT_THROW(plc.set_float("T4:0.ACC", 1.5), ControllerError);
  plc.set("T4:0.ACC", 32767);
  EXPECT_EQ(plc.get_int("T4:0.ACC"), 32767);
  EXPECT_FALSE(plc.get_bit("I:1/0"));
}

TEST(ControllerApi, BenchDevicesAreInjectedAndObserved) {
  Controller plc = Controller::load(example("1747-sn/ch4_m1_status.slc"), example("1747-sn/ch4_m1_status.bench"));
  plc.run_for(softslc::milliseconds(400));
  // Chapter 4 "RIO Status Example": the 3/4 rack at rack 3 group 2 is faulted (M1 word 15 bits 1-3).
  EXPECT_EQ(plc.get_int("N7:15") & 0xF, 0xE);
  EXPECT_EQ(plc.observe("R3G2", "faulted"), std::vector<std::int64_t>{1});
  const auto faulted = plc.snapshot();
  plc.inject("R3G2", "online");
  plc.run_for(softslc::milliseconds(400));
  EXPECT_EQ(plc.get_int("N7:15") & 0xF, 0);
  plc.restore(faulted);  // the injection is undone with the rest
  EXPECT_EQ(plc.observe("R3G2", "faulted"), std::vector<std::int64_t>{1});
  EXPECT_THAT(plc.devices(), ::testing::Contains("RIO"));
}

}  // namespace
