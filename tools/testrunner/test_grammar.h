// PEGTL grammar of ladder test files (.test), as rule types only (the format: docs/testing.md).
//
// A test file is line-oriented: every line is one statement (`program`, `test`, `row`, or a
// step such as `set`, `scan`, `expect`), optionally followed by a `#` comment. The parser
// (test_parser.cpp) feeds the grammar one line at a time, so a syntax error costs one line and
// every independent error in a file is reported. Rows of table-driven tests substitute their
// values into `$NAME` references before the line is parsed; the grammar never sees a `$`.
// Actions live in test_parser.cpp, error messages in test_grammar_messages.h, as in parser/.
//
// Addresses reuse the program grammar (parser/grammar.h): `address_body` with its must<> commit
// points and their messages, so an address is spelled and diagnosed exactly as in a program. The
// program grammar's token end is "whitespace or end of input"; a test line also ends tokens at
// `#`, `)`, a comparison operator and `..`, so this grammar puts its own token_end after the
// reused rules rather than reusing `address` and `number` whole. Ranges (`N11:0..13`) are
// recognised before plain addresses because the program grammar would take the first '.' of
// '..' for a sub-element separator.
//
// Note (as in parser/grammar.h): PEGTL's must_if control raises a rule's message whenever that
// rule fails, so a rule with a message is used only inside must<>; where the same syntax is
// optional, a separately named rule is used.
#pragma once

#include <tao/pegtl.hpp>

#include "parser/grammar.h"

namespace softslc::testing::grammar {

namespace pegtl = tao::pegtl;
namespace pg = softslc::grammar;
using namespace tao::pegtl;

// ---- Lexical ---------------------------------------------------------------------------------------

// Blanks separate tokens; the driver hands over one line at a time, without its line break.
struct blank : one<' ', '\t'> {};
struct ws : plus<blank> {};
struct opt_ws : star<blank> {};
// A comment runs from '#' to the end of the line.
struct line_comment : seq<one<'#'>, star<any>> {};
struct two_dots : string<'.', '.'> {};
// Where a token may end: a blank, the end of the line, a comment, a closing parenthesis, a
// comparison operator, or the '..' of a range.
struct token_end : at<sor<blank, eof, one<'#', ')', '=', '!', '<', '>'>, two_dots>> {};

// ---- Keywords --------------------------------------------------------------------------------------

struct kw_program : TAO_PEGTL_KEYWORD("program") {};
struct kw_bench : TAO_PEGTL_KEYWORD("bench") {};
struct kw_processor : TAO_PEGTL_KEYWORD("processor") {};
struct kw_node : TAO_PEGTL_KEYWORD("node") {};
struct kw_peer : TAO_PEGTL_KEYWORD("peer") {};
struct kw_ip : TAO_PEGTL_KEYWORD("ip") {};
struct kw_channel : TAO_PEGTL_KEYWORD("channel") {};
struct kw_network : TAO_PEGTL_KEYWORD("network") {};
struct kw_df1 : TAO_PEGTL_KEYWORD("df1") {};
struct kw_modbus : TAO_PEGTL_KEYWORD("modbus") {};
struct kw_test : TAO_PEGTL_KEYWORD("test") {};
struct kw_with : TAO_PEGTL_KEYWORD("with") {};
struct kw_row : TAO_PEGTL_KEYWORD("row") {};
struct kw_set : TAO_PEGTL_KEYWORD("set") {};
struct kw_force : TAO_PEGTL_KEYWORD("force") {};
struct kw_unforce : TAO_PEGTL_KEYWORD("unforce") {};
struct kw_all : TAO_PEGTL_KEYWORD("all") {};
struct kw_scan : TAO_PEGTL_KEYWORD("scan") {};
struct kw_run : TAO_PEGTL_KEYWORD("run") {};
struct kw_until : TAO_PEGTL_KEYWORD("until") {};
struct kw_within : TAO_PEGTL_KEYWORD("within") {};
struct kw_expect : TAO_PEGTL_KEYWORD("expect") {};
struct kw_mode : TAO_PEGTL_KEYWORD("mode") {};
struct kw_power : TAO_PEGTL_KEYWORD("power") {};
struct kw_cycle : TAO_PEGTL_KEYWORD("cycle") {};
struct kw_clear : TAO_PEGTL_KEYWORD("clear") {};
struct kw_fault : TAO_PEGTL_KEYWORD("fault") {};
struct kw_no : TAO_PEGTL_KEYWORD("no") {};
struct kw_snapshot : TAO_PEGTL_KEYWORD("snapshot") {};
struct kw_restore : TAO_PEGTL_KEYWORD("restore") {};
struct kw_and : TAO_PEGTL_KEYWORD("and") {};
struct kw_or : TAO_PEGTL_KEYWORD("or") {};
struct kw_in : TAO_PEGTL_KEYWORD("in") {};
struct kw_elapsed : TAO_PEGTL_KEYWORD("elapsed") {};
struct kw_scans : TAO_PEGTL_KEYWORD("scans") {};
struct kw_device : TAO_PEGTL_KEYWORD("device") {};
struct kw_mode_program : TAO_PEGTL_KEYWORD("program") {};
struct kw_mode_run : TAO_PEGTL_KEYWORD("run") {};
struct kw_mode_test : TAO_PEGTL_KEYWORD("test") {};
struct kw_mode_faulted : TAO_PEGTL_KEYWORD("faulted") {};
struct kw_mode_suspended : TAO_PEGTL_KEYWORD("suspended") {};

// Words that a condition reads as keywords; a program SYMBOL spelled exactly so cannot be named
// in a condition (symbols are case-sensitive, and these are lower case).
struct reserved_word
    : sor<kw_and, kw_or, kw_in, kw_within, kw_elapsed, kw_scans, kw_fault, kw_no, kw_mode, kw_until, kw_device> {};

// ---- Values ----------------------------------------------------------------------------------------

struct digits : plus<digit> {};
// Binary with '_' separators; 'x' digits make it a pattern that ignores those bits.
struct binary_digit : one<'0', '1', 'x', 'X', '_'> {};
struct binary_number : seq<opt<one<'-'>>, one<'0'>, one<'b', 'B'>, plus<binary_digit>> {};
// A number: binary, hexadecimal (0x1F, 1Fh), float or integer. Each alternative carries its own
// token end so that "1..5" backtracks from the float "1." to the integer "1".
struct value : sor<seq<binary_number, token_end>, seq<pg::hex_number, token_end>, seq<pg::float_number, token_end>,
                   seq<pg::int_number, token_end>> {};

// A duration: a decimal number and a unit (ns, us, ms, s, m).
struct duration_unit : sor<TAO_PEGTL_STRING("ns"), TAO_PEGTL_STRING("us"), TAO_PEGTL_STRING("ms"), one<'s'>, one<'m'>> {};
struct duration : seq<digits, opt<one<'.'>, digits>, duration_unit, token_end> {};
// A count of scans.
struct count : seq<digits, token_end> {};

// ---- Data operands ---------------------------------------------------------------------------------

// A single address, spelled as in programs (the rules and their messages are the program
// grammar's).
// A controller of the test's MSG network other than the program's (`peer NAME ...`): B.N7:0.
struct controller_prefix : seq<pg::identifier, one<'.'>, at<sor<upper, one<'#'>>>> {};
struct address : seq<opt<controller_prefix>, opt<pg::index_mark>, pg::address_body, token_end> {};
// A range of whole elements of one file: N11:0..13.
struct range_first : seq<pg::file_type, opt<pg::file_number>, one<':'>, pg::element_number> {};
struct range_last : seq<digits, token_end> {};
struct address_range : seq<opt<controller_prefix>, range_first, two_dots, must<range_last>> {};
// A program SYMBOL.
struct symbol : seq<not_at<reserved_word>, opt<controller_prefix>, pg::identifier, token_end> {};
struct data_operand : sor<address_range, address, symbol> {};
// The name of a bench device: letters, digits, '_', '-' and '.' (docs/bench-format.md).
struct device_name : seq<plus<sor<alnum, one<'_', '-', '.'>>>, token_end> {};

// ---- Conditions ------------------------------------------------------------------------------------

struct op_eq : string<'=', '='> {};
struct op_ne : string<'!', '='> {};
struct op_le : string<'<', '='> {};
struct op_ge : string<'>', '='> {};
struct op_lt : one<'<'> {};
struct op_gt : one<'>'> {};
struct compare_op : sor<op_eq, op_ne, op_le, op_ge, op_lt, op_gt> {};

// `lhs in low..high`
struct value_high : value {};
struct value_range : seq<value, two_dots, must<value_high>> {};
struct duration_high : duration {};
struct duration_range : seq<duration, two_dots, must<duration_high>> {};
struct count_high : count {};
struct count_range : seq<count, two_dots, must<count_high>> {};

// Data: N7:0 == 5, MOTOR != 0, N7:0 in 10..20, N7:0 == N7:1, N7:0 == 0b0000_xxxx.
struct data_rhs : sor<value, data_operand> {};
struct data_in : seq<kw_in, opt_ws, must<value_range>> {};
struct data_compare : seq<compare_op, opt_ws, must<data_rhs>> {};
struct data_tail : sor<data_in, data_compare> {};
struct data_comparison : seq<data_operand, opt_ws, must<data_tail>> {};

// elapsed <= 1.05s, elapsed in 0.99s..1.01s: virtual time of the last scan/run step.
struct elapsed_in : seq<kw_in, opt_ws, must<duration_range>> {};
struct elapsed_rhs : duration {};
struct elapsed_compare : seq<compare_op, opt_ws, must<elapsed_rhs>> {};
struct elapsed_tail : sor<elapsed_in, elapsed_compare> {};
struct elapsed_subject : kw_elapsed {};
struct elapsed_comparison : seq<elapsed_subject, opt_ws, must<elapsed_tail>> {};

// scans == 3, scans in 90..110: program scans of the last scan/run step.
struct scans_in : seq<kw_in, opt_ws, must<count_range>> {};
struct scans_rhs : count {};
struct scans_compare : seq<compare_op, opt_ws, must<scans_rhs>> {};
struct scans_tail : sor<scans_in, scans_compare> {};
struct scans_subject : kw_scans {};
struct scans_comparison : seq<scans_subject, opt_ws, must<scans_tail>> {};

// fault, fault 0020h, no fault, mode run.
struct fault_code : value {};
struct fault_primary : seq<kw_fault, opt<ws, fault_code>> {};
struct fault_after_no : kw_fault {};
struct no_fault_primary : seq<kw_no, ws, must<fault_after_no>> {};
struct mode_name : sor<kw_mode_program, kw_mode_run, kw_mode_test, kw_mode_faulted, kw_mode_suspended> {};
struct condition_mode_name : mode_name {};
struct mode_primary : seq<kw_mode, ws, must<condition_mode_name>> {};

// device NAME WHAT[K] == 5, device NAME WHAT in 1..3: an observable value of a bench device
// (Runtime::observe), WHAT being lower-case words ("btw count", "outputs"), K an element index.
struct observation_word : seq<not_at<kw_in>, range<'a', 'z'>, star<sor<range<'a', 'z'>, one<'_', '-'>>>> {};
struct observation_index : seq<one<'['>, digits, one<']'>> {};
struct observation_what : seq<observation_word, star<ws, observation_word>, opt<observation_index>, token_end> {};
struct device_observation : seq<kw_device, ws, must<device_name>, ws, must<observation_what>> {};
struct device_comparison : seq<device_observation, opt_ws, must<data_tail>> {};

struct leaf : sor<fault_primary, no_fault_primary, mode_primary, elapsed_comparison, scans_comparison,
                  device_comparison, data_comparison> {};
struct paren_close : one<')'> {};
struct nested_condition;
struct paren : seq<one<'('>, opt_ws, must<nested_condition>, opt_ws, must<paren_close>> {};
struct primary : sor<paren, leaf> {};
struct next_primary : primary {};
// `and` binds tighter than `or`; parentheses group.
struct conjunction : seq<primary, star<ws, kw_and, ws, must<next_primary>>> {};
struct next_conjunction : conjunction {};
struct condition_body : seq<conjunction, star<ws, kw_or, ws, must<next_conjunction>>> {};
// The same rule three times so that each use has its own message and action.
struct condition : condition_body {};
struct nested_condition : condition_body {};

// ---- Lines -----------------------------------------------------------------------------------------

// A path: quoted (may contain blanks) or a bare token.
struct quoted_path_text : star<not_one<'"'>> {};
struct quote_close : one<'"'> {};
struct quoted_path : seq<one<'"'>, quoted_path_text, must<quote_close>> {};
struct bare_path : plus<not_one<' ', '\t', '#', '"'>> {};
struct path : sor<quoted_path, bare_path> {};
struct program_path : path {};
struct bench_path : path {};

// program PATH [processor CATALOG[:SERIES]]: the processor of a program that is pasted rungs.
struct program_processor_spec : plus<not_one<' ', '\t', '#', '"'>> {};
struct program_processor : seq<ws, kw_processor, ws, must<program_processor_spec>> {};
struct program_line : seq<kw_program, ws, must<program_path>, opt<program_processor>> {};
// MSG networks (docs/testing.md "Several controllers"): `node N` gives the program's node (1 by
// default); `peer NAME PATH node N` adds another controller, its program and node. On Ethernet (SLC
// 5/05) a controller is named by IP address instead: `ip A.B.C.D`, `peer NAME PATH ip A.B.C.D`.
struct node_number : digits {};
struct node_line : seq<kw_node, ws, must<node_number>> {};
struct ip_address : seq<plus<digit>, star<one<'.'>, plus<digit>>, token_end> {};
struct ip_line : seq<kw_ip, ws, must<ip_address>> {};
struct peer_name : seq<pg::identifier, token_end> {};
struct peer_path : path {};
// A second DH-485 network (docs/testing.md "Several controllers"): `channel 1 node N [network NAME]` puts a
// 1764-LRP program's channel 1, its second serial port, at node N of the file's network or of the network
// NAME; `peer NAME PATH node N network NAME` puts a peer on that network instead of the file's.
struct network_name : seq<pg::identifier, token_end> {};
struct network_part : seq<ws, kw_network, ws, must<network_name>> {};
// DF1 full-duplex on channel 0 (docs/testing.md "DF1 full-duplex"): `channel 0 df1 [SETTING...]` configures the
// program's channel 0; `peer NAME PATH df1 [SETTING...]` joins a peer's channel 0 to it by the cable. A SETTING
// is one token (baud=19200, crc, duplicate_detect=off), checked by its action.
struct df1_setting : seq<plus<not_one<' ', '\t', '#'>>> {};
struct df1_part : seq<kw_df1, star<ws, df1_setting>> {};
struct channel_number : digits {};
struct channel_node : seq<kw_node, ws, must<node_number>, opt<network_part>> {};
struct channel_setup : sor<channel_node, df1_part> {};
struct channel_line : seq<kw_channel, ws, must<channel_number>, ws, must<channel_setup>> {};
struct peer_node_part : seq<kw_node, ws, must<node_number>, opt<network_part>> {};
struct peer_ip_part : seq<kw_ip, ws, must<ip_address>> {};
struct peer_df1_part : df1_part {};
// A peer on the program's Modbus RTU line (docs/testing.md "Modbus RTU slaves"): `peer NAME PATH modbus
// [SETTING...]`, its channel 0 a Modbus RTU slave (address=N, baud=N, map=C,D,I,H), each checked by its action.
struct modbus_setting : seq<plus<not_one<' ', '\t', '#'>>> {};
struct peer_modbus_part : seq<kw_modbus, star<ws, modbus_setting>> {};
struct peer_node : sor<peer_node_part, peer_df1_part, peer_modbus_part, peer_ip_part> {};
struct peer_line : seq<kw_peer, ws, must<peer_name>, ws, must<peer_path>, ws, must<peer_node>> {};
struct bench_line : seq<kw_bench, ws, must<bench_path>> {};

// test "name" [with COLUMN...]
struct test_name_text : star<not_one<'"'>> {};
struct test_name : seq<one<'"'>, test_name_text, must<quote_close>> {};
struct column_name : seq<pg::identifier, token_end> {};
struct column_list : seq<column_name, star<ws, column_name>> {};
struct test_with : seq<ws, kw_with, ws, must<column_list>> {};
struct test_line : seq<kw_test, ws, must<test_name>, opt<test_with>> {};

// row VALUE... (one token per column; values may be any token: numbers, addresses, durations).
struct row_value : plus<not_one<' ', '\t', '#'>> {};
struct row_line : seq<kw_row, star<ws, row_value>> {};

// set TARGET = VALUE...   (a range takes one value per element)
struct equals : one<'='> {};
struct set_target : data_operand {};
struct set_value : value {};
struct set_line : seq<kw_set, ws, must<set_target>, opt_ws, must<equals>, opt_ws, must<set_value>, star<ws, value>> {};
// force TARGET = 0|1, unforce TARGET, unforce all
struct force_target : data_operand {};
struct force_value : value {};
struct force_line : seq<kw_force, ws, must<force_target>, opt_ws, must<equals>, opt_ws, must<force_value>> {};
struct unforce_all : kw_all {};
struct unforce_target : sor<unforce_all, data_operand> {};
struct unforce_line : seq<kw_unforce, ws, must<unforce_target>> {};
// scan N
struct scan_count : count {};
struct scan_line : seq<kw_scan, ws, must<scan_count>> {};
// run DURATION, run until CONDITION within DURATION
struct within_duration : duration {};
struct within_clause : seq<ws, kw_within, ws, must<within_duration>> {};
struct run_until : seq<kw_until, ws, must<condition>, must<within_clause>> {};
struct run_duration : duration {};
struct run_what : sor<run_until, run_duration> {};
struct run_line : seq<kw_run, ws, must<run_what>> {};
// expect CONDITION, expect FILE:a..b == v1 v2 ...
struct words_equal : op_eq {};
struct word_values : seq<value, star<ws, value>> {};
struct expect_words : seq<address_range, opt_ws, must<words_equal>, opt_ws, must<word_values>> {};
// expect log Q == "01/10/2000,20:00:00,2315" | none: retrieves the oldest record of MicroLogix data
// log queue Q (removing it, as a communications read does) and compares its text; `none`: the queue
// is empty. In the text \t stands for a TAB delimiter.
struct kw_log : TAO_PEGTL_KEYWORD("log") {};
struct log_queue : seq<plus<digit>, token_end> {};
struct log_text : star<not_one<'"'>> {};
struct log_quoted : seq<one<'"'>, log_text, must<quote_close>> {};
struct log_none : TAO_PEGTL_KEYWORD("none") {};
struct log_expected : sor<log_quoted, log_none> {};
struct expect_log : seq<kw_log, ws, must<log_queue>, opt_ws, must<words_equal>, opt_ws, must<log_expected>> {};
struct expectation : sor<expect_log, expect_words, condition> {};
struct expect_line : seq<kw_expect, ws, must<expectation>> {};
// mode program|run|test
struct step_mode_name : sor<kw_mode_program, kw_mode_run, kw_mode_test> {};
struct mode_line : seq<kw_mode, ws, must<step_mode_name>> {};
// power cycle, clear fault
struct power_cycle_word : kw_cycle {};
struct power_line : seq<kw_power, ws, must<power_cycle_word>> {};
struct clear_fault_word : kw_fault {};
struct clear_line : seq<kw_clear, ws, must<clear_fault_word>> {};
// snapshot NAME, restore NAME
struct snapshot_name : seq<pg::identifier, token_end> {};
struct restore_name : snapshot_name {};
struct snapshot_line : seq<kw_snapshot, ws, must<snapshot_name>> {};
struct restore_line : seq<kw_restore, ws, must<restore_name>> {};

// device NAME CHANGE [ARGS...]: a change injected into a bench device, shaped like
// Runtime::inject(device, change, args). The change is one or more lower-case words ("offline",
// "cable removed", "data size", "bt data", ... as each module family documents); the arguments
// start at the first token that is not such a word, and the switch words `on` and `off` are
// always arguments ("hold last state on" is the change "hold last state" with the argument "on").
//   device NAME offline | cable removed | data size 4 | bt data 1 2 3 | noisy off
struct device_line_name : device_name {};
struct switch_word : sor<TAO_PEGTL_KEYWORD("on"), TAO_PEGTL_KEYWORD("off")> {};
struct device_word : seq<not_at<switch_word>, range<'a', 'z'>, star<sor<range<'a', 'z'>, one<'_', '-'>>>, token_end> {};
struct device_arg : plus<not_one<' ', '\t', '#'>> {};
struct device_change : seq<device_word, star<ws, device_word>, star<ws, device_arg>> {};
struct device_line : seq<kw_device, ws, must<device_line_name>, ws, must<device_change>> {};

// Anything else that starts a line: reported by its action as an unknown statement.
struct unknown_statement : plus<not_one<' ', '\t', '#'>> {};

struct statement : sor<program_line, bench_line, node_line, ip_line, peer_line, channel_line, test_line, row_line, set_line, force_line, unforce_line, scan_line,
                       run_line, expect_line, mode_line, power_line, clear_line, snapshot_line, restore_line,
                       device_line, unknown_statement> {};
struct line_end : eof {};
struct line : seq<opt_ws, opt<statement>, opt_ws, opt<line_comment>, must<line_end>> {};

}  // namespace softslc::testing::grammar
