// Retentive state files: the data table saved so it survives a "power cycle", as on the SLC.
//
// `softslc run --state FILE` loads FILE at start (when it exists) and saves it at the end, on a
// clean interrupt (SIGINT/SIGTERM) and, with --checkpoint, periodically. Guarantees:
//   - a save is atomic: temp file in the same directory, fsync, rename, fsync of the directory,
//     so a crash at any moment leaves the previous file or the new one, never a mixture;
//   - every byte is covered: a magic string and format version up front, a CRC-32 at the end,
//     and exact section lengths, so a corrupt, truncated or foreign file is reported, never
//     half-loaded — and never overwritten, since the run stops before it starts;
//   - a state saved by one program is refused for another (the program fingerprint differs)
//     unless the user forces it, in which case files are restored only where number, type and
//     element size agree.
//
// Besides the data table, a state file carries the M-file words each module retains across a
// power loss (Module::retained_m_words(); the 1747-SN retains none, docs/1747-sn.md). They are
// checked with the rest and restored only into a module that retains the same range now.
//
// Format, version 2, all integers little-endian:
//   magic    16 bytes  "SOFTSLC-STATE\n\0\0"
//   version  u32       2 (version 1, without the modules section, is refused with a clear error)
//   program  u64       FNV-1a 64 of the program's canonical text (parser/formatter.h)
//   files    u32       count N, then N records:
//              u8 file number, u8 file type (FileType), u8 words per element, u8 reserved 0,
//              u32 element count, then elements x words-per-element u16 words
//   modules  u32       count M, then M records, in slot order:
//              u8 slot, u8 M file (0 = M0, 1 = M1), u16 reserved 0, u32 first word,
//              u32 word count, then the u16 words
//   crc      u32       CRC-32 (IEEE 802.3) of every byte before it
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "parser/program.h"
#include "vm/data_table.h"
#include "vm/module.h"

namespace softslc {

class Runtime;

inline constexpr std::uint32_t kStateFormatVersion = 2;

// The chassis modules of a runtime, in slot order: what a state file saves retained words from
// and restores them into.
std::vector<Module*> chassis_modules(const Runtime& runtime);

// The fingerprint that ties a state file to a program.
std::uint64_t program_fingerprint(const Program& program);

// Serialises the data table (every file of the layout) and the modules' retained M-file words.
std::string encode_state(const DataTable& table, std::uint64_t fingerprint, const std::vector<Module*>& modules = {});

struct StateLoadResult {
  bool ok = false;
  std::string error;                  // why the file was refused (ok == false)
  std::vector<std::string> warnings;  // forced restore: files skipped or truncated
};

// Checks `bytes` completely, then restores it into `table` and `modules`. A module record whose
// slot holds no module retaining that range (file, first word, length) is refused; with `force`,
// a state from another program is accepted and restored file by file where the layouts agree,
// and such module records are skipped with a warning.
StateLoadResult decode_state(const std::string& bytes, std::uint64_t fingerprint, DataTable& table, bool force,
                             const std::vector<Module*>& modules = {});

// File helpers. save_state_file writes atomically and returns an empty string on success.
std::string save_state_file(const std::string& path, const DataTable& table, std::uint64_t fingerprint,
                            const std::vector<Module*>& modules = {});
// Reads and restores; a missing file is reported as `missing` (not an error: the first run).
StateLoadResult load_state_file(const std::string& path, std::uint64_t fingerprint, DataTable& table, bool force,
                                bool* missing, const std::vector<Module*>& modules = {});

// CRC-32 (IEEE 802.3, reflected, polynomial 0xEDB88320) of a byte string: zlib's crc32.
std::uint32_t crc32(const void* data, std::size_t size);

// An advisory lock (flock) on a state file for the whole of one run, so two `run --state s.bin`
// at once cannot both save and silently lose one run's scans: the second is refused at start
// with a message naming the file. The lock is held on ".NAME.lock" beside the state file (the
// state file itself is replaced by every save, so it cannot carry a lock); holding it, acquire()
// also removes temporaries of killed saves (".NAME.XXXXXX"), which no other process can be
// writing. Released when the object is destroyed (or the process ends, however it ends).
class StateFileLock {
 public:
  StateFileLock() = default;
  StateFileLock(StateFileLock&& o) noexcept;
  StateFileLock& operator=(StateFileLock&&) = delete;
  ~StateFileLock();
  // Returns an empty string when the lock is held, else why not.
  std::string acquire(const std::filesystem::path& state);
  // Stale temporaries acquire() removed.
  int removed_temporaries() const { return removed_; }

 private:
  int fd_ = -1;
  int removed_ = 0;
};

// Whether a save can succeed: the state file is a regular file (or absent) and its directory
// takes a new file. Checked before the first scan, so an unwritable location is not found
// only after the whole run. Returns an empty string, or why not.
std::string check_state_file_writable(const std::filesystem::path& state);

}  // namespace softslc
