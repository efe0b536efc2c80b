// Explicit Message Program Control (appendix E, p.143-151): transaction blocks written to
// M0:224...255 and read from M1:224...255, each command, every status the model produces, the
// ten-transaction limit, TXID reuse, deletion, reset, response order, and the decoder's totality.
#include <gtest/gtest.h>

#include <random>

#include "tests/devicenet/devicenet_test_util.h"

namespace softslc::devicenet::test {
namespace {

constexpr std::uint8_t kExecute = 1, kGetStatus = 2, kResetAll = 3, kDelete = 4;
constexpr std::uint8_t kGetAttributeSingle = 0x0E, kSetAttributeSingle = 0x10, kGetAttributesAll = 0x01;
constexpr std::uint16_t kResponseAvailable = 1u << 15;

Block request(std::uint8_t command, std::uint8_t txid, std::uint8_t mac, std::uint8_t service = kGetAttributeSingle,
              std::uint8_t cls = 1, std::uint16_t instance = 1, std::uint8_t attribute = 1, Bytes data = {},
              std::optional<int> size = std::nullopt, std::uint8_t port = 0) {
  RequestBlock r;
  r.command = command;
  r.txid = txid;
  r.port = port;
  r.size = static_cast<std::uint8_t>(size ? *size : kRequestPathBytes + static_cast<int>(data.size()));
  r.service = service;
  r.mac = mac;
  r.class_id = cls;
  r.instance = instance;
  r.attribute = attribute;
  r.data = std::move(data);
  return encode_request(r);
}

// Writes the block to M0:224...255 word by word, as a COP would, then tells the scanner.
void send(ExampleNetwork& x, const Block& b) {
  for (int k = 0; k < 32; ++k) x.m0(layout::kTransactionBlock + k, b[static_cast<std::size_t>(k)]);
  x.sdn->process_request_block();
}

ResponseBlock m1_block(const ExampleNetwork& x) {
  Block b{};
  for (int k = 0; k < 32; ++k) b[static_cast<std::size_t>(k)] = x.m1(layout::kTransactionBlock + k);
  return decode_response(b);
}

struct Running : ::testing::Test {
  Running() : x(true) {
    x.run();
    x.start();
  }
  ExampleNetwork x;
};

// ---- layout ---------------------------------------------------------------------------------------

// The header words: TXID : command, port : size, service : MAC ID (p.145, p.148 and the DEM's words
// 6-8, p.101); the request body: class, instance, attribute, data.
TEST(TransactionLayout, RequestWords) {
  const Block b = request(kExecute, 5, 20, kSetAttributeSingle, 0x0F, 39, 1, {0x2C, 0x01});
  EXPECT_EQ(b[0], 0x0501);
  EXPECT_EQ(b[1], 0x0008);  // port 0, body 6 + 2 bytes
  EXPECT_EQ(b[2], 0x1014);  // service 0x10, MAC 20
  EXPECT_EQ(b[3], 0x000F);
  EXPECT_EQ(b[4], 39);
  EXPECT_EQ(b[5], 1);
  EXPECT_EQ(b[6], 0x012C);  // data bytes, low byte first
  const RequestBlock r = decode_request(b);
  EXPECT_EQ(r.txid, 5);
  EXPECT_EQ(r.command, 1);
  EXPECT_EQ(r.size, 8);
  EXPECT_EQ(r.data, (Bytes{0x2C, 0x01}));
}

// "The transaction body can be as many as 29 words (58 bytes)" (p.147): 52 data bytes at most.
TEST(TransactionLayout, BodyLimits) {
  Bytes data(52);
  for (std::size_t i = 0; i < data.size(); ++i) data[i] = static_cast<std::uint8_t>(i + 1);
  const RequestBlock r = decode_request(request(kExecute, 1, 7, 0x10, 1, 1, 1, data));
  EXPECT_EQ(r.size, 58);
  EXPECT_EQ(r.data, data);
  EXPECT_FALSE(check_request(r).has_value());
  ResponseBlock resp{1, 9, 0, 0x8E, 7, Bytes(58, 0xAB)};
  EXPECT_EQ(decode_response(encode_response(resp)).data.size(), 58u);
  EXPECT_EQ(encode_response(resp)[1], 58);
}

TEST(TransactionLayout, CodeTables) {
  EXPECT_EQ(txn_command_text(1), "Execute this transaction block");
  EXPECT_EQ(txn_command_text(4), "Delete transaction from response queue");
  EXPECT_TRUE(txn_command_text(5).empty());
  for (int s = 0; s <= 15; ++s) EXPECT_FALSE(txn_status_text(static_cast<std::uint8_t>(s)).empty()) << s;
  EXPECT_TRUE(txn_status_text(16).empty());
  EXPECT_EQ(txn_status_text(14), "Error - invalid size specified");
}

// ---- execute and the statuses ----------------------------------------------------------------------

// Status 1 with the reply: Get_Attribute_Single of the Identity vendor ID (service 0E hex, p.149).
TEST_F(Running, ExecuteSucceeds) {
  EXPECT_EQ(x.sdn->status_register() & kResponseAvailable, 0);
  EXPECT_EQ(m1_block(x).status, 0);  // "0 Ignore transaction block (block empty)"
  send(x, request(kExecute, 1, kRediStationNode));
  x.advance_ms(50);
  EXPECT_EQ(x.sdn->status_register() & kResponseAvailable, kResponseAvailable);
  const ResponseBlock r = m1_block(x);
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.txid, 1);
  EXPECT_EQ(r.mac, kRediStationNode);
  EXPECT_EQ(r.service, 0x8E);
  EXPECT_EQ(r.data, (Bytes{1, 0}));  // vendor 1
  // Step 5 of p.144: delete the response with its TXID; the TXID can be reused.
  send(x, request(kDelete, 1, 0));
  EXPECT_EQ(x.sdn->status_register() & kResponseAvailable, 0);
  EXPECT_FALSE(x.sdn->txid_in_use(1));
}

// "If a slave device returns a DeviceNet error ... the scanner recognizes the error as a successful
// transaction (status code = 1)"; the error has a general code and an additional code, 0FFH when
// unused (p.150-151). 14H: attribute not supported.
TEST_F(Running, SlaveErrorIsASuccessfulTransaction) {
  send(x, request(kExecute, 2, kRediStationNode, kGetAttributeSingle, 1, 1, 99));
  x.advance_ms(50);
  const ResponseBlock r = m1_block(x);
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.service, 0x94);
  EXPECT_EQ(r.data, (Bytes{0x14, 0xFF}));
}

// Status 2 "Transaction in progress (not ready)" through command 2 "Get status of transaction TXID".
TEST_F(Running, GetStatusInProgressThenDone) {
  send(x, request(kExecute, 3, kDriveNode, kGetAttributeSingle, 0x0F, 39, 1));
  send(x, request(kGetStatus, 3, 0));
  EXPECT_EQ(m1_block(x).status, 2);
  EXPECT_EQ(m1_block(x).txid, 3);
  x.advance_ms(50);
  send(x, request(kGetStatus, 3, 0));  // the newer report replaces the older
  EXPECT_EQ(x.sdn->responses_queued(), 2u);
  const ResponseBlock head = m1_block(x);
  EXPECT_EQ(head.status, 1);
  EXPECT_EQ(head.data, (Bytes{100, 0}));  // Accel Time 1 default 100
  send(x, request(kDelete, 3, 0));
  EXPECT_EQ(x.sdn->responses_queued(), 0u);
}

// Status 3 "slave not in scanlist": "Request Transaction Blocks can be queued only for slave devices
// of the module and must appear in the module's scanlist" (p.149).
TEST_F(Running, SlaveNotInScanlist) {
  send(x, request(kExecute, 4, 30));
  EXPECT_EQ(m1_block(x).status, 3);
  send(x, request(kDelete, 4, 0));
  send(x, request(kExecute, 5, 200));  // not even an address
  EXPECT_EQ(m1_block(x).status, 3);
}

// Status 4 "slave offline": "If a slave device is not communicating at the time the module
// processes its Request Transaction Block, the module will return an error status" (p.149).
TEST_F(Running, SlaveOffline) {
  x.eye->set_online(false);
  x.advance_ms(400);
  send(x, request(kExecute, 6, kPhotoeyeNode));
  EXPECT_EQ(m1_block(x).status, 4);
}

// Status 5 "DeviceNet port disabled/offline"; a request in flight when the port stops gets it too.
TEST_F(Running, PortDisabled) {
  send(x, request(kExecute, 7, kDriveNode));
  x.command(bit(CommandBit::Run) | bit(CommandBit::DisableNetwork));
  EXPECT_EQ(m1_block(x).status, 5);
  EXPECT_EQ(m1_block(x).txid, 7);
  send(x, request(kExecute, 8, kRediStationNode));
  EXPECT_EQ(x.sdn->completed_response(8)->status, 5);
}

// Status 6 "transaction TXID unknown".
TEST_F(Running, GetStatusOfUnknownTxid) {
  send(x, request(kGetStatus, 77, 0));
  EXPECT_EQ(m1_block(x).status, 6);
  EXPECT_EQ(m1_block(x).txid, 77);
}

// Status 7 "slave not responding to explicit request": "A failure to respond to the request within
// the number of retries or timeout period ... is recognized by the module as an error" (p.150).
// Three attempts of 500 ms (timing.h).
TEST_F(Running, SlaveNotResponding) {
  x.redi->set_explicit_silent(true);
  send(x, request(kExecute, 9, kRediStationNode));
  x.advance_ms(1400);
  EXPECT_FALSE(x.sdn->completed_response(9).has_value());
  x.advance_ms(200);
  ASSERT_TRUE(x.sdn->completed_response(9).has_value());
  EXPECT_EQ(x.sdn->completed_response(9)->status, 7);
  EXPECT_TRUE(x.sdn->connected(kRediStationNode));  // I/O was never affected
}

// Status 8 "invalid command code" for the reserved commands 5...255.
TEST_F(Running, InvalidCommand) {
  for (int cmd : {5, 99, 255}) {
    send(x, request(static_cast<std::uint8_t>(cmd), 10, kRediStationNode));
    EXPECT_EQ(m1_block(x).status, 8) << cmd;
    send(x, request(kDelete, 10, 0));
  }
}

// Status 11 "could not connect to slave device": a node whose connection was refused.
TEST_F(Running, CouldNotConnect) {
  x.redi->set_produced_size_override(2);
  x.redi->set_online(false);
  x.advance_ms(400);
  x.redi->set_online(true);
  x.advance_ms(1100);
  ASSERT_EQ(x.sdn->node_code(kRediStationNode), 77);
  send(x, request(kExecute, 11, kRediStationNode));
  EXPECT_EQ(m1_block(x).status, 11);
}

// Status 12 "response data too large for block": the drive's fault history is 78 bytes.
TEST_F(Running, ResponseTooLarge) {
  send(x, request(kExecute, 12, kDriveNode, kGetAttributesAll, 151, 1, 0));
  x.advance_ms(50);
  EXPECT_EQ(m1_block(x).status, 12);
  EXPECT_TRUE(m1_block(x).data.empty());
}

// Status 13 "invalid port": "the DeviceNet port (zero)" (p.147).
TEST_F(Running, InvalidPort) {
  send(x, request(kExecute, 13, kRediStationNode, kGetAttributeSingle, 1, 1, 1, {}, std::nullopt, 1));
  EXPECT_EQ(m1_block(x).status, 13);
}

// Status 14 "invalid size specified": "If the size exceeds 29 words, an error code will be
// returned" (p.147); a request body also needs its 6 bytes of class, instance and attribute.
TEST_F(Running, InvalidSize) {
  for (int size : {59, 255, 5, 0}) {
    send(x, request(kExecute, 14, kRediStationNode, kGetAttributeSingle, 1, 1, 1, {}, size));
    EXPECT_EQ(m1_block(x).status, 14) << size;
    send(x, request(kDelete, 14, 0));
  }
}

// Explicit messages to the scanner's own address are executed by the scanner (p.95).
TEST_F(Running, ScannerAnswersAtItsOwnAddress) {
  send(x, request(kExecute, 15, kScannerNode, kGetAttributeSingle, 1, 1, 7));
  const ResponseBlock r = m1_block(x);
  EXPECT_EQ(r.status, 1);
  ASSERT_FALSE(r.data.empty());
  EXPECT_EQ(std::string(r.data.begin() + 1, r.data.end()), "1747-SDN Scanner Module");
}

// ---- the queue -------------------------------------------------------------------------------------

// "A maximum of ten Explicit Message Request Transaction Blocks with the execute command can be
// queued ... The module receives and deletes any additional ... requests" (p.149).
TEST_F(Running, TenTransactionsAtMost) {
  x.drive->set_explicit_silent(true);  // keeps them all in progress
  for (int t = 1; t <= 10; ++t) send(x, request(kExecute, static_cast<std::uint8_t>(t), kDriveNode));
  EXPECT_EQ(x.sdn->transactions_in_use(), 10u);
  EXPECT_EQ(x.sdn->handle_request(decode_request(request(kExecute, 11, kDriveNode))), Scanner::Accept::Dropped);
  EXPECT_FALSE(x.sdn->txid_in_use(11));
  send(x, request(kDelete, 4, 0));
  EXPECT_EQ(x.sdn->handle_request(decode_request(request(kExecute, 11, kDriveNode))), Scanner::Accept::Queued);
  EXPECT_EQ(x.sdn->transactions_in_use(), 10u);
}

// "Client/Server commands and requests with transaction IDs that are in use are ignored" (p.150);
// after the delete the TXID can be reused (p.144).
TEST_F(Running, TxidReuse) {
  send(x, request(kExecute, 20, kRediStationNode, kGetAttributeSingle, 1, 1, 1));
  send(x, request(kExecute, 20, kRediStationNode, kGetAttributeSingle, 1, 1, 3));  // ignored
  x.advance_ms(50);
  EXPECT_EQ(x.sdn->responses_queued(), 1u);
  EXPECT_EQ(m1_block(x).data, (Bytes{1, 0}));  // attribute 1, not 3
  send(x, request(kExecute, 20, kRediStationNode, kGetAttributeSingle, 1, 1, 3));  // still in use
  x.advance_ms(50);
  EXPECT_EQ(x.sdn->responses_queued(), 1u);
  send(x, request(kDelete, 20, 0));
  send(x, request(kExecute, 20, kRediStationNode, kGetAttributeSingle, 1, 1, 3));
  x.advance_ms(50);
  EXPECT_EQ(m1_block(x).data, (Bytes{0x91, 0x0A}));  // product code 2705
  // A zero TXID is outside 1...255 (p.146): ignored.
  EXPECT_EQ(x.sdn->handle_request(decode_request(request(kExecute, 0, kRediStationNode))), Scanner::Accept::Ignored);
}

// Command 3 "Reset all client/server transactions".
TEST_F(Running, ResetAll) {
  send(x, request(kExecute, 30, kRediStationNode));
  send(x, request(kExecute, 31, kDriveNode));
  send(x, request(kExecute, 32, 44));
  send(x, request(kResetAll, 0, 0));
  EXPECT_EQ(x.sdn->transactions_in_use(), 0u);
  EXPECT_EQ(x.sdn->responses_queued(), 0u);
  EXPECT_EQ(x.sdn->status_register() & kResponseAvailable, 0);
  x.advance_ms(50);
  EXPECT_EQ(x.sdn->responses_queued(), 0u);  // the cancelled requests never answer
}

// "The slave responses are queued ... in the order in which they are received" (p.148): the drive
// (2 ms to answer) was asked first, the RediSTATION (1 ms) second.
TEST_F(Running, ResponsesInArrivalOrder) {
  send(x, request(kExecute, 41, kDriveNode));
  send(x, request(kExecute, 42, kRediStationNode));
  x.advance_ms(50);
  EXPECT_EQ(m1_block(x).txid, 42);
  send(x, request(kDelete, 42, 0));
  EXPECT_EQ(m1_block(x).txid, 41);
}

// Command 0 and a blank block: "an unused transaction block must be left blank" (p.150).
TEST_F(Running, BlankBlockIsIgnored) {
  send(x, Block{});
  EXPECT_EQ(x.sdn->responses_queued(), 0u);
  EXPECT_EQ(x.sdn->transactions_in_use(), 0u);
}

// ---- totality ---------------------------------------------------------------------------------------

// Any 32 words a ladder program writes give a defined outcome: the queue stays bounded (ten
// transactions, one report per TXID), every status is one of appendix E's, nothing reads outside
// the block. Run under the sanitizers this is the fuzz property in miniature.
TEST(TransactionDecoder, AnyWordsGiveADefinedStatus) {
  ExampleNetwork x(true);
  x.run();
  x.start();
  std::mt19937 rng(1747);
  std::uniform_int_distribution<int> word(0, 0xFFFF), small(0, 7), node(0, 25);
  for (int i = 0; i < 20000; ++i) {
    Block b{};
    for (auto& w : b) w = static_cast<std::uint16_t>(word(rng));
    // Bias a third of the blocks towards plausible requests so the deep paths run too.
    if (i % 3 == 0) {
      b[0] = static_cast<std::uint16_t>((b[0] & 0xFF00) | small(rng));
      b[1] = static_cast<std::uint16_t>(b[1] & 0x007F);
      b[2] = static_cast<std::uint16_t>((b[2] & 0xFF00) | node(rng));
    }
    send(x, b);
    EXPECT_LE(x.sdn->transactions_in_use(), 10u);
    EXPECT_LE(x.sdn->responses_queued(), 10u + 256u);
    if (const auto head = x.sdn->head_response()) {
      EXPECT_LE(head->status, 15);
    }
    if (i % 100 == 0) x.advance_ms(7);
  }
}

TEST(TransactionDecoder, RoundTrips) {
  std::mt19937 rng(42);
  std::uniform_int_distribution<int> byte(0, 255), len(0, 58);
  for (int i = 0; i < 1000; ++i) {
    ResponseBlock r;
    r.status = static_cast<std::uint8_t>(byte(rng) % 16);
    r.txid = static_cast<std::uint8_t>(byte(rng));
    r.service = static_cast<std::uint8_t>(byte(rng));
    r.mac = static_cast<std::uint8_t>(byte(rng) % 64);
    r.data.resize(static_cast<std::size_t>(len(rng)));
    for (auto& d : r.data) d = static_cast<std::uint8_t>(byte(rng));
    const ResponseBlock back = decode_response(encode_response(r));
    EXPECT_EQ(back.data, r.data);
    EXPECT_EQ(back.txid, r.txid);
    EXPECT_EQ(back.service, r.service);
  }
}

}  // namespace
}  // namespace softslc::devicenet::test
