// Repeated scans (docs/semantics.md "Repeated scans"): run_for may take a scan that would repeat
// the one before without executing it. These tests hold it to "same results": every shipped
// example, and programs built to catch a wrong skip, run side by side with the skip on and off and
// must agree word for word at every observation point, while the skip must actually happen where
// it may (else the speed-up silently stopped working).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
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

// ---- Passive modules (Module::passive; docs/semantics.md "Repeated scans") --------------------------

fs::path example(const std::string& relative) { return fs::path(SOFTSLC_SOURCE_DIR) / "examples" / "ladder" / relative; }

// The 1203-SM1's drives are not events: they are brought up to date at each image scan, and a
// drive ramping to its reference shows a new feedback word at every scan. Chapter 3's basic-mode
// example (drive 1 started by I:2/0, stopped by I:2/1 released; reference N7:0): while the drive
// accelerates or decelerates the module is not passive, so no scan may be skipped; once at speed,
// and once stopped, the scans repeat. A passive() that ignored the ramp fails the comparison
// (tried: the feedback word differs in the first slice after the start).
TEST(RepeatedScans, AnSm1DriveRampingIsNeverSkippedOver) {
  const fs::path program = example("1203-sm1/ch3_basic_drives.slc");
  const fs::path bench = example("1203-sm1/drives.bench");
  Controller skipping = Controller::load(program, bench);
  Controller executing = Controller::load(program, bench);
  for (Controller* c : {&skipping, &executing}) {
    c->set("N7:0", 16000);                      // REF1: about half speed
    c->inject("PUSH_BUTTONS", "input", {"42"});  // the three stop buttons released (normally closed)
  }
  run_side_by_side(skipping, executing, 10, milliseconds(100), "SM1 stopped");
  const std::uint64_t stopped = skipping.runtime().stats().repeated;
  EXPECT_GT(stopped, 0u) << "an idle 1203-SM1 must let scans repeat";
  for (Controller* c : {&skipping, &executing}) c->inject("PUSH_BUTTONS", "input", {"43"});  // START1 pressed
  run_side_by_side(skipping, executing, 2, milliseconds(10), "SM1 start pressed");
  for (Controller* c : {&skipping, &executing}) c->inject("PUSH_BUTTONS", "input", {"42"});
  run_side_by_side(skipping, executing, 100, milliseconds(100), "SM1 drive 1 accelerating");
  EXPECT_NE(skipping.get_int("I:1.3"), 0) << "drive 1's feedback";
  const std::uint64_t running = skipping.runtime().stats().repeated;
  EXPECT_GT(running, stopped) << "at speed the drive is settled and the scans repeat again";
  for (Controller* c : {&skipping, &executing}) c->inject("PUSH_BUTTONS", "input", {"40"});  // STOP1 pressed
  run_side_by_side(skipping, executing, 100, milliseconds(100), "SM1 drive 1 stopping");
  EXPECT_EQ(skipping.get_int("I:1.3"), 0);
}

// A tool may change an output word the program does not write between two run_for calls; the
// probe's output scan then hands it to the module, and a drive told to start is no longer settled.
// The runtime asks the modules again after the probe, so the ramp is executed scan by scan
// (without that second question this fails: the feedback word differs within the first slice).
TEST(RepeatedScans, AModuleStartedByTheProbesOutputScanIsNotRepeated) {
  const std::string text =
      "START 1747-L532\nSLOT 1 1203-SM1 SCAN_IN 8 SCAN_OUT 8 ID_CODE 3516\nSLOT 2 1746-IB16 SCAN_IN 1 SCAN_OUT 0\n"
      "LADDER 2\nSOR OTE O:1.0/0 EOR\n";
  std::string bench;
  {
    std::ifstream in(example("1203-sm1/drives.bench"));
    bench.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  Controller skipping = Controller::from_text(text, bench);
  Controller executing = Controller::from_text(text, bench);
  run_side_by_side(skipping, executing, 5, milliseconds(100), "SM1 enabled, stopped");
  const std::uint64_t stopped = skipping.runtime().stats().repeated;
  EXPECT_GT(stopped, 0u);
  for (Controller* c : {&skipping, &executing}) {
    c->set("O:1.3", 16000);  // reference, channel 1 (basic mode word 3)
    c->set("O:1.2", 2);      // logic command: start (bit 1), stop (bit 0) clear
  }
  run_side_by_side(skipping, executing, 50, milliseconds(100), "SM1 started by a tool");
  EXPECT_NE(skipping.get_int("I:1.3"), 0) << "drive 1's feedback";
}

// The 1747-SN: a remote input reaches the input image through the adapter module's input delay,
// the adapter's backplane scan and the scanner's visit, all events. Appendix A's discrete
// throughput example, its remote input toggled at times that fall between visits. Its link visits
// a logical device every millisecond or two, more often than the program scans, so an event runs
// at the end of nearly every scan and the scans do not repeat; what this holds is that a passive
// scanner does not change that, and that the results agree.
TEST(RepeatedScans, AnSnRemoteInputArrivesByEventsWithTheSameResults) {
  const fs::path program = example("1747-sn/throughput_discrete.slc");
  const fs::path bench = example("1747-sn/throughput_discrete.bench");
  Controller skipping = Controller::load(program, bench);
  Controller executing = Controller::load(program, bench);
  run_side_by_side(skipping, executing, 5, milliseconds(100), "SN idle");
  for (int i = 0; i < 9; ++i) {
    for (Controller* c : {&skipping, &executing}) c->inject("IN", "input", {i % 2 ? "0" : "1"});
    run_side_by_side(skipping, executing, 7, milliseconds(3 + i), "SN remote input");
    EXPECT_EQ(skipping.observe("OUT", "outputs"), executing.observe("OUT", "outputs")) << i;
  }
  EXPECT_EQ(skipping.observe("OUT", "outputs"), std::vector<std::int64_t>{1});
}

// The 1747-SDN: a photoeye's data bit, mapped to the discrete input image (I:2.1/0), changes on the
// network's events (the device produces, the scanner's strobe carries it); the module keeps the
// network's next event armed on the runtime's queue, so the repeats stop before it.
TEST(RepeatedScans, AnSdnDeviceInputArrivesByEventsBetweenRepeats) {
  const std::string text =
      "START 1747-L542\nSLOT 2 1747-SDN SCAN_IN 32 SCAN_OUT 32\nLADDER 2\n"
      "SOR OTE O:2.0/0 EOR\n"
      "SOR XIC I:2.1/0 OSR B3:0/0 ADD N7:0 1 N7:0 EOR\n"
      "SOR XIC I:2.1/0 OTE B3:0/1 EOR\n";
  const std::string bench =
      "devicenet DNET slot=2 node=0 baud=125K interscan_delay_ms=10 {\n"
      "  node EYE address=9 model=series-9000-photoeye {\n"
      "    strobe rx=1\n"
      "    input from=strobe byte=0 bit=0 bits=1 to=I:1/0\n"
      "  }\n"
      "}\n";
  Controller skipping = Controller::from_text(text, bench);
  Controller executing = Controller::from_text(text, bench);
  run_side_by_side(skipping, executing, 40, milliseconds(100), "SDN connecting");
  const std::uint64_t idle = skipping.runtime().stats().repeated;
  for (int i = 0; i < 6; ++i) {
    for (Controller* c : {&skipping, &executing}) c->inject("EYE", "input", {"data", i % 2 ? "0" : "1"});
    run_side_by_side(skipping, executing, 10, milliseconds(10 + 3 * i), "SDN photoeye");
  }
  EXPECT_EQ(skipping.get_int("N7:0"), 3);
  EXPECT_GT(idle, 0u) << "an idle 1747-SDN must let scans repeat";
}

// RPC reads the checksum the compiler computed, a constant of the program (1766-RM001A p. 239),
// so its program repeats; CPT combines math on direct addresses like ADD and MUL. An input change
// still reaches them.
TEST(RepeatedScans, RpcAndCptProgramsRepeatAndStillFollowTheirInputs) {
  const std::string text =
      "START 1747-L532\nSLOT 1 1746-IB16 SCAN_IN 1 SCAN_OUT 0\nLADDER 2\n"
      "SOR CPT N7:1 (N7:0 + I:1.0) * 2 EOR\n"
      "SOR XIC I:1/1 CPT F8:0 N7:1 | 4 EOR\n";
  Controller skipping = Controller::from_text(text);
  Controller executing = Controller::from_text(text);
  run_side_by_side(skipping, executing, 5, milliseconds(100), "CPT idle");
  EXPECT_GT(skipping.runtime().stats().repeated, 0u);
  for (Controller* c : {&skipping, &executing}) c->set("I:1/1", 1);
  run_side_by_side(skipping, executing, 5, milliseconds(100), "CPT input");
  // (N7:0 + I:1.0) * 2 with I:1.0 = 2, then / 4.
  EXPECT_EQ(skipping.get_int("N7:1"), 4);
  EXPECT_DOUBLE_EQ(skipping.get_float("F8:0"), 1.0);

  Controller checksum = Controller::load(example("micrologix/ml1400_checksum.slc"));
  Controller reference = Controller::load(example("micrologix/ml1400_checksum.slc"));
  run_side_by_side(checksum, reference, 10, milliseconds(100), "RPC");
  EXPECT_GT(checksum.runtime().stats().repeated, checksum.runtime().stats().scans / 2);
}

// DLG "only captures data on a false-to-true rung transition" (AG-UM008C p. 3-64) and its rung true
// sets the queue's EN bit, a DLS word in the data table (p. 3-65; 1763-RM001C p. 440): the probe of
// a scan that logs sees the change, so records are logged at the same scans with and without
// repeats (five rising edges, five records), and the idle scans between them repeat.
TEST(RepeatedScans, DlgLogsTheSameRecordsWithRepeats) {
  const std::string text =
      "START Bul.1763\nLADDER 2\n"
      "SOR XIC I:0/0 DLG 0 EOR\n"
      "SOR XIC I:0/0 ONS B3:0/0 ADD N7:0 1 N7:0 EOR\n"
      "DATALOG 0 RECORDS 8 TIME DELIMITER COMMA N7:0\n";
  Controller skipping = Controller::from_text(text);
  Controller executing = Controller::from_text(text);
  run_side_by_side(skipping, executing, 3, milliseconds(100), "DLG idle");
  for (int i = 0; i < 10; ++i) {
    for (Controller* c : {&skipping, &executing}) c->set("I:0/0", i % 2 ? 0 : 1);
    run_side_by_side(skipping, executing, 3, milliseconds(37), "DLG sample");
  }
  EXPECT_EQ(skipping.data_log_records(0), executing.data_log_records(0));
  EXPECT_EQ(skipping.data_log_records(0).size(), 5u);
  EXPECT_GT(skipping.runtime().stats().repeated, 0u);
}

// A CPT whose expression reads the free-running clock, or an indexed word, is never repeated: the
// expression's addresses are checked like any operand's.
TEST(RepeatedScans, ACptReadingTheClockIsNeverRepeated) {
  for (const char* rung : {"SOR CPT N7:0 S:4 * 2 EOR\n", "SOR CPT N7:0 #N7:1 + 1 EOR\n"}) {
    const std::string text = std::string("START 1747-L532\nLADDER 2\n") + rung;
    Controller skipping = Controller::from_text(text);
    Controller executing = Controller::from_text(text);
    EXPECT_EQ(run_side_by_side(skipping, executing, 30, milliseconds(100), rung), 0u);
  }
}

}  // namespace
}  // namespace softslc
