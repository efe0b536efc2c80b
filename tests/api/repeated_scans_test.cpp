// Repeated scans (docs/semantics.md "Repeated scans"): run_for may take a scan that would repeat
// the one before without executing it. These tests hold it to "same results": every shipped
// example, and programs built to catch a wrong skip, run side by side with the skip on and off and
// must agree word for word at every observation point, while the skip must actually happen where
// it may (else the speed-up silently stopped working).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "tools/controller/controller.h"
#include "vm/runtime.h"

namespace softslc {
namespace {

namespace fs = std::filesystem;

std::vector<std::uint16_t> table(const Controller& c) {
  const DataTable& d = c.runtime().data();
  return {d.words(), d.words() + d.size()};
}

// Runs both controllers in `slices` steps of `slice` and requires the same state after each.
// Returns the scans the skipping one took without executing them.
std::uint64_t run_side_by_side(Controller& skipping, Controller& executing, int slices, Nanoseconds slice,
                               const std::string& what) {
  executing.runtime().skip_repeated_scans(false);
  for (int i = 0; i < slices; ++i) {
    const auto a = skipping.run_for(slice);
    const auto b = executing.run_for(slice);
    EXPECT_EQ(a, b) << what << " slice " << i << ": scans run";
    EXPECT_EQ(skipping.now(), executing.now()) << what << " slice " << i;
    const ScanStats& sa = skipping.runtime().stats();
    const ScanStats& sb = executing.runtime().stats();
    EXPECT_EQ(sa.scans, sb.scans) << what << " slice " << i;
    EXPECT_EQ(sa.total, sb.total) << what << " slice " << i;
    EXPECT_EQ(sa.max, sb.max) << what << " slice " << i;
    EXPECT_EQ(sa.last, sb.last) << what << " slice " << i;
    EXPECT_EQ(sa.instructions, sb.instructions) << what << " slice " << i;
    EXPECT_EQ(skipping.fault().has_value(), executing.fault().has_value()) << what << " slice " << i;
    const auto ta = table(skipping), tb = table(executing);
    if (ta != tb) {
      const auto at = std::mismatch(ta.begin(), ta.end(), tb.begin()).first - ta.begin();
      ADD_FAILURE() << what << " slice " << i << ": data tables differ first at word " << at << " ("
                    << ta[static_cast<std::size_t>(at)] << " against " << tb[static_cast<std::size_t>(at)] << ")";
      break;
    }
    if (executing.fault()) break;
  }
  EXPECT_EQ(executing.runtime().stats().repeated, 0u) << what;
  return skipping.runtime().stats().repeated;
}

TEST(RepeatedScans, EveryShippedExampleGivesTheSameResultsWithAndWithoutThem) {
  const fs::path root = fs::path(SOFTSLC_SOURCE_DIR) / "examples" / "ladder";
  std::vector<fs::path> programs;
  for (const auto& e : fs::recursive_directory_iterator(root))
    if (e.is_regular_file() && e.path().extension() == ".slc") programs.push_back(e.path());
  std::sort(programs.begin(), programs.end());
  ASSERT_GT(programs.size(), 40u);
  int repeating = 0;
  for (const fs::path& p : programs) {
    fs::path bench = p;
    bench.replace_extension(".bench");
    const std::optional<fs::path> b = fs::exists(bench) ? std::optional<fs::path>(bench) : std::nullopt;
    Controller skipping = Controller::load(p, b);
    Controller executing = Controller::load(p, b);
    // 10 s in 100 ms slices, as sim_bench runs them.
    const std::uint64_t repeated = run_side_by_side(skipping, executing, 100, milliseconds(100), p.filename().string());
    if (repeated > 0) ++repeating;
    // The idle MicroLogix examples (no module, no interrupt, no clock read) must repeat nearly
    // every scan: quiet_scans finds them quiet in 97-100% of their scans.
    if (p.parent_path().filename() == "micrologix" && p.stem() == "ml1100_conveyor") {
      EXPECT_GT(repeated, skipping.runtime().stats().scans * 9 / 10) << p;
    }
  }
  EXPECT_GT(repeating, 5);
}

// A TON timing in an otherwise idle program: between its 10 ms ticks every scan changes nothing,
// so a skip that ignored the timer would jump past ticks. The timer's TT vetoes it; once DN, the
// scans repeat again.
TEST(RepeatedScans, ATimerTimingIsNeverSkippedOver) {
  const std::string text =
      "START 1747-L552\nSLOT 1 1746-IB16 SCAN_IN 1 SCAN_OUT 0\nSLOT 2 1746-OB16 SCAN_IN 0 SCAN_OUT 1\n"
      "LADDER 2\nSOR XIC I:1/0 TON T4:0 0.01 250 0 EOR\nSOR XIC T4:0/DN OTE O:2/0 EOR\nSOR END EOR\n";
  Controller skipping = Controller::from_text(text);
  Controller executing = Controller::from_text(text);
  skipping.run_for(milliseconds(500));
  executing.runtime().skip_repeated_scans(false);
  executing.run_for(milliseconds(500));
  const std::uint64_t idle = skipping.runtime().stats().repeated;
  EXPECT_GT(idle, 0u);
  skipping.set("I:1/0", 1);
  executing.set("I:1/0", 1);
  run_side_by_side(skipping, executing, 40, milliseconds(100), "TON 2.5 s");
  EXPECT_EQ(skipping.get_int("T4:0.ACC"), 250);
  EXPECT_TRUE(skipping.get_bit("O:2/0"));
  EXPECT_GT(skipping.runtime().stats().repeated, idle);
}

// A program that reads the free-running clock (S:4) or the scan toggle bit (S:33/9) never has its
// scans repeated: they differ from one scan to the next although the data table may not show it
// until the clock reaches a value.
TEST(RepeatedScans, AProgramReadingTheRuntimesOwnStatusWordsIsNeverRepeated) {
  for (const char* rung : {"SOR EQU S:4 900 OTL B3:0/0 EOR\n", "SOR XIC S:33/9 OTE B3:0/1 EOR\n"}) {
    const std::string text = std::string("START 1747-L552\nLADDER 2\n") + rung;
    Controller skipping = Controller::from_text(text);
    Controller executing = Controller::from_text(text);
    EXPECT_EQ(run_side_by_side(skipping, executing, 120, milliseconds(100), rung), 0u);
  }
}

// An input whose change reaches the input image after the module's input delay is an event: the
// skip stops before it, and the program sees the input at the same scan as without the skip.
TEST(RepeatedScans, AnInputArrivingAfterItsDelayStopsTheRepeats) {
  const std::string text =
      "START 1747-L552\nSLOT 1 1746-IB16 SCAN_IN 1 SCAN_OUT 0\nLADDER 2\n"
      "SOR XIC I:1/0 OSR B3:0/0 ADD N7:0 1 N7:0 EOR\nSOR XIC I:1/0 OTE B3:0/1 EOR\n";
  const std::string bench = "io sensors slot=1 input_delay=3ms\n";
  Controller skipping = Controller::from_text(text, bench);
  Controller executing = Controller::from_text(text, bench);
  executing.runtime().skip_repeated_scans(false);
  run_side_by_side(skipping, executing, 5, milliseconds(10), "before the input");
  for (int i = 0; i < 5; ++i) {
    skipping.inject("sensors", "input", {i % 2 ? "0" : "1"});
    executing.inject("sensors", "input", {i % 2 ? "0" : "1"});
    run_side_by_side(skipping, executing, 3, milliseconds(7), "input delay");
  }
  EXPECT_EQ(skipping.get_int("N7:0"), 3);
  EXPECT_GT(skipping.runtime().stats().repeated, 0u);
}

}  // namespace
}  // namespace softslc
