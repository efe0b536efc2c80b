// Running the softslc binary from a test as a script would: exit code, stdout and stderr together.
// Shared by the command-line tests (cli_test.cpp), the hardening tests (hardening_test.cpp) and the
// state-file tests (tests/state/state_file_test.cpp).
#pragma once

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
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

// This process's scratch directory, created on first use and removed when the process exits:
// ctest runs every test in a process of its own, so a directory left behind would be one more in
// /tmp per test and per run.
const std::filesystem::path& scratch_dir() {
  struct ScratchDir {
    std::filesystem::path path = std::filesystem::temp_directory_path() / ("softslc-cli-" + std::to_string(::getpid()));
    ~ScratchDir() {
      std::error_code ignored;
      std::filesystem::remove_all(path, ignored);
    }
  };
  static const ScratchDir dir;
  std::filesystem::create_directories(dir.path);
  return dir.path;
}

std::filesystem::path temp_file(const std::string& name, const std::string& contents) {
  auto path = scratch_dir() / name;
  std::filesystem::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << contents;
  return path;
}

}  // namespace
