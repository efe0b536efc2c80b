// The JSON face of the network throughput calculators: config in, result
// out, and a plain-text report of a result.
//
// Design. compute_throughput() reads a config document strictly: every
// object's keys are checked against the keys its kind allows (a misspelt key
// is an error, not a silently ignored figure), every value's JSON type is
// checked, and enumerations accept only the manual's spellings. Each problem
// is reported as a ConfigError whose path() is the JSON path of the
// offending field ("devices[2].size", "drops[0].rails", "" for the document
// itself). The document is then mapped onto the typed model of
// rio_throughput.h or automax_throughput.h, which validates the network as a
// whole (overlapping devices, drop numbers) and computes the figures. Times
// in the config are milliseconds (JSON numbers); the calculators work in
// whole microseconds, so a time with a finer fraction is rounded to the
// nearest microsecond and the result's notes say so. Times in the result are
// milliseconds again, exact to the microsecond, so 132.0 prints as 132.0 and
// 10.448 as 10.448. format_throughput_text() reads only the result document,
// so a saved result can be reported again later. docs/throughput.md gives
// both schemas in full.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "modules/throughput/automax_throughput.h"
#include "modules/throughput/rio_throughput.h"

namespace softslc::throughput {

// Computes the throughput figures of the network `config` describes,
// dispatching on config["network"] ("rio" or "automax"). Throws ConfigError
// for any config the manuals' formulas cannot be applied to.
nlohmann::json compute_throughput(const nlohmann::json& config);

// A readable report of a compute_throughput() result: the inputs, aligned
// tables of the per-device figures with units, the formula with the values
// substituted, and the notes. Throws nlohmann::json::exception if `result`
// is not a compute_throughput() result.
std::string format_throughput_text(const nlohmann::json& result);

}  // namespace softslc::throughput
