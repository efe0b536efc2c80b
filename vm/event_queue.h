// The event queue: timed work for modules and simulated field devices.
//
// Events are ordered by (virtual time, insertion sequence). The sequence number increases by one
// for every event ever scheduled, so events at the same time run in the order they were
// scheduled (first in, first out) and a run is reproducible bit for bit, as in ns-3. Nothing is
// ever dropped: the queue grows as needed. Scheduling before the current time throws
// TimeWentBackwards, and running the queue advances the shared VirtualClock to each event's time
// before calling it, so a callback always sees now() == its own time and time never goes
// backwards.
//
// Storage: an EventHeap (vm/event_heap.h, shared with the DeviceNet network's Timeline): a binary
// min-heap of (time, sequence, slot) keys with the callbacks in reused slots, each an EventCallback
// that keeps a module's small captures in place, so a module scheduling its next event every few
// microseconds of virtual time costs no allocation (a std::function per event was about 12% of a
// busy 1747-SN program's simulation time, docs/performance.md "Executed scans (s17-scan)").
//
// The runtime runs the queue between scans: when a scan ends at time t, every event due at or
// before t runs (in order) and the clock ends at t. An event therefore changes module state
// "between" scans; the program sees the effect at the next input scan, as on the real
// processor where field changes are only sampled by the input scan.
#pragma once

#include <cstdint>
#include <optional>
#include <utility>

#include "vm/event_heap.h"
#include "vm/virtual_time.h"

namespace softslc {

class EventQueue {
 public:
  using Callback = EventCallback;
  using EventId = EventHeap::EventId;

  explicit EventQueue(VirtualClock& clock) : clock_(clock) {}
  EventQueue(const EventQueue&) = delete;
  EventQueue& operator=(const EventQueue&) = delete;

  // Schedules `cb` at absolute time `at` (>= now, else TimeWentBackwards). Returns its id.
  EventId schedule_at(VirtualTime at, Callback cb);
  // Schedules `cb` `delay` nanoseconds from now (delay >= 0).
  EventId schedule_after(Nanoseconds delay, Callback cb) { return schedule_at(clock_.now() + delay, std::move(cb)); }
  // Removes a pending event. Returns false when it already ran or never existed.
  bool cancel(EventId id) { return heap_.cancel(id); }

  // Runs every event due at or before `until`, in (time, sequence) order, including events that
  // callbacks schedule inside that window, then leaves the clock at `until`. Returns how many
  // events ran. `until` before now throws TimeWentBackwards.
  std::size_t run_until(VirtualTime until);

  std::optional<VirtualTime> next_time() const { return heap_.next_time(); }
  // Counts the events ever scheduled, ran or not: the same before and after a stretch that scheduled none.
  EventId scheduled() const { return heap_.next_id() - 1; }
  std::size_t size() const { return heap_.size(); }
  bool empty() const { return heap_.empty(); }
  VirtualTime now() const { return clock_.now(); }

 private:
  VirtualClock& clock_;
  EventHeap heap_;
};

}  // namespace softslc
