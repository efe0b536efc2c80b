// The declarative SLC 500 instruction table.
//
// Every instruction softslc knows is one row of instruction_table.def. This header expands that
// list into (a) the Opcode enum and (b) a constexpr array of InstructionSpec, one per opcode, in
// the same order, so `spec(op)` is an array index. The parser checks operand count and kinds
// against the spec, the compiler reads the operand kinds and access modes, the VM dispatches on
// the opcode, the disassembler prints the mnemonic and box labels, and the scan-time model picks
// the M0/M1 access-time row from each operand's MFileAccess class, and the runtime reads each
// row's Repeat class to decide whether a program's scans may repeat. Adding an instruction is one
// row in the .def file plus one handler in the VM.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

namespace softslc {

// What a program may write in an operand position.
enum class OperandKind : std::uint8_t {
  Bit,             // a bit address: B3:0/1, I:1/0, T4:0/DN, M1:2.0/3
  Source,          // a word address or a numeric constant, read by the instruction
  Dest,            // a word address written by the instruction (never a constant)
  File,            // a '#' file address: the start of a range of elements
  Timer,           // a T-file element: T4:0
  Counter,         // a C-file element: C5:0
  Control,         // an R-file element: R6:0
  Resettable,      // a T, C or R element (RES)
  TimeBase,        // the literal 1.0 or 0.01 (seconds per ACC count)
  Literal,         // an integer constant stored with the instruction (presets, lengths)
  Label,           // a JMP/LBL label number
  ProgramFile,     // a subroutine program file number (JSR)
  SlotWord,        // an I: or O: word naming a chassis slot (IIM, IOM)
  Buffer,          // an M0/M1 block-transfer buffer address M0:e.x00 / M1:e.x00
  ControlBlock3,   // a 3-word integer control block (BTR, BTW)
  ControlBlock70,  // a 70-word integer control block (DEM)
  ControlBlock23,  // a 23-word integer control block (PID: 1747-RM001G p. 9-3, 9-5)
  // Like Source and Dest, but the instruction works on integer words only: an F address or a
  // floating-point constant is refused by `check` (the bitwise instructions, SCL, DDV, TOD, ...).
  WordSource,      // an integer word address or an integer constant
  WordDest,        // an integer word address written by the instruction
  Expression,      // a CPT expression (parser/expression.h)
  String,          // an ST element (42 words; the ASCII instructions, 1747-RM001G ch. 10)
  // MSG (issue 15; docs/semantics.md "MSG"): the words of the instruction box and setup screen.
  MessageCommand,  // READ or WRITE
  MessageDevice,   // the target device: 500CPU, 485CIF or PLC5
  MessageRoute,    // LOCAL or REMOTE
  MessageBlock,    // the control block: an N-file element, as many words as the "control block length"
  MessageData,     // this controller's data table address: a direct word-level element address
  RemoteAddress,   // the target's data table address (500CPU, PLC5) or CIF word offset (485CIF),
                   // never looked up in this program: it names the other controller's data table
  MessageElement,  // the MicroLogix MSG's MG file element (MG11:0): its 25 words are the instruction's
                   // parameters and status (1762-RM001C p. 21-4)
  MessageTarget,   // the MicroLogix MSG's target: a node number on channel 0 (DH-485), the RI routing
                   // element (RI12:0) on the 1100/1400 channel 1 Ethernet, whose words 1-2 hold the target's
                   // IP address (1766-RM001A p. 435; docs/semantics.md "The MicroLogix MSG on Ethernet")
};

// Whether an operand kind is written as a destination word (never a constant).
constexpr bool is_dest_kind(OperandKind k) { return k == OperandKind::Dest || k == OperandKind::WordDest; }

// Whether the instruction reads the operand, writes it, or both.
enum class OperandAccess : std::uint8_t { Read, Write, ReadWrite };

// The row of the M0/M1 access-time table charged when this operand is an M-file address.
// The 1747-SN (appendix B) and 1203-SM1 (appendix A) manuals list the same rows.
enum class MFileAccess : std::uint8_t {
  NoM,         // an M0/M1 address is forbidden here (p. B-2 restrictions)
  ExamineBit,  // "XIC or XIO"
  OutputBit,   // "OTU, OTE, or OTL"
  CopToM,      // "COP to M file" (multi-word: base + per word)
  CopFromM,    // "COP from M file" (multi-word)
  FllToM,      // "FLL" (multi-word)
  MvmToM,      // "MVM to M file"
  OtherM,      // "any source or destination M file address"
};

// Whether an MFileAccess row is charged per instruction plus per word (the table's
// "per Multi-Word Instruction" column) rather than per bit instruction or word.
constexpr bool is_multi_word(MFileAccess a) {
  return a == MFileAccess::CopToM || a == MFileAccess::CopFromM || a == MFileAccess::FllToM;
}

// Where an instruction may stand in a rung.
enum class Role : std::uint8_t {
  Input,    // condition: reads rung-in, produces rung-out
  Output,   // acts on the rung condition; stands at the right of a rung or branch leg
  Leading,  // must be the first instruction of its rung (LBL, SBR)
};

// Which processors implement an instruction (checked against the START line's catalog).
enum class Requirement : std::uint8_t {
  Any,               // every SLC 5/0x and MicroLogix
  BlockTransfer,     // BTR/BTW: SLC 5/03 OS302, 5/04 OS401, 5/05 OS501 and later (1747-SN p. 5-5)
  DeviceNetMessage,  // DEM: SLC 5/03-5/05 OS Series C FRN 10 or later (1747-SDN ch. 8)
  SlcOneShot,        // the one-operand OSR: SLC 500 and MicroLogix 1000 (the 1100-1500 use ONS)
  MicroLogix1100Class,  // MicroLogix 1100, 1200, 1400, 1500 (ONS, two-operand OSR/OSF, CPW, ...)
  Slc502Up,          // SLC 5/02 and later modular processors (RM001 "SLC 5/02" column: SQR, SCL, ENC)
  Os302,             // SLC 5/03 OS302, 5/04 OS401, 5/05 (RM001 4-13: SCP, ABS, CPT, trig, logs, XPY)
  SlcOs302,          // the same SLC processors, not the MicroLogix (RM001 7-15: RHC, TDF in their SLC form)
  SlcPid,            // PID with an N-file control block: SLC 5/02-5/05 (RM001G p. 9-1); the MicroLogix
                     // 1100-1500 PID takes a PD file element instead, which softslc does not have
  // The selectable timed interrupt: SLC 5/02 and later modular processors (RM 11-8). The
  // MicroLogix 1100-1500 have their own STS, on their STI function file (MicroLogixStiFile).
  TimedInterrupt,
  SlcInterruptControl,  // STD/STE: the SLC 5/02-5/05 only (RM 11-14; the MicroLogix use UID/UIE)
  // Instructions that drive the MicroLogix STI function file (the one-operand STS): the
  // MicroLogix 1100, 1200, 1400 and 1500.
  MicroLogixStiFile,
  // ---- I/O interrupts and diagnostics (issue 15) ----
  // The I/O event-driven interrupt's instructions IID, IIE, RPI: the SLC 5/02-5/05 (RM 11-27).
  IoInterrupt,
  // FBC, DDT: the SLC 5/03 OS302, 5/04 OS401 and 5/05 (RM 7-18, firmware history A-9); the
  // MicroLogix instruction sets have no FBC or DDT.
  FileBitCompare,
  // UID, UIE, UIF: the MicroLogix 1100-1500 user interrupt disable/enable/flush, which act on the
  // STI, EII and HSC function files softslc does not simulate yet; the SLC has none of them.
  MicroLogixUserInterrupt,
  // MSG and SVC (RM 12-5): the SLC 5/02's form (7-word control block, one channel) and the
  // SLC 5/03-5/05 form (14 words, channel 0 or 1). The MicroLogix 1100-1500 MSG takes an MG message
  // file element instead (1763/1766-RM001, 1762-RM001C p. 21-3): MicroLogixMessage.
  SlcMessage502,
  SlcMessage,
  MicroLogixMessage,
  SlcCommService,  // SVC without an operand: SLC 5/02-5/05
  // SVC with a channel select (a bit per channel): the SLC 5/03-5/05 and the MicroLogix 1100, 1200,
  // 1400 and 1500 (1762-RM001C p. 21-26, 1763-RM001B p. 344, 1766-RM001A p. 396).
  ChannelSelectService,
  // PTO drives the pulse train output function file PTO:0-1: the MicroLogix 1100, 1200 and 1500
  // (1763-RM001C p. 128 on, 1762-RM001C ch. 6). The MicroLogix 1400's is PTOX on PTOX:0-2 (1766-RM001A
  // p. 146 on).
  MicroLogixPto,
  MicroLogixPtox,
  // RPC: the SLC 5/03 OS302, 5/04 OS401 and 5/05 (1747-RM001G p. 7-23, the same processors as RHC)
  // and the MicroLogix 1400 (1766-RM001A p. 239, whose execution-time table names the 1400 only).
  ProgramChecksum,
  // DLG and the DLS file: the MicroLogix 1100, 1400 and 1500 LRP (AG-UM008C p. 3-58, 1766-RM001A
  // p. 518); not the 1000, the 1200 or the 1500 LSP.
  MicroLogixDataLog,
};

// Whether a program holding the instruction may have its scans repeated (docs/semantics.md
// "Repeated scans"; the REPEAT column of instruction_table.def says why for each class and row).
enum class Repeat : std::uint8_t {
  TableAlone,    // a function of the data table, the rung and the first pass alone
  FunctionFile,  // a MicroLogix function-file instruction: the probe judges the sub-system behind it
  Module,        // acts through the module in its slot, which the probe asks
  Network,       // MSG: acts through the network, which the probe judges when the controller is alone
  KnownTime,     // the table and a time the probe records, before which the repeats end (PID)
  AsciiPort,     // an ASCII channel instruction: the port acts between scans only in its events
  Never,         // rules repeats out
};

struct OperandSpec {
  OperandKind kind;
  OperandAccess access;
  MFileAccess mfile;
  std::string_view label;  // the box label, used in diagnostics and the disassembler
  std::int32_t min;        // literal range (Literal, Label, ProgramFile); unused otherwise
  std::int32_t max;
};

// MSG (SLC 5/03-5/05 form) has 11 operands; FBC and DDT nine (1747-RM001G p. 7-18: three files,
// two control elements with their lengths and positions).
inline constexpr std::size_t kMaxOperands = 11;

enum class Opcode : std::uint8_t {
#define OPERAND(...) 0
#define SOFTSLC_INSTRUCTION(mnemonic, ...) mnemonic,
#include "instructions/instruction_table.def"
#undef SOFTSLC_INSTRUCTION
#undef OPERAND
};

struct InstructionSpec {
  std::string_view mnemonic;
  Opcode opcode;
  Role role;
  Requirement requires_;
  Repeat repeat;
  std::uint8_t operand_count;
  std::array<OperandSpec, kMaxOperands> operands;

  std::span<const OperandSpec> operand_specs() const { return {operands.data(), operand_count}; }
  bool writes_any() const {
    for (const auto& o : operand_specs())
      if (o.access != OperandAccess::Read) return true;
    return false;
  }
};

namespace detail {
template <typename... Ops>
constexpr InstructionSpec make_spec(std::string_view m, Opcode op, Role role, Requirement req, Repeat repeat,
                                    Ops... ops) {
  static_assert(sizeof...(Ops) <= kMaxOperands);
  return InstructionSpec{m, op, role, req, repeat, static_cast<std::uint8_t>(sizeof...(Ops)), {ops...}};
}
}  // namespace detail

inline constexpr InstructionSpec kInstructionTable[] = {
#define OPERAND(kind, access, mfile, label, lo, hi) \
  OperandSpec { OperandKind::kind, OperandAccess::access, MFileAccess::mfile, label, lo, hi }
#define SOFTSLC_INSTRUCTION(mnemonic, role, req, repeat, ...)                                  \
  detail::make_spec(#mnemonic, Opcode::mnemonic, Role::role, Requirement::req, Repeat::repeat \
                    __VA_OPT__(, ) __VA_ARGS__),
#define SOFTSLC_INSTRUCTION_FORM(opcode, text, role, req, repeat, ...)                   \
  detail::make_spec(text, Opcode::opcode, Role::role, Requirement::req, Repeat::repeat \
                    __VA_OPT__(, ) __VA_ARGS__),
#include "instructions/instruction_table.def"
#undef SOFTSLC_INSTRUCTION_FORM
#undef SOFTSLC_INSTRUCTION
#undef OPERAND
};

inline constexpr std::size_t kInstructionCount = std::size(kInstructionTable);

// The row for an opcode (the table is in Opcode order, checked at compile time in the .cpp).
constexpr const InstructionSpec& spec(Opcode op) { return kInstructionTable[static_cast<std::size_t>(op)]; }

// Looks a mnemonic up (exact, upper case). Returns nullptr when unknown. For a mnemonic with
// several forms (OSR: the SLC's one operand, the MicroLogix's two) this is the first row.
const InstructionSpec* find_instruction(std::string_view mnemonic);
// The form of a mnemonic that takes `operand_count` operands; the first row when none does (the
// checker then reports the count). nullptr when the mnemonic is unknown.
const InstructionSpec* find_instruction_form(std::string_view mnemonic, std::size_t operand_count);

std::string_view to_string(OperandKind k);

// The words a keyword operand kind takes (MessageCommand, MessageDevice, MessageRoute), in code
// order: the compiler encodes the word's position. Empty for every other kind.
std::span<const std::string_view> keyword_words(OperandKind k);
// The code of `word` for kind `k` (its position in keyword_words), or nullopt.
std::optional<int> keyword_code(OperandKind k, std::string_view word);
std::string_view to_string(MFileAccess a);

}  // namespace softslc
