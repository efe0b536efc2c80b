// Reading JSON the user wrote (throughput configs, timing profiles, drive and DeviceNet
// descriptions) without letting any JSON problem escape as an exception.
//
// nlohmann::json::parse throws parse_error for bad syntax, which carries a byte offset, but
// out_of_range (406) for a number such as 1e309 that does not fit a double, which carries no
// position at all — callers that caught only parse_error let it escape and abort the process.
// parse_json_document() runs nlohmann's own DOM builder through its SAX interface with
// exceptions off, so every error — syntax, number overflow, nesting too deep — arrives at one
// place with the lexer's position, and the caller gets a value or a line:column and a message.
// It also bounds nesting (the DOM and every reader walking it are recursive), so a file of
// 100,000 '[' is an error, not a stack overflow. Output that may hold user bytes goes through
// json_text(), which replaces invalid UTF-8 rather than throwing (type_error 316).
#pragma once

#include <algorithm>
#include <cstddef>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace softslc {

// Deeper than any description the project reads (they nest four or five levels).
inline constexpr std::size_t kMaxJsonDepth = 64;

struct JsonDocument {
  nlohmann::json value;
  bool ok = false;
  std::size_t line = 0;    // 1-based position of the error (when !ok)
  std::size_t column = 0;  // 1-based
  std::size_t byte = 0;    // 1-based, as nlohmann counts
  std::string message;     // without nlohmann's "[json.exception...]" prefix

  // "LINE:COL: message", for callers that prefix a file name.
  std::string where_and_what() const { return std::to_string(line) + ":" + std::to_string(column) + ": " + message; }
};

namespace detail {

// Forwards every event to nlohmann's DOM builder; records the first error with its position.
class JsonDocumentSax {
 public:
  using json = nlohmann::json;
  explicit JsonDocumentSax(JsonDocument& doc) : doc_(doc), dom_(doc.value, false) {}

  bool null() { return dom_.null(); }
  bool boolean(bool v) { return dom_.boolean(v); }
  bool number_integer(json::number_integer_t v) { return dom_.number_integer(v); }
  bool number_unsigned(json::number_unsigned_t v) { return dom_.number_unsigned(v); }
  bool number_float(json::number_float_t v, const json::string_t& s) { return dom_.number_float(v, s); }
  bool string(json::string_t& v) { return dom_.string(v); }
  bool binary(json::binary_t& v) { return dom_.binary(v); }
  bool start_object(std::size_t n) { return deeper() && dom_.start_object(n); }
  bool key(json::string_t& v) { return dom_.key(v); }
  bool end_object() {
    --depth_;
    return dom_.end_object();
  }
  bool start_array(std::size_t n) { return deeper() && dom_.start_array(n); }
  bool end_array() {
    --depth_;
    return dom_.end_array();
  }
  bool parse_error(std::size_t byte, const std::string& token, const nlohmann::detail::exception& e) {
    (void)token;
    // The lexer's position is the byte after the offending token; nlohmann's own messages use it.
    record(byte, e.what());
    return false;
  }
  bool too_deep() const { return too_deep_; }

 private:
  bool deeper() {
    if (++depth_ <= kMaxJsonDepth) return true;
    too_deep_ = true;
    return false;
  }
  void record(std::size_t byte, std::string what) {
    if (!doc_.message.empty()) return;
    if (auto p = what.find("] "); p != std::string::npos && what.rfind("[json.exception", 0) == 0)
      what = what.substr(p + 2);
    if (what.rfind("parse error", 0) == 0)
      if (auto p = what.find(": "); p != std::string::npos) what = what.substr(p + 2);
    doc_.byte = byte;
    doc_.message = std::move(what);
  }

  JsonDocument& doc_;
  nlohmann::detail::json_sax_dom_parser<json> dom_;
  std::size_t depth_ = 0;
  bool too_deep_ = false;
};

}  // namespace detail

// Parses `text` as one JSON document. Never throws a JSON exception.
inline JsonDocument parse_json_document(std::string_view text) {
  JsonDocument doc;
  detail::JsonDocumentSax sax(doc);
  bool ok = false;
  try {
    ok = nlohmann::json::sax_parse(text.begin(), text.end(), &sax);
  } catch (const nlohmann::json::exception& e) {
    // Defensive: the SAX path reports through parse_error(), but a future nlohmann may throw.
    if (doc.message.empty()) doc.message = e.what();
  }
  if (ok && doc.message.empty()) {
    doc.ok = true;
    return doc;
  }
  if (sax.too_deep() && doc.message.empty())
    doc.message = "nested deeper than " + std::to_string(kMaxJsonDepth) + " arrays or objects";
  if (doc.message.empty()) doc.message = "not valid JSON";
  doc.value = nullptr;
  // Line and column of the byte at which parsing stopped (nlohmann counts bytes from 1). For
  // the nesting limit the position is unknown to the SAX callbacks: find the first bracket past
  // the limit instead.
  std::size_t at = doc.byte > 0 ? doc.byte - 1 : 0;
  if (sax.too_deep() && doc.byte == 0) {
    std::size_t depth = 0;
    bool in_string = false, escaped = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
      const char c = text[i];
      if (in_string) {
        if (escaped) escaped = false;
        else if (c == '\\') escaped = true;
        else if (c == '"') in_string = false;
      } else if (c == '"') {
        in_string = true;
      } else if (c == '[' || c == '{') {
        if (++depth > kMaxJsonDepth) {
          at = i;
          break;
        }
      } else if (c == ']' || c == '}') {
        if (depth > 0) --depth;
      }
    }
    doc.byte = at + 1;
  }
  at = std::min(at, text.size());
  doc.line = 1;
  std::size_t line_start = 0;
  for (std::size_t i = 0; i < at; ++i)
    if (text[i] == '\n') {
      ++doc.line;
      line_start = i + 1;
    }
  doc.column = at - line_start + 1;
  return doc;
}

// JSON text for output: bytes that are not UTF-8 (a file name, a program name) are shown as
// U+FFFD instead of making dump() throw.
inline std::string json_text(const nlohmann::json& j, int indent = 2) {
  return j.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}
inline std::string json_text(const nlohmann::ordered_json& j, int indent = 2) {
  return j.dump(indent, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

}  // namespace softslc
