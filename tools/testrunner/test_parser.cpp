// Actions of the test grammar and the line-by-line driver that assembles tests.
//
// Each line is parsed into a ParsedLine by the actions below. Conditions are built in their own
// small states (PEGTL change_states): a leaf comparison, and the operand lists of `and` and `or`,
// so an alternative that fails and backtracks leaves nothing behind. The driver then places the
// lines into tests, expands table rows and reports structural errors (a step outside a test, a
// row without a table, a test without a program, ...).
#include "tools/testrunner/test_parser.h"

#include <algorithm>
#include <cctype>
#include <map>
#include <optional>
#include <set>
#include <tuple>

#include "parser/limits.h"
#include "parser/loader.h"
#include "tools/testrunner/test_grammar.h"
#include "vm/message_network.h"
#include "tools/testrunner/test_grammar_messages.h"

namespace softslc::testing {

namespace pegtl = tao::pegtl;

namespace {

using namespace grammar;

// ---- Parsed lines ------------------------------------------------------------------------------------

struct ParsedLine {
  enum class Kind : std::uint8_t { Empty, Program, Bench, Node, Ip, Peer, Channel, Test, Row, Step };
  Kind kind = Kind::Empty;
  Location loc;  // the statement's first token
  std::string path;
  Location path_loc;
  std::string processor;  // program PATH processor SPEC
  Location processor_loc;
  std::string peer_name;  // peer NAME PATH node N
  Location peer_loc;
  std::int64_t node = 0;  // node N, peer ... node N
  Location node_loc;
  std::uint32_t ip = 0;   // ip A.B.C.D, peer ... ip A.B.C.D
  Location ip_loc;
  std::string network;    // channel 1 node N network NAME, peer ... node N network NAME
  Location network_loc;
  int channel = -1;       // channel N ...
  bool df1 = false;       // channel 0 df1 ..., peer ... df1 ...
  Df1Options df1_options;
  std::string df1_text;
  bool modbus = false;    // peer ... modbus ...
  modbus::SlaveOptions modbus_options;
  std::string modbus_text;
  std::string test_name;
  Location name_loc;  // the opening quote of the test name
  std::vector<std::pair<std::string, Location>> columns;
  std::vector<std::pair<std::string, Location>> row_values;
  Step step;
  std::uint32_t comment_column = 0;  // 1-based column of '#' starting a comment, 0 = none
};

Location loc_of(const pegtl::position& p) {
  return {static_cast<std::uint32_t>(p.line), static_cast<std::uint32_t>(p.column)};
}

template <typename Input>
Location loc_of(const Input& in) {
  return loc_of(in.position());
}

// Raises a syntax error `offset` characters into the text `in` matched.
template <typename Input>
[[noreturn]] void fail_at(const Input& in, std::size_t offset, const std::string& message) {
  pegtl::position p = in.position();
  p.byte += offset;
  p.column += offset;
  throw pegtl::parse_error(message, std::move(p));
}

std::string strip_quotes(std::string_view s) {
  if (s.size() >= 2 && s.front() == '"' && s.back() == '"') s = s.substr(1, s.size() - 2);
  return std::string(s);
}

// ---- States ---------------------------------------------------------------------------------------------

// The operands and condition of the line being parsed, and the line itself.
struct LineState {
  ParsedLine out;
  std::vector<Operand> operands;
  std::optional<Condition> condition;
  bool unforce_all = false;
  bool words = false;  // expect FILE:a..b == ...
  bool log = false;    // expect log Q == "TEXT" | none
  int log_queue = 0;
  std::string log_text;
  bool log_none = false;

  void add_operand(Operand o) { operands.push_back(std::move(o)); }
  void add_condition(Condition c) { condition = std::move(c); }
};

// One leaf of a condition: a comparison, or fault / no fault / mode.
struct LeafBuilder {
  Condition c;
  bool keyword = false;  // Fault, NoFault or Mode (set by the keyword's action)
  std::vector<Operand> operands;

  void add_operand(Operand o) { operands.push_back(std::move(o)); }

  Condition build() {
    if (!keyword) {
      c.kind = Condition::Kind::Compare;
      c.compare.lhs = operands.at(0);
      c.compare.rhs = operands.at(1);
      if (c.compare.op == CompareOp::In) c.compare.high = operands.at(2);
      c.loc = c.compare.lhs.loc;
    }
    return std::move(c);
  }
};

// The terms of an `and` or an `or`.
struct CondList {
  std::vector<Condition> terms;
  void add_condition(Condition c) { terms.push_back(std::move(c)); }

  Condition combine(Condition::Kind kind) {
    if (terms.size() == 1) return std::move(terms.front());
    Condition c;
    c.kind = kind;
    c.loc = terms.front().loc;
    c.terms = std::move(terms);
    return c;
  }
};

// ---- Actions ------------------------------------------------------------------------------------------

template <typename Rule>
struct action : pegtl::nothing<Rule> {};

// Data operands. Addresses are re-parsed by the program parser's parse_address(), which applies
// the same checks a program gets (file numbers, sub-element and bit names).
template <typename Input>
Address address_or_fail(const Input& in, std::string_view text) {
  std::string error;
  auto a = parse_address(text, &error);
  if (a) return *a;
  // parse_address reports "column N: message"; move the caret to that column of the token.
  std::size_t offset = 0;
  if (error.rfind("column ", 0) == 0) {
    auto colon = error.find(": ");
    offset = static_cast<std::size_t>(std::max(0, std::stoi(error.substr(7, colon - 7)) - 1));
    error = error.substr(colon + 2);
  }
  fail_at(in, offset, error);
}

Operand data_operand_of(Location loc, std::string spelling) {
  Operand o;
  o.kind = Operand::Kind::Data;
  o.loc = loc;
  o.spelling = spelling;
  o.data.loc = loc;
  o.data.spelling = std::move(spelling);
  return o;
}

// The length of a `NAME.` controller prefix at the start of a data operand (B.N7:0), 0 without one.
std::size_t controller_prefix_length(std::string_view text) {
  std::size_t i = 0;
  while (i < text.size() && (std::isalnum(static_cast<unsigned char>(text[i])) || text[i] == '_')) ++i;
  return i > 0 && i < text.size() && text[i] == '.' && !std::isdigit(static_cast<unsigned char>(text[0])) ? i + 1 : 0;
}

// A data operand as written, its controller prefix taken off into data.controller.
template <typename Input>
Operand prefixed_operand(const Input& in, std::size_t& prefix) {
  Operand o = data_operand_of(loc_of(in), in.string());
  prefix = controller_prefix_length(in.string_view());
  if (prefix) o.data.controller = std::string(in.string_view().substr(0, prefix - 1));
  return o;
}

template <typename Input>
Address address_or_fail_at(const Input& in, std::string_view text, std::size_t offset) {
  std::string error;
  if (auto a = parse_address(text, &error)) return *a;
  if (offset == 0) return address_or_fail(in, text);
  fail_at(in, offset, error);
}

template <> struct action<address> {
  template <typename Input, typename State>
  static void apply(const Input& in, State& s) {
    std::size_t prefix = 0;
    Operand o = prefixed_operand(in, prefix);
    o.data.address = address_or_fail_at(in, in.string_view().substr(prefix), prefix);
    s.add_operand(std::move(o));
  }
};

template <> struct action<address_range> {
  template <typename Input, typename State>
  static void apply(const Input& in, State& s) {
    std::size_t prefix = 0;
    Operand o = prefixed_operand(in, prefix);
    const std::string_view text = in.string_view().substr(prefix);
    const auto dots = text.find("..");
    o.data.address = address_or_fail_at(in, text.substr(0, dots), prefix);
    const std::string_view last = text.substr(dots + 2);
    if (last.size() > 5) fail_at(in, prefix + dots + 2, "element number out of range");
    o.data.range_last = std::stoi(std::string(last));
    if (o.data.range_last < o.data.address.element)
      fail_at(in, prefix + dots + 2, "the range ends before it starts (write FIRST..LAST, for example N11:0..13)");
    s.add_operand(std::move(o));
  }
};

template <> struct action<symbol> {
  template <typename Input, typename State>
  static void apply(const Input& in, State& s) {
    std::size_t prefix = 0;
    Operand o = prefixed_operand(in, prefix);
    o.data.symbol = std::string(in.string_view().substr(prefix));
    s.add_operand(std::move(o));
  }
};

// `device NAME WHAT[K]`: the grammar has checked the shape, so the text splits on blanks.
template <> struct action<device_observation> {
  template <typename Input, typename State>
  static void apply(const Input& in, State& s) {
    const std::string text = in.string();
    std::vector<std::pair<std::string, std::size_t>> words;  // word, offset in the text
    for (std::size_t pos = 0; pos < text.size();) {
      const auto b = text.find_first_not_of(" \t", pos);
      if (b == std::string::npos) break;
      const auto e = std::min(text.find_first_of(" \t", b), text.size());
      words.emplace_back(text.substr(b, e - b), b);
      pos = e;
    }
    Operand o;
    o.kind = Operand::Kind::Device;
    o.loc = loc_of(in);
    o.spelling = text;
    DeviceRef& d = o.device;
    d.spelling = text;
    d.loc = o.loc;
    // The grammar matched `device NAME WHAT`: there are at least three words.
    d.name = words.at(1).first;  // cppcheck-suppress containerOutOfBounds
    d.name_loc = {o.loc.line, o.loc.column + static_cast<std::uint32_t>(words[1].second)};  // cppcheck-suppress containerOutOfBounds
    for (std::size_t i = 2; i < words.size(); ++i) d.what += (i > 2 ? " " : "") + words[i].first;
    if (const auto bracket = d.what.find('['); bracket != std::string::npos) {
      const std::string digits = d.what.substr(bracket + 1, d.what.size() - bracket - 2);
      if (digits.size() > 5) fail_at(in, text.find('['), "element index out of range (at most 65535)");
      d.index = std::stoi(digits);
      d.what.resize(bracket);
    }
    s.add_operand(std::move(o));
  }
};

// Literals.
struct literal_action {
  template <typename Input, typename State>
  static void apply(const Input& in, State& s) {
    std::string error;
    auto l = parse_literal(in.string_view(), &error);
    if (!l) fail_at(in, 0, error);
    l->loc = loc_of(in);
    Operand o;
    o.kind = Operand::Kind::Literal;
    o.loc = l->loc;
    o.spelling = l->spelling;
    o.literal = std::move(*l);
    s.add_operand(std::move(o));
  }
};
template <> struct action<value> : literal_action {};
template <> struct action<value_high> : literal_action {};
template <> struct action<set_value> : literal_action {};
template <> struct action<force_value> : literal_action {};

// Durations.
struct duration_action {
  template <typename Input, typename State>
  static void apply(const Input& in, State& s) {
    std::string error;
    auto d = parse_duration(in.string_view(), &error);
    if (!d) fail_at(in, 0, error);
    Operand o;
    o.kind = Operand::Kind::Duration;
    o.duration = *d;
    o.loc = loc_of(in);
    o.spelling = in.string();
    s.add_operand(std::move(o));
  }
};
template <> struct action<duration> : duration_action {};
template <> struct action<duration_high> : duration_action {};
template <> struct action<elapsed_rhs> : duration_action {};
template <> struct action<within_duration> : duration_action {};
template <> struct action<run_duration> : duration_action {};

// Counts.
struct count_action {
  template <typename Input, typename State>
  static void apply(const Input& in, State& s) {
    const std::string_view text = in.string_view();
    if (text.size() > 10 || std::stoll(std::string(text)) > 2'147'483'647)
      fail_at(in, 0, "count too large (at most 2147483647)");
    Operand o;
    o.kind = Operand::Kind::Count;
    o.count = std::stoll(std::string(text));
    o.loc = loc_of(in);
    o.spelling = in.string();
    s.add_operand(std::move(o));
  }
};
template <> struct action<count> : count_action {};
template <> struct action<count_high> : count_action {};
template <> struct action<scans_rhs> : count_action {};
template <> struct action<scan_count> : count_action {};

// `elapsed` and `scans` as the left-hand side of a comparison.
template <Operand::Kind K>
struct subject_action {
  template <typename Input>
  static void apply(const Input& in, LeafBuilder& s) {
    Operand o;
    o.kind = K;
    o.loc = loc_of(in);
    o.spelling = in.string();
    s.add_operand(std::move(o));
  }
};
template <> struct action<elapsed_subject> : subject_action<Operand::Kind::Elapsed> {};
template <> struct action<scans_subject> : subject_action<Operand::Kind::Scans> {};

// Comparison operators.
template <CompareOp Op>
struct op_action {
  template <typename Input>
  static void apply(const Input&, LeafBuilder& s) { s.c.compare.op = Op; }
};
template <> struct action<op_eq> : op_action<CompareOp::Eq> {};
template <> struct action<op_ne> : op_action<CompareOp::Ne> {};
template <> struct action<op_lt> : op_action<CompareOp::Lt> {};
template <> struct action<op_le> : op_action<CompareOp::Le> {};
template <> struct action<op_gt> : op_action<CompareOp::Gt> {};
template <> struct action<op_ge> : op_action<CompareOp::Ge> {};
template <> struct action<kw_in> : op_action<CompareOp::In> {};

// fault [CODE], no fault, mode NAME.
template <> struct action<kw_fault> {
  template <typename Input>
  static void apply(const Input& in, LeafBuilder& s) {
    s.keyword = true;
    s.c.kind = Condition::Kind::Fault;
    s.c.loc = loc_of(in);
  }
};
template <> struct action<fault_code> {
  template <typename Input>
  static void apply(const Input& in, LeafBuilder& s) {
    std::string error;
    auto l = parse_literal(in.string_view(), &error);
    if (!l) fail_at(in, 0, error);
    if (l->kind != Literal::Kind::Integer || l->integer < 0 || l->integer > 0xFFFF)
      fail_at(in, 0, "a fault code is a 16-bit number such as 0020h or 0x0022");
    l->loc = loc_of(in);
    s.c.fault_code = static_cast<std::uint16_t>(l->integer);
    s.c.fault_literal = std::move(*l);
  }
};
template <> struct action<no_fault_primary> {
  template <typename Input>
  static void apply(const Input& in, LeafBuilder& s) {
    s.keyword = true;
    s.c.kind = Condition::Kind::NoFault;
    s.c.fault_code.reset();
    s.c.loc = loc_of(in);
  }
};

Mode mode_from(std::string_view name) {
  if (name == "program") return Mode::Program;
  if (name == "test") return Mode::Test;
  if (name == "faulted") return Mode::Faulted;
  if (name == "suspended") return Mode::Suspended;
  return Mode::Run;
}

template <> struct action<mode_primary> {
  template <typename Input>
  static void apply(const Input& in, LeafBuilder& s) {
    s.keyword = true;
    s.c.kind = Condition::Kind::Mode;
    s.c.loc = loc_of(in);
  }
};
template <> struct action<condition_mode_name> {
  template <typename Input>
  static void apply(const Input& in, LeafBuilder& s) { s.c.mode = mode_from(in.string_view()); }
};

// Condition structure: each leaf and each and/or list is built in its own state.
template <> struct action<leaf> : pegtl::change_states<LeafBuilder> {
  template <typename Input, typename Outer>
  static void success(const Input&, LeafBuilder& b, Outer& outer) {
    outer.add_condition(b.build());
  }
};
template <Condition::Kind K>
struct list_action : pegtl::change_states<CondList> {
  template <typename Input, typename Outer>
  static void success(const Input&, CondList& list, Outer& outer) {
    outer.add_condition(list.combine(K));
  }
};
template <> struct action<conjunction> : list_action<Condition::Kind::And> {};
template <> struct action<next_conjunction> : list_action<Condition::Kind::And> {};
template <> struct action<condition> : list_action<Condition::Kind::Or> {};
template <> struct action<nested_condition> : list_action<Condition::Kind::Or> {};

// ---- Line actions ---------------------------------------------------------------------------------------

template <> struct action<line_comment> {
  template <typename Input>
  static void apply(const Input& in, LineState& s) { s.out.comment_column = loc_of(in).column; }
};

struct path_action {
  template <typename Input>
  static void apply(const Input& in, LineState& s) {
    s.out.path = strip_quotes(in.string_view());
    s.out.path_loc = loc_of(in);
    if (s.out.path.empty()) fail_at(in, 0, "the path is empty");
  }
};
template <> struct action<program_path> : path_action {};
template <> struct action<bench_path> : path_action {};
template <> struct action<program_processor_spec> {
  template <typename Input>
  static void apply(const Input& in, LineState& s) {
    s.out.processor = in.string();
    s.out.processor_loc = loc_of(in);
  }
};

template <ParsedLine::Kind K>
struct line_kind_action {
  template <typename Input>
  static void apply(const Input& in, LineState& s) {
    s.out.kind = K;
    s.out.loc = loc_of(in);
  }
};
template <> struct action<program_line> : line_kind_action<ParsedLine::Kind::Program> {};
template <> struct action<node_line> : line_kind_action<ParsedLine::Kind::Node> {};
template <> struct action<ip_line> : line_kind_action<ParsedLine::Kind::Ip> {};
template <> struct action<peer_line> : line_kind_action<ParsedLine::Kind::Peer> {};
template <> struct action<channel_line> : line_kind_action<ParsedLine::Kind::Channel> {};
// `channel 1 node N` is the 1764-LRP's second serial port (1762-RM001C p. 21-12); `channel 0 df1 ...` the
// program's channel 0 as DF1 full-duplex (its DH-485 node, where it has one, is the program's `node N`).
template <> struct action<channel_number> {
  template <typename Input>
  static void apply(const Input& in, LineState& s) {
    if (in.string() != "0" && in.string() != "1")
      fail_at(in, 0, "a 'channel' line is for channel 1 (a 1764-LRP's second serial port: channel 1 node N) or "
                     "channel 0 (DF1 full-duplex: channel 0 df1)");
    s.out.channel = in.string() == "1" ? 1 : 0;
  }
};
template <> struct action<channel_node> {
  template <typename Input>
  static void apply(const Input& in, LineState& s) {
    if (s.out.channel != 1)
      fail_at(in, 0, "'node N' is for channel 1 (a 1764-LRP's second serial port); channel 0 takes 'df1 "
                     "[SETTING...]' (DF1 full-duplex), and its DH-485 node is the program's 'node N'");
  }
};
template <> struct action<df1_setting> {
  template <typename Input>
  static void apply(const Input& in, LineState& s) {
    if (std::string why = df1_parse_option(in.string_view(), s.out.df1_options); !why.empty()) fail_at(in, 0, "df1: " + why);
    s.out.df1_text += " " + in.string();
  }
};
template <> struct action<kw_modbus> {
  template <typename Input>
  static void apply(const Input&, LineState& s) {
    s.out.modbus = true;
  }
};
template <> struct action<modbus_setting> {
  template <typename Input>
  static void apply(const Input& in, LineState& s) {
    if (std::string why = modbus::parse_slave_option(in.string_view(), s.out.modbus_options); !why.empty())
      fail_at(in, 0, "modbus: " + why);
    s.out.modbus_text += " " + in.string();
  }
};
template <> struct action<kw_df1> {
  template <typename Input>
  static void apply(const Input& in, LineState& s) {
    if (s.out.channel == 1)
      fail_at(in, 0, "DF1 full-duplex is channel 0's (the RS-232 port, 1747-RM001G p. 13-49): write 'channel 0 df1'");
    s.out.df1 = true;
  }
};
template <> struct action<network_name> {
  template <typename Input>
  static void apply(const Input& in, LineState& s) {
    s.out.network = in.string();
    s.out.network_loc = loc_of(in);
  }
};
template <> struct action<ip_address> {
  template <typename Input>
  static void apply(const Input& in, LineState& s) {
    const std::optional<std::uint32_t> ip = parse_ipv4(in.string());
    if (!ip) fail_at(in, 0, "'" + in.string() + "' is not an IP address: four numbers 0-255 separated by dots");
    if (*ip == 0) fail_at(in, 0, "0.0.0.0 is the processor's 'no IP address configured'; give the station an address");
    s.out.ip = *ip;
    s.out.ip_loc = loc_of(in);
  }
};
template <> struct action<peer_path> : path_action {};
template <> struct action<peer_name> {
  template <typename Input>
  static void apply(const Input& in, LineState& s) {
    s.out.peer_name = in.string();
    s.out.peer_loc = loc_of(in);
  }
};
template <> struct action<node_number> {
  template <typename Input>
  static void apply(const Input& in, LineState& s) {
    if (in.size() > 3 || std::stoi(in.string()) > 255) fail_at(in, 0, "node number out of range 0-255");
    s.out.node = std::stoi(in.string());
    s.out.node_loc = loc_of(in);
  }
};
template <> struct action<bench_line> : line_kind_action<ParsedLine::Kind::Bench> {};
template <> struct action<test_line> : line_kind_action<ParsedLine::Kind::Test> {};
template <> struct action<row_line> : line_kind_action<ParsedLine::Kind::Row> {};

template <> struct action<test_name> {
  template <typename Input>
  static void apply(const Input& in, LineState& s) {
    s.out.test_name = strip_quotes(in.string_view());
    s.out.name_loc = loc_of(in);
    if (s.out.test_name.find_first_not_of(" \t") == std::string::npos) fail_at(in, 0, "a test needs a name");
  }
};
template <> struct action<column_name> {
  template <typename Input>
  static void apply(const Input& in, LineState& s) {
    for (const auto& [name, where] : s.out.columns)
      if (name == in.string()) fail_at(in, 0, "column '" + name + "' is named twice");
    s.out.columns.emplace_back(in.string(), loc_of(in));
  }
};
template <> struct action<row_value> {
  template <typename Input>
  static void apply(const Input& in, LineState& s) { s.out.row_values.emplace_back(in.string(), loc_of(in)); }
};

// Steps. Each sets the step kind at the end of its line; operands arrived in order.
template <typename Input>
Step& begin_step(const Input& in, LineState& s, Step::Kind kind) {
  s.out.kind = ParsedLine::Kind::Step;
  s.out.loc = loc_of(in);
  s.out.step.kind = kind;
  s.out.step.loc = loc_of(in);
  return s.out.step;
}

std::vector<Literal> literals_from(const std::vector<Operand>& ops, std::size_t first) {
  std::vector<Literal> out;
  for (std::size_t i = first; i < ops.size(); ++i) out.push_back(ops[i].literal);
  return out;
}

template <> struct action<set_line> {
  template <typename Input>
  static void apply(const Input& in, LineState& s) {
    Step& step = begin_step(in, s, Step::Kind::Set);
    step.target = s.operands.at(0).data;
    step.values = literals_from(s.operands, 1);
  }
};
template <> struct action<force_line> {
  template <typename Input>
  static void apply(const Input& in, LineState& s) {
    Step& step = begin_step(in, s, Step::Kind::Force);
    step.target = s.operands.at(0).data;
    step.values = literals_from(s.operands, 1);
  }
};
template <> struct action<unforce_all> {
  template <typename Input>
  static void apply(const Input&, LineState& s) { s.unforce_all = true; }
};
template <> struct action<unforce_line> {
  template <typename Input>
  static void apply(const Input& in, LineState& s) {
    Step& step = begin_step(in, s, s.unforce_all ? Step::Kind::UnforceAll : Step::Kind::Unforce);
    if (!s.unforce_all) step.target = s.operands.at(0).data;
  }
};
template <> struct action<scan_line> {
  template <typename Input>
  static void apply(const Input& in, LineState& s) {
    Step& step = begin_step(in, s, Step::Kind::Scan);
    step.count = s.operands.at(0).count;
    if (step.count < 1) fail_at(in, 5, "scan needs at least 1 scan");
  }
};
template <> struct action<run_line> {
  template <typename Input>
  static void apply(const Input& in, LineState& s) {
    Step& step = begin_step(in, s, s.condition ? Step::Kind::RunUntil : Step::Kind::Run);
    const Operand& d = s.operands.back();
    step.duration = d.duration;
    if (s.condition) step.condition = std::move(*s.condition);
    if (step.duration <= 0) {
      pegtl::position p = in.position();
      p.column = d.loc.column;
      throw pegtl::parse_error("the duration must be longer than 0", std::move(p));
    }
  }
};
template <> struct action<expect_words> {
  template <typename Input>
  static void apply(const Input&, LineState& s) { s.words = true; }
};
template <> struct action<log_queue> {
  template <typename Input>
  static void apply(const Input& in, LineState& s) {
    s.log = true;
    const auto t = in.string_view();
    s.log_queue = t.size() > 3 ? 256 : std::stoi(std::string(t));
    if (s.log_queue > 255) throw pegtl::parse_error("data log queues are 0-255", in);
  }
};
template <> struct action<log_text> {
  template <typename Input>
  static void apply(const Input& in, LineState& s) {
    // \t stands for the TAB delimiter.
    std::string text;
    const auto t = in.string_view();
    for (std::size_t i = 0; i < t.size(); ++i) {
      if (t[i] == '\\' && i + 1 < t.size() && t[i + 1] == 't') {
        text += '\t';
        ++i;
      } else {
        text += t[i];
      }
    }
    s.log_text = std::move(text);
  }
};
template <> struct action<log_none> {
  template <typename Input>
  static void apply(const Input&, LineState& s) { s.log_none = true; }
};
template <> struct action<expect_line> {
  template <typename Input>
  static void apply(const Input& in, LineState& s) {
    if (s.log) {
      Step& step = begin_step(in, s, Step::Kind::ExpectLog);
      step.count = s.log_queue;
      step.name = s.log_text;
      step.none = s.log_none;
    } else if (s.words) {
      Step& step = begin_step(in, s, Step::Kind::ExpectWords);
      step.target = s.operands.at(0).data;
      step.values = literals_from(s.operands, 1);
    } else {
      Step& step = begin_step(in, s, Step::Kind::Expect);
      step.condition = std::move(*s.condition);
    }
  }
};
template <> struct action<step_mode_name> {
  template <typename Input>
  static void apply(const Input& in, LineState& s) { s.out.step.mode = mode_from(in.string_view()); }
};
template <> struct action<mode_line> {
  template <typename Input>
  static void apply(const Input& in, LineState& s) { begin_step(in, s, Step::Kind::Mode); }
};
template <> struct action<power_line> {
  template <typename Input>
  static void apply(const Input& in, LineState& s) { begin_step(in, s, Step::Kind::PowerCycle); }
};
template <> struct action<clear_line> {
  template <typename Input>
  static void apply(const Input& in, LineState& s) { begin_step(in, s, Step::Kind::ClearFault); }
};
template <> struct action<snapshot_name> {
  template <typename Input>
  static void apply(const Input& in, LineState& s) { s.out.step.name = in.string(); }
};
template <> struct action<restore_name> : action<snapshot_name> {};
template <> struct action<snapshot_line> {
  template <typename Input>
  static void apply(const Input& in, LineState& s) { begin_step(in, s, Step::Kind::Snapshot); }
};
template <> struct action<restore_line> {
  template <typename Input>
  static void apply(const Input& in, LineState& s) { begin_step(in, s, Step::Kind::Restore); }
};

template <> struct action<device_line_name> {
  template <typename Input>
  static void apply(const Input& in, LineState& s) {
    s.out.step.name = in.string();
    s.out.step.name_loc = loc_of(in);
  }
};
template <> struct action<device_word> {
  template <typename Input>
  static void apply(const Input& in, LineState& s) {
    s.out.step.change += (s.out.step.change.empty() ? "" : " ") + in.string();
  }
};
template <> struct action<device_arg> {
  template <typename Input>
  static void apply(const Input& in, LineState& s) { s.out.step.args.push_back(in.string()); }
};
template <> struct action<device_line> {
  template <typename Input>
  static void apply(const Input& in, LineState& s) { begin_step(in, s, Step::Kind::Device); }
};

// The usage of each statement, for a keyword written without its operands.
constexpr std::pair<std::string_view, std::string_view> kUsage[] = {
    {"program", "program FILE.slc [processor CATALOG]"},
    {"bench", "bench FILE.bench"},
    {"node", "node N"},
    {"ip", "ip A.B.C.D"},
    {"peer", "peer NAME FILE.slc node N [network NAME]  or  peer NAME FILE.slc ip A.B.C.D"},
    {"channel", "channel 1 node N [network NAME]"},
    {"test", "test \"name\"  or  test \"name\" with COLUMN..."},
    {"set", "set ADDRESS = VALUE"},
    {"force", "force I:1/0 = 1"},
    {"unforce", "unforce I:1/0  or  unforce all"},
    {"scan", "scan N"},
    {"run", "run DURATION  or  run until CONDITION within DURATION"},
    {"expect", "expect CONDITION"},
    {"mode", "mode program|run|test"},
    {"power", "power cycle"},
    {"clear", "clear fault"},
    {"snapshot", "snapshot NAME"},
    {"restore", "restore NAME"},
    {"device", "device NAME CHANGE [ARGS...]"},
};

template <> struct action<unknown_statement> {
  template <typename Input>
  static void apply(const Input& in, LineState&) {
    const std::string word = in.string();
    for (const auto& [keyword, usage] : kUsage)
      if (word == keyword) fail_at(in, 0, "incomplete '" + word + "' line: write " + std::string(usage));
    fail_at(in, 0,
            "unknown statement '" + word +
                "': expected program, bench, test, row, set, force, unforce, scan, run, expect, mode, power cycle, "
                "clear fault, snapshot, restore or device");
  }
};

// ---- Lines and substitution -------------------------------------------------------------------------------

struct LineError {
  Location loc;
  std::string message;
};

// Parses one line; returns the error when it does not parse.
std::optional<LineError> parse_line(std::string_view text, std::uint32_t number, const std::string& source,
                                    ParsedLine& out) {
  // Parenthesised conditions recurse in the grammar: bound the nesting before parsing, so 40,000
  // '(' are one positioned error, not a stack overflow. (Quoted text — names, paths — may hold
  // any parentheses.)
  int depth = 0;
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '"') quoted = !quoted;
    else if (quoted) continue;
    else if (text[i] == ')' && depth > 0) --depth;
    else if (text[i] == '(' && ++depth > kMaxExpressionNesting)
      return LineError{Location{number, static_cast<std::uint32_t>(i + 1)},
                       "parentheses nested deeper than " + std::to_string(kMaxExpressionNesting) + " levels"};
  }
  pegtl::memory_input in(text.data(), text.data() + text.size(), source, 0, number, 1);
  LineState state;
  try {
    pegtl::parse<grammar::line, action, grammar::control>(in, state);
  } catch (const pegtl::parse_error& e) {
    return LineError{loc_of(e.positions().front()), std::string(e.message())};
  }
  out = std::move(state.out);
  return std::nullopt;
}

// Where a comment starts: '#' at the start of the line or after a blank, unless it is the index
// mark of an address (#N7:0), which a file-type letter follows.
std::size_t comment_start(std::string_view text) {
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '#') continue;
    if (i > 0 && text[i - 1] != ' ' && text[i - 1] != '\t') continue;
    if (i + 1 < text.size() && std::isupper(static_cast<unsigned char>(text[i + 1]))) continue;
    return i;
  }
  return std::string_view::npos;
}

bool is_ident_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

struct Reference {
  std::size_t pos;  // 0-based index of '$'
  std::string name;
};

// The $NAME references of a line, outside its comment.
std::vector<Reference> references(std::string_view text) {
  std::vector<Reference> refs;
  const std::size_t end = std::min(comment_start(text), text.size());
  for (std::size_t i = 0; i < end; ++i) {
    if (text[i] != '$') continue;
    std::size_t j = i + 1;
    while (j < end && is_ident_char(text[j])) ++j;
    refs.push_back({i, std::string(text.substr(i + 1, j - i - 1))});
    i = j - 1;
  }
  return refs;
}

// A line with row values substituted, and where each character came from.
struct Substituted {
  std::string text;
  std::vector<std::uint32_t> column;  // original 1-based column of text[i]; one more for the end
  struct Region {
    std::size_t begin = 0, end = 0;
    std::string name, value;
  };
  std::vector<Region> regions;

  std::uint32_t original(std::uint32_t col) const {
    if (col == 0) return 0;
    return col - 1 < column.size() ? column[col - 1] : column.back();
  }
  const Region* region_at(std::uint32_t col) const {
    for (const auto& r : regions)
      if (col >= 1 && col - 1 >= r.begin && col - 1 < r.end) return &r;
    return nullptr;
  }
};

Substituted substitute(std::string_view text, const std::vector<Reference>& refs,
                       const std::map<std::string, std::string>& values) {
  Substituted s;
  std::size_t at = 0;
  auto copy = [&](std::size_t upto) {
    for (; at < upto; ++at) {
      s.text += text[at];
      s.column.push_back(static_cast<std::uint32_t>(at + 1));
    }
  };
  for (const auto& r : refs) {
    copy(r.pos);
    const std::string& v = values.at(r.name);
    Substituted::Region region{s.text.size(), s.text.size() + v.size(), r.name, v};
    for (char c : v) {
      s.text += c;
      s.column.push_back(static_cast<std::uint32_t>(r.pos + 1));
    }
    s.regions.push_back(region);
    at = r.pos + 1 + r.name.size();
  }
  copy(text.size());
  s.column.push_back(static_cast<std::uint32_t>(text.size() + 1));
  return s;
}

// Calls f on every Location in a parsed line (to map substituted columns back).
template <typename F>
void for_each_location(Condition& c, F& f) {
  f(c.loc);
  for (Operand* o : {&c.compare.lhs, &c.compare.rhs, &c.compare.high}) {
    f(o->loc);
    f(o->data.loc);
    f(o->literal.loc);
    f(o->device.loc);
    f(o->device.name_loc);
  }
  f(c.fault_literal.loc);
  for (auto& t : c.terms) for_each_location(t, f);
}

template <typename F>
void for_each_location(ParsedLine& l, F f) {
  f(l.loc);
  f(l.path_loc);
  f(l.name_loc);
  for (auto& c : l.columns) f(c.second);
  for (auto& v : l.row_values) f(v.second);
  f(l.step.loc);
  f(l.step.target.loc);
  f(l.step.name_loc);
  for (auto& v : l.step.values) f(v.loc);
  for_each_location(l.step.condition, f);
}

std::string step_text(std::string_view text, std::uint32_t comment_column) {
  if (comment_column > 0) text = text.substr(0, comment_column - 1);
  const auto b = text.find_first_not_of(" \t");
  if (b == std::string_view::npos) return {};
  const auto e = text.find_last_not_of(" \t");
  return std::string(text.substr(b, e - b + 1));
}

// The condition of an expect or run-until step as written: what follows `expect`, or what lies
// between `until` and `within` (a reserved word, so its last occurrence is the keyword).
std::string condition_text_of(const Step& s) {
  std::string_view t = s.text;
  auto skip_word = [&t] {
    t.remove_prefix(std::min(t.find_first_of(" \t"), t.size()));
    t.remove_prefix(std::min(t.find_first_not_of(" \t"), t.size()));
  };
  if (s.kind == Step::Kind::Expect || s.kind == Step::Kind::ExpectWords || s.kind == Step::Kind::ExpectLog) {
    skip_word();
    return std::string(t);
  }
  if (s.kind != Step::Kind::RunUntil) return {};
  skip_word();
  skip_word();
  t = t.substr(0, t.rfind("within"));
  return std::string(t.substr(0, t.find_last_not_of(" \t") + 1));
}

std::string first_word(std::string_view text) {
  const auto b = text.find_first_not_of(" \t");
  if (b == std::string_view::npos) return {};
  const auto e = text.find_first_of(" \t#", b);
  return std::string(text.substr(b, e == std::string_view::npos ? std::string_view::npos : e - b));
}

// ---- The driver -----------------------------------------------------------------------------------------

// A line of a test body: parsed, or kept as text until its row values are known. It and
// PendingTest (a test being collected) live outside Driver so that clang sees them complete
// where std::optional needs them.
struct BodyLine {
  std::uint32_t number = 0;
  std::string raw;
  std::vector<Reference> refs;
  std::optional<ParsedLine> parsed;  // empty for deferred lines and for lines with errors
};
struct PendingTest {
  ParsedLine header;
  bool table = false;
  bool rows_broken = false;  // a row was refused: do not also report "no rows"
  std::vector<BodyLine> body;
  std::vector<ParsedLine> rows;
};

class Driver {
 public:
  Driver(const std::string& text, const std::string& name, DiagnosticList& diags)
      : text_(text), name_(name), diags_(diags) {}

  std::vector<TestCase> run() {
    std::size_t pos = 0;
    std::uint32_t number = 0;
    while (pos <= text_.size()) {
      auto nl = text_.find('\n', pos);
      std::string_view line = std::string_view(text_).substr(pos, nl == std::string::npos ? std::string::npos : nl - pos);
      if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
      ++number;
      handle(line, number);
      if (too_many_steps_ || nl == std::string::npos) break;
      pos = nl + 1;
    }
    finish_test();
    return std::move(tests_);
  }

 private:
  void error(Location at, std::string message) {
    if (seen_.insert({at.line, at.column, message}).second) diags_.error(at.line, at.column, std::move(message));
  }

  void handle(std::string_view raw, std::uint32_t number) {
    const std::string word = first_word(raw);
    auto refs = (word == "test" || word == "row") ? std::vector<Reference>{} : references(raw);
    if (!refs.empty()) {
      if (pending_ && pending_->table) {
        add_body({number, std::string(raw), std::move(refs), std::nullopt});
        return;
      }
      const auto& r = refs.front();
      if (pending_) add_body({number, std::string(raw), {}, std::nullopt});  // a broken line
      error({number, static_cast<std::uint32_t>(r.pos + 1)},
            "'$" + r.name + "' refers to a table column, but this line is not in a table-driven test "
            "(test \"name\" with " + (r.name.empty() ? std::string("COLUMN") : r.name) + ")");
      return;
    }
    ParsedLine pl;
    if (auto e = parse_line(raw, number, name_, pl)) {
      error(e->loc, e->message);
      if (pending_ && word != "test") add_body({number, std::string(raw), {}, std::nullopt});
      if (word == "test") {
        // The test is lost, but its lines still belong to it: keep them from being reported as
        // steps outside a test, or as rows and column references without a table.
        finish_test();
        pending_.emplace();
        pending_->header.kind = ParsedLine::Kind::Empty;
        pending_->table = true;
      }
      return;
    }
    pl.step.text = step_text(raw, pl.comment_column);
    pl.step.condition_text = condition_text_of(pl.step);
    switch (pl.kind) {
      case ParsedLine::Kind::Empty:
        return;
      case ParsedLine::Kind::Test:
        finish_test();
        pending_.emplace();
        pending_->table = !pl.columns.empty();
        pending_->header = std::move(pl);
        return;
      case ParsedLine::Kind::Row:
        if (pending_ && pending_->header.kind != ParsedLine::Kind::Test) return;
        if (!pending_ || !pending_->table) {
          error(pl.loc, "'row' belongs to a table-driven test (test \"name\" with COLUMN...)");
          return;
        }
        if (pl.row_values.size() != pending_->header.columns.size()) {
          std::string cols;
          for (const auto& c : pending_->header.columns) cols += (cols.empty() ? "" : " ") + c.first;
          const Location at = pl.row_values.size() > pending_->header.columns.size()
                                  ? pl.row_values[pending_->header.columns.size()].second
                                  : pl.loc;
          error(at, "this row has " + std::to_string(pl.row_values.size()) + " value(s) but the table has " +
                        std::to_string(pending_->header.columns.size()) + " column(s) (" + cols + ")");
          pending_->rows_broken = true;
          return;
        }
        if (count_line(number)) pending_->rows.push_back(std::move(pl));
        return;
      case ParsedLine::Kind::Program:
      case ParsedLine::Kind::Bench: {
        if (pending_) {
          add_body({number, std::string(raw), {}, std::move(pl)});
          return;
        }
        const bool program = pl.kind == ParsedLine::Kind::Program;
        std::string& path = program ? file_program_ : file_bench_;
        Location& where = program ? file_program_loc_ : file_bench_loc_;
        const char* word = program ? "program" : "bench";
        if (!path.empty()) {
          error(pl.loc, std::string("a second file-level '") + word + "' line (the first is at line " +
                            std::to_string(where.line) + "); name a test's own " + word + " inside the test");
          return;
        }
        path = pl.path;
        where = pl.path_loc;
        if (program) {
          file_program_processor_ = pl.processor;
          file_program_processor_loc_ = pl.processor_loc;
        }
        return;
      }
      case ParsedLine::Kind::Node:
      case ParsedLine::Kind::Ip:
      case ParsedLine::Kind::Channel:
      case ParsedLine::Kind::Peer: {
        // The MSG network is the file's: every test of the file runs on it.
        if (pending_) {
          error(pl.loc, "'node', 'ip', 'channel' and 'peer' lines belong at the top of the file, before the first test");
          return;
        }
        if (pl.kind == ParsedLine::Kind::Channel && pl.channel == 0) {
          if (file_channel0_loc_.line) {
            error(pl.loc, "a second 'channel 0' line (the first is at line " + std::to_string(file_channel0_loc_.line) +
                              ")");
            return;
          }
          file_channel0_df1_ = pl.df1_options;
          file_channel0_text_ = pl.df1_text;
          file_channel0_loc_ = pl.loc;
          return;
        }
        if (pl.kind == ParsedLine::Kind::Channel) {
          if (file_channel1_loc_.line) {
            error(pl.loc, "a second 'channel 1' line (the first is at line " + std::to_string(file_channel1_loc_.line) +
                              ")");
            return;
          }
          file_channel1_node_ = static_cast<int>(pl.node);
          file_channel1_network_ = pl.network;
          file_channel1_loc_ = pl.loc;
          return;
        }
        if (pl.kind == ParsedLine::Kind::Ip) {
          if (file_ip_loc_.line) {
            error(pl.loc, "a second 'ip' line (the first is at line " + std::to_string(file_ip_loc_.line) + ")");
            return;
          }
          file_ip_ = pl.ip;
          file_ip_loc_ = pl.ip_loc;
          return;
        }
        if (pl.kind == ParsedLine::Kind::Node) {
          if (file_node_loc_.line) {
            error(pl.loc, "a second 'node' line (the first is at line " + std::to_string(file_node_loc_.line) + ")");
            return;
          }
          file_node_ = static_cast<int>(pl.node);
          file_node_loc_ = pl.node_loc;
          return;
        }
        for (const auto& p : file_peers_)
          if (p.name == pl.peer_name) {
            error(pl.peer_loc, "peer '" + p.name + "' is already defined at line " + std::to_string(p.loc.line));
            return;
          }
        PeerSpec peer;
        peer.name = pl.peer_name;
        peer.loc = pl.peer_loc;
        peer.path = pl.path;
        peer.path_loc = pl.path_loc;
        peer.node = static_cast<int>(pl.node);
        peer.ip = pl.ip;
        peer.network = pl.network;
        if (pl.modbus) {
          peer.modbus = pl.modbus_options;
          peer.modbus_text = pl.modbus_text;
        }
        if (pl.df1) {
          peer.df1 = true;
          peer.df1_options = pl.df1_options;
          peer.df1_text = pl.df1_text;
        }
        file_peers_.push_back(std::move(peer));
        return;
      }
      case ParsedLine::Kind::Step:
        if (!pending_) {
          error(pl.loc, "a step must belong to a test: start one with test \"name\"");
          return;
        }
        add_body({number, std::string(raw), {}, std::move(pl)});
        return;
    }
  }

  // A test's line, counted against the file's step limit: a file of 40,000 copies of one
  // `expect` line cost 640 MB and 12 s under ASan before the limit (tools/mutate.py, mutant 376).
  // At the limit one error names it and the rest of the file is not read.
  void add_body(BodyLine line) {
    if (count_line(line.number)) pending_->body.push_back(std::move(line));
  }
  // Table rows count too: each one is kept until the table is expanded.
  bool count_line(std::uint32_t number) {
    if (++steps_ <= kMaxStepsPerTestFile) return true;
    error({number, 1}, "more than " + std::to_string(kMaxStepsPerTestFile) +
                           " steps in one test file; split it into several files");
    too_many_steps_ = true;
    return false;
  }

  void finish_test() {
    if (!pending_) return;
    PendingTest t = std::move(*pending_);
    pending_.reset();
    if (t.header.kind != ParsedLine::Kind::Test) return;  // the header itself had an error
    if (!t.table) {
      // Lines with syntax errors are already reported; the test is still built from the others
      // so that their own (independent) errors are found too. The file has errors, so it will
      // not run. Only a broken `program` line would cascade into "no program": that one is
      // not reported again.
      std::vector<ParsedLine> lines;
      bool program_line_broken = false, lines_broken = false;
      for (auto& b : t.body) {
        if (b.parsed) {
          lines.push_back(std::move(*b.parsed));
          continue;
        }
        lines_broken = true;
        if (first_word(b.raw) == "program") program_line_broken = true;
      }
      build_case(t.header.test_name, t.header.loc, lines, false, program_line_broken, lines_broken);
      return;
    }
    if (t.rows.empty()) {
      if (!t.rows_broken) error(t.header.loc, "a table-driven test needs at least one 'row' line");
      return;
    }
    // Each row repeats the body: the expanded steps count against the same limit, in place of
    // the body's lines and the rows, which were counted as they were read.
    const std::size_t before = steps_ - t.body.size() - t.rows.size();
    const std::size_t expanded = t.rows.size() * t.body.size();
    if (before > kMaxStepsPerTestFile || expanded > kMaxStepsPerTestFile - before) {
      error(t.header.loc, "this table-driven test expands to " + std::to_string(expanded) + " steps (" +
                              std::to_string(t.rows.size()) + " rows of " + std::to_string(t.body.size()) +
                              "), more than " + std::to_string(kMaxStepsPerTestFile) + " in one test file");
      too_many_steps_ = true;
      return;
    }
    steps_ = before + expanded;
    for (const auto& row : t.rows) expand_row(t, row);
  }

  // One TestCase from one row of a table-driven test.
  void expand_row(PendingTest& t, const ParsedLine& row) {
    std::map<std::string, std::string> values;
    std::string label;
    for (std::size_t i = 0; i < t.header.columns.size(); ++i) {
      values[t.header.columns[i].first] = row.row_values[i].first;
      label += (i ? ", " : "") + t.header.columns[i].first + "=" + row.row_values[i].first;
    }
    const auto known = [&](const std::string& name) { return values.count(name) > 0; };
    const auto columns_text = [&] {
      std::string s;
      for (const auto& c : t.header.columns) s += (s.empty() ? "" : " ") + c.first;
      return s;
    };
    bool ok = true;

    // The test name: $NAME references inside the quotes.
    std::string name = t.header.test_name;
    auto name_refs = references(name);
    for (const auto& r : name_refs)
      if (!known(r.name)) {
        error({t.header.name_loc.line, t.header.name_loc.column + 1 + static_cast<std::uint32_t>(r.pos)},
              "unknown column '$" + r.name + "' (the table has: " + columns_text() + ")");
        ok = false;
      }
    if (!ok) return;
    name = name_refs.empty() ? name + " [" + label + "]" : substitute(name, name_refs, values).text;

    std::vector<ParsedLine> lines;
    for (auto& b : t.body) {
      if (b.parsed) {
        lines.push_back(*b.parsed);
        continue;
      }
      if (b.refs.empty()) {
        ok = false;  // a line with a syntax error, already reported
        continue;
      }
      bool refs_ok = true;
      for (const auto& r : b.refs)
        if (!known(r.name)) {
          error({b.number, static_cast<std::uint32_t>(r.pos + 1)},
                "unknown column '$" + r.name + "' (the table has: " + columns_text() + ")");
          refs_ok = false;
        }
      if (!refs_ok) {
        ok = false;
        continue;
      }
      Substituted s = substitute(b.raw, b.refs, values);
      ParsedLine pl;
      if (auto e = parse_line(s.text, b.number, name_, pl)) {
        std::string message = e->message;
        if (const auto* r = s.region_at(e->loc.column))
          message += " (from $" + r->name + " = " + r->value + " in the row at line " + std::to_string(row.loc.line) + ")";
        error({e->loc.line, s.original(e->loc.column)}, message);
        ok = false;
        continue;
      }
      pl.step.text = step_text(s.text, pl.comment_column);
      pl.step.condition_text = condition_text_of(pl.step);
      for_each_location(pl, [&](Location& l) {
        if (l.line == b.number) l.column = s.original(l.column);
      });
      lines.push_back(std::move(pl));
    }
    if (ok) build_case(name, row.loc, lines, true, false, false);
  }

  void build_case(const std::string& name, Location at, std::vector<ParsedLine>& lines, bool table,
                  bool program_line_broken, bool lines_broken) {
    TestCase tc;
    tc.name = name;
    tc.loc = at;
    tc.program_path = file_program_;
    tc.program_loc = file_program_loc_;
    tc.program_processor = file_program_processor_;
    tc.program_processor_loc = file_program_processor_loc_;
    tc.bench_path = file_bench_;
    tc.bench_loc = file_bench_loc_;
    tc.node = file_node_;
    tc.node_loc = file_node_loc_;
    tc.ip = file_ip_;
    tc.peers = file_peers_;
    tc.channel1_node = file_channel1_node_;
    tc.channel1_network = file_channel1_network_;
    tc.channel1_loc = file_channel1_loc_;
    tc.channel0_df1 = file_channel0_df1_;
    tc.channel0_text = file_channel0_text_;
    tc.channel0_loc = file_channel0_loc_;
    bool steps_seen = false, ok = true;
    std::optional<Location> own_program, own_bench;
    for (auto& pl : lines) {
      if (pl.kind == ParsedLine::Kind::Program || pl.kind == ParsedLine::Kind::Bench) {
        const bool program = pl.kind == ParsedLine::Kind::Program;
        std::optional<Location>& own = program ? own_program : own_bench;
        const std::string word = program ? "program" : "bench";
        if (steps_seen) {
          error(pl.loc, "a test's '" + word + "' line must come before its first step");
          ok = false;
        } else if (own) {
          error(pl.loc, "this test already names its " + word + " at line " + std::to_string(own->line));
          ok = false;
        } else {
          own = pl.loc;
          (program ? tc.program_path : tc.bench_path) = pl.path;
          (program ? tc.program_loc : tc.bench_loc) = pl.path_loc;
          if (program) {
            tc.program_processor = pl.processor;
            tc.program_processor_loc = pl.processor_loc;
          }
        }
        continue;
      }
      if (pl.kind != ParsedLine::Kind::Step) continue;
      if (!steps_seen && pl.step.kind == Step::Kind::Mode) {
        // A first `mode` step chooses the mode the test starts in (no transition from Run).
        tc.initial_mode = pl.step.mode;
        steps_seen = true;
        continue;
      }
      steps_seen = true;
      if (table && pl.step.kind == Step::Kind::Snapshot) {
        error(pl.loc, "a table-driven test cannot take a snapshot (every row would define it); take it in a plain test");
        ok = false;
        continue;
      }
      tc.steps.push_back(std::move(pl.step));
    }
    // A bench describes the wiring of one program: a test that names its own program does not
    // inherit the file's bench (it names its own, or runs without one).
    if (own_program && !own_bench) {
      tc.bench_path.clear();
      tc.bench_loc = {};
    }
    if (tc.program_path.empty()) {
      if (!program_line_broken)
        error(at, "no program for this test: add 'program FILE.slc' at the top of the file or in the test");
      ok = false;
    }
    if (auto it = names_.find(name); it != names_.end()) {
      error(at, "a test named \"" + name + "\" is already defined at line " + std::to_string(it->second));
      ok = false;
    } else {
      names_[name] = at.line;
    }
    if (!ok) return;
    if (tc.steps.empty() && !lines_broken) diags_.warning(at.line, at.column, "test \"" + name + "\" has no steps");
    tests_.push_back(std::move(tc));
  }

  const std::string& text_;
  const std::string& name_;
  DiagnosticList& diags_;
  std::set<std::tuple<std::uint32_t, std::uint32_t, std::string>> seen_;
  std::string file_program_;
  Location file_program_loc_;
  std::string file_program_processor_;
  Location file_program_processor_loc_;
  std::string file_bench_;
  Location file_bench_loc_;
  int file_node_ = 1;
  Location file_node_loc_;
  std::uint32_t file_ip_ = 0;
  Location file_ip_loc_;
  std::vector<PeerSpec> file_peers_;
  int file_channel1_node_ = 0;
  std::string file_channel1_network_;
  Location file_channel1_loc_;
  std::optional<Df1Options> file_channel0_df1_;
  std::string file_channel0_text_;
  Location file_channel0_loc_;
  std::optional<PendingTest> pending_;
  std::size_t steps_ = 0;         // test lines so far, table rows expanded (kMaxStepsPerTestFile)
  bool too_many_steps_ = false;   // the limit was passed: the rest of the file is not read
  std::map<std::string, std::uint32_t> names_;
  std::vector<TestCase> tests_;
};

}  // namespace

ParseResult parse_test_text(std::string text, std::string name) {
  ParseResult r;
  r.file.name = std::move(name);
  r.file.source = std::move(text);
  Driver driver(r.file.source, r.file.name, r.diagnostics);
  r.file.tests = driver.run();
  r.diagnostics.sort_by_position();
  return r;
}

}  // namespace softslc::testing
