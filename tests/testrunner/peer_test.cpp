// Test files with several controllers (docs/testing.md "Several controllers"): `node`, `peer NAME
// PATH node N`, a peer's data as NAME.ADDRESS and NAME.SYMBOL, and their load-time errors.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "testrunner_test_util.h"

namespace softslc::testing {
namespace {

using ::testing::HasSubstr;
using test::Sandbox;

// A reads B's N7:0 into N10:0 whenever its read is not enabled (a polling read), and mirrors
// N10:0 to O:2.0.
constexpr const char* kA =
    "START 1747-L532\nSLOT 1 1746-IB16 SCAN_IN 1 SCAN_OUT 0\nSLOT 2 1746-OB16 SCAN_IN 0 SCAN_OUT 1\n"
    "LADDER 2 MAIN\n"
    "SOR XIO N9:0/15 MSG READ 500CPU LOCAL N9:0 14 1 N10:0 1 2 N7:0 5 EOR\n"
    "SOR MOV N10:0 O:2.0 EOR\n";
constexpr const char* kB =
    "START 1747-L532\nLADDER 2 MAIN\nSOR XIC B3:0/15 CLR N7:9 EOR\nSYMBOL N7:0 SPEED % the value A reads %\n";

std::string run_line(const std::string& head, const std::string& body) {
  Sandbox box;
  box.write("a.slc", kA);
  box.write("b.slc", kB);
  box.write("b504.slc", "START 1747-L542\nLADDER 2 MAIN\nSOR XIC B3:0/15 CLR N7:9 EOR\n");
  return box.run(head + body);
}

TEST(PeerTests, APeersDataIsNamedWithItsName) {
  // A one-word read on DH-485 is 9.17 ms + 10.31 ms of frames (docs/semantics.md "MSG and SVC") plus
  // the scans of the two controllers: with 1 ms scans it is back in under 25 ms.
  const std::string out = run_line("program a.slc\nnode 1\npeer B b.slc node 2\n",
                                   "test \"t\"\n"
                                   "  set    B.SPEED = 1234\n"
                                   "  expect B.N7:0 == 1234\n"
                                   "  run until N10:0 == 1234 within 25ms\n"
                                   "  expect O:2.0 == 0\n"
                                   "  scan   1\n"
                                   "  expect O:2.0 == 1234\n"
                                   "  expect B.N7:0..1 == 1234 0\n");
  EXPECT_EQ(out, "PASS t.test: t\n");
}

TEST(PeerTests, AFailureShowsThePeersValue) {
  const std::string out = run_line("program a.slc\npeer B b.slc node 2\n",
                                   "test \"t\"\n"
                                   "  expect B.SPEED == 5\n");
  EXPECT_THAT(out, HasSubstr("B.SPEED (B.N7:0) = 0"));
}

TEST(PeerTests, LoadErrorsNameTheLine) {
  EXPECT_THAT(run_line("program a.slc\npeer B b.slc node 2\n", "test \"t\"\n  expect C.N7:0 == 0\n"),
              HasSubstr("t.test:4:10: error: no peer 'C' on this test's network (its peers: B)"));
  EXPECT_THAT(run_line("program a.slc\npeer B b.slc node 1\n", "test \"t\"\n  scan 1\n"),
              HasSubstr("node 1 is already this controller's"));
  EXPECT_THAT(run_line("program a.slc\npeer B b504.slc node 2\n", "test \"t\"\n  scan 1\n"),
              HasSubstr("is on DH+, this network is DH-485"));
  EXPECT_THAT(run_line("program a.slc\npeer B b.slc node 2\npeer B b.slc node 3\n", "test \"t\"\n  scan 1\n"),
              HasSubstr("t.test:3:6: error: peer 'B' is already defined at line 2"));
  EXPECT_THAT(run_line("program a.slc\n", "test \"t\"\n  peer B b.slc node 2\n  scan 1\n"),
              HasSubstr("'node', 'ip', 'channel' and 'peer' lines belong at the top of the file"));
  EXPECT_THAT(run_line("program a.slc\npeer B b.slc\n", "test \"t\"\n  scan 1\n"),
              HasSubstr("incomplete 'peer' line: write peer NAME FILE.slc node N"));
  EXPECT_THAT(run_line("program a.slc\npeer B b.slc node 2\n", "test \"t\"\n  force B.I:1/0 = 1\n"),
              HasSubstr("cannot be forced from a test yet"));
  EXPECT_THAT(run_line("program a.slc\npeer B nothing.slc node 2\n", "test \"t\"\n  scan 1\n"),
              HasSubstr("peer 'B' did not load"));
}

// A 1764-LRP's channel 1, its second serial port (docs/testing.md "Several controllers", docs/semantics.md
// "Channel 1 of the 1500 LRP"): `channel 1 node N network NAME` and a peer on that network; node 2 of the
// network PANEL answers the LRP's channel 1 read, and the errors name their line.
constexpr const char* kLrp =
    "START 1764-LRP\nLADDER 2 MAIN\nSOR XIO MG11:0/EN MSG MG11:0 READ 500CPU LOCAL 1 N10:0 1 2 N7:0 5 EOR\n";

TEST(PeerTests, AnLrpsChannel1IsOnTheNetworkItsLineNames) {
  auto run = [](const std::string& head, const std::string& body) {
    Sandbox box;
    box.write("lrp.slc", kLrp);
    box.write("a.slc", kA);
    box.write("b.slc", kB);
    return box.run(head + body);
  };
  const std::string test = "test \"t\"\n  set B.SPEED = 77\n  run until N10:0 == 77 within 50ms\n";
  EXPECT_EQ(run("program lrp.slc\nnode 1\nchannel 1 node 5 network PANEL\npeer B b.slc node 2 network PANEL\n", test),
            "PASS t.test: t\n");
  // Channel 1 on the file's network: node 2 there is B too.
  EXPECT_EQ(run("program lrp.slc\nchannel 1 node 5\npeer B b.slc node 2\n", test), "PASS t.test: t\n");
  EXPECT_THAT(run("program lrp.slc\nchannel 2 node 5\n", test), HasSubstr("t.test:2:9: error: a 'channel' line is for channel 1"));
  EXPECT_THAT(run("program a.slc\nchannel 1 node 5\n", "test \"t\"\n  scan 1\n"),
              HasSubstr("channel 1: a second serial port on DH-485 is the 1764-LRP's"));
  EXPECT_THAT(run("program a.slc\nchannel 1 node 5\n", "test \"t\"\n  scan 1\n"),
              HasSubstr("t.test:2:1: error: the MSG network did not build"));
  EXPECT_THAT(run("program lrp.slc\nchannel 1 node 5\nchannel 1 node 6\n", test),
              HasSubstr("t.test:3:1: error: a second 'channel 1' line (the first is at line 2)"));
  EXPECT_THAT(run("program lrp.slc\nchannel 1 node 5 network PANEL\npeer B b.slc node 2 network OTHER\n", test),
              HasSubstr("peer B: network OTHER is not one this controller is on (its channel 1 is on network PANEL)"));
  EXPECT_THAT(run("program lrp.slc\nchannel 1 node 5 network PANEL\npeer B b.slc node 5 network PANEL\n", test),
              HasSubstr("peer B: node 5 is already this controller's on network PANEL"));
}

// DF1 full-duplex on channel 0 (docs/testing.md "DF1 full-duplex"): `channel 0 df1 [SETTING...]` and a peer
// joined by the cable, `peer NAME PATH df1 [SETTING...]`; A reads B's N7:0 on channel 0. The settings are
// checked at their column, the processor's ranges at load time (1766-RM001A p. 592).
constexpr const char* kA0 =
    "START 1747-L532\nLADDER 2 MAIN\n"
    "SOR XIO N9:0/15 MSG READ 500CPU LOCAL N9:0 14 0 N10:0 1 2 N7:0 5 EOR\n";

TEST(PeerTests, ADf1CableJoinsTheChannel0s) {
  auto run = [](const std::string& head, const std::string& body) {
    Sandbox box;
    box.write("a0.slc", kA0);
    box.write("b.slc", kB);
    return box.run(head + body);
  };
  // A one-word read: 18 characters of command and 14 of reply at 19,200 baud, 10 bits a character: 16.67 ms
  // plus the scans; at 2400 baud eight times the frames, 133.3 ms.
  const std::string test = "test \"t\"\n  set B.SPEED = 77\n  run until N10:0 == 77 within 30ms\n"
                           "  expect device DF1 sent == 1\n  expect device DF1 received == 1\n";
  EXPECT_EQ(run("program a0.slc\nchannel 0 df1\npeer B b.slc df1\n", test), "PASS t.test: t\n");
  const std::string slow = "test \"t\"\n  set B.SPEED = 77\n  run until N10:0 == 77 within 200ms\n"
                           "  expect elapsed in 133ms..150ms\n";
  EXPECT_EQ(run("program a0.slc\nchannel 0 df1 baud=2400\npeer B b.slc df1 baud=2400\n", slow), "PASS t.test: t\n");
  // Breakage: the peer left at 19,200 hears nothing, and the read is not back in 200 ms.
  EXPECT_THAT(run("program a0.slc\nchannel 0 df1 baud=2400\npeer B b.slc df1\n", slow), HasSubstr("FAIL"));
  EXPECT_THAT(run("program a0.slc\nchannel 0 df1 baud=fast\n", test),
              HasSubstr("t.test:2:15: error: df1: baud takes a whole number (baud=N), not 'fast'"));
  EXPECT_THAT(run("program a0.slc\nchannel 0 df1 crc speed=3\n", test),
              HasSubstr("t.test:2:19: error: df1: 'speed' is not a DF1 setting"));
  EXPECT_THAT(run("program a0.slc\nchannel 0 node 3\n", test), HasSubstr("t.test:2:11: error: 'node N' is for channel 1"));
  EXPECT_THAT(run("program a0.slc\nchannel 1 df1\n", test), HasSubstr("t.test:2:11: error: DF1 full-duplex is channel 0's"));
  EXPECT_THAT(run("program a0.slc\nchannel 0 df1\nchannel 0 df1 bcc\n", test),
              HasSubstr("t.test:3:1: error: a second 'channel 0' line (the first is at line 2)"));
  const std::string range = run("program a0.slc\nchannel 0 df1 ack_timeout=0\n", test);
  EXPECT_THAT(range, HasSubstr("channel 0: ack_timeout 0 is out of range 1-65535"));
  EXPECT_THAT(range, HasSubstr("t.test:2:1: error: the MSG network did not build"));
  EXPECT_THAT(run("program a0.slc\npeer B b.slc df1\n", test),
              HasSubstr("peer B: joined by the DF1 cable, but this controller's channel 0 is not DF1 full-duplex"));
}

// Two SLC 5/05s on Ethernet: E reads F's N7:0 into N10:0; the block's IP address string (words 14-20 of
// the 51-word block, the first character in the high byte, 1747-RM001G p. 12-34 table 12.14) names
// 192.168.1.20 = 3139h 322Eh 3136h 382Eh 312Eh 3230h 0.
constexpr const char* kE =
    "START 1747-L552\nLADDER 2 MAIN\n"
    "SOR XIO N9:0/15 MSG READ 500CPU LOCAL N9:0 51 1 N10:0 1 0 N7:0 5 EOR\n"
    "DATA N9:14\n% N9:14 % 12601 12846 12598 14382 12590 12848 0\n";
constexpr const char* kF = "START 1747-L552\nLADDER 2 MAIN\nSOR XIC B3:0/15 CLR N7:9 EOR\n";

std::string run_ethernet(const std::string& head, const std::string& body) {
  Sandbox box;
  box.write("e.slc", kE);
  box.write("f.slc", kF);
  box.write("b.slc", kB);
  return box.run(head + body);
}

TEST(PeerTests, Slc505sOnEthernetAreNamedByIpAddress) {
  EXPECT_EQ(run_ethernet("program e.slc\nip 192.168.1.10\npeer F f.slc ip 192.168.1.20\n",
                         "test \"t\"\n"
                         "  set    F.N7:0 = 555\n"
                         "  run until N10:0 == 555 within 10ms\n"
                         "  expect N9:0/12 == 0\n"),
            "PASS t.test: t\n");
  // The controller without an address: D0h (no IP address configured).
  EXPECT_EQ(run_ethernet("program e.slc\npeer F f.slc ip 192.168.1.20\n",
                         "test \"t\"\n"
                         "  run until N9:0/12 == 1 within 10ms\n"
                         "  expect N9:0 == 0b1xx1_xxxx_1101_0000\n"),
            "PASS t.test: t\n");
}

TEST(PeerTests, EthernetLoadErrorsNameTheLine) {
  EXPECT_THAT(run_ethernet("program e.slc\nip 192.168.1.10\npeer F f.slc node 2\n", "test \"t\"\n  scan 1\n"),
              HasSubstr("peer F: an SLC 5/05 on Ethernet is named by its IP address"));
  EXPECT_THAT(run_ethernet("program e.slc\nip 192.168.1.10\npeer F f.slc ip 192.168.1.10\n", "test \"t\"\n  scan 1\n"),
              HasSubstr("IP address 192.168.1.10 is already this controller's"));
  EXPECT_THAT(run_ethernet("program e.slc\nip 192.168.1.10\npeer F b.slc ip 192.168.1.20\n", "test \"t\"\n  scan 1\n"),
              HasSubstr("is on DH-485, this network is Ethernet"));
  // The error points at the peer it is about, not at the first peer line.
  EXPECT_THAT(run_ethernet("program e.slc\nip 192.168.1.10\npeer F f.slc ip 192.168.1.20\npeer G f.slc node 4\n",
                           "test \"t\"\n  scan 1\n"),
              HasSubstr("t.test:4:6: error: the MSG network did not build"));
  EXPECT_THAT(run_line("program a.slc\npeer B b.slc ip 192.168.1.20\n", "test \"t\"\n  scan 1\n"),
              HasSubstr("names stations by node number (node N), not IP address"));
  EXPECT_THAT(run_ethernet("program e.slc\nip 192.168.1.300\n", "test \"t\"\n  scan 1\n"),
              HasSubstr("t.test:2:4: error: '192.168.1.300' is not an IP address"));
  EXPECT_THAT(run_ethernet("program e.slc\nip\n", "test \"t\"\n  scan 1\n"),
              HasSubstr("incomplete 'ip' line: write ip A.B.C.D"));
  EXPECT_THAT(run_ethernet("program e.slc\nip 10.0.0\n", "test \"t\"\n  scan 1\n"),
              HasSubstr("'10.0.0' is not an IP address"));
  EXPECT_THAT(run_ethernet("program e.slc\nip 192.168.1.10\nip 192.168.1.11\n", "test \"t\"\n  scan 1\n"),
              HasSubstr("a second 'ip' line (the first is at line 2)"));
  EXPECT_THAT(run_ethernet("program e.slc\npeer F f.slc ip\n", "test \"t\"\n  scan 1\n"),
              HasSubstr("t.test:2:16: error: expected 'node N' (DH-485, DH+), 'ip A.B.C.D' (Ethernet), 'df1' (the DF1 cable"));
}

TEST(PeerTests, APowerCycleWithPeersIsRefused) {
  const std::string out = run_line("program a.slc\npeer B b.slc node 2\n", "test \"t\"\n  power cycle\n");
  EXPECT_THAT(out, HasSubstr("power cycle in a test with peers is not supported yet"));
}

}  // namespace
}  // namespace softslc::testing
