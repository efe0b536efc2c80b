// softslc import: an RSLogix project file (.RSS) → canonical export text (.SLC).
//
// The project is decoded by parser/rss and loaded like any program. When softslc can load it,
// the output is the formatter's canonical text, exactly what `softslc fmt` prints for the same
// project; when it cannot (an instruction or MicroLogix feature softslc does not have yet), the
// converted text is written unformatted so that it can still be read and edited, the reasons
// are printed, and the exit status says the program does not load. Output goes to -o
// atomically (vm/atomic_file.h) or to stdout.
#include <fstream>
#include <iostream>
#include <sstream>

#include "commands.h"
#include "parser/formatter.h"
#include "parser/loader.h"
#include "parser/rss/rss_reader.h"
#include "vm/atomic_file.h"

namespace softslc::cli {

int run_import(const ImportOptions& o) {
  std::ifstream f(o.file, std::ios::binary);
  if (!f) {
    std::cerr << o.file << ": error: cannot open file\n";
    return kInputError;
  }
  std::ostringstream ss;
  ss << f.rdbuf();
  std::string bytes = ss.str();
  rss::ReadResult rr = rss::read_project(bytes, o.file);
  if (!rr.text) {
    std::cerr << o.file << ": error: " << rr.error << "\n";
    return kInputError;
  }
  LoadResult r = load_program_bytes(std::move(bytes), o.file);
  std::string text = r.ok() ? format_program(*r.program) : *rr.text;
  if (!r.ok()) {
    std::cerr << r.render_diagnostics();
    std::cerr << o.file << ": note: converted text written unformatted: softslc cannot load this program yet (see above)\n";
  }
  if (o.output.empty() || o.output == "-") {
    std::cout << text;
    if (!std::cout) return kInputError;
  } else if (auto err = write_file_atomically(o.output, text); !err.empty()) {
    std::cerr << "softslc import: " << err << "\n";
    return kInputError;
  }
  return r.ok() ? kOk : kInputError;
}

}  // namespace softslc::cli
