// softslc: a soft-PLC runtime for the Allen-Bradley SLC 500 family.
//
// The command line is a thin layer over the libraries: each subcommand parses its options with
// CLI11 and calls one function in commands.cpp. Usage errors exit 2, as documented in commands.h.
#include <CLI/CLI.hpp>

#include "commands.h"

int main(int argc, char** argv) {
  using namespace softslc::cli;
  CLI::App app{"softslc — run, check and test Allen-Bradley SLC 500 ladder programs without the hardware"};
  app.set_version_flag("--version", std::string("softslc ") + SOFTSLC_VERSION);
  app.require_subcommand(1);

  CheckOptions check;
  auto* check_cmd = app.add_subcommand("check", "Parse and check a program (RSLogix 500 export, .SLC); "
                                                "exit 0 clean or warnings only, 1 errors");
  check_cmd->add_option("FILE", check.file, "program file")->required();

  FmtOptions fmt;
  auto* fmt_cmd = app.add_subcommand("fmt", "Print a program as canonical export text");
  fmt_cmd->add_option("FILE", fmt.file, "program file")->required();
  fmt_cmd->add_option("-o,--output", fmt.output, "write to this file (atomically) instead of stdout");

  ThroughputOptions throughput;
  auto* throughput_cmd = app.add_subcommand(
      "throughput", "Network timing from the 1747-SN (RIO) and AutoMax manuals' formulas for a CONFIG.json");
  throughput_cmd->add_option("CONFIG", throughput.config, "network description (JSON, see docs/throughput.md)")->required();
  throughput_cmd->add_flag("--json", throughput.json, "print the result as JSON");

  auto* instructions_cmd =
      app.add_subcommand("instructions", "List the instruction table: operands in text order, kinds, ranges");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    int rc = app.exit(e);
    return rc == 0 ? kOk : kUsage;
  }
  if (*check_cmd) return run_check(check);
  if (*fmt_cmd) return run_fmt(fmt);
  if (*throughput_cmd) return run_throughput(throughput);
  if (*instructions_cmd) return run_instructions();
  return kUsage;
}
