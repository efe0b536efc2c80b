#include "server/server.h"

#include <spdlog/spdlog.h>

#include <fcntl.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <system_error>

namespace softslc::serve {

// What every TCP connection has, whatever its protocol: the socket, the idle timer that closes it
// when the client goes quiet, the bounds (a copy: a connection's handlers may outlive the
// Server) and its place in the connection count.
struct Server::Link : std::enable_shared_from_this<Server::Link> {
  Link(asio::ip::tcp::socket s, const ServerOptions& o, std::shared_ptr<std::size_t> count, std::string_view protocol)
      : socket(std::move(s)), idle(socket.get_executor()), options(o), connections(std::move(count)) {
    ++*connections;
    boost::system::error_code ec;
    auto ep = socket.remote_endpoint(ec);
    peer = ec ? std::string("?") : ep.address().to_string() + ":" + std::to_string(ep.port());
    if (!protocol.empty()) peer += " (" + std::string(protocol) + ")";
  }
  virtual ~Link() { --*connections; }

  void arm_idle() {
    idle.expires_after(options.idle_timeout);
    idle.async_wait([self = shared_from_this()](const boost::system::error_code& ec) {
      if (ec) return;  // re-armed or closed
      spdlog::info("{}: closed after {} ms without a request", self->peer, self->options.idle_timeout.count());
      self->close();
    });
  }
  void close() {
    boost::system::error_code ignored;
    socket.shutdown(asio::ip::tcp::socket::shutdown_both, ignored);
    socket.close(ignored);
    idle.cancel();
  }
  // Reads exactly `n` bytes into `frame` from `at`, then calls `then` — or closes the connection
  // (logged) when the client goes away, in the middle of a frame or not.
  template <typename Self, typename Then>
  static void read_into(const std::shared_ptr<Self>& self, std::size_t at, std::size_t n, Then then) {
    self->frame.resize(at + n);
    asio::async_read(self->socket, asio::buffer(self->frame.data() + at, n),
                     [self, at, then](const boost::system::error_code& ec, std::size_t) {
                       if (ec) {
                         if (at > 0)
                           spdlog::info("{}: connection closed in the middle of a frame: {}", self->peer, ec.message());
                         else if (ec != asio::error::eof && ec != asio::error::operation_aborted)
                           spdlog::debug("{}: connection closed: {}", self->peer, ec.message());
                         self->close();
                         return;
                       }
                       then();
                     });
  }
  // Sends `bytes`, then closes the connection or calls `then`.
  template <typename Self, typename Then>
  static void send(const std::shared_ptr<Self>& self, std::vector<std::uint8_t>&& bytes, bool close_after, Then then) {
    self->reply = std::move(bytes);
    asio::async_write(self->socket, asio::buffer(self->reply),
                      [self, close_after, then](const boost::system::error_code& ec, std::size_t) {
                        if (ec || close_after) {
                          self->close();
                          return;
                        }
                        then();
                      });
  }

  asio::ip::tcp::socket socket;
  asio::steady_timer idle;
  const ServerOptions options;
  std::shared_ptr<std::size_t> connections;
  std::vector<std::uint8_t> frame;
  std::vector<std::uint8_t> reply;
  std::string peer;
};

// One EtherNet/IP connection: read a 24-byte header, check its length against the bound, read the
// data, hand the frame to its EipSession, write the reply, repeat.
struct Server::Connection : Server::Link {
  Connection(asio::ip::tcp::socket s, LiveController& live, eip::Identity identity, std::uint32_t session,
             const ServerOptions& o, std::shared_ptr<std::size_t> count)
      : Link(std::move(s), o, std::move(count), ""), eip(live, std::move(identity), session) {}

  std::shared_ptr<Connection> self() { return std::static_pointer_cast<Connection>(shared_from_this()); }

  void start() {
    arm_idle();
    read_header();
  }

  void read_header() {
    read_into(self(), 0, eip::kHeaderSize, [self = self()] {
      self->arm_idle();
      const auto h = eip::decode_header(self->frame);
      if (!h) {  // cannot happen: 24 bytes were read; closing is the safe answer all the same
        self->close();
        return;
      }
      if (h->length > self->options.max_frame) {
        spdlog::warn("{}: frame of {} data bytes exceeds the limit of {}; connection closed", self->peer, h->length,
                     self->options.max_frame);
        self->close();
        return;
      }
      if (h->length == 0) {
        self->handle();
        return;
      }
      read_into(self, eip::kHeaderSize, h->length, [self] { self->handle(); });
    });
  }

  void handle() {
    eip::Outcome out = eip.handle(frame);
    if (!out.log.empty()) {
      if (out.close)
        spdlog::warn("{}: {}; connection closed", peer, out.log);
      else
        spdlog::debug("{}: {}", peer, out.log);
    }
    if (out.reply.empty()) {
      if (out.close)
        close();
      else
        read_header();
      return;
    }
    send(self(), std::move(out.reply), out.close, [self = self()] { self->read_header(); });
  }

  eip::EipSession eip;
};

// One Modbus TCP connection: read the 7-byte MBAP header, check its length, read the PDU, hand
// the frame to modbus::handle, write the reply, repeat.
struct Server::ModbusConnection : Server::Link {
  ModbusConnection(asio::ip::tcp::socket s, LiveController& l, const ServerOptions& o, std::shared_ptr<std::size_t> count,
                   std::shared_ptr<const modbus::RtuSlave> r)
      : Link(std::move(s), o, std::move(count), "Modbus"), live(l), rtu(std::move(r)) {}

  std::shared_ptr<ModbusConnection> self() { return std::static_pointer_cast<ModbusConnection>(shared_from_this()); }

  void start() {
    arm_idle();
    read_header();
  }

  void read_header() {
    read_into(self(), 0, modbus::kHeaderSize, [self = self()] {
      self->arm_idle();
      std::string error;
      const auto h = modbus::decode_header(self->frame, &error);
      if (!h) {  // the length is checked here, before any of the PDU is read
        spdlog::warn("{}: {}; connection closed", self->peer, error);
        self->close();
        return;
      }
      read_into(self, modbus::kHeaderSize, h->length - 1u, [self] { self->handle(); });
    });
  }

  void handle() {
    std::string error, refusal;
    // Input registers 30501-30532 report the serial channel's address and counters when there is one.
    const modbus::CommParameters comm = rtu ? rtu->comm_parameters() : modbus::comm_parameters(options.modbus_map);
    auto out = modbus::handle(frame, options.modbus_map, live, &error, &refusal, &comm);
    if (!out) {
      spdlog::warn("{}: {}; connection closed", peer, error);
      close();
      return;
    }
    if (!refusal.empty()) spdlog::debug("{}: {}", peer, refusal);
    send(self(), std::move(*out), false, [self = self()] { self->read_header(); });
  }

  LiveController& live;
  std::shared_ptr<const modbus::RtuSlave> rtu;
};

Server::Server(asio::io_context& io, LiveController& live, ServerOptions options)
    : live_(live),
      options_(std::move(options)),
      acceptor_(io),
      modbus_acceptor_(io),
      udp_(io),
      timer_(io),
      rtu_port_(io),
      rtu_silence_(io) {}

Server::~Server() {
  if (rtu_pty_slave_ >= 0) ::close(rtu_pty_slave_);
}

void listen_on(asio::ip::tcp::acceptor& acceptor, const asio::ip::tcp::endpoint& ep) {
  acceptor.open(ep.protocol());
  acceptor.set_option(asio::ip::tcp::acceptor::reuse_address(true));
  acceptor.bind(ep);
  acceptor.listen();
}

void Server::start() {
  const auto address = asio::ip::make_address(options_.listen);
  listen_on(acceptor_, asio::ip::tcp::endpoint(address, options_.port));
  // ListIdentity is also answered on UDP, on the same port number as TCP.
  const asio::ip::udp::endpoint udp_ep(address, acceptor_.local_endpoint().port());
  udp_.open(udp_ep.protocol());
  udp_.set_option(asio::ip::udp::socket::reuse_address(true));
  udp_.bind(udp_ep);
  if (options_.modbus_port) {
    listen_on(modbus_acceptor_, asio::ip::tcp::endpoint(address, *options_.modbus_port));
    accept_modbus();
  }
  if (options_.modbus_rtu) {
    try {
      open_modbus_rtu();
    } catch (const std::exception& e) {
      throw SerialLineError("cannot open the Modbus RTU line " + options_.modbus_rtu->device + ": " + e.what());
    }
  }
  accept();
  receive_udp();
  restart_pacing();
  tick();
}

void Server::stop() {
  stopped_ = true;
  boost::system::error_code ignored;
  acceptor_.close(ignored);
  modbus_acceptor_.close(ignored);
  udp_.close(ignored);
  timer_.cancel();
  rtu_port_.close(ignored);
  rtu_silence_.cancel();
  if (rtu_pty_slave_ >= 0) ::close(rtu_pty_slave_);
  rtu_pty_slave_ = -1;
}

std::uint16_t Server::tcp_port() const { return acceptor_.local_endpoint().port(); }
std::size_t Server::connections() const { return *live_connections_; }
std::uint16_t Server::modbus_port() const {
  boost::system::error_code ec;
  return modbus_acceptor_.is_open() ? modbus_acceptor_.local_endpoint(ec).port() : 0;
}

eip::Identity Server::identity() const {
  // The socket address item carries the address and port clients reach this server on.
  eip::Identity id = live_.identity();
  id.port = tcp_port();
  boost::system::error_code ec;
  const auto address = asio::ip::make_address(options_.listen, ec);
  if (!ec && address.is_v4()) id.ipv4 = address.to_v4().to_uint();
  return id;
}

void Server::restart_pacing() { pacing_start_ = std::chrono::steady_clock::now(); }

// Accepts on `acceptor` until it closes: past the connection limit a new connection is closed at
// once (logged); otherwise `open(socket)` starts its protocol.
template <typename Open>
void Server::accept_on(asio::ip::tcp::acceptor& acceptor, std::string_view protocol, Open open) {
  acceptor.async_accept([this, &acceptor, protocol, open](const boost::system::error_code& ec, asio::ip::tcp::socket socket) {
    if (ec) {
      if (ec == asio::error::operation_aborted || stopped_) return;
      spdlog::warn("{} accept failed: {}", protocol, ec.message());
    } else if (*live_connections_ >= options_.max_connections) {
      spdlog::warn("refused a {} connection: {} connections is the limit", protocol, options_.max_connections);
      boost::system::error_code ignored;
      socket.close(ignored);
    } else {
      boost::system::error_code ignored;
      socket.set_option(asio::ip::tcp::no_delay(true), ignored);
      open(std::move(socket));
    }
    accept_on(acceptor, protocol, open);
  });
}

void Server::accept() {
  accept_on(acceptor_, "EtherNet/IP", [this](asio::ip::tcp::socket socket) {
    auto c = std::make_shared<Connection>(std::move(socket), live_, identity(), next_session_++, options_,
                                          live_connections_);
    spdlog::debug("{}: connected", c->peer);
    c->start();
  });
}

void Server::accept_modbus() {
  accept_on(modbus_acceptor_, "Modbus TCP", [this](asio::ip::tcp::socket socket) {
    auto c = std::make_shared<ModbusConnection>(std::move(socket), live_, options_, live_connections_, rtu_);
    spdlog::debug("{}: connected", c->peer);
    c->start();
  });
}

void Server::receive_udp() {
  udp_.async_receive_from(asio::buffer(udp_buffer_), udp_peer_, [this](const boost::system::error_code& ec, std::size_t n) {
    if (ec) {
      if (ec == asio::error::operation_aborted || stopped_) return;
      receive_udp();
      return;
    }
    const auto h = eip::decode_header(std::span<const std::uint8_t>(udp_buffer_.data(), n));
    // Only ListIdentity (and ListServices) are answered over UDP; anything else is ignored.
    if (h && h->length + eip::kHeaderSize == n &&
        (h->command == eip::kListIdentity || h->command == eip::kListServices)) {
      eip::EipSession session(live_, identity(), 0);
      auto out = session.handle(std::span<const std::uint8_t>(udp_buffer_.data(), n));
      auto reply = std::make_shared<std::vector<std::uint8_t>>(std::move(out.reply));
      udp_.async_send_to(asio::buffer(*reply), udp_peer_, [reply](const boost::system::error_code&, std::size_t) {});
    }
    receive_udp();
  });
}

std::chrono::microseconds modbus_rtu_silence(int baud) {
  const std::chrono::microseconds t35{baud > 19200 ? 1750 : 38500000 / std::max(baud, 1)};
  return std::max(t35, std::chrono::microseconds{5000});
}

namespace {

[[noreturn]] void throw_errno(const std::string& what) {
  throw std::system_error(errno, std::generic_category(), what);
}

// Sets a tty to raw 8-bit characters at `baud` with `parity` ('N', 'E', 'O'); no parity takes two
// stop bits (Modbus over Serial Line v1.02 §2.5.1: every character is 11 bits).
void set_raw(int fd, int baud, char parity) {
  termios t{};
  if (::tcgetattr(fd, &t) != 0) throw_errno("tcgetattr");
  ::cfmakeraw(&t);
  speed_t speed = B19200;
  switch (baud) {
    case 300: speed = B300; break;
    case 600: speed = B600; break;
    case 1200: speed = B1200; break;
    case 2400: speed = B2400; break;
    case 4800: speed = B4800; break;
    case 9600: speed = B9600; break;
    case 38400: speed = B38400; break;
    default: break;
  }
  ::cfsetispeed(&t, speed);
  ::cfsetospeed(&t, speed);
  t.c_cflag |= CLOCAL | CREAD;
  t.c_cflag &= ~static_cast<tcflag_t>(PARENB | PARODD | CSTOPB);
  if (parity == 'E') t.c_cflag |= PARENB;
  if (parity == 'O') t.c_cflag |= PARENB | PARODD;
  if (parity == 'N') t.c_cflag |= CSTOPB;
  if (::tcsetattr(fd, TCSANOW, &t) != 0) throw_errno("tcsetattr");
}

}  // namespace

void Server::open_modbus_rtu() {
  const auto& o = *options_.modbus_rtu;
  if (o.device == "pty") {
    // A pseudo-terminal: the server reads and writes its master side; clients open the slave path.
    const int master = ::posix_openpt(O_RDWR | O_NOCTTY);
    if (master < 0) throw_errno("posix_openpt");
    char name[256] = {};
    if (::grantpt(master) != 0 || ::unlockpt(master) != 0 || ::ptsname_r(master, name, sizeof name) != 0) {
      const int e = errno;
      ::close(master);
      throw std::system_error(e, std::generic_category(), "pseudo-terminal");
    }
    rtu_pty_slave_ = ::open(name, O_RDWR | O_NOCTTY);
    if (rtu_pty_slave_ < 0) {
      const int e = errno;
      ::close(master);
      throw std::system_error(e, std::generic_category(), name);
    }
    // The slave side's line discipline would echo and translate bytes until a client sets it raw.
    try {
      set_raw(rtu_pty_slave_, o.baud, o.parity);
    } catch (...) {
      ::close(master);
      throw;
    }
    rtu_port_.assign(master);
    rtu_path_ = name;
  } else {
    rtu_port_.open(o.device);
    set_raw(rtu_port_.native_handle(), o.baud, o.parity);
    rtu_path_ = o.device;
  }
  rtu_ = std::make_shared<modbus::RtuSlave>(o.address, options_.modbus_map);
  read_modbus_rtu();
}

void Server::read_modbus_rtu() {
  rtu_port_.async_read_some(asio::buffer(rtu_buffer_), [this](const boost::system::error_code& ec, std::size_t n) {
    if (ec) {
      if (ec == asio::error::operation_aborted || stopped_) return;
      spdlog::warn("Modbus RTU on {}: read failed: {}; the serial line is closed", rtu_path_, ec.message());
      boost::system::error_code ignored;
      rtu_port_.close(ignored);
      return;
    }
    ++rtu_reads_;
    modbus_rtu_events(rtu_->receive(std::span<const std::uint8_t>(rtu_buffer_.data(), n), live_));
    if (rtu_->waiting_for_silence()) {
      rtu_silence_.expires_after(modbus_rtu_silence(options_.modbus_rtu->baud));
      // A wait that completed before bytes arrived is stale: the read count tells.
      rtu_silence_.async_wait([this, reads = rtu_reads_](const boost::system::error_code& wait_ec) {
        if (wait_ec || stopped_ || reads != rtu_reads_) return;
        modbus_rtu_events(rtu_->silence(live_));
      });
    }
    read_modbus_rtu();
  });
}

void Server::modbus_rtu_events(modbus::RtuEvents events) {
  for (const auto& line : events.log) spdlog::debug("{}", line);
  for (auto& reply : events.replies) {
    // A client that sends and never reads (a pseudo-terminal fills up) must not grow the queue.
    if (rtu_out_.size() >= 16) {
      spdlog::warn("Modbus RTU on {}: 16 replies unsent; a reply dropped", rtu_path_);
      continue;
    }
    rtu_out_.push_back(std::move(reply));
    if (rtu_out_.size() == 1) send_modbus_rtu();
  }
}

void Server::send_modbus_rtu() {
  asio::async_write(rtu_port_, asio::buffer(rtu_out_.front()), [this](const boost::system::error_code& ec, std::size_t) {
    if (ec) {
      rtu_out_.clear();
      if (ec != asio::error::operation_aborted && !stopped_)
        spdlog::warn("Modbus RTU on {}: write failed: {}", rtu_path_, ec.message());
      return;
    }
    rtu_out_.pop_front();
    if (!rtu_out_.empty()) send_modbus_rtu();
  });
}

void Server::tick() {
  if (stopped_) return;
  const auto now = std::chrono::steady_clock::now();
  if (last_tick_ != std::chrono::steady_clock::time_point{})
    max_tick_gap_ = std::max(max_tick_gap_, std::chrono::duration_cast<std::chrono::nanoseconds>(now - last_tick_));
  last_tick_ = now;
  const auto elapsed = now - pacing_start_;
  live_.advance(std::chrono::duration_cast<std::chrono::nanoseconds>(elapsed).count());
  timer_.expires_after(options_.tick);
  timer_.async_wait([this](const boost::system::error_code& ec) {
    if (!ec) tick();
  });
}

}  // namespace softslc::serve
