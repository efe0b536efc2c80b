#include "commands.h"

#include <fstream>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <thread>
#include <iostream>
#include <sstream>

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "vm/atomic_file.h"
#include "run_trace.h"
#include "instructions/instruction_table.h"
#include "instructions/processor.h"
#include "modules/throughput/throughput_json.h"
#include "parser/checker.h"
#include "parser/formatter.h"
#include "parser/input_file.h"
#include "parser/json_document.h"
#include "parser/loader.h"
#include "modules/module_setup.h"
#include "vm/disassembler.h"
#include "vm/duration.h"
#include "vm/profile_scan_time_model.h"
#include "vm/runtime.h"
#include "vm/scantime.h"
#include "vm/state_file.h"
#include "tools/testrunner/test_loader.h"
#include "tools/testrunner/values.h"

namespace softslc::cli {

namespace {

// Prints the diagnostics and a one-line summary to stderr.
void report(const LoadResult& r) {
  std::cerr << r.render_diagnostics();
  auto e = r.diagnostics.error_count();
  auto w = r.diagnostics.warning_count();
  if (e > 0 || w > 0)
    std::cerr << r.source_name << ": " << e << " error" << (e == 1 ? "" : "s") << ", " << w << " warning"
              << (w == 1 ? "" : "s") << "\n";
}

// `--processor` on run and scantime: the program re-checked with that processor's rules
// (retarget_program). Prints the errors and returns nullopt when it does not check.
std::optional<Program> retarget(const LoadResult& r, const ProcessorModel& p, const char* command) {
  DiagnosticList diags;
  Program out = retarget_program(*r.program, p, diags);
  if (!diags.has_errors()) return out;
  diags.sort_by_position();
  for (const auto& d : diags.items())
    if (d.severity == Severity::Error) std::cerr << render(d, r.source_name, r.source);
  std::cerr << "softslc " << command << ": the program does not check for " << p.display_name << " (" << p.catalog
            << "); " << diags.error_count() << " error" << (diags.error_count() == 1 ? "" : "s") << "\n";
  return std::nullopt;
}

std::optional<ProcessorModel> parse_processor_option(const std::string& text, std::string& error);

// The program a command works on. Pasted rungs (bare `SOR ... EOR` lines, parser/loader.h) are
// program file 2 of the processor `--processor` names; without one they are a single clear
// error rather than one "rung before any LADDER statement" per rung.
LoadResult load_input(const std::string& file, const std::string& processor_option, const char* command) {
  InputFile in = read_input_file(file, InputKind::Binary);
  if (!in.ok || !is_pasted_rungs(in.contents)) return load_program_file(file);  // a project file never starts with SOR
  LoadResult r;
  r.source_name = file;
  if (processor_option.empty()) {
    r.diagnostics.error(0, 0, std::string("these are pasted rungs (no START or LADDER statement): name the processor, for example `softslc ") +
                                  command + " --processor Bul.1763 " + file + "`");
    return r;
  }
  std::string error;
  auto m = parse_processor_option(processor_option, error);
  if (!m) {
    r.diagnostics.error(0, 0, error);
    return r;
  }
  return load_pasted_rungs(std::move(in.contents), file, *m);
}

// `--processor` on check and run: the processor it names and the program re-checked for it
// (retarget), so that `check --processor X` exit 0 means `run --processor X` loads it. `exit` is
// kUsage for an unknown catalog, kInputError when the program does not check for it; without the
// option, nothing is overridden.
struct ProcessorOverride {
  std::optional<ProcessorModel> processor;
  std::optional<Program> program;
  int exit = kOk;
};

ProcessorOverride override_processor(const LoadResult& r, const std::string& option, const char* command) {
  ProcessorOverride out;
  if (option.empty()) return out;
  std::string error;
  out.processor = parse_processor_option(option, error);
  if (!out.processor) {
    std::cerr << "softslc " << command << ": " << error << "\n";
    out.exit = kUsage;
    return out;
  }
  out.program = retarget(r, *out.processor, command);
  if (!out.program) out.exit = kInputError;
  return out;
}

}  // namespace

int run_check(const CheckOptions& o) {
  auto r = load_input(o.file, o.processor, "check");
  report(r);
  if (!r.ok()) return kInputError;
  // `--processor` on a program with its own START line checks it as `run --processor` runs it:
  // re-checked with that processor's rules, so exit 0 still means `run` (with the same option)
  // loads it. For pasted rungs load_input already made it the program's processor.
  ProcessorOverride over = override_processor(r, o.processor, "check");
  if (over.exit != kOk) return over.exit;
  CompileOptions copts;
  copts.processor = over.processor;
  const Program& program = over.program ? *over.program : *r.program;
  // The specialty modules' own configuration rules (G files, M-file sizes, ID codes), each
  // diagnostic quoting the manual's rule.
  DiagnosticList modules;
  check_module_configuration(program, modules);
  if (!modules.has_errors()) {
    // One source of truth: `check` compiles the program exactly as `run` does (the same module
    // setup, no bench), so every limit the compiler enforces — rungs per file, operand types,
    // module instructions — is a `check` error too, and exit 0 means `run` loads it.
    copts.module_instruction = load_module_setup(program, std::nullopt).options.module_instruction;
    for (const auto& e : compile(program, copts).errors)
      modules.error(e.pos.line, e.pos.column, e.to_string());
  }
  modules.sort_by_position();
  std::cerr << render_all(modules, r.source_name, r.source);
  return modules.has_errors() ? kInputError : kOk;
}

int run_fmt(const FmtOptions& o) {
  auto r = load_program_file(o.file);
  report(r);
  if (!r.ok()) return kInputError;
  std::string text = format_program(*r.program);
  if (o.output.empty() || o.output == "-") {
    std::cout << text;
    return std::cout ? kOk : kInputError;
  }
  if (auto err = write_file_atomically(o.output, text); !err.empty()) {
    std::cerr << "softslc fmt: " << err << "\n";
    return kInputError;
  }
  return kOk;
}

namespace {

double to_us(Nanoseconds ns) { return static_cast<double>(ns) / 1000.0; }

std::string us_text(Nanoseconds ns) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", to_us(ns));
  return buf;
}

std::string pad(const std::string& s, std::size_t w) { return s.size() >= w ? s : std::string(w - s.size(), ' ') + s; }

// "1747-L524:B" → catalog and series.
std::optional<ProcessorModel> parse_processor_option(const std::string& text, std::string& error) {
  auto m = parse_processor_spec(text, error);
  if (!m) error = "--processor " + error;
  return m;
}

nlohmann::json prediction_json(const ScanTimePrediction& t) {
  nlohmann::json j;
  j["processor"] = t.catalog;
  j["timing_key"] = t.processor;
  j["profile"] = t.profile_name;
  j["uses_estimates"] = t.uses_estimates;
  j["rungs"] = nlohmann::json::array();
  for (const auto& r : t.rungs)
    j["rungs"].push_back({{"file", r.file}, {"rung", r.rung}, {"worst_us", to_us(r.worst)}, {"best_us", to_us(r.best)},
                          {"mfile_us", to_us(r.mfile)}, {"mfile_accesses", r.mfile_accesses}});
  j["files"] = nlohmann::json::array();
  for (const auto& f : t.files)
    j["files"].push_back({{"file", f.file}, {"worst_us", to_us(f.worst)}, {"best_us", to_us(f.best)}, {"mfile_us", to_us(f.mfile)}});
  j["housekeeping_us"] = to_us(t.housekeeping);
  j["io_scan_us"] = to_us(t.io_scan);
  j["overhead_us"] = to_us(t.overhead);
  j["total_worst_us"] = to_us(t.total_worst);
  j["total_best_us"] = to_us(t.total_best);
  j["total_mfile_us"] = to_us(t.total_mfile);
  j["hot_spots"] = nlohmann::json::array();
  for (const auto& h : t.hot_spots)
    j["hot_spots"].push_back({{"file", h.file}, {"rung", h.rung}, {"mfile_us", to_us(h.mfile)}, {"remedies", h.remedies}});
  j["notes"] = t.notes;
  return j;
}

void print_prediction(const ScanTimePrediction& t, std::ostream& out) {
  out << "Predicted scan time on " << t.catalog << " (timing profile \"" << t.profile_name << "\")\n\n";
  out << "file  rung    worst us     best us   M-file us\n";
  for (const auto& r : t.rungs)
    out << pad(std::to_string(r.file), 4) << pad(std::to_string(r.rung), 6) << pad(us_text(r.worst), 12)
        << pad(us_text(r.best), 12) << pad(us_text(r.mfile), 12) << "\n";
  out << "\nfile           worst us     best us   M-file us\n";
  for (const auto& f : t.files)
    out << pad(std::to_string(f.file), 4) << "      " << pad(us_text(f.worst), 12) << pad(us_text(f.best), 12)
        << pad(us_text(f.mfile), 12) << "\n";
  out << "\noverhead: housekeeping " << us_text(t.housekeeping) << " us + I/O scan " << us_text(t.io_scan)
      << " us = " << us_text(t.overhead) << " us\n";
  out << "whole scan: worst " << us_text(t.total_worst) << " us (every JSR taken), best " << us_text(t.total_best)
      << " us; M-file accesses " << us_text(t.total_mfile) << " us of the worst case\n";
  if (!t.hot_spots.empty()) {
    out << "\nHot spots (M0/M1 access time, most expensive first):\n";
    for (const auto& h : t.hot_spots) {
      out << "  file " << h.file << " rung " << h.rung << ": " << us_text(h.mfile) << " us\n";
      for (const auto& r : h.remedies) out << "    - " << r << "\n";
    }
  }
  for (const auto& n : t.notes) out << "\nnote: " << n << "\n";
}

void print_comparison(const std::vector<ScanTimePrediction>& ts, std::ostream& out) {
  out << "Predicted scan time, worst case / M-file part in us\n\n" << "file  rung";
  for (const auto& t : ts) out << pad(t.catalog + (t.processor.size() > 4 ? " " + t.processor.substr(4) : ""), 24);
  out << "\n";
  for (std::size_t i = 0; i < ts.front().rungs.size(); ++i) {
    out << pad(std::to_string(ts.front().rungs[i].file), 4) << pad(std::to_string(ts.front().rungs[i].rung), 6);
    for (const auto& t : ts) out << pad(us_text(t.rungs[i].worst) + " / " + us_text(t.rungs[i].mfile), 24);
    out << "\n";
  }
  out << "\noverhead  ";
  for (const auto& t : ts) out << pad(us_text(t.overhead), 24);
  out << "\nscan worst";
  for (const auto& t : ts) out << pad(us_text(t.total_worst) + " / " + us_text(t.total_mfile), 24);
  out << "\nscan best ";
  for (const auto& t : ts) out << pad(us_text(t.total_best), 24);
  out << "\n";
  for (const auto& t : ts)
    for (const auto& n : t.notes) out << "\nnote (" << t.catalog << "): " << n << "\n";
}

}  // namespace

int run_scantime(const ScantimeOptions& o) {
  auto r = load_program_file(o.file);
  report(r);
  if (!r.ok()) return kInputError;
  std::vector<ProcessorModel> processors;
  for (const auto& text : o.processors) {
    std::string error;
    auto m = parse_processor_option(text, error);
    if (!m) {
      std::cerr << "softslc scantime: " << error << "\n";
      return kUsage;
    }
    processors.push_back(*m);
  }
  if (processors.empty()) processors.push_back(r.program->processor);
  std::optional<TimingProfile> user;
  if (!o.timing.empty()) {
    try {
      user = load_timing_profile_file(o.timing);
    } catch (const TimingProfileError& e) {
      std::cerr << "softslc scantime: " << e.what() << "\n";
      return kInputError;
    }
  }
  std::vector<ScanTimePrediction> results;
  for (const auto& p : processors) {
    std::optional<TimingProfile> profile;
    if (user && user->processor == p.timing_key()) profile = user;
    else profile = builtin_timing_profile(p.timing_key());
    if (!profile) {
      std::cerr << "softslc scantime: no timing profile for " << p.display_name << " (" << p.catalog
                << "); profiles exist for the SLC 5/02 Series B and C, 5/03, 5/04 and 5/05 and the MicroLogix 1000, "
                   "1100, 1200, 1400 and 1500\n";
      return kInputError;
    }
    // The processor named by --processor applies the same checks as `run --processor`.
    std::optional<Program> program = r.program;
    if (!o.processors.empty()) program = retarget(r, p, "scantime");
    if (!program) return kInputError;
    results.push_back(predict_scan_time(*program, p, *profile));
  }
  if (o.json) {
    if (results.size() == 1) {
      std::cout << json_text(prediction_json(results[0])) << "\n";
    } else {
      auto arr = nlohmann::json::array();
      for (const auto& t : results) arr.push_back(prediction_json(t));
      std::cout << json_text(arr) << "\n";
    }
  } else if (results.size() == 1) {
    print_prediction(results[0], std::cout);
  } else {
    print_comparison(results, std::cout);
  }
  return kOk;
}

namespace {

// An address written on the command line: an address, or a symbol of the program.
// The checker's address rules apply, as in test files and the Controller API.
std::optional<Address> resolve_cli_address(const Program& p, const std::string& text, std::string& error) {
  if (const Symbol* s = p.find_symbol(text)) return s->address;
  auto a = parse_address(text, &error);
  if (!a) {
    error = "'" + text + "' is neither an address nor a symbol of the program (" + error + ")";
    return a;
  }
  error = check_tool_address(p, *a);
  if (!error.empty()) return std::nullopt;
  return a;
}

// Set by SIGINT/SIGTERM; the run loop stops at the end of the current scan and saves its state.
volatile std::sig_atomic_t g_interrupted = 0;
extern "C" void on_interrupt(int sig) { g_interrupted = sig; }

std::string fault_code_text(std::uint16_t code) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%04Xh", code);
  return buf;
}

}  // namespace

int run_run(const RunOptions& o) {
  auto r = load_input(o.file, o.processor, "run");
  report(r);
  if (!r.ok()) return kInputError;
  spdlog::debug("{}: loaded, {} bytes, {} program files", o.file, r.source.size(), r.program->files.size());
  // Under --processor, the program as that processor sees it (checked with its rules).
  ProcessorOverride over = override_processor(r, o.processor, "run");
  if (over.exit != kOk) return over.exit;
  RuntimeOptions options;
  options.processor = over.processor;
  const ProcessorModel processor = over.processor ? *over.processor : r.program->processor;
  const Program& program = over.program ? *over.program : *r.program;
  if (!o.timing.empty()) {
    try {
      auto user = load_timing_profile_file(o.timing);
      if (user.processor != processor.timing_key()) {
        std::cerr << "softslc run: " << o.timing << " is a profile for " << user.processor << ", but the processor is "
                  << processor.display_name << " (" << processor.timing_key() << ")\n";
        return kInputError;
      }
      options.time_model = make_scan_time_model(processor, &user);
    } catch (const TimingProfileError& e) {
      std::cerr << "softslc run: " << e.what() << "\n";
      return kInputError;
    }
  }

  // Parse every --set and --print before running anything, so a typo costs no simulation.
  struct Assignment {
    Address address;
    Value value;
  };
  std::vector<Assignment> assignments;
  for (const auto& text : o.sets) {
    auto eq = text.find('=');
    if (eq == std::string::npos) {
      std::cerr << "softslc run: --set " << text << ": write ADDR=VALUE, for example --set I:1/0=1\n";
      return kUsage;
    }
    std::string error;
    auto a = resolve_cli_address(program, text.substr(0, eq), error);
    if (!a) {
      std::cerr << "softslc run: --set " << text << ": " << error << "\n";
      return kUsage;
    }
    // A value is written as in a test file and converted by the same rule (testing/values.h):
    // it must fit the operand — never wrapped, rounded or squashed.
    auto literal = testing::parse_literal(text.substr(eq + 1), &error);
    if (!literal) {
      std::cerr << "softslc run: --set " << text << ": '" << text.substr(eq + 1)
                << "' is not a value (decimal, negative, 0x.., 0b.., or float)\n";
      return kUsage;
    }
    auto value = testing::value_for_width(*literal, testing::width_of(*a), &error);
    if (!value) {
      std::cerr << "softslc run: --set " << text << ": " << error << "\n";
      return kUsage;
    }
    assignments.push_back({*a, *value});
  }
  std::vector<std::pair<std::string, Address>> prints;
  for (const auto& text : o.prints) {
    std::string error;
    auto a = resolve_cli_address(program, text, error);
    if (!a) {
      std::cerr << "softslc run: --print " << text << ": " << error << "\n";
      return kUsage;
    }
    prints.emplace_back(text, *a);
  }
  for (int q : o.logs)
    if (!program.find_data_log(q)) {
      std::cerr << "softslc run: --log " << q << ": the program configures no data log queue " << q << " (DATALOG)\n";
      return kUsage;
    }
  Nanoseconds checkpoint = 0;
  if (!o.checkpoint.empty()) {
    std::string error;
    auto d = parse_duration(o.checkpoint, &error);
    if (!d || *d <= 0 || o.state.empty()) {
      std::cerr << "softslc run: --checkpoint " << o.checkpoint << ": "
                << (o.state.empty() ? "needs --state FILE" : d ? "must be positive" : error) << "\n";
      return kUsage;
    }
    checkpoint = *d;
  }
  Nanoseconds duration = 0;
  if (!o.for_duration.empty()) {
    std::string error;
    auto d = parse_duration(o.for_duration, &error);
    if (!d) {
      std::cerr << "softslc run: --for " << o.for_duration << ": " << error << "\n";
      return kUsage;
    }
    duration = *d;
  }

  // Modules for every slot (and the bench's simulated field devices, when given). Always set up,
  // so block-transfer programs compile and discrete cards get their real point counts.
  ModuleSetup modules = load_module_setup(
      program, o.bench.empty() ? std::nullopt : std::optional<std::filesystem::path>(o.bench));
  std::cerr << modules.render(r.source_name, r.source);
  if (!modules.ok()) return kInputError;
  options.module_factory = modules.options.module_factory;
  options.module_instruction = modules.options.module_instruction;
  options.field_processes = modules.options.field_processes;
  options.ascii_channel = modules.options.ascii_channel;

  auto created = Runtime::create(program, std::move(options));
  if (!created.ok()) {
    std::cerr << r.source_name << ": error: the program cannot run:\n" << created.render_errors();
    return kInputError;
  }
  Runtime& rt = *created.runtime;
  // Retentive state: the data table as a power cycle leaves it. A bad state file stops the run
  // before anything executes, so the file is never overwritten.
  const std::uint64_t fingerprint = o.state.empty() ? 0 : program_fingerprint(program);
  // One run per state file at a time (a second would lose one run's scans), and a location the
  // save can write — both found now, not after the whole run.
  StateFileLock state_lock;
  if (!o.state.empty()) {
    for (const auto& err : {state_lock.acquire(o.state), check_state_file_writable(o.state)})
      if (!err.empty()) {
        std::cerr << "softslc run: --state " << o.state << ": " << err << "\n";
        return kInputError;
      }
    spdlog::debug("{}: locked; {} stale temporary file(s) of killed saves removed", o.state,
                  state_lock.removed_temporaries());
  }
  if (!o.state.empty()) {
    bool missing = false;
    auto loaded = load_state_file(o.state, fingerprint, rt.data(), o.force_state, &missing, chassis_modules(rt));
    if (!loaded.ok) {
      std::cerr << "softslc run: " << loaded.error << "\n";
      return kInputError;
    }
    for (const auto& w : loaded.warnings) std::cerr << "softslc run: " << o.state << ": warning: " << w << "\n";
    spdlog::debug("{}: {}", o.state, missing ? "does not exist yet: the run starts from the program's data"
                                             : "restored");
  }
  auto save_state = [&]() -> bool {
    if (o.state.empty()) return true;
    if (auto err = save_state_file(o.state, rt.data(), fingerprint, chassis_modules(rt)); !err.empty()) {
      std::cerr << "softslc run: cannot save state: " << err << "\n";
      return false;
    }
    spdlog::debug("{}: saved after scan {}", o.state, rt.stats().scans);
    return true;
  };
  for (const auto& a : assignments)
    if (auto st = rt.set(a.address, a.value); !st) {
      std::cerr << "softslc run: --set " << to_string(a.address) << ": " << st.message << "\n";
      return kUsage;
    }
  // Every --print must name something the data table has: "N7:999 = ?" with exit 0 misled.
  for (const auto& [text, a] : prints) {
    std::string error;
    if (!a.is_indirect() && !a.indexed && !rt.get(a, &error)) {
      std::cerr << "softslc run: --print " << text << ": " << error << "\n";
      return kUsage;
    }
  }
  if (auto st = rt.set_mode(Mode::Run); !st) {
    std::cerr << "softslc run: " << st.message << "\n";
    return kInputError;
  }
  int trace_rc = kOk;
  auto recorder = start_run_trace(o, program, rt, std::cerr, trace_rc);
  if (trace_rc != kOk) return trace_rc;

  // Virtual time is the simulation's only clock; --realtime merely waits for the wall clock to
  // catch up after each scan, for interactive use.
  const auto wall_start = std::chrono::steady_clock::now();
  const VirtualTime virtual_start = rt.now();
  auto pace = [&] {
    if (o.realtime)
      std::this_thread::sleep_until(wall_start + std::chrono::nanoseconds(rt.now() - virtual_start));
  };
  g_interrupted = 0;
  std::signal(SIGINT, on_interrupt);
  std::signal(SIGTERM, on_interrupt);
  VirtualTime next_checkpoint = rt.now() + checkpoint;
  bool saved_ok = true;
  auto after_scans = [&] {
    pace();
    if (checkpoint > 0 && rt.now() >= next_checkpoint) {
      saved_ok &= save_state();
      next_checkpoint = rt.now() + checkpoint;
    }
  };
  auto one_scan = [&] {
    rt.scan(1);
    after_scans();
  };
  rt.skip_repeated_scans(!o.every_scan);
  if (duration > 0) {
    const VirtualTime end = rt.now() + duration;
    // A fault or a SUS (Suspend Idle) ends the run: nothing executes after either. Scans that
    // repeat the one before are taken without executing them (docs/semantics.md "Repeated
    // scans"), up to the next checkpoint; a repeat never faults or suspends (only an executed
    // scan can), so the run stops where executing every scan would stop it. --realtime paces
    // scan by scan.
    while (rt.now() < end && !rt.fault() && rt.mode() != Mode::Suspended && !g_interrupted) {
      if (o.realtime) {
        one_scan();
        continue;
      }
      rt.advance_toward(checkpoint > 0 ? std::min(end, next_checkpoint) : end);
      after_scans();
    }
  } else {
    const int n = o.scans > 0 ? o.scans : 1;
    for (int i = 0; i < n && !rt.fault() && rt.mode() != Mode::Suspended && !g_interrupted; ++i) one_scan();
  }
  const bool suspended = rt.mode() == Mode::Suspended;
  spdlog::debug("run: {} scans, {} of them taken as repeats of the scan before", rt.stats().scans,
                rt.stats().repeated);
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  saved_ok &= save_state();
  saved_ok &= finish_run_trace(o, program, rt, recorder.get(), std::cerr);

  const auto& fault = rt.fault();
  if (o.json) {
    nlohmann::ordered_json j;
    j["scans"] = rt.stats().scans;
    j["virtual_time_ms"] = static_cast<double>(rt.now()) / static_cast<double>(kNsPerMs);
    j["values"] = nlohmann::ordered_json::object();
    for (const auto& [text, a] : prints) {
      auto v = rt.get(a);
      if (!v) j["values"][text] = nullptr;
      else if (v->kind == Value::Kind::Float) j["values"][text] = v->real;
      else j["values"][text] = v->integer;
    }
    if (fault)
      j["fault"] = {{"code", fault_code_text(fault->code)}, {"file", fault->file}, {"rung", fault->rung},
                    {"message", fault->message}};
    else
      j["fault"] = nullptr;
    if (suspended)  // only when it happened, so the usual output keeps its keys
      j["suspended"] = {{"id", rt.value("S:7").as_int()}, {"file", rt.value("S:8").as_int()}};
    j["scan_time_us"] = {{"last", to_us(rt.stats().last)}, {"max", to_us(rt.stats().max)}, {"avg", to_us(rt.stats().avg())}};
    if (!o.logs.empty()) {  // only when asked, so the usual output keeps its keys
      j["logs"] = nlohmann::ordered_json::object();
      for (int q : o.logs) j["logs"][std::to_string(q)] = rt.data_log_records(q);
    }
    std::cout << json_text(j) << "\n";
  } else {
    for (const auto& [text, a] : prints) {
      auto v = rt.get(a);
      std::cout << text << " = " << (v ? v->to_string() : std::string("?")) << "\n";
    }
    for (int q : o.logs) {
      const auto records = rt.data_log_records(q);
      std::cout << "log " << q << ": " << records.size() << " record" << (records.size() == 1 ? "" : "s") << "\n";
      for (const auto& rec : records) std::cout << "  " << rec << "\n";
    }
    if (fault)
      std::cout << "fault: " << fault_code_text(fault->code) << " file " << fault->file << " rung " << fault->rung << ": "
                << fault->message << "\n";
    if (suspended)
      std::cout << "suspended: SUS " << rt.value("S:7").as_int() << " in file " << rt.value("S:8").as_int()
                << " (Suspend Idle, outputs off; S:7 and S:8 hold the ID and file)\n";
  }
  if (g_interrupted) return 128 + g_interrupted;
  if (!saved_ok) return kInputError;
  return fault ? kProgramFault : kOk;
}

int run_disasm(const DisasmOptions& o) {
  auto r = load_program_file(o.file);
  report(r);
  if (!r.ok()) return kInputError;
  CompileOptions copts;
  copts.module_instruction = load_module_setup(*r.program, std::nullopt).options.module_instruction;
  auto c = compile(*r.program, copts);
  if (!c.ok()) {
    std::cerr << r.source_name << ": error: the program cannot be compiled:\n" << c.render();
    return kInputError;
  }
  std::cout << disassemble(*c.program);
  return kOk;
}

// The REPEAT column of the instruction table in words (instructions/instruction_table.def says why
// each class may repeat; docs/semantics.md "Repeated scans").
const char* repeat_text(Repeat r) {
  switch (r) {
    case Repeat::TableAlone: return "yes: acts on the data table alone";
    case Repeat::FunctionFile: return "while the function file's sub-system stands still";
    case Repeat::Module: return "while the module in its slot is passive";
    case Repeat::Network: return "while no message is in flight, for a controller alone on its network";
    case Repeat::KnownTime: return "until the time it next acts (recorded by the probe)";
    case Repeat::AsciiPort: return "while the ASCII port has nothing to do";
    case Repeat::Never: return "no: a program holding it executes every scan";
  }
  return "no";
}

int run_instructions() {
  for (const auto& s : kInstructionTable) {
    std::cout << s.mnemonic;
    for (const auto& o : s.operand_specs()) std::cout << ' ' << o.label;
    std::cout << "\n    processors: " << requirement_processors(s.requires_) << "\n";
    std::cout << "    repeated scans: " << repeat_text(s.repeat) << "\n";
    for (const auto& o : s.operand_specs()) {
      std::cout << "    " << o.label << ": " << to_string(o.kind);
      bool constant = o.kind == OperandKind::Literal || o.kind == OperandKind::Label ||
                      o.kind == OperandKind::ProgramFile || o.kind == OperandKind::TimeBase;
      if (constant && o.kind != OperandKind::TimeBase) std::cout << " " << o.min << ".." << o.max;
      std::cout << (o.access == OperandAccess::Read    ? ", read"
                    : o.access == OperandAccess::Write ? ", written"
                                                       : ", read and written");
      if (!constant) std::cout << "; M0/M1 access: " << to_string(o.mfile);
      std::cout << "\n";
    }
  }
  return kOk;
}

int run_throughput(const ThroughputOptions& o) {
  InputFile in = read_input_file(o.config);
  if (!in.ok) {
    std::cerr << o.config << ": error: " << in.error << "\n";
    return kInputError;
  }
  // Every JSON error (syntax, a number such as 1e309, nesting) is a positioned diagnostic.
  JsonDocument doc = parse_json_document(in.contents);
  if (!doc.ok) {
    std::cerr << o.config << ":" << doc.line << ":" << doc.column << ": error: not valid JSON: " << doc.message << "\n";
    return kInputError;
  }
  nlohmann::json config = std::move(doc.value);
  try {
    auto result = throughput::compute_throughput(config);
    if (o.json)
      std::cout << json_text(result) << "\n";
    else
      std::cout << throughput::format_throughput_text(result);
  } catch (const throughput::ConfigError& e) {
    std::cerr << o.config << ": error: " << e.what() << "\n";
    return kInputError;
  }
  return kOk;
}

}  // namespace softslc::cli
