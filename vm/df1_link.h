// DF1 full-duplex: channel 0 of an SLC 5/03-5/05 or a MicroLogix joined point to point to another
// controller's channel 0 (a null-modem cable), in virtual time.
//
// What the link does (1770-6.5.16 ch. 2 and 4; AG-UM008C p. 1-16 Figure 1.8): a packet goes out as a
// frame DLE STX <packet, every 10h byte doubled> DLE ETX <BCC or CRC>; each character takes its bits
// (start, 8 data, parity when even parity is set, 1 stop) at the channel's baud rate. The receiver answers
// a good frame with DLE ACK and a bad one (its BCC/CRC does not check) with DLE NAK. The transmitter
// starts its ACK timer when the last character has gone; a NAK makes it send the frame again, up to NAK
// Retries times; a timeout makes it send DLE ENQ, which the receiver answers with its last response (ACK
// or NAK), up to ENQ Retries times; past either limit the message has failed. The receiver passes a
// packet to its sink once: a packet whose source, command and transaction number are those of the last one
// it took is a duplicate, acknowledged and discarded when duplicate packet detection is on. One packet is
// in a transmitter at a time.
//
// Everything here is computed, not scheduled: a transfer's outcome follows from the two ends'
// configurations, the cable, the noise a test injected, and the start time, so MessageNetwork (the only
// user) computes it when a packet is handed to the transmitter and posts what follows (the ACK that sets
// ST, the packets the far end's sink takes, the failure) as timed frames (vm/message_network.h).
// Decisions where the manuals are silent are in docs/semantics.md "DF1 full-duplex on channel 0".
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "instructions/processor.h"
#include "vm/virtual_time.h"

namespace softslc {

enum class Df1ErrorCheck : std::uint8_t { Crc, Bcc };

// A channel 0 DF1 full-duplex configuration as a test or the API writes it: every field left unset takes
// the processor's default (df1_defaults).
struct Df1Options {
  std::optional<int> baud;
  std::optional<bool> parity_even;
  std::optional<Df1ErrorCheck> error_check;
  std::optional<int> ack_timeout;  // in 20 ms counts, as the channel configuration's field "ACK Timeout (x20 ms)"
  std::optional<int> nak_retries;
  std::optional<int> enq_retries;
  std::optional<bool> duplicate_detect;
};

// The configuration in force.
struct Df1Config {
  int baud = 19200;
  bool parity_even = false;
  Df1ErrorCheck error_check = Df1ErrorCheck::Crc;
  int ack_timeout = 50;
  int nak_retries = 3;
  int enq_retries = 3;
  bool duplicate_detect = true;

  Nanoseconds ack_timeout_ns() const { return static_cast<Nanoseconds>(ack_timeout) * 20 * kNsPerMs; }
  // Start bit, 8 data bits, the parity bit when parity is even, one stop bit ("Stop Bits: not a setting,
  // always 1", 1766-RM001A p. 592).
  int bits_per_character() const { return parity_even ? 11 : 10; }
};

// Whether the processor's channel 0 can be configured for DF1 full-duplex: the SLC 5/03-5/05 (1747-RM001G
// p. 13-49) and every MicroLogix (1762-RM001C p. 21-2; 1761-6.2 p. 15-3).
bool has_df1_channel0(const ProcessorModel& p);
// The processor's defaults. MicroLogix 1400 (1766-RM001A p. 592, "DF1 Full-Duplex Configuration Parameters"):
// 19.2K, no parity, CRC, duplicate detect enabled, ACK timeout 50 counts, NAK and ENQ retries 3; the 1100,
// 1200, 1500 and the SLC 5/03-5/05 are taken to have the same [U]. MicroLogix 1000 (AG-UM008C p. 6-14
// table 6.2, series C and later): 9600 baud, CRC, 1 s, 6 NAK and 6 ENQ retries, duplicate detection enabled.
Df1Config df1_defaults(const ProcessorModel& p);
// The configuration `o` gives the processor's channel 0, or a message naming the first setting the
// processor does not take (with the page that says so).
std::string df1_configure(const ProcessorModel& p, const Df1Options& o, Df1Config& out);

// One `key=value` (or `crc`, `bcc`) setting of a test file's channel 0 line into `o`; "" or why it is not one.
std::string df1_parse_option(std::string_view text, Df1Options& o);

// ---- Frames -------------------------------------------------------------------------------------------

inline constexpr std::uint8_t kDle = 0x10, kStx = 0x02, kEtx = 0x03, kAck = 0x06, kNak = 0x15, kEnq = 0x05;

// The block check character: the two's complement of the 8-bit sum of the packet's bytes (1770-6.5.16
// p. 2-7: a doubled DLE counts once, so over the packet as it is before doubling).
std::uint8_t df1_bcc(const std::vector<std::uint8_t>& packet);
// CRC-16 with the polynomial x^16 + x^15 + x^2 + 1, initial value 0, bits taken least significant first
// (the CRC-16/ARC of the CRC catalogues: "123456789" gives BB3Dh).
std::uint16_t crc16(const std::vector<std::uint8_t>& bytes);
// The frame's CRC: over the packet's bytes and the ETX (1770-6.5.16 p. 2-8).
std::uint16_t df1_crc(const std::vector<std::uint8_t>& packet);
// The frame as it goes on the wire: DLE STX, the packet with each 10h doubled, DLE ETX, then the BCC or the
// CRC (low byte first). The check bytes are not doubled [U].
std::vector<std::uint8_t> df1_frame(const std::vector<std::uint8_t>& packet, Df1ErrorCheck check);
// The time `characters` characters take on a line of `c`'s baud rate and framing (rounded up to a whole ns).
Nanoseconds df1_character_time(const Df1Config& c, int characters);

// The PCCC packets of the MSG's commands and replies (1770-6.5.16 ch. 7): DST, SRC, CMD, STS, TNS (2 bytes),
// then for a 500CPU message the protected typed logical read (CMD 0Fh, FNC A2h) or write (FNC AAh) with three
// address fields: FNC, byte size, file number, file type, element number, sub-element number (each of the
// last three one byte below 255, else FFh and two bytes), a write's data words low byte first; for 485CIF the
// unprotected read (CMD 01h: address (2 bytes), size) or write (CMD 08h: address, data). A reply is DST,
// SRC, CMD + 40h, STS, TNS and a read's data.
struct Df1Command {
  int dst = 0;
  int src = 0;
  std::uint16_t tns = 0;
  bool write = false;
  bool cif = false;
  int file = 0;
  std::uint16_t type_code = 0;
  int element = 0;
  int words = 0;
  std::vector<std::uint16_t> data;  // a write's
};
std::vector<std::uint8_t> df1_command_packet(const Df1Command& c);
std::vector<std::uint8_t> df1_reply_packet(const Df1Command& c, std::uint8_t sts, const std::vector<std::uint16_t>& data);

// ---- One end of the link, and a transfer -------------------------------------------------------------

// The channel's diagnostic counters, as the SLC's channel status keeps them for DF1 full-duplex: sent
// (frames, retransmissions included), received (packets passed to the sink, duplicates not), undelivered
// (packets given up after the retries), ENQs sent, NAKs received, ENQs received, bad packets (frames answered
// with NAK), duplicates (discarded). A transfer is computed when it starts, so its events are kept with their
// times and counted once the observer's time has reached them.
enum class Df1Count : std::uint8_t { Sent, Received, Undelivered, EnqsSent, NaksReceived, EnqsReceived, BadPackets, Duplicates };
inline constexpr std::size_t kDf1Counts = 8;
// The counter a test observes by name ("sent", "enqs sent", ...), if any.
std::optional<Df1Count> df1_count_named(std::string_view name);

class Df1Counters {
 public:
  void add(Df1Count c, VirtualTime at) { pending_.emplace(at, c); }
  // The events of kind `c` up to `now`.
  std::int64_t at(Df1Count c, VirtualTime now) const;
  // Folds the events up to `now` into the totals (no observer looks earlier than the link's present).
  void settle(VirtualTime now);

 private:
  std::array<std::int64_t, kDf1Counts> settled_{};
  std::multimap<VirtualTime, Df1Count> pending_;
};

struct Df1Port {
  Df1Config config;
  VirtualTime transmitter_free = 0;  // one packet in the transmitter at a time
  std::uint16_t next_tns = 1;
  // The last packet the receiver took (source, command, transaction number) and its last response.
  std::optional<std::uint32_t> last_key;
  bool last_response_ack = true;
  // Noise a test injected (`device DF1 ...`): the next `corrupt_frames` frames this end sends arrive with a
  // bad check; the next ACK this end receives is destroyed, and the noise also reaches the far receiver, which
  // makes its last response a NAK (1770-6.5.16 p. 4-13, "Message Transfer with Re-transmission").
  int corrupt_frames = 0;
  bool lose_ack = false;
  Df1Counters counters;
};

// What became of a packet handed to `from`'s transmitter at `start`.
struct Df1Outcome {
  bool acked = false;
  VirtualTime done = 0;                 // the ACK's arrival, or when the transmitter gave up
  std::vector<VirtualTime> deliveries;  // when the far end's sink took the packet (twice: a duplicate not detected)
  int frames = 0;
};
// `to` is the far end (nullptr: nobody on the cable); `line_ok` false when the cable is open or the two ends'
// baud rates or parity differ (the receiver recognises nothing). `key` identifies the packet for duplicate
// detection (source, command, transaction number).
Df1Outcome df1_transfer(Df1Port& from, Df1Port* to, bool line_ok, VirtualTime start, int frame_bytes, std::uint32_t key);

}  // namespace softslc
