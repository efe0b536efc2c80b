#include "modules/bench/bench.h"

#include <fstream>
#include <map>
#include <sstream>

#include "modules/bench/bench_grammar.h"
#include "modules/bench/bench_messages.h"
#include "parser/input_file.h"
#include "parser/limits.h"
#include "parser/loader.h"
#include "vm/duration.h"

namespace softslc {

namespace {

namespace pegtl = tao::pegtl;
namespace g = bench_grammar;

// The tree being built: `open` holds the nodes whose blocks are open, innermost last; `current`
// is the node whose line is being read.
struct State {
  std::vector<BenchNode> top;
  std::vector<BenchNode*> open;
  BenchNode* current = nullptr;
};

template <typename Input>
SourcePos pos_of(const Input& in) {
  const auto p = in.position();
  return {static_cast<std::uint32_t>(p.line), static_cast<std::uint32_t>(p.column)};
}

template <typename Rule>
struct action : pegtl::nothing<Rule> {};

template <>
struct action<g::kind> {
  template <typename Input>
  static void apply(const Input& in, State& s) {
    auto& siblings = s.open.empty() ? s.top : s.open.back()->children;
    siblings.emplace_back();
    s.current = &siblings.back();
    s.current->kind = in.string();
    s.current->pos = pos_of(in);
  }
};

template <>
struct action<g::name> {
  template <typename Input>
  static void apply(const Input& in, State& s) {
    s.current->name = in.string();
    s.current->name_pos = pos_of(in);
  }
};

template <>
struct action<g::attribute> {
  template <typename Input>
  static void apply(const Input& in, State& s) {
    const std::string text = in.string();
    const auto eq = text.find('=');
    BenchAttribute a;
    a.key = text.substr(0, eq);
    a.value = text.substr(eq + 1);
    a.pos = pos_of(in);
    a.value_pos = {a.pos.line, a.pos.column + static_cast<std::uint32_t>(eq + 1)};
    if (a.value.size() >= 2 && a.value.front() == '"' && a.value.back() == '"') a.value = a.value.substr(1, a.value.size() - 2);
    s.current->attributes.push_back(std::move(a));
  }
};

template <>
struct action<g::block_open> {
  template <typename Input>
  static void apply(const Input& in, State& s) {
    // Blocks recurse in the grammar: the limit is enforced before the next level is parsed.
    if (s.open.size() >= static_cast<std::size_t>(kMaxBenchNesting))
      throw pegtl::parse_error("blocks nested deeper than " + std::to_string(kMaxBenchNesting) + " levels", in);
    s.open.push_back(s.current);
  }
};

template <>
struct action<g::block_close> {
  template <typename Input>
  static void apply(const Input&, State& s) {
    s.current = s.open.back();
    s.open.pop_back();
  }
};

bool parse_int(std::string_view t, std::int64_t& out) {
  NumberValue v;
  if (!parse_number_text(t, v) || v.is_float) return false;
  out = v.integer;
  return true;
}

}  // namespace

const BenchAttribute* BenchNode::find(std::string_view key) const {
  for (const auto& a : attributes)
    if (a.key == key) return &a;
  return nullptr;
}

BenchParseResult parse_bench(std::string text, std::string source_name) {
  BenchParseResult r;
  r.source = std::move(text);
  r.source_name = std::move(source_name);
  State s;
  pegtl::memory_input in(r.source.data(), r.source.size(), r.source_name);
  try {
    pegtl::parse<g::file, action, g::control>(in, s);
  } catch (const pegtl::parse_error& e) {
    const auto& p = e.positions().front();
    r.diagnostics.error(static_cast<std::uint32_t>(p.line), static_cast<std::uint32_t>(p.column), std::string(e.message()));
    return r;
  }
  // The same attribute given twice on one node is an error: which one would win is not obvious.
  std::vector<const BenchNode*> stack;
  for (const auto& n : s.top) stack.push_back(&n);
  while (!stack.empty()) {
    const BenchNode* n = stack.back();
    stack.pop_back();
    // Each repeat is compared with the first occurrence only: linear, one error per repeat (800
    // copies of one attribute gave 319,600 errors when every pair was reported).
    std::map<std::string_view, std::uint32_t> first_column;
    for (const auto& a : n->attributes)
      if (auto [it, inserted] = first_column.emplace(a.key, a.pos.column); !inserted)
        r.diagnostics.error(a.pos.line, a.pos.column,
                            "attribute '" + a.key + "' is given twice (first at column " + std::to_string(it->second) +
                                ")");
    for (const auto& c : n->children) stack.push_back(&c);
  }
  r.diagnostics.sort_by_position();
  if (r.diagnostics.has_errors()) return r;
  BenchFile f;
  f.source_name = r.source_name;
  f.source = r.source;
  f.nodes = std::move(s.top);
  r.bench = std::move(f);
  return r;
}

BenchParseResult parse_bench_file(const std::filesystem::path& path) {
  InputFile in = read_input_file(path);
  if (!in.ok) {
    BenchParseResult r;
    r.source_name = path.string();
    r.diagnostics.error(0, 0, in.error);
    return r;
  }
  return parse_bench(std::move(in.contents), path.string());
}

// ---- BenchReader -------------------------------------------------------------------------------------

const BenchAttribute* BenchReader::get(std::string_view key) {
  known_.insert(std::string(key));
  return node_.find(key);
}

void BenchReader::error(const std::string& message) {
  failed_ = true;
  diags_.error(node_.pos.line, node_.pos.column, node_.label() + ": " + message);
}

void BenchReader::error_at(std::string_view key, const std::string& message) {
  failed_ = true;
  const BenchAttribute* a = node_.find(key);
  const SourcePos p = a ? a->value_pos : node_.pos;
  diags_.error(p.line, p.column, node_.label() + ": " + message);
}

void BenchReader::require(std::string_view key, std::string_view what) {
  known_.insert(std::string(key));
  if (!node_.find(key)) error("needs " + std::string(key) + "=" + std::string(what));
}

std::optional<std::string> BenchReader::text(std::string_view key) {
  const BenchAttribute* a = get(key);
  if (!a) return std::nullopt;
  return a->value;
}

std::optional<std::int64_t> BenchReader::integer(std::string_view key, std::int64_t min, std::int64_t max) {
  const BenchAttribute* a = get(key);
  if (!a) return std::nullopt;
  std::int64_t v = 0;
  if (!parse_int(a->value, v) || v < min || v > max) {
    error_at(key, std::string(key) + "=" + a->value + ": expected an integer " + std::to_string(min) + "-" +
                      std::to_string(max));
    return std::nullopt;
  }
  return v;
}

std::optional<Nanoseconds> BenchReader::duration(std::string_view key) {
  const BenchAttribute* a = get(key);
  if (!a) return std::nullopt;
  std::string err;
  auto d = parse_duration(a->value, &err);
  if (!d) {
    error_at(key, std::string(key) + "=" + a->value + ": " + err);
    return std::nullopt;
  }
  return d;
}

std::optional<bool> BenchReader::flag(std::string_view key) {
  const BenchAttribute* a = get(key);
  if (!a) return std::nullopt;
  const std::string& v = a->value;
  if (v == "on" || v == "yes" || v == "true" || v == "1") return true;
  if (v == "off" || v == "no" || v == "false" || v == "0") return false;
  error_at(key, std::string(key) + "=" + v + ": expected on or off");
  return std::nullopt;
}

std::optional<std::vector<std::int64_t>> BenchReader::integers(std::string_view key, std::int64_t min,
                                                              std::int64_t max) {
  const BenchAttribute* a = get(key);
  if (!a) return std::nullopt;
  std::vector<std::int64_t> out;
  std::string_view rest = a->value;
  while (true) {
    const auto comma = rest.find(',');
    const std::string_view item = rest.substr(0, comma);
    std::int64_t v = 0;
    if (!parse_int(item, v) || v < min || v > max) {
      error_at(key, std::string(key) + ": '" + std::string(item) + "' is not an integer " + std::to_string(min) + "-" +
                        std::to_string(max) + " (write a comma-separated list such as 1,2,-3,0x00FF)");
      return std::nullopt;
    }
    out.push_back(v);
    if (comma == std::string_view::npos) break;
    rest = rest.substr(comma + 1);
  }
  return out;
}

std::optional<std::string> BenchReader::choice(std::string_view key, const std::vector<std::string>& choices) {
  const BenchAttribute* a = get(key);
  if (!a) return std::nullopt;
  for (const auto& c : choices)
    if (a->value == c) return c;
  std::string list;
  for (const auto& c : choices) list += (list.empty() ? "" : ", ") + c;
  error_at(key, std::string(key) + "=" + a->value + ": expected one of " + list);
  return std::nullopt;
}

void BenchReader::finish() {
  for (const auto& a : node_.attributes)
    if (!known_.count(a.key)) {
      std::string list;
      for (const auto& k : known_) list += (list.empty() ? "" : ", ") + k;
      failed_ = true;
      diags_.error(a.pos.line, a.pos.column,
                   node_.label() + ": unknown attribute '" + a.key + "'" + (list.empty() ? "" : " (known: " + list + ")"));
    }
}

}  // namespace softslc
