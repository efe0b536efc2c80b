// softslc bytecode: the compiled form of a ladder program.
//
// Every program file compiles to a run of 32-bit words in one code array. An instruction is a
// header word followed by its operand words:
//
//   header word
//    31        24 23     20 19     16 15                               0
//   +------------+---------+---------+----------------------------------+
//   |     op     |    n    |  flags  |               aux                |
//   +------------+---------+---------+----------------------------------+
//     op     Op: an instruction-table Opcode (same number) or a structural op (SOR..EOF)
//     n      number of operand words that follow (0-15)
//     flags  bit 0 DYN    an operand is resolved at run time (indexed, indirect, M0/M1), or a
//                         module instruction: the interpreter checks for a fault after it
//            bit 1 FLOAT  math/compare/move in single-precision float (an operand is F)
//            bit 2 A      op-specific: TON/TOF/RTO 1.0 s time base; SOR rung holds an MCR;
//                         MCR unconditional (closes the zone)
//            bit 3 B      op-specific: TON/TOF/RTO 1 ms time base (MicroLogix); COP pre-resolved
//                         (direct source and destination that lie inside their files: aux holds
//                         the number of words copied, and nothing is resolved at run time)
//     aux    SOR: rung number in its file; RES: FileType of the element; BTR/BTW/DEM: the
//            chassis slot of the module that executes it; COP with B: words copied; else 0
//
//   operand word
//    31    28 27      24 23                                              0
//   +--------+----------+-------------------------------------------------+
//   |  mode  |             payload (28 bits)                              |
//   +--------+----------+-------------------------------------------------+
//     BIT    |   bit    |  word index (24 bits)                           |   b = W[word] bit
//     WORD      word index of a signed 16-bit word (or of a T/C/R element's first word)
//     LONG      word index of a 32-bit integer (two words)
//     FLOAT     word index of an IEEE single (two words)
//     IMM       signed 28-bit integer constant
//     KINT      index into int_constants (integers that do not fit 28 bits)
//     KFLOAT    index into float_constants
//     DYN       index into dyn (a DynOperand resolved through the checked path each time)
//     TARGET    code offset (JMP: the SOR of the LBL rung; JSR: the first word of the file)
//
// Instruction operands are encoded in instruction-box order, one word per operand of the
// instruction-table row (spec(op).operands), so the disassembler labels them from the table;
// literals (time base in hundredths of a second, presets, lengths, labels, file numbers) are IMM
// words. JMP and JSR carry one extra TARGET word after their table operand.
//
// Rung logic is a tiny register machine: `rung` is the current rung condition, and a stack of
// (entry, acc) pairs implements branches. Input instructions AND their result into `rung`;
// output instructions act on `rung` and leave it unchanged, so a leg that ends in an output
// contributes its condition to the branch like any other leg.
//
//   op      operands          meaning
//   SOR     aux=rung          rung := not (inside a false MCR zone) or A; W[S:3] watchdog check
//   BST                       push (entry := rung, acc := false)
//   NXB                       acc := acc or rung; rung := entry
//   BND                       rung := acc or rung; pop
//   EOF                       end of file: return from a subroutine, or end the program scan
//   XIC     b                 rung := rung and b
//   XIO     b                 rung := rung and not b
//   OTE     b                 b := rung
//   OTL     b                 if rung then b := 1
//   OTU     b                 if rung then b := 0
//   OSR     b                 out := rung and not b; b := rung; rung := out
//   TON     t tb pre acc      on-delay timer on element t (RM 2-9)
//   TOF     t tb pre acc      off-delay timer (RM 2-10)
//   RTO     t tb pre acc      retentive timer
//   CTU     c pre acc         if rung rises then c.ACC += 1 (wrap +32767 -> -32768, OV)
//   CTD     c pre acc         if rung rises then c.ACC -= 1 (wrap -32768 -> +32767, UN)
//   RES     e                 if rung then clear e's ACC/POS and status bits
//   EQU NEQ LES LEQ GRT GEQ a b      rung := rung and (a op b)
//   LIM     lo t hi           rung := rung and (lo<=hi ? lo<=t<=hi : t>=lo or t<=hi)
//   MEQ     s m c             rung := rung and ((s and m) == (c and m))
//   ADD SUB MUL DIV a b d     if rung then d := a op b, S:0 flags, S:2/14 overflow rule
//   NEG     s d               if rung then d := -s
//   CLR     d                 if rung then d := 0
//   AND OR XOR a b d          if rung then d := a op b (bitwise)
//   NOT     s d               if rung then d := not s
//   MOV     s d               if rung then d := s (converted)
//   MVM     s m d             if rung then d := (s and m) or (d and not m)
//   COP     #s #d n           if rung then copy n destination elements as raw words (B: aux words,
//                             spans resolved by the compiler)
//   FLL     s #d n            if rung then fill n destination elements with s
//   BSL BSR #f r b n          on a rising rung shift the bit array f by one (source bit b)
//   SQO SQC SQL ...           sequencer output / compare / load on a rising rung
//   FFL FFU LFL LFU ...       FIFO / LIFO load and unload on a rising rung
//   JMP     label, TARGET     if rung then pc := TARGET
//   LBL     label             no-op (a jump target)
//   JSR     file, TARGET      if rung then call file (depth checked)
//   SBR                       no-op (subroutine entry marker)
//   RET                       if rung then return to the caller
//   END                       end of file, written explicitly (as EOF)
//   TND                       if rung then end the program scan
//   MCR                       A: close the zone; else open a zone whose state is rung
//   IIM IOM slot mask n       if rung then immediate input / output of n slot words under mask
//   CPT     d, IMM(expr)      if rung then d := the expression exprs[expr] (RPN on a fixed stack)
//   BTR BTW DEM ...           module instructions: operands resolved, then executed by the
//                             module in slot aux (Module::execute); DYN is always set
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "instructions/instruction_table.h"
#include "instructions/processor.h"
#include "parser/expression.h"
#include "parser/program.h"
#include "vm/data_table.h"
#include "vm/module.h"

namespace softslc {

// Bytecode ops: the instruction table's opcodes (same numbers, generated from the table), then
// the structural ops.
enum class Op : std::uint8_t {
#define OPERAND(...) 0
#define SOFTSLC_INSTRUCTION(mnemonic, ...) mnemonic,
#include "instructions/instruction_table.def"
#undef SOFTSLC_INSTRUCTION
#undef OPERAND
  SOR,
  BST,
  NXB,
  BND,
  EOF_,
};

inline constexpr std::size_t kOpCount = static_cast<std::size_t>(Op::EOF_) + 1;
static_assert(static_cast<std::size_t>(Op::SOR) == kInstructionCount, "structural ops follow the table's opcodes");

constexpr Op to_op(Opcode o) { return static_cast<Op>(static_cast<std::uint8_t>(o)); }
constexpr bool is_instruction(Op o) { return static_cast<std::size_t>(o) < kInstructionCount; }
constexpr Opcode to_opcode(Op o) { return static_cast<Opcode>(static_cast<std::uint8_t>(o)); }
std::string_view mnemonic(Op o);

namespace bc {

enum Mode : std::uint32_t {
  kBit = 0,
  kWord = 1,
  kLong = 2,
  kFloat = 3,
  kImm = 4,
  kKInt = 5,
  kKFloat = 6,
  kDyn = 7,
  kTarget = 8,
};

inline constexpr std::uint32_t kFlagDyn = 1;
inline constexpr std::uint32_t kFlagFloat = 2;
inline constexpr std::uint32_t kFlagA = 4;
inline constexpr std::uint32_t kFlagB = 8;

inline constexpr std::uint32_t kPayloadMask = 0x0FFFFFFFu;
inline constexpr std::uint32_t kWordMask = 0x00FFFFFFu;
inline constexpr std::uint32_t kMaxWordIndex = kWordMask;
inline constexpr std::int32_t kImmMin = -(1 << 27);
inline constexpr std::int32_t kImmMax = (1 << 27) - 1;

constexpr std::uint32_t header(Op op, std::uint32_t n, std::uint32_t flags, std::uint32_t aux) {
  return (static_cast<std::uint32_t>(op) << 24) | ((n & 0xF) << 20) | ((flags & 0xF) << 16) | (aux & 0xFFFF);
}
constexpr Op op_of(std::uint32_t h) { return static_cast<Op>(h >> 24); }
constexpr std::uint32_t count_of(std::uint32_t h) { return (h >> 20) & 0xF; }
constexpr std::uint32_t flags_of(std::uint32_t h) { return (h >> 16) & 0xF; }
constexpr std::uint32_t aux_of(std::uint32_t h) { return h & 0xFFFF; }

constexpr std::uint32_t operand(Mode m, std::uint32_t payload) {
  return (static_cast<std::uint32_t>(m) << 28) | (payload & kPayloadMask);
}
constexpr std::uint32_t bit_operand(std::uint32_t word, int bit) {
  return (static_cast<std::uint32_t>(kBit) << 28) | ((static_cast<std::uint32_t>(bit) & 0xF) << 24) | (word & kWordMask);
}
constexpr Mode mode_of(std::uint32_t o) { return static_cast<Mode>(o >> 28); }
constexpr std::uint32_t payload_of(std::uint32_t o) { return o & kPayloadMask; }
constexpr std::uint32_t word_of_bit(std::uint32_t o) { return o & kWordMask; }
constexpr unsigned bit_of(std::uint32_t o) { return (o >> 24) & 0xF; }
constexpr std::int32_t imm_of(std::uint32_t o) {
  // Sign-extend the 28-bit payload.
  return static_cast<std::int32_t>(o << 4) >> 4;
}
constexpr std::uint32_t imm(std::int32_t v) { return operand(kImm, static_cast<std::uint32_t>(v)); }

}  // namespace bc

// An operand whose location is computed each time it is used: indexed (#N7:10 + S:24),
// indirect (N7:[N10:1], N[N10:0]:5, B3/[N7:0]) or in a module's M0/M1 file. The interpreter
// resolves it through one checked function that can only produce an index inside the data
// table, or a fault.
struct DynOperand {
  Address address;                 // as written, for messages and listings
  FileType type = FileType::Integer;
  ValueType vtype = ValueType::Int16;
  bool indexed = false;            // add S:24 to the element (not for a file instruction's '#')
  bool bit_offset = false;         // B3/[N7:0]: the pointer is a bit offset into the file
  int file = 0;                    // static file number (when ptr_file < 0)
  int element = 0;                 // static element or slot (when ptr_element < 0)
  int word = -1;                   // sub-element / slot word (when ptr_word < 0); -1 = none
  int bit = -1;                    // static bit (when ptr_bit < 0); -1 = whole word
  std::int32_t ptr_file = -1;      // word indices of the indirect pointers, -1 = not indirect
  std::int32_t ptr_element = -1;
  std::int32_t ptr_word = -1;
  std::int32_t ptr_bit = -1;
  // M0/M1: the module's immediate accessor is called (element = slot, word = M-file word).
  bool mfile = false;
  MFile which = MFile::M0;
  // The M0/M1 access-time row of this operand position (from the instruction table), charged
  // through ScanTimeModel::mfile_access_cost at each access.
  MFileAccess access_row = MFileAccess::OtherM;
};

// A compiled CPT expression: the RPN list of parser/expression.h with each operand compiled to an
// ordinary operand word. The CPT instruction's second operand is IMM(index into `exprs`).
struct CompiledExprStep {
  ExprCode code = ExprCode::Push;
  std::uint32_t operand = 0;  // Push: the operand word
};
// The interpreter evaluates on a fixed stack of this many values; kMaxExpressionLength bounds an
// expression to at most 128 operands, so its stack never needs more.
inline constexpr int kMaxExprStack = 128;
struct CompiledExpr {
  std::vector<CompiledExprStep> steps;
  bool float_mode = false;  // computes in single precision (an F operand, float constant or function)
};

struct CompiledRung {
  std::uint32_t offset = 0;  // code index of its SOR
  SourcePos pos;
};

struct CompiledFile {
  int number = 2;
  std::uint32_t begin = 0;  // first code word (the first SOR, or the EOF of an empty file)
  std::uint32_t end = 0;    // one past the EOF word
  std::vector<CompiledRung> rungs;
};

// A DATALOG queue with its fields resolved against the layout (vm/ml_data_log.h runs it).
struct CompiledDataLog {
  int number = 0;
  int records = 0;
  bool date = false;
  bool time = false;
  char delimiter = ',';
  std::vector<Location> fields;
};

struct CompiledProgram {
  ProcessorModel processor;
  std::string source_name;
  std::vector<std::uint32_t> code;
  std::vector<CompiledFile> files;       // in file-number order
  std::array<std::int16_t, 256> file_index{};  // file number -> index in `files`, -1 = none
  std::vector<DynOperand> dyn;
  std::vector<std::int64_t> int_constants;
  std::vector<float> float_constants;
  std::vector<CompiledExpr> exprs;  // CPT expressions
  std::shared_ptr<const DataTableLayout> layout;
  std::vector<std::uint16_t> initial_words;  // the data table at download (DATA blocks, literals)
  std::vector<SlotConfig> slots;
  std::vector<ForceBlock> forces;
  int max_branch_depth = 0;  // deepest BST nesting of any rung
  std::uint16_t program_checksum = 0;  // what RPC reads (program_checksum() in vm/compiler.h); 0 without an RPC
  std::vector<CompiledDataLog> data_logs;  // DATALOG queues (MicroLogix 1100, 1400, 1500 LRP)

  const CompiledFile* file(int number) const {
    if (number < 0 || number > 255 || file_index[static_cast<std::size_t>(number)] < 0) return nullptr;
    return &files[static_cast<std::size_t>(file_index[static_cast<std::size_t>(number)])];
  }
};

// Deepest branch nesting the interpreter supports in one rung.
inline constexpr int kMaxBranchDepth = 16;

}  // namespace softslc
