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
// Storage (issue 20: an idle network runs five or six events per scan cycle, and the events were
// most of a quiet 1747-SDN program's simulation time). The order is a binary min-heap of small
// keys (time, sequence, slot) in one vector that keeps its capacity; each key's callback sits in a
// slot of a second vector, reused through a free list, so the heap moves 24-byte keys and never a
// callback. A callback is a Callback: a type-erased callable that keeps captures of up to
// kInlineBytes in place (every scan-cycle event of the scanner) and only larger ones (an explicit
// message's reply) on the heap, so scheduling an event allocates nothing once the vectors have
// grown. cancel() and cancel_owner() search linearly and rebuild the heap: they are rare (the
// scanner's destructor) and a network holds a few dozen events at most. Keys are unique, so the
// order events run in does not depend on how the heap is arranged.
#pragma once

#include <cstddef>
#include <cstdint>
#include <new>
#include <optional>
#include <type_traits>
#include <utility>
#include <vector>

#include "vm/virtual_time.h"

namespace softslc::devicenet {

using softslc::Nanoseconds;
using softslc::VirtualTime;

class Timeline {
 public:
  // A move-only callable void(VirtualTime now). Captures up to kInlineBytes (nothrow-movable) are
  // stored in place, larger ones on the heap.
  class Callback {
   public:
    static constexpr std::size_t kInlineBytes = 64;

    Callback() = default;
    template <class F, class D = std::decay_t<F>,
              class = std::enable_if_t<!std::is_same_v<D, Callback> && std::is_invocable_v<D&, VirtualTime>>>
    Callback(F&& f) {  // NOLINT(google-explicit-constructor): lambdas convert as to std::function
      if constexpr (sizeof(D) <= kInlineBytes && alignof(D) <= alignof(std::max_align_t) &&
                    std::is_nothrow_move_constructible_v<D>) {
        ::new (static_cast<void*>(buf_)) D(std::forward<F>(f));
        ops_ = &kInlineOps<D>;
      } else {
        ::new (static_cast<void*>(buf_)) D*(new D(std::forward<F>(f)));
        ops_ = &kHeapOps<D>;
      }
    }
    Callback(Callback&& o) noexcept { take(o); }
    Callback& operator=(Callback&& o) noexcept {
      if (this != &o) {
        reset();
        take(o);
      }
      return *this;
    }
    Callback(const Callback&) = delete;
    Callback& operator=(const Callback&) = delete;
    ~Callback() { reset(); }

    explicit operator bool() const { return ops_ != nullptr; }
    void operator()(VirtualTime now) { ops_->call(buf_, now); }

   private:
    struct Ops {
      void (*call)(void* self, VirtualTime now);
      void (*move)(void* from, void* to);  // move-constructs at `to` and destroys `from`
      void (*destroy)(void* self);
    };
    template <class D>
    static constexpr Ops kInlineOps{
        [](void* s, VirtualTime now) { (*static_cast<D*>(s))(now); },
        [](void* from, void* to) {
          ::new (to) D(std::move(*static_cast<D*>(from)));
          static_cast<D*>(from)->~D();
        },
        [](void* s) { static_cast<D*>(s)->~D(); }};
    template <class D>
    static constexpr Ops kHeapOps{
        [](void* s, VirtualTime now) { (**static_cast<D**>(s))(now); },
        [](void* from, void* to) { ::new (to) D*(*static_cast<D**>(from)); },
        [](void* s) { delete *static_cast<D**>(s); }};

    void take(Callback& o) noexcept {
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
  using EventId = std::uint64_t;
  // Identifies who scheduled an event, for cancel_owner(). 0 = nobody in particular.
  using Owner = std::uintptr_t;

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
  bool cancel(EventId id);
  // Removes every pending event of `owner`; returns how many.
  std::size_t cancel_owner(Owner owner);

  // Runs every event due at or before `t` in (time, sequence) order, then sets now() to t. Returns the
  // number of events run.
  std::size_t advance_to(VirtualTime t);

  std::optional<VirtualTime> next_time() const {
    if (heap_.empty()) return std::nullopt;
    return heap_.front().at;
  }
  std::size_t pending() const { return heap_.size(); }

 private:
  struct Key {
    VirtualTime at;
    EventId id;
    std::uint32_t slot;
  };
  struct Slot {
    Callback cb;
    Owner owner = 0;
  };
  // The heap's comparator: "a runs after b", so the heap's front is the next event to run.
  static bool runs_after(const Key& a, const Key& b) { return a.at != b.at ? a.at > b.at : a.id > b.id; }
  void release(std::uint32_t slot);

  std::vector<Key> heap_;
  std::vector<Slot> slots_;
  std::vector<std::uint32_t> free_;
  VirtualTime now_ = 0;
  EventId next_id_ = 1;
};

}  // namespace softslc::devicenet
