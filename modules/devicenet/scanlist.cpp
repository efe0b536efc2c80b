#include "modules/devicenet/scanlist.h"

#include <algorithm>
#include <charconv>
#include <set>

namespace softslc::devicenet {

using nlohmann::json;

std::string format_table_ref(const TableRef& r, bool input_side) {
  std::string s = r.area == TableRef::Area::MFile ? (input_side ? "M1:" : "M0:") : (input_side ? "I:" : "O:");
  return s + std::to_string(r.word) + "/" + std::to_string(r.bit);
}

std::optional<TableRef> parse_table_ref(std::string_view text, bool input_side) {
  TableRef r;
  const std::string_view m = input_side ? "M1:" : "M0:";
  const std::string_view d = input_side ? "I:" : "O:";
  if (text.starts_with(m)) {
    r.area = TableRef::Area::MFile;
    text.remove_prefix(m.size());
  } else if (text.starts_with(d)) {
    r.area = TableRef::Area::Discrete;
    text.remove_prefix(d.size());
  } else {
    return std::nullopt;
  }
  auto number = [](std::string_view s, int& out) {
    if (s.empty() || s.size() > 5) return false;
    auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    return ec == std::errc() && p == s.data() + s.size();
  };
  const auto slash = text.find('/');
  if (!number(text.substr(0, slash), r.word)) return std::nullopt;
  if (slash != std::string_view::npos && !number(text.substr(slash + 1), r.bit)) return std::nullopt;
  return r;
}

Nanoseconds default_epr(IoType t) {
  switch (t) {
    case IoType::Cos: return milliseconds(250);
    case IoType::Poll:
    case IoType::Strobe: return milliseconds(75);
    case IoType::Cyclic: return milliseconds(500);
  }
  return milliseconds(75);
}

bool ElectronicKey::matches(const Identity& id) const {
  if (vendor && *vendor != id.vendor) return false;
  if (device_type && *device_type != id.device_type) return false;
  if (product_code && *product_code != id.product_code) return false;
  if (major && *major != id.major) return false;
  if (minor && id.minor < *minor) return false;
  return true;
}

void validate_scanner_settings(const ScannerConfig& c) {
  if (c.node_address < 0 || c.node_address > 63)
    throw ConfigError("node", "the scanner's node address must be 0...63, got " + std::to_string(c.node_address));
  if (c.interscan_delay < milliseconds(1) || c.interscan_delay > milliseconds(9000))
    throw ConfigError("interscan_delay_ms", "the interscan delay must be 1...9000 ms");
  if (c.background_poll_ratio < 1 || c.background_poll_ratio > 65535)
    throw ConfigError("background_poll_ratio", "the background poll ratio must be 1...65535");
  if (c.autoscan_allocation < 1 || c.autoscan_allocation > 32)
    throw ConfigError("autoscan.allocation_bytes", "the AutoScan allocation size must be 1...32 bytes (p.104)");
}

namespace {

// Bits from the start of a table area, and the area's size in bits.
int table_bit(const TableRef& r) { return r.word * 16 + r.bit; }
int table_first_word(TableRef::Area a) { return a == TableRef::Area::Discrete ? 1 : 0; }
int table_end_word(TableRef::Area a) { return a == TableRef::Area::Discrete ? layout::kImageWords : layout::kDataWords; }

void check_segment(const ScanlistEntry& e, const MapSegment& s, bool input, const std::string& path,
                   std::vector<ScanlistIssue>& issues) {
  auto issue = [&](const std::string& key, const std::string& msg) {
    issues.push_back({e.node, child_path(path, key), msg});
  };
  const ConnectionConfig& c = e.conn(s.connection);
  if (!c.enabled) {
    issue(input ? "from" : "to", std::string("the entry has no ") + std::string(to_string(s.connection)) + " connection");
    return;
  }
  if (s.bits < 1) issue("bits", "a segment maps at least 1 bit");
  if (s.device_byte < 0 || s.device_bit < 0 || s.device_bit > 7) issue("bit", "device bit must be 0...7");
  const int size_bits = 8 * (input ? c.rx : c.tx);
  if (s.device_byte * 8 + s.device_bit + s.bits > size_bits)
    issue("bits", "the segment reaches past the " + std::to_string(input ? c.rx : c.tx) + "-byte " +
                      (input ? "rx" : "tx") + " data of the connection");
  if (!input && s.connection == IoType::Strobe && (s.bits != 1 || s.device_byte != 0 || s.device_bit != 0))
    issue("bits", "a strobe output is the node's single strobe bit (byte 0, bit 0, 1 bit)");
  const std::string key = input ? "to" : "from";
  if (s.table.bit < 0 || s.table.bit > 15) issue(key, "table bit must be 0...15");
  const int first = table_first_word(s.table.area) * 16;
  const int end = table_end_word(s.table.area) * 16;
  if (s.table.word < table_first_word(s.table.area) || table_bit(s.table) < first ||
      table_bit(s.table) + std::max(s.bits, 1) > end)
    issue(key, format_table_ref(s.table, input) + " with " + std::to_string(s.bits) + " bits is outside " +
                   (s.table.area == TableRef::Area::Discrete ? (input ? "I:1...31" : "O:1...31")
                                                             : (input ? "M1:0...149" : "M0:0...149")));
}

}  // namespace

std::vector<ScanlistIssue> validate_scanlist(const ScannerConfig& c) {
  std::vector<ScanlistIssue> issues;
  std::set<int> seen;
  // Input bits already claimed: (area, bit index) -> node; a second writer is illegal.
  std::set<std::pair<int, int>> claimed;
  for (std::size_t i = 0; i < c.scanlist.size(); ++i) {
    const ScanlistEntry& e = c.scanlist[i];
    const std::string path = element_path("scanlist", i);
    const std::size_t before = issues.size();
    auto issue = [&](const std::string& key, const std::string& msg) {
      issues.push_back({e.node, key.empty() ? path : child_path(path, key), msg});
    };
    if (e.node < 0 || e.node > 63) {
      issue("node", "node address must be 0...63");
      continue;
    }
    if (e.node == c.node_address) issue("node", "the scanner itself has this address");
    if (!seen.insert(e.node).second) issue("node", "node " + std::to_string(e.node) + " is listed twice");
    bool any = false;
    for (IoType t : kIoTypes) {
      const ConnectionConfig& cc = e.conn(t);
      if (!cc.enabled) continue;
      any = true;
      const std::string cp = child_path(path, to_string(t));
      const int max_rx = t == IoType::Strobe ? 8 : 255;
      const int max_tx = t == IoType::Strobe ? 1 : 255;
      if (cc.rx < 0 || cc.rx > max_rx) issues.push_back({e.node, child_path(cp, "rx"), "rx must be 0..." + std::to_string(max_rx)});
      if (cc.tx < 0 || cc.tx > max_tx) issues.push_back({e.node, child_path(cp, "tx"), "tx must be 0..." + std::to_string(max_tx)});
      if (cc.epr <= 0) issues.push_back({e.node, child_path(cp, "epr_ms"), "the expected packet rate must be positive"});
      if (cc.background && t != IoType::Poll)
        issues.push_back({e.node, child_path(cp, "background"), "only polled connections can be background polled"});
    }
    if (!any) issue("", "the entry has no I/O connection");
    if (e.conn(IoType::Cos).enabled && e.conn(IoType::Cyclic).enabled)
      issue("cyclic", "change of state and cyclic share one connection; choose one");
    for (std::size_t k = 0; k < e.inputs.size(); ++k)
      check_segment(e, e.inputs[k], true, child_path(path, element_path("inputs", k)), issues);
    for (std::size_t k = 0; k < e.outputs.size(); ++k)
      check_segment(e, e.outputs[k], false, child_path(path, element_path("outputs", k)), issues);
    if (issues.size() != before) continue;
    // Overlapping input bits: the second writer of any bit is illegal.
    for (std::size_t k = 0; k < e.inputs.size(); ++k) {
      const MapSegment& s = e.inputs[k];
      bool clash = false;
      for (int b = 0; b < s.bits && !clash; ++b)
        clash = claimed.count({static_cast<int>(s.table.area), table_bit(s.table) + b}) != 0;
      if (clash) {
        issues.push_back({e.node, child_path(path, element_path("inputs", k)),
                          "input bits overlap another mapping's bits"});
        break;
      }
    }
    if (issues.size() != before) continue;
    for (const MapSegment& s : e.inputs)
      for (int b = 0; b < s.bits; ++b) claimed.insert({static_cast<int>(s.table.area), table_bit(s.table) + b});
  }
  return issues;
}

// ---- JSON --------------------------------------------------------------------------------------

namespace {

MapSegment read_segment(const json& v, const std::string& path, bool input) {
  const ObjectReader r(v, path, {input ? "from" : "to", "byte", "bit", "bits", input ? "to" : "from"});
  MapSegment s;
  const std::string conn_key = input ? "from" : "to";
  const std::string name = r.choice(conn_key, {"strobe", "poll", "cos", "cyclic"});
  s.connection = *parse_io_type(name);
  s.device_byte = static_cast<int>(r.optional_integer("byte", 0, 254).value_or(0));
  s.device_bit = static_cast<int>(r.optional_integer("bit", 0, 7).value_or(0));
  s.bits = static_cast<int>(r.optional_integer("bits", 1, std::int64_t{255} * 8).value_or(8));
  const std::string table_key = input ? "to" : "from";
  const std::string text = r.string(table_key);
  const auto ref = parse_table_ref(text, input);
  if (!ref)
    throw ConfigError(r.path(table_key), std::string("expected a table position like ") +
                                             (input ? "\"M1:0/8\" or \"I:1/0\"" : "\"M0:0/0\" or \"O:1/0\"") +
                                             ", got \"" + text + "\"");
  if (ref->bit > 15) throw ConfigError(r.path(table_key), "bit must be 0...15");
  s.table = *ref;
  return s;
}

ScanlistEntry read_entry(const json& v, const std::string& path) {
  const ObjectReader r(v, path, {"node", "key", "strobe", "poll", "cos", "cyclic", "inputs", "outputs"});
  ScanlistEntry e;
  e.node = static_cast<int>(r.integer("node", 0, 63));
  if (const json* k = r.object("key")) {
    const ObjectReader kr(*k, r.path("key"), {"vendor", "device_type", "product_code", "major", "minor"});
    if (auto x = kr.optional_integer("vendor", 0, 65535)) e.key.vendor = static_cast<std::uint16_t>(*x);
    if (auto x = kr.optional_integer("device_type", 0, 65535)) e.key.device_type = static_cast<std::uint16_t>(*x);
    if (auto x = kr.optional_integer("product_code", 0, 65535)) e.key.product_code = static_cast<std::uint16_t>(*x);
    if (auto x = kr.optional_integer("major", 1, 127)) e.key.major = static_cast<std::uint8_t>(*x);
    if (auto x = kr.optional_integer("minor", 1, 255)) e.key.minor = static_cast<std::uint8_t>(*x);
  }
  for (IoType t : kIoTypes) {
    const json* c = r.object(to_string(t));
    if (c == nullptr) continue;
    const std::string rate_key = t == IoType::Cos ? "heartbeat_ms" : t == IoType::Cyclic ? "rate_ms" : "epr_ms";
    const ObjectReader cr(*c, r.path(to_string(t)),
                          t == IoType::Poll ? std::initializer_list<std::string_view>{"rx", "tx", "epr_ms", "background"}
                                            : std::initializer_list<std::string_view>{"rx", "tx", rate_key});
    ConnectionConfig& cc = e.conn(t);
    cc.enabled = true;
    cc.rx = static_cast<int>(cr.optional_integer("rx", 0, t == IoType::Strobe ? 8 : 255).value_or(0));
    cc.tx = static_cast<int>(cr.optional_integer("tx", 0, t == IoType::Strobe ? 1 : 255).value_or(0));
    cc.epr = milliseconds(cr.optional_integer(rate_key, 1, 65535).value_or(default_epr(t) / kNsPerMs));
    cc.background = t == IoType::Poll && cr.boolean("background", false);
  }
  r.array("inputs", [&](const json& s, const std::string& p) { e.inputs.push_back(read_segment(s, p, true)); });
  r.array("outputs", [&](const json& s, const std::string& p) { e.outputs.push_back(read_segment(s, p, false)); });
  return e;
}

}  // namespace

ScannerConfig parse_scanner_config(const json& doc, const std::string& path) {
  const ObjectReader r(doc, path, {"node", "baud", "interscan_delay_ms", "background_poll_ratio", "autoscan", "scanlist"});
  ScannerConfig c;
  c.node_address = static_cast<int>(r.integer("node", 0, 63));
  c.baud = *parse_baud(r.choice("baud", {"125K", "250K", "500K"}, "125K"));
  c.interscan_delay = milliseconds(r.optional_integer("interscan_delay_ms", 1, 9000).value_or(10));
  c.background_poll_ratio = static_cast<int>(r.optional_integer("background_poll_ratio", 1, 65535).value_or(1));
  if (const json* a = r.object("autoscan")) {
    const ObjectReader ar(*a, r.path("autoscan"), {"enabled", "allocation_bytes"});
    c.autoscan = ar.boolean("enabled", false);
    c.autoscan_allocation = static_cast<int>(ar.optional_integer("allocation_bytes", 1, 32).value_or(4));
  }
  r.array("scanlist", [&](const json& v, const std::string& p) { c.scanlist.push_back(read_entry(v, p)); });
  return c;
}

json scanner_config_to_json(const ScannerConfig& c) {
  json out;
  out["node"] = c.node_address;
  out["baud"] = std::string(to_string(c.baud));
  out["interscan_delay_ms"] = c.interscan_delay / kNsPerMs;
  out["background_poll_ratio"] = c.background_poll_ratio;
  out["autoscan"] = {{"enabled", c.autoscan}, {"allocation_bytes", c.autoscan_allocation}};
  json list = json::array();
  for (const ScanlistEntry& e : c.scanlist) {
    json j;
    j["node"] = e.node;
    json key = json::object();
    if (e.key.vendor) key["vendor"] = *e.key.vendor;
    if (e.key.device_type) key["device_type"] = *e.key.device_type;
    if (e.key.product_code) key["product_code"] = *e.key.product_code;
    if (e.key.major) key["major"] = *e.key.major;
    if (e.key.minor) key["minor"] = *e.key.minor;
    if (!key.empty()) j["key"] = key;
    for (IoType t : kIoTypes) {
      const ConnectionConfig& cc = e.conn(t);
      if (!cc.enabled) continue;
      json cj = {{"rx", cc.rx}, {"tx", cc.tx}};
      cj[t == IoType::Cos ? "heartbeat_ms" : t == IoType::Cyclic ? "rate_ms" : "epr_ms"] = cc.epr / kNsPerMs;
      if (t == IoType::Poll) cj["background"] = cc.background;
      j[std::string(to_string(t))] = cj;
    }
    auto segs = [](const std::vector<MapSegment>& v, bool input) {
      json a = json::array();
      for (const MapSegment& s : v)
        a.push_back({{input ? "from" : "to", std::string(to_string(s.connection))},
                     {"byte", s.device_byte},
                     {"bit", s.device_bit},
                     {"bits", s.bits},
                     {input ? "to" : "from", format_table_ref(s.table, input)}});
      return a;
    };
    j["inputs"] = segs(e.inputs, true);
    j["outputs"] = segs(e.outputs, false);
    list.push_back(j);
  }
  out["scanlist"] = list;
  return out;
}

}  // namespace softslc::devicenet
