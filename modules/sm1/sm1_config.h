// The 1203-SM1 SLC to SCANport module's configuration: its SLOT line (mode from the module ID
// code, image and M-file sizes, G file, DIP switches as OPTION keys) and its bench node (the
// SCANport drives on its three channels). docs/1203-sm1.md, "The module".
//
// The checker (`softslc check`) and the module read the SLOT line through decode_sm1_slot(), so
// the configuration the checker accepts is exactly the one the module runs.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "modules/bench/bench.h"
#include "modules/scanport/drive.h"
#include "parser/program.h"

namespace softslc {

// Module ID codes (chapter 3: basic mode; chapter 4, Figure 4.3: enhanced mode).
inline constexpr int kSm1BasicIdCode = 3516;
inline constexpr int kSm1EnhancedIdCode = 13616;
inline constexpr int kSm1Channels = 3;
// I/O image words (chapter 1 table: "Total number of words of I/O for module 8 / 32").
inline constexpr int kSm1BasicImageWords = 8;
inline constexpr int kSm1EnhancedImageWords = 32;
// Largest M files (chapter 4, steps 16-17) and G file sizes ("between 2 and 32 words").
inline constexpr int kSm1MaxM0Words = 800;
inline constexpr int kSm1MaxM1Words = 400;
inline constexpr int kSm1MinGWords = 2;
inline constexpr int kSm1MaxGWords = 32;

enum class Sm1Mode : std::uint8_t { Basic, Enhanced };

// The per-channel "Fault/Program State" DIP switch setting (chapter 2). The numeric value is the
// channel's two switches as they read in M1:e.000 (first switch = low bit, 1 = on); the manual's
// switch pictures are lost, so this encoding is a decision (docs/1203-sm1.md).
enum class Sm1FaultState : std::uint8_t { FaultDevice = 0, ZeroData = 1, HoldLastState = 2, SafeState = 3 };

struct Sm1Config {
  int slot = 0;
  Sm1Mode mode = Sm1Mode::Enhanced;
  std::array<Sm1FaultState, kSm1Channels> fault_state{};  // all "fault SCANport device" (default)
  std::vector<std::uint16_t> g_file;                      // as configured (empty in basic mode)
  int m0_words = 0;                                       // 0 in basic mode
  int m1_words = 0;

  bool enhanced() const { return mode == Sm1Mode::Enhanced; }
  // G file word k, 0 beyond the configured size.
  std::uint16_t g_word(int k) const;
  // M1:e.000: DIP switches 1-8 in bits 0-7 (switches 7 and 8 are reserved, always off).
  std::uint16_t dip_switch_word() const;
};

struct Sm1Finding {
  bool error = true;
  std::string message;
};

// Reads and checks a SLOT line of the 1203-SM1. Findings quote the manual's rule.
Sm1Config decode_sm1_slot(const Program& program, const SlotConfig& slot, std::vector<Sm1Finding>& findings);

// One SCANport device on a channel (bench `drive` node).
struct Sm1DriveSpec {
  std::string name;
  int channel = 1;  // 1-3
  int port = 2;     // the adapter port number the module reads from the device's connector (1-6)
  bool powered = true;
  bool cable = true;
  std::shared_ptr<const scanport::DriveDescription> description;
  SourcePos pos;
};

struct Sm1Bench {
  std::string name;
  std::vector<Sm1DriveSpec> drives;  // at most one per channel
};

// Interprets `scanport NAME slot=N { drive NAME channel=C ... }` (docs/bench-format.md). A drive's
// `file=PATH` (a JSON drive description) is read relative to the directory of `bench_name`.
std::shared_ptr<const Sm1Bench> interpret_sm1_bench(const BenchNode& node, const std::string& bench_name,
                                                    DiagnosticList& diags);

}  // namespace softslc
