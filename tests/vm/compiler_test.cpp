// The compiler: data-table layout, initial data, golden bytecode listings, compile errors.
//
// Expected word indices follow the layout rule documented in vm/data_table.h and
// docs/bytecode.md: O0 then I1 (slot order), then S2 (164 words on a 5/03), then B3, T4, C5, R6,
// N7, F8 and the user files in number order, each at least one element. With the test header
// (slot 1: 1 input word, slot 2: 1 output word): O:2.0 = w0, I:1.0 = w1, S:0 = w2, B3:0 = w166,
// T4:0 = w167, C5:0 = w170, R6:0 = w173, N7:0 = w176, F8:0 = w177 (when N7 has one element).
#include <gtest/gtest.h>

#include "vm/compiler.h"
#include "vm_test_util.h"

namespace softslc::test {
namespace {

CompiledProgram compiled(std::string_view body, std::string_view header = kHeader) {
  LoadResult lr = load_program(program_text(body, header), "golden.slc");
  if (!lr.ok()) throw std::runtime_error(lr.render_diagnostics());
  CompileResult cr = compile(*lr.program);
  if (!cr.ok()) throw std::runtime_error(cr.render());
  return std::move(*cr.program);
}

// Compile errors of the compiler itself, bypassing the checker (a Program built by hand must
// not be able to produce bad bytecode either).
std::string compile_errors(std::string_view body, std::string_view header = kHeader) {
  LoadResult lr = parse_program_syntax(program_text(body, header), "bad.slc");
  if (!lr.ok()) return "syntax: " + lr.render_diagnostics();
  return compile(*lr.program).render();
}

TEST(Layout, DefaultFilesAndIoImages) {
  CompiledProgram p = compiled("SOR XIC I:1/0 OTE O:2/0 EOR");
  const DataTableLayout& L = *p.layout;
  EXPECT_EQ(L.files[0].base, 0u);
  EXPECT_EQ(L.files[0].elements, 1u);
  EXPECT_EQ(L.files[1].base, 1u);
  EXPECT_EQ(L.files[2].base, 2u);
  EXPECT_EQ(L.files[2].elements, 164u) << "5/03 status file S:0-S:163";
  for (int f = 3; f <= 8; ++f) {
    EXPECT_TRUE(L.files[static_cast<std::size_t>(f)].present) << f;
    EXPECT_EQ(L.files[static_cast<std::size_t>(f)].elements, 1u) << f;
  }
  EXPECT_EQ(L.files[4].words_per_element, 3);
  EXPECT_EQ(L.files[8].words_per_element, 2);
  EXPECT_EQ(L.files[3].base, 166u);
  EXPECT_EQ(L.files[8].base, 177u);
  EXPECT_FALSE(L.files[9].present);
  EXPECT_EQ(L.total_words, 179u);
}

TEST(Layout, NoF8OnA502) {
  CompiledProgram p = compiled("SOR XIC B3:0/0 OTE B3:0/1 EOR", "START 1747-L524\n");
  EXPECT_FALSE(p.layout->files[8].present) << "F files need a 5/03 OS301 or later (RM E-3)";
  EXPECT_EQ(p.layout->files[2].elements, 36u) << "a 5/02 has S:0-S:32; the VM keeps at least S:0-S:35";
}

TEST(Layout, FilesSizedFromDataAndHighestAddress) {
  CompiledProgram p = compiled(
      "SOR MOV N10:25 N11:0 EOR\n"
      "SOR COP #N7:0 #N12:3 10 EOR\n"
      "SOR XIC B3/62 OTE B9:1/0 EOR\n"
      "SOR MOV #N13:4 N14:[N11:0] EOR\n"
      "DATA N11:0\n% N11:0 % 1 2 3 4 5");
  const auto& f = p.layout->files;
  EXPECT_EQ(f[10].elements, 26u);
  EXPECT_EQ(f[11].elements, 5u) << "DATA gives 5 elements";
  EXPECT_EQ(f[12].elements, 13u) << "COP into N12:3 for 10 elements";
  EXPECT_EQ(f[7].elements, 10u) << "COP from N7:0 for 10 words";
  EXPECT_EQ(f[3].elements, 4u) << "B3/62 is B3:3/14";
  EXPECT_EQ(f[9].type, FileType::Bit);
  EXPECT_EQ(f[13].elements, 5u) << "an indexed address sizes by its base only (RM E-11)";
  EXPECT_EQ(f[14].elements, 1u) << "an indirect element does not grow the file";
}

TEST(Layout, IoImagesInSlotOrder) {
  CompiledProgram p = compiled("SOR XIC I:3.1/2 OTE O:1/0 EOR",
                               "START 1747-L532\nSLOT 3 1746-IB32 SCAN_IN 2 SCAN_OUT 0\n"
                               "SLOT 1 1746-IO4 SCAN_IN 1 SCAN_OUT 1\n");
  const auto& L = *p.layout;
  EXPECT_EQ(L.input_slots[1].first, 0u);
  EXPECT_EQ(L.input_slots[3].first, 1u);
  EXPECT_EQ(L.input_slots[3].words, 2u);
  EXPECT_EQ(L.files[1].elements, 3u);
  auto loc = L.locate(*parse_address("I:3.1/2"));
  ASSERT_TRUE(loc);
  EXPECT_EQ(loc->word, L.files[1].base + 2);
  EXPECT_EQ(L.describe(loc->word, 2), "I:3.1/2");
}

// file_containing answers from a word -> file index the compiler builds; a layout without the
// index scans the files. Both must name the same file (or none) for every word, including the
// words past the table and, on the MicroLogix controllers, the function files after the data files.
TEST(Layout, FileIndexAgreesWithTheScanForEveryWord) {
  const std::pair<std::string_view, std::string_view> programs[] = {
      {kHeader, "SOR MOV N10:25 N11:0 EOR\nSOR XIC B9:1/0 OTE B3/62 EOR\nSOR SWP #ST12:1.[N7:0] 5 EOR\n"
                "SOR TON T15:2 1.0 10 0 EOR\nDATA ST12:0\n% ST12:0 % \"\"\n% ST12:1 % \"x\"\n"},
      {"START Bul.1763\n", "SOR MOV N10:25 N11:0 EOR\nSOR XIC B9:1/0 OTE B3/62 EOR\nSOR MOV F8:3 L12:1 EOR\n"
                            "SOR TON T15:2 0.001 10 0 EOR\n"},
      // The 1400's function files RTC, HSC (six), PTOX, STI; the 1500's RTC, HSC (two), STI, PTO.
      {"START Bul.1766\n", "SOR MOV N10:25 N11:0 EOR\nSOR MOV F8:3 L12:1 EOR\n"},
      {"START Bul.1764\n", "SOR MOV N10:25 N11:0 EOR\nSOR MOV F8:3 L12:1 EOR\n"}};
  for (const auto& [header, body] : programs) {
    CompiledProgram p = compiled(body, header);
    const DataTableLayout& indexed = *p.layout;
    DataTableLayout scanned;  // the same files, never indexed
    scanned.files = indexed.files;
    scanned.total_words = indexed.total_words;
    int files_seen = 0, last = -2;
    for (std::uint32_t w = 0; w < indexed.total_words + 3; ++w) {
      const int f = indexed.file_containing(w);
      ASSERT_EQ(f, scanned.file_containing(w)) << "word " << w;
      if (w < indexed.total_words) {
        ASSERT_GE(f, 0) << "word " << w << " lies in no file";
        const FileLayout& fl = indexed.files[static_cast<std::size_t>(f)];
        ASSERT_TRUE(w >= fl.base && w < fl.end()) << "word " << w << " is not inside file " << f;
      } else {
        ASSERT_EQ(f, -1) << "word " << w << " is past the table";
      }
      if (f != last) ++files_seen, last = f;
    }
    EXPECT_GE(files_seen, 13) << header;
  }
}

TEST(Layout, InitialDataAndStructuredViews) {
  Plc plc(
      "SOR XIC B3:0/0 OTE B3:0/1 EOR\n"
      "DATA T4:0\n0XE000 100 42 % T4:0 %\n"
      "DATA F8:0\n% F8:0 % 0.01666667 2.5\n"
      "DATA R6:0\n0X0000 12 3 % R6:0 %");
  EXPECT_TRUE(plc.b("T4:0/EN"));
  EXPECT_TRUE(plc.b("T4:0/TT"));
  EXPECT_TRUE(plc.b("T4:0/DN"));
  EXPECT_EQ(plc.i("T4:0.PRE"), 100);
  EXPECT_EQ(plc.i("T4:0.ACC"), 42);
  EXPECT_EQ(plc.i("T4:0.1"), 100) << "PT1 4-9: T4:0.1 is .PRE";
  EXPECT_NEAR(plc.f("F8:0"), 0.01666667, 1e-8);
  EXPECT_EQ(plc.f("F8:1"), 2.5);
  EXPECT_EQ(plc.i("R6:0.LEN"), 12);
  EXPECT_EQ(plc.i("R6:0.POS"), 3);
  EXPECT_EQ(plc.i("S:3") >> 8, 10) << "default watchdog 10 x 10 ms (PT1 27-13)";
}

TEST(Golden, BranchRung) {
  CompiledProgram p = compiled("SOR XIC I:1/0 BST XIC O:2/0 NXB XIO I:1/1 BND OTE O:2/0 EOR");
  EXPECT_EQ(disassemble_rung(p, 2, 0),
            "  0000  SOR\n"
            "  0001  XIC  w1/0  ; bit=I:1.0/0\n"
            "  0003  BST\n"
            "  0004    XIC  w0/0  ; bit=O:2.0/0\n"
            "  0006  NXB\n"
            "  0007    XIO  w1/1  ; bit=I:1.0/1\n"
            "  0009  BND\n"
            "  0010  OTE  w0/0  ; bit=O:2.0/0\n");
}

TEST(Golden, NestedBranchWithOutputsInLegs) {
  CompiledProgram p = compiled("SOR XIC B3:0/0 BST OTE B3:0/1 NXB BST XIC B3:0/2 NXB XIC B3:0/3 BND OTE B3:0/4 BND EOR");
  EXPECT_EQ(disassemble_rung(p, 2, 0),
            "  0000  SOR\n"
            "  0001  XIC  w166/0  ; bit=B3:0/0\n"
            "  0003  BST\n"
            "  0004    OTE  w166/1  ; bit=B3:0/1\n"
            "  0006  NXB\n"
            "  0007    BST\n"
            "  0008      XIC  w166/2  ; bit=B3:0/2\n"
            "  0010    NXB\n"
            "  0011      XIC  w166/3  ; bit=B3:0/3\n"
            "  0013    BND\n"
            "  0014    OTE  w166/4  ; bit=B3:0/4\n"
            "  0016  BND\n");
}

TEST(Golden, TimerAndMath) {
  CompiledProgram p = compiled("SOR XIC T4:0/DN BST TON T4:0 1.0 60 0 NXB ADD F8:0 1.5 N7:0 BND EOR");
  EXPECT_EQ(disassemble_rung(p, 2, 0),
            "  0000  SOR\n"
            "  0001  XIC  w167/13  ; bit=T4:0/DN\n"
            "  0003  BST\n"
            "  0004    TON  w167 #100 #60 #0  ; timer=T4:0, time base=1.0, preset=60, accum=0\n"
            "  0009  NXB\n"
            "  0010    ADD  f177 kf0 w176  ; source A=F8:0, source B=1.5, dest=N7:0, float\n"
            "  0014  BND\n");
}

TEST(Golden, JumpsCallsAndMcr) {
  CompiledProgram p = compiled(
      "SOR XIC B3:0/0 JMP 3 EOR\n"
      "SOR JSR 3 EOR\n"
      "SOR LBL 3 ADD N7:0 1 N7:0 EOR\n"
      "SOR XIC B3:0/1 MCR EOR\n"
      "SOR MCR EOR\n"
      "LADDER 3\n"
      "SOR RET EOR");
  EXPECT_EQ(disassemble_rung(p, 2, 0),
            "  0000  SOR\n"
            "  0001  XIC  w166/0  ; bit=B3:0/0\n"
            "  0003  JMP  #3 ->10  ; label=3, target=rung 2\n");
  EXPECT_EQ(disassemble_rung(p, 2, 1),
            "  0006  SOR\n"
            "  0007  JSR  #3 ->24  ; file=3, target=file 3\n");
  EXPECT_EQ(disassemble_rung(p, 2, 2),
            "  0010  SOR\n"
            "  0011  LBL  #3  ; label=3\n"
            "  0013  ADD  w176 #1 w176  ; source A=N7:0, source B=1, dest=N7:0\n");
  EXPECT_EQ(disassemble_rung(p, 2, 3),
            "  0017  SOR  ; MCR rung: not forced false in a zone\n"
            "  0018  XIC  w166/1  ; bit=B3:0/1\n"
            "  0020  MCR  ; opens a zone\n");
  EXPECT_EQ(disassemble_rung(p, 2, 4),
            "  0021  SOR  ; MCR rung: not forced false in a zone\n"
            "  0022  MCR  ; closes the zone\n");
  EXPECT_EQ(disassemble_rung(p, 3, 0),
            "  0024  SOR\n"
            "  0025  RET\n");
}

TEST(Golden, DynamicOperands) {
  CompiledProgram p = compiled("SOR MOV #N7:1 N7:[N10:0] EOR");
  EXPECT_EQ(disassemble_rung(p, 2, 0),
            "  0000  SOR\n"
            "  0001  MOV  d0 d1  ; source=#N7:1, dest=N7:[N10:0]\n");
  EXPECT_EQ(p.dyn[1].ptr_element, static_cast<std::int32_t>(p.layout->files[10].base));
}

// A COP whose source and destination are direct is resolved by the compiler: flag B and the
// word count in aux (vm/bytecode.h). 2 T elements are 6 words (RM E-11 counts destination
// elements); the source N10 spans 6 elements. Run-time operands keep the resolving path.
TEST(Golden, DirectCopIsPreResolved) {
  CompiledProgram p = compiled(
      "SOR COP #N10:0 #T4:1 2 EOR\n"
      "SOR COP #N[N9:0]:0 #T4:1 2 EOR");
  const std::uint32_t direct = p.code[p.files[0].rungs[0].offset + 1];
  ASSERT_EQ(bc::op_of(direct), Op::COP);
  EXPECT_TRUE(bc::flags_of(direct) & bc::kFlagB);
  EXPECT_FALSE(bc::flags_of(direct) & bc::kFlagDyn);
  EXPECT_EQ(bc::aux_of(direct), 6u);
  const std::uint32_t indirect = p.code[p.files[0].rungs[1].offset + 1];
  ASSERT_EQ(bc::op_of(indirect), Op::COP);
  EXPECT_FALSE(bc::flags_of(indirect) & bc::kFlagB);
  EXPECT_EQ(bc::aux_of(indirect), 0u);
}

TEST(Golden, WholeListingHasAMapAndEveryFile) {
  CompiledProgram p = compiled("SOR JSR 3 EOR\nLADDER 3\nSOR RET EOR");
  const std::string listing = disassemble(p);
  EXPECT_NE(listing.find(";   N7   w176"), std::string::npos) << listing;
  EXPECT_NE(listing.find("file 2: 1 rung(s)"), std::string::npos);
  EXPECT_NE(listing.find("file 3: 1 rung(s)"), std::string::npos);
  EXPECT_NE(listing.find("EOF"), std::string::npos);
}

TEST(CompileErrors, CompilerChecksWhatItDependsOn) {
  EXPECT_NE(compile_errors("SOR XIC B3:0/0 JMP 9 EOR").find("label 9"), std::string::npos);
  EXPECT_NE(compile_errors("SOR JSR 12 EOR").find("program file 12"), std::string::npos);
  EXPECT_NE(compile_errors("SOR OTE B9:0/0 EOR\nSOR MOV N9:0 N7:0 EOR").find("already B9"), std::string::npos);
  EXPECT_NE(compile_errors("SOR MOV F8:0 N7:0 EOR", "START 1747-L524\n").find("F files do not exist"),
            std::string::npos);
  EXPECT_NE(compile_errors("SOR AND F8:0 1 N7:0 EOR").find("integer words"), std::string::npos);
  EXPECT_NE(compile_errors("SOR XIC I:4/0 OTE B3:0/0 EOR").find("slot 4"), std::string::npos);
  EXPECT_NE(compile_errors("SOR XIC B3:0/0 RET EOR").find("RET"), std::string::npos);
  EXPECT_NE(compile_errors("SOR BTW N7:0 M0:1.100 #N10:0 0 0 0 10 EOR").find("1747-SN/1747-SDN"), std::string::npos);
}

TEST(CompileErrors, ModuleInstructionHookDecides) {
  LoadResult lr = parse_program_syntax(program_text("SOR DEM 1 N20:0 70 EOR"), "dem.slc");
  ASSERT_TRUE(lr.ok());
  CompileOptions opts;
  int asked = 0;
  opts.module_instruction = [&](const Instruction& in) -> std::optional<std::string> {
    ++asked;
    return "DEM: no scanner in slot " + std::to_string(in.operands[0].integer);
  };
  CompileResult r = compile(*lr.program, opts);
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(asked, 1);
  EXPECT_NE(r.render().find("no scanner in slot 1"), std::string::npos);
}

}  // namespace
}  // namespace softslc::test
