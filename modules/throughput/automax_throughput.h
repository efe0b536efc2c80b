// Data update rate of a Reliance AutoMax Remote I/O network, as section 4.5
// ("Data Update Rate") of the AutoMax Remote I/O manual, chapter 4, states it
// (seeds/004_b6b94227d784095f.txt).
//
// Design. Each slave drop costs a DROP_TIME given by a linear formula of its
// kind: a base time plus, for some kinds, a time per register, per input or
// output register, or per rail. The update period of every register is the
// sum of the drop times plus 2.7 ms for polling the inactive drops. The kinds
// are one declarative table (automax_drop_types()): its rows carry the
// config name, the formula's base and per-unit terms (each naming the
// AutomaxDrop field it multiplies and that field's limit), and the drop
// numbers the kind may use. The calculator, the JSON layer and the report all
// read that table, so a new kind is one row. Durations are integer
// microseconds (Micros); every constant of section 4.5 is a whole number of
// them, so results are exact. Micros, ConfigError and format_ms() are shared
// with the RIO calculator and come from rio_throughput.h.
//
// The formulas are followed where the manual's worked example disagrees with
// them (see docs/throughput.md): the example's Remote I/O Head drop uses
// constants that appear in no formula, and its digital Shark drop is 1.900 ms
// where the formula says 1.8 ms. compute_automax() adds a note to the result
// whenever a drop of either kind is present.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "modules/throughput/rio_throughput.h"

namespace softslc::throughput {

// The slave drop kinds section 4.5 gives a DROP_TIME formula for.
enum class AutomaxDropType { multibus, head_57c330, head_57c328, drive_head, shark_digital, shark_mixed };

// One slave drop. Only the counts the drop's formula uses matter: registers
// (Multibus rack: N, registers transferred to/from the drop), outputs and
// inputs (57C330 head: X output and Y input registers), rails (57C328 head:
// R connected rails). `number` is the drop number (1..7, or 9..15 for a
// digital Shark rack); without it the drop is labelled by its position.
struct AutomaxDrop {
    AutomaxDropType type = AutomaxDropType::multibus;
    int registers = 0;
    int outputs = 0;
    int inputs = 0;
    int rails = 0;
    std::optional<int> number;
    std::string name;
};

struct AutomaxNetwork {
    std::vector<AutomaxDrop> drops;
};

// One per-unit term of a DROP_TIME formula: `per_unit` times the count in
// AutomaxDrop::*count, which is the config key `field` and may not exceed
// max_count (when the manual gives a limit).
struct AutomaxDropTerm {
    std::string_view field;
    int AutomaxDrop::*count = nullptr;
    Micros per_unit = 0;
    std::optional<int> max_count;
};

// One row of the drop-kind table: DROP_TIME = base + sum of terms.
struct AutomaxDropTypeInfo {
    AutomaxDropType type;
    std::string_view name;         // the config's "type" value
    std::string_view description;  // the manual's wording
    Micros base = 0;
    std::span<const AutomaxDropTerm> terms;
    int min_number = 1;  // drop numbers the kind may use
    int max_number = 7;
};

std::span<const AutomaxDropTypeInfo> automax_drop_types();
const AutomaxDropTypeInfo& automax_drop_type(AutomaxDropType type);
std::optional<AutomaxDropType> parse_automax_drop_type(std::string_view name);

// "2.7 milliseconds to poll any inactive drops", added once per update.
inline constexpr Micros kAutomaxInactivePoll = 2700;

struct AutomaxDropResult {
    std::size_t index = 0;  // position in AutomaxNetwork::drops
    int drop = 0;           // drop number, or position + 1 when none was given
    AutomaxDropType type = AutomaxDropType::multibus;
    Micros drop_time = 0;
    std::string formula;  // the formula with the drop's counts, e.g. "1.5 + (13 x 0.018)"
};

struct AutomaxResult {
    std::vector<AutomaxDropResult> drops;
    Micros inactive_poll = kAutomaxInactivePoll;
    Micros update_period = 0;
    std::vector<std::string> notes;
};

// DROP_TIME of one drop by its section 4.5 formula (no validation).
Micros automax_drop_time(const AutomaxDrop& drop);

// Throws ConfigError (paths like "drops[2].rails") for: no drops, a negative
// count or one over its limit, drop numbers given for some drops only, a drop
// number outside its kind's range or used twice, or more drops of one
// numbering range than it has numbers.
void validate_automax(const AutomaxNetwork& network);

// Validates `network` and computes every drop time and the update period.
AutomaxResult compute_automax(const AutomaxNetwork& network);

}  // namespace softslc::throughput
