// Strict JSON reading with pathed errors, shared by the device description and scanlist loaders.
//
// Every object's keys are checked against the keys its kind allows, so a misspelt key is an error
// rather than a silently ignored setting; every value's JSON type and range is checked; and every
// error names the JSON path of the offending field ("devices[2].io.poll.produce", "" for the
// document itself) so a user can find it. ConfigError is also what the C++ API throws for a
// configuration it refuses, with the path of the equivalent JSON field.
#pragma once

#include <cstdint>
#include <functional>
#include <initializer_list>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace softslc::devicenet {

class ConfigError : public std::runtime_error {
 public:
  ConfigError(std::string path, const std::string& message);
  const std::string& path() const noexcept { return path_; }

 private:
  std::string path_;
};

std::string child_path(const std::string& path, std::string_view key);
std::string element_path(const std::string& path, std::size_t index);
// "an integer 3", "a string \"x\"", ... for error messages.
std::string describe(const nlohmann::json& value);
// Parses `text` as JSON; a syntax error becomes a ConfigError at path "" naming `source` and the
// byte offset.
nlohmann::json parse_json_text(std::string_view text, std::string_view source);

class ObjectReader {
 public:
  // Throws unless `value` is an object whose keys are all in `allowed`.
  ObjectReader(const nlohmann::json& value, std::string path, std::initializer_list<std::string_view> allowed);

  const std::string& path() const { return path_; }
  std::string path(std::string_view key) const { return child_path(path_, key); }
  const nlohmann::json* find(std::string_view key) const;
  bool has(std::string_view key) const { return find(key) != nullptr; }

  std::int64_t integer(std::string_view key, std::int64_t min, std::int64_t max) const;
  std::optional<std::int64_t> optional_integer(std::string_view key, std::int64_t min, std::int64_t max) const;
  bool boolean(std::string_view key, bool fallback) const;
  std::string string(std::string_view key) const;
  std::string optional_string(std::string_view key, std::string fallback = {}) const;
  // A string that must be one of `choices`.
  std::string choice(std::string_view key, std::initializer_list<std::string_view> choices,
                     std::optional<std::string_view> fallback = std::nullopt) const;
  // An optional array; `read` gets each element and its path.
  void array(std::string_view key, const std::function<void(const nlohmann::json&, const std::string&)>& read) const;
  // An optional nested object.
  const nlohmann::json* object(std::string_view key) const;

 private:
  const nlohmann::json& value_;
  std::string path_;
};

std::int64_t integer_at(const nlohmann::json& value, const std::string& path, std::int64_t min, std::int64_t max);

}  // namespace softslc::devicenet
