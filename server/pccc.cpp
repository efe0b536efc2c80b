#include "server/pccc.h"

#include <algorithm>

namespace softslc::pccc {

std::optional<std::uint8_t> type_code(FileType t) {
  switch (t) {
    case FileType::Status: return 0x84;
    case FileType::Bit: return 0x85;
    case FileType::Timer: return 0x86;
    case FileType::Counter: return 0x87;
    case FileType::Control: return 0x88;
    case FileType::Integer: return 0x89;
    case FileType::Float: return 0x8A;
    case FileType::Output: return 0x8B;
    case FileType::Input: return 0x8C;
    case FileType::String: return 0x8D;
    case FileType::Ascii: return 0x8E;
    case FileType::Long: return 0x91;
    case FileType::M0: return kTypeM0;
    case FileType::M1: return kTypeM1;
    // MicroLogix function files (RTC, HSC, ...) are not served over PCCC yet: a typed read of
    // one has no file type to answer with (docs/serve.md, "Not yet").
    // NOLINTNEXTLINE(bugprone-branch-clone): kept apart from MG/RI below, which differ in why
    case FileType::Function: return std::nullopt;
    // Nor are the MicroLogix MG and RI files: no source for their typed-read codes was reached.
    case FileType::Message:
    case FileType::Routing: return std::nullopt;
  }
  return std::nullopt;
}

namespace {

// Reads bytes in order and remembers the first failure, so a decoder reads like the frame layout.
class Reader {
 public:
  explicit Reader(std::span<const std::uint8_t> b) : b_(b) {}
  bool ok() const { return ok_; }
  std::size_t left() const { return b_.size() - at_; }
  std::uint8_t u8() {
    if (at_ >= b_.size()) {
      ok_ = false;
      return 0;
    }
    return b_[at_++];
  }
  std::uint16_t u16() {
    const std::uint8_t lo = u8();
    const std::uint8_t hi = u8();
    return static_cast<std::uint16_t>(lo | (hi << 8));
  }
  // One address field: a byte, or FFh and a 16-bit value.
  std::uint16_t field() {
    const std::uint8_t b = u8();
    return b == 0xFF ? u16() : b;
  }
  std::span<const std::uint8_t> rest() {
    auto r = b_.subspan(at_);
    at_ = b_.size();
    return r;
  }

 private:
  std::span<const std::uint8_t> b_;
  std::size_t at_ = 0;
  bool ok_ = true;
};

void set_error(std::string* error, std::string text) {
  if (error) *error = std::move(text);
}

std::vector<std::uint8_t> reply_header(const Request& r, std::uint8_t sts) {
  return {static_cast<std::uint8_t>(r.cmd | kReplyBit), sts, static_cast<std::uint8_t>(r.tns & 0xFF),
          static_cast<std::uint8_t>(r.tns >> 8)};
}

std::vector<std::uint8_t> extended(const Request& r, std::uint8_t ext, std::string* refusal, std::string why) {
  auto out = reply_header(r, kStsExtended);
  out.push_back(ext);
  if (refusal) *refusal = std::move(why);
  return out;
}

// Packs words into a read reply's data, low byte first, `size` bytes.
void append_bytes(std::vector<std::uint8_t>& out, std::span<const std::uint16_t> words, std::size_t size) {
  for (std::size_t i = 0; i < size; ++i)
    out.push_back(static_cast<std::uint8_t>((i % 2) ? words[i / 2] >> 8 : words[i / 2] & 0xFF));
}

// Unpacks a write's data into words and masks (an odd size writes only the low byte of its last
// word), `mask` applying to every word.
void unpack_write(const Request& r, std::vector<std::uint16_t>& values, std::vector<std::uint16_t>& masks) {
  const std::size_t bytes = std::min<std::size_t>(r.size, values.size() * 2);
  for (std::size_t i = 0; i < bytes; ++i)
    values[i / 2] = static_cast<std::uint16_t>(values[i / 2] | (r.data[i] << ((i % 2) ? 8 : 0)));
  masks.assign(values.size(), r.mask);
  if (bytes % 2) masks.back() = static_cast<std::uint16_t>(masks.back() & 0x00FF);
}

// A typed read or write of an M0/M1 file: file = slot, element = word, through the module.
std::vector<std::uint8_t> execute_module(const Request& r, Target& target, std::string* refusal, const std::string& what) {
  const bool m1 = r.type == kTypeM1;
  const auto words_in_file = target.module_file_words(r.file, m1);
  if (!words_in_file)
    return extended(r, kExtAddressUnusable, refusal, what + ": no module with an " + (m1 ? "M1" : "M0") + " file in that slot");
  if (r.sub != 0 || r.element >= *words_in_file)
    return extended(r, kExtAddressUnusable, refusal, what + ": no such word in the module's file");
  const std::uint32_t words = (static_cast<std::uint32_t>(r.size) + 1) / 2;
  if (r.element + words > *words_in_file) return extended(r, kExtPastEnd, refusal, what + ": past the end of the M file");
  std::vector<std::uint16_t> buf(words);
  if (r.kind == Kind::Read) {
    if (auto why = target.read_module(r.file, m1, r.element, buf); !why.empty())
      return extended(r, kExtNoAccess, refusal, what + ": " + why);
    auto out = reply_header(r, kStsOk);
    append_bytes(out, buf, r.size);
    return out;
  }
  std::vector<std::uint16_t> masks;
  unpack_write(r, buf, masks);
  if (auto why = target.write_module(r.file, m1, r.element, buf, masks); !why.empty())
    return extended(r, kExtNoAccess, refusal, what + ": " + why);
  return reply_header(r, kStsOk);
}

}  // namespace

std::optional<Request> decode(std::span<const std::uint8_t> bytes, std::string* error) {
  Reader in(bytes);
  Request r;
  r.cmd = in.u8();
  r.sts = in.u8();
  r.tns = in.u16();
  if (!in.ok()) {
    set_error(error, "PCCC command shorter than CMD, STS and TNS (4 bytes)");
    return std::nullopt;
  }
  // A command without a function code (CMD 0F and 06 have one) is still a command: answered
  // "illegal command" rather than treated as a broken frame.
  if (r.cmd != kCmdDiagnostic && r.cmd != kCmdTyped) return r;
  r.fnc = in.u8();
  if (!in.ok()) {
    set_error(error, "PCCC CMD " + std::to_string(r.cmd) + " without its function code");
    return std::nullopt;
  }
  if (r.cmd == kCmdDiagnostic) {
    if (r.fnc == kFncEcho) {
      r.kind = Kind::Echo;
      auto rest = in.rest();
      if (rest.size() > kMaxDataBytes) {
        set_error(error, "echo data longer than " + std::to_string(kMaxDataBytes) + " bytes");
        return std::nullopt;
      }
      r.data.assign(rest.begin(), rest.end());
    } else if (r.fnc == kFncDiagnosticStatus) {
      r.kind = Kind::DiagnosticStatus;
    }
    return r;
  }
  switch (r.fnc) {
    case kFncRead2:
    case kFncRead3: r.kind = Kind::Read; break;
    case kFncWrite2:
    case kFncWrite3: r.kind = Kind::Write; break;
    case kFncWriteMask: r.kind = Kind::WriteMask; break;
    default: return r;  // Unsupported: answered STS 10h.
  }
  r.size = in.u8();
  r.file = in.field();
  r.type = in.u8();
  r.element = in.field();
  if (r.fnc == kFncRead3 || r.fnc == kFncWrite3 || r.fnc == kFncWriteMask) r.sub = in.field();
  if (!in.ok()) {
    set_error(error, "typed read/write (FNC " + std::to_string(r.fnc) + ") cut off in its address fields");
    return std::nullopt;
  }
  if (r.kind == Kind::WriteMask) {
    r.mask = in.u16();
    if (!in.ok()) {
      set_error(error, "write with mask without its mask word");
      return std::nullopt;
    }
  }
  if (r.kind == Kind::Read) {
    if (in.left() != 0) {
      set_error(error, "typed read with " + std::to_string(in.left()) + " byte(s) after its address");
      return std::nullopt;
    }
    return r;
  }
  auto data = in.rest();
  if (data.size() != r.size) {
    set_error(error, "typed write of size " + std::to_string(r.size) + " carries " + std::to_string(data.size()) +
                         " data byte(s)");
    return std::nullopt;
  }
  r.data.assign(data.begin(), data.end());
  return r;
}

std::vector<std::uint8_t> execute(const Request& r, Target& target, std::string* refusal) {
  switch (r.kind) {
    case Kind::Unsupported:
      if (refusal) *refusal = "unsupported PCCC command";
      return reply_header(r, kStsIllegalCommand);
    case Kind::Echo: {
      auto out = reply_header(r, kStsOk);
      out.insert(out.end(), r.data.begin(), r.data.end());
      return out;
    }
    case Kind::DiagnosticStatus: {
      auto out = reply_header(r, kStsOk);
      const auto block = target.diagnostic_status();
      out.insert(out.end(), block.begin(), block.end());
      return out;
    }
    case Kind::Read:
    case Kind::Write:
    case Kind::WriteMask: break;
  }
  const std::string what = "file " + std::to_string(r.file) + " element " + std::to_string(r.element) +
                           " sub-element " + std::to_string(r.sub);
  if (r.size > kMaxDataBytes) return extended(r, kExtTooLarge, refusal, what + ": more than 236 data bytes");
  if (r.size == 0) return extended(r, kExtAddressUnusable, refusal, what + ": a transfer of no bytes");
  if (r.type == kTypeM0 || r.type == kTypeM1) return execute_module(r, target, refusal, what);
  const auto file = target.file(r.file);
  if (!file) return extended(r, kExtAddressUnusable, refusal, what + ": no such file");
  if (type_code(file->type) != r.type) return extended(r, kExtIllegalType, refusal, what + ": wrong file type code");
  if (r.element >= file->elements || r.sub >= file->words_per_element)
    return extended(r, kExtAddressUnusable, refusal, what + ": no such element or sub-element");
  const std::uint32_t offset =
      static_cast<std::uint32_t>(r.element) * static_cast<std::uint32_t>(file->words_per_element) + r.sub;
  // Words touched: a byte count rounds up to whole words (an odd size reads or writes the low
  // byte of the last word, as the A file's one-byte characters need).
  std::uint32_t words = (static_cast<std::uint32_t>(r.size) + 1) / 2;
  // A write addressed to a sub-element of a timer, counter or control element (.PRE, .ACC, .LEN,
  // .POS) writes that one word. Clients that work against real SLCs send the whole element's
  // size here with the value in the first word (nodepccc 0.1.17 writes T4:0.PRE as 6 bytes at
  // sub-element 1), so the rest of the data is not a request to overwrite the next words.
  if (r.kind != Kind::Read && r.sub > 0 && is_structured(file->type)) words = 1;
  const std::uint32_t file_words = file->elements * static_cast<std::uint32_t>(file->words_per_element);
  if (offset + words > file_words) return extended(r, kExtPastEnd, refusal, what + ": past the end of the file");

  std::vector<std::uint16_t> buf(words);
  if (r.kind == Kind::Read) {
    target.read(r.file, offset, buf);
    auto out = reply_header(r, kStsOk);
    append_bytes(out, buf, r.size);
    return out;
  }
  std::vector<std::uint16_t> masks;
  unpack_write(r, buf, masks);
  const std::string why = target.write(r.file, offset, buf, masks);
  if (!why.empty()) return extended(r, kExtNoAccess, refusal, what + ": " + why);
  return reply_header(r, kStsOk);
}

}  // namespace softslc::pccc
