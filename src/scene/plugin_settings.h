// The objects of the scene file that plugins read themselves: each method's ("whitted",
// "radiosity", ...) and each accelerator's ("bvh", "grid", "octree"). The scene keeps them as
// parsed JSON with their positions, so that a plugin's errors still name file:line:column (or the
// --set assignment that gave the value), as pbrt's and Mitsuba's plugins read their own
// parameters. The loader checks every such object at load time with its plugin's reader.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <string_view>

#include "io/json_document.h"
#include "io/json_node.h"

namespace candela {

// A top-level object of the scene file that a plugin above the scene reads (a method's settings):
// its key, and the check the loader runs on it (the plugin's own reader; throws InputError).
struct SettingsSection {
  std::string_view key;
  std::function<void(const JsonNode& node)> check;
};

class PluginSettings {
 public:
  PluginSettings();  // no file: every plugin's defaults
  explicit PluginSettings(std::shared_ptr<const JsonDocument> document);

  // A fresh cursor over the object `key` (its keys all unread), or over an empty object standing
  // at path `key` when the file has none: the plugin's defaults.
  JsonNode node(std::string_view key) const;
  bool has(std::string_view key) const;

 private:
  std::shared_ptr<const JsonDocument> document_;
};

}  // namespace candela
