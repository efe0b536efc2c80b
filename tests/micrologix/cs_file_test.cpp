// The communications status files CS0, CS1, CS2 of the MicroLogix 1100-1500 (issue 16; docs/semantics.md
// "The CS file"): the addresses as the manuals write them, what the checker refuses, and the one bit softslc
// keeps, CS0:4/MCP, in the manual's conditional SVC.
//
// Manual facts used:
// - 1762-RM001C p. 21-27 Table 21.5 "Communication Status Bits": CS0:4/0 ICP, CS0:4/1 MRP, CS0:4/2 MCP
//   "Outgoing Message Command Pending", CS0:4/4 CAB; "CS0:4/MCP is set when the message instruction is
//   enabled and put in the communications queue. When CS0:4/MCP is set (1), the SVC instruction is evaluated
//   as true and the program scan is interrupted to execute the service communication's portion of the
//   operating scan. The scan then resumes at the instruction following the SVC instruction"; the example
//   rung `XIC CS0:4/MCP SVC` with channel select 0001h.
// - 1762-RM001C p. 3-13 Table 3.9: the CS file is read only, one per channel (CS0 channel 0, CS1 channel 1
//   of the 1764-LRP), 71 one-word elements; 1763-RM001C p. 57 and 1766-RM001A p. 63: the 1100/1400's
//   channel 1 is Ethernet, its status file ES; the 1400 has CS0 and CS2.
// - 1762-RM001C p. 21-2: the MicroLogix queue holds every MSG of the program; four buffers a channel
//   (RM 12-5, as the SLC 5/03-5/05).
// When MCP is cleared is not on a page reached: softslc clears it when the channel has no message left to
// send (the servicing that sends the last one; decision [U]).
#include <gtest/gtest.h>

#include <memory>
#include <optional>
#include <string>

#include "load_errors.h"
#include "../vm/message_line.h"
#include "parser/address.h"
#include "tools/controller/controller.h"

namespace softslc::test {
namespace {

std::string ml_program(std::string_view processor, std::string_view rungs) {
  return "START " + std::string(processor) + "\nLADDER 2\n" + std::string(rungs) + "\n";
}

TEST(CsFile, TheAddressesAreWrittenWithTheirChannel) {
  EXPECT_EQ(to_string(*parse_address("CS0:4/MCP")), "CS0:4/MCP");
  EXPECT_EQ(to_string(*parse_address("CS0:4/2")), "CS0:4/MCP");  // one-word elements: bit 2 of CS0:4
  EXPECT_EQ(to_string(*parse_address("CS:4/MCP")), "CS0:4/MCP");  // CS alone is channel 0's
  EXPECT_EQ(to_string(*parse_address("CS1:4/ICP")), "CS1:4/ICP");
  EXPECT_EQ(to_string(*parse_address("CS2:0")), "CS2:0");
  EXPECT_EQ(to_string(*parse_address("CS0:5/2")), "CS0:5/2");  // the names are CS0:4's bits only
  EXPECT_EQ(to_string(*parse_address("CS0:4.0/2")), "CS0:4.0/2");
  // Each spelling parses back to the address it was printed from (address_fuzz found CS:4/1 printed as
  // CS0:4/MRP, which parsed with word 0 where CS:4/1 has none).
  for (const char* text : {"CS:4/1", "CS0:4/MRP", "CS0:4.0/2", "CS1:5/2", "CS2:4/CAB"}) {
    const Address a = *parse_address(text);
    EXPECT_EQ(parse_address(to_string(a)), a) << text << " printed as " << to_string(a);
  }
  EXPECT_FALSE(parse_address("CS3:0").has_value());
  EXPECT_EQ(parse_address("C5:0")->type, FileType::Counter);  // CS does not swallow the counter file
}

TEST(CsFile, TheCheckerTakesMcpAndNamesWhatItRefuses) {
  // The manual's conditional SVC (1762-RM001C p. 21-27), on every controller with a CS0 file.
  for (const char* p : {"Bul.1762", "Bul.1763", "Bul.1766", "1764-LSP", "1764-LRP"})
    EXPECT_EQ(load_errors(ml_program(p, "SOR XIC CS0:4/MCP SVC 1 EOR\nSOR XIO CS0:4/2 OTE B3:0/0 EOR")), "") << p;
  EXPECT_EQ(load_errors(ml_program("1764-LRP", "SOR XIC CS1:4/MCP SVC 2 EOR")), "");
  struct Case {
    const char* processor;
    const char* rung;
    const char* error;
  };
  const Case cases[] = {
      {"Bul.1762", "SOR XIC CS0:4/ICP OTE B3:0/0 EOR",
       "t.slc:3:9: error: CS0:4/ICP is not simulated by softslc: of the communications status file it keeps CS0:4/MCP"},
      {"Bul.1762", "SOR XIC CS0:4/CAB OTE B3:0/0 EOR", "CS0:4/CAB is not simulated by softslc"},
      {"Bul.1763", "SOR MOV CS0:4 N7:0 EOR", "CS0:4 is not simulated by softslc"},
      {"Bul.1763", "SOR MOV CS0:10 N7:0 EOR", "CS0:10 is not simulated by softslc"},
      {"Bul.1763", "SOR XIC CS0:71/0 OTE B3:0/0 EOR", "CS0 has 71 one-word elements, CS0:0 to CS0:70 (1762-RM001C p. 3-13 Table 3.9)"},
      // Read only (1762-RM001C p. 3-13).
      {"Bul.1763", "SOR OTE CS0:4/MCP EOR", "CS0:4/MCP: the communications status file is read only (1762-RM001C p. 3-13)"},
      {"Bul.1763", "SOR XIC CS1:4/MCP OTE B3:0/0 EOR", "1763-RM001C p. 57, 1766-RM001A p. 63: the 1100/1400's channel 1 is Ethernet"},
      {"1764-LSP", "SOR XIC CS1:4/MCP OTE B3:0/0 EOR", "has no CS1 file (1762-RM001C p. 3-13: CS1 is channel 1 of the 1764-LRP"},
      {"Bul.1766", "SOR XIC CS2:4/MCP OTE B3:0/0 EOR", "the MicroLogix 1400's channel 2 is not simulated by softslc, nor its CS2 file"},
      {"Bul.1762", "SOR XIC CS2:4/MCP OTE B3:0/0 EOR", "has no channel 2 (CS2 is the MicroLogix 1400's"},
      {"1747-L532", "SOR XIC CS0:4/MCP OTE B3:0/0 EOR", "function file CS0 exists on the MicroLogix 1100, 1200, 1400 and 1500 only"},
      {"Bul.1761", "SOR XIC CS0:4/MCP OTE B3:0/0 EOR", "function file CS0 exists on the MicroLogix 1100, 1200, 1400 and 1500 only"},
  };
  for (const Case& c : cases) {
    const std::string e = load_errors(ml_program(c.processor, c.rung));
    EXPECT_NE(e.find(c.error), std::string::npos) << c.processor << " " << c.rung << "\n" << e;
  }
}

// A 1200 writes two words to a 1100 at node 2. Rung 1 records MCP before the SVC, rung 3 after it.
constexpr std::string_view kConditionalSvc =
    "SOR XIC B3:0/0 MSG MG11:0 WRITE 500CPU LOCAL 0 N7:0 2 2 N10:3 5 EOR\n"
    "SOR XIC CS0:4/MCP OTE B3:1/0 EOR\n"
    "SOR XIC B3:0/1 XIC CS0:4/MCP SVC 1 EOR\n"
    "SOR XIC CS0:4/MCP OTE B3:1/1 EOR";
const std::string kTarget1100 = ml_program("Bul.1763", "SOR XIC B3:0/15 CLR N10:9 EOR");

TEST(CsFile, McpIsSetWhenTheMsgIsQueuedAndTheConditionalSvcSendsIt) {
  MessageLine line(ml_program("Bul.1762", kConditionalSvc), kTarget1100);
  line.set("N7:0", 1234);
  line.set("B3:0/1", 1);  // the conditional SVC's rung is enabled
  line.run();
  line.a->scan(1);
  EXPECT_FALSE(line.abit("CS0:4/MCP"));  // nothing to send yet
  EXPECT_FALSE(line.abit("B3:1/0"));
  line.set("B3:0/0", 1);
  line.a->scan(1);
  // Set when the MSG was enabled and queued; the SVC sent it at once, so the rung after it saw it clear.
  EXPECT_TRUE(line.abit("B3:1/0"));
  EXPECT_FALSE(line.abit("B3:1/1"));
  EXPECT_FALSE(line.abit("CS0:4/MCP"));
  EXPECT_TRUE(line.abit("MG11:0/EN"));
  ASSERT_TRUE(line.until("MG11:0/DN", 100 * kNsPerMs));
  EXPECT_EQ(line.bi("N10:3"), 1234);
  EXPECT_FALSE(line.abit("CS0:4/MCP"));
}

TEST(CsFile, WithoutTheSvcMcpStaysSetUntilTheEndOfScanSendsTheMessage) {
  MessageLine line(ml_program("Bul.1762", kConditionalSvc), kTarget1100);
  line.run();
  line.set("B3:0/0", 1);  // the SVC's rung stays false (B3:0/1 off)
  line.a->scan(1);
  EXPECT_TRUE(line.abit("B3:1/0"));
  EXPECT_TRUE(line.abit("B3:1/1"));     // still pending after the rung where the SVC would have sent it
  EXPECT_FALSE(line.abit("CS0:4/MCP"));  // the end-of-scan servicing sent it
  EXPECT_TRUE(line.abit("MG11:0/EW"));   // sent, not yet acknowledged
}

TEST(CsFile, TheSvcSendsEarlierThanTheEndOfScan) {
  // The same message with the conditional SVC enabled and not. The scans take 50 ms of housekeeping after
  // the rungs, and the write and its reply take a few milliseconds on DH-485: sent by the SVC near the start
  // of the scan, the reply is back by that scan's end-of-scan servicing (DN after one scan); sent at the end
  // of the scan, it is taken at the next one's (DN after two).
  auto done_after = [](bool svc) {
    RuntimeOptions slow;
    slow.time_model = std::make_shared<SlowModel>(make_scan_time_model(*resolve_processor("Bul.1762")), 50 * kNsPerMs);
    MessageLine line(ml_program("Bul.1762", kConditionalSvc), kTarget1100, std::move(slow));
    line.run();
    line.set("B3:0/1", svc ? 1 : 0);
    line.set("B3:0/0", 1);
    int scans = 0;
    while (!line.abit("MG11:0/DN") && scans < 10) scans += line.a->scan(1);
    return scans;
  };
  EXPECT_EQ(done_after(true), 1);
  EXPECT_EQ(done_after(false), 2);
}

TEST(CsFile, AMessageWaitingInTheQueueKeepsMcpSet) {
  // Five messages started in one scan: four fill the buffers and go out at the end of the scan, the fifth
  // waits in the queue (1762-RM001C p. 21-2), so MCP stays set until a buffer frees and it is sent.
  std::string rungs;
  for (int e = 0; e < 5; ++e)
    rungs += "SOR XIC B3:0/0 MSG MG11:" + std::to_string(e) + " WRITE 500CPU LOCAL 0 N7:" + std::to_string(e) +
             " 1 2 N10:" + std::to_string(e) + " 5 EOR\n";
  rungs += "SOR XIC CS0:4/MCP OTE B3:1/0 EOR";
  MessageLine line(ml_program("Bul.1762", rungs), kTarget1100);
  line.run();
  line.set("B3:0/0", 1);
  line.a->scan(1);
  EXPECT_TRUE(line.abit("CS0:4/MCP"));
  EXPECT_TRUE(line.abit("MG11:3/EW"));   // in a buffer, sent
  EXPECT_FALSE(line.abit("MG11:4/EW"));  // in the queue: EN only
  ASSERT_TRUE(line.until("MG11:4/EW", 100 * kNsPerMs));  // a buffer freed: the fifth went in and out
  EXPECT_FALSE(line.abit("CS0:4/MCP"));
  ASSERT_TRUE(line.until("MG11:4/DN", 100 * kNsPerMs));
  EXPECT_FALSE(line.abit("CS0:4/MCP"));
}

// Run mode, B3:0/0 on, one scan: the scan whose MSGs start their messages.
void start_messages(Runtime& rt) {
  ASSERT_TRUE(rt.set_mode(Mode::Run));
  ASSERT_TRUE(rt.set("B3:0/0", Value::of_int(1)));
  rt.scan(1);
}

TEST(CsFile, TheLrpsChannel1KeepsMcpInCs1) {
  // The 1764-LRP's second serial port, alone on its DH-485 network: a message there sets CS1:4/MCP, not
  // CS0:4/MCP, and SVC 2 (channel 1, 1762-RM001C p. 21-27) sends it.
  Controller c = Controller::from_text(
      ml_program("1764-LRP",
                 "SOR XIC B3:0/0 MSG MG11:0 WRITE 500CPU LOCAL 1 N7:0 1 3 N10:0 5 EOR\n"
                 "SOR XIC CS1:4/MCP OTE B3:1/0 EOR\nSOR XIC CS0:4/MCP OTE B3:1/1 EOR\n"
                 "SOR XIC CS1:4/MCP SVC 2 EOR\nSOR XIC CS1:4/MCP OTE B3:1/2 EOR"),
      "", "lrp.slc", "");
  Runtime& rt = c.runtime();
  start_messages(rt);
  EXPECT_TRUE(rt.value("B3:1/0").as_bool());
  EXPECT_FALSE(rt.value("B3:1/1").as_bool());
  EXPECT_FALSE(rt.value("B3:1/2").as_bool());
  // Nobody at node 3: 07h after the frame's time, and nothing pending.
  ASSERT_TRUE(rt.run_until([](const Runtime& r) { return r.value("MG11:0/ER").as_bool(); }, kNsPerS));
  EXPECT_EQ(rt.value("MG11:0.ERR").as_int(), 0x07);
  EXPECT_FALSE(rt.value("CS1:4/MCP").as_bool());
}

TEST(CsFile, TheModbusMasterKeepsMcpUntilTheRequestHasLeft) {
  // A Modbus RTU master's message (1763-RM001B p. 366) waits for the line: MCP is set from its start until
  // its request has been sent (ST, 1763-RM001B p. 355); a second message waiting behind it keeps MCP set.
  Controller c = Controller::from_text(
      ml_program("Bul.1766",
                 "SOR XIC B3:0/0 MSG MG11:0 03 MODBUS LOCAL 0 N7:0 1 1 1 2 EOR\n"
                 "SOR XIC B3:0/0 MSG MG11:1 03 MODBUS LOCAL 0 N7:1 1 1 2 2 EOR\n"
                 "SOR XIC CS0:4/MCP OTE B3:1/0 EOR\nSOR XIC B3:15/0 CLR N7:9 EOR"),
      "modbus VFD slave=1 baud=19200 holding=10\n", "mb.slc", "mb.bench");
  Runtime& rt = c.runtime();
  start_messages(rt);
  EXPECT_TRUE(rt.value("B3:1/0").as_bool());
  auto sent = [&](int e) {
    return rt.run_until([&](const Runtime& r) { return r.value("MG11:" + std::to_string(e) + "/ST").as_bool() ||
                                                       r.value("MG11:" + std::to_string(e) + "/DN").as_bool(); },
                        kNsPerS);
  };
  ASSERT_TRUE(sent(0));
  EXPECT_TRUE(rt.value("CS0:4/MCP").as_bool());  // the second still waits for the line
  ASSERT_TRUE(sent(1));
  ASSERT_TRUE(rt.run_until([](const Runtime& r) { return !r.value("CS0:4/MCP").as_bool(); }, kNsPerS));
  ASSERT_TRUE(rt.run_until([](const Runtime& r) { return r.value("MG11:1/DN").as_bool(); }, kNsPerS));
  EXPECT_FALSE(rt.value("CS0:4/MCP").as_bool());
}

TEST(CsFile, AProgramThatDoesNotNameTheFileHasNone) {
  // The CS file is in the data table only of a program that names it, so no other program's table grows.
  Controller named = Controller::from_text(ml_program("Bul.1763", "SOR XIC CS0:4/MCP OTE B3:0/0 EOR"), "", "a.slc", "");
  EXPECT_TRUE(named.runtime().compiled().layout->communications_status_word(0).has_value());
  EXPECT_FALSE(named.runtime().compiled().layout->communications_status_word(1).has_value());
  Controller plain = Controller::from_text(ml_program("Bul.1763", "SOR XIC B3:0/1 OTE B3:0/0 EOR"), "", "b.slc", "");
  EXPECT_FALSE(plain.runtime().compiled().layout->communications_status_word(0).has_value());
}

}  // namespace
}  // namespace softslc::test
