#include "vm/runtime.h"

#include "instructions/module_catalog.h"

#include "vm/profile_scan_time_model.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

#include "parser/checker.h"
#include "parser/expression.h"
#include "parser/loader.h"
#include "vm/discrete_io.h"
#include "vm/real_time_clock.h"
#include "vm/word_ops.h"

namespace softslc {

namespace {

// S:1/0-4 mode codes (DF1 p.10-3): 1 program, 6 run, 8 test single scan.
std::uint16_t mode_code(Mode m) {
  switch (m) {
    case Mode::Program: return 1;
    case Mode::Run: return 6;
    case Mode::Test: return 8;
    case Mode::Faulted: return 1;
    case Mode::Suspended: return 3;  // "3 idle (SUS)" (DF1 p. 10-3, facts §3)
  }
  return 1;
}

std::uint16_t clamp_u8(std::int64_t v) { return static_cast<std::uint16_t>(std::clamp<std::int64_t>(v, 0, 255)); }
std::uint16_t clamp_u16(std::int64_t v) { return static_cast<std::uint16_t>(std::clamp<std::int64_t>(v, 0, 32767)); }

// Repeated scans (docs/semantics.md "Repeated scans"). The status words the runtime itself changes
// from one scan to the next while the program changes nothing: S:3 (this scan), S:4 (the free-running
// clock), S:22/S:23 (maximum and average scan), S:33 (the scan toggle bit 9) and S:35 (last scan).
constexpr std::array<int, 6> kRuntimeStatusWords = {status::kWatchdog, status::kClock,    status::kMaxScan,
                                                    status::kAvgScan,  status::kCommBits, status::kLastScanMs};

bool reads_only_program_words(const Address& a, bool file_start = false);

// A direct read of the free-running clock S:4, a bit of it or the whole word: allowed, and the bits
// read noted in `bits` (every bit for the word), because S:4 advances at known times and the repeats
// end before the scan in which a bit the program reads would change (Runtime::
// scans_before_the_clock_bits_change). A write to S:4, or S:4 as a file, a pointer or through an
// index, is still refused: the probe does not compare S:4, so a write there would go unseen.
bool clock_read(const Address& a, std::uint16_t& bits) {
  if (a.type != FileType::Status || a.element != status::kClock || a.is_indirect() || a.indexed || a.word >= 0 ||
      a.bit > 15)
    return false;
  bits = static_cast<std::uint16_t>(bits | (a.bit >= 0 ? 1u << a.bit : 0xFFFFu));
  return true;
}

// A CPT expression's operands are its pushed atoms, constants or addresses as the compiler reads
// them (vm/compiler.cpp expression_operand); an expression that does not parse is never repeated.
// Every atom is read, so S:4 is allowed there as a clock read.
bool expression_reads_only_program_words(const std::string& text, std::uint16_t& clock_bits) {
  ExpressionError err;
  const auto items = parse_expression(text, err);
  if (!items) return false;
  for (const ExprItem& it : *items) {
    if (it.code != ExprCode::Push) continue;
    NumberValue v;
    if (parse_number_text(it.text, v)) continue;
    const auto a = parse_address(it.text);
    if (!a || (!clock_read(*a, clock_bits) && !reads_only_program_words(*a))) return false;
  }
  return true;
}

// An operand a repeated scan would read the same: not one of the runtime's own status words (nor a
// file operand in S, which could span them), and, when resolved at run time (indirect or indexed;
// the '#' of a file operand marks where the file starts, as the compiler reads it, and is no index),
// one that resolves the same (below). An M0/M1 word is allowed: the probe asks its module
// (Runtime::reach). A read of S:4 is allowed (clock_read). So is a function-file word (RTC, STI,
// EII, HSC, PTO/PTOX, DLS, CS): they are data-table words, which the probe compares, and what changes
// them between the program's writes is bounded or judged apart: the clock at its next second, the
// STI at its expiry, an EII only on an input edge (an event or a tool), the HSC only with pulses
// arriving, a PTO only while it runs, CS0:4/MCP only at a MSG start, a servicing (the network's
// quiet_until) or a Modbus master's event.
bool reads_only_program_words(const Operand& op, const OperandSpec* spec, std::uint16_t& clock_bits) {
  if (op.kind == Operand::Kind::Expression) return expression_reads_only_program_words(op.spelling, clock_bits);
  if (!op.is_address()) return true;
  const bool file = spec && (spec->kind == OperandKind::File || spec->kind == OperandKind::String);
  if (spec && spec->access == OperandAccess::Read && !file && clock_read(op.address, clock_bits)) return true;
  // An operand past the instruction's table row is read like a source (none is a file).
  return reads_only_program_words(op.address, file);
}

// A pointer of an indirect address (the N10:1 of N7:[N10:1]) is a direct word: it reads the same
// in the next scan unless the runtime changes it (S:3, S:4 ...), or it is a function-file or M word.
bool pointer_reads_a_program_word(const std::optional<IndirectRef>& r) {
  if (!r) return true;
  if (is_function_file(r->type) || is_mfile(r->type)) return false;
  return r->type != FileType::Status ||
         std::find(kRuntimeStatusWords.begin(), kRuntimeStatusWords.end(), r->element) == kRuntimeStatusWords.end();
}

// An indexed or indirect address is resolved at each use (Interpreter::resolve_common), but never
// outside the file it is written in, whose type is fixed: an index, or an element, word or bit
// pointer, stays in that file or faults, and a file pointer names a file of the same type or faults
// (docs/semantics.md "Indexed and indirect addresses"). A scan that starts from the data table the
// probe started from therefore resolves it to the word the probe did — S:24 and the pointers are
// table words the probe would have shown changed — as long as neither a pointer nor the file is one
// the runtime or a module changes: not the status file (S:3, S:4, S:22, S:23, S:33 and S:35 change
// every scan), not a function file, not an M file. All of that is known from the address itself,
// so nothing is checked while the program runs (decision, issue 20).
bool dynamic_address_resolves_the_same(const Address& a) {
  if (a.type == FileType::Status || is_function_file(a.type) || is_mfile(a.type)) return false;
  return pointer_reads_a_program_word(a.indirect_file()) && pointer_reads_a_program_word(a.indirect_element()) &&
         pointer_reads_a_program_word(a.indirect_word()) && pointer_reads_a_program_word(a.indirect_bit());
}

bool reads_only_program_words(const Address& a, bool file_start) {
  const bool dynamic = a.is_indirect() || (a.indexed && !file_start);
  if (dynamic && !dynamic_address_resolves_the_same(a)) return false;
  if (a.type != FileType::Status) return true;
  if (file_start) return false;
  return std::find(kRuntimeStatusWords.begin(), kRuntimeStatusWords.end(), a.element) == kRuntimeStatusWords.end();
}

// What the repeats need to know of the program besides whether it may repeat: the bits of S:4 it
// reads (every bit when it reads the word), and the finest time base of its timers (1 ms when one
// has the MicroLogix 0.001 s base: its stamp counts milliseconds; else the 10 ms tick).
struct RepeatFacts {
  std::uint16_t clock_bits = 0;
  Nanoseconds timer_tick = kTick;
};

// `interrupt_only`: the elements are in a file that only an interrupt may run (routines_only_by_interrupt).
bool elements_repeatable(const std::vector<RungElement>& elements, RepeatFacts& facts, bool interrupt_only) {
  for (const RungElement& e : elements) {
    if (e.kind == RungElement::Kind::Branch) {
      for (const auto& leg : e.legs)
        if (!elements_repeatable(leg, facts, interrupt_only)) return false;
      continue;
    }
    const InstructionSpec& sp = spec(e.instruction.opcode);
    // The instruction's Repeat class (instructions/instruction_table.def, REPEAT, says why each class
    // may repeat and what judges the state outside the table: the probe's module, network, function-file
    // and known-time checks). No default: a new class must be decided here.
    switch (sp.repeat) {
      case Repeat::TableAlone:
      case Repeat::FunctionFile:
      case Repeat::Module:
      case Repeat::Network:
      case Repeat::KnownTime:
      case Repeat::AsciiPort:
        break;
      case Repeat::Never:
        if (!interrupt_only) return false;
        break;
    }
    for (std::size_t i = 0; i < e.instruction.operands.size(); ++i) {
      const Operand& operand = e.instruction.operands[i];
      const OperandSpec* os = i < sp.operand_count ? &sp.operands[i] : nullptr;
      if (!reads_only_program_words(operand, os, facts.clock_bits)) return false;
      if (os && os->kind == OperandKind::TimeBase && operand.kind == Operand::Kind::Float && operand.real < 0.005)
        facts.timer_tick = kNsPerMs;
    }
  }
  return true;
}

// Calls `f` with every instruction of a rung's elements, branch legs included.
template <class F>
void for_each_instruction(const std::vector<RungElement>& elements, const F& f) {
  for (const RungElement& e : elements) {
    if (e.kind == RungElement::Kind::Branch) {
      for (const auto& leg : e.legs) for_each_instruction(leg, f);
      continue;
    }
    f(e.instruction);
  }
}

// The file a JSR calls (0-255), or -1 for any other instruction.
int jsr_target(const Instruction& in) {
  if (in.opcode != Opcode::JSR || in.operands.empty() || in.operands[0].kind != Operand::Kind::Integer ||
      in.operands[0].integer < 0 || in.operands[0].integer >= 256)
    return -1;
  return static_cast<int>(in.operands[0].integer);
}

// Calls note(address, operand index, spec) for each address the instruction names: its address operands
// (the spec null past the row's operands) and each address atom of a CPT expression (spec null, a
// read). Returns false when an expression does not parse.
template <class Note>
bool each_address(const Instruction& in, const Note& note) {
  const InstructionSpec& sp = spec(in.opcode);
  bool parsed = true;
  for (std::size_t i = 0; i < in.operands.size(); ++i) {
    const Operand& operand = in.operands[i];
    if (operand.kind == Operand::Kind::Expression) {
      ExpressionError err;
      const auto items = parse_expression(operand.spelling, err);
      if (!items) {
        parsed = false;
        continue;
      }
      for (const ExprItem& it : *items) {
        NumberValue v;
        if (it.code != ExprCode::Push || parse_number_text(it.text, v)) continue;
        if (const auto a = parse_address(it.text)) note(*a, i, nullptr);
      }
      continue;
    }
    if (!operand.is_address()) continue;
    note(operand.address, i, i < sp.operand_count ? &sp.operands[i] : nullptr);
  }
  return parsed;
}

// The program files that no JSR chain from the main file (2) reaches, whatever its rungs: only an
// interrupt (an STI, DII, I/O event, EII or HSC routine, the fault routine) can run them. A repeat
// never stands for a scan that runs an interrupt routine: the probe is not repeated when one ran in
// it (Interpreter::routine_runs), and what makes one run — a pending DII, a configured ISR, an EII or
// HSC interrupt queued, an STI expiry — ends the repeats or keeps them from starting. So an
// instruction that is never repeated (an IOM sending the DII's batch lamp) may stand in such a file
// (decision, issue 20, session 20: docs/semantics.md "Repeated scans").
std::array<bool, 256> routines_only_by_interrupt(const Program& program) {
  std::array<std::vector<int>, 256> calls{};
  for (const ProgramFile& f : program.files) {
    if (f.number < 0 || f.number >= 256) continue;
    for (const Rung& r : f.rungs)
      for_each_instruction(r.elements, [&](const Instruction& in) {
        if (const int target = jsr_target(in); target >= 0) calls[static_cast<std::size_t>(f.number)].push_back(target);
      });
  }
  std::array<bool, 256> reached{};
  std::vector<int> todo = {2};
  reached[2] = true;
  while (!todo.empty()) {
    const int f = todo.back();
    todo.pop_back();
    for (const int g : calls[static_cast<std::size_t>(f)])
      if (!reached[static_cast<std::size_t>(g)]) {
        reached[static_cast<std::size_t>(g)] = true;
        todo.push_back(g);
      }
  }
  std::array<bool, 256> only{};
  for (std::size_t n = 0; n < only.size(); ++n) only[n] = !reached[n];
  return only;
}

// Whether the program's scans may repeat, and what `facts` the repeats need.
bool program_scans_repeatable(const Program& program, RepeatFacts& facts) {
  facts = {};
  const std::array<bool, 256> interrupt_only = routines_only_by_interrupt(program);
  for (const ProgramFile& f : program.files) {
    const bool only = f.number >= 0 && f.number < 256 && interrupt_only[static_cast<std::size_t>(f.number)];
    for (const Rung& r : f.rungs)
      if (!elements_repeatable(r.elements, facts, only)) return false;
  }
  return true;
}

// Timers accumulating across ticks (docs/semantics.md "Timers accumulating across ticks"). A repeat may
// carry a timing timer's ACC and stamp forward only when nothing but the timer's own instruction sees
// them change: no instruction of the program other than its TON, TOF or RTO (and RES, whose effect
// does not depend on them and which the probe's record of the timer's execution judges) may read or
// write the element's control word or ACC. Bits EN, TT and DN may be read (they do not change while
// the timer accumulates below PRE), and PRE may be read (a CPT expression's atoms are reads). Anything
// that could reach further — a file operand or a multi-word operand in a T file (COP, FLL, a MSG's
// data table address ...), an indexed or indirect T address, an indirect reference whose pointer is a
// timer's control word or ACC — makes the elements it may reach shared. Known from the program's
// text, so nothing is checked while it runs.
struct TimerSharing {
  bool every_file = false;                    // an indirect file number in a T address
  std::array<bool, 256> file{};               // every element of the file may be reached
  std::vector<std::pair<int, int>> elements;  // (file, element) reached directly

  void pointer(const std::optional<IndirectRef>& r) {
    if (r && r->type == FileType::Timer && r->word != 1) elements.emplace_back(r->file, r->element);
  }
  // An address in an operand of `op` at `index` (spec `os`, null for a CPT expression's atom, a read).
  void note(const Address& a, Opcode op, std::size_t index, const OperandSpec* os) {
    pointer(a.indirect_file());
    pointer(a.indirect_element());
    pointer(a.indirect_word());
    pointer(a.indirect_bit());
    if (a.type != FileType::Timer) return;
    if (a.is_indirect() && a.indirect_file()) {
      every_file = true;
      return;
    }
    if (a.file >= file.size()) {
      every_file = true;
      return;
    }
    if (a.is_indirect() || a.indexed) {
      file[a.file] = true;
      return;
    }
    if (index == 0 && (op == Opcode::TON || op == Opcode::TOF || op == Opcode::RTO || op == Opcode::RES)) return;
    const bool single = !os || os->kind == OperandKind::Bit || os->kind == OperandKind::Source ||
                        os->kind == OperandKind::Dest || os->kind == OperandKind::WordSource ||
                        os->kind == OperandKind::WordDest;
    if (!single) {
      file[a.file] = true;
      return;
    }
    const bool read = !os || os->access == OperandAccess::Read;
    const bool status_bit = a.word_in_element() == 0 && (a.bit == 13 || a.bit == 14 || a.bit == 15);
    if (read && (a.word == 1 || status_bit)) return;
    elements.emplace_back(a.file, a.element);
  }
  void walk(const std::vector<RungElement>& elements_of_rung) {
    for_each_instruction(elements_of_rung, [&](const Instruction& in) {
      // An expression that does not parse is never repeated (expression_reads_only_program_words).
      each_address(in, [&](const Address& a, std::size_t i, const OperandSpec* os) { note(a, in.opcode, i, os); });
    });
  }
};

// For each word of the table, 1 at the control word of a timer element that only its own
// instructions reach (TimerSharing).
std::vector<std::uint8_t> private_timers(const Program& program, const DataTableLayout& L) {
  TimerSharing sharing;
  for (const ProgramFile& f : program.files)
    for (const Rung& r : f.rungs) sharing.walk(r.elements);
  std::vector<std::uint8_t> out(L.total_words, 0);
  if (sharing.every_file) return out;
  for (std::size_t n = 0; n < sharing.file.size(); ++n) {
    const FileLayout& f = L.files[n];
    if (!f.present || f.type != FileType::Timer || sharing.file[n]) continue;
    for (std::uint32_t e = f.base; e < f.end(); e += f.words_per_element) out[e] = 1;
  }
  for (const auto& [file, element] : sharing.elements) {
    const FileLayout& f = L.files[static_cast<std::size_t>(file)];
    if (f.present && f.type == FileType::Timer && element >= 0 && static_cast<std::uint32_t>(element) < f.elements)
      out[f.base + static_cast<std::uint32_t>(element) * f.words_per_element] = 0;
  }
  return out;
}

// Counted words (docs/semantics.md "Counted words carried across repeats"). A direct N or B word that
// the program's text reaches only through
// - one ADD W k W, ADD k W W or SUB W k W with a constant k != 0 (the counting instruction),
// - compares of the word with constants (EQU NEQ LES LEQ GRT GEQ, LIM with the other two constants),
// - CLR W and MOV c W with a constant c (resets),
// where the counting instruction runs at most once a scan (its file is loop-free and is the main file or
// a subroutine that only one JSR calls, from such a file): a probe that advanced the word by k with
// nothing else changed may be followed by repeats that advance it by k each. Anything else that may
// name the word makes it shared: any other instruction naming it (a MOV, a bit of it, a CPT atom, a
// JSR parameter ...), a file operand or any multi-word operand in its file (COP, FLL, a BTR's data file,
// a PID's block: the whole file), an indexed or indirect address in its file (every file of its type for
// an indirect file number), an indirect reference whose pointer is the word. A MSG anywhere shares every
// word: a MicroLogix MSG names its local data in its MG element, out of the program's text.
struct WordSharing {
  const DataTableLayout& layout;
  std::vector<std::uint8_t> shared;                    // by word
  std::array<bool, 256> file{};                        // every word of the file shared
  bool every_integer = false, every_bit = false, everything = false;
  struct Candidate {
    CountedWord counted;
    int counting_instructions = 0;
    int program_file = -1;  // the file of its counting instruction
    int data_file = -1;
  };
  std::map<std::uint32_t, Candidate> candidate;  // by word, in word order

  explicit WordSharing(const DataTableLayout& L) : layout(L), shared(L.total_words, 0) {}

  static bool counted_type(FileType t) { return t == FileType::Integer || t == FileType::Bit; }
  // The word of a direct, word-level N or B address, or nullopt.
  std::optional<std::uint32_t> direct_word(const Operand& o) {
    if (!o.is_address()) return std::nullopt;
    const Address& a = o.address;
    if (!counted_type(a.type) || a.indexed || a.is_indirect() || a.has_bit() || a.bit_offset_form) return std::nullopt;
    const std::optional<Location> loc = layout.locate(a);
    if (!loc || loc->bit >= 0 || loc->vtype != ValueType::Int16) return std::nullopt;
    return loc->word;
  }
  static std::optional<std::int64_t> constant(const Operand& o) {
    if (o.kind != Operand::Kind::Integer || o.integer < INT16_MIN || o.integer > INT16_MAX) return std::nullopt;
    return o.integer;
  }
  void pointer(const std::optional<IndirectRef>& r) {
    if (!r) return;
    Address p;
    p.type = r->type;
    p.file = r->file;
    p.element = r->element;
    p.word = r->word;
    if (const std::optional<Location> loc = layout.locate(p)) shared[loc->word] = 1;
  }
  // An address that may name counted words in a way the rule does not allow.
  void note(const Address& a, const OperandSpec* os) {
    pointer(a.indirect_file());
    pointer(a.indirect_element());
    pointer(a.indirect_word());
    pointer(a.indirect_bit());
    if (!counted_type(a.type)) return;
    if (a.is_indirect() && a.indirect_file()) {
      (a.type == FileType::Integer ? every_integer : every_bit) = true;
      return;
    }
    if (a.file >= file.size()) {
      everything = true;
      return;
    }
    const bool single = !os || os->kind == OperandKind::Bit || os->kind == OperandKind::Source ||
                        os->kind == OperandKind::Dest || os->kind == OperandKind::WordSource ||
                        os->kind == OperandKind::WordDest;
    if (a.is_indirect() || a.indexed || !single) {
      file[static_cast<std::size_t>(a.file)] = true;
      return;
    }
    if (const std::optional<Location> loc = layout.locate(a)) shared[loc->word] = 1;
    else file[static_cast<std::size_t>(a.file)] = true;
  }
  Candidate& use(const Operand& o, std::uint32_t word) {
    Candidate& c = candidate[word];
    c.counted.word = word;
    c.data_file = o.address.file;
    return c;
  }
  // Whether the instruction is one of the allowed uses; records it when it is.
  bool allowed(const Instruction& in, int file_number) {
    const auto& o = in.operands;
    switch (in.opcode) {
      case Opcode::ADD:
      case Opcode::SUB: {
        if (o.size() != 3) return false;
        const std::optional<std::uint32_t> d = direct_word(o[2]);
        if (!d) return false;
        const bool first = direct_word(o[0]) == d && constant(o[1]);
        const bool second = in.opcode == Opcode::ADD && constant(o[0]) && direct_word(o[1]) == d;
        if (!first && !second) return false;
        const std::int64_t k = *constant(first ? o[1] : o[0]);
        if (k == 0) return false;
        Candidate& c = use(o[2], *d);
        c.counted.subtract = in.opcode == Opcode::SUB;
        c.counted.constant_first = !first;
        c.counted.k = k;
        ++c.counting_instructions;
        c.program_file = file_number;
        return true;
      }
      case Opcode::CLR:
        if (o.size() != 1 || !direct_word(o[0])) return false;
        use(o[0], *direct_word(o[0])).counted.resets.push_back(0);
        return true;
      case Opcode::MOV:
        if (o.size() != 2 || !constant(o[0]) || !direct_word(o[1])) return false;
        use(o[1], *direct_word(o[1])).counted.resets.push_back(*constant(o[0]));
        return true;
      case Opcode::EQU:
      case Opcode::NEQ:
      case Opcode::LES:
      case Opcode::LEQ:
      case Opcode::GRT:
      case Opcode::GEQ:
      case Opcode::LIM: {
        const std::size_t n = in.opcode == Opcode::LIM ? 3 : 2;
        if (o.size() != n) return false;
        std::optional<std::uint32_t> word;
        CountedWord::Compare cmp{in.opcode, {}, 0};
        for (std::size_t i = 0; i < n; ++i) {
          if (const std::optional<std::int64_t> c = constant(o[i])) {
            cmp.operand[i] = *c;
          } else if (const std::optional<std::uint32_t> w = direct_word(o[i]); w && !word) {
            word = w;
            cmp.at = i;
          } else {
            return false;
          }
        }
        if (!word) return false;
        use(o[cmp.at], *word).counted.compares.push_back(cmp);
        return true;
      }
      default: return false;
    }
  }
  void walk(const std::vector<RungElement>& elements_of_rung, int file_number) {
    for_each_instruction(elements_of_rung, [&](const Instruction& in) {
      if (in.opcode == Opcode::MSG) everything = true;
      if (allowed(in, file_number)) return;
      // An expression that does not parse is never repeated (expression_reads_only_program_words).
      const bool parsed = each_address(in, [&](const Address& a, std::size_t, const OperandSpec* os) {
        if (!os || os->kind != OperandKind::RemoteAddress) note(a, os);
      });
      everything = everything || !parsed;
    });
  }
};

// Whether each program file's instructions run at most once a scan: a file is loop-free when no LBL
// stands at or before a JMP's rung (a JMP can only go forward), and runs at most once a scan when it is
// the main file (2), which no JSR calls, or a subroutine that exactly one JSR calls, from another file
// that is loop-free and runs at most once a scan. An interrupt routine's run shows in the probe (an STI's
// timer, a DII's pending bit), so the repeats never stand for one.
std::vector<std::uint8_t> files_run_once(const Program& program) {
  struct FileFacts {
    bool present = false;
    int first_label = std::numeric_limits<int>::max(), last_jump = -1;
    std::vector<int> callers;  // the file of each JSR calling it
  };
  std::array<FileFacts, 256> facts{};
  for (const ProgramFile& f : program.files) {
    if (f.number < 0 || f.number >= 256) continue;
    facts[static_cast<std::size_t>(f.number)].present = true;
  }
  for (const ProgramFile& f : program.files) {
    if (f.number < 0 || f.number >= 256) continue;
    FileFacts& ff = facts[static_cast<std::size_t>(f.number)];
    for (std::size_t r = 0; r < f.rungs.size(); ++r)
      for_each_instruction(f.rungs[r].elements, [&](const Instruction& in) {
        if (in.opcode == Opcode::LBL) ff.first_label = std::min(ff.first_label, static_cast<int>(r));
        if (in.opcode == Opcode::JMP) ff.last_jump = std::max(ff.last_jump, static_cast<int>(r));
        if (const int target = jsr_target(in); target >= 0)
          facts[static_cast<std::size_t>(target)].callers.push_back(f.number);
      });
  }
  std::vector<std::uint8_t> once(256, 0);
  // Following the single callers up to file 2; a chain longer than the files is a cycle.
  for (std::size_t n = 2; n < facts.size(); ++n) {
    std::size_t f = n;
    bool ok = facts[f].present;
    for (int depth = 0; ok && depth < 257; ++depth) {
      // A jump back over a label, or a file that is not called from exactly one other file, runs more than once.
      const bool backward_jump = facts[f].first_label <= facts[f].last_jump;
      if (!backward_jump && f == 2) break;
      if (backward_jump || facts[f].callers.size() != 1 || facts[f].callers[0] == static_cast<int>(f)) ok = false;
      else f = static_cast<std::size_t>(facts[f].callers[0]);
      if (depth == 256) ok = false;
    }
    ok = ok && f == 2 && facts[2].callers.empty();
    once[n] = ok ? 1 : 0;
  }
  return once;
}

std::vector<CountedWord> counted_words(const Program& program, const DataTableLayout& L) {
  WordSharing sharing(L);
  for (const ProgramFile& f : program.files)
    for (const Rung& r : f.rungs) sharing.walk(r.elements, f.number);
  std::vector<CountedWord> out;
  if (sharing.everything || sharing.candidate.empty()) return out;
  const std::vector<std::uint8_t> once = files_run_once(program);
  for (auto& [word, c] : sharing.candidate) {
    if (sharing.shared[word] || c.counting_instructions != 1) continue;
    if (c.data_file < 0 || c.data_file >= 256) continue;
    const FileType type = L.files[static_cast<std::size_t>(c.data_file)].type;
    if (sharing.file[static_cast<std::size_t>(c.data_file)] || (type == FileType::Integer && sharing.every_integer) ||
        (type == FileType::Bit && sharing.every_bit))
      continue;
    if (c.program_file < 0 || c.program_file >= 256 || !once[static_cast<std::size_t>(c.program_file)]) continue;
    out.push_back(std::move(c.counted));
  }
  return out;
}


// What the counting instruction of `c` leaves in S:0's arithmetic flags when the word holds v, as
// Interpreter::math and the fused ADD/SUB compute them (C, V, Z, N in bits 0-3); V also means the
// result did not fit.
unsigned counted_flags(const CountedWord& c, std::int64_t v) {
  const std::int64_t a = c.constant_first ? c.k : v, b = c.constant_first ? v : c.k;
  const bool carry = c.subtract ? word_ops::sub_carry(a, b, 0xFFFF) : word_ops::add_carry(a, b, 0xFFFF);
  const std::int64_t r = c.subtract ? a - b : a + b;
  const bool overflow = r < INT16_MIN || r > INT16_MAX;
  return (carry ? 1u : 0u) | (overflow ? 2u : 0u) | (r == 0 ? 4u : 0u) | (r < 0 ? 8u : 0u);
}

// A compare of the counted word with constants when the word holds v, as Interpreter::compare computes it.
bool counted_compare(const CountedWord::Compare& cmp, std::int64_t v) {
  std::array<std::int64_t, 3> x = cmp.operand;
  x[cmp.at] = v;
  if (cmp.op == Opcode::LIM) return x[0] <= x[2] ? (x[0] <= x[1] && x[1] <= x[2]) : (x[1] >= x[0] || x[1] <= x[2]);
  return word_ops::compare(to_op(cmp.op), x[0], x[1]);
}

// The last value, going from `from` by `dir` (+1 or -1) within the 16-bit range, up to which `same`
// holds at every value (same(from) holds). `cuts` holds every p at which same(p) and same(p + 1) may
// differ: between two cuts `same` is constant, so only the values beside the cuts are asked.
template <class Same>
std::int64_t last_value_where(std::int64_t from, int dir, std::vector<std::int64_t> cuts, const Same& same) {
  std::sort(cuts.begin(), cuts.end());
  if (dir > 0) {
    for (const std::int64_t p : cuts)
      if (p >= from && p < INT16_MAX && !same(p + 1)) return p;
    return INT16_MAX;
  }
  for (auto it = cuts.rbegin(); it != cuts.rend(); ++it)
    if (*it < from && *it >= INT16_MIN && !same(*it)) return *it + 1;
  return INT16_MIN;
}
}  // namespace

std::string RuntimeResult::render_errors() const {
  std::string s;
  for (const auto& e : errors) s += e.to_string() + "\n";
  return s;
}

// What a field process sees of the runtime: the clock, the event queue and the data table.
class Runtime::ProcessHost final : public FieldProcessHost {
 public:
  explicit ProcessHost(Runtime& rt) : rt_(rt) {}
  VirtualTime now() const override { return rt_.now(); }
  Mode mode() const override { return rt_.mode(); }
  EventQueue::EventId schedule_at(VirtualTime at, EventQueue::Callback cb) override {
    return rt_.events_.schedule_at(at, std::move(cb));
  }
  bool cancel_event(EventQueue::EventId id) override { return rt_.events_.cancel(id); }
  const DataTableLayout& layout() const override { return *rt_.program_->layout; }
  std::uint16_t read_word(std::uint32_t index) const override {
    return index < rt_.data_.size() ? rt_.data_.word(index) : 0;
  }
  void write_word(std::uint32_t index, std::uint16_t value) override {
    if (index >= rt_.data_.size()) return;
    // An event between repeated scans may run a process; one that changes a word stops them.
    if (rt_.data_.word(index) != value) ++rt_.process_writes_;
    rt_.data_.set_word(index, value);
  }

 private:
  Runtime& rt_;
};

RuntimeResult Runtime::create(const Program& program, RuntimeOptions options) {
  CompileOptions co;
  co.processor = options.processor;
  co.module_instruction = options.module_instruction;
  CompileResult cr = compile(program, co);
  RuntimeResult r;
  if (!cr.ok()) {
    r.errors = std::move(cr.errors);
    return r;
  }
  auto compiled = std::make_unique<CompiledProgram>(std::move(*cr.program));
  std::vector<FieldProcessFactory> processes = std::move(options.field_processes);
  auto make_channel = std::move(options.ascii_channel);
  auto make_modbus = std::move(options.modbus_channel);
  const std::vector<PeerController> peers = std::move(options.peers);
  const int channel1_node = options.channel1_node;
  const std::string channel1_network = options.channel1_network;
  const std::optional<Df1Options> channel0_df1 = options.channel0_df1;
  r.runtime.reset(new Runtime(std::move(compiled), std::move(options)));
  Runtime& rt = *r.runtime;
  RepeatFacts facts;
  rt.program_repeatable_ = program_scans_repeatable(program, facts);
  rt.clock_bits_read_ = facts.clock_bits;
  rt.timer_tick_ns_ = facts.timer_tick;
  if (rt.program_repeatable_) rt.timer_private_ = private_timers(program, *rt.program_->layout);
  if (rt.program_repeatable_) rt.counted_words_ = counted_words(program, *rt.program_->layout);
  rt.process_host_ = std::make_unique<ProcessHost>(rt);
  if (make_channel) {
    rt.ascii_channel_ = make_channel();
    if (rt.ascii_channel_) {
      rt.ascii_channel_->attach(*rt.process_host_);
      rt.interp_->set_ascii_port(rt.ascii_channel_.get());
    }
  }
  if (make_modbus) {
    rt.modbus_channel_ = make_modbus();
    if (rt.modbus_channel_) rt.modbus_channel_->attach(*rt.process_host_);
  }
  for (const auto& make : processes) {
    std::unique_ptr<FieldProcess> p = make ? make() : nullptr;
    if (!p) continue;
    if (std::string why = p->attach(*rt.process_host_); !why.empty()) {
      CompileError e;
      e.message = "process " + p->name() + ": " + why;
      r.errors.push_back(std::move(e));
      r.runtime.reset();
      return r;
    }
    rt.processes_.push_back(std::move(p));
  }
  rt.cycles_allowed_ = rt.program_repeatable_ && rt.clock_bits_read_ == 0 && !rt.ascii_channel_ && !rt.modbus_channel_ &&
                      rt.interp_->data_logs().queues().empty();
  // The words a remembered steady scan's comparison leaves out (repeat_remembered), in table order.
  for (std::size_t i = 0; i < kRuntimeStatusWords.size(); ++i)
    rt.steady_.runtime_words[i] = rt.program_->layout->status_word(kRuntimeStatusWords[i]);
  std::sort(rt.steady_.runtime_words.begin(), rt.steady_.runtime_words.end());
  if (!peers.empty() || channel1_node != 0 || channel0_df1) {
    if (std::string why = rt.join_peers(peers, channel1_node, channel1_network, channel0_df1); !why.empty()) {
      CompileError e;
      e.message = why;
      r.errors.push_back(std::move(e));
      r.runtime.reset();
    }
  }
  return r;
}

// The MSG network of a leader and its peers (docs/semantics.md "MSG"): one link, every peer a
// processor on that link; on DH-485 and DH+ every node unique and in the link's range, on Ethernet
// every IP address given and unique. A MicroLogix 1100/1400 is on Ethernet when it has an IP address
// (its channel 1), on DH-485 otherwise (station_link). A 1764-LRP leader may put its channel 1 on DH-485
// too, at its own node, on this network or on a second one that the peers given its name are on
// (`segment` 1; docs/semantics.md "Channel 1 of the 1500 LRP"): node numbers are unique per network.
std::string Runtime::join_peers(const std::vector<PeerController>& peers, int channel1_node,
                                const std::string& channel1_network, const std::optional<Df1Options>& channel0_df1) {
  const MessageLink link = station_link(program_->processor, ip_ != 0);
  // Channel 0 as a DF1 full-duplex port (docs/semantics.md "DF1 full-duplex on channel 0"): a System-mode
  // configuration, so not also the bench's User-mode (ASCII) device or a Modbus RTU master.
  Df1Config df1;
  if (channel0_df1) {
    if (std::string why = df1_configure(program_->processor, *channel0_df1, df1); !why.empty()) return why;
    if (modbus_channel_)
      return "channel 0: it is a Modbus RTU master (the bench's modbus nodes) and cannot also be DF1 full-duplex";
    if (ascii_channel_)
      return "channel 0: it is in User mode (ASCII) with the bench's serial device and cannot also be DF1 full-duplex";
  }
  // A MicroLogix without an IP address meets the network through channel 0, its serial port: a DF1 port is
  // on none (its node is its DF1 station address then, 0-254).
  const bool df1_on_network_channel = channel0_df1 && link != MessageLink::Ethernet && program_->processor.is_micrologix();
  if (link == MessageLink::None)
    return "a MSG network needs SLC 500 or MicroLogix processors (DH-485, DH+ or Ethernet); " +
           program_->processor.display_name + " has none that softslc simulates for MSG";
  const bool ethernet = link == MessageLink::Ethernet;
  // Not a structured binding: clang 14 cannot capture one in the lambda below.
  const auto range = message_node_range(link);
  const int lo = range.first, hi = range.second;
  auto node_error = [&](const std::string& who, int node) -> std::string {
    if (!ethernet && (node < lo || node > hi))
      return who + ": node " + std::to_string(node) + " is out of range " + std::to_string(lo) + "-" +
             std::to_string(hi) + " on " + std::string(to_string(link));
    return {};
  };
  if (df1_on_network_channel) {
    if (node_ < 0 || node_ > 254)
      return "this controller: node " + std::to_string(node_) + " is out of range 0-254 for a DF1 station address "
             "(1766-RM001A p. 592)";
  } else if (auto e = node_error("this controller", node_); !e.empty()) {
    return e;
  }
  if (!ethernet && ip_ != 0)
    return "this controller is on " + std::string(to_string(link)) + ", which names stations by node number: "
           "an IP address is for an SLC 5/05, or a MicroLogix 1100 or 1400 on its channel 1, on Ethernet";
  // A channel 0 that the bench makes a Modbus RTU master (docs/semantics.md "The MicroLogix MSG over
  // Modbus RTU") is not a DH-485 station: a 1100/1400 so configured meets other controllers only on its
  // channel 1, Ethernet.
  // The peers on its Modbus line (`modbus`) are reached through channel 0 itself.
  const bool network_peers = std::any_of(peers.begin(), peers.end(), [](const PeerController& p) { return !p.modbus; });
  if (!ethernet && modbus_channel_ && network_peers)
    return "this controller's channel 0 is a Modbus RTU master (the bench's modbus nodes), so it is on no "
           "DH-485 network; give it an IP address (ip A.B.C.D) to meet its peers on Ethernet, channel 1";
  auto net = std::make_unique<MessageNetwork>(link);
  net->attach(*this, node_, "", nullptr, ip_);
  if (!ethernet && modbus_channel_) net->leave_network(0);
  if (channel0_df1) net->attach_df1(0, df1);
  bool df1_peer_joined = false;
  auto taken = [&](int segment, int node) -> std::string {
    const std::optional<std::size_t> i = net->station_on(segment, node);
    if (!i) return {};
    return *i == 0 ? std::string("this controller's") : "peer " + net->name(*i) + "'s";
  };
  if (channel1_node != 0) {
    // "For controllers with 2 channels (1764-LRP processor installed), the channel can be 0 or 1"
    // (1762-RM001C p. 21-12): only the LRP has a second serial port.
    if (program_->processor.micrologix != MicroLogixModel::ML1500LRP)
      return "channel 1: a second serial port on DH-485 is the 1764-LRP's (1762-RM001C p. 21-12); the " +
             program_->processor.display_name + " has none";
    if (auto e = node_error("this controller's channel 1", channel1_node); !e.empty()) return e;
    const int segment = channel1_network.empty() ? 0 : 1;
    if (auto who = taken(segment, channel1_node); !who.empty())
      return "this controller's channel 1: node " + std::to_string(channel1_node) + " is already " + who;
    net->attach_port(0, 1, channel1_node, segment);
  }
  for (const PeerController& p : peers) {
    if (!p.program) return "peer " + p.name + ": no program";
    if (p.modbus) {
      if (std::string why = join_modbus_peer(*net, p); !why.empty()) return why;
      continue;
    }
    if (p.df1) {
      if (std::string why = join_df1_peer(*net, p, channel0_df1.has_value(), df1_peer_joined); !why.empty()) return why;
      df1_peer_joined = true;
      continue;
    }
    if (df1_on_network_channel)
      return "peer " + p.name + ": this controller's channel 0 is DF1 full-duplex (channel 0 df1), a point-to-point "
             "link, so it is on no DH-485 network; join the peer by the cable ('peer NAME PATH df1')";
    // A peer on a named network is on the one the leader's channel 1 names; no other is reachable.
    if (!p.network.empty() && (channel1_node == 0 || p.network != channel1_network))
      return "peer " + p.name + ": network " + p.network + " is not one this controller is on (its channel 1 " +
             (channel1_node == 0 ? std::string("is on no network") : channel1_network.empty()
                                                                        ? std::string("is on this network")
                                                                        : "is on network " + channel1_network) +
             ")";
    const int segment = p.network.empty() ? 0 : 1;
    RuntimeOptions po = p.options ? *p.options : RuntimeOptions{};
    po.peers.clear();
    po.node = p.node;
    po.ip = p.ip;
    RuntimeResult pr = Runtime::create(*p.program, std::move(po));
    if (!pr.ok()) return "peer " + p.name + ": " + pr.render_errors();
    const ProcessorModel& pproc = pr.runtime->program_->processor;
    const MessageLink plink = station_link(pproc, p.ip != 0);
    // A MicroLogix 1100/1400 without an address is on DH-485: on Ethernet it needs one, as a 5/05 does.
    if (plink != link && !(ethernet && pproc.has_routing_files()))
      return "peer " + p.name + ": its " + pproc.display_name + " is on " + std::string(to_string(plink)) +
             ", this network is " + std::string(to_string(link));
    if (ethernet) {
      if (p.ip == 0)
        return "peer " + p.name + ": " +
               (pproc.is_micrologix() ? "a " + pproc.display_name + " on Ethernet (its channel 1)" : "an SLC 5/05 on Ethernet") +
               " is named by its IP address (ip A.B.C.D), not a node";
      for (std::size_t i = 0; i < net->size(); ++i)
        if (net->ip(i) == p.ip)
          return "peer " + p.name + ": IP address " + format_ipv4(p.ip) + " is already " +
                 (i == 0 ? std::string("this controller's") : "peer " + net->name(i) + "'s");
    } else {
      if (p.ip != 0)
        return "peer " + p.name + ": this network is " + std::string(to_string(link)) +
               ", which names stations by node number (node N), not IP address";
      if (auto e = node_error("peer " + p.name, p.node); !e.empty()) return e;
      if (auto who = taken(segment, p.node); !who.empty())
        return "peer " + p.name + ": node " + std::to_string(p.node) + " is already " + who +
               (segment ? " on network " + p.network : std::string());
    }
    Runtime& peer = *pr.runtime;
    const std::size_t station = net->attach(peer, p.node, p.name, std::move(pr.runtime), p.ip, segment);
    peer.network_ = net.get();
    peer.station_ = station;
  }
  own_network_ = std::move(net);
  network_ = own_network_.get();
  station_ = 0;
  return {};
}

// The peer at the other end of the leader's DF1 cable (docs/semantics.md "DF1 full-duplex on channel 0"):
// one, with a DF1 channel 0 of its own (its options' configuration, or its processor's defaults), on no
// other network.
std::string Runtime::join_df1_peer(MessageNetwork& net, const PeerController& p, bool leader_df1, bool joined) {
  if (!leader_df1)
    return "peer " + p.name + ": joined by the DF1 cable, but this controller's channel 0 is not DF1 full-duplex "
           "(add 'channel 0 df1')";
  if (joined)
    return "peer " + p.name + ": DF1 full-duplex is point to point (1747-RM001G p. 13-49): channel 0 already has "
           "its peer at the cable's other end";
  if (p.node < 0 || p.node > 254)
    return "peer " + p.name + ": node " + std::to_string(p.node) + " is out of range 0-254 for a DF1 station address "
           "(1766-RM001A p. 592)";
  RuntimeOptions po = p.options ? *p.options : RuntimeOptions{};
  po.peers.clear();
  const std::optional<Df1Options> settings = po.channel0_df1;
  po.channel0_df1.reset();  // the peer's port is attached to this network below, not to one of its own
  po.node = p.node;
  po.ip = 0;
  RuntimeResult pr = Runtime::create(*p.program, std::move(po));
  if (!pr.ok()) return "peer " + p.name + ": " + pr.render_errors();
  Df1Config config;
  if (std::string why = df1_configure(pr.runtime->program_->processor, settings.value_or(Df1Options{}), config);
      !why.empty())
    return "peer " + p.name + ": " + why;
  Runtime& peer = *pr.runtime;
  const std::size_t station = net.attach(peer, p.node, p.name, std::move(pr.runtime), 0, 0);
  net.leave_network(station);
  net.attach_df1(station, config);
  net.join_df1(0, station);
  peer.network_ = &net;
  peer.station_ = station;
  return {};
}

// A peer whose channel 0 is a Modbus RTU slave on this controller's Modbus line (docs/semantics.md "A MicroLogix
// as a Modbus RTU slave"): on no other network; its address unique among the line's slaves, the bench's
// simulated ones included; its map's files in its program, as serve checks them.
std::string Runtime::join_modbus_peer(MessageNetwork& net, const PeerController& p) {
  const modbus::SlaveOptions& o = *p.modbus;
  if (!modbus_channel_)
    return "peer " + p.name + ": a Modbus RTU slave answers a Modbus RTU master on its line, but this controller's "
           "channel 0 is not one (give the bench a modbus node, docs/bench-format.md \"Modbus RTU slaves\")";
  if (o.address < modbus::kMinSlaveAddress || o.address > modbus::kMaxSlaveAddress)
    return "peer " + p.name + ": Modbus address " + std::to_string(o.address) +
           " is out of range 1-247 (0 is the broadcast address, 248-255 are reserved)";
  for (const ModbusSlaveConfig& s : modbus_channel_->config().slaves)
    if (s.address == o.address)
      return "peer " + p.name + ": Modbus address " + std::to_string(o.address) + " is already the bench's modbus node " +
             s.name + "'s";
  if (const auto i = net.modbus_slave_at(o.address))
    return "peer " + p.name + ": Modbus address " + std::to_string(o.address) + " is already peer " + net.name(*i) + "'s";
  RuntimeOptions po = *p.options;
  po.peers.clear();
  if (po.channel0_df1 || po.modbus_channel || po.ascii_channel)
    return "peer " + p.name + ": its channel 0 is the Modbus RTU slave, so it cannot also be DF1, a Modbus master or "
           "in User mode";
  RuntimeResult pr = Runtime::create(*p.program, std::move(po));
  if (!pr.ok()) return "peer " + p.name + ": " + pr.render_errors();
  const ProcessorModel& pproc = pr.runtime->program_->processor;
  if (pproc.micrologix != MicroLogixModel::ML1100 && pproc.micrologix != MicroLogixModel::ML1400)
    return "peer " + p.name + ": a Modbus RTU slave channel 0 with the Modbus memory map is the MicroLogix 1100's and "
           "1400's (1763-RM001C p. 530, 1766-RM001A p. 617); its processor is " + pproc.display_name;
  Runtime& peer = *pr.runtime;
  const std::size_t station = net.attach(peer, 0, p.name, std::move(pr.runtime), 0, 0);
  net.leave_network(station);
  if (std::string why = net.attach_modbus_slave(station, o, *modbus_channel_); !why.empty())
    return "peer " + p.name + ": map: " + why;
  peer.network_ = &net;
  peer.station_ = station;
  return {};
}

Runtime* Runtime::peer(std::string_view name) const {
  if (!own_network_) return nullptr;
  for (std::size_t i = 1; i < own_network_->size(); ++i)
    if (own_network_->name(i) == name) return &own_network_->runtime(i);
  return nullptr;
}

std::vector<std::string> Runtime::peer_names() const {
  std::vector<std::string> names;
  if (own_network_)
    for (std::size_t i = 1; i < own_network_->size(); ++i) names.push_back(own_network_->name(i));
  return names;
}

MessageNetwork& Runtime::network() {
  // A controller alone gets a network of its own on its first message: its MSGs to other nodes find
  // nobody (07h), as on a link with no other station.
  if (!network_) {
    own_network_ = std::make_unique<MessageNetwork>(station_link(program_->processor, ip_ != 0));
    station_ = own_network_->attach(*this, node_, "", nullptr, ip_);
    network_ = own_network_.get();
  }
  return *network_;
}

// A Modbus MSG goes to channel 0's Modbus RTU master; on a channel 0 that is not one it ends with 12h, "local
// channel configuration protocol error", as does a PCCC (DH-485) MSG on a channel 0 that is one
// (1766-RM001A p. 466; docs/semantics.md "The MicroLogix MSG over Modbus RTU").
void Runtime::message_start(const MessageInstruction& m) {
  ++message_calls_;
  if (m.modbus_function != 0 && modbus_channel_) return modbus_channel_->start(m);
  if (m.modbus_function != 0 || (m.micrologix && m.channel == 0 && modbus_channel_))
    return ModbusMaster::refuse(*process_host_, m, modbus::kChannelProtocol);
  MessageNetwork& net = network();
  if (m.channel == 0 && !m.micrologix) attach_default_df1_port();
  net.start(station_, m);
}

// An SLC 5/03-5/05 channel 0 that nothing configured is at its factory configuration, DF1 full-duplex
// at the processor's defaults (docs/semantics.md "Channel 0"): a MSG on it goes out on the cable and,
// with nobody at the other end, ends with 07h once the ACK timeouts and ENQ retries are spent. A channel
// 0 the bench makes a User-mode (ASCII) port is no DF1 port: the MSG ends with 12h there. The port is
// attached when something first uses it: a MSG on channel 0, or the test's `device DF1` line.
bool Runtime::default_df1_port() const {
  return !ascii_channel_ && has_df1_channel0(program_->processor) && !program_->processor.is_micrologix();
}
void Runtime::attach_default_df1_port() {
  if (!default_df1_port()) return;
  MessageNetwork& net = network();
  if (!net.df1_port(station_)) net.attach_df1(station_, df1_defaults(program_->processor));
}
void Runtime::message_abort(std::uint32_t block) {
  ++message_calls_;
  if (modbus_channel_ && modbus_channel_->abort(block)) return;
  network().abort(station_, block);
}
void Runtime::service_communications(std::uint16_t channels, VirtualTime at) {
  network().service_now(station_, at, channels);
}

Runtime::Runtime(std::unique_ptr<CompiledProgram> program, RuntimeOptions options)
    : program_(std::move(program)),
      model_(options.time_model ? std::move(options.time_model) : make_scan_time_model(program_->processor)),
      data_(program_->layout, program_->initial_words),
      node_(options.node),
      ip_(options.ip) {
  const DataTableLayout& L = *program_->layout;
  // Modules: a specialty module from the factory, else generic discrete I/O, for every slot.
  for (const auto& s : program_->slots) {
    if (s.slot < 0 || s.slot >= kMaxSlots) continue;
    std::unique_ptr<Module> m = options.module_factory ? options.module_factory(s) : nullptr;
    if (!m) m = std::make_unique<DiscreteIoModule>(s.slot, s.catalog, s.scan_in, s.scan_out);
    m->attach(*this);
    modules_[static_cast<std::size_t>(s.slot)] = m.get();
    owned_modules_.push_back(std::move(m));
  }
  interp_ = std::make_unique<Interpreter>(*program_, data_, static_cast<ChassisAccess&>(*this), *model_);
  // A module's image-transfer cost depends only on its catalog number and image size, both fixed
  // at creation, and the model is fixed too: asked once here, not in every scan (a profile looks
  // it up by catalog string).
  for (Module* m : modules_)
    if (m) scanned_.push_back({m, model_->input_scan_cost(*m), model_->output_scan_cost(*m)});

  const std::uint32_t in_words = L.files[1].elements, out_words = L.files[0].elements;
  in_force_mask_.assign(in_words, 0);
  in_force_value_.assign(in_words, 0);
  out_force_mask_.assign(out_words, 0);
  out_force_value_.assign(out_words, 0);
  out_sent_.assign(out_words, 0);
  std::size_t biggest = 0;
  for (const Module* m : modules_)
    if (m) biggest = std::max<std::size_t>(biggest, static_cast<std::size_t>(std::max(m->input_words(), 0)));
  io_scratch_.assign(biggest, 0);

  // The program's FORCE blocks: ON bits forced to 1; an OFF column bit of 0 forces the bit to 0.
  for (const auto& f : program_->forces) {
    if (f.slot < 0 || f.slot >= kMaxSlots) continue;
    const bool input = f.type == FileType::Input;
    const SlotImage& si = (input ? L.input_slots : L.output_slots)[static_cast<std::size_t>(f.slot)];
    if (!si.present) continue;
    auto& mask = input ? in_force_mask_ : out_force_mask_;
    auto& value = input ? in_force_value_ : out_force_value_;
    for (std::size_t k = 0; k < f.words.size() && k < si.words; ++k) {
      const std::size_t i = si.first + k;
      mask[i] = static_cast<std::uint16_t>(f.words[k].on | ~f.words[k].off);
      value[i] = f.words[k].on;
    }
  }
  // A downloaded status file may carry the state it was saved in; a fresh processor is neither
  // faulted nor in its first pass until it enters Run.
  data_.set_status(status::kMode, static_cast<std::uint16_t>(data_.status(status::kMode) &
                                                              ~(status::kMajorHalt | status::kFirstPass)));
  write_mode_bits();
}

void Runtime::enable_coverage() {
  if (coverage_) return;
  coverage_ = std::make_unique<CoverageRecorder>(*program_);
  interp_->set_coverage(coverage_.get());
}

Runtime::~Runtime() = default;

// ---- Modes ------------------------------------------------------------------------------------------------

void Runtime::write_mode_bits() {
  // A mode or a force changes what the next scan does outside the table (its output image, whether it
  // executes): a remembered steady scan no longer stands for it.
  steady_.valid = false;
  std::uint16_t s1 = data_.status(status::kMode);
  s1 = static_cast<std::uint16_t>((s1 & ~0x001Fu) | mode_code(mode_));
  bool in_installed = false, out_installed = false;
  for (auto m : in_force_mask_) in_installed = in_installed || m != 0;
  for (auto m : out_force_mask_) out_installed = out_installed || m != 0;
  const bool installed = in_installed || out_installed;
  // Every change to the forces or their enable passes through here, so the scans test one flag
  // instead of merging an all-zero mask into every image word.
  in_forces_live_ = in_installed && forces_enabled_;
  out_forces_live_ = out_installed && forces_enabled_;
  s1 = static_cast<std::uint16_t>(installed ? (s1 | status::kForcesInstalled) : (s1 & ~status::kForcesInstalled));
  s1 = static_cast<std::uint16_t>(installed && forces_enabled_ ? (s1 | status::kForcesEnabled)
                                                               : (s1 & ~status::kForcesEnabled));
  data_.set_status(status::kMode, s1);
}

void Runtime::notify_modes(Mode from, Mode to) {
  const bool outer = !notifying_;
  notifying_ = true;
  for (Module* m : modules_)
    if (m) m->on_mode_change(from, to);
  if (ascii_channel_) ascii_channel_->on_mode_change(from, to);
  if (!outer) return;
  notifying_ = false;
  // A module that refused the change (a scanner without a valid G file) faults the processor
  // once every module has seen it.
  if (pending_module_fault_) {
    FaultInfo f = std::move(*pending_module_fault_);
    pending_module_fault_.reset();
    if (!fault_) enter_fault(f);
  }
}

void Runtime::raise_major_fault(std::uint16_t code, std::string message) {
  FaultInfo f;
  f.code = code;
  f.message = std::move(message);
  if (notifying_) {
    if (!pending_module_fault_) pending_module_fault_ = std::move(f);
    return;
  }
  if (!fault_) enter_fault(f);
}

RuntimeStatus Runtime::set_mode(Mode m) {
  if (m == Mode::Faulted) return RuntimeStatus::failure("only a major fault puts the processor in Faulted mode");
  if (m == Mode::Suspended) return RuntimeStatus::failure("only a true SUS instruction suspends the processor");
  if (fault_ || mode_ == Mode::Faulted)
    return RuntimeStatus::failure("a major fault is active (" + fault_->to_string() + "); clear it first");
  if (m == mode_) return {};
  const Mode from = mode_;
  mode_ = m;
  // Leaving Run or Test stops the STI and clears S:2/0 and S:2/2 (RM 11-12, 11-13).
  if (m != Mode::Run && m != Mode::Test) interp_->stop_interrupts();
  if (m == Mode::Run || m == Mode::Test) {
    // Entering Run or Test: a first pass (S:1/15) and S:4 zeroed (PT1 27-13).
    first_pass_ = true;
    data_.set_status(status::kClock, 0);
    s4_tick_ = clock_.now() / program_->processor.free_running_clock_tick_ns();
    single_scan_pending_ = false;
  }
  write_mode_bits();
  notify_modes(from, m);
  // A network's leader switches its peers with it: a line of SLCs tested together runs together.
  if (own_network_ && network_ == own_network_.get())
    for (std::size_t i = 1; i < own_network_->size(); ++i) (void)own_network_->runtime(i).set_mode(m);
  return {};
}

std::optional<std::string> Runtime::retrieve_data_log_record(int queue) {
  return interp_->data_logs().retrieve(queue, interp_->words());
}
std::vector<std::string> Runtime::data_log_records(int queue) const { return interp_->data_logs().records(queue); }
std::vector<int> Runtime::data_log_queues() const { return interp_->data_logs().queues(); }
void Runtime::keep_data_logs_of(const Runtime& other) { interp_->data_logs().keep_records_of(other.interp_->data_logs()); }

void Runtime::clear_fault() {
  if (!fault_ && mode_ != Mode::Faulted) return;
  fault_.reset();
  data_.set_status(status::kMode, static_cast<std::uint16_t>(data_.status(status::kMode) & ~status::kMajorHalt));
  const Mode from = mode_;
  mode_ = Mode::Program;
  write_mode_bits();
  notify_modes(from, mode_);
}

void Runtime::enter_fault(const FaultInfo& f) {
  FaultInfo info = f;
  info.time = clock_.now();
  fault_ = info;
  data_.set_status(status::kFaultCode, f.code);
  data_.set_status(status::kMode, static_cast<std::uint16_t>(data_.status(status::kMode) | status::kMajorHalt));
  const Mode from = mode_;
  mode_ = Mode::Faulted;
  interp_->stop_interrupts();
  notify_modes(from, mode_);
}

void Runtime::enter_suspend() {
  // RM ch. 6 (SUS): Suspend Idle, outputs de-energised (the output scan sends zeros outside Run);
  // S:7 and S:8 were written by the instruction. Not a fault: S:1/13 and S:6 are untouched.
  const Mode from = mode_;
  mode_ = Mode::Suspended;
  interp_->stop_interrupts();
  write_mode_bits();
  notify_modes(from, mode_);
}

// ---- Interrupt sources --------------------------------------------------------------------------

void Runtime::field_input_changed(int slot, int word, std::uint16_t before, std::uint16_t after) {
  // The DII works in Run only (RM 11-18: it begins operation on entry to Run); so does the EII [U].
  if (mode_ != Mode::Run) return;
  interp_->dii_input(slot, word, before, after, clock_.now());
  // The MicroLogix EII sees the embedded inputs' terminals change, at this moment of virtual time
  // (docs/semantics.md "The EII function file").
  interp_->event_input(slot, word, before, after);
}

void Runtime::request_io_interrupt(int slot) {
  if (mode_ == Mode::Run) {
    interp_->io_interrupt_request(slot);
    return;
  }
  // Outside Run nothing services it: answered at once so the module may request again.
  interrupt_serviced(slot);
}

bool Runtime::discrete_input_card(int slot) const {
  if (slot < 0 || slot >= kMaxSlots) return false;
  const Module* m = modules_[static_cast<std::size_t>(slot)];
  if (!m || m->input_words() <= 0) return false;
  // A catalog the module catalog lists as a specialty module is not a discrete card; an unknown
  // catalog is treated as generic discrete I/O, as the checker's warning says.
  auto entry = find_module_catalog(m->catalog());
  return !entry || !entry->specialty;
}

void Runtime::interrupt_serviced(int slot) {
  if (slot < 0 || slot >= kMaxSlots) return;
  if (Module* m = modules_[static_cast<std::size_t>(slot)]) m->interrupt_serviced();
}

Nanoseconds Runtime::io_refresh(VirtualTime at) {
  // REF (RM ch. 6): the output scan, then the input scan, in the middle of the program scan, and between
  // them the communications servicing of every channel, as an SVC without a channel select: on the
  // MicroLogix an incoming command is processed "at the next execution of a Service Communications (SVC)
  // instruction, I/O Refresh (REF) instruction, or when it performs Communications Servicing" (1766-RM001A
  // p. 410-411); the same on every processor (decision, docs/semantics.md "REF"). A controller on no
  // network has nothing to service.
  const Nanoseconds out = output_scan();
  if (network_) network_->service_now(station_, at + out, 0x3);
  return out + input_scan();
}

// ---- The scan cycle ----------------------------------------------------------------------------------------

// [[gnu::hot]] marks the functions every scan runs (here, and Interpreter::program_scan/run_routine,
// the end-of-scan STI/DII checks, service_interrupts_between, EventQueue::run_until and
// FusedProgram::execute): GCC puts them together in .text.hot, so where the rest of the code lands
// no longer decides which of them share instruction-cache sets. Without it, this branch's changes
// elsewhere doubled msg/filler's simulated I1 misses (callgrind --cache-sim, 145k -> 272k for 10 s)
// and the MSG examples ran 5-15% slower with fewer instructions (docs/performance.md "Executed scans
// (s17-scan)").

[[gnu::hot]] Nanoseconds Runtime::input_scan() {
  const DataTableLayout& L = *program_->layout;
  const FileLayout& in = L.files[1];
  std::uint16_t* w = data_.words();
  Nanoseconds cost = 0;
  for (const ScannedModule& sm : scanned_) {
    const SlotImage& si = L.input_slots[static_cast<std::size_t>(sm.module->slot())];
    if (si.present) sm.module->input_scan(std::span<std::uint16_t>(w + in.base + si.first, si.words));
    cost += sm.input_cost;
  }
  // A probe keeps what every module gave, so an event between repeats that changes it stops them.
  if (probing_) probe_inputs_.assign(w + in.base, w + in.base + in.elements);
  apply_input_forces(0, in.elements);
  return cost;
}

void Runtime::apply_input_forces(std::uint32_t first, std::uint32_t count) {
  if (!in_forces_live_) return;
  std::uint16_t* w = data_.words() + program_->layout->files[1].base;
  for (std::uint32_t i = first; i < first + count && i < in_force_mask_.size(); ++i)
    w[i] = static_cast<std::uint16_t>((w[i] & ~in_force_mask_[i]) | (in_force_value_[i] & in_force_mask_[i]));
}

std::uint16_t Runtime::forced_output(std::uint32_t i) const {
  const std::uint16_t v = data_.word(program_->layout->files[0].base + i);
  if (!forces_enabled_) return v;
  return static_cast<std::uint16_t>((v & ~out_force_mask_[i]) | (out_force_value_[i] & out_force_mask_[i]));
}

[[gnu::hot]] ProgramScanResult Runtime::program_scan(VirtualTime scan_start, Nanoseconds elapsed) {
  advance_free_running_clock(scan_start + elapsed);
  advance_rtc(scan_start + elapsed);
  // The MicroLogix high-speed counters: loaded on entry to an executing mode, then counted up to
  // the start of each scan (vm/ml_hsc.h).
  if (interp_->hsc().counters() > 0) {
    if (first_pass_) interp_->hsc().enter_run(data_.words(), scan_start + elapsed);
    interp_->hsc().advance(data_.words(), scan_start + elapsed);
  }
  std::uint16_t s1 = data_.status(status::kMode);
  data_.set_status(status::kMode, static_cast<std::uint16_t>(first_pass_ ? (s1 | status::kFirstPass)
                                                                         : (s1 & ~status::kFirstPass)));
  const Nanoseconds watchdog = static_cast<Nanoseconds>(data_.status(status::kWatchdog) >> 8) * kTick;
  return interp_->program_scan(scan_start, elapsed, first_pass_, watchdog);
}

// S:4 counts the processor's free-running clock ticks of virtual time (10 ms, or 100 us on the
// MicroLogix 1100-1500); it is brought up to date once per program scan, and a repeated scan's
// program scan would have done the same.
void Runtime::advance_free_running_clock(VirtualTime at) {
  const std::int64_t tick = at / program_->processor.free_running_clock_tick_ns();
  data_.set_status(status::kClock, static_cast<std::uint16_t>(data_.status(status::kClock) + (tick - s4_tick_)));
  s4_tick_ = tick;
}

void Runtime::advance_rtc(VirtualTime now) {
  const FileLayout& clock = program_->layout->function_file(FunctionFile::RTC);
  if (!clock.present) return;
  const std::int64_t second = now / kNsPerS;
  advance_real_time_clock(data_.words() + clock.base, second - rtc_second_);
  rtc_second_ = second;
}

[[gnu::hot]] Nanoseconds Runtime::output_scan() {
  const DataTableLayout& L = *program_->layout;
  // Outputs are energised only in Run; Program, Test and Faulted de-energise them.
  const bool live = mode_ == Mode::Run;
  if (!live) {
    std::fill(out_sent_.begin(), out_sent_.end(), std::uint16_t{0});
  } else if (out_forces_live_) {
    for (std::uint32_t i = 0; i < out_sent_.size(); ++i) out_sent_[i] = forced_output(i);
  } else {
    std::copy_n(data_.words() + L.files[0].base, out_sent_.size(), out_sent_.begin());
  }
  Nanoseconds cost = 0;
  for (const ScannedModule& sm : scanned_) {
    const SlotImage& si = L.output_slots[static_cast<std::size_t>(sm.module->slot())];
    if (si.present) sm.module->output_scan(std::span<const std::uint16_t>(out_sent_.data() + si.first, si.words));
    cost += sm.output_cost;
  }
  return cost;
}

[[gnu::hot]] void Runtime::housekeeping(Nanoseconds scan_time) {
  // RM B-19, B-42: S:3 low byte = this scan in 10 ms ticks; S:22 max, S:23 running average
  // (avg*7 + scan)/8, both in 10 ms units unless S:33/13 selects 1 ms; S:35 = last scan.
  std::uint16_t* const s = data_.words() + program_->layout->status_word(0);
  const std::int64_t ticks = scan_time / kTick;
  s[status::kWatchdog] = static_cast<std::uint16_t>((s[status::kWatchdog] & 0xFF00) | clamp_u8(ticks));
  const bool ms_units = (s[status::kCommBits] & status::kScanIn1ms) != 0;
  const std::int64_t unit = ms_units ? scan_time / kNsPerMs : ticks;
  s[status::kMaxScan] = std::max<std::uint16_t>(s[status::kMaxScan], clamp_u16(unit));
  s[status::kAvgScan] = clamp_u16((static_cast<std::int64_t>(s[status::kAvgScan]) * 7 + unit) / 8);
  // S:35 is the last scan in 1 ms on the SLC and in 100 us on the MicroLogix 1100-1500 (RSLogix's
  // own status page for the 1100: "Last 100 uSec Scan Time S:35"; docs/semantics.md).
  const Nanoseconds s35_unit = program_->processor.is_micrologix_1100_class() ? 100 * kNsPerUs : kNsPerMs;
  s[status::kLastScanMs] = clamp_u16(scan_time / s35_unit);
  stats_.scans += 1;
  stats_.last = scan_time;
  stats_.max = std::max(stats_.max, scan_time);
  stats_.total += scan_time;
}

[[gnu::hot]] void Runtime::scan_once(bool single_scan_step) {
  const VirtualTime start = clock_.now();
  Nanoseconds used = input_scan();
  input_scan_ns_ = used;
  const bool execute = mode_ == Mode::Run || (mode_ == Mode::Test && single_scan_step);
  if (execute) {
    ProgramScanResult r = program_scan(start, used);
    used = r.elapsed;
    stats_.instructions += r.instructions;
    const Nanoseconds watchdog_span = static_cast<Nanoseconds>(data_.status(status::kWatchdog) >> 8) * kTick;
    if (r.suspended) {
      enter_suspend();
    } else if (r.faulted) {
      enter_fault(r.fault);
      // NOLINTNEXTLINE(bugprone-branch-clone): the STI and DII checks fault alike, each for its own page
    } else if (mode_ == Mode::Run && !interp_->configure_sti(start + used, false)) {
      // RM 11-12: an S:30/S:31 loaded by the program starts timing at the end of this scan.
      enter_fault(interp_->last_fault());
    } else if (mode_ == Mode::Run && !interp_->configure_dii(false)) {
      // RM 11-24: S:46-S:50 are applied at each end of scan.
      enter_fault(interp_->last_fault());
    }
    used += output_scan();
    used += model_->housekeeping_cost();
    // STI expiries during the output scan and housekeeping run here, at the end of the cycle.
    if (mode_ == Mode::Run) {
      ProgramScanResult late = interp_->service_interrupts_between(start, used, r.watchdog_from + watchdog_span);
      used = late.elapsed;
      stats_.instructions += late.instructions;
      if (late.suspended) enter_suspend();
      else if (late.faulted) enter_fault(late.fault);
    }
    // The watchdog covers the whole scan cycle: a scan whose I/O pushed it past S:3H faults at
    // its end (the program-scan check only sees the time up to each rung). A REF restarts the
    // count (RM B-19), so it runs from the end of the last REF.
    if (!fault_ && mode_ != Mode::Suspended && used - r.watchdog_from >= watchdog_span) {
      FaultInfo f;
      f.code = fault::kWatchdog;
      f.file = r.last_file;
      f.rung = r.last_rung;
      f.message =
          "scan time reached the watchdog (S:3 high byte, " + std::to_string(watchdog_span / kTick) + " x 10 ms)";
      enter_fault(f);
    }
    housekeeping(used);
    first_pass_ = false;
    data_.set_status(status::kMode, static_cast<std::uint16_t>(data_.status(status::kMode) & ~status::kFirstPass));
  } else {
    used += output_scan();
    used += model_->housekeeping_cost();
  }
  // Every scan takes some time, so run_for and run_until always make progress.
  used = std::max<Nanoseconds>(used, kNsPerUs);
  // End-of-scan communication servicing (RM 12-41); the leader of a network also runs its peers up
  // to this time (vm/message_network.h).
  if (network_) [[unlikely]] network_->scanned(station_, start + used);
  events_at_last_scan_end_ = events_.run_until(start + used);
  if (scan_observer_) [[unlikely]] scan_observer_(*this);
}

int Runtime::scan(int n) {
  int done = 0;
  for (; done < n; ++done) {
    const bool had_fault = fault_.has_value();
    scan_once(true);
    if (!had_fault && fault_) return done + 1;
  }
  return done;
}

std::int64_t Runtime::run_for(Nanoseconds duration) {
  const VirtualTime end = clock_.now() + std::max<Nanoseconds>(duration, 0);
  std::int64_t n = 0;
  while (clock_.now() < end) n += advance_toward(end);
  return n;
}

[[gnu::hot]] std::int64_t Runtime::advance_toward(VirtualTime end) {
  if (probe_due()) return probe_and_repeat(end);
  scan_once(false);
  return 1;
}

[[gnu::hot]] bool Runtime::probe_due() {
  if (!program_repeatable_ || !skip_repeated_ || mode_ != Mode::Run || fault_ || first_pass_ || scan_observer_ ||
      (network_ && network_->size() > 1) || coverage_)
    return false;
  if (probe_wait_ > 0) {
    --probe_wait_;
    return false;
  }
  if (modules_passive() && interp_->nothing_pending_between_scans()) return true;
  // Asked again after a wait that grows as after a probe that found a change: a module that is
  // seldom passive (a 1203-SM1 whose drives ramp, a 1747-SDN with a DEM in flight) would cost a
  // question every scan.
  wait_longer_before_probing();
  return false;
}

bool Runtime::network_kept() {
  if (!network_) return net_before_probe_.empty();
  network_->holdings(station_, net_after_cycle_);
  return net_after_cycle_ == net_before_probe_;
}

void Runtime::wait_longer_before_probing() {
  probe_wait_ = probe_backoff_;
  probe_backoff_ = std::min<std::uint32_t>(probe_backoff_ * 2, 64);
}

bool Runtime::modules_passive() const {
  for (const ScannedModule& sm : scanned_)
    if (!sm.module->passive()) return false;
  return true;
}

void Runtime::reach(int slot) {
  Module* m = module(slot);
  if (!m) return;
  for (const ReachedModule& r : reached_)
    if (r.module == m) return;
  const std::optional<std::uint64_t> n = m->program_changes();
  if (!n) probe_unsteady_ = true;
  reached_.push_back({m, n.value_or(0)});
}

bool Runtime::reached_modules_unchanged() const {
  for (const ReachedModule& r : reached_)
    if (r.module->program_changes() != std::optional<std::uint64_t>(r.changes)) return false;
  return true;
}

bool Runtime::probe_reads_the_same() {
  for (const MRead& r : m_reads_) {
    std::uint16_t v = 0;
    if (modules_[static_cast<std::size_t>(r.slot)]->read_m(r.file, r.word, v) != MAccess::Ok || v != r.value) return false;
  }
  for (const MRead& r : m_writes_)
    if (!modules_[static_cast<std::size_t>(r.slot)]->m_write_changes_nothing(r.file, r.word, r.value)) return false;
  const DataTableLayout& L = *program_->layout;
  inputs_scratch_.assign(probe_inputs_.begin(), probe_inputs_.end());
  for (const ScannedModule& sm : scanned_) {
    const SlotImage& si = L.input_slots[static_cast<std::size_t>(sm.module->slot())];
    if (si.present) sm.module->input_scan(std::span<std::uint16_t>(inputs_scratch_.data() + si.first, si.words));
  }
  return inputs_scratch_ == probe_inputs_;
}

// After a probe that repeated nothing. A change the program makes itself — a message started, its
// reply taken, its EN cleared — often lasts a few scans in a row and then settles, so the next
// probes follow at once until kProbesBeforeBackoff have failed in a row (a probe costs the saving and
// comparing of the table, a few hundred instructions beside an executed scan's thousands). After
// that the wait doubles with each failure, to 64 scans: a program that changes its table every
// scan, or whose network has an event at the end of most scans, pays for a probe at most every 64.
void Runtime::probe_failed() {
  if (++probe_failures_ >= kProbesBeforeBackoff) wait_longer_before_probing();
}

// What a probe records before its scan, for its own test and for a cycle's (probe_cycle).
struct Runtime::ProbeStart {
  VirtualTime start;
  std::uint64_t instructions;
  std::uint64_t process_writes;
  std::uint64_t module_time_reads;
  std::uint64_t between_scan_writes;
  EventQueue::EventId scheduled;
  StiTimer sti;
  std::uint64_t routine_runs;
};

constexpr std::uint32_t kScansAfterAServicedChange = 2;

std::int64_t Runtime::probe_and_repeat(VirtualTime end) {
  if (const std::int64_t taken = repeat_remembered(end); taken > 0) return taken;
  before_probe_.assign(data_.words(), data_.words() + data_.size());
  const std::uint64_t message_calls = message_calls_;
  const ProbeStart probe{clock_.now(),
                         stats_.instructions,
                         process_writes_,
                         interp_->module_time_reads(),
                         interp_->between_scan_writes(),
                         events_.scheduled(),
                         interp_->sti(),
                         interp_->routine_runs()};
  const VirtualTime start = probe.start;
  const std::uint64_t instructions = probe.instructions;
  const std::uint64_t process_writes = probe.process_writes;
  const std::uint64_t module_time_reads = probe.module_time_reads;
  const std::uint64_t between_scan_writes = probe.between_scan_writes;
  const StiTimer& sti_before = probe.sti;
  if (network_) network_->holdings(station_, net_before_probe_);
  else net_before_probe_.clear();
  interp_->reset_pid_same_until();
  probing_ = true;
  probe_unsteady_ = false;
  reached_.clear();
  m_reads_.clear();
  m_writes_.clear();
  timer_executions_.clear();
  interp_->record_timer_executions(&timer_executions_);
  scan_once(false);
  interp_->record_timer_executions(nullptr);
  probing_ = false;
  VirtualTime t = clock_.now();  // the end of the probe, the start of the first repeat
  const Nanoseconds d = t - start;
  const std::uint16_t* w = data_.words();
  const DataTableLayout& L = *program_->layout;
  // The probe changed nothing but the runtime's own status words (and the ACC and stamp of timers
  // carried across their ticks, below), nothing is pending, every module is still passive (the
  // probe's output scan may have handed one an output image a tool changed, and a drive told to
  // start is no longer settled), and no module it reached
  // through M0/M1 or an instruction counted a change: the next scan would do exactly what it did.
  // An event that ran at its end may have changed a field input or a module: that is allowed only
  // when no module instruction of the probe asked the time of its execution (the 1747-SDN's DEM
  // advances the network to it, so an event could run in the middle of the scan), no process
  // changed a word, and every module still gives the input image and the M0/M1 answers the probe
  // read, and would take every M0/M1 write it made without a change.
  // The STI timer: no expiry, no routine run, no STS restart during the probe.
  const StiTimer& sti = interp_->sti();
  const bool sti_same = sti == sti_before;
  bool repeats = mode_ == Mode::Run && !fault_ && !probe_unsteady_ && sti_same &&
                 interp_->routine_runs() == probe.routine_runs && interp_->nothing_pending_between_scans() &&
                 modules_passive() && reached_modules_unchanged();
  // Alone on a MSG network: its end-of-scan servicing left nothing to send, and the repeats end
  // before the network's next change (quiet_until). A probe that started a message set its EN, one
  // that aborted it its ER: the table shows both. A MicroLogix 1000 MSG whose transmit buffer is busy
  // only sets EW and leaves the network as it was, so its next scan does the same.
  std::optional<VirtualTime> network_quiet;
  if (network_) {
    network_quiet = network_->quiet_until(station_, t);
    repeats = repeats && network_quiet;
  }
  const std::uint16_t s33_before = before_probe_[L.status_word(status::kCommBits)];
  for (int s : kRuntimeStatusWords) before_probe_[L.status_word(s)] = w[L.status_word(s)];
  // Timers: those that accumulate alone are carried across ticks (their ACC and stamp may differ
  // after the probe); any other timer that read the clock bounds the repeats to the
  // tick the probe started in (sort_timer_executions).
  accumulating_.clear();
  carried_before_.clear();
  const bool timing = repeats && sort_timer_executions(d);
  // Counted words (sort_counted_words): those the probe advanced by their step are carried, and bound
  // the repeats to the scans whose compares and flags stay the probe's.
  counting_.clear();
  const std::int64_t count_limit =
      repeats && !counted_words_.empty() ? sort_counted_words() : std::numeric_limits<std::int64_t>::max();
  const bool steady = repeats;  // everything held but, perhaps, the table
  repeats = repeats && std::equal(before_probe_.begin(), before_probe_.end(), w);
  const bool across_events = interp_->module_time_reads() == module_time_reads;
  if (repeats && events_at_last_scan_end_ != 0)
    repeats = across_events && process_writes_ == process_writes && probe_reads_the_same();
  if (!repeats) {
    // The probe changed the table and nothing else, with no event at its end and the network holding
    // what it held, and so did the probe before it (probes follow at once after a failure): it may be
    // the first scan of a cycle of two (probe_cycle). Not after one changing probe alone: a change that
    // settles at the next scan (ProbesFollowAtOnceAfterAFewChangingScans) would spend that scan, which
    // then repeats, as the pair's second. (A probe that started a
    // message that stays in a buffer, or took one's reply, changed the network: the next scan would not
    // bring it back, and is probed on its own.) The S:33 word goes back as the probe found it (the cycle
    // compares it aside).
    if (steady && cycles_allowed_ && probe_failures_ > 0 && events_at_last_scan_end_ == 0 && t < end &&
        network_kept()) {
      before_probe_[L.status_word(status::kCommBits)] = s33_before;
      return 1 + probe_cycle(end, probe);
    }
    probe_failed();
    return 1;
  }
  const VirtualTime pid_until = interp_->pid_same_until();  // a timed PID's next update, or max
  RepeatBasis basis{start,
                    d,
                    stats_.last,  // what the probe's housekeeping was given
                    stats_.instructions - instructions,
                    static_cast<std::uint16_t>((data_.status(status::kCommBits) ^ s33_before) & 0x0200u),
                    timing,
                    pid_until,
                    count_limit,
                    across_events,
                    network_quiet,
                    probe.routine_runs,
                    process_writes,
                    between_scan_writes};
  // A probe that leaves nothing outside the table to follow (no timer read the clock, no counted word,
  // no timed PID, no STI, no module reached, no event at its end) is remembered: a later scan that finds
  // the same table repeats it without a probe (repeat_remembered).
  steady_.valid = cycles_allowed_ && !timing && accumulating_.empty() && counting_.empty() &&
                  pid_until == std::numeric_limits<VirtualTime>::max() && sti.file == 0 && reached_.empty() &&
                  m_reads_.empty() && m_writes_.empty() && message_calls_ == message_calls &&
                  events_at_last_scan_end_ == 0;
  if (steady_.valid) {
    steady_.table.assign(w, w + data_.size());
    steady_.basis = basis;
    steady_.input_scan_ns = input_scan_ns_;
  }
  const std::int64_t taken = repeat_scans(end, basis, false);
  return 1 + taken;
}

// The repeats of a steady scan (docs/semantics.md "Repeated scans"), from the clock's time: the probe's,
// or (remembered) a scan taken from steady_ with no probe, which takes nothing rather than count a failure.
std::int64_t Runtime::repeat_scans(VirtualTime end, const RepeatBasis& b, bool remembered) {
  VirtualTime t = clock_.now();
  const Nanoseconds d = b.d;
  const DataTableLayout& L = *program_->layout;
  const std::uint16_t* w = data_.words();
  const StiTimer& sti = interp_->sti();
  const std::int64_t count_limit = b.count_limit;
  const bool across_events = b.across_events;
  const std::optional<VirtualTime>& network_quiet = b.network_quiet;
  const std::uint64_t per_scan = b.per_scan;
  // A timed PID falls due at a known time: the repeats end with the last scan that ends by it.
  const VirtualTime pid_until = b.pid_until;
  const bool pid_timing = pid_until != std::numeric_limits<VirtualTime>::max();
  const Nanoseconds scan_time = b.scan_time;
  const std::uint16_t s33_toggle = b.s33_toggle;
  const FileLayout& rtc = L.function_file(FunctionFile::RTC);
  std::int64_t taken = 0;
  // Takes k scans from t without executing them: each would have advanced S:4 at its program scan
  // (after its input scan), toggled S:33/9 (when the probe did), and gone through housekeeping
  // with the probe's scan time.
  const auto take = [&](std::int64_t k) {
    advance_free_running_clock(t + (k - 1) * d + input_scan_ns_);
    const std::uint16_t s33 = data_.status(status::kCommBits);
    if (k % 2 == 1) data_.set_status(status::kCommBits, static_cast<std::uint16_t>(s33 ^ s33_toggle));
    for (std::int64_t i = 0; i < k; ++i) {
      const std::uint16_t avg = data_.status(status::kAvgScan);
      housekeeping(scan_time);
      if (data_.status(status::kAvgScan) == avg) {  // the rest leave every status word as it is
        const auto rest = static_cast<std::uint64_t>(k - i - 1);
        stats_.scans += rest;
        stats_.total += static_cast<Nanoseconds>(rest) * scan_time;
        break;
      }
    }
    stats_.instructions += per_scan * static_cast<std::uint64_t>(k);
    stats_.repeated += static_cast<std::uint64_t>(k);
    t += k * d;
    taken += k;
    // The carried timers' and counted words as the k scans leave them, before any event can read them.
    if (!accumulating_.empty()) set_accumulated_timers(taken, d);
    if (!counting_.empty()) set_counted_words(taken);
  };
  // Every repeated scan must end before `horizon`: a timing STI's expiry falls in the middle of the
  // scan that reaches it, a timer's tick ends (a scan may end on it: its reads come before), a timed
  // PID's loop update falls due (a scan may end on it), the MSG network's servicing at the end of a
  // scan would find something new.
  VirtualTime horizon = std::numeric_limits<VirtualTime>::max();
  if (sti.file != 0) horizon = sti.due;
  if (pid_timing) horizon = std::min(horizon, pid_until + 1);
  if (b.timing) horizon = std::min(horizon, (b.start / timer_tick_ns_ + 1) * timer_tick_ns_ + 1);
  // A carried timer reaches PRE at a known tick: the scan whose read of it falls in that tick sets DN
  // (TON, RTO) or clears it (TOF) and is executed. A repeat n scans after the probe reads at
  // read_at + n d, so it must start before the tick less the read's offset (and end d later).
  for (const AccumulatingTimer& a : accumulating_) {
    const std::int64_t pre = static_cast<std::int16_t>(w[a.word + 1]);
    const VirtualTime reach = (a.stamp0 + (pre - a.acc0) * a.units_per_acc) * a.unit;
    horizon = std::min(horizon, reach - (a.read_at - b.start) + d);
  }
  const VirtualTime program_horizon = horizon;  // without the network's
  if (network_quiet) horizon = std::min(horizon, *network_quiet);
  bool changed_between = false;  // the events between repeats changed something: the repeats stop here
  bool serviced_change = false;  // the last scan taken ran the servicing that met the network's change
  for (;;) {
    // How many scans would repeat it: those that start before `end`, end before the next event,
    // and (with a real-time clock) start their program scan in the same second, so the clock
    // words stay.
    std::int64_t k = t < end ? (end - t + d - 1) / d : 0;
    std::int64_t in_second = k;
    if (rtc.present) {
      const VirtualTime next_second = (rtc_second_ + 1) * kNsPerS;
      in_second = std::max<std::int64_t>(0, (next_second - t - input_scan_ns_ + d - 1) / d);
      k = std::min(k, in_second);
    }
    // A program that reads bits of S:4: the repeats end before the scan that would see one change.
    const std::int64_t same_clock = scans_before_the_clock_bits_change(t, d);
    k = std::min(k, same_clock);
    const std::optional<VirtualTime> next = events_.next_time();
    if (next) k = std::min<std::int64_t>(k, (*next - t - 1) / d);
    if (horizon != std::numeric_limits<VirtualTime>::max())
      k = std::min<std::int64_t>(k, std::max<std::int64_t>(0, (horizon - t - 1) / d));
    k = std::min(k, count_limit - taken);
    if (k > 0) {
      take(k);
      events_.run_until(t);  // none is due before t: this moves the clock
    }
    // The next scan would end at or after the next event. Its program scan is still the probe's
    // (the event runs after it), so it is taken too when the probe may repeat across events; the
    // events then run as at the end of an executed scan, and the repeats go on while they changed
    // nothing the program reads.
    if (!across_events || !next || t >= end || (rtc.present && in_second <= k) || same_clock <= k || t + d >= horizon ||
        taken >= count_limit)
      break;
    take(1);
    events_at_last_scan_end_ = events_.run_until(t);
    if (mode_ != Mode::Run || fault_ || interp_->routine_runs() != b.routine_runs ||
        !interp_->nothing_pending_between_scans() || !modules_passive() ||
        process_writes_ != b.process_writes || interp_->between_scan_writes() != b.between_scan_writes ||
        !probe_reads_the_same()) {
      changed_between = true;
      break;
    }
  }
  // The repeats ended at the MSG network's next change alone: the next scan's servicing, at its end, would
  // find a frame arrived, a message's second or its timeout. Its program scan, input and output scans and
  // housekeeping are still the probe's (every other bound lets it start and end, and no event runs before
  // its end), so it is taken as a repeat and the servicing runs at its end as scan_once runs it, before
  // the events due then (none is). Executing it would give the same; a probe of it would only find the
  // servicing's change (msg/filler alone: one executed scan fewer in each 12 ms poll). Only when the
  // probe's scan left the network holding what it held (network_kept): a scan that restarts a message
  // its own rungs cleared (OTU of EN, then the MSG rung true) shows nothing in the table, but replaces the
  // message before the servicing, which then drops the old one's frame; taken as a repeat, it would not.
  // A remembered scan calls nothing outside the table (repeat_remembered): it leaves the network as it is.
  if (network_quiet && !changed_between && t < end && t + d >= *network_quiet && t + d < program_horizon &&
      taken < count_limit && (remembered || network_kept())) {
    const std::optional<VirtualTime> next = events_.next_time();
    const bool same_second = !rtc.present || (rtc_second_ + 1) * kNsPerS - t - input_scan_ns_ > 0;
    if ((!next || *next > t + d) && same_second && scans_before_the_clock_bits_change(t, d) >= 1) {
      take(1);
      network_->scanned(station_, t);
      events_at_last_scan_end_ = events_.run_until(t);
      serviced_change = true;
    }
  }
  // A probe that could take no scan (the next event, a timer's tick or the STI was due within one)
  // was an executed scan like any other, but its saving and comparing of the table was wasted: it
  // counts as a failure (a 1747-SDN program with a DEM, whose network has an event at the end of
  // most scans, probes much less often), and the next scan, the one that reaches the event, is
  // executed without a probe.
  if (taken == 0) {
    if (remembered) return 0;  // nothing was taken or changed: the caller probes
    probe_failed();
    probe_wait_ = std::max<std::uint32_t>(probe_wait_, 1);
  } else {
    probe_failures_ = 0;
    probe_backoff_ = 1;
  }
  // The repeats ended because an STI expiry falls in the next scan: that scan runs the routine (its
  // timer moves), so a probe of it would only find the change and make the next probe wait. It is
  // executed without a probe, and the scan after it probes (ml1100_sti: two executed scans in each
  // 10 ms period instead of three).
  if (sti.file != 0 && t < end && t + d >= sti.due) probe_wait_ = std::max<std::uint32_t>(probe_wait_, 1);
  // After the servicing that met the network's change (a message ended: DN or ER; a seconds word moved),
  // the program reacts in the scans that follow: a polling rung (`XIO EN MSG`) clears EN at the next scan
  // and starts the message again at the one after, so probes of those two could only find the change.
  // They are executed without a probe, and the third probes (decision: a program that does not react
  // loses at most two repeats).
  if (serviced_change) probe_wait_ = std::max<std::uint32_t>(probe_wait_, kScansAfterAServicedChange);
  return taken;
}

// Remembered steady scans (docs/semantics.md "Remembered steady scans"). A probe whose scan left the table
// as it found it and read nothing outside it but the table's own words (no timer reading the clock, no
// counted word, no timed PID, no STI, no module reached through M0/M1 or an instruction, no MSG started
// or aborted, no event at its end; the program has no ASCII or Modbus channel, no data log and no read
// of S:4: cycles_allowed_; SVC, REF, IIM and IOM rule repeats out) is remembered with what its repeats
// went by. A scan that would start from the same table (but the runtime's own status words, which such
// a program does not read) executes the same instructions on the same words and leaves the table as it
// found it, as the remembered one did: it is the first of the repeats, taken without a probe, when,
// besides, every module would give the input image the table holds (a tool may have changed a field
// input since the last input scan), the HSC would load and count nothing at its start (the last scan
// may have set SP), the network has nothing to send (quiet_until), the STI is off and no mode or force
// changed since (write_mode_bits forgets the scan). A program that polls a MSG comes back to the table
// it repeated after each reply or failure (EN cleared, the message started again): its probe, one
// executed scan and the saving and comparing of the table in every poll, is spared. The repeats end at
// the first event (a remembered scan does not know which module answers the probe read).
std::int64_t Runtime::repeat_remembered(VirtualTime end) {
  static_assert(std::tuple_size_v<decltype(SteadyScan::runtime_words)> == kRuntimeStatusWords.size());
  if (!steady_.valid || interp_->sti().file != 0) return 0;
  const std::uint16_t* w = data_.words();
  const std::uint16_t* r = steady_.table.data();
  std::uint32_t from = 0;
  for (const std::uint32_t skip : steady_.runtime_words) {
    if (!std::equal(w + from, w + skip, r + from)) return 0;
    from = skip + 1;
  }
  if (!std::equal(w + from, w + data_.size(), r + from) || !inputs_as_scanned() ||
      !interp_->hsc().at_rest(data_.words()))
    return 0;
  std::optional<VirtualTime> network_quiet;
  if (network_) {
    network_quiet = network_->quiet_until(station_, clock_.now());
    if (!network_quiet) return 0;
  }
  RepeatBasis b = steady_.basis;
  b.start = clock_.now();
  b.across_events = false;
  b.network_quiet = network_quiet;
  b.routine_runs = interp_->routine_runs();
  b.process_writes = process_writes_;
  b.between_scan_writes = interp_->between_scan_writes();
  accumulating_.clear();
  counting_.clear();
  input_scan_ns_ = steady_.input_scan_ns;
  const std::size_t events_before = events_at_last_scan_end_;
  events_at_last_scan_end_ = 0;  // a scan taken ends before the next event
  const std::int64_t taken = repeat_scans(end, b, true);
  if (taken == 0) events_at_last_scan_end_ = events_before;
  return taken;
}

bool Runtime::inputs_as_scanned() {
  const DataTableLayout& L = *program_->layout;
  const FileLayout& in = L.files[1];
  const std::uint16_t* w = data_.words() + in.base;
  inputs_scratch_.assign(w, w + in.elements);
  for (const ScannedModule& sm : scanned_) {
    const SlotImage& si = L.input_slots[static_cast<std::size_t>(sm.module->slot())];
    if (si.present) sm.module->input_scan(std::span<std::uint16_t>(inputs_scratch_.data() + si.first, si.words));
  }
  if (in_forces_live_)
    for (std::uint32_t i = 0; i < inputs_scratch_.size() && i < in_force_mask_.size(); ++i)
      inputs_scratch_[i] = static_cast<std::uint16_t>((inputs_scratch_[i] & ~in_force_mask_[i]) |
                                                      (in_force_value_[i] & in_force_mask_[i]));
  return std::equal(inputs_scratch_.begin(), inputs_scratch_.end(), w);
}

// Repeated cycles (docs/semantics.md "Repeated cycles"). A program whose MSG fails at once (D0h on Ethernet
// without an IP address, 12h on a channel 0 with no DF1) and that starts it again when its rung finds EN
// clear changes its table at every scan, so no scan repeats the one before; but two scans in a row, the
// one that starts the message and ends it with ER and the one whose false rung clears EN, bring the table
// back to where it was. The probe (scan A) has passed every test of a repeat but the table; scan B is
// executed here (a scan like any other), and the pair repeats when, after it:
// - the table is the one the probe found, but the runtime's own status words and the carried timers
//   (a timer private to its TON/TOF/RTO, executed once in each of A and B, advancing: after n pairs its
//   words are a function of the tick of its last read, which moves by the pair's length D);
// - A and B left everything outside the table as the probe found it: the network holds the same
//   messages and frames (MessageNetwork::holdings; a message that failed at once left nothing), no event
//   was scheduled or ran, no field process or between-scan write touched the table, the STI timer is the
//   same, the modules reached counted no change and are passive after both scans, and A's output image
//   was B's (the O file at A's end as the probe found it: modules saw the same image);
// - the controller is in Run without a fault and nothing is pending.
// Then a pair that starts from that table at a later time executes the same instructions on the same
// words (each instruction of a repeatable program is a function of the table, the rung and the time the
// bounds below keep: the same as for one scan), takes A's and B's times, and leaves the same table. The
// pairs are taken whole, each one ending before everything that ends the repeats of one scan: the next
// event, an STI expiry, a timed PID's update, a timer's tick (a timer reading the clock but not carried:
// the tick the probe started in), the scan whose read of a carried timer reaches PRE, the MSG network's
// next change (quiet_until after B), the clock's next second (RTC), and run_for's end (B of the last pair
// starts before it). The status words follow as executing would give: S:4 at the last program scan,
// S:33/9 toggled once per pair that toggled it, and housekeeping with A's and B's scan times in turn
// until a pair leaves S:3, S:22, S:23 and S:35 as it found them (S:23's average is a monotone map of
// itself over a pair, so it settles), the rest counted in bulk. A program that reads S:4, an ASCII or
// Modbus channel (their jobs live outside the table) or a data log queue (DLG's records) never cycles.
std::int64_t Runtime::probe_cycle(VirtualTime end, const ProbeStart& probe) {
  std::uint16_t* const w = data_.words();
  const DataTableLayout& L = *program_->layout;
  const FileLayout& out_file = L.files[0];
  // A's output image is the probe's: the O words as the probe found them.
  const bool same_outputs = std::equal(w + out_file.base, w + out_file.base + out_file.words(),
                                       before_probe_.begin() + out_file.base);
  for (const auto& [word, value] : carried_before_) before_probe_[word] = value;
  carried_before_.clear();
  accumulating_.clear();
  counting_.clear();  // a cycle carries no counted word: its table must come back whole
  const std::uint16_t s33_before = before_probe_[L.status_word(status::kCommBits)];
  const VirtualTime mid = clock_.now();
  const Nanoseconds d_a = mid - probe.start;
  const Nanoseconds scan_time_a = stats_.last;
  const std::size_t second = timer_executions_.size();
  probing_ = true;
  interp_->record_timer_executions(&timer_executions_);
  scan_once(false);
  interp_->record_timer_executions(nullptr);
  probing_ = false;
  VirtualTime t = clock_.now();
  const Nanoseconds d = t - probe.start;  // the pair's length
  const Nanoseconds scan_time_b = stats_.last;
  const StiTimer& sti = interp_->sti();
  bool repeats = same_outputs && mode_ == Mode::Run && !fault_ && !probe_unsteady_ && sti == probe.sti &&
                 interp_->routine_runs() == probe.routine_runs &&
                 events_at_last_scan_end_ == 0 && events_.scheduled() == probe.scheduled &&
                 process_writes_ == probe.process_writes && interp_->between_scan_writes() == probe.between_scan_writes &&
                 interp_->nothing_pending_between_scans() && modules_passive() && reached_modules_unchanged();
  std::optional<VirtualTime> network_quiet;
  if (repeats && network_) {
    network_quiet = network_->quiet_until(station_, t);
    network_->holdings(station_, net_after_cycle_);
    repeats = network_quiet && net_after_cycle_ == net_before_probe_;
  }
  for (int st : kRuntimeStatusWords) before_probe_[L.status_word(st)] = w[L.status_word(st)];
  const bool timing = repeats && sort_timer_executions(d, second);
  repeats = repeats && std::equal(before_probe_.begin(), before_probe_.end(), w);
  if (!repeats) {
    probe_failed();
    return 1;
  }
  VirtualTime horizon = std::numeric_limits<VirtualTime>::max();
  if (sti.file != 0) horizon = sti.due;
  if (const VirtualTime pid_until = interp_->pid_same_until(); pid_until != std::numeric_limits<VirtualTime>::max())
    horizon = std::min(horizon, pid_until + 1);
  if (timing) horizon = std::min(horizon, (probe.start / timer_tick_ns_ + 1) * timer_tick_ns_ + 1);
  // A carried timer's last read in a pair is B's: the pair starting at s reads it at s + (read_at - start).
  for (const AccumulatingTimer& a : accumulating_) {
    const std::int64_t pre = static_cast<std::int16_t>(w[a.word + 1]);
    const VirtualTime reach = (a.stamp0 + (pre - a.acc0) * a.units_per_acc) * a.unit;
    horizon = std::min(horizon, reach - (a.read_at - probe.start) + d);
  }
  if (network_quiet) horizon = std::min(horizon, *network_quiet);
  // Pairs whose B starts before `end`, that end before the next event and the horizon, and (with a
  // real-time clock) end by the next second, so that every program scan in them starts in this one.
  std::int64_t k = end - t > d_a ? (end - t - d_a + d - 1) / d : 0;
  if (const std::optional<VirtualTime> next = events_.next_time()) k = std::min<std::int64_t>(k, (*next - t - 1) / d);
  if (horizon != std::numeric_limits<VirtualTime>::max())
    k = std::min<std::int64_t>(k, std::max<std::int64_t>(0, (horizon - t - 1) / d));
  if (L.function_file(FunctionFile::RTC).present)
    k = std::min<std::int64_t>(k, std::max<std::int64_t>(0, ((rtc_second_ + 1) * kNsPerS - t) / d));
  if (k <= 0) {
    probe_failed();
    return 1;
  }
  const std::uint64_t per_pair = stats_.instructions - probe.instructions;
  advance_free_running_clock(t + (k - 1) * d + d_a + input_scan_ns_);
  const std::uint16_t s33_toggle = (data_.status(status::kCommBits) ^ s33_before) & 0x0200u;
  if (k % 2 == 1) data_.set_status(status::kCommBits, static_cast<std::uint16_t>(data_.status(status::kCommBits) ^ s33_toggle));
  constexpr std::array<int, 4> kHousekeeping = {status::kWatchdog, status::kMaxScan, status::kAvgScan, status::kLastScanMs};
  for (std::int64_t i = 0; i < k; ++i) {
    std::array<std::uint16_t, 4> found{};
    for (std::size_t j = 0; j < found.size(); ++j) found[j] = data_.status(kHousekeeping[j]);
    housekeeping(scan_time_a);
    housekeeping(scan_time_b);
    bool same = true;
    for (std::size_t j = 0; j < found.size(); ++j) same = same && found[j] == data_.status(kHousekeeping[j]);
    if (same) {  // every later pair leaves them as they are
      const auto rest = static_cast<std::uint64_t>(k - i - 1);
      stats_.scans += 2 * rest;
      stats_.total += static_cast<Nanoseconds>(rest) * (scan_time_a + scan_time_b);
      break;
    }
  }
  stats_.instructions += per_pair * static_cast<std::uint64_t>(k);
  stats_.repeated += 2 * static_cast<std::uint64_t>(k);
  t += k * d;
  if (!accumulating_.empty()) set_accumulated_timers(k, d);
  events_.run_until(t);
  probe_failures_ = 0;
  probe_backoff_ = 1;
  return 1 + 2 * k;
}

// Timers accumulating across ticks (docs/semantics.md "Timers accumulating across ticks"). A timer
// read the clock in the probe when its execution restarted its stamp or advanced its ACC
// (word_ops::timer_clock_use). One whose element only its own instructions reach (timer_private_),
// executed once in the probe, advancing, and still timing (TT) after it, is carried: every other
// instruction of a repeat reads what it read in the probe (the bits EN, TT and DN and PRE stay while
// ACC < PRE), so the repeat takes the probe's path and executes the timer once, at the same offset
// in the scan, advancing again. Its words are then a function of the tick of each read: n scans
// after the probe the stamp is the tick of read_at + n d (for the 1.0 s base, the unwrapped stamp
// moved by whole seconds) and ACC the probe's plus the units since the probe's stamp. That holds
// while each scan's advance sees less than 256 ticks since the stamp (the stamp is a byte): d under
// 255 ticks, or 155 with the 1.0 s base, whose stamp may lag its read by 99. Any other clock read (a
// restart, a second execution, a timer another instruction reaches) bounds the repeats to the tick
// the probe started in, the rule before this one. A timer timing that the probe did not execute (its
// subroutine not called, a JMP over it) is not executed in a repeat either: it reads nothing.
bool Runtime::sort_timer_executions(Nanoseconds d, std::size_t second) {
  std::uint16_t* const w = data_.words();
  bool timing = false;
  // Which scan of a cycle each execution was in (second: the first of the second scan's; 0 for a probe
  // of one scan), kept in the flags' unused top bit while the executions are sorted by element.
  constexpr std::uint32_t kSecondScan = 1u << 31;
  for (std::size_t i = second; second != 0 && i < timer_executions_.size(); ++i) timer_executions_[i].flags |= kSecondScan;
  // Most probes record one timer or none: no sort (std::stable_sort takes a buffer from the heap).
  if (timer_executions_.size() > 1)
    std::stable_sort(timer_executions_.begin(), timer_executions_.end(),
                     [](const word_ops::TimerExecution& a, const word_ops::TimerExecution& b) { return a.word < b.word; });
  for (std::size_t i = 0; i < timer_executions_.size();) {
    const std::size_t first = i;
    const std::uint32_t word = timer_executions_[i].word;
    std::size_t end = i;
    bool reads = false, all_advance = true;
    for (; end < timer_executions_.size() && timer_executions_[end].word == word; ++end) {
      const word_ops::TimerExecution& e = timer_executions_[end];
      const word_ops::TimerClockUse use = word_ops::timer_clock_use(e.op, e.control, e.acc, e.pre, e.rung, false);
      reads = reads || use != word_ops::TimerClockUse::None;
      all_advance = all_advance && use == word_ops::TimerClockUse::Advance;
    }
    i = end;
    if (!reads) continue;
    // The last execution (the sort is stable): the one whose read the timer's words now show.
    const word_ops::TimerExecution& x = timer_executions_[end - 1];
    // Once in the probe's scan; in a cycle, once in each of its two scans (the first in the first).
    const bool once = second == 0 ? end == first + 1
                                  : end == first + 2 && (timer_executions_[first].flags & kSecondScan) == 0 &&
                                        (x.flags & kSecondScan) != 0;
    const bool base1s = (x.flags & bc::kFlagA) != 0;
    const Nanoseconds unit = (x.flags & bc::kFlagB) ? kNsPerMs : kTick;
    const std::int64_t tick = x.at / unit;  // word_ops::timer_tick, unwrapped
    const std::int64_t stamp_lag = (tick - (w[x.word] & bits::kStampMask)) & 0xFF;
    const auto acc = static_cast<std::int16_t>(w[x.word + 2]);
    const bool carried = once && all_advance && x.word < timer_private_.size() && timer_private_[x.word] &&
                         (w[x.word] & bits::kTT) != 0 && acc < static_cast<std::int16_t>(w[x.word + 1]) &&
                         d < (base1s ? 155 : 255) * unit && stamp_lag < (base1s ? 100 : 1);
    if (!carried) {
      timing = true;
      continue;
    }
    accumulating_.push_back({x.word, x.at, unit, tick - stamp_lag, base1s ? 100 : 1, acc});
    carried_before_.emplace_back(x.word, before_probe_[x.word]);
    carried_before_.emplace_back(x.word + 2, before_probe_[x.word + 2]);
    before_probe_[x.word] =
        static_cast<std::uint16_t>((before_probe_[x.word] & ~bits::kStampMask) | (w[x.word] & bits::kStampMask));
    before_probe_[x.word + 2] = w[x.word + 2];
  }
  return timing;
}

// Writes the carried timers' ACC and stamp as n scans after the probe leave them (sort_timer_executions).
void Runtime::set_accumulated_timers(std::int64_t n, Nanoseconds d) {
  for (const AccumulatingTimer& a : accumulating_) {
    const std::int64_t tick = (a.read_at + n * d) / a.unit;
    const std::int64_t units = (tick - a.stamp0) / a.units_per_acc;
    const std::int64_t stamp = a.stamp0 + units * a.units_per_acc;
    data_.set_word(a.word, static_cast<std::uint16_t>((data_.word(a.word) & ~bits::kStampMask) |
                                                      (static_cast<std::uint16_t>(stamp) & bits::kStampMask)));
    data_.set_word(a.word + 2, static_cast<std::uint16_t>(a.acc0 + units));
  }
}

// Counted words carried across repeats (docs/semantics.md "Counted words carried across repeats"). A
// counted word's counting instruction runs at most once a scan, and its resets (CLR, MOV c) write
// constants. So when the probe left it at W0 + step (step = k, or -k for SUB; in the 16-bit range),
// W0 being its value before, and at neither a reset's constant c nor at c + step, the counting
// instruction ran once and no reset ran (a reset would leave c, or c + step when the count followed
// it). Every other word is the probe's (the table comparison), so a later scan whose compares on the
// word give the probe's results and whose count sets the probe's flags takes the probe's path: its
// resets stay false, its count runs once, and S:0 is the same at every instruction. Scan n after the
// probe counts from W0 + n step, and its compares read W0 + n step or W0 + (n + 1) step: the repeats
// end before the first scan whose count would set other flags (C, Z, N, or V: an overflow, with the
// S:5/0 trap) than the probe's, or one of whose compares could read a value outside the run of values
// from W0 on at which every compare gives its result at W0 (the probe may have read W0 or W0 + step).
std::int64_t Runtime::sort_counted_words() {
  counting_.clear();
  std::int64_t limit = std::numeric_limits<std::int64_t>::max();
  const std::uint16_t* w = data_.words();
  for (const CountedWord& c : counted_words_) {
    const std::int64_t before = static_cast<std::int16_t>(before_probe_[c.word]);
    const std::int64_t after = static_cast<std::int16_t>(w[c.word]);
    if (before == after) continue;
    const std::int64_t step = c.subtract ? -c.k : c.k;
    if (after != before + step) continue;
    bool reset = false;
    for (const std::int64_t r : c.resets) {
      const std::int64_t counted = r + step;  // as a count after the reset would leave it, either overflow rule
      bool overflow = false;
      reset = reset || after == r || after == word_ops::fit_integer(counted, false, false, overflow) ||
              after == word_ops::fit_integer(counted, false, true, overflow);
    }
    if (reset) continue;
    const int dir = step > 0 ? 1 : -1;
    const unsigned flags = counted_flags(c, before);
    std::vector<std::int64_t> cuts = {-1, 0, -c.k - 1, -c.k, c.k - 1, c.k, INT16_MAX - c.k, INT16_MIN - 1 - c.k,
                                      INT16_MAX + c.k, INT16_MIN - 1 + c.k};
    const std::int64_t counts_to = last_value_where(before, dir, cuts, [&](std::int64_t v) { return counted_flags(c, v) == flags; });
    cuts.clear();
    for (const CountedWord::Compare& cmp : c.compares)
      for (std::size_t i = 0; i < cmp.operand.size(); ++i)
        if (i != cmp.at) {
          cuts.push_back(cmp.operand[i] - 1);
          cuts.push_back(cmp.operand[i]);
        }
    const std::int64_t reads_to = last_value_where(before, dir, cuts, [&](std::int64_t v) {
      return std::all_of(c.compares.begin(), c.compares.end(),
                         [&](const CountedWord::Compare& cmp) { return counted_compare(cmp, v) == counted_compare(cmp, before); });
    });
    // Scan n counts from before + n step (n <= counts_to's) and reads up to before + (n + 1) step.
    const std::int64_t n = std::min((counts_to - before) / step, (reads_to - before) / step - 1);
    if (n < 1) continue;
    limit = std::min(limit, n);
    counting_.push_back({c.word, after, step});
    carried_before_.emplace_back(c.word, before_probe_[c.word]);
    before_probe_[c.word] = w[c.word];
  }
  return limit;
}

void Runtime::set_counted_words(std::int64_t n) {
  for (const CarriedCount& c : counting_) data_.set_word(c.word, static_cast<std::uint16_t>(c.after + n * c.step));
}

// S:4 counts ticks of virtual time, brought up to date at each program scan (advance_free_running_clock).
// Of the bits the program reads, the lowest, b, is the first to change: the bits above it change
// only when a carry passes through it, so all of them stay until S:4 reaches the next multiple of
// 2^b (or wraps to 0, a multiple too). The scans whose program scan (at input_scan_ns_ into the
// scan, as take() advances S:4) starts before the tick that reaches it are the ones that see the
// same bits.
std::int64_t Runtime::scans_before_the_clock_bits_change(VirtualTime t, Nanoseconds d) const {
  if (clock_bits_read_ == 0) return std::numeric_limits<std::int64_t>::max();
  const std::int64_t step = clock_bits_read_ & -static_cast<std::int64_t>(clock_bits_read_);  // 2^b
  const std::int64_t s4 = data_.status(status::kClock);
  const std::int64_t change_tick = s4_tick_ + (step - s4 % step);
  const VirtualTime change_at = change_tick * program_->processor.free_running_clock_tick_ns();
  const Nanoseconds left = change_at - t - input_scan_ns_;
  return left <= 0 ? 0 : (left + d - 1) / d;
}

bool Runtime::run_until(const std::function<bool(const Runtime&)>& pred, Nanoseconds limit) {
  if (pred(*this)) return true;
  const VirtualTime end = clock_.now() + std::max<Nanoseconds>(limit, 0);
  while (clock_.now() < end) {
    scan_once(false);
    if (pred(*this)) return true;
  }
  return false;
}

// ---- Data access for tools ----------------------------------------------------------------------------------

std::optional<Location> Runtime::resolve_tool_address(const Address& a, std::string& error) const {
  const DataTableLayout& L = *program_->layout;
  if (!a.is_indirect() && !a.indexed) {
    auto loc = L.locate(a, &error);
    return loc;
  }
  // Indexed and indirect addresses go through the interpreter's checked resolver.
  DynOperand d;
  d.address = a;
  d.type = a.type;
  d.vtype = a.has_bit() || is_structured(a.type) ? ValueType::Int16 : value_type_of(a.type);
  d.indexed = a.indexed;
  d.bit_offset = a.bit_offset_form;
  d.file = a.file;
  d.element = a.element;
  d.word = a.word;
  d.bit = a.bit;
  const auto ref = [&](const std::optional<IndirectRef>& r) -> std::int32_t {
    if (!r) return -1;
    Address p;
    p.type = r->type;
    p.file = r->file;
    p.element = r->element;
    p.word = r->word;
    auto loc = L.locate(p, &error);
    return loc ? static_cast<std::int32_t>(loc->word) : -2;
  };
  d.ptr_file = ref(a.indirect_file());
  d.ptr_element = ref(a.indirect_element());
  d.ptr_word = ref(a.indirect_word());
  d.ptr_bit = ref(a.indirect_bit());
  if (d.ptr_file == -2 || d.ptr_element == -2 || d.ptr_word == -2 || d.ptr_bit == -2) return std::nullopt;
  Location loc;
  if (!interp_->resolve_for_tool(d, loc, error)) return std::nullopt;
  return loc;
}

RuntimeStatus Runtime::set(std::string_view address, Value v) {
  std::string error;
  auto a = parse_address(address, &error);
  if (!a) return RuntimeStatus::failure(error);
  return set(*a, v);
}

namespace {

// The one value-conversion rule for everything a tool writes (run --set, test files, the
// Controller API), the rule test files always had: a bit takes 0 or 1; a 16- or 32-bit word
// takes an integer in its signed range (hex and binary patterns are sign-extended by the caller,
// vm's callers pass values); a float element takes any finite number a 32-bit float holds. A
// value that does not fit is refused, never wrapped (99999 into N7:0 stored -31073), rounded
// (1.5 stored 2) or squashed (2 on a bit stored 1).
std::string value_refusal(const Address& a, const Value& v, int width) {
  const std::string what = to_string(a);
  if (width == 0) {
    const double d = v.as_double();
    if (!std::isfinite(d) || std::fabs(d) > static_cast<double>(std::numeric_limits<float>::max()))
      return what + " holds a 32-bit float; " + v.to_string() + " does not fit";
    return {};
  }
  if (v.kind == Value::Kind::Float)
    return what + " holds " + (width == 1 ? std::string("a bit") : "integers") + "; " + v.to_string() +
           " is not an integer";
  if (width == 1)
    return v.integer == 0 || v.integer == 1 ? std::string() : what + ": a bit is 0 or 1, not " + v.to_string();
  const std::int64_t max = width == 32 ? std::numeric_limits<std::int32_t>::max() : 32767;
  if (v.integer < -max - 1 || v.integer > max)
    return what + ": " + v.to_string() + " does not fit a " + std::to_string(width) + "-bit word (" +
           std::to_string(-max - 1) + ".." + std::to_string(max) + ")";
  return {};
}

int width_of_location(const Address& a, const Location& loc) {
  if (a.has_bit() || loc.bit >= 0) return 1;
  switch (loc.vtype) {
    case ValueType::Float32: return 0;
    case ValueType::Int32: return 32;
    default: return 16;
  }
}

}  // namespace

RuntimeStatus Runtime::set(const Address& a, Value v) {
  // A bit beyond 15 would shift past the word (UB); the checker's rules (check_tool_address) say
  // so with the program's context, this is the runtime's own guard.
  if (a.bit > 15) return RuntimeStatus::failure(to_string(a) + ": bit number " + std::to_string(a.bit) +
                                                " is out of range 0-15");
  if (auto why = value_refusal(a, v, a.has_bit() ? 1 : 16); !why.empty() && (a.type == FileType::Input || is_mfile(a.type)))
    return RuntimeStatus::failure(why);
  if (a.type == FileType::Input && !a.is_indirect() && !a.indexed) {
    Module* m = module(a.element);
    if (!m) return RuntimeStatus::failure(to_string(a) + ": no module in slot " + std::to_string(a.element));
    const std::uint16_t mask = a.bit >= 0 ? static_cast<std::uint16_t>(1u << a.bit) : 0xFFFF;
    const auto value = static_cast<std::uint16_t>(a.bit >= 0 ? (v.as_bool() ? mask : 0) : v.as_int());
    if (!m->set_field_input(a.word_in_element(), value, mask))
      return RuntimeStatus::failure(to_string(a) + ": the module in slot " + std::to_string(a.element) +
                                    " has no such simulated input");
    return {};
  }
  if (is_mfile(a.type)) {
    const MFile f = a.type == FileType::M0 ? MFile::M0 : MFile::M1;
    std::uint16_t word = 0;
    MAccess r = read_m(a.element, f, a.word_in_element(), word);
    if (r == MAccess::Ok) {
      if (a.bit >= 0) {
        const auto mask = static_cast<std::uint16_t>(1u << a.bit);
        word = static_cast<std::uint16_t>(v.as_bool() ? (word | mask) : (word & ~mask));
      } else {
        word = static_cast<std::uint16_t>(v.as_int());
      }
      r = write_m(a.element, f, a.word_in_element(), word);
    }
    if (r != MAccess::Ok) {
      const std::string why = m_refusal(a.element, f, a.word_in_element(), true);
      return RuntimeStatus::failure(to_string(a) + ": module refused (" + std::string(to_string(r)) + ")" +
                                    (why.empty() ? "" : ": " + why));
    }
    return {};
  }
  std::string error;
  auto loc = resolve_tool_address(a, error);
  if (!loc) return RuntimeStatus::failure(error);
  if (auto why = value_refusal(a, v, width_of_location(a, *loc)); !why.empty()) return RuntimeStatus::failure(why);
  data_.write(*loc, v);
  return {};
}

std::optional<Value> Runtime::get(std::string_view address, std::string* error) const {
  std::string err;
  auto a = parse_address(address, &err);
  if (!a) {
    if (error) *error = err;
    return std::nullopt;
  }
  return get(*a, error);
}

std::optional<Value> Runtime::get(const Address& a, std::string* error) const {
  std::string err;
  if (is_mfile(a.type)) {
    std::uint16_t word = 0;
    Module* m = module(a.element);
    const MAccess r = m ? m->read_m(a.type == FileType::M0 ? MFile::M0 : MFile::M1, a.word_in_element(), word)
                        : MAccess::NoSuchWord;
    if (r != MAccess::Ok) {
      const std::string why = m_refusal(a.element, a.type == FileType::M0 ? MFile::M0 : MFile::M1, a.word_in_element(), false);
      if (error) *error = to_string(a) + ": module refused (" + std::string(to_string(r)) + ")" + (why.empty() ? "" : ": " + why);
      return std::nullopt;
    }
    if (a.bit >= 0) return Value::bit((word >> a.bit) & 1u);
    return Value::of_int(static_cast<std::int16_t>(word));
  }
  auto loc = resolve_tool_address(a, err);
  if (!loc) {
    if (error) *error = err;
    return std::nullopt;
  }
  return data_.read(*loc);
}

Value Runtime::value(std::string_view address) const {
  std::string err;
  auto v = get(address, &err);
  if (!v) throw std::invalid_argument(err);
  return *v;
}

std::string Runtime::format(std::string_view address) const { return value(address).to_string(); }

// ---- Forces ------------------------------------------------------------------------------------------------

RuntimeStatus Runtime::force(std::string_view address, bool on) {
  std::string error;
  auto a = parse_address(address, &error);
  if (!a) return RuntimeStatus::failure(error);
  if (!is_io(a->type) || a->bit < 0 || a->is_indirect() || a->indexed)
    return RuntimeStatus::failure(std::string(address) + ": only I: and O: bits can be forced");
  auto loc = program_->layout->locate(*a, &error);
  if (!loc) return RuntimeStatus::failure(error);
  const bool input = a->type == FileType::Input;
  const std::uint32_t i = loc->word - program_->layout->files[input ? 1 : 0].base;
  auto& mask = input ? in_force_mask_ : out_force_mask_;
  auto& value = input ? in_force_value_ : out_force_value_;
  const auto bit = static_cast<std::uint16_t>(1u << loc->bit);
  mask[i] |= bit;
  value[i] = static_cast<std::uint16_t>(on ? (value[i] | bit) : (value[i] & ~bit));
  write_mode_bits();
  return {};
}

RuntimeStatus Runtime::unforce(std::string_view address) {
  std::string error;
  auto a = parse_address(address, &error);
  if (!a) return RuntimeStatus::failure(error);
  if (!is_io(a->type) || a->bit < 0 || a->is_indirect() || a->indexed)
    return RuntimeStatus::failure(std::string(address) + ": only I: and O: bits can be forced");
  auto loc = program_->layout->locate(*a, &error);
  if (!loc) return RuntimeStatus::failure(error);
  const bool input = a->type == FileType::Input;
  const std::uint32_t i = loc->word - program_->layout->files[input ? 1 : 0].base;
  auto& mask = input ? in_force_mask_ : out_force_mask_;
  mask[i] = static_cast<std::uint16_t>(mask[i] & ~(1u << loc->bit));
  write_mode_bits();
  return {};
}

void Runtime::clear_forces() {
  std::fill(in_force_mask_.begin(), in_force_mask_.end(), 0);
  std::fill(out_force_mask_.begin(), out_force_mask_.end(), 0);
  write_mode_bits();
}

void Runtime::enable_forces(bool enabled) {
  forces_enabled_ = enabled;
  write_mode_bits();
}

// ---- Modules ------------------------------------------------------------------------------------------------

Module* Runtime::module(int slot) const {
  if (slot < 0 || slot >= kMaxSlots) return nullptr;
  return modules_[static_cast<std::size_t>(slot)];
}

EventQueue::EventId Runtime::schedule_at(VirtualTime at, EventQueue::Callback cb) {
  return events_.schedule_at(at, std::move(cb));
}

bool Runtime::cancel_event(EventQueue::EventId id) { return events_.cancel(id); }

MAccess Runtime::read_m(int slot, MFile f, int word, std::uint16_t& value) {
  Module* m = module(slot);
  if (!m) return MAccess::NoSuchWord;
  if (probing_) [[unlikely]] reach(slot);
  const MAccess a = m->read_m(f, word, value);
  if (probing_ && a == MAccess::Ok) [[unlikely]] m_reads_.push_back({slot, f, word, value});
  return a;
}

MAccess Runtime::read_m_block(int slot, MFile f, int word, std::span<std::uint16_t> out, std::size_t& done) {
  done = 0;
  Module* m = module(slot);
  if (!m) return MAccess::NoSuchWord;
  if (probing_) [[unlikely]] reach(slot);
  const MAccess a = m->read_m_block(f, word, out, done);
  if (probing_) [[unlikely]] {
    for (std::size_t i = 0; i < done; ++i) m_reads_.push_back({slot, f, word + static_cast<int>(i), out[i]});
  }
  return a;
}

MAccess Runtime::write_m(int slot, MFile f, int word, std::uint16_t value) {
  Module* m = module(slot);
  if (!m) return MAccess::NoSuchWord;
  if (probing_) [[unlikely]] {
    reach(slot);
    m_writes_.push_back({slot, f, word, value});
  }
  return m->write_m(f, word, value);
}

std::string Runtime::m_refusal(int slot, MFile f, int word, bool write) const {
  const Module* m = module(slot);
  return m ? m->m_refusal(f, word, write) : std::string();
}

void Runtime::immediate_input(int slot, int first, int count, std::uint16_t mask) {
  Module* m = module(slot);
  const DataTableLayout& L = *program_->layout;
  if (!m || slot < 0 || slot >= kMaxSlots) return;
  const SlotImage& si = L.input_slots[static_cast<std::size_t>(slot)];
  if (!si.present) return;
  // The module fills a scratch image; only the requested words, under the mask, reach I:.
  std::span<std::uint16_t> tmp(io_scratch_.data(), si.words);
  m->input_scan(tmp);
  std::uint16_t* w = data_.words() + L.files[1].base + si.first;
  for (int k = first; k < first + count && k < static_cast<int>(si.words); ++k)
    w[k] = static_cast<std::uint16_t>((w[k] & ~mask) | (tmp[static_cast<std::size_t>(k)] & mask));
  apply_input_forces(si.first + static_cast<std::uint32_t>(first), static_cast<std::uint32_t>(count));
}

void Runtime::module_instruction(int slot, ModuleInstructionContext& ctx) {
  if (Module* m = module(slot)) {
    if (probing_) [[unlikely]] reach(slot);
    m->execute(ctx);
    return;
  }
  ChassisAccess::module_instruction(slot, ctx);
}

// ---- Field devices ------------------------------------------------------------------------------------------

RuntimeStatus Runtime::inject(std::string_view device, std::string_view fault, std::vector<std::string> args) {
  if (auto counter = hsc_input_name(device); counter >= 0) return inject_hsc_pulses(counter, fault, args);
  DeviceFault f{std::string(device), std::string(fault), std::move(args)};
  for (Module* m : modules_) {
    if (!m) continue;
    DeviceStatus st = m->inject(f);
    if (st.kind == DeviceStatus::Kind::Done) return {};
    if (st.kind == DeviceStatus::Kind::Refused)
      return RuntimeStatus::failure("device " + f.device + ": " + st.message);
  }
  for (const auto& p : processes_) {
    DeviceStatus st = p->inject(f);
    if (st.kind == DeviceStatus::Kind::Done) return {};
    if (st.kind == DeviceStatus::Kind::Refused)
      return RuntimeStatus::failure("device " + f.device + ": " + st.message);
  }
  if (modbus_channel_) {
    DeviceStatus st = modbus_channel_->inject(f);
    if (st.kind == DeviceStatus::Kind::Done) return {};
    if (st.kind == DeviceStatus::Kind::Refused)
      return RuntimeStatus::failure("device " + f.device + ": " + st.message);
  }
  if (ascii_channel_ && ascii_channel_->device().name() == f.device) {
    DeviceStatus st = ascii_channel_->device().inject(f);
    if (st.kind == DeviceStatus::Kind::Done) return {};
    if (st.kind == DeviceStatus::Kind::Refused)
      return RuntimeStatus::failure("device " + f.device + ": " + st.message);
  }
  // The DF1 link on channel 0: its cable and the noise on it (docs/testing.md "DF1 full-duplex"), also on a
  // channel 0 at its factory configuration before any MSG used it.
  if (f.device == kDf1DeviceName) attach_default_df1_port();
  if (f.device == kDf1DeviceName && network_ && network_->df1_port(station_)) {
    if (std::string why = network_->df1_inject(station_, f.fault, f.args); !why.empty())
      return RuntimeStatus::failure("device " + f.device + ": " + why);
    return {};
  }
  return RuntimeStatus::failure("no simulated field device is named '" + f.device + "'");
}

// HSC0 .. HSC5: the pulse-train source wired to a MicroLogix high-speed counter's input (vm/ml_hsc.h);
// -1 for any other name, or on a processor without that counter.
int Runtime::hsc_input_name(std::string_view device) const {
  if (device.size() != 4 || device.substr(0, 3) != "HSC" || device[3] < '0' || device[3] > '5') return -1;
  const int counter = device[3] - '0';
  return counter < interp_->hsc().counters() ? counter : -1;
}

// `device HSC0 pulses N`: N pulses a second on the counter's input from now (0 stops them).
RuntimeStatus Runtime::inject_hsc_pulses(int counter, std::string_view change, const std::vector<std::string>& args) {
  const std::string name = "device HSC" + std::to_string(counter);
  if (change != "pulses" || args.size() != 1)
    return RuntimeStatus::failure(name + ": the high-speed counter's input takes 'pulses N' (N pulses a second, 0 stops them)");
  std::int64_t rate = 0;
  const std::string& text = args[0];
  const bool digits = !text.empty() && text.size() <= 9 && text.find_first_not_of("0123456789") == std::string::npos;
  if (digits) rate = std::stoll(text);
  if (!digits) return RuntimeStatus::failure(name + ": pulses takes a whole number of pulses a second, not '" + text + "'");
  if (auto error = interp_->hsc().set_pulse_rate(counter, rate, clock_.now()); !error.empty())
    return RuntimeStatus::failure(name + ": " + error);
  return {};
}

std::optional<std::vector<std::int64_t>> Runtime::observe(std::string_view device, std::string_view what) const {
  if (auto counter = hsc_input_name(device); counter >= 0 && what == "pulses")
    return std::vector<std::int64_t>{interp_->hsc().pulses_delivered(counter, clock_.now())};
  for (const Module* m : modules_)
    if (m)
      if (auto v = m->observe(device, what)) return v;
  for (const auto& p : processes_)
    if (auto v = p->observe(device, what)) return v;
  if (modbus_channel_)
    if (auto v = modbus_channel_->observe(device, what)) return v;
  if (device == kDf1DeviceName && network_ && network_->df1_port(station_))
    if (auto v = network_->df1_observe(station_, what, clock_.now())) return std::vector<std::int64_t>{*v};
  // A factory-configured channel 0 that nothing has used yet: its port has counted nothing.
  if (device == kDf1DeviceName && default_df1_port() && !(network_ && network_->df1_port(station_)) &&
      df1_count_named(what))
    return std::vector<std::int64_t>{0};
  if (ascii_channel_ && ascii_channel_->device().name() == device) {
    // The channel's own counts, then what the device offers.
    if (what == "buffered") return std::vector<std::int64_t>{static_cast<std::int64_t>(ascii_channel_->buffered())};
    if (what == "dropped") return std::vector<std::int64_t>{static_cast<std::int64_t>(ascii_channel_->dropped())};
    return ascii_channel_->device().observe(what);
  }
  return std::nullopt;
}

std::vector<std::string> Runtime::devices() const {
  std::vector<std::string> out;
  for (const Module* m : modules_)
    if (m)
      for (auto& n : m->device_names()) out.push_back(std::move(n));
  for (const auto& p : processes_) out.push_back(p->name());
  if (ascii_channel_) out.push_back(ascii_channel_->device().name());
  if (modbus_channel_)
    for (auto& n : modbus_channel_->device_names()) out.push_back(std::move(n));
  if (network_ && network_->df1_port(station_)) out.emplace_back(kDf1DeviceName);
  // The inputs of the MicroLogix high-speed counters, which need no bench (vm/ml_hsc.h).
  for (int c = 0; c < interp_->hsc().counters(); ++c) out.push_back("HSC" + std::to_string(c));
  return out;
}

void Runtime::immediate_output(int slot, int first, int count, std::uint16_t mask) {
  Module* m = module(slot);
  const DataTableLayout& L = *program_->layout;
  if (!m || slot < 0 || slot >= kMaxSlots || mode_ != Mode::Run) return;
  const SlotImage& si = L.output_slots[static_cast<std::size_t>(slot)];
  if (!si.present) return;
  for (int k = first; k < first + count && k < static_cast<int>(si.words); ++k) {
    const std::uint32_t i = si.first + static_cast<std::uint32_t>(k);
    out_sent_[i] = static_cast<std::uint16_t>((out_sent_[i] & ~mask) | (forced_output(i) & mask));
  }
  m->output_scan(std::span<const std::uint16_t>(out_sent_.data() + si.first, si.words));
}

}  // namespace softslc

