#include "instructions/module_catalog.h"

#include <array>

namespace softslc {

namespace {

// One row per module catalog. M-file defaults are the sizes the manuals tell users to configure:
// 1747-SN chapter 4 ("If you are using the block transfer (BT) function, you should set the M1
// and M0 file sizes to 3,300"), 1747-SDN appendix D (words 0-394), 1203-SM1 chapter 3 (M0 800,
// M1 400). ID codes: 1747-SN 13608 (chapter 4), 1203-SM1 enhanced mode 13616 (chapter 3; basic
// mode 3516 is selected with ID_CODE); the 1747-SDN manual gives none (0).
constexpr std::array kModules{
    // 1746 discrete I/O: points from the catalog numbers (1746-IB8 = 8 inputs, -IO12 = 6 inputs and
    // 6 outputs); one image word per 16 points.
    ModuleCatalogEntry{"1746-IB8", "8-input 24 VDC sink", 0, 1, 0, 0, 0, false, 8, -1},
    ModuleCatalogEntry{"1746-IB16", "16-input 24 VDC sink", 0, 1, 0, 0, 0, false, 16, -1},
    ModuleCatalogEntry{"1746-IB32", "32-input 24 VDC sink", 0, 2, 0, 0, 0, false, 32, -1},
    ModuleCatalogEntry{"1746-IV16", "16-input 24 VDC source", 0, 1, 0, 0, 0, false, 16, -1},
    ModuleCatalogEntry{"1746-IA16", "16-input 120 VAC", 0, 1, 0, 0, 0, false, 16, -1},
    ModuleCatalogEntry{"1746-IA8", "8-input 120 VAC", 0, 1, 0, 0, 0, false, 8, -1},
    ModuleCatalogEntry{"1746-OB8", "8-output 24 VDC source", 0, 0, 1, 0, 0, false, -1, 8},
    ModuleCatalogEntry{"1746-OB16", "16-output 24 VDC source", 0, 0, 1, 0, 0, false, -1, 16},
    ModuleCatalogEntry{"1746-OB32", "32-output 24 VDC source", 0, 0, 2, 0, 0, false, -1, 32},
    ModuleCatalogEntry{"1746-OV16", "16-output 24 VDC sink", 0, 0, 1, 0, 0, false, -1, 16},
    ModuleCatalogEntry{"1746-OW16", "16-output relay", 0, 0, 1, 0, 0, false, -1, 16},
    ModuleCatalogEntry{"1746-OW8", "8-output relay", 0, 0, 1, 0, 0, false, -1, 8},
    ModuleCatalogEntry{"1746-OA16", "16-output 120/240 VAC", 0, 0, 1, 0, 0, false, -1, 16},
    ModuleCatalogEntry{"1746-IO12", "6-input 6-output combination", 0, 1, 1, 0, 0, false, 6, 6},
    // 1762 expansion I/O (MicroLogix 1100/1200/1400): the catalog number gives the points
    // (IQ16 = 16 inputs, OB32T = 32 outputs, IQ8OW6 = 8 inputs and 6 relay outputs).
    ModuleCatalogEntry{"1762-IA8", "MicroLogix 8-input 120 VAC", 0, 1, 0, 0, 0, false, 8, -1},
    ModuleCatalogEntry{"1762-IQ8", "MicroLogix 8-input 10/30 VDC", 0, 1, 0, 0, 0, false, 8, -1},
    ModuleCatalogEntry{"1762-IQ16", "MicroLogix 16-input 10/30 VDC", 0, 1, 0, 0, 0, false, 16, -1},
    ModuleCatalogEntry{"1762-IQ32T", "MicroLogix 32-input 24 VDC", 0, 2, 0, 0, 0, false, 32, -1},
    ModuleCatalogEntry{"1762-OA8", "MicroLogix 8-output 120/240 VAC", 0, 0, 1, 0, 0, false, -1, 8},
    ModuleCatalogEntry{"1762-OB8", "MicroLogix 8-output 24 VDC source", 0, 0, 1, 0, 0, false, -1, 8},
    ModuleCatalogEntry{"1762-OB16", "MicroLogix 16-output 24 VDC source", 0, 0, 1, 0, 0, false, -1, 16},
    ModuleCatalogEntry{"1762-OB32T", "MicroLogix 32-output 24 VDC source", 0, 0, 2, 0, 0, false, -1, 32},
    ModuleCatalogEntry{"1762-OV32T", "MicroLogix 32-output 24 VDC sink", 0, 0, 2, 0, 0, false, -1, 32},
    ModuleCatalogEntry{"1762-OW8", "MicroLogix 8-output relay", 0, 0, 1, 0, 0, false, -1, 8},
    ModuleCatalogEntry{"1762-OW16", "MicroLogix 16-output relay", 0, 0, 1, 0, 0, false, -1, 16},
    ModuleCatalogEntry{"1762-OX6I", "MicroLogix 6-output isolated relay", 0, 0, 1, 0, 0, false, -1, 6},
    ModuleCatalogEntry{"1762-IQ8OW6", "MicroLogix 8-input 6-output relay combination", 0, 1, 1, 0, 0, false, 8, 6},
    // 1769 Compact I/O discrete modules (MicroLogix 1500), points likewise from the catalog number.
    ModuleCatalogEntry{"1769-IA8I", "Compact 8-input isolated 120 VAC", 0, 1, 0, 0, 0, false, 8, -1},
    ModuleCatalogEntry{"1769-IA16", "Compact 16-input 120 VAC", 0, 1, 0, 0, 0, false, 16, -1},
    ModuleCatalogEntry{"1769-IM12", "Compact 12-input 240 VAC", 0, 1, 0, 0, 0, false, 12, -1},
    ModuleCatalogEntry{"1769-IQ16", "Compact 16-input 24 VDC", 0, 1, 0, 0, 0, false, 16, -1},
    ModuleCatalogEntry{"1769-IQ16F", "Compact 16-input 24 VDC fast", 0, 1, 0, 0, 0, false, 16, -1},
    ModuleCatalogEntry{"1769-IQ32", "Compact 32-input 24 VDC", 0, 2, 0, 0, 0, false, 32, -1},
    ModuleCatalogEntry{"1769-IQ32T", "Compact 32-input 24 VDC", 0, 2, 0, 0, 0, false, 32, -1},
    ModuleCatalogEntry{"1769-OA8", "Compact 8-output 120/240 VAC", 0, 0, 1, 0, 0, false, -1, 8},
    ModuleCatalogEntry{"1769-OA16", "Compact 16-output 120/240 VAC", 0, 0, 1, 0, 0, false, -1, 16},
    ModuleCatalogEntry{"1769-OB8", "Compact 8-output 24 VDC source", 0, 0, 1, 0, 0, false, -1, 8},
    ModuleCatalogEntry{"1769-OB16", "Compact 16-output 24 VDC source", 0, 0, 1, 0, 0, false, -1, 16},
    ModuleCatalogEntry{"1769-OB16P", "Compact 16-output 24 VDC protected", 0, 0, 1, 0, 0, false, -1, 16},
    ModuleCatalogEntry{"1769-OB32", "Compact 32-output 24 VDC source", 0, 0, 2, 0, 0, false, -1, 32},
    ModuleCatalogEntry{"1769-OV16", "Compact 16-output 24 VDC sink", 0, 0, 1, 0, 0, false, -1, 16},
    ModuleCatalogEntry{"1769-OW8", "Compact 8-output relay", 0, 0, 1, 0, 0, false, -1, 8},
    ModuleCatalogEntry{"1769-OW8I", "Compact 8-output isolated relay", 0, 0, 1, 0, 0, false, -1, 8},
    ModuleCatalogEntry{"1769-OW16", "Compact 16-output relay", 0, 0, 1, 0, 0, false, -1, 16},
    ModuleCatalogEntry{"1769-IQ6XOW4", "Compact 6-input 4-output relay combination", 0, 1, 1, 0, 0, false, 6, 4},
    // MicroLogix embedded I/O: slot 0 of a MicroLogix is the controller's own I/O, named by its
    // bulletin as RSLogix 500 exports it (SLOT 0 Bul.1766). Points are those of the largest base
    // unit of each bulletin (1761-L32, 1762-L40, 1763-L16, 1764-28 base, 1766-L32). Image words:
    // MicroLogix 1400 I:0 8 words, O:0 6 words as RSLogix 500 exports them (59-BSGS.SLC, SLOT 0);
    // MicroLogix 1100 I:0.4-I:0.5 embedded analog inputs; the others their digital words only
    // (docs/program-format.md, "Embedded I/O", says which of these are decisions).
    ModuleCatalogEntry{"Bul.1761", "MicroLogix 1000 embedded I/O", 0, 2, 1, 0, 0, false, 20, 12, true},
    ModuleCatalogEntry{"Bul.1762", "MicroLogix 1200 embedded I/O", 0, 2, 1, 0, 0, false, 24, 16, true},
    ModuleCatalogEntry{"Bul.1763", "MicroLogix 1100 embedded I/O", 0, 6, 1, 0, 0, false, 10, 6, true},
    ModuleCatalogEntry{"Bul.1764", "MicroLogix 1500 embedded I/O", 0, 1, 1, 0, 0, false, 16, 12, true},
    ModuleCatalogEntry{"Bul.1766", "MicroLogix 1400 embedded I/O", 0, 8, 6, 0, 0, false, 20, 12, true},
    // Fixed SLC 500 controllers (1747-L20x/L30x/L40x): slot 0 is the controller's own I/O, named by the
    // catalog prefix every suffix shares (the suffix is the I/O voltage type). 1747-PT1 (1747-NP002)
    // p. 4-4: "a fixed I/O controller has 24 inputs and 16 outputs" at I:0, I:0.1 and O:0, so inputs
    // 16-23 are bits 0-7 of I:0.1 (p. 4-5: I:0.1/7 is "Controller input 23"). The 20- and 30-point
    // splits (12/8, 18/12) are decisions [U]: docs/program-format.md "Embedded I/O".
    ModuleCatalogEntry{"1747-L20", "SLC 500 fixed controller I/O (20 points)", 0, 1, 1, 0, 0, false, 12, 8},
    ModuleCatalogEntry{"1747-L30", "SLC 500 fixed controller I/O (30 points)", 0, 2, 1, 0, 0, false, 18, 12},
    ModuleCatalogEntry{"1747-L40", "SLC 500 fixed controller I/O (40 points)", 0, 2, 1, 0, 0, false, 24, 16},
    // Specialty modules.
    ModuleCatalogEntry{"1747-SN", "Remote I/O scanner", 13608, 32, 32, 3300, 3300, true},
    ModuleCatalogEntry{"1747-BSN", "Backup Remote I/O scanner", 13608, 32, 32, 3300, 3300, true},
    ModuleCatalogEntry{"1747-SDN", "DeviceNet scanner", 0, 32, 32, 395, 395, true},
    ModuleCatalogEntry{"1203-SM1", "SLC to SCANport module", 13616, 32, 32, 800, 400, true},
    ModuleCatalogEntry{"57C416", "AutoMax Remote I/O master (dual-port image in M0)", 0, 0, 0, 4096, 0, true},
};

}  // namespace

std::optional<ModuleCatalogEntry> find_module_catalog(std::string_view catalog) {
  for (const auto& m : kModules)
    if (m.catalog == catalog) return m;
  return std::nullopt;
}

std::span<const ModuleCatalogEntry> module_catalog_entries() { return kModules; }

std::uint16_t catalog_point_mask(int points, int word, bool whole_words_after_points) {
  if (points < 0) return 0xFFFF;
  const int here = points - word * 16;
  if (here >= 16) return 0xFFFF;
  if (here > 0) return static_cast<std::uint16_t>((1u << here) - 1);
  // Past the discrete points: a whole analog/status word on embedded I/O, nothing on a card.
  const int discrete_words = (points + 15) / 16;
  return whole_words_after_points && word >= discrete_words ? 0xFFFF : 0;
}

}  // namespace softslc

// ---- 1747-SN RIO scanner configuration --------------------------------------------------------------

namespace softslc {

namespace {

// "logical rack 9 group 2" for a quarter-rack bit of word 1 (primary) or word 3 (complementary).
std::string rio_location(int bit, bool complementary) {
  return "logical rack " + std::to_string(bit / 4 + (complementary ? 8 : 0)) + " group " + std::to_string((bit % 4) * 2);
}

std::string device_text(const RioGDevice& d) {
  static const char* sizes[] = {"", "1/4", "1/2", "3/4", "full"};
  const int quarters = d.groups / 2;
  std::string size = quarters <= 4 ? std::string(sizes[quarters]) + " logical rack"
                                   : std::to_string(d.groups) + "-group";
  return std::string(d.complementary ? "complementary" : "primary") + " " + size + " device at " +
         rio_location(d.bit, d.complementary);
}

// Decodes one address/size word pair into devices. A device runs from its start bit over the
// following size bits up to the next start bit or the first clear size bit.
void decode_pair(std::uint16_t start, std::uint16_t size, bool complementary, int start_word,
                 std::vector<RioGDevice>& out, std::vector<ModuleConfigFinding>& findings) {
  const std::string ws = "word " + std::to_string(start_word), wz = "word " + std::to_string(start_word + 1);
  std::uint16_t covered = 0;
  for (int b = 0; b < 16; ++b) {
    if (!(start & (1u << b))) continue;
    if (!(size & (1u << b))) {
      findings.push_back({true, "G file " + ws + " bit " + std::to_string(b) + " configures a device at " +
                                    rio_location(b, complementary) + " but " + wz +
                                    " allocates it no image (1747-SN manual ch. 4, \"Rules for Configuring the "
                                    "Scanner\": \"If a device is configured in word " +
                                    std::to_string(start_word) + ", there must be image allocated to it in word " +
                                    std::to_string(start_word + 1) + ".\")"});
      continue;
    }
    RioGDevice d;
    d.bit = b;
    d.rack = b / 4;
    d.group = (b % 4) * 2;
    d.complementary = complementary;
    int e = b + 1;
    while (e < 16 && (size & (1u << e)) && !(start & (1u << e))) ++e;
    d.groups = (e - b) * 2;
    for (int k = b; k < e; ++k) covered = static_cast<std::uint16_t>(covered | (1u << k));
    out.push_back(d);
  }
  const std::uint16_t orphan = static_cast<std::uint16_t>(size & ~covered);
  for (int b = 0; b < 16; ++b)
    if (orphan & (1u << b))
      findings.push_back({true, "G file " + wz + " bit " + std::to_string(b) + " allocates image at " +
                                    rio_location(b, complementary) + " to no device: no device starting at or before it in " +
                                    ws + " reaches it (1747-SN manual ch. 4, \"RIO Configuration Using G Files\": \"To "
                                    "specify image size, you place a 1 at each group a device occupies.\")"});
}

}  // namespace

bool is_rio_scanner(std::string_view catalog, std::optional<int> id_code) {
  if (catalog == "1747-SN" || catalog == "1747-BSN") return true;
  return !find_module_catalog(catalog) && id_code && *id_code == kRioScannerIdCode;
}

RioGFile decode_rio_g_file(std::span<const std::uint16_t> g, std::vector<ModuleConfigFinding>& findings) {
  RioGFile out;
  for (std::size_t i = 0; i < g.size() && i < out.words.size(); ++i) out.words[i] = g[i];
  if (g.size() != 3 && g.size() != 5) {
    findings.push_back({true, "the 1747-SN G file has " + std::to_string(g.size()) +
                                  " words; it must have 3, or 5 with complementary I/O (1747-SN manual ch. 4, "
                                  "\"SLC/Scanner Configuration\": \"Set the G file size to 3 (5 if using "
                                  "complementary I/O)\")"});
    if (g.size() < 3) return out;
  }
  const std::uint16_t w1 = out.words[1], w2 = out.words[2];
  const std::uint16_t w3 = g.size() >= 5 ? out.words[3] : 0, w4 = g.size() >= 5 ? out.words[4] : 0;
  if (g.size() < 5) out.words[3] = out.words[4] = 0;
  out.complementary_mode = w3 != 0;
  // "if word 3 = 1 and word 4 = 0, the complementary mode is selected even though no
  // complementary devices are configured."
  const bool mode_marker_only = w3 == 1 && w4 == 0;
  decode_pair(w1, w2, false, 1, out.devices, findings);
  if (!mode_marker_only) decode_pair(w3, w4, true, 3, out.devices, findings);

  std::vector<const RioGDevice*> primary, complementary;
  for (const auto& d : out.devices) (d.complementary ? complementary : primary).push_back(&d);
  if (primary.empty() && complementary.empty()) {
    findings.push_back({true, std::string("the G file configures no device: ") +
                                  (out.complementary_mode
                                       ? "\"G file words 1 and 2 can both be zero (no primary devices). However, in "
                                         "this case there must be at least one complementary device configured in G "
                                         "file words 3 and 4.\""
                                       : "words 1 and 2 are both zero and complementary I/O is not selected; \"G file "
                                         "words 1 and 2 can both be zero (no primary devices). However, in this case "
                                         "there must be at least one complementary device configured in G file words "
                                         "3 and 4.\"") +
                                  " (1747-SN manual ch. 4, \"Concerning Complementary I/O\")"});
  }
  // A complementary device may share image space with a primary device only when both start at
  // the same location; otherwise neither may reach into the other's image.
  for (const RioGDevice* c : complementary) {
    for (const RioGDevice* p : primary) {
      const bool overlap = c->first_quarter() < p->end_quarter() && p->first_quarter() < c->end_quarter();
      if (!overlap || c->bit == p->bit) continue;
      std::string rule;
      if (p->covers_quarter(c->bit))
        rule = "\"A complementary device cannot be configured at locations where primary devices are configured "
               "unless they both start at the same location.\"";
      else if (c->covers_quarter(p->bit))
        rule = "\"The starting group of the primary and complementary chassis should be the same if they share the "
               "same image space. If the starting group is not the same, the image of the complementary device must "
               "not 'cross over' into the space of a primary device.\" (the manual's illegal example: a primary device "
               "at Logical Rack 1, Logical Group 2 \"would be illegal since this image space is already being used by "
               "a complementary device\")";
      findings.push_back({true, "the " + device_text(*c) + " shares image space with the " + device_text(*p) +
                                    " but they start at different groups: " + rule +
                                    " (1747-SN manual ch. 4, \"Concerning Complementary I/O\")"});
    }
  }
  return out;
}

std::optional<RioBaudSetting> rio_baud_setting(const std::map<std::string, std::string>& options, std::string* error) {
  RioBaudSetting s;  // 57.6K: both switches on
  auto baud = options.find("baud");
  auto dip = options.find("dip");
  if (baud != options.end() && dip != options.end()) {
    if (error) *error = "give the baud rate either as OPTION baud=... or as OPTION dip=..., not both";
    return std::nullopt;
  }
  if (baud != options.end()) {
    const std::string& v = baud->second;
    if (v == "57.6K" || v == "57.6k" || v == "57600") s = {0, 3};
    else if (v == "115.2K" || v == "115.2k" || v == "115200") s = {1, 1};
    else if (v == "230.4K" || v == "230.4k" || v == "230400") s = {2, 2};
    else {
      if (error) *error = "OPTION baud=" + v + ": the 1747-SN runs at 57.6K, 115.2K or 230.4K (Table A.2)";
      return std::nullopt;
    }
  }
  if (dip != options.end()) {
    const std::string& v = dip->second;
    // Table A.2: SW1 SW2 on-on 57.6K, on-off 115.2K, off-on and off-off 230.4K.
    if (v == "on-on") s = {0, 3};
    else if (v == "on-off") s = {1, 1};
    else if (v == "off-on") s = {2, 2};
    else if (v == "off-off") s = {2, 0};
    else {
      if (error) *error = "OPTION dip=" + v + ": give switches 1 and 2 as on-on, on-off, off-on or off-off (Table A.2)";
      return std::nullopt;
    }
  }
  return s;
}

std::vector<ModuleConfigFinding> check_rio_scanner_slot(const RioScannerSlot& s) {
  std::vector<ModuleConfigFinding> f;
  auto err = [&](std::string m) { f.push_back({true, std::move(m)}); };
  auto warn = [&](std::string m) { f.push_back({false, std::move(m)}); };
  if (s.slot == 0)
    err("the 1747-SN cannot be in slot 0 (1747-SN manual ch. 1: \"The scanner can reside in any slot of the local SLC "
        "chassis except for slot 0.\")");
  if (!s.processor_ok)
    err("the 1747-SN needs an SLC 5/02 or later processor; this program's processor is " + s.processor_name +
        " (1747-SN manual ch. 1: \"It enables communication between an SLC processor (SLC 5/02 or later) and remotely "
        "located ... 1746 I/O chassis\")");
  for (auto [name, words] : {std::pair<const char*, int>{"SCAN_IN", s.scan_in}, {"SCAN_OUT", s.scan_out}}) {
    if (words == 0)
      err(std::string(name) + " is 0 (1747-SN manual ch. 4, \"SLC/Scanner Configuration\": \"Do not set either of these "
                              "values to 0. If you do, the scanner will not work correctly.\")");
    else if (words > 32)
      err(std::string(name) + " " + std::to_string(words) +
          " is more than the scanner's 32 words (1747-SN manual ch. 4: \"The SLC system allows you to assign up to 32 "
          "words of input and output image data to a scanner.\")");
  }
  if (s.id_code && *s.id_code != kRioScannerIdCode)
    err("ID_CODE " + std::to_string(*s.id_code) +
        " is not the 1747-SN's; \"enter the scanner input module ID code (13608)\" (1747-SN manual ch. 2)");
  std::string baud_error;
  if (!rio_baud_setting(s.options, &baud_error)) err(baud_error);
  for (const auto& [key, value] : s.options)
    if (key != "baud" && key != "dip")
      err("OPTION " + key + "=" + value + ": the 1747-SN knows OPTION baud=... and OPTION dip=... (its only switches)");

  std::vector<ModuleConfigFinding> g;
  RioGFile cfg;
  if (!s.has_g_file) {
    warn("the 1747-SN has no G file; the processor faults with 62H when it enters Run (1747-SN manual ch. 6: \"G file "
         "is missing.\" 62H)");
  } else {
    cfg = decode_rio_g_file(s.g_file, g);
    for (auto& x : g) f.push_back(std::move(x));
  }
  const int min_m = cfg.complementary_mode ? 48 : 32;
  for (auto [name, size] : {std::pair<const char*, std::optional<int>>{"M0_SIZE", s.m0_size}, {"M1_SIZE", s.m1_size}})
    if (size && *size < min_m)
      warn(std::string(name) + " " + std::to_string(*size) + " is below the scanner's minimum of " +
          std::to_string(min_m) +
          " words (1747-SN manual ch. 4: \"set the M1 and M0 file sizes to 32 words (48 words if using complementary "
          "I/O). 32 words is the minimum required for operation.\")");
  if (s.has_g_file && g.empty()) {
    // Devices whose image lies beyond SCAN_IN/SCAN_OUT are scanned but never seen by the processor.
    for (const auto& d : cfg.devices) {
      const int last_word = d.rack * 8 + d.group + d.groups;  // one past the device's last image word
      if (last_word > s.scan_in || last_word > s.scan_out)
        warn(std::string(d.complementary ? "complementary" : "primary") + " device at " +
             rio_location(d.bit, d.complementary) + " reaches image word " + std::to_string(last_word - 1) +
             " but the processor transfers only " + std::to_string(std::min(s.scan_in, s.scan_out)) +
             " words (SCAN_IN/SCAN_OUT); the rest of its image is not seen by the program");
    }
  }
  return f;
}

}  // namespace softslc
