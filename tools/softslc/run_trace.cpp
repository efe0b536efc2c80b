#include "run_trace.h"

#include <filesystem>
#include <ostream>

namespace softslc::cli {

std::unique_ptr<trace::TraceRecorder> start_run_trace(const RunOptions& o, const Program& program, Runtime& rt,
                                                      std::ostream& err, int& exit_code) {
  exit_code = kOk;
  if (o.trace.empty()) {
    if (!o.trace_signals.empty() || o.trace_all_outputs) {
      err << "softslc run: --signals and --all-outputs choose what --trace FILE records; give --trace\n";
      exit_code = kUsage;
    }
    return nullptr;
  }
  std::size_t limit = 0;
  if (!trace::parse_size(o.trace_limit, limit)) {
    err << "softslc run: --trace-limit " << o.trace_limit << ": write a size in bytes, e.g. 1000000, 512k, 64M\n";
    exit_code = kUsage;
    return nullptr;
  }
  std::vector<trace::Signal> signals;
  if (o.trace_all_outputs) signals = trace::program_signals(program, true);
  std::string error;
  if (!o.trace_signals.empty() && !trace::parse_signal_list(program, o.trace_signals, signals, error)) {
    err << "softslc run: --signals: " << error << "\n";
    exit_code = kUsage;
    return nullptr;
  }
  if (o.trace_signals.empty() && !o.trace_all_outputs) signals = trace::program_signals(program, false);
  auto recorder = std::make_unique<trace::TraceRecorder>(std::move(signals), limit);
  if (auto why = recorder->check(rt); !why.empty()) {
    err << "softslc run: --signals: " << why << "\n";
    exit_code = kUsage;
    return nullptr;
  }
  recorder->attach(rt);
  return recorder;
}

bool finish_run_trace(const RunOptions& o, const Program& program, Runtime& rt, trace::TraceRecorder* recorder,
                      std::ostream& err) {
  if (!recorder) return true;
  recorder->detach(rt);
  const std::string name = std::filesystem::path(o.file).filename().string();
  if (recorder->truncated())
    err << "softslc run: warning: --trace-limit " << o.trace_limit << " reached at " << recorder->end_us()
        << " us of virtual time; the trace stops there\n";
  if (auto why = trace::save_trace(*recorder, o.trace, name, program.project.empty() ? "plc" : program.project,
                                   std::string("softslc ") + SOFTSLC_VERSION);
      !why.empty()) {
    err << "softslc run: cannot write the trace: " << why << "\n";
    return false;
  }
  return true;
}

}  // namespace softslc::cli
