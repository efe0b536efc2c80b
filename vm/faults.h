// Major fault codes and the record of a fault.
//
// A major fault stops the program scan at once: the processor sets S:1/13, writes the code to
// S:6, enters Faulted mode and de-energises its outputs. softslc also records where it happened
// (program file and rung, -1 when it was not inside the program) and a sentence saying why, for
// tools and tests. Codes marked [S]/[U] follow docs/semantics.md "Fault codes"; the SLC manual's
// full table (RM 16-8/16-9) was not available, so the choices are written down there.
#pragma once

#include <cstdint>
#include <string>

#include "vm/virtual_time.h"

namespace softslc {

namespace fault {
// A minor error bit (S:5/0 overflow trap) still set at END or TND [C].
inline constexpr std::uint16_t kMinorErrorAtEnd = 0x0020;
// The scan exceeded the watchdog S:3 high byte [C RM 16-7].
inline constexpr std::uint16_t kWatchdog = 0x0022;
// S:31 (or STS) names an STI file that is not a subroutine file of the program [C facts §3, RM 11-12].
inline constexpr std::uint16_t kInvalidStiFile = 0x0023;
// S:30 (or the STS time) is outside the processor's STI setpoint range [C RM 16-7, RM 11-12].
inline constexpr std::uint16_t kInvalidStiSetpoint = 0x0024;
// An indirect address points outside the data space (file missing, element past the file) [S].
inline constexpr std::uint16_t kIndirectOutOfRange = 0x0029;
// An indexed address (S:24 offset) or a file instruction's range runs past its data file [S].
inline constexpr std::uint16_t kIndexOutOfRange = 0x002A;
// JSR nesting deeper than the processor allows [S: MicroLogix 1400 code 0030].
inline constexpr std::uint16_t kSubroutineNesting = 0x0030;
// A timer executed with a negative PRE or ACC [S].
inline constexpr std::uint16_t kNegativeTimerValue = 0x0034;
// A PID instruction found an invalid parameter; the table 9.36 code is in the high byte of the
// control block's word 1 [C 1747-RM001G p. 9-21].
inline constexpr std::uint16_t kPidError = 0x0036;
// The discrete input interrupt's configuration is refused at the end of a scan, at a DII
// routine's exit or on entry to Run: S:46 names no subroutine file 3-255 of the program, or S:47 no
// slot 1-30 holding a discrete input card, or S:50 a preset below 0. RM 11-18 .. 11-26 require valid
// values but the fault table (RM 16-8/16-9) was not reached: both codes are softslc's choice [U].
inline constexpr std::uint16_t kInvalidDiiFile = 0x0042;
inline constexpr std::uint16_t kInvalidDiiConfig = 0x0043;
// A module refused an M0/M1 access: xx55 with the slot in the high byte [U, softslc's choice].
constexpr std::uint16_t module_access(int slot) { return static_cast<std::uint16_t>((slot << 8) | 0x55); }
// A specialty instruction reached a module that does not execute it (or an empty slot); the
// module setup's compile hook normally refuses such programs first [softslc].
inline constexpr std::uint16_t kUnsupportedInstruction = 0x001F;
}  // namespace fault

struct FaultInfo {
  std::uint16_t code = 0;
  int file = -1;  // program file number, -1 when outside the program scan
  int rung = -1;  // rung number within the file, -1 when not known
  std::string message;
  VirtualTime time = 0;

  // "fault 0022h in file 2 rung 5: ..." — the CLI prints this.
  std::string to_string() const;
};

}  // namespace softslc
