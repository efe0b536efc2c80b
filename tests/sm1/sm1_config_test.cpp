// The 1203-SM1's SLOT line (mode, image, M files, G file, DIP switch options) and its bench
// node, as `softslc check` and the module loader see them. Rules from the 1203-SM1 user manual
// (../shared/seeds/001_0b60ddd8c475c2fb.txt), chapters 1-4.
#include <gtest/gtest.h>

#include "modules/module_setup.h"
#include "sm1_test_util.h"

namespace softslc::test {
namespace {

// All configuration messages of a program's SLOT lines, joined.
std::string check(const std::string& program_text) {
  LoadResult lr = load_program(program_text, "test.slc");
  if (!lr.ok()) return "LOAD: " + lr.render_diagnostics();
  DiagnosticList d;
  check_module_configuration(*lr.program, d);
  std::string out;
  for (const auto& i : d.items()) out += (i.severity == Severity::Error ? "error: " : "warning: ") + i.message + "\n";
  return out;
}

std::string bench_errors(const std::string& bench_text, const std::string& slot = kEnhanced) {
  LoadResult lr = load_program(sm1_program(slot), "test.slc");
  EXPECT_TRUE(lr.ok());
  ModuleSetup s = load_module_setup_text(*lr.program, bench_text, "test.bench");
  std::string out;
  for (const auto& i : s.bench_diagnostics.items()) out += std::to_string(i.line) + ":" + std::to_string(i.column) + ": " + i.message + "\n";
  return out;
}

TEST(Sm1Config, BothModesOfTheManualAreAccepted) {
  EXPECT_EQ(check(sm1_program(kEnhanced)), "");
  EXPECT_EQ(check(sm1_program(kBasic)), "");
  // Enhanced is the catalog's default ID code; G files of 2..32 words.
  EXPECT_EQ(check(sm1_program("SCAN_IN 32 SCAN_OUT 32 G_FILE 2\n 0 1")), "");
  std::string g32 = "SCAN_IN 32 SCAN_OUT 32 G_FILE 32\n";
  for (int k = 0; k < 32; ++k) g32 += " 0";
  EXPECT_EQ(check(sm1_program(g32)), "");
}

TEST(Sm1Config, BasicModeIsSelectedByIdCodeAndFoundWithoutTheCatalog) {
  // RSLogix "Other" with ID code 3516 (chapter 3) or 13616 (chapter 4).
  LoadResult lr = load_program(
      "START 1747-L532\nSLOT 0 1747-L532 SCAN_IN 0 SCAN_OUT 0\nSLOT 1 OTHER SCAN_IN 8 SCAN_OUT 8 ID_CODE 3516\n"
      "SLOT 2 OTHER SCAN_IN 32 SCAN_OUT 32 ID_CODE 13616\nPROJECT \"X\"\nLADDER 2 MAIN\nSOR XIC B3:0/0 OTE B3:0/1 EOR \n",
      "test.slc");
  ASSERT_TRUE(lr.ok()) << lr.render_diagnostics();
  const auto registry = builtin_module_registry();
  const auto* basic = registry.find(lr.program->slots[1]);
  const auto* enhanced = registry.find(lr.program->slots[2]);
  ASSERT_NE(basic, nullptr);
  ASSERT_NE(enhanced, nullptr);
  EXPECT_NE(basic->name.find("1203-SM1"), std::string::npos);
  EXPECT_NE(enhanced->name.find("1203-SM1"), std::string::npos);
}

TEST(Sm1Config, EnhancedModeNeedsAnSlc502OrLater) {
  // Chapter 1 table: fixed controllers and the SLC 5/01 support basic mode only.
  EXPECT_NE(check(sm1_program(kEnhanced, "SOR XIC B3:0/15 OTE B3:0/14 EOR \n", "1747-L514")).find("enhanced mode (ID code 13616) needs an SLC 5/02"),
            std::string::npos);
  EXPECT_EQ(check(sm1_program(kBasic, "SOR XIC B3:0/15 OTE B3:0/14 EOR \n", "1747-L514")), "");
  EXPECT_EQ(check(sm1_program(kEnhanced, "SOR XIC B3:0/15 OTE B3:0/14 EOR \n", "1747-L524")), "");
}

TEST(Sm1Config, ImageSizesFollowTheMode) {
  EXPECT_NE(check(sm1_program("SCAN_IN 32 SCAN_OUT 32 ID_CODE 3516")).find("basic mode has 8 input and 8 output words"),
            std::string::npos);
  EXPECT_NE(check(sm1_program("SCAN_IN 8 SCAN_OUT 8 ID_CODE 13616")).find("enhanced mode has 32 input and 32 output words"),
            std::string::npos);
  EXPECT_NE(check(sm1_program("SCAN_IN 32 SCAN_OUT 32 ID_CODE 1234")).find("ID code 1234 is neither"), std::string::npos);
}

TEST(Sm1Config, GFileAndMFileLimits) {
  EXPECT_NE(check(sm1_program("SCAN_IN 32 SCAN_OUT 32 G_FILE 1\n 0")).find("between 2 and 32 words"), std::string::npos);
  EXPECT_NE(check(sm1_program("SCAN_IN 32 SCAN_OUT 32 M0_SIZE 801")).find("maximum M0 file size is 800"), std::string::npos);
  EXPECT_NE(check(sm1_program("SCAN_IN 32 SCAN_OUT 32 M1_SIZE 401")).find("maximum M1 file size is 400"), std::string::npos);
  EXPECT_NE(check(sm1_program(kBasic + " G_FILE 2\n 0 1")).find("basic mode has no G file"), std::string::npos);
  EXPECT_NE(check(sm1_program(kBasic + " M0_SIZE 100")).find("basic mode has no M0/M1 files"), std::string::npos);
  EXPECT_NE(check(sm1_program("SCAN_IN 32 SCAN_OUT 32 G_FILE 2\n 0 61441")).find("warning: "), std::string::npos);
}

TEST(Sm1Config, DipSwitchOptions) {
  EXPECT_EQ(check(sm1_program(kEnhanced + " OPTION ch1=fault OPTION ch2=zero OPTION ch3=safe")), "");
  EXPECT_NE(check(sm1_program(kEnhanced + " OPTION ch4=zero")).find("unknown OPTION ch4"), std::string::npos);
  EXPECT_NE(check(sm1_program(kEnhanced + " OPTION ch1=off")).find("expected fault, zero, hold or safe"), std::string::npos);
}

TEST(Sm1Config, DipSwitchWordInM1) {
  // M1:e.000 holds the DIP switches (Figure 4.10); our encoding: channel c's two switches in
  // bits 2(c-1) and 2(c-1)+1, fault = both off (the default).
  Sm1Config c;
  EXPECT_EQ(c.dip_switch_word(), 0);
  c.fault_state = {Sm1FaultState::ZeroData, Sm1FaultState::HoldLastState, Sm1FaultState::SafeState};
  EXPECT_EQ(c.dip_switch_word(), 0b11'10'01);
}

TEST(Sm1Bench, ErrorsArePositioned) {
  EXPECT_EQ(bench_errors(kOneDrive), "");
  EXPECT_NE(bench_errors("scanport SM1 slot=1 {\n  drive D channel=4\n}\n").find("2:"), std::string::npos);
  EXPECT_NE(bench_errors("scanport SM1 slot=1 {\n  drive D\n}\n").find("channel"), std::string::npos);
  EXPECT_NE(bench_errors("scanport SM1 slot=1 {\n  drive D channel=1 model=9999\n}\n").find("no such built-in drive (known: 1305)"),
            std::string::npos);
  EXPECT_NE(bench_errors("scanport SM1 slot=1 {\n  drive D channel=1\n  drive E channel=1\n}\n").find("3:19: drive E: channel 1 already has drive D"),
            std::string::npos);
  EXPECT_NE(bench_errors("scanport SM1 slot=1 {\n  drive D channel=1 parameters=111:999\n}\n").find("is outside 0..216"),
            std::string::npos);
  EXPECT_NE(bench_errors("scanport SM1 slot=1 {\n  drive D channel=1 parameters=111\n}\n").find("PARAMETER:VALUE"),
            std::string::npos);
  EXPECT_NE(bench_errors("scanport SM1 slot=1 {\n  drive D channel=1 parameters=999:1\n}\n").find("parameter 999 does not exist"),
            std::string::npos);
  EXPECT_NE(bench_errors("scanport SM1 slot=1 {\n  adapter A\n}\n").find("'drive' nodes"), std::string::npos);
  EXPECT_NE(bench_errors("scanport SM1 slot=1 {\n  drive D channel=1 file=no_such_drive.json\n}\n").find("2:26: drive D: no_such_drive.json: cannot open the file"),
            std::string::npos);
  EXPECT_NE(bench_errors("scanport SM1 slot=1 {\n  drive D channel=1 file=x.json model=1305\n}\n").find("give model= or file=, not both"),
            std::string::npos);
  EXPECT_NE(bench_errors("scanport SM1 slot=1 {\n  drive D channel=1 speed=3\n}\n").find("speed"), std::string::npos);
}

TEST(Sm1Bench, DriveDescriptionsFromJsonFilesBesideTheBench) {
  // examples/ladder/1203-sm1/pad6.bench names pad6_drive.json in its own directory.
  LoadResult lr = load_program(sm1_example("appb_messaging.slc"), "appb_messaging.slc");
  ASSERT_TRUE(lr.ok());
  ModuleSetup s = load_module_setup(*lr.program, std::filesystem::path(SOFTSLC_SOURCE_DIR) / "examples/ladder/1203-sm1/pad6.bench");
  EXPECT_TRUE(s.ok()) << s.render("appb_messaging.slc", lr.source);
  // A broken description is reported at the attribute, with the JSON loader's message.
  LoadResult lr2 = load_program(sm1_program(kEnhanced), "t.slc");
  ModuleSetup bad = load_module_setup_text(*lr2.program, "scanport S slot=1 {\n  drive D channel=1 file=" +
                                                             std::string(SOFTSLC_SOURCE_DIR) + "/README.md\n}\n", "t.bench");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.bench_diagnostics.items().at(0).message.find("syntax error"), std::string::npos)
      << bad.bench_diagnostics.items().at(0).message;
}

}  // namespace
}  // namespace softslc::test
