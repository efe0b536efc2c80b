#include "modules/devicenet/timeline.h"

#include <algorithm>
#include <string>

namespace softslc::devicenet {

Timeline::EventId Timeline::schedule_at(VirtualTime at, Callback cb, Owner owner) {
  if (at < now_)
    throw TimeWentBackwards("DeviceNet event scheduled at " + std::to_string(at) + " ns, before now (" +
                            std::to_string(now_) + " ns)");
  std::uint32_t slot = 0;
  if (!free_.empty()) {
    slot = free_.back();
    free_.pop_back();
  } else {
    slot = static_cast<std::uint32_t>(slots_.size());
    slots_.emplace_back();
  }
  slots_[slot].cb = std::move(cb);
  slots_[slot].owner = owner;
  const EventId id = next_id_++;
  heap_.push_back(Key{at, id, slot});
  std::push_heap(heap_.begin(), heap_.end(), runs_after);
  return id;
}

void Timeline::release(std::uint32_t slot) {
  slots_[slot].cb = Callback();
  slots_[slot].owner = 0;
  free_.push_back(slot);
}

bool Timeline::cancel(EventId id) {
  const auto it = std::find_if(heap_.begin(), heap_.end(), [id](const Key& k) { return k.id == id; });
  if (it == heap_.end()) return false;
  release(it->slot);
  heap_.erase(it);
  std::make_heap(heap_.begin(), heap_.end(), runs_after);
  return true;
}

std::size_t Timeline::cancel_owner(Owner owner) {
  const auto kept = std::remove_if(heap_.begin(), heap_.end(), [&](const Key& k) {
    if (slots_[k.slot].owner != owner) return false;
    release(k.slot);
    return true;
  });
  const auto n = static_cast<std::size_t>(heap_.end() - kept);
  heap_.erase(kept, heap_.end());
  std::make_heap(heap_.begin(), heap_.end(), runs_after);
  return n;
}

std::size_t Timeline::advance_to(VirtualTime t) {
  if (t < now_)
    throw TimeWentBackwards("DeviceNet network asked to go from " + std::to_string(now_) + " ns back to " +
                            std::to_string(t) + " ns");
  std::size_t ran = 0;
  while (!heap_.empty() && heap_.front().at <= t) {
    std::pop_heap(heap_.begin(), heap_.end(), runs_after);
    const Key k = heap_.back();
    heap_.pop_back();
    // The callback leaves its slot before it runs: it may schedule more events (at >= now), which
    // may reuse the slot or grow the slot vector; the loop picks them up in order.
    Callback cb = std::move(slots_[k.slot].cb);
    release(k.slot);
    now_ = k.at;
    cb(now_);
    ++ran;
  }
  now_ = t;
  return ran;
}

}  // namespace softslc::devicenet
