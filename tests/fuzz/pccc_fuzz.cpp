// libFuzzer target: PCCC commands as `softslc serve` decodes and executes them (see serve_properties.h).
#include "fuzz_target.h"
#include "serve_properties.h"

SOFTSLC_FUZZ_TARGET(softslc::fuzz::check_pccc_property)
