// PCCC commands, byte for byte. Layouts: DF1 Protocol and Command Set manual (1770-6.5.16)
// chapter 7 (CMD 0F typed logical read/write: size, then address fields of one byte or FFh and a
// 16-bit value) and p. 8-4 (EXT STS codes for CMD 0F). The file type codes are the ones nodepccc
// 0.1.17 sends (stringToSLCAddr: 89h N, 8Ah F, 86h T, 8Dh ST ...).
#include <gtest/gtest.h>

#include "server/pccc.h"
#include "tests/serve/serve_test_util.h"

namespace softslc::serve::testing {
namespace {

class PcccTest : public ::testing::Test {
 protected:
  LiveController live{hmi_program(), std::nullopt, {}};
  Bytes run(const Bytes& command) {
    auto r = pccc::decode(command);
    EXPECT_TRUE(r.has_value());
    if (!r) return {};
    return pccc::execute(*r, live);
  }
};

TEST(PcccDecode, ThreeAddressFieldReadWithShortAndLongFields) {
  // CMD 0F, STS 0, TNS 1234h, FNC A2, size 2, file FFh 0107h (263), type 89h, element 5, sub 0.
  auto r = pccc::decode(Bytes{0x0F, 0x00, 0x34, 0x12, 0xA2, 0x02, 0xFF, 0x07, 0x01, 0x89, 0x05, 0x00});
  ASSERT_TRUE(r);
  EXPECT_EQ(r->kind, pccc::Kind::Read);
  EXPECT_EQ(r->tns, 0x1234);
  EXPECT_EQ(r->file, 263);
  EXPECT_EQ(r->type, 0x89);
  EXPECT_EQ(r->element, 5);
  EXPECT_EQ(r->sub, 0);
}

TEST(PcccDecode, BrokenCommandsAreErrorsNotGuesses) {
  std::string error;
  EXPECT_FALSE(pccc::decode(Bytes{0x0F, 0x00, 0x34}, &error));
  EXPECT_FALSE(pccc::decode(Bytes{0x0F, 0x00, 0x34, 0x12, 0xA2, 0x02, 0xFF, 0x07}, &error));  // file cut off
  EXPECT_NE(error.find("cut off"), std::string::npos);
  // A write whose size byte says 4 but carries 2 data bytes.
  EXPECT_FALSE(pccc::decode(Bytes{0x0F, 0x00, 1, 0, 0xAA, 0x04, 0x07, 0x89, 0x00, 0x00, 0x01, 0x00}, &error));
  // A read with trailing bytes.
  EXPECT_FALSE(pccc::decode(Bytes{0x0F, 0x00, 1, 0, 0xA2, 0x02, 0x07, 0x89, 0x00, 0x00, 0x99}, &error));
}

TEST_F(PcccTest, ReadsAnIntegerWithTwoAndThreeAddressFields) {
  // N7:0 is 500 (01F4h) from the program's DATA block; the reply is CMD 4Fh, STS 0, TNS, data.
  EXPECT_EQ(run({0x0F, 0x00, 0x34, 0x12, 0xA2, 0x02, 0x07, 0x89, 0x00, 0x00}), (Bytes{0x4F, 0x00, 0x34, 0x12, 0xF4, 0x01}));
  EXPECT_EQ(run({0x0F, 0x00, 0x35, 0x12, 0xA1, 0x02, 0x07, 0x89, 0x00}), (Bytes{0x4F, 0x00, 0x35, 0x12, 0xF4, 0x01}));
}

TEST_F(PcccTest, ReadsTimerSubElementsAndWholeElements) {
  // T4:0 is control, PRE, ACC; the program's TON sets PRE 1000 (03E8h) at download. Six bytes
  // read the whole element.
  const Bytes reply = run({0x0F, 0x00, 1, 0, 0xA2, 0x06, 0x04, 0x86, 0x00, 0x00});
  ASSERT_EQ(reply.size(), 10u);
  EXPECT_EQ(reply[6] | (reply[7] << 8), 1000);  // .PRE
  // Sub-element 1 (.PRE) alone.
  EXPECT_EQ(run({0x0F, 0x00, 1, 0, 0xA2, 0x02, 0x04, 0x86, 0x00, 0x01}), (Bytes{0x4F, 0x00, 1, 0, 0xE8, 0x03}));
}

TEST_F(PcccTest, SubElementWriteWritesOneWordWhateverTheSize) {
  // T4:0.PRE = 50 as nodepccc 0.1.17 sends it: FNC AA, size 6 (a whole timer), sub-element 1,
  // the value in the first word and zeros after. ACC must keep its value.
  live.controller().set("T4:0.ACC", 33);
  EXPECT_EQ(run({0x0F, 0x00, 2, 0, 0xAA, 0x06, 0x04, 0x86, 0x00, 0x01, 0x32, 0x00, 0x00, 0x00, 0x00, 0x00}),
            (Bytes{0x4F, 0x00, 2, 0}));
  EXPECT_EQ(live.controller().get_int("T4:0.PRE"), 50);
  EXPECT_EQ(live.controller().get_int("T4:0.ACC"), 33);
}

TEST_F(PcccTest, WritesAFloatWholeAndReadsItBack) {
  // 12.5f is 41480000h, little-endian 00 00 48 41.
  EXPECT_EQ(run({0x0F, 0x00, 2, 0, 0xAA, 0x04, 0x08, 0x8A, 0x01, 0x00, 0x00, 0x00, 0x48, 0x41}), (Bytes{0x4F, 0x00, 2, 0}));
  EXPECT_DOUBLE_EQ(live.controller().get_float("F8:1"), 12.5);
  EXPECT_EQ(run({0x0F, 0x00, 3, 0, 0xA2, 0x04, 0x08, 0x8A, 0x01, 0x00}), (Bytes{0x4F, 0x00, 3, 0, 0x00, 0x00, 0x48, 0x41}));
}

TEST_F(PcccTest, MaskedWriteChangesOnlyTheMaskedBits) {
  live.controller().set("B3:0", 0x00F0);
  // FNC AB, size 2, B3:0 sub 0, mask 0003h, data 0001h: bit 0 set, bit 1 cleared, rest kept.
  EXPECT_EQ(run({0x0F, 0x00, 4, 0, 0xAB, 0x02, 0x03, 0x85, 0x00, 0x00, 0x03, 0x00, 0x01, 0x00}), (Bytes{0x4F, 0x00, 4, 0}));
  EXPECT_EQ(live.controller().get_int("B3:0"), 0x00F1);
}

TEST_F(PcccTest, StringElementIsLengthThenCharactersHighByteFirst) {
  // ST9:0 = "READY": length 5, then 'R''E' in the first word with 'R' in the high byte (the
  // SLC's string layout; nodepccc swaps each pair back).
  const Bytes reply = run({0x0F, 0x00, 5, 0, 0xA2, 0x54, 0x09, 0x8D, 0x00, 0x00});
  ASSERT_EQ(reply.size(), 4u + 84u);
  EXPECT_EQ(reply[4], 5);
  EXPECT_EQ(reply[5], 0);
  EXPECT_EQ(reply[6], 'E');
  EXPECT_EQ(reply[7], 'R');
  // Writing a new string: length 2, "OK".
  Bytes write = {0x0F, 0x00, 6, 0, 0xAA, 0x06, 0x09, 0x8D, 0x01, 0x00, 0x02, 0x00, 'K', 'O', 0, 0};
  EXPECT_EQ(run(write), (Bytes{0x4F, 0x00, 6, 0}));
  EXPECT_EQ(live.controller().get_int("ST9:1"), 2);
}

TEST_F(PcccTest, ErrorStatusCodesOfTheManual) {
  // 1770-6.5.16 p. 8-4: STS F0h with EXT STS 06h (address not usable), 11h (illegal data
  // type), 0Ah (transaction size plus word address too large), 10h (no access).
  EXPECT_EQ(run({0x0F, 0x00, 7, 0, 0xA2, 0x02, 0x2A, 0x89, 0x00, 0x00}), (Bytes{0x4F, 0xF0, 7, 0, 0x06}));  // N42
  EXPECT_EQ(run({0x0F, 0x00, 7, 0, 0xA2, 0x02, 0x07, 0x8A, 0x00, 0x00}), (Bytes{0x4F, 0xF0, 7, 0, 0x11}));  // N7 as F
  EXPECT_EQ(run({0x0F, 0x00, 7, 0, 0xA2, 0x02, 0x07, 0x89, 0x64, 0x00}), (Bytes{0x4F, 0xF0, 7, 0, 0x06}));  // N7:100
  EXPECT_EQ(run({0x0F, 0x00, 7, 0, 0xA2, 0x02, 0x04, 0x86, 0x00, 0x03}), (Bytes{0x4F, 0xF0, 7, 0, 0x06}));  // T4:0.3
  EXPECT_EQ(run({0x0F, 0x00, 7, 0, 0xA2, 0x08, 0x07, 0x89, 0x62, 0x00}), (Bytes{0x4F, 0xF0, 7, 0, 0x0A}));  // N7:98-101
  EXPECT_EQ(run({0x0F, 0x00, 7, 0, 0xA2, 0xF0, 0x07, 0x89, 0x00, 0x00}), (Bytes{0x4F, 0xF0, 7, 0, 0x09}));  // 240 bytes
  // An unknown function: STS 10h, illegal command or format.
  EXPECT_EQ(run({0x0F, 0x00, 8, 0, 0x55}), (Bytes{0x4F, 0x10, 8, 0}));
}

TEST(PcccReadOnly, EveryWriteIsRefusedAndNothingChanges) {
  LiveOptions o;
  o.read_only = true;
  LiveController live(hmi_program(), std::nullopt, o);
  const auto before = live.controller().data_digest();
  auto r = pccc::decode(Bytes{0x0F, 0x00, 9, 0, 0xAA, 0x02, 0x07, 0x89, 0x00, 0x00, 0x01, 0x00});
  ASSERT_TRUE(r);
  EXPECT_EQ(pccc::execute(*r, live), (Bytes{0x4F, 0xF0, 9, 0, 0x10}));
  EXPECT_EQ(live.controller().data_digest(), before);
}

TEST_F(PcccTest, InputWritesSetTheFieldInputAndForcesWin) {
  // Element 0 of the I file is the first image word (slot 1). Writing it sets the field inputs,
  // seen from the next input scan, as `softslc run --set I:1=...` does.
  live.controller().force("I:1/3", false);
  EXPECT_EQ(run({0x0F, 0x00, 10, 0, 0xAA, 0x02, 0x01, 0x8C, 0x00, 0x00, 0x09, 0x00}), (Bytes{0x4F, 0x00, 10, 0}));
  live.step(1);
  EXPECT_EQ(live.controller().get_int("I:1"), 0x0001);  // bit 3 forced off holds
}

TEST_F(PcccTest, DiagnosticStatusNamesTheProcessor) {
  const Bytes reply = run({0x06, 0x00, 11, 0, 0x03});
  ASSERT_EQ(reply.size(), 4u + 24u);
  EXPECT_EQ(reply[0], 0x46);
  EXPECT_EQ(std::string(reply.begin() + 9, reply.begin() + 18), "1747-L552");
  EXPECT_EQ(run({0x06, 0x00, 12, 0, 0x00, 0xAB, 0xCD}), (Bytes{0x46, 0x00, 12, 0, 0xAB, 0xCD}));  // echo
}

}  // namespace
}  // namespace softslc::serve::testing
