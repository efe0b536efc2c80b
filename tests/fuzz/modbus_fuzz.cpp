// libFuzzer target: Modbus TCP frames as `softslc serve --modbus` decodes and executes them (see
// serve_properties.h).
#include "fuzz_target.h"
#include "serve_properties.h"

SOFTSLC_FUZZ_TARGET(softslc::fuzz::check_modbus_property)
