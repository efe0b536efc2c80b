// Literals, durations and their printed forms (tools/testrunner/values.h).
#include <gtest/gtest.h>

#include "tools/testrunner/values.h"

namespace softslc::testing {
namespace {

Literal lit(std::string_view text) {
  std::string error;
  auto l = parse_literal(text, &error);
  EXPECT_TRUE(l.has_value()) << text << ": " << error;
  return l.value_or(Literal{});
}

TEST(Literals, RadixAndKind) {
  EXPECT_EQ(lit("-5").integer, -5);
  EXPECT_EQ(lit("-5").radix, Radix::Decimal);
  EXPECT_EQ(lit("0x00FF").integer, 255);
  EXPECT_EQ(lit("0x00FF").radix, Radix::Hex);
  EXPECT_EQ(lit("0020h").integer, 0x20);
  EXPECT_EQ(lit("0020h").radix, Radix::Hex);
  EXPECT_EQ(lit("0b0000_1111").integer, 15);
  EXPECT_EQ(lit("0b0000_1111").radix, Radix::Binary);
  EXPECT_EQ(lit("0b0000_1111").digits, 8);
  EXPECT_EQ(lit("1.5").kind, Literal::Kind::Float);
  EXPECT_DOUBLE_EQ(lit("-2.5e3").real, -2500.0);
}

TEST(Literals, PatternsKeepTheCaredBits) {
  Literal l = lit("0b1x0x");
  EXPECT_EQ(l.kind, Literal::Kind::Pattern);
  EXPECT_EQ(l.integer, 0b1000);
  EXPECT_EQ(l.care, 0b1010u);
  EXPECT_EQ(l.digits, 4);
  std::string error;
  EXPECT_FALSE(parse_literal("-0b1x", &error));
  EXPECT_EQ(error, "a bit pattern with x digits cannot be negative");
}

TEST(Literals, HexAndBinaryAreBitPatternsOfTheWord) {
  std::string error;
  EXPECT_EQ(integer_for_width(lit("0xFFFF"), 16, &error), -1);
  EXPECT_EQ(integer_for_width(lit("0x8000"), 16, &error), -32768);
  EXPECT_EQ(integer_for_width(lit("0x7FFF"), 16, &error), 32767);
  EXPECT_EQ(integer_for_width(lit("0xFFFFFFFF"), 32, &error), -1);
  EXPECT_EQ(integer_for_width(lit("-32768"), 16, &error), -32768);
  EXPECT_EQ(integer_for_width(lit("1"), 1, &error), 1);

  EXPECT_FALSE(integer_for_width(lit("0x1FFFF"), 16, &error));
  EXPECT_EQ(error, "'0x1FFFF' does not fit a 16-bit word");
  EXPECT_FALSE(integer_for_width(lit("32768"), 16, &error));
  EXPECT_EQ(error, "'32768' does not fit a 16-bit word (-32768..32767)");
  EXPECT_FALSE(integer_for_width(lit("2"), 1, &error));
  EXPECT_EQ(error, "a bit is 0 or 1, not '2'");
  EXPECT_FALSE(integer_for_width(lit("1.5"), 16, &error));
  EXPECT_EQ(error, "'1.5' is not an integer; this operand holds integers");
}

TEST(Durations, ParseExactly) {
  std::string error;
  EXPECT_EQ(parse_duration("250ms", &error), milliseconds(250));
  EXPECT_EQ(parse_duration("1.5s", &error), milliseconds(1500));
  EXPECT_EQ(parse_duration("2m", &error), seconds(120));
  EXPECT_EQ(parse_duration("10us", &error), microseconds(10));
  EXPECT_EQ(parse_duration("7ns", &error), 7);
  EXPECT_EQ(parse_duration("1.000000001s", &error), seconds(1) + 1);
  EXPECT_FALSE(parse_duration("0.5ns", &error));
  EXPECT_EQ(error, "duration '0.5ns' is not a whole number of nanoseconds");
  EXPECT_FALSE(parse_duration("99999999999999m", &error));
  EXPECT_EQ(error, "duration '99999999999999m' is too long");
}

TEST(Durations, FormatExactlyAndReadBack) {
  EXPECT_EQ(format_duration(0), "0s");
  EXPECT_EQ(format_duration(seconds(2)), "2s");
  EXPECT_EQ(format_duration(1'062'200'000), "1.0622s");
  EXPECT_EQ(format_duration(3'204'000), "3.204ms");
  EXPECT_EQ(format_duration(25'000), "25us");
  EXPECT_EQ(format_duration(7), "7ns");
  EXPECT_EQ(format_duration(1'000'000'001), "1.000000001s");
  for (Nanoseconds ns : {Nanoseconds{1}, Nanoseconds{999}, Nanoseconds{1'014'000}, Nanoseconds{100'386'000},
                         Nanoseconds{123'456'789'012}}) {
    std::string error;
    EXPECT_EQ(parse_duration(format_duration(ns), &error), ns) << format_duration(ns);
  }
}

TEST(Values, FormatInTheRadixOfTheLiteral) {
  EXPECT_EQ(format_value(Value::of_int(112)), "112");
  EXPECT_EQ(format_value(Value::of_int(112), Radix::Hex), "0x0070 (112)");
  EXPECT_EQ(format_value(Value::of_int(-1), Radix::Hex), "0xFFFF (-1)");
  EXPECT_EQ(format_value(Value::of_int(15), Radix::Binary), "0b0000_0000_0000_1111 (15)");
  EXPECT_EQ(format_value(Value::of_int(-1), Radix::Hex, 32), "0xFFFFFFFF (-1)");
  EXPECT_EQ(format_value(Value::bit(true), Radix::Hex), "1");
  // Data-table floats are 32-bit: 0.1 prints as the float's shortest spelling.
  EXPECT_EQ(format_value(Value::of_float(static_cast<double>(0.1f))), "0.1");
  EXPECT_EQ(format_value(Value::of_float(2.5)), "2.5");
}

}  // namespace
}  // namespace softslc::testing
