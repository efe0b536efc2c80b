// The disassembler: a readable listing of a CompiledProgram, in the spirit of `luac -l`.
//
// Each instruction is one line: its code offset, the mnemonic (indented by branch depth so the
// BST/NXB/BND structure shows), its raw operand words, and after ';' what they mean, labelled
// from the instruction table's box labels. The listing is driven by the same table as the
// compiler and the interpreter; there is no second list of mnemonics or operand layouts here.
//
//   file 2: 2 rungs, code 0-19
//   rung 0
//     0000  SOR
//     0001  XIC   w1/0  ; bit=I:1.0/0
//     0003  BST
//     0004    XIC   w0/0  ; bit=O:2.0/0
//     0006  NXB
//     ...
//
// Raw operand spellings: wN/b bit b of word N, wN word N, lN long at N, fN float at N, #v
// immediate, kN / kfN constant-pool entries, dN dynamic operand N, ->N code offset.
#pragma once

#include <string>

#include "vm/bytecode.h"

namespace softslc {

// The whole program: a data-table map, then every file.
std::string disassemble(const CompiledProgram& program);
// One rung of one file (no header): what the golden-listing tests compare.
std::string disassemble_rung(const CompiledProgram& program, int file, int rung);

}  // namespace softslc
