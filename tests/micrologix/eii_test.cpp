// The MicroLogix event input interrupt function file EII (issue 16), through the public Controller
// API as `softslc run` and `softslc test` use it.
//
// Expected values come from the MicroLogix manuals as read (docs/micrologix-function-files-sources.md
// section 2): 1763-RM001C p. 272 (the EII scans a program file when an input condition is detected
// from a field device; four elements EII:0-EII:3 on the 1100), p. 275 (UIX set while the routine
// runs, read only; UIE must be set for the routine to run and, cleared, holds it back; UIL: "1
// active and ... up to 2 pending" before the lost bit, read/write), 1762-RM001C p. 18-19 (UIP, read
// only, set while one waits), p. 18-3 (interrupts are serviced at the start of a rung), p. 18-4
// (Event Interrupt 0 has priority over Event Interrupt 1, and both over the STI). The STI's error
// code 1 "Invalid Program File Number" is 1763-RM001C p. 270. What those pages do not give is
// softslc's decision [U] (docs/semantics.md "The EII function file"), tested here as decided: the
// word and bit layout (PFN ER bits IS; EIE at bit 4, AS 5, ED 6, ES 14), EIE arming the EII, AS
// setting EIE on entry to Run, ES 1 = rising edge, the edge seen when the input terminal changes.
#include <gtest/gtest.h>

#include <string>

#include "load_errors.h"
#include "function_file_test_util.h"
#include "parser/address.h"
#include "parser/formatter.h"
#include "parser/loader.h"
#include "tools/controller/controller.h"

namespace softslc {
namespace {

using test::load_errors;

// A MicroLogix 1100 whose EII:0 runs LAD 3 (which counts its runs in N7:0 and copies UIX to B3:1/0),
// EII:1 LAD 4 (which counts in N7:1). `eii` is the DATA EII:0 block's rows; `main` file 2's rungs.
std::string eii_program(const std::string& eii, const std::string& main = "SOR MOV N7:0 N7:5 EOR\n",
                        const std::string& start = "Bul.1763") {
  return "START " + start + "\nLADDER 2\n" + main +
         "LADDER 3\nSOR ADD N7:0 1 N7:0 EOR\nSOR XIC EII:0/UIX OTE B3:1/0 EOR\nSOR ADD N7:9 1 N7:9 MOV N7:9 N7:10 EOR\n"
         "LADDER 4\nSOR ADD N7:1 1 N7:1 EOR\nSOR ADD N7:9 1 N7:9 MOV N7:9 N7:11 EOR\n"
         "DATA EII0:0\n" + eii + "\n";
}

// Bit words [U]: UIE 0x0002, EIE 0x0010, AS 0x0020, ES (rising) 0x4000.
const std::string kRisingArmed = "% EII0:0 %\n3 0 0X4012 0\n";

TEST(MicroLogixEii, SubElementsParseAndPrintByName) {
  test::expect_named_sub_elements({{"EII:0.PFN", eii::kProgramFile, -1}, {"EII:0.ER", eii::kErrorCode, -1},
                                   {"EII:1.IS", eii::kInputSelect, -1}, {"EII:0/UIX", eii::kBits, eii::kExecutingBit},
                                   {"EII:0/UIE", eii::kBits, eii::kEnableBit}, {"EII:2/UIL", eii::kBits, eii::kLostBit},
                                   {"EII:0/UIP", eii::kBits, eii::kPendingBit}, {"EII:0/EIE", eii::kBits, eii::kEventEnableBit},
                                   {"EII:3/AS", eii::kBits, eii::kAutoStartBit}, {"EII:0/ED", eii::kBits, eii::kErrorBit},
                                   {"EII:0/ES", eii::kBits, eii::kEdgeSelectBit}});
  std::string err;
  EXPECT_FALSE(parse_address("EII:0.SPM", &err).has_value());
  EXPECT_NE(err.find("EII has words PFN, ER, IS and bits UIX, UIE"), std::string::npos) << err;
}

TEST(MicroLogixEii, CheckerRefusesWritesToReadOnlySubElements) {
  auto errors = [](const std::string& rung) { return load_errors("START Bul.1763\nLADDER 2\n" + rung + "\n"); };
  // Read/write: UIE, UIL (1763-RM001C p. 275); EIE [U]. Reading any of them is fine.
  EXPECT_EQ(errors("SOR XIC B3:0/0 OTU EII:0/UIE OTU EII:0/UIL OTL EII:1/EIE EOR"), "");
  EXPECT_EQ(errors("SOR XIC EII:0/UIX XIC EII:0/UIP XIC EII:0/ES MOV EII:0.IS N7:0 MOV EII:0.ER N7:1 EOR"), "");
  // Read only: UIX (p. 275), UIP (1762-RM001C p. 18-19); PFN, ER, IS, AS, ED, ES [U].
  for (const char* rung : {"SOR OTE EII:0/UIX EOR", "SOR OTL EII:0/UIP EOR", "SOR MOV 3 EII:0.PFN EOR", "SOR MOV 1 EII:0.IS EOR",
                           "SOR OTU EII:0/ES EOR", "SOR OTL EII:0/AS EOR", "SOR CLR EII:0.ER EOR"}) {
    SCOPED_TRACE(rung);
    EXPECT_NE(errors(rung).find("is read only to the user program (1763-RM001C p. 275"), std::string::npos) << errors(rung);
  }
  EXPECT_NE(errors("SOR COP #N7:0 #EII:0.PFN 4 EOR").find("the EII function file is written one sub-element at a time"),
            std::string::npos);
}

TEST(MicroLogixEii, EachProcessorHasItsEventInputs) {
  // 1763-RM001C p. 272: EII:0 to EII:3 on the 1100.
  EXPECT_EQ(load_errors("START Bul.1763\nLADDER 2\nSOR XIC EII:3/UIX OTE B3:0/0 EOR\n"), "");
  EXPECT_NE(load_errors("START Bul.1763\nLADDER 2\nSOR XIC EII:4/UIX OTE B3:0/0 EOR\n").find("has 4 event input interrupts, EII:0 to EII:3"),
            std::string::npos);
  // 1762-RM001C p. 18-4 names Event Interrupts 0 to 3 (1200, 1500); the 1400's export has EII0:0 to EII0:7.
  EXPECT_NE(load_errors("START Bul.1762\nLADDER 2\nSOR XIC EII:4/UIX OTE B3:0/0 EOR\n").find("has 4 event input"), std::string::npos);
  EXPECT_EQ(load_errors("START Bul.1764\nLADDER 2\nSOR XIC EII:3/UIX OTE B3:0/0 EOR\n"), "");
  EXPECT_EQ(load_errors("START Bul.1766\nLADDER 2\nSOR XIC EII:7/UIX OTE B3:0/0 EOR\n"), "");
  EXPECT_NE(load_errors("START Bul.1761\nLADDER 2\nSOR XIC EII:0/UIX OTE O:0/0 EOR\n").find("function file EII exists on the MicroLogix 1100"),
            std::string::npos);
}

TEST(MicroLogixEii, DataBlockConfiguresItAndIsChecked) {
  // RSLogix's export form (59-BSGS.SLC) loads, and fmt writes it back in that form.
  const std::string text = eii_program("% EII0:0  %\n     3      0 0X4012      0\n\n% EII0:1  %\n     4      0 0X0012      5\n");
  LoadResult r = load_program(text, "t.slc");
  ASSERT_TRUE(r.ok()) << r.render_diagnostics();
  const std::string formatted = format_program(*r.program);
  EXPECT_NE(formatted.find("% EII0:1 % 4 0 0X0012 5"), std::string::npos) << formatted;
  LoadResult again = load_program(formatted, "fmt.slc");
  ASSERT_TRUE(again.ok()) << again.render_diagnostics() << formatted;
  std::string diff;
  EXPECT_TRUE(same_program(*r.program, *again.program, &diff)) << diff;
  Controller plc = Controller::from_text(text);
  EXPECT_EQ(plc.get_int("EII:1.PFN"), 4);
  EXPECT_EQ(plc.get_int("EII:1.IS"), 5);
  // The elements the block leaves out are RSLogix's defaults: UIE and ES set, IS = the element's number.
  EXPECT_EQ(plc.get_int("EII:3.IS"), 3);
  EXPECT_TRUE(plc.get_bit("EII:3/UIE"));
  EXPECT_TRUE(plc.get_bit("EII:3/ES"));
  EXPECT_FALSE(plc.get_bit("EII:3/EIE"));
  // Error code 1 (1763-RM001C p. 270, the STI's): a PFN below 3, above 255 or without its file.
  for (const char* pfn : {"2", "256", "9"}) {
    SCOPED_TRACE(pfn);
    EXPECT_NE(load_errors(eii_program(std::string(pfn) + " 0 0X4002 0")).find("is not a subroutine file of this program (3-255"),
              std::string::npos);
  }
  EXPECT_NE(load_errors(eii_program("0 0 0X4022 0")).find("EII:0/EIE or /AS is set but EII:0.PFN is 0"), std::string::npos);
  EXPECT_NE(load_errors(eii_program("3 0 0X4012 16")).find("EII:0.IS 16 names no embedded input: 0-15"), std::string::npos);
  EXPECT_NE(load_errors(eii_program("3 0 0X4012")).find("each EII element is four values"), std::string::npos);
  // A 1400's eight default elements on an 1100: the last four are dropped with a warning.
  std::string eight;
  for (int e = 0; e < 8; ++e) eight += "0 0 0X4002 " + std::to_string(e) + "\n";
  LoadResult moved = load_program(eii_program(eight), "t.slc");
  ASSERT_TRUE(moved.ok()) << moved.render_diagnostics();
  EXPECT_NE(moved.render_diagnostics().find("gives 8 EII elements; the MicroLogix 1100 has 4"), std::string::npos);
  std::string configured = eight;
  configured.replace(configured.find("0 0 0X4002 4"), 12, "3 0 0X4012 4");
  EXPECT_NE(load_errors(eii_program(configured)).find("configures EII:4; the MicroLogix 1100 has 4"), std::string::npos)
      << load_errors(eii_program(configured));
}

TEST(MicroLogixEii, RisingEdgeRunsTheRoutineBeforeTheNextRung) {
  Controller plc = Controller::from_text(eii_program(kRisingArmed));
  plc.scan(2);
  EXPECT_EQ(plc.get_int("N7:0"), 0);
  plc.set("I:0/0", 1);
  plc.scan(1);
  // p. 18-3: serviced at the start of a rung: the routine ran before rung 0 copied N7:0 to N7:5.
  EXPECT_EQ(plc.get_int("N7:0"), 1);
  EXPECT_EQ(plc.get_int("N7:5"), 1);
  EXPECT_TRUE(plc.get_bit("B3:1/0")) << "UIX set while the routine runs (1763-RM001C p. 275)";
  EXPECT_FALSE(plc.get_bit("EII:0/UIX")) << "and cleared when it completes";
  EXPECT_FALSE(plc.get_bit("EII:0/UIP"));
  // ES set: the falling edge does nothing; the next rising edge runs it again.
  plc.set("I:0/0", 0);
  plc.scan(3);
  EXPECT_EQ(plc.get_int("N7:0"), 1);
  plc.set("I:0/0", 1);
  plc.scan(1);
  EXPECT_EQ(plc.get_int("N7:0"), 2);
  EXPECT_EQ(plc.get_int("N7:1"), 0) << "EII:1 is not armed";
  ASSERT_FALSE(plc.fault().has_value());
}

TEST(MicroLogixEii, TheEdgeIsSeenAtTheTerminalNotAtTheInputScan) {
  // A pulse shorter than a scan (on and off again between two scans) never reaches the input image,
  // but the EII saw its edge when the input changed [U: the edge is taken at that moment of virtual time].
  Controller plc = Controller::from_text(eii_program(kRisingArmed, "SOR XIC I:0/0 OTE B3:2/0 EOR\n"));
  plc.scan(1);
  plc.set("I:0/0", 1);
  plc.set("I:0/0", 0);
  plc.scan(1);
  EXPECT_FALSE(plc.get_bit("B3:2/0")) << "the input image never saw the pulse";
  EXPECT_EQ(plc.get_int("N7:0"), 1);
}

TEST(MicroLogixEii, EsClearFiresOnTheFallingEdgeOfTheSelectedInput) {
  // IS 2: input I:0/2; ES clear: the falling edge [U].
  Controller plc = Controller::from_text(eii_program("3 0 0X0012 2"));
  plc.scan(1);
  plc.set("I:0/0", 1);
  plc.set("I:0/0", 0);
  plc.set("I:0/2", 1);
  plc.scan(2);
  EXPECT_EQ(plc.get_int("N7:0"), 0) << "I:0/0 is not selected; I:0/2 rose";
  plc.set("I:0/2", 0);
  plc.scan(1);
  EXPECT_EQ(plc.get_int("N7:0"), 1);
}

TEST(MicroLogixEii, EieArmsItAndAsSetsEieOnEnteringRun) {
  // UIE and ES without EIE: no event is taken [U].
  {
    Controller plc = Controller::from_text(eii_program("3 0 0X4002 0", "SOR XIC B3:0/0 OTL EII:0/EIE EOR\n"));
    plc.scan(1);
    plc.set("I:0/0", 1);
    plc.scan(2);
    EXPECT_EQ(plc.get_int("N7:0"), 0);
    // The program sets EIE: the next edge is taken.
    plc.set("B3:0/0", 1);
    plc.set("I:0/0", 0);
    plc.scan(1);
    plc.set("I:0/0", 1);
    plc.scan(1);
    EXPECT_EQ(plc.get_int("N7:0"), 1);
  }
  // AS set: EIE is set on entering Run (the 2080-UM002 wording of the same bit [U]).
  Controller plc = Controller::from_text(eii_program("3 0 0X4022 0"));
  EXPECT_FALSE(plc.get_bit("EII:0/EIE"));
  plc.scan(1);
  EXPECT_TRUE(plc.get_bit("EII:0/EIE"));
  plc.set("I:0/0", 1);
  plc.scan(1);
  EXPECT_EQ(plc.get_int("N7:0"), 1);
}

TEST(MicroLogixEii, UieClearHoldsTwoPendingAndLosesTheThird) {
  // 1763-RM001C p. 275: with UIE clear the routine is not processed; "1 active and ... up to 2
  // pending user interrupt conditions before it sets the lost bit"; UIP while one waits (1762-RM001C
  // p. 18-19). Setting UIE again: "EII subroutine processing resumes" - both waiting runs.
  Controller plc = Controller::from_text(
      eii_program("3 0 0X4010 0", "SOR XIC B3:0/0 OTL EII:0/UIE EOR\nSOR MOV N7:0 N7:5 EOR\n"));
  plc.scan(1);
  for (int k = 0; k < 3; ++k) {
    plc.set("I:0/0", 1);
    plc.scan(1);
    EXPECT_TRUE(plc.get_bit("EII:0/UIP"));
    EXPECT_EQ(plc.get_bit("EII:0/UIL"), k == 2) << k;
    plc.set("I:0/0", 0);
    plc.scan(1);
  }
  EXPECT_EQ(plc.get_int("N7:0"), 0);
  plc.set("B3:0/0", 1);
  plc.scan(1);
  // The OTL on rung 0 set UIE; the two waiting events ran at the next rung start, before rung 1.
  EXPECT_EQ(plc.get_int("N7:0"), 2);
  EXPECT_EQ(plc.get_int("N7:5"), 2);
  EXPECT_FALSE(plc.get_bit("EII:0/UIP"));
  EXPECT_TRUE(plc.get_bit("EII:0/UIL")) << "the program clears it";
}

TEST(MicroLogixEii, EventInterruptZeroRunsBeforeOne) {
  // 1762-RM001C p. 18-4: Event Interrupt 0 has a higher priority than Event Interrupt 1. EII:1's
  // input changes first; both wait for the next scan, and EII:0 runs first.
  Controller plc = Controller::from_text(eii_program("3 0 0X4012 0\n4 0 0X4012 1"));
  plc.scan(1);
  plc.set("I:0/1", 1);
  plc.set("I:0/0", 1);
  plc.scan(1);
  EXPECT_EQ(plc.get_int("N7:10"), 1) << "EII:0's routine ran first";
  EXPECT_EQ(plc.get_int("N7:11"), 2);
}

TEST(MicroLogixEii, AnEiiRunsBeforeTheSti) {
  // p. 18-4: every Event Interrupt has priority over the STI (the lowest). Both wait with UIE clear
  // (the STI every 1 ms, TIE and AS set); rung 0 sets both UIEs, and at the next rung start the
  // EII's routine runs first, then the STI's (LAD 5), each numbering its run in N7:9.
  std::string text = eii_program("3 0 0X4010 0", "SOR XIC B3:0/0 OTL EII:0/UIE OTL STI:0/UIE EOR\nSOR MOV N7:0 N7:5 EOR\n");
  text += "LADDER 5\nSOR ADD N7:9 1 N7:9 MOV N7:9 N7:12 EOR\nDATA STI:0\n5 0 0X0030 1\n";
  Controller plc = Controller::from_text(text);
  plc.scan(1);
  plc.set("I:0/0", 1);
  plc.run_for(5 * kNsPerMs);
  EXPECT_TRUE(plc.get_bit("STI:0/UIP"));
  EXPECT_TRUE(plc.get_bit("EII:0/UIP"));
  plc.set("B3:0/0", 1);
  plc.scan(1);
  ASSERT_FALSE(plc.fault().has_value()) << plc.fault()->to_string();
  EXPECT_EQ(plc.get_int("N7:10"), 1) << "the EII's routine ran first";
  EXPECT_GE(plc.get_int("N7:12"), 2) << "then the STI's";
  EXPECT_EQ(plc.get_int("N7:5"), 1);
}

TEST(MicroLogixEii, NothingFiresOutsideRun) {
  Controller plc = Controller::from_text(eii_program(kRisingArmed));
  plc.scan(1);
  plc.set_mode(Mode::Program);
  plc.set("I:0/0", 1);
  plc.set_mode(Mode::Run);
  plc.scan(2);
  EXPECT_EQ(plc.get_int("N7:0"), 0);
  EXPECT_FALSE(plc.get_bit("EII:0/UIP"));
}

TEST(MicroLogixEii, ABadPfnFromAToolSetsEdAndErOneWithoutAFault) {
  Controller plc = Controller::from_text(eii_program(kRisingArmed));
  plc.scan(1);
  plc.set("EII:0.PFN", 99);  // only a tool can: PFN is read only to the program
  plc.set("I:0/0", 1);
  plc.scan(2);
  EXPECT_FALSE(plc.fault().has_value());
  EXPECT_EQ(plc.get_int("N7:0"), 0);
  EXPECT_TRUE(plc.get_bit("EII:0/ED"));
  EXPECT_EQ(plc.get_int("EII:0.ER"), 1) << "error code 1, Invalid Program File Number (1763-RM001C p. 270)";
  // An IS beyond the embedded input word: ED and softslc's ER 2 at the next input change [U].
  plc.set("EII:1.PFN", 4);
  plc.set("EII:1.IS", 20);
  plc.set("EII:1/EIE", 1);
  plc.set("I:0/5", 1);
  plc.scan(1);
  EXPECT_FALSE(plc.fault().has_value());
  EXPECT_TRUE(plc.get_bit("EII:1/ED"));
  EXPECT_EQ(plc.get_int("EII:1.ER"), 2);
  EXPECT_EQ(plc.get_int("N7:1"), 0);
  // A program that sets EIE on an EII whose PFN is 0: ED and ER 1 at its first edge, nothing runs.
  Controller zero = Controller::from_text(eii_program("0 0 0X4002 0", "SOR XIC B3:0/0 OTL EII:0/EIE EOR\n"));
  zero.set("B3:0/0", 1);
  zero.scan(1);
  zero.set("I:0/0", 1);
  zero.scan(1);
  EXPECT_FALSE(zero.fault().has_value());
  EXPECT_TRUE(zero.get_bit("EII:0/ED"));
  EXPECT_EQ(zero.get_int("EII:0.ER"), 1);
  EXPECT_EQ(zero.get_int("N7:0"), 0);
}

TEST(MicroLogixEii, EveryRssFixtureCarriesItsEiiRecord) {
  // The .RSS function-file record of type 0x15: four elements of four words, 0 0 0x4002 n
  // (docs/micrologix-function-files-sources.md section 6.1).
  LoadResult r = load_program_file(std::string(SOFTSLC_SHARED_DIR) + "/fixtures/rss/drbitboy-PLC_2s_lamp_flash/sti_1000ms_live.RSS");
  ASSERT_TRUE(r.ok()) << r.render_diagnostics();
  const std::string text = format_program(*r.program);
  EXPECT_NE(text.find("DATA EII0:0"), std::string::npos);
  EXPECT_NE(text.find("% EII0:3 % 0 0 0X4002 3"), std::string::npos) << text.substr(text.find("DATA EII0:0"), 200);
}

}  // namespace
}  // namespace softslc
