// Timeline: the simulated DeviceNet network's own ordered list of future work.
//
// The network never reads a wall clock. Everything that happens on it (a poll response arriving,
// a connection timing out, a scan cycle starting) is an event at an integer virtual time in
// nanoseconds, run in (time, sequence) order. The sequence number grows by one for every event
// ever scheduled, so events at the same time run in the order they were scheduled and two runs of
// the same inputs run the same events in the same order (as ns-3 does). The caller steps time with
// advance_to(t): every event due at or before t runs in order, including events those callbacks
// schedule inside the window, and the timeline's clock ends at t. Time never goes backwards:
// scheduling before now or advancing to an earlier time throws TimeWentBackwards.
//
// The module wrapper keeps this queue in step with the runtime's EventQueue by scheduling one host
// event at next_time() and calling advance_to() from it; the library itself never needs the VM.
//
// Every event carries an owner tag so an object that schedules work (the scanner) can withdraw all
// of its pending events when it is destroyed; nothing else is ever dropped.
//
// Storage: an EventHeap (vm/event_heap.h), the (time, sequence) heap with callbacks in reused slots
// that the runtime's EventQueue uses too (issue 20: an idle network runs five or six events per
// scan cycle, and the events were most of a quiet 1747-SDN program's simulation time). A callback's
// captures up to EventCallback::kInlineBytes (every scan-cycle event of the scanner) sit in place,
// so scheduling an event allocates nothing once the vectors have grown. cancel() and
// cancel_owner() are rare (the scanner's destructor).
#pragma once

#include <cstddef>
#include <optional>
#include <utility>

#include "vm/event_heap.h"
#include "vm/virtual_time.h"

namespace softslc::devicenet {

using softslc::Nanoseconds;
using softslc::VirtualTime;

class Timeline {
 public:
  // A move-only callable void(VirtualTime now) with small captures in place (vm/event_heap.h).
  using Callback = softslc::EventCallback;
  using EventId = softslc::EventHeap::EventId;
  // Identifies who scheduled an event, for cancel_owner(). 0 = nobody in particular.
  using Owner = softslc::EventHeap::Owner;

  Timeline() = default;
  Timeline(const Timeline&) = delete;
  Timeline& operator=(const Timeline&) = delete;

  VirtualTime now() const { return now_; }

  // Schedules `cb` at absolute time `at` (>= now(), else TimeWentBackwards).
  EventId schedule_at(VirtualTime at, Callback cb, Owner owner = 0);
  EventId schedule_after(Nanoseconds delay, Callback cb, Owner owner = 0) {
    return schedule_at(now_ + delay, std::move(cb), owner);
  }
  // Removes one pending event; false when it already ran or never existed.
  bool cancel(EventId id) { return heap_.cancel(id); }
  // Removes every pending event of `owner`; returns how many.
  std::size_t cancel_owner(Owner owner) { return heap_.cancel_owner(owner); }

  // Runs every event due at or before `t` in (time, sequence) order, then sets now() to t. Returns the
  // number of events run.
  std::size_t advance_to(VirtualTime t);

  std::optional<VirtualTime> next_time() const { return heap_.next_time(); }
  std::size_t pending() const { return heap_.size(); }

 private:
  softslc::EventHeap heap_;
  VirtualTime now_ = 0;
};

}  // namespace softslc::devicenet
