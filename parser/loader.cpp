// Actions of the export-format grammar and the statement-by-statement driver.
//
// The driver splits the text into statements (split_statements), parses each with
// grammar::statement and the actions below, and turns a syntax error into a diagnostic before
// moving on to the next statement. Addresses and operands are built in their own small states
// (PEGTL change_states), so a partial match that backtracks leaves nothing behind.
#include "parser/loader.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>
#include <type_traits>

#include "parser/checker.h"
#include "parser/grammar.h"
#include "parser/input_file.h"
#include "parser/limits.h"
#include "parser/grammar_messages.h"
#include "parser/rss/rss_reader.h"

namespace softslc {

namespace pegtl = tao::pegtl;

// ---- Numbers ---------------------------------------------------------------------------------------

bool parse_number_text(std::string_view text, NumberValue& out) {
  if (text.empty()) return false;
  bool negative = false;
  std::string_view t = text;
  if (t.front() == '+' || t.front() == '-') {
    negative = t.front() == '-';
    t.remove_prefix(1);
  }
  if (t.empty()) return false;
  auto finish_int = [&](std::uint64_t magnitude) {
    // Values beyond 64 bits are rejected; range checks against 16/32-bit words happen later.
    if (magnitude > static_cast<std::uint64_t>(INT64_MAX)) return false;
    out.is_float = false;
    out.integer = negative ? -static_cast<std::int64_t>(magnitude) : static_cast<std::int64_t>(magnitude);
    return true;
  };
  if (t.size() > 2 && t[0] == '0' && (t[1] == 'x' || t[1] == 'X')) {
    std::uint64_t v = 0;
    auto r = std::from_chars(t.data() + 2, t.data() + t.size(), v, 16);
    if (r.ec != std::errc() || r.ptr != t.data() + t.size()) return false;
    return finish_int(v);
  }
  if (t.back() == 'h' || t.back() == 'H') {
    std::uint64_t v = 0;
    auto r = std::from_chars(t.data(), t.data() + t.size() - 1, v, 16);
    if (r.ec != std::errc() || r.ptr != t.data() + t.size() - 1) return false;
    return finish_int(v);
  }
  if (t.find_first_of(".eE") != std::string_view::npos) {
    double d = 0;
    auto r = std::from_chars(t.data(), t.data() + t.size(), d);
    if (r.ec != std::errc() || r.ptr != t.data() + t.size() || !std::isfinite(d)) return false;
    out.is_float = true;
    out.real = negative ? -d : d;
    return true;
  }
  std::uint64_t v = 0;
  auto r = std::from_chars(t.data(), t.data() + t.size(), v, 10);
  if (r.ec != std::errc() || r.ptr != t.data() + t.size()) return false;
  return finish_int(v);
}

namespace {

using namespace grammar;

// A statement's input. PEGTL's eager line tracking updates a line and column at every character
// the grammar consumes and copies them into every backtracking mark (a quarter of loading a large
// program went to the marks and the bumps, docs/performance.md "Load time"); this input tracks
// nothing while parsing, and an action asks for a position only where it keeps one. pos_at counts
// on from the position asked for last (actions ask in text order, so a statement is scanned about
// once, however long its rung), or from the statement's start when asked for an earlier one.
// The source name is held by pointer: a std::string would copy it for every statement (an
// allocation each when the path is longer than 15 characters).
class StatementInput : public pegtl::memory_input<pegtl::tracking_mode::lazy, pegtl::eol::lf_crlf, const char*> {
 public:
  // Actions see this type itself (PEGTL builds an action's input from ParseInput::action_t).
  using action_t = pegtl::internal::action_input<StatementInput>;

  StatementInput(const char* begin, const char* end, const char* source, std::size_t byte, std::size_t line)
      : memory_input(begin, end, source, byte, line, 1), cursor_(begin), line_(line), column_(1) {}

  // The line and column of `p`, a character of this statement, as eager tracking would count
  // them (a byte is a column; '\n' starts the next line).
  SourcePos pos_at(const char* p) const {
    if (p < cursor_) {
      cursor_ = m_begin.data;
      line_ = m_begin.line;
      column_ = m_begin.column;
    }
    for (; cursor_ < p; ++cursor_) {
      if (*cursor_ == '\n') {
        ++line_;
        column_ = 1;
      } else {
        ++column_;
      }
    }
    return {static_cast<std::uint32_t>(line_), static_cast<std::uint32_t>(column_)};
  }

 private:
  mutable const char* cursor_;
  mutable std::size_t line_;
  mutable std::size_t column_;
};

// Where the matched text of an action starts. A statement's input computes it (above); other
// inputs (parse_address) track positions eagerly and read them off the iterator — in.position()
// would build a pegtl::position, whose std::string copy of the source name cost 3% of loading a
// large program.
template <typename Input>
SourcePos pos_of(const Input& in) {
  if constexpr (std::is_same_v<std::decay_t<decltype(in.input())>, StatementInput>) {
    return in.input().pos_at(in.begin());
  } else {
    const auto& it = in.iterator();
    return {static_cast<std::uint32_t>(it.line), static_cast<std::uint32_t>(it.column)};
  }
}

template <typename Input>
int to_int(const Input& in) {
  // Digit runs come from the grammar; saturate absurd lengths instead of overflowing.
  auto s = in.string_view();
  long long v = 0;
  for (char c : s) {
    v = v * 10 + (c - '0');
    if (v > 1'000'000'000) return 1'000'000'000;
  }
  return static_cast<int>(v);
}

std::string strip_percent(std::string_view s) {
  if (s.size() >= 2 && s.front() == '%' && s.back() == '%') s = s.substr(1, s.size() - 2);
  auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string_view::npos) return {};
  auto e = s.find_last_not_of(" \t\r\n");
  return std::string(s.substr(b, e - b + 1));
}

std::string strip_quotes(std::string_view s) {
  if (s.size() >= 2 && s.front() == '"' && s.back() == '"') s = s.substr(1, s.size() - 2);
  return std::string(s);
}

std::optional<FileType> file_type_from_letters(std::string_view s) {
  // A one-letter type without comparing strings: it is the type of nearly every address.
  if (s.size() == 1) {
    switch (s[0]) {
      case 'O': return FileType::Output;
      case 'I': return FileType::Input;
      case 'S': return FileType::Status;
      case 'B': return FileType::Bit;
      case 'T': return FileType::Timer;
      case 'C': return FileType::Counter;
      case 'R': return FileType::Control;
      case 'N': return FileType::Integer;
      case 'F': return FileType::Float;
      case 'L': return FileType::Long;
      case 'A': return FileType::Ascii;
      default: break;
    }
  }
  static constexpr std::pair<std::string_view, FileType> kTypes[] = {
      {"O", FileType::Output}, {"I", FileType::Input},    {"S", FileType::Status},   {"B", FileType::Bit},
      {"T", FileType::Timer},  {"C", FileType::Counter},  {"R", FileType::Control},  {"N", FileType::Integer},
      {"F", FileType::Float},  {"L", FileType::Long},     {"ST", FileType::String},  {"A", FileType::Ascii},
      {"M0", FileType::M0},    {"M1", FileType::M1},      {"MG", FileType::Message}, {"RI", FileType::Routing},
  };
  for (const auto& [letters, type] : kTypes)
    if (letters == s) return type;
  if (function_file_id(s) >= 0) return FileType::Function;
  return std::nullopt;
}

// ---- States ----------------------------------------------------------------------------------------

struct AddressBuilder {
  Address a;
  IndirectRef ref;
  bool has_file_number = false;
  bool ref_has_file_number = false;
  SourcePos pos;
  bool pos_set = false;
};

struct OperandBuilder {
  Operand op;
  void on_address(const Address& a, SourcePos pos) {
    op.kind = Operand::Kind::Address;
    op.address = a;
    op.pos = pos;
    // No spelling: an address's is to_string(address), built where a message needs it
    // (Operand::text()).
  }
};

// The whole-file state: the program being built plus the statement in progress.
struct LoadState {
  LoadState(Program& p, DiagnosticList& d, std::string_view src) : program(p), diags(d), source(src) {}

  Program& program;
  DiagnosticList& diags;
  std::string_view source;

  // START
  std::string catalog;
  SourcePos catalog_pos;
  std::optional<char> series;
  std::optional<int> frn;
  bool have_start = false;

  // LADDER and rungs
  int current_file = -1;  // index into program.files
  Rung rung;
  std::vector<RungElement*> open_branches;  // innermost last
  Instruction instruction;
  bool instruction_known = false;
  std::vector<Operand> operands;
  std::vector<std::string> pending_comments;

  // SLOT
  SlotConfig slot;
  int g_file_count = 0;
  SourcePos g_file_pos;

  // DATA / FORCE
  DataBlock data;
  ForceBlock force;
  std::vector<std::int64_t> force_values;
  bool data_opaque = false;
  std::size_t data_header_end = 0;  // byte offset in `source` where the header ends

  // SYMBOL / DESC
  Symbol symbol;

  // Where the appended elements of the current rung go: the innermost open branch's last leg.
  std::vector<RungElement>& current_elements() {
    return open_branches.empty() ? rung.elements : open_branches.back()->legs.back();
  }

  // DATALOG in progress: its field addresses go to `datalog`, not to `symbol`.
  bool in_datalog = false;
  DataLogQueue datalog;

  void on_address(const Address& a, SourcePos pos) {
    if (in_datalog) {
      datalog.fields.push_back(a);
      datalog.field_pos.push_back(pos);
    } else {
      symbol.address = a;
    }
  }
};

// ---- Actions ---------------------------------------------------------------------------------------

template <typename Rule>
struct action : pegtl::nothing<Rule> {};

// Addresses are built in a fresh AddressBuilder and handed to the enclosing state on success.
struct address_action : pegtl::change_states<AddressBuilder> {
  template <typename Input, typename Outer>
  static void success(const Input&, AddressBuilder& b, Outer& outer) {
    Address a = b.a;
    // I/O and M addresses without a word mean word 0 of the slot: I:1/3 == I:1.0/3.
    if ((is_io(a.type) || is_mfile(a.type)) && a.word < 0 && !a.indirect_word()) a.word = 0;
    // A bit of a T/C/R element is a bit of its word 0: T4:0/13 == T4:0/DN == T4:0.0/13.
    if (is_structured(a.type) && a.has_bit() && a.word < 0 && !a.indirect_word()) a.word = 0;
    outer.on_address(a, b.pos);
  }
};
template <> struct action<address> : address_action {};
template <> struct action<symbol_address> : address_action {};

template <> struct action<index_mark> {
  template <typename Input>
  static void apply(const Input& in, AddressBuilder& b) {
    b.a.indexed = true;
    b.pos = pos_of(in);
    b.pos_set = true;
  }
};

template <> struct action<file_type> {
  template <typename Input>
  static void apply(const Input& in, AddressBuilder& b) {
    b.a.type = *file_type_from_letters(in.string_view());
    if (is_function_file(b.a.type)) {
      // The function file's name is its whole file part: RTC:0, never RTC9:0.
      b.a.file = static_cast<std::uint16_t>(function_file_id(in.string_view()));
      b.has_file_number = true;
    }
    int fixed = fixed_file_number(b.a.type);
    if (fixed >= 0) b.a.file = static_cast<std::uint16_t>(fixed);
    if (b.a.type == FileType::M0) b.a.file = 0;
    if (b.a.type == FileType::M1) b.a.file = 1;
    if (!b.pos_set) {
      b.pos = pos_of(in);
      b.pos_set = true;
    }
  }
};

template <> struct action<file_number> {
  template <typename Input>
  static void apply(const Input& in, AddressBuilder& b) {
    int n = to_int(in);
    int fixed = fixed_file_number(b.a.type);
    if (is_mfile(b.a.type))
      throw pegtl::parse_error("M0/M1 addresses take the slot after ':' (M0:e.w/b), not a file number", in);
    if (fixed >= 0 && n != fixed)
      throw pegtl::parse_error(std::string("file ") + std::string(file_letter(b.a.type)) + " is always file " +
                                   std::to_string(fixed),
                               in);
    if (n > 255) throw pegtl::parse_error("file number must be 0-255", in);
    b.a.file = static_cast<std::uint16_t>(n);
    b.has_file_number = true;
  }
};

// A data file without a fixed number needs one (N7:0, not N:0).
template <typename Input>
void require_file_number(const Input& in, const AddressBuilder& b) {
  if (fixed_file_number(b.a.type) < 0 && !is_mfile(b.a.type) && !b.has_file_number && !b.a.indirect_file())
    throw pegtl::parse_error(std::string("expected a file number after '") + std::string(file_letter(b.a.type)) +
                                 "' (for example " + std::string(file_letter(b.a.type)) + "7:0)",
                             in);
}

template <> struct action<element_number> {
  template <typename Input>
  static void apply(const Input& in, AddressBuilder& b) {
    require_file_number(in, b);
    b.a.element = to_int(in);
  }
};

// A MicroLogix function file's element, word and bit are named directly (RTC:0.YR, HSC:0/FE):
// an indirect part has no canonical spelling for it (address_fuzz found CS:[N102:1] printed as
// CS:0), and no fixture or manual page softslc has uses one.
template <typename Input>
void refuse_indirect_function_file(const Input& in, const AddressBuilder& b) {
  if (is_function_file(b.a.type))
    throw pegtl::parse_error("function file " + std::string(function_file_name(b.a.file)) +
                                 " is addressed directly (" + std::string(function_file_name(b.a.file)) +
                                 ":0.WORD, :0/BIT); copy an indirect value through an N file",
                             in);
}

template <> struct action<indirect_element> {
  template <typename Input>
  static void apply(const Input& in, AddressBuilder& b) {
    require_file_number(in, b);
    refuse_indirect_function_file(in, b);
    b.a.set_indirect_element(b.ref);
    b.ref = {};
  }
};

template <> struct action<word_number> {
  template <typename Input>
  static void apply(const Input& in, AddressBuilder& b) { b.a.word = to_int(in); }
};

// What an MG element's sub-elements are called (1762-RM001C pp. 21-4, 21-6), for an unknown-name diagnostic.
constexpr const char* kMessageNames = "words RBL, LBN, RBN, CHN, NOD, MTO, TFN, ELE, ERR and bits EN, TO, ST, DN, ER, EW, R";

// What a function file's sub-elements are called, for an unknown-name diagnostic.
std::string function_file_hint(int id) {
  if (!function_file_simulated(id)) return " (softslc does not model this function file)";
  return " (" + std::string(function_file_name(id)) + " has " + function_sub_element_names(id) + ")";
}

// When a name written as a word (T4:0.DN) is one of the element's bits: how to write it instead.
std::string bit_written_as_word_hint(const Address& a, std::string_view name) {
  int word = 0, bit = 0;
  const bool is_bit = is_function_file(a.type)  ? function_bit_number(a.file, name, word, bit)
                      : is_message_file(a.type) ? message_bit_number(name, word, bit)
                                                : structured_bit_number(a.type, name) >= 0;
  return is_bit ? "; " + std::string(name) + " is a bit, written after '/' (T4:0/DN), not '.'" : "";
}

template <> struct action<word_name> {
  template <typename Input>
  static void apply(const Input& in, AddressBuilder& b) {
    if (is_function_file(b.a.type)) {
      const int id = b.a.file;
      int w = function_word_number(id, in.string_view());
      if (w < 0)
        throw pegtl::parse_error("unknown sub-element '" + in.string() + "' of function file " +
                                     std::string(function_file_name(id)) + function_file_hint(id) +
                                     bit_written_as_word_hint(b.a, in.string_view()),
                                 in);
      b.a.word = w;
      return;
    }
    if (is_message_file(b.a.type)) {
      const int w = message_word_number(in.string_view());
      if (w < 0)
        throw pegtl::parse_error("unknown sub-element '" + in.string() + "' of an MG element (" + kMessageNames + ")" +
                                     bit_written_as_word_hint(b.a, in.string_view()),
                                 in);
      b.a.word = w;
      return;
    }
    int w = structured_word_number(b.a.type, in.string_view());
    if (w < 0) {
      std::string msg = "unknown sub-element '" + in.string() + "'";
      if (b.a.type == FileType::Timer || b.a.type == FileType::Counter) msg += " (timers and counters have PRE and ACC)";
      else if (b.a.type == FileType::Control) msg += " (control elements have LEN and POS)";
      else msg += " (named sub-elements exist only in T, C and R files)";
      throw pegtl::parse_error(msg + bit_written_as_word_hint(b.a, in.string_view()), in);
    }
    b.a.word = w;
  }
};

template <> struct action<indirect_word> {
  template <typename Input>
  static void apply(const Input& in, AddressBuilder& b) {
    refuse_indirect_function_file(in, b);
    b.a.set_indirect_word(b.ref);
    b.ref = {};
  }
};

template <> struct action<bit_number> {
  template <typename Input>
  static void apply(const Input& in, AddressBuilder& b) { b.a.bit = to_int(in); }
};

template <> struct action<bit_name> {
  template <typename Input>
  static void apply(const Input& in, AddressBuilder& b) {
    if (is_function_file(b.a.type)) {
      const int id = b.a.file;
      int word = -1, bit = -1;
      if (b.a.word >= 0 || !function_bit_number(id, in.string_view(), word, bit))
        throw pegtl::parse_error("unknown bit name '" + in.string() + "' of function file " +
                                     std::string(function_file_name(id)) +
                                     function_file_hint(id),
                                 in);
      // A CS file's elements are one word: CS0:4/MCP is CS0:4/2, its word left unwritten as there.
      b.a.word = communications_status_channel(id) >= 0 ? -1 : word;
      b.a.bit = bit;
      return;
    }
    if (is_message_file(b.a.type)) {
      int word = -1, bit = -1;
      if (b.a.word >= 0 || !message_bit_number(in.string_view(), word, bit))
        throw pegtl::parse_error("unknown bit name '" + in.string() + "' of an MG element (" + kMessageNames +
                                     "; a named bit is written MG11:0/DN)",
                                 in);
      b.a.word = word;
      b.a.bit = bit;
      return;
    }
    int bit = b.a.word <= 0 ? structured_bit_number(b.a.type, in.string_view()) : -1;
    if (bit < 0) {
      std::string msg = "unknown bit name '" + in.string() + "'";
      if (b.a.type == FileType::Timer) msg += " (timer bits are EN, TT, DN)";
      else if (b.a.type == FileType::Counter) msg += " (counter bits are CU, CD, DN, OV, UN, UA)";
      else if (b.a.type == FileType::Control) msg += " (control bits are EN, EU, DN, EM, ER, UL, IN, FD)";
      else msg += " (named bits exist only in T, C and R files)";
      throw pegtl::parse_error(msg, in);
    }
    b.a.bit = bit;
    if (b.a.word < 0) b.a.word = 0;
  }
};

template <> struct action<indirect_bit> {
  template <typename Input>
  static void apply(const Input& in, AddressBuilder& b) {
    refuse_indirect_function_file(in, b);
    b.a.set_indirect_bit(b.ref);
    b.ref = {};
  }
};

template <> struct action<bit_offset_number> {
  template <typename Input>
  static void apply(const Input& in, AddressBuilder& b) {
    if (b.a.type != FileType::Bit)
      throw pegtl::parse_error("the bit-offset form F/n exists only for B files (write N7:0/3 for other files)", in);
    require_file_number(in, b);
    int n = to_int(in);
    if (n > 4095) throw pegtl::parse_error("bit offset must be 0-4095 (B files hold 256 words)", in);
    b.a.element = n / 16;
    b.a.bit = n % 16;
  }
};

template <> struct action<indirect_bit_offset> {
  template <typename Input>
  static void apply(const Input& in, AddressBuilder& b) {
    if (b.a.type != FileType::Bit)
      throw pegtl::parse_error("the bit-offset form F/[...] exists only for B files", in);
    require_file_number(in, b);
    b.a.bit_offset_form = true;
    b.a.element = 0;
    b.a.set_indirect_bit(b.ref);
    b.ref = {};
  }
};

template <> struct action<indirect_file> {
  template <typename Input>
  static void apply(const Input& in, AddressBuilder& b) {
    if (fixed_file_number(b.a.type) >= 0 || is_mfile(b.a.type))
      throw pegtl::parse_error("only data files 3-255 can be addressed with an indirect file number", in);
    b.a.set_indirect_file(b.ref);
    b.ref = {};
  }
};

// Inside brackets: a direct word address.
template <> struct action<ref_type> {
  template <typename Input>
  static void apply(const Input& in, AddressBuilder& b) {
    b.ref = {};
    b.ref.type = *file_type_from_letters(in.string_view());
    if (is_function_file(b.ref.type))
      throw pegtl::parse_error("a function file word cannot be a pointer inside brackets; copy it to an N word first",
                               in);
    int fixed = fixed_file_number(b.ref.type);
    if (fixed >= 0) b.ref.file = static_cast<std::uint16_t>(fixed);
    b.ref_has_file_number = false;
  }
};
template <> struct action<ref_file> {
  template <typename Input>
  static void apply(const Input& in, AddressBuilder& b) {
    int n = to_int(in);
    int fixed = fixed_file_number(b.ref.type);
    if (fixed >= 0 && n != fixed)
      throw pegtl::parse_error(std::string("file ") + std::string(file_letter(b.ref.type)) + " is always file " +
                                   std::to_string(fixed),
                               in);
    if (n > 255) throw pegtl::parse_error("file number must be 0-255", in);
    b.ref.file = static_cast<std::uint16_t>(n);
    b.ref_has_file_number = true;
  }
};
template <> struct action<ref_element> {
  template <typename Input>
  static void apply(const Input& in, AddressBuilder& b) {
    if (is_mfile(b.ref.type) || b.ref.type == FileType::Float || b.ref.type == FileType::String)
      throw pegtl::parse_error("an indirect reference must be an integer word (N, B, T, C, R, S, I, O)", in);
    if (fixed_file_number(b.ref.type) < 0 && !b.ref_has_file_number)
      throw pegtl::parse_error("expected a file number in the indirect reference (for example N10:1)", in);
    b.ref.element = static_cast<std::uint16_t>(std::min(to_int(in), 65535));
  }
};
template <> struct action<ref_word_number> {
  template <typename Input>
  static void apply(const Input& in, AddressBuilder& b) { b.ref.word = static_cast<std::int16_t>(std::min(to_int(in), 255)); }
};
template <> struct action<ref_word_name> {
  template <typename Input>
  static void apply(const Input& in, AddressBuilder& b) {
    int w = structured_word_number(b.ref.type, in.string_view());
    if (w < 0) throw pegtl::parse_error("unknown sub-element '" + in.string() + "'", in);
    b.ref.word = static_cast<std::int16_t>(w);
  }
};

// ---- Operands --------------------------------------------------------------------------------------

template <> struct action<operand_token> : pegtl::change_states<OperandBuilder> {
  template <typename Input>
  static void success(const Input&, OperandBuilder& ob, LoadState& s) {
    s.operands.push_back(std::move(ob.op));
  }
};

template <> struct action<number> {
  template <typename Input>
  static void apply(const Input& in, OperandBuilder& ob) {
    NumberValue v;
    auto text = in.string_view();
    // The rule includes the token end (an empty lookahead), so the text is exactly the number.
    if (!parse_number_text(text, v)) throw pegtl::parse_error("number out of range: " + std::string(text), in);
    ob.op.kind = v.is_float ? Operand::Kind::Float : Operand::Kind::Integer;
    ob.op.integer = v.integer;
    ob.op.real = v.real;
    ob.op.spelling = std::string(text);
    ob.op.pos = pos_of(in);
  }
};

template <> struct action<cpt_expression> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) {
    Operand op;
    op.kind = Operand::Kind::Expression;
    // A statement may continue over lines: keep the expression on one line, blanks collapsed.
    for (char c : in.string_view()) {
      const bool blank = c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
      if (!blank) op.spelling += c;
      else if (op.spelling.empty() || op.spelling.back() != ' ') op.spelling += ' ';
    }
    op.pos = pos_of(in);
    s.operands.push_back(std::move(op));
  }
};

template <> struct action<symbol_name> {
  template <typename Input>
  static void apply(const Input& in, OperandBuilder& ob) {
    ob.op.kind = Operand::Kind::Symbol;
    ob.op.spelling = in.string();
    ob.op.pos = pos_of(in);
  }
};

// ---- START -----------------------------------------------------------------------------------------

template <> struct action<processor_catalog> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) {
    s.catalog = in.string();
    s.catalog_pos = pos_of(in);
  }
};
template <> struct action<series_letter> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) { s.series = in.peek_char(0); }
};
template <> struct action<frn_number> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) { s.frn = to_int(in); }
};
template <> struct action<processor_description> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) { s.program.processor_description = strip_percent(in.string_view()); }
};
template <> struct action<start_stmt> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) {
    if (s.have_start) {
      s.diags.error(s.catalog_pos.line, s.catalog_pos.column, "a second START statement; a program names one processor");
      return;
    }
    s.have_start = true;
    s.program.processor_pos = pos_of(in);
    auto model = resolve_processor(s.catalog, s.series, s.frn);
    if (!model) {
      s.diags.error(s.catalog_pos.line, s.catalog_pos.column,
                    "unknown processor catalog '" + s.catalog + "'; known: " + std::string(known_processor_catalogs()));
      return;
    }
    s.program.processor = *model;
    s.program.series_given = s.series;
    s.program.frn_given = s.frn;
  }
};

// ---- SLOT ------------------------------------------------------------------------------------------

template <> struct action<slot_number> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) {
    s.slot = {};
    s.slot.slot = to_int(in);
    s.slot.pos = pos_of(in);
  }
};
template <> struct action<module_catalog> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) { s.slot.catalog = in.string(); }
};
template <> struct action<slot_description> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) { s.slot.description = strip_percent(in.string_view()); }
};
template <> struct action<scan_in_words> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) { s.slot.scan_in = to_int(in); }
};
template <> struct action<scan_out_words> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) { s.slot.scan_out = to_int(in); }
};
template <> struct action<g_file_count> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) {
    s.g_file_count = to_int(in);
    s.g_file_pos = pos_of(in);
    s.slot.has_g_file = true;
    s.slot.g_file.clear();
  }
};
template <> struct action<g_file_word> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) {
    NumberValue v;
    if (!parse_number_text(in.string_view(), v) || v.integer < -32768 || v.integer > 65535) {
      auto p = pos_of(in);
      s.diags.error(p.line, p.column, "G-file word must be a 16-bit value (-32768..65535)");
      return;
    }
    s.slot.g_file.push_back(static_cast<std::uint16_t>(v.integer));
  }
};
template <> struct action<g_file> {
  template <typename Input>
  static void apply(const Input&, LoadState& s) {
    if (static_cast<int>(s.slot.g_file.size()) != s.g_file_count)
      s.diags.error(s.g_file_pos.line, s.g_file_pos.column,
                    "G_FILE " + std::to_string(s.g_file_count) + " announces " + std::to_string(s.g_file_count) +
                        " words but " + std::to_string(s.slot.g_file.size()) + " follow");
  }
};
template <> struct action<iocard_value> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) {
    NumberValue v;
    parse_number_text(in.string_view(), v);
    s.slot.iocard.push_back(v.integer);
  }
};
template <> struct action<grammar::m0_words> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) { s.slot.m0_size = to_int(in); }
};
template <> struct action<grammar::m1_words> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) { s.slot.m1_size = to_int(in); }
};
template <> struct action<id_code_value> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) { s.slot.id_code = to_int(in); }
};
template <> struct action<option> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) {
    // "OPTION key=value": split the matched text at the first '='.
    auto text = in.string_view();
    text.remove_prefix(text.find_first_not_of(" \t\r\n", 6));
    auto eq = text.find('=');
    s.slot.options[std::string(text.substr(0, eq))] = std::string(text.substr(eq + 1));
  }
};
template <> struct action<slot_stmt> {
  template <typename Input>
  static void apply(const Input&, LoadState& s) {
    for (const auto& existing : s.program.slots)
      if (existing.slot == s.slot.slot) {
        s.diags.error(s.slot.pos.line, s.slot.pos.column,
                      "slot " + std::to_string(s.slot.slot) + " is configured twice (first at line " +
                          std::to_string(existing.pos.line) + ")");
        return;
      }
    s.program.slots.push_back(std::move(s.slot));
  }
};

// ---- PROJECT, LADDER -------------------------------------------------------------------------------

template <> struct action<project_name> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) { s.program.project = strip_quotes(in.string_view()); }
};
// How many lines after `from` begin with SOR before the next line that begins with LADDER: the
// rungs of the program file being declared, counted ahead so that its rung vector is allocated
// once. Grown by doubling, a 50,000-rung file moved every rung 16 times and left each outgrown
// buffer behind (4% of loading a 1M-rung program, docs/performance.md "Load time"). The count only
// sets a capacity: a line it miscounts (a comment line that begins with SOR) costs a rung's worth
// of memory, nothing else.
std::size_t count_rung_lines(std::string_view text, std::size_t from) {
  std::size_t n = 0;
  std::size_t nl = text.find('\n', from);
  while (nl != std::string_view::npos) {
    std::size_t b = nl + 1;
    while (b < text.size() && (text[b] == ' ' || text[b] == '\t')) ++b;
    const std::string_view rest = text.substr(b);
    if (rest.starts_with("SOR")) ++n;
    else if (rest.starts_with("LADDER")) break;
    nl = text.find('\n', b);
  }
  return n;
}

template <> struct action<ladder_number> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) {
    int n = to_int(in);
    auto p = pos_of(in);
    for (std::size_t i = 0; i < s.program.files.size(); ++i)
      if (s.program.files[i].number == n) {
        s.diags.error(p.line, p.column,
                      "program file " + std::to_string(n) + " is defined twice (first at line " +
                          std::to_string(s.program.files[i].pos.line) + ")");
        s.current_file = static_cast<int>(i);
        return;
      }
    ProgramFile f;
    f.number = n;
    f.pos = p;
    f.rungs.reserve(count_rung_lines(s.source, static_cast<std::size_t>(in.end() - s.source.data())));
    s.program.files.push_back(std::move(f));
    s.current_file = static_cast<int>(s.program.files.size() - 1);
  }
};
template <> struct action<ladder_name> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) {
    if (s.current_file >= 0) s.program.files[s.current_file].name = strip_quotes(in.string_view());
  }
};

// ---- Rungs -----------------------------------------------------------------------------------------

template <> struct action<kw_sor> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) {
    // s.rung is scratch: its element vector keeps its capacity from rung to rung (see
    // exact_copy below), so only the rung's comment and position are reset.
    s.rung.elements.clear();
    s.rung.comment.clear();
    s.rung.pos = pos_of(in);
    s.open_branches.clear();
    // The comment lines just before SOR are the rung comment; "% Rung: n %" markers are not.
    for (auto& c : s.pending_comments) {
      if (!s.rung.comment.empty()) s.rung.comment += '\n';
      s.rung.comment += c;
    }
    s.pending_comments.clear();
  }
};

template <> struct action<mnemonic> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) {
    s.instruction = {};
    s.instruction.pos = pos_of(in);
    s.operands.clear();
    auto m = in.string_view();
    const InstructionSpec* spec = find_instruction(m);
    s.instruction_known = spec != nullptr;
    if (spec) {
      s.instruction.opcode = spec->opcode;
    } else {
      s.diags.error(s.instruction.pos.line, s.instruction.pos.column, unknown_instruction_message(m));
    }
  }
};

template <> struct action<instruction> {
  template <typename Input>
  static void apply(const Input&, LoadState& s) {
    if (!s.instruction_known) return;
    // Moved into a list of exactly their count, so s.operands keeps its capacity for the next
    // instruction: moving the vector itself made every instruction grow a new one from empty.
    s.instruction.operands.assign_moved(s.operands.data(), s.operands.data() + s.operands.size());
    s.operands.clear();
    // A mnemonic with several forms (OSR) takes the form its operand count names. The row the
    // mnemonic found is its first, so when its count fits it is already that form; the search
    // (a string comparison per table row, 2% of a 1M-rung load) is only for the others.
    const InstructionSpec& first = spec(s.instruction.opcode);
    if (first.operand_count != s.instruction.operands.size())
      s.instruction.opcode = find_instruction_form(first.mnemonic, s.instruction.operands.size())->opcode;
    RungElement e;
    e.kind = RungElement::Kind::Instruction;
    e.instruction = std::move(s.instruction);
    s.current_elements().push_back(std::move(e));
  }
};

template <> struct action<branch_open> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) {
    // The limit is enforced while parsing, before the grammar recurses further: a file of 15,000
    // nested BSTs is one positioned error, not a stack overflow.
    if (s.open_branches.size() >= static_cast<std::size_t>(kMaxBranchNesting))
      throw pegtl::parse_error("branches nested deeper than " + std::to_string(kMaxBranchNesting) + " levels", in);
    RungElement e;
    e.kind = RungElement::Kind::Branch;
    e.pos() = pos_of(in);
    // Most branches have two legs: room for both at once (the legs block is then kept, see
    // exact_legs) rather than grown when NXB opens the second.
    e.legs.reserve(2);
    e.legs.emplace_back();
    auto& container = s.current_elements();
    container.push_back(std::move(e));
    s.open_branches.push_back(&container.back());
  }
};

template <> struct action<branch_next> {
  template <typename Input>
  static void apply(const Input&, LoadState& s) {
    if (!s.open_branches.empty()) s.open_branches.back()->legs.emplace_back();
  }
};

template <> struct action<branch_close> {
  template <typename Input>
  static void apply(const Input&, LoadState& s) {
    if (!s.open_branches.empty()) s.open_branches.pop_back();
  }
};

template <> struct action<branch_close_required> : action<branch_close> {};

template <> struct action<stray_branch_keyword> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) {
    auto p = pos_of(in);
    s.diags.error(p.line, p.column, "unbalanced branch: " + std::string(in.string_view().substr(0, 3)) +
                                        " without a matching BST");
  }
};

// The elements of a rung as parsed, moved into vectors of exactly their count (branch legs
// too). The scratch vectors the actions append to grow by doubling, which would leave a quarter of
// their capacity unused on average and free every outgrown buffer in the middle of the program
// tree; the copy makes one allocation per vector and no free, and the instructions (with their
// operands) are moved, not copied. A leg that is already exact (one or two elements, as most
// are) is moved whole rather than copied. Recursion is bounded by kMaxBranchNesting, which the
// branch_open action enforces while parsing.
std::vector<RungElement> exact_copy(std::vector<RungElement>& scratch);

void exact_legs(RungElement& c) {
  if (c.legs.empty()) return;  // an instruction: no legs block
  if (c.legs.size() == 2) {
    // The block branch_open reserved for two legs is exact: keep it, trim only the legs.
    for (auto& leg : c.legs) {
      if (leg.capacity() == leg.size()) {
        for (RungElement& x : leg) exact_legs(x);
      } else {
        leg = exact_copy(leg);
      }
    }
    return;
  }
  BranchLegs<RungElement> legs = std::move(c.legs);
  c.legs.clear();
  c.legs.reserve(legs.size());
  for (auto& leg : legs) {
    if (leg.capacity() == leg.size()) {
      for (RungElement& x : leg) exact_legs(x);
      c.legs.push_back(std::move(leg));
    } else {
      c.legs.push_back(exact_copy(leg));
    }
  }
}

std::vector<RungElement> exact_copy(std::vector<RungElement>& scratch) {
  std::vector<RungElement> out;
  out.reserve(scratch.size());
  for (RungElement& e : scratch) exact_legs(out.emplace_back(std::move(e)));
  return out;
}

template <> struct action<rung> {
  template <typename Input>
  static void apply(const Input&, LoadState& s) {
    if (s.current_file < 0) {
      s.diags.error(s.rung.pos.line, s.rung.pos.column, "rung before any LADDER statement");
      return;
    }
    Rung r;
    r.elements = exact_copy(s.rung.elements);
    r.comment = std::move(s.rung.comment);
    r.pos = s.rung.pos;
    s.program.files[s.current_file].rungs.push_back(std::move(r));
    s.rung.elements.clear();
    s.rung.comment.clear();
  }
};

// ---- Comments --------------------------------------------------------------------------------------

template <> struct action<comment_stmt> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) {
    auto text = strip_percent(std::string_view(in.string_view()).substr(0, in.string_view().rfind('%') + 1));
    // RSLogix writes "% Rung: 12 %" before every rung; it carries no information.
    if (text.rfind("Rung:", 0) == 0) return;
    s.pending_comments.push_back(std::move(text));
  }
};

// ---- DATA ------------------------------------------------------------------------------------------

template <> struct action<data_header> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) {
    s.data = {};
    s.force = {};
    s.force_values.clear();
    s.data.pos = pos_of(in);
    s.data.file_name = in.string();
    s.data_header_end = static_cast<std::size_t>(in.end() - s.source.data());
    // Split "N7:0" / "O:0" / "HSC0:0" into letters, number and first element.
    auto text = in.string_view();
    std::size_t i = 0;
    while (i < text.size() && std::isupper(static_cast<unsigned char>(text[i]))) ++i;
    std::string letters(text.substr(0, i));
    std::size_t colon = text.find(':');
    std::string number(text.substr(i, colon - i));
    s.data.start_element = std::stoi(std::string(text.substr(colon + 1)).substr(0, 9));
    auto type = file_type_from_letters(letters);
    int fixed = type ? fixed_file_number(*type) : -1;
    // The STI function file's block gives its configuration (docs/program-format.md); the other
    // function files' blocks are kept as written.
    // The EII's block too (DATA EII0:0, four words an element, as RSLogix exports it).
    const bool sti = type && is_function_file(*type) && (function_file_id(letters) == static_cast<int>(FunctionFile::STI) ||
                                                         function_file_id(letters) == static_cast<int>(FunctionFile::EII));
    // So does a pulse train output file's (DATA PTO0:0 / PTOX0:0, as RSLogix exports PTOX0:0) and the
    // HSC function file's, in RSLogix's export form (DATA HSC0:0, 13 values an element).
    const bool pulse_train = type && is_function_file(*type) && is_pulse_train_file(function_file_id(letters));
    const bool hsc = type && is_function_file(*type) && function_file_id(letters) == static_cast<int>(FunctionFile::HSC);
    s.data_opaque = !type || is_mfile(*type) || (is_function_file(*type) && !sti && !pulse_train && !hsc);
    if (!s.data_opaque) {
      s.data.type = type;
      if (pulse_train || sti) {
        // RSLogix exports it as STI0:0 (PTO0:0, ...); softslc's addresses write STI:0. Either names
        // the one element.
        if (!number.empty() && number != "0")
          s.diags.error(s.data.pos.line, s.data.pos.column, "the " + letters + " function file has no file number: DATA " + letters +
                                                                ":0 or, as RSLogix exports it, DATA " + letters + "0:0");
        s.data.file = function_file_id(letters);
      } else if (hsc) {
        if (!number.empty() && number != "0")
          s.diags.error(s.data.pos.line, s.data.pos.column, "the HSC function file has no file number: DATA HSC:0 or, as RSLogix exports it, DATA HSC0:0");
        s.data.file = function_file_id(letters);
      } else if (fixed >= 0) {
        if (!number.empty() && std::stoi(number.substr(0, 9)) != fixed) s.data_opaque = true;
        s.data.file = fixed;
      } else if (number.empty()) {
        s.diags.error(s.data.pos.line, s.data.pos.column, "expected a file number in '" + s.data.file_name + "'");
      } else {
        s.data.file = std::stoi(number.substr(0, 9));
      }
    }
    if (s.data_opaque) s.data.type.reset();
  }
};

template <> struct action<data_number> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) {
    if (s.data_opaque) return;
    NumberValue v;
    auto p = pos_of(in);
    if (!parse_number_text(in.string_view(), v)) {
      s.diags.error(p.line, p.column, "number out of range");
      return;
    }
    if (s.data.type == FileType::Float) {
      s.data.floats.push_back(v.is_float ? v.real : static_cast<double>(v.integer));
      return;
    }
    if (v.is_float) {
      const std::string file = is_function_file(*s.data.type) ? "the " + std::string(function_file_name(s.data.file)) + " function file"
                                                               : "a " + std::string(file_letter(*s.data.type)) + " file";
      s.diags.error(p.line, p.column, file + " holds integers, not '" + in.string() + "'");
      return;
    }
    if (is_function_file(*s.data.type) && s.data.file == static_cast<int>(FunctionFile::HSC) &&
        hsc::export_value_is_long(s.data.words.size() % hsc::kExportValues)) {
      // HSC:e.ACC, .HIP, .LOP, .OVF, .UNF: 32-bit values.
      if (v.integer < INT32_MIN || v.integer > INT32_MAX)
        s.diags.error(p.line, p.column, "value " + in.string() + " does not fit the HSC's 32-bit long word");
      s.data.words.push_back(v.integer);
      return;
    }
    // A 16-bit word is a bit pattern: 0XA200 and -24064 are the same word. Keep the signed form
    // so a value written either way loads the same (fmt prints control words in hex). A pulse
    // train file's block mixes words and long words (TOP ...): its values stay as written.
    const bool mixed = is_function_file(*s.data.type) && is_pulse_train_file(s.data.file);
    if (s.data.type != FileType::Long && !mixed && v.integer > 32767 && v.integer <= 65535) v.integer -= 65536;
    s.data.words.push_back(v.integer);
  }
};

template <> struct action<data_string> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) {
    if (s.data_opaque) return;
    if (s.data.type != FileType::String) {
      auto p = pos_of(in);
      s.diags.error(p.line, p.column, "quoted strings belong in ST files only");
      return;
    }
    s.data.strings.push_back(strip_quotes(in.string_view()));
  }
};

template <> struct action<data_stmt> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) {
    if (s.data_opaque) {
      // MicroLogix function files (HSC, PTOX, STI, ...) are kept verbatim; softslc does not
      // model them, and says so rather than failing on a real export.
      auto end = static_cast<std::size_t>(in.end() - s.source.data());
      auto text = s.source.substr(s.data_header_end, end - s.data_header_end);
      // Keep the block from the line after the header; trim the rest of the header line and
      // trailing blank lines so the round trip is stable.
      auto first = text.find_first_not_of(" \t\r");
      if (first != std::string_view::npos && text[first] == '\n') text.remove_prefix(first + 1);
      s.data.opaque_text = std::string(text);
      while (!s.data.opaque_text.empty() && std::isspace(static_cast<unsigned char>(s.data.opaque_text.back())))
        s.data.opaque_text.pop_back();
      s.diags.warning(s.data.pos.line, s.data.pos.column,
                      "data file '" + s.data.file_name +
                          "' is not an SLC data file (MicroLogix function file?); kept as opaque data, not simulated");
    }
    s.program.data.push_back(std::move(s.data));
    s.data = {};
  }
};

// ---- FORCE -----------------------------------------------------------------------------------------

template <> struct action<force_number> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) {
    NumberValue v;
    auto p = pos_of(in);
    if (!parse_number_text(in.string_view(), v) || v.is_float || v.integer < -32768 || v.integer > 65535) {
      s.diags.error(p.line, p.column, "force words are 16-bit values such as 0X00FF");
      return;
    }
    s.force_values.push_back(v.integer);
  }
};

template <> struct action<force_stmt> {
  template <typename Input>
  static void apply(const Input&, LoadState& s) {
    auto p = s.data.pos;
    if (!s.data.type || !is_io(*s.data.type)) {
      s.diags.error(p.line, p.column, "forces apply to I and O slots only ('" + s.data.file_name + "')");
      return;
    }
    if (s.force_values.size() % 2 != 0) {
      s.diags.error(p.line, p.column, "each force row has an ON word and an OFF word");
      return;
    }
    ForceBlock f;
    f.type = *s.data.type;
    f.slot = s.data.start_element;
    f.pos = p;
    for (std::size_t i = 0; i + 1 < s.force_values.size(); i += 2)
      f.words.push_back({static_cast<std::uint16_t>(s.force_values[i]), static_cast<std::uint16_t>(s.force_values[i + 1])});
    s.program.forces.push_back(std::move(f));
  }
};

// ---- SYMBOL / DESC ---------------------------------------------------------------------------------

template <> struct action<kw_symbol> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) {
    s.in_datalog = false;
    s.symbol = {};
    s.symbol.pos = pos_of(in);
  }
};
template <> struct action<kw_desc> : action<kw_symbol> {};
template <> struct action<symbol_def_name> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) { s.symbol.name = in.string(); }
};
template <> struct action<symbol_description> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) { s.symbol.description = strip_percent(in.string_view()); }
};
template <> struct action<symbol_note> : action<symbol_description> {};
template <> struct action<symbol_stmt> {
  template <typename Input>
  static void apply(const Input&, LoadState& s) { s.program.symbols.push_back(std::move(s.symbol)); }
};
template <> struct action<desc_stmt> : action<symbol_stmt> {};

// ---- DATALOG (data log queue configuration) -----------------------------------------------------

template <> struct action<kw_datalog> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) {
    s.in_datalog = true;
    s.datalog = {};
    s.datalog.pos = pos_of(in);
  }
};
template <> struct action<datalog_queue> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) { s.datalog.number = to_int(in); }
};
template <> struct action<datalog_records> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) { s.datalog.records = to_int(in); }
};
template <> struct action<datalog_date> {
  template <typename Input>
  static void apply(const Input&, LoadState& s) { s.datalog.date = true; }
};
template <> struct action<datalog_time> {
  template <typename Input>
  static void apply(const Input&, LoadState& s) { s.datalog.time = true; }
};
template <> struct action<datalog_delimiter> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) {
    const auto t = in.string_view();
    s.datalog.delimiter = t.starts_with("TAB") ? '\t' : t.starts_with("SPACE") ? ' ' : ',';
  }
};
template <> struct action<datalog_field> : address_action {};
template <> struct action<datalog_stmt> {
  template <typename Input>
  static void apply(const Input&, LoadState& s) {
    s.program.data_logs.push_back(std::move(s.datalog));
    s.in_datalog = false;
  }
};

// ---- IODEF / RIODEF / MEMDEF (AutoMax symbol definitions) -----------------------------------------

template <typename Input>
void start_automax_def(const Input& in, LoadState& s, AutomaxDef::Kind kind) {
  s.symbol = {};
  s.symbol.pos = pos_of(in);
  s.symbol.automax = AutomaxDef{};
  s.symbol.automax->kind = kind;
}
template <> struct action<kw_iodef> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) { start_automax_def(in, s, AutomaxDef::Kind::IoDef); }
};
template <> struct action<kw_riodef> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) { start_automax_def(in, s, AutomaxDef::Kind::RioDef); }
};
template <> struct action<kw_memdef> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) { start_automax_def(in, s, AutomaxDef::Kind::MemDef); }
};
template <> struct action<def_name> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) {
    auto text = in.string_view();
    s.symbol.name = std::string(text.substr(0, text.size() - 1));
    s.symbol.automax->suffix = text.back();
  }
};
template <> struct action<def_key> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) {
    AutomaxField f;
    f.key = in.string();
    f.line = pos_of(in).line;
    f.column = pos_of(in).column;
    s.symbol.automax->fields.push_back(std::move(f));
  }
};
// A value is decimal (4, 04), hexadecimal (20H, 0x20) or, as the manual writes drop numbers
// 9-F, a single hexadecimal letter (C).
template <> struct action<def_value> {
  template <typename Input>
  static void apply(const Input& in, LoadState& s) {
    AutomaxField& f = s.symbol.automax->fields.back();
    f.spelling = in.string();
    f.value_column = pos_of(in).column;
    NumberValue v;
    const char c = f.spelling.size() == 1 ? static_cast<char>(std::toupper(static_cast<unsigned char>(f.spelling[0]))) : 0;
    if (c >= 'A' && c <= 'F') {
      f.value = c - 'A' + 10;
    } else if (parse_number_text(f.spelling, v) && !v.is_float && v.integer <= 0x7FFFFFFF) {
      f.value = v.integer;
    } else {
      f.value = -1;
      s.diags.error(f.line, f.value_column, "field " + f.key + ": '" + f.spelling + "' is not a number");
    }
  }
};
template <> struct action<def_note> : action<symbol_description> {};
template <> struct action<io_def_stmt> : action<symbol_stmt> {};
template <> struct action<mem_def_stmt> {
  template <typename Input>
  static void apply(const Input&, LoadState& s) {
    for (const auto& other : s.program.symbols)
      if (other.automax && other.automax->kind == AutomaxDef::Kind::MemDef &&
          other.automax->suffix == s.symbol.automax->suffix)
        ++s.symbol.automax->memdef_index;
    s.program.symbols.push_back(std::move(s.symbol));
  }
};

// ---- Statement splitting -------------------------------------------------------------------------

enum class SpanKind { Keyword, Comment, Data, Rung, Other };

struct Span {
  std::size_t begin = 0;
  std::size_t end = 0;
  std::size_t line = 1;
  SpanKind kind = SpanKind::Other;
  // A rung: where its own text ends, before any comment lines that follow it inside the span (a
  // rung without EOR runs on through the comments above the next SOR; its error belongs here).
  std::size_t content_end = 0;
};

std::string_view first_token(std::string_view line) {
  auto b = line.find_first_not_of(" \t\r");
  if (b == std::string_view::npos) return {};
  auto e = line.find_first_of(" \t\r%", b);
  return line.substr(b, e == std::string_view::npos ? std::string_view::npos : e - b);
}

bool is_statement_keyword(std::string_view t) {
  static constexpr std::string_view kKeywords[] = {"START", "SLOT", "PROJECT", "LADDER", "SOR",
                                                   "DATA",  "FORCE", "SYMBOL", "DESC", "IODEF",
                                                   "RIODEF", "MEMDEF", "DATALOG"};
  for (auto k : kKeywords)
    if (k == t) return true;
  return false;
}

// True when `line` is an IODEF/RIODEF/MEMDEF whose variable name ends in '%' (a register): that
// '%' is part of the name, not the start of a comment.
bool defines_register_name(std::string_view line, std::string_view tok) {
  if (tok != "IODEF" && tok != "RIODEF" && tok != "MEMDEF") return false;
  std::size_t i = line.find(tok) + tok.size();
  while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
  while (i < line.size() && (std::isalnum(static_cast<unsigned char>(line[i])) || line[i] == '_')) ++i;
  return i < line.size() && line[i] == '%';
}

// Splits the text into statements: a statement starts at a line whose first token is a
// statement keyword, or at a comment line outside DATA/FORCE blocks; other lines continue the
// current statement (G_FILE words, DATA rows, the rest of a long rung). Each statement is handed
// to `on_statement` as soon as it ends, not gathered first: a list of them took 40 bytes per rung
// and grew by doubling (about 120 MB of memory touched for a 1M-rung program).
template <typename OnStatement>
void split_statements(std::string_view text, OnStatement&& on_statement) {
  std::optional<Span> cur;
  bool comment_open = false;  // inside a comment that spans lines
  std::size_t pos = 0, line = 1;
  auto close = [&](std::size_t at) {
    if (cur) {
      cur->end = at;
      const Span done = *cur;
      cur.reset();
      on_statement(done);
    }
  };
  while (pos < text.size()) {
    auto nl = text.find('\n', pos);
    std::size_t next = nl == std::string_view::npos ? text.size() : nl + 1;
    auto l = text.substr(pos, next - pos);
    auto tok = first_token(l);
    bool in_block = cur && cur->kind == SpanKind::Data;
    // Most lines have no '%': one memchr rather than a count over every character.
    auto percent_count = l.find('%') == std::string_view::npos ? std::size_t{0}
                                                                : static_cast<std::size_t>(std::count(l.begin(), l.end(), '%'));
    if (!comment_open && defines_register_name(l, tok)) --percent_count;  // RIODEF SPD_REF%[...]
    if (comment_open) {
      // Continue the open comment whatever this line holds.
    } else if (tok.empty() && l.find('%') == std::string_view::npos) {
      if (!in_block) close(pos);
    } else if (is_statement_keyword(tok)) {
      close(pos);
      cur = Span{pos, 0, line, tok == "SOR"                      ? SpanKind::Rung
                               : (tok == "DATA" || tok == "FORCE") ? SpanKind::Data
                                                                   : SpanKind::Keyword};
    } else if (l.find_first_not_of(" \t\r") < l.size() && l[l.find_first_not_of(" \t\r")] == '%' && !in_block &&
               !(cur && cur->kind == SpanKind::Rung)) {
      close(pos);
      cur = Span{pos, 0, line, SpanKind::Comment};
    } else if (!cur) {
      cur = Span{pos, 0, line, SpanKind::Other};
    }
    // A line of the rung's own (not a comment line, nor a line inside a comment begun above it).
    if (cur && cur->kind == SpanKind::Rung && !comment_open) {
      auto b = l.find_first_not_of(" \t\r\n");
      if (b != std::string_view::npos && l[b] != '%') cur->content_end = next;
    }
    if (percent_count % 2 == 1) comment_open = !comment_open;
    // A comment statement ends with its line once the comment is closed; a rung ends with the
    // line that closes it with EOR.
    if (cur && cur->kind == SpanKind::Comment && !comment_open) close(next);
    if (cur && cur->kind == SpanKind::Rung && !comment_open) {
      auto t = l.substr(0, l.find_last_not_of(" \t\r\n") + 1);
      if (t.size() >= 3 && t.substr(t.size() - 3) == "EOR" &&
          (t.size() == 3 || t[t.size() - 4] == ' ' || t[t.size() - 4] == '\t'))
        close(next);
    }
    pos = next;
    ++line;
  }
  close(text.size());
}

// What the syntax pass leaves for the semantic checks. A rung with a syntax error is dropped and
// the rest are checked; a declaration (START, SLOT, LADDER, SYMBOL, DATA, ...) or stray text with
// one stops the semantic checks, since every later check depends on the declarations (a
// misspelt LADDER puts its rungs in the file before it; a broken SLOT makes its I/O "no module").
struct SyntaxOutcome {
  bool declarations_parsed = true;
  std::set<int> files_missing_rungs;  // program files that lost a rung (a JMP's label may be on it)
};

SyntaxOutcome parse_statements(LoadState& state, std::string_view text, const std::string& source_name) {
  SyntaxOutcome outcome;
  split_statements(text, [&](const Span& span) {
    // StatementInput holds the source name by pointer and computes positions only where asked.
    StatementInput in(text.data() + span.begin, text.data() + span.end, source_name.c_str(), span.begin, span.line);
    const std::size_t errors_before = state.diags.error_count();
    const std::size_t rungs_before = state.current_file >= 0 ? state.program.files[state.current_file].rungs.size() : 0;
    try {
      pegtl::parse<grammar::statement, action, grammar::control>(in, state);
      // A rung comment is only the comment directly above its SOR: any other statement in
      // between detaches it.
      if (span.kind != SpanKind::Comment && span.kind != SpanKind::Rung) state.pending_comments.clear();
    } catch (const pegtl::parse_error& e) {
      const auto& p = e.positions().front();
      std::string msg(e.message());
      // A rung runs on into the comment lines after it only when it lacks EOR: an error there
      // (at a '%' the rung grammar does not take) is that missing EOR.
      if (span.kind == SpanKind::Rung && span.content_end > span.begin && p.byte >= span.content_end)
        msg = grammar::error_message<grammar::rung_end>;
      // An error at the end of a statement (something missing) is reported just after its last
      // character, on its own line, rather than at the start of the next line; for a rung, after
      // its own last character, not after the comment lines above the next rung.
      const std::size_t stop = span.kind == SpanKind::Rung && span.content_end > span.begin ? span.content_end : span.end;
      auto last = text.find_last_not_of(" \t\r\n", stop == 0 ? 0 : stop - 1);
      if (last != std::string_view::npos && last >= span.begin && p.byte > last) {
        auto line_start = text.rfind('\n', last);
        line_start = line_start == std::string_view::npos ? 0 : line_start + 1;
        auto line = span.line + static_cast<std::size_t>(std::count(text.begin() + span.begin, text.begin() + last, '\n'));
        state.diags.error(static_cast<std::uint32_t>(line), static_cast<std::uint32_t>(last - line_start + 2), msg);
      } else {
        state.diags.error(static_cast<std::uint32_t>(p.line), static_cast<std::uint32_t>(p.column), msg);
      }
      // Leave no partial statement behind.
      state.open_branches.clear();
      state.rung = {};
      state.operands.clear();
      state.pending_comments.clear();
    }
    if (state.diags.error_count() == errors_before) return;
    if (span.kind == SpanKind::Rung) {
      // A rung that parsed with an error (an unknown mnemonic, a stray BND) was kept by its
      // action: drop it too, so no semantic check reports what follows from that error.
      if (state.current_file >= 0) {
        auto& file = state.program.files[state.current_file];
        if (file.rungs.size() > rungs_before) file.rungs.resize(rungs_before);
        outcome.files_missing_rungs.insert(file.number);
      }
    } else {
      // Includes a comment left open, which swallows the rest of the file, declarations too.
      outcome.declarations_parsed = false;
    }
  });
  return outcome;
}

}  // namespace

// ---- Public API ------------------------------------------------------------------------------------

namespace {
// The syntax pass: `program` holds what parsed (every statement that had no error).
SyntaxOutcome parse_into(LoadResult& r, Program& program, bool& have_start) {
  program.source_name = r.source_name;
  LoadState state(program, r.diagnostics, r.source);
  SyntaxOutcome outcome = parse_statements(state, r.source, r.source_name);
  have_start = state.have_start;
  if (!state.have_start && outcome.declarations_parsed)
    r.diagnostics.error(1, 1, "missing START statement naming the processor (for example 'START 1747-L532')");
  return outcome;
}
}  // namespace

LoadResult parse_program_syntax(std::string text, std::string source_name) {
  LoadResult r;
  r.source = std::move(text);
  r.source_name = std::move(source_name);
  Program program;
  bool have_start = false;
  parse_into(r, program, have_start);
  if (!r.diagnostics.has_errors()) r.program = std::move(program);
  r.diagnostics.sort_by_position();
  return r;
}

bool is_pasted_rungs(std::string_view text) {
  // The first statement (skipping blank and comment lines) is a rung, and no line starts with
  // START or LADDER: what RSLogix puts on the clipboard when rungs are copied.
  bool first_statement_seen = false, first_is_rung = false;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    auto b = line.find_first_not_of(" \t\r");
    if (b == std::string_view::npos) continue;
    line = line.substr(b);
    if (line.rfind("START", 0) == 0 || line.rfind("LADDER", 0) == 0) return false;
    if (!first_statement_seen && line[0] != '%') {
      first_statement_seen = true;
      first_is_rung = line.rfind("SOR", 0) == 0;
    }
  }
  return first_is_rung;
}

LoadResult load_pasted_rungs(std::string text, std::string source_name, const ProcessorModel& processor) {
  LoadResult r;
  r.source = std::move(text);
  r.source_name = std::move(source_name);
  Program program;
  program.source_name = r.source_name;
  LoadState state(program, r.diagnostics, r.source);
  // As if the text were preceded by "START <catalog>" and "LADDER 2": the rungs land in program
  // file 2, and the checker adds the processor's default data files and embedded I/O.
  state.have_start = true;
  program.processor = processor;
  ProgramFile main_file;
  main_file.number = 2;
  main_file.pos = {1, 1};
  program.files.push_back(std::move(main_file));
  state.current_file = 0;
  parse_statements(state, r.source, r.source_name);
  if (!r.diagnostics.has_errors()) {
    check_program(program, r.diagnostics);
    if (!r.diagnostics.has_errors()) r.program = std::move(program);
  }
  r.diagnostics.sort_by_position();
  return r;
}

LoadResult load_program(std::string text, std::string source_name) {
  LoadResult r;
  r.source = std::move(text);
  r.source_name = std::move(source_name);
  Program program;
  bool have_start = false;
  const SyntaxOutcome syntax = parse_into(r, program, have_start);
  // Every independent error in one pass: the rungs that parsed are checked even when others did
  // not (those are skipped, and so is what could depend on them); nothing is checked against
  // declarations that failed to parse.
  if (have_start && syntax.declarations_parsed) check_program(program, r.diagnostics, syntax.files_missing_rungs);
  r.diagnostics.sort_by_position();
  if (!r.diagnostics.has_errors()) r.program = std::move(program);
  return r;
}

LoadResult load_program_file(const std::filesystem::path& path) {
  // Regular files only, with a size limit (input_file.h); read as bytes, since the content tells
  // a project file from export text, whose encoding load_program_bytes settles.
  InputFile in = read_input_file(path, InputKind::Binary);
  if (!in.ok) {
    LoadResult r;
    r.source_name = path.string();
    r.diagnostics.error(0, 0, in.error);
    return r;
  }
  return load_program_bytes(std::move(in.contents), path.string());
}

LoadResult load_converted_project(std::string text, const std::vector<rss::RungOrigin>& origins, std::string source_name) {
  LoadResult r = load_program(std::move(text), std::move(source_name));
  // Diagnostics point into the converted text; name the program file and rung as well, since
  // the user knows the project by its rungs, not by the lines of a text they never saw.
  std::map<std::uint32_t, const rss::RungOrigin*> origin_of_line;
  for (const auto& o : origins) origin_of_line[o.line] = &o;
  DiagnosticList named;
  for (const auto& d : r.diagnostics.items()) {
    std::string msg = d.message;
    if (auto o = origin_of_line.find(d.line); o != origin_of_line.end())
      msg = "program file " + std::to_string(o->second->file) + " rung " + std::to_string(o->second->rung) + ": " + msg;
    if (d.severity == Severity::Error) named.error(d.line, d.column, msg);
    else if (d.severity == Severity::Warning) named.warning(d.line, d.column, msg);
    else named.note(d.line, d.column, msg);
  }
  r.diagnostics = std::move(named);
  return r;
}

LoadResult load_program_bytes(std::string bytes, std::string source_name) {
  if (rss::looks_like_ole2(bytes)) {
    rss::ReadResult rr = rss::read_project(bytes, source_name);
    if (!rr.text) {
      LoadResult r;
      r.source_name = std::move(source_name);
      r.diagnostics.error(0, 0, rr.error);
      return r;
    }
    return load_converted_project(std::move(*rr.text), rr.origins, std::move(source_name));
  }
  // Text (before the NUL test, which UTF-16 would fail): a UTF-8 byte-order mark is dropped, UTF-16 refused with what to do about it.
  if (std::string error = normalise_text_encoding(bytes); !error.empty()) {
    LoadResult r;
    r.source_name = std::move(source_name);
    r.diagnostics.error(0, 0, error);
    return r;
  }
  // A NUL byte never occurs in export text; other binary files are refused here rather than
  // parsed, so their bytes are never echoed to the terminal in a diagnostic excerpt.
  if (bytes.find('\0') != std::string::npos) {
    LoadResult r;
    r.source_name = std::move(source_name);
    r.diagnostics.error(0, 0, "not an RSLogix 500 export text or project file (binary content)");
    return r;
  }
  return load_program(std::move(bytes), std::move(source_name));
}

namespace {
struct AddressOnlyState {
  std::optional<Address> address;
  void on_address(const Address& a, SourcePos) { address = a; }
};
}  // namespace

std::optional<Address> parse_address(std::string_view text, std::string* error) {
  pegtl::memory_input in(text.data(), text.data() + text.size(), "address");
  AddressOnlyState state;
  try {
    if (pegtl::parse<grammar::address_only, action, grammar::control>(in, state) && state.address) return state.address;
    if (error) *error = "not an address: '" + std::string(text) + "'";
  } catch (const pegtl::parse_error& e) {
    if (error) *error = "column " + std::to_string(e.positions().front().column) + ": " + std::string(e.message());
  }
  return std::nullopt;
}

}  // namespace softslc
