// A MicroLogix 1100/1400 whose channel 0 is a Modbus RTU slave, on the line of another MicroLogix's Modbus RTU
// master (issue 16; docs/semantics.md "A MicroLogix as a Modbus RTU slave"): the ladder of both runs, the master's
// MSGs read and write the slave's data table through the controller's Modbus map (vm/modbus_slave.h, the map
// `softslc serve --modbus-rtu` answers with), the slave executes each request at its communications servicing,
// and the configuration's errors name the peer.
//
// Manual facts used:
// - the map: coils 00001-04096 the coil file's bits, contacts 10001-14096, input registers 30001-30256, holding
//   registers 40001-40256 the words of their files, each a B or N file (1763-RM001C p. 530, 1766-RM001A p. 617,
//   "Modbus to MicroLogix Memory Map"); a range outside it or its file is exception 02, Illegal Data Address
//   (Modbus Application Protocol v1.1b3 §7);
// - a slave's exception n gives the master's MSG error code 80h + n: "82H Modbus Error 2: Illegal Data Address"
//   (1747-RM001G p. 12-42; AG-UM008C p. 3-55 for the MicroLogix); 37h "message timed out in local processor" and
//   12h "local channel configuration protocol error" (1766-RM001A p. 466);
// - "Under normal operation the controller processes communications once every time it scans the control
//   program" (1763-RM001B p. 344, 1766-RM001A p. 396), an incoming command at the next SVC or communications
//   servicing, whichever comes first (1766-RM001A p. 410);
// - the commands, the MG element and the line's frame sizes and 3.5-character silence: as
//   tests/micrologix/modbus_msg_test.cpp (docs/micrologix-msg-sources.md section 8).
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "modules/module_setup.h"
#include "parser/loader.h"
#include "vm/runtime.h"

namespace softslc::test {
namespace {

constexpr std::uint16_t kST = 1u << 14, kDN = 1u << 13, kER = 1u << 12;  // MG word 17
constexpr Nanoseconds chars(std::int64_t k, std::int64_t baud = 19200) { return k * 11 * 1'000'000'000LL / baud; }

// The bench's simulated drive makes the master's channel 0 a Modbus RTU master (slave 1 on its line).
constexpr const char* kBench = "modbus VFD slave=1 baud=19200 holding=4\n";

std::string zeros(int n) {
  std::string out;
  for (int i = 0; i < n; ++i) out += i ? " 0" : "0";
  return out;
}

std::string master_program(const std::string& rungs) {
  return "START Bul.1766\nLADDER 2\n" + rungs + "\nDATA B3:0\n% B3:0 % 0 0 0 0\nDATA N7:0\n% N7:0 % " + zeros(20) + "\n";
}

// A slave's program: its rungs, B3 of 4 words and N7 of 20 (the default map's coil, contact, input register and
// holding register files), each word given.
std::string slave_program(const std::string& processor, const std::string& rungs, const std::string& n7 = "") {
  std::string words = n7;
  int given = 0;
  for (std::size_t at = 0; at < n7.size(); ++at)
    if (n7[at] != ' ' && (at == 0 || n7[at - 1] == ' ')) ++given;
  for (int i = given; i < 20; ++i) words += (words.empty() ? "" : " ") + std::string("0");
  return "START " + processor + "\nLADDER 2\n" + rungs + "\nDATA B3:0\n% B3:0 % 0 0 0 0\nDATA N7:0\n% N7:0 % " + words +
         "\n";
}

struct SlaveSpec {
  std::string name = "SLAVE";
  std::string text;
  modbus::SlaveOptions options;
};

Program load(const std::string& text, const std::string& name) {
  LoadResult lr = load_program(text, name);
  if (!lr.ok()) throw std::runtime_error(lr.render_diagnostics());
  return std::move(*lr.program);
}

// The master with its bench and the slaves as peers on its line: the runtime, or the errors.
RuntimeResult build(const std::string& master_rungs, const std::vector<SlaveSpec>& slaves, const std::string& bench = kBench) {
  static std::vector<std::unique_ptr<Program>> keep;  // the master program outlives the runtime
  keep.push_back(std::make_unique<Program>(load(master_program(master_rungs), "master.slc")));
  ModuleSetup setup = bench.empty() ? load_module_setup(*keep.back(), std::nullopt)
                                    : load_module_setup_text(*keep.back(), bench, "master.bench");
  if (!setup.ok()) throw std::runtime_error("the bench did not load");
  for (const SlaveSpec& s : slaves) {
    PeerController p;
    p.name = s.name;
    p.modbus = s.options;
    p.program = std::make_shared<const Program>(load(s.text, s.name + ".slc"));
    p.options = std::make_shared<const RuntimeOptions>();
    setup.options.peers.push_back(std::move(p));
  }
  return Runtime::create(*keep.back(), setup.options);
}

struct Line {
  std::unique_ptr<Runtime> rt;
  Runtime* slave = nullptr;
  Line(const std::string& master_rungs, const std::string& slave_rungs, const std::string& n7 = "",
       const std::string& processor = "Bul.1763") {
    SlaveSpec s;
    s.text = slave_program(processor, slave_rungs, n7);
    s.options.address = 2;
    RuntimeResult r = build(master_rungs, {s});
    if (!r.ok()) throw std::runtime_error(r.render_errors());
    rt = std::move(r.runtime);
    slave = rt->peer("SLAVE");
    if (!slave) throw std::runtime_error("no peer SLAVE");
    if (!rt->set_mode(Mode::Run)) throw std::runtime_error("run");
  }
  std::int64_t i(const std::string& a) const { return rt->value(a).as_int(); }
  std::int64_t s(const std::string& a) const { return slave->value(a).as_int(); }
  void set(const std::string& a, std::int64_t v) {
    if (!rt->set(a, Value::of_int(v))) throw std::runtime_error("set " + a);
  }
  void set_slave(const std::string& a, std::int64_t v) {
    if (!slave->set(a, Value::of_int(v))) throw std::runtime_error("set " + a);
  }
  // Scans the master until MG11:e's word 17 has one of `bits`: the time it was seen.
  std::optional<VirtualTime> until(int e, std::uint16_t bits, Nanoseconds limit) {
    const VirtualTime end = rt->now() + limit;
    while (rt->now() < end) {
      rt->scan(1);
      if (i("MG11:" + std::to_string(e) + ".17") & bits) return rt->now();
    }
    return std::nullopt;
  }
};

// ---- Reads and writes through the map ---------------------------------------------------------------------------

TEST(ModbusSlave, TheMasterReadsHoldingRegistersFromTheSlavesN7) {
  // 03 from slave 2, holding registers 40001-40005: N7:0-4 of the slave (the default map's holding register file).
  Line l("SOR XIC B3:0/0 MSG MG11:0 03 MODBUS LOCAL 0 N7:0 5 2 1 2 EOR", "SOR XIC B3:0/0 OTE B3:0/1 EOR",
         "100 -200 300 32767 -32768");
  l.set("B3:0/0", 1);
  ASSERT_TRUE(l.until(0, kDN | kER, 1'000'000'000));
  EXPECT_EQ(l.i("MG11:0.17") & (kDN | kER), kDN);
  EXPECT_EQ(l.i("N7:0"), 100);
  EXPECT_EQ(l.i("N7:1"), -200);
  EXPECT_EQ(l.i("N7:2"), 300);
  EXPECT_EQ(l.i("N7:3"), 32767);
  EXPECT_EQ(l.i("N7:4"), -32768);
  // The slave's current values, not what it had at power-up: the next read sees its ladder's change.
  l.set("B3:0/0", 0);
  l.rt->scan(1);
  l.set_slave("N7:2", 4321);
  l.set("B3:0/0", 1);
  ASSERT_TRUE(l.until(0, kDN | kER, 1'000'000'000));
  EXPECT_EQ(l.i("N7:2"), 4321);
  EXPECT_EQ(l.i("N7:7"), 0);  // the master's own N7 past the five elements is untouched
}

TEST(ModbusSlave, CoilWritesLandInTheSlavesB3WhereItsLadderSeesThem) {
  // 05 writes coil 6 (B3:0/5 of the slave) from the master's B3:1/0; the slave's ladder seals B3:0/6 (coil 7) in
  // and counts the writes into N7:10; 01 reads coils 1-16 back into the master's B3:2.
  Line l("SOR XIC B3:0/1 MSG MG11:1 05 MODBUS LOCAL 0 B3:1/0 1 2 6 2 EOR\n"
         "SOR XIC B3:0/2 MSG MG11:2 01 MODBUS LOCAL 0 B3:2/0 16 2 1 2 EOR",
         "SOR BST XIC B3:0/5 NXB XIC B3:0/6 BND OTE B3:0/6 EOR\n"
         "SOR XIC B3:0/5 ONS B3:3/0 ADD N7:10 1 N7:10 EOR");
  l.set("B3:1/0", 1);
  l.set("B3:0/1", 1);
  ASSERT_TRUE(l.until(1, kDN | kER, 1'000'000'000));
  EXPECT_EQ(l.i("MG11:1.17") & (kDN | kER), kDN);
  EXPECT_EQ(l.s("B3:0/5"), 1);
  l.rt->scan(2);  // the peer scans in lockstep with the master: its ladder sees the coil in its next scan
  EXPECT_EQ(l.s("B3:0/6"), 1);
  EXPECT_EQ(l.s("N7:10"), 1);
  // The master reads the seal-in back: coils 6 and 7 are bits 5 and 6 of its B3:2.
  l.set("B3:0/2", 1);
  ASSERT_TRUE(l.until(2, kDN | kER, 1'000'000'000));
  EXPECT_EQ(l.i("MG11:2.17") & (kDN | kER), kDN);
  EXPECT_EQ(l.i("B3:2"), 0b110'0000);
  // Writing the coil 0 again: the slave's B3:0/5 goes off, its seal-in holds.
  l.set("B3:0/1", 0);
  l.rt->scan(1);
  l.set("B3:1/0", 0);
  l.set("B3:0/1", 1);
  ASSERT_TRUE(l.until(1, kDN | kER, 1'000'000'000));
  EXPECT_EQ(l.s("B3:0/5"), 0);
  EXPECT_EQ(l.s("B3:0/6"), 1);
}

TEST(ModbusSlave, EveryCommandGoesThroughTheMap) {
  // 02 reads contacts (B3 here too), 04 input registers (N7), 06 and 16 write holding registers, 15 coils.
  Line l("SOR XIC B3:0/0 MSG MG11:0 02 MODBUS LOCAL 0 B3:2/4 4 2 17 2 EOR\n"
         "SOR XIC B3:0/1 MSG MG11:1 04 MODBUS LOCAL 0 N7:0 2 2 19 2 EOR\n"
         "SOR XIC B3:0/2 MSG MG11:2 06 MODBUS LOCAL 0 N7:5 1 2 4 2 EOR\n"
         "SOR XIC B3:0/3 MSG MG11:3 16 MODBUS LOCAL 0 N7:6 3 2 12 2 EOR\n"
         "SOR XIC B3:0/4 MSG MG11:4 15 MODBUS LOCAL 0 B3:1/0 10 2 33 2 EOR",
         "", "0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 -5 77");
  l.set_slave("B3:1", 0b1011);  // contacts 17-20: bits 0-3 of word 1
  l.set("N7:5", 555);
  l.set("N7:6", 1);
  l.set("N7:7", -2);
  l.set("N7:8", 3);
  l.set("B3:1", 0b10'1100'0101);
  l.set("B3:0", 0x1F);
  for (int e = 0; e < 5; ++e) {
    ASSERT_TRUE(l.until(e, kDN | kER, 1'000'000'000)) << e;
    EXPECT_EQ(l.i("MG11:" + std::to_string(e) + ".17") & (kDN | kER), kDN) << e;
  }
  EXPECT_EQ(l.i("B3:2"), 0b1011 << 4);     // 02: contacts 17-20 into B3:2/4-7
  EXPECT_EQ(l.i("N7:0"), -5);              // 04: input registers 30019-30020, the slave's N7:18-19
  EXPECT_EQ(l.i("N7:1"), 77);
  EXPECT_EQ(l.s("N7:3"), 555);             // 06: holding register 40004
  EXPECT_EQ(l.s("N7:11"), 1);              // 16: 40012-40014
  EXPECT_EQ(l.s("N7:12"), -2);
  EXPECT_EQ(l.s("N7:13"), 3);
  EXPECT_EQ(l.s("B3:2") & 0x3FF, 0b10'1100'0101);  // 15: coils 33-42, bits 0-9 of the slave's B3:2
}

// The slave's message counters, input registers 30518-30531 of its communication parameters (1766-RM001A p. 618
// "Modbus Slave to MicroLogix Memory Map - Detail": messages to this slave per function code 1, 2, 3, 4, 5, 6, 8,
// 15, 16 at 30518-30526, 30528 total messages responded to by this slave, 30529 total messages to this slave,
// 30530 total messages seen, 30531 link layer error count), counted as serve's slave counts them: every frame on
// the line seen, the request counted before it is executed and its reply after. Here the line carries a read of
// 40001 from slave 2, a read of slave 3 (nobody: seen, not to this slave, no reply) and then slave 2's own
// counters read by function 04: three seen, two to it, one 03 and one 04, one responded (the 04's own reply
// comes after it is read).
TEST(ModbusSlave, TheSlaveCountsTheMessagesItSeesAndAnswers) {
  Line l("SOR XIC B3:0/0 MSG MG11:0 03 MODBUS LOCAL 0 N7:0 1 2 1 2 EOR\n"
         "SOR XIC B3:0/1 MSG MG11:1 03 MODBUS LOCAL 0 N7:1 1 3 1 2 EOR\n"
         "SOR XIC B3:0/2 MSG MG11:2 04 MODBUS LOCAL 0 N7:2 14 2 518 2 EOR",
         "", "42");
  l.set("B3:0/0", 1);
  ASSERT_TRUE(l.until(0, kDN | kER, 1'000'000'000));
  EXPECT_EQ(l.i("N7:0"), 42);
  l.set("B3:0/1", 1);
  ASSERT_TRUE(l.until(1, kDN | kER, 3'000'000'000));
  EXPECT_EQ(l.i("MG11:1.ERR"), 0x37);  // slave 3 is nobody
  l.set("B3:0/2", 1);
  ASSERT_TRUE(l.until(2, kDN | kER, 1'000'000'000));
  ASSERT_EQ(l.i("MG11:2.17") & (kDN | kER), kDN);
  const std::int64_t expected[14] = {0, 0, 1, 1, 0, 0, 0, 0, 0,  // 30518-30526: one 03, one 04
                                     0,                          // 30527 modem status
                                     1, 2, 3,                    // 30528 responded, 30529 to this slave, 30530 seen
                                     0};                         // 30531 link layer errors
  for (int i = 0; i < 14; ++i) EXPECT_EQ(l.i("N7:" + std::to_string(2 + i)), expected[i]) << "register " << 30518 + i;
}

// ---- Exceptions and no reply --------------------------------------------------------------------------------------

TEST(ModbusSlave, AnAddressOutsideTheMapOrItsFileIsException02Error82h) {
  // 40256-40257 run past the 256 holding registers of the map; 40020-40021 past the slave's 20-word N7;
  // coils 65-66 past its 4-word B3. Each is exception 02: MSG error 82h, ER.
  Line l("SOR XIC B3:0/0 MSG MG11:0 03 MODBUS LOCAL 0 N7:0 2 2 256 2 EOR\n"
         "SOR XIC B3:0/1 MSG MG11:1 16 MODBUS LOCAL 0 N7:2 2 2 20 2 EOR\n"
         "SOR XIC B3:0/2 MSG MG11:2 15 MODBUS LOCAL 0 B3:1/0 2 2 64 2 EOR\n"
         "SOR XIC B3:0/3 MSG MG11:3 03 MODBUS LOCAL 0 N7:4 1 2 20 2 EOR",
         "", "1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20");
  l.set("N7:2", 99);
  l.set("B3:0", 0xF);
  for (int e = 0; e < 4; ++e) ASSERT_TRUE(l.until(e, kDN | kER, 1'000'000'000)) << e;
  for (int e = 0; e < 3; ++e) {
    EXPECT_EQ(l.i("MG11:" + std::to_string(e) + ".17") & (kDN | kER), kER) << e;
    EXPECT_EQ(l.i("MG11:" + std::to_string(e) + ".ERR"), 0x82) << e;
  }
  EXPECT_EQ(l.s("N7:19"), 20);  // the refused 16 wrote nothing
  // 40020 alone is the slave's last N7 word.
  EXPECT_EQ(l.i("MG11:3.17") & (kDN | kER), kDN);
  EXPECT_EQ(l.i("N7:4"), 20);
}

TEST(ModbusSlave, AnAddressNobodyHasTimesOutWith37h) {
  // Slave 3 is on nobody's channel: no reply, the line waits until the 2 s timeout: ER, TO, 37h.
  Line l("SOR XIC B3:0/0 MSG MG11:0 03 MODBUS LOCAL 0 N7:0 1 3 1 2 EOR", "");
  l.set("B3:0/0", 1);
  l.rt->scan(1);
  const VirtualTime started = l.rt->now();
  const auto end = l.until(0, kDN | kER, 3'000'000'000);
  ASSERT_TRUE(end);
  EXPECT_EQ(l.i("MG11:0.ERR"), 0x37);
  EXPECT_GE(*end - started + 1'000'000, 2'000'000'000);
  EXPECT_LE(*end - started, 2'002'000'000);
}

TEST(ModbusSlave, ASlaveAtAnotherBaudRateHearsNothing) {
  SlaveSpec s;
  s.text = slave_program("Bul.1763", "", "7");
  s.options.address = 2;
  s.options.baud = 9600;  // the master's line runs at 19,200
  RuntimeResult r = build("SOR XIC B3:0/0 MSG MG11:0 03 MODBUS LOCAL 0 N7:0 1 2 1 2 EOR", {s});
  ASSERT_TRUE(r.ok()) << r.render_errors();
  Runtime& rt = *r.runtime;
  ASSERT_TRUE(rt.set_mode(Mode::Run));
  ASSERT_TRUE(rt.set("B3:0/0", Value::of_int(1)));
  rt.run_for(2'100'000'000);
  EXPECT_EQ(rt.value("MG11:0.ERR").as_int(), 0x37);
  EXPECT_EQ(rt.value("N7:0").as_int(), 0);
}

TEST(ModbusSlave, ABroadcastWriteReachesTheSlaveAndTheBenchsDrive) {
  Line l("SOR XIC B3:0/0 MSG MG11:0 06 MODBUS LOCAL 0 N7:0 1 0 2 2 EOR", "");
  l.set("N7:0", 1500);
  l.set("B3:0/0", 1);
  ASSERT_TRUE(l.until(0, kDN | kER, 1'000'000'000));
  EXPECT_EQ(l.i("MG11:0.17") & (kDN | kER), kDN);
  EXPECT_EQ(l.rt->observe("VFD", "holding").value().at(1), 1500);
  // The slave executes it at its next servicing, after the frame's 3.5 characters; no reply is awaited.
  l.rt->run_for(10'000'000);
  EXPECT_EQ(l.s("N7:1"), 1500);
}

// ---- When the slave answers -----------------------------------------------------------------------------------

// The slave executes the request at its end of scan (or an SVC), after the request's last byte and 3.5 characters
// of silence, and its reply starts then. A slave whose scan is long answers late; one whose ladder services
// channel 0 with an SVC at the top of each scan answers a request that arrived before the scan at that SVC.
TEST(ModbusSlave, TheSlaveAnswersAtItsCommunicationsServicing) {
  // A slow slave: 120 rungs of CPT make a scan of several ms on the 1100 (its timing profile).
  std::string slow;
  for (int k = 0; k < 120; ++k) slow += "SOR CPT N7:15 N7:16*N7:17+N7:18*N7:19-N7:16 EOR\n";
  auto transaction = [&](const std::string& first_rung) {
    Line l("SOR XIC B3:0/0 MSG MG11:0 03 MODBUS LOCAL 0 N7:0 1 2 1 2 EOR", first_rung + slow, "42");
    std::vector<VirtualTime> ends;
    l.slave->set_scan_observer([&ends](const Runtime& r) { ends.push_back(r.now()); });
    l.set("B3:0/0", 1);
    const auto st = l.until(0, kST | kDN | kER, 1'000'000'000);
    const auto dn = l.until(0, kDN | kER, 1'000'000'000);
    EXPECT_TRUE(st && dn);
    EXPECT_EQ(l.i("N7:0"), 42);
    const Nanoseconds slave_scan = l.slave->stats().last;
    const Nanoseconds master_scan = l.rt->stats().last;
    return std::tuple{*dn - *st, slave_scan, master_scan, ends};
  };
  const auto [at_end, slave_scan, master_scan, ends] = transaction("");
  ASSERT_GT(slave_scan, 4'000'000) << "the slave's scan is meant to be long";
  // ST to DN: at least the silence and the 7-byte reply; a slave answering at once would be that within a master
  // scan; this one waits for its end of scan, up to one scan more.
  const Nanoseconds line = chars(7) / 2 + chars(7);
  EXPECT_GE(at_end + master_scan, line);
  EXPECT_LE(at_end, line + slave_scan + master_scan);
}

// ---- The slave's own channel 0 ----------------------------------------------------------------------------------

TEST(ModbusSlave, TheSlavesChannel0SendsNoMsg12h) {
  // A Modbus RTU slave channel originates no messages: a PCCC MSG and a Modbus MSG on it end with 12h.
  Line l("SOR OTE B3:0/7 EOR",
         "SOR XIC B3:0/0 MSG MG11:0 READ 500CPU LOCAL 0 N7:0 1 1 N7:0 2 EOR\n"
         "SOR XIC B3:0/0 MSG MG11:1 03 MODBUS LOCAL 0 N7:1 1 1 1 2 EOR");
  l.set_slave("B3:0/0", 1);
  l.rt->scan(3);
  EXPECT_EQ(l.s("MG11:0.ERR"), 0x12);
  EXPECT_EQ(l.s("MG11:1.ERR"), 0x12);
}

// ---- Configuration errors ---------------------------------------------------------------------------------------

std::string errors_with(const std::vector<SlaveSpec>& slaves, const std::string& bench = kBench) {
  RuntimeResult r = build("SOR OTE B3:0/0 EOR", slaves, bench);
  return r.ok() ? std::string() : r.render_errors();
}

SlaveSpec slave_at(int address, const std::string& name = "SLAVE", const std::string& processor = "Bul.1763") {
  SlaveSpec s;
  s.name = name;
  s.text = slave_program(processor, "");
  s.options.address = address;
  return s;
}

TEST(ModbusSlave, TheLineIsChecked) {
  EXPECT_EQ(errors_with({slave_at(2), slave_at(3, "OTHER", "Bul.1766")}), "");
  // No Modbus master on the leader's channel 0 (no bench modbus node).
  std::string e = errors_with({slave_at(2)}, "");
  EXPECT_NE(e.find("peer SLAVE: a Modbus RTU slave answers a Modbus RTU master on its line, but this controller's "
                   "channel 0 is not one"),
            std::string::npos)
      << e;
  // An address the bench's drive has, another peer has, or out of range.
  e = errors_with({slave_at(1)});
  EXPECT_NE(e.find("peer SLAVE: Modbus address 1 is already the bench's modbus node VFD's"), std::string::npos) << e;
  e = errors_with({slave_at(2), slave_at(2, "OTHER")});
  EXPECT_NE(e.find("peer OTHER: Modbus address 2 is already peer SLAVE's"), std::string::npos) << e;
  for (int bad : {0, 248}) {
    e = errors_with({slave_at(bad)});
    EXPECT_NE(e.find("peer SLAVE: Modbus address " + std::to_string(bad) + " is out of range 1-247"), std::string::npos)
        << e;
  }
  // The Modbus memory map is the 1100's and 1400's.
  e = errors_with({slave_at(2, "SLAVE", "1764-LSP")});
  EXPECT_NE(e.find("peer SLAVE: a Modbus RTU slave channel 0 with the Modbus memory map is the MicroLogix 1100's"),
            std::string::npos)
      << e;
  // The map's files must be B or N files of the slave's program (as serve checks --modbus-map).
  SlaveSpec s = slave_at(2);
  s.options.map.holding_registers = 9;
  e = errors_with({s});
  EXPECT_NE(e.find("peer SLAVE: map: the Modbus holding register file must be a B or N file numbered 3-255"),
            std::string::npos)
      << e;
}

TEST(ModbusSlave, TheSettingsParse) {
  modbus::SlaveOptions o;
  EXPECT_EQ(modbus::parse_slave_option("address=17", o), "");
  EXPECT_EQ(o.address, 17);
  EXPECT_EQ(modbus::parse_slave_option("baud=9600", o), "");
  EXPECT_EQ(o.baud, 9600);
  EXPECT_EQ(modbus::parse_slave_option("map=B10,B11,N12,N13", o), "");
  EXPECT_EQ(o.map.coils, 10);
  EXPECT_EQ(o.map.holding_registers, 13);
  EXPECT_NE(modbus::parse_slave_option("address=248", o).find("1-247"), std::string::npos);
  EXPECT_NE(modbus::parse_slave_option("address=0", o).find("1-247"), std::string::npos);
  EXPECT_NE(modbus::parse_slave_option("baud=14400", o).find("AG-UM008C p. 3-49"), std::string::npos);
  EXPECT_NE(modbus::parse_slave_option("map=B3,B3,N7", o).find("four data files"), std::string::npos);
  EXPECT_NE(modbus::parse_slave_option("parity=even", o).find("not a Modbus RTU slave setting"), std::string::npos);
}

}  // namespace
}  // namespace softslc::test
