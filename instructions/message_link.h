// The links an SLC processor's MSG instruction can use, and their facts: which channel of which
// processor is on which link, the node addresses a link has, its data rate, and the largest message.
//
// softslc simulates one link per network (vm/message_network.h): DH-485 (the SLC 5/02's only
// channel, the SLC 5/03's channel 1), DH+ (the SLC 5/04's channel 1) and Ethernet (the SLC 5/05's
// channel 1, whose stations are named by IP address instead of a node number). Every 5/03-5/05
// channel 0 is the RS-232 port; MSG on it is refused by `check`, so every MSG that loads runs on a
// link described here. Sources: 1747-RM001G p. 12-14 (channels), p. 13-4 (DH-485 nodes), p. 12-34
// table 12.14 and p. D-21 table D.5 (the 5/05's Ethernet block and message lengths), 1747-SG001
// p. 64 (DH+ rates).
#pragma once

#include <cstdint>
#include <string_view>
#include <utility>

#include "instructions/processor.h"
#include "parser/address.h"

namespace softslc {

enum class MessageLink : unsigned char { None, Dh485, DhPlus, Ethernet, Df1 };

// The link `channel` of a processor of `family` is on (None: a channel softslc does not simulate
// for MSG, or one the processor does not have).
constexpr MessageLink message_link(ProcessorFamily family, int channel) {
  switch (family) {
    case ProcessorFamily::Slc502: return channel == 0 ? MessageLink::Dh485 : MessageLink::None;
    // Channel 0 of the 5/03-5/05, the RS-232 port: DF1 full-duplex, the only System-mode link softslc
    // simulates there and its factory configuration (docs/semantics.md "Channel 0"); a MSG on a channel 0
    // in User (ASCII) mode ends with 12h at run time.
    case ProcessorFamily::Slc503: return channel == 1 ? MessageLink::Dh485 : channel == 0 ? MessageLink::Df1 : MessageLink::None;
    case ProcessorFamily::Slc504: return channel == 1 ? MessageLink::DhPlus : channel == 0 ? MessageLink::Df1 : MessageLink::None;
    case ProcessorFamily::Slc505: return channel == 1 ? MessageLink::Ethernet : channel == 0 ? MessageLink::Df1 : MessageLink::None;
    // A MicroLogix's channel 0, its serial port, taken to be configured for DH-485 (network_link below).
    case ProcessorFamily::MicroLogix: return channel == 0 ? MessageLink::Dh485 : MessageLink::None;
    default: return MessageLink::None;
  }
}

// The link a processor's network channel is on: DH-485 for the fixed controllers, the 5/01, 5/02 and
// 5/03 (they all answer messages on it), DH+ for the 5/04, Ethernet for the 5/05. A MicroLogix is on
// DH-485 through its channel 0, the serial port, configured for DH-485 (1762-RM001C p. 21-2 lists DH-485
// among the protocols its MSG uses; decision: DH-485 unless a test or the API makes channel 0 a DF1 port
// or a Modbus RTU master, docs/semantics.md "The MicroLogix MSG"); the 1000 sends its messages there too (1761-6.2 p. 15-3: DH-485 with a MicroLogix
// 1000 "except for Series A and B discrete controllers", and with every SLC 500; docs/semantics.md "The
// MicroLogix 1000 MSG").
constexpr MessageLink network_link(ProcessorFamily family) {
  switch (family) {
    case ProcessorFamily::Fixed:
    case ProcessorFamily::Slc501:
    case ProcessorFamily::Slc502:
    case ProcessorFamily::Slc503:
    case ProcessorFamily::MicroLogix: return MessageLink::Dh485;
    case ProcessorFamily::Slc504: return MessageLink::DhPlus;
    case ProcessorFamily::Slc505: return MessageLink::Ethernet;
    default: return MessageLink::None;
  }
}

// The link a station is on in softslc's one-link network: its family's network_link, except that a
// MicroLogix 1100 or 1400 given an IP address is on its channel 1, the embedded EtherNet/IP port
// (1763-RM001B p. 384, 1766-RM001A p. 435), with the SLC 5/05s. Decision: softslc has no channel
// configuration, and the IP address a test gives the controller is what configures that port (its
// default IP address is 0, "undefined", 1766-UM001O p. 286); without one it is on channel 0, DH-485
// (docs/semantics.md "The MicroLogix MSG on Ethernet").
inline MessageLink station_link(const ProcessorModel& p, bool has_ip) {
  if (p.has_routing_files() && has_ip) return MessageLink::Ethernet;
  return network_link(p.family);
}

// The node addresses a MSG may name on a link. DH-485: "The node address range for all responders
// is 1 to 31" and an SLC processor never has node 0 (RM 13-4). DH+: 0-77 octal (64 stations).
// Ethernet has no node numbers: the target is the IP address string in the control block (RM 12-34).
// DF1: station addresses 0-254 ("Source ID (Node Address) 0...254 decimal", 1766-RM001A p. 592); on a
// full-duplex link the receiver ignores the destination (1747-RM001G p. 13-49).
constexpr std::pair<int, int> message_node_range(MessageLink link) {
  return link == MessageLink::Dh485 ? std::pair{1, 31} : link == MessageLink::Df1 ? std::pair{0, 254} : std::pair{0, 63};
}

// The link's data rate in bits per second and bits sent per byte: DH-485 19,200 baud with 11-bit
// characters (start, 8 data, parity, stop); DH+ 57,600 baud, 8 bits a byte (1747-SG001 p. 64: 57.6K
// the default); Ethernet 10 Mbit/s (10BASE-T, the rate every SLC 5/05 series has; [U]). The default
// rates, not the channel configuration (not simulated).
constexpr int message_link_baud(MessageLink link) {
  switch (link) {
    case MessageLink::Dh485: return 19200;
    case MessageLink::Ethernet: return 10'000'000;
    default: return 57600;
  }
}
constexpr int message_link_bits_per_byte(MessageLink link) { return link == MessageLink::Dh485 ? 11 : 8; }

// The bytes a frame carries besides its data (EST). DH-485 and DH+: 16, the link framing and the PCCC
// header of a typed read or write. Ethernet: 106, the Ethernet II frame with preamble and FCS (26),
// IPv4 (20) and TCP (20) headers, the 24-byte encapsulation header and the same 16 PCCC bytes.
constexpr int message_frame_overhead_bytes(MessageLink link) { return link == MessageLink::Ethernet ? 106 : 16; }

// The most data words one MSG carries on DH-485 and DH+: 103 one-word elements, 51 two-word, 34
// three-word (1762-RM001C p. 21-12, the MicroLogix table of the same message types; the SLC table,
// 1747-RM001G appendix D, was not reachable: docs/semantics.md "MSG").
inline constexpr int kMessageMaxWords = 103;

// The SLC 5/05's channel 1 (Ethernet) control block: 51 words (RM 12-34 table 12.14); word 35's low
// byte is the Ethernet message type (0 not MultiHop, 10h and 11h MultiHop), word 12 bit 15 AO.
inline constexpr int kEthernetMessageBlockWords = 51;
inline constexpr int kEthernetMessageTypeWord = 35;
inline constexpr int kMessageAoWord = 12;
inline constexpr std::uint16_t kMessageAoBit = 1u << 15;

// Word 35's low byte names a MultiHop message (10h or 11h), which softslc does not simulate: `check`
// refuses one a DATA block sets up, the network ends one a program writes with 17h.
constexpr bool is_multihop_message_type(std::uint16_t word35) {
  const unsigned type = word35 & 0xFFu;
  return type == 0x10 || type == 0x11;
}

// The most elements one MSG carries on the SLC 5/05's Ethernet channel, by the local file's type: RM
// p. D-21 table D.5 "SLC 5/05 Message Lengths" (an Ethernet buffer of 2108 bytes), the 485CIF and
// 500CPU column: 256 of O, I, B, T, C, R, N, F, A; 83 of S; 25 of ST (24 for a 500CPU write). The
// PLC5 columns differ for T (208 elements when the target file is a timer file) and ST (11).
constexpr int ethernet_max_elements(FileType local, bool plc5, bool write) {
  switch (local) {
    case FileType::Status: return 83;
    case FileType::String: return plc5 ? 11 : write ? 24 : 25;
    case FileType::Timer: return plc5 ? 208 : 256;
    default: return 256;
  }
}

// The Ethernet channel's MSG Connection Timeout and MSG Reply Timeout, at their defaults: softslc has no
// channel configuration. SLC 5/05: 15,000 ms and 3,000 ms (1747-UM011G p. 242). MicroLogix 1400: MSG
// Reply Timeout 3,000 ms (1766-UM001O p. 287, table 43); its MSG Connection Timeout row was not reached
// and is taken to be the 5/05's 15,000 ms [U]; the MicroLogix 1100's channel configuration was not reached
// either and is taken to be the same [U] (docs/semantics.md "The MicroLogix MSG on Ethernet").
inline constexpr int kEthernetConnectionTimeoutSeconds = 15;
inline constexpr int kEthernetReplyTimeoutSeconds = 3;
// "Message Timeout for any MicroLogix 1400 channel 1 MSG can not be modified in the Ethernet Message
// Setup dialog box. It is assigned by the processor and is determined by adding the Channel 1 MSG
// Connection Timeout to the MSG Reply Timeout, then adding 15 seconds" (1766-RM001A p. 421): 33 s.
inline constexpr int kMl1400EthernetMessageTimeoutSeconds =
    kEthernetConnectionTimeoutSeconds + kEthernetReplyTimeoutSeconds + 15;

// The RI element's subtype (word 0, 1766-RM001A p. 435): 10h a MultiHop message straight to the IP
// address in words 1-2 (every channel 1 MSG of the 1100/1400 is a MultiHop one, its first hop the IP
// address); 11h remote MultiHop to DH+ through a bridge, which softslc does not simulate.
inline constexpr std::uint16_t kRoutingLocal = 0x10;
inline constexpr std::uint16_t kRoutingRemoteDhPlus = 0x11;
// The IP address in the RI element's words 1 and 2, "stored in network byte order (big-endian order)"
// as the manual's table lays it out (1766-RM001A p. 435: 10.121.30.11 is word 1 = 790Ah, word 2 =
// 0B1Eh): each word holds two of the address's bytes, the earlier one in its low byte.
constexpr std::uint32_t routing_ip(std::uint16_t word1, std::uint16_t word2) {
  return (static_cast<std::uint32_t>(word1 & 0xFFu) << 24) | (static_cast<std::uint32_t>(word1 >> 8) << 16) |
         (static_cast<std::uint32_t>(word2 & 0xFFu) << 8) | static_cast<std::uint32_t>(word2 >> 8);
}
constexpr std::uint16_t routing_ip_word(std::uint32_t ip, int word) {
  const std::uint32_t earlier = word == 1 ? ip >> 24 : (ip >> 8) & 0xFFu;
  const std::uint32_t later = word == 1 ? (ip >> 16) & 0xFFu : ip & 0xFFu;
  return static_cast<std::uint16_t>(earlier | (later << 8));
}
static_assert(routing_ip(0x790A, 0x0B1E) == 0x0A791E0Bu, "1766-RM001A p. 435: 10.121.30.11");
static_assert(routing_ip_word(0x0A791E0Bu, 1) == 0x790A && routing_ip_word(0x0A791E0Bu, 2) == 0x0B1E);

// The MSG's target device MODBUS ("Target Device: Modbus Device"): its code, the keyword's position among the
// target devices (instructions/instruction_table.cpp: 500CPU 0, 485CIF 1, PLC5 2, MODBUS 3).
inline constexpr int kModbusDeviceCode = 3;

// The eight Modbus commands of the MicroLogix MSG (1763-RM001B p. 366, "Modbus Command Types"): 01 Read Coil
// Status, 02 Read Input Status (bits), 03 Read Holding Registers, 04 Read Input Registers (words), 05 Write
// Single Coil, 06 Write Single Register, 15 Write Multiple Coils, 16 Write Multiple Registers.
namespace modbus {
constexpr bool is_command(int f) { return (f >= 1 && f <= 6) || f == 15 || f == 16; }
constexpr bool is_bit_command(int f) { return f == 1 || f == 2 || f == 5 || f == 15; }
constexpr bool is_write_command(int f) { return f == 5 || f == 6 || f == 15 || f == 16; }
constexpr bool is_single_command(int f) { return f == 5 || f == 6; }
// Slave addresses: 1-247, 0 a broadcast (writes only).
inline constexpr int kMaxSlave = 247;
// Exception codes a slave answers with (Modbus application protocol), and the MSG error code they give:
// 80h + the exception code, "81H Modbus Error 1: Illegal Function", "82H ... Illegal Data Address", ...
// (1747-RM001G p. 12-42; AG-UM008C p. 3-55 "Received Exception Code" for the MicroLogix 1100/1200/1500).
// The simulated slaves answer exception 01 (illegal function) and 02 (illegal data address), server/modbus.h's
// kIllegalFunction and kIllegalDataAddress (the Modbus application protocol's codes).
inline constexpr std::uint8_t kExceptionErrorBase = 0x80;
// 12h "local channel configuration protocol error" (1766-RM001A p. 466): a Modbus MSG on a channel 0 that is
// not a Modbus RTU master, or a PCCC MSG on channel 0 when it is one (docs/semantics.md, decision).
inline constexpr std::uint8_t kChannelProtocol = 0x12;
// Frame sizes in bytes, address and CRC included (Modbus over serial line, RTU).
constexpr int request_bytes(int f, int n) {
  return f == 15 ? 9 + (n + 7) / 8 : f == 16 ? 9 + 2 * n : 8;
}
constexpr int reply_bytes(int f, int n) {
  return f == 1 || f == 2 ? 5 + (n + 7) / 8 : f == 3 || f == 4 ? 5 + 2 * n : 8;
}
inline constexpr int kExceptionReplyBytes = 5;
inline constexpr int kBitsPerCharacter = 11;
}  // namespace modbus

constexpr std::string_view to_string(MessageLink link) {
  switch (link) {
    case MessageLink::Dh485: return "DH-485";
    case MessageLink::DhPlus: return "DH+";
    case MessageLink::Ethernet: return "Ethernet";
    case MessageLink::Df1: return "DF1 full-duplex";
    case MessageLink::None: break;
  }
  return "none";
}

}  // namespace softslc
