// Channel 0 of a MicroLogix 1100 or 1400 configured as a Modbus RTU master, with the simulated Modbus RTU
// slaves wired to it (docs/semantics.md "The MicroLogix MSG over Modbus RTU", the bench's `modbus` node in
// docs/bench-format.md).
//
// Design. The MSG instruction's state is its MG element; the interpreter does the rung logic there and hands
// a message over when its rung starts one (Runtime::message_start) or its TO bit aborts it. The channel keeps
// what the processor keeps for it: the four message buffers and the queue behind them (1762-RM001C p. 21-2,
// as on the other channels), and the line, which carries one transaction at a time (a serial master waits for
// the reply before the next request). Everything that happens later happens in events on the runtime's queue,
// at the line's character times: a request of B bytes takes B x 11 bits / baud (an RTU character is 11 bits:
// start, 8 data, parity or a second stop bit, stop); the slave answers 3.5 character times after the
// request's last byte (the silence that ends an RTU frame) plus its reply delay; the reply takes its own bytes'
// time; the next request waits 3.5 character times after the last frame. The channel writes the MG element's
// bits and the read data through FieldProcessHost's word access, so repeated scans see each change (a process
// write) and stop at each event.
//
// The slaves are plain data tables (coils, inputs, holding registers, input registers) that tests set and
// read (`device NAME holding 0 1500`, `expect device NAME holding[0] == 1500`); a slave answers the eight
// commands a MicroLogix sends (01-06, 15, 16; 1763-RM001B p. 366) from its tables, with exception 02 (illegal
// data address) past a table's end and 01 (illegal function) for a command it is configured not to take.
//
// Controllers on the line (docs/semantics.md "A MicroLogix as a Modbus RTU slave"): a peer MicroLogix whose
// channel 0 is a Modbus RTU slave is reached through a ModbusPeerLine (the MSG network the peers are on). The
// request goes to it as its PDU when the request's end-of-frame silence has passed; the peer executes it at
// its next communications servicing, against its own data table, with the map of vm/modbus_slave.h, and
// hands the reply PDU back (peer_replied) when its reply starts on the line.
//
// Bounds: a message moves at most 103 elements (the instruction's size field), so frames are at most
// 9 + 2 x 103 bytes; the queue holds at most one message per MG element (a new start replaces it).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "vm/field_process.h"
#include "vm/message_network.h"

namespace softslc {


struct ModbusSlaveConfig {
  std::string name;
  int address = 1;  // 1-247
  std::vector<std::uint8_t> coils, inputs;            // 0 or 1 each; index = Modbus address - 1
  std::vector<std::uint16_t> holding, input_registers;
  Nanoseconds reply_delay = 2'000'000;  // 2 ms after the request's end-of-frame silence (decision)
  std::vector<int> functions;           // the commands it takes; empty: all eight
};

struct ModbusChannelConfig {
  std::int64_t baud = 19200;
  std::vector<ModbusSlaveConfig> slaves;
};

class ModbusMaster {
 public:
  explicit ModbusMaster(ModbusChannelConfig config);
  void attach(FieldProcessHost& host);

  // A Modbus MSG's rung started a message (m.modbus_function set).
  void start(const MessageInstruction& m);
  // The MSG's TO bit aborts the message of MG element `block`: ER, TO and 37h. False when the channel has no
  // message of that element.
  bool abort(std::uint32_t block);
  // Ends a message at once with EN, ER and `code` (a MSG that cannot use channel 0 as it is configured).
  static void refuse(FieldProcessHost& host, const MessageInstruction& m, std::uint8_t code);

  // The controllers on the line as Modbus RTU slaves (nullptr: none).
  void set_peer_line(ModbusPeerLine* line) { peer_line_ = line; }
  // A peer slave's reply PDU to the request of `serial` starts on the line at `at`: its last byte reaches
  // this channel the reply's character times later. Ignored when the message has ended meanwhile.
  void peer_replied(std::uint64_t serial, std::span<const std::uint8_t> pdu, VirtualTime at);
  // A simulated slave (a bench `modbus` node) at `address`.
  bool has_simulated_slave(int address) const;

  DeviceStatus inject(const DeviceFault& f);
  std::optional<std::vector<std::int64_t>> observe(std::string_view device, std::string_view what) const;
  std::vector<std::string> device_names() const;
  const ModbusChannelConfig& config() const { return config_; }
  // The end of character k of a transfer started at 0 (k x 11 bits / baud, no drift).
  Nanoseconds character_time(std::uint64_t k) const;

 private:
  struct Slave {
    ModbusSlaveConfig c;
    std::uint8_t exception = 0;  // injected: answers every request with this exception
    bool offline = false;        // injected: does not answer
    std::uint64_t requests = 0;
  };
  struct Message {
    std::uint64_t serial = 0;
    MessageInstruction in;
    int slave = 0;
    int address = 0;   // 0-based (MG word 13, "Modbus Target Data Address - 1")
    int bit = 0;       // the local data's starting bit (MG word 12) for the bit commands
    bool buffered = false;
    bool on_line = false;
    bool sent = false;  // the request's last byte has left (ST)
    std::vector<std::uint16_t> data;  // a write's data (one entry per element), taken when it enters a buffer
    std::optional<EventQueue::EventId> timer, line_event, second;
  };
  struct Reply {
    std::uint8_t exception = 0;
    std::vector<std::uint16_t> data;  // a read's elements
  };

  Message* find(std::uint64_t serial);
  void enter_buffers();
  void next_on_line(VirtualTime at);
  void request_sent(std::uint64_t serial, VirtualTime at);
  void reply_arrived(std::uint64_t serial, const Reply& r, VirtualTime at);
  void finish(std::uint64_t serial, std::uint8_t error, std::uint16_t extra_bits, VirtualTime at);
  void count_seconds(std::uint64_t serial, VirtualTime started, std::int64_t seconds);
  Reply serve(Slave& s, const Message& m, bool broadcast);
  // The request's PDU (function, address, quantity or value, a write's byte count and data).
  std::vector<std::uint8_t> request_pdu(const Message& m) const;
  std::uint16_t status(const MessageInstruction& in) const;
  void set_status(const MessageInstruction& in, std::uint16_t w0);
  std::uint16_t local_element(const Message& m, int i) const;
  void set_local_element(const Message& m, int i, std::uint16_t v);
  // CS0:4/MCP, "Outgoing Message Command Pending" (1762-RM001C p. 21-27): set while a message of the channel
  // has not been sent, written when it changes (docs/semantics.md "The CS file").
  void publish_command_pending();
  Slave* slave_named(std::string_view name);
  const Slave* slave_named(std::string_view name) const;

  ModbusChannelConfig config_;
  std::vector<Slave> slaves_;
  FieldProcessHost* host_ = nullptr;
  ModbusPeerLine* peer_line_ = nullptr;
  std::vector<Message> messages_;  // in the order they started: the first four are the buffers
  std::uint64_t next_serial_ = 1;
  bool line_busy_ = false;
  VirtualTime line_free_at_ = 0;  // the end of the last frame plus 3.5 character times
  bool command_pending_ = false;   // the MCP this channel last wrote
};

}  // namespace softslc
