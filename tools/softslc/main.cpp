// softslc: a soft-PLC runtime for the Allen-Bradley SLC 500 family.
//
// The command line is a thin layer over the libraries: each subcommand parses its options with
// CLI11 and calls one function in commands.cpp. Usage errors exit 2, as documented in commands.h.
#include <CLI/CLI.hpp>

#include <iostream>

#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>

#include "cmd_plot.h"
#include "cmd_render.h"
#include "cmd_serve.h"
#include "commands.h"
#include "tools/testrunner/test_command.h"

namespace {

int run_main(int argc, char** argv) {
  using namespace softslc::cli;
  CLI::App app{"softslc — run, check and test Allen-Bradley SLC 500 ladder programs without the hardware"};
  app.set_version_flag("--version", std::string("softslc ") + SOFTSLC_VERSION);
  app.require_subcommand(1);
  bool verbose = false;
  app.add_flag("-v,--verbose", verbose, "log what softslc does (files, state file, scans) to stderr");

  CheckOptions check;
  auto* check_cmd = app.add_subcommand("check", "Parse and check a program (RSLogix 500 export, .SLC); "
                                                "exit 0 clean or warnings only, 1 errors");
  check_cmd->add_option("FILE", check.file, "program file")->required();
  check_cmd->add_option("--processor", check.processor, "processor catalog (CATALOG or CATALOG:SERIES): of pasted rungs (bare SOR ... EOR lines), or overriding START as `run --processor` does");

  ImportOptions import_opts;
  auto* import_cmd = app.add_subcommand("import", "Convert an RSLogix 500 / Micro project file (.RSS) to export text");
  import_cmd->add_option("FILE", import_opts.file, "project file (.RSS)")->required();
  import_cmd->add_option("-o,--output", import_opts.output, "write to this file (atomically) instead of stdout");
  FmtOptions fmt;
  auto* fmt_cmd = app.add_subcommand("fmt", "Print a program as canonical export text");
  fmt_cmd->add_option("FILE", fmt.file, "program file")->required();
  fmt_cmd->add_option("-o,--output", fmt.output, "write to this file (atomically) instead of stdout");

  ThroughputOptions throughput;
  auto* throughput_cmd = app.add_subcommand(
      "throughput", "Network timing from the 1747-SN (RIO) and AutoMax manuals' formulas for a CONFIG.json");
  throughput_cmd->add_option("CONFIG", throughput.config, "network description (JSON, see docs/throughput.md)")->required();
  throughput_cmd->add_flag("--json", throughput.json, "print the result as JSON");

  RunOptions run;
  auto* run_cmd = app.add_subcommand("run", "Run a program in virtual time and print values");
  run_cmd->add_option("FILE", run.file, "program file")->required();
  auto* scans_opt = run_cmd->add_option("--scans", run.scans, "number of scans to run (default 1)")->check(CLI::PositiveNumber);
  run_cmd->add_option("--for", run.for_duration, "virtual time to run: 250ms, 1.5s, 2m")->excludes(scans_opt);
  run_cmd->add_option("--set", run.sets, "ADDR=VALUE before the first scan (I: addresses set field inputs)");
  run_cmd->add_option("--print", run.prints, "address or symbol to print after the run, in order");
  run_cmd->add_option("--log", run.logs,
                      "MicroLogix data log queue whose records to print after the run, oldest first (left in the queue)");
  run_cmd->add_flag("--json", run.json, "print one JSON object");
  run_cmd->add_option("--processor", run.processor, "processor catalog (CATALOG or CATALOG:SERIES) overriding START");
  run_cmd->add_option("--timing", run.timing, "timing profile JSON overriding the built-in figures");
  run_cmd->add_flag("--realtime", run.realtime, "pace scans to the wall clock (interactive use)");
  run_cmd->add_flag("--every-scan", run.every_scan,
                    "execute every scan, none taken as a repeat (the same results, slower: for checking repeats)");
  run_cmd->add_option("--state", run.state,
                      "retentive state file: loaded at start if it exists, saved atomically at the end and on "
                      "SIGINT/SIGTERM");
  run_cmd->add_option("--bench", run.bench, "bench file of simulated field devices (docs/bench-format.md)");
  run_cmd->add_flag("--force-state", run.force_state, "restore a state file saved by a different program");
  run_cmd->add_option("--checkpoint", run.checkpoint, "with --state: also save every DURATION of virtual time");
  run_cmd->add_option("--trace", run.trace, "record a signal trace: FILE.vcd (GTKWave) or FILE.svg (timing diagram)");
  run_cmd->add_option("--signals", run.trace_signals, "ADDR,... to trace (default: every address the ladder names)");
  run_cmd->add_flag("--all-outputs", run.trace_all_outputs, "trace what the output instructions write");
  run_cmd->add_option("--trace-limit", run.trace_limit, "largest trace, bytes of value changes (default 64M)");

  DisasmOptions disasm;
  auto* disasm_cmd = app.add_subcommand("disasm", "Print the compiled bytecode with file/rung/branch structure");
  disasm_cmd->add_option("FILE", disasm.file, "program file")->required();

  ScantimeOptions scantime;
  auto* scantime_cmd = app.add_subcommand(
      "scantime", "Predict scan time per rung, per file and per scan, with the manuals' M0/M1 access times");
  scantime_cmd->add_option("FILE", scantime.file, "program file")->required();
  scantime_cmd->add_option("--processor", scantime.processors,
                           "processor catalog, optionally :SERIES (1747-L524:B); repeat to compare side by side");
  scantime_cmd->add_option("--timing", scantime.timing, "timing profile JSON overriding the built-in figures");
  scantime_cmd->add_flag("--json", scantime.json, "print JSON (one object, or an array when comparing)");

  softslc::testing::TestCommandOptions test;
  auto* test_cmd = app.add_subcommand(
      "test", "Run ladder unit tests (*.test files, see docs/testing.md); exit 0 all passed, 1 a test failed, "
              "2 usage or test-file errors");
  test_cmd->add_option("PATH", test.paths, "test files, or directories searched recursively for *.test")
      ->required();
  test_cmd->add_option("--filter", test.filter, "run only the tests whose name matches this glob (* and ?)")
      ->type_name("GLOB");
  // No CLI11 range check: the runner's own message for a bad value is clearer.
  test_cmd->add_option("-j,--jobs", test.jobs, "tests run in parallel (default 0: one per hardware thread)");
  test_cmd->add_flag("--list", test.list, "list the selected tests (FILE: NAME), run nothing");
  test_cmd->add_option("--junit", test.junit, "also write a JUnit XML report to FILE (atomically)")
      ->type_name("FILE");
  test_cmd->add_flag("--coverage", test.coverage,
                     "report ladder coverage: rungs run and seen true/false, conditions that decided their rung "
                     "both ways, outputs energized, subroutines called");
  test_cmd->add_option("--coverage-json", test.coverage_json, "also write the coverage report as JSON to FILE")
      ->type_name("FILE");
  test_cmd->add_option("--trace-dir", test.trace_dir, "write a VCD signal trace of every failing test into DIR")
      ->type_name("DIR");
  test_cmd->add_flag("--trace-all", test.trace_all, "with --trace-dir: a trace of every test, passed or not");
  test_cmd->add_option("--processor", test.processor,
                       "processor of pasted-rung programs (bare SOR ... EOR lines) whose test file names none: "
                       "CATALOG or CATALOG:SERIES");

  RenderOptions render;
  auto* render_cmd = add_render_command(app, render);
  PlotOptions plot;
  auto* plot_cmd = add_plot_command(app, plot);

  auto* instructions_cmd =
      app.add_subcommand("instructions", "List the instruction table: operands in text order, kinds, ranges");

  ServeOptions serve;
  auto* serve_cmd = add_serve_command(app, serve);
  ReplayOptions replay;
  auto* replay_cmd = add_replay_command(app, replay);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    int rc = app.exit(e);
    return rc == 0 ? kOk : kUsage;
  }
  // The log goes to stderr, without timestamps, so a verbose run's output is the same on every
  // run (the simulation has no wall clock, and neither does its log). Off, only errors.
  auto log = spdlog::stderr_logger_st("softslc");
  log->set_pattern("softslc: [%l] %v");
  log->set_level(verbose ? spdlog::level::debug : spdlog::level::err);
  spdlog::set_default_logger(log);
  // Every bad input is reported where it is found, as a positioned diagnostic. This is the
  // guard behind that rule: an exception that still escapes is a bug, but it ends as a message
  // and exit status 1, never as std::terminate's abort (a signal in scripts and CI).
  try {
    if (*check_cmd) return run_check(check);
    if (*fmt_cmd) return run_fmt(fmt);
    if (*import_cmd) return run_import(import_opts);
    if (*throughput_cmd) return run_throughput(throughput);
    if (*instructions_cmd) return run_instructions();
    if (*test_cmd) return softslc::testing::run_test_command(test, std::cout, std::cerr);
    if (*scantime_cmd) return run_scantime(scantime);
    if (*run_cmd) return run_run(run);
    if (*disasm_cmd) return run_disasm(disasm);
    if (*render_cmd) return run_render(render);
    if (*plot_cmd) return run_plot(plot);
    if (*serve_cmd) return run_serve(serve);
    if (*replay_cmd) return run_replay(replay);
  } catch (const std::exception& e) {
    std::cerr << "softslc: internal error (please report it with the input): " << e.what() << "\n";
    return kInputError;
  }
  return kUsage;
}

}  // namespace

int main(int argc, char** argv) {
  // run_main() turns every error of a command into a message and an exit status; this catches
  // what could still escape the command-line setup itself, so main never ends in std::terminate.
  try {
    return run_main(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "softslc: internal error (please report it): " << e.what() << "\n";
  } catch (...) {
    std::cerr << "softslc: internal error (please report it)\n";
  }
  return 1;
}
