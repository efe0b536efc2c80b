// The 1203-SM1 SLC to SCANport communications module on the module framework (vm/module.h).
//
// It wraps the SCANport library (modules/scanport: the simulated drives and the messages of
// appendix B) with what the chassis sees (docs/1203-sm1.md, "The module"):
//   - the I/O image: channel status (ID, valid, datalink valid), message status (READY/DONE,
//     M0 STA) and per channel logic status / feedback / datalink outputs in; channel command
//     (DE, ME, MSG ID) and per channel logic command / reference / datalink inputs out;
//   - basic mode (8 words) and enhanced mode (32 words, datalinks, safe state, messaging);
//   - the Fault/Program State DIP switches, applied whenever the processor is not in Run;
//   - M0 (eight request buffers) and M1 (DIP switches, G file echo, three response buffers);
//   - messages on the SCANport link as events on the runtime's queue.
// The drives run in the runtime's virtual time: every hook first brings them up to now.
//
// Passive (Module::passive, docs/semantics.md "Repeated scans"): the drives are not events; they
// are brought up to date at each image scan. So the module is passive only while nothing it shows
// would move with time alone: every drive settled (its speed at its target, so the plant updates
// change nothing), no message Busy (its completion is an event, but the drive acted on it at its
// start), and M0 STA not waiting for the end of the module's M0 read time (kM0ReadTime; that is
// the clock, not an event). Given the same output image again, the output scan then changes
// nothing: the logic command's functions act on rising edges only, and the reference, datalinks
// and DE are levels the drive already holds.
//
// M files in repeated scans (Module::program_changes): read_m is a copy of M0 or M1; M1 changes
// only when a message's answer lands (an event) and M0 only in write_m. But every M0 write, even
// of the value already there, drops M0 STA for the module's read time (chapter 4, "M0 STA"), so
// every write counts as a change and m_write_changes_nothing is never true: a program that writes
// M0 every scan does not repeat, one that only reads M1 does.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "modules/scanport/drive.h"
#include "modules/scanport/messages.h"
#include "modules/sm1/sm1_config.h"
#include "vm/module.h"

namespace softslc {

// The fault code a drive latches when its SCANport connection is lost while the channel is
// enabled (DE cleared, cable pulled, or the DIP switch's "fault SCANport device"). The manual
// says only that the device "will fault"; the code is an assumption (docs/1203-sm1.md).
inline constexpr std::uint16_t kScanportLossFault = 81;
// Time the module takes to read M0 changes before it sets M0 STA again (assumption).
inline constexpr Nanoseconds kM0ReadTime = 1 * kNsPerMs;

class Sm1Module final : public Module {
 public:
  Sm1Module(const SlotConfig& slot, Sm1Config config, const std::shared_ptr<const Sm1Bench>& bench);

  // ---- Module ----
  void input_scan(std::span<std::uint16_t> image) override;
  void output_scan(std::span<const std::uint16_t> image) override;
  int m_file_words(MFile f) const override;
  MAccess read_m(MFile f, int word, std::uint16_t& value) override;
  MAccess write_m(MFile f, int word, std::uint16_t value) override;
  void on_mode_change(Mode from, Mode to) override;
  bool passive() const override;
  std::optional<std::uint64_t> program_changes() const override { return program_changes_; }
  std::vector<std::string> device_names() const override;
  DeviceStatus inject(const DeviceFault& fault) override;
  std::optional<std::vector<std::int64_t>> observe(std::string_view device, std::string_view what) const override;
  std::optional<std::uint16_t> field_output(int word) const override;

  // ---- For tests and tools ----
  enum class MessageState : std::uint8_t { Ready, Busy, Done };
  MessageState message_state(int channel) const { return channel_(channel).message; }
  const scanport::Drive* drive(int channel) const;
  bool m0_status() const;

 private:
  struct Channel {
    std::optional<scanport::Drive> drive;  // the bench's drive, if one is plugged in
    std::string name;
    int port = 2;
    bool powered = true;
    bool cable = true;
    bool message_timeout = false;  // injected: the device ignores messages
    // Channel command as the module applies it.
    bool de = false;
    bool me = false;
    int msg_id = 0;
    // The output data last sent (held, zeroed or replaced by safe state outside Run).
    std::uint16_t command = 0, reference = 0;
    std::array<std::uint16_t, scanport::kDatalinkWords> datalinks{};
    // Messaging.
    MessageState message = MessageState::Ready;
    std::vector<std::uint16_t> request;  // the M0 buffer as sent
    VirtualTime message_start = 0;
    std::uint64_t link_epoch = 0;     // counts link losses (cable removed, drive powered off)
    std::uint64_t message_epoch = 0;  // link_epoch when the message went out
    std::uint64_t messages = 0;
    std::uint16_t datalink_error = 0;  // first refusal of the last datalink transfer
  };

  const Channel& channel_(int c) const { return channels_[static_cast<std::size_t>(c - 1)]; }
  Channel& channel_(int c) { return channels_[static_cast<std::size_t>(c - 1)]; }
  // In Run the outputs follow the image; in every other mode the DIP switches rule.
  bool outputs_live() const;
  bool connected(const Channel& ch) const { return ch.drive && ch.powered && ch.cable; }
  // The channel's valid datalinks, bit n = link n (0-3 = A-D): enabled in G word 1, present in the
  // connected device, channel enabled, enhanced mode.
  unsigned valid_datalinks(const Channel& ch) const;
  void advance_drives();
  void fault_if_enabled(Channel& ch);
  void set_enable(Channel& ch, bool de);
  void send_outputs(Channel& ch);
  void apply_fault_state();
  void command_bits(int c, std::span<const std::uint16_t> image, bool& de, bool& me, int& msg_id) const;
  void start_message(int c);
  void finish_message(int c, const scanport::Response& response);
  Channel* find_drive(std::string_view name);
  const Channel* find_drive(std::string_view name) const;

  Sm1Config config_;
  std::string module_name_;
  std::array<Channel, kSm1Channels> channels_;
  std::vector<std::uint16_t> m0_, m1_;
  std::vector<std::uint16_t> last_outputs_;
  bool m0_loaded_ = false;
  std::uint64_t program_changes_ = 0;  // M0 writes (each one drops M0 STA)
  VirtualTime m0_ready_at_ = 0;
};

}  // namespace softslc
