#include "vm/fused.h"

#include <cstring>
#include <map>
#include <utility>

#include "vm/word_ops.h"

namespace softslc {

namespace {

// A rule must agree with its instruction-table row: a contact is an Input that reads one bit, a
// coil an Output that writes one bit. Checked at compile time for every row fused_rule names
// (every_rule_fits_its_row_and_kernels, below), so a change to a row cannot silently leave its
// fused rule behind.
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

// A compare is an Input that reads two Sources; a no-op leads its rung and writes nothing.
constexpr bool row_is_compare(Opcode op) {
  const InstructionSpec& s = spec(op);
  return s.role == Role::Input && s.operand_count == 2 && s.operands[0].kind == OperandKind::Source &&
         s.operands[1].kind == OperandKind::Source && s.operands[0].access == OperandAccess::Read &&
         s.operands[1].access == OperandAccess::Read;
}
constexpr bool row_is_no_op(Opcode op) {
  const InstructionSpec& s = spec(op);
  for (unsigned i = 0; i < s.operand_count; ++i)
    if (s.operands[i].access != OperandAccess::Read) return false;
  return s.role == Role::Leading;
}
static_assert(row_is_compare(Opcode::EQU) && row_is_compare(Opcode::NEQ) && row_is_compare(Opcode::LES) &&
              row_is_compare(Opcode::LEQ) && row_is_compare(Opcode::GRT) && row_is_compare(Opcode::GEQ));
static_assert(row_is_no_op(Opcode::LBL) && row_is_no_op(Opcode::SBR) && row_is_no_op(Opcode::INT));

// An action's operands, from its row: element, source and destination operands are recorded
// (pre-decoded) for the kernel; literals and time bases are not (the handlers read the element).
constexpr bool recorded(OperandKind k) {
  return k == OperandKind::Source || k == OperandKind::Dest || k == OperandKind::Timer ||
         k == OperandKind::Counter || k == OperandKind::Resettable || k == OperandKind::File;
}
constexpr bool skipped(OperandKind k) { return k == OperandKind::Literal || k == OperandKind::TimeBase; }
constexpr unsigned recorded_operands(Opcode op) {
  unsigned n = 0;
  for (unsigned i = 0; i < spec(op).operand_count; ++i) n += recorded(spec(op).operands[i].kind) ? 1 : 0;
  return n;
}
// An action's row is an Output whose operands are only recorded kinds and literals, and whose
// element or destination comes where its kernel (word_rung) expects it.
constexpr bool row_is_action(Opcode op, unsigned sources, OperandKind last) {
  const InstructionSpec& s = spec(op);
  if (s.role != Role::Output || recorded_operands(op) != sources + 1) return false;
  for (unsigned i = 0; i < s.operand_count; ++i)
    if (!recorded(s.operands[i].kind) && !skipped(s.operands[i].kind)) return false;
  for (unsigned i = 0; i < sources; ++i)
    if (s.operands[i].kind != OperandKind::Source || s.operands[i].access != OperandAccess::Read) return false;
  return s.operands[sources].kind == last && s.operands[sources].access != OperandAccess::Read;
}
static_assert(row_is_action(Opcode::TON, 0, OperandKind::Timer) &&
              row_is_action(Opcode::TOF, 0, OperandKind::Timer) && row_is_action(Opcode::RTO, 0, OperandKind::Timer));
static_assert(row_is_action(Opcode::CTU, 0, OperandKind::Counter) &&
              row_is_action(Opcode::CTD, 0, OperandKind::Counter));
static_assert(row_is_action(Opcode::RES, 0, OperandKind::Resettable));
static_assert(row_is_action(Opcode::MOV, 1, OperandKind::Dest) && row_is_action(Opcode::CLR, 0, OperandKind::Dest));
static_assert(row_is_action(Opcode::ADD, 2, OperandKind::Dest) && row_is_action(Opcode::SUB, 2, OperandKind::Dest));
// A file instruction's row: an Output reading one File, writing another, with a length Literal,
// which (unlike a timer's presets) its handler reads from the instruction, so it is recorded too.
constexpr bool row_is_file_copy(Opcode op) {
  const InstructionSpec& s = spec(op);
  return s.role == Role::Output && s.operand_count == 3 && s.operands[0].kind == OperandKind::File &&
         s.operands[0].access == OperandAccess::Read && s.operands[1].kind == OperandKind::File &&
         s.operands[1].access == OperandAccess::Write && s.operands[2].kind == OperandKind::Literal;
}
static_assert(row_is_file_copy(Opcode::COP));
constexpr bool row_has_file(const InstructionSpec& s) {
  for (unsigned i = 0; i < s.operand_count; ++i)
    if (s.operands[i].kind == OperandKind::File) return true;
  return false;
}
// A transfer is an Output that writes no data: a program file it calls (JSR) or nothing (RET).
constexpr bool row_is_transfer(Opcode op) {
  const InstructionSpec& s = spec(op);
  return s.role == Role::Output &&
         (s.operand_count == 0 || (s.operand_count == 1 && s.operands[0].kind == OperandKind::ProgramFile &&
                                   s.operands[0].access == OperandAccess::Read));
}
static_assert(row_is_transfer(Opcode::JSR) && row_is_transfer(Opcode::RET));

constexpr bool is_contact(FusedRule r) { return r == FusedRule::Contact || r == FusedRule::OpenContact; }
constexpr bool is_coil(FusedRule r) {
  return r == FusedRule::Energize || r == FusedRule::Latch || r == FusedRule::Unlatch;
}

// The actions a word rung may end in, in the order of the word-rung loop's kernels (execute).
constexpr Op kActions[] = {Op::SOR, Op::TON, Op::TOF, Op::RTO, Op::CTU, Op::CTD,
                           Op::RES, Op::MOV, Op::ADD, Op::SUB, Op::COP, Op::CLR};
constexpr bool is_timer(Op a) { return a == Op::TON || a == Op::TOF || a == Op::RTO; }

// What a fused rung does with each op (fused_rule). A per-opcode list kept here rather than as a
// column of the instruction table: each rule but None names a kernel of this file (a contact, coil
// or compare rule the truth tables run, an action in kActions with its word_rung kernel), so a row
// could not choose one without code here, and None, the general path, is right for any row.
constexpr FusedRule rule_of(Opcode op) {
  switch (op) {
    case Opcode::XIC: return FusedRule::Contact;
    case Opcode::XIO: return FusedRule::OpenContact;
    case Opcode::OTE: return FusedRule::Energize;
    case Opcode::OTL: return FusedRule::Latch;
    case Opcode::OTU: return FusedRule::Unlatch;
    case Opcode::LBL:
    case Opcode::SBR:
    case Opcode::INT: return FusedRule::NoOp;
    case Opcode::EQU:
    case Opcode::NEQ:
    case Opcode::LES:
    case Opcode::LEQ:
    case Opcode::GRT:
    case Opcode::GEQ: return FusedRule::Compare;
    case Opcode::TON:
    case Opcode::TOF:
    case Opcode::RTO:
    case Opcode::CTU:
    case Opcode::CTD:
    case Opcode::RES:
    case Opcode::MOV:
    case Opcode::ADD:
    case Opcode::SUB:
    case Opcode::COP:
    case Opcode::CLR: return FusedRule::Action;
    case Opcode::JSR:
    case Opcode::RET: return FusedRule::Transfer;
    default: return FusedRule::None;
  }
}

// Every op with a rule has the row its rule expects, and the ops with the Action rule are exactly
// kActions' (the word-rung loop has a kernel for each), so the list cannot drift from the table or
// from the kernels.
constexpr bool rule_fits_row(Opcode op, FusedRule r) {
  switch (r) {
    case FusedRule::None: return true;
    case FusedRule::Contact:
    case FusedRule::OpenContact: return row_is_contact(op);
    case FusedRule::Energize:
    case FusedRule::Latch:
    case FusedRule::Unlatch: return row_is_coil(op);
    case FusedRule::NoOp: return row_is_no_op(op);
    case FusedRule::Compare: return row_is_compare(op);
    case FusedRule::Action:
      return row_is_action(op, 0, OperandKind::Timer) || row_is_action(op, 0, OperandKind::Counter) ||
             row_is_action(op, 0, OperandKind::Resettable) || row_is_action(op, 0, OperandKind::Dest) ||
             row_is_action(op, 1, OperandKind::Dest) ||
             row_is_action(op, 2, OperandKind::Dest) || row_is_file_copy(op);
    case FusedRule::Transfer: return row_is_transfer(op);
  }
  return false;
}
constexpr bool every_rule_fits_its_row_and_kernels() {
  for (std::size_t i = 0; i < kInstructionCount; ++i) {
    const Opcode op = static_cast<Opcode>(i);
    bool action = false;
    for (Op a : kActions) action = action || a == to_op(op);
    if (!rule_fits_row(op, rule_of(op)) || action != (rule_of(op) == FusedRule::Action)) return false;
  }
  return true;
}
static_assert(every_rule_fits_its_row_and_kernels());

// Per action, the word-rung loop has kernels for 0-2 contacts and 0-1 compares with no coils, and
// for 1-2 contacts with one coil (the common rungs, and a contact network built as a word rung:
// straight-line code), then one for any counts (loops).
constexpr unsigned kAnyCount = 0xFF;
constexpr unsigned kWordVariants = 9;
constexpr unsigned word_variant(unsigned contacts, unsigned compares, unsigned coils) {
  if (coils == 0 && contacts <= 2 && compares <= 1) return contacts * 2 + compares;
  if (coils == 1 && contacts >= 1 && contacts <= 2 && compares == 0) return 5 + contacts;
  return kWordVariants - 1;
}
// The words an action's operands take in a record, from its row as Builder::take_action records
// them: element, source and destination operands, and a file instruction's length literal.
constexpr unsigned action_words(Op a) {
  if (a == Op::SOR) return 0;
  const InstructionSpec& row = spec(to_opcode(a));
  unsigned n = 0;
  for (unsigned i = 0; i < row.operand_count; ++i)
    n += recorded(row.operands[i].kind) || (row_has_file(row) && row.operands[i].kind == OperandKind::Literal) ? 1 : 0;
  return n;
}
// The record size of a word rung with no coils and no transfer, NC contacts and NM compares: a
// constant in the word-rung loop's fixed-count kernels (Builder::build_shape checks it).
constexpr unsigned fixed_word_stride(Op a, unsigned nc, unsigned nm, unsigned nk) {
  return 1 + nc + 2 * nm + nk + action_words(a);
}
static_assert(fixed_word_stride(Op::TON, 1, 0, 0) == 3 && fixed_word_stride(Op::MOV, 0, 1, 0) == 5 &&
              fixed_word_stride(Op::ADD, 1, 0, 0) == 5 && fixed_word_stride(Op::COP, 1, 0, 0) == 5 &&
              fixed_word_stride(Op::SOR, 1, 0, 1) == 3);

// A read operand in a word-rung record: a word index, or an immediate (vm/fused.h).
constexpr std::uint32_t kImmediate = 0x80000000u;
inline std::int64_t read_operand(const std::uint16_t* w, std::uint32_t x) {
  if (x & kImmediate) return static_cast<std::int32_t>(x << 1) >> 1;
  return static_cast<std::int16_t>(w[x]);
}

}  // namespace

FusedRule fused_rule(Opcode op) { return rule_of(op); }

// Builds the shapes: one per distinct op sequence, keyed by the rung's header words (operands
// are per rung and live in the records).
class FusedProgram::Builder {
 public:
  Builder(FusedProgram& out, const std::vector<Nanoseconds>& cost) : out_(out), cost_(cost) {}

  // Reads the rung [sor, end): true when it is a pure contact network or a word rung (vm/fused.h),
  // which add() then appends. Appends nothing.
  bool parse(const std::uint32_t* code, std::uint32_t sor, std::uint32_t end) {
    key_.clear();
    contacts_.clear();
    coils_.clear();
    compares_.clear();
    action_operands_.clear();
    steps_.clear();
    action_ = Op::SOR;
    transfer_ = Op::SOR;
    int depth = 0;
    for (std::uint32_t pc = sor + 1; pc < end;) {
      const std::uint32_t h = code[pc];
      const Op op = bc::op_of(h);
      // Only BNDs follow a transfer: after a taken JSR the general path resumes at the next SOR.
      if (transfer_ != Op::SOR && op != Op::BND) return false;
      // After the first action only branch structure, more actions and a transfer: every
      // condition and coil is evaluated before an action writes.
      if (action_ != Op::SOR && op != Op::NXB && op != Op::BND &&
          !(is_instruction(op) && (fused_rule(to_opcode(op)) == FusedRule::Transfer ||
                                   fused_rule(to_opcode(op)) == FusedRule::Action)))
        return false;
      switch (op) {
        case Op::BST: ++depth; break;
        case Op::NXB: break;
        case Op::BND: --depth; break;
        default: {
          if (!is_instruction(op)) return false;
          const FusedRule rule = fused_rule(to_opcode(op));
          if (rule == FusedRule::None) return false;
          if (rule == FusedRule::NoOp) break;
          // DYN (run-time address, M-file) and FLOAT keep the rung general.
          if (bc::flags_of(h) & (bc::kFlagDyn | bc::kFlagFloat)) return false;
          const std::uint32_t* o = code + pc + 1;
          if (rule == FusedRule::Compare) {
            if (!readable(o[0]) || !readable(o[1]) || conditions() == kMaxContacts) return false;
            // Conditions are evaluated before any coil writes (as contacts are).
            for (std::uint32_t c : coils_)
              if (reads_word(o[0], bc::word_of_bit(c)) || reads_word(o[1], bc::word_of_bit(c))) return false;
            compares_.push_back(o[0]);
            compares_.push_back(o[1]);
            break;
          }
          if (rule == FusedRule::Action) {
            // Several actions hold no timer (vm/fused.h, "Several actions").
            if (!steps_.empty() && (is_timer(op) || is_timer(action_))) return false;
            const auto first_operand = static_cast<std::uint32_t>(action_operands_.size());
            if (!take_action(op, h, o)) return false;
            action_ = op;
            steps_.push_back({op, bc::aux_of(h), first_operand});
            break;
          }
          if (rule == FusedRule::Transfer) {
            // A timer sees the scan time of its whole rung, which a JSR's charge would change.
            if (is_timer(action_)) return false;
            transfer_ = op;
            transfer_at_ = pc;
            // A JSR's subroutine file (an immediate).
            if (op == Op::JSR) call_file_ = static_cast<std::uint32_t>(bc::imm_of(o[0]));
            break;
          }
          if (bc::count_of(h) != 1 || bc::mode_of(o[0]) != bc::kBit) return false;
          const std::uint32_t bit = o[0];
          if (is_contact(rule)) {
            if (conditions() == kMaxContacts) return false;
            // Every contact is gathered before any coil writes: a contact that reads a bit an
            // earlier coil of this rung writes must see the new value, so such a rung stays general.
            for (std::uint32_t c : coils_)
              if (c == bit) return false;
            contacts_.push_back(bit);
          } else {
            if (coils_.size() == kMaxCoils) return false;
            coils_.push_back(bit);
          }
          break;
        }
      }
      if (depth < 0 || depth > kMaxBranchDepth) return false;
      key_.push_back(h);
      pc += 1 + bc::count_of(h);
    }
    if (depth != 0) return false;
    rung_number_ = bc::aux_of(code[sor]);
    sor_at_ = sor;
    end_ = end;
    // A word record's first word holds the shape index in 24 bits (kShapeShift).
    return out_.shapes_.size() < kMaxWordShapes;
  }

  // The rung parse() read is a word rung: compares, an action or a transfer.
  bool word_rung() const { return !compares_.empty() || action_ != Op::SOR || transfer_ != Op::SOR; }
  // ... holding several actions (vm/fused.h, "Several actions").
  bool several_actions() const { return steps_.size() > 1; }

  // Appends the record of the rung parse() accepted and returns its shape. `as_word`: a contact
  // network is built as a word rung (run in the word-rung loop beside word rungs, instead of as a
  // segment of its own; the FusedProgram constructor decides).
  std::uint32_t add(bool as_word) {
    as_word_ = as_word;
    auto& index = as_word && !word_rung() ? word_form_index_ : shape_index_;
    auto [it, inserted] = index.try_emplace(key_, static_cast<std::uint32_t>(out_.shapes_.size()));
    if (inserted) build_shape();
    const Shape& shape = out_.shapes_[it->second];
    if (shape.word)
      append_word_record(it->second);
    else
      append_record(shape);
    out_.sor_.push_back(sor_at_);
    return it->second;
  }

 private:
  unsigned conditions() const { return static_cast<unsigned>(contacts_.size() + compares_.size() / 2); }

  // A read operand the kernels take directly: a 16-bit word or an immediate.
  static bool readable(std::uint32_t o) { return bc::mode_of(o) == bc::kWord || bc::mode_of(o) == bc::kImm; }
  static bool reads_word(std::uint32_t o, std::uint32_t word) {
    return bc::mode_of(o) == bc::kWord && bc::payload_of(o) == word;
  }
  static std::uint32_t encode(std::uint32_t o) {
    return bc::mode_of(o) == bc::kImm ? (kImmediate | (static_cast<std::uint32_t>(bc::imm_of(o)) & ~kImmediate))
                                      : bc::payload_of(o);
  }
  // Records the action's operands, walking its instruction-table row: sources may be words or
  // immediates, the element or destination must be a direct word; literals are skipped except in
  // a file instruction (its length), whose files must be spans the compiler resolved (flag B).
  bool take_action(Op op, std::uint32_t h, const std::uint32_t* o) {
    const InstructionSpec& row = spec(to_opcode(op));
    const bool file_instruction = row_has_file(row);
    if (file_instruction && !(row_is_file_copy(to_opcode(op)) && (bc::flags_of(h) & bc::kFlagB))) return false;
    for (unsigned i = 0; i < row.operand_count; ++i) {
      const OperandKind k = row.operands[i].kind;
      if (file_instruction && k == OperandKind::Literal) {
        if (bc::mode_of(o[i]) != bc::kImm) return false;
        action_operands_.push_back(encode(o[i]));
        continue;
      }
      if (!recorded(k)) continue;
      if (k == OperandKind::File) {
        action_operands_.push_back(bc::payload_of(o[i]));
        continue;
      }
      const bool source = k == OperandKind::Source;
      if (source ? !readable(o[i]) : bc::mode_of(o[i]) != bc::kWord) return false;
      action_operands_.push_back(encode(o[i]));
    }
    return true;
  }

  // A contact's or coil's bit operand in a word-rung record: its word index above its bit number
  // (FusedProgram::wrecords_), so a kernel takes the index with one shift and the bit as it is.
  static std::uint32_t word_bit(std::uint32_t bit_operand) {
    return (bc::word_of_bit(bit_operand) << 8) | bc::bit_of(bit_operand);
  }

  void append_word_record(std::uint32_t shape) {
    auto& r = out_.wrecords_;
    r.push_back((shape << kShapeShift) | out_.shapes_[shape].kernel);
    for (std::uint32_t c : contacts_) r.push_back(word_bit(c));
    for (std::uint32_t o : compares_) r.push_back(encode(o));
    for (std::uint32_t c : coils_) r.push_back(word_bit(c));
    if (several_actions()) {
      // A step word before each action's operands, and the step ending the rung.
      for (std::size_t i = 0; i < steps_.size(); ++i) {
        const Step& st = steps_[i];
        const std::uint32_t end =
            i + 1 < steps_.size() ? steps_[i + 1].operands : static_cast<std::uint32_t>(action_operands_.size());
        r.push_back((st.aux << kStepAuxShift) | (kFirstStep + action_index(st.op)));
        r.insert(r.end(), action_operands_.begin() + st.operands, action_operands_.begin() + end);
      }
      r.push_back(transfer_ != Op::SOR ? kStepsEndTransfer : kStepsEnd);
    } else {
      r.insert(r.end(), action_operands_.begin(), action_operands_.end());
    }
    if (transfer_ == Op::JSR) {
      // The call words (FusedProgram::kCallWords); the runs are filled in once every file's runs
      // are known (the FusedProgram constructor).
      r.push_back(call_file_);
      r.push_back(static_cast<std::uint32_t>(-1));
      r.push_back(end_);
      r.push_back(static_cast<std::uint32_t>(-1));
      r.push_back(kNoWordEntry);
      r.push_back(kNoWordEntry);
    }
    if (transfer_ != Op::SOR) {
      r.push_back(transfer_at_);
      r.push_back(rung_number_);
    }
  }

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

  // Runs the rung's ops for every value of the contact (and compare) bits with the interpreter's
  // rung rules (docs/bytecode.md "Rung logic") and records each instruction's charge and each
  // coil's (and the action's) rung-in.
  void build_shape() {
    Shape s;
    const unsigned k = out_.wide_ ? 2 : 1;
    const unsigned nc = static_cast<unsigned>(contacts_.size());
    const unsigned n = conditions();
    const unsigned outputs =
        static_cast<unsigned>(coils_.size() + steps_.size()) + (transfer_ != Op::SOR ? 1 : 0);
    s.contacts = static_cast<std::uint8_t>(nc);
    s.compares = static_cast<std::uint8_t>(n - nc);
    s.coils = static_cast<std::uint8_t>(coils_.size());
    s.word = word_rung() || as_word_;
    s.action = action_;
    s.transfer = transfer_ != Op::SOR;
    s.call = transfer_ == Op::JSR;
    s.cost_at = static_cast<std::uint32_t>(out_.costs_.size());
    s.on_at = static_cast<std::uint32_t>(out_.on_.size());
    s.rules_at = static_cast<std::uint32_t>(out_.rules_.size());
    for (std::uint32_t h : key_) {
      const Op op = bc::op_of(h);
      if (!is_instruction(op)) continue;
      ++s.instructions;
      const FusedRule rule = fused_rule(to_opcode(op));
      if (is_coil(rule)) out_.rules_.push_back(static_cast<std::uint8_t>(rule));
      if (rule == FusedRule::Action) {
        s.action_flags = static_cast<std::uint8_t>(bc::flags_of(h));
        s.action_aux = static_cast<std::uint16_t>(bc::aux_of(h));
      }
    }
    for (std::uint32_t h : key_)
      if (is_instruction(bc::op_of(h)) && fused_rule(to_opcode(bc::op_of(h))) == FusedRule::Compare)
        out_.rules_.push_back(static_cast<std::uint8_t>(word_ops::compare_mask(bc::op_of(h))));
    if (s.word && several_actions()) {
      // Its step words: one per action and the last.
      s.stride = static_cast<std::uint16_t>(1 + n + (n - nc) + coils_.size() + action_operands_.size() +
                                            steps_.size() + 1 + (s.transfer ? 2 : 0) + (s.call ? kCallWords : 0));
      s.kernel = static_cast<std::uint8_t>(kMultiRung);
    } else if (s.word) {
      s.stride = static_cast<std::uint16_t>(1 + n + (n - nc) + coils_.size() + action_operands_.size() +
                                            (s.transfer ? 2 : 0) + (s.call ? kCallWords : 0));
      const unsigned a = action_index(action_);
      unsigned variant = word_variant(nc, n - nc, s.coils);
      // The fixed-count kernels advance by fixed_word_stride; a record of another size (none is
      // expected: the layout above is the one take_action records) runs the any-count kernel.
      if (variant != kWordVariants - 1 && !s.transfer && s.stride != fixed_word_stride(action_, nc, n - nc, s.coils))
        variant = kWordVariants - 1;
      s.kernel = static_cast<std::uint8_t>((a * 2 + (s.transfer ? 1 : 0)) * kWordVariants + variant);
    } else {
      s.stride = static_cast<std::uint16_t>(n * k + (n + 1) / 2 + coils_.size() * (k + 1));
      // A single coil has a kernel of its own per FusedRule (1 OTE, 2 OTL, 3 OTU); 0 is any count.
      const unsigned coil_kind = s.coils == 1 ? static_cast<unsigned>(out_.rules_[s.rules_at]) -
                                                    static_cast<unsigned>(FusedRule::Energize) + 1
                                              : 0;
      s.kernel = static_cast<std::uint8_t>((n * 2 + (out_.wide_ ? 1 : 0)) * 4 + coil_kind);
    }
    out_.on_.resize(out_.on_.size() + (outputs << n), 0);
    struct Frame {
      bool entry;
      bool acc;
    };
    std::vector<Frame> stack;
    for (std::uint32_t v = 0; v < (1u << n); ++v) {
      bool rung = true;  // SOR outside a false MCR zone
      Nanoseconds t = 0;
      unsigned contact = 0, compare = nc, output = 0;
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
            } else if (rule == FusedRule::Compare) {
              rung = rung && ((v >> compare++) & 1u) != 0;
            } else if (is_coil(rule) || rule == FusedRule::Action || rule == FusedRule::Transfer) {
              if (rung) out_.on_[s.on_at + (output << n) + v] = 0xFFFF;
              ++output;
            }
            break;
          }
        }
      }
      out_.costs_.push_back(t);
    }
    if (n <= kSmallConditions)
      std::copy(out_.costs_.begin() + s.cost_at, out_.costs_.end(), s.small_cost);
    if (n <= kSmallConditions && outputs <= kSmallOutputs)
      for (unsigned j = 0; j < outputs; ++j)
        for (std::uint32_t v = 0; v < (1u << n); ++v)
          if (out_.on_[s.on_at + (j << n) + v] != 0) s.on_bits |= 1u << (j * 8 + v);
    out_.shapes_.push_back(s);
  }

  FusedProgram& out_;
  const std::vector<Nanoseconds>& cost_;
  std::map<std::vector<std::uint32_t>, std::uint32_t> shape_index_;
  std::map<std::vector<std::uint32_t>, std::uint32_t> word_form_index_;  // contact networks built as word rungs
  // Its index in kActions (every action has one: every_rule_fits_its_row_and_kernels).
  static unsigned action_index(Op op) {
    unsigned a = 0;
    while (kActions[a] != op) ++a;
    return a;
  }

  std::vector<std::uint32_t> key_, contacts_, coils_, compares_, action_operands_;
  // Each action of the rung in program order: its op, its header's aux, and its first operand in
  // action_operands_.
  struct Step {
    Op op;
    std::uint32_t aux;
    std::uint32_t operands;
  };
  std::vector<Step> steps_;
  Op action_ = Op::SOR;             // the rung's (last) action, or SOR
  Op transfer_ = Op::SOR;           // JSR or RET ending the rung, or SOR
  std::uint32_t transfer_at_ = 0;   // its code offset
  std::uint32_t rung_number_ = 0;   // the rung's number in its file
  std::uint32_t sor_at_ = 0;        // the rung's SOR
  std::uint32_t end_ = 0;           // the next rung's SOR, or the file's EOF
  bool as_word_ = false;            // add(): a contact network built as a word rung
  std::uint32_t call_file_ = 0;     // a JSR's subroutine file
};

FusedProgram::FusedProgram(const CompiledProgram& program, const std::vector<Nanoseconds>& cost,
                           const Nanoseconds* per_word) {
  // 16-bit word indices halve the records whenever the data table allows them.
  wide_ = program.layout->total_words > 0x10000;
  s0_ = program.layout->status_word(status::kArith);
  s2_ = program.layout->status_word(status::kControl);
  s5_ = program.layout->status_word(status::kMinor);
  s24_ = program.layout->status_word(status::kIndex);
  cop_per_word_ = per_word[static_cast<std::size_t>(Opcode::COP)];
  Builder b(*this, cost);
  Builder peek(*this, cost);  // reads the next rung, appending nothing
  file_first_rung_.assign(256, 0);
  std::uint32_t total = 0;
  for (const CompiledFile& f : program.files) {
    file_first_rung_[static_cast<std::size_t>(f.number)] = total;
    total += static_cast<std::uint32_t>(f.rungs.size());
  }
  run_of_rung_.assign(total, -1);
  // execute() returns code offsets in 30 bits (kOffsetMask); a larger program (4 GB of code) is
  // not fused.
  if (program.code.size() > kOffsetMask) return;
  const std::uint32_t* code = program.code.data();
  // Runs that start after a transfer inside another run, and that run: they end where it ends.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> tails;
  // Each fused JSR rung's record and the index in run_of_rung_ of the rung after it (or -1).
  std::vector<std::pair<std::uint32_t, std::int64_t>> calls;
  for (const CompiledFile& f : program.files) {
    const std::uint32_t base = file_first_rung_[static_cast<std::size_t>(f.number)];
    std::int32_t open = -1;        // the run being extended
    bool after_transfer = false;   // the rung before ended in a JSR or RET
    bool after_word = false;       // the rung before is a word rung of this run
    for (std::size_t r = 0; r < f.rungs.size(); ++r) {
      const std::uint32_t sor = f.rungs[r].offset;
      const std::uint32_t end = r + 1 < f.rungs.size() ? f.rungs[r + 1].offset : f.end - 1;  // f.end - 1: EOF
      // A label rung is a jump target: it starts a run, so a JMP to it lands on fused rungs.
      if (sor + 1 < end && bc::op_of(code[sor + 1]) == Op::LBL) open = -1;
      const std::size_t records_before = records_.size(), wrecords_before = wrecords_.size();
      if (!b.parse(code, sor, end)) {
        open = -1;
        after_transfer = false;
        after_word = false;
        continue;
      }
      // A contact network beside a word rung of its run is built as a word rung: in the word-rung
      // loop it costs a jump, where a segment of its own costs a kernel call (the mixed bench's
      // subroutine starts with one). Only a true word rung before or after counts, so a stretch of
      // contact networks keeps its segment of one shape.
      const bool word_rung = b.word_rung();
      bool as_word = false;
      if (!word_rung) {
        const std::uint32_t next_end = r + 2 < f.rungs.size() ? f.rungs[r + 2].offset : f.end - 1;
        as_word = (open >= 0 && after_word) ||
                  (r + 1 < f.rungs.size() && peek.parse(code, end, next_end) && peek.word_rung());
      }
      const std::int64_t shape = b.add(as_word);
      after_word = word_rung;
      ++fused_rungs_;
      const bool word = shapes_[static_cast<std::size_t>(shape)].word;
      if (word_rung) ++word_rungs_;
      if (b.several_actions()) ++several_action_rungs_;
      if (as_word) ++word_form_rungs_;
      const auto at = static_cast<std::uint32_t>(word ? wrecords_before : records_before);
      const auto rung_index = static_cast<std::uint32_t>(sor_.size() - 1);
      if (open < 0) {
        open = static_cast<std::int32_t>(runs_.size());
        runs_.push_back({static_cast<std::uint32_t>(segments_.size()), 0, 0});
        run_of_rung_[base + r] = open;
      } else if (after_transfer) {
        // A JSR returns to this rung's SOR: it starts a run of its own (vm/fused.h), the rest of
        // the run it is in, from the segment it starts; its end is the enclosing run's, set below.
        run_of_rung_[base + r] = static_cast<std::int32_t>(runs_.size());
        tails.push_back({static_cast<std::uint32_t>(runs_.size()), static_cast<std::uint32_t>(open)});
        runs_.push_back({static_cast<std::uint32_t>(segments_.size()), 0, 0});
      }
      Run& run = runs_[static_cast<std::size_t>(open)];
      // Consecutive word rungs share one segment whatever their shapes (each record names its
      // shape); consecutive contact networks share one only when their shape is the same. A rung
      // after a transfer starts a segment, since a run may start there.
      const std::uint32_t key = word ? kWordSegment : static_cast<std::uint32_t>(shape);
      if (run.last > run.first && segments_.back().shape == key && !after_transfer)
        ++segments_.back().rungs;
      else
        segments_.push_back({at, 1, key, rung_index, 0, 0});
      if (word) {
        segments_.back().rec_end = static_cast<std::uint32_t>(wrecords_.size());
        segments_.back().instructions += shapes_[static_cast<std::size_t>(shape)].instructions;
      }
      run.last = static_cast<std::uint32_t>(segments_.size());
      run.next = end;
      after_transfer = shapes_[static_cast<std::size_t>(shape)].transfer;
      if (after_transfer) ++transfer_rungs_;
      if (shapes_[static_cast<std::size_t>(shape)].call)
        calls.emplace_back(at, r + 1 < f.rungs.size() ? std::int64_t{base} + static_cast<std::int64_t>(r) + 1 : -1);
    }
  }
  for (const auto& [tail, whole] : tails) {
    runs_[tail].last = runs_[whole].last;
    runs_[tail].next = runs_[whole].next;
  }
  // The call words of every fused JSR (vm/fused.h, "Calls"): the run at the subroutine's first
  // rung, when the JSR's code offset is that rung's SOR, and the run at the rung after the JSR.
  for (const auto& [at, next_rung] : calls) {
    std::uint32_t* c = wrecords_.data() + at + shapes_[wrecords_[at] >> kShapeShift].stride - 2 - kCallWords;
    const CompiledFile* target = program.file(static_cast<int>(c[0]));
    const std::uint32_t* jo = code + c[kCallWords] + 1;
    if (target != nullptr && !target->rungs.empty() && target->rungs[0].offset == bc::payload_of(jo[1]))
      c[1] = static_cast<std::uint32_t>(run_of_rung_[file_first_rung_[c[0] & 0xFF]]);
    if (static_cast<std::int32_t>(c[1]) >= 0) ++linked_calls_;
    if (next_rung >= 0) c[3] = static_cast<std::uint32_t>(run_of_rung_[static_cast<std::size_t>(next_rung)]);
  }
  // Each word segment's records are followed by its end record, so the word-rung loop needs no
  // end test per rung: the end record's kernel leaves the loop.
  std::vector<std::uint32_t> laid;
  laid.reserve(wrecords_.size() + segments_.size());
  for (Segment& sg : segments_) {
    if (sg.shape != kWordSegment) continue;
    const auto at = static_cast<std::uint32_t>(laid.size());
    laid.insert(laid.end(), wrecords_.begin() + sg.rec, wrecords_.begin() + sg.rec_end);
    sg.rec = at;
    sg.rec_end = static_cast<std::uint32_t>(laid.size());
    laid.push_back(kEndOfSegment);
  }
  wrecords_ = std::move(laid);
  // Each fused JSR's two word entries (kCallWords), now that the records are laid out.
  const auto word_entry = [&](std::uint32_t run) {
    if (static_cast<std::int32_t>(run) < 0) return kNoWordEntry;
    const Segment& sg = segments_[runs_[run].first];
    return sg.shape == kWordSegment ? sg.rec : kNoWordEntry;
  };
  for (const Segment& sg : segments_) {
    if (sg.shape != kWordSegment) continue;
    for (std::uint32_t at = sg.rec; at != sg.rec_end; at += shapes_[wrecords_[at] >> kShapeShift].stride) {
      const Shape& sh = shapes_[wrecords_[at] >> kShapeShift];
      if (!sh.call) continue;
      std::uint32_t* c = wrecords_.data() + at + sh.stride - 2 - kCallWords;
      c[4] = word_entry(c[1]);
      c[5] = word_entry(c[3]);
    }
  }
  for (Shape& sh : shapes_) {
    sh.cost = costs_.data() + sh.cost_at;
    sh.on = on_.data() + sh.on_at;
    sh.rules = rules_.data() + sh.rules_at;
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
  const auto* bits = reinterpret_cast<const unsigned char*>(rec + std::size_t{N} * k);
  return [&]<unsigned... K>(std::integer_sequence<unsigned, K...>) {
    return (0u | ... | (((static_cast<unsigned>(w[word_index<Wide>(rec + std::size_t{K} * k)]) >> bits[K]) & 1u) << K));
  }(std::make_integer_sequence<unsigned, N>{});
}

// Output j's rung-in for the condition bits v of a word rung with n conditions: from the shape's
// on_bits in a fixed-count kernel (Small), else from its table.
template <bool Small>
inline bool output_on(std::uint32_t on_bits, const std::uint16_t* on, unsigned j, unsigned n, unsigned v) {
  if constexpr (Small)
    return ((on_bits >> (j * 8 + v)) & 1u) != 0;
  else
    return on[(j << n) + v] != 0;
}

// A coil's action on its word: `on` is its rung-in as 0 or 0xFFFF, `mask` its bit.
inline void apply_coil(unsigned rule, std::uint16_t& word, std::uint16_t mask, std::uint16_t on) {
  switch (rule) {
    case 1: word = static_cast<std::uint16_t>(word ^ ((word ^ on) & mask)); break;  // OTE: bit := rung
    case 2: word = static_cast<std::uint16_t>(word | (on & mask)); break;           // OTL
    default: word = static_cast<std::uint16_t>(word & ~(on & mask)); break;         // OTU
  }
}

// A word rung's condition bits v (contact k at bit k, then each compare) from its record's
// operands at `o`; returns the operands after them (its coils'). `masks`: the compares'
// word_ops::compare_mask values.
[[gnu::always_inline]] inline const std::uint32_t* word_conditions(const std::uint16_t* w, const std::uint32_t* o,
                                                                  unsigned nc, unsigned nm,
                                                                  const std::uint8_t* masks, unsigned& v) {
  v = 0;
  for (unsigned i = 0; i < nc; ++i, ++o)
    v |= ((static_cast<unsigned>(w[*o >> 8]) >> (*o & 31)) & 1u) << i;  // word_bit: the bit is below 16
  for (unsigned j = 0; j < nm; ++j, o += 2)
    v |= static_cast<unsigned>(word_ops::compare_by_mask(masks[j], read_operand(w, o[0]), read_operand(w, o[1])))
         << (nc + j);
  return o;
}

// A word rung's coils (operands at `o`, FusedRules in `rules`) with their rung-ins for v.
template <bool Small>
[[gnu::always_inline]] inline void word_coils(std::uint16_t* w, const std::uint32_t* o, unsigned coils,
                                              const std::uint8_t* rules, std::uint32_t on_bits,
                                              const std::uint16_t* on, unsigned n, unsigned v) {
  for (unsigned j = 0; j < coils; ++j, ++o)
    apply_coil(static_cast<unsigned>(rules[j]) - static_cast<unsigned>(FusedRule::Energize) + 1, w[*o >> 8],
               static_cast<std::uint16_t>(1u << (*o & 31)),
               static_cast<std::uint16_t>(0u - static_cast<unsigned>(output_on<Small>(on_bits, on, j, n, v))));
}

}  // namespace

template <unsigned N, bool Wide, unsigned Coil>
std::uint32_t FusedProgram::run_segment(const FusedProgram& p, const Segment& segment, std::uint16_t* w,
                                        Nanoseconds& elapsed, Nanoseconds limit, const FusedScan&) {
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

// Action A on its operands (vm/fused.h, run_action): the interpreter's rule for each (vm/word_ops.h).
template <Op A>
[[gnu::always_inline]] inline void FusedProgram::run_action(const FusedProgram& p, const std::uint32_t* act,
                                                            std::uint16_t* w, Nanoseconds& t, const FusedScan& scan,
                                                            word_ops::TickClock& ticks, bool rung,
                                                            [[maybe_unused]] std::uint8_t flags,
                                                            [[maybe_unused]] std::uint16_t aux) {
  if constexpr (A == Op::TON || A == Op::TOF || A == Op::RTO) {
    if (scan.timers) [[unlikely]]
      word_ops::record_timer(*scan.timers, A, w, act[0], rung, scan.scan_start + t, flags);
    word_ops::timer(A, w + act[0], rung, scan.first_pass, ticks.at(scan.scan_start + t, flags),
                    (flags & bc::kFlagA) != 0);
  } else if constexpr (A == Op::CTU || A == Op::CTD) {
    word_ops::counter(A, w + act[0], rung, scan.first_pass);
  } else if constexpr (A == Op::RES) {
    if (rung) word_ops::reset(static_cast<FileType>(aux), w + act[0]);
  } else if constexpr (A == Op::MOV) {
    // Interpreter::move: an integer that does not fit saturates and sets V.
    if (rung) {
      bool overflow = false;
      const std::int64_t stored = word_ops::saturate(read_operand(w, act[0]), INT16_MIN, INT16_MAX, overflow);
      w[act[1]] = static_cast<std::uint16_t>(stored);
      word_ops::set_arith_flags(w, p.s0_, p.s5_, false, overflow, stored == 0, stored < 0);
    }
  } else if constexpr (A == Op::ADD || A == Op::SUB) {
    // Interpreter::math into a 16-bit word: C from the unsigned sum or difference, the
    // S:2/14 overflow rule, then the flags and the S:5/0 trap.
    if (rung) {
      const std::int64_t a = read_operand(w, act[0]), b = read_operand(w, act[1]);
      const bool carry = A == Op::ADD ? word_ops::add_carry(a, b, 0xFFFF) : word_ops::sub_carry(a, b, 0xFFFF);
      bool overflow = false;
      const std::int64_t stored = word_ops::fit_integer(A == Op::ADD ? a + b : a - b, false,
                                                        (w[p.s2_] & status::kOverflowSelect) != 0, overflow);
      w[act[2]] = static_cast<std::uint16_t>(stored);
      word_ops::set_arith_flags(w, p.s0_, p.s5_, carry, overflow, stored == 0, stored < 0);
    }
  } else if constexpr (A == Op::COP) {
    // Interpreter::copy_file with both spans resolved (flag B): the words, S:24, and the
    // per-word charge after the instruction's own.
    if (rung) {
      const std::uint32_t words = aux;
      word_ops::copy_direct(w, act[0], act[1], words, p.s24_, static_cast<std::int32_t>(act[2] << 1) >> 1);
      t += p.cop_per_word_ * static_cast<Nanoseconds>(words);
    }
  } else if constexpr (A == Op::CLR) {
    if (rung) word_ops::clear(w, act[0], p.s0_, p.s5_);
  }
}

// The head of a rung of several actions: word_rung's conditions and coils for any counts (no
// timer, so nothing is handed back).
[[gnu::always_inline]] inline const std::uint32_t* FusedProgram::multi_head(const Shape& sh, const std::uint32_t* rec,
                                                                           std::uint16_t* w, Nanoseconds& t,
                                                                           unsigned& v) {
  const std::uint32_t* const o = word_conditions(w, rec, sh.contacts, sh.compares, sh.rules + sh.coils, v);
  t += sh.cost[v];
  word_coils<false>(w, o, sh.coils, sh.rules, 0, sh.on, sh.contacts + sh.compares, v);
  return o + sh.coils;
}

// One word rung whose record (after its shape word) is `rec`: its action is A (SOR: none), with
// NC contacts, NM compares and NK coils, or (NC = NM = NK = kAnyCount) any counts, and when Transfer
// a JSR or RET last. Adds its charge to t; returns kRungGeneral, having changed nothing, when the
// general path must run it, kRungTransfer when its JSR or RET is taken.
template <Op A, unsigned NC, unsigned NM, unsigned NK, bool Transfer>
[[gnu::always_inline]] inline unsigned FusedProgram::word_rung(const FusedProgram& p, const Shape& sh, const std::uint32_t* rec,
                                    std::uint16_t* w, Nanoseconds& t, const FusedScan& scan,
                                    word_ops::TickClock& ticks) {
  constexpr bool fixed = NC != kAnyCount;
  static_assert(!fixed || (NC + NM <= kSmallConditions && NK + 2 <= kSmallOutputs),
                "a fixed-count kernel's rung-ins are in Shape::on_bits");
  const Nanoseconds* const cost = sh.cost;
  const std::uint16_t* const on = sh.on;
  const unsigned nc = fixed ? NC : sh.contacts;
  const unsigned nm = fixed ? NM : sh.compares;
  const unsigned coils = fixed ? NK : sh.coils;
  const unsigned n = nc + nm;
  // The coils' FusedRules, then the compares' masks (word_ops::compare_mask).
  const std::uint8_t* const rules = sh.rules;
  unsigned v = 0;
  const std::uint32_t* const o = word_conditions(w, rec, nc, nm, rules + coils, v);
  const std::uint32_t* const act = o + coils;
  if constexpr (A == Op::TON || A == Op::TOF || A == Op::RTO) {
    // Fault 0034h: the general path runs this rung and raises it (before anything is written).
    if (word_ops::timer_negative(w + act[0])) [[unlikely]]
      return kRungGeneral;
  }
  if constexpr (fixed)
    t += sh.small_cost[v];
  else
    t += cost[v];
  const std::uint32_t on_bits = sh.on_bits;
  word_coils<fixed>(w, o, coils, rules, on_bits, on, n, v);
  // The action's rung-in; it is the rung's last instruction, so the scan time it sees is t.
  [[maybe_unused]] const bool rung = output_on<fixed>(on_bits, on, coils, n, v);
  if constexpr (A != Op::SOR) run_action<A>(p, act, w, t, scan, ticks, rung, sh.action_flags, sh.action_aux);
  if constexpr (Transfer) {
    constexpr unsigned kAction = A == Op::SOR ? 0 : 1;
    if (output_on<fixed>(on_bits, on, coils + kAction, n, v)) return kRungTransfer;
  }
  return kRungDone;
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
static_assert(std::size(kActions) == 12, "the word-rung loop has a kernel and a step kernel for every action");
static_assert(FusedProgram::kMaxContacts == 8, "the kernel table covers every contact count");

// Hot: run at every scan (vm/runtime.cpp, "The scan cycle", says why it is marked).
[[gnu::hot]] FusedProgram::Exit FusedProgram::execute(std::int32_t run, std::uint16_t* w, Nanoseconds& elapsed,
                                         std::uint64_t& count, Nanoseconds limit, const FusedScan& scan,
                                         FusedCalls& calls) const {
  const Run* r = &runs_[static_cast<std::size_t>(run)];
  Nanoseconds t = elapsed;
  word_ops::TickClock ticks;
  // A copy the compiler knows no store reaches (through `scan` it reloaded first_pass through the
  // reference on every counter rung).
  const FusedScan this_scan = scan;
  // The call state in locals, written back at the end (a store and a reload through `calls` on
  // every call and return were on the path to the next rung).
  unsigned depth = calls.depth;
  const unsigned room = calls.room;
  std::uint32_t file = calls.file;
  std::uint64_t n = 0;
  Exit out;
  for (std::uint32_t s = r->first;;) {
    const Segment* sg = &segments_[s];
    std::uint32_t result;
    if (sg->shape == kWordSegment) {
      // The word-rung loop, direct-threaded: each record's first word holds its rung kernel's
      // number, and every kernel ends by jumping to the next record's kernel through kRungKernels
      // (its own indirect jump, so the pattern of shapes is predicted per kernel), with no
      // `switch`, bounds test or end test: the segment's end record has a kernel of its own
      // (kEndOfSegment). A fixed-count kernel advances by its record size, a constant. (This
      // loop is written here, not in a function: GCC does not inline a function holding a table
      // of label addresses, and a call per segment costs more.)
      const std::uint32_t* first = wrecords_.data() + sg->rec;
      const std::uint32_t* rec = first;
      const Shape* const shapes = shapes_.data();
      const Shape* sh = nullptr;
      unsigned rung = kRungDone;
      // A rung of several actions: its next step word, and the next action's rung-in in its
      // shape's table (one row of 2^n entries per output, so a step moves on by `step_row`).
      const std::uint32_t* step = nullptr;
      const std::uint16_t* step_on = nullptr;
      std::uint32_t step_row = 0;
      // The rungs before `at` and their instructions: a segment that stops early counts them
      // then, so a rung adds nothing to the count as it runs.
      auto completed = [&](const std::uint32_t* at) {
        std::uint32_t rungs = 0;
        for (const std::uint32_t* q = first; q != at; q += shapes[*q >> kShapeShift].stride, ++rungs)
          n += shapes[*q >> kShapeShift].instructions;
        return rungs;
      };
      // Kernel ((A * 2 + T) * kWordVariants + V), as Builder::build_shape numbers them, then
      // kEndOfSegment; the builder makes no other kernel number.
      static_assert(kLastWordKernel == (std::size(kActions) * 2 - 1) * kWordVariants + kWordVariants - 1);
      static_assert(kStepsEnd == kFirstStep + std::size(kActions) && kStepsEndTransfer <= kKernelMask,
                    "a step kernel for every action, and every kernel number in one byte");
#define SOFTSLC_WORD_LABEL(A, T, V) &&word_##A##_##T##_##V
#define SOFTSLC_WORD_LABELS_T(A, T)                                                                        \
  SOFTSLC_WORD_LABEL(A, T, 0), SOFTSLC_WORD_LABEL(A, T, 1), SOFTSLC_WORD_LABEL(A, T, 2),                 \
      SOFTSLC_WORD_LABEL(A, T, 3), SOFTSLC_WORD_LABEL(A, T, 4), SOFTSLC_WORD_LABEL(A, T, 5),             \
      SOFTSLC_WORD_LABEL(A, T, 6), SOFTSLC_WORD_LABEL(A, T, 7), SOFTSLC_WORD_LABEL(A, T, 8)
#define SOFTSLC_NO_WORD_LABELS                                                                             \
  &&word_not_built, &&word_not_built, &&word_not_built, &&word_not_built, &&word_not_built,              \
      &&word_not_built, &&word_not_built, &&word_not_built, &&word_not_built
#define SOFTSLC_WORD_LABELS(A) SOFTSLC_WORD_LABELS_T(A, 0), SOFTSLC_WORD_LABELS_T(A, 1)
      // A timer never precedes a transfer (Builder::parse): those kernels are not built.
      static const void* const kRungKernels[kKernelMask + 1] = {
          // cppcheck-suppress syntaxError ; cppcheck 2.10 cannot parse GNU labels as values (&&label)
          SOFTSLC_WORD_LABELS(0),       SOFTSLC_WORD_LABELS_T(1, 0), SOFTSLC_NO_WORD_LABELS,
          SOFTSLC_WORD_LABELS_T(2, 0), SOFTSLC_NO_WORD_LABELS,      SOFTSLC_WORD_LABELS_T(3, 0),
          SOFTSLC_NO_WORD_LABELS,      SOFTSLC_WORD_LABELS(4),      SOFTSLC_WORD_LABELS(5),
          SOFTSLC_WORD_LABELS(6),      SOFTSLC_WORD_LABELS(7),      SOFTSLC_WORD_LABELS(8),
          SOFTSLC_WORD_LABELS(9),      SOFTSLC_WORD_LABELS(10),     SOFTSLC_WORD_LABELS(11),
          &&word_segment_end,
          // A rung of several actions (never a timer, so no timer steps), and its steps' kernels.
          &&word_multi,                &&word_not_built,            &&word_not_built,
          &&word_not_built,            &&word_not_built,            &&word_step_4,
          &&word_step_5,               &&word_step_6,               &&word_step_7,
          &&word_step_8,               &&word_step_9,               &&word_step_10,
          &&word_step_11,              &&word_steps_end,            &&word_steps_end_transfer};
#undef SOFTSLC_WORD_LABELS
#undef SOFTSLC_NO_WORD_LABELS
#undef SOFTSLC_WORD_LABELS_T
#undef SOFTSLC_WORD_LABEL
      goto* kRungKernels[*rec & kKernelMask];
      // One rung kernel: word_rung for the action, transfer and counts; then the next record's.
#define SOFTSLC_WORD_RUNG(A, T, V, NC, NM, NK)                                                           \
  word_##A##_##T##_##V:                                                                                  \
    sh = shapes + (*rec >> kShapeShift);                                                                  \
    rung = word_rung<kActions[A], NC, NM, NK, (T) != 0>(*this, *sh, rec + 1, w, t, this_scan, ticks);     \
    if (rung != kRungDone) [[unlikely]]                                                                   \
      goto word_stopped;                                                                                  \
    rec += (T) == 0 && (NC) != kAnyCount ? fixed_word_stride(kActions[A], NC, NM, NK) : sh->stride;      \
    if (t >= limit) [[unlikely]]                                                                          \
      goto word_limit;                                                                                    \
    goto* kRungKernels[*rec & kKernelMask];
#define SOFTSLC_WORD_RUNGS_T(A, T)                                                                             \
  SOFTSLC_WORD_RUNG(A, T, 0, 0, 0, 0) SOFTSLC_WORD_RUNG(A, T, 1, 0, 1, 0) SOFTSLC_WORD_RUNG(A, T, 2, 1, 0, 0)  \
  SOFTSLC_WORD_RUNG(A, T, 3, 1, 1, 0) SOFTSLC_WORD_RUNG(A, T, 4, 2, 0, 0) SOFTSLC_WORD_RUNG(A, T, 5, 2, 1, 0)  \
  SOFTSLC_WORD_RUNG(A, T, 6, 1, 0, 1) SOFTSLC_WORD_RUNG(A, T, 7, 2, 0, 1)                                      \
  SOFTSLC_WORD_RUNG(A, T, 8, kAnyCount, kAnyCount, kAnyCount)
#define SOFTSLC_WORD_RUNGS(A) SOFTSLC_WORD_RUNGS_T(A, 0) SOFTSLC_WORD_RUNGS_T(A, 1)
      SOFTSLC_WORD_RUNGS(0) SOFTSLC_WORD_RUNGS_T(1, 0) SOFTSLC_WORD_RUNGS_T(2, 0) SOFTSLC_WORD_RUNGS_T(3, 0)
      SOFTSLC_WORD_RUNGS(4) SOFTSLC_WORD_RUNGS(5) SOFTSLC_WORD_RUNGS(6) SOFTSLC_WORD_RUNGS(7) SOFTSLC_WORD_RUNGS(8)
      SOFTSLC_WORD_RUNGS(9) SOFTSLC_WORD_RUNGS(10) SOFTSLC_WORD_RUNGS(11)
#undef SOFTSLC_WORD_RUNGS
#undef SOFTSLC_WORD_RUNGS_T
#undef SOFTSLC_WORD_RUNG
    word_multi:
      // A rung of several actions: its conditions, charge and coils, then its steps in order.
      {
        sh = shapes + (*rec >> kShapeShift);
        unsigned v = 0;
        step = multi_head(*sh, rec + 1, w, t, v);
        step_row = 1u << (sh->contacts + sh->compares);
        step_on = sh->on + (std::size_t{sh->coils} << (sh->contacts + sh->compares)) + v;
        goto* kRungKernels[*step & kKernelMask];
      }
      // One step: action A with its rung-in and its operands after the step word; then the next step's kernel.
#define SOFTSLC_WORD_STEP(A)                                                                                \
  word_step_##A:                                                                                            \
    run_action<kActions[A]>(*this, step + 1, w, t, this_scan, ticks, *step_on != 0, 0,                      \
                            static_cast<std::uint16_t>(*step >> kStepAuxShift));                            \
    step += 1 + action_words(kActions[A]);                                                                  \
    step_on += step_row;                                                                                    \
    goto* kRungKernels[*step & kKernelMask];
      SOFTSLC_WORD_STEP(4) SOFTSLC_WORD_STEP(5) SOFTSLC_WORD_STEP(6) SOFTSLC_WORD_STEP(7)
      SOFTSLC_WORD_STEP(8) SOFTSLC_WORD_STEP(9) SOFTSLC_WORD_STEP(10) SOFTSLC_WORD_STEP(11)
#undef SOFTSLC_WORD_STEP
    word_steps_end_transfer:
      // The transfer is the output after the actions.
      if (*step_on != 0) {
        rung = kRungTransfer;
        goto word_stopped;
      }
    word_steps_end:
      rec += sh->stride;
      if (t >= limit) [[unlikely]]
        goto word_limit;
      goto* kRungKernels[*rec & kKernelMask];
    word_not_built:
      // Never reached (no record names these kernels); the general path would run the rung.
      sh = shapes + (*rec >> kShapeShift);
      rung = kRungGeneral;
      goto word_stopped;
    word_limit:
      // The watchdog or an interrupt point: at the end record the segment is complete, and
      // execute() tests the limit again before the next segment.
      if ((*rec & kKernelMask) == kEndOfSegment) goto word_segment_end;
      result = completed(rec);
      goto word_done;
    word_stopped:
      if (rung == kRungGeneral) {
        result = completed(rec) | kRunsGeneral;
        goto word_done;
      }
      {
        // The rung ran to its JSR or RET: counted (a transfer rung ends its segment, since the
        // rung after it starts one, so this is seldom a walk). A transfer is always its run's
        // last rung: the run continues in the subroutine, or after the JSR the RET returns to, or
        // stops there for run_routine (vm/fused.h, "Calls"); a word segment continues there
        // without leaving the word-rung loop.
        if ((rec[sh->stride] & kKernelMask) == kEndOfSegment) [[likely]] {
          n += sg->instructions;
        } else {
          n += sh->instructions;
          completed(rec);
        }
        const Exit exit{rec[sh->stride - 2] | kTransfer, rec[sh->stride - 1]};
        std::int32_t next_run;
        // For a JSR not read: the subroutine's first SOR is looked up only if the run stops there.
        std::uint32_t at = 0;
        std::uint32_t entry;  // the next run's first word-rung record, or kNoWordEntry
        if (sh->call) {
          const std::uint32_t* const call = rec + sh->stride - 2 - kCallWords;
          next_run = static_cast<std::int32_t>(call[1]);
          // Fault 0030h, or a subroutine that does not start fused: the JSR handler's work.
          if (next_run < 0 || depth == room) {
            out = exit;
            break;
          }
          calls.call[depth++] = {call[2], file, exit.rung, static_cast<std::int32_t>(call[3]), call[5]};
          file = call[0];
          entry = call[4];
        } else {
          // A RET with no call of this run outstanding: run_routine returns (or ends the scan).
          if (depth == 0) {
            out = exit;
            break;
          }
          const FusedCall& c = calls.call[--depth];
          file = c.file;
          next_run = c.ret_run;
          at = c.ret;
          entry = c.ret_words;
        }
        // The SOR the general path would dispatch next: the watchdog or an interrupt is checked
        // there, and a rung that is not fused runs there.
        if (next_run < 0) {
          out = {at, 0};
          break;
        }
        r = &runs_[static_cast<std::size_t>(next_run)];
        if (t >= limit) [[unlikely]] {
          out = {sor_[segments_[r->first].first_rung], 0};
          break;
        }
        s = r->first;
        sg = &segments_[s];
        if (entry == kNoWordEntry) continue;
        first = rec = wrecords_.data() + entry;
        goto* kRungKernels[*rec & kKernelMask];
      }
    word_segment_end:
      n += sg->instructions;
      result = sg->rungs;
    word_done:;
    } else {
      const Shape& sh = shapes_[sg->shape];
      result = kKernels[sh.kernel](*this, *sg, w, t, limit, scan);
      n += std::uint64_t{sh.instructions} * (result & ~kRunsGeneral);
    }
    const std::uint32_t done = result & ~kRunsGeneral;
    if (result & kRunsGeneral) [[unlikely]] {
      out = {sor_[sg->first_rung + done] | kRunsGeneral, 0};
      break;
    }
    if (++s == r->last && done == sg->rungs) {
      out = {r->next, 0};
      break;
    }
    // The next rung's SOR: the general path raises the watchdog fault or runs the interrupt there.
    if (t >= limit) [[unlikely]] {
      out = {sor_[sg->first_rung + done], 0};
      break;
    }
  }
  elapsed = t;
  count += n;
  calls.depth = depth;
  calls.file = file;
  return out;
}

}  // namespace softslc
