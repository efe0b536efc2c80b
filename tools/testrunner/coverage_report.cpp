#include "tools/testrunner/coverage_report.h"

#include <nlohmann/json.hpp>

#include "parser/json_document.h"

namespace softslc::testing {

void CoverageCollector::add(const TestOutcome& outcome) {
  for (const auto& [program, flags] : outcome.coverage) merge_coverage(merged_, program, flags);
}

std::vector<CoverageReport> CoverageCollector::reports(std::string& error) const {
  std::vector<CoverageReport> out;
  for (const auto& [program, flags] : merged_) {
    // The runtimes that recorded the flags compiled the program with these same options; the
    // compiler is deterministic, so the code offsets agree.
    RuntimeResult r = Runtime::create(program->program, program->modules);
    if (!r.ok()) {
      error += program->path + ": " + r.render_errors();
      continue;
    }
    out.push_back(build_coverage_report(program->program, r.runtime->compiled(), flags, program->path));
  }
  return out;
}

namespace {

std::string ratio(int n, int of) {
  if (of == 0) return "-";
  return std::to_string(n) + "/" + std::to_string(of) + " (" + std::to_string(n * 100 / of) + "%)";
}

std::string pad(std::string s, std::size_t width) {
  if (s.size() < width) s.append(width - s.size(), ' ');
  return s;
}

std::string row(const std::string& name, const FileCoverage& f) {
  return "  " + pad(name, 24) + pad(ratio(f.rungs_executed, f.rungs), 16) + pad(ratio(f.rungs_both_ways, f.rungs), 16) +
         pad(ratio(f.conditions_both_ways, f.conditions), 18) + ratio(f.outputs_energized, f.outputs) + "\n";
}

nlohmann::ordered_json counts(const FileCoverage& f) {
  nlohmann::ordered_json j;
  j["rungs"] = f.rungs;
  j["rungs_executed"] = f.rungs_executed;
  j["rungs_true_and_false"] = f.rungs_both_ways;
  j["conditions"] = f.conditions;
  j["conditions_decided_both_ways"] = f.conditions_both_ways;
  j["outputs"] = f.outputs;
  j["outputs_energized"] = f.outputs_energized;
  return j;
}

std::string where(const CoverageItem& i) {
  if (i.text.rfind("file ", 0) == 0) return i.text;  // a whole file: "file 4 NEVER"
  std::string s = "file " + std::to_string(i.file) + " rung " + std::to_string(i.rung);
  if (i.instruction >= 0) s += " instruction " + std::to_string(i.instruction) + " " + i.text;
  return s;
}

}  // namespace

std::string render_coverage_text(const std::vector<CoverageReport>& reports) {
  std::string out;
  for (const auto& r : reports) {
    out += "coverage of " + r.program + "\n";
    out += "  " + pad("file", 24) + pad("rungs run", 16) + pad("true+false", 16) + pad("conditions", 18) + "outputs\n";
    for (const auto& f : r.files) {
      std::string name = std::to_string(f.file) + (f.name.empty() ? "" : " " + f.name);
      if (!f.called) name += " (not called)";
      out += row(name, f);
    }
    out += row("total", r.total());
    if (r.uncovered.empty()) {
      out += "  everything covered\n";
      continue;
    }
    out += "  uncovered:\n";
    for (const auto& i : r.uncovered)
      out += "    " + r.program + ":" + std::to_string(i.line) + ": " + where(i) + ": " + i.problem + "\n";
  }
  return out;
}

std::string render_coverage_json(const std::vector<CoverageReport>& reports) {
  nlohmann::ordered_json doc;
  doc["programs"] = nlohmann::ordered_json::array();
  for (const auto& r : reports) {
    nlohmann::ordered_json p;
    p["program"] = r.program;
    p["files"] = nlohmann::ordered_json::array();
    for (const auto& f : r.files) {
      nlohmann::ordered_json j;
      j["file"] = f.file;
      j["name"] = f.name;
      j["called"] = f.called;
      j.update(counts(f));
      p["files"].push_back(std::move(j));
    }
    p["total"] = counts(r.total());
    p["uncovered"] = nlohmann::ordered_json::array();
    for (const auto& i : r.uncovered) {
      nlohmann::ordered_json j;
      j["file"] = i.file;
      j["rung"] = i.rung;
      if (i.instruction >= 0) j["instruction"] = i.instruction;
      j["line"] = i.line;
      j["text"] = i.text;
      j["problem"] = i.problem;
      p["uncovered"].push_back(std::move(j));
    }
    doc["programs"].push_back(std::move(p));
  }
  return json_text(doc) + "\n";
}

}  // namespace softslc::testing
