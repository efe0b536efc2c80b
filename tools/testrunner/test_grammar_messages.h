// Error messages for the test grammar's commit points (must<> rules), kept apart from the rules.
//
// Every rule that appears inside must<> has a message here, or, for the address rules reused from
// the program grammar, the program grammar's own message (parser/grammar_messages.h), so an
// address is diagnosed in a test file exactly as in a program. PEGTL's must_if control refuses
// to compile a grammar where a message is missing.
#pragma once

#include "parser/grammar_messages.h"
#include "tools/testrunner/test_grammar.h"

namespace softslc::testing::grammar {

template <typename Rule>
inline constexpr const char* error_message = softslc::grammar::error_message<Rule>;

#define SOFTSLC_VALUE_EXAMPLES "a value (5, -3, 0x00FF, 00FFh, 0b0000_1111, 1.5)"
#define SOFTSLC_DURATION_EXAMPLES "a duration (250ms, 1.5s, 2m, 10us)"

template <> inline constexpr auto error_message<range_last> = "expected the last element number after '..' (for example N11:0..13)";
template <> inline constexpr auto error_message<value_high> = "expected the upper bound after '..': " SOFTSLC_VALUE_EXAMPLES;
template <> inline constexpr auto error_message<value_range> = "expected a range 'LOW..HIGH' after 'in' (for example 10..20)";
template <> inline constexpr auto error_message<duration_high> = "expected the upper bound after '..': " SOFTSLC_DURATION_EXAMPLES;
template <> inline constexpr auto error_message<duration_range> =
    "expected a range of durations after 'in' (for example 0.99s..1.01s)";
template <> inline constexpr auto error_message<count_high> = "expected the upper bound after '..' (a number of scans)";
template <> inline constexpr auto error_message<count_range> = "expected a range of scan counts after 'in' (for example 90..110)";
template <> inline constexpr auto error_message<data_rhs> =
    "expected " SOFTSLC_VALUE_EXAMPLES ", an address or a symbol after the operator";
template <> inline constexpr auto error_message<data_tail> =
    "expected a comparison after the operand: ==, !=, <, <=, >, >= or 'in LOW..HIGH'";
template <> inline constexpr auto error_message<elapsed_rhs> = "expected " SOFTSLC_DURATION_EXAMPLES " after the operator";
template <> inline constexpr auto error_message<elapsed_tail> =
    "expected a comparison after 'elapsed': ==, !=, <, <=, >, >= and a duration, or 'in LOW..HIGH'";
template <> inline constexpr auto error_message<scans_rhs> = "expected a number of scans after the operator";
template <> inline constexpr auto error_message<scans_tail> =
    "expected a comparison after 'scans': ==, !=, <, <=, >, >= and a number, or 'in LOW..HIGH'";
template <> inline constexpr auto error_message<fault_after_no> = "expected 'fault' after 'no'";
template <> inline constexpr auto error_message<condition_mode_name> = "expected a mode: program, run, test, faulted or suspended";
template <> inline constexpr auto error_message<paren_close> = "expected ')' to close the '('";
template <> inline constexpr auto error_message<next_primary> = "expected a condition after 'and'";
template <> inline constexpr auto error_message<next_conjunction> = "expected a condition after 'or'";
template <> inline constexpr auto error_message<condition> =
    "expected a condition: a comparison (N7:0 == 5, MOTOR != 0, N7:0 in 10..20), elapsed, scans, fault, "
    "no fault or mode";
template <> inline constexpr auto error_message<nested_condition> = "expected a condition after '('";
template <> inline constexpr auto error_message<quote_close> = "unterminated string: expected a closing '\"'";
template <> inline constexpr auto error_message<program_path> = "expected the path of the program (.slc) after 'program'";
template <> inline constexpr auto error_message<program_processor_spec> =
    "expected the processor of the pasted rungs after 'processor' (CATALOG or CATALOG:SERIES, for example Bul.1763)";
template <> inline constexpr auto error_message<bench_path> = "expected the path of the bench file after 'bench'";
template <> inline constexpr auto error_message<node_number> = "expected a node number after 'node' (node 2)";
template <> inline constexpr auto error_message<peer_name> =
    "expected the peer's name after 'peer' (peer B line_b.slc node 2)";
template <> inline constexpr auto error_message<peer_path> = "expected the path of the peer's program after its name";
template <> inline constexpr auto error_message<peer_node> =
    "expected 'node N' (DH-485, DH+), 'ip A.B.C.D' (Ethernet), 'df1' (the DF1 cable on channel 0) or 'modbus "
    "address=N' (a Modbus RTU slave on the program's channel 0 line) after the peer's program";
template <> inline constexpr auto error_message<network_name> =
    "expected the network's name after 'network' (network PANEL)";
template <> inline constexpr auto error_message<channel_number> =
    "expected the channel number after 'channel' (channel 1 node 3)";
template <> inline constexpr auto error_message<channel_setup> =
    "expected 'node N' (channel 1 node 3 network PANEL) or 'df1' (channel 0 df1 baud=19200) after the channel";
template <> inline constexpr auto error_message<ip_address> = "expected an IP address after 'ip' (ip 192.168.1.20)";
template <> inline constexpr auto error_message<test_name> = "expected the test name in double quotes (test \"name\")";
template <> inline constexpr auto error_message<column_list> =
    "expected the table's column names after 'with' (test \"name\" with A B)";
template <> inline constexpr auto error_message<set_target> = "expected an address or a symbol to set";
template <> inline constexpr auto error_message<equals> = "expected '=' after the address (set N7:0 = 5)";
template <> inline constexpr auto error_message<set_value> = "expected " SOFTSLC_VALUE_EXAMPLES " after '='";
template <> inline constexpr auto error_message<force_target> = "expected an I: or O: bit to force";
template <> inline constexpr auto error_message<force_value> = "expected 0 or 1 after '='";
template <> inline constexpr auto error_message<unforce_target> = "expected an I: or O: bit, or 'all', after 'unforce'";
template <> inline constexpr auto error_message<scan_count> = "expected the number of scans after 'scan'";
template <> inline constexpr auto error_message<within_duration> = "expected " SOFTSLC_DURATION_EXAMPLES " after 'within'";
template <> inline constexpr auto error_message<within_clause> =
    "expected 'within DURATION' after the condition (run until MOTOR == 0 within 2s)";
template <> inline constexpr auto error_message<run_what> =
    "expected " SOFTSLC_DURATION_EXAMPLES " or 'until CONDITION within DURATION' after 'run'";
template <> inline constexpr auto error_message<log_queue> = "expected the data log queue number after 'expect log'";
template <> inline constexpr auto error_message<log_expected> = "expected the record as a quoted string, or none";
template <> inline constexpr auto error_message<words_equal> =
    "expected '==' and one value per element after a range (expect N11:0..2 == 1 2 3)";
template <> inline constexpr auto error_message<word_values> = "expected one value per element of the range after '=='";
template <> inline constexpr auto error_message<expectation> = "expected a condition after 'expect'";
template <> inline constexpr auto error_message<step_mode_name> = "expected a mode: program, run or test";
template <> inline constexpr auto error_message<power_cycle_word> = "expected 'power cycle'";
template <> inline constexpr auto error_message<clear_fault_word> = "expected 'clear fault'";
template <> inline constexpr auto error_message<snapshot_name> = "expected a snapshot name (letters, digits, '_')";
template <> inline constexpr auto error_message<restore_name> = "expected the name of a snapshot to restore";
template <> inline constexpr auto error_message<device_name> = "expected a bench device name after 'device'";
template <> inline constexpr auto error_message<device_line_name> = "expected a bench device name after 'device'";
template <> inline constexpr auto error_message<observation_what> =
    "expected what to observe of the device, in lower-case words, optionally with an element index (btw count, "
    "btw data[2], outputs[0])";
template <> inline constexpr auto error_message<device_change> =
    "expected the change to inject, in lower-case words, then its arguments (offline, cable removed, data size 4, "
    "...)";
template <> inline constexpr auto error_message<line_end> = "unexpected text at the end of the line";

#undef SOFTSLC_VALUE_EXAMPLES
#undef SOFTSLC_DURATION_EXAMPLES

struct error_messages {
  template <typename Rule>
  static constexpr auto message = error_message<Rule>;
};

template <typename Rule>
using control = tao::pegtl::must_if<error_messages>::control<Rule>;

}  // namespace softslc::testing::grammar
