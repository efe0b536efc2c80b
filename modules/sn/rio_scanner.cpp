#include "modules/sn/rio_scanner.h"

#include <algorithm>
#include <limits>

#include "parser/loader.h"
#include "vm/duration.h"

namespace softslc {

namespace {

constexpr VirtualTime kNever = std::numeric_limits<VirtualTime>::max();
constexpr std::uint16_t kRetryMax = 0x7FFF;

int first_word_of(const RioModuleSpec& m) { return (m.rack % 8) * 8 + m.group; }

// The image bits of word `w` that a discrete module's value maps to (an 8-point module uses the
// byte of its slot, a 32-point module two words).
std::uint16_t word_from_module(const RioModuleSpec& m, std::uint32_t value, int w) {
  const int first = first_word_of(m);
  if (m.kind == RioModuleKind::BlockTransfer) return 0;
  if (m.points == 8) return w == first ? static_cast<std::uint16_t>((value & 0xFF) << (m.slot ? 8 : 0)) : 0;
  if (m.points == 16) return w == first ? static_cast<std::uint16_t>(value & 0xFFFF) : 0;
  if (w == first) return static_cast<std::uint16_t>(value & 0xFFFF);
  if (w == first + 1) return static_cast<std::uint16_t>(value >> 16);
  return 0;
}

// The inverse: the module bits that image word `w` (value `word`) drives.
std::uint32_t module_from_word(const RioModuleSpec& m, std::uint16_t word, int w) {
  const int first = first_word_of(m);
  if (m.kind == RioModuleKind::BlockTransfer) return 0;
  if (m.points == 8) return w == first ? static_cast<std::uint32_t>((word >> (m.slot ? 8 : 0)) & 0xFF) : 0;
  if (m.points == 16) return w == first ? word : 0;
  if (w == first) return word;
  if (w == first + 1) return static_cast<std::uint32_t>(word) << 16;
  return 0;
}

bool parse_int_arg(const std::string& t, std::int64_t& out) {
  NumberValue v;
  if (!parse_number_text(t, v) || v.is_float) return false;
  out = v.integer;
  return true;
}

std::string join_args(const std::vector<std::string>& a) {
  std::string s;
  for (const auto& x : a) s += (s.empty() ? "" : " ") + x;
  return s;
}

}  // namespace

bool RioScanner::Device::faulted() const {
  return std::any_of(failing.begin(), failing.end(), [](bool b) { return b; });
}

RioScanner::RioScanner(const SlotConfig& slot, int m0_words, int m1_words, std::shared_ptr<const RioScannerBench> bench)
    : Module(slot.slot, slot.catalog, slot.scan_in, slot.scan_out), bench_(std::move(bench)) {
  scan_in_ = std::clamp(slot.scan_in, 0, 32);
  scan_out_ = std::clamp(slot.scan_out, 0, 32);
  m0_.assign(static_cast<std::size_t>(std::max(m0_words, 0)), 0);
  m1_.assign(static_cast<std::size_t>(std::max(m1_words, 0)), 0);
  if (auto b = rio_baud_setting(slot.options)) {
    baud_ = static_cast<throughput::RioBaud>(b->kbaud_index);
    baud_word_ = b->m1_word2;
  }
  has_g_ = slot.has_g_file;
  if (has_g_) g_ = decode_rio_g_file(slot.g_file, g_findings_);
  if (bench_) {
    duplicate_ = bench_->duplicate_node;
    for (const auto& spec : bench_->adapters) {
      Adapter a;
      a.spec = spec;
      a.online = spec.online;
      a.answer_groups = spec.groups;
      a.noisy = spec.noisy;
      a.hold_last_state = spec.hold_last_state;
      const auto words = static_cast<std::size_t>(spec.groups);
      a.in_buffer.assign(words, 0);
      a.received.assign(words, 0);
      a.out_buffer.assign(words, 0);
      a.generic_in.assign(words, 0);
      a.generic_out.assign(words, 0);
      for (const auto& ms : spec.modules) {
        RemoteModule m;
        m.spec = ms;
        m.btr_data = ms.data;
        m.length = ms.length;
        m.write_length = ms.write_length;
        m.responding = ms.responding;
        m.failing = ms.failing;
        m.response_delay = ms.response_delay;
        m.ramps = ms.ramps;
        m.steps = ms.steps;
        if (ms.kind == RioModuleKind::Input) a.input_modules.push_back(static_cast<int>(a.modules.size()));
        a.modules.push_back(std::move(m));
      }
      adapters_.push_back(std::move(a));
    }
  }
  for (std::size_t ai = 0; ai < adapters_.size(); ++ai) {
    const auto& spec = adapters_[ai].spec;
    for (int o = 0; o < spec.groups; ++o) {
      const int w = spec.first_word() + o;
      if (w >= 0 && w < static_cast<int>(image_sources_.size()))
        image_sources_[static_cast<std::size_t>(w)].push_back({ai, static_cast<std::size_t>(o)});
    }
  }
  build_devices();
}

RioScanner::~RioScanner() = default;

// ---- Configuration ---------------------------------------------------------------------------------------

void RioScanner::build_devices() {
  const bool g_ok = has_g_ && std::none_of(g_findings_.begin(), g_findings_.end(), [](const auto& f) { return f.error; });
  if (!g_ok) return;
  for (const auto& gd : g_.devices) {
    Device d;
    d.g = gd;
    for (std::size_t i = 0; i < adapters_.size(); ++i) {
      const auto& s = adapters_[i].spec;
      if (s.complementary == gd.complementary && s.rack % 8 == gd.rack && s.group == gd.group) {
        d.adapter = static_cast<int>(i);
        break;
      }
    }
    // Split at logical rack boundaries: one logical device per rack the image touches.
    int w = gd.rack * 8 + gd.group, left = gd.groups, part = 0;
    while (left > 0) {
      const int n = std::min(left, 8 - w % 8);
      Logical l;
      l.device = static_cast<int>(devices_.size());
      l.part = part++;
      l.rack = w / 8;
      l.first_word = w;
      l.words = n;
      l.slot_time = microseconds(throughput::rio_scan_time(baud_, n));
      logical_.push_back(l);
      w += n;
      left -= n;
    }
    d.failing.assign(static_cast<std::size_t>(part), false);
    devices_.push_back(std::move(d));
  }
  // Logical devices in image order; at one location the primary chassis first.
  std::stable_sort(logical_.begin(), logical_.end(), [&](const Logical& a, const Logical& b) {
    const bool ca = devices_[static_cast<std::size_t>(a.device)].g.complementary;
    const bool cb = devices_[static_cast<std::size_t>(b.device)].g.complementary;
    return std::tie(a.first_word, ca) < std::tie(b.first_word, cb);
  });
  // T_SNo-bt for the configured logical racks (appendix A, "Determining the Number of Logical
  // Racks Configured": a primary rack and its complementary rack count once).
  std::array<bool, 4> racks{};
  for (const auto& l : logical_) racks[static_cast<std::size_t>(l.rack)] = true;
  const int n = static_cast<int>(std::count(racks.begin(), racks.end(), true));
  if (n > 0)
    tick_period_ = microseconds(throughput::t_sno_bt(
        g_.complementary_mode ? throughput::RioMode::complementary : throughput::RioMode::normal, baud_, n));
}

std::uint16_t& RioScanner::m1w(int word) {
  static thread_local std::uint16_t scratch;
  if (word < 0 || static_cast<std::size_t>(word) >= m1_.size()) {
    scratch = 0;
    return scratch;
  }
  return m1_[static_cast<std::size_t>(word)];
}

void RioScanner::write_config_status() {
  // Chapter 4, "M1 Status File Description": word 2 the DIP-switch baud rate, words 8/9 images of
  // G words 1/2, words 3/4 of G words 3/4.
  m1w(2) = baud_word_;
  m1w(3) = g_.words[3];
  m1w(4) = g_.words[4];
  m1w(8) = g_.words[1];
  m1w(9) = g_.words[2];
}

bool RioScanner::configuration_fault(Mode to) {
  const auto code = [&](std::uint16_t c) { return static_cast<std::uint16_t>((slot() << 8) | c); };
  const std::string where = catalog() + " in slot " + std::to_string(slot()) + ": ";
  if (!has_g_) {
    host()->raise_major_fault(code(0x62), where + "G file is missing (1747-SN ch. 6, error 62H) at " +
                                              std::string(to_string(to)) + " entry");
    return true;
  }
  for (const auto& f : g_findings_)
    if (f.error) {
      host()->raise_major_fault(code(0x63), where + "invalid G file configuration (1747-SN ch. 6, error 63H): " + f.message);
      return true;
    }
  if (duplicate_) {
    host()->raise_major_fault(code(0x64), where + "duplicate node detected: another scanner on the RIO link (1747-SN ch. 6, "
                                                  "error 64H)");
    return true;
  }
  return false;
}

void RioScanner::set_m0_defaults() {
  // "Upon entering Run or Test modes, the SLC processor sets the M0 file to a default state":
  // device inhibit set for every starting group with no configured device, remote output reset
  // set for every configured device, device reset clear (chapter 4). Complementary devices use
  // the bit of their starting location (control functions are selected through the primary).
  std::fill(m0_.begin(), m0_.end(), 0);
  std::array<std::uint16_t, 4> starts{};
  for (const auto& d : devices_) starts[static_cast<std::size_t>(d.g.bit / 4)] |= static_cast<std::uint16_t>(1u << (d.g.bit % 4));
  for (int r = 0; r < 4; ++r) {
    const auto i = static_cast<std::size_t>(r);
    if (8 + i < m0_.size()) m0_[8 + i] = static_cast<std::uint16_t>(~starts[i] & 0x000F);
    if (24 + i < m0_.size()) m0_[24 + i] = starts[i];
  }
  for (auto& b : bt_) b.en_written = b.to_written = false;
}

std::uint16_t RioScanner::control(int first_word, int rack) const {
  const int w = first_word + rack;
  if (pending_mode_) {
    const int idx = first_word == 8 ? rack : first_word == 16 ? 4 + rack : 8 + rack;
    return held_control_[static_cast<std::size_t>(idx)];
  }
  return w >= 0 && static_cast<std::size_t>(w) < m0_.size() ? m0_[static_cast<std::size_t>(w)] : 0;
}

bool RioScanner::inhibited(const Device& d) const {
  return (control(8, d.g.bit / 4) >> (d.g.bit % 4)) & 1u;
}

RioScanner::Command RioScanner::command_for(const Device& d) const {
  const bool dr = (control(16, d.g.bit / 4) >> (d.g.bit % 4)) & 1u;
  const bool ror = (control(24, d.g.bit / 4) >> (d.g.bit % 4)) & 1u;
  // Chapter 4 mode table: in Run, DR = 1 turns the outputs off, else they follow the image; in
  // Program, Test or Fault, DR = 1 or ROR = 1 resets them, DR = ROR = 0 lets the device's hold
  // last state switch decide.
  if (effective_mode_ == Mode::Run) return dr ? Command::Reset : Command::Run;
  return dr || ror ? Command::Reset : Command::Decide;
}

// ---- Module interface ------------------------------------------------------------------------------------

void RioScanner::attach(ModuleHost& host) {
  Module::attach(host);
  // The adapters' chassis run from power-up, whatever the scanner does.
  backplane_groups_.clear();
  for (std::size_t i = 0; i < adapters_.size(); ++i) {
    const Nanoseconds period = adapters_[i].spec.backplane_scan;
    if (period <= 0) continue;
    const auto g = std::find_if(backplane_groups_.begin(), backplane_groups_.end(),
                                [&](const BackplaneGroup& bg) { return bg.period == period; });
    if (g != backplane_groups_.end()) g->adapters.push_back(static_cast<int>(i));
    else backplane_groups_.push_back({period, {static_cast<int>(i)}});
  }
  for (std::size_t g = 0; g < backplane_groups_.size(); ++g)
    schedule_backplanes(static_cast<int>(g), host.now() + backplane_groups_[g].period);
}

void RioScanner::input_scan(std::span<std::uint16_t> image) {
  // The words the link keeps, as many as SCAN_IN takes; zeros past them. One copy: the runtime also
  // asks for the image after every event between repeated scans.
  const std::size_t n = std::min({image.size(), in_image_.size(), static_cast<std::size_t>(std::max(scan_in_, 0))});
  std::copy_n(in_image_.begin(), n, image.begin());
  std::fill(image.begin() + static_cast<std::ptrdiff_t>(n), image.end(), std::uint16_t{0});
}

void RioScanner::output_scan(std::span<const std::uint16_t> image) {
  const std::size_t n = std::min({image.size(), out_image_.size(), static_cast<std::size_t>(std::max(scan_out_, 0))});
  std::copy_n(image.begin(), n, out_image_.begin());
  std::fill(out_image_.begin() + static_cast<std::ptrdiff_t>(n), out_image_.end(), std::uint16_t{0});
  // The end of the first full scan in a new Run/Test mode: the M0 settings take effect and the
  // outputs are updated ("The outputs of the RIO are updated after the end of the first SLC
  // processor scan").
  if (pending_mode_ && host() && host()->mode() == *pending_mode_) {
    effective_mode_ = *pending_mode_;
    pending_mode_.reset();
  }
}

int RioScanner::m_file_words(MFile f) const { return static_cast<int>((f == MFile::M0 ? m0_ : m1_).size()); }

MAccess RioScanner::read_m(MFile f, int word, std::uint16_t& value) {
  const auto& file = f == MFile::M0 ? m0_ : m1_;
  if (word < 0 || static_cast<std::size_t>(word) >= file.size()) return MAccess::NoSuchWord;
  value = file[static_cast<std::size_t>(word)];
  return MAccess::Ok;
}

// read_m for each word, at once: both files are plain words.
MAccess RioScanner::read_m_block(MFile f, int word, std::span<std::uint16_t> out, std::size_t& done) {
  const auto& file = f == MFile::M0 ? m0_ : m1_;
  done = 0;
  if (word < 0 || static_cast<std::size_t>(word) >= file.size()) return out.empty() ? MAccess::Ok : MAccess::NoSuchWord;
  done = std::min(out.size(), file.size() - static_cast<std::size_t>(word));
  std::copy_n(file.begin() + word, done, out.begin());
  return done == out.size() ? MAccess::Ok : MAccess::NoSuchWord;
}

MAccess RioScanner::write_m(MFile f, int word, std::uint16_t value) {
  auto& file = f == MFile::M0 ? m0_ : m1_;
  if (word < 0 || static_cast<std::size_t>(word) >= file.size()) return MAccess::NoSuchWord;
  // "M1 is a read only file; do not write to this file" (chapter 4; appendix B: the M1 file is a
  // module input file, read only to the processor).
  if (f == MFile::M1) return MAccess::Forbidden;
  // m_write_changes_nothing's test, made here once: the word changes, or a control word's EN or TO
  // differs from those noted last (note_control_write notes them).
  std::uint16_t& w = file[static_cast<std::size_t>(word)];
  bool changes = w != value;
  w = value;
  if (const int x = rio::buffer_at(word)) changes = note_control_write(x, value) || changes;
  if (changes) ++program_changes_;
  return MAccess::Ok;
}

// See the header: the word holds the value, and a control word's EN and TO are those noted last.
bool RioScanner::m_write_changes_nothing(MFile f, int word, std::uint16_t value) const {
  if (f != MFile::M0 || word < 0 || static_cast<std::size_t>(word) >= m0_.size()) return false;
  if (m0_[static_cast<std::size_t>(word)] != value) return false;
  if (const int x = rio::buffer_at(word)) {
    const Buffer& b = bt_[static_cast<std::size_t>(x)];
    if (((value & rio::kEN) != 0) != b.en_written || ((value & rio::kTO) != 0) != b.to_written) return false;
  }
  return true;
}

void RioScanner::on_mode_change(Mode from, Mode to) {
  if (to == Mode::Run || to == Mode::Test) {
    if (configuration_fault(to)) return;
    // Retry counters: cleared "when going from Program to Run mode, Test to Run mode, and when
    // going from Program to Test mode".
    if (to == Mode::Run || from == Mode::Program)
      for (int w = 16; w <= 47; ++w) m1w(w) = 0;
    // Communications attempted: no transitions "until a processor change of state occurs (i.e.,
    // Program mode to Run mode or Test mode, or Test mode to Run mode)".
    m1w(0) = 0;
    for (auto& d : devices_) d.attempted = false;
    for (int r = 0; r < 4; ++r) {
      held_control_[static_cast<std::size_t>(r)] = control(8, r);
      held_control_[4 + static_cast<std::size_t>(r)] = control(16, r);
      held_control_[8 + static_cast<std::size_t>(r)] = control(24, r);
    }
    cancel_all();
    pending_mode_ = to;
    set_m0_defaults();
    write_config_status();
    if (!link_running_) start_link();
    update_status();
    return;
  }
  // Program or Fault: "When the processor changes to Program mode, all pending block transfers
  // are cancelled." The link keeps running with the outputs reset or held (chapter 3, "When
  // Changing From Run Mode").
  if (from == Mode::Run || from == Mode::Test) cancel_all();
  pending_mode_.reset();
  effective_mode_ = to;
}

// See the header: the image scans are copies, the rest is events; not while a new mode waits for
// its first scan. A block transfer in progress is passive too (decision, issue 20, session 16):
// everything it does later is an event already on the queue (a note or a finished transfer has
// its service tick scheduled, request_tick; a Waiting buffer moves when the one before it ends; an
// Active one at the link's visits and its BT timer), and the program sees it only through M1,
// which the runtime reads again after the events between repeats, and through the M0 control
// word, whose EN/TO edges count as changes (program_changes).
bool RioScanner::passive() const { return !pending_mode_; }

void RioScanner::execute(ModuleInstructionContext& ctx) {
  if (ctx.opcode() == Opcode::BTR || ctx.opcode() == Opcode::BTW) {
    rio::execute_block_transfer(ctx);
    return;
  }
  Module::execute(ctx);
}

// ---- The RIO link --------------------------------------------------------------------------------------

void RioScanner::start_link() {
  link_running_ = true;
  cursor_ = 0;
  rio_scan_start_ = host()->now();
  tick_origin_ = host()->now();
  schedule_next(host()->now());
}

RioScanner::Reply RioScanner::reply_of(const Device& d) const {
  if (!cable_ok_ || d.adapter < 0) return Reply::NoReply;
  const Adapter& a = adapters_[static_cast<std::size_t>(d.adapter)];
  if (!a.online || !a.cable) return Reply::NoReply;
  // "configured to an incorrect logical rack size", or a primary-mode chassis while the scanner
  // is not in complementary mode ("the system will flag the device as faulted").
  if (a.answer_groups != d.g.groups) return Reply::WrongSize;
  if (a.spec.primary_switch && !g_.complementary_mode) return Reply::WrongSize;
  return Reply::Ok;
}

void RioScanner::schedule_next(VirtualTime t) {
  const std::size_t n = logical_.size();
  const auto idle = [&] {
    host()->schedule_at(t + microseconds(throughput::rio_scan_time(baud_, 2)),
                        [this](VirtualTime te) { schedule_next(te); });
  };
  if (n == 0) return idle();
  for (std::size_t step = 0; step <= n; ++step) {
    if (cursor_ >= n) {
      // A RIO scan ended: every logical device had its turn.
      last_rio_scan_ = t - rio_scan_start_;
      rio_scan_start_ = t;
      ++rio_scans_;
      cursor_ = 0;
      rack_bt_used_.fill(false);
    }
    const Logical& l = logical_[cursor_];
    Device& d = devices_[static_cast<std::size_t>(l.device)];
    if (inhibited(d)) {
      ++cursor_;
      continue;
    }
    Visit v;
    v.logical = static_cast<int>(cursor_);
    v.reply = reply_of(d);
    Nanoseconds dur = l.slot_time;
    const auto retry = [&] {
      dur += l.slot_time;
      std::uint16_t& c = m1w((d.g.complementary ? 32 : 16) + d.g.bit);
      if (c < kRetryMax) ++c;
    };
    if (v.reply == Reply::Ok) {
      Adapter& a = adapters_[static_cast<std::size_t>(d.adapter)];
      ++a.transfers;
      if (a.noisy > 0 && a.transfers % static_cast<std::uint64_t>(a.noisy) == 0) retry();
    } else if (v.reply == Reply::NoReply && !d.failing[static_cast<std::size_t>(l.part)]) {
      retry();  // one retry before the device is declared faulted
    }
    // Block transfers of this logical rack: one at a time, data at most once per RIO scan.
    auto& q = rack_queue_[static_cast<std::size_t>(l.rack)];
    if (!q.empty()) {
      const int x = q.front();
      Buffer& b = bt_[static_cast<std::size_t>(x)];
      if (b.state == BtState::Active && !b.result_ready && b.logical == static_cast<int>(cursor_)) {
        if (b.phase == BtPhase::Request) {
          v.bt_request = x;
        } else if (b.phase == BtPhase::Awaiting && b.ready_at <= t && v.reply == Reply::Ok &&
                   !rack_bt_used_[static_cast<std::size_t>(l.rack)]) {
          const RemoteModule& m = adapters_[static_cast<std::size_t>(b.adapter)].modules[static_cast<std::size_t>(b.module)];
          if (m.responding) {
            const int words = b.requested > 0 ? b.requested : b.read ? m.length : rio::kMaxWords;
            v.bt_data = x;
            rack_bt_used_[static_cast<std::size_t>(l.rack)] = true;
            dur += microseconds(throughput::t_ri(baud_, std::clamp(words, 1, rio::kMaxWords)));
          }
        }
      }
    }
    // One visit is in flight at a time, so it waits in visit_ and the event captures only `this`
    // (a std::function holds that without allocating).
    visit_ = v;
    host()->schedule_at(t + dur, [this](VirtualTime te) {
      const Visit done = visit_;
      end_visit(done, te);
    });
    return;
  }
  idle();  // every device is inhibited
}

void RioScanner::end_visit(const Visit& v, VirtualTime t) {
  const Logical& l = logical_[static_cast<std::size_t>(v.logical)];
  Device& d = devices_[static_cast<std::size_t>(l.device)];
  const bool was_attempted = d.attempted;
  const bool was_failing = d.failing[static_cast<std::size_t>(l.part)];
  d.attempted = true;
  if (v.reply == Reply::Ok) {
    exchange(l, d, adapters_[static_cast<std::size_t>(d.adapter)], t);
    d.failing[static_cast<std::size_t>(l.part)] = false;
  } else {
    d.failing[static_cast<std::size_t>(l.part)] = true;
  }
  if (v.bt_request) bt_visit_end(v.bt_request, v, t);
  if (v.bt_data) bt_visit_end(v.bt_data, v, t);
  // update_status is a function of the devices' attempted and failing flags and the inhibit words
  // in effect, and gives the same words again for the same ones: it runs when one of them moved.
  if (d.attempted != was_attempted || d.failing[static_cast<std::size_t>(l.part)] != was_failing ||
      inhibit_words() != status_inhibit_)
    update_status();
  cursor_ = static_cast<std::size_t>(v.logical) + 1;
  schedule_next(t);
}

std::uint32_t RioScanner::module_inputs(const RemoteModule& m) const { return m.seen_in; }

std::uint16_t RioScanner::adapter_input_word(const Adapter& a, int w) const {
  const int idx = w - a.spec.first_word();
  if (a.modules.empty()) return a.generic_in[static_cast<std::size_t>(idx)];
  std::uint16_t v = 0;
  for (int mi : a.input_modules) {
    const RemoteModule& m = a.modules[static_cast<std::size_t>(mi)];
    v = static_cast<std::uint16_t>(v | word_from_module(m.spec, module_inputs(m), w));
  }
  return v;
}

void RioScanner::exchange(const Logical& l, Device& d, Adapter& a, VirtualTime t) {
  const std::size_t ai = static_cast<std::size_t>(d.adapter);
  // A watchdog that expires now expired before this visit's end (arm_watchdog).
  if (a.watchdog_due == t) watchdog_expires(static_cast<int>(ai), t);
  const Command c = command_for(d);
  for (int w = l.first_word; w < l.first_word + l.words; ++w) {
    const auto idx = static_cast<std::size_t>(w - a.spec.first_word());
    const std::uint16_t before = a.out_buffer[idx];
    switch (c) {
      case Command::Run: a.out_buffer[idx] = out_image_[static_cast<std::size_t>(w)]; break;
      case Command::Reset: a.out_buffer[idx] = 0; break;
      case Command::Decide:
        if (!a.hold_last_state) a.out_buffer[idx] = 0;
        break;
    }
    if (a.out_buffer[idx] != before) a.outputs_stale = true;
    // The adapter answers with its input buffer (its chassis inputs as of its last backplane
    // scan, or now when it has no backplane delay).
    a.received[idx] = a.spec.backplane_scan > 0 ? a.in_buffer[idx] : adapter_input_word(a, w);
    // Primary and complementary images overlap in the scanner: the word is the OR of both.
    std::uint16_t word = 0;
    for (const ImageSource& src : image_sources_[static_cast<std::size_t>(w)])
      word = static_cast<std::uint16_t>(word | adapters_[src.adapter].received[src.index]);
    in_image_[static_cast<std::size_t>(w)] = word;
  }
  a.last_comm = t;
  arm_watchdog(static_cast<int>(ai), t);
  if (a.spec.backplane_scan <= 0) apply_outputs(a, t);
}

// The watchdog expires comm_timeout after the adapter's last exchange. Every visit re-arms it, and
// cancelling and scheduling an event at each visit was a tenth of the simulation's time, so one
// event stands for it: it is scheduled when the watchdog is armed with none pending, and when it
// runs before the (since moved) expiry it moves itself there (watchdog_event). The watchdog then
// expires at the same time as an event armed at each visit would, and in the same order among
// the events of that time that it does not commute with: those that read or write the adapter's
// output buffer. An event armed at the last exchange would run before every visit ending at the
// expiry (each was scheduled after that exchange) and before the adapter's backplane scan there
// when that was scheduled after the arm; exchange() and backplane() let it expire first in
// those cases, and the moved event then finds nothing to do. Every other event touches neither
// the output buffer nor what the expiry reads, so its order against them does not matter.
void RioScanner::arm_watchdog(int ai, VirtualTime t) {
  Adapter& a = adapters_[static_cast<std::size_t>(ai)];
  a.watchdog_due = t + a.spec.comm_timeout;
  a.watchdog_armed = ++order_;
  if (a.watchdog_event_at >= 0) return;  // it moves itself to the new expiry
  a.watchdog_event_at = a.watchdog_due;
  host()->schedule_at(a.watchdog_due, [this, ai](VirtualTime te) { watchdog_event(ai, te); });
}

void RioScanner::watchdog_event(int ai, VirtualTime t) {
  Adapter& a = adapters_[static_cast<std::size_t>(ai)];
  a.watchdog_event_at = -1;
  if (a.watchdog_due < 0) return;  // expired already, at the start of a visit or backplane scan
  if (a.watchdog_due > t) {
    a.watchdog_event_at = a.watchdog_due;
    host()->schedule_at(a.watchdog_due, [this, ai](VirtualTime te) { watchdog_event(ai, te); });
    return;
  }
  watchdog_expires(ai, t);
}

void RioScanner::watchdog_expires(int ai, VirtualTime t) {
  Adapter& a = adapters_[static_cast<std::size_t>(ai)];
  a.watchdog_due = -1;
  // No valid transfer for the adapter's time-out: "Inhibited devices eventually time out and
  // either return to their last state or reset (depending on the device's last state setting)".
  if (!a.hold_last_state) {
    std::fill(a.out_buffer.begin(), a.out_buffer.end(), 0);
    a.outputs_stale = true;
  }
  if (a.spec.backplane_scan <= 0) apply_outputs(a, t);
}

// One event for the backplane scans of a group of adapters with the same backplane_scan, in place
// of one event per adapter (issue 20: they were two thirds of a busy scanner's events). The group's
// adapters were scheduled together at attach, so their per-adapter events would all fall at the
// same times, each scheduled right after the one before it: nothing else could run between them
// but the output-delay events the scans themselves scheduled (apply_outputs), which write only
// out_field and out_changed_at, which no backplane scan reads. Every other event at the same time
// was scheduled before the first of them or after the last, as it is before or after the group's
// event, so every event runs in the same order against each adapter's scan. Each adapter's
// backplane_scheduled still counts in order_ where its own event would have been scheduled
// against the watchdog arms (none can come between), which is all that order is used for.
void RioScanner::schedule_backplanes(int g, VirtualTime at) {
  for (int ai : backplane_groups_[static_cast<std::size_t>(g)].adapters)
    adapters_[static_cast<std::size_t>(ai)].backplane_scheduled = ++order_;
  host()->schedule_at(at, [this, g](VirtualTime te) { backplanes(g, te); });
}

void RioScanner::backplanes(int g, VirtualTime t) {
  const BackplaneGroup& group = backplane_groups_[static_cast<std::size_t>(g)];
  for (int ai : group.adapters) backplane(ai, t);
  schedule_backplanes(g, t + group.period);
}

void RioScanner::backplane(int ai, VirtualTime t) {
  Adapter& a = adapters_[static_cast<std::size_t>(ai)];
  // A watchdog armed before this scan was scheduled and expiring now expired first (arm_watchdog).
  if (a.watchdog_due == t && a.watchdog_armed < a.backplane_scheduled) watchdog_expires(ai, t);
  // The input buffer is a function of the input modules' seen_in (generic_in without modules):
  // when none changed since the last scan, it holds what the scan would copy.
  if (a.inputs_changed) {
    a.inputs_changed = false;
    if (a.modules.empty()) {
      std::copy(a.generic_in.begin(), a.generic_in.end(), a.in_buffer.begin());
    } else {
      // adapter_input_word for every word at once: each input module gives only its one or two
      // words, so the others are zero.
      std::fill(a.in_buffer.begin(), a.in_buffer.end(), std::uint16_t{0});
      for (int mi : a.input_modules) {
        const RemoteModule& m = a.modules[static_cast<std::size_t>(mi)];
        for (int w = first_word_of(m.spec); w <= first_word_of(m.spec) + 1; ++w) {
          const int k = w - a.spec.first_word();
          if (k < 0 || k >= a.spec.groups) continue;
          auto& word = a.in_buffer[static_cast<std::size_t>(k)];
          word = static_cast<std::uint16_t>(word | word_from_module(m.spec, module_inputs(m), w));
        }
      }
    }
  }
  apply_outputs(a, t);
}

void RioScanner::apply_outputs(Adapter& a, VirtualTime t) {
  // An output buffer that has not changed since the last call gives every module the target it
  // has: nothing to do.
  if (!a.outputs_stale) return;
  a.outputs_stale = false;
  a.generic_out = a.out_buffer;
  const auto ai = static_cast<std::size_t>(&a - adapters_.data());
  for (std::size_t mi = 0; mi < a.modules.size(); ++mi) {
    RemoteModule& m = a.modules[mi];
    if (m.spec.kind != RioModuleKind::Output) continue;
    std::uint32_t target = 0;
    for (int k = 0; k < a.spec.groups; ++k)
      target |= module_from_word(m.spec, a.out_buffer[static_cast<std::size_t>(k)], a.spec.first_word() + k);
    if (target == m.out_target) continue;
    m.out_target = target;
    if (m.spec.output_delay <= 0) {
      m.out_field = target;
      m.out_changed_at = t;
      continue;
    }
    host()->schedule_at(t + m.spec.output_delay, [this, ai, mi, target](VirtualTime te) {
      RemoteModule& mm = adapters_[ai].modules[mi];
      if (mm.out_field != target) {
        mm.out_field = target;
        mm.out_changed_at = te;
      }
    });
  }
}

void RioScanner::set_module_input(int ai, int mi, std::uint32_t value, std::uint32_t mask) {
  RemoteModule& m = adapters_[static_cast<std::size_t>(ai)].modules[static_cast<std::size_t>(mi)];
  m.field_in = (m.field_in & ~mask) | (value & mask);
  const std::uint32_t now_value = m.field_in;
  if (m.spec.input_delay <= 0 || !host()) {
    m.seen_in = now_value;
    adapters_[static_cast<std::size_t>(ai)].inputs_changed = true;
    return;
  }
  host()->schedule_at(host()->now() + m.spec.input_delay, [this, ai, mi, now_value](VirtualTime) {
    Adapter& a = adapters_[static_cast<std::size_t>(ai)];
    a.modules[static_cast<std::size_t>(mi)].seen_in = now_value;
    a.inputs_changed = true;
  });
}

std::array<std::uint16_t, 4> RioScanner::inhibit_words() const {
  return {control(8, 0), control(8, 1), control(8, 2), control(8, 3)};
}

void RioScanner::update_status() {
  status_inhibit_ = inhibit_words();
  std::uint16_t w0 = static_cast<std::uint16_t>(m1w(0) & 0x0002);
  bool all_attempted = !devices_.empty();
  bool any_fault = false;
  std::uint16_t active_primary = 0, active_comp = 0;
  std::array<std::uint16_t, 4> fault_bits{};
  for (const auto& d : devices_) {
    const bool inh = inhibited(d);
    if (!inh && !d.attempted) all_attempted = false;
    if (d.faulted()) {
      if (!inh) any_fault = true;
      for (int q = d.g.first_quarter(); q < d.g.end_quarter() && q < 16; ++q)
        fault_bits[static_cast<std::size_t>(q / 4)] |= static_cast<std::uint16_t>(1u << (q % 4 + (d.g.complementary ? 4 : 0)));
    } else if (!inh && d.attempted) {
      (d.g.complementary ? active_comp : active_primary) |= static_cast<std::uint16_t>(1u << d.g.bit);
    }
  }
  // "When RIO communication has been attempted with all configured devices, this bit is set to 1.
  // There are no further transitions of this bit until a processor change of state occurs."
  if (all_attempted) w0 |= 0x0002;
  if (any_fault) w0 |= 0x0001;
  m1w(0) = w0;
  // "Until this bit is set, all devices in M1 file word 10 (active device status) appear to be
  // inactive."
  const bool attempted = w0 & 0x0002;
  m1w(10) = attempted ? active_primary : 0;
  m1w(5) = attempted ? active_comp : 0;
  for (int r = 0; r < 4; ++r) m1w(12 + r) = fault_bits[static_cast<std::size_t>(r)];
}

// ---- Block transfers ---------------------------------------------------------------------------------

bool RioScanner::note_control_write(int x, std::uint16_t value) {
  Buffer& b = bt_[static_cast<std::size_t>(x)];
  const bool en = value & rio::kEN, to = value & rio::kTO;
  if (en == b.en_written && to == b.to_written) return false;
  b.en_written = en;
  b.to_written = to;
  if (!link_running_) return true;
  notes_.push_back({x, en, to});
  request_tick();
  return true;
}

void RioScanner::request_tick() {
  if (next_tick_ >= 0 || !host()) return;
  const VirtualTime now = host()->now();
  const Nanoseconds p = tick_period_;
  const VirtualTime k = now <= tick_origin_ ? 0 : (now - tick_origin_ + p - 1) / p;
  VirtualTime t = tick_origin_ + k * p;
  if (t <= last_tick_) t = last_tick_ + p;
  next_tick_ = t;
  host()->schedule_at(t, [this](VirtualTime te) { tick(te); });
}

void RioScanner::tick(VirtualTime t) {
  next_tick_ = -1;
  last_tick_ = t;
  // One enable (or time-out request) per T_SNo-bt, in the order the program made them; the
  // disables that precede nothing else of their buffer are taken at once (see apply_note).
  // `kept` and the ready list are members that keep their storage: a tick runs at every enable,
  // disable and finished transfer.
  std::deque<Note>& kept = kept_notes_;
  kept.clear();
  std::array<bool, rio::kBufferCount + 1> blocked{};  // buffers with an earlier note still waiting
  bool slot_used = false;
  for (const Note& n : notes_) {
    Buffer& b = bt_[static_cast<std::size_t>(n.buffer)];
    if (blocked[static_cast<std::size_t>(n.buffer)]) {
      kept.push_back(n);
      continue;
    }
    const bool is_disable = !n.en && b.en_seen;
    const bool is_change = is_disable || (n.en && !b.en_seen) || (n.en && n.to && !b.to_seen);
    if (!is_change) {
      apply_note(n);  // nothing to do but remember TO
      continue;
    }
    if (is_disable || !slot_used) {
      apply_note(n);
      if (!is_disable) slot_used = true;
      continue;
    }
    kept.push_back(n);
    blocked[static_cast<std::size_t>(n.buffer)] = true;
  }
  notes_.swap(kept);
  // Finished transfers are posted to M1 (one T_SNo-bt "to handle the BT response").
  std::vector<int>& ready = posting_;
  ready.clear();
  ready.swap(ready_);
  for (int x : ready) post(x);
  if (!notes_.empty() || !ready_.empty()) request_tick();
}

bool RioScanner::apply_note(const Note& n) {
  Buffer& b = bt_[static_cast<std::size_t>(n.buffer)];
  if (n.en && !b.en_seen) {
    b.en_seen = true;
    b.to_seen = n.to;
    // "The RIO scanner ignores a block transfer request if both TO and EN bits are set at the
    // same time."
    if (!n.to) enable(n.buffer);
    return true;
  }
  if (!n.en && b.en_seen) {
    b.en_seen = false;
    b.to_seen = n.to;
    disable(n.buffer);
    return true;
  }
  if (n.en && n.to && !b.to_seen) {
    b.to_seen = true;
    // TO "cancel[s] block transfer operation by forcing the BT to time out once the Enabled
    // Waiting (EW) bit sets": ER and -9.
    if ((b.state == BtState::Waiting || b.state == BtState::Active) && !b.result_ready)
      finish(n.buffer, false, rio::kErrTimeout);
    return true;
  }
  b.to_seen = n.to;
  return false;
}

void RioScanner::enable(int x) {
  Buffer& b = bt_[static_cast<std::size_t>(x)];
  const int base = x * rio::kBufferStride;
  const auto m0 = [&](int k) -> std::uint16_t {
    return static_cast<std::size_t>(base) + static_cast<std::size_t>(k) < m0_.size() ? m0_[static_cast<std::size_t>(base) + static_cast<std::size_t>(k)] : 0;
  };
  const std::uint16_t ctl = m0(rio::kControlWord);
  const auto requested = static_cast<std::int16_t>(m0(rio::kRequestedCount));
  b = Buffer{};
  b.en_seen = true;
  b.en_written = true;
  b.to_written = (ctl & rio::kTO) != 0;
  b.read = ctl & rio::kRW;
  b.rack = rio::rack_of(ctl);
  b.group = rio::group_of(ctl);
  b.slot = rio::slot_of(ctl);
  b.requested = requested;
  const std::uint16_t echo = static_cast<std::uint16_t>(rio::kEN | (ctl & (rio::kRW | rio::kTO | rio::kAddressBits)));
  m1w(base + rio::kRequestedCount) = static_cast<std::uint16_t>(requested);
  m1w(base + rio::kTransmittedCount) = 0;
  m1w(base + rio::kErrorCode) = 0;

  std::int16_t code = 0;
  if (requested < 0 || requested > rio::kMaxWords) {
    code = rio::kErrIllegalLength;
  } else if (b.rack > 3) {
    code = rio::kErrNoChannel;  // decision: the scanner's one RIO channel has logical racks 0-3
  } else {
    const int q = b.rack * 4 + b.group / 2;
    const int word = b.rack * 8 + b.group;
    const Device* primary = nullptr;
    const Device* comp = nullptr;
    for (const auto& d : devices_) {
      if (!d.g.covers_quarter(q)) continue;
      (d.g.complementary ? comp : primary) = &d;
    }
    if (!primary) {
      // Not configured, or a complementary location without primary image space (-11).
      code = rio::kErrNotConfigured;
    } else if (inhibited(*primary)) {
      code = rio::kErrInhibited;
    } else {
      const auto locate = [&](const Device* d) {
        const int di = static_cast<int>(d - devices_.data());
        for (std::size_t li = 0; li < logical_.size(); ++li)
          if (logical_[li].device == di && word >= logical_[li].first_word &&
              word < logical_[li].first_word + logical_[li].words)
            b.logical = static_cast<int>(li);
        b.adapter = d->adapter;
        b.module = -1;
        if (d->adapter < 0) return;
        const Adapter& a = adapters_[static_cast<std::size_t>(d->adapter)];
        for (std::size_t mi = 0; mi < a.modules.size(); ++mi) {
          const auto& s = a.modules[mi].spec;
          if (s.kind == RioModuleKind::BlockTransfer && first_word_of(s) == word && s.slot == b.slot)
            b.module = static_cast<int>(mi);
        }
      };
      locate(primary);
      // The block-transfer module may sit in the complementary chassis at the same location.
      if (b.module < 0 && comp && comp->g.bit == primary->g.bit) {
        const Buffer saved = b;
        locate(comp);
        if (b.module < 0) {
          b.logical = saved.logical;
          b.adapter = saved.adapter;
          b.module = -1;
        }
      }
    }
  }
  if (code) {
    b.state = BtState::Error;
    m1w(base) = static_cast<std::uint16_t>(echo | rio::kER);
    m1w(base + rio::kErrorCode) = static_cast<std::uint16_t>(code);
    return;
  }
  b.state = BtState::Waiting;
  m1w(base) = static_cast<std::uint16_t>(echo | rio::kEW);
  auto& q = rack_queue_[static_cast<std::size_t>(b.rack)];
  q.push_back(x);
  if (q.front() == x) start(x);
}

void RioScanner::start(int x) {
  Buffer& b = bt_[static_cast<std::size_t>(x)];
  const int base = x * rio::kBufferStride;
  b.state = BtState::Active;
  b.phase = BtPhase::Request;
  m1w(base) = static_cast<std::uint16_t>(m1w(base) | rio::kST);
  // The four-second BT timer runs from the moment the transfer is scheduled on the link.
  b.timer = host()->schedule_at(host()->now() + rio::kBtTimer, [this, x](VirtualTime) {
    Buffer& bb = bt_[static_cast<std::size_t>(x)];
    bb.timer = 0;
    if (bb.state == BtState::Active && !bb.result_ready) finish(x, false, rio::kErrTimeout);
  });
}

void RioScanner::finish(int x, bool ok, std::int16_t code, std::vector<std::uint16_t> data, int count) {
  Buffer& b = bt_[static_cast<std::size_t>(x)];
  if (b.timer) {
    host()->cancel_event(b.timer);
    b.timer = 0;
  }
  b.phase = BtPhase::None;
  b.result_ready = true;
  b.result_ok = ok;
  b.result_code = code;
  b.result_data = std::move(data);
  b.result_count = count;
  ready_.push_back(x);
  request_tick();
}

void RioScanner::post(int x) {
  Buffer& b = bt_[static_cast<std::size_t>(x)];
  if (!b.result_ready) return;
  b.result_ready = false;
  const int base = x * rio::kBufferStride;
  if (b.result_ok) {
    for (std::size_t k = 0; k < b.result_data.size(); ++k) m1w(base + rio::kDataOffset + static_cast<int>(k)) = b.result_data[k];
    m1w(base + rio::kTransmittedCount) = static_cast<std::uint16_t>(b.result_count);
    m1w(base + rio::kErrorCode) = 0;
    m1w(base) = static_cast<std::uint16_t>(m1w(base) | rio::kDN);
    b.state = BtState::Done;
  } else {
    m1w(base + rio::kTransmittedCount) = 0;
    m1w(base + rio::kErrorCode) = static_cast<std::uint16_t>(b.result_code);
    m1w(base) = static_cast<std::uint16_t>(m1w(base) | rio::kER);
    b.state = BtState::Error;
  }
  auto& q = rack_queue_[static_cast<std::size_t>(b.rack)];
  q.erase(std::remove(q.begin(), q.end(), x), q.end());
  if (!q.empty() && bt_[static_cast<std::size_t>(q.front())].state == BtState::Waiting) start(q.front());
}

void RioScanner::disable(int x) {
  Buffer& b = bt_[static_cast<std::size_t>(x)];
  if (b.timer) host()->cancel_event(b.timer);
  const int rack = b.rack;
  const bool en_written = b.en_written, to_written = b.to_written;
  const bool queued = b.state == BtState::Waiting || b.state == BtState::Active;
  b = Buffer{};
  b.en_written = en_written;
  b.to_written = to_written;
  b.to_seen = to_written;
  ready_.erase(std::remove(ready_.begin(), ready_.end(), x), ready_.end());
  // "When the RIO scanner detects that the EN bit cleared, it then clears the EW, ST and DN or ER
  // bits, as well as the Transmitted Word Count/Error Code."
  const int base = x * rio::kBufferStride;
  for (int k = 0; k <= rio::kErrorCode; ++k) m1w(base + k) = 0;
  if (queued) {
    auto& q = rack_queue_[static_cast<std::size_t>(rack)];
    q.erase(std::remove(q.begin(), q.end(), x), q.end());
    if (!q.empty() && bt_[static_cast<std::size_t>(q.front())].state == BtState::Waiting) start(q.front());
  }
}

void RioScanner::cancel_all() {
  for (int x = 1; x <= rio::kBufferCount; ++x) {
    Buffer& b = bt_[static_cast<std::size_t>(x)];
    if (b.timer && host()) host()->cancel_event(b.timer);
    const bool en_written = b.en_written, to_written = b.to_written;
    b = Buffer{};
    b.en_written = en_written;
    b.to_written = to_written;
    const int base = x * rio::kBufferStride;
    for (int k = 0; k <= rio::kErrorCode; ++k) m1w(base + k) = 0;
  }
  notes_.clear();
  ready_.clear();
  for (auto& q : rack_queue_) q.clear();
}

std::vector<std::int16_t> RioScanner::btr_source(RemoteModule& m, VirtualTime t) const {
  std::vector<std::int16_t> data = m.btr_data;
  for (const auto& s : m.steps)
    if (s.at <= t) data = s.data;
  for (const auto& r : m.ramps) {
    const std::int64_t n = t >= m.ramp_origin ? (t - m.ramp_origin) / r.every : 0;
    if (static_cast<std::size_t>(r.word) >= data.size()) data.resize(static_cast<std::size_t>(r.word) + 1, 0);
    data[static_cast<std::size_t>(r.word)] = static_cast<std::int16_t>(static_cast<std::uint16_t>(r.from + r.step * n));
  }
  return data;
}

void RioScanner::bt_visit_end(int x, const Visit& v, VirtualTime t) {
  Buffer& b = bt_[static_cast<std::size_t>(x)];
  if (b.state != BtState::Active || b.result_ready) return;
  if (v.bt_request == x) {
    // Step 1 on the link: the request goes out with the discrete transfer; a device that does
    // not answer makes it a communication error when the request was initiated (-7).
    if (v.reply != Reply::Ok) return finish(x, false, rio::kErrCommunication);
    b.phase = BtPhase::Awaiting;
    const Adapter& a = adapters_[static_cast<std::size_t>(b.adapter)];
    // No block-transfer module there (an output module, an empty slot) or one that does not
    // answer: nothing comes back and the BT timer ends it with -9.
    if (b.module < 0 || !a.modules[static_cast<std::size_t>(b.module)].responding) {
      b.ready_at = kNever;
      return;
    }
    b.ready_at = t + a.spec.bt_delay + a.modules[static_cast<std::size_t>(b.module)].response_delay;
    return;
  }
  // The data phase.
  RemoteModule& m = adapters_[static_cast<std::size_t>(b.adapter)].modules[static_cast<std::size_t>(b.module)];
  if (m.failing) return finish(x, false, rio::kErrProtocol);
  if (b.read) {
    const int count = b.requested > 0 ? b.requested : m.length;
    // "This number should match the requested word count ... If these numbers do not match, the
    // processor sets the ER bit": a module that answers another length is a protocol error.
    if (b.requested > 0 && b.requested != m.length) return finish(x, false, rio::kErrProtocol);
    std::vector<std::int16_t> src = btr_source(m, t);
    std::vector<std::uint16_t> data(static_cast<std::size_t>(count), 0);
    for (int k = 0; k < count && static_cast<std::size_t>(k) < src.size(); ++k)
      data[static_cast<std::size_t>(k)] = static_cast<std::uint16_t>(src[static_cast<std::size_t>(k)]);
    ++m.btr_count;
    return finish(x, true, 0, std::move(data), count);
  }
  const int count = b.requested > 0 ? b.requested : rio::kMaxWords;
  if (b.requested > 0 && b.requested != m.write_length) return finish(x, false, rio::kErrProtocol);
  m.last_btw.assign(static_cast<std::size_t>(count), 0);
  const int base = x * rio::kBufferStride + rio::kDataOffset;
  for (int k = 0; k < count; ++k)
    if (static_cast<std::size_t>(base) + static_cast<std::size_t>(k) < m0_.size())
      m.last_btw[static_cast<std::size_t>(k)] = static_cast<std::int16_t>(m0_[static_cast<std::size_t>(base) + static_cast<std::size_t>(k)]);
  ++m.btw_count;
  finish(x, true, 0, {}, count);
}

// ---- Field access, devices by name -----------------------------------------------------------------

bool RioScanner::set_field_input(int word, std::uint16_t value, std::uint16_t mask) {
  if (word < 0 || word >= 32) return false;
  bool handled = false;
  for (std::size_t ai = 0; ai < adapters_.size(); ++ai) {
    Adapter& a = adapters_[ai];
    const int idx = word - a.spec.first_word();
    if (idx < 0 || idx >= a.spec.groups) continue;
    if (a.modules.empty()) {
      auto& g = a.generic_in[static_cast<std::size_t>(idx)];
      g = static_cast<std::uint16_t>((g & ~mask) | (value & mask));
      a.inputs_changed = true;
      handled = true;
      continue;
    }
    for (std::size_t mi = 0; mi < a.modules.size(); ++mi) {
      const auto& s = a.modules[mi].spec;
      if (s.kind != RioModuleKind::Input) continue;
      const std::uint16_t bits = static_cast<std::uint16_t>(word_from_module(s, 0xFFFFFFFFu, word) & mask);
      if (!bits) continue;
      set_module_input(static_cast<int>(ai), static_cast<int>(mi), module_from_word(s, value, word),
                       module_from_word(s, bits, word));
      handled = true;
    }
  }
  return handled;
}

std::optional<std::uint16_t> RioScanner::field_input(int word) const {
  if (word < 0 || word >= 32) return std::nullopt;
  std::uint16_t v = 0;
  for (const auto& a : adapters_) {
    const int idx = word - a.spec.first_word();
    if (idx < 0 || idx >= a.spec.groups) continue;
    if (a.modules.empty()) v = static_cast<std::uint16_t>(v | a.generic_in[static_cast<std::size_t>(idx)]);
    for (const auto& m : a.modules)
      if (m.spec.kind == RioModuleKind::Input) v = static_cast<std::uint16_t>(v | word_from_module(m.spec, m.field_in, word));
  }
  return v;
}

std::optional<std::uint16_t> RioScanner::field_output(int word) const {
  if (word < 0 || word >= 32) return std::nullopt;
  std::uint16_t v = 0;
  for (const auto& a : adapters_) {
    const int idx = word - a.spec.first_word();
    if (idx < 0 || idx >= a.spec.groups) continue;
    if (a.modules.empty()) v = static_cast<std::uint16_t>(v | a.generic_out[static_cast<std::size_t>(idx)]);
    for (const auto& m : a.modules)
      if (m.spec.kind == RioModuleKind::Output) v = static_cast<std::uint16_t>(v | word_from_module(m.spec, m.out_field, word));
  }
  return v;
}

RioScanner::Adapter* RioScanner::find_adapter(std::string_view name) {
  for (auto& a : adapters_)
    if (!name.empty() && a.spec.name == name) return &a;
  return nullptr;
}

const RioScanner::Adapter* RioScanner::find_adapter(std::string_view name) const {
  for (const auto& a : adapters_)
    if (!name.empty() && a.spec.name == name) return &a;
  return nullptr;
}

std::pair<int, int> RioScanner::find_module(std::string_view name) const {
  for (std::size_t ai = 0; ai < adapters_.size(); ++ai)
    for (std::size_t mi = 0; mi < adapters_[ai].modules.size(); ++mi)
      if (!name.empty() && adapters_[ai].modules[mi].spec.name == name) return {static_cast<int>(ai), static_cast<int>(mi)};
  return {-1, -1};
}

VirtualTime RioScanner::output_changed_at(std::string_view module) const {
  auto [ai, mi] = find_module(module);
  if (ai < 0) return -1;
  return adapters_[static_cast<std::size_t>(ai)].modules[static_cast<std::size_t>(mi)].out_changed_at;
}

std::vector<std::string> RioScanner::device_names() const {
  std::vector<std::string> out;
  if (bench_ && !bench_->name.empty()) out.push_back(bench_->name);
  for (const auto& a : adapters_) {
    out.push_back(a.spec.name);
    for (const auto& m : a.modules)
      if (!m.spec.name.empty()) out.push_back(m.spec.name);
  }
  return out;
}

DeviceStatus RioScanner::inject(const DeviceFault& f) {
  const auto& args = f.args;
  const auto one_int = [&](std::int64_t lo, std::int64_t hi, std::int64_t& v) {
    return args.size() == 1 && parse_int_arg(args[0], v) && v >= lo && v <= hi;
  };
  // The scanner itself.
  if (bench_ && !bench_->name.empty() && f.device == bench_->name) {
    if (f.fault == "cable removed") cable_ok_ = false;
    else if (f.fault == "cable restored") cable_ok_ = true;
    else if (f.fault == "duplicate node") {
      duplicate_ = true;
      if (link_running_ && host() && (host()->mode() == Mode::Run || host()->mode() == Mode::Test))
        host()->raise_major_fault(static_cast<std::uint16_t>((slot() << 8) | 0x64),
                                  catalog() + " in slot " + std::to_string(slot()) +
                                      ": duplicate node detected: another scanner on the RIO link (1747-SN ch. 6, error 64H)");
    } else if (f.fault == "normal") {
      cable_ok_ = true;
      duplicate_ = false;
    } else {
      return DeviceStatus::refused("the scanner accepts 'cable removed', 'cable restored', 'duplicate node' and 'normal', not '" +
                                   f.fault + "'");
    }
    return DeviceStatus::done();
  }
  if (Adapter* a = find_adapter(f.device)) {
    std::int64_t v = 0;
    if (f.fault == "offline") a->online = false;
    else if (f.fault == "online") a->online = true;
    else if (f.fault == "cable removed") a->cable = false;
    else if (f.fault == "cable restored") a->cable = true;
    else if (f.fault == "data size" && one_int(1, 32, v)) a->answer_groups = static_cast<int>(v);
    else if (f.fault == "noisy" && args.size() == 1 && args[0] == "off") a->noisy = 0;
    else if (f.fault == "noisy" && one_int(0, 1000000, v)) a->noisy = static_cast<int>(v);
    else if (f.fault == "hold last state" && args.size() == 1 && (args[0] == "on" || args[0] == "off"))
      a->hold_last_state = args[0] == "on";
    else if (f.fault == "normal") {
      a->online = a->spec.online;
      a->cable = true;
      a->answer_groups = a->spec.groups;
      a->noisy = a->spec.noisy;
      a->hold_last_state = a->spec.hold_last_state;
    } else {
      return DeviceStatus::refused(
          "an adapter accepts 'offline', 'online', 'cable removed', 'cable restored', 'data size N' (groups, 1-32), "
          "'noisy N' (every N-th transfer is retried; 'noisy off'), 'hold last state on|off' and 'normal', not '" +
          f.fault + (args.empty() ? "" : " " + join_args(args)) + "'");
    }
    return DeviceStatus::done();
  }
  auto [ai, mi] = find_module(f.device);
  if (ai < 0) return {};
  RemoteModule& m = adapters_[static_cast<std::size_t>(ai)].modules[static_cast<std::size_t>(mi)];
  std::int64_t v = 0;
  if (m.spec.kind == RioModuleKind::BlockTransfer) {
    if (f.fault == "message timeout" || f.fault == "not responding") m.responding = false;
    else if (f.fault == "responding") m.responding = true;
    else if (f.fault == "bt error") m.failing = true;
    else if (f.fault == "data size" && one_int(1, 64, v)) m.length = m.write_length = static_cast<int>(v);
    else if (f.fault == "response delay" && args.size() == 1) {
      std::string err;
      auto d = parse_duration(args[0], &err);
      if (!d) return DeviceStatus::refused("response delay: " + err);
      m.response_delay = *d;
    } else if (f.fault == "bt data" && !args.empty() && args.size() <= 64) {
      std::vector<std::int16_t> data;
      for (const auto& s : args) {
        if (!parse_int_arg(s, v) || v < -32768 || v > 65535) return DeviceStatus::refused("bt data: '" + s + "' is not a 16-bit word");
        data.push_back(static_cast<std::int16_t>(v));
      }
      m.btr_data = std::move(data);
      m.steps.clear();
      m.ramps.clear();
    } else if (f.fault == "bt ramp" && args.size() == 4) {
      RioBtRamp r;
      std::int64_t w = 0, from = 0, step = 0;
      std::string err;
      auto every = parse_duration(args[3], &err);
      if (!parse_int_arg(args[0], w) || w < 0 || w > 63 || !parse_int_arg(args[1], from) || !parse_int_arg(args[2], step) ||
          !every || *every <= 0)
        return DeviceStatus::refused("bt ramp takes WORD(0-63) FROM STEP EVERY(time)");
      r.word = static_cast<int>(w);
      r.from = from;
      r.step = step;
      r.every = *every;
      m.ramps.push_back(r);
      m.ramp_origin = host() ? host()->now() : 0;
    } else if (f.fault == "normal") {
      m.responding = m.spec.responding;
      m.failing = m.spec.failing;
      m.length = m.spec.length;
      m.write_length = m.spec.write_length;
      m.response_delay = m.spec.response_delay;
      m.btr_data = m.spec.data;
      m.steps = m.spec.steps;
      m.ramps = m.spec.ramps;
      m.ramp_origin = 0;
    } else {
      return DeviceStatus::refused(
          "a block-transfer module accepts 'message timeout' (or 'not responding'), 'responding', 'bt error', 'data "
          "size N', 'response delay T', 'bt data V...', 'bt ramp WORD FROM STEP EVERY' and 'normal', not '" +
          f.fault + "'");
    }
    return DeviceStatus::done();
  }
  if (f.fault == "input" && m.spec.kind == RioModuleKind::Input && !args.empty() && args.size() <= 2) {
    std::int64_t value = 0, mask = 0xFFFFFFFF;
    if (!parse_int_arg(args[0], value) || (args.size() == 2 && !parse_int_arg(args[1], mask)))
      return DeviceStatus::refused("input takes VALUE [MASK]");
    const std::uint32_t points = m.spec.points >= 32 ? 0xFFFFFFFFu : (1u << m.spec.points) - 1;
    set_module_input(ai, mi, static_cast<std::uint32_t>(value), static_cast<std::uint32_t>(mask) & points);
    return DeviceStatus::done();
  }
  if (f.fault == "normal") return DeviceStatus::done();
  return DeviceStatus::refused(std::string(m.spec.kind == RioModuleKind::Input ? "an input module accepts 'input VALUE [MASK]' and"
                                                                               : "an output module accepts only") +
                               " 'normal', not '" + f.fault + "'");
}

std::optional<std::vector<std::int64_t>> RioScanner::observe(std::string_view device, std::string_view what) const {
  if (bench_ && !bench_->name.empty() && device == bench_->name) {
    if (what == "rio scan time") return std::vector<std::int64_t>{last_rio_scan_};
    if (what == "rio scans") return std::vector<std::int64_t>{static_cast<std::int64_t>(rio_scans_)};
    return std::nullopt;
  }
  if (const Adapter* a = find_adapter(device)) {
    std::vector<std::int64_t> out;
    const auto di = std::find_if(devices_.begin(), devices_.end(),
                                 [&](const Device& d) { return d.adapter == static_cast<int>(a - adapters_.data()); });
    if (what == "outputs") for (auto w : a->generic_out) out.push_back(w);
    else if (what == "inputs") for (auto w : a->received) out.push_back(w);
    else if (what == "faulted") out.push_back(di != devices_.end() && di->faulted() ? 1 : 0);
    else if (what == "retries") {
      if (di == devices_.end()) return std::nullopt;
      const std::size_t w = static_cast<std::size_t>(di->g.complementary ? 32 : 16) + static_cast<std::size_t>(di->g.bit);
      out.push_back(w < m1_.size() ? m1_[w] : 0);
    } else return std::nullopt;
    return out;
  }
  auto [ai, mi] = find_module(device);
  if (ai < 0) return std::nullopt;
  const RemoteModule& m = adapters_[static_cast<std::size_t>(ai)].modules[static_cast<std::size_t>(mi)];
  if (what == "inputs") return std::vector<std::int64_t>{m.field_in};
  if (what == "outputs") return std::vector<std::int64_t>{m.out_field};
  if (what == "output changed at") return std::vector<std::int64_t>{m.out_changed_at};
  if (what == "btw data") return std::vector<std::int64_t>(m.last_btw.begin(), m.last_btw.end());
  if (what == "btw count") return std::vector<std::int64_t>{m.btw_count};
  if (what == "btr count") return std::vector<std::int64_t>{m.btr_count};
  return std::nullopt;
}

}  // namespace softslc
