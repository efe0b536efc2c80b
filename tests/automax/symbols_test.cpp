// IODEF / RIODEF / MEMDEF in the program text: parsed, resolved to the master's M0 words,
// checked with positioned errors, and formatted back (docs/automax.md "Symbols").
#include <gtest/gtest.h>

#include "parser/formatter.h"
#include "parser/loader.h"

namespace softslc {
namespace {

const std::string kHeader =
    "START 1747-L532\n"
    "SLOT 8 57C416 % AutoMax RIO master %\n"
    "LADDER 2 MAIN\n";

LoadResult load(const std::string& defs, const std::string& rungs = "SOR XIC RIO_D02 OTE B3:0/0 EOR\n") {
  return load_program(kHeader + rungs + defs, "t.slc");
}

std::string errors_of(const std::string& defs, const std::string& rungs = "SOR XIC B3:0/1 OTE B3:0/0 EOR\n") {
  auto r = load(defs, rungs);
  EXPECT_FALSE(r.ok());
  return r.render_diagnostics();
}

// The configuration task of section 4.7.1.1 (the manual's `&` continuations are line breaks
// here), with the addresses the layout of parser/automax_def.h gives: drop 0 register r is M0
// word r; drop d slot s register r is word 512 d + 32 s + r.
TEST(AutomaxSymbols, ManualConfigurationTaskResolvesToMasterWords) {
  auto r = load(
      "IODEF RIO_D02@[SLOT=8,REGISTER=4,BIT=2]\n"
      "IODEF RIO_D04@[SLOT=8,REGISTER=4,BIT=4]\n"
      "RIODEF START@[MASTER_SLOT=8,DROP=2,SLOT=11,REGISTER=0,\n      BIT=5]\n"
      "RIODEF SPD_REF%[MASTER_SLOT=8,DROP=04,SLOT=0,REGISTER=0]\n"
      "RIODEF SPD_IND%[MASTER_SLOT=8,DROP=02,SLOT=0,REGISTER=3] % speed indicator %\n"
      "RIODEF ON@[MASTER_SLOT=8,DROP=C,SLOT=1,REGISTER=0,BIT=2]\n"
      "MEMDEF RIONET_OK@\n"
      "MEMDEF OTHER@\n"
      "MEMDEF COUNT%\n");
  ASSERT_TRUE(r.ok()) << r.render_diagnostics();
  auto addr = [&](const char* n) { return to_string(r.program->find_symbol(n)->address); };
  EXPECT_EQ(addr("RIO_D02"), "M0:8.4/2");
  EXPECT_EQ(addr("RIO_D04"), "M0:8.4/4");
  EXPECT_EQ(addr("START"), "M0:8.1376/5");  // 2*512 + 11*32 + 0
  EXPECT_EQ(addr("SPD_REF"), "M0:8.2048");  // 4*512
  EXPECT_EQ(addr("SPD_IND"), "M0:8.1027");  // 2*512 + 3
  EXPECT_EQ(addr("ON"), "M0:8.2080/2");     // drop C is image area 4: 4*512 + 32
  EXPECT_EQ(addr("RIONET_OK"), "B255:0/0");
  EXPECT_EQ(addr("OTHER"), "B255:0/1");
  EXPECT_EQ(addr("COUNT"), "N254:0");
  EXPECT_EQ(r.program->find_symbol("SPD_IND")->description, "speed indicator");
  // The rung's XIC RIO_D02 reads the master word.
  EXPECT_EQ(to_string(r.program->files[0].rungs[0].elements[0].instruction.operands[0].address), "M0:8.4/2");
}

TEST(AutomaxSymbols, FormatRoundTripKeepsTheDefinitionsAsWritten) {
  const std::string defs =
      "IODEF RIO_D02@[SLOT=8,REGISTER=4,BIT=2] % drop 2 on-line %\n"
      "RIODEF D02_CFG%[MASTER_SLOT=8,DROP=2,SLOT=0,REGISTER=0]\n"
      "RIODEF ON@[MASTER_SLOT=8,DROP=C,SLOT=1,REGISTER=0,BIT=2]\n"
      "MEMDEF RIONET_OK@\n";
  auto r = load(defs);
  ASSERT_TRUE(r.ok()) << r.render_diagnostics();
  const std::string text = format_program(*r.program);
  EXPECT_NE(text.find(defs), std::string::npos) << text;
  auto again = load_program(text, "fmt.slc");
  ASSERT_TRUE(again.ok()) << again.render_diagnostics();
  std::string diff;
  EXPECT_TRUE(same_program(*r.program, *again.program, &diff)) << diff;
  EXPECT_EQ(format_program(*again.program), text);
}

TEST(AutomaxSymbols, PositionedErrors) {
  EXPECT_EQ(errors_of("IODEF X@[SLOT=8,REGISTER=4,BIT=16]\n"),
            "t.slc:5:32: error: IODEF X@: BIT must be 0-15 (registers are 16 bits)\n"
            "IODEF X@[SLOT=8,REGISTER=4,BIT=16]\n                               ^\n");
  EXPECT_NE(errors_of("IODEF X@[SLOT=3,REGISTER=4,BIT=1]\n")
                .find("5:15: error: IODEF X@: slot 3 holds no AutoMax Remote I/O master (a SLOT 3 57C416 line)"),
            std::string::npos);
  EXPECT_NE(errors_of("RIODEF X%[MASTER_SLOT=8,DROP=8,SLOT=1,REGISTER=0]\n")
                .find("5:30: error: RIODEF X%: DROP must be 1-7, or 9-F for an all-digital Shark rack"),
            std::string::npos);
  EXPECT_NE(errors_of("RIODEF X%[MASTER_SLOT=8,DROP=2,SLOT=16,REGISTER=0]\n").find("5:37: error: RIODEF X%: SLOT must be 0-15"),
            std::string::npos);
  EXPECT_NE(errors_of("RIODEF X%[MASTER_SLOT=8,DROP=2,SLOT=1,REGISTER=32]\n")
                .find("5:48: error: RIODEF X%: REGISTER must be 0-31"),
            std::string::npos);
  EXPECT_NE(errors_of("RIODEF X@[MASTER_SLOT=8,DROP=2,SLOT=1,REGISTER=0]\n")
                .find("5:1: error: RIODEF X@: missing field BIT (a name ending in '@' is a bit)"),
            std::string::npos);
  EXPECT_NE(errors_of("RIODEF X%[MASTER_SLOT=8,DROP=2,SLOT=1,REGISTER=0,BIT=3]\n")
                .find("5:50: error: RIODEF X%: unknown field BIT (a RIODEF register takes MASTER_SLOT, DROP, SLOT, REGISTER)"),
            std::string::npos);
  EXPECT_NE(errors_of("IODEF X%[SLOT=8,REGISTER=99999]\n")
                .find("5:26: error: IODEF X%: REGISTER must be 0-511 (drop 0 registers, figure 4.1)"),
            std::string::npos);
  EXPECT_NE(errors_of("IODEF X%[SLOT=8,SLOT=8,REGISTER=1]\n").find("5:17: error: IODEF X%: field SLOT is given twice"),
            std::string::npos);
  EXPECT_NE(errors_of("IODEF X%[SLOT=8,REGISTER=4Q]\n").find("5:26: error: field REGISTER: '4Q' is not a number"),
            std::string::npos);
  // Syntax: the suffix, the brackets, the separators.
  EXPECT_NE(errors_of("IODEF X[SLOT=8,REGISTER=4]\n").find("5:8: error: expected '@' (a bit) or '%' (a register)"),
            std::string::npos);
  EXPECT_NE(errors_of("IODEF X@ SLOT=8\n").find("5:10: error: expected '[' and the point's fields"), std::string::npos);
  EXPECT_NE(errors_of("IODEF X@[SLOT=8 REGISTER=4,BIT=1]\n")
                .find("5:17: error: expected ',' and another field, or ']' to close the fields"),
            std::string::npos);
  // Drop 0 is read only: a program that writes an IODEF point is refused.
  EXPECT_NE(errors_of("IODEF RIO_D02@[SLOT=8,REGISTER=4,BIT=2]\n", "SOR XIC B3:0/1 OTE RIO_D02 EOR\n")
                .find("4:20: error: OTE bit: RIO_D02 is an IODEF point of drop 0, and drop 0 registers are read only"),
            std::string::npos);
  // MEMDEF bits live in B255: the program may not address that file directly.
  EXPECT_NE(errors_of("MEMDEF OK@\n", "SOR XIC B255:0/3 OTE B3:0/0 EOR\n")
                .find("4:9: error: XIC bit: B255 holds the program's MEMDEF variables; name them instead"),
            std::string::npos);
  EXPECT_TRUE(load("MEMDEF OK%\n", "SOR XIC B255:0/3 OTE B3:0/0 EOR\n").ok());  // no MEMDEF bits: B255 is free
  // A name defined twice, and a ladder name that no definition gives.
  EXPECT_NE(errors_of("MEMDEF A@\nMEMDEF A@\n").find("6:1: error: symbol 'A' is defined twice (first at line 5)"),
            std::string::npos);
  EXPECT_NE(errors_of("MEMDEF A@\n", "SOR XIC B@ OTE A EOR\n").find("error"), std::string::npos);
}

// A '%' ending a register name is not a comment: the statements after it still parse.
TEST(AutomaxSymbols, RegisterSuffixDoesNotOpenAComment) {
  auto r = load(
      "RIODEF SPD_REF%[MASTER_SLOT=8,DROP=4,SLOT=0,REGISTER=0]\n"
      "SYMBOL N7:0 SPEED % copy %\n"
      "IODEF RIO_D02@[SLOT=8,REGISTER=4,BIT=2]\n");
  ASSERT_TRUE(r.ok()) << r.render_diagnostics();
  ASSERT_NE(r.program->find_symbol("SPEED"), nullptr);
  EXPECT_EQ(r.program->find_symbol("SPEED")->description, "copy");
}

}  // namespace
}  // namespace softslc
