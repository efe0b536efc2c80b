#include "server/live.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <variant>

#include "parser/checker.h"
#include "parser/loader.h"
#include "vm/state_file.h"

namespace softslc::serve {

namespace {

constexpr const char* kReadOnly = "the server is read-only (--read-only)";

std::string hex32(std::uint32_t v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%08x", v);
  return buf;
}

std::string hex64(std::uint64_t v) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

std::uint32_t float_bits(double d) {
  const auto f = static_cast<float>(d);
  std::uint32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
  return bits;
}

}  // namespace

LiveController::LiveController(const std::filesystem::path& program, const std::optional<std::filesystem::path>& bench,
                               LiveOptions options)
    : controller_(Controller::load(program, bench)), options_(std::move(options)) {
  controller_.keep_journal(false);
  base_ = controller_.now();
  if (options_.journal) {
    journal_ = std::make_unique<std::ofstream>(*options_.journal, std::ios::trunc);
    if (!*journal_) throw ControllerError(options_.journal->string() + ": error: cannot write the journal");
    *journal_ << "softslc-journal 1\n"
              << "program " << std::filesystem::absolute(program).string() << ' '
              << hex64(program_fingerprint(controller_.program())) << '\n'
              << "bench " << (bench ? std::filesystem::absolute(*bench).string() : std::string("-")) << '\n';
    journal_->flush();
  }
}

LiveController::~LiveController() = default;

void LiveController::run_scans(int n) {
  // One scan at a time: Controller::scan(n) stops at a major fault, while a faulted processor's
  // scan(1) still passes virtual time. "scans N" in the journal is N calls of scan(1), which is
  // what replay() performs, so a session that faults (a divide by zero pressed from the online
  // view) replays to the same virtual times.
  for (int i = 0; i < n; ++i) controller_.scan(1);
  if (n > 0) pending_scans_ += static_cast<std::uint64_t>(n);
}

void LiveController::flush_scans() {
  if (journal_ && pending_scans_ > 0) *journal_ << "scans " << pending_scans_ << '\n';
  pending_scans_ = 0;
}

int LiveController::advance(Nanoseconds wall_elapsed) {
  if (options_.paused) return 0;
  // The target is computed from the start of pacing, not accumulated, so rounding never drifts.
  const auto target = base_ + static_cast<VirtualTime>(std::llround(static_cast<double>(wall_elapsed) * options_.speed));
  int ran = 0;
  // One scan at a time, so virtual time overshoots the target by less than one scan. (A faulted
  // processor's scans still pass virtual time, so the loop always ends.)
  while (controller_.now() < target && ran < kMaxScansPerAdvance) {
    run_scans(1);
    ++ran;
  }
  lag_ = controller_.now() < target ? target - controller_.now() : 0;
  max_lag_ = std::max(max_lag_, lag_);
  return ran;
}

int LiveController::step(int n) {
  run_scans(n);
  return n;
}

void LiveController::pause() { options_.paused = true; }

void LiveController::resume() {
  options_.paused = false;
  base_ = controller_.now();
}

void LiveController::finish() {
  flush_scans();
  if (journal_) {
    *journal_ << "end @" << controller_.now() << ' ' << hex32(controller_.data_digest()) << '\n';
    journal_->flush();
  }
}

eip::Identity LiveController::identity() const {
  eip::Identity id;
  const ProcessorModel& p = controller_.program().processor;
  id.product_name = p.catalog + "/" + std::string(1, p.series) + " (softslc)";
  // The product code is not in our sources for the SLC 5/05; 0 marks it unknown (docs/serve.md).
  id.product_code = 0;
  id.major = static_cast<std::uint8_t>(p.frn);
  id.minor = 0;
  // A fixed serial derived from the program, so one program always reports the same identity.
  id.serial = static_cast<std::uint32_t>(program_fingerprint(controller_.program()) & 0xFFFFFFFFu);
  return id;
}

std::optional<pccc::Target::File> LiveController::file(int number) const {
  auto info = controller_.file_info(number);
  if (!info) return std::nullopt;
  File f;
  f.type = info->type;
  f.elements = info->elements;
  f.words_per_element = info->words_per_element;
  return f;
}

void LiveController::read(int number, std::uint32_t offset, std::span<std::uint16_t> out) const {
  controller_.read_file_words(number, offset, out);
}

std::string LiveController::write(int number, std::uint32_t offset, std::span<const std::uint16_t> values,
                                  std::span<const std::uint16_t> masks) {
  if (options_.read_only) return kReadOnly;
  // A write refused half-way (a module refusing its word) has performed the calls before it: they
  // are journaled all the same, so the journal holds every change the data table saw.
  auto [calls, error] = controller_.write_file_words(number, offset, values, masks);
  journal_calls(calls);
  return error;
}

void LiveController::journal_calls(const std::vector<ControllerCall>& calls) {
  if (calls.empty()) return;
  flush_scans();
  const VirtualTime now = controller_.now();
  if (journal_) {
    for (const auto& c : calls) {
      switch (c.kind) {
        case ControllerCall::Kind::Set: *journal_ << "set @" << now << ' ' << c.target << ' ' << c.integer << '\n'; break;
        case ControllerCall::Kind::SetFloat:
          *journal_ << "setf @" << now << ' ' << c.target << ' ' << hex32(float_bits(c.real)) << '\n';
          break;
        case ControllerCall::Kind::SetWord:
          *journal_ << "setword @" << now << ' ' << c.target << ' ' << c.word << ' ' << c.integer << '\n';
          break;
        case ControllerCall::Kind::Force: *journal_ << "force @" << now << ' ' << c.target << ' ' << c.integer << '\n'; break;
        case ControllerCall::Kind::Unforce: *journal_ << "unforce @" << now << ' ' << c.target << '\n'; break;
        case ControllerCall::Kind::SetMode: *journal_ << "mode @" << now << ' ' << to_string(c.mode) << '\n'; break;
        case ControllerCall::Kind::ClearFault: *journal_ << "clearfault @" << now << '\n'; break;
        default: break;
      }
    }
    *journal_ << "digest @" << now << ' ' << hex32(controller_.data_digest()) << '\n';
    journal_->flush();
  }
  writes_ += calls.size();
}

// ---- Changes from the online view ----

namespace {

// A value as typed: a whole integer, or a real number.
std::optional<std::variant<std::int64_t, double>> parse_number(std::string_view text) {
  while (!text.empty() && text.front() == ' ') text.remove_prefix(1);
  while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
  if (text.empty() || text.size() > 40) return std::nullopt;
  std::int64_t i = 0;
  if (auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), i); ec == std::errc() && p == text.data() + text.size())
    return i;
  double d = 0.0;
  if (auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), d); ec == std::errc() &&
      p == text.data() + text.size() && std::isfinite(d))
    return d;
  return std::nullopt;
}

}  // namespace

std::string LiveController::resolved(std::string_view target) const {
  if (const Symbol* s = controller_.program().find_symbol(target); s && !s->name.empty()) return to_string(s->address);
  if (auto a = parse_address(target)) return to_string(*a);
  return std::string(target);
}

std::string LiveController::set_value(std::string_view target, std::string_view text) {
  if (options_.read_only) return kReadOnly;
  auto number = parse_number(text);
  if (!number) return "'" + std::string(text) + "' is not a number";
  ControllerCall c;
  c.target = resolved(target);
  try {
    if (const auto* i = std::get_if<std::int64_t>(&*number)) {
      c.kind = ControllerCall::Kind::Set;
      c.integer = *i;
      controller_.set(target, *i);
    } else {
      c.kind = ControllerCall::Kind::SetFloat;
      c.real = std::get<double>(*number);
      controller_.set_float(target, c.real);
    }
  } catch (const ControllerError& e) {
    return e.what();
  }
  journal_calls({c});
  return {};
}

std::string LiveController::force(std::string_view target, std::optional<bool> on) {
  if (options_.read_only) return kReadOnly;
  ControllerCall c;
  c.target = resolved(target);
  try {
    if (on) {
      c.kind = ControllerCall::Kind::Force;
      c.integer = *on ? 1 : 0;
      controller_.force(target, *on);
      forces_[c.target] = *on;
    } else {
      c.kind = ControllerCall::Kind::Unforce;
      controller_.unforce(target);
      forces_.erase(c.target);
    }
  } catch (const ControllerError& e) {
    return e.what();
  }
  journal_calls({c});
  return {};
}

std::string LiveController::set_mode(Mode mode) {
  if (options_.read_only) return kReadOnly;
  ControllerCall c;
  c.kind = ControllerCall::Kind::SetMode;
  c.mode = mode;
  try {
    controller_.set_mode(mode);
  } catch (const ControllerError& e) {
    return e.what();
  }
  journal_calls({c});
  return {};
}

std::string LiveController::clear_fault() {
  if (options_.read_only) return kReadOnly;
  ControllerCall c;
  c.kind = ControllerCall::Kind::ClearFault;
  controller_.clear_fault();
  journal_calls({c});
  return {};
}

namespace {

std::string m_address(int slot, bool m1, std::uint32_t word, int bit = -1) {
  return std::string(m1 ? "M1:" : "M0:") + std::to_string(slot) + "." + std::to_string(word) +
         (bit >= 0 ? "/" + std::to_string(bit) : std::string());
}

}  // namespace

std::optional<std::uint32_t> LiveController::module_file_words(int slot, bool m1) const {
  const SlotConfig* config = controller_.program().find_slot(slot);
  if (!config || !controller_.runtime().module(slot)) return std::nullopt;
  const int words = m1 ? m1_words(*config) : m0_words(*config);
  if (words <= 0) return std::nullopt;
  return static_cast<std::uint32_t>(words);
}

std::string LiveController::read_module(int slot, bool m1, std::uint32_t word, std::span<std::uint16_t> out) {
  for (std::size_t i = 0; i < out.size(); ++i) {
    try {
      out[i] = static_cast<std::uint16_t>(controller_.get(m_address(slot, m1, word + static_cast<std::uint32_t>(i))).as_int());
    } catch (const ControllerError& e) {
      return e.what();
    }
  }
  return {};
}

std::string LiveController::write_module(int slot, bool m1, std::uint32_t word, std::span<const std::uint16_t> values,
                                         std::span<const std::uint16_t> masks) {
  if (options_.read_only) return kReadOnly;
  // The same calls `run --set` makes: a whole word, or one bit at a time for a masked write.
  std::vector<ControllerCall> calls;
  std::string error;
  const auto perform = [&](std::string target, std::int64_t value) {
    ControllerCall c;
    c.kind = ControllerCall::Kind::Set;
    c.target = std::move(target);
    c.integer = value;
    try {
      controller_.perform(c);
    } catch (const ControllerError& e) {
      error = e.what();
      return false;
    }
    calls.push_back(std::move(c));
    return true;
  };
  for (std::size_t i = 0; i < values.size() && error.empty(); ++i) {
    const auto w = word + static_cast<std::uint32_t>(i);
    if (masks[i] == 0xFFFF) {
      perform(m_address(slot, m1, w), static_cast<std::int16_t>(values[i]));
      continue;
    }
    for (int b = 0; b < 16 && error.empty(); ++b)
      if ((masks[i] >> b) & 1u) perform(m_address(slot, m1, w, b), (values[i] >> b) & 1u);
  }
  journal_calls(calls);
  return error;
}

std::vector<std::uint8_t> LiveController::diagnostic_status() const {
  // The DF1 manual's diagnostic status block (1770-6.5.16 chapter 10): mode/status byte, the
  // interface/processor type, extended types, series/revision, then the bulletin name in ASCII.
  // The SLC-specific byte values are not in our sources: softslc sends the mode bits of S:1 and
  // EEh (extended interface, extended processor), and the catalog number as the name, so a
  // client that shows "processor type" shows the program's processor (docs/serve.md).
  std::vector<std::uint8_t> b(24, 0);
  const ProcessorModel& p = controller_.program().processor;
  std::uint16_t s1 = 0;
  controller_.read_file_words(2, 1, std::span<std::uint16_t>(&s1, 1));
  b[0] = static_cast<std::uint8_t>(s1 & 0x1F);
  b[1] = 0xEE;
  b[4] = static_cast<std::uint8_t>(((p.series - 'A') & 0x7) << 5 | (p.frn & 0x1F));
  for (std::size_t i = 0; i < 11; ++i) b[5 + i] = i < p.catalog.size() ? static_cast<std::uint8_t>(p.catalog[i]) : ' ';
  return b;
}

// ---- Replay ----

ReplayResult replay(const std::filesystem::path& journal) {
  ReplayResult r;
  std::ifstream in(journal);
  if (!in) {
    r.message = journal.string() + ": error: cannot open the journal";
    return r;
  }
  std::string line;
  int line_no = 0;
  const auto fail = [&](const std::string& why) {
    r.ok = false;
    r.message = journal.string() + ":" + std::to_string(line_no) + ": " + why;
    return std::move(r);
  };
  std::string program, bench, fingerprint;
  while (std::getline(in, line)) {
    ++line_no;
    std::istringstream ls(line);
    std::string word;
    ls >> word;
    if (line_no == 1) {
      std::string version;
      ls >> version;
      if (word != "softslc-journal" || version != "1") return fail("not a softslc journal (version 1)");
      continue;
    }
    // Paths may contain spaces: the program path is everything between "program " and the
    // fingerprint (the last word), the bench path everything after "bench ".
    if (word == "program") {
      const auto last = line.rfind(' ');
      if (last == std::string::npos || last <= 8) return fail("expected: program PATH FINGERPRINT");
      program = line.substr(8, last - 8);
      fingerprint = line.substr(last + 1);
      continue;
    }
    if (word == "bench") {
      bench = line.size() > 6 ? line.substr(6) : std::string();
      try {
        r.controller = Controller::load(program, bench == "-" ? std::nullopt : std::optional<std::filesystem::path>(bench));
      } catch (const ControllerError& e) {
        return fail(std::string("cannot load the journal's program: ") + e.what());
      }
      r.controller->keep_journal(false);
      if (hex64(program_fingerprint(r.controller->program())) != fingerprint)
        return fail("the program " + program + " has changed since the journal was written");
      continue;
    }
    if (!r.controller) return fail("a record before the program and bench lines");
    Controller& c = *r.controller;
    if (word == "scans") {
      long long n = 0;
      if (!(ls >> n) || n < 0) return fail("bad scan count");
      for (; n > 0; --n) c.scan(1);  // as LiveController::run_scans performed them
      continue;
    }
    std::string at;
    ls >> at;
    long long vt = -1;
    if (at.size() < 2 || at[0] != '@' || std::sscanf(at.c_str() + 1, "%lld", &vt) != 1)
      return fail("expected @VIRTUAL_TIME");
    if (vt != c.now())
      return fail("record at virtual time " + std::to_string(vt) + " but the replay is at " + std::to_string(c.now()));
    if (word == "digest" || word == "end") {
      std::string crc;
      ls >> crc;
      if (crc != hex32(c.data_digest()))
        return fail("data table differs at " + std::to_string(vt) + " ns (journal " + crc + ", replay " +
                    hex32(c.data_digest()) + ")");
      ++r.digests;
      continue;
    }
    ControllerCall call;
    if (word != "mode" && word != "clearfault") ls >> call.target;
    try {
      if (word == "set") {
        call.kind = ControllerCall::Kind::Set;
        if (!(ls >> call.integer)) return fail("bad value");
      } else if (word == "setf") {
        std::string bits;
        ls >> bits;
        std::uint32_t u = 0;
        if (std::sscanf(bits.c_str(), "%x", &u) != 1) return fail("bad float bits");
        float f;
        std::memcpy(&f, &u, sizeof f);
        call.kind = ControllerCall::Kind::SetFloat;
        call.real = static_cast<double>(f);
      } else if (word == "setword") {
        call.kind = ControllerCall::Kind::SetWord;
        if (!(ls >> call.word >> call.integer)) return fail("bad word or value");
      } else if (word == "force") {
        call.kind = ControllerCall::Kind::Force;
        if (!(ls >> call.integer) || (call.integer != 0 && call.integer != 1)) return fail("bad force state");
      } else if (word == "unforce") {
        call.kind = ControllerCall::Kind::Unforce;
      } else if (word == "mode") {
        std::string name;
        ls >> name;
        call.kind = ControllerCall::Kind::SetMode;
        if (name == "program") call.mode = Mode::Program;
        else if (name == "run") call.mode = Mode::Run;
        else if (name == "test") call.mode = Mode::Test;
        else return fail("bad mode '" + name + "'");
      } else if (word == "clearfault") {
        call.kind = ControllerCall::Kind::ClearFault;
      } else {
        return fail("unknown record '" + word + "'");
      }
      c.perform(call);
    } catch (const ControllerError& e) {
      return fail(e.what());
    }
    ++r.writes;
  }
  if (!r.controller) return fail("no program line");
  r.ok = true;
  r.message = "replayed " + std::to_string(r.writes) + " write(s) to " + std::to_string(r.controller->now()) +
              " ns; the data table matched at all " + std::to_string(r.digests) + " digest(s)";
  return r;
}

}  // namespace softslc::serve
