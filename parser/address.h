// SLC 500 data addresses as values.
//
// An Address is what the program text names: a file type and number, an element, optionally a
// word (sub-element) and a bit, plus the two run-time addressing modes of the SLC: indexed ('#'
// outside file instructions, offset by S:24) and indirect ('[N10:1]' in the file, element, word
// or bit position). The parser produces Addresses; the checker validates them against the
// processor and the chassis; the compiler resolves direct ones to data-table locations once.
//
// Conventions, uniform across file types:
//   I/O and M files (I:e.s/b, O:e.s/b, M0:e.s/b):  element = slot e, word = s (0 when omitted).
//   T/C/R files: element = e, word = sub-element 0..2 (-1 = the whole element), named bits are
//                word 0 bits (DN = 13 ...), .PRE/.ACC/.LEN/.POS are words 1 and 2.
//   B files:     B3/62 (bit-offset form) is normalised to element 3 bit 14; `bit_offset_form`
//                remembers the spelling only where it matters (an indirect bit offset).
//   Other files: element = e, word = -1.
//   Function files (MicroLogix RTC:0.YR, HSC:0/FE, ...): type Function, `file` = the
//                FunctionFile kind, element = e, word = the named sub-element's word (a named
//                bit also sets its word). They have no file number: RSLogix writes RTC:0, never
//                RTC9:0 (1762-RM001C ch. 3 "Function Files").
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

namespace softslc {

enum class FileType : std::uint8_t {
  Output,   // O0
  Input,    // I1
  Status,   // S2
  Bit,      // B
  Timer,    // T
  Counter,  // C
  Control,  // R
  Integer,  // N
  Float,    // F
  Long,     // L (32-bit integer, MicroLogix)
  String,   // ST
  Ascii,    // A
  M0,       // specialty-module output file (module memory, no image in the processor)
  M1,       // specialty-module input file
  Function, // MicroLogix function file (RTC, HSC, STI, ...): Address::file says which
  Message,  // MG: MicroLogix MSG file, 25-word elements (1762-RM001C p. 21-4)
  Routing,  // RI: MicroLogix 1100/1400 routing information file, 20-word elements (1766-RM001A p. 435)
};

// The MicroLogix MSG file element (MG11:0): 25 words, sub-elements 0-24 (1762-RM001C p. 21-4,
// 1763-RM001B pp. 347-348, 1766-RM001A pp. 399-400; docs/micrologix-msg-sources.md section 2). Named
// words as the manuals name them (MG11:0.NOD ...); the status bits of word 17 as 1762-RM001C p. 21-6
// places them (MG11:0/DN is bit 13 of word 17); the control bits of word 16 (EN, TO) at the SLC control
// word's positions, bit 15 and bit 8 (RM 12-31): the manuals' control-bit table (1762-RM001C p. 21-5,
// 1763-RM001B p. 351, 1766-RM001A p. 402) was not reached [U]. The user program may write CHN, NOD,
// MTO, TFN, ELE and the control bits; every other sub-element is "read only" (the tables' access column).
namespace mg {
inline constexpr int kWords = 25;
inline constexpr int kMessagingType = 2, kCommand = 3, kRemoteBridgeLink = 5, kLocalBridgeNode = 6,
                     kRemoteBridgeNode = 7, kChannel = 8, kNode = 9, kTimeout = 10, kByteCount = 11,
                     kTargetFileType = 12, kTargetFile = 13, kTargetElement = 14, kTargetSubElement = 15,
                     kControl = 16, kStatus = 17, kError = 18, kElapsed = 19, kStartTime = 21,
                     kInternalError = 22, kExtendedError = 23, kRoutingPath = 24;
// Word 16 (control, [U] positions) and word 17 (status, 1762-RM001C p. 21-6).
inline constexpr int kEnableBit = 15, kTimeOutBit = 8;
inline constexpr int kStartBit = 14, kDoneBit = 13, kErrorBit = 12, kWaitingBit = 10, kRangeBit = 0;
}  // namespace mg

// The MicroLogix routing information file element (RI12:0), 20 words (1766-RM001A p. 435, 1763-RM001B
// p. 384): 0 subtype (10h normal MultiHop, 11h remote MultiHop to DH+), 1-2 the target IP address in
// network byte order, 3 IOI size and ASA service code, 4-8 ASA IOI, 9 connection path size, 10-17
// connection paths, 18-19 reserved. The manuals name no sub-elements: RI12:0.1 is word 1.
namespace ri {
inline constexpr int kWords = 20;
inline constexpr int kSubtype = 0, kIpHigh = 1, kIpLow = 2;
}  // namespace ri
// Named words and bits of an MG element: the word number (-1 when unknown); a bit sets `word` and `bit`.
int message_word_number(std::string_view name);
std::string_view message_word_name(int word);
bool message_bit_number(std::string_view name, int& word, int& bit);
std::string_view message_bit_name(int word, int bit);
// Whether the user program may write word `word` (bit `bit`, or -1 for the whole word) of an MG element.
bool message_sub_element_writable(int word, int bit);
inline bool is_message_file(FileType t) { return t == FileType::Message; }
// MG and RI: elements of many plain words, written word by word in a DATA block.
inline bool is_multiword_data(FileType t) { return t == FileType::Message || t == FileType::Routing; }

// The MicroLogix function files, by the names RSLogix gives them (1762-RM001C ch. 3, 1763-RM001,
// 1766-RM001 "Function Files"). The real-time clock and the selectable timed interrupt are
// simulated; the others are recognised so that a program naming them gets a clear diagnostic
// instead of a syntax error.
// PTO is the MicroLogix 1100/1200/1500 pulse train output file, PTOX the MicroLogix 1400's
// (1766-RM001A p. 146); both are simulated (docs/semantics.md "The PTO function file").
// DLS is the Data Log Status file (1763-RM001C p. 440, AG-UM008C p. 3-64): one element per configured
// data log queue, written DLS0:q as the manuals write it (docs/semantics.md "Data logging").
// CS0, CS1 and CS2 are the communications status files of channels 0, 1 (the 1764-LRP's second serial
// port) and 2 (the 1400's): last, so that a program naming one puts it after every other file.
enum class FunctionFile : std::uint8_t { RTC, HSC, PTOX, PWMX, STI, EII, BHI, MMI, DAT, TPI, IOS, LCD, PTO, DLS, CS0, CS1, CS2 };
inline constexpr int kFunctionFileCount = 17;
// "RTC", "HSC", ... for a FunctionFile number; "?" when out of range.
std::string_view function_file_name(int id);
// The FunctionFile number of a name ("RTC" -> 0), or -1.
int function_file_id(std::string_view name);
// Whether softslc simulates the function file (has its layout and behaviour): RTC, STI, HSC, PTO/PTOX.
bool function_file_simulated(int id);
// Elements and words per element of a simulated function file (RTC: 1 element of 8 words, STI: 1
// of 4, HSC: up to 6 of 18; how many HSCs a processor has is ProcessorModel::hsc_count()).
int function_file_elements(int id);
int function_file_words_per_element(int id);
// Named sub-elements of a function file element: word number, or -1 when unknown.
int function_word_number(int id, std::string_view name);
std::string_view function_word_name(int id, int word);
// Named bits: sets `word` and `bit` and returns true when known.
bool function_bit_number(int id, std::string_view name, int& word, int& bit);
std::string_view function_bit_name(int id, int word, int bit);
// Whether the user program may write the sub-element at word `word` (bit `bit`, or -1 for the whole
// word) of function file `id`: false for the manuals' "read only" sub-elements, and for a whole
// word that holds any of them (STI:0's bit word is written bit by bit).
bool function_sub_element_writable(int id, int word, int bit);
// The names of a simulated function file's words and bits, for diagnostics ("YR, MON, ...").
std::string function_sub_element_names(int id);

// The real-time clock function file's words (1762-RM001C p. 3-3 Table 3.2, same in 1763-RM001 and
// 1766-RM001): YR 1998-2097, MON 1-12, DAY 1-31, HR 0-23, MIN 0-59, SEC 0-59, DOW 0-6 (Sunday =
// 0), then the status word holding DS (clock disabled) and BL (battery low). The order of the
// seven value words is the order the table lists them, which is what `CPW N:0 RTC:0.YR 6`
// (slc_adjust_clock.RSS) relies on; the bit positions of DS and BL in word 7 are softslc's choice
// (the manual names the bits, not their positions).
namespace rtc {
inline constexpr int kYear = 0, kMonth = 1, kDay = 2, kHour = 3, kMinute = 4, kSecond = 5, kDayOfWeek = 6;
inline constexpr int kStatusWord = 7;
inline constexpr int kDisabledBit = 0, kBatteryLowBit = 1;
inline constexpr int kWords = 8;
}  // namespace rtc

// The selectable timed interrupt function file STI:0 (1763-RM001C pp. 269-272, 1762-RM001C ch. 18,
// 1766-RM001A p. 318 on). One element of four words, in the order RSLogix itself writes them in a
// library export (`DATA STI0:0` / `0 0 0X0002 0` in 59-BSGS.SLC) and stores them in a project's
// DATA FILES stream (docs/micrologix-function-files-sources.md section 6): PFN (program file
// number), ER (error code), the bit word, SPM (set point, ms, 0-65,535). Access (1763 pp. 270/272
// read; the rest [U], docs/semantics.md "MicroLogix"): PFN, ER, UIX, UIP, AS, ED read only; UIE,
// UIL, TIE, SPM read/write. The bit positions are softslc's decision [U]: the manuals name the bits
// without positions; the order of the manual's sub-element list (UIX, UIE, UIL, UIP, TIE, AS, ED)
// fits the saved projects, where 0x0002 (UIE) is RSLogix's default and the auto-started STI of
// TVZ_1100_REV02.RSS has 0x0032 (UIE, TIE, AS).
namespace sti {
inline constexpr int kProgramFile = 0, kErrorCode = 1, kBits = 2, kSetPoint = 3;
inline constexpr int kWords = 4;
inline constexpr int kExecutingBit = 0, kEnableBit = 1, kLostBit = 2, kPendingBit = 3, kTimedEnableBit = 4,
                     kAutoStartBit = 5, kErrorBit = 6;
// RSLogix's default bit word (UIE set): what every saved project without an STI has.
inline constexpr std::uint16_t kDefaultBits = 1u << kEnableBit;
// STI:0.ER 1: "Invalid Program File Number" (1763-RM001C p. 270).
inline constexpr std::uint16_t kErrorInvalidFile = 1;
}  // namespace sti

// The event input interrupt function file EII:0 .. EII:n (1763-RM001C pp. 272-276, 1762-RM001C
// pp. 18-17 .. 18-20): per element four words, in the order RSLogix writes them in a library export
// (`DATA EII0:0` / `0 0 0X4002 n` for element n, 59-BSGS.SLC) and stores them in a project (the
// .RSS function-file record of type 0x15: four elements of four words, word 3 = 0, 1, 2, 3): PFN,
// ER, the bit word, IS (input select; RSLogix's default is the element's own number). Access as
// read: UIX, UIP read only, UIE, UIL read/write (1763-RM001C p. 275, 1762-RM001C p. 18-19); the
// rest [U]. The bit positions are softslc's decision [U]: UIX, UIE, UIL, UIP, EIE, AS, ED at the
// STI's positions (its TIE is the EII's EIE), and ES (edge select, 1 = rising edge) at bit 14, the
// only other bit of RSLogix's default 0x4002 (docs/semantics.md "The EII function file").
// The Data Log Status file (AG-UM008C p. 3-65 Table 3.13, 1763-RM001C p. 440, 1766-RM001A p. 526):
// 3-word elements, one per data log queue. Word 0: EN bit 15, DN bit 13, OV bit 12 (bit-addressed
// only); word 1 FSZ (records allocated), word 2 RST (records stored). The 1400's CQ (bit 11) is not
// simulated (docs/semantics.md "Data logging").
namespace dls {
inline constexpr int kBits = 0, kFileSize = 1, kRecordsStored = 2;
inline constexpr int kWords = 3;
inline constexpr int kMaxQueues = 256;  // queues 0-255 (1763-RM001C p. 433)
inline constexpr int kEnableBit = 15, kDoneBit = 13, kOverflowBit = 12;
}  // namespace dls
// Whether `id` is the DLS file.
bool is_data_log_status_file(int id);

// The communications status files CS0, CS1, CS2 (1762-RM001C p. 3-13, 1763-RM001C p. 57, 1766-RM001A
// p. 63): read only, one per channel, 71 one-word elements. softslc simulates one bit of them, MCP
// "Outgoing Message Command Pending" (CS0:4/2, 1762-RM001C p. 21-27 Table 21.5), the bit of the
// manual's conditional SVC; the checker refuses the rest by name (docs/semantics.md "The CS file").
namespace cs {
inline constexpr int kElements = 71;
inline constexpr int kStatusElement = 4;  // CS0:4: ICP bit 0, MRP bit 1, MCP bit 2, CAB bit 4
inline constexpr int kIncomingCommandBit = 0, kReplyPendingBit = 1, kCommandPendingBit = 2, kActiveBit = 4;
inline constexpr std::uint16_t kCommandPending = 1u << kCommandPendingBit;
}  // namespace cs
// The channel whose communications status file `id` is (0, 1, 2), or -1 when it is none.
int communications_status_channel(int id);

namespace eii {
inline constexpr int kProgramFile = 0, kErrorCode = 1, kBits = 2, kInputSelect = 3;
inline constexpr int kWords = 4;
inline constexpr int kMaxElements = 8;
inline constexpr int kExecutingBit = 0, kEnableBit = 1, kLostBit = 2, kPendingBit = 3, kEventEnableBit = 4,
                     kAutoStartBit = 5, kErrorBit = 6, kEdgeSelectBit = 14;
// RSLogix's default bit word: UIE and ES (rising edge).
inline constexpr std::uint16_t kDefaultBits = (1u << kEnableBit) | (1u << kEdgeSelectBit);
// EII:n.ER 1: "Invalid Program File Number", as the STI's code 1 (1763-RM001C p. 270) [U];
// ER 2: IS names no embedded input (0-15) [U].
inline constexpr std::uint16_t kErrorInvalidFile = 1, kErrorInvalidInput = 2;
// The largest IS: the bits of the embedded input word I:0.0 [U].
inline constexpr int kMaxInput = 15;
}  // namespace eii

// The pulse train output function files: PTO:0-1 on the MicroLogix 1100, 1200 and 1500, PTOX:0-2
// on the MicroLogix 1400. Layout (docs/micrologix-function-files-sources.md section 6.3): the
// words RSLogix stores in a project (the .RSS function-file record of type 0x12: two elements of 12
// words) and exports (PTOX0:n in 59-BSGS.SLC: three words and six long words). Read from the
// fixtures: word 0 OUT (2 in 2080-MOT-HSC.RSS, whose comments say "PTO:0.OUT = 2"; -1 when unset),
// word 1 the bit word (the export writes it in hex), word 3 OF (2000: "2000 for 2kHz"), words 6-7
// TOP (2147483647, low word first). The rest by the manual's sub-element order [U]: word 2 ER,
// 4 OFS, 5 JF, 8-9 OPP, 10-11 ADP. The PTOX widens OF, OFS and JF to long words [U] (its frequency
// reaches 100 kHz). TOP, OPP and ADP are long words (32-bit INT, 1762-RM001C p. 6-12). The bit
// positions are softslc's decision [U], the manual's order from bit 0 (as the STI's):
// DN DS RS AS RP IS ED NS EH EN CS JP JPS JC JCS.
namespace pto {
inline constexpr int kOutput = 0, kBits = 1, kErrorCode = 2;
// Word offsets of the frequency and count sub-elements: PTO (16-bit OF/OFS/JF) and PTOX (32-bit).
struct Layout {
  int frequency, frequency_status, jog_frequency, total, produced, accel_decel, words;
  bool long_frequencies;
};
inline constexpr Layout kPto{3, 4, 5, 6, 8, 10, 12, false};
inline constexpr Layout kPtox{3, 5, 7, 9, 11, 13, 15, true};
inline constexpr int kPtoElements = 2, kPtoxElements = 3;
inline constexpr int kDoneBit = 0, kDecelBit = 1, kRunBit = 2, kAccelBit = 3, kRampBit = 4, kIdleBit = 5, kErrorBit = 6,
                     kNormalBit = 7, kHardStopBit = 8, kEnableBit = 9, kControlStopBit = 10, kJogPulseBit = 11,
                     kJogPulseStatusBit = 12, kJogContinuousBit = 13, kJogContinuousStatusBit = 14;
// The values a DATA PTO0:0 row gives per element, as the export writes a PTOX element: OUT, the bit
// word, ER, then OF, OFS, JF, TOP, OPP, ADP (one value each, 16 or 32 bits by the layout).
inline constexpr int kValuesPerElement = 9;
}  // namespace pto
// Whether `id` is PTO or PTOX.
bool is_pulse_train_file(int id);
// The high-speed counter function file HSC:0.. (1762-RM001C ch. 5, 1763-RM001C and 1766-RM001A
// "Using the High-Speed Counter"). Each element is 18 words in the order RSLogix writes it in a
// library export (`DATA HSC0:0`: five words, five long words, three words; 59-BSGS.SLC) and stores
// it in a project's DATA FILES stream (type 0x11; docs/micrologix-function-files-sources.md
// section 6): PFN, ER, two bit words, MOD; the long words ACC, HIP, LOP, OVF, UNF (low word first,
// as the .RSS stores 30 as 001E 0000); OMB, HPO, LPO. Which word is which name is inferred from the
// defaults and TVZ_1100_REV02.RSS (PFN 11 = its HSC0 file, HIP 30 = its N17:11), and the bit
// positions are softslc's decision [U] that fits every saved project (docs/semantics.md "The HSC
// function file"). Access: LPR, OMB read only and LPI, UFI, OF, OVF read/write as read on
// 1762-RM001C pp. 5-10, 5-13, 5-23, 5-24; the rest [U].
namespace hsc {
inline constexpr int kProgramFile = 0, kErrorCode = 1, kBits = 2, kStatus = 3, kMode = 4;
inline constexpr int kAccumulator = 5, kHighPreset = 7, kLowPreset = 9, kOverflow = 11, kUnderflow = 13;
inline constexpr int kOutputMask = 15, kHighOutput = 16, kLowOutput = 17;
inline constexpr int kWords = 18;
// Word 2 (kBits).
inline constexpr int kExecutingBit = 0, kEnableBit = 1, kLostBit = 2, kPendingBit = 3, kFunctionEnabledBit = 4,
                     kAutoStartBit = 5, kErrorBit = 6, kSetParametersBit = 7, kCountingEnabledBit = 8,
                     kLowInterruptBit = 9, kUnderflowInterruptBit = 10, kHighInterruptBit = 11,
                     kOverflowInterruptBit = 12;
// Word 3 (kStatus).
inline constexpr int kLowMaskBit = 0, kHighMaskBit = 1, kUnderflowMaskBit = 2, kOverflowMaskBit = 3,
                     kLowReachedBit = 4, kHighReachedBit = 5, kUnderflowBit = 6, kOverflowBit = 7,
                     kDirectionBit = 12, kModeDoneBit = 13, kCountDownBit = 14, kCountUpBit = 15;
// RSLogix's defaults for an unconfigured counter (59-BSGS.SLC, every .RSS fixture but TVZ's).
inline constexpr std::uint16_t kDefaultBits = 0x0002, kDefaultStatus = 0x000F;
// An element as RSLogix's export writes it: 13 values (5 words, 5 long words, 3 words).
inline constexpr std::size_t kExportValues = 13;
// Whether export value `k` (0-12) of an element is a long word, and the word it starts at.
inline constexpr bool export_value_is_long(std::size_t k) { return k >= 5 && k < 10; }
inline constexpr int export_value_word(std::size_t k) {
  return k < 5 ? static_cast<int>(k) : k < 10 ? 5 + 2 * static_cast<int>(k - 5) : 15 + static_cast<int>(k - 10);
}
// Whether word `word` of an element starts one of the five long words.
inline constexpr bool is_long_word(int word) {
  return word == kAccumulator || word == kHighPreset || word == kLowPreset || word == kOverflow || word == kUnderflow;
}
}  // namespace hsc
// Whether word `word` of function file `id` begins a 32-bit long word (PTO:0.TOP, HSC:0.ACC ...).
bool function_word_is_long(int id, int word);

// The letter(s) of a file type as written in addresses: "O", "I", "S", "B", ..., "ST", "M0".
std::string_view file_letter(FileType t);
// Words per element: 3 for T/C/R, 2 for F and L, 42 for ST, 1 otherwise.
int words_per_element(FileType t);
// Whether the element has named sub-elements (T, C, R).
inline bool is_structured(FileType t) {
  return t == FileType::Timer || t == FileType::Counter || t == FileType::Control;
}
inline bool is_io(FileType t) { return t == FileType::Output || t == FileType::Input; }
inline bool is_mfile(FileType t) { return t == FileType::M0 || t == FileType::M1; }
inline bool is_function_file(FileType t) { return t == FileType::Function; }
// The fixed file number of O/I/S (0/1/2); -1 for the others.
int fixed_file_number(FileType t);

// A direct word address used inside brackets for indirection, e.g. the N10:1 in N7:[N10:1].
struct IndirectRef {
  FileType type = FileType::Integer;
  std::uint16_t file = 0;
  std::uint16_t element = 0;
  std::int16_t word = -1;  // sub-element for T/C/R (T4:0.ACC), -1 otherwise

  bool operator==(const IndirectRef&) const = default;
};

// The four indirect references an Address may have ([N10:1] in the file, element, word or bit
// position). Held out of line by Address: almost no operand has one, and in place they were 40 of
// the Address's 60 bytes (docs/performance.md "Load time").
struct IndirectRefs {
  std::optional<IndirectRef> file;
  std::optional<IndirectRef> element;
  std::optional<IndirectRef> word;
  std::optional<IndirectRef> bit;

  bool operator==(const IndirectRefs&) const = default;
};

// An address's indirect references with value semantics: empty (no allocation) for a direct
// address, a copied IndirectRefs otherwise. Two holders compare by what they hold.
class IndirectHolder {
 public:
  IndirectHolder() = default;
  IndirectHolder(const IndirectHolder& o) : refs_(o.refs_ ? std::make_unique<IndirectRefs>(*o.refs_) : nullptr) {}
  IndirectHolder(IndirectHolder&&) noexcept = default;
  IndirectHolder& operator=(const IndirectHolder& o) {
    if (this != &o) refs_ = o.refs_ ? std::make_unique<IndirectRefs>(*o.refs_) : nullptr;
    return *this;
  }
  IndirectHolder& operator=(IndirectHolder&&) noexcept = default;
  ~IndirectHolder() = default;

  const IndirectRefs* get() const { return refs_.get(); }
  IndirectRefs& make() {
    if (!refs_) refs_ = std::make_unique<IndirectRefs>();
    return *refs_;
  }
  bool operator==(const IndirectHolder& o) const {
    static const IndirectRefs kNone{};
    return (refs_ ? *refs_ : kNone) == (o.refs_ ? *o.refs_ : kNone);
  }

 private:
  std::unique_ptr<IndirectRefs> refs_;
};

// 24 bytes: the two flags are one-bit fields beside the type, and the indirect references are
// behind one pointer that is null for a direct address.
struct Address {
  FileType type = FileType::Integer;
  bool indexed : 1 = false;          // written with a leading '#'
  bool bit_offset_form : 1 = false;  // written B3/n (element computed from n)
  std::uint16_t file = 0;   // data file number; 0/1 for M0/M1 (the slot is the element)
  std::int32_t element = 0;
  std::int32_t word = -1;   // word within the slot (I/O/M) or sub-element (T/C/R); -1 = none
  std::int32_t bit = -1;    // 0..15, -1 = none
  IndirectHolder indirect;  // the indirect references; read through the accessors below

  // Each indirect reference, or nullopt (the accessors read the out-of-line block when present).
  const std::optional<IndirectRef>& indirect_file() const { return refs().file; }
  const std::optional<IndirectRef>& indirect_element() const { return refs().element; }
  const std::optional<IndirectRef>& indirect_word() const { return refs().word; }
  const std::optional<IndirectRef>& indirect_bit() const { return refs().bit; }
  void set_indirect_file(const IndirectRef& r) { indirect.make().file = r; }
  void set_indirect_element(const IndirectRef& r) { indirect.make().element = r; }
  void set_indirect_word(const IndirectRef& r) { indirect.make().word = r; }
  void set_indirect_bit(const IndirectRef& r) { indirect.make().bit = r; }

  bool has_bit() const { return bit >= 0 || indirect_bit().has_value(); }
  // The holder is only made by a setter, so a non-null block always holds a reference.
  bool is_indirect() const { return indirect.get() != nullptr; }
  // The word offset of this address inside its element (0 when the address names a whole
  // single-word element or the control word of a T/C/R element).
  int word_in_element() const { return word < 0 ? 0 : word; }

  bool operator==(const Address&) const = default;

 private:
  const IndirectRefs& refs() const {
    static const IndirectRefs kNone{};
    return indirect.get() ? *indirect.get() : kNone;
  }
};

// The canonical spelling: "B3:3/14", "T4:0/DN", "T4:0.ACC", "I:1.0/3", "M0:1.100/13",
// "N7:[N10:1]", "#N7:10". Named bits and sub-elements are used for T/C/R where they exist.
std::string to_string(const Address& a);
std::string to_string(const IndirectRef& r);

// The mnemonic of a T/C/R status bit ("DN") or sub-element word ("PRE"), or empty.
std::string_view structured_bit_name(FileType t, int bit);
std::string_view structured_word_name(FileType t, int word);
// Parses a named bit ("DN") or word ("ACC") of a T/C/R element. Returns -1 when unknown.
int structured_bit_number(FileType t, std::string_view name);
int structured_word_number(FileType t, std::string_view name);

}  // namespace softslc
