// Writing output files so that a crash or a full disk never leaves a half-written file.
//
// write_file_atomically() writes to a temporary file in the same directory, flushes it to disk
// (fsync), then renames it over the destination: readers see either the old file or the new
// one, never a mixture. A replaced file keeps its permission bits; a symbolic link is written
// through (the file it names is replaced, the link stays); a destination that exists but is
// not a regular file (a device, a directory, a FIFO) is refused.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace softslc {

// Returns an empty string on success, else a message saying what failed.
std::string write_file_atomically(const std::filesystem::path& path, std::string_view contents);

}  // namespace softslc
