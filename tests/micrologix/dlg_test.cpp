// MicroLogix data logging: DATALOG queues, the DLG instruction and the Data Log Status file DLS0:q
// (issue 16; docs/semantics.md "Data logging: DLG and the DLS file").
//
// Manual facts used: DLG captures on a false-to-true rung transition only (AG-UM008C p. 3-64,
// 1763-RM001C p. 439); DLS0:q has EN (rung true), DN (set when the queue becomes full, cleared
// when a record is retrieved), OV (set when a record is overwritten, kept until the user clears
// it), FSZ (records allocated), RST (records stored, decremented when a record is read) (AG-UM008C
// pp. 3-65, 3-66 Table 3.13); a full queue overwrites its oldest record and retrieval takes the
// oldest first and deletes it (p. 3-66); the record string: date 10 characters, time 8, word 6,
// long word 11, float 13, a delimiter 1, at most 80 characters (1763-RM001C p. 435, AG-UM008C
// p. 3-61) or 109 on the 1400 (1766-RM001A p. 519); memory: 2 bytes per date, time or word, 4 per
// long word, 2 for the integrity check, 128 K bytes on the 1100 and 1400, 48 K on the 1500 LRP
// (1763-RM001C pp. 433-436, 1766-RM001A pp. 518-521, AG-UM008C pp. 3-58..3-61); the example
// records of queue 0 and queue 5 are those pages' tables.
#include <gtest/gtest.h>

#include <string>

#include "load_errors.h"
#include "parser/formatter.h"
#include "parser/loader.h"
#include "tools/controller/controller.h"

namespace softslc {
namespace {

using test::load_errors;

constexpr Nanoseconds kMs = 1'000'000;

// The manuals' queue 0 (Date, Time, Delimiter ',': N7:11 L14:0 T4:5.ACC I1:3.0 B3:2), logged by
// DLG 0 on B3:0/0, on a MicroLogix 1400 with an input module in slot 3 for I1:3.0.
std::string queue0_program(const std::string& start = "Bul.1766") {
  return "START " + start +
         "\nSLOT 3 1762-IQ16 SCAN_IN 1 SCAN_OUT 0\nLADDER 2\nSOR XIC B3:0/0 DLG 0 EOR\nSOR TON T4:5 1.0 1000 0 EOR\n"
         "DATA L14:0\n% L14:0 % 0\n"
         "DATALOG 0 RECORDS 12 DATE TIME DELIMITER COMMA N7:11 L14:0 T4:5.ACC I1:3.0 B3:2\n";
}

// Sets the RTC (the record's date and time come from it) just after a virtual second begins, so the
// clock does not tick before the DLG that follows in the next scan.
void set_clock(Controller& plc, int year, int month, int day, int hour, int minute, int second) {
  plc.run_until([](const Controller& c) { return c.now() % kNsPerS < 100 * kMs; }, 2 * kNsPerS);
  plc.set("RTC:0.YR", year);
  plc.set("RTC:0.MON", month);
  plc.set("RTC:0.DAY", day);
  plc.set("RTC:0.HR", hour);
  plc.set("RTC:0.MIN", minute);
  plc.set("RTC:0.SEC", second);
}

// One false-to-true transition of B3:0/0.
void trigger(Controller& plc) {
  plc.set("B3:0/0", 1);
  plc.scan(1);
  plc.set("B3:0/0", 0);
  plc.scan(1);
}

// 1766-RM001A p. 519 (and 1763-RM001C p. 434), Queue 0, records 0 and 8: the values at the DLG
// and the RTC's date and time, in the manual's record text.
TEST(MicroLogixDataLog, RecordTextIsTheManualsQueue0Example) {
  Controller plc = Controller::from_text(queue0_program());
  plc.scan(1);
  // Record 0: 01/10/2000 , 20:00:00 , 2315 , 103457 , 200 , 8190 , 4465
  set_clock(plc, 2000, 1, 10, 20, 0, 0);
  plc.set("N7:11", 2315);
  plc.set("L14:0", 103457);
  plc.set("T4:5.ACC", 200);
  plc.set("I1:3.0", 8190);
  plc.set("B3:2", 4465);
  plc.scan(1);  // the input scan brings I1:3.0 in
  plc.set("T4:5.ACC", 200);
  trigger(plc);
  // Record 8: 01/11/2000 , 00:00:00 , 2295 , 103457 , 209 , 8145 , 4505
  set_clock(plc, 2000, 1, 11, 0, 0, 0);
  plc.set("N7:11", 2295);
  plc.set("I1:3.0", 8145);
  plc.set("B3:2", 4505);
  plc.scan(1);
  plc.set("T4:5.ACC", 209);
  trigger(plc);
  EXPECT_EQ(plc.get_int("DLS0:0.RST"), 2);
  EXPECT_EQ(plc.get_int("DLS0:0.FSZ"), 12);
  EXPECT_EQ(plc.retrieve_data_log_record(0), "01/10/2000,20:00:00,2315,103457,200,8190,4465");
  EXPECT_EQ(plc.get_int("DLS0:0.RST"), 1) << "RST is decremented when a record is read (AG-UM008C p. 3-66)";
  EXPECT_EQ(plc.retrieve_data_log_record(0), "01/11/2000,00:00:00,2295,103457,209,8145,4505");
  EXPECT_EQ(plc.retrieve_data_log_record(0), std::nullopt);
  EXPECT_EQ(plc.get_int("DLS0:0.RST"), 0);
}

// 1763-RM001C p. 435, Queue 5 (Time, Delimiter TAB: N7:11 I1:3.0 I1:2.1), record 0
// "20:00:00 TAB 2315 TAB 8190 TAB 4465", on a MicroLogix 1100 whose DATALOG logs N7:11 N7:12 N7:13
// (the 1100 has no slots 2 and 3; the record's text depends on the values only).
TEST(MicroLogixDataLog, TimeOnlyTabDelimitedRecordIsTheManualsQueue5Example) {
  Controller plc = Controller::from_text(
      "START Bul.1763\nLADDER 2\nSOR XIC B3:0/0 DLG 5 EOR\n"
      "DATALOG 5 RECORDS 7 TIME DELIMITER TAB N7:11 N7:12 N7:13\n");
  plc.scan(1);
  set_clock(plc, 2009, 10, 1, 20, 0, 0);
  plc.set("N7:11", 2315);
  plc.set("N7:12", 8190);
  plc.set("N7:13", 4465);
  trigger(plc);
  EXPECT_EQ(plc.data_log_records(5), std::vector<std::string>{"20:00:00\t2315\t8190\t4465"});
}

// The values logged are those at the DLG's execution: a rung after the DLG that changes N7:11
// changes the next record, not this one.
TEST(MicroLogixDataLog, CapturesTheValuesWhenTheInstructionExecutes) {
  Controller plc = Controller::from_text(
      "START Bul.1763\nLADDER 2\nSOR XIC B3:0/0 DLG 0 EOR\nSOR XIC B3:0/0 ADD N7:0 1 N7:0 EOR\n"
      "DATALOG 0 RECORDS 4 DELIMITER COMMA N7:0\n");
  plc.scan(1);
  plc.set("N7:0", 10);
  trigger(plc);
  EXPECT_EQ(plc.get_int("N7:0"), 11);
  EXPECT_EQ(plc.data_log_records(0), std::vector<std::string>{"10"});
}

// "The DLG instruction only captures data on a false-to-true rung transition" (AG-UM008C p. 3-64);
// EN is set while the rung is true (p. 3-65).
TEST(MicroLogixDataLog, CapturesOnFalseToTrueTransitionsOnly) {
  Controller plc = Controller::from_text(
      "START Bul.1763\nLADDER 2\nSOR XIC B3:0/0 DLG 0 EOR\nDATALOG 0 RECORDS 10 DELIMITER COMMA N7:0\n");
  plc.scan(3);
  EXPECT_EQ(plc.get_int("DLS0:0.RST"), 0);
  plc.set("B3:0/0", 1);
  plc.scan(5);
  EXPECT_TRUE(plc.get_bit("DLS0:0/EN"));
  EXPECT_EQ(plc.get_int("DLS0:0.RST"), 1) << "five true scans, one record";
  plc.set("B3:0/0", 0);
  plc.scan(1);
  EXPECT_FALSE(plc.get_bit("DLS0:0/EN"));
  plc.set("B3:0/0", 1);
  plc.scan(1);
  EXPECT_EQ(plc.get_int("DLS0:0.RST"), 2);
}

// DN when the queue becomes full; a further record overwrites the oldest and sets OV, which stays
// until the program clears it; retrieving a record clears DN (AG-UM008C pp. 3-65, 3-66).
TEST(MicroLogixDataLog, FullQueueOverwritesTheOldestRecord) {
  Controller plc = Controller::from_text(
      "START Bul.1763\nLADDER 2\nSOR XIC B3:0/0 DLG 0 EOR\nSOR XIC B3:0/1 OTU DLS0:0/OV EOR\n"
      "DATALOG 0 RECORDS 3 DELIMITER COMMA N7:0\n");
  plc.scan(1);
  for (int v = 1; v <= 3; ++v) {
    EXPECT_FALSE(plc.get_bit("DLS0:0/DN")) << v;
    plc.set("N7:0", v);
    trigger(plc);
  }
  EXPECT_TRUE(plc.get_bit("DLS0:0/DN")) << "set when the queue becomes full";
  EXPECT_FALSE(plc.get_bit("DLS0:0/OV"));
  EXPECT_EQ(plc.get_int("DLS0:0.RST"), 3);
  plc.set("N7:0", 4);
  trigger(plc);
  EXPECT_TRUE(plc.get_bit("DLS0:0/OV"));
  EXPECT_EQ(plc.get_int("DLS0:0.RST"), 3);
  EXPECT_EQ(plc.data_log_records(0), (std::vector<std::string>{"2", "3", "4"})) << "record 1 was overwritten";
  EXPECT_EQ(plc.retrieve_data_log_record(0), "2");
  EXPECT_FALSE(plc.get_bit("DLS0:0/DN")) << "cleared when a record is retrieved";
  EXPECT_TRUE(plc.get_bit("DLS0:0/OV")) << "OV remains set until you clear it";
  plc.set("B3:0/1", 1);
  plc.scan(1);
  EXPECT_FALSE(plc.get_bit("DLS0:0/OV"));
  EXPECT_EQ(plc.retrieve_data_log_record(0), "3");
  EXPECT_EQ(plc.retrieve_data_log_record(0), "4");
  EXPECT_EQ(plc.retrieve_data_log_record(0), std::nullopt);
}

// Records are in battery-backed memory outside the data table: a power cycle keeps them
// (1763-RM001C p. 433: "non-volatile (battery-backed) to prevent loss during power-down").
TEST(MicroLogixDataLog, RecordsSurviveModeChanges) {
  Controller plc = Controller::from_text(
      "START Bul.1763\nLADDER 2\nSOR XIC B3:0/0 DLG 0 EOR\nDATALOG 0 RECORDS 3 DELIMITER SPACE N7:0 N7:1\n");
  plc.scan(1);
  plc.set("N7:0", -7);
  plc.set("N7:1", 32767);
  trigger(plc);
  plc.set_mode(Mode::Program);
  plc.set_mode(Mode::Run);
  plc.scan(2);
  EXPECT_EQ(plc.data_log_records(0), std::vector<std::string>{"-7 32767"});
}

TEST(MicroLogixDataLog, FormatRoundTrips) {
  const std::string text =
      "START Bul.1766\nLADDER 2\nSOR XIC B3:0/0 DLG 3 EOR\n"
      "DATALOG 3 RECORDS 100 DATE TIME DELIMITER TAB N7:0 L9:1 F8:2 T4:0.ACC\n"
      "DATALOG 0 RECORDS 5 TIME DELIMITER SPACE N7:1\n";
  LoadResult a = load_program(text, "a.slc");
  ASSERT_TRUE(a.ok()) << a.render_diagnostics();
  const std::string printed = format_program(*a.program);
  EXPECT_NE(printed.find("DATALOG 3 RECORDS 100 DATE TIME DELIMITER TAB N7:0 L9:1 F8:2 T4:0.ACC\n"), std::string::npos) << printed;
  LoadResult b = load_program(printed, "b.slc");
  ASSERT_TRUE(b.ok()) << b.render_diagnostics();
  std::string why;
  EXPECT_TRUE(same_program(*a.program, *b.program, &why)) << why;
}

// Which controllers log: the MicroLogix 1100 and 1500 LRP (AG-UM008C p. 3-58) and the 1400
// (1766-RM001A p. 518); not the 1200, the 1500 LSP or the SLC.
TEST(MicroLogixDataLog, CheckRefusesControllersWithoutDataLogging) {
  for (const std::string start : {"Bul.1762", "1764-LSP", "1747-L532"}) {
    const std::string e = load_errors("START " + start + "\nLADDER 2\nSOR XIC B3:0/0 DLG 0 EOR\n"
                                      "DATALOG 0 RECORDS 5 DELIMITER COMMA N7:0\n");
    EXPECT_NE(e.find("DLG is not available on the"), std::string::npos) << start << e;
    EXPECT_NE(e.find("DATALOG 0: data logging is available on the MicroLogix 1100, 1400, 1500 LRP only"), std::string::npos)
        << start << e;
  }
  for (const std::string start : {"Bul.1763", "Bul.1766", "1764-LRP"})
    EXPECT_EQ(load_errors("START " + start + "\nLADDER 2\nSOR XIC B3:0/0 DLG 0 EOR\n"
                          "DATALOG 0 RECORDS 5 DELIMITER COMMA N7:0\n"), "") << start;
}

TEST(MicroLogixDataLog, CheckRefusesUnconfiguredQueues) {
  const std::string e = load_errors("START Bul.1763\nLADDER 2\nSOR XIC B3:0/0 DLG 1 EOR\nSOR XIC DLS0:2/DN OTE B3:0/1 EOR\n"
                                    "DATALOG 0 RECORDS 5 DELIMITER COMMA N7:0\n");
  EXPECT_NE(e.find("DLG 1: data log queue 1 is not configured"), std::string::npos) << e;
  EXPECT_NE(e.find("DLS0:2/DN: data log queue 2 is not configured"), std::string::npos) << e;
  EXPECT_NE(load_errors("START Bul.1763\nLADDER 2\nSOR XIC B3:0/0 DLG 0 EOR\nDATALOG 0 RECORDS 5 DELIMITER COMMA N7:0\n"
                        "DATALOG 0 RECORDS 6 DELIMITER COMMA N7:1\n")
                .find("DATALOG 0 is configured twice"),
            std::string::npos);
  // The status bits are the controller's, except OV (the user clears it).
  EXPECT_NE(load_errors("START Bul.1763\nLADDER 2\nSOR XIC B3:0/0 OTE DLS0:0/DN EOR\nDATALOG 0 RECORDS 5 DELIMITER COMMA N7:0\n")
                .find("DLS0:0/DN is read only to the user program"),
            std::string::npos);
  EXPECT_EQ(load_errors("START Bul.1763\nLADDER 2\nSOR XIC B3:0/0 OTU DLS0:0/OV EOR\nDATALOG 0 RECORDS 5 DELIMITER COMMA N7:0\n"),
            "");
}

// 1763-RM001C p. 435: queue 0 takes 18 bytes a record, so one queue holds at most 7281 records in
// 128 K; p. 436: queue 5 takes 10 bytes, 13107 records. AG-UM008C p. 3-60/3-61: 2730 and 4915 in
// the 1500 LRP's 48 K.
TEST(MicroLogixDataLog, CheckEnforcesTheDataLogMemory) {
  const auto queue0 = [](const std::string& start, int records) {
    return load_errors("START " + start + "\nLADDER 2\nSOR XIC B3:0/0 DLG 0 EOR\nDATALOG 0 RECORDS " +
                       std::to_string(records) + " DATE TIME DELIMITER COMMA N7:11 L14:0 T4:5.ACC N7:12 B3:2\n");
  };
  const auto queue5 = [](const std::string& start, int records) {
    return load_errors("START " + start + "\nLADDER 2\nSOR XIC B3:0/0 DLG 5 EOR\nDATALOG 5 RECORDS " +
                       std::to_string(records) + " TIME DELIMITER TAB N7:11 N7:12 N7:13\n");
  };
  EXPECT_EQ(queue0("Bul.1763", 7281), "");
  EXPECT_NE(queue0("Bul.1763", 7282).find("the DATALOG queues need 131076 bytes"), std::string::npos) << queue0("Bul.1763", 7282);
  EXPECT_EQ(queue5("Bul.1763", 13107), "");
  EXPECT_NE(queue5("Bul.1763", 13108), "");
  EXPECT_EQ(queue0("1764-LRP", 2730), "");
  EXPECT_NE(queue0("1764-LRP", 2731), "");
  EXPECT_EQ(queue5("1764-LRP", 4915), "");
  EXPECT_NE(queue5("1764-LRP", 4916), "");
}

// The formatted record's length limit: 80 characters on the 1100 (1763-RM001C p. 435), 109 on the
// 1400 (1766-RM001A p. 519). Date, time and six long words: 10+8+6*11 and 7 delimiters = 91.
TEST(MicroLogixDataLog, CheckEnforcesTheRecordLength) {
  const std::string q = "DATALOG 0 RECORDS 5 DATE TIME DELIMITER COMMA L9:0 L9:1 L9:2 L9:3 L9:4 L9:5\n";
  const std::string e = load_errors("START Bul.1763\nLADDER 2\nSOR XIC B3:0/0 DLG 0 EOR\n" + q);
  EXPECT_NE(e.find("the formatted record is 91 characters; the MicroLogix 1100 allows 80"), std::string::npos) << e;
  EXPECT_EQ(load_errors("START Bul.1766\nLADDER 2\nSOR XIC B3:0/0 DLG 0 EOR\n" + q), "");
  // The manuals' queue 0 is 59 characters (1766-RM001A p. 519): accepted on the 1100 too.
  EXPECT_EQ(load_errors("START Bul.1763\nLADDER 2\nSOR XIC B3:0/0 DLG 0 EOR\n"
                        "DATALOG 0 RECORDS 12 DATE TIME DELIMITER COMMA N7:11 L14:0 T4:5.ACC N7:12 B3:2\n"),
            "");
}

TEST(MicroLogixDataLog, CheckRefusesFieldsThatAreNotWords) {
  const auto e = [](const std::string& start, const std::string& field) {
    return load_errors("START " + start + "\nLADDER 2\nSOR XIC B3:0/0 DLG 0 EOR\nDATALOG 0 RECORDS 5 DELIMITER COMMA " + field + "\n");
  };
  EXPECT_NE(e("Bul.1763", "B3:0/1").find("a field is a direct word"), std::string::npos);
  EXPECT_NE(e("Bul.1763", "N7:[N7:1]").find("a field is a direct word"), std::string::npos);
  EXPECT_NE(e("Bul.1763", "F8:0").find("logs words and long words only"), std::string::npos);
  EXPECT_EQ(e("Bul.1766", "F8:0"), "");
  EXPECT_NE(load_errors("START Bul.1763\nLADDER 2\nDATALOG 0 RECORDS 0 DELIMITER COMMA N7:0\n").find("at least 1 record"),
            std::string::npos);
  EXPECT_NE(load_errors("START Bul.1763\nLADDER 2\nDATALOG 0 RECORDS 5 DELIMITER PIPE N7:0\n").find("expected COMMA, TAB or SPACE"),
            std::string::npos);
}

// RCP (recipes) is a real MicroLogix instruction softslc does not run yet: refused by name, not
// taken for a typo (docs/instructions.md).
TEST(MicroLogixDataLog, RecipeInstructionIsRefusedByName) {
  const std::string e = load_errors("START Bul.1763\nLADDER 2\nSOR XIC B3:0/0 RCP 0 1 EOR\n");
  EXPECT_NE(e.find("instruction RCP is not supported by softslc yet"), std::string::npos) << e;
}

}  // namespace
}  // namespace softslc
