// Processor models: what the START line's catalog number means for the rest of softslc.
//
// A ProcessorModel is a plain value resolved once when a program loads. It answers the
// questions the checker (which instructions and file types exist), the VM (subroutine nesting
// depth) and the timing model (which row of the M0/M1 access-time table) ask. Series and FRN
// are optional in the export; when absent softslc assumes the latest series the catalog was
// sold in (documented in docs/program-format.md), because that is what an engineer testing a
// program today most likely has.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "instructions/instruction_table.h"

namespace softslc {

enum class ProcessorFamily : std::uint8_t {
  Fixed,       // fixed-I/O SLC 500 controllers (1747-L20x/L30x/L40x)
  Slc501,      // 1747-L511, -L514
  Slc502,      // 1747-L524
  Slc503,      // 1747-L531, -L532
  Slc504,      // 1747-L541, -L542, -L543
  Slc505,      // 1747-L551, -L552, -L553
  MicroLogix,  // Bul.1761/1762/1763/1764/1766 (loaded so their exports can be checked and run)
};

struct ProcessorModel {
  std::string catalog;       // as written, e.g. "1747-L532" or "Bul.1766"
  ProcessorFamily family = ProcessorFamily::Slc505;
  char series = 'C';         // hardware/OS series letter
  int frn = 11;              // firmware revision number
  std::string display_name;  // "SLC 5/03" etc.

  // Subroutine nesting limit: 8 on 5/02 and later, 4 on fixed controllers and 5/01 (RM 6-4).
  int max_subroutine_depth() const;
  // F files and float math: SLC 5/03 OS301 and later, 5/04, 5/05, MicroLogix 1200/1400/1500.
  bool has_float_files() const;
  // Indirect addressing N7:[N10:1]: 5/03 OS302, 5/04 OS401, 5/05 (and MicroLogix 1400).
  bool has_indirect_addressing() const;
  // Whether the processor implements an instruction row's Requirement.
  bool supports(Requirement r) const;
  // Why it does not, for diagnostics ("BTR needs SLC 5/03 OS302 ... ; this program's processor is ...").
  std::string requirement_text(Requirement r) const;
  // Key of this processor's column in the M0/M1 access-time tables and timing profiles:
  // "5/02B", "5/02C", "5/03", "5/04", "5/05"; empty for processors without M files.
  std::string timing_key() const;
};

// Resolves a catalog number plus optional series/FRN. Returns nullopt for unknown catalogs.
std::optional<ProcessorModel> resolve_processor(std::string_view catalog, std::optional<char> series = std::nullopt,
                                                std::optional<int> frn = std::nullopt);

// Which processors have an instruction row's Requirement, in words (`softslc instructions`, diagnostics).
std::string_view requirement_processors(Requirement r);

// The catalog numbers accepted, for help texts and diagnostics.
std::string_view known_processor_catalogs();

}  // namespace softslc
