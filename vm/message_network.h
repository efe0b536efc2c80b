// The MSG network: SLC controllers that message each other on one simulated link, in one virtual time.
//
// A MessageNetwork joins several Runtimes (stations), each with its node address, on one link
// (DH-485, DH+ or Ethernet, instructions/message_link.h; on Ethernet a station is named by its IP
// address and a message by the IP address string in its 51-word control block, RM 12-34, or on a
// MicroLogix 1100/1400's channel 1 by the IP address in the RI element its MG element names,
// 1766-RM001A p. 435). A MicroLogix's other channel is off the network: its messages there reach
// nobody (docs/semantics.md "The MicroLogix MSG on Ethernet"). A 1764-LRP's channel 1, its second serial
// port, has a node of its own, on the network of its channel 0 or on a second DH-485 network (a segment)
// with stations of its own; every frame belongs to the channel it arrives on, and a servicing takes the
// frames of the channels it services (docs/semantics.md "Channel 1 of the 1500 LRP"). It keeps, per
// station and channel, what the
// processor keeps for MSG (1747-RM001G ch. 12): four message buffers and a 10-position overflow
// queue on the SLC 5/03-5/05 (one buffer on the 5/02), the message timers, and the frames in
// flight. The MSG instruction's state is its control block in the data table; the interpreter
// handles the rung logic there and calls in here only when a message starts or is aborted.
//
// Frames travel as timed items: a request written at time t reaches its target at t + d, where d
// is the frame's bytes at the link's bit rate (a documented figure) with an estimated 16 bytes of
// framing (EST). A station acts on what reached it only at its communication servicing points, as
// the processor does: the end of every scan and every SVC. There it answers requests (reads and
// writes of its own data table: the only way another controller reaches it), takes acks and
// replies (ST, DN, ER and the error code), times messages out, unloads the queue into free
// buffers and sends what the buffers hold.
//
// Lockstep and determinism: station 0 (the leader) is the Runtime the caller drives. After each of
// its scans, the network runs every other station's scans and every station's end-of-scan
// servicing in one order, smallest virtual time first, ties by station index, until all have
// reached the leader's time. Every frame is sent at a servicing point and takes more than zero
// time, so when a station services at time t every frame that reaches it by t has already been
// sent: the order is causal, and two runs give byte-identical results. (An SVC in the middle of a
// scan sees the frames sent up to the start of that scan by stations the lockstep has already run;
// docs/semantics.md "MSG".) Nothing is dropped: every queue is bounded by the processor's own
// limits (14 messages a channel, the MSG's WQ bit beyond), and frames in flight by them.
//
// DF1 full-duplex (vm/df1_link.h): a station's channel 0 may instead be a DF1 port joined point to point to
// another station's (the leader and one peer). A message there is handed to the port's transmitter at the
// servicing point that sends it; the link's exchange (frames, ACK/NAK, ENQ, retries, duplicates) is computed
// at once, and what it leads to is posted as the timed frames above: the ACK (ST), each packet the far end's
// sink takes (a Request; a reply is its own transfer back), or the failure (07h). The far end answers the
// command at its servicing points with the same code as on the other links.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "instructions/message_link.h"
#include "parser/address.h"
#include "vm/df1_link.h"
#include "vm/modbus_slave.h"
#include "vm/virtual_time.h"

namespace softslc {

class Runtime;
class ModbusMaster;
struct MessageInstruction;

// The controllers on a Modbus RTU master's line whose channel 0 is a Modbus RTU slave (implemented by
// MessageNetwork, used by vm/modbus_master.h).
class ModbusPeerLine {
 public:
  virtual ~ModbusPeerLine() = default;
  // A request frame to `address` (0: a broadcast, which no slave answers) sent at `baud`, its PDU, complete
  // (its end-of-frame silence passed) at `at`: every controller on the line at that baud rate hears it (and
  // counts it, modbus::SlaveCounters); the one at `address` answers through ModbusMaster::peer_replied with
  // `serial`.
  virtual void deliver(int address, std::uint64_t serial, std::vector<std::uint8_t> pdu, std::int64_t baud,
                       VirtualTime at) = 0;
};

// The control block word 0 bits (RM 12-31, table 12.11) and word 7's WQ (RM 12-29).
namespace msg {
inline constexpr std::uint16_t kEN = 1u << 15;
inline constexpr std::uint16_t kST = 1u << 14;
inline constexpr std::uint16_t kDN = 1u << 13;
inline constexpr std::uint16_t kER = 1u << 12;
inline constexpr std::uint16_t kCO = 1u << 11;
inline constexpr std::uint16_t kEW = 1u << 10;
inline constexpr std::uint16_t kNR = 1u << 9;
inline constexpr std::uint16_t kTO = 1u << 8;
inline constexpr std::uint16_t kErrorCode = 0x00FF;
inline constexpr std::uint16_t kWQ = 1u << 0;  // word 7

// Error codes (RM 12-41/12-42 table 12.17; the E0h-F1h codes as 1762-RM001C p. 21-22 lists them,
// RM 12-43 was not reachable: docs/semantics.md "MSG").
inline constexpr std::uint8_t kBadParameters = 0x04;     // "does not understand the command parameters OR the
                                                          // control block may have been inadvertently modified"
inline constexpr std::uint8_t kNoResponse = 0x07;        // "Target node does not respond"
inline constexpr std::uint8_t kNoSuchFile = 0x10;        // "... or the data file specified does not exist"
inline constexpr std::uint8_t kUnsupportedCommand = 0x10;  // the same code: "incorrect command parameters or
                                                            // unsupported command" (1761-6.3 p. 13-11)
inline constexpr std::uint8_t kNodeTooHigh = 0x16;       // "Target ... address is higher than the maximum node address"
inline constexpr std::uint8_t kBroadcast = 0x18;         // "Broadcast (Node Address 255) is not supported" (the
                                                          // MicroLogix 1000's table, 1761-6.3 p. 13-11)
inline constexpr std::uint8_t kTimedOut = 0x37;          // "Message timed out in local processor"
inline constexpr std::uint8_t kAddressUnusable = 0xE6;   // "Illegal Address, address does not exist"
inline constexpr std::uint8_t kPastEnd = 0xEA;           // "transaction size plus word address is too large"
inline constexpr std::uint8_t kIllegalFileType = 0xF1;   // "illegal target file type"
inline constexpr std::uint8_t kServiceUnsupported = 0x17;  // "Local service is not supported": softslc's code for
                                                           // what it does not simulate (MultiHop, AO=1)
// The Ethernet codes as 1762-RM001C lists them (D7H-DAH on p. 21-22; D0H-D6H on p. 21-21, which could not be
// reached: their texts are [U], docs/semantics.md "MSG on Ethernet").
inline constexpr std::uint8_t kNoIpConfigured = 0xD0;    // "No IP address configured for the network" [U]
inline constexpr std::uint8_t kBadIpAddress = 0xD2;      // "Invalid internet address or host name" [U]
inline constexpr std::uint8_t kConnectionTimeout = 0xD5;  // "Connection not completed before user-specified timeout" [U]
inline constexpr std::uint8_t kReplyTimeout = 0xD9;      // "Reply not received before user-specified timeout."
// "Bad MSG file parameter for building message" (1766-RM001A p. 466): a MicroLogix channel 1 MSG whose RI
// routing element (MG word 24) is not an RI element of the program, or whose subtype is neither 10h nor 11h.
inline constexpr std::uint8_t kBadMessageFile = 0x21;

// The MicroLogix MG element keeps the control word's bits in two words: EN and TO in word 16 (the control
// bits, [U] positions: docs/semantics.md "The MG and RI files"), ST, DN, ER and EW in word 17 at the same
// positions as the SLC's word 0 (1762-RM001C p. 21-6), and the error code in word 18 (ERR). It has no CO,
// NR or WQ.
inline constexpr std::uint16_t kMgControlBits = kEN | kTO;
inline constexpr std::uint16_t kMgStatusBits = kST | kDN | kER | kEW;

// The MG element at `block` as the SLC control word (bits above, the code in the low byte), read with
// read(index) and written with write(index, value) on whatever holds the table: a station of the
// network, or the process host of a channel that acts in events (the Modbus master).
template <class Read>
std::uint16_t mg_status_word(std::uint32_t block, Read read) {
  return static_cast<std::uint16_t>((read(block + mg::kControl) & kMgControlBits) |
                                    (read(block + mg::kStatus) & kMgStatusBits) | (read(block + mg::kError) & kErrorCode));
}
template <class Read, class Write>
void set_mg_status_word(std::uint32_t block, std::uint16_t w0, Read read, Write write) {
  const std::uint32_t control = block + mg::kControl, st = block + mg::kStatus;
  write(control, static_cast<std::uint16_t>((read(control) & ~kMgControlBits) | (w0 & kMgControlBits)));
  write(st, static_cast<std::uint16_t>((read(st) & ~kMgStatusBits) | (w0 & kMgStatusBits)));
  write(block + mg::kError, static_cast<std::uint16_t>(w0 & kErrorCode));
}

inline constexpr int kBuffersPerChannel = 4;  // RM 12-5: "up to four message instructions per channel"
inline constexpr int kQueuePositions = 10;    // RM 12-41: "Each channel has its own 10-position MSG queue"

// The SLC 5/05's channel 1 (Ethernet) block, RM 12-34 table 12.14: word 11 the data length in bytes (the
// processor writes it at run time, RM D-21), word 12 bit 15 AO (logical ASCII addressing, PLC5 only,
// 1747-10.4 p. 4-3), words 14-34 the target's IP address as a NULL-terminated ASCII string of up to 42
// bytes, the first character in the high byte of word 14, word 35's low byte the Ethernet message type
// (0 not MultiHop; 10h, 11h MultiHop).
inline constexpr std::uint32_t kByteCountWord = 11;
inline constexpr std::uint32_t kAoWord = kMessageAoWord;
inline constexpr std::uint32_t kIpWord = 14;
inline constexpr int kIpBytes = 42;
inline constexpr std::uint32_t kEthernetTypeWord = kEthernetMessageTypeWord;
// The channel's MSG Connection Timeout: 15,000 ms by default (1747-UM011G p. 242; the channel
// configuration is not simulated). A message to an IP address no station has fails when it expires.
inline constexpr Nanoseconds kConnectionTimeoutNs = kEthernetConnectionTimeoutSeconds * kNsPerS;
// The channel's MSG Reply Timeout, "the amount of time (in ms) that the SLC 5/05 will wait for a reply to a
// command that it has initiated via a MSG instruction": 3,000 ms by default (1747-UM011G p. 242).
inline constexpr Nanoseconds kReplyTimeoutNs = kEthernetReplyTimeoutSeconds * kNsPerS;
}  // namespace msg

// An IPv4 address written A.B.C.D (each 0-255 in decimal, leading zeros allowed: the manual's own
// example is 423.156.78.012, RM 12-34), as a 32-bit number with A in the high byte; nullopt when the
// text is not one. format_ipv4 writes it back without leading zeros.
std::optional<std::uint32_t> parse_ipv4(std::string_view text);
std::string format_ipv4(std::uint32_t ip);

// The common interface file a 485CIF message reaches: N9 of an SLC (docs/semantics.md "MSG"), N7 of a
// MicroLogix 1000 (1761-6.2 p. 15-3: CIF messages to a MicroLogix 1000 reach N7, to an SLC 500 N9).
inline constexpr int kCommonInterfaceFile = 9;
inline constexpr int kMl1000CommonInterfaceFile = 7;

// The file type code in control block word 4: the PCCC typed read/write code of the type (84h S,
// 85h B, 86h T, 87h C, 88h R, 89h N, 8Ah F, 8Bh O, 8Ch I, 8Dh ST, 8Eh A); 0 for a type MSG cannot carry.
std::uint16_t message_file_type_code(FileType t);
std::optional<FileType> message_file_type(std::uint16_t code);

// The time a frame of `bytes` bytes takes on `link` (the link's bit rate; framing EST).
Nanoseconds message_frame_time(MessageLink link, int data_bytes);

// A MSG instruction as the interpreter hands it over when its rung starts a message (EN was 0) or
// its TO bit aborts one (docs/semantics.md "MSG").
struct MessageInstruction {
  bool slc502 = false;       // the 7-word form: one buffer, no WQ, no timer
  // The MicroLogix 1000's MSG, the 7-word form (slc502 is set too) with its own rules (1761-6.3 ch. 13,
  // docs/semantics.md "The MicroLogix 1000 MSG"): EN only once the transmit buffer is free (no queue:
  // EW alone meanwhile), 18h for node 255, no 16h.
  bool ml1000 = false;
  // The MicroLogix 1100-1500 form: `block` is the MG element (control bits in word 16, status in 17, the
  // error code in 18, the setup in 8-14); its element count is the instruction's (docs/semantics.md "The
  // MicroLogix MSG").
  bool micrologix = false;
  int elements = 0;
  bool write = false;
  // 0 500CPU, 1 485CIF, 2 PLC5 (keyword_code of MessageDevice). The targets on a simulated network are
  // SLCs, which answer a PLC5 typed command as a 500CPU one; 485CIF's target is in the control block
  // (N9, the offset): so the network needs no more than the block (docs/semantics.md "MSG and SVC").
  int device = 0;
  // A MicroLogix 1100/1400 Modbus RTU master message (target device MODBUS): its Modbus command, 01-06, 15 or
  // 16 (1763-RM001B p. 366); 0 for every PCCC message. It goes to the channel's ModbusMaster (vm/modbus_master.h).
  int modbus_function = 0;
  int channel = 0;
  std::uint32_t block = 0;   // data-table word index of control block word 0
  std::uint32_t data = 0;    // data-table word index of this controller's data address
  VirtualTime at = 0;        // virtual time of the instruction
};

class MessageNetwork final : public ModbusPeerLine {
 public:
  explicit MessageNetwork(MessageLink link) : link_(link) {}
  MessageNetwork(const MessageNetwork&) = delete;
  MessageNetwork& operator=(const MessageNetwork&) = delete;
  ~MessageNetwork() override;

  // Adds a station. The first one added is the leader. `owned`, when given, is kept alive by the
  // network (the peers a leader's RuntimeOptions named). Returns the station's index.
  // `ip` is the station's IP address on Ethernet (0: none configured, the processor's default).
  std::size_t attach(Runtime& rt, int node, std::string name, std::unique_ptr<Runtime> owned = nullptr,
                     std::uint32_t ip = 0, int segment = 0);
  // Puts channel `channel` of `station` on the DH-485 network `segment` at `node` as well: the 1764-LRP's
  // channel 1, its second serial port (1762-RM001C p. 21-12: "For controllers with 2 channels (1764-LRP
  // processor installed), the channel can be 0 or 1"). Segments are the DH-485 networks of one test, all
  // in this network's virtual time and lockstep; 0 is the network the leader's channel 0 is on
  // (docs/semantics.md "Channel 1 of the 1500 LRP").
  void attach_port(std::size_t station, int channel, int node, int segment);
  // The station with a channel at `node` on `segment` (a DH-485 or DH+ network), if any.
  std::optional<std::size_t> station_on(int segment, int node) const;

  // DF1 full-duplex on channel 0 of `station` (vm/df1_link.h): the port, with its configuration; such a
  // channel is on no DH-485 network. join_df1 joins two ports by the cable (`device DF1 cable removed` opens it).
  void attach_df1(std::size_t station, const Df1Config& config);
  void join_df1(std::size_t a, std::size_t b);
  // Takes the station's network channel off the network (a peer reached only through its DF1 port).
  void leave_network(std::size_t station);
  const Df1Port* df1_port(std::size_t station) const;
  // `device DF1 CHANGE` on the station's port (docs/testing.md "DF1 full-duplex"): "" or why it is refused.
  std::string df1_inject(std::size_t station, std::string_view change, const std::vector<std::string>& args);
  // The port's diagnostic counter `what` (df1_count_named) at `now`.
  std::optional<std::int64_t> df1_observe(std::size_t station, std::string_view what, VirtualTime now) const;

  // Channel 0 of `station` as a Modbus RTU slave (docs/semantics.md "A MicroLogix as a Modbus RTU slave") on the
  // line of `master`, the leader's channel 0: its address, baud rate and map. Such a channel is on no DH-485
  // network and sends no MSG (12h); the requests that reach it are executed at its communications servicing
  // (end of scan, SVC with channel 0 selected) against its data table, through modbus::handle_pdu.
  // Returns "" or why the map does not fit the station's program (modbus::check_map).
  std::string attach_modbus_slave(std::size_t station, const modbus::SlaveOptions& options, ModbusMaster& master);
  // The station whose channel 0 is a Modbus RTU slave at `address`, if any.
  std::optional<std::size_t> modbus_slave_at(int address) const;
  // ModbusPeerLine.
  void deliver(int address, std::uint64_t serial, std::vector<std::uint8_t> pdu, std::int64_t baud,
               VirtualTime at) override;

  MessageLink link() const { return link_; }
  std::size_t size() const { return stations_.size(); }
  Runtime& runtime(std::size_t station) const { return *stations_[station].rt; }
  const std::string& name(std::size_t station) const { return stations_[station].name; }
  int node(std::size_t station) const { return stations_[station].node; }
  std::uint32_t ip(std::size_t station) const { return stations_[station].ip; }

  // The interpreter's calls (through the Runtime): a MSG rung starts a message; a MSG's TO bit
  // aborts the one in progress.
  void start(std::size_t station, const MessageInstruction& m);
  void abort(std::size_t station, std::uint32_t block);
  // SVC: services the channels in `channel_mask` of `station` now.
  void service_now(std::size_t station, VirtualTime at, std::uint16_t channel_mask);
  // A station finished a scan at `end`: its end-of-scan servicing is due then. For the leader this
  // also runs the lockstep up to `end` (see the header comment).
  void scanned(std::size_t station, VirtualTime end);
  // For repeated scans (docs/semantics.md "Repeated scans"): when `station` is alone on the network
  // and its servicing at `at` left nothing to send or to move into a buffer, the time before which
  // no servicing would change anything (the first frame to arrive, the next whole second of a
  // message's timer words, a timeout; the largest time when nothing is in flight). nullopt when
  // another station is on the link (its scans could send at any time) or something waits to go out.
  std::optional<VirtualTime> quiet_until(std::size_t station, VirtualTime at) const;
  // For repeated cycles (docs/semantics.md "Repeated cycles"): what the network holds for `station` that the
  // data table does not show, as numbers in `out` (replaced): each channel's messages in its buffers and
  // queue (serial, whether sent, when acknowledged) and the frames waiting for it (arrival, sequence).
  // Two equal holdings are the same messages in the same states: a serial is never reused.
  void holdings(std::size_t station, std::vector<std::uint64_t>& out) const;

 private:
  struct Message {
    std::uint64_t serial = 0;
    MessageInstruction in;
    int target_node = 0;
    std::uint32_t target_ip = 0;  // Ethernet: the address the block's string names
    int elements = 0;
    int words = 0;            // data words (elements x words per element)
    int target_file = 0;
    std::uint16_t type_code = 0;
    int target_element = 0;
    VirtualTime started = 0;  // the timer starts with the rung (1762-RM001C p. 21-12)
    // The whole seconds since `started` at the last call of seconds_at, and when the next second begins
    // (after `started`): every servicing and quiet_until ask, most of them within the same second, and
    // virtual time only moves forward, so the division is made once a second.
    mutable std::int64_t seconds = 0;
    mutable Nanoseconds second_end = kNsPerS;
    std::int64_t seconds_at(VirtualTime at) const {
      const Nanoseconds elapsed = at - started;
      if (elapsed >= second_end) {
        seconds = elapsed / kNsPerS;
        second_end = (seconds + 1) * kNsPerS;
      }
      return seconds;
    }
    // When the whole second after the one `at` is in begins (quiet_until's bound for the seconds word).
    VirtualTime next_second_at(VirtualTime at) const {
      seconds_at(at);
      return started + second_end;
    }
    Nanoseconds timeout = 0;  // 0: no timer
    bool sent = false;
    std::optional<VirtualTime> acked;  // Ethernet: when the target acknowledged (the reply timeout runs from there)
    std::vector<std::uint16_t> data;  // a write's data, buffered when the message enters a buffer
  };
  struct Channel {
    std::vector<Message> buffers;  // at most kBuffersPerChannel (1 on the 5/02)
    std::vector<Message> queue;    // at most kQueuePositions, FIFO
  };
  enum class FrameKind : std::uint8_t { Request, Ack, NoAck, Reply };
  struct Frame {
    FrameKind kind = FrameKind::Request;
    std::size_t from = 0;        // the station that sent it
    int channel = 0;             // the receiving station's channel it arrives on (serviced with that channel)
    int reply_channel = 0;       // Request: the sender's channel, where the reply goes
    std::uint64_t serial = 0;    // the message it belongs to
    bool write = false;
    bool cif = false;            // a 485CIF request: the target answers from its common interface file
    int file = 0;
    std::uint16_t type_code = 0;
    int element = 0;
    int words = 0;
    std::uint8_t error = 0;            // Reply, NoAck: 0 or the MSG error code
    std::vector<std::uint16_t> data;   // a write's data, a read's reply data
    // A Request that came over DF1: the reply goes back over the link, with these header fields.
    bool df1 = false;
    int dst = 0, src = 0;
    std::uint16_t tns = 0;
  };
  struct Station {
    Runtime* rt = nullptr;
    std::shared_ptr<Runtime> owned;  // shared_ptr: Runtime is incomplete here
    int node = 0;
    std::uint32_t ip = 0;
    std::string name;
    std::array<Channel, 2> channels;
    // Each channel's node on this network and the segment (DH-485 network) it is on; -1: the channel is
    // not on it (a MicroLogix 1100/1400's other channel, a 1764-LRP's channel 1 given no network).
    std::array<int, 2> port_node{-1, -1};
    std::array<int, 2> port_segment{0, 0};
    // The frames on their way to this station, by (arrival, sequence): a few at most, so a sorted vector
    // (a post allocates nothing once it has grown).
    struct Arrival {
      VirtualTime at = 0;
      std::uint64_t sequence = 0;
      Frame frame;
    };
    std::vector<Arrival> inbox;
    // channel_link of each channel, kept by refresh_links whenever what decides it changes (attach, a
    // port, DF1, a Modbus slave): asked at every servicing.
    std::array<MessageLink, 2> links{};
    std::optional<VirtualTime> service_due;
    // Channel 0 as a DF1 full-duplex port, the station at the cable's other end, and whether the cable is
    // connected (kept the same at both ends).
    std::optional<Df1Port> df1;
    std::optional<std::size_t> df1_partner;
    bool df1_cable = true;
    // Channel 0 as a Modbus RTU slave: its configuration and the requests that reached it, in arrival order
    // (the master sends one at a time: a broadcast and the request behind it at most).
    struct ModbusRequest {
      VirtualTime arrival = 0;
      std::uint64_t serial = 0;
      bool broadcast = false;
      bool to_this = true;  // false: a frame to another address, only counted as seen
      std::vector<std::uint8_t> pdu;
    };
    std::optional<modbus::SlaveOptions> modbus_slave;
    modbus::SlaveCounters modbus_counters;
    std::vector<ModbusRequest> modbus_requests;
    // Each channel's CSn:4 word, where the program has the CS file, and the MCP bit this network last
    // wrote there (docs/semantics.md "The CS file"): written only when it changes, so that a channel 0
    // Modbus master (vm/modbus_master.h), which keeps the bit for its own messages, is not overwritten.
    std::array<std::optional<std::uint32_t>, 2> status_word;
    std::array<bool, 2> command_pending{};
  };

  // How many messages the channel's buffers take: four, or one while the 5/02's message is at the
  // queue's front (RM 12-41).
  static std::size_t buffer_limit(const Channel& ch);
  void service(std::size_t station, VirtualTime at, std::uint16_t channel_mask);
  // MCP, "Outgoing Message Command Pending" (1762-RM001C p. 21-27): set while a channel holds a message
  // not yet sent (in the queue or a buffer), cleared by the servicing that sends the last one.
  void publish_command_pending(std::size_t station);
  void start_message(std::size_t station, const MessageInstruction& m);
  void service_channel(std::size_t station, VirtualTime at, int channel);
  // Executes the Modbus requests that reached `station`'s channel 0 by `at` and starts their replies.
  void serve_modbus(std::size_t station, VirtualTime at);
  void run_lockstep(VirtualTime until);
  void receive(std::size_t station, VirtualTime at, Frame& f);
  void answer(std::size_t station, VirtualTime at, const Frame& request);
  void finish(std::size_t station, Message& m, std::uint8_t error, std::uint16_t extra_bits = 0);
  void send(std::size_t station, VirtualTime at, Message& m);
  void send_df1(std::size_t station, VirtualTime at, Message& m);
  // The request frame of `m` from `station`, arriving on the target's `channel`.
  static Frame request_frame(std::size_t station, const Message& m, int channel);
  void reply_df1(std::size_t station, VirtualTime at, const Frame& request, const Frame& reply);
  // The far end of `station`'s DF1 port and whether it hears this end (cable connected, same baud and parity).
  Df1Port* df1_far(std::size_t station, bool* line_ok);
  void post(std::size_t to, VirtualTime arrival, Frame f);
  void enter_buffer(std::size_t station, Message& m);
  Message* find(std::size_t station, std::uint64_t serial, int* channel = nullptr, bool* queued = nullptr);
  void remove(std::size_t station, std::uint64_t serial);
  std::uint16_t word(std::size_t station, std::uint32_t index) const;
  // The MSG's control word in the SLC layout (word 0 of its block), for either form: on a MicroLogix it is
  // put together from the MG element's words 16-18 and written back into them.
  std::uint16_t status(std::size_t station, const MessageInstruction& in) const;
  void set_status(std::size_t station, const MessageInstruction& in, std::uint16_t w0);
  void set_word(std::size_t station, std::uint32_t index, std::uint16_t value);
  // The station and its channel at `node` on `segment`.
  std::optional<std::pair<std::size_t, int>> port_at(int segment, int node) const;
  std::optional<std::size_t> station_at_ip(std::uint32_t ip) const;
  std::uint8_t check_ethernet_block(std::size_t station, const MessageInstruction& in, Message& m);
  std::uint8_t check_routing_element(std::size_t station, const MessageInstruction& in, Message& m);
  // The channel of `station` this network's link is on: 0 on the SLC 5/02 and on a MicroLogix on DH-485
  // (its serial port), 1 on the SLC 5/03-5/05 and on a MicroLogix 1100/1400 on Ethernet.
  int network_channel(std::size_t station) const;
  // The link a message on `channel` of `station` travels: DF1 on a channel 0 configured for it; None on
  // an SLC 5/03-5/05's channel 0 that is not (its MSG ends with 12h); this network's on a channel that is on it; on
  // the other channel of a MicroLogix 1100/1400 (Ethernet when it is on DH-485, DH-485 when it is on
  // Ethernet) a link no other station is on (docs/semantics.md "The MicroLogix MSG on Ethernet"); on a
  // 1764-LRP's channel 1 given no network, DH-485 with no other station.
  MessageLink channel_link(std::size_t station, int channel) const { return stations_[station].links[channel & 1]; }
  MessageLink find_channel_link(std::size_t station, int channel) const;
  void refresh_links(std::size_t station);

  MessageLink link_;
  std::vector<Station> stations_;
  std::uint64_t next_serial_ = 1;
  std::uint64_t next_frame_ = 1;
  bool driving_ = false;
  std::vector<std::uint64_t> expired_, late_;  // service_channel's, kept so that a servicing allocates nothing
  // The leader's channel 0 as a Modbus RTU master when some station's channel 0 is a slave on its line: the
  // lockstep then runs the leader's events in time order with the other stations' scans (run_lockstep).
  ModbusMaster* modbus_master_ = nullptr;
};

}  // namespace softslc
