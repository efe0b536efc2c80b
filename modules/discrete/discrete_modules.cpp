#include "modules/discrete/discrete_modules.h"

#include <algorithm>

#include "instructions/module_catalog.h"
#include "modules/module_registry.h"
#include "parser/loader.h"

namespace softslc {

namespace {

// The bits of each image word that exist, from the catalog row's explicit point counts.
std::vector<std::uint16_t> point_masks(int words, int points, bool whole_words_after_points) {
  std::vector<std::uint16_t> out(static_cast<std::size_t>(std::max(words, 0)), 0);
  for (std::size_t w = 0; w < out.size(); ++w)
    out[w] = catalog_point_mask(points, static_cast<int>(w), whole_words_after_points);
  return out;
}

bool parse_word(const std::string& t, std::uint16_t& out) {
  NumberValue v;
  if (!parse_number_text(t, v) || v.is_float || v.integer < -32768 || v.integer > 0xFFFF) return false;
  out = static_cast<std::uint16_t>(v.integer);
  return true;
}

}  // namespace

DiscreteModule::DiscreteModule(int slot, std::string catalog, int input_words, int output_words, DiscreteModuleSpec spec)
    : DiscreteIoModule(slot, std::move(catalog), input_words, output_words),
      spec_(std::move(spec)),
      last_delivered_(static_cast<std::size_t>(std::max(output_words, 0)), 0) {}

std::uint16_t DiscreteModule::in_points(int word) const {
  if (word < 0) return 0;
  if (static_cast<std::size_t>(word) < spec_.input_points.size()) return spec_.input_points[static_cast<std::size_t>(word)];
  return word < input_words() ? 0xFFFF : 0;
}

std::uint16_t DiscreteModule::out_points(int word) const {
  if (word < 0) return 0;
  if (static_cast<std::size_t>(word) < spec_.output_points.size()) return spec_.output_points[static_cast<std::size_t>(word)];
  return word < output_words() ? 0xFFFF : 0;
}

void DiscreteModule::output_scan(std::span<const std::uint16_t> image) {
  // Every scan delivers the image: the masked copy reuses one buffer, so a scan allocates nothing.
  if (out_mask_.size() != image.size()) {
    out_mask_.resize(image.size());
    for (std::size_t w = 0; w < image.size(); ++w) out_mask_[w] = out_points(static_cast<int>(w));
    masked_.resize(image.size());
  }
  for (std::size_t w = 0; w < image.size(); ++w) masked_[w] = static_cast<std::uint16_t>(image[w] & out_mask_[w]);
  if (spec_.output_delay <= 0 || !host()) {
    DiscreteIoModule::output_scan(masked_);
    return;
  }
  // The terminals follow after the output delay; only changes are scheduled.
  if (masked_ == last_delivered_) return;
  last_delivered_ = masked_;
  host()->schedule_at(host()->now() + spec_.output_delay,
                      [this, masked = masked_](VirtualTime) { DiscreteIoModule::output_scan(masked); });
}

bool DiscreteModule::set_field_input(int word, std::uint16_t value, std::uint16_t mask) {
  const std::uint16_t points = in_points(word);
  mask = static_cast<std::uint16_t>(mask & points);
  if (mask == 0) return false;
  if (spec_.input_delay <= 0 || !host()) return DiscreteIoModule::set_field_input(word, value, mask);
  host()->schedule_at(host()->now() + spec_.input_delay, [this, word, value, mask](VirtualTime) {
    DiscreteIoModule::set_field_input(word, value, mask);
  });
  return true;
}

std::vector<std::string> DiscreteModule::device_names() const {
  if (spec_.name.empty()) return {};
  return {spec_.name};
}

DeviceStatus DiscreteModule::inject(const DeviceFault& f) {
  if (spec_.name.empty() || f.device != spec_.name) return {};
  if (f.fault == "input") {
    std::uint16_t value = 0, mask = 0xFFFF;
    if (f.args.empty() || f.args.size() > 2 || !parse_word(f.args[0], value) ||
        (f.args.size() == 2 && !parse_word(f.args[1], mask)))
      return DeviceStatus::refused("input takes VALUE [MASK] (16-bit words)");
    if (input_words() <= 0 || !set_field_input(0, value, mask))
      return DeviceStatus::refused("the " + catalog() + " has no such input points");
    return DeviceStatus::done();
  }
  if (f.fault == "normal") return DeviceStatus::done();
  return DeviceStatus::refused("a discrete module accepts 'input VALUE [MASK]' and 'normal', not '" + f.fault + "'");
}

std::optional<std::vector<std::int64_t>> DiscreteModule::observe(std::string_view device, std::string_view what) const {
  if (spec_.name.empty() || device != spec_.name) return std::nullopt;
  std::vector<std::int64_t> out;
  if (what == "inputs") {
    for (int w = 0; w < input_words(); ++w) out.push_back(field_input(w).value_or(0));
  } else if (what == "outputs") {
    for (int w = 0; w < output_words(); ++w) out.push_back(field_output(w).value_or(0));
  } else {
    return std::nullopt;
  }
  return out;
}

void register_discrete_io_family(ModuleRegistry& registry) {
  ModuleFamily f;
  f.name = "discrete I/O (1746, 1762, 1769, MicroLogix embedded)";
  // Every non-specialty row of the catalog is a discrete card (or a controller's embedded I/O).
  for (const auto& e : module_catalog_entries())
    if (!e.specialty) f.catalogs.emplace_back(e.catalog);
  f.bench_kinds = {"io"};
  f.prepare = [](const ModulePrepareContext& ctx) -> SlotModuleBuilder {
    DiscreteModuleSpec spec;
    auto entry = find_module_catalog(ctx.slot.catalog);
    if (entry) {
      spec.input_points = point_masks(ctx.slot.scan_in, entry->input_points, entry->whole_words_after_points);
      spec.output_points = point_masks(ctx.slot.scan_out, entry->output_points, entry->whole_words_after_points);
    }
    if (ctx.bench) {
      BenchReader r(*ctx.bench, ctx.bench_diagnostics);
      r.skip("slot");
      spec.name = ctx.bench->name;
      if (auto d = r.duration("input_delay")) spec.input_delay = *d;
      if (auto d = r.duration("output_delay")) spec.output_delay = *d;
      for (const auto& c : ctx.bench->children)
        ctx.bench_diagnostics.error(c.pos.line, c.pos.column, ctx.bench->label() + ": a discrete module has no child devices");
      r.finish();
    }
    return [spec](const SlotConfig& s) -> std::unique_ptr<Module> {
      return std::make_unique<DiscreteModule>(s.slot, s.catalog, s.scan_in, s.scan_out, spec);
    };
  };
  registry.add(std::move(f));
}

}  // namespace softslc
