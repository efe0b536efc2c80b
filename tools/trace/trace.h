// Signal traces: what chosen data-table values did over virtual time, as a VCD file for GTKWave
// or an SVG timing diagram.
//
// A TraceRecorder samples its signals at scan boundaries, through the Runtime's scan observer
// (Runtime::set_scan_observer): once when attached (time of attachment), then at the end of every
// scan cycle, stamped with the virtual time the scan ended at, at 1 µs resolution. Sampling at
// scan boundaries keeps tracing out of the interpreter (nothing costs when no recorder is
// attached) and matches what the ladder can see: a value that changes and changes back inside one
// scan is not recorded. Only changes are stored, per signal, so a long steady run costs nothing.
//
// Signals are chosen by address or symbol. Bits become 1-bit wires, 16-bit words (N, T/C/R
// sub-elements, I/O words, M0/M1 words, S words) integer vectors of 16 bits, L words 32 bits, F
// words reals. A whole timer or counter (T4:0, C5:0) expands to its /EN and /DN bits and its .ACC;
// a control element (R6:0) to /EN, /DN and .POS. A marker signal, `scan`, counts scan cycles, so
// every scan boundary is a value change in the viewer.
//
// Bounded: the recorder counts the bytes its VCD value changes take; once `limit_bytes` is
// reached it stops recording and says so (truncated(), and a comment in the file). Both outputs
// are built from the same stored changes with fixed formatting and no wall clock, so the same run
// gives byte-identical files.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "parser/program.h"
#include "vm/runtime.h"

namespace softslc::trace {

struct Signal {
  enum class Kind : std::uint8_t { Bit, Word16, Word32, Real };
  std::string name;  // the symbol when the address has one, else the canonical address
  Address address;
  Kind kind = Kind::Bit;
  bool has_address = true;  // false for a signal read back from a VCD by name only (read_vcd)
};

// Resolves a comma-separated list of addresses or symbols ("START_PB,MOTOR,T4:0.ACC") into
// signals, expanding whole T/C/R elements. Returns false with a message for an unknown name or an
// address that cannot be traced (indexed, indirect, a whole string element).
bool parse_signal_list(const Program& program, const std::string& list, std::vector<Signal>& out,
                       std::string& error);
// Every direct address the ladder names, in order of first appearance (file by file, rung by
// rung); with outputs_only, just the operands output instructions write. Indexed and indirect
// operands are left out (their address is only known at run time).
std::vector<Signal> program_signals(const Program& program, bool outputs_only);

// One recorded value: bits and integers in `integer`, F words in `real`.
struct SampleValue {
  std::int64_t integer = 0;
  double real = 0.0;
  bool operator==(const SampleValue&) const = default;
};

struct Change {
  std::int64_t time_us = 0;
  SampleValue value;
};

class TraceRecorder {
 public:
  TraceRecorder(std::vector<Signal> signals, std::size_t limit_bytes);

  // An empty string, or why a signal cannot be read in `runtime` (an M-file word of an empty
  // slot, a file the program lacks); such a signal records 0.
  std::string check(const Runtime& runtime) const;
  // Installs this recorder as the runtime's scan observer and takes the first sample now. The
  // recorder must outlive the attachment (detach() or the runtime's end).
  void attach(Runtime& runtime);
  void detach(Runtime& runtime);
  // Records the signals' values at runtime.now() (the observer calls this).
  void sample(const Runtime& runtime);
  // Virtual time added to runtime.now(): a test's clock carries on across power cycles, each of
  // which builds a new Runtime starting at 0.
  void set_time_base(VirtualTime base) { time_base_ = base; }
  // Forgets everything recorded (a test's `restore` replays a snapshot from time 0).
  void reset();

  const std::vector<Signal>& signals() const { return signals_; }
  // Per signal, its changes in time order; the first is the initial value.
  const std::vector<std::vector<Change>>& changes() const { return changes_; }
  // Scan count per scan boundary (time, count), the `scan` marker.
  const std::vector<Change>& scans() const { return scans_; }
  std::int64_t end_us() const { return end_us_; }
  bool truncated() const { return truncated_; }
  std::size_t limit_bytes() const { return limit_; }

 private:
  std::vector<Signal> signals_;
  std::vector<std::vector<Change>> changes_;
  std::vector<Change> scans_;
  std::size_t limit_ = 0;
  std::size_t bytes_ = 0;  // VCD bytes the stored changes take
  std::int64_t end_us_ = 0;
  std::int64_t scan_count_ = 0;
  VirtualTime time_base_ = 0;
  bool started_ = false;
  bool truncated_ = false;
};

// The IEEE 1364 VCD text: `title` goes into the header comment, `module` names the scope.
std::string write_vcd(const TraceRecorder& trace, const std::string& title, const std::string& module,
                      const std::string& version);
// An SVG timing diagram of the same signals (one row per signal, the scan marker omitted).
std::string write_timing_svg(const TraceRecorder& trace, const std::string& title);

// A trace read back from a VCD file softslc wrote (`softslc plot`): the same signals and changes
// a TraceRecorder holds, without the scan marker.
struct TraceData {
  std::vector<Signal> signals;
  std::vector<std::vector<Change>> changes;
  std::int64_t end_us = 0;
};
// The timing diagram of a trace read back.
std::string write_timing_svg(const TraceData& trace, const std::string& title);
// Reads a VCD in the form write_vcd() writes (timescale 1us; wire 1, integer 16/32 and real 64
// variables in one scope; the `scan` marker is dropped); `only`, when not empty, keeps just the
// signals of those names, in that order. Returns an empty string or the first problem as
// "N: error: what" (N the line; the caller puts the file name in front). Bounded by the text: at most kMaxVcdSignals variables; the caller limits the
// file's size.
inline constexpr std::size_t kMaxVcdSignals = 10000;
std::string read_vcd(std::string_view text, const std::vector<std::string>& only, TraceData& out);

// Writes the trace to `path` atomically, as SVG when the name ends in .svg, else VCD. Returns an
// empty string or the reason it failed.
std::string save_trace(const TraceRecorder& trace, const std::string& path, const std::string& title,
                       const std::string& module, const std::string& version);

// Text for SVG/XML character data and attribute values: & < > " escaped.
std::string xml_escape(std::string_view s);

// Parses a size such as 1000000, 64k, 10M (bytes). Returns false for anything else or zero.
bool parse_size(const std::string& text, std::size_t& out);

}  // namespace softslc::trace
