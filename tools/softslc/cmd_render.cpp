#include "cmd_render.h"

#include <CLI/CLI.hpp>

#include <charconv>
#include <filesystem>
#include <iostream>

#include "commands.h"
#include "modules/module_setup.h"
#include "parser/loader.h"
#include "tools/trace/ladder_layout.h"
#include "vm/atomic_file.h"
#include "vm/bytecode.h"
#include "vm/coverage.h"
#include "vm/runtime.h"
#include "vm/state_file.h"

namespace softslc::cli {

namespace {

bool parse_int(std::string_view s, int& out) {
  if (s.empty()) return false;
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && p == s.data() + s.size() && out >= 0;
}

// "N" or "N..M".
bool parse_rung_range(const std::string& text, int& first, int& last) {
  auto dots = text.find("..");
  if (dots == std::string::npos) {
    if (!parse_int(text, first)) return false;
    last = first;
    return true;
  }
  return parse_int(std::string_view(text).substr(0, dots), first) &&
         parse_int(std::string_view(text).substr(dots + 2), last) && first <= last;
}

// The truth of every input instruction in the last scan, from a coverage record of that scan
// alone: an input whose rung condition was true passed power unless it decided its segment false.
void input_truth_from_coverage(const CompiledProgram& compiled, const std::vector<std::uint8_t>& flags,
                               ladder::LadderState& state) {
  for (const CompiledFile& cf : compiled.files) {
    auto& rungs = state.input_truth[cf.number];
    for (std::size_t r = 0; r < cf.rungs.size(); ++r) {
      const std::uint32_t begin = cf.rungs[r].offset;
      const std::uint32_t end = r + 1 < cf.rungs.size() ? cf.rungs[r + 1].offset : cf.end;
      std::vector<std::optional<bool>> truth;
      for (std::uint32_t pc = begin; pc < end; pc += 1 + bc::count_of(compiled.code[pc])) {
        const Op op = bc::op_of(compiled.code[pc]);
        if (!is_instruction(op)) continue;
        const std::uint8_t f = pc < flags.size() ? flags[pc] : 0;
        if (f & coverage::kRungInTrue) truth.emplace_back((f & coverage::kDecidedFalse) == 0);
        else truth.emplace_back(std::nullopt);
      }
      rungs.push_back(std::move(truth));
    }
  }
}

}  // namespace

CLI::App* add_render_command(CLI::App& app, RenderOptions& o) {
  auto* cmd = app.add_subcommand("render", "Draw ladder rungs as RSLogix shows them, as text or SVG (docs/traces.md)");
  cmd->add_option("FILE", o.file, "program file")->required();
  cmd->add_option("--file", o.program_file, "only this program file (2 = main)");
  cmd->add_option("--rung", o.rungs, "only rung N, or rungs N..M");
  cmd->add_option("--svg", o.svg, "write an SVG drawing to OUT (atomically)")->type_name("OUT");
  auto* text = cmd->add_flag("--text", o.text, "print the text drawing (the default without --svg)");
  cmd->add_flag("--json", o.json, "print the layout as JSON (blocks and wires in cell coordinates) instead")->excludes(text);
  auto* state = cmd->add_option("--state", o.state, "show values and power flow from a state file (softslc run --state)");
  cmd->add_option("--after-scans", o.after_scans, "show values and power flow after running N scans in Run mode")
      ->check(CLI::PositiveNumber)
      ->excludes(state);
  cmd->add_option("--bench", o.bench, "bench file of simulated field devices for the scans");
  return cmd;
}

int run_render(const RenderOptions& o) {
  auto r = load_program_file(o.file);
  std::cerr << r.render_diagnostics();
  if (!r.ok()) return kInputError;
  const Program& program = *r.program;
  ladder::LayoutOptions lo;
  if (o.program_file >= 0) {
    if (!program.find_file(o.program_file)) {
      std::cerr << "softslc render: --file " << o.program_file << ": the program has no ladder file " << o.program_file << "\n";
      return kUsage;
    }
    lo.file = o.program_file;
  }
  if (!o.rungs.empty() && !parse_rung_range(o.rungs, lo.first_rung, lo.last_rung)) {
    std::cerr << "softslc render: --rung " << o.rungs << ": write N or N..M (rung numbers from 0, N <= M)\n";
    return kUsage;
  }
  if (!o.rungs.empty()) {
    // A range that starts past the END rung of every chosen file would draw nothing: say so.
    bool any = false;
    for (const auto& f : program.files)
      if ((!lo.file || *lo.file == f.number) && lo.first_rung <= static_cast<int>(f.rungs.size())) any = true;
    if (!any) {
      std::cerr << "softslc render: --rung " << o.rungs << ": no such rung (rungs are numbered from 0; the END rung "
                << "is the last)\n";
      return kUsage;
    }
  }
  // The state: a runtime holding the values, and what the last scan says of input instructions.
  std::unique_ptr<Runtime> rt;
  ladder::LadderState state;
  if (!o.state.empty() || o.after_scans > 0) {
    ModuleSetup modules = load_module_setup(
        program, o.bench.empty() ? std::nullopt : std::optional<std::filesystem::path>(o.bench));
    std::cerr << modules.render(r.source_name, r.source);
    if (!modules.ok()) return kInputError;
    auto created = Runtime::create(program, modules.options);
    if (!created.ok()) {
      std::cerr << r.source_name << ": error: the program cannot run:\n" << created.render_errors();
      return kInputError;
    }
    rt = std::move(created.runtime);
    if (!o.state.empty()) {
      bool missing = false;
      auto loaded = load_state_file(o.state, program_fingerprint(program), rt->data(), false, &missing, chassis_modules(*rt));
      if (!loaded.ok || missing) {
        std::cerr << "softslc render: " << (missing ? o.state + ": no such state file" : loaded.error) << "\n";
        return kInputError;
      }
    } else {
      if (auto st = rt->set_mode(Mode::Run); !st) {
        std::cerr << "softslc render: " << st.message << "\n";
        return kInputError;
      }
      // The last scan alone is recorded, so the picture shows that scan's power flow.
      rt->scan(o.after_scans - 1);
      rt->enable_coverage();
      if (!rt->fault()) rt->scan(1);
      input_truth_from_coverage(rt->compiled(), rt->coverage()->flags(), state);
      if (const auto& f = rt->fault())
        std::cerr << "softslc render: warning: the program faulted in file " << f->file << " rung " << f->rung << ": "
                  << f->message << "\n";
    }
    const Runtime* runtime = rt.get();
    state.value = [runtime](const Address& a) { return runtime->get(a); };
    lo.state = &state;
  }
  const auto layout = ladder::layout_ladder(program, lo);
  if (!o.svg.empty()) {
    const std::string title = std::filesystem::path(o.file).filename().string();
    if (auto err = write_file_atomically(o.svg, ladder::render_svg(layout, title)); !err.empty()) {
      std::cerr << "softslc render: " << err << "\n";
      return kInputError;
    }
  }
  if (o.json) std::cout << ladder::render_json(layout);
  else if (o.svg.empty() || o.text) std::cout << ladder::render_text(layout);
  return kOk;
}

}  // namespace softslc::cli
