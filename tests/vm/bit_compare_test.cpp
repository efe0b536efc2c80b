// FBC (file bit comparison) and DDT (diagnostic detect).
//
// Sources: 1747-RM001G p. 7-18 (both compare bits of a source file with a reference file and record
// the bit number of each mismatch in the result file; "If no mismatches are found, the DN bit is set
// and the result file remains unchanged"; DDT changes the reference bit to match the source bit;
// one bit at a time: each false-to-true transition compares the next bit, a mismatch sets FD and is
// recorded; the found bit resets when the rung goes false; the box: Source #B3:0, Reference
// #B3:10, Result #N7:0, compare control R6:0 length 48 position 0, result control R6:1 length 10
// position 0), p. 7-21 (table 7.8: EN, DN, ER, IN, FD of the compare control; the result control's
// DN when the result file fills, after which a false-to-true transition wraps the result position;
// the control elements reset on a false-to-true transition when a position equals its length; the
// control bits reset when the rung goes false). Pages 7-19 and 7-20 were not reached: what rests on
// them (one compare per transition in one-bit mode, ER for a position past its length) is written in
// docs/semantics.md "FBC and DDT" and the tests below say so.
#include <gtest/gtest.h>

#include <string>

#include "vm_test_util.h"

namespace softslc::test {
namespace {

// The manual's box (RM 7-18), on B3:0 bit 0 (the rung condition) and a source at B3:20.
std::string bit_compare(std::string_view mnemonic, int cmp_len = 48, int res_len = 10) {
  return "SOR XIC B3:0/0 " + std::string(mnemonic) + " #B3:20 #B3:10 #N7:0 R6:0 " + std::to_string(cmp_len) +
         " 0 R6:1 " + std::to_string(res_len) + " 0 EOR";
}

constexpr int kEN = 1 << 15, kDN = 1 << 13, kER = 1 << 11, kIN = 1 << 9, kFD = 1 << 8;

TEST(BitCompare, AllPerScanRecordsEveryMismatchedBitNumber) {
  Plc plc(bit_compare("FBC"));
  plc.set("B3:20", 0x0005);  // bits 0 and 2
  plc.set("B3:10", 0x0001);  // bit 0: bit 2 differs
  plc.set("B3:22", static_cast<std::int16_t>(0x8000));  // bit 47 differs
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:0"), 0) << "rung false: nothing yet";
  plc.set("B3:0/0", 1);
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:0"), 2);
  EXPECT_EQ(plc.i("N7:1"), 47);
  EXPECT_EQ(plc.i("N7:2"), 0) << "two mismatches, two entries";
  EXPECT_EQ(plc.i("R6:1.POS"), 2);
  EXPECT_EQ(plc.i("R6:0.POS"), 48) << "the whole 48 bits in one scan (IN clear)";
  const auto cmp = plc.i("R6:0");
  EXPECT_TRUE(cmp & kEN);
  EXPECT_TRUE(cmp & kDN) << "the end of the files";
  EXPECT_TRUE(cmp & kFD) << "after recording all mismatches";
  EXPECT_EQ(plc.i("B3:10"), 0x0001) << "FBC leaves the reference alone";
  EXPECT_EQ(plc.i("R6:0.LEN"), 48) << "the box's lengths are the control elements' LEN";
  EXPECT_EQ(plc.i("R6:1.LEN"), 10);
}

TEST(BitCompare, DdtUpdatesTheReference) {
  Plc plc(bit_compare("DDT"));
  plc.set("B3:20", 0x0005);
  plc.set("B3:10", 0x0001);
  plc.set("B3:22", static_cast<std::int16_t>(0x8000));
  plc.set("B3:0/0", 1);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:0"), 2);
  EXPECT_EQ(plc.i("N7:1"), 47);
  EXPECT_EQ(plc.i("B3:10"), 0x0005) << "RM 7-18: the reference bit changed to match the source";
  EXPECT_EQ(plc.i("B3:12") & 0xFFFF, 0x8000);
}

TEST(BitCompare, NoMismatchSetsDoneAndLeavesTheResultAlone) {
  Plc plc(bit_compare("FBC"));
  plc.set("N7:0", 1234);
  plc.set("B3:20", 0x00F0);
  plc.set("B3:10", 0x00F0);
  plc.set("B3:0/0", 1);
  plc.run_scans(1);
  EXPECT_TRUE(plc.i("R6:0") & kDN);
  EXPECT_FALSE(plc.i("R6:0") & kFD);
  EXPECT_EQ(plc.i("N7:0"), 1234) << "RM 7-18: the result file remains unchanged";
}

TEST(BitCompare, WorksOnFalseToTrueOnlyAndRestartsWhenDone) {
  Plc plc(bit_compare("FBC"));
  plc.set("B3:20", 0x0002);
  plc.set("B3:0/0", 1);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("R6:1.POS"), 1);
  plc->scan(2);
  EXPECT_EQ(plc.i("R6:1.POS"), 1) << "a rung that stays true does nothing more";
  plc.set("B3:0/0", 0);
  plc->scan(1);
  EXPECT_EQ(plc.i("R6:0") & (kEN | kDN | kFD), 0) << "RM 7-21: the control bits reset when the rung goes false";
  EXPECT_EQ(plc.i("R6:0.POS"), 48) << "the positions stay";
  plc.set("B3:20", 0x0008);
  plc.set("B3:0/0", 1);
  plc->scan(1);
  // RM 7-21: position == length clears both positions on the false-to-true transition.
  EXPECT_EQ(plc.i("N7:0"), 3) << "compared again from bit 0; the result from entry 0";
  EXPECT_EQ(plc.i("R6:1.POS"), 1);
}

TEST(BitCompare, OneBitAtATimeWithTheInhibitBit) {
  // RM 7-18 "One Bit at a Time": each false-to-true transition compares the next bit; table 7.8:
  // IN set selects it and "the ladder program must toggle the EN bit after ... each bit".
  Plc plc(bit_compare("FBC", 4, 4));
  plc.set("R6:0", kIN);
  plc.set("B3:20", 0x0006);  // bits 1 and 2 differ from a zero reference
  plc.run_scans(1);
  const int expect_fd[] = {0, 1, 1, 0};
  for (int bit = 0; bit < 4; ++bit) {
    plc.set("B3:0/0", 1);
    plc->scan(1);
    EXPECT_EQ(plc.i("R6:0.POS"), bit + 1) << "bit " << bit;
    EXPECT_EQ((plc.i("R6:0") & kFD) != 0, expect_fd[bit] != 0) << "bit " << bit;
    plc.set("B3:0/0", 0);
    plc->scan(1);
    EXPECT_EQ(plc.i("R6:0") & kFD, 0) << "FD resets when the rung goes false (RM 7-18)";
  }
  EXPECT_EQ(plc.i("N7:0"), 1);
  EXPECT_EQ(plc.i("N7:1"), 2);
  EXPECT_EQ(plc.i("R6:1.POS"), 2);
}

TEST(BitCompare, FullResultFileSetsResultDoneAndWrapsOnTheNextTransition) {
  // RM 7-21, result control DN: "set when the result file fills. The instruction stops and requires
  // another false-to-true rung transition to reset the result DN bit and then continue."
  Plc plc(bit_compare("FBC", 16, 1));
  plc.set("B3:20", 0x0012);  // bits 1 and 4 differ
  plc.set("B3:0/0", 1);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:0"), 1);
  EXPECT_TRUE(plc.i("R6:1") & kDN) << "one entry: full";
  EXPECT_EQ(plc.i("R6:0.POS"), 2) << "stopped after the bit it recorded";
  EXPECT_FALSE(plc.i("R6:0") & kDN);
  plc.set("B3:0/0", 0);
  plc->scan(1);
  EXPECT_TRUE(plc.i("R6:1") & kDN) << "the result DN waits for the next false-to-true transition";
  plc.set("B3:0/0", 1);
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:0"), 4) << "the result position wrapped to 0";
  EXPECT_EQ(plc.i("R6:0.POS"), 5) << "full again after bit 4";
  plc.set("B3:0/0", 0);
  plc->scan(1);
  plc.set("B3:0/0", 1);
  plc->scan(1);
  EXPECT_TRUE(plc.i("R6:0") & kDN) << "bits 5-15 match: the end of the files";
  EXPECT_FALSE(plc.i("R6:1") & kDN);
  EXPECT_EQ(plc.i("N7:0"), 4) << "nothing more recorded";
}

TEST(BitCompare, ErrorBitStopsTheInstructionUntilTheLadderResetsIt) {
  // Table 7.8: ER "if the length (LEN) is less than or equal to zero or if the position (POS) is
  // less than zero. The ladder program must reset the ER bit".
  Plc plc(bit_compare("FBC"));
  plc.set("R6:0.LEN", 0);
  plc.set("B3:20", 1);
  plc.set("B3:0/0", 1);
  plc.run_scans(1);
  EXPECT_TRUE(plc.i("R6:0") & kER);
  EXPECT_EQ(plc.i("R6:1.POS"), 0);
  plc.set("R6:0.LEN", 16);
  plc.set("B3:0/0", 0);
  plc->scan(1);
  plc.set("B3:0/0", 1);
  plc->scan(1);
  EXPECT_EQ(plc.i("R6:1.POS"), 0) << "ER still set: stopped";
  plc.set("R6:0", 0);
  plc.set("B3:0/0", 0);
  plc->scan(1);
  plc.set("B3:0/0", 1);
  plc->scan(1);
  EXPECT_EQ(plc.i("R6:1.POS"), 1) << "reset by the ladder: it runs";
  EXPECT_FALSE(plc->fault().has_value()) << "ER is not a processor fault";
}

TEST(BitCompare, FilesShorterThanTheLengthFault002A) {
  // The literal length sizes the files (32 bits: two words of B3 and of N7); a LEN the program
  // raises past them runs off the end of the source file at run time.
  Plc plc("SOR XIC B3:0/0 FBC #B3:0 #N7:0 #N9:0 R6:0 32 0 R6:1 2 0 EOR");
  plc.run_scans(1);
  plc.set("R6:0.LEN", 64);
  plc.set("B3:0/0", 1);
  plc->scan(1);
  EXPECT_EQ(plc.fault_code(), 0x002A);
}

std::string errors_of(std::string_view body, std::string_view header = kHeader) {
  return build_errors(program_text(body, header));
}

TEST(BitCompareCheck, ResultIsAnIntegerFileAndTheControlsDiffer) {
  std::string e = errors_of("SOR FBC #B3:0 #B3:10 #B3:30 R6:0 16 0 R6:1 4 0 EOR");
  EXPECT_NE(e.find("result must be an integer (N) file"), std::string::npos) << e;
  e = errors_of("SOR DDT #B3:0 #B3:10 #N7:0 R6:0 16 0 R6:0 4 0 EOR");
  EXPECT_NE(e.find("two control elements"), std::string::npos) << e;
  EXPECT_EQ(errors_of(bit_compare("DDT")), "");
}

TEST(BitCompareCheck, RefusedWhereTheProcessorLacksIt) {
  std::string e = errors_of(bit_compare("FBC"), "START 1747-L524\n");
  EXPECT_NE(e.find("FBC is not available"), std::string::npos) << e;
  e = errors_of(bit_compare("DDT"), "START Bul.1766\n");
  EXPECT_NE(e.find("is not a MicroLogix instruction"), std::string::npos) << e;
}

}  // namespace
}  // namespace softslc::test
