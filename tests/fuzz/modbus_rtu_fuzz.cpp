// libFuzzer target: bytes on a Modbus RTU line as `softslc serve --modbus-rtu` frames and answers
// them (see serve_properties.h).
#include "fuzz_target.h"
#include "serve_properties.h"

SOFTSLC_FUZZ_TARGET(softslc::fuzz::check_modbus_rtu_property)
