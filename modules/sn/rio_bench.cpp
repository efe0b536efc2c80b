#include "modules/sn/rio_bench.h"

#include <algorithm>

namespace softslc {

namespace {

int leading_number(std::string_view text) {
  int n = 0;
  for (char c : text) {
    if (c < '0' || c > '9') break;
    n = n * 10 + (c - '0');
  }
  return n;
}

std::optional<int> groups_of_size(const std::string& s) {
  if (s == "1/4") return 2;
  if (s == "1/2") return 4;
  if (s == "3/4") return 6;
  if (s == "full") return 8;
  return std::nullopt;
}

void read_bt_children(const BenchNode& node, RioModuleSpec& m, DiagnosticList& diags) {
  for (const auto& c : node.children) {
    BenchReader r(c, diags);
    if (c.kind == "read") {
      RioBtStep s;
      r.require("at", "TIME");
      r.require("data", "V1,V2,...");
      if (auto t = r.duration("at")) s.at = *t;
      if (auto d = r.integers("data", -32768, 65535))
        for (auto v : *d) s.data.push_back(static_cast<std::int16_t>(v));
      r.finish();
      if (!m.steps.empty() && s.at <= m.steps.back().at)
        r.error("read steps must be in increasing order of at=");
      m.steps.push_back(std::move(s));
    } else if (c.kind == "ramp") {
      RioBtRamp p;
      r.require("word", "N");
      if (auto w = r.integer("word", 0, 63)) p.word = static_cast<int>(*w);
      if (auto v = r.integer("from", -32768, 65535)) p.from = *v;
      if (auto v = r.integer("step", -32768, 32767)) p.step = *v;
      if (auto t = r.duration("every")) {
        if (*t <= 0) r.error_at("every", "every= must be a positive time");
        else p.every = *t;
      }
      r.finish();
      m.ramps.push_back(p);
    } else {
      r.error("a block-transfer module's children are 'read at=T data=...' and 'ramp word=N from=V step=S every=T'");
    }
  }
}

std::optional<RioModuleSpec> read_module(const BenchNode& node, const RioAdapterSpec& a, DiagnosticList& diags) {
  BenchReader r(node, diags);
  RioModuleSpec m;
  m.name = node.name;
  m.pos = node.pos;
  m.rack = a.rack;
  if (node.kind != "module") {
    r.error("an adapter holds 'module' nodes");
    return std::nullopt;
  }
  if (auto c = r.text("catalog")) m.catalog = *c;
  auto kind = r.choice("kind", {"input", "output", "bt"});
  std::optional<ModuleCatalogEntry> entry = m.catalog.empty() ? std::nullopt : find_module_catalog(m.catalog);
  if (kind) {
    m.kind = *kind == "input" ? RioModuleKind::Input : *kind == "output" ? RioModuleKind::Output : RioModuleKind::BlockTransfer;
  } else if (entry && !entry->specialty && (entry->default_scan_in > 0) != (entry->default_scan_out > 0)) {
    m.kind = entry->default_scan_in > 0 ? RioModuleKind::Input : RioModuleKind::Output;
  } else if (!r.failed()) {
    r.error("say what the module is with kind=input, kind=output or kind=bt (softslc does not know catalog '" +
            m.catalog + "')");
    return std::nullopt;
  }
  if (entry && !kind) m.points = std::max(8, leading_number(entry->description));
  if (auto p = r.integer("points", 8, 32)) {
    if (*p != 8 && *p != 16 && *p != 32) r.error_at("points", "points= must be 8, 16 or 32");
    else m.points = static_cast<int>(*p);
  }
  if (auto v = r.integer("rack", 0, 11)) m.rack = static_cast<int>(*v);
  r.require("group", "0-7");
  if (auto v = r.integer("group", 0, 7)) m.group = static_cast<int>(*v);
  if (auto v = r.integer("slot", 0, 1)) m.slot = static_cast<int>(*v);
  if (auto d = r.duration("input_delay")) m.input_delay = *d;
  if (auto d = r.duration("output_delay")) m.output_delay = *d;
  if (m.kind == RioModuleKind::BlockTransfer) {
    if (auto v = r.integer("length", 1, 64)) m.length = static_cast<int>(*v);
    m.write_length = m.length;
    if (auto v = r.integer("write_length", 1, 64)) m.write_length = static_cast<int>(*v);
    if (auto d = r.duration("response_delay")) m.response_delay = *d;
    if (auto d = r.integers("data", -32768, 65535))
      for (auto v : *d) m.data.push_back(static_cast<std::int16_t>(v));
    if (auto s = r.choice("state", {"responding", "not_responding", "failing"})) {
      m.responding = *s != "not_responding";
      m.failing = *s == "failing";
    }
    read_bt_children(node, m, diags);
  } else if (!node.children.empty()) {
    r.error("a discrete module has no child nodes");
  }
  r.finish();
  // The module must sit inside its adapter's image.
  const bool comp_rack = m.rack >= 8;
  if (comp_rack != a.complementary) {
    r.error_at("rack", "rack " + std::to_string(m.rack) + " is not in the " +
                           (a.complementary ? "complementary" : "primary") + " chassis of adapter " + a.name);
    return std::nullopt;
  }
  const int first = (m.rack % 8) * 8 + m.group;
  const int words = m.kind != RioModuleKind::BlockTransfer && m.points == 32 ? 2 : 1;
  if (first < a.first_word() || first + words > a.first_word() + a.groups) {
    r.error("rack " + std::to_string(m.rack) + " group " + std::to_string(m.group) + " is outside adapter " + a.name +
            "'s image (rack " + std::to_string(a.rack) + " group " + std::to_string(a.group) + ", " +
            std::to_string(a.groups) + " groups)");
    return std::nullopt;
  }
  if (m.points == 8 && m.kind != RioModuleKind::BlockTransfer) {
    // An 8-point module uses the byte of its slot.
  } else if (m.kind != RioModuleKind::BlockTransfer && m.slot != 0) {
    r.error_at("slot", "only 8-point modules and block-transfer modules use slot=1 (the high byte of the group)");
  }
  if (r.failed()) return std::nullopt;
  return m;
}

// The bits of image word `w` a discrete module uses.
std::uint16_t module_mask(const RioModuleSpec& m, int w) {
  const int first = (m.rack % 8) * 8 + m.group;
  if (m.kind == RioModuleKind::BlockTransfer) return 0;
  if (m.points == 8) return w == first ? static_cast<std::uint16_t>(m.slot ? 0xFF00 : 0x00FF) : 0;
  if (m.points == 16) return w == first ? 0xFFFF : 0;
  return (w == first || w == first + 1) ? 0xFFFF : 0;
}

}  // namespace

std::shared_ptr<const RioScannerBench> interpret_rio_bench(const BenchNode& node, const RioGFile* g,
                                                           DiagnosticList& diags) {
  auto bench = std::make_shared<RioScannerBench>();
  bench->name = node.name;
  {
    BenchReader r(node, diags);
    r.skip("slot");
    if (auto d = r.flag("duplicate_node")) bench->duplicate_node = *d;
    r.finish();
  }
  for (const auto& an : node.children) {
    BenchReader r(an, diags);
    if (an.kind != "adapter") {
      r.error("a scanner's children are 'adapter' nodes (the devices on its RIO link)");
      continue;
    }
    RioAdapterSpec a;
    a.name = an.name;
    a.pos = an.pos;
    if (a.name.empty()) r.error("an adapter needs a name (tests reach devices by name): adapter NAME rack=...");
    if (auto c = r.text("catalog")) a.catalog = *c;
    r.require("rack", "0-3 (8-11 for a complementary chassis)");
    r.require("group", "0, 2, 4 or 6");
    if (auto v = r.integer("rack", 0, 11)) {
      if (*v > 3 && *v < 8) r.error_at("rack", "rack " + std::to_string(*v) + ": the scanner has logical racks 0-3, and 8-11 for complementary chassis");
      a.rack = static_cast<int>(*v);
      a.complementary = a.rack >= 8;
    }
    if (auto v = r.integer("group", 0, 7)) {
      if (*v % 2) r.error_at("group", "a device starts at an even logical group (0, 2, 4 or 6)");
      a.group = static_cast<int>(*v);
    }
    auto size = r.text("size");
    auto groups = r.integer("groups", 2, 32);
    if (size && groups) r.error("give size= or groups=, not both");
    if (size) {
      if (auto n = groups_of_size(*size)) a.groups = *n;
      else r.error_at("size", "size=" + *size + ": expected 1/4, 1/2, 3/4 or full (or groups=N for larger devices)");
    } else if (groups) {
      if (*groups % 2) r.error_at("groups", "an image is an even number of groups (2 = 1/4 logical rack)");
      a.groups = static_cast<int>(*groups);
    } else {
      r.require("size", "1/4, 1/2, 3/4 or full");
    }
    if (auto v = r.choice("chassis", {"normal", "primary", "complementary"})) {
      a.primary_switch = *v == "primary";
      if ((*v == "complementary") != a.complementary)
        r.error_at("chassis", "a complementary chassis has rack 8-11, a primary or normal one rack 0-3");
    }
    if (auto v = r.flag("hold_last_state")) a.hold_last_state = *v;
    if (auto v = r.duration("backplane_scan")) a.backplane_scan = *v;
    a.bt_delay = a.backplane_scan;
    if (auto v = r.duration("bt_delay")) a.bt_delay = *v;
    if (auto v = r.duration("comm_timeout")) a.comm_timeout = *v;
    if (auto v = r.choice("state", {"online", "offline"})) a.online = *v == "online";
    if (auto v = r.integer("noisy", 0, 1000000)) a.noisy = static_cast<int>(*v);
    r.finish();
    if ((a.rack % 8) * 8 + a.group + a.groups > 32)
      r.error("the image runs past logical rack 3 (" + std::to_string(a.groups) + " groups from rack " +
              std::to_string(a.rack) + " group " + std::to_string(a.group) + ")");
    for (const auto& mn : an.children)
      if (auto m = read_module(mn, a, diags)) a.modules.push_back(std::move(*m));
    // Two modules of the same direction must not share image bits in one chassis. Each module is
    // reported once, against the first module it clashes with: a pair each made n copies of one
    // module line n^2/2 errors (10,000 copies: 9.8 GB, found by tools/mutate.py).
    for (std::size_t i = 0; i < a.modules.size(); ++i)
      for (std::size_t j = 0; j < i; ++j) {
        const auto& x = a.modules[i];
        const auto& y = a.modules[j];
        bool clash = false;
        if (x.kind == RioModuleKind::BlockTransfer || y.kind == RioModuleKind::BlockTransfer) {
          clash = x.kind == y.kind && x.rack == y.rack && x.group == y.group && x.slot == y.slot;
        } else if (x.kind == y.kind) {
          for (int w = 0; w < 32; ++w) clash = clash || (module_mask(x, w) & module_mask(y, w));
        }
        if (clash) {
          diags.error(x.pos.line, x.pos.column,
                      "module " + x.name + " uses the same image location as module " + y.name + " (line " +
                          std::to_string(y.pos.line) + ")");
          break;
        }
      }
    if (g && !r.failed()) {
      bool found = false;
      for (const auto& d : g->devices)
        found = found || (d.complementary == a.complementary && d.rack == a.rack % 8 && d.group == a.group);
      if (!found)
        diags.warning(a.pos.line, a.pos.column,
                      "adapter " + a.name + " (rack " + std::to_string(a.rack) + " group " + std::to_string(a.group) +
                          ") is not a device of the scanner's G file; the scanner never scans it");
    }
    bench->adapters.push_back(std::move(a));
  }
  // Complementary I/O (chapter 1): input modules of a primary and a complementary chassis must
  // never share an image location, and the complementary group opposite a block-transfer module
  // must be empty.
  for (const auto& p : bench->adapters) {
    if (p.complementary) continue;
    for (const auto& c : bench->adapters) {
      if (!c.complementary) continue;
      for (const auto& pm : p.modules)
        for (const auto& cm : c.modules) {
          const int pw = (pm.rack % 8) * 8 + pm.group, cw = (cm.rack % 8) * 8 + cm.group;
          if (pm.kind == RioModuleKind::BlockTransfer && pw == cw)
            diags.error(cm.pos.line, cm.pos.column,
                        "module " + cm.name + " is opposite block-transfer module " + pm.name +
                            "; the complementary I/O group opposite a block-transfer module must be empty (1747-SN "
                            "ch. 1, \"Summary for Placing Modules Used In Complementary I/O\")");
          if (pm.kind == RioModuleKind::Input && cm.kind == RioModuleKind::Input) {
            bool clash = false;
            for (int w = 0; w < 32; ++w) clash = clash || (module_mask(pm, w) & module_mask(cm, w));
            if (clash)
              diags.error(cm.pos.line, cm.pos.column,
                          "input module " + cm.name + " shares its image location with input module " + pm.name +
                              " of the primary chassis (1747-SN ch. 1: \"input and specialty combination I/O modules "
                              "must never share the same image location\")");
          }
        }
    }
  }
  return bench;
}

}  // namespace softslc
