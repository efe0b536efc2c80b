// The VM's module-instruction path and mode/fault hooks (vm/module.h), with a test module: the
// operands as the interpreter resolves them, charged M-file time, checked data-table access,
// faults raised by the module, DEM addressed by its slot literal, and a module refusing a mode
// change.
#include <gtest/gtest.h>

#include "modules_test_util.h"
#include "vm/discrete_io.h"
#include "vm/scan_time_model.h"

namespace softslc::test {
namespace {

struct Recorder : MemoryModule {
  Recorder(int slot) : MemoryModule(slot, "TEST", 1, 1, 400, 400) {}
  std::vector<ModuleOperand> seen;
  bool rung = false;
  std::string action;  // what execute() does: "", "read-past-end", "fault", "charge", "read-block", ...
  std::array<std::uint16_t, 4> block{};
  bool block_ok = false;
  void execute(ModuleInstructionContext& ctx) override {
    seen.assign(ctx.operands().begin(), ctx.operands().end());
    rung = ctx.rung_in();
    std::uint16_t v = 0;
    if (action == "read-past-end") ctx.read(0, seen[0].limit, v);
    if (action == "fault") ctx.fault(0x0363, "refused");
    if (action == "charge") ctx.charge(MFileAccess::CopFromM, 10);
    if (action == "write") ctx.write(0, 2, 1234);
    if (action == "read-2-past-end") ctx.read(2, seen[2].limit, v);
    if (action == "read-block") block_ok = ctx.read_block(2, 0, block);
    if (action == "read-block-past-end") block_ok = ctx.read_block(2, seen[2].limit - 2, block);
    if (action == "write-block") block_ok = ctx.write_block(2, 0, block);
    if (action == "write-block-past-end") block_ok = ctx.write_block(2, seen[2].limit - 2, block);
    if (action == "write-words-past-end")
      for (std::uint32_t k = 0; k < block.size(); ++k)
        if (!(block_ok = ctx.write(2, seen[2].limit - 2 + k, block[k]))) break;
    if (action == "read-m-block") m_got = ctx.read_m_block(1, MFile::M1, 100, block);
    if (action == "read-m-words")
      for (std::size_t k = 0; k < block.size(); ++k, ++m_got)
        if (!ctx.read_m(1, MFile::M1, 100 + static_cast<int>(k), block[k])) break;
  }
  std::size_t m_got = 0;
  bool refuse_run = false;
  void on_mode_change(Mode from, Mode to) override {
    MemoryModule::on_mode_change(from, to);
    if (refuse_run && to == Mode::Run) host()->raise_major_fault(0x0262, "no configuration");
  }
};

// A time model that charges M-file accesses 1 us per word plus 100 us.
struct MTime : DefaultScanTimeModel {
  Nanoseconds mfile_access_cost(MFileAccess, int words) const override { return microseconds(100 + words); }
};

struct Fixture {
  Recorder* rec = nullptr;
  std::unique_ptr<Runtime> rt;
  explicit Fixture(const std::string& rungs, const std::function<void(Recorder&)>& setup = {}) {
    LoadResult lr = load_program("START 1747-L532\nSLOT 1 1747-SN SCAN_IN 8 SCAN_OUT 8 M0_SIZE 400 M1_SIZE 400\n"
                                 "SLOT 3 1747-SDN SCAN_IN 8 SCAN_OUT 8\nLADDER 2\n" + rungs,
                                 "t.slc");
    if (!lr.ok()) throw std::runtime_error(lr.render_diagnostics());
    RuntimeOptions o;
    o.time_model = std::make_shared<MTime>();
    o.module_factory = [&, setup](const SlotConfig& s) -> std::unique_ptr<Module> {
      auto m = std::make_unique<Recorder>(s.slot);
      if (s.slot == 1) {
        rec = m.get();
        if (setup) setup(*m);
      }
      return m;
    };
    o.module_instruction = [](const Instruction&) { return std::optional<std::string>{}; };
    auto r = Runtime::create(*lr.program, o);
    if (!r.ok()) throw std::runtime_error(r.render_errors());
    rt = std::move(r.runtime);
  }
};

TEST(VmModulePath, OperandsAreResolvedForTheModule) {
  Fixture f("SOR XIC B3:0/0 BTR N10:0 M1:1.300 #N11:5 1 3 1 12 EOR\n");
  ASSERT_TRUE(f.rt->set_mode(Mode::Run));
  f.rt->scan(1);
  ASSERT_EQ(f.rec->seen.size(), 7u);
  EXPECT_FALSE(f.rec->rung);
  const auto& s = f.rec->seen;
  EXPECT_EQ(s[0].kind, ModuleOperand::Kind::Table);
  EXPECT_EQ(s[1].kind, ModuleOperand::Kind::MFile);
  EXPECT_EQ(s[1].slot, 1);
  EXPECT_EQ(s[1].file, MFile::M1);
  EXPECT_EQ(s[1].word, 300u);
  EXPECT_EQ(s[2].kind, ModuleOperand::Kind::Table);
  EXPECT_EQ(s[2].limit, 12u) << "N11 is sized to the requested length from element 5";
  EXPECT_EQ(s[3].value, 1);
  EXPECT_EQ(s[4].value, 3);
  EXPECT_EQ(s[5].value, 1);
  EXPECT_EQ(s[6].value, 12);
  // The control block got rack 1, group 3, slot 1 and RW at download.
  EXPECT_EQ(f.rt->value("N10:0").as_int(), 0x0080 | (1 << 4) | (3 << 1) | 1);
  EXPECT_EQ(f.rt->value("N10:1").as_int(), 12);
  f.rt->set("B3:0/0", Value::bit(true));
  f.rt->scan(1);
  EXPECT_TRUE(f.rec->rung);
}

// read_block is read() for a run of words: the same words, and the same fault (002Ah, naming
// the first word past the end of the file) when the run leaves the operand's file.
TEST(VmModulePath, BlockReadIsCheckedLikeWordReads) {
  Fixture f("SOR BTR N10:0 M1:1.100 #N11:0 0 0 0 4 EOR\n", [](Recorder& r) { r.action = "read-block"; });
  for (int k = 0; k < 4; ++k) ASSERT_TRUE(f.rt->set("N11:" + std::to_string(k), Value::of_int(100 + k)));
  ASSERT_TRUE(f.rt->set_mode(Mode::Run));
  f.rt->scan(1);
  EXPECT_FALSE(f.rt->fault().has_value());
  EXPECT_TRUE(f.rec->block_ok);
  EXPECT_EQ(f.rec->block, (std::array<std::uint16_t, 4>{100, 101, 102, 103}));
  Fixture word("SOR BTR N10:0 M1:1.100 #N11:0 0 0 0 4 EOR\n", [](Recorder& r) { r.action = "read-2-past-end"; });
  Fixture block("SOR BTR N10:0 M1:1.100 #N11:0 0 0 0 4 EOR\n", [](Recorder& r) { r.action = "read-block-past-end"; });
  for (Fixture* x : {&word, &block}) {
    ASSERT_TRUE(x->rt->set_mode(Mode::Run));
    x->rt->scan(1);
  }
  ASSERT_TRUE(block.rt->fault().has_value());
  EXPECT_FALSE(block.rec->block_ok);
  EXPECT_EQ(block.rt->fault()->code, 0x002A);
  EXPECT_NE(block.rt->fault()->message.find("word 4 runs past the end"), std::string::npos) << block.rt->fault()->message;
  ASSERT_TRUE(word.rt->fault().has_value());
  EXPECT_EQ(word.rt->fault()->message, block.rt->fault()->message);
}

// write_block is write() for a run of words: the same words written, and where the run leaves the
// operand's file the words before the end written and the same fault (002Ah, naming the first word
// past the end).
TEST(VmModulePath, BlockWriteIsCheckedLikeWordWrites) {
  const auto with = [](const std::string& action) {
    return [action](Recorder& r) {
      r.action = action;
      r.block = {700, 701, 702, 703};
    };
  };
  Fixture ok("SOR BTR N10:0 M1:1.100 #N11:0 0 0 0 4 EOR\n", with("write-block"));
  ASSERT_TRUE(ok.rt->set_mode(Mode::Run));
  ok.rt->scan(1);
  EXPECT_FALSE(ok.rt->fault().has_value());
  EXPECT_TRUE(ok.rec->block_ok);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(ok.rt->value("N11:" + std::to_string(k)).as_int(), 700 + k);
  Fixture block("SOR BTR N10:0 M1:1.100 #N11:0 0 0 0 4 EOR\n", with("write-block-past-end"));
  Fixture word("SOR BTR N10:0 M1:1.100 #N11:0 0 0 0 4 EOR\n", with("write-words-past-end"));
  for (Fixture* x : {&block, &word}) {
    ASSERT_TRUE(x->rt->set_mode(Mode::Run));
    x->rt->scan(1);
    ASSERT_TRUE(x->rt->fault().has_value());
    EXPECT_FALSE(x->rec->block_ok);
    EXPECT_EQ(x->rt->fault()->code, 0x002A);
    // N11 has the 4 words of the BTR's length: the first two of the run are written.
    EXPECT_EQ(x->rt->value("N11:2").as_int(), 700);
    EXPECT_EQ(x->rt->value("N11:3").as_int(), 701);
  }
  EXPECT_NE(block.rt->fault()->message.find("word 4 runs past the end"), std::string::npos) << block.rt->fault()->message;
  EXPECT_EQ(word.rt->fault()->message, block.rt->fault()->message);
}

// read_m_block is read_m() for a run of M0/M1 words (a BTR's status words and data): the same
// words, and where a word is refused the words before it read, the same fault (xx55h, naming the
// refused word) and the count of words read.
TEST(VmModulePath, MBlockReadIsReadMWordByWord) {
  const auto fill = [](Recorder& r, const std::string& action, bool refuse) {
    r.action = action;
    for (int k = 0; k < 4; ++k) r.write_m(MFile::M1, 100 + k, static_cast<std::uint16_t>(500 + k));
    if (refuse) r.forbid(MFile::M1, 102);
  };
  Fixture ok("SOR BTR N10:0 M1:1.100 #N11:0 0 0 0 4 EOR\n", [&](Recorder& r) { fill(r, "read-m-block", false); });
  ASSERT_TRUE(ok.rt->set_mode(Mode::Run));
  ok.rt->scan(1);
  EXPECT_FALSE(ok.rt->fault().has_value());
  EXPECT_EQ(ok.rec->m_got, 4u);
  EXPECT_EQ(ok.rec->block, (std::array<std::uint16_t, 4>{500, 501, 502, 503}));
  Fixture block("SOR BTR N10:0 M1:1.100 #N11:0 0 0 0 4 EOR\n", [&](Recorder& r) { fill(r, "read-m-block", true); });
  Fixture word("SOR BTR N10:0 M1:1.100 #N11:0 0 0 0 4 EOR\n", [&](Recorder& r) { fill(r, "read-m-words", true); });
  for (Fixture* x : {&block, &word}) {
    ASSERT_TRUE(x->rt->set_mode(Mode::Run));
    x->rt->scan(1);
    ASSERT_TRUE(x->rt->fault().has_value());
    EXPECT_EQ(x->rec->m_got, 2u);
    EXPECT_EQ(x->rec->block[0], 500);
    EXPECT_EQ(x->rec->block[1], 501);
  }
  EXPECT_EQ(block.rt->fault()->code, word.rt->fault()->code);
  EXPECT_EQ(block.rt->fault()->message, word.rt->fault()->message);
  EXPECT_NE(block.rt->fault()->message.find("M1:1.102"), std::string::npos) << block.rt->fault()->message;
}

// COP from an M file into the data table reads the module's words as blocks (vm/interpreter.cpp
// copy_file): the words copied, and where a word is refused the words before it copied,
// the refused word zero and the rest untouched, fault xx55h naming the refused word, and S:24 =
// length - 1 as after any COP (RM E-11).
TEST(VmModulePath, CopFromAnMFileCopiesTheWordsUpToARefusedOne) {
  const auto fill = [](Recorder& r, int forbidden) {
    for (int k = 0; k < 120; ++k) r.write_m(MFile::M1, 50 + k, static_cast<std::uint16_t>(1000 + 3 * k));
    if (forbidden >= 0) r.forbid(MFile::M1, forbidden);
  };
  const std::string rungs = "SOR COP #M1:1.50 #N11:0 120 EOR\nSOR OTE B3:0/1 EOR\nSOR XIC N11:119/0 OTE B3:0/2 EOR\n";
  for (const int forbidden : {-1, 52, 50, 129, 169}) {
    Fixture f(rungs, [&](Recorder& r) { fill(r, forbidden); });
    for (int k = 0; k < 120; ++k) ASSERT_TRUE(f.rt->set("N11:" + std::to_string(k), Value::of_int(77)));
    ASSERT_TRUE(f.rt->set_mode(Mode::Run));
    f.rt->scan(1);
    const std::string what = "word " + std::to_string(forbidden) + " refused";
    const int bad = forbidden < 0 ? 120 : forbidden - 50;
    for (int k = 0; k < 120; ++k) {
      const std::int64_t want = k < bad ? 1000 + 3 * k : k == bad ? 0 : 77;
      ASSERT_EQ(f.rt->value("N11:" + std::to_string(k)).as_int(), want) << what << ", N11:" << k;
    }
    EXPECT_EQ(f.rt->value("S:24").as_int(), 119) << what;
    if (forbidden < 0) {
      EXPECT_FALSE(f.rt->fault().has_value());
      EXPECT_TRUE(f.rt->value("B3:0/1").as_bool());
      continue;
    }
    ASSERT_TRUE(f.rt->fault().has_value()) << what;
    EXPECT_EQ(f.rt->fault()->code, 0x0155) << what;
    EXPECT_NE(f.rt->fault()->message.find("M1:1." + std::to_string(forbidden)), std::string::npos) << f.rt->fault()->message;
    EXPECT_FALSE(f.rt->value("B3:0/1").as_bool()) << what;
  }
}

TEST(VmModulePath, DataTableAccessIsCheckedAndFaultsStopTheScan) {
  Fixture f("SOR BTR N10:0 M1:1.100 #N11:0 0 0 0 4 EOR\nSOR OTE B3:0/1 EOR\n",
            [](Recorder& r) { r.action = "read-past-end"; });
  ASSERT_TRUE(f.rt->set_mode(Mode::Run));
  f.rt->scan(1);
  ASSERT_TRUE(f.rt->fault().has_value());
  EXPECT_EQ(f.rt->fault()->code, 0x002A);
  EXPECT_EQ(f.rt->fault()->rung, 0);
  EXPECT_FALSE(f.rt->value("B3:0/1").as_bool());
  Fixture g("SOR BTR N10:0 M1:1.100 #N11:0 0 0 0 4 EOR\n", [](Recorder& r) { r.action = "fault"; });
  ASSERT_TRUE(g.rt->set_mode(Mode::Run));
  g.rt->scan(1);
  EXPECT_EQ(g.rt->fault()->code, 0x0363);
  Fixture h("SOR BTR N10:0 M1:1.100 #N11:0 0 0 0 4 EOR\n", [](Recorder& r) { r.action = "write"; });
  ASSERT_TRUE(h.rt->set_mode(Mode::Run));
  h.rt->scan(1);
  EXPECT_EQ(h.rt->value("N10:2").as_int(), 1234);
}

TEST(VmModulePath, ChargedAccessTimeIsAddedToTheScan) {
  Fixture a("SOR BTR N10:0 M1:1.100 #N11:0 0 0 0 4 EOR\n");
  Fixture b("SOR BTR N10:0 M1:1.100 #N11:0 0 0 0 4 EOR\n", [](Recorder& r) { r.action = "charge"; });
  ASSERT_TRUE(a.rt->set_mode(Mode::Run));
  ASSERT_TRUE(b.rt->set_mode(Mode::Run));
  a.rt->scan(1);
  b.rt->scan(1);
  EXPECT_EQ(b.rt->stats().last - a.rt->stats().last, microseconds(110));
}

TEST(VmModulePath, DemGoesToTheModuleInItsSlotLiteral) {
  Fixture f("SOR DEM 3 N20:0 70 EOR\n");
  ASSERT_TRUE(f.rt->set_mode(Mode::Run));
  f.rt->scan(1);
  auto* sdn = dynamic_cast<Recorder*>(f.rt->module(3));
  ASSERT_NE(sdn, nullptr);
  ASSERT_EQ(sdn->seen.size(), 3u);
  EXPECT_EQ(sdn->seen[1].kind, ModuleOperand::Kind::Table);
  EXPECT_EQ(sdn->seen[1].limit, 70u) << "the 70-word control block sizes N20";
  EXPECT_TRUE(f.rec->seen.empty());
}

TEST(VmModulePath, AModuleWithoutTheInstructionFaults001F) {
  LoadResult lr = load_program("START 1747-L532\nSLOT 1 1747-SN SCAN_IN 8 SCAN_OUT 8\nLADDER 2\n"
                               "SOR BTR N10:0 M1:1.100 #N11:0 0 0 0 4 EOR\n",
                               "t.slc");
  ASSERT_TRUE(lr.ok());
  RuntimeOptions o;
  o.module_instruction = [](const Instruction&) { return std::optional<std::string>{}; };
  o.module_factory = [](const SlotConfig& s) -> std::unique_ptr<Module> {
    return std::make_unique<MemoryModule>(s.slot, s.catalog, 8, 8, 400, 400);
  };
  auto r = Runtime::create(*lr.program, o);
  ASSERT_TRUE(r.ok());
  ASSERT_TRUE(r.runtime->set_mode(Mode::Run));
  r.runtime->scan(1);
  ASSERT_TRUE(r.runtime->fault().has_value());
  EXPECT_EQ(r.runtime->fault()->code, 0x001F);
  EXPECT_NE(r.runtime->fault()->message.find("has no such instruction"), std::string::npos);
}

TEST(VmModulePath, AModuleCanRefuseAModeChange) {
  Fixture f("SOR XIC B3:0/0 OTE B3:0/1 EOR\n", [](Recorder& r) { r.refuse_run = true; });
  EXPECT_TRUE(f.rt->set_mode(Mode::Run));
  EXPECT_EQ(f.rt->mode(), Mode::Faulted);
  EXPECT_EQ(f.rt->fault()->code, 0x0262);
  EXPECT_EQ(f.rt->value("S:6").as_int(), 0x0262);
  EXPECT_TRUE(f.rt->value("S:1/13").as_bool());
  // Every module saw Run, then Faulted.
  EXPECT_EQ(f.rec->last_mode(), Mode::Faulted);
}

}  // namespace
}  // namespace softslc::test
