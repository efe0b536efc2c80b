#include "tools/controller/controller.h"

#include <fstream>
#include <sstream>

#include "modules/module_setup.h"
#include "parser/address.h"
#include "parser/checker.h"
#include "parser/loader.h"

namespace softslc {

// What every processor of one Controller (and its restores) is built from.
struct Controller::Loaded {
  Program program;
  RuntimeOptions options;
};

namespace {

std::string read_or_throw(const std::filesystem::path& p, const char* what) {
  std::ifstream f(p, std::ios::binary);
  if (!f) throw ControllerError(p.string() + ": error: cannot open the " + what + " file");
  std::ostringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

void check(const RuntimeStatus& st, std::string_view call, std::string_view target) {
  if (!st) throw ControllerError(std::string(call) + " " + std::string(target) + ": " + st.message);
}

}  // namespace

Controller Controller::load(const std::filesystem::path& program, const std::optional<std::filesystem::path>& bench) {
  return from_text(read_or_throw(program, "program"), bench ? read_or_throw(*bench, "bench") : std::string(),
                   program.string(), bench ? bench->string() : std::string());
}

Controller Controller::from_text(std::string program_text, std::string bench_text, std::string name,
                                 std::string bench_name) {
  LoadResult lr = load_program_bytes(std::move(program_text), name);  // .SLC text or .RSS project
  if (!lr.ok()) throw ControllerError(lr.render_diagnostics());
  ModuleSetup setup = bench_text.empty() ? load_module_setup(*lr.program, std::nullopt)
                                         : load_module_setup_text(*lr.program, std::move(bench_text), bench_name);
  if (!setup.ok()) throw ControllerError(setup.render(lr.source_name, lr.source));
  auto loaded = std::make_shared<Loaded>();
  loaded->program = std::move(*lr.program);
  loaded->options = std::move(setup.options);
  Controller c(std::move(loaded));
  c.set_mode(Mode::Run);
  c.journal_.clear();  // the starting mode is part of the download state, not of a snapshot
  return c;
}

Controller::Controller(std::shared_ptr<const Loaded> loaded) : loaded_(std::move(loaded)) { fresh_runtime(); }
Controller::Controller(Controller&&) noexcept = default;
Controller& Controller::operator=(Controller&&) noexcept = default;
Controller::~Controller() = default;

void Controller::fresh_runtime() {
  RuntimeResult r = Runtime::create(loaded_->program, loaded_->options);
  if (!r.ok()) throw ControllerError("the program did not compile:\n" + r.render_errors());
  runtime_ = std::move(r.runtime);
}

std::string Controller::address_of(std::string_view target) const {
  if (const Symbol* s = loaded_->program.find_symbol(std::string(target)); s && !s->name.empty())
    return to_string(s->address);
  // The checker's address rules, as for `run --set` and test files: no bit 16-31, no slot or
  // element the program cannot name.
  if (auto a = parse_address(target))
    if (auto error = check_tool_address(loaded_->program, *a); !error.empty()) throw ControllerError(error);
  return std::string(target);
}

void Controller::apply(const ControllerCall& c, bool record) {
  Runtime& rt = *runtime_;
  switch (c.kind) {
    case ControllerCall::Kind::Set: check(rt.set(c.target, Value::of_int(c.integer)), "set", c.target); break;
    case ControllerCall::Kind::SetFloat: check(rt.set(c.target, Value::of_float(c.real)), "set", c.target); break;
    case ControllerCall::Kind::Force: check(rt.force(c.target, c.integer != 0), "force", c.target); break;
    case ControllerCall::Kind::Unforce: check(rt.unforce(c.target), "unforce", c.target); break;
    case ControllerCall::Kind::Scans: rt.scan(static_cast<int>(c.integer)); break;
    case ControllerCall::Kind::RunFor: rt.run_for(c.integer); break;
    case ControllerCall::Kind::SetMode: check(rt.set_mode(c.mode), "set_mode", to_string(c.mode)); break;
    case ControllerCall::Kind::ClearFault: rt.clear_fault(); break;
    case ControllerCall::Kind::Inject: check(rt.inject(c.target, c.change, c.args), "inject", c.target); break;
  }
  if (record) journal_.push_back(c);
}

void Controller::set(std::string_view target, std::int64_t value) {
  ControllerCall c;
  c.kind = ControllerCall::Kind::Set;
  c.target = address_of(target);
  c.integer = value;
  // A bit takes 0/1 (the runtime would take any non-zero integer as 1).
  if (auto a = parse_address(c.target); a && a->has_bit() && value != 0 && value != 1)
    throw ControllerError("set " + std::string(target) + ": a bit takes 0 or 1, not " + std::to_string(value));
  apply(c, true);
}

void Controller::set_float(std::string_view target, double value) {
  ControllerCall c;
  c.kind = ControllerCall::Kind::SetFloat;
  c.target = address_of(target);
  c.real = value;
  apply(c, true);
}

Value Controller::get(std::string_view target) const {
  std::string error;
  auto v = runtime_->get(address_of(target), &error);
  if (!v) throw ControllerError("get " + std::string(target) + ": " + error);
  return *v;
}

void Controller::force(std::string_view target, bool on) {
  ControllerCall c;
  c.kind = ControllerCall::Kind::Force;
  c.target = address_of(target);
  c.integer = on ? 1 : 0;
  apply(c, true);
}

void Controller::unforce(std::string_view target) {
  ControllerCall c;
  c.kind = ControllerCall::Kind::Unforce;
  c.target = address_of(target);
  apply(c, true);
}

int Controller::scan(int n) {
  if (n < 0) throw ControllerError("scan: the count must not be negative");
  ControllerCall c;
  c.kind = ControllerCall::Kind::Scans;
  c.integer = n;
  journal_.push_back(c);
  return runtime_->scan(n);
}

int Controller::run_for(Nanoseconds duration) {
  ControllerCall c;
  c.kind = ControllerCall::Kind::RunFor;
  c.integer = duration;
  journal_.push_back(c);
  return runtime_->run_for(duration);
}

bool Controller::run_until(const std::function<bool(const Controller&)>& condition, Nanoseconds limit) {
  // Recorded as a run for the virtual time it took: run_for of that time runs the same whole
  // scans (the last one ends exactly then), so a replay reaches the same state.
  const VirtualTime start = runtime_->now();
  const bool held = runtime_->run_until([&](const Runtime&) { return condition(*this); }, limit);
  if (runtime_->now() > start) {
    ControllerCall c;
    c.kind = ControllerCall::Kind::RunFor;
    c.integer = runtime_->now() - start;
    journal_.push_back(c);
  }
  return held;
}

VirtualTime Controller::now() const { return runtime_->now(); }
std::uint64_t Controller::scans() const { return runtime_->stats().scans; }

void Controller::set_mode(Mode m) {
  ControllerCall c;
  c.kind = ControllerCall::Kind::SetMode;
  c.mode = m;
  apply(c, true);
}

Mode Controller::mode() const { return runtime_->mode(); }
const std::optional<FaultInfo>& Controller::fault() const { return runtime_->fault(); }

void Controller::clear_fault() {
  ControllerCall c;
  c.kind = ControllerCall::Kind::ClearFault;
  apply(c, true);
}

void Controller::inject(std::string_view device, std::string_view change, std::vector<std::string> args) {
  ControllerCall c;
  c.kind = ControllerCall::Kind::Inject;
  c.target = std::string(device);
  c.change = std::string(change);
  c.args = std::move(args);
  apply(c, true);
}

std::vector<std::int64_t> Controller::observe(std::string_view device, std::string_view what) const {
  auto v = runtime_->observe(device, what);
  if (!v) throw ControllerError("observe " + std::string(device) + " '" + std::string(what) + "': no such device or observation");
  return *v;
}

std::vector<std::string> Controller::devices() const { return runtime_->devices(); }

Controller::Snapshot Controller::snapshot() const {
  Snapshot s;
  s.journal_ = journal_;
  return s;
}

void Controller::restore(const Snapshot& s) {
  fresh_runtime();
  journal_.clear();
  ControllerCall run;
  run.kind = ControllerCall::Kind::SetMode;
  run.mode = Mode::Run;
  apply(run, false);
  for (const auto& c : s.journal_) apply(c, true);
}

Runtime& Controller::runtime() { return *runtime_; }
const Runtime& Controller::runtime() const { return *runtime_; }
const Program& Controller::program() const { return loaded_->program; }

}  // namespace softslc
