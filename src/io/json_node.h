// A read cursor over one value of a JsonDocument. Every getter checks type and range and
// reports failures with file:line:column and the JSON path; finish() rejects the keys nobody
// asked for, listing the ones that are valid (STYLE.md habit 2).
#pragma once

#include <initializer_list>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>

#include "io/json_document.h"
#include "math/constants.h"
#include "math/vector.h"
#include "util/enum_names.h"

namespace candela {

struct Range {
  double lower = -kInfinity;
  double upper = kInfinity;
  bool lower_open = false;  // true: value must be > lower
  bool upper_open = false;  // true: value must be < upper

  static Range positive() { return {0, kInfinity, true, false}; }
  static Range non_negative() { return {0, kInfinity, false, false}; }
  static Range unit() { return {0, 1, false, false}; }
  static Range at_least(double value) { return {value, kInfinity, false, false}; }
  bool contains(double value) const;
  std::string describe() const;  // "> 0", "in [0, 1]"
};

class JsonNode {
 public:
  JsonNode(const JsonDocument& document, const nlohmann::json& value, std::string path);

  const std::string& path() const { return path_; }
  const nlohmann::json& json() const { return *value_; }
  SourceLocation location() const { return document_->locate(path_); }
  [[noreturn]] void fail(const std::string& message) const;

  // --- this value ---
  double as_number(Range range = {}) const;
  int as_int(Range range = {}) const;
  bool as_bool() const;
  std::string as_string() const;
  Vec3 as_vec3() const;
  // A color is [r, g, b] or one number for a grey.
  Color as_color(Range per_channel = {}) const;
  std::size_t size() const;  // elements of an array (fails otherwise)
  JsonNode element(std::size_t index) const;
  void expect_object() const;

  // --- members of this object (each call records the key as known) ---
  bool has(std::string_view key) const;
  JsonNode at(std::string_view key) const;  // a required member
  std::optional<JsonNode> get(std::string_view key) const;
  double number(std::string_view key, double fallback, Range range = {}) const;
  double number(std::string_view key, Range range = {}) const;
  int integer(std::string_view key, int fallback, Range range = {}) const;
  bool boolean(std::string_view key, bool fallback) const;
  std::string string(std::string_view key, const std::string& fallback) const;
  Vec3 vec3(std::string_view key, const Vec3& fallback) const;
  Vec3 vec3(std::string_view key) const;
  Color color(std::string_view key, const Color& fallback, Range per_channel = {}) const;
  // A string that must be one of the choices.
  std::string choice(std::string_view key, const std::string& fallback,
                     std::initializer_list<std::string_view> choices) const;
  // A string naming one of the table's values; fails listing the names otherwise.
  template <typename Enum, std::size_t N>
  Enum enumeration(std::string_view key, Enum fallback, const EnumNames<Enum, N>& names) const {
    const auto node = get(key);
    return node ? node->as_enumeration(names) : fallback;
  }
  template <typename Enum, std::size_t N>
  Enum as_enumeration(const EnumNames<Enum, N>& names) const {
    const std::string text = as_string();
    if (const auto value = names.value(text)) return *value;
    fail("unknown value \"" + text + "\" (expected one of: " + names.names() + ")");
  }
  // Marks keys that are read elsewhere as known without reading them.
  void allow(std::initializer_list<std::string_view> keys) const;
  // Fails on the first member nobody asked about.
  void finish() const;

 private:
  JsonNode child(std::string_view key) const;
  const JsonDocument* document_;
  const nlohmann::json* value_;
  std::string path_;
  std::shared_ptr<std::set<std::string, std::less<>>> known_keys_;
};

}  // namespace candela
