#include "modules/module_setup.h"

#include <algorithm>
#include <map>

#include "modules/process/plant.h"
#include "modules/modbus/modbus_node.h"
#include "modules/serial/serial_device.h"
#include "parser/loader.h"
#include "vm/compiler.h"

namespace softslc {

std::string ModuleSetup::render(std::string_view program_name, std::string_view program_source) const {
  return render_all(program_diagnostics, program_name, program_source) +
         render_all(bench_diagnostics, bench_name, bench_source);
}

namespace {

// Which slot each top-level bench node is wired to, with the checks that do not need a family.
std::map<int, const BenchNode*> bind_bench_nodes(const Program& program, const BenchFile& bench,
                                                 const ModuleRegistry& registry, DiagnosticList& diags) {
  std::map<int, const BenchNode*> out;
  for (const auto& n : bench.nodes) {
    if (n.kind == "process") continue;  // a simulated plant wired to data-table words, not to a slot
    if (n.kind == "serial") continue;   // channel 0 and its device, not a slot
    if (n.kind == "modbus") continue;   // a Modbus slave on channel 0, not a slot
    const BenchAttribute* a = n.find("slot");
    if (!a) {
      diags.error(n.pos.line, n.pos.column,
                  n.label() + ": a top-level bench node names the chassis slot it is wired to with slot=N");
      continue;
    }
    NumberValue v;
    if (!parse_number_text(a->value, v) || v.is_float || v.integer < 0 || v.integer > 30) {
      diags.error(a->value_pos.line, a->value_pos.column, n.label() + ": slot=" + a->value + ": expected a slot 0-30");
      continue;
    }
    const int slot = static_cast<int>(v.integer);
    const SlotConfig* sc = program.find_slot(slot);
    if (!sc) {
      diags.error(a->value_pos.line, a->value_pos.column,
                  n.label() + ": the program has no module in slot " + std::to_string(slot) + " (no SLOT " +
                      std::to_string(slot) + " line)");
      continue;
    }
    const ModuleFamily* fam = registry.find(*sc);
    if (!fam || fam->bench_kinds.empty()) {
      diags.error(n.pos.line, n.pos.column,
                  n.label() + ": slot " + std::to_string(slot) + " holds a " + sc->catalog +
                      ", which has no simulated field devices in softslc");
      continue;
    }
    if (std::find(fam->bench_kinds.begin(), fam->bench_kinds.end(), n.kind) == fam->bench_kinds.end()) {
      std::string kinds;
      for (const auto& k : fam->bench_kinds) kinds += (kinds.empty() ? "" : " or ") + k;
      diags.error(n.pos.line, n.pos.column,
                  "'" + n.kind + "' does not describe the " + sc->catalog + " in slot " + std::to_string(slot) +
                      " (" + fam->name + "); write " + kinds);
      continue;
    }
    auto [it, inserted] = out.emplace(slot, &n);
    if (!inserted)
      diags.error(n.pos.line, n.pos.column,
                  n.label() + ": slot " + std::to_string(slot) + " is already described at line " +
                      std::to_string(it->second->pos.line));
  }
  // Device names are how tests reach devices: they must be unique in the whole bench.
  std::map<std::string, SourcePos> names;
  std::vector<const BenchNode*> stack;
  for (const auto& n : bench.nodes) stack.push_back(&n);
  std::vector<const BenchNode*> ordered;
  while (!stack.empty()) {
    const BenchNode* n = stack.back();
    stack.pop_back();
    ordered.push_back(n);
    for (auto it = n->children.rbegin(); it != n->children.rend(); ++it) stack.push_back(&*it);
  }
  for (const BenchNode* n : ordered) {
    if (n->name.empty()) continue;
    auto [it, inserted] = names.emplace(n->name, n->name_pos);
    if (!inserted)
      diags.error(n->name_pos.line, n->name_pos.column,
                  "device name '" + n->name + "' is already used at line " + std::to_string(it->second.line));
  }
  return out;
}

// Simulated processes (modules/process/plant.h): wired to data-table words, not to a slot. Their
// words must be words of the program's data table, which the compiler lays out from the program:
// the program is compiled once here so a bench naming a word the program lacks is refused at the
// attribute, and a setup that is ok() always gives a runtime.
void add_processes(const Program& program, const BenchFile& bench, ModuleSetup& s) {
  std::optional<CompileResult> compiled;
  for (const auto& n : bench.nodes) {
    if (n.kind != "process") continue;
    auto config = read_plant_node(n, s.bench_diagnostics);
    if (!config) continue;
    if (!compiled) {
      CompileOptions co;
      co.module_instruction = s.options.module_instruction;
      compiled = compile(program, co);
    }
    if (compiled->ok()) {
      bool bad = false;
      for (const char* key : {"cv", "pv"}) {
        const std::string why = plant_word_problem(key[0] == 'c' ? config->cv : config->pv, *compiled->program->layout);
        if (why.empty()) continue;
        const SourcePos p = n.find(key)->value_pos;
        s.bench_diagnostics.error(p.line, p.column, n.label() + ": " + key + "=" + why);
        bad = true;
      }
      if (bad) continue;
    }
    s.options.field_processes.push_back([c = *config] { return make_plant(c); });
  }
  s.bench_diagnostics.sort_by_position();
}

// The `serial` node (modules/serial/serial_device.h): channel 0 in User mode with its device.
// There is one channel 0, and only the processors with the ASCII instructions have a User mode
// for it in softslc.
void add_serial_channel(const Program& program, const BenchFile& bench, ModuleSetup& s) {
  const BenchNode* first = nullptr;
  for (const auto& n : bench.nodes) {
    if (n.kind != "serial") continue;
    if (first) {
      s.bench_diagnostics.error(n.pos.line, n.pos.column,
                                n.label() + ": channel 0 is already wired to " + first->label() + " at line " +
                                    std::to_string(first->pos.line));
      continue;
    }
    first = &n;
    if (!program.processor.supports(Requirement::Os302)) {
      s.bench_diagnostics.error(n.pos.line, n.pos.column,
                                n.label() + ": channel 0 in User (ASCII) mode needs " +
                                    std::string(requirement_processors(Requirement::Os302)) +
                                    "; this program's processor is " + program.processor.display_name);
      continue;
    }
    if (auto config = read_serial_node(n, s.bench_diagnostics))
      s.options.ascii_channel = [c = *config] { return make_serial_channel(c); };
  }
  s.bench_diagnostics.sort_by_position();
}

// The `modbus` nodes (modules/modbus/modbus_node.h): channel 0 of a MicroLogix 1100 or 1400 as a Modbus RTU
// master with its slaves. Channel 0 is one port: a `serial` node and `modbus` nodes exclude each other.
void add_modbus_channel(const Program& program, const BenchFile& bench, ModuleSetup& s) {
  std::vector<const BenchNode*> slaves;
  const BenchNode* serial = nullptr;
  for (const auto& n : bench.nodes) {
    if (n.kind == "serial" && !serial) serial = &n;
    if (n.kind == "modbus") slaves.push_back(&n);
  }
  if (slaves.empty()) return;
  const BenchNode& first = *slaves.front();
  if (serial) {
    s.bench_diagnostics.error(first.pos.line, first.pos.column,
                              first.label() + ": channel 0 is already wired to " + serial->label() + " at line " +
                                  std::to_string(serial->pos.line) + " (User mode); a Modbus slave needs it as a "
                                  "Modbus RTU master");
    return;
  }
  if (!program.processor.has_routing_files()) {
    s.bench_diagnostics.error(first.pos.line, first.pos.column,
                              first.label() + ": a Modbus RTU master channel 0 with a MSG that uses it is the "
                              "MicroLogix 1100's and 1400's (1763-RM001B p. 366, 1766-RM001A); this program's "
                              "processor is " + program.processor.display_name);
    return;
  }
  if (auto config = read_modbus_nodes(slaves, s.bench_diagnostics))
    s.options.modbus_channel = [c = *config] { return std::make_unique<ModbusMaster>(c); };
  s.bench_diagnostics.sort_by_position();
}

}  // namespace

ModuleSetup setup_modules(const Program& program, const BenchFile* bench, const ModuleRegistry& registry) {
  ModuleSetup s;
  std::map<int, const BenchNode*> nodes;
  if (bench) {
    s.bench_name = bench->source_name;
    s.bench_source = bench->source;
    nodes = bind_bench_nodes(program, *bench, registry, s.bench_diagnostics);
  }
  std::map<int, SlotModuleBuilder> builders;
  struct SlotInfo {
    std::string catalog;
    std::vector<Opcode> instructions;
  };
  std::map<int, SlotInfo> info;
  for (const auto& slot : program.slots) {
    const ModuleFamily* family = registry.find(slot);
    info[slot.slot] = SlotInfo{slot.catalog, family ? family->instructions : std::vector<Opcode>{}};
    if (!family) continue;
    auto it = nodes.find(slot.slot);
    ModulePrepareContext ctx{program, slot, it == nodes.end() ? nullptr : it->second, s.program_diagnostics,
                             s.bench_diagnostics, s.bench_name};
    if (SlotModuleBuilder b = family->prepare(ctx)) builders.emplace(slot.slot, std::move(b));
  }
  s.program_diagnostics.sort_by_position();
  s.bench_diagnostics.sort_by_position();

  auto shared = std::make_shared<const std::map<int, SlotModuleBuilder>>(std::move(builders));
  s.options.module_factory = [shared](const SlotConfig& sc) -> std::unique_ptr<Module> {
    auto it = shared->find(sc.slot);
    return it == shared->end() ? nullptr : it->second(sc);
  };
  // Which catalogs execute each module instruction, for the refusal message.
  std::map<Opcode, std::string> executors;
  for (const auto& f : registry.families())
    for (Opcode op : f.instructions)
      for (const auto& c : f.catalogs) executors[op] += (executors[op].empty() ? "" : " or ") + c;
  s.options.module_instruction = [info = std::move(info),
                                  executors = std::move(executors)](const Instruction& in) -> std::optional<std::string> {
    const std::string m(spec(in.opcode).mnemonic);
    auto slot = module_instruction_slot(in);
    if (!slot) return m + " does not name the slot of its module";
    auto it = info.find(*slot);
    auto ex = executors.find(in.opcode);
    const std::string needs = ex == executors.end() ? std::string("a module that executes it") : "a " + ex->second;
    if (it == info.end()) return m + " needs " + needs + " in slot " + std::to_string(*slot) + ", which is empty";
    if (std::find(it->second.instructions.begin(), it->second.instructions.end(), in.opcode) ==
        it->second.instructions.end())
      return m + " needs " + needs + " in slot " + std::to_string(*slot) + "; slot " + std::to_string(*slot) +
             " holds a " + it->second.catalog;
    return std::nullopt;
  };
  if (bench) add_processes(program, *bench, s);
  if (bench) add_serial_channel(program, *bench, s);
  if (bench) add_modbus_channel(program, *bench, s);
  return s;
}

ModuleSetup load_module_setup(const Program& program, const std::optional<std::filesystem::path>& bench_path,
                              const ModuleRegistry& registry) {
  if (!bench_path) return setup_modules(program, nullptr, registry);
  BenchParseResult br = parse_bench_file(*bench_path);
  if (!br.ok()) {
    ModuleSetup s = setup_modules(program, nullptr, registry);
    s.bench_diagnostics = std::move(br.diagnostics);
    s.bench_name = br.source_name;
    s.bench_source = br.source;
    return s;
  }
  return setup_modules(program, &*br.bench, registry);
}

ModuleSetup load_module_setup_text(const Program& program, std::string bench_text, std::string bench_name,
                                   const ModuleRegistry& registry) {
  BenchParseResult br = parse_bench(std::move(bench_text), std::move(bench_name));
  if (!br.ok()) {
    ModuleSetup s = setup_modules(program, nullptr, registry);
    s.bench_diagnostics = std::move(br.diagnostics);
    s.bench_name = br.source_name;
    s.bench_source = br.source;
    return s;
  }
  return setup_modules(program, &*br.bench, registry);
}

void check_module_configuration(const Program& program, DiagnosticList& diagnostics, const ModuleRegistry& registry) {
  for (const auto& slot : program.slots)
    if (const ModuleFamily* f = registry.find(slot); f && f->check) f->check(program, slot, diagnostics);
  diagnostics.sort_by_position();
}

}  // namespace softslc
