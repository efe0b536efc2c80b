// The MicroLogix high-speed counter function file HSC, HSL and RAC (issue 16), through the public
// Controller API as `softslc run` and `softslc test` use them.
//
// Expected values come from the MicroLogix manuals as read (docs/micrologix-function-files-sources.md
// section 3): 1762-RM001C p. 5-10 (LPI read/write, LPR read only, modes 2 to 7), p. 5-13 (UFI, OF
// read/write; OF set when the accumulator counts through the overflow value), p. 5-23 (OVF: counting
// past it rolls the accumulator to UNF, no count lost; OVF must be greater than HIP; SP low to high
// loads the function file), p. 5-24 (OMB read only; the outputs it selects follow HPO), p. 5-27
// (RAC writes the accumulator; HSC1 on the 1500 only; 21.2 / 17.8 us), 1766-RM001A p. 127 (UNF must
// be <= LOP). What the manuals as found do not say is softslc's decision [U] (docs/semantics.md "The
// HSC function file"), tested here as decided: the word and bit layout, mode 0 clearing at HIP and
// setting MD, FE enabling the count, HSL loading at once.
#include <gtest/gtest.h>

#include <string>

#include "load_errors.h"
#include "parser/address.h"
#include "function_file_test_util.h"
#include "parser/formatter.h"
#include "parser/loader.h"
#include "tools/controller/controller.h"
#include "vm/timing_profile.h"

namespace softslc {
namespace {

using test::load_errors;

// A MicroLogix 1100 with `rungs` in file 2 and DATA HSC:0 `hsc` (13 values as RSLogix exports them).
std::string hsc_program(const std::string& hsc, const std::string& rungs = "SOR XIC B3:0/0 OTE HSC:0/FE EOR\n",
                        const std::string& start = "Bul.1763") {
  return "START " + start + "\nLADDER 2\n" + rungs + "DATA HSC:0\n" + hsc + "\n";
}

// Mode 0 with the given long words and output mask/pattern.
std::string config(std::int64_t acc, std::int64_t hip, std::int64_t lop, std::int64_t ovf, std::int64_t unf, int omb = 0,
                   int hpo = 0, int mode = 0) {
  return "0 0 0X0002 0X000F " + std::to_string(mode) + "\n" + std::to_string(acc) + " " + std::to_string(hip) + " " +
         std::to_string(lop) + " " + std::to_string(ovf) + " " + std::to_string(unf) + "\n" + std::to_string(omb) + " " +
         std::to_string(hpo) + " 0";
}

TEST(MicroLogixHsc, SubElementsParseAndPrintByName) {
  test::expect_named_sub_elements({{"HSC:0.PFN", hsc::kProgramFile, -1}, {"HSC:0.MOD", hsc::kMode, -1},
                                   {"HSC:0.ACC", hsc::kAccumulator, -1}, {"HSC:0.HIP", hsc::kHighPreset, -1},
                                   {"HSC:0.OVF", hsc::kOverflow, -1}, {"HSC:0.OMB", hsc::kOutputMask, -1},
                                   {"HSC:0/FE", hsc::kBits, hsc::kFunctionEnabledBit}, {"HSC:0/SP", hsc::kBits, hsc::kSetParametersBit},
                                   {"HSC:0/LPI", hsc::kBits, hsc::kLowInterruptBit}, {"HSC:0/OF", hsc::kStatus, hsc::kOverflowBit},
                                   {"HSC:0/LPR", hsc::kStatus, hsc::kLowReachedBit}, {"HSC:0/MD", hsc::kStatus, hsc::kModeDoneBit}});
  // ACC, HIP, LOP, OVF, UNF are 32-bit (1762-RM001C p. 5-23: OVF "long word (32-bit INT)").
  for (int w : {hsc::kAccumulator, hsc::kHighPreset, hsc::kLowPreset, hsc::kOverflow, hsc::kUnderflow})
    EXPECT_TRUE(function_word_is_long(static_cast<int>(FunctionFile::HSC), w)) << w;
  EXPECT_FALSE(function_word_is_long(static_cast<int>(FunctionFile::HSC), hsc::kOutputMask));
  std::string err;
  EXPECT_FALSE(parse_address("HSC:0.PRE", &err).has_value());
  EXPECT_NE(err.find("HSC has words PFN, ER, MOD, ACC"), std::string::npos) << err;
}

TEST(MicroLogixHsc, CheckerRefusesWritesToReadOnlySubElements) {
  auto errors = [](const std::string& rung) { return load_errors("START Bul.1763\nLADDER 2\n" + rung + "\n"); };
  // Read/write: LPI (p. 5-10), UFI and OF (p. 5-13), OVF (p. 5-23); FE, SP, ACC, HIP [U].
  EXPECT_EQ(errors("SOR XIC B3:0/0 OTU HSC:0/LPI OTU HSC:0/UFI OTU HSC:0/OF OTE HSC:0/FE OTE HSC:0/SP EOR"), "");
  EXPECT_EQ(errors("SOR XIC B3:0/0 MOV L9:0 HSC:0.OVF MOV 5 HSC:0.HIP MOV 0 HSC:0.ACC EOR"), "");
  // Read only: LPR (p. 5-10), OMB (p. 5-24); MOD, PFN [U]. Reading them is fine.
  EXPECT_EQ(errors("SOR XIC HSC:0/LPR MOV HSC:0.OMB N7:0 MOV HSC:0.MOD N7:1 EOR"), "");
  for (const char* rung : {"SOR OTE HSC:0/LPR EOR", "SOR MOV 1 HSC:0.OMB EOR", "SOR MOV 1 HSC:0.MOD EOR", "SOR CLR HSC:0.PFN EOR"}) {
    SCOPED_TRACE(rung);
    EXPECT_NE(errors(rung).find("is read only to the user program"), std::string::npos) << errors(rung);
  }
  EXPECT_NE(errors("SOR COP #N7:0 #HSC:0.HIP 2 EOR").find("the HSC function file is written one sub-element at a time"),
            std::string::npos);
}

TEST(MicroLogixHsc, EachProcessorHasItsCounters) {
  // 1762-RM001C p. 5-27: counter 0 = HSC0 (MicroLogix 1200 and 1500), 1 = HSC1 (MicroLogix 1500 only).
  EXPECT_EQ(load_errors("START Bul.1764\nLADDER 2\nSOR XIC HSC:1/MD RAC HSC1 0 EOR\n"), "");
  EXPECT_NE(load_errors("START Bul.1762\nLADDER 2\nSOR XIC HSC:1/MD OTE B3:0/0 EOR\n").find("has 1 high-speed counter(s)"),
            std::string::npos);
  EXPECT_NE(load_errors("START Bul.1762\nLADDER 2\nSOR RAC HSC1 0 EOR\n").find("RAC counter HSC1"), std::string::npos);
  // The MicroLogix 1400's export writes HSC0:0 to HSC0:5 (59-BSGS.SLC); its .RSS-saved 1100 projects one.
  EXPECT_EQ(load_errors("START Bul.1766\nLADDER 2\nSOR XIC HSC:5/MD HSL HSC5 10 0 0 0 EOR\n"), "");
  EXPECT_NE(load_errors("START Bul.1763\nLADDER 2\nSOR XIC HSC:1/MD OTE B3:0/0 EOR\n").find("has 1 high-speed counter(s)"),
            std::string::npos);
  // Not on the MicroLogix 1000 (its HSC is the C5:0 counter) or an SLC.
  EXPECT_NE(load_errors("START Bul.1761\nLADDER 2\nSOR XIC HSC:0/MD OTE O:0/0 EOR\n").find("function file HSC exists on the MicroLogix 1100"),
            std::string::npos);
  EXPECT_NE(load_errors("START 1747-L532\nLADDER 2\nSOR RAC 0 N7:0 EOR\n").find("RAC"), std::string::npos);
}

TEST(MicroLogixHsc, DataBlockConfiguresItAndIsChecked) {
  // RSLogix's export form loads, and fmt writes it back in that form.
  const std::string text = hsc_program("% HSC0:0  %\n     0      0 0X0002 0X000F      0\n"
                                       "            0    100   -2147483648    2147483647   -2147483648\n     1      1      0\n");
  LoadResult r = load_program(text, "t.slc");
  ASSERT_TRUE(r.ok()) << r.render_diagnostics();
  const std::string formatted = format_program(*r.program);
  EXPECT_NE(formatted.find(" 2147483647  -2147483648"), std::string::npos) << formatted;
  LoadResult again = load_program(formatted, "fmt.slc");
  ASSERT_TRUE(again.ok()) << again.render_diagnostics() << formatted;
  std::string diff;
  EXPECT_TRUE(same_program(*r.program, *again.program, &diff)) << diff;
  // OVF must be greater than HIP (1762-RM001C p. 5-23; equal is RSLogix's own default, 2147483647 both,
  // and is accepted), UNF less than or equal to LOP (1766-RM001A p. 127).
  EXPECT_NE(load_errors(hsc_program(config(0, 100, 0, 99, -5))).find("OVF 99 must not be less than HIP 100"), std::string::npos);
  EXPECT_EQ(load_errors(hsc_program(config(0, 2147483647, 0, 2147483647, -5))), "");
  EXPECT_NE(load_errors(hsc_program(config(0, 100, -6, 1000, -5))).find("UNF -5 must be less than or equal to LOP -6"),
            std::string::npos);
  // A mode without a source is refused by name, not guessed.
  EXPECT_NE(load_errors(hsc_program(config(0, 100, 0, 1000, -5, 0, 0, 2))).find("HSC:0.MOD 2: softslc simulates HSC mode 0"),
            std::string::npos);
  EXPECT_NE(load_errors(hsc_program("0 0 0X0002 0X000F 0\n0 100 0 1000")).find("13 values"), std::string::npos);
  EXPECT_NE(load_errors(hsc_program("9 0 0X0002 0X000F 0\n0 100 0 1000 -5\n0 0 0")).find("HSC:0.PFN 9 is not a subroutine file"),
            std::string::npos);
}

TEST(MicroLogixHsc, FeEnablesCountingOfInjectedPulses) {
  Controller plc = Controller::from_text(hsc_program(config(0, 1000000, 0, 2000000, 0)));
  plc.inject("HSC0", "pulses", {"2000"});
  plc.run_for(100 * kNsPerMs);
  plc.inject("HSC0", "pulses", {"0"});
  const std::int64_t while_clear = plc.observe("HSC0", "pulses").at(0);
  EXPECT_GE(while_clear, 200);
  plc.scan(1);
  EXPECT_EQ(plc.get_int("HSC:0.ACC"), 0) << "FE clear: not counted";
  plc.set("B3:0/0", 1);
  plc.scan(2);
  EXPECT_TRUE(plc.get_bit("HSC:0/FE"));
  plc.inject("HSC0", "pulses", {"2000"});
  plc.run_for(100 * kNsPerMs);
  plc.inject("HSC0", "pulses", {"0"});
  const std::int64_t total = plc.observe("HSC0", "pulses").at(0);
  plc.scan(1);
  // One count per pulse delivered since FE was set, none lost or added by rounding: 2000 a second
  // for at least 100 ms of whole scans.
  EXPECT_EQ(plc.get_int("HSC:0.ACC"), total - while_clear);
  EXPECT_GE(total - while_clear, 200);
  EXPECT_LE(total - while_clear, 202);
  EXPECT_TRUE(plc.get_bit("HSC:0/CU"));
}

TEST(MicroLogixHsc, CountingThroughOverflowRollsToUnderflowAndSetsOf) {
  // p. 5-23: past OVF the accumulator rolls over to UNF, counts not lost; p. 5-13: OF set. ACC starts
  // above HIP (100), so it counts on towards OVF.
  Controller plc = Controller::from_text(hsc_program(config(2147483640, 100, 0, 2147483647, -10), "SOR OTE HSC:0/FE EOR\n"));
  plc.scan(1);
  plc.inject("HSC0", "pulses", {"1000"});
  plc.run_for(12 * kNsPerMs);
  plc.inject("HSC0", "pulses", {"0"});
  const std::int64_t n = plc.observe("HSC0", "pulses").at(0);
  ASSERT_GE(n, 12);
  ASSERT_LT(n, 100);
  plc.scan(1);
  // 7 pulses reach OVF (2147483647), the 8th lands on UNF (-10), the rest count up from there.
  EXPECT_EQ(plc.get_int("HSC:0.ACC"), -10 + (n - 8));
  EXPECT_TRUE(plc.get_bit("HSC:0/OF"));
  EXPECT_FALSE(plc.get_bit("HSC:0/MD"));
}

TEST(MicroLogixHsc, ModeZeroClearsAtTheHighPresetAndDrivesTheMaskedOutputs) {
  // HIP 10, OMB 0x0003, HPO 0x0001: at the high preset O:0/0 goes on and O:0/1 off (p. 5-24);
  // O:0/2 is not in the mask and keeps the program's value.
  Controller plc = Controller::from_text(
      hsc_program(config(0, 10, 0, 1000, 0, 3, 1), "SOR OTE HSC:0/FE EOR\nSOR OTE O:0/2 EOR\nSOR XIC B3:0/1 OTL O:0/1 EOR\n"));
  plc.set("B3:0/1", 1);
  plc.scan(1);
  plc.set("B3:0/1", 0);
  plc.inject("HSC0", "pulses", {"1000"});
  plc.run_for(25 * kNsPerMs);
  plc.inject("HSC0", "pulses", {"0"});
  const std::int64_t n = plc.observe("HSC0", "pulses").at(0);
  plc.scan(1);
  EXPECT_EQ(plc.get_int("HSC:0.ACC"), n % 10);
  EXPECT_TRUE(plc.get_bit("HSC:0/MD"));
  EXPECT_TRUE(plc.get_bit("O:0/0"));
  EXPECT_FALSE(plc.get_bit("O:0/1"));
  EXPECT_TRUE(plc.get_bit("O:0/2"));
}

TEST(MicroLogixHsc, SpLoadsTheFileHslAndRacLoadTheRunningCounter) {
  Controller plc = Controller::from_text(hsc_program(
      config(0, 1000, 0, 100000, 0),
      "SOR OTE HSC:0/FE EOR\nSOR XIC B3:0/1 OTE HSC:0/SP EOR\nSOR XIC B3:0/2 HSL HSC0 N7:0 N7:1 5 6 EOR\n"
      "SOR XIC B3:0/3 RAC HSC0 L9:0 EOR\n") + "DATA N7:0\n20 0\nDATA L9:0\n70000 0\n");
  plc.scan(1);
  // A program write to HIP reaches the counter only with SP low to high (p. 5-23).
  plc.set("HSC:0.HIP", 5);
  plc.inject("HSC0", "pulses", {"1000"});
  plc.run_for(8 * kNsPerMs);
  EXPECT_FALSE(plc.get_bit("HSC:0/MD")) << "still counting to 1000";
  plc.set("B3:0/1", 1);
  plc.run_for(2 * kNsPerMs);
  // The SP load took the file's ACC (what the counter had written there) and HIP 5: above HIP, so it
  // counts on to OVF; RAC brings it back.
  plc.set("B3:0/3", 1);
  plc.scan(1);
  plc.inject("HSC0", "pulses", {"0"});
  EXPECT_EQ(plc.get_int("HSC:0.ACC"), 70000) << "RAC (p. 5-27)";
  plc.set("B3:0/3", 0);
  // HSL: HIP 20, LOP 0, HPO 5, LPO 6 into the file and the counter.
  plc.set("B3:0/2", 1);
  plc.scan(1);
  EXPECT_EQ(plc.get_int("HSC:0.HIP"), 20);
  EXPECT_EQ(plc.get_int("HSC:0.HPO"), 5);
  EXPECT_EQ(plc.get_int("HSC:0.LPO"), 6);
  EXPECT_FALSE(plc.get_bit("HSC:0/ED"));
  plc.set("B3:0/2", 0);
  // SP loads OVF 1000 from the file (HIP 20 < 1000: accepted).
  plc.set("HSC:0.OVF", 1000);
  plc.set("B3:0/1", 0);
  plc.scan(1);
  plc.set("B3:0/1", 1);
  plc.scan(2);
  EXPECT_FALSE(plc.get_bit("HSC:0/ED"));
  // An HSL high preset the overflow does not exceed is refused (p. 5-23): ED set, nothing loaded [U].
  plc.set("N7:0", 32000);
  plc.set("B3:0/2", 1);
  plc.scan(1);
  EXPECT_TRUE(plc.get_bit("HSC:0/ED"));
  EXPECT_EQ(plc.get_int("HSC:0.HIP"), 20);
}

TEST(MicroLogixHsc, PulseSourceRefusesWhatItCannotBe) {
  Controller plc = Controller::from_text(hsc_program(config(0, 100, 0, 1000, 0)));
  EXPECT_THROW(plc.inject("HSC0", "pulses", {"1000001"}), std::exception);
  EXPECT_THROW(plc.inject("HSC0", "pulses", {"1.5"}), std::exception);
  EXPECT_THROW(plc.inject("HSC0", "pulse", {"10"}), std::exception);
  EXPECT_THROW(plc.inject("HSC1", "pulses", {"10"}), std::exception) << "a MicroLogix 1100 has HSC0 only";
  plc.inject("HSC0", "pulses", {"1000000"});
  plc.run_for(kNsPerMs);
  EXPECT_GE(plc.observe("HSC0", "pulses").at(0), 1000);
}

TEST(MicroLogixHsc, RacTimingIsTheManualsOnThe1200And1500) {
  // 1762-RM001C p. 5-27: RAC 21.2 us (1200) and 17.8 us (1500) true, 0.0 us false.
  auto p1200 = *builtin_timing_profile("ML1200");
  EXPECT_EQ(p1200.instruction(Opcode::RAC).true_ns, 21200);
  EXPECT_EQ(p1200.instruction(Opcode::RAC).false_ns, 0);
  EXPECT_FALSE(p1200.is_estimate(p1200.instruction(Opcode::RAC).source));
  auto p1500 = *builtin_timing_profile("ML1500");
  EXPECT_EQ(p1500.instruction(Opcode::RAC).true_ns, 17800);
  for (const char* key : {"ML1100", "ML1200", "ML1400", "ML1500"}) {
    SCOPED_TRACE(key);
    auto p = *builtin_timing_profile(key);
    EXPECT_TRUE(p.is_estimate(p.instruction(Opcode::HSL).source)) << "no HSL figure found";
  }
  for (const char* key : {"ML1100", "ML1400"}) {
    auto p = *builtin_timing_profile(key);
    EXPECT_TRUE(p.is_estimate(p.instruction(Opcode::RAC).source)) << key;
  }
}

// ---- The HSC interrupt ------------------------------------------------------------------------------------
// The PFN routine runs when the counter reaches its high preset or counts through OVF, with the STI's
// and EII's pending/lost rules (1763-RM001C p. 275: "1 active and ... up to 2 pending") and priority
// (1762-RM001C p. 18-4: High-Speed Counter Interrupt 0 below Event Interrupts 0 and 1, above Event
// Interrupt 2 and the STI). [U], as decided in docs/semantics.md "The HSC function file": a set mask
// bit (HPM, OFM) lets its event interrupt, as RSLogix's default 0X000F and TVZ_1100_REV02's 0XB00F have
// them; UIE holds the routine back while clear; HPI or OFI says which event it was; the counter is
// updated (and its events taken) at the start of each scan and at HSL and RAC.

// PFN 3, UIE (and `bits`), masks `status`; LAD 3 counts its runs in N7:0 and copies HPI to B3:1/0.
std::string hsc_interrupt_program(const std::string& bits, const std::string& status, std::int64_t hip, std::int64_t acc = 0,
                                  std::int64_t ovf = 1000000) {
  return "START Bul.1763\nLADDER 2\nSOR OTE HSC:0/FE EOR\nSOR XIC B3:0/0 OTL HSC:0/UIE EOR\nSOR MOV N7:0 N7:5 EOR\n"
         "LADDER 3\nSOR ADD N7:0 1 N7:0 EOR\nSOR XIC HSC:0/HPI OTE B3:1/0 EOR\nSOR XIC HSC:0/OFI OTE B3:1/1 EOR\n"
         "DATA HSC:0\n3 0 " + bits + " " + status + " 0\n" + std::to_string(acc) + " " + std::to_string(hip) + " -10 " +
         std::to_string(ovf) + " -10\n0 0 0\n";
}

TEST(MicroLogixHsc, HighPresetRunsTheInterruptRoutine) {
  // 1000 pulses a second, HIP 10: a high preset every 10 ms, each one run of LAD 3 at the next scan.
  Controller plc = Controller::from_text(hsc_interrupt_program("0X0002", "0X000F", 10));
  plc.scan(1);
  plc.inject("HSC0", "pulses", {"1000"});
  plc.run_for(95 * kNsPerMs);
  plc.inject("HSC0", "pulses", {"0"});
  const std::int64_t n = plc.observe("HSC0", "pulses").at(0);
  plc.scan(1);
  ASSERT_FALSE(plc.fault().has_value()) << plc.fault()->to_string();
  EXPECT_EQ(plc.get_int("N7:0"), n / 10);
  EXPECT_GE(n / 10, 9);
  EXPECT_EQ(plc.get_int("N7:5"), n / 10) << "at the first rung start of the scan, before rung 2";
  EXPECT_TRUE(plc.get_bit("B3:1/0")) << "HPI: the high preset caused it";
  EXPECT_FALSE(plc.get_bit("HSC:0/UIX"));
  EXPECT_FALSE(plc.get_bit("HSC:0/UIP"));
  EXPECT_FALSE(plc.get_bit("HSC:0/UIL"));
}

TEST(MicroLogixHsc, OverflowRunsTheInterruptRoutineWithOfi) {
  // ACC starts above HIP, so it counts on to OVF (p. 5-23) and through it: one overflow interrupt.
  Controller plc = Controller::from_text(hsc_interrupt_program("0X0002", "0X000F", 10, 990, 1000));
  plc.scan(1);
  plc.inject("HSC0", "pulses", {"1000"});
  plc.run_for(20 * kNsPerMs);
  plc.inject("HSC0", "pulses", {"0"});
  plc.scan(1);
  EXPECT_TRUE(plc.get_bit("HSC:0/OF"));
  EXPECT_GE(plc.get_int("N7:0"), 1);
  EXPECT_TRUE(plc.get_bit("B3:1/1")) << "OFI";
}

TEST(MicroLogixHsc, AClearMaskOrAZeroPfnHasNoInterrupt) {
  // HPM clear (0X000D): the high preset is reached (MD) but nothing runs [U].
  Controller plc = Controller::from_text(hsc_interrupt_program("0X0002", "0X000D", 10));
  plc.scan(1);
  plc.inject("HSC0", "pulses", {"1000"});
  plc.run_for(50 * kNsPerMs);
  EXPECT_TRUE(plc.get_bit("HSC:0/MD"));
  EXPECT_EQ(plc.get_int("N7:0"), 0);
  EXPECT_FALSE(plc.get_bit("HSC:0/UIP"));
  // RSLogix's default counter (PFN 0) never interrupts.
  Controller plain = Controller::from_text(hsc_program(config(0, 10, 0, 1000, 0), "SOR OTE HSC:0/FE EOR\n"));
  plain.inject("HSC0", "pulses", {"1000"});
  plain.run_for(50 * kNsPerMs);
  EXPECT_TRUE(plain.get_bit("HSC:0/MD"));
  EXPECT_FALSE(plain.get_bit("HSC:0/UIP"));
  EXPECT_FALSE(plain.fault().has_value());
}

TEST(MicroLogixHsc, UieClearHoldsTwoInterruptsAndLosesTheRest) {
  // UIE clear: the high presets wait, two of them, then UIL (1763-RM001C p. 275, the same rule for
  // every MicroLogix user interrupt); setting UIE runs the two.
  Controller plc = Controller::from_text(hsc_interrupt_program("0X0000", "0X000F", 10));
  plc.scan(1);
  plc.inject("HSC0", "pulses", {"1000"});
  plc.run_for(15 * kNsPerMs);
  EXPECT_TRUE(plc.get_bit("HSC:0/UIP"));
  EXPECT_FALSE(plc.get_bit("HSC:0/UIL"));
  plc.run_for(30 * kNsPerMs);
  plc.inject("HSC0", "pulses", {"0"});
  EXPECT_TRUE(plc.get_bit("HSC:0/UIL"));
  EXPECT_EQ(plc.get_int("N7:0"), 0);
  plc.set("B3:0/0", 1);
  plc.scan(1);
  EXPECT_EQ(plc.get_int("N7:0"), 2);
  EXPECT_FALSE(plc.get_bit("HSC:0/UIP"));
}

// ---- TVZ_1100_REV02: a production MicroLogix 1100 program with an encoder on HSC0 ---------------

const std::string kTvzDir = std::string(SOFTSLC_SHARED_DIR) + "/fixtures/rss/drbitboy-PLC_reject_timing/";

TEST(MicroLogixHsc, TvzCarriesItsHscRecordAndRunsTenSeconds) {
  for (const char* name : {"TVZ_1100_REV02.RSS", "TVZ_1100_REV02_LatchmoorAnnotations.RSS"}) {
    SCOPED_TRACE(name);
    LoadResult r = load_program_file(kTvzDir + name);
    ASSERT_TRUE(r.ok()) << r.render_diagnostics();
    // The type-0x11 record: PFN 11 (its LAD 11 "HSC0"), MOD 0, HIP 30 (its N17:11; the annotations:
    // "A typical value for HSC:0.HIP seems to be 30"), OVF/UNF the defaults.
    const std::string text = format_program(*r.program);
    EXPECT_NE(text.find("DATA HSC0:0"), std::string::npos);
    EXPECT_NE(text.find("    11      0 0X0822 0XB00F      0"), std::string::npos) << text.substr(text.find("DATA HSC0:0"));
    EXPECT_NE(text.find("HSL HSC0 N17:11 N17:11 0 0"), std::string::npos);
    Controller plc = Controller::load(kTvzDir + name);
    EXPECT_EQ(plc.get_int("HSC:0.PFN"), 11);
    EXPECT_EQ(plc.get_int("HSC:0.HIP"), 30);
    EXPECT_EQ(plc.get_int("HSC:0.MOD"), 0);
    plc.run_for(seconds(10));
    ASSERT_FALSE(plc.fault().has_value()) << plc.fault()->to_string();
    EXPECT_GE(plc.now(), seconds(10));
    EXPECT_FALSE(plc.get_bit("HSC:0/FE")) << "USE_ENCODER (B13:0/11) is 0 in the saved data";
  }
}

TEST(MicroLogixHsc, TvzCountsEncoderPulsesWhenTheEncoderIsInUse) {
  Controller plc = Controller::load(kTvzDir + "TVZ_1100_REV02.RSS");
  plc.set("B13:0/11", 1);  // USE_ENCODER: MAIN_PROG rung 2 sets HSC:0/FE
  // The reject offset (N17:2, from the GUI's limits N17:0 and N17:1: 250 as saved) indexes the bit
  // stream B11:0/[N17:2]; softslc does not run a B-file indirect bit past its element (as for
  // lecky_demo_tof_loop.RSS), so the limits here keep it within B11:0 (INSPECTION rungs 3-4).
  plc.set("N17:0", 0);
  plc.set("N17:1", 10);
  plc.scan(2);
  EXPECT_TRUE(plc.get_bit("HSC:0/FE"));
  plc.inject("HSC0", "pulses", {"3000"});
  plc.run_for(seconds(1));
  ASSERT_FALSE(plc.fault().has_value()) << plc.fault()->to_string();
  // Mode 0 with HIP 30: the accumulator stays below 30 and the high preset has been reached.
  EXPECT_GE(plc.get_int("HSC:0.ACC"), 0);
  EXPECT_LT(plc.get_int("HSC:0.ACC"), 30);
  EXPECT_TRUE(plc.get_bit("HSC:0/MD"));
  EXPECT_GE(plc.observe("HSC0", "pulses").at(0), 3000);
}

TEST(MicroLogixHsc, TvzHscInterruptFeedsItsSpeedCalculation) {
  // TVZ's HSC:0 (PFN 11, UIE, masks 0XB00F) runs LAD 11 "HSC0" at every high preset (its annotations),
  // which adds HIP (30) to F18:11; LAD 13, its STI every 300 ms, turns F18:11 into pulses a minute
  // (x 200) and revolutions a minute (/ 100 pulses a revolution, F18:15), then clears it. At 3000
  // pulses a second that is 900 pulses in 300 ms: 180,000 a minute, 1800 RPM, give or take one high
  // preset (30 pulses: 60 RPM) at either end of the STI's period.
  Controller plc = Controller::load(kTvzDir + "TVZ_1100_REV02.RSS");
  plc.set("B13:0/11", 1);
  plc.set("N17:0", 0);
  plc.set("N17:1", 10);
  plc.scan(2);
  plc.inject("HSC0", "pulses", {"3000"});
  plc.run_for(seconds(2));
  ASSERT_FALSE(plc.fault().has_value()) << plc.fault()->to_string();
  EXPECT_FALSE(plc.get_bit("HSC:0/UIL")) << "every high preset's routine ran";
  EXPECT_GE(plc.get_float("F18:15"), 1740.0);
  EXPECT_LE(plc.get_float("F18:15"), 1860.0);
}

}  // namespace
}  // namespace softslc
