// Bench files: the generic grammar (rule by rule), the tree it builds, positioned syntax errors,
// and the per-family interpretation errors.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include <tao/pegtl/contrib/analyze.hpp>

#include "modules/bench/bench.h"
#include "modules/bench/bench_grammar.h"
#include "modules/bench/bench_messages.h"
#include "modules/module_setup.h"
#include "parser/loader.h"

namespace softslc {
namespace {

namespace pegtl = tao::pegtl;
namespace g = bench_grammar;

std::string test_read(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::ostringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

TEST(BenchGrammar, HasNoLoopsOrUnreachableRules) { EXPECT_EQ(pegtl::analyze<g::file>(), 0u); }

template <typename Rule>
bool matches(const std::string& text) {
  pegtl::memory_input in(text, "t");
  try {
    return pegtl::parse<pegtl::seq<Rule, pegtl::eof>>(in);
  } catch (const pegtl::parse_error&) {
    return false;
  }
}

TEST(BenchGrammar, Rules) {
  EXPECT_TRUE(matches<g::kind>("adapter"));
  EXPECT_FALSE(matches<g::kind>("1adapter"));
  EXPECT_TRUE(matches<g::name>("RACK_0.a-1"));
  EXPECT_TRUE(matches<g::value>("4.5ms"));
  EXPECT_TRUE(matches<g::value>("1/2"));
  EXPECT_TRUE(matches<g::value>("1,2,-3,0x00FF"));
  EXPECT_TRUE(matches<g::value>("\"two words\""));
  EXPECT_FALSE(matches<g::value>("a{b"));
  EXPECT_TRUE(matches<g::attribute>("rack=0"));
  EXPECT_FALSE(matches<g::attribute>("rack"));
  EXPECT_TRUE(matches<g::header>("adapter A rack=0 group=2"));
  EXPECT_TRUE(matches<g::header>("adapter rack=0"));
  EXPECT_TRUE(matches<g::line_end>("  # comment\n"));
  EXPECT_TRUE(matches<g::empty_line>("   \n"));
  EXPECT_TRUE(matches<g::node>("a b c=1 {\n  d e\n}\n"));
}

const char* kTree = R"(# a bench
scanner RIO slot=1 {
  adapter A rack=0 group=2 size=1/2 note="two words"   # trailing comment

  adapter B rack=1 group=0 size=full {
    module IN catalog=1746-IB16 group=0
  }
}
)";

TEST(BenchParse, BuildsTheTreeWithPositions) {
  auto r = parse_bench(kTree, "t.bench");
  ASSERT_TRUE(r.ok()) << r.render_diagnostics();
  const auto& nodes = r.bench->nodes;
  ASSERT_EQ(nodes.size(), 1u);
  EXPECT_EQ(nodes[0].kind, "scanner");
  EXPECT_EQ(nodes[0].name, "RIO");
  EXPECT_EQ(nodes[0].pos, (SourcePos{2, 1}));
  ASSERT_EQ(nodes[0].children.size(), 2u);
  const auto& a = nodes[0].children[0];
  EXPECT_EQ(a.label(), "adapter A");
  ASSERT_EQ(a.attributes.size(), 4u);
  EXPECT_EQ(a.attributes[3].key, "note");
  EXPECT_EQ(a.attributes[3].value, "two words");
  EXPECT_EQ(a.attributes[1].pos, (SourcePos{3, 20}));
  EXPECT_EQ(a.attributes[1].value_pos, (SourcePos{3, 26}));
  const auto& b = nodes[0].children[1];
  ASSERT_EQ(b.children.size(), 1u);
  EXPECT_EQ(b.children[0].find("catalog")->value, "1746-IB16");
  EXPECT_EQ(b.children[0].pos, (SourcePos{6, 5}));
}

TEST(BenchParse, AFileWithoutAFinalLineBreakAndOnlyComments) {
  EXPECT_TRUE(parse_bench("scanner S slot=1", "t").ok());
  EXPECT_TRUE(parse_bench("# nothing\n\n   # more", "t").ok());
  EXPECT_TRUE(parse_bench("", "t").ok());
}

std::string syntax_error(const std::string& text) { return parse_bench(text, "t.bench").render_diagnostics(); }

TEST(BenchParse, SyntaxErrorsArePositioned) {
  EXPECT_EQ(syntax_error("scanner S slot=1 {\n  adapter A rack=0\n"),
            "t.bench:3:1: error: expected a node line or '}' to close the block (nodes are KIND [NAME] [key=value "
            "...])\n\n^\n");
  EXPECT_EQ(syntax_error("adapter A rack=\n"),
            "t.bench:1:16: error: expected a value after '=' (a token such as 4.5ms or a quoted string)\n"
            "adapter A rack=\n               ^\n");
  EXPECT_EQ(syntax_error("adapter A B rack=1\n"),
            "t.bench:1:11: error: expected key=value, '{' or the end of the line (a node line is KIND [NAME] "
            "[key=value ...] [{])\nadapter A B rack=1\n          ^\n");
  EXPECT_NE(syntax_error("}\n").find("t.bench:1:1: error: expected a node line"), std::string::npos);
  EXPECT_NE(syntax_error("a n=\"open\n").find("unterminated string"), std::string::npos);
  EXPECT_NE(syntax_error("a n=1 n=2\n").find("t.bench:1:7: error: attribute 'n' is given twice"), std::string::npos);
}

// ---- Interpretation by the 1747-SN family, through the setup loader ------------------------------

const std::string kProgram =
    "START 1747-L532\n"
    "SLOT 1 1747-SN SCAN_IN 32 SCAN_OUT 32 G_FILE 3\n 0 17 63\n"
    "SLOT 2 1746-IB16 SCAN_IN 1 SCAN_OUT 0\n"
    "SLOT 3 1746-HSCE SCAN_IN 8 SCAN_OUT 8\n"
    "LADDER 2\nSOR XIC B3:0/0 OTE B3:0/1 EOR\n";

std::string bench_errors(const std::string& bench) {
  LoadResult lr = load_program(kProgram, "p.slc");
  EXPECT_TRUE(lr.ok()) << lr.render_diagnostics();
  ModuleSetup s = load_module_setup_text(*lr.program, bench, "t.bench");
  return render_all(s.bench_diagnostics, "t.bench", bench);
}

TEST(BenchInterpret, AValidBench) {
  EXPECT_EQ(bench_errors("scanner RIO slot=1 {\n"
                         "  adapter A rack=0 group=0 size=full hold_last_state=on backplane_scan=4.5ms {\n"
                         "    module IN catalog=1746-IB16 group=0 input_delay=10ms\n"
                         "    module OUT catalog=1746-OB8 group=1 slot=1\n"
                         "    module AI kind=bt group=2 length=4 data=1,2,3,4 {\n"
                         "      read at=1s data=5,6,7,8\n"
                         "      ramp word=0 from=0 step=1 every=10ms\n"
                         "    }\n"
                         "  }\n"
                         "  adapter B rack=1 group=0 size=1/2\n"
                         "}\n"
                         "io PB slot=2 input_delay=8ms\n"),
            "");
}

TEST(BenchInterpret, ErrorsArePositionedAtTheirAttribute) {
  EXPECT_EQ(bench_errors("scanner RIO slot=1 {\n  adapter A rack=0 group=3 size=1/2\n}\n"),
            "t.bench:2:26: error: adapter A: a device starts at an even logical group (0, 2, 4 or 6)\n"
            "  adapter A rack=0 group=3 size=1/2\n                         ^\n");
  EXPECT_NE(bench_errors("scanner RIO slot=1 {\n  adapter A rack=0 group=0 size=1/3\n}\n")
                .find("t.bench:2:33: error: adapter A: size=1/3: expected 1/4, 1/2, 3/4 or full"),
            std::string::npos);
  EXPECT_NE(bench_errors("scanner RIO slot=1 {\n  adapter A rack=0 group=0 size=full colour=red\n}\n")
                .find("t.bench:2:38: error: adapter A: unknown attribute 'colour' (known:"),
            std::string::npos);
  EXPECT_NE(bench_errors("scanner RIO slot=1 {\n  adapter A rack=0 group=0 size=1/4 backplane_scan=4.5 \n}\n")
                .find("backplane_scan=4.5: "),
            std::string::npos);
  EXPECT_NE(bench_errors("scanner RIO slot=1 {\n  adapter A rack=0 group=0 size=1/4 {\n    module M catalog=1746-IB16 "
                         "group=4\n  }\n}\n")
                .find("t.bench:3:5: error: module M: rack 0 group 4 is outside adapter A's image"),
            std::string::npos);
  EXPECT_NE(bench_errors("scanner RIO slot=1 {\n  adapter A rack=0 group=0 size=1/4 {\n    module M catalog=1771-IFE "
                         "group=0\n  }\n}\n")
                .find("kind=input, kind=output or kind=bt"),
            std::string::npos);
}

TEST(BenchInterpret, BindingToSlots) {
  EXPECT_NE(bench_errors("scanner RIO\n").find("t.bench:1:1: error: scanner RIO: a top-level bench node names the chassis slot"),
            std::string::npos);
  EXPECT_NE(bench_errors("scanner RIO slot=7\n").find("the program has no module in slot 7"), std::string::npos);
  EXPECT_NE(bench_errors("io RIO slot=1\n").find("'io' does not describe the 1747-SN in slot 1 (1747-SN RIO scanner); write scanner"),
            std::string::npos);
  EXPECT_NE(bench_errors("thing X slot=3\n").find("slot 3 holds a 1746-HSCE, which has no simulated field devices"),
            std::string::npos);
  EXPECT_NE(bench_errors("scanner A slot=1\nscanner B slot=1\n").find("t.bench:2:1: error: scanner B: slot 1 is already described at line 1"),
            std::string::npos);
  EXPECT_NE(bench_errors("scanner RIO slot=1 {\n  adapter RIO rack=0 group=0 size=full\n}\n")
                .find("t.bench:2:11: error: device name 'RIO' is already used at line 1"),
            std::string::npos);
}

TEST(BenchInterpret, AdaptersTheGFileDoesNotScanAreWarnings) {
  EXPECT_NE(bench_errors("scanner RIO slot=1 {\n  adapter X rack=3 group=0 size=1/4\n}\n")
                .find("t.bench:2:3: warning: adapter X (rack 3 group 0) is not a device of the scanner's G file"),
            std::string::npos);
}

TEST(BenchInterpret, ComplementaryPlacementRules) {
  LoadResult lr = load_program(
      "START 1747-L532\nSLOT 1 1747-SN SCAN_IN 32 SCAN_OUT 32 G_FILE 5\n 0 1 1 1 1\nLADDER 2\nSOR XIC B3:0/0 OTE B3:0/1 EOR\n",
      "p.slc");
  ASSERT_TRUE(lr.ok()) << lr.render_diagnostics();
  const std::string bench =
      "scanner RIO slot=1 {\n"
      "  adapter P rack=0 group=0 size=1/4 chassis=primary {\n"
      "    module PI catalog=1746-IB16 group=0\n"
      "    module PBT kind=bt group=1\n"
      "  }\n"
      "  adapter C rack=8 group=0 size=1/4 {\n"
      "    module CI catalog=1746-IB16 rack=8 group=0\n"
      "    module CO catalog=1746-OB16 rack=8 group=1\n"
      "  }\n"
      "}\n";
  ModuleSetup s = load_module_setup_text(*lr.program, bench, "t.bench");
  const std::string e = render_all(s.bench_diagnostics, "t.bench", bench);
  EXPECT_NE(e.find("t.bench:7:5: error: input module CI shares its image location with input module PI"), std::string::npos) << e;
  EXPECT_NE(e.find("t.bench:8:5: error: module CO is opposite block-transfer module PBT"), std::string::npos) << e;
}

// tools/mutate.py: one RIO module line copied n times gave n^2/2 "same image location" errors
// (10,000 copies: 9.8 GB; 20,000 killed by the OOM killer). Each copy is now one such error.
TEST(BenchInterpret, CopiedModuleLinesGiveOneClashErrorEach) {
  LoadResult lr = load_program(
      "START 1747-L532\nSLOT 1 1747-SN SCAN_IN 32 SCAN_OUT 32 G_FILE 5\n 0 1 1 1 1\nLADDER 2\nSOR XIC B3:0/0 OTE B3:0/1 EOR\n",
      "p.slc");
  ASSERT_TRUE(lr.ok()) << lr.render_diagnostics();
  std::string bench = "scanner RIO slot=1 {\n  adapter P rack=0 group=0 size=1/4 {\n";
  for (int i = 0; i < 300; ++i) bench += "    module PBT kind=bt group=1\n";
  bench += "  }\n}\n";
  ModuleSetup s = load_module_setup_text(*lr.program, bench, "t.bench");
  std::size_t clashes = 0;
  for (const auto& d : s.bench_diagnostics.items())
    if (d.message.find("uses the same image location") != std::string::npos) ++clashes;
  EXPECT_EQ(clashes, 299u);  // every copy after the first, once
}

TEST(BenchDocs, TheCompleteExampleOfDocsBenchFormatLoads) {
  const std::string doc = test_read(std::string(SOFTSLC_SOURCE_DIR) + "/docs/bench-format.md");
  const auto start = doc.find("```\n", doc.find("## A complete example"));
  ASSERT_NE(start, std::string::npos);
  const auto end = doc.find("```", start + 4);
  const std::string bench = doc.substr(start + 4, end - start - 4);
  LoadResult lr = load_program(
      "START 1747-L532\nSLOT 1 1747-SN SCAN_IN 32 SCAN_OUT 32 G_FILE 3\n 0 769 831 OPTION baud=115.2K\n"
      "SLOT 2 1746-IB16 SCAN_IN 1 SCAN_OUT 0\nLADDER 2\nSOR XIC B3:0/0 OTE B3:0/1 EOR\n",
      "p.slc");
  ASSERT_TRUE(lr.ok()) << lr.render_diagnostics();
  ModuleSetup s = load_module_setup_text(*lr.program, bench, "bench-format.md");
  EXPECT_TRUE(s.ok()) << s.render("p.slc", lr.source);
  EXPECT_EQ(s.bench_diagnostics.items().size(), 0u) << s.render("p.slc", lr.source);
}

}  // namespace
}  // namespace softslc
