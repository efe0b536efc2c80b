// Bench files and device steps in test files: `bench FILE`, `device NAME CHANGE ARGS`, and
// `device NAME WHAT[K]` observations in conditions, with their load-time errors and failure
// messages. The bench wires named 1746 cards to data/lamp.slc (inputs in slot 1, outputs in slot
// 2); with the sandbox's fixed scan-time model a scan of lamp.slc takes exactly 1.014 ms.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "testrunner_test_util.h"

namespace softslc::testing {
namespace {

using ::testing::HasSubstr;
using test::Sandbox;

constexpr const char* kBench =
    "io IN slot=1 input_delay=5ms    # the input card's filter\n"
    "io OUT slot=2 output_delay=2ms  # the output card's turn-on delay\n";

std::string run_with_bench(const std::string& body) {
  Sandbox box;
  box.write("lamp.bench", kBench);
  return box.run("program lamp.slc\nbench lamp.bench\n" + body);
}

TEST(BenchSteps, AnInjectedInputReachesTheProgramAfterTheCardsFilterDelay) {
  // Injected at 0; the input scans start every 1.014 ms, and the first one at or after 5 ms is the
  // sixth (5.070 ms); LAMP is on at the end of that scan, 6.084 ms.
  const std::string out = run_with_bench(
      "test \"t\"\n"
      "  device IN input 1\n"
      "  run until LAMP == 1 within 20ms\n"
      "  expect elapsed == 6.084ms\n"
      "  expect device IN inputs == 1\n");
  EXPECT_EQ(out, "PASS t.test: t\n");
}

TEST(BenchSteps, ObservesWhatTheOutputTerminalsReceive) {
  // The O: file has the bit at once; the card's terminals follow the output scan 2 ms later. The
  // output scan of the scan that set LAMP (starting at S, ending at S + 1.014 ms) is stamped with the
  // scan's start (module callbacks see the scan's start time), so the terminals change at S + 2 ms,
  // inside the next scan: the first check that sees it ends at S + 2.028 ms, 1.014 ms after LAMP.
  const std::string out = run_with_bench(
      "test \"t\"\n"
      "  set SWITCH = 1\n"
      "  run until LAMP == 1 within 20ms\n"
      "  expect device OUT outputs[0] == 0\n"
      "  run until device OUT outputs[0] == 1 within 10ms\n"
      "  expect elapsed == 1.014ms\n"
      "  expect device OUT outputs == 0b0000_0000_0000_0001 and device OUT outputs != 3\n");
  EXPECT_EQ(out, "PASS t.test: t\n");
}

TEST(BenchSteps, AChangeTheDeviceRefusesFailsWithTheModulesReason) {
  const std::string out = run_with_bench(
      "test \"t\"\n"
      "  scan 1\n"
      "  device IN explode now\n");
  EXPECT_EQ(out,
            "FAIL t.test: t\n"
            "    t.test:5: device IN explode now\n"
            "      error: device IN: a discrete module accepts 'input VALUE [MASK]' and 'normal', not 'explode now'\n"
            "      at virtual time 1.014ms, scan 1\n");
}

TEST(BenchSteps, SwitchWordsAreArguments) {
  // `on`/`off` end the change: "hold last state on" is the change "hold last state" with "on".
  const std::string out = run_with_bench(
      "test \"t\"\n"
      "  device IN input off\n");
  EXPECT_THAT(out, HasSubstr("error: device IN: input takes VALUE [MASK] (16-bit words)")) << out;
}

TEST(BenchSteps, AFailedObservationShowsItsValue) {
  const std::string out = run_with_bench(
      "test \"t\"\n"
      "  run until device OUT outputs[0] == 1 within 5ms\n");
  EXPECT_EQ(out,
            "FAIL t.test: t\n"
            "    t.test:4: run until device OUT outputs[0] == 1 within 5ms\n"
            "      expected: device OUT outputs[0] == 1 within 5ms\n"
            "      actual:   still false after 5.07ms: device OUT outputs[0] = 0\n"
            "      at virtual time 5.07ms, scan 5\n");
}

TEST(BenchSteps, AnIndexPastTheObservationIsAnError) {
  const std::string out = run_with_bench(
      "test \"t\"\n"
      "  expect device IN inputs[3] == 0\n");
  EXPECT_THAT(out, HasSubstr("error: device IN inputs has 1 value(s); there is no element 3")) << out;
}

TEST(BenchSteps, SnapshotsReplayDeviceSteps) {
  const std::string out = run_with_bench(
      "test \"on\"\n"
      "  device IN input 1\n"
      "  run 10ms\n"
      "  snapshot lit\n"
      "test \"restored\"\n"
      "  restore lit\n"
      "  expect LAMP == 1 and device IN inputs == 1\n");
  EXPECT_EQ(out, "PASS t.test: on\nPASS t.test: restored\n");
}

TEST(BenchSteps, ATestWithItsOwnProgramDoesNotInheritTheFilesBench) {
  Sandbox box;
  box.write("lamp.bench", kBench);
  EXPECT_EQ(box.diagnostics("program lamp.slc\nbench lamp.bench\n"
                            "test \"t\"\n  program other.slc\n  device IN input 1\n"),
            "t.test:5:10: error: no bench device 'IN' (this test has no bench: add 'bench FILE.bench')\n"
            "  device IN input 1\n         ^\n");
  // Naming both is fine, and a test may name a bench of its own.
  EXPECT_EQ(box.diagnostics("program lamp.slc\n"
                            "test \"t\"\n  program other.slc\n  bench lamp.bench\n  device IN input 1\n"),
            "");
}

TEST(BenchSteps, LoadTimeErrorsArePositioned) {
  Sandbox box;
  box.write("lamp.bench", kBench);
  box.write("broken.bench", "io IN slot=9\n");
  const std::string header = "program lamp.slc\nbench lamp.bench\ntest \"t\"\n";
  EXPECT_EQ(box.diagnostics(header + "  device NOPE offline\n"),
            "t.test:4:10: error: no bench device 'NOPE' in lamp.bench (its devices: IN, OUT)\n"
            "  device NOPE offline\n         ^\n");
  EXPECT_EQ(box.diagnostics(header + "  expect device IN temperature == 3\n"),
            "t.test:4:10: error: device 'IN' has no observable 'temperature' (the observations of each device kind "
            "are listed in docs/bench-format.md)\n  expect device IN temperature == 3\n         ^\n");
  EXPECT_EQ(box.diagnostics(header + "  expect device IN inputs == 1.5\n"),
            "t.test:4:30: error: a device observation is an integer; write an integer\n"
            "  expect device IN inputs == 1.5\n                             ^\n");
  EXPECT_EQ(box.diagnostics(header + "  expect device IN == 1\n"),
            "t.test:4:20: error: expected what to observe of the device, in lower-case words, optionally with an "
            "element index (btw count, btw data[2], outputs[0])\n  expect device IN == 1\n                   ^\n");
  EXPECT_EQ(box.diagnostics("program lamp.slc\nbench lamp.bench\nbench other.bench\n"),
            "t.test:3:1: error: a second file-level 'bench' line (the first is at line 2); name a test's own bench "
            "inside the test\nbench other.bench\n^\n");
  // A bench with errors: its own diagnostics first, then the test file's line.
  const std::string d = box.diagnostics("program lamp.slc\nbench broken.bench\ntest \"t\"\n  scan 1\n");
  EXPECT_THAT(d, HasSubstr("broken.bench:1:")) << d;
  EXPECT_THAT(d, HasSubstr("t.test:2:7: error: bench 'broken.bench' did not load (its errors are listed above)")) << d;
}

}  // namespace
}  // namespace softslc::testing
