// The program grammar: statements, rungs and branch nesting, every DATA and FORCE block kind,
// SLOT keys, symbols; and the grammar's own soundness (PEGTL analyze).
#include <gtest/gtest.h>

#include <tao/pegtl/contrib/analyze.hpp>

#include "parser/grammar.h"
#include "parser/loader.h"

namespace softslc {
namespace {

Program load_ok(const std::string& text) {
  auto r = load_program(text, "test.slc");
  EXPECT_TRUE(r.ok()) << r.render_diagnostics();
  return r.program ? *r.program : Program{};
}

const std::string kHeader =
    "START 1747-L532\n"
    "SLOT 1 1746-IB16 SCAN_IN 1 SCAN_OUT 0\n"
    "SLOT 2 1746-OB16 SCAN_IN 0 SCAN_OUT 1\n";

TEST(Grammar, HasNoLeftRecursionOrInfiniteLoops) {
  EXPECT_EQ(tao::pegtl::analyze<grammar::statement>(), 0u);
  EXPECT_EQ(tao::pegtl::analyze<grammar::address_only>(), 0u);
}

TEST(Program, StartLineWithSeriesAndFrn) {
  auto p = load_ok("START 1747-L524 SERIES B % SLC 5/02 %\nLADDER 2\nSOR XIC B3:0/0 OTE B3:0/1 EOR\n");
  EXPECT_EQ(p.processor.family, ProcessorFamily::Slc502);
  EXPECT_EQ(p.processor.series, 'B');
  EXPECT_EQ(p.processor.timing_key(), "5/02B");
  EXPECT_EQ(p.processor_description, "SLC 5/02");
  auto q = load_ok("START 1747-L552 FRN 9\nLADDER 2\nSOR XIC B3:0/0 OTE B3:0/1 EOR\n");
  EXPECT_EQ(q.processor.frn, 9);
  EXPECT_FALSE(q.processor.supports(Requirement::DeviceNetMessage));
}

TEST(Program, NestedBranchesWithOutputsInLegs) {
  auto p = load_ok(kHeader +
                   "LADDER 2\n"
                   "SOR XIC I:1/0 BST XIC I:1/1 BST XIC I:1/2 NXB XIO I:1/3 BST XIC I:1/4 NXB XIC I:1/5 BND BND "
                   "OTE O:2/0 NXB OTL O:2/1 NXB XIC I:1/6 OTU O:2/2 BND EOR\n");
  ASSERT_EQ(p.files.size(), 1u);
  const auto& rung = p.files[0].rungs.at(0);
  ASSERT_EQ(rung.elements.size(), 2u);
  const auto& outer = rung.elements[1];
  ASSERT_EQ(outer.kind, RungElement::Kind::Branch);
  ASSERT_EQ(outer.legs.size(), 3u);
  // Leg 1: XIC, nested branch (2 legs, the second holding a third level), OTE.
  ASSERT_EQ(outer.legs[0].size(), 3u);
  const auto& nested = outer.legs[0][1];
  ASSERT_EQ(nested.kind, RungElement::Kind::Branch);
  ASSERT_EQ(nested.legs.size(), 2u);
  ASSERT_EQ(nested.legs[1].size(), 2u);
  EXPECT_EQ(nested.legs[1][1].kind, RungElement::Kind::Branch);
  EXPECT_EQ(nested.legs[1][1].legs.size(), 2u);
  EXPECT_EQ(outer.legs[0][2].instruction.opcode, Opcode::OTE);
  EXPECT_EQ(outer.legs[1][0].instruction.opcode, Opcode::OTL);
  EXPECT_EQ(outer.legs[2][1].instruction.opcode, Opcode::OTU);
}

// A program tree copies deeply (operand lists and branch legs are held out of line, see
// parser/program.h): a change to the copy leaves the original as loaded.
TEST(Program, CopyOfTheTreeIsIndependent) {
  const auto p = load_ok(kHeader + "LADDER 2\nSOR XIC I:1/0 BST MOV 5 N7:[N10:0] NXB OTE O:2/0 BND EOR\n");
  Program q = p;
  auto& br = q.files[0].rungs[0].elements[1];
  ASSERT_EQ(br.kind, RungElement::Kind::Branch);
  ASSERT_EQ(br.legs.size(), 2u);
  auto& mov = br.legs[0][0].instruction;
  ASSERT_EQ(mov.operands.size(), 2u);
  EXPECT_TRUE(mov.operands[1].address.is_indirect());
  mov.operands[0].integer = 6;
  br.legs[1].clear();
  std::string diff;
  EXPECT_FALSE(same_program(p, q, &diff));
  const auto& orig = p.files[0].rungs[0].elements[1];
  EXPECT_EQ(orig.legs[0][0].instruction.operands[0].integer, 5);
  EXPECT_EQ(orig.legs[1].size(), 1u);
  EXPECT_TRUE(p.files[0].rungs[0].elements[0].legs.empty());  // an instruction has no legs
  Program r = p;
  EXPECT_TRUE(same_program(p, r, &diff)) << diff;
}

// The sizes the load-time work brought the tree to on LP64 (docs/performance.md "Load time"):
// a regression here is a regression of the 1M-rung load.
TEST(Program, TreeNodesAreSmallOnLp64) {
  if constexpr (sizeof(void*) == 8) {
    EXPECT_LE(sizeof(Operand), 88u);
    EXPECT_LE(sizeof(Instruction), 24u);
    EXPECT_LE(sizeof(RungElement), 32u);
  }
}

TEST(Program, EmptyBranchLegIsAWire) {
  auto p = load_ok(kHeader + "LADDER 2\nSOR BST XIC I:1/0 NXB BND OTE O:2/0 EOR\n");
  const auto& br = p.files[0].rungs[0].elements[0];
  ASSERT_EQ(br.legs.size(), 2u);
  EXPECT_TRUE(br.legs[1].empty());
}

TEST(Program, RungCommentsAndRungMarkers) {
  auto p = load_ok(kHeader +
                   "LADDER 2\n% Rung: 0 %\n% Start the motor %\nSOR XIC I:1/0 OTE O:2/0 EOR\n"
                   "% Rung: 1 %\nSOR XIC I:1/1 OTE O:2/1 EOR\n");
  EXPECT_EQ(p.files[0].rungs[0].comment, "Start the motor");
  EXPECT_EQ(p.files[0].rungs[1].comment, "");
}

TEST(Program, RungMaySpanLines) {
  auto p = load_ok(kHeader + "LADDER 2\nSOR XIC I:1/0\n    XIO I:1/1\n    OTE O:2/0 EOR\n");
  EXPECT_EQ(p.files[0].rungs[0].elements.size(), 3u);
}

// Positions on the continuation lines of a rung, counted by hand: a byte (a tab too) is a column,
// and the line after '\n' starts at column 1. The loader computes positions on demand rather than
// tracking them while parsing (docs/performance.md "Load time"), so this checks the count.
TEST(Program, PositionsOnContinuationLinesOfARung) {
  // kHeader is lines 1-3, LADDER line 4, SOR line 5.
  auto p = load_ok(kHeader + "LADDER 2\nSOR XIC I:1/0\n    XIO I:1/1\n\tOTE O:2/0 EOR\nSOR XIC I:1/2 OTE O:2/2 EOR\n");
  const auto& e = p.files[0].rungs[0].elements;
  ASSERT_EQ(e.size(), 3u);
  EXPECT_EQ(e[0].instruction.operands[0].pos, (SourcePos{5, 9}));
  EXPECT_EQ(e[1].pos(), (SourcePos{6, 5}));
  EXPECT_EQ(e[1].instruction.operands[0].pos, (SourcePos{6, 9}));
  EXPECT_EQ(e[2].pos(), (SourcePos{7, 2}));
  EXPECT_EQ(e[2].instruction.operands[0].pos, (SourcePos{7, 6}));
  const auto& next = p.files[0].rungs[1];
  EXPECT_EQ(next.pos, (SourcePos{8, 1}));
  EXPECT_EQ(next.elements[1].instruction.operands[0].pos, (SourcePos{8, 19}));
}

TEST(Program, ErrorsOnContinuationLinesArePositioned) {
  // An action's error (unknown mnemonic, line 9 after a tab) and a syntax error raised inside the
  // address grammar (N without a file number: at the element, line 6 column 9).
  auto r = load_program(kHeader + "LADDER 2\nSOR XIC I:1/0\n  XIC N:0\n  OTE O:2/0 EOR\nSOR XIC I:1/0\n\tFOO I:1/1\n  OTE O:2/0 EOR\n",
                        "t.slc");
  ASSERT_FALSE(r.ok());
  const auto text = r.render_diagnostics();
  EXPECT_NE(text.find("t.slc:6:9: error: expected a file number after 'N'"), std::string::npos) << text;
  EXPECT_NE(text.find("t.slc:9:2: error: unknown instruction 'FOO'"), std::string::npos) << text;
}

// A token that only begins like a mnemonic or a rung keyword is an operand (a symbol); the whole
// token spelling one ends the instruction's operands.
TEST(Program, SymbolsThatBeginLikeAMnemonicOrKeyword) {
  auto p = load_ok(kHeader + "SYMBOL B3:0/1 XICX\nSYMBOL B3:0/2 EORX\nSYMBOL B3:0/3 BSTA\nSYMBOL B3:0/4 MOV_\n" +
                   "LADDER 2\nSOR XIC XICX XIO EORX BST XIC BSTA NXB XIC MOV_ BND OTE O:2/0 EOR\n");
  const auto& e = p.files[0].rungs[0].elements;
  ASSERT_EQ(e.size(), 4u);
  EXPECT_EQ(e[0].instruction.operands[0].spelling, "XICX");
  EXPECT_EQ(e[1].instruction.operands[0].spelling, "EORX");
  ASSERT_EQ(e[2].legs.size(), 2u);
  EXPECT_EQ(e[2].legs[0][0].instruction.operands[0].spelling, "BSTA");
  EXPECT_EQ(e[2].legs[1][0].instruction.operands[0].spelling, "MOV_");
  // OTE followed by the mnemonic XIC: OTE has no operand, and XIC starts the next instruction.
  auto r = load_program(kHeader + "LADDER 2\nSOR XIC I:1/0 OTE XIC I:1/1 EOR\n", "t.slc");
  EXPECT_NE(r.render_diagnostics().find("OTE takes 1 operand (bit), found 0"), std::string::npos) << r.render_diagnostics();
}

// An address operand keeps no spelling; text() is its canonical one (B3/17 is bit 1 of word 1,
// PT1 4-8 as in address_test; bit 13 of a timer's word 0 is DN), other operands' text is as written.
TEST(Program, AddressOperandTextIsTheCanonicalSpelling) {
  auto p = load_ok(kHeader + "LADDER 2\nSOR XIC B3/17 MOV 0x00FF N7:0 OTE T4:0/13 EOR\n");
  const auto& e = p.files[0].rungs[0].elements;
  EXPECT_TRUE(e[0].instruction.operands[0].spelling.empty());
  EXPECT_EQ(e[0].instruction.operands[0].text(), "B3:1/1");
  EXPECT_EQ(e[1].instruction.operands[0].text(), "0x00FF");
  EXPECT_EQ(e[2].instruction.operands[0].text(), "T4:0/DN");
}

// Each program file's rung vector is allocated once, at the count of SOR lines before the next
// LADDER (docs/performance.md "Load time").
TEST(Program, RungVectorIsReservedToTheFilesRungs) {
  auto p = load_ok(kHeader + "LADDER 2\nSOR JSR 3 EOR\nSOR XIC I:1/0 OTE O:2/0 EOR\nSOR XIC I:1/1 OTE O:2/1 EOR\n" +
                   "LADDER 3\nSOR SBR OTE B3:1/0 EOR\nSOR RET EOR\n");
  ASSERT_EQ(p.files.size(), 2u);
  EXPECT_EQ(p.files[0].rungs.size(), 3u);
  EXPECT_EQ(p.files[0].rungs.capacity(), 3u);
  EXPECT_EQ(p.files[1].rungs.capacity(), 2u);
}

TEST(Program, ProjectAndLadderNames) {
  auto p = load_ok(kHeader + "PROJECT \"CONVEYOR\"\nLADDER 2 MAIN\nSOR JSR 3 EOR\nLADDER 3 \"FILL\"\nSOR XIC I:1/0 OTE O:2/0 EOR\n");
  EXPECT_EQ(p.project, "CONVEYOR");
  EXPECT_EQ(p.files[0].name, "MAIN");
  EXPECT_EQ(p.files[1].name, "FILL");
}

TEST(Program, SlotLineWithGFileContinuationAndExtensions) {
  auto p = load_ok(
      "START 1747-L532\n"
      "SLOT 1 1747-SN % RIO Scanner % SCAN_IN 32 SCAN_OUT 32 G_FILE 3\n"
      "     0 256 8 IOCARD 1 2 3 M0_SIZE 3300 M1_SIZE 400 ID_CODE 13608 OPTION baud=115.2K\n"
      "LADDER 2\nSOR XIC M1:1.0/0 OTE B3:0/0 EOR\n");
  ASSERT_EQ(p.slots.size(), 1u);
  const auto& s = p.slots[0];
  EXPECT_EQ(s.catalog, "1747-SN");
  EXPECT_EQ(s.description, "RIO Scanner");
  EXPECT_EQ(s.scan_in, 32);
  EXPECT_EQ(s.g_file, (std::vector<std::uint16_t>{0, 256, 8}));
  EXPECT_EQ(s.iocard, (std::vector<std::int64_t>{1, 2, 3}));
  EXPECT_EQ(s.m0_size, 3300);
  EXPECT_EQ(s.m1_size, 400);
  EXPECT_EQ(s.id_code, 13608);
  EXPECT_EQ(s.options.at("baud"), "115.2K");
}

TEST(Program, PlainScannerExportLineLoadsWithDefaultMFileSizes) {
  // The example: a plain export line with its three G-file words.
  auto p = load_ok(
      "START 1747-L532\nSLOT 1 1747-SN % RIO Scanner % SCAN_IN 32 SCAN_OUT 32 G_FILE 3\n 0 0 0\n"
      "LADDER 2\nSOR XIC M1:1.3299/0 OTE M0:1.3299/15 EOR\n");
  EXPECT_EQ(p.slots[0].g_file.size(), 3u);
}

TEST(Program, OperandKindsLiteralsAndConstants) {
  auto p = load_ok(kHeader +
                   "LADDER 2\nSOR TON T4:0 0.01 100 0 EOR\nSOR MOV -5 N7:0 EOR\nSOR MVM N7:0 0x00FF N7:1 EOR\n"
                   "SOR MOV 1.5 F8:0 EOR\nSOR COP #N7:0 #N10:0 5 EOR\n");
  const auto& rungs = p.files[0].rungs;
  const auto& ton = rungs[0].elements[0].instruction;
  EXPECT_EQ(ton.operands[1].kind, Operand::Kind::Float);
  EXPECT_DOUBLE_EQ(ton.operands[1].real, 0.01);
  EXPECT_EQ(ton.operands[2].integer, 100);
  EXPECT_EQ(rungs[1].elements[0].instruction.operands[0].integer, -5);
  EXPECT_EQ(rungs[2].elements[0].instruction.operands[1].integer, 0xFF);
  EXPECT_TRUE(rungs[4].elements[0].instruction.operands[0].address.indexed);
}

TEST(Program, DataBlocksOfEveryKind) {
  auto p = load_ok(kHeader +
                   "LADDER 2\nSOR XIC B3:0/0 OTE B3:0/1 EOR\n"
                   "DATA O:2\n% O:2.0 % 0X00F0 \n"
                   "DATA I:1\n% I:1.0 % 0X0003 \n"
                   "DATA S:0\n% S:0 %      4   5414      0   2560 \n"
                   "DATA B3:0\n% B3:0 % 1 2 3\n"
                   "DATA T4:0\n% .CTL   .PRE   .ACC    %\n0XA200     60     60 % T4:0 %\n0X0000 10 0 % T4:1 %\n"
                   "DATA C5:0\n% .CTL   .PRE   .ACC    %\n0X0000      5     -2 % C5:0  %\n"
                   "DATA R6:0\n% .CTL   .LEN   .POS    %\n0X0000     16      3 % R6:0  %\n"
                   "DATA N7:0\n% N7:0 % 60 -1 32767 \n% N7:3 % 7\n"
                   "DATA F8:0\n% F8:0 % 0.01666667 2 -3.5e2\n"
                   "DATA ST9:0\n% ST9:0 % \"HELLO\"\n"
                   "DATA N10:0\n\n");
  ASSERT_EQ(p.data.size(), 11u);
  EXPECT_EQ(p.data[0].type, FileType::Output);
  EXPECT_EQ(p.data[0].start_element, 2);
  EXPECT_EQ(p.data[0].words, (std::vector<std::int64_t>{0xF0}));
  EXPECT_EQ(p.data[2].words, (std::vector<std::int64_t>{4, 5414, 0, 2560}));
  // 16-bit words load in their signed form: 0XA200 is -24064.
  EXPECT_EQ(p.data[4].words, (std::vector<std::int64_t>{static_cast<std::int16_t>(0xA200), 60, 60, 0, 10, 0}));
  EXPECT_EQ(p.data[5].words, (std::vector<std::int64_t>{0, 5, -2}));
  EXPECT_EQ(p.data[6].words, (std::vector<std::int64_t>{0, 16, 3}));
  EXPECT_EQ(p.data[7].words, (std::vector<std::int64_t>{60, -1, 32767, 7}));
  EXPECT_EQ(p.data[8].floats, (std::vector<double>{0.01666667, 2.0, -350.0}));
  EXPECT_EQ(p.data[9].strings, (std::vector<std::string>{"HELLO"}));
  EXPECT_TRUE(p.data[10].words.empty());
}

TEST(Program, LongAndAsciiDataBlocks) {
  auto p = load_ok("START Bul.1766\nLADDER 2\nSOR XIC B3:0/0 OTE B3:0/1 EOR\n"
                   "DATA L41:0\n% L41:0  %       14400     -70000 \n"
                   "DATA A9:0\n% A9:0 % 16706 17220\n");
  ASSERT_EQ(p.data.size(), 2u);
  EXPECT_EQ(p.data[0].type, FileType::Long);
  EXPECT_EQ(p.data[0].words, (std::vector<std::int64_t>{14400, -70000}));
  EXPECT_EQ(p.data[1].type, FileType::Ascii);
  EXPECT_EQ(p.data[1].words, (std::vector<std::int64_t>{16706, 17220}));
}

TEST(Program, FunctionFilesAreKeptOpaqueWithAWarning) {
  auto r = load_program("START Bul.1766\nLADDER 2\nSOR XIC B3:0/0 OTE B3:0/1 EOR\n"
                        "DATA BHI0:0 \n% BHI0:0  %\n     0      0 0X0002\n\nDATA PWMX0:0\n% PWMX0:0 %\n    -1 0X0000\n",
                        "ml.slc");
  ASSERT_TRUE(r.ok()) << r.render_diagnostics();
  EXPECT_EQ(r.diagnostics.warning_count(), 2u);
  ASSERT_EQ(r.program->data.size(), 2u);
  EXPECT_FALSE(r.program->data[0].type.has_value());
  EXPECT_EQ(r.program->data[0].file_name, "BHI0:0");
  EXPECT_EQ(r.program->data[0].opaque_text, "% BHI0:0  %\n     0      0 0X0002");
}

TEST(Program, ForceBlocks) {
  auto p = load_ok(kHeader +
                   "LADDER 2\nSOR XIC I:1/0 OTE O:2/0 EOR\n"
                   "FORCE O:02\n% ON     OFF  %\n0X0001 0XFFFE % FORCE O:2.0 %\n"
                   "FORCE I:01\n% ON     OFF  %\n0X0000 0XFFFF % FORCE I:1.0 %\n");
  ASSERT_EQ(p.forces.size(), 2u);
  EXPECT_EQ(p.forces[0].type, FileType::Output);
  EXPECT_EQ(p.forces[0].slot, 2);
  EXPECT_EQ(p.forces[0].words[0].on, 1);
  EXPECT_EQ(p.forces[0].words[0].off, 0xFFFE);
  EXPECT_EQ(p.forces[1].type, FileType::Input);
}

TEST(Program, SymbolsAndDescriptionsResolveInOperands) {
  auto p = load_ok(kHeader +
                   "LADDER 2\nSOR XIC START_PB OTE MOTOR EOR\n"
                   "SYMBOL I:1/0 START_PB % Start push button %\n"
                   "SYMBOL O:2/0 MOTOR\n"
                   "DESC N7:0 % Part count %\n");
  ASSERT_EQ(p.symbols.size(), 3u);
  EXPECT_EQ(p.symbols[0].description, "Start push button");
  EXPECT_TRUE(p.symbols[2].name.empty());
  const auto& xic = p.files[0].rungs[0].elements[0].instruction;
  EXPECT_TRUE(xic.operands[0].resolved);
  EXPECT_EQ(to_string(xic.operands[0].address), "I:1.0/0");
}

TEST(Program, TheFixtureLoads) {
  auto r = load_program_file(std::string(SOFTSLC_SHARED_DIR) + "/fixtures/rslogix500/59-BSGS.SLC");
  ASSERT_TRUE(r.ok()) << r.render_diagnostics();
  const auto& p = *r.program;
  EXPECT_EQ(p.processor.family, ProcessorFamily::MicroLogix);
  EXPECT_EQ(p.project, "BSGS");
  EXPECT_EQ(p.slots.size(), 5u);
  EXPECT_EQ(p.slots[0].g_file.size(), 17u);
  EXPECT_EQ(p.files.size(), 6u);
  EXPECT_EQ(p.files[0].rungs.size(), 5u);
  EXPECT_EQ(p.forces.size(), 6u);
  // Only the MicroLogix function files give warnings.
  for (const auto& d : r.diagnostics.items()) EXPECT_EQ(d.severity, Severity::Warning) << d.message;
}

}  // namespace
}  // namespace softslc
