// `softslc run --trace`: the glue between the run command and the trace recorder (tools/trace).
//
// start_run_trace() resolves the signals and attaches a recorder to the runtime before the first
// scan; finish_run_trace() writes the file atomically after the last. Kept out of commands.cpp so
// the run command gains two calls, not a block of option handling.
#pragma once

#include <iosfwd>
#include <memory>

#include "commands.h"
#include "parser/program.h"
#include "tools/trace/trace.h"
#include "vm/runtime.h"

namespace softslc::cli {

// Returns the attached recorder (nullptr when --trace was not given); on a bad option prints the
// reason to `err` and sets `exit_code` (kUsage).
std::unique_ptr<trace::TraceRecorder> start_run_trace(const RunOptions& o, const Program& program, Runtime& rt,
                                                      std::ostream& err, int& exit_code);
// Writes the trace; false (after printing why) when the file could not be written.
bool finish_run_trace(const RunOptions& o, const Program& program, Runtime& rt, trace::TraceRecorder* recorder,
                      std::ostream& err);

}  // namespace softslc::cli
