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
//
// Specialty instructions (BTR, BTW, DEM) are executed by the module in the slot they name:
// the interpreter resolves the instruction's operands to data-table locations, M-file words and
// literals (ModuleOperand) and calls Module::execute with a ModuleInstructionContext through
// which the module reads and writes the data table (bounds-checked), makes immediate M0/M1
// accesses and charges them to the scan time (ScanTimeModel::mfile_access_cost), or raises a
// major fault. The VM knows no instruction's semantics beyond that call.
//
// Simulated field devices (the "bench") have names. Tools and tests reach them through the
// family-neutral inject()/observe() entry points: a fault or change is a word ("offline",
// "cable removed", "data size", ...) with string arguments, and a module answers only for the
// devices it owns (DeviceStatus::Kind::NotMine otherwise), so the runtime can ask every module
// in slot order without knowing any module type.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "instructions/instruction_table.h"
#include "vm/event_queue.h"
#include "vm/virtual_time.h"

namespace softslc {

// Processor modes (S:1/0-4 codes in brackets, DF1 p.10-3): Program (1), Run (6), Test single
// scan (8), and Faulted (a major error halted the processor, S:1/13).
// Suspended: Suspend Idle after a true SUS (RM ch. 6): no program scan, outputs off, not a fault.
enum class Mode : std::uint8_t { Program, Run, Test, Faulted, Suspended };
std::string_view to_string(Mode m);

enum class MFile : std::uint8_t { M0 = 0, M1 = 1 };

// The result of an immediate M0/M1 access.
enum class MAccess : std::uint8_t {
  Ok,
  NoSuchWord,  // the module has no such word (outside its M0/M1 size, or no M files at all)
  Forbidden,   // the word exists but may not be accessed this way (read-only, reserved)
};
std::string_view to_string(MAccess a);

// A run of M-file words a module retains across a power loss, with their contents.
struct RetainedMWords {
  MFile file = MFile::M0;
  int first = 0;  // first word
  std::vector<std::uint16_t> words;
};

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
  // Puts the processor in a major fault (S:6 = code, S:1/13), as a module error does on the SLC
  // (for example a scanner refusing its G file at Run entry). Raised during a mode change it
  // takes effect once every module has seen the change; raised from an event it takes effect at
  // once. The first fault wins. The default ignores the request (hosts without faults).
  virtual void raise_major_fault(std::uint16_t /*code*/, std::string /*message*/) {}
  // A discrete card's field input word changed at now(): the discrete input interrupt
  // watches the first byte of the card in slot S:47 itself, not the input image (RM 11-20). The
  // default ignores it.
  virtual void field_input_changed(int /*slot*/, int /*word*/, std::uint16_t /*before*/, std::uint16_t /*after*/) {}
  // A specialty module requests service (the I/O event-driven interrupt, RM 11-27): the ISR file its
  // slot's configuration names runs when S:27/S:28 and the interrupt priorities allow; the module is
  // told through Module::interrupt_serviced when it may request again. The default ignores it.
  virtual void request_io_interrupt(int /*slot*/) {}
};

// ---- Specialty-module instructions ------------------------------------------------------------

// One operand of a specialty-module instruction, resolved by the interpreter for this execution.
struct ModuleOperand {
  enum class Kind : std::uint8_t { Table, MFile, Literal };
  Kind kind = Kind::Literal;
  std::uint32_t word = 0;   // Table: data-table word index; MFile: word in the module's M file
  std::uint32_t limit = 0;  // Table: words from `word` to the end of its data file
  int slot = 0;             // MFile: the module's slot
  MFile file = MFile::M0;   // MFile
  std::int64_t value = 0;   // Literal
};

// What a module may do while the processor executes one of its instructions. Every access is
// checked: a data-table access outside the operand's file raises fault 002Ah, a refused M-file
// access fault xx55h (both then return false); nothing reaches outside the data table.
// M-file accesses are not charged by themselves: the module charges the access-time rows the
// real processor pays (charge()), so a multi-word copy is charged as one multi-word access.
class ModuleInstructionContext {
 public:
  virtual ~ModuleInstructionContext() = default;
  virtual Opcode opcode() const = 0;
  virtual bool rung_in() const = 0;
  // The first program scan after entering Run or Test.
  virtual bool first_pass() const = 0;
  // Virtual time of this execution (scan start plus the scan time so far).
  virtual VirtualTime now() const = 0;
  virtual std::span<const ModuleOperand> operands() const = 0;
  // Word k of Table operand i.
  virtual bool read(std::size_t i, std::uint32_t k, std::uint16_t& value) = 0;
  virtual bool write(std::size_t i, std::uint32_t k, std::uint16_t value) = 0;
  // Words k .. k + out.size() - 1 of Table operand i, as out.size() calls of read() would give
  // them (the same fault at the first word past the file), in one call: a module reads a 70-word
  // control block every scan.
  virtual bool read_block(std::size_t i, std::uint32_t k, std::span<std::uint16_t> out) {
    for (std::size_t j = 0; j < out.size(); ++j)
      if (!read(i, k + static_cast<std::uint32_t>(j), out[j])) return false;
    return true;
  }
  // Words k .. k + in.size() - 1 of Table operand i, as in.size() calls of write() would write
  // them (the words before the first past the file written, then the same fault), in one call: a
  // BTR copies up to 64 words into its data file.
  virtual bool write_block(std::size_t i, std::uint32_t k, std::span<const std::uint16_t> in) {
    for (std::size_t j = 0; j < in.size(); ++j)
      if (!write(i, k + static_cast<std::uint32_t>(j), in[j])) return false;
    return true;
  }
  // Immediate M0/M1 access to the module in `slot` (normally the executing module).
  virtual bool read_m(int slot, MFile f, int word, std::uint16_t& value) = 0;
  virtual bool write_m(int slot, MFile f, int word, std::uint16_t value) = 0;
  // Words word .. word + out.size() - 1 of M0/M1, as out.size() calls of read_m() would read them
  // (the same fault at the first word refused), in one call: a BTR reads its four status words
  // and its data every time it executes (issue 20). Returns how many words were read: out.size(),
  // or fewer when one was refused (the fault raised).
  virtual std::size_t read_m_block(int slot, MFile f, int word, std::span<std::uint16_t> out) {
    for (std::size_t j = 0; j < out.size(); ++j)
      if (!read_m(slot, f, word + static_cast<int>(j), out[j])) return j;
    return out.size();
  }
  // Adds the access time of one access under `row` (`words` words for the multi-word rows).
  virtual void charge(MFileAccess row, int words) = 0;
  // Raises a major fault; the program scan stops after this instruction.
  virtual void fault(std::uint16_t code, std::string message) = 0;
};

// ---- Field devices -------------------------------------------------------------------------------

// A change injected into a simulated field device: `fault` is a word or phrase ("offline",
// "online", "cable removed", "cable restored", "data size", "noisy", "message timeout",
// "bt error", "bt data", "input", "normal", ...) and `args` its arguments. Each module family
// documents the words it accepts (docs/modules.md).
struct DeviceFault {
  std::string device;
  std::string fault;
  std::vector<std::string> args;
};

struct DeviceStatus {
  enum class Kind : std::uint8_t { NotMine, Done, Refused };
  Kind kind = Kind::NotMine;
  std::string message;  // why it was refused
  static DeviceStatus done() { return {Kind::Done, {}}; }
  static DeviceStatus refused(std::string m) { return {Kind::Refused, std::move(m)}; }
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
  // Reads out.size() words from `word` on, as read_m word by word: stops at the first word refused
  // and returns its status (Ok when none was), with `done` the words read before it. A module
  // whose reads are plain copies answers the block at once (a BTR reads its status and data as
  // blocks, issue 20); the default calls read_m for each word.
  virtual MAccess read_m_block(MFile f, int word, std::span<std::uint16_t> out, std::size_t& done);
  // Why the module refuses that access, in its own terms (for the fault message; empty: no more
  // to say than the MAccess status), e.g. the AutoMax master's "bus error: drop 2 slot 5 ...".
  virtual std::string m_refusal(MFile, int /*word*/, bool /*write*/) const { return {}; }

  virtual void on_mode_change(Mode /*from*/, Mode /*to*/) {}

  // True when the module does nothing of its own between the runtime's calls: given the same output
  // image, every input scan gives the same image until a tool changes a field input or injects a
  // change, and whatever it does later in time is an event on the runtime's queue. The runtime may
  // then skip scans that repeat the last one (docs/semantics.md "Repeated scans"); the default,
  // false, never allows that.
  virtual bool passive() const { return false; }

  // Repeated scans of a program that reaches the module through M0/M1 or its instructions (BTR,
  // BTW, DEM; docs/semantics.md "Repeated scans"). A module that returns a count promises, while
  // it is passive(): read_m changes nothing and answers from state that changes only in the
  // module's own events and in write_m and execute; every write_m or execute that changes
  // anything the module does or answers (a value not already there, a transfer or message started
  // or dropped, a command taken) advances the count; and execute depends only on what it reads
  // through its context (the table, M0/M1, the rung, the time) and on state that only write_m and
  // execute change. So a scan whose M0/M1 writes and module instructions left every count where it
  // was, and whose M0/M1 reads read the same afterwards, is followed by the same scan. The
  // default, nullopt ("cannot say"), keeps a program that reaches the module from repeating.
  virtual std::optional<std::uint64_t> program_changes() const { return std::nullopt; }
  // Whether write_m(f, word, value) now would be accepted and change nothing. The runtime asks it
  // of every M0/M1 write a probe made, after an event, to go on repeating the probe past the event
  // (the event may have changed what a write does: an AutoMax drop's rail, a pending mode). The
  // default, false, stops the repeats at the first event.
  virtual bool m_write_changes_nothing(MFile /*f*/, int /*word*/, std::uint16_t /*value*/) const { return false; }

  // The ISR for this module's interrupt request has been scanned to completion, or an RPI reset
  // the request (RM 11-27 step 3): the module may request again.
  virtual void interrupt_serviced() {}

  // M-file words the real module keeps across a power loss ("Certain specialty I/O modules retain
  // the status of M0-M1 data after power is removed. See your specialty I/O module user's
  // manual", 1747-SN appendix B). `softslc run --state` saves them with the data table and puts
  // them back into the fresh module before the first scan (vm/state_file.h). Each family decides
  // from its manual and documents it; the default retains nothing.
  virtual std::vector<RetainedMWords> retained_m_words() const { return {}; }
  // Called only with a range retained_m_words() lists (same file, first word and length).
  virtual void restore_m_words(const RetainedMWords& /*saved*/) {}

  // Executes a specialty instruction addressed to this module (BTR/BTW to a scanner, DEM to a
  // DeviceNet scanner). The default refuses with fault 001Fh: the module has no such instruction.
  virtual void execute(ModuleInstructionContext& ctx);

  // Field devices this module simulates: their names, injected changes and observable values
  // (what = "outputs", "inputs", "btw data", ... as the family documents). NotMine / nullopt for
  // devices the module does not own.
  virtual std::vector<std::string> device_names() const { return {}; }
  virtual DeviceStatus inject(const DeviceFault& /*fault*/) { return {}; }
  virtual std::optional<std::vector<std::int64_t>> observe(std::string_view /*device*/, std::string_view /*what*/) const {
    return std::nullopt;
  }

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
