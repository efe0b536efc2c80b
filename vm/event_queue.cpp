#include "vm/event_queue.h"

#include <string>

namespace softslc {

EventQueue::EventId EventQueue::schedule_at(VirtualTime at, Callback cb) {
  if (at < clock_.now())
    throw TimeWentBackwards("event scheduled at " + std::to_string(at) + " ns, before the current time " +
                            std::to_string(clock_.now()) + " ns");
  const EventId id = next_id_++;
  heap_.push_back(Event{at, id, std::move(cb)});
  sift_up(heap_.size() - 1);
  return id;
}

bool EventQueue::cancel(EventId id) {
  for (std::size_t i = 0; i < heap_.size(); ++i)
    if (heap_[i].id == id) {
      take(i);
      return true;
    }
  return false;
}

void EventQueue::sift_up(std::size_t i) {
  while (i > 0) {
    const std::size_t parent = (i - 1) / 2;
    if (!heap_[parent].after(heap_[i])) break;
    std::swap(heap_[parent], heap_[i]);
    i = parent;
  }
}

void EventQueue::sift_down(std::size_t i) {
  const std::size_t n = heap_.size();
  for (;;) {
    std::size_t first = i;
    const std::size_t l = 2 * i + 1, r = l + 1;
    if (l < n && heap_[first].after(heap_[l])) first = l;
    if (r < n && heap_[first].after(heap_[r])) first = r;
    if (first == i) return;
    std::swap(heap_[i], heap_[first]);
    i = first;
  }
}

EventQueue::Event EventQueue::take(std::size_t i) {
  Event e = std::move(heap_[i]);
  if (i + 1 != heap_.size()) {
    heap_[i] = std::move(heap_.back());
    heap_.pop_back();
    // The moved-in event may belong above or below position i.
    sift_up(i);
    sift_down(i);
  } else {
    heap_.pop_back();
  }
  return e;
}

std::size_t EventQueue::run_until(VirtualTime until) {
  if (until < clock_.now())
    throw TimeWentBackwards("event queue asked to run until " + std::to_string(until) + " ns, before now (" +
                            std::to_string(clock_.now()) + " ns)");
  std::size_t ran = 0;
  while (!heap_.empty() && heap_.front().at <= until) {
    Event e = take(0);
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
