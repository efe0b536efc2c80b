#include "modules/serial/serial_device.h"

#include <deque>

#include "vm/duration.h"

namespace softslc {

namespace {

constexpr std::size_t kMaxLineChars = 256;
constexpr std::size_t kKeptLines = 64;
constexpr std::size_t kMaxText = 1024;  // a `send` or an `answer` (with its end of line)

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

class LineDevice final : public SerialDevice {
 public:
  explicit LineDevice(const SerialDeviceConfig& c) : c_(c) {}

  std::string name() const override { return c_.name; }
  void attach(SerialLine& line) override { line_ = &line; }

  void receive(std::uint8_t ch) override {
    if (ch == '\r' || ch == '\n') {
      // CR LF (or LF CR) ends one line, not two.
      if (pending_end_ && ch != last_end_) {
        pending_end_ = false;
        return;
      }
      end_line();
      pending_end_ = true;
      last_end_ = ch;
      return;
    }
    pending_end_ = false;
    if (current_.size() < kMaxLineChars) current_.push_back(static_cast<char>(ch));
  }

  void outputs_changed(bool dtr, bool rts) override {
    dtr_ = dtr;
    rts_ = rts;
  }

  DeviceStatus inject(const DeviceFault& f) override {
    if (f.device != c_.name) return {};
    std::string text;
    for (std::size_t i = 0; i < f.args.size(); ++i) text += (i ? " " : "") + f.args[i];
    if (f.fault == "send") {
      if (text.size() + c_.eol.size() > kMaxText) return DeviceStatus::refused("a line is at most 1024 characters");
      if (!transmit(text)) return DeviceStatus::refused("the line would pass the 1024 characters in flight to the processor");
      return DeviceStatus::done();
    }
    if (f.fault == "answer") {
      if (text.size() + c_.eol.size() > kMaxText) return DeviceStatus::refused("an answer is at most 1024 characters");
      c_.answer = text;
      return DeviceStatus::done();
    }
    if (f.fault == "silent") {
      c_.answer.clear();
      return DeviceStatus::done();
    }
    return DeviceStatus::refused("a serial device takes 'send TEXT', 'answer TEXT' or 'silent', not '" + f.fault + "'");
  }

  std::optional<std::vector<std::int64_t>> observe(std::string_view what) const override {
    auto one = [](std::int64_t v) { return std::vector<std::int64_t>{v}; };
    if (what == "lines") return one(static_cast<std::int64_t>(received_));
    if (what == "sent") return one(static_cast<std::int64_t>(sent_));
    if (what == "dtr") return one(dtr_ ? 1 : 0);
    if (what == "rts") return one(rts_ ? 1 : 0);
    if (what == "last line") {
      if (lines_.empty()) return std::vector<std::int64_t>{};
      std::vector<std::int64_t> v;
      for (char ch : lines_.back()) v.push_back(static_cast<unsigned char>(ch));
      return v;
    }
    if (what == "last number") {
      // Empty (unavailable to a test) until a line with a number has arrived.
      if (lines_.empty()) return std::vector<std::int64_t>{};
      const std::string& s = lines_.back();
      for (std::size_t i = 0; i < s.size(); ++i) {
        if (s[i] < '0' || s[i] > '9') continue;
        std::int64_t v = 0;
        std::size_t k = i;
        while (k < s.size() && s[k] >= '0' && s[k] <= '9' && v < 1'000'000'000'000LL) v = v * 10 + (s[k++] - '0');
        return one(i > 0 && s[i - 1] == '-' ? -v : v);
      }
      return std::vector<std::int64_t>{};
    }
    return std::nullopt;
  }

 private:
  bool transmit(const std::string& text) {
    if (!line_ || !line_->transmit(text + c_.eol)) return false;
    ++sent_;
    return true;
  }

  void end_line() {
    lines_.push_back(current_);
    if (lines_.size() > kKeptLines) lines_.pop_front();
    current_.clear();
    ++received_;
    if (c_.answer.empty() || !line_ || (!c_.request.empty() && lines_.back() != c_.request)) return;
    const std::string answer = c_.answer;
    line_->schedule_at(line_->now() + c_.answer_delay, [this, answer](VirtualTime) { transmit(answer); });
  }

  SerialDeviceConfig c_;
  SerialLine* line_ = nullptr;
  std::string current_;
  std::deque<std::string> lines_;
  std::uint64_t received_ = 0;
  std::uint64_t sent_ = 0;
  bool pending_end_ = false;
  std::uint8_t last_end_ = 0;
  bool dtr_ = true, rts_ = true;
};

}  // namespace

std::optional<std::string> parse_serial_characters(std::string_view s) {
  std::string out;
  if (s == "NONE" || s == "none") return out;
  for (std::size_t i = 0; i < s.size();) {
    if (s.substr(i, 2) == "CR") {
      out += '\r';
      i += 2;
    } else if (s.substr(i, 2) == "LF") {
      out += '\n';
      i += 2;
    } else if (s[i] == '\\' && i + 2 < s.size() + 0 && hex_digit(s[i + 1]) >= 0 && hex_digit(s[i + 2]) >= 0) {
      out += static_cast<char>(hex_digit(s[i + 1]) * 16 + hex_digit(s[i + 2]));
      i += 3;
    } else if (s[i] > ' ' && s[i] < 0x7F && s[i] != '\\') {
      out += s[i++];
    } else {
      return std::nullopt;
    }
    if (out.size() > 2) return std::nullopt;
  }
  return out;
}

std::optional<SerialDeviceConfig> read_serial_node(const BenchNode& node, DiagnosticList& diags) {
  BenchReader r(node, diags);
  SerialDeviceConfig c;
  c.name = node.name;
  if (node.name.empty()) r.error("a serial device needs a name (tests reach it by name): serial NAME baud=...");
  if (!node.children.empty()) r.error("a serial device has no child nodes");
  r.require("baud", "the channel's baud rate (110-38400, RSLogix 500 channel 0 configuration)");
  if (auto b = r.choice("baud", {"110", "300", "600", "1200", "2400", "4800", "9600", "19200", "38400"}))
    c.channel.baud = std::stoll(*b);
  if (auto d = r.choice("data_bits", {"7", "8"})) c.channel.data_bits = std::stoi(*d);
  if (auto p = r.choice("parity", {"none", "even", "odd"})) c.channel.parity = *p == "none" ? 'N' : *p == "even" ? 'E' : 'O';
  if (auto st = r.choice("stop_bits", {"1", "2"})) c.channel.stop_bits = std::stoi(*st);
  auto characters = [&](std::string_view key, std::string& out) {
    if (auto t = r.text(key)) {
      if (auto v = parse_serial_characters(*t); v && (key == "eol" || !v->empty()))
        out = *v;
      else
        r.error_at(key, std::string(key) + "=" + *t + ": expected 1 or 2 characters: CR, LF, CRLF, \\hh or printable");
    }
  };
  characters("termination", c.channel.termination);
  characters("append", c.channel.append);
  characters("eol", c.eol);
  if (auto a = r.text("answer")) {
    if (a->size() > kMaxText - 2)
      r.error_at("answer", "an answer is at most 1022 characters");
    else
      c.answer = *a;
  }
  if (auto q = r.text("request")) {
    if (q->size() > kMaxLineChars)
      r.error_at("request", "a request is at most 256 characters");
    else
      c.request = *q;
  }
  if (auto d = r.duration("answer_delay")) {
    if (*d < 0 || *d > 60'000'000'000LL)
      r.error_at("answer_delay", "answer_delay must be 0 to 60s");
    else
      c.answer_delay = *d;
  }
  r.finish();
  if (r.failed()) return std::nullopt;
  return c;
}

std::unique_ptr<AsciiChannel> make_serial_channel(const SerialDeviceConfig& config) {
  return std::make_unique<AsciiChannel>(config.channel, std::make_unique<LineDevice>(config));
}

}  // namespace softslc
