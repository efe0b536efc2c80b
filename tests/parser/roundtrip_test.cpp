// fmt round trip: parsing the canonical text of a program gives the same program, for the
// fixture and for every example program shipped in examples/ladder.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "parser/formatter.h"
#include "parser/loader.h"

namespace softslc {
namespace {

void expect_round_trip(const std::filesystem::path& path) {
  auto first = load_program_file(path);
  ASSERT_TRUE(first.ok()) << first.render_diagnostics();
  std::string text = format_program(*first.program);
  auto second = load_program(text, path.string() + " (formatted)");
  ASSERT_TRUE(second.ok()) << second.render_diagnostics() << "\n" << text;
  std::string diff;
  EXPECT_TRUE(same_program(*first.program, *second.program, &diff)) << path << ": " << diff;
  // fmt is idempotent: formatting the formatted program changes nothing.
  EXPECT_EQ(format_program(*second.program), text) << path;
}

TEST(RoundTrip, Fixture) {
  expect_round_trip(std::filesystem::path(SOFTSLC_SHARED_DIR) / "fixtures/rslogix500/59-BSGS.SLC");
}

TEST(RoundTrip, EveryExampleProgram) {
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::recursive_directory_iterator(std::filesystem::path(SOFTSLC_SOURCE_DIR) /
                                                                     "examples/ladder"))
    if (e.is_regular_file() && e.path().extension() == ".slc") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  ASSERT_FALSE(files.empty());
  for (const auto& f : files) {
    SCOPED_TRACE(f.string());
    expect_round_trip(f);
  }
}

TEST(RoundTrip, CanonicalSpellingIsUsed) {
  auto r = load_program(
      "START 1747-L532\nSLOT 1 1746-IB16 SCAN_IN 1 SCAN_OUT 0\nLADDER 2\n"
      "SOR XIC I:1/3 XIC B3/62 XIC T4:0/13 MVM N7:0 0FF0h N7:1 MOV 1.0 F8:0 EOR\n",
      "t.slc");
  ASSERT_TRUE(r.ok()) << r.render_diagnostics();
  EXPECT_EQ(format_rung(r.program->files[0].rungs[0]),
            "SOR XIC I:1.0/3 XIC B3:3/14 XIC T4:0/DN MVM N7:0 0x0FF0 N7:1 MOV 1.0 F8:0 EOR");
}

}  // namespace
}  // namespace softslc
