// The fuzz targets' properties (tests/fuzz/serve_properties.h) on the frames of the other serve
// tests and on every truncation and single-byte change of them, so the properties run in every
// ctest and not only under libFuzzer.
#include <gtest/gtest.h>

#include "tests/fuzz/serve_properties.h"
#include "tests/serve/serve_test_util.h"

namespace softslc::serve::testing {
namespace {

std::string str(const Bytes& b) { return std::string(b.begin(), b.end()); }

void check_mutations(const Bytes& seed, std::string (*property)(std::string_view)) {
  for (std::size_t n = 0; n <= seed.size(); ++n) EXPECT_EQ(property(str(Bytes(seed.begin(), seed.begin() + static_cast<std::ptrdiff_t>(n)))), "") << "prefix " << n;
  for (std::size_t i = 0; i < seed.size(); ++i) {
    for (const std::uint8_t v : {0x00, 0x01, 0x7F, 0x80, 0xFE, 0xFF}) {
      Bytes m = seed;
      m[i] = v;
      EXPECT_EQ(property(str(m)), "") << "byte " << i << " = " << int(v);
    }
  }
}

TEST(ServeFuzzProperties, PcccCommands) {
  check_mutations({0x0F, 0x00, 0x34, 0x12, 0xA2, 0x02, 0x07, 0x89, 0x00, 0x00}, fuzz::check_pccc_property);
  check_mutations({0x0F, 0x00, 0x01, 0x00, 0xAB, 0x02, 0x03, 0x85, 0x00, 0x00, 0x02, 0x00, 0x02, 0x00}, fuzz::check_pccc_property);
  check_mutations({0x0F, 0x00, 0x01, 0x00, 0xAA, 0x04, 0x08, 0x8A, 0xFF, 0x01, 0x00, 0x00, 0x00, 0x00, 0x48, 0x41}, fuzz::check_pccc_property);
  check_mutations({0x06, 0x00, 0x01, 0x00, 0x03}, fuzz::check_pccc_property);
}

TEST(ServeFuzzProperties, EncapsulationFrames) {
  check_mutations(register_session_frame(), fuzz::check_eip_property);
  const Bytes rr = execute_pccc_frame(7, {0x0F, 0x00, 0x34, 0x12, 0xA2, 0x02, 0x07, 0x89, 0x00, 0x00});
  check_mutations(rr, fuzz::check_eip_property);
  check_mutations(Bytes(rr.begin() + 30, rr.end()), fuzz::check_eip_property);  // the CPF alone
  check_mutations(header(0x63, 0, 0), fuzz::check_eip_property);
}

TEST(ServeFuzzProperties, ModbusFrames) {
  check_mutations({0x00, 0x01, 0x00, 0x00, 0x00, 0x06, 0x01, 0x03, 0x00, 0x00, 0x00, 0x02}, fuzz::check_modbus_property);
  check_mutations({0x00, 0x02, 0x00, 0x00, 0x00, 0x06, 0x01, 0x05, 0x00, 0x01, 0xFF, 0x00}, fuzz::check_modbus_property);
  check_mutations({0x00, 0x03, 0x00, 0x00, 0x00, 0x0B, 0x01, 0x10, 0x00, 0x05, 0x00, 0x02, 0x04, 0x00, 0x07, 0x00, 0x08},
                  fuzz::check_modbus_property);
  check_mutations({0x00, 0x04, 0x00, 0x00, 0x00, 0x08, 0x01, 0x0F, 0x00, 0x00, 0x00, 0x0A, 0x02, 0xFF, 0x03},
                  fuzz::check_modbus_property);
}

// The first byte is how the line delivers the rest (serve_properties.h): 3Fh one chunk, 7Fh one
// chunk then silence, 40h a byte at a time with a silence after each (every frame cut short).
TEST(ServeFuzzProperties, ModbusRtuFrames) {
  const Bytes read = {0x01, 0x03, 0x00, 0x00, 0x00, 0x02, 0xC4, 0x0B};
  const Bytes write_echo = {0x01, 0x10, 0x00, 0x00, 0x00, 0x02, 0x04, 0x00, 0x07, 0x00, 0x08, 0x43, 0xA8,
                            0x01, 0x08, 0x00, 0x00, 0xA5, 0x37, 0xDA, 0x8D};
  for (const std::uint8_t how : {0x3F, 0x7F, 0x40, 0x01, 0x43}) {
    check_mutations(cat({{how}, read}), fuzz::check_modbus_rtu_property);
    check_mutations(cat({{how}, write_echo}), fuzz::check_modbus_rtu_property);
  }
}

TEST(ServeFuzzProperties, WebRequests) {
  for (const char* request : {R"({"op":"view","file":2,"first":0,"last":30})", R"({"op":"table","name":"N7","offset":3})",
                              R"({"op":"set","address":"N7:0","value":"12"})", R"({"op":"force","address":"I:1/0","state":"on"})",
                              R"({"op":"trend","addresses":["N7:0","T4:0.ACC"]})", R"({"op":"mode","mode":"run"})",
                              R"({"op":"step","scans":2})", R"({"op":"table","name":"M1:1"})"}) {
    const std::string r = request;
    check_mutations(Bytes(r.begin(), r.end()), fuzz::check_web_property);
  }
}

}  // namespace
}  // namespace softslc::serve::testing
