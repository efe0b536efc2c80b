#include "tools/testrunner/test_loader.h"

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>
#include <tuple>

#include "modules/module_setup.h"
#include "parser/checker.h"
#include "parser/input_file.h"
#include "parser/loader.h"
#include "tools/testrunner/test_parser.h"

namespace softslc::testing {

namespace {

// Regular files only, with a size limit; a UTF-8 BOM dropped, UTF-16 refused (input_file.h).
std::optional<std::string> read_file(const std::filesystem::path& path, std::string& error) {
  InputFile in = read_input_file(path);
  if (!in.ok) {
    error = in.error;
    return std::nullopt;
  }
  return std::move(in.contents);
}

std::string cache_key(const std::filesystem::path& path) {
  std::error_code ec;
  auto canonical = std::filesystem::weakly_canonical(path, ec);
  return ec ? path.lexically_normal().string() : canonical.string();
}

// The value a literal writes into an operand of `width` (validated by the caller).
Value value_for(const Literal& l, int width) { return value_for_width(l, width, nullptr).value_or(Value{}); }

bool is_word_file(FileType t) {
  return t == FileType::Integer || t == FileType::Bit || t == FileType::Float || t == FileType::Long ||
         t == FileType::Status || t == FileType::Ascii;
}

// Checks one test file's tests against their programs and resolves its snapshots.
class Checker {
 public:
  Checker(TestFileLoad& out, const std::filesystem::path& dir, ProgramCache& cache)
      : out_(out), dir_(dir), display_dir_(std::filesystem::path(out.file.name).parent_path()), cache_(cache) {}

  void run() {
    for (auto& tc : out_.file.tests) check_test(tc);
    out_.diagnostics.sort_by_position();
  }

 private:
  void error(Location at, std::string message) {
    if (seen_.insert({at.line, at.column, message}).second) out_.diagnostics.error(at.line, at.column, std::move(message));
  }

  // A path as written in the test file: where it is, and how messages show it.
  std::pair<std::filesystem::path, std::string> locate(const std::string& path_text) const {
    const std::filesystem::path written(path_text);
    if (written.is_absolute()) return {written, written.generic_string()};
    return {dir_ / written, (display_dir_ / written).lexically_normal().generic_string()};
  }

  ProgramCache::Entry* program_for(const TestCase& tc) {
    const auto [actual, display] = locate(tc.program_path);
    const auto [bench, bench_display] =
        tc.bench_path.empty() ? std::pair<std::filesystem::path, std::string>{} : locate(tc.bench_path);
    std::optional<ProcessorModel> processor;
    if (!tc.program_processor.empty()) {
      std::string why;
      processor = parse_processor_spec(tc.program_processor, why);
      if (!processor) {
        error(tc.program_processor_loc, "processor " + why);
        return nullptr;
      }
    }
    std::vector<ProgramCache::Peer> peers;
    for (const auto& p : tc.peers) {
      const auto [peer_actual, peer_display] = locate(p.path);
      peers.push_back({p.name, peer_actual, peer_display, p.node, p.ip, p.network, p.df1, p.df1_options, p.df1_text,
                       p.modbus, p.modbus_text});
    }
    auto& entry = cache_.load(actual, display, bench, bench_display, processor ? &*processor : nullptr, peers, tc.node,
                              tc.ip, {tc.channel1_node, tc.channel1_network, tc.channel0_df1, tc.channel0_text});
    if (!entry.program) {
      if (!entry.errors.empty() && reported_.insert(display + "\n" + bench_display).second)
        out_.program_diagnostics += entry.errors;
      if (!entry.failed_peer.empty()) {
        for (const auto& p : tc.peers)
          if (p.name == entry.failed_peer)
            error(p.loc, "peer '" + p.name + "' did not load (its errors are listed above)");
        if (entry.failed_peer == "*") {
          // The network's error names the peer it is about ("peer SRV: ..."): point at that line.
          Location where = tc.peers.empty() ? tc.program_loc : tc.peers.front().loc;
          if (tc.channel1_loc.line && entry.errors.find("channel 1") != std::string::npos) where = tc.channel1_loc;
          if (tc.channel0_loc.line && entry.errors.find("channel 0") != std::string::npos) where = tc.channel0_loc;
          for (const auto& p : tc.peers)
            if (entry.errors.find("error: peer " + p.name + ": ") != std::string::npos) {
              where = p.loc;
              break;
            }
          error(where, "the MSG network did not build (its errors are listed above)");
        }
      } else if (entry.bench_failed)
        error(tc.bench_loc, "bench '" + tc.bench_path + "' did not load (its errors are listed above)");
      else
        error(tc.program_loc, "program '" + tc.program_path + "' did not load" +
                                  (entry.errors.empty() ? "" : " (its errors are listed above)"));
      return nullptr;
    }
    return &entry;
  }

  void check_test(TestCase& tc) {
    ProgramCache::Entry* entry = program_for(tc);
    if (!entry) {
      for (const auto& s : tc.steps)
        if (s.kind == Step::Kind::Snapshot) unavailable_.insert(s.name);
      return;
    }
    tc.program = entry->program;
    // The steps that lead from a fresh Runtime to the current point, for snapshots.
    std::shared_ptr<const LoadedProgram> program = entry->program;
    Runtime* probe = entry->probe.get();
    Mode initial = tc.initial_mode;
    std::vector<Step> history;
    // After a restore that failed, the steps are still checked against the current program (an
    // independent error is worth reporting), but a snapshot taken there is not defined, so that
    // restoring it later does not report a second, dependent error.
    bool broken = false;
    for (auto& step : tc.steps) {
      if (step.kind == Step::Kind::Restore) {
        auto it = snapshots_.find(step.name);
        if (it == snapshots_.end()) {
          if (!unavailable_.count(step.name))
            error(step.loc, "no snapshot '" + step.name + "' is defined above this line (a 'snapshot " + step.name +
                                "' step of an earlier test in this file)");
          broken = true;
          continue;
        }
        step.snapshot = it->second;
        program = it->second->program;
        probe = cache_.probe_for(program.get());
        initial = it->second->initial_mode;
        history = it->second->steps;
        broken = false;
        continue;
      }
      if (step.kind == Step::Kind::Snapshot) {
        if (auto it = snapshots_.find(step.name); it != snapshots_.end()) {
          error(step.loc, "snapshot '" + step.name + "' is already defined at line " + std::to_string(it->second->loc.line));
          continue;
        }
        if (broken) {
          unavailable_.insert(step.name);
          continue;
        }
        auto snap = std::make_shared<Snapshot>();
        snap->name = step.name;
        snap->loc = step.loc;
        snap->program = program;
        snap->initial_mode = initial;
        snap->steps = history;
        snapshots_[step.name] = std::move(snap);
        continue;
      }
      check_step(step, *program, *probe);
      history.push_back(step);
    }
  }

  // ---- Operands ----

  // The program a data operand belongs to: the test's, or the peer its prefix names (B.N7:0).
  const Program* program_of(const DataRef& r, const LoadedProgram& p) {
    if (r.controller.empty()) return &p.program;
    std::string names;
    for (const auto& peer : p.modules.peers) {
      if (peer.name == r.controller) return peer.program.get();
      names += (names.empty() ? "" : ", ") + peer.name;
    }
    error(r.loc, "no peer '" + r.controller + "' on this test's network" +
                     (names.empty() ? std::string(" (the file has no 'peer' lines)") : " (its peers: " + names + ")"));
    return nullptr;
  }

  // The runtime that holds a data operand: the probe, or its peer.
  static Runtime& runtime_of(const DataRef& r, Runtime& probe) {
    Runtime* peer = r.controller.empty() ? nullptr : probe.peer(r.controller);
    return peer ? *peer : probe;
  }

  bool resolve(DataRef& r, const LoadedProgram& p) {
    const Program* program = program_of(r, p);
    if (!program) return false;
    if (!r.symbol.empty()) {
      const Symbol* s = program->find_symbol(r.symbol);
      if (!s || s->name.empty()) {
        error(r.loc, "unknown symbol '" + r.symbol + "': not a SYMBOL of " +
                         (r.controller.empty() ? p.path : "peer " + r.controller));
        return false;
      }
      r.address = s->address;
    }
    // The checker's address rules, as for `run --set` and the Controller API.
    if (auto e = check_tool_address(*program, r.address); !e.empty()) {
      error(r.loc, e);
      return false;
    }
    return true;
  }

  bool probe_read(const DataRef& r, const Address& a, Runtime& probe) {
    if (a.is_indirect() || a.indexed) return true;  // depends on run-time values
    std::string err;
    if (runtime_of(r, probe).get(a, &err)) return true;
    error(r.loc, err);
    return false;
  }

  bool check_range(DataRef& r, Runtime& probe) {
    const Address& a = r.address;
    if (!is_word_file(a.type)) {
      error(r.loc, "a range names whole words of an N, B, F, L, S or A file; name T, C and R sub-elements and I/O "
                   "words one by one");
      return false;
    }
    if (a.has_bit() || a.word >= 0 || a.indexed || a.is_indirect()) {
      error(r.loc, "a range names whole elements: write FILE:FIRST..LAST (for example N11:0..13)");
      return false;
    }
    Address last = a;
    last.element = r.range_last;
    return probe_read(r, a, probe) && probe_read(r, last, probe);
  }

  // A data operand that is read: resolved and present in the data table.
  bool check_readable(DataRef& r, const LoadedProgram& p, Runtime& probe) {
    if (!resolve(r, p)) return false;
    if (r.is_range()) return check_range(r, probe);
    return probe_read(r, r.address, probe);
  }

  bool check_single(DataRef& r, const LoadedProgram& p, Runtime& probe) {
    if (!check_readable(r, p, probe)) return false;
    if (r.is_range()) {
      error(r.loc, "a range can only be compared with '==' and one value per element (expect N11:0..2 == 1 2 3)");
      return false;
    }
    return true;
  }

  // A literal compared with (or written into) an operand of `width` bits.
  bool check_literal(const Literal& l, int width, const std::string& what, bool comparison, CompareOp op) {
    if (l.kind == Literal::Kind::Pattern) {
      if (!comparison || (op != CompareOp::Eq && op != CompareOp::Ne)) {
        error(l.loc, "a bit pattern with x digits can only be compared with == or !=");
        return false;
      }
      if (width == 0) {
        error(l.loc, what + " holds a float; a bit pattern applies to integer words");
        return false;
      }
      if (l.digits > width) {
        error(l.loc, "the pattern has " + std::to_string(l.digits) + " digits but " + what + " has " +
                         std::to_string(width) + " bit(s)");
        return false;
      }
      return true;
    }
    if (width == 0) return true;  // any number compares with, or converts to, a float
    std::string err;
    if (!integer_for_width(l, width, &err)) {
      error(l.loc, err);
      return false;
    }
    return true;
  }

  // ---- Steps ----

  void check_step(Step& s, const LoadedProgram& p, Runtime& probe) {
    switch (s.kind) {
      case Step::Kind::Set: check_set(s, p, probe); return;
      case Step::Kind::Force:
      case Step::Kind::Unforce: check_force(s, p, probe); return;
      case Step::Kind::ExpectWords: check_words(s, p, probe); return;
      case Step::Kind::RunUntil:
      case Step::Kind::Expect: check_condition(s.condition, p, probe); return;
      case Step::Kind::Device: check_device(s.name, s.name_loc, p, probe); return;
      case Step::Kind::ExpectLog:
        if (!p.program.find_data_log(static_cast<int>(s.count)))
          error(s.loc, "data log queue " + std::to_string(s.count) + " is not configured by the program (no DATALOG " +
                           std::to_string(s.count) + ")");
        return;
      default: return;
    }
  }

  // A bench device named by a `device` step or an observation. Which changes it accepts can
  // depend on its state, so those are checked when the step runs (a refusal fails the test with
  // the module's reason).
  bool check_device(const std::string& name, Location at, const LoadedProgram& p, Runtime& probe) {
    const auto names = probe.devices();
    if (std::find(names.begin(), names.end(), name) != names.end()) return true;
    std::string known;
    for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
    error(at, "no bench device '" + name + "'" +
                  (p.bench_path.empty() ? std::string(" (this test has no bench: add 'bench FILE.bench')")
                                        : " in " + p.bench_path + (known.empty() ? "" : " (its devices: " + known + ")")));
    return false;
  }

  void check_observation(const DeviceRef& d, const LoadedProgram& p, Runtime& probe) {
    if (!check_device(d.name, d.name_loc, p, probe)) return;
    if (!probe.observe(d.name, d.what))
      error(d.loc, "device '" + d.name + "' has no observable '" + d.what +
                       "' (the observations of each device kind are listed in docs/bench-format.md)");
  }

  void check_set(Step& s, const LoadedProgram& p, Runtime& probe) {
    DataRef& t = s.target;
    if (!resolve(t, p)) return;
    if (t.is_range() && !check_range(t, probe)) return;
    const std::size_t n = static_cast<std::size_t>(t.range_size());
    if (s.values.size() != n) {
      const Location at = s.values.size() > n ? s.values[n].loc : t.loc;
      error(at, t.is_range() ? t.spelling + " has " + std::to_string(n) + " element(s) but " +
                                   std::to_string(s.values.size()) + " value(s) follow"
                             : "set writes one value to one address; a range (set N7:0..3 = 1 2 3 4) takes one "
                               "value per element");
      return;
    }
    const int width = width_of(t.address);
    bool ok = true;
    for (const auto& v : s.values) ok = check_literal(v, width, t.describe(), false, CompareOp::Eq) && ok;
    if (!ok || t.is_range() || t.address.is_indirect() || t.address.indexed) return;
    // Writing on the probe applies the runtime's own rules: an I: address needs a module with
    // that input in its slot, an M0/M1 address a module that accepts the access.
    if (auto st = runtime_of(t, probe).set(t.address, value_for(s.values[0], width)); !st) error(t.loc, st.message);
  }

  void check_force(Step& s, const LoadedProgram& p, Runtime& probe) {
    if (!s.target.controller.empty()) {
      error(s.target.loc, "forces apply to the program's own I/O; a peer's (" + s.target.spelling +
                              ") cannot be forced from a test yet");
      return;
    }
    if (!resolve(s.target, p)) return;
    const Address& a = s.target.address;
    if (s.target.is_range() || !is_io(a.type) || a.bit < 0 || a.indexed || a.is_indirect()) {
      error(s.target.loc, "only I: and O: bits can be forced, as on the SLC ('" + s.target.describe() + "' is not one)");
      return;
    }
    const std::string addr = to_string(a);
    if (s.kind == Step::Kind::Force) {
      if (!check_literal(s.values.at(0), 1, s.target.describe(), false, CompareOp::Eq)) return;
      if (auto st = probe.force(addr, s.values[0].integer != 0); !st) {
        error(s.target.loc, st.message);
        return;
      }
    }
    if (auto st = probe.unforce(addr); !st) error(s.target.loc, st.message);
  }

  void check_words(Step& s, const LoadedProgram& p, Runtime& probe) {
    if (!check_readable(s.target, p, probe)) return;
    const int n = s.target.range_size();
    if (static_cast<int>(s.values.size()) != n) {
      const Location at = static_cast<int>(s.values.size()) > n ? s.values[static_cast<std::size_t>(n)].loc : s.target.loc;
      error(at, s.target.spelling + " has " + std::to_string(n) + " element(s) but " + std::to_string(s.values.size()) +
                    " value(s) follow");
      return;
    }
    const int width = width_of(s.target.address);
    for (const auto& v : s.values) check_literal(v, width, s.target.spelling, true, CompareOp::Eq);
  }

  void check_condition(Condition& c, const LoadedProgram& p, Runtime& probe) {
    switch (c.kind) {
      case Condition::Kind::And:
      case Condition::Kind::Or:
        for (auto& t : c.terms) check_condition(t, p, probe);
        return;
      case Condition::Kind::Compare: break;
      default: return;
    }
    Comparison& k = c.compare;
    if (k.lhs.kind == Operand::Kind::Device) {
      check_observation(k.lhs.device, p, probe);
      if (k.rhs.kind == Operand::Kind::Data) {
        check_single(k.rhs.data, p, probe);
        return;
      }
      // Observations are 64-bit integers: a value must be an integer (hexadecimal and binary
      // patterns up to 64 bits).
      for (const Literal* l : {&k.rhs.literal, k.op == CompareOp::In ? &k.high.literal : nullptr})
        if (l && l->kind == Literal::Kind::Float) error(l->loc, "a device observation is an integer; write an integer");
      return;
    }
    if (k.lhs.kind == Operand::Kind::Elapsed || k.lhs.kind == Operand::Kind::Scans) {
      if (k.op == CompareOp::In) {
        const bool empty = k.lhs.kind == Operand::Kind::Elapsed ? k.rhs.duration > k.high.duration
                                                                : k.rhs.count > k.high.count;
        if (empty) error(k.rhs.loc, "empty range: " + k.rhs.spelling + ".." + k.high.spelling);
      }
      return;
    }
    if (!check_single(k.lhs.data, p, probe)) return;
    const int width = width_of(k.lhs.data.address);
    const std::string what = k.lhs.data.describe();
    if (k.rhs.kind == Operand::Kind::Data) {
      check_single(k.rhs.data, p, probe);
      return;
    }
    const bool low_ok = check_literal(k.rhs.literal, width, what, true, k.op);
    if (k.op != CompareOp::In) return;
    const bool high_ok = check_literal(k.high.literal, width, what, true, CompareOp::In);
    if (!low_ok || !high_ok) return;
    const auto number = [&](const Literal& l) {
      return width == 0 || l.kind == Literal::Kind::Float
                 ? (l.kind == Literal::Kind::Float ? l.real : static_cast<double>(l.integer))
                 : static_cast<double>(*integer_for_width(l, width, nullptr));
    };
    if (number(k.rhs.literal) > number(k.high.literal))
      error(k.rhs.loc, "empty range: " + k.rhs.spelling + ".." + k.high.spelling);
  }

  TestFileLoad& out_;
  std::filesystem::path dir_;
  std::filesystem::path display_dir_;
  ProgramCache& cache_;
  std::set<std::tuple<std::uint32_t, std::uint32_t, std::string>> seen_;
  std::set<std::string> reported_;
  std::map<std::string, std::shared_ptr<const Snapshot>> snapshots_;
  std::set<std::string> unavailable_;  // snapshots whose test could not be checked
};

}  // namespace

int width_of(const Address& a) {
  if (a.has_bit()) return 1;
  if (a.type == FileType::Float) return 0;
  if (a.type == FileType::Long) return 32;
  // HSC:0.ACC, .HIP, .LOP, .OVF, .UNF (parser/address.h hsc::).
  if (is_function_file(a.type) && function_word_is_long(a.file, a.word)) return 32;
  return 16;
}

ProgramCache::Entry& ProgramCache::load(const std::filesystem::path& path, const std::string& display,
                                        const std::filesystem::path& bench, const std::string& bench_display,
                                        const ProcessorModel* pasted_processor, const std::vector<Peer>& peers,
                                        int node, std::uint32_t ip, const ChannelOneSpec& channel1) {
  std::string key = cache_key(path) + "\n" + (bench.empty() ? std::string() : cache_key(bench)) + "\n" +
                    (pasted_processor ? pasted_processor->catalog + ":" + pasted_processor->series : std::string());
  const bool networked = !peers.empty() || ip != 0 || channel1.node != 0 || channel1.channel0_df1;
  if (networked) {
    key += "\nnode " + std::to_string(node) + " ip " + std::to_string(ip) + " channel 1 node " +
           std::to_string(channel1.node) + " network " + channel1.network;
    if (channel1.channel0_df1) key += "\nchannel 0 df1" + channel1.channel0_text;
    for (const auto& p : peers)
      key += "\npeer " + p.name + " " + std::to_string(p.node) + " " + std::to_string(p.ip) + " " + p.network + " " +
             (p.df1 ? "df1" + p.df1_text + " " : std::string()) +
             (p.modbus ? "modbus" + p.modbus_text + " " : std::string()) + cache_key(p.path);
  }
  if (auto it = entries_.find(key); it != entries_.end()) return it->second;
  Entry& e = entries_[key];
  std::string error;
  auto text = read_file(path, error);
  if (!text) {
    e.errors = display + ": error: " + error + "\n";
    return e;
  }
  softslc::LoadResult lr;
  if (is_pasted_rungs(*text)) {
    const ProcessorModel* processor = pasted_processor ? pasted_processor
                                      : default_pasted_processor_ ? &*default_pasted_processor_
                                                                  : nullptr;
    if (!processor) {
      e.errors = display + ": error: these are pasted rungs (no START or LADDER statement): name their processor, " +
                 "`program " + display + " processor Bul.1763` in the test file or `softslc test --processor Bul.1763`\n";
      return e;
    }
    lr = load_pasted_rungs(std::move(*text), display, *processor);
  } else if (pasted_processor) {
    e.errors = display + ": error: 'processor' names the processor of pasted rungs, and this is a whole program " +
               "with its own; remove 'processor' from its program line\n";
    return e;
  } else {
    lr = load_program_bytes(std::move(*text), display);  // .SLC text or .RSS project
  }
  if (!lr.ok()) {
    e.errors = lr.render_diagnostics();
    return e;
  }
  ModuleSetup setup;
  if (bench.empty()) {
    setup = load_module_setup(*lr.program, std::nullopt);
  } else {
    auto bench_text = read_file(bench, error);
    if (!bench_text) {
      e.errors = bench_display + ": error: " + error + "\n";
      e.bench_failed = true;
      return e;
    }
    setup = load_module_setup_text(*lr.program, std::move(*bench_text), bench_display);
  }
  if (!setup.ok()) {
    e.errors = setup.render(display, lr.source);
    e.bench_failed = setup.bench_diagnostics.has_errors();
    return e;
  }
  // The MSG network's other controllers: each program with its own SLOT lines (no bench).
  for (const auto& p : peers) {
    auto peer_text = read_file(p.path, error);
    if (!peer_text) {
      e.errors = p.display + ": error: " + error + "\n";
      e.failed_peer = p.name;
      return e;
    }
    softslc::LoadResult plr = load_program_bytes(std::move(*peer_text), p.display);
    if (!plr.ok()) {
      e.errors = plr.render_diagnostics();
      e.failed_peer = p.name;
      return e;
    }
    ModuleSetup peer_setup = load_module_setup(*plr.program, std::nullopt);
    if (!peer_setup.ok()) {
      e.errors = peer_setup.render(p.display, plr.source);
      e.failed_peer = p.name;
      return e;
    }
    PeerController peer;
    peer.name = p.name;
    peer.node = p.node;
    peer.ip = p.ip;
    peer.network = p.network;
    peer.df1 = p.df1;
    peer.modbus = p.modbus;
    if (p.df1) peer_setup.options.channel0_df1 = p.df1_options;
    peer.program = std::make_shared<const Program>(std::move(*plr.program));
    peer.options = std::make_shared<const RuntimeOptions>(std::move(peer_setup.options));
    setup.options.peers.push_back(std::move(peer));
  }
  setup.options.node = node;
  setup.options.ip = ip;
  setup.options.channel1_node = channel1.node;
  setup.options.channel1_network = channel1.network;
  setup.options.channel0_df1 = channel1.channel0_df1;
  RuntimeResult rr = Runtime::create(*lr.program, setup.options);
  if (!rr.ok()) {
    for (const auto& err : rr.errors) e.errors += display + ": error: " + err.to_string() + "\n";
    if (networked) e.failed_peer = "*";
    return e;
  }
  auto loaded = std::make_shared<LoadedProgram>();
  loaded->path = display;
  loaded->bench_path = bench_display;
  loaded->program = std::move(*lr.program);
  loaded->modules = std::move(setup.options);
  e.program = std::move(loaded);
  e.probe = std::move(rr.runtime);
  return e;
}

Runtime* ProgramCache::probe_for(const LoadedProgram* program) {
  for (auto& [key, e] : entries_)
    if (e.program.get() == program) return e.probe.get();
  return nullptr;
}

std::string TestFileLoad::render() const {
  return program_diagnostics + render_all(diagnostics, file.name, file.source);
}

TestFileLoad load_test_text(std::string text, const std::string& display, const std::filesystem::path& dir,
                            ProgramCache& cache) {
  TestFileLoad out;
  ParseResult pr = parse_test_text(std::move(text), display);
  out.file = std::move(pr.file);
  out.diagnostics = std::move(pr.diagnostics);
  Checker(out, dir, cache).run();
  return out;
}

TestFileLoad load_test_file(const std::filesystem::path& path, const std::string& display, ProgramCache& cache) {
  std::string error;
  auto text = read_file(path, error);
  if (!text) {
    TestFileLoad out;
    out.file.name = display;
    out.diagnostics.error(0, 0, error);
    return out;
  }
  return load_test_text(std::move(*text), display, path.parent_path(), cache);
}

}  // namespace softslc::testing
