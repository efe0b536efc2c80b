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
// Format, version 1, all integers little-endian:
//   magic    16 bytes  "SOFTSLC-STATE\n\0\0"
//   version  u32       1
//   program  u64       FNV-1a 64 of the program's canonical text (parser/formatter.h)
//   files    u32       count N, then N records:
//              u8 file number, u8 file type (FileType), u8 words per element, u8 reserved 0,
//              u32 element count, then elements x words-per-element u16 words
//   crc      u32       CRC-32 (IEEE 802.3) of every byte before it
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "parser/program.h"
#include "vm/data_table.h"

namespace softslc {

inline constexpr std::uint32_t kStateFormatVersion = 1;

// The fingerprint that ties a state file to a program.
std::uint64_t program_fingerprint(const Program& program);

// Serialises the data table (every file of the layout).
std::string encode_state(const DataTable& table, std::uint64_t fingerprint);

struct StateLoadResult {
  bool ok = false;
  std::string error;                  // why the file was refused (ok == false)
  std::vector<std::string> warnings;  // forced restore: files skipped or truncated
};

// Checks `bytes` completely, then restores it into `table`. With `force`, a state from another
// program is accepted and restored file by file where the layouts agree.
StateLoadResult decode_state(const std::string& bytes, std::uint64_t fingerprint, DataTable& table, bool force);

// File helpers. save_state_file writes atomically and returns an empty string on success.
std::string save_state_file(const std::string& path, const DataTable& table, std::uint64_t fingerprint);
// Reads and restores; a missing file is reported as `missing` (not an error: the first run).
StateLoadResult load_state_file(const std::string& path, std::uint64_t fingerprint, DataTable& table, bool force,
                                bool* missing);

// CRC-32 (IEEE 802.3, reflected, polynomial 0xEDB88320) of a byte string.
std::uint32_t crc32(const void* data, std::size_t size);

}  // namespace softslc
