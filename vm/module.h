// The module interface: what the VM knows about anything in a chassis slot.
//
// As in simavr, a module is a plug-in behind a small table of callbacks and the VM never names a
// module type. A module owns one slot and says how many input and output image words it has (the
// SLOT line's SCAN_IN / SCAN_OUT). The runtime calls it at fixed points of the scan:
//
//   input scan   input_scan(image)     the module writes its input words into the I file slice
//   output scan  output_scan(image)    the module receives its output words (all zero unless Run)
//   M0/M1        read_m() / write_m()  immediate word access from the ladder program; the module
//                                      answers with an MAccess status so a forbidden access can
//                                      fault the processor instead of being ignored
//   mode change  on_mode_change()      Program/Run/Test/Faulted transitions
//
// Timed behaviour (a field device that answers later, a scanner that completes a block
// transfer) is scheduled on the runtime's event queue through ModuleHost::schedule_at; events
// run between scans in (time, sequence) order. A module must not keep references into the data
// table: image spans are valid only during the call.
//
// Field-side access (set_field_input, field_output) is for tools and tests: it is how
// `Runtime::set("I:1/0", 1)` reaches the simulated field device.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "vm/event_queue.h"
#include "vm/virtual_time.h"

namespace softslc {

// Processor modes (S:1/0-4 codes in brackets, DF1 p.10-3): Program (1), Run (6), Test single
// scan (8), and Faulted (a major error halted the processor, S:1/13).
enum class Mode : std::uint8_t { Program, Run, Test, Faulted };
std::string_view to_string(Mode m);

enum class MFile : std::uint8_t { M0 = 0, M1 = 1 };

// The result of an immediate M0/M1 access.
enum class MAccess : std::uint8_t {
  Ok,
  NoSuchWord,  // the module has no such word (outside its M0/M1 size, or no M files at all)
  Forbidden,   // the word exists but may not be accessed this way (read-only, reserved)
};
std::string_view to_string(MAccess a);

// What the runtime offers a module.
class ModuleHost {
 public:
  virtual ~ModuleHost() = default;
  // The virtual time. During a scan's callbacks (input_scan, output_scan, M0/M1 accesses) the
  // clock still reads the scan's start; it advances when the scan ends, and event callbacks see
  // their own time.
  virtual VirtualTime now() const = 0;
  virtual Mode mode() const = 0;
  // Schedules work on the runtime's event queue (time >= now()).
  virtual EventQueue::EventId schedule_at(VirtualTime at, EventQueue::Callback cb) = 0;
  virtual bool cancel_event(EventQueue::EventId id) = 0;
};

class Module {
 public:
  Module(int slot, std::string catalog, int input_words, int output_words)
      : slot_(slot), catalog_(std::move(catalog)), input_words_(input_words), output_words_(output_words) {}
  virtual ~Module() = default;
  Module(const Module&) = delete;
  Module& operator=(const Module&) = delete;

  int slot() const { return slot_; }
  const std::string& catalog() const { return catalog_; }
  int input_words() const { return input_words_; }
  int output_words() const { return output_words_; }

  // Called once when the runtime takes the module; the host outlives the module's use of it.
  virtual void attach(ModuleHost& host) { host_ = &host; }

  // Input scan: write the module's current input data into `image` (input_words() words).
  virtual void input_scan(std::span<std::uint16_t> image) = 0;
  // Output scan: receive the output image (output_words() words). Outside Run mode the runtime
  // passes zeros, which is what a de-energised output card sees.
  virtual void output_scan(std::span<const std::uint16_t> image) = 0;

  // M0/M1 files: sizes in words (0 = the module has none) and immediate word access.
  virtual int m_file_words(MFile) const { return 0; }
  virtual MAccess read_m(MFile, int /*word*/, std::uint16_t& /*value*/) { return MAccess::NoSuchWord; }
  virtual MAccess write_m(MFile, int /*word*/, std::uint16_t /*value*/) { return MAccess::NoSuchWord; }

  virtual void on_mode_change(Mode /*from*/, Mode /*to*/) {}

  // Field side, for tools and tests. set_field_input changes the bits of input word `word`
  // selected by `mask`; it returns false when the module has no such simulated input.
  virtual bool set_field_input(int /*word*/, std::uint16_t /*value*/, std::uint16_t /*mask*/) { return false; }
  virtual std::optional<std::uint16_t> field_input(int /*word*/) const { return std::nullopt; }
  // The output word the field sees (what the last output scan delivered).
  virtual std::optional<std::uint16_t> field_output(int /*word*/) const { return std::nullopt; }

 protected:
  ModuleHost* host() const { return host_; }

 private:
  int slot_;
  std::string catalog_;
  int input_words_;
  int output_words_;
  ModuleHost* host_ = nullptr;
};

}  // namespace softslc
