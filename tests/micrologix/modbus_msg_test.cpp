// The MicroLogix 1100/1400 MSG as a Modbus RTU master on channel 0 (issue 16; docs/semantics.md "The MicroLogix
// MSG over Modbus RTU"): the text form and its checks, the setup in the MG element, the eight commands moving
// bits and words between the data table and simulated slaves (the bench's `modbus` nodes), the line's timing,
// broadcast writes, exception replies, the timeout and the bench's checks.
//
// Manual facts used (docs/micrologix-msg-sources.md section 8 has them with their pages):
// - the eight commands, 01 Read Coil Status and 02 Read Input Status "reading bits", 03 Read Holding Registers and
//   04 Read Input Registers "reading words", 05 Write Single Coil "writing 1 bit", 06 Write Single Register
//   "writing 1 word", 15 Write Multiple Coil, 16 Write Multiple Registers (1763-RM001B p. 366);
// - MG element for a Modbus device: word 12 "starting bit address for coils and inputs", word 13 "Modbus Target
//   Data Address - 1" (1763-RM001B p. 350); word 2 the messaging type, 2 = Modbus master; word 3 the function
//   code; word 11 the number of elements (1763-RM001B p. 347-348, 1766-RM001A p. 399-400); on the 1200/1500 word 2
//   is reserved (1762-RM001C p. 21-4);
// - "MB Data Address (1-65536)", decremented by 1 when sent (1747-RM001G p. 12-22, the same setup screen);
//   B and N data only, a bit address for 01/02/05/15, a word address for 03/04/06/16 (1747-RM001G p. 12-18);
// - ST: "on DF1 radio modem and Modbus RTU master, which have no ACK, ST is set when the message has been sent"
//   (1763-RM001B p. 355); the timeout, 0 = never, "Timing begins when the false-to-true rung transition occurs"
//   (1762-RM001C p. 21-12); 37h "message timed out in local processor" (1766-RM001A p. 466);
// - a slave's exception n gives error code 80h + n: 81h Illegal Function, 82h Illegal Data Address, 84h Slave
//   Device Failure (1747-RM001G p. 12-42; AG-UM008C p. 3-55); 12h "local channel configuration protocol error"
//   and 18h "broadcast not supported" (1766-RM001A p. 466).
// Decisions (docs/semantics.md): an RTU character is 11 bits; a slave replies 3.5 character times after the
// request plus its reply_delay (default 2 ms); frame sizes of the Modbus RTU serial line (a read request 8 bytes,
// a register read reply 5 + 2n); one transaction on the line at a time.
#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <string>

#include "modules/module_setup.h"
#include "parser/formatter.h"
#include "parser/loader.h"
#include "tools/controller/controller.h"
#include "vm/runtime.h"

namespace softslc::test {
namespace {

constexpr std::uint16_t kEN = 1u << 15, kTO = 1u << 8;                         // word 16
constexpr std::uint16_t kST = 1u << 14, kDN = 1u << 13, kER = 1u << 12, kEW = 1u << 10;  // word 17
// 11 bits at 19,200 baud: 572,916.67 ns a character.
constexpr Nanoseconds chars(std::int64_t k, std::int64_t baud = 19200) { return k * 11 * 1'000'000'000LL / baud; }

std::string program(const std::string& rungs, const std::string& processor = "Bul.1766") {
  return "START " + processor + "\nLADDER 2\n" + rungs + "\nDATA N7:0\n% N7:0 % 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0\n";
}

// Errors come as the Controller's exception, rendered gcc-style with the file names given here.
std::string errors_of(const std::string& text, const std::string& bench = "") {
  try {
    Controller::from_text(text, bench, "mb.slc", "mb.bench");
  } catch (const ControllerError& e) {
    return e.what();
  }
  return "";
}

constexpr const char* kBench =
    "modbus VFD slave=1 baud=19200 coils=16 inputs=16 holding=10 input_registers=10\n"
    "modbus METER slave=2 holding=4 functions=3,16\n";

struct Plc {
  Controller c;
  Runtime* rt;
  explicit Plc(const std::string& rungs, const std::string& bench = kBench)
      : c(Controller::from_text(program(rungs), bench, "mb.slc", "mb.bench")), rt(&c.runtime()) {}
  Runtime* operator->() { return rt; }
  std::int64_t i(const std::string& a) { return rt->value(a).as_int(); }
  std::uint16_t w(const std::string& a) { return static_cast<std::uint16_t>(rt->value(a).as_int()); }
  void set(const std::string& a, std::int64_t v) {
    if (!rt->set(a, Value::of_int(v))) throw std::runtime_error("set " + a);
  }
  void inject(const std::string& dev, const std::string& what, std::vector<std::string> args) {
    if (!rt->inject(dev, what, std::move(args))) throw std::runtime_error("inject " + what);
  }
  std::vector<std::int64_t> observe(const std::string& dev, const std::string& what) {
    return rt->observe(dev, what).value_or(std::vector<std::int64_t>{});
  }
  // Scans until MG11:e's status word has one of `bits`, at most `limit` of virtual time: the time it was seen.
  std::optional<VirtualTime> until(int e, std::uint16_t bits, Nanoseconds limit) {
    const VirtualTime end = rt->now() + limit;
    while (rt->now() < end) {
      rt->scan(1);
      if (w("MG11:" + std::to_string(e) + ".17") & bits) return rt->now();
    }
    return std::nullopt;
  }
};

// ---- The text form and check ----------------------------------------------------------------------------------

TEST(ModbusMsg, The1100And1400TakeTheFormThe1200And1500DoNot) {
  const std::string rung = "SOR XIC B3:0/0 MSG MG11:0 03 MODBUS LOCAL 0 N7:0 5 1 1 2 EOR";
  EXPECT_EQ(errors_of(program(rung, "Bul.1763")), "");
  EXPECT_EQ(errors_of(program(rung, "Bul.1766")), "");
  // 1762-RM001C p. 21-4: MG sub-element 2 (the messaging type) is reserved on the 1200 and 1500.
  for (const char* p : {"Bul.1762", "1764-LRP"}) {
    const std::string e = errors_of(program(rung, p));
    EXPECT_NE(e.find("mb.slc:3:30: error: MSG MODBUS: the"), std::string::npos) << e;
    EXPECT_NE(e.find("reserved on the MicroLogix 1200 and 1500 (1762-RM001C p. 21-4)"), std::string::npos) << e;
  }
  // The SLC's MSG and the MicroLogix 1000's have no MODBUS device in softslc.
  const std::string slc = errors_of(program("SOR XIC B3:0/0 MSG READ MODBUS LOCAL N9:0 14 1 N7:0 5 2 N10:0 5 EOR",
                                            "1747-L532"));
  EXPECT_NE(slc.find("MSG MODBUS is the MicroLogix 1100/1400 form"), std::string::npos) << slc;
}

TEST(ModbusMsg, CheckNamesWhatIsWrongWhereItIs) {
  struct Case {
    const char* rung;
    const char* expected;
  };
  const Case cases[] = {
      // Not one of the eight commands of 1763-RM001B p. 366.
      {"SOR MSG MG11:0 07 MODBUS LOCAL 0 N7:0 1 1 1 2 EOR", "3:16: error: MSG MODBUS command '07'"},
      // READ with MODBUS, and a Modbus command with 500CPU.
      {"SOR MSG MG11:0 READ MODBUS LOCAL 0 N7:0 1 1 1 2 EOR", "3:16: error: MSG MODBUS command 'READ'"},
      {"SOR MSG MG11:0 03 500CPU LOCAL 0 N7:0 1 1 N10:0 2 EOR", "3:16: error: MSG command 03: a Modbus command"},
      // 1747-RM001G p. 12-18: bit commands need a bit address, register commands a word address, B and N only.
      {"SOR MSG MG11:0 03 MODBUS LOCAL 0 N7:0/3 1 1 1 2 EOR", "3:34: error: MSG MODBUS 03 moves registers"},
      {"SOR MSG MG11:0 01 MODBUS LOCAL 0 B3:0 8 1 1 2 EOR", "3:34: error: MSG MODBUS 01 moves bits"},
      {"SOR MSG MG11:0 03 MODBUS LOCAL 0 F8:0 1 1 1 2 EOR", "3:34: error: MSG MODBUS data F8:0: only B and N files"},
      // 06 writes one register (p. 366: "writing 1 word").
      {"SOR MSG MG11:0 06 MODBUS LOCAL 0 N7:0 2 1 1 2 EOR", "3:39: error: MSG MODBUS 06 writes one register"},
      // Slave 0 is a broadcast, writes only; 248 is past 247.
      {"SOR MSG MG11:0 03 MODBUS LOCAL 0 N7:0 1 0 1 2 EOR", "3:41: error: MSG MODBUS slave address 0 is a broadcast"},
      {"SOR MSG MG11:0 16 MODBUS LOCAL 0 N7:0 1 248 1 2 EOR", "3:41: error: MSG MODBUS slave address 248"},
      // The Modbus data address is 1-65536 (1747-RM001G p. 12-22).
      {"SOR MSG MG11:0 03 MODBUS LOCAL 0 N7:0 1 1 0 2 EOR", "3:43: error: MSG MODBUS target address 0"},
      {"SOR MSG MG11:0 03 MODBUS LOCAL 0 N7:0 5 1 65533 2 EOR", "3:43: error: MSG MODBUS 5 elements from Modbus address 65533"},
      // Channel 1 is the Ethernet port.
      {"SOR MSG MG11:0 03 MODBUS LOCAL 1 N7:0 1 1 1 2 EOR", "3:32: error: MSG MODBUS on channel 1"},
      {"SOR MSG MG11:0 03 MODBUS REMOTE 0 N7:0 1 1 1 2 EOR", "3:26: error: MSG MODBUS is LOCAL"},
  };
  for (const Case& c : cases) {
    const std::string e = errors_of(program(c.rung));
    EXPECT_NE(e.find(std::string("mb.slc:") + c.expected), std::string::npos) << c.rung << "\n" << e;
  }
}

TEST(ModbusMsg, FmtWritesTheCommandInTwoDigitsAsRsLogixShowsIt) {
  // RSLogix: "Modbus Command: 03 Read Holding Registers" (the command numbers of 1763-RM001B p. 366).
  LoadResult first = load_program(program("SOR MSG MG11:0 3 MODBUS LOCAL 0 N7:0 5 1 1 2 EOR\n"
                                          "SOR MSG MG11:1 16 MODBUS LOCAL 0 N7:5 2 0 7 2 EOR"),
                                  "mb.slc");
  ASSERT_TRUE(first.ok()) << first.render_diagnostics();
  const std::string formatted = format_program(*first.program);
  EXPECT_NE(formatted.find("MSG MG11:0 03 MODBUS LOCAL 0 N7:0 5 1 1 2"), std::string::npos) << formatted;
  EXPECT_NE(formatted.find("MSG MG11:1 16 MODBUS LOCAL 0 N7:5 2 0 7 2"), std::string::npos) << formatted;
  LoadResult second = load_program(formatted, "mb.slc");
  ASSERT_TRUE(second.ok()) << second.render_diagnostics();
  EXPECT_EQ(format_program(*second.program), formatted);
}

TEST(ModbusMsg, TheSetupGoesIntoTheMgElement) {
  Plc p("SOR XIC B3:0/0 MSG MG11:0 01 MODBUS LOCAL 0 B3:1/3 10 7 40 2 EOR");
  // 1763-RM001B pp. 347-350: word 2 = 2 (Modbus master), 3 the function code, 9 the slave, 10 MTO, 11 the
  // elements, 12 the starting bit, 13 the Modbus address - 1; word 17 bit 0 R = 1 (local).
  EXPECT_EQ(p.i("MG11:0.2"), 2);
  EXPECT_EQ(p.i("MG11:0.3"), 1);
  EXPECT_EQ(p.i("MG11:0.8"), 0);
  EXPECT_EQ(p.i("MG11:0.9"), 7);
  EXPECT_EQ(p.i("MG11:0.10"), 2);
  EXPECT_EQ(p.i("MG11:0.11"), 10);
  EXPECT_EQ(p.i("MG11:0.12"), 3);
  EXPECT_EQ(p.i("MG11:0.13"), 39);
  EXPECT_EQ(p.i("MG11:0.17"), 1);
}

// ---- The commands ------------------------------------------------------------------------------------------------

TEST(ModbusMsg, ReadHoldingRegistersTakesTheFramesTimeOnTheLine) {
  Plc p("SOR XIC B3:0/0 MSG MG11:0 03 MODBUS LOCAL 0 N7:0 5 1 3 2 EOR");
  p.inject("VFD", "holding", {"2", "100", "-200", "300", "400", "500"});
  p.set("B3:0/0", 1);
  p->scan(1);
  const VirtualTime started = p->now();  // the end of the scan whose MSG started it
  EXPECT_EQ(p.w("MG11:0.16") & kEN, kEN);
  EXPECT_EQ(p.w("MG11:0.17") & (kEW | kST), kEW);
  // The request: 8 bytes (address, function, start, count, CRC) at 11 bits a character, 19,200 baud.
  const auto st = p.until(0, kST, 1'000'000'000);
  ASSERT_TRUE(st);
  EXPECT_EQ(p.w("MG11:0.17") & (kEW | kDN), 0);  // ST without DN: sent, no reply yet; EW cleared
  EXPECT_LE(*st - started, chars(8));
  // DN: the request, 3.5 characters of silence, the slave's 2 ms, the reply of 5 + 2 x 5 = 15 bytes.
  const auto dn = p.until(0, kDN | kER, 1'000'000'000);
  ASSERT_TRUE(dn);
  const Nanoseconds transaction = chars(8) + chars(7) / 2 + 2'000'000 + chars(15);
  EXPECT_GE(*dn - started + 1'000'000, transaction);  // the MSG ran less than a scan before `started`
  EXPECT_LE(*dn - started, transaction + 1'000'000);
  EXPECT_EQ(p.w("MG11:0.17") & (kST | kDN | kER), kDN);
  // Modbus address 3 is index 2 of the slave's holding registers.
  EXPECT_EQ(p.i("N7:0"), 100);
  EXPECT_EQ(p.i("N7:1"), -200);
  EXPECT_EQ(p.i("N7:4"), 500);
  EXPECT_EQ(p.observe("VFD", "requests"), std::vector<std::int64_t>{1});
}

TEST(ModbusMsg, EachCommandMovesItsDataBitsOrWords) {
  Plc p("SOR XIC B3:0/0 MSG MG11:0 01 MODBUS LOCAL 0 B3:1/3 10 1 1 2 EOR\n"
        "SOR XIC B3:0/1 MSG MG11:1 02 MODBUS LOCAL 0 N7:10/14 4 1 5 2 EOR\n"
        "SOR XIC B3:0/2 MSG MG11:2 04 MODBUS LOCAL 0 N7:12 3 1 8 2 EOR\n"
        "SOR XIC B3:0/3 MSG MG11:3 05 MODBUS LOCAL 0 B3:2/9 1 1 16 2 EOR\n"
        "SOR XIC B3:0/4 MSG MG11:4 06 MODBUS LOCAL 0 N7:15 1 1 10 2 EOR\n"
        "SOR XIC B3:0/5 MSG MG11:5 15 MODBUS LOCAL 0 B3:3/0 3 1 12 2 EOR\n"
        "SOR XIC B3:0/6 MSG MG11:6 16 MODBUS LOCAL 0 N7:16 2 1 1 2 EOR");
  p.inject("VFD", "coils", {"0", "1", "0", "1", "1", "0", "0", "1", "1", "1", "0"});
  p.inject("VFD", "inputs", {"4", "1", "1", "0", "1"});
  p.inject("VFD", "input_registers", {"7", "-1", "2", "32767"});
  p.set("B3:2/9", 1);
  p.set("N7:15", 1234);
  p.set("B3:3", 0b101);
  p.set("N7:16", 11);
  p.set("N7:17", -12);
  p.set("B3:0", 0x7F);
  for (int e = 0; e < 7; ++e) ASSERT_TRUE(p.until(e, kDN | kER, 2'000'000'000)) << e;
  for (int e = 0; e < 7; ++e) EXPECT_EQ(p.w("MG11:" + std::to_string(e) + ".17") & (kDN | kER), kDN) << e;
  // 01: coils 1-10 into B3:1 bits 3-12.
  const int coils[] = {1, 0, 1, 1, 0, 0, 1, 1, 1, 0};
  for (int k = 0; k < 10; ++k) EXPECT_EQ(p.i("B3:1/" + std::to_string(3 + k)), coils[k]) << k;
  EXPECT_EQ(p.i("B3:1/2"), 0);
  // 02: inputs 5-8 into N7:10 bits 14, 15 and N7:11 bits 0, 1 (the bits run on into the next word).
  EXPECT_EQ(p.i("N7:10/14"), 1);
  EXPECT_EQ(p.i("N7:10/15"), 1);
  EXPECT_EQ(p.i("N7:11/0"), 0);
  EXPECT_EQ(p.i("N7:11/1"), 1);
  // 04: input registers 8-10.
  EXPECT_EQ(p.i("N7:12"), -1);
  EXPECT_EQ(p.i("N7:13"), 2);
  EXPECT_EQ(p.i("N7:14"), 32767);
  // 05, 06, 15, 16 write the slave's coils and holding registers.
  const auto c = p.observe("VFD", "coils");
  ASSERT_EQ(c.size(), 16u);
  EXPECT_EQ(c[15], 1);                                         // 05: coil 16 from B3:2/9
  EXPECT_EQ((std::vector<std::int64_t>{c[11], c[12], c[13]}), (std::vector<std::int64_t>{1, 0, 1}));  // 15
  const auto h = p.observe("VFD", "holding");
  EXPECT_EQ(h[9], 1234);  // 06: register 10
  EXPECT_EQ(h[0], 11);    // 16: registers 1-2
  EXPECT_EQ(h[1], -12);
}

TEST(ModbusMsg, OneTransactionOnTheLineAtATime) {
  // Two reads started in one scan: the second request goes out 3.5 characters after the first reply.
  Plc p("SOR XIC B3:0/0 MSG MG11:0 03 MODBUS LOCAL 0 N7:0 1 1 1 2 EOR\n"
        "SOR XIC B3:0/0 MSG MG11:1 03 MODBUS LOCAL 0 N7:1 1 2 1 2 EOR");
  p.set("B3:0/0", 1);
  p->scan(1);
  const VirtualTime started = p->now();
  // Both in buffers (EW), one on the line.
  EXPECT_EQ(p.w("MG11:1.17") & kEW, kEW);
  const auto first = p.until(0, kDN, 1'000'000'000);
  ASSERT_TRUE(first);
  EXPECT_EQ(p.w("MG11:1.17") & kDN, 0);
  const auto second = p.until(1, kDN, 1'000'000'000);
  ASSERT_TRUE(second);
  const Nanoseconds one = chars(8) + chars(7) / 2 + 2'000'000 + chars(7);  // a one-register reply is 7 bytes
  EXPECT_GE(*second - started + 1'000'000, 2 * one + chars(7) / 2);
}

TEST(ModbusMsg, BroadcastWriteReachesEverySlaveAndEndsWhenSent) {
  Plc p("SOR XIC B3:0/0 MSG MG11:0 16 MODBUS LOCAL 0 N7:0 2 0 1 2 EOR");
  p.set("N7:0", 5);
  p.set("N7:1", 6);
  p.set("B3:0/0", 1);
  p->scan(1);
  const VirtualTime started = p->now();
  const auto dn = p.until(0, kDN | kER, 1'000'000'000);
  ASSERT_TRUE(dn);
  EXPECT_EQ(p.w("MG11:0.17") & (kDN | kER | kST), kDN);
  // No reply: DN once the request's 9 + 2 x 2 = 13 bytes have gone.
  EXPECT_LE(*dn - started, chars(13) + 1'000'000);
  EXPECT_EQ(p.observe("VFD", "holding")[0], 5);
  EXPECT_EQ(p.observe("METER", "holding")[1], 6);
}

// ---- Errors --------------------------------------------------------------------------------------------------------

TEST(ModbusMsg, ExceptionRepliesGiveEightyHexPlusTheException) {
  Plc p("SOR XIC B3:0/0 MSG MG11:0 03 MODBUS LOCAL 0 N7:0 5 1 8 2 EOR\n"
        "SOR XIC B3:0/1 MSG MG11:1 04 MODBUS LOCAL 0 N7:5 1 2 1 2 EOR\n"
        "SOR XIC B3:0/2 MSG MG11:2 03 MODBUS LOCAL 0 N7:6 1 2 1 2 EOR");
  p.inject("METER", "exception", {"4"});
  p.set("B3:0", 7);
  for (int e = 0; e < 3; ++e) ASSERT_TRUE(p.until(e, kDN | kER, 1'000'000'000)) << e;
  // Registers 8-12 of a 10-register table: 82h Illegal Data Address.
  EXPECT_EQ(p.w("MG11:0.17") & (kDN | kER), kER);
  EXPECT_EQ(p.i("MG11:0.ERR"), 0x82);
  // METER answers every request with exception 4 (its `functions=3,16` would make 04 an 01 otherwise): 84h.
  EXPECT_EQ(p.i("MG11:1.ERR"), 0x84);
  EXPECT_EQ(p.i("MG11:2.ERR"), 0x84);
  p.inject("METER", "normal", {});
  p.set("B3:0", 0);
  p->scan(1);
  p.set("B3:0/1", 1);
  ASSERT_TRUE(p.until(1, kDN | kER, 1'000'000'000));
  EXPECT_EQ(p.i("MG11:1.ERR"), 0x81);  // 04 is not among its functions: 81h Illegal Function
}

TEST(ModbusMsg, ASlaveThatNeverAnswersTimesOutAndHoldsTheLine) {
  // Slave 9 is not on the line; MTO 2 s. The read of slave 1 behind it waits for the line.
  Plc p("SOR XIC B3:0/0 MSG MG11:0 03 MODBUS LOCAL 0 N7:0 1 9 1 2 EOR\n"
        "SOR XIC B3:0/0 MSG MG11:1 03 MODBUS LOCAL 0 N7:1 1 1 1 5 EOR");
  p.set("B3:0/0", 1);
  p->scan(1);
  const VirtualTime started = p->now();
  const auto end = p.until(0, kDN | kER, 3'000'000'000);
  ASSERT_TRUE(end);
  EXPECT_EQ(p.w("MG11:0.16") & kTO, kTO);
  EXPECT_EQ(p.w("MG11:0.17") & (kDN | kER | kST), kER);
  EXPECT_EQ(p.i("MG11:0.ERR"), 0x37);
  EXPECT_GE(*end - started + 1'000'000, 2'000'000'000);
  EXPECT_LE(*end - started, 2'002'000'000);
  EXPECT_EQ(p.w("MG11:1.17") & kDN, 0);  // not sent before the line was free
  ASSERT_TRUE(p.until(1, kDN, 100'000'000));
}

// MG word 19, "time since message started" in seconds (1762-RM001C p. 21-4; 1763-RM001B p. 348): it counts
// while the message waits (slave 9 never answers, MTO 5 s), shows the whole timeout when it expires, stays
// after the message ends, and starts from 0 with the next message.
TEST(ModbusMsg, WordNineteenCountsTheSecondsSinceTheMessageStarted) {
  Plc p("SOR XIC B3:0/0 MSG MG11:0 03 MODBUS LOCAL 0 N7:0 1 9 1 5 EOR");
  p.set("MG11:0.19", 77);  // what an earlier message left
  p.set("B3:0/0", 1);
  p->scan(1);
  const VirtualTime started = p->now();
  EXPECT_EQ(p.i("MG11:0.19"), 0);
  p->run_for(2'500'000'000 - (p->now() - started));
  EXPECT_EQ(p.i("MG11:0.19"), 2);
  ASSERT_TRUE(p.until(0, kER, 3'000'000'000));
  EXPECT_EQ(p.i("MG11:0.ERR"), 0x37);
  EXPECT_EQ(p.i("MG11:0.19"), 5);
  p->run_for(3'000'000'000);
  EXPECT_EQ(p.i("MG11:0.19"), 5);
  p.set("B3:0/0", 0);
  p->scan(1);
  p.set("MG11:0.NOD", 1);  // slave 1 answers within the first second
  p.set("B3:0/0", 1);
  p->scan(1);
  EXPECT_EQ(p.i("MG11:0.19"), 0);
  ASSERT_TRUE(p.until(0, kDN, 100'000'000));
  EXPECT_EQ(p.i("MG11:0.19"), 0);
}

TEST(ModbusMsg, TheToBitAbortsAndBadSetupsEndAtOnce) {
  Plc p("SOR XIC B3:0/0 MSG MG11:0 03 MODBUS LOCAL 0 N7:0 1 9 1 0 EOR");
  p.set("B3:0/0", 1);
  p->run_for(500'000'000);  // MTO 0: never times out
  EXPECT_EQ(p.w("MG11:0.17") & (kDN | kER | kST), kST);
  p.set("MG11:0/TO", 1);
  p->scan(1);
  EXPECT_EQ(p.w("MG11:0.17") & (kDN | kER), kER);
  EXPECT_EQ(p.i("MG11:0.ERR"), 0x37);
  // A program that writes slave 0 into NOD for a read: 18h, broadcast not supported (1766-RM001A p. 466);
  // 248: 16h, the address above the maximum.
  p.set("B3:0/0", 0);
  p->scan(1);
  p.set("MG11:0.NOD", 0);
  p.set("B3:0/0", 1);
  p->scan(1);
  EXPECT_EQ(p.i("MG11:0.ERR"), 0x18);
  p.set("B3:0/0", 0);
  p->scan(1);
  p.set("MG11:0.NOD", 248);
  p.set("B3:0/0", 1);
  p->scan(1);
  EXPECT_EQ(p.i("MG11:0.ERR"), 0x16);
}

TEST(ModbusMsg, AChannelThatIsNoModbusMasterEndsWith12h) {
  // No `modbus` node: channel 0 is not a Modbus RTU master (it is on DH-485).
  Plc p("SOR XIC B3:0/0 MSG MG11:0 03 MODBUS LOCAL 0 N7:0 1 1 1 2 EOR", "");
  p.set("B3:0/0", 1);
  p->scan(1);
  EXPECT_EQ(p.w("MG11:0.17") & (kDN | kER), kER);
  EXPECT_EQ(p.i("MG11:0.ERR"), 0x12);
  // And with one, a DH-485 (500CPU) message on channel 0 ends the same way.
  Plc q("SOR XIC B3:0/0 MSG MG11:0 READ 500CPU LOCAL 0 N7:0 5 2 N10:0 5 EOR");
  q.set("B3:0/0", 1);
  q->scan(1);
  EXPECT_EQ(q.i("MG11:0.ERR"), 0x12);
}

// A Modbus master's channel 0 speaks Modbus, not DH-485: a test that puts the controller on a DH-485
// network with peers is refused (it used to stay a DH-485 station there and answer the peers'
// messages); on Ethernet, channel 1, it meets them.
TEST(ModbusMsg, AModbusMastersChannel0IsOnNoDh485Network) {
  auto with_peer = [](std::uint32_t ip, const std::string& peer_processor, std::uint32_t peer_ip) {
    LoadResult lr = load_program(program("SOR XIC B3:0/0 OTE B3:0/1 EOR"), "mb.slc");
    if (!lr.ok()) throw std::runtime_error(lr.render_diagnostics());
    ModuleSetup setup = load_module_setup_text(*lr.program, kBench, "mb.bench");
    if (!setup.ok()) throw std::runtime_error("the bench did not load");
    LoadResult plr = load_program("START " + peer_processor + "\nLADDER 2\nSOR XIC B3:0/0 OTE B3:0/1 EOR\n", "peer.slc");
    if (!plr.ok()) throw std::runtime_error(plr.render_diagnostics());
    PeerController p;
    p.name = "PEER";
    p.node = 2;
    p.ip = peer_ip;
    p.program = std::make_shared<const Program>(std::move(*plr.program));
    p.options = std::make_shared<const RuntimeOptions>();
    setup.options.ip = ip;
    setup.options.peers.push_back(std::move(p));
    RuntimeResult r = Runtime::create(*lr.program, setup.options);
    return r.ok() ? std::string() : r.render_errors();
  };
  const std::string dh485 = with_peer(0, "Bul.1763", 0);
  EXPECT_NE(dh485.find("channel 0 is a Modbus RTU master (the bench's modbus nodes), so it is on no DH-485 network"),
            std::string::npos)
      << dh485;
  EXPECT_EQ(with_peer(0xC0A8011E, "1747-L552", 0xC0A80114), "");  // 192.168.1.30 and an SLC 5/05 at .20
}

TEST(ModbusMsg, TheBenchNodesAreChecked) {
  const std::string rung = program("SOR OTE B3:0/0 EOR");
  std::string e = errors_of(rung, "modbus A slave=1\nmodbus B slave=1\n");
  EXPECT_NE(e.find("mb.bench:2:16: error: modbus B: slave address 1 is also A's"), std::string::npos) << e;
  e = errors_of(rung, "modbus A slave=1 baud=9600\nmodbus B slave=2 baud=19200\n");
  EXPECT_NE(e.find("baud=19200: the slaves share channel 0's line"), std::string::npos) << e;
  e = errors_of(rung, "modbus A slave=248\n");
  EXPECT_NE(e.find("mb.bench:1:"), std::string::npos) << e;
  e = errors_of(rung, "modbus A slave=1 functions=3,7\n");
  EXPECT_NE(e.find("functions: 7 is not one of the eight commands"), std::string::npos) << e;
  e = errors_of(rung, "serial S baud=9600\nmodbus A slave=1\n");
  EXPECT_NE(e.find("channel 0 is already wired to"), std::string::npos) << e;
  e = errors_of(program("SOR OTE B3:0/0 EOR", "Bul.1762"), "modbus A slave=1\n");
  EXPECT_NE(e.find("is the MicroLogix 1100's and 1400's"), std::string::npos) << e;
  // A slave's table refuses a change past its end.
  Plc p("SOR OTE B3:0/0 EOR");
  EXPECT_FALSE(p->inject("METER", "holding", {"3", "1", "2"}));
  EXPECT_TRUE(p->inject("METER", "holding", {"3", "1"}));
}

}  // namespace
}  // namespace softslc::test
