// Error messages for the bench grammar's commit points (must<> rules), kept apart from the rules.
// PEGTL's must_if control refuses to compile a grammar where a must<> rule has no message.
#pragma once

#include "modules/bench/bench_grammar.h"

namespace softslc::bench_grammar {

template <typename>
inline constexpr const char* error_message = nullptr;

template <> inline constexpr auto error_message<quote_close> = "unterminated string: expected a closing '\"'";
template <> inline constexpr auto error_message<value> = "expected a value after '=' (a token such as 4.5ms or a quoted string)";
template <> inline constexpr auto error_message<line_end> =
    "expected key=value, '{' or the end of the line (a node line is KIND [NAME] [key=value ...] [{])";
template <> inline constexpr auto error_message<block_body_end> =
    "expected a node line or '}' to close the block (nodes are KIND [NAME] [key=value ...])";
template <> inline constexpr auto error_message<file_end> =
    "expected a node line (KIND [NAME] [key=value ...]); a '}' without an open block?";

struct error {
  template <typename Rule>
  static constexpr auto message = error_message<Rule>;
};

template <typename Rule>
using control = tao::pegtl::must_if<error>::control<Rule>;

}  // namespace softslc::bench_grammar
