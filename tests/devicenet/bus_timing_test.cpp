// CAN frame timing and the Timeline. No figure here comes from the 1747-SDN manual, which gives no
// bus timing: frame sizes are CAN 2.0A's (47 bits of overhead + 8 per data byte + worst-case stuffing
// floor((34 + 8n - 1) / 4)), hand-computed below, at 8/4/2 us per bit for 125/250/500K.
#include <gtest/gtest.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "modules/devicenet/bus_timing.h"
#include "modules/devicenet/timeline.h"

namespace softslc::devicenet {
namespace {

TEST(BusTiming, FrameBits) {
  EXPECT_EQ(can_frame_bits(0), 55);   // 47 + 0 + 8
  EXPECT_EQ(can_frame_bits(1), 65);   // 47 + 8 + 10
  EXPECT_EQ(can_frame_bits(4), 95);   // 47 + 32 + 16
  EXPECT_EQ(can_frame_bits(8), 135);  // 47 + 64 + 24
  EXPECT_EQ(bit_time(Baud::k125), 8000);
  EXPECT_EQ(bit_time(Baud::k250), 4000);
  EXPECT_EQ(bit_time(Baud::k500), 2000);
  EXPECT_EQ(frame_time(Baud::k125, 8), 1'080'000);
  EXPECT_EQ(frame_time(Baud::k500, 1), 130'000);
}

TEST(BusTiming, Fragmentation) {
  EXPECT_EQ(io_message_time(Baud::k500, 8), 135 * 2000);
  // 9 bytes: [frag + 7] = 8 bytes (135 bits), [frag + 2] = 3 bytes (85 bits).
  EXPECT_EQ(io_message_time(Baud::k500, 9), (135 + 85) * 2000);
  EXPECT_EQ(io_message_time(Baud::k500, 0), 55 * 2000);
  // Explicit: body 7 + header = 8 bytes, one frame; body 8: [hdr frag 6] (135) + ack (85),
  // [hdr frag 2] (95) + ack (85).
  EXPECT_EQ(explicit_message_time(Baud::k500, 7), 135 * 2000);
  EXPECT_EQ(explicit_message_time(Baud::k500, 8), (135 + 85 + 95 + 85) * 2000);
  EXPECT_EQ(explicit_request_body(1, 1, 0), 4);
  EXPECT_EQ(explicit_request_body(300, 0, 2), 6);
}

TEST(BusTiming, BaudNames) {
  EXPECT_EQ(parse_baud("250K"), Baud::k250);
  EXPECT_FALSE(parse_baud("250k").has_value());
  EXPECT_EQ(to_string(Baud::k500), "500K");
}

// Events at the same time run in the order they were scheduled; time never goes backwards.
TEST(Timeline, OrderedByTimeThenSequence) {
  Timeline t;
  std::vector<std::string> log;
  t.schedule_at(20, [&](VirtualTime now) { log.push_back("b@" + std::to_string(now)); });
  t.schedule_at(10, [&](VirtualTime) { log.push_back("a1"); });
  t.schedule_at(10, [&](VirtualTime) {
    log.push_back("a2");
    t.schedule_at(10, [&](VirtualTime) { log.push_back("a3"); });  // same time, scheduled later
  });
  EXPECT_EQ(t.advance_to(15), 3u);
  EXPECT_EQ(t.now(), 15);
  EXPECT_EQ(t.advance_to(20), 1u);
  EXPECT_EQ(log, (std::vector<std::string>{"a1", "a2", "a3", "b@20"}));
  EXPECT_THROW(t.schedule_at(19, [](VirtualTime) {}), TimeWentBackwards);
  EXPECT_THROW(t.advance_to(19), TimeWentBackwards);
}

TEST(Timeline, CancelAndOwners) {
  Timeline t;
  int ran = 0;
  const auto id = t.schedule_at(5, [&](VirtualTime) { ++ran; });
  t.schedule_at(5, [&](VirtualTime) { ++ran; }, 7);
  t.schedule_at(6, [&](VirtualTime) { ++ran; }, 7);
  EXPECT_TRUE(t.cancel(id));
  EXPECT_FALSE(t.cancel(id));
  EXPECT_EQ(t.cancel_owner(7), 2u);
  EXPECT_EQ(t.pending(), 0u);
  t.advance_to(10);
  EXPECT_EQ(ran, 0);
}

// A callback's captures sit in place up to Timeline::Callback::kInlineBytes and on the heap beyond
// (an explicit message's reply): both run with their captures intact, in (time, sequence) order,
// also when events scheduled from a running callback reuse the slots of events that ran.
TEST(Timeline, LargeCapturesAndReusedSlots) {
  Timeline t;
  std::vector<int> log;
  std::array<int, 64> big{};  // 256 bytes: on the heap
  big[63] = 7;
  auto shared = std::make_shared<int>(3);  // counts copies left alive
  t.schedule_at(2, [&log, big](VirtualTime) { log.push_back(big[63]); });
  t.schedule_at(1, [&log, &t, shared](VirtualTime now) {
    log.push_back(*shared);
    for (int k = 0; k < 3; ++k) t.schedule_at(now, [&log, k](VirtualTime) { log.push_back(10 + k); });
  });
  t.schedule_at(9, [shared](VirtualTime) {}, 5);
  EXPECT_EQ(t.advance_to(2), 5u);
  EXPECT_EQ(log, (std::vector<int>{3, 10, 11, 12, 7}));
  EXPECT_EQ(shared.use_count(), 2);  // the ran event's copy is gone, the pending one's is not
  EXPECT_EQ(t.cancel_owner(5), 1u);
  EXPECT_EQ(shared.use_count(), 1);
}

}  // namespace
}  // namespace softslc::devicenet
