// `softslc serve` and `softslc replay`: the live controller on the network, and the replay of its
// journal (server/live.h, server/server.h, docs/serve.md). Each command registers its own options
// so main.cpp only adds two lines per command.
#pragma once

#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <vector>

namespace softslc::cli {

struct ServeOptions {
  std::string program;
  std::string bench;
  double speed = 1.0;
  bool paused = false;
  std::string listen = "127.0.0.1";
  int port = 44818;
  bool read_only = false;
  std::string journal;
  int max_connections = 64;
  int idle_seconds = 60;
  bool verbose = false;
  int modbus_port = -1;        // -1: no Modbus TCP
  std::string modbus_map = "B3,B3,N7,N7";  // coil, contact, input register, holding register files
  std::string modbus_rtu;      // a serial device or "pty"; empty: no Modbus RTU
  int modbus_address = 1;      // the RTU slave address
  int modbus_baud = 19200;
  std::string modbus_parity = "none";
  std::string http = "8044";   // the online view's port; "off": none (server/web.h)
  bool http_given = false;     // --http named: a port that cannot be bound is an error, not a warning
};
CLI::App* add_serve_command(CLI::App& app, ServeOptions& o);
int run_serve(const ServeOptions& o);

struct ReplayOptions {
  std::string journal;
  std::vector<std::string> prints;
};
CLI::App* add_replay_command(CLI::App& app, ReplayOptions& o);
int run_replay(const ReplayOptions& o);

}  // namespace softslc::cli
