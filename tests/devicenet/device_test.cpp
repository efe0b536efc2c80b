// Simulated devices: the built-in models, the JSON description reader's pathed errors, and the
// explicit-message server's CIP objects and general status codes (the codes and names of chapter 8's
// "CIP Response Error Codes" table, p.99).
#include <gtest/gtest.h>

#include "modules/devicenet/device_model.h"
#include "modules/devicenet/sim_device.h"

namespace softslc::devicenet {
namespace {

constexpr std::uint8_t kGet = 0x0E, kSet = 0x10, kGetAll = 0x01, kReset = 0x05;

CipReply ask(SimDevice& d, std::uint8_t service, std::uint8_t cls, std::uint16_t instance, Bytes body = {}) {
  return d.handle(CipRequest{service, cls, instance, std::move(body)});
}

std::uint8_t status(const CipReply& r) { return r.general_status; }

// ---- built-in models ---------------------------------------------------------------------------------

TEST(BuiltinModels, AllThreeLoad) {
  EXPECT_EQ(builtin_device_names(), (std::vector<std::string>{"series-9000-photoeye", "redistation", "ac-drive"}));
  for (const auto& name : builtin_device_names()) {
    const DeviceModel m = builtin_device_model(name);
    EXPECT_EQ(m.name, name);
  }
  EXPECT_THROW(builtin_device_model("nope"), ConfigError);
}

// The photoeye: "1 byte of input data in response to the strobe message" (p.29), data bit 0 and
// status bit 1 (p.29-30); no outputs.
TEST(BuiltinModels, Photoeye) {
  const DeviceModel m = builtin_device_model("series-9000-photoeye");
  EXPECT_TRUE(m.support(IoType::Strobe).supported);
  EXPECT_EQ(m.support(IoType::Strobe).produce, 1);
  EXPECT_FALSE(m.support(IoType::Poll).supported);
  EXPECT_FALSE(m.support(IoType::Cos).supported);
  EXPECT_EQ(m.input_size(), 1);
  EXPECT_EQ(m.output_size(), 0);
  SimDevice d(m);
  d.set_input("data", true);
  EXPECT_EQ(d.inputs()[0], 0x01);
  d.set_input("status", true);
  EXPECT_EQ(d.inputs()[0], 0x03);
}

// The RediSTATION: polled, 1 byte each way (p.57: "Rx Size and Tx Size are each 1 byte"); stop bit
// 0, start bit 1, bulb missing bit 4, light output bit 0 (p.26-28); outputs off on fault (p.43).
TEST(BuiltinModels, RediStation) {
  const DeviceModel m = builtin_device_model("redistation");
  EXPECT_EQ(m.support(IoType::Poll).produce, 1);
  EXPECT_EQ(m.support(IoType::Poll).consume, 1);
  EXPECT_EQ(m.fault_action, OutputAction::Clear);
  SimDevice d(m);
  for (auto [name, bit] : {std::pair{"stop", 0}, {"start", 1}, {"bulb_missing", 4}}) {
    d.set_input_byte(0, 0);
    d.set_input(name, true);
    EXPECT_EQ(d.inputs()[0], 1u << bit) << name;
  }
  ASSERT_EQ(m.outputs.size(), 1u);
  EXPECT_EQ(m.outputs[0].name, "light");
  EXPECT_EQ(m.outputs[0].bit, 0);
}

// ---- the explicit-message server ----------------------------------------------------------------------

struct Drive : ::testing::Test {
  Drive() : d(builtin_device_model("ac-drive")) { d.set_address(20, Baud::k500); }
  SimDevice d;
};

TEST_F(Drive, IdentityObject) {
  EXPECT_EQ(ask(d, kGet, 1, 1, {1}).data, (Bytes{1, 0}));         // vendor
  EXPECT_EQ(ask(d, kGet, 1, 1, {2}).data, (Bytes{2, 0}));         // device type: AC drive
  EXPECT_EQ(ask(d, kGet, 1, 1, {4}).data, (Bytes{3, 1}));         // revision 3.1
  const Bytes all = ask(d, kGetAll, 1, 1).data;
  EXPECT_EQ(all.size(), 14u + 1u + 16u);  // attributes 1...6 (14 bytes), then "softslc AC Drive"
  EXPECT_EQ(status(ask(d, kGet, 1, 1, {8})), 0x14);
  EXPECT_EQ(status(ask(d, kSet, 1, 1, {1, 5, 0})), 0x0E);  // attribute cannot be set
  EXPECT_EQ(status(ask(d, kGet, 1, 2, {1})), 0x16);        // object does not exist
  EXPECT_EQ(status(ask(d, 0x4B, 1, 1)), 0x08);             // service unsupported
  EXPECT_EQ(status(ask(d, kGet, 1, 1)), 0x13);             // too little data
  EXPECT_EQ(status(ask(d, kGet, 1, 1, {1, 2})), 0x15);     // too much data
  EXPECT_EQ(ask(d, kGet, 1, 0, {1}).data, (Bytes{1, 0}));  // class revision
}

TEST_F(Drive, ResetTypes) {
  const IoType poll[] = {IoType::Poll};
  ASSERT_EQ(d.allocate(poll), SimDevice::AllocateResult::Ok);
  EXPECT_EQ(status(ask(d, kReset, 1, 1, {2})), 0x20);  // invalid parameter
  EXPECT_TRUE(d.allocated());
  EXPECT_TRUE(ask(d, kReset, 1, 1).ok());
  EXPECT_FALSE(d.allocated());
  // Type 1 restores factory defaults.
  EXPECT_TRUE(ask(d, kSet, 0x0F, 39, {1, 0x2C, 0x01}).ok());
  EXPECT_TRUE(ask(d, kReset, 1, 1, {1}).ok());
  EXPECT_EQ(ask(d, kGet, 0x0F, 39, {1}).data, (Bytes{100, 0}));
}

TEST_F(Drive, ParameterObject) {
  EXPECT_EQ(ask(d, kGet, 0x0F, 39, {1}).data, (Bytes{100, 0}));
  EXPECT_TRUE(ask(d, kSet, 0x0F, 39, {1, 0x2C, 0x01}).ok());  // 300
  EXPECT_EQ(ask(d, kGet, 0x0F, 39, {1}).data, (Bytes{0x2C, 0x01}));
  EXPECT_EQ(status(ask(d, kSet, 0x0F, 39, {1, 0xFF, 0xFF})), 0x09);  // 65535 > 36000
  EXPECT_EQ(status(ask(d, kSet, 0x0F, 39, {1, 0x01})), 0x13);
  EXPECT_EQ(status(ask(d, kSet, 0x0F, 39, {1, 1, 2, 3})), 0x15);
  EXPECT_EQ(status(ask(d, kSet, 0x0F, 1, {1, 0, 0})), 0x0E);  // Output Frequency is read only
  EXPECT_EQ(status(ask(d, kSet, 0x0F, 39, {7, 0})), 0x0E);    // the name
  EXPECT_EQ(status(ask(d, kGet, 0x0F, 39, {40})), 0x14);
  EXPECT_EQ(status(ask(d, kGet, 0x0F, 38, {1})), 0x16);
  EXPECT_EQ(status(ask(d, kGetAll, 0x0F, 39)), 0x08);
  // Descriptor bit 4 = read only; data type UINT = C7 hex, 2 bytes; name; min/max/default.
  EXPECT_EQ(ask(d, kGet, 0x0F, 1, {4}).data, (Bytes{0x10, 0}));
  EXPECT_EQ(ask(d, kGet, 0x0F, 39, {4}).data, (Bytes{0x00, 0}));
  EXPECT_EQ(ask(d, kGet, 0x0F, 39, {5}).data, (Bytes{0xC7}));
  EXPECT_EQ(ask(d, kGet, 0x0F, 39, {6}).data, (Bytes{2}));
  const Bytes name = ask(d, kGet, 0x0F, 39, {7}).data;
  EXPECT_EQ(std::string(name.begin() + 1, name.end()), "Accel Time 1");
  EXPECT_EQ(ask(d, kGet, 0x0F, 39, {11}).data, (Bytes{0xA0, 0x8C}));  // 36000
  EXPECT_EQ(ask(d, kGet, 0x0F, 0, {2}).data, (Bytes{60, 0}));          // max instance
  // A signed parameter: INT -500 is 0xFE0C.
  EXPECT_TRUE(ask(d, kSet, 0x0F, 50, {1, 0x0C, 0xFE}).ok());
  EXPECT_EQ(ask(d, kGet, 0x0F, 50, {1}).data, (Bytes{0x0C, 0xFE}));
  EXPECT_EQ(status(ask(d, kSet, 0x0F, 50, {1, 0x00, 0x80})), 0x09);  // -32768 < -1000
}

TEST_F(Drive, AssemblyObject) {
  d.set_input_byte(2, 0x34);
  EXPECT_EQ(ask(d, kGet, 4, 70, {3}).data, (Bytes{0, 0, 0x34, 0}));
  EXPECT_TRUE(ask(d, kSet, 4, 20, {3, 1, 0, 0x10, 0x0E}).ok());  // not connected: allowed
  EXPECT_EQ(d.outputs(), (Bytes{1, 0, 0x10, 0x0E}));
  EXPECT_EQ(status(ask(d, kSet, 4, 20, {3, 1, 0})), 0x13);
  EXPECT_EQ(status(ask(d, kSet, 4, 20, {3, 1, 0, 0, 0, 0})), 0x15);
  EXPECT_EQ(status(ask(d, kSet, 4, 70, {3, 1, 0, 0, 0})), 0x0E);
  const IoType poll[] = {IoType::Poll};
  d.allocate(poll);
  const Bytes run = {1, 0, 0, 0};
  d.consume(IoType::Poll, run);
  EXPECT_EQ(status(ask(d, kSet, 4, 20, {3, 0, 0, 0, 0})), 0x10);  // device state conflict
  EXPECT_EQ(status(ask(d, kGet, 4, 99, {3})), 0x16);
}

TEST_F(Drive, ConnectionObjectReportsSizes) {
  EXPECT_EQ(ask(d, kGet, 5, 2, {7}).data, (Bytes{4, 0}));
  EXPECT_EQ(ask(d, kGet, 5, 2, {8}).data, (Bytes{4, 0}));
  EXPECT_EQ(status(ask(d, kGet, 5, 3, {7})), 0x16);  // no strobe connection
  d.set_produced_size_override(6);
  EXPECT_EQ(ask(d, kGet, 5, 2, {7}).data, (Bytes{6, 0}));
  EXPECT_TRUE(ask(d, kSet, 5, 2, {9, 75, 0}).ok());
  EXPECT_EQ(ask(d, kGet, 5, 2, {9}).data, (Bytes{75, 0}));
  EXPECT_EQ(status(ask(d, kSet, 5, 2, {7, 1, 0})), 0x0E);
}

TEST_F(Drive, VendorObject) {
  const Bytes name = ask(d, kGet, 151, 1, {3}).data;
  EXPECT_EQ(std::string(name.begin() + 1, name.end()), "Conveyor 1");
  EXPECT_TRUE(ask(d, kSet, 151, 1, {3, 2, 'A', 'B'}).ok());
  EXPECT_EQ(ask(d, kGet, 151, 1, {3}).data, (Bytes{2, 'A', 'B'}));
  EXPECT_EQ(status(ask(d, kSet, 151, 1, {3, 3, 'A', 'B'})), 0x13);
  EXPECT_EQ(status(ask(d, kSet, 151, 1, {1, 5, 0})), 0x0E);  // Fault Count not settable
  EXPECT_EQ(status(ask(d, kSet, 151, 1, {4, 2})), 0x09);     // Clear Faults max 1
  EXPECT_EQ(ask(d, kGetAll, 151, 1).data.size(), 2u + 64u + 3u + 1u);
  EXPECT_EQ(status(ask(d, kGet, 151, 2, {1})), 0x16);
  EXPECT_EQ(status(ask(d, kGet, 152, 1, {1})), 0x16);
}

TEST_F(Drive, DeviceNetObject) {
  EXPECT_EQ(ask(d, kGet, 3, 1, {1}).data, (Bytes{20}));
  EXPECT_EQ(ask(d, kGet, 3, 1, {2}).data, (Bytes{2}));  // 500K
  EXPECT_EQ(status(ask(d, kSet, 3, 1, {1, 5})), 0x0E);
}

// Fault and idle actions; the watchdog; offline de-energises outputs.
TEST(SimDeviceIo, OutputStates) {
  SimDevice d(builtin_device_model("redistation"));
  const IoType poll[] = {IoType::Poll};
  EXPECT_FALSE(d.produce(IoType::Poll).has_value());  // not allocated: silent
  ASSERT_EQ(d.allocate(poll), SimDevice::AllocateResult::Ok);
  const Bytes on = {1};
  d.consume(IoType::Poll, on);
  EXPECT_EQ(d.output("light"), true);
  EXPECT_EQ(d.output_state(), OutputState::Run);
  d.consume(IoType::Poll, Bytes{});
  EXPECT_EQ(d.output_state(), OutputState::Idle);
  EXPECT_EQ(d.output("light"), false);
  d.consume(IoType::Poll, on);
  d.master_lost();
  EXPECT_EQ(d.output_state(), OutputState::Fault);
  EXPECT_EQ(d.output("light"), false);
  EXPECT_FALSE(d.allocated());
  EXPECT_EQ(d.allocate(std::span<const IoType>(std::array{IoType::Strobe})), SimDevice::AllocateResult::Refused);
  d.set_online(false);
  EXPECT_EQ(d.allocate(poll), SimDevice::AllocateResult::NoResponse);
  EXPECT_FALSE(d.answers_explicit());
}

// ---- the JSON reader --------------------------------------------------------------------------------

std::string error_path(const std::string& text) {
  try {
    parse_device_model_text(text);
  } catch (const ConfigError& e) {
    return e.path();
  }
  return "(no error)";
}

constexpr const char* kMinimal = R"({"name": "x",
  "identity": {"vendor": 1, "device_type": 7, "product_code": 1, "major": 1, "minor": 1, "product_name": "x"},
  "io": {"poll": {"produce": 2, "consume": 1}}})";

TEST(DeviceJson, MinimalAndDefaults) {
  const DeviceModel m = parse_device_model_text(kMinimal);
  EXPECT_EQ(m.input_size(), 2);
  EXPECT_EQ(m.output_size(), 1);
  EXPECT_EQ(m.io_response_time, microseconds(100));
  EXPECT_EQ(m.idle_action, OutputAction::Clear);
}

TEST(DeviceJson, PathedErrors) {
  const std::string identity =
      R"("identity": {"vendor": 1, "device_type": 7, "product_code": 1, "major": 1, "minor": 1, "product_name": "x"})";
  EXPECT_EQ(error_path(R"({"name": "x", "io": {}})"), "identity");
  EXPECT_EQ(error_path(R"({"name": "x", )" + identity + R"(, "io": {"poll": {"produces": 1}}})"), "io.poll.produces");
  EXPECT_EQ(error_path(R"({"name": "x", )" + identity + R"(, "io": {"poll": {"produce": 256}}})"), "io.poll.produce");
  EXPECT_EQ(error_path(R"({"name": "x", )" + identity + R"(, "io": {"strobe": {"produce": 9}}})"), "io.strobe.produce");
  EXPECT_EQ(error_path(R"({"name": "x", )" + identity +
                       R"(, "io": {"poll": {"produce": 1}}, "inputs": [{"name": "a", "byte": 1, "bit": 0}]})"),
            "inputs[0].byte");
  EXPECT_EQ(error_path(R"({"name": "x", )" + identity +
                       R"(, "io": {"poll": {"produce": 1}}, "parameters": [{"number": 1, "name": "p", "type": "USINT", "default": 9, "max": 5}]})"),
            "parameters[0].default");
  EXPECT_EQ(error_path(R"({"name": "x", )" + identity +
                       R"(, "io": {"poll": {"produce": 1}}, "parameters": [{"number": 1, "name": "p", "type": "REAL", "default": 0}]})"),
            "parameters[0].type");
  EXPECT_EQ(error_path(R"({"name": "x", )" + identity +
                       R"(, "io": {"poll": {"produce": 1}}, "objects": [{"class": 15, "instances": []}]})"),
            "objects[0].class");
  EXPECT_EQ(error_path(R"({"name": "x", )" + identity +
                       R"(, "io": {"poll": {"produce": 1}}, "objects": [{"class": 100}, {"class": 100}]})"),
            "objects[1].class");
  EXPECT_EQ(error_path(R"({"name": "x", )" + identity +
                       R"(, "io": {"poll": {"produce": 1}}, "objects": [{"class": 100, "instances": [{"instance": 1, "attributes": [{"id": 1, "type": "USINT", "value": 300}]}]}]})"),
            "objects[0].instances[0].attributes[0].value");
  EXPECT_EQ(error_path(R"({"name": "x", )" + identity + R"(, "io": {"poll": {"produce": 1}}, "fault_action": "keep"})"),
            "fault_action");
  EXPECT_EQ(error_path(R"({"name": "x", )" + identity +
                       R"(, "io": {"cos": {"produce": 1}, "cyclic": {"produce": 2}}})"),
            "io.cyclic");
  EXPECT_EQ(error_path("{not json"), "");
  try {
    parse_device_model_text(R"({"name": "x", )" + identity + R"(, "io": {"poll": {"produces": 1}}})");
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("io.poll.produces: unknown key"), std::string::npos) << e.what();
  }
}

TEST(CipTables, NamesAndTypes) {
  EXPECT_EQ(cip_status_name(0x14), "Attribute not supported");
  EXPECT_EQ(cip_status_name(0x16), "Object does not exist");
  EXPECT_FALSE(cip_status_listed(0x00));
  EXPECT_FALSE(cip_status_listed(0x12));
  EXPECT_EQ(cip_type_code(CipType::Uint), 0xC7);
  EXPECT_EQ(cip_type_min(CipType::Int), -32768);
  EXPECT_EQ(cip_type_max(CipType::Udint), 0xFFFFFFFFLL);
  EXPECT_EQ(parse_cip_type("SHORT_STRING"), CipType::ShortString);
  EXPECT_EQ(reply_service(0x0E, CipReply::success()), 0x8E);
  EXPECT_EQ(reply_service(0x0E, CipReply::error(CipStatus::TooMuchData)), 0x94);
  EXPECT_EQ(reply_bytes(CipReply::error(CipStatus::TooMuchData)), (Bytes{0x15, 0xFF}));
}

}  // namespace
}  // namespace softslc::devicenet
