// Issue 15, group 1 and 2: DDV, SQR, SCL, SCP, ABS, the float functions (LN LOG XPY SIN COS TAN
// ASN ACS ATN DEG RAD), TOD, FRD, DCD, ENC; the integer-only operand rule and processor availability.
//
// Expected values come from the manuals' own examples where they give one, otherwise from an
// independent hand calculation written next to the assertion:
//   RM = 1747-RM001G (SLC 500 Instruction Set Reference, Nov 2008); PT1 = 1747-NP002 (1747-PT1
//   Hand-Held Terminal user manual); ML1400 = 1766-RM001A.
#include <gtest/gtest.h>

#include <cmath>

#include "vm_test_util.h"

namespace softslc::test {
namespace {

constexpr int C = 1, V = 2, Z = 4, S = 8;

// ---- DDV (RM 4-11, table 4.9) ------------------------------------------------------------------------------

TEST(AdvancedMath, DdvDividesTheMathRegisterAndRounds) {
  // MUL leaves the 32-bit product in S:14:S:13 (RM 4-10); 301 * 3 = 903; 903 / 2 = 451.5, and "if
  // the remainder is 0.5 or greater, the destination is rounded up" (RM 4-11): 452. The unrounded
  // quotient 451 goes to S:14, the remainder 1 to S:13.
  Plc plc(with_trap_sample("SOR MUL 301 3 N7:0 EOR\nSOR DDV 2 N7:1 EOR"));
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:1"), 452);
  EXPECT_EQ(plc.i("S:14"), 451);
  EXPECT_EQ(plc.i("S:13"), 1);
  EXPECT_EQ(arith_flags(plc), 0) << "C always resets (table 4.9)";
}

TEST(AdvancedMath, DdvOfA32BitProduct) {
  // 300 * 300 = 90000 does not fit N7:0 but is whole in the math register; 90000 / 7 = 12857.14.
  Plc plc(with_trap_sample("SOR MUL 300 300 N7:0 EOR\nSOR DDV 7 N7:1 EOR"));
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:1"), 12857);
  EXPECT_EQ(plc.i("S:14"), 12857);
  EXPECT_EQ(plc.i("S:13"), 1) << "90000 - 7 * 12857 = 1";
}

TEST(AdvancedMath, DdvOverflowAndDivideByZeroPut32767) {
  // Table 4.9: V "sets if division by zero or if result is greater than 32,767 ...; on overflow the
  // minor error flag is also set. The value 32,767 is placed in the destination."
  Plc plc(with_trap_sample("SOR MUL 300 300 N7:0 EOR\nSOR DDV 2 N7:1 EOR\nSOR MUL 1 1 N7:2 EOR\nSOR DDV 0 N7:3 EOR"));
  plc.set("S:2", 0x4000);  // S:2/14 set: DDV still puts 32767 (S:2/14 has no effect on DDV, PT1 20-5)
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:1"), 32767) << "90000 / 2 = 45000 overflows";
  EXPECT_EQ(plc.i("N7:3"), 32767) << "divide by zero";
  EXPECT_TRUE(arith_flags(plc) & V);
  EXPECT_TRUE(plc.b("B3:1/0")) << "the minor error bit S:5/0";
  EXPECT_FALSE(plc->fault().has_value());
}

// ---- SQR (RM 4-12), ABS ------------------------------------------------------------------------------------

TEST(AdvancedMath, SqrOfTheAbsoluteValueRounded) {
  Plc plc(with_trap_sample("SOR SQR -25 N7:0 EOR\nSOR SQR 2 N7:1 EOR\nSOR SQR 3 N7:2 EOR\nSOR SQR F8:0 F8:1 EOR"));
  plc.setf("F8:0", 2.0);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:0"), 5) << "the root of |-25| (RM 4-12: absolute value of the source)";
  EXPECT_EQ(plc.i("N7:1"), 1) << "1.414 rounds to 1";
  EXPECT_EQ(plc.i("N7:2"), 2) << "1.732 rounds to 2";
  EXPECT_NEAR(plc.f("F8:1"), 1.41421356, 1e-6);
  EXPECT_FALSE(plc.b("B3:1/0"));
}

TEST(AdvancedMath, AbsIntegerAndFloat) {
  Plc plc(with_trap_sample("SOR ABS N7:0 N7:1 EOR\nSOR ABS F8:0 F8:1 EOR"));
  plc.set("N7:0", -5);
  plc.setf("F8:0", -2.5);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:1"), 5);
  EXPECT_DOUBLE_EQ(plc.f("F8:1"), 2.5);
  EXPECT_EQ(arith_flags(plc), 0);
}

TEST(AdvancedMath, AbsOfMinus32768Overflows) {
  // |-32768| = 32768 does not fit 16 bits: V and S:5/0, and the default S:2/14 = 0 clamps to 32767.
  Plc plc(with_trap_sample("SOR ABS N7:0 N7:1 EOR"));
  plc.set("N7:0", -32768);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:1"), 32767);
  EXPECT_TRUE(arith_flags(plc) & V);
  EXPECT_TRUE(plc.b("B3:1/0"));
}

// ---- SCL (PT1 20-22, 20-23) and SCP (RM 4-13) ------------------------------------------------------------

TEST(AdvancedMath, SclManualExamples) {
  // PT1 20-22: 100 * 25000 / 10000 + 127 = 377. PT1 20-23: 25 degrees C * 18000 / 10000 + 32 = 77 F.
  Plc plc(with_trap_sample("SOR SCL N7:0 25000 127 N7:1 EOR\nSOR SCL N7:2 18000 32 N7:3 EOR"));
  plc.set("N7:0", 100);
  plc.set("N7:2", 25);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:1"), 377);
  EXPECT_EQ(plc.i("N7:3"), 77);
  EXPECT_EQ(arith_flags(plc) & (V | Z | S), 0);
}

TEST(AdvancedMath, SclOverflowBeforeTheOffset) {
  // PT1 20-22: "V: presence of an overflow at the destination is checked before and after the
  // offset value is applied ... the value -32,768 or 32,767 is placed in the destination";
  // 1761-6.3 (MicroLogix 1000, same instruction): 32767 "regardless of the current offset".
  // 30000 * 20000 / 10000 = 60000 overflows before the offset -30000 could bring it back.
  Plc plc(with_trap_sample("SOR SCL 30000 20000 -30000 N7:0 EOR\nSOR SCL 30000 10000 5000 N7:1 EOR"));
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:0"), 32767);
  EXPECT_EQ(plc.i("N7:1"), 32767) << "30000 + 5000 overflows after the offset";
  EXPECT_TRUE(plc.b("B3:1/0"));
}

TEST(AdvancedMath, ScpRm413ExampleAndExtrapolation) {
  // RM 4-13's box: input N7:30 = 100, input 0..32767, scaled 0..10000.
  // m = 10000 / 32767 = 0.305185; y = 100 m = 30.52, rounded to 31 in an integer output.
  // A Fahrenheit-to-Celsius scaling 32..212 -> 0..100 extrapolates (RM 4-13 tip: the output is not
  // clamped): -40 F -> (-40 - 32) * 100 / 180 = -40 C.
  Plc plc(with_trap_sample("SOR SCP N7:30 0 32767 0 10000 N7:31 EOR\nSOR SCP N7:32 32 212 0 100 N7:33 EOR\n"
                           "SOR SCP N7:34 0 100 4.0 20.0 F8:0 EOR"));
  plc.set("N7:30", 100);
  plc.set("N7:32", -40);
  plc.set("N7:34", 50);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:31"), 31);
  EXPECT_EQ(plc.i("N7:33"), -40);
  EXPECT_NEAR(plc.f("F8:0"), 12.0, 1e-5) << "50 % of 4..20";
  EXPECT_FALSE(plc.b("B3:1/0"));
}

TEST(AdvancedMath, ScpWithAnEmptyInputRangeOverflows) {
  Plc plc(with_trap_sample("SOR SCP 5 10 10 0 100 N7:0 EOR"));
  plc.run_scans(1);
  EXPECT_TRUE(arith_flags(plc) & V);
  EXPECT_TRUE(plc.b("B3:1/0"));
}

// ---- Float functions (RM chapter 4, 5/03 OS302+) ----------------------------------------------------------

TEST(AdvancedMath, TrigLogAndPowerValues) {
  // Independent values: sin(pi/2) = 1, cos(0) = 1, tan(pi/4) = 1, asin(1) = pi/2, acos(0) = pi/2,
  // atan(1) = pi/4, ln(e) = 1, log10(1000) = 3, 2**10 = 1024, pi rad = 180 deg, 90 deg = pi/2 rad.
  Plc plc(with_trap_sample(
      "SOR SIN 1.5707963 F8:0 EOR\nSOR COS 0 F8:1 EOR\nSOR TAN 0.7853982 F8:2 EOR\nSOR ASN 1 F8:3 EOR\n"
      "SOR ACS 0 F8:4 EOR\nSOR ATN 1 F8:5 EOR\nSOR LN 2.7182818 F8:6 EOR\nSOR LOG 1000 F8:7 EOR\n"
      "SOR XPY 2 10 F8:8 EOR\nSOR DEG 3.1415927 F8:9 EOR\nSOR RAD 90 F8:10 EOR\nSOR SIN 1.5707963 N7:0 EOR"));
  plc.run_scans(1);
  const double pi = 3.14159265358979;
  EXPECT_NEAR(plc.f("F8:0"), 1.0, 1e-6);
  EXPECT_NEAR(plc.f("F8:1"), 1.0, 1e-6);
  EXPECT_NEAR(plc.f("F8:2"), 1.0, 1e-6);
  EXPECT_NEAR(plc.f("F8:3"), pi / 2, 1e-6);
  EXPECT_NEAR(plc.f("F8:4"), pi / 2, 1e-6);
  EXPECT_NEAR(plc.f("F8:5"), pi / 4, 1e-6);
  EXPECT_NEAR(plc.f("F8:6"), 1.0, 1e-6);
  EXPECT_NEAR(plc.f("F8:7"), 3.0, 1e-6);
  EXPECT_NEAR(plc.f("F8:8"), 1024.0, 1e-3);
  EXPECT_NEAR(plc.f("F8:9"), 180.0, 1e-4);
  EXPECT_NEAR(plc.f("F8:10"), pi / 2, 1e-6);
  EXPECT_EQ(plc.i("N7:0"), 1) << "an integer destination gets the rounded result";
  EXPECT_FALSE(plc.b("B3:1/0"));
}

TEST(AdvancedMath, UnsupportedInputsSetOverflow) {
  // RM (ASN/ACS status tables): V "sets if an overflow is generated or an unsupported input is
  // detected"; C always resets. Each rung is checked on its own.
  for (std::string_view rung : {"SOR ASN 2 F8:0 EOR", "SOR ACS -1.5 F8:0 EOR", "SOR LN 0 F8:0 EOR",
                                "SOR LOG -10 F8:0 EOR", "SOR XPY 10 100 F8:0 EOR"}) {
    Plc plc(with_trap_sample(rung));
    plc.run_scans(1);
    EXPECT_EQ(arith_flags(plc) & (C | V), V) << rung;
    EXPECT_TRUE(plc.b("B3:1/0")) << rung;
  }
}

// ---- TOD, FRD (RM 5-2 .. 5-5), DCD, ENC (RM 5-10 .. 5-12) -------------------------------------------------

TEST(DataHandling, TodManualExamples) {
  // RM 5-3 example 1: 9760 -> BCD 9760 (1001 0111 0110 0000) in N10:0.
  // RM 5-3 example 2: 32760 into the math register: the five BCD digits fill S:13 (2760) and S:14
  // (3); V and S:5/0 because the result is above 9999.
  Plc plc(with_trap_sample("SOR TOD N7:3 N10:0 EOR\nSOR XIC B3:0/0 TOD N7:4 S:13 EOR"));
  plc.set("N7:3", 9760);
  plc.set("N7:4", 32760);
  plc.run_scans(1);
  EXPECT_EQ(static_cast<std::uint16_t>(plc.i("N10:0")), 0x9760);
  EXPECT_EQ(arith_flags(plc), 0) << "0x9760 has bit 15 set, but S follows the source's sign (table 5.2)";
  plc.set("B3:0/0", 1);
  plc->scan(1);
  EXPECT_EQ(static_cast<std::uint16_t>(plc.i("S:13")), 0x2760);
  EXPECT_EQ(plc.i("S:14"), 3);
  EXPECT_TRUE(arith_flags(plc) & V);
  EXPECT_TRUE(plc.b("B3:1/0"));
}

TEST(DataHandling, TodOfANegativeNumberUsesItsAbsoluteValue) {
  // RM 5-2: "If the integer value you enter is negative, the absolute value of the number is used";
  // table 5.2: S "sets if the source word is negative".
  Plc plc(with_trap_sample("SOR TOD N7:0 N7:1 EOR"));
  plc.set("N7:0", -824);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:1"), 0x0824);
  EXPECT_EQ(arith_flags(plc), S);
}

TEST(DataHandling, FrdConvertsBcdBack) {
  Plc plc(with_trap_sample(
      "SOR FRD N7:0 N7:1 EOR\nSOR TOD 32760 S:13 EOR\nSOR FRD S:13 N7:2 EOR\nSOR FRD N7:3 N7:4 EOR"));
  plc.set("N7:0", static_cast<std::int16_t>(0x9760));  // the BCD word 9760h
  plc.set("N7:3", 0x0000);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:1"), 9760);
  EXPECT_EQ(plc.i("N7:2"), 32760) << "the math register holds five BCD digits (RM 5-4)";
  EXPECT_EQ(plc.i("N7:4"), 0);
  EXPECT_EQ(arith_flags(plc), Z);
}

TEST(DataHandling, DcdSetsOneBit) {
  Plc plc("SOR DCD N7:0 N7:1 EOR");
  plc.set("N7:0", 0x0125);  // only the low four bits count: 5
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:1"), 0x0020);
}

TEST(DataHandling, EncFindsTheLowestSetBit) {
  // RM 5-12: "If more than one bit in the source is set, the destination bits are set based on the
  // least significant bit that is set"; table 5.6: V sets, "the math overflow bit (S:5/0) is not
  // set"; a zero source resets the destination and sets Z.
  Plc plc(with_trap_sample("SOR ENC N7:0 N7:1 EOR"));
  plc.set("N7:0", 0x0010);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:1"), 4);
  EXPECT_EQ(arith_flags(plc), 0);
  plc.set("N7:0", 0x0018);
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:1"), 3);
  EXPECT_EQ(arith_flags(plc), V);
  EXPECT_FALSE(plc.b("B3:1/0")) << "ENC's V does not set S:5/0";
  plc.set("N7:0", 0);
  plc.set("N7:1", 0x7FFF);
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:1"), 0);
  EXPECT_EQ(arith_flags(plc), Z);
}

// ---- SWP (RM 4-28) -------------------------------------------------------------------------------------------

TEST(DataHandling, AStringElementsWordsAreAddressable) {
  // ST9:0.0 is the length, .1-.41 two characters each, the first in the high byte. Before, any
  // word of an ST element silently named word 0 (the length): MOV ST9:0.1 read 3, not "ab".
  Plc plc("SOR MOV ST9:0.1 N7:0 MOV ST9:0.2 N7:1 MOV ST9:0.0 N7:2 EOR\nDATA ST9:0\n% ST9:0 % \"abc\"\n");
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:0"), 0x6162);
  EXPECT_EQ(plc.i("N7:1"), 0x6300);
  EXPECT_EQ(plc.i("N7:2"), 3);
  std::string errors;
  EXPECT_EQ(try_build(program_text("SOR MOV ST9:0.42 N7:0 EOR\nDATA ST9:0\n% ST9:0 % \"abc\"\n"), errors), nullptr);
  EXPECT_NE(errors.find("ST elements have words 0-41"), std::string::npos) << errors;
}

TEST(DataHandling, SwpReproducesTheManualsStringExample) {
  // RM 4-28: "Before: ST10:1 = abcdefghijklmnopqrstuvwxyz", SWP Source #ST10:1.1 Length 13,
  // "After ST10:1 = badcfehgjilknmporqtsvuxwzy". Two characters per word, the first in the high
  // byte: swapping every byte pair of the 26 characters is swapping the bytes of all 13 words.
  Plc plc("SOR SWP #ST10:1.1 13 EOR\nDATA ST10:0\n% ST10:0 % \"\"\n% ST10:1 % \"abcdefghijklmnopqrstuvwxyz\"\n");
  plc.run_scans(1);
  const std::string after = "badcfehgjilknmporqtsvuxwzy";
  EXPECT_EQ(plc.i("ST10:1.0"), 26) << "the length word is not swapped";
  for (std::size_t w = 0; w < 13; ++w) {
    const int expected = (static_cast<unsigned char>(after[2 * w]) << 8) | static_cast<unsigned char>(after[2 * w + 1]);
    EXPECT_EQ(static_cast<std::uint16_t>(plc.i("ST10:1." + std::to_string(w + 1))), expected) << "word " << w + 1;
  }
}

TEST(DataHandling, SwpSwapsLengthWordsOfAnIntegerFile) {
  // RM 4-28: "Length refers to the number of words to be swapped"; the words after them are left.
  Plc plc("SOR SWP #N7:1 2 EOR\nDATA N7:0\n% N7:0 % 0 0 0 0\n");
  plc.set("N7:0", 0x1234);
  plc.set("N7:1", 0x1234);
  plc.set("N7:2", static_cast<std::int16_t>(0xABCD));
  plc.set("N7:3", 0x0102);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:0"), 0x1234);
  EXPECT_EQ(plc.i("N7:1"), 0x3412);
  EXPECT_EQ(static_cast<std::uint16_t>(plc.i("N7:2")), 0xCDAB);
  EXPECT_EQ(plc.i("N7:3"), 0x0102);
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:1"), 0x1234) << "a rung left true swaps back every scan";
}

TEST(DataHandling, SwpIndexedPastTheStringElementFaults) {
  // An indirect start word is known only at run time: .40 + 5 words leaves the 41 data words of
  // the element ("cannot cross a string element boundary"), which faults as a COP past its file.
  Plc plc("SOR SWP #ST10:1.[N7:0] 5 EOR\nDATA ST10:0\n% ST10:0 % \"\"\n% ST10:1 % \"x\"\n");
  plc.set("N7:0", 37);
  plc.run_scans(1);
  ASSERT_FALSE(plc->fault().has_value()) << "words 37-41 stay inside the element: " << plc->fault()->message;
  plc.set("N7:0", 40);
  plc->scan(1);
  ASSERT_TRUE(plc->fault().has_value());
  EXPECT_NE(plc->fault()->message.find("leaves the data words of its string element"), std::string::npos)
      << plc->fault()->message;
}

// ---- RHC, TDF (RM 7-15 .. 7-17) -------------------------------------------------------------------------------

TEST(FreeRunningClock, RhcCountsTenMicrosecondTicksOfVirtualTime) {
  // RM 7-15: "a 20-bit integer free running clock. This 20-bit value increments every 10 us";
  // softslc's runs on virtual time since start-up, so a stamp lies between the scan's start and end.
  Plc plc("SOR RHC F8:0 RHC N7:0 EOR");
  plc.run();
  for (int k = 0; k < 5; ++k) {
    const VirtualTime before = plc->now();
    plc->scan(1);
    const VirtualTime after = plc->now();
    const auto ticks = static_cast<std::int64_t>(plc.f("F8:0"));
    EXPECT_GE(ticks, before / 10'000) << "scan " << k;
    EXPECT_LE(ticks, after / 10'000) << "scan " << k;
    // "If the destination is an integer address, the RHC moves the first 16 least significant bits".
    const auto low16 = static_cast<std::uint16_t>(plc.i("N7:0"));
    EXPECT_LE(static_cast<std::uint16_t>(low16 - static_cast<std::uint16_t>(ticks)), 1) << "the next instruction, within one tick";
  }
}

TEST(FreeRunningClock, TdfOfConsecutiveStampsIsTheScanPeriod) {
  // The manual's use: stamp an event twice with RHC, TDF the two. Here the event is rung 0 of two
  // consecutive scans, so the difference is the scan period, measured independently by now().
  Plc plc("SOR RHC N7:73 TDF N7:72 N7:73 N7:74 MOV N7:73 N7:72 EOR\nSOR RHC F8:1 TDF F8:0 F8:1 F8:2 MOV F8:1 F8:0 EOR");
  plc.run();
  plc->scan(1);
  VirtualTime last = plc->now();
  for (int k = 0; k < 5; ++k) {
    plc->scan(1);
    const VirtualTime period = plc->now() - last;
    last = plc->now();
    EXPECT_NEAR(static_cast<double>(plc.i("N7:74")), static_cast<double>(period) / 10'000, 1.0) << "scan " << k;
    EXPECT_NEAR(plc.f("F8:2"), static_cast<double>(period) / 10'000, 1.0) << "scan " << k;
  }
}

TEST(FreeRunningClock, TheClockWrapsAt20Bits) {
  // RM 7-15: "Once the free running clock reaches 0x000FFFFF (10.48575 seconds), it wraps around to
  // 0". Run 12 s of virtual time: every stamp stays below 2^20 and one scan's stamp is below the last.
  Plc plc("SOR RHC F8:0 EOR");
  plc.run();
  double highest = 0;
  bool wrapped = false;
  double previous = -1;
  while (plc->now() < 12'000'000'000LL) {
    plc->scan(1);
    const double v = plc.f("F8:0");
    highest = std::max(highest, v);
    if (v < previous) wrapped = true;
    previous = v;
  }
  EXPECT_LE(highest, 1048575.0);
  EXPECT_GT(highest, 1048575.0 - 5000) << "it reached the top before wrapping";
  EXPECT_TRUE(wrapped);
}

TEST(FreeRunningClock, TdfTakesTheDifferenceModuloTheWidthItsOperandsHold) {
  // RM 7-16: integer stamps are exact within 65536 ticks of each other (one wrap of the low 16 bits
  // is harmless), float stamps within 1048575.
  Plc plc(with_trap_sample("SOR TDF N7:72 N7:73 N7:74 TDF N7:75 N7:76 N7:77 TDF F8:0 F8:1 F8:2 EOR"));
  plc.set("N7:72", static_cast<std::int16_t>(65530 - 65536));
  plc.set("N7:73", 4);
  plc.set("N7:75", 0);
  plc.set("N7:76", static_cast<std::int16_t>(40000 - 65536));  // 40,000 ticks = 400 ms
  plc.setf("F8:0", 1048570);
  plc.setf("F8:1", 5);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:74"), 10) << "65530 -> 4 across the 16-bit wrap";
  EXPECT_EQ(static_cast<std::uint16_t>(plc.i("N7:77")), 40000) << "a difference above 327.67 ms fills the word's 16 bits";
  EXPECT_EQ(plc.f("F8:2"), 11.0) << "1048570 -> 5 across the 20-bit wrap";
  EXPECT_FALSE(plc.b("B3:1/0"));
}

TEST(FreeRunningClock, AFloatStampRhcCannotHaveWrittenSetsOverflow) {
  // Decision (docs/semantics.md): a float stamp that is not a whole count 0-000FFFFFh did not come
  // from RHC; TDF leaves the destination and sets V (and so S:5/0).
  Plc plc(with_trap_sample("SOR TDF F8:0 F8:1 F8:2 EOR"));
  plc.setf("F8:0", 1.5);
  plc.setf("F8:1", 10);
  plc.setf("F8:2", 77);
  plc.run_scans(1);
  EXPECT_EQ(plc.f("F8:2"), 77.0);
  EXPECT_TRUE(arith_flags(plc) & V);
  EXPECT_TRUE(plc.b("B3:1/0"));
}

// ---- RPC (RM 7-23) --------------------------------------------------------------------------------------------

TEST(ReadProgramChecksum, ProcMemReadsTheLadderImageChecksumAndMemModZero) {
  // RM 7-23: "a 16-bit value that is calculated for the entire ladder logic image, excluding the data
  // table values". softslc's algorithm (docs/semantics.md "RPC"): CRC-32 of "LADDER 2\nSOR RPC 0 N7:0
  // EOR\nSOR RPC 1 N7:1 EOR\n" is 2912F261h (computed by hand with Python's zlib.crc32, outside
  // softslc), folded high XOR low to 16 bits: 2912h ^ F261h = DB73h. MEM-MOD reads 0: softslc has no
  // memory module.
  Plc plc("SOR RPC 0 N7:0 EOR\nSOR RPC 1 N7:1 EOR");
  plc.set("N7:1", 555);
  plc.run_scans(1);
  EXPECT_EQ(static_cast<std::uint16_t>(plc.i("N7:0")), 0xDB73);
  EXPECT_EQ(plc.i("N7:1"), 0);
}

TEST(ReadProgramChecksum, AnEditedRungChangesItAndTheProcessorDoesNot) {
  // "The checksum changes any time program edits are made" (RM 7-23): the one-rung image
  // "LADDER 2\nSOR RPC 0 N7:0 EOR\n" folds to 9EEDh, with an XIC S:1/15 in front 263Eh (zlib.crc32, by hand).
  // The START line is not ladder logic: a MicroLogix 1400 reads the same 9EEDh (tests/micrologix).
  Plc plain("SOR RPC 0 N7:0 EOR");
  plain.run_scans(1);
  EXPECT_EQ(static_cast<std::uint16_t>(plain.i("N7:0")), 0x9EED);
  Plc edited("SOR XIC S:1/15 RPC 0 N7:0 EOR");
  edited.run_scans(1);
  EXPECT_EQ(static_cast<std::uint16_t>(edited.i("N7:0")), 0x263E);
  Plc on_505("SOR RPC 0 N7:0 EOR", {}, "START 1747-L552\n");
  on_505.run_scans(1);
  EXPECT_EQ(static_cast<std::uint16_t>(on_505.i("N7:0")), 0x9EED);
}

// ---- check: integer-only operands and processor availability ----------------------------------------------

std::string check_errors(std::string_view body, std::string_view header = kHeader) {
  std::string errors;
  auto rt = try_build(program_text(body, header), errors);
  return errors;
}

TEST(InstructionRules, BitwiseInstructionsRefuseFloatOperandsAtCheck) {
  // One rule, in the table (WordSource/WordDest): `AND F8:0 1 N7:0` used to pass check and fail
  // when compiled for run.
  for (std::string_view rung : {"SOR AND F8:0 1 N7:0 EOR", "SOR OR N7:0 1.5 N7:1 EOR", "SOR XOR N7:0 1 F8:1 EOR",
                                "SOR NOT F8:0 N7:0 EOR", "SOR SCL F8:0 100 0 N7:0 EOR", "SOR TOD F8:0 N7:0 EOR"}) {
    LoadResult lr = load_program(program_text(rung), "test.slc");
    EXPECT_FALSE(lr.ok()) << rung;
    EXPECT_NE(lr.render_diagnostics().find("integer words"), std::string::npos) << lr.render_diagnostics();
  }
  EXPECT_EQ(check_errors("SOR AND N7:0 1 N7:1 EOR"), "");
}

TEST(InstructionRules, AnInstructionTheProcessorLacksNamesIt) {
  const std::string slc502 = "START 1747-L524\n";
  const std::string e = check_errors("SOR SCP N7:0 0 100 0 10 N7:1 EOR", slc502);
  EXPECT_NE(e.find("SCP is not available on the SLC 5/02"), std::string::npos) << e;
  const std::string e2 = check_errors("SOR SQR N7:0 N7:1 EOR", "START 1747-L511\n");
  EXPECT_NE(e2.find("SQR is not available on the SLC 5/01"), std::string::npos) << e2;
  // A 5/03 before OS302 (Series B) has no SCP either (RM 4-13: SLC 5/03 OS302).
  const std::string e3 = check_errors("SOR ABS N7:0 N7:1 EOR", "START 1747-L532 SERIES B\n");
  EXPECT_NE(e3.find("ABS is not available on the SLC 5/03"), std::string::npos) << e3;
  EXPECT_EQ(check_errors("SOR SQR N7:0 N7:1 EOR\nSOR DDV 3 N7:2 EOR\nSOR TOD N7:0 N7:3 EOR", slc502), "");
}

TEST(InstructionRules, RhcAndTdfOperandRules) {
  // RM 7-17: "an integer address (Nx:x) or Float address (Fx:x)"; TDF's parameters "should be of the
  // same data type"; SLC 5/03, 5/04 and 5/05 columns.
  EXPECT_EQ(check_errors("SOR RHC N7:0 RHC F8:0 TDF N7:72 N7:73 N7:74 TDF F8:1 F8:2 F8:3 EOR"), "");
  EXPECT_NE(check_errors("SOR RHC B3:0 EOR").find("RHC takes N or F words"), std::string::npos);
  EXPECT_NE(check_errors("SOR TDF 5 N7:1 N7:2 EOR").find("not the constant 5"), std::string::npos);
  EXPECT_NE(check_errors("SOR TDF N7:0 F8:1 N7:2 EOR").find("all N words or all F words"), std::string::npos);
  EXPECT_NE(check_errors("SOR RHC N7:0 EOR", "START 1747-L524\n").find("RHC is not available on the SLC 5/02"),
            std::string::npos);
  const std::string ml = check_errors("SOR RHC N7:0 EOR", "START Bul.1766\n");
  EXPECT_NE(ml.find("MicroLogix form"), std::string::npos) << ml;
}

TEST(InstructionRules, RpcOperandRules) {
  // RM 7-23: PROC-MEM or MEM-MOD, and "the integer file address where to copy the selected program
  // checksum"; the SLC 5/03, 5/04 and 5/05 columns.
  EXPECT_EQ(check_errors("SOR RPC 0 N7:0 RPC 1 N10:5 EOR"), "");
  for (std::string_view rung : {"SOR RPC 0 F8:0 EOR", "SOR RPC 0 B3:0 EOR"})
    EXPECT_NE(check_errors(rung).find("RPC writes its checksum to an N word"), std::string::npos) << rung;
  EXPECT_NE(check_errors("SOR RPC 2 N7:0 EOR").find("out of range"), std::string::npos);
  EXPECT_NE(check_errors("SOR RPC 0 N7:0 EOR", "START 1747-L524\n").find("RPC is not available on the SLC 5/02"),
            std::string::npos);
}

TEST(InstructionRules, SwpOperandRules) {
  // RM 4-28: "a bit, integer, ASCII, or string file"; "For the string file type, the length range is
  // 1 to 41"; SLC 5/03 (OS302), SLC 5/04 (OS401) and SLC 5/05 only.
  EXPECT_EQ(check_errors("SOR SWP #B3:0 128 EOR\nSOR SWP #N7:0 1 EOR\nSOR SWP #ST10:1.1 41 EOR"), "");
  EXPECT_NE(check_errors("SOR SWP #F8:0 2 EOR").find("B, N, A or ST file"), std::string::npos);
  EXPECT_NE(check_errors("SOR SWP #T4:0 2 EOR").find("B, N, A or ST file"), std::string::npos);
  EXPECT_NE(check_errors("SOR SWP #N7:0 129 EOR").find("out of range 1-128"), std::string::npos);
  EXPECT_NE(check_errors("SOR SWP #ST10:1.2 41 EOR").find("leaves the string element"), std::string::npos);
  EXPECT_NE(check_errors("SOR SWP #ST10:1 5 EOR").find("name the first one"), std::string::npos);
  EXPECT_NE(check_errors("SOR SWP #N7:0 1 EOR", "START 1747-L532 SERIES B\n").find("SWP is not available"),
            std::string::npos);
  EXPECT_EQ(check_errors("SOR SWP #N7:0 1 EOR", "START Bul.1763\n"), "") << "MicroLogix 1100 has SWP";
}

}  // namespace
}  // namespace softslc::test

namespace softslc::test {
namespace {

// ---- Issue 15 re-check: NEG of -32768 (PT1 20-10) ---------------------------------------------------------

TEST(Recheck, NegOfMinus32768ClearsCarry) {
  // PT1 20-10, NEG: "C cleared if 0 or overflow, otherwise set. V set if overflow ... The value
  // 32,767 is placed in the destination", or with S:2/14 set "the unsigned, truncated overflow".
  Plc plc(with_trap_sample("SOR NEG N7:0 N7:1 EOR"));
  plc.set("N7:0", -32768);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:1"), 32767);
  EXPECT_EQ(arith_flags(plc), V) << "C = 0 on overflow; 32767 is positive";
  EXPECT_TRUE(plc.b("B3:1/0"));
  plc.set("S:2", 0x4000);
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:1"), -32768) << "S:2/14: the truncated result";
  EXPECT_EQ(arith_flags(plc), V | S);
  plc.set("N7:0", 98);  // PT1 20-10's example: 98 -> -98, C set (not 0, no overflow)
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:1"), -98);
  EXPECT_EQ(arith_flags(plc), C | S);
  plc.set("N7:0", 0);
  plc->scan(1);
  EXPECT_EQ(arith_flags(plc), Z) << "C cleared if 0";
}

// ---- Issue 15 re-check: S:24 after FFL/FFU (PT1 23-7) ---------------------------------------------------

TEST(Recheck, FifoLeavesEntryPositionForLoadsAndExitPositionForUnloads) {
  // PT1 23-7: "For the FFL, the position value determined at instruction entry is placed in S:24.
  // For the FFU, the position value determined at instruction exit is placed in S:24."
  Plc plc("SOR XIC B3:0/0 FFL N7:0 #N10:0 R6:0 5 2 EOR\nSOR XIC B3:0/0 MOV S:24 N7:1 EOR\n"
          "SOR XIC B3:0/1 FFU #N10:0 N7:2 R6:0 5 2 EOR\nSOR XIC B3:0/1 MOV S:24 N7:3 EOR");
  plc.set("B3:0/0", 1);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("R6:0.POS"), 3);
  EXPECT_EQ(plc.i("N7:1"), 2) << "FFL: the position at entry (the word just loaded)";
  plc.set("B3:0/0", 0);
  plc.set("B3:0/1", 1);
  plc->scan(1);
  EXPECT_EQ(plc.i("R6:0.POS"), 2);
  EXPECT_EQ(plc.i("N7:3"), 2) << "FFU: the position at exit";
}

}  // namespace
}  // namespace softslc::test
