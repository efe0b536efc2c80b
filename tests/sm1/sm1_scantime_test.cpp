// `softslc scantime` charges the 1203-SM1 examples' M0/M1 accesses per the manual's access-time
// table (1203-SM1 user manual appendix A, "Access Time", p. A-5).
#include <gtest/gtest.h>

#include "instructions/processor.h"
#include "parser/loader.h"
#include "sm1_test_util.h"
#include "vm/scantime.h"

namespace softslc::test {
namespace {

Nanoseconds mfile_of(const std::string& example, const std::string& catalog, std::optional<char> series) {
  auto lr = load_program(sm1_example(example), example);
  EXPECT_TRUE(lr.ok()) << lr.render_diagnostics();
  auto proc = resolve_processor(catalog, series);
  EXPECT_TRUE(proc.has_value());
  auto profile = builtin_timing_profile(proc->timing_key());
  EXPECT_TRUE(profile.has_value());
  return predict_scan_time(*lr.program, *proc, *profile).total_mfile;
}

// Figure B.3's program copies 100 words to M0 (rung 0) and 100 words from M1 (rung 2).
TEST(Sm1ScanTime, FigureB3ProgramIsChargedPerTheAccessTable) {
  // SLC 5/02 Series B, all types: 1580 us + 670 us per word, each copy.
  EXPECT_EQ(mfile_of("appb_messaging.slc", "1747-L524", 'B'), 2 * microseconds(1580 + 670 * 100));
  // Series C: 950 us + 400 us per word.
  EXPECT_EQ(mfile_of("appb_messaging.slc", "1747-L524", 'C'), 2 * microseconds(950 + 400 * 100));
  // SLC 5/03: COP to M file 772 us + 23 us per word; COP from M file 760 us + 22 us per word.
  EXPECT_EQ(mfile_of("appb_messaging.slc", "1747-L532", {}), microseconds(772 + 2300 + 760 + 2200));
  // SLC 5/04 OS400: 735 + 23 per word; 722 + 22 per word.
  EXPECT_EQ(mfile_of("appb_messaging.slc", "1747-L542", {}), microseconds(735 + 2300 + 722 + 2200));
}

TEST(Sm1ScanTime, ImageOnlyExamplesHaveNoMFileAccess) {
  for (const char* e : {"ch3_basic_drives.slc", "ch4_enhanced_drives.slc", "ch4_datalink.slc", "ch4_safe_state.slc"})
    EXPECT_EQ(mfile_of(e, "1747-L532", {}), 0) << e;
}

}  // namespace
}  // namespace softslc::test
