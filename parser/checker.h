// Semantic checks of a parsed program against the instruction table, the processor and the
// chassis configuration.
//
// The checker resolves symbols, then walks every rung and reports, with positions: unknown
// symbols; wrong operand count or kind (from the instruction table); literals out of range;
// addresses the processor or chassis cannot have (bit > 15, element beyond the file's limit,
// I/O on an empty slot or beyond the slot's image, M0/M1 on a module without M files or beyond
// the module's file size, M0/M1 where the SLC forbids them); instructions the processor lacks;
// unbalanced or misplaced structure (outputs where the SLC does not allow them, LBL/SBR not
// first, END not last, MCR rules); undefined or duplicate labels and JSR targets; one file
// number used with two file types; DATA and FORCE blocks that do not fit; and, as warnings,
// duplicate OSR storage bits and unknown module catalogs. It never stops at the first problem.
#pragma once

#include <set>
#include <span>
#include <string>
#include <string_view>

#include "parser/diagnostics.h"
#include "parser/program.h"

namespace softslc {

// Checks `program` and resolves its symbol operands in place. Adds diagnostics to `diags`.
// `files_missing_rungs`: program files from which the loader dropped a rung with a syntax error;
// what could follow from the missing rung (a JMP whose label it held) is not reported there.
void check_program(Program& program, DiagnosticList& diags, const std::set<int>& files_missing_rungs = {});

// The program as it would be on another processor (`run --processor`, `scantime --processor`):
// the same text with `processor` in place of the START line's, checked again with that
// processor's rules, so both commands refuse exactly what the checker refuses for it (L files on
// a 1747-L551, ONS on an SLC, ...). The embedded slot 0 follows the new processor. Problems go
// to `diags`; the result is meaningful only when they hold no error.
Program retarget_program(const Program& program, const ProcessorModel& processor, DiagnosticList& diags);

// Checks an address a tool reads or writes — `run --set/--print`, a test file, the C++
// Controller API — by the same rules as a program operand (bit 0-15, the slot's I/O image, the
// element limits, M-file sizes). Returns the first error ("I:1/32: bit number 32 is out of range
// 0-15"), or an empty string. One rule for every entry point: none can write a bit the program
// could not name.
std::string check_tool_address(const Program& program, const Address& a);

// "unknown instruction 'FOO'", or, for a real SLC 500 / MicroLogix instruction the table does not
// have, that it is not supported — so a real instruction does not read like a typo.
std::string unknown_instruction_message(std::string_view name);
// SLC 500 and MicroLogix mnemonics that have no instruction-table row yet: `check` says they are
// "not supported by softslc yet" rather than unknown.
std::span<const std::string_view> real_mnemonics_without_rows();

// The number of words of the status file on this processor.
int status_file_words(const ProcessorModel& p);

// M0/M1 sizes of a slot: explicit M0_SIZE/M1_SIZE, else the catalog default, else 0.
int m0_words(const SlotConfig& slot);
int m1_words(const SlotConfig& slot);

}  // namespace softslc
