// PEGTL grammar of the RSLogix 500 library export format (.SLC), as rule types only.
//
// The loader (loader.cpp) first splits a file into statements at lines that begin with a
// statement keyword (START, SLOT, PROJECT, LADDER, SOR, DATA, FORCE, SYMBOL, DESC) or a comment,
// then parses each statement with the `statement` rule below. A syntax error therefore costs one
// statement, not the file: the loader records it and carries on with the next, so every
// independent error is reported. Actions live in loader.cpp, error messages in
// grammar_messages.h. `must<>` marks commit points: once a keyword has matched, a failure
// further in is a positioned error rather than a silent backtrack.
//
// Whitespace inside a statement includes line breaks, so a rung or a SLOT line may continue on
// the next line (exports put G_FILE words on a continuation line).
#pragma once

#include <tao/pegtl.hpp>
#include <tao/pegtl/contrib/analyze_traits.hpp>

#include <algorithm>
#include <array>
#include <string_view>

#include "instructions/instruction_table.h"

namespace softslc::grammar {

namespace pegtl = tao::pegtl;
using namespace tao::pegtl;

// Note: PEGTL's must_if control raises the error message of a rule whenever that rule fails,
// so a rule with a message (grammar_messages.h) is used only inside must<>; where the same
// syntax is optional, a separately named rule is used.

// ---- Lexical ---------------------------------------------------------------------------------

// Blanks and line breaks separate tokens.
struct space_char : one<' ', '\t', '\r', '\n', '\f', '\v'> {};
struct ws : plus<space_char> {};
struct opt_ws : star<space_char> {};
// The end of a token: whitespace or end of input.
struct token_end : sor<at<space_char>, eof> {};

// A comment: text between percent signs, possibly spanning lines.
struct comment_text : star<not_one<'%'>> {};
struct comment_close : one<'%'> {};
struct comment : seq<one<'%'>, comment_text, must<comment_close>> {};

// A double-quoted string without escapes (project names, string data).
struct quoted_text : star<not_one<'"', '\n'>> {};
struct quote_close : one<'"'> {};
struct quoted : seq<one<'"'>, quoted_text, must<quote_close>> {};

struct digits : plus<digit> {};
struct sign : one<'+', '-'> {};
// Hexadecimal: 0x1F / 0X1F (as exports write data) or 1Fh (as RSLogix displays masks).
struct hex_c_style : seq<one<'0'>, one<'x', 'X'>, plus<xdigit>> {};
struct hex_h_style : seq<digit, star<xdigit>, one<'h', 'H'>> {};
struct hex_number : seq<opt<sign>, sor<hex_c_style, hex_h_style>> {};
struct exponent : seq<one<'e', 'E'>, opt<sign>, digits> {};
struct float_number : seq<opt<sign>, sor<seq<digits, one<'.'>, star<digit>, opt<exponent>>,
                                         seq<one<'.'>, digits, opt<exponent>>, seq<digits, exponent>>> {};
struct int_number : seq<opt<sign>, digits> {};
struct number : seq<sor<hex_number, float_number, int_number>, token_end> {};

// Identifiers name symbols, catalogs and keywords.
struct ident_first : sor<alpha, one<'_'>> {};
struct ident_other : sor<alnum, one<'_'>> {};
struct identifier : seq<ident_first, star<ident_other>> {};

// A token of any printable characters (catalog numbers such as 1747-L532 or Bul.1766).
struct word : plus<not_one<' ', '\t', '\r', '\n', '%', '"'>> {};

// ---- Addresses -----------------------------------------------------------------------------------
// I:1/3  I:1.0/3  O:2.1/15  S:1/15  B3:0/7  B3/62  N7:10/4  F8:2  T4:0.ACC  T4:0/DN  C5:1/OV
// R6:0.LEN  #N7:10  N7:[N10:1]  N[N10:0]:5  B3/[N7:0]  M0:1.100/13  M1:3.210  L41:0  ST9:0  RTC:0.YR
// MG11:0.NOD  MG11:0/DN  RI12:0.1

struct file_type_st : string<'S', 'T'> {};
struct file_type_m : seq<one<'M'>, one<'0', '1'>> {};
struct file_type_letter : one<'O', 'I', 'S', 'B', 'T', 'C', 'R', 'N', 'F', 'L', 'A'> {};
// MicroLogix function files (RTC:0.YR, HSC:0/FE): a name and no file number, so the name must
// be followed by ':' (that keeps STI from swallowing ST9:0 and CS from C5:0). The communications
// status file is written with its channel, CS0:4/MCP (1762-RM001C p. 21-27; CS1 the 1764-LRP's
// channel 1, CS2 the 1400's channel 2; CS alone is CS0). Every name starts
// with two capitals, and the lookahead for them turns away B3:0, N7:0 or T4:0 at their second
// character instead of trying each name (a memcmp per name, 3% of a large program's load).
struct file_type_function
    : seq<at<upper, upper>,
          sor<TAO_PEGTL_STRING("RTC"), TAO_PEGTL_STRING("HSC"), TAO_PEGTL_STRING("PTOX"), TAO_PEGTL_STRING("PTO"),
              TAO_PEGTL_STRING("PWMX"),
              TAO_PEGTL_STRING("STI"), TAO_PEGTL_STRING("EII"), TAO_PEGTL_STRING("BHI"), TAO_PEGTL_STRING("MMI"),
              TAO_PEGTL_STRING("DAT"), TAO_PEGTL_STRING("TPI"), seq<TAO_PEGTL_STRING("CS"), opt<range<'0', '2'>>>,
              TAO_PEGTL_STRING("IOS"), TAO_PEGTL_STRING("LCD")>,
          at<one<':'>>> {};
// The Data Log Status file is written with its file number, DLS0:0/DN (1763-RM001C p. 440); DLS:0
// is accepted too. The name is the whole match, so the '0' is no file number (action<file_type>).
struct file_type_data_log : seq<TAO_PEGTL_STRING("DLS"), opt<one<'0'>>, at<one<':'>>> {};
// The MicroLogix message (MG11:0) and routing information (RI12:0) files; RI before the R file's letter.
struct file_type_mg : string<'M', 'G'> {};
struct file_type_ri : string<'R', 'I'> {};
// Most addresses are B3:0, N7:0 or T4:0: a one-letter type not followed by a capital, which no
// longer name can be (every one starts with two capitals or M0/M1), is taken at once; the rest are
// tried in order only after an initial capital. Before, a number operand and every one-letter
// type first failed the function names and the DLS, ST, MG and RI strings, a memcmp each (3% of
// loading a large program, docs/performance.md "Load time"). Same language, same matched text.
struct file_type_single : seq<file_type_letter, not_at<upper>> {};
struct file_type
    : sor<file_type_single, seq<at<upper>, sor<file_type_function, file_type_data_log, file_type_st, file_type_m,
                                                file_type_mg, file_type_ri, file_type_letter>>> {};

// The word address inside brackets (no nesting, no expressions).
struct ref_type : file_type {};
struct ref_file : digits {};
struct ref_element : digits {};
struct ref_word_number : digits {};
struct ref_word_name : plus<upper> {};
struct ref_word : seq<one<'.'>, sor<ref_word_number, ref_word_name>> {};
struct ref_body : seq<ref_type, opt<ref_file>, one<':'>, ref_element, opt<ref_word>> {};
struct ref_close : one<']'> {};
struct ref : seq<one<'['>, must<ref_body>, must<ref_close>> {};

struct index_mark : one<'#'> {};
struct file_number : digits {};
struct indirect_file : ref {};
struct element_number : digits {};
struct indirect_element : ref {};
struct word_number : digits {};
struct word_name : plus<upper> {};
struct indirect_word : ref {};
struct bit_number : digits {};
struct bit_name : plus<upper> {};
struct indirect_bit : ref {};
struct bit_offset_number : digits {};
struct indirect_bit_offset : ref {};

struct element_part : sor<element_number, indirect_element> {};
struct word_spec : sor<word_number, word_name, indirect_word> {};
struct word_part : seq<one<'.'>, must<word_spec>> {};
struct bit_spec : sor<bit_number, bit_name, indirect_bit> {};
struct bit_part : seq<one<'/'>, must<bit_spec>> {};
struct colon_form : seq<one<':'>, must<element_part>, opt<word_part>, opt<bit_part>> {};
// B3/62: a bit offset counted from the start of the file.
struct bit_offset_spec : sor<bit_offset_number, indirect_bit_offset> {};
struct bit_offset_form : seq<one<'/'>, must<bit_offset_spec>> {};
struct address_body : seq<file_type, opt<sor<file_number, indirect_file>>, sor<colon_form, bit_offset_form>> {};
struct address : seq<opt<index_mark>, address_body, token_end> {};

// A standalone address (command lines, test files): optional blanks around one address.
struct address_only : seq<opt_ws, address, opt_ws, eof> {};

// ---- Rungs ---------------------------------------------------------------------------------------

// The rung keywords as three one-character rules: TAO_PEGTL_STRING calls memcmp, and EOR, NXB and
// BND are tried before every rung element (3% of loading a 1M-rung program, docs/performance.md
// "Load time"); this way a first-letter mismatch is one inlined compare. Same bytes matched.
template <char A, char B, char C>
struct keyword3 : seq<one<A>, one<B>, one<C>> {};
struct kw_sor : keyword3<'S', 'O', 'R'> {};
struct kw_eor : keyword3<'E', 'O', 'R'> {};
struct kw_bst : keyword3<'B', 'S', 'T'> {};
struct kw_nxb : keyword3<'N', 'X', 'B'> {};
struct kw_bnd : keyword3<'B', 'N', 'D'> {};
struct structure_keyword : seq<sor<kw_sor, kw_eor, kw_bst, kw_nxb, kw_bnd>, token_end> {};

// The blank-delimited token at the current position, at most `limit` characters (a longer one
// is returned cut to limit + 1 characters, enough to tell it is longer).
template <typename ParseInput>
std::string_view token_at(ParseInput& in, std::size_t limit) {
  const std::size_t available = in.size(limit + 1);
  const char* p = in.current();
  std::size_t n = 0;
  while (n < available && n <= limit && !(p[n] == ' ' || p[n] == '\t' || p[n] == '\r' || p[n] == '\n' || p[n] == '\f' ||
                                           p[n] == '\v'))
    ++n;
  return {p, n};
}

// A mnemonic's group for known_mnemonic: its length and first letter (a capital).
constexpr std::size_t mnemonic_group(std::size_t length, char first) {
  return length * 26 + static_cast<std::size_t>(first - 'A');
}

// A token that is a mnemonic of the instruction table (followed by a blank or the end of the
// input), generated from the table itself. It is tried before every operand (a symbol may not
// spell a mnemonic), so it is a lookup rather than a PEGTL sor<> of a string per row (the sor<>
// was a fifth of the load time of a large program) or a binary search of the sorted names (its
// string comparisons were 3-4%; docs/performance.md "Load time"): the names are grouped by length
// and first letter, and a token is compared only with the few of its own group.
struct known_mnemonic {
  using rule_t = known_mnemonic;
  using subs_t = tao::pegtl::empty_list;

  // Every row's mnemonic as the .def spells it (a second form's opcode name too, as before).
  static constexpr auto kNames = [] {
    std::array names{
#define OPERAND(...)
#define SOFTSLC_INSTRUCTION(m, ...) std::string_view(#m),
#include "instructions/instruction_table.def"
#undef SOFTSLC_INSTRUCTION
#undef OPERAND
    };
    return names;
  }();
  static constexpr std::size_t kLongest = [] {
    std::size_t n = 0;
    for (auto m : kNames) n = std::max(n, m.size());
    return n;
  }();
  // The names ordered by group, and where each group starts in that order (kStart[g] to
  // kStart[g + 1]).
  static constexpr auto kOrdered = [] {
    auto names = kNames;
    std::sort(names.begin(), names.end(), [](std::string_view a, std::string_view b) {
      const std::size_t ga = mnemonic_group(a.size(), a[0]), gb = mnemonic_group(b.size(), b[0]);
      return ga < gb || (ga == gb && a < b);
    });
    return names;
  }();
  static constexpr auto kStart = [] {
    std::array<std::uint16_t, mnemonic_group(kLongest + 1, 'A') + 1> start{};
    std::size_t i = 0;
    for (std::size_t g = 0; g < start.size(); ++g) {
      while (i < kOrdered.size() && mnemonic_group(kOrdered[i].size(), kOrdered[i][0]) < g) ++i;
      start[g] = static_cast<std::uint16_t>(i);
    }
    return start;
  }();
  static_assert(std::all_of(kNames.begin(), kNames.end(), [](std::string_view m) { return !m.empty() && m[0] >= 'A' && m[0] <= 'Z'; }),
                "known_mnemonic groups names by a capital first letter");

  static constexpr bool is_mnemonic(std::string_view token) {
    if (token.empty() || token.size() > kLongest || token[0] < 'A' || token[0] > 'Z') return false;
    const std::size_t g = mnemonic_group(token.size(), token[0]);
    for (std::size_t i = kStart[g]; i < kStart[g + 1]; ++i)
      if (std::equal(token.begin() + 1, token.end(), kOrdered[i].begin() + 1)) return true;
    return false;
  }

  template <typename ParseInput>
  static bool match(ParseInput& in) {
    const std::string_view token = token_at(in, kLongest);
    if (!is_mnemonic(token)) return false;
    in.bump(token.size());
    return true;
  }
};

// Whether a token is the three letters a, b, c: compared as characters, since a string_view
// comparison calls memcmp and these run for every operand and element (4% of loading a large
// program, docs/performance.md "Load time").
constexpr bool is_word3(std::string_view t, char a, char b, char c) {
  return t.size() == 3 && t[0] == a && t[1] == b && t[2] == c;
}

// Whether a token is one of the rung keywords SOR, EOR, BST, NXB, BND (as structure_keyword
// matches them: the whole token).
constexpr bool is_structure_keyword(std::string_view t) {
  return is_word3(t, 'S', 'O', 'R') || is_word3(t, 'E', 'O', 'R') || is_word3(t, 'B', 'S', 'T') ||
         is_word3(t, 'N', 'X', 'B') || is_word3(t, 'B', 'N', 'D');
}

// Where an operand may start: not at the end of the input, and not at a rung keyword or a
// mnemonic (a symbol may not spell one). One look at the token, consuming nothing: as three
// not_at<> rules (eof, structure_keyword, known_mnemonic) each saved and restored the input's
// position and the keyword rules were tried in turn (docs/performance.md "Load time"). Same
// tokens accepted.
struct operand_start {
  using rule_t = operand_start;
  using subs_t = tao::pegtl::empty_list;
  template <typename ParseInput>
  static bool match(ParseInput& in) {
    if (in.empty()) return false;
    const std::string_view token = token_at(in, known_mnemonic::kLongest);
    return !is_structure_keyword(token) && !known_mnemonic::is_mnemonic(token);
  }
};

// Where a rung element may start: not at EOR, NXB or BND (the end of the rung or of a branch
// leg), as not_at<> of each did, in one look at the token.
struct element_start {
  using rule_t = element_start;
  using subs_t = tao::pegtl::empty_list;
  template <typename ParseInput>
  static bool match(ParseInput& in) {
    const std::string_view t = token_at(in, 3);
    return !(is_word3(t, 'E', 'O', 'R') || is_word3(t, 'N', 'X', 'B') || is_word3(t, 'B', 'N', 'D'));
  }
};

// Operands: an address, a number, or a symbol name. Symbols may not spell a mnemonic. The MSG
// target devices 500CPU and 485CIF (RM 12-5) start with digits; they are words of the same kind.
struct message_device_word : sor<TAO_PEGTL_STRING("500CPU"), TAO_PEGTL_STRING("485CIF")> {};
struct symbol_name : seq<sor<message_device_word, identifier>, token_end> {};
struct operand : sor<address, number, symbol_name> {};
struct operand_token : seq<operand_start, must<operand>> {};
struct mnemonic : seq<identifier, token_end> {};
// CPT (issue 15): its expression runs from after the destination to the end of the instruction:
// EOR, a branch keyword, or the next mnemonic that is not also an expression word (AND, OR, XOR,
// NOT and the functions are both). parser/expression.h parses the text itself.
struct expression_word
    : seq<sor<TAO_PEGTL_STRING("AND"), TAO_PEGTL_STRING("OR"), TAO_PEGTL_STRING("XOR"), TAO_PEGTL_STRING("NOT"),
              TAO_PEGTL_STRING("SQR"), TAO_PEGTL_STRING("ABS"), TAO_PEGTL_STRING("LN"), TAO_PEGTL_STRING("LOG"),
              TAO_PEGTL_STRING("SIN"), TAO_PEGTL_STRING("COS"), TAO_PEGTL_STRING("TAN"), TAO_PEGTL_STRING("ASN"),
              TAO_PEGTL_STRING("ACS"), TAO_PEGTL_STRING("ATN"), TAO_PEGTL_STRING("DEG"), TAO_PEGTL_STRING("RAD"),
              TAO_PEGTL_STRING("TOD"), TAO_PEGTL_STRING("FRD")>,
          token_end> {};
struct expression_stop : sor<eof, structure_keyword, seq<not_at<expression_word>, known_mnemonic>> {};
struct expression_piece : plus<not_one<' ', '\t', '\r', '\n', '\f', '\v', '%', '"'>> {};
struct cpt_expression : seq<expression_piece, star<ws, not_at<expression_stop>, expression_piece>> {};
struct kw_cpt : seq<keyword3<'C', 'P', 'T'>, token_end> {};
struct cpt_instruction : seq<at<kw_cpt>, mnemonic, ws, operand_token, ws, not_at<expression_stop>, cpt_expression> {};
struct instruction : sor<cpt_instruction, seq<mnemonic, star<ws, operand_token>>> {};

struct rung_element;
struct leg : star<rung_element, opt_ws> {};
struct branch_open : seq<kw_bst, token_end> {};
struct branch_next : seq<kw_nxb, token_end> {};
struct branch_close : seq<kw_bnd, token_end> {};
// The same rule as branch_close where its absence is an error (messages key on the rule type).
struct branch_close_required : branch_close {};
struct branch : seq<branch_open, opt_ws, leg, star<branch_next, opt_ws, leg>, must<branch_close_required>> {};
struct rung_element : seq<element_start, sor<branch, instruction>> {};
struct rung_end : seq<kw_eor, token_end> {};
// NXB or BND with no open BST: reported by its action, then parsing goes on.
struct stray_branch_keyword : sor<branch_next, branch_close> {};
struct rung : seq<kw_sor, token_end, opt_ws, star<sor<rung_element, stray_branch_keyword>, opt_ws>, must<rung_end>> {};

// ---- Configuration statements -----------------------------------------------------------------------

struct catalog : word {};
struct kw_start : TAO_PEGTL_STRING("START") {};
struct series_letter : upper {};
struct start_series : seq<TAO_PEGTL_STRING("SERIES"), ws, must<series_letter>> {};
struct frn_number : digits {};
struct start_frn : seq<TAO_PEGTL_STRING("FRN"), ws, must<frn_number>> {};
struct processor_description : comment {};
struct start_item : sor<start_series, start_frn, processor_description> {};
struct processor_catalog : catalog {};
struct start_stmt : seq<kw_start, ws, must<processor_catalog>, star<ws, start_item>, opt_ws> {};

struct slot_number : digits {};
struct slot_description : comment {};
struct scan_in_words : digits {};
struct scan_in : seq<TAO_PEGTL_STRING("SCAN_IN"), ws, must<scan_in_words>> {};
struct scan_out_words : digits {};
struct scan_out : seq<TAO_PEGTL_STRING("SCAN_OUT"), ws, must<scan_out_words>> {};
struct g_file_count : digits {};
struct g_file_word : seq<int_number, token_end> {};
struct g_file : seq<TAO_PEGTL_STRING("G_FILE"), ws, must<g_file_count>, star<ws, g_file_word>> {};
struct iocard_value : seq<int_number, token_end> {};
struct iocard : seq<TAO_PEGTL_STRING("IOCARD"), star<ws, iocard_value>> {};
struct m0_words : digits {};
struct m0_size : seq<TAO_PEGTL_STRING("M0_SIZE"), ws, must<m0_words>> {};
struct m1_words : digits {};
struct m1_size : seq<TAO_PEGTL_STRING("M1_SIZE"), ws, must<m1_words>> {};
struct id_code_value : digits {};
struct id_code : seq<TAO_PEGTL_STRING("ID_CODE"), ws, must<id_code_value>> {};
struct option_key : identifier {};
struct option_value : word {};
struct option_equals : one<'='> {};
struct option : seq<TAO_PEGTL_STRING("OPTION"), ws, must<option_key>, must<option_equals>, must<option_value>> {};
struct slot_item : sor<scan_in, scan_out, g_file, iocard, m0_size, m1_size, id_code, option, slot_description> {};
struct kw_slot : TAO_PEGTL_STRING("SLOT") {};
struct module_catalog : catalog {};
struct slot_stmt : seq<kw_slot, ws, must<slot_number>, ws, must<module_catalog>, star<ws, slot_item>, opt_ws> {};

struct project_name : quoted {};
struct kw_project : TAO_PEGTL_STRING("PROJECT") {};
struct project_stmt : seq<kw_project, ws, must<project_name>, opt_ws> {};

struct ladder_number : digits {};
struct ladder_name : sor<quoted, identifier> {};
struct kw_ladder : TAO_PEGTL_STRING("LADDER") {};
struct ladder_stmt : seq<kw_ladder, ws, must<ladder_number>, opt<ws, ladder_name>, opt_ws> {};

// ---- Data and forces ----------------------------------------------------------------------------------

// DATA headers name a file and its first element: N7:0, O:0, S:0, HSC0:0 (function files).
struct data_file_letters : plus<upper> {};
struct data_file_number : digits {};
struct data_start : digits {};
struct data_colon : one<':'> {};
struct data_header : seq<data_file_letters, opt<data_file_number>, must<data_colon>, must<data_start>> {};
struct data_label : comment {};
struct data_number : number {};
struct data_string : quoted {};
struct data_item : sor<data_label, data_string, data_number> {};
struct kw_data : TAO_PEGTL_STRING("DATA") {};
struct data_stmt : seq<kw_data, ws, must<data_header>, star<ws, not_at<eof>, must<data_item>>, opt_ws> {};

struct force_number : number {};
struct force_item : sor<comment, force_number> {};
struct kw_force : TAO_PEGTL_STRING("FORCE") {};
struct force_stmt : seq<kw_force, ws, must<data_header>, star<ws, not_at<eof>, must<force_item>>, opt_ws> {};

// ---- Symbols -------------------------------------------------------------------------------------------

struct symbol_address : address {};
// RSLogix also accepts symbols that start with digits ("5120MS_TIMER" in lecky_demo.RSS); such a
// name is defined by SYMBOL and shown, but operands in rungs use the address.
struct digit_led_name : seq<plus<digit>, sor<alpha, one<'_'>>, star<ident_other>> {};
struct symbol_def_name : seq<sor<identifier, digit_led_name>, token_end> {};
struct symbol_description : comment {};
struct kw_symbol : TAO_PEGTL_STRING("SYMBOL") {};
struct symbol_note : comment {};
struct symbol_stmt : seq<kw_symbol, ws, must<symbol_address>, ws, must<symbol_def_name>, opt<ws, symbol_note>, opt_ws> {};
struct kw_desc : TAO_PEGTL_STRING("DESC") {};
struct desc_stmt : seq<kw_desc, ws, must<symbol_address>, ws, must<symbol_description>, opt_ws> {};

// AutoMax configuration statements (docs/automax.md): IODEF NAME@[SLOT=8,REGISTER=4,BIT=2],
// RIODEF NAME%[MASTER_SLOT=8,DROP=2,SLOT=0,REGISTER=3], MEMDEF NAME@. A value is a decimal or
// hexadecimal number (04, 20H) or a hexadecimal drop digit (C).
struct def_suffix : one<'@', '%'> {};
struct def_name : seq<identifier, must<def_suffix>> {};
struct def_key : identifier {};
struct def_equals : one<'='> {};
struct def_value : plus<alnum> {};
struct def_field : seq<def_key, opt_ws, must<def_equals>, opt_ws, must<def_value>> {};
struct def_close : one<']'> {};
struct def_fields : seq<one<'['>, opt_ws, must<def_field>, star<opt_ws, one<','>, opt_ws, must<def_field>>, opt_ws,
                        must<def_close>> {};
struct kw_iodef : TAO_PEGTL_STRING("IODEF") {};
struct kw_riodef : TAO_PEGTL_STRING("RIODEF") {};
struct kw_memdef : TAO_PEGTL_STRING("MEMDEF") {};
struct def_note : comment {};
struct io_def_stmt : seq<sor<kw_iodef, kw_riodef>, ws, must<def_name>, opt_ws, must<def_fields>, opt<ws, def_note>,
                         opt_ws> {};
struct mem_def_stmt : seq<kw_memdef, ws, must<def_name>, opt<ws, def_note>, opt_ws> {};

// A data log queue (docs/program-format.md "Data log queues"):
// DATALOG 0 RECORDS 12 DATE TIME DELIMITER COMMA N7:11 L14:0 T4:5.ACC I1:3.0 B3:2
struct kw_datalog : TAO_PEGTL_STRING("DATALOG") {};
struct datalog_queue : digits {};
struct kw_records : TAO_PEGTL_STRING("RECORDS") {};
struct datalog_records : digits {};
struct datalog_date : seq<TAO_PEGTL_STRING("DATE"), token_end> {};
struct datalog_time : seq<TAO_PEGTL_STRING("TIME"), token_end> {};
struct kw_delimiter : TAO_PEGTL_STRING("DELIMITER") {};
struct datalog_delimiter : seq<sor<TAO_PEGTL_STRING("COMMA"), TAO_PEGTL_STRING("TAB"), TAO_PEGTL_STRING("SPACE")>, token_end> {};
struct datalog_field : address {};
struct datalog_stmt : seq<kw_datalog, ws, must<datalog_queue>, ws, must<kw_records>, ws, must<datalog_records>,
                          opt<ws, datalog_date>, opt<ws, datalog_time>, ws, must<kw_delimiter>, ws,
                          must<datalog_delimiter>, star<ws, not_at<eof>, must<datalog_field>>, opt_ws> {};

// A free comment line (section headings, "% Rung: 0 %" markers, rung comments).
struct comment_stmt : seq<comment, opt_ws> {};

// One statement; the loader feeds statements one at a time.
struct statement_end : eof {};
struct rung_stmt : seq<rung, opt_ws> {};
struct statement : seq<opt_ws, sor<start_stmt, slot_stmt, project_stmt, ladder_stmt, rung_stmt, data_stmt,
                                   force_stmt, symbol_stmt, desc_stmt, io_def_stmt, mem_def_stmt,
                                   datalog_stmt, comment_stmt>, must<statement_end>> {};

}  // namespace softslc::grammar

// For tao::pegtl::analyze (tests/parser/program_test.cpp): a mnemonic consumes at least one character.
template <typename Name>
struct tao::pegtl::analyze_traits<Name, softslc::grammar::known_mnemonic> : tao::pegtl::analyze_any_traits<> {};
// The guards look ahead without consuming, as the not_at<> rules they replace.
template <typename Name>
struct tao::pegtl::analyze_traits<Name, softslc::grammar::operand_start> : tao::pegtl::analyze_opt_traits<> {};
template <typename Name>
struct tao::pegtl::analyze_traits<Name, softslc::grammar::element_start> : tao::pegtl::analyze_opt_traits<> {};
