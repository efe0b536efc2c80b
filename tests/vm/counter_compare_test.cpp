// CTU, CTD, RES on counters; EQU NEQ LES LEQ GRT GEQ LIM MEQ.
//
// Sources: RM 2-14 (count on false-to-true only, OV/UN wrap, DN = ACC >= PRE, CU set before Run
// so there is no phantom count), PT1 17-2 (counter PRE/ACC -32768..32767), facts §1 (LIM low
// test high), the .def rows (comparison meanings; LIM with low > high tests outside the band).
#include <gtest/gtest.h>

#include "vm_test_util.h"

namespace softslc::test {
namespace {

constexpr std::uint16_t CU = 1u << 15, CD = 1u << 14, DN = 1u << 13, OV = 1u << 12, UN = 1u << 11;

std::uint16_t cbits(Plc& plc, std::string_view c) { return static_cast<std::uint16_t>(plc.i(c)) & 0xF800; }

TEST(Counters, CtuCountsRisingEdgesOnly) {
  Plc plc("SOR XIC B3:0/0 CTU C5:0 3 0 EOR");
  plc.run();
  plc->scan(1);
  for (int pulse = 1; pulse <= 4; ++pulse) {
    plc.set("B3:0/0", 1);
    plc->scan(3);  // held true for several scans: one count
    EXPECT_EQ(plc.i("C5:0.ACC"), pulse);
    EXPECT_TRUE(cbits(plc, "C5:0") & CU);
    plc.set("B3:0/0", 0);
    plc->scan(2);
    EXPECT_FALSE(cbits(plc, "C5:0") & CU);
    EXPECT_EQ(plc.b("C5:0/DN"), pulse >= 3) << "DN = ACC >= PRE";
  }
}

TEST(Counters, NoPhantomCountOnTheFirstScan) {
  // RM 2-14: CU is set before entering Run, so a rung that is already true does not count.
  Plc plc("SOR XIC B3:0/0 CTU C5:0 10 0 EOR");
  plc.set("B3:0/0", 1);
  plc.run();
  plc->scan(2);
  EXPECT_EQ(plc.i("C5:0.ACC"), 0);
  plc.set("B3:0/0", 0);
  plc->scan(1);
  plc.set("B3:0/0", 1);
  plc->scan(1);
  EXPECT_EQ(plc.i("C5:0.ACC"), 1);
}

TEST(Counters, CtuWrapsToMinus32768AndSetsOv) {
  Plc plc(
      "SOR XIC B3:0/0 CTU C5:0 100 0 EOR\n"
      "DATA C5:0\n"
      "0 100 32767 % C5:0 %\n");
  plc.run();
  plc->scan(1);
  plc.set("B3:0/0", 1);
  plc->scan(1);
  EXPECT_EQ(plc.i("C5:0.ACC"), -32768);
  EXPECT_TRUE(cbits(plc, "C5:0") & OV);
  EXPECT_FALSE(cbits(plc, "C5:0") & DN) << "DN = ACC >= PRE, and -32768 < 100";
  plc.set("B3:0/0", 0);
  plc->scan(1);
  plc.set("B3:0/0", 1);
  plc->scan(1);
  EXPECT_EQ(plc.i("C5:0.ACC"), -32767) << "counting continues after the wrap";
  EXPECT_TRUE(cbits(plc, "C5:0") & OV);
}

TEST(Counters, CtdWrapsToPlus32767AndSetsUn) {
  Plc plc(
      "SOR XIC B3:0/0 CTD C5:1 0 0 EOR\n"
      "DATA C5:1\n"
      "0 0 -32768 % C5:1 %\n");
  plc.run();
  plc->scan(1);
  plc.set("B3:0/0", 1);
  plc->scan(1);
  EXPECT_EQ(plc.i("C5:1.ACC"), 32767);
  EXPECT_TRUE(cbits(plc, "C5:1") & UN);
  EXPECT_TRUE(cbits(plc, "C5:1") & CD);
}

TEST(Counters, CtdBringingTheCountBackClearsOv) {
  // RM 2-14: OV clears when a CTD brings the count back to <= +32767.
  Plc plc(
      "SOR XIC B3:0/0 CTU C5:0 5 0 EOR\n"
      "SOR XIC B3:0/1 CTD C5:0 5 0 EOR\n"
      "DATA C5:0\n"
      "0 5 32767 % C5:0 %\n");
  plc.run();
  plc->scan(1);
  plc.set("B3:0/0", 1);
  plc->scan(1);
  ASSERT_TRUE(cbits(plc, "C5:0") & OV);
  plc.set("B3:0/1", 1);
  plc->scan(1);
  EXPECT_EQ(plc.i("C5:0.ACC"), 32767);
  EXPECT_FALSE(cbits(plc, "C5:0") & OV);
  EXPECT_FALSE(cbits(plc, "C5:0") & UN);
}

TEST(Counters, UpDownOnOneCounter) {
  Plc plc(
      "SOR XIC B3:0/0 CTU C5:0 2 0 EOR\n"
      "SOR XIC B3:0/1 CTD C5:0 2 0 EOR");
  plc.run();
  plc->scan(1);
  auto pulse = [&](const char* bit) {
    plc.set(bit, 1);
    plc->scan(1);
    plc.set(bit, 0);
    plc->scan(1);
  };
  pulse("B3:0/0");
  pulse("B3:0/0");
  EXPECT_TRUE(plc.b("C5:0/DN"));
  pulse("B3:0/1");
  EXPECT_EQ(plc.i("C5:0.ACC"), 1);
  EXPECT_FALSE(plc.b("C5:0/DN"));
  pulse("B3:0/1");
  pulse("B3:0/1");
  EXPECT_EQ(plc.i("C5:0.ACC"), -1) << "counters go negative (PT1 17-2: -32768..32767)";
}

TEST(Counters, ResClearsAccumulatorAndStatus) {
  Plc plc(
      "SOR XIC B3:0/0 CTU C5:0 1 0 EOR\n"
      "SOR XIC B3:0/1 RES C5:0 EOR\n"
      "DATA C5:0\n"
      "0 1 32767 % C5:0 %\n");
  plc.run();
  plc->scan(1);
  plc.set("B3:0/0", 1);
  plc->scan(1);
  ASSERT_TRUE(cbits(plc, "C5:0") & OV);
  plc.set("B3:0/0", 0);
  plc.set("B3:0/1", 1);
  plc->scan(1);
  EXPECT_EQ(plc.i("C5:0.ACC"), 0);
  EXPECT_EQ(cbits(plc, "C5:0"), 0);
  EXPECT_EQ(plc.i("C5:0.PRE"), 1) << "RES leaves the preset";
}

TEST(Counters, CounterLiteralsInitialisePresetAndAccum) {
  Plc plc("SOR CTU C5:3 -20 -25 EOR");
  EXPECT_EQ(plc.i("C5:3.PRE"), -20);
  EXPECT_EQ(plc.i("C5:3.ACC"), -25);
}

// ---- Comparisons -----------------------------------------------------------------------------------

struct CompareCase {
  const char* instr;
  int a;
  int b;
  bool expected;
};

TEST(Compare, IntegerComparisons) {
  const CompareCase cases[] = {
      {"EQU", 5, 5, true},    {"EQU", 5, 6, false},   {"NEQ", 5, 6, true},   {"NEQ", -1, -1, false},
      {"LES", -3, 2, true},   {"LES", 2, 2, false},   {"LEQ", 2, 2, true},   {"LEQ", 3, 2, false},
      {"GRT", 3, -2, true},   {"GRT", 2, 2, false},   {"GEQ", 2, 2, true},   {"GEQ", -32768, 32767, false},
  };
  for (const auto& c : cases) {
    Plc plc(std::string("SOR ") + c.instr + " N7:0 N7:1 OTE B3:0/0 EOR");
    plc.set("N7:0", c.a);
    plc.set("N7:1", c.b);
    plc.run_scans(1);
    EXPECT_EQ(plc.b("B3:0/0"), c.expected) << c.instr << " " << c.a << " " << c.b;
  }
}

TEST(Compare, ComparisonWithConstantsAndFloats) {
  Plc plc(
      "SOR GRT F8:0 2.5 OTE B3:0/0 EOR\n"
      "SOR EQU N7:0 F8:1 OTE B3:0/1 EOR\n"
      "SOR LES N7:0 100 OTE B3:0/2 EOR");
  plc.setf("F8:0", 2.75);
  plc.set("N7:0", 3);
  plc.setf("F8:1", 3.0);
  plc.run_scans(1);
  EXPECT_TRUE(plc.b("B3:0/0"));
  EXPECT_TRUE(plc.b("B3:0/1")) << "an integer and a float compare by value";
  EXPECT_TRUE(plc.b("B3:0/2"));
  plc.setf("F8:1", 3.25);
  plc->scan(1);
  EXPECT_FALSE(plc.b("B3:0/1")) << "no rounding of the float operand in a comparison";
}

TEST(Compare, LimInsideAndOutsideTheBand) {
  // LIM low test high. low <= high: true when low <= test <= high. low > high: true when test
  // >= low or test <= high (the band between them is excluded).
  Plc plc("SOR LIM N7:0 N7:1 N7:2 OTE B3:0/0 EOR");
  plc.run();
  struct Case { int lo, test, hi; bool expected; };
  const Case cases[] = {
      {0, 0, 10, true},  {0, 10, 10, true}, {0, 11, 10, false}, {0, -1, 10, false},
      {10, 11, 0, true}, {10, 10, 0, true}, {10, 0, 0, true},   {10, 5, 0, false}, {10, -5, 0, true},
  };
  for (const auto& c : cases) {
    plc.set("N7:0", c.lo);
    plc.set("N7:1", c.test);
    plc.set("N7:2", c.hi);
    plc->scan(1);
    EXPECT_EQ(plc.b("B3:0/0"), c.expected) << c.lo << " " << c.test << " " << c.hi;
  }
}

TEST(Compare, MeqComparesUnderTheMask) {
  Plc plc("SOR MEQ N7:0 0x00FF N7:1 OTE B3:0/0 EOR");
  plc.run();
  plc.set("N7:0", 0x1234);
  plc.set("N7:1", 0x5634);
  plc->scan(1);
  EXPECT_TRUE(plc.b("B3:0/0"));
  plc.set("N7:1", 0x5635);
  plc->scan(1);
  EXPECT_FALSE(plc.b("B3:0/0"));
}

TEST(Compare, FalseRungStaysFalse) {
  Plc plc("SOR XIC B3:0/1 EQU N7:0 N7:0 OTE B3:0/0 EOR");
  plc.run_scans(1);
  EXPECT_FALSE(plc.b("B3:0/0"));
}

}  // namespace
}  // namespace softslc::test
