// The CPT expression language (issue 15): parsed with PEGTL into reverse Polish notation.
//
// Design. CPT (SLC 5/03 OS302, 5/04 OS401, 5/05) carries an infix expression instead of fixed
// operands. The export writes it after the destination, as RSLogix 500 shows it:
// `CPT N7:0 (N7:1 + N7:2) | 2`. parse_expression turns that text into a flat RPN list, the form
// both the checker (which checks every operand like an instruction operand) and the compiler
// (which turns each list into a small bytecode program the interpreter runs on a fixed stack)
// read; nobody walks a tree. Operators and their precedence, loosest first: OR, XOR, AND, + and
// -, * and | (divide: `/` is the bit separator of addresses), unary - and NOT, ** (power), then
// the functions SQR ABS LN LOG SIN COS TAN ASN ACS ATN DEG RAD TOD FRD, then parentheses. A
// function takes one primary: `SQR N7:0` or `SQR(N7:0 + 1)`. Operands are word addresses and
// numeric constants (docs/program-format.md, "CPT").
//
// Limits: the text is at most kMaxExpressionLength characters and parentheses nest at most
// kMaxExpressionDepth deep; both are checked before the grammar runs, so the recursive rules
// are bounded.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace softslc {

inline constexpr std::size_t kMaxExpressionLength = 255;
inline constexpr int kMaxExpressionDepth = 16;

enum class ExprCode : std::uint8_t {
  Push,  // an operand (address or constant) in `text`
  Neg, Not,
  Add, Sub, Mul, Div, Pow, And, Or, Xor,
  Sqr, Abs, Ln, Log, Sin, Cos, Tan, Asn, Acs, Atn, Deg, Rad, Tod, Frd,
};

struct ExprItem {
  ExprCode code = ExprCode::Push;
  std::string text;     // Push: the operand as written
  std::size_t column = 0;  // 0-based offset of the item in the expression text
};

// Whether an operation needs integer operands (bitwise) or computes in floating point only.
bool expr_is_bitwise(ExprCode c);
bool expr_is_float_function(ExprCode c);
std::string_view to_string(ExprCode c);

struct ExpressionError {
  std::size_t column = 0;  // 0-based offset into the expression text
  std::string message;
};

// Parses a CPT expression. Returns the RPN items, or nullopt with `error` set.
std::optional<std::vector<ExprItem>> parse_expression(std::string_view text, ExpressionError& error);

// The deepest evaluation stack the RPN list needs.
int expr_stack_depth(const std::vector<ExprItem>& items);

}  // namespace softslc
