#include "integrators/scene_loading.h"

#include "integrators/method_registry.h"

namespace candela {

std::unique_ptr<Scene> load_scene_file(const std::string& path, const std::vector<std::string>& overrides) {
  return read_scene_file(path, overrides, method_settings_sections());
}

std::unique_ptr<Scene> load_scene_text(const std::string& text, const std::string& name,
                                       const std::string& base_directory,
                                       const std::vector<std::string>& overrides) {
  return read_scene_text(text, name, base_directory, overrides, method_settings_sections());
}

std::unique_ptr<Scene> load_default_scene(const std::vector<std::string>& overrides) {
  return read_default_scene(overrides, method_settings_sections());
}

}  // namespace candela
