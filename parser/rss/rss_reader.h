// Reading RSLogix 500 / RSLogix Micro project files (.RSS).
//
// A .RSS file is an OLE2 compound document (read with libolecf) whose streams hold the project
// as an MFC archive, most of them zlib-compressed after a 16-byte header (inflated with zlib).
// The reader decodes the parts softslc needs (the processor; every ladder program file with its
// rungs, branches, instructions and operands; symbols, address descriptions and rung comments from
// MEM DATABASE; every O/I/S/B/N/T/C/R/F/L/ST data file with its saved values, and the O/I force
// tables, from DATA FILES) and writes
// them as RSLogix 500 library export text. The text then goes through the same loader and checker as a .SLC file, so the program
// model, every check and every later stage are exactly those of the text front end, and
// `softslc import` is simply this text, formatted.
//
// Nothing is guessed: an unknown class, an unknown instruction selector, a record whose operand
// count does not match its instruction, or any length running past its stream is an error
// naming the stream, program file, rung and offset. The result is then no text at all, so a
// file that does not decode leaves nothing half-loaded. Every length read from the file is
// bounded (kMaxFileBytes, kMaxStreamBytes, kMaxBranchDepth, kMaxObjects).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace softslc::rss {

inline constexpr std::size_t kMaxFileBytes = 64u << 20;    // whole .RSS file
inline constexpr std::size_t kMaxStreamBytes = 64u << 20;  // one stream, after inflating
inline constexpr int kMaxBranchDepth = 32;                 // nested BST..BND
inline constexpr std::size_t kMaxObjects = 1u << 22;       // MFC archive objects in one stream

// Where one rung of the generated text came from: lets the loader name the program file and
// rung in a diagnostic about a .RSS input instead of a line of text the user never saw.
struct RungOrigin {
  std::uint32_t line = 0;  // 1-based line of the SOR in the generated text
  int file = 0;            // program file number
  int rung = 0;            // rung number within the file (0-based, as RSLogix numbers them)
};

struct ReadResult {
  std::optional<std::string> text;  // export text; set only when the whole project decoded
  std::string error;                // when text is empty: the first problem, positioned
  std::vector<RungOrigin> origins;  // in line order
};

// True when `bytes` starts with the OLE2 compound-document signature. This is how the loader
// tells a project file from export text, whatever the file is called.
bool looks_like_ole2(std::string_view bytes);

// Decodes a whole project. `source_name` is named in the generated text's first comment;
// `error` does not repeat it (the loader's diagnostic rendering puts it in front).
ReadResult read_project(std::string_view bytes, std::string_view source_name);

// Decodes an inflated DATA FILES payload (the MFC archive) of a MicroLogix 1100 project into the
// DATA and FORCE blocks read_project writes for it. For tests of data-file layouts no fixture has
// (expansion I/O); read_project is the way in for everything else.
ReadResult decode_data_files_payload(std::string_view payload);

// True when `mnemonic` is an instruction the .RSS reader knows by name (the selector table).
// The loader uses it to say "not supported yet" rather than "unknown instruction".
bool is_known_rslogix_mnemonic(std::string_view mnemonic);

}  // namespace softslc::rss
