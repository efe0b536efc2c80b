// Literals, durations and counts of the test-file format, and how they are printed back.
//
// A test file writes values the way a controls engineer reads them in RSLogix: decimal (-5, 100),
// hexadecimal (0x00FF or 00FFh), binary with optional '_' separators (0b0000_1111), binary
// patterns with don't-care digits (0b1xxx_0000_xxxx_0001) and floats (1.5, 2e3). A literal keeps
// its radix so a failure message prints the actual value in the same radix the test used:
// "expected 0x00F0, actual 0x0070 (112)" is readable where "112" alone is not.
//
// Hexadecimal and binary literals are bit patterns: compared with a 16-bit word, 0xFFFF means all
// sixteen bits set, i.e. the signed value -1 the SLC stores. Decimal literals are signed values.
// integer_for_width() applies that rule for a given word width (1 for a bit, 16, 32).
//
// Durations are exact integers of nanoseconds (never doubles, like the VM's virtual time):
// "1.5s" is parsed digit by digit, and a duration that is not a whole number of nanoseconds is
// an error rather than a rounding. format_duration() prints the inverse, exactly, in the largest
// unit that keeps the value at least 1 ("1.0622s", "3.204ms", "25us"), so every printed duration
// can be pasted back into a test file.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "vm/data_table.h"
#include "vm/duration.h"
#include "vm/virtual_time.h"

namespace softslc::testing {

// A 1-based position in a test file.
struct Location {
  std::uint32_t line = 0;
  std::uint32_t column = 0;
  bool operator==(const Location&) const = default;
};

enum class Radix : std::uint8_t { Decimal, Hex, Binary };

struct Literal {
  enum class Kind : std::uint8_t { Integer, Float, Pattern };
  Kind kind = Kind::Integer;
  Radix radix = Radix::Decimal;
  std::int64_t integer = 0;  // Integer, and the 1-bits of a Pattern
  double real = 0.0;         // Float
  std::uint64_t care = 0;    // Pattern: the digits written as 0 or 1 (x digits are 0 here)
  int digits = 0;            // Hex/Binary: how many digits were written (sets the printed width)
  std::string spelling;
  Location loc;
};

// Parses one literal token (the grammar has already matched its shape). Returns nullopt and sets
// `error` when the token is out of range (more than 64 bits, a negative pattern, ...).
std::optional<Literal> parse_literal(std::string_view text, std::string* error);

// The integer a literal stands for in a word of `width` bits (1, 16 or 32): decimal literals must
// lie in the signed range (a bit takes 0 or 1), hexadecimal and binary ones in the unsigned range,
// and are then sign-extended. Float and pattern literals are refused. On refusal returns nullopt
// and sets `error` to a sentence naming the range.
std::optional<std::int64_t> integer_for_width(const Literal& l, int width, std::string* error);

// The value a literal writes into an operand of `width` bits (1, 16, 32; 0 for a float):
// integer_for_width()'s rule, a float only into a float operand. The one conversion rule of
// test-file `set` and `softslc run --set` (the runtime refuses the same values from the C++ API).
// On refusal returns nullopt and sets `error`.
std::optional<Value> value_for_width(const Literal& l, int width, std::string* error);

// Durations are parsed and printed by vm/duration.h, shared with the CLI.
using softslc::format_duration;
using softslc::parse_duration;

// Prints a value read from the data table. Floats use the shortest spelling that reads back as
// the same 32-bit float; integers print in decimal, or in hex / binary padded to the word's
// width and followed by the decimal value in parentheses ("0x00F0 (240)").
std::string format_value(const Value& v, Radix radix = Radix::Decimal, int width = 16);

// The unsigned bit pattern of a signed value in `width` bits.
std::uint64_t pattern_of(std::int64_t v, int width);

}  // namespace softslc::testing
