#include "modules/devicenet/json_reader.h"

#include "parser/json_document.h"

namespace softslc::devicenet {

using nlohmann::json;

ConfigError::ConfigError(std::string path, const std::string& message)
    : std::runtime_error(path.empty() ? message : path + ": " + message), path_(std::move(path)) {}

std::string child_path(const std::string& path, std::string_view key) {
  return path.empty() ? std::string(key) : path + "." + std::string(key);
}

std::string element_path(const std::string& path, std::size_t index) {
  return path + "[" + std::to_string(index) + "]";
}

std::string describe(const json& value) {
  switch (value.type()) {
    case json::value_t::null: return "null";
    case json::value_t::boolean: return std::string("a boolean ") + (value.get<bool>() ? "true" : "false");
    case json::value_t::number_integer:
    case json::value_t::number_unsigned: return "an integer " + value.dump();
    case json::value_t::number_float: return "a number " + value.dump();
    // Strings from a bench file may hold any bytes: invalid UTF-8 is shown as U+FFFD, not thrown.
    case json::value_t::string: return "a string " + value.dump(-1, ' ', false, json::error_handler_t::replace);
    case json::value_t::array: return "an array";
    case json::value_t::object: return "an object";
    default: return "an unsupported value";
  }
}

json parse_json_text(std::string_view text, std::string_view source) {
  // Every JSON error (syntax, a number such as 1e309, nesting) is a positioned ConfigError.
  JsonDocument doc = parse_json_document(text);
  if (!doc.ok) throw ConfigError("", std::string(source) + ":" + doc.where_and_what());
  return std::move(doc.value);
}

std::int64_t integer_at(const json& value, const std::string& path, std::int64_t min, std::int64_t max) {
  if (!value.is_number_integer()) throw ConfigError(path, "expected an integer, got " + describe(value));
  std::int64_t v = 0;
  if (value.is_number_unsigned()) {
    const auto u = value.get<std::uint64_t>();
    if (u > static_cast<std::uint64_t>(max))
      throw ConfigError(path, "expected an integer in " + std::to_string(min) + "..." + std::to_string(max) +
                                  ", got " + value.dump());
    v = static_cast<std::int64_t>(u);
  } else {
    v = value.get<std::int64_t>();
  }
  if (v < min || v > max)
    throw ConfigError(path, "expected an integer in " + std::to_string(min) + "..." + std::to_string(max) + ", got " +
                                value.dump());
  return v;
}

ObjectReader::ObjectReader(const json& value, std::string path, std::initializer_list<std::string_view> allowed)
    : value_(value), path_(std::move(path)) {
  if (!value_.is_object()) throw ConfigError(path_, "expected a JSON object, got " + describe(value_));
  for (const auto& [key, v] : value_.items()) {
    bool ok = false;
    for (auto a : allowed) ok = ok || a == key;
    if (!ok) {
      std::string list;
      for (auto a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      throw ConfigError(child_path(path_, key), "unknown key (allowed: " + list + ")");
    }
  }
}

const json* ObjectReader::find(std::string_view key) const {
  auto it = value_.find(std::string(key));
  return it == value_.end() ? nullptr : &*it;
}

std::int64_t ObjectReader::integer(std::string_view key, std::int64_t min, std::int64_t max) const {
  const json* v = find(key);
  if (v == nullptr) throw ConfigError(path(key), "required; expected an integer");
  return integer_at(*v, path(key), min, max);
}

std::optional<std::int64_t> ObjectReader::optional_integer(std::string_view key, std::int64_t min,
                                                           std::int64_t max) const {
  const json* v = find(key);
  if (v == nullptr) return std::nullopt;
  return integer_at(*v, path(key), min, max);
}

bool ObjectReader::boolean(std::string_view key, bool fallback) const {
  const json* v = find(key);
  if (v == nullptr) return fallback;
  if (!v->is_boolean()) throw ConfigError(path(key), "expected true or false, got " + describe(*v));
  return v->get<bool>();
}

std::string ObjectReader::string(std::string_view key) const {
  const json* v = find(key);
  if (v == nullptr) throw ConfigError(path(key), "required; expected a string");
  if (!v->is_string()) throw ConfigError(path(key), "expected a string, got " + describe(*v));
  return v->get<std::string>();
}

std::string ObjectReader::optional_string(std::string_view key, std::string fallback) const {
  if (!has(key)) return fallback;
  return string(key);
}

std::string ObjectReader::choice(std::string_view key, std::initializer_list<std::string_view> choices,
                                 std::optional<std::string_view> fallback) const {
  std::string list;
  for (auto c : choices) list += (list.empty() ? "\"" : ", \"") + std::string(c) + "\"";
  const json* v = find(key);
  if (v == nullptr) {
    if (fallback) return std::string(*fallback);
    throw ConfigError(path(key), "required; expected one of " + list);
  }
  if (v->is_string())
    for (auto c : choices)
      if (v->get<std::string>() == c) return std::string(c);
  throw ConfigError(path(key), "expected one of " + list + ", got " + describe(*v));
}

void ObjectReader::array(std::string_view key,
                         const std::function<void(const json&, const std::string&)>& read) const {
  const json* v = find(key);
  if (v == nullptr) return;
  if (!v->is_array()) throw ConfigError(path(key), "expected an array, got " + describe(*v));
  for (std::size_t i = 0; i < v->size(); ++i) read((*v)[i], element_path(path(key), i));
}

const json* ObjectReader::object(std::string_view key) const {
  const json* v = find(key);
  if (v != nullptr && !v->is_object()) throw ConfigError(path(key), "expected a JSON object, got " + describe(*v));
  return v;
}

}  // namespace softslc::devicenet
