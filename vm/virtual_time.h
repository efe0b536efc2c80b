// Virtual time: the only clock the VM knows.
//
// softslc never reads the wall clock. Time is an integer count of nanoseconds since the runtime
// was created (power-up), held by one VirtualClock per runtime. The clock only moves forward:
// each scan advances it by that scan's predicted duration (see ScanTimeModel), and the event
// queue advances it to each event's time in order. Integer nanoseconds make every sum exact, so
// two runs of the same program with the same inputs reach exactly the same times; a double
// would accumulate rounding that depends on the order of additions.
//
// The SLC's own time unit is the 10 ms tick of its free-running clock (S:4, timers); kTick
// names it so code that converts between the two says so.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

namespace softslc {

// A point in virtual time: nanoseconds since power-up.
using VirtualTime = std::int64_t;
// A span of virtual time in nanoseconds.
using Nanoseconds = std::int64_t;

inline constexpr Nanoseconds kNsPerUs = 1'000;
inline constexpr Nanoseconds kNsPerMs = 1'000'000;
inline constexpr Nanoseconds kNsPerS = 1'000'000'000;
// The SLC clock tick: S:4 counts it, timers accumulate it, S:3 and S:22/S:23 report in it.
inline constexpr Nanoseconds kTick = 10 * kNsPerMs;

constexpr Nanoseconds microseconds(std::int64_t n) { return n * kNsPerUs; }
constexpr Nanoseconds milliseconds(std::int64_t n) { return n * kNsPerMs; }
constexpr Nanoseconds seconds(std::int64_t n) { return n * kNsPerS; }

// Thrown when something asks time to run backwards. It is a programming error in the caller
// (a module scheduling in the past, a clock moved behind an event), never a user-program error,
// so it is an exception rather than a fault.
class TimeWentBackwards : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

// The processor's clock. It never moves backwards; every attempt to do so throws.
class VirtualClock {
 public:
  VirtualTime now() const { return now_; }

  void advance_to(VirtualTime t) {
    if (t < now_)
      throw TimeWentBackwards("virtual clock asked to go from " + std::to_string(now_) + " ns back to " +
                              std::to_string(t) + " ns");
    now_ = t;
  }
  void advance_by(Nanoseconds d) {
    if (d < 0) throw TimeWentBackwards("virtual clock asked to advance by a negative duration");
    now_ += d;
  }

 private:
  VirtualTime now_ = 0;
};

}  // namespace softslc
