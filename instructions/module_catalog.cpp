#include "instructions/module_catalog.h"

#include <array>

namespace softslc {

namespace {

// One row per module catalog. M-file defaults are the sizes the manuals tell users to configure:
// 1747-SN chapter 4 ("If you are using the block transfer (BT) function, you should set the M1
// and M0 file sizes to 3,300"), 1747-SDN appendix D (words 0-394), 1203-SM1 chapter 3 (M0 800,
// M1 400). ID codes: 1747-SN 13608 (chapter 4), 1203-SM1 enhanced mode 13616 (chapter 3; basic
// mode 3516 is selected with ID_CODE); the 1747-SDN manual gives none (0).
constexpr std::array kModules{
    ModuleCatalogEntry{"1746-IB8", "8-input 24 VDC sink", 0, 1, 0, 0, 0, false},
    ModuleCatalogEntry{"1746-IB16", "16-input 24 VDC sink", 0, 1, 0, 0, 0, false},
    ModuleCatalogEntry{"1746-IB32", "32-input 24 VDC sink", 0, 2, 0, 0, 0, false},
    ModuleCatalogEntry{"1746-IV16", "16-input 24 VDC source", 0, 1, 0, 0, 0, false},
    ModuleCatalogEntry{"1746-IA16", "16-input 120 VAC", 0, 1, 0, 0, 0, false},
    ModuleCatalogEntry{"1746-IA8", "8-input 120 VAC", 0, 1, 0, 0, 0, false},
    ModuleCatalogEntry{"1746-OB8", "8-output 24 VDC source", 0, 0, 1, 0, 0, false},
    ModuleCatalogEntry{"1746-OB16", "16-output 24 VDC source", 0, 0, 1, 0, 0, false},
    ModuleCatalogEntry{"1746-OB32", "32-output 24 VDC source", 0, 0, 2, 0, 0, false},
    ModuleCatalogEntry{"1746-OV16", "16-output 24 VDC sink", 0, 0, 1, 0, 0, false},
    ModuleCatalogEntry{"1746-OW16", "16-output relay", 0, 0, 1, 0, 0, false},
    ModuleCatalogEntry{"1746-OW8", "8-output relay", 0, 0, 1, 0, 0, false},
    ModuleCatalogEntry{"1746-OA16", "16-output 120/240 VAC", 0, 0, 1, 0, 0, false},
    ModuleCatalogEntry{"1746-IO12", "6-input 6-output combination", 0, 1, 1, 0, 0, false},
    ModuleCatalogEntry{"1762-IQ16", "MicroLogix 16-input 10/30 VDC", 0, 1, 0, 0, 0, false},
    ModuleCatalogEntry{"1762-OB16", "MicroLogix 16-output 24 VDC source", 0, 0, 1, 0, 0, false},
    ModuleCatalogEntry{"1747-SN", "Remote I/O scanner", 13608, 32, 32, 3300, 3300, true},
    ModuleCatalogEntry{"1747-BSN", "Backup Remote I/O scanner", 13608, 32, 32, 3300, 3300, true},
    ModuleCatalogEntry{"1747-SDN", "DeviceNet scanner", 0, 32, 32, 395, 395, true},
    ModuleCatalogEntry{"1203-SM1", "SLC to SCANport module", 13616, 32, 32, 800, 400, true},
};

}  // namespace

std::optional<ModuleCatalogEntry> find_module_catalog(std::string_view catalog) {
  for (const auto& m : kModules)
    if (m.catalog == catalog) return m;
  return std::nullopt;
}

}  // namespace softslc
