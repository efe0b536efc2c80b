#include "vm/event_queue.h"

#include <algorithm>
#include <string>

namespace softslc {

EventQueue::EventId EventQueue::schedule_at(VirtualTime at, Callback cb) {
  if (at < clock_.now())
    throw TimeWentBackwards("event scheduled at " + std::to_string(at) + " ns, before the current time " +
                            std::to_string(clock_.now()) + " ns");
  const EventId id = next_id_++;
  heap_.push_back(Event{at, id, std::move(cb)});
  std::push_heap(heap_.begin(), heap_.end(), runs_after);
  return id;
}

bool EventQueue::cancel(EventId id) {
  const auto it = std::find_if(heap_.begin(), heap_.end(), [id](const Event& e) { return e.id == id; });
  if (it == heap_.end()) return false;
  heap_.erase(it);
  std::make_heap(heap_.begin(), heap_.end(), runs_after);
  return true;
}

std::size_t EventQueue::run_until(VirtualTime until) {
  if (until < clock_.now())
    throw TimeWentBackwards("event queue asked to run until " + std::to_string(until) + " ns, before now (" +
                            std::to_string(clock_.now()) + " ns)");
  std::size_t ran = 0;
  while (!heap_.empty() && heap_.front().at <= until) {
    std::pop_heap(heap_.begin(), heap_.end(), runs_after);
    Event e = std::move(heap_.back());
    heap_.pop_back();
    clock_.advance_to(e.at);
    // The callback may schedule more events (at >= now); the loop picks them up in order.
    e.cb(e.at);
    ++ran;
  }
  clock_.advance_to(until);
  return ran;
}

std::optional<VirtualTime> EventQueue::next_time() const {
  if (heap_.empty()) return std::nullopt;
  return heap_.front().at;
}

}  // namespace softslc
