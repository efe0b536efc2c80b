// Loading a test file: parse it, load the programs it names, and check every step against them.
//
// After parsing (test_parser.h) the loader
//   1. loads each program a test names with its bench (paths are relative to the test file), once
//      per (program, bench) for the whole run, through ProgramCache; a program or bench that does
//      not load or compile is reported with its own diagnostics and marks the `program` (or
//      `bench`) line of the test file;
//   2. resolves symbols to addresses (a name that is not a SYMBOL of the program is an error);
//   3. checks every operand and literal: an address the program's data table does not have, a
//      value that does not fit its word, a force on something other than an I/O bit, a range
//      over a structured file, a bench device the bench does not have or an observation it
//      does not offer. Addresses are checked by reading (or writing) them on a probe
//      Runtime of the program, so the rules are exactly the runtime's;
//   4. resolves snapshots: `snapshot NAME` records the steps that lead to it (flattened through
//      earlier restores) and `restore NAME` must name a snapshot defined above it in the file.
// A test file that loads without errors can then only fail by the ladder's behaviour.
//
// ProgramCache is an explicit object owned by the caller (one per run), not a global: it keeps
// the loaded programs, their probe runtimes and which program errors were already printed.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "instructions/processor.h"
#include "parser/diagnostics.h"
#include "tools/testrunner/test_file.h"
#include "vm/runtime.h"

namespace softslc::testing {

// The program's channel 1 on DH-485 (`channel 1 node N [network NAME]`, a 1764-LRP's second port).
struct ChannelOneSpec {
  int node = 0;  // 0: on no network
  std::string network;
  // `channel 0 df1 ...`: channel 0 as DF1 full-duplex, and its settings as written (the cache key).
  std::optional<Df1Options> channel0_df1;
  std::string channel0_text;
};

class ProgramCache {
 public:
  struct Entry {
    std::shared_ptr<const LoadedProgram> program;  // null when the program did not load
    std::unique_ptr<Runtime> probe;                // for checking operands at load time
    std::string errors;                            // rendered diagnostics of the program and bench
    bool bench_failed = false;                     // the bench (not the program) has the errors
    std::string failed_peer;                       // or this peer's program (or the network) has them
  };
  // A peer controller on the program's MSG network (`peer NAME PATH node N`).
  struct Peer {
    std::string name;
    std::filesystem::path path;
    std::string display;
    int node = 2;
    std::uint32_t ip = 0;
    std::string network;  // "" the program's network, else the one its channel 1 names
    bool df1 = false;     // joined by the DF1 cable to the program's channel 0
    Df1Options df1_options;
    std::string df1_text;
    std::optional<modbus::SlaveOptions> modbus;  // on the program's Modbus RTU line, its channel 0 a slave
    std::string modbus_text;
  };

  // Loads the program at `path` (shown as `display`) with the bench at `bench` (shown as
  // `bench_display`; an empty path means no bench) once per pair: the program is parsed and
  // checked, the modules set up from its SLOT lines and the bench (modules/module_setup.h), and a
  // probe Runtime built with them. Configuration and bench errors are the entry's errors, as for
  // `softslc run --bench`. Not thread-safe: loading happens before the run.
  // A program that is pasted rungs (parser/loader.h) is program file 2 of `pasted_processor`
  // (the test file's `program PATH processor SPEC`), else of the run's default (`softslc test
  // --processor`); with neither it does not load, and the error says how to name one. A whole
  // program names its own processor: a processor given for it is an error.
  // With `peers`, the program is node `node` of a MSG network with them (vm/message_network.h):
  // each peer's program is loaded with its SLOT lines, and the probe is the network's leader.
  Entry& load(const std::filesystem::path& path, const std::string& display, const std::filesystem::path& bench = {},
              const std::string& bench_display = {}, const ProcessorModel* pasted_processor = nullptr,
              const std::vector<Peer>& peers = {}, int node = 1, std::uint32_t ip = 0,
              const ChannelOneSpec& channel1 = ChannelOneSpec());
  // The processor of pasted-rung programs whose test file names none (`softslc test --processor`).
  void set_default_pasted_processor(std::optional<ProcessorModel> p) { default_pasted_processor_ = std::move(p); }
  // The probe runtime of a loaded program.
  Runtime* probe_for(const LoadedProgram* program);

 private:
  std::map<std::string, Entry> entries_;  // by canonical paths (program, bench) and processor
  std::optional<ProcessorModel> default_pasted_processor_;
};

struct TestFileLoad {
  TestFile file;
  DiagnosticList diagnostics;       // of the test file, sorted by position
  std::string program_diagnostics;  // rendered diagnostics of programs that failed to load

  bool ok() const { return !diagnostics.has_errors() && program_diagnostics.empty(); }
  // Program diagnostics first (they explain the test file's "cannot load" errors), then the test
  // file's, gcc style.
  std::string render() const;
};

// Parses and loads test-file text; `dir` is where program paths are relative to, and `display`
// the file name used in messages.
TestFileLoad load_test_text(std::string text, const std::string& display, const std::filesystem::path& dir,
                            ProgramCache& cache);
// Reads a test file; an unreadable file is a diagnostic.
TestFileLoad load_test_file(const std::filesystem::path& path, const std::string& display, ProgramCache& cache);

// The width of what an address designates: 1 for a bit, 16 or 32 for integer words, 0 for a float.
int width_of(const Address& a);

}  // namespace softslc::testing
