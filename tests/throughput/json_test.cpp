// The JSON front end and the text report, on the example configs in
// examples/throughput/ (the manuals' worked examples). Expected figures are
// the manuals': the 1747-SN manual appendix A (seeds/000_6bdfccac32889807.txt)
// and the AutoMax manual section 4.5 (seeds/004_b6b94227d784095f.txt), with
// the AutoMax figures by its formulas (see automax_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "modules/throughput/throughput_json.h"

namespace softslc::throughput {
namespace {

using nlohmann::json;

json load_example(const std::string& name) {
    const std::string path = std::string(SOFTSLC_SOURCE_DIR) + "/examples/throughput/" + name;
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cannot open " + path);
    return json::parse(in);
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

// Appendix A, example without block transfers: T_RIO 25.5 ms, T_SNO 7.0 ms,
// step 4 "T_dm-nbt = 2(25.0) + 2(25.5) + 8.0 + 7.0 + 5.0 + 10.0 + 1.0",
// "T_dm-nbt = 132.0 ms".
TEST(ThroughputJson, RioExample1) {
    const json result = compute_throughput(load_example("rio_example1.json"));
    EXPECT_EQ(result["network"], "rio");
    EXPECT_EQ(result["t_rio_ms"].dump(), "25.5");
    EXPECT_EQ(result["t_sno_ms"].dump(), "7.0");
    EXPECT_EQ(result["t_sni_ms"].dump(), "5.0");
    EXPECT_EQ(result["t_btx_ms"].dump(), "0.0");
    EXPECT_EQ(result["t_dm_nbt_ms"].dump(), "132.0");
    EXPECT_FALSE(result.contains("t_dm_bt_ms"));
    EXPECT_EQ(result["calculation"], "2(25.0) + 2(25.5) + 8.0 + 7.0 + 5.0 + 10.0 + 1.0");
    EXPECT_EQ(result["formula"], "T_dm-nbt = 2T_ps + 2T_RIO + T_adp + T_SNO + T_SNI + T_id + T_od");
    EXPECT_EQ(result["logical_racks_configured"], 4);
    // "Find T_SNO on page A-14 in the table T_SNO without M0 File Writes
    // (Normal Mode). For this example T_upd > T_hold, and there are 4 logical
    // racks configured."
    EXPECT_EQ(result["t_sno"]["table"], "T_SNO without M0 File Writes");
    EXPECT_EQ(result["t_sno"]["mode"], "normal");
    EXPECT_EQ(result["t_sno"]["column"], "all baud rates");
    EXPECT_EQ(result["t_sno"]["logical_racks"], 4);
    EXPECT_EQ(result["t_sno"]["t_upd"], "T_upd > T_hold");
    EXPECT_EQ(result["t_sno"]["t_hold_ms"].dump(), "11.0");
    // "T_RIO = 1(4.0 ms) + 2(5.5 ms) + 3(3.5 ms)"
    const json& devices = result["logical_devices"];
    ASSERT_EQ(devices.size(), 6u);
    const std::vector<std::string> sizes{"1/2", "full", "full", "1/4", "1/4", "1/4"};
    const std::vector<std::string> times{"4.0", "5.5", "5.5", "3.5", "3.5", "3.5"};
    for (std::size_t i = 0; i < devices.size(); ++i) {
        EXPECT_EQ(devices[i]["size"], sizes[i]);
        EXPECT_EQ(devices[i]["t_rio_ms"].dump(), times[i]);
        EXPECT_EQ(devices[i]["image"], "normal");
    }
    EXPECT_EQ(result["notes"], json::array());
}

// Appendix A, example with block transfers: "T_RIO = 1(5.5) + 1(4.0) +
// 2(3.5) = 16.5 ms", T_ri 4.7, 3.8, 13.1 ms, "T_btX = 21.6 ms",
// "T_SNO-bt = 22.0 ms", step 4 "T_dm-bt = 2(25.0) + 2(16.5) + 2(21.6) + 9.0 +
// 22.0 + 5.0 + 10.0 + 1.0", "T_dm-bt = 173.2 ms".
TEST(ThroughputJson, RioExample2WithBlockTransfers) {
    const json result = compute_throughput(load_example("rio_example2_bt.json"));
    EXPECT_EQ(result["t_rio_ms"].dump(), "16.5");
    EXPECT_EQ(result["t_btx_ms"].dump(), "21.6");
    EXPECT_EQ(result["t_sno_ms"].dump(), "22.0");
    EXPECT_EQ(result["t_dm_bt_ms"].dump(), "173.2");
    EXPECT_FALSE(result.contains("t_dm_nbt_ms"));
    EXPECT_EQ(result["calculation"], "2(25.0) + 2(16.5) + 2(21.6) + 9.0 + 22.0 + 5.0 + 10.0 + 1.0");
    EXPECT_EQ(result["formula"], "T_dm-bt = 2T_ps + 2T_RIO + 2T_btx + T_adp + T_SNO-bt + T_SNI + T_id + T_od");
    EXPECT_EQ(result["t_sno"]["symbol"], "T_SNo-bt");
    EXPECT_EQ(result["t_sno"]["logical_racks"], 3);
    EXPECT_FALSE(result["t_sno"].contains("t_hold_ms"));
    const json& racks = result["block_transfer_racks"];
    ASSERT_EQ(racks.size(), 3u);
    EXPECT_EQ(racks[0]["t_ri_ms"].dump(), "4.7");
    EXPECT_EQ(racks[1]["t_ri_ms"].dump(), "3.8");
    EXPECT_EQ(racks[2]["t_ri_ms"].dump(), "13.1");
    EXPECT_EQ(racks[2]["max_words"], 64);
    EXPECT_EQ(racks[2]["block_transfers"], json::array({4, 5}));
    // "a full-rack device plus a half-rack device" for adapter #1.
    const json& devices = result["logical_devices"];
    ASSERT_EQ(devices.size(), 4u);
    EXPECT_EQ(devices[0]["device"], 0);
    EXPECT_EQ(devices[0]["size"], "full");
    EXPECT_EQ(devices[1]["device"], 0);
    EXPECT_EQ(devices[1]["rack"], 1);
    EXPECT_EQ(devices[1]["size"], "1/2");
    EXPECT_EQ(devices[0]["name"], "Adapter #1 (1747-ASB), 1 1/2 logical racks");
    ASSERT_EQ(result["notes"].size(), 2u);
    EXPECT_TRUE(contains(result["notes"][0], "devices[0] (12 groups from rack 0 group 0)"));
}

// Block-transfer throughput in JSON, on the figures of the hand calculation
// in rio_compute_test.cpp (appendix A, "Block Transfer Throughput").
TEST(ThroughputJson, RioBlockTransferThroughput) {
    json config = load_example("rio_example2_bt.json");
    config["m0_write_ms"] = 0.5;
    config["adapter_bt_delay_ms"] = 4.5;
    const json result = compute_throughput(config);
    const json& bt = result.at("block_transfer_throughput");
    EXPECT_EQ(bt["t_m0_ms"].dump(), "0.5");
    EXPECT_EQ(bt["t_adp_bt_ms"].dump(), "4.5");
    EXPECT_EQ(bt["number_of_bts"], 6);
    EXPECT_EQ(bt["block_transfers"][0]["t_bt_ms"].dump(), "802.6");
    EXPECT_EQ(bt["block_transfers"][3]["t_btwait_ms"].dump(), "0.0");
    EXPECT_EQ(bt["block_transfers"][3]["t_bt_ms"].dump(), "260.2");
    EXPECT_EQ(bt["block_transfers"][5]["t_bt_ms"].dump(), "542.4");
    EXPECT_EQ(bt["block_transfers"][5]["name"], "Adapter #3, 32-word BT module");
    EXPECT_EQ(bt["t_buffer_free_ms"].dump(), "157.5");
    const std::string text = format_throughput_text(result);
    EXPECT_TRUE(contains(text, "T_free = T_M0 + T_SNo-bt(number of BTs) + T_ps = 157.5 ms"));
}

// Section 4.5 by its formulas: 1.734, 1.698, 2.516 and 1.8 ms, plus 2.7 ms,
// makes 10.448 ms.
TEST(ThroughputJson, AutomaxExample) {
    const json result = compute_throughput(load_example("automax_example.json"));
    EXPECT_EQ(result["network"], "automax");
    EXPECT_EQ(result["name"], "AutoMax Remote I/O manual, section 4.5: example network of four drops");
    const json& drops = result["drops"];
    ASSERT_EQ(drops.size(), 4u);
    const std::vector<std::string> times{"1.734", "1.698", "2.516", "1.8"};
    const std::vector<std::string> types{"multibus", "multibus", "head_57c330", "shark_digital"};
    for (std::size_t i = 0; i < drops.size(); ++i) {
        EXPECT_EQ(drops[i]["drop"], static_cast<int>(i) + 1);
        EXPECT_EQ(drops[i]["type"], types[i]);
        EXPECT_EQ(drops[i]["drop_time_ms"].dump(), times[i]);
    }
    EXPECT_EQ(drops[0]["registers"], 13);
    EXPECT_EQ(drops[2]["outputs"], 5);
    EXPECT_EQ(drops[2]["inputs"], 6);
    EXPECT_EQ(drops[2]["formula"], "1.9 + (5 x 0.08) + (6 x 0.036)");
    EXPECT_EQ(result["inactive_poll_ms"].dump(), "2.7");
    EXPECT_EQ(result["update_period_ms"].dump(), "10.448");
    ASSERT_EQ(result["notes"].size(), 2u);
    EXPECT_TRUE(contains(result["notes"][0], "1.933 ms"));
    EXPECT_TRUE(contains(result["notes"][1], "1.900 ms"));
}

// Appendix A, example without block transfers (132.0 ms): a T_ps of
// 25.0004 ms rounds to the example's 25.0 ms.
TEST(ThroughputJson, FinerThanMicrosecondTimesAreRoundedAndNoted) {
    json config = load_example("rio_example1.json");
    config["processor_scan_ms"] = 25.0004;
    const json result = compute_throughput(config);
    EXPECT_EQ(result["t_ps_ms"].dump(), "25.0");
    EXPECT_EQ(result["t_dm_nbt_ms"].dump(), "132.0");
    ASSERT_EQ(result["notes"].size(), 1u);
    EXPECT_EQ(result["notes"][0],
              "processor_scan_ms: 25.0004 ms is taken as 25.0 ms (the calculator works in whole microseconds).");
}

// Appendix A tables on example 1 in complementary mode, plus a complementary
// 1/2 rack at rack 1 (chapter 1, "Complementary I/O": racks 1 and 9 pair).
TEST(ThroughputJson, ComplementaryImagesAreNamed) {
    json config = load_example("rio_example1.json");
    config["mode"] = "complementary";
    config["devices"].push_back({{"rack", 1}, {"group", 0}, {"size", "1/2"}, {"complementary", true}});
    const json result = compute_throughput(config);
    EXPECT_EQ(result["logical_devices"][0]["image"], "primary");
    EXPECT_EQ(result["logical_devices"][6]["image"], "complementary");
    EXPECT_EQ(result["t_sno"]["column"], "115.2K");
    // "T_SNO without M0 File Writes", complementary, 115.2K, 4 racks, T_upd > T_hold: 10.0 ms.
    EXPECT_EQ(result["t_sno_ms"].dump(), "10.0");
    // T_RIO gains a 1/2 rack at 115.2K (4.0 ms): 29.5 ms.
    EXPECT_EQ(result["t_rio_ms"].dump(), "29.5");
}

// Appendix A, example with block transfers, computed twice.
TEST(ThroughputJson, SameConfigSameBytes) {
    const json config = load_example("rio_example2_bt.json");
    EXPECT_EQ(compute_throughput(config).dump(2), compute_throughput(config).dump(2));
    EXPECT_EQ(format_throughput_text(compute_throughput(config)), format_throughput_text(compute_throughput(config)));
}

// Appendix A, example without block transfers, step 4: the report prints the
// manual's substitution line and 132.0 ms; T_SNO from "T_SNO without M0
// File Writes", 4 racks, T_hold 11.0 ms.
TEST(ThroughputText, RioReportShowsTheSubstitutedFormula) {
    const std::string text = format_throughput_text(compute_throughput(load_example("rio_example1.json")));
    EXPECT_TRUE(contains(text, "RIO network throughput (1747-SN Series B scanner, manual appendix A)\n"));
    EXPECT_TRUE(contains(text, "Baud rate 115.2K, normal mode, 4 logical rack(s) configured (0, 1, 2, 3)"));
    EXPECT_TRUE(contains(text,
                         "  T_dm-nbt = 2T_ps + 2T_RIO + T_adp + T_SNO + T_SNI + T_id + T_od\n"
                         "           = 2(25.0) + 2(25.5) + 8.0 + 7.0 + 5.0 + 10.0 + 1.0\n"
                         "           = 132.0 ms\n"));
    EXPECT_TRUE(contains(text,
                         "T_SNO without M0 File Writes, normal mode (all baud rates), 4 logical racks, "
                         "T_upd > T_hold (T_hold 11.0 ms)"));
    EXPECT_FALSE(contains(text, "Notes"));
}

// Appendix A, example with block transfers: T_RIO 16.5 ms and step 4's
// substitution line, 173.2 ms.
TEST(ThroughputText, RioReportTablesAreAligned) {
    const std::string text = format_throughput_text(compute_throughput(load_example("rio_example2_bt.json")));
    const std::vector<std::string> lines = lines_of(text);
    // The logical device table: the header and its five rows (four devices
    // and the T_RIO total) end in the right-aligned T_RIO column.
    const auto header =
        std::find_if(lines.begin(), lines.end(), [](const std::string& l) { return contains(l, "T_RIO (ms)"); });
    ASSERT_NE(header, lines.end());
    for (auto it = header; it != header + 6; ++it) EXPECT_EQ(it->size(), header->size()) << *it;
    EXPECT_TRUE(contains(*(header + 5), "T_RIO") && contains(*(header + 5), "16.5"));
    EXPECT_TRUE(contains(text, "= 2(25.0) + 2(16.5) + 2(21.6) + 9.0 + 22.0 + 5.0 + 10.0 + 1.0\n"));
    EXPECT_TRUE(contains(text, "= 173.2 ms\n"));
    EXPECT_TRUE(contains(text, "\nNotes\n  - devices[0] (12 groups from rack 0 group 0)"));
}

// "RIO Scan Times for Adapters", 230.4K column: 1/2 rack 2.75 ms, full rack
// 3.5 ms, together 6.25 ms. Figures keep their exact form and line up on the
// decimal point.
TEST(ThroughputText, FiguresLineUpOnTheDecimalPoint) {
    json config = load_example("rio_example1.json");
    config["baud"] = "230.4K";
    config["devices"] =
        json::parse(R"([{"rack": 0, "group": 0, "size": "1/2"}, {"rack": 1, "group": 0, "size": "full"}])");
    const std::vector<std::string> lines = lines_of(format_throughput_text(compute_throughput(config)));
    const auto header =
        std::find_if(lines.begin(), lines.end(), [](const std::string& l) { return contains(l, "T_RIO (ms)"); });
    ASSERT_LT(header + 3, lines.end());
    EXPECT_TRUE(header[1].ends_with(" 2.75")) << header[1];
    EXPECT_TRUE(header[2].ends_with(" 3.5")) << header[2];
    EXPECT_TRUE(header[3].ends_with(" 6.25")) << header[3];
    EXPECT_EQ(header[1].rfind('.'), header[2].rfind('.'));
    EXPECT_EQ(header[1].rfind('.'), header[3].rfind('.'));
}

// Section 4.5 example by the formulas: 10.448 ms.
TEST(ThroughputText, AutomaxReport) {
    const std::string text = format_throughput_text(compute_throughput(load_example("automax_example.json")));
    const std::vector<std::string> lines = lines_of(text);
    EXPECT_EQ(lines[0], "AutoMax Remote I/O data update rate (manual chapter 4, section 4.5)");
    EXPECT_TRUE(contains(text, "1.9 + (5 x 0.08) + (6 x 0.036)"));
    const auto total =
        std::find_if(lines.begin(), lines.end(), [](const std::string& l) { return contains(l, "update period"); });
    ASSERT_NE(total, lines.end());
    EXPECT_EQ(total->substr(total->size() - 6), "10.448");
    EXPECT_TRUE(contains(text, "\nNotes\n  - 57C330 Remote I/O Head drops use the section 4.5 formula"));
}

// Only compute_throughput() results can be reported.
TEST(ThroughputText, RejectsWhatIsNotAResult) {
    EXPECT_THROW(format_throughput_text(json{{"network", "devicenet"}}), json::exception);
    EXPECT_THROW(format_throughput_text(json::object()), json::exception);
}

}  // namespace
}  // namespace softslc::throughput
