#include "modules/devicenet/timeline.h"

#include <string>

namespace softslc::devicenet {

Timeline::EventId Timeline::schedule_at(VirtualTime at, Callback cb, Owner owner) {
  if (at < now_)
    throw TimeWentBackwards("DeviceNet event scheduled at " + std::to_string(at) + " ns, before now (" +
                            std::to_string(now_) + " ns)");
  return heap_.push(at, std::move(cb), owner);
}

std::size_t Timeline::advance_to(VirtualTime t) {
  if (t < now_)
    throw TimeWentBackwards("DeviceNet network asked to go from " + std::to_string(now_) + " ns back to " +
                            std::to_string(t) + " ns");
  const std::size_t ran = heap_.run_due(t, [this](VirtualTime at) { now_ = at; });
  now_ = t;
  return ran;
}

}  // namespace softslc::devicenet
