// The MicroLogix 1100-1500 MSG on an MG element (issue 16; docs/semantics.md "The MicroLogix MSG"):
// the text form and its per-processor checks, the setup written into the MG element, the rung logic
// and status bits, messages between MicroLogix controllers and SLCs on the simulated DH-485 link,
// the message timeout, the error codes, and the execution times in the timing profiles.
//
// Manual facts used (docs/micrologix-msg-sources.md has them all):
// - the MG element, 25 words: 8 CHN, 9 NOD, 10 MTO, 11 (1100/1400) the bytes to read or write, 12 the
//   target file type, 13 TFN, 14 ELE, 16 control bits, 17 status bits (14 ST, 13 DN, 12 ER, 10 EW, 0 R:
//   1 = local), 18 ERR, 19 the seconds since the message started (1762-RM001C pp. 21-4, 21-6;
//   1766-RM001A pp. 399-400); "Each MSG instruction must use a unique Element in a MSG File" (p. 21-4);
// - the bits (1762-RM001C p. 21-15): EW set once the message is in a buffer waiting to be sent and
//   cleared at the target's ACK; ST set at the ACK, cleared when DN, ER or TO is set; DN and ER
//   cleared the next time the rung goes false to true; EN (the SLC's rule, RM 12-29) stays set until
//   the message is done and the rung false;
// - four buffers, and a queue that "can accommodate all MSG instructions in a ladder program"
//   (1762-RM001C p. 21-2): no WQ;
// - the timeout: "Timing begins when the false-to-true rung transition occurs", 0 = never (p. 21-12);
// - error codes (1766-RM001A p. 466; 1762-RM001C p. 21-21): 07h target does not respond, 10h
//   incorrect command parameters (the target has no such file), 16h the target address above the
//   maximum node address, 37h message timed out in the local processor;
// - elements per message, one-word elements 103 (1762-RM001C p. 21-12);
// - execution times: 1762-RM001C p. 21-3 Table 21.1 (1200: 20.0 us true, 6.0 us false; 1500: 17.0 us,
//   6.0 us), 1766-RM001A p. 398 (1400: 2.5670 us, 0.7310 us).
// Delivery: DH-485 at 19,200 baud, 11 bits a character, 16 framing bytes (EST; instructions/message_link.h).
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "load_errors.h"
#include "../vm/message_line.h"
#include "vm/profile_scan_time_model.h"
#include "vm/scantime.h"
#include "vm/timing_profile.h"

namespace softslc::test {
namespace {

std::string ml_program(std::string_view processor, std::string_view rungs) {
  return "START " + std::string(processor) + "\nLADDER 2\n" + std::string(rungs) + "\n";
}

// A leader (node 1) and a peer "B" (node 2) on one DH-485 link, each a full program text.
using Line = MessageLine;

// B's N10:0-9 exist (a rung that never runs names N10:9).
const std::string kTarget1100 = ml_program("Bul.1763", "SOR XIC B3:0/15 CLR N10:9 EOR");
// A reads five words of B's N10:0 into its own N7:0-4 while B3:0/0 is on.
constexpr std::string_view kRead = "SOR XIC B3:0/0 MSG MG11:0 READ 500CPU LOCAL 0 N7:0 5 2 N10:0 5 EOR";

TEST(MicroLogixMsg, EachControllerWithAnMgFileTakesTheForm) {
  for (const char* p : {"Bul.1763", "Bul.1762", "Bul.1766", "1764-LSP", "1764-LRP"})
    EXPECT_EQ(load_errors(ml_program(p, kRead)), "") << p;
  // The MicroLogix 1000 has no MG file (its MSG keeps an integer control block, 1761-6.3 p. 13-13;
  // tests/micrologix/ml1000_msg_test.cpp).
  const std::string ml1000 = load_errors(ml_program("Bul.1761", kRead));
  EXPECT_NE(ml1000.find("MSG with an MG element is the MicroLogix 1100-1500 form; the MicroLogix 1000 has no MG file"),
            std::string::npos)
      << ml1000;
  // The SLC form on a MicroLogix, and the MicroLogix form on an SLC, each name the other.
  const std::string slc_form =
      load_errors(ml_program("Bul.1766", "SOR XIC B3:0/0 MSG READ 500CPU LOCAL N9:0 14 1 N7:0 5 2 N10:0 5 EOR"));
  EXPECT_NE(slc_form.find("works on an MG message file element (1762-RM001C p. 21-3): MSG MG11:0 READ|WRITE"),
            std::string::npos)
      << slc_form;
  const std::string ml_form = load_errors(ml_program("1747-L532", kRead));
  EXPECT_NE(ml_form.find("with an MG element is the MicroLogix 1100-1500 form"), std::string::npos) << ml_form;
}

int count_errors(const std::string& diagnostics) {
  int n = 0;
  for (std::size_t at = diagnostics.find("error:"); at != std::string::npos; at = diagnostics.find("error:", at + 1)) ++n;
  return n;
}

// A MicroLogix MSG with an operand missing (no form of MSG takes 9) is held to the MicroLogix form:
// the one message lists its 10 operands, not the SLC form's 11 with a second error about the SLC.
// The same on an SLC 5/02, whose own form takes 8 (RM 12-5).
TEST(MicroLogixMsg, AWrongOperandCountListsTheProcessorsOwnForm) {
  const std::string ml = load_errors(ml_program("Bul.1763", "SOR XIC B3:0/0 MSG MG11:0 READ 500CPU LOCAL 0 N7:0 5 2 N10:0 EOR"));
  EXPECT_NE(ml.find("MSG takes 10 operands (message file, read/write,"), std::string::npos) << ml;
  EXPECT_NE(ml.find("found 9"), std::string::npos) << ml;
  EXPECT_EQ(ml.find("SLC 500 form"), std::string::npos) << ml;
  EXPECT_EQ(count_errors(ml), 1) << ml;
  const std::string slc502 = load_errors(ml_program("1747-L524", "SOR XIC B3:0/0 MSG READ 500CPU N7:0 EOR"));
  EXPECT_NE(slc502.find("MSG takes 8 operands"), std::string::npos) << slc502;
  EXPECT_EQ(count_errors(slc502), 1) << slc502;
}

TEST(MicroLogixMsg, CheckRefusesWhatTheChannelCannotSend) {
  struct Case {
    const char* processor;
    const char* rung;
    const char* error;
  };
  const Case cases[] = {
      // 1762-RM001C p. 21-4: one element per MSG.
      {"Bul.1763", "SOR MSG MG11:0 READ 500CPU LOCAL 0 N7:0 5 2 N10:0 5 EOR\nSOR MSG MG11:0 WRITE 500CPU LOCAL 0 N7:0 5 2 N10:0 5 EOR",
       "each MSG instruction must use a unique element in a MSG file (1762-RM001C p. 21-4)"},
      {"Bul.1763", "SOR MSG MG11:0.9 READ 500CPU LOCAL 0 N7:0 5 2 N10:0 5 EOR", "expected an MG file element such as MG11:0"},
      {"Bul.1763", "SOR MSG N7:0 READ 500CPU LOCAL 0 N7:0 5 2 N10:0 5 EOR", "expected an MG file element such as MG11:0"},
      // One message carries 103 one-word elements (1762-RM001C p. 21-12).
      {"Bul.1762", "SOR MSG MG11:0 READ 500CPU LOCAL 0 N7:0 104 2 N10:0 5 EOR", "size in elements 104 is out of range 1-103"},
      {"Bul.1762", "SOR MSG MG11:0 READ 500CPU LOCAL 0 T4:0 35 2 T4:0 5 EOR", "is 105 words; one message carries at most 103"},
      {"Bul.1762", "SOR MSG MG11:0 READ 500CPU LOCAL 0 N7:250 10 2 N10:0 5 EOR", "runs past the end of the file"},
      {"Bul.1762", "SOR MSG MG11:0 READ 500CPU LOCAL 0 N7:0 5 2 F8:0 5 EOR", "is not of the local data's file type"},
      {"Bul.1766", "SOR MSG MG11:0 READ 500CPU LOCAL 0 L9:0 5 2 L9:0 5 EOR", "MSG of L (long word) elements is not simulated"},
      // Channel 0 is DH-485 or DF1 full-duplex by its configuration, not in the program: a DF1 station address,
      // 0-254 (1766-RM001A p. 592); on DH-485 a node above 31 ends with 16h at run time (df1_test.cpp).
      {"Bul.1763", "SOR MSG MG11:0 READ 500CPU LOCAL 0 N7:0 5 255 N10:0 5 EOR", "target node 255 is out of range 0-254 on channel 0"},
      {"Bul.1763", "SOR MSG MG11:0 READ 500CPU REMOTE 0 N7:0 5 2 N10:0 5 EOR", "MSG REMOTE"},
      {"Bul.1763", "SOR MSG MG11:0 READ PLC5 LOCAL 0 N7:0 5 2 N10:0 5 EOR", "MSG PLC5 on DH-485"},
      // Channel 1: Ethernet on the 1100/1400, with an RI element where the node is (msg_ethernet_test.cpp),
      // the LRP's second port (lrp_channel1_test.cpp), none on the 1200.
      {"Bul.1766", "SOR MSG MG11:0 READ 500CPU LOCAL 1 N7:0 5 2 N10:0 5 EOR", "names its RI routing element where channel 0 names the target node"},
      {"Bul.1762", "SOR MSG MG11:0 READ 500CPU LOCAL 1 N7:0 5 2 N10:0 5 EOR", "its MSG channel is always 0"},
      {"Bul.1762", "SOR MSG MG11:0 READ 500CPU LOCAL 0 N7:0 5 2 N10:0 256 EOR", "message timeout 256 is out of range 0-255"},
  };
  for (const Case& c : cases) {
    const std::string e = load_errors(ml_program(c.processor, c.rung));
    EXPECT_NE(e.find(c.error), std::string::npos) << c.processor << " " << c.rung << "\n" << e;
  }
}

TEST(MicroLogixMsg, TheSetupIsWrittenIntoTheMgElement) {
  // 1762-RM001C p. 21-4 / 1766-RM001A pp. 399-401: CHN, NOD, MTO, the target file type (the PCCC code
  // of N, 89h, as the SLC block's), TFN, ELE; word 17 bit 0 R = 1 for a local message (p. 21-6); the
  // 1100's word 11 is the byte count, 5 words = 10 bytes (reserved, 0, on the 1200).
  for (const char* p : {"Bul.1763", "Bul.1762"}) {
    Plc plc(kRead, {}, "START " + std::string(p) + "\n");
    EXPECT_EQ(plc.i("MG11:0.CHN"), 0) << p;
    EXPECT_EQ(plc.i("MG11:0.NOD"), 2) << p;
    EXPECT_EQ(plc.i("MG11:0.MTO"), 5) << p;
    EXPECT_EQ(plc.i("MG11:0.12"), 0x89) << p;
    EXPECT_EQ(plc.i("MG11:0.TFN"), 10) << p;
    EXPECT_EQ(plc.i("MG11:0.ELE"), 0) << p;
    EXPECT_EQ(plc.i("MG11:0.17"), 1) << p;
    EXPECT_EQ(plc.i("MG11:0.11"), std::string(p) == "Bul.1763" ? 10 : 0) << p;
  }
}

TEST(MicroLogixMsg, AReadBetweenTwo1100sGoesThroughEnEwStDn) {
  Line line(ml_program("Bul.1763", kRead), kTarget1100);
  for (int i = 0; i < 5; ++i) line.setb("N10:" + std::to_string(i), 100 + i);
  line.run();
  line.set("B3:0/0", 1);
  ASSERT_EQ(line.a->scan(1), 1);
  // In a buffer and sent at the end of the scan, not yet acknowledged: EN and EW (p. 21-15).
  EXPECT_EQ(line.ai("MG11:0.16") & 0x8000, 0x8000);
  EXPECT_EQ(line.ai("MG11:0.17"), 0b0000'0100'0000'0001);  // EW, R
  ASSERT_TRUE(line.until("MG11:0/ST", 100 * kNsPerMs));
  EXPECT_FALSE(line.abit("MG11:0/EW"));  // cleared at the ACK
  EXPECT_FALSE(line.abit("MG11:0/DN"));
  ASSERT_TRUE(line.until("MG11:0/DN", 100 * kNsPerMs));
  EXPECT_FALSE(line.abit("MG11:0/ST"));  // cleared when DN is set
  EXPECT_FALSE(line.abit("MG11:0/ER"));
  EXPECT_EQ(line.ai("MG11:0.ERR"), 0);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(line.ai("N7:" + std::to_string(i)), 100 + i);
  // EN stays while the rung is true; a false rung clears it, and DN stays until the next
  // false-to-true transition, which clears it (p. 21-15).
  line.a->scan(2);
  EXPECT_TRUE(line.abit("MG11:0/EN"));
  line.set("B3:0/0", 0);
  line.a->scan(1);
  EXPECT_FALSE(line.abit("MG11:0/EN"));
  EXPECT_TRUE(line.abit("MG11:0/DN"));
  line.setb("N10:0", 7);
  line.set("B3:0/0", 1);
  line.a->scan(1);
  EXPECT_FALSE(line.abit("MG11:0/DN"));
  EXPECT_TRUE(line.abit("MG11:0/EN"));
  ASSERT_TRUE(line.until("MG11:0/DN", 100 * kNsPerMs));
  EXPECT_EQ(line.ai("N7:0"), 7);
}

TEST(MicroLogixMsg, AMicroLogixAndAnSlcMessageEachOtherOnDh485) {
  // A MicroLogix 1200 writes to an SLC 5/03 (node 2), which reads the 1200's N7 back.
  const std::string slc = program_text(
      "SOR XIC B3:0/0 MSG READ 500CPU LOCAL N9:0 14 1 N11:0 2 1 N7:0 5 EOR\nSOR XIC B3:0/15 CLR N10:9 EOR");
  Line line(ml_program("Bul.1762", "SOR XIC B3:0/0 MSG MG11:0 WRITE 500CPU LOCAL 0 N7:0 2 2 N10:3 5 EOR"), slc);
  line.set("N7:0", 1234);
  line.set("N7:1", -5);
  line.run();
  line.set("B3:0/0", 1);
  ASSERT_TRUE(line.until("MG11:0/DN", 100 * kNsPerMs));
  EXPECT_EQ(line.bi("N10:3"), 1234);
  EXPECT_EQ(line.bi("N10:4"), -5);
  line.setb("B3:0/0", 1);
  ASSERT_TRUE(line.a->run_until([&](const Runtime&) { return line.b->value("N9:0/13").as_bool(); }, 100 * kNsPerMs));
  EXPECT_EQ(line.bi("N11:0"), 1234);
  EXPECT_EQ(line.bi("N11:1"), -5);
}

TEST(MicroLogixMsg, ANodeNobodyHasEndsWithErAnd07h) {
  // 07h "target node does not respond" (1766-RM001A p. 466), after the request's frame time on DH-485.
  Line line(ml_program("Bul.1763", "SOR XIC B3:0/0 MSG MG11:0 READ 500CPU LOCAL 0 N7:0 1 5 N10:0 5 EOR"), kTarget1100);
  line.run();
  line.set("B3:0/0", 1);
  ASSERT_TRUE(line.until("MG11:0/ER", 100 * kNsPerMs));
  EXPECT_EQ(line.ai("MG11:0.ERR"), 0x07);
  EXPECT_FALSE(line.abit("MG11:0/DN"));
  EXPECT_FALSE(line.abit("MG11:0/ST"));
  // NOD is read/write (p. 21-4): the program sends the next message to node 2, which answers; the
  // false-to-true transition clears ER and the code (p. 21-15).
  line.set("MG11:0.NOD", 2);
  line.set("B3:0/0", 0);
  line.a->scan(1);
  line.set("B3:0/0", 1);
  line.a->scan(1);
  EXPECT_FALSE(line.abit("MG11:0/ER"));
  EXPECT_EQ(line.ai("MG11:0.ERR"), 0);
  ASSERT_TRUE(line.until("MG11:0/DN", 100 * kNsPerMs));
}

TEST(MicroLogixMsg, TheTargetsErrorsComeBackAsTheManualsCodes) {
  Line line(ml_program("Bul.1763", "SOR XIC B3:0/0 MSG MG11:0 READ 500CPU LOCAL 0 N7:0 1 2 N10:0 5 EOR"), kTarget1100);
  line.run();
  // 10h: "incorrect command parameters or unsupported command" — the target has no N20 (TFN is read/write).
  line.set("MG11:0.TFN", 20);
  line.set("B3:0/0", 1);
  ASSERT_TRUE(line.until("MG11:0/ER", 100 * kNsPerMs));
  EXPECT_EQ(line.ai("MG11:0.ERR"), 0x10);
  // 16h: a target node above DH-485's maximum, found when the message starts.
  line.set("B3:0/0", 0);
  line.a->scan(1);
  line.set("MG11:0.TFN", 10);
  line.set("MG11:0.NOD", 40);
  line.set("B3:0/0", 1);
  line.a->scan(1);
  EXPECT_TRUE(line.abit("MG11:0/ER"));
  EXPECT_EQ(line.ai("MG11:0.ERR"), 0x16);
}

TEST(MicroLogixMsg, TheMessageTimeoutEndsAMessageTheTargetDoesNotAnswer) {
  // The target's scans take 3 s, so it answers at its end of scan, after the 1 s timeout: ER and
  // 37h "message timed out in local processor" (1766-RM001A p. 466), the timer running from the rung's
  // false-to-true transition (1762-RM001C p. 21-12); MTO 1 stays 1 s on the MicroLogix.
  Line line(ml_program("Bul.1763", "SOR XIC B3:0/0 MSG MG11:0 READ 500CPU LOCAL 0 N7:0 1 2 N10:0 1 EOR"), kTarget1100, {},
            slow_target("Bul.1763"));
  line.run();
  line.a->scan(1);
  const VirtualTime start = line.a->now();
  line.set("B3:0/0", 1);
  ASSERT_TRUE(line.until("MG11:0/ER", 2 * kNsPerS));
  EXPECT_GE(line.a->now() - start, kNsPerS);
  EXPECT_LT(line.a->now() - start, kNsPerS + 10 * kNsPerMs);
  EXPECT_EQ(line.ai("MG11:0.ERR"), 0x37);
  EXPECT_TRUE(line.abit("MG11:0/TO"));  // with ER, as on the SLC (decision, docs/semantics.md)
  EXPECT_EQ(line.ai("MG11:0.19"), 1);  // the seconds since the message started
  EXPECT_FALSE(line.abit("MG11:0/DN"));
  // The late reply changes nothing.
  line.a->run_for(4 * kNsPerS);
  EXPECT_FALSE(line.abit("MG11:0/DN"));
  EXPECT_EQ(line.ai("MG11:0.ERR"), 0x37);
}

TEST(MicroLogixMsg, TheProgramAbortsAMessageWithTo) {
  // Setting TO (a read/write control bit, p. 21-4) errors the message in progress the next time the
  // MSG is scanned (RM 12-30, the SLC's rule; docs/semantics.md): ER and 37h.
  Line line(ml_program("Bul.1763", "SOR XIC B3:0/0 MSG MG11:0 READ 500CPU LOCAL 0 N7:0 1 2 N10:0 0 EOR"), kTarget1100, {},
            slow_target("Bul.1763"));
  line.run();
  line.set("B3:0/0", 1);
  line.a->scan(3);
  EXPECT_TRUE(line.abit("MG11:0/EN"));
  EXPECT_FALSE(line.abit("MG11:0/ER"));  // MTO 0: no timeout
  line.set("MG11:0/TO", 1);
  line.a->scan(1);
  EXPECT_TRUE(line.abit("MG11:0/ER"));
  EXPECT_EQ(line.ai("MG11:0.ERR"), 0x37);
}

TEST(MicroLogixMsg, FourBuffersThenTheQueueAndNoWq) {
  // Six MSGs start in one scan: four take the buffers (EN and EW), two wait in the queue with EN only
  // (1762-RM001C p. 21-2: the queue holds every MSG of the program).
  std::string rungs;
  for (int i = 0; i < 6; ++i)
    rungs += "SOR XIC B3:0/0 MSG MG11:" + std::to_string(i) + " READ 500CPU LOCAL 0 N7:" + std::to_string(i) +
             " 1 2 N10:" + std::to_string(i) + " 5 EOR\n";
  Line line(ml_program("Bul.1763", rungs), kTarget1100);
  line.run();
  line.a->scan(1);
  line.set("B3:0/0", 1);
  line.a->scan(1);  // its end-of-scan servicing sends the four; the queue waits for a free buffer
  for (int i = 0; i < 6; ++i) {
    const std::string e = "MG11:" + std::to_string(i);
    EXPECT_TRUE(line.abit(e + "/EN")) << e;
    EXPECT_EQ(line.abit(e + "/EW"), i < 4) << e;
  }
  for (int i = 0; i < 6; ++i)
    ASSERT_TRUE(line.until("MG11:" + std::to_string(i) + "/DN", 200 * kNsPerMs)) << i;
}

TEST(MicroLogixMsg, ProfilesPriceTheManualsFigures) {
  struct Figure {
    const char* processor;
    Nanoseconds true_ns, false_ns;
    bool estimate;
  };
  const Figure figures[] = {
      {"Bul.1762", 20'000, 6'000, false}, {"1764-LSP", 17'000, 6'000, false}, {"1764-LRP", 17'000, 6'000, false},
      {"Bul.1766", 2'567, 731, false},    {"Bul.1763", 2'567, 731, true},  // the 1100's table was not reached
  };
  for (const Figure& f : figures) {
    LoadResult r = load_program(ml_program(f.processor, kRead), "t.slc");
    ASSERT_TRUE(r.ok()) << r.render_diagnostics();
    auto profile = builtin_timing_profile(r.program->processor.timing_key());
    ASSERT_TRUE(profile.has_value()) << f.processor;
    const InstructionTiming& t = profile->instruction(Opcode::MSG_ML);
    EXPECT_EQ(t.true_ns, f.true_ns) << f.processor;
    EXPECT_EQ(t.false_ns, f.false_ns) << f.processor;
    EXPECT_EQ(profile->is_estimate(t.source), f.estimate) << f.processor;
  }
}

// The scan where a MSG's rung goes false to true costs the manual's "false-to-true transition" figure
// instead of the steady-state true one; the scans after it the steady-state figure again. 1762-RM001C
// p. 21-3 Table 21.1: MicroLogix 1200 reads 230.0 us, writes 264 us + 1.6 us per word, steady state true
// 20.0 us; 1500 reads 198.0 us, writes 226 us + 1.4 us per word, true 17.0 us. 1766-RM001A p. 398:
// MicroLogix 1400 reads 48.1677 us, writes 58.8510 us, true 2.5670 us. Five one-word elements: the
// 1200's write is 264 + 5 x 1.6 = 272 us, the 1500's 226 + 5 x 1.4 = 233 us.
TEST(MicroLogixMsg, TheFalseToTrueScanCostsTheTransitionFigure) {
  struct Figure {
    const char* processor;
    const char* command;
    Nanoseconds transition_ns, true_ns;
  };
  const Figure figures[] = {
      {"Bul.1762", "READ", 230'000, 20'000}, {"Bul.1762", "WRITE", 272'000, 20'000},
      {"1764-LSP", "READ", 198'000, 17'000}, {"1764-LRP", "WRITE", 233'000, 17'000},
      {"Bul.1766", "READ", 48'168, 2'567},   {"Bul.1766", "WRITE", 58'851, 2'567},
  };
  for (const Figure& f : figures) {
    Plc plc("SOR XIC B3:0/0 MSG MG11:0 " + std::string(f.command) + " 500CPU LOCAL 0 N7:0 5 2 N10:0 5 EOR", {},
            "START " + std::string(f.processor) + "\n");
    plc.run_scans(2);
    auto scan_ns = [&] {
      const VirtualTime t = plc->now();
      plc->scan(1);
      return plc->now() - t;
    };
    const Nanoseconds rung_false = scan_ns();
    plc.set("B3:0/0", 1);
    const Nanoseconds transition = scan_ns();
    const Nanoseconds steady = scan_ns();
    EXPECT_EQ(transition - steady, f.transition_ns - f.true_ns) << f.processor << " " << f.command;
    EXPECT_GT(steady, rung_false) << f.processor;  // true costs more than false on every profile
  }
}

}  // namespace
}  // namespace softslc::test
