// 1747-SN block transfers: the M0/M1 buffer layout and the processor side of BTR/BTW.
//
// The scanner has 32 block-transfer buffers, buffer x at words x00-x99 of both M files (M0:e.x00
// and M1:e.x00, x = 1-32; 1747-SN p. 5-6: "each instruction uses both the M0 and M1 file for that
// buffer number"). The manual's "Block Transfer Buffer Layout" section is not in our copy; the
// layout below is INFERRED from Table 5.1, the chapter 4 example (COP #M1:1.100 #B3:0 4, then
// "B3/13" = done, "B3/12" = error, "buffer the BT status from B3:3") and the Appendix D programs
// (the ladder MOVes a "virtual control word" with bit 15 = enable and bit 7 = read to M0:e.x00):
//
//   M0:e.x00  control word   EN 15, TO 8, RW 7 (1 = read), rack 6-4, group 3-1, slot 0
//   M0:e.x01  requested word count (0-64; 0 = 64 for a BTW, "what the device sends" for a BTR)
//   M0:e.x10  BTW data, up to 64 words (x10-x73)
//   M1:e.x00  status word    EN 15 (echo), ST 14, DN 13, ER 12, EW 10, TO 8 (echo), RW 7 and
//                            rack/group/slot (echo)
//   M1:e.x01  requested word count (echo)
//   M1:e.x02  transmitted word count
//   M1:e.x03  error code (0, or -6 ... -12 of Table 5.3)
//   M1:e.x10  BTR data, up to 64 words (x10-x73)
//
// The scanner (rio_scanner.h) sees only these words: it reacts to changes of the M0 control word
// and answers in the M1 status words. The SLC 5/03+ BTR/BTW instructions are implemented here as
// what the processor does with those words each time it scans the instruction
// (execute_block_transfer), and the Appendix D programs for earlier processors do the same with
// MOV/COP in ladder, so both paths share the scanner's one implementation.
#pragma once

#include <cstdint>

#include "parser/diagnostics.h"
#include "parser/program.h"
#include "vm/module.h"
#include "vm/virtual_time.h"

namespace softslc::rio {

inline constexpr int kBufferCount = 32;
inline constexpr int kBufferStride = 100;

// Control block / control word / status word bits (Table 5.1 word 0).
inline constexpr std::uint16_t kEN = 1u << 15;
inline constexpr std::uint16_t kST = 1u << 14;
inline constexpr std::uint16_t kDN = 1u << 13;
inline constexpr std::uint16_t kER = 1u << 12;
inline constexpr std::uint16_t kEW = 1u << 10;
inline constexpr std::uint16_t kTO = 1u << 8;
inline constexpr std::uint16_t kRW = 1u << 7;
inline constexpr std::uint16_t kAddressBits = 0x007F;  // rack 6-4, group 3-1, slot 0
inline constexpr std::uint16_t kStatusBits = kST | kDN | kER | kEW;

// Word offsets inside a buffer.
inline constexpr int kControlWord = 0;
inline constexpr int kRequestedCount = 1;
inline constexpr int kTransmittedCount = 2;
inline constexpr int kErrorCode = 3;
inline constexpr int kDataOffset = 10;
inline constexpr int kMaxWords = 64;

// Table 5.3 error codes.
inline constexpr std::int16_t kErrIllegalLength = -6;
inline constexpr std::int16_t kErrCommunication = -7;
inline constexpr std::int16_t kErrProtocol = -8;
inline constexpr std::int16_t kErrTimeout = -9;
inline constexpr std::int16_t kErrNoChannel = -10;
inline constexpr std::int16_t kErrNotConfigured = -11;
inline constexpr std::int16_t kErrInhibited = -12;

// "the RIO scanner's internal four-second block transfer timer" (Table 5.2, TO).
inline constexpr Nanoseconds kBtTimer = seconds(4);

// The buffer number of an M-file word that starts a buffer (x00, x = 1-32), else 0.
constexpr int buffer_at(int word) {
  return word % kBufferStride == 0 && word / kBufferStride >= 1 && word / kBufferStride <= kBufferCount
             ? word / kBufferStride
             : 0;
}
constexpr int rack_of(std::uint16_t control) { return (control >> 4) & 7; }
constexpr int group_of(std::uint16_t control) { return (control >> 1) & 7; }
constexpr int slot_of(std::uint16_t control) { return control & 1; }

// One scan of a BTR or BTW instruction (operands: control block, buffer M1:e.x00 / M0:e.x00,
// data file, rack, group, slot, length). What it does, following Table 5.2 and "Instruction
// Operation" steps 1-5:
//   - EN follows the rung. On a false-to-true transition (or a true rung on the first scan after
//     entering Run/Test, when the scanner's buffers start cleared) it clears ST/DN/ER/EW and
//     word 2, and for a BTW copies the data file into M0:e.x10 first;
//   - it writes the control word (EN, TO, RW, rack/group/slot of the control block) and the
//     requested count to M0:e.x00/x01, reads M1:e.x00-x03, and copies ST, DN, ER, EW into the
//     control block and the transmitted count (DN) or error code (ER) into word 2; the bits change
//     only when the instruction is scanned;
//   - when DN appears, a BTR copies the transmitted words from M1:e.x10 into its data file.
// Access times charged: the control word and count as two "any M file address" accesses, the
// status as one "COP from M file" of 4 words, BTW data "COP to M file", BTR data "COP from M file".
void execute_block_transfer(ModuleInstructionContext& ctx);

// "A total of 32 block transfer buffers are available; you can execute a maximum of 32 different
// block transfers", "the next BT instruction must use another M-file buffer" (1747-SN p. 5-5,
// 5-6). Two BTR/BTW instructions of different control blocks on the same buffer of scanner
// `slot` would overwrite each other's control word and both take the one transfer's status and
// data, silently; so a 33rd block transfer (or any second user of a buffer) is refused at its
// operand, naming the first. The same control block on the same buffer is the same transfer
// (written twice in the ladder, e.g. in two subroutines) and is allowed.
void check_buffer_sharing(const Program& program, int slot, DiagnosticList& diags);

}  // namespace softslc::rio
