// Cross-check of the simulated RIO link against the manual's own timing (1747-SN appendix A):
// for the manual's two example networks, the discrete I/O throughput measured in simulation
// (remote input change -> remote output change) and the block-transfer throughput (EN -> DN)
// stay within the maxima the throughput library computes for the same configuration (T_dm-nbt,
// T_dm-bt, BT throughput). The measured and maximum figures are printed so docs/1747-sn.md can
// show them side by side.
#include <gtest/gtest.h>

#include <iostream>

#include "modules/throughput/rio_throughput.h"
#include "modules_test_util.h"

namespace softslc::test {
namespace {

namespace tp = softslc::throughput;

tp::Micros us_up(Nanoseconds ns) { return (ns + kNsPerUs - 1) / kNsPerUs; }

// The network the scanner runs, as the throughput library describes it.
tp::RioNetwork network_of(RioScanner& sn) {
  tp::RioNetwork n;
  n.baud = sn.baud();
  n.mode = sn.g_file().complementary_mode ? tp::RioMode::complementary : tp::RioMode::normal;
  for (const auto& d : sn.g_file().devices) n.devices.push_back({d.rack, d.group, d.groups, d.complementary, ""});
  return n;
}

// Toggles the remote input and measures, each time, from the field change to the remote output
// terminal's change; the phase against the scans and the RIO scan varies from toggle to toggle.
Nanoseconds measure_discrete(Bench& b, int toggles) {
  Nanoseconds worst = 0;
  for (int k = 0; k < toggles; ++k) {
    b->run_for(microseconds(1700 * (k % 13) + 300 * (k % 7)));
    const bool on = k % 2 == 0;
    const VirtualTime t0 = b->now();
    b.set("I:1.0/0", on ? 1 : 0);
    EXPECT_TRUE(b.until([&] { return ((*b->observe("OUT", "outputs"))[0] & 1) == (on ? 1 : 0); }, milliseconds(500)));
    const VirtualTime t1 = (*b->observe("OUT", "output changed at"))[0];
    worst = std::max(worst, t1 - t0);
  }
  return worst;
}

void print_row(const std::string& what, Nanoseconds measured, tp::Micros max) {
  std::cout << "| " << what << " | " << tp::format_ms(us_up(measured)) << " | " << tp::format_ms(max) << " |\n";
}

TEST(ThroughputCheck, DiscreteWithoutBlockTransfers) {
  // Appendix A, "Example Discrete I/O Throughput without Block Transfers Present".
  Bench b = Bench::example("throughput_discrete.slc", "throughput_discrete.bench");
  b.run();
  b->run_for(milliseconds(200));
  const Nanoseconds measured = measure_discrete(b, 40);
  tp::RioNetwork n = network_of(b.sn());
  n.processor_scan = us_up(b->stats().max);
  n.adapter_delay = tp::Micros{2} * 4000;  // "For a 1747-ASB, this is two ASB backplane scan times."
  n.input_delay = 10000;       // T_id of the example
  n.output_delay = 1000;       // T_od of the example
  n.t_upd = us_up(b->stats().max);
  const tp::RioResult r = tp::compute_rio(n);
  EXPECT_EQ(r.t_rio, 25500);  // the example's T_RIO
  EXPECT_EQ(b.sn().last_rio_scan(), microseconds(r.t_rio));
  EXPECT_LE(measured, microseconds(r.t_dm)) << "measured " << measured << " ns, T_dm-nbt " << r.t_dm << " us";
  std::cout << "T_ps " << tp::format_ms(n.processor_scan) << " ms\n";
  print_row("discrete, appendix A example 1 (T_dm-nbt)", measured, r.t_dm);
}

TEST(ThroughputCheck, DiscreteAndBlockTransfersWithBlockTransfersPresent) {
  // Appendix A, "Example Discrete I/O Throughput with Block Transfers Present", with a block
  // transfer read running continuously to each of the six block-transfer modules.
  Bench b = Bench::example("throughput_bt.slc", "throughput_bt.bench");
  b.run();
  b->run_for(milliseconds(300));
  // Block-transfer throughput: EN (the rung makes the BTR enabled) to DN (the program sees done),
  // for each of the six BTRs, over many cycles.
  const std::vector<std::string> cbs = {"N10:0", "N10:3", "N10:6", "N10:9", "N10:12", "N10:15"};
  std::vector<VirtualTime> enabled(cbs.size(), -1);
  std::vector<Nanoseconds> worst(cbs.size(), 0);
  std::vector<int> cycles(cbs.size(), 0);
  std::vector<bool> en_before(cbs.size(), false), dn_before(cbs.size(), false);
  const VirtualTime end = b->now() + seconds(20);
  while (b->now() < end) {
    b->scan(1);
    for (std::size_t i = 0; i < cbs.size(); ++i) {
      const std::uint16_t w = b.u(cbs[i]);
      const bool en = w & 0x8000, dn = w & 0x2000;
      EXPECT_FALSE(w & 0x1000) << cbs[i] << " error " << b.i(cbs[i].substr(0, 4) + std::to_string(std::stoi(cbs[i].substr(4)) + 2));
      if (en && !en_before[i]) enabled[i] = b->now();
      if (dn && !dn_before[i] && enabled[i] >= 0) {
        worst[i] = std::max(worst[i], b->now() - enabled[i]);
        ++cycles[i];
      }
      en_before[i] = en;
      dn_before[i] = dn;
    }
  }
  // Discrete throughput while the block transfers run.
  const Nanoseconds discrete = measure_discrete(b, 30);

  tp::RioNetwork n = network_of(b.sn());
  n.processor_scan = us_up(b->stats().max);
  n.adapter_delay = tp::Micros{2} * 4500;
  n.input_delay = 10000;
  n.output_delay = 1000;
  n.block_transfers = {{0, 8, "BT8"}, {0, 4, "BT4A"}, {0, 4, "BT4B"}, {1, 2, "BT2"}, {2, 64, "BT64"}, {2, 32, "BT32"}};
  // T_M0: the BTR's control-word write, an "any M file address" access on the SLC 5/03 (730 us,
  // appendix B); T_adp-bt: one ASB backplane scan.
  n.bt_times = tp::RioBtTimes{730, 4500};
  const tp::RioResult r = tp::compute_rio(n);
  EXPECT_EQ(r.t_rio, 16500);   // the example's T_RIO
  EXPECT_EQ(r.t_btx, 21600);   // the example's T_btx
  EXPECT_EQ(r.t_sno.value, 22000);  // T_SNo-bt, 3 logical racks
  EXPECT_LE(discrete, microseconds(r.t_dm)) << "T_dm-bt " << r.t_dm << " us";
  std::cout << "T_ps " << tp::format_ms(n.processor_scan) << " ms\n";
  print_row("discrete with block transfers, appendix A example 2 (T_dm-bt)", discrete, r.t_dm);
  ASSERT_EQ(r.bt->per_block_transfer.size(), cbs.size());
  for (std::size_t i = 0; i < cbs.size(); ++i) {
    EXPECT_GE(cycles[i], 3) << n.block_transfers[i].name;
    EXPECT_LE(worst[i], microseconds(r.bt->per_block_transfer[i].t_bt)) << n.block_transfers[i].name;
    print_row("BT throughput " + n.block_transfers[i].name + " (rack " + std::to_string(n.block_transfers[i].rack) + ", " +
                  std::to_string(n.block_transfers[i].words) + " words)",
              worst[i], r.bt->per_block_transfer[i].t_bt);
  }
}

}  // namespace
}  // namespace softslc::test
