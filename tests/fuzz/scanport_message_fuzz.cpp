// libFuzzer target: SCANport request buffers (1203-SM1 M0) (see module_properties.h for what must hold).
#include "fuzz_target.h"
#include "module_properties.h"

SOFTSLC_FUZZ_TARGET(softslc::fuzz::check_scanport_message_property)
