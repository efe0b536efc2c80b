// ADD SUB MUL DIV NEG CLR, AND OR XOR NOT: results, S:0 flags, overflow, S:13/S:14.
//
// Sources: RM B-5 (S:0 C V Z S; V sets S:5/0), PT1 20-5 and ML B-10 (S:2/14 overflow select:
// 0 clamps to +32767/-32768, 1 keeps the truncated low 16 bits), RM 4-10 (MUL 32-bit product in
// S:13/S:14; DIV rounds, S:14 unrounded quotient, S:13 remainder, 11/2 -> 6, 5, 1; divide by zero
// sets V and puts 32767 in dest; C always reset), PT1 20-2 (S:5/0 still set at END is major fault
// 0020h), ML1400 RM p.204 (float: round to even, integer destinations saturate ignoring S:2/14).
#include <gtest/gtest.h>

#include "vm_test_util.h"

namespace softslc::test {
namespace {

constexpr int C = 1, V = 2, Z = 4, S = 8;

int flags(Plc& plc) { return static_cast<int>(plc.i("S:0") & 0xF); }

// Each program clears the overflow trap before END so overflow does not fault (PT1 20-2).
std::string with_trap_clear(std::string_view rung) {
  return std::string(rung) + "\nSOR OTU S:5/0 EOR";
}

TEST(Math, AddSubFlags) {
  Plc plc(with_trap_clear("SOR XIC B3:0/0 ADD N7:0 N7:1 N7:2 EOR\nSOR XIC B3:0/1 SUB N7:0 N7:1 N7:2 EOR"));
  plc.run();
  plc.set("B3:0/0", 1);
  plc.set("N7:0", 2);
  plc.set("N7:1", 3);
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:2"), 5);
  EXPECT_EQ(flags(plc), 0);
  plc.set("N7:1", -2);
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:2"), 0);
  EXPECT_EQ(flags(plc), Z | C) << "2 + 0xFFFE carries out of 16 bits, result zero";
  plc.set("B3:0/0", 0);
  plc.set("B3:0/1", 1);
  plc.set("N7:0", 2);
  plc.set("N7:1", 3);
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:2"), -1);
  EXPECT_EQ(flags(plc), S | C) << "2 - 3 borrows and is negative";
}

TEST(Math, AddOverflowClampsByDefault) {
  Plc plc(with_trap_clear("SOR ADD N7:0 1 N7:1 EOR\nSOR SUB N7:2 1 N7:3 EOR\nSOR XIC S:5/0 OTE B3:0/0 EOR"));
  // The trap-clear rung runs last; B3:0/0 samples S:5/0 just before it.
  plc.set("N7:0", 32767);
  plc.set("N7:2", -32768);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:1"), 32767);
  EXPECT_EQ(plc.i("N7:3"), -32768);
  EXPECT_TRUE(flags(plc) & V);
  EXPECT_TRUE(plc.b("B3:0/0")) << "V sets the overflow trap S:5/0 (RM B-5)";
  EXPECT_FALSE(plc->fault().has_value());
}

TEST(Math, OverflowSelectTruncates) {
  Plc plc(with_trap_clear("SOR OTL S:2/14 EOR\nSOR ADD N7:0 1 N7:1 EOR\nSOR MUL N7:2 N7:2 N7:3 EOR"));
  plc.set("N7:0", 32767);
  plc.set("N7:2", 300);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:1"), -32768) << "S:2/14 = 1: the low 16 bits of 32768";
  // 300 * 300 = 90000 = 0x15F90: low word 0x5F90 = 24464.
  EXPECT_EQ(plc.i("N7:3"), 24464);
  EXPECT_TRUE(flags(plc) & V);
}

TEST(Math, MulPutsThe32BitProductInS13S14) {
  Plc plc(with_trap_clear("SOR MUL N7:0 N7:1 N7:2 EOR"));
  plc.set("N7:0", 300);
  plc.set("N7:1", 300);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:2"), 32767) << "overflow clamps (S:2/14 = 0)";
  EXPECT_EQ(static_cast<std::uint16_t>(plc.i("S:13")), 0x5F90);
  EXPECT_EQ(plc.i("S:14"), 1);
  EXPECT_EQ(flags(plc), V);
  plc.set("N7:1", -3);
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:2"), -900);
  EXPECT_EQ(flags(plc), S);
  EXPECT_EQ(static_cast<std::uint16_t>(plc.i("S:14")), 0xFFFF);
}

TEST(Math, DivRoundsAndReportsQuotientAndRemainder) {
  // RM 4-10: 11 / 2 -> dest 6, S:14 = 5, S:13 = 1.
  Plc plc("SOR DIV N7:0 N7:1 N7:2 EOR");
  plc.set("N7:0", 11);
  plc.set("N7:1", 2);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:2"), 6);
  EXPECT_EQ(plc.i("S:14"), 5);
  EXPECT_EQ(plc.i("S:13"), 1);
  EXPECT_EQ(flags(plc), 0);
  plc.set("N7:0", 10);
  plc.set("N7:1", 4);
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:2"), 3) << "2.5 rounds up";
  plc.set("N7:0", 9);
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:2"), 2) << "2.25 rounds down";
  plc.set("N7:0", -11);
  plc.set("N7:1", 2);
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:2"), -6) << "halves round away from zero [U, docs/semantics.md]";
  EXPECT_EQ(plc.i("S:14"), -5);
  EXPECT_EQ(plc.i("S:13"), -1);
  EXPECT_EQ(flags(plc), S);
}

TEST(Math, DivideByZeroPuts32767AndTrapsAtEnd) {
  Plc plc("SOR DIV N7:0 0 N7:1 EOR");
  plc.set("N7:0", -7);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:1"), 32767);
  EXPECT_TRUE(flags(plc) & V);
  EXPECT_FALSE(flags(plc) & C);
  // The overflow trap is still set at END: major fault 0020h (PT1 20-2).
  ASSERT_TRUE(plc->fault().has_value());
  EXPECT_EQ(plc.fault_code(), 0x0020);
  EXPECT_EQ(plc->fault()->file, 2);
  EXPECT_EQ(plc->fault()->rung, 1) << "reported at the END rung of file 2";
}

TEST(Math, DivOverflowFollowsOverflowSelect) {
  Plc plc(with_trap_clear("SOR DIV -32768 N7:0 N7:1 EOR"));
  plc.set("N7:0", -1);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:1"), 32767);
  EXPECT_TRUE(flags(plc) & V);
}

TEST(Math, NegAndClr) {
  Plc plc(with_trap_clear("SOR NEG N7:0 N7:1 EOR\nSOR XIC B3:0/0 CLR N7:2 EOR"));
  plc.set("N7:0", 5);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:1"), -5);
  EXPECT_TRUE(flags(plc) & S);
  plc.set("N7:0", -32768);
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:1"), 32767) << "-(-32768) overflows and clamps";
  EXPECT_TRUE(flags(plc) & V);
  plc.set("N7:2", 99);
  plc.set("B3:0/0", 1);
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:2"), 0);
  EXPECT_EQ(flags(plc), Z);
}

TEST(Math, FalseRungLeavesDestinationAndFlags) {
  Plc plc("SOR XIC B3:0/0 ADD 1 2 N7:0 EOR");
  plc.set("N7:0", 42);
  plc.set("S:0", Z);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:0"), 42);
  EXPECT_EQ(flags(plc), Z);
}

TEST(Math, FloatMathAndRoundingIntoIntegers) {
  Plc plc(with_trap_clear(
      "SOR ADD F8:0 F8:1 F8:2 EOR\n"
      "SOR ADD F8:0 0.0 N7:0 EOR\n"
      "SOR MUL N7:1 0.5 N7:2 EOR\n"
      "SOR DIV N7:3 N7:4 F8:3 EOR"));
  plc.setf("F8:0", 2.5);
  plc.setf("F8:1", 0.25);
  plc.set("N7:1", 7);
  plc.set("N7:3", 1);
  plc.set("N7:4", 4);
  plc.run_scans(1);
  EXPECT_DOUBLE_EQ(plc.f("F8:2"), 2.75);
  EXPECT_EQ(plc.i("N7:0"), 2) << "2.5 rounds to even (ML1400 RM p.204)";
  EXPECT_EQ(plc.i("N7:2"), 4) << "3.5 rounds to even";
  EXPECT_DOUBLE_EQ(plc.f("F8:3"), 0.25) << "an F destination makes DIV a float division";
  EXPECT_EQ(plc->format("F8:3"), "0.25");
}

TEST(Math, FloatIntoIntegerSaturatesIgnoringOverflowSelect) {
  Plc plc(with_trap_clear("SOR OTL S:2/14 EOR\nSOR MUL F8:0 10.0 N7:0 EOR"));
  plc.setf("F8:0", 1e6);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:0"), 32767);
  EXPECT_TRUE(flags(plc) & V);
}

TEST(Math, FloatDivideByZeroSetsOverflow) {
  Plc plc(with_trap_clear("SOR DIV F8:0 0.0 F8:1 EOR"));
  plc.setf("F8:0", 1.0);
  plc.run_scans(1);
  EXPECT_TRUE(flags(plc) & V);
}

TEST(Math, LongIntegerMathOnMicroLogix) {
  constexpr std::string_view kMl1400 = "START Bul.1766\nSLOT 0 Bul.1766 SCAN_IN 8 SCAN_OUT 6\n";
  Plc plc(with_trap_clear("SOR ADD L9:0 1 L9:0 EOR\nSOR MOV L9:0 N7:0 EOR"), {}, kMl1400);
  plc.set("L9:0", 2147483646);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("L9:0"), 2147483647);
  EXPECT_EQ(plc.i("N7:0"), 32767) << "a long that does not fit a word saturates";
  EXPECT_TRUE(flags(plc) & V);
  plc->scan(1);
  EXPECT_EQ(plc.i("L9:0"), 2147483647) << "32-bit overflow clamps too";
}

TEST(Logic, BitwiseInstructions) {
  Plc plc(
      "SOR AND N7:0 0x00FF N7:1 EOR\n"
      "SOR OR N7:0 0x000F N7:2 EOR\n"
      "SOR XOR N7:0 -1 N7:3 EOR\n"
      "SOR NOT N7:0 N7:4 EOR");
  plc.set("N7:0", 0x1234);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:1"), 0x0034);
  EXPECT_EQ(plc.i("N7:2"), 0x123F);
  EXPECT_EQ(static_cast<std::uint16_t>(plc.i("N7:3")), 0xEDCB);
  EXPECT_EQ(static_cast<std::uint16_t>(plc.i("N7:4")), 0xEDCB);
  EXPECT_EQ(flags(plc), S) << "NOT of 0x1234 has the sign bit set";
  plc.set("N7:0", 0);
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:1"), 0);
  EXPECT_EQ(static_cast<std::uint16_t>(plc.i("N7:4")), 0xFFFF);
}

TEST(Logic, HexMasksAreSixteenBitPatterns) {
  Plc plc("SOR AND N7:0 0xFF00 N7:1 EOR");
  plc.set("N7:0", -1);
  plc.run_scans(1);
  EXPECT_EQ(static_cast<std::uint16_t>(plc.i("N7:1")), 0xFF00);
  EXPECT_FALSE(plc->fault().has_value());
}

}  // namespace
}  // namespace softslc::test
