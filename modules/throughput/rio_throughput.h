// RIO network throughput for the 1747-SN Series B scanner, as appendix A
// ("Specifications", "Calculating Throughput") of the 1747-SN Remote I/O
// Scanner user manual states it (seeds/000_6bdfccac32889807.txt).
//
// Design. The calculator is a pure function from a typed description of an
// RIO network (RioNetwork) to every figure the manual's formulas use
// (RioResult). Nothing here knows about JSON: throughput_json.{h,cpp} maps the
// config file onto these types and the result back. Every duration is an
// integer count of microseconds (Micros), because every figure in the
// manual's tables and formulas is a whole number of microseconds (2.75 ms,
// 0.075 ms per word); sums of them are therefore exact, and the same network
// always yields byte-identical output. The manual's tables live in
// rio_throughput.cpp as constant data with one row per row of the printed
// table; the lookup functions below are the only way to read them.
//
// Invariants. compute_rio() validates its input first and throws ConfigError
// (with the JSON-style path of the offending field, e.g. "devices[2]") for
// any configuration the scanner cannot run; after validation, every device
// lies inside racks 0..3, starts on an even group, and no two logical devices
// of the same image share a group. An adapter whose image crosses a logical
// rack boundary is split at that boundary into one logical device per rack
// it touches (manual chapter 4, "Creating More than One Logical Rack
// Device"): the scanner exchanges data per logical device, and T_RIO adds one
// table entry per logical device.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace softslc::throughput {

// A duration in whole microseconds. All of the manuals' figures are exact in
// this unit, so the calculators never round.
using Micros = std::int64_t;

// A configuration the calculators refuse. path() names the offending field as
// a JSON path into the config file ("devices[2].size", "drops[0].rails", or
// "" for the whole document), so a user can find it; what() is
// "path: message". It lives here, beside the first calculator, because both
// calculators and the JSON layer throw it and the module has no other shared
// header.
class ConfigError : public std::runtime_error {
public:
    ConfigError(std::string path, const std::string& message);
    const std::string& path() const noexcept { return path_; }

private:
    std::string path_;
};

// The three RIO baud rates the 1747-SN supports (manual table A.1). The
// enumerators index the baud columns of every table in rio_throughput.cpp.
enum class RioBaud { b57_6k = 0, b115_2k = 1, b230_4k = 2 };

// Normal or complementary I/O mode (manual chapter 1, "Complementary I/O").
// The mode selects the T_SNO table column.
enum class RioMode { normal, complementary };

// The manual's labels: "57.6K", "115.2K", "230.4K"; "normal", "complementary".
std::string_view to_string(RioBaud baud);
std::string_view to_string(RioMode mode);
std::optional<RioBaud> parse_rio_baud(std::string_view text);
std::optional<RioMode> parse_rio_mode(std::string_view text);

// The logical image sizes of the T_RIO table, as group counts: a quarter
// logical rack is two groups, a full logical rack eight (manual chapter 1,
// "Scanner I/O Image Concepts").
// rack_size_label() maps 2/4/6/8 to "1/4", "1/2", "3/4", "full";
// groups_for_rack_size() is its inverse.
std::string_view rack_size_label(int groups);
std::optional<int> groups_for_rack_size(std::string_view label);

// One adapter (physical device) as the G file configures it: a starting
// logical rack and even starting group, and an image of `groups` groups
// (2..32, even). A complementary device is given with the rack number of
// its primary (0..3), not the G file's 8..11.
struct RioDevice {
    int rack = 0;
    int group = 0;
    int groups = 8;
    bool complementary = false;
    std::string name;
};

// One block transfer (one BTR or BTW, i.e. one of the scanner's 32 BT
// buffers) to a device in logical rack `rack`, of `words` words. A word count
// of 0 is the instruction's "let the module choose" setting; the calculator
// charges it as the 64-word maximum.
struct RioBlockTransfer {
    int rack = 0;
    int words = 0;
    std::string name;
};

// The inputs of the "Block Transfer Throughput" formula that only the user
// can supply: T_M0 (the processor's M0 file write time, manual appendix B)
// and T_adp-bt (the adapter's block-transfer acknowledge time; one backplane
// scan for a 1747-ASB).
struct RioBtTimes {
    Micros m0_write = 0;
    Micros adapter_bt_delay = 0;
};

// Which T_SNO table applies when there are no block transfers: the manual
// prints one for programs that write the scanner's M0 file and one for
// programs that do not. With block transfers the T_SNo-bt table applies.
enum class TsnoTable { without_m0_writes, with_m0_writes, with_block_transfers };
std::string_view to_string(TsnoTable table);

// Everything the appendix A formulas take from the user. Times are the
// manual's T_ps, T_adp, T_id and T_od. How T_upd compares with T_hold may be
// given as a yes/no (t_upd_gt_t_hold) or as a time (t_upd) the calculator
// compares with the table's T_hold; with neither, the calculator takes the
// larger T_SNO (the T_upd <= T_hold column), which is always safe.
struct RioNetwork {
    RioBaud baud = RioBaud::b57_6k;
    RioMode mode = RioMode::normal;
    Micros processor_scan = 0;
    Micros adapter_delay = 0;
    Micros input_delay = 0;
    Micros output_delay = 0;
    bool m0_file_writes = false;
    std::optional<bool> t_upd_gt_t_hold;
    std::optional<Micros> t_upd;
    std::vector<RioDevice> devices;
    std::vector<RioBlockTransfer> block_transfers;
    std::optional<RioBtTimes> bt_times;
};

// One logical device: the part of adapter `device` (an index into
// RioNetwork::devices) that lies in one logical rack, and its T_RIO entry.
struct RioLogicalDevice {
    std::size_t device = 0;
    int rack = 0;
    int group = 0;
    int groups = 0;
    bool complementary = false;
    Micros t_rio = 0;
};

// The T_SNO (or T_SNo-bt) figure and the table cell it came from. t_hold and
// upd_gt_hold are empty for the T_SNo-bt table, which has no T_upd columns.
struct RioTsno {
    TsnoTable table = TsnoTable::without_m0_writes;
    int logical_racks = 0;
    std::optional<bool> upd_gt_hold;
    std::optional<Micros> t_hold;
    Micros value = 0;
};

// T_ri for one logical rack: the longest block transfer to the rack (one BT
// per logical rack per RIO scan, so only the longest counts) and the block
// transfers (indices into RioNetwork::block_transfers) aimed at it.
struct RioRackBlockTransfers {
    int rack = 0;
    int max_words = 0;
    std::vector<std::size_t> block_transfers;
    Micros t_ri = 0;
};

// Block-transfer throughput of one block transfer, and the T_btwait in it.
struct RioBtThroughput {
    std::size_t block_transfer = 0;
    int rack = 0;
    int words = 0;
    Micros t_btwait = 0;
    Micros t_bt = 0;
};

// The figures of the manual's "Block Transfer Throughput" section.
struct RioBtFigures {
    Micros m0_write = 0;
    Micros adapter_bt_delay = 0;
    std::vector<RioBtThroughput> per_block_transfer;
    Micros buffer_free = 0;
};

// Every figure of the appendix A calculation. t_dm is T_dm-bt when
// with_block_transfers, T_dm-nbt otherwise; t_btx is zero without block
// transfers. configured_racks lists the logical racks (0..3) that hold a
// device, the count the T_SNO tables are indexed by.
struct RioResult {
    std::vector<RioLogicalDevice> logical_devices;
    std::vector<int> configured_racks;
    Micros t_rio = 0;
    RioTsno t_sno;
    Micros t_sni = 0;
    std::vector<RioRackBlockTransfers> bt_racks;
    Micros t_btx = 0;
    bool with_block_transfers = false;
    Micros t_dm = 0;
    std::optional<RioBtFigures> bt;
    std::vector<std::string> notes;
};

// T_SNI, the scanner input delay: "5 ms (constant value for all formulas in
// this appendix)".
inline constexpr Micros kRioScannerInputDelay = 5000;

// The "RIO Scan Times for Adapters" table: the T_RIO entry for one logical
// device of `groups` groups (2, 4, 6 or 8) at `baud`. Throws
// std::invalid_argument for any other group count.
Micros rio_scan_time(RioBaud baud, int groups);

// One cell of a T_SNO table that has T_upd columns.
struct TsnoCell {
    Micros if_upd_le_hold = 0;
    Micros t_hold = 0;
    Micros if_upd_gt_hold = 0;
};

// The T_SNO tables without block transfers ("T_SNO without M0 File Writes",
// "T_SNo with M0 File Writes (No Block Transfers)"): the cell for
// `logical_racks` (1..4) configured racks. In normal mode every baud rate
// shares one column. Throws std::invalid_argument for the T_SNo-bt table or a
// rack count outside 1..4.
TsnoCell t_sno_cell(TsnoTable table, RioMode mode, RioBaud baud, int logical_racks);

// The "Determining T_SNo-bt" table: T_SNO with block transfers present.
// Throws std::invalid_argument for a rack count outside 1..4.
Micros t_sno_bt(RioMode mode, RioBaud baud, int logical_racks);

// The T_ri table: the RIO scan time increase for one logical rack whose
// longest block transfer is `words` words (0..64; 0 is charged as 64).
Micros t_ri(RioBaud baud, int words);

// Splits every device at logical rack boundaries, in device order and then
// rack order. Expects devices that validate_rio() accepts.
std::vector<RioLogicalDevice> split_into_logical_devices(RioBaud baud, const std::vector<RioDevice>& devices);

// Throws ConfigError for the first problem in `network`: a device outside the
// scanner image, an odd starting group, overlapping devices, a complementary
// device in normal mode, a block transfer to an empty rack, more than 32 block
// transfers, a negative time, or both T_upd inputs given.
void validate_rio(const RioNetwork& network);

// Validates `network` and computes every figure of appendix A.
RioResult compute_rio(const RioNetwork& network);

// Formats a duration as milliseconds with at least one decimal and no
// trailing zeros beyond it: 132000 -> "132.0", 2750 -> "2.75",
// 10448 -> "10.448". Both calculators' reports use it.
std::string format_ms(Micros duration);

}  // namespace softslc::throughput
