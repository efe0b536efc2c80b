// Static facts about module catalog numbers, as the program checker needs them.
//
// The behaviour of modules lives in modules/; this table only says what a SLOT line's catalog
// number implies before anything runs: whether the module has M0/M1 files and their default
// sizes (the sizes each manual tells users to configure), its module ID code, and its default
// image size. Unknown catalogs are accepted as generic I/O cards sized by SCAN_IN/SCAN_OUT.
#pragma once

#include <optional>
#include <string_view>

namespace softslc {

struct ModuleCatalogEntry {
  std::string_view catalog;
  std::string_view description;
  int id_code;          // module ID code (0 where the manuals do not give one)
  int default_scan_in;  // input image words
  int default_scan_out; // output image words
  int default_m0;       // M0 file words (0 = no M files)
  int default_m1;       // M1 file words
  bool specialty;       // reached through M0/M1/G files by ladder
};

// Looks a catalog number up; nullopt when softslc does not know it.
std::optional<ModuleCatalogEntry> find_module_catalog(std::string_view catalog);

}  // namespace softslc
