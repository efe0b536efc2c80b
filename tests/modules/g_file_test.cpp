// The 1747-SN configuration rules (1747-SN manual, chapter 4, "Rules for Configuring the
// Scanner", "Concerning Complementary I/O", "Illegal Configuration Examples"; chapters 1, 2, 6).
// Each illegal configuration is rejected with the manual's rule quoted; the manual's legal
// examples are accepted.
#include <gtest/gtest.h>

#include "instructions/module_catalog.h"
#include "modules/module_setup.h"
#include "parser/loader.h"

namespace softslc {
namespace {

std::vector<ModuleConfigFinding> decode(std::vector<std::uint16_t> g, RioGFile* out = nullptr) {
  std::vector<ModuleConfigFinding> f;
  RioGFile r = decode_rio_g_file(g, f);
  if (out) *out = r;
  return f;
}

std::string errors(const std::vector<ModuleConfigFinding>& f) {
  std::string s;
  for (const auto& x : f)
    if (x.error) s += x.message + "\n";
  return s;
}

// Chapter 4, "Example G File Showing Primary and Complementary Device Configurations":
// word 0 = 0010 0000 0010 0000; word 1 racks 3..0 = 1010 0001 1000 0010; word 2 = 1010 0111 1000
// 1110; word 3 = 0010 0001 1001 0010; word 4 = 0110 0001 1011 1110.
const std::vector<std::uint16_t> kManualExample = {0x2020, 0xA182, 0xA78E, 0x2192, 0x61BE};

TEST(GFile, TheManualsComplementaryExampleIsLegal) {
  RioGFile g;
  EXPECT_EQ(errors(decode(kManualExample, &g)), "");
  EXPECT_TRUE(g.complementary_mode);
  ASSERT_EQ(g.devices.size(), 10u);
  // "Logical Racks 0/8, Logical Group 2 contain a primary 3/4 logical rack device, and a
  // complementary 3/4 logical rack device."
  EXPECT_EQ(g.devices[0].rack, 0);
  EXPECT_EQ(g.devices[0].group, 2);
  EXPECT_EQ(g.devices[0].groups, 6);
  EXPECT_FALSE(g.devices[0].complementary);
  // "Logical Racks 3/11, Logical Group 2 contain a primary 1/4 logical rack device, and a
  // complementary 1/2 logical rack device."
  const auto& c = g.devices[9];
  EXPECT_TRUE(c.complementary);
  EXPECT_EQ(c.rack, 3);
  EXPECT_EQ(c.group, 2);
  EXPECT_EQ(c.groups, 4);
}

TEST(GFile, IllegalPrimaryInsideAComplementaryImage) {
  // "Having a primary device configured at Logical Rack 1, Logical Group 2 (bit 5) would be
  // illegal since this image space is already being used by a complementary device."
  auto g = kManualExample;
  g[1] |= 1u << 5;
  g[2] |= 1u << 5;
  const std::string e = errors(decode(g));
  EXPECT_NE(e.find("primary 1/4 logical rack device at logical rack 1 group 2"), std::string::npos) << e;
  EXPECT_NE(e.find("must not 'cross over' into the space of a primary device"), std::string::npos) << e;
}

TEST(GFile, IllegalComplementaryInsideAPrimaryImage) {
  // "Having a complementary device configured at Logical Rack 10, Logical Group 2 (bit 9) would
  // also be illegal since this image space is already being used by a primary device."
  auto g = kManualExample;
  g[3] |= 1u << 9;
  g[4] |= 1u << 9;
  const std::string e = errors(decode(g));
  EXPECT_NE(e.find("complementary 1/4 logical rack device at logical rack 10 group 2"), std::string::npos) << e;
  EXPECT_NE(e.find("A complementary device cannot be configured at locations where primary devices are configured "
                   "unless they both start at the same location."),
            std::string::npos)
      << e;
}

TEST(GFile, ComplementaryDeviceMayNotCrossIntoAPrimaryDevice) {
  // "if a primary device exists at Logical Rack 1 Logical Group 4, the maximum size of a
  // complementary device at Logical Rack 9 Logical Group 0 is a half logical rack".
  std::vector<std::uint16_t> g = {0, 1u << 6, 1u << 6, 1u << 4, 0x0070};  // comp r9g0 3/4
  EXPECT_NE(errors(decode(g)).find("cross over"), std::string::npos);
  g[4] = 0x0030;  // a half rack: legal
  EXPECT_EQ(errors(decode(g)), "");
}

TEST(GFile, DeviceWithoutImage) {
  const std::string e = errors(decode({0, 0x0001, 0x0000}));
  EXPECT_NE(e.find("\"If a device is configured in word 1, there must be image allocated to it in word 2.\""),
            std::string::npos)
      << e;
  EXPECT_NE(errors(decode({0, 1, 1, 0x0010, 0})).find("configured in word 3, there must be image allocated to it in word 4"),
            std::string::npos);
}

TEST(GFile, ImageWithoutDevice) {
  const std::string e = errors(decode({0, 0x0001, 0x0007 | 0x0100}));
  EXPECT_NE(e.find("word 2 bit 8 allocates image at logical rack 2 group 0 to no device"), std::string::npos) << e;
}

TEST(GFile, NoDeviceAtAll) {
  // "G file words 1 and 2 can both be zero (no primary devices). However, in this case there
  // must be at least one complementary device configured in G file words 3 and 4."
  EXPECT_NE(errors(decode({0, 0, 0})).find("at least one complementary device"), std::string::npos);
  EXPECT_NE(errors(decode({0, 0, 0, 1, 0})).find("at least one complementary device"), std::string::npos);
  EXPECT_EQ(errors(decode({0, 0, 0, 0x0001, 0x0003})), "");  // complementary devices only: legal
}

TEST(GFile, ComplementaryModeWithoutComplementaryDevices) {
  // "if word 3 = 1 and word 4 = 0, the complementary mode is selected even though no
  // complementary devices are configured."
  RioGFile g;
  EXPECT_EQ(errors(decode({0, 0x0011, 0x00FF, 1, 0}, &g)), "");
  EXPECT_TRUE(g.complementary_mode);
  ASSERT_EQ(g.devices.size(), 2u);
  EXPECT_FALSE(g.devices[1].complementary);
  // "words 3 and 4 can both be zero, or the G file size can be set to 3".
  EXPECT_EQ(errors(decode({0, 0x0011, 0x00FF, 0, 0}, &g)), "");
  EXPECT_FALSE(g.complementary_mode);
}

TEST(GFile, Size) {
  EXPECT_NE(errors(decode({0, 1, 1, 0})).find("Set the G file size to 3 (5 if using complementary I/O)"),
            std::string::npos);
}

TEST(GFile, DevicesCrossRackBoundaries) {
  // Chapter 4, "Creating More than One Logical Rack Device": an adapter at rack 0 group 0 with 14
  // words of image.
  RioGFile g;
  EXPECT_EQ(errors(decode({0, 0x0001, 0x007F}, &g)), "");
  ASSERT_EQ(g.devices.size(), 1u);
  EXPECT_EQ(g.devices[0].groups, 14);
}

// ---- The checks of a whole SLOT line, as `softslc check` reports them ---------------------------

std::string check(const std::string& slot_line, const std::string& processor = "1747-L532") {
  LoadResult lr = load_program("START " + processor + "\n" + slot_line + "\nLADDER 2\nSOR XIC B3:0/0 OTE B3:0/1 EOR\n", "c.slc");
  EXPECT_TRUE(lr.ok()) << lr.render_diagnostics();
  DiagnosticList d;
  check_module_configuration(*lr.program, d);
  return render_all(d, "c.slc", lr.source);
}

TEST(SnSlotCheck, AValidScannerHasNoDiagnostics) {
  EXPECT_EQ(check("SLOT 1 1747-SN SCAN_IN 32 SCAN_OUT 32 G_FILE 3\n 0 1 15"), "");
  EXPECT_EQ(check("SLOT 2 OTHER SCAN_IN 8 SCAN_OUT 8 ID_CODE 13608 G_FILE 3\n 0 1 3 OPTION baud=230.4K"), "");
}

TEST(SnSlotCheck, EveryRuleIsPositionedAtTheSlotLineAndQuotesTheManual) {
  EXPECT_EQ(check("SLOT 1 1747-SN SCAN_IN 32 SCAN_OUT 32 G_FILE 3\n 0 0 0"),
            "c.slc:2:6: error: 1747-SN in slot 1: the G file configures no device: words 1 and 2 are both zero and "
            "complementary I/O is not selected; \"G file words 1 and 2 can both be zero (no primary devices). "
            "However, in this case there must be at least one complementary device configured in G file words 3 and "
            "4.\" (1747-SN manual ch. 4, \"Concerning Complementary I/O\")\n"
            "SLOT 1 1747-SN SCAN_IN 32 SCAN_OUT 32 G_FILE 3\n     ^\n");
  EXPECT_NE(check("SLOT 0 1747-SN SCAN_IN 32 SCAN_OUT 32 G_FILE 3\n 0 1 1").find("except for slot 0"), std::string::npos);
  EXPECT_NE(check("SLOT 1 1747-SN SCAN_IN 0 SCAN_OUT 32 G_FILE 3\n 0 1 1").find("Do not set either of these values to 0"),
            std::string::npos);
  EXPECT_NE(check("SLOT 1 1747-SN SCAN_IN 40 SCAN_OUT 32 G_FILE 3\n 0 1 1").find("up to 32 words"), std::string::npos);
  EXPECT_NE(check("SLOT 1 1747-SN SCAN_IN 32 SCAN_OUT 32 ID_CODE 3516 G_FILE 3\n 0 1 1").find("(13608)"),
            std::string::npos);
  EXPECT_NE(check("SLOT 1 1747-SN SCAN_IN 32 SCAN_OUT 32 G_FILE 3\n 0 1 1", "1747-L511").find("SLC 5/02 or later"),
            std::string::npos);
  EXPECT_NE(check("SLOT 1 1747-SN SCAN_IN 32 SCAN_OUT 32 OPTION baud=9600 G_FILE 3\n 0 1 1").find("57.6K, 115.2K or 230.4K"),
            std::string::npos);
}

TEST(SnSlotCheck, WarningsForWhatStillLoads) {
  // A missing G file loads; the processor faults with 62H at Run entry.
  EXPECT_NE(check("SLOT 1 1747-SN SCAN_IN 32 SCAN_OUT 32").find("warning: 1747-SN in slot 1: the 1747-SN has no G file"),
            std::string::npos);
  // "32 words is the minimum required for operation" (48 with complementary I/O).
  EXPECT_NE(check("SLOT 1 1747-SN SCAN_IN 32 SCAN_OUT 32 M0_SIZE 16 G_FILE 3\n 0 1 1").find("warning: 1747-SN in slot 1: M0_SIZE 16"),
            std::string::npos);
  EXPECT_NE(check("SLOT 1 1747-SN SCAN_IN 32 SCAN_OUT 32 M0_SIZE 40 M1_SIZE 48 G_FILE 5\n 0 1 1 1 0").find("M0_SIZE 40 is below the scanner's minimum of 48"),
            std::string::npos);
  // A device beyond the scanned image words.
  EXPECT_NE(check("SLOT 1 1747-SN SCAN_IN 8 SCAN_OUT 8 G_FILE 3\n 0 16 16").find("warning"), std::string::npos);
}

}  // namespace
}  // namespace softslc
