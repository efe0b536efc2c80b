// The string instructions of 1747-RM001G chapter 10 (ACI, AIC, ACN, AEX, ASC, ASR) as pure
// functions over ST elements.
//
// Design. An ST element is 42 words: word 0 the length (0-82 characters), words 1-41 two
// characters each, the first in the high byte (RM 10-3; 1763-RM001 "String Data File Structure").
// The interpreter hands these functions the element's words (std::span of exactly 42, already
// bounds-checked against the data table) and applies what they return: the destination words, the
// S:0 flags, the ASCII error bit S:5/15. Nothing here allocates or reads outside the spans, so the
// functions are tested directly against the manual's rules (tests/vm/ascii_test.cpp).
//
// Invariant: a Text never holds more than kMaxLength characters; a length word outside 0-82 is an
// error the caller turns into S:5/15 ("lengths that are outside of this range cause the processor
// to set the ASCII Error bit (S:5/15) and the instruction is not executed", RM 10-3).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace softslc::ascii {

inline constexpr int kMaxLength = 82;         // characters in a string element (RM 10-3)
inline constexpr std::uint32_t kElementWords = 42;
inline constexpr std::uint16_t kAsciiErrorBit = 1u << 15;  // S:5/15 (RM 10-3)
// The MicroLogix also writes this code to S:6 when it sets S:5/15 ("Invalid String Length Error
// (1F39H) is written to the Major Error Fault Code word", 1763-RM001 ACN, 1766-RM001 ACI).
inline constexpr std::uint16_t kMicroLogixStringLengthError = 0x1F39;

using Element = std::span<std::uint16_t, kElementWords>;
using ConstElement = std::span<const std::uint16_t, kElementWords>;

struct Text {
  std::array<std::uint8_t, kMaxLength> chars{};
  int length = 0;
  std::string_view view() const { return {reinterpret_cast<const char*>(chars.data()), static_cast<std::size_t>(length)}; }
};

// Reads an element. False when its length word is outside 0-82 (the caller sets S:5/15).
bool read(ConstElement e, Text& out);
// Writes length and characters; the words past the new length keep what they held (the pad byte
// of an odd length's last word included).
void write(Element e, const Text& t);
Text from(std::string_view s);  // the first 82 characters of s

// ACI (RM 10-8, table 10.6).
struct IntegerResult {
  bool converted = false;  // a digit was found: the destination is written
  bool overflow = false;   // V: outside -32768..32767 (value then saturated, docs/semantics.md)
  std::int16_t value = 0;
};
IntegerResult to_integer(const Text& t);

// AIC (RM 10-14): the decimal text of v, "-" first when negative.
Text from_integer(std::int16_t v);

// ACN: A then B, the first 82 characters.
Text concatenate(const Text& a, const Text& b);

// AEX (RM 10-12). False (S:5/15, destination unchanged) for a source length 0, an index or number
// outside 1-82, or an index past the source's last character.
bool extract(const Text& source, std::int64_t index, std::int64_t number, Text& out);

// ASC (RM 10-18, 10-19): the position (1-based) of `find` in `in` at or after `index`; 0 when it
// is not there. False (S:5/15, result unchanged) for an empty string, an index outside 1-82 or
// past the searched string's last character.
bool search(const Text& find, std::int64_t index, const Text& in, std::int64_t& position);

}  // namespace softslc::ascii
