#include "parser/address.h"

#include <array>
#include <span>

namespace softslc {

namespace {

struct NamedBit {
  FileType type;
  std::string_view name;
  int bit;
};

// Status bits of T/C/R word 0 (RM 1-6, 1-8; PT1 4-9).
constexpr std::array kNamedBits{
    NamedBit{FileType::Timer, "EN", 15},   NamedBit{FileType::Timer, "TT", 14},
    NamedBit{FileType::Timer, "DN", 13},   NamedBit{FileType::Counter, "CU", 15},
    NamedBit{FileType::Counter, "CD", 14}, NamedBit{FileType::Counter, "DN", 13},
    NamedBit{FileType::Counter, "OV", 12}, NamedBit{FileType::Counter, "UN", 11},
    NamedBit{FileType::Counter, "UA", 10}, NamedBit{FileType::Control, "EN", 15},
    NamedBit{FileType::Control, "EU", 14}, NamedBit{FileType::Control, "DN", 13},
    NamedBit{FileType::Control, "EM", 12}, NamedBit{FileType::Control, "ER", 11},
    NamedBit{FileType::Control, "UL", 10}, NamedBit{FileType::Control, "IN", 9},
    NamedBit{FileType::Control, "FD", 8},
};

struct NamedWord {
  FileType type;
  std::string_view name;
  int word;
};

constexpr std::array kNamedWords{
    NamedWord{FileType::Timer, "PRE", 1},   NamedWord{FileType::Timer, "ACC", 2},
    NamedWord{FileType::Counter, "PRE", 1}, NamedWord{FileType::Counter, "ACC", 2},
    NamedWord{FileType::Control, "LEN", 1}, NamedWord{FileType::Control, "POS", 2},
};

constexpr std::array<std::string_view, kFunctionFileCount> kFunctionFileNames{
    "RTC", "HSC", "PTOX", "PWMX", "STI", "EII", "BHI", "MMI", "DAT", "TPI", "IOS", "LCD", "PTO", "DLS", "CS0", "CS1", "CS2"};

// The RTC element's named words and bits (1762-RM001C p. 3-3 Table 3.2; see rtc:: in address.h).
constexpr std::array<std::string_view, rtc::kDayOfWeek + 1> kRtcWords{"YR", "MON", "DAY", "HR", "MIN", "SEC", "DOW"};

struct FunctionBit {
  std::string_view name;
  int word;
  int bit;
};
constexpr std::array kRtcBits{FunctionBit{"DS", rtc::kStatusWord, rtc::kDisabledBit},
                              FunctionBit{"BL", rtc::kStatusWord, rtc::kBatteryLowBit}};

bool is_rtc(int id) { return id == static_cast<int>(FunctionFile::RTC); }

// The STI element's named words and bits (see sti:: in address.h). `writable` is the manual's
// "User Program Access" (1763-RM001C pp. 270, 272 for UIX, UIE, UIL, ED, SPM; the others [U]).
struct FunctionSubElement {
  std::string_view name;
  int word;
  int bit;  // -1: a word
  bool writable;
};
constexpr std::array kStiSubElements{
    FunctionSubElement{"PFN", sti::kProgramFile, -1, false},  FunctionSubElement{"ER", sti::kErrorCode, -1, false},
    FunctionSubElement{"SPM", sti::kSetPoint, -1, true},      FunctionSubElement{"UIX", sti::kBits, sti::kExecutingBit, false},
    FunctionSubElement{"UIE", sti::kBits, sti::kEnableBit, true}, FunctionSubElement{"UIL", sti::kBits, sti::kLostBit, true},
    FunctionSubElement{"UIP", sti::kBits, sti::kPendingBit, false},
    FunctionSubElement{"TIE", sti::kBits, sti::kTimedEnableBit, true},
    FunctionSubElement{"AS", sti::kBits, sti::kAutoStartBit, false}, FunctionSubElement{"ED", sti::kBits, sti::kErrorBit, false},
};

bool is_sti(int id) { return id == static_cast<int>(FunctionFile::STI); }

// The EII element's named words and bits (see eii:: in address.h). `writable` as read on
// 1763-RM001C p. 275 (UIX read only, UIE and UIL read/write) and 1762-RM001C p. 18-19 (UIP read
// only); the others [U] (docs/semantics.md "The EII function file").
constexpr std::array kEiiSubElements{
    FunctionSubElement{"PFN", eii::kProgramFile, -1, false}, FunctionSubElement{"ER", eii::kErrorCode, -1, false},
    FunctionSubElement{"IS", eii::kInputSelect, -1, false},
    FunctionSubElement{"UIX", eii::kBits, eii::kExecutingBit, false},
    FunctionSubElement{"UIE", eii::kBits, eii::kEnableBit, true},
    FunctionSubElement{"UIL", eii::kBits, eii::kLostBit, true},
    FunctionSubElement{"UIP", eii::kBits, eii::kPendingBit, false},
    FunctionSubElement{"EIE", eii::kBits, eii::kEventEnableBit, true},
    FunctionSubElement{"AS", eii::kBits, eii::kAutoStartBit, false},
    FunctionSubElement{"ED", eii::kBits, eii::kErrorBit, false},
    FunctionSubElement{"ES", eii::kBits, eii::kEdgeSelectBit, false},
};

bool is_eii(int id) { return id == static_cast<int>(FunctionFile::EII); }

// The PTO/PTOX element's named words and bits (see pto:: in address.h). `writable` is the manual's
// "User Program Access": read on pages for DN, DS, RS, AS, RP, IS, ED, NS, OFS, TOP, OPP
// (1762-RM001C pp. 6-9..6-12, 1763-RM001C pp. 136-140, 1766-RM001A p. 146); the others [U]
// (docs/semantics.md "The PTO function file"; CS is written by an OTE in 2080-MOT-HSC.RSS).
bool is_pulse_train(int id) { return id == static_cast<int>(FunctionFile::PTO) || id == static_cast<int>(FunctionFile::PTOX); }
const pto::Layout& pulse_train_layout(int id) { return id == static_cast<int>(FunctionFile::PTOX) ? pto::kPtox : pto::kPto; }
struct PulseTrainSubElement {
  std::string_view name;
  int word;  // pto::kOutput..kErrorCode, or -1 - n for the layout's n-th frequency/count word
  int bit;
  bool writable;
};
constexpr std::array kPulseTrainSubElements{
    PulseTrainSubElement{"OUT", pto::kOutput, -1, false},
    PulseTrainSubElement{"ER", pto::kErrorCode, -1, false},
    PulseTrainSubElement{"OF", -1, -1, true},
    PulseTrainSubElement{"OFS", -2, -1, false},
    PulseTrainSubElement{"JF", -3, -1, true},
    PulseTrainSubElement{"TOP", -4, -1, true},
    PulseTrainSubElement{"OPP", -5, -1, false},
    PulseTrainSubElement{"ADP", -6, -1, true},
    PulseTrainSubElement{"DN", pto::kBits, pto::kDoneBit, false},
    PulseTrainSubElement{"DS", pto::kBits, pto::kDecelBit, false},
    PulseTrainSubElement{"RS", pto::kBits, pto::kRunBit, false},
    PulseTrainSubElement{"AS", pto::kBits, pto::kAccelBit, false},
    PulseTrainSubElement{"RP", pto::kBits, pto::kRampBit, true},
    PulseTrainSubElement{"IS", pto::kBits, pto::kIdleBit, false},
    PulseTrainSubElement{"ED", pto::kBits, pto::kErrorBit, false},
    PulseTrainSubElement{"NS", pto::kBits, pto::kNormalBit, false},
    PulseTrainSubElement{"EH", pto::kBits, pto::kHardStopBit, true},
    PulseTrainSubElement{"EN", pto::kBits, pto::kEnableBit, false},
    PulseTrainSubElement{"CS", pto::kBits, pto::kControlStopBit, true},
    PulseTrainSubElement{"JP", pto::kBits, pto::kJogPulseBit, true},
    PulseTrainSubElement{"JPS", pto::kBits, pto::kJogPulseStatusBit, false},
    PulseTrainSubElement{"JC", pto::kBits, pto::kJogContinuousBit, true},
    PulseTrainSubElement{"JCS", pto::kBits, pto::kJogContinuousStatusBit, false},
};
// A named bit of a sub-element table (STI, HSC, PTO): sets `word` and `bit`.
template <typename Table>
bool named_bit(const Table& table, std::string_view name, int& word, int& bit) {
  for (const auto& e : table)
    if (e.bit >= 0 && e.name == name) {
      word = e.word;
      bit = e.bit;
      return true;
    }
  return false;
}

// The word a sub-element starts at, in the file's layout.
int pulse_train_word(int id, const PulseTrainSubElement& e) {
  if (e.word >= 0) return e.word;
  const pto::Layout& l = pulse_train_layout(id);
  const int words[] = {l.frequency, l.frequency_status, l.jog_frequency, l.total, l.produced, l.accel_decel};
  return words[-e.word - 1];
}
// How many words a word sub-element takes: TOP, OPP, ADP 2; OF, OFS, JF 2 on the PTOX; else 1.
int pulse_train_width(int id, const PulseTrainSubElement& e) {
  if (e.word >= 0) return 1;
  return e.word <= -4 || pulse_train_layout(id).long_frequencies ? 2 : 1;
}

// The HSC element's named words and bits (see hsc:: in address.h). `writable` as read on
// 1762-RM001C pp. 5-10, 5-13, 5-23, 5-24 for LPI, LPR, UFI, OF, OVF, OMB; the others [U].
constexpr std::array kHscSubElements{
    FunctionSubElement{"PFN", hsc::kProgramFile, -1, false}, FunctionSubElement{"ER", hsc::kErrorCode, -1, false},
    FunctionSubElement{"MOD", hsc::kMode, -1, false},        FunctionSubElement{"ACC", hsc::kAccumulator, -1, true},
    FunctionSubElement{"HIP", hsc::kHighPreset, -1, true},   FunctionSubElement{"LOP", hsc::kLowPreset, -1, true},
    FunctionSubElement{"OVF", hsc::kOverflow, -1, true},     FunctionSubElement{"UNF", hsc::kUnderflow, -1, true},
    FunctionSubElement{"OMB", hsc::kOutputMask, -1, false},  FunctionSubElement{"HPO", hsc::kHighOutput, -1, true},
    FunctionSubElement{"LPO", hsc::kLowOutput, -1, true},
    FunctionSubElement{"UIX", hsc::kBits, hsc::kExecutingBit, false},
    FunctionSubElement{"UIE", hsc::kBits, hsc::kEnableBit, true},
    FunctionSubElement{"UIL", hsc::kBits, hsc::kLostBit, true},
    FunctionSubElement{"UIP", hsc::kBits, hsc::kPendingBit, false},
    FunctionSubElement{"FE", hsc::kBits, hsc::kFunctionEnabledBit, true},
    FunctionSubElement{"AS", hsc::kBits, hsc::kAutoStartBit, false},
    FunctionSubElement{"ED", hsc::kBits, hsc::kErrorBit, false},
    FunctionSubElement{"SP", hsc::kBits, hsc::kSetParametersBit, true},
    FunctionSubElement{"CE", hsc::kBits, hsc::kCountingEnabledBit, true},
    FunctionSubElement{"LPI", hsc::kBits, hsc::kLowInterruptBit, true},
    FunctionSubElement{"UFI", hsc::kBits, hsc::kUnderflowInterruptBit, true},
    FunctionSubElement{"HPI", hsc::kBits, hsc::kHighInterruptBit, true},
    FunctionSubElement{"OFI", hsc::kBits, hsc::kOverflowInterruptBit, true},
    FunctionSubElement{"LPM", hsc::kStatus, hsc::kLowMaskBit, true},
    FunctionSubElement{"HPM", hsc::kStatus, hsc::kHighMaskBit, true},
    FunctionSubElement{"UFM", hsc::kStatus, hsc::kUnderflowMaskBit, true},
    FunctionSubElement{"OFM", hsc::kStatus, hsc::kOverflowMaskBit, true},
    FunctionSubElement{"LPR", hsc::kStatus, hsc::kLowReachedBit, false},
    FunctionSubElement{"HPR", hsc::kStatus, hsc::kHighReachedBit, false},
    FunctionSubElement{"UF", hsc::kStatus, hsc::kUnderflowBit, true},
    FunctionSubElement{"OF", hsc::kStatus, hsc::kOverflowBit, true},
    FunctionSubElement{"DIR", hsc::kStatus, hsc::kDirectionBit, false},
    FunctionSubElement{"MD", hsc::kStatus, hsc::kModeDoneBit, true},
    FunctionSubElement{"CD", hsc::kStatus, hsc::kCountDownBit, false},
    FunctionSubElement{"CU", hsc::kStatus, hsc::kCountUpBit, false},
};

bool is_hsc(int id) { return id == static_cast<int>(FunctionFile::HSC); }

// The DLS element's named words and bits (see dls:: in address.h). OV is cleared by the user ("Once
// set, the OV bit remains set until you clear (0) it", AG-UM008C p. 3-65); EN, DN, FSZ and RST are the
// controller's [U] (docs/semantics.md "Data logging").
constexpr std::array kDlsSubElements{
    FunctionSubElement{"FSZ", dls::kFileSize, -1, false}, FunctionSubElement{"RST", dls::kRecordsStored, -1, false},
    FunctionSubElement{"EN", dls::kBits, dls::kEnableBit, false}, FunctionSubElement{"DN", dls::kBits, dls::kDoneBit, false},
    FunctionSubElement{"OV", dls::kBits, dls::kOverflowBit, true},
};

bool is_dls(int id) { return id == static_cast<int>(FunctionFile::DLS); }

// The communications status bits of CS0:4 (1762-RM001C p. 21-27 Table 21.5): all read only. Their word
// is the element's only one; only element 4 has them (to_string and the checker see to that).
constexpr std::array kCsSubElements{
    FunctionSubElement{"ICP", 0, cs::kIncomingCommandBit, false}, FunctionSubElement{"MRP", 0, cs::kReplyPendingBit, false},
    FunctionSubElement{"MCP", 0, cs::kCommandPendingBit, false}, FunctionSubElement{"CAB", 0, cs::kActiveBit, false},
};

bool is_cs(int id) {
  return id >= static_cast<int>(FunctionFile::CS0) && id <= static_cast<int>(FunctionFile::CS2);
}

// The table of named sub-elements of the STI, the EII, the HSC, the DLS or a CS file; empty for the others.
std::span<const FunctionSubElement> sub_elements(int id) {
  if (is_sti(id)) return kStiSubElements;
  if (is_eii(id)) return kEiiSubElements;
  if (is_hsc(id)) return kHscSubElements;
  if (is_dls(id)) return kDlsSubElements;
  if (is_cs(id)) return kCsSubElements;
  return {};
}
bool has_sub_elements(int id) { return !sub_elements(id).empty(); }

}  // namespace

std::string_view function_file_name(int id) {
  if (id < 0 || id >= kFunctionFileCount) return "?";
  return kFunctionFileNames[static_cast<std::size_t>(id)];
}

int function_file_id(std::string_view name) {
  if (name == "DLS0") name = "DLS";  // the manuals' spelling of the one DLS file
  if (name == "CS") name = "CS0";  // CS:4/MCP, a shorthand for channel 0's
  for (std::size_t i = 0; i < kFunctionFileNames.size(); ++i)
    if (kFunctionFileNames[i] == name) return static_cast<int>(i);
  return -1;
}

bool function_file_simulated(int id) { return is_rtc(id) || has_sub_elements(id) || is_pulse_train(id); }
int function_file_elements(int id) {
  if (is_pulse_train(id)) return id == static_cast<int>(FunctionFile::PTOX) ? pto::kPtoxElements : pto::kPtoElements;
  return is_rtc(id) || is_sti(id) ? 1 : is_hsc(id) ? 6 : is_eii(id) ? eii::kMaxElements : is_dls(id) ? dls::kMaxQueues
         : is_cs(id) ? cs::kElements : 0;
}
int function_file_words_per_element(int id) {
  if (is_pulse_train(id)) return pulse_train_layout(id).words;
  return is_rtc(id) ? rtc::kWords : is_sti(id) ? sti::kWords : is_eii(id) ? eii::kWords : is_hsc(id) ? hsc::kWords
         : is_dls(id) ? dls::kWords : is_cs(id) ? 1 : 0;
}

bool is_pulse_train_file(int id) { return is_pulse_train(id); }
bool is_data_log_status_file(int id) { return is_dls(id); }
int communications_status_channel(int id) { return is_cs(id) ? id - static_cast<int>(FunctionFile::CS0) : -1; }

bool function_word_is_long(int id, int word) {
  if (is_hsc(id)) return hsc::is_long_word(word);
  if (!is_pulse_train(id)) return false;
  for (const auto& e : kPulseTrainSubElements)
    if (e.bit < 0 && pulse_train_word(id, e) == word) return pulse_train_width(id, e) == 2;
  return false;
}

int function_word_number(int id, std::string_view name) {
  if (is_pulse_train(id)) {
    for (const auto& e : kPulseTrainSubElements)
      if (e.bit < 0 && e.name == name) return pulse_train_word(id, e);
    return -1;
  }
  if (has_sub_elements(id)) {
    for (const auto& e : sub_elements(id))
      if (e.bit < 0 && e.name == name) return e.word;
    return -1;
  }
  if (!is_rtc(id)) return -1;
  for (std::size_t i = 0; i < kRtcWords.size(); ++i)
    if (kRtcWords[i] == name) return static_cast<int>(i);
  return -1;
}

std::string_view function_word_name(int id, int word) {
  if (is_pulse_train(id)) {
    for (const auto& e : kPulseTrainSubElements)
      if (e.bit < 0 && pulse_train_word(id, e) == word) return e.name;
    return {};
  }
  if (has_sub_elements(id)) {
    for (const auto& e : sub_elements(id))
      if (e.bit < 0 && e.word == word) return e.name;
    return {};
  }
  if (!is_rtc(id) || word < 0 || word >= static_cast<int>(kRtcWords.size())) return {};
  return kRtcWords[static_cast<std::size_t>(word)];
}

bool function_bit_number(int id, std::string_view name, int& word, int& bit) {
  if (is_pulse_train(id)) return named_bit(kPulseTrainSubElements, name, word, bit);
  if (has_sub_elements(id)) return named_bit(sub_elements(id), name, word, bit);
  if (!is_rtc(id)) return false;
  for (const auto& b : kRtcBits)
    if (b.name == name) {
      word = b.word;
      bit = b.bit;
      return true;
    }
  return false;
}

std::string_view function_bit_name(int id, int word, int bit) {
  if (is_pulse_train(id)) {
    for (const auto& e : kPulseTrainSubElements)
      if (e.bit >= 0 && e.word == word && e.bit == bit) return e.name;
    return {};
  }
  if (has_sub_elements(id)) {
    for (const auto& e : sub_elements(id))
      if (e.bit >= 0 && e.word == word && e.bit == bit) return e.name;
    return {};
  }
  if (!is_rtc(id)) return {};
  for (const auto& b : kRtcBits)
    if (b.word == word && b.bit == bit) return b.name;
  return {};
}

bool function_sub_element_writable(int id, int word, int bit) {
  if (is_pulse_train(id)) {
    // A word (or either word of a long) is writable when every sub-element in it is.
    bool any = false;
    for (const auto& e : kPulseTrainSubElements) {
      const int first = pulse_train_word(id, e);
      if (word < first || word >= first + pulse_train_width(id, e)) continue;
      if (bit >= 0 && e.bit >= 0 && e.bit != bit) continue;
      any = true;
      if (!e.writable) return false;
    }
    return any;  // bit 15 of the bit word is nobody's to write
  }
  // The RTC words are written by programs (CPW into RTC:0.YR, slc_adjust_clock.RSS).
  if (!has_sub_elements(id)) return true;
  bool any = false;
  for (const auto& e : sub_elements(id)) {
    if (e.word != word) continue;
    if (bit >= 0 && e.bit >= 0 && e.bit != bit) continue;
    any = true;
    if (!e.writable) return false;
  }
  return any;  // an unnamed bit of the bit word (7-15) is nobody's to write
}

namespace {
// "words PFN, ER, ... and bits UIX, ..." of a sub-element table.
template <typename Table>
std::string listed_names(const Table& table) {
  std::string words, bits;
  for (const auto& e : table) {
    std::string& list = e.bit < 0 ? words : bits;
    list += (list.empty() ? "" : ", ") + std::string(e.name);
  }
  return "words " + words + " and bits " + bits;
}
}  // namespace

std::string function_sub_element_names(int id) {
  if (is_rtc(id)) return "words YR, MON, DAY, HR, MIN, SEC, DOW and bits DS, BL";
  if (is_pulse_train(id)) return listed_names(kPulseTrainSubElements);
  if (has_sub_elements(id)) return listed_names(sub_elements(id));
  return {};
}

namespace {
// The MG element's named words (1762-RM001C p. 21-4, 1766-RM001A pp. 399-400) and bits (word 17:
// 1762-RM001C p. 21-6; word 16: [U], address.h namespace mg). `writable`: the tables' access column.
constexpr std::array kMessageSubElements{
    FunctionSubElement{"RBL", mg::kRemoteBridgeLink, -1, false}, FunctionSubElement{"LBN", mg::kLocalBridgeNode, -1, false},
    FunctionSubElement{"RBN", mg::kRemoteBridgeNode, -1, false}, FunctionSubElement{"CHN", mg::kChannel, -1, true},
    FunctionSubElement{"NOD", mg::kNode, -1, true},              FunctionSubElement{"MTO", mg::kTimeout, -1, true},
    FunctionSubElement{"TFN", mg::kTargetFile, -1, true},        FunctionSubElement{"ELE", mg::kTargetElement, -1, true},
    FunctionSubElement{"ERR", mg::kError, -1, false},
    FunctionSubElement{"EN", mg::kControl, mg::kEnableBit, true}, FunctionSubElement{"TO", mg::kControl, mg::kTimeOutBit, true},
    FunctionSubElement{"ST", mg::kStatus, mg::kStartBit, false},  FunctionSubElement{"DN", mg::kStatus, mg::kDoneBit, false},
    FunctionSubElement{"ER", mg::kStatus, mg::kErrorBit, false},  FunctionSubElement{"EW", mg::kStatus, mg::kWaitingBit, false},
    FunctionSubElement{"R", mg::kStatus, mg::kRangeBit, false},
};
}  // namespace

int message_word_number(std::string_view name) {
  for (const auto& e : kMessageSubElements)
    if (e.bit < 0 && e.name == name) return e.word;
  return -1;
}

std::string_view message_word_name(int word) {
  for (const auto& e : kMessageSubElements)
    if (e.bit < 0 && e.word == word) return e.name;
  return {};
}

bool message_bit_number(std::string_view name, int& word, int& bit) {
  return named_bit(kMessageSubElements, name, word, bit);
}

std::string_view message_bit_name(int word, int bit) {
  for (const auto& e : kMessageSubElements)
    if (e.bit >= 0 && e.word == word && e.bit == bit) return e.name;
  return {};
}

bool message_sub_element_writable(int word, int /*bit: sub-element 16's bits are all read/write*/) {
  // Sub-element 16 is read/write as a whole ("Control bits ... read/write", 1766-RM001A p. 400); the
  // others as their named entry (CHN, NOD, MTO, TFN, ELE); unnamed ones are read only.
  if (word == mg::kControl) return true;
  for (const auto& e : kMessageSubElements)
    if (e.bit < 0 && e.word == word) return e.writable;
  return false;
}

std::string_view file_letter(FileType t) {
  switch (t) {
    case FileType::Output: return "O";
    case FileType::Input: return "I";
    case FileType::Status: return "S";
    case FileType::Bit: return "B";
    case FileType::Timer: return "T";
    case FileType::Counter: return "C";
    case FileType::Control: return "R";
    case FileType::Integer: return "N";
    case FileType::Float: return "F";
    case FileType::Long: return "L";
    case FileType::String: return "ST";
    case FileType::Ascii: return "A";
    case FileType::M0: return "M0";
    case FileType::M1: return "M1";
    case FileType::Function: return "FN";
    case FileType::Message: return "MG";
    case FileType::Routing: return "RI";
  }
  return "?";
}

int words_per_element(FileType t) {
  switch (t) {
    case FileType::Timer:
    case FileType::Counter:
    case FileType::Control: return 3;
    case FileType::Float:
    case FileType::Long: return 2;
    case FileType::String: return 42;
    case FileType::Message: return mg::kWords;
    case FileType::Routing: return ri::kWords;
    default: return 1;
  }
}

int fixed_file_number(FileType t) {
  switch (t) {
    case FileType::Output: return 0;
    case FileType::Input: return 1;
    case FileType::Status: return 2;
    default: return -1;
  }
}

std::string_view structured_bit_name(FileType t, int bit) {
  for (const auto& b : kNamedBits)
    if (b.type == t && b.bit == bit) return b.name;
  return {};
}

std::string_view structured_word_name(FileType t, int word) {
  for (const auto& w : kNamedWords)
    if (w.type == t && w.word == word) return w.name;
  return {};
}

int structured_bit_number(FileType t, std::string_view name) {
  for (const auto& b : kNamedBits)
    if (b.type == t && b.name == name) return b.bit;
  return -1;
}

int structured_word_number(FileType t, std::string_view name) {
  for (const auto& w : kNamedWords)
    if (w.type == t && w.name == name) return w.word;
  return -1;
}

std::string to_string(const IndirectRef& r) {
  std::string s(file_letter(r.type));
  if (fixed_file_number(r.type) < 0) s += std::to_string(r.file);
  s += ':';
  s += std::to_string(r.element);
  if (r.word >= 0) {
    auto name = structured_word_name(r.type, r.word);
    s += '.';
    s += name.empty() ? std::to_string(r.word) : std::string(name);
  }
  return s;
}

std::string to_string(const Address& a) {
  std::string s;
  if (a.indexed) s += '#';
  if (is_function_file(a.type)) {
    // RTC:0.YR, RTC:0/DS, RTC:0.SEC/1: no file number, named words and bits where they exist.
    // DLS0:0/DN keeps the file number the manuals write it with (1763-RM001C p. 440).
    const int id = a.file;
    s += function_file_name(id);
    if (is_dls(id)) s += '0';
    s += ':' + std::to_string(a.element);
    // A CS file's elements are one word, so CS0:4/2 is CS0:4/MCP (both parse to word -1); its bit names
    // are CS0:4's only, and CS0:4.0/2 keeps its spelling.
    const bool cs_file = is_cs(id);
    auto bit_name = a.bit < 0    ? std::string_view{}
                    : !cs_file   ? function_bit_name(id, a.word, a.bit)
                    : a.word < 0 && a.element == cs::kStatusElement ? function_bit_name(id, 0, a.bit)
                                                                   : std::string_view{};
    if (!bit_name.empty()) return s + '/' + std::string(bit_name);
    if (a.word >= 0) {
      auto name = function_word_name(id, a.word);
      s += '.';
      s += name.empty() ? std::to_string(a.word) : std::string(name);
    }
    if (a.bit >= 0) s += '/' + std::to_string(a.bit);
    return s;
  }
  s += file_letter(a.type);
  if (a.indirect_file()) {
    s += '[' + to_string(*a.indirect_file()) + ']';
  } else if (fixed_file_number(a.type) < 0 && !is_mfile(a.type)) {
    s += std::to_string(a.file);
  }
  if (a.bit_offset_form && a.indirect_bit() && !a.indirect_element()) {
    // B3/[N7:0]: a bit offset into the file computed at run time.
    s += "/[" + to_string(*a.indirect_bit()) + ']';
    return s;
  }
  s += ':';
  s += a.indirect_element() ? '[' + to_string(*a.indirect_element()) + ']' : std::to_string(a.element);
  if (a.indirect_word()) {
    s += ".[" + to_string(*a.indirect_word()) + ']';
  } else if (is_structured(a.type)) {
    // T4:0 is the whole element; T4:0.0 its control word; T4:0/DN a bit of that word.
    if (a.word > 0 || (a.word == 0 && !a.has_bit())) {
      auto name = structured_word_name(a.type, a.word);
      s += '.';
      s += name.empty() ? std::to_string(a.word) : std::string(name);
    }
  } else if (is_io(a.type) || is_mfile(a.type)) {
    s += '.' + std::to_string(a.word_in_element());
  } else if (is_message_file(a.type) && a.word >= 0) {
    // MG11:0.NOD, MG11:0/DN (a named bit names its word), MG11:0.19.
    auto bit_name = a.bit >= 0 ? message_bit_name(a.word, a.bit) : std::string_view{};
    if (!bit_name.empty()) return s + '/' + std::string(bit_name);
    auto name = message_word_name(a.word);
    s += '.';
    s += name.empty() ? std::to_string(a.word) : std::string(name);
  } else if (a.word >= 0) {
    s += '.' + std::to_string(a.word);
  }
  if (a.indirect_bit()) {
    s += "/[" + to_string(*a.indirect_bit()) + ']';
  } else if (a.bit >= 0) {
    // A bit name (T4:0/DN) names a bit of the control word: not for a word chosen at run time
    // (C0:1.[N1:5]/10 is bit 10 of whichever word N1:5 selects).
    const bool control_word = a.word <= 0 && !a.indirect_word();
    auto name = is_structured(a.type) && control_word ? structured_bit_name(a.type, a.bit) : std::string_view{};
    s += '/';
    s += name.empty() ? std::to_string(a.bit) : std::string(name);
  }
  return s;
}

}  // namespace softslc
