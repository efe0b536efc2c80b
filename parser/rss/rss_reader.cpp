// The .RSS reader: OLE2 container (libolecf) → stream payload (zlib) → MFC archive → export text.
// See rss_reader.h for the design; docs/program-format.md for what is and is not read.
#include "parser/rss/rss_reader.h"

#include <libbfio.h>
#include <libolecf.h>
#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <array>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>

#include "instructions/instruction_table.h"

namespace softslc::rss {
namespace {

// ---- the selector table ---------------------------------------------------------------------
struct SelectorRow {
  std::uint16_t selector;
  std::string_view mnemonic;
  std::string_view shape;
};

constexpr SelectorRow kSelectors[] = {
#define RSS_SELECTOR(sel, mnemonic, shape) SelectorRow{sel, #mnemonic, shape},
#include "parser/rss/rss_selectors.def"
#undef RSS_SELECTOR
};

const SelectorRow* find_selector(std::uint16_t selector) {
  for (const auto& row : kSelectors)
    if (row.selector == selector) return &row;
  return nullptr;
}

// Structural selectors: they frame the rung, its branches and branch legs.
enum Structural : std::uint16_t { RungOpen = 0, RungClose = 1, BranchOpen = 2, BranchClose = 3, LegOpen = 4, LegClose = 5 };

std::string hex(std::uint64_t v, int digits = 0) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "0x%0*llX", digits, static_cast<unsigned long long>(v));
  return buf;
}

// A decoding error, thrown inside the reader and turned into ReadResult::error at the top.
struct DecodeError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// ---- the OLE2 container -----------------------------------------------------------------------
// RAII owners for the libolecf/libbfio handles, so every exit path frees them.
struct BfioDeleter {
  void operator()(libbfio_handle_t* h) const { libbfio_handle_free(&h, nullptr); }
};
struct OlecfFileDeleter {
  void operator()(libolecf_file_t* f) const {
    libolecf_file_close(f, nullptr);
    libolecf_file_free(&f, nullptr);
  }
};
struct OlecfItemDeleter {
  void operator()(libolecf_item_t* i) const { libolecf_item_free(&i, nullptr); }
};
using ItemPtr = std::unique_ptr<libolecf_item_t, OlecfItemDeleter>;

void drop(libolecf_error_t* e) {
  if (e) libolecf_error_free(&e);
}

class Container {
 public:
  explicit Container(std::string_view bytes) : bytes_(bytes) {
    // Debian's libbfio (20170123) copies a whole sector from a memory range even when the range
    // ends inside it (found by fuzzing truncated files under ASan). An OLE2 file is a whole
    // number of 512-byte sectors, so the range is rounded up to one (a truncated file then reads
    // as zeros, which libolecf rejects as damaged) and the buffer has slack beyond it for any
    // read that starts inside the range.
    std::size_t range = (bytes.size() + 511) / 512 * 512;
    padded_.assign(range + kReadSlack, '\0');
    std::memcpy(padded_.data(), bytes.data(), bytes.size());
    libbfio_handle_t* h = nullptr;
    if (libbfio_memory_range_initialize(&h, nullptr) != 1) throw DecodeError("out of memory");
    io_.reset(h);
    auto* start = reinterpret_cast<std::uint8_t*>(padded_.data());
    if (libbfio_memory_range_set(io_.get(), start, range, nullptr) != 1) throw DecodeError("out of memory");
    libolecf_file_t* f = nullptr;
    if (libolecf_file_initialize(&f, nullptr) != 1) throw DecodeError("out of memory");
    libolecf_error_t* err = nullptr;
    if (libolecf_file_open_file_io_handle(f, io_.get(), LIBOLECF_OPEN_READ, &err) != 1) {
      drop(err);
      libolecf_file_free(&f, nullptr);
      throw DecodeError("not an RSLogix project file: the OLE2 container is damaged");
    }
    file_.reset(f);
  }

  // The ObjectData stream of the storage `storage` (for example "PROGRAM FILES"), or nullopt
  // when the project has no such storage.
  std::optional<std::string> object_data(std::string_view storage) {
    libolecf_item_t* root = nullptr;
    libolecf_error_t* err = nullptr;
    if (libolecf_file_get_root_item(file_.get(), &root, &err) != 1 || !root) {
      drop(err);
      throw DecodeError("not an RSLogix project file: the OLE2 container has no root storage");
    }
    ItemPtr root_owner(root);
    ItemPtr dir = sub_item(root, storage);
    if (!dir) return std::nullopt;
    ItemPtr stream = sub_item(dir.get(), "ObjectData");
    if (!stream) return std::nullopt;
    std::uint32_t size = 0;
    if (libolecf_item_get_size(stream.get(), &size, &err) != 1) {
      drop(err);
      throw DecodeError(std::string(storage) + ": cannot read the stream size");
    }
    if (size > kMaxStreamBytes || size > bytes_.size())
      throw DecodeError(std::string(storage) + ": stream size " + std::to_string(size) + " exceeds the file");
    std::string data(size, '\0');
    ssize_t got = size == 0 ? 0 : libolecf_stream_read_buffer(stream.get(), reinterpret_cast<std::uint8_t*>(data.data()), size, &err);
    if (got != static_cast<ssize_t>(size)) {
      drop(err);
      throw DecodeError(std::string(storage) + ": the stream is truncated");
    }
    return data;
  }

 private:
  static ItemPtr sub_item(libolecf_item_t* parent, std::string_view name) {
    libolecf_item_t* out = nullptr;
    libolecf_error_t* err = nullptr;
    int rc = libolecf_item_get_sub_item_by_utf8_name(parent, reinterpret_cast<const std::uint8_t*>(name.data()), name.size(), &out, &err);
    drop(err);
    if (rc != 1) return nullptr;
    return ItemPtr(out);
  }

  static constexpr std::size_t kReadSlack = 64u << 10;  // larger than any sector (4096 in OLE2 v4)
  std::string_view bytes_;
  std::string padded_;  // declared before io_: the handle points into it and is freed first
  std::unique_ptr<libbfio_handle_t, BfioDeleter> io_;
  std::unique_ptr<libolecf_file_t, OlecfFileDeleter> file_;
};

// ---- stream payloads ----------------------------------------------------------------------------
std::uint32_t le32(std::string_view s, std::size_t at) {
  auto b = [&](std::size_t i) { return static_cast<std::uint32_t>(static_cast<unsigned char>(s[at + i])); };
  return b(0) | b(1) << 8 | b(2) << 16 | b(3) << 24;
}

// The 16-byte stream header is: kind (0 stored, 2 zlib), header size (16), stored size, payload
// size. Both kinds occur in every fixture (PROCESSOR is stored, PROGRAM FILES compressed).
std::string payload(std::string_view stream, std::string_view name) {
  if (stream.size() < 16) throw DecodeError(std::string(name) + ": stream shorter than its 16-byte header");
  std::uint32_t kind = le32(stream, 0), header = le32(stream, 4), stored = le32(stream, 8), size = le32(stream, 12);
  if (header != 16 || stored != stream.size() - 16)
    throw DecodeError(std::string(name) + ": stream header does not match the stream (truncated or not an RSLogix project)");
  if (size > kMaxStreamBytes) throw DecodeError(std::string(name) + ": payload of " + std::to_string(size) + " bytes exceeds the limit");
  if (kind == 0) {
    if (size != stored) throw DecodeError(std::string(name) + ": stored stream with inconsistent sizes");
    return std::string(stream.substr(16));
  }
  if (kind != 2) throw DecodeError(std::string(name) + ": unknown stream encoding " + hex(kind));
  std::string out(size, '\0');
  uLongf out_len = size;
  int rc = uncompress(reinterpret_cast<Bytef*>(out.data()), &out_len, reinterpret_cast<const Bytef*>(stream.data() + 16), stored);
  if (rc != Z_OK || out_len != size) throw DecodeError(std::string(name) + ": compressed payload is corrupt");
  return out;
}

// ---- the MFC archive ----------------------------------------------------------------------------
// MFC's CArchive writes an object as a 16-bit tag: 0xFFFF introduces a new class (schema, name
// length, name), 0x8000|n refers to the class registered at map index n; classes and objects
// share one index counter that starts at 1.
class Archive {
 public:
  Archive(std::string_view data, std::string_view stream) : d_(data), stream_(stream) {}

  std::size_t offset() const { return p_; }
  void set_context(std::string c) { context_ = std::move(c); }

  [[noreturn]] void fail(const std::string& what, std::size_t at) const {
    std::string msg(stream_);
    if (!context_.empty()) msg += ": " + context_;
    throw DecodeError(msg + ": " + what + " at offset " + hex(at));
  }

  void need(std::size_t n) const {
    if (n > d_.size() - p_) fail("record runs past the end of the stream", p_);
  }
  std::uint8_t u8() {
    need(1);
    return static_cast<std::uint8_t>(d_[p_++]);
  }
  std::uint16_t u16() {
    need(2);
    std::uint16_t v = static_cast<std::uint16_t>(static_cast<unsigned char>(d_[p_]) | static_cast<unsigned char>(d_[p_ + 1]) << 8);
    p_ += 2;
    return v;
  }
  std::uint32_t u32() {
    need(4);
    std::uint32_t v = le32(d_, p_);
    p_ += 4;
    return v;
  }
  std::string_view bytes(std::size_t n) {
    need(n);
    auto v = d_.substr(p_, n);
    p_ += n;
    return v;
  }
  // An MFC CString: a byte length, or 0xFF and a 16-bit length. Longer strings do not occur in
  // a project and are refused rather than followed.
  std::string cstring() {
    std::size_t at = p_;
    std::size_t n = u8();
    if (n == 0xFF) {
      n = u16();
      if (n == 0xFFFF) fail("string longer than 65534 bytes", at);
    }
    return std::string(bytes(n));
  }
  // Reads an object tag and returns its class name.
  std::string_view object() {
    std::size_t at = p_;
    std::uint16_t tag = u16();
    if (++objects_ > kMaxObjects) fail("too many objects", at);
    if (tag == 0xFFFF) {
      u16();  // schema
      std::uint16_t len = u16();
      if (len == 0 || len > 64) fail("bad class name length", at);
      std::string name(bytes(len));
      for (char c : name)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') fail("class name with characters other than letters and digits", at);
      classes_.emplace_back(next_index_++, std::move(name));
      ++next_index_;  // the object itself
      return classes_.back().second;
    }
    if (!(tag & 0x8000)) fail("unexpected object reference " + hex(tag, 4), at);
    std::uint16_t index = tag & 0x7FFF;
    ++next_index_;
    for (const auto& [i, name] : classes_)
      if (i == index) return name;
    fail("reference to undefined class " + hex(index, 4), at);
  }
  void expect(std::string_view cls) {
    std::size_t at = p_;
    std::string_view got = object();
    if (got != cls) fail("expected a " + std::string(cls) + " record, found " + std::string(got), at);
  }

 private:
  std::string_view d_;
  std::string_view stream_;
  std::string context_;
  std::size_t p_ = 0;
  std::size_t objects_ = 0;
  std::uint32_t next_index_ = 1;
  std::vector<std::pair<std::uint32_t, std::string>> classes_;
};

// One decoded CIns record.
struct InsRecord {
  std::uint16_t selector = 0;
  std::vector<std::string> strings;
  std::size_t offset = 0;  // of the record's tag, for diagnostics
};

// ---- program files → export text ---------------------------------------------------------------
class ProgramDecoder {
 public:
  explicit ProgramDecoder(Archive& a) : a_(a) {}

  // Decodes PROGRAM FILES; appends LADDER sections to `out`.
  void decode(std::string& out, std::vector<RungOrigin>& origins) {
    a_.expect("CProgHolder");
    std::uint16_t files = a_.u16();
    for (std::uint16_t i = 0; i < files; ++i) {
      a_.set_context("program file entry " + std::to_string(i));
      a_.expect("CLadFile");
      a_.u16();  // rung count as displayed; the count before the rungs is the one followed
      std::uint16_t type = a_.u16();
      std::string name(a_.bytes(10));
      name.erase(std::find(name.begin(), name.end(), '\0'), name.end());
      std::uint16_t number = a_.u16();
      std::string description = a_.cstring();
      std::uint16_t rungs = a_.u16();
      // Types seen: 0 system files 0/1, 1 ladder, 3 an unused file number.
      if (type != 1) {
        if (rungs != 0) a_.fail("non-ladder program file " + std::to_string(number) + " with rungs", a_.offset());
        continue;
      }
      if (number < 2 || number > 255) a_.fail("ladder file number " + std::to_string(number) + " out of range", a_.offset());
      out += "\nLADDER " + std::to_string(number);
      if (!name.empty()) out += " " + ladder_name(name);
      out += "\n";
      if (!description.empty()) out += "% " + sanitize_comment(description) + " %\n";
      for (std::uint16_t r = 0; r < rungs; ++r) {
        a_.set_context("file " + std::to_string(number) + " rung " + std::to_string(r));
        a_.expect("CRung");
        std::string text = "SOR";
        leg(text, RungOpen, RungClose, 0);
        a_.bytes(12);  // rung trailer: the last word keys the rung comment in MEM DATABASE
        text += " EOR\n";
        origins.push_back({0, number, r});  // line filled in by read_project
        out += text;
      }
    }
    a_.set_context("");
  }

 private:
  // A file name is written bare when it is an identifier, quoted otherwise ("2FAILSPLUS").
  static std::string ladder_name(std::string s) {
    bool ident = std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_';
    for (char& c : s) {
      if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) ident = false;
      if (c == '"' || static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7F) c = '_';
    }
    return ident ? s : "\"" + s + "\"";
  }
  static std::string sanitize_comment(std::string s) {
    for (char& c : s)
      if (c == '%' || c == '\n' || c == '\r' || static_cast<unsigned char>(c) < 0x20) c = ' ';
    return s;
  }

  InsRecord ins() {
    InsRecord r;
    r.offset = a_.offset();
    std::uint16_t n = a_.u16();
    if (n > 64) a_.fail("instruction record with " + std::to_string(n) + " operand strings", r.offset);
    for (std::uint16_t i = 0; i < n; ++i) r.strings.push_back(a_.cstring());
    std::uint16_t blobs = a_.u16();
    r.selector = a_.u16();
    a_.u32();
    if (blobs > 1) a_.fail("instruction record with " + std::to_string(blobs) + " code blocks", r.offset);
    for (std::uint16_t i = 0; i < blobs; ++i) a_.bytes(a_.u16());  // the compiled form; not needed
    return r;
  }

  // A CBranchLeg: a count, then CIns/CBranch objects framed by `open` and `close` markers.
  void leg(std::string& text, std::uint16_t open, std::uint16_t close, int depth) {
    std::size_t at = a_.offset();
    a_.expect("CBranchLeg");
    std::uint16_t n = a_.u16();
    if (n < 2) a_.fail("branch leg without its start and end markers", at);
    for (std::uint16_t i = 0; i < n; ++i) {
      bool first = i == 0, last = i + 1 == n;
      std::size_t el = a_.offset();
      std::string_view cls = a_.object();
      if (cls == "CBranch") {
        if (first || last) a_.fail("branch where a leg marker belongs", el);
        branch(text, depth + 1);
        continue;
      }
      if (cls != "CIns") a_.fail("unknown record class " + std::string(cls), el);
      InsRecord r = ins();
      if (first || last) {
        std::uint16_t want = first ? open : close;
        if (r.selector != want || !r.strings.empty()) a_.fail("expected leg marker " + std::to_string(want) + ", found selector " + hex(r.selector, 2), el);
        continue;
      }
      instruction(text, r);
    }
  }

  // A CBranch: a count, then the BST marker, the legs, the BND marker.
  void branch(std::string& text, int depth) {
    std::size_t at = a_.offset();
    if (depth > kMaxBranchDepth) a_.fail("branches nested deeper than " + std::to_string(kMaxBranchDepth), at);
    std::uint16_t n = a_.u16();
    if (n < 3) a_.fail("branch with fewer than one leg", at);
    for (std::uint16_t i = 0; i < n; ++i) {
      std::size_t el = a_.offset();
      if (i == 0 || i + 1 == n) {
        a_.expect("CIns");
        InsRecord r = ins();
        std::uint16_t want = i == 0 ? BranchOpen : BranchClose;
        if (r.selector != want || !r.strings.empty()) a_.fail("expected branch marker " + std::to_string(want) + ", found selector " + hex(r.selector, 2), el);
        text += i == 0 ? " BST" : " BND";
        continue;
      }
      if (i > 1) text += " NXB";
      leg(text, LegOpen, LegClose, depth);
    }
  }

  void instruction(std::string& text, const InsRecord& r) {
    const SelectorRow* row = find_selector(r.selector);
    if (!row) a_.fail("unknown instruction selector " + hex(r.selector, 2), r.offset);
    const InstructionSpec* spec = find_instruction(row->mnemonic);
    text += " ";
    text += row->mnemonic;
    if (row->shape == "*") {
      // Layout unconfirmed: only acceptable for an instruction softslc cannot run, which the
      // loader then reports by name. For one it can run, passing strings through unchecked
      // could silently mean something else, so it is an error.
      if (spec)
        a_.fail("operand layout of " + std::string(row->mnemonic) + " records is not known (selector " + hex(r.selector, 2) + ")", r.offset);
      for (const auto& s : r.strings) text += " " + operand_text(s);
      return;
    }
    std::size_t want = 0;
    for (char c : row->shape) want += c == 'v' ? 2 : 1;
    if (r.strings.size() != want)
      a_.fail(std::string(row->mnemonic) + " record has " + std::to_string(r.strings.size()) + " operand strings, expected " + std::to_string(want), r.offset);
    std::size_t k = 0;
    for (std::size_t i = 0; i < row->shape.size(); ++i) {
      std::string s = r.strings[k];
      k += row->shape[i] == 'v' ? 2 : 1;
      if (spec && i < spec->operand_count) s = convert(spec->operands[i].kind, s);
      text += " " + operand_text(s);
    }
  }

  // RSLogix writes a JSR target as "U:3" and a label as "Q2:1"; the export text writes the numbers.
  static std::string convert(OperandKind kind, const std::string& s) {
    if (kind == OperandKind::ProgramFile && s.rfind("U:", 0) == 0) return s.substr(2);
    if (kind == OperandKind::Label && s.size() > 1 && s[0] == 'Q') {
      auto colon = s.find(':');
      if (colon != std::string::npos) return s.substr(colon + 1);
    }
    return s;
  }

  // An operand string must be one token of printable text; anything else is not what RSLogix
  // writes and must not reach the terminal raw.
  std::string operand_text(const std::string& s) {
    if (s.empty()) a_.fail("empty operand string", a_.offset());
    for (char c : s)
      if (static_cast<unsigned char>(c) <= 0x20 || static_cast<unsigned char>(c) >= 0x7F || c == '%')
        a_.fail("operand string with a non-printable or reserved character", a_.offset());
    return s;
  }

  Archive& a_;
};

// ---- processor ----------------------------------------------------------------------------------
// The PROCESSOR stream's CProc record carries a processor type code after its version word.
// Only the code of the fixtures is mapped: every one of them is 0x009C and every report says
// "Processor Type: Bul.1763 MicroLogix 1100 Series B".
// The embedded I/O of a fixed controller becomes SLOT 0 with the image sizes its reports show in
// the Data File List (MicroLogix 1100: INPUT 6 elements, last I:5; OUTPUT 4 elements, last O:3;
// the same in every fixture report). The IO CONFIGURATION stream is not decoded beyond that.
struct ProcessorCode {
  std::uint16_t code;
  std::string_view catalog;
  char series;
  int input_words;
  int output_words;
};
constexpr ProcessorCode kProcessors[] = {{0x009C, "Bul.1763", 'B', 6, 4}};

std::string decode_processor(std::string_view data) {
  Archive a(data, "PROCESSOR");
  a.expect("CProc");
  a.u16();  // record version
  std::size_t at = a.offset();
  std::uint16_t code = a.u16();
  for (const auto& p : kProcessors)
    if (p.code == code)
      return "START " + std::string(p.catalog) + " SERIES " + std::string(1, p.series) + "\nSLOT 0 " + std::string(p.catalog) +
             " SCAN_IN " + std::to_string(p.input_words) + " SCAN_OUT " + std::to_string(p.output_words) + "\n";
  a.fail("unknown processor type code " + hex(code, 4), at);
}

}  // namespace

bool looks_like_ole2(std::string_view bytes) {
  static constexpr unsigned char kSig[] = {0xD0, 0xCF, 0x11, 0xE0, 0xA1, 0xB1, 0x1A, 0xE1};
  return bytes.size() >= sizeof kSig && std::memcmp(bytes.data(), kSig, sizeof kSig) == 0;
}

bool is_known_rslogix_mnemonic(std::string_view mnemonic) {
  return std::any_of(std::begin(kSelectors), std::end(kSelectors), [&](const SelectorRow& r) { return r.mnemonic == mnemonic; });
}

ReadResult read_project(std::string_view bytes, std::string_view source_name) {
  ReadResult result;
  // Messages leave the file name to the caller's diagnostic rendering.
  std::string prefix;
  if (!looks_like_ole2(bytes)) {
    result.error = prefix + "not an RSLogix project file (no OLE2 compound-document signature)";
    return result;
  }
  if (bytes.size() > kMaxFileBytes) {
    result.error = prefix + "file larger than " + std::to_string(kMaxFileBytes >> 20) + " MiB";
    return result;
  }
  try {
    Container c(bytes);
    auto proc = c.object_data("PROCESSOR");
    auto prog = c.object_data("PROGRAM FILES");
    if (!proc || !prog) throw DecodeError("not an RSLogix project file: no PROCESSOR or PROGRAM FILES stream");
    // The file name only (not the path), so the converted text does not depend on where it was read.
    std::string base(source_name.substr(source_name.find_last_of("/\\") == std::string_view::npos ? 0 : source_name.find_last_of("/\\") + 1));
    for (char& ch : base)
      if (static_cast<unsigned char>(ch) < 0x20 || ch == '%' || static_cast<unsigned char>(ch) >= 0x7F) ch = '_';
    std::string text = "% Converted from the RSLogix project file " + base + " by softslc %\n";
    text += decode_processor(payload(*proc, "PROCESSOR"));
    std::string program = payload(*prog, "PROGRAM FILES");
    Archive a(program, "PROGRAM FILES");
    ProgramDecoder(a).decode(text, result.origins);
    // Every rung is one line starting with SOR, in the order of `origins`.
    std::uint32_t line = 1;
    std::size_t next = 0;
    for (std::size_t i = 0; i < text.size(); ++i) {
      if ((i == 0 || text[i - 1] == '\n') && text.compare(i, 4, "SOR ") == 0 && next < result.origins.size())
        result.origins[next++].line = line;
      if (text[i] == '\n') ++line;
    }
    result.text = std::move(text);
  } catch (const DecodeError& e) {
    result.error = prefix + e.what();
    result.origins.clear();
  } catch (const std::bad_alloc&) {
    result.error = prefix + "out of memory while reading the project";
    result.origins.clear();
  }
  return result;
}

}  // namespace softslc::rss

// Debian's libolecf (20181231) leaks its allocation tables and directory entries on some damaged
// files: the leak is inside the library, on its own error paths (found by tests/fuzz/rss_fuzz.cpp,
// 2026-11-24). Under LeakSanitizer every program that links the reader (the CLI, the tests, the
// fuzz target) suppresses exactly that, so a damaged-file test checks softslc, not libolecf. The
// hook lives in this object file because the linker pulls it in with the reader itself.
#if defined(__SANITIZE_ADDRESS__)
#define SOFTSLC_RSS_LSAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SOFTSLC_RSS_LSAN 1
#endif
#endif
#ifdef SOFTSLC_RSS_LSAN
extern "C" const char* __lsan_default_suppressions() { return "leak:libolecf\n"; }
#endif
