// Channel 1 of the MicroLogix 1500 LRP (issue 16; docs/semantics.md "Channel 1 of the 1500 LRP"): the
// 1764-LRP's second serial port on DH-485, at its own node, on the network of channel 0 or on another;
// the MSG on it, CHN read from the MG element when a message starts, and SVC's channel select.
//
// Manual facts used (docs/micrologix-msg-sources.md section 3):
// - MG word 8 CHN: "0 (channel 0) or 1 (channel 1) MicroLogix 1500 1764-LRP Processors", read/write;
//   "Always 0 for MicroLogix 1200 Controllers and MicroLogix 1500 1764-LSP Processors", read only
//   (1762-RM001C p. 21-4);
// - "For controllers with only one communication channel, this value is factory-set to channel 0 and
//   cannot be changed. For controllers with 2 channels (1764-LRP processor installed), the channel can
//   be 0 or 1" (1762-RM001C p. 21-12);
// - SVC: "bit 0 equals channel 0. When any bit is set (1), the corresponding channel is serviced"
//   (1762-RM001C p. 21-26); the 1500 LRP takes 1, 2 or 3 (p. 21-27);
// - error codes (1762-RM001C p. 21-21, 1766-RM001A p. 466): 07h target node does not respond, 21h bad MSG
//   file parameter for building the message.
// Delivery: DH-485 at 19,200 baud, 11 bits a character, 16 framing bytes (EST; instructions/message_link.h).
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "load_errors.h"
#include "../vm/message_line.h"

namespace softslc::test {
namespace {

std::string ml_program(std::string_view processor, std::string_view rungs) {
  return "START " + std::string(processor) + "\nLADDER 2\n" + std::string(rungs) + "\n";
}

PeerController peer(std::string name, int node, std::string_view text, std::string network = "",
                    RuntimeOptions options = {}) {
  PeerController p;
  p.name = std::move(name);
  p.node = node;
  p.network = std::move(network);
  p.program = load_peer_program(text);
  p.options = std::make_shared<const RuntimeOptions>(std::move(options));
  return p;
}

// A 1764-LRP at node 1 (channel 0) with its channel 1 at node 5 on the network PANEL; a MicroLogix 1200
// "LINE" at node 2 of channel 0's network and an SLC 5/03 "HMI" at node 2 of PANEL: one node number on
// two networks. Each target holds its own values in N10:0-1.
struct TwoNetworks {
  std::unique_ptr<Runtime> a;
  Runtime* line = nullptr;
  Runtime* hmi = nullptr;
  explicit TwoNetworks(std::string_view a_rungs, std::string_view hmi_rungs = "SOR XIC B3:0/15 CLR N11:9 EOR",
                       RuntimeOptions a_opts = {}, const std::string& channel1_network = "PANEL") {
    a_opts.node = 1;
    a_opts.channel1_node = 5;
    a_opts.channel1_network = channel1_network;
    a_opts.peers.push_back(peer("LINE", 2, ml_program("Bul.1762", "SOR XIC B3:0/15 CLR N10:9 EOR")));
    // The HMI's N10 exists whatever its rungs (a rung that never runs names N10:9).
    a_opts.peers.push_back(peer("HMI", channel1_network.empty() ? 3 : 2,
                                program_text(std::string(hmi_rungs) + "\nSOR XIC B3:0/15 CLR N10:9 EOR"), channel1_network));
    std::string errors;
    a = try_build(ml_program("1764-LRP", a_rungs), errors, std::move(a_opts));
    if (!a) throw std::runtime_error("network did not build:\n" + errors);
    line = a->peer("LINE");
    hmi = a->peer("HMI");
    EXPECT_TRUE(line->set("N10:0", Value::of_int(1111)));
    EXPECT_TRUE(hmi->set("N10:0", Value::of_int(2222)));
    EXPECT_TRUE(a->set_mode(Mode::Run));
  }
  std::int64_t ai(std::string_view addr) const { return a->value(addr).as_int(); }
  bool until(std::string_view bit, Nanoseconds limit = kNsPerS) {
    return a->run_until([&](const Runtime& r) { return r.value(bit).as_bool(); }, limit);
  }
};

constexpr std::string_view kReadChannel1 = "SOR XIC B3:0/0 MSG MG11:0 READ 500CPU LOCAL 1 N7:0 1 2 N10:0 5 EOR";
constexpr std::string_view kReadChannel0 = "SOR XIC B3:0/1 MSG MG11:1 READ 500CPU LOCAL 0 N7:1 1 2 N10:0 5 EOR";

TEST(LrpChannel1, CheckTakesChannel1OnTheLrpOnly) {
  // p. 21-12: the LRP's channel is 0 or 1; the one-channel controllers' is always 0 (p. 21-4).
  EXPECT_EQ(load_errors(ml_program("1764-LRP", kReadChannel1)), "");
  for (const char* p : {"1764-LSP", "Bul.1762"}) {
    const std::string e = load_errors(ml_program(p, kReadChannel1));
    EXPECT_NE(e.find("has one channel: its MSG channel is always 0 (1762-RM001C p. 21-4"), std::string::npos) << p << e;
  }
  // Channel 1 is DH-485 as channel 0 is: nodes 1-31, no PLC5, no RI element.
  const std::string node = load_errors(ml_program("1764-LRP", "SOR MSG MG11:0 READ 500CPU LOCAL 1 N7:0 1 32 N10:0 5 EOR"));
  EXPECT_NE(node.find("target node 32 is out of range 1-31 for DH-485"), std::string::npos) << node;
  const std::string plc5 = load_errors(ml_program("1764-LRP", "SOR MSG MG11:0 READ PLC5 LOCAL 1 N7:0 1 2 N10:0 5 EOR"));
  EXPECT_NE(plc5.find("channel 1 on the simulated DH-485 link sends 500CPU and 485CIF"), std::string::npos) << plc5;
  const std::string ri = load_errors(ml_program("1764-LRP", "SOR MSG MG11:0 READ 500CPU LOCAL 1 N7:0 1 RI12:0 N10:0 5 EOR"));
  EXPECT_FALSE(ri.empty());
}

TEST(LrpChannel1, TheSetupWritesChn1) {
  // MG word 8, CHN (1762-RM001C p. 21-4): the setup's channel.
  Plc plc(kReadChannel1, {}, "START 1764-LRP\n");
  EXPECT_EQ(plc.i("MG11:0.CHN"), 1);
  EXPECT_EQ(plc.i("MG11:0.NOD"), 2);
}

TEST(LrpChannel1, EachChannelReachesItsOwnNetwork) {
  // Node 2 is the 1200 on channel 0's network and the SLC 5/03 on PANEL, channel 1's.
  TwoNetworks net(std::string(kReadChannel1) + "\n" + std::string(kReadChannel0));
  ASSERT_TRUE(net.a->set("B3:0/0", Value::bit(true)));
  ASSERT_TRUE(net.a->set("B3:0/1", Value::bit(true)));
  ASSERT_TRUE(net.until("MG11:0/DN", 200 * kNsPerMs));
  ASSERT_TRUE(net.until("MG11:1/DN", 200 * kNsPerMs));
  EXPECT_EQ(net.ai("N7:0"), 2222);
  EXPECT_EQ(net.ai("N7:1"), 1111);
  EXPECT_EQ(net.ai("MG11:0.ERR"), 0);
}

TEST(LrpChannel1, APeerOnPanelReachesTheLrpAtItsChannel1Node) {
  // The SLC 5/03 on PANEL writes into the LRP at node 5, its channel 1 node; node 1 is nobody there.
  TwoNetworks net("SOR XIC B3:0/15 CLR N10:9 EOR",
                  "SOR XIC B3:0/0 MSG WRITE 500CPU LOCAL N9:0 14 1 N11:0 1 5 N10:3 5 EOR\n"
                  "SOR XIC B3:0/1 MSG WRITE 500CPU LOCAL N9:20 14 1 N11:0 1 1 N10:3 5 EOR\n"
                  "SOR XIC B3:0/15 CLR N11:9 EOR");
  ASSERT_TRUE(net.hmi->set("N11:0", Value::of_int(-42)));
  ASSERT_TRUE(net.hmi->set("B3:0/0", Value::bit(true)));
  ASSERT_TRUE(net.a->run_until([&](const Runtime&) { return net.hmi->value("N9:0/13").as_bool(); }, 200 * kNsPerMs));
  EXPECT_EQ(net.ai("N10:3"), -42);
  ASSERT_TRUE(net.hmi->set("B3:0/1", Value::bit(true)));
  ASSERT_TRUE(net.a->run_until([&](const Runtime&) { return net.hmi->value("N9:20/12").as_bool(); }, 200 * kNsPerMs));
  EXPECT_EQ(net.hmi->value("N9:20").as_int() & 0xFF, 0x07) << "07h: node 1 is the LRP's channel 0, not on PANEL";
}

TEST(LrpChannel1, BothPortsOnOneNetworkAreTwoNodes) {
  // Channel 1 on channel 0's network (no network name): node 5 is the LRP there too, and the HMI (node 3)
  // reaches it at either node.
  TwoNetworks net(std::string(kReadChannel1), "SOR XIC B3:0/15 CLR N11:9 EOR", {}, "");
  ASSERT_TRUE(net.a->set("B3:0/0", Value::bit(true)));
  ASSERT_TRUE(net.until("MG11:0/DN", 200 * kNsPerMs));
  EXPECT_EQ(net.ai("N7:0"), 1111) << "node 2 of the one network is the 1200";
}

TEST(LrpChannel1, WritingChnSendsTheNextMessageOnTheOtherPort) {
  // CHN is read/write on the LRP (p. 21-4) and read when the message starts: a program that writes 0
  // sends the next message on channel 0, to the 1200 at node 2; 2 names no channel: ER with 21h (decision).
  TwoNetworks net(kReadChannel1);
  ASSERT_TRUE(net.a->set("B3:0/0", Value::bit(true)));
  ASSERT_TRUE(net.until("MG11:0/DN", 200 * kNsPerMs));
  EXPECT_EQ(net.ai("N7:0"), 2222);
  ASSERT_TRUE(net.a->set("B3:0/0", Value::bit(false)));
  net.a->scan(1);
  ASSERT_TRUE(net.a->set("MG11:0.CHN", Value::of_int(0)));
  ASSERT_TRUE(net.a->set("B3:0/0", Value::bit(true)));
  net.a->scan(1);
  ASSERT_TRUE(net.until("MG11:0/DN", 200 * kNsPerMs));
  EXPECT_EQ(net.ai("N7:0"), 1111);
  ASSERT_TRUE(net.a->set("B3:0/0", Value::bit(false)));
  net.a->scan(1);
  ASSERT_TRUE(net.a->set("MG11:0.CHN", Value::of_int(2)));
  ASSERT_TRUE(net.a->set("B3:0/0", Value::bit(true)));
  net.a->scan(1);
  EXPECT_TRUE(net.a->value("MG11:0/ER").as_bool());
  EXPECT_EQ(net.ai("MG11:0.ERR"), 0x21);
}

TEST(LrpChannel1, Channel1OnNoNetworkReachesNobody) {
  // An LRP whose channel 1 is given no network: its channel 1 messages end with 07h "target node does
  // not respond" (p. 21-21) after the request's frame time, as channel 0's to a node nobody has.
  Plc plc(kReadChannel1, {}, "START 1764-LRP\n");
  ASSERT_TRUE(plc.rt->set_mode(Mode::Run));
  ASSERT_TRUE(plc.rt->set("B3:0/0", Value::bit(true)));
  ASSERT_TRUE(plc.rt->run_until([](const Runtime& r) { return r.value("MG11:0/ER").as_bool(); }, 100 * kNsPerMs));
  EXPECT_EQ(plc.i("MG11:0.ERR"), 0x07);
}

TEST(LrpChannel1, TheNetworkRefusesWhatItCannotBuild) {
  auto build = [](RuntimeOptions o, std::string_view processor = "1764-LRP") {
    std::string errors;
    auto rt = try_build(ml_program(processor, kReadChannel0), errors, std::move(o));
    return rt ? std::string() : errors;
  };
  RuntimeOptions lsp;
  lsp.channel1_node = 5;
  EXPECT_NE(build(lsp, "1764-LSP").find("channel 1: a second serial port on DH-485 is the 1764-LRP's"), std::string::npos)
      << build(lsp, "1764-LSP");
  RuntimeOptions same;
  same.node = 1;
  same.channel1_node = 1;
  EXPECT_NE(build(same).find("this controller's channel 1: node 1 is already this controller's"), std::string::npos)
      << build(same);
  RuntimeOptions far;
  far.channel1_node = 32;
  EXPECT_NE(build(far).find("node 32 is out of range 1-31"), std::string::npos) << build(far);
  RuntimeOptions stray;
  stray.channel1_node = 5;
  stray.channel1_network = "PANEL";
  stray.peers.push_back(peer("X", 2, program_text("SOR XIC B3:0/15 CLR N10:9 EOR"), "OTHER"));
  EXPECT_NE(build(stray).find("peer X: network OTHER is not one this controller is on (its channel 1 is on network PANEL)"),
            std::string::npos)
      << build(stray);
  RuntimeOptions clash;
  clash.channel1_node = 5;
  clash.channel1_network = "PANEL";
  clash.peers.push_back(peer("X", 5, program_text("SOR XIC B3:0/15 CLR N10:9 EOR"), "PANEL"));
  EXPECT_NE(build(clash).find("peer X: node 5 is already this controller's on network PANEL"), std::string::npos)
      << build(clash);
}

// SVC's channel select (1762-RM001C p. 21-26): bit 1 services channel 1. The HMI on PANEL writes 77 into
// the LRP's N7:0 through its channel 1 node; the LRP copies N7:0 to N7:1, runs SVC, copies N7:0 to N7:2,
// each MOV 4.5 ms long (the pattern of tests/vm/message_test.cpp SvcServicesTheChannelAtItsPlaceInTheScan:
// the write arrives in the LRP's second scan before its SVC). SVC 2 and SVC 3 take it there: that scan's
// N7:2 has the value and its N7:1 not; SVC 1 (channel 0 only) leaves it to the end of the scan. A REF in the
// SVC's place services every channel, channel 1 too (1766-RM001A p. 410-411; docs/semantics.md "REF").
TEST(LrpChannel1, SvcServicesChannel1WhenItsBitIsSet) {
  auto copies = [](const std::string& middle) {
    RuntimeOptions a_opts;
    ProcessorModel p = *resolve_processor("1764-LRP");
    a_opts.time_model = std::make_shared<SlowModel>(make_scan_time_model(p), 500'000, 4'500'000);
    TwoNetworks net("SOR MOV N7:0 N7:1 EOR\nSOR " + middle + " EOR\nSOR MOV N7:0 N7:2 EOR\n" +
                        "SOR XIC B3:0/15 CLR N7:9 EOR",
                    "SOR XIC B3:0/0 MSG WRITE 500CPU LOCAL N9:0 14 1 N11:0 1 5 N7:0 5 EOR\nSOR XIC B3:0/15 CLR N11:9 EOR",
                    a_opts);
    EXPECT_TRUE(net.hmi->set("N11:0", Value::of_int(77)));
    EXPECT_TRUE(net.hmi->set("B3:0/0", Value::bit(true)));
    std::vector<std::pair<std::int64_t, std::int64_t>> seen;
    for (int i = 0; i < 3; ++i) {
      net.a->scan(1);
      seen.emplace_back(net.ai("N7:1"), net.ai("N7:2"));
    }
    return seen;
  };
  using Seen = std::vector<std::pair<std::int64_t, std::int64_t>>;
  EXPECT_EQ(copies("SVC 2"), (Seen{{0, 0}, {0, 77}, {77, 77}}));
  EXPECT_EQ(copies("SVC 3"), (Seen{{0, 0}, {0, 77}, {77, 77}}));
  EXPECT_EQ(copies("SVC 1"), (Seen{{0, 0}, {0, 0}, {77, 77}}));
  EXPECT_EQ(copies("REF"), (Seen{{0, 0}, {0, 77}, {77, 77}}));
}

}  // namespace
}  // namespace softslc::test
