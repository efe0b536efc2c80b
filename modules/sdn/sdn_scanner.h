// The 1747-SDN DeviceNet scanner in a chassis slot: the library's Scanner (modules/devicenet) on
// the backplane interface of vm/module.h.
//
// The module owns a simulated DeviceNet Network with the bench's devices attached and a Scanner
// configured from the bench (or the factory defaults: node 63, 125K, empty scanlist; p.140). The
// network keeps its own timeline; the module keeps it in step with the runtime: one host event at
// the network's next event time advances it, and every access from the processor (image scans,
// M0/M1, DEM) first advances it to the access's time, so both clocks agree and nothing happens
// out of order. The network never runs ahead of the processor except to a DEM's own execution
// time within the current scan.
//
//   input scan   I:e.0...n-1  = the scanner's input image (word 0 = module status register)
//   output scan  O:e.0...n-1  -> the scanner (word 0 = command register; zeros outside Run = Idle)
//   M0/M1        forwarded word by word, both files read/write (appendix D); a write to M0 words
//                224-255 marks the request block, which the scanner takes once at the end of
//                that processor scan (so a block written word by word or by one COP is one request)
//   DEM          the module's single DemPort (chapter 8) over the instruction's 70-word control block
//
// Bench devices are reached by name: the network's name takes bus-level changes, each node's name
// device-level ones (docs/1747-sdn.md, "The module").
//
// Passive (Module::passive, docs/semantics.md "Repeated scans"): the network changes only in its
// own timeline's events, and the module always has the host event armed at the next of them
// (rearm after every access), so whatever the network does later is an event on the runtime's
// queue; between events the input scan copies the same image. The output scan hands the scanner the
// command register and output words: the scanner stores the words, acts on the reboot bit's rising
// edge only, and otherwise reconciles the port with levels it already holds, so the same image
// again changes nothing. The module is passive unless a DEM is in flight, a request block written
// this scan waits for its event, or an explicit-message transaction is open (their progress is
// events too, but the M1 response area changes with it).
//
// M files and DEM in repeated scans (Module::program_changes): read_m reads M0 as written and M1
// as the network's events left it (the data area, or status recomputed from the node states), so
// its answers change only in those events and in write_m. A write changes something when it
// stores a value the word does not hold (M0, or M1's data area; the rest of M1 ignores writes) and
// always when it is to the request block (M0 224-255: every write has the block taken at the end
// of the scan). A DEM changes something when it starts or drops a message (the port's owner or
// its abandoned block changes), when it changes its control block (the runtime sees that in the
// table too), or when it advances the network to its own time within the scan past one of the
// network's events (the event then ran mid-scan instead of at its end). Only a DEM that has its
// message in flight or starts one reads the time and advances the network
// (DemPort::reads_network): any other (a false rung, EN still set, WS) acts from its control block,
// the rung and the slot, so a probe with such DEMs may repeat across the network's events.
#pragma once

#include <memory>
#include <optional>

#include "modules/devicenet/dem.h"
#include "modules/devicenet/network.h"
#include "modules/devicenet/scanner.h"
#include "modules/sdn/sdn_bench.h"
#include "parser/program.h"
#include "vm/module.h"

namespace softslc {

class SdnScanner final : public Module {
 public:
  SdnScanner(const SlotConfig& slot, int m0_words, int m1_words, std::shared_ptr<const SdnBench> bench);
  ~SdnScanner() override;

  // ---- Module ----
  void attach(ModuleHost& host) override;
  void input_scan(std::span<std::uint16_t> image) override;
  void output_scan(std::span<const std::uint16_t> image) override;
  int m_file_words(MFile f) const override;
  MAccess read_m(MFile f, int word, std::uint16_t& value) override;
  MAccess write_m(MFile f, int word, std::uint16_t value) override;
  void on_mode_change(Mode from, Mode to) override;
  bool passive() const override;
  std::optional<std::uint64_t> program_changes() const override { return program_changes_; }
  bool m_write_changes_nothing(MFile f, int word, std::uint16_t value) const override;
  void execute(ModuleInstructionContext& ctx) override;
  std::vector<std::string> device_names() const override;
  DeviceStatus inject(const DeviceFault& fault) override;
  std::optional<std::vector<std::int64_t>> observe(std::string_view device, std::string_view what) const override;

  // ---- For tests and tools ----
  devicenet::Scanner& scanner() { return *scanner_; }
  const devicenet::Scanner& scanner() const { return *scanner_; }
  devicenet::Network& network() { return *network_; }

 private:
  // Advances the network to `t` (never backwards) and re-arms the host event.
  void sync(VirtualTime t);
  void rearm();
  void wake(VirtualTime t);
  DeviceStatus inject_network(const DeviceFault& fault);
  DeviceStatus inject_node(int address, const DeviceFault& fault);
  std::optional<int> address_of(std::string_view device) const;

  std::shared_ptr<const SdnBench> bench_;
  int m0_words_ = 0, m1_words_ = 0;
  std::unique_ptr<devicenet::Network> network_;
  std::unique_ptr<devicenet::Scanner> scanner_;       // made in attach(), at power-up time
  std::unique_ptr<devicenet::dem::DemPort> dem_;
  std::optional<VirtualTime> wake_at_;  // time of the armed host event
  EventQueue::EventId wake_id_ = 0;
  bool request_block_written_ = false;  // M0:224-255 written this processor scan
  std::uint64_t program_changes_ = 0;   // see the header
};

}  // namespace softslc
