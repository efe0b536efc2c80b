// The RIO link in virtual time: T_RIO per appendix A, the discrete transfers, the chapter 4 mode
// table (device reset, remote output reset, hold last state), inhibit, faults, retries,
// complementary I/O, the Run-entry faults 62H/63H/64H, and determinism.
#include <gtest/gtest.h>

#include "modules_test_util.h"

namespace softslc::test {
namespace {

// The appendix A discrete-throughput example network at 115.2K: a 1/2 rack ASB at rack 0 (with a
// 1746-IB16 and a 1746-OB16), two full racks (1 and 2), three 1/4 racks in rack 3. G word 1:
// rack 0 g0, rack 1 g0, rack 2 g0, rack 3 g0 g2 g4 = 0x7111; word 2: 0x0033 | 0x0F00... see below.
//   rack 0: 1/2 rack at g0 -> bits 0,1; rack 1 full -> bits 4-7; rack 2 full -> bits 8-11;
//   rack 3: 1/4 at g0, g2, g4 -> bits 12, 13, 14.
// word 1 = 0x0001 | 0x0010 | 0x0100 | 0x7000 = 0x7111 (28945); word 2 = 0x0003 | 0x00F0 | 0x0F00 |
// 0x7000 = 0x7FF3 (32755).
const std::string kExampleProgram =
    "START 1747-L532\n"
    "SLOT 1 1747-SN SCAN_IN 32 SCAN_OUT 32 G_FILE 3\n 0 28945 32755 OPTION baud=115.2K\n"
    "LADDER 2\n"
    "SOR XIC I:1.0/0 OTE O:1.1/0 EOR\n";

const std::string kExampleBench = R"(
scanner RIO slot=1 {
  adapter ASB rack=0 group=0 size=1/2 hold_last_state=off {
    module IN catalog=1746-IB16 group=0
    module OUT catalog=1746-OB16 group=1
  }
  adapter FULL1 rack=1 group=0 size=full
  adapter FULL2 rack=2 group=0 size=full
  adapter Q0 rack=3 group=0 size=1/4 hold_last_state=on
  adapter Q2 rack=3 group=2 size=1/4
  adapter Q4 rack=3 group=4 size=1/4
}
)";

TEST(RioLink, ScanTimeIsTRio) {
  // Appendix A example: T_RIO = 1(4.0 ms) + 2(5.5 ms) + 3(3.5 ms) = 25.5 ms.
  Bench b(kExampleProgram, kExampleBench);
  b.run();
  b->run_for(milliseconds(300));
  EXPECT_GE(b.sn().rio_scans(), 10u);
  EXPECT_EQ(b.sn().last_rio_scan(), microseconds(25500));
  EXPECT_EQ(*b->observe("RIO", "rio scan time"), (std::vector<std::int64_t>{25500000}));
}

TEST(RioLink, ScanTimeAtEachBaudRate) {
  // One full rack and one 1/4 rack: 9.5 + 6.0 at 57.6K, 5.5 + 3.5 at 115.2K, 3.5 + 2.5 at 230.4K.
  for (auto [opt, expect] : {std::pair<const char*, Nanoseconds>{"57.6K", microseconds(15500)},
                             {"115.2K", microseconds(9000)},
                             {"230.4K", microseconds(6000)}}) {
    Bench b(std::string("START 1747-L532\nSLOT 1 1747-SN SCAN_IN 32 SCAN_OUT 32 G_FILE 3\n 0 17 31 OPTION baud=") + opt +
                "\nLADDER 2\nSOR XIC B3:0/0 OTE B3:0/1 EOR\n",
            "scanner RIO slot=1 {\n  adapter A rack=0 group=0 size=full\n  adapter B rack=1 group=0 size=1/4\n}\n");
    b.run();
    b->run_for(milliseconds(200));
    EXPECT_EQ(b.sn().last_rio_scan(), expect) << opt;
  }
}

TEST(RioLink, RemoteInputToRemoteOutput) {
  Bench b(kExampleProgram, kExampleBench);
  b.run();
  b->run_for(milliseconds(100));
  b.set("I:1.0/0", 1);  // the field input of the IB16 in the remote chassis
  ASSERT_TRUE(b.until([&] { return (*b->observe("OUT", "outputs"))[0] == 1; }, milliseconds(200)));
  EXPECT_EQ(*b->module(1)->field_output(1), 1);
  b.set("I:1.0/0", 0);
  ASSERT_TRUE(b.until([&] { return (*b->observe("OUT", "outputs"))[0] == 0; }, milliseconds(200)));
}

TEST(RioLink, DevicesOfMoreThanOneRackAreOneLogicalDevicePerRack) {
  // Chapter 4: an adapter at rack 0 group 0 with 14 words of image is two logical devices, and
  // two discrete transfers update it: 9.5 ms (full rack) + 7.5 ms (3/4 rack) at 57.6K.
  Bench b("START 1747-L532\nSLOT 1 1747-SN SCAN_IN 32 SCAN_OUT 32 G_FILE 3\n 0 1 127\nLADDER 2\nSOR XIC B3:0/0 OTE B3:0/1 EOR\n",
          "scanner RIO slot=1 {\n  adapter BIG rack=0 group=0 groups=14\n}\n");
  b.run();
  b->run_for(milliseconds(200));
  EXPECT_EQ(b.sn().last_rio_scan(), microseconds(17000));
  EXPECT_EQ(b.m1(10), 0x0001);
}

// Outputs of the remote OB16 for the mode-table tests: the program turns O:1.1/0 on.
struct ModeFixture {
  Bench b;
  explicit ModeFixture(const std::string& extra_rungs = "", bool hls = false)
      : b("START 1747-L532\nSLOT 1 1747-SN SCAN_IN 32 SCAN_OUT 32 G_FILE 3\n 0 1 3 OPTION baud=230.4K\nLADDER 2\n"
          "SOR OTE O:1.1/0 EOR\n" + extra_rungs,
          std::string("scanner RIO slot=1 {\n  adapter ASB rack=0 group=0 size=1/2 hold_last_state=") + (hls ? "on" : "off") +
              " {\n    module OUT catalog=1746-OB16 group=1\n  }\n}\n") {}
  std::int64_t out() { return (*b->observe("OUT", "outputs"))[0]; }
  void settle() { b->run_for(milliseconds(60)); }
};

TEST(ModeTable, InRunOutputsFollowTheImageAndDeviceResetTurnsThemOff) {
  // "Example 2 - Once the SLC processor is in Run mode, the bits in the Remote Output Reset word
  // have no effect on the RIO link device's outputs. Setting the appropriate bits in the Device
  // Reset Word to 1 instructs the RIO link device to reset its outputs."
  ModeFixture f("SOR XIC B3:0/0 OTE M0:1.16/0 EOR\nSOR XIC B3:0/1 OTU M0:1.24/0 EOR\n");
  f.b.run();
  f.settle();
  EXPECT_EQ(f.out(), 1);
  f.b.set("B3:0/1", 1);  // ROR = 0: no effect in Run
  f.settle();
  EXPECT_EQ(f.out(), 1);
  f.b.set("B3:0/0", 1);  // DR = 1
  f.settle();
  EXPECT_EQ(f.out(), 0);
  f.b.set("B3:0/0", 0);
  f.settle();
  EXPECT_EQ(f.out(), 1);
}

TEST(ModeTable, RunToProgramWithDefaultsResetsEvenWithHoldLastState) {
  // Default ROR = 1: "These two combinations will reset device outputs" (Run -> Program).
  ModeFixture f("", true);
  f.b.run();
  f.settle();
  ASSERT_EQ(f.out(), 1);
  ASSERT_TRUE(f.b->set_mode(Mode::Program));
  f.settle();
  EXPECT_EQ(f.out(), 0);
}

TEST(ModeTable, RunToProgramWithDrAndRorClearTheHoldLastStateSwitchDecides) {
  // "Example 3 - When going from Run to Program mode, if both of the appropriate bits in the
  // Device Reset and Remote Output Reset words are reset to 0 before leaving Run mode, the RIO
  // link device is instructed to decide whether to hold its last output state or to reset".
  for (bool hls : {true, false}) {
    ModeFixture f("SOR OTU M0:1.24/0 EOR\n", hls);
    f.b.run();
    f.settle();
    ASSERT_EQ(f.out(), 1);
    ASSERT_TRUE(f.b->set_mode(Mode::Program));
    f.b->run_for(milliseconds(500));  // well past the adapter's communication time-out
    EXPECT_EQ(f.out(), hls ? 1 : 0) << "hold last state " << hls;
  }
}

TEST(ModeTable, ProgramToRunSetsTheDefaultsAndOutputsFollowAfterTheFirstScan) {
  // "Program -> Run: DR = 0 ROR = 1 Default values are set automatically. Outputs reflect those of
  // the scanner output image." and "The outputs of the RIO are updated after the end of the first
  // SLC processor scan."
  ModeFixture f("SOR OTU M0:1.24/0 EOR\n", true);
  f.b.run();
  f.settle();
  ASSERT_TRUE(f.b->set_mode(Mode::Program));
  f.settle();
  EXPECT_EQ(f.b.m0(24), 0) << "the program's ROR = 0 stays until Run entry";
  ASSERT_TRUE(f.b->set_mode(Mode::Run));
  EXPECT_EQ(f.b.m0(24), 1) << "the default is set on entering Run";
  f.settle();
  EXPECT_EQ(f.out(), 1);
}

TEST(ModeTable, TestModeResetsOutputsUnlessRorIsClearedOnTheFirstScan) {
  // "Program -> Test: DR = 0 ROR = 1 These default values are set automatically. Outputs are
  // reset, unless ROR is changed to 0 on the first scan."
  {
    ModeFixture f("", true);
    f.b.run();
    f.settle();
    ASSERT_EQ(f.out(), 1);
    ASSERT_TRUE(f.b->set_mode(Mode::Program));
    ASSERT_TRUE(f.b->set_mode(Mode::Test));
    f.b->scan(1);
    f.b->run_for(milliseconds(60));
    EXPECT_EQ(f.out(), 0);
  }
  {
    // Run -> Test with ROR cleared by the program: the hold-last-state switch is valid.
    ModeFixture f("SOR OTU M0:1.24/0 EOR\n", true);
    f.b.run();
    f.settle();
    ASSERT_EQ(f.out(), 1);
    ASSERT_TRUE(f.b->set_mode(Mode::Test));
    f.b->scan(1);  // the first (single) scan clears ROR again
    for (int i = 0; i < 10; ++i) {
      f.b->scan(1);
      f.b->run_for(milliseconds(10));
    }
    EXPECT_EQ(f.out(), 1);
  }
}

TEST(ModeTable, FaultModeResetsOutputs) {
  ModeFixture g("SOR XIC B3:0/0 OTE S:5/0 EOR\n");
  g.b.run();
  g.settle();
  ASSERT_EQ(g.out(), 1);
  g.b.set("B3:0/0", 1);  // overflow trap left set: fault 0020h at END
  g.b->scan(1);
  ASSERT_EQ(g.b.fault_code(), 0x0020);
  g.settle();
  EXPECT_EQ(g.out(), 0);
}

// The adapter's communication watchdog ("Inhibited devices eventually time out and either return
// to their last state or reset"; decision: comm_timeout, 100 ms by default, docs/1747-sn.md "The
// RIO link in virtual time"). One 1/2 rack ASB at 115.2K, so a RIO scan is its one visit, 4.0 ms
// (appendix A, "RIO Scan Times for Adapters"), ending at multiples of 4 ms from Run entry at 0;
// its OB16's terminals follow 1 ms after the adapter drives them. The adapter goes off line, so
// its last exchange ends the visit under way then (answered when it started), and its outputs reset
// comm_timeout later:
// at once without a backplane scan, else at the first backplane scan from then on. A scan at the
// same time as the expiry was scheduled one backplane scan before it, after the watchdog was armed,
// so the reset applies at that scan (100 ms: the expiry falls on a scan, at 164 ms and at 300 ms;
// 98 ms: 2 ms before one). The last case is the one where the softslc scanner's single watchdog
// event (rio_scanner.cpp, arm_watchdog) is moved to the expiry only after that backplane scan was
// scheduled, so the scan must let the watchdog expire first: without that it resets 10 ms late
// (tried).
TEST(RioLink, AnAdapterThatHearsNothingResetsItsOutputsCommTimeoutAfterItsLastExchange) {
  struct Case {
    const char* backplane;  // the adapter's backplane_scan setting ("" = none)
    int timeout_ms;
    int offline_at_ms;  // when the adapter goes off line (at the end of a scan from then on)
    int off_after_ms;   // after the last exchange, to the terminals
  };
  for (const Case c : {Case{"", 100, 61, 101}, Case{" backplane_scan=4ms", 100, 61, 101},
                       Case{" backplane_scan=4ms", 98, 61, 101}, Case{" backplane_scan=10ms", 100, 197, 101}}) {
    Bench b("START 1747-L532\nSLOT 1 1747-SN SCAN_IN 32 SCAN_OUT 32 G_FILE 3\n 0 1 3 OPTION baud=115.2K\nLADDER 2\n"
            "SOR OTE O:1.1/0 EOR\n",
            std::string("scanner RIO slot=1 {\n  adapter ASB rack=0 group=0 size=1/2") + c.backplane +
                " comm_timeout=" + std::to_string(c.timeout_ms) +
                "ms {\n    module OUT catalog=1746-OB16 group=1 output_delay=1ms\n  }\n}\n");
    const std::string what = std::string("backplane") + c.backplane + ", time-out " + std::to_string(c.timeout_ms);
    b.run();
    b->run_for(milliseconds(c.offline_at_ms) + microseconds(300));
    ASSERT_EQ((*b->observe("OUT", "outputs"))[0], 1) << what;
    // The visit under way was answered: the last exchange is its end.
    const VirtualTime last = (b->now() / milliseconds(4) + 1) * milliseconds(4);
    if (c.offline_at_ms == 197) {
      ASSERT_EQ(last, milliseconds(200)) << what;
    }
    b.inject("ASB", "offline");
    b->run_for(milliseconds(300));
    EXPECT_EQ((*b->observe("OUT", "outputs"))[0], 0) << what;
    EXPECT_EQ((*b->observe("OUT", "output changed at"))[0], last + milliseconds(c.off_after_ms)) << what;
    b.inject("ASB", "online");
    b->run_for(milliseconds(50));
    EXPECT_EQ((*b->observe("OUT", "outputs"))[0], 1) << what;
  }
}

// The same watchdog when it runs out at every visit: comm_timeout equal to the 4.0 ms visit. Each
// visit's exchange re-arms it for the end of the next visit, where it expires (the visit's event
// was scheduled after the arm) and the exchange then drives the outputs again. The backplane scan
// every 8 ms falls on every other visit end; it was scheduled 8 ms before, before the watchdog was
// armed, so it drives the outputs before the watchdog clears them: the terminals stay on.
TEST(RioLink, AWatchdogRunningOutAtEachVisitLeavesTheOutputsAsTheBackplaneScanFindsThem) {
  Bench b("START 1747-L532\nSLOT 1 1747-SN SCAN_IN 32 SCAN_OUT 32 G_FILE 3\n 0 1 3 OPTION baud=115.2K\nLADDER 2\n"
          "SOR OTE O:1.1/0 EOR\n",
          "scanner RIO slot=1 {\n  adapter ASB rack=0 group=0 size=1/2 backplane_scan=8ms comm_timeout=4ms {\n"
          "    module OUT catalog=1746-OB16 group=1 output_delay=1ms\n  }\n}\n");
  b.run();
  b->run_for(milliseconds(50));
  ASSERT_EQ((*b->observe("OUT", "outputs"))[0], 1);
  const std::int64_t on_at = (*b->observe("OUT", "output changed at"))[0];
  b->run_for(milliseconds(200));
  EXPECT_EQ((*b->observe("OUT", "outputs"))[0], 1);
  EXPECT_EQ((*b->observe("OUT", "output changed at"))[0], on_at);
}

TEST(RioLink, InhibitedDeviceIsNotScanned) {
  Bench b(kExampleProgram + "SOR XIC B3:0/0 OTE M0:1.11/0 EOR\n", kExampleBench);
  b.run();
  b->run_for(milliseconds(200));
  ASSERT_TRUE(b.m1(10) & (1u << 12));
  b.set("B3:0/0", 1);  // inhibit the 1/4 rack at rack 3 group 0
  b->run_for(milliseconds(200));
  // "Devices that are inhibited in the M0 file ... are represented by a 0" in word 10; the RIO
  // scan no longer visits it (25.5 - 3.5 ms).
  EXPECT_FALSE(b.m1(10) & (1u << 12));
  EXPECT_EQ(b.sn().last_rio_scan(), microseconds(22000));
  EXPECT_EQ(b.m1(15), 0) << "inhibiting does not fault the device";
  EXPECT_EQ(b.m1(0) & 1, 0);
}

TEST(RioLink, OfflineDeviceIsRetriedOnceThenFaultedAndRecovers) {
  Bench b(kExampleProgram, kExampleBench);
  b.run();
  b->run_for(milliseconds(100));
  b.inject("Q2", "offline");
  b->run_for(milliseconds(200));
  EXPECT_EQ(b.m1(15), 0b0010);  // rack 3 quarter 1 (group 2)
  EXPECT_EQ(b.m1(0), 0x0003);
  EXPECT_EQ(b.m1(16 + 13), 1) << "one retry before the device was declared faulted";
  EXPECT_EQ(*b->observe("Q2", "faulted"), (std::vector<std::int64_t>{1}));
  b.inject("Q2", "online");
  b->run_for(milliseconds(100));
  EXPECT_EQ(b.m1(15), 0);
  EXPECT_EQ(b.m1(0), 0x0002);
  EXPECT_TRUE(b.m1(10) & (1u << 13));
}

TEST(RioLink, WrongSizeOrPrimaryModeFaultsTheDevice) {
  Bench b(kExampleProgram, kExampleBench);
  b.run();
  b.inject("FULL2", "data size", {"6"});
  b->run_for(milliseconds(200));
  // "configured to an incorrect logical rack size": all bits of the device set.
  EXPECT_EQ(b.m1(14), 0b1111);
  EXPECT_EQ(b.m1(16 + 8), 0) << "no retries for an answer of the wrong size";
  b.inject("FULL2", "normal");
  b->run_for(milliseconds(100));
  EXPECT_EQ(b.m1(14), 0);
  // "If you configure your system so that complementary I/O is not selected ..., you must not set
  // up any of the actual devices to be in the primary mode. If you do, the system will flag the
  // device as faulted".
  Bench p(kExampleProgram,
          "scanner RIO slot=1 {\n  adapter ASB rack=0 group=0 size=1/2 chassis=primary\n}\n");
  p.run();
  p->run_for(milliseconds(200));
  EXPECT_EQ(p.m1(12), 0b0011);
}

TEST(RioLink, NoisyLinkCountsRetriesAndRetryCountersClearOnModeChanges) {
  Bench b(kExampleProgram, kExampleBench);
  b.inject("FULL1", "noisy", {"2"});
  b.run();
  b->run_for(milliseconds(500));
  const std::uint16_t retries = b.m1(16 + 4);
  EXPECT_GE(retries, 8);
  EXPECT_EQ(b.m1(13), 0) << "a retried transfer that succeeds does not fault the device";
  // Not cleared Run -> Program; cleared Program -> Run (and Test -> Run, Program -> Test).
  ASSERT_TRUE(b->set_mode(Mode::Program));
  EXPECT_GE(b.m1(16 + 4), retries);
  b.inject("FULL1", "noisy", {"off"});
  ASSERT_TRUE(b->set_mode(Mode::Run));
  EXPECT_EQ(b.m1(16 + 4), 0);
  b->run_for(milliseconds(100));
  EXPECT_EQ(b.m1(16 + 4), 0);
}

TEST(RioLink, RetryCountersClearOnlyOnTheDocumentedModeChanges) {
  // "The scanner clears the retry counters when going from Program to Run mode, Test to Run mode,
  // and when going from Program to Test mode."
  Bench b(kExampleProgram, kExampleBench);
  b.inject("FULL1", "noisy", {"1"});  // every transfer needs a retry
  b.run();
  b->run_for(milliseconds(200));
  ASSERT_GT(b.m1(20), 0);
  ASSERT_TRUE(b->set_mode(Mode::Test));  // Run -> Test: kept
  EXPECT_GT(b.m1(20), 0);
  ASSERT_TRUE(b->set_mode(Mode::Run));  // Test -> Run: cleared
  EXPECT_EQ(b.m1(20), 0);
  b->run_for(milliseconds(200));
  ASSERT_GT(b.m1(20), 0);
  ASSERT_TRUE(b->set_mode(Mode::Program));
  ASSERT_TRUE(b->set_mode(Mode::Test));  // Program -> Test: cleared
  EXPECT_EQ(b.m1(20), 0);
}

TEST(RioLink, ControlFunctionsOfThePrimaryApplyToItsComplementaryDevice) {
  // "Control functions (i.e., device inhibit, device reset, and device output reset) are only
  // selectable for the primary device, but also apply to the complementary device." "When a
  // primary device is inhibited, its complementary device is also inhibited."
  Bench b("START 1747-L532\nSLOT 1 1747-SN SCAN_IN 32 SCAN_OUT 32 G_FILE 5\n 0 1 1 1 1 OPTION baud=230.4K\nLADDER 2\n"
          "SOR XIC B3:0/0 OTE M0:1.8/0 EOR\n",
          "scanner RIO slot=1 {\n  adapter P rack=0 group=0 size=1/4 chassis=primary\n  adapter C rack=8 group=0 size=1/4\n}\n");
  b.run();
  b->run_for(milliseconds(50));
  EXPECT_EQ(b.m1(10), 1);
  EXPECT_EQ(b.m1(5), 1);
  b.set("B3:0/0", 1);
  b->run_for(milliseconds(50));
  EXPECT_EQ(b.m1(10), 0);
  EXPECT_EQ(b.m1(5), 0);
}

TEST(RioLink, CommunicationsAttemptedAndActiveStatus) {
  Bench b(kExampleProgram, kExampleBench);
  b.run();
  // "Until this bit is set, all devices in M1 file word 10 (active device status) appear to be
  // inactive."
  EXPECT_EQ(b.m1(0) & 2, 0);
  EXPECT_EQ(b.m1(10), 0);
  b->run_for(milliseconds(30));
  EXPECT_EQ(b.m1(0) & 2, 2);
  EXPECT_EQ(b.m1(10), 0x7111);
}

TEST(RioLink, CableRemovedAtTheScannerFaultsEveryDevice) {
  Bench b(kExampleProgram, kExampleBench);
  b.run();
  b->run_for(milliseconds(100));
  b.inject("RIO", "cable removed");
  b->run_for(milliseconds(200));
  EXPECT_EQ(b.m1(0) & 1, 1);
  EXPECT_EQ(b.m1(10), 0);
  EXPECT_EQ(b.m1(12), 0b0011);
  EXPECT_EQ(b.m1(13), 0b1111);
  EXPECT_EQ(b.m1(14), 0b1111);
  EXPECT_EQ(b.m1(15), 0b0111);
  b.inject("RIO", "cable restored");
  b->run_for(milliseconds(100));
  EXPECT_EQ(b.m1(0), 2);
}

TEST(RioLink, ComplementaryChassisShareTheImage) {
  // Chapter 1, "Complementary I/O": an input module in the primary chassis and an output module in
  // the same slot of the complementary chassis share the logical group; inputs of both chassis
  // appear in the one image.
  Bench b("START 1747-L532\nSLOT 1 1747-SN SCAN_IN 32 SCAN_OUT 32 G_FILE 5\n 0 1 1 1 1 OPTION baud=230.4K\nLADDER 2\n"
          "SOR XIC I:1.0/0 OTE O:1.1/3 EOR\nSOR XIC I:1.1/5 OTE O:1.0/4 EOR\n",
          "scanner RIO slot=1 {\n"
          "  adapter P rack=0 group=0 size=1/4 chassis=primary {\n"
          "    module PIN catalog=1746-IB16 group=0\n"
          "    module POUT catalog=1746-OB16 group=1\n"
          "  }\n"
          "  adapter C rack=8 group=0 size=1/4 {\n"
          "    module COUT catalog=1746-OB16 rack=8 group=0\n"
          "    module CIN catalog=1746-IB16 rack=8 group=1\n"
          "  }\n"
          "}\n");
  b.run();
  b.set("I:1.0/0", 1);
  b.set("I:1.1/5", 1);
  b->run_for(milliseconds(100));
  EXPECT_EQ((*b->observe("POUT", "outputs"))[0], 1 << 3);
  EXPECT_EQ((*b->observe("COUT", "outputs"))[0], 1 << 4);
  EXPECT_EQ(b.m1(10), 1);
  EXPECT_EQ(b.m1(5), 1);
  EXPECT_EQ(b.m1(3), 1);
  EXPECT_EQ(b.m1(4), 1);
  // A fault of the complementary device shows in bits 4-7 of the fault word.
  b.inject("C", "offline");
  b->run_for(milliseconds(100));
  EXPECT_EQ(b.m1(12), 0x0010);
}

TEST(RunEntryFaults, MissingInvalidAndDuplicate) {
  // Chapter 6: 62H "G file is missing", 63H "Invalid G file configuration", 64H "Duplicate node
  // detected", in S:6 (softslc puts the slot in the high byte, as for xx55h).
  {
    Bench b("START 1747-L532\nSLOT 2 1747-SN SCAN_IN 32 SCAN_OUT 32\nLADDER 2\nSOR XIC B3:0/0 OTE B3:0/1 EOR\n", "");
    b.run();
    EXPECT_EQ(b.fault_code(), 0x0262);
    EXPECT_EQ(b->mode(), Mode::Faulted);
    EXPECT_EQ(b.i("S:6"), 0x0262);
  }
  {
    Bench b("START 1747-L532\nSLOT 2 1747-SN SCAN_IN 32 SCAN_OUT 32 G_FILE 3\n 0 0 0\nLADDER 2\nSOR XIC B3:0/0 OTE B3:0/1 EOR\n",
            "", /*allow_errors=*/true);
    EXPECT_FALSE(b.setup.ok());
    b.run();
    EXPECT_EQ(b.fault_code(), 0x0263);
    EXPECT_NE(b->fault()->message.find("at least one complementary device"), std::string::npos);
    // Test mode takes the G file too.
    b->clear_fault();
    ASSERT_TRUE(b->set_mode(Mode::Test));
    EXPECT_EQ(b.fault_code(), 0x0263);
  }
  {
    Bench b("START 1747-L532\nSLOT 2 1747-SN SCAN_IN 32 SCAN_OUT 32 G_FILE 3\n 0 1 1\nLADDER 2\nSOR XIC B3:0/0 OTE B3:0/1 EOR\n",
            "scanner RIO slot=2 duplicate_node=on\n");
    b.run();
    EXPECT_EQ(b.fault_code(), 0x0264);
    b->clear_fault();
    b.inject("RIO", "normal");
    b.run();
    EXPECT_EQ(b.fault_code(), 0);
    b->run_for(milliseconds(20));
    b.inject("RIO", "duplicate node");
    EXPECT_EQ(b.fault_code(), 0x0264);
  }
}

// The adapters' chassis scans, with two adapters sharing a backplane_scan (the scanner runs their
// scans in one event, rio_scanner.cpp schedule_backplanes) and one with its own. Three 1/4-rack
// adapters at 230.4K: 2.5 ms visits (appendix A), T_RIO 7.5 ms from Run entry at 0, so A's visits
// end at 2.5 + 7.5n ms, B's at 5 + 7.5n, C's at 7.5 + 7.5n. A and B scan their chassis every 4 ms,
// C every 3 ms, from power-up at 0. An input set at time s is in the adapter's input buffer from its
// first backplane scan after s, and the scanner receives it at the adapter's first visit ending at
// or after that scan; where a scan and a visit end at the same time, the scan runs first (it was
// scheduled one backplane_scan before, the visit one visit before). Each case sets the input just
// after `set_after` and expects it received at `expected`; the ties are A at 40 ms, B at 20 ms and
// C at 15 ms. Grouping C with A and B (scanning it every 4 ms) fails the C cases, and so would a
// merged event that ran after the visit ending at its time.
TEST(RioLink, EachChassisScansAtItsOwnBackplaneScanAndBeforeAVisitEndingThen) {
  struct Case {
    const char* module;
    const char* adapter;
    int set_after_us;
    int expected_us;
    int next_scan_us;  // the adapter's first backplane scan after set_after
  };
  for (const Case c : {Case{"INA", "A", 36100, 40000, 40000}, Case{"INA", "A", 40100, 47500, 44000},
                       Case{"INB", "B", 16100, 20000, 20000}, Case{"INB", "B", 20100, 27500, 24000},
                       Case{"INC", "C", 12100, 15000, 15000}, Case{"INC", "C", 15100, 22500, 18000},
                       Case{"INC", "C", 18100, 22500, 21000}}) {
    const std::string what = std::string(c.module) + " set after " + std::to_string(c.set_after_us) + " us";
    Bench b("START 1747-L532\nSLOT 1 1747-SN SCAN_IN 32 SCAN_OUT 32 G_FILE 3\n 0 7 7 OPTION baud=230.4K\nLADDER 2\n"
            "SOR XIC B3:0/0 OTE B3:0/1 EOR\n",
            "scanner RIO slot=1 {\n"
            "  adapter A rack=0 group=0 size=1/4 backplane_scan=4ms {\n    module INA catalog=1746-IB16 group=0\n  }\n"
            "  adapter B rack=0 group=2 size=1/4 backplane_scan=4ms {\n    module INB catalog=1746-IB16 group=2\n  }\n"
            "  adapter C rack=0 group=4 size=1/4 backplane_scan=3ms {\n    module INC catalog=1746-IB16 group=4\n  }\n"
            "}\n");
    b.run();
    b->run_for(microseconds(c.set_after_us));
    ASSERT_LT(b->now(), microseconds(c.next_scan_us)) << what << ": the scans are too long for the case";
    b.inject(c.module, "input", {"1"});
    VirtualTime before = b->now();
    while ((*b->observe(c.adapter, "inputs"))[0] == 0 && b->now() < milliseconds(100)) {
      before = b->now();
      b->scan(1);
    }
    EXPECT_LT(before, microseconds(c.expected_us)) << what;
    EXPECT_GE(b->now(), microseconds(c.expected_us)) << what;
    EXPECT_EQ(b.sn().last_rio_scan(), microseconds(7500)) << what;
  }
}

TEST(RioLink, Deterministic) {
  auto run = [] {
    Bench b(kExampleProgram, kExampleBench);
    b.inject("FULL1", "noisy", {"3"});
    b.run();
    std::vector<std::uint16_t> trace;
    for (int i = 0; i < 200; ++i) {
      if (i == 50) b.set("I:1.0/0", 1);
      if (i == 120) b.inject("Q2", "offline");
      b->scan(1);
      trace.push_back(b.m1(0));
      trace.push_back(b.m1(15));
      trace.push_back(b.m1(20));
      trace.push_back(static_cast<std::uint16_t>((*b->observe("OUT", "outputs"))[0]));
      trace.push_back(static_cast<std::uint16_t>(b->now() & 0xFFFF));
    }
    return trace;
  };
  EXPECT_EQ(run(), run());
}

}  // namespace
}  // namespace softslc::test
