// Issue 15: CPT, the compute instruction (SLC 5/03 OS302, 5/04 OS401, 5/05): the expression's
// text form, precedence, integer and floating-point evaluation, flags, and the check errors.
//
// Expected values are hand calculations written next to each assertion; the Celsius-to-Fahrenheit
// case is PT1 20-23's worked example (25 C -> 77 F) written as one expression, and `|` as the
// divide operator is RSLogix 500's (docs/program-format.md, "CPT"). Rounding of `|` follows DIV
// (RM 4-10: 11/2 -> 6), a decision documented in docs/semantics.md.
#include <gtest/gtest.h>

#include "parser/formatter.h"
#include "vm_test_util.h"

namespace softslc::test {
namespace {

constexpr int V = 2, Z = 4, S = 8;

TEST(Cpt, IntegerExpressionsAndPrecedence) {
  Plc plc(with_trap_sample("SOR CPT N7:0 (N7:1 + N7:2) * 3 EOR\n"
                           "SOR CPT N7:3 2 + 3 * 4 EOR\n"
                           "SOR CPT N7:4 N7:5 | 2 EOR\n"
                           "SOR CPT N7:6 N7:7 AND 0xFF OR 0x100 EOR\n"
                           "SOR CPT N7:8 NOT 0 EOR\n"
                           "SOR CPT N7:9 -(N7:1 - 10) EOR"));
  plc.set("N7:1", 2);
  plc.set("N7:2", 5);
  plc.set("N7:5", 11);
  plc.set("N7:7", 0x1234);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:0"), 21) << "(2 + 5) * 3";
  EXPECT_EQ(plc.i("N7:3"), 14) << "* binds tighter than +";
  EXPECT_EQ(plc.i("N7:4"), 6) << "11 | 2 = 5.5, rounded like DIV (RM 4-10)";
  EXPECT_EQ(plc.i("N7:6"), 0x134) << "AND binds tighter than OR: (1234h AND FFh) OR 100h";
  EXPECT_EQ(plc.i("N7:8"), -1);
  EXPECT_EQ(plc.i("N7:9"), 8) << "-(2 - 10)";
  EXPECT_EQ(arith_flags(plc), 0);
  EXPECT_FALSE(plc.b("B3:1/0"));
}

TEST(Cpt, FloatingPointExpressions) {
  // PT1 20-23: F = 1.8 C + 32; 25 C = 77 F. Hypotenuse 3-4-5. Power binds tighter than unary minus:
  // -2 ** 2 = -(2 ** 2) = -4.
  Plc plc(with_trap_sample("SOR CPT F8:0 (F8:1 * 1.8) + 32.0 EOR\n"
                           "SOR CPT F8:2 SQR(N7:0 ** 2 + N7:1 ** 2) EOR\n"
                           "SOR CPT N7:2 -2 ** 2 EOR\n"
                           "SOR CPT F8:3 SIN(RAD 30.0) EOR\n"
                           "SOR CPT N7:3 F8:1 | 2 EOR"));
  plc.setf("F8:1", 25.0);
  plc.set("N7:0", 3);
  plc.set("N7:1", 4);
  plc.run_scans(1);
  EXPECT_NEAR(plc.f("F8:0"), 77.0, 1e-4);
  EXPECT_NEAR(plc.f("F8:2"), 5.0, 1e-5);
  EXPECT_EQ(plc.i("N7:2"), -4);
  EXPECT_NEAR(plc.f("F8:3"), 0.5, 1e-6) << "sin 30 degrees";
  EXPECT_EQ(plc.i("N7:3"), 12) << "25.0 / 2 = 12.5 in float, rounded half to even into N7";
  EXPECT_FALSE(plc.b("B3:1/0"));
}

TEST(Cpt, OverflowAndDivideByZero) {
  Plc plc(with_trap_sample("SOR CPT N7:0 N7:1 * 1000 EOR\nSOR CPT N7:2 5 | N7:3 EOR"));
  plc.set("N7:1", 100);
  plc.set("N7:3", 0);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:0"), 32767) << "100000 does not fit: clamped (S:2/14 = 0)";
  EXPECT_EQ(plc.i("N7:2"), 32767) << "a zero divisor gives 32767, as DIV";
  EXPECT_EQ(arith_flags(plc) & V, V);
  EXPECT_TRUE(plc.b("B3:1/0"));
}

TEST(Cpt, ResultFlags) {
  Plc plc("SOR CPT N7:0 N7:1 - 5 EOR");
  plc.set("N7:1", 5);
  plc.run_scans(1);
  EXPECT_EQ(arith_flags(plc), Z);
  plc.set("N7:1", 4);
  plc->scan(1);
  EXPECT_EQ(arith_flags(plc), S);
}

TEST(Cpt, TheExpressionEndsAtABranchOrTheNextInstruction) {
  Plc plc("SOR XIC B3:0/0 BST CPT N7:0 N7:1 + 1 NXB OTE B3:0/1 BND EOR\nSOR CPT N7:2 N7:1 AND 3 OTE B3:0/2 EOR");
  plc.set("B3:0/0", 1);
  plc.set("N7:1", 6);
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:0"), 7);
  EXPECT_TRUE(plc.b("B3:0/1"));
  EXPECT_EQ(plc.i("N7:2"), 2) << "AND continues the expression; OTE ends it";
  EXPECT_TRUE(plc.b("B3:0/2"));
}

TEST(Cpt, FormatWritesTheExpressionBack) {
  LoadResult lr = load_program(program_text("SOR CPT N7:0 ( N7:1  +  N7:2 )   | 2 EOR"), "t.slc");
  ASSERT_TRUE(lr.ok()) << lr.render_diagnostics();
  const std::string text = format_program(*lr.program);
  EXPECT_NE(text.find("SOR CPT N7:0 ( N7:1 + N7:2 ) | 2 EOR"), std::string::npos) << text;
}

std::string diagnostics(std::string_view body, std::string_view header = kHeader) {
  LoadResult lr = load_program(program_text(body, header), "t.slc");
  return lr.ok() ? std::string() : lr.render_diagnostics();
}

TEST(Cpt, CheckErrorsArePositioned) {
  // The rung starts at column 1 of line 5 (after the 3-line header and LADDER 2).
  std::string e = diagnostics("SOR CPT N7:0 (N7:1 + ) EOR");
  EXPECT_NE(e.find("t.slc:5:22: error: CPT expression: expected an operand"), std::string::npos) << e;
  e = diagnostics("SOR CPT F8:0 N7:1 AND 3 EOR");
  EXPECT_NE(e.find("AND works on integer words, but this expression computes in floating point"), std::string::npos)
      << e;
  e = diagnostics("SOR CPT N7:0 N7:1 + B3:0/1 EOR");
  EXPECT_NE(e.find("B3:0/1 is a bit"), std::string::npos) << e;
  e = diagnostics("SOR CPT N7:0 (((((((((((((((((1))))))))))))))))) EOR");
  EXPECT_NE(e.find("parentheses nest deeper than 16 levels"), std::string::npos) << e;
  e = diagnostics("SOR CPT N7:0 " + std::string(300, '1') + " EOR");
  EXPECT_NE(e.find("longer than 255 characters"), std::string::npos) << e;
  e = diagnostics("SOR CPT N7:0 N7:1 ** EOR");
  EXPECT_NE(e.find("expected an operand"), std::string::npos) << e;
  e = diagnostics("SOR CPT N7:0 XYZ + 1 EOR");
  EXPECT_NE(e.find("'XYZ' is not an address or a constant"), std::string::npos) << e;
  e = diagnostics("SOR CPT N7:0 N7:1 + 1 EOR", "START 1747-L524\n");
  EXPECT_NE(e.find("CPT is not available on the SLC 5/02"), std::string::npos) << e;
  EXPECT_EQ(diagnostics("SOR CPT N7:0 N7:1 + 1 EOR"), "");
}

}  // namespace
}  // namespace softslc::test
