// Bench files: the simulated field devices wired to a program's modules.
//
// A bench file sits next to a program and says what is on the other side of its modules'
// terminals: remote adapters and their I/O modules on a 1747-SN RIO link today, DeviceNet nodes,
// SCANport drives and AutoMax drops later. The syntax knows none of them. It is a tree of nodes,
// one per line, each `KIND [NAME] [key=value ...]`, a node's children in a `{ ... }` block (see
// docs/bench-format.md):
//
//   scanner RIO slot=1 {
//     adapter RACK0 rack=0 group=0 size=1/2 backplane_scan=4.5ms {
//       module PB catalog=1746-IB16 group=0 input_delay=10ms
//     }
//   }
//
// parse_bench() turns text into BenchNodes (kind, name, attributes, children, positions) and
// reports syntax errors gcc-style (parser/diagnostics.h). Each top-level node names the chassis
// slot it is wired to with `slot=N`; the module family of that slot interprets the node and its
// children with a BenchReader, which reports unknown attributes, bad values and missing ones at
// their own positions. The grammar (bench_grammar.h), its messages (bench_messages.h) and the
// actions (bench.cpp) are kept apart, as in the program parser.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "parser/diagnostics.h"
#include "parser/program.h"
#include "vm/virtual_time.h"

namespace softslc {

struct BenchAttribute {
  std::string key;
  std::string value;  // without quotes
  SourcePos pos;      // of the key
  SourcePos value_pos;
};

struct BenchNode {
  std::string kind;
  std::string name;  // empty when the node has none
  std::vector<BenchAttribute> attributes;
  std::vector<BenchNode> children;
  SourcePos pos;  // of the kind
  SourcePos name_pos;

  const BenchAttribute* find(std::string_view key) const;
  // "adapter RACK0" / "module" — for messages.
  std::string label() const { return name.empty() ? kind : kind + " " + name; }
};

struct BenchFile {
  std::string source_name;
  std::string source;
  std::vector<BenchNode> nodes;  // the top-level nodes in file order
};

struct BenchParseResult {
  std::optional<BenchFile> bench;  // set only when there are no errors
  DiagnosticList diagnostics;
  std::string source;
  std::string source_name;
  bool ok() const { return bench.has_value(); }
  std::string render_diagnostics() const { return render_all(diagnostics, source_name, source); }
};

// Parses bench text. Syntax errors are positioned; a file with any error yields no tree.
BenchParseResult parse_bench(std::string text, std::string source_name);
// Reads and parses a file; an unreadable file is a diagnostic.
BenchParseResult parse_bench_file(const std::filesystem::path& path);

// Reads one node's attributes with positioned errors. Every getter marks its key as known;
// finish() reports the attributes nobody asked for, so a typo never passes silently. Getters
// return nullopt when the attribute is absent (and, after reporting, when it is invalid).
class BenchReader {
 public:
  BenchReader(const BenchNode& node, DiagnosticList& diags) : node_(node), diags_(diags) {}

  const BenchNode& node() const { return node_; }
  std::optional<std::string> text(std::string_view key);
  std::optional<std::int64_t> integer(std::string_view key, std::int64_t min, std::int64_t max);
  std::optional<Nanoseconds> duration(std::string_view key);
  std::optional<bool> flag(std::string_view key);  // on/off, yes/no, true/false, 1/0
  // A comma-separated list of integers (decimal, negative, 0x.. hex), each in min..max.
  std::optional<std::vector<std::int64_t>> integers(std::string_view key, std::int64_t min, std::int64_t max);
  // One of `choices`; the error lists them.
  std::optional<std::string> choice(std::string_view key, const std::vector<std::string>& choices);
  // Marks an attribute as read by someone else (the `slot` of a top-level node).
  void skip(std::string_view key) { known_.insert(std::string(key)); }
  // Reports a missing required attribute at the node.
  void require(std::string_view key, std::string_view what);
  // An error at the attribute (or the node when the attribute is absent).
  void error_at(std::string_view key, const std::string& message);
  void error(const std::string& message);
  void finish();
  bool failed() const { return failed_; }

 private:
  const BenchAttribute* get(std::string_view key);
  const BenchNode& node_;
  DiagnosticList& diags_;
  std::set<std::string, std::less<>> known_;
  bool failed_ = false;
};

}  // namespace softslc
