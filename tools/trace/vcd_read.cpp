// Reading back a VCD that softslc wrote (write_vcd), for `softslc plot`: the header's variables,
// then time stamps and value changes. Only the subset write_vcd produces is accepted, each
// departure named with its line, so a VCD from another tool is refused rather than misdrawn.
#include <charconv>
#include <cmath>
#include <map>

#include "tools/trace/trace.h"

namespace softslc::trace {

namespace {

// Whitespace-separated words with their line numbers.
class Words {
 public:
  explicit Words(std::string_view text) : text_(text) {}
  // The next word, or empty at the end.
  std::string_view next() {
    while (at_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[at_]))) {
      if (text_[at_] == '\n') ++line_;
      ++at_;
    }
    const std::size_t start = at_;
    while (at_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[at_]))) ++at_;
    return text_.substr(start, at_ - start);
  }
  int line() const { return line_; }

 private:
  std::string_view text_;
  std::size_t at_ = 0;
  int line_ = 1;
};

template <typename T>
bool number(std::string_view s, T& out) {
  if (s.empty()) return false;
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && p == s.data() + s.size();
}

}  // namespace

std::string read_vcd(std::string_view text, const std::vector<std::string>& only, TraceData& out) {
  out = {};
  Words w(text);
  const auto fail = [&](const std::string& what) { return std::to_string(w.line()) + ": error: " + what; };
  // Skips to the $end of a block.
  const auto skip_block = [&](std::string_view name) -> std::string {
    for (std::string_view t = w.next(); t != "$end"; t = w.next())
      if (t.empty()) return fail(std::string(name) + " without $end");
    return {};
  };
  std::vector<Signal> all;
  std::map<std::string, std::size_t, std::less<>> ids;  // VCD id -> index in `all` (scan: npos)
  constexpr std::size_t kMarker = static_cast<std::size_t>(-1);
  bool definitions_done = false;
  while (!definitions_done) {
    const std::string_view t = w.next();
    if (t.empty()) return fail("no $enddefinitions: not a VCD");
    if (t == "$comment" || t == "$version" || t == "$date" || t == "$scope" || t == "$upscope") {
      if (auto e = skip_block(t); !e.empty()) return e;
    } else if (t == "$timescale") {
      std::string scale;
      for (std::string_view u = w.next(); u != "$end"; u = w.next()) {
        if (u.empty()) return fail("$timescale without $end");
        scale += u;
      }
      if (scale != "1us") return fail("timescale " + scale + ": softslc writes 1us");
    } else if (t == "$var") {
      const std::string_view type = w.next(), width = w.next(), id = w.next(), name = w.next();
      if (w.next() != "$end") return fail("expected: $var TYPE WIDTH ID NAME $end");
      Signal s;
      s.name = std::string(name);
      s.has_address = false;
      if (type == "wire" && width == "1") s.kind = Signal::Kind::Bit;
      else if (type == "integer" && width == "16") s.kind = Signal::Kind::Word16;
      else if (type == "integer" && width == "32") s.kind = Signal::Kind::Word32;
      else if (type == "real" && width == "64") s.kind = Signal::Kind::Real;
      else return fail("variable type " + std::string(type) + " " + std::string(width) + " is not one softslc writes");
      if (id.empty() || ids.count(id)) return fail("missing or repeated identifier '" + std::string(id) + "'");
      if (name == "scan" && id == "!") {
        ids.emplace(std::string(id), kMarker);
        continue;
      }
      if (all.size() >= kMaxVcdSignals) return fail("more than " + std::to_string(kMaxVcdSignals) + " variables");
      ids.emplace(std::string(id), all.size());
      all.push_back(std::move(s));
    } else if (t == "$enddefinitions") {
      if (w.next() != "$end") return fail("$enddefinitions without $end");
      definitions_done = true;
    } else {
      return fail("unexpected '" + std::string(t) + "' in the header");
    }
  }
  std::vector<std::vector<Change>> changes(all.size());
  std::int64_t now = -1;
  const auto record = [&](std::string_view id, SampleValue v) -> std::string {
    auto it = ids.find(id);
    if (it == ids.end()) return fail("unknown identifier '" + std::string(id) + "'");
    if (now < 0) return fail("a value before the first time stamp");
    if (it->second == kMarker) return {};
    auto& ch = changes[it->second];
    if (!ch.empty() && ch.back().time_us == now) ch.back().value = v;
    else ch.push_back({now, v});
    return {};
  };
  for (std::string_view t = w.next(); !t.empty(); t = w.next()) {
    if (t == "$dumpvars" || t == "$end") continue;
    if (t == "$comment") {
      if (auto e = skip_block(t); !e.empty()) return e;
      continue;
    }
    const char c = t.front();
    std::string error;
    if (c == '#') {
      std::int64_t time = 0;
      if (!number(t.substr(1), time) || time < 0 || time > (std::int64_t{1} << 62)) return fail("bad time stamp " + std::string(t));
      if (time < now) return fail("time goes backwards at " + std::string(t));
      now = time;
    } else if (c == '0' || c == '1') {
      error = record(t.substr(1), SampleValue{c - '0', 0.0});
    } else if (c == 'b') {
      const std::string_view bits = t.substr(1), id = w.next();
      if (bits.empty() || bits.size() > 64) return fail("bad vector value " + std::string(t));
      std::uint64_t v = 0;
      for (char b : bits) {
        if (b != '0' && b != '1') return fail("bad vector value " + std::string(t));
        v = v << 1 | static_cast<std::uint64_t>(b - '0');
      }
      // Two's complement at the variable's width (write_vcd writes negatives at full width).
      auto it = ids.find(id);
      const int width = it == ids.end() || it->second == kMarker ? 32 : all[it->second].kind == Signal::Kind::Word16 ? 16 : 32;
      if (bits.size() > static_cast<std::size_t>(width)) return fail("value " + std::string(t) + " wider than its variable");
      std::int64_t signed_v = static_cast<std::int64_t>(v);
      if (bits.size() == static_cast<std::size_t>(width) && bits.front() == '1') signed_v -= std::int64_t{1} << width;
      error = record(id, SampleValue{signed_v, 0.0});
    } else if (c == 'r') {
      double d = 0.0;
      const std::string_view id = w.next();
      if (!number(t.substr(1), d) || !std::isfinite(d)) return fail("bad real value " + std::string(t));
      error = record(id, SampleValue{0, d});
    } else {
      return fail("unexpected '" + std::string(t) + "'");
    }
    if (!error.empty()) return error;
  }
  if (now < 0) return fail("no time stamp: the trace is empty");
  out.end_us = now;
  if (only.empty()) {
    out.signals = std::move(all);
    out.changes = std::move(changes);
    return {};
  }
  for (const auto& name : only) {
    std::size_t i = 0;
    while (i < all.size() && all[i].name != name) ++i;
    if (i == all.size()) return " error: no signal named " + name + " in the trace";
    out.signals.push_back(all[i]);
    out.changes.push_back(changes[i]);
  }
  return {};
}

}  // namespace softslc::trace
