// libFuzzer target: DEM control blocks (1747-SDN) (see module_properties.h for what must hold).
#include "fuzz_target.h"
#include "module_properties.h"

SOFTSLC_FUZZ_TARGET(softslc::fuzz::check_dem_property)
