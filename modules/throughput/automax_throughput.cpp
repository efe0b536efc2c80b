// The section 4.5 DROP_TIME formulas as one table, and the update period.
#include "modules/throughput/automax_throughput.h"

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <utility>

namespace softslc::throughput {

namespace {

// Per-unit terms of the formulas, in the manual's order within each formula.
// Multibus rack: "DROP_TIME = [1.5 + (N x 0.018)] milliseconds".
constexpr std::array<AutomaxDropTerm, 1> kMultibusTerms{{{"registers", &AutomaxDrop::registers, 18, std::nullopt}}};
// M/N 57C330 Remote I/O Head: "DROP_TIME = [1.9 + (X x 0.08) + (Y x 0.036)]".
constexpr std::array<AutomaxDropTerm, 2> kHead57c330Terms{{
    {"outputs", &AutomaxDrop::outputs, 80, std::nullopt},
    {"inputs", &AutomaxDrop::inputs, 36, std::nullopt},
}};
// M/N 57C328 Remote I/O Head: "DROP_TIME = [1.7 + R x 0.036]". The head has
// four input/output register pairs, one per rail (section 4.3), so at most
// four rails.
constexpr std::array<AutomaxDropTerm, 1> kHead57c328Terms{{{"rails", &AutomaxDrop::rails, 36, 4}}};

// Section 4.5, one row per formula. Drop numbers: section 4.4 allows 1..7,
// or 9..F for digital Shark racks; section 4.5 ties the digital Shark
// formula to drops 9..F and the mixed Shark formula to drops 1..7.
constexpr std::array<AutomaxDropTypeInfo, 6> kDropTypes{{
    {AutomaxDropType::multibus, "multibus", "Multibus rack slave drop", 1500, kMultibusTerms, 1, 7},
    {AutomaxDropType::head_57c330, "head_57c330", "M/N 57C330 Remote I/O Head slave drop", 1900, kHead57c330Terms, 1,
     7},
    {AutomaxDropType::head_57c328, "head_57c328", "M/N 57C328 Remote I/O Head drop", 1700, kHead57c328Terms, 1, 7},
    {AutomaxDropType::drive_head, "drive_head", "Remote Drive Interface Head slave drop", 2100, {}, 1, 7},
    {AutomaxDropType::shark_digital, "shark_digital", "Shark slave drop (all digital I/O)", 1800, {}, 9, 15},
    {AutomaxDropType::shark_mixed, "shark_mixed", "Shark slave drop (analog and digital I/O)", 4000, {}, 1, 7},
}};

std::string drop_path(std::size_t index) { return "drops[" + std::to_string(index) + "]"; }

// Drop numbers as the manual writes them: 1..7 in decimal, 9..F in hex;
// numbers above 9 are shown both ways.
std::string hex_digit(int number) { return std::string(1, "0123456789ABCDEF"[number & 0xF]); }

std::string number_text(int number) {
    std::string text = std::to_string(number);
    if (number > 9 && number < 16) text += " (hex " + hex_digit(number) + ")";
    return text;
}

std::string range_text(const AutomaxDropTypeInfo& info) {
    std::string text = std::to_string(info.min_number) + ".." + std::to_string(info.max_number);
    if (info.max_number > 9) text += " (hex " + hex_digit(info.min_number) + ".." + hex_digit(info.max_number) + ")";
    return text;
}

std::string formula_text(const AutomaxDrop& drop) {
    const AutomaxDropTypeInfo& info = automax_drop_type(drop.type);
    std::string text = format_ms(info.base);
    for (const AutomaxDropTerm& term : info.terms) {
        text += " + (" + std::to_string(drop.*term.count) + " x " + format_ms(term.per_unit) + ")";
    }
    return text;
}

void validate_numbers(const AutomaxNetwork& network) {
    const auto numbered = std::count_if(network.drops.begin(), network.drops.end(),
                                        [](const AutomaxDrop& d) { return d.number.has_value(); });
    if (numbered != 0 && static_cast<std::size_t>(numbered) != network.drops.size()) {
        for (std::size_t i = 0; i < network.drops.size(); ++i) {
            if (!network.drops[i].number) {
                throw ConfigError(drop_path(i) + ".drop", "give a drop number for every drop or for none");
            }
        }
    }
    std::set<int> used;
    for (std::size_t i = 0; i < network.drops.size(); ++i) {
        const AutomaxDrop& drop = network.drops[i];
        if (!drop.number) continue;
        const AutomaxDropTypeInfo& info = automax_drop_type(drop.type);
        if (*drop.number < info.min_number || *drop.number > info.max_number) {
            throw ConfigError(drop_path(i) + ".drop", "a " + std::string(info.name) + " drop is numbered " +
                                                          range_text(info) + ", got " + std::to_string(*drop.number));
        }
        if (!used.insert(*drop.number).second) {
            throw ConfigError(drop_path(i) + ".drop", "drop number " + number_text(*drop.number) + " is used twice");
        }
    }
    // Without drop numbers the positions still have to fit the numbers the
    // master can address, per numbering range.
    std::map<std::pair<int, int>, int> per_range;
    for (const AutomaxDrop& drop : network.drops) {
        const AutomaxDropTypeInfo& info = automax_drop_type(drop.type);
        const int count = ++per_range[{info.min_number, info.max_number}];
        if (count > info.max_number - info.min_number + 1) {
            throw ConfigError("drops", "more than " + std::to_string(info.max_number - info.min_number + 1) +
                                           " drops use drop numbers " + range_text(info));
        }
    }
}

}  // namespace

std::span<const AutomaxDropTypeInfo> automax_drop_types() { return kDropTypes; }

const AutomaxDropTypeInfo& automax_drop_type(AutomaxDropType type) {
    for (const AutomaxDropTypeInfo& info : kDropTypes) {
        if (info.type == type) return info;
    }
    throw std::invalid_argument("automax_drop_type: unknown drop type");
}

std::optional<AutomaxDropType> parse_automax_drop_type(std::string_view name) {
    for (const AutomaxDropTypeInfo& info : kDropTypes) {
        if (info.name == name) return info.type;
    }
    return std::nullopt;
}

Micros automax_drop_time(const AutomaxDrop& drop) {
    const AutomaxDropTypeInfo& info = automax_drop_type(drop.type);
    Micros time = info.base;
    for (const AutomaxDropTerm& term : info.terms) time += term.per_unit * drop.*term.count;
    return time;
}

void validate_automax(const AutomaxNetwork& network) {
    if (network.drops.empty()) throw ConfigError("drops", "expected at least one drop");
    for (std::size_t i = 0; i < network.drops.size(); ++i) {
        const AutomaxDrop& drop = network.drops[i];
        for (const AutomaxDropTerm& term : automax_drop_type(drop.type).terms) {
            const int count = drop.*term.count;
            const std::string path = drop_path(i) + "." + std::string(term.field);
            if (count < 0) throw ConfigError(path, "expected 0 or more, got " + std::to_string(count));
            if (term.max_count && count > *term.max_count) {
                throw ConfigError(
                    path, "expected at most " + std::to_string(*term.max_count) + ", got " + std::to_string(count));
            }
        }
    }
    validate_numbers(network);
}

AutomaxResult compute_automax(const AutomaxNetwork& network) {
    validate_automax(network);
    AutomaxResult result;
    result.update_period = result.inactive_poll;
    for (std::size_t i = 0; i < network.drops.size(); ++i) {
        const AutomaxDrop& drop = network.drops[i];
        const Micros time = automax_drop_time(drop);
        result.drops.push_back({i, drop.number.value_or(static_cast<int>(i) + 1), drop.type, time, formula_text(drop)});
        result.update_period += time;
    }
    const auto has = [&](AutomaxDropType type) {
        return std::any_of(network.drops.begin(), network.drops.end(),
                           [type](const AutomaxDrop& d) { return d.type == type; });
    };
    if (has(AutomaxDropType::head_57c330)) {
        result.notes.push_back(
            "57C330 Remote I/O Head drops use the section 4.5 formula 1.9 + (X x 0.08) + (Y x 0.036). The manual's "
            "worked example instead computes its Remote I/O Head (5 outputs, 6 inputs) as 1.7 + (5 x .013) + "
            "(6 x .028) = 1.933 ms, with constants no formula states; by the formula that head takes 2.516 ms.");
    }
    if (has(AutomaxDropType::shark_digital)) {
        result.notes.push_back(
            "Digital Shark drops use the section 4.5 figure of 1.8 ms. The manual's worked example uses 1.900 ms "
            "for its digital Shark rack.");
    }
    return result;
}

}  // namespace softslc::throughput
