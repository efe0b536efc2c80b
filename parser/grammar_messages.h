// Error messages for the grammar's commit points (must<> rules), kept apart from the rules.
//
// Every rule that appears inside must<> has a message here; PEGTL's must_if control refuses to
// compile a grammar where one is missing, so no syntax error can surface without text.
#pragma once

#include "parser/grammar.h"

namespace softslc::grammar {

template <typename>
inline constexpr const char* error_message = nullptr;

template <> inline constexpr auto error_message<comment_close> = "unterminated comment: expected a closing '%'";
template <> inline constexpr auto error_message<quote_close> = "unterminated string: expected a closing '\"'";
template <> inline constexpr auto error_message<ref_body> =
    "expected a direct word address inside '[...]' (for example N10:1)";
template <> inline constexpr auto error_message<ref_close> = "expected ']' to close the indirect address";
template <> inline constexpr auto error_message<element_part> =
    "expected an element number or an indirect address '[...]' after ':'";
template <> inline constexpr auto error_message<word_spec> =
    "expected a word number, a sub-element name (PRE, ACC, LEN, POS) or '[...]' after '.'";
template <> inline constexpr auto error_message<bit_spec> =
    "expected a bit number 0-15, a bit name (EN, TT, DN, CU, CD, OV, UN, ...) or '[...]' after '/'";
template <> inline constexpr auto error_message<bit_offset_spec> = "expected a bit offset or '[...]' after '/'";
template <> inline constexpr auto error_message<operand> =
    "expected an operand: an address (N7:0, B3:0/1, T4:0.ACC), a number or a symbol";
template <> inline constexpr auto error_message<branch_close_required> =
    "unbalanced branch: expected NXB or BND to continue or close the BST";
template <> inline constexpr auto error_message<rung_end> =
    "expected an instruction mnemonic, a branch (BST, NXB, BND) or EOR";
template <> inline constexpr auto error_message<processor_catalog> = "expected the processor catalog number (for example 1747-L532)";
template <> inline constexpr auto error_message<module_catalog> = "expected the module catalog number (for example 1746-IB16)";
template <> inline constexpr auto error_message<series_letter> = "expected a series letter (A, B, C, ...)";
template <> inline constexpr auto error_message<frn_number> = "expected a firmware revision number";
template <> inline constexpr auto error_message<slot_number> = "expected a slot number";
template <> inline constexpr auto error_message<scan_in_words> = "expected the number of input words after SCAN_IN";
template <> inline constexpr auto error_message<scan_out_words> = "expected the number of output words after SCAN_OUT";
template <> inline constexpr auto error_message<g_file_count> = "expected the number of G-file words after G_FILE";
template <> inline constexpr auto error_message<m0_words> = "expected the M0 file size in words after M0_SIZE";
template <> inline constexpr auto error_message<m1_words> = "expected the M1 file size in words after M1_SIZE";
template <> inline constexpr auto error_message<id_code_value> = "expected the module ID code after ID_CODE";
template <> inline constexpr auto error_message<option_key> = "expected an option name after OPTION";
template <> inline constexpr auto error_message<option_equals> = "expected '=' between option name and value";
template <> inline constexpr auto error_message<option_value> = "expected an option value after '='";
template <> inline constexpr auto error_message<project_name> = "expected a quoted project name";
template <> inline constexpr auto error_message<ladder_number> = "expected a program file number after LADDER";
template <> inline constexpr auto error_message<data_header> =
    "expected a file and first element after DATA/FORCE (for example N7:0 or O:0)";
template <> inline constexpr auto error_message<data_colon> = "expected ':' in the file name";
template <> inline constexpr auto error_message<data_start> = "expected the first element number";
template <> inline constexpr auto error_message<data_item> = "expected a number, a quoted string or a '% label %'";
template <> inline constexpr auto error_message<force_item> = "expected a hexadecimal force word or a '% label %'";
template <> inline constexpr auto error_message<symbol_address> = "expected an address";
template <> inline constexpr auto error_message<datalog_queue> = "expected the data log queue number (0-255) after DATALOG";
template <> inline constexpr auto error_message<kw_records> = "expected RECORDS and the number of records after the queue number";
template <> inline constexpr auto error_message<datalog_records> = "expected the number of records after RECORDS";
template <> inline constexpr auto error_message<kw_delimiter> =
    "expected [DATE] [TIME] DELIMITER COMMA|TAB|SPACE after the number of records";
template <> inline constexpr auto error_message<datalog_delimiter> = "expected COMMA, TAB or SPACE after DELIMITER";
template <> inline constexpr auto error_message<datalog_field> = "expected the address of a field to log (N7:11, L14:0, T4:5.ACC)";
template <> inline constexpr auto error_message<symbol_def_name> = "expected a symbol name (letters, digits, '_')";
template <> inline constexpr auto error_message<symbol_description> = "expected a description between '%' signs";
template <> inline constexpr auto error_message<def_name> =
    "expected a variable name ending in '@' (bit) or '%' (register), for example RIO_D02@";
template <> inline constexpr auto error_message<def_suffix> =
    "expected '@' (a bit) or '%' (a register) at the end of the variable name";
template <> inline constexpr auto error_message<def_fields> =
    "expected '[' and the point's fields, for example [SLOT=8,REGISTER=4,BIT=2]";
template <> inline constexpr auto error_message<def_field> = "expected a field KEY=value (SLOT, REGISTER, BIT, ...)";
template <> inline constexpr auto error_message<def_equals> = "expected '=' between the field name and its value";
template <> inline constexpr auto error_message<def_value> = "expected the field's value (a number)";
template <> inline constexpr auto error_message<def_close> = "expected ',' and another field, or ']' to close the fields";
template <> inline constexpr auto error_message<statement_end> = "unexpected text at the end of the statement";

struct error_messages {
  template <typename Rule>
  static constexpr auto message = error_message<Rule>;
};

template <typename Rule>
using control = tao::pegtl::must_if<error_messages>::control<Rule>;

}  // namespace softslc::grammar
