// Pacing and the journal: virtual time follows the wall time given, times the speed, in whole
// scans; a journal replayed into a fresh controller reaches the same data table at every write.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "tests/serve/serve_test_util.h"

namespace softslc::serve::testing {
namespace {

constexpr Nanoseconds kMs = 1000000;

std::filesystem::path temp_journal(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("softslc-serve-" + name + "-" + std::to_string(::getpid()) + ".journal");
}

TEST(Pacing, VirtualTimeFollowsWallTimeTimesSpeedWithinOneScan) {
  LiveOptions o;
  o.speed = 10.0;
  LiveController live(hmi_program(), std::nullopt, o);
  live.advance(100 * kMs);  // 100 ms of wall time at speed 10: 1 s of virtual time
  const VirtualTime t = live.controller().now();
  EXPECT_GE(t, 1000 * kMs);
  // Whole scans: the overshoot is less than one scan (this program's scans are well under 10 ms).
  EXPECT_LT(t, 1010 * kMs);
  EXPECT_EQ(live.lag(), 0);
}

TEST(Pacing, PausedRunsOnlySingleSteps) {
  LiveOptions o;
  o.paused = true;
  LiveController live(hmi_program(), std::nullopt, o);
  EXPECT_EQ(live.advance(500 * kMs), 0);
  EXPECT_EQ(live.controller().scans(), 0u);
  live.step(1);
  EXPECT_EQ(live.controller().scans(), 1u);
  live.resume();
  live.advance(50 * kMs);
  EXPECT_GT(live.controller().scans(), 1u);
}

TEST(Journal, ReplayReproducesTheDataTableAtEveryWrite) {
  const auto path = temp_journal("replay");
  std::uint32_t final_digest = 0;
  {
    LiveOptions o;
    o.journal = path;
    LiveController live(hmi_program(), std::nullopt, o);
    live.advance(20 * kMs);
    const std::uint16_t start = 0x0002, mask = 0x0002;  // B3:0/1, HMI_START
    EXPECT_EQ(live.write(3, 0, std::span(&start, 1), std::span(&mask, 1)), "");
    live.advance(300 * kMs);
    const std::uint16_t speed[2] = {0x0000, 0x4148};  // F8:2 = 12.5
    const std::uint16_t all[2] = {0xFFFF, 0xFFFF};
    EXPECT_EQ(live.write(8, 4, speed, all), "");
    const std::uint16_t n = 1234, full = 0xFFFF;
    EXPECT_EQ(live.write(7, 0, std::span(&n, 1), std::span(&full, 1)), "");
    live.advance(700 * kMs);
    const std::uint16_t text[2] = {2, 0x4F4B};  // ST9:1 = "OK"
    EXPECT_EQ(live.write(9, 42, text, all), "");
    live.advance(1000 * kMs);
    live.finish();
    final_digest = live.controller().data_digest();
    EXPECT_EQ(live.controller().get_int("N7:1"), 1234);  // the ladder copied the write
  }
  auto r = replay(path);
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_EQ(r.writes, 5u);   // one bit, one float, one word, two string words
  EXPECT_EQ(r.digests, 5u);  // four requests and the end
  EXPECT_EQ(r.controller->data_digest(), final_digest);

  // A journal whose write is changed no longer replays to the same history.
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  const auto at = s.find(" N7:0 1234");
  ASSERT_NE(at, std::string::npos);
  s.replace(at, 10, " N7:0 1235");
  in.close();
  std::ofstream(path) << s;
  auto bad = replay(path);
  EXPECT_FALSE(bad.ok);
  EXPECT_NE(bad.message.find("data table differs"), std::string::npos) << bad.message;
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace softslc::serve::testing
