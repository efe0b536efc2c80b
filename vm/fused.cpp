#include "vm/fused.h"

#include <cstring>
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
// are per rung and live in the records).
class FusedProgram::Builder {
 public:
  Builder(FusedProgram& out, const std::vector<Nanoseconds>& cost) : out_(out), cost_(cost) {}

  // Appends the rung [sor, end)'s record and returns its shape, or returns -1 (and appends
  // nothing) when it is not a pure contact network.
  std::int64_t add_rung(const std::uint32_t* code, std::uint32_t sor, std::uint32_t end) {
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
          if (!is_instruction(op) || bc::count_of(h) != 1 || bc::mode_of(code[pc + 1]) != bc::kBit) return -1;
          const FusedRule rule = fused_rule(to_opcode(op));
          if (rule == FusedRule::None) return -1;
          const std::uint32_t bit = code[pc + 1];
          if (is_contact(rule)) {
            if (contacts_.size() == kMaxContacts) return -1;
            // Every contact is gathered before any coil writes: a contact that reads a bit an
            // earlier coil of this rung writes must see the new value, so such a rung stays general.
            for (std::uint32_t c : coils_)
              if (c == bit) return -1;
            contacts_.push_back(bit);
          } else {
            if (coils_.size() == kMaxCoils) return -1;
            coils_.push_back(bit);
          }
          break;
        }
      }
      if (depth < 0 || depth > kMaxBranchDepth) return -1;
      key_.push_back(h);
      pc += 1 + bc::count_of(h);
    }
    if (depth != 0) return -1;
    auto [it, inserted] = shape_index_.try_emplace(key_, static_cast<std::uint32_t>(out_.shapes_.size()));
    if (inserted) build_shape();
    append_record(out_.shapes_[it->second]);
    out_.sor_.push_back(sor);
    return it->second;
  }

 private:
  // The record layout in vm/fused.h: word indices, then bit numbers (bytes), then coils.
  void append_record(const Shape& s) {
    const unsigned k = out_.wide_ ? 2 : 1;
    const std::size_t at = out_.records_.size();
    out_.records_.resize(at + s.stride, 0);
    std::uint16_t* rec = out_.records_.data() + at;
    auto put_index = [&](std::uint16_t* to, std::uint32_t word) {
      if (out_.wide_)
        std::memcpy(to, &word, sizeof word);
      else
        *to = static_cast<std::uint16_t>(word);
    };
    auto* bits = reinterpret_cast<unsigned char*>(rec + contacts_.size() * k);
    for (std::size_t i = 0; i < contacts_.size(); ++i) {
      put_index(rec + i * k, bc::word_of_bit(contacts_[i]));
      bits[i] = static_cast<unsigned char>(bc::bit_of(contacts_[i]));
    }
    std::uint16_t* c = rec + contacts_.size() * k + (contacts_.size() + 1) / 2;
    for (std::uint32_t coil : coils_) {
      put_index(c, bc::word_of_bit(coil));
      c[k] = static_cast<std::uint16_t>(1u << bc::bit_of(coil));
      c += k + 1;
    }
  }

  // Runs the rung's ops for every value of the contact bits with the interpreter's rung rules
  // (docs/bytecode.md "Rung logic") and records each instruction's charge and each coil's rung-in.
  void build_shape() {
    Shape s;
    const unsigned k = out_.wide_ ? 2 : 1;
    const unsigned n = static_cast<unsigned>(contacts_.size());
    s.contacts = static_cast<std::uint8_t>(n);
    s.coils = static_cast<std::uint8_t>(coils_.size());
    s.stride = static_cast<std::uint16_t>(n * k + (n + 1) / 2 + coils_.size() * (k + 1));
    s.cost_at = static_cast<std::uint32_t>(out_.costs_.size());
    s.on_at = static_cast<std::uint32_t>(out_.on_.size());
    s.rules_at = static_cast<std::uint32_t>(out_.rules_.size());
    for (std::uint32_t h : key_) {
      const Op op = bc::op_of(h);
      if (!is_instruction(op)) continue;
      ++s.instructions;
      const FusedRule rule = fused_rule(to_opcode(op));
      if (!is_contact(rule)) out_.rules_.push_back(static_cast<std::uint8_t>(rule));
    }
    // A single coil has a kernel of its own per FusedRule (1 OTE, 2 OTL, 3 OTU); 0 is any count.
    const unsigned coil_kind =
        s.coils == 1 ? static_cast<unsigned>(out_.rules_[s.rules_at]) - static_cast<unsigned>(FusedRule::Energize) + 1 : 0;
    s.kernel = static_cast<std::uint8_t>((n * 2 + (out_.wide_ ? 1 : 0)) * 4 + coil_kind);
    out_.on_.resize(out_.on_.size() + (coils_.size() << n), 0);
    struct Frame {
      bool entry;
      bool acc;
    };
    std::vector<Frame> stack;
    for (std::uint32_t v = 0; v < (1u << n); ++v) {
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
              if (rung) out_.on_[s.on_at + (coil << n) + v] = 0xFFFF;
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
  // 16-bit word indices halve the records whenever the data table allows them.
  wide_ = program.layout->total_words > 0x10000;
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
      const auto at = static_cast<std::uint32_t>(records_.size());
      const std::int64_t shape = b.add_rung(code, sor, end);
      if (shape < 0) {
        open = -1;
        continue;
      }
      ++fused_rungs_;
      const auto rung_index = static_cast<std::uint32_t>(sor_.size() - 1);
      if (open < 0) {
        open = static_cast<std::int32_t>(runs_.size());
        runs_.push_back({static_cast<std::uint32_t>(segments_.size()), 0, 0});
        run_of_rung_[base + r] = open;
      }
      Run& run = runs_[static_cast<std::size_t>(open)];
      if (run.last > run.first && segments_.back().shape == static_cast<std::uint32_t>(shape))
        ++segments_.back().rungs;
      else
        segments_.push_back({at, 1, static_cast<std::uint32_t>(shape), rung_index});
      run.last = static_cast<std::uint32_t>(segments_.size());
      run.next = end;
    }
  }
}

namespace {

template <bool Wide>
inline std::uint32_t word_index(const std::uint16_t* at) {
  if constexpr (Wide) {
    std::uint32_t i;
    std::memcpy(&i, at, sizeof i);
    return i;
  } else {
    return *at;
  }
}

// The contact bits of a rung, bit k = contact k, with the contact count a constant so the
// gather is straight-line code (an index load, the word's load, a shift by its bit number, and
// the OR into place).
template <unsigned N, bool Wide>
inline unsigned gather(const std::uint16_t* w, const std::uint16_t* rec) {
  constexpr unsigned k = Wide ? 2 : 1;
  const auto* bits = reinterpret_cast<const unsigned char*>(rec + N * k);
  return [&]<unsigned... K>(std::integer_sequence<unsigned, K...>) {
    return (0u | ... | (((static_cast<unsigned>(w[word_index<Wide>(rec + K * k)]) >> bits[K]) & 1u) << K));
  }(std::make_integer_sequence<unsigned, N>{});
}

// A coil's action on its word: `on` is its rung-in as 0 or 0xFFFF, `mask` its bit.
inline void apply_coil(unsigned rule, std::uint16_t& word, std::uint16_t mask, std::uint16_t on) {
  switch (rule) {
    case 1: word = static_cast<std::uint16_t>(word ^ ((word ^ on) & mask)); break;  // OTE: bit := rung
    case 2: word = static_cast<std::uint16_t>(word | (on & mask)); break;           // OTL
    default: word = static_cast<std::uint16_t>(word & ~(on & mask)); break;         // OTU
  }
}

}  // namespace

template <unsigned N, bool Wide, unsigned Coil>
std::uint32_t FusedProgram::run_segment(const FusedProgram& p, const Segment& segment, std::uint16_t* w,
                                        Nanoseconds& elapsed, Nanoseconds limit) {
  constexpr unsigned k = Wide ? 2 : 1;
  constexpr unsigned coils_at = N * k + (N + 1) / 2;
  const Shape& sh = p.shapes_[segment.shape];
  const std::uint16_t* rec = p.records_.data() + segment.rec;
  const Nanoseconds* const cost = p.costs_.data() + sh.cost_at;
  const std::uint16_t* const on = p.on_.data() + sh.on_at;
  const unsigned stride = Coil != 0 ? coils_at + k + 1 : sh.stride;
  Nanoseconds t = elapsed;
  std::uint32_t done = 0;
  const std::uint32_t rungs = segment.rungs;
  for (;;) {
    const unsigned v = gather<N, Wide>(w, rec);
    t += cost[v];
    const std::uint16_t* c = rec + coils_at;
    if constexpr (Coil != 0) {
      apply_coil(Coil, w[word_index<Wide>(c)], c[k], on[v]);
    } else {
      const std::uint8_t* rule = p.rules_.data() + sh.rules_at;
      for (unsigned j = 0; j < sh.coils; ++j, c += k + 1)
        apply_coil(static_cast<unsigned>(rule[j]) - static_cast<unsigned>(FusedRule::Energize) + 1,
                   w[word_index<Wide>(c)], c[k], on[(j << N) + v]);
    }
    rec += stride;
    ++done;
    if (t >= limit || done == rungs) break;
  }
  elapsed = t;
  return done;
}

// Kernel (N * 2 + Wide) * 4 + Coil, as Builder::build_shape numbers it.
const FusedProgram::Kernel FusedProgram::kKernels[] = {
#define SOFTSLC_FUSED_KERNELS(N)                                                                          \
  &run_segment<N, false, 0>, &run_segment<N, false, 1>, &run_segment<N, false, 2>, &run_segment<N, false, 3>, \
      &run_segment<N, true, 0>, &run_segment<N, true, 1>, &run_segment<N, true, 2>, &run_segment<N, true, 3>
    SOFTSLC_FUSED_KERNELS(0), SOFTSLC_FUSED_KERNELS(1), SOFTSLC_FUSED_KERNELS(2),
    SOFTSLC_FUSED_KERNELS(3), SOFTSLC_FUSED_KERNELS(4), SOFTSLC_FUSED_KERNELS(5),
    SOFTSLC_FUSED_KERNELS(6), SOFTSLC_FUSED_KERNELS(7), SOFTSLC_FUSED_KERNELS(8),
#undef SOFTSLC_FUSED_KERNELS
};
static_assert(FusedProgram::kMaxContacts == 8, "the kernel table covers every contact count");

std::uint32_t FusedProgram::execute(std::int32_t run, std::uint16_t* w, Nanoseconds& elapsed, std::uint64_t& count,
                                    Nanoseconds limit) const {
  const Run& r = runs_[static_cast<std::size_t>(run)];
  Nanoseconds t = elapsed;
  std::uint64_t n = 0;
  for (std::uint32_t s = r.first;;) {
    const Segment& sg = segments_[s];
    const Shape& sh = shapes_[sg.shape];
    const std::uint32_t done = kKernels[sh.kernel](*this, sg, w, t, limit);
    n += std::uint64_t{sh.instructions} * done;
    if (++s == r.last && done == sg.rungs) break;
    // The next rung's SOR: the general path raises the watchdog fault or runs the interrupt there.
    if (t >= limit) [[unlikely]] {
      elapsed = t;
      count += n;
      return sor_[sg.first_rung + done];
    }
  }
  elapsed = t;
  count += n;
  return r.next;
}

}  // namespace softslc
