// Retentive state files: round trip, every corruption and truncation detected, refusal of a
// foreign program's state, and the CLI guarantees (state survives a "power cycle"; a bad file
// stops the run and is never overwritten; killing the process mid-save never loses the previous
// state; SIGTERM saves).
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sys/wait.h>
#include <unistd.h>

#include "parser/loader.h"
#include "vm/runtime.h"
#include "vm/state_file.h"

namespace softslc {
namespace {

// Counts scans in N7:2 * 10000 + N7:0 (rolling N7:0 over before it could overflow).
const char* kCounter =
    "START 1747-L532\nLADDER 2\nSOR ADD N7:0 1 N7:0 EOR\nSOR MOV 1234 N7:1 EOR\nSOR OTE B3:0/5 EOR\n"
    "SOR GEQ N7:0 10000 BST CLR N7:0 NXB ADD N7:2 1 N7:2 BND EOR\n";

std::int64_t scans_counted(Runtime& rt) { return rt.value("N7:2").integer * 10000 + rt.value("N7:0").integer; }

std::unique_ptr<Runtime> make_runtime(const Program& p) {
  auto r = Runtime::create(p);
  EXPECT_TRUE(r.ok()) << r.render_errors();
  return std::move(r.runtime);
}

Program load(const std::string& text) {
  auto r = load_program(text, "t.slc");
  EXPECT_TRUE(r.ok()) << r.render_diagnostics();
  return *r.program;
}

TEST(StateFile, RoundTripRestoresEveryWord) {
  auto p = load(kCounter);
  auto a = make_runtime(p);
  a->set_mode(Mode::Run);
  a->scan(7);
  auto fp = program_fingerprint(p);
  std::string bytes = encode_state(a->data(), fp);
  auto b = make_runtime(p);
  auto r = decode_state(bytes, fp, b->data(), false);
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_EQ(a->data().size(), b->data().size());
  for (std::uint32_t i = 0; i < a->data().size(); ++i) EXPECT_EQ(a->data().word(i), b->data().word(i)) << i;
  EXPECT_EQ(b->value("N7:0").integer, 7);
}

TEST(StateFile, EveryCorruptedByteIsDetected) {
  auto p = load(kCounter);
  auto rt = make_runtime(p);
  auto fp = program_fingerprint(p);
  const std::string good = encode_state(rt->data(), fp);
  for (std::size_t i = 0; i < good.size(); ++i) {
    for (std::uint8_t flip : {0x01, 0x80, 0xFF}) {
      std::string bad = good;
      bad[i] = static_cast<char>(bad[i] ^ flip);
      auto target = make_runtime(p);
      auto before = std::vector<std::uint16_t>(target->data().words(), target->data().words() + target->data().size());
      auto r = decode_state(bad, fp, target->data(), false);
      EXPECT_FALSE(r.ok) << "byte " << i << " flipped with " << int(flip) << " was not detected";
      // A refused file restores nothing.
      EXPECT_TRUE(std::equal(before.begin(), before.end(), target->data().words())) << i;
    }
  }
}

TEST(StateFile, EveryTruncationIsDetected) {
  auto p = load(kCounter);
  auto rt = make_runtime(p);
  auto fp = program_fingerprint(p);
  const std::string good = encode_state(rt->data(), fp);
  for (std::size_t len = 0; len < good.size(); ++len) {
    auto target = make_runtime(p);
    EXPECT_FALSE(decode_state(good.substr(0, len), fp, target->data(), false).ok) << len;
  }
  auto target = make_runtime(p);
  EXPECT_FALSE(decode_state(good + "x", fp, target->data(), false).ok);
}

TEST(StateFile, ForeignProgramIsRefusedUnlessForced) {
  auto p = load(kCounter);
  auto a = make_runtime(p);
  a->set_mode(Mode::Run);
  a->scan(3);
  std::string bytes = encode_state(a->data(), program_fingerprint(p));
  // Another program: N7 has one element more, B3 is the same, and it has an extra N10 file.
  auto q = load("START 1747-L532\nLADDER 2\nSOR MOV 5 N7:3 EOR\nSOR OTE B3:0/1 EOR\nSOR MOV 9 N10:0 EOR\n");
  auto b = make_runtime(q);
  auto refused = decode_state(bytes, program_fingerprint(q), b->data(), false);
  EXPECT_FALSE(refused.ok);
  EXPECT_NE(refused.error.find("saved by a different program"), std::string::npos) << refused.error;
  EXPECT_NE(refused.error.find("--force-state"), std::string::npos);
  auto forced = decode_state(bytes, program_fingerprint(q), b->data(), true);
  ASSERT_TRUE(forced.ok) << forced.error;
  EXPECT_EQ(b->value("N7:0").integer, 3);
  EXPECT_EQ(b->value("N7:1").integer, 1234);
  bool warned_n7 = false;
  for (const auto& w : forced.warnings) warned_n7 |= w.find("file N7 has 4 elements here and 3") != std::string::npos;
  EXPECT_TRUE(warned_n7);
}

// ---- Through the command line ------------------------------------------------------------------

struct Cmd {
  int exit_code;
  std::string out;
};

Cmd run_cli(const std::string& args) {
  std::string cmd = std::string(SOFTSLC_BINARY) + " " + args + " 2>&1";
  Cmd r{-1, {}};
  FILE* p = ::popen(cmd.c_str(), "r");
  char buf[4096];
  while (std::size_t n = std::fread(buf, 1, sizeof buf, p)) r.out.append(buf, n);
  int st = ::pclose(p);
  r.exit_code = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

std::filesystem::path scratch() {
  auto d = std::filesystem::temp_directory_path() / ("softslc-state-" + std::to_string(::getpid()));
  std::filesystem::create_directories(d);
  return d;
}

std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(StateCli, DataSurvivesAPowerCycle) {
  auto dir = scratch();
  auto prog = dir / "counter.slc";
  std::ofstream(prog) << kCounter;
  auto state = dir / "counter.state";
  std::filesystem::remove(state);
  auto first = run_cli("run " + prog.string() + " --scans 5 --state " + state.string() + " --print N7:0");
  EXPECT_EQ(first.out, "N7:0 = 5\n");
  auto second = run_cli("run " + prog.string() + " --scans 5 --state " + state.string() + " --print N7:0");
  EXPECT_EQ(second.out, "N7:0 = 10\n");
}

TEST(StateCli, BadStateFileStopsTheRunAndIsNeverOverwritten) {
  auto dir = scratch();
  auto prog = dir / "counter2.slc";
  std::ofstream(prog) << kCounter;
  auto state = dir / "bad.state";
  std::ofstream(state, std::ios::binary) << "SOFTSLC-STATE\n garbage";
  const std::string before = read_file(state);
  auto r = run_cli("run " + prog.string() + " --scans 5 --state " + state.string() + " --print N7:0");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find("bad.state: "), std::string::npos) << r.out;
  EXPECT_EQ(read_file(state), before);

  // A state from another program is refused too, unless forced.
  auto other = dir / "other.slc";
  std::ofstream(other) << "START 1747-L532\nLADDER 2\nSOR ADD N7:0 2 N7:0 EOR\n";
  auto good = dir / "good.state";
  std::filesystem::remove(good);
  ASSERT_EQ(run_cli("run " + prog.string() + " --scans 3 --state " + good.string()).exit_code, 0);
  const std::string saved = read_file(good);
  auto foreign = run_cli("run " + other.string() + " --scans 1 --state " + good.string() + " --print N7:0");
  EXPECT_EQ(foreign.exit_code, 1);
  EXPECT_NE(foreign.out.find("saved by a different program"), std::string::npos) << foreign.out;
  EXPECT_EQ(read_file(good), saved);
  auto forced = run_cli("run " + other.string() + " --scans 1 --state " + good.string() + " --force-state --print N7:0");
  EXPECT_EQ(forced.exit_code, 0) << forced.out;
  EXPECT_NE(forced.out.find("N7:0 = 5"), std::string::npos) << forced.out;
}

// Kill the process at many points while it checkpoints every 10 ms of virtual time (thousands of
// saves per second of wall time): after every kill the state file is a complete, valid state,
// and the counter it holds never goes backwards.
TEST(StateCli, KillingDuringSavesNeverLosesTheState) {
  auto dir = scratch();
  auto prog = dir / "counter3.slc";
  std::ofstream(prog) << kCounter;
  auto state = dir / "kill.state";
  std::filesystem::remove(state);
  auto program = load(kCounter);
  const auto fp = program_fingerprint(program);
  std::int64_t last = 0;
  int valid_after_kill = 0;
  for (int i = 0; i < 25; ++i) {
    pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      std::freopen("/dev/null", "w", stdout);
      std::freopen("/dev/null", "w", stderr);
      ::execl(SOFTSLC_BINARY, SOFTSLC_BINARY, "run", prog.c_str(), "--for", "60m", "--state", state.c_str(),
              "--checkpoint", "10ms", static_cast<char*>(nullptr));
      ::_exit(127);
    }
    ::usleep(static_cast<useconds_t>(20000 + 7919 * i % 60000));
    ::kill(pid, SIGKILL);
    int st = 0;
    ::waitpid(pid, &st, 0);
    ASSERT_TRUE(WIFSIGNALED(st)) << "the run ended by itself before the kill";
    if (!std::filesystem::exists(state)) continue;  // killed before the first checkpoint
    auto rt = make_runtime(program);
    auto r = decode_state(read_file(state), fp, rt->data(), false);
    ASSERT_TRUE(r.ok) << "after kill " << i << ": " << r.error;
    ++valid_after_kill;
    std::int64_t now = scans_counted(*rt);
    EXPECT_GE(now, last) << "after kill " << i;
    last = now;
  }
  EXPECT_GT(valid_after_kill, 10);
  // Leftover temporary files of interrupted saves are never mistaken for the state.
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().filename().string().rfind(".kill.state.", 0) == 0) std::filesystem::remove(e.path());
}

TEST(StateCli, SigtermSavesAndExits) {
  auto dir = scratch();
  auto prog = dir / "counter4.slc";
  std::ofstream(prog) << kCounter;
  auto state = dir / "term.state";
  std::filesystem::remove(state);
  pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    std::freopen("/dev/null", "w", stdout);
    ::execl(SOFTSLC_BINARY, SOFTSLC_BINARY, "run", prog.c_str(), "--for", "60m", "--state", state.c_str(),
            static_cast<char*>(nullptr));
    ::_exit(127);
  }
  ::usleep(200000);
  ::kill(pid, SIGTERM);
  int st = 0;
  ::waitpid(pid, &st, 0);
  ASSERT_TRUE(WIFEXITED(st));
  EXPECT_EQ(WEXITSTATUS(st), 128 + SIGTERM);
  auto program = load(kCounter);
  auto rt = make_runtime(program);
  auto r = decode_state(read_file(state), program_fingerprint(program), rt->data(), false);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_GT(scans_counted(*rt), 0);
}

}  // namespace
}  // namespace softslc
