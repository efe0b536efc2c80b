// Channel 0 of an SLC 5/03-5/05 (and MicroLogix) in User (ASCII) mode: the ASCII instruction queue,
// the receive buffer, the transmitter, the handshake lines and the device wired to the port.
//
// Design. The SLC runs its channel instructions (ABL ACB AHL ARD ARL AWA AWT) "outside of the
// program scan" through an ASCII queue of up to 16 instructions (1747-RM001G p. 10-5, 10-6): a
// false-to-true rung sets EN and queues the instruction (EU); the head of the queue runs (IN, the
// running bit) and finishes with DN or ER in the control element's word 0 and its count in POS
// (word 2); the next time the program scans the instruction it sets EM. The interpreter owns the
// rung side (EN, EM, queueing, retrying when the queue is full); AsciiChannel owns the rest and
// writes the control element, the string and nothing else, through FieldProcessHost's checked
// word access, from events on the runtime's queue. So a write's DN comes after its characters'
// transmission time in virtual time, and a read's after the line has arrived at the port's baud
// rate: every character takes (start bit + data bits + parity bit + stop bits) / baud, counted on
// the whole transfer (character k ends at start + k * bits * 1e9 / baud ns, no drift).
//
// The far end is a SerialDevice (a bench `serial` node, modules/serial/): the VM names no device
// type. The device hands the channel the characters it transmits; the channel delivers them to the
// receive buffer one character time apart, and delivers each character the processor transmits to
// the device when it has left the port. Handshake lines: the processor drives DTR and RTS (AHL);
// the device drives CTS, DSR and DCD.
//
// Bounds (never unbounded memory): 16 queued instructions (RM 10-5), a 1024-character receive
// buffer (ABL/ACB report 0-1024, RM 10-6/10-7; a character arriving at a full buffer is dropped
// and counted), and kMaxInFlight characters the device may have in flight towards the processor.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "instructions/instruction_table.h"
#include "vm/field_process.h"
#include "vm/module.h"

namespace softslc {

// The channel's User-mode configuration (RSLogix channel 0 configuration, RM 10-3 table 10.2).
struct SerialConfig {
  std::int64_t baud = 1200;
  int data_bits = 8;                 // 7 or 8 (RM table 10.2: default 8)
  char parity = 'N';                 // N, E or O
  int stop_bits = 1;                 // 1 or 2
  std::string termination = "\r";    // up to 2 characters (default CR)
  std::string append = "\r\n";       // up to 2 characters, AWA (default CR LF)
  // The line time of one character in bits: start + data + parity + stop.
  int bits_per_character() const { return 1 + data_bits + (parity == 'N' ? 0 : 1) + stop_bits; }
};

class SerialDevice;

// What a device sees of the port it is wired to.
class SerialLine {
 public:
  virtual ~SerialLine() = default;
  virtual VirtualTime now() const = 0;
  virtual EventQueue::EventId schedule_at(VirtualTime at, EventQueue::Callback cb) = 0;
  virtual const SerialConfig& config() const = 0;
  // The device starts transmitting `chars` now (after what it already has in flight). False, and
  // nothing sent, when they would take its in-flight characters past kMaxInFlight.
  virtual bool transmit(std::string_view chars) = 0;
  // The lines the device drives (RS-232 from the device's side): CTS, DSR, DCD into the processor.
  virtual void set_inputs(bool cts, bool dsr, bool dcd) = 0;
};

// A simulated device on channel 0 (modules/serial/ for the bench's `serial` node).
class SerialDevice {
 public:
  virtual ~SerialDevice() = default;
  virtual std::string name() const = 0;
  virtual void attach(SerialLine& line) = 0;
  // A character the processor sent has arrived completely.
  virtual void receive(std::uint8_t c) = 0;
  // The processor changed DTR or RTS.
  virtual void outputs_changed(bool /*dtr*/, bool /*rts*/) {}
  virtual DeviceStatus inject(const DeviceFault& /*fault*/) { return {}; }
  virtual std::optional<std::vector<std::int64_t>> observe(std::string_view /*what*/) const { return std::nullopt; }
};

// Error codes in the control element's low byte. The SLC table (RM p. 10-24) could not be
// reached; these follow the codes the MicroLogix manuals give for the same instruction set
// (0Eh: removed by ACL, 1762-RM001C p. 20-8, 1766-RM001A p. 369) and the Logix serial-port table
// that shares them (1756-RM003N p. 577): docs/semantics.md "ASCII and strings" marks them.
namespace ascii_error {
inline constexpr std::uint8_t kSystemMode = 0x04;   // channel not in User mode (no device configured)
inline constexpr std::uint8_t kUnloaded = 0x0A;     // UL was set when the instruction came to run
inline constexpr std::uint8_t kModeChange = 0x0C;   // the processor left Run: the queue is flushed
inline constexpr std::uint8_t kCleared = 0x0E;      // removed from the queue by ACL
inline constexpr std::uint8_t kLength = 0x12;       // the string's length word is outside 0-82 (softslc's choice)
}  // namespace ascii_error

// What the interpreter asks of the channel (implemented by AsciiChannel; tests may fake it).
class AsciiPort {
 public:
  virtual ~AsciiPort() = default;
  struct Request {
    Opcode op = Opcode::ABL;
    std::uint32_t control = 0;  // data-table index of the R element's word 0
    std::uint32_t string = 0;   // data-table index of the ST element's word 0 (ARD ARL AWA AWT)
    std::uint16_t and_mask = 0, or_mask = 0;  // AHL
    VirtualTime at = 0;         // the instruction's virtual time in the scan
  };
  // Queues a channel instruction (EU set); runs it at once when the queue is empty. False when the
  // queue already holds 16 instructions: the interpreter tries again on the next scan.
  virtual bool submit(const Request& r) = 0;
  // ACL: empties the buffers at once and removes the matching queued instructions (1762-RM001C p. 20-8).
  virtual void clear(bool transmit, bool receive, VirtualTime at) = 0;
};

class AsciiChannel final : public AsciiPort {
 public:
  static constexpr std::size_t kQueueSize = 16;
  static constexpr std::size_t kReceiveBuffer = 1024;
  static constexpr std::size_t kMaxInFlight = 1024;

  AsciiChannel(SerialConfig config, std::unique_ptr<SerialDevice> device);
  ~AsciiChannel() override;
  // Wires the channel to the runtime's clock, events and data table, then the device to the line.
  void attach(FieldProcessHost& host);

  bool submit(const Request& r) override;
  void clear(bool transmit, bool receive, VirtualTime at) override;
  // Leaving Run or Test: every queued instruction ends with ER (code 0Ch) and the queue empties.
  void on_mode_change(Mode from, Mode to);

  SerialDevice& device() { return *device_; }
  const SerialDevice& device() const { return *device_; }
  const SerialConfig& config() const { return config_; }
  std::size_t buffered() const { return rx_.size(); }
  std::uint64_t dropped() const { return dropped_; }

 private:
  class Line;
  struct Job {
    Request r;
    std::vector<std::uint8_t> out;  // AWA/AWT: the characters to send
    std::size_t sent = 0;
  };
  Nanoseconds character_time(std::uint64_t k) const;  // end of character k of a transfer from 0
  void run_head(VirtualTime at);
  bool finish_read(Job& j, VirtualTime at);     // ARD/ARL: true when done
  std::size_t line_length(std::size_t limit) const;
  void send_next(VirtualTime at);
  void complete(std::uint32_t control, std::uint16_t set_bits, std::uint8_t code, std::int64_t pos);
  void fail(const Request& r, std::uint8_t code);
  std::uint16_t word(std::uint32_t i) const;
  void set_word(std::uint32_t i, std::uint16_t v);
  std::uint16_t channel_status() const;
  void device_chars(std::string_view chars);
  void deliver_next(VirtualTime at);

  SerialConfig config_;
  std::unique_ptr<SerialDevice> device_;
  std::unique_ptr<Line> line_;
  FieldProcessHost* host_ = nullptr;
  std::deque<Job> queue_;
  bool head_running_ = false;
  VirtualTime tx_start_ = 0;                     // the running write's first character start
  std::optional<EventQueue::EventId> tx_event_;  // the running write's next character
  std::deque<std::uint8_t> rx_;                  // the receive buffer
  std::deque<std::uint8_t> in_flight_;           // device -> processor, not yet arrived
  VirtualTime rx_start_ = 0;
  std::uint64_t rx_index_ = 0;
  std::optional<EventQueue::EventId> rx_event_;
  std::uint64_t dropped_ = 0;
  bool dtr_ = true, rts_ = true, cts_ = true, dsr_ = true, dcd_ = true;
};

}  // namespace softslc
