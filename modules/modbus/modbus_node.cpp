#include "modules/modbus/modbus_node.h"

#include <string>

namespace softslc {

namespace {
// The most elements a slave's table has (decision: 65536 is the whole Modbus address space; 4096 keeps a bench
// small and is the MicroLogix's own coil space as a slave, AG-UM008C p. 3-52).
constexpr std::int64_t kMaxTable = 4096;
}  // namespace

std::optional<ModbusChannelConfig> read_modbus_nodes(const std::vector<const BenchNode*>& nodes, DiagnosticList& diags) {
  if (nodes.empty()) return std::nullopt;
  ModbusChannelConfig channel;
  const BenchNode* baud_from = nullptr;
  bool failed = false;
  for (const BenchNode* n : nodes) {
    BenchReader r(*n, diags);
    ModbusSlaveConfig c;
    c.name = n->name;
    if (n->name.empty()) r.error("a Modbus slave needs a name (tests reach it by name): modbus NAME slave=N");
    if (!n->children.empty()) r.error("a Modbus slave has no child nodes");
    r.require("slave", "its slave address, 1-247");
    if (auto a = r.integer("slave", 1, modbus::kMaxSlave)) c.address = static_cast<int>(*a);
    if (auto b = r.choice("baud", {"1200", "2400", "4800", "9600", "19200", "38400"})) {
      const std::int64_t baud = std::stoll(*b);
      if (baud_from && baud != channel.baud)
        r.error_at("baud", "baud=" + *b + ": the slaves share channel 0's line, which " + baud_from->label() +
                               " at line " + std::to_string(baud_from->pos.line) + " set to " + std::to_string(channel.baud));
      channel.baud = baud;
      if (!baud_from) baud_from = n;
    }
    if (auto k = r.integer("coils", 0, kMaxTable)) c.coils.assign(static_cast<std::size_t>(*k), 0);
    if (auto k = r.integer("inputs", 0, kMaxTable)) c.inputs.assign(static_cast<std::size_t>(*k), 0);
    if (auto k = r.integer("holding", 0, kMaxTable)) c.holding.assign(static_cast<std::size_t>(*k), 0);
    if (auto k = r.integer("input_registers", 0, kMaxTable)) c.input_registers.assign(static_cast<std::size_t>(*k), 0);
    if (auto fs = r.integers("functions", 1, 16)) {
      for (std::int64_t f : *fs) {
        if (!modbus::is_command(static_cast<int>(f)))
          r.error_at("functions", "functions: " + std::to_string(f) + " is not one of the eight commands a MicroLogix "
                                  "sends (1, 2, 3, 4, 5, 6, 15, 16; 1763-RM001B p. 366)");
        c.functions.push_back(static_cast<int>(f));
      }
    }
    if (auto d = r.duration("reply_delay")) {
      if (*d < 0 || *d > 10 * kNsPerS)
        r.error_at("reply_delay", "reply_delay must be 0 to 10s");
      else
        c.reply_delay = *d;
    }
    for (const ModbusSlaveConfig& other : channel.slaves)
      if (other.address == c.address)
        r.error_at("slave", "slave address " + std::to_string(c.address) + " is also " + other.name + "'s: each slave on "
                            "a Modbus line has its own address");
    r.finish();
    failed = failed || r.failed();
    channel.slaves.push_back(std::move(c));
  }
  if (failed) return std::nullopt;
  return channel;
}

}  // namespace softslc
