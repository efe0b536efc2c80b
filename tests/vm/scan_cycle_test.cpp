// The scan cycle: phases, modes, first pass, status words, forces, immediate I/O, modules, events,
// virtual time and determinism.
//
// Sources: DF1 p.10-3 (S:1 mode codes, /5 /6 forces, /13 major halt, /15 first pass), PT1 27-13
// (S:4 +1 per 10 ms, zeroed on entry to Run/Test; S:3 watchdog), RM B-19 (S:3 low byte), RM B-42
// (S:22 max, S:23 average (avg*7+scan)/8), facts §2 (I:e.s/b slot addressing), house-style.md
// (determinism: byte-identical runs).
#include <gtest/gtest.h>

#include <sstream>

#include "instructions/mfile_access_time.h"
#include "vm/discrete_io.h"
#include "vm/profile_scan_time_model.h"
#include "vm_test_util.h"

namespace softslc::test {
namespace {

TEST(ScanCycle, FirstPassBitIsSetForOneScanAfterEnteringRun) {
  Plc plc("SOR XIC S:1/15 ADD N7:0 1 N7:0 EOR");
  plc.run_scans(5);
  EXPECT_EQ(plc.i("N7:0"), 1);
  EXPECT_FALSE(plc.b("S:1/15"));
  ASSERT_TRUE(plc->set_mode(Mode::Program));
  plc.run_scans(3);
  EXPECT_EQ(plc.i("N7:0"), 2);
}

TEST(ScanCycle, ModeCodesInS1) {
  Plc plc("SOR XIC B3:0/0 OTE B3:0/1 EOR");
  EXPECT_EQ(plc.i("S:1") & 0x1F, 1) << "Program";
  plc.run();
  EXPECT_EQ(plc.i("S:1") & 0x1F, 6) << "Run";
  ASSERT_TRUE(plc->set_mode(Mode::Test));
  EXPECT_EQ(plc.i("S:1") & 0x1F, 8) << "Test single scan";
  EXPECT_FALSE(plc->set_mode(Mode::Faulted));
}

TEST(ScanCycle, ProgramModeDoesNotExecuteButTimePasses) {
  Plc plc("SOR ADD N7:0 1 N7:0 EOR\nSOR OTE O:2/0 EOR");
  plc->run_for(milliseconds(50));
  EXPECT_EQ(plc.i("N7:0"), 0);
  EXPECT_GE(plc->now(), milliseconds(50));
  plc.set("O:2.0", 1);
  plc->scan(1);
  EXPECT_EQ(plc->module(2)->field_output(0), 0) << "outputs are off in Program mode";
}

TEST(ScanCycle, TestModeRunsOneScanPerRequestWithOutputsDisabled) {
  Plc plc("SOR ADD N7:0 1 N7:0 EOR\nSOR OTE O:2/0 EOR");
  ASSERT_TRUE(plc->set_mode(Mode::Test));
  plc->scan(1);
  EXPECT_EQ(plc.i("N7:0"), 1);
  EXPECT_TRUE(plc.b("O:2/0")) << "the program wrote the output image";
  EXPECT_EQ(plc->module(2)->field_output(0), 0) << "but Test mode does not energise outputs";
  plc->run_for(milliseconds(20));
  EXPECT_EQ(plc.i("N7:0"), 1) << "idle between single scans";
  plc->scan(2);
  EXPECT_EQ(plc.i("N7:0"), 3);
}

TEST(ScanCycle, FreeRunningClockCountsTenMillisecondTicks) {
  Plc plc("SOR XIC B3:0/0 OTE B3:0/1 EOR");
  plc->run_for(milliseconds(35));
  plc.run();
  EXPECT_EQ(plc.i("S:4"), 0) << "zeroed on entry to Run";
  plc->run_for(seconds(1));
  const auto ticks = plc.i("S:4");
  EXPECT_GE(ticks, 99);
  EXPECT_LE(ticks, 101);
}

TEST(ScanCycle, ScanTimeStatusWords) {
  struct Model : DefaultScanTimeModel {
    Nanoseconds housekeeping_cost() const override { return milliseconds(23); }
  };
  RuntimeOptions opts;
  opts.time_model = std::make_shared<Model>();
  Plc plc("SOR XIC B3:0/0 OTE B3:0/1 EOR", std::move(opts));
  plc.run_scans(8);
  const Nanoseconds scan = plc->stats().last;
  EXPECT_GE(scan, milliseconds(23));
  EXPECT_LT(scan, milliseconds(24));
  EXPECT_EQ(plc.i("S:3") & 0xFF, 2) << "23 ms = 2 whole 10 ms ticks";
  EXPECT_EQ(plc.i("S:3") >> 8, 10) << "watchdog default 10 ticks";
  EXPECT_EQ(plc.i("S:35"), 23);
  EXPECT_EQ(plc.i("S:22"), 2);
  // S:23 = (avg*7 + 2)/8 from 0, eight times: 0,0,0,0,0,0,0,0 — integer arithmetic keeps it at 0
  // until the average can move by a whole unit. With 1 ms units (S:33/13) it converges on 23.
  plc.set("S:33", 1 << 13);
  plc->scan(40);
  EXPECT_EQ(plc.i("S:22"), 23);
  EXPECT_GE(plc.i("S:23"), 16);
  EXPECT_LE(plc.i("S:23"), 23);
  EXPECT_EQ(plc->stats().scans, 48u);
  EXPECT_EQ(plc->stats().last_us(), scan / 1000);
  EXPECT_EQ(plc->stats().max_us(), scan / 1000);
}

TEST(ScanCycle, InputForcesOverrideTheFieldAndOutputForcesTheCard) {
  Plc plc("SOR XIC I:1/0 OTE O:2/0 EOR\nSOR XIC I:1/1 OTE O:2/1 EOR");
  plc.run();
  ASSERT_TRUE(plc->force("I:1/0", true));
  ASSERT_TRUE(plc->force("O:2/1", true));
  plc->scan(1);
  EXPECT_TRUE(plc.b("I:1/0")) << "the forced input";
  EXPECT_TRUE(plc.b("O:2/0"));
  EXPECT_FALSE(plc.b("O:2/1")) << "the program's output image is not forced";
  EXPECT_EQ(plc->module(2)->field_output(0), 0b11) << "the card sees the forced output";
  EXPECT_TRUE(plc.b("S:1/6")) << "forces installed";
  EXPECT_TRUE(plc.b("S:1/5")) << "forces enabled";
  plc->enable_forces(false);
  plc->scan(1);
  EXPECT_FALSE(plc.b("I:1/0"));
  EXPECT_EQ(plc->module(2)->field_output(0), 0);
  EXPECT_FALSE(plc.b("S:1/5"));
  plc->enable_forces(true);
  ASSERT_TRUE(plc->force("I:1/0", false));
  plc->set("I:1/0", Value::bit(true));
  plc->scan(1);
  EXPECT_FALSE(plc.b("I:1/0")) << "forced off wins over the field";
  plc->clear_forces();
  plc->scan(1);
  EXPECT_TRUE(plc.b("I:1/0"));
  EXPECT_FALSE(plc.b("S:1/6"));
  EXPECT_FALSE(plc->force("N7:0/0", true)) << "only I/O bits can be forced";
}

TEST(ScanCycle, ForceBlocksFromTheProgram) {
  Plc plc(
      "SOR XIC I:1/0 OTE B3:0/0 EOR\n"
      "SOR XIC I:1/1 OTE B3:0/1 EOR\n"
      "FORCE I:1\n"
      "% ON OFF %\n"
      "0X0001 0XFFFD % FORCE I:1.0 %\n");
  plc.run();
  plc->set("I:1/1", Value::bit(true));
  plc->scan(1);
  EXPECT_TRUE(plc.b("B3:0/0")) << "ON column: I:1/0 forced on";
  EXPECT_FALSE(plc.b("B3:0/1")) << "OFF column bit 1 clear: I:1/1 forced off";
}

TEST(ScanCycle, ImmediateInputAndOutput) {
  std::vector<CountingInputs*> cards;
  RuntimeOptions opts = counting_cards(cards);
  Plc plc(
      "SOR MOV I:1.0 N7:0 EOR\n"
      "SOR IIM I:1.0 0x00FF 1 EOR\n"
      "SOR MOV I:1.0 N7:1 EOR\n"
      "SOR OTE O:2/3 EOR\n"
      "SOR IOM O:2.0 0xFFFF 1 EOR\n"
      "SOR OTU O:2/3 EOR",
      std::move(opts));
  plc.run_scans(1);
  EXPECT_EQ(plc.i("N7:0"), 1) << "the input scan read the card once";
  EXPECT_EQ(plc.i("N7:1"), 2) << "IIM read it again mid-scan";
  CountingInputs* out = cards[1];
  ASSERT_EQ(out->slot(), 2);
  ASSERT_EQ(out->outputs.size(), 2u) << "IOM, then the output scan";
  EXPECT_EQ(out->outputs[0][0], 1u << 3) << "IOM delivered O:2/3 immediately";
  EXPECT_EQ(out->outputs[1][0], 0u) << "the output scan delivered the final image";
}

TEST(ScanCycle, MFilesGoThroughTheModuleAccessor) {
  RuntimeOptions opts;
  MemoryModule* card = nullptr;
  opts.module_factory = [&](const SlotConfig& s) -> std::unique_ptr<Module> {
    if (s.slot != 3) return nullptr;
    auto m = std::make_unique<MemoryModule>(s.slot, s.catalog, s.scan_in, s.scan_out, 32, 32);
    card = m.get();
    return m;
  };
  constexpr std::string_view kHeaderWithM =
      "START 1747-L532\n"
      "SLOT 1 1746-IB16 SCAN_IN 1 SCAN_OUT 0\n"
      "SLOT 3 1747-SN SCAN_IN 8 SCAN_OUT 8 M0_SIZE 32 M1_SIZE 32\n";
  Plc plc(
      "SOR XIC M1:3.2/4 OTE B3:0/0 EOR\n"
      "SOR MOV N7:0 M0:3.1 EOR\n"
      "SOR OTL M0:3.0/15 EOR\n"
      "SOR COP #N7:0 #M0:3.10 3 EOR",
      std::move(opts), kHeaderWithM);
  ASSERT_NE(card, nullptr);
  card->set_m_word(MFile::M1, 2, 1 << 4);
  plc.set("N7:0", 1234);
  plc.run_scans(1);
  EXPECT_TRUE(plc.b("B3:0/0"));
  EXPECT_EQ(card->m_word(MFile::M0, 1), 1234);
  EXPECT_EQ(card->m_word(MFile::M0, 0), 0x8000);
  EXPECT_EQ(card->m_word(MFile::M0, 10), 1234);
  EXPECT_EQ(plc.i("M0:3.10"), 1234) << "tools read M words through the module too";
  EXPECT_EQ(card->last_mode(), Mode::Run) << "modules hear mode changes";
}

TEST(ScanCycle, TimeModelChargesMFileAccessesAndFileWords) {
  // The M0/M1 access-time rows and per-word file-instruction times are the timing model's; the
  // VM charges them on exactly those paths.
  struct Model : DefaultScanTimeModel {
    mutable std::vector<std::pair<MFileAccess, int>> calls;
    Nanoseconds per_word_cost(Opcode op) const override { return op == Opcode::COP ? microseconds(10) : 0; }
    Nanoseconds mfile_access_cost(MFileAccess row, int words) const override {
      calls.emplace_back(row, words);
      return microseconds(100) * words;
    }
  };
  const auto run = [](std::shared_ptr<const ScanTimeModel> model) {
    RuntimeOptions opts;
    opts.time_model = std::move(model);
    opts.module_factory = [](const SlotConfig& s) -> std::unique_ptr<Module> {
      if (s.slot != 3) return nullptr;
      return std::make_unique<MemoryModule>(s.slot, s.catalog, s.scan_in, s.scan_out, 8, 8);
    };
    Plc plc("SOR XIC M1:3.0/0 OTE B3:0/0 EOR\nSOR COP #N7:0 #N7:10 5 EOR", std::move(opts),
            "START 1747-L532\nSLOT 3 1747-SN SCAN_IN 8 SCAN_OUT 8 M0_SIZE 8 M1_SIZE 8\n");
    plc.run_scans(1);
    return plc->stats().last;
  };
  auto model = std::make_shared<Model>();
  const Nanoseconds charged = run(model);
  const Nanoseconds plain = run(std::make_shared<DefaultScanTimeModel>());
  EXPECT_EQ(charged - plain, microseconds(100) + 5 * microseconds(10));
  ASSERT_EQ(model->calls.size(), 1u);
  EXPECT_EQ(model->calls[0].first, MFileAccess::ExamineBit) << "XIC's row of the access-time table";
  EXPECT_EQ(model->calls[0].second, 1);
}

// A field device: a limit switch that closes 250 ms after the output that drives the motor comes
// on, modelled with the event queue.
class Conveyor : public DiscreteIoModule {
 public:
  using DiscreteIoModule::DiscreteIoModule;
  void output_scan(std::span<const std::uint16_t> image) override {
    const bool motor = image[0] & 1;
    if (motor && !running_) {
      running_ = true;
      host()->schedule_at(host()->now() + milliseconds(250), [this](VirtualTime) { set_field_input(0, 1, 1); });
    }
    DiscreteIoModule::output_scan(image);
  }
  int input_words_hint() const { return 1; }

 private:
  bool running_ = false;
};

std::string conveyor_trace() {
  RuntimeOptions opts;
  opts.module_factory = [](const SlotConfig& s) -> std::unique_ptr<Module> {
    return std::make_unique<Conveyor>(s.slot, s.catalog, s.scan_in, s.scan_out);
  };
  constexpr std::string_view kHeader1 = "START 1747-L532\nSLOT 1 1746-IO12 SCAN_IN 1 SCAN_OUT 1\n";
  Plc plc(
      "SOR XIO I:1/0 OTE O:1/0 EOR\n"
      "SOR XIC I:1/0 OTL B3:0/0 EOR\n"
      "SOR XIO B3:0/0 TON T4:0 0.01 500 0 EOR",
      std::move(opts), kHeader1);
  plc.run();
  std::ostringstream trace;
  bool seen = false;
  while (plc->now() < seconds(1)) {
    plc->scan(1);
    if (plc.b("B3:0/0") && !seen) {
      seen = true;
      trace << "switch at " << plc->now() << "\n";
    }
  }
  trace << "T4:0.ACC " << plc.i("T4:0.ACC") << " S:4 " << plc.i("S:4") << " now " << plc->now() << "\n";
  for (std::uint32_t i = 0; i < plc->data().size(); ++i) trace << plc->data().word(i) << ' ';
  return trace.str();
}

TEST(ScanCycle, FieldDeviceEventsArriveAtTheNextInputScan) {
  const std::string trace = conveyor_trace();
  const auto pos = trace.find("switch at ");
  ASSERT_NE(pos, std::string::npos);
  const VirtualTime t = std::stoll(trace.substr(pos + 10));
  // The motor output goes on at the end of the first scan (~1 ms); the switch closes 250 ms later
  // and the program sees it one scan after that.
  EXPECT_GT(t, milliseconds(250));
  EXPECT_LT(t, milliseconds(254));
}

TEST(ScanCycle, TwoRunsAreByteIdentical) {
  EXPECT_EQ(conveyor_trace(), conveyor_trace());
}

TEST(ScanCycle, RunUntilStopsAtTheLimit) {
  Plc plc("SOR XIC B3:0/0 OTE B3:0/1 EOR");
  plc.run();
  EXPECT_FALSE(plc->run_until([](const Runtime& r) { return r.value("B3:0/1").as_bool(); }, milliseconds(30)));
  EXPECT_GE(plc->now(), milliseconds(30));
  EXPECT_LT(plc->now(), milliseconds(32));
  plc.set("B3:0/0", 1);
  EXPECT_TRUE(plc->run_until([](const Runtime& r) { return r.value("B3:0/1").as_bool(); }, milliseconds(30)));
}

TEST(ScanCycle, SetAndGetFormatValuesForTools) {
  Plc plc("SOR XIC B3:0/0 OTE B3:0/1 EOR\nSOR MOV F8:0 F8:1 EOR\nSOR MOV N7:1 N7:2 EOR");
  ASSERT_TRUE(plc->set("N7:0", Value::of_int(-12)));
  ASSERT_TRUE(plc->set("F8:0", Value::of_float(0.1)));
  ASSERT_TRUE(plc->set("B3:0/0", Value::bit(true)));
  // One value rule for every tool (issue 17): a float does not silently round into a word.
  EXPECT_FALSE(plc->set("N7:1", Value::of_float(2.5)));
  ASSERT_TRUE(plc->set("N7:1", Value::of_int(2)));
  EXPECT_EQ(plc->format("N7:0"), "-12");
  EXPECT_EQ(plc->format("F8:0"), "0.1");
  EXPECT_EQ(plc->format("B3:0/0"), "1");
  EXPECT_EQ(plc->format("N7:1"), "2");
  EXPECT_EQ(plc->value("T4:0/DN").kind, Value::Kind::Bit);
  std::string err;
  EXPECT_FALSE(plc->get("N7:300", &err).has_value());
  EXPECT_FALSE(err.empty());
  EXPECT_FALSE(plc->get("N99:0", &err).has_value());
  EXPECT_FALSE(plc->set("I:9/0", Value::bit(true))) << "no module in slot 9";
  EXPECT_THROW(plc->value("X?"), std::invalid_argument);
}

// The profile model keeps each M-file access class as a cost per first and further word; that must
// be the 1747-SN appendix B / 1203-SM1 appendix A table (mfile_access_us) for every processor with
// a built-in profile, every class and word counts 0-300, and nothing where the table has no row.
TEST(ScanTimeModel, MFileAccessCostIsTheAccessTimeTableForEveryWordCount) {
  int charged = 0;
  for (const std::string& key : builtin_timing_profile_keys()) {
    auto profile = builtin_timing_profile(key);
    ASSERT_TRUE(profile) << key;
    const ProfileScanTimeModel model(*profile, key);
    for (int r = 0; r <= static_cast<int>(MFileAccess::OtherM); ++r)
      for (int words = 0; words <= 300; ++words) {
        const auto row = static_cast<MFileAccess>(r);
        const auto us = mfile_access_us(key, row, words);
        ASSERT_EQ(model.mfile_access_cost(row, words), us ? microseconds(*us) : 0)
            << key << " class " << r << " words " << words;
        charged += us ? 1 : 0;
      }
  }
  EXPECT_GT(charged, 1000) << "the built-in profiles include processors with M files";
}

}  // namespace
}  // namespace softslc::test
