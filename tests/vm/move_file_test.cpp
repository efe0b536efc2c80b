// MOV MVM COP FLL, indexed and indirect addressing, BSL BSR, SQO SQC SQL, FFL FFU LFL LFU.
//
// Sources: facts §5 "Moves and copies" (MOV float->int rounds; MVM formula; COP raw copy counted
// in destination elements and overwrites S:24), RM E-11 (#N7:10 = base + S:24; files are not
// grown for the index; file instructions overwrite S:24), facts §2 indirect forms, the .def rows
// for the shift, sequencer and stack instructions. Fault codes 002Ah / 0029h are [S] (facts §3).
// Decisions on S:24 values, ER handling and empty-stack unloads: docs/semantics.md.
#include <gtest/gtest.h>

#include "vm_test_util.h"

namespace softslc::test {
namespace {

TEST(Move, MovConvertsAndSetsFlags) {
  Plc plc(
      "SOR MOV F8:0 N7:0 EOR\n"
      "SOR MOV N7:1 F8:1 EOR\n"
      "SOR MOV 0 N7:2 EOR");
  plc.setf("F8:0", -3.5);
  plc.set("N7:1", -12);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:0"), -4) << "-3.5 rounds to even";
  EXPECT_DOUBLE_EQ(plc.f("F8:1"), -12.0);
  EXPECT_EQ(plc.i("S:0") & 0xF, 4) << "last MOV wrote 0: Z";
}

TEST(Move, MvmMovesOnlyMaskedBits) {
  // dest = (src AND mask) OR (dest AND NOT mask)
  Plc plc("SOR MVM N7:0 0x0F0F N7:1 EOR");
  plc.set("N7:0", 0x1234);
  plc.set("N7:1", static_cast<std::int16_t>(0xABCD));
  plc.run_scans(1);
  EXPECT_EQ(static_cast<std::uint16_t>(plc.i("N7:1")), 0xA2C4);
}

// The same copy through a pre-resolved (direct) COP and through one the interpreter resolves
// each scan (an indirect file number): same words, same S:24, same scan time.
TEST(Move, DirectCopMatchesResolvedCop) {
  const char* data = "DATA N7:0\n% N7:0 % 11 -12 13 -14 15 -16\nDATA N9:0\n% N9:0 % 7\n";
  Plc direct(std::string("SOR XIC B3:0/0 COP #N7:0 #T4:1 2 EOR\n") + data);
  Plc resolved(std::string("SOR XIC B3:0/0 COP #N[N9:0]:0 #T4:1 2 EOR\n") + data);
  for (Plc* plc : {&direct, &resolved}) {
    plc->run();
    plc->set("B3:0/0", 1);
    plc->set("S:24", 99);
    plc->run_scans(1);
  }
  for (const char* a : {"T4:1.0", "T4:1.PRE", "T4:1.ACC", "T4:2.0", "T4:2.PRE", "T4:2.ACC", "S:24"})
    EXPECT_EQ(direct.i(a), resolved.i(a)) << a;
  EXPECT_EQ(direct.i("T4:2.ACC"), -16);
  EXPECT_EQ(direct.i("S:24"), 1) << "COP leaves length - 1 in S:24";
  EXPECT_EQ(direct->stats().last, resolved->stats().last);
  EXPECT_EQ(direct->stats().instructions, resolved->stats().instructions);
}

TEST(Move, CopCopiesRawWordsInDestinationElements) {
  Plc plc(
      "SOR XIC B3:0/0 COP #N7:0 #N10:2 3 EOR\n"
      "SOR XIC B3:0/1 COP #F8:0 #N11:0 2 EOR\n"
      "DATA N7:0\n% N7:0 % 1 2 3 4\n"
      "DATA F8:0\n% F8:0 % 1.0");
  plc.run();
  plc.set("S:24", 77);
  plc.set("B3:0/0", 1);
  plc->scan(1);
  EXPECT_EQ(plc.i("N10:2"), 1);
  EXPECT_EQ(plc.i("N10:3"), 2);
  EXPECT_EQ(plc.i("N10:4"), 3);
  EXPECT_FALSE(plc->get("N10:5").has_value()) << "N10 was sized to the copy: elements 0-4 only";
  EXPECT_NE(plc.i("S:24"), 77) << "COP overwrites the index register (RM E-11)";
  // No conversion: the float 1.0 (0x3F800000) arrives as its two raw words.
  plc.set("B3:0/0", 0);
  plc.set("B3:0/1", 1);
  plc->scan(1);
  const auto lo = static_cast<std::uint16_t>(plc.i("N11:0"));
  const auto hi = static_cast<std::uint16_t>(plc.i("N11:1"));
  EXPECT_EQ((static_cast<std::uint32_t>(hi) << 16) | lo, 0x3F800000u);
}

TEST(Move, FllFillsWithConversion) {
  Plc plc(
      "SOR FLL 7 #N7:2 4 EOR\n"
      "SOR FLL 2.5 #F8:0 2 EOR");
  plc.run_scans(1);
  for (int e = 2; e < 6; ++e) EXPECT_EQ(plc.i("N7:" + std::to_string(e)), 7);
  EXPECT_EQ(plc.i("N7:0"), 0);
  EXPECT_DOUBLE_EQ(plc.f("F8:1"), 2.5);
}

TEST(Indexed, OffsetByS24) {
  Plc plc(
      "SOR MOV #N7:2 N10:0 EOR\n"
      "SOR MOV 99 #N7:0 EOR\n"
      "DATA N7:0\n% N7:0 % 10 11 12 13 14 15");
  plc.set("S:24", 3);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N10:0"), 15) << "#N7:2 with S:24 = 3 is N7:5";
  EXPECT_EQ(plc.i("N7:3"), 99);
}

TEST(Indexed, PastTheFileIsMajorFault002A) {
  // RM E-11: the file is not grown for the index; past its end is a run-time error.
  Plc plc(
      "SOR XIC B3:0/0 OTE B3:0/1 EOR\n"
      "SOR MOV #N7:2 N10:0 EOR\n"
      "DATA N7:0\n% N7:0 % 10 11 12 13");
  plc.set("S:24", 1);
  plc.run_scans(1);
  ASSERT_FALSE(plc->fault().has_value());
  EXPECT_EQ(plc.i("N10:0"), 13) << "#N7:2 + 1 = N7:3, the last element";
  plc.set("S:24", 2);
  plc->scan(1);
  ASSERT_TRUE(plc->fault().has_value());
  EXPECT_EQ(plc.fault_code(), 0x002A);
  EXPECT_EQ(plc->fault()->file, 2);
  EXPECT_EQ(plc->fault()->rung, 1);
  EXPECT_NE(plc->fault()->message.find("#N7:2"), std::string::npos) << plc->fault()->message;
  plc.set("S:24", -3);
  plc->clear_fault();
  plc.run();
  plc->scan(1);
  EXPECT_EQ(plc.fault_code(), 0x002A) << "negative offsets before the file fault too";
}

TEST(Indexed, IndexedTimerWord) {
  // RM E-11 example: #T4:3.ACC offsets in elements.
  Plc plc("SOR MOV #T4:3.ACC N7:0 EOR\nSOR TON T4:9 0.01 100 0 EOR");
  plc.set("T4:5.ACC", 321);
  plc.set("S:24", 2);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:0"), 321);
}

TEST(Indirect, ElementFileAndBitPointers) {
  Plc plc(
      "SOR MOV N7:[N10:1] N10:5 EOR\n"
      "SOR MOV N[N10:0]:2 N10:6 EOR\n"
      "SOR XIC B3/[N10:2] OTE B3:0/0 EOR\n"
      "DATA N7:0\n% N7:0 % 0 0 0 70 71\n"
      "DATA N12:0\n% N12:0 % 120 121 122\n"
      "DATA N10:0\n% N10:0 % 12 4 35\n"
      "DATA B3:0\n% B3:0 % 0 0 0");
  plc.set("B3:2/3", 1);  // bit 35 = B3:2/3
  plc.run_scans(1);
  ASSERT_FALSE(plc->fault().has_value()) << plc->fault()->to_string();
  EXPECT_EQ(plc.i("N10:5"), 71);
  EXPECT_EQ(plc.i("N10:6"), 122);
  EXPECT_TRUE(plc.b("B3:0/0"));
  // The runtime API resolves the same forms.
  EXPECT_EQ(plc.i("N7:[N10:1]"), 71);
}

TEST(Indirect, PointerPastTheFileIsMajorFault0029) {
  Plc plc(
      "SOR MOV N7:[N10:1] N10:5 EOR\n"
      "DATA N7:0\n% N7:0 % 0 1 2\n"
      "DATA N10:0\n% N10:0 % 0 300");
  plc.run_scans(1);
  ASSERT_TRUE(plc->fault().has_value());
  EXPECT_EQ(plc.fault_code(), 0x0029);
  EXPECT_EQ(plc->fault()->rung, 0);
  EXPECT_EQ(plc.i("N10:5"), 0) << "nothing was written";
}

// A bit pointer must name bit 0-15 of the addressed word on the SLC (docs/semantics.md "Indexed and
// indirect addresses"): 16 and a negative pointer are both 0029h, and nothing is written (a negative
// pointer once addressed the whole word).
TEST(Indirect, BitPointerOutsideTheWordIsMajorFault0029OnTheSlc) {
  for (int pointer : {16, -1}) {
    SCOPED_TRACE(pointer);
    Plc plc("SOR OTL N7:0/[N10:0] EOR\nDATA N7:0\n% N7:0 % 0 0\nDATA N10:0\n% N10:0 % 0");
    plc.set("N10:0", pointer);
    plc.run_scans(1);
    EXPECT_EQ(plc.fault_code(), 0x0029);
    EXPECT_EQ(plc.i("N7:0"), 0);
    EXPECT_EQ(plc.i("N7:1"), 0);
  }
}

TEST(Indirect, PointerToAMissingFileIsMajorFault0029) {
  Plc plc("SOR MOV N[N10:0]:0 N10:5 EOR\nDATA N10:0\n% N10:0 % 40");
  plc.run_scans(1);
  EXPECT_EQ(plc.fault_code(), 0x0029);
}

TEST(Shift, BslShiftsOnRisingEdge) {
  Plc plc("SOR XIC B3:0/0 BSL #B3:1 R6:0 I:1/0 20 EOR");
  EXPECT_EQ(plc.i("R6:0.LEN"), 20) << "the length literal initialises LEN";
  plc.run();
  plc->set("I:1/0", Value::bit(true));
  plc.set("B3:2/3", 1);  // bit 19 of the array: the last one
  plc->scan(1);
  plc.set("B3:0/0", 1);
  plc->scan(3);
  EXPECT_EQ(plc.i("B3:1"), 1) << "source bit shifted in at bit 0, once";
  EXPECT_TRUE(plc.b("R6:0/UL")) << "bit 19 shifted out into UL";
  EXPECT_FALSE(plc.b("B3:2/3"));
  EXPECT_TRUE(plc.b("R6:0/EN"));
  EXPECT_TRUE(plc.b("R6:0/DN"));
  plc.set("B3:0/0", 0);
  plc->scan(1);
  plc->set("I:1/0", Value::bit(false));
  plc.set("B3:0/0", 1);
  plc->scan(1);
  EXPECT_EQ(plc.i("B3:1"), 2);
  EXPECT_FALSE(plc.b("R6:0/UL"));
  EXPECT_EQ(plc.i("B3:2") & 0xFFF0, 0) << "bits above the 20-bit array are untouched";
}

TEST(Shift, BsrShiftsTowardBitZero) {
  Plc plc("SOR XIC B3:0/0 BSR #B3:1 R6:0 B3:0/1 4 EOR");
  plc.set("B3:1", 0b1001);
  plc.set("B3:0/1", 1);
  plc.run();
  plc->scan(1);
  plc.set("B3:0/0", 1);
  plc->scan(1);
  EXPECT_EQ(plc.i("B3:1"), 0b1100) << "source enters at bit 3 (length - 1)";
  EXPECT_TRUE(plc.b("R6:0/UL")) << "bit 0 went to UL";
}

TEST(Sequencer, SqoStepsThroughTheFile) {
  Plc plc(
      "SOR XIC B3:0/0 SQO #N7:0 0x00FF O:2.0 R6:0 3 0 EOR\n"
      "DATA N7:0\n% N7:0 % 0 0x11 0x22 0x33");
  plc.run();
  plc->scan(1);
  auto step = [&] {
    plc.set("B3:0/0", 1);
    plc->scan(1);
    plc.set("B3:0/0", 0);
    plc->scan(1);
  };
  step();
  EXPECT_EQ(plc.i("O:2.0"), 0x11);
  EXPECT_EQ(plc.i("R6:0.POS"), 1);
  step();
  step();
  EXPECT_EQ(plc.i("O:2.0"), 0x33);
  EXPECT_TRUE(plc.b("R6:0/DN")) << "DN at the last step";
  step();
  EXPECT_EQ(plc.i("R6:0.POS"), 1) << "wraps to step 1";
  EXPECT_EQ(plc.i("O:2.0"), 0x11);
  EXPECT_FALSE(plc.b("R6:0/DN"));
}

TEST(Sequencer, SqoKeepsUnmaskedBits) {
  Plc plc("SOR XIC B3:0/0 SQO #N7:0 0x000F N7:10 R6:0 1 0 EOR\nDATA N7:0\n% N7:0 % 0 0x00F5");
  plc.set("N7:10", 0x1230);
  plc.set("B3:0/0", 1);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:10"), 0x1235);
}

TEST(Sequencer, SqcAndSql) {
  Plc plc(
      "SOR XIC B3:0/0 SQL #N10:0 N7:0 R6:1 3 0 EOR\n"
      "SOR XIC B3:0/1 SQC #N10:0 0xFFFF N7:1 R6:2 3 0 EOR");
  plc.run();
  plc->scan(1);
  for (int v : {5, 6, 7}) {
    plc.set("N7:0", v);
    plc.set("B3:0/0", 1);
    plc->scan(1);
    plc.set("B3:0/0", 0);
    plc->scan(1);
  }
  EXPECT_EQ(plc.i("N10:1"), 5);
  EXPECT_EQ(plc.i("N10:3"), 7);
  EXPECT_TRUE(plc.b("R6:1/DN"));
  plc.set("N7:1", 5);
  plc.set("B3:0/1", 1);
  plc->scan(1);
  EXPECT_TRUE(plc.b("R6:2/FD")) << "step 1 holds 5";
  plc.set("B3:0/1", 0);
  plc->scan(1);
  plc.set("B3:0/1", 1);
  plc->scan(1);
  EXPECT_FALSE(plc.b("R6:2/FD")) << "step 2 holds 6";
}

TEST(Sequencer, InvalidLengthSetsErAndFaultsAtEndUnlessCleared) {
  // PT1 24-8: ER "is set when the processor detects a negative position value, or a negative or
  // zero length value. This results in a major error if not cleared before the END or TND
  // instruction is executed. Use an OTU with address S:5/2 to avoid a CPU fault."
  Plc plc("SOR XIC B3:0/0 SQO #N7:0 0xFFFF N7:9 R6:0 3 0 EOR\nSOR XIC B3:0/1 OTU S:5/2 EOR");
  plc.set("R6:0.LEN", -1);
  plc.set("B3:0/0", 1);
  plc.set("B3:0/1", 1);
  plc.run_scans(1);
  EXPECT_TRUE(plc.b("R6:0/ER"));
  EXPECT_FALSE(plc->fault().has_value()) << "OTU S:5/2 before END avoids the fault";

  Plc plc2("SOR XIC B3:0/0 SQO #N7:0 0xFFFF N7:9 R6:0 3 0 EOR\nSOR TND EOR\nSOR OTE B3:0/2 EOR");
  plc2.set("R6:0.LEN", 0);
  plc2.set("B3:0/0", 1);
  plc2.run_scans(1);
  EXPECT_TRUE(plc2.b("R6:0/ER"));
  EXPECT_EQ(plc2.fault_code(), 0x0020) << "ER (S:5/2) still set at TND";
}

TEST(Sequencer, RangePastTheFileFaults002A) {
  Plc plc("SOR XIC B3:0/0 SQO #N7:0 0xFFFF N7:9 R6:0 3 0 EOR");
  plc.set("R6:0.LEN", 200);  // N7 has 10 elements: 0..200 does not fit
  plc.set("B3:0/0", 1);
  plc.run_scans(1);
  EXPECT_EQ(plc.fault_code(), 0x002A);
}

TEST(Indexed, FileInstructionsOverwriteS24) {
  // RM E-11: file instructions overwrite S:24. The values they leave are softslc's decision
  // (docs/semantics.md): COP/FLL n - 1, sequencers the new POS.
  Plc plc(
      "SOR FLL 0 #N7:0 6 EOR\n"
      "SOR MOV S:24 N10:0 EOR\n"
      "SOR XIC B3:0/0 SQO #N7:0 0xFFFF N7:9 R6:0 4 2 EOR\n"
      "SOR MOV S:24 N10:1 EOR");
  plc.set("S:24", 50);
  plc.set("B3:0/0", 1);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N10:0"), 5);
  EXPECT_EQ(plc.i("N10:1"), 3) << "the SQO stepped from position 2 to 3";
}

TEST(Indexed, ToolsResolveIndexedAddressesThroughTheSameCheck) {
  Plc plc("SOR MOV N7:0 N7:4 EOR\nDATA N7:0\n% N7:0 % 5 6 7 8 9");
  plc.set("S:24", 2);
  EXPECT_EQ(plc.i("#N7:1"), 8);
  std::string err;
  plc.set("S:24", 9);
  EXPECT_FALSE(plc->get("#N7:1", &err).has_value());
  EXPECT_NE(err.find("beyond the end of N7"), std::string::npos) << err;
}

TEST(Stack, FifoLoadAndUnload) {
  Plc plc(
      "SOR XIC B3:0/0 FFL N7:0 #N10:0 R6:0 3 0 EOR\n"
      "SOR XIC B3:0/1 FFU #N10:0 N7:1 R6:0 3 0 EOR");
  plc.run();
  plc->scan(1);
  auto pulse = [&](const char* b) {
    plc.set(b, 1);
    plc->scan(1);
    plc.set(b, 0);
    plc->scan(1);
  };
  for (int v : {1, 2, 3, 4}) {
    plc.set("N7:0", v);
    pulse("B3:0/0");
  }
  EXPECT_EQ(plc.i("R6:0.POS"), 3);
  EXPECT_TRUE(plc.b("R6:0/DN")) << "full; the fourth load was ignored";
  EXPECT_EQ(plc.i("N10:2"), 3);
  pulse("B3:0/1");
  EXPECT_EQ(plc.i("N7:1"), 1) << "first in, first out";
  EXPECT_EQ(plc.i("N10:0"), 2);
  EXPECT_EQ(plc.i("N10:2"), 0);
  EXPECT_EQ(plc.i("R6:0.POS"), 2);
  pulse("B3:0/1");
  pulse("B3:0/1");
  EXPECT_EQ(plc.i("N7:1"), 3);
  EXPECT_TRUE(plc.b("R6:0/EM"));
}

TEST(Stack, LifoLoadAndUnload) {
  Plc plc(
      "SOR XIC B3:0/0 LFL N7:0 #N10:0 R6:0 4 0 EOR\n"
      "SOR XIC B3:0/1 LFU #N10:0 N7:1 R6:0 4 0 EOR");
  plc.run();
  plc->scan(1);
  auto pulse = [&](const char* b) {
    plc.set(b, 1);
    plc->scan(1);
    plc.set(b, 0);
    plc->scan(1);
  };
  for (int v : {10, 20, 30}) {
    plc.set("N7:0", v);
    pulse("B3:0/0");
  }
  pulse("B3:0/1");
  EXPECT_EQ(plc.i("N7:1"), 30) << "last in, first out";
  pulse("B3:0/1");
  EXPECT_EQ(plc.i("N7:1"), 20);
  EXPECT_EQ(plc.i("R6:0.POS"), 1);
  EXPECT_FALSE(plc.b("R6:0/EM"));
}

}  // namespace
}  // namespace softslc::test
