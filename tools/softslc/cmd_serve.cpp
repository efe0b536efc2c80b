// `softslc serve PROGRAM`: runs the program paced to the wall clock, answers EtherNet/IP (PCCC)
// clients (and Modbus TCP and RTU masters, as a MicroLogix 1100/1400) and serves the online view (a
// web page, server/web.h); `softslc replay JOURNAL`: replays a serve session's journal and checks
// that the data table went through the same states.
//
// The server, its pacing timer, the online view, the signal handler and the console reader all
// run on one io_context in this thread (server/server.h says why). The console takes one command a line:
// `step [N]` runs N scans (paused or not), `pause`, `resume`, `quit`; with --paused it is how a
// session is single-stepped.
#include "tools/softslc/cmd_serve.h"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cctype>
#include <functional>
#include <iostream>
#include <sstream>

#include "server/server.h"
#include "server/web.h"
#include "tools/softslc/commands.h"

namespace softslc::cli {

CLI::App* add_serve_command(CLI::App& app, ServeOptions& o) {
  auto* cmd = app.add_subcommand("serve", "Run a program paced to the wall clock and serve its data table to "
                                          "EtherNet/IP (PCCC) clients, and with --modbus/--modbus-rtu Modbus TCP/RTU "
                                          "masters: HMIs, SCADA, test scripts");
  cmd->add_option("PROGRAM", o.program, "program file")->required();
  cmd->add_option("--bench", o.bench, "bench file of simulated field devices (docs/bench-format.md)");
  cmd->add_option("--speed", o.speed, "virtual seconds per wall second (default 1)")->check(CLI::Range(0.001, 1000.0));
  cmd->add_flag("--paused", o.paused, "start paused; type `step [N]` or `resume` on standard input");
  cmd->add_option("--listen", o.listen, "address to listen on (default 127.0.0.1: this machine only)");
  cmd->add_option("--port", o.port, "TCP and UDP port (default 44818; 0 picks a free one)")->check(CLI::Range(0, 65535));
  cmd->add_flag("--read-only", o.read_only, "refuse every write (PCCC EXT STS 10h, no access)");
  cmd->add_option("--journal", o.journal, "write every client write, with its virtual time, to FILE (softslc replay)")
      ->type_name("FILE");
  cmd->add_option("--max-connections", o.max_connections, "connections at once (default 64)")->check(CLI::Range(1, 4096));
  cmd->add_option("--idle", o.idle_seconds, "close a connection silent this many seconds (default 60)")
      ->check(CLI::Range(1, 86400));
  cmd->add_flag("-v,--verbose", o.verbose, "log every refused request, not only closed connections");
  cmd->add_option("--modbus", o.modbus_port,
                  "also serve Modbus TCP on PORT, as a MicroLogix 1100/1400 whose channel is configured as a Modbus "
                  "slave (0 picks a free port; the standard port is 502)")
      ->type_name("PORT")
      ->check(CLI::Range(0, 65535));
  cmd->add_option("--modbus-map", o.modbus_map,
                  "the channel's Modbus data files: coils,contacts,input registers,holding registers, each a B or N "
                  "file (default B3,B3,N7,N7)")
      ->type_name("C,D,I,H");
  cmd->add_option("--modbus-rtu", o.modbus_rtu,
                  "also answer Modbus RTU on a serial line, as a MicroLogix 1100/1400 whose channel 0 is configured "
                  "as a Modbus RTU slave (with the --modbus-map files); DEVICE is a serial device (/dev/ttyUSB0) or "
                  "pty: a new pseudo-terminal, whose path is printed")
      ->type_name("DEVICE|pty");
  cmd->add_option("--modbus-address", o.modbus_address, "the Modbus RTU slave address (default 1)")
      ->check(CLI::Range(modbus::kMinSlaveAddress, modbus::kMaxSlaveAddress));
  cmd->add_option("--modbus-baud", o.modbus_baud, "the serial line's baud rate: 300-38400 (default 19200)")
      ->check(CLI::IsMember(std::vector<int>(std::begin(serve::kModbusRtuBauds), std::end(serve::kModbusRtuBauds))));
  cmd->add_option("--modbus-parity", o.modbus_parity, "the serial line's parity (default none: 8 data bits, 2 stop bits)")
      ->check(CLI::IsMember({"none", "even", "odd"}));
  auto* http = cmd->add_option("--http", o.http,
                               "serve the online view (a web page: live ladder, data tables, forces) on PORT, on the "
                               "--listen address (default 8044; 0 picks a free port; off: none)")
                   ->type_name("PORT|off");
  cmd->callback([&o, http] { o.http_given = http->count() > 0; });
  return cmd;
}

namespace {

// "off", or a port 0-65535.
std::optional<int> parse_http(const std::string& text) {
  if (text == "off") return -1;
  if (text.empty() || text.size() > 5) return std::nullopt;
  int n = 0;
  for (char ch : text) {
    if (!std::isdigit(static_cast<unsigned char>(ch))) return std::nullopt;
    n = n * 10 + (ch - '0');
  }
  if (n > 65535) return std::nullopt;
  return n;
}

// "B3,B3,N7,N7" (or "3,3,7,7"): the four file numbers of a Modbus map (vm/modbus_slave.h).
std::optional<modbus::Map> parse_modbus_map(const std::string& text) { return modbus::parse_map(text); }

// Reads console commands from standard input on the io_context.
class Console : public std::enable_shared_from_this<Console> {
 public:
  Console(asio::io_context& io, serve::LiveController& live, serve::Server& server, std::function<void()> on_quit)
      : io_(io), in_(io, ::dup(STDIN_FILENO)), live_(live), server_(server), on_quit_(std::move(on_quit)) {}
  void start() { read(); }

 private:
  void read() {
    asio::async_read_until(in_, buffer_, '\n', [self = shared_from_this()](const boost::system::error_code& ec, std::size_t) {
      if (ec) return;  // end of input: the server goes on until a signal
      std::istream is(&self->buffer_);
      std::string line;
      std::getline(is, line);
      self->command(line);
      self->read();
    });
  }
  void command(const std::string& line) {
    std::istringstream ls(line);
    std::string word;
    ls >> word;
    if (word == "step") {
      int n = 1;
      ls >> n;
      if (n < 1 || n > 1000000) n = 1;
      live_.step(n);
      std::cout << "stepped " << n << " scan(s); virtual time " << live_.controller().now() << " ns" << std::endl;
    } else if (word == "pause") {
      live_.pause();
      std::cout << "paused at virtual time " << live_.controller().now() << " ns" << std::endl;
    } else if (word == "resume") {
      live_.resume();
      server_.restart_pacing();
      std::cout << "running" << std::endl;
    } else if (word == "quit") {
      if (on_quit_) on_quit_();
      server_.stop();
      io_.stop();
    } else if (!word.empty()) {
      std::cout << "commands: step [N], pause, resume, quit" << std::endl;
    }
  }

  asio::io_context& io_;
  asio::posix::stream_descriptor in_;
  asio::streambuf buffer_{4096};
  serve::LiveController& live_;
  serve::Server& server_;
  std::function<void()> on_quit_;
};

}  // namespace

int run_serve(const ServeOptions& o) {
  spdlog::set_default_logger(spdlog::stderr_color_st("serve"));
  spdlog::set_level(o.verbose ? spdlog::level::debug : spdlog::level::info);
  serve::LiveOptions lo;
  lo.speed = o.speed;
  lo.paused = o.paused;
  lo.read_only = o.read_only;
  if (!o.journal.empty()) lo.journal = o.journal;
  std::optional<serve::LiveController> live;
  try {
    live.emplace(o.program, o.bench.empty() ? std::nullopt : std::optional<std::filesystem::path>(o.bench), lo);
  } catch (const ControllerError& e) {
    std::cerr << e.what() << "\n";
    return kInputError;
  }
  asio::io_context io;
  serve::ServerOptions so;
  if (o.modbus_port >= 0 || !o.modbus_rtu.empty()) {
    const char* option = o.modbus_port >= 0 ? "--modbus" : "--modbus-rtu";
    const ProcessorModel& p = live->controller().program().processor;
    if (p.micrologix != MicroLogixModel::ML1100 && p.micrologix != MicroLogixModel::ML1400) {
      std::cerr << "softslc serve: " << option << ": Modbus " << (o.modbus_port >= 0 ? "TCP" : "RTU")
                << " is a MicroLogix 1100/1400 channel protocol; this program's processor is " << p.display_name
                << " (" << p.catalog << ")\n";
      return kInputError;
    }
    auto map = parse_modbus_map(o.modbus_map);
    std::string why = map ? modbus::check_map(*map, *live) : "expected four data files: C,D,I,H (e.g. B3,B3,N7,N7)";
    if (!why.empty()) {
      std::cerr << "softslc serve: --modbus-map " << o.modbus_map << ": " << why << "\n";
      return kInputError;
    }
    if (o.modbus_port >= 0) so.modbus_port = static_cast<std::uint16_t>(o.modbus_port);
    so.modbus_map = *map;
  }
  if (!o.modbus_rtu.empty()) {
    serve::ServerOptions::ModbusRtu rtu;
    rtu.device = o.modbus_rtu;
    rtu.address = static_cast<std::uint8_t>(o.modbus_address);
    rtu.baud = o.modbus_baud;
    rtu.parity = o.modbus_parity == "even" ? 'E' : o.modbus_parity == "odd" ? 'O' : 'N';
    so.modbus_rtu = rtu;
  }
  const auto http_port = parse_http(o.http);
  if (!http_port) {
    std::cerr << "softslc serve: --http " << o.http << ": expected a port (0-65535) or off\n";
    return kUsage;
  }
  so.listen = o.listen;
  so.port = static_cast<std::uint16_t>(o.port);
  so.max_connections = static_cast<std::size_t>(o.max_connections);
  so.idle_timeout = std::chrono::seconds(o.idle_seconds);
  serve::Server server(io, *live, so);
  try {
    server.start();
  } catch (const serve::SerialLineError& e) {
    std::cerr << "softslc serve: " << e.what() << "\n";
    return kInputError;
  } catch (const std::exception& e) {
    std::cerr << "softslc serve: cannot listen on " << o.listen << ":" << o.port << ": " << e.what() << "\n";
    return kInputError;
  }
  std::cout << "softslc serve: " << live->controller().program().processor.catalog << " listening on " << o.listen
            << ":" << server.tcp_port() << " (EtherNet/IP, TCP and UDP)"
            << (o.read_only ? ", read-only" : "") << (o.paused ? ", paused" : "") << ", speed " << o.speed << std::endl;
  if (so.modbus_port)
    std::cout << "softslc serve: Modbus TCP on " << o.listen << ":" << server.modbus_port() << " (data files: coils "
              << so.modbus_map.coils << ", contacts " << so.modbus_map.contacts << ", input registers "
              << so.modbus_map.input_registers << ", holding registers " << so.modbus_map.holding_registers << ")"
              << std::endl;
  if (so.modbus_rtu)
    std::cout << "softslc serve: Modbus RTU slave " << o.modbus_address << " on " << server.modbus_rtu_path() << " ("
              << o.modbus_baud << " baud, parity " << o.modbus_parity << "; data files: coils " << so.modbus_map.coils
              << ", contacts " << so.modbus_map.contacts << ", input registers " << so.modbus_map.input_registers
              << ", holding registers " << so.modbus_map.holding_registers << ")" << std::endl;
  std::optional<serve::WebView> web;
  if (*http_port >= 0) {
    serve::WebOptions wo;
    wo.listen = o.listen;
    wo.port = static_cast<std::uint16_t>(*http_port);
    web.emplace(io, *live, server, wo);
    try {
      web->start();
      std::cout << "softslc serve: online view on http://" << (o.listen.find(':') != std::string::npos ? "[" + o.listen + "]" : o.listen)
                << ":" << web->port() << "/" << std::endl;
    } catch (const std::exception& e) {
      // The default port taken (another serve running) does not stop the EtherNet/IP server; a
      // port asked for does.
      std::cerr << "softslc serve: " << (o.http_given ? "" : "warning: ") << "cannot serve the online view on "
                << o.listen << ":" << *http_port << ": " << e.what() << (o.http_given ? "" : " (--http PORT picks another)")
                << "\n";
      if (o.http_given) {
        server.stop();
        return kInputError;
      }
      web.reset();
    }
  }
  if (o.listen != "127.0.0.1" && o.listen != "::1")
    std::cout << "softslc serve: warning: listening on " << o.listen
              << ", reachable from other machines; PCCC has no authentication" << std::endl;

  asio::signal_set signals(io, SIGINT, SIGTERM);
  signals.async_wait([&](const boost::system::error_code& ec, int) {
    if (ec) return;
    if (web) web->stop();
    server.stop();
    io.stop();
  });
  auto console = std::make_shared<Console>(io, *live, server, [&web] {
    if (web) web->stop();
  });
  console->start();
  io.run();
  live->finish();
  std::cout << "softslc serve: stopped at virtual time " << live->controller().now() << " ns after "
            << live->controller().scans() << " scans; " << live->writes() << " write(s); largest lag behind the wall clock "
            << live->max_lag() / 1000 << " us after a tick, longest tick gap "
            << server.max_tick_gap().count() / 1000 << " us" << std::endl;
  return kOk;
}

CLI::App* add_replay_command(CLI::App& app, ReplayOptions& o) {
  auto* cmd = app.add_subcommand("replay", "Replay a `softslc serve --journal` file and check that the data table "
                                           "goes through the same states; exit 0 identical, 1 diverged");
  cmd->add_option("JOURNAL", o.journal, "journal file")->required();
  cmd->add_option("--print", o.prints, "address or symbol to print after the replay, in order");
  return cmd;
}

int run_replay(const ReplayOptions& o) {
  auto r = serve::replay(o.journal);
  if (!r.ok) {
    std::cerr << r.message << "\n";
    return kInputError;
  }
  std::cout << r.message << "\n";
  for (const auto& p : o.prints) {
    try {
      std::cout << p << " = " << r.controller->get(p).to_string() << "\n";
    } catch (const ControllerError& e) {
      std::cerr << e.what() << "\n";
      return kInputError;
    }
  }
  return kOk;
}

}  // namespace softslc::cli
