#include "parser/diagnostics.h"

#include <algorithm>

namespace softslc {

void DiagnosticList::error(std::uint32_t line, std::uint32_t column, std::string message) {
  items_.push_back({Severity::Error, line, column, std::move(message)});
  ++errors_;
}

void DiagnosticList::warning(std::uint32_t line, std::uint32_t column, std::string message) {
  items_.push_back({Severity::Warning, line, column, std::move(message)});
  ++warnings_;
}

void DiagnosticList::note(std::uint32_t line, std::uint32_t column, std::string message) {
  items_.push_back({Severity::Note, line, column, std::move(message)});
}

void DiagnosticList::sort_by_position() {
  std::stable_sort(items_.begin(), items_.end(), [](const Diagnostic& a, const Diagnostic& b) {
    return a.line != b.line ? a.line < b.line : a.column < b.column;
  });
}

namespace {

std::string_view line_of(std::string_view source, std::uint32_t line) {
  std::size_t start = 0;
  for (std::uint32_t l = 1; l < line; ++l) {
    auto nl = source.find('\n', start);
    if (nl == std::string_view::npos) return {};
    start = nl + 1;
  }
  auto end = source.find('\n', start);
  auto text = source.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start);
  if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
  return text;
}

std::string_view severity_word(Severity s) {
  switch (s) {
    case Severity::Error: return "error";
    case Severity::Warning: return "warning";
    case Severity::Note: return "note";
  }
  return "error";
}

}  // namespace

std::string render(const Diagnostic& d, std::string_view source_name, std::string_view source) {
  std::string out(source_name);
  if (d.line > 0) {
    out += ':' + std::to_string(d.line);
    if (d.column > 0) out += ':' + std::to_string(d.column);
  }
  out += ": ";
  out += severity_word(d.severity);
  out += ": ";
  out += d.message;
  out += '\n';
  if (d.line > 0 && !source.empty()) {
    auto text = line_of(source, d.line);
    out += text;
    out += '\n';
    // Keep tabs so the caret lines up under the offending column in a terminal.
    std::string pad;
    for (std::uint32_t i = 1; i < d.column && i - 1 < text.size(); ++i) pad += text[i - 1] == '\t' ? '\t' : ' ';
    out += pad + "^\n";
  }
  return out;
}

std::string render_all(const DiagnosticList& list, std::string_view source_name, std::string_view source) {
  std::string out;
  for (const auto& d : list.items()) out += render(d, source_name, source);
  return out;
}

}  // namespace softslc
