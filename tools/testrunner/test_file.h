// A ladder test file as plain values: tests, steps, conditions (the format: docs/testing.md).
//
// The parser (test_parser.h) turns text into a TestFile; the loader (test_loader.h) then loads
// the programs it names, resolves symbols and snapshots and checks every operand against the
// program, so a TestFile that reaches the executor can only fail by the ladder's behaviour. Every
// node keeps the Location it came from so that both diagnostics and test failures point at the
// line (and column) the user wrote.
//
// Table-driven tests are expanded by the parser: one TestCase per row, with the row's values
// already substituted, so nothing after the parser knows about tables. Snapshots are flattened
// by the loader: a Snapshot holds the program, the starting mode and the list of steps that lead
// to it from a fresh Runtime (restores inside it already replaced by the steps they stand for).
// Because the runtime is deterministic, replaying that list reproduces the state exactly, and
// every test stays independent of every other, which is what lets tests run in parallel.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "parser/address.h"
#include "parser/program.h"
#include "tools/testrunner/values.h"
#include "vm/df1_link.h"
#include "vm/modbus_slave.h"
#include "vm/module.h"
#include "vm/runtime.h"
#include "vm/virtual_time.h"

namespace softslc::testing {

// A data-table operand: an address (N7:0, I:1/0, T4:0.ACC), a program SYMBOL, or a range of
// whole words (N11:0..13).
struct DataRef {
  std::string spelling;  // as written
  std::string symbol;    // the symbol name when written as one; empty for addresses
  std::string controller;  // the peer it belongs to (B.N7:0); empty for the program's own data
  Address address;       // resolved (symbols: by the loader)
  int range_last = -1;   // last element of a range; -1 for a single address
  Location loc;

  bool is_range() const { return range_last >= 0; }
  int range_size() const { return is_range() ? range_last - address.element + 1 : 1; }
  // "MOTOR (O:2/0)" for a symbol, the address alone otherwise.
  std::string describe() const;
};

// An observable value of a named bench device (Runtime::observe): `device BT8 btw data[2]`.
// The observation is a list of numbers; `[K]` picks element K, and without an index the list
// must hold exactly one number.
struct DeviceRef {
  std::string name;   // the bench device
  std::string what;   // the observation, words joined by one blank ("btw count")
  int index = -1;     // -1: no index
  std::string spelling;
  Location loc;       // of the word `device`
  Location name_loc;
};

// One side of a comparison.
struct Operand {
  enum class Kind : std::uint8_t { Data, Literal, Duration, Count, Elapsed, Scans, Device };
  Kind kind = Kind::Literal;
  DataRef data;
  DeviceRef device;
  Literal literal;
  Nanoseconds duration = 0;
  std::int64_t count = 0;
  std::string spelling;
  Location loc;
};

// The mode as a test file spells it: "program", "run", "test", "faulted", "suspended".
std::string_view mode_word(Mode m);

enum class CompareOp : std::uint8_t { Eq, Ne, Lt, Le, Gt, Ge, In };
std::string_view to_string(CompareOp op);

// lhs OP rhs, or lhs in rhs..high.
struct Comparison {
  Operand lhs;
  CompareOp op = CompareOp::Eq;
  Operand rhs;
  Operand high;  // CompareOp::In only
};

// A condition of `expect` and `run until`: comparisons, fault and mode tests, and/or.
struct Condition {
  enum class Kind : std::uint8_t { Compare, Fault, NoFault, Mode, And, Or };
  Kind kind = Kind::Compare;
  Comparison compare;
  std::optional<std::uint16_t> fault_code;  // Fault: nullopt = any fault
  Literal fault_literal;                    // Fault: the code as written
  Mode mode = Mode::Run;                    // Mode
  std::vector<Condition> terms;             // And / Or
  Location loc;
};
// The canonical spelling, e.g. "MOTOR == 1 and (N7:0 in 10..20 or fault 0020h)".
std::string to_string(const Condition& c);

struct Snapshot;

struct Step {
  enum class Kind : std::uint8_t {
    Set,          // set TARGET = VALUE...
    Force,        // force TARGET = 0|1
    Unforce,      // unforce TARGET
    UnforceAll,   // unforce all
    Scan,         // scan N
    Run,          // run DURATION
    RunUntil,     // run until CONDITION within DURATION
    Expect,       // expect CONDITION
    ExpectWords,  // expect FILE:a..b == v1 v2 ...
    Mode,         // mode program|run|test
    PowerCycle,   // power cycle
    ClearFault,   // clear fault
    Snapshot,     // snapshot NAME
    Restore,      // restore NAME
    Device,       // device NAME CHANGE [ARGS...]: Runtime::inject
    ExpectLog,    // expect log Q == "TEXT" | none: Runtime::retrieve_data_log_record
  };
  Kind kind = Kind::Scan;
  Location loc;
  std::string text;  // the line as written (row values substituted), without its comment
  std::string condition_text;  // Expect, ExpectWords, RunUntil: the condition as written
  DataRef target;
  std::vector<Literal> values;
  std::int64_t count = 0;
  Nanoseconds duration = 0;
  Condition condition;
  Mode mode = Mode::Run;
  std::string name;                           // Snapshot / Restore; Device: the device; ExpectLog: the record
  bool none = false;                          // ExpectLog: the queue is expected empty
  Location name_loc;                          // Device
  std::string change;                         // Device: "offline", "cable removed", ...
  std::vector<std::string> args;              // Device
  std::shared_ptr<const Snapshot> snapshot;   // Restore: resolved by the loader
};

// A program a test runs with its bench (the simulated field devices, or none), loaded once per
// (program, bench) pair and shared (read-only) by every test using it. `modules` builds the
// modules of every Runtime a test creates; the options are copyable and thread-safe
// (modules/module_setup.h).
struct LoadedProgram {
  std::string path;        // as shown in messages (relative to the current directory when given so)
  std::string bench_path;  // likewise; empty without a bench
  Program program;
  RuntimeOptions modules;  // module_factory and module_instruction of the program + bench
};

// The state a `snapshot` step names: replaying `steps` into a fresh Runtime of `program`
// started in `initial_mode` reproduces it exactly.
struct Snapshot {
  std::string name;
  Location loc;
  std::shared_ptr<const LoadedProgram> program;
  Mode initial_mode = Mode::Run;
  std::vector<Step> steps;
};

// A peer controller on the test's MSG network: `peer NAME PATH node N`, or on Ethernet `peer NAME PATH
// ip A.B.C.D` (docs/testing.md).
struct PeerSpec {
  std::string name;
  std::string path;  // as written, relative to the test file
  int node = 2;
  std::uint32_t ip = 0;  // Ethernet: the peer's IP address (0: named by node)
  std::string network;   // `network NAME`: the DH-485 network the program's channel 1 names ("" the file's)
  // `peer NAME PATH df1 [SETTING...]`: joined to the program's DF1 channel 0 by the cable, its own channel 0
  // configured with these settings (docs/testing.md "DF1 full-duplex").
  bool df1 = false;
  Df1Options df1_options;
  std::string df1_text;  // the settings as written (the program cache's key)
  // `peer NAME PATH modbus [SETTING...]`: on the program's Modbus RTU line, its channel 0 a Modbus RTU slave
  // (docs/testing.md "Modbus RTU slaves").
  std::optional<modbus::SlaveOptions> modbus;
  std::string modbus_text;
  Location loc;      // of the name
  Location path_loc;
};

struct TestCase {
  std::string name;
  Location loc;
  std::string program_path;  // as written (file level or in the test), relative to the test file
  Location program_loc;
  std::string program_processor;  // `program PATH processor SPEC`: the processor of pasted rungs
  Location program_processor_loc;
  std::string bench_path;    // likewise; empty without a bench
  Location bench_loc;
  // The program's node and the other controllers of its MSG network (file-level `node`, `peer`).
  int node = 1;
  Location node_loc;
  std::uint32_t ip = 0;  // `ip A.B.C.D`: the program's IP address on Ethernet (0: none)
  std::vector<PeerSpec> peers;
  // `channel 1 node N [network NAME]`: a 1764-LRP program's channel 1 on DH-485 (0: on no network).
  int channel1_node = 0;
  std::string channel1_network;
  Location channel1_loc;
  // `channel 0 df1 [SETTING...]`: channel 0 in System mode, DF1 full-duplex (docs/testing.md "DF1 full-duplex").
  std::optional<Df1Options> channel0_df1;
  std::string channel0_text;
  Location channel0_loc;
  std::shared_ptr<const LoadedProgram> program;  // set by the loader
  // Tests start in Run; a `mode` step written first sets the starting mode instead.
  Mode initial_mode = Mode::Run;
  std::vector<Step> steps;
};

struct TestFile {
  std::string name;    // the path as shown in messages
  std::string source;  // the text, for rendering diagnostics
  std::vector<TestCase> tests;
};

}  // namespace softslc::testing
