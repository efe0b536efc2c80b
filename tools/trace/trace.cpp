#include "tools/trace/trace.h"

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <set>

#include "parser/loader.h"
#include "vm/atomic_file.h"

namespace softslc::trace {

namespace {

std::string symbol_for(const Program& program, const Address& a) {
  for (const auto& s : program.symbols)
    if (!s.name.empty() && s.address == a) return s.name;
  return {};
}

bool traceable(const Address& a) { return !a.indexed && !a.is_indirect() && a.type != FileType::String && a.type != FileType::Ascii; }

Signal::Kind kind_of(const Address& a) {
  if (a.has_bit()) return Signal::Kind::Bit;
  if (a.type == FileType::Float) return Signal::Kind::Real;
  if (a.type == FileType::Long) return Signal::Kind::Word32;
  return Signal::Kind::Word16;
}

// Appends the signal(s) for one address: a whole T/C/R element becomes its status bits and its
// accumulator (or position), the values a timing diagram of it needs. Skips duplicates.
void add_address(const Program& program, const Address& a, std::vector<Signal>& out, std::set<std::string>& seen) {
  std::vector<Address> parts;
  if (is_structured(a.type) && a.word < 0 && a.bit < 0) {
    const bool control = a.type == FileType::Control;
    const bool counter = a.type == FileType::Counter;
    // Timer: EN/DN and ACC; counter: CU/DN and ACC; control: EN/DN and POS.
    const char* first = counter ? "CU" : "EN";
    for (const char* bit : {first, "DN"}) {
      Address b = a;
      b.word = 0;
      b.bit = structured_bit_number(a.type, bit);
      parts.push_back(b);
    }
    Address w = a;
    w.word = structured_word_number(a.type, control ? "POS" : "ACC");
    parts.push_back(w);
  } else {
    parts.push_back(a);
  }
  for (const auto& p : parts) {
    std::string text = to_string(p);
    if (!seen.insert(text).second) continue;
    std::string sym = symbol_for(program, p);
    out.push_back({sym.empty() ? text : sym, p, kind_of(p)});
  }
}

void collect(const Program& program, const std::vector<RungElement>& elements, bool outputs_only,
             std::vector<Signal>& out, std::set<std::string>& seen) {
  for (const auto& e : elements) {
    if (e.kind == RungElement::Kind::Branch) {
      for (const auto& leg : e.legs) collect(program, leg, outputs_only, out, seen);
      continue;
    }
    const auto& s = spec(e.instruction.opcode);
    if (outputs_only && s.role != Role::Output) continue;
    const auto specs = s.operand_specs();
    for (std::size_t i = 0; i < e.instruction.operands.size(); ++i) {
      const Operand& o = e.instruction.operands[i];
      if (!o.is_address() || !traceable(o.address)) continue;
      // A MSG target names the other controller's data table, not a signal of this one.
      if (i < specs.size() && specs[i].kind == OperandKind::RemoteAddress) continue;
      if (outputs_only && i < specs.size() && specs[i].access == OperandAccess::Read) continue;
      add_address(program, o.address, out, seen);
    }
  }
}

// The VCD identifier of signal i: printable ASCII '!'..'~' in base 94. Index 0 is the scan marker.
std::string vcd_id(std::size_t i) {
  std::string id;
  do {
    id += static_cast<char>('!' + i % 94);
    i /= 94;
  } while (i > 0);
  return id;
}

std::string binary(std::uint64_t v, int width) {
  // Non-negative values drop their leading zeros (VCD extends a vector with 0 on the left); a
  // negative value is written at full width so its sign bit is there.
  std::string s;
  for (int b = width - 1; b >= 0; --b) s += ((v >> b) & 1U) ? '1' : '0';
  if ((v >> (width - 1) & 1U) == 0) {
    auto first = s.find('1');
    s = first == std::string::npos ? "0" : s.substr(first);
  }
  return s;
}

std::string vcd_value(const Signal& s, const SampleValue& v, const std::string& id) {
  switch (s.kind) {
    case Signal::Kind::Bit: return (v.integer ? "1" : "0") + id + "\n";
    case Signal::Kind::Word16: return "b" + binary(static_cast<std::uint64_t>(v.integer) & 0xFFFFU, 16) + " " + id + "\n";
    case Signal::Kind::Word32:
      return "b" + binary(static_cast<std::uint64_t>(v.integer) & 0xFFFFFFFFU, 32) + " " + id + "\n";
    case Signal::Kind::Real: {
      char buf[48];
      std::snprintf(buf, sizeof buf, "r%.9g ", v.real);
      return buf + id + "\n";
    }
  }
  return {};
}

std::string scan_value(std::int64_t count) { return "b" + binary(static_cast<std::uint64_t>(count) & 0xFFFFFFFFU, 32) + " !\n"; }

std::string time_line(std::int64_t t) { return "#" + std::to_string(t) + "\n"; }

// A VCD reference may not contain spaces; a symbol or address never does, but be safe.
std::string vcd_name(std::string s) {
  for (char& c : s)
    if (c == ' ' || c == '\t') c = '_';
  return s;
}


std::string value_text(const Signal& s, const SampleValue& v) {
  if (s.kind == Signal::Kind::Real) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v.real);
    return buf;
  }
  return std::to_string(v.integer);
}

// The time in the unit that reads best for a diagram spanning `span` µs.
std::string time_label(std::int64_t us, std::int64_t span) {
  char buf[32];
  if (span >= 2'000'000) std::snprintf(buf, sizeof buf, "%g s", static_cast<double>(us) / 1e6);
  else if (span >= 2'000) std::snprintf(buf, sizeof buf, "%g ms", static_cast<double>(us) / 1e3);
  else std::snprintf(buf, sizeof buf, "%" PRId64 " us", us);
  return buf;
}

// A 1-2-5 step giving about `target` grid lines over `span`.
std::int64_t nice_step(std::int64_t span, int target) {
  std::int64_t step = 1;
  while (true) {
    for (std::int64_t m : {1, 2, 5})
      if (step * m * target >= span) return step * m;
    step *= 10;
  }
}

}  // namespace

std::string xml_escape(std::string_view s) {
  std::string r;
  for (char c : s) {
    switch (c) {
      case '&': r += "&amp;"; break;
      case '<': r += "&lt;"; break;
      case '>': r += "&gt;"; break;
      case '"': r += "&quot;"; break;
      default: r += c;
    }
  }
  return r;
}

bool parse_signal_list(const Program& program, const std::string& list, std::vector<Signal>& out, std::string& error) {
  std::set<std::string> seen;
  for (const auto& s : out) seen.insert(to_string(s.address));
  std::size_t start = 0;
  while (start <= list.size()) {
    std::size_t comma = list.find(',', start);
    if (comma == std::string::npos) comma = list.size();
    std::string name = list.substr(start, comma - start);
    start = comma + 1;
    if (name.empty()) continue;
    std::optional<Address> a;
    if (const Symbol* s = program.find_symbol(name)) a = s->address;
    else {
      std::string why;
      a = parse_address(name, &why);
      if (!a) {
        error = "'" + name;
        error += "' is neither an address nor a symbol of the program (" + why + ")";
        return false;
      }
    }
    if (!traceable(*a)) {
      error = "'" + name + "' cannot be traced: name a direct bit or word (not indexed, indirect or a string)";
      return false;
    }
    add_address(program, *a, out, seen);
  }
  return true;
}

std::vector<Signal> program_signals(const Program& program, bool outputs_only) {
  std::vector<Signal> out;
  std::set<std::string> seen;
  for (const auto& f : program.files)
    for (const auto& r : f.rungs) collect(program, r.elements, outputs_only, out, seen);
  return out;
}

TraceRecorder::TraceRecorder(std::vector<Signal> signals, std::size_t limit_bytes)
    : signals_(std::move(signals)), changes_(signals_.size()), limit_(limit_bytes) {}

std::string TraceRecorder::check(const Runtime& runtime) const {
  for (const auto& s : signals_) {
    std::string error;
    if (!runtime.get(s.address, &error)) return s.name + ": " + error;
  }
  return {};
}

void TraceRecorder::attach(Runtime& runtime) {
  sample(runtime);
  runtime.set_scan_observer([this](const Runtime& rt) {
    ++scan_count_;
    sample(rt);
  });
}

void TraceRecorder::detach(Runtime& runtime) { runtime.set_scan_observer({}); }

void TraceRecorder::reset() {
  for (auto& c : changes_) c.clear();
  scans_.clear();
  bytes_ = 0;
  end_us_ = 0;
  scan_count_ = 0;
  time_base_ = 0;
  started_ = false;
  truncated_ = false;
}

void TraceRecorder::sample(const Runtime& runtime) {
  if (truncated_) return;
  const std::int64_t t = (time_base_ + runtime.now()) / kNsPerUs;
  std::size_t cost = 0;
  std::vector<std::pair<std::size_t, SampleValue>> changed;
  for (std::size_t i = 0; i < signals_.size(); ++i) {
    auto v = runtime.get(signals_[i].address);
    SampleValue sv;
    if (v) {
      if (v->kind == Value::Kind::Float) sv.real = v->real;
      else sv.integer = v->integer;
    }
    if (!changes_[i].empty() && changes_[i].back().value == sv) continue;
    cost += vcd_value(signals_[i], sv, vcd_id(i + 1)).size();
    changed.emplace_back(i, sv);
  }
  cost += scan_value(scan_count_).size() + time_line(t).size();
  if (bytes_ + cost > limit_ && started_) {
    truncated_ = true;
    return;
  }
  bytes_ += cost;
  started_ = true;
  end_us_ = t;
  for (auto& [i, sv] : changed) changes_[i].push_back({t, sv});
  scans_.push_back({t, {scan_count_, 0.0}});
}

std::string write_vcd(const TraceRecorder& trace, const std::string& title, const std::string& module,
                      const std::string& version) {
  std::string out;
  out += "$comment\n  softslc trace: " + title +
         "\n  Values at the end of each scan cycle in virtual time; `scan` counts scan cycles.\n$end\n";
  out += "$version\n  " + version + "\n$end\n";
  out += "$timescale 1us $end\n";
  out += "$scope module " + vcd_name(module.empty() ? "plc" : module) + " $end\n";
  out += "$var integer 32 ! scan $end\n";
  const auto& sigs = trace.signals();
  for (std::size_t i = 0; i < sigs.size(); ++i) {
    const auto& s = sigs[i];
    const char* type = s.kind == Signal::Kind::Bit ? "wire 1" : s.kind == Signal::Kind::Word16 ? "integer 16"
                                                         : s.kind == Signal::Kind::Word32   ? "integer 32"
                                                                                            : "real 64";
    out += std::string("$var ") + type + " " + vcd_id(i + 1) + " " + vcd_name(s.name) + " $end\n";
  }
  out += "$upscope $end\n$enddefinitions $end\n";
  // Merge the per-signal change lists into time order; within one time, the marker first and then
  // the signals in declaration order.
  std::vector<std::size_t> next(sigs.size(), 0);
  const auto& scans = trace.scans();
  for (std::size_t k = 0; k < scans.size(); ++k) {
    const std::int64_t t = scans[k].time_us;
    out += time_line(t);
    if (k == 0) out += "$dumpvars\n";
    out += scan_value(scans[k].value.integer);
    for (std::size_t i = 0; i < sigs.size(); ++i) {
      const auto& ch = trace.changes()[i];
      while (next[i] < ch.size() && ch[next[i]].time_us == t) out += vcd_value(sigs[i], ch[next[i]++].value, vcd_id(i + 1));
    }
    if (k == 0) out += "$end\n";
  }
  if (trace.truncated())
    out += "$comment\n  trace limit of " + std::to_string(trace.limit_bytes()) + " bytes reached at " +
           std::to_string(trace.end_us()) + " us: later changes were not recorded\n$end\n";
  return out;
}

namespace {

// The diagram from signals and their changes: a recorder's, or a VCD's read back.
std::string timing_svg(const std::vector<Signal>& sigs, const std::vector<std::vector<Change>>& changes,
                       std::int64_t end_us, bool truncated, const std::string& title) {
  constexpr int kLabelW = 200, kPlotW = 900, kRowH = 36, kTop = 48, kWave = 20;
  const std::int64_t span = std::max<std::int64_t>(end_us, 1);
  const int height = kTop + static_cast<int>(sigs.size()) * kRowH + 40;
  const int width = kLabelW + kPlotW + 20;
  auto x_of = [&](std::int64_t t) { return kLabelW + static_cast<int>((t * kPlotW) / span); };
  std::string o;
  o += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + std::to_string(width) + "\" height=\"" +
       std::to_string(height) + "\" viewBox=\"0 0 " + std::to_string(width) + " " + std::to_string(height) +
       "\" font-family=\"monospace\" font-size=\"12\">\n";
  o += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  o += "<text x=\"8\" y=\"20\" font-size=\"14\">" + xml_escape(title) + "</text>\n";
  // Time grid.
  const std::int64_t step = nice_step(span, 10);
  const int grid_bottom = kTop + static_cast<int>(sigs.size()) * kRowH;
  for (std::int64_t t = 0; t <= span; t += step) {
    const int x = x_of(t);
    o += "<line x1=\"" + std::to_string(x) + "\" y1=\"" + std::to_string(kTop - 8) + "\" x2=\"" + std::to_string(x) +
         "\" y2=\"" + std::to_string(grid_bottom) + "\" stroke=\"#ddd\"/>\n";
    o += "<text x=\"" + std::to_string(x) + "\" y=\"" + std::to_string(grid_bottom + 16) +
         "\" text-anchor=\"middle\" fill=\"#555\">" + xml_escape(time_label(t, span)) + "</text>\n";
  }
  for (std::size_t i = 0; i < sigs.size(); ++i) {
    const auto& s = sigs[i];
    const auto& ch = changes[i];
    const int top = kTop + static_cast<int>(i) * kRowH;
    const int hi = top + 6, lo = hi + kWave, mid = (hi + lo) / 2;
    std::string label = s.name;
    if (std::string addr = s.has_address ? to_string(s.address) : s.name; addr != s.name) label += " (" + addr + ")";
    o += "<g class=\"signal\" data-name=\"" + xml_escape(s.name) + "\">\n";
    o += "<text x=\"8\" y=\"" + std::to_string(mid + 4) + "\">" + xml_escape(label) + "</text>\n";
    if (s.kind == Signal::Kind::Bit) {
      std::string pts;
      int y = ch.empty() || ch[0].value.integer == 0 ? lo : hi;
      pts += std::to_string(kLabelW) + "," + std::to_string(y);
      for (std::size_t k = 1; k < ch.size(); ++k) {
        const int x = x_of(ch[k].time_us);
        pts += " " + std::to_string(x) + "," + std::to_string(y);
        y = ch[k].value.integer ? hi : lo;
        pts += " " + std::to_string(x) + "," + std::to_string(y);
      }
      pts += " " + std::to_string(kLabelW + kPlotW) + "," + std::to_string(y);
      o += "<polyline fill=\"none\" stroke=\"#0a0\" stroke-width=\"2\" points=\"" + pts + "\"/>\n";
    } else {
      // A bus: one hexagon-ended segment per value, the value written in it where it fits.
      for (std::size_t k = 0; k < ch.size(); ++k) {
        const int x0 = x_of(ch[k].time_us);
        const int x1 = k + 1 < ch.size() ? x_of(ch[k + 1].time_us) : kLabelW + kPlotW;
        const int e = std::min(3, (x1 - x0) / 2);
        o += "<polygon fill=\"#eef\" stroke=\"#33a\" points=\"" + std::to_string(x0) + "," + std::to_string(mid) + " " +
             std::to_string(x0 + e) + "," + std::to_string(hi) + " " + std::to_string(x1 - e) + "," + std::to_string(hi) +
             " " + std::to_string(x1) + "," + std::to_string(mid) + " " + std::to_string(x1 - e) + "," +
             std::to_string(lo) + " " + std::to_string(x0 + e) + "," + std::to_string(lo) + "\"/>\n";
        const std::string v = value_text(s, ch[k].value);
        if (static_cast<int>(v.size()) * 7 + 6 < x1 - x0)
          o += "<text x=\"" + std::to_string(x0 + 4) + "\" y=\"" + std::to_string(mid + 4) + "\">" + xml_escape(v) + "</text>\n";
      }
    }
    o += "</g>\n";
  }
  if (truncated)
    o += "<text x=\"8\" y=\"" + std::to_string(height - 6) + "\" fill=\"#a00\">trace limit reached at " +
         xml_escape(time_label(end_us, span)) + ": later changes were not recorded</text>\n";
  o += "</svg>\n";
  return o;
}

}  // namespace

std::string write_timing_svg(const TraceRecorder& trace, const std::string& title) {
  return timing_svg(trace.signals(), trace.changes(), trace.end_us(), trace.truncated(), title);
}

std::string write_timing_svg(const TraceData& trace, const std::string& title) {
  return timing_svg(trace.signals, trace.changes, trace.end_us, false, title);
}

std::string save_trace(const TraceRecorder& trace, const std::string& path, const std::string& title,
                       const std::string& module, const std::string& version) {
  const bool svg = path.size() >= 4 && path.compare(path.size() - 4, 4, ".svg") == 0;
  return write_file_atomically(path, svg ? write_timing_svg(trace, title) : write_vcd(trace, title, module, version));
}

bool parse_size(const std::string& text, std::size_t& out) {
  if (text.empty() || text.size() > 20) return false;
  std::size_t i = 0;
  std::uint64_t v = 0;
  while (i < text.size() && text[i] >= '0' && text[i] <= '9') {
    v = v * 10 + static_cast<std::uint64_t>(text[i] - '0');
    if (v > (1ULL << 40)) return false;
    ++i;
  }
  if (i == 0) return false;
  std::uint64_t mult = 1;
  if (i < text.size()) {
    if (i + 1 != text.size()) return false;
    switch (text[i]) {
      case 'k': case 'K': mult = 1024; break;
      case 'M': mult = 1024ULL * 1024; break;
      case 'G': mult = 1024ULL * 1024 * 1024; break;
      default: return false;
    }
  }
  out = static_cast<std::size_t>(v * mult);
  return out > 0;
}

}  // namespace softslc::trace
