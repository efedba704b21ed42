// Options shared by the sub-commands that read a scene: SCENE and --set.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace candela::cli {

struct SceneOptions {
  std::string scene_path;  // empty: the built-in default scene
  std::vector<std::string> overrides;
  std::unique_ptr<Scene> load() const;
};

}  // namespace candela::cli
