// Running tests: every step, the exact failure messages, timeouts, snapshots, tables, power
// cycles. Programs are data/lamp.slc and data/other.slc (see testrunner_test_util.h); with the
// sandbox's fixed scan-time model a scan of lamp.slc takes exactly 1.014 ms.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "testrunner_test_util.h"

namespace softslc::testing {
namespace {

using ::testing::HasSubstr;
using test::Sandbox;

// Runs `body` (the lines after "program lamp.slc") and expects every test to pass.
void expect_all_pass(const std::string& body) {
  Sandbox box;
  const std::string out = box.run("program lamp.slc\n" + body);
  EXPECT_THAT(out, ::testing::Not(HasSubstr("FAIL"))) << out;
  EXPECT_THAT(out, HasSubstr("PASS")) << out;
}

// ---- Steps ------------------------------------------------------------------------------------------------

TEST(Steps, SetAnInputReachesTheProgramAtTheNextInputScan) {
  expect_all_pass(
      "test \"t\"\n"
      "  set    SWITCH = 1\n"
      "  expect I:1/0 == 0 and LAMP == 0   # nothing scanned yet\n"
      "  scan   1\n"
      "  expect I:1/0 == 1 and LAMP == 1\n"
      "  set    I:1.0 = 0\n"
      "  scan   1\n"
      "  expect LAMP == 0\n");
}

TEST(Steps, SetWritesDataTableWordsAtOnce) {
  expect_all_pass(
      "test \"t\"\n"
      "  set    N7:3 = -7\n"
      "  expect N7:3 == -7\n"
      "  set    N7:3 = 0xFFFE\n"
      "  expect N7:3 == -2 and N7:3 == 0xFFFE\n"
      "  set    N11:0..2 = 1 2 0b11\n"
      "  expect N11:0..3 == 1 2 3 0xFFFF\n"
      "  set    F8:1 = 3\n"
      "  expect F8:1 == 3.0 and F8:0 == 0.1 and F8:0 in 0.09..0.11\n"
      "  set    T4:0.PRE = 20\n"
      "  expect T4:0.PRE == 20\n"
      "  set    LATCH = 1\n"
      "  expect B3:0/1 == 1 and B3:0 == 2\n");
}

TEST(Steps, ComparisonsAndPatterns) {
  expect_all_pass(
      "test \"t\"\n"
      "  expect N7:0 == 10 and N7:0 != 11 and N7:0 < 11 and N7:0 <= 10 and N7:0 > 9 and N7:0 >= 10\n"
      "  expect N7:0 in 10..20 and N7:0 in -5..10\n"
      "  expect N7:0 < N7:1 and N7:1 == 20\n"
      "  expect N11:1 == 0b0000_0000_0000_1111 and N11:1 == 0b1111 and N11:1 == 0x000F and N11:1 == 000Fh\n"
      "  expect N11:1 == 0bxxxx_xxxx_xxxx_11x1 and N11:1 != 0bxxxx_xxxx_xxxx_xxx0\n"
      "  expect N11:3 == 0b1111_1111_1111_1111 and N11:3 == 0b1xxx_xxxx_xxxx_xxxx\n"
      "  expect N11:1 != 0b1x      # bits above the written digits must be 0\n"
      "  expect LAMP == 1 or N7:0 == 10\n"
      "  expect (LAMP == 1 or N7:0 == 10) and no fault and mode run\n");
}

TEST(Steps, ForcesApplyAsOnTheSlc) {
  expect_all_pass(
      "test \"input force\"\n"
      "  force  SWITCH = 1\n"
      "  expect I:1/0 == 0          # applied after the next input scan\n"
      "  scan   1\n"
      "  expect I:1/0 == 1 and LAMP == 1\n"
      "  unforce I:1/0\n"
      "  scan   1\n"
      "  expect I:1/0 == 0 and LAMP == 0\n"
      "  set    SWITCH = 1\n"
      "  force  I:1/0 = 0\n"
      "  scan   1\n"
      "  expect LAMP == 0           # forced off overrides the field\n"
      "  unforce all\n"
      "  scan   1\n"
      "  expect LAMP == 1\n"
      "test \"output force\"\n"
      "  force  LAMP = 1\n"
      "  scan   1\n"
      "  expect LAMP == 0           # the O: file keeps the program's value; the card gets the force\n");
}

TEST(Steps, ScanRunElapsedAndScans) {
  expect_all_pass(
      "test \"t\"\n"
      "  expect elapsed == 0s and scans == 0\n"
      "  scan   3\n"
      "  expect scans == 3 and elapsed == 3.042ms\n"
      "  run    10ms\n"
      "  expect scans == 10 and elapsed == 10.14ms    # whole scans until at least 10 ms\n"
      "  set    I:1/1 = 1\n"
      "  run    until DELAYED == 1 within 1s\n"
      // The TON starts on the step's first scan, which begins at 13.182 ms: its tick stamp is
      // tick 1 (13.185 ms). It is done at its first execution at or after tick 51 (510 ms): in
      // scan 504 of the test (503 * 1.014 ms + 3 us >= 510 ms), so this step ran 504 - 13 = 491
      // scans, 491 * 1.014 ms = 497.874 ms.
      "  expect scans == 491 and elapsed == 497.874ms\n"
      "  expect T4:0.ACC == 50 and T4:0/DN == 1\n"
      "  run    until DELAYED == 1 within 1s\n"
      "  expect scans == 0 and elapsed == 0s          # the condition held before the first scan\n");
}

TEST(Steps, ModesAndFaults) {
  expect_all_pass(
      "test \"program mode\"\n"
      "  mode   program\n"
      "  expect mode program\n"
      "  set    SWITCH = 1\n"
      "  scan   2\n"
      "  expect LAMP == 0 and scans == 0   # the program does not run in Program mode\n"
      "  mode   run\n"
      "  scan   1\n"
      "  expect LAMP == 1 and S:1/15 == 0\n"
      "test \"test mode\"\n"
      "  mode   test\n"
      "  set    SWITCH = 1\n"
      "  scan   1\n"
      "  expect LAMP == 1 and scans == 1   # one single scan; outputs to the cards stay off\n"
      "  run    20ms\n"
      "  expect scans == 0                 # run only idles in Test mode\n"
      "test \"fault\"\n"
      "  set    N7:0 = 32767\n"
      "  set    N7:1 = 1\n"
      "  set    I:1/2 = 1\n"
      "  scan   5\n"
      "  expect fault 0020h and fault 0x0020 and fault and mode faulted\n"
      "  expect scans == 1                 # the faulted scan was the last program scan\n"
      "  expect S:6 == 0020h and S:1/13 == 1\n"
      "  clear  fault\n"
      "  expect no fault and mode program and S:6 == 0x0020\n");
}

TEST(Steps, ProgramPerTest) {
  expect_all_pass(
      "test \"lamp\"\n"
      "  set SWITCH = 1\n"
      "  scan 1\n"
      "  expect LAMP == 1\n"
      "test \"other\"\n"
      "  program other.slc\n"
      "  set I:1/0 = 1\n"
      "  scan 1\n"
      "  expect GREEN == 1 and O:2/0 == 0\n");
}

// ---- Power cycle ----------------------------------------------------------------------------------------

TEST(PowerCycle, KeepsTheDataTableButNotOteBits) {
  expect_all_pass(
      "test \"t\"\n"
      "  set    SWITCH = 1\n"
      "  set    I:1/3 = 1\n"
      "  scan   1\n"
      "  set    I:1/3 = 0\n"
      "  set    I:1/5 = 1\n"
      "  scan   1\n"
      "  expect LAMP == 1 and LATCH == 1 and C5:0.ACC == 1\n"
      "  set    N7:3 = 77\n"
      "  power  cycle\n"
      "  expect LAMP == 0                  # OTE bits are non-retentive on power loss\n"
      "  expect LATCH == 1 and N7:3 == 77 and C5:0.ACC == 1 and S:4 == 0\n"
      "  expect mode run and scans == 1    # the last step's figures are kept\n"
      "  scan   1\n"
      "  expect LAMP == 1                  # the field input is still on\n"
      "  expect C5:0.ACC == 1              # first pass after power-up: no count\n"
      "test \"forces stay\"\n"
      "  force  SWITCH = 1\n"
      "  power  cycle\n"
      "  scan   1\n"
      "  expect I:1/0 == 1 and LAMP == 1\n"
      "test \"program mode stays\"\n"
      "  mode   program\n"
      "  power  cycle\n"
      "  expect mode program\n");
}

TEST(PowerCycle, VirtualTimeAndScansCarryOn) {
  Sandbox box;
  const std::string out = box.run(
      "program lamp.slc\n"
      "test \"t\"\n"
      "  scan 2\n"
      "  power cycle\n"
      "  scan 1\n"
      "  expect LAMP == 1\n");
  EXPECT_EQ(out,
            "FAIL t.test: t\n"
            "    t.test:6: expect LAMP == 1\n"
            "      expected: LAMP == 1\n"
            "      actual:   LAMP (O:2.0/0) = 0\n"
            "      at virtual time 3.042ms, scan 3\n");
}

// ---- Failure messages -------------------------------------------------------------------------------------

TEST(Failures, ExpectShowsExpectedActualTimeAndScan) {
  Sandbox box;
  EXPECT_EQ(box.run("program lamp.slc\n"
                    "test \"lamp\"\n"
                    "  set    SWITCH = 1\n"
                    "  scan   1\n"
                    "  expect LAMP == 0   # wrong on purpose\n"),
            "FAIL t.test: lamp\n"
            "    t.test:5: expect LAMP == 0\n"
            "      expected: LAMP == 0\n"
            "      actual:   LAMP (O:2.0/0) = 1\n"
            "      at virtual time 1.014ms, scan 1\n");
}

TEST(Failures, EveryOperandOfAConditionIsShownOnceInTheLiteralsRadix) {
  Sandbox box;
  EXPECT_EQ(box.run("program lamp.slc\n"
                    "test \"c\"\n"
                    "  expect N7:0 == 0x00FF or (N11:3 != -1 and N7:0 > N7:1) or elapsed > 1s\n"),
            "FAIL t.test: c\n"
            "    t.test:3: expect N7:0 == 0x00FF or (N11:3 != -1 and N7:0 > N7:1) or elapsed > 1s\n"
            "      expected: N7:0 == 0x00FF or (N11:3 != -1 and N7:0 > N7:1) or elapsed > 1s\n"
            "      actual:   N7:0 = 0x000A (10), N11:3 = -1, N7:1 = 20, elapsed = 0s\n"
            "      at virtual time 0s, scan 0\n");
}

TEST(Failures, PatternsShowTheActualBits) {
  Sandbox box;
  // N11:1 is 15: bit 0 is 1 where the pattern wants 0.
  EXPECT_EQ(box.run("program lamp.slc\ntest \"p\"\n  expect N11:1 == 0b1xx0\n"),
            "FAIL t.test: p\n"
            "    t.test:3: expect N11:1 == 0b1xx0\n"
            "      expected: N11:1 == 0b1xx0\n"
            "      actual:   N11:1 = 0b0000_0000_0000_1111 (15)\n"
            "      at virtual time 0s, scan 0\n");
}

TEST(Failures, WordRangesListTheDifferences) {
  Sandbox box;
  EXPECT_EQ(box.run("program lamp.slc\ntest \"w\"\n  expect N11:0..3 == 0x000E 0x0000 0x0010 -2\n"),
            "FAIL t.test: w\n"
            "    t.test:3: expect N11:0..3 == 0x000E 0x0000 0x0010 -2\n"
            "      expected: N11:0..3 == 0x000E 0x0000 0x0010 -2\n"
            "      actual:   N11:0..3 = 0x000E 0x000F 0x0010 -1\n"
            "      differs at N11:1, N11:3\n"
            "      at virtual time 0s, scan 0\n");
}

TEST(Failures, RunUntilTimesOutWithTheLastValues) {
  Sandbox box;
  // run_until scans until 100 ms have passed: 99 scans of 1.014 ms = 100.386 ms.
  EXPECT_EQ(box.run("program lamp.slc\n"
                    "test \"slow\"\n"
                    "  set I:1/1 = 1\n"
                    "  run until DELAYED == 1 and LAMP == 0 within 100ms\n"),
            "FAIL t.test: slow\n"
            "    t.test:4: run until DELAYED == 1 and LAMP == 0 within 100ms\n"
            "      expected: DELAYED == 1 and LAMP == 0 within 100ms\n"
            "      actual:   still false after 100.386ms: DELAYED (O:2.0/1) = 0, LAMP (O:2.0/0) = 0\n"
            "      at virtual time 100.386ms, scan 99\n");
}

TEST(Failures, ElapsedAndScans) {
  Sandbox box;
  EXPECT_EQ(box.run("program lamp.slc\ntest \"e\"\n  run 50ms\n  expect elapsed <= 50ms and scans == 49\n"),
            "FAIL t.test: e\n"
            "    t.test:4: expect elapsed <= 50ms and scans == 49\n"
            "      expected: elapsed <= 50ms and scans == 49\n"
            "      actual:   elapsed = 50.7ms, scans = 50\n"
            "      at virtual time 50.7ms, scan 50\n");
}

TEST(Failures, AFaultIsShownWithTheFailure) {
  Sandbox box;
  const std::string out = box.run(
      "program lamp.slc\n"
      "test \"f\"\n"
      "  set N7:0 = 32767\n"
      "  set N7:1 = 1\n"
      "  set I:1/2 = 1\n"
      "  scan 1\n"
      "  expect N7:2 == 0\n"
      "test \"g\"\n"
      "  expect fault 0020h\n");
  EXPECT_THAT(out, HasSubstr("FAIL t.test: f\n"
                             "    t.test:7: expect N7:2 == 0\n"
                             "      expected: N7:2 == 0\n"
                             "      actual:   N7:2 = 32767\n"
                             "      the processor is faulted: major fault 0020h in file 2 rung 7: "));
  EXPECT_THAT(out, HasSubstr("\n      at virtual time 1.014ms, scan 1\n"));
  EXPECT_THAT(out, HasSubstr("FAIL t.test: g\n"
                             "    t.test:9: expect fault 0020h\n"
                             "      expected: fault 0020h\n"
                             "      actual:   no fault\n"
                             "      at virtual time 0s, scan 0\n"));
}

TEST(Failures, RefusedRequestsSayWhy) {
  Sandbox box;
  const std::string out = box.run(
      "program lamp.slc\n"
      "test \"mode\"\n"
      "  set N7:0 = 32767\n  set N7:1 = 1\n  set I:1/2 = 1\n  scan 1\n"
      "  mode run\n"
      "test \"power\"\n"
      "  set N7:0 = 32767\n  set N7:1 = 1\n  set I:1/2 = 1\n  scan 1\n"
      "  power cycle\n");
  EXPECT_THAT(out, HasSubstr("FAIL t.test: mode\n    t.test:7: mode run\n      error: a major fault is active ("));
  EXPECT_THAT(out, HasSubstr("FAIL t.test: power\n"
                             "    t.test:13: power cycle\n"
                             "      error: power cycle while faulted is not supported yet: the SLC keeps a major "
                             "fault through a power cycle and softslc cannot restore one; 'clear fault' first\n"
                             "      the processor is faulted: major fault 0020h"));
}

// ---- Snapshots -----------------------------------------------------------------------------------------

TEST(Snapshots, RestoreReproducesTheStateExactly) {
  Sandbox box;
  const std::string out = box.run(
      "program lamp.slc\n"
      "test \"setup\"\n"
      "  set    SWITCH = 1\n"
      "  set    I:1/1 = 1\n"
      "  force  I:1/3 = 1\n"
      "  run    100ms\n"
      "  snapshot warm\n"
      "  set    SWITCH = 0\n"                 // after the snapshot: not part of it
      "test \"uses it\"\n"
      "  restore warm\n"
      "  expect LAMP == 1 and LATCH == 1 and scans == 99 and elapsed == 100.386ms\n"
      "  expect T4:0/TT == 1 and T4:0.ACC in 9..10\n"
      "  scan   1\n"
      "  expect LAMP == 1                    # the field input came back too\n"
      "  expect N7:0 == 1                    # deliberately wrong: shows the restored time\n"
      "test \"nested\"\n"
      "  restore warm\n"
      "  unforce I:1/3\n"
      "  set    I:1/4 = 1\n"
      "  scan   1\n"
      "  snapshot cleared\n"
      "test \"uses nested\"\n"
      "  restore cleared\n"
      "  expect LATCH == 0 and LAMP == 1\n"
      "  scan   1\n"
      "  expect LATCH == 0                   # the unforce was replayed as well\n");
  EXPECT_EQ(out,
            "PASS t.test: setup\n"
            "FAIL t.test: uses it\n"
            "    t.test:15: expect N7:0 == 1\n"
            "      expected: N7:0 == 1\n"
            "      actual:   N7:0 = 10\n"
            "      at virtual time 101.4ms, scan 100\n"
            "PASS t.test: nested\n"
            "PASS t.test: uses nested\n");
}

TEST(Snapshots, AFailureDuringTheReplayNamesTheSnapshot) {
  Sandbox box;
  EXPECT_EQ(box.run("program lamp.slc\n"
                    "test \"setup\"\n"
                    "  scan 2\n"
                    "  expect LAMP == 1\n"
                    "  snapshot s\n"
                    "test \"user\"\n"
                    "  restore s\n"
                    "  scan 1\n"),
            "FAIL t.test: setup\n"
            "    t.test:4: expect LAMP == 1\n"
            "      expected: LAMP == 1\n"
            "      actual:   LAMP (O:2.0/0) = 0\n"
            "      at virtual time 2.028ms, scan 2\n"
            "FAIL t.test: user\n"
            "    t.test:4: expect LAMP == 1\n"
            "      in snapshot 's' (taken at t.test:5), restored at line 7\n"
            "      expected: LAMP == 1\n"
            "      actual:   LAMP (O:2.0/0) = 0\n"
            "      at virtual time 2.028ms, scan 2\n");
}

TEST(Snapshots, ARestoreBringsItsProgram) {
  expect_all_pass(
      "test \"green\"\n"
      "  program other.slc\n"
      "  set I:1/0 = 1\n"
      "  scan 1\n"
      "  snapshot green_on\n"
      "test \"back\"\n"
      "  restore green_on\n"
      "  expect GREEN == 1\n");
}

// ---- Tables -------------------------------------------------------------------------------------------

TEST(Tables, EachRowIsATestWithItsOwnResult) {
  Sandbox box;
  EXPECT_EQ(box.run("program lamp.slc\n"
                    "test \"switch $IN gives lamp $OUT\" with IN OUT\n"
                    "  row 0 0\n"
                    "  row 1 1\n"
                    "  row 1 0\n"
                    "  set    SWITCH = $IN\n"
                    "  scan   1\n"
                    "  expect LAMP == $OUT\n"),
            "PASS t.test: switch 0 gives lamp 0\n"
            "PASS t.test: switch 1 gives lamp 1\n"
            "FAIL t.test: switch 1 gives lamp 0\n"
            "    t.test:8: expect LAMP == 0\n"
            "      expected: LAMP == 0\n"
            "      actual:   LAMP (O:2.0/0) = 1\n"
            "      at virtual time 1.014ms, scan 1\n");
}

TEST(Tables, ValuesCanBeAddressesAndDurations) {
  expect_all_pass(
      "test \"write $WHERE for $T\" with WHERE T\n"
      "  row N7:3 10ms\n"
      "  row N7:2 1s\n"
      "  set    $WHERE = 1\n"
      "  run    $T\n"
      "  expect $WHERE == 1 and elapsed >= $T\n");
}

}  // namespace
}  // namespace softslc::testing
