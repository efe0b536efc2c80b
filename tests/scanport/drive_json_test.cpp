// The JSON drive description loader: the shipped drive loads, and every kind of mistake is
// reported with its place (a JSON path, or line:column with the source line and a caret).
#include <cstdio>
#include <fstream>
#include <functional>

#include <nlohmann/json.hpp>

#include "tests/scanport/scanport_test_util.h"

namespace softslc::scanport::test {
namespace {

using nlohmann::json;

// A small valid description to break one field at a time.
json minimal() {
  return json::parse(R"({
    "schema": "softslc-scanport-drive-1",
    "name": "tiny",
    "product": {"number": 1, "text": "Tiny", "series": 2, "software_versions": [100, 101]},
    "parameters": [
      {"number": 1, "name": "Speed", "units": "RPM", "min": 0, "max": 1800, "default": 0},
      {"number": 2, "name": "Mode", "descriptor": ["enum"], "min": 0, "max": 1, "default": 0, "enums": ["Off", "On"]},
      {"number": 3, "name": "Status", "descriptor": ["read_only"], "min": 0, "max": 65535, "default": 0}
    ]
  })");
}

// The loader's message for `j`, or "" when it loads.
std::string error_of(const json& j) {
  try {
    parse_drive_description(j.dump(), "tiny.json");
  } catch (const DriveDescriptionError& e) {
    return e.what();
  }
  return "";
}

std::string error_of_text(std::string_view text) {
  try {
    parse_drive_description(text, "bad.json");
  } catch (const DriveDescriptionError& e) {
    return e.what();
  }
  return "";
}

TEST(DriveJson, MinimalDescriptionAndDefaults) {
  const DriveDescription d = parse_drive_description(minimal().dump());
  ASSERT_EQ(d.parameters.size(), 3u);
  const auto& p = d.parameters[0];
  EXPECT_EQ(p.type, DataType::kUnsigned16);
  EXPECT_EQ(p.value, p.default_value);
  EXPECT_EQ(p.scaling.divisor, 1);
  EXPECT_EQ(d.product.software_versions, (std::vector<std::uint16_t>{100, 101}));
  for (int k = 0; k < kObjectKindCount; ++k) EXPECT_EQ(d.response_padding[k], 1);
  EXPECT_TRUE(d.optional_features.empty());
  // A drive built from it answers on both microprocessors.
  Drive drive(d);
  EXPECT_EQ(encode_response(transact(&drive, make_request(0x0E, 0x92, 2, 1)))[5], 101);
}

TEST(DriveJson, ShippedDriveIsEmbeddedAndIdenticalToTheFile) {
  const std::string path = std::string(SOFTSLC_SOURCE_DIR) + "/modules/scanport/drives/1305.json";
  std::ifstream in(path);
  ASSERT_TRUE(in) << path;
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(builtin_drive_json("1305"), text);
  EXPECT_EQ(load_drive_description_file(path).parameters.size(), 216u);
  EXPECT_TRUE(builtin_drive_json("1336").empty());
  EXPECT_THROW(builtin_drive("1336"), DriveDescriptionError);
}

TEST(DriveJson, SyntaxErrorsShowLineColumnAndCaret) {
  const std::string msg = error_of_text("{\n  \"schema\": \"softslc-scanport-drive-1\",\n  \"name\": ,\n}\n");
  EXPECT_EQ(msg.rfind("bad.json:3:11: ", 0), 0u) << msg;
  // The line, indented by two, and a caret under column 11.
  EXPECT_NE(msg.find("\n    \"name\": ,\n" + std::string(2 + 10, ' ') + "^"), std::string::npos) << msg;
  EXPECT_EQ(error_of_text("").rfind("bad.json:1:1: ", 0), 0u);
}

TEST(DriveJson, FieldErrorsNameTheirPath) {
  struct Case {
    const char* what;
    std::function<void(json&)> edit;
    const char* message;
  };
  const Case cases[] = {
      {"wrong schema", [](json& j) { j["schema"] = "x"; }, "tiny.json: schema: expected \"softslc-scanport-drive-1\""},
      {"missing name", [](json& j) { j.erase("name"); }, "tiny.json: (top): missing \"name\""},
      {"unknown top key", [](json& j) { j["parameter"] = 1; }, "tiny.json: parameter: unknown key"},
      {"max not an integer", [](json& j) { j["parameters"][2]["max"] = "big"; },
       "tiny.json: parameters[2].max: expected an integer"},
      {"fractional min", [](json& j) { j["parameters"][0]["min"] = 0.5; },
       "tiny.json: parameters[0].min: expected an integer"},
      {"misspelt key", [](json& j) { j["parameters"][1]["maxx"] = 1; }, "tiny.json: parameters[1].maxx: unknown key"},
      {"numbers out of order", [](json& j) { j["parameters"][1]["number"] = 3; },
       "tiny.json: parameters[1].number: expected 2 (parameters are listed in order from 1)"},
      {"name too long", [](json& j) { j["parameters"][0]["name"] = "Seventeen chars!!"; },
       "tiny.json: parameters[0].name: \"Seventeen chars!!\" is longer than 16 characters"},
      {"units too long", [](json& j) { j["parameters"][0]["units"] = "Volts"; },
       "tiny.json: parameters[0].units: \"Volts\" is longer than 4 characters"},
      {"enum too long", [](json& j) { j["parameters"][1]["enums"][1] = "Thirteen char"; },
       "tiny.json: parameters[1].enums[1]: \"Thirteen char\" is longer than 12 characters"},
      {"non-ASCII name", [](json& j) { j["parameters"][0]["name"] = "Vitesse \xc3\xa9"; },
       "tiny.json: parameters[0].name: only printable ASCII"},
      {"default above max", [](json& j) { j["parameters"][0]["default"] = 1801; },
       "tiny.json: parameters[0].default: 1801 is above max 1800"},
      {"value below min", [](json& j) { j["parameters"][0]["value"] = -1; },
       "tiny.json: parameters[0].value: -1 is below min 0"},
      {"max outside the data type", [](json& j) { j["parameters"][0]["max"] = 70000; },
       "tiny.json: parameters[0].max: 70000 does not fit data type 2 (0..65535)"},
      {"min above max", [](json& j) { j["parameters"][0]["min"] = 1900; },
       "tiny.json: parameters[0].max: 1800 is below min 1900"},
      {"data type 9", [](json& j) { j["parameters"][0]["data_type"] = 9; },
       "tiny.json: parameters[0].data_type: expected an integer 1..8, got 9"},
      {"unknown descriptor bit", [](json& j) { j["parameters"][0]["descriptor"] = {"scaling", "fast"}; },
       "tiny.json: parameters[0].descriptor[1]: unknown descriptor bit \"fast\""},
      {"enum bit without strings", [](json& j) { j["parameters"][1].erase("enums"); },
       "tiny.json: parameters[1].enums: descriptor has \"enum\" but no enum strings are given"},
      {"strings without enum bit", [](json& j) { j["parameters"][0]["enums"] = {"A"}; },
       "tiny.json: parameters[0].enums: enum strings need \"enum\" in the descriptor"},
      {"zero divisor", [](json& j) { j["parameters"][0]["scaling"] = {{"divisor", 0}}; },
       "tiny.json: parameters[0].scaling.divisor: must not be 0"},
      {"unknown scaling key", [](json& j) { j["parameters"][0]["scaling"] = {{"gain", 2}}; },
       "tiny.json: parameters[0].scaling.gain: unknown key"},
      {"precision 10", [](json& j) { j["parameters"][0]["scaling"] = {{"precision", 10}}; },
       "tiny.json: parameters[0].scaling.precision: expected 0-9 decimal places"},
      {"scaling link to nowhere", [](json& j) { j["parameters"][0]["scaling"] = {{"base_link", 4}}; },
       "tiny.json: parameters[0].scaling.base_link: 4 is not a parameter number (1-3) or 0"},
      {"link to itself", [](json& j) { j["parameters"][0]["link"] = 1; },
       "tiny.json: parameters[0].link: a parameter cannot be linked to itself"},
      {"link to nowhere", [](json& j) { j["parameters"][0]["default_link"] = 9; },
       "tiny.json: parameters[0].default_link: 9 is not a parameter number"},
      {"no microprocessor", [](json& j) { j["product"]["software_versions"] = json::array(); },
       "tiny.json: product.software_versions: a product has at least one microprocessor"},
      {"product text too long", [](json& j) { j["product"]["text"] = "Seventeen chars!!"; },
       "tiny.json: product.text: \"Seventeen chars!!\" is longer than 16 characters"},
      {"unknown optional service", [](json& j) { j["optional_services"] = {"teleport"}; },
       "tiny.json: optional_services: unknown optional service \"teleport\""},
      {"unknown padding object", [](json& j) { j["response_padding"] = {{"products", 6}}; },
       "tiny.json: response_padding.products: unknown object"},
      {"padding 0", [](json& j) { j["response_padding"] = {{"product", 0}}; },
       "tiny.json: response_padding.product: expected an integer 1..64, got 0"},
      {"bit used twice", [](json& j) { j["logic_command_bits"] = {{"stop", 0}, {"start", 0}}; },
       "tiny.json: logic_command_bits.start: bit 0 is already used by another function"},
      {"bit 16", [](json& j) { j["logic_status_bits"] = {{"running", 16}}; },
       "tiny.json: logic_status_bits.running: expected an integer 0..15, got 16"},
      {"unknown function", [](json& j) { j["logic_command_bits"] = {{"jump", 2}}; },
       "tiny.json: logic_command_bits.jump: unknown function"},
      {"role on a writable parameter", [](json& j) { j["roles"] = {{"output_frequency", 1}}; },
       "tiny.json: roles.output_frequency: parameter 1 is written by the drive, so it must be read_only"},
      {"unknown role", [](json& j) { j["roles"] = {{"torque", 3}}; }, "tiny.json: roles.torque: unknown role"},
      {"seven datalinks", [](json& j) { j["datalinks"] = {{"data_in", {1, 2, 3, 0, 0, 0, 0}}}; },
       "tiny.json: datalinks.data_in: expected 8 parameter numbers"},
      {"datalink to nowhere", [](json& j) { j["datalinks"] = {{"data_out", {0, 0, 0, 0, 0, 0, 0, 4}}}; },
       "tiny.json: datalinks.data_out[7]: 4 is not a parameter number"},
      {"unstable speed step",
       [](json& j) { j["speed_response"] = {{"time_constant_us", 500}, {"update_period_us", 1000}}; },
       "tiny.json: speed_response.time_constant_us: must be at least update_period_us"},
      {"processing time negative", [](json& j) { j["message_processing_us"] = -1; },
       "tiny.json: message_processing_us: expected an integer 0..10000000, got -1"},
      {"no parameters", [](json& j) { j["parameters"] = json::array(); },
       "tiny.json: parameters: a drive has at least one parameter"},
      {"parameters not an array", [](json& j) { j["parameters"] = json::object(); },
       "tiny.json: parameters: expected an array"},
      {"stopped_only not a bool", [](json& j) { j["parameters"][0]["stopped_only"] = 1; },
       "tiny.json: parameters[0].stopped_only: expected true or false"},
  };
  ASSERT_EQ(error_of(minimal()), "");
  for (const auto& c : cases) {
    json j = minimal();
    c.edit(j);
    const std::string msg = error_of(j);
    EXPECT_EQ(msg.rfind(c.message, 0), 0u) << c.what << "\n  got: " << msg << "\n  want: " << c.message;
  }
}

TEST(DriveJson, SignedAndWideTypes) {
  json j = minimal();
  j["parameters"][0] = {{"number", 1}, {"name", "Torque"}, {"data_type", 3},
                        {"min", -32768},  {"max", 32767},      {"default", -5}};
  j["parameters"][1] = {{"number", 2}, {"name", "Position"}, {"data_type", 7}, {"min", -9000000000LL},
                        {"max", 9000000000LL}, {"default", 8000000000LL}};
  j["parameters"][2] = {{"number", 3}, {"name", "Small"}, {"data_type", 5},
                        {"min", -128},   {"max", 127},       {"default", -1}};
  Drive d(parse_drive_description(j.dump()));
  // A 16-bit signed value: 0xFFFB. An 8-byte value: 8 bytes, low first. A short: one byte.
  EXPECT_EQ(hex(first(encode_response(transact(&d, make_request(0x0E, 0x0F, 1, 1))), 6)),
            hex({0x000e, 0x000f, 1, 1, 2, 0xfffb}));
  const Response wide = transact(&d, make_request(0x0E, 0x0F, 2, 1));
  ASSERT_EQ(wide.data.size(), 8u);
  std::int64_t v = 0;
  for (int i = 7; i >= 0; --i) v = (v << 8) | wide.data[static_cast<std::size_t>(i)];
  EXPECT_EQ(v, 8000000000LL);
  EXPECT_EQ(transact(&d, make_request(0x0E, 0x0F, 3, 1)).data, std::vector<std::uint8_t>{0xFF});
  // Read Full Parameter with 8-byte value, min, max and default: 53 - 4 x 2 + 4 x 8 = 77 bytes.
  EXPECT_EQ(transact(&d, make_request(0x01, 0x0F, 2, 0)).data.size(), 77u);
  // Writes take the type's width and sign.
  EXPECT_EQ(transact(&d, make_request(0x10, 0x0F, 3, 1, {0x80})).error(), ErrorCode::kNone);
  EXPECT_EQ(d.value(3), -128);
  EXPECT_EQ(transact(&d, make_request(0x10, 0x0F, 2, 1, {0, 0, 0, 0, 0, 0, 0, 0x80})).error(),
            ErrorCode::kValueOutOfRange);  // INT64_MIN < min
  // Scattered entries carry 16 bits: a wider parameter answers 5 in its entry.
  EXPECT_EQ(hex(encode_response(transact(&d, make_request(0x32, 0x93, 0, 0, bytes_of({2, 0, 3, 0}))))),
            hex({0x0032, 0x0093, 0, 0, 8, 0x8002, 5, 3, 0xFF80}));
  // Wrong JSON types for a wide value are still caught.
  j["parameters"][1]["max"] = 18446744073709551615ULL;
  EXPECT_NE(error_of(j).find("parameters[1].max: expected an integer"), std::string::npos);
}

TEST(DriveJson, FileErrors) {
  EXPECT_EQ(std::string(
                [] {
                  try {
                    load_drive_description_file("/nonexistent/drive.json");
                  } catch (const DriveDescriptionError& e) {
                    return std::string(e.what());
                  }
                  return std::string();
                }()),
            "/nonexistent/drive.json: cannot open the file");
}

TEST(DriveJson, ProgrammaticDescriptionsAreValidatedToo) {
  DriveDescription desc = builtin_drive("1305");
  desc.parameters[6].default_value = 70000;
  EXPECT_THROW(Drive{desc}, DriveDescriptionError);
  try {
    Drive d(desc);
  } catch (const DriveDescriptionError& e) {
    EXPECT_EQ(std::string(e.what()), "parameters[6].default: 70000 is above max 60000");
  }
}

}  // namespace
}  // namespace softslc::scanport::test
