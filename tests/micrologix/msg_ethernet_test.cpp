// The MicroLogix 1100/1400 MSG on channel 1, the embedded EtherNet/IP port (issue 16; docs/semantics.md
// "The MicroLogix MSG on Ethernet"): the RI routing element the MSG names, the target's IP address in its
// words 1-2, the message carried on the simulated Ethernet network of the SLC 5/05's MSG, the 1400's
// channel 1 timeout rule, and the Ethernet error codes.
//
// Manual facts used (docs/micrologix-msg-sources.md sections 3-5):
// - each channel 1 Ethernet MSG names an RI element of 20 words: word 0 the subtype (10h normal MultiHop,
//   11h remote MultiHop to DH+), words 1-2 the target's IP address "stored in network byte order": for
//   10.121.30.11 word 1 = 790Ah and word 2 = 0B1Eh (1766-RM001A p. 435, 1763-RM001B p. 384);
// - MG word 24, "supplemental routing path data address": bits 8-15 the file, 0-7 the element
//   (1766-RM001A p. 400);
// - "Message Timeout for any MicroLogix 1400 channel 1 MSG ... is assigned by the processor and is
//   determined by adding the Channel 1 MSG Connection Timeout to the MSG Reply Timeout, then adding 15
//   seconds" (1766-RM001A p. 421); the MSG Reply Timeout's default is 3,000 ms (1766-UM001O p. 287,
//   table 43); the connection timeout's 15,000 ms is the SLC 5/05's (1747-UM011G p. 242), [U] for the 1400;
// - error codes (1766-RM001A p. 466, 1762-RM001C pp. 21-21/21-22): 07h target does not respond, 17h local
//   service not supported, 21h bad MSG file parameter for building the message, 37h message timed out in
//   the local processor, D0h no IP address configured, D2h invalid internet address, D5h connection not
//   completed before the timeout, D9h reply not received before the timeout;
// - 103 one-word elements a message (1762-RM001C p. 21-12; AG-UM008C p. 3-38).
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "load_errors.h"
#include "parser/formatter.h"
#include "vm/message_network.h"
#include "vm/profile_scan_time_model.h"
#include "../vm/vm_test_util.h"

namespace softslc::test {
namespace {

constexpr std::uint32_t ipv4(unsigned a, unsigned b, unsigned c, unsigned d) { return (a << 24) | (b << 16) | (c << 8) | d; }
constexpr std::uint32_t kIp1400 = ipv4(192, 168, 1, 30);
constexpr std::uint32_t kIp505 = ipv4(192, 168, 1, 20);
constexpr std::uint32_t kIp1100 = ipv4(192, 168, 1, 40);

std::string ml_program(std::string_view processor, std::string_view rungs, std::string_view data = {}) {
  return "START " + std::string(processor) + "\nLADDER 2\n" + std::string(rungs) + "\n" + std::string(data);
}

// A DATA row for RIfile:element: subtype, the two address words, 17 zeros (1766-RM001A p. 435).
std::string ri_row(const std::string& element, std::uint16_t subtype, std::uint16_t word1, std::uint16_t word2) {
  std::string text = "% " + element + " % " + std::to_string(subtype) + " " + std::to_string(static_cast<std::int16_t>(word1)) +
                     " " + std::to_string(static_cast<std::int16_t>(word2));
  for (int i = 3; i < 20; ++i) text += " 0";
  return text + "\n";
}
// A DATA block of one element.
std::string ri_data(const std::string& element, std::uint16_t subtype, std::uint16_t word1, std::uint16_t word2) {
  return "DATA " + element + "\n" + ri_row(element, subtype, word1, word2);
}
// The same for an IP address, its words as the manual lays them out.
std::string ri_to(const std::string& element, std::uint32_t ip, std::uint16_t subtype = 0x10) {
  return ri_data(element, subtype, routing_ip_word(ip, 1), routing_ip_word(ip, 2));
}

std::shared_ptr<const Program> load_peer(const std::string& text) {
  LoadResult lr = load_program(text, "peer.slc");
  if (!lr.ok()) throw std::runtime_error(lr.render_diagnostics());
  return std::make_shared<const Program>(std::move(*lr.program));
}

struct Peer {
  std::string name;
  std::string text;
  std::uint32_t ip = 0;
  RuntimeOptions options = {};
};

// A leader "A" and its peers on one simulated network, built as the test runner builds them.
struct Net {
  std::unique_ptr<Runtime> a;

  Net(const std::string& a_text, std::uint32_t a_ip, std::vector<Peer> peers) {
    RuntimeOptions opts;
    opts.ip = a_ip;
    opts.node = a_ip ? 0 : 1;
    int node = 2;
    for (Peer& p : peers) {
      PeerController pc;
      pc.name = p.name;
      pc.ip = p.ip;
      pc.node = p.ip ? 0 : node++;
      pc.program = load_peer(p.text);
      pc.options = std::make_shared<const RuntimeOptions>(std::move(p.options));
      opts.peers.push_back(std::move(pc));
    }
    std::string errors;
    a = try_build(a_text, errors, std::move(opts));
    if (!a) throw std::runtime_error("network did not build:\n" + errors);
  }
  Runtime& peer(std::string_view name) { return *a->peer(std::string(name)); }
  std::int64_t ai(std::string_view addr) const { return a->value(addr).as_int(); }
  bool abit(std::string_view addr) const { return a->value(addr).as_bool(); }
  void set(std::string_view addr, std::int64_t v) { ASSERT_TRUE(a->set(addr, Value::of_int(v))); }
  void run() { ASSERT_TRUE(a->set_mode(Mode::Run)); }
  bool until(std::string_view bit, Nanoseconds limit = kNsPerS) {
    return a->run_until([&](const Runtime& r) { return r.value(bit).as_bool(); }, limit);
  }
  // Runs until `element`'s ER and expects it `after` from `from` (within one 10 ms window: the servicing
  // point after it), with error code `code`.
  void expect_error_after(const std::string& element, VirtualTime from, Nanoseconds after, int code) {
    ASSERT_TRUE(until(element + "/ER", after + 10 * kNsPerS)) << element;
    EXPECT_GE(a->now() - from, after) << element;
    EXPECT_LT(a->now() - from, after + 10 * kNsPerMs) << element;
    EXPECT_EQ(ai(element + ".ERR"), code) << element;
  }
};

// An SLC 5/05 whose N7:0-9 and N10:0-9 exist, and a MicroLogix 1100 whose N7:0-9 exist.
const std::string kSlc505 = "START 1747-L552\nLADDER 2\nSOR XIC B3:0/15 CLR N7:9 CLR N10:9 EOR\n";
const std::string kMl1100 = ml_program("Bul.1763", "SOR XIC B3:0/15 CLR N7:9 EOR");

// A (an ML1400 at 192.168.1.30) reads five words of the 5/05's N7:0 into its N10:0-4 through RI12:0.
const std::string kRead = "SOR XIC B3:0/0 MSG MG11:0 READ 500CPU LOCAL 1 N10:0 5 RI12:0 N7:0 33 EOR";

// ---- check and fmt ----------------------------------------------------------------------------------------

TEST(MicroLogixMsgEthernetCheck, ChannelOneNamesItsRiElement) {
  // The 1100 and 1400 take channel 1 with an RI element in the target node's place (1763-RM001B p. 384,
  // 1766-RM001A p. 435).
  EXPECT_EQ(load_errors(ml_program("Bul.1766", kRead)), "");
  EXPECT_EQ(load_errors(ml_program("Bul.1763", "SOR MSG MG11:0 WRITE 500CPU LOCAL 1 N7:0 2 RI12:3 N7:0 5 EOR")), "");
  struct Case {
    const char* processor;
    const char* rung;
    const char* error;
  };
  const Case cases[] = {
      {"Bul.1766", "SOR MSG MG11:0 READ 500CPU LOCAL 1 N10:0 5 2 N7:0 33 EOR",
       "names its RI routing element where channel 0 names the target node"},
      {"Bul.1763", "SOR MSG MG11:0 READ 500CPU LOCAL 0 N10:0 5 RI12:0 N7:0 5 EOR",
       "an RI routing element is for a channel 1 Ethernet message"},
      {"Bul.1766", "SOR MSG MG11:0 READ 500CPU LOCAL 1 N10:0 5 N12:0 N7:0 33 EOR",
       "expected a target node number, or on channel 1 (Ethernet) an RI routing element"},
      {"Bul.1766", "SOR MSG MG11:0 READ 500CPU LOCAL 1 N10:0 5 RI12:0.1 N7:0 33 EOR",
       "expected a target node number, or on channel 1 (Ethernet) an RI routing element"},
      {"Bul.1766", "SOR MSG MG11:0 READ 500CPU LOCAL 1 N10:0 5 RI12:0 N7:0 33 EOR\nSOR CLR N12:0 EOR",
       "file 12"},
      // One message carries 103 one-word elements on either channel (1762-RM001C p. 21-12).
      {"Bul.1766", "SOR MSG MG11:0 READ 500CPU LOCAL 1 T4:0 35 RI12:0 T4:0 33 EOR", "one message carries at most 103"},
      // The 1400 assigns its channel 1 timeout: 15 + 3 + 15 s (1766-RM001A p. 421).
      {"Bul.1766", "SOR MSG MG11:0 READ 500CPU LOCAL 1 N10:0 5 RI12:0 N7:0 5 EOR",
       "the MicroLogix 1400 assigns a channel 1 MSG's timeout itself"},
      // The 1500 LRP's channel 1 is its second serial port, on DH-485 (1762-RM001C p. 21-12: a node number
      // names the target); the 1200 has one channel; neither has RI files.
      {"1764-LRP", "SOR MSG MG11:0 READ 500CPU LOCAL 1 N10:0 5 RI12:0 N7:0 5 EOR",
       "on the MicroLogix 1500 LRP's channel 1 (DH-485) the target is a node number, 1-31"},
      {"1764-LRP", "SOR MSG MG11:0 READ 500CPU LOCAL 1 N10:0 5 RI12:0 N7:0 5 EOR",
       "RI (routing information) files exist on the MicroLogix 1100 and 1400 only"},
      {"Bul.1762", "SOR MSG MG11:0 READ 500CPU LOCAL 1 N10:0 5 RI12:0 N7:0 5 EOR", "its MSG channel is always 0"},
  };
  for (const Case& c : cases) {
    const std::string e = load_errors(ml_program(c.processor, c.rung));
    EXPECT_NE(e.find(c.error), std::string::npos) << c.processor << " " << c.rung << "\n" << e;
  }
}

TEST(MicroLogixMsgEthernetCheck, ABadRiReferenceIsPositioned) {
  // Line 3 of the program (START, LADDER, the rung), the operand's column.
  const std::string rung = "SOR MSG MG11:0 READ 500CPU LOCAL 1 N10:0 5 B3:0 N7:0 33 EOR";
  const std::string e = load_errors(ml_program("Bul.1766", rung));
  const std::string at = "t.slc:3:" + std::to_string(rung.find("B3:0") + 1) + ": error: ";
  EXPECT_NE(e.find(at), std::string::npos) << e;
  const std::string number = "SOR MSG MG11:0 READ 500CPU LOCAL 1 N10:0 5 7 N7:0 33 EOR";
  const std::string e2 = load_errors(ml_program("Bul.1763", number));
  EXPECT_NE(e2.find("t.slc:3:" + std::to_string(number.find(" 7 ") + 2) + ": error: MSG on channel 1"), std::string::npos)
      << e2;
}

TEST(MicroLogixMsgEthernetCheck, RoutingTheNetworkDoesNotSimulateIsRefusedWhereTheDataSetsItUp) {
  // Subtype 11h, "remote MultiHop to DH+" (1766-RM001A p. 435): refused by name; another subtype names no
  // routing; 10h with an address loads.
  const std::string remote = load_errors(ml_program("Bul.1766", kRead, ri_to("RI12:0", kIp505, 0x11)));
  EXPECT_NE(remote.find("subtype 11h (set by the DATA block at line 4) is a remote MultiHop to DH+"), std::string::npos)
      << remote;
  const std::string zero = load_errors(ml_program("Bul.1766", kRead, ri_to("RI12:0", kIp505, 0)));
  EXPECT_NE(zero.find("subtype 0 (set by the DATA block at line 4) is neither 10h"), std::string::npos) << zero;
  EXPECT_EQ(load_errors(ml_program("Bul.1766", kRead, ri_to("RI12:0", kIp505))), "");
}

TEST(MicroLogixMsgEthernetCheck, TwoMsgsSharingAnRiElementGetAWarning) {
  const std::string text = ml_program("Bul.1766", std::string(kRead) +
                                                      "\nSOR MSG MG11:1 WRITE 500CPU LOCAL 1 N10:0 1 RI12:0 N7:5 33 EOR");
  LoadResult r = load_program(text, "t.slc");
  ASSERT_TRUE(r.ok()) << r.render_diagnostics();
  const std::string d = r.render_diagnostics();
  EXPECT_NE(d.find("t.slc:4:"), std::string::npos) << d;
  EXPECT_NE(d.find("warning: MSG routing element RI12:0 is also the one of the MSG at line 3"), std::string::npos) << d;
}

TEST(MicroLogixMsgEthernetCheck, TheChannelOneFormRoundTripsThroughFmt) {
  const std::string text = ml_program("Bul.1766", kRead, ri_to("RI12:0", kIp505));
  LoadResult first = load_program(text, "t.slc");
  ASSERT_TRUE(first.ok()) << first.render_diagnostics();
  const std::string formatted = format_program(*first.program);
  EXPECT_NE(formatted.find("MSG MG11:0 READ 500CPU LOCAL 1 N10:0 5 RI12:0 N7:0 33"), std::string::npos) << formatted;
  LoadResult second = load_program(formatted, "t.slc");
  ASSERT_TRUE(second.ok()) << second.render_diagnostics();
  EXPECT_EQ(format_program(*second.program), formatted);
}

TEST(MicroLogixMsgEthernetCheck, TheSetupNamesTheRiElementInWord24) {
  // 1766-RM001A p. 400: word 24 bits 8-15 the RI file (12), bits 0-7 the element (3); CHN 1; MTO the
  // assigned 33 s; word 11 the bytes (5 words, 10).
  Plc plc("SOR XIC B3:0/0 MSG MG11:0 READ 500CPU LOCAL 1 N10:0 5 RI12:3 N7:0 33 EOR", {}, "START Bul.1766\n");
  EXPECT_EQ(plc.i("MG11:0.24"), (12 << 8) | 3);
  EXPECT_EQ(plc.i("MG11:0.CHN"), 1);
  EXPECT_EQ(plc.i("MG11:0.MTO"), 33);
  EXPECT_EQ(plc.i("MG11:0.11"), 10);
  EXPECT_EQ(plc.i("MG11:0.NOD"), 0);
}

// ---- the network ------------------------------------------------------------------------------------------

TEST(MicroLogixMsgEthernet, TheRiWordsAreTheManualsByteOrder) {
  // The manual's own example (1766-RM001A p. 435): word 1 = 790Ah and word 2 = 0B1Eh name 10.121.30.11.
  // A station there answers; one at 10.121.30.12 would not be reached by these words.
  Net net(ml_program("Bul.1766", kRead, ri_data("RI12:0", 0x10, 0x790A, 0x0B1E)), kIp1400,
          {{"B", kSlc505, ipv4(10, 121, 30, 11)}});
  net.peer("B").set("N7:2", Value::of_int(4321));
  net.run();
  net.set("B3:0/0", 1);
  ASSERT_TRUE(net.until("MG11:0/DN", 100 * kNsPerMs));
  EXPECT_EQ(net.ai("N10:2"), 4321);
  EXPECT_EQ(net.ai("MG11:0.ERR"), 0);
}

TEST(MicroLogixMsgEthernet, AnMl1400ReadsAnSlc505ThroughEnEwStDn) {
  Net net(ml_program("Bul.1766", kRead, ri_to("RI12:0", kIp505)), kIp1400, {{"B", kSlc505, kIp505}});
  for (int i = 0; i < 5; ++i) net.peer("B").set("N7:" + std::to_string(i), Value::of_int(200 + i));
  net.run();
  net.set("B3:0/0", 1);
  ASSERT_EQ(net.a->scan(1), 1);
  // In a buffer, sent at the end of the scan: EN (word 16) and EW (1762-RM001C p. 21-15).
  EXPECT_TRUE(net.abit("MG11:0/EN"));
  EXPECT_EQ(net.ai("MG11:0.17"), 0b0000'0100'0000'0001);  // EW, R
  ASSERT_TRUE(net.until("MG11:0/ST", 20 * kNsPerMs));
  EXPECT_FALSE(net.abit("MG11:0/EW"));
  ASSERT_TRUE(net.until("MG11:0/DN", 20 * kNsPerMs));
  EXPECT_FALSE(net.abit("MG11:0/ST"));
  EXPECT_FALSE(net.abit("MG11:0/ER"));
  for (int i = 0; i < 5; ++i) EXPECT_EQ(net.ai("N10:" + std::to_string(i)), 200 + i);
}

TEST(MicroLogixMsgEthernet, AnMl1400WritesAnMl1100AndAn505ReadsTheMl1400) {
  // Three stations on one Ethernet: the 1400 writes two words into the 1100's N7:3; the 5/05 reads the
  // 1400's N7:0 with its own 51-word block (1747-RM001G p. 12-34), "192.168.1.30" in N9:14-20.
  const std::string ml1400 = ml_program("Bul.1766", "SOR XIC B3:0/0 MSG MG11:0 WRITE 500CPU LOCAL 1 N7:0 2 RI12:0 N7:3 33 EOR",
                                        ri_to("RI12:0", kIp1100));
  const std::string slc = "START 1747-L552\nLADDER 2\nSOR XIC B3:0/0 MSG READ 500CPU LOCAL N9:0 51 1 N10:0 1 0 N7:1 5 EOR\n"
                          "DATA N9:14\n% N9:14 % 12601 12846 12598 14382 12590 13104 0\n";
  Net net(ml1400, kIp1400, {{"SLC", slc, kIp505}, {"C", kMl1100, kIp1100}});
  net.set("N7:0", 1111);
  net.set("N7:1", -2222);
  net.run();
  net.set("B3:0/0", 1);
  ASSERT_TRUE(net.until("MG11:0/DN", 20 * kNsPerMs));
  EXPECT_EQ(net.peer("C").value("N7:3").as_int(), 1111);
  EXPECT_EQ(net.peer("C").value("N7:4").as_int(), -2222);
  net.peer("SLC").set("B3:0/0", Value::bit(true));
  ASSERT_TRUE(net.a->run_until([&](const Runtime&) { return net.peer("SLC").value("N9:0/13").as_bool(); }, 20 * kNsPerMs));
  EXPECT_EQ(net.peer("SLC").value("N10:0").as_int(), -2222);
}

TEST(MicroLogixMsgEthernet, WithoutAnIpAddressChannel1EndsWithD0hAndChannel0StillWorks) {
  // A 1400 without an address is on DH-485 (channel 0) with the 1100 at node 2. Its channel 1 message
  // ends at once with D0h "No IP address configured for the network" (the SLC 5/05's code, docs/semantics.md
  // "MSG on Ethernet"; the 1400's IP address is 0, "undefined", by default, 1766-UM001O p. 286).
  const std::string ml1400 = ml_program(
      "Bul.1766", std::string(kRead) + "\nSOR XIC B3:0/0 MSG MG11:1 READ 500CPU LOCAL 0 N10:5 1 2 N7:0 5 EOR",
      ri_to("RI12:0", kIp505));
  Net net(ml1400, 0, {{"C", kMl1100, 0}});
  net.peer("C").set("N7:0", Value::of_int(77));
  net.run();
  net.set("B3:0/0", 1);
  net.a->scan(1);
  EXPECT_TRUE(net.abit("MG11:0/ER"));
  EXPECT_EQ(net.ai("MG11:0.ERR"), 0xD0);
  ASSERT_TRUE(net.until("MG11:1/DN", 100 * kNsPerMs));
  EXPECT_EQ(net.ai("N10:5"), 77);
}

TEST(MicroLogixMsgEthernet, Channel0OfAStationOnEthernetReachesNobody) {
  // A 1400 on Ethernet: its serial port (channel 0) has no other station in softslc's one-link network, so
  // a channel 0 message ends with 07h "target node does not respond" (1766-RM001A p. 466) after its DH-485
  // frame time (16 + 0 bytes at 19,200 baud, 11 bits: 9.17 ms).
  Net net(ml_program("Bul.1766", "SOR XIC B3:0/0 MSG MG11:1 READ 500CPU LOCAL 0 N10:5 1 2 N7:0 5 EOR"), kIp1400,
          {{"B", kSlc505, kIp505}});
  net.run();
  net.set("B3:0/0", 1);
  net.a->scan(1);
  const VirtualTime sent = net.a->now();
  ASSERT_TRUE(net.until("MG11:1/ER", 100 * kNsPerMs));
  EXPECT_EQ(net.ai("MG11:1.ERR"), 0x07);
  EXPECT_GE(net.a->now() - sent, 9'166'667);
}

TEST(MicroLogixMsgEthernet, AnAddressNobodyHasEndsWithD5hBeforeThe33sTimeout) {
  // 192.168.1.99: no connection before the 15 s MSG Connection Timeout: D5h, the 33 s message timeout
  // (1766-RM001A p. 421) not reached; no ACK, so ST never set, and no TO.
  Net net(ml_program("Bul.1766", kRead, ri_to("RI12:0", ipv4(192, 168, 1, 99))), kIp1400, {{"B", kSlc505, kIp505}});
  net.run();
  net.set("B3:0/0", 1);
  net.a->scan(1);
  net.expect_error_after("MG11:0", net.a->now(), 15 * kNsPerS, 0xD5);
  EXPECT_FALSE(net.abit("MG11:0/TO"));
  EXPECT_FALSE(net.abit("MG11:0/ST"));
}

TEST(MicroLogixMsgEthernet, TheMl1400s33sTimeoutEndsAMessageThatWaitedInTheQueue) {
  // Nine messages to 192.168.1.99 start in one scan. Four buffers (1762-RM001C p. 21-3): messages 1-4 end
  // with D5h at 15 s, 5-8 (sent then) with D5h at 30 s; the ninth, sent at 30 s, reaches the 1400's
  // assigned timeout first, 15 + 3 + 15 = 33 s from its rung's false-to-true transition (1766-RM001A
  // p. 421): ER, TO and 37h, whatever its MTO word says.
  std::string rungs, data = "DATA RI12:0\n";
  const std::uint32_t nobody = ipv4(192, 168, 1, 99);
  for (int i = 0; i < 9; ++i) {
    const std::string n = std::to_string(i);
    rungs += "SOR XIC B3:0/0 MSG MG11:" + n + " READ 500CPU LOCAL 1 N10:" + n + " 1 RI12:" + n + " N7:0 33 EOR\n";
    data += ri_row("RI12:" + n, 0x10, routing_ip_word(nobody, 1), routing_ip_word(nobody, 2));
  }
  Net net(ml_program("Bul.1766", rungs, data), kIp1400, {{"B", kSlc505, kIp505}});
  net.run();
  net.a->scan(1);
  net.set("MG11:8.MTO", 0);  // MTO 0 would be "never" on channel 0; channel 1 does not read it
  net.set("B3:0/0", 1);
  const VirtualTime started = net.a->now();
  net.a->scan(1);
  net.expect_error_after("MG11:8", started, 33 * kNsPerS, 0x37);
  EXPECT_TRUE(net.abit("MG11:8/TO"));
  for (int i = 0; i < 8; ++i) EXPECT_EQ(net.ai("MG11:" + std::to_string(i) + ".ERR"), 0xD5) << i;
}

TEST(MicroLogixMsgEthernet, The1100TimesItsChannel1MessageWithItsMto) {
  // The 1400's rule names the 1400 (1766-RM001A p. 421); the 1100's channel 1 MSG keeps the setup's
  // timeout [U] (1763-RM001B's page not reached): MTO 2 ends a message to nobody after 2 s with 37h, before
  // the 15 s connection timeout.
  Net net(ml_program("Bul.1763", "SOR XIC B3:0/0 MSG MG11:0 READ 500CPU LOCAL 1 N10:0 1 RI12:0 N7:0 2 EOR",
                     ri_to("RI12:0", ipv4(192, 168, 1, 99))),
          kIp1100, {{"B", kSlc505, kIp505}});
  net.run();
  net.set("B3:0/0", 1);
  net.expect_error_after("MG11:0", net.a->now(), 2 * kNsPerS, 0x37);
  EXPECT_TRUE(net.abit("MG11:0/TO"));
}

TEST(MicroLogixMsgEthernet, ARoutingElementTheNetworkCannotUseEndsTheMessageAtOnce) {
  // The program writes the RI element (its words are data, as the 5/05's IP string is): 11h remote MultiHop,
  // not simulated: 17h; subtype 0: 21h "bad MSG file parameter for building message"; 0.0.0.0 is no
  // station's address: D2h (1766-RM001A p. 466, 1762-RM001C p. 21-21).
  struct Case {
    std::uint16_t subtype, word1, word2;
    int error;
  };
  const Case cases[] = {{0x11, routing_ip_word(kIp505, 1), routing_ip_word(kIp505, 2), 0x17},
                        {0x00, routing_ip_word(kIp505, 1), routing_ip_word(kIp505, 2), 0x21},
                        {0x10, 0, 0, 0xD2}};
  for (const Case& c : cases) {
    Net net(ml_program("Bul.1766", kRead), kIp1400, {{"B", kSlc505, kIp505}});
    net.set("RI12:0.0", c.subtype);
    net.set("RI12:0.1", static_cast<std::int16_t>(c.word1));
    net.set("RI12:0.2", static_cast<std::int16_t>(c.word2));
    net.run();
    net.set("B3:0/0", 1);
    net.a->scan(1);
    EXPECT_TRUE(net.abit("MG11:0/ER")) << c.error;
    EXPECT_EQ(net.ai("MG11:0.ERR"), c.error);
  }
}

TEST(MicroLogixMsgEthernet, ATargetThatAcknowledgesButDoesNotReplyEndsWithD9h) {
  // The 5/05's scans take 5 s: it acknowledges at once and answers at its end of scan. The 1400 waits its
  // MSG Reply Timeout, 3,000 ms (1766-UM001O p. 287), then D9h, before its 33 s message timeout.
  Peer slow{"B", kSlc505, kIp505};
  slow.options.time_model = std::make_shared<SlowModel>(make_scan_time_model(*resolve_processor("1747-L552")), 5 * kNsPerS);
  Net net(ml_program("Bul.1766", kRead, ri_to("RI12:0", kIp505)), kIp1400, {slow});
  net.run();
  net.set("B3:0/0", 1);
  ASSERT_TRUE(net.until("MG11:0/ST", 10 * kNsPerS));
  // From the acknowledgement's arrival, seen at the end of the scan that ran past it (under 2 ms).
  net.expect_error_after("MG11:0", net.a->now() - 2 * kNsPerMs, 3 * kNsPerS, 0xD9);
  EXPECT_FALSE(net.abit("MG11:0/TO"));
}

TEST(MicroLogixMsgEthernet, AMicroLogixIsOnEthernetByItsIpAddress) {
  std::string errors;
  auto build = [&](const std::string& leader, std::uint32_t leader_ip, const std::string& peer, std::uint32_t peer_ip) {
    PeerController b;
    b.name = "B";
    b.program = load_peer(peer);
    b.ip = peer_ip;
    b.node = peer_ip ? 0 : 2;
    RuntimeOptions opts;
    opts.ip = leader_ip;
    opts.node = 1;
    opts.peers.push_back(b);
    errors.clear();
    return try_build(leader, errors, opts) != nullptr;
  };
  const std::string ml1400 = ml_program("Bul.1766", "SOR XIC B3:0/15 CLR N7:9 EOR");
  EXPECT_TRUE(build(ml1400, kIp1400, kSlc505, kIp505)) << errors;
  EXPECT_TRUE(build(kSlc505, kIp505, ml1400, kIp1400)) << errors;
  // A 1400 without an address on a 5/05's Ethernet; a 1400 with one on DH-485; a 1200 has no Ethernet.
  EXPECT_FALSE(build(kSlc505, kIp505, ml1400, 0));
  EXPECT_NE(errors.find("peer B: a MicroLogix 1400 on Ethernet (its channel 1) is named by its IP address"),
            std::string::npos)
      << errors;
  EXPECT_FALSE(build(kMl1100, 0, ml1400, kIp1400));
  EXPECT_NE(errors.find("peer B: its MicroLogix 1400 is on Ethernet, this network is DH-485"), std::string::npos) << errors;
  EXPECT_FALSE(build(ml_program("Bul.1762", "SOR XIC B3:0/15 CLR N7:9 EOR"), kIp1400, kSlc505, kIp505));
  EXPECT_NE(errors.find("an IP address is for an SLC 5/05, or a MicroLogix 1100 or 1400 on its channel 1"),
            std::string::npos)
      << errors;
}

}  // namespace
}  // namespace softslc::test
