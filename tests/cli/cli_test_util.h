// Running the softslc binary from a test as a script would: exit code, stdout and stderr together.
// Shared by the command-line tests (cli_test.cpp) and the hardening tests (hardening_test.cpp).
#pragma once

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace {

struct Result {
  int exit_code = -1;
  std::string out;  // stdout and stderr, as a user sees them
};

Result run(const std::string& args) {
  std::string cmd = std::string(SOFTSLC_BINARY) + " " + args + " 2>&1";
  Result r;
  FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf;
  while (std::size_t n = std::fread(buf.data(), 1, buf.size(), p)) r.out.append(buf.data(), n);
  int status = ::pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

std::filesystem::path temp_file(const std::string& name, const std::string& contents) {
  auto dir = std::filesystem::temp_directory_path() / ("softslc-cli-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  auto path = dir / name;
  std::filesystem::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << contents;
  return path;
}

}  // namespace
