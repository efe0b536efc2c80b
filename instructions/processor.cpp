#include "instructions/processor.h"

#include <array>
#include <cctype>

namespace softslc {

namespace {

struct CatalogRow {
  std::string_view catalog;
  ProcessorFamily family;
  std::string_view name;
  char latest_series;
  MicroLogixModel micrologix = MicroLogixModel::None;
};

// One row per catalog number softslc recognises.
constexpr std::array kCatalogs{
    CatalogRow{"1747-L20", ProcessorFamily::Fixed, "SLC 500 fixed controller", 'C'},
    CatalogRow{"1747-L30", ProcessorFamily::Fixed, "SLC 500 fixed controller", 'C'},
    CatalogRow{"1747-L40", ProcessorFamily::Fixed, "SLC 500 fixed controller", 'C'},
    CatalogRow{"1747-L511", ProcessorFamily::Slc501, "SLC 5/01", 'C'},
    CatalogRow{"1747-L514", ProcessorFamily::Slc501, "SLC 5/01", 'C'},
    CatalogRow{"1747-L524", ProcessorFamily::Slc502, "SLC 5/02", 'C'},
    CatalogRow{"1747-L531", ProcessorFamily::Slc503, "SLC 5/03", 'C'},
    CatalogRow{"1747-L532", ProcessorFamily::Slc503, "SLC 5/03", 'C'},
    CatalogRow{"1747-L541", ProcessorFamily::Slc504, "SLC 5/04", 'C'},
    CatalogRow{"1747-L542", ProcessorFamily::Slc504, "SLC 5/04", 'C'},
    CatalogRow{"1747-L543", ProcessorFamily::Slc504, "SLC 5/04", 'C'},
    CatalogRow{"1747-L551", ProcessorFamily::Slc505, "SLC 5/05", 'C'},
    CatalogRow{"1747-L552", ProcessorFamily::Slc505, "SLC 5/05", 'C'},
    CatalogRow{"1747-L553", ProcessorFamily::Slc505, "SLC 5/05", 'C'},
    // MicroLogix: RSLogix 500 exports name the bulletin ("START Bul.1766"). A MicroLogix 1500
    // export names the bulletin only; Bul.1764 is taken as the 1764-LRP (the processor with the
    // second serial port and data logging), and 1764-LSP / 1764-LRP may be written to be exact.
    CatalogRow{"Bul.1761", ProcessorFamily::MicroLogix, "MicroLogix 1000", 'A', MicroLogixModel::ML1000},
    CatalogRow{"Bul.1762", ProcessorFamily::MicroLogix, "MicroLogix 1200", 'C', MicroLogixModel::ML1200},
    CatalogRow{"Bul.1763", ProcessorFamily::MicroLogix, "MicroLogix 1100", 'B', MicroLogixModel::ML1100},
    CatalogRow{"Bul.1764", ProcessorFamily::MicroLogix, "MicroLogix 1500", 'C', MicroLogixModel::ML1500LRP},
    CatalogRow{"1764-LSP", ProcessorFamily::MicroLogix, "MicroLogix 1500 LSP", 'C', MicroLogixModel::ML1500LSP},
    CatalogRow{"1764-LRP", ProcessorFamily::MicroLogix, "MicroLogix 1500 LRP", 'C', MicroLogixModel::ML1500LRP},
    CatalogRow{"Bul.1766", ProcessorFamily::MicroLogix, "MicroLogix 1400", 'B', MicroLogixModel::ML1400},
};

bool is_modular_503_or_later(ProcessorFamily f) {
  return f == ProcessorFamily::Slc503 || f == ProcessorFamily::Slc504 || f == ProcessorFamily::Slc505;
}

// The selectable timed interrupt and STD/STE/STS: the SLC 5/02 and later (RM 11-8 availability row:
// not the fixed controllers or the 5/01).
bool slc_has_sti(ProcessorFamily f) { return f == ProcessorFamily::Slc502 || is_modular_503_or_later(f); }

}  // namespace

int ProcessorModel::max_subroutine_depth() const {
  return (family == ProcessorFamily::Fixed || family == ProcessorFamily::Slc501) ? 4 : 8;
}

bool ProcessorModel::has_float_files() const {
  return is_modular_503_or_later(family) || (is_micrologix() && micrologix != MicroLogixModel::ML1000);
}

bool ProcessorModel::has_indirect_addressing() const {
  if (is_modular_503_or_later(family)) return series >= 'C';
  // MicroLogix 1100 Series B: a real controller of that series runs N9:[N7:0] in the fixture
  // rtc_bit_1_live.RSS (its live report shows the indirect MOV and SUB with values), and
  // 1763-RM001 describes indirect addressing as the 1400's 1766-RM001 does. The 1200 and 1500 stay
  // refused until a source says otherwise.
  return micrologix == MicroLogixModel::ML1400 || micrologix == MicroLogixModel::ML1100;
}

bool ProcessorModel::supports(Requirement r) const {
  switch (r) {
    case Requirement::Any: return true;
    case Requirement::BlockTransfer: return is_modular_503_or_later(family) && series >= 'C';
    case Requirement::DeviceNetMessage: return is_modular_503_or_later(family) && series >= 'C' && frn >= 10;
    case Requirement::SlcOneShot: return !is_micrologix_1100_class();
    case Requirement::MicroLogix1100Class: return is_micrologix_1100_class();
    // RM001 marks these with the 5/02 column and later. The MicroLogix controllers have them too
    // (their own reference manuals); issue 16 owns the MicroLogix rows in detail.
    case Requirement::Slc502Up: return family != ProcessorFamily::Fixed && family != ProcessorFamily::Slc501;
    // RM001 4-13 (SCP) and the other 5/03-only rows: OS302 is the Series C operating system, the
    // same condition as BTR/BTW. The MicroLogix 1000 has no floating point, so none of them.
    case Requirement::Os302:
      return (is_modular_503_or_later(family) && series >= 'C') || is_micrologix_1100_class();
    case Requirement::SlcOs302: return is_modular_503_or_later(family) && series >= 'C';
    // RM001G p. 9-1: the PID row marks the 5/02, 5/03, 5/04 and 5/05 (not the fixed controllers or
    // the 5/01). The MicroLogix PID addresses a PD file element (1762/1763/1766-RM001 "Process
    // Control Instruction"), a file type softslc does not have: refused there by name.
    case Requirement::SlcPid:
      return family == ProcessorFamily::Slc502 || is_modular_503_or_later(family);
    // The MicroLogix 1100-1500 keep their STI in the STI function file, which their one-operand STS
    // starts (docs/semantics.md "MicroLogix"); the SLC's two-operand STS and INT stay SLC-only.
    case Requirement::TimedInterrupt:
    case Requirement::SlcInterruptControl: return slc_has_sti(family);
    case Requirement::MicroLogixStiFile: return is_micrologix_1100_class();
    // RM 11-27's availability row marks the 5/02, 5/03, 5/04 and 5/05 for the I/O
    // interrupt; FBC/DDT came with a Series C operating system (RM A-9), the same condition as SCP.
    case Requirement::IoInterrupt: return slc_has_sti(family);
    case Requirement::FileBitCompare: return is_modular_503_or_later(family) && series >= 'C';
    case Requirement::MicroLogixUserInterrupt: return false;
    // MSG and SVC (RM 12-5: the 5/02, 5/03, 5/04 and 5/05 columns; the fixed controllers and the
    // 5/01 answer messages but do not send them). The 5/02 has its own MSG form, which the MicroLogix
    // 1000 shares: read/write, target device, an integer control block of length 7 (1761-6.3 p. 13-13,
    // "Control Block N7:50, Control Block Length 7"; docs/semantics.md "The MicroLogix 1000 MSG").
    case Requirement::SlcMessage502:
      return family == ProcessorFamily::Slc502 || micrologix == MicroLogixModel::ML1000;
    case Requirement::SlcMessage: return is_modular_503_or_later(family);
    // The MicroLogix MSG on an MG element: the controllers with MG files (1762-RM001C p. 21-4, 1763-RM001B
    // p. 347, 1766-RM001A p. 399). The MicroLogix 1000's MSG keeps an integer control block (1761-6.3
    // ch. 13): the SLC 5/02 form, SlcMessage502.
    case Requirement::MicroLogixMessage: return has_message_files();
    case Requirement::SlcCommService: return family == ProcessorFamily::Slc502 || is_modular_503_or_later(family);
    case Requirement::ChannelSelectService: return is_modular_503_or_later(family) || is_micrologix_1100_class();
    case Requirement::MicroLogixPto: return is_micrologix_1100_class() && micrologix != MicroLogixModel::ML1400;
    case Requirement::MicroLogixPtox: return micrologix == MicroLogixModel::ML1400;
    // RM001G p. 7-23 marks the 5/03, 5/04 and 5/05 columns; which operating system brought RPC is not on
    // the page (it "requires RSLogix 500 software, version 7.10 or higher"), so the Series C condition
    // of RHC and TDF (RM A-8) is assumed [U]. 1766-RM001A p. 239 gives the 1400's execution time; the
    // 1100, 1200 and 1500 pages were not reached, so they stay refused.
    case Requirement::ProgramChecksum:
      return (is_modular_503_or_later(family) && series >= 'C') || micrologix == MicroLogixModel::ML1400;
    case Requirement::MicroLogixDataLog: return has_data_logging();
  }
  return false;
}

std::string ProcessorModel::requirement_text(Requirement r) const {
  std::string have = display_name + " (" + catalog + " Series " + std::string(1, series) + " FRN " +
                     std::to_string(frn) + ")";
  switch (r) {
    case Requirement::Any: return {};
    case Requirement::BlockTransfer:
      return "needs SLC 5/03 OS302, SLC 5/04 OS401 or SLC 5/05 OS501 (Series C) or later "
             "(1747-SN manual p. 5-5); this program's processor is " + have;
    case Requirement::DeviceNetMessage:
      return "needs an SLC 5/03, 5/04 or 5/05 with OS Series C FRN 10 or later (1747-SDN manual ch. 8); "
             "this program's processor is " + have;
    case Requirement::SlcOneShot:
      return "with one operand is the SLC 500 and MicroLogix 1000 form; on " + display_name +
             " OSR takes a storage bit and an output bit (1763-RM001 / 1766-RM001 / 1762-RM001 ch. \"Bit "
             "Instructions\"), and the one-operand one-shot is ONS; this program's processor is " + have;
    case Requirement::MicroLogix1100Class:
      return "is a MicroLogix 1100, 1200, 1400 and 1500 instruction (1763-RM001, 1762-RM001, 1766-RM001); this "
             "program's processor is " + have;
    case Requirement::SlcPid:
      if (is_micrologix())
        return "is not available on the " + have + " in softslc: the MicroLogix PID takes a PD file element "
               "(1762/1763/1766-RM001, \"Process Control Instruction\"), and softslc has no PD files; the SLC 5/02-5/05 "
               "PID with an N-file control block is supported (1747-RM001)";
      return "is not available on the " + have + "; it needs " + std::string(requirement_processors(r)) +
             " (1747-RM001G p. 9-1)";
    case Requirement::MicroLogixStiFile:
      return "with one operand (time) is the MicroLogix 1100, 1200, 1400 and 1500 form, which starts the STI function "
             "file (STI:0; 1763-RM001C p. 272); this program's processor is " + have +
             std::string(is_micrologix() ? "" : "; the SLC STS takes a file and a time (1747-RM001 11-16)");
    case Requirement::Slc502Up:
    case Requirement::Os302:
    case Requirement::TimedInterrupt:
    case Requirement::SlcInterruptControl:
      return "is not available on the " + have + "; it needs " + std::string(requirement_processors(r)) +
             " (1747-RM001)";
    case Requirement::IoInterrupt:
      return "is not available on the " + have + "; it needs " + std::string(requirement_processors(r)) +
             " (1747-RM001G p. 11-27)" +
             (is_micrologix() ? "; the MicroLogix controllers have no I/O event interrupt (their UID/UIE act on "
                                "function files)" : "");
    case Requirement::FileBitCompare:
      if (is_micrologix())
        return "is not a MicroLogix instruction (1762/1763/1766-RM001 have no FBC or DDT); it needs " +
               std::string(requirement_processors(r)) + " (1747-RM001G p. 7-18); this program's processor is " + have;
      return "is not available on the " + have + "; it needs " + std::string(requirement_processors(r)) +
             " (1747-RM001G p. 7-18, A-9)";
    case Requirement::MicroLogixUserInterrupt:
      if (is_micrologix())
        return "is the MicroLogix user interrupt instruction (1763-RM001 / 1766-RM001 \"Using Interrupts\"), which acts "
               "on the STI, EII and HSC function files by an interrupt-type operand whose encoding is not in softslc's "
               "sources, so softslc does not simulate it; a program can clear or set the interrupt's UIE bit instead "
               "(docs/semantics.md \"UID, UIE, UIF\")";
      return "is not an SLC 500 instruction: 1747-RM001G chapter 11 has STD/STE/STS and IID/IIE/RPI, and UID/UIE/UIF "
             "belong to the MicroLogix 1100-1500 (1763-RM001, 1766-RM001); this program's processor is " + have;
    case Requirement::SlcOs302:
      if (is_micrologix())
        return "is supported in its SLC 5/03-5/05 form only (1747-RM001 p. 7-15); the MicroLogix form "
               "(1762/1763/1764/1766-RM001) is not supported by softslc: its reference pages (the clock's width "
               "and tick, the operand file types) were not reached (docs/semantics.md \"Free-running clock\"); "
               "this program's processor is " + have;
      return "is not available on the " + have + "; it needs " + std::string(requirement_processors(r)) +
             " (1747-RM001)";
    case Requirement::ChannelSelectService:
      if (family == ProcessorFamily::Slc502)
        return "with a channel select is the SLC 5/03-5/05 and MicroLogix form; the SLC 5/02's SVC takes no operand "
               "(RM 12-41); this program's processor is " + have;
      return "is not available on the " + have + "; it needs " + std::string(requirement_processors(r)) +
             " (1747-RM001G p. 12-41, 1762-RM001C p. 21-26, 1763-RM001B p. 344, 1766-RM001A p. 396)";
    case Requirement::SlcMessage502:
    case Requirement::SlcMessage:
    case Requirement::SlcCommService:
      if (micrologix == MicroLogixModel::ML1000 && r == Requirement::SlcCommService)
        return "is not available on the " + have + ": the project's sources (1761-6.3) give the MicroLogix 1000 no "
               "SVC; its messages are serviced at the end of the scan (docs/semantics.md \"The MicroLogix 1000 MSG\")";
      if (is_micrologix() && r == Requirement::SlcCommService)
        return "takes a channel select on the " + have + " (`SVC 1` services channel 0; 1762-RM001C p. 21-26, "
               "1763-RM001B p. 344, 1766-RM001A p. 396)";
      if (is_micrologix() && has_message_files())
        return "with this operand list is the SLC 500 form; the " + display_name + " MSG works on an MG message "
               "file element (1762-RM001C p. 21-3): MSG MG11:0 READ|WRITE device LOCAL channel data size node "
               "target timeout (docs/semantics.md \"The MicroLogix MSG\"); this program's processor is " + have;
      if (is_micrologix())
        return "with this operand list is the SLC 5/03-5/05 form; the MicroLogix 1000 MSG keeps a 7-word integer "
               "control block (1761-6.3 p. 13-13): MSG READ|WRITE 500CPU|485CIF N7:50 7 data size node target "
               "(docs/semantics.md \"The MicroLogix 1000 MSG\"); this program's processor is " + have;
      if (r == Requirement::SlcMessage502 && is_modular_503_or_later(family))
        return "with 8 operands is the SLC 5/02 form (7-word control block, RM 12-5); the " + display_name +
               " MSG takes 11: READ|WRITE device LOCAL|REMOTE block 14 channel data size node target timeout; "
               "this program's processor is " + have;
      if (r == Requirement::SlcMessage && family == ProcessorFamily::Slc502)
        return "with this operand list is the SLC 5/03-5/05 form; on the SLC 5/02 MSG takes 8 operands (READ|WRITE "
               "device block 7 data size node target, RM 12-5) and SVC none; this program's processor is " + have;
      return "is not available on the " + have + "; it needs " + std::string(requirement_processors(r)) +
             " (1747-RM001G p. 12-5)";
    case Requirement::MicroLogixMessage:
      if (family == ProcessorFamily::MicroLogix)
        return "with an MG element is the MicroLogix 1100-1500 form; the MicroLogix 1000 has no MG file: its MSG "
               "keeps a 7-word integer control block (1761-6.3 p. 13-13): MSG READ|WRITE 500CPU|485CIF N7:50 7 data "
               "size node target (docs/semantics.md \"The MicroLogix 1000 MSG\"); this program's processor is " + have;
      return "with an MG element is the MicroLogix 1100-1500 form (1762-RM001C p. 21-3); the " + display_name +
             " MSG takes an integer control block (1747-RM001G p. 12-5); this program's processor is " + have;
    case Requirement::ProgramChecksum:
      return "is not available on the " + have + "; it needs " + std::string(requirement_processors(r)) +
             " (1747-RM001G p. 7-23, 1766-RM001A p. 239" +
             (is_micrologix() ? "; the MicroLogix 1100, 1200 and 1500 reference pages for RPC were not reached" : "") +
             ")";
    case Requirement::MicroLogixPto:
    case Requirement::MicroLogixPtox:
      return "drives the pulse train output of the " + std::string(requirement_processors(r)) +
             (micrologix == MicroLogixModel::ML1400 ? " (the MicroLogix 1400's is PTOX, 1766-RM001A p. 146)"
              : is_micrologix_1100_class()          ? " (the " + display_name + "'s is PTO, 1763-RM001C p. 128)"
                                                    : "") +
             "; this program's processor is " + have;
    case Requirement::MicroLogixDataLog:
      return "is not available on the " + have + "; data logging needs " + std::string(requirement_processors(r)) +
             " (AG-UM008C p. 3-58, 1766-RM001A p. 518)";
  }
  return {};
}

std::string_view requirement_processors(Requirement r) {
  switch (r) {
    case Requirement::Any: return "all SLC 500 processors";
    case Requirement::BlockTransfer: return "SLC 5/03 OS302, SLC 5/04 OS401, SLC 5/05 OS501 (Series C) or later";
    case Requirement::DeviceNetMessage: return "SLC 5/03, 5/04, 5/05 OS Series C FRN 10 or later";
    case Requirement::Slc502Up: return "SLC 5/02, 5/03, 5/04, 5/05, MicroLogix";
    case Requirement::Os302: return "SLC 5/03 OS302 (Series C), SLC 5/04 OS401, SLC 5/05, MicroLogix 1100/1200/1400/1500";
    case Requirement::SlcOs302: return "SLC 5/03 OS302 (Series C), SLC 5/04 OS401, SLC 5/05";
    case Requirement::SlcOneShot: return "SLC 500 processors, MicroLogix 1000";
    case Requirement::MicroLogix1100Class: return "MicroLogix 1100, 1200, 1400, 1500";
    case Requirement::SlcPid: return "SLC 5/02, 5/03, 5/04, 5/05";
    case Requirement::TimedInterrupt: return "SLC 5/02, 5/03, 5/04, 5/05 (the MicroLogix 1100-1500 STS takes the time only)";
    case Requirement::SlcInterruptControl: return "SLC 5/02, 5/03, 5/04, 5/05";
    case Requirement::MicroLogixStiFile: return "MicroLogix 1100, 1200, 1400, 1500";
    case Requirement::IoInterrupt: return "SLC 5/02, 5/03, 5/04, 5/05";
    case Requirement::FileBitCompare: return "SLC 5/03 OS302 (Series C), SLC 5/04 OS401, SLC 5/05";
    case Requirement::MicroLogixUserInterrupt:
      return "none yet (MicroLogix 1100-1500 once their EII/HSC function files are simulated)";
    case Requirement::SlcMessage502: return "SLC 5/02, MicroLogix 1000 (the 5/03-5/05 form has 11 operands)";
    case Requirement::SlcMessage: return "SLC 5/03, 5/04, 5/05";
    case Requirement::MicroLogixMessage: return "MicroLogix 1100, 1200, 1400, 1500";
    case Requirement::SlcCommService: return "SLC 5/02, 5/03, 5/04, 5/05";
    case Requirement::ChannelSelectService: return "SLC 5/03, 5/04, 5/05, MicroLogix 1100, 1200, 1400, 1500";
    case Requirement::MicroLogixPto: return "MicroLogix 1100, 1200, 1500";
    case Requirement::MicroLogixPtox: return "MicroLogix 1400";
    case Requirement::ProgramChecksum: return "SLC 5/03 OS302 (Series C), SLC 5/04 OS401, SLC 5/05, MicroLogix 1400";
    case Requirement::MicroLogixDataLog: return "MicroLogix 1100, 1400, 1500 LRP";
  }
  return {};
}

std::string ProcessorModel::timing_key() const {
  switch (family) {
    case ProcessorFamily::Slc502: return series <= 'B' ? "5/02B" : "5/02C";
    case ProcessorFamily::Slc503: return "5/03";
    case ProcessorFamily::Slc504: return "5/04";
    case ProcessorFamily::Slc505: return "5/05";
    case ProcessorFamily::MicroLogix:
      switch (micrologix) {
        case MicroLogixModel::ML1000: return "ML1000";
        case MicroLogixModel::ML1100: return "ML1100";
        case MicroLogixModel::ML1200: return "ML1200";
        case MicroLogixModel::ML1400: return "ML1400";
        case MicroLogixModel::ML1500LSP:
        case MicroLogixModel::ML1500LRP: return "ML1500";
        case MicroLogixModel::None: return {};
      }
      return {};
    default: return {};
  }
}

std::string ProcessorModel::embedded_io_catalog() const {
  // A fixed controller's row is the catalog prefix its suffixes share (1747-L20A, -L20B ...: "1747-L20").
  if (family == ProcessorFamily::Fixed) return catalog.substr(0, std::string_view("1747-L20").size());
  switch (micrologix) {
    case MicroLogixModel::None: return {};
    case MicroLogixModel::ML1000: return "Bul.1761";
    case MicroLogixModel::ML1100: return "Bul.1763";
    case MicroLogixModel::ML1200: return "Bul.1762";
    case MicroLogixModel::ML1400: return "Bul.1766";
    case MicroLogixModel::ML1500LSP:
    case MicroLogixModel::ML1500LRP: return "Bul.1764";
  }
  return {};
}

std::optional<ProcessorModel> representative_processor(std::string_view key) {
  static constexpr std::pair<std::string_view, std::string_view> kKeys[] = {
      {"5/02B", "1747-L524"}, {"5/02C", "1747-L524"}, {"5/03", "1747-L532"}, {"5/04", "1747-L542"},
      {"5/05", "1747-L552"},  {"ML1000", "Bul.1761"}, {"ML1100", "Bul.1763"}, {"ML1200", "Bul.1762"},
      {"ML1400", "Bul.1766"}, {"ML1500", "1764-LRP"}};
  for (const auto& [k, catalog] : kKeys)
    if (k == key) return resolve_processor(catalog, key == "5/02B" ? std::optional<char>('B') : std::nullopt);
  return std::nullopt;
}

std::optional<ProcessorModel> resolve_processor(std::string_view catalog, std::optional<char> series,
                                                std::optional<int> frn) {
  for (const auto& row : kCatalogs) {
    // Fixed controllers carry a variable suffix (1747-L20A, -L30B, ...): match on the prefix.
    bool match = row.family == ProcessorFamily::Fixed ? catalog.substr(0, row.catalog.size()) == row.catalog
                                                      : catalog == row.catalog;
    if (!match) continue;
    ProcessorModel m;
    m.catalog = std::string(catalog);
    m.family = row.family;
    m.display_name = std::string(row.name);
    m.micrologix = row.micrologix;
    m.series = series.value_or(row.latest_series);
    m.frn = frn.value_or(11);
    return m;
  }
  return std::nullopt;
}

std::optional<ProcessorModel> parse_processor_spec(std::string_view spec, std::string& error) {
  const auto colon = spec.find(':');
  const std::string_view catalog = spec.substr(0, colon);
  std::optional<char> series;
  if (colon != std::string_view::npos) {
    if (spec.size() != colon + 2 || !std::isupper(static_cast<unsigned char>(spec[colon + 1]))) {
      error = std::string(spec) + ": write CATALOG or CATALOG:SERIES, for example 1747-L524:B";
      return std::nullopt;
    }
    series = spec[colon + 1];
  }
  auto m = resolve_processor(catalog, series);
  if (!m) error = std::string(spec) + ": unknown catalog; known: " + std::string(known_processor_catalogs());
  return m;
}

std::string_view known_processor_catalogs() {
  return "1747-L511 -L514 (5/01), 1747-L524 (5/02), 1747-L531 -L532 (5/03), 1747-L541 -L542 -L543 (5/04), "
         "1747-L551 -L552 -L553 (5/05), 1747-L20x/L30x/L40x (fixed), Bul.1761 (MicroLogix 1000), Bul.1763 (1100), "
         "Bul.1762 (1200), Bul.1766 (1400), Bul.1764 1764-LSP 1764-LRP (1500)";
}

}  // namespace softslc
