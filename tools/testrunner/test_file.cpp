#include "tools/testrunner/test_file.h"

namespace softslc::testing {

std::string DataRef::describe() const {
  if (symbol.empty()) return spelling;
  const std::string prefix = controller.empty() ? "" : controller + ".";
  return prefix + symbol + " (" + prefix + to_string(address) + ")";
}

std::string_view mode_word(Mode m) {
  switch (m) {
    case Mode::Program: return "program";
    case Mode::Run: return "run";
    case Mode::Test: return "test";
    case Mode::Faulted: return "faulted";
    case Mode::Suspended: return "suspended";
  }
  return "?";
}

std::string_view to_string(CompareOp op) {
  switch (op) {
    case CompareOp::Eq: return "==";
    case CompareOp::Ne: return "!=";
    case CompareOp::Lt: return "<";
    case CompareOp::Le: return "<=";
    case CompareOp::Gt: return ">";
    case CompareOp::Ge: return ">=";
    case CompareOp::In: return "in";
  }
  return "?";
}

std::string to_string(const Condition& c) {
  switch (c.kind) {
    case Condition::Kind::Compare: {
      const Comparison& k = c.compare;
      if (k.op == CompareOp::In) return k.lhs.spelling + " in " + k.rhs.spelling + ".." + k.high.spelling;
      return k.lhs.spelling + " " + std::string(to_string(k.op)) + " " + k.rhs.spelling;
    }
    case Condition::Kind::Fault:
      return c.fault_code ? "fault " + c.fault_literal.spelling : "fault";
    case Condition::Kind::NoFault:
      return "no fault";
    case Condition::Kind::Mode:
      return "mode " + std::string(mode_word(c.mode));
    case Condition::Kind::And:
    case Condition::Kind::Or: {
      std::string out;
      const bool is_and = c.kind == Condition::Kind::And;
      for (const auto& t : c.terms) {
        if (!out.empty()) out += is_and ? " and " : " or ";
        // `and` binds tighter than `or`: an `or` inside an `and` was written in parentheses.
        const bool parens = is_and && t.kind == Condition::Kind::Or;
        out += parens ? "(" + to_string(t) + ")" : to_string(t);
      }
      return out;
    }
  }
  return "?";
}

}  // namespace softslc::testing
