// Materials, textures and texture mappings by name (SPEC §7).
// Materials: "phong", "blinn-phong", "cook-torrance" (the classic local model with Whitted's
// kr, kt, the see-through transparency models and bump mapping; they differ in the specular
// term). Textures: constant, checkerboard (3D), checker2d, wood, marble, noise, waves, image.
// Mappings for 2D textures: uv, spherical, planar, cylindrical.
#pragma once

#include <memory>
#include <span>
#include <string_view>

#include "io/json_node.h"
#include "scene/load_context.h"
#include "shading/material.h"

namespace candela {

struct MaterialEntry {
  std::string_view name;
  std::string_view description;
  std::string_view example;
  Material (*create)(const JsonNode& node, const LoadContext& context);
};

// What a texture feeds: a color (kd, ka) or a scalar (ks, n, kr, kt, ior, roughness, a bump
// height). Image files default to sRGB decoding for colors and to linear for scalars (height
// maps and masks store plain numbers).
enum class TextureUse { color, scalar };

struct TextureEntry {
  std::string_view name;
  std::string_view description;
  std::string_view example;
  std::shared_ptr<const Texture> (*create)(const JsonNode& node, const LoadContext& context, TextureUse use);
};

struct MappingEntry {
  std::string_view name;
  std::string_view description;
  std::string_view example;
  // node is null for a mapping given by its bare name: every parameter takes its default.
  std::shared_ptr<const TextureMapping> (*create)(const JsonNode* node, const UvTransform& uv);
};

std::span<const MaterialEntry> material_entries();
const MaterialEntry* find_material(std::string_view name);
std::span<const TextureEntry> texture_entries();
const TextureEntry* find_texture(std::string_view name);
std::span<const MappingEntry> mapping_entries();
const MappingEntry* find_mapping(std::string_view name);

// A material object; "type" defaults to "phong".
Material read_material(const JsonNode& node, const LoadContext& context);
// A color ([r, g, b] or a number) or a texture object with a "type".
std::shared_ptr<const Texture> read_texture(const JsonNode& node, const LoadContext& context,
                                            TextureUse use = TextureUse::color);
// A number or a texture object, read through its channel mean; numbers and constant textures
// are checked against range.
std::shared_ptr<const Texture> read_scalar_texture(const JsonNode& node, const LoadContext& context,
                                                   Range range);
// The "mapping" member of a 2D texture: absent or "uv" for the shape's own uv, a name, or an
// object with "type", the mapping's parameters, "scale" ([su, sv] or s) and "offset".
std::shared_ptr<const TextureMapping> read_mapping(const JsonNode& texture);

}  // namespace candela
