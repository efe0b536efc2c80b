// EtherNet/IP encapsulation, byte for byte: CIP Vol. 2 chapter 2 (the 24-byte header,
// RegisterSession's protocol version 1 and options 0, ListIdentity item 000Ch, SendRRData's
// interface handle, timeout and common packet format) and the frames nodepccc 0.1.17 sends.
#include <gtest/gtest.h>

#include "tests/serve/serve_test_util.h"

namespace softslc::serve::testing {
namespace {

class EipTest : public ::testing::Test {
 protected:
  LiveController live{hmi_program(), std::nullopt, {}};
  eip::EipSession session{live, live.identity(), 0x11223344};
  std::uint32_t register_session() {
    auto out = session.handle(register_session_frame());
    EXPECT_FALSE(out.close);
    return out.reply.size() >= 8 ? static_cast<std::uint32_t>(out.reply[4] | out.reply[5] << 8 | out.reply[6] << 16 |
                                                               out.reply[7] << 24)
                                 : 0;
  }
};

TEST_F(EipTest, RegisterSessionReplyEchoesContextAndGivesAHandle) {
  auto out = session.handle(register_session_frame());
  EXPECT_EQ(out.reply, (Bytes{0x65, 0x00, 0x04, 0x00, 0x44, 0x33, 0x22, 0x11, 0x00, 0x00, 0x00, 0x00, 0x0a, 0x0b,
                              0x0c, 0x0d, 0x0e, 0x0f, 0x0a, 0x0b, 0x00, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00}));
  EXPECT_TRUE(session.registered());
}

TEST_F(EipTest, ExecutePcccReadReturnsTheValueWhereNodepcccLooksForIt) {
  const auto handle = register_session();
  // N7:0 read with A2, TNS 1234h.
  auto out = session.handle(execute_pccc_frame(handle, {0x0F, 0x00, 0x34, 0x12, 0xA2, 0x02, 0x07, 0x89, 0x00, 0x00}));
  ASSERT_FALSE(out.close);
  const Bytes& r = out.reply;
  ASSERT_GE(r.size(), 57u);
  EXPECT_EQ(r[0], 0x6F);
  EXPECT_EQ(r[2] | r[3] << 8, static_cast<int>(r.size()) - 24);  // length
  EXPECT_EQ(r[36], 0xB2);                                          // unconnected data item
  EXPECT_EQ(r[38] | r[39] << 8, static_cast<int>(r.size()) - 40);  // its length
  EXPECT_EQ((Bytes{r[40], r[41], r[42], r[43]}), (Bytes{0xCB, 0x00, 0x00, 0x00}));  // 4Bh | 80h, success
  EXPECT_EQ((Bytes(r.begin() + 44, r.begin() + 51)), (Bytes{0x07, 0x00, 0x00, 0x01, 0x02, 0x03, 0x04}));
  EXPECT_EQ(pccc_reply_of(r), (Bytes{0x4F, 0x00, 0x34, 0x12, 0xF4, 0x01}));
}

TEST_F(EipTest, UnconnectedSendToTheConnectionManagerIsUnwrapped) {
  const auto handle = register_session();
  // 52h to class 6 instance 1, priority 0Ah, 09h ticks, the embedded Execute PCCC, route 1 word
  // (port 1 slot 0) — nodepccc's Routing_Header with a connection path.
  const Bytes inner = {0x4B, 0x02, 0x20, 0x67, 0x24, 0x01, 0x07, 0x00, 0x00, 0x01, 0x02, 0x03, 0x04,
                       0x0F, 0x00, 0x01, 0x00, 0xA2, 0x02, 0x07, 0x89, 0x00, 0x00};
  const Bytes cip = cat({{0x52, 0x02, 0x20, 0x06, 0x24, 0x01, 0x0A, 0x09}, le16(static_cast<std::uint16_t>(inner.size())),
                         inner, {0x00}, {0x01, 0x00, 0x01, 0x00}});
  const Bytes data = cat({le32(0), le16(10), le16(2), le16(0), le16(0), le16(0xB2), le16(static_cast<std::uint16_t>(cip.size())), cip});
  auto out = session.handle(cat({header(0x6F, static_cast<std::uint16_t>(data.size()), handle), data}));
  ASSERT_FALSE(out.close);
  EXPECT_EQ(pccc_reply_of(out.reply), (Bytes{0x4F, 0x00, 0x01, 0x00, 0xF4, 0x01}));
}

TEST_F(EipTest, AWrongSessionHandleIsStatus64h) {
  register_session();
  auto out = session.handle(execute_pccc_frame(0xDEADBEEF, {0x0F, 0x00, 1, 0, 0xA2, 0x02, 0x07, 0x89, 0x00, 0x00}));
  ASSERT_EQ(out.reply.size(), 24u);
  EXPECT_EQ(out.reply[8], 0x64);
  EXPECT_FALSE(out.close);
}

TEST_F(EipTest, MalformedFramesCloseTheConnectionAndChangeNothing) {
  const auto handle = register_session();
  const auto before = live.controller().data_digest();
  // A header whose length disagrees with the bytes.
  Bytes bad = execute_pccc_frame(handle, {0x0F, 0x00, 1, 0, 0xAA, 0x02, 0x07, 0x89, 0x00, 0x00, 0x01, 0x00});
  bad.pop_back();
  EXPECT_TRUE(session.handle(bad).close);
  // A PCCC write whose size byte lies.
  EXPECT_TRUE(session.handle(execute_pccc_frame(handle, {0x0F, 0x00, 1, 0, 0xAA, 0x08, 0x07, 0x89, 0x00, 0x00, 0x01, 0x00})).close);
  // A CPF item running past the end.
  Bytes cpf = cat({le32(0), le16(10), le16(2), le16(0), le16(0), le16(0xB2), le16(200), {0x4B}});
  EXPECT_TRUE(session.handle(cat({header(0x6F, static_cast<std::uint16_t>(cpf.size()), handle), cpf})).close);
  EXPECT_EQ(live.controller().data_digest(), before);
}

TEST_F(EipTest, ListIdentityReportsARockwellPlc) {
  auto out = session.handle(header(0x63, 0, 0));
  const Bytes& r = out.reply;
  ASSERT_GT(r.size(), 24u + 2 + 4 + 2 + 16 + 14);
  EXPECT_EQ(r[24] | r[25] << 8, 1);       // one item
  EXPECT_EQ(r[26] | r[27] << 8, 0x000C);  // CIP identity
  const std::size_t item = 30;
  EXPECT_EQ((Bytes{r[item + 2], r[item + 3], r[item + 4], r[item + 5]}), (Bytes{0x00, 0x02, 0xAF, 0x12}));  // AF_INET, 44818 big-endian
  EXPECT_EQ(r[item + 18] | r[item + 19] << 8, 1);     // vendor: Rockwell Automation
  EXPECT_EQ(r[item + 20] | r[item + 21] << 8, 0x0E);  // device type: PLC
  const std::size_t name = item + 32;
  const std::string product(r.begin() + static_cast<std::ptrdiff_t>(name) + 1,
                            r.begin() + static_cast<std::ptrdiff_t>(name) + 1 + r[name]);
  EXPECT_EQ(product.rfind("1747-L552", 0), 0u);
}

TEST_F(EipTest, UnRegisterSessionCloses) {
  const auto handle = register_session();
  EXPECT_TRUE(session.handle(header(0x66, 0, handle)).close);
}

}  // namespace
}  // namespace softslc::serve::testing
