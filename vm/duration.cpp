#include "vm/duration.h"

#include <cstdint>
#include <limits>

namespace softslc {

namespace {
void set_error(std::string* error, std::string message) {
  if (error) *error = std::move(message);
}
}  // namespace

std::optional<Nanoseconds> parse_duration(std::string_view text, std::string* error) {
  const std::string spelling(text);
  std::size_t unit_at = text.find_first_not_of("0123456789.");
  if (unit_at == std::string_view::npos || unit_at == 0) {
    set_error(error, "'" + spelling + "' is not a duration (write 250ms, 1.5s, 2m, 10us)");
    return std::nullopt;
  }
  const std::string_view number = text.substr(0, unit_at), unit = text.substr(unit_at);
  Nanoseconds scale = 0;
  if (unit == "ns") scale = 1;
  else if (unit == "us") scale = kNsPerUs;
  else if (unit == "ms") scale = kNsPerMs;
  else if (unit == "s") scale = kNsPerS;
  else if (unit == "m") scale = 60 * kNsPerS;
  else {
    set_error(error, "unknown time unit '" + std::string(unit) + "' (use ns, us, ms, s or m)");
    return std::nullopt;
  }
  const auto dot = number.find('.');
  const std::string_view whole = number.substr(0, dot);
  const std::string_view fraction = dot == std::string_view::npos ? std::string_view{} : number.substr(dot + 1);
  // Integer arithmetic in 128 bits: the value is whole.fraction * scale, and it must come out as
  // a whole number of nanoseconds no larger than what a signed 64-bit count can hold.
  if (whole.size() > 18 || fraction.size() > 18) {
    set_error(error, "duration '" + spelling + "' is too long");
    return std::nullopt;
  }
  __int128 num = 0, den = 1;
  for (char c : whole) num = num * 10 + (c - '0');
  for (char c : fraction) {
    num = num * 10 + (c - '0');
    den *= 10;
  }
  const __int128 total = num * scale;
  if (total % den != 0) {
    set_error(error, "duration '" + spelling + "' is not a whole number of nanoseconds");
    return std::nullopt;
  }
  const __int128 ns = total / den;
  if (ns > static_cast<__int128>(std::numeric_limits<Nanoseconds>::max() / 2)) {
    set_error(error, "duration '" + spelling + "' is too long");
    return std::nullopt;
  }
  return static_cast<Nanoseconds>(ns);
}

std::string format_duration(Nanoseconds ns) {
  if (ns == 0) return "0s";
  std::string sign = ns < 0 ? "-" : "";
  const std::uint64_t v = ns < 0 ? static_cast<std::uint64_t>(-(ns + 1)) + 1 : static_cast<std::uint64_t>(ns);
  struct Unit {
    std::uint64_t ns;
    const char* name;
    int decimals;
  };
  static constexpr Unit kUnits[] = {{1'000'000'000, "s", 9}, {1'000'000, "ms", 6}, {1'000, "us", 3}, {1, "ns", 0}};
  for (const auto& u : kUnits) {
    if (v < u.ns) continue;
    std::string out = sign + std::to_string(v / u.ns);
    std::uint64_t rest = v % u.ns;
    if (rest != 0) {
      std::string frac = std::to_string(rest);
      frac.insert(0, static_cast<std::size_t>(u.decimals) - frac.size(), '0');
      while (!frac.empty() && frac.back() == '0') frac.pop_back();
      out += "." + frac;
    }
    return out + u.name;
  }
  return "0s";
}

}  // namespace softslc
