#include "parser/expression.h"

#include <tao/pegtl.hpp>

#include <algorithm>

namespace softslc {

namespace {

namespace ex {
using namespace tao::pegtl;

struct sp : star<one<' ', '\t'>> {};
// Characters of an operand token: addresses (N7:0, B3:0/1, T4:0.ACC, #N7:[N10:0]) and numbers.
struct atom_char : sor<alnum, one<':', '.', '/', '#', '[', ']', '_'>> {};
template <typename Str>
struct kw : seq<Str, not_at<atom_char>> {};

struct kw_and : kw<TAO_PEGTL_STRING("AND")> {};
struct kw_or : kw<TAO_PEGTL_STRING("OR")> {};
struct kw_xor : kw<TAO_PEGTL_STRING("XOR")> {};
struct kw_not : kw<TAO_PEGTL_STRING("NOT")> {};
struct func_name : sor<kw<TAO_PEGTL_STRING("SQR")>, kw<TAO_PEGTL_STRING("ABS")>, kw<TAO_PEGTL_STRING("LN")>,
                       kw<TAO_PEGTL_STRING("LOG")>, kw<TAO_PEGTL_STRING("SIN")>, kw<TAO_PEGTL_STRING("COS")>,
                       kw<TAO_PEGTL_STRING("TAN")>, kw<TAO_PEGTL_STRING("ASN")>, kw<TAO_PEGTL_STRING("ACS")>,
                       kw<TAO_PEGTL_STRING("ATN")>, kw<TAO_PEGTL_STRING("DEG")>, kw<TAO_PEGTL_STRING("RAD")>,
                       kw<TAO_PEGTL_STRING("TOD")>, kw<TAO_PEGTL_STRING("FRD")>> {};
struct keyword : sor<kw_and, kw_or, kw_xor, kw_not, func_name> {};

// 1.5E-3: the exponent's sign is not an operator.
struct signed_exponent_number
    : seq<plus<digit>, opt<one<'.'>, star<digit>>, one<'e', 'E'>, one<'+', '-'>, plus<digit>, not_at<atom_char>> {};
struct word_atom : seq<not_at<keyword>, plus<atom_char>> {};
struct atom : sor<signed_exponent_number, word_atom> {};

struct expr;
struct close_paren : one<')'> {};
struct paren : seq<one<'('>, sp, must<expr>, sp, must<close_paren>> {};
struct primary;
struct func_call : seq<func_name, sp, must<primary>> {};
struct primary : sor<paren, func_call, atom> {};
struct pow_op : TAO_PEGTL_STRING("**") {};
struct pow_tail : seq<sp, pow_op, sp, must<primary>> {};
struct power : seq<primary, star<pow_tail>> {};
struct unary;
struct neg : seq<one<'-'>, sp, must<unary>> {};
struct lnot : seq<kw_not, sp, must<unary>> {};
struct unary : sor<neg, lnot, power> {};
struct mul_op : sor<seq<one<'*'>, not_at<one<'*'>>>, one<'|'>> {};
struct mul_tail : seq<sp, mul_op, sp, must<unary>> {};
struct mul : seq<unary, star<mul_tail>> {};
struct add_op : one<'+', '-'> {};
struct add_tail : seq<sp, add_op, sp, must<mul>> {};
struct add : seq<mul, star<add_tail>> {};
struct and_tail : seq<sp, kw_and, sp, must<add>> {};
struct and_expr : seq<add, star<and_tail>> {};
struct xor_tail : seq<sp, kw_xor, sp, must<and_expr>> {};
struct xor_expr : seq<and_expr, star<xor_tail>> {};
struct or_tail : seq<sp, kw_or, sp, must<xor_expr>> {};
struct or_expr : seq<xor_expr, star<or_tail>> {};
struct expr : or_expr {};
struct end_of_expression : eof {};
struct whole : seq<sp, must<expr>, sp, must<end_of_expression>> {};

constexpr const char* kOperandExpected = "expected an operand (an address, a constant, a function or '(')";
template <typename>
inline constexpr const char* kMessage = kOperandExpected;
template <>
inline constexpr const char* kMessage<close_paren> = "expected ')'";
template <>
inline constexpr const char* kMessage<end_of_expression> =
    "expected an operator (+ - * | ** AND OR XOR) or the end of the expression";

template <typename Rule>
struct control : normal<Rule> {
  template <typename Input, typename... States>
  [[noreturn]] static void raise(const Input& in, States&&...) {
    throw parse_error(kMessage<Rule>, in);
  }
};

struct State {
  std::vector<ExprItem> out;
  std::vector<ExprItem> pending;  // operators and functions waiting for their right operand
};

template <typename Rule>
struct action : nothing<Rule> {};

// An operator is remembered when it is read and emitted when its right operand has been parsed.
template <ExprCode Code>
struct remember {
  template <typename Input>
  static void apply(const Input& in, State& s) {
    s.pending.push_back({Code, {}, in.position().byte});
  }
};
struct emit {
  template <typename Input>
  static void apply(const Input&, State& s) {
    s.out.push_back(s.pending.back());
    s.pending.pop_back();
  }
};

template <>
struct action<atom> {
  template <typename Input>
  static void apply(const Input& in, State& s) {
    s.out.push_back({ExprCode::Push, in.string(), in.position().byte});
  }
};
template <>
struct action<func_name> {
  template <typename Input>
  static void apply(const Input& in, State& s) {
    static constexpr std::pair<std::string_view, ExprCode> kNames[] = {
        {"SQR", ExprCode::Sqr}, {"ABS", ExprCode::Abs}, {"LN", ExprCode::Ln},   {"LOG", ExprCode::Log},
        {"SIN", ExprCode::Sin}, {"COS", ExprCode::Cos}, {"TAN", ExprCode::Tan}, {"ASN", ExprCode::Asn},
        {"ACS", ExprCode::Acs}, {"ATN", ExprCode::Atn}, {"DEG", ExprCode::Deg}, {"RAD", ExprCode::Rad},
        {"TOD", ExprCode::Tod}, {"FRD", ExprCode::Frd}};
    for (const auto& [name, code] : kNames)
      if (in.string_view() == name) s.pending.push_back({code, {}, in.position().byte});
  }
};
template <>
struct action<func_call> : emit {};
template <>
struct action<pow_op> : remember<ExprCode::Pow> {};
template <>
struct action<pow_tail> : emit {};
// Unary minus and NOT follow their operand directly: nothing can come between.
template <>
struct action<neg> {
  template <typename Input>
  static void apply(const Input& in, State& s) {
    s.out.push_back({ExprCode::Neg, {}, in.position().byte});
  }
};
template <>
struct action<lnot> {
  template <typename Input>
  static void apply(const Input& in, State& s) {
    s.out.push_back({ExprCode::Not, {}, in.position().byte});
  }
};
template <>
struct action<mul_op> {
  template <typename Input>
  static void apply(const Input& in, State& s) {
    s.pending.push_back({in.peek_char() == '|' ? ExprCode::Div : ExprCode::Mul, {}, in.position().byte});
  }
};
template <>
struct action<mul_tail> : emit {};
template <>
struct action<add_op> {
  template <typename Input>
  static void apply(const Input& in, State& s) {
    s.pending.push_back({in.peek_char() == '+' ? ExprCode::Add : ExprCode::Sub, {}, in.position().byte});
  }
};
template <>
struct action<add_tail> : emit {};
template <>
struct action<kw_and> : remember<ExprCode::And> {};
template <>
struct action<and_tail> : emit {};
template <>
struct action<kw_xor> : remember<ExprCode::Xor> {};
template <>
struct action<xor_tail> : emit {};
template <>
struct action<kw_or> : remember<ExprCode::Or> {};
template <>
struct action<or_tail> : emit {};

}  // namespace ex

}  // namespace

bool expr_is_bitwise(ExprCode c) {
  return c == ExprCode::And || c == ExprCode::Or || c == ExprCode::Xor || c == ExprCode::Not;
}

bool expr_is_float_function(ExprCode c) {
  switch (c) {
    case ExprCode::Pow:
    case ExprCode::Ln:
    case ExprCode::Log:
    case ExprCode::Sin:
    case ExprCode::Cos:
    case ExprCode::Tan:
    case ExprCode::Asn:
    case ExprCode::Acs:
    case ExprCode::Atn:
    case ExprCode::Deg:
    case ExprCode::Rad: return true;
    default: return false;
  }
}

std::string_view to_string(ExprCode c) {
  switch (c) {
    case ExprCode::Push: return "push";
    case ExprCode::Neg: return "-";
    case ExprCode::Not: return "NOT";
    case ExprCode::Add: return "+";
    case ExprCode::Sub: return "-";
    case ExprCode::Mul: return "*";
    case ExprCode::Div: return "|";
    case ExprCode::Pow: return "**";
    case ExprCode::And: return "AND";
    case ExprCode::Or: return "OR";
    case ExprCode::Xor: return "XOR";
    case ExprCode::Sqr: return "SQR";
    case ExprCode::Abs: return "ABS";
    case ExprCode::Ln: return "LN";
    case ExprCode::Log: return "LOG";
    case ExprCode::Sin: return "SIN";
    case ExprCode::Cos: return "COS";
    case ExprCode::Tan: return "TAN";
    case ExprCode::Asn: return "ASN";
    case ExprCode::Acs: return "ACS";
    case ExprCode::Atn: return "ATN";
    case ExprCode::Deg: return "DEG";
    case ExprCode::Rad: return "RAD";
    case ExprCode::Tod: return "TOD";
    case ExprCode::Frd: return "FRD";
  }
  return "?";
}

std::optional<std::vector<ExprItem>> parse_expression(std::string_view text, ExpressionError& error) {
  if (text.size() > kMaxExpressionLength) {
    error = {kMaxExpressionLength, "the expression is longer than " + std::to_string(kMaxExpressionLength) +
                                       " characters"};
    return std::nullopt;
  }
  // Bound the grammar's recursion before it runs: parentheses nest at most kMaxExpressionDepth.
  int depth = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '(' && ++depth > kMaxExpressionDepth) {
      error = {i, "parentheses nest deeper than " + std::to_string(kMaxExpressionDepth) + " levels"};
      return std::nullopt;
    }
    if (text[i] == ')') --depth;
  }
  ex::State state;
  try {
    tao::pegtl::memory_input in(text.data(), text.size(), "expression");
    tao::pegtl::parse<ex::whole, ex::action, ex::control>(in, state);
  } catch (const tao::pegtl::parse_error& e) {
    error = {e.positions().empty() ? 0 : e.positions().front().byte, std::string(e.message())};
    return std::nullopt;
  }
  return std::move(state.out);
}

int expr_stack_depth(const std::vector<ExprItem>& items) {
  int depth = 0, deepest = 0;
  for (const auto& it : items) {
    if (it.code == ExprCode::Push) {
      deepest = std::max(deepest, ++depth);
    } else if (!(it.code == ExprCode::Neg || it.code == ExprCode::Not || it.code >= ExprCode::Sqr)) {
      --depth;  // a binary operator pops two and pushes one
    }
  }
  return deepest;
}

}  // namespace softslc
