// The event queue: (time, sequence) order, FIFO ties, time never goes backwards.
//
// Source: house-style.md (ns-3: events ordered by (timestamp, uid); the simulator asserts that
// time never goes backwards).
#include <gtest/gtest.h>

#include <string>
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

}  // namespace
}  // namespace softslc
