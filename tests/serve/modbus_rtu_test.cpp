// `softslc serve --modbus-rtu`: Modbus RTU as a MicroLogix 1100/1400 whose channel 0 is configured
// as a Modbus RTU slave answers it (server/modbus_rtu.h), on the shipped example
// examples/ladder/micrologix/ml1400_batch.slc with the map B3 (coils and contacts), N7 (input and
// holding registers).
//
// The client is Debian's libmodbus (modbus_new_rtu) on the pseudo-terminal the server creates —
// an implementation independent of softslc's framing and CRC. Expected values come from the
// program (DATA N7:0 500, the rungs), the map from 1763-RM001C p. 530 / 1766-RM001A p. 617, the
// exception codes from the Modbus Application Protocol v1.1b3 §7, the framing (address, PDU,
// CRC-16 low byte first; address 0 broadcast, never answered; a bad CRC never answered) from the
// Modbus over Serial Line specification v1.02 §2.2 and §2.5.1.
#include <gtest/gtest.h>
#include <modbus.h>
#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>

#include "server/modbus_rtu.h"
#include "server/server.h"
#include "tests/serve/modbus_test_util.h"

namespace softslc::serve::testing {
namespace {

using Bytes = std::vector<std::uint8_t>;

constexpr int kSlave = 17;

class ModbusRtuServerTest : public ModbusClientTest {
 protected:
  void start(const LiveOptions& lo = {}) {
    ServerOptions so;
    so.modbus_rtu = ServerOptions::ModbusRtu{"pty", kSlave, 19200, 'E'};
    start_server(so, lo);
    ASSERT_FALSE(server_->modbus_rtu_path().empty());
    // libmodbus sets the line as it would a real port: 19200 baud, even parity, 8 data bits,
    // 1 stop bit (a pseudo-terminal stores these settings and honours none of them).
    ctx_ = modbus_new_rtu(server_->modbus_rtu_path().c_str(), 19200, 'E', 8, 1);
    ASSERT_NE(ctx_, nullptr);
    ASSERT_EQ(modbus_set_slave(ctx_, kSlave), 0);
    modbus_set_response_timeout(ctx_, 1, 0);
    ASSERT_EQ(modbus_connect(ctx_), 0) << modbus_strerror(errno);
  }
  int n7(int word) {
    return on_server([&] { return live_->controller().get_int("N7:" + std::to_string(word)); });
  }
  // Whether any byte comes back on the client's line within `ms`.
  bool line_answers_within(int ms) {
    pollfd p{modbus_get_socket(ctx_), POLLIN, 0};
    return ::poll(&p, 1, ms) > 0;
  }
  // Reads up to `n` bytes from the line, waiting at most `ms` for each.
  Bytes read_raw(std::size_t n, int ms) {
    Bytes out;
    while (out.size() < n && line_answers_within(ms)) {
      std::uint8_t b[256];
      const ssize_t got = ::read(modbus_get_socket(ctx_), b, std::min(sizeof b, n - out.size()));
      if (got <= 0) break;
      out.insert(out.end(), b, b + got);
    }
    return out;
  }
  // Writes raw bytes on the line (not through libmodbus: its frames always carry a good CRC).
  void write_raw(const Bytes& bytes) {
    ASSERT_EQ(::write(modbus_get_socket(ctx_), bytes.data(), bytes.size()), static_cast<ssize_t>(bytes.size()));
  }
};

TEST_F(ModbusRtuServerTest, CoilsAndRegistersAreTheMappedFiles) {
  start();
  // Holding registers 40001-40002 = N7:0-1 (DATA N7:0 500 0); input registers 30001- the same file.
  std::uint16_t regs[2] = {0, 0};
  ASSERT_EQ(modbus_read_registers(ctx_, 0, 2, regs), 2) << modbus_strerror(errno);
  EXPECT_EQ(regs[0], 500);
  EXPECT_EQ(regs[1], 0);
  ASSERT_EQ(modbus_read_input_registers(ctx_, 0, 1, regs), 1);
  EXPECT_EQ(regs[0], 500);
  // FC 6 and FC 16 write N7 through the controller.
  ASSERT_EQ(modbus_write_register(ctx_, 0, 1234), 1);
  EXPECT_EQ(n7(0), 1234);
  const std::uint16_t two[2] = {0xFFFF, 7};
  ASSERT_EQ(modbus_write_registers(ctx_, 0, 2, two), 2);
  EXPECT_EQ(n7(0), -1);
  EXPECT_EQ(holding(1), 7);
  // Coils 00001-00016 = B3:0/0-15: FC 5 and FC 15 write, FC 1 and FC 2 read.
  ASSERT_EQ(modbus_write_bit(ctx_, 9, 1), 1);  // coil 00010 = B3:0/9
  EXPECT_EQ(on_server([&] { return live_->controller().get_int("B3:0/9"); }), 1);
  std::uint8_t bits[8] = {};
  ASSERT_EQ(modbus_read_bits(ctx_, 8, 3, bits), 3);
  EXPECT_EQ((std::vector<int>{bits[0], bits[1], bits[2]}), (std::vector<int>{0, 1, 0}));
  const std::uint8_t pattern[4] = {1, 0, 1, 1};  // coils 00011-00014 = B3:0/10-13
  ASSERT_EQ(modbus_write_bits(ctx_, 10, 4, pattern), 4);
  EXPECT_EQ(on_server([&] { return live_->controller().get_int("B3:0") & 0x3C00; }), 0x3400);
  ASSERT_EQ(modbus_read_input_bits(ctx_, 9, 5, bits), 5);  // contacts 10010-10014, B3 here too
  EXPECT_EQ((std::vector<int>{bits[0], bits[1], bits[2], bits[3], bits[4]}), (std::vector<int>{1, 1, 0, 1, 1}));
  // Holding registers 41501- are the status file: S:1's mode bits say remote Run (6).
  std::uint16_t s1 = 0;
  ASSERT_EQ(modbus_read_registers(ctx_, 1501, 1, &s1), 1);
  EXPECT_EQ(s1 & 0x1F, 6);
}

TEST_F(ModbusRtuServerTest, BadRequestsGetTheTcpServersExceptionCodes) {
  start();
  std::uint16_t regs[4];
  // 02: N7 has 2 words (40003 runs past it); 40300 is outside the map; coil 00017 past B3's word.
  EXPECT_EQ(exception_of(modbus_read_registers(ctx_, 2, 1, regs)), MODBUS_EXCEPTION_ILLEGAL_DATA_ADDRESS);
  EXPECT_EQ(exception_of(modbus_read_registers(ctx_, 299, 1, regs)), MODBUS_EXCEPTION_ILLEGAL_DATA_ADDRESS);
  EXPECT_EQ(exception_of(modbus_write_bit(ctx_, 16, 1)), MODBUS_EXCEPTION_ILLEGAL_DATA_ADDRESS);
  // 01: FC 7 is not in the MicroLogix's table; it has no length rule, so the silence ends it. The
  // confirmation is the whole ADU: address, function | 80h, code, CRC.
  std::uint8_t reply[MODBUS_RTU_MAX_ADU_LENGTH];
  const std::uint8_t fc7[] = {kSlave, 0x07};
  ASSERT_GT(modbus_send_raw_request(ctx_, fc7, sizeof fc7), 0);
  ASSERT_EQ(modbus_receive_confirmation(ctx_, reply), 5) << modbus_strerror(errno);
  EXPECT_EQ(reply[0], kSlave);
  EXPECT_EQ(reply[1], 0x87);
  EXPECT_EQ(reply[2], MODBUS_EXCEPTION_ILLEGAL_FUNCTION);
  // 03: FC 5 with a value other than FF00h/0000h.
  const std::uint8_t fc5[] = {kSlave, 0x05, 0x00, 0x00, 0x12, 0x34};
  ASSERT_GT(modbus_send_raw_request(ctx_, fc5, sizeof fc5), 0);
  ASSERT_EQ(modbus_receive_confirmation(ctx_, reply), 5);
  EXPECT_EQ(reply[1], 0x85);
  EXPECT_EQ(reply[2], MODBUS_EXCEPTION_ILLEGAL_DATA_VALUE);
  // FC 8 subfunction 0 echoes its data (no length rule either: the silence ends it). libmodbus
  // cannot receive an FC 8 confirmation (it expects one byte after the function), so the reply is
  // read off the line: the request itself, CRC included.
  const std::uint8_t echo[] = {kSlave, 0x08, 0x00, 0x00, 0xA5, 0x37};
  ASSERT_GT(modbus_send_raw_request(ctx_, echo, sizeof echo), 0);
  EXPECT_EQ(read_raw(8, 1000), modbus::with_crc(Bytes(echo, echo + 6)));
  EXPECT_EQ(holding(0), 500) << "nothing was written";
}

TEST_F(ModbusRtuServerTest, ABroadcastWriteIsExecutedAndNotAnswered) {
  start();
  ASSERT_EQ(modbus_set_slave(ctx_, MODBUS_BROADCAST_ADDRESS), 0);
  const std::uint8_t fc6[] = {0x00, 0x06, 0x00, 0x01, 0x00, 0x2A};  // holding 40002 = N7:1 := 42
  ASSERT_GT(modbus_send_raw_request(ctx_, fc6, sizeof fc6), 0);
  EXPECT_FALSE(line_answers_within(300)) << "a broadcast is never answered";
  EXPECT_EQ(n7(1), 42);
  ASSERT_EQ(modbus_set_slave(ctx_, kSlave), 0);
  EXPECT_EQ(holding(1), 42);
}

TEST_F(ModbusRtuServerTest, AFrameForAnotherSlaveIsIgnored) {
  start();
  ASSERT_EQ(modbus_set_slave(ctx_, kSlave + 1), 0);
  modbus_set_response_timeout(ctx_, 0, 300000);
  std::uint16_t v = 0;
  EXPECT_EQ(modbus_read_registers(ctx_, 0, 1, &v), -1);
  EXPECT_EQ(errno, ETIMEDOUT) << modbus_strerror(errno);
  EXPECT_EQ(modbus_write_register(ctx_, 0, 9), -1);
  EXPECT_EQ(errno, ETIMEDOUT) << modbus_strerror(errno);
  EXPECT_EQ(n7(0), 500) << "a write to another slave is not performed";
  ASSERT_EQ(modbus_set_slave(ctx_, kSlave), 0);
  EXPECT_EQ(holding(0), 500);
}

TEST_F(ModbusRtuServerTest, ABadCrcIsIgnoredAndTheNextFrameAnswered) {
  start();
  // FC 6 to N7:0 := 7 with the CRC's last byte flipped: dropped, no reply, not written.
  Bytes bad = {kSlave, 0x06, 0x00, 0x00, 0x00, 0x07};
  const std::uint16_t crc = modbus::crc16(bad);
  bad.push_back(static_cast<std::uint8_t>(crc & 0xFF));
  bad.push_back(static_cast<std::uint8_t>((crc >> 8) ^ 0x01));
  write_raw(bad);
  EXPECT_FALSE(line_answers_within(300));
  EXPECT_EQ(n7(0), 500);
  // Garbage with no frame in it, then (after the line was quiet) a good request: answered.
  write_raw({0xFF, 0x00, 0x13, 0x37, 0x42});
  EXPECT_FALSE(line_answers_within(300));
  ASSERT_EQ(modbus_write_register(ctx_, 0, 77), 1) << modbus_strerror(errno);
  EXPECT_EQ(n7(0), 77);
  // A run of bytes longer than any frame (an FC 16 announcing 250 bytes of data: 259 in all) is
  // dropped whole, with a bounded buffer, and the line recovers.
  Bytes flood = {kSlave, 0x10, 0x00, 0x00, 0x00, 0x7D, 0xFA};
  flood.resize(600, 0x55);
  write_raw(flood);
  EXPECT_FALSE(line_answers_within(300));
  EXPECT_LE(on_server([&] { return server_->modbus_rtu()->buffered(); }), modbus::kRtuMaxFrame);
  EXPECT_EQ(holding(0), 77);
  const auto& c = on_server([&] { return server_->modbus_rtu()->counters(); });
  EXPECT_GE(c.link_errors, 3);
}

// Input registers 30501-30532, "Modbus Communication Parameters" (1766-RM001A p. 618, AG-UM008C
// p. 3-52, "Modbus Slave to MicroLogix Memory Map - Detail"): 30501-30504 the map's files, 30507
// the slave address, 30518-30526 messages per function code (1, 2, 3, 4, 5, 6, 8, 15, 16), 30528
// responded to, 30529 to this slave, 30530 seen, 30531 link layer errors.
TEST_F(ModbusRtuServerTest, CommunicationParametersCountTheLine) {
  start();
  std::uint16_t v = 0;
  ASSERT_EQ(modbus_read_registers(ctx_, 0, 1, &v), 1);      // FC 3
  ASSERT_EQ(modbus_write_register(ctx_, 1, 5), 1);          // FC 6
  ASSERT_EQ(modbus_set_slave(ctx_, kSlave + 1), 0);         // seen, not to this slave
  modbus_set_response_timeout(ctx_, 0, 200000);
  EXPECT_EQ(modbus_read_registers(ctx_, 0, 1, &v), -1);
  ASSERT_EQ(modbus_set_slave(ctx_, MODBUS_BROADCAST_ADDRESS), 0);  // to this slave, not answered
  const std::uint8_t fc6[] = {0x00, 0x06, 0x00, 0x01, 0x00, 0x06};
  ASSERT_GT(modbus_send_raw_request(ctx_, fc6, sizeof fc6), 0);
  EXPECT_FALSE(line_answers_within(200));
  write_raw({kSlave, 0x03, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00});  // bad CRC: a link layer error
  EXPECT_FALSE(line_answers_within(200));
  ASSERT_EQ(modbus_set_slave(ctx_, kSlave), 0);
  modbus_set_response_timeout(ctx_, 1, 0);
  std::uint16_t p[32];
  ASSERT_EQ(modbus_read_input_registers(ctx_, 500, 32, p), 32) << modbus_strerror(errno);  // FC 4, counted too
  EXPECT_EQ((std::vector<int>{p[0], p[1], p[2], p[3]}), (std::vector<int>{3, 3, 7, 7}));
  EXPECT_EQ(p[6], kSlave);
  // Function counters 30518-30526: FC 3 once, FC 4 once (this read), FC 6 twice (one broadcast).
  EXPECT_EQ((std::vector<int>(p + 17, p + 26)), (std::vector<int>{0, 0, 1, 1, 0, 2, 0, 0, 0}));
  EXPECT_EQ(p[27], 2) << "30528 responded to (this read's reply is not sent yet)";
  EXPECT_EQ(p[28], 4) << "30529 to this slave";
  EXPECT_EQ(p[29], 5) << "30530 seen";
  EXPECT_EQ(p[30], 1) << "30531 link layer errors";
  EXPECT_EQ(n7(1), 6) << "the broadcast wrote N7:1";
}

TEST_F(ModbusRtuServerTest, TheLadderRespondsToWrittenValues) {
  LiveOptions lo;
  lo.speed = 10;
  start(lo);
  run_a_batch();
}

// The framer without a line: byte-exact frames through modbus::RtuSlave.
class RtuFrames : public ::testing::Test {
 protected:
  LiveController live_{batch_program(), std::nullopt, {}};
  modbus::RtuSlave slave_{kSlave, kBatchMap};
};

TEST_F(RtuFrames, TheCrcIsModbusCrc16LowByteFirst) {
  // The serial line guide's read of holding registers 40108-40110 from slave 17 (11h) is
  // 11 03 00 6B 00 03 76 87 (a worked example published with the Modbus RTU framing, e.g.
  // bbs.21ic.com/icview-162927; CRC-16/MODBUS's check value of "123456789" is 4B37h).
  EXPECT_EQ(modbus::with_crc({0x11, 0x03, 0x00, 0x6B, 0x00, 0x03}), (Bytes{0x11, 0x03, 0x00, 0x6B, 0x00, 0x03, 0x76, 0x87}));
  const Bytes check = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  EXPECT_EQ(modbus::crc16(check), 0x4B37);
}

TEST_F(RtuFrames, ARequestIsCutByItsLengthAndAnsweredWithTheSlavesAddress) {
  // Holding 40001-40002 = N7:0-1 (500, 0), delivered a byte at a time: one reply, after the 8th.
  const Bytes read = modbus::with_crc({kSlave, 0x03, 0x00, 0x00, 0x00, 0x02});
  for (std::size_t i = 0; i + 1 < read.size(); ++i)
    EXPECT_TRUE(slave_.receive(std::span(&read[i], 1), live_).replies.empty()) << i;
  const auto e = slave_.receive(std::span(&read.back(), 1), live_);
  ASSERT_EQ(e.replies.size(), 1u);
  EXPECT_EQ(e.replies[0], modbus::with_crc({kSlave, 0x03, 0x04, 0x01, 0xF4, 0x00, 0x00}));
  // Two requests back to back in one read: two replies (FC 16 by its byte count, then FC 3).
  Bytes two = modbus::with_crc({kSlave, 0x10, 0x00, 0x00, 0x00, 0x01, 0x02, 0x00, 0x09});
  two.insert(two.end(), read.begin(), read.end());
  const auto e2 = slave_.receive(two, live_);
  ASSERT_EQ(e2.replies.size(), 2u);
  EXPECT_EQ(e2.replies[0], modbus::with_crc({kSlave, 0x10, 0x00, 0x00, 0x00, 0x01}));
  EXPECT_EQ(e2.replies[1], modbus::with_crc({kSlave, 0x03, 0x04, 0x00, 0x09, 0x00, 0x00}));
  EXPECT_FALSE(slave_.waiting_for_silence());
}

TEST_F(RtuFrames, BadFramesAreDroppedUntilTheLineIsSilent) {
  Bytes bad = modbus::with_crc({kSlave, 0x06, 0x00, 0x00, 0x00, 0x07});
  bad.back() ^= 0x80;
  const Bytes good = modbus::with_crc({kSlave, 0x06, 0x00, 0x00, 0x00, 0x08});
  // A good frame right behind a bad one, without silence, is part of the bad run (§2.5.1.1).
  Bytes both = bad;
  both.insert(both.end(), good.begin(), good.end());
  EXPECT_TRUE(slave_.receive(both, live_).replies.empty());
  EXPECT_TRUE(slave_.waiting_for_silence());
  EXPECT_TRUE(slave_.silence(live_).replies.empty());
  EXPECT_EQ(live_.controller().get_int("N7:0"), 500);
  // After the silence the same good frame is answered (FC 6 echoes the request).
  const auto e = slave_.receive(good, live_);
  ASSERT_EQ(e.replies.size(), 1u);
  EXPECT_EQ(e.replies[0], good);
  EXPECT_EQ(live_.controller().get_int("N7:0"), 8);
  // A frame cut short by the silence is dropped; so is one shorter than address, function, CRC.
  EXPECT_TRUE(slave_.receive(Bytes(good.begin(), good.begin() + 5), live_).replies.empty());
  EXPECT_TRUE(slave_.silence(live_).replies.empty());
  EXPECT_TRUE(slave_.receive(Bytes{kSlave}, live_).replies.empty());
  EXPECT_TRUE(slave_.silence(live_).replies.empty());
  EXPECT_EQ(slave_.counters().link_errors, 3);
  EXPECT_EQ(slave_.buffered(), 0u);
}

TEST_F(RtuFrames, OtherSlavesBroadcastsAndFunctionsWithoutALengthRule) {
  // Slave 18's request: a good frame, seen, not answered, not performed.
  EXPECT_TRUE(slave_.receive(modbus::with_crc({kSlave + 1, 0x06, 0x00, 0x00, 0x00, 0x05}), live_).replies.empty());
  EXPECT_EQ(live_.controller().get_int("N7:0"), 500);
  // Broadcast: performed, not answered.
  EXPECT_TRUE(slave_.receive(modbus::with_crc({0x00, 0x06, 0x00, 0x00, 0x00, 0x05}), live_).replies.empty());
  EXPECT_EQ(live_.controller().get_int("N7:0"), 5);
  // FC 43 (not in the MicroLogix's table): waits for the silence, then exception 01.
  EXPECT_TRUE(slave_.receive(modbus::with_crc({kSlave, 0x2B, 0x0E, 0x01, 0x00}), live_).replies.empty());
  const auto e = slave_.silence(live_);
  ASSERT_EQ(e.replies.size(), 1u);
  EXPECT_EQ(e.replies[0], modbus::with_crc({kSlave, 0xAB, 0x01}));
  EXPECT_EQ(slave_.counters().seen, 3);
  EXPECT_EQ(slave_.counters().to_slave, 2);
  EXPECT_EQ(slave_.counters().responded, 1);
}

TEST_F(RtuFrames, GarbageNeverGrowsTheBuffer) {
  // 10,000 bytes of a function without a length rule and no silence: the first 257 are dropped as
  // too long a frame, the rest until the line is silent.
  const Bytes garbage(10000, 0x41);
  const auto e = slave_.receive(garbage, live_);
  EXPECT_TRUE(e.replies.empty());
  EXPECT_LE(slave_.buffered(), modbus::kRtuMaxFrame);
  EXPECT_TRUE(slave_.silence(live_).replies.empty());
  EXPECT_EQ(slave_.buffered(), 0u);
  // An FC 15 whose byte count makes the frame 257 bytes (9 + F8h) is dropped at once.
  EXPECT_TRUE(slave_.receive(Bytes{kSlave, 0x0F, 0x00, 0x00, 0x07, 0xC0, 0xF8}, live_).replies.empty());
  EXPECT_TRUE(slave_.waiting_for_silence());
  EXPECT_EQ(slave_.buffered(), 0u);
}

}  // namespace
}  // namespace softslc::serve::testing
