#include "cmd_plot.h"

#include <CLI/CLI.hpp>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "commands.h"
#include "tools/trace/trace.h"
#include "vm/atomic_file.h"

namespace softslc::cli {

namespace {

// The largest VCD plot reads: four times run --trace's default --trace-limit (64M).
constexpr std::uintmax_t kMaxVcdBytes = 256u << 20;

}  // namespace

CLI::App* add_plot_command(CLI::App& app, PlotOptions& o) {
  auto* cmd = app.add_subcommand("plot", "Draw a VCD written by `softslc run --trace` or `test --trace-dir` as an SVG "
                                         "timing diagram (docs/traces.md)");
  cmd->add_option("VCD", o.vcd, "the trace (VCD)")->required();
  cmd->add_option("-o,--output", o.out, "the SVG to write (atomically)")->required()->type_name("OUT.svg");
  cmd->add_option("--signals", o.signals, "only these signals, in this order (names as in the VCD), comma-separated")
      ->type_name("NAME,...");
  cmd->add_option("--title", o.title, "the diagram's title (default: the VCD's file name)");
  return cmd;
}

int run_plot(const PlotOptions& o) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(o.vcd, ec);
  if (ec) {
    std::cerr << "softslc plot: " << o.vcd << ": cannot read: " << ec.message() << "\n";
    return kInputError;
  }
  if (size > kMaxVcdBytes) {
    std::cerr << "softslc plot: " << o.vcd << ": " << size << " bytes; the limit is " << kMaxVcdBytes
              << " (draw a shorter run, or --trace-limit)\n";
    return kInputError;
  }
  std::ifstream in(o.vcd, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in) {
    std::cerr << "softslc plot: " << o.vcd << ": cannot read\n";
    return kInputError;
  }
  std::vector<std::string> only;
  std::istringstream names(o.signals);
  for (std::string name; std::getline(names, name, ',');)
    if (!name.empty()) only.push_back(name);
  trace::TraceData data;
  if (auto why = trace::read_vcd(text.str(), only, data); !why.empty()) {
    std::cerr << o.vcd << ":" << why << "\n";
    return kInputError;
  }
  const std::string title = o.title.empty() ? std::filesystem::path(o.vcd).filename().string() : o.title;
  if (auto why = write_file_atomically(o.out, trace::write_timing_svg(data, title)); !why.empty()) {
    std::cerr << "softslc plot: " << why << "\n";
    return kInputError;
  }
  return kOk;
}

}  // namespace softslc::cli
