#include "scene/light_registry.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>

#include "io/eulumdat_reader.h"
#include "io/ies_reader.h"
#include "math/constants.h"
#include "math/direction.h"
#include "scene/area_light.h"
#include "scene/directional_light.h"
#include "scene/luminaire_light.h"
#include "scene/photometric_settings.h"
#include "scene/point_light.h"
#include "scene/solar_settings.h"
#include "scene/spot_light.h"
#include "shading/photometric_units.h"
#include "util/registry.h"

namespace candela {

namespace {

// "attenuation": "none" | "inverse-square" | {"mode": "linear", "d0": 1} |
// {"mode": "polynomial", "constant": c, "linear": l, "quadratic": q}
Attenuation read_attenuation(const JsonNode& light) {
  Attenuation attenuation;
  const auto node = light.get("attenuation");
  if (!node) return attenuation;
  std::string mode;
  std::optional<JsonNode> object;
  if (node->json().is_string()) {
    mode = node->as_string();
  } else {
    object = node;
    mode = node->at("mode").as_string();
  }
  if (mode == "none")
    attenuation.mode = Attenuation::Mode::none;
  else if (mode == "inverse-square")
    attenuation.mode = Attenuation::Mode::inverse_square;
  else if (mode == "linear")
    attenuation.mode = Attenuation::Mode::linear;
  else if (mode == "polynomial")
    attenuation.mode = Attenuation::Mode::polynomial;
  else
    (object ? object->at("mode") : *node)
        .fail("unknown attenuation \"" + mode +
              "\" (expected one of: none, inverse-square, linear, polynomial)");
  if (object) {
    if (attenuation.mode == Attenuation::Mode::linear)
      attenuation.d0 = object->number("d0", 1.0, Range::non_negative());
    if (attenuation.mode == Attenuation::Mode::polynomial) {
      attenuation.constant = object->number("constant", 1.0, Range::non_negative());
      attenuation.linear_coefficient = object->number("linear", 0.0, Range::non_negative());
      attenuation.quadratic = object->number("quadratic", 0.0, Range::non_negative());
      if (attenuation.constant + attenuation.linear_coefficient + attenuation.quadratic <= 0)
        object->fail("constant, linear and quadratic cannot all be 0");
    }
    object->finish();
  } else if (attenuation.mode == Attenuation::Mode::linear ||
             attenuation.mode == Attenuation::Mode::polynomial) {
    // Defaults: d0 = 1; c = 1 (no attenuation until coefficients are given).
  }
  return attenuation;
}

Color intensity_of(const JsonNode& node) {
  return node.color("intensity", Color(1), Range::non_negative());
}

// A point or spot light given in candela or lumens shines as a physical source: inverse-square
// attenuation (the default then; any other is refused). Its f = 1/(4π d²) (000 §2.6) makes the
// light's "intensity" a power: I candela become an intensity of 4π I / K.
Attenuation photometric_attenuation(const JsonNode& node) {
  const Attenuation attenuation = read_attenuation(node);
  if (node.json().contains("attenuation") && attenuation.mode != Attenuation::Mode::inverse_square)
    node.at("attenuation")
        .fail(
            "a light given in candela or lumens falls off as the inverse square: "
            "\"inverse-square\" or no attenuation key");
  Attenuation physical = attenuation;
  physical.mode = Attenuation::Mode::inverse_square;
  return physical;
}

std::unique_ptr<Light> make_ambient(const JsonNode& node, Color& ambient, const LoadContext&) {
  ambient += intensity_of(node);
  return nullptr;
}

// "intensity" (RGB, W/sr), "luminous_intensity" (cd) or "luminous_flux" (lm, over the 4π sr).
std::unique_ptr<Light> make_point(const JsonNode& node, Color&, const LoadContext&) {
  const Vec3 position = node.vec3("position");
  const std::string key = amount_key(node, {"intensity", "luminous_intensity", "luminous_flux"});
  if (key == "intensity")
    return std::make_unique<PointLight>(position, intensity_of(node), read_attenuation(node));
  const double amount = node.number(key, 0, Range::non_negative());
  const double candela = key == "luminous_flux" ? amount / (4 * kPi) : amount;
  return std::make_unique<PointLight>(position, radiometric(4 * kPi * candela, read_photometric_color(node)),
                                      photometric_attenuation(node));
}

// A directional light's disc: "angular_diameter" (degrees, 0 to 10; 0: one direction) and, for a
// disc, "samples" (per side of its strata, 1 to 64, default 4).
struct DirectionalDisc {
  double radians = 0;
  int samples = 1;
};
DirectionalDisc read_directional_disc(const JsonNode& node, double default_degrees) {
  DirectionalDisc disc;
  disc.radians = node.number("angular_diameter", default_degrees, {0, 10, false, false}) * kPi / 180;
  disc.samples = node.integer("samples", 4, {1, 64, false, false});
  return disc;
}

// "intensity" (RGB, W/m² on a surface facing it) or "illuminance" (lux on such a surface); a disc
// of directions by "angular_diameter" (default 0).
std::unique_ptr<Light> make_directional(const JsonNode& node, Color&, const LoadContext&) {
  const JsonNode direction = node.at("direction");
  const Vec3 d = direction.as_vec3();
  if (!direction_of(d)) direction.fail("must be non-zero");
  const DirectionalDisc disc = read_directional_disc(node, 0);
  const Color intensity =
      amount_key(node, {"intensity", "illuminance"}) == "intensity"
          ? intensity_of(node)
          : radiometric(node.number("illuminance", 0, Range::non_negative()), read_photometric_color(node));
  return std::make_unique<DirectionalLight>(d, intensity, "directional", disc.radians, disc.samples);
}

std::unique_ptr<Light> make_spot(const JsonNode& node, Color&, const LoadContext&) {
  const Vec3 position = node.vec3("position");
  const JsonNode target = node.at("target");
  const Vec3 aim = target.as_vec3();
  if (aim == position) target.fail("must differ from position");
  const double cutoff = node.number("cutoff", 30.0, {0, 90, true, false});
  const double falloff_start = node.number("falloff_start", cutoff, {0, 90, false, false});
  if (falloff_start > cutoff) node.at("falloff_start").fail("must be <= cutoff");
  const double exponent = node.number("exponent", 0.0, Range::non_negative());
  // "intensity" (RGB, W/sr on the axis), "luminous_intensity" (cd on the axis) or "luminous_flux"
  // (lm: all the cone emits, its falloff and exponent counted).
  const std::string key = amount_key(node, {"intensity", "luminous_intensity", "luminous_flux"});
  if (key == "intensity")
    return std::make_unique<SpotLight>(position, aim, intensity_of(node), cutoff, falloff_start, exponent,
                                       read_attenuation(node));
  const double amount = node.number(key, 0, Range::non_negative());
  const Attenuation attenuation = photometric_attenuation(node);
  const SpotLight unit(position, aim, Color(1), cutoff, falloff_start, exponent, attenuation);
  const double candela = key == "luminous_flux" ? amount / unit.solid_angle() : amount;
  return std::make_unique<SpotLight>(position, aim,
                                     radiometric(4 * kPi * candela, read_photometric_color(node)), cutoff,
                                     falloff_start, exponent, attenuation);
}

std::unique_ptr<Light> make_area(const JsonNode& node, Color&, const LoadContext&) {
  const Vec3 corner = node.vec3("corner");
  const Vec3 edge_u = node.vec3("edge_u"), edge_v = node.vec3("edge_v");
  if (!(length(cross(edge_u, edge_v)) > 0))
    node.at("edge_v").fail("must not be parallel to edge_u (the light needs an area)");
  const int samples = node.integer("samples", 4, {1, 64, false, false});
  const bool two_sided = node.boolean("two_sided", false);
  // "exitance" (RGB, W/m² per side), "luminance" (cd/m²: a Lambertian exitance of π × it) or
  // "luminous_flux" (lm, from every side it lights).
  const std::string key = amount_key(node, {"exitance", "luminance", "luminous_flux"});
  Color exitance;
  if (key == "exitance") {
    exitance = node.color("exitance", Color(1), Range::non_negative());
  } else {
    const double amount = node.number(key, 0, Range::non_negative());
    const double area = length(cross(edge_u, edge_v));
    const double luminous_exitance =
        key == "luminance" ? kPi * amount : amount / (area * (two_sided ? 2 : 1));
    exitance = radiometric(luminous_exitance, read_photometric_color(node));
  }
  return std::make_unique<AreaLight>(corner, edge_u, edge_v, exitance, samples, two_sided);
}

// The sun as a directional light from a place, a date and a time (Michalsky's
// algorithm, shading/solar_position.h): "latitude" (° north), "longitude" (° east), "date"
// ("YYYY-MM-DD"), "time" (local "HH:MM[:SS]"), "timezone" (hours ahead of UT), "north" (the
// scene's north, default −z; y is up and east is north × up: +x for the default), and its
// "illuminance" on a surface facing it (lx, default 100,000: a clear day's direct normal
// illuminance) of "color" or "temperature" (default 5,800 K). Below the horizon it gives nothing
// (with a warning). Its disc: "angular_diameter" (default 0.53°, the sun's mean; 0: sharp shadows)
// and "samples" (per side, default 4).
std::unique_ptr<Light> make_sun(const JsonNode& node, Color&, const LoadContext& context) {
  const SunPlacement sun = read_sun_placement(node, false);
  const double illuminance = node.number("illuminance", 100000, Range::non_negative());
  Color intensity =
      radiometric(illuminance, read_photometric_color(node, "color", "temperature", blackbody_color(5800)));
  if (sun.position.elevation_degrees <= 0) {
    intensity = Color();
    if (context.warnings)
      context.warnings->push_back(fmt::format(
          "{}: the sun is below the horizon ({:.2f}°) on {} at {}: it gives no light", node.path(),
          sun.position.elevation_degrees, node.at("date").as_string(), node.at("time").as_string()));
  }
  const DirectionalDisc disc = read_directional_disc(node, 0.53);
  return std::make_unique<DirectionalLight>(-sun.toward_sun, intensity, "sun", disc.radians, disc.samples);
}

// A measured luminaire: "file" (.ies or .ldt), "position", "target" (where its nadir points),
// "c0" (the direction of its C0 plane, default: the world axis least along the nadir), and
// "multiplier" (every candela × it) or "luminous_flux" (lm: the table scaled to emit that),
// with "color" or "temperature"; "size" makes it an area luminaire (scene/luminaire_light.h).
std::unique_ptr<Light> make_luminaire(const JsonNode& node, Color&, const LoadContext& context) {
  const JsonNode file = node.at("file");
  const std::string name = file.as_string();
  const std::string path = context.resolve(name).string();
  const std::string extension = std::filesystem::path(name).extension().string();
  std::shared_ptr<const Photometry> photometry;
  const bool ies = extension == ".ies" || extension == ".IES";
  if (!ies && extension != ".ldt" && extension != ".LDT")
    file.fail("\"" + name + "\": expected an IES (.ies) or EULUMDAT (.ldt) file");
  try {
    photometry = std::make_shared<Photometry>(ies ? read_ies(path) : read_eulumdat(path));
  } catch (const InputError& e) {
    file.fail(e.what());
  }
  if (photometry->type != PhotometricType::c)
    file.fail("\"" + name + "\" has type A or B photometry (floodlights, automotive): only type C is placed");
  const Vec3 position = node.vec3("position");
  const JsonNode target = node.at("target");
  const Vec3 nadir = target.as_vec3() - position;
  if (!(length(nadir) > 0)) target.fail("must differ from position");
  Vec3 fallback{1, 0, 0};
  const Vec3 unit_nadir = normalize(nadir);
  for (const Vec3 axis : {Vec3{1, 0, 0}, Vec3{0, 0, 1}, Vec3{0, 1, 0}})
    if (std::fabs(dot(axis, unit_nadir)) < std::fabs(dot(fallback, unit_nadir))) fallback = axis;
  const Vec3 c0 = node.vec3("c0", fallback);
  if (!(length(c0 - unit_nadir * dot(c0, unit_nadir)) > 1e-9 * length(c0)))
    node.at("c0").fail("must not be parallel to the nadir (position to target)");
  double scale = 1;
  const std::string amount = amount_key(node, {"multiplier", "luminous_flux"});
  if (amount == "multiplier") {
    scale = node.number("multiplier", 1, Range::non_negative());
  } else {
    const double flux = photometry->flux();
    if (!(flux > 0)) file.fail("\"" + name + "\" emits nothing: it cannot be scaled to a luminous_flux");
    scale = node.number("luminous_flux", 0, Range::non_negative()) / flux;
  }
  // The file's peak times the scale is held to the limit a point light's intensity has
  // (a tiny table scaled to a large flux overflowed to an infinite intensity).
  const double peak = photometry->candela.empty()
                          ? 0.0
                          : *std::max_element(photometry->candela.begin(), photometry->candela.end());
  if (!(peak * scale <= kMaxSceneMagnitude))
    (node.has(amount) ? node.at(amount) : file)
        .fail(fmt::format(
            "\"{}\" peaks at {:g} cd, × {:g} is {:g} cd: above {:g}, the largest intensity supported", name,
            peak, scale, peak * scale, kMaxSceneMagnitude));
  // An area luminaire: "size" [width along C0, depth along C90] in metres, "samples" per side.
  double width = 0, depth = 0;
  int samples = 1;
  if (node.has("size")) {
    const JsonNode size = node.at("size");
    if (size.size() != 2) size.fail("expected [width, depth] in metres");
    width = size.element(0).as_number(Range::non_negative());
    depth = size.element(1).as_number(Range::non_negative());
    if (!(width > 0 || depth > 0)) size.fail("a width or a depth must be above 0");
    samples = node.integer("samples", 4, {1, 64, false, false});
  }
  return std::make_unique<LuminaireLight>(photometry, position, nadir, c0, scale,
                                          read_photometric_color(node), width, depth, samples);
}

const std::array kLightEntries = {
    LightEntry{"ambient", "uniform ambient light Ia (000 §2.4)", R"({"type": "ambient", "intensity": 0.3})",
               make_ambient},
    LightEntry{
        "point", "point source with attenuation",
        R"({"type": "point", "position": [0, 5, 0], "intensity": 1, "attenuation": {"mode": "linear", "d0": 1}})",
        make_point},
    LightEntry{"directional", "source at infinity; direction is the way the light travels",
               R"({"type": "directional", "direction": [0, -1, 0], "intensity": [1, 1, 0.9]})",
               make_directional},
    LightEntry{
        "spot", "cone of light: cutoff and falloff_start angles in degrees, exponent",
        R"({"type": "spot", "position": [0, 5, 0], "target": [0, 0, 0], "intensity": 2, "cutoff": 30, "falloff_start": 20, "exponent": 1, "attenuation": "none"})",
        make_spot},
    LightEntry{
        "area",
        "Lambertian parallelogram corner + s·edge_u + t·edge_v emitting exitance from edge_u × edge_v; "
        "samples² shadow rays",
        R"({"type": "area", "corner": [-0.5, 4, -0.5], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1], "exitance": 10, "samples": 4})",
        make_area},
    LightEntry{
        "sun",
        "the sun from latitude, longitude, date, local time and timezone (a directional light of "
        "illuminance lx)",
        R"({"type": "sun", "latitude": 48.85, "longitude": 2.35, "date": "2026-06-21", "time": "14:00", "timezone": 2, "illuminance": 90000})",
        make_sun},
    LightEntry{
        "luminaire",
        "a measured luminaire: an IES LM-63 or EULUMDAT file's intensities, its nadir toward target, C0 "
        "along c0",
        R"({"type": "luminaire", "file": "luminaires/downlight.ies", "position": [0, 3, 0], "target": [0, 0, 0], "c0": [1, 0, 0]})",
        make_luminaire},
};

}  // namespace

std::span<const LightEntry> light_entries() {
  return kLightEntries;
}

const LightEntry* find_light(std::string_view name) {
  return find_entry<LightEntry>(kLightEntries, name);
}

}  // namespace candela
