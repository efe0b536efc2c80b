// libFuzzer target: the test-file parser (see properties.h for what must hold).
#include "fuzz_target.h"
#include "properties.h"

SOFTSLC_FUZZ_TARGET(softslc::fuzz::check_testfile_property)
