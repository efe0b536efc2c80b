// libFuzzer target: EtherNet/IP encapsulation frames and the CIP/PCCC inside them (see serve_properties.h).
#include "fuzz_target.h"
#include "serve_properties.h"

SOFTSLC_FUZZ_TARGET(softslc::fuzz::check_eip_property)
