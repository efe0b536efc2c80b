// Registration of the AutoMax Remote I/O master (M/N 57C416): its SLOT line checks, its bench
// node (`automax`), and the builder of AutomaxMaster modules.
#include "modules/automax/automax_network.h"
#include "modules/module_registry.h"

namespace softslc {

namespace {

void check_master(const Program&, const SlotConfig& slot, DiagnosticList& diags) {
  // The dual port is the M0 file: 8 areas of 512 registers (parser/automax_def.h).
  if (slot.m0_size && *slot.m0_size != kAutomaxImageWords)
    diags.error(slot.pos.line, slot.pos.column,
                std::string(kAutomaxMasterCatalog) + " in slot " + std::to_string(slot.slot) +
                    ": M0_SIZE must be 4096 (the dual-port image: 8 areas of 512 registers, section 4.2)");
  if (slot.scan_in || slot.scan_out || slot.has_g_file)
    diags.error(slot.pos.line, slot.pos.column,
                std::string(kAutomaxMasterCatalog) + " in slot " + std::to_string(slot.slot) +
                    ": the AutoMax master has no SLC image words or G file (its data is the M0 file)");
}

}  // namespace

void register_automax_family(ModuleRegistry& registry) {
  ModuleFamily f;
  f.name = "AutoMax Remote I/O master";
  f.catalogs = {kAutomaxMasterCatalog};
  f.bench_kinds = {"automax"};
  f.check = check_master;
  f.prepare = [](const ModulePrepareContext& ctx) -> SlotModuleBuilder {
    check_master(ctx.program, ctx.slot, ctx.program_diagnostics);
    std::shared_ptr<const AutomaxBench> bench;
    if (ctx.bench) bench = interpret_automax_bench(*ctx.bench, ctx.bench_diagnostics);
    auto names = std::make_shared<AutomaxMaster::SymbolNames>();
    for (const auto& sym : ctx.program.symbols)
      if (sym.automax && sym.address.type == FileType::M0 && sym.address.element == ctx.slot.slot) {
        std::string& text = (*names)[sym.address.word_in_element()];
        text += (text.empty() ? "" : ", ") + std::string(keyword_of(sym.automax->kind)) + " " + sym.name;
      }
    return [bench, names](const SlotConfig& s) -> std::unique_ptr<Module> {
      return std::make_unique<AutomaxMaster>(s, bench, names);
    };
  };
  registry.add(std::move(f));
}

}  // namespace softslc
