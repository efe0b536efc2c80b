// What `check` says about instruction names without a row: real SLC 500 / MicroLogix mnemonics
// are "not supported by softslc yet", BTD is "not an SLC 500 instruction" (docs/semantics.md
// "BTD"), anything else is unknown.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <string_view>

#include "instructions/instruction_table.h"
#include "parser/checker.h"
#include "parser/loader.h"

namespace softslc {
namespace {

TEST(InstructionNames, TheListOfRealMnemonicsAgreesWithTheTable) {
  // Every name the checker calls "real but not supported" has no row; the ones that got rows
  // (SWP, RHC, TDF, PID, SUS, IID, ...) are gone from it.
  for (std::string_view m : real_mnemonics_without_rows()) {
    EXPECT_EQ(find_instruction(m), nullptr) << m << " has a row: take it off the checker's list";
    EXPECT_NE(unknown_instruction_message(m).find("not supported by softslc yet"), std::string::npos) << m;
  }
  for (std::string_view m : {"SWP", "RHC", "TDF", "PID", "SUS", "REF", "STD", "STE", "STS", "INT", "IID", "IIE",
                             "RPI", "DDV", "SQR", "SCP", "TOD", "FRD", "ENC", "DCD", "CPT", "FBC", "DDT",
                             "ABL", "ACB", "ACI", "ACL", "ACN", "AEX", "AHL", "AIC", "ARD", "ARL", "ASC", "ASR",
                             "AWA", "AWT", "MSG", "SVC", "RPC", "DLG"}) {
    const auto list = real_mnemonics_without_rows();
    EXPECT_EQ(std::find(list.begin(), list.end(), m), list.end()) << m << " has a row and is still listed";
  }
}

TEST(InstructionNames, BtdIsNotAnSlc500Instruction) {
  EXPECT_NE(unknown_instruction_message("BTD").find("BTD is not an SLC 500 instruction"), std::string::npos);
  LoadResult r = load_program("START 1747-L552\nLADDER 2\nSOR BTD N7:0 0 N7:1 0 4 EOR\n", "btd.slc");
  EXPECT_FALSE(r.ok());
  EXPECT_NE(r.render_diagnostics().find("BTD is not an SLC 500 instruction"), std::string::npos)
      << r.render_diagnostics();
  EXPECT_NE(unknown_instruction_message("FOO").find("unknown instruction 'FOO'"), std::string::npos);
}

}  // namespace
}  // namespace softslc
