// The AutoMax master and its network: drop 0 registers (figure 4.1), access rules and bus
// errors (section 4.3), polling, retries and off-line drops (section 4.4), the update period
// (section 4.5), Shark configuration (4.6.1), head rails (4.6.2, 4.6.3) and the drive head
// (4.6.4). Programs reach the image through IODEF/RIODEF symbols, i.e. M0 accesses.
#include <gtest/gtest.h>

#include "modules/automax/automax_network.h"
#include "modules/throughput/throughput_json.h"
#include "tests/modules/modules_test_util.h"

namespace softslc {
namespace {

using test::Bench;

const std::string kHead = "START 1747-L532\nSLOT 8 57C416 % AutoMax RIO master %\nLADDER 2 MAIN\n";

// The address a program symbol (IODEF/RIODEF/MEMDEF) resolved to, for the runtime's tool access.
std::string A(const Bench& b, const char* name) {
  const Symbol* s = b.load.program->find_symbol(name);
  if (!s) throw std::runtime_error(std::string("no symbol ") + name);
  return to_string(s->address);
}

AutomaxMaster& master(Bench& b) { return dynamic_cast<AutomaxMaster&>(*b->module(8)); }

// A program whose rungs copy nothing; tests read and write the image through symbols.
std::string program(const std::string& rungs, const std::string& defs) { return kHead + rungs + defs; }

const std::string kTwoDrops =
    "automax NET slot=8 {\n"
    "  multibus RACK2 drop=2 {\n"
    "    module AOUT slot=0 outputs=4\n"
    "    module DIN slot=11 inputs=1\n"
    "  }\n"
    "  head_57c330 HEAD4 drop=4 rails=0,1\n"
    "  multibus RACK5 drop=5 state=offline {\n"
    "    module IN slot=0 inputs=2\n"
    "  }\n"
    "}\n";

const std::string kStatusDefs =
    "IODEF RIO_D02@[SLOT=8,REGISTER=4,BIT=2]\n"
    "IODEF RIO_D04@[SLOT=8,REGISTER=4,BIT=4]\n"
    "IODEF RIO_D05@[SLOT=8,REGISTER=4,BIT=5]\n"
    "IODEF STATUS%[SLOT=8,REGISTER=4]\n"
    "IODEF DROPNO%[SLOT=8,REGISTER=12]\n"
    "IODEF KEYSW%[SLOT=8,REGISTER=13]\n"
    "IODEF RECEIVED%[SLOT=8,REGISTER=14]\n"
    "IODEF TIMEOUTS%[SLOT=8,REGISTER=15]\n"
    "IODEF CRC%[SLOT=8,REGISTER=16]\n"
    "IODEF SENT%[SLOT=8,REGISTER=19]\n"
    "RIODEF START@[MASTER_SLOT=8,DROP=2,SLOT=11,REGISTER=0,BIT=5]\n"
    "RIODEF SPD_IND%[MASTER_SLOT=8,DROP=2,SLOT=0,REGISTER=3]\n"
    "RIODEF HEAD_R0%[MASTER_SLOT=8,DROP=4,SLOT=1,REGISTER=0]\n"
    "RIODEF HEAD_R1%[MASTER_SLOT=8,DROP=4,SLOT=1,REGISTER=1]\n"
    "RIODEF HEAD_R2%[MASTER_SLOT=8,DROP=4,SLOT=1,REGISTER=2]\n"
    "RIODEF NOWHERE%[MASTER_SLOT=8,DROP=2,SLOT=5,REGISTER=0]\n"
    "RIODEF R5IN%[MASTER_SLOT=8,DROP=5,SLOT=0,REGISTER=0]\n"
    "RIODEF R3IN%[MASTER_SLOT=8,DROP=3,SLOT=0,REGISTER=0]\n";

const std::string kNoRungs = "SOR XIC B3:0/1 OTE B3:0/0 EOR\n";

// Figure 4.1: register 4 has a bit per active drop, 12 the drop number, 13 the keyswitch,
// 14-19 the message counters; at power-up the master polls all seven drops (section 4.4).
TEST(AutomaxMaster, Drop0RegistersAfterPowerUp) {
  Bench b(program(kNoRungs, kStatusDefs), kTwoDrops);
  b->scan(1);  // the master's power-up poll is its first event
  EXPECT_EQ(b.i(A(b, "STATUS")), (1 << 2) | (1 << 4));  // drop 5 is off-line: its bit is clear
  EXPECT_EQ(b.i(A(b, "DROPNO")), 0);
  EXPECT_EQ(b.i(A(b, "KEYSW")), 3);  // program (the bench default)
  // Power-up: 7 polls, drops 2 and 4 answer, the other 5 numbers do not. Then the first update
  // cycle (the scan is far shorter than one cycle): drops 2 and 4, and one inactive poll (drop 1,
  // absent).
  EXPECT_EQ(b.i(A(b, "SENT")), 7 + 3);
  EXPECT_EQ(b.i(A(b, "RECEIVED")), 2 + 2);
  EXPECT_EQ(b.i(A(b, "TIMEOUTS")), 5 + 1);
  // Drop 0 is read only (section 4.2): a write is refused (fault xx55h with the slot).
  EXPECT_FALSE(b->set("M0:8.12", Value::of_int(1)));
}

// Section 4.5: each cycle costs the active drops' DROP_TIME plus 2.7 ms for the inactive poll.
// RACK2: Multibus, N = 4 + 1 registers: 1.5 + 5 x 0.018 = 1.590 ms. HEAD4: 57C330, two rails
// not yet defined (data both ways, X = 2, Y = 2): 1.9 + 2 x 0.08 + 2 x 0.036 = 2.132 ms.
TEST(AutomaxMaster, UpdatePeriodIsTheSection45Sum) {
  Bench b(program(kNoRungs, kStatusDefs), kTwoDrops);
  b->scan(1);  // the master's power-up poll is its first event
  b.run();
  b->run_for(milliseconds(100));
  EXPECT_EQ(master(b).update_period(), microseconds(1590 + 2132 + 2700));
  // Cycles follow each other by exactly that period.
  const auto cycles = b->observe("NET", "cycles")->at(0);
  b->run_for(microseconds(6422) * 10);
  EXPECT_NEAR(static_cast<double>(b->observe("NET", "cycles")->at(0) - cycles), 10.0, 1.0);
}

// The manual's own example network of section 4.5, as drops: the simulated period equals the
// throughput calculator's (softslc throughput) and the formulas worked by hand:
// 1.734 + 1.698 + (1.9 + 5 x 0.08 + 6 x 0.036 = 2.516) + 1.8 + 2.7 = 10.448 ms. (The manual
// prints 9.965 ms using constants that appear in no formula; docs/throughput.md.)
TEST(AutomaxMaster, UpdatePeriodOfTheManualExampleMatchesTheThroughputCalculator) {
  const std::string bench =
      "automax NET slot=8 {\n"
      "  multibus D1 drop=1 {\n    module A slot=0 inputs=5 outputs=8\n  }\n"
      "  multibus D2 drop=2 {\n    module B slot=0 inputs=5 outputs=6\n  }\n"
      "  head_57c330 D3 drop=3 rails=0,1,2,3,4,5,6,7,8,9,10\n"
      "  shark D4 drop=12 {\n    module C slot=1 type=digital inputs=1\n  }\n"
      "}\n";
  Bench b(program(kNoRungs, ""), bench);
  b->scan(1);  // the master's power-up poll is its first event
  // Define the head's rails as the example has them: 6 input rails (0-5), 5 output rails (6-10).
  for (int r = 0; r < 6; ++r) b.inject("D3", "input", {"0", std::to_string(r), "1"});
  for (int r = 6; r < 11; ++r) ASSERT_TRUE(b->set("M0:8." + std::to_string(3 * 512 + r), Value::of_int(1)));
  b.run();
  b->run_for(milliseconds(100));
  EXPECT_EQ(master(b).update_period(), microseconds(10448));
  // What `softslc throughput examples/throughput/automax_example.json` prints for the same drops.
  const auto config = nlohmann::json::parse(
      test::read_text(std::string(SOFTSLC_SOURCE_DIR) + "/examples/throughput/automax_example.json"));
  const auto result = throughput::compute_throughput(config);
  EXPECT_EQ(result.at("update_period_ms").get<double>(), 10.448);
  EXPECT_EQ(master(b).update_period(), microseconds(10448));
  EXPECT_EQ(b->observe("D4", "active")->at(0), 1);  // switch C: image area and status bit 4
}

// Section 4.3: input registers read only, output registers read/write, a register the drop does
// not have is a bus error. Through the ladder, the refusal faults the processor (xx55h, 0855h
// for slot 8).
TEST(AutomaxMaster, AccessRulesAndBusErrorFault) {
  Bench b(program(kNoRungs, kStatusDefs), kTwoDrops);
  b->scan(1);  // the master's power-up poll is its first event
  EXPECT_TRUE(b->set(A(b, "SPD_IND"), Value::of_int(7)));          // output: read/write
  EXPECT_FALSE(b->set(A(b, "START"), Value::of_int(1)));            // input: read only
  EXPECT_FALSE(b->get(A(b, "NOWHERE")).has_value());                // no module in drop 2 slot 5
  EXPECT_FALSE(b->get(A(b, "R3IN")).has_value());                   // no drop 3 on the network
  EXPECT_EQ(b->get(A(b, "R5IN"))->as_int(), 0);  // drop 5 has not answered, but it is configured
  EXPECT_EQ(master(b).refusal(2 * 512 + 5 * 32, false), "bus error: drop 2 slot 5 register 0: no module in slot 5");
  EXPECT_EQ(master(b).refusal(2 * 512 + 11 * 32, true),
            "write refused: drop 2 slot 11 register 0 (DIN input, read only)");
  EXPECT_EQ(master(b).refusal(3 * 512, false), "bus error: drop 3 slot 0 register 0: there is no drop 3 on the network");

  Bench f(program("SOR XIC B3:0/1 MOV NOWHERE N7:0 EOR\n", kStatusDefs), kTwoDrops);
  f->scan(1);  // the master's power-up poll is its first event
  f.run();
  f->scan(1);
  EXPECT_EQ(f.fault_code(), 0);
  f.set("B3:0/1", 1);
  f->scan(1);
  EXPECT_EQ(f.fault_code(), 0x0855);
  // The fault names the symbol, the drop, slot and register, and why.
  EXPECT_EQ(f->fault()->message,
            "reading M0:8.1184: module refused (no such word): RIODEF NOWHERE: bus error: drop 2 slot 5 register 0: "
            "no module in slot 5");
  // A write to an input register is refused too (read only, section 4.3).
  Bench w(program("SOR XIC B3:0/2 OTE START EOR\n", kStatusDefs), kTwoDrops);
  w.run();
  w.set("B3:0/2", 1);
  w->scan(1);
  EXPECT_EQ(w.fault_code(), 0x0855);
  EXPECT_EQ(w->fault()->message,
            "writing M0:8.1376/5: module refused (forbidden): RIODEF START: write refused: drop 2 slot 11 register 0 "
            "(DIN input, read only)");
}

// Section 4.4: a drop that stops answering is retried three times, then goes off-line (its
// status bit clears); the inactive poll finds it again when it answers.
TEST(AutomaxMaster, DropGoesOfflineAfterThreeRetriesAndRejoins) {
  Bench b(program(kNoRungs, kStatusDefs), kTwoDrops);
  b->scan(1);  // the master's power-up poll is its first event
  b.run();
  b->run_for(milliseconds(50));
  const auto timeouts = b.i(A(b, "TIMEOUTS"));
  EXPECT_TRUE(b.b(A(b, "RIO_D02")));
  b.inject("RACK2", "offline");
  b->run_for(milliseconds(10));
  EXPECT_FALSE(b.b(A(b, "RIO_D02")));
  EXPECT_TRUE(b.b(A(b, "RIO_D04")));
  EXPECT_EQ(b->observe("RACK2", "retries")->at(0), 3);
  // 4 attempts timed out, plus one per inactive poll of an absent drop per cycle.
  EXPECT_GE(b.i(A(b, "TIMEOUTS")) - timeouts, 4);
  b.inject("RACK2", "online");
  // Seven drop numbers are polled round robin, one per cycle: within 7 cycles it is back.
  EXPECT_TRUE(b.until([&] { return b.b(A(b, "RIO_D02")); }, milliseconds(60)));
  // Data flows again: a field input reaches the image.
  b.inject("RACK2", "input", {"11", "0", "0x0020"});
  EXPECT_TRUE(b.until([&] { return b.b(A(b, "START")); }, milliseconds(20)));
}

// The master's cable removed: every drop stops answering and goes off-line after its retries;
// restored, the inactive poll brings them back one per cycle.
TEST(AutomaxMaster, CableRemovedTakesEveryDropOffline) {
  Bench b(program(kNoRungs, kStatusDefs), kTwoDrops);
  b->scan(1);  // the master's power-up poll is its first event
  b.run();
  b->run_for(milliseconds(20));
  b.inject("NET", "cable removed");
  b->run_for(milliseconds(20));
  EXPECT_EQ(b.i(A(b, "STATUS")), 0);
  b.inject("NET", "cable restored");
  EXPECT_TRUE(b.until([&] { return b.i(A(b, "STATUS")) == ((1 << 2) | (1 << 4)); }, milliseconds(60)));
}

// A noisy drop: a message in error (CRC) is retried and the drop stays on-line.
TEST(AutomaxMaster, NoisyDropIsRetriedAndCounted) {
  Bench b(program(kNoRungs, kStatusDefs), kTwoDrops);
  b->scan(1);  // the master's power-up poll is its first event
  b.inject("RACK2", "noisy", {"3"});
  b.run();
  b->run_for(milliseconds(100));
  EXPECT_TRUE(b.b(A(b, "RIO_D02")));
  EXPECT_GT(b.i(A(b, "CRC")), 0);
  EXPECT_EQ(b->observe("RACK2", "retries")->at(0), b.i(A(b, "CRC")));
}

// Section 4.6.3: 57C330 rails are undefined (read/write) until non-zero data defines them:
// from the rail an input (then read only), from the master an output. The definition sticks
// until the line goes inactive.
TEST(AutomaxMaster, Head57C330RailDefinition) {
  Bench b(program(kNoRungs, kStatusDefs), kTwoDrops);
  b->scan(1);  // the master's power-up poll is its first event
  b.run();
  EXPECT_TRUE(b->set(A(b, "HEAD_R0"), Value::of_int(0)));  // undefined: writable
  b.inject("HEAD4", "input", {"0", "0", "0x0102"});
  b->run_for(milliseconds(20));
  EXPECT_EQ(b.i(A(b, "HEAD_R0")), 0x0102);
  EXPECT_FALSE(b->set(A(b, "HEAD_R0"), Value::of_int(0)));  // now an input: read only
  EXPECT_TRUE(b->set(A(b, "HEAD_R1"), Value::of_int(5)));    // defines rail 1 as an output
  b->run_for(milliseconds(20));
  EXPECT_EQ(b->observe("HEAD4", "outputs")->at(1), 5);
  EXPECT_EQ(b->observe("HEAD4", "rails")->at(1), 3);  // output
  b.inject("HEAD4", "input", {"0", "0", "0"});        // zero data does not undefine it
  b->run_for(milliseconds(20));
  EXPECT_FALSE(b->set(A(b, "HEAD_R0"), Value::of_int(0)));
  EXPECT_FALSE(b->get(A(b, "HEAD_R2")).has_value());  // no rail 2: bus error
  // Line inactive: the definitions are lost; on reconnection the rails are undefined again.
  b.inject("HEAD4", "offline");
  b->run_for(milliseconds(20));
  b.inject("HEAD4", "online");
  EXPECT_TRUE(b.until([&] { return b.b(A(b, "RIO_D04")); }, milliseconds(80)));
  EXPECT_EQ(b->observe("HEAD4", "rails")->at(0), 1);
  EXPECT_TRUE(b->set(A(b, "HEAD_R0"), Value::of_int(0)));
  // Rail 1 removed: the head notices at its next rail read, within about 20 ms, and the rail
  // loses its definition; the master keeps the configuration the drop sent when it connected, so
  // the register stays accessible until the drop reconnects.
  b->run_for(milliseconds(20));
  EXPECT_EQ(b->observe("HEAD4", "rails")->at(1), 3);
  b.inject("HEAD4", "rail removed", {"1"});
  b->run_for(milliseconds(30));
  EXPECT_EQ(b->observe("HEAD4", "rails")->at(1), 0);
  EXPECT_TRUE(b->set(A(b, "HEAD_R1"), Value::of_int(0)));
  b.inject("HEAD4", "rail added", {"1"});
  b->run_for(milliseconds(30));
  EXPECT_EQ(b->observe("HEAD4", "rails")->at(1), 1);  // found again: undefined
  // A power cycle of the drop also clears the definitions (4.6.3 a).
  b.inject("HEAD4", "input", {"0", "0", "1"});
  b->run_for(milliseconds(20));
  EXPECT_EQ(b->observe("HEAD4", "rails")->at(0), 2);
  b.inject("HEAD4", "power cycle");
  b->run_for(milliseconds(20));
  EXPECT_EQ(b->observe("HEAD4", "active")->at(0), 0);  // running its power-up diagnostics
  EXPECT_EQ(b->observe("HEAD4", "rails")->at(0), 0);
  EXPECT_TRUE(b.until([&] { return b.b(A(b, "RIO_D04")); }, seconds(1)));
}

// Section 4.6.2: the 57C328's registers 0-3 are rail inputs, 4-7 rail outputs, 8-31 not
// accessible; a rail change disconnects the drop, which re-runs its diagnostics and sends the
// new configuration.
TEST(AutomaxMaster, Head57C328RailsAndReconfiguration) {
  const std::string bench = "automax NET slot=8 {\n  head_57c328 H drop=3 rails=0,1 diagnostics=100ms\n}\n";
  const std::string defs =
      "IODEF RIO_D03@[SLOT=8,REGISTER=4,BIT=3]\n"
      "RIODEF IN0%[MASTER_SLOT=8,DROP=3,SLOT=0,REGISTER=0]\n"
      "RIODEF OUT1%[MASTER_SLOT=8,DROP=3,SLOT=0,REGISTER=5]\n"
      "RIODEF OUT2%[MASTER_SLOT=8,DROP=3,SLOT=0,REGISTER=6]\n"
      "RIODEF R8%[MASTER_SLOT=8,DROP=3,SLOT=0,REGISTER=8]\n";
  Bench b(program(kNoRungs, defs), bench);
  b->scan(1);  // the master's power-up poll is its first event
  b.run();
  EXPECT_FALSE(b->set(A(b, "IN0"), Value::of_int(1)));
  EXPECT_TRUE(b->set(A(b, "OUT1"), Value::of_int(9)));
  EXPECT_FALSE(b->set(A(b, "OUT2"), Value::of_int(1)));  // rail 2 not connected
  EXPECT_FALSE(b->get(A(b, "R8")).has_value());
  b->run_for(milliseconds(10));
  EXPECT_EQ(b->observe("H", "outputs")->at(5), 9);
  b.inject("H", "rail added", {"2"});
  b->run_for(milliseconds(10));
  EXPECT_FALSE(b.b(A(b, "RIO_D03")));
  b->run_for(milliseconds(50));
  EXPECT_FALSE(b.b(A(b, "RIO_D03")));  // still running its diagnostics
  EXPECT_TRUE(b.until([&] { return b.b(A(b, "RIO_D03")); }, milliseconds(100)));
  EXPECT_TRUE(b->set(A(b, "OUT2"), Value::of_int(1)));
}

// Section 4.6.1: a mixed Shark rack exchanges data once the configuration word (slot 0 reg 0,
// bits 1-10 digital, bit 15 complete) is written; it is taken once; a Stop-All or a
// reconnection allows another. Digital modules of a mixed rack report no bus error.
TEST(AutomaxMaster, SharkConfigurationRules) {
  const std::string bench =
      "automax NET slot=8 {\n"
      "  shark S2 drop=2 {\n"
      "    module AIN slot=1 type=analog inputs=4\n"
      "    module DIN slot=5 type=digital inputs=1\n"
      "  }\n"
      "}\n";
  const std::string defs =
      "RIODEF CFG%[MASTER_SLOT=8,DROP=2,SLOT=0,REGISTER=0]\n"
      "RIODEF SPD_REF%[MASTER_SLOT=8,DROP=2,SLOT=1,REGISTER=0]\n"
      "RIODEF START@[MASTER_SLOT=8,DROP=2,SLOT=5,REGISTER=0,BIT=5]\n"
      "RIODEF DIN_R20%[MASTER_SLOT=8,DROP=2,SLOT=5,REGISTER=20]\n"
      "RIODEF AIN_R20%[MASTER_SLOT=8,DROP=2,SLOT=1,REGISTER=20]\n"
      "RIODEF EMPTY%[MASTER_SLOT=8,DROP=2,SLOT=3,REGISTER=0]\n";
  Bench b(program(kNoRungs, defs), bench);
  b->scan(1);  // the master's power-up poll is its first event
  b.inject("S2", "input", {"1", "0", "1234"});
  b.inject("S2", "input", {"5", "0", "0x0020"});
  b.run();
  b->run_for(milliseconds(20));
  EXPECT_EQ(b.i(A(b, "SPD_REF")), 0);  // not configured: no I/O
  EXPECT_EQ(b->observe("S2", "configured")->at(0), 0);
  EXPECT_EQ(b->get(A(b, "DIN_R20"))->as_int(), 0);     // digital module, mixed rack: no bus error
  EXPECT_FALSE(b->get(A(b, "AIN_R20")).has_value());   // analog: bus error (16-32 not accessible)
  EXPECT_FALSE(b->get(A(b, "EMPTY")).has_value());     // no module in slot 3
  b.set(A(b, "CFG"), 0x20);  // slot 5 digital, but bit 15 not yet set
  b->run_for(milliseconds(20));
  EXPECT_EQ(b->observe("S2", "configured")->at(0), 0);
  b.set(A(b, "CFG"), static_cast<std::int16_t>(0x8020));  // the manual's 20H with the ready bit 15
  b->run_for(milliseconds(20));
  EXPECT_EQ(b->observe("S2", "configured")->at(0), 1);
  EXPECT_EQ(b.i(A(b, "SPD_REF")), 1234);
  EXPECT_TRUE(b.b(A(b, "START")));
  // A second configuration word is ignored: slot 5 stays digital.
  b.set(A(b, "CFG"), static_cast<std::int16_t>(0x8000));
  b->run_for(milliseconds(20));
  EXPECT_TRUE(b.b(A(b, "START")));
  // A Stop-All (Run -> Program) allows a new configuration: now slot 5 is configured analog,
  // which does not match its digital module, so it exchanges nothing.
  ASSERT_TRUE(b->set_mode(Mode::Program));
  b->run_for(milliseconds(20));
  EXPECT_FALSE(b.b(A(b, "START")));
  EXPECT_EQ(b.i(A(b, "SPD_REF")), 1234);
}

// Section 4.6.4: a drive that stops answering: the head clears its input registers, keeps the
// drop on-line and keeps trying.
// (The reference register is DRV_REF: REF is the I/O refresh instruction, and a symbol may not
// spell a mnemonic.)
TEST(AutomaxMaster, DriveHeadClearsInputsOfASilentDrive) {
  const std::string bench = "automax NET slot=8 {\n  drive_head DH drop=6 ports=0,1\n}\n";
  const std::string defs =
      "IODEF RIO_D06@[SLOT=8,REGISTER=4,BIT=6]\n"
      "RIODEF DRV_REF%[MASTER_SLOT=8,DROP=6,SLOT=1,REGISTER=0]\n"
      "RIODEF FDBK%[MASTER_SLOT=8,DROP=6,SLOT=1,REGISTER=2]\n"
      "RIODEF P2%[MASTER_SLOT=8,DROP=6,SLOT=2,REGISTER=0]\n";
  Bench b(program(kNoRungs, defs), bench);
  b->scan(1);  // the master's power-up poll is its first event
  b.inject("DH", "input", {"1", "2", "500"});
  b.run();
  EXPECT_TRUE(b->set(A(b, "DRV_REF"), Value::of_int(300)));
  EXPECT_FALSE(b->set(A(b, "FDBK"), Value::of_int(1)));
  EXPECT_FALSE(b->get(A(b, "P2")).has_value());
  b->run_for(milliseconds(10));
  EXPECT_EQ(b.i(A(b, "FDBK")), 500);
  EXPECT_EQ(b->observe("DH", "outputs")->at(32), 300);
  b.inject("DH", "drive offline", {"1"});
  b->run_for(milliseconds(10));
  EXPECT_EQ(b.i(A(b, "FDBK")), 0);
  EXPECT_TRUE(b.b(A(b, "RIO_D06")));
  b.inject("DH", "drive online", {"1"});
  b->run_for(milliseconds(10));
  EXPECT_EQ(b.i(A(b, "FDBK")), 500);  // the drive answers again with what it sends
  b.inject("DH", "input", {"1", "2", "77"});
  b->run_for(milliseconds(10));
  EXPECT_EQ(b.i(A(b, "FDBK")), 77);
}

// The master's SLOT line: no SLC image words or G file, and the M0 file is the 4096-word image.
TEST(AutomaxMaster, SlotLineChecks) {
  auto check = [](const std::string& slot_line) {
    auto lr = load_program("START 1747-L532\n" + slot_line + "\nLADDER 2 MAIN\n" + kNoRungs, "t.slc");
    EXPECT_TRUE(lr.ok()) << lr.render_diagnostics();
    DiagnosticList d;
    check_module_configuration(*lr.program, d);
    return render_all(d, "t.slc", lr.source);
  };
  EXPECT_EQ(check("SLOT 8 57C416"), "");
  EXPECT_NE(check("SLOT 8 57C416 SCAN_IN 2").find("t.slc:2:6: error: 57C416 in slot 8: the AutoMax master has no SLC image"),
            std::string::npos);
  EXPECT_NE(check("SLOT 8 57C416 M0_SIZE 512").find("M0_SIZE must be 4096"), std::string::npos);
}

TEST(AutomaxBench, PositionedErrors) {
  auto errors = [](const std::string& bench) {
    auto lr = load_program(program(kNoRungs, ""), "t.slc");
    EXPECT_TRUE(lr.ok());
    auto s = load_module_setup_text(*lr.program, bench, "t.bench");
    EXPECT_FALSE(s.ok());
    return s.render("t.slc", lr.source);
  };
  EXPECT_NE(errors("automax N slot=8 {\n  multibus A drop=8\n}\n").find("t.bench:2:19: error: multibus A: drop=8: expected an integer 1-7"), std::string::npos);
  EXPECT_NE(errors("automax N slot=8 {\n  shark A drop=4\n  shark B drop=12\n}\n")
                .find("drop 12 uses image area 4, already used by shark A"),
            std::string::npos);
  EXPECT_NE(errors("automax N slot=8 {\n  shark A drop=12 {\n    module M slot=1 type=analog\n  }\n}\n")
                .find("is an all-digital Shark rack"),
            std::string::npos);
  EXPECT_NE(errors("automax N slot=8 {\n  remote A drop=1\n}\n").find("unknown drop kind 'remote'"), std::string::npos);
  EXPECT_NE(errors("automax N slot=8 {\n  head_57c328 H drop=1 rails=0,4\n}\n").find("t.bench:2:30: error: head_57c328 H: rails"),
            std::string::npos);
}

}  // namespace
}  // namespace softslc
