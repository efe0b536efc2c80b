// The softslc command line as scripts use it: exit codes, output streams, fmt's file output.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sys/wait.h>

namespace {

struct Result {
  int exit_code = -1;
  std::string out;  // stdout and stderr, as a user sees them
};

Result run(const std::string& args) {
  std::string cmd = std::string(SOFTSLC_BINARY) + " " + args + " 2>&1";
  Result r;
  FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf;
  while (std::size_t n = std::fread(buf.data(), 1, buf.size(), p)) r.out.append(buf.data(), n);
  int status = ::pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

std::filesystem::path temp_file(const std::string& name, const std::string& contents) {
  auto dir = std::filesystem::temp_directory_path() / ("softslc-cli-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  auto path = dir / name;
  std::ofstream(path) << contents;
  return path;
}

const std::string kFixture = std::string(SOFTSLC_SHARED_DIR) + "/fixtures/rslogix500/59-BSGS.SLC";
const std::string kExample = std::string(SOFTSLC_SOURCE_DIR) + "/examples/ladder/seal_in/seal_in.slc";

TEST(Cli, CheckFixtureExitsZeroWithWarningsOnly) {
  auto r = run("check " + kFixture);
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("0 errors, 14 warnings"), std::string::npos) << r.out;
}

TEST(Cli, CheckCleanProgramPrintsNothing) {
  auto r = run("check " + kExample);
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.out, "");
}

TEST(Cli, CheckErrorsExitOne) {
  auto f = temp_file("bad.slc", "START 1747-L532\nLADDER 2\nSOR XIC B3:0/16 OTE B3:0/1 EOR\n");
  auto r = run("check " + f.string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find("bad.slc:3:9: error: bit number 16 is out of range 0-15"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("1 error, 0 warnings"), std::string::npos) << r.out;
}

TEST(Cli, UsageErrorsExitTwo) {
  EXPECT_EQ(run("").exit_code, 2);
  EXPECT_EQ(run("check").exit_code, 2);
  EXPECT_EQ(run("frobnicate x").exit_code, 2);
  EXPECT_EQ(run("check a b c").exit_code, 2);
}

TEST(Cli, HelpAndVersion) {
  auto h = run("--help");
  EXPECT_EQ(h.exit_code, 0);
  EXPECT_NE(h.out.find("check"), std::string::npos);
  EXPECT_NE(h.out.find("fmt"), std::string::npos);
  EXPECT_EQ(run("check --help").exit_code, 0);
  auto v = run("--version");
  EXPECT_EQ(v.exit_code, 0);
  EXPECT_EQ(v.out.rfind("softslc ", 0), 0u) << v.out;
}

TEST(Cli, FmtToFileRoundTrips) {
  auto out = temp_file("fmt-out.slc", "");
  auto r = run("fmt " + kFixture + " -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.out;
  auto again = run("fmt " + out.string());
  ASSERT_EQ(again.exit_code, 0);
  std::ifstream in(out);
  std::string written((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // The second formatting prints the warnings, then the identical text.
  EXPECT_NE(again.out.find(written), std::string::npos);
}

TEST(Cli, FmtRefusesAProgramWithErrorsAndLeavesTheOutputAlone) {
  auto bad = temp_file("bad2.slc", "START 1747-L532\nLADDER 2\nSOR FOO EOR\n");
  auto out = temp_file("keep.slc", "precious\n");
  auto r = run("fmt " + bad.string() + " -o " + out.string());
  EXPECT_EQ(r.exit_code, 1);
  std::ifstream in(out);
  std::string kept((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(kept, "precious\n");
}

TEST(Cli, ThroughputExamples) {
  auto r = run("throughput --json " + std::string(SOFTSLC_SOURCE_DIR) + "/examples/throughput/rio_example1.json");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  // 1747-SN manual appendix A, discrete throughput example without block transfers.
  EXPECT_NE(r.out.find("\"t_dm_nbt_ms\": 132.0"), std::string::npos) << r.out;
  auto a = run("throughput " + std::string(SOFTSLC_SOURCE_DIR) + "/examples/throughput/automax_example.json");
  ASSERT_EQ(a.exit_code, 0) << a.out;
  EXPECT_NE(a.out.find("10.448"), std::string::npos) << a.out;
}

TEST(Cli, ThroughputBadInput) {
  auto notjson = temp_file("x.json", "{ not json");
  auto r = run("throughput " + notjson.string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find("x.json: error: not valid JSON"), std::string::npos) << r.out;
  auto bad = temp_file("y.json", R"({"network": "rio", "baud": "9600"})");
  auto b = run("throughput " + bad.string());
  EXPECT_EQ(b.exit_code, 1);
  EXPECT_NE(b.out.find("y.json: error: baud"), std::string::npos) << b.out;
}

}  // namespace
