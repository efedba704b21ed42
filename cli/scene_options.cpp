#include "scene_options.h"

#include "integrators/scene_loading.h"

namespace candela::cli {

std::unique_ptr<Scene> SceneOptions::load() const {
  return scene_path.empty() ? load_default_scene(overrides) : load_scene_file(scene_path, overrides);
}

}  // namespace candela::cli
