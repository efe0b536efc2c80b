// The MicroLogix pulse train output: the PTO/PTOX function file and the PTO/PTOX instruction
// (issue 16; docs/semantics.md "The PTO function file").
//
// Manual facts used (docs/micrologix-function-files-sources.md section 4.2): the sub-elements DN, DS,
// RS, AS, IS, ED, NS, OFS, OPP are read only, RP and TOP read/write (1762-RM001C pp. 6-9..6-12,
// 1763-RM001C pp. 136-140, 1766-RM001A p. 146); TOP counts the whole profile and "in all cases, an
// exact number of pulses are produced" (1762-RM001C p. 6-12); OFS ranges to 20,000 Hz on the
// 1200/1500 and the 1100 Series A, 40,000 on the 1100 Series B (1763-RM001C p. 140); DN is set when
// the PTO completes, cleared while its rung is false, and held to the next scan of the instruction
// when it completes with the rung false (1766-RM001A p. 146); IS means not running and no error,
// NS running or done without error (1762-RM001C p. 6-10); status is refreshed when the
// instruction is scanned (1763-RM001C p. 129). What the pages do not give (the word layout beyond
// the fixture, bit positions, CS/EH/EN behaviour, error numbers, the rising-edge start) is softslc's
// [U] decision, tested here as documented.
#include <gtest/gtest.h>

#include <string>
#include <utility>

#include "load_errors.h"
#include "parser/address.h"
#include "function_file_test_util.h"
#include "parser/formatter.h"
#include "parser/loader.h"
#include "parser/rss/rss_reader.h"
#include "tools/controller/controller.h"
#include "vm/timing_profile.h"

namespace softslc {
namespace {

using test::load_errors;

constexpr std::int64_t kMs = 1'000'000;

// A MicroLogix 1100 whose PTO:0 runs while B3:0/0 is true, with `pto0` as PTO:0's DATA row
// (OUT bits ER OF OFS JF TOP OPP ADP).
std::string pto_program(const std::string& pto0, const std::string& start = "Bul.1763", const std::string& extra = "") {
  return "START " + start + "\nLADDER 2\nSOR XIC B3:0/0 PTO 0 EOR\n" + extra + "DATA PTO0:0\n% PTO0:0 %\n" + pto0 + "\n";
}

TEST(MicroLogixPto, SubElementsParseAndPrintByName) {
  test::expect_named_sub_elements({{"PTO:0.OUT", 0, -1}, {"PTO:0.ER", 2, -1}, {"PTO:0.OF", 3, -1}, {"PTO:0.OFS", 4, -1},
                                   {"PTO:0.JF", 5, -1}, {"PTO:0.TOP", 6, -1}, {"PTO:1.OPP", 8, -1}, {"PTO:0.ADP", 10, -1},
                                   {"PTO:0/DN", 1, 0}, {"PTO:0/RS", 1, 2}, {"PTO:0/IS", 1, 5}, {"PTO:0/ED", 1, 6},
                                   {"PTO:0/NS", 1, 7}, {"PTO:0/EH", 1, 8}, {"PTO:0/EN", 1, 9}, {"PTO:0/CS", 1, 10},
                                   {"PTOX:2.OF", 3, -1}, {"PTOX:0.TOP", 9, -1}, {"PTOX:0.ADP", 13, -1}});
  std::string err;
  EXPECT_FALSE(parse_address("PTO:0.FREQ", &err).has_value());
  EXPECT_NE(err.find("PTO has words OUT, ER, OF, OFS, JF, TOP, OPP, ADP and bits DN"), std::string::npos) << err;
  // TOP, OPP, ADP are 32-bit (1762-RM001C p. 6-12); OF/OFS/JF are on the PTOX only [U].
  EXPECT_TRUE(function_word_is_long(static_cast<int>(FunctionFile::PTO), 6));
  EXPECT_FALSE(function_word_is_long(static_cast<int>(FunctionFile::PTO), 3));
  EXPECT_TRUE(function_word_is_long(static_cast<int>(FunctionFile::PTOX), 3));
}

TEST(MicroLogixPto, CheckerRefusesWritesToReadOnlySubElements) {
  auto errors = [](const std::string& rung) { return load_errors("START Bul.1763\nLADDER 2\n" + rung + "\n"); };
  // Read/write: RP, TOP (1762-RM001C pp. 6-9, 6-12); OF, ADP, EH, CS [U] (CS is an OTE's in 2080-MOT-HSC.RSS).
  EXPECT_EQ(errors("SOR XIC B3:0/0 OTE PTO:0/CS OTL PTO:0/RP OTU PTO:0/EH MOV 500 PTO:0.OF MOV 100000 PTO:0.TOP "
                   "MOV 10 PTO:0.ADP EOR"),
            "");
  // Reading the status is fine.
  EXPECT_EQ(errors("SOR XIC PTO:0/DN XIC PTO:0/RS XIO PTO:0/IS MOV PTO:0.OPP N7:0 MOV PTO:1.OFS N7:1 MOV PTO:0.ER N7:2 EOR"), "");
  for (const char* rung : {"SOR OTE PTO:0/DN EOR", "SOR OTL PTO:0/RS EOR", "SOR OTU PTO:0/IS EOR", "SOR OTL PTO:0/ED EOR",
                           "SOR OTL PTO:0/NS EOR", "SOR MOV 0 PTO:0.OPP EOR", "SOR MOV 0 PTO:0.OFS EOR", "SOR MOV 3 PTO:0.OUT EOR",
                           "SOR CLR PTO:0.ER EOR", "SOR MOV 0 PTO:0.9 EOR", "SOR MOV 0 PTO:0.1 EOR"}) {
    SCOPED_TRACE(rung);
    EXPECT_NE(errors(rung).find("is read only to the user program"), std::string::npos) << errors(rung);
  }
  EXPECT_NE(errors("SOR COP #N7:0 #PTO:0.OF 2 EOR").find("written one sub-element at a time"), std::string::npos);
  // Jog is not simulated: a program that uses it loads, with a warning naming it.
  LoadResult jog = load_program("START Bul.1763\nLADDER 2\nSOR XIC B3:0/0 OTE PTO:0/JC MOV 100 PTO:0.JF EOR\n", "t.slc");
  EXPECT_TRUE(jog.ok()) << jog.render_diagnostics();
  EXPECT_EQ(jog.diagnostics.warning_count(), 2u) << jog.render_diagnostics();
  EXPECT_NE(jog.render_diagnostics().find("does not simulate the PTO's jog"), std::string::npos);
  EXPECT_NE(errors("SOR XIC PTO:2/DN OTE B3:0/0 EOR").find("PTO has elements 0-1"), std::string::npos);
}

// PTO on the 1100, 1200, 1500; PTOX on the 1400 (1766-RM001A p. 146); none on the 1000 or an SLC.
TEST(MicroLogixPto, EachControllerHasItsOwnName) {
  for (const char* start : {"Bul.1763", "Bul.1762", "Bul.1764"}) {
    SCOPED_TRACE(start);
    EXPECT_EQ(load_errors(std::string("START ") + start + "\nLADDER 2\nSOR XIC PTO:0/DN PTO 0 EOR\n"), "");
    EXPECT_NE(load_errors(std::string("START ") + start + "\nLADDER 2\nSOR XIC PTOX:0/DN OTE B3:0/0 EOR\n").find("PTOX is the MicroLogix 1400's"),
              std::string::npos);
    EXPECT_NE(load_errors(std::string("START ") + start + "\nLADDER 2\nSOR PTOX 0 EOR\n").find("MicroLogix 1400"), std::string::npos);
  }
  EXPECT_EQ(load_errors("START Bul.1766\nLADDER 2\nSOR XIC PTOX:2/DN PTOX 2 EOR\n"), "");
  EXPECT_NE(load_errors("START Bul.1766\nLADDER 2\nSOR XIC PTO:0/DN OTE B3:0/0 EOR\n").find("is PTOX (1766-RM001A p. 146), not PTO"),
            std::string::npos);
  EXPECT_NE(load_errors("START Bul.1766\nLADDER 2\nSOR PTO 0 EOR\n").find("PTO"), std::string::npos);
  EXPECT_NE(load_errors("START Bul.1761\nLADDER 2\nSOR XIC PTO:0/DN OTE O:0/0 EOR\n").find("exists on the MicroLogix 1100"),
            std::string::npos);
  // Another controller's block (a 1400 export retargeted to an 1100) loads with a warning, unused.
  LoadResult other = load_program("START Bul.1763\nLADDER 2\nSOR XIC B3:0/0 OTE B3:0/1 EOR\nDATA PTOX0:0\n4 0 0 50000 0 0 10 0 0\n", "t.slc");
  EXPECT_TRUE(other.ok()) << other.render_diagnostics();
  EXPECT_NE(other.render_diagnostics().find("the MicroLogix 1100's is PTO: not used"), std::string::npos) << other.render_diagnostics();
  EXPECT_FALSE(load_errors("START Bul.1761\nLADDER 2\nSOR PTO 0 EOR\n").empty());
  EXPECT_FALSE(load_errors("START 1747-L532\nLADDER 2\nSOR PTO 0 EOR\n").empty());
}

TEST(MicroLogixPto, DataBlockLoadsFormatsAndIsChecked) {
  // The ML1400 export's own block (59-BSGS.SLC) and an ML1100 block with long values.
  for (const std::string& text : {std::string("START Bul.1766\nLADDER 2\nSOR XIC B3:0/0 PTOX 0 EOR\nDATA PTOX0:0 \n% PTOX0:0  %\n"
                                             "    -1 0X0000      0             0             0             0\n"
                                             "            0             0             0\n"),
                                 pto_program("2 0X0010 0 40000 0 0 2147483647 0 100")}) {
    LoadResult r = load_program(text, "t.slc");
    ASSERT_TRUE(r.ok()) << r.render_diagnostics();
    EXPECT_EQ(r.render_diagnostics().find("opaque"), std::string::npos);
    const std::string formatted = format_program(*r.program);
    LoadResult again = load_program(formatted, "fmt.slc");
    ASSERT_TRUE(again.ok()) << again.render_diagnostics() << formatted;
    std::string diff;
    EXPECT_TRUE(same_program(*r.program, *again.program, &diff)) << diff;
  }
  Controller plc = Controller::from_text(pto_program("2 0X0010 0 40000 0 0 2147483647 0 100"));
  EXPECT_EQ(plc.get_int("PTO:0.OUT"), 2);
  EXPECT_TRUE(plc.get_bit("PTO:0/RP"));
  EXPECT_EQ(plc.get_int("PTO:0.OF"), 40000 - 65536) << "a 16-bit word; the PTO reads it as 0-65,535";
  EXPECT_EQ(plc.get_int("PTO:0.TOP"), 2147483647);
  EXPECT_EQ(plc.get_int("PTO:0.ADP"), 100);
  EXPECT_EQ(plc.get_int("PTO:1.OUT"), -1) << "an element the block does not give: no output, as RSLogix saves it";
  EXPECT_NE(load_errors(pto_program("2 0X0000 0 1000")).find("each PTO element takes nine values"), std::string::npos);
  EXPECT_NE(load_errors(pto_program("2 0 0 1000 0 0 1 0 0 2 0 0 1000 0 0 1 0 0 2 0 0 1000 0 0 1 0 0")).find("elements 0-1"),
            std::string::npos);
  EXPECT_NE(load_errors(pto_program("2 0 0 70000 0 0 1 0 0")).find("does not fit PTO word"), std::string::npos);
  EXPECT_NE(load_errors(pto_program("2 0 0 1000 0 0 1.5 0 0")).find("holds integers"), std::string::npos);
}

// TOP pulses at OF Hz from the scan whose rung went true; status on every scan of the instruction.
TEST(MicroLogixPto, ProducesTopPulsesAtTheOutputFrequency) {
  Controller plc = Controller::from_text(pto_program("2 0 0 1000 0 0 500 0 0"));
  plc.scan(2);
  EXPECT_TRUE(plc.get_bit("PTO:0/IS")) << "idle on entering Run";
  EXPECT_FALSE(plc.get_bit("PTO:0/RS"));
  const VirtualTime before = plc.now();
  plc.set("B3:0/0", 1);
  plc.scan(1);
  const VirtualTime after = plc.now();  // the start lies between `before` and `after`
  EXPECT_TRUE(plc.get_bit("PTO:0/RS"));
  EXPECT_TRUE(plc.get_bit("PTO:0/NS"));
  EXPECT_TRUE(plc.get_bit("PTO:0/EN"));
  EXPECT_FALSE(plc.get_bit("PTO:0/IS"));
  EXPECT_EQ(plc.get_int("PTO:0.OFS"), 1000);
  plc.run_for(200 * kMs);
  // OPP = whole periods since the start, as of the last scan of PTO 0 (before now).
  const std::int64_t opp = plc.get_int("PTO:0.OPP");
  EXPECT_LE(opp, (plc.now() - before) / kMs);
  EXPECT_GE(opp, (plc.now() - after) / kMs - 2);
  EXPECT_FALSE(plc.get_bit("PTO:0/DN"));
  // 500 pulses at 1 kHz take 500 ms; exactly TOP are produced (1762-RM001C p. 6-12).
  plc.run_for(400 * kMs);
  EXPECT_EQ(plc.get_int("PTO:0.OPP"), 500);
  EXPECT_TRUE(plc.get_bit("PTO:0/DN"));
  EXPECT_TRUE(plc.get_bit("PTO:0/NS")) << "DONE is a normal state";
  EXPECT_TRUE(plc.get_bit("PTO:0/IS"));
  EXPECT_FALSE(plc.get_bit("PTO:0/RS"));
  EXPECT_EQ(plc.get_int("PTO:0.OFS"), 0);
  EXPECT_FALSE(plc.get_bit("O:0/2")) << "the output is low when the train ends";
  // The rung stays true: no restart without a false-to-true transition [U].
  plc.run_for(100 * kMs);
  EXPECT_EQ(plc.get_int("PTO:0.OPP"), 500);
  EXPECT_TRUE(plc.get_bit("PTO:0/DN"));
  // DN clears when the rung is false (1766-RM001A p. 146); a new transition starts again from 0.
  plc.set("B3:0/0", 0);
  plc.scan(1);
  EXPECT_FALSE(plc.get_bit("PTO:0/DN"));
  plc.set("B3:0/0", 1);
  plc.run_for(100 * kMs);
  EXPECT_TRUE(plc.get_bit("PTO:0/RS"));
  EXPECT_LT(plc.get_int("PTO:0.OPP"), 101);
  EXPECT_GT(plc.get_int("PTO:0.OPP"), 90);
}

// The output image bit shows the pulse level when the instruction is scanned: high in the first
// half of each period [U]. At 1 Hz a scan sees each half.
TEST(MicroLogixPto, OutputBitFollowsThePulseLevelAtEachScan) {
  Controller plc = Controller::from_text(pto_program("3 0 0 1 0 0 3 0 0"));
  plc.set("B3:0/0", 1);
  plc.scan(1);
  const VirtualTime start = plc.now();
  auto at = [&](std::int64_t ms) {
    plc.run_for(start + ms * kMs - plc.now());
    return plc.get_bit("O:0/3");
  };
  EXPECT_TRUE(at(250));
  EXPECT_FALSE(at(750));
  EXPECT_EQ(plc.get_int("PTO:0.OPP"), 0);
  EXPECT_TRUE(at(1250));
  EXPECT_EQ(plc.get_int("PTO:0.OPP"), 1);
  EXPECT_FALSE(at(2750));
  EXPECT_EQ(plc.get_int("PTO:0.OPP"), 2);
  EXPECT_FALSE(at(3250));
  EXPECT_EQ(plc.get_int("PTO:0.OPP"), 3);
  EXPECT_TRUE(plc.get_bit("PTO:0/DN"));
}

// 1766-RM001A p. 146: "If the rung is false when the PTO instruction completes, the Done bit is set
// until the next scan of the PTO instruction."
TEST(MicroLogixPto, DoneSeenWithTheRungFalseLastsOneScan) {
  Controller plc = Controller::from_text(pto_program("2 0 0 1000 0 0 50 0 0"));
  plc.set("B3:0/0", 1);
  plc.scan(1);
  plc.set("B3:0/0", 0);
  plc.scan(1);
  EXPECT_TRUE(plc.get_bit("PTO:0/RS")) << "the train runs on with the rung false";
  while (plc.get_bit("PTO:0/RS") && plc.now() < seconds(1)) plc.scan(1);
  EXPECT_EQ(plc.get_int("PTO:0.OPP"), 50);
  EXPECT_TRUE(plc.get_bit("PTO:0/DN"));
  plc.scan(1);
  EXPECT_FALSE(plc.get_bit("PTO:0/DN"));
}

// CS stops a running train at the next scan of the instruction, without an error and without DN [U].
TEST(MicroLogixPto, ControlStopStopsTheTrain) {
  Controller plc = Controller::from_text(pto_program("2 0 0 2000 0 0 100000 0 0", "Bul.1763", "SOR XIC B3:0/1 OTE PTO:0/CS EOR\n"));
  plc.set("B3:0/0", 1);
  plc.run_for(100 * kMs);
  ASSERT_TRUE(plc.get_bit("PTO:0/RS"));
  plc.set("B3:0/1", 1);
  plc.scan(1);
  EXPECT_TRUE(plc.get_bit("PTO:0/RS")) << "CS is written after the PTO rung: the PTO sees it at its next scan";
  plc.scan(1);
  const std::int64_t stopped = plc.get_int("PTO:0.OPP");
  EXPECT_FALSE(plc.get_bit("PTO:0/RS"));
  EXPECT_TRUE(plc.get_bit("PTO:0/IS"));
  EXPECT_FALSE(plc.get_bit("PTO:0/DN"));
  EXPECT_FALSE(plc.get_bit("PTO:0/ED"));
  EXPECT_FALSE(plc.get_bit("O:0/2"));
  plc.run_for(100 * kMs);
  EXPECT_EQ(plc.get_int("PTO:0.OPP"), stopped);
}

// Bad configurations set ED and the error code, and the PTO does not start; the error clears with
// the rung false. The numbers are softslc's [U] (the manual's error table was not reached).
TEST(MicroLogixPto, ABadConfigurationIsAnErrorNotAStart) {
  struct Case {
    const char* start;
    const char* row;
    int error;
  };
  for (const Case& c : {Case{"Bul.1763", "-1 0 0 1000 0 0 10 0 0", -1}, Case{"Bul.1763", "5 0 0 1000 0 0 10 0 0", -1},
                        Case{"Bul.1762", "3 0 0 1000 0 0 10 0 0", -1}, Case{"Bul.1763", "2 0 0 0 0 0 10 0 0", 3},
                        Case{"Bul.1762", "2 0 0 20001 0 0 10 0 0", 3}, Case{"Bul.1763 SERIES A", "2 0 0 20001 0 0 10 0 0", 3},
                        Case{"Bul.1763", "2 0 0 40001 0 0 10 0 0", 3}, Case{"Bul.1763", "2 0 0 1000 0 0 -5 0 0", 7},
                        Case{"Bul.1763", "2 0 0 1000 0 0 10 0 6", 4}, Case{"Bul.1763", "2 0 0 1000 0 0 10 0 -1", 4},
                        Case{"Bul.1763", "2 0X0100 0 1000 0 0 10 0 0", 1}}) {
    SCOPED_TRACE(std::string(c.start) + " " + c.row);
    Controller plc = Controller::from_text(pto_program(c.row, c.start));
    plc.set("B3:0/0", 1);
    plc.run_for(50 * kMs);
    EXPECT_TRUE(plc.get_bit("PTO:0/ED"));
    EXPECT_EQ(plc.get_int("PTO:0.ER"), c.error);
    EXPECT_FALSE(plc.get_bit("PTO:0/RS"));
    EXPECT_FALSE(plc.get_bit("PTO:0/IS")) << "idle means no error (1762-RM001C p. 6-10)";
    EXPECT_FALSE(plc.get_bit("PTO:0/NS"));
    EXPECT_EQ(plc.get_int("PTO:0.OPP"), 0);
    plc.set("B3:0/0", 0);
    plc.scan(1);
    if (c.error != 1) {
      EXPECT_FALSE(plc.get_bit("PTO:0/ED"));
      EXPECT_EQ(plc.get_int("PTO:0.ER"), 0);
      EXPECT_TRUE(plc.get_bit("PTO:0/IS"));
    }
  }
  // The highest frequencies that are not errors: 40,000 Hz on an 1100 Series B, 20,000 on a 1200.
  for (const auto& [start, row] : {std::pair{"Bul.1763", "2 0 0 40000 0 0 10 0 0"}, std::pair{"Bul.1762", "2 0 0 20000 0 0 10 0 0"}}) {
    Controller plc = Controller::from_text(pto_program(row, start));
    plc.set("B3:0/0", 1);
    plc.run_for(50 * kMs);
    EXPECT_FALSE(plc.get_bit("PTO:0/ED")) << start;
    EXPECT_EQ(plc.get_int("PTO:0.OPP"), 10) << start;
  }
}

// EH stops a running train at once with error 1 [U]; clearing EH with the rung false clears it.
TEST(MicroLogixPto, HardStopIsAnError) {
  Controller plc = Controller::from_text(pto_program("2 0 0 1000 0 0 100000 0 0", "Bul.1763", "SOR XIC B3:0/1 OTE PTO:0/EH EOR\n"));
  plc.set("B3:0/0", 1);
  plc.run_for(50 * kMs);
  plc.set("B3:0/1", 1);
  plc.scan(2);  // EH is written after the PTO rung
  EXPECT_FALSE(plc.get_bit("PTO:0/RS"));
  EXPECT_TRUE(plc.get_bit("PTO:0/ED"));
  EXPECT_EQ(plc.get_int("PTO:0.ER"), 1);
  plc.set("B3:0/1", 0);
  plc.set("B3:0/0", 0);
  plc.scan(2);
  EXPECT_FALSE(plc.get_bit("PTO:0/ED"));
  EXPECT_TRUE(plc.get_bit("PTO:0/IS"));
}

// The MicroLogix 1400's PTOX: three elements, long frequencies [U], outputs 2-4.
TEST(MicroLogixPto, PtoxRunsOnTheMicroLogix1400) {
  Controller plc = Controller::from_text(
      "START Bul.1766\nLADDER 2\nSOR XIC B3:0/0 PTOX 2 EOR\nDATA PTOX0:0\n% PTOX0:0 %\n-1 0 0 0 0 0 0 0 0\n"
      "% PTOX0:1 %\n-1 0 0 0 0 0 0 0 0\n% PTOX0:2 %\n4 0 0 50000 0 0 1000 0 0\n");
  plc.set("B3:0/0", 1);
  plc.run_for(100 * kMs);
  EXPECT_FALSE(plc.get_bit("PTOX:2/ED"));
  EXPECT_EQ(plc.get_int("PTOX:2.OFS"), 0) << "done: 1000 pulses at 50 kHz take 20 ms";
  EXPECT_EQ(plc.get_int("PTOX:2.OPP"), 1000);
  EXPECT_TRUE(plc.get_bit("PTOX:2/DN"));
}

// A program sets TOP, a long word, with MOV; the PTO reads all 32 bits.
TEST(MicroLogixPto, TopIsALongWord) {
  Controller plc = Controller::from_text(pto_program("2 0 0 1000 0 0 0 0 0", "Bul.1763", "SOR MOV 70000 PTO:0.TOP EOR\n"));
  plc.scan(1);
  EXPECT_EQ(plc.get_int("PTO:0.TOP"), 70000);
  plc.set("B3:0/0", 1);
  plc.run_for(100 * kMs);
  EXPECT_TRUE(plc.get_bit("PTO:0/RS")) << "70,000 pulses, not 70000 - 65536";
}

TEST(MicroLogixPto, TimingIsAnEstimateInEveryProfile) {
  for (const auto& [key, op] : {std::pair{"ML1100", Opcode::PTO}, std::pair{"ML1200", Opcode::PTO}, std::pair{"ML1500", Opcode::PTO},
                                std::pair{"ML1400", Opcode::PTOX}}) {
    SCOPED_TRACE(key);
    auto p = *builtin_timing_profile(key);
    EXPECT_GT(p.instruction(op).true_ns, 0);
    EXPECT_TRUE(p.is_estimate(p.instruction(op).source)) << "no PTO row was found in the manuals' tables";
  }
}

// ---- The fixture: 20230719_MicroLogix_1100_driver_of_Micro8xx_2080-MOT-HSC.RSS. Its comments: "PTO:0.OUT = 2",
// "PTO:0.OF = frequency Hz ... 2000 for 2kHz", "PTO:0.TOP = 2147483647"; "Toggle T4:0/TT to 1 to restart
// PTO:0"; a 50 ms timer holds PTO:0/CS while it runs and its DN starts PTO 0. --------------------------------

const std::string kFixture = std::string(SOFTSLC_SHARED_DIR) +
                             "/fixtures/rss/drbitboy-PLC_reject_timing/20230719_MicroLogix_1100_driver_of_Micro8xx_2080-MOT-HSC.RSS";

TEST(MicroLogixPto, FixtureCarriesItsConfigurationThroughTheReader) {
  LoadResult r = load_program_file(kFixture);
  ASSERT_TRUE(r.ok()) << r.render_diagnostics();
  Controller plc = Controller::load(kFixture);
  EXPECT_EQ(plc.get_int("PTO:0.OUT"), 2);
  EXPECT_EQ(plc.get_int("PTO:0.OF"), 2000);
  EXPECT_EQ(plc.get_int("PTO:0.TOP"), 2147483647);
  EXPECT_EQ(plc.get_int("PTO:1.OUT"), -1);
}

TEST(MicroLogixPto, FixtureDrivesTwoKilohertzForTenSecondsAndRestarts) {
  Controller plc = Controller::load(kFixture);
  plc.run_for(seconds(10));
  ASSERT_FALSE(plc.fault().has_value()) << plc.fault()->to_string();
  EXPECT_TRUE(plc.get_bit("PTO:0/RS"));
  EXPECT_EQ(plc.get_int("PTO:0.OFS"), 2000);
  // Started when the 50 ms timer is done: about 9.95 s of 2 kHz.
  const std::int64_t opp = plc.get_int("PTO:0.OPP");
  EXPECT_LE(opp, 2000 * 9950 / 1000);
  EXPECT_GE(opp, 2000 * 9940 / 1000);
  // "Toggle T4:0/TT to 1 to restart": CS stops the train while the timer runs, its DN starts it again.
  plc.set("T4:0/TT", 1);
  plc.scan(2);
  EXPECT_FALSE(plc.get_bit("PTO:0/RS"));
  EXPECT_TRUE(plc.get_bit("PTO:0/CS"));
  plc.run_for(100 * kMs);
  EXPECT_TRUE(plc.get_bit("PTO:0/RS"));
  EXPECT_LT(plc.get_int("PTO:0.OPP"), 200) << "counting from 0 again";
  EXPECT_GT(plc.get_int("PTO:0.OPP"), 50);
}

}  // namespace
}  // namespace softslc
