#include "vm/event_queue.h"

#include <string>

namespace softslc {

EventQueue::EventId EventQueue::schedule_at(VirtualTime at, Callback cb) {
  if (at < clock_.now())
    throw TimeWentBackwards("event scheduled at " + std::to_string(at) + " ns, before the current time " +
                            std::to_string(clock_.now()) + " ns");
  return heap_.push(at, std::move(cb));
}

// Hot: run at every scan (vm/runtime.cpp, "The scan cycle", says why it is marked).
[[gnu::hot]] std::size_t EventQueue::run_until(VirtualTime until) {
  if (until < clock_.now())
    throw TimeWentBackwards("event queue asked to run until " + std::to_string(until) + " ns, before now (" +
                            std::to_string(clock_.now()) + " ns)");
  // The callback may schedule more events (at >= now); run_due picks them up in order.
  const std::size_t ran = heap_.run_due(until, [this](VirtualTime at) { clock_.advance_to(at); });
  clock_.advance_to(until);
  return ran;
}

}  // namespace softslc
