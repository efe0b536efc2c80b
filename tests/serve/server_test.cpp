// Fault tests against the real server on loopback: clients that misbehave lose their own
// connection and nothing else; the data table is unchanged by anything that is not a write.
// The server runs on its io_context in a second thread; the test talks to it with blocking
// sockets, as an HMI would.
#include <gtest/gtest.h>

#include <thread>

#include "server/server.h"
#include "tests/serve/serve_test_util.h"

namespace softslc::serve::testing {
namespace {

using asio::ip::tcp;

class ServerTest : public ::testing::Test {
 protected:
  void start(const LiveOptions& lo = {}, ServerOptions so = {}) {
    live_.emplace(hmi_program(), std::nullopt, lo);
    live_->controller().force("I:1/3", false);
    so.port = 0;
    so.idle_timeout = std::chrono::milliseconds(500);
    server_ = std::make_unique<Server>(io_, *live_, so);
    server_->start();
    port_ = server_->tcp_port();
    thread_ = std::thread([this] { io_.run(); });
  }
  void TearDown() override {
    if (!thread_.joinable()) return;
    asio::post(io_, [this] { server_->stop(); io_.stop(); });
    thread_.join();
  }

  tcp::socket connect() {
    tcp::socket s(client_io_);
    s.connect(tcp::endpoint(asio::ip::make_address("127.0.0.1"), port_));
    return s;
  }
  static Bytes exchange(tcp::socket& s, const Bytes& frame) {
    asio::write(s, asio::buffer(frame));
    Bytes reply(24);
    asio::read(s, asio::buffer(reply));
    const std::size_t len = reply[2] | reply[3] << 8;
    reply.resize(24 + len);
    if (len) asio::read(s, asio::buffer(reply.data() + 24, len));
    return reply;
  }
  static std::uint32_t register_session(tcp::socket& s) {
    const Bytes r = exchange(s, register_session_frame());
    return static_cast<std::uint32_t>(r[4] | r[5] << 8 | r[6] << 16 | r[7] << 24);
  }
  // Whether the server closed the connection (a read ends with EOF or reset within the time).
  static bool closed_by_server(tcp::socket& s) {
    std::uint8_t b;
    boost::system::error_code ec;
    s.read_some(asio::buffer(&b, 1), ec);
    return ec == asio::error::eof || ec == asio::error::connection_reset;
  }
  Bytes read_n7_0(tcp::socket& s, std::uint32_t handle) {
    return pccc_reply_of(exchange(s, execute_pccc_frame(handle, {0x0F, 0x00, 1, 0, 0xA2, 0x02, 0x07, 0x89, 0x00, 0x00})));
  }

  asio::io_context io_;
  asio::io_context client_io_;
  std::optional<LiveController> live_;
  std::unique_ptr<Server> server_;
  std::thread thread_;
  std::uint16_t port_ = 0;
};

TEST_F(ServerTest, MisbehavingClientsLoseOnlyTheirOwnConnection) {
  start();
  auto good = connect();
  const auto handle = register_session(good);
  EXPECT_EQ(read_n7_0(good, handle), (Bytes{0x4F, 0x00, 1, 0, 0xF4, 0x01}));

  {  // Disconnects in the middle of a request: half a header.
    auto s = connect();
    const Bytes frame = register_session_frame();
    asio::write(s, asio::buffer(frame.data(), 10));
  }
  {  // Disconnects with half a frame's data sent.
    auto s = connect();
    const auto h = register_session(s);
    Bytes frame = execute_pccc_frame(h, {0x0F, 0x00, 1, 0, 0xAA, 0x02, 0x07, 0x89, 0x00, 0x00, 0x39, 0x30});
    asio::write(s, asio::buffer(frame.data(), frame.size() - 5));
  }
  {  // Oversized: a header announcing 60000 data bytes is refused before they are read.
    auto s = connect();
    asio::write(s, asio::buffer(header(0x6F, 60000, 0)));
    EXPECT_TRUE(closed_by_server(s));
  }
  {  // Malformed PCCC (a write whose size byte lies): the connection closes, nothing is written.
    auto s = connect();
    const auto h = register_session(s);
    asio::write(s, asio::buffer(execute_pccc_frame(h, {0x0F, 0x00, 1, 0, 0xAA, 0x08, 0x07, 0x89, 0x00, 0x00, 0x39, 0x30})));
    EXPECT_TRUE(closed_by_server(s));
  }
  // The good client is still served, and N7:0 still holds its download value (the half-sent
  // write of 12345 never happened).
  EXPECT_EQ(read_n7_0(good, handle), (Bytes{0x4F, 0x00, 1, 0, 0xF4, 0x01}));
}

TEST_F(ServerTest, HalfAFrameThenSilenceIsClosedByTheIdleTimeout) {
  start();  // idle timeout 500 ms
  auto s = connect();
  const auto h = register_session(s);
  Bytes frame = execute_pccc_frame(h, {0x0F, 0x00, 1, 0, 0xAA, 0x02, 0x07, 0x89, 0x00, 0x00, 0x39, 0x30});
  asio::write(s, asio::buffer(frame.data(), frame.size() - 5));
  EXPECT_TRUE(closed_by_server(s));
  auto good = connect();
  EXPECT_EQ(read_n7_0(good, register_session(good)), (Bytes{0x4F, 0x00, 1, 0, 0xF4, 0x01}));
}

TEST_F(ServerTest, ThousandConnectDisconnectCycles) {
  start();
  for (int i = 0; i < 1000; ++i) {
    auto s = connect();
    if (i % 2) register_session(s);
  }
  auto good = connect();
  const auto handle = register_session(good);
  EXPECT_EQ(read_n7_0(good, handle), (Bytes{0x4F, 0x00, 1, 0, 0xF4, 0x01}));
}

TEST_F(ServerTest, ConnectionsBeyondTheLimitAreClosed) {
  ServerOptions so;
  so.max_connections = 2;
  start({}, so);
  auto a = connect();
  register_session(a);
  auto b = connect();
  register_session(b);
  auto c = connect();
  EXPECT_TRUE(closed_by_server(c));
  const auto h = register_session(a);
  (void)h;
}

TEST_F(ServerTest, WriteToAForcedInputIsAcceptedAndTheForceHolds) {
  start();
  auto s = connect();
  const auto handle = register_session(s);
  // I:1 (I file element 0) = 0009h: bit 0 and the forced-off bit 3.
  EXPECT_EQ(pccc_reply_of(exchange(s, execute_pccc_frame(handle, {0x0F, 0x00, 2, 0, 0xAA, 0x02, 0x01, 0x8C, 0x00, 0x00, 0x09, 0x00}))),
            (Bytes{0x4F, 0x00, 2, 0}));
  std::this_thread::sleep_for(std::chrono::milliseconds(100));  // a few paced scans
  EXPECT_EQ(pccc_reply_of(exchange(s, execute_pccc_frame(handle, {0x0F, 0x00, 3, 0, 0xA2, 0x02, 0x01, 0x8C, 0x00, 0x00}))),
            (Bytes{0x4F, 0x00, 3, 0, 0x01, 0x00}));
}

TEST_F(ServerTest, ReadOnlyServerRefusesWrites) {
  LiveOptions lo;
  lo.read_only = true;
  start(lo);
  auto s = connect();
  const auto handle = register_session(s);
  EXPECT_EQ(pccc_reply_of(exchange(s, execute_pccc_frame(handle, {0x0F, 0x00, 4, 0, 0xAA, 0x02, 0x07, 0x89, 0x00, 0x00, 0x39, 0x30}))),
            (Bytes{0x4F, 0xF0, 4, 0, 0x10}));
  EXPECT_EQ(read_n7_0(s, handle), (Bytes{0x4F, 0x00, 1, 0, 0xF4, 0x01}));
}

}  // namespace
}  // namespace softslc::serve::testing
