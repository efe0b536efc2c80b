// libFuzzer target: the bench-file parser and the module setup it feeds (see module_properties.h for what must hold).
#include "fuzz_target.h"
#include "module_properties.h"

SOFTSLC_FUZZ_TARGET(softslc::fuzz::check_bench_property)
