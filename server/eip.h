// EtherNet/IP encapsulation and the CIP messages an SLC 5/05 answers, without any sockets.
//
// A frame is a 24-byte encapsulation header (all fields little-endian: command u16, length u16,
// session handle u32, status u32, sender context 8 bytes, options u32) followed by `length`
// bytes of command data. EipSession holds one TCP connection's protocol state (its registered
// session) and turns each whole request frame into a reply frame, or into "close this
// connection" with the reason; it owns no I/O, so the fuzz target and the unit tests drive it
// exactly as the network server does, and a malformed frame can never reach the data table.
//
// Commands (CIP Vol. 2, chapter 2): NOP 0000h (no reply), ListServices 0004h, ListIdentity
// 0063h, ListInterfaces 0064h (an empty list), RegisterSession 0065h, UnRegisterSession 0066h
// (closes), SendRRData 006Fh. SendRRData carries a common packet format (CPF) with a null address
// item (0000h) and an unconnected data item (00B2h) holding a CIP request:
//   4Bh Execute PCCC to class 67h instance 1: requestor ID (length byte, vendor u16, serial
//       u32, any extra bytes the length covers), then the PCCC command (server/pccc.h). The reply
//       is CBh, 0, status 0, 0, the requestor ID echoed, the PCCC reply.
//   52h Unconnected Send to the connection manager (class 06h instance 1): the embedded request
//       is executed as if sent directly and its reply returned (the route path is ignored: the
//       processor is the only node).
// Any other service is answered with CIP general status 08h (service not supported), a path to
// another object with 05h (path destination unknown). SendUnitData (connected messaging after a
// Forward Open) is not supported: no client that talks PCCC to an SLC needs it, and the
// encapsulation answers 0001h (invalid command) as an SLC 5/05 without class-3 connections does.
//
// A frame whose command needs a registered session and carries another handle is answered with
// encapsulation status 0064h (invalid session handle); a frame that cannot be parsed — a length
// that disagrees with the bytes, a CPF whose items run past the end — closes the connection.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "server/pccc.h"

namespace softslc::eip {

inline constexpr std::size_t kHeaderSize = 24;
inline constexpr std::uint16_t kPort = 44818;

inline constexpr std::uint16_t kNop = 0x0000;
inline constexpr std::uint16_t kListServices = 0x0004;
inline constexpr std::uint16_t kListIdentity = 0x0063;
inline constexpr std::uint16_t kListInterfaces = 0x0064;
inline constexpr std::uint16_t kRegisterSession = 0x0065;
inline constexpr std::uint16_t kUnRegisterSession = 0x0066;
inline constexpr std::uint16_t kSendRRData = 0x006F;
inline constexpr std::uint16_t kSendUnitData = 0x0070;

inline constexpr std::uint32_t kStatusInvalidCommand = 0x0001;
inline constexpr std::uint32_t kStatusIncorrectData = 0x0003;
inline constexpr std::uint32_t kStatusInvalidSession = 0x0064;
inline constexpr std::uint32_t kStatusUnsupportedProtocol = 0x0069;

struct Header {
  std::uint16_t command = 0;
  std::uint16_t length = 0;
  std::uint32_t session = 0;
  std::uint32_t status = 0;
  std::array<std::uint8_t, 8> context{};
  std::uint32_t options = 0;
};

// Decodes the first 24 bytes (nullopt when fewer).
std::optional<Header> decode_header(std::span<const std::uint8_t> bytes);
// A whole frame: the header (its length set from `data`) and the data.
std::vector<std::uint8_t> encode_frame(Header h, std::span<const std::uint8_t> data);

struct CpfItem {
  std::uint16_t type = 0;
  std::span<const std::uint8_t> data;
};
// Decodes a common packet format: item count, then (type, length, data) per item. nullopt when an
// item runs past the end, bytes are left over, or there are more than 4 items.
std::optional<std::vector<CpfItem>> decode_cpf(std::span<const std::uint8_t> bytes);

// The identity a ListIdentity reply reports.
struct Identity {
  std::uint16_t vendor = 1;          // Rockwell Automation/Allen-Bradley
  std::uint16_t device_type = 0x0E;  // programmable logic controller
  std::uint16_t product_code = 0;
  std::uint8_t major = 1, minor = 0;
  std::uint32_t serial = 0;
  std::string product_name;
  std::uint32_t ipv4 = 0x7F000001;  // host order; the socket address item carries it big-endian
  std::uint16_t port = kPort;
};
// The ListIdentity reply's command data (item count 1, the identity item 000Ch).
std::vector<std::uint8_t> list_identity_data(const Identity& id);

// What happened to one frame.
struct Outcome {
  std::vector<std::uint8_t> reply;  // empty: nothing to send
  bool close = false;                // close the connection after sending the reply
  std::string log;                   // why it closed, or a refused request worth logging
};

// One connection's protocol state.
class EipSession {
 public:
  EipSession(pccc::Target& target, Identity identity, std::uint32_t session_handle)
      : target_(target), identity_(std::move(identity)), handle_(session_handle) {}
  // Handles one whole frame (header and exactly `length` data bytes).
  Outcome handle(std::span<const std::uint8_t> frame);
  bool registered() const { return registered_; }
  std::uint32_t handle_value() const { return handle_; }

 private:
  Outcome send_rr_data(const Header& h, std::span<const std::uint8_t> data);
  // Executes one CIP request; returns the CIP reply (nullopt: malformed, close).
  std::optional<std::vector<std::uint8_t>> cip(std::span<const std::uint8_t> request, int depth, std::string& log);

  pccc::Target& target_;
  Identity identity_;
  std::uint32_t handle_;
  bool registered_ = false;
};

}  // namespace softslc::eip
