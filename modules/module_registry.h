// The module registry: which code simulates the module in a chassis slot.
//
// Each module family (discrete 1746 I/O, the 1747-SN RIO scanner; the 1747-SDN, 1203-SM1 and
// AutoMax modules later) registers one ModuleFamily: the catalog numbers it serves (and an ID
// code, for a SLOT line that says "Other" with an ID_CODE, as RSLogix does), the specialty
// instructions its modules execute (BTR/BTW, DEM), and a prepare() function. prepare() runs once
// per slot when a program and its bench file are loaded: it checks the slot's configuration
// (errors positioned in the program file), interprets the bench node wired to the slot (errors
// positioned in the bench file), and returns a SlotModuleBuilder, a function that makes a fresh
// module instance from that immutable preparation. RuntimeOptions::module_factory calls the
// builders, so every Runtime built from the same setup (the test runner builds one per test, on
// any thread) gets its own modules with the same configuration. The VM never names a module
// type: it sees only the Module interface (vm/module.h).
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "instructions/instruction_table.h"
#include "modules/bench/bench.h"
#include "parser/program.h"
#include "vm/module.h"

namespace softslc {

using SlotModuleBuilder = std::function<std::unique_ptr<Module>(const SlotConfig&)>;

// What prepare() sees for one slot.
struct ModulePrepareContext {
  const Program& program;
  const SlotConfig& slot;
  const BenchNode* bench;              // the top-level bench node wired to this slot, or nullptr
  DiagnosticList& program_diagnostics;  // positions in the program file (the SLOT line)
  DiagnosticList& bench_diagnostics;    // positions in the bench file
  std::string bench_name = {};          // the bench file's path as given (files it names are beside it)
};

struct ModuleFamily {
  std::string name;                  // "1747-SN RIO scanner"
  std::vector<std::string> catalogs;  // SLOT catalogs the family serves
  std::optional<int> id_code;        // an unknown catalog with this ID_CODE belongs to the family
  std::vector<Opcode> instructions;  // specialty instructions its modules execute
  std::vector<std::string> bench_kinds;  // top-level bench node kinds it accepts
  // Checks the slot and interprets its bench node; returns nullptr when the slot cannot be built
  // (after reporting why).
  std::function<SlotModuleBuilder(const ModulePrepareContext&)> prepare;
  // Configuration checks alone (softslc check): the same checks prepare() makes on the SLOT line.
  std::function<void(const Program&, const SlotConfig&, DiagnosticList&)> check;
};

class ModuleRegistry {
 public:
  void add(ModuleFamily family);
  // The family of a SLOT line: by catalog, else by ID_CODE for a catalog no family claims.
  const ModuleFamily* find(const SlotConfig& slot) const;
  const std::vector<ModuleFamily>& families() const { return families_; }

 private:
  std::vector<ModuleFamily> families_;
};

// The families softslc ships: 1746 discrete I/O and the 1747-SN (and 1747-BSN) RIO scanner.
ModuleRegistry builtin_module_registry();

// Registration functions of the built-in families (each family's own source file).
void register_discrete_io_family(ModuleRegistry& registry);
void register_rio_scanner_family(ModuleRegistry& registry);
void register_sdn_scanner_family(ModuleRegistry& registry);
void register_scanport_family(ModuleRegistry& registry);
void register_automax_family(ModuleRegistry& registry);

}  // namespace softslc
