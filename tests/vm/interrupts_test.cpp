// Program control and interrupts: SUS, REF, the selectable timed interrupt (S:30, S:31, S:2/0-2,
// S:5/10, S:36/9, STD, STE, STS) and the user fault routine (S:29).
//
// Sources: 1747-RM001G chapter 11 "Understanding Interrupt Routines": p. 11-2 (user fault routine,
// table 11.2: recoverable faults are cleared by clearing S:1/13; non-recoverable ones run the
// routine for one pass), p. 11-4 (the example that recovers 0020h and 0034h), p. 11-8 (STI
// overview; 5/03 setpoint range), p. 11-12 (S:31 file 3-255, 0 disables, invalid -> 0023h; S:30
// setpoint, invalid -> 0024h; timing starts at the end of the scan that loaded them; S:2/0 pending;
// S:2/1 enable, default set), p. 11-13 (S:2/2 executing; S:5/10 overflow when the timer expires
// while the routine runs or while one is pending; S:36/9 lost when an expiry finds one pending);
// p. B-43 (S:24 restored after an STI or fault routine), B-19 via facts §3 (S:3 count restarts on
// return from REF), PT1 30-3 (S:0, S:13/S:14, S:24 saved around the STI), PT1 20-2 via facts §3
// (S:5/0 still set at END, TND or REF is fault 0020h), DF1 p. 10-3 via facts §3 (S:1/0-4 = 3 in
// Suspend Idle). Where the manual is silent the choice is written in docs/semantics.md
// "Program control and interrupts" and the test says so.
#include <gtest/gtest.h>

#include <cstdlib>

#include "vm_test_util.h"

namespace softslc::test {
namespace {

constexpr Nanoseconds kMs = kNsPerMs;

// ---- SUS -------------------------------------------------------------------------------------------------------

TEST(Suspend, TrueSusStoresIdAndFileAndStopsInSuspendIdle) {
  Plc plc(
      "SOR OTE O:2/0 EOR\n"
      "SOR JSR 3 EOR\n"
      "SOR ADD N7:0 1 N7:0 EOR\n"
      "LADDER 3\n"
      "SOR SBR XIC B3:0/0 SUS 42 EOR\n"
      "SOR ADD N7:1 1 N7:1 EOR");
  plc.run_scans(2);
  EXPECT_EQ(plc.i("N7:0"), 2);
  ASSERT_EQ(plc->module(2)->field_output(0), std::optional<std::uint16_t>(1)) << "Run: O:2/0 is on";
  plc.set("B3:0/0", 1);
  plc->scan(1);
  EXPECT_EQ(plc->mode(), Mode::Suspended);
  EXPECT_FALSE(plc->fault().has_value()) << "a suspend is not a fault";
  EXPECT_EQ(plc.i("S:7"), 42) << "suspend ID";
  EXPECT_EQ(plc.i("S:8"), 3) << "the file holding the SUS";
  EXPECT_EQ(plc.i("S:1") & 0x1F, 3) << "S:1/0-4 = 3, idle (SUS)";
  EXPECT_EQ(plc.i("S:1") & (1 << 13), 0) << "S:1/13 not set";
  EXPECT_EQ(plc.i("S:6"), 0);
  EXPECT_EQ(plc.i("N7:1"), 2) << "the rung after the SUS did not run";
  EXPECT_EQ(plc.i("N7:0"), 2) << "nor the rest of file 2";
  EXPECT_EQ(plc->module(2)->field_output(0), std::optional<std::uint16_t>(0)) << "outputs de-energised";
  plc->scan(3);
  EXPECT_EQ(plc.i("N7:0"), 2) << "no program scan in Suspend Idle";
  // Back to Run with the condition false: the program runs again; S:7/S:8 keep the last SUS.
  plc.set("B3:0/0", 0);
  ASSERT_TRUE(plc->set_mode(Mode::Run));
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:0"), 3);
  EXPECT_EQ(plc.i("S:7"), 42);
  EXPECT_FALSE(plc->set_mode(Mode::Suspended)) << "only a SUS suspends";
}

TEST(Suspend, FalseSusDoesNothing) {
  Plc plc("SOR XIC B3:0/0 SUS -7 EOR\nSOR ADD N7:0 1 N7:0 EOR");
  plc.run_scans(3);
  EXPECT_EQ(plc->mode(), Mode::Run);
  EXPECT_EQ(plc.i("N7:0"), 3);
  plc.set("B3:0/0", 1);
  plc->scan(1);
  EXPECT_EQ(plc.i("S:7"), -7) << "suspend ID -32768..32767";
}

TEST(Suspend, NotOnTheFixedControllers) {
  std::string errors;
  auto rt = try_build("START 1747-L20\nLADDER 2\nSOR SUS 1 EOR\n", errors);
  EXPECT_EQ(rt, nullptr);
  EXPECT_NE(errors.find("SUS is not available"), std::string::npos) << errors;
}

// ---- REF -------------------------------------------------------------------------------------------------------

TEST(Refresh, RefDoesAnOutputAndAnInputScanMidScan) {
  std::vector<CountingInputs*> cards;
  RuntimeOptions opts = counting_cards(cards);
  Plc plc(
      "SOR MOV I:1.0 N7:0 EOR\n"
      "SOR OTE O:2/3 EOR\n"
      "SOR REF EOR\n"
      "SOR MOV I:1.0 N7:1 EOR\n"
      "SOR OTU O:2/3 EOR",
      std::move(opts));
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:0"), 1) << "the input scan";
  EXPECT_EQ(plc.i("N7:1"), 2) << "REF read the inputs again";
  CountingInputs* out = cards[1];
  ASSERT_EQ(out->outputs.size(), 2u) << "REF's output scan, then the scan's own";
  EXPECT_EQ(out->outputs[0][0], 1u << 3) << "REF delivered O:2/3 mid-scan";
  EXPECT_EQ(out->outputs[1][0], 0u);
}

TEST(Refresh, OverflowTrapStillSetAtRefIsFault0020) {
  Plc plc(
      "SOR MUL 30000 30000 N7:0 EOR\n"
      "SOR REF EOR\n"
      "SOR OTU S:5/0 EOR");
  plc.run_scans(1);
  EXPECT_EQ(plc.fault_code(), 0x0020) << "PT1 20-2: S:5/0 at END, TND or REF";
  EXPECT_EQ(plc->fault()->rung, 1);
}

// A JMP loop of N7:51 iterations, about 6.4 us each on the 5/03 profile (measured through
// stats(): 1000 iterations make a 6.4 ms scan), with label `label`.
std::string slow_rungs(int label = 1) {
  const std::string l = std::to_string(label);
  return "SOR CLR N7:50 EOR\n"
         "SOR LBL " + l + " ADD N7:50 1 N7:50 EOR\n"
         "SOR LES N7:50 N7:51 JMP " + l + " EOR\n";
}
constexpr int kLoops35ms = 5500;

TEST(Refresh, ScanToggleBitChangesAtEveryEndAndRef) {
  // RM B-48: S:33/9 is cleared on entry into Run and changes state at every END, TND or REF.
  Plc plc("SOR MOV S:33 N7:0 EOR\nSOR XIC B3:0/0 REF EOR\nSOR MOV S:33 N7:1 EOR");
  plc.set("S:33", 1 << 9);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:0") & (1 << 9), 0) << "cleared on entry into Run";
  EXPECT_TRUE(plc.i("S:33") & (1 << 9)) << "the END toggled it";
  plc.set("B3:0/0", 1);
  plc->scan(1);
  EXPECT_TRUE(plc.i("N7:0") & (1 << 9));
  EXPECT_EQ(plc.i("N7:1") & (1 << 9), 0) << "the REF toggled it";
  EXPECT_TRUE(plc.i("S:33") & (1 << 9)) << "and the END again";
}

TEST(Refresh, RefRestartsTheWatchdogCount) {
  // Two long loops, each under the 100 ms watchdog, together over it.
  const std::string body = slow_rungs(1) + "SOR REF EOR\n" + slow_rungs(2) +
                           "SOR ADD N7:0 1 N7:0 EOR";
  Plc with_ref(body);
  with_ref.set("N7:51", 10000);  // about 54 ms per loop
  with_ref.run_scans(1);
  ASSERT_GT(with_ref->stats().last, 100 * kMs) << "the scan is longer than the watchdog";
  EXPECT_FALSE(with_ref->fault().has_value()) << "RM B-19: the count restarts on return from REF";
  EXPECT_EQ(with_ref.i("N7:0"), 1);

  std::string no_ref = body;
  no_ref.replace(no_ref.find("SOR REF EOR\n"), 12, "");
  Plc without(no_ref);
  without.set("N7:51", 10000);
  without.run_scans(1);
  EXPECT_EQ(without.fault_code(), 0x0022);
}

// ---- The selectable timed interrupt ----------------------------------------------------------------------------

// STI file 3 counts its runs in N7:0; S:30 = 1 (10 ms), S:31 = 3 are loaded before Run.
Plc sti_plc(std::string_view main, std::string_view sti_rungs = "SOR ADD N7:0 1 N7:0 EOR",
            std::string_view extra = "") {
  Plc plc(std::string(main) + "\nLADDER 3\n" + std::string(sti_rungs) + "\n" + std::string(extra));
  plc.set("S:30", 1);
  plc.set("S:31", 3);
  return plc;
}

// The number of 10 ms expiries between `start` and now.
std::int64_t expiries(Plc& plc, VirtualTime start) { return (plc->now() - start) / (10 * kMs); }

TEST(Sti, RunsEvery10msWithAShortMainScan) {
  Plc plc = sti_plc("SOR ADD N7:1 1 N7:1 EOR");
  EXPECT_TRUE(plc.i("S:2") & 0x0002) << "S:2/1 enable defaults to set (RM 11-12)";
  plc.run();
  const VirtualTime start = plc->now();
  plc->run_for(1000 * kMs);
  ASSERT_LT(plc->stats().max, 5 * kMs) << "short main scan";
  EXPECT_FALSE(plc->fault().has_value());
  EXPECT_LE(std::llabs(plc.i("N7:0") - expiries(plc, start)), 1) << "one run per 10 ms of virtual time";
  EXPECT_GT(plc.i("N7:1"), 200) << "many main scans";
  EXPECT_EQ(plc.i("S:2") & 0x0005, 0) << "not pending, not executing between scans";
}

TEST(Sti, RunsEvery10msWhateverTheMainScanLength) {
  Plc plc = sti_plc(slow_rungs() + "SOR ADD N7:1 1 N7:1 EOR");
  plc.set("N7:51", kLoops35ms);
  plc.run();
  const VirtualTime start = plc->now();
  plc->run_for(1000 * kMs);
  ASSERT_GT(plc->stats().last, 25 * kMs) << "a main scan several STI periods long";
  ASSERT_LT(plc->stats().max, 100 * kMs) << "under the watchdog";
  EXPECT_FALSE(plc->fault().has_value());
  // Once per scan would be about 28; the STI interrupts the loop's rungs instead.
  EXPECT_LE(std::llabs(plc.i("N7:0") - expiries(plc, start)), 1);
  EXPECT_LT(plc.i("N7:1"), 40);
  EXPECT_EQ(plc.i("S:5") & (1 << 10), 0) << "no overflow: the routine is short";
}

TEST(Sti, ExecutingBitIsSetInsideTheRoutineOnly) {
  Plc plc = sti_plc("SOR XIC S:2/2 OTL B3:0/0 EOR", "SOR XIC S:2/2 OTL B3:0/1 EOR\nSOR XIO S:2/0 OTL B3:0/2 EOR");
  plc.run();
  plc->run_for(100 * kMs);
  EXPECT_FALSE(plc.b("B3:0/0")) << "S:2/2 clear in the main program";
  EXPECT_TRUE(plc.b("B3:0/1")) << "S:2/2 set while the STI file is scanned (RM 11-13)";
  EXPECT_TRUE(plc.b("B3:0/2")) << "S:2/0 reset on starting the routine (RM 11-12)";
}

TEST(Sti, StatusWordsAreRestoredAfterTheRoutine) {
  // The main program keeps S:24 = 3 through a long loop while the STI writes S:24 and S:13.
  Plc plc = sti_plc("SOR MOV 3 S:24 EOR\nSOR MOV 9 S:13 EOR\n" + slow_rungs() +
                        "SOR MOV S:24 N7:20 EOR\nSOR MOV S:13 N7:21 EOR",
                    "SOR MOV 7 S:24 EOR\nSOR MOV 8 S:13 EOR\nSOR ADD N7:0 1 N7:0 EOR");
  plc.set("N7:51", kLoops35ms);
  plc.run_scans(1);
  ASSERT_GE(plc.i("N7:0"), 2) << "the STI ran during the scan";
  EXPECT_EQ(plc.i("N7:20"), 3) << "S:24 restored (RM B-43)";
  EXPECT_EQ(plc.i("N7:21"), 9) << "S:13 restored (PT1 30-3)";
}

TEST(Sti, OverflowAndLostBitsWhenTheRoutineOutlastsItsSetpoint) {
  // The first STI run loops for about 35 ms: the timer expires at +10 ms (routine executing:
  // S:5/10) and again at +20 ms (one already pending: lost, S:36/9).
  Plc plc = sti_plc("SOR ADD N7:1 1 N7:1 EOR",
                    "SOR XIC B3:0/0 RET EOR\nSOR OTL B3:0/0 EOR\n" + slow_rungs() +
                        "SOR ADD N7:0 1 N7:0 EOR");
  plc.set("N7:51", kLoops35ms);
  plc.run();
  plc->run_for(200 * kMs);
  EXPECT_FALSE(plc->fault().has_value());
  EXPECT_TRUE(plc.i("S:5") & (1 << 10)) << "S:5/10 STI overflow (RM 11-13)";
  EXPECT_TRUE(plc.i("S:36") & (1 << 9)) << "S:36/9 STI lost (RM 11-13)";
  EXPECT_EQ(plc.i("N7:0"), 1) << "the long run happened once";
}

TEST(Sti, NoOverflowBitsWhenTheRoutineFits) {
  Plc plc = sti_plc("SOR ADD N7:1 1 N7:1 EOR");
  plc.run();
  plc->run_for(200 * kMs);
  EXPECT_EQ(plc.i("S:5") & (1 << 10), 0);
  EXPECT_EQ(plc.i("S:36") & (1 << 9), 0);
}

TEST(Sti, StdSteRegionIsNotInterrupted) {
  // Rungs 1-5 are protected: the counter the STI keeps does not move across the ~35 ms loop;
  // the expiry inside waits pending and runs as soon as STE enables it.
  Plc plc = sti_plc("SOR STD EOR\n"
                    "SOR MOV N7:0 N7:10 EOR\n" +
                    slow_rungs() +
                    "SOR MOV N7:0 N7:11 EOR\n"
                    "SOR MOV S:2 N7:13 EOR\n"
                    "SOR STE EOR\n"
                    "SOR MOV N7:0 N7:12 EOR");
  plc.set("N7:51", kLoops35ms);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:10"), plc.i("N7:11")) << "no STI inside the STD/STE zone";
  EXPECT_TRUE(plc.i("N7:13") & 0x0001) << "S:2/0 pending inside the zone";
  EXPECT_EQ(plc.i("N7:13") & 0x0002, 0) << "S:2/1 cleared by STD";
  EXPECT_EQ(plc.i("N7:12"), plc.i("N7:11") + 1) << "the pending STI ran right after STE";
  EXPECT_TRUE(plc.i("S:2") & 0x0002) << "STE set S:2/1";
  EXPECT_TRUE(plc.i("S:5") & (1 << 10)) << "expiries while disabled and pending: overflow";
}

TEST(Sti, StsSetsFileAndSetpointAndStartsTheTimer) {
  Plc plc("SOR XIC B3:0/0 OSR B3:0/1 STS 4 2 EOR\n"
          "LADDER 4\n"
          "SOR ADD N7:0 1 N7:0 EOR");
  plc.run();
  plc->run_for(100 * kMs);
  EXPECT_EQ(plc.i("N7:0"), 0) << "S:30/S:31 are 0: no STI";
  plc.set("S:2", 0);  // STS sets the enable bit whatever it was (RM 11-16)
  plc.set("B3:0/0", 1);
  plc->scan(1);
  EXPECT_EQ(plc.i("S:31"), 4);
  EXPECT_EQ(plc.i("S:30"), 2);
  EXPECT_TRUE(plc.i("S:2") & 0x0002);
  const VirtualTime start = plc->now();
  plc->run_for(200 * kMs);
  EXPECT_LE(std::llabs(plc.i("N7:0") - (plc->now() - start) / (20 * kMs)), 1) << "every 20 ms";
}

TEST(Sti, InvalidFileIsFault0023AndInvalidSetpoint0024) {
  Plc file("SOR ADD N7:1 1 N7:1 EOR");
  file.set("S:30", 1);
  file.set("S:31", 9);
  file.run_scans(1);
  EXPECT_EQ(file.fault_code(), 0x0023) << "S:31 names no program file (RM 11-12)";

  Plc setpoint = sti_plc("SOR ADD N7:1 1 N7:1 EOR");
  setpoint.set("S:30", 4000);  // 40,000 ms in 10 ms units: above 32,767 ms (RM 11-8)
  setpoint.run_scans(1);
  EXPECT_EQ(setpoint.fault_code(), 0x0024);

  constexpr std::string_view k502 = "START 1747-L524\nSLOT 1 1746-IB16 SCAN_IN 1 SCAN_OUT 0\n";
  Plc slc502("SOR XIC B3:0/0 STS 3 256 EOR\nLADDER 3\nSOR ADD N7:0 1 N7:0 EOR", {}, k502);
  slc502.run_scans(1);
  EXPECT_FALSE(slc502->fault().has_value());
  slc502.set("B3:0/0", 1);
  slc502->scan(1);
  EXPECT_EQ(slc502.fault_code(), 0x0024) << "5/02: setpoint 1-255 (RM 11-12)";
}

TEST(Sti, ResolutionBitSelectsMillisecondsAtTheTransitionToRun) {
  // RM 11-13: S:2/10 set selects 1 ms units for S:30, read on the Program-to-Run transition.
  Plc plc = sti_plc("SOR ADD N7:1 1 N7:1 EOR");
  plc.set("S:2", 0x0002 | 0x0400);
  plc.set("S:30", 5);
  plc.run();
  const VirtualTime start = plc->now();
  plc->run_for(100 * kMs);
  EXPECT_LE(std::llabs(plc.i("N7:0") - (plc->now() - start) / (5 * kMs)), 1) << "every 5 ms";
  plc.set("S:2", 0x0002);  // cleared while running: no effect until the next entry into Run
  const std::int64_t before = plc.i("N7:0");
  plc->run_for(50 * kMs);
  EXPECT_GE(plc.i("N7:0") - before, 9);

  // RM 11-8: the 5/03 range starts at 2 ms, the 5/04's at 1 ms.
  Plc l532 = sti_plc("SOR ADD N7:1 1 N7:1 EOR");
  l532.set("S:2", 0x0002 | 0x0400);
  l532.set("S:30", 1);
  l532.run_scans(1);
  EXPECT_EQ(l532.fault_code(), 0x0024);
  constexpr std::string_view k504 = "START 1747-L541\nSLOT 1 1746-IB16 SCAN_IN 1 SCAN_OUT 0\n";
  Plc l541("SOR ADD N7:1 1 N7:1 EOR\nLADDER 3\nSOR ADD N7:0 1 N7:0 EOR", {}, k504);
  l541.set("S:2", 0x0002 | 0x0400);
  l541.set("S:30", 1);
  l541.set("S:31", 3);
  l541.run();
  l541->run_for(20 * kMs);
  EXPECT_FALSE(l541->fault().has_value());
  EXPECT_GE(l541.i("N7:0"), 19) << "every 1 ms";
}

TEST(Sti, LoadedSetpointStartsTimingAtTheEndOfThatScan) {
  Plc plc("SOR XIC B3:0/0 MOV 3 S:31 MOV 5 S:30 EOR\nLADDER 3\nSOR ADD N7:0 1 N7:0 EOR");
  plc.run_scans(2);
  plc.set("B3:0/0", 1);
  plc->scan(1);
  const VirtualTime loaded = plc->now();
  plc->run_until([&](const Runtime& r) { return r.value("N7:0").as_int() > 0; }, 200 * kMs);
  // The timer started at the end of that scan's program scan, before its output scan and
  // housekeeping (under 1 ms here), so the first run ends a short scan after 50 ms from there.
  EXPECT_GE(plc->now() - loaded, 49 * kMs);
  EXPECT_LT(plc->now() - loaded, 55 * kMs);
}

TEST(Sti, StoppedOutsideRun) {
  Plc plc = sti_plc("SOR ADD N7:1 1 N7:1 EOR");
  plc.run();
  plc->run_for(50 * kMs);
  ASSERT_TRUE(plc->set_mode(Mode::Program));
  const std::int64_t runs = plc.i("N7:0");
  plc->run_for(100 * kMs);
  EXPECT_EQ(plc.i("N7:0"), runs) << "no STI in Program mode";
}

TEST(Sti, CheckerRules) {
  std::string errors;
  EXPECT_EQ(try_build(program_text("SOR STS 9 1 EOR"), errors), nullptr);
  EXPECT_NE(errors.find("STS names STI file 9"), std::string::npos) << errors;
  errors.clear();
  EXPECT_EQ(try_build(program_text("SOR STS 3 1 EOR\nLADDER 3\nSOR ADD N7:0 1 N7:0 EOR\nSOR INT EOR"), errors),
            nullptr);
  EXPECT_NE(errors.find("INT belongs at the start"), std::string::npos) << errors;
  errors.clear();
  EXPECT_EQ(try_build("START 1747-L511\nLADDER 2\nSOR STD EOR\n", errors), nullptr);
  EXPECT_NE(errors.find("STD is not available"), std::string::npos) << errors;
  errors.clear();
  // The MicroLogix STS (time only, sti_1000ms_live.pdf) starts the STI function file: the MicroLogix
  // 1000 has none (and an SLC takes file and time); the 1100 needs STI:0.PFN to start anything
  // (tests/micrologix "MicroLogixSti"). The SLC form is refused on the MicroLogix.
  EXPECT_EQ(try_build("START Bul.1761\nLADDER 2\nSOR STS 2000 EOR\n", errors), nullptr);
  EXPECT_NE(errors.find("STS with one operand (time) is the MicroLogix 1100, 1200, 1400 and 1500 form"), std::string::npos) << errors;
  errors.clear();
  EXPECT_EQ(try_build("START Bul.1763\nLADDER 2\nSOR STS 2000 EOR\n", errors), nullptr);
  EXPECT_NE(errors.find("whose program file STI:0.PFN is 0"), std::string::npos) << errors;
  errors.clear();
  EXPECT_EQ(try_build(program_text("SOR STS 5 EOR"), errors), nullptr);
  EXPECT_NE(errors.find("the SLC STS takes a file and a time"), std::string::npos) << errors;
  errors.clear();
  EXPECT_EQ(try_build("START Bul.1766\nLADDER 2\nSOR STS 3 1 EOR\nLADDER 3\nSOR INT ADD N7:0 1 N7:0 EOR\n", errors),
            nullptr);
  EXPECT_NE(errors.find("STS is not available on the MicroLogix 1400"), std::string::npos) << errors;
  errors.clear();
  EXPECT_NE(try_build(program_text("SOR STD EOR\nSOR STE EOR\nSOR STS 3 1 EOR\nLADDER 3\nSOR INT ADD N7:0 1 N7:0 EOR"), errors),
            nullptr)
      << errors;
}

TEST(Sti, DisassemblerLabelsTheOperandsFromTheTable) {
  Plc plc("SOR STS 3 25 EOR\nSOR SUS -3 EOR\nSOR STD EOR\nSOR REF EOR\nLADDER 3\nSOR INT ADD N7:0 1 N7:0 EOR");
  const std::string listing = disassemble(plc->compiled());
  EXPECT_NE(listing.find("STS"), std::string::npos) << listing;
  EXPECT_NE(listing.find("file=3"), std::string::npos) << listing;
  EXPECT_NE(listing.find("time=25"), std::string::npos) << listing;
  EXPECT_NE(listing.find("suspend ID=-3"), std::string::npos) << listing;
  EXPECT_NE(listing.find("INT"), std::string::npos) << listing;
  EXPECT_NE(listing.find("REF"), std::string::npos) << listing;
}

// ---- The user fault routine ------------------------------------------------------------------------------------

// File 3 is the fault routine: it counts its runs in N7:9 and copies S:6 to N7:8; with B3:0/0 set
// it clears S:5/0 and S:1/13 (the RM 11-4 example's recovery).
constexpr std::string_view kFaultRoutine =
    "LADDER 3\n"
    "SOR ADD N7:9 1 N7:9 EOR\n"
    "SOR MOV S:6 N7:8 EOR\n"
    "SOR XIC B3:0/0 OTU S:5/0 OTU S:1/13 EOR\n";

TEST(FaultRoutine, ClearsA0020AtEndOfScanAndTheProcessorCarriesOn) {
  Plc plc("SOR DIV N7:0 0 N7:1 EOR\nSOR ADD N7:2 1 N7:2 EOR\n" + std::string(kFaultRoutine));
  plc.set("S:29", 3);
  plc.set("B3:0/0", 1);
  plc.run_scans(3);
  EXPECT_FALSE(plc->fault().has_value());
  EXPECT_EQ(plc->mode(), Mode::Run);
  EXPECT_EQ(plc.i("N7:9"), 3) << "once per faulting scan";
  EXPECT_EQ(plc.i("N7:8"), 0x0020) << "S:6 holds the code while the routine runs";
  EXPECT_EQ(plc.i("N7:2"), 3);
}

TEST(FaultRoutine, NotClearedTheFaultStands) {
  Plc plc("SOR DIV N7:0 0 N7:1 EOR\n" + std::string(kFaultRoutine));
  plc.set("S:29", 3);
  plc.run_scans(3);
  EXPECT_EQ(plc.fault_code(), 0x0020);
  EXPECT_EQ(plc.i("N7:9"), 1) << "the routine ran once, then the processor halted";
}

TEST(FaultRoutine, IndexedAddressFaultRecoveredAtTheNextRung) {
  Plc plc(
      "SOR MOV 300 S:24 EOR\n"
      "SOR MOV #N7:0 N7:1 OTE B3:1/0 EOR\n"
      "SOR OTE B3:1/1 EOR\n" +
      std::string(kFaultRoutine));
  plc.set("S:29", 3);
  plc.set("B3:0/0", 1);
  plc.run_scans(1);
  EXPECT_FALSE(plc->fault().has_value());
  EXPECT_EQ(plc.i("N7:8"), 0x002A);
  EXPECT_FALSE(plc.b("B3:1/0")) << "the rest of the faulting rung is abandoned (docs/semantics.md)";
  EXPECT_TRUE(plc.b("B3:1/1")) << "the scan goes on at the next rung";
  EXPECT_EQ(plc.i("S:24"), 300) << "S:24 as the interrupted program left it";

  plc.set("B3:0/0", 0);
  plc->scan(1);
  EXPECT_EQ(plc.fault_code(), 0x002A) << "not cleared: the fault stands";
  EXPECT_EQ(plc->fault()->rung, 1);
}

TEST(FaultRoutine, NonRecoverableWatchdogRunsTheRoutineOnceAndHalts) {
  Plc plc("SOR LBL 1 JMP 1 EOR\n" + std::string(kFaultRoutine));
  plc.set("S:29", 3);
  plc.set("B3:0/0", 1);
  plc.run_scans(1);
  EXPECT_EQ(plc.fault_code(), 0x0022);
  EXPECT_EQ(plc.i("N7:9"), 1);
  EXPECT_EQ(plc.i("N7:8"), 0x0022);
}

TEST(FaultRoutine, NoRoutineWhenS29IsZero) {
  Plc plc("SOR DIV N7:0 0 N7:1 EOR\n" + std::string(kFaultRoutine));
  plc.run_scans(1);
  EXPECT_EQ(plc.fault_code(), 0x0020);
  EXPECT_EQ(plc.i("N7:9"), 0);
}

}  // namespace
}  // namespace softslc::test
