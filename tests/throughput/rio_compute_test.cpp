// The RIO calculator on the manual's worked examples and on the rules of
// appendix A and chapters 1 and 4 of the 1747-SN manual
// (seeds/000_6bdfccac32889807.txt). Expected figures are the manual's; where
// a test combines figures (block-transfer throughput has no worked example),
// the comment shows the hand calculation from the manual's formula.
#include <gtest/gtest.h>

#include <vector>

#include "modules/throughput/rio_throughput.h"

namespace softslc::throughput {
namespace {

// Appendix A, "Example Discrete I/O Throughput without Block Transfers
// Present": 115.2K baud; a 1/2 rack 1747-ASB at rack 0, full racks 1 and 2,
// three 1/4 racks in rack 3; T_ps 25.0, T_adp 8.0, T_id 10.0, T_od 1.0 ms;
// T_upd > T_hold.
RioNetwork manual_example_1() {
    RioNetwork network;
    network.baud = RioBaud::b115_2k;
    network.processor_scan = 25000;
    network.adapter_delay = 8000;
    network.input_delay = 10000;
    network.output_delay = 1000;
    network.t_upd_gt_t_hold = true;
    network.devices = {{0, 0, 4, false, "1747-ASB"}, {1, 0, 8, false, ""}, {2, 0, 8, false, ""},
                       {3, 0, 2, false, ""},         {3, 2, 2, false, ""}, {3, 4, 2, false, ""}};
    return network;
}

// Appendix A, "Example Discrete I/O Throughput with Block Transfers
// Present": 115.2K baud; adapter #1 (1747-ASB) 12 groups from rack 0 group 0
// with 8- and 4-word BTs in rack 0 and a 2-word BT in rack 1; adapters #2 and
// #3 (1771-ASB) 1/4 rack each at rack 2 groups 0 and 2 with 64- and 32-word
// BTs; T_ps 25.0, T_adp 2(4.5) = 9.0, T_id 10.0, T_od 1.0 ms.
RioNetwork manual_example_2() {
    RioNetwork network;
    network.baud = RioBaud::b115_2k;
    network.processor_scan = 25000;
    network.adapter_delay = 9000;
    network.input_delay = 10000;
    network.output_delay = 1000;
    network.devices = {{0, 0, 12, false, "adapter #1"}, {2, 0, 2, false, "adapter #2"}, {2, 2, 2, false, "adapter #3"}};
    network.block_transfers = {{0, 8, ""}, {0, 4, ""}, {0, 4, ""}, {1, 2, ""}, {2, 64, ""}, {2, 32, ""}};
    return network;
}

// Appendix A, example without block transfers, steps 2-4: "T_RIO = 1(4.0 ms)
// + 2(5.5 ms) + 3(3.5 ms) = 25.5 ms", "there are 4 logical racks configured.
// Therefore: T_SNO = 7.0 ms", "T_dm-nbt = 132.0 ms".
TEST(RioExample, WithoutBlockTransfersReproducesTheManual) {
    const RioResult result = compute_rio(manual_example_1());
    EXPECT_EQ(result.t_rio, 25500);
    EXPECT_EQ(result.configured_racks, (std::vector<int>{0, 1, 2, 3}));
    EXPECT_EQ(result.t_sno.table, TsnoTable::without_m0_writes);
    EXPECT_EQ(result.t_sno.logical_racks, 4);
    EXPECT_EQ(result.t_sno.upd_gt_hold, true);
    EXPECT_EQ(result.t_sno.t_hold, 11000);
    EXPECT_EQ(result.t_sno.value, 7000);
    EXPECT_EQ(result.t_sni, 5000);
    EXPECT_EQ(result.t_btx, 0);
    EXPECT_FALSE(result.with_block_transfers);
    EXPECT_EQ(result.t_dm, 132000);
    EXPECT_FALSE(result.bt.has_value());
    EXPECT_TRUE(result.notes.empty());
}

// Appendix A, example with block transfers, steps 1-4: "T_SNO-bt = 22.0 ms
// ... There are 3 logical racks configured", "T_RIO = 1(5.5) + 1(4.0) +
// 2(3.5) = 16.5 ms", T_ri 4.7, 3.8 and 13.1 ms, "T_btX = 21.6 ms",
// "T_dm-bt = 173.2 ms".
TEST(RioExample, WithBlockTransfersReproducesTheManual) {
    const RioResult result = compute_rio(manual_example_2());
    ASSERT_EQ(result.logical_devices.size(), 4u);  // "3 adapters and 4 logical devices"
    EXPECT_EQ(result.t_rio, 16500);
    EXPECT_EQ(result.configured_racks, (std::vector<int>{0, 1, 2}));
    EXPECT_EQ(result.t_sno.table, TsnoTable::with_block_transfers);
    EXPECT_EQ(result.t_sno.value, 22000);
    EXPECT_FALSE(result.t_sno.t_hold.has_value());
    ASSERT_EQ(result.bt_racks.size(), 3u);
    EXPECT_EQ(result.bt_racks[0].rack, 0);
    EXPECT_EQ(result.bt_racks[0].max_words, 8);  // "maximum BT to rack 0 is 8 words"
    EXPECT_EQ(result.bt_racks[0].t_ri, 4700);
    EXPECT_EQ(result.bt_racks[0].block_transfers, (std::vector<std::size_t>{0, 1, 2}));
    EXPECT_EQ(result.bt_racks[1].max_words, 2);  // "maximum BT to rack 1 is 2 words"
    EXPECT_EQ(result.bt_racks[1].t_ri, 3800);
    EXPECT_EQ(result.bt_racks[2].max_words, 64);  // "maximum BT to rack 2 is 64 words"
    EXPECT_EQ(result.bt_racks[2].t_ri, 13100);
    EXPECT_EQ(result.t_btx, 21600);
    EXPECT_TRUE(result.with_block_transfers);
    EXPECT_EQ(result.t_dm, 173200);
}

// Appendix A, example with block transfers: adapter #1 uses "12 logical
// groups (1 1/2 logical racks)" from rack 0 group 0, and the example counts it
// as 1(5.5) + 1(4.0) in T_RIO: a full-rack logical device plus a half-rack one.
TEST(RioLogicalDevices, TwelveGroupAdapterIsAFullAndAHalfRack) {
    const auto logical = split_into_logical_devices(RioBaud::b115_2k, {{0, 0, 12, false, ""}});
    ASSERT_EQ(logical.size(), 2u);
    EXPECT_EQ(logical[0].rack, 0);
    EXPECT_EQ(logical[0].group, 0);
    EXPECT_EQ(logical[0].groups, 8);
    EXPECT_EQ(logical[0].t_rio, 5500);
    EXPECT_EQ(logical[1].rack, 1);
    EXPECT_EQ(logical[1].group, 0);
    EXPECT_EQ(logical[1].groups, 4);
    EXPECT_EQ(logical[1].t_rio, 4000);
}

// Chapter 4, "Creating More than One Logical Rack Device": an adapter at rack
// 0 group 0 using 14 words "contain[s] two logical devices".
TEST(RioLogicalDevices, FourteenWordAdapterIsTwoLogicalDevices) {
    const auto logical = split_into_logical_devices(RioBaud::b57_6k, {{0, 0, 14, false, ""}});
    ASSERT_EQ(logical.size(), 2u);
    EXPECT_EQ(logical[0].groups, 8);
    EXPECT_EQ(logical[1].groups, 6);
    EXPECT_EQ(logical[0].t_rio + logical[1].t_rio, 9500 + 7500);  // full + 3/4 at 57.6K
}

// Chapter 4, "Examples of Crossing Logical Rack Boundaries", example 2: an
// image smaller than a rack "consumes two groups in logical rack 0 and four
// groups in logical rack 1" when it starts at rack 0 group 6.
TEST(RioLogicalDevices, SmallAdapterCrossingARackBoundaryIsSplitAtTheBoundary) {
    const auto logical = split_into_logical_devices(RioBaud::b230_4k, {{0, 6, 6, false, ""}});
    ASSERT_EQ(logical.size(), 2u);
    EXPECT_EQ(logical[0].rack, 0);
    EXPECT_EQ(logical[0].group, 6);
    EXPECT_EQ(logical[0].groups, 2);
    EXPECT_EQ(logical[0].t_rio, 2500);  // 1/4 rack at 230.4K
    EXPECT_EQ(logical[1].rack, 1);
    EXPECT_EQ(logical[1].group, 0);
    EXPECT_EQ(logical[1].groups, 4);
    EXPECT_EQ(logical[1].t_rio, 2750);  // 1/2 rack at 230.4K
}

// Chapter 4, "Crossing Logical Rack Boundaries" (page 4-13): "the 1747-ASB image can be
// any size from two logical groups up to 32 logical groups (four logical
// racks)". The largest image is four full-rack logical devices.
TEST(RioLogicalDevices, ThirtyTwoGroupsAreFourFullRacks) {
    const auto logical = split_into_logical_devices(RioBaud::b57_6k, {{0, 0, 32, false, ""}});
    ASSERT_EQ(logical.size(), 4u);
    for (int rack = 0; rack < 4; ++rack) {
        EXPECT_EQ(logical[static_cast<std::size_t>(rack)].rack, rack);
        EXPECT_EQ(logical[static_cast<std::size_t>(rack)].groups, 8);
        EXPECT_EQ(logical[static_cast<std::size_t>(rack)].t_rio, 9500);
    }
}

// Appendix A, example with block transfers: adapter #1 is "1 1/2 logical
// racks", a full rack in rack 0 and a half rack in rack 1.
TEST(RioLogicalDevices, SplitNoteNamesEveryPart) {
    const RioResult result = compute_rio(manual_example_2());
    ASSERT_FALSE(result.notes.empty());
    EXPECT_EQ(result.notes[0],
              "devices[0] (12 groups from rack 0 group 0) crosses a logical rack boundary and is scanned as 2 "
              "logical devices: rack 0 groups 0-7 (full), rack 1 groups 0-3 (1/2).");
}

// Appendix A, "Determining the Number of Logical Racks Configured": "if there
// are four 1/4 rack devices in logical rack 0 and one full rack device in
// logical rack 3, there would be two logical racks configured".
TEST(RioLogicalRacks, CountsRacksThatHoldDevices) {
    RioNetwork network = manual_example_1();
    network.devices = {
        {0, 0, 2, false, ""}, {0, 2, 2, false, ""}, {0, 4, 2, false, ""}, {0, 6, 2, false, ""}, {3, 0, 8, false, ""}};
    const RioResult result = compute_rio(network);
    EXPECT_EQ(result.configured_racks, (std::vector<int>{0, 3}));
    EXPECT_EQ(result.t_sno.logical_racks, 2);
    EXPECT_EQ(result.t_sno.value, 4000);  // 2 logical racks, T_upd > T_hold, normal mode
    EXPECT_EQ(result.t_rio, 4 * 3500 + 5500);
}

// Appendix A, "RIO Scanner Output Delay Time (T_SNO) Tables": "If T_upd is
// less than T_hold, then the larger T_SNO number must be used"; the table
// columns read "T_SNO if T_upd <= T_hold" and "T_SNO if T_upd > T_hold". With
// a T_upd time the calculator compares it with the row's T_hold (11.0 ms for
// four racks, normal mode).
TEST(RioTsnoSelection, TupdTimeIsComparedWithTheRowsThold) {
    RioNetwork network = manual_example_1();
    network.t_upd_gt_t_hold.reset();
    network.t_upd = 25000;  // T_ps of the example
    EXPECT_EQ(compute_rio(network).t_sno.value, 7000);
    network.t_upd = 11001;
    EXPECT_EQ(compute_rio(network).t_sno.value, 7000);
    network.t_upd = 11000;  // equal: the "T_upd <= T_hold" column
    const RioResult at_hold = compute_rio(network);
    EXPECT_EQ(at_hold.t_sno.value, 11000);
    EXPECT_EQ(at_hold.t_sno.upd_gt_hold, false);
    EXPECT_EQ(at_hold.t_dm, 132000 - 7000 + 11000);
}

// Appendix A, "T_SNO without M0 File Writes", normal, 4 racks: 11.0 ms if
// T_upd <= T_hold (T_hold 11.0 ms), the figure that "must be used" when
// T_upd is below T_hold.
TEST(RioTsnoSelection, WithoutTupdTheLargerFigureIsUsedAndNoted) {
    RioNetwork network = manual_example_1();
    network.t_upd_gt_t_hold.reset();
    const RioResult result = compute_rio(network);
    EXPECT_EQ(result.t_sno.value, 11000);
    ASSERT_EQ(result.notes.size(), 1u);
    EXPECT_NE(result.notes[0].find("Neither t_upd_gt_t_hold nor t_upd_ms was given"), std::string::npos);
    EXPECT_NE(result.notes[0].find("T_hold = 11.0 ms"), std::string::npos);
}

// Appendix A, "T_SNo with M0 File Writes (No Block Transfers)", normal mode,
// 4 logical racks, T_upd > T_hold: 8.0 ms, so example 1 becomes 133.0 ms.
TEST(RioTsnoSelection, M0FileWritesSelectTheirTable) {
    RioNetwork network = manual_example_1();
    network.m0_file_writes = true;
    const RioResult result = compute_rio(network);
    EXPECT_EQ(result.t_sno.table, TsnoTable::with_m0_writes);
    EXPECT_EQ(result.t_sno.t_hold, 12000);
    EXPECT_EQ(result.t_sno.value, 8000);
    EXPECT_EQ(result.t_dm, 133000);
}

// Chapter 4, "Example G File Showing Primary and Complementary Device
// Configurations": five primary and five complementary devices. Appendix A,
// "Determining the Number of Logical Racks Configured": a primary rack and
// its complementary rack count as one, so this is 4 logical racks. At 57.6K,
// T_SNO without M0 writes, complementary, 4 racks: 15.0 ms if T_upd <=
// T_hold, 9.0 ms otherwise. T_RIO sums all ten logical devices: primary
// 3/4 + 1/4 + 3/4 + 1/4 + 1/4 = 7.5 + 6.0 + 7.5 + 6.0 + 6.0 = 33.0 ms,
// complementary 3/4 + 1/2 + 1/4 + 1/4 + 1/2 = 7.5 + 6.5 + 6.0 + 6.0 + 6.5 =
// 32.5 ms.
RioNetwork manual_complementary_example() {
    RioNetwork network;
    network.baud = RioBaud::b57_6k;
    network.mode = RioMode::complementary;
    network.processor_scan = 20000;
    network.adapter_delay = 9000;
    network.input_delay = 10000;
    network.output_delay = 1000;
    network.t_upd_gt_t_hold = false;
    network.devices = {
        {0, 2, 6, false, "device 1"}, {1, 6, 2, false, "device 2"}, {2, 0, 6, false, "device 3"},
        {3, 2, 2, false, "device 4"}, {3, 6, 2, false, "device 5"}, {0, 2, 6, true, "device 6"},
        {1, 0, 4, true, "device 7"},  {1, 6, 2, true, "device 8"},  {2, 0, 2, true, "device 9"},
        {3, 2, 4, true, "device 10"},
    };
    return network;
}

TEST(RioComplementary, ManualGFileExampleCountsPrimaryAndComplementaryRacksOnce) {
    RioNetwork network = manual_complementary_example();
    RioResult result = compute_rio(network);
    EXPECT_EQ(result.logical_devices.size(), 10u);
    EXPECT_EQ(result.configured_racks.size(), 4u);
    EXPECT_EQ(result.t_rio, 65500);
    EXPECT_EQ(result.t_sno.table, TsnoTable::without_m0_writes);
    EXPECT_EQ(result.t_sno.t_hold, 14000);
    EXPECT_EQ(result.t_sno.value, 15000);
    // 2(20.0) + 2(65.5) + 9.0 + 15.0 + 5.0 + 10.0 + 1.0 = 211.0 ms
    EXPECT_EQ(result.t_dm, 211000);

    network.t_upd_gt_t_hold = true;
    EXPECT_EQ(compute_rio(network).t_sno.value, 9000);
}

// Appendix A, "T_SNO without M0 File Writes", complementary, and "Determining
// T_SNo-bt", complementary: the baud rate selects the column ("a faster baud
// rate ... has an inverse affect on T_SNO").
TEST(RioComplementary, BaudRateSelectsTheComplementaryColumn) {
    RioNetwork network;
    network.mode = RioMode::complementary;
    network.devices = {{0, 0, 8, false, ""}, {0, 0, 8, true, ""}, {1, 0, 4, true, ""}};  // racks 0/8 and 9: two racks
    network.t_upd_gt_t_hold = false;
    const Micros expected_le[] = {9000, 10000, 12000};
    const Micros expected_gt[] = {5000, 6000, 7000};
    const Micros expected_bt[] = {23000, 27000, 36000};
    const RioBaud bauds[] = {RioBaud::b57_6k, RioBaud::b115_2k, RioBaud::b230_4k};
    for (std::size_t i = 0; i < 3; ++i) {
        network.baud = bauds[i];
        network.t_upd_gt_t_hold = false;
        network.block_transfers.clear();
        EXPECT_EQ(compute_rio(network).t_sno.value, expected_le[i]) << to_string(bauds[i]);
        network.t_upd_gt_t_hold = true;
        EXPECT_EQ(compute_rio(network).t_sno.value, expected_gt[i]) << to_string(bauds[i]);
        network.block_transfers = {{1, 16, ""}};
        EXPECT_EQ(compute_rio(network).t_sno.value, expected_bt[i]) << to_string(bauds[i]);
    }
}

// Appendix A, "Determining T_btX": "only the longest BT to that logical rack
// needs to be considered"; T_btX sums T_ri over the racks with BTs.
TEST(RioBlockTransfers, OnlyTheLongestBlockTransferPerRackCounts) {
    RioNetwork network = manual_example_2();
    network.block_transfers = {{0, 2, ""}, {0, 40, ""}, {0, 10, ""}};
    const RioResult result = compute_rio(network);
    ASSERT_EQ(result.bt_racks.size(), 1u);
    EXPECT_EQ(result.bt_racks[0].max_words, 40);
    EXPECT_EQ(result.t_btx, 150 * 40 + 3500);  // 0.150 x 40 + 3.5 = 9.5 ms
}

// Chapter 5, "Requested Word Count": 0 reserves 64 words; appendix A T_ri at
// 115.2K: 0.150 x 64 + 3.5 = 13.1 ms.
TEST(RioBlockTransfers, ZeroWordRequestIsChargedAsSixtyFourAndNoted) {
    RioNetwork network = manual_example_2();
    network.block_transfers = {{2, 0, ""}};
    const RioResult result = compute_rio(network);
    EXPECT_EQ(result.bt_racks[0].max_words, 64);
    EXPECT_EQ(result.t_btx, 13100);
    bool noted = false;
    for (const std::string& note : result.notes) noted |= note.find("block_transfers[0] requests 0 words") == 0;
    EXPECT_TRUE(noted);
}

// Appendix A, "Block Transfer Throughput":
//   T_bt   = T_M0 + T_SNo-bt(number of BTs + 1) + T_btwait + 2T_RIO + 2T_btx + T_adp-bt + T_ps
//   T_free = T_M0 + T_SNo-bt(number of BTs) + T_ps
// The manual has no worked example. On example 2 (6 BTs, T_SNo-bt 22.0,
// T_RIO 16.5, T_btx 21.6, T_ps 25.0) with T_M0 = 0.5 ms and T_adp-bt = 4.5 ms
// (one 1747-ASB backplane scan, "2(4.5)" in the example being two):
//   base   = 0.5 + 22.0 x 7 + 2 x 16.5 + 2 x 21.6 + 4.5 + 25.0 = 260.2 ms
//   rack 0 (3 BTs): T_btwait = 2 x 260.2 + 22.0 = 542.4, T_bt = 802.6 ms
//   rack 1 (1 BT):  T_btwait = 0 ("If multiple BTs are not being performed
//                   to the same logical rack, this value equals zero"), T_bt = 260.2 ms
//   rack 2 (2 BTs): T_btwait = 260.2 + 22.0 = 282.2, T_bt = 542.4 ms
//   T_free = 0.5 + 22.0 x 6 + 25.0 = 157.5 ms
TEST(RioBlockTransfers, BlockTransferThroughputFollowsTheFormula) {
    RioNetwork network = manual_example_2();
    network.bt_times = RioBtTimes{500, 4500};
    const RioResult result = compute_rio(network);
    ASSERT_TRUE(result.bt.has_value());
    const auto& per_bt = result.bt->per_block_transfer;
    ASSERT_EQ(per_bt.size(), 6u);
    for (std::size_t i = 0; i < per_bt.size(); ++i) EXPECT_EQ(per_bt[i].block_transfer, i);
    for (std::size_t i : {0u, 1u, 2u}) {
        EXPECT_EQ(per_bt[i].t_btwait, 542400);
        EXPECT_EQ(per_bt[i].t_bt, 802600);
    }
    EXPECT_EQ(per_bt[3].t_btwait, 0);
    EXPECT_EQ(per_bt[3].t_bt, 260200);
    for (std::size_t i : {4u, 5u}) {
        EXPECT_EQ(per_bt[i].t_btwait, 282200);
        EXPECT_EQ(per_bt[i].t_bt, 542400);
    }
    EXPECT_EQ(per_bt[4].words, 64);
    EXPECT_EQ(result.bt->buffer_free, 157500);
    // The discrete figures do not change.
    EXPECT_EQ(result.t_dm, 173200);
}

// Appendix A, "Block Transfer Throughput": T_M0 comes from appendix B and
// T_adp-bt from the adapter manual, so the user must supply both.
TEST(RioBlockTransfers, MissingBtTimesAreNotedInsteadOfGuessed) {
    const RioResult result = compute_rio(manual_example_2());
    EXPECT_FALSE(result.bt.has_value());
    ASSERT_EQ(result.notes.size(), 2u);
    EXPECT_NE(result.notes[1].find("needs m0_write_ms (T_M0) and adapter_bt_delay_ms (T_adp-bt)"), std::string::npos);
}

// Appendix A, "Determining T_SNo-bt": no T_upd columns; 3 racks, normal: 22.0 ms.
TEST(RioBlockTransfers, TupdInputsAreNotUsedWithBlockTransfers) {
    RioNetwork network = manual_example_2();
    network.t_upd_gt_t_hold = false;
    const RioResult result = compute_rio(network);
    EXPECT_EQ(result.t_sno.value, 22000);
    EXPECT_FALSE(result.t_sno.upd_gt_hold.has_value());
    bool noted = false;
    for (const std::string& note : result.notes)
        noted |= note.find("T_SNo-bt table, which has no T_upd") != std::string::npos;
    EXPECT_TRUE(noted);
}

// The typed API validates as the JSON front end does, with the same paths.
TEST(RioValidation, TypedApiNamesTheField) {
    EXPECT_NO_THROW(validate_rio(manual_example_1()));
    RioNetwork network = manual_example_1();
    network.devices[2].rack = 5;
    try {
        validate_rio(network);
        ADD_FAILURE() << "no error";
    } catch (const ConfigError& error) {
        EXPECT_EQ(error.path(), "devices[2].rack");
        EXPECT_STREQ(error.what(), "devices[2].rack: expected a logical rack 0..3, got 5");
    }
    network = manual_example_1();
    network.processor_scan = -1;
    EXPECT_THROW(compute_rio(network), ConfigError);
}

// Appendix A, example with block transfers, computed twice.
TEST(RioDeterminism, SameNetworkSameFigures) {
    const RioResult a = compute_rio(manual_example_2());
    const RioResult b = compute_rio(manual_example_2());
    EXPECT_EQ(a.t_dm, b.t_dm);
    EXPECT_EQ(a.notes, b.notes);
}

}  // namespace
}  // namespace softslc::throughput
