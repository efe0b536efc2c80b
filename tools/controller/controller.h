// softslc::Controller — the C++ API for testing ladder programs from GoogleTest (or any C++).
//
// One Controller is one simulated SLC 500 with its chassis and bench: load a program (and its
// bench file of simulated field devices), then drive it the way `softslc test` files do —
// set/get/force by address or SYMBOL, scan, run for a virtual duration or until a condition,
// change modes, inject device faults, observe devices, take snapshots and restore them.
//
//   softslc::Controller plc = softslc::Controller::load("seal_in.slc");
//   plc.scan();                                   // the first pass
//   plc.set("START_PB", 1);
//   plc.scan();
//   EXPECT_EQ(plc.get_bit("MOTOR"), true);
//   EXPECT_TRUE(plc.run_until([](const auto& p) { return p.get_bit("OL_TRIPPED"); }, softslc::seconds(2)));
//
// Errors are exceptions (softslc::ControllerError) carrying the whole message — gcc-style
// diagnostics for a program or bench that does not load, the runtime's reason for a refused
// request — so a test fails at the call that went wrong with a readable reason. A major fault of
// the ladder is not an error: it is state, read with fault().
//
// Snapshots are exact and cheap to take: the simulation is deterministic, so a snapshot is the
// journal of state-changing calls made since load (a run_until recorded as a run for the
// virtual time it took), and restore() replays it into a fresh processor of the same program
// and bench. A snapshot can be restored any number of times.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "parser/program.h"
#include "vm/faults.h"
#include "vm/runtime.h"

namespace softslc {

class ControllerError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// One state-changing call, as a snapshot journal records it.
struct ControllerCall {
  enum class Kind : std::uint8_t { Set, SetFloat, Force, Unforce, Scans, RunFor, SetMode, ClearFault, Inject, SetWord, RetrieveDataLog };
  Kind kind = Kind::Scans;
  std::string target;  // address (symbols resolved) or device
  std::int64_t integer = 0;  // Set, SetWord: value; Force: 0/1; Scans: how many; RunFor: nanoseconds; RetrieveDataLog: queue
  int word = 0;              // SetWord: the word within the element
  double real = 0.0;         // SetFloat
  Mode mode = Mode::Run;     // SetMode
  std::string change;        // Inject
  std::vector<std::string> args;
};

class Controller {
 public:
  // A snapshot: the calls that lead from the download state to the state it names.
  class Snapshot {
   public:
    std::size_t calls() const { return journal_.size(); }

   private:
    friend class Controller;
    std::vector<ControllerCall> journal_;
  };

  // Loads a program file and, optionally, its bench file. The processor starts in Run (as a
  // `softslc test` test does): call set_mode(Mode::Program) first to start elsewhere.
  static Controller load(const std::filesystem::path& program,
                         const std::optional<std::filesystem::path>& bench = std::nullopt);
  // The same from text (`name` and `bench_name` are used in diagnostics).
  static Controller from_text(std::string program_text, std::string bench_text = {},
                              std::string name = "program.slc", std::string bench_name = "program.bench");

  Controller(Controller&&) noexcept;
  Controller& operator=(Controller&&) noexcept;
  ~Controller();

  // ---- Data: addresses as in programs (N7:0, I:1/0, T4:0.ACC, #N7:2) or SYMBOL names ----
  // An I: address sets the field input (seen at the next input scan); anything else writes now.
  void set(std::string_view target, std::int64_t value);
  void set_float(std::string_view target, double value);
  Value get(std::string_view target) const;
  bool get_bit(std::string_view target) const { return get(target).as_bool(); }
  std::int64_t get_int(std::string_view target) const { return get(target).as_int(); }
  double get_float(std::string_view target) const { return get(target).as_double(); }

  // ---- Forces (I: and O: bits), as on the SLC ----
  void force(std::string_view target, bool on);
  void unforce(std::string_view target);

  // ---- Data files word by word (network servers: PCCC, Modbus) ----
  // A data file as a protocol addresses it: element e, word w of the element is word
  // e * words_per_element + w of the file. The I and O files have one word per element, in
  // image order (slot 1's words first), as PCCC's logical-by-slot I/O types number them.
  struct FileInfo {
    FileType type = FileType::Integer;
    int number = 0;
    std::uint32_t elements = 0;
    int words_per_element = 1;
    std::uint32_t words() const { return elements * static_cast<std::uint32_t>(words_per_element); }
  };
  std::optional<FileInfo> file_info(int number) const;
  // Copies out.size() words starting at word `offset` of data file `number`; false (nothing
  // copied) when the file does not exist or the range does not fit in it.
  bool read_file_words(int number, std::uint32_t offset, std::span<std::uint16_t> out) const;
  // Writes words of a data file: bits set in masks[i] take the bits of values[i]. Every word goes
  // through the same path as set()/set_float() (an I word sets the field input, a float is
  // written whole), so forces and module rules hold; string words, which no address names
  // singly, go through set_word(). Returns the calls performed, in order (also recorded in the
  // snapshot journal when it is kept), and why the write stopped early, if it did (a range
  // outside the file performs nothing; a refused word stops the write there).
  struct WriteResult {
    std::vector<ControllerCall> calls;
    std::string error;
  };
  WriteResult write_file_words(int number, std::uint32_t offset, std::span<const std::uint16_t> values,
                               std::span<const std::uint16_t> masks);
  // Writes word `word` of an element that has several (ST9:0 word 5) as a raw 16-bit pattern.
  void set_word(std::string_view element, int word, std::uint16_t value);
  // Performs one recorded call (a journal's replay).
  void perform(const ControllerCall& call);
  // A CRC-32 of every word of the data table, for comparing histories.
  std::uint32_t data_digest() const;

  // ---- Running (virtual time) ----
  // Runs n scan cycles; returns how many ran (fewer when the processor faulted).
  int scan(int n = 1);
  // Runs whole scans until at least `duration` of virtual time has passed; returns scans run.
  // Scans that would repeat the one before may be taken without executing them, with the same
  // results (docs/semantics.md "Repeated scans"; runtime().skip_repeated_scans(false) turns it off).
  std::int64_t run_for(Nanoseconds duration);
  // Runs whole scans until `condition` holds (checked before the first scan and after each) or
  // `limit` has passed; returns whether it held.
  bool run_until(const std::function<bool(const Controller&)>& condition, Nanoseconds limit);
  VirtualTime now() const;
  std::uint64_t scans() const;

  // ---- Modes and faults ----
  void set_mode(Mode m);
  Mode mode() const;
  const std::optional<FaultInfo>& fault() const;
  void clear_fault();

  // ---- MicroLogix data logging (docs/semantics.md "Data logging: DLG and the DLS file") ----
  // Reads and removes the oldest record of data log queue `queue`, as a communications read does
  // (1763-RM001C p. 442): its text, e.g. "01/10/2000,20:00:00,2315,103457,200,8190,4465"; nullopt
  // when the queue is empty. Throws ControllerError for a queue the program does not configure.
  std::optional<std::string> retrieve_data_log_record(int queue);
  // The records of a queue as text, oldest first, left in place.
  std::vector<std::string> data_log_records(int queue) const;

  // ---- Bench devices (docs/bench-format.md) ----
  void inject(std::string_view device, std::string_view change, std::vector<std::string> args = {});
  std::vector<std::int64_t> observe(std::string_view device, std::string_view what) const;
  std::vector<std::string> devices() const;

  // ---- Snapshots ----
  // Whether state-changing calls are recorded for snapshot() (on by default). A long-running
  // server turns it off: it keeps its own journal, and a snapshot journal would grow forever.
  void keep_journal(bool on) { keep_journal_ = on; }
  Snapshot snapshot() const;
  void restore(const Snapshot& s);

  // ---- The underlying processor, for anything the API does not cover ----
  // (Changes made through it directly are not recorded in snapshots.)
  Runtime& runtime();
  const Runtime& runtime() const;
  const Program& program() const;

 private:
  struct Loaded;
  explicit Controller(std::shared_ptr<const Loaded> loaded);
  void fresh_runtime();
  std::string address_of(std::string_view target) const;
  // Performs a call on the current processor; records it in the journal when `record`.
  void apply(const ControllerCall& c, bool record);
  void write_file_words_or_throw(int number, std::uint32_t offset, std::span<const std::uint16_t> values,
                                 std::span<const std::uint16_t> masks, std::vector<ControllerCall>& calls);

  std::shared_ptr<const Loaded> loaded_;
  std::unique_ptr<Runtime> runtime_;
  std::vector<ControllerCall> journal_;
  bool keep_journal_ = true;
};

}  // namespace softslc
