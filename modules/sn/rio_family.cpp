// Registration of the 1747-SN (and 1747-BSN) RIO scanner family: configuration checks of its
// SLOT line, interpretation of its bench node, and the builder of RioScanner modules.
#include <algorithm>

#include "instructions/module_catalog.h"
#include "modules/module_registry.h"
#include "modules/sn/block_transfer.h"
#include "modules/sn/rio_bench.h"
#include "modules/sn/rio_scanner.h"
#include "parser/checker.h"

namespace softslc {

namespace {

RioScannerSlot scanner_slot(const Program& program, const SlotConfig& slot) {
  const auto family = program.processor.family;
  RioScannerSlot s;
  s.slot = slot.slot;
  s.processor_ok = family == ProcessorFamily::Slc502 || family == ProcessorFamily::Slc503 ||
                   family == ProcessorFamily::Slc504 || family == ProcessorFamily::Slc505;
  s.processor_name = program.processor.display_name;
  s.scan_in = slot.scan_in;
  s.scan_out = slot.scan_out;
  s.m0_size = slot.m0_size;
  s.m1_size = slot.m1_size;
  s.id_code = slot.id_code;
  s.has_g_file = slot.has_g_file;
  s.g_file = slot.g_file;
  s.options = slot.options;
  return s;
}

void check_scanner(const Program& program, const SlotConfig& slot, DiagnosticList& diags) {
  for (const auto& f : check_rio_scanner_slot(scanner_slot(program, slot))) {
    std::string m = slot.catalog + " in slot " + std::to_string(slot.slot) + ": " + f.message;
    if (f.error) diags.error(slot.pos.line, slot.pos.column, std::move(m));
    else diags.warning(slot.pos.line, slot.pos.column, std::move(m));
  }
  rio::check_buffer_sharing(program, slot.slot, diags);
}

}  // namespace

void register_rio_scanner_family(ModuleRegistry& registry) {
  ModuleFamily f;
  f.name = "1747-SN RIO scanner";
  f.catalogs = {"1747-SN", "1747-BSN"};
  f.id_code = kRioScannerIdCode;
  f.instructions = {Opcode::BTR, Opcode::BTW};
  f.bench_kinds = {"scanner"};
  f.check = check_scanner;
  f.prepare = [](const ModulePrepareContext& ctx) -> SlotModuleBuilder {
    check_scanner(ctx.program, ctx.slot, ctx.program_diagnostics);
    std::shared_ptr<const RioScannerBench> bench;
    if (ctx.bench) {
      std::vector<ModuleConfigFinding> findings;
      RioGFile g = decode_rio_g_file(ctx.slot.g_file, findings);
      const bool g_ok = ctx.slot.has_g_file && std::none_of(findings.begin(), findings.end(), [](auto& x) { return x.error; });
      bench = interpret_rio_bench(*ctx.bench, g_ok ? &g : nullptr, ctx.bench_diagnostics);
    }
    const int m0 = m0_words(ctx.slot), m1 = m1_words(ctx.slot);
    return [bench, m0, m1](const SlotConfig& s) -> std::unique_ptr<Module> {
      return std::make_unique<RioScanner>(s, m0, m1, bench);
    };
  };
  registry.add(std::move(f));
}

}  // namespace softslc
