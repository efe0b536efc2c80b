// libFuzzer target: the .RSS project-file reader (parser/rss) and loading what it produces.
//
// What must hold for any input: no crash, leak, hang or UB; the reader gives either text and no
// error, or an error and no text; an error is one printable line; decoded text loads without a
// crash, and its diagnostics are printable (no file bytes reach the terminal). Seeded by
// tools/fuzz.sh with the 15 projects of ../shared/fixtures/rss.
#include <string>
#include <string_view>

#include "fuzz_target.h"
#include "parser/loader.h"
#include "parser/rss/rss_reader.h"

namespace {

bool printable(std::string_view s) {
  for (char c : s)
    if (c != '\n' && (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7F)) return false;
  return true;
}

std::string rss_property(std::string_view bytes) {
  auto r = softslc::rss::read_project(bytes, "fuzz.RSS");
  if (r.text.has_value() == !r.error.empty()) return "reader returned both or neither of text and error";
  if (!r.text) return printable(r.error) && r.error.find('\n') == std::string::npos ? "" : "error message not one printable line: " + r.error;
  if (!printable(*r.text)) return "converted text holds non-printable bytes";
  auto loaded = softslc::load_program_bytes(std::string(bytes), "fuzz.RSS");
  for (const auto& d : loaded.diagnostics.items())
    if (!printable(d.message)) return "diagnostic with non-printable bytes: " + d.message;
  return "";
}

}  // namespace

SOFTSLC_FUZZ_TARGET(rss_property)
