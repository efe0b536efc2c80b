// Reading a file the user named — a program, test, bench, JSON or state file — as one function.
//
// A user can name anything: a directory, /dev/zero, a FIFO, a 2 GB log, a file saved as UTF-16
// by a Windows editor. read_input_file() accepts regular files only (refusing the rest by what
// they are, before reading a byte, and opening without blocking so a FIFO cannot hang the open),
// reads at most a size limit (checked again while reading: /proc files report size 0), and for
// text drops a UTF-8 byte-order mark (as Windows editors write one) and refuses UTF-16 with what
// to do about it, rather than letting the parser report "missing START" on every other byte.
// Every reader of user files goes through it, so a new input type gets the same rules.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

#include "parser/limits.h"

namespace softslc {

enum class InputKind : bool { Text, Binary };

struct InputFile {
  bool ok = false;
  std::string contents;  // the bytes (for Text: without a UTF-8 byte-order mark)
  std::string error;     // when !ok, a phrase to follow "NAME: error: ": "cannot open file: No such file or
                         // directory", "a directory, not a regular file", "UTF-16 file: save it as UTF-8 ..."
};

InputFile read_input_file(const std::filesystem::path& path, InputKind kind = InputKind::Text,
                          std::size_t limit = kMaxInputFileBytes);

// Checks that text is not UTF-16 and drops a UTF-8 byte-order mark. Returns an error or "".
std::string normalise_text_encoding(std::string& text);

}  // namespace softslc
