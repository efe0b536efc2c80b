// LiveController: a softslc::Controller paced to the wall clock, with a journal of every client
// write, for `softslc serve` and `softslc replay`.
//
// Virtual time stays an integer and the simulation reads no clock: the caller (the server's timer)
// passes in how much wall time has passed since pacing started, and advance() runs whole scans
// until virtual time reaches that much times the speed (--speed), at most kMaxScansPerAdvance
// scans per call so a slow machine falls behind instead of starving the network. Paused, only
// step() runs scans. Writes from clients happen between scans, at the virtual time now().
//
// The journal is a text file, one record a line, written as it happens:
//   softslc-journal 1
//   program PATH FINGERPRINT        the program file and the FNV-1a of its canonical text
//   bench PATH | bench -
//   scans N                         N scans ran (consecutive pacing scans are merged)
//   set @VT ADDR VALUE              a client write, as the controller performed it, at virtual
//   setf @VT ADDR HEXBITS           time VT (ns); setf carries the float's IEEE bits, setword a
//   setword @VT ADDR WORD VALUE     raw word of a string element
//   force @VT ADDR 0|1              a force from the online view (server/web.h), unforce @VT ADDR
//   mode @VT program|run|test       a mode change from the online view; clearfault @VT a fault clear
//   digest @VT CRC                  the data table's CRC-32 after the write(s) of one request
//   end @VT CRC                     the state when the server stopped
// Replaying the records in order into a fresh controller of the same program and bench reproduces
// every data-table state the clients saw: replay() checks each write's virtual time and each
// digest, so "byte for byte" is verified, not assumed.
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "server/eip.h"
#include "server/pccc.h"
#include "tools/controller/controller.h"

namespace softslc::serve {

inline constexpr int kMaxScansPerAdvance = 10000;

struct LiveOptions {
  double speed = 1.0;  // virtual seconds per wall second
  bool paused = false;
  bool read_only = false;
  std::optional<std::filesystem::path> journal;
};

class LiveController final : public pccc::Target {
 public:
  LiveController(const std::filesystem::path& program, const std::optional<std::filesystem::path>& bench,
                 LiveOptions options);
  ~LiveController() override;

  // Pacing. `wall_elapsed` is the wall time since pacing (re)started; returns the scans run.
  int advance(Nanoseconds wall_elapsed);
  int step(int n = 1);
  void pause();
  // Resumes pacing: the caller restarts its wall clock at 0.
  void resume();
  bool paused() const { return options_.paused; }
  // How far virtual time trails the wall clock target after the last advance() (0 when on time).
  Nanoseconds lag() const { return lag_; }
  // The largest lag seen since start (the pacing bound a run held).
  Nanoseconds max_lag() const { return max_lag_; }

  Controller& controller() { return controller_; }
  const Controller& controller() const { return controller_; }
  std::uint64_t writes() const { return writes_; }
  // Writes the journal's end record and flushes it.
  void finish();

  // ---- Changes from the online view (server/web.h) ----
  // Each is performed between scans through the Controller API (addresses or SYMBOL names, the
  // rules of `run --set`) and journaled like a client write, so `softslc replay` reproduces a
  // session driven from the browser. Each returns why it was refused ("" when done); with
  // --read-only every one is refused.
  // A value: an integer, or a real number ("1.5", "2e3") written as a float.
  std::string set_value(std::string_view target, std::string_view text);
  // Forces an I or O bit on or off; nullopt removes the force.
  std::string force(std::string_view target, std::optional<bool> on);
  std::string set_mode(Mode mode);
  std::string clear_fault();
  // The forces installed through force(), by canonical address (the program's own FORCE lines
  // are not listed: the Controller API has no query for them).
  const std::map<std::string, bool>& forces() const { return forces_; }
  bool read_only() const { return options_.read_only; }

  // The identity ListIdentity reports, from the program's processor.
  eip::Identity identity() const;

  // pccc::Target.
  std::optional<File> file(int number) const override;
  void read(int number, std::uint32_t offset, std::span<std::uint16_t> out) const override;
  std::string write(int number, std::uint32_t offset, std::span<const std::uint16_t> values,
                    std::span<const std::uint16_t> masks) override;
  std::vector<std::uint8_t> diagnostic_status() const override;
  // M0/M1 through the module, as `run --set M0:1.100=5` and `get` reach them.
  std::optional<std::uint32_t> module_file_words(int slot, bool m1) const override;
  std::string read_module(int slot, bool m1, std::uint32_t word, std::span<std::uint16_t> out) override;
  std::string write_module(int slot, bool m1, std::uint32_t word, std::span<const std::uint16_t> values,
                           std::span<const std::uint16_t> masks) override;

 private:
  void flush_scans();
  // Journals the calls one request performed, with the digest after them.
  void journal_calls(const std::vector<ControllerCall>& calls);
  void run_scans(int n);
  // A SYMBOL's canonical address; anything else as given (the controller checks it).
  std::string resolved(std::string_view target) const;

  Controller controller_;
  LiveOptions options_;
  VirtualTime base_ = 0;  // virtual time when pacing (re)started
  Nanoseconds lag_ = 0;
  Nanoseconds max_lag_ = 0;
  std::uint64_t pending_scans_ = 0;
  std::uint64_t writes_ = 0;
  std::unique_ptr<std::ofstream> journal_;
  std::map<std::string, bool> forces_;
};

// The result of replaying a journal.
struct ReplayResult {
  bool ok = false;
  std::string message;  // what diverged, or a summary
  std::uint64_t writes = 0;
  std::uint64_t digests = 0;
  std::optional<Controller> controller;  // the final state
};
// Replays a journal (the program and bench paths it names, relative to the current directory).
ReplayResult replay(const std::filesystem::path& journal);

}  // namespace softslc::serve
