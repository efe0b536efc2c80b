// Parameter scaling: the four formulas of the 1203-SM1 manual, page B-13, in exact arithmetic.
//
// A SCANport parameter holds an integer "internal value"; its scaling attributes (multiplier,
// divisor, base, offset, decimal precision; Read Full Parameter attributes 13-16 and 21) turn it
// into the engineering value a display shows. The manual gives two formula pairs:
//
//   extended precision (descriptor bit 6 set):
//     Engineering = (Internal + Offset) x Multiplier x Base / (Divisor x 10^Precision)
//     Internal    = Engineering x Divisor x 10^Precision / (Multiplier x Base) - Offset
//   normal:
//     Engineering = (Internal + Offset) x Multiplier x Base / Divisor
//     Internal    = Engineering x Divisor / (Multiplier x Base) - Offset
//
// and "the decimal precision variable is always used to locate the decimal point for a display
// by counting from the rightmost digit". So a normal engineering value is counted in units of
// the last displayed digit and the display divides it by 10^Precision, while an extended one is
// already in display units; display_text() applies that rule, and both kinds of a parameter
// with the same factors display the same text (Accel Time 1 = 100 -> "1.0" either way).
//
// Everything is exact: engineering values are reduced fractions of 64-bit integers computed in
// 128-bit intermediates, conversions back round half away from zero, and any result that does
// not fit (or a zero multiplier/base/divisor, which a scaling link can produce at run time)
// gives nullopt instead of a wrong number. No floating point, so results never depend on the
// platform.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace softslc::scanport {

// A reduced fraction; denominator > 0.
struct Rational {
  std::int64_t numerator = 0;
  std::int64_t denominator = 1;
  friend bool operator==(const Rational&, const Rational&) = default;
};

// The factors after resolving scaling links (Drive::scaling_factors).
struct ScalingFactors {
  std::int64_t multiplier = 1;
  std::int64_t divisor = 1;
  std::int64_t base = 1;
  std::int64_t offset = 0;
  int precision = 0;  // decimal places, 0-18
};

// The reduced fraction n/d, or nullopt when d == 0.
std::optional<Rational> make_rational(std::int64_t n, std::int64_t d);

// Formula 1 (extended) or 3 (normal).
std::optional<Rational> engineering_value(const ScalingFactors& f, std::int64_t internal, bool extended);
// Formula 2 (extended) or 4 (normal), rounded half away from zero.
std::optional<std::int64_t> internal_value(const ScalingFactors& f, Rational engineering, bool extended);
// The number a display shows (before rounding to `precision` places): the extended engineering
// value, or the normal one divided by 10^precision. This is the value in the parameter's units
// ("Secs", "Hz"), so two parameters with different factors can be compared through it.
std::optional<Rational> display_value(const ScalingFactors& f, std::int64_t internal, bool extended);
// The inverse of display_value(), rounded half away from zero.
std::optional<std::int64_t> internal_from_display(const ScalingFactors& f, Rational shown, bool extended);
// `value` with exactly `decimals` places (0-18), rounded half away from zero: "-12.50".
std::optional<std::string> format_fixed(Rational value, int decimals);
// The text a display shows for `internal`, per the decimal-precision rule above.
std::optional<std::string> display_text(const ScalingFactors& f, std::int64_t internal, bool extended);

}  // namespace softslc::scanport
