// Issue 15: the ASCII and string instructions of 1747-RM001G chapter 10 (ABL ACB ACI ACL ACN AEX
// AHL AIC ARD ARL ASC ASR AWA AWT), the checker's rules for them, and channel 0 wired to a bench
// `serial` device so that reads and writes complete in virtual time.
//
// Expected values come from the manual's pages (cited at each test) or from a hand calculation
// written next to the assertion:
//   RM = 1747-RM001G (SLC 500 Instruction Set Reference, Nov 2008), chapter 10;
//   ML1100 = 1763-RM001C; ML1200/1500 = 1762-RM001C; ML1400 = 1766-RM001A.
// Where the manual is silent the decision is in docs/semantics.md "ASCII and strings" and the test
// says "decision".
#include <gtest/gtest.h>

#include <string>

#include "modules/module_setup.h"
#include "modules/serial/serial_device.h"
#include "parser/loader.h"
#include "vm/ascii.h"
#include "vm/runtime.h"

namespace softslc::test {
namespace {

constexpr std::uint16_t kEN = 1u << 15, kEU = 1u << 14, kDN = 1u << 13, kEM = 1u << 12, kER = 1u << 11,
                        kUL = 1u << 10, kFD = 1u << 8;

// A 5/03 program with an N7, an R6 and the strings in ST10 (DATA rows), plus `rungs`.
std::string program(const std::string& rungs, const std::vector<std::string>& strings = {},
                    const std::string& start = "START 1747-L532\n") {
  std::string p = start + "LADDER 2\n" + rungs + "\n";
  if (!strings.empty()) {
    p += "DATA ST10:0\n";
    for (std::size_t i = 0; i < strings.size(); ++i)
      p += "% ST10:" + std::to_string(i) + " % \"" + strings[i] + "\"\n";
  }
  return p;
}

std::unique_ptr<Runtime> build(const std::string& text, const std::string& bench, std::string* errors) {
  LoadResult lr = load_program(text, "ascii.slc");
  if (!lr.ok()) {
    *errors = lr.render_diagnostics();
    return nullptr;
  }
  ModuleSetup s = load_module_setup_text(*lr.program, bench, "ascii.bench");
  if (!s.ok()) {
    *errors = s.render("ascii.slc", lr.source);
    return nullptr;
  }
  RuntimeResult rr = Runtime::create(*lr.program, s.options);
  if (!rr.ok()) {
    *errors = rr.render_errors();
    return nullptr;
  }
  return std::move(rr.runtime);
}

struct Plc {
  std::unique_ptr<Runtime> rt;
  explicit Plc(const std::string& text, const std::string& bench = "") {
    std::string errors;
    rt = build(text, bench, &errors);  // cppcheck-suppress useInitializationList ; the build reports into the local errors
    if (!rt) throw std::runtime_error(errors);
  }
  Runtime* operator->() { return rt.get(); }
  std::int64_t i(const std::string& a) { return rt->value(a).as_int(); }
  std::uint16_t w(const std::string& a) { return static_cast<std::uint16_t>(rt->value(a).as_int()); }
  void set(const std::string& a, std::int64_t v) {
    if (!rt->set(a, Value::of_int(v))) throw std::runtime_error("set " + a);
  }
  void scans(int n) {
    if (rt->mode() != Mode::Run) {
      ASSERT_TRUE(rt->set_mode(Mode::Run));
    }
    rt->scan(n);
  }
  // The text of ST10:e, read word by word (RM 10-3: word 0 the length, the first character in the
  // high byte of word 1).
  std::string text(int e) {
    const std::string base = "ST10:" + std::to_string(e);
    const int len = static_cast<int>(i(base + ".0"));
    std::string s;
    for (int k = 0; k < len && k < 82; ++k) {
      const auto word = w(base + "." + std::to_string(1 + k / 2));
      s += static_cast<char>(k % 2 == 0 ? word >> 8 : word & 0xFF);
    }
    return s;
  }
  int flags() { return static_cast<int>(i("S:0") & 0xF); }
  bool ascii_error() { return (w("S:5") & 0x8000) != 0; }
  std::string device_line(const std::string& dev) {
    auto v = rt->observe(dev, "last line");
    std::string s;
    if (v)
      for (auto c : *v) s += static_cast<char>(c);
    return s;
  }
};

std::string check_errors(const std::string& text) {
  std::string errors;
  build(text, "", &errors);
  return errors;
}

// ---- The string element (RM 10-3) -----------------------------------------------------------------------------

TEST(AsciiString, ElementLayoutIsLengthThenTwoCharactersPerWordHighByteFirst) {
  // RM 10-3 and ML1100 p. 312 "String Data File Structure": word 0 the length (0-82), word 1
  // character 0 in the upper byte and character 1 in the lower byte.
  Plc plc(program("SOR OTE B3:0/0 EOR", {"AB", "xyz"}));
  EXPECT_EQ(plc.i("ST10:0.0"), 2);
  EXPECT_EQ(plc.w("ST10:0.1"), 0x4142);
  EXPECT_EQ(plc.i("ST10:1.0"), 3);
  EXPECT_EQ(plc.w("ST10:1.1"), 0x7879);
  EXPECT_EQ(plc.w("ST10:1.2") >> 8, 0x7A);
}

// ---- ACI (RM 10-8, table 10.6) ------------------------------------------------------------------------------

TEST(AsciiString, AciTakesTheNumberFromTheFirstDigitOn) {
  // RM 10-8: "searches the source ... for the first character between 0 and 9. All numeric
  // characters are extracted until a non-numeric character or the end of the string".
  Plc plc(program("SOR ACI ST10:0 N7:0 EOR\nSOR ACI ST10:1 N7:1 EOR", {"W 123 kg", "ST,GS,+00125kg"}));
  plc.scans(1);
  EXPECT_EQ(plc.i("N7:0"), 123);
  EXPECT_EQ(plc.i("N7:1"), 125) << "the leading zeros and the + sign: RM 10-8 'Commas and signs (+, -) are allowed'";
  EXPECT_EQ(plc.flags(), 0) << "table 10.6: V, Z, S clear for 125";
}

TEST(AsciiString, AciSignZeroAndOverflowFlags) {
  // Table 10.6: S "sets if the result is negative", Z "if the integer value is zero", V "if the
  // integer value is outside of the valid range"; RM 10-8: "The value of 32,767 is returned".
  Plc plc(program("SOR ACI ST10:0 N7:0 EOR\nSOR XIC S:0/3 OTE B3:0/0 EOR\n"
                  "SOR ACI ST10:1 N7:1 EOR\nSOR XIC S:0/2 OTE B3:0/1 EOR\n"
                  "SOR ACI ST10:2 N7:2 EOR\nSOR XIC S:0/1 OTE B3:0/2 EOR\nSOR OTU S:5/0 EOR",
                  {"T=-45", "000", "99999"}));
  plc.scans(1);
  EXPECT_EQ(plc.i("N7:0"), -45);
  EXPECT_EQ(plc.i("B3:0/0"), 1) << "S";
  EXPECT_EQ(plc.i("N7:1"), 0);
  EXPECT_EQ(plc.i("B3:0/1"), 1) << "Z";
  EXPECT_EQ(plc.i("N7:2"), 32767);
  EXPECT_EQ(plc.i("B3:0/2"), 1) << "V";
  EXPECT_FALSE(plc->fault().has_value()) << "the overflow trap S:5/0 was cleared by the program";
}

TEST(AsciiString, AciOfAStringWithoutDigitsDoesNothing) {
  // RM 10-8: "Action is taken only if numeric characters are found."
  Plc plc(program("SOR ACI ST10:0 N7:0 EOR", {"NO DATA"}));
  plc.set("N7:0", 77);
  plc.scans(1);
  EXPECT_EQ(plc.i("N7:0"), 77);
  EXPECT_FALSE(plc.ascii_error());
}

TEST(AsciiString, AciOfAnInvalidLengthSetsTheAsciiErrorBit) {
  // RM 10-8: "If the string contains an invalid length (<0 or >82) the ASCII Error bit S:5/15 is set."
  Plc plc(program("SOR ACI ST10:0 N7:0 EOR", {"42"}));
  plc.set("N7:0", 5);
  plc.set("ST10:0.0", 83);
  plc.scans(1);
  EXPECT_TRUE(plc.ascii_error());
  EXPECT_EQ(plc.i("N7:0"), 5) << "RM 10-3: 'the instruction is not executed'";
  EXPECT_FALSE(plc->fault().has_value()) << "S:5/15 is not a major fault on the SLC";
}

TEST(AsciiString, AciSkipsCommasBetweenDigits) {
  // Decision (docs/semantics.md): "Commas ... are allowed in the string" read as thousands
  // separators: "-1,234" is -1234.
  Plc plc(program("SOR ACI ST10:0 N7:0 EOR", {"-1,234"}));
  plc.scans(1);
  EXPECT_EQ(plc.i("N7:0"), -1234);
}

// ---- AIC (RM 10-14) ---------------------------------------------------------------------------------------

TEST(AsciiString, AicWritesTheDecimalText) {
  // RM 10-14: "converts an integer value (-32,768 and 32,767) to an ASCII string".
  Plc plc(program("SOR AIC N7:98 ST10:6 EOR\nSOR AIC -32768 ST10:7 EOR\nSOR AIC 0 ST10:8 EOR", {"", "", "", "", "", "", "", "", ""}));
  plc.set("N7:98", 32767);
  plc.scans(1);
  EXPECT_EQ(plc.text(6), "32767");
  EXPECT_EQ(plc.text(7), "-32768");
  EXPECT_EQ(plc.text(8), "0");
}

// ---- ACN ------------------------------------------------------------------------------------------------------

TEST(AsciiString, AcnAppendsBToAAndKeeps82Characters) {
  // ML1100 p. 326: "Source B is appended to Source A ... Only the first 82 characters (0 to 81) are
  // written to the destination."
  const std::string fifty(50, 'x');
  Plc plc(program("SOR ACN ST10:0 ST10:1 ST10:2 EOR\nSOR ACN ST10:3 ST10:3 ST10:4 EOR", {"ABC", "DEF", "", fifty, ""}));
  plc.scans(1);
  EXPECT_EQ(plc.text(2), "ABCDEF");
  EXPECT_EQ(plc.i("ST10:4.0"), 82);
  EXPECT_EQ(plc.text(4), std::string(82, 'x'));
}

TEST(AsciiString, AcnPast82CharactersSetsS515AndOnAMicroLogix1F39) {
  // RM 10-3: lengths outside 0-82 set S:5/15 and the instruction is not executed; ML1100 p. 326:
  // "If the string length of Source A, Source B, or Destination is greater than 82, the ASCII String
  // Manipulation Error bit S:5/15 is set and the Invalid String Length Error (1F39H) is written to
  // the Major Error Fault Code word (S:6)".
  const std::string body = "SOR ACN ST10:0 ST10:1 ST10:2 EOR";
  Plc slc(program(body, {"ABC", "DEF", "old"}));
  slc.set("ST10:1.0", 90);
  slc.scans(1);
  EXPECT_TRUE(slc.ascii_error());
  EXPECT_EQ(slc.text(2), "old");
  EXPECT_NE(slc.i("S:6"), 0x1F39);

  Plc ml(program(body, {"ABC", "DEF", "old"}, "START Bul.1766\n"));
  ml.set("ST10:1.0", 90);
  ml.scans(1);
  EXPECT_TRUE(ml.ascii_error());
  EXPECT_EQ(ml.i("S:6"), 0x1F39);
  EXPECT_EQ(ml.text(2), "old");
}

// ---- AEX (RM 10-12) -------------------------------------------------------------------------------------------

TEST(AsciiString, AexTakesNumberCharactersFromIndex) {
  // RM 10-12: "Index is the starting position (from 1 to 82) ... An index of 1 indicates the
  // left-most character"; the manual's box: AEX ST28:0 index 32 number 10 -> characters 32-41.
  const std::string src = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ";
  Plc plc(program("SOR AEX ST10:0 32 10 ST10:1 EOR\nSOR AEX ST10:0 1 5 ST10:2 EOR", {src, "", ""}));
  plc.scans(1);
  EXPECT_EQ(plc.text(1), src.substr(31, 10));
  EXPECT_EQ(plc.text(1), "FGHIJKLMNO");
  EXPECT_EQ(plc.text(2), "abcde");
  EXPECT_FALSE(plc.ascii_error());
}

TEST(AsciiString, AexPastTheEndTakesTheRestWithoutAnError) {
  // RM 10-12: "If the index plus the number is greater than the total characters in the source
  // string, the destination string will be the characters from the index to the end" and "the
  // ASCII Error bit (S:5/15) is not set".
  Plc plc(program("SOR AEX ST10:0 7 20 ST10:1 EOR", {"ST,GS,+00125kg", ""}));
  plc.scans(1);
  EXPECT_EQ(plc.text(1), "+00125kg");
  EXPECT_FALSE(plc.ascii_error());
}

TEST(AsciiString, AexRangeErrorsLeaveTheDestination) {
  // RM 10-12: S:5/15 for "Invalid source string length or string length of zero", "Index or number
  // values outside of range", "Index value greater than the length of the source string"; "The
  // destination string is not changed in any of the above error conditions."
  for (const auto& [source, index, number] : std::vector<std::tuple<std::string, int, int>>{
           {"", 1, 1}, {"abc", 0, 1}, {"abc", 83, 1}, {"abc", 1, 0}, {"abc", 1, 83}, {"abc", 4, 1}}) {
    Plc plc(program("SOR AEX ST10:0 N7:0 N7:1 ST10:1 EOR", {source, "keep"}));
    plc.set("N7:0", index);
    plc.set("N7:1", number);
    plc.scans(1);
    EXPECT_TRUE(plc.ascii_error()) << source << " " << index << " " << number;
    EXPECT_EQ(plc.text(1), "keep");
  }
}

// ---- ASC (RM 10-18, 10-19) ------------------------------------------------------------------------------------

TEST(AsciiString, AscFindsTheFirstPositionFromIndex) {
  Plc plc(program("SOR ASC ST10:0 1 ST10:1 N7:0 EOR\nSOR ASC ST10:2 1 ST10:1 N7:1 EOR\nSOR ASC ST10:3 4 ST10:1 N7:2 EOR",
                  {"kg", "ST,GS,+00125kg", "lb", "GS"}));
  plc.scans(1);
  EXPECT_EQ(plc.i("N7:0"), 13) << "'kg' starts at character 13 of ST,GS,+00125kg (1 = the first)";
  EXPECT_EQ(plc.i("N7:1"), 0) << "not found (decision: 0)";
  EXPECT_EQ(plc.i("N7:2"), 4);
  EXPECT_FALSE(plc.ascii_error());
}

TEST(AsciiString, AscErrorsLeaveTheResult) {
  // RM 10-19: S:5/15 for "Invalid string length or string length of zero", "Index value outside of
  // range", "Index value greater than the length of the source string"; "The destination is not
  // changed".
  Plc plc(program("SOR ASC ST10:0 N7:1 ST10:1 N7:0 EOR", {"kg", "abc"}));
  plc.set("N7:0", -9);
  plc.set("N7:1", 4);
  plc.scans(1);
  EXPECT_TRUE(plc.ascii_error());
  EXPECT_EQ(plc.i("N7:0"), -9);
}

// ---- ASR (RM 10-19) -------------------------------------------------------------------------------------------

TEST(AsciiString, AsrIsTrueForIdenticalStringsOnly) {
  // RM 10-19: "looks for a match in length and upper/lower case characters. If two strings are
  // identical, the rung is true; if there are any differences, the rung is false."
  Plc plc(program("SOR ASR ST10:0 ST10:1 OTE B3:0/0 EOR\nSOR ASR ST10:0 ST10:2 OTE B3:0/1 EOR\n"
                  "SOR ASR ST10:0 ST10:3 OTE B3:0/2 EOR",
                  {"ST", "ST", "st", "ST "}));
  plc.scans(1);
  EXPECT_EQ(plc.i("B3:0/0"), 1);
  EXPECT_EQ(plc.i("B3:0/1"), 0) << "case differs";
  EXPECT_EQ(plc.i("B3:0/2"), 0) << "length differs";
}

TEST(AsciiString, AsrOfAnInvalidLengthIsFalseWithS515) {
  // RM 10-19: "An invalid string length causes the processor to set ASCII Error bit S:5/15, and the
  // rung goes false."
  Plc plc(program("SOR ASR ST10:0 ST10:1 OTE B3:0/0 EOR", {"ST", "ST"}));
  plc.set("ST10:1.0", -1);
  plc.scans(1);
  EXPECT_EQ(plc.i("B3:0/0"), 0);
  EXPECT_TRUE(plc.ascii_error());
}

// ---- check: operands and processors -----------------------------------------------------------------------------

TEST(AsciiCheck, TheProcessorsThatHaveThem) {
  // RM 10-8, 10-13, 10-14, 10-19: "Fixed, SLC 5/01, SLC 5/02: -; SLC 5/03, 5/04, 5/05: •".
  const std::string rung = "SOR AEX ST10:0 1 5 ST10:1 EOR";
  EXPECT_EQ(check_errors(program(rung, {"abc", ""})), "");
  EXPECT_EQ(check_errors(program(rung, {"abc", ""}, "START 1747-L551\n")), "");
  const std::string e = check_errors(program(rung, {}, "START 1747-L524\n"));
  EXPECT_NE(e.find("AEX is not available on the SLC 5/02"), std::string::npos) << e;
  const std::string ml = check_errors(program("SOR AHL 0 0 0 R6:0 0 EOR", {}, "START Bul.1761\n"));
  EXPECT_NE(ml.find("AHL is not available on the MicroLogix 1000"), std::string::npos) << ml;
  EXPECT_EQ(check_errors(program("SOR ARL 0 ST10:0 R6:0 82 0 EOR", {""}, "START Bul.1763\n")), "");
}

TEST(AsciiCheck, OperandKindsAndRanges) {
  EXPECT_NE(check_errors(program("SOR ACI N7:0 N7:1 EOR")).find("expected a string element"), std::string::npos);
  EXPECT_NE(check_errors(program("SOR ACN ST10:0 ST10:0.3 ST10:1 EOR", {"a", "b"})).find("expected a string element"),
            std::string::npos);
  const std::string idx = check_errors(program("SOR AEX ST10:0 83 1 ST10:1 EOR", {"a", "b"}));
  EXPECT_NE(idx.find("AEX index 83 is out of range 1-82"), std::string::npos) << idx;
  EXPECT_NE(check_errors(program("SOR AEX ST10:0 1 0 ST10:1 EOR", {"a", "b"})).find("AEX number 0 is out of range 1-82"),
            std::string::npos);
  const std::string ch = check_errors(program("SOR AWT 1 ST10:0 R6:0 5 0 EOR", {"a"}));
  EXPECT_NE(ch.find("out of range 0-0"), std::string::npos) << ch;
  EXPECT_NE(check_errors(program("SOR ARL 0 ST10:0 R6:0 83 0 EOR", {"a"})).find("out of range 0-82"), std::string::npos);
  EXPECT_NE(check_errors(program("SOR ABL 0 N7:0 0 EOR")).find("control"), std::string::npos);
  const std::string lng = check_errors(program("SOR ACI ST10:0 L9:0 EOR", {"1"}, "START Bul.1766\n"));
  EXPECT_NE(lng.find("long-word form"), std::string::npos) << lng;
}

// ---- Channel 0 and a serial device ----------------------------------------------------------------------------

// 9600 baud, 8 data bits, no parity, 1 stop bit: 10 bits, 1.0416667 ms a character.
constexpr const char* kBench = "serial SCALE baud=9600 termination=CR append=CRLF eol=CR\n";

TEST(AsciiChannel, AwaDoneAfterTheCharactersTransmissionTime) {
  // RM 10-5: DN "is set opposite to a program scan when an instruction successfully completes";
  // the append characters default to CR LF (RM 10-3, table 10.2). "HELLO" + CR LF = 7 characters of
  // 10 bits at 9600 baud = 7.2917 ms.
  Plc plc(program("SOR XIC B3:0/0 AWA 0 ST10:0 R6:0 0 0 EOR", {"HELLO"}), kBench);
  plc.scans(1);
  plc.set("B3:0/0", 1);
  const VirtualTime start = plc->now();
  plc.scans(1);
  EXPECT_TRUE(plc.w("R6:0") & kEN);
  EXPECT_TRUE(plc.w("R6:0") & kEU) << "queued";
  EXPECT_FALSE(plc.w("R6:0") & kDN);
  ASSERT_TRUE(plc->run_until([](const Runtime& r) { return (r.value("R6:0").as_int() & (1 << 13)) != 0; }, 100'000'000));
  EXPECT_GE(plc->now() - start, 7'291'666);
  EXPECT_EQ(plc.i("R6:0.POS"), 7) << "characters sent, the append characters included (ML1200 p. 20-11: 25 + 2 = 27)";
  EXPECT_EQ(plc.device_line("SCALE"), "HELLO");
  EXPECT_FALSE(plc.w("R6:0") & kEU) << "left the queue";
  plc.scans(1);
  EXPECT_TRUE(plc.w("R6:0") & kEM) << "RM 10-6: EM when the program scans the instruction with DN set";
}

TEST(AsciiChannel, ArlReadsALineAtTheBaudRate) {
  // The device sends "W 00125" CR: 8 characters = 8.333 ms at 9600 baud. ARL (LEN 82) is done when
  // the termination character (CR, table 10.2 default) arrives, which is moved too (ML1400 p. 385).
  Plc plc(program("SOR XIC B3:0/0 ARL 0 ST10:0 R6:0 82 0 EOR\nSOR XIC R6:0/DN ACI ST10:0 N7:0 EOR", {""}), kBench);
  plc.set("B3:0/0", 1);
  plc.scans(1);
  ASSERT_TRUE(plc.w("R6:0") & kEU);
  ASSERT_TRUE(plc->inject("SCALE", "send", {"W", "00125"}));
  const VirtualTime sent = plc->now();
  ASSERT_TRUE(plc->run_until([](const Runtime& r) { return r.value("N7:0").as_int() == 125; }, 100'000'000));
  EXPECT_GE(plc->now() - sent, 8'333'333);
  EXPECT_EQ(plc.text(0), "W 00125\r");
  EXPECT_EQ(plc.i("R6:0.POS"), 8);
}

TEST(AsciiChannel, AblAndAcbCountTheReceiveBuffer) {
  // RM 10-6: ABL reports the characters "up to and including the end-of-line characters", FD when
  // not zero; RM 10-7: ACB the total characters in the buffer.
  Plc plc(program("SOR XIC B3:0/0 ABL 0 R6:0 0 EOR\nSOR XIC B3:0/0 ACB 0 R6:1 0 EOR"), kBench);
  plc.scans(1);
  ASSERT_TRUE(plc->inject("SCALE", "send", {"AB"}));   // "AB" CR
  ASSERT_TRUE(plc->inject("SCALE", "send", {"CDEF"}));  // "CDEF" CR
  plc->run_for(20'000'000);                              // 8 characters: 8.33 ms
  plc.set("B3:0/0", 1);
  plc.scans(1);
  EXPECT_EQ(plc.i("R6:0.POS"), 3);
  EXPECT_TRUE(plc.w("R6:0") & kFD);
  EXPECT_TRUE(plc.w("R6:0") & kDN) << "executes at once when the queue is empty (RM 10-6)";
  EXPECT_EQ(plc.i("R6:1.POS"), 8);
  EXPECT_EQ(*plc->observe("SCALE", "buffered"), std::vector<std::int64_t>{8});
}

TEST(AsciiChannel, AhlSetsAndResetsDtrAndRts) {
  // RM 10-13: a 1 in the AND mask resets the line, a 1 in the OR mask sets it; bit 0 DTR, bit 1
  // RTS. Table 10.7: channel status bits 0 CTS, 1 RTS, 2 DSR, 3 DCD, 4 DTR; the manual's example
  // shows 001F with every line on.
  Plc plc(program("SOR XIC B3:0/0 AHL 0 0 0 R6:0 0 EOR\nSOR XIC B3:0/1 AHL 0 3 0 R6:1 0 EOR\n"
                  "SOR XIC B3:0/2 AHL 0 0 2 R6:2 0 EOR"),
          kBench);
  plc.set("B3:0/0", 1);
  plc.scans(1);
  EXPECT_EQ(plc.i("R6:0.POS"), 0x001F);
  plc.set("B3:0/1", 1);
  plc.scans(1);
  EXPECT_EQ(plc.i("R6:1.POS"), 0x000D) << "DTR and RTS reset: CTS + DSR + DCD";
  EXPECT_EQ(*plc->observe("SCALE", "dtr"), std::vector<std::int64_t>{0});
  plc.set("B3:0/2", 1);
  plc.scans(1);
  EXPECT_EQ(plc.i("R6:2.POS"), 0x000F) << "RTS set again";
}

TEST(AsciiChannel, WithoutAUserModeChannelTheInstructionErrs) {
  // RM 10-7: ER "if the instruction is aborted - serial port not in User mode". Error code 04h:
  // unverified (docs/semantics.md).
  Plc plc(program("SOR AWT 0 ST10:0 R6:0 0 0 EOR", {"X"}));
  plc.scans(1);
  EXPECT_TRUE(plc.w("R6:0") & kER);
  EXPECT_EQ(plc.w("R6:0") & 0xFF, 0x04);
  EXPECT_FALSE(plc.w("R6:0") & kDN);
}

TEST(AsciiChannel, UnloadBitStopsAQueuedInstruction) {
  // RM 10-5: UL "ceases instruction operation before (may be queued) or during execution"; ER "the
  // instruction was cancelled using the UL bit". Error code 0Ah: unverified (docs/semantics.md).
  Plc plc(program("SOR XIC B3:0/0 ARL 0 ST10:0 R6:0 82 0 EOR\nSOR XIC B3:0/0 AWT 0 ST10:1 R6:1 0 0 EOR", {"", "X"}),
          kBench);
  plc.set("R6:1.0", kUL);
  plc.set("B3:0/0", 1);
  plc.scans(1);
  EXPECT_TRUE(plc.w("R6:1") & kEU) << "queued behind the ARL, which waits for a line";
  ASSERT_TRUE(plc->inject("SCALE", "send", {"1"}));
  plc->run_for(10'000'000);
  EXPECT_TRUE(plc.w("R6:0") & kDN);
  EXPECT_TRUE(plc.w("R6:1") & kER);
  EXPECT_EQ(plc.w("R6:1") & 0xFF, 0x0A);
  EXPECT_EQ(*plc->observe("SCALE", "lines"), std::vector<std::int64_t>{0}) << "nothing was sent";
}

TEST(AsciiChannel, AclRemovesQueuedReadsWithCode0E) {
  // ML1200 p. 20-8 / ML1400 p. 369: when both buffers are cleared the receive and transmit
  // instructions "are removed from the ASCII queue ... ER = 1, RN = 0, EU = 0, and ERR = 0x0E".
  Plc plc(program("SOR XIC B3:0/0 ARL 0 ST10:0 R6:0 82 0 EOR\nSOR XIC B3:0/1 ACL 0 1 1 EOR", {""}), kBench);
  plc.set("B3:0/0", 1);
  plc.scans(1);
  ASSERT_TRUE(plc.w("R6:0") & kEU);
  plc.set("B3:0/1", 1);
  plc.scans(1);
  EXPECT_TRUE(plc.w("R6:0") & kER);
  EXPECT_FALSE(plc.w("R6:0") & kEU);
  EXPECT_EQ(plc.w("R6:0") & 0xFF, 0x0E);
}

TEST(AsciiChannel, LeavingRunFlushesTheQueue) {
  // RM 10-14: ER "if the instruction is aborted due to channel mode change"; softslc flushes the
  // queue when the processor leaves Run, with code 0Ch (unverified, docs/semantics.md).
  Plc plc(program("SOR ARL 0 ST10:0 R6:0 82 0 EOR", {""}), kBench);
  plc.scans(1);
  ASSERT_TRUE(plc.w("R6:0") & kEU);
  ASSERT_TRUE(plc->set_mode(Mode::Program));
  EXPECT_TRUE(plc.w("R6:0") & kER);
  EXPECT_EQ(plc.w("R6:0") & 0xFF, 0x0C);
}

TEST(AsciiChannel, ANewOperationNeedsAFalseToTrueRung) {
  // RM 10-6: the instruction is queued "when the rung goes from false-to-true"; a rung that stays
  // true does not send again.
  Plc plc(program("SOR XIC B3:0/0 AWA 0 ST10:0 R6:0 0 0 EOR", {"P"}), kBench);
  plc.set("B3:0/0", 1);
  plc.scans(1);
  plc->run_for(50'000'000);
  EXPECT_EQ(*plc->observe("SCALE", "lines"), std::vector<std::int64_t>{1});
  plc.set("B3:0/0", 0);
  plc.scans(1);
  EXPECT_FALSE(plc.w("R6:0") & kEN);
  plc.set("B3:0/0", 1);
  plc.scans(1);
  plc->run_for(50'000'000);
  EXPECT_EQ(*plc->observe("SCALE", "lines"), std::vector<std::int64_t>{2});
}

TEST(AsciiChannel, AnInstructionStillQueuedIsNotQueuedTwice) {
  // Decision (docs/semantics.md): a false-to-true rung while the previous operation of the same
  // control element is still queued or running queues nothing.
  Plc plc(program("SOR XIC B3:0/0 ARL 0 ST10:0 R6:0 82 0 EOR", {""}), kBench);
  plc.set("B3:0/0", 1);
  plc.scans(1);
  plc.set("B3:0/0", 0);
  plc.scans(1);
  plc.set("B3:0/0", 1);
  plc.scans(1);
  ASSERT_TRUE(plc->inject("SCALE", "send", {"A"}));
  ASSERT_TRUE(plc->inject("SCALE", "send", {"B"}));
  plc->run_for(20'000'000);
  EXPECT_EQ(plc.text(0), "A\r");
  EXPECT_TRUE(plc.w("R6:0") & kDN);
  EXPECT_EQ(*plc->observe("SCALE", "buffered"), std::vector<std::int64_t>{2}) << "B CR stays: one read only";
}

TEST(AsciiChannel, AChannel0MsgOnAUserModePortEndsWith12h) {
  // Channel 0 wired to the bench's serial device is in User (ASCII) mode, not DF1: a MSG on it ends with
  // 12h "Local channel configuration protocol error exists" (RM 12-41 table 12.17; docs/semantics.md
  // "Channel 0"). Unwired, the same MSG is DF1's and waits for the cable (Df1Msg.AnUnconfiguredChannel0...).
  const std::string msg = program("SOR XIC B3:0/0 MSG READ 500CPU LOCAL N9:0 14 0 N10:0 5 2 N7:0 5 EOR");
  Plc p(msg, kBench);
  p.set("B3:0/0", 1);
  p.scans(2);
  EXPECT_EQ(p.w("N9:0") & (1u << 12), 1u << 12);
  EXPECT_EQ(p.i("N9:0") & 0xFF, 0x12);
  Plc unwired(msg);
  unwired.set("B3:0/0", 1);
  unwired.scans(2);
  EXPECT_EQ(unwired.w("N9:0") & (1u << 12), 0u);
}

TEST(AsciiChannel, TheBenchNodeIsChecked) {
  std::string errors;
  EXPECT_EQ(build(program("SOR OTE B3:0/0 EOR"), "serial S baud=9601\n", &errors), nullptr);
  EXPECT_NE(errors.find("baud"), std::string::npos) << errors;
  EXPECT_EQ(build(program("SOR OTE B3:0/0 EOR"), "serial S baud=9600 termination=ABC\n", &errors), nullptr);
  EXPECT_NE(errors.find("termination=ABC"), std::string::npos) << errors;
  EXPECT_EQ(build(program("SOR OTE B3:0/0 EOR", {}, "START 1747-L524\n"), "serial S baud=9600\n", &errors), nullptr);
  EXPECT_NE(errors.find("User (ASCII) mode needs"), std::string::npos) << errors;
  EXPECT_EQ(build(program("SOR OTE B3:0/0 EOR"), "serial S baud=9600\nserial T baud=9600\n", &errors), nullptr);
  EXPECT_NE(errors.find("already wired"), std::string::npos) << errors;
}

TEST(AsciiChannel, SerialCharactersSpelling) {
  EXPECT_EQ(parse_serial_characters("CRLF"), std::string("\r\n"));
  EXPECT_EQ(parse_serial_characters("\\0D\\0A"), std::string("\r\n"));
  EXPECT_EQ(parse_serial_characters(";"), std::string(";"));
  EXPECT_FALSE(parse_serial_characters("ABC").has_value());
}

}  // namespace
}  // namespace softslc::test
