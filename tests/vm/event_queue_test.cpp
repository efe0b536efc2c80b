// The event queue: (time, sequence) order, FIFO ties, time never goes backwards.
//
// Source: house-style.md (ns-3: events ordered by (timestamp, uid); the simulator asserts that
// time never goes backwards).
#include <gtest/gtest.h>

#include <functional>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "vm/event_queue.h"

namespace softslc {
namespace {

TEST(EventQueue, RunsInTimeOrderAndTiesFirstInFirstOut) {
  VirtualClock clock;
  EventQueue q(clock);
  std::vector<std::string> trace;
  q.schedule_at(30, [&](VirtualTime t) { trace.push_back("c@" + std::to_string(t)); });
  q.schedule_at(10, [&](VirtualTime t) { trace.push_back("a@" + std::to_string(t)); });
  q.schedule_at(20, [&](VirtualTime t) { trace.push_back("b1@" + std::to_string(t)); });
  q.schedule_at(20, [&](VirtualTime t) { trace.push_back("b2@" + std::to_string(t)); });
  q.schedule_at(20, [&](VirtualTime t) { trace.push_back("b3@" + std::to_string(t)); });
  EXPECT_EQ(q.run_until(25), 4u);
  EXPECT_EQ(clock.now(), 25);
  EXPECT_EQ(q.run_until(100), 1u);
  EXPECT_EQ(trace, (std::vector<std::string>{"a@10", "b1@20", "b2@20", "b3@20", "c@30"}));
}

TEST(EventQueue, CallbacksSeeTheirOwnTimeAndMayScheduleMore) {
  VirtualClock clock;
  EventQueue q(clock);
  std::vector<VirtualTime> seen;
  std::function<void(VirtualTime)> tick = [&](VirtualTime t) {
    seen.push_back(clock.now());
    EXPECT_EQ(t, clock.now());
    if (seen.size() < 5) q.schedule_after(7, tick);
  };
  q.schedule_at(0, tick);
  q.run_until(100);
  EXPECT_EQ(seen, (std::vector<VirtualTime>{0, 7, 14, 21, 28}));
}

TEST(EventQueue, SameTimeEventsScheduledByACallbackRunAfterTheOnesAlreadyQueued) {
  VirtualClock clock;
  EventQueue q(clock);
  std::string order;
  q.schedule_at(5, [&](VirtualTime) {
    order += "A";
    q.schedule_at(5, [&](VirtualTime) { order += "C"; });
  });
  q.schedule_at(5, [&](VirtualTime) { order += "B"; });
  q.run_until(5);
  EXPECT_EQ(order, "ABC");
}

TEST(EventQueue, TimeNeverGoesBackwards) {
  VirtualClock clock;
  EventQueue q(clock);
  q.run_until(50);
  EXPECT_THROW(q.schedule_at(49, [](VirtualTime) {}), TimeWentBackwards);
  EXPECT_THROW(q.run_until(10), TimeWentBackwards);
  EXPECT_THROW(clock.advance_to(1), TimeWentBackwards);
  EXPECT_THROW(clock.advance_by(-1), TimeWentBackwards);
  EXPECT_EQ(clock.now(), 50);
  EXPECT_NO_THROW(q.schedule_at(50, [](VirtualTime) {}));
}

TEST(EventQueue, CancelRemovesAPendingEvent) {
  VirtualClock clock;
  EventQueue q(clock);
  int ran = 0;
  auto id = q.schedule_at(10, [&](VirtualTime) { ++ran; });
  q.schedule_at(10, [&](VirtualTime) { ran += 10; });
  EXPECT_TRUE(q.cancel(id));
  EXPECT_FALSE(q.cancel(id));
  q.run_until(10);
  EXPECT_EQ(ran, 10);
  EXPECT_TRUE(q.empty());
}

// The queue against a model of its contract (a std::map on (time, sequence)) under seeded random
// schedules, cancels (of pending, run and unknown ids) and runs, with callbacks that schedule and
// cancel in turn: the same events run in the same order at the same times, cancel answers the
// same, and size() and next_time() agree after every step.
TEST(EventQueue, RandomSchedulesAndCancelsMatchATimeThenSequenceModel) {
  for (std::uint32_t seed = 1; seed <= 20; ++seed) {
    std::mt19937 rng(seed);
    auto pick = [&](int n) { return static_cast<int>(rng() % static_cast<std::uint32_t>(n)); };
    VirtualClock clock;
    EventQueue q(clock);
    using Key = std::pair<VirtualTime, EventQueue::EventId>;
    std::map<Key, int> model;  // pending events by (time, id) -> tag
    std::vector<EventQueue::EventId> ids;
    std::vector<Key> key_of_tag;
    int ran = 0;
    auto model_cancel = [&](EventQueue::EventId id) {
      for (auto it = model.begin(); it != model.end(); ++it)
        if (it->first.second == id) {
          model.erase(it);
          return true;
        }
      return false;
    };
    std::function<void(VirtualTime, int)> add = [&](VirtualTime at, int depth) {
      const int tag = static_cast<int>(key_of_tag.size());
      key_of_tag.emplace_back();
      const EventQueue::EventId id = q.schedule_at(at, [&, tag, depth](VirtualTime t) {
        // The event that runs is the model's first, at its own time, and the clock shows it.
        ASSERT_FALSE(model.empty());
        EXPECT_EQ(model.begin()->first, key_of_tag[static_cast<std::size_t>(tag)]) << "seed " << seed;
        EXPECT_EQ(t, key_of_tag[static_cast<std::size_t>(tag)].first);
        EXPECT_EQ(clock.now(), t);
        model.erase(model.begin());
        ++ran;
        // Some callbacks schedule at their own time or later, or cancel another event.
        if (depth < 2 && pick(3) == 0) add(t + static_cast<std::int64_t>(pick(4)) * 5, depth + 1);
        if (pick(5) == 0) {
          const auto victim = ids[static_cast<std::size_t>(pick(static_cast<int>(ids.size())))];
          EXPECT_EQ(q.cancel(victim), model_cancel(victim)) << "seed " << seed;
        }
      });
      key_of_tag[static_cast<std::size_t>(tag)] = {at, id};
      ids.push_back(id);
      model.emplace(Key{at, id}, tag);
    };
    for (int step = 0; step < 300; ++step) {
      const int what = pick(10);
      if (what < 6) {
        add(clock.now() + pick(50), 0);
      } else if (what < 8 && !ids.empty()) {
        const auto id = pick(4) == 0 ? EventQueue::EventId{999'999} : ids[static_cast<std::size_t>(pick(static_cast<int>(ids.size())))];
        ASSERT_EQ(q.cancel(id), model_cancel(id)) << "seed " << seed << " step " << step;
      } else {
        const VirtualTime until = clock.now() + pick(30);
        q.run_until(until);
        ASSERT_TRUE(model.empty() || model.begin()->first.first > until) << "seed " << seed << " step " << step;
        ASSERT_EQ(clock.now(), until);
      }
      ASSERT_EQ(q.size(), model.size());
      ASSERT_EQ(q.next_time(), model.empty() ? std::nullopt : std::optional<VirtualTime>(model.begin()->first.first));
    }
    EXPECT_GT(ran, 50) << "seed " << seed;
  }
}

}  // namespace
}  // namespace softslc
