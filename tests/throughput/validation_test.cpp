// Every configuration error compute_throughput() reports: the JSON path it
// names and the message. The rules come from the 1747-SN manual
// (seeds/000_6bdfccac32889807.txt) chapters 1, 4 and 5 and the AutoMax
// manual (seeds/004_b6b94227d784095f.txt) sections 4.3 and 4.4; each test
// names its rule.
#include <gtest/gtest.h>

#include <string>

#include <nlohmann/json.hpp>

#include "modules/throughput/throughput_json.h"

namespace softslc::throughput {
namespace {

using nlohmann::json;

// A valid RIO config (the manual's first worked example) to break one field
// at a time.
json rio_config() {
    return json::parse(R"({
        "network": "rio", "baud": "115.2K", "mode": "normal",
        "processor_scan_ms": 25.0, "adapter_delay_ms": 8.0, "input_delay_ms": 10.0, "output_delay_ms": 1.0,
        "t_upd_gt_t_hold": true,
        "devices": [
            {"rack": 0, "group": 0, "size": "1/2"},
            {"rack": 1, "group": 0, "size": "full"},
            {"rack": 2, "group": 0, "size": "full"},
            {"rack": 3, "group": 0, "size": "1/4"},
            {"rack": 3, "group": 2, "size": "1/4"},
            {"rack": 3, "group": 4, "size": "1/4"}
        ]
    })");
}

json automax_config() {
    return json::parse(R"({
        "network": "automax",
        "drops": [
            {"type": "multibus", "registers": 13},
            {"type": "multibus", "registers": 11},
            {"type": "head_57c330", "outputs": 5, "inputs": 6},
            {"type": "shark_digital"}
        ]
    })");
}

// Runs the config and checks that it fails at `path` with a message that
// contains `message`; what() must read "path: message...".
void expect_error(const json& config, const std::string& path, const std::string& message) {
    try {
        compute_throughput(config);
        ADD_FAILURE() << "no error; expected " << path << ": " << message;
    } catch (const ConfigError& error) {
        EXPECT_EQ(error.path(), path) << error.what();
        const std::string what = error.what();
        EXPECT_EQ(what.rfind((path.empty() ? std::string("(config)") : path) + ": ", 0), 0u) << what;
        EXPECT_NE(what.find(message), std::string::npos) << what;
    }
}

// The two networks: "rio" (1747-SN appendix A) and "automax" (section 4.5).
TEST(ThroughputConfigErrors, DocumentAndNetwork) {
    expect_error(json::array(), "", "expected a JSON object, got an array");
    expect_error(json::object(), "network", "required; expected one of \"rio\",\"automax\"");
    json config = rio_config();
    config["network"] = "devicenet";
    expect_error(config, "network", "expected one of \"rio\",\"automax\", got \"devicenet\"");
}

// The manuals' worked examples are valid configs.
TEST(ThroughputConfigErrors, ValidExamplesPass) {
    EXPECT_NO_THROW(compute_throughput(rio_config()));
    EXPECT_NO_THROW(compute_throughput(automax_config()));
}

// A misspelt key would silently drop a figure of the appendix A formula.
TEST(RioConfigErrors, UnknownKeysAreRejected) {
    json config = rio_config();
    config["processor_scan"] = 25.0;
    expect_error(config, "processor_scan", "unknown key");
    config = rio_config();
    config["devices"][1]["slot"] = 3;
    expect_error(config, "devices[1].slot", "unknown key");
    config = rio_config();
    config["name"] = "labels are allowed";
    config["comment"] = "so are comments";
    config["devices"][0]["name"] = "1747-ASB";
    EXPECT_NO_THROW(compute_throughput(config));
    config["name"] = 5;
    expect_error(config, "name", "expected a string, got 5");
    config["name"] = "x";
    config["devices"][0]["name"] = false;
    expect_error(config, "devices[0].name", "expected a string, got false");
}

// Table A.1: the scanner runs at 57.6K, 115.2K or 230.4K baud.
TEST(RioConfigErrors, BaudRate) {
    json config = rio_config();
    config.erase("baud");
    expect_error(config, "baud", "required; expected one of \"57.6K\",\"115.2K\",\"230.4K\"");
    config["baud"] = "19.2K";
    expect_error(config, "baud", "expected one of \"57.6K\",\"115.2K\",\"230.4K\", got \"19.2K\"");
    config["baud"] = 115.2;
    expect_error(config, "baud", "expected one of \"57.6K\",\"115.2K\",\"230.4K\", got 115.2");
}

// Chapter 1, "Complementary I/O": normal or complementary mode.
TEST(RioConfigErrors, Mode) {
    json config = rio_config();
    config["mode"] = "primary";
    expect_error(config, "mode", "expected one of \"normal\",\"complementary\", got \"primary\"");
    config.erase("mode");  // normal by default
    EXPECT_DOUBLE_EQ(compute_throughput(config)["t_dm_nbt_ms"].get<double>(), 132.0);
}

// Appendix A: T_ps, T_adp, T_id, T_od are times in milliseconds.
TEST(RioConfigErrors, Times) {
    json config = rio_config();
    config.erase("processor_scan_ms");
    expect_error(config, "processor_scan_ms", "required; expected a time in milliseconds");
    config["processor_scan_ms"] = "25";
    expect_error(config, "processor_scan_ms", "expected a time in milliseconds (a number), got \"25\"");
    config["processor_scan_ms"] = 2e6;
    expect_error(config, "processor_scan_ms", "expected a time of at most 1000000 ms");
    config = rio_config();
    config["adapter_delay_ms"] = -1.0;
    expect_error(config, "adapter_delay_ms", "expected a time of 0 ms or more");
    config = rio_config();
    config["input_delay_ms"] = -0.5;
    expect_error(config, "input_delay_ms", "expected a time of 0 ms or more");
    config = rio_config();
    config["output_delay_ms"] = nullptr;
    expect_error(config, "output_delay_ms", "expected a time in milliseconds (a number), got null");
}

// Appendix A, "RIO Scanner Output Delay Time (T_SNO) Tables": T_upd is given
// one way or the other.
TEST(RioConfigErrors, Tupd) {
    json config = rio_config();
    config["t_upd_gt_t_hold"] = "yes";
    expect_error(config, "t_upd_gt_t_hold", "expected true or false, got \"yes\"");
    config = rio_config();
    config["t_upd_ms"] = 25.0;
    expect_error(config, "t_upd_ms", "give either t_upd_gt_t_hold or t_upd_ms, not both");
    config.erase("t_upd_gt_t_hold");
    config["t_upd_ms"] = -2.0;
    expect_error(config, "t_upd_ms", "expected a time of 0 ms or more");
    config = rio_config();
    config["m0_file_writes"] = 1;
    expect_error(config, "m0_file_writes", "expected true or false, got 1");
}

// Appendix A: T_RIO needs at least one logical device.
TEST(RioConfigErrors, DeviceList) {
    json config = rio_config();
    config.erase("devices");
    expect_error(config, "devices", "required; expected an array of devices");
    config["devices"] = json::object();
    expect_error(config, "devices", "expected an array, got an object");
    config["devices"] = json::array();
    expect_error(config, "devices", "expected at least one device");
    config["devices"] = json::array({7});
    expect_error(config, "devices[0]", "expected a JSON object, got 7");
}

// Chapter 1, "Scanner I/O Image Concepts" (page 1-6): devices are a quarter, half,
// three-quarter or full logical rack, or (via "groups") any even number of
// groups up to 32.
TEST(RioConfigErrors, DeviceSize) {
    json config = rio_config();
    config["devices"][2]["size"] = "7/8";
    expect_error(config, "devices[2].size", "expected one of \"1/4\",\"1/2\",\"3/4\",\"full\", got \"7/8\"");
    config = rio_config();
    config["devices"][0]["groups"] = 4;
    expect_error(config, "devices[0].groups", "give either size or groups, not both");
    config = rio_config();
    config["devices"][0].erase("size");
    expect_error(config, "devices[0]", "expected a size (one of \"1/4\",\"1/2\",\"3/4\",\"full\") or a groups count");
    for (int groups : {0, 7, 34, -2}) {
        config = rio_config();
        config["devices"][0].erase("size");
        config["devices"][0]["groups"] = groups;
        expect_error(config, "devices[0].groups",
                     "expected an even number of groups from 2 to 32, got " + std::to_string(groups));
    }
    config = rio_config();
    config["devices"][0].erase("size");
    config["devices"][0]["groups"] = 4.5;
    expect_error(config, "devices[0].groups", "expected an integer, got 4.5");
}

// Chapter 4, "Rules for Configuring the Scanner" (page 4-7): logical racks
// 0..3, starting groups 0, 2, 4 or 6 ("A logical device's starting group
// must begin at even group numbers").
TEST(RioConfigErrors, DeviceAddress) {
    json config = rio_config();
    config["devices"][3]["rack"] = 4;
    expect_error(config, "devices[3].rack", "expected a logical rack 0..3, got 4");
    config["devices"][3]["rack"] = 9;
    expect_error(config, "devices[3].rack", "give a complementary device its primary rack number");
    config["devices"][3]["rack"] = -1;
    expect_error(config, "devices[3].rack", "expected a logical rack 0..3, got -1");
    config = rio_config();
    config["devices"][3]["group"] = 8;
    expect_error(config, "devices[3].group", "expected a logical group 0..7, got 8");
    config["devices"][3]["group"] = 3;
    expect_error(config, "devices[3].group", "a logical device starts at an even group (0, 2, 4 or 6), got 3");
    config = rio_config();
    config["devices"][0]["rack"] = 1.5;
    expect_error(config, "devices[0].rack", "expected an integer, got 1.5");
    config["devices"][0]["rack"] = "0";
    expect_error(config, "devices[0].rack", "expected an integer, got \"0\"");
    config["devices"][0]["rack"] = 4294967296LL;
    expect_error(config, "devices[0].rack", "integer out of range");
    config = rio_config();
    config["devices"][0].erase("group");
    expect_error(config, "devices[0].group", "required; expected an integer");
}

// Chapter 4, "Crossing Logical Rack Boundaries" (page 4-13): an image may cross into the
// next rack, but the scanner image ends at rack 3 group 7.
TEST(RioConfigErrors, DeviceMustFitTheScannerImage) {
    json config = rio_config();
    config["devices"] = json::parse(R"([{"rack": 3, "group": 2, "size": "full"}])");
    expect_error(config, "devices[0]", "8 groups starting at rack 3 group 2 run past rack 3 group 7");
    config["devices"] = json::parse(R"([{"rack": 1, "group": 2, "groups": 24}])");
    expect_error(config, "devices[0]", "24 groups starting at rack 1 group 2 run past rack 3 group 7");
    config["devices"] = json::parse(R"([{"rack": 0, "group": 2, "size": "full"}])");  // crosses into rack 1: fine
    EXPECT_NO_THROW(compute_throughput(config));
}

// Chapter 4, "Rules for Configuring the Scanner": each group of an image
// belongs to one device.
TEST(RioConfigErrors, OverlappingDevices) {
    json config = rio_config();
    config["devices"][4]["group"] = 0;
    expect_error(config, "devices[4]", "overlaps devices[3] in the normal image at rack 3 groups 0-1");
    config = rio_config();
    config["devices"][0].erase("size");
    config["devices"][0]["groups"] = 10;  // now runs into rack 1, which devices[1] holds
    expect_error(config, "devices[1]", "overlaps devices[0] in the normal image at rack 1 groups 0-1");
}

// Chapter 1, "Complementary I/O" (page 1-10), and chapter 4, "Concerning Complementary
// I/O": complementary devices need complementary mode, and may share image
// space with a primary device only when both start at the same location.
TEST(RioConfigErrors, ComplementaryDevices) {
    json config = rio_config();
    config["devices"][0]["complementary"] = true;
    expect_error(config, "devices[0].complementary", "complementary devices need \"mode\": \"complementary\"");
    config["devices"][0]["complementary"] = "yes";
    expect_error(config, "devices[0].complementary", "expected true or false, got \"yes\"");

    config = rio_config();
    config["mode"] = "complementary";
    config["devices"].push_back({{"rack", 3}, {"group", 2}, {"size", "1/4"}, {"complementary", true}});
    config["devices"].push_back({{"rack", 3}, {"group", 2}, {"size", "1/4"}, {"complementary", true}});
    expect_error(config, "devices[7]", "overlaps devices[6] in the complementary image at rack 3 groups 2-3");
}

// Chapter 4, "Illegal Configuration Examples", on the manual's example G
// file: "Having a primary device configured at Logical Rack 1, Logical Group
// 2 ... would be illegal since this image space is already being used by a
// complementary device. Having a complementary device configured at Logical
// Rack 10, Logical Group 2 ... would also be illegal since this image space is
// already being used by a primary device."
TEST(RioConfigErrors, ManualIllegalComplementaryExamples) {
    const json legal = json::parse(R"({
        "network": "rio", "baud": "57.6K", "mode": "complementary",
        "processor_scan_ms": 20, "adapter_delay_ms": 9, "input_delay_ms": 10, "output_delay_ms": 1,
        "devices": [
            {"rack": 0, "group": 2, "size": "3/4"},
            {"rack": 1, "group": 6, "size": "1/4"},
            {"rack": 2, "group": 0, "size": "3/4"},
            {"rack": 3, "group": 2, "size": "1/4"},
            {"rack": 3, "group": 6, "size": "1/4"},
            {"rack": 0, "group": 2, "size": "3/4", "complementary": true},
            {"rack": 1, "group": 0, "size": "1/2", "complementary": true},
            {"rack": 1, "group": 6, "size": "1/4", "complementary": true},
            {"rack": 2, "group": 0, "size": "1/4", "complementary": true},
            {"rack": 3, "group": 2, "size": "1/2", "complementary": true}
        ]
    })");
    EXPECT_NO_THROW(compute_throughput(legal));

    json config = legal;
    config["devices"].push_back({{"rack", 1}, {"group", 2}, {"size", "1/4"}});
    expect_error(config, "devices[10]",
                 "complementary devices[6] (rack 1 groups 0-3) overlaps primary devices[10] (rack 1 groups 2-3) but "
                 "they start at different groups");

    config = legal;
    config["devices"].push_back({{"rack", 2}, {"group", 2}, {"size", "1/4"}, {"complementary", true}});
    expect_error(config, "devices[10]",
                 "complementary devices[10] (rack 2 groups 2-3) overlaps primary devices[2] (rack 2 groups 0-5) "
                 "but they start at different groups");
}

// Chapter 5: "A total of 32 block transfer buffers are available", "up to 64
// words"; appendix A: T_ri is per logical rack, so the rack must hold a device.
TEST(RioConfigErrors, BlockTransfers) {
    json config = rio_config();
    config["block_transfers"] = json::object();
    expect_error(config, "block_transfers", "expected an array, got an object");
    config["block_transfers"] = json::parse(R"([{"rack": 0, "words": 65}])");
    expect_error(config, "block_transfers[0].words", "expected a block transfer length of 0..64 words, got 65");
    config["block_transfers"] = json::parse(R"([{"rack": 0, "words": -1}])");
    expect_error(config, "block_transfers[0].words", "expected a block transfer length of 0..64 words, got -1");
    config["block_transfers"] = json::parse(R"([{"rack": 0, "words": 8}, {"rack": 4, "words": 8}])");
    expect_error(config, "block_transfers[1].rack", "expected a logical rack 0..3, got 4");
    config["block_transfers"] = json::parse(R"([{"rack": 0, "words": 8, "slot": 2}])");
    expect_error(config, "block_transfers[0].slot", "unknown key");
    config["block_transfers"] = json::parse(R"([{"rack": 0}])");
    expect_error(config, "block_transfers[0].words", "required; expected an integer");
    config["block_transfers"] = json::parse(R"(["bt"])");
    expect_error(config, "block_transfers[0]", "expected a JSON object, got \"bt\"");

    config["devices"] = json::parse(R"([{"rack": 0, "group": 0, "size": "full"}])");
    config["block_transfers"] = json::parse(R"([{"rack": 2, "words": 8}])");
    expect_error(config, "block_transfers[0].rack", "no device is configured in logical rack 2");

    config["block_transfers"] = json::array();
    for (int i = 0; i < 33; ++i) config["block_transfers"].push_back({{"rack", 0}, {"words", 1}});
    expect_error(config, "block_transfers", "at most 32 block transfers (the scanner has 32 BT buffers), got 33");
    config["block_transfers"].erase(0);
    EXPECT_NO_THROW(compute_throughput(config));
}

// Appendix A, "Block Transfer Throughput" needs both T_M0 and T_adp-bt.
TEST(RioConfigErrors, BlockTransferTimesComeTogether) {
    json config = rio_config();
    config["m0_write_ms"] = 0.5;
    expect_error(config, "adapter_bt_delay_ms", "required together with m0_write_ms");
    config.erase("m0_write_ms");
    config["adapter_bt_delay_ms"] = 4.5;
    expect_error(config, "m0_write_ms", "required together with adapter_bt_delay_ms");
    config["m0_write_ms"] = -0.5;
    expect_error(config, "m0_write_ms", "expected a time of 0 ms or more");
}

// Section 4.5: the update period sums the drops of the network.
TEST(AutomaxConfigErrors, DropList) {
    json config = automax_config();
    config.erase("drops");
    expect_error(config, "drops", "required; expected an array of drops");
    config["drops"] = json::array();
    expect_error(config, "drops", "expected at least one drop");
    config["drops"] = "multibus";
    expect_error(config, "drops", "expected an array, got \"multibus\"");
    config = automax_config();
    config["baud"] = "57.6K";
    expect_error(config, "baud", "unknown key");
}

// Section 4.5 gives formulas for six drop kinds only.
TEST(AutomaxConfigErrors, DropType) {
    json config = automax_config();
    config["drops"][3].erase("type");
    expect_error(config, "drops[3].type",
                 "required; expected one of \"multibus\",\"head_57c330\",\"head_57c328\",\"drive_head\","
                 "\"shark_digital\",\"shark_mixed\"");
    config["drops"][3]["type"] = "shark";
    expect_error(config, "drops[3].type", "got \"shark\"");
}

// Section 4.5: each formula takes its own counts, and only those.
TEST(AutomaxConfigErrors, DropCounts) {
    json config = automax_config();
    config["drops"][0].erase("registers");
    expect_error(config, "drops[0].registers", "required; expected an integer (required for a \"multibus\" drop)");
    config = automax_config();
    config["drops"][0]["rails"] = 2;
    expect_error(config, "drops[0].rails",
                 "unknown key; a \"multibus\" drop takes type, drop, registers, name and comment");
    config = automax_config();
    config["drops"][3]["registers"] = 2;
    expect_error(config, "drops[3].registers", "a \"shark_digital\" drop takes type, drop, name and comment");
    config = automax_config();
    config["drops"][0]["registers"] = -1;
    expect_error(config, "drops[0].registers", "expected 0 or more, got -1");
    config = automax_config();
    config["drops"][2]["inputs"] = 2.5;
    expect_error(config, "drops[2].inputs", "expected an integer, got 2.5");
    config = automax_config();
    config["drops"][2]["outputs"] = -3;
    expect_error(config, "drops[2].outputs", "expected 0 or more, got -3");
}

// Section 4.3: the 57C328 head has four input/output register pairs, one per
// rail.
TEST(AutomaxConfigErrors, RailsAtMostFour) {
    json config = automax_config();
    config["drops"][0] = {{"type", "head_57c328"}, {"rails", 5}};
    expect_error(config, "drops[0].rails", "expected at most 4, got 5");
    config["drops"][0]["rails"] = 4;
    EXPECT_NO_THROW(compute_throughput(config));
}

// Section 4.4: "You can assign Multibus slave drop numbers (1 through 7) or
// (9 through F for Shark digital racks) arbitrarily, but each drop must have
// a unique number"; section 4.5 ties mixed Shark racks to drops 1 to 7.
TEST(AutomaxConfigErrors, DropNumbers) {
    json config = automax_config();
    config["drops"][1]["drop"] = 2;
    expect_error(config, "drops[0].drop", "give a drop number for every drop or for none");

    config = automax_config();
    for (int i = 0; i < 4; ++i) config["drops"][static_cast<std::size_t>(i)]["drop"] = i + 1;
    expect_error(config, "drops[3].drop", "a shark_digital drop is numbered 9..15 (hex 9..F), got 4");
    config["drops"][3]["drop"] = "F";
    EXPECT_EQ(compute_throughput(config)["drops"][3]["drop"], 15);
    config["drops"][3]["drop"] = "f";
    EXPECT_EQ(compute_throughput(config)["drops"][3]["drop"], 15);
    config["drops"][3]["drop"] = "G";
    expect_error(config, "drops[3].drop", "expected a drop number 1..7 or 9..15 (hex 9..F), got \"G\"");
    config["drops"][3]["drop"] = "10";
    expect_error(config, "drops[3].drop", "expected a drop number 1..7 or 9..15 (hex 9..F), got \"10\"");
    config["drops"][3]["drop"] = 9;
    config["drops"][0]["drop"] = 9;
    expect_error(config, "drops[0].drop", "a multibus drop is numbered 1..7, got 9");
    config["drops"][0]["drop"] = 0;
    expect_error(config, "drops[0].drop", "a multibus drop is numbered 1..7, got 0");
    config["drops"][0]["drop"] = 2;
    expect_error(config, "drops[1].drop", "drop number 2 is used twice");
    config["drops"][0]["drop"] = 1;
    config["drops"][2]["drop"] = 9;
    expect_error(config, "drops[2].drop", "a head_57c330 drop is numbered 1..7, got 9");
    config["drops"][2]["drop"] = 3;
    config["drops"].push_back({{"type", "shark_digital"}, {"drop", "9"}});
    expect_error(config, "drops[4].drop", "drop number 9 is used twice");
    config["drops"][4]["drop"] = 12;
    EXPECT_NO_THROW(compute_throughput(config));
    config["drops"][4]["drop"] = 12;
    config["drops"][3]["drop"] = "C";
    expect_error(config, "drops[4].drop", "drop number 12 (hex C) is used twice");
}

// Section 4.4: drop numbers 1..7, and 9..F for digital Shark racks.
TEST(AutomaxConfigErrors, TooManyDropsForTheNumbers) {
    json config = automax_config();
    config["drops"] = json::array();
    for (int i = 0; i < 8; ++i) config["drops"].push_back({{"type", "multibus"}, {"registers", 1}});
    expect_error(config, "drops", "more than 7 drops use drop numbers 1..7");
    config["drops"] = json::array();
    for (int i = 0; i < 8; ++i) config["drops"].push_back({{"type", "shark_digital"}});
    expect_error(config, "drops", "more than 7 drops use drop numbers 9..15 (hex 9..F)");
    config["drops"].erase(0);
    for (int i = 0; i < 7; ++i) config["drops"].push_back({{"type", "shark_mixed"}});
    EXPECT_NO_THROW(compute_throughput(config));
}

}  // namespace
}  // namespace softslc::throughput
