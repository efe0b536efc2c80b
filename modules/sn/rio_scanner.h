// The 1747-SN Remote I/O scanner and the RIO link it masters, in virtual time.
//
// The scanner is a Module in the local chassis. Toward the processor it has an input and an
// output image (SCAN_IN/SCAN_OUT words of its 32: logical rack r group g is word 8r + g), an M0
// control file and an M1 status file (1747-SN ch. 4), a G file it takes at Run/Test entry, and
// the BTR/BTW instructions (block_transfer.h). Toward the field it runs the RIO link: it visits
// the logical devices of its G file one after another, each visit taking the appendix A time for
// the device's size at the scanner's baud rate (modules/throughput rio_scan_time), plus T_ri when
// the visit carries block-transfer data, so an undisturbed RIO scan takes exactly T_RIO. The link
// runs on the runtime's event queue, asynchronously to the processor scan, as the real card does.
//
// Each visit exchanges one logical device's image: the scanner sends the output words and a
// command — RUN (outputs follow the image), ADAPTER RESET, or RESET DECIDE (the adapter's
// hold-last-state switch decides) — chosen from the processor mode and the M0 device-reset (DR,
// words 16-19) and remote-output-reset (ROR, words 24-27) bits exactly as the mode table of
// chapter 4 prescribes; the adapter answers with its inputs. Devices inhibited in M0 words 8-11
// are not visited. An adapter that does not answer (offline, cable removed, not in the bench) is
// retried once (M1 retry counter + 1) and then faulted; one that answers with a wrong image size,
// or is set to primary mode while the scanner is in normal mode, is faulted. M1 shows the
// configuration (words 3, 4, 8, 9 are G-file words), the baud rate (word 2), communication
// attempted / enabled-device fault (word 0), the active devices (5, 10), the device fault bits
// (12-15) and the retry counters (16-47).
//
// Adapters run their own chassis: every backplane_scan they copy input modules into their input
// buffer and their output buffer to output modules (T_adp); input modules see a field change
// after their input delay (T_id), output terminals follow after the output delay (T_od). An
// adapter that hears nothing for its comm_timeout resets or holds its outputs per its switch.
//
// Block transfers are driven by the M0 control words of the 32 buffers. The scanner handles one
// enable (or TO request) per service tick of T_SNo-bt (appendix A: "the scanner processes only one
// BT enable or disable every T_SNo-bt"), takes the disables waiting at a tick together with it,
// and posts finished transfers at the next tick — so a transfer costs T_SNo-bt once for its
// enable (after the enables queued before it) and once for its response, as the BT throughput
// formula T_SNo-bt(number of BTs + 1) counts; per logical rack one block transfer is started at a time, first come first
// served, and at most one carries data per RIO scan. A started transfer first sends its request
// with a discrete visit; the adapter acknowledges after its bt_delay (plus the module's
// response_delay) and the data moves on a later visit. The four-second BT timer, the TO bit and
// every Table 5.3 error code are simulated (docs/1747-sn.md lists when each occurs).
//
// Determinism: all state changes happen in module callbacks and events ordered by (time,
// sequence); nothing depends on the host.
//
// Passive (Module::passive, docs/semantics.md "Repeated scans"): the input scan copies the input
// image the link's visits last left, and the output scan stores the output image the visits will
// send; neither looks at the clock. Everything the link, the adapters' chassis, the input and
// output delays, the watchdogs and the block-transfer service do later is an event on the runtime's
// queue. So the scanner is passive unless a new Run/Test mode is waiting for the end of its first
// scan (the output scan would then change the M0 settings in effect). A block transfer in progress
// does not stop it: its progress is events too (service ticks, visits, the BT timer), and the M1
// words that change with it are read again by the runtime after the events between repeats.
//
// M files and BTR/BTW in repeated scans (Module::program_changes): read_m is a copy of M0 or M1,
// which change only in the link's and the block-transfer service's events and in write_m. A write
// to M0 changes something when the word holds another value or when it is a buffer's control word
// whose EN or TO differs from what the scanner last noted (note_control_write); both count. BTR
// and BTW act on the scanner only through M0 writes and M1 reads
// (block_transfer.cpp), so they are covered by the same count. m_write_changes_nothing answers
// the same question without writing.
#pragma once

#include <array>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "instructions/module_catalog.h"
#include "modules/sn/block_transfer.h"
#include "modules/sn/rio_bench.h"
#include "modules/throughput/rio_throughput.h"
#include "parser/program.h"
#include "vm/module.h"

namespace softslc {

class RioScanner final : public Module {
 public:
  RioScanner(const SlotConfig& slot, int m0_words, int m1_words, std::shared_ptr<const RioScannerBench> bench);
  ~RioScanner() override;

  // ---- Module ----
  void attach(ModuleHost& host) override;
  void input_scan(std::span<std::uint16_t> image) override;
  void output_scan(std::span<const std::uint16_t> image) override;
  int m_file_words(MFile f) const override;
  MAccess read_m(MFile f, int word, std::uint16_t& value) override;
  MAccess read_m_block(MFile f, int word, std::span<std::uint16_t> out, std::size_t& done) override;
  MAccess write_m(MFile f, int word, std::uint16_t value) override;
  void on_mode_change(Mode from, Mode to) override;
  bool passive() const override;
  std::optional<std::uint64_t> program_changes() const override { return program_changes_; }
  bool m_write_changes_nothing(MFile f, int word, std::uint16_t value) const override;
  void execute(ModuleInstructionContext& ctx) override;
  bool set_field_input(int word, std::uint16_t value, std::uint16_t mask) override;
  std::optional<std::uint16_t> field_input(int word) const override;
  std::optional<std::uint16_t> field_output(int word) const override;
  std::vector<std::string> device_names() const override;
  DeviceStatus inject(const DeviceFault& fault) override;
  std::optional<std::vector<std::int64_t>> observe(std::string_view device, std::string_view what) const override;

  // ---- For tests and tools ----
  const std::vector<std::uint16_t>& m0() const { return m0_; }
  const std::vector<std::uint16_t>& m1() const { return m1_; }
  bool link_running() const { return link_running_; }
  // Duration of the last complete RIO scan (all logical devices once) and how many there were.
  Nanoseconds last_rio_scan() const { return last_rio_scan_; }
  std::uint64_t rio_scans() const { return rio_scans_; }
  // When the named remote output module's terminals last changed (-1: never).
  VirtualTime output_changed_at(std::string_view module) const;
  // The T_SNo-bt service period this configuration uses.
  Nanoseconds bt_service_period() const { return tick_period_; }
  throughput::RioBaud baud() const { return baud_; }
  const RioGFile& g_file() const { return g_; }

 private:
  enum class Command : std::uint8_t { Run, Reset, Decide };
  enum class Reply : std::uint8_t { Ok, NoReply, WrongSize };

  struct RemoteModule {
    RioModuleSpec spec;
    std::uint32_t field_in = 0;   // terminals
    std::uint32_t seen_in = 0;    // after the input delay
    std::uint32_t out_target = 0;  // what the adapter drives
    std::uint32_t out_field = 0;   // terminals, after the output delay
    VirtualTime out_changed_at = -1;
    // Block transfer.
    std::vector<std::int16_t> btr_data;
    std::vector<std::int16_t> last_btw;
    std::int64_t btw_count = 0, btr_count = 0;
    int length = 64;
    int write_length = 64;
    bool responding = true;
    bool failing = false;
    Nanoseconds response_delay = 0;
    std::vector<RioBtRamp> ramps;
    std::vector<RioBtStep> steps;
    VirtualTime ramp_origin = 0;
  };
  struct Adapter {
    RioAdapterSpec spec;
    bool online = true;
    bool cable = true;
    int answer_groups = 8;  // the size it answers with ("data size" changes it)
    int noisy = 0;
    bool hold_last_state = false;
    std::uint64_t transfers = 0;
    std::vector<std::uint16_t> in_buffer, out_buffer;  // per image word of the adapter
    std::vector<std::uint16_t> received;               // what the scanner last received from it
    std::vector<std::uint16_t> generic_in, generic_out;  // adapters described without modules
    VirtualTime last_comm = -1;
    // The communication watchdog (arm_watchdog): the time it expires unless the adapter is heard
    // from again (-1: expired or never armed), the order in which it was last armed, and the time
    // of the one event that stands for it (-1: none).
    VirtualTime watchdog_due = -1;
    std::uint64_t watchdog_armed = 0;
    VirtualTime watchdog_event_at = -1;
    std::uint64_t backplane_scheduled = 0;  // the order of its pending backplane scan (schedule_backplanes)
    bool outputs_stale = true;  // out_buffer changed since apply_outputs last ran
    bool inputs_changed = true;  // a module's seen_in or generic_in changed since backplane last ran
    std::vector<RemoteModule> modules;
    std::vector<int> input_modules;  // indices of its discrete input modules
  };
  struct Device {
    RioGDevice g;
    int adapter = -1;
    bool attempted = false;
    std::vector<bool> failing;  // per logical device of this device
    bool faulted() const;
  };
  struct Logical {
    int device = 0;
    int part = 0;     // index among the device's logical devices
    int rack = 0;     // 0-3
    int first_word = 0;
    int words = 0;
    Nanoseconds slot_time = 0;
  };
  struct Visit {
    int logical = -1;
    Reply reply = Reply::NoReply;
    int bt_request = 0;  // buffer whose request this visit carries
    int bt_data = 0;     // buffer whose data this visit carries
  };
  enum class BtState : std::uint8_t { Idle, Waiting, Active, Done, Error };
  enum class BtPhase : std::uint8_t { None, Request, Awaiting };
  struct Buffer {
    BtState state = BtState::Idle;
    BtPhase phase = BtPhase::None;
    bool en_written = false, to_written = false;  // last values written to M0 (edge detection)
    bool en_seen = false, to_seen = false;        // last values the scanner has processed
    bool read = true;
    int rack = 0, group = 0, slot = 0;
    int requested = 0;
    int logical = -1, adapter = -1, module = -1;
    VirtualTime ready_at = 0;
    EventQueue::EventId timer = 0;
    bool result_ready = false;
    bool result_ok = false;
    std::int16_t result_code = 0;
    std::vector<std::uint16_t> result_data;
    int result_count = 0;
  };
  struct Note {
    int buffer = 0;
    bool en = false, to = false;
  };

  // Configuration.
  void build_devices();
  void write_config_status();
  bool configuration_fault(Mode to);
  void set_m0_defaults();
  std::uint16_t control(int first_word, int rack) const;  // M0 control word as the link uses it
  Command command_for(const Device& d) const;
  bool inhibited(const Device& d) const;

  // The RIO link.
  void start_link();
  void schedule_next(VirtualTime t);
  void end_visit(const Visit& v, VirtualTime t);
  Reply reply_of(const Device& d) const;
  void exchange(const Logical& l, Device& d, Adapter& a, VirtualTime t);
  void update_status();
  std::array<std::uint16_t, 4> inhibit_words() const;  // M0 words 8-11 in effect
  void backplane(int adapter, VirtualTime t);
  void apply_outputs(Adapter& a, VirtualTime t);
  void arm_watchdog(int adapter, VirtualTime t);
  void watchdog_event(int adapter, VirtualTime t);
  void watchdog_expires(int adapter, VirtualTime t);
  void schedule_backplanes(int group, VirtualTime at);
  void backplanes(int group, VirtualTime t);
  std::uint32_t module_inputs(const RemoteModule& m) const;
  std::uint16_t adapter_input_word(const Adapter& a, int w) const;
  void set_module_input(int adapter, int module, std::uint32_t value, std::uint32_t mask);

  // Block transfers.
  bool note_control_write(int buffer, std::uint16_t value);  // true: EN or TO differ from those noted
  void request_tick();
  void tick(VirtualTime t);
  bool apply_note(const Note& n);
  void enable(int x);
  void disable(int x);
  void start(int x);
  void finish(int x, bool ok, std::int16_t code, std::vector<std::uint16_t> data = {}, int count = 0);
  void post(int x);
  void cancel_all();
  void bt_visit_end(int x, const Visit& v, VirtualTime t);
  std::vector<std::int16_t> btr_source(RemoteModule& m, VirtualTime t) const;
  std::uint16_t& m1w(int word);

  // Devices by name.
  Adapter* find_adapter(std::string_view name);
  const Adapter* find_adapter(std::string_view name) const;
  std::pair<int, int> find_module(std::string_view name) const;

  // Configuration from the SLOT line and the bench.
  std::shared_ptr<const RioScannerBench> bench_;
  throughput::RioBaud baud_ = throughput::RioBaud::b57_6k;
  std::uint16_t baud_word_ = 3;
  bool has_g_ = false;
  RioGFile g_;
  std::vector<ModuleConfigFinding> g_findings_;
  bool duplicate_ = false;
  int scan_in_ = 0, scan_out_ = 0;

  std::vector<std::uint16_t> m0_, m1_;
  std::array<std::uint16_t, 32> in_image_{}, out_image_{};
  std::vector<Device> devices_;
  std::vector<Logical> logical_;
  std::vector<Adapter> adapters_;
  // For each scanner image word, the adapters whose image holds it and where (a primary and a
  // complementary chassis may share a word): exchange() ORs their received words.
  struct ImageSource {
    std::size_t adapter = 0, index = 0;
  };
  std::array<std::vector<ImageSource>, 32> image_sources_;
  // Adapters whose chassis scan with the same backplane_scan, in adapter order: their scans fall at
  // the same times and run in one event (schedule_backplanes says why that is the same).
  struct BackplaneGroup {
    Nanoseconds period = 0;
    std::vector<int> adapters;
  };
  std::vector<BackplaneGroup> backplane_groups_;

  // Link state.
  bool link_running_ = false;
  bool cable_ok_ = true;
  std::size_t cursor_ = 0;
  Visit visit_;  // the one visit in flight (schedule_next); the event captures only `this`
  // Counts the watchdog arms and backplane schedulings, in the order they happen, so that the
  // order of two of them can be told (arm_watchdog).
  std::uint64_t order_ = 0;
  VirtualTime rio_scan_start_ = 0;
  Nanoseconds last_rio_scan_ = 0;
  std::uint64_t rio_scans_ = 0;
  std::array<std::uint16_t, 4> status_inhibit_{};  // the inhibit words update_status last used
  std::array<bool, 4> rack_bt_used_{};
  // The mode the link acts on: a new Run/Test mode takes effect after the first full program
  // scan ("The processor does not use the M0 file until a full program scan occurs"); until then
  // the control words in effect before the change are used.
  Mode effective_mode_ = Mode::Program;
  std::optional<Mode> pending_mode_;
  std::array<std::uint16_t, 12> held_control_{};  // M0 words 8-11, 16-19, 24-27 before the change

  // Block-transfer state.
  std::array<Buffer, rio::kBufferCount + 1> bt_{};
  std::deque<Note> notes_;
  std::array<std::deque<int>, 4> rack_queue_;
  std::vector<int> ready_;
  std::deque<Note> kept_notes_;  // tick()'s scratch
  std::vector<int> posting_;     // tick()'s scratch
  Nanoseconds tick_period_ = milliseconds(16);
  VirtualTime tick_origin_ = 0;
  VirtualTime next_tick_ = -1;  // scheduled tick time, -1 = none
  VirtualTime last_tick_ = -1;
  std::uint64_t program_changes_ = 0;  // M0 writes that changed a word or a buffer's EN/TO
};

}  // namespace softslc
