// Bad programs: each ends in the SLC's major fault with file and rung — never a host crash,
// hang or out-of-bounds access (these tests also run under ASan/UBSan).
//
// Sources: PT1 20-2 (S:5/0 at END -> 0020h), RM 16-7 (0022h watchdog; S:3 high byte default 10 =
// 100 ms), facts §3 [S] (0029h indirection, 002Ah index, 0034h negative timer), [S] ML1400 0030h
// nesting, PT1 27-17 (S:6 is not cleared by the processor), DF1 (S:1/13 major error halted).
#include <gtest/gtest.h>

#include "vm/discrete_io.h"
#include "vm_test_util.h"

namespace softslc::test {
namespace {

struct BadProgram {
  const char* name;
  const char* body;
  std::uint16_t code;
  int file;
  int rung;
};
// How ctest and gtest name this case (else "GetParam() = 32-byte object <54-29 ...>").
void PrintTo(const BadProgram& c, std::ostream* os) { *os << c.name; }

class BadPrograms : public ::testing::TestWithParam<BadProgram> {};

TEST_P(BadPrograms, FaultWithFileAndRung) {
  const BadProgram& p = GetParam();
  Plc plc(p.body);
  plc.set("N7:0", 1);
  plc.run();
  plc->run_for(seconds(1));
  ASSERT_TRUE(plc->fault().has_value()) << p.name;
  EXPECT_EQ(plc.fault_code(), p.code) << p.name << ": " << plc->fault()->to_string();
  EXPECT_EQ(plc->fault()->file, p.file) << p.name;
  EXPECT_EQ(plc->fault()->rung, p.rung) << p.name;
  EXPECT_FALSE(plc->fault()->message.empty());
  EXPECT_EQ(plc->mode(), Mode::Faulted);
  EXPECT_EQ(plc.i("S:6"), p.code);
  EXPECT_TRUE(plc.b("S:1/13"));
  EXPECT_GE(plc->now(), seconds(1)) << "a faulted processor still lets time pass";
}

INSTANTIATE_TEST_SUITE_P(
    Catalogue, BadPrograms,
    ::testing::Values(
        BadProgram{"divide by zero", "SOR XIC B3:0/0 OTE B3:0/1 EOR\nSOR DIV 10 N7:1 N7:2 EOR", 0x0020, 2, 2},
        BadProgram{"overflow", "SOR MUL 1000 1000 N7:2 EOR", 0x0020, 2, 1},
        BadProgram{"index past the file", "SOR MOV 300 S:24 EOR\nSOR MOV #N7:0 N7:1 EOR", 0x002A, 2, 1},
        BadProgram{"negative index", "SOR MOV -1 S:24 EOR\nSOR OTE #B3:0/2 EOR", 0x002A, 2, 1},
        BadProgram{"indirect past the file", "SOR MOV 999 N7:3 EOR\nSOR MOV 5 N7:[N7:3] EOR", 0x0029, 2, 1},
        BadProgram{"indirect file missing", "SOR MOV 99 N7:3 EOR\nSOR XIC B[N7:3]:0/0 OTE B3:0/0 EOR", 0x0029, 2, 1},
        BadProgram{"recursion past the nesting limit", "SOR JSR 3 EOR\nLADDER 3\nSOR JSR 3 EOR", 0x0030, 3, 0},
        BadProgram{"infinite JMP loop", "SOR ADD N7:5 1 N7:5 EOR\nSOR LBL 7 JMP 7 EOR", 0x0022, 2, 1},
        BadProgram{"negative timer preset", "SOR MOV -1 T4:0.PRE EOR\nSOR TON T4:0 0.01 10 0 EOR", 0x0034, 2, 1},
        BadProgram{"COP past the file", "SOR MOV 9 S:24 EOR\nSOR COP #N7:[N7:0] #N10:0 8 EOR\nDATA N7:0\n% N7:0 % 0 0 0 0",
                   0x002A, 2, 1}),
    [](const ::testing::TestParamInfo<BadProgram>& info) {
      std::string n = info.param.name;
      for (char& c : n)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
      return n;
    });

TEST(Faults, WatchdogFiresAfterTheWatchdogTimeOfVirtualTime) {
  // S:3 high byte = 5 ticks = 50 ms.
  Plc plc("SOR LBL 1 JMP 1 EOR\nDATA S:0\n% S:0 % 0 0 0 0x0500");
  plc.run();
  plc->scan(1);
  ASSERT_EQ(plc.fault_code(), 0x0022);
  EXPECT_GE(plc->now(), milliseconds(50));
  EXPECT_LT(plc->now(), milliseconds(52)) << "the loop stops at the first rung start past 50 ms";
}

TEST(Faults, WatchdogCoversTheWholeScanCycle) {
  struct SlowHousekeeping : DefaultScanTimeModel {
    Nanoseconds housekeeping_cost() const override { return milliseconds(120); }
  };
  RuntimeOptions opts;
  opts.time_model = std::make_shared<SlowHousekeeping>();
  Plc plc("SOR XIC B3:0/0 OTE B3:0/1 EOR", std::move(opts));
  plc.run();
  plc->scan(1);
  EXPECT_EQ(plc.fault_code(), 0x0022) << "120 ms of housekeeping exceeds the default 100 ms watchdog";
}

TEST(Faults, FaultStopsTheScanAtTheFaultingRung) {
  Plc plc(
      "SOR ADD N7:0 1 N7:0 EOR\n"
      "SOR MOV #N7:0 N7:1 EOR\n"
      "SOR ADD N7:2 1 N7:2 EOR");
  plc.set("S:24", 100);
  plc.run_scans(3);
  EXPECT_EQ(plc.fault_code(), 0x002A);
  EXPECT_EQ(plc.i("N7:0"), 1) << "rung 0 ran once; nothing ran after the fault";
  EXPECT_EQ(plc.i("N7:2"), 0) << "rung 2 never ran";
  EXPECT_EQ(plc.i("N7:1"), 0);
}

TEST(Faults, OutputsAreDeEnergisedAndClearFaultReturnsToProgram) {
  Plc plc(
      "SOR OTE O:2/0 EOR\n"
      "SOR XIC B3:0/0 DIV 1 0 N7:0 EOR");
  plc.run_scans(1);
  EXPECT_EQ(plc->module(2)->field_output(0), 1);
  plc.set("B3:0/0", 1);
  plc->scan(1);
  ASSERT_EQ(plc.fault_code(), 0x0020);
  EXPECT_EQ(plc->module(2)->field_output(0), 0) << "a faulted processor de-energises its outputs";
  EXPECT_FALSE(plc->set_mode(Mode::Run)) << "Run is refused while the fault is active";
  plc->clear_fault();
  EXPECT_EQ(plc->mode(), Mode::Program);
  EXPECT_FALSE(plc.b("S:1/13"));
  EXPECT_EQ(plc.i("S:6"), 0x0020) << "S:6 keeps the last code (PT1 27-17)";
  plc.set("B3:0/0", 0);
  plc.set("S:5", 0);
  ASSERT_TRUE(plc->set_mode(Mode::Run));
  plc->scan(1);
  EXPECT_FALSE(plc->fault().has_value());
  EXPECT_EQ(plc->module(2)->field_output(0), 1);
}

TEST(Faults, ForbiddenMFileAccessFaultsWithTheSlot) {
  RuntimeOptions opts;
  opts.module_factory = [](const SlotConfig& s) -> std::unique_ptr<Module> {
    if (s.slot != 3) return nullptr;
    auto m = std::make_unique<MemoryModule>(s.slot, s.catalog, s.scan_in, s.scan_out, 16, 16);
    m->forbid(MFile::M0, 5);
    return m;
  };
  constexpr std::string_view kHeaderWithM =
      "START 1747-L532\n"
      "SLOT 1 1746-IB16 SCAN_IN 1 SCAN_OUT 0\n"
      "SLOT 3 1747-SN SCAN_IN 8 SCAN_OUT 8 M0_SIZE 16 M1_SIZE 16\n";
  Plc plc("SOR MOV 1 M0:3.4 EOR\nSOR XIC B3:0/0 MOV 1 M0:3.5 EOR", std::move(opts), kHeaderWithM);
  plc.run_scans(1);
  EXPECT_FALSE(plc->fault().has_value());
  plc.set("B3:0/0", 1);
  plc->scan(1);
  EXPECT_EQ(plc.fault_code(), 0x0355);
  EXPECT_EQ(plc->fault()->rung, 1);
}

TEST(Faults, ModuleInstructionsAreRejectedAtCompileTime) {
  std::string errors;
  auto rt = try_build(program_text("SOR BTR N7:0 M1:1.100 #N10:0 0 0 0 10 EOR",
                                   "START 1747-L532\nSLOT 1 1747-SN SCAN_IN 8 SCAN_OUT 8 M0_SIZE 400 M1_SIZE 400\n"),
                      errors);
  EXPECT_EQ(rt, nullptr);
  EXPECT_NE(errors.find("not supported until the 1747-SN/1747-SDN module lands"), std::string::npos) << errors;
}

}  // namespace
}  // namespace softslc::test
