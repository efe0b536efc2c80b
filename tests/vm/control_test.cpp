// JMP LBL JSR SBR RET END TND MCR, and subroutine nesting.
//
// Sources: the .def rows (JMP/LBL/JSR/SBR/RET/END/TND/MCR meanings), RM 6-4 (nesting 8 levels on
// 5/02 and later, 4 on fixed and 5/01; overflow is an error; JSR enters at the first
// instruction), facts §5 MCR (zones end with an unconditional MCR; in a false zone rungs are
// scanned with rung-in false: OTE off, OTL/OTU hold, timers and counters stop, a TOF starts
// timing), PT1 20-2 (S:5/0 checked at END or TND). Fault 0030h for nesting is [S] (facts §3).
#include <gtest/gtest.h>

#include "vm_test_util.h"

namespace softslc::test {
namespace {

TEST(Control, JmpSkipsRungsAndTheirOutputsHold) {
  Plc plc(
      "SOR XIC B3:0/0 JMP 5 EOR\n"
      "SOR XIC B3:0/1 OTE B3:1/0 EOR\n"
      "SOR ADD N7:0 1 N7:0 EOR\n"
      "SOR LBL 5 ADD N7:1 1 N7:1 EOR");
  plc.run();
  plc.set("B3:0/1", 1);
  plc->scan(1);
  EXPECT_TRUE(plc.b("B3:1/0"));
  plc.set("B3:0/0", 1);
  plc.set("B3:0/1", 0);
  plc->scan(3);
  EXPECT_TRUE(plc.b("B3:1/0")) << "skipped OTE keeps its last state";
  EXPECT_EQ(plc.i("N7:0"), 1);
  EXPECT_EQ(plc.i("N7:1"), 4) << "the LBL rung runs";
}

TEST(Control, BackwardJmpLoops) {
  Plc plc(
      "SOR LBL 1 ADD N7:0 1 N7:0 EOR\n"
      "SOR LES N7:0 10 JMP 1 EOR");
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:0"), 10);
  EXPECT_FALSE(plc->fault().has_value());
}

TEST(Control, JsrRunsTheSubroutineAndReturns) {
  Plc plc(
      "SOR JSR 3 EOR\n"
      "SOR MOV N7:0 N7:1 EOR\n"
      "LADDER 3\n"
      "SOR SBR ADD N7:0 5 N7:0 EOR\n"
      "SOR XIC B3:0/0 RET EOR\n"
      "SOR ADD N7:0 100 N7:0 EOR");
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:0"), 105);
  EXPECT_EQ(plc.i("N7:1"), 105) << "execution continues after the JSR";
  plc.set("B3:0/0", 1);
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:0"), 110) << "RET skipped the last rung";
}

TEST(Control, JsrInsideABranchLeg) {
  Plc plc(
      "SOR XIC B3:0/0 BST JSR 3 NXB OTE B3:0/1 BND EOR\n"
      "LADDER 3\n"
      "SOR BST XIC B3:0/2 NXB XIO B3:0/2 BND ADD N7:0 1 N7:0 EOR");
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:0"), 0);
  plc.set("B3:0/0", 1);
  plc->scan(2);
  EXPECT_EQ(plc.i("N7:0"), 2);
  EXPECT_TRUE(plc.b("B3:0/1")) << "the other leg still sees the rung";
}

std::string chain(int depth) {
  // File 2 calls 3, 3 calls 4, ... : `depth` nested subroutine levels.
  std::string s = "SOR JSR 3 EOR\n";
  for (int f = 3; f < 3 + depth; ++f) {
    s += "LADDER " + std::to_string(f) + "\n";
    if (f + 1 < 3 + depth) s += "SOR JSR " + std::to_string(f + 1) + " EOR\n";
    else s += "SOR ADD N7:0 1 N7:0 EOR\n";
  }
  return s;
}

TEST(Control, EightNestedLevelsAreAllowedOnA503) {
  Plc plc(chain(8));
  plc.run_scans(2);
  EXPECT_FALSE(plc->fault().has_value());
  EXPECT_EQ(plc.i("N7:0"), 2);
}

TEST(Control, NinthLevelIsMajorFault0030) {
  Plc plc(chain(9));
  plc.run_scans(1);
  ASSERT_TRUE(plc->fault().has_value());
  EXPECT_EQ(plc.fault_code(), 0x0030);
  EXPECT_EQ(plc->fault()->file, 10) << "the ninth JSR is in file 10";
  EXPECT_EQ(plc->fault()->rung, 0);
}

TEST(Control, A501AllowsFourLevels) {
  constexpr std::string_view k501 = "START 1747-L511\nSLOT 1 1746-IB16 SCAN_IN 1 SCAN_OUT 0\n";
  Plc ok(chain(4), {}, k501);
  ok.run_scans(1);
  EXPECT_FALSE(ok->fault().has_value());
  Plc deep(chain(5), {}, k501);
  deep.run_scans(1);
  EXPECT_EQ(deep.fault_code(), 0x0030);
}

TEST(Control, RecursionEndsInTheNestingFault) {
  Plc plc(
      "SOR JSR 3 EOR\n"
      "LADDER 3\n"
      "SOR ADD N7:0 1 N7:0 EOR\n"
      "SOR JSR 3 EOR");
  plc.run_scans(1);
  EXPECT_EQ(plc.fault_code(), 0x0030);
  EXPECT_EQ(plc->fault()->file, 3);
  EXPECT_EQ(plc->fault()->rung, 1);
  EXPECT_EQ(plc.i("N7:0"), 8) << "eight levels ran before the ninth call faulted";
}

TEST(Control, TndEndsTheScan) {
  Plc plc(
      "SOR ADD N7:0 1 N7:0 EOR\n"
      "SOR XIC B3:0/0 TND EOR\n"
      "SOR ADD N7:1 1 N7:1 EOR");
  plc.run_scans(2);
  EXPECT_EQ(plc.i("N7:1"), 2);
  plc.set("B3:0/0", 1);
  plc->scan(2);
  EXPECT_EQ(plc.i("N7:0"), 4);
  EXPECT_EQ(plc.i("N7:1"), 2);
}

TEST(Control, TndInASubroutineEndsTheWholeScan) {
  Plc plc(
      "SOR JSR 3 EOR\n"
      "SOR ADD N7:1 1 N7:1 EOR\n"
      "LADDER 3\n"
      "SOR TND EOR");
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:1"), 0);
}

TEST(Control, OverflowTrapIsCheckedAtTnd) {
  Plc plc("SOR ADD 32767 1 N7:0 EOR\nSOR TND EOR\nSOR OTU S:5/0 EOR");
  plc.run_scans(1);
  EXPECT_EQ(plc.fault_code(), 0x0020);
  EXPECT_EQ(plc->fault()->rung, 1) << "reported at the TND";
}

TEST(Control, ExplicitEndStopsTheFile) {
  Plc plc("SOR ADD N7:0 1 N7:0 EOR\nSOR END EOR");
  plc.run_scans(3);
  EXPECT_EQ(plc.i("N7:0"), 3);
}

TEST(Mcr, FalseZoneDeEnergisesOutputsAndHoldsLatches) {
  Plc plc(
      "SOR XIC B3:0/0 MCR EOR\n"
      "SOR XIC B3:0/1 OTE B3:1/0 EOR\n"
      "SOR XIC B3:0/1 OTL B3:1/1 EOR\n"
      "SOR XIC B3:0/1 TON T4:0 0.01 1000 0 EOR\n"
      "SOR XIC B3:0/1 CTU C5:0 100 0 EOR\n"
      "SOR XIC B3:0/1 TOF T4:1 0.01 50 0 EOR\n"
      "SOR MCR EOR\n"
      "SOR XIC B3:0/1 OTE B3:1/2 EOR");
  plc.run();
  plc.set("B3:0/0", 1);
  plc->scan(1);
  plc.set("B3:0/1", 1);
  plc->run_for(milliseconds(100));
  EXPECT_TRUE(plc.b("B3:1/0"));
  EXPECT_TRUE(plc.b("B3:1/1"));
  EXPECT_GT(plc.i("T4:0.ACC"), 0);
  EXPECT_EQ(plc.i("C5:0.ACC"), 1);
  EXPECT_TRUE(plc.b("T4:1/DN"));
  // The zone goes false: every rung in it sees rung-in false.
  plc.set("B3:0/0", 0);
  plc->scan(1);
  EXPECT_FALSE(plc.b("B3:1/0")) << "OTE de-energised";
  EXPECT_TRUE(plc.b("B3:1/1")) << "OTL holds";
  EXPECT_EQ(plc.i("T4:0.ACC"), 0) << "a TON in a false zone is reset";
  EXPECT_TRUE(plc.b("T4:1/TT")) << "a TOF starts timing";
  EXPECT_TRUE(plc.b("B3:1/2")) << "after the closing MCR rungs run normally";
  plc->run_for(milliseconds(600));
  EXPECT_FALSE(plc.b("T4:1/DN"));
  // Zone true again: the CTU sees a false-to-true transition and counts.
  plc.set("B3:0/0", 1);
  plc->scan(1);
  EXPECT_EQ(plc.i("C5:0.ACC"), 2);
  EXPECT_TRUE(plc.b("B3:1/0"));
}

}  // namespace
}  // namespace softslc::test
