// The scanner configuration JSON (docs/1747-sdn.md, "Scanner configuration") and scanlist validation
// (code 71 "Illegal data in scanlist table", p.91).
#include <gtest/gtest.h>

#include "tests/devicenet/devicenet_test_util.h"

namespace softslc::devicenet::test {
namespace {

// The chapter 4 example (p.58-61) written as a scanner configuration.
constexpr const char* kExample = R"({
  "node": 0,
  "baud": "500K",
  "interscan_delay_ms": 10,
  "scanlist": [
    {"node": 7, "poll": {"rx": 1, "tx": 1},
     "inputs": [{"from": "poll", "byte": 0, "bit": 0, "bits": 8, "to": "M1:0/0"}],
     "outputs": [{"to": "poll", "byte": 0, "bit": 0, "bits": 8, "from": "M0:0/0"}]},
    {"node": 9, "strobe": {"rx": 1},
     "inputs": [{"from": "strobe", "bits": 8, "to": "M1:0/8"}]}
  ]
})";

bool same(const ScannerConfig& a, const ScannerConfig& b) {
  return scanner_config_to_json(a) == scanner_config_to_json(b);
}

TEST(ScannerConfigJson, ExampleMatchesTheFixture) {
  const ScannerConfig c = parse_scanner_config(parse_json_text(kExample, "example"));
  EXPECT_TRUE(same(c, example_config())) << scanner_config_to_json(c).dump(2);
  EXPECT_TRUE(validate_scanlist(c).empty());
  EXPECT_TRUE(same(parse_scanner_config(scanner_config_to_json(c)), c));
}

TEST(ScannerConfigJson, Defaults) {
  const ScannerConfig c = parse_scanner_config(nlohmann::json::parse(R"({"node": 5})"));
  EXPECT_EQ(c.baud, Baud::k125);
  EXPECT_EQ(c.interscan_delay, milliseconds(10));
  EXPECT_EQ(c.background_poll_ratio, 1);
  EXPECT_FALSE(c.autoscan);
  EXPECT_EQ(c.autoscan_allocation, 4);
}

std::string error_path(const char* text) {
  try {
    parse_scanner_config(nlohmann::json::parse(text));
  } catch (const ConfigError& e) {
    return e.path();
  }
  return "(no error)";
}

TEST(ScannerConfigJson, PathedErrors) {
  EXPECT_EQ(error_path(R"({})"), "node");
  EXPECT_EQ(error_path(R"({"node": 64})"), "node");
  EXPECT_EQ(error_path(R"({"node": 0, "baud": "1M"})"), "baud");
  EXPECT_EQ(error_path(R"({"node": 0, "interscan_delay_ms": 0})"), "interscan_delay_ms");
  EXPECT_EQ(error_path(R"({"node": 0, "autoscan": {"allocation_bytes": 33}})"), "autoscan.allocation_bytes");
  EXPECT_EQ(error_path(R"({"node": 0, "scanlist": [{"node": 7, "poll": {"rx": 300}}]})"), "scanlist[0].poll.rx");
  EXPECT_EQ(error_path(R"({"node": 0, "scanlist": [{"node": 7, "strobe": {"tx": 2}}]})"), "scanlist[0].strobe.tx");
  EXPECT_EQ(error_path(R"({"node": 0, "scanlist": [{"node": 7, "poll": {"rate_ms": 5}}]})"), "scanlist[0].poll.rate_ms");
  EXPECT_EQ(error_path(R"({"node": 0, "scanlist": [{"node": 7, "poll": {}, "inputs": [{"from": "poll", "to": "N7:0"}]}]})"),
            "scanlist[0].inputs[0].to");
  EXPECT_EQ(error_path(R"({"node": 0, "scanlist": [{"node": 7, "poll": {}, "outputs": [{"to": "poll", "from": "M1:0"}]}]})"),
            "scanlist[0].outputs[0].from");
  EXPECT_EQ(error_path(R"({"node": 0, "scanlist": [{"node": 7, "poll": {}, "inputs": [{"from": "bitstrobe", "to": "M1:0"}]}]})"),
            "scanlist[0].inputs[0].from");
}

TEST(TableRefs, ParseAndFormat) {
  EXPECT_EQ(parse_table_ref("M1:2/8", true), (TableRef{TableRef::Area::MFile, 2, 8}));
  EXPECT_EQ(parse_table_ref("I:1", true), (TableRef{TableRef::Area::Discrete, 1, 0}));
  EXPECT_EQ(parse_table_ref("O:31/15", false), (TableRef{TableRef::Area::Discrete, 31, 15}));
  EXPECT_FALSE(parse_table_ref("M0:1", true).has_value());
  EXPECT_FALSE(parse_table_ref("M1:", true).has_value());
  EXPECT_FALSE(parse_table_ref("M1:1/x", true).has_value());
  EXPECT_EQ(format_table_ref(TableRef{TableRef::Area::MFile, 0, 8}, true), "M1:0/8");
  EXPECT_EQ(format_table_ref(TableRef{TableRef::Area::Discrete, 1, 0}, false), "O:1/0");
}

// ---- validation (code 71) -----------------------------------------------------------------------------

std::vector<std::string> issue_paths(const ScannerConfig& c) {
  std::vector<std::string> out;
  for (const auto& i : validate_scanlist(c)) out.push_back(i.path);
  return out;
}

TEST(ScanlistValidation, TableRanges) {
  ScannerConfig c = example_config();
  c.scanlist[0].inputs[0].table = TableRef{TableRef::Area::MFile, 149, 8};  // 8 bits from 149/8: fits
  EXPECT_TRUE(issue_paths(c).empty());
  c.scanlist[0].inputs[0].table = TableRef{TableRef::Area::MFile, 150, 0};  // past the 150 data words
  EXPECT_EQ(issue_paths(c), (std::vector<std::string>{"scanlist[0].inputs[0].to"}));
  c.scanlist[0].inputs[0].table = TableRef{TableRef::Area::Discrete, 0, 0};  // I:s.0 is the status register
  EXPECT_EQ(issue_paths(c), (std::vector<std::string>{"scanlist[0].inputs[0].to"}));
  c.scanlist[0].inputs[0].table = TableRef{TableRef::Area::Discrete, 31, 8};  // last byte of I:s.31
  EXPECT_TRUE(issue_paths(c).empty());
  c.scanlist[0].outputs[0].table = TableRef{TableRef::Area::Discrete, 0, 0};  // O:s.0 is the command register
  EXPECT_EQ(issue_paths(c), (std::vector<std::string>{"scanlist[0].outputs[0].from"}));
}

TEST(ScanlistValidation, EntryProblems) {
  ScannerConfig c = example_config();
  c.scanlist[1].inputs[0].table = TableRef{TableRef::Area::MFile, 0, 4};  // overlaps the RediSTATION's bits
  EXPECT_EQ(issue_paths(c), (std::vector<std::string>{"scanlist[1].inputs[0]"}));

  c = example_config();
  c.scanlist[0].inputs[0].bits = 9;  // past the 1-byte rx
  EXPECT_EQ(issue_paths(c), (std::vector<std::string>{"scanlist[0].inputs[0].bits"}));

  c = example_config();
  c.scanlist[1].node = kRediStationNode;
  EXPECT_EQ(validate_scanlist(c).at(0).message, "node 7 is listed twice");

  c = example_config();
  c.scanlist[0].node = kScannerNode;
  EXPECT_EQ(issue_paths(c).at(0), "scanlist[0].node");

  c = example_config();
  c.scanlist[0].conn(IoType::Cos) = ConnectionConfig{true, 1, 1, milliseconds(250), false};
  c.scanlist[0].conn(IoType::Cyclic) = ConnectionConfig{true, 1, 1, milliseconds(500), false};
  EXPECT_EQ(issue_paths(c), (std::vector<std::string>{"scanlist[0].cyclic"}));

  c = example_config();
  c.scanlist[0].conn(IoType::Poll).enabled = false;
  EXPECT_FALSE(issue_paths(c).empty());  // no connection, and segments naming a missing one

  c = example_config();
  c.scanlist[1].conn(IoType::Strobe).tx = 1;
  c.scanlist[1].outputs.push_back(segment(IoType::Strobe, 0, 0, 2, TableRef::Area::MFile, 1, 0));
  EXPECT_EQ(issue_paths(c), (std::vector<std::string>{"scanlist[1].outputs[0].bits"}));
}

TEST(ScanlistValidation, ScannerSettings) {
  ScannerConfig c = example_config();
  c.node_address = 64;
  EXPECT_THROW(validate_scanner_settings(c), ConfigError);
  c = example_config();
  c.background_poll_ratio = 0;
  EXPECT_THROW(validate_scanner_settings(c), ConfigError);
  Network net(Baud::k500);
  c = example_config();
  c.interscan_delay = 0;
  EXPECT_THROW(Scanner(net, c), ConfigError);
}

}  // namespace
}  // namespace softslc::devicenet::test
