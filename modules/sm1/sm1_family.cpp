// Registration of the 1203-SM1 SLC to SCANport module family: checks of its SLOT line, its bench
// node (`scanport`), and the builder of Sm1Module instances.
#include "modules/module_registry.h"
#include "modules/sm1/sm1_config.h"
#include "modules/sm1/sm1_module.h"

namespace softslc {

namespace {

// Decodes the SLOT line and reports its findings at the line.
Sm1Config decode_and_report(const Program& program, const SlotConfig& slot, DiagnosticList& diags) {
  std::vector<Sm1Finding> findings;
  Sm1Config config = decode_sm1_slot(program, slot, findings);
  for (const auto& f : findings) {
    std::string m = slot.catalog + " in slot " + std::to_string(slot.slot) + ": " + f.message;
    if (f.error) diags.error(slot.pos.line, slot.pos.column, std::move(m));
    else diags.warning(slot.pos.line, slot.pos.column, std::move(m));
  }
  return config;
}

void check_sm1(const Program& program, const SlotConfig& slot, DiagnosticList& diags) {
  decode_and_report(program, slot, diags);
}

ModuleFamily sm1_family(std::string name, int id_code, std::vector<std::string> catalogs) {
  ModuleFamily f;
  f.name = std::move(name);
  f.catalogs = std::move(catalogs);
  f.id_code = id_code;
  f.bench_kinds = {"scanport"};
  f.check = check_sm1;
  f.prepare = [](const ModulePrepareContext& ctx) -> SlotModuleBuilder {
    const Sm1Config config = decode_and_report(ctx.program, ctx.slot, ctx.program_diagnostics);
    std::shared_ptr<const Sm1Bench> bench;
    if (ctx.bench) bench = interpret_sm1_bench(*ctx.bench, ctx.bench_name, ctx.bench_diagnostics);
    return [config, bench](const SlotConfig& s) -> std::unique_ptr<Module> {
      return std::make_unique<Sm1Module>(s, config, bench);
    };
  };
  return f;
}

}  // namespace

void register_scanport_family(ModuleRegistry& registry) {
  // The catalog serves both modes (the ID code picks one); an "Other" slot is recognised by
  // either ID code, so the family is registered once per code.
  registry.add(sm1_family("1203-SM1 SLC to SCANport module", kSm1EnhancedIdCode, {"1203-SM1"}));
  registry.add(sm1_family("1203-SM1 SLC to SCANport module (basic mode)", kSm1BasicIdCode, {}));
}

}  // namespace softslc
