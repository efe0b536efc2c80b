// Drive descriptions as JSON, and the drives compiled into the library.
//
// The format (schema "softslc-scanport-drive-1") is documented with an example in
// docs/1203-sm1.md; drives/1305.json is the shipped instance. Parsing is strict so a typo never
// silently becomes a default: every object rejects unknown keys, every number is range-checked
// for the field it fills, and each error names its place the way a reader finds it, as
// "<source>: parameters[3].max: expected an integer" for a bad field (JSON path; parameter
// array index i is parameter number i + 1) or "<source>:12:5: syntax error: ..." followed by
// the offending line and a caret for malformed JSON. After the fields are read, validate()
// (drive.h) checks the cross-field invariants with the same path spelling.
//
// Built-in drives are the files of modules/scanport/drives/, embedded at configure time by
// modules/scanport/CMakeLists.txt, so the runtime needs no data files.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "modules/scanport/drive.h"

namespace softslc::scanport {

inline constexpr std::string_view kDriveSchema = "softslc-scanport-drive-1";

// Parses a description; throws DriveDescriptionError ("<source_name>: ..." as above).
DriveDescription parse_drive_description(std::string_view json_text, std::string_view source_name = "<drive>");
// Reads and parses a file; the file name is the source name.
DriveDescription load_drive_description_file(const std::string& path);

// Names of the built-in drives ("1305"), sorted.
std::vector<std::string> builtin_drive_names();
// The embedded JSON text of a built-in drive; empty when there is no such drive.
std::string_view builtin_drive_json(std::string_view name);
// Parses a built-in drive; throws DriveDescriptionError for an unknown name.
DriveDescription builtin_drive(std::string_view name);

}  // namespace softslc::scanport
