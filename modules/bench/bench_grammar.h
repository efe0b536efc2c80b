// PEGTL grammar of bench files, as rule types only (actions in bench.cpp, messages in
// bench_messages.h).
//
// A bench file is lines. A node line is `KIND [NAME] [key=value ...]`, optionally ending in `{`,
// which opens a block of child nodes closed by a line holding `}`. `#` starts a comment that runs
// to the end of the line; blank lines are free. Values are bare tokens (no blanks, braces, `#`
// or quotes: `4.5ms`, `1/2`, `1,2,3`, `1746-IB16`) or double-quoted strings.
#pragma once

#include <tao/pegtl.hpp>

namespace softslc::bench_grammar {

using namespace tao::pegtl;

// Blanks separate tokens inside a line; line breaks end a node's line.
struct blank_char : one<' ', '\t'> {};
struct blanks : star<blank_char> {};
struct blank1 : plus<blank_char> {};
struct comment : seq<one<'#'>, star<not_one<'\r', '\n'>>> {};
struct newline : sor<string<'\r', '\n'>, one<'\n'>> {};
// The end of a node's line: blanks, an optional comment, then a line break or the end of input.
struct line_end : seq<blanks, opt<comment>, sor<newline, eof>> {};
// A line with nothing on it (it must end in a line break, so repetition always advances).
struct empty_line : seq<blanks, opt<comment>, newline> {};

struct identifier : seq<sor<alpha, one<'_'>>, star<sor<alnum, one<'_'>>>> {};
// A node kind: an identifier (adapter, module, scanner, ...).
struct kind : identifier {};
// A node name: letters, digits, '_', '-', '.'; never followed by '=' (that is an attribute).
struct name_char : sor<alnum, one<'_', '-', '.'>> {};
struct name : plus<name_char> {};
// Attribute values.
struct quoted_text : star<not_one<'"', '\r', '\n'>> {};
struct quote_close : one<'"'> {};
struct quoted : seq<one<'"'>, quoted_text, must<quote_close>> {};
struct bare : plus<not_one<' ', '\t', '\r', '\n', '#', '{', '}', '"'>> {};
struct value : sor<quoted, bare> {};
struct key : identifier {};
struct attribute : seq<key, one<'='>, must<value>> {};
struct attribute_start : seq<key, one<'='>> {};

struct header : seq<kind, opt<blank1, not_at<attribute_start>, name, not_at<one<'='>>>, star<blank1, attribute>> {};

struct node;
// A block of children: `{` ends its line, then child nodes and empty lines up to a `}`.
struct block_open : one<'{'> {};
struct block_close : one<'}'> {};
struct block_body_end : seq<blanks, block_close> {};
struct item : sor<empty_line, node> {};
struct block : seq<block_open, must<line_end>, star<item>, must<block_body_end>> {};
struct node : seq<blanks, header, blanks, opt<block>, must<line_end>> {};

// The whole file: items, then perhaps a last comment line without a line break.
struct file_end : seq<blanks, opt<comment>, eof> {};
struct file : seq<star<item>, must<file_end>> {};

}  // namespace softslc::bench_grammar
