// PCCC: the SLC 500's command set, as it arrives inside CIP's Execute PCCC service.
//
// Two layers. decode() is a pure function from the bytes of one PCCC command (CMD, STS, TNS,
// then the command's own fields) to a Request, or an error saying which byte is wrong; it never
// reads past the span and allocates at most the request's own data. execute() runs a decoded
// request against a Target — the live controller, or a test double — and always returns a
// reply: a refused request is a reply with the status codes the real processor sends, never an
// exception or a closed connection (only bytes that are not a PCCC command at all are that).
//
// Supported, with the DF1 Protocol and Command Set manual (1770-6.5.16) as the reference:
//   CMD 06 FNC 00  echo                                   reply CMD 46, the data echoed
//   CMD 06 FNC 03  diagnostic status                      reply CMD 46, the status block
//   CMD 0F FNC A1  protected typed logical read, 2 address fields (file, type, element)
//   CMD 0F FNC A2  protected typed logical read, 3 address fields (+ sub-element)
//   CMD 0F FNC A9  protected typed logical write, 2 address fields
//   CMD 0F FNC AA  protected typed logical write, 3 address fields
//   CMD 0F FNC AB  protected typed logical write with mask, 3 address fields (read-modify-write)
// An address field is one byte, or 0xFF followed by a 16-bit little-endian value. Everything else
// is answered STS 10h (illegal command or format). Element e, sub-element s of a file is word
// e * words-per-element + s; a read or write covers size/2 words from there (within the file).
// Decision (the manual is silent): a write addressed to a sub-element of a T, C or R element
// writes that one word whatever its size byte says, because clients that work against real SLCs
// send the whole element's size there (nodepccc writes T4:0.PRE as 6 bytes at sub-element 1).
//
// Error replies (1770-6.5.16 p. 8-4, "EXT STS codes for CMD 0F"; STS F0h carries EXT STS):
//   06h  address does not point to something usable — no such file, element or sub-element
//   0Ah  transaction size plus word address is too large — the range runs past the file's end
//   10h  no access — a write refused by --read-only or by the controller (a module's rule)
//   11h  illegal data type — the file type code does not match the file
//   09h  data too large — more than kMaxDataBytes in one request
//
// M0/M1 files (specialty-module files, 1747-SN manual appendix B: "M0 and M1 files are data files
// that reside in specialty I/O modules only"). The SLC's typed-read file type code for them is not
// in our sources (the DF1 manual's file-type table, p. 7-17 as drivers quote it, stops at 8Fh;
// no PCCC client we know of has an M address syntax), so softslc chooses one and docs/serve.md
// says so: file type F0h is M0, F1h is M1; the file field is the module's slot, the element the
// word (M0:1.100 is file 1 element 100), the sub-element must be 0. The file has as many elements
// as the module's M file has words. Every word is read or written through the module, as the
// ladder and `run --set` reach it (Target::read_module / write_module), so the module's refusal —
// a word it does not have, a file it does not let the processor write — is the client's error:
// EXT STS 10h (no access), or 06h when the slot has no module with that M file at all.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "parser/address.h"
#include "vm/pccc_target.h"

namespace softslc::pccc {

// The largest data field of one read or write. The size is one byte; the sources we have do not
// state the SLC 5/05's limit over EtherNet/IP, so this is softslc's choice (documented in
// docs/serve.md): 236 bytes, above the 220 that nodepccc keeps to.
inline constexpr std::size_t kMaxDataBytes = 236;

inline constexpr std::uint8_t kCmdDiagnostic = 0x06;
inline constexpr std::uint8_t kCmdTyped = 0x0F;
inline constexpr std::uint8_t kReplyBit = 0x40;

inline constexpr std::uint8_t kFncEcho = 0x00;
inline constexpr std::uint8_t kFncDiagnosticStatus = 0x03;
inline constexpr std::uint8_t kFncRead2 = 0xA1;
inline constexpr std::uint8_t kFncRead3 = 0xA2;
inline constexpr std::uint8_t kFncWrite2 = 0xA9;
inline constexpr std::uint8_t kFncWrite3 = 0xAA;
inline constexpr std::uint8_t kFncWriteMask = 0xAB;

inline constexpr std::uint8_t kStsOk = 0x00;
inline constexpr std::uint8_t kStsIllegalCommand = 0x10;
inline constexpr std::uint8_t kStsExtended = 0xF0;

inline constexpr std::uint8_t kExtAddressUnusable = 0x06;
inline constexpr std::uint8_t kExtTooLarge = 0x09;
inline constexpr std::uint8_t kExtPastEnd = 0x0A;
inline constexpr std::uint8_t kExtNoAccess = 0x10;
inline constexpr std::uint8_t kExtIllegalType = 0x11;

// The file type code of a typed read/write for each SLC file type (the codes SLC/MicroLogix
// drivers send: 84h S, 85h B, 86h T, 87h C, 88h R, 89h N, 8Ah F, 8Bh O, 8Ch I, 8Dh ST, 8Eh A,
// 91h L); for M0/M1, softslc's own codes (F0h, F1h; see above).
std::optional<std::uint8_t> type_code(FileType t);
inline constexpr std::uint8_t kTypeM0 = 0xF0;
inline constexpr std::uint8_t kTypeM1 = 0xF1;

enum class Kind : std::uint8_t { Echo, DiagnosticStatus, Read, Write, WriteMask, Unsupported };

struct Request {
  Kind kind = Kind::Unsupported;
  std::uint8_t cmd = 0;
  std::uint8_t sts = 0;
  std::uint16_t tns = 0;
  std::uint8_t fnc = 0;
  // Typed read/write.
  std::uint8_t size = 0;  // bytes to read, or bytes of data written
  std::uint16_t file = 0;
  std::uint8_t type = 0;
  std::uint16_t element = 0;
  std::uint16_t sub = 0;  // 0 when the command has two address fields
  std::uint16_t mask = 0xFFFF;      // WriteMask: the bits written
  std::vector<std::uint8_t> data;   // Write/WriteMask: the data; Echo: the bytes to echo
};

// Decodes one PCCC command. Returns nullopt with `error` set when the bytes are not a
// well-formed command (too short, a field cut off, data longer or shorter than its size byte).
// An unknown CMD/FNC decodes as Kind::Unsupported (answered STS 10h).
std::optional<Request> decode(std::span<const std::uint8_t> bytes, std::string* error = nullptr);

// What execute() needs from the processor: pccc::Target (vm/pccc_target.h).


// Runs a request and returns the whole reply (CMD|40h, STS, TNS, data or EXT STS). `refusal`, when
// given, receives the reason a write or read was refused (for the log).
std::vector<std::uint8_t> execute(const Request& request, Target& target, std::string* refusal = nullptr);

}  // namespace softslc::pccc
