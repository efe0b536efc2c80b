// libFuzzer target: the address parser (see properties.h for what must hold).
#include "fuzz_target.h"
#include "properties.h"

SOFTSLC_FUZZ_TARGET(softslc::fuzz::check_address_property)
