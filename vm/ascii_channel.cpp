#include "vm/ascii_channel.h"

#include <algorithm>

#include "vm/ascii.h"
#include "vm/data_table.h"

namespace softslc {

class AsciiChannel::Line final : public SerialLine {
 public:
  explicit Line(AsciiChannel& c) : c_(c) {}
  VirtualTime now() const override { return c_.host_->now(); }
  EventQueue::EventId schedule_at(VirtualTime at, EventQueue::Callback cb) override {
    return c_.host_->schedule_at(std::max(at, c_.host_->now()), std::move(cb));
  }
  const SerialConfig& config() const override { return c_.config_; }
  bool transmit(std::string_view chars) override {
    if (c_.in_flight_.size() + chars.size() > kMaxInFlight) return false;
    c_.device_chars(chars);
    return true;
  }
  void set_inputs(bool cts, bool dsr, bool dcd) override {
    c_.cts_ = cts;
    c_.dsr_ = dsr;
    c_.dcd_ = dcd;
  }

 private:
  AsciiChannel& c_;
};

AsciiChannel::AsciiChannel(SerialConfig config, std::unique_ptr<SerialDevice> device)
    : config_(std::move(config)), device_(std::move(device)) {}

AsciiChannel::~AsciiChannel() = default;

void AsciiChannel::attach(FieldProcessHost& host) {
  host_ = &host;
  line_ = std::make_unique<Line>(*this);
  device_->attach(*line_);
}

Nanoseconds AsciiChannel::character_time(std::uint64_t k) const {
  // k characters of bits_per_character() bits at `baud` bits per second, rounded down to the ns.
  return static_cast<Nanoseconds>(k * static_cast<std::uint64_t>(config_.bits_per_character()) * 1'000'000'000ULL /
                                  static_cast<std::uint64_t>(config_.baud));
}

std::uint16_t AsciiChannel::word(std::uint32_t i) const { return host_->read_word(i); }
void AsciiChannel::set_word(std::uint32_t i, std::uint16_t v) { host_->write_word(i, v); }

std::uint16_t AsciiChannel::channel_status() const {
  // RM 10-14, table 10.7: bit 0 CTS, 1 RTS, 2 DSR, 3 DCD, 4 DTR.
  return static_cast<std::uint16_t>((cts_ ? 1 : 0) | (rts_ ? 2 : 0) | (dsr_ ? 4 : 0) | (dcd_ ? 8 : 0) | (dtr_ ? 16 : 0));
}

void AsciiChannel::complete(std::uint32_t control, std::uint16_t set_bits, std::uint8_t code, std::int64_t pos) {
  std::uint16_t w0 = word(control);
  w0 = static_cast<std::uint16_t>((w0 & ~(bits::kEU | bits::kIN | 0x00FF)) | set_bits | code);
  set_word(control, w0);
  if (pos >= 0) set_word(control + 2, static_cast<std::uint16_t>(pos));
}

void AsciiChannel::fail(const Request& r, std::uint8_t code) { complete(r.control, bits::kER, code, -1); }

bool AsciiChannel::submit(const Request& r) {
  if (queue_.size() >= kQueueSize) return false;
  set_word(r.control, static_cast<std::uint16_t>(word(r.control) | bits::kEU));
  queue_.push_back(Job{r, {}, 0});
  if (queue_.size() == 1) run_head(r.at);
  return true;
}

// Runs the queue's head, and every following instruction that finishes at once, at time `at`.
void AsciiChannel::run_head(VirtualTime at) {
  while (!queue_.empty() && !head_running_) {
    Job& j = queue_.front();
    const Request r = j.r;
    // UL "is only examined when the instruction is ready to start executing" (1763-RM001 p. 314).
    if (word(r.control) & bits::kUL) {
      fail(r, ascii_error::kUnloaded);
      queue_.pop_front();
      continue;
    }
    set_word(r.control, static_cast<std::uint16_t>(word(r.control) | bits::kIN));
    switch (r.op) {
      case Opcode::ACB: {
        const auto n = static_cast<std::int64_t>(rx_.size());
        complete(r.control, static_cast<std::uint16_t>(bits::kDN | (n > 0 ? bits::kFD : 0)), 0, n);
        break;
      }
      case Opcode::ABL: {
        // RM 10-6: the characters up to and including the termination characters; 0 when absent.
        const auto n = static_cast<std::int64_t>(line_length(rx_.size()));
        complete(r.control, static_cast<std::uint16_t>(bits::kDN | (n > 0 ? bits::kFD : 0)), 0, n);
        break;
      }
      case Opcode::AHL: {
        // RM 10-13: a 1 in the AND mask resets the line, a 1 in the OR mask sets it (bit 0 DTR, 1 RTS).
        if (r.and_mask & 1) dtr_ = false;
        if (r.and_mask & 2) rts_ = false;
        if (r.or_mask & 1) dtr_ = true;
        if (r.or_mask & 2) rts_ = true;
        device_->outputs_changed(dtr_, rts_);
        complete(r.control, bits::kDN, 0, channel_status());
        break;
      }
      case Opcode::ARD:
      case Opcode::ARL:
        if (!finish_read(j, at)) {
          head_running_ = true;
          return;
        }
        break;
      case Opcode::AWA:
      case Opcode::AWT: {
        ascii::Text text;
        std::array<std::uint16_t, ascii::kElementWords> e{};
        for (std::uint32_t i = 0; i < ascii::kElementWords; ++i) e[i] = word(r.string + i);
        if (!ascii::read(e, text)) {
          fail(r, ascii_error::kLength);
          break;
        }
        // LEN (word 1): 0 sends the whole string; never more than the string holds (decision).
        const auto len = static_cast<std::int16_t>(word(r.control + 1));
        const int count = len <= 0 ? text.length : std::min<int>(len, text.length);
        j.out.assign(text.chars.begin(), text.chars.begin() + count);
        if (r.op == Opcode::AWA) j.out.insert(j.out.end(), config_.append.begin(), config_.append.end());
        set_word(r.control + 2, 0);
        if (j.out.empty()) {
          complete(r.control, bits::kDN, 0, 0);
          break;
        }
        head_running_ = true;
        tx_start_ = at;
        tx_event_ = host_->schedule_at(std::max(at + character_time(1), host_->now()), [this](VirtualTime t) { send_next(t); });
        return;
      }
      default: fail(r, ascii_error::kSystemMode); break;
    }
    queue_.pop_front();
  }
}

// The characters up to and including the first termination sequence among the first `limit`
// buffered, or 0 when it is not there.
std::size_t AsciiChannel::line_length(std::size_t limit) const {
  const std::string& t = config_.termination;
  if (t.empty()) return 0;
  for (std::size_t i = 0; i + t.size() <= limit; ++i)
    if (std::equal(t.begin(), t.end(), rx_.begin() + static_cast<std::ptrdiff_t>(i))) return i + t.size();
  return 0;
}

// A read is done once LEN characters (0 or more than 82: 82) are buffered, or, for ARL, once the
// termination characters have arrived within them; the characters then move to the string.
bool AsciiChannel::finish_read(Job& j, VirtualTime) {
  const Request& r = j.r;
  auto len = static_cast<std::int16_t>(word(r.control + 1));
  if (len <= 0 || len > ascii::kMaxLength) len = ascii::kMaxLength;
  const auto want = static_cast<std::size_t>(len);
  std::size_t n = r.op == Opcode::ARL ? line_length(std::min(rx_.size(), want)) : 0;
  if (n == 0) {
    if (rx_.size() < want) {
      set_word(r.control + 2, static_cast<std::uint16_t>(rx_.size()));  // "continuously updated"
      return false;
    }
    n = want;
  }
  ascii::Text text;
  text.length = static_cast<int>(n);
  for (std::size_t i = 0; i < n; ++i) text.chars[i] = rx_[i];
  rx_.erase(rx_.begin(), rx_.begin() + static_cast<std::ptrdiff_t>(n));
  std::array<std::uint16_t, ascii::kElementWords> e{};
  for (std::uint32_t i = 0; i < ascii::kElementWords; ++i) e[i] = word(r.string + i);
  ascii::write(e, text);
  for (std::uint32_t i = 0; i < ascii::kElementWords; ++i) set_word(r.string + i, e[i]);
  complete(r.control, bits::kDN, 0, static_cast<std::int64_t>(n));
  return true;
}

void AsciiChannel::send_next(VirtualTime at) {
  tx_event_.reset();
  if (queue_.empty() || !head_running_) return;
  Job& j = queue_.front();
  device_->receive(j.out[j.sent]);
  ++j.sent;
  set_word(j.r.control + 2, static_cast<std::uint16_t>(j.sent));
  const bool unloaded = (word(j.r.control) & bits::kUL) != 0;
  if (j.sent == j.out.size() || unloaded) {
    // UL mid-write: "any data already processed is sent" and the rest is not (RM 10-5).
    if (unloaded && j.sent < j.out.size())
      complete(j.r.control, bits::kER, ascii_error::kUnloaded, static_cast<std::int64_t>(j.sent));
    else
      complete(j.r.control, bits::kDN, 0, static_cast<std::int64_t>(j.sent));
    queue_.pop_front();
    head_running_ = false;
    run_head(at);
    return;
  }
  tx_event_ = host_->schedule_at(tx_start_ + character_time(j.sent + 1), [this](VirtualTime t) { send_next(t); });
}

void AsciiChannel::device_chars(std::string_view chars) {
  if (chars.empty()) return;
  const bool idle = in_flight_.empty();
  in_flight_.insert(in_flight_.end(), chars.begin(), chars.end());
  if (!idle) return;
  // The line is free once the last character sent has ended.
  rx_start_ = std::max(host_->now(), rx_start_ + character_time(rx_index_));
  rx_index_ = 0;
  rx_event_ = host_->schedule_at(rx_start_ + character_time(1), [this](VirtualTime t) { deliver_next(t); });
}

void AsciiChannel::deliver_next(VirtualTime at) {
  rx_event_.reset();
  if (in_flight_.empty()) return;
  const std::uint8_t c = in_flight_.front();
  in_flight_.pop_front();
  ++rx_index_;
  if (rx_.size() < kReceiveBuffer)
    rx_.push_back(c);
  else
    ++dropped_;
  if (!in_flight_.empty())
    rx_event_ = host_->schedule_at(rx_start_ + character_time(rx_index_ + 1), [this](VirtualTime t) { deliver_next(t); });
  if (head_running_ && !queue_.empty() && (queue_.front().r.op == Opcode::ARD || queue_.front().r.op == Opcode::ARL)) {
    if (finish_read(queue_.front(), at)) {
      queue_.pop_front();
      head_running_ = false;
      run_head(at);
    }
  }
}

void AsciiChannel::clear(bool transmit, bool receive, VirtualTime at) {
  if (receive) rx_.clear();
  auto matches = [&](Opcode op) {
    return (receive && (op == Opcode::ARD || op == Opcode::ARL)) || (transmit && (op == Opcode::AWA || op == Opcode::AWT));
  };
  bool head_removed = false;
  for (std::size_t i = 0; i < queue_.size();) {
    if (matches(queue_[i].r.op)) {
      if (i == 0) head_removed = true;
      // "ER = 1, RN = 0, EU = 0, and ERR = 0x0E" (1762-RM001C p. 20-8).
      fail(queue_[i].r, ascii_error::kCleared);
      queue_.erase(queue_.begin() + static_cast<std::ptrdiff_t>(i));
    } else {
      ++i;
    }
  }
  if (head_removed) {
    if (tx_event_) host_->cancel_event(*tx_event_);
    tx_event_.reset();
    head_running_ = false;
    run_head(at);
  }
}

void AsciiChannel::on_mode_change(Mode from, Mode to) {
  const bool was_running = from == Mode::Run || from == Mode::Test;
  const bool runs = to == Mode::Run || to == Mode::Test;
  if (!was_running || runs) return;
  for (const Job& j : queue_) fail(j.r, ascii_error::kModeChange);
  queue_.clear();
  if (tx_event_) host_->cancel_event(*tx_event_);
  tx_event_.reset();
  head_running_ = false;
}

}  // namespace softslc
