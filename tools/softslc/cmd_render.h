// `softslc render`: ladder diagrams as text or SVG (tools/trace/ladder_layout.h), optionally with
// values and power flow from a state file or after running some scans.
#pragma once

#include <string>

namespace CLI {
class App;
}

namespace softslc::cli {

struct RenderOptions {
  std::string file;
  int program_file = -1;     // --file N; -1 = every file
  std::string rungs;         // --rung N or N..M; empty = all
  std::string svg;           // --svg OUT; empty = text on stdout
  bool text = false;         // --text: text on stdout (also with --svg)
  bool json = false;         // --json: the layout as JSON on stdout
  std::string state;         // --state STATEFILE
  int after_scans = -1;      // --after-scans N; -1 = not given
  std::string bench;         // simulated field devices for the scans
};

// Adds the subcommand to `app`; the returned command is tested with `if (*cmd)` after parsing.
CLI::App* add_render_command(CLI::App& app, RenderOptions& options);
int run_render(const RenderOptions& o);

}  // namespace softslc::cli
