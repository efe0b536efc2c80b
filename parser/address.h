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
#pragma once

#include <cstdint>
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
};

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

struct Address {
  FileType type = FileType::Integer;
  std::uint16_t file = 0;   // data file number; 0/1 for M0/M1 (the slot is the element)
  std::int32_t element = 0;
  std::int32_t word = -1;   // word within the slot (I/O/M) or sub-element (T/C/R); -1 = none
  std::int32_t bit = -1;    // 0..15, -1 = none
  bool indexed = false;     // written with a leading '#'
  bool bit_offset_form = false;  // written B3/n (element computed from n)
  std::optional<IndirectRef> indirect_file;
  std::optional<IndirectRef> indirect_element;
  std::optional<IndirectRef> indirect_word;
  std::optional<IndirectRef> indirect_bit;

  bool has_bit() const { return bit >= 0 || indirect_bit.has_value(); }
  bool is_indirect() const {
    return indirect_file || indirect_element || indirect_word || indirect_bit;
  }
  // The word offset of this address inside its element (0 when the address names a whole
  // single-word element or the control word of a T/C/R element).
  int word_in_element() const { return word < 0 ? 0 : word; }

  bool operator==(const Address&) const = default;
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
