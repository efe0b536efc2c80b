// The `automax` bench node: the slave drops on a master's Remote I/O network
// (docs/bench-format.md, "AutoMax"; docs/automax.md).
#include <algorithm>

#include "modules/automax/automax_network.h"

namespace softslc {

namespace {

struct DropKindInfo {
  const char* bench_kind;
  AutomaxDropKind kind;
};
constexpr DropKindInfo kDropKinds[] = {
    {"multibus", AutomaxDropKind::Multibus},       {"shark", AutomaxDropKind::Shark},
    {"head_57c328", AutomaxDropKind::Head57C328}, {"head_57c330", AutomaxDropKind::Head57C330},
    {"drive_head", AutomaxDropKind::DriveHead},
};

void read_modules(const BenchNode& node, AutomaxDropSpec& drop, DiagnosticList& diags) {
  const bool shark = drop.kind == AutomaxDropKind::Shark;
  std::vector<int> used;
  for (const auto& mn : node.children) {
    BenchReader r(mn, diags);
    if (mn.kind != "module") {
      r.error("a " + node.kind + " drop's children are 'module' nodes (the modules in its rack)");
      continue;
    }
    AutomaxModuleSpec m;
    m.name = mn.name;
    // Multibus: up to 15 modules (section 4.4), slots 0-15 of the image area. Shark: up to 10
    // modules in remote slots 1-10 (figure 4.2), slot 0 is the interface's configuration word.
    r.require("slot", shark ? "1-10" : "0-15");
    if (auto v = r.integer("slot", shark ? 1 : 0, shark ? 10 : kAutomaxSlots - 1)) {
      m.slot = static_cast<int>(*v);
      if (std::find(used.begin(), used.end(), m.slot) != used.end()) r.error_at("slot", "slot " + std::to_string(m.slot) + " holds two modules");
      used.push_back(m.slot);
    }
    const int max_io = shark ? 8 : kAutomaxSlotRegisters;
    if (auto v = r.integer("inputs", 0, max_io)) m.inputs = static_cast<int>(*v);
    if (auto v = r.integer("outputs", 0, max_io)) m.outputs = static_cast<int>(*v);
    if (!shark && m.inputs + m.outputs > kAutomaxSlotRegisters)
      r.error_at("outputs", "a module has at most " + std::to_string(kAutomaxSlotRegisters) + " registers");
    if (shark) {
      r.require("type", "digital or analog");
      if (auto t = r.choice("type", {"digital", "analog"})) m.digital = *t == "digital";
      if (drop.all_digital_shark() && !m.digital)
        r.error_at("type", "drop " + std::to_string(drop.number) + " (9-F) is an all-digital Shark rack (section 4.5)");
    }
    r.finish();
    drop.modules.push_back(std::move(m));
  }
  if (drop.modules.size() > (shark ? 10u : 15u))
    diags.error(node.pos.line, node.pos.column,
                node.label() + ": a " + (shark ? "Shark rack holds up to 10" : "Multibus rack holds up to 15") +
                    " modules (section 4.4)");
}

}  // namespace

std::shared_ptr<const AutomaxBench> interpret_automax_bench(const BenchNode& node, DiagnosticList& diags) {
  auto bench = std::make_shared<AutomaxBench>();
  bench->name = node.name;
  {
    BenchReader r(node, diags);
    r.skip("slot");
    if (auto k = r.choice("keyswitch", {"protect", "setup", "program"}))
      bench->keyswitch = *k == "protect" ? 1 : *k == "setup" ? 2 : 3;
    r.finish();
  }
  std::array<std::string, kAutomaxAreas> area_owner;
  for (const auto& dn : node.children) {
    BenchReader r(dn, diags);
    const auto* info = std::find_if(std::begin(kDropKinds), std::end(kDropKinds),
                                    [&](const DropKindInfo& k) { return dn.kind == k.bench_kind; });
    if (info == std::end(kDropKinds)) {
      r.error("unknown drop kind '" + dn.kind + "' (multibus, shark, head_57c328, head_57c330, drive_head)");
      continue;
    }
    AutomaxDropSpec d;
    d.name = dn.name;
    d.kind = info->kind;
    if (d.name.empty()) r.error("a drop needs a name (tests reach devices by name): " + dn.kind + " NAME drop=N");
    const bool shark = d.kind == AutomaxDropKind::Shark;
    r.require("drop", shark ? "1-7 (mixed rack) or 9-15 (all digital)" : "1-7");
    if (auto v = r.integer("drop", 1, shark ? 15 : 7)) {
      d.number = static_cast<int>(*v);
      if (d.number == 8) r.error_at("drop", "drop numbers are 1-7, or 9-15 (9-F) for an all-digital Shark rack");
      d.area = automax_image_area(d.number);
      auto& owner = area_owner[static_cast<std::size_t>(d.area)];
      if (!owner.empty())
        r.error_at("drop", "drop " + std::to_string(d.number) + " uses image area " + std::to_string(d.area) +
                               ", already used by " + owner + " (9-F use the area of number - 8)");
      owner = dn.label();
    }
    if (auto s = r.choice("state", {"online", "offline"})) d.online = *s == "online";
    if (auto v = r.integer("noisy", 0, 1000000)) d.noisy = static_cast<int>(*v);
    if (auto v = r.duration("diagnostics")) d.diagnostics = *v;
    switch (d.kind) {
      case AutomaxDropKind::Multibus:
      case AutomaxDropKind::Shark: read_modules(dn, d, diags); break;
      case AutomaxDropKind::Head57C328:
      case AutomaxDropKind::Head57C330:
      case AutomaxDropKind::DriveHead: {
        // 57C328: four input/output register pairs, one per rail; 57C330: one register per rail
        // (16 of them, decision); drive head: up to four drives, one per port.
        const int max_rail = d.kind == AutomaxDropKind::Head57C330 ? 15 : 3;
        const char* key = d.kind == AutomaxDropKind::DriveHead ? "ports" : "rails";
        r.require(key, d.kind == AutomaxDropKind::Head57C330 ? "rail numbers 0-15" : "numbers 0-3");
        if (auto list = r.integers(key, 0, max_rail)) {
          for (auto v : *list) {
            if (std::find(d.rails.begin(), d.rails.end(), v) != d.rails.end())
              r.error_at(key, std::string(key) + " lists " + std::to_string(v) + " twice");
            d.rails.push_back(static_cast<int>(v));
          }
          std::sort(d.rails.begin(), d.rails.end());
        }
        if (!dn.children.empty()) r.error("a " + dn.kind + " drop has no module nodes (its rails say what is connected)");
        break;
      }
    }
    r.finish();
    bench->drops.push_back(std::move(d));
  }
  return bench;
}

throughput::AutomaxDrop throughput_drop(const AutomaxDropSpec& spec) {
  throughput::AutomaxDrop t;
  t.number = spec.number;
  t.name = spec.name;
  switch (spec.kind) {
    case AutomaxDropKind::Multibus:
      t.type = throughput::AutomaxDropType::multibus;
      for (const auto& m : spec.modules) t.registers += m.inputs + m.outputs;
      break;
    case AutomaxDropKind::Shark:
      t.type = spec.all_digital_shark() ? throughput::AutomaxDropType::shark_digital : throughput::AutomaxDropType::shark_mixed;
      break;
    case AutomaxDropKind::Head57C328:
      t.type = throughput::AutomaxDropType::head_57c328;
      t.rails = static_cast<int>(spec.rails.size());
      break;
    case AutomaxDropKind::Head57C330:
      t.type = throughput::AutomaxDropType::head_57c330;
      break;
    case AutomaxDropKind::DriveHead: t.type = throughput::AutomaxDropType::drive_head; break;
  }
  return t;
}

}  // namespace softslc
