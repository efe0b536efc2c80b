// The AutoMax calculator against section 4.5 ("Data Update Rate") of the
// AutoMax Remote I/O manual, chapter 4 (seeds/004_b6b94227d784095f.txt).
//
// The manual's worked example prints an update period of 9.965 ms, but two of
// its drop times disagree with the section's own formulas (see
// docs/throughput.md). The calculator follows the formulas; these tests pin
// both the formula figures and the fact that they differ from the example.
#include <gtest/gtest.h>

#include <string>

#include "modules/throughput/automax_throughput.h"

namespace softslc::throughput {
namespace {

AutomaxDrop drop_of(AutomaxDropType type) {
    AutomaxDrop drop;
    drop.type = type;
    return drop;
}

// Section 4.5 example: "Drop 1, Multibus Rack: 5 inputs, 8 outputs; Drop 2,
// Multibus Rack: 5 inputs, 6 outputs; Drop 3, Remote I/O Head: 6 inputs,
// 5 outputs; Drop 4, Digital Shark Rack".
AutomaxNetwork manual_example() {
    AutomaxNetwork network;
    AutomaxDrop drop1 = drop_of(AutomaxDropType::multibus);
    drop1.registers = 13;
    AutomaxDrop drop2 = drop_of(AutomaxDropType::multibus);
    drop2.registers = 11;
    AutomaxDrop drop3 = drop_of(AutomaxDropType::head_57c330);
    drop3.outputs = 5;
    drop3.inputs = 6;
    network.drops = {drop1, drop2, drop3, drop_of(AutomaxDropType::shark_digital)};
    return network;
}

// Section 4.5 example: "Drop 1 Time = [1.5 + (13 x .018)] = 1.734 msec" and
// "Drop 2 Time = [1.5 + (11 x .018)] = 1.698 msec" agree with the Multibus
// formula "DROP_TIME = [1.5 + (N x 0.018)]".
TEST(AutomaxExample, MultibusDropsMatchTheManual) {
    const AutomaxResult result = compute_automax(manual_example());
    EXPECT_EQ(result.drops[0].drop_time, 1734);
    EXPECT_EQ(result.drops[0].formula, "1.5 + (13 x 0.018)");
    EXPECT_EQ(result.drops[1].drop_time, 1698);
    EXPECT_EQ(result.drops[1].formula, "1.5 + (11 x 0.018)");
}

// Section 4.5, 57C330 formula "DROP_TIME = [1.9 + (X x 0.08) + (Y x 0.036)]"
// with X = 5 outputs and Y = 6 inputs: 1.9 + 0.4 + 0.216 = 2.516 ms. The
// worked example prints "Drop 3 Time = [1.7 + (5 x .013) + (6 x .028)] =
// 1.933 msec" instead; the formula is followed.
TEST(AutomaxExample, RemoteHeadDropFollowsTheFormulaNotTheExample) {
    const AutomaxResult result = compute_automax(manual_example());
    EXPECT_EQ(result.drops[2].drop_time, 2516);  // (the example's 1.933 ms is ruled out by this)
    EXPECT_EQ(result.drops[2].formula, "1.9 + (5 x 0.08) + (6 x 0.036)");
}

// Section 4.5, digital Shark: "DROP_TIME = 1.8 milliseconds". The worked
// example prints "Drop 4 Time = 1.900 msec"; the formula is followed.
TEST(AutomaxExample, DigitalSharkDropFollowsTheFormulaNotTheExample) {
    const AutomaxResult result = compute_automax(manual_example());
    EXPECT_EQ(result.drops[3].drop_time, 1800);  // (the example's 1.900 ms is ruled out by this)
    EXPECT_EQ(result.drops[3].formula, "1.8");
}

// Section 4.5: "the sum of the drop time for each drop on the network plus
// 2.7 milliseconds to poll any inactive drops": 1.734 + 1.698 + 2.516 + 1.8
// + 2.7 = 10.448 ms by the formulas (the manual prints 9.965 ms, which is
// 1.734 + 1.698 + 1.933 + 1.900 + 2.700). Every assertion is on the calculator's output: the
// period is the sum of the drop times it computed plus the poll time, and that sum is 10.448.
TEST(AutomaxExample, UpdatePeriodByTheFormulasIs10448) {
    const AutomaxResult result = compute_automax(manual_example());
    EXPECT_EQ(result.inactive_poll, 2700);
    EXPECT_EQ(result.update_period, 10448);
    Micros sum = result.inactive_poll;
    for (const auto& drop : result.drops) sum += drop.drop_time;
    EXPECT_EQ(result.update_period, sum);
}

// Section 4.5 example: the drops are called "Drop 1" to "Drop 4" by position
// (its digital Shark rack would be numbered 9..F by section 4.4).
TEST(AutomaxExample, DropsAreLabelledByPositionWithoutDropNumbers) {
    const AutomaxResult result = compute_automax(manual_example());
    ASSERT_EQ(result.drops.size(), 4u);
    for (std::size_t i = 0; i < 4; ++i) {
        EXPECT_EQ(result.drops[i].drop, static_cast<int>(i) + 1);
        EXPECT_EQ(result.drops[i].index, i);
    }
}

// Section 4.5 example figures quoted by the notes: 1.933 ms and 1.900 ms
// printed, 2.516 ms and 1.8 ms by the formulas.
TEST(AutomaxExample, NotesExplainBothDiscrepancies) {
    const AutomaxResult result = compute_automax(manual_example());
    ASSERT_EQ(result.notes.size(), 2u);
    EXPECT_NE(result.notes[0].find("1.933 ms"), std::string::npos);
    EXPECT_NE(result.notes[0].find("2.516 ms"), std::string::npos);
    EXPECT_NE(result.notes[1].find("1.8 ms"), std::string::npos);
    EXPECT_NE(result.notes[1].find("1.900 ms"), std::string::npos);
}

// Section 4.5: the Multibus and Drive Interface Head formulas agree with the
// example (drops 1 and 2) or are not in it, so no note is due.
TEST(AutomaxNotes, NoNotesWhenNoDiscrepantDropKindIsPresent) {
    AutomaxNetwork network;
    AutomaxDrop multibus = drop_of(AutomaxDropType::multibus);
    multibus.registers = 4;
    network.drops = {multibus, drop_of(AutomaxDropType::drive_head)};
    EXPECT_TRUE(compute_automax(network).notes.empty());
}

// Section 4.5, the remaining formulas: 57C328 head "[1.7 + R x 0.036]",
// Remote Drive Interface Head "2.1 milliseconds", mixed Shark "4.0
// milliseconds", and the Multibus formula with N = 0.
TEST(AutomaxFormulas, EveryDropKind) {
    AutomaxDrop head328 = drop_of(AutomaxDropType::head_57c328);
    for (int rails = 0; rails <= 4; ++rails) {
        head328.rails = rails;
        EXPECT_EQ(automax_drop_time(head328), 1700 + 36 * rails);
    }
    head328.rails = 4;
    EXPECT_EQ(automax_drop_time(head328), 1844);  // 1.7 + 4 x 0.036 = 1.844
    EXPECT_EQ(automax_drop_time(drop_of(AutomaxDropType::drive_head)), 2100);
    EXPECT_EQ(automax_drop_time(drop_of(AutomaxDropType::shark_digital)), 1800);
    EXPECT_EQ(automax_drop_time(drop_of(AutomaxDropType::shark_mixed)), 4000);
    EXPECT_EQ(automax_drop_time(drop_of(AutomaxDropType::multibus)), 1500);
    AutomaxDrop head330 = drop_of(AutomaxDropType::head_57c330);
    head330.outputs = 1;
    EXPECT_EQ(automax_drop_time(head330), 1980);  // 1.9 + 0.08
    head330.outputs = 0;
    head330.inputs = 1;
    EXPECT_EQ(automax_drop_time(head330), 1936);  // 1.9 + 0.036
}

// Section 4.5: 1.7 + 3 x 0.036 = 1.808 ms, 2.1 ms and 4.0 ms, plus 2.7 ms.
TEST(AutomaxFormulas, FormulaTextShowsTheDropsCounts) {
    AutomaxDrop head328 = drop_of(AutomaxDropType::head_57c328);
    head328.rails = 3;
    AutomaxNetwork network;
    network.drops = {head328, drop_of(AutomaxDropType::drive_head), drop_of(AutomaxDropType::shark_mixed)};
    const AutomaxResult result = compute_automax(network);
    EXPECT_EQ(result.drops[0].formula, "1.7 + (3 x 0.036)");
    EXPECT_EQ(result.drops[1].formula, "2.1");
    EXPECT_EQ(result.drops[2].formula, "4.0");
    EXPECT_EQ(result.update_period, 1808 + 2100 + 4000 + 2700);
}

// The six DROP_TIME formulas of section 4.5, one table row each.
TEST(AutomaxDropTypes, TableNamesRoundTrip) {
    for (const AutomaxDropTypeInfo& info : automax_drop_types()) {
        EXPECT_EQ(parse_automax_drop_type(info.name), info.type);
        EXPECT_EQ(&automax_drop_type(info.type), &info);
    }
    EXPECT_FALSE(parse_automax_drop_type("shark"));
}

// Section 4.4: drop numbers 1..7, or 9..F for digital Shark racks; given
// numbers label the drops in the result.
TEST(AutomaxDropNumbers, GivenNumbersLabelTheDrops) {
    AutomaxNetwork network = manual_example();
    network.drops[0].number = 3;
    network.drops[1].number = 1;
    network.drops[2].number = 7;
    network.drops[3].number = 15;
    const AutomaxResult result = compute_automax(network);
    EXPECT_EQ(result.drops[0].drop, 3);
    EXPECT_EQ(result.drops[1].drop, 1);
    EXPECT_EQ(result.drops[2].drop, 7);
    EXPECT_EQ(result.drops[3].drop, 15);
    EXPECT_EQ(result.update_period, 10448);
}

}  // namespace
}  // namespace softslc::throughput
