// The MicroLogix 1000 MSG (issue 16; docs/semantics.md "The MicroLogix 1000 MSG"): the 7-word integer
// control block form and what `check` refuses on the 1000, and the message's life on the simulated
// DH-485 link with SLCs and other MicroLogix 1000s: the control bits, the one transmit buffer, TO, the
// error codes and the common interface file.
//
// Manual facts used (docs/micrologix-msg-sources.md section 7 has them all):
// - the instruction: "Read/write READ, Target Device SLC500/ML1000, Control Block N7:50, Control Block
//   Length 7" (1761-6.3 p. 13-13, example 2); command types SLC500/ML1000 and CIF, READ or WRITE; a CIF
//   message reaches N7 of a MicroLogix 1000 and N9 of an SLC 500; a PLC-5 only with CIF over DF1
//   full-duplex (1761-6.2 p. 15-3);
// - the control word: EN 15, ST 14, DN 13, ER 12, EW 10, NR 09, TO 08, the error code in the low byte
//   (1761-6.2 p. 15-3; 1761-6.3 p. 13-6, 13-10);
// - 1761-6.3 p. 13-6: TO "has no effect unless the ST bit has first been set due to receiving an ACK",
//   it errors the message out with code 37; EW "is set on any false-to-true MSG rung transition ...
//   reset when an ACK or NAK ... is received, or on any true-to-false MSG rung transition"; ER and DN
//   reset the next time the rung goes from false to true;
// - 1761-6.3 p. 13-8: "If the transmit buffer is not available, the EN flag remains false (0). When rung
//   conditions go true and the transmit buffer becomes available, the EN flag goes true (1)";
// - 1761-6.2 p. 15-5: ST "is set when the processor receives acknowledgement from the target device ...
//   reset when the DN, ER, or TO bit is set"; EN "remains set until the next false rung execution after
//   the MSG completes (DN bit set) or an error occurs (ER bit set)";
// - 1761-6.3 p. 13-10: at the end of the scan after the reply DN (or ER) is set and ST cleared, a read's
//   data written to the data table;
// - error codes (1761-6.3 p. 13-11): 07h "Target node does not respond", 10h "Target node cannot respond
//   because of incorrect command parameters or unsupported command", 18h "Broadcast (Node Address 255)
//   is not supported", 37h "Message timed out in local processor".
// Delivery: DH-485 at 19,200 baud, 11 bits a character, 16 framing bytes (EST; instructions/message_link.h).
#include <gtest/gtest.h>

#include <string>

#include "load_errors.h"
#include "../vm/message_line.h"
#include "vm/timing_profile.h"

namespace softslc::test {
namespace {

std::string ml1000(std::string_view rungs) { return "START Bul.1761\nLADDER 2\n" + std::string(rungs) + "\n"; }

struct Line : MessageLine {
  using MessageLine::MessageLine;
  // A control word as its 16 bits (EN, bit 15, is the sign bit of the N word).
  std::int64_t bits(std::string_view addr) const { return ai(addr) & 0xFFFF; }
};

// B, an SLC 5/03 at node 2, whose N10:0-9 exist (a rung that never runs names N10:9).
const std::string kSlcTarget = program_text("SOR XIC B3:0/15 CLR N10:9 EOR");
// A reads five words of B's N10:0 into its own N7:0-4 while B3:0/0 is on; the control block is N7:50
// (1761-6.3 p. 13-13's example).
constexpr std::string_view kRead = "SOR XIC B3:0/0 MSG READ 500CPU N7:50 7 N7:0 5 2 N10:0 EOR";

// The control word's bits (1761-6.2 p. 15-3).
constexpr std::int64_t kEN = 1 << 15, kST = 1 << 14, kDN = 1 << 13, kER = 1 << 12, kEW = 1 << 10, kTO = 1 << 8;

TEST(MicroLogix1000Msg, TheSevenWordControlBlockFormLoads) {
  EXPECT_EQ(load_errors(ml1000(kRead)), "");
  EXPECT_EQ(load_errors(ml1000("SOR XIC B3:0/0 MSG WRITE 485CIF N7:50 7 N7:0 5 2 3 EOR")), "");
  // The 1100-1500 form on an MG element, and the SLC 5/03-5/05 form, each name the 1000's own form.
  const std::string mg = load_errors(ml1000("SOR XIC B3:0/0 MSG MG11:0 READ 500CPU LOCAL 0 N7:0 5 2 N10:0 5 EOR"));
  EXPECT_NE(mg.find("the MicroLogix 1000 has no MG file: its MSG keeps a 7-word integer control block "
                    "(1761-6.3 p. 13-13)"),
            std::string::npos)
      << mg;
  const std::string slc = load_errors(ml1000("SOR XIC B3:0/0 MSG READ 500CPU LOCAL N7:50 14 1 N7:0 5 2 N10:0 5 EOR"));
  EXPECT_NE(slc.find("the MicroLogix 1000 MSG keeps a 7-word integer control block (1761-6.3 p. 13-13): MSG "
                     "READ|WRITE 500CPU|485CIF N7:50 7"),
            std::string::npos)
      << slc;
}

TEST(MicroLogix1000Msg, CheckRefusesWhatTheMl1000DoesNotHave) {
  struct Case {
    const char* rung;
    const char* error;
  };
  const Case cases[] = {
      // 1761-6.2 p. 15-3: SLC500/ML1000 and CIF; a PLC-5 only with CIF over DF1 full-duplex.
      {"SOR MSG READ PLC5 N7:50 7 N7:0 5 2 N10:0 EOR", "MSG PLC5: the MicroLogix 1000's command types are SLC500/ML1000"},
      // 1761-6.3 p. 13-13: the control block is 7 words.
      {"SOR MSG READ 500CPU N7:50 14 N7:0 5 2 N10:0 EOR", "1761-6.3 p. 13-13: \"Control Block Length 7\""},
      // Channel 0 is DH-485 or DF1 full-duplex by its configuration, not in the program: DF1 station addresses
      // are 0-254 (AG-UM008C p. 6-14 table 6.2: "Valid range is 0 to 254"); on DH-485 a node above 31 does not
      // respond (07h at run time, df1_test.cpp).
      {"SOR MSG READ 500CPU N7:50 7 N7:0 5 255 N10:0 EOR", "target node 255 is out of range 0-254"},
      // The control block is an integer file element, and one per MSG.
      {"SOR MSG READ 500CPU B3:0 7 N7:0 5 2 N10:0 EOR", "expected an integer file element such as N9:0"},
      {"SOR MSG READ 500CPU N7:50 7 N7:0 5 2 N10:0 EOR\nSOR MSG WRITE 500CPU N7:53 7 N7:0 5 2 N10:0 EOR",
       "overlaps the one of the MSG at line"},
      // The target address is of the local data's type (one file type code in the block).
      {"SOR MSG READ 500CPU N7:50 7 N7:0 5 2 B3:0 EOR", "is not of the local data's file type"},
      // The 1000 has no SVC.
      {"SOR SVC EOR", "the project's sources (1761-6.3) give the MicroLogix 1000 no SVC"},
  };
  for (const Case& c : cases) {
    const std::string e = load_errors(ml1000(c.rung));
    EXPECT_NE(e.find(c.error), std::string::npos) << c.rung << "\n" << e;
  }
}

// The setup goes into the control block as on the SLC 5/02 (docs/semantics.md "MSG"): word 1 the node,
// 2 the elements, 3 the target file, 4 the file type code (89h for N), 5 the target element.
TEST(MicroLogix1000Msg, TheSetupIsWrittenIntoTheControlBlock) {
  Plc plc(kRead, {}, "START Bul.1761\n");
  EXPECT_EQ(plc.i("N7:51"), 2);
  EXPECT_EQ(plc.i("N7:52"), 5);
  EXPECT_EQ(plc.i("N7:53"), 10);
  EXPECT_EQ(plc.i("N7:54"), 0x89);
  EXPECT_EQ(plc.i("N7:55"), 0);
}

TEST(MicroLogix1000Msg, AReadFromAnSlcGoesThroughEnEwStDn) {
  Line line(ml1000(kRead), kSlcTarget);
  for (int i = 0; i < 5; ++i) line.setb("N10:" + std::to_string(i), 200 + i);
  line.run();
  line.set("B3:0/0", 1);
  ASSERT_EQ(line.a->scan(1), 1);
  // The rung went true with the transmit buffer free: EN and EW (1761-6.3 p. 13-8), nothing else.
  EXPECT_EQ(line.bits("N7:50"), kEN | kEW);
  ASSERT_TRUE(line.until("N7:50/14", 100 * kNsPerMs));
  // The ACK sets ST and resets EW (p. 13-6; 1761-6.2 p. 15-5).
  EXPECT_EQ(line.bits("N7:50"), kEN | kST);
  ASSERT_TRUE(line.until("N7:50/13", 100 * kNsPerMs));
  // The reply: DN set, ST cleared, the data in the table (p. 13-10).
  EXPECT_EQ(line.bits("N7:50"), kEN | kDN);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(line.ai("N7:" + std::to_string(i)), 200 + i);
  // EN stays while the rung is true and clears on the next false rung execution (1761-6.2 p. 15-5);
  // DN stays until the next false-to-true transition, which resets it (p. 13-6).
  line.a->scan(2);
  EXPECT_EQ(line.bits("N7:50"), kEN | kDN);
  line.set("B3:0/0", 0);
  line.a->scan(1);
  EXPECT_EQ(line.bits("N7:50"), kDN);
  line.setb("N10:0", -7);
  line.set("B3:0/0", 1);
  line.a->scan(1);
  EXPECT_EQ(line.bits("N7:50"), kEN | kEW);
  ASSERT_TRUE(line.until("N7:50/13", 100 * kNsPerMs));
  EXPECT_EQ(line.ai("N7:0"), -7);
}

TEST(MicroLogix1000Msg, EwResetsOnATrueToFalseRungAndTheMessageGoesOn) {
  // p. 13-6: EW is reset "on any true-to-false MSG rung transition"; the message, in the buffer, is
  // sent and completes; EN, set, clears at the first false rung execution after DN.
  Line line(ml1000(kRead), kSlcTarget);
  line.setb("N10:0", 42);
  line.run();
  line.set("B3:0/0", 1);
  line.a->scan(1);
  EXPECT_EQ(line.bits("N7:50"), kEN | kEW);
  line.set("B3:0/0", 0);
  line.a->scan(1);  // a scan is far shorter than the 9 ms request: not yet acknowledged
  EXPECT_EQ(line.bits("N7:50"), kEN);
  ASSERT_TRUE(line.until("N7:50/13", 100 * kNsPerMs));
  EXPECT_EQ(line.ai("N7:0"), 42);
  line.a->scan(1);
  EXPECT_EQ(line.bits("N7:50"), kDN);
}

TEST(MicroLogix1000Msg, OneTransmitBufferAndNoQueue) {
  // Two MSGs go true in one scan: the first takes the transmit buffer (EN, EW), the second has EW only,
  // EN false until the buffer is free (p. 13-8); its rung still true, it starts once the first is done.
  Line line(ml1000("SOR XIC B3:0/0 MSG READ 500CPU N7:50 7 N7:0 1 2 N10:0 EOR\n"
                   "SOR XIC B3:0/1 MSG READ 500CPU N7:60 7 N7:1 1 2 N10:1 EOR"),
            kSlcTarget);
  line.setb("N10:0", 11);
  line.setb("N10:1", 22);
  line.run();
  line.set("B3:0/0", 1);
  line.set("B3:0/1", 1);
  line.a->scan(1);
  EXPECT_EQ(line.bits("N7:50"), kEN | kEW);
  EXPECT_EQ(line.bits("N7:60"), kEW);
  ASSERT_TRUE(line.until("N7:50/13", 100 * kNsPerMs));
  EXPECT_EQ(line.ai("N7:1"), 0);  // the second has not been sent
  ASSERT_TRUE(line.until("N7:60/13", 100 * kNsPerMs));
  EXPECT_EQ(line.ai("N7:0"), 11);
  EXPECT_EQ(line.ai("N7:1"), 22);
  // A MSG whose rung goes false while it waits for the buffer loses EW (p. 13-6) and is never sent:
  // there is no queue to hold it.
  line.set("B3:0/0", 0);
  line.set("B3:0/1", 0);
  line.a->scan(1);
  line.setb("N10:1", 33);
  line.set("B3:0/0", 1);
  line.set("B3:0/1", 1);
  line.a->scan(1);
  EXPECT_EQ(line.bits("N7:60"), kEW);
  line.set("B3:0/1", 0);
  line.a->scan(1);
  EXPECT_EQ(line.bits("N7:60"), 0);
  ASSERT_TRUE(line.until("N7:50/13", 100 * kNsPerMs));
  line.a->run_for(100 * kNsPerMs);
  EXPECT_EQ(line.bits("N7:60"), 0);
  EXPECT_EQ(line.ai("N7:1"), 22);
}

TEST(MicroLogix1000Msg, ToErrorsOutOnlyAStartedMessage) {
  // B's scans take 3 s: it acknowledges a request when the frame arrives but replies only at its end of
  // scan, so ST stays set for seconds. The 1000 has no message timer: "Your application must supply its
  // own timer" (p. 13-6).
  Line line(ml1000(kRead), kSlcTarget, {}, slow_target("1747-L532"));
  line.run();
  line.set("B3:0/0", 1);
  line.a->scan(1);
  // TO before the ACK "has no effect unless the ST bit has first been set" (p. 13-6).
  line.set("N7:50/8", 1);
  line.a->scan(1);
  EXPECT_EQ(line.bits("N7:50"), kEN | kEW | kTO);
  ASSERT_TRUE(line.until("N7:50/14", 100 * kNsPerMs));
  EXPECT_FALSE(line.abit("N7:50/12"));
  // Once ST is set, TO errors the message out with 37h at the next scan of the MSG (p. 13-6, 13-11).
  line.a->scan(1);
  EXPECT_EQ(line.bits("N7:50"), kEN | kER | kTO | 0x37);
  // Without TO a started message waits for B's reply however long it takes: no timer ends it.
  line.set("B3:0/0", 0);
  line.a->scan(1);
  line.set("B3:0/0", 1);
  line.a->scan(1);
  EXPECT_EQ(line.bits("N7:50") & (kER | kTO | 0xFF), 0);  // the false-to-true transition reset TO, ER, the code
  ASSERT_TRUE(line.until("N7:50/13", 7 * kNsPerS));
  EXPECT_FALSE(line.abit("N7:50/12"));
}

TEST(MicroLogix1000Msg, ErrorCodesAsTheManualLists) {
  Line line(ml1000("SOR XIC B3:0/0 MSG READ 500CPU N7:50 7 N7:0 1 2 N10:0 EOR"), kSlcTarget);
  line.run();
  auto restart = [&] {
    line.set("B3:0/0", 0);
    line.a->scan(1);
    line.set("B3:0/0", 1);
    line.a->scan(1);
  };
  // 07h "Target node does not respond" (p. 13-11): no station at node 5 (word 1, the node, is the
  // program's to write), after the request's frame time. No ACK: ST never set.
  line.set("N7:51", 5);
  line.set("B3:0/0", 1);
  line.a->scan(1);
  ASSERT_TRUE(line.until("N7:50/12", 100 * kNsPerMs));
  EXPECT_EQ(line.bits("N7:50"), kEN | kER | 0x07);
  // 18h "Broadcast (Node Address 255) is not supported" (p. 13-11), found when the message starts.
  line.set("N7:51", 255);
  restart();
  EXPECT_EQ(line.bits("N7:50"), kEN | kER | 0x18);
  // The 1000's table has no 16h (the 1100-1500's "above the maximum node address"): node 40 is a node
  // no station answers, 07h (decision, docs/semantics.md "The MicroLogix 1000 MSG").
  line.set("N7:51", 40);
  restart();
  ASSERT_TRUE(line.until("N7:50/12", 100 * kNsPerMs));
  EXPECT_EQ(line.bits("N7:50") & 0xFF, 0x07);
  // 10h "incorrect command parameters or unsupported command" (p. 13-11): B has no N20.
  line.set("N7:51", 2);
  line.set("N7:53", 20);
  restart();
  ASSERT_TRUE(line.until("N7:50/12", 100 * kNsPerMs));
  EXPECT_EQ(line.bits("N7:50"), kEN | kER | 0x10);
  // The false-to-true transition resets ER and the code (p. 13-6); B's N10 answers.
  line.set("N7:53", 10);
  restart();
  EXPECT_EQ(line.bits("N7:50") & (kER | 0xFF), 0);
  ASSERT_TRUE(line.until("N7:50/13", 100 * kNsPerMs));
}

// 1761-6.2 p. 15-3 note 4: "SLC 500, SLC 5/01, and SLC 5/02 processors do not support O or I file access
// from a MSG instruction. SLC 5/03, SLC 5/04 and SLC 5/05 processors do support O and I file access, but
// only when unprotected." softslc has no file protection: a 5/03 answers; the fixed controller, the 5/01
// and the 5/02 end the message with 10h, "incorrect command parameters or unsupported command" (p. 13-11;
// note 4 gives no code: decision [U], docs/semantics.md "The MicroLogix 1000 MSG"). Their N files answer.
TEST(MicroLogix1000Msg, OAndIFilesOfAnSlcAnswerOnlyOnThe503AndLater) {
  // softslc's MSG takes an O or I target's element as the word offset into the target's image (O:0 is the
  // first output word, here slot 2's on the modular chassis); the note's rule is what this test is about.
  struct Target {
    const char* catalog;
    const char* header;
    const char* first_output;  // the target's first output word, as the target's program names it
    bool answers;
  };
  const Target targets[] = {
      // The fixed controller with I/O in its expansion chassis (softslc has no model of its embedded I/O).
      {"1747-L20", "START 1747-L20\nSLOT 1 1746-IB16 SCAN_IN 1 SCAN_OUT 0\nSLOT 2 1746-OB16 SCAN_IN 0 SCAN_OUT 1\n", "O:2.0",
       false},
      {"1747-L511", "START 1747-L511\nSLOT 1 1746-IB16 SCAN_IN 1 SCAN_OUT 0\nSLOT 2 1746-OB16 SCAN_IN 0 SCAN_OUT 1\n", "O:2.0",
       false},
      {"1747-L524", "START 1747-L524\nSLOT 1 1746-IB16 SCAN_IN 1 SCAN_OUT 0\nSLOT 2 1746-OB16 SCAN_IN 0 SCAN_OUT 1\n", "O:2.0",
       false},
      {"1747-L532", kHeader.data(), "O:2.0", true},
  };
  for (const Target& t : targets) {
    const std::string rungs = std::string("SOR XIC B3:0/0 MSG READ 500CPU N7:50 7 O:0 1 2 O:0 EOR\n") +
                              "SOR XIC B3:0/1 MSG READ 500CPU N7:60 7 I:0 1 2 I:0 EOR\n" +
                              "SOR XIC B3:0/2 MSG READ 500CPU N7:70 7 N7:0 1 2 N10:0 EOR";
    Line line(ml1000(rungs), program_text("SOR XIC B3:0/15 CLR N10:9 EOR", t.header));
    line.setb(t.first_output, 0x55);
    line.setb("N10:0", 9);
    line.run();
    line.set("B3:0/0", 1);
    line.set("B3:0/1", 1);
    line.set("B3:0/2", 1);
    ASSERT_TRUE(line.until("N7:70/13", 100 * kNsPerMs)) << t.catalog;
    ASSERT_TRUE(line.a->run_until(
        [](const Runtime& r) { return (r.value("N7:50").as_int() & (kDN | kER)) && (r.value("N7:60").as_int() & (kDN | kER)); },
        100 * kNsPerMs))
        << t.catalog;
    EXPECT_EQ(line.ai("N7:0"), 9) << t.catalog << ": its N files answer";
    if (t.answers) {
      EXPECT_EQ(line.bits("N7:50") & (kDN | kER | 0xFF), kDN) << t.catalog;
      EXPECT_EQ(line.bits("N7:60") & (kDN | kER | 0xFF), kDN) << t.catalog;
      EXPECT_EQ(line.ai("O:0"), 0x55) << t.catalog;
    } else {
      EXPECT_EQ(line.bits("N7:50") & (kDN | kER | 0xFF), kER | 0x10) << t.catalog;
      EXPECT_EQ(line.bits("N7:60") & (kDN | kER | 0xFF), kER | 0x10) << t.catalog;
    }
  }
}

TEST(MicroLogix1000Msg, CifReachesN7OfAnMl1000AndN9OfAnSlc) {
  // 1761-6.2 p. 15-3: a CIF message to a MicroLogix 1000 reaches its N7, to an SLC 500 its N9; the
  // target's file, at the word offset given.
  struct Target {
    std::string program;
    const char* first;  // the word the offset 3 lands on
    const char* second;
  };
  const Target targets[] = {{ml1000("SOR XIC B3:0/15 CLR N7:9 EOR"), "N7:3", "N7:4"},
                            {program_text("SOR XIC B3:0/15 CLR N9:9 EOR"), "N9:3", "N9:4"}};
  for (const Target& t : targets) {
    Line line(ml1000("SOR XIC B3:0/0 MSG WRITE 485CIF N7:50 7 N7:0 2 2 3 EOR"), t.program);
    line.set("N7:0", 1000);
    line.set("N7:1", -1000);
    line.run();
    line.set("B3:0/0", 1);
    ASSERT_TRUE(line.until("N7:50/13", 100 * kNsPerMs)) << t.first;
    EXPECT_EQ(line.bi(t.first), 1000);
    EXPECT_EQ(line.bi(t.second), -1000);
  }
  // An SLC 5/03's 485CIF read of a MicroLogix 1000 reads the 1000's N7.
  {
    Line line(program_text("SOR XIC B3:0/0 MSG READ 485CIF LOCAL N9:0 14 1 N11:0 2 2 5 5 EOR"),
              ml1000("SOR XIC B3:0/15 CLR N7:9 EOR"));
    line.setb("N7:5", 77);
    line.setb("N7:6", 78);
    line.run();
    line.set("B3:0/0", 1);
    ASSERT_TRUE(line.until("N9:0/13", 100 * kNsPerMs));
    EXPECT_EQ(line.ai("N11:0"), 77);
    EXPECT_EQ(line.ai("N11:1"), 78);
  }
}

TEST(MicroLogix1000Msg, TwoMl1000sReadAndWriteEachOther) {
  // SLC500/ML1000 between two MicroLogix 1000s (1761-6.2 p. 15-3: O, I, S, B, T, C, R, N either way):
  // A writes its B3:1 into B's B3:2, then reads B's T4:0 (three words an element; an RTO, whose false
  // rung keeps the accumulator).
  Line line(ml1000("SOR XIC B3:0/0 MSG WRITE 500CPU N7:50 7 B3:1 1 2 B3:2 EOR\n"
                   "SOR XIC B3:0/1 MSG READ 500CPU N7:60 7 T4:1 1 2 T4:0 EOR"),
            ml1000("SOR XIC B3:0/15 CLR B3:2 EOR\nSOR XIC B3:0/15 RTO T4:0 1.0 400 0 EOR"));
  line.set("B3:1", 0x1234);
  line.setb("T4:0.PRE", 321);
  line.setb("T4:0.ACC", 5);
  line.run();
  line.set("B3:0/0", 1);
  ASSERT_TRUE(line.until("N7:50/13", 100 * kNsPerMs));
  EXPECT_EQ(line.b->value("B3:2").as_int(), 0x1234);
  line.set("B3:0/1", 1);
  ASSERT_TRUE(line.until("N7:60/13", 100 * kNsPerMs));
  EXPECT_EQ(line.ai("T4:1.PRE"), 321);
  EXPECT_EQ(line.ai("T4:1.ACC"), 5);
}

TEST(MicroLogix1000Msg, TheProfileMarksItsMsgRowAnEstimate) {
  // No MSG execution time for the 1000 is in the project's sources (1761-6.3 appendix B was not reached
  // for it): its row is the EST base table's (the SLC 5/03's 60 / 8 us scaled by 3.5, docs/timing.md).
  auto profile = builtin_timing_profile("ML1000");
  ASSERT_TRUE(profile.has_value());
  const InstructionTiming& t = profile->instruction(Opcode::MSG_502);
  EXPECT_EQ(t.true_ns, 210'000);
  EXPECT_EQ(t.false_ns, 28'000);
  EXPECT_TRUE(profile->is_estimate(t.source));
}

}  // namespace
}  // namespace softslc::test
