#include "vm/modbus_master.h"

#include <algorithm>

#include "parser/address.h"
#include "vm/data_table.h"
#include "vm/modbus_slave.h"

namespace softslc {

namespace {
// The Modbus application protocol's exception codes the simulated slaves answer.
constexpr std::uint8_t kIllegalFunction = modbus::kIllegalFunction;
constexpr std::uint8_t kIllegalDataAddress = modbus::kIllegalDataAddress;

void put16(std::vector<std::uint8_t>& out, std::uint32_t v) {
  out.push_back(static_cast<std::uint8_t>((v >> 8) & 0xFF));
  out.push_back(static_cast<std::uint8_t>(v & 0xFF));
}

std::optional<std::int64_t> whole_number(const std::string& text) {
  if (text.empty() || text.size() > 9 || text.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
  return std::stoll(text);
}

}  // namespace

ModbusMaster::ModbusMaster(ModbusChannelConfig config) : config_(std::move(config)) {
  for (const ModbusSlaveConfig& c : config_.slaves) slaves_.push_back(Slave{c});
}

void ModbusMaster::attach(FieldProcessHost& host) { host_ = &host; }

Nanoseconds ModbusMaster::character_time(std::uint64_t k) const {
  return static_cast<Nanoseconds>(k * modbus::kBitsPerCharacter * 1'000'000'000ULL / static_cast<std::uint64_t>(config_.baud));
}

std::uint16_t ModbusMaster::status(const MessageInstruction& in) const {
  return msg::mg_status_word(in.block, [this](std::uint32_t i) { return host_->read_word(i); });
}
void ModbusMaster::set_status(const MessageInstruction& in, std::uint16_t w0) {
  msg::set_mg_status_word(
      in.block, w0, [this](std::uint32_t i) { return host_->read_word(i); },
      [this](std::uint32_t i, std::uint16_t v) { host_->write_word(i, v); });
}

void ModbusMaster::refuse(FieldProcessHost& host, const MessageInstruction& m, std::uint8_t code) {
  auto read = [&host](std::uint32_t i) { return host.read_word(i); };
  std::uint16_t w0 = msg::mg_status_word(m.block, read);
  w0 = static_cast<std::uint16_t>(w0 & ~(msg::kST | msg::kDN | msg::kER | msg::kEW | msg::kTO | msg::kErrorCode));
  msg::set_mg_status_word(m.block, static_cast<std::uint16_t>(w0 | msg::kEN | msg::kER | code), read,
                          [&host](std::uint32_t i, std::uint16_t v) { host.write_word(i, v); });
}

// Element i of the local data: bit (start bit + i) of the words from the data address for the bit commands
// (the data table address is a bit address, 1747-RM001G p. 12-18), word i for the register commands.
std::uint16_t ModbusMaster::local_element(const Message& m, int i) const {
  if (!modbus::is_bit_command(m.in.modbus_function)) return host_->read_word(m.in.data + static_cast<std::uint32_t>(i));
  const int b = m.bit + i;
  return static_cast<std::uint16_t>((host_->read_word(m.in.data + static_cast<std::uint32_t>(b / 16)) >> (b % 16)) & 1u);
}

void ModbusMaster::set_local_element(const Message& m, int i, std::uint16_t v) {
  if (!modbus::is_bit_command(m.in.modbus_function))
    return host_->write_word(m.in.data + static_cast<std::uint32_t>(i), v);
  const int b = m.bit + i;
  const std::uint32_t w = m.in.data + static_cast<std::uint32_t>(b / 16);
  const auto mask = static_cast<std::uint16_t>(1u << (b % 16));
  host_->write_word(w, static_cast<std::uint16_t>(v ? host_->read_word(w) | mask : host_->read_word(w) & ~mask));
}

void ModbusMaster::start(const MessageInstruction& in) {
  // A message of this MG element still in the channel is replaced (the program cleared EN before DN or ER).
  for (Message& old : messages_)
    if (old.in.block == in.block) {
      if (old.timer) host_->cancel_event(*old.timer);
      if (old.line_event) host_->cancel_event(*old.line_event);
      if (old.second) host_->cancel_event(*old.second);
      if (old.on_line) {
        line_busy_ = false;
        line_free_at_ = std::max(line_free_at_, in.at + character_time(7) / 2);
      }
    }
  std::erase_if(messages_, [&](const Message& m) { return m.in.block == in.block; });

  // The false-to-true transition clears DN, ER, ST, EW, TO and the error code (1762-RM001C p. 21-15).
  std::uint16_t w0 = status(in);
  w0 = static_cast<std::uint16_t>(w0 & ~(msg::kEN | msg::kST | msg::kDN | msg::kER | msg::kEW | msg::kTO | msg::kErrorCode));

  // The MG element's setup as the processor reads it when the message starts: NOD the slave address, word 12
  // the local starting bit, word 13 (TFN) the Modbus data address - 1 (1763-RM001B p. 350), MTO in seconds.
  Message m;
  m.serial = next_serial_++;
  m.in = in;
  m.slave = host_->read_word(in.block + mg::kNode) & 0xFF;
  m.address = host_->read_word(in.block + mg::kTargetFile);
  m.bit = host_->read_word(in.block + mg::kTargetFileType) & 0x0F;
  const int f = in.modbus_function, n = in.elements;
  const DataTableLayout& layout = host_->layout();
  const int file = layout.file_containing(in.data);
  std::uint8_t error = 0;
  if (file < 0) {
    error = msg::kBadParameters;
  } else {
    const FileLayout& fl = layout.files[static_cast<std::size_t>(file)];
    const int words = modbus::is_bit_command(f) ? (m.bit + n + 15) / 16 : n;
    if ((fl.type != FileType::Bit && fl.type != FileType::Integer) || n < 1 || n > kMessageMaxWords ||
        (modbus::is_single_command(f) && n != 1) || m.address + n > 65536 ||
        in.data + static_cast<std::uint32_t>(words) > fl.end())
      error = msg::kBadParameters;
    else if (m.slave > modbus::kMaxSlave)
      error = msg::kNodeTooHigh;
    else if (m.slave == 0 && !modbus::is_write_command(f))
      error = msg::kBroadcast;  // "broadcast not supported" (1766-RM001A p. 466): a read has no broadcast
  }
  if (error) {
    set_status(in, static_cast<std::uint16_t>(w0 | msg::kEN | msg::kER | error));
    publish_command_pending();  // a message of this element it replaced may have been the one pending
    return;
  }
  set_status(in, static_cast<std::uint16_t>(w0 | msg::kEN));
  // MTO, whole seconds from the rung's false-to-true transition, 0 = never (1762-RM001C p. 21-12): ER, TO, 37h.
  if (const int seconds = host_->read_word(in.block + mg::kTimeout) & 0xFF; seconds > 0) {
    const std::uint64_t serial = m.serial;
    m.timer = host_->schedule_at(std::max(in.at + seconds * kNsPerS, host_->now()), [this, serial, seconds](VirtualTime t) {
      if (Message* x = find(serial)) {
        x->timer.reset();
        // Word 19 shows the whole timeout, as the DH-485 channel's end-of-scan count does when it expires.
        host_->write_word(x->in.block + mg::kElapsed, static_cast<std::uint16_t>(seconds));
        finish(serial, msg::kTimedOut, msg::kTO, t);
      }
    });
  }
  const std::uint64_t serial = m.serial;
  messages_.push_back(std::move(m));
  count_seconds(serial, in.at, 0);
  enter_buffers();
  next_on_line(in.at);
  publish_command_pending();
}

void ModbusMaster::publish_command_pending() {
  const std::optional<std::uint32_t> at = host_->layout().communications_status_word(0);
  if (!at) return;
  const bool pending = std::any_of(messages_.begin(), messages_.end(), [](const Message& m) { return !m.sent; });
  if (pending == command_pending_) return;
  command_pending_ = pending;
  const std::uint16_t w = host_->read_word(*at);
  host_->write_word(*at, static_cast<std::uint16_t>(pending ? w | cs::kCommandPending : w & ~cs::kCommandPending));
}

// MG word 19, "time since message started" in seconds (1762-RM001C p. 21-4): 0 when the message starts,
// one more at each whole second while it is in the channel, and left as it was when it ends. The DH-485
// channel counts at each end of scan (vm/message_network.cpp); here the count is an event at each second,
// so the scans after it see the same value without the channel acting at every scan.
void ModbusMaster::count_seconds(std::uint64_t serial, VirtualTime started, std::int64_t seconds) {
  Message* m = find(serial);
  if (!m) return;
  host_->write_word(m->in.block + mg::kElapsed, static_cast<std::uint16_t>(std::min<std::int64_t>(seconds, 32767)));
  m->second = host_->schedule_at(started + (seconds + 1) * kNsPerS, [this, serial, started, seconds](VirtualTime) {
    if (Message* x = find(serial)) x->second.reset();
    count_seconds(serial, started, seconds + 1);
  });
}

ModbusMaster::Message* ModbusMaster::find(std::uint64_t serial) {
  for (Message& m : messages_)
    if (m.serial == serial) return &m;
  return nullptr;
}

// The first four messages are in the buffers: EW ("the message is in the buffer ... and waiting to be sent",
// 1762-RM001C p. 21-15), and a write's data is taken now; the others wait in the queue with EN only.
void ModbusMaster::enter_buffers() {
  for (std::size_t i = 0; i < messages_.size() && i < static_cast<std::size_t>(msg::kBuffersPerChannel); ++i) {
    Message& m = messages_[i];
    if (m.buffered) continue;
    m.buffered = true;
    set_status(m.in, static_cast<std::uint16_t>(status(m.in) | msg::kEW));
    if (modbus::is_write_command(m.in.modbus_function))
      for (int k = 0; k < m.in.elements; ++k) m.data.push_back(local_element(m, k));
  }
}

// The line carries one transaction at a time, the buffered messages in the order they started.
void ModbusMaster::next_on_line(VirtualTime at) {
  if (line_busy_) return;
  auto it = std::find_if(messages_.begin(), messages_.end(), [](const Message& m) { return m.buffered && !m.on_line; });
  if (it == messages_.end()) return;
  line_busy_ = true;
  it->on_line = true;
  const VirtualTime begin = std::max({at, line_free_at_, host_->now()});
  const auto bytes = static_cast<std::uint64_t>(modbus::request_bytes(it->in.modbus_function, it->in.elements));
  const std::uint64_t serial = it->serial;
  it->line_event = host_->schedule_at(begin + character_time(bytes), [this, serial](VirtualTime t) { request_sent(serial, t); });
}

// The request's last byte has left: ST, as on a link without ACK ("on DF1 radio modem and Modbus RTU master
// ... ST is set when the message has been sent", 1763-RM001B p. 355), and EW cleared. The slave it names acts
// on it now; a broadcast write is done (no slave replies to one).
void ModbusMaster::request_sent(std::uint64_t serial, VirtualTime at) {
  Message* m = find(serial);
  if (!m) return;
  m->line_event.reset();
  m->sent = true;
  publish_command_pending();
  set_status(m->in, static_cast<std::uint16_t>((status(m->in) | msg::kST) & ~msg::kEW));
  const Nanoseconds silence = character_time(7) / 2;  // 3.5 characters end an RTU frame
  if (m->slave == 0) {
    for (Slave& s : slaves_) serve(s, *m, true);
    if (peer_line_) peer_line_->deliver(0, serial, request_pdu(*m), config_.baud, at + silence);
    line_busy_ = false;
    line_free_at_ = at + silence;
    finish(serial, 0, 0, at);
    return;
  }
  Slave* target = nullptr;
  for (Slave& s : slaves_)
    if (s.c.address == m->slave && !s.offline) target = &s;
  // Every controller on the line hears the frame (and counts it); the one at its address takes it at its next
  // communications servicing and answers through peer_replied.
  if (peer_line_) peer_line_->deliver(m->slave, serial, request_pdu(*m), config_.baud, at + silence);
  // Until a reply comes the line waits for it, until the message times out or TO aborts it.
  if (!target) return;
  Reply r = serve(*target, *m, false);
  const int bytes = r.exception ? modbus::kExceptionReplyBytes : modbus::reply_bytes(m->in.modbus_function, m->in.elements);
  const VirtualTime arrival = at + silence + target->c.reply_delay + character_time(static_cast<std::uint64_t>(bytes));
  m->line_event = host_->schedule_at(arrival, [this, serial, r = std::move(r)](VirtualTime t) { reply_arrived(serial, r, t); });
}

std::vector<std::uint8_t> ModbusMaster::request_pdu(const Message& m) const {
  const int f = m.in.modbus_function, n = m.in.elements;
  std::vector<std::uint8_t> pdu{static_cast<std::uint8_t>(f)};
  put16(pdu, static_cast<std::uint32_t>(m.address));
  switch (f) {
    case 5: put16(pdu, m.data.at(0) ? 0xFF00u : 0u); break;
    case 6: put16(pdu, m.data.at(0)); break;
    case 15: {
      put16(pdu, static_cast<std::uint32_t>(n));
      pdu.push_back(static_cast<std::uint8_t>((n + 7) / 8));
      const std::size_t at = pdu.size();
      pdu.resize(at + static_cast<std::size_t>((n + 7) / 8), 0);
      for (int i = 0; i < n; ++i)
        if (m.data.at(static_cast<std::size_t>(i))) pdu[at + static_cast<std::size_t>(i / 8)] |= static_cast<std::uint8_t>(1u << (i % 8));
      break;
    }
    case 16:
      put16(pdu, static_cast<std::uint32_t>(n));
      pdu.push_back(static_cast<std::uint8_t>(2 * n));
      for (int i = 0; i < n; ++i) put16(pdu, m.data.at(static_cast<std::size_t>(i)));
      break;
    default: put16(pdu, static_cast<std::uint32_t>(n)); break;  // the reads: the quantity
  }
  return pdu;
}

// The reply's frame is the slave's address, the PDU and the CRC; its last byte arrives its character times
// after it starts. An exception reply is function | 80h and the code; a read's reply its byte count and data
// (bits from bit 0 of its first byte, registers high byte first); a write's reply echoes the request.
void ModbusMaster::peer_replied(std::uint64_t serial, std::span<const std::uint8_t> pdu, VirtualTime at) {
  Message* m = find(serial);
  if (!m || !m->on_line || m->line_event || pdu.empty()) return;
  const int f = m->in.modbus_function, n = m->in.elements;
  Reply r;
  if (pdu[0] & 0x80) {
    if (pdu.size() != 2) return;
    r.exception = pdu[1];
  } else if (f == 1 || f == 2) {
    if (pdu.size() != 2 + static_cast<std::size_t>((n + 7) / 8)) return;
    for (int i = 0; i < n; ++i) r.data.push_back((pdu[2 + static_cast<std::size_t>(i / 8)] >> (i % 8)) & 1u);
  } else if (f == 3 || f == 4) {
    if (pdu.size() != 2 + 2 * static_cast<std::size_t>(n)) return;
    for (int i = 0; i < n; ++i)
      r.data.push_back(static_cast<std::uint16_t>(pdu[2 + 2 * static_cast<std::size_t>(i)] << 8 | pdu[3 + 2 * static_cast<std::size_t>(i)]));
  }
  const auto bytes = static_cast<std::uint64_t>(1 + pdu.size() + 2);
  m->line_event = host_->schedule_at(at + character_time(bytes), [this, serial, r = std::move(r)](VirtualTime t) { reply_arrived(serial, r, t); });
}

bool ModbusMaster::has_simulated_slave(int address) const {
  for (const Slave& s : slaves_)
    if (s.c.address == address) return true;
  return false;
}

void ModbusMaster::reply_arrived(std::uint64_t serial, const Reply& r, VirtualTime at) {
  Message* m = find(serial);
  if (!m) return;
  m->line_event.reset();
  line_busy_ = false;
  line_free_at_ = at + character_time(7) / 2;
  if (r.exception) return finish(serial, static_cast<std::uint8_t>(modbus::kExceptionErrorBase + r.exception), 0, at);
  for (std::size_t i = 0; i < r.data.size(); ++i) set_local_element(*m, static_cast<int>(i), r.data[i]);
  finish(serial, 0, 0, at);
}

// DN, or ER with the code (and TO); ST and EW cleared; EN stays until the rung is false (the interpreter).
void ModbusMaster::finish(std::uint64_t serial, std::uint8_t error, std::uint16_t extra_bits, VirtualTime at) {
  Message* m = find(serial);
  if (!m) return;
  if (m->timer) host_->cancel_event(*m->timer);
  if (m->line_event) host_->cancel_event(*m->line_event);
  if (m->second) host_->cancel_event(*m->second);
  if (m->on_line && line_busy_ && error) {
    // The message on the line ended without its reply: the line is free after the end-of-frame silence.
    line_busy_ = false;
    line_free_at_ = std::max(line_free_at_, at + character_time(7) / 2);
  }
  std::uint16_t w0 = status(m->in);
  w0 = static_cast<std::uint16_t>(w0 & ~(msg::kST | msg::kEW | msg::kErrorCode));
  w0 = error ? static_cast<std::uint16_t>(w0 | msg::kER | error | extra_bits) : static_cast<std::uint16_t>(w0 | msg::kDN);
  set_status(m->in, w0);
  std::erase_if(messages_, [&](const Message& x) { return x.serial == serial; });
  enter_buffers();
  next_on_line(at);
  publish_command_pending();
}

bool ModbusMaster::abort(std::uint32_t block) {
  for (const Message& m : messages_)
    if (m.in.block == block) {
      finish(m.serial, msg::kTimedOut, msg::kTO, host_->now());
      return true;
    }
  return false;
}

// The slave's side of a transaction (Modbus application protocol): a command it does not take is exception
// 01; an address range past its table's end, exception 02. Writes change its tables; reads copy them.
ModbusMaster::Reply ModbusMaster::serve(Slave& s, const Message& m, bool broadcast) {
  Reply r;
  if (s.offline) return r;
  ++s.requests;
  const int f = m.in.modbus_function, n = m.in.elements;
  if (s.exception) {
    r.exception = s.exception;
    return r;
  }
  if (!s.c.functions.empty() && std::find(s.c.functions.begin(), s.c.functions.end(), f) == s.c.functions.end()) {
    r.exception = kIllegalFunction;
    return r;
  }
  const std::size_t first = static_cast<std::size_t>(m.address), end = first + static_cast<std::size_t>(n);
  auto in_range = [&](std::size_t size) { return end <= size; };
  switch (f) {
    case 1:
    case 2: {
      const auto& table = f == 1 ? s.c.coils : s.c.inputs;
      if (!in_range(table.size())) break;
      for (std::size_t i = first; i < end; ++i) r.data.push_back(table[i]);
      return r;
    }
    case 3:
    case 4: {
      const auto& table = f == 3 ? s.c.holding : s.c.input_registers;
      if (!in_range(table.size())) break;
      r.data.assign(table.begin() + static_cast<std::ptrdiff_t>(first), table.begin() + static_cast<std::ptrdiff_t>(end));
      return r;
    }
    case 5:
    case 15:
      if (!in_range(s.c.coils.size())) break;
      for (std::size_t i = 0; i < m.data.size(); ++i) s.c.coils[first + i] = m.data[i] ? 1 : 0;
      return r;
    case 6:
    case 16:
      if (!in_range(s.c.holding.size())) break;
      for (std::size_t i = 0; i < m.data.size(); ++i) s.c.holding[first + i] = m.data[i];
      return r;
    default: break;
  }
  // A broadcast is never answered, its exceptions neither (Modbus application protocol).
  r.exception = broadcast ? 0 : kIllegalDataAddress;
  return r;
}

ModbusMaster::Slave* ModbusMaster::slave_named(std::string_view name) {
  for (Slave& s : slaves_)
    if (s.c.name == name) return &s;
  return nullptr;
}
const ModbusMaster::Slave* ModbusMaster::slave_named(std::string_view name) const {
  for (const Slave& s : slaves_)
    if (s.c.name == name) return &s;
  return nullptr;
}

std::vector<std::string> ModbusMaster::device_names() const {
  std::vector<std::string> out;
  for (const Slave& s : slaves_) out.push_back(s.c.name);
  return out;
}

// `device NAME holding|input_registers|coils|inputs FIRST V...` sets the table from index FIRST (the Modbus
// address - 1); `exception N` answers every request with exception N (1-255), `offline` answers none, `normal`
// withdraws both.
DeviceStatus ModbusMaster::inject(const DeviceFault& f) {
  Slave* s = slave_named(f.device);
  if (!s) return {};
  if (f.fault == "normal" || f.fault == "online") {
    s->exception = 0;
    s->offline = false;
    return DeviceStatus::done();
  }
  if (f.fault == "offline") {
    s->offline = true;
    return DeviceStatus::done();
  }
  if (f.fault == "exception") {
    const auto code = f.args.size() == 1 ? whole_number(f.args[0]) : std::nullopt;
    if (!code || *code < 1 || *code > 255) return DeviceStatus::refused("exception takes one exception code, 1-255");
    s->exception = static_cast<std::uint8_t>(*code);
    return DeviceStatus::done();
  }
  const bool bits = f.fault == "coils" || f.fault == "inputs";
  if (!bits && f.fault != "holding" && f.fault != "input_registers")
    return DeviceStatus::refused("a Modbus slave takes 'holding|input_registers|coils|inputs FIRST VALUE...', "
                                 "'exception N', 'offline' or 'normal', not '" + f.fault + "'");
  const std::size_t size = f.fault == "coils" ? s->c.coils.size() : f.fault == "inputs" ? s->c.inputs.size()
                           : f.fault == "holding" ? s->c.holding.size() : s->c.input_registers.size();
  const auto first = f.args.empty() ? std::nullopt : whole_number(f.args[0]);
  if (!first || f.args.size() < 2)
    return DeviceStatus::refused(f.fault + " takes the first index (Modbus address - 1) and one or more values");
  if (static_cast<std::size_t>(*first) + f.args.size() - 1 > size)
    return DeviceStatus::refused(f.fault + " has " + std::to_string(size) + " elements (indexes 0-" +
                                 std::to_string(static_cast<std::int64_t>(size) - 1) + ")");
  std::vector<std::int64_t> values;
  for (std::size_t i = 1; i < f.args.size(); ++i) {
    const std::string& t = f.args[i];
    const bool negative = !t.empty() && t[0] == '-';
    auto v = whole_number(negative ? t.substr(1) : t);
    if (!v || (bits && (negative || *v > 1)) || (!bits && (negative ? *v > 32768 : *v > 65535)))
      return DeviceStatus::refused(f.fault + ": '" + t + "' is not " + (bits ? "0 or 1" : "a 16-bit value"));
    values.push_back(negative ? -*v : *v);
  }
  for (std::size_t i = 0; i < values.size(); ++i) {
    const std::size_t k = static_cast<std::size_t>(*first) + i;
    if (f.fault == "coils") s->c.coils[k] = static_cast<std::uint8_t>(values[i]);
    else if (f.fault == "inputs") s->c.inputs[k] = static_cast<std::uint8_t>(values[i]);
    else if (f.fault == "holding") s->c.holding[k] = static_cast<std::uint16_t>(values[i]);
    else s->c.input_registers[k] = static_cast<std::uint16_t>(values[i]);
  }
  return DeviceStatus::done();
}

// Observations: the four tables (element k is Modbus address k + 1; registers as signed 16-bit words, as the
// data table shows them) and `requests`, the requests it has received (broadcasts too).
std::optional<std::vector<std::int64_t>> ModbusMaster::observe(std::string_view device, std::string_view what) const {
  const Slave* s = slave_named(device);
  if (!s) return std::nullopt;
  std::vector<std::int64_t> out;
  if (what == "coils" || what == "inputs") {
    for (std::uint8_t b : what == "coils" ? s->c.coils : s->c.inputs) out.push_back(b);
    return out;
  }
  if (what == "holding" || what == "input_registers" || what == "input registers") {
    for (std::uint16_t w : what == "holding" ? s->c.holding : s->c.input_registers) out.push_back(static_cast<std::int16_t>(w));
    return out;
  }
  if (what == "requests") return std::vector<std::int64_t>{static_cast<std::int64_t>(s->requests)};
  return std::nullopt;
}

}  // namespace softslc
