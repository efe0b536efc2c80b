#include "modules/module_registry.h"

#include <algorithm>

namespace softslc {

void ModuleRegistry::add(ModuleFamily family) { families_.push_back(std::move(family)); }

const ModuleFamily* ModuleRegistry::find(const SlotConfig& slot) const {
  for (const auto& f : families_)
    if (std::find(f.catalogs.begin(), f.catalogs.end(), slot.catalog) != f.catalogs.end()) return &f;
  if (!slot.id_code) return nullptr;
  for (const auto& f : families_)
    if (f.id_code && *f.id_code == *slot.id_code) return &f;
  return nullptr;
}

ModuleRegistry builtin_module_registry() {
  ModuleRegistry r;
  register_discrete_io_family(r);
  register_rio_scanner_family(r);
  register_sdn_scanner_family(r);
  register_scanport_family(r);
  register_automax_family(r);
  return r;
}

}  // namespace softslc
