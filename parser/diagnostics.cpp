#include "parser/diagnostics.h"

#include <algorithm>
#include <map>
#include <set>
#include <tuple>

#include "parser/limits.h"

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

// Where each line of a text starts: built once per rendering, so finding the line of each of n
// diagnostics costs O(log lines), not a rescan of the file.
class LineIndex {
 public:
  explicit LineIndex(std::string_view source) : source_(source) {
    starts_.push_back(0);
    for (std::size_t i = 0; i < source.size(); ++i)
      if (source[i] == '\n') starts_.push_back(i + 1);
  }
  std::string_view line(std::uint32_t number) const {
    if (number == 0 || number > starts_.size()) return {};
    const std::size_t start = starts_[number - 1];
    if (start > source_.size()) return {};
    auto end = source_.find('\n', start);
    auto text = source_.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start);
    if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
    return text;
  }

 private:
  std::string_view source_;
  std::vector<std::size_t> starts_;
};

std::string_view severity_word(Severity s) {
  switch (s) {
    case Severity::Error: return "error";
    case Severity::Warning: return "warning";
    case Severity::Note: return "note";
  }
  return "error";
}

// At most this much of a source line is shown under a diagnostic: a window around the column.
constexpr std::size_t kExcerptWidth = 160;

std::string render_with_line(const Diagnostic& d, std::string_view source_name, std::string_view text, bool show) {
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
  if (show) {
    // A long line (a 220 KB rung) is shown as a window around the column, so the output of
    // many errors stays proportional to their number, not to the line's length.
    std::size_t first = 0;
    std::uint32_t column = d.column;
    std::string excerpt;
    if (text.size() > kExcerptWidth) {
      const std::size_t col0 = column > 0 ? column - 1 : 0;
      first = col0 > kExcerptWidth / 2 ? std::min(col0 - kExcerptWidth / 2, text.size() - kExcerptWidth) : 0;
      excerpt = (first > 0 ? "..." : "") + std::string(text.substr(first, kExcerptWidth)) +
                (first + kExcerptWidth < text.size() ? "..." : "");
      if (first > 0) column = static_cast<std::uint32_t>(col0 - first + 1 + 3);
      text = excerpt;
    }
    out += text;
    out += '\n';
    // Keep tabs so the caret lines up under the offending column in a terminal.
    std::string pad;
    for (std::uint32_t i = 1; i < column && i - 1 < text.size(); ++i) pad += text[i - 1] == '\t' ? '\t' : ' ';
    out += pad + "^\n";
  }
  return out;
}

}  // namespace

std::string render(const Diagnostic& d, std::string_view source_name, std::string_view source) {
  const bool show = d.line > 0 && !source.empty();
  return render_with_line(d, source_name, show ? LineIndex(source).line(d.line) : std::string_view(), show);
}

std::string render_all(const DiagnosticList& list, std::string_view source_name, std::string_view source) {
  std::string out;
  if (list.items().empty()) return out;
  // As compilers do: at most kMaxErrorsPerFile errors and warnings, kMaxErrorsPerLine per line,
  // exact repeats (position and message) dropped; a note goes with the diagnostic before it.
  // The rest are counted in one closing note, so 20,000 errors on one 220 KB line render in
  // linear time and a few kilobytes.
  const LineIndex lines(source);
  std::size_t kept = 0, suppressed = 0;
  bool last_kept = true;
  std::map<std::uint32_t, std::size_t> per_line;
  std::set<std::tuple<std::uint32_t, std::uint32_t, std::string_view>> seen;
  for (const auto& d : list.items()) {
    if (d.severity == Severity::Note) {
      if (!last_kept) continue;
    } else {
      last_kept = kept < kMaxErrorsPerFile && (d.line == 0 || per_line[d.line] < kMaxErrorsPerLine) &&
                  seen.emplace(d.line, d.column, d.message).second;
      if (!last_kept) {
        ++suppressed;
        continue;
      }
      ++kept;
      if (d.line > 0) ++per_line[d.line];
    }
    const bool show = d.line > 0 && !source.empty();
    out += render_with_line(d, source_name, show ? lines.line(d.line) : std::string_view(), show);
  }
  if (suppressed > 0)
    out += std::string(source_name) + ": note: " + std::to_string(suppressed) +
           " more diagnostic(s) not shown (at most " + std::to_string(kMaxErrorsPerFile) + " per file and " +
           std::to_string(kMaxErrorsPerLine) + " per line; repeats dropped)\n";
  return out;
}

}  // namespace softslc
