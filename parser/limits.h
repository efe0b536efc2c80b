// Limits on what softslc reads, in one place.
//
// Every input has a size limit and every recursive parser or checker a depth limit, so a hostile
// or broken file costs a positioned error, never a stack overflow, unbounded memory or minutes of
// CPU. Where the SLC has its own limit the number is the SLC's, so `check` and `run` refuse the
// same programs; elsewhere the number is far beyond anything a real program, test or bench file
// needs (docs/robustness.md, "Limits").
#pragma once

#include <cstddef>

namespace softslc {

// Deepest branch nesting in one rung. The loader refuses a 17th nested BST while parsing (so no
// recursive walk of a rung — checker, formatter, compiler — can be driven deep), and the
// interpreter sizes its branch stack from the same number (vm/bytecode.h kMaxBranchDepth, tied
// to this by a static_assert in vm/compiler.cpp).
inline constexpr int kMaxBranchNesting = 16;

// Rungs in one program file: the compiled program numbers them in 16 bits.
inline constexpr std::size_t kMaxRungsPerFile = 65535;

// Nesting of parentheses in a test file's expression and of blocks in a bench file.
inline constexpr int kMaxExpressionNesting = 64;
inline constexpr int kMaxBenchNesting = 64;

// Steps in one test file, a table-driven test's rows expanded (the largest shipped test file has
// about 220). Each parsed step holds its condition tree, so the limit bounds memory and time.
inline constexpr std::size_t kMaxStepsPerTestFile = 10000;

// Errors reported for one file. Beyond these, one line saying how many more were suppressed:
// a compiler's behaviour, and what keeps a file of 80,000 bad rungs linear.
inline constexpr std::size_t kMaxErrorsPerFile = 100;
inline constexpr std::size_t kMaxErrorsPerLine = 5;

// Largest program, test, bench, JSON or state file read (the largest real export in
// ../shared/fixtures is well under 1 MB; a full SLC 5/05 program is a few MB of text).
inline constexpr std::size_t kMaxInputFileBytes = 64u * 1024u * 1024u;

}  // namespace softslc
