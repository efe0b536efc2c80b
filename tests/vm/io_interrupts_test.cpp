// The discrete input interrupt (DII: S:46-S:52, S:2/11-13, S:5/12, S:36/8), the I/O event-driven
// interrupt (ISR: OPTION ISR, S:25-S:28, S:32, IID/IIE/RPI) and the MicroLogix UID/UIE/UIF refusals.
//
// Sources: 1747-RM001G chapter 11 "Understanding Interrupt Routines": p. 11-18 (DII overview: the
// first bits of one discrete input card compared with a compare value; the accumulator counts to
// the preset and "immediately wraps around and begins counting again at zero"; the DII may be
// reconfigured inside its routine), p. 11-20 (event mode, preset 0 or 1: an interrupt each time the
// pattern matches), p. 11-24 (S:48 mask and S:49 compare, bits 0-7 used; S:50 preset 2-32767 counts;
// all applied at each end of scan and DII routine exit), p. 11-27 (I/O interrupt overview: a
// specialty module requests, its slot's ISR file runs, the module is then told), p. 11-30 (the
// lowest slot first; STI and DII interrupt an ISR), p. 11-31 (S:25/S:26 pending, S:27/S:28 enable,
// bit n = slot n), p. 11-33 (IID clears, IIE sets the enable bits; a pending ISR then runs at
// once), B-24 (S:5/12 DII overflow), B-43 (S:24 restored after a DII; pending cleared by IIE or
// RPI), B-46 (S:32 the slot of the executing ISR, cleared when it completes), B-56 (S:49/S:50, S:51
// return mask written just before the routine). Where a page was not reached (S:2/11-13, S:36/8,
// the DII fault codes, RPI's page) the choice is in docs/semantics.md "I/O and discrete input
// interrupts" and the test says so.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "vm_test_util.h"

namespace softslc::test {
namespace {

constexpr Nanoseconds kMs = kNsPerMs;

// ---- The discrete input interrupt ---------------------------------------------------------------------------

// Slot 1 is a 1746-IB16 (kHeader). The DII routine (file 3) counts its runs in N7:0 and records
// S:51 in N7:1 and S:2/13 in B3:0/0; the main program records S:2/13 in B3:0/1.
Plc dii_plc(int mask, int compare, int preset, std::string_view dii_rungs = "") {
  Plc plc(
      "SOR XIC S:2/13 OTL B3:0/1 EOR\n"
      "SOR ADD N7:10 1 N7:10 EOR\n"
      "LADDER 3\n"
      "SOR INT ADD N7:0 1 N7:0 EOR\n"
      "SOR MOV S:51 N7:1 EOR\n"
      "SOR XIC S:2/13 OTL B3:0/0 EOR\n" +
      std::string(dii_rungs));
  plc.set("S:46", 3);
  plc.set("S:47", 1);
  plc.set("S:48", mask);
  plc.set("S:49", compare);
  plc.set("S:50", preset);
  return plc;
}

TEST(Dii, EventModeRunsTheRoutineOnTheTransitionThatMatches) {
  // RM 11-20: preset 0 -> an interrupt each time the masked input matches the compare value.
  Plc plc = dii_plc(0x01, 0x01, 0);
  plc.run_scans(2);
  EXPECT_EQ(plc.i("N7:0"), 0) << "nothing matched yet";
  plc.set("I:1/0", 1);
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:0"), 1) << "the routine ran in the next scan";
  EXPECT_EQ(plc.i("N7:1"), 0x01) << "S:51: the transition that caused it (RM B-56)";
  EXPECT_TRUE(plc.b("B3:0/0")) << "S:2/13 set inside the routine";
  EXPECT_FALSE(plc.b("B3:0/1")) << "and clear in the main program";
  plc->scan(3);
  EXPECT_EQ(plc.i("N7:0"), 1) << "a steady match is not a new event";
  plc.set("I:1/1", 1);
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:0"), 1) << "bit 1 is outside the mask";
  plc.set("I:1/0", 0);
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:0"), 1) << "leaving the pattern does not interrupt";
  plc.set("I:1/0", 1);
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:0"), 2);
  EXPECT_FALSE(plc->fault().has_value());
}

TEST(Dii, EveryMaskedBitMustMatch) {
  // RM 11-24: each bit of the mask compared with its compare bit, 1 or 0: bit 1 on and bit 0 off.
  Plc plc = dii_plc(0x03, 0x02, 1);
  plc.run_scans(1);
  plc.set("I:1/0", 1);
  plc.set("I:1/1", 1);
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:0"), 0) << "bit 0 must be off";
  plc.set("I:1/0", 0);
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:0"), 1) << "the falling edge of bit 0 completes the pattern";
  EXPECT_EQ(plc.i("N7:1"), 0x01) << "S:51: bit 0 made the transition";
  plc.set("I:1/8", 1);
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:0"), 1) << "only bits 0-7 of the card are watched (RM 11-24)";
}

TEST(Dii, CounterModeInterruptsAtThePresetAndWrapsToZero) {
  // RM 11-18, 11-24: a preset of 3 counts matches in S:52; the third interrupts, S:52 back to 0.
  Plc plc = dii_plc(0x01, 0x01, 3);
  plc.run_scans(1);
  for (int k = 1; k <= 2; ++k) {
    plc.set("I:1/0", 1);
    plc.set("I:1/0", 0);
    plc->scan(1);
    EXPECT_EQ(plc.i("S:52"), k);
    EXPECT_EQ(plc.i("N7:0"), 0);
  }
  plc.set("I:1/0", 1);
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:0"), 1) << "the third match";
  EXPECT_EQ(plc.i("S:52"), 0) << "wraps around to zero";
  plc.set("I:1/0", 0);
  plc.set("I:1/0", 1);
  plc->scan(1);
  EXPECT_EQ(plc.i("S:52"), 1) << "and counts again";
}

TEST(Dii, LatencyIsTheInputScanAndTheEntryCost) {
  // The change reaches the runtime between scans; the routine starts at the first rung start of
  // the next scan: the input scan, the first SOR and the entry charged as a true JSR, as the STI's.
  Plc plc = dii_plc(0x01, 0x01, 0);
  plc.run_scans(1);
  plc.set("I:1/0", 1);
  plc->scan(1);
  ASSERT_EQ(plc->dii().runs, 1u);
  const Nanoseconds latency = plc->dii().last_latency;
  EXPECT_GT(latency, 0);
  EXPECT_LT(latency, 1 * kMs) << "well inside one scan of this short program";
}

TEST(Dii, StatusWordsAreRestoredAfterTheRoutine) {
  // RM B-43: "When a DII interrupts normal execution of your program, the original value of this
  // register [S:24] is restored"; S:13 and the arithmetic flags with it, as for the STI.
  Plc plc = dii_plc(0x01, 0x01, 0, "SOR MOV 7 S:24 EOR\nSOR MOV 8 S:13 EOR\n");
  plc.set("S:24", 0);
  plc.run_scans(1);
  plc.set("S:24", 3);
  plc.set("S:13", 9);
  plc.set("I:1/0", 1);
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:0"), 1);
  EXPECT_EQ(plc.i("S:24"), 3);
  EXPECT_EQ(plc.i("S:13"), 9);
}

TEST(Dii, DisabledInterruptWaitsPendingWithOverflowAndLost) {
  // RM B-24: S:5/12 when the interrupt occurs while pending or disabled. S:2/11 pending, S:2/12
  // enable and S:36/8 lost are the status file's bits for it [U, docs/semantics.md].
  Plc plc = dii_plc(0x01, 0x01, 0);
  EXPECT_TRUE(plc.i("S:2") & (1 << 12)) << "S:2/12 starts set (docs/semantics.md)";
  plc.run_scans(1);
  plc.set("S:2", plc.i("S:2") & ~(1 << 12));
  plc.set("I:1/0", 1);
  plc->scan(2);
  EXPECT_EQ(plc.i("N7:0"), 0) << "disabled: it waits";
  EXPECT_TRUE(plc.i("S:2") & (1 << 11)) << "pending";
  EXPECT_TRUE(plc.i("S:5") & (1 << 12)) << "overflow: it occurred while disabled";
  EXPECT_EQ(plc.i("S:36") & (1 << 8), 0);
  plc.set("I:1/0", 0);
  plc.set("I:1/0", 1);
  EXPECT_TRUE(plc.i("S:36") & (1 << 8)) << "a second one while one is pending is lost";
  plc.set("S:2", plc.i("S:2") | (1 << 12));
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:0"), 1) << "enabled: the pending one runs, once";
  EXPECT_EQ(plc.i("S:2") & (1 << 11), 0);
}

TEST(Dii, TheRoutineMayReconfigureTheDii) {
  // RM 11-18: "While scanning the DII subroutine, you can reconfigure the DII to look for an
  // entirely different event"; RM 11-24: the new values apply at the routine's exit. Here each run
  // flips the compare value, so the DII runs on both edges of I:1/0.
  Plc plc = dii_plc(0x01, 0x01, 0, "SOR XOR S:49 1 S:49 EOR\n");
  plc.run_scans(1);
  plc.set("I:1/0", 1);
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:0"), 1);
  EXPECT_EQ(plc->dii().compare, 0) << "applied at the routine's exit";
  plc.set("I:1/0", 0);
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:0"), 2) << "the falling edge now matches";
}

TEST(Dii, OnlyInRun) {
  Plc plc = dii_plc(0x01, 0x01, 0);
  plc.set("I:1/0", 1);
  plc.set("I:1/0", 0);
  plc.run_scans(2);
  EXPECT_EQ(plc.i("N7:0"), 0) << "changes in Program mode do not count";
  EXPECT_EQ(plc.i("S:52"), 0);
}

TEST(Dii, InvalidFileFaults) {
  // RM 11-18: the DII file is a subroutine file 3-255. The fault code is softslc's choice [U].
  Plc plc = dii_plc(0x01, 0x01, 0);
  plc.set("S:46", 9);  // no LADDER 9
  plc.run_scans(1);
  EXPECT_EQ(plc.fault_code(), 0x0042);
}

TEST(Dii, SlotWithoutADiscreteInputCardFaults) {
  // RM 11-18: the DII watches "any single I/O slot, which contains any discrete input card".
  for (int slot : {2, 7, 0, 31}) {
    Plc plc = dii_plc(0x01, 0x01, 0);
    plc.set("S:47", slot);  // 2: an output card; 7: empty; 0: the processor; 31: no such slot
    plc.run_scans(1);
    EXPECT_EQ(plc.fault_code(), 0x0043) << "slot " << slot;
  }
}

// The chassis is asked whether a slot holds a discrete input card once per slot (the DII's
// configuration is applied at every end of scan): a program that moves S:47 to another slot while
// running is still checked against that slot's card.
TEST(Dii, ASlotChangedWhileRunningIsCheckedForItsOwnCard) {
  Plc plc = dii_plc(0x01, 0x01, 0);
  plc.run_scans(3);
  ASSERT_EQ(plc.fault_code(), 0);
  plc.set("S:47", 2);  // an output card
  plc.run_scans(1);
  EXPECT_EQ(plc.fault_code(), 0x0043);
}

TEST(Dii, NegativePresetFaultsAtTheEndOfTheScanThatLoadsIt) {
  Plc plc = dii_plc(0x01, 0x01, 0, "");
  plc.run_scans(1);
  EXPECT_FALSE(plc->fault().has_value());
  plc.set("S:50", -5);
  plc->scan(1);
  EXPECT_EQ(plc.fault_code(), 0x0043) << "RM 11-24: presets are 0-32767";
}

TEST(Dii, ZeroFileIsOff) {
  Plc plc = dii_plc(0x01, 0x01, 0);
  plc.set("S:46", 0);
  plc.run_scans(1);
  plc.set("I:1/0", 1);
  plc->scan(2);
  EXPECT_EQ(plc.i("N7:0"), 0);
  EXPECT_FALSE(plc->fault().has_value());
}

// RM 11-24: S:46-S:50 are applied at each end of scan, so a DII switched off (S:46 = 0) for one
// scan and back on with the same words watches again. (The runtime skips applying words it has
// already applied while a DII is configured; after a scan with the DII off they must apply again.)
TEST(Dii, SwitchedOffAndOnAgainWithTheSameWordsWatchesAgain) {
  Plc plc = dii_plc(0x01, 0x01, 0);
  plc.run_scans(2);
  plc.set("S:46", 0);
  plc.run_scans(1);
  EXPECT_EQ(plc->dii().file, 0) << "off";
  plc.set("S:46", 3);
  plc.run_scans(1);
  EXPECT_EQ(plc->dii().file, 3) << "on again, with the words it had before";
  plc.set("I:1/0", 1);
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:0"), 1) << "the matching transition runs the routine";
  EXPECT_FALSE(plc->fault().has_value());
}

// ---- The I/O event-driven interrupt -------------------------------------------------------------------------

// A specialty card that requests service when told to and counts how often it was answered.
class InterruptingCard : public DiscreteIoModule {
 public:
  using DiscreteIoModule::DiscreteIoModule;
  void request() {
    if (host()) host()->request_io_interrupt(slot());
  }
  void interrupt_serviced() override { ++serviced; }
  int serviced = 0;
};

// Slots 3 and 5 hold interrupting cards with ISR files 4 and 5; each ISR records S:32 and the
// order it ran in.
struct IsrPlc {
  std::vector<InterruptingCard*> cards;
  std::unique_ptr<Plc> plc;

  explicit IsrPlc(std::string_view main_rungs, std::string_view isr4_extra = "", std::string_view more_files = "") {
    RuntimeOptions opts;
    opts.module_factory = [this](const SlotConfig& s) -> std::unique_ptr<Module> {
      if (s.slot != 3 && s.slot != 5) return nullptr;
      auto m = std::make_unique<InterruptingCard>(s.slot, s.catalog, s.scan_in, s.scan_out);
      cards.push_back(m.get());
      return m;
    };
    const std::string header = std::string(kHeader) +
                               "SLOT 3 1746-HSCE SCAN_IN 8 SCAN_OUT 8 OPTION ISR=4\n"
                               "SLOT 5 1746-HSCE SCAN_IN 8 SCAN_OUT 8 OPTION ISR=5\n";
    plc = std::make_unique<Plc>(std::string(main_rungs) +
                                    "\nLADDER 4\n"
                                    "SOR INT ADD N7:0 1 N7:0 EOR\n"
                                    "SOR MOV S:32 N7:1 EOR\n"
                                    "SOR ADD N7:20 1 N7:20 EOR\n"
                                    "SOR MOV N7:20 N7:4 EOR\n" +
                                    std::string(isr4_extra) +
                                    "LADDER 5\n"
                                    "SOR INT ADD N7:2 1 N7:2 EOR\n"
                                    "SOR MOV S:32 N7:3 EOR\n"
                                    "SOR ADD N7:20 1 N7:20 EOR\n"
                                    "SOR MOV N7:20 N7:5 EOR\n" +
                                    std::string(more_files),
                                std::move(opts), header);
  }
  InterruptingCard& card(int slot) { return *cards.at(slot == 3 ? 0 : 1); }
};

TEST(IoInterrupt, ARequestRunsTheSlotsIsrAndTellsTheModule) {
  IsrPlc t("SOR ADD N7:10 1 N7:10 EOR");
  Plc& plc = *t.plc;
  plc.run_scans(1);
  t.card(3).request();
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:0"), 1) << "RM 11-27: the slot's ISR file ran";
  EXPECT_EQ(plc.i("N7:1"), 3) << "RM B-46: S:32 holds the interrupting slot inside the ISR";
  EXPECT_EQ(plc.i("S:32"), 0) << "and is cleared when it completes";
  EXPECT_EQ(t.card(3).serviced, 1) << "RM 11-27 step 3: the module is told";
  EXPECT_EQ(plc->isr_runs(), 1u);
  plc->scan(2);
  EXPECT_EQ(plc.i("N7:0"), 1) << "one request, one run";
}

TEST(IoInterrupt, LowestSlotFirst) {
  // RM 11-30: requests detected together are served lowest slot first.
  IsrPlc t("SOR ADD N7:10 1 N7:10 EOR");
  Plc& plc = *t.plc;
  plc.run_scans(1);
  t.card(5).request();
  t.card(3).request();
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:4"), 1) << "slot 3's ISR first";
  EXPECT_EQ(plc.i("N7:5"), 2) << "then slot 5's";
}

TEST(IoInterrupt, IidHoldsTheRequestPendingAndIieRunsIt) {
  // RM 11-33 (the IID/IIE zone example): slot 3 is bit 3 of the slots mask (8).
  IsrPlc t(
      "SOR XIC B3:0/0 IID 8 EOR\n"
      "SOR XIO B3:0/0 IIE 8 EOR\n"
      "SOR MOV N7:0 N7:6 EOR");
  Plc& plc = *t.plc;
  plc.set("B3:0/0", 1);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("S:27") & (1 << 3), 0) << "IID cleared S:27/3";
  t.card(3).request();
  EXPECT_TRUE(plc.i("S:25") & (1 << 3)) << "RM 11-31: requested while disabled: pending";
  plc->scan(2);
  EXPECT_EQ(plc.i("N7:0"), 0) << "it waits";
  plc.set("B3:0/0", 0);
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:0"), 1) << "IIE: the pending ISR runs at once";
  EXPECT_EQ(plc.i("N7:6"), 1) << "within the scan, before the next rung";
  EXPECT_EQ(plc.i("S:25") & (1 << 3), 0) << "pending cleared (RM B-43)";
  EXPECT_TRUE(plc.i("S:27") & (1 << 3));
}

TEST(IoInterrupt, RpiDropsThePendingRequest) {
  // RM B-43: the pending bit is cleared "when an associated RPI instruction is executed"; softslc
  // drops the request and answers the module (docs/semantics.md).
  IsrPlc t(
      "SOR XIC B3:0/0 IID 8 EOR\n"
      "SOR XIC B3:0/1 RPI 8 EOR\n"
      "SOR XIO B3:0/0 IIE 8 EOR");
  Plc& plc = *t.plc;
  plc.set("B3:0/0", 1);
  plc.run_scans(1);
  t.card(3).request();
  plc.set("B3:0/1", 1);
  plc->scan(1);
  EXPECT_EQ(plc.i("S:25") & (1 << 3), 0);
  EXPECT_EQ(t.card(3).serviced, 1);
  plc.set("B3:0/0", 0);
  plc->scan(2);
  EXPECT_EQ(plc.i("N7:0"), 0) << "nothing left to run after IIE";
}

TEST(IoInterrupt, TheStiInterruptsAnIsr) {
  // RM 11-30: "If the STI timer expires while executing the I/O interrupt subroutine, execution
  // immediately switches to the STI subroutine"; RM B-46: S:32 tells the STI an ISR was running.
  // Slot 3's ISR loops N7:51 times (about 35 ms on the 5/03 profile, as interrupts_test.cpp's slow
  // rungs); the 10 ms STI (file 6) counts its runs in N7:30 and latches B3:1/0 when S:32 is set.
  IsrPlc t("SOR ADD N7:10 1 N7:10 EOR",
           "SOR CLR N7:50 EOR\nSOR LBL 1 ADD N7:50 1 N7:50 EOR\nSOR LES N7:50 N7:51 JMP 1 EOR\n",
           "LADDER 6\nSOR INT ADD N7:30 1 N7:30 EOR\nSOR GRT S:32 0 OTL B3:1/0 EOR\n");
  Plc& plc = *t.plc;
  plc.set("N7:51", 5500);
  plc.set("S:30", 1);
  plc.set("S:31", 6);
  plc.run_scans(1);
  EXPECT_FALSE(plc.b("B3:1/0")) << "no ISR yet";
  const auto before = plc.i("N7:30");
  t.card(3).request();
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:0"), 1) << "the ISR ran";
  EXPECT_TRUE(plc.b("B3:1/0")) << "an STI ran while the ISR was executing";
  EXPECT_GE(plc.i("N7:30") - before, 3) << "every 10 ms of the 35 ms ISR";
  EXPECT_FALSE(plc->fault().has_value());
}

TEST(IoInterrupt, RequestWithoutAnIsrNumberIsAnswered) {
  IsrPlc t("SOR ADD N7:10 1 N7:10 EOR");
  Plc& plc = *t.plc;
  plc.run_scans(1);
  // Outside Run nothing services a request: it is answered at once.
  ASSERT_TRUE(plc->set_mode(Mode::Program));
  t.card(5).request();
  EXPECT_EQ(t.card(5).serviced, 1);
}

// ---- Checks ----------------------------------------------------------------------------------------------------

TEST(IoInterruptCheck, SlotsMaskBitZeroIsReserved) {
  const std::string e = build_errors(program_text("SOR IIE 3 EOR"));
  EXPECT_NE(e.find("bit 0 is reserved"), std::string::npos) << e;
  EXPECT_EQ(build_errors(program_text("SOR IIE 0x86 EOR")), "") << "slots 1, 2 and 7 (RM 11-33's example)";
}

TEST(IoInterruptCheck, NotBeforeThe502) {
  const std::string e = build_errors("START 1747-L511\nLADDER 2\nSOR IID 2 EOR\n");
  EXPECT_NE(e.find("IID is not available"), std::string::npos) << e;
}

TEST(IoInterruptCheck, IsrOptionNamesAnExistingFile) {
  const std::string header = std::string(kHeader) + "SLOT 3 1746-HSCE SCAN_IN 8 SCAN_OUT 8 OPTION ISR=9\n";
  std::string e = build_errors(program_text("SOR IIE 8 EOR", header));
  EXPECT_NE(e.find("no LADDER 9"), std::string::npos) << e;
  const std::string bad = std::string(kHeader) + "SLOT 3 1746-HSCE SCAN_IN 8 SCAN_OUT 8 OPTION ISR=2\n";
  e = build_errors(program_text("SOR IIE 8 EOR", bad));
  EXPECT_NE(e.find("3-255"), std::string::npos) << e;
}

TEST(UserInterrupt, UidUieUifAreRefusedByNameOnEveryProcessor) {
  // 1747-RM001G has no UID/UIE/UIF; the MicroLogix 1100-1500 have them (1763/1766-RM001) on the
  // STI/EII/HSC function files, with an interrupt-type operand whose encoding was not found.
  for (std::string_view m : {"UID", "UIE", "UIF"}) {
    const std::string slc = build_errors(program_text("SOR " + std::string(m) + " 1 EOR"));
    EXPECT_NE(slc.find("is not an SLC 500 instruction"), std::string::npos) << slc;
    const std::string ml = build_errors("START Bul.1766\nLADDER 2\nSOR " + std::string(m) + " 1 EOR\n");
    EXPECT_NE(ml.find("does not simulate"), std::string::npos) << ml;
  }
}

}  // namespace
}  // namespace softslc::test
