// Golden diagnostics: each semantic and syntax error the issue lists, rendered exactly as
// `softslc check` prints it (gcc style: file:line:col: severity: message, source line, caret).
#include <gtest/gtest.h>

#include "parser/loader.h"

namespace softslc {
namespace {

const std::string kHeader =
    "START 1747-L532\n"                                 // line 1
    "SLOT 1 1746-IB16 SCAN_IN 1 SCAN_OUT 0\n"           // line 2
    "SLOT 2 1746-OB16 SCAN_IN 0 SCAN_OUT 1\n"           // line 3
    "SLOT 3 1747-SN SCAN_IN 32 SCAN_OUT 32 G_FILE 3\n"  // line 4
    " 0 0 0\n"                                          // line 5
    "LADDER 2\n";                                       // line 6; rungs start on line 7

struct Golden {
  const char* name;
  const char* rungs;     // text after the header
  const char* expected;  // the full rendered diagnostics
};
// How ctest and gtest name this case (else "GetParam() = 32-byte object <54-29 ...>").
void PrintTo(const Golden& c, std::ostream* os) { *os << c.name; }

class GoldenDiagnostics : public ::testing::TestWithParam<Golden> {};

TEST_P(GoldenDiagnostics, RenderExactly) {
  const auto& g = GetParam();
  auto r = load_program(kHeader + g.rungs, "t.slc");
  EXPECT_EQ(r.render_diagnostics(), g.expected);
}

INSTANTIATE_TEST_SUITE_P(
    Check, GoldenDiagnostics,
    ::testing::Values(
        Golden{"UnknownMnemonic", "SOR FOO I:1/0 OTE O:2/0 EOR\n",
               "t.slc:7:5: error: unknown instruction 'FOO'\nSOR FOO I:1/0 OTE O:2/0 EOR\n    ^\n"},
        Golden{"UnknownMnemonicAfterOperands", "SOR XIC I:1/0 FOO OTE O:2/0 EOR\n",
               "t.slc:7:15: error: unknown instruction 'FOO'\nSOR XIC I:1/0 FOO OTE O:2/0 EOR\n              ^\n"},
        Golden{"WrongOperandCount", "SOR TON T4:0 1.0 10 EOR\n",
               "t.slc:7:5: error: TON takes 4 operands (timer, time base, preset, accum), found 3\n"
               "SOR TON T4:0 1.0 10 EOR\n    ^\n"},
        Golden{"WrongOperandKind", "SOR XIC N7:0 OTE O:2/0 EOR\n",
               "t.slc:7:9: error: XIC bit: expected a bit address (for example B3:0/1 or T4:0/DN), found 'N7:0'\n"
               "SOR XIC N7:0 OTE O:2/0 EOR\n        ^\n"},
        Golden{"ConstantAsDestination", "SOR MOV N7:0 5 EOR\n",
               "t.slc:7:14: error: MOV dest: expected a destination word address, found '5'\n"
               "SOR MOV N7:0 5 EOR\n             ^\n"},
        Golden{"LiteralOutOfRange", "SOR TON T4:0 1.0 40000 0 EOR\n",
               "t.slc:7:18: error: TON preset 40000 is out of range 0-32767\nSOR TON T4:0 1.0 40000 0 EOR\n"
               "                 ^\n"},
        Golden{"BitNumberAbove15", "SOR XIC B3:0/16 OTE O:2/0 EOR\n",
               "t.slc:7:9: error: bit number 16 is out of range 0-15\nSOR XIC B3:0/16 OTE O:2/0 EOR\n        ^\n"},
        Golden{"ElementBeyondFile", "SOR MOV 1 N7:256 EOR\n",
               "t.slc:7:11: error: element 256 is beyond the largest file size (elements 0-255)\n"
               "SOR MOV 1 N7:256 EOR\n          ^\n"},
        Golden{"WordBeyondSlotImage", "SOR XIC I:1.1/0 OTE O:2/0 EOR\n",
               "t.slc:7:9: error: input word 1 is beyond slot 1's 1-word input image (1746-IB16)\n"
               "SOR XIC I:1.1/0 OTE O:2/0 EOR\n        ^\n"},
        Golden{"SlotWithNoModule", "SOR XIC I:5/0 OTE O:2/0 EOR\n",
               "t.slc:7:9: error: slot 5 has no module (no SLOT 5 line)\nSOR XIC I:5/0 OTE O:2/0 EOR\n        ^\n"},
        Golden{"MFileOnModuleWithout", "SOR XIC M1:1.0/0 OTE O:2/0 EOR\n",
               "t.slc:7:9: error: the module in slot 1 (1746-IB16) has no M1 file\nSOR XIC M1:1.0/0 OTE O:2/0 EOR\n"
               "        ^\n"},
        Golden{"MFileWordBeyondSize", "SOR XIC M1:3.3300/0 OTE O:2/0 EOR\n",
               "t.slc:7:9: error: M1 word 3300 is beyond the 3300-word M1 file of slot 3 (1747-SN)\n"
               "SOR XIC M1:3.3300/0 OTE O:2/0 EOR\n        ^\n"},
        Golden{"MFileInOsr", "SOR XIC I:1/0 OSR M0:3.0/0 OTE O:2/0 EOR\n",
               "t.slc:7:19: error: M0/M1 addresses are not allowed here (1747-SN manual p. B-2: not in OSR, nor in "
               "the file parameter of BSL, BSR, SQO, SQC, SQL, LFL, LFU, FFL, FFU)\n"
               "SOR XIC I:1/0 OSR M0:3.0/0 OTE O:2/0 EOR\n                  ^\n"},
        Golden{"MFileInBslFile", "SOR BSL #M0:3.0 R6:0 B3:0/0 16 EOR\n",
               "t.slc:7:9: error: M0/M1 addresses are not allowed here (1747-SN manual p. B-2: not in OSR, nor in "
               "the file parameter of BSL, BSR, SQO, SQC, SQL, LFL, LFU, FFL, FFU)\n"
               "SOR BSL #M0:3.0 R6:0 B3:0/0 16 EOR\n        ^\n"},
        Golden{"MissingBnd", "SOR BST XIC I:1/0 OTE O:2/0 EOR\n",
               "t.slc:7:29: error: unbalanced branch: expected NXB or BND to continue or close the BST\n"
               "SOR BST XIC I:1/0 OTE O:2/0 EOR\n                            ^\n"},
        Golden{"StrayBnd", "SOR XIC I:1/0 BND OTE O:2/0 EOR\n",
               "t.slc:7:15: error: unbalanced branch: BND without a matching BST\nSOR XIC I:1/0 BND OTE O:2/0 EOR\n"
               "              ^\n"},
        Golden{"MissingEor", "SOR XIC I:1/0 OTE O:2/0\nSOR XIC I:1/1 OTE O:2/1 EOR\n",
               "t.slc:7:24: error: expected an instruction mnemonic, a branch (BST, NXB, BND) or EOR\n"
               "SOR XIC I:1/0 OTE O:2/0\n                       ^\n"},
        Golden{"InputAfterOutput", "SOR OTE O:2/0 XIC I:1/0 OTE O:2/1 EOR\n",
               "t.slc:7:15: error: input instruction XIC after an output instruction (line 7, column 5); the SLC "
               "places conditions before outputs — use a branch\nSOR OTE O:2/0 XIC I:1/0 OTE O:2/1 EOR\n"
               "              ^\n"},
        Golden{"RungWithoutOutput", "SOR XIC I:1/0 EOR\n",
               "t.slc:7:1: error: rung has no output instruction\nSOR XIC I:1/0 EOR\n^\n"},
        Golden{"OutputBranchLegWithoutOutput", "SOR BST OTE O:2/0 NXB XIC I:1/0 BND EOR\n",
               "t.slc:7:1: error: rung must end with an output instruction\n"
               "SOR BST OTE O:2/0 NXB XIC I:1/0 BND EOR\n^\n"
               "t.slc:7:5: error: leg 2 of this output branch does not end in an output instruction\n"
               "SOR BST OTE O:2/0 NXB XIC I:1/0 BND EOR\n    ^\n"},
        Golden{"LabelNotFirst", "SOR XIC I:1/0 LBL 5 OTE O:2/0 EOR\n",
               "t.slc:7:15: error: LBL must be the first instruction of its rung\n"
               "SOR XIC I:1/0 LBL 5 OTE O:2/0 EOR\n              ^\n"},
        Golden{"JumpToUndefinedLabel", "SOR XIC I:1/0 JMP 7 EOR\n",
               "t.slc:7:19: error: JMP to label 7, which is not defined in program file 2\n"
               "SOR XIC I:1/0 JMP 7 EOR\n                  ^\n"},
        Golden{"JsrToMissingFile", "SOR JSR 9 EOR\n",
               "t.slc:7:9: error: JSR to program file 9, which is not defined (no LADDER 9)\nSOR JSR 9 EOR\n        ^\n"},
        Golden{"DuplicateOsrStorageBit",
               "SOR XIC I:1/0 OSR B3:0/0 OTE O:2/0 EOR\nSOR XIC I:1/1 OSR B3:0/0 OTE O:2/1 EOR\n",
               "t.slc:8:19: warning: OSR storage bit B3:0/0 is also used by the OSR at line 7; each OSR needs its "
               "own bit\nSOR XIC I:1/1 OSR B3:0/0 OTE O:2/1 EOR\n                  ^\n"},
        Golden{"FileNumberUsedAsTwoTypes", "SOR MOV N10:0 N7:0 EOR\nSOR XIC B10:0/0 OTE O:2/0 EOR\n",
               "t.slc:8:9: error: file 10 is used as B10 here but as N10 at line 7\n"
               "SOR XIC B10:0/0 OTE O:2/0 EOR\n        ^\n"},
        Golden{"UnknownSymbol", "SOR XIC START_PB OTE O:2/0 EOR\n",
               "t.slc:7:9: error: unknown symbol 'START_PB' (XIC bit)\nSOR XIC START_PB OTE O:2/0 EOR\n        ^\n"},
        Golden{"BufferNotAtX00", "SOR BTR N10:0 M1:3.150 #N11:0 0 1 0 8 EOR\n",
               "t.slc:7:15: error: BTR buffer file: expected M1:e.x00 with buffer x = 1-32 (1747-SN manual p. 5-6), "
               "found 'M1:3.150'\nSOR BTR N10:0 M1:3.150 #N11:0 0 1 0 8 EOR\n              ^\n"}),
    [](const ::testing::TestParamInfo<Golden>& info) { return std::string(info.param.name); });

TEST(Diagnostics, ProcessorWithoutBlockTransfers) {
  auto r = load_program(
      "START 1747-L524\nSLOT 3 1747-SN SCAN_IN 32 SCAN_OUT 32\nLADDER 2\nSOR BTR N10:0 M1:3.100 #N11:0 0 1 0 8 EOR\n",
      "t.slc");
  EXPECT_EQ(r.render_diagnostics(),
            "t.slc:4:5: error: BTR needs SLC 5/03 OS302, SLC 5/04 OS401 or SLC 5/05 OS501 (Series C) or later "
            "(1747-SN manual p. 5-5); this program's processor is SLC 5/02 (1747-L524 Series C FRN 11)\n"
            "SOR BTR N10:0 M1:3.100 #N11:0 0 1 0 8 EOR\n    ^\n");
}

TEST(Diagnostics, AllIndependentErrorsAreReported) {
  auto r = load_program(kHeader + "SOR XIC I:1/0 BND OTE O:2/0 EOR\nSOR FOO EOR\nSLOT x\nSOR XIC B3:0/16 OTE O:2/0 EOR\n",
                        "t.slc");
  EXPECT_FALSE(r.ok());
  // Syntax errors on lines 7, 8 and 9 are all reported. The broken SLOT is a declaration, and
  // the bit 16 on line 10 is not checked against declarations that failed to parse.
  ASSERT_EQ(r.diagnostics.error_count(), 3u) << r.render_diagnostics();
  EXPECT_EQ(r.diagnostics.items()[0].line, 7u);
  EXPECT_EQ(r.diagnostics.items()[1].line, 8u);
  EXPECT_EQ(r.diagnostics.items()[2].line, 9u);
}

// Issue 17: semantic errors were hidden whenever any rung had a syntax error. The rungs that
// parse are checked in the same pass; a rung with a syntax error is skipped (an unknown mnemonic
// does not also make its rung "have no output instruction").
TEST(Diagnostics, SemanticErrorsAreReportedBesideSyntaxErrors) {
  auto r = load_program(kHeader +
                            "SOR XIC I:1/0 BND OTE O:2/0 EOR\n"   // 7: stray BND (syntax)
                            "SOR XIC B3:0/16 OTE O:2/0 EOR\n"     // 8: bit 16 (semantic)
                            "SOR FOO EOR\n"                       // 9: unknown mnemonic, and nothing else
                            "SOR XIC I:1/0 OTE O:2/0\n"           // 10: no EOR (syntax)
                            "SOR MOV N7:0 5 EOR\n"                // 11: constant as destination (semantic)
                            "SOR XIC I:5/0 OTE O:2/0 EOR\n",      // 12: slot 5 has no module (semantic)
                        "t.slc");
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(r.render_diagnostics(),
            "t.slc:7:15: error: unbalanced branch: BND without a matching BST\n"
            "SOR XIC I:1/0 BND OTE O:2/0 EOR\n              ^\n"
            "t.slc:8:9: error: bit number 16 is out of range 0-15\n"
            "SOR XIC B3:0/16 OTE O:2/0 EOR\n        ^\n"
            "t.slc:9:5: error: unknown instruction 'FOO'\n"
            "SOR FOO EOR\n    ^\n"
            "t.slc:10:24: error: expected an instruction mnemonic, a branch (BST, NXB, BND) or EOR\n"
            "SOR XIC I:1/0 OTE O:2/0\n                       ^\n"
            "t.slc:11:14: error: MOV dest: expected a destination word address, found '5'\n"
            "SOR MOV N7:0 5 EOR\n             ^\n"
            "t.slc:12:9: error: slot 5 has no module (no SLOT 5 line)\n"
            "SOR XIC I:5/0 OTE O:2/0 EOR\n        ^\n");
}

// A rung lost to a syntax error may hold a label: the JMP to it is not reported as undefined,
// while a JMP in a file that lost no rung still is.
TEST(Diagnostics, NothingThatFollowsFromASkippedRungIsReported) {
  auto r = load_program(kHeader +
                            "SOR LBL 5 XIC I:1/0 BND OTE O:2/0 EOR\n"  // 7: syntax error; holds label 5
                            "SOR XIC I:1/1 JMP 5 EOR\n"                // 8: fine once line 7 is fixed
                            "LADDER 3\n"
                            "SOR XIC I:1/1 JMP 6 EOR\n",               // 10: label 6 is nowhere
                        "t.slc");
  EXPECT_EQ(r.render_diagnostics(),
            "t.slc:7:21: error: unbalanced branch: BND without a matching BST\n"
            "SOR LBL 5 XIC I:1/0 BND OTE O:2/0 EOR\n                    ^\n"
            "t.slc:10:19: error: JMP to label 6, which is not defined in program file 3\n"
            "SOR XIC I:1/1 JMP 6 EOR\n                  ^\n");
}

// Many broken and many wrong rungs: both kinds reported, within the per-file cap, each once.
TEST(Diagnostics, SyntaxAndSemanticErrorsShareTheCaps) {
  std::string rungs;
  for (int i = 0; i < 300; ++i) rungs += "SOR XIC I:1/0 BND OTE O:2/0 EOR\nSOR XIC B3:0/16 OTE O:2/0 EOR\n";
  auto r = load_program(kHeader + rungs, "t.slc");
  EXPECT_EQ(r.diagnostics.error_count(), 600u);
  const std::string out = r.render_diagnostics();
  std::size_t shown = 0;
  for (std::size_t at = out.find(": error: "); at != std::string::npos; at = out.find(": error: ", at + 1)) ++shown;
  EXPECT_EQ(shown, 100u);
  EXPECT_NE(out.find("t.slc:8:9: error: bit number 16 is out of range 0-15"), std::string::npos);
  EXPECT_NE(out.find("t.slc: note: 500 more diagnostic(s) not shown"), std::string::npos) << out.substr(out.size() - 300);
}

// Issue 17: a rung without EOR is reported on that rung, just after its last instruction — not
// after the comment lines that RSLogix writes above the next rung, and not at the end of the file.
TEST(Diagnostics, MissingEorIsReportedOnItsRung) {
  auto r = load_program(kHeader +
                            "SOR XIC I:1/0 OTE O:2/0\n"       // 7: no EOR
                            "% Rung: 1 %\n"
                            "% Start the pump %\n"
                            "SOR XIC I:1/1 OTE O:2/1 EOR\n"
                            "SOR XIC I:1/2\n"                 // 11: no EOR, its rung continued
                            "    OTE O:2/2\n"                 // 12
                            "% a comment spanning\n"
                            "  two lines %\n"
                            "\n"
                            "SOR XIC I:1/3 OTE O:2/3\n"       // 16: no EOR, last rung of the file
                            "% trailing comment %\n",
                        "t.slc");
  EXPECT_EQ(r.render_diagnostics(),
            "t.slc:7:24: error: expected an instruction mnemonic, a branch (BST, NXB, BND) or EOR\n"
            "SOR XIC I:1/0 OTE O:2/0\n                       ^\n"
            "t.slc:12:14: error: expected an instruction mnemonic, a branch (BST, NXB, BND) or EOR\n"
            "    OTE O:2/2\n             ^\n"
            "t.slc:16:24: error: expected an instruction mnemonic, a branch (BST, NXB, BND) or EOR\n"
            "SOR XIC I:1/3 OTE O:2/3\n                       ^\n");
}

TEST(Diagnostics, UnreadableFile) {
  auto r = load_program_file("/nonexistent/x.slc");
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(r.render_diagnostics(), "/nonexistent/x.slc: error: cannot open file: No such file or directory\n");
}

TEST(Diagnostics, MissingStart) {
  auto r = load_program("LADDER 2\nSOR XIC B3:0/0 OTE B3:0/1 EOR\n", "t.slc");
  EXPECT_EQ(r.render_diagnostics(),
            "t.slc:1:1: error: missing START statement naming the processor (for example 'START 1747-L532')\n"
            "LADDER 2\n^\n");
}

TEST(Diagnostics, UnterminatedComment) {
  auto r = load_program("START 1747-L532 % unterminated\nLADDER 2\n", "t.slc");
  EXPECT_FALSE(r.ok());
  EXPECT_NE(r.render_diagnostics().find("unterminated comment"), std::string::npos) << r.render_diagnostics();
}

}  // namespace
}  // namespace softslc
