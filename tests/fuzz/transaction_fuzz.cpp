// libFuzzer target: DeviceNet explicit-message transaction blocks (1747-SDN M0:224) (see module_properties.h for what must hold).
#include "fuzz_target.h"
#include "module_properties.h"

SOFTSLC_FUZZ_TARGET(softslc::fuzz::check_transaction_property)
