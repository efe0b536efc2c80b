// The module registry and the setup loader: which family serves a slot, the module-instruction
// hook's refusals, the factory's fresh instances, field devices by name, and the local 1746
// discrete modules (points and delays).
#include <gtest/gtest.h>

#include "modules/discrete/discrete_modules.h"
#include "modules/module_setup.h"
#include "modules_test_util.h"

namespace softslc::test {
namespace {

TEST(Registry, FindsFamiliesByCatalogAndIdCode) {
  const ModuleRegistry r = builtin_module_registry();
  SlotConfig s;
  s.catalog = "1747-SN";
  ASSERT_NE(r.find(s), nullptr);
  EXPECT_EQ(r.find(s)->name, "1747-SN RIO scanner");
  s.catalog = "1747-BSN";
  EXPECT_EQ(r.find(s)->name, "1747-SN RIO scanner");
  // RSLogix "Other" with the scanner's ID code (1747-SN ch. 2, step 6: "enter the scanner input
  // module ID code (13608)").
  s.catalog = "OTHER";
  s.id_code = 13608;
  EXPECT_EQ(r.find(s)->name, "1747-SN RIO scanner");
  s.id_code.reset();
  EXPECT_EQ(r.find(s), nullptr);
  s.catalog = "1746-OB16";
  EXPECT_EQ(r.find(s)->name, "discrete I/O (1746, 1762, 1769, MicroLogix embedded)");
}

const std::string kTwoSlots =
    "START 1747-L532\n"
    "SLOT 1 1747-SN SCAN_IN 32 SCAN_OUT 32 G_FILE 3\n 0 1 15\n"
    "SLOT 2 1746-IB8 SCAN_IN 1 SCAN_OUT 0\n"
    "SLOT 3 1746-OB16 SCAN_IN 0 SCAN_OUT 1\n"
    "LADDER 2\n";

TEST(Registry, ModuleInstructionsNeedTheirModule) {
  LoadResult lr = load_program(kTwoSlots + "SOR BTR N10:0 M1:1.100 #N11:0 0 0 0 4 EOR\n", "p.slc");
  ASSERT_TRUE(lr.ok()) << lr.render_diagnostics();
  ModuleSetup s = setup_modules(*lr.program, nullptr);
  ASSERT_TRUE(s.ok());
  EXPECT_TRUE(Runtime::create(*lr.program, s.options).ok());
  // The same instruction naming the slot of a discrete card.
  Program p = *lr.program;
  Instruction in = p.files[0].rungs[0].elements[0].instruction;
  in.operands[1].address.element = 2;
  EXPECT_EQ(*s.options.module_instruction(in), "BTR needs a 1747-SN or 1747-BSN in slot 2; slot 2 holds a 1746-IB8");
  in.operands[1].address.element = 9;
  EXPECT_EQ(*s.options.module_instruction(in), "BTR needs a 1747-SN or 1747-BSN in slot 9, which is empty");
}

TEST(Registry, EveryRuntimeGetsFreshModules) {
  LoadResult lr = load_program(kTwoSlots + "SOR XIC I:2/0 OTE O:3/0 EOR\n", "p.slc");
  ASSERT_TRUE(lr.ok());
  ModuleSetup s = setup_modules(*lr.program, nullptr);
  auto a = Runtime::create(*lr.program, s.options);
  auto b = Runtime::create(*lr.program, s.options);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_NE(a.runtime->module(1), b.runtime->module(1));
  EXPECT_NE(dynamic_cast<RioScanner*>(a.runtime->module(1)), nullptr);
  EXPECT_NE(dynamic_cast<DiscreteModule*>(a.runtime->module(2)), nullptr);
}

TEST(Discrete, AnEightPointCardHasEightPoints) {
  Bench b(kTwoSlots + "SOR XIC I:2/0 OTE O:3/0 EOR\n", "");
  EXPECT_TRUE(b->set("I:2/7", Value::bit(true)));
  EXPECT_FALSE(b->set("I:2/8", Value::bit(true)));
  b.set("I:2.0", static_cast<std::int16_t>(0xFFFF));  // every bit; only the eight points exist
  b.run();
  b->scan(1);
  EXPECT_EQ(b.u("I:2.0"), 0x00FF);
  EXPECT_EQ(*b->module(3)->field_output(0), 1);
}

TEST(Discrete, InputAndOutputDelaysFromTheBench) {
  Bench b(kTwoSlots + "SOR XIC I:2/0 OTE O:3/0 EOR\n",
          "io PB slot=2 input_delay=8ms\nio LAMP slot=3 output_delay=3ms\n");
  b.run();
  b->scan(1);
  const VirtualTime t0 = b->now();
  b.inject("PB", "input", {"1"});
  ASSERT_TRUE(b.until([&] { return (*b->observe("LAMP", "outputs"))[0] == 1; }, milliseconds(50)));
  // The input filter (8 ms) and the output delay (3 ms) are both in the path.
  EXPECT_GE(b->now() - t0, milliseconds(11));
  EXPECT_EQ(*b->observe("PB", "inputs"), (std::vector<std::int64_t>{1}));
}

TEST(Devices, InjectAndObserveByName) {
  Bench b(kTwoSlots + "SOR XIC I:2/0 OTE O:3/0 EOR\n",
          "scanner RIO slot=1 {\n  adapter A rack=0 group=0 size=full\n}\nio PB slot=2\n");
  EXPECT_EQ(b->devices(), (std::vector<std::string>{"RIO", "A", "PB"}));
  auto st = b->inject("NOPE", "offline");
  EXPECT_FALSE(st);
  EXPECT_EQ(st.message, "no simulated field device is named 'NOPE'");
  st = b->inject("A", "melt");
  EXPECT_FALSE(st);
  EXPECT_NE(st.message.find("device A: an adapter accepts 'offline', 'online'"), std::string::npos);
  EXPECT_TRUE(b->inject("A", "offline"));
  EXPECT_FALSE(b->observe("A", "colour").has_value());
  EXPECT_TRUE(b->observe("A", "outputs").has_value());
}

}  // namespace
}  // namespace softslc::test
