#include "vm/state_file.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include "parser/formatter.h"
#include "parser/input_file.h"
#include "vm/atomic_file.h"
#include "vm/runtime.h"

namespace softslc {

namespace {

constexpr char kMagic[16] = {'S', 'O', 'F', 'T', 'S', 'L', 'C', '-', 'S', 'T', 'A', 'T', 'E', '\n', 0, 0};

void put_u8(std::string& out, std::uint8_t v) { out.push_back(static_cast<char>(v)); }
void put_u16(std::string& out, std::uint16_t v) {
  put_u8(out, static_cast<std::uint8_t>(v));
  put_u8(out, static_cast<std::uint8_t>(v >> 8));
}
void put_u32(std::string& out, std::uint32_t v) {
  put_u16(out, static_cast<std::uint16_t>(v));
  put_u16(out, static_cast<std::uint16_t>(v >> 16));
}
void put_u64(std::string& out, std::uint64_t v) {
  put_u32(out, static_cast<std::uint32_t>(v));
  put_u32(out, static_cast<std::uint32_t>(v >> 32));
}

// Reads fixed-size little-endian fields, failing (not throwing) past the end.
class Reader {
 public:
  Reader(const std::string& bytes, std::size_t end) : bytes_(bytes), end_(end) {}
  bool u8(std::uint8_t& v) {
    if (pos_ + 1 > end_) return false;
    v = static_cast<std::uint8_t>(bytes_[pos_++]);
    return true;
  }
  bool u16(std::uint16_t& v) {
    std::uint8_t lo, hi;
    if (!u8(lo) || !u8(hi)) return false;
    v = static_cast<std::uint16_t>(lo | (hi << 8));
    return true;
  }
  bool u32(std::uint32_t& v) {
    std::uint16_t lo, hi;
    if (!u16(lo) || !u16(hi)) return false;
    v = lo | (static_cast<std::uint32_t>(hi) << 16);
    return true;
  }
  bool u64(std::uint64_t& v) {
    std::uint32_t lo, hi;
    if (!u32(lo) || !u32(hi)) return false;
    v = lo | (static_cast<std::uint64_t>(hi) << 32);
    return true;
  }
  bool skip(std::size_t n) {
    if (n > end_ - pos_) return false;
    pos_ += n;
    return true;
  }
  std::size_t pos() const { return pos_; }
  std::size_t remaining() const { return end_ - pos_; }

 private:
  const std::string& bytes_;
  std::size_t end_;
  std::size_t pos_ = 0;
};

// Little-endian word `index` of the words starting at byte `first_byte` (already bounds-checked).
std::uint16_t word_at(const std::string& bytes, std::size_t first_byte, std::uint32_t index) {
  const std::size_t at = first_byte + 2 * static_cast<std::size_t>(index);
  return static_cast<std::uint16_t>(static_cast<std::uint8_t>(bytes[at]) | (static_cast<std::uint8_t>(bytes[at + 1]) << 8));
}

std::string hex64(std::uint64_t v) {
  char buf[20];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

struct ModuleRecord {
  int slot = 0;
  MFile file = MFile::M0;
  std::uint32_t first = 0;
  std::uint32_t count = 0;
  std::size_t first_byte = 0;

  std::string name() const {
    const std::string m = "M" + std::to_string(static_cast<int>(file)) + ":" + std::to_string(slot) + ".";
    return m + std::to_string(first) + "-" + m + std::to_string(first + count - 1);
  }
};

// The range of `saved` that `module` retains now, if it does (same file, first word and length).
bool retains(const Module* module, const ModuleRecord& saved) {
  if (!module) return false;
  for (const auto& r : module->retained_m_words())
    if (r.file == saved.file && r.first >= 0 && static_cast<std::uint32_t>(r.first) == saved.first &&
        r.words.size() == saved.count)
      return true;
  return false;
}

Module* module_in_slot(const std::vector<Module*>& modules, int slot) {
  for (Module* m : modules)
    if (m && m->slot() == slot) return m;
  return nullptr;
}

struct FileRecord {
  int number = 0;
  FileType type = FileType::Integer;
  std::uint8_t words_per_element = 1;
  std::uint32_t elements = 0;
  std::size_t first_byte = 0;  // offset of the words in the byte string
};

}  // namespace

std::uint32_t crc32(const void* data, std::size_t size) {
  // zlib's CRC-32 is the same IEEE 802.3 CRC the format has always used, so files saved before
  // and after the change read alike (format version unchanged). zlib takes lengths as uInt:
  // feed it in chunks.
  const auto* p = static_cast<const Bytef*>(data);
  uLong c = ::crc32(0L, Z_NULL, 0);
  while (size > 0) {
    const auto n = static_cast<uInt>(std::min<std::size_t>(size, 1u << 30));
    c = ::crc32(c, p, n);
    p += n;
    size -= n;
  }
  return static_cast<std::uint32_t>(c);
}

std::uint64_t program_fingerprint(const Program& program) {
  // FNV-1a 64 over the canonical text: independent of spelling, comments and layout of the
  // source file, changed by any change to configuration, rungs, data or symbols.
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (unsigned char c : format_program(program)) {
    h ^= c;
    h *= 0x100000001b3ull;
  }
  return h;
}

std::vector<Module*> chassis_modules(const Runtime& runtime) {
  std::vector<Module*> modules;
  for (int slot = 0; slot < kMaxSlots; ++slot)
    if (Module* m = runtime.module(slot)) modules.push_back(m);
  return modules;
}

std::string encode_state(const DataTable& table, std::uint64_t fingerprint, const std::vector<Module*>& modules) {
  const auto& layout = table.layout();
  std::string out(kMagic, sizeof kMagic);
  put_u32(out, kStateFormatVersion);
  put_u64(out, fingerprint);
  std::uint32_t count = 0;
  // Data files only: a function file (the RTC) is a clock, not program data, and the record's
  // file number is one byte.
  for (std::size_t n = 0; n < kFunctionFileIndex; ++n) count += layout.files[n].present ? 1 : 0;
  put_u32(out, count);
  for (std::size_t n = 0; n < kFunctionFileIndex; ++n) {
    const auto& f = layout.files[n];
    if (!f.present) continue;
    put_u8(out, static_cast<std::uint8_t>(n));
    put_u8(out, static_cast<std::uint8_t>(f.type));
    put_u8(out, f.words_per_element);
    put_u8(out, 0);
    put_u32(out, f.elements);
    for (std::uint32_t w = f.base; w < f.end(); ++w) put_u16(out, table.word(w));
  }
  std::vector<std::pair<int, RetainedMWords>> retained;
  for (const Module* m : modules)
    for (auto& r : m->retained_m_words()) retained.emplace_back(m->slot(), std::move(r));
  put_u32(out, static_cast<std::uint32_t>(retained.size()));
  for (const auto& [slot, r] : retained) {
    put_u8(out, static_cast<std::uint8_t>(slot));
    put_u8(out, static_cast<std::uint8_t>(r.file));
    put_u16(out, 0);
    put_u32(out, static_cast<std::uint32_t>(r.first));
    put_u32(out, static_cast<std::uint32_t>(r.words.size()));
    for (std::uint16_t w : r.words) put_u16(out, w);
  }
  put_u32(out, crc32(out.data(), out.size()));
  return out;
}

StateLoadResult decode_state(const std::string& bytes, std::uint64_t fingerprint, DataTable& table, bool force,
                             const std::vector<Module*>& modules) {
  StateLoadResult r;
  auto refuse = [&](std::string why) {
    r.ok = false;
    r.error = std::move(why);
    return r;
  };
  const std::size_t header = sizeof kMagic + 4 + 8 + 4;
  if (bytes.size() < sizeof kMagic || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
    return refuse("not a softslc state file (bad magic)");
  if (bytes.size() < header + 4) return refuse("truncated state file (" + std::to_string(bytes.size()) + " bytes)");
  // The checksum covers everything else; check it before trusting any length in the file.
  const std::size_t body = bytes.size() - 4;
  std::uint32_t stored = static_cast<std::uint8_t>(bytes[body]) | (static_cast<std::uint8_t>(bytes[body + 1]) << 8) |
                         (static_cast<std::uint8_t>(bytes[body + 2]) << 16) |
                         (static_cast<std::uint32_t>(static_cast<std::uint8_t>(bytes[body + 3])) << 24);
  std::uint32_t version = 0;
  Reader in(bytes, body);
  in.skip(sizeof kMagic);
  in.u32(version);
  if (version == 1)
    return refuse("state file format version 1 is no longer read: this softslc writes version 2, which also "
                  "keeps the M-file words modules retain; remove the file (the run then starts from the "
                  "program's data) or run it with the softslc that saved it");
  if (version != kStateFormatVersion)
    return refuse("state file format version " + std::to_string(version) + " is not supported (this softslc reads " +
                  std::to_string(kStateFormatVersion) + ")");
  if (crc32(bytes.data(), body) != stored)
    return refuse("state file is corrupt or truncated (checksum mismatch)");
  std::uint64_t saved_fingerprint = 0;
  std::uint32_t count = 0;
  in.u64(saved_fingerprint);
  in.u32(count);
  // Parse every record before touching the table, so a bad file restores nothing.
  std::vector<FileRecord> records;
  for (std::uint32_t i = 0; i < count; ++i) {
    FileRecord rec;
    std::uint8_t number, type, wpe, reserved;
    if (!in.u8(number) || !in.u8(type) || !in.u8(wpe) || !in.u8(reserved) || !in.u32(rec.elements))
      return refuse("state file is truncated in file record " + std::to_string(i));
    // Data files: O to M1, and the MicroLogix MG and RI files (function files are not records).
    const bool data_file_type = type <= static_cast<std::uint8_t>(FileType::M1) ||
                                type == static_cast<std::uint8_t>(FileType::Message) ||
                                type == static_cast<std::uint8_t>(FileType::Routing);
    if (!data_file_type || wpe == 0 || reserved != 0 || rec.elements > kMaxElements * 64)
      return refuse("state file has an invalid record for file " + std::to_string(number));
    rec.number = number;
    rec.type = static_cast<FileType>(type);
    rec.words_per_element = wpe;
    rec.first_byte = in.pos();
    std::size_t need = static_cast<std::size_t>(rec.elements) * wpe * 2;
    if (!in.skip(need)) return refuse("state file is truncated in file " + std::to_string(number));
    records.push_back(rec);
  }
  std::uint32_t module_count = 0;
  if (!in.u32(module_count)) return refuse("state file is truncated before its modules section");
  std::vector<ModuleRecord> module_records;
  for (std::uint32_t i = 0; i < module_count; ++i) {
    ModuleRecord rec;
    std::uint8_t slot, file;
    std::uint16_t reserved;
    if (!in.u8(slot) || !in.u8(file) || !in.u16(reserved) || !in.u32(rec.first) || !in.u32(rec.count))
      return refuse("state file is truncated in module record " + std::to_string(i));
    if (slot >= kMaxSlots || file > 1 || reserved != 0 || rec.count == 0)
      return refuse("state file has an invalid module record " + std::to_string(i));
    rec.slot = slot;
    rec.file = static_cast<MFile>(file);
    rec.first_byte = in.pos();
    if (!in.skip(static_cast<std::size_t>(rec.count) * 2))
      return refuse("state file is truncated in the words of " + rec.name());
    module_records.push_back(rec);
  }
  if (in.remaining() != 0) return refuse("state file has trailing bytes after its last record");
  if (saved_fingerprint != fingerprint && !force)
    return refuse("state file was saved by a different program (fingerprint " + hex64(saved_fingerprint) +
                  ", this program " + hex64(fingerprint) + "); use --force-state to restore it anyway");
  for (const auto& rec : module_records)
    if (!force && !retains(module_in_slot(modules, rec.slot), rec))
      return refuse("state file holds " + rec.name() + ", which the module in slot " + std::to_string(rec.slot) +
                    " does not retain; use --force-state to restore the rest anyway");

  const auto& layout = table.layout();
  for (const auto& rec : records) {
    const auto& f = layout.files[static_cast<std::size_t>(rec.number)];
    std::string name = std::string(file_letter(rec.type)) + std::to_string(rec.number);
    if (!f.present || f.type != rec.type || f.words_per_element != rec.words_per_element) {
      r.warnings.push_back("file " + name + " from the state file does not exist in this program; not restored");
      continue;
    }
    std::uint32_t elements = std::min(f.elements, rec.elements);
    if (elements != rec.elements || elements != f.elements)
      r.warnings.push_back("file " + name + " has " + std::to_string(f.elements) + " elements here and " +
                           std::to_string(rec.elements) + " in the state file; restored the first " +
                           std::to_string(elements));
    for (std::uint32_t w = 0; w < elements * f.words_per_element; ++w)
      table.set_word(f.base + w, word_at(bytes, rec.first_byte, w));
  }
  for (const auto& rec : module_records) {
    Module* m = module_in_slot(modules, rec.slot);
    if (!retains(m, rec)) {
      r.warnings.push_back(rec.name() + " from the state file is not retained by the module in slot " +
                           std::to_string(rec.slot) + " here; not restored");
      continue;
    }
    RetainedMWords saved{rec.file, static_cast<int>(rec.first), {}};
    for (std::uint32_t w = 0; w < rec.count; ++w) saved.words.push_back(word_at(bytes, rec.first_byte, w));
    m->restore_m_words(saved);
  }
  r.ok = true;
  return r;
}

std::string save_state_file(const std::string& path, const DataTable& table, std::uint64_t fingerprint,
                            const std::vector<Module*>& modules) {
  return write_file_atomically(path, encode_state(table, fingerprint, modules));
}

StateLoadResult load_state_file(const std::string& path, std::uint64_t fingerprint, DataTable& table, bool force,
                                bool* missing, const std::vector<Module*>& modules) {
  *missing = false;
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 && errno == ENOENT) {
    *missing = true;
    return {true, {}, {}};
  }
  // Regular files only, with a size limit: --state /dev/zero is refused, not read forever.
  InputFile in = read_input_file(path, InputKind::Binary);
  if (!in.ok) return {false, path + ": " + in.error, {}};
  auto r = decode_state(in.contents, fingerprint, table, force, modules);
  if (!r.ok) r.error = path + ": " + r.error;
  return r;
}

namespace {

// The lock file of a state file: ".NAME.lock" beside it. The state file itself cannot carry the
// lock, because every save replaces it (rename) with a new inode a second process could lock.
std::string lock_path_of(const std::filesystem::path& state) {
  auto dir = state.has_parent_path() ? state.parent_path() : std::filesystem::path(".");
  return (dir / ("." + state.filename().string() + ".lock")).string();
}

// A temporary left by write_file_atomically() for this file: ".NAME.XXXXXX", six characters
// from mkstemp's alphabet.
bool is_save_temporary(const std::string& name, const std::string& prefix) {
  if (name.size() != prefix.size() + 6 || name.compare(0, prefix.size(), prefix) != 0) return false;
  return std::all_of(name.begin() + static_cast<std::ptrdiff_t>(prefix.size()), name.end(),
                     [](char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0; });
}

}  // namespace

StateFileLock::~StateFileLock() {
  if (fd_ >= 0) ::close(fd_);  // closing releases the flock
}

StateFileLock::StateFileLock(StateFileLock&& o) noexcept : fd_(o.fd_), removed_(o.removed_) { o.fd_ = -1; }

std::string StateFileLock::acquire(const std::filesystem::path& link_or_state) {
  // Through a symbolic link, the file saved (and locked) is the one it names.
  std::error_code ec;
  const std::filesystem::path state =
      std::filesystem::is_symlink(std::filesystem::symlink_status(link_or_state, ec))
          ? std::filesystem::weakly_canonical(link_or_state, ec)
          : link_or_state;
  const std::string lock = lock_path_of(state);
  fd_ = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0666);
  if (fd_ < 0) return "cannot create the lock file " + lock + ": " + std::strerror(errno);
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int e = errno;
    ::close(fd_);
    fd_ = -1;
    if (e == EWOULDBLOCK)
      return state.string() + " is in use by another softslc run (it holds " + lock +
             "); wait for it to finish, or use another --state file";
    return "cannot lock " + lock + ": " + std::strerror(e);
  }
  // Holding the lock, no other softslc saves this file: any temporary of it is a leftover of a
  // killed save and can go.
  auto dir = state.has_parent_path() ? state.parent_path() : std::filesystem::path(".");
  const std::string prefix = "." + state.filename().string() + ".";
  for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (is_save_temporary(name, prefix) && it->is_regular_file(ec) && std::filesystem::remove(it->path(), ec))
      ++removed_;
  }
  return {};
}

std::string check_state_file_writable(const std::filesystem::path& state) {
  // The file itself: a regular file (or a link to one) or nothing yet.
  std::error_code ec;
  auto st = std::filesystem::status(state, ec);
  if (!ec && std::filesystem::exists(st) && !std::filesystem::is_regular_file(st))
    return state.string() + ": not a regular file; a state file is replaced on every save";
  // The directory the save's temporary goes in: try it, exactly as a save does.
  auto target = std::filesystem::is_symlink(std::filesystem::symlink_status(state, ec))
                    ? std::filesystem::weakly_canonical(state, ec)
                    : state;
  auto dir = target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
  std::string tmpl = (dir / ("." + target.filename().string() + ".XXXXXX")).string();
  int fd = ::mkstemp(tmpl.data());
  if (fd < 0) return "cannot save state in " + dir.string() + ": " + std::strerror(errno);
  ::close(fd);
  ::unlink(tmpl.c_str());
  return {};
}

}  // namespace softslc

