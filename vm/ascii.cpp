#include "vm/ascii.h"

#include <algorithm>

namespace softslc::ascii {

bool read(ConstElement e, Text& out) {
  const auto len = static_cast<std::int16_t>(e[0]);
  if (len < 0 || len > kMaxLength) return false;
  out.length = len;
  for (int i = 0; i < len; ++i) {
    const std::uint16_t w = e[1 + static_cast<std::size_t>(i / 2)];
    out.chars[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(i % 2 == 0 ? w >> 8 : w & 0xFF);
  }
  return true;
}

void write(Element e, const Text& t) {
  e[0] = static_cast<std::uint16_t>(t.length);
  for (int i = 0; i < t.length; ++i) {
    std::uint16_t& w = e[1 + static_cast<std::size_t>(i / 2)];
    const std::uint8_t c = t.chars[static_cast<std::size_t>(i)];
    w = i % 2 == 0 ? static_cast<std::uint16_t>((w & 0x00FF) | (c << 8)) : static_cast<std::uint16_t>((w & 0xFF00) | c);
  }
}

Text from(std::string_view s) {
  Text t;
  t.length = static_cast<int>(std::min<std::size_t>(s.size(), kMaxLength));
  for (int i = 0; i < t.length; ++i) t.chars[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(s[static_cast<std::size_t>(i)]);
  return t;
}

namespace {
bool is_digit(std::uint8_t c) { return c >= '0' && c <= '9'; }
}  // namespace

// RM 10-8: "The processor searches the source ... for the first character between 0 and 9. All
// numeric characters are extracted until a non-numeric character or the end of the string is
// reached. Action is taken only if numeric characters are found. ... Commas and signs (+, -) are
// allowed in the string. However, only the minus sign is displayed". softslc reads a sign right
// before the first digit and skips commas between digits ("-1,234" is -1234); decisions in
// docs/semantics.md.
IntegerResult to_integer(const Text& t) {
  IntegerResult r;
  int i = 0;
  while (i < t.length && !is_digit(t.chars[static_cast<std::size_t>(i)])) ++i;
  if (i == t.length) return r;
  const bool negative = i > 0 && t.chars[static_cast<std::size_t>(i - 1)] == '-';
  std::int64_t v = 0;
  for (; i < t.length; ++i) {
    const std::uint8_t c = t.chars[static_cast<std::size_t>(i)];
    if (c == ',') continue;
    if (!is_digit(c)) break;
    v = std::min<std::int64_t>(v * 10 + (c - '0'), 1'000'000);  // bounded: only "out of range" matters past here
  }
  if (negative) v = -v;
  r.converted = true;
  if (v > 32767 || v < -32768) {
    r.overflow = true;
    v = v > 0 ? 32767 : -32768;
  }
  r.value = static_cast<std::int16_t>(v);
  return r;
}

Text from_integer(std::int16_t v) {
  Text t;
  char buf[8];
  int n = 0;
  std::int32_t x = v;
  const bool negative = x < 0;
  if (negative) x = -x;
  do {
    buf[n++] = static_cast<char>('0' + x % 10);
    x /= 10;
  } while (x > 0);
  if (negative) t.chars[static_cast<std::size_t>(t.length++)] = '-';
  while (n > 0) t.chars[static_cast<std::size_t>(t.length++)] = static_cast<std::uint8_t>(buf[--n]);
  return t;
}

Text concatenate(const Text& a, const Text& b) {
  Text t = a;
  for (int i = 0; i < b.length && t.length < kMaxLength; ++i) t.chars[static_cast<std::size_t>(t.length++)] = b.chars[static_cast<std::size_t>(i)];
  return t;
}

bool extract(const Text& source, std::int64_t index, std::int64_t number, Text& out) {
  if (source.length == 0 || index < 1 || index > kMaxLength || number < 1 || number > kMaxLength || index > source.length)
    return false;
  const auto first = static_cast<int>(index - 1);
  const int count = static_cast<int>(std::min<std::int64_t>(number, source.length - first));
  out = Text{};
  for (int i = 0; i < count; ++i) out.chars[static_cast<std::size_t>(i)] = source.chars[static_cast<std::size_t>(first) + static_cast<std::size_t>(i)];
  out.length = count;
  return true;
}

bool search(const Text& find, std::int64_t index, const Text& in, std::int64_t& position) {
  if (find.length == 0 || in.length == 0 || index < 1 || index > kMaxLength || index > in.length) return false;
  position = 0;
  const std::string_view hay = in.view();
  const std::size_t at = hay.find(find.view(), static_cast<std::size_t>(index - 1));
  if (at != std::string_view::npos) position = static_cast<std::int64_t>(at) + 1;
  return true;
}

}  // namespace softslc::ascii
