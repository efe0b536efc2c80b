// Parsing a test file: text → TestFile, every syntax and structure problem a positioned diagnostic.
//
// The driver splits the text into lines and parses each with grammar::line (test_grammar.h) and
// the actions in test_parser.cpp, so one bad line costs only itself and all independent errors
// in a file are reported. It then assembles tests from the lines: the file-level `program`, test
// headers, their steps, and the rows of table-driven tests. A table-driven test becomes one
// TestCase per row: lines that mention `$NAME` are parsed once per row after textual
// substitution, with columns mapped back to the original line, so an error in a substituted
// value points at the `$NAME` that brought it in and says which row it came from.
//
// Nothing here reads the program: symbols, address ranges and snapshots are resolved by the
// loader (test_loader.h), which calls this first.
#pragma once

#include <string>

#include "parser/diagnostics.h"
#include "tools/testrunner/test_file.h"

namespace softslc::testing {

struct ParseResult {
  TestFile file;
  DiagnosticList diagnostics;  // sorted by position
};

// Parses test-file text. `name` is used in diagnostics and stored in the TestFile.
ParseResult parse_test_text(std::string text, std::string name);

}  // namespace softslc::testing
