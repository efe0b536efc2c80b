#include "modules/devicenet/timeline.h"

#include <string>

namespace softslc::devicenet {

Timeline::EventId Timeline::schedule_at(VirtualTime at, Callback cb, Owner owner) {
  if (at < now_)
    throw TimeWentBackwards("DeviceNet event scheduled at " + std::to_string(at) + " ns, before now (" +
                            std::to_string(now_) + " ns)");
  const EventId id = next_id_++;
  events_.emplace(Key{at, id}, Entry{std::move(cb), owner});
  time_of_.emplace(id, at);
  return id;
}

bool Timeline::cancel(EventId id) {
  auto it = time_of_.find(id);
  if (it == time_of_.end()) return false;
  events_.erase(Key{it->second, id});
  time_of_.erase(it);
  return true;
}

std::size_t Timeline::cancel_owner(Owner owner) {
  std::size_t n = 0;
  for (auto it = events_.begin(); it != events_.end();) {
    if (it->second.owner == owner) {
      time_of_.erase(it->first.second);
      it = events_.erase(it);
      ++n;
    } else {
      ++it;
    }
  }
  return n;
}

std::size_t Timeline::advance_to(VirtualTime t) {
  if (t < now_)
    throw TimeWentBackwards("DeviceNet network asked to go from " + std::to_string(now_) + " ns back to " +
                            std::to_string(t) + " ns");
  std::size_t ran = 0;
  while (!events_.empty() && events_.begin()->first.first <= t) {
    auto node = events_.extract(events_.begin());
    time_of_.erase(node.key().second);
    now_ = node.key().first;
    // The callback may schedule more events at >= now; the loop picks them up in order.
    node.mapped().cb(now_);
    ++ran;
  }
  now_ = t;
  return ran;
}

std::optional<VirtualTime> Timeline::next_time() const {
  if (events_.empty()) return std::nullopt;
  return events_.begin()->first.first;
}

}  // namespace softslc::devicenet
