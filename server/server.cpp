#include "server/server.h"

#include <spdlog/spdlog.h>

#include <algorithm>

namespace softslc::serve {

// One TCP connection: read a 24-byte header, check its length against the bound, read the data,
// hand the frame to its EipSession, write the reply, repeat. An idle timer closes it when the
// client goes quiet.
struct Server::Connection : std::enable_shared_from_this<Server::Connection> {
  Connection(asio::ip::tcp::socket s, LiveController& live, eip::Identity identity, std::uint32_t session,
             const ServerOptions& o, std::shared_ptr<std::size_t> count)
      : socket(std::move(s)),
        idle(socket.get_executor()),
        eip(live, std::move(identity), session),
        options(o),
        connections(std::move(count)) {
    ++*connections;
    std::error_code ec;
    auto ep = socket.remote_endpoint(ec);
    peer = ec ? std::string("?") : ep.address().to_string() + ":" + std::to_string(ep.port());
  }
  ~Connection() { --*connections; }

  void start() {
    arm_idle();
    read_header();
  }

  void arm_idle() {
    idle.expires_after(options.idle_timeout);
    idle.async_wait([self = shared_from_this()](const std::error_code& ec) {
      if (ec) return;  // re-armed or closed
      spdlog::info("{}: closed after {} ms without a request", self->peer, self->options.idle_timeout.count());
      self->close();
    });
  }

  void close() {
    std::error_code ignored;
    socket.shutdown(asio::ip::tcp::socket::shutdown_both, ignored);
    socket.close(ignored);
    idle.cancel();
  }

  void read_header() {
    frame.resize(eip::kHeaderSize);
    asio::async_read(socket, asio::buffer(frame), [self = shared_from_this()](const std::error_code& ec, std::size_t) {
      if (ec) {
        if (ec != asio::error::eof && ec != asio::error::operation_aborted)
          spdlog::debug("{}: connection closed: {}", self->peer, ec.message());
        self->close();
        return;
      }
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
      self->frame.resize(eip::kHeaderSize + h->length);
      if (h->length == 0) {
        self->handle();
        return;
      }
      asio::async_read(socket_of(self), asio::buffer(self->frame.data() + eip::kHeaderSize, h->length),
                       [self](const std::error_code& ec2, std::size_t) {
                         if (ec2) {
                           spdlog::info("{}: connection closed in the middle of a frame: {}", self->peer, ec2.message());
                           self->close();
                           return;
                         }
                         self->handle();
                       });
    });
  }

  static asio::ip::tcp::socket& socket_of(const std::shared_ptr<Connection>& c) { return c->socket; }

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
    reply = std::move(out.reply);
    asio::async_write(socket, asio::buffer(reply),
                      [self = shared_from_this(), close_after = out.close](const std::error_code& ec, std::size_t) {
                        if (ec || close_after) {
                          self->close();
                          return;
                        }
                        self->read_header();
                      });
  }

  asio::ip::tcp::socket socket;
  asio::steady_timer idle;
  eip::EipSession eip;
  const ServerOptions options;  // a copy: a connection's handlers may outlive the Server
  std::shared_ptr<std::size_t> connections;
  std::vector<std::uint8_t> frame;
  std::vector<std::uint8_t> reply;
  std::string peer;
};

Server::Server(asio::io_context& io, LiveController& live, ServerOptions options)
    : live_(live), options_(std::move(options)), acceptor_(io), udp_(io), timer_(io) {}

Server::~Server() = default;

void Server::start() {
  const auto address = asio::ip::make_address(options_.listen);
  const asio::ip::tcp::endpoint tcp_ep(address, options_.port);
  acceptor_.open(tcp_ep.protocol());
  acceptor_.set_option(asio::ip::tcp::acceptor::reuse_address(true));
  acceptor_.bind(tcp_ep);
  acceptor_.listen();
  // ListIdentity is also answered on UDP, on the same port number as TCP.
  const asio::ip::udp::endpoint udp_ep(address, acceptor_.local_endpoint().port());
  udp_.open(udp_ep.protocol());
  udp_.set_option(asio::ip::udp::socket::reuse_address(true));
  udp_.bind(udp_ep);
  accept();
  receive_udp();
  restart_pacing();
  tick();
}

void Server::stop() {
  stopped_ = true;
  std::error_code ignored;
  acceptor_.close(ignored);
  udp_.close(ignored);
  timer_.cancel();
}

std::uint16_t Server::tcp_port() const { return acceptor_.local_endpoint().port(); }
std::size_t Server::connections() const { return *live_connections_; }

eip::Identity Server::identity() const {
  // The socket address item carries the address and port clients reach this server on.
  eip::Identity id = live_.identity();
  id.port = tcp_port();
  std::error_code ec;
  const auto address = asio::ip::make_address(options_.listen, ec);
  if (!ec && address.is_v4()) id.ipv4 = address.to_v4().to_uint();
  return id;
}

void Server::restart_pacing() { pacing_start_ = std::chrono::steady_clock::now(); }

void Server::accept() {
  acceptor_.async_accept([this](const std::error_code& ec, asio::ip::tcp::socket socket) {
    if (ec) {
      if (ec == asio::error::operation_aborted || stopped_) return;
      spdlog::warn("accept failed: {}", ec.message());
    } else if (*live_connections_ >= options_.max_connections) {
      spdlog::warn("refused a connection: {} connections is the limit", options_.max_connections);
      std::error_code ignored;
      socket.close(ignored);
    } else {
      std::error_code ignored;
      socket.set_option(asio::ip::tcp::no_delay(true), ignored);
      auto c = std::make_shared<Connection>(std::move(socket), live_, identity(), next_session_++, options_,
                                            live_connections_);
      spdlog::debug("{}: connected", c->peer);
      c->start();
    }
    accept();
  });
}

void Server::receive_udp() {
  udp_.async_receive_from(asio::buffer(udp_buffer_), udp_peer_, [this](const std::error_code& ec, std::size_t n) {
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
      udp_.async_send_to(asio::buffer(*reply), udp_peer_, [reply](const std::error_code&, std::size_t) {});
    }
    receive_udp();
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
  timer_.async_wait([this](const std::error_code& ec) {
    if (!ec) tick();
  });
}

}  // namespace softslc::serve
