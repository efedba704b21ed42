// Loading a scene for rendering: the scene loader (scene/scene_loader.h) with every method's
// settings object checked at load time by the method's own reader (method_registry.h), so that a
// bad "whitted" or "radiosity" object is refused with file:line:column before any work.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "scene/scene_loader.h"

namespace candela {

std::unique_ptr<Scene> load_scene_file(const std::string& path,
                                       const std::vector<std::string>& overrides = {});
std::unique_ptr<Scene> load_scene_text(const std::string& text, const std::string& name,
                                       const std::string& base_directory,
                                       const std::vector<std::string>& overrides = {});
std::unique_ptr<Scene> load_default_scene(const std::vector<std::string>& overrides = {});

}  // namespace candela
