// Positioned diagnostics in the gcc style.
//
// Every stage that reads user input (program, test, bench and state files, command lines)
// reports problems as Diagnostics, collected in a DiagnosticList, so a file with several
// independent errors reports them all. Rendering is `FILE:LINE:COL: error: message`, then the
// offending source line and a caret under the column, exactly as gcc does, which editors and CI
// log viewers already understand.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace softslc {

enum class Severity : std::uint8_t { Error, Warning, Note };

struct Diagnostic {
  Severity severity = Severity::Error;
  std::uint32_t line = 0;    // 1-based; 0 = no position (whole file)
  std::uint32_t column = 0;  // 1-based
  std::string message;
};

class DiagnosticList {
 public:
  void error(std::uint32_t line, std::uint32_t column, std::string message);
  void warning(std::uint32_t line, std::uint32_t column, std::string message);
  void note(std::uint32_t line, std::uint32_t column, std::string message);

  bool has_errors() const { return errors_ > 0; }
  std::size_t error_count() const { return errors_; }
  std::size_t warning_count() const { return warnings_; }
  const std::vector<Diagnostic>& items() const { return items_; }
  // Sorts by position (stable, so diagnostics at one position keep their order).
  void sort_by_position();

 private:
  std::vector<Diagnostic> items_;
  std::size_t errors_ = 0;
  std::size_t warnings_ = 0;
};

// Renders one diagnostic: "name:line:col: error: message\n<source line>\n<caret>\n".
// `source` is the whole file text (to show the line); pass empty to omit the excerpt.
std::string render(const Diagnostic& d, std::string_view source_name, std::string_view source);
// Renders all, in order.
std::string render_all(const DiagnosticList& list, std::string_view source_name, std::string_view source);

}  // namespace softslc
