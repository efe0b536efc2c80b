// Retentive state files: round trip, every corruption and truncation detected, refusal of a
// foreign program's state, and the CLI guarantees (state survives a "power cycle"; a bad file
// stops the run and is never overwritten; killing the process mid-save never loses the previous
// state; SIGTERM saves).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sys/wait.h>
#include <unistd.h>

#include "../cli/cli_test_util.h"
#include "modules/module_setup.h"
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

// ---- Module M-file words a module retains (format version 2) -----------------------------------

// A specialty card whose M1 words 4-11 survive a power loss (a module that keeps totals, say) and
// whose M0 does not; the ladder may write both files.
class RetentiveCard final : public Module {
 public:
  RetentiveCard(int slot, int retained_words) : Module(slot, "TEST-RETENTIVE", 0, 0), retained_words_(retained_words) {}
  void input_scan(std::span<std::uint16_t>) override {}
  void output_scan(std::span<const std::uint16_t>) override {}
  int m_file_words(MFile) const override { return 16; }
  MAccess read_m(MFile f, int word, std::uint16_t& value) override {
    if (word < 0 || word >= 16) return MAccess::NoSuchWord;
    value = file(f)[static_cast<std::size_t>(word)];
    return MAccess::Ok;
  }
  MAccess write_m(MFile f, int word, std::uint16_t value) override {
    if (word < 0 || word >= 16) return MAccess::NoSuchWord;
    file(f)[static_cast<std::size_t>(word)] = value;
    return MAccess::Ok;
  }
  std::vector<RetainedMWords> retained_m_words() const override {
    return {{MFile::M1, 4, std::vector<std::uint16_t>(m1_.begin() + 4, m1_.begin() + 4 + retained_words_)}};
  }
  void restore_m_words(const RetainedMWords& saved) override {
    ++restores;
    std::copy(saved.words.begin(), saved.words.end(), m1_.begin() + saved.first);
  }
  std::uint16_t m(MFile f, int word) { return file(f)[static_cast<std::size_t>(word)]; }
  int restores = 0;

 private:
  std::array<std::uint16_t, 16>& file(MFile f) { return f == MFile::M0 ? m0_ : m1_; }
  int retained_words_;
  std::array<std::uint16_t, 16> m0_{}, m1_{};
};

// Counts scans into N7:0 and copies the count to M0:1.5 (not retained) and M1:1.5 (retained).
const char* kRetentiveCardProgram =
    "START 1747-L532\nSLOT 1 1747-SN SCAN_IN 0 SCAN_OUT 0 M0_SIZE 16 M1_SIZE 16\nLADDER 2\n"
    "SOR ADD N7:0 1 N7:0 EOR\nSOR MOV N7:0 M0:1.5 MOV N7:0 M1:1.5 EOR\n";

struct CardRuntime {
  std::unique_ptr<Runtime> rt;
  RetentiveCard* card = nullptr;
};

CardRuntime make_card_runtime(const Program& p, int retained_words = 8) {
  CardRuntime c;
  RuntimeOptions options;
  options.module_factory = [&c, retained_words](const SlotConfig& s) -> std::unique_ptr<Module> {
    if (s.slot != 1) return nullptr;
    auto m = std::make_unique<RetentiveCard>(s.slot, retained_words);
    c.card = m.get();
    return m;
  };
  auto r = Runtime::create(p, options);
  EXPECT_TRUE(r.ok()) << r.render_errors();
  c.rt = std::move(r.runtime);
  EXPECT_NE(c.card, nullptr);
  return c;
}

// A saved state of the card program after 6 scans.
std::string saved_card_state(const Program& p) {
  auto a = make_card_runtime(p);
  a.rt->set_mode(Mode::Run);
  a.rt->scan(6);
  EXPECT_EQ(a.card->m(MFile::M1, 5), 6);
  return encode_state(a.rt->data(), program_fingerprint(p), chassis_modules(*a.rt));
}

TEST(StateModules, RetainedWordsSurviveAPowerCycleAndOthersDoNot) {
  auto p = load(kRetentiveCardProgram);
  const std::string bytes = saved_card_state(p);
  auto b = make_card_runtime(p);
  auto r = decode_state(bytes, program_fingerprint(p), b.rt->data(), false, chassis_modules(*b.rt));
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_TRUE(r.warnings.empty());
  EXPECT_EQ(b.card->restores, 1);
  EXPECT_EQ(b.card->m(MFile::M1, 5), 6);  // retained
  EXPECT_EQ(b.card->m(MFile::M0, 5), 0);  // not retained: the fresh module's power-up contents
  EXPECT_EQ(b.rt->value("N7:0").integer, 6);
}

TEST(StateModules, EveryCorruptedByteAndTruncationIsDetectedAndRestoresNothing) {
  auto p = load(kRetentiveCardProgram);
  const std::string good = saved_card_state(p);
  const auto fp = program_fingerprint(p);
  auto check_refused = [&](const std::string& bad, const std::string& what) {
    auto target = make_card_runtime(p);
    auto r = decode_state(bad, fp, target.rt->data(), false, chassis_modules(*target.rt));
    EXPECT_FALSE(r.ok) << what << " was not detected";
    EXPECT_EQ(target.card->restores, 0) << what;
    EXPECT_EQ(target.rt->value("N7:0").integer, 0) << what;
  };
  // The modules section is the last record before the CRC: 4 (count) + 12 (record header) + 16 bytes.
  const std::size_t modules_section = good.size() - 4 - (4 + 12 + 16);
  ASSERT_EQ(static_cast<std::uint8_t>(good[modules_section]), 1);  // one module record
  for (std::size_t i = 0; i < good.size(); ++i)
    for (std::uint8_t flip : {0x01, 0x80, 0xFF}) {
      std::string bad = good;
      bad[i] = static_cast<char>(bad[i] ^ flip);
      check_refused(bad, "byte " + std::to_string(i) + " flipped with " + std::to_string(flip));
    }
  for (std::size_t len = 0; len < good.size(); ++len) check_refused(good.substr(0, len), "truncation to " + std::to_string(len));
}

TEST(StateModules, AVersion1FileIsRefusedWithAClearError) {
  auto p = load(kRetentiveCardProgram);
  std::string v1 = saved_card_state(p);
  // The version word follows the 16-byte magic; re-seal the CRC so only the version is wrong.
  v1[16] = 1;
  v1.resize(v1.size() - 4);
  const std::uint32_t crc = crc32(v1.data(), v1.size());
  for (int k = 0; k < 4; ++k) v1.push_back(static_cast<char>(crc >> (8 * k)));
  auto target = make_card_runtime(p);
  auto r = decode_state(v1, program_fingerprint(p), target.rt->data(), false, chassis_modules(*target.rt));
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("format version 1 is no longer read"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("remove the file"), std::string::npos) << r.error;
  EXPECT_EQ(target.card->restores, 0);
}

TEST(StateModules, ARangeTheModuleDoesNotRetainIsRefusedUnlessForced) {
  auto p = load(kRetentiveCardProgram);
  const std::string bytes = saved_card_state(p);
  // The same program, but the module retains 6 words now (e.g. another softslc version).
  auto b = make_card_runtime(p, 6);
  auto refused = decode_state(bytes, program_fingerprint(p), b.rt->data(), false, chassis_modules(*b.rt));
  EXPECT_FALSE(refused.ok);
  EXPECT_NE(refused.error.find("state file holds M1:1.4-M1:1.11, which the module in slot 1 does not retain"),
            std::string::npos)
      << refused.error;
  EXPECT_EQ(b.rt->value("N7:0").integer, 0);
  auto forced = decode_state(bytes, program_fingerprint(p), b.rt->data(), true, chassis_modules(*b.rt));
  ASSERT_TRUE(forced.ok) << forced.error;
  EXPECT_EQ(b.card->restores, 0);
  EXPECT_EQ(b.rt->value("N7:0").integer, 6);
  ASSERT_EQ(forced.warnings.size(), 1u);
  EXPECT_NE(forced.warnings[0].find("M1:1.4-M1:1.11 from the state file is not retained"), std::string::npos);
}

TEST(StateModules, NoBuiltInModuleFamilyRetainsMFileWords) {
  // docs/robustness.md "Module M-file words": the 1747-SN's M0 is set to its defaults on entering
  // Run or Test and its M1 is status rebuilt after power-up; the 1203-SM1's M files are message
  // buffers (what survives is the drive's non-volatile storage); the 1747-SDN keeps its scanlist
  // in nonvolatile memory and its M-file tables in RAM.
  auto p = load("START 1747-L532\nSLOT 1 1747-SN SCAN_IN 32 SCAN_OUT 32 G_FILE 3\n 0 1 15\n"
                "SLOT 2 1203-SM1 SCAN_IN 32 SCAN_OUT 32 ID_CODE 13616 G_FILE 2\n 0 0\n"
                "SLOT 3 1747-SDN SCAN_IN 32 SCAN_OUT 32\nLADDER 2\nSOR OTE B3:0/0 EOR\n");
  auto setup = setup_modules(p, nullptr);
  auto r = Runtime::create(p, setup.options);
  ASSERT_TRUE(r.ok()) << r.render_errors();
  for (auto [slot, catalog] : {std::pair{1, "1747-SN"}, std::pair{2, "1203-SM1"}, std::pair{3, "1747-SDN"}}) {
    ASSERT_NE(r.runtime->module(slot), nullptr);
    EXPECT_EQ(r.runtime->module(slot)->catalog(), catalog);
    EXPECT_TRUE(r.runtime->module(slot)->retained_m_words().empty()) << catalog;
  }
}

// ---- Through the command line ------------------------------------------------------------------

std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(StateCli, DataSurvivesAPowerCycle) {
  const auto& dir = scratch_dir();
  auto prog = temp_file("counter.slc", kCounter);
  auto state = dir / "counter.state";
  std::filesystem::remove(state);
  auto first = run("run " + prog.string() + " --scans 5 --state " + state.string() + " --print N7:0");
  EXPECT_EQ(first.out, "N7:0 = 5\n");
  auto second = run("run " + prog.string() + " --scans 5 --state " + state.string() + " --print N7:0");
  EXPECT_EQ(second.out, "N7:0 = 10\n");
}

TEST(StateCli, BadStateFileStopsTheRunAndIsNeverOverwritten) {
  const auto& dir = scratch_dir();
  auto prog = temp_file("counter2.slc", kCounter);
  auto state = dir / "bad.state";
  std::ofstream(state, std::ios::binary) << "SOFTSLC-STATE\n garbage";
  const std::string before = read_file(state);
  auto r = run("run " + prog.string() + " --scans 5 --state " + state.string() + " --print N7:0");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find("bad.state: "), std::string::npos) << r.out;
  EXPECT_EQ(read_file(state), before);

  // A state from another program is refused too, unless forced.
  auto other = dir / "other.slc";
  std::ofstream(other) << "START 1747-L532\nLADDER 2\nSOR ADD N7:0 2 N7:0 EOR\n";
  auto good = dir / "good.state";
  std::filesystem::remove(good);
  ASSERT_EQ(run("run " + prog.string() + " --scans 3 --state " + good.string()).exit_code, 0);
  const std::string saved = read_file(good);
  auto foreign = run("run " + other.string() + " --scans 1 --state " + good.string() + " --print N7:0");
  EXPECT_EQ(foreign.exit_code, 1);
  EXPECT_NE(foreign.out.find("saved by a different program"), std::string::npos) << foreign.out;
  EXPECT_EQ(read_file(good), saved);
  auto forced = run("run " + other.string() + " --scans 1 --state " + good.string() + " --force-state --print N7:0");
  EXPECT_EQ(forced.exit_code, 0) << forced.out;
  EXPECT_NE(forced.out.find("N7:0 = 5"), std::string::npos) << forced.out;
}

// Kill the process at many points while it checkpoints every 10 ms of virtual time (thousands of
// saves per second of wall time): after every kill the state file is a complete, valid state,
// and the counter it holds never goes backwards.
TEST(StateCli, KillingDuringSavesNeverLosesTheState) {
  const auto& dir = scratch_dir();
  auto prog = temp_file("counter3.slc", kCounter);
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
      // A child that cannot silence its output exits (126) rather than run unsilenced.
      if (!std::freopen("/dev/null", "w", stdout) || !std::freopen("/dev/null", "w", stderr)) ::_exit(126);
      ::execl(SOFTSLC_BINARY, SOFTSLC_BINARY, "run", prog.c_str(), "--for", "60m", "--state", state.c_str(),
              "--checkpoint", "10ms", static_cast<char*>(nullptr));
      ::_exit(127);
    }
    // Wait until this run has replaced the state file at least once, then kill it at a varied
    // point 0-60 ms later: the kill lands among the saves however long the process took to start
    // (on a loaded machine start-up alone can exceed a fixed delay, and no kill would test a save).
    const auto saved_before = std::filesystem::exists(state) ? std::filesystem::last_write_time(state)
                                                             : std::filesystem::file_time_type::min();
    for (int waited_ms = 0;; ++waited_ms) {
      std::error_code ec;
      const auto t = std::filesystem::last_write_time(state, ec);
      if (!ec && t != saved_before) break;
      if (waited_ms > 20000) {
        ::kill(pid, SIGKILL);
        ::waitpid(pid, nullptr, 0);
        FAIL() << "run " << i << " saved no state within 20 s";
      }
      ::usleep(1000);
    }
    ::usleep(static_cast<useconds_t>(7919 * i % 60000));
    ::kill(pid, SIGKILL);
    int st = 0;
    ::waitpid(pid, &st, 0);
    ASSERT_TRUE(WIFSIGNALED(st)) << "the run ended by itself before the kill";
    auto rt = make_runtime(program);
    auto r = decode_state(read_file(state), fp, rt->data(), false);
    ASSERT_TRUE(r.ok) << "after kill " << i << ": " << r.error;
    ++valid_after_kill;
    std::int64_t now = scans_counted(*rt);
    EXPECT_GE(now, last) << "after kill " << i;
    last = now;
  }
  EXPECT_EQ(valid_after_kill, 25);
  // Leftover temporary files of interrupted saves are never mistaken for the state.
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().filename().string().rfind(".kill.state.", 0) == 0) std::filesystem::remove(e.path());
}

TEST(StateCli, SigtermSavesAndExits) {
  const auto& dir = scratch_dir();
  auto prog = temp_file("counter4.slc", kCounter);
  auto state = dir / "term.state";
  std::filesystem::remove(state);
  pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    if (!std::freopen("/dev/null", "w", stdout)) ::_exit(126);
    ::execl(SOFTSLC_BINARY, SOFTSLC_BINARY, "run", prog.c_str(), "--for", "60m", "--state", state.c_str(),
            "--checkpoint", "1s", static_cast<char*>(nullptr));
    ::_exit(127);
  }
  // Signal only once the scan loop runs (its first checkpoint has written the state file): a
  // fixed delay lost the race to a slow start under AddressSanitizer, and a SIGTERM before the
  // handler is installed kills the process instead of stopping it.
  for (int waited_ms = 0; !std::filesystem::exists(state); ++waited_ms) {
    if (waited_ms > 30000) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, nullptr, 0);
      FAIL() << "the run saved no checkpoint within 30 s";
    }
    ::usleep(1000);
  }
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
