#include "tools/testrunner/values.h"

#include <charconv>
#include <limits>

#include "parser/loader.h"

namespace softslc::testing {

namespace {

bool starts_with_binary_prefix(std::string_view t) {
  if (!t.empty() && (t.front() == '-' || t.front() == '+')) t.remove_prefix(1);
  return t.size() > 2 && t[0] == '0' && (t[1] == 'b' || t[1] == 'B');
}

bool is_hex_spelling(std::string_view t) {
  if (!t.empty() && (t.front() == '-' || t.front() == '+')) t.remove_prefix(1);
  if (t.size() > 2 && t[0] == '0' && (t[1] == 'x' || t[1] == 'X')) return true;
  return !t.empty() && (t.back() == 'h' || t.back() == 'H');
}

int hex_digit_count(std::string_view t) {
  if (!t.empty() && (t.front() == '-' || t.front() == '+')) t.remove_prefix(1);
  if (t.size() > 2 && t[0] == '0' && (t[1] == 'x' || t[1] == 'X')) return static_cast<int>(t.size() - 2);
  return static_cast<int>(t.size() - 1);
}

void set_error(std::string* error, std::string message) {
  if (error) *error = std::move(message);
}

}  // namespace

std::optional<Literal> parse_literal(std::string_view text, std::string* error) {
  Literal l;
  l.spelling = std::string(text);
  if (starts_with_binary_prefix(text)) {
    l.radix = Radix::Binary;
    const bool negative = text.front() == '-';
    std::string_view digits = text.substr(text.find_first_of("bB") + 1);
    std::uint64_t ones = 0, care = 0;
    int count = 0;
    bool has_x = false;
    for (char c : digits) {
      if (c == '_') continue;
      if (++count > 64) {
        set_error(error, "binary literal '" + l.spelling + "' has more than 64 digits");
        return std::nullopt;
      }
      ones <<= 1;
      care <<= 1;
      if (c == 'x' || c == 'X') {
        has_x = true;
        continue;
      }
      care |= 1;
      if (c == '1') ones |= 1;
    }
    if (count == 0) {
      set_error(error, "binary literal '" + l.spelling + "' has no digits");
      return std::nullopt;
    }
    l.digits = count;
    if (has_x) {
      if (negative) {
        set_error(error, "a bit pattern with x digits cannot be negative");
        return std::nullopt;
      }
      l.kind = Literal::Kind::Pattern;
      l.integer = static_cast<std::int64_t>(ones);
      l.care = care;
      return l;
    }
    if (ones > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) {
      set_error(error, "binary literal '" + l.spelling + "' does not fit 63 bits");
      return std::nullopt;
    }
    l.integer = negative ? -static_cast<std::int64_t>(ones) : static_cast<std::int64_t>(ones);
    return l;
  }
  NumberValue v;
  if (!parse_number_text(text, v)) {
    set_error(error, "number out of range: '" + l.spelling + "'");
    return std::nullopt;
  }
  if (v.is_float) {
    l.kind = Literal::Kind::Float;
    l.real = v.real;
    return l;
  }
  l.integer = v.integer;
  if (is_hex_spelling(text)) {
    l.radix = Radix::Hex;
    l.digits = hex_digit_count(text);
  }
  return l;
}

std::optional<Value> value_for_width(const Literal& l, int width, std::string* error) {
  if (width == 0) {
    if (l.kind == Literal::Kind::Pattern) {
      set_error(error, "a bit pattern with x digits can only be compared with == or !=");
      return std::nullopt;
    }
    return Value::of_float(l.kind == Literal::Kind::Float ? l.real : static_cast<double>(l.integer));
  }
  auto i = integer_for_width(l, width, error);
  if (!i) return std::nullopt;
  return width == 1 ? Value::bit(*i != 0) : Value::of_int(*i);
}

std::optional<std::int64_t> integer_for_width(const Literal& l, int width, std::string* error) {
  if (l.kind == Literal::Kind::Float) {
    set_error(error, "'" + l.spelling + "' is not an integer; this operand holds integers");
    return std::nullopt;
  }
  if (l.kind == Literal::Kind::Pattern) {
    set_error(error, "a bit pattern with x digits can only be compared with == or !=");
    return std::nullopt;
  }
  if (width == 1) {
    if (l.integer != 0 && l.integer != 1) {
      set_error(error, "a bit is 0 or 1, not '" + l.spelling + "'");
      return std::nullopt;
    }
    return l.integer;
  }
  const std::int64_t smax = (std::int64_t{1} << (width - 1)) - 1;
  const std::int64_t smin = -smax - 1;
  const std::int64_t umax = (std::int64_t{1} << width) - 1;
  if (l.radix == Radix::Decimal || l.integer < 0) {
    if (l.integer < smin || l.integer > smax) {
      set_error(error, "'" + l.spelling + "' does not fit a " + std::to_string(width) + "-bit word (" +
                           std::to_string(smin) + ".." + std::to_string(smax) + ")");
      return std::nullopt;
    }
    return l.integer;
  }
  if (l.integer > umax) {
    set_error(error, "'" + l.spelling + "' does not fit a " + std::to_string(width) + "-bit word");
    return std::nullopt;
  }
  // A pattern with the top bit set is the negative value the processor stores.
  return l.integer > smax ? l.integer - (umax + 1) : l.integer;
}

std::uint64_t pattern_of(std::int64_t v, int width) {
  const std::uint64_t mask = width >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << width) - 1;
  return static_cast<std::uint64_t>(v) & mask;
}



std::string format_value(const Value& v, Radix radix, int width) {
  if (v.kind == Value::Kind::Float) {
    // Data-table floats are 32-bit: the shortest spelling of the float is what RSLogix shows.
    char buf[64];
    auto r = std::to_chars(buf, buf + sizeof buf, static_cast<float>(v.real));
    return std::string(buf, r.ptr);
  }
  if (v.kind == Value::Kind::Bit || radix == Radix::Decimal) return std::to_string(v.integer);
  const std::uint64_t bits = pattern_of(v.integer, width);
  std::string digits;
  if (radix == Radix::Hex) {
    static constexpr char kHex[] = "0123456789ABCDEF";
    for (int i = (width + 3) / 4 - 1; i >= 0; --i) digits += kHex[(bits >> (4 * i)) & 0xF];
    return "0x" + digits + " (" + std::to_string(v.integer) + ")";
  }
  for (int i = width - 1; i >= 0; --i) {
    digits += ((bits >> i) & 1) ? '1' : '0';
    if (i > 0 && i % 4 == 0) digits += '_';
  }
  return "0b" + digits + " (" + std::to_string(v.integer) + ")";
}

}  // namespace softslc::testing
