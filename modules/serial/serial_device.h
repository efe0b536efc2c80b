// The bench `serial` node: channel 0 of the processor in User (ASCII) mode, and a line-oriented
// device (a scale, a barcode reader, a terminal) wired to it.
//
// Design. One node configures both ends of the cable, as the two must agree: the channel's baud
// rate, data bits, parity and stop bits, its termination characters (ARL, ABL) and append
// characters (AWA), and the device's own end of line. The device is a SerialDevice behind the
// small interface of vm/ascii_channel.h; the VM never names it. It
//   - transmits a line (`device NAME send TEXT` from a test, or its answer) at the baud rate,
//   - collects what the processor transmits into lines (ended by CR or LF; CR LF is one end),
//   - optionally answers every line it receives (or only the lines equal to `request`) with
//     `answer` after `answer_delay`.
// Observations: `lines` (lines received), `last line` (its character codes), `last number` (the
// first signed decimal number in the last line), `sent` (lines the device transmitted), `dtr`,
// `rts`, and the channel's `buffered` and `dropped` counts (docs/bench-format.md, "Serial
// devices"). Bounds: a line the device collects holds at most 256 characters (the rest of an
// over-long line is counted, not kept); it keeps its last 64 lines; a `send` is refused when the
// channel's in-flight limit would be passed.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "modules/bench/bench.h"
#include "parser/diagnostics.h"
#include "vm/ascii_channel.h"

namespace softslc {

struct SerialDeviceConfig {
  std::string name;
  SerialConfig channel;
  std::string eol = "\r\n";      // what the device ends the lines it sends with
  std::string answer;            // sent back after each line received (empty: none)
  std::string request;           // when set, only a line equal to it is answered
  Nanoseconds answer_delay = 0;
};

// Reads one `serial` node; errors are positioned in the bench file. nullopt after an error.
std::optional<SerialDeviceConfig> read_serial_node(const BenchNode& node, DiagnosticList& diags);

// Channel 0 in User mode with the configured device wired to it.
std::unique_ptr<AsciiChannel> make_serial_channel(const SerialDeviceConfig& config);

// "CR", "LF", "CRLF", "\0D\0A", printable characters: at most 2 characters. nullopt when the
// spelling is not one of those.
std::optional<std::string> parse_serial_characters(std::string_view spelling);

}  // namespace softslc
