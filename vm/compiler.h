// The compiler: a loaded Program -> CompiledProgram (data-table layout, initial data, bytecode).
//
// It works in two passes. The first decides the data table: which files exist (the default
// files O0 I1 S2 B3 T4 C5 R6 N7, F8 where the processor has floats, and every user file 9-255
// that a DATA block or an address names), each file's type (one per file number) and element
// count (the largest of its DATA block and the highest element the program addresses directly,
// including the ranges file instructions cover; at most 256). Indexed and indirect addresses do
// not grow files: the SLC does not either (RM E-11), and they are checked at run time.
//
// The second pass emits each program file's rungs as bytecode (see bytecode.h), resolving every
// direct operand to a data-table word index, so the interpreter never parses or looks anything
// up. Indexed, indirect and M0/M1 operands become DynOperands, resolved at run time through one
// checked path. Timer, counter and control literals (preset, accum, length, position) become the
// element's initial PRE/ACC/LEN/POS unless a DATA block gives them; the first instruction that
// names an element wins.
//
// The compiler re-checks what it depends on (types, ranges, labels, files) and reports problems
// as CompileErrors rather than trusting the checker, so a Program built by hand cannot produce
// bytecode that indexes outside the data table. Specialty-module instructions (BTR, BTW, DEM)
// go through CompileOptions::module_instruction; with no module support installed they are
// rejected with a clear error, never silently dropped.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "parser/program.h"
#include "vm/bytecode.h"

namespace softslc {

struct CompileError {
  int file = -1;
  int rung = -1;
  SourcePos pos;
  std::string message;
  // "file 2 rung 3 (line 12): message"
  std::string to_string() const;
};

// Decides whether a specialty-module instruction can be compiled: returns an error message, or
// nullopt to accept it. Until the module framework lands the default refuses BTR/BTW/DEM.
using ModuleInstructionHook = std::function<std::optional<std::string>(const Instruction&)>;

struct CompileOptions {
  // Replaces the program's START processor (for example to run a 5/04 program as a 5/05).
  std::optional<ProcessorModel> processor;
  ModuleInstructionHook module_instruction;
};

struct CompileResult {
  std::optional<CompiledProgram> program;
  std::vector<CompileError> errors;
  bool ok() const { return program.has_value(); }
  std::string render() const;  // one error per line
};

CompileResult compile(const Program& program, const CompileOptions& options = {});

// The checksum RPC reads (1747-RM001G p. 7-23: "a 16-bit value that is calculated for the entire
// ladder logic image, excluding the data table values"). The manuals do not give the algorithm;
// softslc's (docs/semantics.md "RPC"): CRC-32 (IEEE) of the program files in file-number order, each
// as "LADDER n" and its rungs' canonical text (format_rung) one per line, folded to 16 bits (high
// half XOR low half). Any change to a rung changes the text; data, comments, symbols, file names
// and the chassis do not enter it.
std::uint16_t program_checksum(const Program& program);

// The message the default hook gives for a module instruction.
std::string module_instruction_unsupported(Opcode op);

// The chassis slot a specialty-module instruction addresses: the slot of its first M0/M1 operand
// (BTR/BTW buffer M1:e.x00 / M0:e.x00), else its literal operand labelled "slot" in the
// instruction table (DEM). The compiler stores it in the instruction header's aux field and the
// interpreter hands the instruction to that slot's module. nullopt when neither is written.
std::optional<int> module_instruction_slot(const Instruction& in);

}  // namespace softslc
