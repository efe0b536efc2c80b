#include "vm/coverage.h"

#include <algorithm>

namespace softslc {

namespace {

Role role_of(Op op) {
  if (!is_instruction(op)) return Role::Leading;  // structure: neither input nor output
  return spec(to_opcode(op)).role;
}

// The source instructions of a rung in code order: depth first through branch legs.
void flatten(const std::vector<RungElement>& elements, std::vector<const Instruction*>& out) {
  for (const auto& e : elements) {
    if (e.kind == RungElement::Kind::Instruction) {
      out.push_back(&e.instruction);
      continue;
    }
    for (const auto& leg : e.legs) flatten(leg, out);
  }
}

std::string instruction_text(const Instruction& in) {
  std::string s(spec(in.opcode).mnemonic);
  for (const auto& o : in.operands) s += " " + o.text();
  return s;
}

bool has(std::uint8_t f, std::uint8_t bit) { return (f & bit) != 0; }

}  // namespace

CoverageRecorder::CoverageRecorder(const CompiledProgram& program)
    : program_(program), flags_(program.code.size(), 0) {
  segment_.reserve(64);
}

void CoverageRecorder::record(std::uint32_t at, Op op, bool rung_in, bool rung_out) {
  if (at >= flags_.size()) return;
  std::uint8_t& f = flags_[at];
  f |= coverage::kExecuted;
  if (role_of(op) == Role::Input) {
    f |= rung_in ? coverage::kRungInTrue : coverage::kRungInFalse;
    segment_.push_back({at, rung_in, rung_out});
    return;
  }
  // Outputs and structure points end the segment of inputs before them.
  close_segment();
  if (role_of(op) == Role::Output) f |= rung_in ? coverage::kRungInTrue : coverage::kRungInFalse;
}

void CoverageRecorder::called(int file) {
  if (const CompiledFile* cf = program_.file(file); cf && cf->begin < flags_.size()) flags_[cf->begin] |= coverage::kCalled;
}

void CoverageRecorder::close_segment() {
  if (segment_.empty()) return;
  // The segment's outcome is the rung condition after its last input. An input whose rung
  // condition was true decided the segment false when it was false itself (it is the first false
  // input), and true when it was true and the segment came out true.
  const bool outcome = segment_.back().value;
  for (const auto& p : segment_) {
    if (!p.rung_in) continue;
    if (!p.value) flags_[p.at] |= coverage::kDecidedFalse;
    else if (outcome) flags_[p.at] |= coverage::kDecidedTrue;
  }
  segment_.clear();
}

void CoverageRecorder::merge(const std::vector<std::uint8_t>& other) {
  const std::size_t n = std::min(other.size(), flags_.size());
  for (std::size_t i = 0; i < n; ++i) flags_[i] |= other[i];
}

FileCoverage CoverageReport::total() const {
  FileCoverage t;
  t.file = -1;
  t.name = "total";
  for (const auto& f : files) {
    t.rungs += f.rungs;
    t.rungs_executed += f.rungs_executed;
    t.rungs_both_ways += f.rungs_both_ways;
    t.conditions += f.conditions;
    t.conditions_both_ways += f.conditions_both_ways;
    t.outputs += f.outputs;
    t.outputs_energized += f.outputs_energized;
  }
  return t;
}

CoverageReport build_coverage_report(const Program& source, const CompiledProgram& compiled,
                                     const std::vector<std::uint8_t>& flags, std::string program_name) {
  CoverageReport report;
  report.program = std::move(program_name);
  const auto flag = [&](std::uint32_t at) -> std::uint8_t { return at < flags.size() ? flags[at] : 0; };
  for (const CompiledFile& cf : compiled.files) {
    const ProgramFile* pf = nullptr;
    for (const auto& f : source.files)
      if (f.number == cf.number) pf = &f;
    FileCoverage fc;
    fc.file = cf.number;
    fc.name = pf ? pf->name : std::string();
    fc.called = cf.number == 2 || has(flag(cf.begin), coverage::kCalled);
    if (!fc.called)
      report.uncovered.push_back({cf.number, 0, -1, pf ? pf->pos.line : 0,
                                  "file " + std::to_string(cf.number) + (fc.name.empty() ? "" : " " + fc.name),
                                  "never called"});
    for (std::size_t r = 0; r < cf.rungs.size(); ++r) {
      const std::uint32_t begin = cf.rungs[r].offset;
      const std::uint32_t end = r + 1 < cf.rungs.size() ? cf.rungs[r + 1].offset : cf.end;
      std::vector<const Instruction*> src;
      if (pf && r < pf->rungs.size()) flatten(pf->rungs[r].elements, src);
      const int rung = static_cast<int>(r);
      const std::uint32_t rung_line = cf.rungs[r].pos.line;
      const bool executed = has(flag(begin), coverage::kExecuted);
      ++fc.rungs;
      if (executed) ++fc.rungs_executed;
      else if (fc.called)
        report.uncovered.push_back({cf.number, rung, -1, rung_line, "rung " + std::to_string(rung), "never executed"});
      bool seen_true = false, seen_false = false, any_output = false, any_input = false;
      int k = 0;
      std::vector<CoverageItem> items;
      for (std::uint32_t pc = begin; pc < end; pc += 1 + bc::count_of(compiled.code[pc])) {
        const Op op = bc::op_of(compiled.code[pc]);
        if (!is_instruction(op)) continue;
        const int index = k++;
        const Instruction* in = static_cast<std::size_t>(index) < src.size() ? src[static_cast<std::size_t>(index)] : nullptr;
        const std::string text = in ? instruction_text(*in) : std::string(mnemonic(op));
        const std::uint32_t line = in ? in->pos.line : rung_line;
        const std::uint8_t f = flag(pc);
        switch (spec(to_opcode(op)).role) {
          case Role::Input: {
            any_input = true;
            ++fc.conditions;
            const bool t = has(f, coverage::kDecidedTrue), fl = has(f, coverage::kDecidedFalse);
            if (t && fl) ++fc.conditions_both_ways;
            else if (executed)
              items.push_back({cf.number, rung, index, line, text,
                               !t && !fl ? "never decided its rung" : t ? "never decided its rung false"
                                                                        : "never decided its rung true"});
            break;
          }
          case Role::Output:
            any_output = true;
            ++fc.outputs;
            seen_true |= has(f, coverage::kRungInTrue);
            seen_false |= has(f, coverage::kRungInFalse);
            if (has(f, coverage::kRungInTrue)) ++fc.outputs_energized;
            else if (executed) items.push_back({cf.number, rung, index, line, text, "never energized"});
            break;
          case Role::Leading: break;
        }
      }
      // A rung without an input instruction (SOR RET EOR, an unconditional OTE) can only be true
      // (short of an MCR zone): seen true is all the coverage it can have.
      const bool unconditional_done = !any_input && seen_true;
      if (executed && (!any_output || (seen_true && seen_false) || unconditional_done)) ++fc.rungs_both_ways;
      else if (executed)
        report.uncovered.push_back({cf.number, rung, -1, rung_line, "rung " + std::to_string(rung),
                                    seen_true ? "never false" : "never true"});
      report.uncovered.insert(report.uncovered.end(), items.begin(), items.end());
    }
    report.files.push_back(std::move(fc));
  }
  return report;
}

}  // namespace softslc
