// M0/M1 access times: the table of the 1747-SN manual (appendix B, "Access Time", p. B-4) and
// the 1203-SM1 manual (appendix A, "Access Time", p. A-5), as data.
//
// The processor keeps no image of M files; every M0/M1 address an instruction touches is an
// immediate transfer across the backplane, and the manuals give its cost per processor and
// instruction type. Both manuals print the same figures (the 1203-SM1 table has no SLC 5/05
// row; the 1747-SN table gives 5/05 the 5/04 OS400 figures). The instruction table's
// MFileAccess class of an operand selects the row; an instruction with several M operands is
// charged once per M operand. Figures are microseconds, exactly as printed.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "instructions/instruction_table.h"

namespace softslc {

struct MFileAccessRow {
  std::string_view processor;  // ProcessorModel::timing_key(): "5/02B", "5/02C", "5/03", "5/04", "5/05"
  MFileAccess access;          // OtherM on the 5/02 rows stands for "All Types"
  std::int64_t per_access_us;  // "per Bit Instruction or Word of Data" (0 where the table has "--")
  std::int64_t multi_base_us;  // "per Multi-Word Instruction": base ...
  std::int64_t multi_per_word_us;  // ... plus this per word
};

// The whole table, in the manuals' order.
std::span<const MFileAccessRow> mfile_access_table();

// Access time in µs of one M-file operand of class `access` moving `words` words (1 for bit and
// single-word operands; the length for COP/FLL), on the processor with `timing_key`. nullopt
// when the processor has no row (fixed controllers, 5/01, MicroLogix: no specialty M files).
std::optional<std::int64_t> mfile_access_us(std::string_view timing_key, MFileAccess access, int words);

}  // namespace softslc
