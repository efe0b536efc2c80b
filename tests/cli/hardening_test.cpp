// Hardening (issue 17): bad input as a hostile or careless user writes it, through the command a
// user runs. Each test is a regression test for one finding; the comment says which.
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include "parser/json_document.h"
#include "cli_test_util.h"

namespace {

const std::string kExample = std::string(SOFTSLC_SOURCE_DIR) + "/examples/ladder/seal_in/seal_in.slc";

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::string read_all(const std::filesystem::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

// ---- JSON: no exception escapes, every error positioned ----------------------------------------

// nlohmann throws out_of_range (not parse_error) for a number beyond a double; it aborted
// `throughput` and `--timing`. The position is the number's: line 2, after "1e309".
TEST(HardeningJson, NumberOverflowIsAPositionedError) {
  auto d = softslc::parse_json_document("{\n  \"x\": 1e309\n}");
  EXPECT_FALSE(d.ok);
  EXPECT_EQ(d.line, 2u);
  EXPECT_TRUE(contains(d.message, "number overflow")) << d.message;
}

TEST(HardeningJson, NestingBeyondTheLimitIsAnError) {
  std::string deep(100000, '[');
  auto d = softslc::parse_json_document(deep);
  EXPECT_FALSE(d.ok);
  EXPECT_EQ(d.line, 1u);
  EXPECT_EQ(d.column, softslc::kMaxJsonDepth + 1);
  EXPECT_TRUE(contains(d.message, "nested deeper than")) << d.message;
  EXPECT_TRUE(softslc::parse_json_document(std::string(10, '[') + std::string(10, ']')).ok);
}

TEST(HardeningJson, ThroughputConfigWithHugeNumber) {
  auto f = temp_file("huge.json", "{\"network\": \"rio\",\n \"baud\": 1e309}\n");
  auto r = run("throughput " + f.string());
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_TRUE(contains(r.out, "huge.json:2:")) << r.out;
  EXPECT_TRUE(contains(r.out, "number overflow")) << r.out;
}

TEST(HardeningJson, TimingProfileWithHugeNumber) {
  auto f = temp_file("huge-timing.json", "{\"schema\": \"softslc-timing-profile-1\", \"processor\": 1e309}");
  auto r = run("run " + kExample + " --timing " + f.string());
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_TRUE(contains(r.out, "huge-timing.json:1:")) << r.out;
  EXPECT_TRUE(contains(r.out, "number overflow")) << r.out;
}

// The SCANport drive files and DeviceNet descriptions a bench names went through the same
// nlohmann parse that aborted on 1e309: now the bench run stops with the file's position. The
// example's bench is copied beside a replacement for the JSON file it names.
void expect_bench_json_overflow(const std::string& example_dir, const std::string& program, const std::string& bench,
                                const std::string& json_name, const std::string& json, const std::string& where) {
  const auto dir = std::filesystem::path(SOFTSLC_SOURCE_DIR) / "examples/ladder" / example_dir;
  auto copy = temp_file("huge-" + json_name + "/" + bench, read_all(dir / bench));
  temp_file("huge-" + json_name + "/" + json_name, json);
  auto r = run("run " + (dir / program).string() + " --bench " + copy.string() + " --for 10ms");
  EXPECT_EQ(r.exit_code, 1) << json_name << ": " << r.out;
  EXPECT_TRUE(contains(r.out, where)) << r.out;
  EXPECT_TRUE(contains(r.out, "number overflow")) << r.out;
}

TEST(HardeningJson, DriveFileAndDeviceNetDescriptionWithHugeNumber) {
  expect_bench_json_overflow("1203-sm1", "appb_messaging.slc", "pad6.bench", "pad6_drive.json",
                             "{\n  \"schema\": 1e309\n}\n", "pad6_drive.json:2:");
  expect_bench_json_overflow("1747-sdn", "appe_drive_parameter.slc", "appe_drive_parameter.bench", "weigh-scale.json",
                             "{\"vendor\": 1e309}\n", "weigh-scale.json:1:");
}

// `test --coverage-json` aborted (nlohmann type_error 316) when a program's path was not UTF-8:
// the report names the program by its path; the byte becomes U+FFFD and the file is written.
TEST(HardeningJson, CoverageJsonOfANonUtf8PathIsWritten) {
  const auto dir = std::filesystem::path(SOFTSLC_SOURCE_DIR) / "examples/ladder/seal_in";
  auto test = temp_file("latin1-\xe9/seal_in.test", read_all(dir / "seal_in.test"));
  std::filesystem::copy_file(dir / "seal_in.slc", test.parent_path() / "seal_in.slc",
                             std::filesystem::copy_options::overwrite_existing);
  const auto report = test.parent_path().parent_path() / "latin1-coverage.json";
  auto r = run("test " + test.string() + " --coverage-json " + report.string());
  EXPECT_EQ(r.exit_code, 0) << r.out;
  const std::string json = read_all(report);
  EXPECT_TRUE(contains(json, "latin1-\xef\xbf\xbd/seal_in.slc")) << json.substr(0, 500);
  EXPECT_FALSE(contains(json, "latin1-\xe9")) << json.substr(0, 500);
}

// ---- One address rule and one value rule for every entry point -----------------------------------

const char* const kWordProgram =
    "START 1747-L532\n"
    "SLOT 0 1747-L532 SCAN_IN 0 SCAN_OUT 0\n"
    "SLOT 1 1746-IB16 SCAN_IN 1 SCAN_OUT 0\n"
    "SLOT 2 1746-OB16 SCAN_IN 0 SCAN_OUT 1\n"
    "LADDER 2 MAIN\n"
    "SOR XIC I:1/0 OTE O:2/0 EOR\n"
    "SOR MOV N7:0 N7:1 EOR\n"
    "SOR MOV F8:0 F8:1 EOR\n";

// `--set I:1/32=1` wrote I:1/0 (the shift wrapped, UBSan reported it); O:2/16 wrote nothing.
TEST(HardeningAddresses, SetBitBeyondFifteenIsRefused) {
  auto f = temp_file("words.slc", kWordProgram);
  auto r = run("run " + f.string() + " --set I:1/32=1 --print I:1/0");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_TRUE(contains(r.out, "bit number 32 is out of range 0-15")) << r.out;
  auto o = run("run " + f.string() + " --set O:2/16=1");
  EXPECT_EQ(o.exit_code, 2) << o.out;
  EXPECT_TRUE(contains(o.out, "bit number 16 is out of range 0-15")) << o.out;
}

// 99999 stored -31073, 1.5 stored 2, 2 on a bit stored 1: the test-file rule now applies.
TEST(HardeningValues, SetValueMustFitItsOperand) {
  auto f = temp_file("words.slc", kWordProgram);
  auto big = run("run " + f.string() + " --set N7:0=99999 --print N7:0");
  EXPECT_EQ(big.exit_code, 2) << big.out;
  EXPECT_TRUE(contains(big.out, "does not fit a 16-bit word (-32768..32767)")) << big.out;
  auto real = run("run " + f.string() + " --set N7:0=1.5");
  EXPECT_EQ(real.exit_code, 2) << real.out;
  EXPECT_TRUE(contains(real.out, "is not an integer")) << real.out;
  auto bit = run("run " + f.string() + " --set I:1/0=2");
  EXPECT_EQ(bit.exit_code, 2) << bit.out;
  EXPECT_TRUE(contains(bit.out, "a bit is 0 or 1")) << bit.out;
  // What does fit is written: a hex word is a bit pattern (0xFFFF is -1, docs/testing.md), the
  // limits themselves, and an integer into a float element.
  auto hex = run("run " + f.string() + " --set N7:0=0xFFFF --print N7:1");
  EXPECT_EQ(hex.exit_code, 0) << hex.out;
  EXPECT_EQ(hex.out, "N7:1 = -1\n");
  auto ok = run("run " + f.string() + " --set N7:0=-32768 --set F8:0=3 --print N7:1 --print F8:1");
  EXPECT_EQ(ok.exit_code, 0) << ok.out;
  EXPECT_EQ(ok.out, "N7:1 = -32768\nF8:1 = 3\n");
}

// `--print N7:999` printed "= ?" and exited 0.
TEST(HardeningAddresses, PrintOfAnAddressThatDoesNotExistIsAnError) {
  auto f = temp_file("words.slc", kWordProgram);
  auto far = run("run " + f.string() + " --print N7:999");
  EXPECT_EQ(far.exit_code, 2) << far.out;
  EXPECT_TRUE(contains(far.out, "element 999 is beyond the largest file size")) << far.out;
  auto near = run("run " + f.string() + " --print N7:200");
  EXPECT_EQ(near.exit_code, 2) << near.out;
  EXPECT_FALSE(contains(near.out, "= ?")) << near.out;
}

// ---- Nesting: explicit limits, the SLC's where it has one -----------------------------------------

std::string nested_rung(int depth) {
  std::string rung = "SOR ";
  for (int i = 0; i < depth; ++i) rung += "BST XIC B3:0/0 ";
  for (int i = 0; i < depth; ++i) rung += "NXB XIC B3:0/2 BND ";
  return rung + "OTE B3:0/1 EOR\n";
}

// `run` refused branches deeper than 16 while `check` accepted them; 15,000 levels overflowed
// the stack of every command.
TEST(HardeningNesting, BranchesDeeperThanSixteenAreRefusedByEveryCommand) {
  auto ok = temp_file("deep16.slc", "START 1747-L532\nLADDER 2 MAIN\n" + nested_rung(16));
  EXPECT_EQ(run("check " + ok.string()).exit_code, 0);
  EXPECT_EQ(run("run " + ok.string()).exit_code, 0);
  auto deep = temp_file("deep17.slc", "START 1747-L532\nLADDER 2 MAIN\n" + nested_rung(17));
  for (const char* cmd : {"check", "run", "fmt", "disasm", "scantime"}) {
    auto r = run(std::string(cmd) + " " + deep.string());
    EXPECT_EQ(r.exit_code, 1) << cmd << ": " << r.out;
    // The 17th BST, column 5 + 16 * 15.
    EXPECT_TRUE(contains(r.out, "deep17.slc:3:245: error: branches nested deeper than 16 levels")) << cmd << r.out;
  }
  auto hostile = temp_file("deep15000.slc", "START 1747-L532\nLADDER 2 MAIN\n" + nested_rung(15000));
  auto r = run("check " + hostile.string());
  EXPECT_EQ(r.exit_code, 1) << r.out.substr(0, 2000);
  EXPECT_TRUE(contains(r.out, "branches nested deeper than 16 levels")) << r.out.substr(0, 2000);
}

// ---- check agrees with run ------------------------------------------------------------------------

// `check` accepted AND on a float, which `run` refuses.
TEST(HardeningCheckIsRun, CheckRefusesWhatTheCompilerRefuses) {
  auto f = temp_file("andfloat.slc", "START 1747-L532\nLADDER 2 MAIN\nSOR AND F8:0 N7:0 N7:1 EOR\n");
  auto c = run("check " + f.string());
  EXPECT_EQ(c.exit_code, 1) << c.out;
  // The instruction table's word-only operand kind refuses it, at the float operand.
  EXPECT_TRUE(contains(c.out, "andfloat.slc:3:9: error: AND source A: AND works on integer words; an F address is not allowed"))
      << c.out;
  EXPECT_EQ(run("run " + f.string()).exit_code, 1);
}

// ---- Files: what is read, how it is written -------------------------------------------------------

// `check /dev/zero` read forever; a directory gave a confusing message.
TEST(HardeningFiles, SpecialFilesAreRefusedByWhatTheyAre) {
  auto z = run("check /dev/zero");
  EXPECT_EQ(z.exit_code, 1) << z.out;
  EXPECT_TRUE(contains(z.out, "/dev/zero: error: a character device, not a regular file")) << z.out;
  auto d = run("check " + std::filesystem::temp_directory_path().string());
  EXPECT_EQ(d.exit_code, 1) << d.out;
  EXPECT_TRUE(contains(d.out, "a directory, not a regular file")) << d.out;
  auto s = run("run " + kExample + " --state /dev/zero");
  EXPECT_EQ(s.exit_code, 1) << s.out;
  EXPECT_TRUE(contains(s.out, "not a regular file")) << s.out;
}

// A Windows editor's UTF-8 byte-order mark made "missing START"; UTF-16 must say what it is.
TEST(HardeningFiles, ByteOrderMarkLoadsAndUtf16IsNamed) {
  const std::string text = read_all(kExample);
  auto bom = temp_file("bom.slc", "\xEF\xBB\xBF" + text);
  EXPECT_EQ(run("check " + bom.string()).exit_code, 0);
  std::string utf16 = "\xFF\xFE";
  for (char c : text) utf16 += std::string{c, '\0'};
  auto wide = temp_file("wide.slc", utf16);
  auto r = run("check " + wide.string());
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_TRUE(contains(r.out, "UTF-16 file: save it as UTF-8")) << r.out;
  EXPECT_FALSE(contains(r.out, "START")) << r.out;
}

// Two `run --state s.bin` at once both saved: one run's scans were lost.
TEST(HardeningState, ASecondRunOnTheSameStateFileIsRefused) {
  auto dir = temp_file("lock/x", "").parent_path();
  const auto state = dir / "s.bin";
  std::filesystem::remove(state);
  // The first run holds the lock for 120 s of wall time (--realtime) and saves a checkpoint every
  // virtual second. Only the lock's holder saves, so the state file's appearing proves the first
  // run holds the lock: the second starts only then. (Starting the second while the first was
  // still starting let the second take the lock and the first be the one refused; CI saw it.)
  const pid_t first = ::fork();
  ASSERT_GE(first, 0);
  if (first == 0) {
    if (!std::freopen("/dev/null", "w", stdout) || !std::freopen("/dev/null", "w", stderr)) ::_exit(126);
    ::execl(SOFTSLC_BINARY, SOFTSLC_BINARY, "run", kExample.c_str(), "--state", state.c_str(), "--for", "120s",
            "--realtime", "--checkpoint", "1s", static_cast<char*>(nullptr));
    ::_exit(127);
  }
  for (int waited_ms = 0; !std::filesystem::exists(state); waited_ms += 10) {
    if (waited_ms > 60000 || ::waitpid(first, nullptr, WNOHANG) == first) {
      ::kill(first, SIGKILL);
      ::waitpid(first, nullptr, 0);
      FAIL() << "the first run saved no checkpoint within 60 s";
    }
    ::usleep(10000);
  }
  auto second = run("run " + kExample + " --state " + state.string());
  ::kill(first, SIGTERM);
  ::waitpid(first, nullptr, 0);
  EXPECT_EQ(second.exit_code, 1) << second.out;
  EXPECT_TRUE(contains(second.out, "is in use by another softslc run")) << second.out;
}

// Killed saves left ".s.bin.XXXXXX" forever; a kept mode (0600) became 0644; a symlinked state
// file was replaced by a regular file.
TEST(HardeningState, StaleTemporariesGoModesStayLinksAreWrittenThrough) {
  auto dir = temp_file("state/x", "").parent_path();
  const auto state = dir / "real.bin";
  ASSERT_EQ(run("run " + kExample + " --state " + state.string()).exit_code, 0);
  std::filesystem::permissions(state, std::filesystem::perms::owner_read | std::filesystem::perms::owner_write);
  std::ofstream(dir / ".real.bin.AbC123") << "half a save";
  std::ofstream(dir / ".real.bin.keepme.txt") << "not ours";
  const auto link = dir / "link.bin";
  std::filesystem::remove(link);
  std::filesystem::create_symlink("real.bin", link);
  ASSERT_EQ(run("run " + kExample + " --state " + link.string() + " --set START_PB=1 --scans 3").exit_code, 0);
  EXPECT_TRUE(std::filesystem::is_symlink(link));
  EXPECT_FALSE(std::filesystem::exists(dir / ".real.bin.AbC123"));
  EXPECT_TRUE(std::filesystem::exists(dir / ".real.bin.keepme.txt"));
  EXPECT_EQ(std::filesystem::status(state).permissions() & std::filesystem::perms::all,
            std::filesystem::perms::owner_read | std::filesystem::perms::owner_write);
  // The run through the link saved into real.bin: the motor started then is still running.
  auto again = run("run " + kExample + " --state " + state.string() + " --print MOTOR");
  EXPECT_EQ(again.out, "MOTOR = 1\n");
}

// An unwritable location was found only after the whole run.
TEST(HardeningState, AnUnwritableLocationIsFoundBeforeTheFirstScan) {
  auto r = run("run " + kExample + " --state /proc/softslc-no-such-dir/s.bin --for 60s");
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_TRUE(contains(r.out, "--state /proc/softslc-no-such-dir/s.bin")) << r.out;
}

// `--junit` naming the test file overwrote it.
TEST(HardeningFiles, ReportsRefuseToOverwriteAnInput) {
  const auto dir = std::filesystem::path(SOFTSLC_SOURCE_DIR) / "examples/ladder/seal_in";
  auto copy = temp_file("overwrite/seal_in.test", read_all(dir / "seal_in.test"));
  std::filesystem::copy_file(dir / "seal_in.slc", copy.parent_path() / "seal_in.slc",
                             std::filesystem::copy_options::overwrite_existing);
  const std::string before = read_all(copy);
  auto j = run("test " + copy.string() + " --junit " + copy.string());
  EXPECT_EQ(j.exit_code, 2) << j.out;
  EXPECT_TRUE(contains(j.out, "refusing to overwrite it")) << j.out;
  auto c = run("test " + copy.string() + " --coverage-json " + (copy.parent_path() / "seal_in.slc").string());
  EXPECT_EQ(c.exit_code, 2) << c.out;
  EXPECT_EQ(read_all(copy), before);
}

// ---- Error reporting stays linear -------------------------------------------------------------------

// 20,000 errors on one line took 40 s and 6.9 GB; 80,000 bad rungs 17 s.
TEST(HardeningErrors, ErrorsAreCappedPerLineAndPerFile) {
  std::string line = "SOR";
  for (int i = 0; i < 20000; ++i) line += " XIC B3:0/16";
  line += " OTE B3:0/1 EOR\n";
  auto f = temp_file("many.slc", "START 1747-L532\nLADDER 2 MAIN\n" + line);
  auto r = run("check " + f.string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_LT(r.out.size(), 20000u) << r.out.substr(0, 2000);
  EXPECT_TRUE(contains(r.out, "more diagnostic(s) not shown")) << r.out.substr(0, 2000);
  EXPECT_TRUE(contains(r.out, "20000 errors")) << r.out.substr(r.out.size() - 500);
}

// A bench line with 800 copies of one attribute gave 319,600 errors (every pair).
TEST(HardeningErrors, DuplicateBenchAttributesAreReportedOnceEach) {
  std::string node = "scanner RIO slot=1";
  for (int i = 0; i < 800; ++i) node += " baud=115.2k";
  auto bench = temp_file("dup.bench", node + "\n");
  auto r = run("run " + kExample + " --bench " + bench.string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(contains(r.out, "attribute 'baud' is given twice")) << r.out.substr(0, 1000);
  EXPECT_LT(r.out.size(), 20000u);
}

// 20,000 nested blocks in a bench and 40,000 nested parentheses in an expect overflowed the stack.
TEST(HardeningNesting, BenchBlocksAndTestParenthesesHaveLimits) {
  std::string deep = "scanner RIO slot=1";
  for (int i = 0; i < 20000; ++i) deep += " {\nadapter A rack=0 group=0 size=full";
  auto bench = temp_file("deep.bench", deep + "\n");
  auto b = run("run " + kExample + " --bench " + bench.string());
  EXPECT_EQ(b.exit_code, 1) << b.out.substr(0, 1000);
  EXPECT_TRUE(contains(b.out, "blocks nested deeper than 64 levels")) << b.out.substr(0, 1000);
  auto dir = temp_file("paren/x", "").parent_path();
  std::filesystem::copy_file(kExample, dir / "seal_in.slc", std::filesystem::copy_options::overwrite_existing);
  auto t = temp_file("paren/deep.test", "program seal_in.slc\ntest \"t\"\n  expect " + std::string(40000, '(') +
                                            "MOTOR == 0" + std::string(40000, ')') + "\n");
  auto r = run("test " + t.string());
  EXPECT_EQ(r.exit_code, 2) << r.out.substr(0, 1000);
  EXPECT_TRUE(contains(r.out, "deep.test:3:74: error: parentheses nested deeper than 64 levels")) << r.out.substr(0, 1000);
}

// spdlog was a dependency used nowhere: --verbose logs what a run does with its files.
TEST(HardeningLog, VerboseLogsTheStateFile) {
  auto dir = temp_file("verbose/x", "").parent_path();
  const std::string state = (dir / "v.bin").string();
  std::filesystem::remove(state);
  auto r = run("--verbose run " + kExample + " --state " + state + " --scans 2");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_TRUE(contains(r.out, "softslc: [debug] " + state + ": does not exist yet")) << r.out;
  EXPECT_TRUE(contains(r.out, "softslc: [debug] " + state + ": saved after scan 2")) << r.out;
  EXPECT_FALSE(contains(run("run " + kExample + " --state " + state).out, "[debug]"));
}

// An unknown instruction was reported after "rung has no output instruction" (a consequence);
// a real instruction softslc lacks read like a typo.
TEST(HardeningCheckIsRun, UnknownAndUnsupportedInstructions) {
  auto typo = temp_file("typo.slc", "START 1747-L532\nLADDER 2 MAIN\nSOR XIC B3:0/0 FOO EOR\n");
  auto t = run("check " + typo.string());
  EXPECT_EQ(t.exit_code, 1);
  EXPECT_TRUE(contains(t.out, "typo.slc:3:16: error: unknown instruction 'FOO'")) << t.out;
  EXPECT_FALSE(contains(t.out, "rung has no output instruction")) << t.out;
  auto rcp = temp_file("rcp.slc", "START 1747-L532\nLADDER 2 MAIN\nSOR RCP EOR\n");
  auto p = run("check " + rcp.string());
  EXPECT_EQ(p.exit_code, 1);
  EXPECT_TRUE(contains(p.out, "rcp.slc:3:5: error: instruction RCP is not supported by softslc yet")) << p.out;
}

// `check` accepted a file of 65,536 rungs, which `run` refuses (rungs are numbered in 16 bits).
TEST(HardeningCheckIsRun, MoreRungsThanAFileCanHold) {
  std::string rungs;
  for (int i = 0; i < 65536; ++i) rungs += "SOR OTE B3:0/0 EOR\n";
  auto f = temp_file("rungs.slc", "START 1747-L532\nLADDER 2 MAIN\n" + rungs);
  auto c = run("check " + f.string());
  EXPECT_EQ(c.exit_code, 1);
  EXPECT_TRUE(contains(c.out, "rungs.slc:2:8: error: file 2 (line 2): more than 65535 rungs in one file")) << c.out;
}

}  // namespace
