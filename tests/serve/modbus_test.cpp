// `softslc serve --modbus`: Modbus TCP as a MicroLogix 1400 channel configured as a Modbus slave
// answers it (server/modbus.h), on the shipped example examples/ladder/micrologix/ml1400_batch.slc
// with the map B3 (coils and contacts), N7 (input and holding registers).
//
// The client is Debian's libmodbus — an implementation independent of softslc's — on loopback,
// against the real server (its io_context in a second thread). Expected values come from the
// program (DATA N7:0 500, the rungs), the map from 1763-RM001C p. 530 / 1766-RM001A p. 617
// ("Modbus to MicroLogix Memory Map - Summary"), the exception codes from the Modbus Application
// Protocol v1.1b3 §7.
#include <gtest/gtest.h>
#include <modbus.h>

#include <cerrno>
#include <chrono>

#include "server/server.h"
#include "tests/serve/modbus_test_util.h"

namespace softslc::serve::testing {
namespace {

using Bytes = std::vector<std::uint8_t>;

class ModbusServerTest : public ModbusClientTest {
 protected:
  void start(const LiveOptions& lo = {}) {
    ServerOptions so;
    so.modbus_port = 0;
    so.idle_timeout = std::chrono::milliseconds(2000);
    start_server(so, lo);
    ctx_ = modbus_new_tcp("127.0.0.1", server_->modbus_port());
    ASSERT_NE(ctx_, nullptr);
    modbus_set_response_timeout(ctx_, 2, 0);
    ASSERT_EQ(modbus_connect(ctx_), 0) << modbus_strerror(errno);
  }
};

TEST_F(ModbusServerTest, RegistersAndCoilsAreTheMappedFiles) {
  start();
  // Holding registers 40001-40002 = N7:0-1 (DATA N7:0 500 0); input registers 30001-30002 the same
  // file here.
  std::uint16_t regs[2] = {0, 0};
  ASSERT_EQ(modbus_read_registers(ctx_, 0, 2, regs), 2);
  EXPECT_EQ(regs[0], 500);
  EXPECT_EQ(regs[1], 0);
  ASSERT_EQ(modbus_read_input_registers(ctx_, 0, 1, regs), 1);
  EXPECT_EQ(regs[0], 500);

  // FC 6 and FC 16 write N7 through the controller.
  ASSERT_EQ(modbus_write_register(ctx_, 0, 1234), 1);
  EXPECT_EQ(on_server([&] { return live_->controller().get_int("N7:0"); }), 1234);
  const std::uint16_t two[2] = {0xFFFF, 7};
  ASSERT_EQ(modbus_write_registers(ctx_, 0, 2, two), 2);
  EXPECT_EQ(on_server([&] { return live_->controller().get_int("N7:0"); }), -1);
  EXPECT_EQ(holding(1), 7);

  // Coils 00001-00016 = B3:0/0-15; FC 5 and FC 15 write single bits, FC 1/2 read them.
  ASSERT_EQ(modbus_write_bit(ctx_, 9, 1), 1);  // coil 00010 = B3:0/9 (no rung uses it)
  EXPECT_EQ(on_server([&] { return live_->controller().get_int("B3:0/9"); }), 1);
  std::uint8_t bits[16] = {};
  ASSERT_EQ(modbus_read_bits(ctx_, 8, 3, bits), 3);
  EXPECT_EQ(bits[0], 0);
  EXPECT_EQ(bits[1], 1);
  EXPECT_EQ(bits[2], 0);
  const std::uint8_t pattern[4] = {1, 0, 1, 1};  // coils 00011-00014 = B3:0/10-13
  ASSERT_EQ(modbus_write_bits(ctx_, 10, 4, pattern), 4);
  EXPECT_EQ(on_server([&] { return live_->controller().get_int("B3:0") & 0x3C00; }), 0x3400);
  ASSERT_EQ(modbus_read_input_bits(ctx_, 9, 5, bits), 5);  // contacts 10010-10014, the same B3 here
  EXPECT_EQ((std::vector<int>{bits[0], bits[1], bits[2], bits[3], bits[4]}), (std::vector<int>{1, 1, 0, 1, 1}));

  // Holding registers 41501- are the status file: S:0-65 (read and write).
  std::uint16_t s1 = 0;
  ASSERT_EQ(modbus_read_registers(ctx_, 1501, 1, &s1), 1);
  EXPECT_EQ(s1 & 0x1F, 6) << "S:1 mode bits: remote Run";
  ASSERT_EQ(modbus_read_input_registers(ctx_, 1500 + 65, 1, regs), 1);
}

TEST_F(ModbusServerTest, BadRequestsGetTheModbusExceptionCodes) {
  start();
  std::uint16_t regs[130];
  std::uint8_t bits[16];
  // 02 illegal data address: N7 has 2 words, so 40003 runs past the file; 40300 is outside the
  // map; 30500 lies between the input register file and the communication parameters; coil 00017
  // is past B3's one word.
  EXPECT_EQ(exception_of(modbus_read_registers(ctx_, 2, 1, regs)), MODBUS_EXCEPTION_ILLEGAL_DATA_ADDRESS);
  EXPECT_EQ(exception_of(modbus_read_registers(ctx_, 1, 2, regs)), MODBUS_EXCEPTION_ILLEGAL_DATA_ADDRESS);
  EXPECT_EQ(exception_of(modbus_read_registers(ctx_, 299, 1, regs)), MODBUS_EXCEPTION_ILLEGAL_DATA_ADDRESS);
  EXPECT_EQ(exception_of(modbus_read_input_registers(ctx_, 499, 1, regs)), MODBUS_EXCEPTION_ILLEGAL_DATA_ADDRESS);
  EXPECT_EQ(exception_of(modbus_read_registers(ctx_, 1566, 1, regs)), MODBUS_EXCEPTION_ILLEGAL_DATA_ADDRESS);
  EXPECT_EQ(exception_of(modbus_write_bit(ctx_, 16, 1)), MODBUS_EXCEPTION_ILLEGAL_DATA_ADDRESS);
  EXPECT_EQ(exception_of(modbus_read_bits(ctx_, 4090, 10, bits)), MODBUS_EXCEPTION_ILLEGAL_DATA_ADDRESS);
  // 01 illegal function: FC 7 (read exception status) is not in the MicroLogix's table.
  // (A raw request's confirmation is the whole ADU: MBAP, function | 80h, exception code.)
  std::uint8_t reply[MODBUS_TCP_MAX_ADU_LENGTH];
  const std::uint8_t fc7[] = {0xFF, 0x07};
  ASSERT_GT(modbus_send_raw_request(ctx_, fc7, sizeof fc7), 0);
  ASSERT_EQ(modbus_receive_confirmation(ctx_, reply), 9);
  EXPECT_EQ(reply[7], 0x87);
  EXPECT_EQ(reply[8], MODBUS_EXCEPTION_ILLEGAL_FUNCTION);
  // 03 illegal data value: FC 5 with a value other than FF00h/0000h.
  const std::uint8_t fc5[] = {0xFF, 0x05, 0x00, 0x00, 0x12, 0x34};
  ASSERT_GT(modbus_send_raw_request(ctx_, fc5, sizeof fc5), 0);
  ASSERT_EQ(modbus_receive_confirmation(ctx_, reply), 9);
  EXPECT_EQ(reply[7], 0x85);
  EXPECT_EQ(reply[8], MODBUS_EXCEPTION_ILLEGAL_DATA_VALUE);
  // 03 also for a quantity of 0 registers (sent raw: libmodbus refuses to send it).
  const std::uint8_t zero[] = {0xFF, 0x03, 0x00, 0x00, 0x00, 0x00};
  ASSERT_GT(modbus_send_raw_request(ctx_, zero, sizeof zero), 0);
  ASSERT_EQ(modbus_receive_confirmation(ctx_, reply), 9);
  EXPECT_EQ(reply[7], 0x83);
  EXPECT_EQ(reply[8], MODBUS_EXCEPTION_ILLEGAL_DATA_VALUE);
  // Nothing was written, and the connection still serves.
  EXPECT_EQ(holding(0), 500);
  EXPECT_EQ(on_server([&] { return live_->controller().get_int("B3:0"); }), 0);
}

// Input registers 30501-30532 are the "Modbus Communication Parameters" (1766-RM001A p. 617-618,
// AG-UM008C p. 3-52): 30501-30504 the coil, contact, input register and holding register file
// numbers. Without a serial channel the address and counters read 0; the block ends at 30532.
TEST_F(ModbusServerTest, CommunicationParametersNameTheMapsFiles) {
  start();
  std::uint16_t regs[32];
  ASSERT_EQ(modbus_read_input_registers(ctx_, 500, 32, regs), 32) << modbus_strerror(errno);
  EXPECT_EQ((std::vector<int>{regs[0], regs[1], regs[2], regs[3]}), (std::vector<int>{3, 3, 7, 7}));
  EXPECT_EQ(regs[6], 0) << "30507 slave address: no serial channel";
  EXPECT_EQ(regs[29], 0) << "30530 total messages seen: Modbus TCP requests are not counted";
  EXPECT_EQ(exception_of(modbus_read_input_registers(ctx_, 531, 2, regs)), MODBUS_EXCEPTION_ILLEGAL_DATA_ADDRESS);
  // FC 3 does not reach them: holding register 40501 is not mapped.
  EXPECT_EQ(exception_of(modbus_read_registers(ctx_, 500, 1, regs)), MODBUS_EXCEPTION_ILLEGAL_DATA_ADDRESS);
}

TEST_F(ModbusServerTest, ReadOnlyServerRefusesWritesWithServerDeviceFailure) {
  LiveOptions lo;
  lo.read_only = true;
  start(lo);
  EXPECT_EQ(exception_of(modbus_write_register(ctx_, 0, 1)), MODBUS_EXCEPTION_SLAVE_OR_SERVER_FAILURE);
  EXPECT_EQ(exception_of(modbus_write_bit(ctx_, 1, 1)), MODBUS_EXCEPTION_SLAVE_OR_SERVER_FAILURE);
  EXPECT_EQ(holding(0), 500);
}

TEST_F(ModbusServerTest, TheLadderRespondsToWrittenValues) {
  LiveOptions lo;
  lo.speed = 10;
  start(lo);
  run_a_batch();
}

TEST_F(ModbusServerTest, MalformedFramesCloseOnlyTheirConnection) {
  start();
  asio::io_context client;
  asio::ip::tcp::socket s(client);
  s.connect(asio::ip::tcp::endpoint(asio::ip::make_address("127.0.0.1"), server_->modbus_port()));
  // Protocol identifier 1 is not Modbus: the server closes the connection.
  const Bytes bad = {0x00, 0x01, 0x00, 0x01, 0x00, 0x06, 0x01, 0x03, 0x00, 0x00, 0x00, 0x01};
  asio::write(s, asio::buffer(bad));
  std::uint8_t b;
  boost::system::error_code ec;
  s.read_some(asio::buffer(&b, 1), ec);
  EXPECT_TRUE(ec == asio::error::eof || ec == asio::error::connection_reset) << ec.message();
  // The libmodbus connection is unaffected.
  EXPECT_EQ(holding(0), 500);
}

// Byte-exact frames through the decoder, without sockets: the MBAP header comes back with the
// request's transaction and unit, the PDU as the Modbus specification lays it out.
TEST(ModbusFrames, ReadHoldingRegistersAndWriteSingleCoil) {
  LiveController live(batch_program(), std::nullopt, {});
  const Bytes read = {0x12, 0x34, 0x00, 0x00, 0x00, 0x06, 0x11, 0x03, 0x00, 0x00, 0x00, 0x02};
  EXPECT_EQ(modbus::handle(read, kBatchMap, live),
            (Bytes{0x12, 0x34, 0x00, 0x00, 0x00, 0x07, 0x11, 0x03, 0x04, 0x01, 0xF4, 0x00, 0x00}));
  const Bytes coil = {0x00, 0x02, 0x00, 0x00, 0x00, 0x06, 0x01, 0x05, 0x00, 0x09, 0xFF, 0x00};
  EXPECT_EQ(modbus::handle(coil, kBatchMap, live), coil);  // FC 5 echoes the request
  EXPECT_EQ(live.controller().get_int("B3:0/9"), 1);
  std::string error;
  const Bytes short_pdu = {0x00, 0x02, 0x00, 0x00, 0x00, 0x06, 0x01, 0x05, 0x00};
  EXPECT_FALSE(modbus::handle(short_pdu, kBatchMap, live, &error));
  EXPECT_NE(error.find("disagrees"), std::string::npos) << error;
}

TEST(ModbusFrames, TheMapMustNameBOrNFiles) {
  LiveController live(batch_program(), std::nullopt, {});
  EXPECT_EQ(modbus::check_map(kBatchMap, live), "");
  EXPECT_NE(modbus::check_map({3, 3, 9, 7}, live), "");  // L9 is a long file
  EXPECT_NE(modbus::check_map({3, 3, 7, 42}, live), "");  // no N42
  EXPECT_NE(modbus::check_map({2, 3, 7, 7}, live), "");  // S2: not 3-255
}

}  // namespace
}  // namespace softslc::serve::testing
