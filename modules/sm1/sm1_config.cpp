#include "modules/sm1/sm1_config.h"

#include <charconv>
#include <filesystem>

#include "modules/scanport/drive_json.h"

namespace softslc {

std::uint16_t Sm1Config::g_word(int k) const {
  return k >= 0 && k < static_cast<int>(g_file.size()) ? g_file[static_cast<std::size_t>(k)] : 0;
}

std::uint16_t Sm1Config::dip_switch_word() const {
  std::uint16_t w = 0;
  for (int c = 0; c < kSm1Channels; ++c)
    w = static_cast<std::uint16_t>(w | (static_cast<unsigned>(fault_state[static_cast<std::size_t>(c)]) << (2 * c)));
  return w;
}

namespace {

void add(std::vector<Sm1Finding>& f, bool error, std::string m) { f.push_back({error, std::move(m)}); }

std::optional<Sm1FaultState> fault_state_named(const std::string& v) {
  if (v == "fault") return Sm1FaultState::FaultDevice;
  if (v == "zero") return Sm1FaultState::ZeroData;
  if (v == "hold") return Sm1FaultState::HoldLastState;
  if (v == "safe") return Sm1FaultState::SafeState;
  return std::nullopt;
}

}  // namespace

Sm1Config decode_sm1_slot(const Program& program, const SlotConfig& slot, std::vector<Sm1Finding>& findings) {
  Sm1Config c;
  c.slot = slot.slot;
  const int id = slot.id_code.value_or(kSm1EnhancedIdCode);
  if (id == kSm1BasicIdCode) c.mode = Sm1Mode::Basic;
  else if (id != kSm1EnhancedIdCode)
    add(findings, true, "ID code " + std::to_string(id) + " is neither basic mode (3516, chapter 3) nor enhanced mode (13616, chapter 4)");

  const auto family = program.processor.family;
  const bool enhanced_ok = family == ProcessorFamily::Slc502 || family == ProcessorFamily::Slc503 ||
                           family == ProcessorFamily::Slc504 || family == ProcessorFamily::Slc505;
  if (c.enhanced() && !enhanced_ok)
    add(findings, true, "enhanced mode (ID code 13616) needs an SLC 5/02, 5/03 or 5/04 (chapter 1); a " +
                            program.processor.display_name + " supports basic mode only (ID code 3516)");

  const int image = c.enhanced() ? kSm1EnhancedImageWords : kSm1BasicImageWords;
  const std::string mode_name = c.enhanced() ? "enhanced" : "basic";
  if (slot.scan_in != image || slot.scan_out != image)
    add(findings, true, mode_name + " mode has " + std::to_string(image) + " input and " + std::to_string(image) +
                            " output words (chapter 1), not SCAN_IN " + std::to_string(slot.scan_in) + " SCAN_OUT " +
                            std::to_string(slot.scan_out) +
                            (c.enhanced() && slot.scan_in == kSm1BasicImageWords ? " (ID_CODE 3516 selects basic mode)" : ""));

  if (c.enhanced()) {
    // M0_SIZE/M1_SIZE, else the sizes the manual tells users to configure (also for a slot
    // that names the module only by its ID code).
    c.m0_words = slot.m0_size.value_or(kSm1MaxM0Words);
    c.m1_words = slot.m1_size.value_or(kSm1MaxM1Words);
    if (c.m0_words > kSm1MaxM0Words)
      add(findings, true, "M0_SIZE " + std::to_string(c.m0_words) + ": for this module, the maximum M0 file size is 800 (chapter 4)");
    if (c.m1_words > kSm1MaxM1Words)
      add(findings, true, "M1_SIZE " + std::to_string(c.m1_words) + ": for this module, the maximum M1 file size is 400 (chapter 4)");
    if (slot.has_g_file) {
      const int n = static_cast<int>(slot.g_file.size());
      if (n < kSm1MinGWords || n > kSm1MaxGWords)
        add(findings, true, "G_FILE " + std::to_string(n) + ": you can configure G files that are between 2 and 32 words in length (chapter 4)");
      c.g_file = slot.g_file;
      if (c.g_word(1) & 0xF000)
        add(findings, false, "G file word 1 bits 12-15 are not used (Figure 4.8); they are ignored");
    }
  } else {
    if (slot.has_g_file) add(findings, true, "basic mode has no G file (datalinks and safe state data are enhanced-mode functions, chapter 1)");
    if (slot.m0_size || slot.m1_size) add(findings, true, "basic mode has no M0/M1 files (messaging is an enhanced-mode function, chapter 1)");
  }

  for (const auto& [key, value] : slot.options) {
    int ch = 0;
    if (key == "ch1") ch = 1;
    else if (key == "ch2") ch = 2;
    else if (key == "ch3") ch = 3;
    if (ch == 0) {
      add(findings, true, "unknown OPTION " + key + " (the 1203-SM1 takes ch1, ch2, ch3 = fault|zero|hold|safe: the Fault/Program State DIP switches)");
      continue;
    }
    auto s = fault_state_named(value);
    if (!s) {
      add(findings, true, "OPTION " + key + "=" + value + ": expected fault, zero, hold or safe (chapter 2 DIP switches)");
      continue;
    }
    c.fault_state[static_cast<std::size_t>(ch - 1)] = *s;
  }
  return c;
}

// ---- Bench --------------------------------------------------------------------------------------------------

namespace {

// "111:27,119:27": parameter:value pairs (the values a HIM would have set, kept in storage).
bool parse_parameter_settings(const std::string& text, std::vector<std::pair<long long, long long>>& out) {
  std::size_t i = 0;
  while (i < text.size()) {
    std::size_t end = text.find(',', i);
    if (end == std::string::npos) end = text.size();
    const std::string item = text.substr(i, end - i);
    const std::size_t colon = item.find(':');
    if (colon == std::string::npos) return false;
    long long p = 0, v = 0;
    auto r1 = std::from_chars(item.data(), item.data() + colon, p);
    auto r2 = std::from_chars(item.data() + colon + 1, item.data() + item.size(), v);
    if (r1.ec != std::errc{} || r1.ptr != item.data() + colon || r2.ec != std::errc{} || r2.ptr != item.data() + item.size())
      return false;
    out.emplace_back(p, v);
    i = end + 1;
  }
  return !out.empty();
}

std::optional<Sm1DriveSpec> read_drive(const BenchNode& node, const std::string& bench_name, DiagnosticList& diags) {
  BenchReader r(node, diags);
  if (node.kind != "drive") {
    r.error("a scanport module's children are 'drive' nodes (the SCANport devices on its channels)");
    return std::nullopt;
  }
  Sm1DriveSpec d;
  d.name = node.name;
  d.pos = node.pos;
  if (d.name.empty()) r.error("a drive needs a name (tests reach devices by name): drive NAME channel=1");
  r.require("channel", "1-3");
  if (auto v = r.integer("channel", 1, 3)) d.channel = static_cast<int>(*v);
  if (auto v = r.integer("port", 1, 6)) d.port = static_cast<int>(*v);
  if (auto v = r.choice("power", {"on", "off"})) d.powered = *v == "on";
  if (auto v = r.choice("cable", {"connected", "removed"})) d.cable = *v == "connected";
  const auto file = r.text("file");
  const std::string model = r.text("model").value_or(file ? *file : "1305");
  if (file && r.node().find("model")) r.error("give model= or file=, not both");
  auto pad = r.integer("pad", 1, 96);
  auto settings = r.text("parameters");
  r.finish();
  scanport::DriveDescription desc;
  if (file) {
    const auto path = std::filesystem::path(bench_name).parent_path() / *file;
    try {
      desc = scanport::load_drive_description_file(path.string());
    } catch (const scanport::DriveDescriptionError& e) {
      r.error_at("file", e.what());
      return std::nullopt;
    }
  } else {
    try {
      desc = scanport::builtin_drive(model);
    } catch (const scanport::DriveDescriptionError&) {
      std::string known;
      for (const auto& n : scanport::builtin_drive_names()) known += (known.empty() ? "" : ", ") + n;
      r.error_at("model", "model=" + model + ": no such built-in drive (known: " + known + ")");
      return std::nullopt;
    }
  }
  // pad=6: a device that pads every reply to a multiple of six bytes (Figure B.2 footnote,
  // "These products always return a length which is a multiple of six").
  if (pad) desc.response_padding.fill(static_cast<int>(*pad));
  if (settings) {
    std::vector<std::pair<long long, long long>> pairs;
    if (!parse_parameter_settings(*settings, pairs)) {
      r.error_at("parameters", "parameters=" + *settings + ": expected PARAMETER:VALUE pairs separated by commas (111:27,119:27)");
      return std::nullopt;
    }
    for (auto [p, v] : pairs) {
      if (p < 1 || p > static_cast<long long>(desc.parameters.size())) {
        r.error_at("parameters", "parameter " + std::to_string(p) + " does not exist (the " + model + " has 1-" +
                                     std::to_string(desc.parameters.size()) + ")");
        return std::nullopt;
      }
      auto& spec = desc.parameters[static_cast<std::size_t>(p - 1)];
      if (v < spec.minimum || v > spec.maximum) {
        r.error_at("parameters", "parameter " + std::to_string(p) + " (" + spec.name + ") = " + std::to_string(v) +
                                     " is outside " + std::to_string(spec.minimum) + ".." + std::to_string(spec.maximum));
        return std::nullopt;
      }
      spec.value = v;
    }
  }
  try {
    scanport::validate(desc);
  } catch (const scanport::DriveDescriptionError& e) {
    r.error(std::string("drive description: ") + e.what());
    return std::nullopt;
  }
  if (r.failed()) return std::nullopt;
  d.description = std::make_shared<const scanport::DriveDescription>(std::move(desc));
  return d;
}

}  // namespace

std::shared_ptr<const Sm1Bench> interpret_sm1_bench(const BenchNode& node, const std::string& bench_name,
                                                    DiagnosticList& diags) {
  auto bench = std::make_shared<Sm1Bench>();
  bench->name = node.name;
  {
    BenchReader r(node, diags);
    r.skip("slot");
    r.finish();
  }
  std::array<std::string, kSm1Channels> taken_by;  // drive name per channel
  for (const auto& dn : node.children) {
    auto d = read_drive(dn, bench_name, diags);
    if (!d) continue;
    auto& owner = taken_by[static_cast<std::size_t>(d->channel - 1)];
    if (!owner.empty()) {
      BenchReader r(dn, diags);
      r.skip("channel");
      r.error_at("channel", "channel " + std::to_string(d->channel) + " already has drive " + owner);
      continue;
    }
    owner = d->name;
    bench->drives.push_back(std::move(*d));
  }
  return bench;
}

}  // namespace softslc
