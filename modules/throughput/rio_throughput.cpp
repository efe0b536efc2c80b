// The 1747-SN appendix A tables as data, and the throughput formulas over
// them. Every table below has one entry per row of the printed table, in the
// manual's order, with the manual's figures converted to microseconds.
#include "modules/throughput/rio_throughput.h"

#include <algorithm>
#include <array>
#include <string>

namespace softslc::throughput {

namespace {

constexpr std::size_t kBaudCount = 3;

// The scanner image is four logical racks of eight groups each (manual
// chapter 1, "Scanner I/O Image Concepts"); logical devices start on even
// groups, and an adapter uses 2..32 groups in steps of two ("Crossing
// Logical Rack Boundaries").
constexpr int kRacks = 4;
constexpr int kGroupsPerRack = 8;
constexpr int kImageGroups = kRacks * kGroupsPerRack;

// The scanner has 32 block-transfer buffers, so at most 32 different block
// transfers (manual chapter 5, "Using Block Transfer Instructions").
constexpr std::size_t kMaxBlockTransfers = 32;

// A block transfer moves at most 64 words; a requested length of 0 reserves
// 64 words (manual chapter 5, "Requested Word Count").
constexpr int kMaxBtWords = 64;

std::size_t baud_index(RioBaud baud) { return static_cast<std::size_t>(baud); }

// Appendix A, "RIO Scan Time Calculation (T_RIO)", table "RIO Scan Times for
// Adapters": the RIO scan time of one logical device by its size and the
// baud rate, in the columns 57.6K, 115.2K, 230.4K.
struct RioScanTimeRow {
    int groups;
    std::string_view label;
    std::array<Micros, kBaudCount> by_baud;
};
constexpr std::array<RioScanTimeRow, 4> kRioScanTimes{{
    {2, "1/4", {6000, 3500, 2500}},
    {4, "1/2", {6500, 4000, 2750}},
    {6, "3/4", {7500, 4500, 3000}},
    {8, "full", {9500, 5500, 3500}},
}};

// One row of a T_SNO table with T_upd columns: the normal-mode cell (all baud
// rates) and the complementary-mode cells for 57.6K, 115.2K and 230.4K. Each
// cell reads "T_SNO if T_upd <= T_hold | T_hold | T_SNO if T_upd > T_hold".
struct TsnoRow {
    int logical_racks;
    TsnoCell normal;
    std::array<TsnoCell, kBaudCount> complementary;
};

// Appendix A, "T_SNO without M0 File Writes", normal and complementary
// tables (the values are printed as in the manual, including the 230.4K,
// four-rack cell whose T_hold of 22.0 exceeds its T_SNO of 21.0).
constexpr std::array<TsnoRow, 4> kTsnoWithoutM0Writes{{
    {1, {5000, 5000, 2500}, {{{6000, 5000, 4000}, {7000, 7000, 4000}, {10000, 9000, 4000}}}},
    {2, {7000, 7000, 4000}, {{{9000, 8000, 5000}, {10000, 10000, 6000}, {12000, 12000, 7000}}}},
    {3, {9000, 9000, 5500}, {{{12000, 11000, 7000}, {12000, 12000, 8000}, {16000, 16000, 10000}}}},
    {4, {11000, 11000, 7000}, {{{15000, 14000, 9000}, {16000, 16000, 10000}, {21000, 22000, 13000}}}},
}};

// Appendix A, "T_SNo with M0 File Writes (No Block Transfers)", normal and
// complementary tables.
constexpr std::array<TsnoRow, 4> kTsnoWithM0Writes{{
    {1, {8000, 6000, 4500}, {{{10000, 6000, 6000}, {12000, 8000, 8000}, {15000, 10000, 9000}}}},
    {2, {10000, 8000, 5500}, {{{12000, 9000, 8000}, {14000, 11000, 9000}, {17000, 15000, 12000}}}},
    {3, {12000, 10000, 7000}, {{{15000, 12000, 9000}, {16000, 14000, 11000}, {21000, 20000, 14000}}}},
    {4, {14000, 12000, 8000}, {{{18000, 15000, 10000}, {20000, 17000, 12000}, {26000, 24000, 17000}}}},
}};

// Appendix A, "Determining T_SNo-bt": the scanner output delay with block
// transfers present, normal mode (all baud rates) and complementary mode
// (57.6K, 115.2K, 230.4K). This table has no T_upd columns.
struct TsnoBtRow {
    int logical_racks;
    Micros normal;
    std::array<Micros, kBaudCount> complementary;
};
constexpr std::array<TsnoBtRow, 4> kTsnoBt{{
    {1, 16000, {19000, 24000, 32000}},
    {2, 19000, {23000, 27000, 36000}},
    {3, 22000, {26000, 30000, 39000}},
    {4, 25000, {28000, 34000, 42000}},
}};

// Appendix A, "Determining T_btX": the RIO scan time increase per logical
// rack, T_ri = per_word x BT length + base, one row per baud rate.
struct TriRow {
    RioBaud baud;
    Micros per_word;
    Micros base;
};
constexpr std::array<TriRow, kBaudCount> kTri{{
    {RioBaud::b57_6k, 300, 5000},
    {RioBaud::b115_2k, 150, 3500},
    {RioBaud::b230_4k, 75, 2000},
}};

// The labels the config file and the reports use, one row per enumerator.
struct BaudName {
    RioBaud baud;
    std::string_view name;
};
constexpr std::array<BaudName, kBaudCount> kBaudNames{{
    {RioBaud::b57_6k, "57.6K"},
    {RioBaud::b115_2k, "115.2K"},
    {RioBaud::b230_4k, "230.4K"},
}};

const TsnoRow& tsno_row(TsnoTable table, int logical_racks) {
    if (table == TsnoTable::with_block_transfers) {
        throw std::invalid_argument("t_sno_cell: the T_SNo-bt table has no T_upd columns");
    }
    if (logical_racks < 1 || logical_racks > kRacks) {
        throw std::invalid_argument("t_sno_cell: logical rack count must be 1..4");
    }
    const auto& rows = table == TsnoTable::with_m0_writes ? kTsnoWithM0Writes : kTsnoWithoutM0Writes;
    return rows[static_cast<std::size_t>(logical_racks - 1)];
}

// Words charged for a block transfer: a requested length of 0 lets the module
// transfer up to the 64-word maximum, so the worst case is 64.
int charged_words(int words) { return words == 0 ? kMaxBtWords : words; }

std::string device_path(std::size_t index) { return "devices[" + std::to_string(index) + "]"; }
std::string bt_path(std::size_t index) { return "block_transfers[" + std::to_string(index) + "]"; }

// "rack 1 group 2" or "rack 1 groups 0-3", for error messages and notes.
std::string span_text(int rack, int group, int groups) {
    std::string text = "rack " + std::to_string(rack);
    if (groups <= 1) return text + " group " + std::to_string(group);
    return text + " groups " + std::to_string(group) + "-" + std::to_string(group + groups - 1);
}

// The manual calls racks 0..3 the "normal" image in normal mode and the
// "primary" image in complementary mode.
std::string image_name(RioMode mode, bool complementary) {
    if (complementary) return "complementary";
    return mode == RioMode::normal ? "normal" : "primary";
}

void require_non_negative(Micros value, const char* path) {
    if (value < 0) throw ConfigError(path, "expected a time of 0 ms or more");
}

void validate_device(const RioNetwork& network, std::size_t index) {
    const RioDevice& device = network.devices[index];
    const std::string path = device_path(index);
    if (device.rack < 0 || device.rack >= kRacks) {
        std::string message = "expected a logical rack 0..3, got " + std::to_string(device.rack);
        if (device.rack >= 8 && device.rack <= 11) {
            message += " (give a complementary device its primary rack number with \"complementary\": true)";
        }
        throw ConfigError(path + ".rack", message);
    }
    if (device.group < 0 || device.group >= kGroupsPerRack) {
        throw ConfigError(path + ".group", "expected a logical group 0..7, got " + std::to_string(device.group));
    }
    if (device.group % 2 != 0) {
        throw ConfigError(path + ".group", "a logical device starts at an even group (0, 2, 4 or 6), got " +
                                               std::to_string(device.group));
    }
    if (device.groups < 2 || device.groups > kImageGroups || device.groups % 2 != 0) {
        throw ConfigError(path + ".groups",
                          "expected an even number of groups from 2 to 32, got " + std::to_string(device.groups));
    }
    const int first = device.rack * kGroupsPerRack + device.group;
    if (first + device.groups > kImageGroups) {
        throw ConfigError(path, std::to_string(device.groups) + " groups starting at rack " +
                                    std::to_string(device.rack) + " group " + std::to_string(device.group) +
                                    " run past rack 3 group 7, the end of the scanner image");
    }
    if (device.complementary && network.mode != RioMode::complementary) {
        throw ConfigError(path + ".complementary", "complementary devices need \"mode\": \"complementary\"");
    }
}

// Checks that no two logical devices of one image share a group, and that a
// complementary logical device overlaps a primary one only when both start at
// the same rack and group (manual chapter 4, "Rules for Configuring the
// Scanner", "Concerning Complementary I/O"). The check works per logical
// device, because the scanner exchanges data per logical device and the G
// file marks "the starting logical address of each logical device".
void validate_overlaps(RioMode mode, const std::vector<RioLogicalDevice>& logical) {
    for (std::size_t later = 0; later < logical.size(); ++later) {
        const RioLogicalDevice& b = logical[later];
        for (std::size_t earlier = 0; earlier < later; ++earlier) {
            const RioLogicalDevice& a = logical[earlier];
            if (a.rack != b.rack) continue;
            const int lo = std::max(a.group, b.group);
            const int hi = std::min(a.group + a.groups, b.group + b.groups);
            if (lo >= hi) continue;
            if (a.complementary == b.complementary) {
                throw ConfigError(device_path(b.device), "overlaps " + device_path(a.device) + " in the " +
                                                             image_name(mode, b.complementary) + " image at " +
                                                             span_text(b.rack, lo, hi - lo));
            }
            if (a.group != b.group) {
                const RioLogicalDevice& comp = a.complementary ? a : b;
                const RioLogicalDevice& prim = a.complementary ? b : a;
                throw ConfigError(device_path(b.device),
                                  "complementary " + device_path(comp.device) + " (" +
                                      span_text(comp.rack, comp.group, comp.groups) + ") overlaps primary " +
                                      device_path(prim.device) + " (" + span_text(prim.rack, prim.group, prim.groups) +
                                      ") but they start at different groups; a complementary device may share "
                                      "image space with a primary device only when both start at the same group");
            }
        }
    }
}

void validate_block_transfers(const RioNetwork& network, const std::vector<RioLogicalDevice>& logical) {
    if (network.block_transfers.size() > kMaxBlockTransfers) {
        throw ConfigError("block_transfers", "at most 32 block transfers (the scanner has 32 BT buffers), got " +
                                                 std::to_string(network.block_transfers.size()));
    }
    for (std::size_t i = 0; i < network.block_transfers.size(); ++i) {
        const RioBlockTransfer& bt = network.block_transfers[i];
        if (bt.rack < 0 || bt.rack >= kRacks) {
            throw ConfigError(bt_path(i) + ".rack", "expected a logical rack 0..3, got " + std::to_string(bt.rack));
        }
        if (bt.words < 0 || bt.words > kMaxBtWords) {
            throw ConfigError(bt_path(i) + ".words",
                              "expected a block transfer length of 0..64 words, got " + std::to_string(bt.words));
        }
        const bool rack_used =
            std::any_of(logical.begin(), logical.end(), [&](const RioLogicalDevice& d) { return d.rack == bt.rack; });
        if (!rack_used) {
            throw ConfigError(bt_path(i) + ".rack",
                              "no device is configured in logical rack " + std::to_string(bt.rack));
        }
    }
}

// Chooses the T_SNO figure: the T_SNo-bt table when block transfers are
// present; otherwise the cell of the T_SNO table with or without M0 file
// writes for the configured rack count, in the column the T_upd comparison
// selects.
RioTsno select_t_sno(const RioNetwork& network, int logical_racks, bool with_bts, std::vector<std::string>& notes) {
    RioTsno tsno;
    tsno.logical_racks = logical_racks;
    if (with_bts) {
        tsno.table = TsnoTable::with_block_transfers;
        tsno.value = t_sno_bt(network.mode, network.baud, logical_racks);
        if (network.t_upd_gt_t_hold || network.t_upd || network.m0_file_writes) {
            notes.push_back(
                "With block transfers present T_SNO comes from the T_SNo-bt table, which has no T_upd "
                "columns and no M0-write variant; t_upd_gt_t_hold, t_upd_ms and m0_file_writes are not "
                "used.");
        }
        return tsno;
    }
    tsno.table = network.m0_file_writes ? TsnoTable::with_m0_writes : TsnoTable::without_m0_writes;
    const TsnoCell cell = t_sno_cell(tsno.table, network.mode, network.baud, logical_racks);
    tsno.t_hold = cell.t_hold;
    if (network.t_upd_gt_t_hold) {
        tsno.upd_gt_hold = *network.t_upd_gt_t_hold;
    } else if (network.t_upd) {
        tsno.upd_gt_hold = *network.t_upd > cell.t_hold;
    } else {
        tsno.upd_gt_hold = false;
        notes.push_back(
            "Neither t_upd_gt_t_hold nor t_upd_ms was given, so T_SNO is the larger figure of the "
            "T_upd <= T_hold column (T_hold = " +
            format_ms(cell.t_hold) + " ms), which the manual says must be used when T_upd is below T_hold.");
    }
    tsno.value = *tsno.upd_gt_hold ? cell.if_upd_gt_hold : cell.if_upd_le_hold;
    return tsno;
}

std::vector<RioRackBlockTransfers> group_block_transfers(const RioNetwork& network) {
    std::vector<RioRackBlockTransfers> racks;
    for (int rack = 0; rack < kRacks; ++rack) {
        RioRackBlockTransfers entry;
        entry.rack = rack;
        for (std::size_t i = 0; i < network.block_transfers.size(); ++i) {
            const RioBlockTransfer& bt = network.block_transfers[i];
            if (bt.rack != rack) continue;
            entry.block_transfers.push_back(i);
            entry.max_words = std::max(entry.max_words, charged_words(bt.words));
        }
        if (entry.block_transfers.empty()) continue;
        entry.t_ri = t_ri(network.baud, entry.max_words);
        racks.push_back(std::move(entry));
    }
    return racks;
}

// Appendix A, "Block Transfer Throughput":
//   T_bt   = T_M0 + T_SNo-bt (number of BTs + 1) + T_btwait + 2T_RIO + 2T_btx + T_adp-bt + T_ps
//   T_free = T_M0 + T_SNo-bt (number of BTs) + T_ps
// T_btwait is the sum of the throughput times of the other block transfers
// queued to the same logical rack plus one T_SNo-bt to schedule the pending
// transfer, and zero when the rack has a single block transfer. The other
// transfers' times are taken without their own wait (their worst case would
// count this transfer's wait in turn), which makes every block transfer in a
// rack of k transfers wait (k - 1) base times plus one T_SNo-bt: the worst
// case of being last in the rack's queue.
RioBtFigures block_transfer_figures(const RioNetwork& network, const RioResult& result) {
    const RioBtTimes& times = *network.bt_times;
    const Micros count = static_cast<Micros>(network.block_transfers.size());
    const Micros sno = result.t_sno.value;
    const Micros base = times.m0_write + sno * (count + 1) + 2 * result.t_rio + 2 * result.t_btx +
                        times.adapter_bt_delay + network.processor_scan;
    RioBtFigures figures;
    figures.m0_write = times.m0_write;
    figures.adapter_bt_delay = times.adapter_bt_delay;
    figures.buffer_free = times.m0_write + sno * count + network.processor_scan;
    for (const RioRackBlockTransfers& rack : result.bt_racks) {
        const Micros others = static_cast<Micros>(rack.block_transfers.size()) - 1;
        const Micros wait = others > 0 ? others * base + sno : 0;
        for (std::size_t index : rack.block_transfers) {
            const RioBlockTransfer& bt = network.block_transfers[index];
            figures.per_block_transfer.push_back({index, bt.rack, charged_words(bt.words), wait, base + wait});
        }
    }
    std::sort(figures.per_block_transfer.begin(), figures.per_block_transfer.end(),
              [](const RioBtThroughput& a, const RioBtThroughput& b) { return a.block_transfer < b.block_transfer; });
    return figures;
}

void add_split_notes(const RioNetwork& network, const std::vector<RioLogicalDevice>& logical,
                     std::vector<std::string>& notes) {
    for (std::size_t i = 0; i < network.devices.size(); ++i) {
        std::vector<const RioLogicalDevice*> parts;
        for (const RioLogicalDevice& d : logical) {
            if (d.device == i) parts.push_back(&d);
        }
        if (parts.size() < 2) continue;
        const RioDevice& device = network.devices[i];
        std::string note = device_path(i) + " (" + std::to_string(device.groups) + " groups from rack " +
                           std::to_string(device.rack) + " group " + std::to_string(device.group) +
                           ") crosses a logical rack boundary and is scanned as " + std::to_string(parts.size()) +
                           " logical devices:";
        for (std::size_t p = 0; p < parts.size(); ++p) {
            note += (p == 0 ? " " : ", ") + span_text(parts[p]->rack, parts[p]->group, parts[p]->groups) + " (" +
                    std::string(rack_size_label(parts[p]->groups)) + ")";
        }
        notes.push_back(note + ".");
    }
}

}  // namespace

ConfigError::ConfigError(std::string path, const std::string& message)
    : std::runtime_error((path.empty() ? std::string("(config)") : path) + ": " + message), path_(std::move(path)) {}

std::string_view to_string(RioBaud baud) { return kBaudNames[baud_index(baud)].name; }

std::string_view to_string(RioMode mode) { return mode == RioMode::normal ? "normal" : "complementary"; }

std::optional<RioBaud> parse_rio_baud(std::string_view text) {
    for (const BaudName& entry : kBaudNames) {
        if (entry.name == text) return entry.baud;
    }
    return std::nullopt;
}

std::optional<RioMode> parse_rio_mode(std::string_view text) {
    if (text == "normal") return RioMode::normal;
    if (text == "complementary") return RioMode::complementary;
    return std::nullopt;
}

std::string_view rack_size_label(int groups) {
    for (const RioScanTimeRow& row : kRioScanTimes) {
        if (row.groups == groups) return row.label;
    }
    throw std::invalid_argument("rack_size_label: a logical device has 2, 4, 6 or 8 groups");
}

std::optional<int> groups_for_rack_size(std::string_view label) {
    for (const RioScanTimeRow& row : kRioScanTimes) {
        if (row.label == label) return row.groups;
    }
    return std::nullopt;
}

std::string_view to_string(TsnoTable table) {
    switch (table) {
        case TsnoTable::without_m0_writes:
            return "T_SNO without M0 File Writes";
        case TsnoTable::with_m0_writes:
            return "T_SNo with M0 File Writes (No Block Transfers)";
        case TsnoTable::with_block_transfers:
            return "T_SNo-bt (Determining T_SNo-bt)";
    }
    return "";
}

Micros rio_scan_time(RioBaud baud, int groups) {
    for (const RioScanTimeRow& row : kRioScanTimes) {
        if (row.groups == groups) return row.by_baud[baud_index(baud)];
    }
    throw std::invalid_argument("rio_scan_time: a logical device has 2, 4, 6 or 8 groups");
}

TsnoCell t_sno_cell(TsnoTable table, RioMode mode, RioBaud baud, int logical_racks) {
    const TsnoRow& row = tsno_row(table, logical_racks);
    return mode == RioMode::normal ? row.normal : row.complementary[baud_index(baud)];
}

Micros t_sno_bt(RioMode mode, RioBaud baud, int logical_racks) {
    if (logical_racks < 1 || logical_racks > kRacks) {
        throw std::invalid_argument("t_sno_bt: logical rack count must be 1..4");
    }
    const TsnoBtRow& row = kTsnoBt[static_cast<std::size_t>(logical_racks - 1)];
    return mode == RioMode::normal ? row.normal : row.complementary[baud_index(baud)];
}

Micros t_ri(RioBaud baud, int words) {
    if (words < 0 || words > kMaxBtWords) throw std::invalid_argument("t_ri: a block transfer has 0..64 words");
    for (const TriRow& row : kTri) {
        if (row.baud == baud) return row.per_word * charged_words(words) + row.base;
    }
    throw std::invalid_argument("t_ri: unknown baud rate");
}

std::vector<RioLogicalDevice> split_into_logical_devices(RioBaud baud, const std::vector<RioDevice>& devices) {
    std::vector<RioLogicalDevice> logical;
    for (std::size_t i = 0; i < devices.size(); ++i) {
        const RioDevice& device = devices[i];
        int position = device.rack * kGroupsPerRack + device.group;
        const int end = position + device.groups;
        while (position < end) {
            const int rack = position / kGroupsPerRack;
            const int group = position % kGroupsPerRack;
            const int groups = std::min(end, (rack + 1) * kGroupsPerRack) - position;
            logical.push_back({i, rack, group, groups, device.complementary, rio_scan_time(baud, groups)});
            position += groups;
        }
    }
    return logical;
}

namespace {

// Validates `network` and returns its logical devices, which the overlap
// check needs and compute_rio() reuses.
std::vector<RioLogicalDevice> validated_logical_devices(const RioNetwork& network) {
    require_non_negative(network.processor_scan, "processor_scan_ms");
    require_non_negative(network.adapter_delay, "adapter_delay_ms");
    require_non_negative(network.input_delay, "input_delay_ms");
    require_non_negative(network.output_delay, "output_delay_ms");
    if (network.t_upd) require_non_negative(*network.t_upd, "t_upd_ms");
    if (network.t_upd && network.t_upd_gt_t_hold) {
        throw ConfigError("t_upd_ms", "give either t_upd_gt_t_hold or t_upd_ms, not both");
    }
    if (network.bt_times) {
        require_non_negative(network.bt_times->m0_write, "m0_write_ms");
        require_non_negative(network.bt_times->adapter_bt_delay, "adapter_bt_delay_ms");
    }
    if (network.devices.empty()) throw ConfigError("devices", "expected at least one device");
    for (std::size_t i = 0; i < network.devices.size(); ++i) validate_device(network, i);
    std::vector<RioLogicalDevice> logical = split_into_logical_devices(network.baud, network.devices);
    validate_overlaps(network.mode, logical);
    validate_block_transfers(network, logical);
    return logical;
}

}  // namespace

void validate_rio(const RioNetwork& network) { validated_logical_devices(network); }

RioResult compute_rio(const RioNetwork& network) {
    RioResult result;
    result.logical_devices = validated_logical_devices(network);
    add_split_notes(network, result.logical_devices, result.notes);

    // "The number of logical racks configured is determined by the number of
    // racks that contain configured devices"; in complementary mode a primary
    // rack and its complementary rack count once, which holds here because a
    // complementary device carries its primary's rack number.
    for (const RioLogicalDevice& d : result.logical_devices) {
        result.t_rio += d.t_rio;
        if (std::find(result.configured_racks.begin(), result.configured_racks.end(), d.rack) ==
            result.configured_racks.end()) {
            result.configured_racks.push_back(d.rack);
        }
    }
    std::sort(result.configured_racks.begin(), result.configured_racks.end());

    result.with_block_transfers = !network.block_transfers.empty();
    result.t_sno = select_t_sno(network, static_cast<int>(result.configured_racks.size()), result.with_block_transfers,
                                result.notes);
    result.t_sni = kRioScannerInputDelay;
    result.bt_racks = group_block_transfers(network);
    for (const RioRackBlockTransfers& rack : result.bt_racks) result.t_btx += rack.t_ri;

    // T_dm-nbt = 2T_ps + 2T_RIO + T_adp + T_SNO + T_SNI + T_id + T_od
    // T_dm-bt  = 2T_ps + 2T_RIO + 2T_btx + T_adp + T_SNO-bt + T_SNI + T_id + T_od
    result.t_dm = 2 * network.processor_scan + 2 * result.t_rio + 2 * result.t_btx + network.adapter_delay +
                  result.t_sno.value + result.t_sni + network.input_delay + network.output_delay;

    for (std::size_t i = 0; i < network.block_transfers.size(); ++i) {
        if (network.block_transfers[i].words == 0) {
            result.notes.push_back(bt_path(i) +
                                   " requests 0 words, which lets the module transfer up to 64; it is charged as 64.");
        }
    }
    if (result.with_block_transfers && network.bt_times) {
        result.bt = block_transfer_figures(network, result);
    } else if (result.with_block_transfers) {
        result.notes.push_back(
            "Block-transfer throughput (appendix A, \"Block Transfer Throughput\") needs "
            "m0_write_ms (T_M0) and adapter_bt_delay_ms (T_adp-bt); give both to compute it.");
    } else if (network.bt_times) {
        result.notes.push_back("m0_write_ms and adapter_bt_delay_ms are not used: there are no block transfers.");
    }
    return result;
}

std::string format_ms(Micros duration) {
    const bool negative = duration < 0;
    const Micros magnitude = negative ? -duration : duration;
    std::string fraction = std::to_string(magnitude % 1000);
    fraction.insert(0, 3 - fraction.size(), '0');
    while (fraction.size() > 1 && fraction.back() == '0') fraction.pop_back();
    return (negative ? "-" : "") + std::to_string(magnitude / 1000) + "." + fraction;
}

}  // namespace softslc::throughput
