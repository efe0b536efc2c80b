#include "tools/testrunner/test_command.h"

#include "tools/testrunner/runner.h"

namespace softslc::testing {

int run_test_command(const TestCommandOptions& options, std::ostream& out, std::ostream& err) {
  RunOptions run;
  run.paths = options.paths;
  run.filter = options.filter;
  run.junit = options.junit;
  run.list = options.list;
  run.jobs = options.jobs;
  run.coverage = options.coverage;
  run.coverage_json = options.coverage_json;
  run.trace_dir = options.trace_dir;
  run.trace_all = options.trace_all;
  if (!options.processor.empty()) {
    std::string why;
    run.pasted_processor = parse_processor_spec(options.processor, why);
    if (!run.pasted_processor) {
      err << "error: --processor " << why << "\n";
      return kUsageError;
    }
  }
  return run_tests(run, out, err);
}

}  // namespace softslc::testing
