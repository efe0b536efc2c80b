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
  MicroLogix,  // Bul.1761/1762/1763/1764/1766: which one is ProcessorModel::micrologix
};

// Which MicroLogix controller (None on the SLC 500 processors). The instruction set reference
// manuals differ per controller (1761-6.3 for the 1000, 1763-RM001 for the 1100, 1762-RM001 for
// the 1200 and 1764-RM001 for the 1500, 1766-RM001 for the 1400), and so do the rules below.
enum class MicroLogixModel : std::uint8_t { None, ML1000, ML1100, ML1200, ML1400, ML1500LSP, ML1500LRP };

struct ProcessorModel {
  std::string catalog;       // as written, e.g. "1747-L532" or "Bul.1766"
  ProcessorFamily family = ProcessorFamily::Slc505;
  char series = 'C';         // hardware/OS series letter
  int frn = 11;              // firmware revision number
  std::string display_name;  // "SLC 5/03" etc.
  MicroLogixModel micrologix = MicroLogixModel::None;

  bool is_micrologix() const { return micrologix != MicroLogixModel::None; }
  // MicroLogix 1100, 1200, 1400 and 1500: the controllers whose instruction set has ONS, the
  // two-operand OSR/OSF, the 0.001 s time base, L files and the function files (RTC, HSC, ...).
  bool is_micrologix_1100_class() const { return is_micrologix() && micrologix != MicroLogixModel::ML1000; }
  // The HSC function file's elements (high-speed counters): 1 on the MicroLogix 1100 (its .RSS
  // function-file record is one element of 18 words in every fixture), 1 on the 1200 and 2 on the
  // 1500 (RAC's counter number, 1762-RM001C p. 5-27: HSC1 "MicroLogix 1500 only"), 6 on the 1400
  // (its RSLogix export writes HSC0:0 to HSC0:5, 59-BSGS.SLC); 0 elsewhere (the MicroLogix 1000's
  // HSC is the C5:0 counter, not simulated).
  int hsc_count() const {
    switch (micrologix) {
      case MicroLogixModel::ML1100: case MicroLogixModel::ML1200: return 1;
      case MicroLogixModel::ML1400: return 6;
      case MicroLogixModel::ML1500LSP: case MicroLogixModel::ML1500LRP: return 2;
      default: return 0;
    }
  }
  // The EII function file's elements (event input interrupts): 4 on the MicroLogix 1100
  // (1763-RM001C p. 272: "four EII elements", EII:0 to EII:3) and on the 1200 and 1500 (the
  // priority list of 1762-RM001C p. 18-4 names Event Interrupts 0 to 3), 8 on the 1400 (its
  // RSLogix export writes EII0:0 to EII0:7, 59-BSGS.SLC); 0 elsewhere.
  int eii_count() const {
    if (!is_micrologix_1100_class()) return 0;
    return micrologix == MicroLogixModel::ML1400 ? 8 : 4;
  }
  // Data logging (DLG, the DLS file, DATALOG queues): the MicroLogix 1100 and 1500 LRP (AG-UM008C
  // p. 3-58) and the 1400 (1766-RM001A p. 518).
  bool has_data_logging() const {
    return micrologix == MicroLogixModel::ML1100 || micrologix == MicroLogixModel::ML1400 ||
           micrologix == MicroLogixModel::ML1500LRP;
  }
  // Bytes of data log memory: 128 K on the 1100 (1763-RM001C p. 433) and the 1400 (1766-RM001A
  // p. 518), 48 K on the 1500 LRP (AG-UM008C p. 3-58); 0 elsewhere.
  std::int32_t data_log_bytes() const {
    if (!has_data_logging()) return 0;
    return (micrologix == MicroLogixModel::ML1500LRP ? 48 : 128) * 1024;
  }
  // The longest formatted record: 80 characters on the 1100 and 1500 LRP (1763-RM001C p. 435,
  // AG-UM008C p. 3-61), 109 on the 1400 (1766-RM001A p. 519).
  int data_log_max_characters() const { return micrologix == MicroLogixModel::ML1400 ? 109 : 80; }
  // L (32-bit long integer) files: MicroLogix 1100, 1200, 1400, 1500 (not the 1000, not SLC).
  bool has_long_files() const { return is_micrologix_1100_class(); }
  // MG (message) files, the MicroLogix MSG's 25-word elements: MicroLogix 1100, 1200, 1400 and 1500
  // (1763-RM001B p. 347, 1762-RM001C p. 21-4, 1766-RM001A p. 399); the SLC's MSG uses an N-file
  // control block instead, and the MicroLogix 1000 has no MSG file in its manual (1761-6.3).
  bool has_message_files() const { return is_micrologix_1100_class(); }
  // RI (routing information) files, one 20-word element per channel 1 Ethernet MSG: the MicroLogix
  // 1100 and 1400, whose channel 1 is Ethernet (1763-RM001B p. 384, 1766-RM001A p. 435).
  bool has_routing_files() const {
    return micrologix == MicroLogixModel::ML1100 || micrologix == MicroLogixModel::ML1400;
  }
  // The 0.001 s timer time base: MicroLogix 1100/1200/1400/1500 (the SLC and the MicroLogix
  // 1000 have 0.01 s and 1.0 s only).
  bool has_millisecond_timebase() const { return is_micrologix_1100_class(); }

  // The S:4 free-running clock's tick: 10 ms on the SLC 500 and the MicroLogix 1000, 100 us on
  // the MicroLogix 1100, 1200 and 1500 (1763-RM001C p. 476, "S:4 Free Running Clock Comparison");
  // the 1400 is taken to be the 1100's (docs/semantics.md, decision).
  std::int64_t free_running_clock_tick_ns() const { return is_micrologix_1100_class() ? 100'000 : 10'000'000; }

  // Subroutine nesting limit: 8 on 5/02 and later, 4 on fixed controllers and 5/01 (RM 6-4).
  int max_subroutine_depth() const;
  // F files and float math: SLC 5/03 OS301 and later, 5/04, 5/05, MicroLogix 1200/1400/1500.
  bool has_float_files() const;
  // Indirect addressing N7:[N10:1]: 5/03 OS302, 5/04 OS401, 5/05, MicroLogix 1100 and 1400.
  bool has_indirect_addressing() const;
  // Whether the processor implements an instruction row's Requirement.
  bool supports(Requirement r) const;
  // Why it does not, for diagnostics ("BTR needs SLC 5/03 OS302 ... ; this program's processor is ...").
  std::string requirement_text(Requirement r) const;
  // Key of this processor's column in the M0/M1 access-time tables and timing profiles:
  // "5/02B", "5/02C", "5/03", "5/04", "5/05", and "ML1000", "ML1100", "ML1200", "ML1400",
  // "ML1500" for the MicroLogix controllers; empty for the fixed controllers and the 5/01.
  std::string timing_key() const;
  // The module catalog row of this controller's embedded I/O (slot 0): "Bul.1766", "1747-L40"
  // etc.; empty on the modular SLC 500 processors, whose slot 0 holds only the processor.
  std::string embedded_io_catalog() const;
};

// A processor that a timing key stands for (the built-in profile of that key must have a figure
// for every instruction this processor supports). nullopt for an unknown key.
std::optional<ProcessorModel> representative_processor(std::string_view timing_key);

// Resolves a catalog number plus optional series/FRN. Returns nullopt for unknown catalogs.
std::optional<ProcessorModel> resolve_processor(std::string_view catalog, std::optional<char> series = std::nullopt,
                                                std::optional<int> frn = std::nullopt);

// Resolves a processor as users write it on a command line or in a test file: "CATALOG" or
// "CATALOG:SERIES" (1747-L524:B). On failure sets `error` to why, starting with the text.
std::optional<ProcessorModel> parse_processor_spec(std::string_view spec, std::string& error);

// Which processors have an instruction row's Requirement, in words (`softslc instructions`, diagnostics).
std::string_view requirement_processors(Requirement r);

// The catalog numbers accepted, for help texts and diagnostics.
std::string_view known_processor_catalogs();

}  // namespace softslc
