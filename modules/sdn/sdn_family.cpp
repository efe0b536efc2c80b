// Registration of the 1747-SDN DeviceNet scanner family: checks of its SLOT line, interpretation of
// its `devicenet` bench node, and the builder of SdnScanner modules.
#include <algorithm>

#include "modules/module_registry.h"
#include "modules/sdn/sdn_bench.h"
#include "modules/sdn/sdn_scanner.h"
#include "parser/checker.h"

namespace softslc {

namespace {

constexpr int kImageWords = 32;     // "a 32-word input and output image" (1747-SDN ch. 1)
constexpr int kMaxMFileWords = 395;  // appendix D ends at word 394 (firmware 6.002 and later, p.121)
constexpr int kEmpcEnd = 256;        // Explicit Message Program Control uses words 224-255 (appendix E)

void check_sdn(const Program& program, const SlotConfig& slot, DiagnosticList& diags) {
  const std::string who = slot.catalog + " in slot " + std::to_string(slot.slot) + ": ";
  const auto family = program.processor.family;
  if (family != ProcessorFamily::Slc502 && family != ProcessorFamily::Slc503 && family != ProcessorFamily::Slc504 &&
      family != ProcessorFamily::Slc505)
    diags.error(slot.pos.line, slot.pos.column,
                who + "needs a modular SLC 5/02 or later processor with M0/M1 files (" +
                    program.processor.display_name + " has none)");
  if (slot.scan_in > kImageWords || slot.scan_out > kImageWords)
    diags.error(slot.pos.line, slot.pos.column,
                who + "the module has a 32-word input and output image; SCAN_IN/SCAN_OUT must be 0-32");
  for (int f = 0; f < 2; ++f) {
    const int words = f == 0 ? m0_words(slot) : m1_words(slot);
    const std::string name = f == 0 ? "M0" : "M1";
    if (words > kMaxMFileWords)
      diags.error(slot.pos.line, slot.pos.column,
                  who + name + " is " + std::to_string(words) + " words; the module's files end at word 394 (appendix D)");
    else if (words < kEmpcEnd)
      diags.warning(slot.pos.line, slot.pos.column,
                    who + name + " is " + std::to_string(words) +
                        " words: Explicit Message Program Control (words 224-255, appendix E) is out of reach");
  }
}

}  // namespace

void register_sdn_scanner_family(ModuleRegistry& registry) {
  ModuleFamily f;
  f.name = "1747-SDN DeviceNet scanner";
  f.catalogs = {"1747-SDN"};
  f.instructions = {Opcode::DEM};
  f.bench_kinds = {"devicenet"};
  f.check = check_sdn;
  f.prepare = [](const ModulePrepareContext& ctx) -> SlotModuleBuilder {
    check_sdn(ctx.program, ctx.slot, ctx.program_diagnostics);
    std::shared_ptr<const SdnBench> bench;
    if (ctx.bench) bench = interpret_sdn_bench(*ctx.bench, ctx.bench_diagnostics, ctx.bench_name);
    if (ctx.bench_diagnostics.has_errors()) bench = nullptr;  // a broken bench builds the bare module
    const int m0 = std::min(m0_words(ctx.slot), kMaxMFileWords), m1 = std::min(m1_words(ctx.slot), kMaxMFileWords);
    return [bench, m0, m1](const SlotConfig& s) -> std::unique_ptr<Module> {
      return std::make_unique<SdnScanner>(s, m0, m1, bench);
    };
  };
  registry.add(std::move(f));
}

}  // namespace softslc
