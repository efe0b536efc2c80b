#include "vm/interpreter.h"

#include "vm/message_network.h"

#include "vm/coverage.h"
#include "vm/fused.h"
#include "vm/word_ops.h"

#include "vm/compiler.h"
#include "vm/ascii_channel.h"
#include "vm/modbus_master.h"
#include "vm/pid.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <new>
#include <utility>

namespace softslc {

namespace {

// S:33/9, the status scan toggle bit (RM B-48, SLC 5/03 and later): cleared on entry into Run,
// changes state at every END, TND or REF.
constexpr std::uint16_t kScanToggle = 1u << 9;

// Changes (or, with `clear`, clears) S:33/9 on the processors that have it.
void scan_toggle(const CompiledProgram& p, std::uint16_t* w, bool clear) {
  const ProcessorFamily f = p.processor.family;
  if (f != ProcessorFamily::Slc503 && f != ProcessorFamily::Slc504 && f != ProcessorFamily::Slc505) return;
  std::uint16_t& s33 = w[p.layout->status_word(status::kCommBits)];
  s33 = static_cast<std::uint16_t>(clear ? (s33 & ~kScanToggle) : (s33 ^ kScanToggle));
}

std::string hex4(unsigned v) {
  static const char* digits = "0123456789ABCDEF";
  std::string s = "0000";
  for (int i = 3; i >= 0; --i, v >>= 4) s[static_cast<std::size_t>(i)] = digits[v & 0xF];
  return s + "h";
}

}  // namespace

std::string FaultInfo::to_string() const {
  std::string s = "major fault " + hex4(code);
  if (file >= 0) s += " in file " + std::to_string(file);
  if (rung >= 0) s += " rung " + std::to_string(rung);
  return s + ": " + message;
}

Interpreter::Interpreter(const CompiledProgram& program, DataTable& table, ChassisAccess& chassis,
                         const ScanTimeModel& model)
    : prog_(program),
      table_(table),
      chassis_(chassis),
      model_(model),
      w_(table.words()),
      code_(program.code.data()) {
  // Costs are tabulated once so the hot loop does one load and one add per instruction. Every
  // instruction costs at least 1 ns so an endless JMP loop always reaches the watchdog.
  cost_.assign(kOpCount * 2, 0);
  for (std::size_t i = 0; i < kInstructionCount; ++i) {
    const auto op = static_cast<Opcode>(i);
    cost_[i * 2 + 0] = std::max<Nanoseconds>(1, model.instruction_cost(op, false));
    cost_[i * 2 + 1] = std::max<Nanoseconds>(1, model.instruction_cost(op, true));
    countable_[i] = 1;
    per_word_[i] = std::max<Nanoseconds>(0, model.per_word_cost(op));
    for (std::size_t v = 0; v < transition_[i].size(); ++v) transition_[i][v] = model.transition_cost(op, static_cast<int>(v));
  }
  // SVC's channel select (1-3) can have figures of its own (the MicroLogix manuals print one per
  // channel): the difference from the table's cost is charged at the SVC.
  for (std::size_t v = 1; v < svc_select_extra_.size(); ++v)
    for (int rung = 0; rung < 2; ++rung)
      svc_select_extra_[v][static_cast<std::size_t>(rung)] =
          std::max<Nanoseconds>(1, model.literal_operand_cost(Opcode::SVC_CH, static_cast<std::int64_t>(v), rung != 0)) -
          cost_[static_cast<std::size_t>(Opcode::SVC_CH) * 2 + static_cast<std::size_t>(rung)];
  max_depth_ = std::clamp(program.processor.max_subroutine_depth(), 1, kMaxCallDepth);
  pulse_trains_.attach(program);
  data_logs_.attach(program);
  const auto& L = *program.layout;
  s0_ = L.status_word(status::kArith);
  s2_ = L.status_word(status::kControl);
  s5_ = L.status_word(status::kMinor);
  s13_ = L.status_word(status::kMathLow);
  s14_ = L.status_word(status::kMathHigh);
  s24_ = L.status_word(status::kIndex);
  s1_ = L.status_word(status::kMode);
  s6_ = L.status_word(status::kFaultCode);
  s7_ = L.status_word(status::kSuspendCode);
  s8_ = L.status_word(status::kSuspendFile);
  s29_ = L.status_word(status::kFaultRoutine);
  s30_ = L.status_word(status::kStiSetpoint);
  s31_ = L.status_word(status::kStiFile);
  if (L.files[2].elements > static_cast<std::uint32_t>(status::kMinorExtended))
    s36_ = L.status_word(status::kMinorExtended);
  // the DII's words S:46-S:52 exist on the 5/03-5/05 (RM 11-18); the I/O event
  // interrupt's S:25-S:28 and S:32 on the 5/02 and later (RM 11-27, B-43, B-46).
  dii_supported_ = !program.processor.is_micrologix() &&
                   program.processor.supports(Requirement::IoInterrupt) &&
                   program.processor.family != ProcessorFamily::Slc502 &&
                   L.files[2].elements > static_cast<std::uint32_t>(status::kDiiAccumulator);
  indirect_bit_runs_on_ = program.processor.is_micrologix();
  io_supported_ = program.processor.supports(Requirement::IoInterrupt) &&
                  L.files[2].elements > static_cast<std::uint32_t>(status::kIsrExecuting);
  if (io_supported_) {
    s25_ = L.status_word(status::kIoPendingLow);
    s27_ = L.status_word(status::kIoEnableLow);
    s32_ = L.status_word(status::kIsrExecuting);
    // OPTION ISR=n on the SLOT line: the slot's ISR file (RM 11-31; checked by `check`).
    for (const auto& slot : program.slots) {
      auto it = slot.options.find("ISR");
      if (it == slot.options.end() || slot.slot < 1 || slot.slot > 30) continue;
      int file = 0;
      for (char c : it->second) file = (c >= '0' && c <= '9' && file < 1000) ? file * 10 + (c - '0') : 1000;
      if (file >= 3 && file <= 255 && program.file(file)) {
        isr_file_[static_cast<std::size_t>(slot.slot)] = file;
        any_isr_ = true;
      }
    }
  }
  if (dii_supported_) s46_ = L.status_word(status::kDiiFile);
  locate_sti_bits();
  hsc_.attach(L.function_file(FunctionFile::HSC), L.files[0].base);
  locate_event_interrupts();
  fused_ = std::make_shared<const FusedProgram>(program, cost_, per_word_.data());
}

std::string Interpreter::refused(MAccess a, int slot, MFile f, int word, bool write) const {
  std::string text = "module refused (" + std::string(to_string(a)) + ")";
  const std::string why = chassis_.m_refusal(slot, f, word, write);
  return why.empty() ? text : text + ": " + why;
}

void Interpreter::raise(std::uint16_t code, std::string message) {
  if (faulted_) return;
  faulted_ = true;
  fault_.code = code;
  fault_.message = std::move(message);
}

// ---- The checked run-time resolver ---------------------------------------------------------------------

bool Interpreter::resolve_common(const DynOperand& d, Ref& out, std::uint16_t& code, std::string& message) {
  const DataTableLayout& L = *prog_.layout;
  const bool indirect = d.ptr_file >= 0 || d.ptr_element >= 0 || d.ptr_word >= 0 || d.ptr_bit >= 0;
  code = indirect ? fault::kIndirectOutOfRange : fault::kIndexOutOfRange;
  const auto ptr = [&](std::int32_t idx) { return static_cast<int>(static_cast<std::int16_t>(w_[idx])); };
  const auto index_note = [&] {
    std::string s;
    if (d.indexed) s += " (S:24 = " + std::to_string(static_cast<std::int16_t>(w_[s24_])) + ")";
    for (std::int32_t p : {d.ptr_file, d.ptr_element, d.ptr_word, d.ptr_bit})
      if (p >= 0) s += " (" + L.describe(static_cast<std::uint32_t>(p)) + " = " + std::to_string(ptr(p)) + ")";
    return s;
  };
  if (d.mfile) {
    mfile_ref(d, out);
    return true;
  }
  int file = d.type == FileType::Status ? 2 : is_io(d.type) ? fixed_file_number(d.type) : d.file;
  if (d.ptr_file >= 0) {
    file = ptr(d.ptr_file);
    if (file < 3 || file > 255 || !L.files[static_cast<std::size_t>(file)].present ||
        L.files[static_cast<std::size_t>(file)].type != d.type) {
      message = to_string(d.address) + index_note() + ": there is no " + std::string(file_letter(d.type)) +
                " file number " + std::to_string(file);
      return false;
    }
  }
  const FileLayout& f = L.files[static_cast<std::size_t>(file)];
  std::int64_t word_index = 0;
  int bit = d.bit;
  if (is_io(d.type)) {
    const auto& slots = d.type == FileType::Input ? L.input_slots : L.output_slots;
    const int slot = d.ptr_element >= 0 ? ptr(d.ptr_element) : d.element;
    const int word = d.ptr_word >= 0 ? ptr(d.ptr_word) : std::max(d.word, 0);
    if (slot < 0 || slot >= kMaxSlots || !slots[static_cast<std::size_t>(slot)].present) {
      message = to_string(d.address) + index_note() + ": slot " + std::to_string(slot) + " has no image in " +
                std::string(file_letter(d.type)) + ":";
      return false;
    }
    const SlotImage& si = slots[static_cast<std::size_t>(slot)];
    std::int64_t off = static_cast<std::int64_t>(si.first) + word;
    // An indexed I/O address moves through the whole image file (RM E-11: offsets in words).
    if (d.indexed) off += static_cast<std::int16_t>(w_[s24_]);
    const bool inside = d.indexed ? (off >= 0 && off < static_cast<std::int64_t>(f.elements))
                                  : (word >= 0 && static_cast<std::uint32_t>(word) < si.words);
    if (!inside) {
      message = to_string(d.address) + index_note() + " is outside the " + std::string(file_letter(d.type)) +
                ": image";
      return false;
    }
    word_index = f.base + off;
  } else {
    std::int64_t elem;
    if (d.bit_offset && d.ptr_bit >= 0) {
      // B3/[N7:0]: the pointer is a bit number counted from the start of the file.
      const int n = ptr(d.ptr_bit);
      if (n < 0) {
        message = to_string(d.address) + index_note() + ": negative bit offset";
        return false;
      }
      elem = n / 16;
      bit = n % 16;
    } else {
      elem = d.ptr_element >= 0 ? ptr(d.ptr_element) : d.element;
    }
    if (d.indexed) elem += static_cast<std::int16_t>(w_[s24_]);
    const std::string fname = std::string(file_letter(f.type)) + (file > 2 ? std::to_string(file) : std::string());
    if (elem < 0 || elem >= static_cast<std::int64_t>(f.elements)) {
      message = to_string(d.address) + index_note() + " is beyond the end of " + fname + " (elements 0-" +
                std::to_string(static_cast<int>(f.elements) - 1) + ")";
      return false;
    }
    int sub = 0;
    if (is_structured(d.type) || d.type == FileType::String || is_multiword_data(d.type)) {
      // T/C/R words 0-2; ST words 0 (the length) to 41; MG 0-24, RI 0-19 (vm/data_table.cpp, the same rule).
      const int last_word = static_cast<int>(f.words_per_element) - 1;
      sub = d.ptr_word >= 0 ? ptr(d.ptr_word) : std::max(d.word, 0);
      if (sub < 0 || sub > last_word) {
        message = to_string(d.address) + index_note() + ": sub-element " + std::to_string(sub) + " does not exist";
        return false;
      }
    }
    word_index = f.base + elem * f.words_per_element + sub;
  }
  const bool pointer_bit = d.ptr_bit >= 0 && !d.bit_offset;
  if (pointer_bit) {
    bit = ptr(d.ptr_bit);
    if (bit < 0) {
      message = to_string(d.address) + index_note() + ": negative bit number";
      return false;
    }
  }
  if (bit >= 0) {
    const int limit = d.type == FileType::Long ? 32 : 16;
    // MicroLogix (decision, docs/semantics.md "Indexed and indirect addresses"): a pointer bit past
    // the word's last bit counts on into the following words of a B, N or L file, as B3/[N7:0] does.
    const bool runs_on = pointer_bit && indirect_bit_runs_on_ &&
                         (d.type == FileType::Bit || d.type == FileType::Integer || d.type == FileType::Long);
    if (bit >= limit && !runs_on) {
      message = to_string(d.address) + index_note() + ": bit " + std::to_string(bit) + " does not exist";
      return false;
    }
    word_index += bit / 16;
    bit %= 16;
    if (word_index >= static_cast<std::int64_t>(f.end())) {
      message = to_string(d.address) + index_note() + " is beyond the end of " + std::string(file_letter(f.type)) +
                std::to_string(file);
      return false;
    }
  }
  out = {};
  out.word = static_cast<std::uint32_t>(word_index);
  out.bit = bit;
  out.file = file;
  return true;
}

// An M0/M1 operand names its slot and word directly (the module checks the word): nothing to
// compute and no fault possible.
void Interpreter::mfile_ref(const DynOperand& d, Ref& out) {
  out = {};
  out.mfile = true;
  out.slot = d.element;
  out.which = d.which;
  out.word = static_cast<std::uint32_t>(std::max(d.word, 0));
  out.bit = d.bit;
}

bool Interpreter::resolve(const DynOperand& d, Ref& out) {
  // A module instruction's M-file operand (a BTR's M1:1.100) is resolved at every execution.
  if (d.mfile) {
    mfile_ref(d, out);
    return true;
  }
  std::uint16_t code = 0;
  std::string message;
  if (resolve_common(d, out, code, message)) return true;
  raise(code, message);
  return false;
}

bool Interpreter::resolve_for_tool(const DynOperand& d, Location& out, std::string& message) {
  w_ = table_.words();
  Ref r;
  std::uint16_t code = 0;
  if (d.mfile) {
    message = "M0/M1 words are read through the module, not the data table";
    return false;
  }
  if (!resolve_common(d, r, code, message)) return false;
  out.word = r.word;
  out.bit = r.bit;
  out.vtype = r.bit >= 0 ? ValueType::Int16 : d.vtype;
  out.type = d.type;
  out.file = r.file;
  return true;
}

// ---- Operand access ----------------------------------------------------------------------------------------

inline bool Interpreter::rd_bit(std::uint32_t o) {
  if (bc::mode_of(o) == bc::kBit) [[likely]]
    return (w_[bc::word_of_bit(o)] >> bc::bit_of(o)) & 1u;
  return rd_bit_slow(o);
}

inline void Interpreter::wr_bit(std::uint32_t o, bool v) {
  if (bc::mode_of(o) == bc::kBit) [[likely]] {
    std::uint16_t& word = w_[bc::word_of_bit(o)];
    const auto mask = static_cast<std::uint16_t>(1u << bc::bit_of(o));
    word = static_cast<std::uint16_t>(v ? (word | mask) : (word & ~mask));
    return;
  }
  wr_bit_slow(o, v);
}

bool Interpreter::rd_bit_slow(std::uint32_t o) {
  if (bc::mode_of(o) != bc::kDyn) return false;
  const DynOperand& d = prog_.dyn[bc::payload_of(o)];
  Ref r;
  if (!resolve(d, r)) return false;
  if (r.mfile) {
    std::uint16_t v = 0;
    charge_m(d.access_row, 1);
    const MAccess a = chassis_.read_m(r.slot, r.which, static_cast<int>(r.word), v);
    if (a != MAccess::Ok) {
      raise(fault::module_access(r.slot), "reading " + to_string(d.address) + ": " +
                                              refused(a, r.slot, r.which, static_cast<int>(r.word), false));
      return false;
    }
    return (v >> r.bit) & 1u;
  }
  return (w_[r.word] >> r.bit) & 1u;
}

void Interpreter::wr_bit_slow(std::uint32_t o, bool v) {
  if (bc::mode_of(o) != bc::kDyn) return;
  const DynOperand& d = prog_.dyn[bc::payload_of(o)];
  Ref r;
  if (!resolve(d, r)) return;
  const auto mask = static_cast<std::uint16_t>(1u << r.bit);
  if (r.mfile) {
    // A bit write is a read-modify-write of the module word, charged as one access.
    std::uint16_t word = 0;
    charge_m(d.access_row, 1);
    MAccess a = chassis_.read_m(r.slot, r.which, static_cast<int>(r.word), word);
    if (a == MAccess::Ok)
      a = chassis_.write_m(r.slot, r.which, static_cast<int>(r.word),
                           static_cast<std::uint16_t>(v ? (word | mask) : (word & ~mask)));
    if (a != MAccess::Ok)
      raise(fault::module_access(r.slot), "writing " + to_string(d.address) + ": " +
                                              refused(a, r.slot, r.which, static_cast<int>(r.word), true));
    return;
  }
  std::uint16_t& word = w_[r.word];
  word = static_cast<std::uint16_t>(v ? (word | mask) : (word & ~mask));
}

ValueType Interpreter::dest_type(std::uint32_t o) const {
  switch (bc::mode_of(o)) {
    case bc::kLong: return ValueType::Int32;
    case bc::kFloat: return ValueType::Float32;
    case bc::kDyn: {
      const DynOperand& d = prog_.dyn[bc::payload_of(o)];
      return d.mfile ? ValueType::Int16 : d.vtype;
    }
    default: return ValueType::Int16;
  }
}

std::int64_t Interpreter::rd_int_slow(std::uint32_t o) {
  const std::uint32_t p = bc::payload_of(o);
  switch (bc::mode_of(o)) {
    case bc::kWord: return static_cast<std::int16_t>(w_[p]);
    case bc::kImm: return bc::imm_of(o);
    case bc::kLong: return table_.i32(p);
    case bc::kKInt: return prog_.int_constants[p];
    case bc::kFloat:
    case bc::kKFloat: {
      bool ignored = false;
      return numeric::float_to_integer(rd_flt(o), ValueType::Int32, ignored);
    }
    case bc::kDyn: {
      const DynOperand& d = prog_.dyn[p];
      Ref r;
      if (!resolve(d, r)) return 0;
      if (r.mfile) {
        std::uint16_t v = 0;
        // MVM's read of its M destination is part of the "MVM to M file" access, charged on write.
        if (d.access_row != MFileAccess::MvmToM) charge_m(d.access_row, 1);
        const MAccess a = chassis_.read_m(r.slot, r.which, static_cast<int>(r.word), v);
        if (a != MAccess::Ok) {
          raise(fault::module_access(r.slot),
                "reading " + to_string(d.address) + ": " + refused(a, r.slot, r.which, static_cast<int>(r.word), false));
          return 0;
        }
        return static_cast<std::int16_t>(v);
      }
      switch (d.vtype) {
        case ValueType::Int16: return static_cast<std::int16_t>(w_[r.word]);
        case ValueType::Int32: return table_.i32(r.word);
        case ValueType::Float32: {
          bool ignored = false;
          return numeric::float_to_integer(table_.f32(r.word), ValueType::Int32, ignored);
        }
      }
      return 0;
    }
    default: return 0;
  }
}

float Interpreter::rd_flt(std::uint32_t o) {
  const std::uint32_t p = bc::payload_of(o);
  switch (bc::mode_of(o)) {
    case bc::kFloat: return numeric::flush_denormal(table_.f32(p));
    case bc::kKFloat: return numeric::flush_denormal(prog_.float_constants[p]);
    case bc::kDyn: {
      const DynOperand& d = prog_.dyn[p];
      if (!d.mfile && d.vtype == ValueType::Float32) {
        Ref r;
        if (!resolve(d, r)) return 0.0f;
        return numeric::flush_denormal(table_.f32(r.word));
      }
      return static_cast<float>(rd_int(o));
    }
    default: return static_cast<float>(rd_int(o));
  }
}

std::uint16_t Interpreter::rd_word(std::uint32_t o) {
  if (bc::mode_of(o) == bc::kWord) return w_[bc::payload_of(o)];
  return static_cast<std::uint16_t>(rd_int(o));
}

void Interpreter::wr_word_slow(std::uint32_t o, std::uint16_t v) {
  const std::uint32_t p = bc::payload_of(o);
  switch (bc::mode_of(o)) {
    case bc::kWord: w_[p] = v; return;
    case bc::kLong: table_.set_i32(p, static_cast<std::int16_t>(v)); return;
    case bc::kFloat: table_.set_f32(p, static_cast<std::int16_t>(v)); return;
    case bc::kDyn: {
      const DynOperand& d = prog_.dyn[p];
      Ref r;
      if (!resolve(d, r)) return;
      if (r.mfile) {
        charge_m(d.access_row, 1);
        const MAccess a = chassis_.write_m(r.slot, r.which, static_cast<int>(r.word), v);
        if (a != MAccess::Ok)
          raise(fault::module_access(r.slot),
                "writing " + to_string(d.address) + ": " + refused(a, r.slot, r.which, static_cast<int>(r.word), true));
        return;
      }
      switch (d.vtype) {
        case ValueType::Int16: w_[r.word] = v; return;
        case ValueType::Int32: table_.set_i32(r.word, static_cast<std::int16_t>(v)); return;
        case ValueType::Float32: table_.set_f32(r.word, static_cast<std::int16_t>(v)); return;
      }
      return;
    }
    default: return;  // constants are never destinations (the compiler refuses them)
  }
}

std::uint16_t* Interpreter::element(std::uint32_t o) {
  if (bc::mode_of(o) == bc::kWord) [[likely]]
    return w_ + bc::payload_of(o);
  if (bc::mode_of(o) == bc::kDyn) {
    Ref r;
    if (resolve(prog_.dyn[bc::payload_of(o)], r) && !r.mfile) return w_ + r.word;
  }
  scratch_.fill(0);
  return scratch_.data();
}

std::int64_t Interpreter::st_int(std::uint32_t o, std::int64_t v, bool& overflow) {
  const ValueType vt = dest_type(o);
  if (vt == ValueType::Float32) {
    // An integer result into an F destination converts exactly (within float precision).
    bool ignored = false;
    return static_cast<std::int64_t>(st_flt(o, static_cast<float>(v), ignored));
  }
  // S:2/14 = 1: keep the truncated low bits; 0 (default): clamp (PT1 20-5, ML B-10).
  return st_bits(o, word_ops::fit_integer(v, vt == ValueType::Int32, (w_[s2_] & status::kOverflowSelect) != 0, overflow));
}

std::int64_t Interpreter::st_bits(std::uint32_t o, std::int64_t v) {
  if (bc::mode_of(o) == bc::kWord) [[likely]] {  // a direct 16-bit word: the common case
    const auto stored = static_cast<std::int16_t>(static_cast<std::uint16_t>(v));
    w_[bc::payload_of(o)] = static_cast<std::uint16_t>(stored);
    return stored;
  }
  const ValueType vt = dest_type(o);
  if (vt == ValueType::Int32) {
    const auto stored = static_cast<std::int32_t>(static_cast<std::uint32_t>(v));
    if (bc::mode_of(o) == bc::kLong) {
      table_.set_i32(bc::payload_of(o), stored);
    } else if (bc::mode_of(o) == bc::kDyn) {
      Ref r;
      if (resolve(prog_.dyn[bc::payload_of(o)], r)) table_.set_i32(r.word, stored);
    }
    return stored;
  }
  if (vt == ValueType::Float32) {
    bool ignored = false;
    return static_cast<std::int64_t>(st_flt(o, static_cast<float>(v), ignored));
  }
  const auto stored = static_cast<std::int16_t>(static_cast<std::uint16_t>(v));
  wr_word(o, static_cast<std::uint16_t>(stored));
  return stored;
}

double Interpreter::st_flt(std::uint32_t o, float v, bool& overflow) {
  const ValueType vt = dest_type(o);
  if (vt == ValueType::Float32) {
    v = numeric::flush_denormal(v);
    if (!std::isfinite(v)) overflow = true;
    if (bc::mode_of(o) == bc::kFloat) {
      table_.set_f32(bc::payload_of(o), v);
    } else if (bc::mode_of(o) == bc::kDyn) {
      Ref r;
      if (resolve(prog_.dyn[bc::payload_of(o)], r)) table_.set_f32(r.word, v);
    }
    return v;
  }
  // A float result into an integer destination rounds half to even and saturates, whatever
  // S:2/14 says (ML1400 RM p.204).
  const std::int64_t i = numeric::float_to_integer(v, vt, overflow);
  return static_cast<double>(st_bits(o, i));
}

void Interpreter::set_flags(bool c, bool v, bool z, bool s) {
  word_ops::set_arith_flags(w_, s0_, s5_, c, v, z, s);
}

bool Interpreter::file_span(std::uint32_t o, std::uint32_t elements, Span& out, std::string_view what) {
  out = {};
  const DataTableLayout& L = *prog_.layout;
  std::uint32_t base = 0;
  int file = -1;
  const bc::Mode m = bc::mode_of(o);
  if (m == bc::kWord || m == bc::kLong || m == bc::kFloat) {
    base = bc::payload_of(o);
    file = L.file_containing(base);
  } else if (m == bc::kDyn) {
    const DynOperand& d = prog_.dyn[bc::payload_of(o)];
    Ref r;
    if (!resolve(d, r)) return false;
    if (r.mfile) {
      out.mfile = true;
      out.row = d.access_row;
      out.slot = r.slot;
      out.which = r.which;
      out.base = r.word;
      out.count = elements;
      return true;
    }
    base = r.word;
    file = r.file;
  } else {
    return false;
  }
  if (file < 0) return false;
  const FileLayout& f = L.files[static_cast<std::size_t>(file)];
  out.wpe = f.words_per_element;
  out.vtype = is_structured(f.type) ? ValueType::Int16 : value_type_of(f.type);
  const std::uint64_t words = static_cast<std::uint64_t>(elements) * out.wpe;
  if (base + words > f.end()) {
    // The message is built only here: the normal path allocates nothing.
    const std::string name = m == bc::kDyn ? to_string(prog_.dyn[bc::payload_of(o)].address) : L.describe(base);
    raise(fault::kIndexOutOfRange, std::string(what) + " of " + std::to_string(elements) + " element(s) from " + name +
                                       " runs past the end of its file");
    return false;
  }
  out.base = base;
  out.count = static_cast<std::uint32_t>(words);
  return true;
}

std::uint16_t Interpreter::span_get(const Span& s, std::uint32_t i) {
  if (!s.mfile) return w_[s.base + i];
  std::uint16_t v = 0;
  const MAccess a = chassis_.read_m(s.slot, s.which, static_cast<int>(s.base + i), v);
  if (a != MAccess::Ok) m_read_refused(s, i, a);
  return v;
}

void Interpreter::m_read_refused(const Span& s, std::uint32_t i, MAccess a) {
  raise(fault::module_access(s.slot), "reading M" + std::to_string(static_cast<int>(s.which)) + ":" +
                                          std::to_string(s.slot) + "." + std::to_string(s.base + i) + ": " +
                                          refused(a, s.slot, s.which, static_cast<int>(s.base + i), false));
}

void Interpreter::span_set(const Span& s, std::uint32_t i, std::uint16_t v) {
  if (!s.mfile) {
    w_[s.base + i] = v;
    return;
  }
  const MAccess a = chassis_.write_m(s.slot, s.which, static_cast<int>(s.base + i), v);
  if (a != MAccess::Ok)
    raise(fault::module_access(s.slot), "writing M" + std::to_string(static_cast<int>(s.which)) + ":" +
                                            std::to_string(s.slot) + "." + std::to_string(s.base + i) + ": " +
                                            refused(a, s.slot, s.which, static_cast<int>(s.base + i), true));
}

// ---- Specialty-module instructions ------------------------------------------------------------------

void ChassisAccess::module_instruction(int slot, ModuleInstructionContext& ctx) {
  ctx.fault(fault::kUnsupportedInstruction, std::string(spec(ctx.opcode()).mnemonic) + ": there is no module in slot " +
                                               std::to_string(slot) + " to execute it");
}

// The interpreter's side of a module instruction: checked data-table and M-file access, charged
// to the scan through the timing model, faults through raise().
class ModuleCall final : public ModuleInstructionContext {
 public:
  ModuleCall(Interpreter& in, Opcode op, bool rung, VirtualTime now, std::span<const ModuleOperand> ops)
      : in_(in), op_(op), rung_(rung), now_(now), ops_(ops) {}

  Opcode opcode() const override { return op_; }
  bool rung_in() const override { return rung_; }
  bool first_pass() const override { return in_.first_pass_; }
  VirtualTime now() const override {
    ++in_.module_time_reads_;
    return now_;
  }
  std::span<const ModuleOperand> operands() const override { return ops_; }

  bool read(std::size_t i, std::uint32_t k, std::uint16_t& value) override {
    if (!check(i, k)) return false;
    value = in_.w_[ops_[i].word + k];
    return true;
  }
  bool read_block(std::size_t i, std::uint32_t k, std::span<std::uint16_t> out) override {
    if (out.empty()) return true;
    // One file, one limit: the block is inside when it starts inside and fits in what remains (no
    // sum that could wrap). A block that leaves the file faults at its first word past the end,
    // as read() would.
    if (i < ops_.size() && ops_[i].kind == ModuleOperand::Kind::Table && k < ops_[i].limit &&
        out.size() <= ops_[i].limit - k) {
      std::copy_n(in_.w_ + ops_[i].word + k, out.size(), out.begin());
      return true;
    }
    const std::uint32_t first_bad =
        i < ops_.size() && ops_[i].kind == ModuleOperand::Kind::Table ? std::max(k, ops_[i].limit) : k;
    return check(i, first_bad);
  }
  bool write(std::size_t i, std::uint32_t k, std::uint16_t value) override {
    if (!check(i, k)) return false;
    in_.w_[ops_[i].word + k] = value;
    return true;
  }
  bool write_block(std::size_t i, std::uint32_t k, std::span<const std::uint16_t> in) override {
    if (in.empty()) return true;
    // As read_block: inside when it starts inside and fits in what remains; else the words up to
    // the file's end are written and the first word past it faults, as write() would.
    const bool table = i < ops_.size() && ops_[i].kind == ModuleOperand::Kind::Table;
    const std::uint32_t room = table && k < ops_[i].limit ? ops_[i].limit - k : 0;
    const std::size_t fit = std::min<std::size_t>(in.size(), room);
    if (fit > 0) std::copy_n(in.begin(), fit, in_.w_ + ops_[i].word + k);
    return fit == in.size() || check(i, k + static_cast<std::uint32_t>(fit));
  }
  bool read_m(int slot, MFile f, int word, std::uint16_t& value) override {
    const MAccess a = in_.chassis_.read_m(slot, f, word, value);
    if (a == MAccess::Ok) return true;
    in_.raise(fault::module_access(slot), std::string(spec(op_).mnemonic) + " reading M" + std::to_string(static_cast<int>(f)) +
                                              ":" + std::to_string(slot) + "." + std::to_string(word) + ": " +
                                              in_.refused(a, slot, f, word, false));
    return false;
  }
  std::size_t read_m_block(int slot, MFile f, int word, std::span<std::uint16_t> out) override {
    std::size_t done = 0;
    const MAccess a = in_.chassis_.read_m_block(slot, f, word, out, done);
    if (a == MAccess::Ok) return done;
    const int bad = word + static_cast<int>(done);
    in_.raise(fault::module_access(slot), std::string(spec(op_).mnemonic) + " reading M" + std::to_string(static_cast<int>(f)) +
                                              ":" + std::to_string(slot) + "." + std::to_string(bad) + ": " +
                                              in_.refused(a, slot, f, bad, false));
    return done;
  }
  bool write_m(int slot, MFile f, int word, std::uint16_t value) override {
    const MAccess a = in_.chassis_.write_m(slot, f, word, value);
    if (a == MAccess::Ok) return true;
    in_.raise(fault::module_access(slot), std::string(spec(op_).mnemonic) + " writing M" + std::to_string(static_cast<int>(f)) +
                                              ":" + std::to_string(slot) + "." + std::to_string(word) + ": " +
                                              in_.refused(a, slot, f, word, true));
    return false;
  }
  void charge(MFileAccess row, int words) override { in_.charge_m(row, words); }
  void fault(std::uint16_t code, std::string message) override { in_.raise(code, std::move(message)); }

 private:
  bool check(std::size_t i, std::uint32_t k) {
    if (i < ops_.size() && ops_[i].kind == ModuleOperand::Kind::Table && k < ops_[i].limit) [[likely]] return true;
    out_of_file(i, k);
    return false;
  }
  // check()'s fault, apart so that check() itself is inlined into every access.
  [[gnu::noinline, gnu::cold]] void out_of_file(std::size_t i, std::uint32_t k) {
    in_.raise(fault::kIndexOutOfRange, std::string(spec(op_).mnemonic) + " " +
                                          (i < spec(op_).operand_count ? std::string(spec(op_).operands[i].label)
                                                                       : std::string("operand")) +
                                          ": word " + std::to_string(k) + " runs past the end of its data file");
  }

  Interpreter& in_;
  Opcode op_;
  bool rung_;
  VirtualTime now_;
  std::span<const ModuleOperand> ops_;
};

void Interpreter::module_instruction(Op op, const std::uint32_t* o, std::uint32_t h, bool rung, Nanoseconds now_in_scan) {
  const DataTableLayout& L = *prog_.layout;
  // The operands the instruction has (a BTR 7 of the 15 a module instruction may have) are
  // initialised, not all 15: a busy 1747-SN program executes several BTRs per scan.
  constexpr std::uint32_t kMaxOperands = 15;
  alignas(ModuleOperand) unsigned char storage[sizeof(ModuleOperand) * kMaxOperands];
  const std::uint32_t n = std::min<std::uint32_t>(bc::count_of(h), kMaxOperands);
  ModuleOperand* const ops = reinterpret_cast<ModuleOperand*>(storage);
  for (std::uint32_t i = 0; i < n; ++i) ::new (static_cast<void*>(ops + i)) ModuleOperand{};
  auto table = [&](ModuleOperand& m, std::uint32_t word) {
    m.kind = ModuleOperand::Kind::Table;
    m.word = word;
    const int file = L.file_containing(word);
    m.limit = file < 0 ? 1 : L.files[static_cast<std::size_t>(file)].end() - word;
  };
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t w = o[i];
    ModuleOperand& m = ops[i];
    switch (bc::mode_of(w)) {
      case bc::kWord:
      case bc::kLong:
      case bc::kFloat: table(m, bc::payload_of(w)); break;
      case bc::kDyn: {
        Ref r;
        if (!resolve(prog_.dyn[bc::payload_of(w)], r)) return;
        if (r.mfile) {
          m.kind = ModuleOperand::Kind::MFile;
          m.slot = r.slot;
          m.file = r.which;
          m.word = r.word;
        } else {
          table(m, r.word);
        }
        break;
      }
      case bc::kImm: m.value = bc::imm_of(w); break;
      case bc::kKInt: m.value = prog_.int_constants[bc::payload_of(w)]; break;
      default: break;
    }
  }
  ModuleCall call(*this, to_opcode(op), rung, scan_start_ + now_in_scan, std::span<const ModuleOperand>(ops, n));
  chassis_.module_instruction(static_cast<int>(bc::aux_of(h)), call);
}

// ---- PID ------------------------------------------------------------------------------------------------------

bool Interpreter::pid(const std::uint32_t* o, bool rung, Nanoseconds now_in_scan) {
  Span block;
  if (!file_span(o[0], pid::kBlockWords, block, "PID control block")) {
    if (!faulted_) raise(fault::kIndexOutOfRange, "PID control block is not a 23-word run of an integer file");
    return false;
  }
  const std::int64_t pv = rd_int(o[1]);
  const std::int64_t cv = rd_int(o[2]);
  if (faulted_) return false;
  pid::Execution x;
  x.rung = rung;
  x.first_pass = first_pass_;
  x.slc502 = prog_.processor.family == ProcessorFamily::Slc502;
  x.now = scan_start_ + now_in_scan;
  x.pv = static_cast<std::int16_t>(pv);
  x.cv = static_cast<std::int16_t>(cv);
  const pid::Outcome r = pid::execute(std::span<std::uint16_t, pid::kBlockWords>(w_ + block.base, pid::kBlockWords), x);
  pid_same_until_ = std::min(pid_same_until_, r.same_until);
  if (r.error != pid::Error::None) {
    raise(fault::kPidError, prog_.layout->describe(block.base) + ": " + r.message);
    return false;
  }
  if (r.write_cv) st_bits(o[2], r.cv);
  return !faulted_;
}

// ---- ASCII and strings (1747-RM001G ch. 10) -----------------------------------------------------------------

// S:5/15, the ASCII error bit (RM 10-3). The MicroLogix also writes 1F39h to S:6 (1763-RM001,
// 1766-RM001: "Invalid String Length Error (1F39H) is written to the Major Error Fault Code word");
// neither halts the processor.
void Interpreter::ascii_error() {
  w_[s5_] |= ascii::kAsciiErrorBit;
  if (prog_.processor.family == ProcessorFamily::MicroLogix) w_[s6_] = ascii::kMicroLogixStringLengthError;
}

bool Interpreter::string_words(std::uint32_t o, std::uint16_t*& words, const char* what) {
  Span s;
  if (!file_span(o, 1, s, what)) return false;
  if (s.mfile || s.count != ascii::kElementWords) {
    raise(fault::kIndexOutOfRange, std::string(what) + " is not a string element");
    return false;
  }
  words = w_ + s.base;
  return true;
}

bool Interpreter::read_string(std::uint32_t o, ascii::Text& out, const char* what) {
  std::uint16_t* e = nullptr;
  if (!string_words(o, e, what)) return false;
  if (!ascii::read(ascii::ConstElement(e, ascii::kElementWords), out)) {
    ascii_error();
    return false;
  }
  return true;
}

// ACI AIC ACN AEX ASC: each reads its operands, computes through vm/ascii.h and writes its
// destination; a bad length or range sets S:5/15 and leaves the destination as it was.
void Interpreter::string_instruction(Op op, const std::uint32_t* o) {
  ascii::Text a, b, out;
  std::uint16_t* dest = nullptr;
  switch (op) {
    case Op::ACI: {
      if (!read_string(o[0], a, "ACI source")) return;
      charge_words(op, static_cast<std::uint32_t>(a.length));  // per character (the profile's per_word_us)
      const ascii::IntegerResult r = ascii::to_integer(a);
      if (!r.converted) return;  // RM 10-8: "Action is taken only if numeric characters are found"
      st_bits(o[1], r.value);
      set_flags(false, r.overflow, r.value == 0, r.value < 0);
      return;
    }
    case Op::AIC:
      if (!string_words(o[1], dest, "AIC dest")) return;
      out = ascii::from_integer(static_cast<std::int16_t>(rd_int(o[0])));
      ascii::write(ascii::Element(dest, ascii::kElementWords), out);
      charge_words(op, static_cast<std::uint32_t>(out.length));
      return;
    case Op::ACN:
      if (!read_string(o[0], a, "ACN source A") || !read_string(o[1], b, "ACN source B")) return;
      if (!string_words(o[2], dest, "ACN dest")) return;
      out = ascii::concatenate(a, b);
      ascii::write(ascii::Element(dest, ascii::kElementWords), out);
      charge_words(op, static_cast<std::uint32_t>(out.length));
      return;
    case Op::AEX: {
      if (!read_string(o[0], a, "AEX source")) return;
      const std::int64_t index = rd_int(o[1]), number = rd_int(o[2]);
      if (!string_words(o[3], dest, "AEX dest")) return;
      if (!ascii::extract(a, index, number, out)) return ascii_error();
      ascii::write(ascii::Element(dest, ascii::kElementWords), out);
      charge_words(op, static_cast<std::uint32_t>(out.length));
      return;
    }
    case Op::ASC: {
      if (!read_string(o[0], a, "ASC source") || !read_string(o[2], b, "ASC string search")) return;
      std::int64_t position = 0;
      if (!ascii::search(a, rd_int(o[1]), b, position)) return ascii_error();
      charge_words(op, static_cast<std::uint32_t>(b.length));
      st_bits(o[3], position);
      return;
    }
    default: return;
  }
}

// ASR (RM 10-19): true when the strings match in length and every character (case counts); "An
// invalid string length causes the processor to set ASCII Error bit S:5/15, and the rung goes false".
bool Interpreter::string_compare(const std::uint32_t* o) {
  ascii::Text a, b;
  if (!read_string(o[0], a, "ASR source A") || !read_string(o[1], b, "ASR source B")) return false;
  // Timed per matching character (1763-RM001C p. 334).
  const auto common = std::mismatch(a.view().begin(), a.view().end(), b.view().begin(), b.view().end());
  charge_words(Op::ASR, static_cast<std::uint32_t>(common.first - a.view().begin()));
  return a.view() == b.view();
}

void Interpreter::channel_instruction(Op op, const std::uint32_t* o, bool rung, Nanoseconds now_in_scan) {
  // Operands: ABL/ACB channel, control; AHL channel, AND, OR, control; ARD/ARL/AWA/AWT channel,
  // string, control.
  const std::uint32_t control = op == Op::ABL || op == Op::ACB ? o[1] : op == Op::AHL ? o[3] : o[2];
  std::uint16_t* r = element(control);
  if (faulted_) return;
  // RM 10-6: "When the program scans the instruction and finds the Done bit (DN) set, the
  // processor then sets the Synchronous Done bit (EM)"; softslc does the same for ER.
  if (r[0] & (bits::kDN | bits::kER)) r[0] |= bits::kEM;
  if (!rung) {
    r[0] &= static_cast<std::uint16_t>(~bits::kEN);
    return;
  }
  const bool enabled = (r[0] & bits::kEN) != 0;
  // Enabled but neither queued, running nor done: the queue was full; try again (RM 10-5: "This
  // action is delayed if the queue is already filled").
  const bool waiting = enabled && !(r[0] & (bits::kEU | bits::kIN | bits::kDN | bits::kER));
  if (enabled && !waiting) return;
  if (!enabled) {
    // The previous operation is still queued or running: it is not queued twice (decision).
    if (r[0] & (bits::kEU | bits::kIN)) {
      r[0] |= bits::kEN;
      return;
    }
    // A new operation: the previous one's result bits, error code and count go.
    r[0] = static_cast<std::uint16_t>((r[0] & ~(bits::kDN | bits::kEM | bits::kER | bits::kFD | 0x00FF)) | bits::kEN);
    r[2] = 0;
  }
  const std::uint32_t control_word = static_cast<std::uint32_t>(r - w_);
  if (!ascii_port_) {
    // RM 10-7: "the instruction is aborted - serial port not in User mode".
    r[0] = static_cast<std::uint16_t>((r[0] & ~0x00FF) | bits::kER | ascii_error::kSystemMode);
    return;
  }
  AsciiPort::Request req;
  req.op = to_opcode(op);
  req.control = control_word;
  req.at = scan_start_ + now_in_scan;
  if (op == Op::AHL) {
    req.and_mask = rd_word(o[1]);
    req.or_mask = rd_word(o[2]);
  } else if (op == Op::ARD || op == Op::ARL || op == Op::AWA || op == Op::AWT) {
    std::uint16_t* e = nullptr;
    if (!string_words(o[1], e, std::string(mnemonic(op)).c_str())) return;
    req.string = static_cast<std::uint32_t>(e - w_);
    // A write is timed per character it hands the port (1763-RM001C p. 317: AWA per character).
    if (op == Op::AWA || op == Op::AWT) {
      const auto len = static_cast<std::int16_t>(r[1]);
      const auto have = static_cast<std::int16_t>(e[0]);
      charge_words(op, static_cast<std::uint32_t>(std::clamp<int>(len > 0 ? std::min<int>(len, have) : have, 0, ascii::kMaxLength)));
    }
  }
  ascii_port_->submit(req);
}

void Interpreter::ascii_clear(const std::uint32_t* o, Nanoseconds now_in_scan) {
  if (ascii_port_) ascii_port_->clear(bc::imm_of(o[1]) != 0, bc::imm_of(o[2]) != 0, scan_start_ + now_in_scan);
}

// ---- Timers, counters, reset ----------------------------------------------------------------------------------

bool Interpreter::timer(Op op, const std::uint32_t* o, std::uint32_t h, bool rung, Nanoseconds now_in_scan) {
  std::uint16_t* t = element(o[0]);
  if (faulted_) return true;  // a DYN fault: the dispatch loop stops the scan after this instruction
  if (word_ops::timer_negative(t)) {
    const auto pre = static_cast<std::int16_t>(t[1]);
    const auto acc = static_cast<std::int16_t>(t[2]);
    const DataTableLayout& L = *prog_.layout;
    const std::string name = bc::mode_of(o[0]) == bc::kWord ? L.describe(bc::payload_of(o[0]))
                                                            : to_string(prog_.dyn[bc::payload_of(o[0])].address);
    raise(fault::kNegativeTimerValue, std::string(mnemonic(op)) + " " + name + " has a negative " +
                                          (pre < 0 ? "PRE (" + std::to_string(pre) + ")" : "ACC (" + std::to_string(acc) + ")"));
    return false;
  }
  if (timer_executions_) [[unlikely]]
    word_ops::record_timer(*timer_executions_, op, w_, static_cast<std::uint32_t>(t - w_), rung,
                           scan_start_ + now_in_scan, bc::flags_of(h));
  // The tick count at this instruction's virtual time (vm/word_ops.h).
  word_ops::timer(op, t, rung, first_pass_, word_ops::timer_tick(scan_start_ + now_in_scan, bc::flags_of(h)),
                  (bc::flags_of(h) & bc::kFlagA) != 0);
  return true;
}

void Interpreter::counter(Op op, const std::uint32_t* o, bool rung) {
  std::uint16_t* c = element(o[0]);
  if (faulted_) return;
  word_ops::counter(op, c, rung, first_pass_);
}

void Interpreter::reset(const std::uint32_t* o, std::uint32_t h) {
  std::uint16_t* e = element(o[0]);
  if (faulted_) return;
  word_ops::reset(static_cast<FileType>(bc::aux_of(h)), e);
}

// ---- Compare, math, logical, move ----------------------------------------------------------------------------

namespace {

// The integer quotient a / b (b != 0) with DIV's rounding: a remainder of one half or more rounds
// away from zero (RM 4-10: 11/2 -> 6; the negative side is docs/semantics.md's decision). DIV,
// DDV, SCL and CPT's | share it.
std::int64_t rounded_quotient(std::int64_t a, std::int64_t b) {
  const std::int64_t q = a / b, rem = a % b;
  if (2 * (rem < 0 ? -rem : rem) >= (b < 0 ? -b : b)) return q + (((a < 0) != (b < 0)) ? -1 : 1);
  return q;
}

// The single-precision functions of the float instructions and of CPT. An input the function does
// not take (LN or LOG of 0 or less, ASN or ACS outside -1..1) gives NaN, which the store reports
// as V (RM ASN/ACS: "sets if ... an unsupported input is detected").
float float_function(ExprCode c, float x) {
  constexpr float kPi = 3.14159265358979f;
  constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
  switch (c) {
    case ExprCode::Sqr: return std::sqrt(std::fabs(x));  // RM 4-12: the root of the absolute value
    case ExprCode::Abs: return std::fabs(x);
    case ExprCode::Ln: return x > 0.0f ? std::log(x) : kNaN;
    case ExprCode::Log: return x > 0.0f ? std::log10(x) : kNaN;
    case ExprCode::Sin: return std::sin(x);
    case ExprCode::Cos: return std::cos(x);
    case ExprCode::Tan: return std::tan(x);
    case ExprCode::Asn: return std::fabs(x) <= 1.0f ? std::asin(x) : kNaN;
    case ExprCode::Acs: return std::fabs(x) <= 1.0f ? std::acos(x) : kNaN;
    case ExprCode::Atn: return std::atan(x);
    case ExprCode::Deg: return x * (180.0f / kPi);
    case ExprCode::Rad: return x * (kPi / 180.0f);
    default: return x;
  }
}

// Binary-coded decimal helpers shared by TOD/FRD and the CPT functions of the same names.
std::uint32_t to_bcd(std::uint32_t m) {
  std::uint32_t bcd = 0;
  for (int shift = 0; shift < 20; shift += 4, m /= 10) bcd |= (m % 10) << shift;
  return bcd;
}
// Returns false when a digit is above 9.
bool from_bcd(std::uint32_t bcd, std::uint32_t& value) {
  value = 0;
  bool ok = true;
  for (int shift = 16; shift >= 0; shift -= 4) {
    const std::uint32_t d = (bcd >> shift) & 0xF;
    ok = ok && d <= 9;
    value = value * 10 + d;
  }
  return ok;
}

}  // namespace

bool Interpreter::compare(Op op, const std::uint32_t* o, std::uint32_t h) {
  if (op == Op::MEQ) {
    const std::uint16_t mask = rd_word(o[1]);
    return (rd_word(o[0]) & mask) == (rd_word(o[2]) & mask);
  }
  if (bc::flags_of(h) & bc::kFlagFloat) {
    const double a = rd_flt(o[0]), b = rd_flt(o[1]);
    switch (op) {
      case Op::EQU: return a == b;
      case Op::NEQ: return a != b;
      case Op::LES: return a < b;
      case Op::LEQ: return a <= b;
      case Op::GRT: return a > b;
      case Op::GEQ: return a >= b;
      case Op::LIM: {
        const double hi = rd_flt(o[2]);
        return a <= hi ? (a <= b && b <= hi) : (b >= a || b <= hi);
      }
      default: return false;
    }
  }
  const std::int64_t a = rd_int(o[0]), b = rd_int(o[1]);
  if (op == Op::LIM) {
    // LIM low test high: low <= high tests inside the band, low > high outside it.
    const std::int64_t hi = rd_int(o[2]);
    return a <= hi ? (a <= b && b <= hi) : (b >= a || b <= hi);
  }
  return word_ops::compare(op, a, b);
}

void Interpreter::math(Op op, const std::uint32_t* o, std::uint32_t h) {
  bool overflow = false;
  if (bc::flags_of(h) & bc::kFlagFloat) {
    const float a = rd_flt(o[0]), b = rd_flt(o[1]);
    float r = 0.0f;
    switch (op) {
      case Op::ADD: r = a + b; break;
      case Op::SUB: r = a - b; break;
      case Op::MUL: r = a * b; break;
      case Op::DIV: r = a / b; break;  // b == 0 gives inf or NaN, reported as overflow
      default: break;
    }
    const double stored = st_flt(o[2], r, overflow);
    set_flags(false, overflow, stored == 0.0, stored < 0.0);
    return;
  }
  const std::int64_t a = rd_int(o[0]), b = rd_int(o[1]);
  const bool wide = dest_type(o[2]) == ValueType::Int32;
  const std::uint64_t width_mask = wide ? 0xFFFFFFFFull : 0xFFFFull;
  bool carry = false;
  std::int64_t r = 0;
  switch (op) {
    case Op::ADD:
      r = a + b;
      carry = word_ops::add_carry(a, b, width_mask);
      break;
    case Op::SUB:
      r = a - b;
      carry = word_ops::sub_carry(a, b, width_mask);
      break;
    case Op::MUL: {
      r = a * b;
      // RM 4-10: the 32-bit product goes to S:13 (low word) and S:14 (high word).
      const auto p = static_cast<std::uint32_t>(r);
      w_[s13_] = static_cast<std::uint16_t>(p & 0xFFFF);
      w_[s14_] = static_cast<std::uint16_t>(p >> 16);
      break;
    }
    case Op::DIV: {
      if (b == 0) {
        // RM 4-10: divide by zero sets V (and the S:5/0 trap) and puts the maximum in dest.
        const std::int64_t stored = st_bits(o[2], wide ? INT32_MAX : INT16_MAX);
        set_flags(false, true, stored == 0, stored < 0);
        return;
      }
      const std::int64_t q = a / b;
      const std::int64_t rem = a % b;
      // RM 4-10: dest gets the rounded quotient (11/2 -> 6), S:14 the unrounded quotient and
      // S:13 the remainder. Halves round away from zero (-11/2 -> -6) [U: symmetric].
      r = rounded_quotient(a, b);
      w_[s14_] = static_cast<std::uint16_t>(q);
      w_[s13_] = static_cast<std::uint16_t>(rem);
      break;
    }
    default: break;
  }
  const std::int64_t stored = st_int(o[2], r, overflow);
  // DIV always resets C (RM 4-10); MUL has no carry.
  set_flags(op == Op::ADD || op == Op::SUB ? carry : false, overflow, stored == 0, stored < 0);
}

void Interpreter::unary(Op op, const std::uint32_t* o, std::uint32_t h) {
  bool overflow = false;
  if (op == Op::CLR) {
    if (bc::mode_of(o[0]) == bc::kWord) {  // a direct word: the rule the fused word rungs run too
      word_ops::clear(w_, bc::payload_of(o[0]), s0_, s5_);
      return;
    }
    if (dest_type(o[0]) == ValueType::Float32) st_flt(o[0], 0.0f, overflow);
    else st_bits(o[0], 0);
    set_flags(false, false, true, false);
    return;
  }
  // NEG
  if (bc::flags_of(h) & bc::kFlagFloat) {
    const double stored = st_flt(o[1], -rd_flt(o[0]), overflow);
    set_flags(false, overflow, stored == 0.0, stored < 0.0);
    return;
  }
  const std::int64_t a = rd_int(o[0]);
  const std::int64_t stored = st_int(o[1], -a, overflow);
  // C: "cleared if 0 or overflow, otherwise set" (PT1 20-10): NEG of -32768 overflows, so C = 0.
  set_flags(a != 0 && !overflow, overflow, stored == 0, stored < 0);
}

void Interpreter::logical(Op op, const std::uint32_t* o) {
  std::int64_t r = 0;
  std::uint32_t dest = 0;
  switch (op) {
    case Op::AND: r = rd_int(o[0]) & rd_int(o[1]); dest = o[2]; break;
    case Op::OR: r = rd_int(o[0]) | rd_int(o[1]); dest = o[2]; break;
    case Op::XOR: r = rd_int(o[0]) ^ rd_int(o[1]); dest = o[2]; break;
    case Op::NOT: r = ~rd_int(o[0]); dest = o[1]; break;
    default: return;
  }
  const std::int64_t stored = st_bits(dest, r);
  set_flags(false, false, stored == 0, stored < 0);
}

// ---- Issue 15: DDV, SQR, ABS, float functions, SCL, SCP, BCD and bit encode/decode ---------------------------

void Interpreter::double_divide(const std::uint32_t* o) {
  // RM 4-11 (table 4.9): the 32-bit math register S:14 (high) : S:13 (low) is the dividend. The
  // quotient is rounded (a remainder of one half or more rounds away from zero, as DIV); division
  // by zero or a quotient outside -32768..32767 sets V (and S:5/0) and puts 32767 in dest whatever
  // S:2/14 says. C always resets.
  const auto dividend = static_cast<std::int32_t>((static_cast<std::uint32_t>(w_[s14_]) << 16) | w_[s13_]);
  const std::int64_t b = rd_int(o[0]);
  if (b == 0) {
    const std::int64_t stored = st_bits(o[1], INT16_MAX);
    set_flags(false, true, stored == 0, stored < 0);
    return;
  }
  const std::int64_t q = dividend / b;
  const std::int64_t rem = dividend % b;
  const std::int64_t r = rounded_quotient(dividend, b);
  if (r > INT16_MAX || r < INT16_MIN) {
    // The math register keeps the dividend: an unrounded quotient that does not fit has no 16-bit
    // home [U, docs/semantics.md].
    const std::int64_t stored = st_bits(o[1], INT16_MAX);
    set_flags(false, true, stored == 0, stored < 0);
    return;
  }
  w_[s14_] = static_cast<std::uint16_t>(q);
  w_[s13_] = static_cast<std::uint16_t>(rem);
  const std::int64_t stored = st_bits(o[1], r);
  set_flags(false, false, stored == 0, stored < 0);
}

void Interpreter::function(Op op, const std::uint32_t* o, std::uint32_t h) {
  bool overflow = false;
  if (op == Op::ABS && !(bc::flags_of(h) & bc::kFlagFloat)) {
    // Integer ABS: |-32768| does not fit and follows the S:2/14 overflow rule like NEG.
    const std::int64_t a = rd_int(o[0]);
    const std::int64_t stored = st_int(o[1], a < 0 ? -a : a, overflow);
    set_flags(false, overflow, stored == 0, stored < 0);
    return;
  }
  // Everything else computes in single precision, as the processor's float unit does. An integer
  // source converts exactly; an integer destination gets the result rounded to nearest (half to
  // even) and saturated, with V (ML1400 RM p.204). NaN or infinity sets V and S:5/0.
  const float x = rd_flt(o[0]);
  float r = 0.0f;
  std::uint32_t dest = o[1];
  switch (op) {
    case Op::SQR: r = float_function(ExprCode::Sqr, x); break;
    case Op::ABS: r = float_function(ExprCode::Abs, x); break;
    case Op::LN: r = float_function(ExprCode::Ln, x); break;
    case Op::LOG: r = float_function(ExprCode::Log, x); break;
    case Op::SIN: r = float_function(ExprCode::Sin, x); break;
    case Op::COS: r = float_function(ExprCode::Cos, x); break;
    case Op::TAN: r = float_function(ExprCode::Tan, x); break;
    case Op::ASN: r = float_function(ExprCode::Asn, x); break;
    case Op::ACS: r = float_function(ExprCode::Acs, x); break;
    case Op::ATN: r = float_function(ExprCode::Atn, x); break;
    case Op::DEG: r = float_function(ExprCode::Deg, x); break;
    case Op::RAD: r = float_function(ExprCode::Rad, x); break;
    case Op::XPY:
      r = std::pow(x, rd_flt(o[1]));
      dest = o[2];
      break;
    default: return;
  }
  const double stored = st_flt(dest, r, overflow);
  set_flags(false, overflow, stored == 0.0, std::signbit(stored) && stored != 0.0);
}

void Interpreter::scale(Op op, const std::uint32_t* o, std::uint32_t h) {
  bool overflow = false;
  if (op == Op::SCP) {
    // RM 4-13: y = m x + b with m = (scaled max - scaled min) / (input max - input min) and
    // b = scaled min - input min * m, in single precision; the output is not clamped to the scaled
    // range. Input max = input min gives an infinite or undefined slope: V.
    (void)h;
    const float x = rd_flt(o[0]), in_min = rd_flt(o[1]), in_max = rd_flt(o[2]);
    const float s_min = rd_flt(o[3]), s_max = rd_flt(o[4]);
    const float m = (s_max - s_min) / (in_max - in_min);
    const float b = s_min - in_min * m;
    const double stored = st_flt(o[5], m * x + b, overflow);
    set_flags(false, overflow, stored == 0.0, std::signbit(stored) && stored != 0.0);
    return;
  }
  // SCL (PT1 20-22): source * rate / 10000, rounded, plus offset. V is checked before and after
  // the offset: an overflow of the product puts +32767 or -32768 in dest whatever the offset is.
  // C is reserved (left as it was). Halves round away from zero, as DIV [U].
  const std::int64_t q = rounded_quotient(rd_int(o[0]) * rd_int(o[1]), 10000);
  std::int64_t r = q;
  if (q > INT16_MAX || q < INT16_MIN) {
    overflow = true;
  } else {
    r = q + rd_int(o[2]);
    overflow = r > INT16_MAX || r < INT16_MIN;
  }
  if (overflow) r = r > 0 ? INT16_MAX : INT16_MIN;
  const std::int64_t stored = st_bits(o[3], r);
  set_flags((w_[s0_] & status::kCarry) != 0, overflow, stored == 0, stored < 0);
}

void Interpreter::convert(Op op, const std::uint32_t* o) {
  // The math register as an operand: a direct S:13 word address (RM 5-2 / 5-4).
  auto is_math_register = [&](std::uint32_t w) { return bc::mode_of(w) == bc::kWord && bc::payload_of(w) == s13_; };
  switch (op) {
    case Op::TOD: {
      // RM 5-2, table 5.2: the absolute value is converted; V (and S:5/0) when the BCD result is
      // above 9999; S is the sign of the source. Into S:13 the five digits fill S:13 and S:14 and
      // are valid at overflow; into a word the low four digits are stored [U].
      const std::int64_t a = rd_int(o[0]);
      const std::uint32_t bcd = to_bcd(static_cast<std::uint32_t>(a < 0 ? -a : a));
      const bool over = bcd > 0x9999;
      std::uint16_t stored = static_cast<std::uint16_t>(bcd & 0xFFFF);
      if (is_math_register(o[1])) {
        w_[s13_] = stored;
        w_[s14_] = static_cast<std::uint16_t>(bcd >> 16);
      } else {
        st_bits(o[1], stored);
      }
      set_flags(false, over, bcd == 0, a < 0);
      return;
    }
    case Op::FRD: {
      // RM 5-4: the BCD source (S:13 reads the five digits of S:14:S:13) to an integer. A digit above
      // 9, or a value above 32767, is not a valid source: V and S:5/0, dest unchanged [U].
      const std::uint32_t bcd = is_math_register(o[0])
                              ? ((static_cast<std::uint32_t>(w_[s14_] & 0xF) << 16) | w_[s13_])
                              : rd_word(o[0]);
      std::uint32_t value = 0;
      const bool bad = !from_bcd(bcd, value);
      if (bad || value > 32767) {
        set_flags(false, true, false, false);
        return;
      }
      const std::int64_t stored = st_bits(o[1], value);
      set_flags(false, false, stored == 0, false);
      return;
    }
    case Op::DCD:
      // RM 5-10: the low four bits of the source select the one bit set in dest. The arithmetic
      // status bits are not changed [U].
      st_bits(o[1], std::int64_t{1} << (rd_word(o[0]) & 0xF));
      return;
    case Op::ENC: {
      // RM 5-12, table 5.6: the lowest set bit wins; V when more than one bit is set, but the
      // overflow trap S:5/0 is NOT set, so the flags are written here rather than by set_flags.
      const std::uint16_t s = rd_word(o[0]);
      const int n = s == 0 ? 0 : std::countr_zero(s);
      const bool many = std::popcount(s) > 1;
      st_bits(o[1], n);
      w_[s0_] = static_cast<std::uint16_t>((w_[s0_] & ~word_ops::kArithFlags) | (many ? status::kOverflow : 0) |
                                           (n == 0 ? status::kZero : 0));
      return;
    }
    default: return;
  }
}

void Interpreter::compute(const std::uint32_t* o) {
  // CPT (docs/semantics.md, "CPT"): the RPN steps run on a fixed local stack. Integer mode keeps
  // 64-bit intermediates and stores with the S:2/14 rule; | rounds like DIV and a zero divisor
  // sets V with 32767. Float mode computes in single precision like the float instructions. V
  // from any step is reported with the result; C always resets.
  const CompiledExpr& e = prog_.exprs[static_cast<std::size_t>(bc::imm_of(o[1]))];
  bool overflow = false;
  int sp = 0;
  if (e.float_mode) {
    std::array<float, kMaxExprStack> st{};
    for (const auto& step : e.steps) {
      if (step.code == ExprCode::Push) {
        st[static_cast<std::size_t>(sp++)] = rd_flt(step.operand);
        continue;
      }
      const bool binary = step.code >= ExprCode::Add && step.code <= ExprCode::Xor;
      const float b = binary ? st[static_cast<std::size_t>(--sp)] : 0.0f;
      float& x = st[static_cast<std::size_t>(sp - 1)];
      switch (step.code) {
        case ExprCode::Neg: x = -x; break;
        case ExprCode::Add: x = x + b; break;
        case ExprCode::Sub: x = x - b; break;
        case ExprCode::Mul: x = x * b; break;
        case ExprCode::Div: x = x / b; break;
        case ExprCode::Pow: x = std::pow(x, b); break;
        // Bitwise operations and TOD/FRD are refused in float mode by check; the rest are functions.
        default: x = float_function(step.code, x); break;
      }
      if (!std::isfinite(x)) overflow = true;
    }
    const double stored = st_flt(o[0], st[0], overflow);
    set_flags(false, overflow, stored == 0.0, std::signbit(stored) && stored != 0.0);
    return;
  }
  std::array<std::int64_t, kMaxExprStack> st{};
  // Intermediates are kept within 32 bits, so nothing below can overflow the 64-bit arithmetic.
  auto clamp32 = [&](std::int64_t v) {
    if (v > INT32_MAX || v < INT32_MIN) {
      overflow = true;
      return v > 0 ? std::int64_t{INT32_MAX} : std::int64_t{INT32_MIN};
    }
    return v;
  };
  for (const auto& step : e.steps) {
    if (step.code == ExprCode::Push) {
      st[static_cast<std::size_t>(sp++)] = rd_int(step.operand);
      continue;
    }
    const bool binary = step.code >= ExprCode::Add && step.code <= ExprCode::Xor;
    const std::int64_t b = binary ? st[static_cast<std::size_t>(--sp)] : 0;
    std::int64_t& x = st[static_cast<std::size_t>(sp - 1)];
    switch (step.code) {
      case ExprCode::Neg: x = -x; break;
      case ExprCode::Not: x = ~x; break;
      case ExprCode::Add: x = x + b; break;
      case ExprCode::Sub: x = x - b; break;
      case ExprCode::Mul: x = x * b; break;
      case ExprCode::Div: {
        if (b == 0) {
          overflow = true;
          x = INT16_MAX;
          break;
        }
        x = rounded_quotient(x, b);
        break;
      }
      case ExprCode::And: x = x & b; break;
      case ExprCode::Or: x = x | b; break;
      case ExprCode::Xor: x = x ^ b; break;
      case ExprCode::Sqr: x = std::llround(std::sqrt(static_cast<double>(x < 0 ? -x : x))); break;
      case ExprCode::Abs: x = x < 0 ? -x : x; break;
      case ExprCode::Tod: {
        const std::uint32_t bcd = to_bcd(static_cast<std::uint32_t>(std::min<std::int64_t>(x < 0 ? -x : x, 99999)));
        overflow = overflow || bcd > 0x9999;
        x = static_cast<std::int16_t>(bcd & 0xFFFF);
        break;
      }
      case ExprCode::Frd: {
        std::uint32_t v = 0;
        if (!from_bcd(static_cast<std::uint16_t>(x), v)) overflow = true;
        x = v;
        break;
      }
      default: break;  // float-only functions force float mode at compile time
    }
    x = clamp32(x);
  }
  const std::int64_t stored = st_int(o[0], st[0], overflow);
  set_flags(false, overflow, stored == 0, stored < 0);
}

void Interpreter::move(Op op, const std::uint32_t* o, std::uint32_t h) {
  if (op == Op::MVM) {
    const std::uint16_t mask = rd_word(o[1]);
    const auto r = static_cast<std::uint16_t>((rd_word(o[0]) & mask) | (rd_word(o[2]) & ~mask));
    wr_word(o[2], r);
    set_flags(false, false, r == 0, (r & 0x8000) != 0);
    return;
  }
  bool overflow = false;
  if (bc::flags_of(h) & bc::kFlagFloat) {
    const double stored = st_flt(o[1], rd_flt(o[0]), overflow);
    set_flags(false, overflow, stored == 0.0, stored < 0.0);
    return;
  }
  // An integer MOV that does not fit (L into N) saturates and sets V, like float-to-integer
  // conversion; S:2/14 governs only ADD/SUB/MUL/DIV (PT1 20-5).
  const std::int64_t v = rd_int(o[0]);
  const ValueType vt = dest_type(o[1]);
  const std::int64_t hi = vt == ValueType::Int32 ? INT32_MAX : INT16_MAX;
  const std::int64_t lo = vt == ValueType::Int32 ? INT32_MIN : INT16_MIN;
  const std::int64_t c = vt == ValueType::Float32 ? v : word_ops::saturate(v, lo, hi, overflow);
  const std::int64_t stored = st_bits(o[1], c);
  set_flags(false, overflow, stored == 0, stored < 0);
}

// ---- File instructions -----------------------------------------------------------------------------------------

void Interpreter::copy_file(const std::uint32_t* o, std::uint32_t h) {
  if (bc::flags_of(h) & bc::kFlagB) {
    // Both spans were resolved by the compiler and lie inside their files (bytecode.h, COP).
    // The fused rungs (vm/fused.cpp) run the same copy.
    const std::uint32_t words = bc::aux_of(h);
    word_ops::copy_direct(w_, bc::payload_of(o[0]), bc::payload_of(o[1]), words, s24_, bc::imm_of(o[2]));
    charge_words(Op::COP, words);
    return;
  }
  const auto len = static_cast<std::uint32_t>(std::max(bc::imm_of(o[2]), 1));
  Span dst;
  if (!file_span(o[1], len, dst, "COP destination")) return;
  // COP moves raw words, counted in destination elements (RM E-11).
  Span src;
  const std::uint32_t src_wpe = [&] {
    Span probe;
    if (!file_span(o[0], 1, probe, "COP source")) return 1u;
    return probe.wpe;
  }();
  if (faulted_) return;
  if (!file_span(o[0], (dst.count + src_wpe - 1) / src_wpe, src, "COP source")) return;
  if (!src.mfile && !dst.mfile) {
    std::memmove(w_ + dst.base, w_ + src.base, dst.count * sizeof(std::uint16_t));
  } else if (!dst.mfile) {
    // An M file into the data table (a status block copied every scan, issue 20): read in blocks,
    // one call into the module instead of one per word, with the word-by-word loop's results: the
    // words before a refused one copied, span_get's fault, then the refused word set to what the
    // module left in a zeroed word (span_get's v).
    charge_m(src.row, static_cast<int>(dst.count));
    constexpr std::uint32_t kChunk = 128;
    std::array<std::uint16_t, kChunk> got;
    for (std::uint32_t i = 0; i < dst.count;) {
      const std::uint32_t n = std::min(kChunk, dst.count - i);
      std::fill_n(got.begin(), n, std::uint16_t{0});
      std::size_t done = 0;
      const MAccess a = chassis_.read_m_block(src.slot, src.which, static_cast<int>(src.base + i),
                                              std::span<std::uint16_t>(got.data(), n), done);
      std::copy_n(got.begin(), done, w_ + dst.base + i);
      if (a != MAccess::Ok) {
        const auto bad = i + static_cast<std::uint32_t>(done);
        m_read_refused(src, bad, a);
        w_[dst.base + bad] = got[done];
        break;
      }
      i += n;
    }
  } else {
    if (src.mfile) charge_m(src.row, static_cast<int>(dst.count));
    if (dst.mfile) charge_m(dst.row, static_cast<int>(dst.count));
    for (std::uint32_t i = 0; i < dst.count && !faulted_; ++i) span_set(dst, i, span_get(src, i));
  }
  charge_words(Op::COP, dst.count);
  // File instructions use the index register; it holds the last offset they used [U].
  w_[s24_] = static_cast<std::uint16_t>(len - 1);
}

// CPW (MicroLogix 1100-1500): `length` raw words, counted in words whatever the element size of
// either file, so a long word can be split into two integers and back. The words of an L or F
// element are taken in the data table's order, low 16 bits first (docs/semantics.md,
// "MicroLogix"). Both ranges must lie inside their files (a fault otherwise, as COP).
void Interpreter::copy_words(const std::uint32_t* o) {
  const auto len = static_cast<std::uint32_t>(std::max(bc::imm_of(o[2]), 1));
  Span probe_src, probe_dst, src, dst;
  if (!file_span(o[0], 1, probe_src, "CPW source") || !file_span(o[1], 1, probe_dst, "CPW destination")) return;
  if (!file_span(o[0], (len + probe_src.wpe - 1) / probe_src.wpe, src, "CPW source") ||
      !file_span(o[1], (len + probe_dst.wpe - 1) / probe_dst.wpe, dst, "CPW destination"))
    return;
  std::memmove(w_ + dst.base, w_ + src.base, len * sizeof(std::uint16_t));
  charge_words(Op::CPW, len);
}

// SWP (RM001 4-28): swap the two bytes of `length` consecutive words. The run stays inside the
// source's file and, in a string file, inside one element's 41 data words (the manual: "cannot
// cross a string element boundary"); `check` proves that for a direct address, so only an indexed
// or indirect one can fault here, with the index fault a COP past its file gets.
void Interpreter::swap_bytes(const std::uint32_t* o) {
  const auto len = static_cast<std::uint32_t>(std::max(bc::imm_of(o[1]), 1));
  Span s;
  if (!file_span(o[0], 0, s, "SWP source")) return;
  const int file = s.mfile ? -1 : prog_.layout->file_containing(s.base);
  if (file < 0) return raise(fault::kIndexOutOfRange, "SWP source is not in a data file");
  const FileLayout& f = prog_.layout->files[static_cast<std::size_t>(file)];
  const std::uint32_t in_element = (s.base - f.base) % f.words_per_element;
  const bool string_file = f.type == FileType::String;
  if (s.base + len > f.end() || (string_file && (in_element == 0 || in_element + len > f.words_per_element))) {
    raise(fault::kIndexOutOfRange, "SWP of " + std::to_string(len) + " word(s) from " + prog_.layout->describe(s.base) +
                                       (string_file ? " leaves the data words of its string element"
                                                    : " runs past the end of its file"));
    return;
  }
  for (std::uint32_t i = 0; i < len; ++i) {
    const std::uint16_t v = w_[s.base + i];
    w_[s.base + i] = static_cast<std::uint16_t>((v << 8) | (v >> 8));
  }
  charge_words(Op::SWP, len);
}

// RHC and TDF (RM001G 7-15 .. 7-17). The free-running clock is 20 bits of 10 us ticks since
// power-up, which here is virtual time since the controller started, so a program timing an event
// with it gets the same answer on every run. An N word holds the clock's low 16 bits (655.35 ms);
// an F word the whole count (10.48575 s): TDF takes the difference modulo the width the operands
// hold, so one wrap between the two stamps is harmless, as on the processor. A float stamp that
// is not a whole count 0-000FFFFFh cannot have come from RHC: V and S:5/0, destination unchanged
// (docs/semantics.md, decision).
void Interpreter::free_running_clock(Op op, const std::uint32_t* o, Nanoseconds now_in_scan) {
  constexpr std::int64_t kTicks = std::int64_t{1} << 20;  // the clock wraps from 000FFFFFh to 0
  constexpr Nanoseconds kTick = 10'000;                    // 10 us
  const std::uint32_t dest = op == Op::RHC ? o[0] : o[2];
  const bool to_float = dest_type(dest) == ValueType::Float32;
  std::int64_t ticks = 0;
  if (op == Op::RHC) {
    ticks = static_cast<std::int64_t>((scan_start_ + now_in_scan) / kTick) % kTicks;
  } else if (to_float) {
    const double start = rd_flt(o[0]), stop = rd_flt(o[1]);
    auto stamp = [&](double v) { return std::isfinite(v) && v >= 0 && v < kTicks && v == std::floor(v); };
    if (!stamp(start) || !stamp(stop)) return set_flags(false, true, false, false);
    ticks = ((static_cast<std::int64_t>(stop) - static_cast<std::int64_t>(start)) % kTicks + kTicks) % kTicks;
  } else {
    ticks = static_cast<std::uint16_t>(rd_word(o[1]) - rd_word(o[0]));
  }
  if (to_float) {
    bool overflow = false;  // a 20-bit count is exact in a float
    st_flt(dest, static_cast<float>(ticks), overflow);
  } else {
    st_bits(dest, static_cast<std::int16_t>(static_cast<std::uint16_t>(ticks & 0xFFFF)));
  }
}

// MSG (RM 12-5 .. 12-30; docs/semantics.md "MSG"). The control block is the instruction's state: this
// handler does the rung logic on word 0 and hands the message layer only a start (the rung is true and
// EN is 0: a false-to-true transition, or EN cleared by the program after DN or ER) and an abort (TO
// set while the message is in progress, RM 12-30). EN "remains set until message transmission is
// completed and the rung goes false" (RM 12-29).
//
// The MicroLogix 1000 runs the 7-word form with its own rules (1761-6.3 p. 13-6, 13-8; docs/semantics.md
// "The MicroLogix 1000 MSG"): TO "has no effect unless the ST bit has first been set due to receiving an
// ACK", and EW "is reset when an ACK or NAK ... is received, or on any true-to-false MSG rung transition".
void Interpreter::message(Op op, const std::uint32_t* o, bool rung, Nanoseconds now_in_scan) {
  const bool slc502 = op == Op::MSG_502;
  const bool ml1000 = slc502 && prog_.processor.micrologix == MicroLogixModel::ML1000;
  const std::uint32_t block = bc::payload_of(o[slc502 ? 2 : 3]);
  const std::uint16_t w0 = w_[block];
  const bool done = (w0 & (msg::kDN | msg::kER)) != 0;
  if (ml1000 && !rung && (w0 & msg::kEW)) w_[block] = static_cast<std::uint16_t>(w_[block] & ~msg::kEW);
  if (rung && !(w0 & msg::kEN)) {
    MessageInstruction m;
    m.slc502 = slc502;
    m.ml1000 = ml1000;
    m.write = bc::imm_of(o[0]) == 1;
    m.device = bc::imm_of(o[1]);
    m.channel = slc502 ? 0 : bc::imm_of(o[5]);
    m.block = block;
    m.data = bc::payload_of(o[slc502 ? 4 : 6]);
    m.at = scan_start_ + now_in_scan;
    charge_transition(op, m.write ? 1 : 0, message_words(m.data, w_[block + 2]));
    chassis_.message_start(m);
  } else if ((w0 & msg::kTO) && (w0 & msg::kEN) && !done && (!ml1000 || (w0 & msg::kST))) {
    chassis_.message_abort(block);
  } else if (!rung && (w0 & msg::kEN) && done) {
    w_[block] = static_cast<std::uint16_t>(w_[block] & ~msg::kEN);
  }
}

// How many words `elements` elements of the file holding `data` take: the words a MSG moves (0 outside
// every file, a message the network ends with 04h).
std::uint32_t Interpreter::message_words(std::uint32_t data, std::uint16_t elements) const {
  const int file = prog_.layout->file_containing(data);
  if (file < 0) return 0;
  return static_cast<std::uint32_t>(static_cast<std::int16_t>(elements) > 0 ? static_cast<std::int16_t>(elements) : 0) *
         prog_.layout->files[static_cast<std::size_t>(file)].words_per_element;
}

// The MicroLogix MSG (1762-RM001C pp. 21-3, 21-15; docs/semantics.md "The MicroLogix MSG"): the same rung
// logic on the MG element, whose control bits EN and TO are in word 16 and whose status bits DN and ER
// are in word 17. The setup (node, target, timeout) is read from the element when the message starts.
void Interpreter::micrologix_message(const std::uint32_t* o, bool rung, Nanoseconds now_in_scan) {
  const std::uint32_t element = bc::payload_of(o[0]);
  const std::uint16_t control = w_[element + mg::kControl];
  const bool enabled = (control & msg::kEN) != 0;
  const bool done = (w_[element + mg::kStatus] & (msg::kDN | msg::kER)) != 0;
  if (rung && !enabled) {
    MessageInstruction m;
    m.micrologix = true;
    m.device = bc::imm_of(o[2]);
    // Target device MODBUS: the command operand holds the Modbus command (01-06, 15, 16), not READ/WRITE.
    if (m.device == kModbusDeviceCode) m.modbus_function = bc::imm_of(o[1]);
    m.write = m.modbus_function != 0 ? modbus::is_write_command(m.modbus_function) : bc::imm_of(o[1]) == 1;
    m.channel = bc::imm_of(o[4]);
    m.block = element;
    m.data = bc::payload_of(o[5]);
    m.elements = bc::imm_of(o[6]);
    m.at = scan_start_ + now_in_scan;
    // The false-to-true figures of 1762-RM001C Table 21.1 / 1766-RM001A p. 398 ("264 us + 1.6 us per word").
    const int counted = modbus::is_bit_command(m.modbus_function) ? (m.elements + 15) / 16 : m.elements;
    charge_transition(Op::MSG_ML, m.write ? 1 : 0, message_words(m.data, static_cast<std::uint16_t>(counted)));
    chassis_.message_start(m);
  } else if ((control & msg::kTO) && enabled && !done) {
    chassis_.message_abort(element);
  } else if (!rung && enabled && done) {
    w_[element + mg::kControl] = static_cast<std::uint16_t>(control & ~msg::kEN);
  }
}

void Interpreter::fill_file(const std::uint32_t* o, std::uint32_t h) {
  const auto len = static_cast<std::uint32_t>(std::max(bc::imm_of(o[2]), 1));
  Span dst;
  if (!file_span(o[1], len, dst, "FLL destination")) return;
  charge_words(Op::FLL, dst.count);
  if (dst.mfile) charge_m(dst.row, static_cast<int>(dst.count));
  if (dst.vtype == ValueType::Float32) {
    const float v = rd_flt(o[0]);
    for (std::uint32_t e = 0; e < len; ++e) table_.set_f32(dst.base + e * 2, v);
  } else {
    // The source converts to the destination type (rounding, saturating); flags are untouched.
    bool ignored = false;
    const std::int64_t v = (bc::flags_of(h) & bc::kFlagFloat)
                               ? numeric::float_to_integer(rd_flt(o[0]), dst.vtype, ignored)
                               : std::clamp<std::int64_t>(rd_int(o[0]), dst.vtype == ValueType::Int32 ? INT32_MIN : INT16_MIN,
                                                          dst.vtype == ValueType::Int32 ? INT32_MAX : INT16_MAX);
    if (dst.vtype == ValueType::Int32) {
      for (std::uint32_t e = 0; e < len; ++e) table_.set_i32(dst.base + e * 2, static_cast<std::int32_t>(v));
    } else {
      for (std::uint32_t i = 0; i < dst.count && !faulted_; ++i) span_set(dst, i, static_cast<std::uint16_t>(v));
    }
  }
  w_[s24_] = static_cast<std::uint16_t>(len - 1);
}

void Interpreter::bit_shift(Op op, const std::uint32_t* o, bool rung) {
  std::uint16_t* r = element(o[1]);
  if (faulted_) return;
  if (!rung) {
    r[0] &= static_cast<std::uint16_t>(~(bits::kEN | bits::kDN));
    return;
  }
  if (r[0] & bits::kEN) return;  // shifts only on a false-to-true transition
  r[0] |= bits::kEN;
  const int len = static_cast<std::int16_t>(r[1]);
  if (len <= 0) {
    // A zero or negative length is an instruction error: ER is set and nothing shifts [U].
    r[0] |= bits::kER;
    return;
  }
  const auto words = static_cast<std::uint32_t>((len + 15) / 16);
  Span f;
  if (!file_span(o[0], words, f, mnemonic(op))) return;
  const bool in = rd_bit(o[2]);
  charge_words(op, words);
  const auto get = [&](int i) { return (w_[f.base + static_cast<std::uint32_t>(i / 16)] >> (i % 16)) & 1u; };
  const auto put = [&](int i, bool v) {
    std::uint16_t& w = w_[f.base + static_cast<std::uint32_t>(i / 16)];
    const auto m = static_cast<std::uint16_t>(1u << (i % 16));
    w = static_cast<std::uint16_t>(v ? (w | m) : (w & ~m));
  };
  bool out;
  if (op == Op::BSL) {
    // Bits move up one position; the source enters at bit 0; the top bit goes to UL.
    out = get(len - 1);
    for (int i = len - 1; i > 0; --i) put(i, get(i - 1));
    put(0, in);
  } else {
    out = get(0);
    for (int i = 0; i < len - 1; ++i) put(i, get(i + 1));
    put(len - 1, in);
  }
  r[0] = static_cast<std::uint16_t>((out ? (r[0] | bits::kUL) : (r[0] & ~bits::kUL)) | bits::kDN);
  r[0] &= static_cast<std::uint16_t>(~bits::kER);
  w_[s24_] = static_cast<std::uint16_t>(words - 1);
}

void Interpreter::sequencer(Op op, const std::uint32_t* o, bool rung) {
  // Operand positions: SQO/SQC file, mask, dest/source, control; SQL file, source, control.
  const std::uint32_t control = op == Op::SQL ? o[2] : o[3];
  std::uint16_t* r = element(control);
  if (faulted_) return;
  if (!rung) {
    r[0] &= static_cast<std::uint16_t>(~bits::kEN);
    return;
  }
  if (r[0] & bits::kEN) return;  // steps only on a false-to-true transition
  r[0] |= bits::kEN;
  const int len = static_cast<std::int16_t>(r[1]);
  int pos = static_cast<std::int16_t>(r[2]);
  if (len <= 0 || pos < 0 || pos > len) {
    // PT1 24-8: ER "results in a major error if not cleared before the END or TND instruction is
    // executed. Use an OTU with address S:5/2 to avoid a CPU fault": ER comes with the minor
    // error bit S:5/2, which the end of the program scan checks like S:5/0.
    r[0] |= bits::kER;
    w_[s5_] |= status::kControlRegisterError;
    return;
  }
  Span f;
  if (!file_span(o[0], static_cast<std::uint32_t>(len) + 1, f, mnemonic(op))) return;
  r[0] &= static_cast<std::uint16_t>(~bits::kER);
  // Step to the next position; after the last step the sequencer wraps to step 1 (step 0 is
  // the start-up position).
  pos = pos + 1 > len ? 1 : pos + 1;
  const std::uint16_t step = w_[f.base + static_cast<std::uint32_t>(pos)];
  switch (op) {
    case Op::SQO: {
      const std::uint16_t mask = rd_word(o[1]);
      wr_word(o[2], static_cast<std::uint16_t>((rd_word(o[2]) & ~mask) | (step & mask)));
      break;
    }
    case Op::SQC: {
      const std::uint16_t mask = rd_word(o[1]);
      const bool found = (rd_word(o[2]) & mask) == (step & mask);
      r[0] = static_cast<std::uint16_t>(found ? (r[0] | bits::kFD) : (r[0] & ~bits::kFD));
      break;
    }
    case Op::SQL: w_[f.base + static_cast<std::uint32_t>(pos)] = rd_word(o[1]); break;
    default: break;
  }
  r[2] = static_cast<std::uint16_t>(pos);
  r[0] = static_cast<std::uint16_t>(pos == len ? (r[0] | bits::kDN) : (r[0] & ~bits::kDN));
  w_[s24_] = static_cast<std::uint16_t>(pos);
}

void Interpreter::stack(Op op, const std::uint32_t* o, bool rung) {
  // FFL/LFL: source, stack, control; FFU/LFU: stack, dest, control. Loads use EN, unloads EU.
  const bool load = op == Op::FFL || op == Op::LFL;
  const std::uint16_t edge = load ? bits::kEN : bits::kEU;
  std::uint16_t* r = element(o[2]);
  if (faulted_) return;
  if (!rung) {
    r[0] &= static_cast<std::uint16_t>(~edge);
    return;
  }
  if (r[0] & edge) return;
  r[0] |= edge;
  const int len = static_cast<std::int16_t>(r[1]);
  int pos = static_cast<std::int16_t>(r[2]);
  if (len <= 0 || pos < 0 || pos > len) {
    r[0] |= bits::kER;
    return;
  }
  Span f;
  if (!file_span(load ? o[1] : o[0], static_cast<std::uint32_t>(len), f, mnemonic(op))) return;
  r[0] &= static_cast<std::uint16_t>(~bits::kER);
  std::uint16_t* s = w_ + f.base;
  const int entry_pos = pos;
  if (load) {
    if (pos < len) s[pos++] = rd_word(o[0]);  // a full stack ignores the load (DN stays set)
  } else if (pos > 0) {
    if (op == Op::FFU) {
      // FIFO: the first word comes out; the rest move down one; a zero enters at the top.
      charge_words(op, static_cast<std::uint32_t>(len));
      wr_word(o[1], s[0]);
      std::memmove(s, s + 1, static_cast<std::size_t>(len - 1) * sizeof(std::uint16_t));
      s[len - 1] = 0;
    } else {
      // LIFO: the last word loaded comes out and its place is cleared.
      --pos;
      wr_word(o[1], s[pos]);
      s[pos] = 0;
    }
    if (op == Op::FFU) --pos;
  }
  r[2] = static_cast<std::uint16_t>(pos);
  r[0] = static_cast<std::uint16_t>(pos >= len ? (r[0] | bits::kDN) : (r[0] & ~bits::kDN));
  r[0] = static_cast<std::uint16_t>(pos == 0 ? (r[0] | bits::kEM) : (r[0] & ~bits::kEM));
  // PT1 23-7 and 23-9: "For the FFL [LFL], the position value determined at instruction entry is
  // placed in S:24. For the FFU [LFU], the position value determined at instruction exit".
  w_[s24_] = static_cast<std::uint16_t>(load ? entry_pos : pos);
}

// ---- FBC and DDT (issue 15) ---------------------------------------------------------------------
// 1747-RM001G p. 7-18 .. 7-22 (7-19 and 7-20 not reached: docs/semantics.md "FBC and DDT" marks what
// rests on them). Operands: source, reference, result files; compare control (LEN bits, POS the next
// bit); its box length/position; result control (LEN words, POS the next word); its length/position.
// Bit k of a file is bit k % 16 of its word k / 16, counted from the file address.
void Interpreter::bit_compare(Op op, const std::uint32_t* o, bool rung) {
  std::uint16_t* cmp = element(o[3]);
  if (faulted_) return;
  std::uint16_t* res = element(o[6]);
  if (faulted_) return;
  if (!rung) {
    // RM 7-21: "The instruction control bits are reset when the rung's input conditions go false";
    // RM 7-18: the found bit resets when the rung goes false. ER stays for the ladder to reset, IN
    // is the mode the ladder chose, and the result DN waits for the next false-to-true transition.
    cmp[0] &= static_cast<std::uint16_t>(~(bits::kEN | bits::kDN | bits::kFD));
    return;
  }
  if (cmp[0] & bits::kEN) return;  // works on a false-to-true transition only
  cmp[0] |= bits::kEN;
  if (cmp[0] & bits::kER) return;  // table 7.8: stopped until the ladder resets ER
  int len = static_cast<std::int16_t>(cmp[1]);
  int pos = static_cast<std::int16_t>(cmp[2]);
  const int rlen = static_cast<std::int16_t>(res[1]);
  int rpos = static_cast<std::int16_t>(res[2]);
  // Table 7.8: an error when a length is <= 0 or a position < 0; a position past its length is
  // one too (softslc's reading, docs/semantics.md).
  if (len <= 0 || pos < 0 || pos > len || rlen <= 0 || rpos < 0 || rpos > rlen) {
    cmp[0] |= bits::kER;
    return;
  }
  // RM 7-21: on a false-to-true transition the control elements reset when the compare position
  // equals the compare length (both positions cleared) and when the result position equals the
  // result length (result position cleared; its DN reset and the search continues).
  if (pos == len) {
    pos = 0;
    rpos = 0;
    cmp[0] &= static_cast<std::uint16_t>(~bits::kDN);
  }
  if (rpos == rlen) {
    rpos = 0;
    res[0] &= static_cast<std::uint16_t>(~bits::kDN);
  }
  cmp[0] &= static_cast<std::uint16_t>(~bits::kFD);
  const auto words = static_cast<std::uint32_t>((len + 15) / 16);
  Span src, ref, out;
  if (!file_span(o[0], words, src, mnemonic(op)) || !file_span(o[1], words, ref, mnemonic(op)) ||
      !file_span(o[2], static_cast<std::uint32_t>(rlen), out, mnemonic(op)))
    return;
  const bool one_at_a_time = (cmp[0] & bits::kIN) != 0;
  const int stop = one_at_a_time ? pos + 1 : len;
  bool found = false;
  for (; pos < stop; ++pos) {
    const std::uint32_t wi = static_cast<std::uint32_t>(pos) / 16;
    const auto mask = static_cast<std::uint16_t>(1u << (pos % 16));
    const std::uint16_t s_bit = w_[src.base + wi] & mask;
    std::uint16_t& r_word = w_[ref.base + wi];
    if (s_bit == (r_word & mask)) continue;
    w_[out.base + static_cast<std::uint32_t>(rpos++)] = static_cast<std::uint16_t>(pos);
    found = true;
    // RM 7-18: DDT also makes the reference bit match the source bit.
    if (op == Op::DDT) r_word = static_cast<std::uint16_t>((r_word & ~mask) | s_bit);
    if (rpos == rlen) {
      // RM 7-21: the result file is full: result DN, and the instruction stops after this bit
      // until the next false-to-true transition, which wraps the result position to 0.
      res[0] |= bits::kDN;
      ++pos;
      break;
    }
  }
  charge_words(op, words);
  // Table 7.8: FD each time a mismatch is recorded (one at a time) or after recording all of them
  // (all per scan); DN when the end of the files is reached.
  if (found) cmp[0] |= bits::kFD;
  if (pos >= len) cmp[0] |= bits::kDN;
  cmp[2] = static_cast<std::uint16_t>(pos);
  res[2] = static_cast<std::uint16_t>(rpos);
}

// ---- The dispatch loop -----------------------------------------------------------------------------------------

// Hot: run at every scan (vm/runtime.cpp, "The scan cycle", says why it is marked).
[[gnu::hot]] ProgramScanResult Interpreter::program_scan(VirtualTime scan_start, Nanoseconds elapsed, bool first_pass,
                                            Nanoseconds watchdog) {
  first_pass_ = first_pass;
  begin_pass(scan_start, watchdog);
  watchdog_span_ = watchdog;
  watchdog_from_ = 0;
  bool ok = true;
  // Entering Run: the STI starts timing now (RM 11-12); an invalid S:30/S:31 faults at once.
  if (first_pass && !configure_sti(scan_start + elapsed, true)) ok = false;
  // the DII's S:46-S:50 too (RM 11-24).
  if (ok && first_pass && !configure_dii(true)) ok = false;
  if (first_pass) scan_toggle(prog_, w_, true);
  if (first_pass) pulse_trains_.enter_run(w_);  // every PTO idle on entering Run [U]
  // The MicroLogix EII and HSC interrupts: nothing waits on entering Run; the counters were brought
  // up to this scan's start (Runtime::program_scan), so a preset reached since runs at the first rung.
  if (first_pass) reset_event_interrupts(true);
  collect_counter_events();
  update_limit(elapsed);
  if (ok) ok = run_routine(2, elapsed, max_depth_);
  if (ok) scan_toggle(prog_, w_, false);  // END or TND
  if (ok) {
    // PT1 20-2: the overflow trap still set at END or TND is major fault 0020h.
    if (w_[s5_] & status::kOverflowTrap)
      raise(fault::kMinorErrorAtEnd, "math overflow trap S:5/0 still set at the end of the program scan");
    // PT1 24-8: a sequencer error (ER, with S:5/2) not cleared before END or TND is a major error.
    else if (w_[s5_] & status::kControlRegisterError)
      raise(fault::kMinorErrorAtEnd,
            "control register error S:5/2 (a sequencer's ER) still set at the end of the program scan");
    if (faulted_) {
      fault_.file = last_file_;
      fault_.rung = last_rung_;
      fault_located_ = true;
      // RM 11-2: a recoverable fault at the end of the scan can be cleared by the fault routine.
      ok = user_fault_routine(elapsed);
    }
  }
  ProgramScanResult res = pass_result(ok, elapsed);
  res.watchdog_from = watchdog_from_;
  return res;
}

void Interpreter::begin_pass(VirtualTime scan_start, Nanoseconds watchdog) {
  scan_start_ = scan_start;
  clear_fault();
  fault_located_ = false;
  suspended_ = false;
  extra_ns_ = 0;
  count_ = 0;
  w_ = table_.words();
  watchdog_ = watchdog;
  interrupt_level_ = 0;
  priority_ = 0;
  in_fault_routine_ = false;
}

ProgramScanResult Interpreter::pass_result(bool ok, Nanoseconds elapsed) const {
  ProgramScanResult res;
  res.elapsed = elapsed;
  res.instructions = count_;
  res.last_file = last_file_;
  res.last_rung = last_rung_;
  if (suspended_) {
    res.suspended = true;
  } else if (!ok) {
    res.faulted = true;
    res.fault = fault_;
  }
  return res;
}

namespace {

// The ops run_routine's bit-logic fast path executes (direct-bit XIC/XIO/OTE and the branch
// structure); every other op goes straight to the general switch. Indexed by the op byte.
// With coverage every op takes the general switch (kNoFastPathOp).
constexpr std::array<bool, 256> kFastPathOp = [] {
  std::array<bool, 256> a{};
  for (Op op : {Op::XIC, Op::XIO, Op::OTE, Op::BST, Op::NXB, Op::BND}) a[static_cast<std::size_t>(op)] = true;
  return a;
}();
constexpr std::array<bool, 256> kNoFastPathOp{};

}  // namespace

[[gnu::hot]] bool Interpreter::run_routine(int file, Nanoseconds& elapsed, int max_depth) {
  struct BranchFrame {
    bool entry;  // the rung condition at BST: every leg starts from it
    bool acc;    // OR of the legs finished so far
  };
  struct CallFrame {
    const std::uint32_t* ret;
    int file;
    int rung;
    bool mcr_off;
    int bsp;
    int bsp_base;
  };
  std::array<BranchFrame, std::size_t{kMaxBranchDepth} * (kMaxCallDepth + 1)> bstack;
  std::array<CallFrame, kMaxCallDepth> frames;
  int bsp = 0;
  int bsp_base = 0;
  int fsp = 0;
  int cur_rung = -1;
  bool mcr_off = false;  // inside an MCR zone whose MCR rung was false
  bool rung = true;
  // The instruction count and the cost table are reached through `this` in the general switch,
  // which leaves the compiler registers for the program counter and the scan time.
  int cur_file = file;
  const std::uint32_t* pc = code_ + prog_.file(file)->begin;
  const bool* const fast_op = coverage_ ? kNoFastPathOp.data() : kFastPathOp.data();
  const std::uint32_t* general_sor = nullptr;  // a SOR fused rungs handed back (FusedProgram::kRunsGeneral)
  const std::uint32_t* call_ret = nullptr;     // call_subroutine: where the taken JSR at pc returns
  FusedCalls fused_calls;                      // the calls a fused run takes itself (vm/fused.h, "Calls")
  static_assert(FusedCalls::kCapacity >= kMaxCallDepth);

  for (;;) {
  resume:
    // The bit-logic fast path: the ops a ladder program is mostly made of, in a tight loop with
    // only pc, the rung condition, the scan time and the branch stack live, so they stay in
    // registers. Everything else leaves it for the general switch below. (Measured with
    // tests/benchmarks/vm_bench: the single big switch kept `rung` in memory.)
    {
      unsigned r = rung;
      Nanoseconds t = elapsed;
      std::uint64_t n = 0;
      std::uint16_t* const w = w_;
      const Nanoseconds* const cost = cost_.data();
      // Coverage observes every instruction in the general switch (one test per fast-path entry).
      if (coverage_) [[unlikely]] goto general;
      for (;;) {
        // The operand word is read only by the ops that have one: a 0-operand op may be the last
        // word of the code array.
        std::uint32_t fo;
        switch (bc::op_of(*pc)) {
          case Op::XIC:
            fo = pc[1];
            if (bc::mode_of(fo) != bc::kBit) goto general;
            t += cost[(static_cast<unsigned>(Op::XIC) << 1) | r];
            r &= (w[bc::word_of_bit(fo)] >> bc::bit_of(fo)) & 1u;
            ++n;
            pc += 2;
            continue;
          case Op::XIO:
            fo = pc[1];
            if (bc::mode_of(fo) != bc::kBit) goto general;
            t += cost[(static_cast<unsigned>(Op::XIO) << 1) | r];
            r &= ~(w[bc::word_of_bit(fo)] >> bc::bit_of(fo)) & 1u;
            ++n;
            pc += 2;
            continue;
          case Op::OTE: {
            fo = pc[1];
            if (bc::mode_of(fo) != bc::kBit) goto general;
            t += cost[(static_cast<unsigned>(Op::OTE) << 1) | r];
            std::uint16_t& word = w[bc::word_of_bit(fo)];
            const auto mask = static_cast<std::uint16_t>(1u << bc::bit_of(fo));
            word = static_cast<std::uint16_t>((word & ~mask) | (-r & mask));
            ++n;
            pc += 2;
            continue;
          }
          case Op::BST:
            bstack[static_cast<std::size_t>(bsp++)] = {r != 0, false};
            pc += 1;
            continue;
          case Op::NXB: {
            BranchFrame& b = bstack[static_cast<std::size_t>(bsp - 1)];
            b.acc |= r != 0;
            r = b.entry;
            pc += 1;
            continue;
          }
          case Op::BND:
            r |= bstack[static_cast<std::size_t>(bsp - 1)].acc;
            --bsp;
            pc += 1;
            continue;
          default: goto general;
        }
      }
    general:
      rung = r != 0;
      elapsed = t;
      count_ += n;
    }
  dispatch:
    const std::uint32_t h = *pc;
    const Op op = bc::op_of(h);
    const std::uint32_t* const o = pc + 1;
    const bool rung_in = rung;
    elapsed += cost_[(static_cast<unsigned>(op) << 1) | static_cast<unsigned>(rung)];
    count_ += countable_[static_cast<unsigned>(op)];
    switch (op) {
      // ---- Rung structure ----
      case Op::SOR:
        cur_rung = static_cast<int>(bc::aux_of(h));
        bsp = bsp_base;  // a JMP out of a branch leaves nothing behind
        // limit_ is the watchdog, or sooner an STI expiry: one compare per rung either way.
        if (elapsed >= limit_) [[unlikely]] {
          if (!at_limit(elapsed)) goto fault;
        }
        rung = !mcr_off || (bc::flags_of(h) & bc::kFlagA);
        // A run of fused rungs (vm/fused.h) starting here executes in one call; coverage keeps
        // the general path so it sees every instruction.
        // A rung a run handed back to the general path (it would fault) is not fused again.
        if (!mcr_off && fusion_ && !coverage_ && pc != general_sor) {
          const std::int32_t run = fused_->run_at(cur_file, bc::aux_of(h));
          if (run >= 0) {
            Nanoseconds t = elapsed;
            std::uint64_t n = 0;
            fused_calls.file = static_cast<std::uint32_t>(cur_file);
            fused_calls.room = static_cast<unsigned>(max_depth - fsp);
            fused_calls.depth = 0;
            const FusedProgram::Exit x =
                fused_->execute(run, w_, t, n, limit_, FusedScan{scan_start_, first_pass_, timer_executions_},
                                fused_calls);
            // The subroutine calls the run took and did not return from: the JSR handler's frames
            // (in a fused run the branch stack is at its base and no MCR zone is off).
            for (unsigned i = 0; i < fused_calls.depth; ++i) {
              const FusedCall& c = fused_calls.call[i];
              frames[static_cast<std::size_t>(fsp++)] = {code_ + c.ret, static_cast<int>(c.file),
                                                         static_cast<int>(c.rung), false, bsp, bsp_base};
            }
            cur_file = static_cast<int>(fused_calls.file);
            pc = code_ + (x.next & FusedProgram::kOffsetMask);
            if (x.next & FusedProgram::kRunsGeneral) general_sor = pc;
            elapsed = t;
            count_ += n;
            if (x.next & FusedProgram::kTransfer) [[unlikely]] {
              // The run's last rung took its JSR or RET (charged and counted): the handler's
              // work without the charge. A JSR returns past the rung's closing BNDs, to the next
              // SOR, which replaces their rung condition (vm/fused.h, "Transfers").
              cur_rung = static_cast<int>(x.rung);
              if (bc::op_of(*pc) == Op::RET) goto take_return;
              call_ret = pc + 1 + bc::count_of(*pc);
              while (bc::op_of(*call_ret) == Op::BND) ++call_ret;
              goto call_subroutine;
            }
            // The run ends at a SOR (or EOF): dispatched here directly, as after a handler.
            if (!fast_op[static_cast<std::size_t>(bc::op_of(*pc))]) goto dispatch;
            continue;
          }
        }
        break;
      // BST/NXB/BND (and direct-bit XIC/XIO/OTE) are normally taken by the fast path above;
      // these cases give the same result if the general switch ever sees them.
      case Op::BST: bstack[static_cast<std::size_t>(bsp++)] = {rung, false}; break;
      case Op::NXB: {
        BranchFrame& b = bstack[static_cast<std::size_t>(bsp - 1)];
        b.acc |= rung;
        rung = b.entry;
        break;
      }
      case Op::BND:
        rung |= bstack[static_cast<std::size_t>(bsp - 1)].acc;
        --bsp;
        break;
      case Op::EOF_:
        // The implicit END: RSLogix shows it as the rung after the last one.
        if (fsp == 0) {
          cur_rung = static_cast<int>(prog_.file(cur_file)->rungs.size());
          goto end_of_scan;
        }
        goto return_from_subroutine;
      case Op::END:
        if (fsp == 0) goto end_of_scan;
        goto return_from_subroutine;

      // ---- Bit ----
      // The direct-bit cases are written out branch-free: a rung condition that depends on
      // field data is unpredictable, and a mispredicted branch costs more than the whole XIC.
      case Op::XIC:
        if (bc::mode_of(o[0]) == bc::kBit) [[likely]]
          rung &= static_cast<bool>((w_[bc::word_of_bit(o[0])] >> bc::bit_of(o[0])) & 1u);
        else
          rung &= rd_bit_slow(o[0]);
        break;
      case Op::XIO:
        if (bc::mode_of(o[0]) == bc::kBit) [[likely]]
          rung &= !((w_[bc::word_of_bit(o[0])] >> bc::bit_of(o[0])) & 1u);
        else
          rung &= !rd_bit_slow(o[0]);
        break;
      case Op::OTE:
        if (bc::mode_of(o[0]) == bc::kBit) [[likely]] {
          std::uint16_t& word = w_[bc::word_of_bit(o[0])];
          const auto mask = static_cast<std::uint16_t>(1u << bc::bit_of(o[0]));
          word = static_cast<std::uint16_t>((word & ~mask) | (-static_cast<unsigned>(rung) & mask));
        } else {
          wr_bit_slow(o[0], rung);
        }
        break;
      case Op::OTL:
        if (rung) wr_bit(o[0], true);
        break;
      case Op::OTU:
        if (rung) wr_bit(o[0], false);
        break;
      case Op::OSR:
      case Op::ONS: {  // the MicroLogix 1100-1500 name of the one-operand one-shot
        const bool stored = rd_bit(o[0]);
        wr_bit(o[0], rung);
        rung = rung && !stored;
        break;
      }
      // MicroLogix two-operand one-shots (1763-RM001/1766-RM001/1762-RM001 "Using Bit Instructions").
      case Op::OSR_ML:
      case Op::OSF: {
        const bool stored = rd_bit(o[0]);
        wr_bit(o[0], rung);
        wr_bit(o[1], op == Op::OSR_ML ? (rung && !stored) : (!rung && stored));
        break;
      }

      // ---- Timers and counters ----
      case Op::TON:
      case Op::TOF:
      case Op::RTO:
        if (!timer(op, o, h, rung, elapsed)) goto fault;
        break;
      case Op::CTU:
      case Op::CTD: counter(op, o, rung); break;
      case Op::RES:
        if (rung) reset(o, h);
        break;

      // ---- Compare ----
      case Op::EQU:
      case Op::NEQ:
      case Op::LES:
      case Op::LEQ:
      case Op::GRT:
      case Op::GEQ:
      case Op::LIM:
      case Op::MEQ:
        // A false rung stays false; the comparison is still charged (false execution time).
        if (rung) rung = compare(op, o, h);
        break;

      // ---- Math and logic ----
      case Op::ADD:
      case Op::SUB:
      case Op::MUL:
      case Op::DIV:
        if (rung) math(op, o, h);
        break;
      case Op::NEG:
      case Op::CLR:
        if (rung) unary(op, o, h);
        break;
      case Op::AND:
      case Op::OR:
      case Op::XOR:
      case Op::NOT:
        if (rung) logical(op, o);
        break;

      // ---- Issue 15: math, floating point, data handling ----
      case Op::DDV:
        if (rung) double_divide(o);
        break;
      case Op::SQR:
      case Op::ABS:
      case Op::LN:
      case Op::LOG:
      case Op::XPY:
      case Op::SIN:
      case Op::COS:
      case Op::TAN:
      case Op::ASN:
      case Op::ACS:
      case Op::ATN:
      case Op::DEG:
      case Op::RAD:
        if (rung) function(op, o, h);
        break;
      case Op::SCL:
      case Op::SCP:
        if (rung) scale(op, o, h);
        break;
      case Op::TOD:
      case Op::FRD:
      case Op::DCD:
      case Op::ENC:
        if (rung) convert(op, o);
        break;
      case Op::CPT:
        if (rung) compute(o);
        break;

      // ---- Move and file ----
      case Op::MOV:
        // The commonest MOVs, a 16-bit word or an immediate that fits one into a word, inline: the
        // value always fits, so move()'s rule comes down to the copy and Z and S (C and V clear).
        // The fused word rungs run the same rule (word_ops); tests/vm/fused_test.cpp compares them.
        if (rung) {
          const std::uint32_t src = o[0];
          const bool fits = bc::mode_of(src) == bc::kWord ||
                            (bc::mode_of(src) == bc::kImm && bc::imm_of(src) >= INT16_MIN && bc::imm_of(src) <= INT16_MAX);
          if (fits && bc::mode_of(o[1]) == bc::kWord && !(bc::flags_of(h) & bc::kFlagFloat)) [[likely]] {
            const auto v = static_cast<std::uint16_t>(bc::mode_of(src) == bc::kWord ? w_[bc::payload_of(src)]
                                                                                    : bc::imm_of(src));
            w_[bc::payload_of(o[1])] = v;
            word_ops::set_arith_flags(w_, s0_, s5_, false, false, v == 0, (v & 0x8000) != 0);
          } else {
            move(op, o, h);
          }
        }
        break;
      case Op::MVM:
        if (rung) move(op, o, h);
        break;
      case Op::COP:
        if (rung) copy_file(o, h);
        if (faulted_) goto fault;
        elapsed += std::exchange(extra_ns_, 0);
        break;
      case Op::CPW:
        if (rung) copy_words(o);
        if (faulted_) goto fault;
        elapsed += std::exchange(extra_ns_, 0);
        break;
      case Op::RHC:
      case Op::TDF:
        if (rung) free_running_clock(op, o, elapsed);
        break;
      // RPC (RM001G p. 7-23, 1766-RM001A p. 239): PROC-MEM reads the checksum of the program in RAM,
      // computed once at compile time; MEM-MOD reads a memory module, which softslc has none of: 0
      // (docs/semantics.md "RPC", decision).
      case Op::RPC:
        if (rung) st_bits(o[1], static_cast<std::int16_t>(bc::imm_of(o[0]) == 0 ? prog_.program_checksum : 0));
        break;
      // ---- ASCII and strings ----
      case Op::ACI:
      case Op::AIC:
      case Op::ACN:
      case Op::AEX:
      case Op::ASC:
        if (rung) string_instruction(op, o);
        if (faulted_) goto fault;
        elapsed += std::exchange(extra_ns_, 0);
        break;
      case Op::ASR:
        if (rung) rung = string_compare(o);
        if (faulted_) goto fault;
        elapsed += std::exchange(extra_ns_, 0);
        break;
      case Op::ABL:
      case Op::ACB:
      case Op::AHL:
      case Op::ARD:
      case Op::ARL:
      case Op::AWA:
      case Op::AWT:
        channel_instruction(op, o, rung, elapsed);
        if (faulted_) goto fault;
        elapsed += std::exchange(extra_ns_, 0);
        break;
      case Op::ACL:
        if (rung) ascii_clear(o, elapsed);
        break;
      case Op::SWP:
        if (rung) swap_bytes(o);
        if (faulted_) goto fault;
        elapsed += std::exchange(extra_ns_, 0);
        break;
      case Op::FLL:
        if (rung) fill_file(o, h);
        if (faulted_) goto fault;
        elapsed += std::exchange(extra_ns_, 0);
        break;
      case Op::BSL:
      case Op::BSR:
        bit_shift(op, o, rung);
        if (faulted_) goto fault;
        elapsed += std::exchange(extra_ns_, 0);
        break;
      case Op::SQO:
      case Op::SQC:
      case Op::SQL:
        sequencer(op, o, rung);
        if (faulted_) goto fault;
        break;
      case Op::LFL:
      case Op::LFU:
      case Op::FFL:
      case Op::FFU:
        stack(op, o, rung);
        if (faulted_) goto fault;
        elapsed += std::exchange(extra_ns_, 0);
        break;

      // ---- Program control ----
      case Op::JMP:
        if (rung) {
          if (coverage_) [[unlikely]] coverage_->record(static_cast<std::uint32_t>(pc - code_), op, rung_in, rung);
          pc = code_ + bc::payload_of(o[1]);
          continue;
        }
        break;
      case Op::LBL:
      case Op::SBR:
      case Op::INT: break;
      case Op::JSR:
        if (rung) {
          call_ret = o + bc::count_of(h);
          goto call_subroutine;
        }
        break;
      case Op::RET:
        if (!rung) break;
        // Taken, RET leaves before the common coverage record below: record it here, or an
        // unconditional SOR RET EOR reads "never true".
        if (coverage_) [[unlikely]] coverage_->record(static_cast<std::uint32_t>(pc - code_), op, rung_in, rung);
        goto take_return;
      case Op::TND:
        if (rung) {
          if (coverage_) [[unlikely]] coverage_->record(static_cast<std::uint32_t>(pc - code_), op, rung_in, rung);
          goto end_of_scan;
        }
        break;
      case Op::MCR:
        // An unconditional MCR closes the zone; a conditional one opens a zone that is live
        // when its rung is true. In a false zone every rung's rung-in is false (SOR above).
        mcr_off = (bc::flags_of(h) & bc::kFlagA) ? false : !rung;
        break;

      // ---- Program control and interrupts (issue 15) ----
      case Op::SUS:
        if (rung) {
          // RM ch. 6 (SUS): the suspend ID goes to S:7 and the file holding the SUS to S:8; the
          // processor then stops in Suspend Idle (the runtime de-energises the outputs).
          w_[s7_] = static_cast<std::uint16_t>(bc::imm_of(o[0]));
          w_[s8_] = static_cast<std::uint16_t>(cur_file);
          if (coverage_) [[unlikely]] coverage_->record(static_cast<std::uint32_t>(pc - code_), op, rung_in, rung);
          suspended_ = true;
          goto fault;
        }
        break;
      case Op::REF:
        if (rung) {
          elapsed += chassis_.io_refresh(scan_start_ + elapsed);
          scan_toggle(prog_, w_, false);
          // PT1 20-2 (facts §3): the overflow trap still set at END, TND or REF is fault 0020h.
          if (w_[s5_] & status::kOverflowTrap) {
            raise(fault::kMinorErrorAtEnd, "math overflow trap S:5/0 still set at REF");
            goto fault;
          }
          // RM B-19: the scan-time count (and so the watchdog) restarts on return from REF.
          watchdog_from_ = elapsed;
          watchdog_ = elapsed + watchdog_span_;
          // RM 11-24: S:46-S:50 are applied at each end of scan (END, TND or REF).
          if (dii_supported_ && !apply_dii_config()) goto fault;
          update_limit(elapsed);
        }
        break;
      case Op::STD:
        if (rung) w_[s2_] = static_cast<std::uint16_t>(w_[s2_] & ~status::kStiEnabled);
        break;
      case Op::STE:
        if (rung) {
          w_[s2_] = static_cast<std::uint16_t>(w_[s2_] | status::kStiEnabled);
          // A pending STI runs at once: at the next rung start (docs/semantics.md).
          update_limit(elapsed);
        }
        break;
      case Op::STS:
        if (rung) sti_start(o, elapsed);
        if (faulted_) goto fault;
        break;
      case Op::STS_ML:
        if (rung) function_file_sti_start(o, elapsed);
        if (faulted_) goto fault;
        break;
      case Op::PTO:
      case Op::PTOX:
        pulse_trains_.scan(static_cast<int>(bc::imm_of(o[0])), rung, scan_start_ + elapsed, w_);
        break;
      case Op::DLG:
        data_logs_.scan(static_cast<int>(bc::imm_of(o[0])), rung, w_);
        break;
      case Op::HSL:
      case Op::RAC:
        if (rung) high_speed_counter(op, o, elapsed);
        break;

      // ---- I/O interrupts and diagnostics (issue 15) ----
      case Op::IID:
      case Op::IIE:
      case Op::RPI:
        if (rung) io_interrupt_control(op, o, elapsed);
        break;
      case Op::UID:
      case Op::UIE:
      case Op::UIF:
        // Refused by the checker on every processor (Requirement::MicroLogixUserInterrupt).
        raise(fault::kUnsupportedInstruction,
              std::string(mnemonic(op)) + " on the MicroLogix interrupt function files is not simulated");
        goto fault;
      case Op::FBC:
      case Op::DDT:
        bit_compare(op, o, rung);
        if (faulted_) goto fault;
        elapsed += std::exchange(extra_ns_, 0);
        break;

      // ---- Immediate I/O ----
      case Op::IIM:
      case Op::IOM:
        if (rung) {
          const int sw = bc::imm_of(o[0]);
          const std::uint16_t mask = rd_word(o[1]);
          if (op == Op::IIM) chassis_.immediate_input(sw / 256, sw % 256, bc::imm_of(o[2]), mask);
          else chassis_.immediate_output(sw / 256, sw % 256, bc::imm_of(o[2]), mask);
        }
        break;

      // ---- Communication (docs/semantics.md "MSG") ----
      case Op::MSG:
      case Op::MSG_502:
        message(op, o, rung, elapsed);
        elapsed += std::exchange(extra_ns_, 0);  // the false-to-true figure of a message started here
        break;
      case Op::MSG_ML:
        micrologix_message(o, rung, elapsed);
        elapsed += std::exchange(extra_ns_, 0);
        break;
      case Op::SVC:
        if (rung) chassis_.service_communications(0x3, scan_start_ + elapsed);
        break;
      case Op::SVC_CH: {
        const auto select = static_cast<std::uint16_t>(bc::imm_of(o[0]));  // 1-3 (the table's range)
        if (rung) chassis_.service_communications(select, scan_start_ + elapsed);
        elapsed += svc_select_extra_[select & 3u][rung ? 1 : 0];
        break;
      }

      // ---- Process control ----
      case Op::PID:
        if (!pid(o, rung, elapsed)) goto fault;
        break;

      // ---- Specialty-module instructions ----
      case Op::BTR:
      case Op::BTW:
      case Op::DEM:
        // The module in the slot does the work; the compiler set DYN so its M-file access time
        // is folded in and a fault it raises stops the scan below.
        module_instruction(op, o, h, rung, elapsed);
        break;
    }
    if (bc::flags_of(h) & bc::kFlagDyn) [[unlikely]] {
      if (faulted_) goto fault;
      elapsed += extra_ns_;
      extra_ns_ = 0;
    }
    if (coverage_) [[unlikely]] coverage_->record(static_cast<std::uint32_t>(pc - code_), op, rung_in, rung);
    // The program counter advances here, after the handler, so only one copy of it is live
    // across the switch (computing it before the switch made the compiler spill it).
    pc = o + bc::count_of(h);
    // An op the fast path would only hand back is dispatched here directly, and with coverage
    // every op is: entering and leaving the fast path costs more than this test
    // (docs/performance.md, "mixed").
    if (!fast_op[static_cast<std::size_t>(bc::op_of(*pc))]) goto dispatch;
    continue;

  // A taken JSR at pc (from its handler or a fused rung; charged and counted), returning to call_ret.
  call_subroutine: {
    const std::uint32_t* const jo = pc + 1;
    if (fsp >= max_depth) {
      raise(fault::kSubroutineNesting, "JSR " + std::to_string(bc::imm_of(jo[0])) + " would nest subroutines " +
                                           std::to_string(fsp + 1) + " deep; " + prog_.processor.display_name +
                                           " allows " + std::to_string(max_depth) +
                                           (interrupt_level_ ? " inside an interrupt or fault routine" : "") + " (RM 6-4)");
      goto fault;
    }
    frames[static_cast<std::size_t>(fsp++)] = {call_ret, cur_file, cur_rung, mcr_off, bsp, bsp_base};
    if (coverage_) [[unlikely]] {
      coverage_->record(static_cast<std::uint32_t>(pc - code_), Op::JSR, true, true);
      coverage_->called(bc::imm_of(jo[0]));
    }
    cur_file = bc::imm_of(jo[0]);
    pc = code_ + bc::payload_of(jo[1]);
    mcr_off = false;
    bsp_base = bsp;
    // The subroutine's first SOR: dispatched directly, as after a handler.
    if (!fast_op[static_cast<std::size_t>(bc::op_of(*pc))]) goto dispatch;
    continue;
  }
  // A taken RET (charged and counted): the end of the scan in the main file, else the return.
  take_return:
    if (fsp == 0) goto end_of_scan;
    goto return_from_subroutine;

  return_from_subroutine: {
    const CallFrame& f = frames[static_cast<std::size_t>(--fsp)];
    pc = f.ret;
    cur_file = f.file;
    cur_rung = f.rung;
    mcr_off = f.mcr_off;
    bsp = f.bsp;
    bsp_base = f.bsp_base;
    rung = true;  // the JSR's rung was true, and an output passes its rung on
    // After a fused JSR rung the return is the next SOR: dispatched directly.
    if (!fast_op[static_cast<std::size_t>(bc::op_of(*pc))]) goto dispatch;
    continue;
  }
  }

end_of_scan:
  last_file_ = cur_file;
  last_rung_ = cur_rung;
  return true;

fault:
  last_file_ = cur_file;
  last_rung_ = cur_rung;
  if (suspended_) return false;
  if (!fault_located_) {
    // The innermost routine places the fault and offers it to the user fault routine once.
    fault_located_ = true;
    fault_.file = cur_file;
    fault_.rung = cur_rung;
    if (user_fault_routine(elapsed)) {
      // Recovered (RM 11-2): the scan goes on at the start of the next rung of this file; the
      // faulting instruction wrote nothing (its operand went to scratch).
      fault_located_ = false;
      fault_ = {};
      const CompiledFile* cf = prog_.file(cur_file);
      const auto next = static_cast<std::size_t>(cur_rung) + 1;
      pc = code_ + (next < cf->rungs.size() ? cf->rungs[next].offset : cf->end - 1);
      rung = true;
      goto resume;
    }
  }
  return false;
}

}  // namespace softslc
