// EventHeap: the ordered store of future work shared by the runtime's EventQueue (vm/event_queue.h)
// and the simulated DeviceNet network's Timeline (modules/devicenet/timeline.h).
//
// Both queues run callbacks void(VirtualTime now) in (time, sequence) order: the sequence number
// grows by one for every event ever scheduled, so events at the same time run in the order they
// were scheduled and a run is reproducible bit for bit (as in ns-3). What differs is only who keeps
// the clock (the runtime's VirtualClock, the network's own now()) and what an error says; the
// storage and the order are here, once.
//
// Storage (issue 20: a module schedules its next event every few microseconds of virtual time, and
// the queues were a large part of the simulation time of the 1747-SN and 1747-SDN examples). The
// order is a binary min-heap of small keys (time, sequence, slot) in one vector that keeps its
// capacity; each key's callback sits in a slot of a second vector, reused through a free list, so
// the heap moves 24-byte keys and never a callback. A callback is an EventCallback: a type-erased
// callable that keeps captures of up to kInlineBytes in place (every periodic event of the modules)
// and only larger ones (an explicit message's reply) on the heap, so scheduling an event allocates
// nothing once the vectors have grown (a std::function allocates for captures over 16 bytes, and
// a std::map of them cost two nodes per event). cancel() and cancel_owner() search linearly and
// rebuild the heap: cancels are rare and a queue holds a few dozen events at most. Keys are unique,
// so the order events run in does not depend on how the heap is arranged.
//
// Header-only: the DeviceNet library is a pure library that does not link the VM.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <new>
#include <optional>
#include <type_traits>
#include <utility>
#include <vector>

#include "vm/virtual_time.h"

namespace softslc {

// A move-only callable void(VirtualTime now). Captures up to kInlineBytes (nothrow-movable) are
// stored in place, larger ones on the heap.
class EventCallback {
 public:
  static constexpr std::size_t kInlineBytes = 64;

  EventCallback() = default;
  template <class F, class D = std::decay_t<F>,
            class = std::enable_if_t<!std::is_same_v<D, EventCallback> && std::is_invocable_v<D&, VirtualTime>>>
  EventCallback(F&& f) {  // NOLINT(google-explicit-constructor): lambdas convert as to std::function
    if constexpr (sizeof(D) <= kInlineBytes && alignof(D) <= alignof(std::max_align_t) &&
                  std::is_nothrow_move_constructible_v<D>) {
      ::new (static_cast<void*>(buf_)) D(std::forward<F>(f));
      ops_ = &kInlineOps<D>;
    } else {
      ::new (static_cast<void*>(buf_)) D*(new D(std::forward<F>(f)));
      ops_ = &kHeapOps<D>;
    }
  }
  EventCallback(EventCallback&& o) noexcept { take(o); }
  EventCallback& operator=(EventCallback&& o) noexcept {
    if (this != &o) {
      reset();
      take(o);
    }
    return *this;
  }
  EventCallback(const EventCallback&) = delete;
  EventCallback& operator=(const EventCallback&) = delete;
  ~EventCallback() { reset(); }

  explicit operator bool() const { return ops_ != nullptr; }
  void operator()(VirtualTime now) { ops_->call(buf_, now); }

 private:
  struct Ops {
    void (*call)(void* self, VirtualTime now);
    void (*move)(void* from, void* to);  // move-constructs at `to` and destroys `from`
    void (*destroy)(void* self);
  };
  template <class D>
  static constexpr Ops kInlineOps{[](void* s, VirtualTime now) { (*static_cast<D*>(s))(now); },
                                  [](void* from, void* to) {
                                    ::new (to) D(std::move(*static_cast<D*>(from)));
                                    static_cast<D*>(from)->~D();
                                  },
                                  [](void* s) { static_cast<D*>(s)->~D(); }};
  template <class D>
  static constexpr Ops kHeapOps{[](void* s, VirtualTime now) { (**static_cast<D**>(s))(now); },
                                [](void* from, void* to) { ::new (to) D*(*static_cast<D**>(from)); },
                                [](void* s) { delete *static_cast<D**>(s); }};

  void take(EventCallback& o) noexcept {
    ops_ = o.ops_;
    if (ops_ != nullptr) ops_->move(o.buf_, buf_);
    o.ops_ = nullptr;
  }
  void reset() noexcept {
    if (ops_ != nullptr) ops_->destroy(buf_);
    ops_ = nullptr;
  }

  alignas(std::max_align_t) unsigned char buf_[kInlineBytes];
  const Ops* ops_ = nullptr;
};

// The (time, sequence) heap itself. It keeps no clock: the owning queue checks times against its
// own and moves its clock to each event's time before calling it (run_due).
class EventHeap {
 public:
  using EventId = std::uint64_t;
  // Identifies who scheduled an event, for cancel_owner(). 0 = nobody in particular.
  using Owner = std::uintptr_t;

  EventHeap() = default;
  EventHeap(const EventHeap&) = delete;
  EventHeap& operator=(const EventHeap&) = delete;

  // Adds `cb` at `at` (the caller has checked that `at` is not before its clock). Returns its id.
  EventId push(VirtualTime at, EventCallback cb, Owner owner = 0) {
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

  // The id the next push will get: unchanged while nothing was scheduled (repeated cycles,
  // docs/semantics.md "Repeated cycles", check that a cycle scheduled nothing).
  EventId next_id() const { return next_id_; }

  // Removes one pending event; false when it already ran or never existed.
  bool cancel(EventId id) {
    const auto it = std::find_if(heap_.begin(), heap_.end(), [id](const Key& k) { return k.id == id; });
    if (it == heap_.end()) return false;
    release(it->slot);
    heap_.erase(it);
    std::make_heap(heap_.begin(), heap_.end(), runs_after);
    return true;
  }

  // Removes every pending event of `owner`; returns how many.
  std::size_t cancel_owner(Owner owner) {
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

  // Runs every event due at or before `until` in (time, sequence) order, including events the
  // callbacks schedule inside the window; `set_now(at)` moves the owner's clock to each event's
  // time before its callback runs. Returns the number of events run.
  template <class SetNow>
  std::size_t run_due(VirtualTime until, SetNow&& set_now) {
    std::size_t ran = 0;
    while (!heap_.empty() && heap_.front().at <= until) {
      std::pop_heap(heap_.begin(), heap_.end(), runs_after);
      const Key k = heap_.back();
      heap_.pop_back();
      // The callback leaves its slot before it runs: it may schedule more events (at >= now), which
      // may reuse the slot or grow the slot vector; the loop picks them up in order.
      EventCallback cb = std::move(slots_[k.slot].cb);
      release(k.slot);
      set_now(k.at);
      cb(k.at);
      ++ran;
    }
    return ran;
  }

  std::optional<VirtualTime> next_time() const {
    if (heap_.empty()) return std::nullopt;
    return heap_.front().at;
  }
  std::size_t size() const { return heap_.size(); }
  bool empty() const { return heap_.empty(); }

 private:
  struct Key {
    VirtualTime at;
    EventId id;
    std::uint32_t slot;
  };
  struct Slot {
    EventCallback cb;
    Owner owner = 0;
  };
  // The heap's comparator: "a runs after b" (later time, then later sequence), so the heap's front
  // is the next event to run. A function object, not a function pointer, so the heap algorithms
  // inline it.
  struct RunsAfter {
    bool operator()(const Key& a, const Key& b) const { return a.at != b.at ? a.at > b.at : a.id > b.id; }
  };
  static constexpr RunsAfter runs_after{};
  void release(std::uint32_t slot) {
    slots_[slot].cb = EventCallback();
    slots_[slot].owner = 0;
    free_.push_back(slot);
  }

  std::vector<Key> heap_;
  std::vector<Slot> slots_;
  std::vector<std::uint32_t> free_;
  EventId next_id_ = 1;
};

}  // namespace softslc
