// Explicit Message Program Control transaction blocks (appendix E, p.143-151): the 32-word blocks
// the ladder writes to M0:224...255 (requests) and reads from M1:224...255 (responses).
//
// Byte layout (word offsets from 224; "hi:lo" = high byte : low byte of the word). The manual's
// figure (p.145/148) is missing from our copy; this is the layout of the 1747-SDN family's figure,
// and it is the layout the DEM control block embeds at its words 6...37 and 38...69 (chapter 8,
// p.101), which is how we checked it:
//
//          request (M0)                              response (M1)
//   +0     TXID : command                            TXID : status
//   +1     port : size (body bytes)                  port : size (body bytes)
//   +2     service : MAC ID                          service : MAC ID
//   +3     reserved : class                          reply data bytes 0, 1   (low byte first)
//   +4     instance (16 bits)                        reply data bytes 2, 3
//   +5     reserved : attribute (0 = none)           ...
//   +6...31 service data, 2 bytes a word,            ... up to +31: 29 words = 58 bytes
//           low byte first (at most 26 words = 52 bytes)
//
// A request body is class, instance and attribute (3 words, 6 bytes, always counted) plus the
// service data, so its size is 6...58; a response body is the reply data only, 0...58 bytes.
// This is why the DEM's "Size of Send Data" maximum is 52 bytes and its reply data 58 (p.94-95).
// The reserved bytes are ignored on input and written 0.
//
// Decoding is total: every combination of 32 words decodes to a RequestBlock, and check_request()
// gives every malformed one a defined status (13 invalid port, 14 invalid size); nothing reads
// outside the block whatever the size byte says. The decoder is fuzzed on that property.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "modules/devicenet/cip.h"

namespace softslc::devicenet {

enum class TxnCommand : std::uint8_t {
#define TXN_COMMAND(value, name, text) name = value,
#include "modules/devicenet/transaction_codes.def"
#undef TXN_COMMAND
};
enum class TxnStatus : std::uint8_t {
#define TXN_STATUS(value, name, text) name = value,
#include "modules/devicenet/transaction_codes.def"
#undef TXN_STATUS
};
std::string_view txn_command_text(std::uint8_t command);  // "" for reserved values
std::string_view txn_status_text(std::uint8_t status);    // "" for reserved values

using Block = std::array<std::uint16_t, 32>;

inline constexpr int kRequestPathBytes = 6;    // class, instance, attribute words
inline constexpr int kMaxBodyBytes = 58;       // 29 words
inline constexpr int kMaxRequestDataBytes = 52;

struct RequestBlock {
  std::uint8_t command = 0;
  std::uint8_t txid = 0;
  std::uint8_t port = 0;
  std::uint8_t size = 0;  // body bytes as written (may be invalid)
  std::uint8_t service = 0;
  std::uint8_t mac = 0;
  std::uint8_t class_id = 0;
  std::uint16_t instance = 0;
  std::uint8_t attribute = 0;
  Bytes data;  // min(max(size - 6, 0), 52) bytes of service data
};

struct ResponseBlock {
  std::uint8_t status = 0;
  std::uint8_t txid = 0;
  std::uint8_t port = 0;
  std::uint8_t service = 0;
  std::uint8_t mac = 0;
  Bytes data;  // at most 58 bytes; size = data.size()
};

RequestBlock decode_request(std::span<const std::uint16_t, 32> words);
Block encode_request(const RequestBlock& r);  // size as given in r.size
ResponseBlock decode_response(std::span<const std::uint16_t, 32> words);
Block encode_response(const ResponseBlock& r);

// The status an execute request gets before it reaches the network, if it is malformed:
// InvalidPort (port != 0) or InvalidSize (size < 6 or > 58). nullopt = well formed.
std::optional<TxnStatus> check_request(const RequestBlock& r);
// The CIP request an execute block carries (attribute byte only when non-zero, chapter 8 p.96).
CipRequest to_cip_request(const RequestBlock& r);

}  // namespace softslc::devicenet
