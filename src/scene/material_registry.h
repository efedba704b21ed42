// Materials and textures by name. One material model today ("phong": the classic local model
// with Whitted's kr, kt); textures "constant" and "checkerboard".
#pragma once

#include <memory>
#include <span>
#include <string_view>

#include "scene/json_node.h"
#include "shading/material.h"

namespace candela {

struct MaterialEntry {
  std::string_view name;
  std::string_view description;
  std::string_view example;
  Material (*create)(const JsonNode& node);
};

struct TextureEntry {
  std::string_view name;
  std::string_view description;
  std::string_view example;
  std::shared_ptr<const Texture> (*create)(const JsonNode& node);
};

std::span<const MaterialEntry> material_entries();
const MaterialEntry* find_material(std::string_view name);
std::span<const TextureEntry> texture_entries();
const TextureEntry* find_texture(std::string_view name);

// A material object; "type" defaults to "phong".
Material read_material(const JsonNode& node);
// A colour ([r, g, b] or a number) or a texture object with a "type".
std::shared_ptr<const Texture> read_texture(const JsonNode& node);

}  // namespace candela
