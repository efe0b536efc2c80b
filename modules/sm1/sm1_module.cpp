#include "modules/sm1/sm1_module.h"

#include <algorithm>
#include <charconv>

namespace softslc {

namespace {

// Channel status and command bytes: channel 1 = word 0 low byte, 2 = word 0 high byte, 3 = word 1
// low byte (chapter 3 "Channel Status Input Image Definitions", chapter 4 "Enhanced Mode Interface").
constexpr int status_word(int c) { return c == 3 ? 1 : 0; }
constexpr int byte_shift(int c) { return c == 2 ? 8 : 0; }

// Bits within a channel's status byte: ID 0-2, V 3, datalink A-D valid 4-7.
constexpr std::uint16_t kIdMask = 0x0007;
constexpr std::uint16_t kNotConnectedId = 7;
constexpr int kValidBit = 3;
constexpr int kDatalinkValidBit = 4;
// Bits within a channel's command byte: DE 0, ME 1, MSG ID 2-4.
constexpr std::uint16_t kDataEnable = 0x01;
constexpr std::uint16_t kMessageEnable = 0x02;
constexpr int kMsgIdShift = 2;
constexpr std::uint16_t kMsgIdMask = 0x07;
// Input word 1: DONE (8, 10, 12), READY (9, 11, 13) per channel, M0 STA (14).
constexpr int done_bit(int c) { return 8 + 2 * (c - 1); }
constexpr int ready_bit(int c) { return 9 + 2 * (c - 1); }
constexpr int kM0StaBit = 14;

// Image words of channel c: logic command/status, reference/feedback, datalinks A1-D2.
constexpr int command_word(int c) { return 2 + 2 * (c - 1); }
constexpr int reference_word(int c) { return 3 + 2 * (c - 1); }
constexpr int datalink_word(int c, int i) { return 8 + 8 * (c - 1) + i; }
// G file: datalink enables in word 1 (EA1 = bit 0 ... ED3 = bit 11); safe state data in the
// same places as the output image (Figure 4.8).
constexpr int datalink_enable_bit(int c, int link) { return 4 * (c - 1) + link; }

std::optional<std::int64_t> integer_arg(const std::string& s) {
  std::int64_t v = 0;
  const char* b = s.data();
  const char* e = s.data() + s.size();
  int base = 10;
  if (s.size() > 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X')) {
    b += 2;
    base = 16;
  }
  auto r = std::from_chars(b, e, v, base);
  if (r.ec != std::errc{} || r.ptr != e) return std::nullopt;
  return v;
}

}  // namespace

Sm1Module::Sm1Module(const SlotConfig& slot, Sm1Config config, const std::shared_ptr<const Sm1Bench>& bench)
    : Module(slot.slot, slot.catalog, slot.scan_in, slot.scan_out), config_(std::move(config)) {
  m0_.assign(static_cast<std::size_t>(config_.m0_words), 0);
  m1_.assign(static_cast<std::size_t>(config_.m1_words), 0);
  // M1:e.000 = DIP switches, M1:e.001-031 = echo of G file words 1-31 (Figure 4.10).
  if (!m1_.empty()) m1_[0] = config_.dip_switch_word();
  for (int k = 1; k < kSm1MaxGWords && k < config_.m1_words; ++k) m1_[static_cast<std::size_t>(k)] = config_.g_word(k);
  last_outputs_.assign(static_cast<std::size_t>(std::max(slot.scan_out, 0)), 0);
  if (!bench) return;
  module_name_ = bench->name;
  for (const auto& d : bench->drives) {
    Channel& ch = channel_(d.channel);
    ch.drive.emplace(*d.description);
    ch.name = d.name;
    ch.port = d.port;
    ch.powered = d.powered;
    ch.cable = d.cable;
  }
}

const scanport::Drive* Sm1Module::drive(int channel) const {
  const Channel& ch = channel_(channel);
  return ch.drive ? &*ch.drive : nullptr;
}

// See the header: nothing may move with the clock alone between events.
bool Sm1Module::passive() const {
  if (m0_loaded_ && (!host() || host()->now() < m0_ready_at_)) return false;
  for (const Channel& ch : channels_) {
    if (ch.message == MessageState::Busy) return false;
    if (ch.drive && !ch.drive->settled()) return false;
  }
  return true;
}

bool Sm1Module::m0_status() const { return m0_loaded_ && host() && host()->now() >= m0_ready_at_; }

void Sm1Module::advance_drives() {
  if (!host()) return;
  for (auto& ch : channels_)
    if (ch.drive) ch.drive->advance_to(std::max(host()->now(), ch.drive->now()));
}

unsigned Sm1Module::valid_datalinks(const Channel& ch) const {
  if (!config_.enhanced() || !ch.de || !connected(ch)) return 0;
  const int c = static_cast<int>(&ch - channels_.data()) + 1;
  const std::uint16_t enables = config_.g_word(1);
  // A datalink the device does not have carries nothing ("if supported in the connected
  // SCANport device").
  const auto& d = ch.drive->description();
  unsigned links = 0;
  for (int link = 0; link < 4; ++link) {
    if (!(enables & (1u << datalink_enable_bit(c, link)))) continue;
    for (int i = 2 * link; i < 2 * link + 2; ++i)
      if (d.data_in[static_cast<std::size_t>(i)] || d.data_out[static_cast<std::size_t>(i)]) links |= 1u << link;
  }
  return links;
}

// ---- I/O image -------------------------------------------------------------------------------------------------

void Sm1Module::input_scan(std::span<std::uint16_t> image) {
  advance_drives();
  std::fill(image.begin(), image.end(), 0);
  auto put = [&](int w, std::uint16_t v) {
    if (w < static_cast<int>(image.size())) image[static_cast<std::size_t>(w)] = v;
  };
  auto get = [&](int w) { return w < static_cast<int>(image.size()) ? image[static_cast<std::size_t>(w)] : std::uint16_t{0}; };
  for (int c = 1; c <= kSm1Channels; ++c) {
    const Channel& ch = channel_(c);
    std::uint16_t status = connected(ch) ? static_cast<std::uint16_t>(ch.port & kIdMask) : kNotConnectedId;
    // V goes high only after the program sets DE (chapter 3): DE as the module last received it.
    const bool valid = ch.de && connected(ch);
    if (valid) status |= 1u << kValidBit;
    // Asked once per channel and scan: the answer holds for the status bits and every datalink word.
    const unsigned links = valid_datalinks(ch);
    status |= static_cast<std::uint16_t>(links << kDatalinkValidBit);
    put(status_word(c), static_cast<std::uint16_t>(get(status_word(c)) | (status << byte_shift(c))));
    if (valid) {
      put(command_word(c), ch.drive->logic_status());
      put(reference_word(c), ch.drive->feedback());
    }
    if (!config_.enhanced()) continue;
    for (int i = 0; i < scanport::kDatalinkWords; ++i)
      if (links & (1u << (i / 2))) put(datalink_word(c, i), ch.drive->read_datalink(i));
    std::uint16_t msg = 0;
    if (ch.message == MessageState::Ready) msg |= 1u << ready_bit(c);
    if (ch.message == MessageState::Done) msg |= 1u << done_bit(c);
    put(1, static_cast<std::uint16_t>(get(1) | msg));
  }
  if (config_.enhanced() && m0_status()) put(1, static_cast<std::uint16_t>(get(1) | (1u << kM0StaBit)));
}

void Sm1Module::command_bits(int c, std::span<const std::uint16_t> image, bool& de, bool& me, int& msg_id) const {
  const int w = status_word(c);
  const std::uint16_t byte = w < static_cast<int>(image.size())
                                 ? static_cast<std::uint16_t>((image[static_cast<std::size_t>(w)] >> byte_shift(c)) & 0xFF)
                                 : 0;
  de = byte & kDataEnable;
  // Basic mode has no messaging: only DE is defined (chapter 3).
  me = config_.enhanced() && (byte & kMessageEnable);
  msg_id = (byte >> kMsgIdShift) & kMsgIdMask;
}

void Sm1Module::output_scan(std::span<const std::uint16_t> image) {
  advance_drives();
  if (!outputs_live()) {
    // Program, Test or Faulted: the DIP switches decided the data at the mode change.
    for (auto& ch : channels_) send_outputs(ch);
    return;
  }
  std::copy_n(image.begin(), std::min(image.size(), last_outputs_.size()), last_outputs_.begin());
  auto word = [&](int w) { return w < static_cast<int>(image.size()) ? image[static_cast<std::size_t>(w)] : std::uint16_t{0}; };
  for (int c = 1; c <= kSm1Channels; ++c) {
    Channel& ch = channel_(c);
    bool de = false, me = false;
    int msg_id = 0;
    command_bits(c, image, de, me, msg_id);
    set_enable(ch, de);
    ch.command = word(command_word(c));
    ch.reference = word(reference_word(c));
    for (int i = 0; i < scanport::kDatalinkWords; ++i)
      ch.datalinks[static_cast<std::size_t>(i)] = config_.enhanced() ? word(datalink_word(c, i)) : 0;
    send_outputs(ch);
    // Messaging: a rising ME sends the buffer MSG ID names; clearing ME returns DONE to READY.
    const bool rising = me && !ch.me;
    const bool falling = !me && ch.me;
    ch.me = me;
    ch.msg_id = msg_id;
    if (rising && ch.message == MessageState::Ready) start_message(c);
    if (falling && ch.message == MessageState::Done) ch.message = MessageState::Ready;
  }
}

void Sm1Module::fault_if_enabled(Channel& ch) {
  // "When reset to low (0), the channel disconnects from the SCANport device. This usually causes
  // the connected SCANport device to fault" (chapter 3); likewise a cable removed while enabled.
  if (ch.de && connected(ch)) ch.drive->fault(kScanportLossFault);
}

void Sm1Module::set_enable(Channel& ch, bool de) {
  if (ch.de && !de) fault_if_enabled(ch);
  ch.de = de;
}

void Sm1Module::send_outputs(Channel& ch) {
  if (!ch.de || !connected(ch)) return;
  ch.drive->set_logic_command(ch.command);
  ch.drive->set_reference(ch.reference);
  // The drive refuses a value it cannot take (read-only, out of range, running) and keeps the old
  // one, as for a message; the first refusal of this transfer is observable as "datalink error".
  scanport::ErrorCode refusal = scanport::ErrorCode::kNone;
  const unsigned links = valid_datalinks(ch);
  for (int i = 0; i < scanport::kDatalinkWords; ++i) {
    if (!(links & (1u << (i / 2))) || ch.drive->description().data_in[static_cast<std::size_t>(i)] == 0) continue;
    const auto e = ch.drive->write_datalink(i, ch.datalinks[static_cast<std::size_t>(i)]);
    if (refusal == scanport::ErrorCode::kNone) refusal = e;
  }
  ch.datalink_error = static_cast<std::uint16_t>(refusal);
}

// ---- Processor modes and the Fault/Program State DIP switches ---------------------------------------------------

bool Sm1Module::outputs_live() const { return host() && host()->mode() == Mode::Run; }

void Sm1Module::on_mode_change(Mode /*from*/, Mode to) {
  advance_drives();
  if (to != Mode::Run) apply_fault_state();
}

void Sm1Module::apply_fault_state() {
  for (int c = 1; c <= kSm1Channels; ++c) {
    Channel& ch = channel_(c);
    Sm1FaultState s = config_.fault_state[static_cast<std::size_t>(c - 1)];
    // The fourth setting is "Safe state data (enhanced mode only), Fault (basic mode only)".
    if (s == Sm1FaultState::SafeState && !config_.enhanced()) s = Sm1FaultState::FaultDevice;
    switch (s) {
      case Sm1FaultState::FaultDevice:
        set_enable(ch, false);
        break;
      case Sm1FaultState::ZeroData:
        // "If you select a state other than Fault, the channel enable bits ... retain their last
        // state values"; the data sent changes as the switch says.
        ch.command = ch.reference = 0;
        ch.datalinks.fill(0);
        break;
      case Sm1FaultState::HoldLastState:
        break;
      case Sm1FaultState::SafeState:
        ch.command = config_.g_word(command_word(c));
        ch.reference = config_.g_word(reference_word(c));
        for (int i = 0; i < scanport::kDatalinkWords; ++i)
          ch.datalinks[static_cast<std::size_t>(i)] = config_.g_word(datalink_word(c, i));
        break;
    }
    send_outputs(ch);
  }
}

// ---- M0/M1 files -----------------------------------------------------------------------------------------------

int Sm1Module::m_file_words(MFile f) const {
  return static_cast<int>(f == MFile::M0 ? m0_.size() : m1_.size());
}

MAccess Sm1Module::read_m(MFile f, int word, std::uint16_t& value) {
  const auto& file = f == MFile::M0 ? m0_ : m1_;
  if (word < 0 || word >= static_cast<int>(file.size())) return MAccess::NoSuchWord;
  value = file[static_cast<std::size_t>(word)];
  return MAccess::Ok;
}

MAccess Sm1Module::write_m(MFile f, int word, std::uint16_t value) {
  const int size = m_file_words(f);
  if (word < 0 || word >= size) return MAccess::NoSuchWord;
  // "The M1 file is a module input file (read-only)" (chapter 4).
  if (f == MFile::M1) return MAccess::Forbidden;
  m0_[static_cast<std::size_t>(word)] = value;
  // M0 STA drops while the module reads the changes (chapter 4, "M0 STA"), whatever was written.
  ++program_changes_;
  m0_loaded_ = true;
  if (host()) m0_ready_at_ = host()->now() + kM0ReadTime;
  return MAccess::Ok;
}

// ---- Messaging -------------------------------------------------------------------------------------------------

void Sm1Module::start_message(int c) {
  Channel& ch = channel_(c);
  const int first = scanport::request_buffer_word(ch.msg_id);
  const int last = std::min(first + scanport::kBufferWords, static_cast<int>(m0_.size()));
  ch.request.assign(m0_.begin() + std::min(first, last), m0_.begin() + last);
  scanport::Drive* d = connected(ch) && !ch.message_timeout ? &*ch.drive : nullptr;
  const scanport::Transaction t = scanport::execute_message(d, ch.request);
  ch.message = MessageState::Busy;
  ch.message_start = host()->now();
  ch.message_epoch = ch.link_epoch;
  ++ch.messages;
  // The drive has acted on the message; the answer lands in M1 once the link has carried it.
  host()->schedule_at(ch.message_start + t.duration, [this, c, response = t.response](VirtualTime now) mutable {
    Channel& chn = channel_(c);
    if (chn.message_epoch != chn.link_epoch) {
      // The connection was lost during the transaction: the reply never arrives and the module
      // times out (0xFE) as it would have without a device.
      const scanport::Transaction lost = scanport::execute_message(nullptr, chn.request);
      chn.message_epoch = chn.link_epoch;
      const VirtualTime due = chn.message_start + lost.duration;
      if (due > now) {
        host()->schedule_at(due, [this, c, r = lost.response](VirtualTime) { finish_message(c, r); });
        return;
      }
      response = lost.response;
    }
    finish_message(c, response);
  });
}

void Sm1Module::finish_message(int c, const scanport::Response& response) {
  Channel& ch = channel_(c);
  std::array<std::uint16_t, scanport::kBufferWords> buffer{};
  scanport::write_response(response, buffer);
  const int first = scanport::response_buffer_word(c);
  for (int k = 0; k < scanport::kBufferWords && first + k < static_cast<int>(m1_.size()); ++k)
    m1_[static_cast<std::size_t>(first) + static_cast<std::size_t>(k)] = buffer[static_cast<std::size_t>(k)];
  // DONE while ME is held; if the program cleared ME meanwhile the buffer is READY again.
  ch.message = ch.me ? MessageState::Done : MessageState::Ready;
}

// ---- Bench devices ---------------------------------------------------------------------------------------------

Sm1Module::Channel* Sm1Module::find_drive(std::string_view name) {
  for (auto& ch : channels_)
    if (ch.drive && ch.name == name) return &ch;
  return nullptr;
}

const Sm1Module::Channel* Sm1Module::find_drive(std::string_view name) const {
  for (const auto& ch : channels_)
    if (ch.drive && ch.name == name) return &ch;
  return nullptr;
}

std::vector<std::string> Sm1Module::device_names() const {
  std::vector<std::string> names;
  if (!module_name_.empty()) names.push_back(module_name_);
  for (const auto& ch : channels_)
    if (ch.drive) names.push_back(ch.name);
  return names;
}

DeviceStatus Sm1Module::inject(const DeviceFault& f) {
  Channel* ch = find_drive(f.device);
  if (!ch) {
    if (!module_name_.empty() && f.device == module_name_)
      return DeviceStatus::refused("the 1203-SM1 itself takes no changes; inject them into its drives");
    return {};
  }
  advance_drives();
  const std::string& w = f.fault;
  auto no_args = [&]() -> bool { return f.args.empty(); };
  if ((w == "offline" || w == "power off") && no_args()) {
    if (ch->powered) {
      // An unpowered device does not fault; it stops answering, and powers up from storage.
      ch->powered = false;
      ++ch->link_epoch;
    }
  } else if ((w == "online" || w == "power on") && no_args()) {
    if (!ch->powered) {
      ch->powered = true;
      ch->drive->power_cycle();
    }
  } else if (w == "cable removed" && no_args()) {
    if (ch->cable) {
      fault_if_enabled(*ch);
      ch->cable = false;
      ++ch->link_epoch;
    }
  } else if (w == "cable restored" && no_args()) {
    ch->cable = true;
  } else if (w == "message timeout" && no_args()) {
    ch->message_timeout = true;
  } else if (w == "normal" && no_args()) {
    ch->message_timeout = false;
    ch->cable = true;
    if (!ch->powered) {
      ch->powered = true;
      ch->drive->power_cycle();
    }
  } else if (w == "fault" && f.args.size() == 1) {
    auto code = integer_arg(f.args[0]);
    if (!code || *code < 0 || *code > 0xFFFF) return DeviceStatus::refused("fault CODE: expected a code 0-65535");
    ch->drive->fault(static_cast<std::uint16_t>(*code));
  } else if (w == "parameter" && f.args.size() == 2) {
    // A value set at the drive itself (a HIM), e.g. Data In A1 = 27 for a datalink.
    auto p = integer_arg(f.args[0]);
    auto v = integer_arg(f.args[1]);
    if (!p || !v) return DeviceStatus::refused("parameter NUMBER VALUE: expected two integers");
    if (!ch->drive->parameter(*p)) return DeviceStatus::refused("parameter " + f.args[0] + " does not exist");
    const auto e = ch->drive->write_value(*p, *v);
    if (e != scanport::ErrorCode::kNone)
      return DeviceStatus::refused("the drive refuses parameter " + f.args[0] + " = " + f.args[1] + " (SCANport error " +
                                   std::to_string(static_cast<int>(e)) + ")");
  } else {
    return DeviceStatus::refused("a SCANport drive takes: offline, online, power off, power on, cable removed, "
                                 "cable restored, message timeout, fault CODE, parameter NUMBER VALUE, normal");
  }
  return DeviceStatus::done();
}

std::optional<std::vector<std::int64_t>> Sm1Module::observe(std::string_view device, std::string_view what) const {
  if (!module_name_.empty() && device == module_name_) {
    if (what == "messages") {
      std::vector<std::int64_t> v;
      for (const auto& ch : channels_) v.push_back(static_cast<std::int64_t>(ch.messages));
      return v;
    }
    if (what == "dip switches") return std::vector<std::int64_t>{config_.dip_switch_word()};
    return std::nullopt;
  }
  const Channel* ch = find_drive(device);
  if (!ch) return std::nullopt;
  const scanport::Drive& d = *ch->drive;
  if (what == "command") return std::vector<std::int64_t>{d.logic_command()};
  if (what == "reference") return std::vector<std::int64_t>{d.reference()};
  if (what == "status") return std::vector<std::int64_t>{d.logic_status()};
  if (what == "feedback") return std::vector<std::int64_t>{d.feedback()};
  if (what == "running") return std::vector<std::int64_t>{d.running() ? 1 : 0};
  if (what == "faulted") return std::vector<std::int64_t>{d.faulted() ? 1 : 0};
  if (what == "datalink error") return std::vector<std::int64_t>{ch->datalink_error};
  if (what == "parameters") {
    // Element n is parameter n (element 0: the parameter count).
    std::vector<std::int64_t> v{d.parameter_count()};
    for (int n = 1; n <= d.parameter_count(); ++n) v.push_back(d.value(n));
    return v;
  }
  return std::nullopt;
}

std::optional<std::uint16_t> Sm1Module::field_output(int word) const {
  if (word < 0 || word >= static_cast<int>(last_outputs_.size())) return std::nullopt;
  return last_outputs_[static_cast<std::size_t>(word)];
}

}  // namespace softslc
