// SVC on the MicroLogix (issue 16): the channel select each controller takes, and the execution
// times its manual prints per channel, in `scantime` and in virtual time.
//
// Manual facts used: "the channel select variable is a one-word bit pattern ... bit 0 equals channel
// 0" (1762-RM001C p. 21-26, 1766-RM001A p. 396); the channel-select table (1762-RM001C p. 21-27):
// MicroLogix 1200 and the 1500 LSP take 1 (channel 0), the 1500 LRP 1, 2 or 3 (both); the execution
// times: 1762-RM001C p. 21-26 Table 21.4 (1200 208 us, 1500 166 us with one channel and 327 us with
// both, 0.0 us false), 1763-RM001B p. 344 (1100 channel 0 94.1 us, channel 1 87.0 us, both 203.1 us,
// 0.8 us false), 1766-RM001A p. 396 (1400 CH0 39.8260 us, CH1 5.9042 us, both 36.5800 us; false
// 0.1933, 0.1857, 0.1774 us).
#include <gtest/gtest.h>

#include <algorithm>
#include <iterator>
#include <string>
#include <utility>

#include "load_errors.h"
#include "parser/loader.h"
#include "tools/controller/controller.h"
#include "vm/scantime.h"
#include "vm/timing_profile.h"

namespace softslc {
namespace {

using test::load_errors;

std::string svc_program(const std::string& processor, const std::string& rungs) {
  return "START " + processor + "\nLADDER 2\n" + rungs;
}

TEST(MicroLogixSvc, EachControllerTakesTheChannelSelectsOfItsManual) {
  for (const char* p : {"Bul.1763", "Bul.1766", "1764-LRP"})
    for (const char* sel : {"1", "2", "3"})
      EXPECT_EQ(load_errors(svc_program(p, std::string("SOR SVC ") + sel + " EOR\n")), "") << p << " SVC " << sel;
  for (const char* p : {"Bul.1762", "1764-LSP"}) {
    EXPECT_EQ(load_errors(svc_program(p, "SOR SVC 1 EOR\n")), "") << p;
    for (const char* sel : {"2", "3"}) {
      const std::string e = load_errors(svc_program(p, std::string("SOR SVC ") + sel + " EOR\n"));
      EXPECT_NE(e.find("t.slc:3:9: error: SVC channel select " + std::string(sel) + ": the MicroLogix"),
                std::string::npos)
          << p << ": " << e;
      EXPECT_NE(e.find("has one channel, channel 0: its channel select is 1 (1762-RM001C p. 21-27)"), std::string::npos) << e;
    }
  }
  // The table's range (bits 0 and 1) holds on every processor; the MicroLogix SVC has no form
  // without a channel select, and the MicroLogix 1000 has no SVC in softslc's sources.
  EXPECT_NE(load_errors(svc_program("Bul.1763", "SOR SVC 4 EOR\n")).find("out of range"), std::string::npos)
      << load_errors(svc_program("Bul.1763", "SOR SVC 4 EOR\n"));
  EXPECT_NE(load_errors(svc_program("Bul.1763", "SOR SVC EOR\n")).find("takes a channel select on the MicroLogix 1100"),
            std::string::npos)
      << load_errors(svc_program("Bul.1763", "SOR SVC EOR\n"));
  EXPECT_NE(load_errors(svc_program("Bul.1761", "SOR SVC 1 EOR\n")).find("SVC is not available on the MicroLogix 1000"),
            std::string::npos)
      << load_errors(svc_program("Bul.1761", "SOR SVC 1 EOR\n"));
  // The SLC 5/02's SVC takes no operand (RM 12-41).
  EXPECT_NE(load_errors("START 1747-L524\nLADDER 2\nSOR SVC 1 EOR\n").find("the SLC 5/02's SVC takes no operand"),
            std::string::npos);
}

struct SvcFigure {
  const char* processor;
  const char* select;
  Nanoseconds true_ns;
  Nanoseconds false_ns;
};

// The manuals' figures, each as printed (microseconds to the nanosecond).
constexpr SvcFigure kFigures[] = {
    {"Bul.1763", "1", 94'100, 800},    {"Bul.1763", "2", 87'000, 800},    {"Bul.1763", "3", 203'100, 800},
    {"Bul.1766", "1", 39'826, 193},    {"Bul.1766", "2", 5'904, 186},     {"Bul.1766", "3", 36'580, 177},
    {"Bul.1762", "1", 208'000, 0},     {"1764-LSP", "1", 166'000, 0},     {"1764-LRP", "1", 166'000, 0},
    {"1764-LRP", "2", 166'000, 0},     {"1764-LRP", "3", 327'000, 0},
};

TEST(MicroLogixSvc, ScantimePricesEachChannelSelectAsItsManual) {
  for (const auto& f : kFigures) {
    LoadResult r = load_program(svc_program(f.processor, std::string("SOR SVC ") + f.select + " EOR\n"), "t.slc");
    ASSERT_TRUE(r.ok()) << r.render_diagnostics();
    auto profile = builtin_timing_profile(r.program->processor.timing_key());
    ASSERT_TRUE(profile.has_value()) << f.processor;
    const ScanTimePrediction t = predict_scan_time(*r.program, r.program->processor, *profile);
    ASSERT_EQ(t.rungs.size(), 1u);
    EXPECT_EQ(t.rungs[0].worst, f.true_ns) << f.processor << " SVC " << f.select;
    EXPECT_EQ(t.rungs[0].best, f.false_ns) << f.processor << " SVC " << f.select;
    EXPECT_FALSE(profile->is_estimate(profile->instruction(Opcode::SVC_CH).source)) << f.processor;
  }
}

// In virtual time: one rung holding SVC 1 and SVC `select` on two branches, against one holding SVC 1
// twice; the scans differ by the select's figure less channel 0's, rung true and rung false.
TEST(MicroLogixSvc, VirtualTimeChargesEachChannelSelectAsItsManual) {
  auto scans = [](const char* processor, const std::string& select) {
    Controller plc = Controller::from_text(
        svc_program(processor, "SOR XIC B3:0/0 BST SVC 1 NXB SVC " + select + " BND EOR\n"));
    plc.scan(2);
    const Nanoseconds off = plc.runtime().stats().last;
    plc.set("B3:0/0", 1);
    plc.scan(1);
    return std::pair{plc.runtime().stats().last, off};
  };
  for (const auto& f : kFigures) {
    if (std::string(f.select) == "1") continue;
    const SvcFigure& channel0 = *std::find_if(std::begin(kFigures), std::end(kFigures), [&](const SvcFigure& g) {
      return std::string(g.processor) == f.processor && std::string(g.select) == "1";
    });
    const auto [on, off] = scans(f.processor, f.select);
    const auto [on1, off1] = scans(f.processor, "1");
    EXPECT_EQ(on - on1, f.true_ns - channel0.true_ns) << f.processor << " SVC " << f.select;
    EXPECT_EQ(off - off1, f.false_ns - channel0.false_ns) << f.processor << " SVC " << f.select;
  }
}

}  // namespace
}  // namespace softslc
