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

#include <array>
#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

// <utility> first: Boost 1.74's asio/awaitable.hpp uses std::exchange without including it (GCC 12, C++20).
#include <utility>

#include <boost/asio.hpp>

#include "server/live.h"
#include "server/modbus.h"
#include "server/modbus_rtu.h"

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
  // Modbus RTU slave on a serial line (channel 0), with the same map; none: no Modbus RTU.
  struct ModbusRtu {
    std::string device;  // a serial device path, or "pty": a new pseudo-terminal (its path: modbus_rtu_path())
    std::uint8_t address = 1;
    int baud = 19200;
    char parity = 'N';  // 'N', 'E' or 'O'
  };
  std::optional<ModbusRtu> modbus_rtu;
};

// The baud rates a MicroLogix channel offers (AG-UM008C p. 3-49: 300-38.4K).
inline constexpr const auto& kModbusRtuBauds = modbus::kSlaveBauds;
// The silence that ends a Modbus RTU frame: 3.5 characters of 11 bits at `baud` (Modbus over
// Serial Line v1.02 §2.5.1.1; 1.75 ms above 19200 baud), but never under 5 ms, so the scheduling
// of the event loop and of a USB serial adapter does not cut frames.
std::chrono::microseconds modbus_rtu_silence(int baud);

// The Modbus RTU serial line could not be opened or configured (what() names the device and why).
struct SerialLineError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Opens, binds and listens (reusing the address); throws std::system_error when it cannot.
void listen_on(asio::ip::tcp::acceptor& acceptor, const asio::ip::tcp::endpoint& ep);

class Server {
 public:
  Server(asio::io_context& io, LiveController& live, ServerOptions options);
  ~Server();
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  // Opens the sockets (and the Modbus RTU serial line) and starts accepting and pacing. Throws
  // std::system_error when the address cannot be bound, SerialLineError when the line cannot be opened.
  void start();
  // Closes every socket and stops the timer; the io_context then runs out of work.
  void stop();
  std::uint16_t tcp_port() const;
  // The Modbus TCP port (0 when Modbus is off).
  std::uint16_t modbus_port() const;
  // The serial device Modbus RTU answers on (the pseudo-terminal's path for "pty"); empty when off.
  const std::string& modbus_rtu_path() const { return rtu_path_; }
  // The Modbus RTU slave (its counters), or nullptr when off.
  const modbus::RtuSlave* modbus_rtu() const { return rtu_.get(); }
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
  void open_modbus_rtu();
  void read_modbus_rtu();
  void modbus_rtu_events(modbus::RtuEvents events);
  void send_modbus_rtu();
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
  // Modbus RTU: the serial line (a device, or a pseudo-terminal's master side), the slave, the
  // silence timer, the replies waiting to be written, and for a pseudo-terminal its slave side,
  // held open so reads do not fail while no client has it open.
  asio::serial_port rtu_port_;
  asio::steady_timer rtu_silence_;
  std::shared_ptr<modbus::RtuSlave> rtu_;  // shared: Modbus TCP connections answer its parameters
  std::array<std::uint8_t, 512> rtu_buffer_{};
  std::uint64_t rtu_reads_ = 0;
  std::deque<std::vector<std::uint8_t>> rtu_out_;
  std::string rtu_path_;
  int rtu_pty_slave_ = -1;
};

}  // namespace softslc::serve
