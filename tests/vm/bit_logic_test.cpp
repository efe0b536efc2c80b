// Bit instructions and rung/branch logic.
//
// Sources: the .def rows (XIC/XIO/OTE/OTL/OTU/OSR meanings), facts §1 (branches nest, outputs
// may stand inside branch legs), RSLogix OSR help quoted in facts §5.
#include <gtest/gtest.h>

#include "vm_test_util.h"

namespace softslc::test {
namespace {

TEST(BitLogic, XicXioOteTruthTable) {
  // Rung: XIC B3:0/0 XIO B3:0/1 OTE B3:0/2  =>  /2 = /0 AND NOT /1.
  Plc plc("SOR XIC B3:0/0 XIO B3:0/1 OTE B3:0/2 EOR");
  plc.run();
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) {
      plc.set("B3:0/0", a);
      plc.set("B3:0/1", b);
      plc->scan(1);
      EXPECT_EQ(plc.b("B3:0/2"), a == 1 && b == 0) << "a=" << a << " b=" << b;
    }
}

TEST(BitLogic, OteFollowsTheRungEveryScan) {
  Plc plc("SOR XIC B3:0/0 OTE B3:0/5 EOR");
  plc.run();
  plc.set("B3:0/5", 1);  // set by hand; the OTE rewrites it each scan
  plc->scan(1);
  EXPECT_FALSE(plc.b("B3:0/5"));
}

TEST(BitLogic, LatchAndUnlatchHoldWhenTheRungIsFalse) {
  Plc plc(
      "SOR XIC B3:0/0 OTL B3:1/0 EOR\n"
      "SOR XIC B3:0/1 OTU B3:1/0 EOR");
  plc.run();
  plc.set("B3:0/0", 1);
  plc->scan(1);
  EXPECT_TRUE(plc.b("B3:1/0"));
  plc.set("B3:0/0", 0);
  plc->scan(3);
  EXPECT_TRUE(plc.b("B3:1/0")) << "OTL is retentive: a false rung does not clear it";
  plc.set("B3:0/1", 1);
  plc->scan(1);
  EXPECT_FALSE(plc.b("B3:1/0"));
  plc.set("B3:0/1", 0);
  plc->scan(2);
  EXPECT_FALSE(plc.b("B3:1/0"));
}

TEST(BitLogic, OsrGivesOnePulsePerRisingEdge) {
  // OSR: rung-out true for one scan on a false-to-true rung-in; the storage bit tracks rung-in.
  Plc plc(
      "SOR XIC B3:0/0 OSR B3:0/15 OTE B3:0/1 EOR\n"
      "SOR XIC B3:0/1 ADD N7:0 1 N7:0 EOR");
  plc.run();
  plc->scan(2);
  EXPECT_EQ(plc.i("N7:0"), 0);
  plc.set("B3:0/0", 1);
  plc->scan(1);
  EXPECT_TRUE(plc.b("B3:0/1"));
  EXPECT_TRUE(plc.b("B3:0/15"));
  plc->scan(5);
  EXPECT_FALSE(plc.b("B3:0/1"));
  EXPECT_EQ(plc.i("N7:0"), 1);
  plc.set("B3:0/0", 0);
  plc->scan(1);
  EXPECT_FALSE(plc.b("B3:0/15"));
  plc.set("B3:0/0", 1);
  plc->scan(3);
  EXPECT_EQ(plc.i("N7:0"), 2);
}

TEST(BitLogic, ParallelBranchIsAnOr) {
  Plc plc("SOR BST XIC B3:0/0 NXB XIC B3:0/1 NXB XIC B3:0/2 BND OTE B3:0/8 EOR");
  plc.run();
  for (int v = 0; v < 8; ++v) {
    plc.set("B3:0", v);
    plc->scan(1);
    EXPECT_EQ(plc.b("B3:0/8"), v != 0) << v;
  }
}

TEST(BitLogic, NestedBranches) {
  // (a AND (b OR (c AND d))) OR e
  Plc plc("SOR BST XIC B3:0/0 BST XIC B3:0/1 NXB XIC B3:0/2 XIC B3:0/3 BND NXB XIC B3:0/4 BND OTE B3:1/0 EOR");
  plc.run();
  for (int v = 0; v < 32; ++v) {
    plc.set("B3:0", v);
    plc->scan(1);
    const bool a = v & 1, b = v & 2, c = v & 4, d = v & 8, e = v & 16;
    EXPECT_EQ(plc.b("B3:1/0"), (a && (b || (c && d))) || e) << v;
  }
}

TEST(BitLogic, OutputsInsideBranchLegs) {
  // As in the 59-BSGS export: outputs in legs, each leg starting from the branch's rung-in.
  Plc plc("SOR XIC B3:0/0 BST OTE B3:1/0 NXB XIC B3:0/1 OTE B3:1/1 NXB XIO B3:0/1 OTE B3:1/2 BND EOR");
  plc.run();
  plc.set("B3:0", 0b01);
  plc->scan(1);
  EXPECT_TRUE(plc.b("B3:1/0"));
  EXPECT_FALSE(plc.b("B3:1/1"));
  EXPECT_TRUE(plc.b("B3:1/2"));
  plc.set("B3:0", 0b11);
  plc->scan(1);
  EXPECT_TRUE(plc.b("B3:1/0"));
  EXPECT_TRUE(plc.b("B3:1/1"));
  EXPECT_FALSE(plc.b("B3:1/2"));
  plc.set("B3:0", 0b10);
  plc->scan(1);
  EXPECT_FALSE(plc.b("B3:1/0"));
  EXPECT_FALSE(plc.b("B3:1/1")) << "every leg starts from the rung condition before BST";
  EXPECT_FALSE(plc.b("B3:1/2"));
}

TEST(BitLogic, SealInCircuitThroughRealIo) {
  // Start (I:1/0) seals in the motor (O:2/0) until stop (I:1/1) opens; the field sees O:2.
  Plc plc("SOR BST XIC I:1/0 NXB XIC O:2/0 BND XIO I:1/1 OTE O:2/0 EOR");
  plc.run();
  ASSERT_TRUE(plc->set("I:1/0", Value::bit(true)));
  EXPECT_FALSE(plc.b("I:1/0")) << "a field input reaches I: only at the next input scan";
  plc->scan(1);
  EXPECT_TRUE(plc.b("O:2/0"));
  EXPECT_EQ(plc->module(2)->field_output(0), 1) << "the output scan delivered O:2 to the card";
  plc->set("I:1/0", Value::bit(false));
  plc->scan(3);
  EXPECT_TRUE(plc.b("O:2/0")) << "sealed in";
  plc->set("I:1/1", Value::bit(true));
  plc->scan(1);
  EXPECT_FALSE(plc.b("O:2/0"));
  EXPECT_EQ(plc->module(2)->field_output(0), 0);
}

TEST(BitLogic, BitOffsetAndNamedBits) {
  // PT1 4-8: B3/62 is B3:3/14. T4:0/DN is bit 13 of the timer's control word (PT1 4-9).
  Plc plc(
      "SOR XIC B3:0/0 OTE B3/62 EOR\n"
      "SOR XIC T4:0/DN OTE B3:0/1 EOR");
  plc.run();
  plc.set("B3:0/0", 1);
  plc.set("T4:0", 1 << 13);
  plc->scan(1);
  EXPECT_TRUE(plc.b("B3:3/14"));
  EXPECT_EQ(plc.i("B3:3"), static_cast<std::int16_t>(0x4000));
  EXPECT_TRUE(plc.b("B3:0/1"));
}

}  // namespace
}  // namespace softslc::test
