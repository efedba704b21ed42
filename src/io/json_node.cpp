#include "io/json_node.h"

#include <fmt/format.h>

#include <cmath>

#include "math/constants.h"

namespace candela {

bool Range::contains(double value) const {
  const bool above = lower_open ? value > lower : value >= lower;
  const bool below = upper_open ? value < upper : value <= upper;
  return above && below;
}

std::string Range::describe() const {
  const bool has_lower = std::isfinite(lower), has_upper = std::isfinite(upper);
  if (has_lower && has_upper)
    return fmt::format("in {}{}, {}{}", lower_open ? '(' : '[', lower, upper, upper_open ? ')' : ']');
  if (has_lower) return fmt::format("{} {}", lower_open ? ">" : ">=", lower);
  if (has_upper) return fmt::format("{} {}", upper_open ? "<" : "<=", upper);
  return "finite";
}

namespace {
std::string type_name(const nlohmann::json& value) {
  if (value.is_number()) return "a number";
  if (value.is_string()) return "a string \"" + value.get<std::string>() + "\"";
  if (value.is_boolean()) return "a boolean";
  if (value.is_array()) return "an array";
  if (value.is_object()) return "an object";
  return "null";
}
}  // namespace

JsonNode::JsonNode(const JsonDocument& document, const nlohmann::json& value, std::string path)
    : document_(&document),
      value_(&value),
      path_(std::move(path)),
      known_keys_(std::make_shared<std::set<std::string, std::less<>>>()) {}

void JsonNode::fail(const std::string& message) const {
  throw InputError(location(), message);
}

double JsonNode::as_number(Range range) const {
  if (!value_->is_number()) fail("expected a number, found " + type_name(*value_));
  const double value = value_->get<double>();
  if (!std::isfinite(value)) fail("must be a finite number");
  static_assert(kMaxSceneMagnitude == 1e16, "the message below names it");
  if (std::fabs(value) > kMaxSceneMagnitude)
    fail(fmt::format("magnitude above 1e16 is not supported (found {})", value));
  if (!range.contains(value)) fail("must be " + range.describe() + fmt::format(" (found {})", value));
  return value;
}

int JsonNode::as_int(Range range) const {
  const double value = as_number(range);
  if (value != std::floor(value) || std::fabs(value) > 2147483647.0)
    fail(fmt::format("expected an integer, found {}", value));
  return static_cast<int>(value);
}

bool JsonNode::as_bool() const {
  if (!value_->is_boolean()) fail("expected true or false, found " + type_name(*value_));
  return value_->get<bool>();
}

std::string JsonNode::as_string() const {
  if (!value_->is_string()) fail("expected a string, found " + type_name(*value_));
  return value_->get<std::string>();
}

Vec3 JsonNode::as_vec3() const {
  if (!value_->is_array() || value_->size() != 3)
    fail("expected an array of 3 numbers [x, y, z], found " + type_name(*value_));
  return {element(0).as_number(), element(1).as_number(), element(2).as_number()};
}

Color JsonNode::as_color(Range per_channel) const {
  if (value_->is_number()) return Color(as_number(per_channel));
  if (!value_->is_array() || value_->size() != 3)
    fail("expected a color: [r, g, b] or one number, found " + type_name(*value_));
  return {element(0).as_number(per_channel), element(1).as_number(per_channel),
          element(2).as_number(per_channel)};
}

std::size_t JsonNode::size() const {
  if (!value_->is_array()) fail("expected an array, found " + type_name(*value_));
  return value_->size();
}

JsonNode JsonNode::element(std::size_t index) const {
  return JsonNode(*document_, (*value_)[index], path_ + "[" + std::to_string(index) + "]");
}

void JsonNode::expect_object() const {
  if (!value_->is_object()) fail("expected an object, found " + type_name(*value_));
}

bool JsonNode::has(std::string_view key) const {
  expect_object();
  known_keys_->emplace(key);
  return value_->contains(key);
}

JsonNode JsonNode::child(std::string_view key) const {
  const std::string name(key);
  return JsonNode(*document_, value_->at(name), path_.empty() ? name : path_ + "." + name);
}

JsonNode JsonNode::at(std::string_view key) const {
  if (!has(key)) fail(fmt::format("missing required key \"{}\"", key));
  return child(key);
}

std::optional<JsonNode> JsonNode::get(std::string_view key) const {
  if (!has(key)) return std::nullopt;
  return child(key);
}

double JsonNode::number(std::string_view key, double fallback, Range range) const {
  const auto node = get(key);
  return node ? node->as_number(range) : fallback;
}

double JsonNode::number(std::string_view key, Range range) const {
  return at(key).as_number(range);
}

int JsonNode::integer(std::string_view key, int fallback, Range range) const {
  const auto node = get(key);
  return node ? node->as_int(range) : fallback;
}

bool JsonNode::boolean(std::string_view key, bool fallback) const {
  const auto node = get(key);
  return node ? node->as_bool() : fallback;
}

std::string JsonNode::string(std::string_view key, const std::string& fallback) const {
  const auto node = get(key);
  return node ? node->as_string() : fallback;
}

Vec3 JsonNode::vec3(std::string_view key, const Vec3& fallback) const {
  const auto node = get(key);
  return node ? node->as_vec3() : fallback;
}

Vec3 JsonNode::vec3(std::string_view key) const {
  return at(key).as_vec3();
}

Color JsonNode::color(std::string_view key, const Color& fallback, Range per_channel) const {
  const auto node = get(key);
  return node ? node->as_color(per_channel) : fallback;
}

std::string JsonNode::choice(std::string_view key, const std::string& fallback,
                             std::initializer_list<std::string_view> choices) const {
  const auto node = get(key);
  if (!node) return fallback;
  const std::string value = node->as_string();
  for (const auto choice : choices)
    if (choice == value) return value;
  std::string valid;
  for (const auto choice : choices) valid += (valid.empty() ? "" : ", ") + std::string(choice);
  node->fail("unknown value \"" + value + "\" (expected one of: " + valid + ")");
}

void JsonNode::allow(std::initializer_list<std::string_view> keys) const {
  for (const auto key : keys) known_keys_->emplace(key);
}

void JsonNode::finish() const {
  expect_object();
  for (const auto& [key, value] : value_->items()) {
    if (known_keys_->count(key)) continue;
    std::string valid;
    for (const auto& known : *known_keys_) valid += (valid.empty() ? "" : ", ") + known;
    child(key).fail("unknown key \"" + key + "\"" +
                    (valid.empty() ? std::string() : " (expected one of: " + valid + ")"));
  }
}

}  // namespace candela
