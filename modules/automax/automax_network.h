// The Reliance AutoMax Remote I/O network (AutoMax Remote I/O manual, chapter 4): the master
// module (M/N 57C416) in an SLC chassis slot, whose M0 file is its dual-port image, and the slave
// drops of the bench. docs/automax.md describes the model and its decisions.
//
// The dual port is 8 areas of 512 registers (parser/automax_def.h): area 0 is the master's
// status (figure 4.1, read only), areas 1-7 the drops. Ladder reaches it through IODEF/RIODEF
// symbols, i.e. ordinary immediate M0 accesses: read_m/write_m apply the access rules of
// section 4.3 (input registers read only, output registers read/write, a register the slave
// drop does not have is a bus error — refused, so the processor faults with xx55h).
//
// The network runs on the runtime's event queue. At power-up the master polls every drop; then
// each update cycle it polls the active drops in drop-number order (a message in error is
// retried up to three times, then the drop goes off-line), and polls one inactive drop (a drop
// that answers joins). Each poll costs the drop's DROP_TIME of section 4.5 and the inactive
// poll 2.7 ms (modules/throughput/automax_throughput.h), so the update period is the one
// `softslc throughput` computes. The counters of drop 0 registers 14-19 count the messages.
//
// Passive (Module::passive, docs/semantics.md "Repeated scans"): always. The master has no image
// words (its input and output scans do nothing); everything it does in time — polls, retries, the
// rail reads, a drop's power-up diagnostics, which `answers` compares with the time of its poll —
// happens in its update-cycle events on the runtime's queue.
//
// M0 in repeated scans (Module::program_changes): M0 is the dual-port image, changed only by the
// update-cycle events (a poll stores a drop's inputs and the drop 0 counters) and by write_m; read_m
// copies it under the access rules. A write changes something only when it stores a value the
// image does not hold (an output register, read/write); a write the rules ignore changes nothing,
// and a refused one faults the processor. The access rules follow the drops' configuration and
// rails, which events may change, so m_write_changes_nothing asks them again.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "modules/bench/bench.h"
#include "modules/throughput/automax_throughput.h"
#include "parser/automax_def.h"
#include "vm/module.h"

namespace softslc {

// ---- What the bench describes (immutable) ---------------------------------------------------------

enum class AutomaxDropKind : std::uint8_t { Multibus, Shark, Head57C328, Head57C330, DriveHead };

// A module in a Multibus or Shark rack. Multibus: registers 0..inputs-1 are inputs (read only),
// the next `outputs` registers outputs. Shark: registers 0..inputs-1 (of 0-7) inputs, 8..8+outputs-1
// (of 8-15) outputs.
struct AutomaxModuleSpec {
  std::string name;
  int slot = 0;
  int inputs = 0;
  int outputs = 0;
  bool digital = true;  // Shark modules: digital or analog
};

struct AutomaxDropSpec {
  std::string name;
  AutomaxDropKind kind = AutomaxDropKind::Multibus;
  int number = 1;  // as set on the drop: 1-7, or 9-F for an all-digital Shark rack
  int area = 1;    // image area 1-7
  bool online = true;
  int noisy = 0;   // every N-th message is received in error (0: clean)
  std::vector<AutomaxModuleSpec> modules;  // Multibus, Shark
  std::vector<int> rails;                  // heads: connected rails; drive head: connected ports
  Nanoseconds diagnostics = milliseconds(500);  // power-up diagnostics after a reset
  bool all_digital_shark() const { return kind == AutomaxDropKind::Shark && number >= 9; }
};

struct AutomaxBench {
  std::string name;
  int keyswitch = 3;  // 1 memory protect, 2 setup, 3 program (figure 4.1 register 13)
  std::vector<AutomaxDropSpec> drops;
};

// Interprets the `automax` node wired to a master's slot (positioned errors in `diags`).
std::shared_ptr<const AutomaxBench> interpret_automax_bench(const BenchNode& node, DiagnosticList& diags);

// The section 4.5 description of a drop for the throughput formulas.
throughput::AutomaxDrop throughput_drop(const AutomaxDropSpec& spec);

// ---- The master module --------------------------------------------------------------------------

class AutomaxMaster : public Module {
 public:
  // Drop 0 register numbers (figure 4.1).
  static constexpr int kStatusRegister = 4;
  static constexpr int kDropNumberRegister = 12;
  static constexpr int kKeyswitchRegister = 13;
  static constexpr int kMessagesReceived = 14;
  static constexpr int kReceiveTimeouts = 15;
  static constexpr int kCrcErrors = 16;
  static constexpr int kOverrunErrors = 17;
  static constexpr int kAbortErrors = 18;
  static constexpr int kMessagesTransmitted = 19;
  static constexpr int kRetries = 3;  // "re-transmitted up to three times"
  static constexpr Nanoseconds kRailReadPeriod = milliseconds(20);  // 57C330, section 4.6.3

  // `symbols`: the program's IODEF/RIODEF names by M0 word, so a refused access names them.
  using SymbolNames = std::map<int, std::string>;
  AutomaxMaster(const SlotConfig& slot, std::shared_ptr<const AutomaxBench> bench,
                std::shared_ptr<const SymbolNames> symbols = nullptr);

  void attach(ModuleHost& host) override;
  void input_scan(std::span<std::uint16_t>) override {}
  void output_scan(std::span<const std::uint16_t>) override {}
  int m_file_words(MFile f) const override { return f == MFile::M0 ? kAutomaxImageWords : 0; }
  MAccess read_m(MFile f, int word, std::uint16_t& value) override;
  MAccess write_m(MFile f, int word, std::uint16_t value) override;
  void on_mode_change(Mode from, Mode to) override;
  bool passive() const override { return true; }
  std::optional<std::uint64_t> program_changes() const override { return program_changes_; }
  bool m_write_changes_nothing(MFile f, int word, std::uint16_t value) const override;

  std::vector<std::string> device_names() const override;
  DeviceStatus inject(const DeviceFault& fault) override;
  std::optional<std::vector<std::int64_t>> observe(std::string_view device, std::string_view what) const override;

  // Why an access to M0 word `word` is refused (empty when it is not): "bus error: ..." or
  // "read only: ...", naming the drop, slot and register.
  std::string refusal(int word, bool write) const;
  std::string m_refusal(MFile f, int word, bool write) const override;
  Nanoseconds update_period() const { return update_period_; }

 private:
  enum class Rail : std::uint8_t { None, Undefined, Input, Output };
  enum class Access : std::uint8_t { BusError, ReadOnly, ReadWrite, Ignored };
  struct Drop {
    const AutomaxDropSpec* spec = nullptr;
    bool online = true;        // the drop answers (bench state, offline/online injections)
    int noisy = 0;
    bool active = false;       // in the master's list of active drops (status bit)
    VirtualTime ready_at = 0;  // running its power-up diagnostics until then
    std::uint64_t messages = 0;  // messages exchanged with it (for `noisy`)
    std::uint64_t retries = 0;
    std::array<std::uint16_t, kAutomaxAreaWords> field_in{};   // what its inputs read
    std::array<std::uint16_t, kAutomaxAreaWords> field_out{};  // what it last received
    std::vector<int> rails;                   // connected rails / ports now
    std::vector<int> known_rails;             // as sent at the last connection (configured at first)
    std::array<Rail, 16> rail_state{};        // 57C330 rail definitions
    std::vector<int> head_rails;              // 57C330: the rails at its last rail read
    VirtualTime next_rail_read = 0;
    std::array<bool, 4> port_online{true, true, true, true};  // drive head
    bool shark_configured = false;
    std::uint16_t shark_config = 0;
  };

  Access access(int word, std::string* why) const;
  int storage_word(int word) const;
  Drop* find_drop(std::string_view name);
  const Drop* find_drop(std::string_view name) const;
  bool has_rail(const Drop& d, int rail) const;
  Nanoseconds drop_time(const Drop& d) const;
  // One message exchange with drop `d`, with retries; false when the drop goes off-line.
  bool poll(Drop& d, Nanoseconds& elapsed);
  bool answers(Drop& d);
  void exchange(Drop& d);
  void go_offline(Drop& d);
  void join(Drop& d);
  void read_rails(Drop& d);
  void power_up();
  void poll_inactive(int area);
  void update_cycle();
  void count(int reg);
  void set_status();

  std::shared_ptr<const AutomaxBench> bench_;
  std::shared_ptr<const SymbolNames> symbols_;
  std::array<std::uint16_t, kAutomaxImageWords> image_{};
  std::array<std::optional<Drop>, kAutomaxAreas> drops_;  // by image area
  bool cable_removed_ = false;
  int next_inactive_ = 1;  // round robin of the inactive poll
  Nanoseconds update_period_ = 0;
  std::int64_t cycles_ = 0;
  std::uint64_t program_changes_ = 0;  // M0 writes that stored a new value
};

}  // namespace softslc
