// The properties the fuzz targets check, shared with the regression tests that replay every
// input the fuzzers ever found (tests/fuzz/regressions/), so a fixed bug stays fixed in the
// ordinary test suite too. Each returns an empty string when the property holds, else what broke.
#pragma once

#include <string>
#include <string_view>

#include "parser/formatter.h"
#include "parser/loader.h"
#include "tools/testrunner/test_parser.h"

namespace softslc::fuzz {

// Loading never fails by crashing; a program that loads formats to text that loads again as
// the same program.
inline std::string check_program_property(std::string_view bytes) {
  auto r = load_program(std::string(bytes), "fuzz.slc");
  (void)r.render_diagnostics();
  if (!r.ok()) return {};
  std::string formatted = format_program(*r.program);
  auto again = load_program(formatted, "fuzz-formatted.slc");
  if (!again.ok()) return "formatted program does not load:\n" + again.render_diagnostics();
  std::string diff;
  if (!same_program(*r.program, *again.program, &diff)) return "round trip changed the program: " + diff;
  return {};
}

// An address that parses prints to a canonical spelling that parses back to the same address.
inline std::string check_address_property(std::string_view bytes) {
  std::string error;
  auto a = parse_address(bytes, &error);
  if (!a) return {};
  auto canonical = to_string(*a);
  auto again = parse_address(canonical, &error);
  if (!again) return "canonical spelling '" + canonical + "' does not parse: " + error;
  if (!(*again == *a)) return "canonical spelling '" + canonical + "' parses to a different address";
  return {};
}

// A test file parses to tests or to positioned diagnostics, whatever its bytes; every
// diagnostic points inside the file.
inline std::string check_testfile_property(std::string_view bytes) {
  auto r = testing::parse_test_text(std::string(bytes), "fuzz.test");
  std::size_t lines = 1;
  for (char c : bytes) lines += c == '\n';
  for (const auto& d : r.diagnostics.items())
    if (d.line > lines) return "diagnostic at line " + std::to_string(d.line) + " beyond the file's " + std::to_string(lines);
  (void)render_all(r.diagnostics, "fuzz.test", bytes);
  return {};
}

}  // namespace softslc::fuzz
