// The bench `modbus` node: a Modbus RTU slave on channel 0 of a MicroLogix 1100 or 1400, which the node makes a
// Modbus RTU master (vm/modbus_master.h; docs/bench-format.md "Modbus RTU slaves: `modbus`").
//
//   modbus NAME slave=N [baud=B] [coils=N] [inputs=N] [holding=N] [input_registers=N]
//          [functions=1,3,...] [reply_delay=T]
//
// Every `modbus` node is one slave on the same line; the line's baud rate is the channel's, so the nodes that
// give one must agree. The tables start at 0 (sizes 0: a request reaching one is exception 02).
#pragma once

#include <optional>
#include <vector>

#include "modules/bench/bench.h"
#include "parser/diagnostics.h"
#include "vm/modbus_master.h"

namespace softslc {

// Reads the `modbus` nodes of a bench into one channel; errors are positioned in the bench file. nullopt when the
// bench has none or after an error.
std::optional<ModbusChannelConfig> read_modbus_nodes(const std::vector<const BenchNode*>& nodes, DiagnosticList& diags);

}  // namespace softslc
