// The DeviceNet Explicit Message (DEM) instruction: its 70-word control block and the state machine
// the VM drives (chapter 8, p.93-101).
//
// Control block (p.101):
//   word 0   bit 15 EN, 13 DN, 12 ER, 10 WS, 8 AB; bits 7-0 error code (0...4)
//   word 1   bit 8 IMR (kept, not interpreted: the manual does not say what it does);
//            bits 7-0 message timeout preset in seconds (0 = none, 1 is treated as 2)
//   word 2   message timeout accumulator: whole seconds since the message was accepted
//   word 3   message timer scaled zero: the 10 ms tick count (low 16 bits) when it was accepted
//   word 4-5 unused
//   word 6   TXID : scanner command       +
//   word 7   port (0) : size of send data  |  the request transaction block of appendix E
//   word 8   service : target MAC ID       |  (transaction.h), except that word 7's size counts
//   word 9   reserved : class              |  the send data only; the DEM adds the 6 path bytes
//   word 10  instance                      |  when it hands the block to the scanner
//   word 11  reserved : attribute (0=none) |
//   word 12-37 send data (52 bytes)       +
//   word 38  TXID : scanner status         +  the response transaction block, copied as is:
//   word 39  port : size of reply data      |  38-40 reply header, 41-69 reply data (58 bytes)
//   word 40  reply service : target MAC ID  |
//   word 41-69 reply data                  +
//
// One DEM per module at a time (p.94): DemPort is that one slot. A DEM whose rung goes false to
// true while another DEM of the same module holds the slot gets WS and keeps asking while its rung
// stays true; it gets EN when it is accepted. The DEM always issues command 1 (execute) with a TXID
// the port chooses (written into word 6), so its transactions never collide with ladder-driven
// ones in M0:224. Completion is seen when the instruction next executes, true or false rung, as a
// MSG's is: DN with error 0 on success; ER with error 4 when the slave answered with a CIP error
// (its general status is reply data byte 0, word 41 low byte); ER with error 2 for scanner statuses
// 2...15 (word 38 low byte); ER with error 1 when the timeout expires; ER with error 3 when the
// ladder sets AB. DN, ER and AB clear on the next false-to-true rung; EN clears when the rung is
// false after DN or ER, or the ladder may clear it to retrigger with the rung still true (p.100).
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "modules/devicenet/scanner.h"
#include "modules/devicenet/transaction.h"

namespace softslc::devicenet::dem {

inline constexpr int kWords = 70;
inline constexpr int kStatusWord = 0;
inline constexpr int kTimeoutWord = 1;
inline constexpr int kAccumulatorWord = 2;
inline constexpr int kScaledZeroWord = 3;
inline constexpr int kRequestWord = 6;   // 6...37
inline constexpr int kReplyWord = 38;    // 38...69
inline constexpr int kSendDataWord = 12;
inline constexpr int kReplyDataWord = 41;
inline constexpr int kMaxSendBytes = 52;
inline constexpr int kMaxReplyBytes = 58;

inline constexpr std::uint16_t kEN = 1u << 15;
inline constexpr std::uint16_t kDN = 1u << 13;
inline constexpr std::uint16_t kER = 1u << 12;
inline constexpr std::uint16_t kWS = 1u << 10;
inline constexpr std::uint16_t kAB = 1u << 8;
inline constexpr std::uint16_t kErrorMask = 0x00FF;
inline constexpr std::uint16_t kIMR = 1u << 8;  // word 1
inline constexpr std::uint16_t kPresetMask = 0x00FF;

// "Complete List of Valid DEM Error Codes" (p.99).
enum class Error : std::uint8_t { None = 0, Timeout = 1, Scanner = 2, User = 3, Cip = 4 };

// The timeout an accepted message runs with: 0 = none, 1 -> 2 s, n -> n s (p.96).
Nanoseconds timeout_for_preset(std::uint8_t preset);

// What the DEM setup dialog writes into a control block (for tests and tools).
struct Setup {
  std::uint8_t service = 0;
  std::uint8_t mac = 0;
  std::uint8_t class_id = 0;
  std::uint16_t instance = 0;
  std::uint8_t attribute = 0;
  Bytes send;                 // at most 52 bytes are stored; the size byte says send.size()
  std::uint8_t timeout_s = 0;
};
void write_setup(std::span<std::uint16_t, kWords> cb, const Setup& s);

// The request block the DEM hands to the scanner for control block `cb` (command 1, `txid`).
RequestBlock request_from_control_block(std::span<const std::uint16_t, kWords> cb, std::uint8_t txid);
// Maps a completed response to (error code, DN?) as chapter 8 specifies.
Error error_for_response(const ResponseBlock& r);

class DemPort {
 public:
  explicit DemPort(Scanner& scanner) : scanner_(scanner) {}

  // One execution of a DEM instruction. `owner` identifies its control block (for example the
  // data-table index of word 0) so several DEM instructions can share the module's one slot.
  // `now` and the scanner are read only when reads_network() says so; otherwise `now` is unused.
  void on_rung(std::uint32_t owner, std::span<std::uint16_t, kWords> cb, bool rung_in, VirtualTime now);
  // Whether on_rung(owner, cb, rung_in, ...) would read the time or the scanner: when this control
  // block has the message in flight (its completion, timeout or accumulator) or would start one now
  // (rung true, EN clear, the slot free). Otherwise the execution only clears WS or EN, sets WS, or
  // leaves the block alone, from the block, the rung and the slot alone (chapter 8, p.100), and
  // the wrapper need not advance the network to the instruction's time.
  bool reads_network(std::uint32_t owner, std::span<const std::uint16_t, kWords> cb, bool rung_in) const {
    return owner_ == owner || (rung_in && (cb[kStatusWord] & kEN) == 0 && !owner_);
  }
  // Forgets the in-flight message and deletes its transaction (the processor left Run). The
  // owner's control block keeps EN until it executes again with its rung false, which clears it.
  void abandon();
  std::optional<std::uint32_t> owner() const { return owner_; }
  // The owner abandon() dropped, until its EN is cleared.
  std::optional<std::uint32_t> abandoned() const { return abandoned_; }

 private:
  void finish(std::span<std::uint16_t, kWords> cb, Error e, bool done);

  Scanner& scanner_;
  std::optional<std::uint32_t> owner_;
  std::optional<std::uint32_t> abandoned_;  // the owner abandon() dropped, until its EN is cleared
  std::uint8_t txid_ = 0;
  VirtualTime start_ = 0;
  Nanoseconds timeout_ = 0;
  std::uint8_t next_txid_ = 1;
};

}  // namespace softslc::devicenet::dem
