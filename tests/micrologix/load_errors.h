// What the MicroLogix tests ask of a program text that should not load: its rendered diagnostics
// (gcc style, file "t.slc"), or "" when it loads.
#pragma once

#include <string>

#include "parser/loader.h"

namespace softslc::test {

inline std::string load_errors(const std::string& text) {
  LoadResult r = load_program(text, "t.slc");
  return r.ok() ? std::string() : r.render_diagnostics();
}

}  // namespace softslc::test
