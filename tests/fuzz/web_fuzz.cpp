// libFuzzer target: messages from a page of the online view, as WebModel::handle takes them (see
// serve_properties.h).
#include "fuzz_target.h"
#include "serve_properties.h"

SOFTSLC_FUZZ_TARGET(softslc::fuzz::check_web_property)
