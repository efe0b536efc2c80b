// Parsing and loading test files: the model the parser builds, table expansion, and every kind of
// error in a bad test file rendered exactly as `softslc test` prints it (gcc style, with caret).
#include <gtest/gtest.h>

#include <tao/pegtl/contrib/analyze.hpp>

#include "testrunner_test_util.h"
#include "parser/limits.h"
#include "tools/testrunner/test_grammar.h"
#include "tools/testrunner/test_parser.h"

namespace softslc::testing {
namespace {

using test::Sandbox;

// PEGTL's grammar analysis: no rule can loop without consuming input.
TEST(Grammar, HasNoLoopsWithoutProgress) { EXPECT_EQ(tao::pegtl::analyze<grammar::line>(), 0u); }

// ---- The model ---------------------------------------------------------------------------------------

TEST(Parse, StepsAndOperands) {
  auto r = parse_test_text(
      "program lamp.slc   # the program\n"
      "test \"one\"\n"
      "  set    SWITCH = 1\n"
      "  set    N11:0..2 = 1 0x2 0b11\n"
      "  force  I:1/0 = 1\n"
      "  unforce I:1/0\n"
      "  unforce all\n"
      "  scan   3\n"
      "  run    1.5s\n"
      "  run    until LAMP == 1 within 250ms   # comment\n"
      "  expect N7:0 in -5..0x10\n"
      "  expect N11:0..1 == 14 15\n"
      "  power  cycle\n"
      "  clear  fault\n"
      "  mode   program\n"
      "  snapshot here\n"
      "  restore here\n"
      "  set    #N7:0 = 5\n",
      "t.test");
  ASSERT_FALSE(r.diagnostics.has_errors()) << render_all(r.diagnostics, "t.test", r.file.source);
  ASSERT_EQ(r.file.tests.size(), 1u);
  const TestCase& t = r.file.tests[0];
  EXPECT_EQ(t.name, "one");
  EXPECT_EQ(t.program_path, "lamp.slc");
  EXPECT_EQ(t.initial_mode, Mode::Run);
  ASSERT_EQ(t.steps.size(), 16u);
  using K = Step::Kind;
  const K kinds[] = {K::Set,         K::Set,    K::Force,      K::Unforce,    K::UnforceAll, K::Scan,
                     K::Run,         K::RunUntil, K::Expect,   K::ExpectWords, K::PowerCycle, K::ClearFault,
                     K::Mode,        K::Snapshot, K::Restore,  K::Set};
  for (std::size_t i = 0; i < t.steps.size(); ++i) EXPECT_EQ(t.steps[i].kind, kinds[i]) << "step " << i;

  EXPECT_EQ(t.steps[0].target.symbol, "SWITCH");
  EXPECT_EQ(t.steps[0].loc, (Location{3, 3}));
  EXPECT_EQ(t.steps[0].target.loc, (Location{3, 10}));
  EXPECT_EQ(t.steps[1].target.range_last, 2);
  EXPECT_EQ(t.steps[1].values.size(), 3u);
  EXPECT_EQ(t.steps[1].values[2].integer, 3);
  EXPECT_EQ(t.steps[5].count, 3);
  EXPECT_EQ(t.steps[6].duration, milliseconds(1500));
  EXPECT_EQ(t.steps[7].duration, milliseconds(250));
  EXPECT_EQ(t.steps[7].text, "run    until LAMP == 1 within 250ms");
  EXPECT_EQ(to_string(t.steps[7].condition), "LAMP == 1");
  EXPECT_EQ(to_string(t.steps[8].condition), "N7:0 in -5..0x10");
  EXPECT_EQ(t.steps[12].mode, Mode::Program);
  EXPECT_EQ(t.steps[14].name, "here");
  // '#' followed by a file letter is an indexed address, not a comment.
  EXPECT_TRUE(t.steps[15].target.address.indexed);
}

TEST(Parse, AndBindsTighterThanOr) {
  auto r = parse_test_text(
      "program lamp.slc\n"
      "test \"c\"\n"
      "  expect LAMP == 1 or N7:0 > 2 and N7:1 <= 3\n"
      "  expect (LAMP == 1 or N7:0 > 2) and no fault\n"
      "  expect fault 0020h or fault or mode faulted\n"
      "  expect elapsed in 1s..2s and scans != 3 and N7:0 == 0b1x\n",
      "t.test");
  ASSERT_FALSE(r.diagnostics.has_errors()) << render_all(r.diagnostics, "t.test", r.file.source);
  const auto& s = r.file.tests.at(0).steps;
  EXPECT_EQ(s[0].condition.kind, Condition::Kind::Or);
  EXPECT_EQ(s[0].condition.terms.at(1).kind, Condition::Kind::And);
  EXPECT_EQ(to_string(s[0].condition), "LAMP == 1 or N7:0 > 2 and N7:1 <= 3");
  EXPECT_EQ(s[1].condition.kind, Condition::Kind::And);
  EXPECT_EQ(to_string(s[1].condition), "(LAMP == 1 or N7:0 > 2) and no fault");
  EXPECT_EQ(s[2].condition.terms.at(0).fault_code, 0x20);
  EXPECT_FALSE(s[2].condition.terms.at(1).fault_code.has_value());
  EXPECT_EQ(s[2].condition.terms.at(2).mode, Mode::Faulted);
  EXPECT_EQ(to_string(s[3].condition), "elapsed in 1s..2s and scans != 3 and N7:0 == 0b1x");
}

TEST(Parse, FirstModeStepChoosesTheStartingMode) {
  auto r = parse_test_text("program lamp.slc\ntest \"t\"\n  mode test\n  scan 1\n  mode run\n", "t.test");
  ASSERT_FALSE(r.diagnostics.has_errors());
  EXPECT_EQ(r.file.tests[0].initial_mode, Mode::Test);
  ASSERT_EQ(r.file.tests[0].steps.size(), 2u);  // the later `mode run` is a step
  EXPECT_EQ(r.file.tests[0].steps[1].kind, Step::Kind::Mode);
}

TEST(Parse, ProgramPerFileAndPerTest) {
  auto r = parse_test_text(
      "program lamp.slc\n"
      "test \"a\"\n  scan 1\n"
      "test \"b\"\n  program other.slc\n  scan 1\n",
      "t.test");
  ASSERT_FALSE(r.diagnostics.has_errors());
  EXPECT_EQ(r.file.tests[0].program_path, "lamp.slc");
  EXPECT_EQ(r.file.tests[1].program_path, "other.slc");
  EXPECT_EQ(r.file.tests[1].program_loc, (Location{5, 11}));
}

TEST(Parse, TableRowsBecomeTests) {
  auto r = parse_test_text(
      "program lamp.slc\n"
      "test \"lamp follows $IN\" with IN OUT\n"
      "  row 0 0\n"
      "  row 1 1   # on\n"
      "  set SWITCH = $IN\n"
      "  scan 1\n"
      "  expect LAMP == $OUT\n"
      "test \"plain\" with T\n"
      "  row 10ms\n"
      "  run $T\n",
      "t.test");
  ASSERT_FALSE(r.diagnostics.has_errors()) << render_all(r.diagnostics, "t.test", r.file.source);
  ASSERT_EQ(r.file.tests.size(), 3u);
  EXPECT_EQ(r.file.tests[0].name, "lamp follows 0");
  EXPECT_EQ(r.file.tests[1].name, "lamp follows 1");
  EXPECT_EQ(r.file.tests[1].loc.line, 4u);  // a row's test is located at its row
  EXPECT_EQ(r.file.tests[1].steps[0].text, "set SWITCH = 1");
  EXPECT_EQ(r.file.tests[1].steps[0].values[0].integer, 1);
  // Locations inside substituted lines point at the original columns.
  EXPECT_EQ(r.file.tests[1].steps[2].condition.compare.rhs.loc, (Location{7, 18}));
  // A name without references gets the row's values.
  EXPECT_EQ(r.file.tests[2].name, "plain [T=10ms]");
  EXPECT_EQ(r.file.tests[2].steps[0].duration, milliseconds(10));
}

// ---- Diagnostics ------------------------------------------------------------------------------------

struct Golden {
  const char* name;
  const char* text;      // the test file (t.test), beside lamp.slc and other.slc
  const char* expected;  // the rendered diagnostics
};
// How ctest and gtest name this case (else "GetParam() = 32-byte object <54-29 ...>").
void PrintTo(const Golden& c, std::ostream* os) { *os << c.name; }

class BadTestFiles : public ::testing::TestWithParam<Golden> {};

TEST_P(BadTestFiles, RenderExactly) {
  Sandbox box;
  EXPECT_EQ(box.diagnostics(GetParam().text), GetParam().expected);
}

INSTANTIATE_TEST_SUITE_P(
    Diagnostics, BadTestFiles,
    ::testing::Values(
        Golden{"MissingValue", "program lamp.slc\ntest \"t\"\n  expect N7:0 ==\n",
               "t.test:3:17: error: expected a value (5, -3, 0x00FF, 00FFh, 0b0000_1111, 1.5), an address or a "
               "symbol after the operator\n  expect N7:0 ==\n                ^\n"},
        Golden{"MissingOperator", "program lamp.slc\ntest \"t\"\n  expect N7:0 = 5\n",
               "t.test:3:15: error: expected a comparison after the operand: ==, !=, <, <=, >, >= or 'in "
               "LOW..HIGH'\n  expect N7:0 = 5\n              ^\n"},
        Golden{"UnknownStatement", "program lamp.slc\ntest \"t\"\n  frobnicate N7:0\n",
               "t.test:3:3: error: unknown statement 'frobnicate': expected program, bench, test, row, set, "
               "force, unforce, scan, run, expect, mode, power cycle, clear fault, snapshot, restore or device\n"
               "  frobnicate N7:0\n  ^\n"},
        Golden{"IncompleteStep", "program lamp.slc\ntest \"t\"\n  run\n",
               "t.test:3:3: error: incomplete 'run' line: write run DURATION  or  run until CONDITION within "
               "DURATION\n  run\n  ^\n"},
        Golden{"MissingWithin", "program lamp.slc\ntest \"t\"\n  run until LAMP == 1\n",
               "t.test:3:22: error: expected 'within DURATION' after the condition (run until MOTOR == 0 within "
               "2s)\n  run until LAMP == 1\n                     ^\n"},
        Golden{"DurationWithoutUnit", "program lamp.slc\ntest \"t\"\n  expect elapsed <= 5\n",
               // The caret is where the unit is missing.
               "t.test:3:22: error: expected a duration (250ms, 1.5s, 2m, 10us) after the operator\n  expect "
               "elapsed <= 5\n                     ^\n"},
        Golden{"ProgramGrammarAddressError", "program lamp.slc\ntest \"t\"\n  expect T4:0/XX == 1\n",
               "t.test:3:15: error: unknown bit name 'XX' (timer bits are EN, TT, DN)\n  expect T4:0/XX == 1\n  "
               "            ^\n"},
        Golden{"UnclosedParenthesis", "program lamp.slc\ntest \"t\"\n  expect (LAMP == 1 or N7:0 == 2\n",
               // The caret is at the end of the line, where the ')' is missing.
               "t.test:3:33: error: expected ')' to close the '('\n  expect (LAMP == 1 or N7:0 == 2\n          "
               "                      ^\n"},
        Golden{"TrailingText", "program lamp.slc\ntest \"t\"\n  scan 1 2\n",
               "t.test:3:10: error: unexpected text at the end of the line\n  scan 1 2\n         ^\n"},
        Golden{"StepOutsideTest", "program lamp.slc\nscan 1\n",
               "t.test:2:1: error: a step must belong to a test: start one with test \"name\"\nscan 1\n^\n"},
        Golden{"MissingBenchFile", "program lamp.slc\nbench nowhere.bench\ntest \"t\"\n  scan 1\n",
               "nowhere.bench: error: cannot open file: No such file or directory\nt.test:2:7: error: bench 'nowhere.bench' did "
               "not load (its errors are listed above)\nbench nowhere.bench\n      ^\n"},
        Golden{"DeviceWithoutBench", "program lamp.slc\ntest \"t\"\n  device DRIVE1 cable removed\n",
               "t.test:3:10: error: no bench device 'DRIVE1' (this test has no bench: add 'bench FILE.bench')\n"
               "  device DRIVE1 cable removed\n         ^\n"},
        Golden{"DeviceWithoutChange", "program lamp.slc\ntest \"t\"\n  device DRIVE1 42\n",
               "t.test:3:17: error: expected the change to inject, in lower-case words, then its arguments "
               "(offline, cable removed, data size 4, ...)\n  device DRIVE1 42\n                ^\n"},
        Golden{"UnknownSymbol", "program lamp.slc\ntest \"t\"\n  set MOTOR = 1\n",
               "t.test:3:7: error: unknown symbol 'MOTOR': not a SYMBOL of lamp.slc\n  set MOTOR = 1\n      ^\n"},
        Golden{"AddressNotInTheDataTable", "program lamp.slc\ntest \"t\"\n  expect N7:9 == 0\n",
               "t.test:3:10: error: N7:9 is beyond the end of N7 (elements 0-3)\n  expect N7:9 == 0\n         "
               "^\n"},
        Golden{"NoInputModule", "program lamp.slc\ntest \"t\"\n  set I:3/0 = 1\n",
               "t.test:3:7: error: I:3.0/0: slot 3 has no module (no SLOT 3 line)\n  set I:3/0 = 1\n      ^\n"},
        // Issue 17: bit 32 wrapped to bit 0 and O:2/16 wrote nothing; the checker's address rule.
        Golden{"InputBitBeyondFifteen", "program lamp.slc\ntest \"t\"\n  set I:1/32 = 1\n",
               "t.test:3:7: error: I:1.0/32: bit number 32 is out of range 0-15\n  set I:1/32 = 1\n      ^\n"},
        Golden{"OutputBitBeyondFifteen", "program lamp.slc\ntest \"t\"\n  expect O:2/16 == 0\n",
               "t.test:3:10: error: O:2.0/16: bit number 16 is out of range 0-15\n  expect O:2/16 == 0\n         ^\n"},
        Golden{"ValueDoesNotFit", "program lamp.slc\ntest \"t\"\n  set N7:0 = 0x1FFFF\n",
               "t.test:3:14: error: '0x1FFFF' does not fit a 16-bit word\n  set N7:0 = 0x1FFFF\n             ^\n"},
        Golden{"BitValue", "program lamp.slc\ntest \"t\"\n  expect LAMP == 2\n",
               "t.test:3:18: error: a bit is 0 or 1, not '2'\n  expect LAMP == 2\n                 ^\n"},
        Golden{"FloatIntoInteger", "program lamp.slc\ntest \"t\"\n  set N7:0 = 1.5\n",
               "t.test:3:14: error: '1.5' is not an integer; this operand holds integers\n  set N7:0 = 1.5\n     "
               "        ^\n"},
        Golden{"PatternWithOrdering", "program lamp.slc\ntest \"t\"\n  expect N7:0 < 0b1x\n",
               "t.test:3:17: error: a bit pattern with x digits can only be compared with == or !=\n  expect "
               "N7:0 < 0b1x\n                ^\n"},
        Golden{"ForceOnlyIoBits", "program lamp.slc\ntest \"t\"\n  force LATCH = 1\n",
               "t.test:3:9: error: only I: and O: bits can be forced, as on the SLC ('LATCH (B3:0/1)' is not "
               "one)\n  force LATCH = 1\n        ^\n"},
        Golden{"RangeCount", "program lamp.slc\ntest \"t\"\n  expect N11:0..3 == 1 2 3\n",
               "t.test:3:10: error: N11:0..3 has 4 element(s) but 3 value(s) follow\n  expect N11:0..3 == 1 2 "
               "3\n         ^\n"},
        Golden{"RangeOfTimers", "program lamp.slc\ntest \"t\"\n  expect T4:0..1 == 1 2\n",
               "t.test:3:10: error: a range names whole words of an N, B, F, L, S or A file; name T, C and R "
               "sub-elements and I/O words one by one\n  expect T4:0..1 == 1 2\n         ^\n"},
        Golden{"EmptyRange", "program lamp.slc\ntest \"t\"\n  expect N7:0 in 20..10\n",
               "t.test:3:18: error: empty range: 20..10\n  expect N7:0 in 20..10\n                 ^\n"},
        Golden{"RowOutsideTable", "program lamp.slc\ntest \"t\"\n  row 1 2\n  scan 1\n",
               "t.test:3:3: error: 'row' belongs to a table-driven test (test \"name\" with COLUMN...)\n  row 1 "
               "2\n  ^\n"},
        Golden{"RowWidth", "program lamp.slc\ntest \"t\" with A B\n  row 1 2 3\n  scan $A\n",
               "t.test:3:11: error: this row has 3 value(s) but the table has 2 column(s) (A B)\n  row 1 2 3\n  "
               "        ^\n"},
        Golden{"UnknownColumn", "program lamp.slc\ntest \"t\" with A\n  row 1\n  scan $B\n",
               "t.test:4:8: error: unknown column '$B' (the table has: A)\n  scan $B\n       ^\n"},
        Golden{"ReferenceOutsideTable", "program lamp.slc\ntest \"t\"\n  scan $N\n",
               "t.test:3:8: error: '$N' refers to a table column, but this line is not in a table-driven test "
               "(test \"name\" with N)\n  scan $N\n       ^\n"},
        Golden{"BadRowValue", "program lamp.slc\ntest \"t\" with V\n  row 1\n  row x\n  set N7:0 = $V\n",
               "t.test:5:14: error: expected a value (5, -3, 0x00FF, 00FFh, 0b0000_1111, 1.5) after '=' (from $V "
               "= x in the row at line 4)\n  set N7:0 = $V\n             ^\n"},
        Golden{"RowValueDoesNotFit", "program lamp.slc\ntest \"t\" with V\n  row 1\n  row 99999\n  set N7:0 = $V\n",
               "t.test:5:14: error: '99999' does not fit a 16-bit word (-32768..32767)\n  set N7:0 = $V\n        "
               "     ^\n"},
        Golden{"TableWithoutRows", "program lamp.slc\ntest \"t\" with V\n  scan $V\n",
               "t.test:2:1: error: a table-driven test needs at least one 'row' line\ntest \"t\" with V\n^\n"},
        Golden{"SnapshotInTable", "program lamp.slc\ntest \"t\" with V\n  row 1\n  scan $V\n  snapshot s\n",
               "t.test:5:3: error: a table-driven test cannot take a snapshot (every row would define it); take "
               "it in a plain test\n  snapshot s\n  ^\n"},
        Golden{"DuplicateTest", "program lamp.slc\ntest \"t\"\n  scan 1\ntest \"t\"\n  scan 2\n",
               "t.test:4:1: error: a test named \"t\" is already defined at line 2\ntest \"t\"\n^\n"},
        Golden{"DuplicateSnapshot",
               "program lamp.slc\ntest \"a\"\n  snapshot s\ntest \"b\"\n  scan 1\n  snapshot s\n",
               "t.test:6:3: error: snapshot 's' is already defined at line 3\n  snapshot s\n  ^\n"},
        Golden{"RestoreUndefined", "program lamp.slc\ntest \"a\"\n  restore later\ntest \"b\"\n  snapshot later\n",
               "t.test:3:3: error: no snapshot 'later' is defined above this line (a 'snapshot later' step of an "
               "earlier test in this file)\n  restore later\n  ^\n"},
        Golden{"ProgramAfterSteps", "program lamp.slc\ntest \"t\"\n  scan 1\n  program other.slc\n",
               "t.test:4:3: error: a test's 'program' line must come before its first step\n  program "
               "other.slc\n  ^\n"},
        Golden{"NoProgram", "test \"t\"\n  scan 1\n",
               "t.test:1:1: error: no program for this test: add 'program FILE.slc' at the top of the file or in "
               "the test\ntest \"t\"\n^\n"},
        Golden{"MissingProgram", "program nowhere.slc\ntest \"t\"\n  scan 1\n",
               "nowhere.slc: error: cannot open file: No such file or directory\nt.test:1:9: error: program 'nowhere.slc' did "
               "not load (its errors are listed above)\nprogram nowhere.slc\n        ^\n"},
        Golden{"SecondFileProgram", "program lamp.slc\nprogram other.slc\ntest \"t\"\n  scan 1\n",
               "t.test:2:1: error: a second file-level 'program' line (the first is at line 1); name a test's "
               "own program inside the test\nprogram other.slc\n^\n"},
        Golden{"UnterminatedName", "program lamp.slc\ntest \"t\n  scan 1\n",
               "t.test:2:8: error: unterminated string: expected a closing '\"'\ntest \"t\n       ^\n"}),
    [](const ::testing::TestParamInfo<Golden>& info) { return std::string(info.param.name); });

TEST(Diagnostics, EveryIndependentErrorOfAFileIsReported) {
  Sandbox box;
  const std::string text =
      "program lamp.slc\n"         // 1
      "test \"t\"\n"               // 2
      "  set FOO = 1\n"            // 3  unknown symbol
      "  expect N7:0 ==\n"         // 4  syntax
      "  scan 1\n"                 // 5  fine
      "  expect N7:9 == 0\n"       // 6  not in the data table
      "  force N7:0 = 1\n"         // 7  not an I/O bit
      "test \"u\"\n"               // 8
      "  frobnicate\n"             // 9  syntax
      "  expect LAMP == 7\n";      // 10 bit value
  auto f = box.load(text);
  std::vector<std::uint32_t> lines;
  for (const auto& d : f.diagnostics.items()) lines.push_back(d.line);
  EXPECT_EQ(lines, (std::vector<std::uint32_t>{3, 4, 6, 7, 9, 10})) << f.render();
}

TEST(Diagnostics, ProgramErrorsAreShownWithTheProgramsOwnLines) {
  Sandbox box;
  box.write("broken.slc", "START 1747-L532\nLADDER 2\nSOR XIC B3:0/0 FOO B3:0/1 EOR\n");
  // The unknown instruction is the error; "rung has no output instruction", its consequence,
  // is not reported (issue 17).
  EXPECT_EQ(box.diagnostics("program broken.slc\ntest \"t\"\n  scan 1\n"),
            "broken.slc:3:16: error: unknown instruction 'FOO'\nSOR XIC B3:0/0 FOO B3:0/1 EOR\n               ^\n"
            "t.test:1:9: error: program 'broken.slc' did not load (its errors are listed above)\n"
            "program broken.slc\n        ^\n");
}

TEST(Diagnostics, ATestWithoutStepsIsAWarning) {
  Sandbox box;
  auto f = box.load("program lamp.slc\ntest \"empty\"\n");
  EXPECT_TRUE(f.ok());
  EXPECT_EQ(f.render(), "t.test:2:1: warning: test \"empty\" has no steps\ntest \"empty\"\n^\n");
}

// A file of 40,000 copies of one `expect` line cost 640 MB and over 10 s of CPU under ASan
// (tools/mutate.py, issue 17): test files hold at most kMaxStepsPerTestFile steps, table rows
// expanded; past it one error names the line and the rest of the file is not read.
TEST(Limits, ATestFileHoldsAtMostTenThousandSteps) {
  auto steps = [](std::size_t n) {
    std::string text = "program lamp.slc\ntest \"t\"\n";
    for (std::size_t i = 0; i < n; ++i) text += "  scan 1\n";
    return text;
  };
  auto at_limit = parse_test_text(steps(kMaxStepsPerTestFile), "t.test");
  EXPECT_FALSE(at_limit.diagnostics.has_errors());
  ASSERT_EQ(at_limit.file.tests.size(), 1u);
  EXPECT_EQ(at_limit.file.tests[0].steps.size(), kMaxStepsPerTestFile);

  auto over = parse_test_text(steps(40000), "t.test");
  ASSERT_EQ(over.diagnostics.items().size(), 1u);
  EXPECT_EQ(over.diagnostics.items()[0].line, kMaxStepsPerTestFile + 3);  // two header lines
  EXPECT_EQ(over.diagnostics.items()[0].message, "more than 10000 steps in one test file; split it into several files");

  // 101 rows of a 100-step body: each row alone is small, together 10,100 steps.
  std::string table = "program lamp.slc\ntest \"t $N\" with N\n";
  for (int r = 0; r <= 100; ++r) table += "  row " + std::to_string(r) + "\n";
  for (int i = 0; i < 100; ++i) table += "  set N7:0 = $N\n";
  auto rows = parse_test_text(table, "t.test");
  ASSERT_EQ(rows.diagnostics.items().size(), 1u);
  EXPECT_EQ(rows.diagnostics.items()[0].line, 2u);
  EXPECT_EQ(rows.diagnostics.items()[0].message,
            "this table-driven test expands to 10100 steps (101 rows of 100), more than 10000 in one test file");
  EXPECT_TRUE(rows.file.tests.empty());
}

}  // namespace
}  // namespace softslc::testing
