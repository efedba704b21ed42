#include "scene/material_registry.h"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "math/constants.h"
#include "scene/environment_registry.h"
#include "scene/json_transform.h"
#include "scene/photometric_settings.h"
#include "shading/checkerboard_texture.h"
#include "shading/image_texture.h"
#include "shading/photometric_units.h"
#include "shading/procedural_textures.h"
#include "util/registry.h"

namespace candela {

namespace {

// --- materials ---------------------------------------------------------------------------

Transparency read_transparency(const JsonNode& node) {
  node.expect_object();
  Transparency transparency;
  const std::string model = node.choice("model", "constant", {"constant", "linear", "nonlinear"});
  if (model == "constant") {
    transparency.model = TransparencyModel::constant;
    transparency.t_min = transparency.t_max = node.number("t", Range::unit());
  } else {
    transparency.model = model == "linear" ? TransparencyModel::linear : TransparencyModel::nonlinear;
    transparency.t_min = node.number("t_min", Range::unit());
    transparency.t_max = node.number("t_max", Range::unit());
    if (model == "nonlinear") transparency.exponent = node.number("m", 2.0, Range::positive());
  }
  node.finish();
  return transparency;
}

BumpMap read_bump(const JsonNode& node, const LoadContext& context) {
  node.expect_object();
  BumpMap bump;
  const JsonNode height = node.at("height");
  bump.height = read_scalar_texture(height, context, {});
  if (const auto* planar = dynamic_cast<const Texture2D*>(bump.height.get())) {
    const auto* spherical = dynamic_cast<const SphericalMapping*>(&planar->mapping());
    if (spherical && !spherical->has_center())
      height.fail(
          "a spherical mapping without \"center\" reads only the surface normal, which the bump's "
          "finite differences do not move: give the sphere's centre (object coordinates)");
  }
  bump.scale = node.number("scale", 1.0, {-1e6, 1e6, false, false});
  bump.delta = node.number("delta", 1e-4, {0, 1, true, false});
  node.finish();
  return bump;
}

double constant_value(const std::shared_ptr<const Texture>& texture) {
  SurfaceHit anywhere;
  return texture->evaluate_scalar(anywhere);
}

Material read_classic(const JsonNode& node, const LoadContext& context, SpecularModel fallback) {
  Material material;
  const std::string specular = node.choice("specular",
                                           fallback == SpecularModel::phong         ? "phong"
                                           : fallback == SpecularModel::blinn_phong ? "blinn-phong"
                                                                                    : "cook-torrance",
                                           {"phong", "blinn-phong", "cook-torrance"});
  material.specular_model = specular == "phong"         ? SpecularModel::phong
                            : specular == "blinn-phong" ? SpecularModel::blinn_phong
                                                        : SpecularModel::cook_torrance;
  if (const auto kd = node.get("kd")) material.kd = read_texture(*kd, context);
  if (const auto ka = node.get("ka")) material.ka = read_texture(*ka, context);
  // Cook-Torrance's ks weighs a term that is already a reflectance: 1 unless given.
  if (material.specular_model == SpecularModel::cook_torrance) material.ks = constant_texture(1.0);
  if (const auto ks = node.get("ks")) material.ks = read_scalar_texture(*ks, context, Range::non_negative());
  material.shininess = constant_texture(20.0);
  if (material.specular_model == SpecularModel::cook_torrance) {
    if (const auto m = node.get("roughness"))
      material.roughness = read_scalar_texture(*m, context, Range::positive());
    // The path tracer's facet distribution (docs/materials.md, "Path tracing").
    material.microfacet = node.choice("microfacet", "beckmann", {"beckmann", "ggx"}) == "ggx"
                              ? MicrofacetDistribution::ggx
                              : MicrofacetDistribution::beckmann;
    material.layered = node.boolean("layered", false);
  } else if (const auto n = node.get("n")) {
    material.shininess = read_scalar_texture(*n, context, Range::non_negative());
  }
  if (node.has("layered") && material.specular_model != SpecularModel::cook_torrance)
    node.at("layered").fail("is for cook-torrance materials (a diffuse under a microfacet reflection)");
  if (const auto kr = node.get("kr")) material.kr = read_scalar_texture(*kr, context, Range::unit());
  if (const auto kt = node.get("kt")) material.kt = read_scalar_texture(*kt, context, Range::unit());
  // Each level of the ray tree must carry less than its parent, or it never shrinks; textured
  // values are scaled down where they exceed 1 (Material::at).
  if (material.kr->is_constant() && material.kt->is_constant()) {
    const double sum = constant_value(material.kr) + constant_value(material.kt);
    if (sum > 1)
      node.at(node.has("kt") ? "kt" : "kr").fail(fmt::format("kr + kt must be <= 1 (found {})", sum));
  }
  if (const auto ior = node.get("ior")) material.ior = read_scalar_texture(*ior, context, Range::positive());
  material.thin = node.boolean("thin", false);
  if (material.thin && !node.has("kt"))
    node.at("thin").fail("a thin sheet needs kt, the part of the light it lets through");
  if (material.specular_model == SpecularModel::cook_torrance) {
    // The Fresnel index defaults to the refraction index when that is a constant.
    const Color fallback_ior =
        material.ior->is_constant() && node.has("ior") ? Color(constant_value(material.ior)) : Color(1.5);
    const Color eta = node.color("fresnel_ior", fallback_ior, Range::positive());
    if (const auto f0 = node.get("fresnel_f0")) {
      // A measured reflectance at normal incidence: Schlick's form, which whitens toward grazing
      // incidence as a metal does (shading/fresnel.h: not Cook and Torrance's derived index,
      // whose Brewster dip turns copper bluish near 87°).
      if (node.has("fresnel_ior")) f0->fail("give fresnel_ior or fresnel_f0, not both");
      if (node.has("fresnel_k"))
        f0->fail("give fresnel_k with fresnel_ior (a metal's n + iκ), not with fresnel_f0");
      material.fresnel = Fresnel::schlick(f0->as_color({0, 1, false, true}));
    } else if (node.has("fresnel_k")) {
      // A conductor's complex index n + iκ per channel (a metal's measured optical constants).
      material.fresnel = Fresnel::conductor(eta, node.color("fresnel_k", Color(), Range::non_negative()));
    } else {
      material.fresnel = Fresnel::dielectric(eta);
    }
  }
  material.absorption = node.color("absorption", Color(), Range::non_negative());
  if (material.thin && node.has("absorption"))
    node.at("absorption")
        .fail(
            "absorption is per unit length inside a solid; a thin sheet has no inside (kt is its "
            "transmittance)");
  // 000 eq. 6-7's E (W/m², radiance E/π), or "emission_luminance" (cd/m²: E = π L / 179 lm/W)
  // or "emission_luminous_flux" (lm from each side of each object: the loader divides by its area)
  // of "emission_color" or "emission_temperature".
  const std::string amount = amount_key(node, {"emission", "emission_luminance", "emission_luminous_flux"});
  if (amount == "emission") {
    material.emission = node.color("emission", Color(), Range::non_negative());
  } else if (amount == "emission_luminance") {
    material.emission = radiometric(kPi * node.number("emission_luminance", 0, Range::non_negative()),
                                    read_photometric_color(node, "emission_color", "emission_temperature"));
  } else {
    material.emission_flux = node.number("emission_luminous_flux", 0, Range::non_negative());
    material.emission_flux_color = read_photometric_color(node, "emission_color", "emission_temperature");
  }
  if (const auto transparency = node.get("transparency"))
    material.transparency = read_transparency(*transparency);
  if (const auto bump = node.get("bump")) material.bump = read_bump(*bump, context);
  return material;
}

Material make_phong(const JsonNode& node, const LoadContext& context) {
  return read_classic(node, context, SpecularModel::phong);
}
Material make_blinn_phong(const JsonNode& node, const LoadContext& context) {
  return read_classic(node, context, SpecularModel::blinn_phong);
}
Material make_cook_torrance(const JsonNode& node, const LoadContext& context) {
  return read_classic(node, context, SpecularModel::cook_torrance);
}

// --- mappings ----------------------------------------------------------------------------

// Defaults when the mapping is given by its bare name (node null).
Vec3 vec3_or(const JsonNode* node, std::string_view key, const Vec3& fallback) {
  return node ? node->vec3(key, fallback) : fallback;
}

template <typename Make>
std::shared_ptr<const TextureMapping> checked(const JsonNode* node, Make make) {
  try {
    return make();
  } catch (const std::invalid_argument& e) {
    if (!node) throw;
    node->fail(e.what());
  }
}

std::shared_ptr<const TextureMapping> make_uv_mapping(const JsonNode*, const UvTransform& uv) {
  return std::make_shared<ParametricMapping>(uv);
}

std::shared_ptr<const TextureMapping> make_spherical_mapping(const JsonNode* node, const UvTransform& uv) {
  const Vec3 pole = vec3_or(node, "pole", {0, 1, 0});
  const Vec3 equator = vec3_or(node, "equator", {1, 0, 0});
  std::optional<Vec3> center;
  if (node && node->has("center")) center = node->vec3("center");
  return checked(node, [&] {
    return std::make_shared<SphericalMapping>(pole, equator, center ? &*center : nullptr, uv);
  });
}

std::shared_ptr<const TextureMapping> make_planar_mapping(const JsonNode* node, const UvTransform& uv) {
  const Vec3 origin = vec3_or(node, "origin", {0, 0, 0});
  const Vec3 u_axis = vec3_or(node, "u_axis", {1, 0, 0});
  const Vec3 v_axis = vec3_or(node, "v_axis", {0, 1, 0});
  return checked(node, [&] { return std::make_shared<PlanarMapping>(origin, u_axis, v_axis, uv); });
}

std::shared_ptr<const TextureMapping> make_cylindrical_mapping(const JsonNode* node, const UvTransform& uv) {
  const Vec3 center = vec3_or(node, "center", {0, 0, 0});
  const Vec3 axis = vec3_or(node, "axis", {0, 1, 0});
  const Vec3 reference = vec3_or(node, "reference", {1, 0, 0});
  const double height = node ? node->number("height", 1.0, Range::positive()) : 1.0;
  return checked(node,
                 [&] { return std::make_shared<CylindricalMapping>(center, axis, reference, height, uv); });
}

const std::array kMappings = {
    MappingEntry{"uv",
                 "the shape's own parametric uv (polygon, disc, cylinder, cone, torus, box, sphere, OBJ vt)",
                 R"({"type": "uv", "scale": [4, 2], "offset": [0, 0]})", make_uv_mapping},
    MappingEntry{"spherical", "latitude/longitude of 000 §4.1.1 from the normal, or from a centre",
                 R"({"type": "spherical", "pole": [0, 1, 0], "equator": [1, 0, 0]})", make_spherical_mapping},
    MappingEntry{"planar", "u = (p − origin)·u_axis, v = (p − origin)·v_axis in object coordinates",
                 R"({"type": "planar", "origin": [0, 0, 0], "u_axis": [1, 0, 0], "v_axis": [0, 0, -1]})",
                 make_planar_mapping},
    MappingEntry{
        "cylindrical", "u = angle about the axis / 2π from reference, v = height / height",
        R"({"type": "cylindrical", "center": [0, 0, 0], "axis": [0, 1, 0], "reference": [1, 0, 0], "height": 2})",
        make_cylindrical_mapping},
};

UvTransform read_uv_transform(const JsonNode& node) {
  UvTransform uv;
  if (const auto scale = node.get("scale")) {
    if (scale->json().is_number()) {
      const double s = scale->as_number();
      if (s == 0) scale->fail("must be non-zero");
      uv.scale = {s, s};
    } else {
      if (scale->size() != 2) scale->fail("expected [su, sv] or one number");
      uv.scale = {scale->element(0).as_number(), scale->element(1).as_number()};
      if (uv.scale.x == 0 || uv.scale.y == 0) scale->fail("must be non-zero");
    }
  }
  if (const auto offset = node.get("offset")) {
    if (offset->size() != 2) offset->fail("expected [ou, ov]");
    uv.offset = {offset->element(0).as_number(), offset->element(1).as_number()};
  }
  return uv;
}

// --- textures ----------------------------------------------------------------------------

// The placement of a solid texture: "transform" (as for shapes) moves the pattern within the
// object; the texture reads points through its inverse.
Transform read_solid_placement(const JsonNode& node) {
  if (const auto transform = node.get("transform")) return read_transform(*transform).inverse();
  return {};
}

template <typename Make>
std::shared_ptr<const Texture> checked_texture(const JsonNode& node, Make make) {
  try {
    return make();
  } catch (const std::invalid_argument& e) {
    node.fail(e.what());
  }
}

std::shared_ptr<const Texture> make_constant(const JsonNode& node, const LoadContext&, TextureUse) {
  return std::make_shared<ConstantTexture>(node.color("value", Color(1), Range::non_negative()));
}

std::shared_ptr<const Texture> make_checkerboard(const JsonNode& node, const LoadContext&, TextureUse) {
  const Color even = node.color("even", Color(0.9), Range::non_negative());
  const Color odd = node.color("odd", Color(0.1), Range::non_negative());
  const double size = node.number("size", 1.0, Range::positive());
  const Vec3 offset = node.vec3("offset", {0, 0, 0});
  const Transform placement = read_solid_placement(node);
  return checked_texture(node, [&] {
    return std::make_shared<CheckerboardTexture>(even, odd, size, Transform::translate(offset) * placement);
  });
}

std::shared_ptr<const Texture> make_checker2d(const JsonNode& node, const LoadContext&, TextureUse) {
  const Color even = node.color("even", Color(0.9), Range::non_negative());
  const Color odd = node.color("odd", Color(0.1), Range::non_negative());
  return std::make_shared<Checkerboard2DTexture>(even, odd, read_mapping(node));
}

std::shared_ptr<const Texture> make_image(const JsonNode& node, const LoadContext& context, TextureUse use) {
  const ColorEncoding encoding =
      use == TextureUse::scalar && !node.has("encoding") ? ColorEncoding::linear : read_color_encoding(node);
  const WrapMode wrap = read_wrap_mode(node);
  const Color multiplier = node.color("multiplier", Color(1), Range::non_negative());
  auto image = load_texture_image(node.at("file"), context, encoding);
  return std::make_shared<ImageTexture>(std::move(image), wrap, multiplier, read_mapping(node));
}

const std::array kMaterials = {
    MaterialEntry{
        "phong",
        "local model ka·Ia + Σ Ip·f_at·s·[kd(N·L) + ks(R·V)^n] with Whitted's kr, kt and ior; "
        "\"specular\" picks phong, blinn-phong or cook-torrance",
        R"({"type": "phong", "kd": [0.7, 0.2, 0.2], "ks": 0.5, "n": 40, "kr": 0.2, "kt": 0, "ior": 1.5})",
        make_phong},
    MaterialEntry{"blinn-phong", "as phong with the specular term ks(N·H)^n",
                  R"({"type": "blinn-phong", "kd": [0.2, 0.5, 0.2], "ks": 0.4, "n": 80})", make_blinn_phong},
    MaterialEntry{
        "cook-torrance",
        "specular term ks·(N·L)·DGF/(π(N·V)(N·L)) (000 §4.2.2): Beckmann roughness m, "
        "Fresnel per RGB channel (fresnel_ior a dielectric's index, with fresnel_k a metal's n + iκ, or "
        "fresnel_f0 the "
        "reflectance at normal incidence in Schlick's form)",
        R"({"type": "cook-torrance", "kd": [0.1, 0.05, 0.02], "ks": 1, "roughness": 0.3, "fresnel_f0": [0.9, 0.7, 0.3]})",
        make_cook_torrance},
};

}  // namespace

std::shared_ptr<const TextureMapping> read_mapping(const JsonNode& texture) {
  const auto mapping = texture.get("mapping");
  if (!mapping) return std::make_shared<ParametricMapping>();
  const bool is_object = mapping->json().is_object();
  const std::string name = is_object ? mapping->at("type").as_string() : mapping->as_string();
  const MappingEntry* entry = find_mapping(name);
  if (!entry)
    (is_object ? mapping->at("type") : *mapping)
        .fail("unknown mapping \"" + name + "\" (expected one of: " + entry_names<MappingEntry>(kMappings) +
              ")");
  if (!is_object) return entry->create(nullptr, {});
  const UvTransform uv = read_uv_transform(*mapping);
  auto result = entry->create(&*mapping, uv);
  mapping->finish();
  return result;
}

namespace {

const Range kOctaves{1, 16, false, false};

std::shared_ptr<const Texture> make_wood(const JsonNode& node, const LoadContext&, TextureUse) {
  WoodParameters p;
  p.light = node.color("light", p.light, Range::non_negative());
  p.dark = node.color("dark", p.dark, Range::non_negative());
  p.ring_frequency = node.number("ring_frequency", p.ring_frequency, Range::positive());
  p.turbulence = node.number("turbulence", p.turbulence, Range::non_negative());
  p.noise_scale = node.number("noise_scale", p.noise_scale, Range::positive());
  p.octaves = node.integer("octaves", p.octaves, kOctaves);
  const Transform placement = read_solid_placement(node);
  return checked_texture(node, [&] { return std::make_shared<WoodTexture>(p, placement); });
}

std::shared_ptr<const Texture> make_marble(const JsonNode& node, const LoadContext&, TextureUse) {
  MarbleParameters p;
  p.base = node.color("base", p.base, Range::non_negative());
  p.vein = node.color("vein", p.vein, Range::non_negative());
  p.frequency = node.number("frequency", p.frequency, Range::positive());
  p.turbulence = node.number("turbulence", p.turbulence, Range::non_negative());
  p.noise_scale = node.number("noise_scale", p.noise_scale, Range::positive());
  p.octaves = node.integer("octaves", p.octaves, kOctaves);
  p.sharpness = node.number("sharpness", p.sharpness, Range::positive());
  const Transform placement = read_solid_placement(node);
  return checked_texture(node, [&] { return std::make_shared<MarbleTexture>(p, placement); });
}

std::shared_ptr<const Texture> make_noise(const JsonNode& node, const LoadContext&, TextureUse) {
  NoiseParameters p;
  p.mode =
      node.choice("mode", "fbm", {"fbm", "turbulence"}) == "fbm" ? NoiseMode::fbm : NoiseMode::turbulence;
  p.octaves = node.integer("octaves", p.octaves, kOctaves);
  p.lacunarity = node.number("lacunarity", p.lacunarity, Range::positive());
  p.gain = node.number("gain", p.gain, Range::positive());
  p.amplitude = node.number("amplitude", p.amplitude);
  p.offset = node.number("offset", p.offset);
  p.scale = node.number("scale", p.scale, Range::positive());
  const Transform placement = read_solid_placement(node);
  return checked_texture(node, [&] { return std::make_shared<NoiseTexture>(p, placement); });
}

std::shared_ptr<const Texture> make_waves(const JsonNode& node, const LoadContext&, TextureUse) {
  const JsonNode list = node.at("waves");
  if (list.size() == 0) list.fail("expected at least one wave");
  std::vector<Wave> waves;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const JsonNode item = list.element(i);
    item.expect_object();
    Wave wave;
    wave.amplitude = item.number("amplitude", 1.0);
    const JsonNode frequency = item.at("frequency");
    if (frequency.size() != 2) frequency.fail("expected [cycles per unit u, cycles per unit v]");
    wave.frequency = {frequency.element(0).as_number(), frequency.element(1).as_number()};
    if (wave.frequency.x == 0 && wave.frequency.y == 0) frequency.fail("must not be [0, 0]");
    wave.phase = item.number("phase", 0.0);
    item.finish();
    waves.push_back(wave);
  }
  return checked_texture(
      node, [&] { return std::make_shared<WavesTexture>(std::move(waves), read_mapping(node)); });
}

const std::array kTextures = {
    TextureEntry{"constant", "one color", R"({"type": "constant", "value": [0.5, 0.5, 0.5]})", make_constant},
    TextureEntry{"checkerboard", "solid 3D checkerboard of cell size `size` in object space",
                 R"({"type": "checkerboard", "even": [0.9, 0.9, 0.9], "odd": [0.1, 0.1, 0.1], "size": 1})",
                 make_checkerboard},
    TextureEntry{
        "checker2d", "checkerboard of unit cells in (u, v) through a mapping",
        R"({"type": "checker2d", "even": [0.9, 0.9, 0.9], "odd": [0.2, 0.2, 0.2], "mapping": {"type": "uv", "scale": [8, 4]}})",
        make_checker2d},
    TextureEntry{
        "wood", "concentric rings about the z axis perturbed by gradient noise",
        R"({"type": "wood", "light": [0.75, 0.52, 0.3], "dark": [0.45, 0.26, 0.12], "ring_frequency": 6, "turbulence": 0.4})",
        make_wood},
    TextureEntry{
        "marble", "sin(frequency·x + turbulence) veins (Perlin 1985)",
        R"({"type": "marble", "base": [0.9, 0.9, 0.88], "vein": [0.3, 0.3, 0.35], "frequency": 4, "turbulence": 5})",
        make_marble},
    TextureEntry{"noise", "gradient-noise grey value (fbm or turbulence), for heights and masks",
                 R"({"type": "noise", "mode": "fbm", "octaves": 4, "scale": 4})", make_noise},
    TextureEntry{"waves", "sum of sine waves over (u, v), for bump heights (000 §4.2.1)",
                 R"({"type": "waves", "waves": [{"amplitude": 1, "frequency": [8, 0]}], "mapping": "uv"})",
                 make_waves},
    TextureEntry{
        "image", "PNG, JPG, EXR or PFM image, bilinear, wrap repeat/clamp/mirror",
        R"({"type": "image", "file": "textures/checker.png", "wrap": "repeat", "mapping": {"type": "uv", "scale": 2}})",
        make_image},
};

}  // namespace

std::span<const MaterialEntry> material_entries() {
  return kMaterials;
}
const MaterialEntry* find_material(std::string_view name) {
  return find_entry<MaterialEntry>(kMaterials, name);
}
std::span<const TextureEntry> texture_entries() {
  return kTextures;
}
const TextureEntry* find_texture(std::string_view name) {
  return find_entry<TextureEntry>(kTextures, name);
}
std::span<const MappingEntry> mapping_entries() {
  return kMappings;
}
const MappingEntry* find_mapping(std::string_view name) {
  return find_entry<MappingEntry>(kMappings, name);
}

Material read_material(const JsonNode& node, const LoadContext& context) {
  node.expect_object();
  const std::string type = node.string("type", "phong");
  const MaterialEntry* entry = find_material(type);
  if (!entry)
    node.at("type").fail("unknown material \"" + type +
                         "\" (expected one of: " + entry_names<MaterialEntry>(kMaterials) + ")");
  Material material = entry->create(node, context);
  node.allow({"name"});
  node.finish();
  return material;
}

std::shared_ptr<const Texture> read_texture(const JsonNode& node, const LoadContext& context,
                                            TextureUse use) {
  if (!node.json().is_object())
    return std::make_shared<ConstantTexture>(node.as_color(Range::non_negative()));
  const JsonNode type = node.at("type");
  const std::string name = type.as_string();
  const TextureEntry* entry = find_texture(name);
  if (!entry)
    type.fail("unknown texture \"" + name + "\" (expected one of: " + entry_names<TextureEntry>(kTextures) +
              ")");
  auto texture = entry->create(node, context, use);
  node.finish();
  return texture;
}

std::shared_ptr<const Texture> read_scalar_texture(const JsonNode& node, const LoadContext& context,
                                                   Range range) {
  if (node.json().is_number()) return constant_texture(node.as_number(range));
  if (!node.json().is_object()) node.fail("expected a number or a texture object with a \"type\"");
  auto texture = read_texture(node, context, TextureUse::scalar);
  if (texture->is_constant()) {
    const double value = texture->evaluate_scalar(SurfaceHit{});
    if (!range.contains(value)) node.fail(fmt::format("must be {} (found {})", range.describe(), value));
  }
  return texture;
}

}  // namespace candela
