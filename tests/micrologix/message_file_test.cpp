// The MicroLogix MG (message) and RI (routing information) data files (issue 16): declared,
// addressed, checked, loaded from DATA blocks and printed by `fmt`. The MicroLogix MSG that works on
// them is tests/micrologix/msg_test.cpp.
//
// Manual facts used (docs/micrologix-msg-sources.md):
// - the MG element has sub-elements 0-24: 5 RBL, 6 LBN, 7 RBN, 8 CHN, 9 NOD, 10 MTO, 13 TFN, 14 ELE,
//   16 the control bits, 17 the status bits, 18 ERR, 19 the time since the message started; the user
//   program may write CHN, NOD, MTO, TFN, ELE and the control bits, every other sub-element is read
//   only (1762-RM001C p. 21-4, 1763-RM001B pp. 347-348, 1766-RM001A pp. 399-400);
// - sub-element 17: ST bit 14, DN 13, ER 12, EW 10, R 0, all read only (1762-RM001C p. 21-6);
// - sub-element 16's bit positions: the table (1762-RM001C p. 21-5) was not reached: EN 15 and TO 8 are
//   softslc's decision [U] (the SLC control word's positions, 1747-RM001G p. 12-31);
// - the RI element has 20 words; 10.121.30.11 is word 1 = 790Ah, word 2 = 0B1Eh (1766-RM001A p. 435);
//   RI files on the MicroLogix 1100 and 1400 (1763-RM001B p. 384, 1766-RM001A p. 435).
#include <gtest/gtest.h>

#include <string>

#include "load_errors.h"
#include "function_file_test_util.h"
#include "parser/address.h"
#include "parser/formatter.h"
#include "parser/loader.h"
#include "tools/controller/controller.h"
#include "vm/runtime.h"
#include "vm/state_file.h"

namespace softslc {
namespace {

using test::load_errors;

std::string rung_errors(const std::string& processor, const std::string& rung) {
  return load_errors("START " + processor + "\nLADDER 2\n" + rung + "\n");
}

TEST(MicroLogixMessageFile, SubElementsParseAndPrintByName) {
  // Words 5-10, 13, 14, 18 as 1762-RM001C p. 21-4 numbers them; bits of word 17 as p. 21-6 places them.
  test::expect_named_sub_elements({{"MG11:0.RBL", 5, -1},  {"MG11:0.LBN", 6, -1},  {"MG11:0.RBN", 7, -1},
                                   {"MG11:0.CHN", 8, -1},  {"MG11:0.NOD", 9, -1},  {"MG11:0.MTO", 10, -1},
                                   {"MG11:1.TFN", 13, -1}, {"MG11:1.ELE", 14, -1}, {"MG11:2.ERR", 18, -1},
                                   {"MG11:0/ST", 17, 14},  {"MG11:0/DN", 17, 13},  {"MG11:0/ER", 17, 12},
                                   {"MG11:0/EW", 17, 10},  {"MG11:0/R", 17, 0},    {"MG11:0/EN", 16, 15},
                                   {"MG11:0/TO", 16, 8},   {"MG11:0.19", 19, -1},  {"RI12:0.1", 1, -1}});
  std::string err;
  EXPECT_FALSE(parse_address("MG11:0.PRE", &err).has_value());
  EXPECT_NE(err.find("unknown sub-element 'PRE' of an MG element (words RBL, LBN"), std::string::npos) << err;
  EXPECT_FALSE(parse_address("MG11:0.NOD/DN", &err).has_value());
  EXPECT_NE(err.find("a named bit is written MG11:0/DN"), std::string::npos) << err;
  // RI is its own file type, not R; R6:0.LEN is still a control element.
  const auto r = parse_address("R6:0.LEN", &err);
  ASSERT_TRUE(r.has_value()) << err;
  EXPECT_EQ(r->type, FileType::Control);
  EXPECT_EQ(parse_address("RI12:0", &err)->type, FileType::Routing);
}

TEST(MicroLogixMessageFile, OnlyTheMicroLogixWithAMsgFileHaveThem) {
  // MG: the 1100, 1200, 1400, 1500 (1763-RM001B p. 347, 1762-RM001C p. 21-4, 1766-RM001A p. 399).
  for (const char* p : {"Bul.1763", "Bul.1762", "Bul.1766", "1764-LSP", "1764-LRP"})
    EXPECT_EQ(rung_errors(p, "SOR XIC MG11:0/DN OTE B3:0/0 EOR"), "") << p;
  for (const char* p : {"Bul.1761", "1747-L552"}) {
    const std::string e = rung_errors(p, "SOR XIC MG11:0/DN OTE B3:0/0 EOR");
    EXPECT_NE(e.find("t.slc:3:9: error: MG (message) files exist on the MicroLogix 1100, 1200, 1400 and 1500 only"),
              std::string::npos)
        << p << ": " << e;
  }
  // RI: the two controllers whose channel 1 is Ethernet.
  for (const char* p : {"Bul.1763", "Bul.1766"}) EXPECT_EQ(rung_errors(p, "SOR MOV RI12:0.1 N7:0 EOR"), "") << p;
  for (const char* p : {"Bul.1762", "1764-LRP", "1747-L552"})
    EXPECT_NE(rung_errors(p, "SOR MOV RI12:0.1 N7:0 EOR").find("RI (routing information) files exist on the MicroLogix 1100 and 1400"),
              std::string::npos)
        << p;
  // Sub-elements 0-24 and words 0-19.
  EXPECT_NE(rung_errors("Bul.1766", "SOR MOV MG11:0.25 N7:0 EOR").find("an MG element has sub-elements 0-24"),
            std::string::npos);
  EXPECT_NE(rung_errors("Bul.1766", "SOR MOV RI12:0.20 N7:0 EOR").find("an RI element has words 0-19"), std::string::npos);
}

TEST(MicroLogixMessageFile, CheckerRefusesWritesToReadOnlySubElements) {
  // Read/write (the access column of 1762-RM001C p. 21-4): CHN, NOD, MTO, TFN, ELE, the control bits.
  for (const char* ok : {"SOR MOV 1 MG11:0.CHN EOR", "SOR MOV 4 MG11:0.NOD EOR", "SOR MOV 9 MG11:0.MTO EOR",
                         "SOR MOV 10 MG11:0.TFN EOR", "SOR MOV 3 MG11:0.ELE EOR", "SOR OTL MG11:0/TO EOR",
                         "SOR OTU MG11:0/EN EOR", "SOR MOV MG11:0.ERR N7:0 EOR", "SOR XIC MG11:0/ER OTE B3:0/0 EOR",
                         "SOR MOV 30986 RI12:0.1 EOR"})
    EXPECT_EQ(rung_errors("Bul.1766", ok), "") << ok;
  // Read only: the status bits (p. 21-6), ERR, the elapsed time (19), reserved words, the whole element.
  for (const char* ro : {"SOR OTL MG11:0/DN EOR", "SOR OTE MG11:0/ST EOR", "SOR OTU MG11:0/EW EOR",
                         "SOR MOV 0 MG11:0.ERR EOR", "SOR MOV 0 MG11:0.19 EOR", "SOR MOV 0 MG11:0.RBL EOR",
                         "SOR MOV 0 MG11:0 EOR"}) {
    const std::string e = rung_errors("Bul.1766", ro);
    EXPECT_NE(e.find("is read only to the user program (1762-RM001C pp. 21-4, 21-6"), std::string::npos) << ro << ": " << e;
  }
  // A file instruction would write the read-only words with the others.
  EXPECT_NE(rung_errors("Bul.1766", "SOR COP N7:0 MG11:0 25 EOR").find("an MG element is written one sub-element at a time"),
            std::string::npos);
}

// Two MG elements and one RI element, as a DATA block gives them: element 0's NOD 4 (value 9), MTO 5
// (value 10), TFN 7 (13), ELE 2 (14); element 1's ERR 55 (value 25 + 18 = 43); the RI element the
// manual's 10.121.30.11: word 1 790Ah = 30986, word 2 0B1Eh = 2846 (1766-RM001A p. 435).
std::string data_program() {
  std::string mg0 = "0 0 0 0 0 0 0 0 1 4 5 0 0 7 2 0 0 0 0 0 0 0 0 0 0";
  std::string mg1 = "0 0 0 0 0 0 0 0 1 4 5 0 0 7 2 0 0 0 55 0 0 0 0 0 0";
  return "START Bul.1766\nLADDER 2\nSOR XIC B3:0/0 MOV 6 MG11:0.NOD EOR\nSOR XIC MG11:1/ER MOV MG11:1.ERR N7:0 EOR\n"
         "DATA MG11:0\n% MG11:0 % " + mg0 + "\n% MG11:1 % " + mg1 +
         "\nDATA RI12:0\n% RI12:0 % 16 30986 2846 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0\n";
}

TEST(MicroLogixMessageFile, DataBlockFillsTheElementsWordByWord) {
  Controller plc = Controller::from_text(data_program());
  EXPECT_EQ(plc.get_int("MG11:0.NOD"), 4);
  EXPECT_EQ(plc.get_int("MG11:0.MTO"), 5);
  EXPECT_EQ(plc.get_int("MG11:0.TFN"), 7);
  EXPECT_EQ(plc.get_int("MG11:0.ELE"), 2);
  EXPECT_EQ(plc.get_int("MG11:1.ERR"), 55);
  EXPECT_EQ(plc.get_int("RI12:0.1"), 0x790A);
  EXPECT_EQ(plc.get_int("RI12:0.2"), 0x0B1E);
  // The program reads and writes them as any data word: the MOV into NOD lands in element 0 only.
  plc.set("B3:0/0", 1);
  plc.scan(1);
  EXPECT_EQ(plc.get_int("MG11:0.NOD"), 6);
  EXPECT_EQ(plc.get_int("MG11:1.NOD"), 4);
  EXPECT_EQ(plc.get_int("N7:0"), 0) << "MG11:1/ER is clear: its ERR is not copied";
}

TEST(MicroLogixMessageFile, FmtWritesTheDataBackAndItLoadsTheSame) {
  LoadResult r = load_program(data_program(), "t.slc");
  ASSERT_TRUE(r.ok()) << r.render_diagnostics();
  const std::string formatted = format_program(*r.program);
  EXPECT_NE(formatted.find("% MG11:1 % 0 0 0 0 0 0 0 0 1 4 5 0 0 7 2 0 0 0 55 0 0 0 0 0 0 \n"), std::string::npos)
      << formatted;
  EXPECT_NE(formatted.find("MOV 6 MG11:0.NOD"), std::string::npos) << formatted;
  LoadResult again = load_program(formatted, "fmt.slc");
  ASSERT_TRUE(again.ok()) << again.render_diagnostics() << formatted;
  std::string diff;
  EXPECT_TRUE(same_program(*r.program, *again.program, &diff)) << diff;
  // A block whose last element is short is refused with the element's size.
  EXPECT_NE(load_errors("START Bul.1766\nLADDER 2\nSOR MOV MG11:0.NOD N7:0 EOR\nDATA MG11:0\n% MG11:0 % 0 0 0\n")
                .find("each MG element takes 25 values, its words 0-24 (1762-RM001C p. 21-4)"),
            std::string::npos);
}

TEST(MicroLogixMessageFile, StateFileSavesAndRestoresThem) {
  // `--state` keeps the MG and RI words as any data file's: the element written by the program comes back.
  LoadResult loaded = load_program(data_program(), "t.slc");
  ASSERT_TRUE(loaded.ok()) << loaded.render_diagnostics();
  auto made = Runtime::create(*loaded.program);
  ASSERT_TRUE(made.ok()) << made.render_errors();
  made.runtime->set_mode(Mode::Run);
  made.runtime->set("B3:0/0", Value::of_int(1));
  made.runtime->scan(1);
  const auto fp = program_fingerprint(*loaded.program);
  const std::string bytes = encode_state(made.runtime->data(), fp);
  auto fresh = Runtime::create(*loaded.program);
  ASSERT_TRUE(fresh.ok()) << fresh.render_errors();
  const auto r = decode_state(bytes, fp, fresh.runtime->data(), false);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(fresh.runtime->value("MG11:0.NOD").integer, 6);
  EXPECT_EQ(fresh.runtime->value("RI12:0.1").integer, 0x790A);
}

}  // namespace
}  // namespace softslc
