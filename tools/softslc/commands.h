// The softslc subcommands, each a function from parsed options to an exit code.
//
// Exit codes are the contract scripts and CI rely on: 0 success (warnings allowed), 1 the input
// has errors (or a check failed), 2 usage error, 3 the PLC program faulted (run).
#pragma once

#include <string>

namespace softslc::cli {

enum ExitCode : int { kOk = 0, kInputError = 1, kUsage = 2, kProgramFault = 3 };

struct CheckOptions {
  std::string file;
};
int run_check(const CheckOptions& o);

struct FmtOptions {
  std::string file;
  std::string output;  // empty = stdout
};
int run_fmt(const FmtOptions& o);

struct ThroughputOptions {
  std::string config;
  bool json = false;
};
int run_throughput(const ThroughputOptions& o);

// Prints the instruction table: mnemonic, role, operands in text order with kinds and ranges.
int run_instructions();

}  // namespace softslc::cli
