#pragma once

#include <memory>
#include <span>
#include <string_view>

#include "camera/camera.h"
#include "io/json_node.h"

namespace candela {

struct CameraEntry {
  std::string_view name;
  std::string_view description;
  std::string_view example;
  std::unique_ptr<Camera> (*create)(const JsonNode& node, int width, int height);
};

std::span<const CameraEntry> camera_entries();
const CameraEntry* find_camera(std::string_view name);
// The "camera" object: type (default perspective), width, height and the type's own keys.
// default_width and default_height stand in for absent width and height (the named cameras of
// "cameras" take the image size of "camera").
std::unique_ptr<Camera> read_camera(const JsonNode& node, int default_width = 640, int default_height = 480);

}  // namespace candela
