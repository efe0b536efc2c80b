// Durations as people write them ("250ms", "1.5s", "2m", "10us") and back, exactly.
//
// Virtual time is an integer count of nanoseconds, so a duration is parsed digit by digit into
// nanoseconds (never through a double), and one that is not a whole number of nanoseconds is
// an error rather than a rounding. format_duration() prints the inverse in the largest unit that
// keeps the value at least 1 ("1.0622s", "3.204ms", "25us"), so every printed duration can be
// pasted back into a command line or a test file. Shared by the CLI and the test runner.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "vm/virtual_time.h"

namespace softslc {

// Parses "250ms", "1.5s", "2m", "10us", "7ns". Returns nullopt and sets `error` otherwise.
std::optional<Nanoseconds> parse_duration(std::string_view text, std::string* error = nullptr);
// Exact, re-parseable spelling: "2s", "1.0622s", "3.204ms", "25us", "0s".
std::string format_duration(Nanoseconds ns);

}  // namespace softslc
