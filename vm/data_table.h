// The data table: every data file of the processor in one array of 16-bit words.
//
// Layout. All files live in one std::vector<uint16_t>, in file-number order: O0, I1, S2, B3, T4,
// C5, R6, N7, F8, then user files 9-255 that exist. A DataTableLayout records, per file number,
// whether the file exists, its type, its first word (base), its element count and its words per
// element (1; 3 for T/C/R; 2 for F and L; 42 for ST). The compiler decides the layout once (from
// DATA blocks and the highest address the program uses, at most 256 elements per file) and
// resolves every direct operand to a word index in this array, so the interpreter's hot path is
// `words[index]` and nothing else. The layout never changes while the program runs.
//
//   word 0                                                              total_words
//   +---------+---------+----------------+------+-------+-------+------+-----+------+----
//   | O0      | I1      | S2 (164 words) | B3   | T4    | C5    | R6   | N7  | F8   | 9.. (then RTC)
//   | SCAN_OUT| SCAN_IN |                | 1/el | 3/el  | 3/el  | 3/el | 1/el| 2/el |
//   +---------+---------+----------------+------+-------+-------+------+-----+------+----
//
// I/O files. O0 and I1 hold the image words of every configured slot, in slot order; element
// e of an I/O address is the slot and the word is the word within the slot (I:1.0/3), resolved
// through the per-slot table (input_slots / output_slots).
//
// Structured elements (T, C, R) are three consecutive words: control (status bits), PRE/LEN,
// ACC/POS. The timer control word's low byte holds the timer's 10 ms tick stamp (see
// docs/semantics.md "Timer tick model"); the high byte holds EN/TT/DN (and the counter/control
// bits), as RM 1-6 / 1-8 and PT1 4-9 lay them out.
//
// 32-bit values (F floats, L longs) occupy two consecutive words in host byte order of the
// 32-bit value (least significant word first on the little-endian hosts softslc targets); COP
// moves them as raw words.
//
// Invariant: every index the compiler emits or the checked run-time resolver returns is inside
// [0, total_words); nothing outside this file touches the array by any other route.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "parser/address.h"

namespace softslc {

// Minimum status file size. The status file has the processor's length (checker.h
// status_file_words: 16 words on fixed controllers up to 164 on the 5/04 and 5/05), but never
// fewer than 36 words, so every status word the VM maintains (up to S:35) exists.
inline constexpr std::uint32_t kMinStatusWords = 36;
// Elements per data file (PT1 4-8/4-9: 0-255).
inline constexpr std::uint32_t kMaxElements = 256;
// Slots per chassis address space: 0 (processor) to 30 (RM 1-2).
inline constexpr int kMaxSlots = 31;

// Status-file words and bits the VM reads or writes (facts §3).
namespace status {
inline constexpr int kArith = 0;       // S:0: C /0, V /1, Z /2, S /3
inline constexpr int kMode = 1;        // S:1: mode /0-4, forces /5 /6, major halt /13, first pass /15
inline constexpr int kControl = 2;     // S:2: overflow select /14
inline constexpr int kWatchdog = 3;    // S:3: low byte scan ticks, high byte watchdog ticks
inline constexpr int kClock = 4;       // S:4: free-running 10 ms clock
inline constexpr int kMinor = 5;       // S:5: minor errors, /0 overflow trap
inline constexpr int kFaultCode = 6;   // S:6: major fault code
inline constexpr int kMathLow = 13;    // S:13: math register low word
inline constexpr int kMathHigh = 14;   // S:14: math register high word
inline constexpr int kMaxScan = 22;    // S:22: maximum scan (10 ms, or 1 ms with S:33/13)
inline constexpr int kAvgScan = 23;    // S:23: average scan
inline constexpr int kIndex = 24;      // S:24: index register
inline constexpr int kCommBits = 33;   // S:33: /13 selects 1 ms units for S:22/S:23
inline constexpr int kLastScanMs = 35; // S:35: last scan in 1 ms
// Program control and interrupts (RM 11-2 to 11-16, RM ch. 6 SUS).
inline constexpr int kSuspendCode = 7;   // S:7: the ID of the SUS that suspended the processor
inline constexpr int kSuspendFile = 8;   // S:8: the program file holding that SUS
inline constexpr int kFaultRoutine = 29; // S:29: user fault routine file (0 = none)
inline constexpr int kStiSetpoint = 30;  // S:30: STI setpoint (10 ms units; 1 ms with S:2/10 on 5/03+)
inline constexpr int kStiFile = 31;      // S:31: STI program file (0 = none)
inline constexpr int kMinorExtended = 36;  // S:36: extended minor errors, /9 STI lost (5/03+)

inline constexpr std::uint16_t kCarry = 1u << 0;
inline constexpr std::uint16_t kOverflow = 1u << 1;
inline constexpr std::uint16_t kZero = 1u << 2;
inline constexpr std::uint16_t kSign = 1u << 3;
inline constexpr std::uint16_t kForcesEnabled = 1u << 5;
inline constexpr std::uint16_t kForcesInstalled = 1u << 6;
inline constexpr std::uint16_t kMajorHalt = 1u << 13;
inline constexpr std::uint16_t kFirstPass = 1u << 15;
inline constexpr std::uint16_t kOverflowSelect = 1u << 14;
inline constexpr std::uint16_t kOverflowTrap = 1u << 0;
// S:5/2: control register error, set with a sequencer's ER bit (PT1 24-8).
inline constexpr std::uint16_t kControlRegisterError = 1u << 2;
inline constexpr std::uint16_t kScanIn1ms = 1u << 13;
inline constexpr std::uint16_t kStiPending = 1u << 0;     // S:2/0
inline constexpr std::uint16_t kStiEnabled = 1u << 1;     // S:2/1
inline constexpr std::uint16_t kStiExecuting = 1u << 2;   // S:2/2
inline constexpr std::uint16_t kStiResolution = 1u << 10; // S:2/10: S:30 in 1 ms units (5/03+)
inline constexpr std::uint16_t kStiOverflow = 1u << 10;   // S:5/10
inline constexpr std::uint16_t kStiLost = 1u << 9;        // S:36/9
// the discrete input interrupt (RM 11-18 .. 11-26, B-24, B-56) and the I/O event
// interrupt (RM 11-27 .. 11-35, B-43, B-46). Bit numbers marked [U] are from RSLogix 500's status
// file layout, their RM pages (B-9 .. B-12, B-48, B-50) not reached (docs/semantics.md).
inline constexpr int kIoPendingLow = 25;   // S:25/S:26: I/O interrupt pending, bit n = slot n (B-43)
inline constexpr int kIoEnableLow = 27;    // S:27/S:28: I/O interrupt enable, bit n = slot n (11-31)
inline constexpr int kIsrExecuting = 32;   // S:32: slot of the executing ISR (B-46)
inline constexpr int kDiiFile = 46;        // S:46: DII subroutine file (0 = none)
inline constexpr int kDiiSlot = 47;        // S:47: DII input slot
inline constexpr int kDiiMask = 48;        // S:48: bit mask (bits 0-7 used)
inline constexpr int kDiiCompare = 49;     // S:49: compare value (bits 0-7 used)
inline constexpr int kDiiPreset = 50;      // S:50: preset (0/1 event mode, 2-32767 counter mode)
inline constexpr int kDiiReturnMask = 51;  // S:51: the transitions that caused the interrupt
inline constexpr int kDiiAccumulator = 52; // S:52: accumulator
inline constexpr std::uint16_t kDiiPending = 1u << 11;    // S:2/11 [U]
inline constexpr std::uint16_t kDiiEnabled = 1u << 12;    // S:2/12 [U]
inline constexpr std::uint16_t kDiiExecuting = 1u << 13;  // S:2/13 [U]
inline constexpr std::uint16_t kDiiOverflow = 1u << 12;   // S:5/12 (B-24)
inline constexpr std::uint16_t kDiiLost = 1u << 8;        // S:36/8 [U]
}  // namespace status

// T/C/R control-word bits (RM 1-6, 1-8; PT1 4-9).
namespace bits {
inline constexpr std::uint16_t kEN = 1u << 15;  // timer, control
inline constexpr std::uint16_t kTT = 1u << 14;  // timer
inline constexpr std::uint16_t kDN = 1u << 13;  // timer, counter, control
inline constexpr std::uint16_t kCU = 1u << 15;  // counter
inline constexpr std::uint16_t kCD = 1u << 14;
inline constexpr std::uint16_t kOV = 1u << 12;
inline constexpr std::uint16_t kUN = 1u << 11;
inline constexpr std::uint16_t kEU = 1u << 14;  // control
inline constexpr std::uint16_t kEM = 1u << 12;
inline constexpr std::uint16_t kER = 1u << 11;
inline constexpr std::uint16_t kUL = 1u << 10;
inline constexpr std::uint16_t kIN = 1u << 9;
inline constexpr std::uint16_t kFD = 1u << 8;
inline constexpr std::uint16_t kStampMask = 0x00FF;  // timer tick stamp (softslc's choice, see docs)
}  // namespace bits

// How a word (or word pair) is interpreted.
enum class ValueType : std::uint8_t { Int16, Int32, Float32 };
inline ValueType value_type_of(FileType t) {
  return t == FileType::Float ? ValueType::Float32 : t == FileType::Long ? ValueType::Int32 : ValueType::Int16;
}

struct FileLayout {
  bool present = false;
  FileType type = FileType::Integer;
  std::uint32_t base = 0;        // first word index in the table
  std::uint32_t elements = 0;    // element count; for O0/I1 the number of image words
  std::uint8_t words_per_element = 1;

  std::uint32_t words() const { return elements * words_per_element; }
  std::uint32_t end() const { return base + words(); }
};

// A slot's words inside the O0 or I1 image (offsets relative to the file's base).
struct SlotImage {
  bool present = false;
  std::uint32_t first = 0;
  std::uint32_t words = 0;
};

// A resolved data-table location.
struct Location {
  std::uint32_t word = 0;  // index in the table
  int bit = -1;            // 0-15, or -1 for a word / value
  ValueType vtype = ValueType::Int16;
  FileType type = FileType::Integer;
  int file = 0;
};

// Where the function files sit in DataTableLayout::files: after the 256 data files, one entry per
// FunctionFile (files[kFunctionFileIndex + RTC] is the real-time clock). Only simulated function
// files are present; they follow the data files in the word array, so the file-number order of
// `files` is still the word order.
inline constexpr std::size_t kFunctionFileIndex = 256;

struct DataTableLayout {
  std::array<FileLayout, kFunctionFileIndex + kFunctionFileCount> files{};
  std::array<SlotImage, kMaxSlots> input_slots{};
  std::array<SlotImage, kMaxSlots> output_slots{};
  std::uint32_t total_words = 0;

  std::uint32_t status_word(int n) const { return files[2].base + static_cast<std::uint32_t>(n); }
  // The layout of a function file (present only when softslc simulates it on this processor).
  const FileLayout& function_file(FunctionFile f) const { return files[kFunctionFileIndex + static_cast<std::size_t>(f)]; }
  // The word of CSn:4, channel n's communications status bits (MCP), when the program has that CS file.
  std::optional<std::uint32_t> communications_status_word(int channel) const {
    if (channel < 0 || channel > 2) return std::nullopt;
    const FileLayout& f = function_file(static_cast<FunctionFile>(static_cast<int>(FunctionFile::CS0) + channel));
    if (!f.present) return std::nullopt;
    return f.base + static_cast<std::uint32_t>(cs::kStatusElement);
  }

  // Resolves a direct address (no '#' index, no [indirection], not M0/M1) to its location.
  // `as_file_start` treats a leading '#' as the file marker of file instructions rather than as
  // an S:24 index. Returns nullopt with a message when the address is outside the layout.
  std::optional<Location> locate(const Address& a, std::string* error = nullptr, bool as_file_start = false) const;

  // The file whose words contain `word`, or -1. O(1) once index_files() has run (the compiler runs
  // it on every layout it makes): module instructions, file instructions and MSG ask this for their
  // operands in every scan. A layout built by hand without the index is scanned file by file.
  int file_containing(std::uint32_t word) const {
    if (word < word_file_.size()) return word_file_[word] == kNoFile ? -1 : word_file_[word];
    return word_file_.empty() ? scan_for_file(word) : -1;
  }
  // Records, for every word of the table, the file holding it (2 bytes a word, the size of the table
  // itself). Call it again after changing `files` or `total_words`.
  void index_files();
  // The canonical address of a word (and bit), e.g. "I:1.0/3", "T4:0.ACC", "T4:0/DN", "F8:2".
  std::string describe(std::uint32_t word, int bit = -1) const;

 private:
  static constexpr std::uint16_t kNoFile = 0xFFFF;
  int scan_for_file(std::uint32_t word) const;
  // word -> file number (kNoFile for a word in no file), total_words entries; empty until indexed.
  std::vector<std::uint16_t> word_file_;
};

// A value as tools see it: a bit, a (16- or 32-bit) integer, or a float.
struct Value {
  enum class Kind : std::uint8_t { Bit, Integer, Float };
  Kind kind = Kind::Integer;
  std::int64_t integer = 0;  // Bit: 0 or 1
  double real = 0.0;

  static Value bit(bool b) { return {Kind::Bit, b ? 1 : 0, 0.0}; }
  static Value of_int(std::int64_t i) { return {Kind::Integer, i, 0.0}; }
  static Value of_float(double d) { return {Kind::Float, 0, d}; }

  bool as_bool() const { return kind == Kind::Float ? real != 0.0 : integer != 0; }
  std::int64_t as_int() const;  // floats round half to even
  double as_double() const { return kind == Kind::Float ? real : static_cast<double>(integer); }
  // Bits "0"/"1", integers signed decimal, floats printf "%g".
  std::string to_string() const;
  bool operator==(const Value&) const = default;
};

// Numeric helpers shared by the interpreter and the runtime API.
namespace numeric {
// Denormal floats count as zero (facts §5 Float, ML1400 RM p.204).
inline float flush_denormal(float f) {
  return (f != 0.0f && std::fabs(f) < 1.17549435e-38f) ? 0.0f : f;
}
// Rounds half to even and saturates into the range of `vt` (Int16 or Int32). Sets `overflow`
// when the value was out of range or not a number (NaN saturates to the positive limit).
std::int64_t float_to_integer(double f, ValueType vt, bool& overflow);
}  // namespace numeric

class DataTable {
 public:
  DataTable(std::shared_ptr<const DataTableLayout> layout, std::vector<std::uint16_t> initial);

  const DataTableLayout& layout() const { return *layout_; }
  std::uint16_t* words() { return words_.data(); }
  const std::uint16_t* words() const { return words_.data(); }
  std::uint32_t size() const { return static_cast<std::uint32_t>(words_.size()); }

  std::uint16_t word(std::uint32_t i) const { return words_[i]; }
  void set_word(std::uint32_t i, std::uint16_t v) { words_[i] = v; }
  std::uint16_t status(int n) const { return words_[layout_->status_word(n)]; }
  void set_status(int n, std::uint16_t v) { words_[layout_->status_word(n)] = v; }

  std::int32_t i32(std::uint32_t i) const {
    std::int32_t v;
    std::memcpy(&v, &words_[i], sizeof v);
    return v;
  }
  float f32(std::uint32_t i) const {
    float v;
    std::memcpy(&v, &words_[i], sizeof v);
    return v;
  }
  void set_i32(std::uint32_t i, std::int32_t v) { std::memcpy(&words_[i], &v, sizeof v); }
  void set_f32(std::uint32_t i, float v) { std::memcpy(&words_[i], &v, sizeof v); }

  Value read(const Location& loc) const;
  // Writes with conversion: floats into integer words round half to even and saturate.
  void write(const Location& loc, const Value& v);

 private:
  std::shared_ptr<const DataTableLayout> layout_;
  std::vector<std::uint16_t> words_;
};

}  // namespace softslc
