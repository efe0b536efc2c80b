#include "vm/compiler.h"

#include "vm/message_network.h"
#include "vm/modbus_master.h"
#include "vm/state_file.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>

#include "parser/checker.h"
#include "parser/formatter.h"
#include "parser/loader.h"
#include "parser/limits.h"

namespace softslc {

// The loader refuses deeper nesting than the interpreter's branch stack holds: one number.
static_assert(kMaxBranchDepth == kMaxBranchNesting, "the loader's branch limit is the interpreter's");

std::string CompileError::to_string() const {
  std::string s;
  if (file >= 0) s += "file " + std::to_string(file);
  if (rung >= 0) s += " rung " + std::to_string(rung);
  if (pos.line > 0) s += (s.empty() ? "" : " ") + std::string("(line ") + std::to_string(pos.line) + ")";
  if (!s.empty()) s += ": ";
  return s + message;
}

std::string CompileResult::render() const {
  std::string s;
  for (const auto& e : errors) s += e.to_string() + "\n";
  return s;
}

std::string module_instruction_unsupported(Opcode op) {
  return std::string(spec(op).mnemonic) +
         " is not supported until the 1747-SN/1747-SDN module lands in this runtime (specialty-module instructions need "
         "their module's implementation: build the RuntimeOptions with the module registry, modules/module_setup.h)";
}

std::optional<int> module_instruction_slot(const Instruction& in) {
  for (const auto& op : in.operands)
    if (op.is_address() && is_mfile(op.address.type)) return op.address.element;
  const InstructionSpec& sp = spec(in.opcode);
  for (std::size_t i = 0; i < in.operands.size() && i < sp.operand_count; ++i)
    if (sp.operands[i].kind == OperandKind::Literal && sp.operands[i].label == "slot" &&
        in.operands[i].kind == Operand::Kind::Integer)
      return static_cast<int>(in.operands[i].integer);
  return std::nullopt;
}

namespace {

std::uint32_t wpe_of(FileType t) {
  if (is_io(t) || t == FileType::Status) return 1;
  return static_cast<std::uint32_t>(words_per_element(t));
}

bool is_module_instruction(Opcode op) { return op == Opcode::BTR || op == Opcode::BTW || op == Opcode::DEM; }

struct FileUse {
  bool present = false;
  FileType type = FileType::Integer;
  std::uint32_t elements = 0;
  SourcePos pos;
};

struct Fixup {
  std::uint32_t at;  // code index of the TARGET word
  int target;        // label number (JMP) or file number (JSR)
  SourcePos pos;
  int file;
  int rung;
};

class Compiler {
 public:
  Compiler(const Program& p, const CompileOptions& o) : prog_(p), opts_(o), proc_(o.processor ? *o.processor : p.processor) {}

  CompileResult run() {
    size_files();
    if (errors_.empty()) build_layout();
    if (errors_.empty()) load_data();
    if (errors_.empty()) emit_program();
    if (errors_.empty()) compile_data_logs();
    CompileResult r;
    r.errors = std::move(errors_);
    if (r.errors.empty()) {
      out_.processor = proc_;
      out_.source_name = prog_.source_name;
      out_.layout = std::make_shared<const DataTableLayout>(layout_);
      out_.initial_words = std::move(init_);
      out_.slots = prog_.slots;
      out_.forces = prog_.forces;
      // Only RPC reads the checksum, and computing it formats the whole ladder (8% of loading a
      // 1M-rung program, docs/performance.md "Load time"): a program without RPC keeps 0.
      if (reads_checksum_) out_.program_checksum = program_checksum(prog_);
      r.program = std::move(out_);
    }
    return r;
  }

 private:
  void error(SourcePos pos, std::string msg) { errors_.push_back({cur_file_, cur_rung_, pos, std::move(msg)}); }

  const SlotConfig* slot_config(int slot) const {
    for (const auto& s : prog_.slots)
      if (s.slot == slot) return &s;
    return nullptr;
  }

  // ---- Pass 1: which files exist, their types and sizes -------------------------------------------

  bool file_type_allowed(FileType t) const {
    switch (t) {
      case FileType::Float: return proc_.has_float_files();
      case FileType::Long: return proc_.has_long_files();
      case FileType::Message: return proc_.has_message_files();
      case FileType::Routing: return proc_.has_routing_files();
      case FileType::String:
      case FileType::Ascii:
        return proc_.family == ProcessorFamily::Slc503 || proc_.family == ProcessorFamily::Slc504 ||
               proc_.family == ProcessorFamily::Slc505 || proc_.family == ProcessorFamily::MicroLogix;
      default: return true;
    }
  }

  void note_file(int file, FileType t, std::uint32_t elements, SourcePos pos) {
    if (file < 3 || file > 255) return;  // O/I/S are sized from the configuration
    auto& u = use_[static_cast<std::size_t>(file)];
    if (!u.present) {
      if (!file_type_allowed(t)) {
        error(pos, std::string(file_letter(t)) + " files do not exist on " + proc_.display_name);
        return;
      }
      u.present = true;
      u.type = t;
      u.pos = pos;
    } else if (u.type != t) {
      error(pos, "file " + std::to_string(file) + " is used as " + std::string(file_letter(t)) + std::to_string(file) +
                     " but it is already " + std::string(file_letter(u.type)) + std::to_string(file) + " (line " +
                     std::to_string(u.pos.line) + ")");
      return;
    }
    if (elements > kMaxElements) {
      error(pos, std::string(file_letter(t)) + std::to_string(file) + " would need " + std::to_string(elements) +
                     " elements; a data file has at most 256 (0-255)");
      return;
    }
    u.elements = std::max(u.elements, elements);
  }

  void note_ref(const IndirectRef& r, SourcePos pos) {
    Address a;
    a.type = r.type;
    a.file = r.file;
    a.element = r.element;
    a.word = r.word;
    note_address(a, 1, pos);
  }

  void note_address(const Address& a, std::uint32_t extent, SourcePos pos) {
    if (a.indirect_file()) note_ref(*a.indirect_file(), pos);
    if (a.indirect_element()) note_ref(*a.indirect_element(), pos);
    if (a.indirect_word()) note_ref(*a.indirect_word(), pos);
    if (a.indirect_bit()) note_ref(*a.indirect_bit(), pos);
    if (is_function_file(a.type) && a.file < kFunctionFileCount) named_function_files_[a.file] = true;
    if (is_io(a.type) || is_mfile(a.type) || a.type == FileType::Status || is_function_file(a.type)) return;
    if (a.indirect_file()) return;  // which file is only known at run time
    std::uint32_t elements = 1;
    if (!a.indirect_element() && !(a.bit_offset_form && a.indirect_bit())) {
      if (a.element < 0) {
        error(pos, "negative element in " + to_string(a));
        return;
      }
      elements = static_cast<std::uint32_t>(a.element) + std::max<std::uint32_t>(extent, 1);
    }
    note_file(a.file, a.type, elements, pos);
  }

  // COP with direct source and destination: both spans are fixed at compile time. When both lie
  // inside their files, returns the number of words the copy moves (destination elements times
  // their words, RM E-11), which the interpreter then copies without resolving anything; else 0,
  // and the interpreter resolves the operands at run time (and faults where the SLC would).
  std::uint32_t direct_copy_words(std::uint32_t src, std::uint32_t dst, std::uint32_t length) const {
    auto direct = [](std::uint32_t o) {
      const bc::Mode m = bc::mode_of(o);
      return m == bc::kWord || m == bc::kLong || m == bc::kFloat;
    };
    if (!direct(src) || !direct(dst) || bc::mode_of(length) != bc::kImm) return 0;
    const int src_file = layout_.file_containing(bc::payload_of(src));
    const int dst_file = layout_.file_containing(bc::payload_of(dst));
    if (src_file < 0 || dst_file < 0) return 0;
    const FileLayout& sf = layout_.files[static_cast<std::size_t>(src_file)];
    const FileLayout& df = layout_.files[static_cast<std::size_t>(dst_file)];
    const auto len = static_cast<std::uint64_t>(std::max(bc::imm_of(length), 1));
    const std::uint64_t words = len * df.words_per_element;
    const std::uint64_t src_words = (words + sf.words_per_element - 1) / sf.words_per_element * sf.words_per_element;
    if (bc::payload_of(dst) + words > df.end() || bc::payload_of(src) + src_words > sf.end()) return 0;
    return words <= 0xFFFF ? static_cast<std::uint32_t>(words) : 0;
  }

  static std::int64_t literal(const Instruction& in, std::size_t i) {
    if (i < in.operands.size() && in.operands[i].kind == Operand::Kind::Integer) return in.operands[i].integer;
    return 0;
  }

  // How many elements from its start a file-instruction operand covers (1 for other operands).
  static std::uint32_t extent(const Instruction& in, std::size_t i) {
    auto len = [&](std::size_t k) { return static_cast<std::uint32_t>(std::clamp<std::int64_t>(literal(in, k), 0, 4096)); };
    auto type_of = [&](std::size_t k) {
      return in.operands.size() > k && in.operands[k].is_address() ? in.operands[k].address.type : FileType::Integer;
    };
    switch (in.opcode) {
      case Opcode::COP:
        if (i == 1) return len(2);
        if (i == 0) {
          const std::uint32_t words = len(2) * wpe_of(type_of(1));
          const std::uint32_t w = wpe_of(type_of(0));
          return (words + w - 1) / w;
        }
        return 1;
      case Opcode::CPW:  // length counts words (MicroLogix), whatever either file's element size
        if (i <= 1) return (len(2) + wpe_of(type_of(i)) - 1) / wpe_of(type_of(i));
        return 1;
      case Opcode::SWP:  // length counts words; a string element holds 41 of them
        return i == 0 ? (len(1) + wpe_of(type_of(0)) - 1) / wpe_of(type_of(0)) : 1;
      case Opcode::FLL: return i == 1 ? len(2) : 1;
      case Opcode::BSL:
      case Opcode::BSR: return i == 0 ? (len(3) + 15) / 16 : 1;
      case Opcode::SQO:
      case Opcode::SQC: return i == 0 ? len(4) + 1 : 1;
      case Opcode::SQL: return i == 0 ? len(3) + 1 : 1;
      case Opcode::FFL:
      case Opcode::LFL: return i == 1 ? len(3) : 1;
      case Opcode::FFU:
      case Opcode::LFU: return i == 0 ? len(3) : 1;
      // Block transfers: the 3-word control block, and the data file's requested length (0
      // reserves 64 words, 1747-SN manual p. 5-7). DEM: the 70-word control block.
      case Opcode::BTR:
      case Opcode::BTW:
        if (i == 0) return 3;
        if (i == 2) return len(6) == 0 ? 64 : len(6);
        return 1;
      case Opcode::DEM: return i == 1 ? 70 : 1;
      case Opcode::PID: return i == 0 ? 23 : 1;  // RM001G p. 9-3: N10:0 allocates N10:0-N10:22
      // FBC/DDT (RM 7-18): source and reference hold `cmp length` bits; the result file one word
      // per result position.
      case Opcode::FBC:
      case Opcode::DDT:
        if (i <= 1) return (len(4) + 15) / 16;
        if (i == 2) return len(7);
        return 1;
      // MSG: the control block (its length operand) and `size` elements of the local data.
      case Opcode::MSG: return i == 3 ? len(4) : i == 6 ? std::max<std::uint32_t>(len(7), 1) : 1;
      case Opcode::MSG_502: return i == 2 ? len(3) : i == 4 ? std::max<std::uint32_t>(len(5), 1) : 1;
      case Opcode::MSG_ML:
        if (i != 5) return 1;
        // A Modbus bit command (01, 02, 05, 15) moves `size` bits from the data's bit on.
        if (in.operands.size() > 5 && in.operands[1].kind == Operand::Kind::Integer &&
            modbus::is_bit_command(static_cast<int>(in.operands[1].integer)))
          return static_cast<std::uint32_t>((std::max(in.operands[5].address.bit, 0) + std::max<std::int64_t>(len(6), 1) + 15) / 16);
        return std::max<std::uint32_t>(len(6), 1);
      default: return 1;
    }
  }

  void note_elements(const std::vector<RungElement>& elems) {
    for (const auto& e : elems) {
      if (e.kind == RungElement::Kind::Branch) {
        code_words_ += 1 + e.legs.size();  // BST, an NXB between legs, BND
        for (const auto& leg : e.legs) note_elements(leg);
        continue;
      }
      const auto& in = e.instruction;
      code_words_ += 1 + in.operands.size() + (in.opcode == Opcode::JMP || in.opcode == Opcode::JSR ? 1 : 0);
      if (in.opcode == Opcode::RPC) reads_checksum_ = true;
      const InstructionSpec& sp = spec(in.opcode);
      for (std::size_t i = 0; i < in.operands.size(); ++i) {
        const auto& op = in.operands[i];
        // A MSG target names the other controller's data table, never a file of this program.
        if (i < sp.operand_count && sp.operands[i].kind == OperandKind::RemoteAddress) continue;
        if (op.is_address()) note_address(op.address, extent(in, i), op.pos);
        if (op.kind == Operand::Kind::Expression) note_expression(op);
      }
    }
  }

  // The addresses inside a CPT expression size their files like any operand.
  void note_expression(const Operand& op) {
    ExpressionError err;
    auto items = parse_expression(op.spelling, err);
    if (!items) return;  // reported when the instruction is compiled
    for (const auto& it : *items)
      if (it.code == ExprCode::Push)
        if (auto a = parse_address(it.text)) note_address(*a, 1, op.pos);
  }

  void size_files() {
    // The default files exist on every processor (RM E-3); F8 where the processor has floats.
    const SourcePos none{};
    note_file(3, FileType::Bit, 1, none);
    note_file(4, FileType::Timer, 1, none);
    note_file(5, FileType::Counter, 1, none);
    note_file(6, FileType::Control, 1, none);
    note_file(7, FileType::Integer, 1, none);
    if (proc_.has_float_files()) note_file(8, FileType::Float, 1, none);
    for (const auto& d : prog_.data) {
      if (!d.type || is_io(*d.type) || *d.type == FileType::Status || is_mfile(*d.type) || is_function_file(*d.type)) continue;
      const FileType t = *d.type;
      const std::size_t n = t == FileType::Float    ? d.floats.size()
                            : t == FileType::String ? d.strings.size()
                            : is_structured(t) || is_multiword_data(t)
                                ? (d.words.size() + words_per_element(t) - 1) / words_per_element(t)
                                : d.words.size();
      note_file(d.file, t, static_cast<std::uint32_t>(d.start_element) + static_cast<std::uint32_t>(std::max<std::size_t>(n, 1)),
                d.pos);
    }
    for (const auto& f : prog_.files) {
      cur_file_ = f.number;
      code_words_ += f.rungs.size() + 1;  // a SOR per rung, the file's EOF
      for (std::size_t r = 0; r < f.rungs.size(); ++r) {
        cur_rung_ = static_cast<int>(r);
        note_elements(f.rungs[r].elements);
      }
    }
    cur_file_ = cur_rung_ = -1;
    // A DATALOG field is a use of its file as an operand is (N7:11 makes N7 at least 12 long).
    for (const auto& q : prog_.data_logs)
      for (std::size_t i = 0; i < q.fields.size(); ++i) note_address(q.fields[i], 1, q.field_pos[i]);
  }

  void build_layout() {
    std::uint32_t next = 0;
    // O0 and I1: each configured slot's image words, in slot order.
    std::vector<const SlotConfig*> slots;
    for (const auto& s : prog_.slots) {
      if (s.slot < 0 || s.slot >= kMaxSlots) {
        error(s.pos, "slot " + std::to_string(s.slot) + " is outside the chassis (0-30)");
        continue;
      }
      slots.push_back(&s);
    }
    std::sort(slots.begin(), slots.end(), [](auto* a, auto* b) { return a->slot < b->slot; });
    auto io_file = [&](int number, FileType t, auto words_of, auto& table) {
      FileLayout& f = layout_.files[static_cast<std::size_t>(number)];
      f.present = true;
      f.type = t;
      f.base = next;
      f.words_per_element = 1;
      std::uint32_t off = 0;
      for (const auto* s : slots) {
        const int n = words_of(*s);
        if (n <= 0) continue;
        table[static_cast<std::size_t>(s->slot)] = SlotImage{true, off, static_cast<std::uint32_t>(n)};
        off += static_cast<std::uint32_t>(n);
      }
      f.elements = off;
      next += off;
    };
    io_file(0, FileType::Output, [](const SlotConfig& s) { return s.scan_out; }, layout_.output_slots);
    io_file(1, FileType::Input, [](const SlotConfig& s) { return s.scan_in; }, layout_.input_slots);
    FileLayout& st = layout_.files[2];
    st.present = true;
    st.type = FileType::Status;
    st.base = next;
    st.elements = std::max<std::uint32_t>(static_cast<std::uint32_t>(status_file_words(proc_)), kMinStatusWords);
    st.words_per_element = 1;
    next += st.elements;
    for (int n = 3; n < 256; ++n) {
      const auto& u = use_[static_cast<std::size_t>(n)];
      if (!u.present) continue;
      FileLayout& f = layout_.files[static_cast<std::size_t>(n)];
      f.present = true;
      f.type = u.type;
      f.base = next;
      f.elements = std::max<std::uint32_t>(u.elements, 1);
      f.words_per_element = static_cast<std::uint8_t>(wpe_of(u.type));
      next += f.words();
    }
    // The real-time clock function file: built into the MicroLogix 1100 and 1400, a plug-in on the
    // 1200 and 1500 (1762-RM001C p. 3-3), present in the data table of all four so that a program
    // and a test can read and set it. It starts at softslc's fixed power-up date (docs/semantics.md
    // "Real-time clock") and runs in virtual time (Runtime::advance_rtc).
    // The STI function file (1763-RM001C pp. 269-272) follows it on the same four controllers; the
    // interpreter runs the selectable timed interrupt from it (vm/interrupts.cpp).
    // The pulse train output file too: PTO on the 1100, 1200 and 1500, PTOX on the 1400 (vm/ml_pto.h).
    if (proc_.is_micrologix_1100_class()) {
      // So does the HSC function file, with as many elements as the processor has high-speed
      // counters (ProcessorModel::hsc_count; vm/ml_hsc.h runs them). In FunctionFile order, which
      // DataTableLayout::scan_for_file relies on.
      const FunctionFile pulse_train = proc_.micrologix == MicroLogixModel::ML1400 ? FunctionFile::PTOX : FunctionFile::PTO;
      for (const FunctionFile kind :
           {FunctionFile::RTC, FunctionFile::HSC, FunctionFile::PTOX, FunctionFile::STI, FunctionFile::EII, FunctionFile::PTO}) {
        const bool counters = kind == FunctionFile::HSC;
        if (counters && proc_.hsc_count() == 0) continue;
        // The EII file has as many elements as the processor has event inputs (eii_count).
        const bool events = kind == FunctionFile::EII;
        if ((kind == FunctionFile::PTO || kind == FunctionFile::PTOX) && kind != pulse_train) continue;
        FileLayout& f = layout_.files[kFunctionFileIndex + static_cast<std::size_t>(kind)];
        f.present = true;
        f.type = FileType::Function;
        f.base = next;
        f.elements = static_cast<std::uint32_t>(counters ? proc_.hsc_count()
                                                : events ? proc_.eii_count()
                                                         : function_file_elements(static_cast<int>(kind)));
        f.words_per_element = static_cast<std::uint8_t>(function_file_words_per_element(static_cast<int>(kind)));
        next += f.words();
      }
    }
    // The Data Log Status file: "The DLS file does not exist until a data log queue has been
    // configured" (1763-RM001C p. 440); an element for each queue up to the highest configured.
    if (proc_.has_data_logging() && !prog_.data_logs.empty()) {
      int highest = 0;
      for (const auto& q : prog_.data_logs) highest = std::max(highest, std::clamp(q.number, 0, dls::kMaxQueues - 1));
      FileLayout& f = layout_.files[kFunctionFileIndex + static_cast<std::size_t>(FunctionFile::DLS)];
      f.present = true;
      f.type = FileType::Function;
      f.base = next;
      f.elements = static_cast<std::uint32_t>(highest + 1);
      f.words_per_element = static_cast<std::uint8_t>(dls::kWords);
      next += f.words();
    }
    // A communications status file that the program names (the checker allows CS0:4/MCP of a channel the
    // processor has): 71 one-word elements, zero but for the bit the MSG network and the Modbus master keep
    // (docs/semantics.md "The CS file"). Only when named, so that no other program's table grows.
    for (const FunctionFile kind : {FunctionFile::CS0, FunctionFile::CS1, FunctionFile::CS2}) {
      if (!proc_.is_micrologix_1100_class() || !named_function_files_[static_cast<std::size_t>(kind)]) continue;
      FileLayout& f = layout_.files[kFunctionFileIndex + static_cast<std::size_t>(kind)];
      f.present = true;
      f.type = FileType::Function;
      f.base = next;
      f.elements = static_cast<std::uint32_t>(cs::kElements);
      f.words_per_element = 1;
      next += f.words();
    }
    layout_.total_words = next;
    if (next > bc::kMaxWordIndex) error({}, "the data table is too large to address");
    else layout_.index_files();
  }

  // ---- Initial data ------------------------------------------------------------------------------------

  void set_init(std::uint32_t word, std::uint16_t v) {
    init_[word] = v;
    initialised_[word] = true;
  }

  // DATA PTO0:0 / PTOX0:0: nine values per element (OUT bits ER OF OFS JF TOP OPP ADP, as RSLogix
  // exports a PTOX element), spread over the element's words; the long ones low word first.
  void load_pulse_train_data(const DataBlock& d) {
    const FileLayout& f = layout_.files[kFunctionFileIndex + static_cast<std::size_t>(d.file)];
    if (!f.present) return;
    const pto::Layout& l = d.file == static_cast<int>(FunctionFile::PTOX) ? pto::kPtox : pto::kPto;
    const int words[pto::kValuesPerElement] = {pto::kOutput, pto::kBits, pto::kErrorCode, l.frequency, l.frequency_status,
                                               l.jog_frequency, l.total, l.produced, l.accel_decel};
    for (std::size_t i = 0; i < d.words.size(); ++i) {
      const std::uint32_t element = static_cast<std::uint32_t>(i / pto::kValuesPerElement);
      const int word = words[i % pto::kValuesPerElement];
      if (element >= f.elements) break;
      const std::uint32_t at = f.base + element * f.words_per_element + static_cast<std::uint32_t>(word);
      const auto v = static_cast<std::uint32_t>(static_cast<std::int64_t>(d.words[i]));
      set_init(at, static_cast<std::uint16_t>(v & 0xFFFF));
      if (function_word_is_long(d.file, word)) set_init(at + 1, static_cast<std::uint16_t>(v >> 16));
    }
  }

  void load_data() {
    init_.assign(layout_.total_words, 0);
    initialised_.assign(layout_.total_words, false);
    if (const FileLayout& clock = layout_.function_file(FunctionFile::RTC); clock.present) {
      // softslc's power-up date: Saturday 2000-01-01 00:00:00 (a fixed date keeps runs
      // deterministic; a test sets the clock it needs with --set or a .test SET line).
      set_init(clock.base + rtc::kYear, 2000);
      set_init(clock.base + rtc::kMonth, 1);
      set_init(clock.base + rtc::kDay, 1);
      set_init(clock.base + rtc::kDayOfWeek, 6);
    }
    // The STI as RSLogix creates it (UIE set, nothing configured) unless a DATA STI:0 block says
    // otherwise (every saved project without an STI has 0 0 0X0002 0; docs/semantics.md "MicroLogix").
    if (const FileLayout& timed = layout_.function_file(FunctionFile::STI); timed.present)
      set_init(timed.base + sti::kBits, sti::kDefaultBits);
    // Each EII as RSLogix creates it: UIE and ES set, IS = the element's number (0 0 0X4002 n in
    // 59-BSGS.SLC and the .RSS record of type 0x15; docs/semantics.md "The EII function file").
    if (const FileLayout& events = layout_.function_file(FunctionFile::EII); events.present)
      for (std::uint32_t e = 0; e < events.elements; ++e) {
        set_init(events.base + e * eii::kWords + eii::kBits, eii::kDefaultBits);
        set_init(events.base + e * eii::kWords + eii::kInputSelect, static_cast<std::uint16_t>(e));
      }
    // Each configured queue's DLS0:q.FSZ: "the number of records ... set when the data log queue is
    // configured" (AG-UM008C p. 3-65).
    if (const FileLayout& f = layout_.function_file(FunctionFile::DLS); f.present)
      for (const auto& q : prog_.data_logs)
        if (q.number >= 0 && static_cast<std::uint32_t>(q.number) < f.elements)
          set_init(f.base + static_cast<std::uint32_t>(q.number) * dls::kWords + dls::kFileSize, static_cast<std::uint16_t>(q.records));
    // Every PTO/PTOX element's OUT is -1 (no output) until configured: the .RSS record and the export
    // hold -1 in every unused element (docs/micrologix-function-files-sources.md section 6.3).
    for (const FunctionFile pulse_train : {FunctionFile::PTO, FunctionFile::PTOX})
      if (const FileLayout& f = layout_.function_file(pulse_train); f.present)
        for (std::uint32_t e = 0; e < f.elements; ++e) set_init(f.base + e * f.words_per_element + pto::kOutput, 0xFFFF);
    // Each HSC as RSLogix creates it: the two bit words 0X0002 0X000F, HIP and OVF 2147483647, LOP
    // and UNF -2147483648 (59-BSGS.SLC and every .RSS fixture without an HSC; docs/semantics.md).
    if (const FileLayout& counters = layout_.function_file(FunctionFile::HSC); counters.present)
      for (std::uint32_t e = 0; e < counters.elements; ++e) {
        const std::uint32_t base = counters.base + e * hsc::kWords;
        set_init(base + hsc::kBits, hsc::kDefaultBits);
        set_init(base + hsc::kStatus, hsc::kDefaultStatus);
        for (int w : {hsc::kHighPreset, hsc::kOverflow}) {
          set_init(base + static_cast<std::uint32_t>(w), 0xFFFF);
          set_init(base + static_cast<std::uint32_t>(w) + 1, 0x7FFF);
        }
        for (int w : {hsc::kLowPreset, hsc::kUnderflow}) {
          set_init(base + static_cast<std::uint32_t>(w), 0x0000);
          set_init(base + static_cast<std::uint32_t>(w) + 1, 0x8000);
        }
      }
    for (const auto& d : prog_.data) {
      if (!d.type || is_mfile(*d.type)) continue;
      const FileType t = *d.type;
      if (is_function_file(t) && is_pulse_train_file(d.file)) {
        load_pulse_train_data(d);
        continue;
      }
      if (is_function_file(t)) {
        const FileLayout& f = layout_.files[kFunctionFileIndex + static_cast<std::size_t>(d.file)];
        if (d.file == static_cast<int>(FunctionFile::HSC)) {
          // RSLogix's export form: 13 values an element, five of them 32-bit (low word first).
          for (std::size_t i = 0; f.present && i < d.words.size(); ++i) {
            const std::size_t e = static_cast<std::size_t>(std::max(d.start_element, 0)) + i / hsc::kExportValues;
            if (e >= f.elements) break;
            const std::size_t k = i % hsc::kExportValues;
            const std::uint32_t at = f.base + static_cast<std::uint32_t>(e * hsc::kWords) +
                                     static_cast<std::uint32_t>(hsc::export_value_word(k));
            const auto bits = static_cast<std::uint32_t>(d.words[i]);
            set_init(at, static_cast<std::uint16_t>(bits));
            if (hsc::export_value_is_long(k)) set_init(at + 1, static_cast<std::uint16_t>(bits >> 16));
          }
          continue;
        }
        const std::size_t first = static_cast<std::size_t>(std::max(d.start_element, 0)) * f.words_per_element;
        for (std::size_t i = 0; f.present && i < d.words.size() && first + i < f.words(); ++i)
          set_init(f.base + static_cast<std::uint32_t>(first + i), static_cast<std::uint16_t>(d.words[i]));
        continue;
      }
      if (is_io(t)) {
        const FileLayout& f = layout_.files[static_cast<std::size_t>(fixed_file_number(t))];
        const auto& slots = t == FileType::Input ? layout_.input_slots : layout_.output_slots;
        // The block's words run on from the image of its first slot through the following slots.
        std::uint32_t off = 0;
        if (d.start_element >= 0 && d.start_element < kMaxSlots) {
          const auto& s = slots[static_cast<std::size_t>(d.start_element)];
          off = s.present ? s.first : f.elements;
        }
        for (std::size_t i = 0; i < d.words.size() && off + i < f.elements; ++i)
          set_init(f.base + off + static_cast<std::uint32_t>(i), static_cast<std::uint16_t>(d.words[i]));
        continue;
      }
      if (t == FileType::Status) {
        const FileLayout& f = layout_.files[2];
        for (std::size_t i = 0; i < d.words.size(); ++i) {
          const std::size_t w = static_cast<std::size_t>(d.start_element) + i;
          if (w >= f.elements) break;
          set_init(f.base + static_cast<std::uint32_t>(w), static_cast<std::uint16_t>(d.words[i]));
        }
        continue;
      }
      if (d.file < 3 || d.file > 255) continue;
      const FileLayout& f = layout_.files[static_cast<std::size_t>(d.file)];
      if (!f.present || f.type != t) continue;
      const std::uint32_t start = f.base + static_cast<std::uint32_t>(d.start_element) * f.words_per_element;
      if (t == FileType::Float) {
        for (std::size_t i = 0; i < d.floats.size(); ++i) {
          const std::uint32_t w = start + static_cast<std::uint32_t>(i) * 2;
          if (w + 2 > f.end()) break;
          const float v = static_cast<float>(d.floats[i]);
          std::uint16_t parts[2];
          std::memcpy(parts, &v, sizeof v);
          set_init(w, parts[0]);
          set_init(w + 1, parts[1]);
        }
      } else if (t == FileType::Long) {
        for (std::size_t i = 0; i < d.words.size(); ++i) {
          const std::uint32_t w = start + static_cast<std::uint32_t>(i) * 2;
          if (w + 2 > f.end()) break;
          const auto v = static_cast<std::int32_t>(d.words[i]);
          std::uint16_t parts[2];
          std::memcpy(parts, &v, sizeof v);
          set_init(w, parts[0]);
          set_init(w + 1, parts[1]);
        }
      } else if (t == FileType::String) {
        // ST element: word 0 = length, then two characters per word, first in the high byte [U].
        for (std::size_t i = 0; i < d.strings.size(); ++i) {
          const std::uint32_t w = start + static_cast<std::uint32_t>(i) * 42;
          if (w + 42 > f.end()) break;
          const std::string& s = d.strings[i];
          const std::size_t n = std::min<std::size_t>(s.size(), 82);
          set_init(w, static_cast<std::uint16_t>(n));
          for (std::size_t c = 0; c < n; ++c) {
            const std::uint32_t ww = w + 1 + static_cast<std::uint32_t>(c / 2);
            const auto ch = static_cast<std::uint8_t>(s[c]);
            init_[ww] = static_cast<std::uint16_t>(c % 2 == 0 ? (init_[ww] & 0x00FF) | (ch << 8) : (init_[ww] & 0xFF00) | ch);
            initialised_[ww] = true;
          }
        }
      } else {
        for (std::size_t i = 0; i < d.words.size(); ++i) {
          const std::uint32_t w = start + static_cast<std::uint32_t>(i);
          if (w >= f.end()) break;
          set_init(w, static_cast<std::uint16_t>(d.words[i]));
        }
      }
    }
    // Watchdog: S:3 high byte, default 10 ticks = 100 ms (PT1 27-13) when no DATA gives one.
    const std::uint32_t s3 = layout_.status_word(status::kWatchdog);
    if ((init_[s3] >> 8) == 0) init_[s3] = static_cast<std::uint16_t>((init_[s3] & 0x00FF) | (10u << 8));
    // STI enable: S:2/1 "The default value is 1 (set)" (RM 11-12) when no DATA block gives S:2.
    const std::uint32_t s2 = layout_.status_word(status::kControl);
    if (!initialised_[s2]) init_[s2] = static_cast<std::uint16_t>(init_[s2] | status::kStiEnabled);
    // The DII enable S:2/12 on the 5/03-5/05 and the I/O interrupt enables S:27/S:28 (slots 1-30) on
    // the 5/02 and later start set unless DATA gives them, as the STI enable does; the manual pages
    // that would say were not reached (docs/semantics.md "I/O and discrete input interrupts").
    const bool modular_503 = proc_.family == ProcessorFamily::Slc503 || proc_.family == ProcessorFamily::Slc504 ||
                             proc_.family == ProcessorFamily::Slc505;
    if (!initialised_[s2] && modular_503) init_[s2] = static_cast<std::uint16_t>(init_[s2] | status::kDiiEnabled);
    if (proc_.supports(Requirement::IoInterrupt) &&
        layout_.files[2].elements > static_cast<std::uint32_t>(status::kIoEnableLow + 1)) {
      const std::uint32_t s27 = layout_.status_word(status::kIoEnableLow);
      if (!initialised_[s27]) init_[s27] = 0xFFFE;      // S:27/1-15: slots 1-15
      if (!initialised_[s27 + 1]) init_[s27 + 1] = 0x7FFF;  // S:28/0-14: slots 16-30
    }
  }

  // A literal operand initialises an element word unless DATA (or an earlier instruction) did.
  // MSG: "Most of the MSG instruction parameters are stored in its associated control block" (RM 12-31,
  // table 12.11): like RSLogix when the instruction is entered, the setup goes into the block so that the
  // processor reads it from there (and a program that rewrites word 1 sends to another node). Word 1 the
  // target node, 2 the number of elements, 3 the target file, 4 the file type (the PCCC typed-read code of
  // the local file's type, docs/semantics.md), 5 the target element; 8 the timeout (5/03-5/05). 485CIF
  // targets the common interface file, N9, at the offset given.
  void init_message_block(const Instruction& in, const std::vector<std::uint32_t>& ops) {
    const bool slc502 = in.opcode == Opcode::MSG_502;
    const std::size_t block = slc502 ? 2 : 3, data = slc502 ? 4 : 6, size = slc502 ? 5 : 7, node = slc502 ? 6 : 8,
                      target = slc502 ? 7 : 9;
    if (in.operands.size() <= target || !in.operands[data].is_address()) return;
    const Operand& t = in.operands[target];
    const bool cif = in.operands[1].kind == Operand::Kind::Symbol && in.operands[1].spelling == "485CIF";
    init_literal(ops[block], 1, literal(in, node));
    init_literal(ops[block], 2, literal(in, size));
    init_literal(ops[block], 3, cif ? kCommonInterfaceFile : (t.is_address() ? t.address.file : 0));
    init_literal(ops[block], 4, message_file_type_code(in.operands[data].address.type));
    init_literal(ops[block], 5, cif ? (t.kind == Operand::Kind::Integer ? t.integer : 0)
                                    : (t.is_address() ? t.address.element : 0));
    if (!slc502) init_literal(ops[block], 8, literal(in, 10));
  }

  // The MicroLogix MSG: the setup screen's values go into the MG element where the manuals place them
  // (1762-RM001C p. 21-4, 1766-RM001A pp. 399-401): 8 CHN, 9 NOD, 10 MTO, 12 the target file type (the
  // PCCC typed-read code of the local file's type, as the SLC block's word 4), 13 TFN, 14 ELE (485CIF: the
  // offset into the common interface file, N9), 17 bit 0 R = 1 (local). The 1100 and 1400 keep the byte
  // count in word 11 (1766-RM001A p. 399; reserved on the 1200/1500). The read/write command, the local
  // address and the element count stay with the instruction: the manuals keep them in the internal words
  // 3 and 4, whose encoding they do not give (docs/semantics.md "The MicroLogix MSG").
  void init_micrologix_message(const Instruction& in, const std::vector<std::uint32_t>& ops) {
    if (in.operands.size() < 10 || !in.operands[5].is_address()) return;
    const Operand& t = in.operands[8];
    const bool cif = in.operands[2].kind == Operand::Kind::Symbol && in.operands[2].spelling == "485CIF";
    const FileType local = in.operands[5].address.type;
    if (in.operands[2].kind == Operand::Kind::Symbol && in.operands[2].spelling == "MODBUS")
      return init_modbus_message(in, ops);
    init_literal(ops[0], mg::kChannel, literal(in, 4));
    init_literal(ops[0], mg::kNode, literal(in, 7));
    init_literal(ops[0], mg::kTimeout, literal(in, 9));
    if (proc_.micrologix == MicroLogixModel::ML1100 || proc_.micrologix == MicroLogixModel::ML1400)
      init_literal(ops[0], mg::kByteCount, 2 * literal(in, 6) * words_per_element(local));
    init_literal(ops[0], mg::kTargetFileType, message_file_type_code(local));
    init_literal(ops[0], mg::kTargetFile, cif ? kCommonInterfaceFile : (t.is_address() ? t.address.file : 0));
    init_literal(ops[0], mg::kTargetElement, cif ? (t.kind == Operand::Kind::Integer ? t.integer : 0)
                                                 : (t.is_address() ? t.address.element : 0));
    init_literal(ops[0], mg::kStatus, 1u << mg::kRangeBit);
    // Channel 1 (Ethernet): word 24, "supplemental routing path data address", names the RI element, bits
    // 8-15 its file, 0-7 its element (1766-RM001A p. 400); the processor reads the IP address there.
    if (const Operand& ri = in.operands[7]; ri.is_address() && ri.address.type == FileType::Routing)
      init_literal(ops[0], mg::kRoutingPath, (ri.address.file << 8) | ri.address.element);
  }

  // The Modbus RTU master MSG's setup in the MG element (1763-RM001B pp. 347-350, 1766-RM001A pp. 399-401): word
  // 2 messaging type 2 (Modbus master), 3 the function code, 8 CHN, 9 NOD (the slave address), 10 MTO, 11 the
  // number of elements, 12 the local starting bit for coils and inputs, 13 the Modbus target data address - 1.
  void init_modbus_message(const Instruction& in, const std::vector<std::uint32_t>& ops) {
    init_literal(ops[0], mg::kMessagingType, 2);
    init_literal(ops[0], mg::kCommand, literal(in, 1));
    init_literal(ops[0], mg::kChannel, literal(in, 4));
    init_literal(ops[0], mg::kNode, literal(in, 7));
    init_literal(ops[0], mg::kTimeout, literal(in, 9));
    init_literal(ops[0], mg::kByteCount, literal(in, 6));
    const Address& data = in.operands[5].address;
    init_literal(ops[0], mg::kTargetFileType, data.bit >= 0 ? data.bit : 0);
    init_literal(ops[0], mg::kTargetFile, literal(in, 8) - 1);
    init_literal(ops[0], mg::kStatus, 1u << mg::kRangeBit);
  }

  void init_literal(std::uint32_t op_word, std::uint32_t sub, std::int64_t value) {
    if (bc::mode_of(op_word) != bc::kWord) return;  // indexed/indirect elements are not known here
    const std::uint32_t w = bc::payload_of(op_word) + sub;
    if (w >= init_.size() || initialised_[w]) return;
    set_init(w, static_cast<std::uint16_t>(value));
  }

  // ---- Pass 2: operands ------------------------------------------------------------------------------

  std::int32_t ref_word(const IndirectRef& r, SourcePos pos) {
    Address a;
    a.type = r.type;
    a.file = r.file;
    a.element = r.element;
    a.word = r.word;
    std::string err;
    auto loc = layout_.locate(a, &err);
    if (!loc || loc->vtype != ValueType::Int16) {
      error(pos, "indirect reference [" + to_string(r) + "]: " + (loc ? "must be a 16-bit integer word" : err));
      return -1;
    }
    return static_cast<std::int32_t>(loc->word);
  }

  std::uint32_t dyn_operand(const Address& a, bool file_start, SourcePos pos) {
    DynOperand d;
    d.address = a;
    d.type = a.type;
    d.vtype = a.has_bit() || is_structured(a.type) ? ValueType::Int16 : value_type_of(a.type);
    d.indexed = a.indexed && !file_start;
    d.bit_offset = a.bit_offset_form;
    d.file = a.file;
    d.element = a.element;
    d.word = a.word;
    d.bit = a.bit;
    if (a.indirect_file()) d.ptr_file = ref_word(*a.indirect_file(), pos);
    if (a.indirect_element()) d.ptr_element = ref_word(*a.indirect_element(), pos);
    if (a.indirect_word()) d.ptr_word = ref_word(*a.indirect_word(), pos);
    if (a.indirect_bit()) d.ptr_bit = ref_word(*a.indirect_bit(), pos);
    if (is_mfile(a.type)) {
      d.mfile = true;
      d.access_row = current_row_;
      d.which = a.type == FileType::M0 ? MFile::M0 : MFile::M1;
      if (a.is_indirect() || (a.indexed && !file_start))
        error(pos, "indexed or indirect M0/M1 addresses are not supported: " + to_string(a));
      const SlotConfig* s = slot_config(a.element);
      const int size = s ? (d.which == MFile::M0 ? m0_words(*s) : m1_words(*s)) : 0;
      if (!s || size <= 0)
        error(pos, to_string(a) + ": slot " + std::to_string(a.element) + " has no module with an " +
                       std::string(file_letter(a.type)) + " file");
      else if (a.word_in_element() >= size)
        error(pos, to_string(a) + " is beyond the module's " + std::string(file_letter(a.type)) + " file (" +
                       std::to_string(size) + " words)");
    } else if (is_function_file(a.type)) {
      error(pos, "function file addresses cannot be indexed or indirect: " + to_string(a));
    } else if (!a.indirect_file()) {
      // The file itself must exist even when the element is computed at run time.
      if (!is_io(a.type) && a.type != FileType::Status) {
        const auto& f = layout_.files[a.file];
        if (!f.present || f.type != a.type) error(pos, to_string(a) + ": the file does not exist");
      }
    }
    out_.dyn.push_back(d);
    return bc::operand(bc::kDyn, static_cast<std::uint32_t>(out_.dyn.size() - 1));
  }

  bool needs_dyn(const Address& a, bool file_start) const {
    return is_mfile(a.type) || a.is_indirect() || (a.indexed && !file_start);
  }

  // A value operand (Source, Dest, File). Sets `is_float` when it is a float.
  std::uint32_t value_operand(const Operand& op, bool dest, bool file_start, bool& is_float, SourcePos pos) {
    if (op.kind == Operand::Kind::Symbol && !op.resolved) {
      error(pos, "unknown symbol '" + op.spelling + "'");
      return 0;
    }
    if (!op.is_address()) {
      if (dest || file_start) {
        error(pos, "'" + op.text() + "' is a constant; this operand must be an address");
        return 0;
      }
      if (op.kind == Operand::Kind::Float) {
        is_float = true;
        out_.float_constants.push_back(static_cast<float>(op.real));
        return bc::operand(bc::kKFloat, static_cast<std::uint32_t>(out_.float_constants.size() - 1));
      }
      std::int64_t v = op.integer;
      // A hex constant 0x8000-0xFFFF is a 16-bit pattern (masks such as 0xFF00), so it means the
      // signed word with those bits, as the SLC stores it.
      const bool hex = op.spelling.size() > 2 && (op.spelling[1] == 'x' || op.spelling[1] == 'X' ||
                                                  op.spelling.back() == 'h' || op.spelling.back() == 'H');
      if (hex && v >= 0x8000 && v <= 0xFFFF) v -= 0x10000;
      if (v >= bc::kImmMin && v <= bc::kImmMax) return bc::imm(static_cast<std::int32_t>(v));
      out_.int_constants.push_back(v);
      return bc::operand(bc::kKInt, static_cast<std::uint32_t>(out_.int_constants.size() - 1));
    }
    const Address& a = op.address;
    if (a.has_bit()) {
      error(pos, to_string(a) + " is a bit; this operand takes a word");
      return 0;
    }
    if (needs_dyn(a, file_start)) {
      const std::uint32_t o = dyn_operand(a, file_start, pos);
      is_float = is_float || out_.dyn.back().vtype == ValueType::Float32;
      return o;
    }
    std::string err;
    auto loc = layout_.locate(a, &err, file_start);
    if (!loc) {
      error(pos, err);
      return 0;
    }
    switch (loc->vtype) {
      case ValueType::Int16: return bc::operand(bc::kWord, loc->word);
      case ValueType::Int32: return bc::operand(bc::kLong, loc->word);
      case ValueType::Float32: is_float = true; return bc::operand(bc::kFloat, loc->word);
    }
    return 0;
  }

  // CPT: compiles the expression's operands and records it in out_.exprs; the instruction's
  // operand is IMM(index). The expression computes in floating point when the destination
  // (`is_float` on entry), an operand or a constant is F, or it uses a float-only function.
  std::uint32_t expression_operand(const Operand& op, bool is_float, std::uint32_t& flags, SourcePos pos) {
    ExpressionError err;
    auto items = parse_expression(op.spelling, err);
    if (!items) {
      error(pos, "CPT expression: " + err.message);
      return 0;
    }
    if (expr_stack_depth(*items) > kMaxExprStack) {
      error(pos, "CPT expression needs too deep an evaluation stack");
      return 0;
    }
    CompiledExpr ce;
    for (const auto& it : *items) {
      CompiledExprStep step{it.code, 0};
      if (it.code == ExprCode::Push) {
        Operand atom;
        atom.spelling = it.text;
        NumberValue v;
        if (parse_number_text(it.text, v)) {
          atom.kind = v.is_float ? Operand::Kind::Float : Operand::Kind::Integer;
          atom.integer = v.integer;
          atom.real = v.real;
        } else if (auto a = parse_address(it.text)) {
          atom.kind = Operand::Kind::Address;
          atom.address = *a;
        } else {
          error(pos, "CPT expression: '" + it.text + "' is not an address or a constant");
          return 0;
        }
        step.operand = value_operand(atom, false, false, is_float, pos);
        if (bc::mode_of(step.operand) == bc::kDyn) flags |= bc::kFlagDyn;
      } else if (expr_is_float_function(it.code)) {
        is_float = true;
      }
      ce.steps.push_back(step);
    }
    ce.float_mode = is_float;
    out_.exprs.push_back(std::move(ce));
    return bc::imm(static_cast<std::int32_t>(out_.exprs.size() - 1));
  }

  std::uint32_t bit_operand(const Operand& op, SourcePos pos) {
    if (op.kind == Operand::Kind::Symbol && !op.resolved) {
      error(pos, "unknown symbol '" + op.spelling + "'");
      return 0;
    }
    if (!op.is_address() || !op.address.has_bit()) {
      error(pos, "'" + op.text() + "' is not a bit address");
      return 0;
    }
    const Address& a = op.address;
    if (needs_dyn(a, false)) return dyn_operand(a, false, pos);
    std::string err;
    auto loc = layout_.locate(a, &err);
    if (!loc) {
      error(pos, err);
      return 0;
    }
    return bc::bit_operand(loc->word, loc->bit);
  }

  std::uint32_t element_operand(const Operand& op, OperandKind kind, SourcePos pos, FileType& type) {
    if (op.kind == Operand::Kind::Symbol && !op.resolved) {
      error(pos, "unknown symbol '" + op.spelling + "'");
      return 0;
    }
    const Address& a = op.address;
    const bool ok_type = op.is_address() &&
                         ((kind == OperandKind::Timer && a.type == FileType::Timer) ||
                          (kind == OperandKind::Counter && a.type == FileType::Counter) ||
                          (kind == OperandKind::Control && a.type == FileType::Control) ||
                          (kind == OperandKind::Resettable && is_structured(a.type)));
    if (!ok_type || a.has_bit() || a.word > 0 || a.indirect_word()) {
      error(pos, "'" + op.text() + "' is not a " +
                     (kind == OperandKind::Timer     ? "timer (T) element"
                      : kind == OperandKind::Counter ? "counter (C) element"
                      : kind == OperandKind::Control ? "control (R) element"
                                                     : "timer, counter or control element"));
      return 0;
    }
    type = a.type;
    if (needs_dyn(a, false)) return dyn_operand(a, false, pos);
    std::string err;
    auto loc = layout_.locate(a, &err);
    if (!loc) {
      error(pos, err);
      return 0;
    }
    return bc::operand(bc::kWord, loc->word);
  }

  std::uint32_t slot_word_operand(const Instruction& in, const Operand& op, SourcePos pos) {
    if (!op.is_address() || !is_io(op.address.type) || op.address.is_indirect() || op.address.indexed) {
      error(pos, "'" + op.text() + "' must name a slot word such as I:1.0 or O:2.0");
      return 0;
    }
    const Address& a = op.address;
    const bool input = a.type == FileType::Input;
    if ((in.opcode == Opcode::IIM) != input) {
      error(pos, std::string(spec(in.opcode).mnemonic) + " takes an " + (in.opcode == Opcode::IIM ? "I:" : "O:") +
                     " slot word");
      return 0;
    }
    const auto& slots = input ? layout_.input_slots : layout_.output_slots;
    const std::int64_t len = literal(in, 2);
    const int word = a.word_in_element();
    if (a.element < 0 || a.element >= kMaxSlots || !slots[static_cast<std::size_t>(a.element)].present ||
        word + len > static_cast<std::int64_t>(slots[static_cast<std::size_t>(a.element)].words)) {
      error(pos, to_string(a) + " with length " + std::to_string(len) + " is outside the slot's " +
                     (input ? "input" : "output") + " image");
      return 0;
    }
    return bc::imm(a.element * 256 + word);
  }

  // ---- Pass 2: instructions ------------------------------------------------------------------------

  void emit(std::uint32_t w) { out_.code.push_back(w); }

  void emit_instruction(const Instruction& in, bool mcr_unconditional) {
    const InstructionSpec& sp = spec(in.opcode);
    std::optional<int> module_slot;
    if (is_module_instruction(in.opcode)) {
      std::optional<std::string> refusal =
          opts_.module_instruction ? opts_.module_instruction(in) : module_instruction_unsupported(in.opcode);
      if (refusal) {
        error(in.pos, *refusal);
        return;
      }
      module_slot = module_instruction_slot(in);
      if (!module_slot || *module_slot < 0 || *module_slot >= kMaxSlots) {
        error(in.pos, std::string(sp.mnemonic) + " does not name a chassis slot (0-30) for its module");
        return;
      }
    }
    if (in.operands.size() != sp.operand_count) {
      error(in.pos, std::string(sp.mnemonic) + " takes " + std::to_string(sp.operand_count) + " operand(s), not " +
                        std::to_string(in.operands.size()));
      return;
    }
    if (in.opcode == Opcode::END) {
      emit(bc::header(Op::END, 0, 0, 0));
      return;
    }
    if (in.opcode == Opcode::RET && cur_file_ == 2) {
      error(in.pos, "RET in the main program file (2); RET returns from a subroutine");
      return;
    }
    std::uint32_t flags = 0;
    std::uint32_t aux = 0;
    bool any_float = false;
    bool bad_int_operand = false;  // a float or long where only 16-bit words are allowed
    // The operand words: a scratch vector that keeps its capacity (one allocation per instruction
    // otherwise). emit_instruction does not call itself.
    std::vector<std::uint32_t>& ops = ops_scratch_;
    ops.clear();
    FileType element_type = FileType::Timer;
    for (std::size_t i = 0; i < sp.operand_count; ++i) {
      const OperandSpec& os = sp.operands[i];
      const Operand& op = in.operands[i];
      const SourcePos pos = op.pos.line ? op.pos : in.pos;
      current_row_ = os.mfile;
      if (op.is_address() && is_mfile(op.address.type) && os.mfile == MFileAccess::NoM) {
        error(pos, std::string(sp.mnemonic) + " cannot use an M0/M1 address as its " + std::string(os.label));
        ops.push_back(0);
        continue;
      }
      std::uint32_t w = 0;
      switch (os.kind) {
        case OperandKind::Bit: w = bit_operand(op, pos); break;
        case OperandKind::Source:
        case OperandKind::Dest:
        case OperandKind::WordSource:
        case OperandKind::WordDest:
        case OperandKind::File: {
          bool f = false;
          w = value_operand(op, is_dest_kind(os.kind), os.kind == OperandKind::File, f, pos);
          any_float = any_float || f;
          // The checker refuses these first; this keeps an unchecked program from running one.
          if (f && (os.kind == OperandKind::WordSource || os.kind == OperandKind::WordDest))
            error(pos, std::string(sp.mnemonic) + " works on integer words; it takes no float operands");
          const bool is_long = bc::mode_of(w) == bc::kLong ||
                               (bc::mode_of(w) == bc::kDyn && out_.dyn[bc::payload_of(w)].vtype == ValueType::Int32);
          if (f || is_long) bad_int_operand = true;
          break;
        }
        case OperandKind::Timer:
        case OperandKind::Counter:
        case OperandKind::Control:
        case OperandKind::Resettable: w = element_operand(op, os.kind, pos, element_type); break;
        case OperandKind::TimeBase: {
          const double tb = op.kind == Operand::Kind::Float     ? op.real
                            : op.kind == Operand::Kind::Integer ? static_cast<double>(op.integer)
                                                                : -1.0;
          if (tb == 1.0) {
            w = bc::imm(100);
            flags |= bc::kFlagA;
          } else if (std::fabs(tb - 0.01) < 1e-9) {
            w = bc::imm(1);
          } else if (std::fabs(tb - 0.001) < 1e-12 && proc_.has_millisecond_timebase()) {
            // MicroLogix 1100-1500: ACC counts milliseconds (kFlagB selects the 1 ms stamp; the
            // immediate 0 tells the disassembler which base it is).
            w = bc::imm(0);
            flags |= bc::kFlagB;
          } else {
            error(pos, "time base must be 1.0 or 0.01 seconds (RM 2-8), not '" + op.text() + "'");
          }
          break;
        }
        case OperandKind::Literal:
        case OperandKind::Label:
        case OperandKind::ProgramFile:
          if (op.kind != Operand::Kind::Integer) {
            error(pos, std::string(sp.mnemonic) + " " + std::string(os.label) + " must be an integer constant");
          } else if (op.integer < os.min || op.integer > os.max) {
            error(pos, std::string(sp.mnemonic) + " " + std::string(os.label) + " must be " + std::to_string(os.min) +
                           "-" + std::to_string(os.max));
          } else if (op.integer >= bc::kImmMin && op.integer <= bc::kImmMax) {
            w = bc::imm(static_cast<std::int32_t>(op.integer));
          } else {
            // A literal wider than an immediate (the 30-slot mask of IID/IIE/RPI): a constant.
            out_.int_constants.push_back(op.integer);
            w = bc::operand(bc::kKInt, static_cast<std::uint32_t>(out_.int_constants.size() - 1));
          }
          break;
        case OperandKind::SlotWord: w = slot_word_operand(in, op, pos); break;
        case OperandKind::Expression: w = expression_operand(op, any_float, flags, pos); break;
        case OperandKind::String: {
          // An ST element: the handler reads and writes its 42 words through file_span.
          bool f = false;
          w = value_operand(op, false, true, f, pos);
          break;
        }
        case OperandKind::Buffer:
        case OperandKind::ControlBlock3:
        case OperandKind::ControlBlock70:
        case OperandKind::ControlBlock23:
          // Only module instructions and the PID have these, and a hook that accepted one owns its encoding;
          // the generic encoding keeps the address for the listing.
          if (op.is_address() && !is_mfile(op.address.type) && !needs_dyn(op.address, false)) {
            bool f = false;
            w = value_operand(op, false, false, f, pos);
          } else if (op.is_address()) {
            w = dyn_operand(op.address, false, pos);
          }
          break;
        // MSG (docs/semantics.md "MSG"): the keywords as their codes; the control block and the data
        // as direct word indexes (check refuses anything else); the target goes into the control block.
        case OperandKind::MessageCommand:
        case OperandKind::MessageDevice:
        case OperandKind::MessageRoute:
          if (auto code = op.kind == Operand::Kind::Symbol ? keyword_code(os.kind, op.spelling) : std::nullopt)
            w = bc::imm(*code);
          else if (os.kind == OperandKind::MessageCommand && op.kind == Operand::Kind::Integer &&
                   modbus::is_command(static_cast<int>(op.integer)))
            w = bc::imm(static_cast<std::int32_t>(op.integer));  // a Modbus MSG's command (check holds the form)
          else
            error(pos, std::string(sp.mnemonic) + " " + std::string(os.label) + ": '" + op.text() + "' is not one of its words");
          break;
        case OperandKind::MessageBlock:
        case OperandKind::MessageData:
        case OperandKind::MessageElement:
          if (op.is_address() && !is_mfile(op.address.type) && !needs_dyn(op.address, false)) {
            bool f = false;
            // A Modbus bit command's data is a bit address (B3:0/4): the word here, the bit in MG word 12
            // (init_micrologix_message).
            Operand word_op = op;
            if (os.kind == OperandKind::MessageData && in.opcode == Opcode::MSG_ML) word_op.address.bit = -1;
            w = value_operand(word_op, false, true, f, pos);
          } else {
            error(pos, std::string(sp.mnemonic) + " " + std::string(os.label) + " must be a direct data table address");
          }
          break;
        case OperandKind::RemoteAddress: w = bc::imm(0); break;
        // The MicroLogix MSG's target: a node number, or the RI element (its word index, for the listing:
        // the processor finds it through MG word 24, which the setup holds).
        case OperandKind::MessageTarget:
          if (op.kind == Operand::Kind::Integer) {
            w = bc::imm(static_cast<std::int32_t>(op.integer));
          } else if (op.is_address() && !needs_dyn(op.address, false)) {
            bool f = false;
            w = value_operand(op, false, true, f, pos);
          } else {
            error(pos, std::string(sp.mnemonic) + " " + std::string(os.label) + " must be a node number or an RI element");
          }
          break;
      }
      if (bc::mode_of(w) == bc::kDyn) flags |= bc::kFlagDyn;
      ops.push_back(w);
    }

    // Operand-type rules that depend on the instruction.
    switch (in.opcode) {
      case Opcode::BSL:
      case Opcode::BSR:
      case Opcode::SQO:
      case Opcode::SQC:
      case Opcode::SQL:
      case Opcode::FFL:
      case Opcode::FFU:
      case Opcode::LFL:
      case Opcode::LFU:
      case Opcode::IIM:
      case Opcode::IOM:
        if (bad_int_operand)
          error(in.pos, std::string(sp.mnemonic) + " works on 16-bit words; F and L operands are not allowed");
        break;
      default: break;
    }
    if (any_float) flags |= bc::kFlagFloat;
    if (in.opcode == Opcode::RES) aux = static_cast<std::uint32_t>(element_type);
    if (in.opcode == Opcode::COP && ops.size() == 3) {
      if (const std::uint32_t words = direct_copy_words(ops[0], ops[1], ops[2])) {
        flags |= bc::kFlagB;
        aux = words;
      }
    }
    if (in.opcode == Opcode::MCR && mcr_unconditional) flags |= bc::kFlagA;
    // A module instruction carries its module's slot in aux, and DYN so its M-file time is
    // folded into the scan and a fault it raises stops the scan.
    if (module_slot) {
      aux = static_cast<std::uint32_t>(*module_slot);
      flags |= bc::kFlagDyn;
    }

    // Literals that initialise their element (unless DATA did).
    switch (in.opcode) {
      case Opcode::TON:
      case Opcode::TOF:
      case Opcode::RTO:
        init_literal(ops[0], 1, literal(in, 2));
        init_literal(ops[0], 2, literal(in, 3));
        break;
      case Opcode::CTU:
      case Opcode::CTD:
        init_literal(ops[0], 1, literal(in, 1));
        init_literal(ops[0], 2, literal(in, 2));
        break;
      case Opcode::BSL:
      case Opcode::BSR: init_literal(ops[1], 1, literal(in, 3)); break;
      case Opcode::SQO:
      case Opcode::SQC:
        init_literal(ops[3], 1, literal(in, 4));
        init_literal(ops[3], 2, literal(in, 5));
        break;
      case Opcode::SQL:
      case Opcode::FFL:
      case Opcode::FFU:
      case Opcode::LFL:
      case Opcode::LFU:
        init_literal(ops[2], 1, literal(in, 3));
        init_literal(ops[2], 2, literal(in, 4));
        break;
      case Opcode::FBC:
      case Opcode::DDT:
        // The box's lengths and positions are the two control elements' LEN and POS (RM 7-18).
        init_literal(ops[3], 1, literal(in, 4));
        init_literal(ops[3], 2, literal(in, 5));
        init_literal(ops[6], 1, literal(in, 7));
        init_literal(ops[6], 2, literal(in, 8));
        break;
      // ASCII channel instructions: the box's length and display fields are the control element's
      // words 1 (LEN) and 2 (POS), as exported (docs/semantics.md "ASCII and strings").
      case Opcode::ARD:
      case Opcode::ARL:
      case Opcode::AWA:
      case Opcode::AWT:
        init_literal(ops[2], 1, literal(in, 3));
        init_literal(ops[2], 2, literal(in, 4));
        break;
      case Opcode::ABL:
      case Opcode::ACB: init_literal(ops[1], 2, literal(in, 2)); break;
      case Opcode::AHL: init_literal(ops[3], 2, literal(in, 4)); break;
      case Opcode::BTR:
      case Opcode::BTW:
        // "A BTR or BTW instruction writes information into its control structure address ... when
        // the instruction is entered" (1747-SN p. 5-6): Table 5.1 word 0 holds RW (bit 7, 1 = BTR),
        // the rack (bits 6-4), group (bits 3-1) and slot (bit 0); word 1 the requested word count.
        init_literal(ops[0], 0,
                     (in.opcode == Opcode::BTR ? 0x0080 : 0) | ((literal(in, 3) & 7) << 4) |
                         ((literal(in, 4) & 7) << 1) | (literal(in, 5) & 1));
        init_literal(ops[0], 1, literal(in, 6));
        break;
      case Opcode::MSG:
      case Opcode::MSG_502: init_message_block(in, ops); break;
      case Opcode::MSG_ML: init_micrologix_message(in, ops); break;
      default: break;
    }

    // Jump and call targets are filled in once every label and file is placed.
    std::uint32_t extra = 0;
    if (in.opcode == Opcode::JMP || in.opcode == Opcode::JSR) extra = 1;
    emit(bc::header(to_op(in.opcode), static_cast<std::uint32_t>(ops.size()) + extra, flags, aux));
    for (auto w : ops) emit(w);
    if (in.opcode == Opcode::JMP) {
      jumps_.push_back({static_cast<std::uint32_t>(out_.code.size()), static_cast<int>(literal(in, 0)), in.pos, cur_file_, cur_rung_});
      emit(bc::operand(bc::kTarget, 0));
    } else if (in.opcode == Opcode::JSR) {
      calls_.push_back({static_cast<std::uint32_t>(out_.code.size()), static_cast<int>(literal(in, 0)), in.pos, cur_file_, cur_rung_});
      emit(bc::operand(bc::kTarget, 0));
    }
  }

  void emit_elements(const std::vector<RungElement>& elems, int depth, bool mcr_unconditional) {
    for (const auto& e : elems) {
      if (e.kind == RungElement::Kind::Instruction) {
        emit_instruction(e.instruction, mcr_unconditional);
        continue;
      }
      if (depth + 1 > kMaxBranchDepth) {
        error(e.pos(), "branches nested deeper than " + std::to_string(kMaxBranchDepth) + " levels");
        return;
      }
      out_.max_branch_depth = std::max(out_.max_branch_depth, depth + 1);
      emit(bc::header(Op::BST, 0, 0, 0));
      for (std::size_t l = 0; l < e.legs.size(); ++l) {
        if (l > 0) emit(bc::header(Op::NXB, 0, 0, 0));
        emit_elements(e.legs[l], depth + 1, false);
      }
      emit(bc::header(Op::BND, 0, 0, 0));
    }
  }

  static bool contains(const std::vector<RungElement>& elems, Opcode op) {
    for (const auto& e : elems) {
      if (e.kind == RungElement::Kind::Instruction) {
        if (e.instruction.opcode == op) return true;
      } else {
        for (const auto& leg : e.legs)
          if (contains(leg, op)) return true;
      }
    }
    return false;
  }

  void emit_file(const ProgramFile& f) {
    cur_file_ = f.number;
    CompiledFile cf;
    cf.number = f.number;
    cf.begin = static_cast<std::uint32_t>(out_.code.size());
    cf.rungs.reserve(std::min<std::size_t>(f.rungs.size(), 0x10000));
    std::map<int, std::uint32_t> labels;
    std::map<int, SourcePos> label_pos;
    const std::size_t first_jump = jumps_.size();
    if (f.rungs.size() > 0xFFFF) error(f.pos, "more than 65535 rungs in one file");
    for (std::size_t r = 0; r < f.rungs.size() && r <= 0xFFFF; ++r) {
      cur_rung_ = static_cast<int>(r);
      const Rung& rung = f.rungs[r];
      const std::uint32_t sor = static_cast<std::uint32_t>(out_.code.size());
      cf.rungs.push_back({sor, rung.pos});
      const bool has_mcr = contains(rung.elements, Opcode::MCR);
      emit(bc::header(Op::SOR, 0, has_mcr ? bc::kFlagA : 0, static_cast<std::uint32_t>(r)));
      // Every LBL of the rung makes the rung a jump target (the checker wants it first).
      std::vector<const RungElement*>& stack = element_stack_;
      stack.clear();
      for (const auto& e : rung.elements) stack.push_back(&e);
      while (!stack.empty()) {
        const RungElement* e = stack.back();
        stack.pop_back();
        if (e->kind == RungElement::Kind::Branch) {
          for (const auto& leg : e->legs)
            for (const auto& x : leg) stack.push_back(&x);
        } else if (e->instruction.opcode == Opcode::LBL) {
          const int label = static_cast<int>(literal(e->instruction, 0));
          if (labels.count(label))
            error(e->instruction.pos, "label " + std::to_string(label) + " is defined twice in file " +
                                          std::to_string(f.number) + " (line " +
                                          std::to_string(label_pos[label].line) + ")");
          labels[label] = sor;
          label_pos[label] = e->instruction.pos;
        }
      }
      const bool mcr_unconditional =
          rung.elements.size() == 1 && rung.elements[0].kind == RungElement::Kind::Instruction &&
          rung.elements[0].instruction.opcode == Opcode::MCR;
      emit_elements(rung.elements, 0, mcr_unconditional);
    }
    cur_rung_ = -1;
    emit(bc::header(Op::EOF_, 0, 0, 0));
    cf.end = static_cast<std::uint32_t>(out_.code.size());
    for (std::size_t j = first_jump; j < jumps_.size(); ++j) {
      auto it = labels.find(jumps_[j].target);
      if (it == labels.end()) {
        errors_.push_back({jumps_[j].file, jumps_[j].rung, jumps_[j].pos,
                           "JMP to label " + std::to_string(jumps_[j].target) + ", which file " +
                               std::to_string(f.number) + " does not define"});
        continue;
      }
      out_.code[jumps_[j].at] = bc::operand(bc::kTarget, it->second);
    }
    out_.files.push_back(std::move(cf));
  }

  void emit_program() {
    out_.file_index.fill(-1);
    std::vector<const ProgramFile*> files;
    for (const auto& f : prog_.files) {
      if (f.number < 2 || f.number > 255) {
        error(f.pos, "program file " + std::to_string(f.number) + " is outside 2-255");
        continue;
      }
      files.push_back(&f);
    }
    std::sort(files.begin(), files.end(), [](auto* a, auto* b) { return a->number < b->number; });
    if (files.empty() || files.front()->number != 2) {
      error({}, "the program has no main program file (LADDER 2)");
      return;
    }
    // The code is allocated once at about its size rather than grown by doubling (each doubling
    // copied all of it and left the old block behind: 5% of loading a 1M-rung program,
    // docs/performance.md "Load time"). The estimate is a header and a word per operand for each
    // instruction; a sixteenth more covers what it misses, and capacity not written to is never
    // touched.
    out_.code.reserve(code_words_ + code_words_ / 16);
    for (const auto* f : files) {
      out_.file_index[static_cast<std::size_t>(f->number)] = static_cast<std::int16_t>(out_.files.size());
      emit_file(*f);
    }
    for (const auto& c : calls_) {
      const CompiledFile* target = out_.file(c.target);
      if (!target) {
        errors_.push_back({c.file, c.rung, c.pos, "JSR to program file " + std::to_string(c.target) + ", which does not exist"});
        continue;
      }
      out_.code[c.at] = bc::operand(bc::kTarget, target->begin);
    }
  }

  // DATALOG queues: each field resolved to its place in the data table (vm/ml_data_log.h).
  void compile_data_logs() {
    if (!layout_.function_file(FunctionFile::DLS).present) return;
    for (const auto& q : prog_.data_logs) {
      CompiledDataLog c;
      c.number = q.number;
      c.records = q.records;
      c.date = q.date;
      c.time = q.time;
      c.delimiter = q.delimiter;
      for (std::size_t i = 0; i < q.fields.size(); ++i) {
        std::string err;
        auto loc = layout_.locate(q.fields[i], &err);
        if (!loc) {
          error(q.field_pos[i], "DATALOG " + std::to_string(q.number) + ": " + err);
          continue;
        }
        c.fields.push_back(*loc);
      }
      out_.data_logs.push_back(std::move(c));
    }
  }

  const Program& prog_;
  const CompileOptions& opts_;
  ProcessorModel proc_;
  std::vector<CompileError> errors_;
  std::array<FileUse, 256> use_{};
  DataTableLayout layout_;
  std::vector<std::uint16_t> init_;
  std::vector<bool> initialised_;
  CompiledProgram out_;
  std::vector<Fixup> jumps_;
  std::vector<Fixup> calls_;
  int cur_file_ = -1;
  int cur_rung_ = -1;
  bool reads_checksum_ = false;  // the program has an RPC, so out_.program_checksum is computed
  std::array<bool, kFunctionFileCount> named_function_files_{};  // by FunctionFile: an address names it
  std::size_t code_words_ = 0;   // the code's expected size, counted by size_files
  std::vector<std::uint32_t> ops_scratch_;           // emit_instruction's operand words
  std::vector<const RungElement*> element_stack_;    // emit_file's walk of a rung for its LBLs
  MFileAccess current_row_ = MFileAccess::OtherM;  // access-time row of the operand being compiled
};

}  // namespace

CompileResult compile(const Program& program, const CompileOptions& options) {
  return Compiler(program, options).run();
}

std::uint16_t program_checksum(const Program& program) {
  std::vector<const ProgramFile*> files;
  for (const ProgramFile& f : program.files) files.push_back(&f);
  std::sort(files.begin(), files.end(), [](const ProgramFile* a, const ProgramFile* b) { return a->number < b->number; });
  std::string image;
  for (const ProgramFile* f : files) {
    image += "LADDER " + std::to_string(f->number) + "\n";
    for (const Rung& r : f->rungs) image += format_rung(r) + "\n";
  }
  const std::uint32_t crc = crc32(image.data(), image.size());
  return static_cast<std::uint16_t>((crc >> 16) ^ (crc & 0xFFFFu));
}

}  // namespace softslc
