// `softslc plot TRACE.vcd -o OUT.svg`: the SVG timing diagram of a VCD that `softslc run --trace`
// or `softslc test --trace-dir` wrote (tools/trace/trace.h, read_vcd), so a trace kept from CI or
// a run can be drawn later, or a few of its signals only.
#pragma once

#include <string>

namespace CLI {
class App;
}

namespace softslc::cli {

struct PlotOptions {
  std::string vcd;
  std::string out;      // -o OUT.svg
  std::string signals;  // --signals NAME,...; empty = all
  std::string title;    // --title; empty = the VCD's file name
};

CLI::App* add_plot_command(CLI::App& app, PlotOptions& options);
int run_plot(const PlotOptions& o);

}  // namespace softslc::cli
