// What a 1747-SN bench node describes: the adapters on the RIO link and the modules in their
// chassis (docs/bench-format.md, "1747-SN"). These are immutable descriptions, read once from the
// bench file by interpret_rio_bench(); every scanner built from them starts from the same state.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "instructions/module_catalog.h"
#include "modules/bench/bench.h"
#include "vm/virtual_time.h"

namespace softslc {

enum class RioModuleKind : std::uint8_t { Input, Output, BlockTransfer };

// A BTR source value that changes over virtual time: from `at` on, the module answers `data`.
struct RioBtStep {
  Nanoseconds at = 0;
  std::vector<std::int16_t> data;
};
// Word `word` of the BTR data counts from `from` by `step` every `every` (wrapping at 16 bits).
struct RioBtRamp {
  int word = 0;
  std::int64_t from = 0;
  std::int64_t step = 1;
  Nanoseconds every = milliseconds(100);
};

struct RioModuleSpec {
  std::string name;
  std::string catalog;
  RioModuleKind kind = RioModuleKind::Input;
  int rack = 0;    // as the adapter's chassis numbers it: 0-3, or 8-11 in a complementary chassis
  int group = 0;   // 0-7
  int slot = 0;    // 0 (low byte, or the whole word) or 1 (high byte of an 8-point module)
  int points = 16; // 8, 16 or 32 (discrete)
  Nanoseconds input_delay = 0;   // T_id
  Nanoseconds output_delay = 0;  // T_od
  // Block-transfer modules.
  int length = 64;                // words it sends to a BTR
  int write_length = 64;          // words it expects from a BTW (default: length)
  Nanoseconds response_delay = 0;  // added to the adapter's acknowledge time
  bool responding = true;
  bool failing = false;            // answers every BT with a protocol error (-8)
  std::vector<std::int16_t> data;  // BTR data
  std::vector<RioBtStep> steps;
  std::vector<RioBtRamp> ramps;
  SourcePos pos;
};

struct RioAdapterSpec {
  std::string name;
  std::string catalog;
  int rack = 0;       // 0-3, or 8-11 for a complementary chassis (its DIP switches)
  int group = 0;      // even starting group
  int groups = 8;     // image size in groups (2 = 1/4 logical rack ... 32 = four racks)
  bool complementary = false;
  bool primary_switch = false;   // configured as the primary chassis of a complementary pair
  bool hold_last_state = false;
  Nanoseconds backplane_scan = 0;  // the adapter's chassis scan (T_adp = 2 of them for an ASB)
  Nanoseconds bt_delay = 0;        // block-transfer acknowledge time (T_adp-bt)
  Nanoseconds comm_timeout = milliseconds(100);
  bool online = true;
  int noisy = 0;  // every n-th discrete transfer is corrupted and retried (0 = clean)
  std::vector<RioModuleSpec> modules;
  SourcePos pos;
  int first_word() const { return (rack % 8) * 8 + group; }
};

struct RioScannerBench {
  std::string name;
  bool duplicate_node = false;  // another scanner on the link (fault 64H at Run entry)
  std::vector<RioAdapterSpec> adapters;
};

// Interprets a `scanner NAME slot=N { adapter ... { module ... } }` node; problems are reported
// at their positions in `diags`. `g` is the scanner's decoded G file, used only for warnings
// about adapters it never scans.
std::shared_ptr<const RioScannerBench> interpret_rio_bench(const BenchNode& node, const RioGFile* g,
                                                           DiagnosticList& diags);

}  // namespace softslc
