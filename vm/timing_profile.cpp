#include "vm/timing_profile.h"

#include "instructions/processor.h"

#include <charconv>
#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>
#include <sstream>

#include "parser/input_file.h"
#include "parser/json_document.h"

namespace softslc {

namespace detail {
struct BuiltinProfileText {
  const char* name;
  const char* json;
};
extern const BuiltinProfileText kBuiltinProfiles[];
extern const std::size_t kBuiltinProfileCount;
}  // namespace detail

namespace {

using nlohmann::json;

constexpr std::string_view kSchema = "softslc-timing-profile-1";

[[noreturn]] void fail(const std::string& path, const std::string& message) {
  throw TimingProfileError(path + ": " + message);
}

// Microseconds as written (may have decimals) to integer nanoseconds, rounded to nearest.
Nanoseconds us_to_ns(const json& v, const std::string& path) {
  if (!v.is_number()) fail(path, "expected a number of microseconds");
  double us = v.get<double>();
  if (!std::isfinite(us) || us < 0 || us > 1e9) fail(path, "must be between 0 and 1e9 microseconds");
  return static_cast<Nanoseconds>(std::llround(us * 1000.0));
}

const json& member(const json& obj, const char* key, const std::string& path) {
  auto it = obj.find(key);
  if (it == obj.end()) fail(path, std::string("missing \"") + key + "\"");
  return *it;
}

std::string source_of(const json& obj, const std::string& path, const TimingProfile& p) {
  auto s = member(obj, "source", path);
  if (!s.is_string()) fail(path + ".source", "expected a source name");
  auto name = s.get<std::string>();
  if (!p.sources.count(name)) fail(path + ".source", "unknown source \"" + name + "\" (not in \"sources\")");
  return name;
}

TimedFigure figure(const json& obj, const std::string& path, const TimingProfile& p) {
  if (!obj.is_object()) fail(path, "expected {\"value\": microseconds, \"source\": name}");
  return {us_to_ns(member(obj, "value", path), path + ".value"), source_of(obj, path, p)};
}

void check_keys(const json& obj, const std::string& path, std::initializer_list<std::string_view> allowed) {
  for (auto it = obj.begin(); it != obj.end(); ++it) {
    bool ok = false;
    for (auto a : allowed) ok |= it.key() == a;
    if (!ok) fail(path, "unknown key \"" + it.key() + "\"");
  }
}

// An instruction row's "transition": {"true_us": T, "per_word_us": W} for every instance, or one such row
// per word of the instruction's first keyword operand, as the instruction table spells them ("READ",
// "WRITE" for MSG: 1762-RM001C Table 21.1 gives reads and writes apart).
void parse_transition(const json& tr, const InstructionSpec& spec, const std::string& path, InstructionTiming& t) {
  auto row = [&](const json& r, const std::string& rpath, int variant) {
    check_keys(r, rpath, {"true_us", "per_word_us"});
    TransitionTiming x;
    x.variant = variant;
    x.true_ns = us_to_ns(member(r, "true_us", rpath), rpath + ".true_us");
    x.per_word_ns = r.contains("per_word_us") ? us_to_ns(r["per_word_us"], rpath + ".per_word_us") : 0;
    t.transitions.push_back(x);
  };
  // Only MSG charges it in a run (the handler that starts a message, Interpreter::charge_transition), so
  // a figure scantime's steady state leaves out and run would never charge is refused, as by_operand is.
  if (spec.mnemonic != "MSG") fail(path, "only MSG has a false-to-true figure charged in a run (docs/timing.md \"MSG\")");
  if (!tr.is_object()) fail(path, "expected an object");
  if (tr.contains("true_us")) return row(tr, path, -1);
  const OperandSpec* keyword = nullptr;
  for (const OperandSpec& os : spec.operand_specs())
    if (!keyword_words(os.kind).empty()) {
      keyword = &os;
      break;
    }
  for (auto v = tr.begin(); v != tr.end(); ++v) {
    const std::optional<int> code = keyword ? keyword_code(keyword->kind, v.key()) : std::nullopt;
    if (!code) fail(path + "." + v.key(), "expected true_us, or rows keyed by the words of the instruction's first keyword operand");
    row(*v, path + "." + v.key(), *code);
  }
}

// Applies `j` onto `p`. A built-in profile is applied onto an empty one; a user profile onto
// the built-in one of its processor, so it may give any subset of figures.
void apply_profile_json(const json& j, TimingProfile& p) {
  if (!j.is_object()) fail("(top)", "a timing profile is a JSON object");
  check_keys(j, "(top)", {"schema", "processor", "name", "sources", "housekeeping_us", "io_scan", "instructions"});
  if (member(j, "schema", "(top)") != kSchema) fail("schema", "expected \"" + std::string(kSchema) + "\"");
  if (auto it = j.find("name"); it != j.end()) p.name = it->get<std::string>();
  if (auto it = j.find("sources"); it != j.end()) {
    if (!it->is_object()) fail("sources", "expected an object of named sources");
    for (auto s = it->begin(); s != it->end(); ++s) {
      std::string path = "sources." + s.key();
      check_keys(*s, path, {"estimate", "citation"});
      auto est = member(*s, "estimate", path);
      if (!est.is_boolean()) fail(path + ".estimate", "expected true or false");
      auto cit = member(*s, "citation", path);
      if (!cit.is_string()) fail(path + ".citation", "expected a citation text");
      p.sources[s.key()] = {est.get<bool>(), cit.get<std::string>()};
    }
  }
  if (auto it = j.find("housekeeping_us"); it != j.end()) p.housekeeping = figure(*it, "housekeeping_us", p);
  if (auto it = j.find("io_scan"); it != j.end()) {
    check_keys(*it, "io_scan", {"input_scan_base_us", "modules", "default_per_image_word_us", "default_module_us"});
    if (auto f = it->find("input_scan_base_us"); f != it->end())
      p.input_scan_base = figure(*f, "io_scan.input_scan_base_us", p);
    if (auto f = it->find("default_per_image_word_us"); f != it->end())
      p.default_per_image_word = figure(*f, "io_scan.default_per_image_word_us", p);
    if (auto f = it->find("default_module_us"); f != it->end())
      p.default_module = figure(*f, "io_scan.default_module_us", p);
    if (auto m = it->find("modules"); m != it->end()) {
      for (auto e = m->begin(); e != m->end(); ++e) {
        std::string path = "io_scan.modules." + e.key();
        check_keys(*e, path, {"input_us", "output_us"});
        p.modules[e.key()] = {figure(member(*e, "input_us", path), path + ".input_us", p),
                              figure(member(*e, "output_us", path), path + ".output_us", p)};
      }
    }
  }
  if (auto it = j.find("instructions"); it != j.end()) {
    if (!it->is_object()) fail("instructions", "expected an object keyed by mnemonic");
    for (auto e = it->begin(); e != it->end(); ++e) {
      std::string path = "instructions." + e.key();
      const InstructionSpec* spec = find_instruction(e.key());
      if (!spec) fail(path, "unknown instruction mnemonic");
      check_keys(*e, path, {"true_us", "false_us", "per_word_us", "by_operand", "transition", "source"});
      InstructionTiming t;
      t.true_ns = us_to_ns(member(*e, "true_us", path), path + ".true_us");
      t.false_ns = us_to_ns(member(*e, "false_us", path), path + ".false_us");
      t.per_word_ns = e->contains("per_word_us") ? us_to_ns((*e)["per_word_us"], path + ".per_word_us") : 0;
      t.source = source_of(*e, path, p);
      if (auto b = e->find("by_operand"); b != e->end()) {
        // Only SVC's channel select is charged per value in a run (Interpreter's
        // svc_select_extra_); a figure scantime would price and run would not charge is refused.
        if (e.key() != "SVC")
          fail(path + ".by_operand", "only SVC's channel select (1-3) has figures per operand value");
        if (!b->is_object() || b->size() > 16)
          fail(path + ".by_operand", "expected an object of at most 16 rows keyed by the first operand's value");
        for (auto v = b->begin(); v != b->end(); ++v) {
          const std::string vpath = path + ".by_operand." + v.key();
          std::int64_t value = 0;
          const auto* end = v.key().data() + v.key().size();
          if (auto [ptr, ec] = std::from_chars(v.key().data(), end, value);
              ec != std::errc{} || ptr != end || value < 1 || value > 3)
            fail(vpath, "the key must be a channel select 1, 2 or 3");
          check_keys(*v, vpath, {"true_us", "false_us"});
          t.by_operand.push_back({value, us_to_ns(member(*v, "true_us", vpath), vpath + ".true_us"),
                                  us_to_ns(member(*v, "false_us", vpath), vpath + ".false_us")});
        }
      }
      if (auto tr = e->find("transition"); tr != e->end()) parse_transition(*tr, *spec, path + ".transition", t);
      // A mnemonic's figure covers every form of it (OSR: the SLC's and the MicroLogix's), since a
      // processor has only one of them.
      for (const auto& row : kInstructionTable)
        if (row.mnemonic == e.key()) p.instructions[static_cast<std::size_t>(row.opcode)] = t;
    }
  }
}

TimingProfile parse_builtin(const detail::BuiltinProfileText& text) {
  TimingProfile p;
  json j = json::parse(text.json);
  p.processor = j.at("processor").get<std::string>();
  apply_profile_json(j, p);
  // A built-in profile must be complete: every instruction its processor has gets a figure
  // (an SLC profile need not time ONS, a MicroLogix profile not BTR).
  const auto proc = representative_processor(p.processor);
  if (!proc) throw TimingProfileError(std::string("built-in profile ") + text.name + " names no known processor");
  for (std::size_t i = 0; i < kInstructionCount; ++i)
    if (proc->supports(kInstructionTable[i].requires_) && p.instructions[i].source.empty())
      throw TimingProfileError(std::string("built-in profile ") + text.name + " has no figure for " +
                               std::string(kInstructionTable[i].mnemonic));
  return p;
}

}  // namespace

bool TimingProfile::is_estimate(const std::string& source) const {
  auto it = sources.find(source);
  return it == sources.end() || it->second.estimate;
}

Nanoseconds TimingProfile::input_scan(const std::string& catalog, int words) const {
  if (words <= 0) return 0;
  if (auto it = modules.find(catalog); it != modules.end()) return it->second.input.ns;
  return default_module.ns + default_per_image_word.ns * words;
}

Nanoseconds TimingProfile::output_scan(const std::string& catalog, int words) const {
  if (words <= 0) return 0;
  if (auto it = modules.find(catalog); it != modules.end()) return it->second.output.ns;
  return default_module.ns + default_per_image_word.ns * words;
}

std::optional<TimingProfile> builtin_timing_profile(std::string_view timing_key) {
  for (std::size_t i = 0; i < detail::kBuiltinProfileCount; ++i) {
    json j = json::parse(detail::kBuiltinProfiles[i].json);
    if (j.at("processor").get<std::string>() == timing_key) return parse_builtin(detail::kBuiltinProfiles[i]);
  }
  return std::nullopt;
}

std::vector<std::string> builtin_timing_profile_keys() {
  std::vector<std::string> keys;
  for (std::size_t i = 0; i < detail::kBuiltinProfileCount; ++i)
    keys.push_back(json::parse(detail::kBuiltinProfiles[i].json).at("processor").get<std::string>());
  return keys;
}

TimingProfile load_timing_profile(const json& user) {
  if (!user.is_object()) fail("(top)", "a timing profile is a JSON object");
  const auto& proc = member(user, "processor", "(top)");
  if (!proc.is_string()) fail("processor", "expected a processor key such as \"5/03\"");
  auto base = builtin_timing_profile(proc.get<std::string>());
  if (!base) {
    std::string known;
    for (const auto& k : builtin_timing_profile_keys()) known += (known.empty() ? "" : ", ") + k;
    fail("processor", "no built-in profile for \"" + proc.get<std::string>() + "\" (known: " + known + ")");
  }
  apply_profile_json(user, *base);
  return *base;
}

TimingProfile load_timing_profile_file(const std::string& path) {
  InputFile in = read_input_file(path);
  if (!in.ok) throw TimingProfileError(path + ": " + in.error);
  // Every JSON error (syntax, a number such as 1e309, nesting) is positioned.
  JsonDocument doc = parse_json_document(in.contents);
  if (!doc.ok) throw TimingProfileError(path + ":" + doc.where_and_what());
  json j = std::move(doc.value);
  try {
    return load_timing_profile(j);
  } catch (const TimingProfileError& e) {
    throw TimingProfileError(path + ": " + e.what());
  } catch (const json::exception& e) {
    throw TimingProfileError(path + ": " + e.what());
  }
}

}  // namespace softslc
