// The softslc subcommands, each a function from parsed options to an exit code.
//
// Exit codes are the contract scripts and CI rely on: 0 success (warnings allowed), 1 the input
// has errors (or a check failed), 2 usage error, 3 the PLC program faulted (run).
#pragma once

#include <string>
#include <vector>

namespace softslc::cli {

enum ExitCode : int { kOk = 0, kInputError = 1, kUsage = 2, kProgramFault = 3 };

struct CheckOptions {
  std::string file;
  std::string processor;  // --processor: the processor of pasted rungs (CATALOG or CATALOG:SERIES)
};
int run_check(const CheckOptions& o);

struct FmtOptions {
  std::string file;
  std::string output;  // empty = stdout
};
int run_fmt(const FmtOptions& o);

// softslc import FILE.RSS [-o FILE.slc] (cmd_import.cpp).
struct ImportOptions {
  std::string file;
  std::string output;  // empty = stdout
};
int run_import(const ImportOptions& o);

struct ThroughputOptions {
  std::string config;
  bool json = false;
};
int run_throughput(const ThroughputOptions& o);

// Prints the instruction table: mnemonic, role, operands in text order with kinds and ranges.
int run_instructions();

struct ScantimeOptions {
  std::string file;
  std::vector<std::string> processors;  // CATALOG or CATALOG:SERIES; empty = the program's own
  std::string timing;                   // user timing profile (JSON)
  bool json = false;
};
int run_scantime(const ScantimeOptions& o);

struct RunOptions {
  std::string file;
  int scans = 0;                         // 0 = not given
  std::string for_duration;              // "" = not given
  std::vector<std::string> sets;         // ADDR=VALUE, applied before the first scan
  std::vector<std::string> prints;       // ADDR or symbol, printed in order
  std::vector<int> logs;                 // data log queues whose records are printed (DATALOG)
  bool json = false;
  std::string processor;                 // CATALOG[:SERIES] overriding START
  std::string timing;                    // user timing profile
  bool realtime = false;                 // pace scans to the wall clock
  bool every_scan = false;               // no repeated scans (docs/semantics.md "Repeated scans")
  std::string state;                     // retentive state file: loaded at start, saved at the end
  bool force_state = false;              // accept a state file saved by another program
  std::string checkpoint;                // also save every this much virtual time
  std::string bench;                     // simulated field devices (docs/bench-format.md)
  // Signal trace (docs/traces.md): FILE.vcd or FILE.svg; empty = none.
  std::string trace;
  std::string trace_signals;             // ADDR,... ; empty = every address the ladder names
  bool trace_all_outputs = false;        // only what output instructions write
  std::string trace_limit = "64M";       // bytes of VCD value changes
};
int run_run(const RunOptions& o);

struct DisasmOptions {
  std::string file;
};
int run_disasm(const DisasmOptions& o);

}  // namespace softslc::cli
