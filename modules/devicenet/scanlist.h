// Scanner configuration (SCT) and scanlist (SLT): what RSNetWorx downloads to a 1747-SDN.
//
// The scanner configuration table holds the module's own settings: node address, data rate,
// interscan delay and background poll ratio (chapter 1, "Data Table Information", p.20), plus the
// AutoScan settings of chapter 9. The scanlist holds one entry per slave: its node address, the
// electronic key to check, the I/O connections to open (strobe, poll, change of state, cyclic)
// with their receive (rx, device to scanner) and transmit (tx, scanner to device) sizes in bytes,
// and where each device's data lives in the scanner's tables.
//
// Mapping is bit-granular, as RSNetWorx's data table map is: a MapSegment moves `bits` bits
// starting at bit `device_bit` of byte `device_byte` of one connection's data to (inputs) or from
// (outputs) a table position: the discrete image (I:s.1...31 / O:s.1...31) or the M file data
// area (M1/M0 words 0...149). The manual's example (chapter 4, p.58-61) is three segments:
//   RediSTATION (node 7, poll rx 1, tx 1): poll byte 0 bits 0-7 -> M1:0/0 ; M0:0/0 -> poll byte 0
//   photoeye    (node 9, strobe rx 1):     strobe byte 0 bits 0-7 -> M1:0/8
// Table positions are written "M1:w/b", "I:w/b" (inputs) and "M0:w/b", "O:w/b" (outputs), slot-free.
//
// A strobed device's output is its bit in the 8-byte bit-strobe message (appendix A, p.118), so a
// strobe connection's tx is 0 or 1 (bit) and a strobe output segment is exactly one bit.
//
// Validation has two levels. Scanner-level settings the module cannot run with at all (address,
// interscan delay, ratio, allocation size) throw ConfigError. Problems of one scanlist entry
// (table positions out of range, sizes, overlapping inputs, a node listed twice) are ScanlistIssues:
// the scanner skips that entry and shows code 71 "Illegal data in scanlist table" with its node,
// as the real module does; a loader may also choose to refuse them outright.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "modules/devicenet/bus_timing.h"
#include "modules/devicenet/device_model.h"
#include "modules/devicenet/json_reader.h"
#include "modules/devicenet/tables.h"

namespace softslc::devicenet {

// Where a mapped bit range lives in the scanner's tables.
struct TableRef {
  enum class Area : std::uint8_t { Discrete, MFile };
  Area area = Area::MFile;
  int word = 0;  // Discrete: image word 1...31; MFile: word 0...149
  int bit = 0;   // 0...15
  bool operator==(const TableRef&) const = default;
};
// "M1:0/8", "I:1/0" (input side); "M0:0/0", "O:1/0" (output side).
std::string format_table_ref(const TableRef& r, bool input_side);
// Parses "M1:w", "M1:w/b", "I:w/b" (input side) or "M0:..."/"O:..." (output side); nullopt if the
// text is not of that shape (ranges are checked by validate_scanlist).
std::optional<TableRef> parse_table_ref(std::string_view text, bool input_side);

struct MapSegment {
  IoType connection = IoType::Poll;
  int device_byte = 0;
  int device_bit = 0;
  TableRef table;
  int bits = 8;
};

struct ConnectionConfig {
  bool enabled = false;
  int rx = 0;  // bytes the device produces
  int tx = 0;  // bytes the device consumes (strobe: 0, or 1 = the node's strobe bit)
  // Expected packet rate: poll/strobe connection timeout base, the COS heartbeat, the cyclic rate.
  // The connection times out after 4 x EPR without a packet (CIP inactivity watchdog).
  Nanoseconds epr = 0;
  bool background = false;  // poll only: polled once every background_poll_ratio scans
};

// Default expected packet rates: the EPR column of chapter 9's AutoScan table (p.110).
Nanoseconds default_epr(IoType t);

struct ElectronicKey {
  std::optional<std::uint16_t> vendor, device_type, product_code;
  std::optional<std::uint8_t> major;
  std::optional<std::uint8_t> minor;  // "minor revision or higher"
  bool matches(const Identity& id) const;
};

struct ScanlistEntry {
  int node = 0;
  ElectronicKey key;
  std::array<ConnectionConfig, 4> connections{};  // indexed by IoType
  std::vector<MapSegment> inputs;
  std::vector<MapSegment> outputs;

  ConnectionConfig& conn(IoType t) { return connections[static_cast<std::size_t>(t)]; }
  const ConnectionConfig& conn(IoType t) const { return connections[static_cast<std::size_t>(t)]; }
};

struct ScannerConfig {
  int node_address = 63;                       // factory default: node 63, 125K, no scanlist (p.140)
  Baud baud = Baud::k125;
  Nanoseconds interscan_delay = 10 * kNsPerMs; // AutoScan's "default setting of ISD from 10 ms" (p.113)
  int background_poll_ratio = 1;
  bool autoscan = false;                       // factory default: disabled (p.112)
  int autoscan_allocation = 4;                 // bytes per node, 1...32, default 4 (p.104, p.111)
  std::vector<ScanlistEntry> scanlist;
};

// Throws ConfigError for scanner-level settings the module cannot run with.
void validate_scanner_settings(const ScannerConfig& c);

struct ScanlistIssue {
  int node = 0;
  std::string path;  // "scanlist[1].inputs[0].to"
  std::string message;
};
// Every problem of every entry, in scanlist order. Entries named here are not scanned.
std::vector<ScanlistIssue> validate_scanlist(const ScannerConfig& c);

// The scanner configuration as JSON (docs/1747-sdn.md, "Scanner configuration"): structure, types
// and ranges are checked here with pathed errors; table-level problems are left to
// validate_scanlist (code 71 at run time).
ScannerConfig parse_scanner_config(const nlohmann::json& doc, const std::string& path = "");
nlohmann::json scanner_config_to_json(const ScannerConfig& c);

}  // namespace softslc::devicenet
