// Loading a program: text → Program, with every problem reported as a positioned diagnostic.
//
// load_program() parses the export text statement by statement (see grammar.h), then runs the
// semantic checker (checker.h) on what parsed — every rung without a syntax error, as long as the
// declarations parsed — so one pass reports every independent error. The result holds a Program
// only when there were no errors: a file that fails leaves nothing half-loaded. Warnings do not
// prevent loading.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "parser/diagnostics.h"
#include "parser/program.h"

namespace softslc {

struct LoadResult {
  std::optional<Program> program;  // set only when diagnostics has no errors
  DiagnosticList diagnostics;
  std::string source;              // the text that was loaded (for rendering diagnostics)
  std::string source_name;

  bool ok() const { return program.has_value(); }
  std::string render_diagnostics() const { return render_all(diagnostics, source_name, source); }
};

// Parses and checks program text. `source_name` is used in diagnostics.
LoadResult load_program(std::string text, std::string source_name);
// Reads and loads a file; an unreadable file is reported as a diagnostic, not an exception.
// The format is told by content, not by name: an RSLogix project file (.RSS, an OLE2 compound
// document) is decoded by parser/rss and loaded as the export text it converts to; other
// binary content is refused without echoing it; anything else is export text.
LoadResult load_program_file(const std::filesystem::path& path);
// The same for a file's bytes already in memory (the test runner, the C++ API, the fuzzer).
LoadResult load_program_bytes(std::string bytes, std::string source_name);
namespace rss { struct RungOrigin; }
// The export text a project file converted to (parser/rss), loaded with each diagnostic also
// naming the program file and rung its line came from (`origins`).
LoadResult load_converted_project(std::string text, const std::vector<rss::RungOrigin>& origins, std::string source_name);

// Pasted rungs: rungs copied out of RSLogix as bare text (`SOR ... EOR`, one rung a line, no
// START or LADDER statement). `is_pasted_rungs` tells such a text; `load_pasted_rungs` loads it
// as program file 2 of `processor`, with that processor's default data files and (for fixed and
// MicroLogix controllers) its embedded I/O, exactly as if "START <catalog>" and "LADDER 2" came
// first. Diagnostics keep the pasted text's own line numbers.
bool is_pasted_rungs(std::string_view text);
LoadResult load_pasted_rungs(std::string text, std::string source_name, const ProcessorModel& processor);

// Parses the syntax only (no semantic checks): for tests of the grammar and for tools that
// want the tree of a program with semantic errors.
LoadResult parse_program_syntax(std::string text, std::string source_name);

// Parses one address written alone ("N7:0", "T4:0/DN", "I:1/3"). Returns nullopt and sets
// `error` (with a column) when the text is not an address.
std::optional<Address> parse_address(std::string_view text, std::string* error = nullptr);

// Parses a numeric constant as the program format writes it (decimal, negative, float, 0x..,
// ..h). Returns false when the text is not a number.
struct NumberValue {
  bool is_float = false;
  std::int64_t integer = 0;
  double real = 0.0;
};
bool parse_number_text(std::string_view text, NumberValue& out);

}  // namespace softslc
