// The 1747-SDN module on the chassis: its image (status and command registers), the M0/M1 tables,
// Run/Idle, the failures a bench injects, and the errors of its SLOT line and bench node. Expected
// values are the manual's (1747-UM655B, pages as cited), never read back from the module.
#include <gtest/gtest.h>

#include "sdn_test_util.h"

namespace softslc::test {
namespace {

// A 1747-SDN in slot 1. N7:0 is copied to the command register every scan; B3 mirrors nothing.
const std::string kProgram =
    "START 1747-L542\n"
    "SLOT 0 1747-L542 SCAN_IN 0 SCAN_OUT 0\n"
    "SLOT 1 1747-SDN SCAN_IN 32 SCAN_OUT 32\n"
    "LADDER 2\n"
    "SOR MOV N7:0 O:1.0 EOR\n";

// The manual's example network (p.57-61) at node 0, 125K.
const std::string kNetwork =
    "devicenet DNET slot=1 node=0 baud=125K {\n"
    "  node STATION address=7 model=redistation {\n"
    "    key vendor=1 device_type=24 product_code=2705\n"
    "    poll rx=1 tx=1\n"
    "    input from=poll bits=8 to=M1:0/0\n"
    "    output to=poll bits=8 from=M0:0/0\n"
    "  }\n"
    "  node EYE address=9 model=series-9000-photoeye {\n"
    "    strobe rx=1\n"
    "    input from=strobe bits=8 to=M1:0/8\n"
    "  }\n"
    "  node GHOST address=12 {\n"
    "    poll rx=2 tx=0\n"
    "    input from=poll bits=16 to=M1:1/0\n"
    "  }\n"
    "}\n";

constexpr std::int64_t kRun = 1, kFault = 2, kDisable = 16;

// M1:210, high byte node, low byte code (p.136 "node address and status").
std::int64_t node_status(int node, int code) { return (node << 8) | code; }

Bench network(const std::string& extra_nodes = "") {
  std::string bench = kNetwork;
  bench.insert(bench.rfind('}'), extra_nodes);
  return Bench(kProgram, bench);
}

// Processor in Run, scanner commanded to Run, devices connected (the 2 s duplicate node check and the
// connections).
void start_in_run(Bench& b) {
  b.run();
  b.set("N7:0", kRun);
  b->run_for(seconds(4));
}

TEST(SdnModule, FactoryDefaultsWithoutBench) {
  // Without a bench the module has the factory configuration (p.140): node 63, no scanlist, and it
  // is alone on its cable: "79 Module has failed to transmit a message" once the duplicate node
  // check (2 s) is over, with the communication failure bit 10 (p.135).
  Bench b(kProgram, "");
  b.run();
  b->run_for(seconds(3));
  EXPECT_EQ(b.i("M1:1.210"), node_status(63, 79));
  EXPECT_TRUE(b.b("I:1.0/10"));
  EXPECT_EQ(b->devices().size(), 0u);
}

TEST(SdnModule, StatusRegisterEchoesRunFaultDisable) {
  // Status register bits 0, 1 and 4 echo command bits 0, 1 and 4 (p.135).
  Bench b = network();
  b.run();
  for (std::int64_t cmd : {kRun, kFault, kDisable, std::int64_t{0}}) {
    b.set("N7:0", cmd);
    b->scan(3);
    EXPECT_EQ(b.i("I:1.0") & 0x13, cmd) << cmd;
  }
}

TEST(SdnModule, CommandCodesInNodeStatusWord) {
  // Fault network shows 81, disable network 90, halt 97 (chapter 7, p.90-91); a reserved command
  // bit is a command error (81, docs/1747-sdn.md decision 4).
  Bench b = network();
  b.run();
  b->run_for(seconds(3));
  const std::vector<std::pair<std::int64_t, int>> cases = {{kFault, 81}, {kDisable, 90}, {64, 97}, {8, 81}};
  for (auto [cmd, code] : cases) {
    b.set("N7:0", cmd);
    b->scan(3);
    EXPECT_EQ(b.i("M1:1.210"), node_status(0, code)) << cmd;
  }
}

TEST(SdnModule, RunMapsOutputsIdleKeepsConnectionsAndInputs) {
  Bench b = network();
  b.run();
  b.set("M0:1.0", 1);  // the light's output bit, written by the processor
  b->run_for(seconds(4));
  // Idle (command bit 0 off): connections made, active table bits 7 and 9 (p.136), inputs mapped,
  // outputs not: the RediSTATION gets idle data and its light stays off.
  EXPECT_TRUE(b.b("M1:1.206/7"));
  EXPECT_TRUE(b.b("M1:1.206/9"));
  EXPECT_EQ(b.i("M1:1.210"), node_status(12, 78));  // GHOST: no device answers (chapter 7)
  b.inject("STATION", "input", {"start", "1"});
  b->run_for(milliseconds(200));
  EXPECT_TRUE(b.b("M1:1.0/1"));
  EXPECT_EQ(*b->observe("STATION", "light"), one(0));
  // Run: outputs are mapped.
  b.set("N7:0", kRun);
  b->run_for(milliseconds(200));
  EXPECT_EQ(*b->observe("STATION", "light"), one(1));
  // Back to Idle: the device applies its idle action (clear).
  b.set("N7:0", 0);
  b->run_for(milliseconds(200));
  EXPECT_EQ(*b->observe("STATION", "light"), one(0));
}

TEST(SdnModule, ProcessorProgramModeSendsZerosSoTheScannerGoesIdle) {
  Bench b = network();
  b.set("M0:1.0", 1);
  start_in_run(b);
  EXPECT_EQ(*b->observe("STATION", "light"), one(1));
  ASSERT_TRUE(b->set_mode(Mode::Program));
  b->run_for(milliseconds(300));
  EXPECT_FALSE(b.b("I:1.0/0")) << "the output image is zeros outside Run: command Idle";
  EXPECT_EQ(*b->observe("STATION", "light"), one(0));
  EXPECT_TRUE(b.b("M1:1.206/7")) << "Idle keeps the connection";
}

TEST(SdnModule, FlushFollowsTheManualsProcedure) {
  // p.139: "While the SLC processor in Program mode, clear the module command word 0 and set bit 2",
  // then cycle the keyswitch to Run and back: the word reaches the module with the Run output scan
  // and it shows E9 "Module memory has been flushed" (chapter 7) until its power is cycled.
  Bench b = network();
  b.set("N7:0", 4);
  b->scan(2);
  EXPECT_NE(b.i("M1:1.210") & 0xFF, 0xE9) << "Program mode: the module saw only zeros";
  b.run();
  b->scan(2);
  ASSERT_TRUE(b->set_mode(Mode::Program));
  b->scan(2);
  EXPECT_EQ(b.i("M1:1.210"), node_status(63, 0xE9)) << "factory default node 63";
  b.set("N7:0", kRun);
  b.run();
  b->run_for(seconds(3));
  EXPECT_EQ(b.i("M1:1.210") & 0xFF, 0xE9);
  EXPECT_FALSE(b.b("M1:1.206/7"));
}

TEST(SdnModule, OfflineDeviceFailsAndRecovers) {
  Bench b = network();
  start_in_run(b);
  ASSERT_TRUE(b.b("M1:1.206/7"));
  b.inject("STATION", "offline");
  // The connection times out after 4 x the 75 ms expected packet rate; the device failure table
  // (M1:216-219, p.137) and status bit 6 (p.135) show it, with code 72 for node 7.
  b->run_for(milliseconds(400));
  EXPECT_TRUE(b.b("M1:1.216/7"));
  EXPECT_FALSE(b.b("M1:1.206/7"));
  EXPECT_TRUE(b.b("I:1.0/6"));
  EXPECT_EQ(b.i("M1:1.210") & 0xFF00, 7 << 8);  // node 7 is the lowest failing node...
  EXPECT_EQ(b.i("M1:1.210") & 0xFF, 72);        // ...with "72 Slave device stopped communicating"
  b.inject("STATION", "online");
  b->run_for(seconds(2));
  EXPECT_FALSE(b.b("M1:1.216/7"));
  EXPECT_TRUE(b.b("M1:1.206/7"));
}

TEST(SdnModule, InjectedFailuresShowTheirChapter7Codes) {
  struct Case {
    std::string device, fault;
    std::vector<std::string> args;
    int node, code;
    std::string status_bit;  // an I:1.0 bit that must be set, or ""
    bool at_power_up = false;  // keying and ownership are checked when a connection is made
  };
  const std::vector<Case> cases = {
      {"STATION", "data size", {"2"}, 7, 77, "I:1.0/8"},  // autoverify failure (p.135 bit 8)
      {"STATION", "key mismatch", {}, 7, 73, "I:1.0/6", true},  // "Device's identity information does not match"
      {"STATION", "owned elsewhere", {}, 7, 83, "I:1.0/6", true},
      {"STATION", "idle", {}, 7, 86, ""},                 // "Device is producing zero length data (idle)"
      {"DNET", "bus off", {}, 0, 91, "I:1.0/10"},
      {"DNET", "power off", {}, 0, 92, "I:1.0/10"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.device + " " + c.fault);
    Bench b = network("  node EXTRA address=20 model=redistation\n");
    if (c.at_power_up) b.inject(c.device, c.fault, c.args);
    b.run();
    b.set("N7:0", kRun);
    b->run_for(seconds(4));
    if (!c.at_power_up) b.inject(c.device, c.fault, c.args);
    b->run_for(seconds(3));  // a reconnection (1 s) and its checks
    EXPECT_EQ(b.i("M1:1.210"), node_status(c.node, c.code));
    if (!c.status_bit.empty()) {
      EXPECT_TRUE(b.b(c.status_bit));
    }
    // "normal" withdraws the change.
    b.inject(c.device, "normal");
    b->run_for(seconds(4));
    EXPECT_EQ(b.i("M1:1.210"), node_status(12, 78)) << "only the missing GHOST remains";
  }
}

TEST(SdnModule, DuplicateNodeAddressAtPortStart) {
  // A node answering the scanner's address in the duplicate MAC ID check: 70 and status bit 12.
  Bench b = network();
  b.inject("DNET", "duplicate", {"0"});
  b.run();
  b->run_for(seconds(3));
  EXPECT_EQ(b.i("M1:1.210"), node_status(0, 70));
  EXPECT_TRUE(b.b("I:1.0/12"));
}

TEST(SdnModule, WrongDataRateIsBusOff) {
  // The scanner at 125K on a 500K network: "91 Bus-off condition detected on integral DeviceNet port"
  // (chapter 7), communication failure bit 10.
  std::string bench = kNetwork;
  bench.replace(bench.find("baud=125K"), 9, "baud=125K network_baud=500K");
  Bench b(kProgram, bench);
  b.run();
  b->run_for(seconds(3));
  EXPECT_EQ(b.i("M1:1.210"), node_status(0, 91));
  EXPECT_TRUE(b.b("I:1.0/10"));
}

TEST(SdnModule, HaltSendsRunningDevicesToTheirFaultState) {
  // Halt (command bit 6, p.138): "No communication occur ... If scanner was in Run mode, devices will
  // go to their fault state" once their connections time out; reboot (bit 7) restarts the port (84).
  Bench b = network();
  b.set("M0:1.0", 1);
  start_in_run(b);
  ASSERT_EQ(*b->observe("STATION", "light"), one(1));
  b.set("N7:0", kRun | 64);
  b->run_for(seconds(1));
  EXPECT_EQ(b.i("M1:1.210"), node_status(0, 97));
  EXPECT_EQ(*b->observe("STATION", "output state"), one(3));  // Fault
  EXPECT_EQ(*b->observe("STATION", "light"), one(0));         // fault action: clear
  b.set("N7:0", kRun | 128);
  b->scan(2);
  EXPECT_EQ(b.i("M1:1.210"), node_status(0, 84));
  b.set("N7:0", kRun);
  b->run_for(seconds(6));
  // The reboot cleared the module's RAM, M0 included (docs/1747-sdn.md decision 6): the light stays
  // off until the processor writes M0 again.
  EXPECT_EQ(b.i("M0:1.0"), 0);
  EXPECT_EQ(*b->observe("STATION", "light"), one(0));
  b.set("M0:1.0", 1);
  b->run_for(milliseconds(100));
  EXPECT_EQ(*b->observe("STATION", "light"), one(1));
}

// Appendix E through the M0/M1 files (p.145-150), the way a ladder program does it: the block is
// written word by word, taken after the scan.
struct Empc {
  Bench& b;
  void write(std::vector<std::int64_t> words) {
    for (std::size_t k = 0; k < words.size(); ++k) b.set("M0:1." + std::to_string(224 + k), words[k]);
    b->scan(1);
  }
  std::int64_t head(int word) { return b.u("M1:1." + std::to_string(224 + word)); }
};

TEST(SdnModule, TransactionCommandsThroughTheMFiles) {
  Bench b = network();
  start_in_run(b);
  b.inject("STATION", "message timeout");  // requests stay in progress for 1.5 s
  Empc e{b};
  const std::int64_t get_identity_vendor = 0x0E07;  // Get_Attribute_Single to MAC 7
  e.write({(5 << 8) | 1, 6, get_identity_vendor, 1, 1, 1});
  EXPECT_FALSE(b.b("I:1.0/15")) << "in progress: nothing queued yet";
  // Command 2, get status: "2 Transaction in progress".
  e.write({(5 << 8) | 2});
  b->scan(1);
  EXPECT_TRUE(b.b("I:1.0/15"));
  EXPECT_EQ(e.head(0), (5 << 8) | 2);
  // Command 4 deletes the report; get status of an unknown TXID: 6.
  e.write({(5 << 8) | 4});
  e.write({(9 << 8) | 2});
  b->scan(1);
  EXPECT_EQ(e.head(0), (9 << 8) | 6);
  e.write({(9 << 8) | 4});
  // An unknown command: status 8.
  e.write({(9 << 8) | 7});
  b->scan(1);
  EXPECT_EQ(e.head(0), (9 << 8) | 8);
  // Command 3 resets everything: the queue empties and TXID 5 is free again.
  e.write({3});
  b->scan(1);
  EXPECT_FALSE(b.b("I:1.0/15"));
  EXPECT_FALSE(sdn(b, 1).scanner().txid_in_use(5));
  // A TXID in use is ignored (p.150): the second execute with TXID 6 does not replace the first.
  b.inject("STATION", "responding");
  e.write({(6 << 8) | 1, 6, get_identity_vendor, 1, 1, 1});
  e.write({(6 << 8) | 1, 6, 0x0E09, 1, 1, 1});  // to the photoeye instead
  ASSERT_TRUE(b.until([&] { return b.b("I:1.0/15"); }, milliseconds(100)));
  b->scan(1);
  EXPECT_EQ(e.head(0), (6 << 8) | 1);
  EXPECT_EQ(e.head(2), 0x8E07) << "the answer of the first request, from MAC 7";
  EXPECT_EQ(e.head(3), 1) << "vendor 1 (the RediSTATION's identity)";
}

TEST(SdnModule, ResponsesQueueInArrivalOrder) {
  Bench b = network();
  start_in_run(b);
  Empc e{b};
  // "Responses are queued in the order they complete" (p.148), not in the order asked: TXID 1 goes
  // to a photoeye that does not answer (status 7 after the retries), TXID 2 to the RediSTATION.
  b.inject("EYE", "message timeout");
  e.write({(1 << 8) | 1, 6, 0x0E09, 1, 1, 1});
  e.write({(2 << 8) | 1, 6, 0x0E07, 1, 1, 1});
  ASSERT_TRUE(b.until([&] { return b.b("I:1.0/15"); }, milliseconds(100)));
  b->scan(1);
  EXPECT_EQ(e.head(0), (2 << 8) | 1);
  b->run_for(seconds(2));
  EXPECT_EQ(e.head(0), (2 << 8) | 1) << "the head stays until deleted";
  e.write({(2 << 8) | 4});
  b->scan(1);
  EXPECT_EQ(e.head(0), (1 << 8) | 7);
  e.write({(1 << 8) | 4});
  b->scan(1);
  EXPECT_FALSE(b.b("I:1.0/15"));
  EXPECT_EQ(sdn(b, 1).scanner().transactions_in_use(), 0u);
}

TEST(SdnModule, ARequestBlockWrittenOverSeveralRungsIsOneRequest) {
  // Decision 1 (docs/1747-sdn.md): the block is taken after the scan that wrote it, so the command
  // word may come first and the body later in the same scan.
  const std::string program = kProgram.substr(0, kProgram.find("LADDER")) +
                              "LADDER 2\nSOR MOV N7:0 O:1.0 EOR\n"
                              "SOR XIC B3:0/0 MOV 0x0301 M0:1.224 EOR\n"
                              "SOR XIC B3:0/0 BST MOV 6 M0:1.225 NXB MOV 0x0E07 M0:1.226 NXB MOV 1 M0:1.227 NXB "
                              "MOV 1 M0:1.228 NXB MOV 1 M0:1.229 BND EOR\nSOR XIC B3:0/0 OTU B3:0/0 EOR\n";
  Bench b(program, kNetwork);
  start_in_run(b);
  b.set("B3:0/0", 1);
  ASSERT_TRUE(b.until([&] { return b.b("I:1.0/15"); }, milliseconds(100)));
  b->scan(1);
  EXPECT_EQ(b.i("M1:1.224"), (3 << 8) | 1);
  EXPECT_EQ(b.i("M1:1.227"), 1) << "vendor 1: the whole block was sent";
}

TEST(SdnModule, MFilesAreReadWriteAndSized) {
  // Both files are read/write for this module (appendix D); M1 data written by the ladder stays
  // until the scanner next updates those bits; the pass-through area is not emulated (reads 0).
  Bench b = network();
  b.run();
  b.set("M1:1.100", 1234);
  EXPECT_EQ(b.i("M1:1.100"), 1234);
  b.set("M0:1.149", -1);
  EXPECT_EQ(b.i("M0:1.149"), -1);
  EXPECT_EQ(b.i("M1:1.300"), 0);
  EXPECT_EQ(sdn(b, 1).m_file_words(MFile::M0), 395);
  std::uint16_t v = 0;
  EXPECT_EQ(sdn(b, 1).read_m(MFile::M1, 395, v), MAccess::NoSuchWord);
}

TEST(SdnModule, DeviceChangesAreRefusedWithReasons) {
  Bench b = network();
  EXPECT_FALSE(b->inject("STATION", "exploded"));
  EXPECT_NE(b->inject("STATION", "exploded").message.find("'offline'"), std::string::npos);
  EXPECT_NE(b->inject("STATION", "input", {"nonesuch", "1"}).message.find("stop, start, bulb_missing"),
            std::string::npos);
  EXPECT_NE(b->inject("GHOST", "offline").message.find("no device"), std::string::npos);
  EXPECT_FALSE(b->inject("DNET", "duplicate"));
  EXPECT_EQ(b->devices(), (std::vector<std::string>{"DNET", "STATION", "EYE", "GHOST"}));
}

// ---- Configuration errors ----------------------------------------------------------------------------------

std::string setup_messages(const std::string& program, const std::string& bench) {
  LoadResult lr = load_program(program, "test.slc");
  EXPECT_TRUE(lr.ok()) << lr.render_diagnostics();
  ModuleSetup s = load_module_setup_text(*lr.program, bench, "test.bench");
  return s.render("test.slc", lr.source);
}

TEST(SdnModule, SlotLineChecks) {
  const std::string big = "START 1747-L542\nSLOT 1 1747-SDN SCAN_IN 33 SCAN_OUT 32 M0_SIZE 400\nLADDER 2\n";
  const std::string m = setup_messages(big, "");
  EXPECT_NE(m.find("test.slc:2:6: error: 1747-SDN in slot 1: the module has a 32-word input and output image"),
            std::string::npos)
      << m;
  EXPECT_NE(m.find("M0 is 400 words"), std::string::npos) << m;
  const std::string small = "START 1747-L542\nSLOT 1 1747-SDN SCAN_IN 32 SCAN_OUT 32 M1_SIZE 150\nLADDER 2\n";
  EXPECT_NE(setup_messages(small, "").find("warning: 1747-SDN in slot 1: M1 is 150 words"), std::string::npos);
  const std::string slc501 = "START 1747-L511\nSLOT 1 1747-SDN SCAN_IN 32 SCAN_OUT 32\nLADDER 2\n";
  EXPECT_NE(setup_messages(slc501, "").find("needs a modular SLC 5/02 or later"), std::string::npos);
}

TEST(SdnModule, BenchErrorsArePositioned) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"devicenet D slot=1 node=0 {\n  node A address=7 model=toaster\n}\n",
       "test.bench:2:26: error: node A: model=toaster: no such built-in DeviceNet device"},
      {"devicenet D slot=1 node=0 {\n  node A address=7 {\n    poll rxx=1\n  }\n}\n",
       "test.bench:3:14: error: scanlist[0].poll.rxx: unknown key"},
      {"devicenet D slot=1 node=0 baud=99K\n", "test.bench:1:32: error: baud"},
      {"devicenet D slot=1 node=64\n", "test.bench:1:25: error: node: expected an integer in 0...63, got 64"},
      {"devicenet D slot=1 node=0 {\n  node A address=0 model=redistation\n}\n",
       "test.bench:2:18: error: node A has the scanner's own address 0"},
      {"devicenet D slot=1 node=0 {\n  node A address=5 model=redistation\n  node B address=5 model=redistation\n}\n",
       "test.bench:3:18: error: address 5 already holds device A"},
      {"devicenet D slot=1 {\n  adapter X\n}\n", "test.bench:2:3: error: a devicenet network's children"},
      {"devicenet D slot=1 node=0 {\n  node A address=7 description=no-such-file.json\n}\n",
       "test.bench:2:32: error: node A: cannot read device description no-such-file.json"},
      {"devicenet D slot=1 node=0 {\n  node A address=7 model=redistation description=x.json\n}\n",
       "test.bench:2:3: error: node A: give model= (a built-in device) or description= (a JSON file), not both"},
      {"devicenet D slot=1 node=0 {\n  node A address=7 {\n    input from=poll to=M1:0/0\n  }\n}\n",
       "test.bench:3:16: warning: node 7: the entry has no poll connection"},
  };
  for (const auto& [bench, expected] : cases) {
    const std::string m = setup_messages(kProgram, bench);
    EXPECT_NE(m.find(expected), std::string::npos) << bench << "\n--- got:\n" << m;
  }
}

TEST(SdnModule, DeviceDescriptionsAreReadBesideTheBench) {
  LoadResult lr = load_program(kProgram, "test.slc");
  ASSERT_TRUE(lr.ok());
  const std::string dir = std::string(SOFTSLC_SOURCE_DIR) + "/examples/ladder/1747-sdn/";
  ModuleSetup good = load_module_setup_text(
      *lr.program, "devicenet D slot=1 node=0 {\n  node S address=5 description=weigh-scale.json\n}\n", dir + "x.bench");
  EXPECT_TRUE(good.ok()) << good.render("test.slc", lr.source);
  ModuleSetup bad = load_module_setup_text(
      *lr.program, "devicenet D slot=1 node=0 {\n  node S address=5 description=device_failure_idle.slc\n}\n",
      dir + "x.bench");
  const std::string m = bad.render("test.slc", lr.source);
  EXPECT_NE(m.find("x.bench:2:32: error: node S: "), std::string::npos) << m;
  // The description's own error is positioned in it (line and column of the first bad byte).
  EXPECT_NE(m.find("device_failure_idle.slc:1:1: syntax error"), std::string::npos) << m;
}

TEST(SdnModule, IllegalScanlistEntryShowsCode71) {
  // An entry whose input lands outside the 150-word M1 data area: the scanner skips it and shows
  // "71 Illegal data in scan list table" for its node (chapter 7).
  Bench b(kProgram,
          "devicenet D slot=1 node=0 {\n  node A address=7 model=redistation {\n    poll rx=1 tx=1\n"
          "    input from=poll bits=8 to=M1:150/0\n  }\n}\n");
  b.run();
  b->run_for(seconds(3));
  EXPECT_EQ(b.i("M1:1.210"), node_status(7, 71));
}

}  // namespace
}  // namespace softslc::test
