// The PID instruction (issue 15): every error code of RM001G table 9.36, every word-0 bit, and the
// manual's worked numbers, first on the control block itself (pid::execute with chosen virtual
// times, so each update is exactly where the test puts it), then in ladder through the Runtime
// (the checker's rules, major fault 0036h, EN and the CV word).
//
// RM = 1747-RM001G (SLC 500 Instruction Set Reference, Nov 2008), chapter 9. Expected values are
// the manual's examples where it gives one, otherwise a hand calculation written next to the
// assertion from the equation of RM 9-2 and the units of RM 9-6, 9-7, 9-8, 9-10, 9-11.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "vm/pid.h"
#include "../vm/vm_test_util.h"

namespace softslc::test {
namespace {

using namespace softslc::pid;

// A control block as the manual lays it out (RM 9-5, table 9.2), zeroed, timed mode.
struct Block {
  std::array<std::uint16_t, kBlockWords> w{};
  Block() { w[kFlags] = kTM; }
  void set(Word k, int v) { w[k] = static_cast<std::uint16_t>(static_cast<std::int16_t>(v)); }
  int get(Word k) const { return static_cast<std::int16_t>(w[k]); }
  void flag(std::uint16_t bit, bool on) {
    w[kFlags] = static_cast<std::uint16_t>(on ? (w[kFlags] | bit) : (w[kFlags] & ~bit));
  }
  bool has(std::uint16_t bit) const { return (w[kFlags] & bit) != 0; }
  int error_code() const { return w[kErrorCode] >> 8; }
  Outcome run(int pv, VirtualTime t, int cv = 0, bool slc502 = false, bool rung = true) {
    Execution x;
    x.rung = rung;
    x.slc502 = slc502;
    x.now = t;
    x.pv = static_cast<std::int16_t>(pv);
    x.cv = static_cast<std::int16_t>(cv);
    Outcome o = execute(std::span<std::uint16_t, kBlockWords>(w), x);
    if (o.write_cv) last_cv = o.cv;
    return o;
  }
  int last_cv = 0;
};

// A valid loop: Kc 1.0 (10 x 0.1), no reset or rate, loop update 0.10 s (10 x 0.01 s), output
// limits 0-100 %, no scaling.
Block valid_loop() {
  Block b;
  b.set(kGain, 10);
  b.set(kLoopUpdate, 10);
  b.set(kOutputMax, 100);
  b.set(kOutputMin, 0);
  return b;
}

constexpr VirtualTime ms(std::int64_t n) { return n * kNsPerMs; }

// ---- Table 9.36: each error code (RM 9-21) -----------------------------------------------------------------

struct ErrorCase {
  const char* what;
  void (*mutate)(Block&);
  bool slc502;
  int code;
};

TEST(PidErrors, EachCodeOfTable936LandsInWord1HighByte) {
  const ErrorCase cases[] = {
      {"loop update 0", [](Block& b) { b.set(kLoopUpdate, 0); }, false, 0x11},
      {"loop update 1025 (5/03: > 1024)", [](Block& b) { b.set(kLoopUpdate, 1025); }, false, 0x11},
      {"loop update 256 (5/02: > 255)", [](Block& b) { b.set(kLoopUpdate, 256); }, true, 0x11},
      {"gain < 0 (5/03)", [](Block& b) { b.set(kGain, -1); }, false, 0x12},
      {"gain 0 (5/02)", [](Block& b) { b.set(kGain, 0); }, true, 0x12},
      {"gain 256 (5/02)", [](Block& b) { b.set(kGain, 256); }, true, 0x12},
      {"reset < 0 (5/03)", [](Block& b) { b.set(kReset, -1); }, false, 0x13},
      {"reset 256 (5/02)", [](Block& b) { b.set(kReset, 256); }, true, 0x13},
      {"rate < 0 (5/03)", [](Block& b) { b.set(kRate, -1); }, false, 0x14},
      {"rate 256 (5/02)", [](Block& b) { b.set(kRate, 256); }, true, 0x14},
      {"Smax 16384 (5/02 only)", [](Block& b) { b.set(kSetpointMax, 16384); }, true, 0x21},
      {"Smin -16384 (5/02 only)", [](Block& b) { b.set(kSetpointMax, 100); b.set(kSetpointMin, -16384); }, true, 0x22},
      {"Smin > Smax", [](Block& b) { b.set(kSetpointMax, 100); b.set(kSetpointMin, 200); }, false, 0x23},
      {"deadband < 0", [](Block& b) { b.set(kDeadband, -1); }, false, 0x41},
      {"deadband > 16383 without scaling", [](Block& b) { b.set(kDeadband, 16384); }, false, 0x41},
      {"deadband > Smax - Smin", [](Block& b) { b.set(kSetpointMax, 100); b.set(kDeadband, 101); b.set(kSetpoint, 50); }, false, 0x41},
      {"output max > 100", [](Block& b) { b.set(kOutputMax, 101); }, false, 0x51},
      {"output max < 0", [](Block& b) { b.set(kOutputMax, -1); }, false, 0x51},
      {"output min > 100", [](Block& b) { b.set(kOutputMin, 101); }, false, 0x52},
      {"output min > output max", [](Block& b) { b.set(kOutputMax, 40); b.set(kOutputMin, 60); }, false, 0x53},
      {"setpoint 16384 without scaling, initial execution", [](Block& b) { b.set(kSetpoint, 16384); }, false, 0x31},
      {"setpoint below Smin, initial execution", [](Block& b) { b.set(kSetpointMax, 100); b.set(kSetpointMin, 10); b.set(kSetpoint, 5); }, false, 0x31},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.what);
    Block b = valid_loop();
    b.w[kErrorCode] = 0x00AB;  // the low byte is not the instruction's
    c.mutate(b);
    const Outcome o = b.run(0, 0, 0, c.slc502);
    EXPECT_EQ(static_cast<int>(o.error), c.code);
    EXPECT_EQ(b.error_code(), c.code);
    EXPECT_EQ(b.w[kErrorCode] & 0xFF, 0xAB);
    EXPECT_FALSE(o.write_cv);
    EXPECT_FALSE(b.has(kDN));
    EXPECT_NE(o.message.find("table 9.36"), std::string::npos) << o.message;
  }
}

TEST(PidErrors, The503RangesAcceptWhatThe502Refuses) {
  // Table 9.36: the 5/02's 0-255 limits on Kc, Ti, Td, the loop update and Smax/Smin (21H, 22H
  // are "SLC 5/02 only") do not apply to the 5/03 and higher: Kc 0 and 32767, loop update 1024
  // (10.24 s, RM 9-8), Smax 20000 are valid there.
  Block b = valid_loop();
  b.set(kGain, 0);
  b.set(kReset, 32767);
  b.set(kRate, 300);
  b.set(kLoopUpdate, 1024);
  b.set(kSetpointMax, 20000);
  b.set(kSetpointMin, -20000);
  EXPECT_EQ(b.run(0, 0).error, Error::None);
}

TEST(PidErrors, AnOutOfRangeSetpointAfterTheFirstExecutionKeepsTheOldOne) {
  // Table 9.36, 31H: "during subsequent execution of the PID loop if an invalid loop setpoint is
  // entered, the PID loop continues to execute using the old setpoint, and bit 11 of word 0 of the
  // control block is set." P-only, Kc 1.0: CV = SP - PV.
  Block b = valid_loop();
  b.set(kSetpoint, 8000);
  b.run(6000, 0);
  EXPECT_EQ(b.last_cv, 2000);
  b.set(kSetpoint, 20000);
  const Outcome o = b.run(6000, ms(100));
  EXPECT_EQ(o.error, Error::None);
  EXPECT_TRUE(b.has(kSP));
  EXPECT_EQ(b.last_cv, 2000) << "still 8000 - 6000";
  b.set(kSetpoint, 9000);
  b.run(6000, ms(200));
  EXPECT_FALSE(b.has(kSP));
  EXPECT_EQ(b.last_cv, 3000);
}

// ---- Word 0 bits (RM 9-5 table 9.2, 9-7 to 9-14) -------------------------------------------------------------

TEST(PidBits, EnFollowsTheRungAndAFalseRungClearsTheIntegral) {
  // RM 9-14 table 9.23: EN "follows the rung state"; RM 9-3: "If a PID instruction goes false,
  // the integral term is cleared."
  Block b = valid_loop();
  b.set(kReset, 1);
  b.set(kSetpoint, 5000);
  b.run(4000, 0);
  b.run(4000, ms(100));
  EXPECT_TRUE(b.has(kEN));
  EXPECT_NE(integral_sum(b.w), 0);
  b.run(4000, ms(200), 0, false, /*rung=*/false);
  EXPECT_FALSE(b.has(kEN));
  EXPECT_FALSE(b.has(kDN));
  EXPECT_EQ(integral_sum(b.w), 0);
  EXPECT_EQ(b.get(kIntegralMsw), 0);
  EXPECT_EQ(b.get(kIntegralLsw), 0);
}

TEST(PidBits, TimedModeComputesAtTheLoopUpdateRateAndDnForOneExecution) {
  // RM 9-7/9-8: TM = 1 updates the CV at the loop update rate (word 13, 0.01 s: "the value 10 (for
  // 100 ms)"); RM 9-13 table 9.21: DN "is set for one scan when the PID algorithm is computed".
  Block b = valid_loop();
  b.set(kSetpoint, 8000);
  b.run(6000, 0);
  EXPECT_TRUE(b.has(kDN)) << "the initial execution computes";
  int computed = 0;
  for (int t = 5; t <= 1000; t += 5) {  // a 5 ms scan for one second
    b.run(6000, ms(t));
    computed += b.has(kDN) ? 1 : 0;
  }
  EXPECT_EQ(computed, 10) << "every 100 ms";
  EXPECT_FALSE(b.has(kTF));
}

TEST(PidBits, TimedModeSaysUntilWhenItActsTheSame) {
  // Repeated scans (docs/semantics.md "The SLC's PID"): a timed PID that did not compute acts the
  // same until its next update is due, 100 ms after the last one (RM 9-7: loop update 10 = 100 ms,
  // on the 10 ms clock); one that computed, until the next 10 ms tick; an STI-mode (RM 9-8) or
  // rung-false one never reads the clock.
  Block b = valid_loop();
  b.set(kSetpoint, 8000);
  EXPECT_EQ(b.run(6000, ms(3)).same_until, ms(10)) << "the initial execution computes";
  EXPECT_EQ(b.run(6000, ms(47)).same_until, ms(100)) << "due at the tick 100 ms after the first update's";
  EXPECT_FALSE(b.has(kDN));
  EXPECT_EQ(b.run(6000, ms(99)).same_until, ms(100));
  const Outcome due = b.run(6000, ms(100));
  EXPECT_TRUE(b.has(kDN)) << "computed at 100 ms";
  EXPECT_EQ(due.same_until, ms(110));
  EXPECT_EQ(b.run(6000, ms(101)).same_until, ms(200));
  EXPECT_EQ(b.run(6000, ms(150), 0, false, false).same_until, std::numeric_limits<VirtualTime>::max()) << "rung false";
  b.flag(kTM, false);
  EXPECT_EQ(b.run(6000, ms(160)).same_until, std::numeric_limits<VirtualTime>::max()) << "STI mode";
}

TEST(PidBits, StiModeComputesEveryExecution) {
  // RM 9-8: "When set for STI mode, the PID executes and updates the CV every time the PID
  // instruction is scanned".
  Block b = valid_loop();
  b.flag(kTM, false);
  b.set(kSetpoint, 8000);
  for (int t = 0; t < 50; t += 5) {
    b.run(6000, ms(t));
    EXPECT_TRUE(b.has(kDN));
  }
}

TEST(PidBits, TfWhenAScanIsLongerThanTheLoopUpdate) {
  // RM 9-11: TF "is set by the PID algorithm if the loop update time specified cannot be achieved
  // by the controller due to scan time limitations". Loop update 100 ms; executions 250 ms apart.
  Block b = valid_loop();
  b.set(kSetpoint, 8000);
  b.run(6000, 0);
  b.run(6000, ms(250));
  EXPECT_TRUE(b.has(kTF));
  EXPECT_TRUE(b.has(kDN));
  b.run(6000, ms(350));
  EXPECT_FALSE(b.has(kTF)) << "100 ms later the rate is achieved again";
}

TEST(PidBits, ControlModeSelectsTheSignOfTheError) {
  // RM 9-10 table 9.11: CM = 0 reverse acting, E = SP - PV ("the control variable decreases when
  // the process variable is greater than the setpoint"); CM = 1 forward acting, E = PV - SP.
  Block rev = valid_loop();
  rev.set(kSetpoint, 8000);
  rev.set(kBias, 8000);
  rev.run(9000, 0);
  EXPECT_EQ(rev.last_cv, 7000) << "8000 + 1.0 x (8000 - 9000)";
  EXPECT_EQ(rev.get(kScaledError), -1000);
  Block fwd = valid_loop();
  fwd.flag(kCM, true);
  fwd.set(kSetpoint, 8000);
  fwd.set(kBias, 8000);
  fwd.run(9000, 0);
  EXPECT_EQ(fwd.last_cv, 9000) << "8000 + 1.0 x (9000 - 8000)";
  EXPECT_EQ(fwd.get(kScaledError), 1000);
}

TEST(PidBits, OutputLimitingClampsAndTheAlarmsSayWhy) {
  // RM 9-12 tables 9.17/9.18: UL "set when the calculated CV output exceeds the upper CV limit",
  // LL "when the calculated CV output is less than the lower CV limit". With OL the CV is held to
  // output max/min (percent of 16383): 80 % = 13106.4 -> 13106, 20 % = 3276.6 -> 3277.
  Block b = valid_loop();
  b.flag(kOL, true);
  b.set(kOutputMax, 80);
  b.set(kOutputMin, 20);
  b.set(kSetpoint, 16000);
  b.run(0, 0);
  EXPECT_EQ(b.last_cv, 13106);
  EXPECT_TRUE(b.has(kUL));
  EXPECT_FALSE(b.has(kLL));
  EXPECT_EQ(b.get(kOutputPercent), 80);
  b.set(kSetpoint, 1000);
  b.run(0, ms(100));
  EXPECT_EQ(b.last_cv, 3277) << "1000 is below 20 %";
  EXPECT_TRUE(b.has(kLL));
  EXPECT_FALSE(b.has(kUL));
  // Without OL the alarms still compare with the limits, but the CV is not overridden.
  b.flag(kOL, false);
  b.run(0, ms(200));
  EXPECT_EQ(b.last_cv, 1000);
  EXPECT_TRUE(b.has(kLL));
}

TEST(PidBits, AntiResetWindupHoldsTheIntegralAtTheLimit) {
  // While the output is held at its limit, the integral does not keep growing into it, so the CV
  // leaves the limit as soon as the error reverses (docs/semantics.md, "PID").
  Block b = valid_loop();
  b.flag(kOL, true);
  b.set(kOutputMax, 50);
  b.set(kReset, 1);  // 6 s/repeat
  b.set(kSetpoint, 10000);
  b.run(0, 0);  // P alone is 10000 > 50 % (8191.5)
  const std::int32_t held = integral_sum(b.w);
  for (int k = 1; k <= 100; ++k) b.run(0, ms(std::int64_t{100} * k));
  EXPECT_EQ(integral_sum(b.w), held);
  EXPECT_EQ(b.last_cv, 8192);
  // PV passes the setpoint: the output leaves the limit at once.
  b.run(10100, ms(10100));
  EXPECT_EQ(b.last_cv, 0) << "-100 of P, no wound-up integral";
}

TEST(PidBits, SetpointScalingAndTheScBit) {
  // RM 9-11 table 9.14: "The SC bit is cleared when setpoint scaling values are specified."
  // Smin 0, Smax 1000: SP 500 is 8191.5 counts; PV 8192 is 500.03 -> scaled PV 500 (word 14), the
  // scaled error SP - PV = 0 in engineering units (word 15, RM 9-9 table 9.9).
  Block b = valid_loop();
  b.set(kSetpointMax, 1000);
  b.set(kSetpointMin, 0);
  b.set(kSetpoint, 500);
  b.set(kBias, 100);
  b.run(8192, 0);
  EXPECT_FALSE(b.has(kSC));
  EXPECT_EQ(b.get(kScaledPv), 500);
  EXPECT_EQ(b.get(kScaledError), 0);
  EXPECT_EQ(b.last_cv, 100) << "100 + 1.0 x (8191.5 - 8192) = 99.5, rounded half away from zero";
  Block n = valid_loop();
  n.set(kSetpoint, 500);
  n.run(400, 0);
  EXPECT_TRUE(n.has(kSC)) << "no scaling values";
  EXPECT_EQ(n.get(kScaledPv), 400);
}

TEST(PidBits, PvOutOfRange) {
  // RM 9-13 table 9.20: PV set when the unscaled PV exceeds 16383 or is less than zero.
  Block b = valid_loop();
  b.set(kSetpoint, 100);
  b.run(-5, 0);
  EXPECT_TRUE(b.has(kPV));
  EXPECT_EQ(b.last_cv, 100) << "the loop uses PV 0";
  b.run(16384, ms(100));
  EXPECT_TRUE(b.has(kPV));
  b.run(16383, ms(200));
  EXPECT_FALSE(b.has(kPV));
}

TEST(PidBits, RationalApproximationChangesNothingHere) {
  // RM 9-14 table 9.22: RA selects "rational approximation ... resulting in a more accurate
  // output" (5/03 OS Series C FRN 11+). softslc always computes in double precision, so RA set or
  // clear gives the same loop (docs/semantics.md, "PID").
  Block a = valid_loop(), b = valid_loop();
  b.flag(kRA, true);
  for (Block* x : {&a, &b}) {
    x->set(kReset, 3);
    x->set(kRate, 2);
    x->set(kSetpoint, 7000);
  }
  for (int k = 0; k < 50; ++k) {
    a.run(3000 + 40 * k, ms(std::int64_t{100} * k));
    b.run(3000 + 40 * k, ms(std::int64_t{100} * k));
    EXPECT_EQ(a.last_cv, b.last_cv);
  }
  EXPECT_TRUE(b.has(kRA)) << "the instruction leaves the control bit alone";
}

TEST(PidBits, ZeroCrossingDeadband) {
  // RM 9-8/9-9: "The deadband is entered at the zero crossing of the process variable and the
  // setpoint. This means that the deadband is in effect only after the process variable enters the
  // deadband and passes through the setpoint." SP 8000, deadband 100, P-only with bias 5000.
  Block b = valid_loop();
  b.set(kSetpoint, 8000);
  b.set(kDeadband, 100);
  b.set(kBias, 5000);
  b.run(7800, 0);
  EXPECT_FALSE(b.has(kDB));
  b.run(7950, ms(100));  // inside the band, not yet through the setpoint
  EXPECT_FALSE(b.has(kDB));
  EXPECT_EQ(b.last_cv, 5050);
  b.run(8010, ms(200));  // passed through the setpoint: error 0 inside the band
  EXPECT_TRUE(b.has(kDB));
  EXPECT_EQ(b.last_cv, 5000);
  b.run(7960, ms(300));  // still within 100
  EXPECT_TRUE(b.has(kDB));
  EXPECT_EQ(b.last_cv, 5000);
  b.run(7850, ms(400));  // left the band
  EXPECT_FALSE(b.has(kDB));
  EXPECT_EQ(b.last_cv, 5150);
}

TEST(PidBits, ManualModeIsBumpless) {
  // RM 9-9 table 9.10: AM = 1 "specifies manual operation ... the user/control program controls
  // the CV"; "Output limiting is also applied when in manual." The integral tracks so that the
  // return to auto starts from the manual CV: no reset, P = 1.0 x 1000, so I = 5000 - 1000.
  Block b = valid_loop();
  b.flag(kAM, true);
  b.set(kSetpoint, 5000);
  b.run(4000, 0, 5000);
  EXPECT_EQ(b.last_cv, 5000);
  EXPECT_EQ(integral_sum(b.w), 4000 * 65536);
  b.flag(kAM, false);
  b.run(4000, ms(100));
  EXPECT_EQ(b.last_cv, 5000) << "no bump at the transfer";
  // Limits apply in manual too.
  b.flag(kAM, true);
  b.flag(kOL, true);
  b.set(kOutputMax, 50);
  b.run(4000, ms(200), 12000);
  EXPECT_EQ(b.last_cv, 8192);
  EXPECT_TRUE(b.has(kUL));
}

// ---- The manual's numbers -------------------------------------------------------------------------------------

TEST(PidNumbers, RgSetGainAndResetUnitsRm911) {
  // RM 9-11, "Example with the RG bit set: The reset term (TI) of 1 indicates that the integral
  // value of 0.01 minutes/repeat (0.6 seconds/repeat) is applied ... The gain value (KC) of 1
  // indicates that the error is multiplied by 0.01."
  Block g = valid_loop();
  g.flag(kRG, true);
  g.set(kGain, 1);
  g.set(kSetpoint, 3000);
  g.run(1000, 0);
  EXPECT_EQ(g.last_cv, 20) << "2000 x 0.01";
  // Kc 100 (1.00), Ti 1 (0.6 s/repeat), E 1000, 0.1 s updates: after 0.6 s the integral has
  // repeated the proportional action once: CV = 1000 + 1000.
  Block b = valid_loop();
  b.flag(kRG, true);
  b.set(kGain, 100);
  b.set(kReset, 1);
  b.set(kSetpoint, 5000);
  b.run(4000, 0);
  EXPECT_EQ(b.last_cv, 1000);
  for (int k = 1; k <= 6; ++k) b.run(4000, ms(std::int64_t{100} * k));
  EXPECT_EQ(b.last_cv, 2000);
  // The integral sum is a long in words 17 (MSW) and 18 (LSW) (RM 9-14 table 9.24), here 16.16
  // fixed-point counts: 1000 counts and the few 1/65536 that six roundings of 166.67 leave.
  EXPECT_EQ(b.get(kIntegralMsw), 1000);
  EXPECT_NEAR(integral_sum(b.w) / 65536.0, 1000.0, 1e-4);
}

TEST(PidNumbers, RgClearGainAndResetUnitsRm911) {
  // RM 9-11, "Example with the RG bit clear: The reset term (TI) of 1 indicates that the integral
  // value of 0.1 minutes/repeat (6.0 seconds/repeat) ... The gain value (KC) of 1 indicates that
  // the error is multiplied by 0.1."
  Block g = valid_loop();
  g.set(kGain, 1);
  g.set(kSetpoint, 3000);
  g.run(1000, 0);
  EXPECT_EQ(g.last_cv, 200) << "2000 x 0.1";
  Block b = valid_loop();  // Kc 10 = 1.0
  b.set(kReset, 1);
  b.set(kSetpoint, 5000);
  b.run(4000, 0);
  for (int k = 1; k <= 59; ++k) b.run(4000, ms(std::int64_t{100} * k));
  EXPECT_EQ(b.last_cv, 1983) << "1000 + 59/60 x 1000 = 1983.3";
  b.run(4000, ms(6000));
  EXPECT_EQ(b.last_cv, 2000) << "one repeat in 6.0 s";
}

TEST(PidNumbers, The502IgnoresRgAndHasRateInTenthsOfAMinute) {
  // RM 9-2 table 9.1, SLC 5/02 column: Kc 0.1-25.5, reset 25.5-0.1 min/repeat, rate 0.1-25.5 min;
  // RG (RM 9-10) and DA (RM 9-12) apply to the 5/03 and higher only.
  Block b = valid_loop();
  b.flag(kRG, true);
  b.set(kSetpoint, 3000);
  b.run(1000, 0, 0, /*slc502=*/true);
  EXPECT_EQ(b.last_cv, 2000) << "Kc 10 is 1.0 on the 5/02 whatever RG says";
}

TEST(PidNumbers, DerivativeFilterCutOffIs16TimesTheCornerRm92) {
  // RM 9-2: "The derivative term (rate) provides smoothing by means of a low-pass filter. The
  // cutoff frequency of the filter is 16 times greater than the corner frequency of the derivative
  // term." Td 1 = 0.01 min = 0.6 s, filter time constant 0.6/16 = 0.0375 s, loop update 0.01 s,
  // Kc 1.0, SP 8000; the PV steps 0 -> 100 at the second update (derivative on the PV, RM 9-12).
  // Backward Euler: D1 = Kc Td (-100) / (Tf + dt) = -60 / 0.0475 = -1263.16; CV = 7900 - 1263.16.
  // Then D2 = Tf / (Tf + dt) x D1 = 15/19 x (-1263) = -997.1 (the stored term is whole counts).
  Block b = valid_loop();
  b.set(kLoopUpdate, 1);
  b.set(kRate, 1);
  b.set(kSetpoint, 8000);
  b.run(0, 0);
  EXPECT_EQ(b.last_cv, 8000);
  b.run(100, ms(10));
  EXPECT_EQ(b.last_cv, 6637);
  b.run(100, ms(20));
  EXPECT_EQ(b.last_cv, 6903);
  // DA = 1 (RM 9-12): on the error instead; a setpoint step then kicks the output.
  Block e = valid_loop();
  e.flag(kDA, true);
  e.set(kLoopUpdate, 1);
  e.set(kRate, 1);
  e.set(kSetpoint, 8000);
  e.run(0, 0);
  e.set(kSetpoint, 8100);
  e.run(0, ms(10));
  EXPECT_EQ(e.last_cv, 9363) << "8100 + 1263.16";
}

TEST(PidNumbers, CvPercentAndTheFullScaleRm94) {
  // RM 9-4: "The output value ranges from 0 to 16383, with 16383 being the 100% on value"; word 16
  // is the output CV% (0 to 100 %, table 9.2): 2000 / 16383 = 12.2 %.
  Block b = valid_loop();
  b.set(kSetpoint, 8000);
  b.run(6000, 0);
  EXPECT_EQ(b.last_cv, 2000);
  EXPECT_EQ(b.get(kOutputPercent), 12);
  b.set(kSetpoint, 16383);
  b.set(kGain, 100);  // 10.0 x 16383 saturates at 100 %
  b.run(0, ms(100));
  EXPECT_EQ(b.last_cv, 16383);
  EXPECT_EQ(b.get(kOutputPercent), 100);
}

// ---- In ladder: the checker, fault 0036h, the CV word -------------------------------------------------------

std::string check_errors(std::string_view body, std::string_view header = kHeader) {
  std::string errors;
  auto rt = try_build(program_text(body, header), errors);
  return errors;
}

TEST(PidLadder, TheCheckerRulesOfRm93) {
  // RM 9-3: the control block "should be entered as an integer file address ... an entry of N10:0
  // will allocate elements N10:0 through N10:22"; the PV and CV are element addresses.
  EXPECT_EQ(check_errors("SOR PID N10:0 N10:28 N10:29 EOR"), "");
  EXPECT_NE(check_errors("SOR PID B3:0 N10:28 N10:29 EOR").find("23 words of an N file"), std::string::npos);
  EXPECT_NE(check_errors("SOR PID F8:0 N10:28 N10:29 EOR").find("23 words of an N file"), std::string::npos);
  EXPECT_NE(check_errors("SOR PID N10:240 N7:0 N7:1 EOR").find("runs past the end of the file"), std::string::npos);
  EXPECT_EQ(check_errors("SOR PID N10:233 N7:0 N7:1 EOR"), "") << "233 + 23 = 256 fits";
  const std::string inside = check_errors("SOR PID N10:0 N10:5 N10:29 EOR");
  EXPECT_NE(inside.find("PID process variable N10:5 lies inside the control block"), std::string::npos) << inside;
  const std::string cv_inside = check_errors("SOR PID N10:0 N10:28 N10:22 EOR");
  EXPECT_NE(cv_inside.find("PID control variable N10:22 lies inside"), std::string::npos) << cv_inside;
  EXPECT_NE(check_errors("SOR PID N10:0 100 N10:29 EOR").find("expected an element address"), std::string::npos);
  EXPECT_NE(check_errors("SOR PID N10:0 N10:28 F8:0 EOR").find("integer words"), std::string::npos);
  EXPECT_NE(check_errors("SOR PID N10:0 N10:28 N10:29/3 EOR").find("not a bit"), std::string::npos);
  EXPECT_NE(check_errors("SOR PID N10:0 N10:28 EOR").find("PID takes 3 operands"), std::string::npos);
}

TEST(PidLadder, WhichProcessorsHaveItRm91) {
  // RM 9-1: SLC 5/02, 5/03, 5/04, 5/05; not the fixed controllers or the 5/01.
  EXPECT_EQ(check_errors("SOR PID N10:0 N10:28 N10:29 EOR", "START 1747-L524\n"), "");
  EXPECT_EQ(check_errors("SOR PID N10:0 N10:28 N10:29 EOR", "START 1747-L551\n"), "");
  const std::string e = check_errors("SOR PID N10:0 N10:28 N10:29 EOR", "START 1747-L511\n");
  EXPECT_NE(e.find("PID is not available on the SLC 5/01"), std::string::npos) << e;
  const std::string ml = check_errors("SOR PID N10:0 N10:28 N10:29 EOR", "START Bul.1766\n");
  EXPECT_NE(ml.find("PD file element"), std::string::npos) << ml;
}

TEST(PidLadder, AnInvalidParameterIsMajorFault0036) {
  // RM 9-21: "Error code 0036 appears in the status file when a PID instruction runtime error
  // occurs ... a unique single byte code value that appears in the MS byte of the second word of
  // the control block." Loop update 0: 11H.
  Plc plc("SOR PID N10:0 N10:28 N10:29 EOR");
  plc.set("N10:0", 1);  // TM
  plc.set("N10:3", 10);
  plc.run_scans(1);
  ASSERT_EQ(plc.fault_code(), 0x0036);
  EXPECT_EQ(plc.i("S:6"), 0x0036);
  EXPECT_EQ(plc.i("N10:1") >> 8 & 0xFF, 0x11);
  EXPECT_NE(plc->fault()->message.find("N10:0: PID error 11H: loop update time (word 13) is 0"), std::string::npos)
      << plc->fault()->message;
}

TEST(PidLadder, TimedModeFollowsVirtualTimeWhateverTheScan) {
  // RM 9-7/9-8: in timed mode the CV is updated at the loop update rate (0.10 s here), not once per
  // scan: over 2 s of virtual time DN is set on 20 scans, whatever the scan time.
  Plc plc("SOR PID N10:0 N10:28 N10:29 EOR");
  plc.set("N10:0", 1);
  plc.set("N10:2", 8000);
  plc.set("N10:3", 10);
  plc.set("N10:11", 100);
  plc.set("N10:13", 10);
  plc.run_scans(1);  // the initial execution
  ASSERT_TRUE(plc.b("N10:0/13"));
  int updates = 0;
  const VirtualTime start = plc->now();
  while (plc->now() < start + milliseconds(2000)) {
    plc->scan(1);
    updates += plc.b("N10:0/13") ? 1 : 0;
  }
  EXPECT_GT(plc->stats().scans, 200u) << "many scans per update";
  EXPECT_EQ(updates, 20);
  EXPECT_FALSE(plc.b("N10:0/6")) << "TF: the rate is achieved";
}

TEST(PidLadder, RunsInTheScanWithEnDnAndTheCvWord) {
  Plc plc("SOR XIC B3:0/0 PID N10:0 N10:28 N10:29 EOR");
  plc.set("N10:0", 1);       // TM
  plc.set("N10:2", 8000);    // SP
  plc.set("N10:3", 10);      // Kc 1.0
  plc.set("N10:11", 100);    // output max %
  plc.set("N10:13", 10);     // 0.10 s
  plc.set("N10:28", 6000);   // PV
  plc.set("B3:0", 1);
  plc.run_scans(1);
  ASSERT_FALSE(plc->fault().has_value()) << plc->fault()->to_string();
  EXPECT_EQ(plc.i("N10:29"), 2000);
  EXPECT_TRUE(plc.b("N10:0/15"));
  EXPECT_TRUE(plc.b("N10:0/13"));
  plc.set("B3:0", 0);
  plc->scan(1);
  EXPECT_FALSE(plc.b("N10:0/15"));
  EXPECT_EQ(plc.i("N10:29"), 2000) << "a false PID leaves the CV";
}

}  // namespace
}  // namespace softslc::test
