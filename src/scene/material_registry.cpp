#include "scene/material_registry.h"

#include <array>

#include "shading/checkerboard_texture.h"
#include "util/registry.h"

namespace candela {

namespace {

Material make_phong(const JsonNode& node) {
  Material material;
  if (const auto kd = node.get("kd")) material.kd = read_texture(*kd);
  else material.kd = std::make_shared<ConstantTexture>(Color(0.8));
  if (node.has("ka")) {
    material.ka = node.color("ka", Color(), Range::non_negative());
    material.ka_follows_kd = false;
  }
  material.ks = node.number("ks", 0.0, Range::non_negative());
  material.shininess = node.number("n", 20.0, Range::at_least(0));
  material.specular_model = node.choice("specular", "phong", {"phong", "blinn-phong"}) == "phong"
                                ? SpecularModel::phong
                                : SpecularModel::blinn_phong;
  material.kr = node.number("kr", 0.0, Range::unit());
  material.kt = node.number("kt", 0.0, Range::unit());
  // Each level of the ray tree must carry less than its parent, or it never shrinks.
  if (material.kr + material.kt > 1)
    node.at(node.has("kt") ? "kt" : "kr").fail("kr + kt must be <= 1 (found " + std::to_string(material.kr + material.kt) + ")");
  material.ior = node.number("ior", 1.0, Range::positive());
  material.absorption = node.color("absorption", Color(), Range::non_negative());
  return material;
}

std::shared_ptr<const Texture> make_constant(const JsonNode& node) {
  return std::make_shared<ConstantTexture>(node.color("value", Color(1), Range::non_negative()));
}

std::shared_ptr<const Texture> make_checkerboard(const JsonNode& node) {
  const Color even = node.color("even", Color(0.9), Range::non_negative());
  const Color odd = node.color("odd", Color(0.1), Range::non_negative());
  const double size = node.number("size", 1.0, Range::positive());
  const Vec3 offset = node.vec3("offset", {0, 0, 0});
  return std::make_shared<CheckerboardTexture>(even, odd, size, offset);
}

const std::array kMaterials = {
    MaterialEntry{"phong",
                  "local model ka·Ia + Σ Ip·f_at·s·[kd(N·L) + ks(R·V)^n] (or Blinn-Phong N·H), "
                  "with Whitted's kr, kt and ior",
                  R"({"type": "phong", "kd": [0.7, 0.2, 0.2], "ks": 0.5, "n": 40, "specular": "blinn-phong", "kr": 0.2, "kt": 0, "ior": 1.5})",
                  make_phong},
};

const std::array kTextures = {
    TextureEntry{"constant", "one colour", R"({"type": "constant", "value": [0.5, 0.5, 0.5]})",
                 make_constant},
    TextureEntry{"checkerboard", "solid 3D checkerboard of cell size `size` in object space",
                 R"({"type": "checkerboard", "even": [0.9, 0.9, 0.9], "odd": [0.1, 0.1, 0.1], "size": 1})",
                 make_checkerboard},
};

}  // namespace

std::span<const MaterialEntry> material_entries() { return kMaterials; }
const MaterialEntry* find_material(std::string_view name) { return find_entry<MaterialEntry>(kMaterials, name); }
std::span<const TextureEntry> texture_entries() { return kTextures; }
const TextureEntry* find_texture(std::string_view name) { return find_entry<TextureEntry>(kTextures, name); }

Material read_material(const JsonNode& node) {
  node.expect_object();
  const std::string type = node.string("type", "phong");
  const MaterialEntry* entry = find_material(type);
  if (!entry)
    node.at("type").fail("unknown material \"" + type + "\" (expected one of: " + entry_names<MaterialEntry>(kMaterials) + ")");
  Material material = entry->create(node);
  node.allow({"name"});
  node.finish();
  return material;
}

std::shared_ptr<const Texture> read_texture(const JsonNode& node) {
  if (!node.json().is_object())
    return std::make_shared<ConstantTexture>(node.as_color(Range::non_negative()));
  const JsonNode type = node.at("type");
  const std::string name = type.as_string();
  const TextureEntry* entry = find_texture(name);
  if (!entry)
    type.fail("unknown texture \"" + name + "\" (expected one of: " + entry_names<TextureEntry>(kTextures) + ")");
  auto texture = entry->create(node);
  node.finish();
  return texture;
}

}  // namespace candela
