// Config parsing, result building and the text report for both calculators.
#include "modules/throughput/throughput_json.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

namespace softslc::throughput {

namespace {

using nlohmann::json;

// The largest time a config may give. Larger figures are certainly typing
// errors, and the bound keeps every sum far from overflowing Micros.
constexpr double kMaxConfigMs = 1'000'000.0;

// The spellings a config may use, in the order error messages list them.
constexpr std::array<RioBaud, 3> kAllBauds{RioBaud::b57_6k, RioBaud::b115_2k, RioBaud::b230_4k};
constexpr std::array<RioMode, 2> kAllModes{RioMode::normal, RioMode::complementary};
constexpr std::array<int, 4> kAllRackSizes{2, 4, 6, 8};

std::string child_path(const std::string& path, std::string_view key) {
    return path.empty() ? std::string(key) : path + "." + std::string(key);
}

std::string element_path(const std::string& path, std::size_t index) {
    return path + "[" + std::to_string(index) + "]";
}

// A JSON value as an error message shows it: scalars as written, containers
// by their type, so a message stays one short line.
std::string describe(const json& value) {
    if (value.is_object() || value.is_array()) return std::string("an ") + value.type_name();
    std::string text = value.dump();
    if (text.size() > 40) text.replace(37, std::string::npos, "...");
    return text;
}

std::string quoted_list(const std::vector<std::string_view>& names) {
    std::string text;
    for (std::string_view name : names) {
        if (!text.empty()) text += ",";
        text += "\"" + std::string(name) + "\"";
    }
    return text;
}

int integer_at(const json& value, const std::string& path) {
    if (!value.is_number_integer()) throw ConfigError(path, "expected an integer, got " + describe(value));
    if (value.is_number_unsigned() ? value.get<std::uint64_t>() > static_cast<std::uint64_t>(INT_MAX)
                                   : (value.get<std::int64_t>() > INT_MAX || value.get<std::int64_t>() < INT_MIN)) {
        throw ConfigError(path, "integer out of range: " + value.dump());
    }
    return value.get<int>();
}

// Reads one object of the config. Each accessor names the field's full path
// in its errors; allow_only() rejects keys the object's kind does not use.
class ObjectReader {
public:
    ObjectReader(const json& value, std::string path) : value_(value), path_(std::move(path)) {
        if (!value_.is_object()) throw ConfigError(path_, "expected a JSON object, got " + describe(value_));
    }

    std::string path(std::string_view key) const { return child_path(path_, key); }

    // "name" and "comment" are free-text labels every object may carry.
    void allow_only(const std::vector<std::string_view>& allowed, const std::string& hint = "") const {
        for (const auto& [key, unused] : value_.items()) {
            if (key == "name" || key == "comment") continue;
            if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
            throw ConfigError(path(key), hint.empty() ? "unknown key" : "unknown key; " + hint);
        }
    }

    const json* find(std::string_view key) const {
        const auto it = value_.find(key);
        return it == value_.end() ? nullptr : &*it;
    }

    const json& required(std::string_view key, const std::string& what) const {
        const json* value = find(key);
        if (value == nullptr) throw ConfigError(path(key), "required; expected " + what);
        return *value;
    }

    int integer(std::string_view key) const { return integer_at(required(key, "an integer"), path(key)); }

    std::optional<int> optional_integer(std::string_view key) const {
        const json* value = find(key);
        if (value == nullptr) return std::nullopt;
        return integer_at(*value, path(key));
    }

    std::optional<bool> optional_boolean(std::string_view key) const {
        const json* value = find(key);
        if (value == nullptr) return std::nullopt;
        if (!value->is_boolean()) throw ConfigError(path(key), "expected true or false, got " + describe(*value));
        return value->get<bool>();
    }

    std::optional<std::string> optional_string(std::string_view key) const {
        const json* value = find(key);
        if (value == nullptr) return std::nullopt;
        if (!value->is_string()) throw ConfigError(path(key), "expected a string, got " + describe(*value));
        return value->get<std::string>();
    }

    // A string that must be one of `choices`.
    std::optional<std::string> optional_choice(std::string_view key,
                                               const std::vector<std::string_view>& choices) const {
        const json* value = find(key);
        if (value == nullptr) return std::nullopt;
        if (!value->is_string() ||
            std::find(choices.begin(), choices.end(), value->get<std::string>()) == choices.end()) {
            throw ConfigError(path(key), "expected one of " + quoted_list(choices) + ", got " + describe(*value));
        }
        return value->get<std::string>();
    }

    std::string choice(std::string_view key, const std::vector<std::string_view>& choices) const {
        required(key, "one of " + quoted_list(choices));
        return *optional_choice(key, choices);
    }

    // A time in milliseconds, converted to whole microseconds. A finer
    // fraction is rounded to the nearest microsecond and noted.
    std::optional<Micros> optional_millis(std::string_view key, std::vector<std::string>& notes) const {
        const json* value = find(key);
        if (value == nullptr) return std::nullopt;
        if (!value->is_number()) {
            throw ConfigError(path(key), "expected a time in milliseconds (a number), got " + describe(*value));
        }
        const double ms = value->get<double>();
        if (!std::isfinite(ms) || std::fabs(ms) > kMaxConfigMs) {
            throw ConfigError(path(key), "expected a time of at most 1000000 ms, got " + describe(*value));
        }
        const double us = ms * 1000.0;
        const Micros rounded = std::llround(us);
        if (std::fabs(us - static_cast<double>(rounded)) > 1e-6) {
            notes.push_back(path(key) + ": " + value->dump() + " ms is taken as " + format_ms(rounded) +
                            " ms (the calculator works in whole microseconds).");
        }
        return rounded;
    }

    Micros millis(std::string_view key, std::vector<std::string>& notes) const {
        required(key, "a time in milliseconds");
        return *optional_millis(key, notes);
    }

    // An optional array; each element is handed to `read` with its path.
    template <typename Read>
    void for_each_element(std::string_view key, Read read) const {
        const json* value = find(key);
        if (value == nullptr) return;
        if (!value->is_array()) throw ConfigError(path(key), "expected an array, got " + describe(*value));
        for (std::size_t i = 0; i < value->size(); ++i) read((*value)[i], element_path(path(key), i));
    }

private:
    const json& value_;
    std::string path_;
};

double to_ms(Micros duration) { return static_cast<double>(duration) / 1000.0; }

// Results hold milliseconds that are exact to the microsecond; the report
// turns them back into integers so it formats them exactly.
Micros micros_of(const json& ms) { return std::llround(ms.get<double>() * 1000.0); }

// The config spellings of `values`, for choice() and its error messages.
template <typename Values, typename Name>
std::vector<std::string_view> names_of(const Values& values, Name name) {
    std::vector<std::string_view> names;
    names.reserve(std::size(values));
    for (const auto& value : values) names.push_back(name(value));
    return names;
}

// ---------------------------------------------------------------- RIO ----

RioDevice parse_rio_device(const json& value, const std::string& path) {
    const ObjectReader reader(value, path);
    reader.allow_only({"rack", "group", "size", "groups", "complementary"});
    RioDevice device;
    device.rack = reader.integer("rack");
    device.group = reader.integer("group");
    const std::vector<std::string_view> sizes = names_of(kAllRackSizes, rack_size_label);
    const std::optional<std::string> size = reader.optional_choice("size", sizes);
    const std::optional<int> groups = reader.optional_integer("groups");
    if (size && groups) throw ConfigError(reader.path("groups"), "give either size or groups, not both");
    if (!size && !groups) {
        throw ConfigError(path, "expected a size (one of " + quoted_list(sizes) + ") or a groups count");
    }
    device.groups = size ? *groups_for_rack_size(*size) : *groups;
    device.complementary = reader.optional_boolean("complementary").value_or(false);
    device.name = reader.optional_string("name").value_or("");
    return device;
}

RioBlockTransfer parse_rio_block_transfer(const json& value, const std::string& path) {
    const ObjectReader reader(value, path);
    reader.allow_only({"rack", "words"});
    RioBlockTransfer bt;
    bt.rack = reader.integer("rack");
    bt.words = reader.integer("words");
    bt.name = reader.optional_string("name").value_or("");
    return bt;
}

RioNetwork parse_rio(const ObjectReader& root, std::vector<std::string>& notes) {
    root.allow_only({"network", "baud", "mode", "processor_scan_ms", "adapter_delay_ms", "input_delay_ms",
                     "output_delay_ms", "t_upd_gt_t_hold", "t_upd_ms", "m0_file_writes", "devices", "block_transfers",
                     "m0_write_ms", "adapter_bt_delay_ms"});
    RioNetwork network;
    const auto baud_name = [](RioBaud baud) { return to_string(baud); };
    const auto mode_name = [](RioMode mode) { return to_string(mode); };
    network.baud = *parse_rio_baud(root.choice("baud", names_of(kAllBauds, baud_name)));
    network.mode = *parse_rio_mode(root.optional_choice("mode", names_of(kAllModes, mode_name)).value_or("normal"));
    network.processor_scan = root.millis("processor_scan_ms", notes);
    network.adapter_delay = root.millis("adapter_delay_ms", notes);
    network.input_delay = root.millis("input_delay_ms", notes);
    network.output_delay = root.millis("output_delay_ms", notes);
    network.t_upd_gt_t_hold = root.optional_boolean("t_upd_gt_t_hold");
    network.t_upd = root.optional_millis("t_upd_ms", notes);
    network.m0_file_writes = root.optional_boolean("m0_file_writes").value_or(false);
    root.required("devices", "an array of devices");
    root.for_each_element("devices", [&](const json& value, const std::string& path) {
        network.devices.push_back(parse_rio_device(value, path));
    });
    root.for_each_element("block_transfers", [&](const json& value, const std::string& path) {
        network.block_transfers.push_back(parse_rio_block_transfer(value, path));
    });
    const std::optional<Micros> m0_write = root.optional_millis("m0_write_ms", notes);
    const std::optional<Micros> adapter_bt_delay = root.optional_millis("adapter_bt_delay_ms", notes);
    if (m0_write.has_value() != adapter_bt_delay.has_value()) {
        throw ConfigError(
            m0_write ? "adapter_bt_delay_ms" : "m0_write_ms",
            m0_write ? "required together with m0_write_ms" : "required together with adapter_bt_delay_ms");
    }
    if (m0_write) network.bt_times = RioBtTimes{*m0_write, *adapter_bt_delay};
    return network;
}

json rio_t_sno_json(const RioNetwork& network, const RioTsno& tsno) {
    json out;
    out["symbol"] = tsno.table == TsnoTable::with_block_transfers ? "T_SNo-bt" : "T_SNO";
    out["table"] = to_string(tsno.table);
    out["mode"] = to_string(network.mode);
    out["column"] =
        network.mode == RioMode::normal ? std::string("all baud rates") : std::string(to_string(network.baud));
    out["logical_racks"] = tsno.logical_racks;
    if (tsno.upd_gt_hold) out["t_upd"] = *tsno.upd_gt_hold ? "T_upd > T_hold" : "T_upd <= T_hold";
    if (tsno.t_hold) out["t_hold_ms"] = to_ms(*tsno.t_hold);
    return out;
}

json rio_bt_json(const RioNetwork& network, const RioBtFigures& bt) {
    json out;
    out["t_m0_ms"] = to_ms(bt.m0_write);
    out["t_adp_bt_ms"] = to_ms(bt.adapter_bt_delay);
    out["number_of_bts"] = network.block_transfers.size();
    out["formula"] = "T_bt = T_M0 + T_SNo-bt(number of BTs + 1) + T_btwait + 2T_RIO + 2T_btx + T_adp-bt + T_ps";
    out["block_transfers"] = json::array();
    for (const RioBtThroughput& entry : bt.per_block_transfer) {
        json row;
        row["block_transfer"] = entry.block_transfer;
        const std::string& name = network.block_transfers[entry.block_transfer].name;
        if (!name.empty()) row["name"] = name;
        row["rack"] = entry.rack;
        row["words"] = entry.words;
        row["t_btwait_ms"] = to_ms(entry.t_btwait);
        row["t_bt_ms"] = to_ms(entry.t_bt);
        out["block_transfers"].push_back(row);
    }
    out["buffer_free_formula"] = "T_free = T_M0 + T_SNo-bt(number of BTs) + T_ps";
    out["t_buffer_free_ms"] = to_ms(bt.buffer_free);
    return out;
}

json rio_json(const RioNetwork& network, const RioResult& result, std::vector<std::string> notes) {
    json out;
    out["network"] = "rio";
    out["baud"] = to_string(network.baud);
    out["mode"] = to_string(network.mode);

    out["logical_devices"] = json::array();
    for (const RioLogicalDevice& d : result.logical_devices) {
        json row;
        row["device"] = d.device;
        const std::string& name = network.devices[d.device].name;
        if (!name.empty()) row["name"] = name;
        row["rack"] = d.rack;
        row["group"] = d.group;
        row["groups"] = d.groups;
        row["size"] = rack_size_label(d.groups);
        row["image"] = network.mode == RioMode::normal ? "normal" : (d.complementary ? "complementary" : "primary");
        row["t_rio_ms"] = to_ms(d.t_rio);
        out["logical_devices"].push_back(row);
    }
    out["configured_racks"] = result.configured_racks;
    out["logical_racks_configured"] = result.configured_racks.size();
    out["t_rio_ms"] = to_ms(result.t_rio);
    out["t_sno"] = rio_t_sno_json(network, result.t_sno);
    out["t_sno_ms"] = to_ms(result.t_sno.value);
    out["t_sni_ms"] = to_ms(result.t_sni);
    out["t_ps_ms"] = to_ms(network.processor_scan);
    out["t_adp_ms"] = to_ms(network.adapter_delay);
    out["t_id_ms"] = to_ms(network.input_delay);
    out["t_od_ms"] = to_ms(network.output_delay);

    out["block_transfer_racks"] = json::array();
    for (const RioRackBlockTransfers& rack : result.bt_racks) {
        json row;
        row["rack"] = rack.rack;
        row["max_words"] = rack.max_words;
        row["block_transfers"] = rack.block_transfers;
        row["t_ri_ms"] = to_ms(rack.t_ri);
        out["block_transfer_racks"].push_back(row);
    }
    out["t_btx_ms"] = to_ms(result.t_btx);

    // The calculation line reads like the manual's substituted formulas,
    // e.g. "2(25.0) + 2(25.5) + 8.0 + 7.0 + 5.0 + 10.0 + 1.0".
    std::string calculation = "2(" + format_ms(network.processor_scan) + ") + 2(" + format_ms(result.t_rio) + ")";
    if (result.with_block_transfers) calculation += " + 2(" + format_ms(result.t_btx) + ")";
    for (Micros term :
         {network.adapter_delay, result.t_sno.value, result.t_sni, network.input_delay, network.output_delay}) {
        calculation += " + " + format_ms(term);
    }
    out["formula"] = result.with_block_transfers
                         ? "T_dm-bt = 2T_ps + 2T_RIO + 2T_btx + T_adp + T_SNO-bt + T_SNI + T_id + T_od"
                         : "T_dm-nbt = 2T_ps + 2T_RIO + T_adp + T_SNO + T_SNI + T_id + T_od";
    out["calculation"] = calculation;
    out[result.with_block_transfers ? "t_dm_bt_ms" : "t_dm_nbt_ms"] = to_ms(result.t_dm);
    if (result.bt) out["block_transfer_throughput"] = rio_bt_json(network, *result.bt);
    notes.insert(notes.end(), result.notes.begin(), result.notes.end());
    out["notes"] = notes;
    return out;
}

// ------------------------------------------------------------ AutoMax ----

// A drop number is an integer, or one hex digit as the manual writes drops
// 9..F.
int parse_drop_number(const json& value, const std::string& path) {
    if (value.is_string()) {
        const std::string text = value.get<std::string>();
        static constexpr std::string_view kHex = "0123456789ABCDEF";
        const std::size_t digit = text.size() == 1
                                      ? kHex.find(static_cast<char>(std::toupper(static_cast<unsigned char>(text[0]))))
                                      : std::string_view::npos;
        if (digit == std::string_view::npos) {
            throw ConfigError(path, "expected a drop number 1..7 or 9..15 (hex 9..F), got " + describe(value));
        }
        return static_cast<int>(digit);
    }
    return integer_at(value, path);
}

AutomaxDrop parse_automax_drop(const json& value, const std::string& path) {
    const ObjectReader reader(value, path);
    const auto type_name = [](const AutomaxDropTypeInfo& info) { return info.name; };
    AutomaxDrop drop;
    drop.type = *parse_automax_drop_type(reader.choice("type", names_of(automax_drop_types(), type_name)));
    const AutomaxDropTypeInfo& info = automax_drop_type(drop.type);

    std::vector<std::string_view> allowed{"type", "drop"};
    for (const AutomaxDropTerm& term : info.terms) allowed.push_back(term.field);
    std::string hint = "a \"" + std::string(info.name) + "\" drop takes type, drop";
    for (const AutomaxDropTerm& term : info.terms) hint += ", " + std::string(term.field);
    reader.allow_only(allowed, hint + ", name and comment");

    for (const AutomaxDropTerm& term : info.terms) {
        const json& count =
            reader.required(term.field, "an integer (required for a \"" + std::string(info.name) + "\" drop)");
        drop.*term.count = integer_at(count, reader.path(term.field));
    }
    if (const json* number = reader.find("drop")) drop.number = parse_drop_number(*number, reader.path("drop"));
    drop.name = reader.optional_string("name").value_or("");
    return drop;
}

AutomaxNetwork parse_automax(const ObjectReader& root) {
    root.allow_only({"network", "drops"});
    AutomaxNetwork network;
    root.required("drops", "an array of drops");
    root.for_each_element("drops", [&](const json& value, const std::string& path) {
        network.drops.push_back(parse_automax_drop(value, path));
    });
    return network;
}

json automax_json(const AutomaxNetwork& network, const AutomaxResult& result) {
    json out;
    out["network"] = "automax";
    out["drops"] = json::array();
    for (const AutomaxDropResult& d : result.drops) {
        const AutomaxDrop& drop = network.drops[d.index];
        const AutomaxDropTypeInfo& info = automax_drop_type(d.type);
        json row;
        row["drop"] = d.drop;
        if (!drop.name.empty()) row["name"] = drop.name;
        row["type"] = info.name;
        for (const AutomaxDropTerm& term : info.terms) row[std::string(term.field)] = drop.*term.count;
        row["formula"] = d.formula;
        row["drop_time_ms"] = to_ms(d.drop_time);
        out["drops"].push_back(row);
    }
    out["inactive_poll_ms"] = to_ms(result.inactive_poll);
    out["update_period_ms"] = to_ms(result.update_period);
    out["notes"] = result.notes;
    return out;
}

// --------------------------------------------------------- text report ----

// A plain-text table: a header row, then rows, columns padded to their
// widest cell. Figure columns are right-aligned with their decimal points in
// line: a figure is padded after its last digit to the column's longest
// fraction, so each figure keeps its exact printed form (2.75 next to 4.0).
enum class Align { left, right, decimal };

struct Column {
    std::string header;
    Align align = Align::left;
};

std::size_t fraction_length(const std::string& cell) {
    const std::size_t dot = cell.find('.');
    return dot == std::string::npos ? 0 : cell.size() - dot;
}

std::string render_table(const std::vector<Column>& columns, std::vector<std::vector<std::string>> rows) {
    for (std::size_t c = 0; c < columns.size(); ++c) {
        if (columns[c].align != Align::decimal) continue;
        std::size_t fraction = 0;
        for (const auto& row : rows) fraction = std::max(fraction, fraction_length(row[c]));
        for (auto& row : rows) {
            if (row[c].find('.') != std::string::npos) row[c] += std::string(fraction - fraction_length(row[c]), ' ');
        }
    }
    std::vector<std::size_t> widths;
    widths.reserve(columns.size());
    for (const Column& column : columns) widths.push_back(column.header.size());
    for (const auto& row : rows) {
        for (std::size_t c = 0; c < row.size(); ++c) widths[c] = std::max(widths[c], row[c].size());
    }
    const auto line = [&](const std::vector<std::string>& cells) {
        std::string text = " ";
        for (std::size_t c = 0; c < columns.size(); ++c) {
            const std::string& cell = cells[c];
            const std::string pad(widths[c] - cell.size(), ' ');
            text += std::string(c == 0 ? " " : "  ") + (columns[c].align == Align::left ? cell + pad : pad + cell);
        }
        while (!text.empty() && text.back() == ' ') text.pop_back();
        return text + "\n";
    };
    std::vector<std::string> headers;
    headers.reserve(columns.size());
    for (const Column& column : columns) headers.push_back(column.header);
    std::string text = line(headers);
    for (const auto& row : rows) text += line(row);
    return text;
}

std::string ms_text(const json& ms) { return format_ms(micros_of(ms)); }

std::string notes_text(const json& result) {
    if (result.at("notes").empty()) return "";
    std::string text = "\nNotes\n";
    for (const json& note : result.at("notes")) text += "  - " + note.get<std::string>() + "\n";
    return text;
}

std::string name_line(const json& result) {
    return result.contains("name") ? "  " + result.at("name").get<std::string>() + "\n" : "";
}

std::string join_numbers(const json& values) {
    std::string text;
    for (const json& value : values) text += (text.empty() ? "" : ", ") + value.dump();
    return text;
}

std::string t_sno_description(const json& tsno) {
    std::string text = tsno.at("table").get<std::string>() + ", " + tsno.at("mode").get<std::string>() + " mode (" +
                       tsno.at("column").get<std::string>() + "), " + tsno.at("logical_racks").dump() +
                       " logical rack" + (tsno.at("logical_racks").get<int>() == 1 ? "" : "s");
    if (tsno.contains("t_upd")) {
        text += ", " + tsno.at("t_upd").get<std::string>() + " (T_hold " + ms_text(tsno.at("t_hold_ms")) + " ms)";
    }
    return text;
}

std::string rio_text(const json& result) {
    std::string text = "RIO network throughput (1747-SN Series B scanner, manual appendix A)\n" + name_line(result);
    text += "  Baud rate " + result.at("baud").get<std::string>() + ", " + result.at("mode").get<std::string>() +
            " mode, " + result.at("logical_racks_configured").dump() + " logical rack(s) configured (" +
            join_numbers(result.at("configured_racks")) + ")\n";

    text +=
        "\nLogical devices (\"RIO Scan Times for Adapters\", " + result.at("baud").get<std::string>() + " column)\n";
    std::vector<std::vector<std::string>> rows;
    for (const json& d : result.at("logical_devices")) {
        const int group = d.at("group").get<int>();
        rows.push_back({d.at("device").dump(), d.value("name", ""), d.at("rack").dump(),
                        std::to_string(group) + "-" + std::to_string(group + d.at("groups").get<int>() - 1),
                        d.at("size").get<std::string>(), d.at("image").get<std::string>(), ms_text(d.at("t_rio_ms"))});
    }
    rows.push_back({"", "", "", "", "", "T_RIO", ms_text(result.at("t_rio_ms"))});
    text += render_table({{"Device", Align::right},
                          {"Name"},
                          {"Rack", Align::right},
                          {"Groups"},
                          {"Size"},
                          {"Image"},
                          {"T_RIO (ms)", Align::decimal}},
                         rows);

    const bool with_bts = result.contains("t_dm_bt_ms");
    if (with_bts) {
        text += "\nBlock transfers (one per logical rack per RIO scan; the longest counts)\n";
        rows.clear();
        for (const json& rack : result.at("block_transfer_racks")) {
            rows.push_back({rack.at("rack").dump(), join_numbers(rack.at("block_transfers")),
                            rack.at("max_words").dump(), ms_text(rack.at("t_ri_ms"))});
        }
        rows.push_back({"", "", "T_btx", ms_text(result.at("t_btx_ms"))});
        text += render_table({{"Rack", Align::right},
                              {"Block transfers"},
                              {"Longest (words)", Align::right},
                              {"T_ri (ms)", Align::decimal}},
                             rows);
    }

    text += with_bts ? "\nDiscrete I/O throughput with block transfers\n"
                     : "\nDiscrete I/O throughput without block transfers\n";
    const std::string sno_symbol = result.at("t_sno").at("symbol").get<std::string>();
    rows = {{"T_ps", ms_text(result.at("t_ps_ms")), "ms", "processor scan time"},
            {"T_RIO", ms_text(result.at("t_rio_ms")), "ms", "RIO scan time"}};
    if (with_bts)
        rows.push_back({"T_btx", ms_text(result.at("t_btx_ms")), "ms", "RIO scan time added by block transfers"});
    rows.push_back({"T_adp", ms_text(result.at("t_adp_ms")), "ms", "adapter throughput delay"});
    rows.push_back({sno_symbol, ms_text(result.at("t_sno_ms")), "ms", t_sno_description(result.at("t_sno"))});
    rows.push_back({"T_SNI", ms_text(result.at("t_sni_ms")), "ms", "scanner input delay"});
    rows.push_back({"T_id", ms_text(result.at("t_id_ms")), "ms", "input module delay"});
    rows.push_back({"T_od", ms_text(result.at("t_od_ms")), "ms", "output module delay"});
    text += render_table({{"Figure"}, {"Value", Align::decimal}, {"Unit"}, {"Source"}}, rows);

    const std::string formula = result.at("formula").get<std::string>();
    const std::size_t equals = formula.find(" = ");
    const std::string indent(equals + 1, ' ');
    text += "\n  " + formula + "\n";
    text += "  " + indent + "= " + result.at("calculation").get<std::string>() + "\n";
    text += "  " + indent + "= " + ms_text(result.at(with_bts ? "t_dm_bt_ms" : "t_dm_nbt_ms")) + " ms\n";

    if (result.contains("block_transfer_throughput")) {
        const json& bt = result.at("block_transfer_throughput");
        text += "\nBlock transfer throughput (T_M0 " + ms_text(bt.at("t_m0_ms")) + " ms, T_adp-bt " +
                ms_text(bt.at("t_adp_bt_ms")) + " ms, " + bt.at("number_of_bts").dump() + " BTs)\n";
        text += "  " + bt.at("formula").get<std::string>() + "\n";
        rows.clear();
        for (const json& entry : bt.at("block_transfers")) {
            rows.push_back({entry.at("block_transfer").dump(), entry.value("name", ""), entry.at("rack").dump(),
                            entry.at("words").dump(), ms_text(entry.at("t_btwait_ms")), ms_text(entry.at("t_bt_ms"))});
        }
        text += render_table({{"BT", Align::right},
                              {"Name"},
                              {"Rack", Align::right},
                              {"Words", Align::right},
                              {"T_btwait (ms)", Align::decimal},
                              {"T_bt (ms)", Align::decimal}},
                             rows);
        text += "  " + bt.at("buffer_free_formula").get<std::string>() + " = " + ms_text(bt.at("t_buffer_free_ms")) +
                " ms\n";
    }
    return text + notes_text(result);
}

std::string automax_text(const json& result) {
    std::string text =
        "AutoMax Remote I/O data update rate (manual chapter 4, section 4.5)\n" + name_line(result) + "\n";
    std::vector<std::vector<std::string>> rows;
    for (const json& d : result.at("drops")) {
        rows.push_back({d.at("drop").dump(), d.value("name", ""), d.at("type").get<std::string>(),
                        d.at("formula").get<std::string>(), ms_text(d.at("drop_time_ms"))});
    }
    rows.push_back({"", "", "", "polling inactive drops", ms_text(result.at("inactive_poll_ms"))});
    rows.push_back({"", "", "", "update period", ms_text(result.at("update_period_ms"))});
    text += render_table(
        {{"Drop", Align::right}, {"Name"}, {"Type"}, {"DROP_TIME formula (ms)"}, {"Time (ms)", Align::decimal}}, rows);
    return text + notes_text(result);
}

}  // namespace

json compute_throughput(const json& config) {
    const ObjectReader root(config, "");
    const std::string kind = root.choice("network", {"rio", "automax"});
    const std::optional<std::string> name = root.optional_string("name");
    json result;
    if (kind == "rio") {
        std::vector<std::string> notes;
        const RioNetwork network = parse_rio(root, notes);
        result = rio_json(network, compute_rio(network), std::move(notes));
    } else {
        const AutomaxNetwork network = parse_automax(root);
        result = automax_json(network, compute_automax(network));
    }
    // The config's label travels with the result so a saved report says
    // which network it describes.
    if (name) result["name"] = *name;
    return result;
}

std::string format_throughput_text(const json& result) {
    const std::string network = result.at("network").get<std::string>();
    if (network == "rio") return rio_text(result);
    if (network == "automax") return automax_text(result);
    throw json::other_error::create(501, "not a throughput result: unknown network \"" + network + "\"", &result);
}

}  // namespace softslc::throughput
