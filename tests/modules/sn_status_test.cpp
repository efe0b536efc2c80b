// The 1747-SN's M0 control and M1 status files (1747-SN manual, chapter 4), checked against the
// manual's own examples. Expected values are the manual's, cited at each test.
#include <gtest/gtest.h>

#include "modules_test_util.h"

namespace softslc::test {
namespace {

// Chapter 4, "RIO Status Example" (pp. 4-28/4-29): G file word 1 = 0010 0010 0001 1001
// (0x2219), word 2 = 1110 0110 1111 1001 (0xE6F9): 1/4 rack at rack 0 group 0, 1/4 rack at rack
// 0 group 6, a full rack 1, 1/2 rack at rack 2 group 2, 3/4 rack at rack 3 group 2. 115.2K baud.
const std::string kStatusProgram =
    "START 1747-L532\n"
    "SLOT 1 1747-SN SCAN_IN 32 SCAN_OUT 32 G_FILE 3\n 0 8729 59129 OPTION baud=115.2K\n"
    "LADDER 2\n"
    "SOR XIC B3:0/0 OTE B3:0/1 EOR\n";

const std::string kStatusBench = R"(# the five devices of the RIO status example
scanner RIO slot=1 {
  adapter R0G0 rack=0 group=0 size=1/4
  adapter R0G6 rack=0 group=6 size=1/4
  adapter R1   rack=1 group=0 size=full
  adapter R2G2 rack=2 group=2 size=1/2
  adapter R3G2 rack=3 group=2 size=3/4
}
)";

TEST(SnStatus, Chapter4RioStatusExampleWithAFaultInRack3Group2) {
  Bench b(kStatusProgram, kStatusBench);
  b.inject("R3G2", "offline");
  b.run();
  b->run_for(milliseconds(200));
  // "The three quarter logical rack device located in logical rack 3 (M1:e.9/13) is not active.
  // The fault is indicated by the Enabled Device Fault status bit, bit 0, word 0 (M1:e.0/0)."
  EXPECT_EQ(b.m1(0), 0x0003);  // Status Word, Word 0: bits 1 and 0 set
  EXPECT_EQ(b.m1(2), 0x0001);  // Baud Rate, Word 2: 01 = 115.2K
  EXPECT_EQ(b.m1(8), 0x2219);  // Primary Device Address, Word 8 = G word 1
  EXPECT_EQ(b.m1(9), 0xE6F9);  // Primary Device Size, Word 9 = G word 2
  EXPECT_EQ(b.m1(10), 0x0219);  // Primary Active Device Status: 0000 0010 0001 1001
  EXPECT_EQ(b.m1(12), 0);
  EXPECT_EQ(b.m1(13), 0);
  EXPECT_EQ(b.m1(14), 0);
  EXPECT_EQ(b.m1(15), 0x000E);  // Word 15 bits 1, 2, 3: the 3/4 rack device at rack 3 group 2
  // Through the processor, as a ladder program reads them.
  EXPECT_EQ(b.u("M1:1.0"), 0x0003);
  EXPECT_TRUE(b.b("M1:1.15/1"));
  EXPECT_FALSE(b.b("M1:1.10/13"));
}

TEST(SnStatus, AllDevicesActiveWhenEveryAdapterAnswers) {
  Bench b(kStatusProgram, kStatusBench);
  b.run();
  b->run_for(milliseconds(200));
  // "Unless devices are inhibited, not responding to communications, or configured to an
  // incorrect logical rack size, this word is identical to the device configuration (M1:e.8)."
  EXPECT_EQ(b.m1(10), b.m1(8));
  EXPECT_EQ(b.m1(0), 0x0002);
  for (int w = 12; w <= 15; ++w) EXPECT_EQ(b.m1(w), 0) << w;
}

TEST(SnStatus, DeviceInhibitDefaultsFollowTheGFile) {
  // Chapter 4, "Example of Device Inhibit Control": G word 1 starting groups rack 3: 6 4 2,
  // rack 2: 4 2, rack 1: 6 4 2 0, rack 0: 6 0 (1110 0110 1111 1001 = 0xE6F9), and the default
  // inhibit words 8-11 are 0110, 0000, 1001, 0001.
  Bench b("START 1747-L532\nSLOT 1 1747-SN SCAN_IN 32 SCAN_OUT 32 G_FILE 3\n 0 59129 59129\nLADDER 2\n"
          "SOR XIC B3:0/0 OTE B3:0/1 EOR\n",
          "");
  b.run();
  EXPECT_EQ(b.m0(8), 0b0110);
  EXPECT_EQ(b.m0(9), 0b0000);
  EXPECT_EQ(b.m0(10), 0b1001);
  EXPECT_EQ(b.m0(11), 0b0001);
  // Device reset words default to 0; remote output reset is set for every configured device.
  for (int w = 16; w <= 19; ++w) EXPECT_EQ(b.m0(w), 0) << w;
  EXPECT_EQ(b.m0(24), 0b1001);
  EXPECT_EQ(b.m0(25), 0b1111);
  EXPECT_EQ(b.m0(26), 0b0110);
  EXPECT_EQ(b.m0(27), 0b1110);
}

TEST(SnStatus, M1IsReadOnlyToTheProgram) {
  // "M1 is a read only file; do not write to this file." A write faults the processor (xx55h).
  Bench b("START 1747-L532\nSLOT 1 1747-SN SCAN_IN 32 SCAN_OUT 32 G_FILE 3\n 0 1 1\nLADDER 2\n"
          "SOR MOV 5 M1:1.2 EOR\n",
          "");
  b.run();
  b->scan(1);
  EXPECT_EQ(b.fault_code(), 0x0155);
}

// The scanner answers a block read of M0 or M1 (a BTR's status and data words) at once: the same
// words and the same refusal as its read_m word by word, where the block starts inside the file,
// runs past its end or starts outside it (the module's default, vm/module.cpp, reads word by word).
TEST(SnStatus, MBlockReadsAreReadMWordByWord) {
  Bench b("START 1747-L532\nSLOT 1 1747-SN SCAN_IN 32 SCAN_OUT 32 M0_SIZE 120 M1_SIZE 110 G_FILE 3\n 0 8729 59129 "
          "OPTION baud=115.2K\nLADDER 2\nSOR XIC B3:0/0 OTE B3:0/1 EOR\n",
          kStatusBench);
  b.run();
  b->run_for(milliseconds(200));
  RioScanner& sn = b.sn();
  for (int w = 100; w < 120; ++w) ASSERT_EQ(sn.write_m(MFile::M0, w, static_cast<std::uint16_t>(7 * w + 1)), MAccess::Ok);
  for (const MFile f : {MFile::M0, MFile::M1})
    for (const auto& [word, n] : {std::pair{0, 16}, std::pair{8, 4}, std::pair{100, 4}, std::pair{106, 8}, std::pair{116, 8},
                                  std::pair{109, 1}, std::pair{110, 2}, std::pair{-1, 3}, std::pair{200, 0}, std::pair{5, 0}}) {
      std::vector<std::uint16_t> block(static_cast<std::size_t>(n), 0xEEEE), words(static_cast<std::size_t>(n), 0xEEEE);
      std::size_t done = 99;
      const MAccess got = sn.read_m_block(f, word, block, done);
      std::size_t read = 0;
      MAccess want = MAccess::Ok;
      for (; read < words.size(); ++read)
        if ((want = sn.read_m(f, word + static_cast<int>(read), words[read])) != MAccess::Ok) break;
      const std::string what = std::string(f == MFile::M0 ? "M0" : "M1") + " " + std::to_string(word) + "+" + std::to_string(n);
      EXPECT_EQ(got, want) << what;
      EXPECT_EQ(done, read) << what;
      EXPECT_EQ(block, words) << what;
    }
  // Reads that run past the end stop there: M1 has 110 words, M0 120.
  std::vector<std::uint16_t> block(8);
  std::size_t done = 0;
  EXPECT_EQ(sn.read_m_block(MFile::M1, 106, block, done), MAccess::NoSuchWord);
  EXPECT_EQ(done, 4u);
  EXPECT_EQ(sn.read_m_block(MFile::M0, 112, block, done), MAccess::Ok);
  EXPECT_EQ(done, 8u);
  EXPECT_EQ(block[3], 7 * 115 + 1);
}

}  // namespace
}  // namespace softslc::test
