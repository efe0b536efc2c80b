#include "modules/scanport/scaling.h"

#include <limits>

namespace softslc::scanport {
namespace {

// 128-bit intermediates: GCC's builtin type. Every product below is overflow-checked, because
// scaling links feed parameter values (up to 64 bits) into the factors at run time.
using I128 = __int128;

constexpr I128 kI64Max = std::numeric_limits<std::int64_t>::max();
constexpr I128 kI64Min = std::numeric_limits<std::int64_t>::min();

std::optional<I128> mul(I128 a, I128 b) {
  I128 r = 0;
  if (__builtin_mul_overflow(a, b, &r)) return std::nullopt;
  return r;
}

std::optional<I128> pow10(int n) {
  if (n < 0 || n > 36) return std::nullopt;
  I128 r = 1;
  for (int i = 0; i < n; ++i) r *= 10;
  return r;
}

I128 abs128(I128 v) { return v < 0 ? -v : v; }

I128 gcd128(I128 a, I128 b) {
  a = abs128(a);
  b = abs128(b);
  while (b != 0) {
    I128 t = a % b;
    a = b;
    b = t;
  }
  return a;
}

// n/d reduced, denominator positive, both fitting 64 bits.
std::optional<Rational> reduce(I128 n, I128 d) {
  if (d == 0) return std::nullopt;
  if (d < 0) {
    n = -n;
    d = -d;
  }
  I128 g = gcd128(n, d);
  if (g > 1) {
    n /= g;
    d /= g;
  }
  if (n > kI64Max || n < kI64Min || d > kI64Max) return std::nullopt;
  return Rational{static_cast<std::int64_t>(n), static_cast<std::int64_t>(d)};
}

// n/d rounded half away from zero (d > 0).
I128 round_div(I128 n, I128 d) {
  I128 q = n / d;
  I128 r = n % d;
  if (abs128(r) * 2 >= d) q += n < 0 ? -1 : 1;
  return q;
}

}  // namespace

std::optional<Rational> make_rational(std::int64_t n, std::int64_t d) { return reduce(n, d); }

std::optional<Rational> engineering_value(const ScalingFactors& f, std::int64_t internal, bool extended) {
  auto scale = pow10(extended ? f.precision : 0);
  if (!scale) return std::nullopt;
  auto num = mul(static_cast<I128>(internal) + f.offset, f.multiplier);
  if (!num) return std::nullopt;
  num = mul(*num, f.base);
  auto den = mul(f.divisor, *scale);
  if (!num || !den) return std::nullopt;
  return reduce(*num, *den);
}

std::optional<std::int64_t> internal_value(const ScalingFactors& f, Rational engineering, bool extended) {
  auto scale = pow10(extended ? f.precision : 0);
  if (!scale || engineering.denominator <= 0) return std::nullopt;
  auto num = mul(engineering.numerator, f.divisor);
  if (!num) return std::nullopt;
  num = mul(*num, *scale);
  auto den = mul(static_cast<I128>(f.multiplier) * 1, f.base);
  if (!num || !den || *den == 0) return std::nullopt;
  den = mul(*den, engineering.denominator);
  if (!den) return std::nullopt;
  I128 n = *num, d = *den;
  if (d < 0) {
    n = -n;
    d = -d;
  }
  I128 r = round_div(n, d) - f.offset;
  if (r > kI64Max || r < kI64Min) return std::nullopt;
  return static_cast<std::int64_t>(r);
}

std::optional<std::string> format_fixed(Rational value, int decimals) {
  if (decimals < 0 || decimals > 18 || value.denominator <= 0) return std::nullopt;
  auto scaled = mul(value.numerator, *pow10(decimals));
  if (!scaled) return std::nullopt;
  I128 units = round_div(*scaled, value.denominator);
  const bool negative = units < 0;
  I128 mag = abs128(units);
  // Digits least significant first, at least one before the decimal point.
  std::string reversed;
  do {
    reversed.push_back(static_cast<char>('0' + static_cast<int>(mag % 10)));
    mag /= 10;
  } while (mag != 0);
  while (static_cast<int>(reversed.size()) <= decimals) reversed.push_back('0');
  std::string out = negative ? "-" : "";
  for (std::size_t i = reversed.size(); i-- > 0;) {
    out.push_back(reversed[i]);
    if (decimals > 0 && i == static_cast<std::size_t>(decimals)) out.push_back('.');
  }
  return out;
}

std::optional<Rational> display_value(const ScalingFactors& f, std::int64_t internal, bool extended) {
  auto eng = engineering_value(f, internal, extended);
  if (!eng || extended) return eng;
  // Normal scaling counts the engineering value in units of the last displayed digit.
  auto scale = pow10(f.precision);
  if (!scale) return std::nullopt;
  auto den = mul(eng->denominator, *scale);
  if (!den) return std::nullopt;
  return reduce(eng->numerator, *den);
}

std::optional<std::int64_t> internal_from_display(const ScalingFactors& f, Rational shown, bool extended) {
  if (extended) return internal_value(f, shown, true);
  auto scale = pow10(f.precision);
  if (!scale) return std::nullopt;
  auto num = mul(shown.numerator, *scale);
  if (!num) return std::nullopt;
  auto eng = reduce(*num, shown.denominator);
  if (!eng) return std::nullopt;
  return internal_value(f, *eng, false);
}

std::optional<std::string> display_text(const ScalingFactors& f, std::int64_t internal, bool extended) {
  auto shown = display_value(f, internal, extended);
  if (!shown) return std::nullopt;
  return format_fixed(*shown, f.precision);
}

}  // namespace softslc::scanport
