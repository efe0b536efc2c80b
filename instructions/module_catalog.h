// Static facts about module catalog numbers, as the program checker needs them.
//
// The behaviour of modules lives in modules/; this table only says what a SLOT line's catalog
// number implies before anything runs: whether the module has M0/M1 files and their default
// sizes (the sizes each manual tells users to configure), its module ID code, and its default
// image size. Unknown catalogs are accepted as generic I/O cards sized by SCAN_IN/SCAN_OUT.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace softslc {

struct ModuleCatalogEntry {
  std::string_view catalog;
  std::string_view description;
  int id_code;          // module ID code (0 where the manuals do not give one)
  int default_scan_in;  // input image words
  int default_scan_out; // output image words
  int default_m0;       // M0 file words (0 = no M files)
  int default_m1;       // M1 file words
  bool specialty;       // reached through M0/M1/G files by ladder
  // Discrete points, counted from bit 0 of the first image word (the wiring tables of the 1746,
  // 1762 and 1769 module manuals): a 1762-IQ8OW6 has input bits 0-7 and output bits 0-5. -1
  // means every bit of every image word (specialty and analog modules, unknown cards). These are
  // explicit per row; nothing is derived from the description text.
  int input_points = -1;
  int output_points = -1;
  // Image words after the discrete ones are whole data words (a controller's embedded analog
  // channels and status words: MicroLogix 1400 I:0.4-I:0.7). False on plug-in cards, whose words
  // beyond their points do not exist.
  bool whole_words_after_points = false;
};

// The bits of image word `word` that exist on a module with `points` discrete points (-1: all).
std::uint16_t catalog_point_mask(int points, int word, bool whole_words_after_points);

// Looks a catalog number up; nullopt when softslc does not know it.
std::optional<ModuleCatalogEntry> find_module_catalog(std::string_view catalog);

// Every catalog row, in table order (for the discrete-I/O module family and the tests).
std::span<const ModuleCatalogEntry> module_catalog_entries();

}  // namespace softslc

// ---- 1747-SN Remote I/O scanner configuration (1747-SN manual, chapter 4) ----------------------------
//
// The checker (`softslc check`) and the scanner module (modules/sn) both read a scanner's SLOT
// line through the functions below, so the configuration the checker accepts is exactly the one
// the simulated scanner runs, and the rule quoted in a check error is the one the scanner applies
// when it refuses its G file at Run entry (fault 63H).

namespace softslc {

// The 1747-SN's module ID code ("enter the scanner input module ID code (13608)", chapter 2).
inline constexpr int kRioScannerIdCode = 13608;

// True for the catalogs (or the ID code of an "Other" module) that are a 1747-SN RIO scanner.
bool is_rio_scanner(std::string_view catalog, std::optional<int> id_code);

// One logical device of the G file: a bit of word 1 (primary/normal) or word 3 (complementary)
// and the run of word 2 / word 4 bits that belongs to it. `rack` is the primary rack number
// 0-3 (a complementary device's G-file rack is rack + 8); `group` its even starting group;
// `groups` its image size in groups (2-32, crossing rack boundaries as chapter 4 allows).
struct RioGDevice {
  int bit = 0;  // start bit: rack * 4 + group / 2
  int rack = 0;
  int group = 0;
  int groups = 2;
  bool complementary = false;
  int first_quarter() const { return bit; }
  int end_quarter() const { return bit + groups / 2; }  // one past the last quarter rack
  bool covers_quarter(int q) const { return q >= first_quarter() && q < end_quarter(); }
};

struct RioGFile {
  std::array<std::uint16_t, 5> words{};  // words 0-4 (3 and 4 are 0 when the G file has 3 words)
  bool complementary_mode = false;       // word 3 != 0 ("Setting device addresses in word 3 ...")
  std::vector<RioGDevice> devices;       // primary devices in bit order, then complementary ones
};

// A problem with a module's configuration. `rule` quotes the manual.
struct ModuleConfigFinding {
  bool error = true;  // false: a warning
  std::string message;
};

// Decodes a 1747-SN G file and checks every rule of chapter 4 ("Rules for Configuring the
// Scanner", "Concerning Complementary I/O", "Illegal Configuration Examples"). Each violated rule
// adds an error quoting it; the devices are decoded as far as the words allow.
RioGFile decode_rio_g_file(std::span<const std::uint16_t> g, std::vector<ModuleConfigFinding>& findings);

// A scanner's SLOT line, as plain values.
struct RioScannerSlot {
  int slot = 1;
  bool processor_ok = true;  // an SLC 5/02 or later (modular) processor
  std::string processor_name;
  int scan_in = 32;
  int scan_out = 32;
  std::optional<int> m0_size;  // explicit M0_SIZE / M1_SIZE
  std::optional<int> m1_size;
  std::optional<int> id_code;
  bool has_g_file = false;
  std::vector<std::uint16_t> g_file;
  std::map<std::string, std::string> options;
};

// The RIO baud rate the scanner's DIP switches select, as M1 word 2 shows it ("bit 0 = SW1 and
// bit 1 = SW2", on = 1): 57.6K = 3, 115.2K = 1, 230.4K = 2 (or 0, both switches off).
struct RioBaudSetting {
  int kbaud_index = 0;      // 0 = 57.6K, 1 = 115.2K, 2 = 230.4K
  std::uint16_t m1_word2 = 3;
};
// Reads OPTION baud=57.6K|115.2K|230.4K or OPTION dip=on-on|on-off|off-on|off-off (the two
// switches SW1-SW2); the default is 57.6K (both switches on). nullopt when the option is invalid.
std::optional<RioBaudSetting> rio_baud_setting(const std::map<std::string, std::string>& options, std::string* error = nullptr);

// Every configuration check of a scanner slot: placement, processor, image and M-file sizes, ID
// code, options and the G file. A missing G file is a warning (the processor faults with 62H
// when it enters Run, as the real one does).
std::vector<ModuleConfigFinding> check_rio_scanner_slot(const RioScannerSlot& slot);

}  // namespace softslc
