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

namespace softslc::serve::testing {
namespace {

// M0/M1 over PCCC (server/pccc.h: softslc's file type F0h/F1h, file = slot, element = word) on the
// shipped 1747-SN example of the scanner manual's chapter 4 "RIO Status Example" (p. 4-28). Reads
// and writes go through the module, as the ladder's M0/M1 addresses and `run --set` do, so the
// module's rules are the client's: the SLC may not write the scanner's M1 (status) file (1747-SN
// manual p. B-1: "the M1 file is a module input file (a read only file)").
Bytes m_request(std::uint8_t fnc, std::uint8_t type, std::uint8_t slot, std::uint8_t word, const Bytes& data = {},
                std::uint8_t size = 2) {
  // Built byte by byte: GCC 12 warns falsely (-Warray-bounds) on inserting into a 9-byte vector.
  Bytes r;
  r.reserve(9 + data.size());
  for (const std::uint8_t b : {std::uint8_t{0x0F}, std::uint8_t{0x00}, std::uint8_t{0x21}, std::uint8_t{0x00}, fnc, size, slot, type, word})
    r.push_back(b);
  for (const std::uint8_t b : data) r.push_back(b);
  return r;
}

Bytes run_pccc(LiveController& live, const Bytes& request, std::string* refusal = nullptr) {
  std::string error;
  auto r = pccc::decode(request, &error);
  EXPECT_TRUE(r) << error;
  return r ? pccc::execute(*r, live, refusal) : Bytes{};
}

TEST(ModuleFiles, M0AndM1ThroughTheModuleWithItsRefusals) {
  const auto path = temp_journal("mfiles");
  const auto dir = std::filesystem::path(SOFTSLC_SOURCE_DIR) / "examples/ladder/1747-sn";
  {
    LiveOptions o;
    o.journal = path;
    LiveController live(dir / "ch4_m1_status.slc", dir / "ch4_m1_status.bench", o);
    live.advance(400 * kMs);
    // M1:1.0, the scanner's status word: bits 0-1 set (communication attempted, enabled device
    // fault), the figure's row that ch4_m1_status.test checks through the ladder's copy in N7:0.
    const Bytes read = run_pccc(live, m_request(pccc::kFncRead2, pccc::kTypeM1, 1, 0));
    ASSERT_EQ(read.size(), 6u);
    EXPECT_EQ(read[1], pccc::kStsOk);
    const int m1_0 = read[4] | read[5] << 8;
    EXPECT_EQ(m1_0 & 0x3, 0x3);
    EXPECT_EQ(m1_0, static_cast<std::uint16_t>(live.controller().get_int("M1:1.0")));

    // M0 word 210 (block-transfer buffer 2's first data word, 1747-SN ch. 5: no instruction uses
    // buffer 2 here): a word, then one bit of it with a masked write (FNC AB, mask 0008h).
    EXPECT_EQ(run_pccc(live, m_request(pccc::kFncWrite2, pccc::kTypeM0, 1, 210, {0x34, 0x12})),
              (Bytes{0x4F, 0x00, 0x21, 0x00}));
    EXPECT_EQ(live.controller().get_int("M0:1.210"), 0x1234);
    const Bytes mask = {0x0F, 0x00, 0x22, 0x00, 0xAB, 0x02, 1, pccc::kTypeM0, 210, 0, 0x08, 0x00, 0x00, 0x00};
    EXPECT_EQ(run_pccc(live, mask), (Bytes{0x4F, 0x00, 0x22, 0x00}));
    EXPECT_EQ(live.controller().get_int("M0:1.210"), 0x1234 & ~0x0008);

    // The module's refusal is the client's error: M1 is not writable by the SLC (EXT STS 10h).
    std::string why;
    EXPECT_EQ(run_pccc(live, m_request(pccc::kFncWrite2, pccc::kTypeM1, 1, 0, {0xFF, 0xFF}), &why),
              (Bytes{0x4F, 0xF0, 0x21, 0x00, pccc::kExtNoAccess}));
    EXPECT_NE(why.find("module refused"), std::string::npos) << why;
    EXPECT_EQ(live.controller().get_int("M1:1.0"), static_cast<std::int16_t>(m1_0));
    // No module in slot 5, a word past the scanner's M0 file: 06h.
    EXPECT_EQ(run_pccc(live, m_request(pccc::kFncRead2, pccc::kTypeM0, 5, 0)),
              (Bytes{0x4F, 0xF0, 0x21, 0x00, pccc::kExtAddressUnusable}));
    const Bytes past = {0x0F, 0x00, 0x21, 0x00, pccc::kFncRead2, 2, 1, pccc::kTypeM0, 0xFF, 0xE4, 0x0C};  // word 3300
    EXPECT_EQ(run_pccc(live, past), (Bytes{0x4F, 0xF0, 0x21, 0x00, pccc::kExtAddressUnusable}));
    // --read-only refuses M writes too (checked below on a second controller).
    live.advance(500 * kMs);
    live.finish();
  }
  // The M0 writes are journaled as `set` records and replay.
  auto r = replay(path);
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_EQ(r.writes, 2u);  // the word and the one masked bit
  EXPECT_EQ(r.controller->get_int("M0:1.210"), 0x1234 & ~0x0008);
  std::filesystem::remove(path);

  LiveOptions ro;
  ro.read_only = true;
  LiveController live(dir / "ch4_m1_status.slc", dir / "ch4_m1_status.bench", ro);
  EXPECT_EQ(run_pccc(live, m_request(pccc::kFncWrite2, pccc::kTypeM0, 1, 210, {0x34, 0x12})),
            (Bytes{0x4F, 0xF0, 0x21, 0x00, pccc::kExtNoAccess}));
}

}  // namespace
}  // namespace softslc::serve::testing
