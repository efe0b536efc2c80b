#include "vm/event_queue.h"

#include <string>

namespace softslc {

EventQueue::EventId EventQueue::schedule_at(VirtualTime at, Callback cb) {
  if (at < clock_.now())
    throw TimeWentBackwards("event scheduled at " + std::to_string(at) + " ns, before the current time " +
                            std::to_string(clock_.now()) + " ns");
  const EventId id = next_id_++;
  events_.emplace(Key{at, id}, std::move(cb));
  time_of_.emplace(id, at);
  return id;
}

bool EventQueue::cancel(EventId id) {
  auto it = time_of_.find(id);
  if (it == time_of_.end()) return false;
  events_.erase(Key{it->second, id});
  time_of_.erase(it);
  return true;
}

std::size_t EventQueue::run_until(VirtualTime until) {
  if (until < clock_.now())
    throw TimeWentBackwards("event queue asked to run until " + std::to_string(until) + " ns, before now (" +
                            std::to_string(clock_.now()) + " ns)");
  std::size_t ran = 0;
  while (!events_.empty() && events_.begin()->first.first <= until) {
    auto node = events_.extract(events_.begin());
    time_of_.erase(node.key().second);
    clock_.advance_to(node.key().first);
    // The callback may schedule more events (at >= now); the loop picks them up in order.
    node.mapped()(node.key().first);
    ++ran;
  }
  clock_.advance_to(until);
  return ran;
}

std::optional<VirtualTime> EventQueue::next_time() const {
  if (events_.empty()) return std::nullopt;
  return events_.begin()->first.first;
}

}  // namespace softslc
