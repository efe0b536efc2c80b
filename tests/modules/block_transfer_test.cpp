// BTR and BTW through the 1747-SN: the handshake of Table 5.2 and "Instruction Operation" steps
// 1-5 (1747-SN ch. 5; RM 1747-RM001G p. 8-7), every error code of Table 5.3, the TO bit and the
// four-second timer, one block transfer per logical rack in FIFO order, and Program mode
// cancelling pending transfers.
#include <gtest/gtest.h>

#include <map>
#include <set>

#include "modules/sn/block_transfer.h"
#include "modules_test_util.h"

namespace softslc::test {
namespace {

using namespace softslc::rio;

// One full logical rack 0 (G word 1 = 1, word 2 = 0x000F) and a half rack at rack 1 group 0
// (word 1 bit 4, word 2 bits 4-5), 115.2K.
const std::string kHeader =
    "START 1747-L532\n"
    "SLOT 1 1747-SN SCAN_IN 32 SCAN_OUT 32 G_FILE 3\n 0 17 63 OPTION baud=115.2K\n"
    "LADDER 2\n";

const std::string kBench = R"(
scanner RIO slot=1 {
  adapter RACK0 rack=0 group=0 size=full backplane_scan=4.5ms {
    module ANALOG kind=bt group=2 slot=0 length=8 data=1,2,3,4,5,6,7,8 response_delay=1ms
    module ANALOG_OUT kind=bt group=3 slot=0 length=4
    module SHORT kind=bt group=4 slot=0 length=5 data=10,20,30,40,50
    module OUTS catalog=1746-OB16 group=5
  }
  adapter RACK1 rack=1 group=0 size=1/2 {
    module FAR kind=bt group=0 length=2 data=77,88
  }
}
)";

// Bits of a control block word 0, as a short string for sequences.
std::string bits(std::uint16_t w) {
  std::string s;
  if (w & kEN) s += "EN ";
  if (w & kEW) s += "EW ";
  if (w & kST) s += "ST ";
  if (w & kDN) s += "DN ";
  if (w & kER) s += "ER ";
  if (w & kTO) s += "TO ";
  if (!s.empty()) s.pop_back();
  return s.empty() ? "-" : s;
}

// Records the distinct successive states of a control block while running.
std::vector<std::string> run_recording(Bench& b, const std::string& cb, Nanoseconds d) {
  std::vector<std::string> seq;
  const VirtualTime end = b->now() + d;
  while (b->now() < end) {
    b->scan(1);
    std::string s = bits(b.u(cb));
    if (seq.empty() || seq.back() != s) seq.push_back(s);
  }
  return seq;
}

TEST(BlockTransfer, ControlBlockIsWrittenAtDownload) {
  // "rack/group/slot/length are stored into the control block": Table 5.1 word 0 RW bit 7
  // (1 = BTR), rack bits 6-4, group 3-1, slot 0; word 1 the requested word count.
  Bench b(kHeader + "SOR XIC B3:0/0 BTR N10:0 M1:1.100 #N11:0 0 2 0 8 EOR\n"
                    "SOR XIC B3:0/1 BTW N10:3 M0:1.200 #N12:0 1 0 0 2 EOR\n",
          kBench);
  EXPECT_EQ(b.u("N10:0"), 0x0080 | (2 << 1));
  EXPECT_EQ(b.i("N10:1"), 8);
  EXPECT_EQ(b.u("N10:3"), (1 << 4));
  EXPECT_EQ(b.i("N10:4"), 2);
}

TEST(BlockTransfer, SuccessfulBtrHandshakeAndData) {
  Bench b(kHeader + "SOR XIC B3:0/0 BTR N10:0 M1:1.100 #N11:0 0 2 0 8 EOR\n", kBench);
  b.run();
  b->scan(2);
  EXPECT_EQ(bits(b.u("N10:0")), "-");
  b.set("B3:0/0", 1);
  // Figure 5.1: EN (rung true), then EW and ST (scanner accepted and started it), then DN.
  auto seq = run_recording(b, "N10:0", milliseconds(200));
  EXPECT_EQ(seq, (std::vector<std::string>{"EN", "EN EW ST", "EN EW ST DN"}));
  // Step 2: DN means word 2 holds the transmitted count and the data file the data.
  EXPECT_EQ(b.i("N10:2"), 8);
  for (int k = 0; k < 8; ++k) EXPECT_EQ(b.i("N11:" + std::to_string(k)), k + 1) << k;
  // Steps 4-5: the rung goes false; EN clears at once, the scanner then clears EW, ST, DN and
  // the count.
  b.set("B3:0/0", 0);
  seq = run_recording(b, "N10:0", milliseconds(100));
  EXPECT_EQ(seq, (std::vector<std::string>{"EW ST DN", "-"}));
  EXPECT_EQ(b.i("N10:2"), 0);
  // The data file keeps the data.
  EXPECT_EQ(b.i("N11:7"), 8);
  // Again: the same transfer can be re-initiated.
  b.set("B3:0/0", 1);
  EXPECT_TRUE(b.until([&] { return b.b("N10:0/13"); }, milliseconds(200)));
}

TEST(BlockTransfer, RequestedLengthZeroTakesTheDevicesLength) {
  // "If RLEN = 0 for a BTR instruction, the actual length is determined by the RIO device".
  Bench b(kHeader + "SOR XIC B3:0/0 BTR N10:0 M1:1.100 #N11:0 0 4 0 0 EOR\n", kBench);
  b.run();
  b.set("B3:0/0", 1);
  ASSERT_TRUE(b.until([&] { return b.b("N10:0/13"); }, milliseconds(300)));
  EXPECT_EQ(b.i("N10:2"), 5);
  EXPECT_EQ(b.i("N11:4"), 50);
}

TEST(BlockTransfer, BtwSendsTheDataFile) {
  Bench b(kHeader + "SOR XIC B3:0/0 BTW N10:0 M0:1.100 #N11:0 0 3 0 4 EOR\n"
                    "DATA N11:0\n% N11:0 % 11 -22 33 44\n",
          kBench);
  b.run();
  b.set("B3:0/0", 1);
  ASSERT_TRUE(b.until([&] { return b.b("N10:0/13"); }, milliseconds(300)));
  EXPECT_EQ(bits(b.u("N10:0")), "EN EW ST DN");
  EXPECT_EQ(b.i("N10:2"), 4);
  EXPECT_EQ(*b->observe("ANALOG_OUT", "btw data"), (std::vector<std::int64_t>{11, -22, 33, 44}));
  EXPECT_EQ(*b->observe("ANALOG_OUT", "btw count"), (std::vector<std::int64_t>{1}));
}

TEST(BlockTransfer, BtwWithLengthZeroSends64Words) {
  // "If RLEN = 0 for a BTW instruction, 64 words are sent."
  Bench b(kHeader + "SOR XIC B3:0/0 BTW N10:0 M0:1.100 #N11:0 0 3 0 0 EOR\n", kBench);
  b.run();
  b.set("B3:0/0", 1);
  ASSERT_TRUE(b.until([&] { return b.b("N10:0/13"); }, milliseconds(300)));
  EXPECT_EQ(b.i("N10:2"), 64);
  EXPECT_EQ(b->observe("ANALOG_OUT", "btw data")->size(), 64u);
}

// Runs one BTR with the rung true until ER or DN; returns the control block word 2.
std::int64_t error_of(Bench& b, const std::string& cb = "N10:0", Nanoseconds limit = seconds(6)) {
  b.set("B3:0/0", 1);
  const std::string er = cb + "/12", dn = cb + "/13";
  if (!b.until([&] { return b.b(er) || b.b(dn); }, limit)) return 9999;
  if (b.b(dn)) return 0;
  return b.i(cb.substr(0, cb.find(':') + 1) + std::to_string(std::stoi(cb.substr(cb.find(':') + 1)) + 2));
}

TEST(BlockTransfer, ErrorMinus6IllegalLength) {
  // Table 5.3: -6 "Illegal block transfer length requested" (the program changed RLEN to 70).
  Bench b(kHeader + "SOR MOV 70 N10:1 EOR\nSOR XIC B3:0/0 BTR N10:0 M1:1.100 #N11:0 0 2 0 8 EOR\n", kBench);
  b.run();
  EXPECT_EQ(error_of(b), -6);
  // "If no problems occur, the EW bit and ST bit are set": with a problem, only ER.
  EXPECT_FALSE(b.b("N10:0/10"));
  EXPECT_FALSE(b.b("N10:0/14"));
}

TEST(BlockTransfer, ErrorMinus7CommunicationErrorWhenInitiated) {
  Bench b(kHeader + "SOR XIC B3:0/0 BTR N10:0 M1:1.100 #N11:0 0 2 0 8 EOR\n", kBench);
  b.run();
  b->run_for(milliseconds(50));
  b.inject("RACK0", "offline");
  EXPECT_EQ(error_of(b), -7);
}

TEST(BlockTransfer, ErrorMinus8ProtocolErrors) {
  {
    Bench b(kHeader + "SOR XIC B3:0/0 BTR N10:0 M1:1.100 #N11:0 0 2 0 8 EOR\n", kBench);
    b.run();
    b.inject("ANALOG", "bt error");
    EXPECT_EQ(error_of(b), -8);
    // "If the block transfer fails, the length field and the data file are not updated."
    EXPECT_EQ(b.i("N11:0"), 0);
  }
  {
    // The module answers 6 words to a request for 8: the counts do not match.
    Bench b(kHeader + "SOR XIC B3:0/0 BTR N10:0 M1:1.100 #N11:0 0 2 0 8 EOR\n", kBench);
    b.run();
    b.inject("ANALOG", "data size", {"6"});
    EXPECT_EQ(error_of(b), -8);
  }
}

TEST(BlockTransfer, ErrorMinus9TimeOuts) {
  {
    // The module does not answer: the scanner's four-second timer (Table 5.2, TO).
    Bench b(kHeader + "SOR XIC B3:0/0 BTR N10:0 M1:1.100 #N11:0 0 2 0 8 EOR\n", kBench);
    b.run();
    b.inject("ANALOG", "message timeout");
    b.set("B3:0/0", 1);
    ASSERT_TRUE(b.until([&] { return b.b("N10:0/14"); }, milliseconds(100)));
    const VirtualTime started = b->now();
    ASSERT_TRUE(b.until([&] { return b.b("N10:0/12"); }, seconds(6)));
    EXPECT_EQ(b.i("N10:2"), -9);
    EXPECT_GE(b->now() - started, seconds(4) - milliseconds(40));  // ST is seen up to a tick late
    EXPECT_LE(b->now() - started, seconds(4) + milliseconds(100));
  }
  {
    // "a time-out error occurs if a block transfer is attempted at a location that is not
    // configured for block transfer operation (e.g., ... an output module)".
    Bench b(kHeader + "SOR XIC B3:0/0 BTR N10:0 M1:1.100 #N11:0 0 5 0 8 EOR\n", kBench);
    b.run();
    EXPECT_EQ(error_of(b), -9);
  }
  {
    // The program sets TO after EW: "Cancelling a block transfer causes an error (ER) bit to set
    // and an error code of -9".
    Bench b(kHeader + "SOR XIC B3:0/0 BTR N10:0 M1:1.100 #N11:0 0 2 0 8 EOR\n"
                      "SOR XIC N10:0/10 XIC B3:0/2 OTL N10:0/8 EOR\n",
            kBench);
    b.run();
    b.inject("ANALOG", "message timeout");
    b.set("B3:0/2", 1);
    b.set("B3:0/0", 1);
    const VirtualTime t0 = b->now();
    ASSERT_TRUE(b.until([&] { return b.b("N10:0/12"); }, seconds(2)));
    EXPECT_EQ(b.i("N10:2"), -9);
    EXPECT_LT(b->now() - t0, seconds(1));
  }
}

TEST(BlockTransfer, TimeOutAndEnableTogetherAreIgnored) {
  // "The RIO scanner ignores a block transfer request if both TO and EN bits are set at the
  // same time."
  Bench b(kHeader + "SOR OTL N10:0/8 EOR\nSOR XIC B3:0/0 BTR N10:0 M1:1.100 #N11:0 0 2 0 8 EOR\n", kBench);
  b.run();
  b.set("B3:0/0", 1);
  b->run_for(milliseconds(500));
  EXPECT_EQ(bits(b.u("N10:0")), "EN TO");
  EXPECT_EQ(*b->observe("ANALOG", "btr count"), (std::vector<std::int64_t>{0}));
}

TEST(BlockTransfer, ErrorMinus10NoRioChannel) {
  // Decision (docs/1747-sn.md): a rack field of 4-7 addresses no RIO channel of the scanner.
  Bench b(kHeader + "SOR MOV 0x00D4 N10:0 EOR\nSOR XIC B3:0/0 BTR N10:0 M1:1.100 #N11:0 0 2 0 8 EOR\n", kBench);
  b.run();
  EXPECT_EQ(error_of(b), -10);
}

TEST(BlockTransfer, ErrorMinus11NotConfigured) {
  // Rack 2 has no device in the G file.
  Bench b(kHeader + "SOR XIC B3:0/0 BTR N10:0 M1:1.100 #N11:0 2 0 0 8 EOR\n", kBench);
  b.run();
  EXPECT_EQ(error_of(b), -11);
}

TEST(BlockTransfer, ErrorMinus11ComplementaryLocationWithoutPrimaryImage) {
  // "Attempted a block transfer ... at a complementary device location where there is no
  // corresponding primary image space allocated."
  Bench b("START 1747-L532\nSLOT 1 1747-SN SCAN_IN 32 SCAN_OUT 32 G_FILE 5\n 0 0 0 1 1\nLADDER 2\n"
          "SOR XIC B3:0/0 BTR N10:0 M1:1.100 #N11:0 0 0 0 4 EOR\n",
          "scanner RIO slot=1 {\n  adapter C rack=8 group=0 size=1/4 {\n    module BT kind=bt rack=8 group=0 length=4\n  }\n}\n");
  b.run();
  EXPECT_EQ(error_of(b), -11);
}

TEST(BlockTransfer, ErrorMinus12InhibitedDevice) {
  Bench b(kHeader + "SOR OTL M0:1.8/0 EOR\nSOR XIC B3:0/0 BTR N10:0 M1:1.100 #N11:0 0 2 0 8 EOR\n", kBench);
  b.run();
  b->scan(3);
  EXPECT_EQ(error_of(b), -12);
}

TEST(BlockTransfer, OneBlockTransferPerLogicalRackInRequestOrder) {
  // Two BTRs to rack 0 and one to rack 1, all enabled in the same scan. "The ST bit is set only
  // after any previous pending block transfers to the same logical rack are completed."
  Bench b(kHeader +
              "SOR XIC B3:0/0 BTR N10:0 M1:1.100 #N11:0 0 2 0 8 EOR\n"
              "SOR XIC B3:0/0 BTR N10:3 M1:1.200 #N12:0 0 4 0 5 EOR\n"
              "SOR XIC B3:0/0 BTR N10:6 M1:1.300 #N13:0 1 0 0 2 EOR\n",
          kBench);
  b.run();
  b.set("B3:0/0", 1);
  bool second_waited = false;
  VirtualTime first_done = -1, second_started = -1;
  while (b->now() < milliseconds(600) && !(b.b("N10:3/13"))) {
    b->scan(1);
    if (b.b("N10:3/10") && !b.b("N10:3/14") && !b.b("N10:0/13")) second_waited = true;
    if (first_done < 0 && b.b("N10:0/13")) first_done = b->now();
    if (second_started < 0 && b.b("N10:3/14")) second_started = b->now();
  }
  EXPECT_TRUE(second_waited) << "the second BT to rack 0 waited with EW set and ST clear";
  ASSERT_GE(first_done, 0);
  ASSERT_GE(second_started, 0);
  EXPECT_GE(second_started, first_done - milliseconds(20));
  EXPECT_TRUE(b.b("N10:3/13"));
  EXPECT_EQ(b.i("N12:4"), 50);
  EXPECT_TRUE(b.b("N10:6/13"));
  EXPECT_EQ(b.i("N13:1"), 88);
}

TEST(BlockTransfer, ProgramModeCancelsPendingTransfers) {
  Bench b(kHeader + "SOR XIC B3:0/0 BTR N10:0 M1:1.100 #N11:0 0 2 0 8 EOR\n", kBench);
  b.run();
  b.inject("ANALOG", "message timeout");
  b.set("B3:0/0", 1);
  ASSERT_TRUE(b.until([&] { return b.b("N10:0/14"); }, milliseconds(100)));
  ASSERT_TRUE(b->set_mode(Mode::Program));
  b->run_for(milliseconds(100));
  EXPECT_EQ(b.m1(100), 0) << "the scanner dropped the request";
  b.inject("ANALOG", "responding");
  b.run();
  // Entering Run clears the buffers; the true rung starts a new transfer, which completes.
  ASSERT_TRUE(b.until([&] { return b.b("N10:0/13"); }, milliseconds(300)));
  EXPECT_EQ(b.i("N11:0"), 1);
}

TEST(BlockTransfer, StatusBitsChangeOnlyWhenTheInstructionIsScanned) {
  // "The BTR/BTW instruction must be scanned (true or false) in order to update the control and
  // status bits." B3:0/1 jumps over the BTR.
  Bench b(kHeader +
              "SOR XIC B3:0/1 JMP 1 EOR\n"
              "SOR XIC B3:0/0 BTR N10:0 M1:1.100 #N11:0 0 2 0 8 EOR\n"
              "SOR LBL 1 XIC B3:0/5 OTE B3:0/6 EOR\n",
          kBench);
  b.run();
  b.set("B3:0/0", 1);
  b->scan(1);
  b.set("B3:0/1", 1);
  b->run_for(milliseconds(300));
  EXPECT_TRUE(b.m1(100) & kDN) << "the scanner finished the transfer";
  EXPECT_EQ(bits(b.u("N10:0")), "EN") << "but the control block has not been updated";
  b.set("B3:0/1", 0);
  b->scan(1);
  EXPECT_EQ(bits(b.u("N10:0")), "EN EW ST DN");
}

TEST(BlockTransfer, TimeVaryingBtrData) {
  Bench b(kHeader + "SOR XIO N10:0/13 XIO N10:0/12 BTR N10:0 M1:1.100 #N11:0 1 0 0 2 EOR\n"
                    "SOR XIC N10:0/13 OSR B3:1/0 ADD N20:0 1 N20:0 EOR\n"
                    "SOR XIC N10:0/13 OSR B3:1/1 COP #N11:0 #N21:[N20:0] 1 EOR\n"
                    "DATA N21:0\n% N21:0 % 0 0 0 0 0 0 0 0 0 0\n% N21:10 % 0 0 0 0 0 0 0 0 0 0\n"
                    "% N21:20 % 0 0 0 0 0 0 0 0 0 0\n% N21:30 % 0 0 0 0 0 0 0 0 0 0\n",
          kBench);
  b.inject("FAR", "bt ramp", {"0", "100", "1", "100ms"});
  b.run();
  b->run_for(seconds(2));
  ASSERT_FALSE(b->fault().has_value()) << b->fault()->to_string();
  const std::int64_t n = b.i("N20:0");
  ASSERT_GE(n, 5);
  // The values read increase with virtual time.
  for (std::int64_t k = 2; k < n; ++k)
    EXPECT_LE(b.i("N21:" + std::to_string(k - 1)), b.i("N21:" + std::to_string(k))) << k;
  EXPECT_GT(b.i("N21:" + std::to_string(n - 1)), b.i("N21:1"));
}

TEST(BlockTransfer, BtrInstructionChargesMFileAccessTime) {
  // The instruction's M0/M1 accesses are charged through the timing model (SLC 5/03 appendix B
  // rows): a true BTR writes two words and reads 4 status words every scan.
  Bench idle(kHeader + "SOR XIC B3:0/0 OTE B3:0/1 EOR\n", kBench);
  Bench bt(kHeader + "SOR XIC B3:0/0 BTR N10:0 M1:1.100 #N11:0 0 2 0 8 EOR\n", kBench);
  idle.run();
  bt.run();
  idle->scan(2);
  bt->scan(2);
  // 730 + 730 (control word, count) + 760 + 4 x 22 (COP from M, 4 words) = 2308 us at least.
  EXPECT_GE(bt->stats().last - idle->stats().last, microseconds(2308));
}


// ---- A 33rd block transfer: every buffer serves one transfer (docs/1747-sn.md) ----------------

namespace buffer_check {

// The SLOT lines of examples/ladder/faults/block_transfer_buffers.slc with the given rungs.
std::string program_with(const std::string& rungs) {
  return "START 1747-L532\nSLOT 0 1747-L532 SCAN_IN 0 SCAN_OUT 0\n"
         "SLOT 1 1747-SN SCAN_IN 32 SCAN_OUT 32 G_FILE 3\n 0 17 255 OPTION baud=115.2K\n"
         "LADDER 2 MAIN\n" + rungs;
}

std::string check(const std::string& source) {
  LoadResult lr = load_program(source, "t.slc");
  EXPECT_TRUE(lr.ok()) << lr.render_diagnostics();
  DiagnosticList diags;
  check_module_configuration(*lr.program, diags);
  return render_all(diags, "t.slc", source);
}

}  // namespace buffer_check

TEST(BlockTransferCheck, ThirtyTwoTransfersOnThirtyTwoBuffersAreAccepted) {
  // Every BTR of the faults example: buffers 1-32, control blocks N10:0 ... N10:93.
  const std::string source = read_text(std::string(SOFTSLC_SOURCE_DIR) + "/examples/ladder/faults/block_transfer_buffers.slc");
  EXPECT_EQ(buffer_check::check(source), "");
}

TEST(BlockTransferCheck, AThirtyThirdTransferOnAnUsedBufferIsRefusedAtItsBufferOperand) {
  // 1747-SN p. 5-5/5-6: "A total of 32 block transfer buffers are available; you can execute a
  // maximum of 32 different block transfers"; "the next BT instruction must use another M-file
  // buffer (2 through 32)".
  std::string rungs;
  for (int k = 0; k < 32; ++k)
    rungs += "SOR XIC B3:0/0 BTR N10:" + std::to_string(3 * k) + " M1:1." + std::to_string((k + 1) * 100) + " #N11:" +
             std::to_string(k) + " " + std::to_string(k / 16) + " " + std::to_string(k % 16 / 2) + " " +
             std::to_string(k % 2) + " 1 EOR\n";
  rungs += "SOR XIC B3:0/0 BTW N10:96 M0:1.100 #N12:0 0 0 0 1 EOR\n";  // line 38, file 2 rung 32
  const std::string out = buffer_check::check(buffer_check::program_with(rungs));
  EXPECT_NE(out.find("t.slc:38:27: error: block-transfer buffer 1 of the 1747-SN in slot 1 (M0:1.100 and M1:1.100) is "
                     "already used by BTR N10:0 in file 2 rung 0 (line 6)"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("the scanner has 32 buffers, one per block transfer"), std::string::npos) << out;
}

TEST(BlockTransferCheck, TheSameControlBlockOnTheSameBufferIsTheSameTransfer) {
  // The same BTR written in two rungs (e.g. two subroutines) is one transfer, not two.
  EXPECT_EQ(buffer_check::check(buffer_check::program_with("SOR XIC B3:0/0 BTR N10:0 M1:1.100 #N11:0 0 0 0 1 EOR\n"
                                                           "SOR XIC B3:0/1 BTR N10:0 M1:1.100 #N11:0 0 0 0 1 EOR\n")),
            "");
}

TEST(BlockTransferCheck, BuffersOfDifferentScannersAreIndependent) {
  EXPECT_EQ(buffer_check::check("START 1747-L532\nSLOT 0 1747-L532 SCAN_IN 0 SCAN_OUT 0\n"
                                "SLOT 1 1747-SN SCAN_IN 32 SCAN_OUT 32 G_FILE 3\n 0 17 255\n"
                                "SLOT 2 1747-SN SCAN_IN 32 SCAN_OUT 32 G_FILE 3\n 0 17 255\n"
                                "LADDER 2 MAIN\n"
                                "SOR BTR N10:0 M1:1.100 #N11:0 0 0 0 1 EOR\n"
                                "SOR BTR N10:3 M1:2.100 #N11:1 0 0 0 1 EOR\n"),
            "");
}

}  // namespace
}  // namespace softslc::test
