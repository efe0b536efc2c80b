// The DEM instruction (chapter 8, p.93-101): control block layout, EN/DN/ER/WS/AB on rung
// transitions, the timeout preset, and the mapping of scanner statuses and CIP errors to error
// codes 0...4.
#include <gtest/gtest.h>

#include "modules/devicenet/dem.h"
#include "tests/devicenet/devicenet_test_util.h"

namespace softslc::devicenet::test {
namespace {

using dem::kAB;
using dem::kDN;
using dem::kEN;
using dem::kER;
using dem::kWS;
using ControlBlock = std::array<std::uint16_t, dem::kWords>;

constexpr std::uint8_t kGetAttributeSingle = 0x0E;

struct DemFixture : ::testing::Test {
  DemFixture() : x(true), port(*x.sdn) {
    x.run();
    x.start();
  }
  // One execution of the DEM with control block `cb` (owner 1 unless given).
  void exec(ControlBlock& cb, bool rung, std::uint32_t owner = 1) { port.on_rung(owner, cb, rung, x.net.now()); }
  int error(const ControlBlock& cb) const { return cb[0] & 0xFF; }

  ExampleNetwork x;
  dem::DemPort port;
};

ControlBlock read_parameter(std::uint16_t number, std::uint8_t mac = kDriveNode, std::uint8_t timeout = 0) {
  ControlBlock cb{};
  dem::write_setup(cb, dem::Setup{kGetAttributeSingle, mac, 0x0F, number, 1, {}, timeout});
  return cb;
}

// ---- the control block -----------------------------------------------------------------------------

// Words 6-11 are the request header and path of appendix E's transaction block, words 12-37 its
// data; word 7 counts the send data only (p.101, p.95 "Size of Send Data").
TEST(DemLayout, RequestWordsAreTheTransactionBlock) {
  ControlBlock cb{};
  dem::write_setup(cb, dem::Setup{0x10, 20, 0x0F, 39, 1, {0x2C, 0x01}, 5});
  EXPECT_EQ(cb[1], 5);
  EXPECT_EQ(cb[7], 2);
  EXPECT_EQ(cb[8], 0x1014);
  EXPECT_EQ(cb[9], 0x0F);
  EXPECT_EQ(cb[10], 39);
  EXPECT_EQ(cb[11], 1);
  EXPECT_EQ(cb[12], 0x012C);
  const RequestBlock r = dem::request_from_control_block(cb, 9);
  RequestBlock expected;
  expected.command = 1;
  expected.txid = 9;
  expected.size = 8;
  expected.service = 0x10;
  expected.mac = 20;
  expected.class_id = 0x0F;
  expected.instance = 39;
  expected.attribute = 1;
  expected.data = {0x2C, 0x01};
  EXPECT_EQ(encode_request(r), encode_request(expected));
}

// "a value of 0 disables the Message Timeout and a value of 1 second gets bumped to 2 seconds" (p.96).
TEST(DemLayout, TimeoutPreset) {
  EXPECT_EQ(dem::timeout_for_preset(0), 0);
  EXPECT_EQ(dem::timeout_for_preset(1), seconds(2));
  EXPECT_EQ(dem::timeout_for_preset(2), seconds(2));
  EXPECT_EQ(dem::timeout_for_preset(255), seconds(255));
}

// "All error codes listed above [scanner codes 2H...15H] result in an error code of 2" (p.98); a CIP
// error is error code 4 (p.99); success is 0.
TEST(DemLayout, ErrorCodeMapping) {
  for (int status = 2; status <= 15; ++status)
    EXPECT_EQ(dem::error_for_response(ResponseBlock{static_cast<std::uint8_t>(status), 1, 0, 0x8E, 7, {}}),
              dem::Error::Scanner)
        << status;
  for (int code : {0x02, 0x08, 0x09, 0x0B, 0x0C, 0x0E, 0x0F, 0x10, 0x11, 0x13, 0x14, 0x15, 0x16, 0x18, 0x19, 0x1F, 0x20,
                   0xD0, 0xFF}) {
    EXPECT_TRUE(cip_status_listed(static_cast<std::uint8_t>(code))) << code;
    EXPECT_EQ(dem::error_for_response(ResponseBlock{1, 1, 0, 0x94, 7, {static_cast<std::uint8_t>(code), 0xFF}}),
              dem::Error::Cip);
  }
  EXPECT_EQ(dem::error_for_response(ResponseBlock{1, 1, 0, 0x8E, 7, {1, 0}}), dem::Error::None);
}

// ---- the state machine --------------------------------------------------------------------------------

// Success: EN when accepted, DN with error 0 when the reply arrives; the reply header and data are in
// words 38-41... (p.101). EN stays while the rung is true and clears when it goes false (p.100).
TEST_F(DemFixture, ReadParameterSucceeds) {
  ControlBlock cb = read_parameter(39);
  exec(cb, false);
  EXPECT_EQ(cb[0] & (kEN | kDN | kER), 0);
  exec(cb, true);
  EXPECT_EQ(cb[0] & (kEN | kDN | kER | kWS), kEN);
  EXPECT_NE(cb[6] >> 8, 0);  // the TXID the DEM chose
  EXPECT_EQ(cb[6] & 0xFF, 1);
  x.advance_ms(50);
  exec(cb, true);
  EXPECT_EQ(cb[0] & (kEN | kDN | kER), kEN | kDN);
  EXPECT_EQ(error(cb), 0);
  EXPECT_EQ(cb[38], static_cast<std::uint16_t>((cb[6] & 0xFF00) | 1));  // TXID : status 1
  EXPECT_EQ(cb[39], 2);                                                 // 2 bytes of reply data
  EXPECT_EQ(cb[40], 0x8E00 | kDriveNode);                               // reply service : MAC
  EXPECT_EQ(cb[41], 100);                                               // Accel Time 1
  EXPECT_EQ(x.sdn->transactions_in_use(), 0u);                          // the DEM deleted its transaction
  exec(cb, true);
  EXPECT_EQ(cb[0] & (kEN | kDN), kEN | kDN);  // no retrigger while the rung stays true
  exec(cb, false);
  EXPECT_EQ(cb[0] & (kEN | kDN), kDN);
  exec(cb, true);  // the next false-to-true transition clears DN and starts again
  EXPECT_EQ(cb[0] & (kEN | kDN), kEN);
}

// A completion seen with the rung false clears EN at once.
TEST_F(DemFixture, CompletesWithRungFalse) {
  ControlBlock cb = read_parameter(40);
  exec(cb, true);
  exec(cb, false);
  EXPECT_EQ(cb[0] & kEN, kEN);  // EN stays until done
  x.advance_ms(50);
  exec(cb, false);
  EXPECT_EQ(cb[0] & (kEN | kDN), kDN);
}

// "If the message rung conditions remain true, you may retrigger the message instruction by
// resetting this bit after either the ER or DN bit has been set" (p.100).
TEST_F(DemFixture, RetriggerByClearingEn) {
  ControlBlock cb = read_parameter(39);
  exec(cb, true);
  x.advance_ms(50);
  exec(cb, true);
  ASSERT_EQ(cb[0] & kDN, kDN);
  cb[0] = static_cast<std::uint16_t>(cb[0] & ~kEN);
  exec(cb, true);
  EXPECT_EQ(cb[0] & (kEN | kDN), kEN);
}

// A slave's CIP error: ER with error code 4; "the error description displays the CIP response
// error code" (p.99), here reply data byte 0: 09H for a value outside the parameter's range.
TEST_F(DemFixture, CipErrorIsErrorFour) {
  ControlBlock cb{};
  dem::write_setup(cb, dem::Setup{0x10, kDriveNode, 0x0F, 39, 1, {0xFF, 0xFF}, 0});  // 65535 > 36000
  exec(cb, true);
  x.advance_ms(50);
  exec(cb, true);
  EXPECT_EQ(cb[0] & (kDN | kER), kER);
  EXPECT_EQ(error(cb), 4);
  EXPECT_EQ(cb[40] >> 8, 0x94);
  EXPECT_EQ(cb[41], 0xFF09);  // general 09H, additional FFH
}

// A scanner status is error code 2 with the status in word 38 (p.98): 3H slave not in scanlist.
TEST_F(DemFixture, ScannerStatusIsErrorTwo) {
  ControlBlock cb = read_parameter(39, 33);
  exec(cb, true);
  exec(cb, true);
  EXPECT_EQ(cb[0] & (kDN | kER), kER);
  EXPECT_EQ(error(cb), 2);
  EXPECT_EQ(cb[38] & 0xFF, 3);
}

// Send data above 52 bytes (p.94): the transaction body exceeds 58 bytes, scanner status 14.
TEST_F(DemFixture, TooMuchSendDataIsStatus14) {
  ControlBlock cb = read_parameter(39);
  cb[7] = 53;
  exec(cb, true);
  exec(cb, true);
  EXPECT_EQ(error(cb), 2);
  EXPECT_EQ(cb[38] & 0xFF, 14);
}

// "if the value of the Attribute is set to 0, the DeviceNet scanner does not transmit an Attribute
// byte. Some Service Codes require that a zero-value Attribute byte be transmitted. For these ... the
// first byte of the Send Data must be set to zero" (p.96). Reset (05H) takes no attribute; and an
// attribute given as the first send-data byte reaches the device exactly as attribute 3 would.
TEST_F(DemFixture, AttributeZeroSendsNoAttributeByte) {
  ControlBlock reset{};
  dem::write_setup(reset, dem::Setup{0x05, kRediStationNode, 0x01, 1, 0, {}, 0});
  exec(reset, true);
  x.advance_ms(50);
  exec(reset, true);
  EXPECT_EQ(reset[0] & (kDN | kER), kDN);
  EXPECT_EQ(reset[40] >> 8, 0x85);

  ControlBlock as_data{};
  dem::write_setup(as_data, dem::Setup{kGetAttributeSingle, kRediStationNode, 0x01, 1, 0, {3}, 0});
  exec(as_data, false, 2);
  exec(as_data, true, 2);
  x.advance_ms(50);
  exec(as_data, true, 2);
  EXPECT_EQ(as_data[0] & (kDN | kER), kDN);
  EXPECT_EQ(as_data[41], 2705);  // product code
}

// AB: "lets you abort an executing DEM instruction ... The ER bit will be set as soon as the AB bit
// is set. This bit is reset the next time the message rung goes from false to true" (p.99);
// error code 3 "DeviceNet explicit message aborted by user".
TEST_F(DemFixture, Abort) {
  x.drive->set_explicit_silent(true);
  ControlBlock cb = read_parameter(39);
  exec(cb, true);
  cb[0] = static_cast<std::uint16_t>(cb[0] | kAB);
  exec(cb, true);
  EXPECT_EQ(cb[0] & (kER | kAB), kER | kAB);
  EXPECT_EQ(error(cb), 3);
  EXPECT_FALSE(port.owner().has_value());
  EXPECT_EQ(x.sdn->transactions_in_use(), 0u);
  exec(cb, false);
  exec(cb, true);
  EXPECT_EQ(cb[0] & (kEN | kER | kAB), kEN);
}

// Error code 1 "DeviceNet explicit message timed out by processor" (p.99). The slave is made
// unreachable for longer than the preset: the ten transactions the module can hold are taken, so the
// DEM's request is deleted by the module (p.149) and only the timeout ends it. Preset 1 means 2 s.
TEST_F(DemFixture, TimeoutPresetOneMeansTwoSeconds) {
  x.drive->set_explicit_silent(true);
  for (int t = 100; t < 110; ++t) {
    RequestBlock r;
    r.command = 1;
    r.txid = static_cast<std::uint8_t>(t);
    r.size = 6;
    r.service = kGetAttributeSingle;
    r.mac = kDriveNode;
    r.class_id = 1;
    r.instance = 1;
    r.attribute = 1;
    ASSERT_EQ(x.sdn->handle_request(r), Scanner::Accept::Queued);
  }
  ControlBlock cb = read_parameter(39, kRediStationNode, 1);
  exec(cb, true);
  EXPECT_EQ(cb[0] & kEN, kEN);
  x.advance_ms(1999);
  exec(cb, true);
  EXPECT_EQ(cb[0] & (kDN | kER), 0);
  EXPECT_EQ(cb[2], 1);  // the accumulator counts whole seconds
  x.advance_ms(1);
  exec(cb, true);
  EXPECT_EQ(cb[0] & (kDN | kER), kER);
  EXPECT_EQ(error(cb), 1);
}

// Preset 0: no timeout; "user-programmed timeout logic must be included to avoid a message lockup"
// (p.96).
TEST_F(DemFixture, PresetZeroNeverTimesOut) {
  x.drive->set_explicit_silent(true);
  for (int t = 100; t < 110; ++t) {
    RequestBlock r;
    r.command = 1;
    r.txid = static_cast<std::uint8_t>(t);
    r.size = 6;
    r.mac = kDriveNode;
    x.sdn->handle_request(r);
  }
  ControlBlock cb = read_parameter(39, kRediStationNode, 0);
  exec(cb, true);
  for (int s = 0; s < 20; ++s) {
    x.advance_ms(1000);
    exec(cb, true);
  }
  EXPECT_EQ(cb[0] & (kEN | kDN | kER), kEN);
}

// One DEM per module: the second waits with WS while its rung stays true and is accepted (EN, WS
// cleared) once the first completes (p.94, p.100).
TEST_F(DemFixture, WaitingForSlot) {
  ControlBlock first = read_parameter(39);
  ControlBlock second = read_parameter(40);
  exec(first, true, 1);
  exec(second, true, 2);
  EXPECT_EQ(second[0] & (kEN | kWS), kWS);
  x.advance_ms(50);
  exec(first, true, 1);
  ASSERT_EQ(first[0] & kDN, kDN);
  exec(second, true, 2);
  EXPECT_EQ(second[0] & (kEN | kWS), kEN);
  x.advance_ms(50);
  exec(second, true, 2);
  EXPECT_EQ(second[0] & kDN, kDN);
  EXPECT_EQ(second[41], 100);  // Decel Time 1
}

// "If the message rung goes false before the module accepts this message, then the enable bit will
// remain off and the message will not be executed" (p.100).
TEST_F(DemFixture, WaitingDemGivesUpWhenRungGoesFalse) {
  ControlBlock first = read_parameter(39);
  ControlBlock second = read_parameter(40);
  exec(first, true, 1);
  exec(second, true, 2);
  ASSERT_EQ(second[0] & kWS, kWS);
  exec(second, false, 2);
  EXPECT_EQ(second[0] & (kEN | kWS), 0);
  x.advance_ms(50);
  exec(first, true, 1);
  exec(second, false, 2);
  EXPECT_EQ(second[0] & (kEN | kWS | kDN | kER), 0);
  EXPECT_EQ(x.sdn->transactions_in_use(), 0u);
}

// The DEM's transactions use TXIDs the ladder's M0 blocks are not using.
TEST_F(DemFixture, TxidAvoidsTransactionsInUse) {
  for (int t = 1; t <= 3; ++t) {
    RequestBlock r;
    r.command = 1;
    r.txid = static_cast<std::uint8_t>(t);
    r.size = 6;
    r.mac = kDriveNode;
    x.sdn->handle_request(r);
  }
  ControlBlock cb = read_parameter(39);
  exec(cb, true);
  EXPECT_EQ(cb[6] >> 8, 4);
}

// abandon() (the processor leaving Run) frees the slot and deletes the transaction.
TEST_F(DemFixture, Abandon) {
  x.drive->set_explicit_silent(true);
  ControlBlock cb = read_parameter(39);
  exec(cb, true);
  port.abandon();
  EXPECT_FALSE(port.owner().has_value());
  EXPECT_EQ(x.sdn->transactions_in_use(), 0u);
}

// DemPort::reads_network (issue 20): the module wrapper asks the instruction's time and advances the
// network only when it says so. Two identical networks run the same chapter 8 sequence (a start,
// WS, a waiting DEM giving up, the accumulator, a timeout, a completion, DN with the rung true,
// EN cleared by a false rung, abandon); the second's DEM is given a wrong time (0) whenever
// reads_network is false, and both must agree word for word at every step. Tried: with
// reads_network false for the block in flight, the accumulator and the timeout differ.
TEST(DemReadsNetwork, ADemThatDoesNotReadTheNetworkActsTheSameAtAnyTime) {
  ExampleNetwork a(true), b(true);
  dem::DemPort pa(*a.sdn), pb(*b.sdn);
  for (ExampleNetwork* x : {&a, &b}) {
    x->run();
    x->start();
    x->drive->set_explicit_silent(true);
  }
  ControlBlock a1 = read_parameter(39, kDriveNode, 3), b1 = a1;
  ControlBlock a2 = read_parameter(40), b2 = a2;
  int step = 0, untimed = 0;
  const auto exec = [&](int which, bool rung) {
    ControlBlock& ca = which == 1 ? a1 : a2;
    ControlBlock& cb = which == 1 ? b1 : b2;
    const auto owner = static_cast<std::uint32_t>(which);
    const bool reads = pa.reads_network(owner, ca, rung);
    ASSERT_EQ(reads, pb.reads_network(owner, cb, rung)) << "step " << step;
    if (!reads) ++untimed;
    pa.on_rung(owner, ca, rung, a.net.now());
    pb.on_rung(owner, cb, rung, reads ? b.net.now() : 0);
    EXPECT_EQ(ca, cb) << "step " << step;
    EXPECT_EQ(pa.owner(), pb.owner()) << "step " << step;
    EXPECT_EQ(pa.abandoned(), pb.abandoned()) << "step " << step;
    EXPECT_EQ(a.sdn->transactions_in_use(), b.sdn->transactions_in_use()) << "step " << step;
    ++step;
  };
  const auto advance = [&](int ms) {
    a.advance_ms(ms);
    b.advance_ms(ms);
  };
  exec(1, false);  // idle
  exec(1, true);   // starts: EN
  exec(2, true);   // WS: the slot is taken
  advance(1200);
  exec(1, true);   // in flight: the accumulator counts 1 s
  EXPECT_EQ(a1[2], 1);
  exec(2, true);
  exec(2, false);  // gives up: WS clears
  advance(2000);
  exec(1, false);  // the 3 s timeout: ER, and EN clears with the rung false
  EXPECT_EQ(a1[0] & (kEN | kER), kER);
  exec(1, false);
  for (ExampleNetwork* x : {&a, &b}) x->drive->set_explicit_silent(false);
  exec(1, true);  // starts again
  exec(1, true);
  advance(50);
  exec(1, true);  // DN
  EXPECT_EQ(a1[0] & (kEN | kDN), kEN | kDN);
  exec(1, true);   // EN still set: nothing to do
  exec(1, false);  // EN clears
  exec(2, true);   // starts
  pa.abandon();
  pb.abandon();
  exec(2, true);   // abandoned, EN still set
  exec(2, false);  // EN clears
  EXPECT_EQ(a2[0] & kEN, 0);
  EXPECT_GE(untimed, 8);
}

}  // namespace
}  // namespace softslc::devicenet::test
