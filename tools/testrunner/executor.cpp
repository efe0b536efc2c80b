#include "tools/testrunner/executor.h"

#include <algorithm>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>

#include "tools/testrunner/test_loader.h"
#include "tools/trace/trace.h"
#include "vm/runtime.h"

namespace softslc::testing {

std::string Failure::summary() const {
  return file + ":" + std::to_string(loc.line) + ": " + step;
}

std::string Failure::render(const std::string& indent) const {
  const std::string deeper = indent + "  ";
  std::string out = indent + summary() + "\n";
  if (!context.empty()) out += deeper + context + "\n";
  if (!error.empty()) out += deeper + "error: " + error + "\n";
  if (!expected.empty()) out += deeper + "expected: " + expected + "\n";
  if (!actual.empty()) out += deeper + "actual:   " + actual + "\n";
  for (const auto& n : notes) out += deeper + n + "\n";
  out += deeper + "at virtual time " + format_duration(time) + ", scan " + std::to_string(scan) + "\n";
  return out;
}

namespace {

// A number read from the data table or written in the test, compared the way the SLC would:
// integers exactly, floats as the 32-bit floats the data table holds.
struct Number {
  bool is_float = false;
  std::int64_t i = 0;
  double d = 0.0;
  double as_double() const { return is_float ? d : static_cast<double>(i); }
};

Number number_of(const Value& v) {
  if (v.kind == Value::Kind::Float) return {true, 0, v.real};
  return {false, v.integer, 0.0};
}

Number number_of(const Literal& l, int width) {
  if (width == 0) {
    // An F-file operand: compare with the float nearest the literal, as a MOV of it would store.
    const double d = l.kind == Literal::Kind::Float ? l.real : static_cast<double>(l.integer);
    return {true, 0, static_cast<double>(static_cast<float>(d))};
  }
  return {false, integer_for_width(l, width, nullptr).value_or(0), 0.0};
}

bool compare_numbers(const Number& a, CompareOp op, const Number& b) {
  if (a.is_float || b.is_float) {
    const double x = a.as_double(), y = b.as_double();
    switch (op) {
      case CompareOp::Eq: return x == y;
      case CompareOp::Ne: return x != y;
      case CompareOp::Lt: return x < y;
      case CompareOp::Le: return x <= y;
      case CompareOp::Gt: return x > y;
      case CompareOp::Ge: return x >= y;
      case CompareOp::In: return false;
    }
    return false;
  }
  switch (op) {
    case CompareOp::Eq: return a.i == b.i;
    case CompareOp::Ne: return a.i != b.i;
    case CompareOp::Lt: return a.i < b.i;
    case CompareOp::Le: return a.i <= b.i;
    case CompareOp::Gt: return a.i > b.i;
    case CompareOp::Ge: return a.i >= b.i;
    case CompareOp::In: return false;
  }
  return false;
}

template <typename T>
bool compare_ordered(T a, CompareOp op, T b, T high) {
  switch (op) {
    case CompareOp::Eq: return a == b;
    case CompareOp::Ne: return a != b;
    case CompareOp::Lt: return a < b;
    case CompareOp::Le: return a <= b;
    case CompareOp::Gt: return a > b;
    case CompareOp::Ge: return a >= b;
    case CompareOp::In: return a >= b && a <= high;
  }
  return false;
}

// Whether `v` matches a pattern literal: the written 0/1 digits must match, x digits are free,
// and bits above the written digits must be 0 (the literal is right-aligned like any number).
bool matches_pattern(const Value& v, const Literal& l, int width) {
  const std::uint64_t word_mask = pattern_of(-1, width);
  const std::uint64_t written = l.digits >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << l.digits) - 1;
  const std::uint64_t care = (l.care | (word_mask & ~written)) & word_mask;
  return (pattern_of(v.integer, width) & care) == (static_cast<std::uint64_t>(l.integer) & care);
}

std::string fault_text(const Runtime& rt) {
  return rt.fault() ? rt.fault()->to_string() : "no fault";
}

Address element_of(const DataRef& r, int offset) {
  Address a = r.address;
  a.element += offset;
  return a;
}

// Formats a value in the radix of the literal it is compared with.
std::string format_as(const Value& v, const Literal* l, int width) {
  if (l && l->kind == Literal::Kind::Pattern) return format_value(v, Radix::Binary, width);
  return format_value(v, l ? l->radix : Radix::Decimal, width);
}

// Short form for word lists: hex/binary digits without the decimal value.
std::string format_short(const Value& v, const Literal& l, int width) {
  std::string s = format_as(v, &l, width);
  if (auto paren = s.find(" ("); paren != std::string::npos) s.resize(paren);
  return s;
}

// The bits that OTE instructions write (directly addressed ones): on the SLC they are
// non-retentive on power loss, so a hold-in rung drops out at power-up (1747-SN user manual,
// "a hold-in rung ... will not function as it would if the OTE instruction were non-retentive on
// power loss"; only M0/M1 addresses behave otherwise, and those live in modules).
void collect_ote_bits(const std::vector<RungElement>& elements, std::vector<Address>& out) {
  for (const auto& e : elements) {
    if (e.kind == RungElement::Kind::Branch) {
      for (const auto& leg : e.legs) collect_ote_bits(leg, out);
      continue;
    }
    if (e.instruction.opcode != Opcode::OTE || e.instruction.operands.empty()) continue;
    const softslc::Operand& op = e.instruction.operands.front();
    if (!op.is_address()) continue;
    const Address& a = op.address;
    if (a.bit < 0 || a.indexed || a.is_indirect() || is_mfile(a.type) || a.type == FileType::Input) continue;
    out.push_back(a);
  }
}

class Session {
 public:
  Session(const std::string& file, const RuntimeOptions& options, bool record_coverage, bool record_trace)
      : file_(file), options_(options), record_coverage_(record_coverage), record_trace_(record_trace) {}

  TestOutcome run(const TestCase& tc) {
    TestOutcome out;
    const Step* current = nullptr;
    try {
      out.failure = start(*tc.program, tc.initial_mode, tc.loc, "test \"" + tc.name + "\"");
      for (const auto& step : tc.steps) {
        if (out.failure) break;
        current = &step;
        out.failure = execute(step, {});
      }
    } catch (const std::exception& e) {
      // The runtime throws only on a programming error (time going backwards, ...); report it at
      // the step that caused it rather than aborting the whole run.
      Failure f = failure_at(current ? current->loc : tc.loc, current ? current->text : "test \"" + tc.name + "\"", {});
      f.error = std::string("internal error: ") + e.what();
      out.failure = std::move(f);
    }
    out.virtual_time = rt_ ? now() : 0;
    out.scans = rt_ ? scans() : 0;
    harvest_coverage();
    out.coverage = std::move(coverage_);
    if (trace_) {
      if (rt_) trace_->detach(*rt_);
      out.trace_vcd = trace::write_vcd(*trace_, file_ + ": " + tc.name, tc.program->program.project, "softslc test");
    }
    return out;
  }

 private:
  // ---- Coverage ----

  // Folds the coverage of the current Runtime into the test's, before the Runtime is replaced.
  void harvest_coverage() {
    if (rt_ && rt_->coverage() && program_) merge_coverage(coverage_, program_, rt_->coverage()->flags());
  }

  void replace_runtime(std::unique_ptr<Runtime> fresh) {
    harvest_coverage();
    rt_ = std::move(fresh);
    if (record_coverage_) rt_->enable_coverage();
  }

  // ---- Trace ----

  // Attaches the test's trace to the current Runtime; `from_start` forgets what was recorded (a
  // fresh start or a restore, whose replay begins at time 0).
  void attach_trace(const LoadedProgram& program, bool from_start) {
    if (!record_trace_) return;
    if (!trace_) trace_ = std::make_unique<trace::TraceRecorder>(trace::program_signals(program.program, false), kTraceLimit);
    if (from_start) trace_->reset();
    trace_->set_time_base(time_base_);
    trace_->attach(*rt_);  // an unreadable signal records 0: the trace is a debugging aid
  }

  // ---- Time and scans across power cycles ----

  VirtualTime now() const { return time_base_ + rt_->now(); }
  std::uint64_t scans() const { return scan_base_ + rt_->stats().scans; }

  Failure failure_at(Location loc, const std::string& step, const std::string& context) const {
    Failure f;
    f.file = file_;
    f.loc = loc;
    f.step = step;
    f.context = context;
    if (rt_) {
      f.time = now();
      f.scan = scans();
    }
    return f;
  }

  Failure step_failure(const Step& s, const std::string& context) const { return failure_at(s.loc, s.text, context); }

  // Adds the active major fault to a failure, unless the failure already shows it.
  void note_fault(Failure& f) const {
    if (!rt_ || !rt_->fault()) return;
    const std::string text = rt_->fault()->to_string();
    if (f.actual.find(text) == std::string::npos && f.error.find(text) == std::string::npos)
      f.notes.push_back("the processor is faulted: " + text);
  }

  // A fresh Runtime of `program` in `mode`, with the test's clock, scans and forces reset.
  // The options of every Runtime of `program`: its modules (from its SLOT lines and bench),
  // with the caller's processor and scan-time model where given.
  static RuntimeOptions options_for(const LoadedProgram& program, const RuntimeOptions& caller) {
    RuntimeOptions o = program.modules;
    if (caller.processor) o.processor = caller.processor;
    if (caller.time_model) o.time_model = caller.time_model;
    if (caller.module_factory) o.module_factory = caller.module_factory;
    if (caller.module_instruction) o.module_instruction = caller.module_instruction;
    return o;
  }

  std::optional<Failure> start(const LoadedProgram& program, Mode mode, Location loc, const std::string& what) {
    RuntimeResult r = Runtime::create(program.program, options_for(program, options_));
    if (!r.ok()) {
      Failure f = failure_at(loc, what, {});
      f.error = "the program did not compile: " + r.render_errors();
      return f;
    }
    replace_runtime(std::move(r.runtime));
    program_ = &program;
    time_base_ = 0;
    scan_base_ = 0;
    last_elapsed_ = 0;
    last_scans_ = 0;
    forces_cleared_ = false;
    forces_.clear();
    injected_.clear();
    attach_trace(program, true);
    if (mode != Mode::Program) {
      if (auto st = rt_->set_mode(mode); !st) {
        Failure f = failure_at(loc, what, {});
        f.error = st.message;
        return f;
      }
    }
    return std::nullopt;
  }

  // ---- Steps ----

  std::optional<Failure> execute(const Step& s, const std::string& context) {
    switch (s.kind) {
      case Step::Kind::Set: return set(s, context);
      case Step::Kind::Force: {
        const std::string addr = to_string(s.target.address);
        const bool on = s.values.at(0).integer != 0;
        if (auto st = rt_->force(addr, on); !st) return refused(s, context, st.message);
        forces_[addr] = on;
        return std::nullopt;
      }
      case Step::Kind::Unforce: {
        const std::string addr = to_string(s.target.address);
        if (auto st = rt_->unforce(addr); !st) return refused(s, context, st.message);
        forces_[addr] = std::nullopt;
        return std::nullopt;
      }
      case Step::Kind::UnforceAll:
        rt_->clear_forces();
        forces_cleared_ = true;
        forces_.clear();
        return std::nullopt;
      case Step::Kind::Scan: {
        const auto t0 = now();
        const auto s0 = scans();
        rt_->scan(static_cast<int>(s.count));
        last_elapsed_ = now() - t0;
        last_scans_ = scans() - s0;
        return std::nullopt;
      }
      case Step::Kind::Run: {
        const auto t0 = now();
        const auto s0 = scans();
        rt_->run_for(s.duration);
        last_elapsed_ = now() - t0;
        last_scans_ = scans() - s0;
        return std::nullopt;
      }
      case Step::Kind::RunUntil: return run_until(s, context);
      case Step::Kind::Expect: return expect(s, context);
      case Step::Kind::ExpectWords: return expect_words(s, context);
      case Step::Kind::ExpectLog: return expect_log(s, context);
      case Step::Kind::Mode:
        if (auto st = rt_->set_mode(s.mode); !st) return refused(s, context, st.message);
        return std::nullopt;
      case Step::Kind::PowerCycle: return power_cycle(s, context);
      case Step::Kind::ClearFault:
        rt_->clear_fault();
        return std::nullopt;
      case Step::Kind::Snapshot: return std::nullopt;
      case Step::Kind::Restore: return restore(s, context);
      case Step::Kind::Device:
        if (auto st = rt_->inject(s.name, s.change, s.args); !st) return refused(s, context, st.message);
        injected_.push_back(&s);
        return std::nullopt;
    }
    return std::nullopt;
  }

  std::optional<Failure> refused(const Step& s, const std::string& context, const std::string& message) const {
    Failure f = step_failure(s, context);
    f.error = message;
    note_fault(f);
    return f;
  }

  std::optional<Failure> set(const Step& s, const std::string& context) {
    const int width = width_of(s.target.address);
    for (std::size_t i = 0; i < s.values.size(); ++i) {
      const Literal& l = s.values[i];
      Value v = width == 1   ? Value::bit(l.integer != 0)
                : width == 0 ? Value::of_float(l.kind == Literal::Kind::Float ? l.real : static_cast<double>(l.integer))
                             : Value::of_int(integer_for_width(l, width, nullptr).value_or(0));
      if (auto st = runtime_of(s.target).set(element_of(s.target, static_cast<int>(i)), v); !st)
        return refused(s, context, st.message);
    }
    return std::nullopt;
  }

  std::optional<Failure> run_until(const Step& s, const std::string& context) {
    const auto t0 = now();
    const auto s0 = scans();
    std::string error;
    bool errored = false;
    const bool held = rt_->run_until(
        [&](const Runtime&) {
          // `elapsed` and `scans` inside the condition count from the start of this step.
          last_elapsed_ = now() - t0;
          last_scans_ = scans() - s0;
          auto r = evaluate(s.condition, error);
          if (!r) errored = true;
          return !r || *r;
        },
        s.duration);
    last_elapsed_ = now() - t0;
    last_scans_ = scans() - s0;
    if (errored) return refused(s, context, error);
    if (held) return std::nullopt;
    Failure f = step_failure(s, context);
    f.expected = s.condition_text + " within " + format_duration(s.duration);
    f.actual = "still false after " + format_duration(last_elapsed_) + ": " + describe(s.condition);
    note_fault(f);
    return f;
  }

  std::optional<Failure> expect(const Step& s, const std::string& context) {
    std::string error;
    auto r = evaluate(s.condition, error);
    if (!r) return refused(s, context, error);
    if (*r) return std::nullopt;
    Failure f = step_failure(s, context);
    f.expected = s.condition_text;
    f.actual = describe(s.condition);
    note_fault(f);
    return f;
  }

  std::optional<Failure> expect_words(const Step& s, const std::string& context) {
    const int width = width_of(s.target.address);
    std::string actual = s.target.spelling + " = ", differs;
    bool ok = true;
    for (std::size_t i = 0; i < s.values.size(); ++i) {
      const Address a = element_of(s.target, static_cast<int>(i));
      std::string error;
      auto v = runtime_of(s.target).get(a, &error);
      if (!v) return refused(s, context, error);
      const Literal& l = s.values[i];
      const bool same = l.kind == Literal::Kind::Pattern
                            ? matches_pattern(*v, l, width)
                            : compare_numbers(number_of(*v), CompareOp::Eq, number_of(l, width));
      actual += (i ? " " : "") + format_short(*v, l, width);
      if (!same) {
        ok = false;
        differs += (differs.empty() ? "" : ", ") + to_string(a);
      }
    }
    if (ok) return std::nullopt;
    Failure f = step_failure(s, context);
    f.expected = s.condition_text;
    f.actual = actual;
    f.notes.push_back("differs at " + differs);
    note_fault(f);
    return f;
  }

  // expect log Q == "TEXT" | none: a communications read of the queue's oldest record, which
  // removes it (docs/semantics.md "Data logging: DLG and the DLS file").
  std::optional<Failure> expect_log(const Step& s, const std::string& context) {
    const auto record = rt_->retrieve_data_log_record(static_cast<int>(s.count));
    const auto shown = [](const std::string& t) {
      std::string out = "\"";
      for (char c : t) out += c == '\t' ? std::string("\\t") : std::string(1, c);
      return out + "\"";
    };
    if (s.none ? !record : record && *record == s.name) return std::nullopt;
    Failure f = step_failure(s, context);
    f.expected = s.condition_text;
    f.actual = "log " + std::to_string(s.count) + " == " + (record ? shown(*record) : std::string("none"));
    note_fault(f);
    return f;
  }

  std::optional<Failure> restore(const Step& s, const std::string& context) {
    const Snapshot& snap = *s.snapshot;
    if (auto f = start(*snap.program, snap.initial_mode, s.loc, s.text)) return f;
    // A snapshot restored inside a replay names the outermost restore, where the user looks.
    const std::string replay = context.empty() ? "in snapshot '" + snap.name + "' (taken at " + file_ + ":" +
                                                     std::to_string(snap.loc.line) + "), restored at line " +
                                                     std::to_string(s.loc.line)
                                               : context;
    for (const auto& step : snap.steps)
      if (auto f = execute(step, replay)) return f;
    return std::nullopt;
  }

  // Power off and on: a new Runtime with the old data table (battery-backed on the SLC) except
  // the bits OTE instructions write (non-retentive on power loss), the field inputs and the
  // changes injected into bench devices as they were (the field did not change), the test's
  // forces (kept in processor memory), in the mode the processor was in. Entering Run sets the
  // first pass bit and zeroes S:4, as on power-up in Run.
  std::optional<Failure> power_cycle(const Step& s, const std::string& context) {
    if (!rt_->peer_names().empty())
      return refused(s, context,
                     "power cycle in a test with peers is not supported yet: it would restart one controller of the "
                     "network");
    if (rt_->fault() || rt_->mode() == Mode::Faulted)
      return refused(s, context,
                     "power cycle while faulted is not supported yet: the SLC keeps a major fault through a power "
                     "cycle and softslc cannot restore one; 'clear fault' first");
    const Mode mode = rt_->mode();
    RuntimeResult r = Runtime::create(program_->program, options_for(*program_, options_));
    if (!r.ok()) return refused(s, context, "the program did not compile: " + r.render_errors());
    Runtime& fresh = *r.runtime;
    const std::uint16_t fresh_s1 = fresh.data().status(status::kMode);
    const std::uint16_t old_s1 = rt_->data().status(status::kMode);
    std::copy(rt_->data().words(), rt_->data().words() + rt_->data().size(), fresh.data().words());
    // S:1 is the processor's own: mode, forces, fault and first pass come from the new runtime;
    // only the user's power-up options (S:1/8-12) are kept.
    constexpr std::uint16_t kUserBits = 0x1F00;
    fresh.data().set_status(status::kMode,
                            static_cast<std::uint16_t>((old_s1 & kUserBits) | (fresh_s1 & ~kUserBits)));
    std::vector<Address> ote_bits;
    for (const auto& file : program_->program.files)
      for (const auto& rung : file.rungs) collect_ote_bits(rung.elements, ote_bits);
    for (const auto& a : ote_bits) fresh.set(a, Value::bit(false));
    // The MicroLogix data log queues are battery-backed too (1763-RM001C p. 433).
    fresh.keep_data_logs_of(*rt_);
    for (int slot = 0; slot < kMaxSlots; ++slot) {
      Module* before = rt_->module(slot);
      Module* after = fresh.module(slot);
      if (!before || !after) continue;
      for (int w = 0; w < before->input_words(); ++w)
        if (auto v = before->field_input(w)) after->set_field_input(w, *v, 0xFFFF);
    }
    time_base_ += rt_->now();
    scan_base_ += rt_->stats().scans;
    replace_runtime(std::move(r.runtime));
    attach_trace(*program_, false);
    // The field devices did not lose power with the processor: what the test injected into them
    // (an adapter off line, a module's data) still holds, so it is applied to the new modules.
    for (const Step* d : injected_)
      if (auto st = rt_->inject(d->name, d->change, d->args); !st) return refused(s, context, st.message);
    if (forces_cleared_) rt_->clear_forces();
    for (const auto& [addr, on] : forces_) {
      if (on) rt_->force(addr, *on);
      else rt_->unforce(addr);
    }
    if (mode != Mode::Program)
      if (auto st = rt_->set_mode(mode); !st) return refused(s, context, st.message);
    return std::nullopt;
  }

  // ---- Conditions ----

  // The runtime that holds a data operand: the test's, or the peer its prefix names (B.N7:0; the
  // loader checked the name).
  Runtime& runtime_of(const DataRef& r) const {
    Runtime* peer = r.controller.empty() ? nullptr : rt_->peer(r.controller);
    return peer ? *peer : *rt_;
  }

  std::optional<Value> read(const DataRef& r, std::string& error) {
    auto v = runtime_of(r).get(r.address, &error);
    if (!v) error = r.describe() + ": " + error;
    return v;
  }

  // The observed value of a bench device: element `index` of the observation, or its only one.
  std::optional<std::int64_t> observe(const DeviceRef& d, std::string& error) const {
    const auto values = rt_->observe(d.name, d.what);
    const std::string what = "device " + d.name + " " + d.what;
    if (!values) {
      error = what + ": not observable";
      return std::nullopt;
    }
    if (d.index < 0) {
      if (values->size() == 1) return values->front();
      error = what + " has " + std::to_string(values->size()) + " values; name one with an index (" + d.what + "[0])";
      return std::nullopt;
    }
    if (static_cast<std::size_t>(d.index) < values->size()) return (*values)[static_cast<std::size_t>(d.index)];
    error = what + " has " + std::to_string(values->size()) + " value(s); there is no element " + std::to_string(d.index);
    return std::nullopt;
  }

  // nullopt with `error` set when an operand cannot be read.
  std::optional<bool> evaluate(const Condition& c, std::string& error) {
    switch (c.kind) {
      case Condition::Kind::And:
        for (const auto& t : c.terms) {
          auto r = evaluate(t, error);
          if (!r || !*r) return r;
        }
        return true;
      case Condition::Kind::Or:
        for (const auto& t : c.terms) {
          auto r = evaluate(t, error);
          if (!r || *r) return r;
        }
        return false;
      case Condition::Kind::Fault:
        return rt_->fault().has_value() && (!c.fault_code || rt_->fault()->code == *c.fault_code);
      case Condition::Kind::NoFault:
        return !rt_->fault().has_value();
      case Condition::Kind::Mode:
        return rt_->mode() == c.mode;
      case Condition::Kind::Compare:
        break;
    }
    const Comparison& k = c.compare;
    if (k.lhs.kind == Operand::Kind::Elapsed)
      return compare_ordered<Nanoseconds>(last_elapsed_, k.op, k.rhs.duration, k.high.duration);
    if (k.lhs.kind == Operand::Kind::Scans)
      return compare_ordered<std::int64_t>(static_cast<std::int64_t>(last_scans_), k.op, k.rhs.count, k.high.count);
    if (k.lhs.kind == Operand::Kind::Device) {
      auto a = observe(k.lhs.device, error);
      if (!a) return std::nullopt;
      if (k.rhs.kind == Operand::Kind::Data) {
        auto b = read(k.rhs.data, error);
        if (!b) return std::nullopt;
        return compare_numbers(Number{false, *a, 0.0}, k.op, number_of(*b));
      }
      // Observations are 64-bit numbers: literals compare as written (hexadecimal as its value).
      if (k.rhs.literal.kind == Literal::Kind::Pattern) {
        const bool m = matches_pattern(Value::of_int(*a), k.rhs.literal, 64);
        return k.op == CompareOp::Eq ? m : !m;
      }
      return compare_ordered<std::int64_t>(*a, k.op, k.rhs.literal.integer, k.high.literal.integer);
    }
    auto a = read(k.lhs.data, error);
    if (!a) return std::nullopt;
    const int width = width_of(k.lhs.data.address);
    if (k.rhs.kind == Operand::Kind::Data) {
      auto b = read(k.rhs.data, error);
      if (!b) return std::nullopt;
      return compare_numbers(number_of(*a), k.op, number_of(*b));
    }
    if (k.rhs.literal.kind == Literal::Kind::Pattern) {
      const bool m = matches_pattern(*a, k.rhs.literal, width);
      return k.op == CompareOp::Eq ? m : !m;
    }
    if (k.op == CompareOp::In)
      return compare_numbers(number_of(*a), CompareOp::Ge, number_of(k.rhs.literal, width)) &&
             compare_numbers(number_of(*a), CompareOp::Le, number_of(k.high.literal, width));
    return compare_numbers(number_of(*a), k.op, number_of(k.rhs.literal, width));
  }

  // The current values of a condition's operands, each once, in the order written:
  // "MOTOR (O:2/0) = 0, N7:0 = 0x0070 (112), elapsed = 1.0622s".
  std::string describe(const Condition& c) {
    std::vector<std::string> parts;
    std::set<std::string> seen;
    collect(c, parts, seen);
    std::string out;
    for (const auto& p : parts) out += (out.empty() ? "" : ", ") + p;
    return out;
  }

  void add_part(std::vector<std::string>& parts, std::set<std::string>& seen, std::string key, std::string text) {
    if (seen.insert(std::move(key)).second) parts.push_back(std::move(text));
  }

  void collect(const Condition& c, std::vector<std::string>& parts, std::set<std::string>& seen) {
    switch (c.kind) {
      case Condition::Kind::And:
      case Condition::Kind::Or:
        for (const auto& t : c.terms) collect(t, parts, seen);
        return;
      case Condition::Kind::Fault:
      case Condition::Kind::NoFault:
        add_part(parts, seen, "fault", fault_text(*rt_));
        return;
      case Condition::Kind::Mode:
        add_part(parts, seen, "mode", "mode " + std::string(mode_word(rt_->mode())));
        return;
      case Condition::Kind::Compare:
        break;
    }
    const Comparison& k = c.compare;
    if (k.lhs.kind == Operand::Kind::Elapsed) {
      add_part(parts, seen, "elapsed", "elapsed = " + format_duration(last_elapsed_));
      return;
    }
    if (k.lhs.kind == Operand::Kind::Scans) {
      add_part(parts, seen, "scans", "scans = " + std::to_string(last_scans_));
      return;
    }
    const Literal* hint = k.rhs.kind == Operand::Kind::Literal ? &k.rhs.literal : nullptr;
    if (k.lhs.kind == Operand::Kind::Device) {
      std::string error;
      const auto v = observe(k.lhs.device, error);
      add_part(parts, seen, k.lhs.spelling, v ? k.lhs.spelling + " = " + std::to_string(*v) : error);
    }
    for (const Operand* o : {&k.lhs, &k.rhs}) {
      if (o->kind != Operand::Kind::Data) continue;
      std::string error;
      auto v = runtime_of(o->data).get(o->data.address, &error);
      const int width = width_of(o->data.address);
      add_part(parts, seen, (o->data.controller.empty() ? "" : o->data.controller + ".") + to_string(o->data.address),
               o->data.describe() + " = " + (v ? format_as(*v, hint, width) : "unreadable (" + error + ")"));
    }
  }

  const std::string& file_;
  const RuntimeOptions& options_;
  bool record_coverage_ = false;
  ProgramCoverage coverage_;
  std::unique_ptr<Runtime> rt_;
  bool record_trace_ = false;
  std::unique_ptr<trace::TraceRecorder> trace_;
  static constexpr std::size_t kTraceLimit = 64u << 20;
  const LoadedProgram* program_ = nullptr;
  VirtualTime time_base_ = 0;       // virtual time of the Runtimes before the last power cycle
  std::uint64_t scan_base_ = 0;     // their program scans
  Nanoseconds last_elapsed_ = 0;    // of the most recent scan/run step
  std::uint64_t last_scans_ = 0;
  bool forces_cleared_ = false;     // `unforce all` removed the program's own FORCE blocks
  std::map<std::string, std::optional<bool>> forces_;  // by address: forced value, or unforced
  std::vector<const Step*> injected_;  // the device steps run on the current bench, in order
};

}  // namespace

void merge_coverage(ProgramCoverage& into, const LoadedProgram* program, const std::vector<std::uint8_t>& flags) {
  for (auto& [p, merged] : into)
    if (p == program) {
      for (std::size_t i = 0; i < merged.size() && i < flags.size(); ++i) merged[i] |= flags[i];
      return;
    }
  into.emplace_back(program, flags);
}

TestOutcome run_test(const TestCase& test, const std::string& file_name, const RuntimeOptions& options,
                     bool record_coverage, bool record_trace) {
  Session session(file_name, options, record_coverage, record_trace);
  return session.run(test);
}

}  // namespace softslc::testing
