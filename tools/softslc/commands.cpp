#include "commands.h"

#include <fstream>
#include <iostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "file_output.h"
#include "instructions/instruction_table.h"
#include "modules/throughput/throughput_json.h"
#include "parser/formatter.h"
#include "parser/loader.h"

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

}  // namespace

int run_check(const CheckOptions& o) {
  auto r = load_program_file(o.file);
  report(r);
  return r.ok() ? kOk : kInputError;
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

int run_instructions() {
  for (const auto& s : kInstructionTable) {
    std::cout << s.mnemonic;
    for (const auto& o : s.operand_specs()) std::cout << ' ' << o.label;
    std::cout << "\n";
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
  std::ifstream in(o.config, std::ios::binary);
  if (!in) {
    std::cerr << o.config << ": error: cannot open file\n";
    return kInputError;
  }
  nlohmann::json config;
  try {
    config = nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    // nlohmann reports the byte offset; say which file it is in.
    std::cerr << o.config << ": error: not valid JSON: " << e.what() << "\n";
    return kInputError;
  }
  try {
    auto result = throughput::compute_throughput(config);
    if (o.json)
      std::cout << result.dump(2) << "\n";
    else
      std::cout << throughput::format_throughput_text(result);
  } catch (const throughput::ConfigError& e) {
    std::cerr << o.config << ": error: " << e.what() << "\n";
    return kInputError;
  }
  return kOk;
}

}  // namespace softslc::cli
