#include "vm/ml_hsc.h"

#include "parser/address.h"

namespace softslc {

namespace {

constexpr std::int64_t kNsPerSecond = 1'000'000'000;

std::int64_t read_long(const std::uint16_t* w, std::uint32_t at) {
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(w[at]) | static_cast<std::uint32_t>(w[at + 1]) << 16);
}

void write_long(std::uint16_t* w, std::uint32_t at, std::int64_t v) {
  const auto bits = static_cast<std::uint32_t>(static_cast<std::int32_t>(v));
  w[at] = static_cast<std::uint16_t>(bits);
  w[at + 1] = static_cast<std::uint16_t>(bits >> 16);
}

void set_bit(std::uint16_t& word, int bit, bool on) {
  word = static_cast<std::uint16_t>(on ? word | (1u << bit) : word & ~(1u << bit));
}

bool bit_of(std::uint16_t word, int bit) { return (word >> bit) & 1u; }

}  // namespace

void MicroLogixHsc::attach(const FileLayout& file, std::uint32_t output_word) {
  count_ = file.present ? static_cast<int>(file.elements) : 0;
  if (count_ > static_cast<int>(counters_.size())) count_ = static_cast<int>(counters_.size());
  base_ = file.base;
  output_word_ = output_word;
}

void MicroLogixHsc::enter_run(std::uint16_t* w, std::int64_t now) {
  for (int c = 0; c < count_; ++c) {
    Counter& k = counters_[static_cast<std::size_t>(c)];
    std::uint16_t& bits = w[base(c) + hsc::kBits];
    for (int b : {hsc::kLowInterruptBit, hsc::kHighInterruptBit, hsc::kUnderflowInterruptBit, hsc::kOverflowInterruptBit})
      set_bit(bits, b, false);
    if (bit_of(bits, hsc::kAutoStartBit)) set_bit(bits, hsc::kFunctionEnabledBit, true);
    k.config = {};
    k.events = {};
    load_from_file(w, c);
    k.seen = pulses_delivered(c, now);
    k.set_parameters = bit_of(bits, hsc::kSetParametersBit);
  }
}

void MicroLogixHsc::advance(std::uint16_t* w, std::int64_t now) {
  for (int c = 0; c < count_; ++c) {
    Counter& k = counters_[static_cast<std::size_t>(c)];
    // No source and nothing delivered since the last update: catch_up would count nothing.
    if (k.source.rate != 0 || k.seen != k.source.before) catch_up(w, c, now);
    const bool sp = bit_of(w[base(c) + hsc::kBits], hsc::kSetParametersBit);
    if (sp && !k.set_parameters) load_from_file(w, c);
    k.set_parameters = sp;
  }
}

void MicroLogixHsc::catch_up(std::uint16_t* w, int counter, std::int64_t now) {
  Counter& k = counters_[static_cast<std::size_t>(counter)];
  const std::int64_t delivered = pulses_delivered(counter, now);
  const std::int64_t fresh = delivered - k.seen;
  k.seen = delivered;
  // FE enables the counter [U: the FE row was not found; TVZ_1100_REV02's MAIN_PROG rung 2 writes it
  // to enable the encoder's counter, as its annotations say]. Pulses while it is clear are not counted.
  if (fresh > 0 && k.config.loaded && bit_of(w[base(counter) + hsc::kBits], hsc::kFunctionEnabledBit))
    count(w, counter, fresh);
}

// Mode 0, the up counter: each pulse adds one; the accumulator is cleared (0) when it reaches the high
// preset [U: the mode table (1762-RM001C p. 5-16) was not reached; the same family's Micro800 table
// says so for its mode 0 (2080-UM002N p. 284 Table 70), and TVZ_1100_REV02's annotations say so of
// its MOD 0]. An accumulator at or above HIP (after RAC or SP) counts on to OVF and then rolls over
// to UNF, the pulse not lost, setting OF (1762-RM001C pp. 5-13, 5-23). Whole cycles are counted by
// arithmetic, so a long interval costs no more than a short one.
void MicroLogixHsc::count(std::uint16_t* w, int counter, std::int64_t pulses) {
  Counter& k = counters_[static_cast<std::size_t>(counter)];
  const Config& c = k.config;
  const std::uint32_t at = base(counter);
  std::uint16_t& status = w[at + hsc::kStatus];
  bool reached_high = false;
  while (pulses > 0) {
    if (k.accumulator < c.high) {
      const std::int64_t to_high = c.high - k.accumulator;
      if (pulses < to_high) {
        k.accumulator += pulses;
        pulses = 0;
      } else {
        // Reaches HIP and is cleared; each further HIP pulses (if HIP > 0) is one more cycle, and
        // one more high-preset event.
        pulses -= to_high;
        k.accumulator = 0;
        reached_high = true;
        ++k.events.high;
        if (c.high > 0) {
          k.events.high += pulses / c.high;
          k.accumulator = pulses % c.high;
          pulses = 0;
        }
      }
    } else {
      const std::int64_t to_roll = c.overflow - k.accumulator + 1;
      if (pulses < to_roll) {
        k.accumulator += pulses;
        pulses = 0;
      } else {
        pulses -= to_roll;
        k.accumulator = c.underflow;
        ++k.events.overflow;
        set_bit(status, hsc::kOverflowBit, true);
      }
    }
  }
  set_bit(status, hsc::kCountUpBit, true);
  set_bit(status, hsc::kDirectionBit, true);
  if (reached_high) {
    // MD, mode done [U], for the program to see and clear; the outputs OMB selects follow HPO
    // (1762-RM001C p. 5-24).
    set_bit(status, hsc::kModeDoneBit, true);
    drive_outputs(w, c, c.high_out);
  }
  write_accumulator(w, counter);
}

void MicroLogixHsc::drive_outputs(std::uint16_t* w, const Config& c, std::uint16_t pattern) const {
  if (c.mask == 0) return;
  std::uint16_t& out = w[output_word_];
  out = static_cast<std::uint16_t>((out & ~c.mask) | (pattern & c.mask));
}

bool MicroLogixHsc::load_from_file(std::uint16_t* w, int counter) {
  Counter& k = counters_[static_cast<std::size_t>(counter)];
  const std::uint32_t at = base(counter);
  Config c;
  c.mode = static_cast<std::int16_t>(w[at + hsc::kMode]);
  c.high = read_long(w, at + hsc::kHighPreset);
  c.low = read_long(w, at + hsc::kLowPreset);
  c.overflow = read_long(w, at + hsc::kOverflow);
  c.underflow = read_long(w, at + hsc::kUnderflow);
  c.mask = w[at + hsc::kOutputMask];
  c.high_out = w[at + hsc::kHighOutput];
  c.low_out = w[at + hsc::kLowOutput];
  c.loaded = true;
  // OVF >= HIP (1762-RM001C p. 5-23 writes "greater than"; RSLogix's default has them equal), UNF <=
  // LOP (1766-RM001A p. 127); a mode other than 0 is not run
  // (`check` refuses it in a DATA block, and MOD is read only). A refused load sets ED and keeps what
  // was loaded before [U: the HSC error codes were not found, so ER is left as it is].
  std::uint16_t& bits = w[at + hsc::kBits];
  if (c.mode != 0 || c.overflow < c.high || c.underflow > c.low) {
    set_bit(bits, hsc::kErrorBit, true);
    return false;
  }
  set_bit(bits, hsc::kErrorBit, false);
  k.config = c;
  k.accumulator = read_long(w, at + hsc::kAccumulator);
  set_bit(w[at + hsc::kStatus], hsc::kCountUpBit, true);
  set_bit(w[at + hsc::kStatus], hsc::kCountDownBit, false);
  return true;
}

bool MicroLogixHsc::load(std::uint16_t* w, int counter, std::int64_t high, std::int64_t low, std::uint16_t high_out,
                         std::uint16_t low_out, std::int64_t now) {
  if (counter < 0 || counter >= count_) return false;
  catch_up(w, counter, now);
  Counter& k = counters_[static_cast<std::size_t>(counter)];
  const std::uint32_t at = base(counter);
  const std::int64_t overflow = k.config.loaded ? k.config.overflow : read_long(w, at + hsc::kOverflow);
  const std::int64_t underflow = k.config.loaded ? k.config.underflow : read_long(w, at + hsc::kUnderflow);
  if (overflow < high || underflow > low) {
    set_bit(w[at + hsc::kBits], hsc::kErrorBit, true);
    return false;
  }
  write_long(w, at + hsc::kHighPreset, high);
  write_long(w, at + hsc::kLowPreset, low);
  w[at + hsc::kHighOutput] = high_out;
  w[at + hsc::kLowOutput] = low_out;
  k.config.high = high;
  k.config.low = low;
  k.config.high_out = high_out;
  k.config.low_out = low_out;
  return true;
}

void MicroLogixHsc::reset_accumulator(std::uint16_t* w, int counter, std::int64_t value, std::int64_t now) {
  if (counter < 0 || counter >= count_) return;
  catch_up(w, counter, now);
  counters_[static_cast<std::size_t>(counter)].accumulator = value;
  write_accumulator(w, counter);
}

void MicroLogixHsc::write_accumulator(std::uint16_t* w, int counter) const {
  write_long(w, base(counter) + hsc::kAccumulator, counters_[static_cast<std::size_t>(counter)].accumulator);
}

std::string MicroLogixHsc::set_pulse_rate(int counter, std::int64_t rate, std::int64_t now) {
  if (counter < 0 || counter >= count_)
    return "this processor has " + std::to_string(count_) + " high-speed counter(s)" +
           (count_ ? ", HSC0" + (count_ > 1 ? " to HSC" + std::to_string(count_ - 1) : std::string()) : std::string());
  if (rate < 0 || rate > kMaxPulseRate)
    return "pulse rate " + std::to_string(rate) + " is out of range 0-" + std::to_string(kMaxPulseRate) + " pulses a second";
  PulseSource& s = counters_[static_cast<std::size_t>(counter)].source;
  s.before = pulses_delivered(counter, now);
  s.start = now;
  s.rate = rate;
  return {};
}

MicroLogixHsc::Events MicroLogixHsc::take_events(int counter) {
  if (counter < 0 || counter >= count_) return {};
  Events e = counters_[static_cast<std::size_t>(counter)].events;
  counters_[static_cast<std::size_t>(counter)].events = {};
  return e;
}

std::int64_t MicroLogixHsc::pulses_delivered(int counter, std::int64_t now) const {
  const PulseSource& s = counters_[static_cast<std::size_t>(counter)].source;
  if (s.rate == 0 || now <= s.start) return s.before;
  const std::int64_t dt = now - s.start;
  // floor(dt * rate / 1e9) without overflowing: whole seconds, then the remainder (< 1e9 x 1e6).
  return s.before + dt / kNsPerSecond * s.rate + dt % kNsPerSecond * s.rate / kNsPerSecond;
}

bool MicroLogixHsc::pulses_arriving() const {
  for (int i = 0; i < count_; ++i)
    if (counters_[static_cast<std::size_t>(i)].source.rate != 0) return true;
  return false;
}

bool MicroLogixHsc::at_rest(const std::uint16_t* w) const {
  for (int c = 0; c < count_; ++c) {
    const Counter& k = counters_[static_cast<std::size_t>(c)];
    if (k.source.rate != 0 || k.seen != k.source.before ||
        bit_of(w[base(c) + hsc::kBits], hsc::kSetParametersBit) != k.set_parameters)
      return false;
  }
  return true;
}

}  // namespace softslc
