// libFuzzer target: the program parser, checker and formatter (see properties.h for what must hold).
#include "fuzz_target.h"
#include "properties.h"

SOFTSLC_FUZZ_TARGET(softslc::fuzz::check_program_property)
