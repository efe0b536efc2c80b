// SCANport messages as the 1203-SM1 carries them: M0 request buffers in, M1 response buffers out.
//
// The ladder program writes a request into one of eight M0 buffers, the module sends it to the
// drive on the channel the Message Enable names, and writes the drive's answer into that
// channel's M1 buffer (1203-SM1 manual, Figures 4.9-4.12, B.1, B.2). Both buffers are 100
// words; a word carries two message bytes, the first in its low byte ("in ASCII mode, the
// string is shown in a byte-swapped fashion", appendix B):
//
//   M0:e.n00 request, n = 0-7              M1:e.c00 response, c = channel 1-3
//   +------+---------------------------+   +------+-------------------------------------------+
//   | n00  | service                   |   | c00  | service echo, or 0x0014 on error          |
//   | n01  | class                     |   | c01  | class echo                                |
//   | n02  | instance                  |   | c02  | instance echo                             |
//   | n03  | attribute (< 256)         |   | c03  | attribute echo                            |
//   | n04  | request length, bytes     |   | c04  | response length, bytes (padding included) |
//   | n05  | data byte 2 | data byte 1 |   | c05  | data byte 2 | data byte 1                 |
//   | ...  | up to 96 bytes (scattered |   | ...  | error: c05 = error code (codes.h)         |
//   |      | up to 47 x 4 = 188)       |   |      |                                           |
//   +------+---------------------------+   +------+-------------------------------------------+
//
// The data of each message (byte offsets; "u16" = low byte first, "str n" = n characters,
// space-padded; figure of the manual's example in brackets):
//
//   service class inst attr  request data          response data
//   0x0E    0x0F  0    2     -                     u16 last parameter number            [B.4]
//   0x0E    0x0F  p    a     -                     attribute a of parameter p (table
//                                                  below)                     [B.5, B.6]
//   0x10    0x0F  p    1     value (data size)     -                                    [B.7]
//   0x01    0x0F  p    0     -                     attributes 1, 2, 4-21 concatenated
//                                                  (53 bytes for a 16-bit value)        [B.8]
//   0x05    0x0F  0    0     -                     -   RAM and storage <- defaults      [B.9]
//   0x15    0x0F  0    0     -                     -   RAM <- storage                  [B.10]
//   0x16    0x0F  0    0     -                     -   storage <- RAM                  [B.11]
//   0x4B    0x0F  p    v     -                     str 12, text of value/bit v of p    [B.12]
//   0x0E    0x92  0    0     -                     u16 product number                  [B.13]
//   0x0E    0x92  0    1     -                     str 16 product text                 [B.14]
//   0x0E    0x92  0    3     -                     u16 series (1 = A, 2 = B, ...)      [B.15]
//   0x0E    0x92  m    1     -                     u16 software version of micro m     [B.16]
//   0x32    0x93  0    0     (u16 p, u16 0) x k    (u16 p, u16 value) x k; on error
//                                                  (p | 0x8000, u16 error code)        [B.17]
//   0x34    0x93  0    0     (u16 p, u16 v) x k    (u16 p, u16 0) x k; on error
//                                                  (p | 0x8000, u16 error code)        [B.18]
//   0x0E    0x99  p    0     -                     u16 parameter p is linked to (0 = none) [B.19]
//   0x10    0x99  p    0     u16 link              -                                   [B.20]
//
// A device pads every reply to a multiple of its padding granule for the object
// (DriveDescription::response_padding), so replies B.4, B.13, B.15, B.16 and B.19 carry 2 data bytes in a length of 6.
//
// Totality: decode_request() reads any span of words (missing words read as 0, at most one
// 100-word buffer is looked at), and transact()/serve() answer every Request with either the
// echo and the data above or an error response; no input reads or writes out of bounds.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "modules/scanport/codes.h"
#include "modules/scanport/drive.h"
#include "vm/virtual_time.h"

namespace softslc::scanport {

inline constexpr int kRequestBuffers = 8;       // M0:e.000, .100, ... .700
inline constexpr int kChannels = 3;             // M1:e.100, .200, .300
inline constexpr int kBufferWords = 100;
inline constexpr int kHeaderWords = 5;
inline constexpr int kBufferDataBytes = (kBufferWords - kHeaderWords) * 2;  // 190
inline constexpr int kScatteredEntryBytes = 4;
inline constexpr int kMaxScatteredEntries = 47;  // "can continue on in this pattern for up to 47 parameters"
static_assert(kMaxScatteredEntries * kScatteredEntryBytes == kMaxScatteredRequestBytes);
static_assert(kMaxScatteredRequestBytes <= kBufferDataBytes, "a full scattered list fits one buffer");

// Word offset of request buffer n (0-7) in M0, and of channel c's (1-3) response buffer in M1.
constexpr int request_buffer_word(int n) { return n * kBufferWords; }
constexpr int response_buffer_word(int channel) { return channel * kBufferWords; }

// ---------------------------------------------------------------------------------------------
// Parameter object attributes (the attribute table of "Read Full Parameter", page B-12).
// Columns: enumerator, attribute, meaning, size in bytes (0 = the parameter's value size).
// Read Full Parameter sends the rows in this order; Get Attribute Single sends one row; only
// the value is settable. Attribute 3 (the link path itself) is not in the manual's table: its
// size is "always 0", so the library answers it as an unsupported attribute.
#define SOFTSLC_SCANPORT_PARAMETER_ATTRIBUTES(X)                                       \
  X(kValue, 1, "Parameter value", 0)                                                    \
  X(kLinkPathSize, 2, "Link path size (always 0)", 1)                                   \
  X(kDescriptor, 4, "Descriptor", 2)                                                    \
  X(kDataType, 5, "Data type", 1)                                                       \
  X(kDataSize, 6, "Parameter value data size in bytes", 1)                              \
  X(kName, 7, "Parameter name string: count (16) and 16 characters", 17)                \
  X(kUnits, 8, "Units string: count (4) and 4 characters", 5)                           \
  X(kHelp, 9, "Help string (always 0 indicating no help string)", 1)                    \
  X(kMinimum, 10, "Minimum value", 0)                                                   \
  X(kMaximum, 11, "Maximum value", 0)                                                   \
  X(kDefault, 12, "Default value", 0)                                                   \
  X(kScalingMultiplier, 13, "Scaling multiplier", 2)                                    \
  X(kScalingDivisor, 14, "Scaling divisor", 2)                                          \
  X(kScalingBase, 15, "Scaling base", 2)                                                \
  X(kScalingOffset, 16, "Scaling offset", 2)                                            \
  X(kMultiplierLink, 17, "Multiplier link - parameter containing multiplier value", 2)  \
  X(kDivisorLink, 18, "Divisor link - parameter containing divisor value", 2)           \
  X(kBaseLink, 19, "Base link - parameter containing base value", 2)                    \
  X(kOffsetLink, 20, "Offset link - parameter containing offset value", 2)              \
  X(kDecimalPrecision, 21, "Decimal precision", 1)

enum class ParameterAttribute : std::uint8_t {
#define SOFTSLC_X(name, id, text, size) name = id,
  SOFTSLC_SCANPORT_PARAMETER_ATTRIBUTES(SOFTSLC_X)
#undef SOFTSLC_X
};

struct ParameterAttributeInfo {
  ParameterAttribute attribute;
  std::uint8_t id;
  std::string_view meaning;
  int size;  // 0 = value size
};

inline constexpr ParameterAttributeInfo kParameterAttributes[] = {
#define SOFTSLC_X(name, id, text, size) {ParameterAttribute::name, id, text, size},
    SOFTSLC_SCANPORT_PARAMETER_ATTRIBUTES(SOFTSLC_X)
#undef SOFTSLC_X
};

// Class 0x0F instance 0 attribute 2 ("Attribute=Last Parameter Number", Figure B.4).
inline constexpr std::uint16_t kLastParameterNumberAttribute = 2;
// Class 0x92 instance 0 attributes (Figures B.13-B.15) and instance m attribute (Figure B.16).
inline constexpr std::uint16_t kProductNumberAttribute = 0;
inline constexpr std::uint16_t kProductTextAttribute = 1;
inline constexpr std::uint16_t kProductSeriesAttribute = 3;
inline constexpr std::uint16_t kSoftwareVersionAttribute = 1;
// Class 0x99 attribute ("Attribute=Link", Figure B.19).
inline constexpr std::uint16_t kLinkAttribute = 0;
// A scattered entry's parameter word with this bit set reports an error (Figures B.17, B.18).
inline constexpr std::uint16_t kScatteredErrorFlag = 0x8000;

// ---------------------------------------------------------------------------------------------
// Requests and responses.

struct Request {
  std::uint16_t service = 0;
  std::uint16_t class_code = 0;
  std::uint16_t instance = 0;
  std::uint16_t attribute = 0;
  std::uint16_t length = 0;        // the request length word as written, bytes
  std::vector<std::uint8_t> data;  // the bytes of the buffer the length covers (fewer if it runs off)

  bool truncated() const { return data.size() < length; }
};

// A request with length = data.size().
Request make_request(std::uint16_t service, std::uint16_t class_code, std::uint16_t instance,
                     std::uint16_t attribute, std::vector<std::uint8_t> data = {});
// Data bytes from words, low byte first (for scattered lists and tests).
std::vector<std::uint8_t> bytes_of(std::span<const std::uint16_t> words);
std::vector<std::uint8_t> bytes_of(std::initializer_list<std::uint16_t> words);

// Reads one M0 request buffer (its first 100 words at most; missing words read as 0).
Request decode_request(std::span<const std::uint16_t> buffer);
// The words the ladder writes for `r`: the header and ceil(data/2) data words.
std::vector<std::uint16_t> encode_request(const Request& r);

struct Response {
  std::uint16_t service = 0;
  std::uint16_t class_code = 0;
  std::uint16_t instance = 0;
  std::uint16_t attribute = 0;
  std::vector<std::uint8_t> data;  // the response length word is data.size()

  bool is_error() const { return service == kErrorService; }
  // The error code of an error response (kNone otherwise).
  ErrorCode error() const;
};

// An error response to `r`: service 0x0014, the echo, the code in the first data word, padded
// to `granule`.
Response error_response(const Request& r, ErrorCode code, int granule = 1);

// The 1203-SM1's own check before it transmits (error 0xFD, "too long or too short to
// transmit"): the length runs off the buffer, exceeds the service's limit (96 bytes, 188 for
// scattered services, 96 for unknown services), or a scattered list is empty or not whole
// 4-byte entries. kNone when the request can be sent.
ErrorCode check_length(const Request& r);

// What the drive answers. Includes check_length() so it is total on its own. Checks run in
// this order, the first failure answering: length (0xFD), class (3), service (2: unknown,
// not offered by the device, or not answered by the class), instance (4), service at that
// instance (2: reset/restore/save only at instance 0; read full, set and enum only at a
// parameter), attribute (5), data shorter than the attribute (0xFD), then the drive's own
// checks: read-only (1), running (7), range (6).
Response serve(Drive& drive, const Request& r);

// One message transaction as the module performs it: check_length(), then 0xFE (timeout) when
// no drive answers (`drive` == nullptr: nothing connected, cable pulled, drive unpowered), else
// serve().
Response transact(Drive* drive, const Request& r);

// The M1 words of a response: the header and ceil(length/2) data words, at most 100 words.
std::vector<std::uint16_t> encode_response(const Response& r);
// Writes encode_response() into an M1 response buffer and clears the rest of it, so no word of
// an earlier, longer response survives (Figures B.9-B.11 show zeros after B.8's 32 words).
void write_response(const Response& r, std::span<std::uint16_t> buffer);

// ---------------------------------------------------------------------------------------------
// Time on the SCANport link. The 1203-SM1 manual gives no SCANport timing (only the processor's
// M0/M1 access times, which the VM charges). ASSUMPTION, documented in docs/1203-sm1.md:
// SCANport runs on a CAN physical layer at 125 kbit/s; a message travels as one header frame
// plus one frame per 6 data bytes (the six-byte granule is what the padding of Figure B.2
// suggests); each frame is a full 8-byte CAN 2.0A data frame, 111 bit times including the
// interframe space, without stuffing bits. A transaction is request frames + the drive's
// processing time + response frames; a timeout costs the request frames + response_timeout;
// a message refused with 0xFD never reaches the link and costs nothing.
struct LinkTiming {
  std::int64_t bit_rate = 125'000;       // bits per second
  int frame_bits = 111;                  // one 8-byte CAN 2.0A data frame + interframe space
  int header_frames = 1;
  int data_bytes_per_frame = 6;
  Nanoseconds device_processing = 2 * kNsPerMs;  // from the drive description when there is one
  Nanoseconds response_timeout = 1 * kNsPerS;    // how long the module waits before 0xFE
};

// The link timing with `drive`'s processing time (defaults when nullptr).
LinkTiming link_timing(const Drive* drive);
// Frames for a message with `data_bytes` of data, and the time of one frame.
int frames_for(int data_bytes, const LinkTiming& t);
Nanoseconds frame_time(const LinkTiming& t);
// From the module starting to send `request` until `response` is complete in the module.
Nanoseconds transaction_time(const Request& request, const Response& response, const LinkTiming& t);

// ---------------------------------------------------------------------------------------------
// The seam for the module wrapper: one message from an M0 buffer, answered by `drive` (nullptr
// when nothing answers) in its current state, and how long it occupies the link. The wrapper
// runs it when Message Enable rises (after drive->advance_to(now)), keeps the channel BUSY for
// `duration`, then writes `response` with write_response() and sets DONE.
struct Transaction {
  Request request;
  Response response;
  Nanoseconds duration = 0;
};
Transaction execute_message(Drive* drive, std::span<const std::uint16_t> m0_buffer);

}  // namespace softslc::scanport
