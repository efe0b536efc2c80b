#include "modules/sdn/sdn_bench.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <map>

#include "parser/loader.h"

namespace softslc {

namespace {

using nlohmann::json;
using devicenet::ConfigError;

// The bench spells the configuration JSON's keys as attributes: integers become numbers, true/false
// booleans, anything else a string. The JSON reader then checks types and ranges.
json attribute_json(const std::string& value) {
  if (value == "true") return true;
  if (value == "false") return false;
  NumberValue v;
  if (parse_number_text(value, v) && !v.is_float) return v.integer;
  return value;
}

// Builds the configuration JSON and remembers where in the bench each JSON path was written, so a
// ConfigError lands on its own line.
class ConfigBuilder {
 public:
  json doc = json::object();
  std::map<std::string, SourcePos> where;

  void attributes(const BenchNode& n, json& into, const std::string& path, const std::vector<std::string>& skip) {
    for (const auto& a : n.attributes) {
      if (std::find(skip.begin(), skip.end(), a.key) != skip.end()) continue;
      into[a.key] = attribute_json(a.value);
      where[devicenet::child_path(path, a.key)] = a.value_pos;
    }
  }

  SourcePos position(std::string path, SourcePos fallback) const {
    while (true) {
      if (auto it = where.find(path); it != where.end()) return it->second;
      const auto cut = path.find_last_of(".[");
      if (cut == std::string::npos) return fallback;
      path.resize(cut);
    }
  }
};

bool is_connection(std::string_view kind) {
  return kind == "strobe" || kind == "poll" || kind == "cos" || kind == "cyclic";
}

}  // namespace

std::shared_ptr<const SdnBench> interpret_sdn_bench(const BenchNode& node, DiagnosticList& diags,
                                                    const std::string& bench_path) {
  auto bench = std::make_shared<SdnBench>();
  bench->name = node.name;
  ConfigBuilder b;
  b.where[""] = node.pos;
  b.attributes(node, b.doc, "", {"slot", "network_baud"});
  if (const BenchAttribute* a = node.find("network_baud")) {
    if (auto baud = devicenet::parse_baud(a->value)) bench->network_baud = *baud;
    else diags.error(a->value_pos.line, a->value_pos.column, "network_baud=" + a->value + ": expected 125K, 250K or 500K");
  }
  json scanlist = json::array();
  for (const auto& c : node.children) {
    if (c.kind == "autoscan") {
      json as = json::object();
      b.where["autoscan"] = c.pos;
      b.attributes(c, as, "autoscan", {});
      b.doc["autoscan"] = as;
      continue;
    }
    if (c.kind != "node") {
      diags.error(c.pos.line, c.pos.column,
                  "a devicenet network's children are 'node NAME address=N [model=...]' and 'autoscan' ('" + c.kind +
                      "' is neither)");
      continue;
    }
    BenchReader r(c, diags);
    if (c.name.empty()) r.error("a node needs a name (tests reach devices by name): node NAME address=N");
    r.require("address", "0-63");
    const auto address = r.integer("address", 0, 63);
    const auto model = r.text("model");
    const auto description = r.text("description");
    r.finish();
    if (model && description) r.error("give model= (a built-in device) or description= (a JSON file), not both");
    if (!address) continue;
    if (!c.name.empty()) bench->nodes.push_back({c.name, static_cast<int>(*address)});
    if (model) {
      try {
        bench->devices.push_back({c.name, static_cast<int>(*address), devicenet::builtin_device_model(*model)});
      } catch (const std::exception&) {
        std::string names;
        for (const auto& n : devicenet::builtin_device_names()) names += (names.empty() ? "" : ", ") + n;
        r.error_at("model", "model=" + *model + ": no such built-in DeviceNet device (" + names + ")");
      }
    }
    if (description && !model) {
      // A device description (docs/1747-sdn.md, "Device descriptions"), beside the bench file.
      const std::filesystem::path file = std::filesystem::path(bench_path).parent_path() / *description;
      std::ifstream in(file, std::ios::binary);
      if (!in.is_open()) {
        r.error_at("description", "cannot read device description " + file.string());
      } else {
        std::ostringstream text;
        text << in.rdbuf();
        try {
          bench->devices.push_back(
              {c.name, static_cast<int>(*address), devicenet::parse_device_model_text(text.str(), file.string())});
        } catch (const ConfigError& e) {
          // JSON syntax errors name the file already; structural ones give their JSON path only.
          std::string m = e.what();
          if (m.rfind(file.string(), 0) != 0) m = file.string() + ": " + m;
          r.error_at("description", m);
        }
      }
    }
    // The scanlist entry, if the node has one.
    json entry = json::object();
    const std::string path = devicenet::element_path("scanlist", scanlist.size());
    bool listed = false;
    entry["node"] = *address;
    b.where[path] = c.pos;
    std::map<std::string, int> counts;
    for (const auto& k : c.children) {
      if (is_connection(k.kind) || k.kind == "key") {
        json obj = json::object();
        const std::string p = devicenet::child_path(path, k.kind);
        b.where[p] = k.pos;
        b.attributes(k, obj, p, {});
        entry[k.kind] = obj;
        listed = true;
      } else if (k.kind == "input" || k.kind == "output") {
        const std::string list = k.kind + "s";
        json obj = json::object();
        const std::string p = devicenet::element_path(devicenet::child_path(path, list), counts[list]++);
        b.where[p] = k.pos;
        b.attributes(k, obj, p, {});
        entry[list].push_back(obj);
        listed = true;
      } else {
        diags.error(k.pos.line, k.pos.column,
                    "a node's children are its scanlist entry: strobe, poll, cos, cyclic, key, input, output ('" +
                        k.kind + "' is none of them)");
      }
    }
    if (listed) scanlist.push_back(std::move(entry));
  }
  b.doc["scanlist"] = std::move(scanlist);
  try {
    bench->config = devicenet::parse_scanner_config(b.doc);
    devicenet::validate_scanner_settings(bench->config);
    if (!node.find("network_baud")) bench->network_baud = bench->config.baud;
    for (const auto& issue : devicenet::validate_scanlist(bench->config)) {
      const SourcePos p = b.position(issue.path, node.pos);
      diags.warning(p.line, p.column,
                    "node " + std::to_string(issue.node) + ": " + issue.message +
                        "; the scanner does not scan this entry and shows code 71 (1747-SDN ch. 7)");
    }
  } catch (const ConfigError& e) {
    const SourcePos p = b.position(e.path(), node.pos);
    diags.error(p.line, p.column, std::string(e.what()));
  }
  // Two devices at one address would be one node answering twice; the cable has one per address.
  std::map<int, std::string> taken;
  for (const auto& c : node.children) {
    if (c.kind != "node") continue;
    const BenchAttribute* a = c.find("address");
    const BenchAttribute* m = c.find("model") ? c.find("model") : c.find("description");
    NumberValue v;
    if (!a || !m || !parse_number_text(a->value, v) || v.is_float) continue;
    const int addr = static_cast<int>(v.integer);
    if (addr == bench->config.node_address)
      diags.error(a->value_pos.line, a->value_pos.column,
                  "node " + c.name + " has the scanner's own address " + std::to_string(addr) +
                      " (use 'device NET duplicate N' to test a duplicate address)");
    else if (auto [it, fresh] = taken.emplace(addr, c.name); !fresh)
      diags.error(a->value_pos.line, a->value_pos.column,
                  "address " + std::to_string(addr) + " already holds device " + it->second);
  }
  return bench;
}

}  // namespace softslc
