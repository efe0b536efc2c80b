#include "vm/scantime.h"

#include <algorithm>
#include <map>
#include <set>

#include "instructions/mfile_access_time.h"

namespace softslc {

namespace {

// The number of words a file instruction moves: its "length" literal, else 1.
int length_operand(const Instruction& in) {
  const auto& s = spec(in.opcode);
  for (std::size_t i = 0; i < in.operands.size() && i < s.operand_count; ++i)
    if (s.operands[i].kind == OperandKind::Literal && s.operands[i].label == "length" &&
        in.operands[i].kind == Operand::Kind::Integer)
      return static_cast<int>(std::max<std::int64_t>(1, in.operands[i].integer));
  return 1;
}

// Whether the instruction touches its operands when its rung-in is false: conditions read
// their operands to produce rung-out; OTE writes 0.
bool accesses_when_false(Opcode op) { return spec(op).role == Role::Input || op == Opcode::OTE; }

struct RungCost {
  Nanoseconds worst = 0, best = 0, mfile_worst = 0;
  int accesses = 0;
  // For the remedies: M bits examined, COPs from M, whether the rung has conditions.
  std::vector<std::string> m_bits_examined;
  std::vector<std::string> m_words_read;
  bool unconditioned_cop_from_m = false;
  std::vector<int> jsr_targets;
};

class Predictor {
 public:
  Predictor(const Program& p, const ProcessorModel& proc, const TimingProfile& t)
      : program_(p), key_(proc.timing_key()), profile_(t) {}

  ScanTimePrediction run(const ProcessorModel& proc) {
    ScanTimePrediction out;
    out.catalog = proc.catalog;
    out.processor = profile_.processor;
    out.profile_name = profile_.name;
    for (const auto& f : program_.files) {
      FileScanTime ft;
      ft.file = f.number;
      for (std::size_t r = 0; r < f.rungs.size(); ++r) {
        RungCost c;
        bool has_condition = false;
        cost_elements(f.rungs[r].elements, c, has_condition);
        costs_[{f.number, static_cast<int>(r)}] = c;
        out.rungs.push_back({f.number, static_cast<int>(r), f.rungs[r].pos, c.worst, c.best, c.mfile_worst, c.accesses});
        ft.worst += c.worst;
        ft.best += c.best;
        ft.mfile += c.mfile_worst;
      }
      out.files.push_back(ft);
    }
    // Overhead: housekeeping plus the I/O scan of every module.
    out.housekeeping = profile_.housekeeping.ns;
    note_source(profile_.housekeeping.source);
    // The fixed part of the input scan is paid every scan (1747-PT1 p. D-5: base + per module).
    out.io_scan = profile_.input_scan_base.ns;
    note_source(profile_.input_scan_base.source);
    for (const auto& s : program_.slots) {
      out.io_scan += profile_.input_scan(s.catalog, s.scan_in) + profile_.output_scan(s.catalog, s.scan_out);
    }
    out.overhead = out.housekeeping + out.io_scan;
    // Whole scan from file 2, expanding JSRs for the worst case.
    std::set<int> stack;
    auto [worst, mfile] = expand_file(2, stack, 0, out.notes);
    out.total_worst = worst + out.overhead;
    out.total_mfile = mfile;
    for (const auto& f : out.files)
      if (f.file == 2) out.total_best = f.best + out.overhead;
    if (!program_.find_file(2)) out.total_best = out.overhead;
    hot_spots(out);
    out.uses_estimates = uses_estimates_;
    if (key_.empty()) out.notes.push_back("this processor has no M0/M1 access-time row; M-file accesses are not charged");
    if (uses_estimates_)
      out.notes.push_back("instruction and overhead times of profile \"" + profile_.name +
                          "\" include estimates (not from an Allen-Bradley document); M0/M1 access times are the "
                          "manuals' own table (1747-SN appendix B, 1203-SM1 appendix A)");
    return out;
  }

 private:
  const Program& program_;
  std::string key_;
  const TimingProfile& profile_;
  std::map<std::pair<int, int>, RungCost> costs_;
  bool uses_estimates_ = false;

  void note_source(const std::string& source) { uses_estimates_ |= profile_.is_estimate(source); }

  void cost_elements(const std::vector<RungElement>& elems, RungCost& c, bool& has_condition) {
    for (const auto& e : elems) {
      if (e.kind == RungElement::Kind::Branch) {
        for (const auto& leg : e.legs) cost_elements(leg, c, has_condition);
        continue;
      }
      cost_instruction(e.instruction, c, has_condition);
    }
  }

  void cost_instruction(const Instruction& in, RungCost& c, bool& has_condition) {
    const auto& s = spec(in.opcode);
    const auto& t = profile_.instruction(in.opcode);
    note_source(t.source);
    int words = length_operand(in);
    // A row per value of the first operand (SVC's channel select) where the manual prints one.
    const bool literal_first = !t.by_operand.empty() && !in.operands.empty() &&
                               in.operands[0].kind == Operand::Kind::Integer;
    const std::int64_t first = literal_first ? in.operands[0].integer : 0;
    const Nanoseconds when_true = literal_first ? t.for_operand(first, true) : t.true_ns;
    const Nanoseconds when_false = literal_first ? t.for_operand(first, false) : t.false_ns;
    // The worst case takes each instruction at its longer time: a MicroLogix 1000 XIC or XIO takes longer
    // false than true (1761-6.3 p. 6-4: 1.54 us true, 1.72 us false), so an all-true rung is not its worst.
    c.worst += std::max(when_true, when_false) + t.per_word_ns * (t.per_word_ns ? words : 0);
    c.best += when_false;
    if (s.role == Role::Input) has_condition = true;
    if (in.opcode == Opcode::JSR && !in.operands.empty() && in.operands[0].kind == Operand::Kind::Integer)
      c.jsr_targets.push_back(static_cast<int>(in.operands[0].integer));
    for (std::size_t i = 0; i < in.operands.size() && i < s.operand_count; ++i) {
      const auto& op = in.operands[i];
      if (!op.is_address() || !is_mfile(op.address.type)) continue;
      MFileAccess cls = s.operands[i].mfile;
      auto us = mfile_access_us(key_, cls, is_multi_word(cls) ? words : 1);
      if (!us) continue;
      Nanoseconds ns = microseconds(*us);
      ++c.accesses;
      c.worst += ns;
      c.mfile_worst += ns;
      if (accesses_when_false(in.opcode)) c.best += ns;
      std::string where = to_string(op.address);
      if (cls == MFileAccess::ExamineBit) c.m_bits_examined.push_back(where);
      if (s.operands[i].access != OperandAccess::Write && cls != MFileAccess::ExamineBit) c.m_words_read.push_back(where);
      if (in.opcode == Opcode::COP && cls == MFileAccess::CopFromM && !has_condition) c.unconditioned_cop_from_m = true;
    }
  }

  // Worst-case time and M part of a file with every JSR taken (callees expanded). Recursion is
  // cut at the processor's nesting limit (a real SLC would fault there).
  std::pair<Nanoseconds, Nanoseconds> expand_file(int file, std::set<int>& stack, int depth,
                                                  std::vector<std::string>& notes) {
    const ProgramFile* f = program_.find_file(file);
    if (!f) return {0, 0};
    if (stack.count(file) || depth > 8) {
      notes.push_back("JSR recursion through file " + std::to_string(file) +
                      " is not expanded (the worst case counts each file once per call chain)");
      return {0, 0};
    }
    stack.insert(file);
    Nanoseconds worst = 0, mfile = 0;
    for (std::size_t r = 0; r < f->rungs.size(); ++r) {
      const auto& c = costs_[std::pair{file, static_cast<int>(r)}];
      worst += c.worst;
      mfile += c.mfile_worst;
      for (int target : c.jsr_targets) {
        auto [w, m] = expand_file(target, stack, depth + 1, notes);
        worst += w;
        mfile += m;
      }
    }
    stack.erase(file);
    return {worst, mfile};
  }

  void hot_spots(ScanTimePrediction& out) {
    // Which M bits are examined in how many rungs (the manual's "do not examine the same M bit
    // in several rungs").
    std::map<std::string, std::vector<std::pair<int, int>>> bit_uses;
    for (const auto& [key, c] : costs_)
      for (const auto& b : c.m_bits_examined) bit_uses[b].push_back(key);
    for (const auto& [key, c] : costs_) {
      if (c.mfile_worst == 0) continue;
      HotSpot h{key.first, key.second, c.mfile_worst, {}};
      std::set<std::string> seen;
      for (const auto& b : c.m_bits_examined) {
        if (!seen.insert(b).second) continue;
        const auto& uses = bit_uses[b];
        if (uses.size() > 1)
          h.remedies.push_back("M bit " + b + " is examined in " + std::to_string(uses.size()) +
                               " rungs: examine it once, keep its state in a B3 bit (OTE B3/n) and use that bit in "
                               "the other rungs (1747-SN appendix B, \"Minimizing the Scan Time\")");
      }
      if (c.m_bits_examined.size() + c.m_words_read.size() > 1)
        h.remedies.push_back("this rung makes " + std::to_string(c.accesses) +
                             " separate M-file accesses: read the M-file words it uses once with a COP into a B or N "
                             "file and use those bits and words instead");
      if (c.unconditioned_cop_from_m)
        h.remedies.push_back("this COP from an M file runs every scan: if it only monitors the module, condition "
                             "it on a clock bit such as XIC S:4/8 so it runs periodically");
      out.hot_spots.push_back(std::move(h));
    }
    std::stable_sort(out.hot_spots.begin(), out.hot_spots.end(),
                     [](const HotSpot& a, const HotSpot& b) { return a.mfile > b.mfile; });
  }
};

}  // namespace

ScanTimePrediction predict_scan_time(const Program& program, const ProcessorModel& processor,
                                     const TimingProfile& profile) {
  return Predictor(program, processor, profile).run(processor);
}

}  // namespace softslc
