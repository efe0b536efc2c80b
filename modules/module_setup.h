// Loading a program's modules: the Program plus an optional bench file -> RuntimeOptions.
//
// This is the one entry point the CLI (`softslc run --bench FILE`, `softslc check`) and the test
// runner (`bench FILE` in a .test file) use. setup_modules() asks the registry for the family of
// every SLOT line, lets each family check its slot and interpret the bench node wired to it
// (`slot=N` on a top-level bench node), and returns:
//   - options.module_factory: builds a fresh module for each slot of each new Runtime (slots no
//     family claims get the runtime's generic discrete I/O);
//   - options.module_instruction: accepts BTR/BTW/DEM when the slot they name holds a module of
//     a family that executes them, with a clear refusal otherwise;
//   - diagnostics: configuration problems positioned in the program file, bench problems
//     positioned in the bench file. ok() is false when either has an error; the options are
//     still filled, so a tool may choose to run anyway (tests use this to reach the run-time
//     faults 62H/63H).
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "modules/bench/bench.h"
#include "modules/module_registry.h"
#include "parser/diagnostics.h"
#include "parser/program.h"
#include "vm/runtime.h"

namespace softslc {

struct ModuleSetup {
  RuntimeOptions options;
  DiagnosticList program_diagnostics;  // positions in the program file
  DiagnosticList bench_diagnostics;    // positions in the bench file
  std::string bench_name;              // for rendering bench diagnostics
  std::string bench_source;

  bool ok() const { return !program_diagnostics.has_errors() && !bench_diagnostics.has_errors(); }
  // Both lists rendered gcc-style: the program's with its own name and text, the bench's.
  std::string render(std::string_view program_name, std::string_view program_source) const;
};

// With a parsed bench (or none).
ModuleSetup setup_modules(const Program& program, const BenchFile* bench,
                          const ModuleRegistry& registry = builtin_module_registry());
// Reads and parses the bench file when a path is given; a syntax error in it is a bench
// diagnostic and no bench devices are built.
ModuleSetup load_module_setup(const Program& program, const std::optional<std::filesystem::path>& bench_path,
                              const ModuleRegistry& registry = builtin_module_registry());
ModuleSetup load_module_setup_text(const Program& program, std::string bench_text, std::string bench_name,
                                   const ModuleRegistry& registry = builtin_module_registry());

// The configuration checks alone, for `softslc check`: every family's checks of its SLOT lines
// (for the 1747-SN: placement, processor, image and M-file sizes, ID code, options and every G
// file rule of chapter 4, each quoting the manual). Errors are positioned at the SLOT line.
void check_module_configuration(const Program& program, DiagnosticList& diagnostics,
                                const ModuleRegistry& registry = builtin_module_registry());

}  // namespace softslc
