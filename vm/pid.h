// The SLC 500 PID instruction (1747-RM001G chapter 9), as one function over its control block.
//
// Design. The whole state of a loop lives in its 23-word integer control block (RM001G p. 9-5,
// table 9.2), as on the processor: the flags of word 0, the error code in word 1's high byte,
// the tuning words 2-13, the status words 14-16, the integral sum as a 32-bit long in words 17
// (MSW) and 18 (LSW), and softslc's own bookkeeping in the words the manual marks "internal use,
// do not change" (10 and 19-22). Nothing is kept outside the block, so `--state` snapshots,
// replays and several loops need no extra storage, and the same block and inputs always give the
// same result. execute_pid() is called by the interpreter with the rung condition, the process
// variable word, the control variable word and the virtual time of the execution; it returns the
// error code of table 9.36 when a parameter is invalid (the interpreter then raises major fault
// 0036h) and otherwise leaves the new CV for the caller to store.
//
// The equation is RM001G p. 9-2's standard (ISA, dependent-gains) form
//   CV = Kc * (E + 1/Ti * integral(E dt) + Td * d(PV)/dt) + bias,
// computed in CV counts (0-16383 = 0-100 %) at the configured loop update time, with the
// derivative low-pass filter of p. 9-2 (cut-off 16 times the derivative corner frequency), the
// zero-crossing deadband of p. 9-9, output limiting with anti-reset windup, and bumpless
// manual-to-auto transfer. The choices the manual leaves open are in docs/semantics.md, "PID".
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <string>

#include "vm/virtual_time.h"

namespace softslc::pid {

inline constexpr std::uint32_t kBlockWords = 23;  // RM001G p. 9-3: "fixed at 23 words"

// Word 0 flags (RM001G table 9.2).
inline constexpr std::uint16_t kTM = 1u << 0;   // timed mode (1) / STI mode (0)
inline constexpr std::uint16_t kAM = 1u << 1;   // manual (1) / auto (0)
inline constexpr std::uint16_t kCM = 1u << 2;   // E = PV - SP (1) / E = SP - PV (0)
inline constexpr std::uint16_t kOL = 1u << 3;   // output limiting
inline constexpr std::uint16_t kRG = 1u << 4;   // reset and gain range x0.01 (5/03+)
inline constexpr std::uint16_t kSC = 1u << 5;   // set: no setpoint scaling
inline constexpr std::uint16_t kTF = 1u << 6;   // loop update too fast
inline constexpr std::uint16_t kDA = 1u << 7;   // derivative on error (5/03+)
inline constexpr std::uint16_t kDB = 1u << 8;   // PV in the deadband
inline constexpr std::uint16_t kUL = 1u << 9;   // output alarm, upper limit
inline constexpr std::uint16_t kLL = 1u << 10;  // output alarm, lower limit
inline constexpr std::uint16_t kSP = 1u << 11;  // setpoint out of range
inline constexpr std::uint16_t kPV = 1u << 12;  // PV out of range
inline constexpr std::uint16_t kDN = 1u << 13;  // computed on this scan
inline constexpr std::uint16_t kRA = 1u << 14;  // rational approximation (5/03 OS Series C FRN 11+)
inline constexpr std::uint16_t kEN = 1u << 15;  // follows the rung

// Word numbers (RM001G table 9.2).
enum Word : std::uint32_t {
  kFlags = 0,
  kErrorCode = 1,   // high byte
  kSetpoint = 2,
  kGain = 3,        // Kc, x0.1 (x0.01 with RG)
  kReset = 4,       // Ti, minutes/repeat x0.1 (x0.01 with RG)
  kRate = 5,        // Td, minutes x0.01 (x0.1 on the 5/02)
  kBias = 6,        // feed forward/bias, CV counts
  kSetpointMax = 7,
  kSetpointMin = 8,
  kDeadband = 9,
  kOldSetpoint = 10,  // internal: the setpoint in use (the last valid one)
  kOutputMax = 11,    // percent
  kOutputMin = 12,    // percent
  kLoopUpdate = 13,   // 0.01 s
  kScaledPv = 14,
  kScaledError = 15,
  kOutputPercent = 16,
  kIntegralMsw = 17,
  kIntegralLsw = 18,
  kDerivativeInput = 19,  // internal: the last derivative input (PV, or E with DA), CV counts
  kDerivativeTerm = 20,   // internal: the filtered derivative term, CV counts
  kState = 21,            // internal: kInitialized, kInDeadband, kErrorNegative
  kUpdateStamp = 22,      // internal: 10 ms tick (low 16 bits) of the last update
};

// Word 21 bits (softslc's own).
inline constexpr std::uint16_t kInitialized = 1u << 0;
inline constexpr std::uint16_t kInDeadband = 1u << 1;
inline constexpr std::uint16_t kErrorNegative = 1u << 2;

// The integral sum (words 17-18) holds the integral term in CV counts as a 16.16 fixed-point
// long: 65536 is one count.
inline constexpr double kIntegralScale = 65536.0;

// Table 9.36 codes (word 1 high byte).
enum class Error : std::uint8_t {
  None = 0,
  LoopUpdate = 0x11,
  Gain = 0x12,
  Reset = 0x13,
  Rate = 0x14,
  SetpointMax = 0x21,  // SLC 5/02 only
  SetpointMin = 0x22,  // SLC 5/02 only
  SetpointScale = 0x23,
  Setpoint = 0x31,
  Deadband = 0x41,
  OutputMax = 0x51,
  OutputMin = 0x52,
  OutputLimits = 0x53,
};

struct Execution {
  bool rung = false;
  bool first_pass = false;  // first scan after entering Run or Test
  bool slc502 = false;      // the SLC 5/02 column of table 9.36 (ranges 0-255, no RG, DA)
  VirtualTime now = 0;      // virtual time of this execution
  std::int16_t pv = 0;      // the process variable word
  std::int16_t cv = 0;      // the control variable word as it is now (the program's in manual)
};

struct Outcome {
  Error error = Error::None;
  std::string message;      // what was wrong, with the word, for the fault record
  bool write_cv = false;    // store `cv` into the control variable word
  std::int16_t cv = 0;
  // The earliest time at which an execution on the same block and words could act otherwise than
  // this one: a timed-mode PID reads the clock only to see whether its loop update is due, so
  // until the tick at which it falls due (or, on a scan that computed, the next tick) it acts the
  // same. Never for a rung-false or STI-mode PID, which do not read the clock (repeated scans,
  // docs/semantics.md).
  VirtualTime same_until = std::numeric_limits<VirtualTime>::max();
};

// Executes the instruction once over `block` (23 words). Never reads or writes outside it.
Outcome execute(std::span<std::uint16_t, kBlockWords> block, const Execution& x);

// The integral sum of words 17 (MSW) and 18 (LSW).
std::int32_t integral_sum(std::span<const std::uint16_t, kBlockWords> block);

}  // namespace softslc::pid
