#include "scene/plugin_settings.h"

namespace candela {

namespace {
const nlohmann::json& empty_object() {
  static const nlohmann::json empty = nlohmann::json::object();
  return empty;
}
}  // namespace

// One empty document serves every scene made without a file.
PluginSettings::PluginSettings() {
  static const auto empty = std::make_shared<const JsonDocument>(JsonDocument::parse("{}", "<defaults>"));
  document_ = empty;
}

PluginSettings::PluginSettings(std::shared_ptr<const JsonDocument> document)
    : document_(std::move(document)) {}

bool PluginSettings::has(std::string_view key) const {
  const nlohmann::json& root = document_->root();
  return root.is_object() && root.contains(key);
}

JsonNode PluginSettings::node(std::string_view key) const {
  const std::string path(key);
  if (!has(key)) return JsonNode(*document_, empty_object(), path);
  return JsonNode(*document_, document_->root().at(path), path);
}

}  // namespace candela
