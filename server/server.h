// The network face of `softslc serve`: EtherNet/IP on TCP and UDP, on one Boost.Asio io_context.
//
// Everything runs on the caller's io_context in one thread: the accept loop, every connection's
// reads and writes, the UDP ListIdentity responder and the pacing timer that advances the
// LiveController. So a request is always handled between two scans, with no lock, and the
// journal's order is the order things happened. The online view (server/web.h: HTTP + WebSocket
// through Boost.Beast) adds its own acceptor to the same io_context and reads the controller from
// its handlers, on the same thread, the same way (docs/serve.md).
//
// Boost.Asio rather than standalone Asio because Beast is built on it; `asio` below is a
// namespace alias for boost::asio, so the code reads as it did with standalone Asio.
//
// Bounds (ServerOptions, all documented in docs/serve.md): connections at once, the largest
// encapsulation frame accepted, and idle time per connection. A connection past the limit is
// accepted and closed at once (the client sees the refusal), a frame longer than the limit
// closes its connection before any of it is read into memory, a connection silent longer than
// the idle time is closed. Each closure is logged with spdlog; none affects other connections.
//
// Modbus TCP (server/modbus.h), when ServerOptions::modbus_port is set, is a second acceptor on
// the same io_context with the same bounds (the connection limit counts both protocols), for a
// MicroLogix 1100/1400 program whose channel is configured as a Modbus slave.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

// <utility> first: Boost 1.74's asio/awaitable.hpp uses std::exchange without including it (GCC 12, C++20).
#include <utility>

#include <boost/asio.hpp>

#include "server/live.h"
#include "server/modbus.h"

namespace asio = boost::asio;

namespace softslc::serve {

struct ServerOptions {
  std::string listen = "127.0.0.1";
  std::uint16_t port = eip::kPort;  // 0: any free port (tests)
  std::size_t max_connections = 64;
  std::size_t max_frame = 4096;  // encapsulation data bytes
  std::chrono::milliseconds idle_timeout{60000};
  std::chrono::milliseconds tick{10};  // pacing timer period
  // Modbus TCP on this port (0: any free port) with this map; none: no Modbus.
  std::optional<std::uint16_t> modbus_port;
  modbus::Map modbus_map;
};

// Opens, binds and listens (reusing the address); throws std::system_error when it cannot.
void listen_on(asio::ip::tcp::acceptor& acceptor, const asio::ip::tcp::endpoint& ep);

class Server {
 public:
  Server(asio::io_context& io, LiveController& live, ServerOptions options);
  ~Server();
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  // Opens the sockets and starts accepting and pacing. Throws std::system_error when the
  // address cannot be bound.
  void start();
  // Closes every socket and stops the timer; the io_context then runs out of work.
  void stop();
  std::uint16_t tcp_port() const;
  // The Modbus TCP port (0 when Modbus is off).
  std::uint16_t modbus_port() const;
  std::size_t connections() const;
  // The longest wall time between two pacing ticks: with LiveController::max_lag() it bounds how
  // far virtual time trailed the wall clock (times the speed).
  std::chrono::nanoseconds max_tick_gap() const { return max_tick_gap_; }
  // Restarts the pacing wall clock (after resume()).
  void restart_pacing();

  struct Link;
  struct Connection;
  struct ModbusConnection;

 private:
  void accept();
  void accept_modbus();
  template <typename Open>
  void accept_on(asio::ip::tcp::acceptor& acceptor, std::string_view protocol, Open open);
  void receive_udp();
  void tick();
  eip::Identity identity() const;

  LiveController& live_;
  ServerOptions options_;
  asio::ip::tcp::acceptor acceptor_;
  asio::ip::tcp::acceptor modbus_acceptor_;
  asio::ip::udp::socket udp_;
  asio::steady_timer timer_;
  std::chrono::steady_clock::time_point pacing_start_;
  std::chrono::steady_clock::time_point last_tick_;
  std::chrono::nanoseconds max_tick_gap_{0};
  std::uint32_t next_session_ = 0x00010000;
  std::shared_ptr<std::size_t> live_connections_ = std::make_shared<std::size_t>(0);
  std::array<std::uint8_t, 600> udp_buffer_{};
  asio::ip::udp::endpoint udp_peer_;
  bool stopped_ = false;
};

}  // namespace softslc::serve
