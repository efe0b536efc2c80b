// The MicroLogix high-speed counters (the HSC function file, issue 16).
//
// The HSC function file (HSC:0 .. HSC:5, 18 words an element, hsc:: in parser/address.h) is the
// program's view of the HSC sub-system, a counter that runs beside the scan. As the manuals put it
// (1762-RM001C p. 5-23, 1766-RM001A p. 127), toggling Set Parameters (SP) low to high transfers the
// data in the function file into the sub-system; between loads the sub-system works on its own
// copy, so a program write to HSC:0.HIP changes nothing until the next SP or HSL. This class is that
// sub-system: one loaded configuration per counter, the accumulator it keeps, and the pulse source
// wired to its input.
//
// Pulses come from a pulse-train source on the counter's input (`device HSC0 pulses 1000` in a test,
// Runtime::inject): N pulses a second from the moment it is set, pulse k rising at start + k/N s in
// integer virtual time, so a run is deterministic and no pulse is lost or invented by rounding. The
// sub-system is brought up to date (advance) at the start of each program scan and before HSL, RAC
// and an SP edge act; the program reads HSC:n.ACC as the last update left it. What is known from
// the manuals and what is softslc's decision [U] is listed in docs/semantics.md "The HSC function
// file": mode 0 (up counter, cleared when it reaches the high preset) is the only mode run.
//
// The object holds word indices, never pointers, so an Interpreter that owns it can be copied with
// its data table; every call is handed the table's words.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "vm/data_table.h"

namespace softslc {

class MicroLogixHsc {
 public:
  // The largest pulse rate a source may be given (pulses a second): 1 MHz, above every MicroLogix
  // HSC's rating, so that a test can drive any of them; a higher rate is refused, not clipped.
  static constexpr std::int64_t kMaxPulseRate = 1'000'000;

  // `file` is the HSC function file's layout (absent: no counters), `output_word` the word of O:0.0
  // that OMB/HPO/LPO drive.
  void attach(const FileLayout& file, std::uint32_t output_word);
  int counters() const { return count_; }

  // Entering an executing mode: each counter's function-file data is loaded (as by SP), the interrupt
  // flags LPI, HPI, UFI and OFI are cleared (1762-RM001C pp. 5-10, 5-13), AS sets FE [U], and pulses
  // that arrived while the controller was not executing are not counted [U].
  void enter_run(std::uint16_t* w, std::int64_t now);
  // Counts the pulses delivered up to `now` on every counter whose FE is set, then loads a counter
  // whose SP has risen since the last update.
  void advance(std::uint16_t* w, std::int64_t now);
  // HSL: the counter's HIP, LOP, HPO and LPO := the sources, in the file and the sub-system. Returns
  // false (and sets ED) when the presets break OVF >= HIP or UNF <= LOP; nothing is loaded then.
  bool load(std::uint16_t* w, int counter, std::int64_t high, std::int64_t low, std::uint16_t high_out,
            std::uint16_t low_out, std::int64_t now);
  // RAC: the counter's accumulator := value (1762-RM001C p. 5-27).
  void reset_accumulator(std::uint16_t* w, int counter, std::int64_t value, std::int64_t now);

  // The pulse source on a counter's input: `rate` pulses a second from `now` (0 stops it). Returns an
  // empty string, or why the rate is refused.
  std::string set_pulse_rate(int counter, std::int64_t rate, std::int64_t now);
  // Some counter's input has a pulse source running (its accumulator moves with time).
  bool pulses_arriving() const;
  // The next advance would change nothing: no pulse to count on any counter, and every SP bit in `w` as
  // the last advance found it (a rise loads the counter; the last executed scan may have set SP).
  bool at_rest(const std::uint16_t* w) const;
  // Pulses the source has delivered to the counter's input by `now` (counted or not).
  std::int64_t pulses_delivered(int counter, std::int64_t now) const;

  // The interrupt events of a counter since the last call: how many times it reached the high preset
  // and counted through the overflow value. The interpreter turns them into HSC interrupts (the
  // masks, UIE and PFN decide; vm/interrupts.cpp) and the counts start again from 0.
  struct Events {
    std::int64_t high = 0, overflow = 0;
  };
  Events take_events(int counter);
  // Some counter has events not yet taken (asked at every scan before taking them one by one).
  bool has_events() const {
    for (int c = 0; c < count_; ++c) {
      const Events& e = counters_[static_cast<std::size_t>(c)].events;
      if (e.high != 0 || e.overflow != 0) return true;
    }
    return false;
  }

 private:
  struct Config {
    bool loaded = false;
    int mode = 0;
    std::int64_t high = 0, low = 0, overflow = 0, underflow = 0;
    std::uint16_t mask = 0, high_out = 0, low_out = 0;
  };
  struct PulseSource {
    std::int64_t rate = 0;         // pulses a second; 0 = none
    std::int64_t start = 0;        // virtual time the rate was set
    std::int64_t before = 0;       // pulses delivered before `start`
  };
  struct Counter {
    Config config;
    std::int64_t accumulator = 0;
    std::int64_t seen = 0;         // pulses delivered at the last update
    bool set_parameters = false;   // SP at the last update (for its rising edge)
    Events events;                 // not yet taken by the interpreter
    PulseSource source;
  };

  std::uint32_t base(int counter) const { return base_ + static_cast<std::uint32_t>(counter) * static_cast<std::uint32_t>(hsc::kWords); }
  void count(std::uint16_t* w, int counter, std::int64_t pulses);
  bool load_from_file(std::uint16_t* w, int counter);
  void write_accumulator(std::uint16_t* w, int counter) const;
  void drive_outputs(std::uint16_t* w, const Config& c, std::uint16_t pattern) const;
  void catch_up(std::uint16_t* w, int counter, std::int64_t now);

  std::uint32_t base_ = 0;
  std::uint32_t output_word_ = 0;
  int count_ = 0;
  std::array<Counter, 6> counters_{};
};

}  // namespace softslc
