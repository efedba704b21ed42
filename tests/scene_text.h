// Scenes written inline in the tests: a body of shapes, materials and lights seen by a camera.
#pragma once

#include <memory>
#include <string>

#include "integrators/scene_loading.h"

namespace candela::testing {

inline std::unique_ptr<Scene> scene_from(const std::string& body, const std::string& camera,
                                         const std::string& directory = ".") {
  return load_scene_text(R"({"format": "candela/1", "camera": )" + camera + ", " + body + "}", "test.json",
                         directory);
}

// One pixel looking straight down −z through the image centre.
inline constexpr const char* kCentreCamera =
    R"({"eye": [0, 0, 10], "target": [0, 0, 0], "fov": 1, "width": 1, "height": 1})";

}  // namespace candela::testing
