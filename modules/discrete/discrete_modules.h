// Discrete I/O modules: 1746 cards in the local chassis, 1762/1769 MicroLogix expansion I/O and
// a MicroLogix controller's embedded I/O in slot 0.
//
// Every non-specialty catalog that instructions/module_catalog.cpp knows becomes a
// DiscreteModule: the generic DiscreteIoModule (vm/discrete_io.h) plus what the catalog says
// about its terminals — how many points exist (an 8-point card has bits 0-7 of its word, the
// 1746-IO12 six inputs and six outputs) — and, from the bench, the module's input filter and
// output delays (T_id, T_od in the 1747-SN throughput formulas). A field input set at time t is
// seen by the input scan from t + input_delay; an output word delivered by the output scan at t
// reaches the terminals at t + output_delay. Bits a card does not have cannot be set and always
// read 0.
//
// Bench node (optional): `io NAME slot=N [input_delay=T] [output_delay=T]`. The name lets tests
// inject `input VALUE [MASK]` and observe "inputs"/"outputs" by name.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "vm/discrete_io.h"

namespace softslc {

struct DiscreteModuleSpec {
  std::string name;  // bench device name, empty when none
  std::vector<std::uint16_t> input_points;   // per input word, the bits that exist
  std::vector<std::uint16_t> output_points;  // per output word
  Nanoseconds input_delay = 0;
  Nanoseconds output_delay = 0;
};

class DiscreteModule : public DiscreteIoModule {
 public:
  DiscreteModule(int slot, std::string catalog, int input_words, int output_words, DiscreteModuleSpec spec);

  void output_scan(std::span<const std::uint16_t> image) override;
  bool set_field_input(int word, std::uint16_t value, std::uint16_t mask) override;

  std::vector<std::string> device_names() const override;
  DeviceStatus inject(const DeviceFault& fault) override;
  std::optional<std::vector<std::int64_t>> observe(std::string_view device, std::string_view what) const override;

 private:
  std::uint16_t in_points(int word) const;
  std::uint16_t out_points(int word) const;
  DiscreteModuleSpec spec_;
  std::vector<std::uint16_t> last_delivered_;
  std::vector<std::uint16_t> masked_;  // the image under the output points (output_scan's buffer)
  // out_points(w) for each word of the image output_scan was last given (the image's size is the
  // slot's, so it is built once): the mask is not looked up per word at every output scan.
  std::vector<std::uint16_t> out_mask_;
};

}  // namespace softslc
