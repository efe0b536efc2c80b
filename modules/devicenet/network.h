// Network: the simulated DeviceNet cable, its 64 node addresses, and its virtual time.
//
// The network owns the Timeline every DeviceNet event runs on and the slave devices attached to
// node addresses 0...63. It does not own a clock: the caller steps it with advance_to(t), which
// runs every due event in (time, sequence) order. A master (the Scanner) registers itself as the
// observer to hear about field changes (for change-of-state production) and bus-level changes
// (bus-off, network power, duplicate address claims), which it must react to even while it has no
// events pending.
//
// Bus-level failure injections:
//   set_bus_fault(true)        the scanner's port detects communication errors and goes bus-off
//                              (code 91) until the fault is removed
//   set_network_power(false)   no network power on the scanner's port (code 92)
//   set_duplicate_claim(n)     a node not in the simulation claims address n: it answers the
//                              Duplicate MAC ID check, so a scanner at address n fails it (code 70)
// Device-level injections are on SimDevice (device(n)->set_online(false), ...).
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "modules/devicenet/bus_timing.h"
#include "modules/devicenet/device_model.h"
#include "modules/devicenet/sim_device.h"
#include "modules/devicenet/timeline.h"

namespace softslc::devicenet {

inline constexpr int kNodeCount = 64;

class NetworkObserver {
 public:
  virtual ~NetworkObserver() = default;
  // The inputs of the device at `node` changed (a field change).
  virtual void on_input_changed(int node) = 0;
  // A bus-level condition changed (bus fault, network power, duplicate claims, attach/detach).
  virtual void on_bus_changed() = 0;
};

class Network {
 public:
  explicit Network(Baud baud) : baud_(baud) {}
  Network(const Network&) = delete;
  Network& operator=(const Network&) = delete;

  Baud baud() const { return baud_; }

  Timeline& timeline() { return timeline_; }
  VirtualTime now() const { return timeline_.now(); }
  std::size_t advance_to(VirtualTime t) { return timeline_.advance_to(t); }
  std::size_t advance_by(Nanoseconds d) { return timeline_.advance_to(timeline_.now() + d); }
  std::optional<VirtualTime> next_event_time() const { return timeline_.next_time(); }

  // Attaches a device built from `model` at `node` (0...63, free; else ConfigError).
  SimDevice& attach(int node, DeviceModel model);
  bool detach(int node);
  SimDevice* device(int node);
  const SimDevice* device(int node) const;
  // Addresses with a device attached, ascending.
  std::vector<int> nodes() const;

  void set_bus_fault(bool on);
  bool bus_fault() const { return bus_fault_; }
  void set_network_power(bool on);
  bool network_power() const { return power_; }
  void set_duplicate_claim(int node, bool on);
  bool duplicate_claim(int node) const;

  // Whether some node answers at `node`: an online device or a duplicate claim.
  bool address_answers(int node) const;
  // Whether any node other than `except` is on the wire to acknowledge frames.
  bool any_other_node(int except) const;

  // Field side: sets a named input of the device at `node`; false if none.
  bool set_input(int node, std::string_view point, bool value);

  void set_observer(NetworkObserver* o) { observer_ = o; }

 private:
  void bus_changed() {
    if (observer_ != nullptr) observer_->on_bus_changed();
  }

  Baud baud_;
  Timeline timeline_;
  std::array<std::unique_ptr<SimDevice>, kNodeCount> devices_{};
  std::vector<int> attached_;  // addresses with a device, ascending
  std::array<bool, kNodeCount> claims_{};
  bool bus_fault_ = false;
  bool power_ = true;
  NetworkObserver* observer_ = nullptr;
};

}  // namespace softslc::devicenet
