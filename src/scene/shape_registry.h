// Shapes by the name used in the scene file's "type" (STYLE.md habit 2: an explicit table).
#pragma once

#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "geometry/shape.h"
#include "io/json_node.h"
#include "math/transform.h"
#include "scene/load_context.h"

namespace candela {

struct ShapeBuild {
  std::vector<std::unique_ptr<Shape>> shapes;
  // Per shape: a material index from the context, or -1 for the object's own material.
  std::vector<int> materials;
  bool transform_applied = false;  // meshes bake the transform into their vertices
};

struct ShapeEntry {
  std::string_view name;
  std::string_view description;
  std::string_view example;  // a complete JSON object for docs and the registry test
  // Reads the entry's own keys (not type, name, material, transform) and builds the shapes.
  ShapeBuild (*create)(const JsonNode& node, const Transform& transform, LoadContext& context);
};

std::span<const ShapeEntry> shape_entries();
const ShapeEntry* find_shape(std::string_view name);

}  // namespace candela
