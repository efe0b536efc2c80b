// The loaded program: what an RSLogix 500 library export (.SLC) says, as plain values.
//
// The loader builds a Program from text; the checker validates it against the instruction table
// and the processor; the formatter writes it back as canonical export text; the compiler turns it
// into bytecode. Every node keeps the position it came from so any later stage can report a
// positioned diagnostic. A Program is either fully loaded or not produced at all: the loader
// never hands out a half-built one.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "instructions/instruction_table.h"
#include "instructions/processor.h"
#include "parser/address.h"
#include "parser/automax_def.h"

namespace softslc {

// A 1-based line and column in the source file.
struct SourcePos {
  std::uint32_t line = 0;
  std::uint32_t column = 0;
  bool operator==(const SourcePos&) const = default;
};

// One operand of an instruction as written.
//
// A program holds about five operands per rung, so their size is most of a large program's memory
// (docs/performance.md "Load time"): the one-byte members and the position fill the gap after the
// 24-byte Address instead of each opening an 8-byte slot of its own, and a symbol's name is its
// spelling rather than a second string: 88 bytes.
struct Operand {
  enum class Kind : std::uint8_t { Address, Integer, Float, Symbol, Expression };
  Address address;             // Kind::Address, and Kind::Symbol once resolved
  Kind kind = Kind::Integer;
  bool resolved = false;       // Kind::Symbol: address holds the symbol's address
  SourcePos pos;
  std::int64_t integer = 0;    // Kind::Integer
  double real = 0.0;           // Kind::Float
  // Kind::Symbol: the symbol's name; Kind::Expression: the CPT expression, blanks collapsed;
  // Kind::Integer and Kind::Float: the number as written (fmt keeps a hexadecimal constant hex).
  // Kind::Address: empty as the loader leaves it — the canonical spelling is to_string(address),
  // built where a message needs it (storing it cost a to_string per address, 4% of loading a
  // large program, docs/performance.md "Load time"); an operand made elsewhere (a CPT atom) may
  // carry its text here. Read it through text() where the operand may be an address.
  std::string spelling;

  // True when the operand designates a data-table location (directly or through a symbol).
  bool is_address() const { return kind == Kind::Address || (kind == Kind::Symbol && resolved); }
  bool is_number() const { return kind == Kind::Integer || kind == Kind::Float; }
  // The operand's text for a message: `spelling`, or for an address without one its canonical
  // spelling ("T4:0/DN").
  std::string text() const;
  // Semantic equality (ignores spelling and position).
  bool same_as(const Operand& o) const;
};

// The operands of one instruction: one allocation of exactly their count, a pointer and a count
// (12 bytes used, where a std::vector took 24 and kept a capacity the loader never used). Read like
// a vector (size, [], range-for); only the loader fills one, with assign_moved. Copies are deep.
// The storage comes from std::allocator, not new[], so it carries no array-size cookie: one
// operand is a 96-byte heap chunk, not 112.
class OperandList {
 public:
  OperandList() = default;
  OperandList(const OperandList& o) { copy_from(o); }
  OperandList(OperandList&& o) noexcept : data_(std::exchange(o.data_, nullptr)), size_(std::exchange(o.size_, 0)) {}
  OperandList& operator=(const OperandList& o) {
    if (this != &o) {
      release();
      copy_from(o);
    }
    return *this;
  }
  OperandList& operator=(OperandList&& o) noexcept {
    if (this != &o) {
      release();
      data_ = std::exchange(o.data_, nullptr);
      size_ = std::exchange(o.size_, 0);
    }
    return *this;
  }
  ~OperandList() { release(); }

  // Replaces the contents with [first, last), moved.
  void assign_moved(Operand* first, Operand* last) {
    release();
    const auto n = static_cast<std::size_t>(last - first);
    if (n == 0) return;
    data_ = std::allocator<Operand>().allocate(n);
    std::uninitialized_move(first, last, data_);
    size_ = static_cast<std::uint32_t>(n);
  }

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  Operand& operator[](std::size_t i) { return data_[i]; }
  const Operand& operator[](std::size_t i) const { return data_[i]; }
  Operand& front() { return data_[0]; }
  const Operand& front() const { return data_[0]; }
  Operand& back() { return data_[size_ - 1]; }
  const Operand& back() const { return data_[size_ - 1]; }
  Operand* begin() { return data_; }
  Operand* end() { return data_ + size_; }
  const Operand* begin() const { return data_; }
  const Operand* end() const { return data_ + size_; }
  const Operand* data() const { return data_; }

 private:
  void copy_from(const OperandList& o) {
    if (o.size_ == 0) return;
    Operand* p = std::allocator<Operand>().allocate(o.size_);
    try {
      std::uninitialized_copy(o.begin(), o.end(), p);
    } catch (...) {
      std::allocator<Operand>().deallocate(p, o.size_);
      throw;
    }
    data_ = p;
    size_ = o.size_;
  }
  void release() {
    if (!data_) return;
    std::destroy(data_, data_ + size_);
    std::allocator<Operand>().deallocate(data_, size_);
    data_ = nullptr;
    size_ = 0;
  }
  Operand* data_ = nullptr;
  std::uint32_t size_ = 0;
};

// The opcode comes last so that a RungElement can place its kind in the bytes after it, and the
// operand list is [[no_unique_address]] so the position fills the 4 bytes after its count: 24
// bytes.
struct Instruction {
  [[no_unique_address]] OperandList operands;
  SourcePos pos;
  Opcode opcode = Opcode::XIC;
};

// The legs of a branch, held out of line: only a branch has them, and in place the vector was 24
// of an element's 64 bytes. Read like a vector of legs; an instruction's holder is empty (no
// allocation). Copies are deep. A template only so that it can name RungElement before that is
// complete.
template <typename Element>
class BranchLegs {
 public:
  using Leg = std::vector<Element>;
  BranchLegs() = default;
  BranchLegs(const BranchLegs& o) : legs_(o.legs_ ? std::make_unique<std::vector<Leg>>(*o.legs_) : nullptr) {}
  BranchLegs(BranchLegs&&) noexcept = default;
  BranchLegs& operator=(const BranchLegs& o) {
    if (this != &o) legs_ = o.legs_ ? std::make_unique<std::vector<Leg>>(*o.legs_) : nullptr;
    return *this;
  }
  BranchLegs& operator=(BranchLegs&&) noexcept = default;
  ~BranchLegs() = default;

  std::size_t size() const { return legs_ ? legs_->size() : 0; }
  bool empty() const { return size() == 0; }
  Leg& operator[](std::size_t i) { return (*legs_)[i]; }
  const Leg& operator[](std::size_t i) const { return (*legs_)[i]; }
  Leg& back() { return legs_->back(); }
  const Leg& back() const { return legs_->back(); }
  Leg* begin() { return legs_ ? legs_->data() : nullptr; }
  Leg* end() { return legs_ ? legs_->data() + legs_->size() : nullptr; }
  const Leg* begin() const { return legs_ ? legs_->data() : nullptr; }
  const Leg* end() const { return legs_ ? legs_->data() + legs_->size() : nullptr; }
  Leg& emplace_back() { return vec().emplace_back(); }
  void push_back(Leg&& leg) { vec().push_back(std::move(leg)); }
  void reserve(std::size_t n) { vec().reserve(n); }
  void clear() { legs_.reset(); }

 private:
  std::vector<Leg>& vec() {
    if (!legs_) legs_ = std::make_unique<std::vector<Leg>>();
    return *legs_;
  }
  std::unique_ptr<std::vector<Leg>> legs_;
};

// A rung element is an instruction or a branch (BST leg NXB leg ... BND).
//
// A program holds about 3.6 elements per rung: the element's position is its instruction's (a
// branch keeps the BST's there), its kind sits in the instruction's tail padding, and a branch's
// legs are out of line, so an element is 32 bytes (docs/performance.md "Load time").
struct RungElement {
  enum class Kind : std::uint8_t { Instruction, Branch };
  [[no_unique_address]] Instruction instruction;  // Kind::Instruction; a branch uses only its pos
  Kind kind = Kind::Instruction;
  BranchLegs<RungElement> legs;                   // Kind::Branch

  // Where the element starts: its mnemonic, or the BST of a branch.
  const SourcePos& pos() const { return instruction.pos; }
  SourcePos& pos() { return instruction.pos; }
};

struct Rung {
  std::vector<RungElement> elements;
  std::string comment;  // rung comment text (without the % delimiters); empty when none
  SourcePos pos;        // position of SOR
};

struct ProgramFile {
  int number = 2;       // 2 = main, 3..255 subroutines
  std::string name;
  std::vector<Rung> rungs;
  SourcePos pos;
};

// A SLOT line: one chassis slot and its module.
struct SlotConfig {
  int slot = 0;
  std::string catalog;
  std::string description;
  int scan_in = 0;   // input image words
  int scan_out = 0;  // output image words
  std::vector<std::uint16_t> g_file;      // G_FILE n followed by n words
  bool has_g_file = false;
  std::vector<std::int64_t> iocard;       // IOCARD fields, kept as exported
  // softslc extensions for specialty modules (see docs/program-format.md).
  std::optional<int> m0_size;
  std::optional<int> m1_size;
  std::optional<int> id_code;
  std::map<std::string, std::string> options;  // OPTION key=value pairs (DIP switches, module mode)
  SourcePos pos;
  // Added by the checker, not written in the file: a MicroLogix's embedded I/O in slot 0 when the
  // program has no SLOT 0 line. The formatter does not write it.
  bool implicit = false;
};

// A DATA block: initial values of one data file, or an opaque MicroLogix function file.
struct DataBlock {
  std::string file_name;       // as written in the header: "N7:0", "O:0", "HSC0:0"
  std::optional<FileType> type;  // nullopt for function files kept opaque
  int file = 0;
  int start_element = 0;       // element (or slot for O/I) the block starts at
  // Values in element order; T/C/R contribute 3 per element, F and L one per element.
  std::vector<std::int64_t> words;
  std::vector<double> floats;  // F files
  std::vector<std::string> strings;  // ST files
  std::string opaque_text;     // function files: the block's text, kept as written
  SourcePos pos;
};

// A FORCE block: forces installed on an I or O slot. Per word: bits forced on and bits forced off.
struct ForceBlock {
  FileType type = FileType::Input;
  int slot = 0;
  struct Word {
    std::uint16_t on = 0;   // the ON column: bits forced to 1
    std::uint16_t off = 0;  // the OFF column as exported (see docs: 1 = not forced off)
  };
  std::vector<Word> words;
  SourcePos pos;
};

// A data log queue (the DATALOG statement, docs/program-format.md "Data log queues"): what DLG q
// captures into queue q. RSLogix keeps this in the project's Data Log configuration (1763-RM001C
// p. 437); the text form is softslc's.
struct DataLogQueue {
  int number = 0;        // 0-255
  int records = 0;       // records allocated (DLS0:q.FSZ)
  bool date = false;     // the record starts with a date stamp (mm/dd/yyyy)
  bool time = false;     // then a time stamp (hh:mm:ss)
  char delimiter = ',';  // between the fields of the retrieved record: ',', '\t' or ' '
  std::vector<Address> fields;
  std::vector<SourcePos> field_pos;
  SourcePos pos;
};

struct Symbol {
  std::string name;
  Address address;
  std::string description;
  SourcePos pos;
  // Defined by an AutoMax IODEF/RIODEF/MEMDEF statement (the checker computes `address`).
  std::optional<AutomaxDef> automax;
};

struct Program {
  std::string source_name;     // file name for diagnostics
  ProcessorModel processor;
  std::optional<char> series_given;  // SERIES on the START line, when written
  std::optional<int> frn_given;      // FRN on the START line, when written
  std::string processor_description;
  SourcePos processor_pos;
  std::string project;
  std::vector<SlotConfig> slots;       // in SLOT order as written
  std::vector<ProgramFile> files;      // in LADDER order as written
  std::vector<DataBlock> data;
  std::vector<ForceBlock> forces;
  std::vector<Symbol> symbols;         // in definition order (a DESC line gives a nameless entry)
  std::vector<DataLogQueue> data_logs;  // DATALOG statements, in the order written

  const ProgramFile* find_file(int number) const;
  const SlotConfig* find_slot(int slot) const;
  const Symbol* find_symbol(std::string_view name) const;
  const DataLogQueue* find_data_log(int number) const;
};

// Semantic equality of two programs: same processor, configuration, rungs, data and symbols.
// Positions, spellings and free comments are ignored. Used by the fmt round-trip tests.
bool same_program(const Program& a, const Program& b, std::string* first_difference = nullptr);

}  // namespace softslc
