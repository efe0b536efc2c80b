// The SLC 5/05 instruction set of 1747-RM001G, held here independently of the instruction table,
// and checked against it: every mnemonic the manual gives the 5/05 has a table row whose
// Requirement admits an SLC 5/05 (so `softslc instructions` lists it and `check` accepts it).
//
// Source: 1747-RM001G-EN-P (November 2008), the instruction overview table at the start of each
// chapter and the instruction pages. Pages marked "[page]" were read (manualshelf.com /
// easymanua.ls pages of the manual, or the page cited by an earlier, reviewed commit); "[ch. N]"
// means the chapter is known but the page that lists the instruction was not reached in this
// session (docs/instructions.md says which). The 5/05 column of each instruction's availability row
// is what this list claims; instructions of the fixed controllers only (HSC) are listed apart.
#include <gtest/gtest.h>

#include <set>
#include <stdexcept>
#include <string>
#include <string_view>

#include "instructions/instruction_table.h"
#include "instructions/processor.h"

namespace softslc {
namespace {

struct ManualEntry {
  std::string_view mnemonic;
  std::string_view where;  // RM001G page or chapter
};

// The SLC 5/05's instructions in 1747-RM001G, chapter by chapter.
constexpr ManualEntry kSlc505Instructions[] = {
    // Chapter 2, Basic Instructions: bit (XIC/XIO p. 2-3), timer (p. 2-8 .. 2-11), counter (p. 2-14).
    {"XIC", "2-3"}, {"XIO", "2-3"}, {"OTE", "ch. 2"}, {"OTL", "ch. 2"}, {"OTU", "ch. 2"}, {"OSR", "ch. 2"},
    {"TON", "2-9"}, {"TOF", "2-10"}, {"RTO", "ch. 2"}, {"CTU", "2-14"}, {"CTD", "2-14"}, {"RES", "ch. 2"},
    // Chapter 3, Comparison Instructions, table 3.1 (p. 3-1).
    {"EQU", "3-2"}, {"NEQ", "3-2"}, {"LES", "3-3"}, {"LEQ", "3-3"}, {"GRT", "3-3"}, {"GEQ", "3-4"},
    {"MEQ", "3-4"}, {"LIM", "3-5"},
    // Chapter 4, Math Instructions (DIV/MUL p. 4-10, DDV 4-11, SQR 4-12, SCP 4-13, SWP 4-28).
    {"ADD", "ch. 4"}, {"SUB", "ch. 4"}, {"MUL", "4-10"}, {"DIV", "4-10"}, {"DDV", "4-11"}, {"CLR", "ch. 4"},
    {"SQR", "4-12"}, {"SCP", "4-13"}, {"SCL", "ch. 4"}, {"ABS", "ch. 4"}, {"CPT", "ch. 4"}, {"SWP", "4-28"},
    {"NEG", "ch. 4"}, {"ASN", "ch. 4"}, {"ACS", "ch. 4"}, {"ATN", "ch. 4"}, {"COS", "ch. 4"}, {"SIN", "ch. 4"},
    {"TAN", "ch. 4"}, {"LN", "ch. 4"}, {"LOG", "ch. 4"}, {"XPY", "ch. 4"}, {"DEG", "ch. 4"}, {"RAD", "ch. 4"},
    // Chapter 5, Data Handling Instructions (TOD 5-2, FRD 5-4, DCD 5-10, ENC 5-12), with the move,
    // logical, copy/fill and FIFO/LIFO instructions.
    {"TOD", "5-2"}, {"FRD", "5-4"}, {"DCD", "5-10"}, {"ENC", "5-12"}, {"COP", "ch. 5"}, {"FLL", "ch. 5"},
    {"MOV", "ch. 5"}, {"MVM", "ch. 5"}, {"AND", "ch. 5"}, {"OR", "ch. 5"}, {"XOR", "ch. 5"}, {"NOT", "ch. 5"},
    {"FFL", "ch. 5"}, {"FFU", "ch. 5"}, {"LFL", "ch. 5"}, {"LFU", "ch. 5"},
    // Chapter 6, Program Flow Control Instructions (JSR/SBR/RET p. 6-4).
    {"JMP", "ch. 6"}, {"LBL", "ch. 6"}, {"JSR", "6-4"}, {"SBR", "6-4"}, {"RET", "6-4"}, {"MCR", "ch. 6"},
    {"TND", "ch. 6"}, {"SUS", "ch. 6"}, {"IIM", "ch. 6"}, {"IOM", "ch. 6"}, {"REF", "ch. 6"},
    // Chapter 7, Application Specific Instructions (RHC 7-15, TDF 7-15 .. 7-17, FBC/DDT 7-18, RPC 7-23).
    {"BSL", "ch. 7"}, {"BSR", "ch. 7"}, {"SQO", "ch. 7"}, {"SQC", "ch. 7"}, {"SQL", "ch. 7"}, {"RHC", "7-15"},
    {"TDF", "7-15..7-17"}, {"FBC", "7-18"}, {"DDT", "7-18"}, {"RPC", "7-23"},
    // Block transfers through a 1747-SN (the manual's BTR/BTW operation, seeds 002; 1747-SN p. 5-5).
    {"BTR", "BTR/BTW section"}, {"BTW", "BTR/BTW section"},
    // Chapter 9, PID (p. 9-1).
    {"PID", "9-1"},
    // Chapter 11, Understanding Interrupt Routines: STI (STD/STE p. 11-14, STS 11-16), the I/O
    // event-driven interrupt (p. 11-27; IID and IIE on 11-33, the zone example; RPI and INT pages not reached).
    {"STD", "11-14"}, {"STE", "11-14"}, {"STS", "11-16"}, {"IID", "11-33"}, {"IIE", "11-33"}, {"RPI", "ch. 11"},
    {"INT", "ch. 11"},
    // Chapter 10, ASCII Instructions (ACI p. 10-8, AEX 10-12, AHL 10-13, AIC 10-14, ASC 10-18, ASR 10-19).
    {"ABL", "10-6"}, {"ACB", "10-7"}, {"ACI", "10-8"}, {"ACL", "ch. 10"}, {"ACN", "ch. 10"}, {"AEX", "10-12"},
    {"AHL", "10-13"}, {"AIC", "10-14"}, {"ARD", "ch. 10"}, {"ARL", "ch. 10"}, {"ASC", "10-18"}, {"ASR", "10-19"},
    {"AWA", "ch. 10"}, {"AWT", "ch. 10"},
    // Chapter 12, SLC Communication Instructions (MSG p. 12-5, SVC p. 12-41; the "chapter 13"
    // is chapter 12 in 1747-RM001G).
    {"MSG", "12-5"}, {"SVC", "12-41"},
};

// Whether some form of `mnemonic` in the table is available on `p`.
bool has_row_for(std::string_view mnemonic, const ProcessorModel& p) {
  for (const auto& s : kInstructionTable)
    if (s.mnemonic == mnemonic && p.supports(s.requires_)) return true;
  return false;
}

ProcessorModel slc505() {
  auto p = resolve_processor("1747-L552");
  if (!p) throw std::runtime_error("the SLC 5/05 catalog 1747-L552 is not known");
  return *p;
}

TEST(InstructionList, EverySlc505InstructionOfTheManualHasARowAdmittingThe505) {
  const ProcessorModel p = slc505();
  for (const auto& e : kSlc505Instructions) {
    EXPECT_NE(find_instruction(e.mnemonic), nullptr) << e.mnemonic << " (RM001G " << e.where << ") has no table row";
    EXPECT_TRUE(has_row_for(e.mnemonic, p)) << e.mnemonic << " (RM001G " << e.where
                                            << ") is not admitted on the SLC 5/05";
  }
}

TEST(InstructionList, TheListHasNoDuplicates) {
  std::set<std::string_view> seen;
  for (const auto& e : kSlc505Instructions) EXPECT_TRUE(seen.insert(e.mnemonic).second) << e.mnemonic;
}

// The instructions of other processors or families that the SLC 5/05 does not have are refused on
// it: HSC (fixed controllers, RM001G ch. 2), UID/UIE/UIF (MicroLogix 1100-1500, 1763/1766-RM001),
// ONS, OSF and CPW (MicroLogix 1100-1500).
TEST(InstructionList, NotOnTheSlc505) {
  const ProcessorModel p = slc505();
  for (std::string_view m : {"UID", "UIE", "UIF", "ONS", "OSF", "CPW"}) {
    ASSERT_NE(find_instruction(m), nullptr) << m;
    EXPECT_FALSE(has_row_for(m, p)) << m;
  }
  EXPECT_EQ(find_instruction("BTD"), nullptr) << "BTD is not an SLC 500 instruction (docs/semantics.md)";
}

// Where the 5/01-5/04 differ (each instruction's availability row): FBC/DDT need the Series C
// operating system of the 5/03-5/05 (RM 7-18, A-9); IID/IIE/RPI the 5/02 and later (RM 11-27).
TEST(InstructionList, OlderProcessors) {
  auto l532 = resolve_processor("1747-L532");
  auto l524 = resolve_processor("1747-L524");
  auto l511 = resolve_processor("1747-L511");
  ASSERT_TRUE(l532 && l524 && l511);
  for (std::string_view m : {"FBC", "DDT"}) {
    EXPECT_TRUE(has_row_for(m, *l532)) << m;
    EXPECT_FALSE(has_row_for(m, *l524)) << m;
  }
  for (std::string_view m : {"IID", "IIE", "RPI"}) {
    EXPECT_TRUE(has_row_for(m, *l524)) << m;
    EXPECT_FALSE(has_row_for(m, *l511)) << m;
  }
}

}  // namespace
}  // namespace softslc
