#include "vm/disassembler.h"

#include <cstdio>

namespace softslc {

std::string_view mnemonic(Op o) {
  if (is_instruction(o)) return spec(to_opcode(o)).mnemonic;
  switch (o) {
    case Op::SOR: return "SOR";
    case Op::BST: return "BST";
    case Op::NXB: return "NXB";
    case Op::BND: return "BND";
    case Op::EOF_: return "EOF";
    default: return "???";
  }
}

namespace {

std::string raw(std::uint32_t o) {
  const std::uint32_t p = bc::payload_of(o);
  switch (bc::mode_of(o)) {
    case bc::kBit: return "w" + std::to_string(bc::word_of_bit(o)) + "/" + std::to_string(bc::bit_of(o));
    case bc::kWord: return "w" + std::to_string(p);
    case bc::kLong: return "l" + std::to_string(p);
    case bc::kFloat: return "f" + std::to_string(p);
    case bc::kImm: return "#" + std::to_string(bc::imm_of(o));
    case bc::kKInt: return "k" + std::to_string(p);
    case bc::kKFloat: return "kf" + std::to_string(p);
    case bc::kDyn: return "d" + std::to_string(p);
    case bc::kTarget: return "->" + std::to_string(p);
  }
  return "?";
}

std::string fmt_float(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// Which rung of which file starts at a code offset (for JMP targets).
std::string rung_at(const CompiledProgram& p, std::uint32_t offset) {
  for (const auto& f : p.files)
    for (std::size_t r = 0; r < f.rungs.size(); ++r)
      if (f.rungs[r].offset == offset) return "rung " + std::to_string(r);
  return "offset " + std::to_string(offset);
}

std::string meaning(const CompiledProgram& p, Op op, const OperandSpec& os, std::uint32_t o) {
  const DataTableLayout& L = *p.layout;
  switch (bc::mode_of(o)) {
    case bc::kBit: return L.describe(bc::word_of_bit(o), static_cast<int>(bc::bit_of(o)));
    case bc::kWord:
    case bc::kLong:
    case bc::kFloat: return L.describe(bc::payload_of(o));
    case bc::kDyn: {
      const DynOperand& d = p.dyn[bc::payload_of(o)];
      std::string s = to_string(d.address);
      if (os.kind == OperandKind::File && s.front() != '#') s = "#" + s;
      return s;
    }
    case bc::kKInt: return std::to_string(p.int_constants[bc::payload_of(o)]);
    case bc::kKFloat: return fmt_float(p.float_constants[bc::payload_of(o)]);
    case bc::kImm: {
      const std::int32_t v = bc::imm_of(o);
      if (os.kind == OperandKind::TimeBase) return v == 100 ? "1.0" : v == 0 ? "0.001" : "0.01";
      if (os.kind == OperandKind::SlotWord)
        return std::string(op == Op::IIM ? "I:" : "O:") + std::to_string(v / 256) + "." + std::to_string(v % 256);
      if (const auto words = keyword_words(os.kind); v >= 0 && static_cast<std::size_t>(v) < words.size())
        return std::string(words[static_cast<std::size_t>(v)]);
      if (os.kind == OperandKind::RemoteAddress) return "(in the control block)";
      return std::to_string(v);
    }
    case bc::kTarget: return rung_at(p, bc::payload_of(o));
  }
  return "?";
}

void list_range(const CompiledProgram& p, std::uint32_t begin, std::uint32_t end, int& depth, std::string& out) {
  std::uint32_t pc = begin;
  while (pc < end) {
    const std::uint32_t h = p.code[pc];
    const Op op = bc::op_of(h);
    const std::uint32_t n = bc::count_of(h);
    if (op == Op::NXB || op == Op::BND) --depth;
    char head[32];
    std::snprintf(head, sizeof head, "  %04u  ", pc);
    std::string line = head;
    line.append(static_cast<std::size_t>(depth) * 2, ' ');
    std::string m(mnemonic(op));
    line += m;
    std::string notes;
    const std::uint32_t flags = bc::flags_of(h);
    if (is_instruction(op)) {
      const InstructionSpec& sp = spec(to_opcode(op));
      if (n > 0) line.append(m.size() < 5 ? 5 - m.size() : 1, ' ');
      for (std::uint32_t i = 0; i < n; ++i) {
        const std::uint32_t o = p.code[pc + 1 + i];
        if (i > 0) line += ' ';
        line += raw(o);
        if (i < sp.operand_count) {
          if (!notes.empty()) notes += ", ";
          notes += std::string(sp.operands[i].label) + "=" + meaning(p, op, sp.operands[i], o);
        } else if (bc::mode_of(o) == bc::kTarget) {
          notes += std::string(notes.empty() ? "" : ", ") + "target=" +
                   (op == Op::JSR ? "file " + std::to_string(bc::imm_of(p.code[pc + 1])) : rung_at(p, bc::payload_of(o)));
        }
      }
      if (flags & bc::kFlagFloat) notes += std::string(notes.empty() ? "" : ", ") + "float";
      if (op == Op::MCR) notes += (flags & bc::kFlagA) ? "closes the zone" : "opens a zone";
      if (op == Op::BTR || op == Op::BTW || op == Op::DEM)
        notes += std::string(notes.empty() ? "" : ", ") + "module in slot " + std::to_string(bc::aux_of(h));
    } else if (op == Op::SOR && (flags & bc::kFlagA)) {
      notes = "MCR rung: not forced false in a zone";
    }
    if (!notes.empty()) line += "  ; " + notes;
    out += line + "\n";
    if (op == Op::BST || op == Op::NXB) ++depth;
    pc += 1 + n;
  }
}

}  // namespace

std::string disassemble_rung(const CompiledProgram& p, int file, int rung) {
  const CompiledFile* f = p.file(file);
  if (!f || rung < 0 || static_cast<std::size_t>(rung) >= f->rungs.size()) return {};
  const std::uint32_t begin = f->rungs[static_cast<std::size_t>(rung)].offset;
  const std::uint32_t end = static_cast<std::size_t>(rung) + 1 < f->rungs.size()
                                ? f->rungs[static_cast<std::size_t>(rung) + 1].offset
                                : f->end - 1;  // the file's EOF is listed by disassemble()
  std::string out;
  int depth = 0;
  list_range(p, begin, end, depth, out);
  return out;
}

std::string disassemble(const CompiledProgram& p) {
  const DataTableLayout& L = *p.layout;
  std::string out = "; softslc bytecode: " + (p.source_name.empty() ? std::string("<program>") : p.source_name) + ", " +
                    p.processor.display_name + "\n";
  out += "; data table: " + std::to_string(L.total_words) + " words\n";
  for (int n = 0; n < 256; ++n) {
    const FileLayout& f = L.files[static_cast<std::size_t>(n)];
    if (!f.present) continue;
    char buf[128];
    std::snprintf(buf, sizeof buf, ";   %-4s w%-6u %u element(s) x %u word(s)\n",
                  (std::string(file_letter(f.type)) + (n > 2 ? std::to_string(n) : std::string())).c_str(), f.base,
                  f.elements, static_cast<unsigned>(f.words_per_element));
    out += buf;
  }
  for (const auto& f : p.files) {
    out += "file " + std::to_string(f.number) + ": " + std::to_string(f.rungs.size()) + " rung(s), code " +
           std::to_string(f.begin) + "-" + std::to_string(f.end - 1) + "\n";
    int depth = 0;
    for (std::size_t r = 0; r < f.rungs.size(); ++r) {
      out += "rung " + std::to_string(r) + "\n";
      const std::uint32_t end = r + 1 < f.rungs.size() ? f.rungs[r + 1].offset : f.end - 1;
      list_range(p, f.rungs[r].offset, end, depth, out);
    }
    list_range(p, f.end - 1, f.end, depth, out);
  }
  return out;
}

}  // namespace softslc
