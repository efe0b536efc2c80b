// The .RSS reader: OLE2 container (libolecf) → stream payload (zlib) → MFC archive → export text.
// See rss_reader.h for the design; docs/program-format.md for what is and is not read.
#include "parser/rss/rss_reader.h"

#include <libbfio.h>
#include <libolecf.h>
#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <array>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <stdexcept>

#include "instructions/instruction_table.h"
#include "parser/address.h"

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
  // libolecf sizes its allocation tables from the header's sector counts before it reads a
  // sector: a damaged header asking for 16 million MSAT sectors made it allocate and clear
  // hundreds of MB for a 140 KB file (found by rss_fuzz). Every sector a count names must be in
  // the file, so a count larger than the file's sectors is refused here, before libolecf.
  static void check_sector_counts(const std::string& padded, std::size_t range) {
    auto u16 = [&](std::size_t at) {
      return static_cast<std::uint32_t>(static_cast<std::uint8_t>(padded[at]) |
                                        static_cast<std::uint8_t>(padded[at + 1]) << 8);
    };
    auto u32 = [&](std::size_t at) { return u16(at) | u16(at + 2) << 16; };
    const std::uint32_t shift = u16(0x1E);  // sector size 2^shift: 512 (v3) or 4096 (v4)
    if (shift != 9 && shift != 12) throw DecodeError("not an RSLogix project file: the OLE2 container is damaged");
    const std::uint64_t sectors = (range + (std::uint64_t{1} << shift) - 1) >> shift;
    for (const auto& [at, what] : {std::pair<std::size_t, const char*>{0x2C, "allocation-table"},
                                   {0x40, "short-allocation-table"},
                                   {0x48, "master-allocation-table"}}) {
      if (u32(at) > sectors)
        throw DecodeError("not an RSLogix project file: the OLE2 container is damaged (its header names " +
                          std::to_string(u32(at)) + " " + what + " sectors in a file of " + std::to_string(sectors) +
                          ")");
    }
  }

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
    check_sector_counts(padded_, range);
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
// Rung comments from MEM DATABASE: (program file, rung) → text, lines separated by '\n'.
using RungComments = std::map<std::pair<int, int>, std::string>;

// One line of free text as the export's `% ... %` comment syntax can carry it: '%' (the
// delimiter), tabs, control and non-ASCII bytes become blanks; leading/trailing blanks go.
std::string comment_text(std::string_view s) {
  std::string out;
  for (char c : s) {
    auto u = static_cast<unsigned char>(c);
    out += (c == '%' || u < 0x20 || u >= 0x7F) ? ' ' : c;
  }
  auto b = out.find_first_not_of(' ');
  if (b == std::string::npos) return {};
  return out.substr(b, out.find_last_not_of(' ') - b + 1);
}

class ProgramDecoder {
 public:
  ProgramDecoder(Archive& a, const RungComments& comments) : a_(a), comments_(comments) {}

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
      a_.cstring();  // the file's description: the export text has no place for it (a comment
                     // line after LADDER would become rung 0's comment)
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
      for (std::uint16_t r = 0; r < rungs; ++r) {
        a_.set_context("file " + std::to_string(number) + " rung " + std::to_string(r));
        a_.expect("CRung");
        // The comment goes on `% ... %` lines directly above the SOR, one per line of the
        // comment (the loader joins them with newlines again).
        if (auto c = comments_.find({number, r}); c != comments_.end()) {
          std::size_t start = 0;
          const std::string& body = c->second;
          while (start <= body.size()) {
            std::size_t end = body.find('\n', start);
            if (end == std::string::npos) end = body.size();
            out += "% " + comment_text(std::string_view(body).substr(start, end - start)) + " %\n";
            start = end + 1;
          }
        }
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
  const RungComments& comments_;
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

const ProcessorCode& decode_processor(std::string_view data) {
  Archive a(data, "PROCESSOR");
  a.expect("CProc");
  a.u16();  // record version
  std::size_t at = a.offset();
  std::uint16_t code = a.u16();
  for (const auto& p : kProcessors)
    if (p.code == code) return p;
  a.fail("unknown processor type code " + hex(code, 4), at);
}

std::string processor_text(const ProcessorCode& p) {
  return "START " + std::string(p.catalog) + " SERIES " + std::string(1, p.series) + "\nSLOT 0 " + std::string(p.catalog) +
         " SCAN_IN " + std::to_string(p.input_words) + " SCAN_OUT " + std::to_string(p.output_words) + "\n";
}

// ---- MEM DATABASE: symbols, address descriptions, rung comments ----------------------------------
// The payload (confirmed on all 15 fixtures: every byte is accounted for) is a DBXMemMap record:
// six 32-bit words (version 1, 20 characters a line, 5 lines, ...), the marker string "Valid
// Database Entry!", five 32-bit words, a 16-bit entry count and two 16-bit words; then per entry
// 8 bytes, the key (an address in RSLogix's fixed-width form, "B0003:000/11", "I0001:000.000/02",
// or a non-address key: "DFILE:00007", "PFILE:00012", "U:00003", "Q2:0", function files
// "RTC0000:000.005/01"), the symbol, the 5 description lines, and 16 bytes of list links. Then a
// 16-bit count of rung comments, each a 32-bit id, the comment (CRLF between lines), the page
// title and the key "RUNGffffff-rrrrrr" (program file, rung). Then a 16-bit count that is 0 in
// every fixture. The reports print the same symbols ("(LAMP_FLASH_TON)" beside T4:0) and comments.
struct AddressEntry {
  std::string address;  // in the export text's spelling
  std::string symbol;
  std::string description;
};
struct MemDatabase {
  std::vector<AddressEntry> entries;  // in database order; only entries with an address key
  RungComments comments;
};

// "B0003:000/11" → "B3:0/11", "I0001:000.000/02" → "I:0.0/2", "S0002:001/15" → "S:1/15",
// "T0004:000.002" → "T4:0.2". Any other key (function files, indirect keys, program files,
// labels, data-file names) gives nullopt: it names no data-table address the text can carry.
std::optional<std::string> key_to_address(std::string_view key) {
  std::size_t i = 0;
  while (i < key.size() && std::isupper(static_cast<unsigned char>(key[i]))) ++i;
  std::string type(key.substr(0, i));
  static constexpr std::string_view kTypes[] = {"O", "I", "S", "B", "T", "C", "R", "N", "F", "L", "ST"};
  if (std::find(std::begin(kTypes), std::end(kTypes), type) == std::end(kTypes)) return std::nullopt;
  auto digits = [&](std::size_t n) -> std::optional<int> {
    if (key.size() - i < n) return std::nullopt;
    int v = 0;
    for (std::size_t k = 0; k < n; ++k) {
      char c = key[i + k];
      if (c < '0' || c > '9') return std::nullopt;
      v = v * 10 + (c - '0');
    }
    i += n;
    return v;
  };
  auto file = digits(4);
  if (!file || i >= key.size() || key[i++] != ':') return std::nullopt;
  auto element = digits(3);
  if (!element) return std::nullopt;
  std::optional<int> word, bit;
  if (i < key.size() && key[i] == '.') {
    ++i;
    if (!(word = digits(3))) return std::nullopt;
  }
  if (i < key.size() && key[i] == '/') {
    ++i;
    if (!(bit = digits(2))) return std::nullopt;
  }
  if (i != key.size()) return std::nullopt;
  std::string out;
  if (type == "O" || type == "I") {
    if (*file != (type == "O" ? 0 : 1)) return std::nullopt;
    out = type + ":" + std::to_string(*element);
  } else if (type == "S") {
    if (*file != 2 || word) return std::nullopt;
    out = "S:" + std::to_string(*element);
  } else {
    out = type + std::to_string(*file) + ":" + std::to_string(*element);
  }
  if (word) out += "." + std::to_string(*word);
  if (bit) out += "/" + std::to_string(*bit);
  return out;
}

MemDatabase decode_mem_database(std::string_view data) {
  MemDatabase db;
  Archive a(data, "MEM DATABASE");
  a.expect("DBXMemMap");
  std::array<std::uint32_t, 6> head{};
  for (auto& w : head) w = a.u32();
  if (head[0] != 1 || head[2] != 5) a.fail("unknown database layout (version " + std::to_string(head[0]) + ", " + std::to_string(head[2]) + " description lines)", 0);
  a.cstring();
  for (int k = 0; k < 5; ++k) a.u32();
  std::uint16_t count = a.u16();
  a.u16();
  a.u16();
  for (std::uint16_t e = 0; e < count; ++e) {
    a.bytes(8);
    std::size_t at = a.offset();
    std::string key = a.cstring();
    std::string symbol = a.cstring();
    std::string description;
    for (int line = 0; line < 5; ++line) {
      std::string t = comment_text(a.cstring());
      if (t.empty()) continue;
      if (!description.empty()) description += ' ';
      description += t;
    }
    a.bytes(16);
    if (symbol.empty() && description.empty()) continue;
    auto address = key_to_address(key);
    if (!address) continue;
    if (!symbol.empty()) {
      // Letters, digits and '_', not digits only (the SYMBOL statement's name).
      bool ident = std::any_of(symbol.begin(), symbol.end(), [](char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; });
      for (char c : symbol)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') ident = false;
      if (!ident) a.fail("symbol of " + *address + " is not a name", at);
    }
    db.entries.push_back({*address, symbol, description});
  }
  std::uint16_t comments = a.u16();
  for (std::uint16_t c = 0; c < comments; ++c) {
    a.u32();
    std::string text = a.cstring();
    a.cstring();  // page title: not carried by the export text
    std::size_t at = a.offset();
    std::string key = a.cstring();
    // "RUNG000002-000007": program file 2, rung 7. A comment attached to an output address
    // (research: key "B0003:000/01") has no place in the export text; none of the fixtures has one.
    if (key.size() != 17 || key.compare(0, 4, "RUNG") != 0 || key[10] != '-') continue;
    int file = 0, rung = 0;
    for (std::size_t k = 4; k < 17; ++k) {
      if (k == 10) continue;
      if (key[k] < '0' || key[k] > '9') a.fail("malformed rung comment key", at);
      (k < 10 ? file : rung) = (k < 10 ? file : rung) * 10 + (key[k] - '0');
    }
    std::string joined;
    for (char ch : text)
      if (ch != '\r') joined += ch;
    while (!joined.empty() && (joined.back() == '\n' || joined.back() == ' ')) joined.pop_back();
    db.comments[{file, rung}] = joined;
  }
  std::size_t at = a.offset();
  if (a.u16() != 0) a.fail("unknown MEM DATABASE record group", at);
  if (a.offset() != data.size()) a.fail("unexpected data after the last record", a.offset());
  return db;
}

void write_symbols(const MemDatabase& db, std::string& out) {
  if (db.entries.empty()) return;
  out += "\n";
  for (const auto& e : db.entries) {
    if (e.symbol.empty())
      out += "DESC " + e.address + " % " + e.description + " %\n";
    else
      out += "SYMBOL " + e.address + " " + e.symbol + (e.description.empty() ? "" : " % " + e.description + " %") + "\n";
  }
}

// ---- DATA FILES: every data file's type, number, size and saved values ------------------------
// The payload is a CDataHolder: a 16-bit count of data files 0..n, each a CDataFile record; a
// count of MicroLogix function files (CDataFile records of types 0x11 and up); then M files.
// A CDataFile record: type (0 O, 1 I, 2 S, 3 B, 4 T, 5 C, 6 R, 7 N, 8 F, 0x0A unused number,
// 0x0E ST, 0x10 L, 0x13 MG), 6 bytes, element count, words per element, 2 bytes, 0xFFFF, the
// values (little-endian words; T/C/R as CTL PRE ACC; F IEEE single and L two's complement, low
// word first; ST a length word and 82 characters, two to a word, high byte first), for O and I
// an ON/OFF force pair per word, the file number, description and name, and 4 bytes.
// Confirmed against the Data File List and the data-file pages of the reports.
enum DataType : std::uint16_t { DtOutput = 0, DtInput = 1, DtStatus = 2, DtBinary = 3, DtTimer = 4, DtCounter = 5, DtControl = 6,
                                DtInteger = 7, DtFloat = 8, DtUnused = 0x0A, DtString = 0x0E, DtLong = 0x10, DtMessage = 0x13 };

// The type code of the STI function file's record among the function files.
constexpr std::uint16_t kStiFunctionFile = 0x14;
// The EII's (MicroLogix 1100: four elements of four words, PFN ER bits IS; eii:: in parser/address.h).
constexpr std::uint16_t kEiiFunctionFile = 0x15;
// The PTO's (MicroLogix 1100: two elements of 12 words; docs/micrologix-function-files-sources.md 6.3).
constexpr std::uint16_t kPtoFunctionFile = 0x12;
// The type code of the HSC function file's record: one element of 18 words per high-speed counter
// (docs/micrologix-function-files-sources.md section 6.1).
constexpr std::uint16_t kHscFunctionFile = 0x11;

struct DataFileRecord {
  std::uint16_t type = 0;
  int number = 0;
  int elements = 0;
  int words_per_element = 0;
  std::string_view values;
  std::string_view forces;  // O and I: an ON word and an OFF word per image word
};

DataFileRecord data_file_record(Archive& a) {
  DataFileRecord r;
  std::size_t at = a.offset();
  r.type = a.u16();
  a.bytes(6);
  r.elements = a.u16();
  r.words_per_element = a.u16();
  a.u16();
  a.u16();
  r.values = a.bytes(static_cast<std::size_t>(r.elements) * static_cast<std::size_t>(r.words_per_element) * 2);
  if (r.type == DtOutput || r.type == DtInput) r.forces = a.bytes(static_cast<std::size_t>(r.elements) * 4);
  r.number = a.u16();
  a.cstring();
  a.cstring();
  a.bytes(4);
  static constexpr std::pair<std::uint16_t, int> kWords[] = {{DtOutput, 1}, {DtInput, 1},   {DtStatus, 1}, {DtBinary, 1},
                                                            {DtInteger, 1}, {DtTimer, 3},   {DtCounter, 3}, {DtControl, 3},
                                                            {DtFloat, 2},   {DtLong, 2},    {DtString, 42}};
  for (auto [t, w] : kWords)
    if (t == r.type && w != r.words_per_element)
      a.fail("data file " + std::to_string(r.number) + " has " + std::to_string(r.words_per_element) + " words per element", at);
  if (r.elements > 256) a.fail("data file " + std::to_string(r.number) + " has " + std::to_string(r.elements) + " elements", at);
  return r;
}

std::uint16_t word_at(std::string_view v, std::size_t w) {
  return static_cast<std::uint16_t>(static_cast<unsigned char>(v[2 * w]) | static_cast<unsigned char>(v[2 * w + 1]) << 8);
}

std::string hex_word(std::uint16_t w) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "0X%04X", w);
  return buf;
}

// The O and I files hold the embedded slot's image words (docs/program-format.md): the saved
// image as a DATA block and the force table as a FORCE block, in the export's own form
// ("FORCE O:00", one "ON OFF" row per word; 0X0000 0XFFFF is "nothing forced", the pair every
// fixture stores for every word). A file larger than the embedded image means expansion I/O,
// whose modules the reader does not decode: that is an error, not a silent loss of slots.
void write_io_file(const DataFileRecord& r, const ProcessorCode& processor, Archive& a, std::string& out, std::string& forces) {
  const bool output = r.type == DtOutput;
  const int embedded = output ? processor.output_words : processor.input_words;
  const std::string letter = output ? "O" : "I";
  if (r.elements != embedded)
    a.fail(std::string(output ? "OUTPUT" : "INPUT") + " file of " + std::to_string(r.elements) + " words; the " + std::string(processor.catalog) +
               "'s embedded I/O has " + std::to_string(embedded) +
               ": expansion I/O is not read by softslc yet (docs/program-format.md)",
           a.offset());
  out += "\nDATA " + letter + ":0\n% " + letter + ":0.0 %";
  for (int w = 0; w < r.elements; ++w) out += " " + hex_word(word_at(r.values, static_cast<std::size_t>(w)));
  out += "\n";
  forces += "\nFORCE " + letter + ":00\n% ON     OFF  %\n";
  for (int w = 0; w < r.elements; ++w)
    forces += hex_word(word_at(r.forces, 2 * static_cast<std::size_t>(w))) + " " + hex_word(word_at(r.forces, 2 * static_cast<std::size_t>(w) + 1)) +
              " % FORCE " + letter + ":0." + std::to_string(w) + " %\n";
}

void write_data_file(const DataFileRecord& r, const ProcessorCode& processor, Archive& a, std::string& out, std::string& forces) {
  if (r.elements == 0) return;
  if (r.type == DtOutput || r.type == DtInput) return write_io_file(r, processor, a, out, forces);
  std::string letter;
  switch (r.type) {
    case DtStatus: letter = "S"; break;
    case DtBinary: letter = "B"; break;
    case DtTimer: letter = "T"; break;
    case DtCounter: letter = "C"; break;
    case DtControl: letter = "R"; break;
    case DtInteger: letter = "N"; break;
    case DtFloat: letter = "F"; break;
    case DtLong: letter = "L"; break;
    case DtString: letter = "ST"; break;
    default: return;  // MG, unused numbers: not carried (docs/program-format.md)
  }
  // The status file is addressed without its number: DATA S:0, rows "% S:10 %".
  const std::string file = r.type == DtStatus ? letter : letter + std::to_string(r.number);
  out += "\nDATA " + file + ":0\n";
  auto element = [&](int e) { return "% " + file + ":" + std::to_string(e) + " %"; };
  if (r.type == DtTimer || r.type == DtCounter || r.type == DtControl) {
    out += r.type == DtControl ? "% .CTL .LEN .POS %\n" : "% .CTL .PRE .ACC %\n";
    for (int e = 0; e < r.elements; ++e) {
      char row[64];
      std::snprintf(row, sizeof row, "0X%04X %d %d ", word_at(r.values, 3 * static_cast<std::size_t>(e)), static_cast<std::int16_t>(word_at(r.values, 3 * e + 1)),
                    static_cast<std::int16_t>(word_at(r.values, 3 * e + 2)));
      out += row + element(e) + "\n";
    }
    return;
  }
  if (r.type == DtString) {
    for (int e = 0; e < r.elements; ++e) {
      std::size_t base = static_cast<std::size_t>(e) * 42;
      std::size_t length = word_at(r.values, base);
      if (length > 82) a.fail("string " + file + ":" + std::to_string(e) + " is " + std::to_string(length) + " characters long", a.offset());
      std::string text;
      for (std::size_t k = 0; k < length; ++k) {
        std::uint16_t w = word_at(r.values, base + 1 + k / 2);
        char c = static_cast<char>(k % 2 == 0 ? w >> 8 : w & 0xFF);
        if (c == '"' || static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7F)
          a.fail("string " + file + ":" + std::to_string(e) + " holds a character the export text cannot carry", a.offset());
        text += c;
      }
      out += element(e) + " \"" + text + "\"\n";
    }
    return;
  }
  const bool wide = r.type == DtFloat || r.type == DtLong;
  const int per_row = wide ? 5 : 10;
  for (int e = 0; e < r.elements; ++e) {
    if (e % per_row == 0) out += (e ? "\n" : "") + element(e);
    std::string v;
    if (!wide) {
      v = std::to_string(static_cast<std::int16_t>(word_at(r.values, e)));
    } else {
      std::uint32_t bits = word_at(r.values, 2 * static_cast<std::size_t>(e)) | static_cast<std::uint32_t>(word_at(r.values, 2 * e + 1)) << 16;
      if (r.type == DtLong) {
        v = std::to_string(static_cast<std::int32_t>(bits));
      } else {
        float f;
        std::memcpy(&f, &bits, sizeof f);
        if (!std::isfinite(f)) a.fail(file + ":" + std::to_string(e) + " holds an infinity or NaN, which the export text cannot carry", a.offset());
        char buf[32];
        auto res = std::to_chars(buf, buf + sizeof buf, f);
        v.assign(buf, res.ptr);
        if (v.find_first_of(".e") == std::string::npos) v += ".0";
      }
    }
    out += " " + v;
  }
  out += "\n";
}

// The PTO record (type 0x12): per element OUT, bits, ER, OF, OFS, JF and the long words TOP, OPP, ADP
// (low word first). 20230719_MicroLogix_1100_driver_of_Micro8xx_2080-MOT-HSC.RSS holds 2 0 0 2000 0 0
// 2147483647 0 0 in PTO:0 (its comments: OUT 2, OF 2000, TOP 2147483647), every other project -1 and
// zeros. Written as RSLogix exports a PTOX element (59-BSGS.SLC): nine values, the bit word in hex.
void write_pto_function_file(const DataFileRecord& r, Archive& a, std::size_t at, std::string& out) {
  if (r.words_per_element != 12 || r.elements < 1 || r.elements > 2)
    a.fail("the PTO function file has " + std::to_string(r.elements) + " elements of " + std::to_string(r.words_per_element) +
               " words (one or two of 12 expected)",
           at);
  out += "\nDATA PTO0:0\n";
  for (int e = 0; e < r.elements; ++e) {
    const std::size_t b = static_cast<std::size_t>(e) * 12;
    auto word = [&](std::size_t w) { return std::to_string(static_cast<std::int16_t>(word_at(r.values, b + w))); };
    auto uword = [&](std::size_t w) { return std::to_string(word_at(r.values, b + w)); };
    auto long_word = [&](std::size_t w) {
      return std::to_string(static_cast<std::int32_t>(word_at(r.values, b + w) | static_cast<std::uint32_t>(word_at(r.values, b + w + 1)) << 16));
    };
    out += "% PTO0:" + std::to_string(e) + " %\n" + word(0) + " " + hex_word(word_at(r.values, b + 1)) + " " + word(2) + " " + uword(3) +
           " " + uword(4) + " " + uword(5) + " " + long_word(6) + " " + long_word(8) + " " + long_word(10) + "\n";
  }
}

// The HSC record, written as RSLogix's export writes DATA HSC0:0 (59-BSGS.SLC): per element PFN ER
// bits bits MOD, the long words ACC HIP LOP OVF UNF (stored low word first: TVZ_1100_REV02.RSS holds
// HIP 30 as 001E 0000), then OMB HPO LPO (hsc:: in parser/address.h).
void write_hsc_function_file(const DataFileRecord& r, Archive& a, std::size_t at, std::string& out) {
  if (r.elements < 1 || r.elements > 6 || r.words_per_element != hsc::kWords)
    a.fail("the HSC function file has " + std::to_string(r.elements) + " elements of " + std::to_string(r.words_per_element) +
               " words (1 to 6 of 18 expected)",
           at);
  out += "\nDATA HSC0:0\n";
  for (int e = 0; e < r.elements; ++e) {
    const std::size_t base = static_cast<std::size_t>(e) * static_cast<std::size_t>(hsc::kWords);
    const auto word = [&](std::size_t w) { return word_at(r.values, base + w); };
    out += "% HSC0:" + std::to_string(e) + " %\n";
    for (std::size_t k = 0; k < hsc::kExportValues; ++k) {
      const auto w = static_cast<std::size_t>(hsc::export_value_word(k));
      std::string v;
      if (hsc::export_value_is_long(k))
        v = std::to_string(static_cast<std::int32_t>(word(w) | static_cast<std::uint32_t>(word(w + 1)) << 16));
      else if (w == hsc::kBits || w == hsc::kStatus)
        v = hex_word(word(w));
      else
        v = std::to_string(word(w));
      out += v + (k == 4 || k == 9 || k == 12 ? "\n" : " ");
    }
  }
}

// The EII record (type 0x15), written as RSLogix's export writes DATA EII0:0 (59-BSGS.SLC): per
// element PFN ER bits IS, the bit word in hex. Every fixture holds 0 0 0x4002 n in element n.
void write_eii_function_file(const DataFileRecord& r, Archive& a, std::size_t at, std::string& out) {
  if (r.elements < 1 || r.elements > eii::kMaxElements || r.words_per_element != eii::kWords)
    a.fail("the EII function file has " + std::to_string(r.elements) + " elements of " + std::to_string(r.words_per_element) +
               " words (1 to 8 of 4 expected)",
           at);
  out += "\nDATA EII0:0\n";
  for (int e = 0; e < r.elements; ++e) {
    const std::size_t base = static_cast<std::size_t>(e) * static_cast<std::size_t>(eii::kWords);
    out += "% EII0:" + std::to_string(e) + " %\n" + std::to_string(word_at(r.values, base)) + " " +
           std::to_string(word_at(r.values, base + 1)) + " " + hex_word(word_at(r.values, base + 2)) + " " +
           std::to_string(word_at(r.values, base + 3)) + "\n";
  }
}

void decode_data_files(std::string_view data, const ProcessorCode& processor, std::string& out) {
  Archive a(data, "DATA FILES");
  a.expect("CDataHolder");
  std::uint16_t files = a.u16();
  std::string forces;
  for (std::uint16_t i = 0; i < files; ++i) {
    a.set_context("data file entry " + std::to_string(i));
    a.expect("CDataFile");
    DataFileRecord r = data_file_record(a);
    write_data_file(r, processor, a, out, forces);
  }
  // Then a count of function files, each a CDataFile record whose type code names it. The STI's
  // (type 0x14) is one element of four words, PFN ER bits SPM: sti_1000ms_live.RSS holds 3 0 0x0002 0
  // (its STS sets the time), TVZ_1100_REV02.RSS 13 0 0x0032 300 (an auto-started STI every 300 ms,
  // as its annotations say), every project without an STI 0 0 0x0002 0, which is also the row an
  // RSLogix export writes (DATA STI0:0 in 59-BSGS.SLC; docs/micrologix-function-files-sources.md
  // section 6). It is written as that export writes it, after the data files and before the force
  // tables; the other function files and the M files that follow are not read (docs/program-format.md).
  const std::uint16_t functions = a.u16();
  for (std::uint16_t i = 0; i < functions; ++i) {
    a.set_context("function file entry " + std::to_string(i));
    a.expect("CDataFile");
    const std::size_t at = a.offset();
    DataFileRecord r = data_file_record(a);
    if (r.type == kHscFunctionFile) {
      write_hsc_function_file(r, a, at, out);
      continue;
    }
    if (r.type == kPtoFunctionFile) {
      write_pto_function_file(r, a, at, out);
      continue;
    }
    if (r.type == kEiiFunctionFile) {
      write_eii_function_file(r, a, at, out);
      continue;
    }
    if (r.type != kStiFunctionFile) continue;
    if (r.elements != 1 || r.words_per_element != 4)
      a.fail("the STI function file has " + std::to_string(r.elements) + " elements of " + std::to_string(r.words_per_element) +
                 " words (one of four expected)",
             at);
    out += "\nDATA STI0:0\n% STI0:0 %\n";
    for (std::size_t w = 0; w < 4; ++w)
      out += (w ? " " : "") + (w == 2 ? hex_word(word_at(r.values, w)) : std::to_string(word_at(r.values, w)));
    out += "\n";
  }
  out += forces;
}

}  // namespace

bool looks_like_ole2(std::string_view bytes) {
  static constexpr unsigned char kSig[] = {0xD0, 0xCF, 0x11, 0xE0, 0xA1, 0xB1, 0x1A, 0xE1};
  return bytes.size() >= sizeof kSig && std::memcmp(bytes.data(), kSig, sizeof kSig) == 0;
}

ReadResult decode_data_files_payload(std::string_view payload) {
  ReadResult result;
  try {
    std::string text;
    decode_data_files(payload, kProcessors[0], text);
    result.text = std::move(text);
  } catch (const DecodeError& e) {
    result.error = e.what();
  }
  return result;
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
    const ProcessorCode& processor = decode_processor(payload(*proc, "PROCESSOR"));
    text += processor_text(processor);
    MemDatabase db;
    if (auto mem = c.object_data("MEM DATABASE")) db = decode_mem_database(payload(*mem, "MEM DATABASE"));
    std::string program = payload(*prog, "PROGRAM FILES");
    Archive a(program, "PROGRAM FILES");
    ProgramDecoder(a, db.comments).decode(text, result.origins);
    if (auto data = c.object_data("DATA FILES")) decode_data_files(payload(*data, "DATA FILES"), processor, text);
    write_symbols(db, text);
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
