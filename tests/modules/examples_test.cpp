// The 1747-SN manual's programs, running (examples/ladder/1747-sn): the chapter 5 patterns with
// the BTR/BTW instructions, the appendix D control logic for earlier processors (virtual control
// word MOVed to M0, status COPied from M1), and the chapter 4 examples. Each test loads the
// example and its bench exactly as `softslc run --bench` and the test runner do.
#include <gtest/gtest.h>

#include <filesystem>

#include "modules/sn/block_transfer.h"
#include "modules_test_util.h"
#include "modules/throughput/rio_throughput.h"
#include "vm/scantime.h"
#include "vm/timing_profile.h"

namespace softslc::test {
namespace {

using namespace softslc::rio;

std::vector<std::string> example_names() {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::directory_iterator(example_path("")))
    if (e.path().extension() == ".slc") out.push_back(e.path().stem().string());
  std::sort(out.begin(), out.end());
  return out;
}

TEST(Examples, EveryExampleChecksLoadsItsBenchPredictsAndRuns) {
  const auto names = example_names();
  ASSERT_GE(names.size(), 18u);
  for (const auto& n : names) {
    SCOPED_TRACE(n);
    LoadResult lr = load_program_file(example_path(n + ".slc"));
    ASSERT_TRUE(lr.ok()) << lr.render_diagnostics();
    EXPECT_EQ(lr.diagnostics.items().size(), 0u) << lr.render_diagnostics();
    DiagnosticList config;
    check_module_configuration(*lr.program, config);
    EXPECT_EQ(config.items().size(), 0u) << render_all(config, n, lr.source);
    ModuleSetup s = load_module_setup(*lr.program, example_path(n + ".bench"));
    EXPECT_TRUE(s.ok()) << s.render(n, lr.source);
    EXPECT_EQ(s.bench_diagnostics.items().size(), 0u) << s.render(n, lr.source);
    auto rr = Runtime::create(*lr.program, s.options);
    ASSERT_TRUE(rr.ok()) << rr.render_errors();
    ASSERT_TRUE(rr.runtime->set_mode(Mode::Run));
    rr.runtime->run_for(milliseconds(500));
    EXPECT_FALSE(rr.runtime->fault().has_value()) << rr.runtime->fault()->to_string();
    // `softslc scantime` predicts it.
    auto profile = builtin_timing_profile(lr.program->processor.timing_key());
    ASSERT_TRUE(profile.has_value());
    ScanTimePrediction p = predict_scan_time(*lr.program, lr.program->processor, *profile);
    EXPECT_GT(p.total_worst, 0);
  }
}

// Counts completions (rising DN in control block word `cb`) and errors while running.
struct Watch {
  std::vector<char> order;  // 'R' / 'W' in completion order
  int r = 0, w = 0;
};

// ---- Chapter 5 ---------------------------------------------------------------------------------------------

TEST(Ch5, DirectionalReadsOncePerRisingEdge) {
  Bench b = Bench::example("ch5_directional.slc", "ch5_directional.bench");
  b.run();
  b->run_for(milliseconds(100));
  EXPECT_EQ(b.i("N20:0"), 0);
  b.set("B3:0/0", 1);
  ASSERT_TRUE(b.until([&] { return b.b("N10:0/13"); }, milliseconds(300)));
  EXPECT_EQ(b.u("N10:0") & (kEN | kEW | kST | kDN | kER), kEN | kEW | kST | kDN);
  EXPECT_EQ(b.i("N10:2"), 8);
  // The bench's module: word 0 ramps from 100 every 50 ms, words 1-7 are 200 ... 800.
  EXPECT_GE(b.i("N11:0"), 100);
  for (int k = 1; k < 8; ++k) EXPECT_EQ(b.i("N11:" + std::to_string(k)), (k + 1) * 100) << k;
  // Holding the rung true does not read again.
  b->run_for(seconds(1));
  EXPECT_EQ(b.i("N20:0"), 1);
  EXPECT_EQ(*b->observe("ANALOG", "btr count"), (std::vector<std::int64_t>{1}));
  // A new false-to-true transition reads again, with newer data.
  const std::int64_t first = b.i("N11:0");
  b.set("B3:0/0", 0);
  b->run_for(milliseconds(100));
  b.set("B3:0/0", 1);
  ASSERT_TRUE(b.until([&] { return b.i("N20:0") == 2; }, milliseconds(300)));
  EXPECT_GT(b.i("N11:0"), first);
}

// The BT throughput of one repeating transfer bounds how many complete in a time (appendix A
// "Block Transfer Throughput": at most t_bt + buffer_free per cycle; every cycle takes at least
// two T_SNo-bt service periods, one for the enable and one for the response).
void expect_completions_within_manual_bounds(std::int64_t count, Nanoseconds span, int bts, int words) {
  throughput::RioNetwork n;
  n.baud = throughput::RioBaud::b115_2k;
  n.devices = {{0, 0, 8, false, "RACK0"}};
  for (int k = 0; k < bts; ++k) n.block_transfers.push_back({0, words, "BT"});
  n.bt_times = throughput::RioBtTimes{730, 4500 + 1000};
  n.processor_scan = 20000;  // generous bound on the examples' scan (a few ms)
  const auto r = throughput::compute_rio(n);
  const Nanoseconds cycle_max = microseconds(r.bt->per_block_transfer[0].t_bt + r.bt->buffer_free);
  const Nanoseconds cycle_min = 2 * microseconds(r.t_sno.value);
  EXPECT_GE(count, span / cycle_max) << "fewer completions than the manual's maximum cycle allows";
  EXPECT_LE(count, span / cycle_min + 1) << "more completions than two T_SNo-bt per transfer allow";
}

TEST(Ch5, DirectionalRepeatingReadsAsFastAsPossible) {
  Bench b = Bench::example("ch5_directional_repeating.slc", "ch5_directional_repeating.bench");
  b.run();
  b->run_for(seconds(5));
  EXPECT_EQ(b.i("N20:2"), 0) << "no errors";
  expect_completions_within_manual_bounds(b.i("N20:0"), seconds(5), 1, 8);
}

TEST(Ch5, DirectionalContinuousFollowsItsPrecondition) {
  Bench b = Bench::example("ch5_directional_continuous.slc", "ch5_directional_continuous.bench");
  b.run();
  b->run_for(seconds(1));
  EXPECT_EQ(b.i("N20:0"), 0);
  b.set("B3:0/11", 1);
  b->run_for(seconds(3));
  const std::int64_t n = b.i("N20:0");
  expect_completions_within_manual_bounds(n, seconds(3), 1, 8);
  b.set("B3:0/11", 0);
  b->run_for(seconds(1));
  EXPECT_LE(b.i("N20:0"), n + 1) << "at most the transfer in progress completes";
  const std::int64_t stopped = b.i("N20:0");
  b->run_for(seconds(1));
  EXPECT_EQ(b.i("N20:0"), stopped);
}

TEST(Ch5, BidirectionalContinuousReadsAndWritesIndependently) {
  Bench b = Bench::example("ch5_bidirectional_continuous.slc", "ch5_bidirectional_continuous.bench");
  b.run();
  b->run_for(seconds(4));
  const std::int64_t reads = b.i("N20:0"), writes = b.i("N20:1");
  EXPECT_GE(reads, 10);
  EXPECT_GE(writes, 10);
  // The module may have answered a read whose DN the program has not seen yet.
  EXPECT_GE((*b->observe("ANALOG", "btr count"))[0], reads);
  EXPECT_LE((*b->observe("ANALOG", "btr count"))[0], reads + 1);
  // The BTW sends N12:0 = the read count at the time it was started.
  const auto sent = *b->observe("ANALOG", "btw data");
  ASSERT_EQ(sent.size(), 4u);
  EXPECT_GE(sent[0], reads - 2);
  EXPECT_LE(sent[0], reads);
}

// Records the order in which reads and writes complete (module counters), scan by scan.
std::string completion_order(Bench& b, Nanoseconds span) {
  std::string order;
  std::int64_t r = 0, w = 0;
  const VirtualTime end = b->now() + span;
  while (b->now() < end) {
    b->scan(1);
    const std::int64_t nr = (*b->observe("ANALOG", "btr count"))[0], nw = (*b->observe("ANALOG", "btw count"))[0];
    for (; r < nr; ++r) order += 'R';
    for (; w < nw; ++w) order += 'W';
  }
  return order;
}

bool alternates(const std::string& s) {
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s[i] != (i % 2 == 0 ? 'R' : 'W')) return false;
  return true;
}

TEST(Ch5, BidirectionalAlternatingAlternatesWhileEnabled) {
  Bench b = Bench::example("ch5_bidirectional_alternating.slc", "ch5_bidirectional_alternating.bench");
  b.run();
  EXPECT_EQ(completion_order(b, seconds(1)), "");
  b.set("B3:0/11", 1);
  const std::string order = completion_order(b, seconds(4));
  EXPECT_GE(order.size(), 8u);
  EXPECT_TRUE(alternates(order)) << order;
  EXPECT_EQ(b.i("N20:0"), static_cast<std::int64_t>(std::count(order.begin(), order.end(), 'R')));
}

TEST(Ch5, BidirectionalAlternatingRepeatingAlternates) {
  Bench b = Bench::example("ch5_bidirectional_alternating_repeating.slc", "ch5_bidirectional_alternating_repeating.bench");
  b.run();
  const std::string order = completion_order(b, seconds(4));
  EXPECT_GE(order.size(), 8u);
  EXPECT_TRUE(alternates(order)) << order;
  // Each write carries the number of reads before it.
  EXPECT_EQ((*b->observe("ANALOG", "btw data"))[0], b.i("N20:0") - (order.back() == 'R' ? 1 : 0));
}

// ---- Appendix D ---------------------------------------------------------------------------------------------

// The virtual bits of the appendix D programs: EN B3:100/15 (B3/1615), DN B3/13, ER B3/12.
std::string virtual_bits(Bench& b) {
  std::string s;
  if (b.b("B3/1615")) s += "EN ";
  if (b.b("B3/13")) s += "DN ";
  if (b.b("B3/12")) s += "ER ";
  if (!s.empty()) s.pop_back();
  return s.empty() ? "-" : s;
}

TEST(AppendixD, BtrControlLogicHandshake) {
  Bench b = Bench::example("d_btr_control_logic.slc", "d_btr_control_logic.bench");
  b.run();
  b->scan(2);
  EXPECT_EQ(b.u("B3:100"), 0x0084) << "rung 2:0 configured the read at power-up";
  EXPECT_EQ(b.m0(101), 8);
  b.set("B3/83", 1);
  std::vector<std::string> seq;
  const VirtualTime end = b->now() + milliseconds(400);
  while (b->now() < end) {
    b->scan(1);
    const std::string s = virtual_bits(b) + (b.b("B3/80") ? " P" : "") + (b.b("B3/81") ? " C" : "");
    if (seq.empty() || seq.back() != s) seq.push_back(s);
  }
  // Enable + pending; done seen (enable and pending unlatched, check latched in the same scan);
  // then the scanner turns DN off and the check bit is unlatched.
  EXPECT_EQ(seq, (std::vector<std::string>{"EN P", "DN C", "-"}));
  for (int k = 1; k < 8; ++k) EXPECT_EQ(b.i("N10:" + std::to_string(k)), (k + 1) * 100) << k;
  EXPECT_EQ(b.m0(100), 0x0084) << "the last control word sent has EN off";
  EXPECT_EQ(b.m1(100), 0) << "the scanner cleared the status";
}

TEST(AppendixD, BtrControlLogicBuffersTheErrorCode) {
  Bench b = Bench::example("d_btr_control_logic.slc", "d_btr_control_logic.bench");
  b.inject("ANALOG", "bt error");
  b.run();
  b.set("B3/83", 1);
  ASSERT_TRUE(b.until([&] { return b.i("N10:64") != 0; }, milliseconds(400)));
  EXPECT_EQ(b.i("N10:64"), kErrProtocol);
  ASSERT_TRUE(b.until([&] { return virtual_bits(b) == "-" && !b.b("B3/81"); }, milliseconds(400)));
}

TEST(AppendixD, BtwControlLogicWritesTheDataFile) {
  Bench b = Bench::example("d_btw_control_logic.slc", "d_btw_control_logic.bench");
  b.run();
  b->scan(1);
  EXPECT_EQ(b.u("B3:100"), 0x0004);
  for (int k = 0; k < 4; ++k) b.set("N11:" + std::to_string(k), 1000 + k);
  b.set("B3/83", 1);
  ASSERT_TRUE(b.until([&] { return (*b->observe("ANALOG", "btw count"))[0] == 1; }, milliseconds(400)));
  EXPECT_EQ(*b->observe("ANALOG", "btw data"), (std::vector<std::int64_t>{1000, 1001, 1002, 1003}));
  ASSERT_TRUE(b.until([&] { return !b.b("B3/81") && !b.b("B3/80"); }, milliseconds(400)));
  // A module that does not answer: the four-second BT timer, -9, buffered in N10:64.
  b.inject("ANALOG", "message timeout");
  b.set("B3/83", 1);
  ASSERT_TRUE(b.until([&] { return b.i("N10:64") != 0; }, seconds(5)));
  EXPECT_EQ(b.i("N10:64"), kErrTimeout);
}

std::int64_t btr_count(Bench& b) { return (*b->observe("ANALOG", "btr count"))[0]; }
std::int64_t btw_count(Bench& b) { return (*b->observe("ANALOG", "btw count"))[0]; }

TEST(AppendixD, DirectionalContinuousRunsWhileThePreconditionIsTrue) {
  Bench b = Bench::example("d_directional_continuous.slc", "d_directional_continuous.bench");
  b.run();
  b->run_for(seconds(1));
  EXPECT_EQ(btr_count(b), 0);
  b.set("B3/90", 1);
  b->run_for(seconds(4));
  const std::int64_t n = btr_count(b);
  EXPECT_GE(n, 8);
  b.set("B3/90", 0);
  b->run_for(seconds(1));
  EXPECT_LE(btr_count(b), n + 1);
  EXPECT_EQ(b.i("N10:1"), 200);
}

TEST(AppendixD, DirectionalRepeating) {
  Bench b = Bench::example("d_directional_repeating.slc", "d_directional_repeating.bench");
  b.run();
  b->run_for(seconds(4));
  EXPECT_GE(btr_count(b), 8);
  EXPECT_EQ(b.i("N10:64"), 0);
  EXPECT_EQ(b.i("N10:7"), 800);
}

TEST(AppendixD, DirectionalNonContinuousReadsOncePerInputTransition) {
  Bench b = Bench::example("d_directional_non_continuous.slc", "d_directional_non_continuous.bench");
  b.run();
  b->run_for(milliseconds(200));
  EXPECT_EQ(btr_count(b), 0);
  b.set("I:2.0/0", 1);  // held on
  b->run_for(seconds(1));
  EXPECT_EQ(btr_count(b), 1);
  b.set("I:2.0/0", 0);
  b->run_for(milliseconds(100));
  b.inject("START_PB", "input", {"1"});  // the same input, by its bench name
  b->run_for(seconds(1));
  EXPECT_EQ(btr_count(b), 2);
  EXPECT_FALSE(b.b("B3/83"));
}

TEST(AppendixD, BidirectionalContinuous) {
  Bench b = Bench::example("d_bidirectional_continuous.slc", "d_bidirectional_continuous.bench");
  b.run();
  for (int k = 0; k < 4; ++k) b.set("N11:" + std::to_string(k), std::int64_t{7} * (k + 1));
  b->run_for(seconds(4));
  EXPECT_GE(btr_count(b), 6);
  EXPECT_GE(btw_count(b), 6);
  EXPECT_EQ(*b->observe("ANALOG", "btw data"), (std::vector<std::int64_t>{7, 14, 21, 28}));
  EXPECT_EQ(b.i("N7:70"), 0);
  EXPECT_EQ(b.i("N7:71"), 0);
  EXPECT_EQ(b.u("N7:50"), 0x0084 | (b.b("N7:50/15") ? 0x8000 : 0));
}

TEST(AppendixD, BidirectionalAlternating) {
  Bench b = Bench::example("d_bidirectional_alternating.slc", "d_bidirectional_alternating.bench");
  b.run();
  EXPECT_EQ(completion_order(b, seconds(1)), "");
  b.set("B3:0/11", 1);
  const std::string order = completion_order(b, seconds(5));
  EXPECT_GE(order.size(), 8u);
  EXPECT_TRUE(alternates(order)) << order;
}

TEST(AppendixD, BidirectionalAlternatingRepeatingBuffersTheBtwErrorCode) {
  Bench b = Bench::example("d_bidirectional_alternating_repeating.slc", "d_bidirectional_alternating_repeating.bench");
  b.run();
  const std::string order = completion_order(b, seconds(4));
  EXPECT_GE(order.size(), 8u);
  EXPECT_TRUE(alternates(order)) << order;
  // A write the module refuses (it expects 4 words; now 3): -8, buffered by rung 2:7.
  b.inject("ANALOG", "data size", {"3"});
  ASSERT_TRUE(b.until([&] { return b.i("N7:71") != 0; }, seconds(2)));
  EXPECT_EQ(b.i("N7:71"), kErrProtocol);
}

// ---- Chapter 4 ---------------------------------------------------------------------------------------------

TEST(Ch4, M1StatusExampleShowsTheDocumentedWords) {
  Bench b = Bench::example("ch4_m1_status.slc", "ch4_m1_status.bench");
  b.run();
  b->run_for(milliseconds(400));
  // Chapter 4 "RIO Status Example" (p. 4-28): words 0, 2, 8, 9, 10, 12-15 of M1.
  EXPECT_EQ(b.u("N7:0"), 0x0003);
  EXPECT_EQ(b.u("N7:2"), 0x0001);
  EXPECT_EQ(b.u("N7:8"), 0x2219);
  EXPECT_EQ(b.u("N7:9"), 0xE6F9);
  EXPECT_EQ(b.u("N7:10"), 0x0219);
  EXPECT_EQ(b.u("N7:12"), 0);
  EXPECT_EQ(b.u("N7:13"), 0);
  EXPECT_EQ(b.u("N7:14"), 0);
  EXPECT_EQ(b.u("N7:15"), 0x000E);
  EXPECT_TRUE(b.b("B3:0/0"));
  EXPECT_TRUE(b.b("B3:0/1"));
  // The device comes back: the alarm clears.
  b.inject("R3G2", "online");
  b->run_for(milliseconds(400));
  EXPECT_EQ(b.u("N7:15"), 0);
  EXPECT_EQ(b.u("N7:10"), 0x2219);
  EXPECT_FALSE(b.b("B3:0/0"));
}

TEST(Ch4, CopyingTheStatusOnceCostsLessScanTime) {
  // Chapter 4: "copy the first four words of the M1 File to a binary file and use these addresses
  // throughout the program ... without interrupting the program scan many times."
  Bench once = Bench::example("ch4_copy_status_once.slc", "ch4_copy_status_once.bench");
  Bench naive = Bench::example("ch4_examine_m1_directly.slc", "ch4_examine_m1_directly.bench");
  once.run();
  naive.run();
  once->run_for(seconds(2));
  naive->run_for(seconds(2));
  EXPECT_EQ(once.i("N10:7"), 800);
  EXPECT_EQ(naive.i("N10:7"), 800);
  EXPECT_GE(btr_count(once), 5);
  EXPECT_LT(once->stats().avg(), naive->stats().avg());
  // The same in the static prediction (`softslc scantime`), and the naive program's hot spots
  // carry the manual's remedy.
  auto predict = [](const std::string& n) {
    LoadResult lr = load_program_file(example_path(n));
    return predict_scan_time(*lr.program, lr.program->processor, *builtin_timing_profile("5/03"));
  };
  const auto p_once = predict("ch4_copy_status_once.slc");
  const auto p_naive = predict("ch4_examine_m1_directly.slc");
  EXPECT_LT(p_once.total_mfile, p_naive.total_mfile);
  ASSERT_FALSE(p_naive.hot_spots.empty());
  std::string remedies;
  for (const auto& h : p_naive.hot_spots)
    for (const auto& r : h.remedies) remedies += r + "\n";
  EXPECT_NE(remedies.find("COP"), std::string::npos) << remedies;
}

}  // namespace
}  // namespace softslc::test
