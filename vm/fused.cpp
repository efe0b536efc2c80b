#include "vm/fused.h"

#include <map>
#include <utility>

namespace softslc {

namespace {

// A rule must agree with its instruction-table row: a contact is an Input that reads one bit, a
// coil an Output that writes one bit. Checked at compile time for every row fused_rule names,
// so a change to a row cannot silently leave its fused rule behind.
constexpr bool row_is_contact(Opcode op) {
  const InstructionSpec& s = spec(op);
  return s.role == Role::Input && s.operand_count == 1 && s.operands[0].kind == OperandKind::Bit &&
         s.operands[0].access == OperandAccess::Read;
}
constexpr bool row_is_coil(Opcode op) {
  const InstructionSpec& s = spec(op);
  return s.role == Role::Output && s.operand_count == 1 && s.operands[0].kind == OperandKind::Bit &&
         s.operands[0].access == OperandAccess::Write;
}
static_assert(row_is_contact(Opcode::XIC) && row_is_contact(Opcode::XIO));
static_assert(row_is_coil(Opcode::OTE) && row_is_coil(Opcode::OTL) && row_is_coil(Opcode::OTU));

constexpr bool is_contact(FusedRule r) { return r == FusedRule::Contact || r == FusedRule::OpenContact; }

}  // namespace

FusedRule fused_rule(Opcode op) {
  switch (op) {
    case Opcode::XIC: return FusedRule::Contact;
    case Opcode::XIO: return FusedRule::OpenContact;
    case Opcode::OTE: return FusedRule::Energize;
    case Opcode::OTL: return FusedRule::Latch;
    case Opcode::OTU: return FusedRule::Unlatch;
    default: return FusedRule::None;
  }
}

// Builds the shapes: one per distinct op sequence, keyed by the rung's header words (operands
// are per rung and live in the stream).
class FusedProgram::Builder {
 public:
  Builder(FusedProgram& out, const std::vector<Nanoseconds>& cost) : out_(out), cost_(cost) {}

  // Appends the rung [sor, end) to the stream and returns true, or returns false (and appends
  // nothing) when it is not a pure contact network.
  bool add_rung(const std::uint32_t* code, std::uint32_t sor, std::uint32_t end) {
    key_.clear();
    contacts_.clear();
    coils_.clear();
    int depth = 0;
    for (std::uint32_t pc = sor + 1; pc < end;) {
      const std::uint32_t h = code[pc];
      const Op op = bc::op_of(h);
      switch (op) {
        case Op::BST: ++depth; break;
        case Op::NXB: break;
        case Op::BND: --depth; break;
        default: {
          if (!is_instruction(op) || bc::count_of(h) != 1 || bc::mode_of(code[pc + 1]) != bc::kBit) return false;
          const FusedRule rule = fused_rule(to_opcode(op));
          if (rule == FusedRule::None) return false;
          const std::uint32_t bit = code[pc + 1];
          if (is_contact(rule)) {
            if (contacts_.size() == kMaxContacts) return false;
            // Every contact is gathered before any coil writes: a contact that reads a bit an
            // earlier coil of this rung writes must see the new value, so such a rung stays general.
            for (std::uint32_t c : coils_)
              if ((c & ~(0xFu << 28)) == bit) return false;
            contacts_.push_back(bit);  // mode BIT is 0: the top byte is the bit number
          } else {
            if (coils_.size() == kMaxCoils) return false;
            coils_.push_back(bit | (static_cast<std::uint32_t>(rule) << 28));
          }
          break;
        }
      }
      if (depth < 0 || depth > kMaxBranchDepth) return false;
      key_.push_back(h);
      pc += 1 + bc::count_of(h);
    }
    if (depth != 0 || out_.shapes_.size() >= kShapeMask) return false;
    auto [it, inserted] = shape_index_.try_emplace(key_, static_cast<std::uint32_t>(out_.shapes_.size()));
    if (inserted) build_shape();
    // The head word carries the contact count beside the shape, so the gather starts without
    // waiting for the shape's load.
    out_.stream_.push_back(it->second | static_cast<std::uint32_t>(contacts_.size()) << 24);
    out_.sor_.push_back(sor);
    out_.stream_.insert(out_.stream_.end(), contacts_.begin(), contacts_.end());
    out_.stream_.insert(out_.stream_.end(), coils_.begin(), coils_.end());
    return true;
  }

 private:
  // Runs the rung's ops for every value of the contact bits with the interpreter's rung rules
  // (docs/bytecode.md "Rung logic") and records each instruction's charge and each coil's rung-in.
  void build_shape() {
    Shape s;
    s.contacts = static_cast<std::uint8_t>(contacts_.size());
    s.coils = static_cast<std::uint8_t>(coils_.size());
    s.cost_at = static_cast<std::uint32_t>(out_.costs_.size());
    s.truth_at = static_cast<std::uint32_t>(out_.truth_.size());
    for (std::uint32_t h : key_)
      if (is_instruction(bc::op_of(h))) ++s.instructions;
    out_.truth_.resize(out_.truth_.size() + 4 * coils_.size(), 0);
    struct Frame {
      bool entry;
      bool acc;
    };
    std::vector<Frame> stack;
    for (std::uint32_t v = 0; v < (1u << s.contacts); ++v) {
      bool rung = true;  // SOR outside a false MCR zone
      Nanoseconds t = 0;
      unsigned contact = 0, coil = 0;
      stack.clear();
      for (std::uint32_t h : key_) {
        const Op op = bc::op_of(h);
        switch (op) {
          case Op::BST: stack.push_back({rung, false}); break;
          case Op::NXB:
            stack.back().acc = stack.back().acc || rung;
            rung = stack.back().entry;
            break;
          case Op::BND:
            rung = stack.back().acc || rung;
            stack.pop_back();
            break;
          default: {
            t += cost_[(static_cast<std::size_t>(op) << 1) | (rung ? 1u : 0u)];
            const FusedRule rule = fused_rule(to_opcode(op));
            if (is_contact(rule)) {
              const bool bit = ((v >> contact++) & 1u) != 0;
              rung = rung && (rule == FusedRule::Contact ? bit : !bit);
            } else {
              if (rung) out_.truth_[s.truth_at + coil * 4 + (v >> 6)] |= std::uint64_t{1} << (v & 63);
              ++coil;
            }
            break;
          }
        }
      }
      out_.costs_.push_back(t);
    }
    out_.shapes_.push_back(s);
  }

  FusedProgram& out_;
  const std::vector<Nanoseconds>& cost_;
  std::map<std::vector<std::uint32_t>, std::uint32_t> shape_index_;
  std::vector<std::uint32_t> key_, contacts_, coils_;
};

FusedProgram::FusedProgram(const CompiledProgram& program, const std::vector<Nanoseconds>& cost) {
  Builder b(*this, cost);
  file_first_rung_.assign(256, 0);
  std::uint32_t total = 0;
  for (const CompiledFile& f : program.files) {
    file_first_rung_[static_cast<std::size_t>(f.number)] = total;
    total += static_cast<std::uint32_t>(f.rungs.size());
  }
  run_of_rung_.assign(total, -1);
  const std::uint32_t* code = program.code.data();
  for (const CompiledFile& f : program.files) {
    const std::uint32_t base = file_first_rung_[static_cast<std::size_t>(f.number)];
    std::int32_t open = -1;  // the run being extended
    for (std::size_t r = 0; r < f.rungs.size(); ++r) {
      const std::uint32_t sor = f.rungs[r].offset;
      const std::uint32_t end = r + 1 < f.rungs.size() ? f.rungs[r + 1].offset : f.end - 1;  // f.end - 1: EOF
      const auto at = static_cast<std::uint32_t>(stream_.size());
      if (!b.add_rung(code, sor, end)) {
        open = -1;
        continue;
      }
      ++fused_rungs_;
      if (open < 0) {
        open = static_cast<std::int32_t>(runs_.size());
        runs_.push_back({at, at, 0, static_cast<std::uint32_t>(sor_.size() - 1)});
        run_of_rung_[base + r] = open;
      }
      runs_[static_cast<std::size_t>(open)].last = static_cast<std::uint32_t>(stream_.size());
      runs_[static_cast<std::size_t>(open)].next = end;
    }
  }
}

namespace {

// The contact bits of a rung, bit k = contact k, with the contact count a constant so the
// gather is straight-line code (one load, shift, mask and OR per contact).
template <unsigned N>
inline unsigned gather(const std::uint16_t* w, const std::uint32_t* c) {
  return [&]<unsigned... K>(std::integer_sequence<unsigned, K...>) {
    return (0u | ... | (((static_cast<unsigned>(w[c[K] & bc::kWordMask]) >> (c[K] >> 24)) & 1u) << K));
  }(std::make_integer_sequence<unsigned, N>{});
}

}  // namespace

std::uint32_t FusedProgram::execute(std::int32_t run, std::uint16_t* w, Nanoseconds& elapsed, std::uint64_t& count,
                                    Nanoseconds limit) const {
  const Run& r = runs_[static_cast<std::size_t>(run)];
  const std::uint32_t* s = stream_.data() + r.first;
  const std::uint32_t* const end = stream_.data() + r.last;
  const Shape* const shapes = shapes_.data();
  const Nanoseconds* const costs = costs_.data();
  const std::uint64_t* const truth = truth_.data();
  Nanoseconds t = elapsed;
  std::uint64_t n = 0;
  std::uint32_t rung = r.first_rung;
  for (;;) {
    const Shape& sh = shapes[s[0] & kShapeMask];
    const std::uint32_t* c = s + 1;
    unsigned v = 0;
    switch (s[0] >> 24) {
      case 0: break;
      case 1: v = gather<1>(w, c); break;
      case 2: v = gather<2>(w, c); break;
      case 3: v = gather<3>(w, c); break;
      case 4: v = gather<4>(w, c); break;
      case 5: v = gather<5>(w, c); break;
      case 6: v = gather<6>(w, c); break;
      case 7: v = gather<7>(w, c); break;
      default: v = gather<8>(w, c); break;
    }
    static_assert(kMaxContacts == 8, "gather cases cover every contact count");
    t += costs[sh.cost_at + v];
    n += sh.instructions;
    const std::uint32_t* o = c + sh.contacts;
    const std::uint64_t* tt = truth + sh.truth_at + (v >> 6);
    const std::uint32_t* const o_end = o + sh.coils;
    for (; o != o_end; ++o, tt += 4) {
      const auto in = static_cast<unsigned>((*tt >> (v & 63)) & 1u);
      std::uint16_t& word = w[bc::word_of_bit(*o)];
      const auto mask = static_cast<std::uint16_t>(1u << bc::bit_of(*o));
      const auto on = static_cast<std::uint16_t>(-in & mask);
      switch (static_cast<FusedRule>(*o >> 28)) {
        case FusedRule::Energize: word = static_cast<std::uint16_t>((word & ~mask) | on); break;
        case FusedRule::Latch: word = static_cast<std::uint16_t>(word | on); break;
        default: word = static_cast<std::uint16_t>(word & ~on); break;  // Unlatch
      }
    }
    s = o_end;
    if (s == end) break;
    ++rung;
    // The next rung's SOR: the general path raises the watchdog fault or runs the interrupt there.
    if (t >= limit) [[unlikely]] {
      elapsed = t;
      count += n;
      return sor_[rung];
    }
  }
  elapsed = t;
  count += n;
  return r.next;
}

}  // namespace softslc
