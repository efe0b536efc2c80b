#include "vm/message_network.h"

#include <algorithm>
#include <limits>

#include "vm/modbus_master.h"
#include "vm/runtime.h"

namespace softslc {

namespace {

constexpr std::uint16_t kTypeCodes[][2] = {
    {static_cast<std::uint16_t>(FileType::Status), 0x84},  {static_cast<std::uint16_t>(FileType::Bit), 0x85},
    {static_cast<std::uint16_t>(FileType::Timer), 0x86},   {static_cast<std::uint16_t>(FileType::Counter), 0x87},
    {static_cast<std::uint16_t>(FileType::Control), 0x88}, {static_cast<std::uint16_t>(FileType::Integer), 0x89},
    {static_cast<std::uint16_t>(FileType::Float), 0x8A},   {static_cast<std::uint16_t>(FileType::Output), 0x8B},
    {static_cast<std::uint16_t>(FileType::Input), 0x8C},   {static_cast<std::uint16_t>(FileType::String), 0x8D},
    {static_cast<std::uint16_t>(FileType::Ascii), 0x8E},
};

std::int16_t as_signed(std::uint16_t w) { return static_cast<std::int16_t>(w); }

// A station's data table as a Modbus request reaches it (vm/modbus_slave.h): the files of its layout, words
// read and written in place, as a DH-485 request's are (answer below). A MicroLogix has no forced bits in the
// B and N files and S2 the map names, so no write is refused.
class DataTableTarget final : public pccc::Target {
 public:
  explicit DataTableTarget(DataTable& data) : data_(data) {}
  std::optional<File> file(int number) const override {
    if (number < 0 || number >= static_cast<int>(data_.layout().files.size())) return std::nullopt;
    const FileLayout& f = data_.layout().files[static_cast<std::size_t>(number)];
    if (!f.present) return std::nullopt;
    return File{f.type, f.elements, f.words_per_element};
  }
  void read(int number, std::uint32_t offset, std::span<std::uint16_t> out) const override {
    const std::uint32_t base = data_.layout().files[static_cast<std::size_t>(number)].base + offset;
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = data_.word(base + static_cast<std::uint32_t>(i));
  }
  std::string write(int number, std::uint32_t offset, std::span<const std::uint16_t> values,
                    std::span<const std::uint16_t> masks) override {
    const std::uint32_t base = data_.layout().files[static_cast<std::size_t>(number)].base + offset;
    for (std::size_t i = 0; i < values.size(); ++i) {
      const std::uint32_t w = base + static_cast<std::uint32_t>(i);
      data_.set_word(w, static_cast<std::uint16_t>((data_.word(w) & ~masks[i]) | (values[i] & masks[i])));
    }
    return {};
  }
  std::vector<std::uint8_t> diagnostic_status() const override { return {}; }

 private:
  DataTable& data_;
};

}  // namespace

std::uint16_t message_file_type_code(FileType t) {
  for (const auto& row : kTypeCodes)
    if (row[0] == static_cast<std::uint16_t>(t)) return row[1];
  return 0;
}

std::optional<FileType> message_file_type(std::uint16_t code) {
  for (const auto& row : kTypeCodes)
    if (row[1] == code) return static_cast<FileType>(row[0]);
  return std::nullopt;
}

std::optional<std::uint32_t> parse_ipv4(std::string_view text) {
  std::uint32_t ip = 0;
  int parts = 0;
  std::size_t i = 0;
  while (parts < 4) {
    int value = 0, digits = 0;
    while (i < text.size() && text[i] >= '0' && text[i] <= '9' && digits < 3) value = value * 10 + (text[i++] - '0'), ++digits;
    if (digits == 0 || value > 255) return std::nullopt;
    ip = (ip << 8) | static_cast<std::uint32_t>(value);
    if (++parts < 4) {
      if (i >= text.size() || text[i] != '.') return std::nullopt;
      ++i;
    }
  }
  if (i != text.size()) return std::nullopt;
  return ip;
}

std::string format_ipv4(std::uint32_t ip) {
  return std::to_string(ip >> 24) + "." + std::to_string((ip >> 16) & 0xFF) + "." + std::to_string((ip >> 8) & 0xFF) +
         "." + std::to_string(ip & 0xFF);
}

Nanoseconds message_frame_time(MessageLink link, int data_bytes) {
  const std::int64_t bits =
      static_cast<std::int64_t>(message_frame_overhead_bytes(link) + data_bytes) * message_link_bits_per_byte(link);
  const std::int64_t baud = message_link_baud(link);
  return (bits * kNsPerS + baud - 1) / baud;  // rounded up: a frame never takes zero time
}

MessageNetwork::~MessageNetwork() = default;

std::size_t MessageNetwork::attach(Runtime& rt, int node, std::string name, std::unique_ptr<Runtime> owned,
                                   std::uint32_t ip, int segment) {
  Station s;
  s.rt = &rt;
  s.owned = std::move(owned);
  s.node = node;
  s.ip = ip;
  s.name = std::move(name);
  for (int channel = 0; channel < 2; ++channel)
    s.status_word[static_cast<std::size_t>(channel)] = rt.compiled().layout->communications_status_word(channel);
  stations_.push_back(std::move(s));
  const std::size_t index = stations_.size() - 1;
  attach_port(index, network_channel(index), node, segment);
  return index;
}

void MessageNetwork::attach_port(std::size_t station, int channel, int node, int segment) {
  Station& s = stations_[station];
  s.port_node[static_cast<std::size_t>(channel & 1)] = node;
  s.port_segment[static_cast<std::size_t>(channel & 1)] = segment;
  refresh_links(station);
}

std::optional<std::size_t> MessageNetwork::station_on(int segment, int node) const {
  if (const auto at = port_at(segment, node)) return at->first;
  return std::nullopt;
}

std::uint16_t MessageNetwork::word(std::size_t station, std::uint32_t index) const {
  const DataTable& d = stations_[station].rt->data();
  return index < d.size() ? d.word(index) : 0;
}

void MessageNetwork::set_word(std::size_t station, std::uint32_t index, std::uint16_t value) {
  DataTable& d = stations_[station].rt->data();
  if (index < d.size()) d.set_word(index, value);
}

std::uint16_t MessageNetwork::status(std::size_t station, const MessageInstruction& in) const {
  if (!in.micrologix) return word(station, in.block);
  return msg::mg_status_word(in.block, [&](std::uint32_t i) { return word(station, i); });
}

void MessageNetwork::set_status(std::size_t station, const MessageInstruction& in, std::uint16_t w0) {
  if (!in.micrologix) return set_word(station, in.block, w0);
  msg::set_mg_status_word(
      in.block, w0, [&](std::uint32_t i) { return word(station, i); },
      [&](std::uint32_t i, std::uint16_t v) { set_word(station, i, v); });
}

int MessageNetwork::network_channel(std::size_t station) const {
  const ProcessorFamily family = stations_[station].rt->compiled().processor.family;
  if (family == ProcessorFamily::MicroLogix) return link_ == MessageLink::Ethernet ? 1 : 0;
  return family == ProcessorFamily::Slc502 ? 0 : 1;
}

void MessageNetwork::refresh_links(std::size_t station) {
  for (int c = 0; c < 2; ++c) stations_[station].links[static_cast<std::size_t>(c)] = find_channel_link(station, c);
}

MessageLink MessageNetwork::find_channel_link(std::size_t station, int channel) const {
  if (channel == 0 && stations_[station].df1) return MessageLink::Df1;
  // A channel 0 that is a Modbus RTU slave sends no MSG: 12h, as a PCCC MSG on a Modbus master's (decision).
  if (channel == 0 && stations_[station].modbus_slave) return MessageLink::None;
  // The SLC 5/03-5/05's channel 0 sends MSG only as a DF1 port (docs/semantics.md "DF1 full-duplex on channel 0").
  const ProcessorFamily family = stations_[station].rt->compiled().processor.family;
  if (channel == 0 && (family == ProcessorFamily::Slc503 || family == ProcessorFamily::Slc504 ||
                       family == ProcessorFamily::Slc505))
    return MessageLink::None;
  if (channel == network_channel(station) || stations_[station].port_node[static_cast<std::size_t>(channel & 1)] >= 0)
    return link_;
  // The 1764-LRP's channel 1 is a serial port like its channel 0 (DH-485 in softslc), here on no network.
  if (stations_[station].rt->compiled().processor.micrologix == MicroLogixModel::ML1500LRP) return MessageLink::Dh485;
  // Only a MicroLogix 1100/1400 sends on a channel off the network (check holds every other MSG to its
  // processor's network channel): its Ethernet port (channel 1) or its serial port (channel 0, DH-485).
  return channel == 1 ? MessageLink::Ethernet : MessageLink::Dh485;
}

std::optional<std::pair<std::size_t, int>> MessageNetwork::port_at(int segment, int node) const {
  for (std::size_t i = 0; i < stations_.size(); ++i)
    for (std::size_t c = 0; c < 2; ++c)
      if (stations_[i].port_node[c] == node && stations_[i].port_segment[c] == segment)
        return std::pair{i, static_cast<int>(c)};
  return std::nullopt;
}

std::optional<std::size_t> MessageNetwork::station_at_ip(std::uint32_t ip) const {
  for (std::size_t i = 0; i < stations_.size(); ++i)
    if (stations_[i].ip == ip) return i;
  return std::nullopt;
}

MessageNetwork::Message* MessageNetwork::find(std::size_t station, std::uint64_t serial, int* channel, bool* queued) {
  for (int c = 0; c < 2; ++c) {
    Channel& ch = stations_[station].channels[static_cast<std::size_t>(c)];
    for (auto* list : {&ch.buffers, &ch.queue})
      for (Message& m : *list)
        if (m.serial == serial) {
          if (channel) *channel = c;
          if (queued) *queued = list == &ch.queue;
          return &m;
        }
  }
  return nullptr;
}

void MessageNetwork::remove(std::size_t station, std::uint64_t serial) {
  int channel = 0;
  bool queued = false;
  const Message* m = find(station, serial, &channel, &queued);
  if (!m) return;
  Channel& ch = stations_[station].channels[static_cast<std::size_t>(channel)];
  std::vector<Message>& list = queued ? ch.queue : ch.buffers;
  list.erase(list.begin() + (m - list.data()));
}

// ---- The instruction ---------------------------------------------------------------------------------------

void MessageNetwork::start(std::size_t station, const MessageInstruction& instruction) {
  start_message(station, instruction);
  if (const Station& st = stations_[station]; st.status_word[0] || st.status_word[1]) publish_command_pending(station);
}

void MessageNetwork::publish_command_pending(std::size_t station) {
  Station& st = stations_[station];
  for (std::size_t c = 0; c < st.channels.size(); ++c) {
    if (!st.status_word[c]) continue;
    const Channel& ch = st.channels[c];
    const bool pending =
        !ch.queue.empty() || std::any_of(ch.buffers.begin(), ch.buffers.end(), [](const Message& m) { return !m.sent; });
    if (pending == st.command_pending[c]) continue;
    st.command_pending[c] = pending;
    const std::uint16_t w = word(station, *st.status_word[c]);
    set_word(station, *st.status_word[c],
             static_cast<std::uint16_t>(pending ? w | cs::kCommandPending : w & ~cs::kCommandPending));
  }
}

void MessageNetwork::start_message(std::size_t station, const MessageInstruction& instruction) {
  const Runtime& rt = *stations_[station].rt;
  MessageInstruction in = instruction;
  // The 1764-LRP reads the channel from MG word 8 when the message starts: CHN is read/write there, "0
  // (channel 0) or 1 (channel 1)" (1762-RM001C p. 21-4), so a program that writes it sends on the other
  // port. Any other value names no channel: 21h "bad MSG file parameter" (decision [U], docs/semantics.md
  // "Channel 1 of the 1500 LRP"). The LSP and the 1200 keep CHN 0, read only ("always 0", p. 21-4).
  std::uint8_t bad_channel = 0;
  if (in.micrologix && rt.compiled().processor.micrologix == MicroLogixModel::ML1500LRP) {
    const std::uint16_t chn = word(station, in.block + mg::kChannel);
    if (chn > 1) bad_channel = msg::kBadMessageFile;
    else in.channel = chn;
  }
  const DataTableLayout& layout = *rt.compiled().layout;
  // A message of this control block still in a buffer or the queue is replaced: the program cleared
  // EN before DN or ER, which the manual forbids (RM 12-30); the new one wins.
  for (Channel& ch : stations_[station].channels) {
    std::erase_if(ch.buffers, [&](const Message& m) { return m.in.block == in.block; });
    std::erase_if(ch.queue, [&](const Message& m) { return m.in.block == in.block; });
  }

  // The false-to-true transition resets DN, ER, ST, NR, TO and the error code (RM 12-28, 12-29).
  std::uint16_t w0 = status(station, in);
  w0 = static_cast<std::uint16_t>(w0 & ~(msg::kEN | msg::kST | msg::kDN | msg::kER | msg::kEW | msg::kNR | msg::kTO |
                                         msg::kErrorCode));
  if (!in.slc502 && !in.micrologix)
    set_word(station, in.block + 7, static_cast<std::uint16_t>(word(station, in.block + 7) & ~msg::kWQ));

  Message m;
  m.serial = next_serial_++;
  m.in = in;
  m.started = in.at;
  const MessageLink link = channel_link(station, in.channel);
  // An SLC 5/03-5/05 channel 0 that is not configured for DF1 full-duplex: "12H Local channel configuration
  // protocol error exists" (1747-RM001G p. 12-41 table 12.17; decision, docs/semantics.md "DF1 full-duplex
  // on channel 0").
  if (link == MessageLink::None && bad_channel == 0) bad_channel = modbus::kChannelProtocol;
  if (in.micrologix) {
    // The MG element's setup (1762-RM001C p. 21-4): NOD, the target file type (word 12), TFN, ELE, MTO in
    // whole seconds, 0 = no timeout (p. 21-12). The MicroLogix 1400's channel 1 timeout is not the MSG's:
    // the channel's connection and reply timeouts plus 15 s (1766-RM001A p. 421).
    m.target_node = word(station, in.block + mg::kNode) & 0xFF;
    m.elements = in.elements;
    m.target_file = as_signed(word(station, in.block + mg::kTargetFile));
    m.type_code = word(station, in.block + mg::kTargetFileType);
    m.target_element = as_signed(word(station, in.block + mg::kTargetElement));
    const bool ml1400_ethernet =
        link == MessageLink::Ethernet && rt.compiled().processor.micrologix == MicroLogixModel::ML1400;
    m.timeout = ml1400_ethernet ? static_cast<Nanoseconds>(kMl1400EthernetMessageTimeoutSeconds) * kNsPerS
                                : static_cast<Nanoseconds>(word(station, in.block + mg::kTimeout) & 0xFF) * kNsPerS;
  } else {
    m.target_node = word(station, in.block + 1) & 0xFF;
    m.elements = as_signed(word(station, in.block + 2));
    m.target_file = as_signed(word(station, in.block + 3));
    m.type_code = word(station, in.block + 4);
    m.target_element = as_signed(word(station, in.block + 5));
  }
  if (!in.slc502 && !in.micrologix) {
    // "a value of 1 second gets bumped to 2 seconds upon instruction execution" (RM 12-53, of the
    // standard MSG's timeout).
    int seconds = word(station, in.block + 8) & 0xFF;
    if (seconds == 1) seconds = 2;
    m.timeout = static_cast<Nanoseconds>(seconds) * kNsPerS;
  }

  // The control block as the processor reads it: a file type of the local file, a count that fits the
  // local file and one message, a node the link has (RM 12-41: 04h, 16h).
  const int file = layout.file_containing(in.data);
  std::uint8_t error = bad_channel;  // found first: a message with no channel is built no further
  if (bad_channel != 0) {
    // nothing more to check
  } else if (file < 0) {
    error = msg::kBadParameters;
  } else {
    const FileLayout& f = layout.files[static_cast<std::size_t>(file)];
    m.words = m.elements * f.words_per_element;
    // The SLC 5/05's Ethernet messages are longer (RM D-21 table D.5); a MicroLogix message carries 103
    // words on either channel ("The maximum read or write message for a MicroLogix 1100/1200/1500
    // controller is 103 words", AG-UM008C p. 3-38; 1762-RM001C p. 21-12).
    const bool too_many = link == MessageLink::Ethernet && !in.micrologix
                              ? m.elements > ethernet_max_elements(f.type, in.device == 2, in.write)
                              : m.words > kMessageMaxWords;
    if (m.type_code != message_file_type_code(f.type) || m.elements < 1 || too_many ||
        in.data + static_cast<std::uint32_t>(m.words) > f.end())
      error = msg::kBadParameters;
    else if (link == MessageLink::Ethernet)
      error = in.micrologix ? check_routing_element(station, in, m) : check_ethernet_block(station, in, m);
    else if (in.ml1000 && m.target_node == 255)
      error = msg::kBroadcast;  // "Broadcast (Node Address 255) is not supported" (1761-6.3 p. 13-11)
    else if (m.target_node > message_node_range(link).second && !in.ml1000)
      error = msg::kNodeTooHigh;
    // The MicroLogix 1000's table (1761-6.3 p. 13-11) has no 16h: a node above 31 that no station has
    // does not respond, 07h when the request's frame has gone (decision [U], docs/semantics.md).
  }
  if (error) {
    set_status(station, in, static_cast<std::uint16_t>(w0 | msg::kEN | msg::kER | error));
    return;
  }

  Channel& ch = stations_[station].channels[static_cast<std::size_t>(in.channel & 1)];
  const std::size_t buffers = in.slc502 ? 1 : msg::kBuffersPerChannel;
  if (in.ml1000 && ch.buffers.size() >= buffers) {
    // The MicroLogix 1000: "The EW bit is set (1) and the ST, DN, NR, and TO flags are cleared. If the
    // transmit buffer is not available, the EN flag remains false (0). When rung conditions go true and
    // the transmit buffer becomes available, the EN flag goes true (1)" (1761-6.3 p. 13-8). It has no
    // queue: the rung, still true, starts the message at a later scan once the buffer is free.
    set_status(station, in, static_cast<std::uint16_t>(w0 | msg::kEW));
    return;
  }
  set_status(station, in, static_cast<std::uint16_t>(w0 | msg::kEN));
  if (ch.buffers.size() < buffers) {
    ch.buffers.push_back(std::move(m));
    enter_buffer(station, ch.buffers.back());
  } else if (ch.queue.size() < static_cast<std::size_t>(msg::kQueuePositions) || in.micrologix) {
    // The MicroLogix queue "can accommodate all MSG instructions in a ladder program" (1762-RM001C p. 21-2).
    // RM 12-7: queued messages "will only have control block status bit EN set"; the 5/02's waiting
    // messages have EN and EW (RM 12-5).
    if (in.slc502) set_word(station, in.block, static_cast<std::uint16_t>(word(station, in.block) | msg::kEW));
    ch.queue.push_back(std::move(m));
  } else {
    // RM 12-7: more than 14 on one channel: "only control block status bit WQ is set"; the rung must
    // be scanned true again until there is room. The 5/02 has no WQ (its block has no word 7).
    set_status(station, in, w0);
    if (!in.slc502)
      set_word(station, in.block + 7, static_cast<std::uint16_t>(word(station, in.block + 7) | msg::kWQ));
  }
}

// The Ethernet part of the block (RM 12-34 table 12.14): the message type, AO, this station's own
// address and the target's IP address string; the data length in bytes goes into word 11 (RM D-21).
std::uint8_t MessageNetwork::check_ethernet_block(std::size_t station, const MessageInstruction& in, Message& m) {
  const std::uint16_t type_word = word(station, in.block + msg::kEthernetTypeWord);
  if (is_multihop_message_type(type_word)) return msg::kServiceUnsupported;  // not simulated
  if ((type_word & 0xFF) != 0) return msg::kBadParameters;
  // AO "has no meaning for 485CIF and 500CPU types of reads and writes" (1747-10.4 p. 4-3); with PLC5 it
  // selects logical ASCII addressing, the 93-word block, which softslc does not simulate.
  if (in.device == 2 && (word(station, in.block + msg::kAoWord) & kMessageAoBit)) return msg::kServiceUnsupported;
  if (stations_[station].ip == 0) return msg::kNoIpConfigured;
  std::string text;
  bool terminated = false;
  for (int i = 0; i < msg::kIpBytes && !terminated; ++i) {
    const std::uint16_t w = word(station, in.block + msg::kIpWord + static_cast<std::uint32_t>(i / 2));
    const char c = static_cast<char>(i % 2 == 0 ? w >> 8 : w & 0xFF);  // the first character in the high byte
    if (c == '\0') terminated = true;
    else text += c;
  }
  const std::optional<std::uint32_t> ip = terminated ? parse_ipv4(text) : std::nullopt;
  if (!ip) return msg::kBadIpAddress;
  m.target_ip = *ip;
  set_word(station, in.block + msg::kByteCountWord, static_cast<std::uint16_t>(2 * m.words));
  return 0;
}

// The MicroLogix 1100/1400 channel 1 message's routing (1766-RM001A p. 435, 1763-RM001B p. 384): MG word 24
// names its RI element (bits 8-15 the file, 0-7 the element; 1766-RM001A p. 400), whose subtype says how
// the message is routed and whose words 1-2 hold the target's IP address. The codes are the SLC 5/05's
// ("MSG on Ethernet"): D0h this controller has no IP address, D2h an address that is no station's
// (0.0.0.0: the element was never set up); 17h for the remote MultiHop softslc does not simulate, 21h a
// routing word or subtype that names no routing (docs/semantics.md "The MicroLogix MSG on Ethernet").
std::uint8_t MessageNetwork::check_routing_element(std::size_t station, const MessageInstruction& in, Message& m) {
  const DataTableLayout& layout = *stations_[station].rt->compiled().layout;
  const std::uint16_t path = word(station, in.block + mg::kRoutingPath);
  const std::size_t file = path >> 8, element = path & 0xFFu;
  if (file >= layout.files.size() || !layout.files[file].present || layout.files[file].type != FileType::Routing ||
      element >= layout.files[file].elements)
    return msg::kBadMessageFile;
  const std::uint32_t ri = layout.files[file].base + static_cast<std::uint32_t>(element) * layout.files[file].words_per_element;
  const std::uint16_t subtype = word(station, ri + ri::kSubtype);
  if (subtype == kRoutingRemoteDhPlus) return msg::kServiceUnsupported;  // not simulated
  if (subtype != kRoutingLocal) return msg::kBadMessageFile;
  if (stations_[station].ip == 0) return msg::kNoIpConfigured;
  m.target_ip = routing_ip(word(station, ri + ri::kIpHigh), word(station, ri + ri::kIpLow));
  if (m.target_ip == 0) return msg::kBadIpAddress;
  return 0;
}

void MessageNetwork::enter_buffer(std::size_t station, Message& m) {
  // EW: "the message is in the buffer ... and waiting to be sent"; a write's source data is buffered
  // now (RM 12-29, table 12.10).
  set_status(station, m.in, static_cast<std::uint16_t>(status(station, m.in) | msg::kEN | msg::kEW));
  if (m.in.write) {
    m.data.resize(static_cast<std::size_t>(m.words));
    for (int i = 0; i < m.words; ++i) m.data[static_cast<std::size_t>(i)] = word(station, m.in.data + static_cast<std::uint32_t>(i));
  }
  m.sent = false;
}

void MessageNetwork::abort(std::size_t station, std::uint32_t block) {
  for (Channel& ch : stations_[station].channels)
    for (auto* list : {&ch.buffers, &ch.queue})
      for (Message& m : *list)
        if (m.in.block == block) {
          // RM 12-30: "The next time the processor scans the MSG instruction with the TO bit set, it will
          // error the MSG (ER = 1)"; the code is the timeout's (decision, docs/semantics.md "MSG").
          finish(station, m, msg::kTimedOut, msg::kTO);
          publish_command_pending(station);
          return;
        }
}

void MessageNetwork::finish(std::size_t station, Message& m, std::uint8_t error, std::uint16_t extra_bits) {
  std::uint16_t w0 = status(station, m.in);
  w0 = static_cast<std::uint16_t>(w0 & ~(msg::kST | msg::kEW | msg::kErrorCode));
  if (error) w0 = static_cast<std::uint16_t>(w0 | msg::kER | error | extra_bits);
  else w0 = static_cast<std::uint16_t>(w0 | msg::kDN);
  set_status(station, m.in, w0);
  // CO: "continually resend" (RM 12-61 of the same bit): a message that completed stays in its buffer
  // and goes out again at this servicing point, its timer restarted (SLC 5/03-5/05).
  if (!error && !m.in.slc502 && !m.in.micrologix && (w0 & msg::kCO)) {
    m.sent = false;
    m.acked.reset();
    m.data.clear();
    if (m.in.write) enter_buffer(station, m);
    return;
  }
  remove(station, m.serial);
}

// ---- DF1 full-duplex on channel 0 ----------------------------------------------------------------------------

void MessageNetwork::attach_df1(std::size_t station, const Df1Config& config) {
  Station& s = stations_[station];
  s.df1.emplace();
  s.df1->config = config;
  // A channel 0 that is a DF1 port is on no DH-485 network (a MicroLogix's, a 5/02 has none).
  s.port_node[0] = -1;
  refresh_links(station);
}

void MessageNetwork::join_df1(std::size_t a, std::size_t b) {
  stations_[a].df1_partner = b;
  stations_[b].df1_partner = a;
}

std::string MessageNetwork::attach_modbus_slave(std::size_t station, const modbus::SlaveOptions& options,
                                                ModbusMaster& master) {
  DataTableTarget target(stations_[station].rt->data());
  if (std::string why = modbus::check_map(options.map, target); !why.empty()) return why;
  stations_[station].modbus_slave = options;
  refresh_links(station);
  modbus_master_ = &master;
  master.set_peer_line(this);
  return {};
}

std::optional<std::size_t> MessageNetwork::modbus_slave_at(int address) const {
  for (std::size_t i = 0; i < stations_.size(); ++i)
    if (stations_[i].modbus_slave && stations_[i].modbus_slave->address == address) return i;
  return std::nullopt;
}

// The frame reaches every slave's receiver; one configured for another baud rate hears no frame (its UART
// sees framing errors), so it neither executes nor answers nor counts it. A broadcast reaches every slave; a
// frame to another address is only counted as seen, at the slave's servicing as the others are.
void MessageNetwork::deliver(int address, std::uint64_t serial, std::vector<std::uint8_t> pdu, std::int64_t baud,
                             VirtualTime at) {
  for (Station& st : stations_) {
    if (!st.modbus_slave || st.modbus_slave->baud != baud) continue;
    const bool to_this = address == 0 || st.modbus_slave->address == address;
    st.modbus_requests.push_back({at, serial, address == 0, to_this, to_this ? pdu : std::vector<std::uint8_t>{}});
  }
}

// "Under normal operation the controller processes communications once every time it scans the control
// program" (1763-RM001B p. 344, 1766-RM001A p. 396): an incoming command is executed at the end of a scan or at
// an SVC (1766-RM001A p. 410-411: "One incoming channel 0 or channel 1 command" at each servicing, all remaining
// ones when the Communications Servicing Selection bit is clear; the line brings one at a time). The reply
// starts on the line then.
void MessageNetwork::serve_modbus(std::size_t station, VirtualTime at) {
  Station& st = stations_[station];
  const modbus::SlaveOptions& o = *st.modbus_slave;
  while (!st.modbus_requests.empty() && st.modbus_requests.front().arrival <= at) {
    const Station::ModbusRequest request = std::move(st.modbus_requests.front());
    st.modbus_requests.erase(st.modbus_requests.begin());
    // The counters as serve's slave keeps them (server/modbus_rtu.cpp): the request counted before it is
    // executed (a read of 30518-30531 includes itself), the reply after.
    ++st.modbus_counters.seen;
    if (!request.to_this) continue;
    st.modbus_counters.count_request(request.pdu.at(0));
    const modbus::CommParameters comm = modbus::comm_parameters(o.map, o.address, st.modbus_counters);
    DataTableTarget target(st.rt->data());
    const std::vector<std::uint8_t> reply = modbus::handle_pdu(request.pdu, o.map, target, nullptr, &comm);
    if (request.broadcast || !modbus_master_) continue;
    modbus_master_->peer_replied(request.serial, reply, at);
    ++st.modbus_counters.responded;
  }
}

void MessageNetwork::leave_network(std::size_t station) {
  stations_[station].port_node[static_cast<std::size_t>(network_channel(station) & 1)] = -1;
  refresh_links(station);
}

const Df1Port* MessageNetwork::df1_port(std::size_t station) const {
  return stations_[station].df1 ? &*stations_[station].df1 : nullptr;
}

Df1Port* MessageNetwork::df1_far(std::size_t station, bool* line_ok) {
  const Station& s = stations_[station];
  Df1Port* far = s.df1_partner && stations_[*s.df1_partner].df1 ? &*stations_[*s.df1_partner].df1 : nullptr;
  // A receiver at another baud rate or parity assembles no frame from what arrives (decision [U],
  // docs/semantics.md "DF1 full-duplex on channel 0"): it neither ACKs nor NAKs, as an open cable.
  *line_ok = far && s.df1_cable && far->config.baud == s.df1->config.baud &&
             far->config.parity_even == s.df1->config.parity_even;
  return far;
}

namespace {
// Duplicate detection compares the packet's source, command and transaction number with the last packet
// taken (1770-6.5.16 ch. 4 [U]).
std::uint32_t df1_key(const std::vector<std::uint8_t>& packet) {
  return (static_cast<std::uint32_t>(packet[1]) << 24) | (static_cast<std::uint32_t>(packet[2]) << 16) |
         static_cast<std::uint32_t>(packet[4]) | (static_cast<std::uint32_t>(packet[5]) << 8);
}
}  // namespace

void MessageNetwork::send_df1(std::size_t station, VirtualTime at, Message& m) {
  Station& s = stations_[station];
  Df1Port& port = *s.df1;
  bool line_ok = false;
  Df1Port* far = df1_far(station, &line_ok);
  Df1Command c;
  c.dst = m.target_node;
  c.src = s.node & 0xFF;
  c.tns = port.next_tns++;
  c.write = m.in.write;
  c.cif = m.in.device == 1;
  c.file = m.target_file;
  c.type_code = m.type_code;
  c.element = m.target_element;
  c.words = m.words;
  c.data = m.data;
  const std::vector<std::uint8_t> packet = df1_command_packet(c);
  const int bytes = static_cast<int>(df1_frame(packet, port.config.error_check).size());
  const Df1Outcome o = df1_transfer(port, far, line_ok, at, bytes, df1_key(packet));
  for (VirtualTime when : o.deliveries) {
    Frame req = request_frame(station, m, 0);
    req.df1 = true;
    req.dst = c.dst;
    req.src = c.src;
    req.tns = c.tns;
    post(*s.df1_partner, when, std::move(req));
  }
  Frame f;
  f.channel = m.in.channel;
  f.serial = m.serial;
  if (o.acked) {
    // ST "is set when the processor receives acknowledgment (ACK) from the target device" (RM 12-29).
    f.kind = FrameKind::Ack;
  } else {
    // NAK retries or ENQ retries used up: "07H Target node does not respond" (RM 12-41 table 12.17;
    // decision [U], docs/semantics.md "DF1 full-duplex on channel 0").
    f.kind = FrameKind::NoAck;
    f.error = msg::kNoResponse;
  }
  post(station, o.done, std::move(f));
}

void MessageNetwork::reply_df1(std::size_t station, VirtualTime at, const Frame& req, const Frame& reply) {
  Station& s = stations_[station];
  if (!s.df1) return;
  Df1Port& port = *s.df1;
  bool line_ok = false;
  Df1Port* far = df1_far(station, &line_ok);
  Df1Command c;
  c.dst = req.dst;
  c.src = req.src;
  c.tns = req.tns;
  c.write = req.write;
  c.cif = req.cif;
  // The reply's STS carries the error; the codes E0h and above travel as STS F0h with an EXT STS byte.
  std::vector<std::uint8_t> packet =
      df1_reply_packet(c, reply.error >= 0xE0 ? 0xF0 : reply.error, reply.data);
  if (reply.error >= 0xE0) packet.push_back(static_cast<std::uint8_t>(reply.error & 0x0F));
  const int bytes = static_cast<int>(df1_frame(packet, port.config.error_check).size());
  // A reply the link fails to deliver leaves the message to its timer (37h), or waiting when it has none
  // (RM 12-14: "a message that has been acknowledged waits indefinitely for a reply").
  const Df1Outcome o = df1_transfer(port, far, line_ok, at, bytes, df1_key(packet));
  for (VirtualTime when : o.deliveries) post(req.from, when, reply);
}

std::string MessageNetwork::df1_inject(std::size_t station, std::string_view change, const std::vector<std::string>& args) {
  Station& s = stations_[station];
  if (!s.df1) return "channel 0 is not configured for DF1 full-duplex";
  auto set_cable = [&](bool on) {
    s.df1_cable = on;
    if (s.df1_partner) stations_[*s.df1_partner].df1_cable = on;
  };
  if ((change == "cable removed" || change == "cable connected") && args.empty()) {
    set_cable(change == "cable connected");
    return {};
  }
  if (change == "corrupt" && args.size() == 1) {
    const std::string& n = args[0];
    if (n.empty() || n.size() > 3 || n.find_first_not_of("0123456789") != std::string::npos)
      return "corrupt takes the number of frames (0-999) whose check the noise breaks, not '" + n + "'";
    s.df1->corrupt_frames = std::stoi(n);
    return {};
  }
  if (change == "lose ack" && args.empty()) {
    s.df1->lose_ack = true;
    return {};
  }
  if (change == "normal" && args.empty()) {
    set_cable(true);
    s.df1->corrupt_frames = 0;
    s.df1->lose_ack = false;
    return {};
  }
  return "the DF1 link takes 'cable removed', 'cable connected', 'corrupt N' (the next N frames this controller "
         "sends arrive with a bad BCC/CRC), 'lose ack' (the next ACK it receives is destroyed) or 'normal'";
}

std::optional<std::int64_t> MessageNetwork::df1_observe(std::size_t station, std::string_view what,
                                                        VirtualTime now) const {
  const Station& s = stations_[station];
  const std::optional<Df1Count> c = df1_count_named(what);
  if (!s.df1 || !c) return std::nullopt;
  return s.df1->counters.at(*c, now);
}

// ---- Servicing ---------------------------------------------------------------------------------------------

void MessageNetwork::post(std::size_t to, VirtualTime arrival, Frame f) {
  // After every frame arriving no later: the new one has the largest sequence yet.
  std::vector<Station::Arrival>& inbox = stations_[to].inbox;
  const auto at = std::upper_bound(inbox.begin(), inbox.end(), arrival,
                                   [](VirtualTime t, const Station::Arrival& a) { return t < a.at; });
  inbox.insert(at, Station::Arrival{arrival, next_frame_++, std::move(f)});
}

MessageNetwork::Frame MessageNetwork::request_frame(std::size_t station, const Message& m, int channel) {
  Frame req;
  req.kind = FrameKind::Request;
  req.from = station;
  req.channel = channel;
  req.reply_channel = m.in.channel;
  req.serial = m.serial;
  req.write = m.in.write;
  req.cif = m.in.device == 1;
  req.file = m.target_file;
  req.type_code = m.type_code;
  req.element = m.target_element;
  req.words = m.words;
  req.data = m.data;
  return req;
}

void MessageNetwork::send(std::size_t station, VirtualTime at, Message& m) {
  m.sent = true;
  const MessageLink link = channel_link(station, m.in.channel);
  if (link == MessageLink::Df1) return send_df1(station, at, m);
  const Nanoseconds d = message_frame_time(link, m.in.write ? 2 * m.words : 0);
  const bool ethernet = link == MessageLink::Ethernet;
  // A MicroLogix's channel off this network reaches nobody (a serial port no other station is on). On
  // DH-485 and DH+ the target is the station with a channel at the node on the sender's channel's segment
  // (the 1764-LRP's channel 1 may be on a network of its own); on Ethernet the station at the address.
  const Station& from = stations_[station];
  const auto port = static_cast<std::size_t>(m.in.channel & 1);
  std::optional<std::pair<std::size_t, int>> target;
  if (link == link_ && from.port_node[port] >= 0) {
    if (!ethernet) target = port_at(from.port_segment[port], m.target_node);
    else if (const auto at = station_at_ip(m.target_ip)) target = std::pair{*at, network_channel(*at)};
  }
  if (!target) {
    // No station acknowledges: on DH-485 and DH+ the link gives up after the frame's time (EST: retries
    // not modelled); on Ethernet the connection is not completed before the channel's MSG Connection
    // Timeout (15 s, 1747-UM011G p. 242): D5H, unless the message timer ends it first (37h).
    Frame f;
    f.kind = FrameKind::NoAck;
    f.channel = m.in.channel;
    f.serial = m.serial;
    f.error = ethernet ? msg::kConnectionTimeout : msg::kNoResponse;
    post(station, ethernet ? at + msg::kConnectionTimeoutNs : at + d, std::move(f));
    return;
  }
  post(target->first, at + d, request_frame(station, m, target->second));
  // The link-level acknowledgement: ST "is set when the processor receives acknowledgment (ACK) from
  // the target device" (RM 12-29), here when the frame arrives.
  Frame ack;
  ack.kind = FrameKind::Ack;
  ack.channel = m.in.channel;
  ack.serial = m.serial;
  post(station, at + d, std::move(ack));
}

void MessageNetwork::answer(std::size_t station, VirtualTime at, const Frame& req) {
  Runtime& rt = *stations_[station].rt;
  const DataTableLayout& layout = *rt.compiled().layout;
  Frame reply;
  reply.kind = FrameKind::Reply;
  reply.channel = req.reply_channel;
  reply.serial = req.serial;
  // A 485CIF request reaches the target's common interface file: an SLC's is the file the control block
  // names (N9, docs/semantics.md "MSG"); a MicroLogix 1000's is N7 (1761-6.2 p. 15-3).
  const int file = req.cif && rt.compiled().processor.micrologix == MicroLogixModel::ML1000 ? kMl1000CommonInterfaceFile
                                                                                            : req.file;
  const FileLayout* f = nullptr;
  if (file >= 0 && file <= 255 && layout.files[static_cast<std::size_t>(file)].present)
    f = &layout.files[static_cast<std::size_t>(file)];
  const std::optional<FileType> type = message_file_type(req.type_code);
  // "SLC 500, SLC 5/01, and SLC 5/02 processors do not support O or I file access from a MSG instruction.
  // SLC 5/03, SLC 5/04 and SLC 5/05 processors do support O and I file access, but only when unprotected"
  // (1761-6.2 p. 15-3 note 4). softslc has no file protection, so the 5/03-5/05 always answer; the fixed
  // controllers, the 5/01 and the 5/02 answer 10h, "incorrect command parameters or unsupported command"
  // (1761-6.3 p. 13-11; the code is not in note 4: decision [U], docs/semantics.md "The MicroLogix 1000 MSG").
  const ProcessorFamily family = rt.compiled().processor.family;
  const bool no_io_access =
      family == ProcessorFamily::Fixed || family == ProcessorFamily::Slc501 || family == ProcessorFamily::Slc502;
  if (no_io_access && type && (*type == FileType::Output || *type == FileType::Input)) {
    reply.error = msg::kUnsupportedCommand;
  } else if (!f) {
    reply.error = msg::kNoSuchFile;
  } else if (!type || *type != f->type) {
    reply.error = msg::kIllegalFileType;
  } else if (req.element < 0 || static_cast<std::uint32_t>(req.element) >= f->elements) {
    reply.error = msg::kAddressUnusable;
  } else if (static_cast<std::uint32_t>(req.element) * f->words_per_element + static_cast<std::uint32_t>(req.words) >
             f->words()) {
    reply.error = msg::kPastEnd;
  } else {
    const std::uint32_t first = f->base + static_cast<std::uint32_t>(req.element) * f->words_per_element;
    if (req.write) {
      for (int i = 0; i < req.words; ++i)
        set_word(station, first + static_cast<std::uint32_t>(i), req.data[static_cast<std::size_t>(i)]);
    } else {
      reply.data.resize(static_cast<std::size_t>(req.words));
      for (int i = 0; i < req.words; ++i) reply.data[static_cast<std::size_t>(i)] = word(station, first + static_cast<std::uint32_t>(i));
    }
  }
  if (req.df1) return reply_df1(station, at, req, reply);
  const Nanoseconds d = message_frame_time(link_, static_cast<int>(2 * reply.data.size()));
  post(req.from, at + d, std::move(reply));
}

void MessageNetwork::receive(std::size_t station, VirtualTime at, Frame& f) {
  if (f.kind == FrameKind::Request) return answer(station, at, f);
  Message* m = find(station, f.serial);
  if (!m) return;  // the message was aborted or timed out meanwhile: a late frame changes nothing
  switch (f.kind) {
    case FrameKind::Ack:
      set_status(station, m->in, static_cast<std::uint16_t>((status(station, m->in) | msg::kST) & ~msg::kEW));
      m->acked = at;
      break;
    case FrameKind::NoAck: finish(station, *m, f.error); break;
    case FrameKind::Reply:
      if (f.error == 0 && !m->in.write)
        for (std::size_t i = 0; i < f.data.size(); ++i)
          set_word(station, m->in.data + static_cast<std::uint32_t>(i), f.data[i]);
      finish(station, *m, f.error);
      break;
    case FrameKind::Request: break;
  }
}

void MessageNetwork::service(std::size_t station, VirtualTime at, std::uint16_t channel_mask) {
  Station& st = stations_[station];
  // 1. What reached this station's serviced channels by now, in arrival order (each frame belongs to the
  // channel it arrived on: a request to the port at the node it names, an acknowledgement or a reply to
  // the channel the message went out on). A frame a request posts here arrives after `at`.
  // (A frame receive posts here arrives after every frame before index i: it goes in at i or later.)
  for (std::size_t i = 0; i < st.inbox.size() && st.inbox[i].at <= at;) {
    if (!(channel_mask & (1u << (st.inbox[i].frame.channel & 1)))) {
      ++i;
      continue;
    }
    Frame f = std::move(st.inbox[i].frame);
    st.inbox.erase(st.inbox.begin() + static_cast<std::ptrdiff_t>(i));
    receive(station, at, f);
  }
  if ((channel_mask & 1u) && !st.modbus_requests.empty()) serve_modbus(station, at);
  for (int channel = 0; channel < 2; ++channel)
    if ((channel_mask & (1u << channel)) && !(st.channels[static_cast<std::size_t>(channel)].buffers.empty() &&
                                              st.channels[static_cast<std::size_t>(channel)].queue.empty()))
      service_channel(station, at, channel);
  if (st.status_word[0] || st.status_word[1]) publish_command_pending(station);  // a program naming a CS file
}

void MessageNetwork::service_channel(std::size_t station, VirtualTime at, int channel) {
  Channel& ch = stations_[station].channels[static_cast<std::size_t>(channel)];
  // 2. Message timers (SLC 5/03-5/05): ER, TO and 37h once the timeout has passed since the rung went
  // true; the accumulator (word 10) shows the whole seconds so far (docs/semantics.md "MSG").
  // Ended after the walk (finish removes the message): those whose timer expired, then Ethernet's
  // acknowledged ones with no reply within the channel's MSG Reply Timeout (1747-UM011G p. 242).
  expired_.clear();
  late_.clear();
  const bool ethernet = channel_link(station, channel) == MessageLink::Ethernet;
  for (std::size_t i = 0, n = ch.buffers.size() + ch.queue.size(); i < n; ++i) {
    const Message& m = i < ch.buffers.size() ? ch.buffers[i] : ch.queue[i - ch.buffers.size()];
    if (m.in.slc502) continue;
    const Nanoseconds elapsed = at - m.started;
    // The MicroLogix keeps the seconds in MG word 19, "time since message started" (1762-RM001C p. 21-4).
    const std::uint32_t word = m.in.block + (m.in.micrologix ? mg::kElapsed : 10);
    set_word(station, word, static_cast<std::uint16_t>(std::min<std::int64_t>(m.seconds_at(at), 32767)));
    if (m.timeout > 0 && elapsed >= m.timeout) expired_.push_back(m.serial);
    else if (ethernet && m.acked && at - *m.acked >= msg::kReplyTimeoutNs) late_.push_back(m.serial);
  }
  for (std::uint64_t serial : expired_)
    if (Message* m = find(station, serial)) finish(station, *m, msg::kTimedOut, msg::kTO);
  for (std::uint64_t serial : late_)
    if (Message* m = find(station, serial)) finish(station, *m, msg::kReplyTimeout);
  // 3. The queue into free buffers, first in first out (RM 12-41: "at end of scan or SVC").
  while (!ch.queue.empty() && ch.buffers.size() < buffer_limit(ch)) {
    ch.buffers.push_back(std::move(ch.queue.front()));
    ch.queue.erase(ch.queue.begin());
    enter_buffer(station, ch.buffers.back());
  }
  // 4. What the buffers hold goes out.
  for (Message& m : ch.buffers)
    if (!m.sent) send(station, at, m);
}

std::size_t MessageNetwork::buffer_limit(const Channel& ch) {
  return ch.queue.empty() || !ch.queue.front().in.slc502 ? msg::kBuffersPerChannel : 1;
}

std::optional<VirtualTime> MessageNetwork::quiet_until(std::size_t station, VirtualTime at) const {
  if (stations_.size() != 1) return std::nullopt;
  const Station& st = stations_[station];
  VirtualTime until = std::numeric_limits<VirtualTime>::max();
  if (!st.inbox.empty()) until = st.inbox.front().at;
  for (const Channel& ch : st.channels) {
    if (!ch.queue.empty() && ch.buffers.size() < buffer_limit(ch)) return std::nullopt;
    for (const Message& m : ch.buffers)
      if (!m.sent) return std::nullopt;
    const bool ethernet = channel_link(station, static_cast<int>(&ch - st.channels.data())) == MessageLink::Ethernet;
    for (const auto* list : {&ch.buffers, &ch.queue})
      for (const Message& m : *list) {
        // service_channel's step 2: the seconds word, the message timer, Ethernet's reply timeout.
        if (m.in.slc502) continue;
        until = std::min(until, m.next_second_at(at));
        if (m.timeout > 0) until = std::min(until, m.started + m.timeout);
        if (ethernet && m.acked) until = std::min(until, *m.acked + msg::kReplyTimeoutNs);
      }
  }
  return until;
}

void MessageNetwork::holdings(std::size_t station, std::vector<std::uint64_t>& out) const {
  const Station& st = stations_[station];
  std::size_t n = 2 * st.inbox.size();
  for (const Channel& ch : st.channels) n += 2 + 3 * (ch.buffers.size() + ch.queue.size());
  out.resize(n);  // written in place: a probe asks at every scan it makes
  std::uint64_t* o = out.data();
  const auto put = [&](const std::vector<Message>& list) {
    // The count first, so that a message moved from the queue into a buffer reads differently.
    *o++ = list.size();
    for (const Message& m : list) {
      *o++ = m.serial;
      *o++ = m.sent ? 1 : 0;
      *o++ = m.acked ? static_cast<std::uint64_t>(*m.acked) + 1 : 0;
    }
  };
  for (const Channel& ch : st.channels) {
    put(ch.buffers);
    put(ch.queue);
  }
  for (const Station::Arrival& a : st.inbox) {
    *o++ = static_cast<std::uint64_t>(a.at);
    *o++ = a.sequence;
  }
}

void MessageNetwork::service_now(std::size_t station, VirtualTime at, std::uint16_t channel_mask) {
  service(station, at, channel_mask);
}

void MessageNetwork::scanned(std::size_t station, VirtualTime end) {
  stations_[station].service_due = end;
  if (station != 0 || driving_) return;
  driving_ = true;
  // Alone, with no Modbus line: the lockstep would run the leader's servicing and nothing else.
  if (stations_.size() == 1 && !modbus_master_) {
    stations_[0].service_due.reset();
    service(0, end, 0x3);
  } else {
    run_lockstep(end);
  }
  driving_ = false;
}

void MessageNetwork::run_lockstep(VirtualTime until) {
  for (;;) {
    std::optional<std::size_t> next;
    VirtualTime next_at = 0;
    for (std::size_t i = 0; i < stations_.size(); ++i) {
      const Station& s = stations_[i];
      // A pending end-of-scan servicing is due at its time; otherwise the station's next scan starts
      // at its clock, and only a station behind `until` needs one.
      // The leader's scans are its caller's: only its servicing is run here (its clock reaches `until`
      // once this returns).
      if (i == 0 && !s.service_due) continue;
      const VirtualTime at = s.service_due ? *s.service_due : s.rt->now();
      if (at > until || (!s.service_due && at >= until)) continue;
      if (!next || at < next_at) {
        next = i;
        next_at = at;
      }
    }
    // With controllers on the leader's Modbus line, the leader's events before `until` (its channel's
    // requests and replies, vm/modbus_master.h) run in time order with the stations' scans and servicings,
    // first at a tie: a request then reaches a slave before the servicing that executes it, and the reply
    // that servicing starts is an event no earlier than the leader's clock. (Without them the leader's
    // events run after the lockstep, Runtime::scan_once.)
    if (modbus_master_) {
      EventQueue& events = stations_[0].rt->events();
      if (const auto q = events.next_time(); q && *q < until && (!next || *q <= next_at)) {
        events.run_until(*q);
        continue;
      }
    }
    if (!next) return;
    Station& s = stations_[*next];
    if (s.service_due) {
      s.service_due.reset();
      service(*next, next_at, 0x3);
    } else {
      s.rt->scan(1);
    }
  }
}

}  // namespace softslc
