#include "modules/devicenet/network.h"

#include <algorithm>

namespace softslc::devicenet {

namespace {
bool valid_node(int node) { return node >= 0 && node < kNodeCount; }
}  // namespace

SimDevice& Network::attach(int node, DeviceModel model) {
  if (!valid_node(node)) throw ConfigError("node", "node address " + std::to_string(node) + " is outside 0...63");
  auto& slot = devices_[static_cast<std::size_t>(node)];
  if (slot) throw ConfigError("node", "node " + std::to_string(node) + " already has a device attached");
  slot = std::make_unique<SimDevice>(std::move(model));
  slot->set_address(node, baud_);
  slot->set_input_listener([this, node] {
    if (observer_ != nullptr) observer_->on_input_changed(node);
  });
  attached_.insert(std::upper_bound(attached_.begin(), attached_.end(), node), node);
  bus_changed();
  return *slot;
}

bool Network::detach(int node) {
  if (!valid_node(node) || !devices_[static_cast<std::size_t>(node)]) return false;
  devices_[static_cast<std::size_t>(node)].reset();
  std::erase(attached_, node);
  bus_changed();
  return true;
}

SimDevice* Network::device(int node) {
  return valid_node(node) ? devices_[static_cast<std::size_t>(node)].get() : nullptr;
}

const SimDevice* Network::device(int node) const {
  return valid_node(node) ? devices_[static_cast<std::size_t>(node)].get() : nullptr;
}

std::vector<int> Network::nodes() const {
  std::vector<int> out;
  for (int n = 0; n < kNodeCount; ++n)
    if (devices_[static_cast<std::size_t>(n)]) out.push_back(n);
  return out;
}

void Network::set_bus_fault(bool on) {
  if (bus_fault_ == on) return;
  bus_fault_ = on;
  bus_changed();
}

void Network::set_network_power(bool on) {
  if (power_ == on) return;
  power_ = on;
  bus_changed();
}

void Network::set_duplicate_claim(int node, bool on) {
  if (!valid_node(node) || claims_[static_cast<std::size_t>(node)] == on) return;
  claims_[static_cast<std::size_t>(node)] = on;
  bus_changed();
}

bool Network::duplicate_claim(int node) const { return valid_node(node) && claims_[static_cast<std::size_t>(node)]; }

bool Network::address_answers(int node) const {
  if (!valid_node(node)) return false;
  const auto& d = devices_[static_cast<std::size_t>(node)];
  return claims_[static_cast<std::size_t>(node)] || (d && d->online());
}

bool Network::any_other_node(int except) const {
  // Asked by every status register the scanner builds: only the attached devices and the claims,
  // not all 64 addresses.
  for (int n : attached_)
    if (n != except && address_answers(n)) return true;
  for (int n = 0; n < kNodeCount; ++n)
    if (n != except && claims_[static_cast<std::size_t>(n)]) return true;
  return false;
}

bool Network::set_input(int node, std::string_view point, bool value) {
  SimDevice* d = device(node);
  return d != nullptr && d->set_input(point, value);
}

}  // namespace softslc::devicenet
