#include "scene/environment_registry.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>
#include <tuple>

#include "math/constants.h"
#include "math/direction.h"
#include "scene/photometric_settings.h"
#include "scene/solar_settings.h"
#include "shading/cie_sky.h"
#include "shading/photometric_units.h"
#include "util/registry.h"

namespace candela {

ColorEncoding read_color_encoding(const JsonNode& owner) {
  return owner.enumeration("encoding", ColorEncoding::automatic, kColorEncodingNames);
}

WrapMode read_wrap_mode(const JsonNode& owner) {
  return owner.enumeration("wrap", WrapMode::repeat, kWrapModeNames);
}

namespace {

// What identifies one decoded image: the same file, unchanged since, decoded the same way.
struct ImageKey {
  std::string canonical_path;
  ColorEncoding encoding;
  std::filesystem::file_time_type::rep modified;
  std::uintmax_t size;
  bool operator<(const ImageKey& other) const {
    return std::tie(canonical_path, encoding, modified, size) <
           std::tie(other.canonical_path, other.encoding, other.modified, other.size);
  }
};

// Images loaded by any scene and still referenced. Weak references: the cache keeps nothing
// alive, it only lets a second use of a file (six faces from one picture, one texture on many
// materials) share the first.
class ImageCache {
 public:
  std::shared_ptr<const TextureImage> find(const ImageKey& key) {
    const std::lock_guard lock(mutex_);
    const auto found = images_.find(key);
    return found == images_.end() ? nullptr : found->second.lock();
  }
  void insert(const ImageKey& key, const std::shared_ptr<const TextureImage>& image) {
    const std::lock_guard lock(mutex_);
    std::erase_if(images_, [](const auto& entry) { return entry.second.expired(); });
    images_[key] = image;
  }

 private:
  std::mutex mutex_;
  std::map<ImageKey, std::weak_ptr<const TextureImage>> images_;
};

ImageCache& image_cache() {
  static ImageCache cache;
  return cache;
}

// False when the file cannot be inspected (it is then loaded uncached, and the load reports why).
bool key_of(const std::filesystem::path& path, ColorEncoding encoding, ImageKey& key) {
  std::error_code error;
  const std::filesystem::path canonical = std::filesystem::canonical(path, error);
  if (error) return false;
  const auto modified = std::filesystem::last_write_time(canonical, error);
  if (error) return false;
  const std::uintmax_t size = std::filesystem::file_size(canonical, error);
  if (error) return false;
  key = {canonical.string(), encoding, modified.time_since_epoch().count(), size};
  return true;
}

}  // namespace

std::shared_ptr<const TextureImage> load_texture_image(const JsonNode& file_node, const LoadContext& context,
                                                       ColorEncoding encoding) {
  const std::string file = file_node.as_string();
  if (file.empty()) file_node.fail("expected an image file name, found an empty string");
  const std::filesystem::path path = context.resolve(file);
  ImageKey key;
  const bool cacheable = key_of(path, encoding, key);
  if (cacheable)
    if (auto image = image_cache().find(key)) return image;
  std::shared_ptr<const TextureImage> image;
  try {
    image = std::make_shared<const TextureImage>(TextureImage::load(path, encoding));
  } catch (const std::runtime_error& e) {
    file_node.fail(e.what());  // "cannot load image PATH: reason", after file:line:column: json.path
  }
  if (cacheable) image_cache().insert(key, image);
  return image;
}

namespace {

Color read_multiplier(const JsonNode& node) {
  return node.color("multiplier", Color(1), Range::non_negative());
}

std::unique_ptr<Environment> make_constant(const JsonNode& node, const LoadContext&) {
  return std::make_unique<ConstantEnvironment>(node.at("color").as_color(Range::non_negative()));
}

std::unique_ptr<Environment> make_cube(const JsonNode& node, const LoadContext& context) {
  const ColorEncoding encoding = read_color_encoding(node);
  const Color multiplier = read_multiplier(node);
  const JsonNode faces_node = node.at("faces");
  faces_node.expect_object();
  // The order CubeMapEnvironment takes: +x, −x, +y, −y, +z, −z.
  constexpr std::array<std::string_view, 6> kFaceKeys = {"+x", "-x", "+y", "-y", "+z", "-z"};
  std::array<std::shared_ptr<const TextureImage>, 6> faces;
  for (std::size_t face = 0; face < faces.size(); ++face) {
    const JsonNode file_node = faces_node.at(kFaceKeys[face]);
    faces[face] = load_texture_image(file_node, context, encoding);
    // Checked here rather than by CubeMapEnvironment so that the message points at the file.
    const TextureImage& image = *faces[face];
    const std::string dimensions = std::to_string(image.width()) + "×" + std::to_string(image.height());
    if (image.width() != image.height())
      file_node.fail("the image is " + dimensions + "; cube-map faces must be square");
    if (face > 0 && image.width() != faces[0]->width())
      file_node.fail("the image is " + dimensions + " but the +x face is " +
                     std::to_string(faces[0]->width()) + "×" + std::to_string(faces[0]->height()) +
                     "; all six faces must be the same size");
  }
  faces_node.finish();
  const CubeLayout layout = node.choice("layout", "inside", {"inside", "opengl"}) == "inside"
                                ? CubeLayout::inside
                                : CubeLayout::opengl;
  return std::make_unique<CubeMapEnvironment>(std::move(faces), multiplier, layout);
}

std::unique_ptr<Environment> make_equirectangular(const JsonNode& node, const LoadContext& context) {
  const ColorEncoding encoding = read_color_encoding(node);
  const Color multiplier = read_multiplier(node);
  auto image = load_texture_image(node.at("file"), context, encoding);
  const Vec3 up = node.vec3("up", {0, 1, 0});
  const Vec3 forward = node.vec3("forward", {0, 0, -1});
  if (!direction_of(up)) node.at("up").fail("must be non-zero");
  if (!(length(forward) > 0)) node.at("forward").fail("must be non-zero");
  try {
    return std::make_unique<EquirectangularEnvironment>(std::move(image), up, forward, multiplier);
  } catch (const std::invalid_argument& e) {
    // Zero vectors were refused above: what is left is forward parallel to up.
    (node.has("forward") ? node.at("forward") : node.at("up")).fail(e.what());
  }
}

// The CIE standard general sky (shading/cie_sky.h) of "sky_type" (1–15, default
// 1, the overcast sky), its sun placed as the sun light places it (scene/solar_settings.h, or
// "sun_elevation" and "sun_azimuth"), scaled so that an unobstructed horizontal surface receives
// "diffuse_illuminance" lux from it (default 10,000), of "color" or "temperature" (default white);
// nothing from below the horizon (no ground). Baked into a latitude-longitude panorama of
// "resolution" × resolution/2 texels (default 512), its forward the scene's north: the
// equirectangular environment then lights, samples and shows it for every method. The sun itself is
// not in it (add a sun light).
std::unique_ptr<Environment> make_cie_sky(const JsonNode& node, const LoadContext&) {
  const int type = node.integer("sky_type", 1, {1, 15, false, false});
  const SunPlacement sun = read_sun_placement(node, true);
  const double diffuse = node.number("diffuse_illuminance", 10000, Range::non_negative());
  const int width = node.integer("resolution", 512, {16, 8192, false, false}), height = width / 2;
  const double sun_zenith = std::acos(std::clamp(sun.toward_sun.y, -1.0, 1.0));
  std::vector<double> relative(std::size_t(width) * height, 0.0);
  double horizontal = 0;              // ∫ relative cos Z dω over the texels' solid angles
  for (int j = 0; j < height; ++j) {  // from the top row (the zenith) down
    const double zenith = kPi * (j + 0.5) / height;
    if (zenith >= kPi / 2) continue;
    const double solid_angle =
        (2 * kPi / width) * (std::cos(kPi * j / height) - std::cos(kPi * (j + 1) / height));
    for (int i = 0; i < width; ++i) {
      // u = 0.5 + azimuth / 2π from north clockwise (the panorama's forward is north, right east).
      const double azimuth = 2 * kPi * ((i + 0.5) / width - 0.5);
      const Vec3 direction = sun.north * (std::sin(zenith) * std::cos(azimuth)) +
                             sun.east * (std::sin(zenith) * std::sin(azimuth)) + Vec3{0, std::cos(zenith), 0};
      const double to_sun = std::acos(std::clamp(dot(direction, sun.toward_sun), -1.0, 1.0));
      const double value = cie_sky_relative_luminance(type, zenith, to_sun, sun_zenith);
      relative[std::size_t(j) * width + i] = value;
      horizontal += value * std::cos(zenith) * solid_angle;
    }
  }
  const Color colour = read_photometric_color(node);
  // An environment's values are in the units of an emitter's exitance (a constant one of value C
  // gives irradiance C): π × the radiance.
  const Color scale = radiometric(diffuse, colour) * (kPi / horizontal);
  std::vector<float> rgb(std::size_t(width) * height * 3);
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i)
      for (int c = 0; c < 3; ++c)  // TextureImage rows start at the bottom
        rgb[(std::size_t(height - 1 - j) * width + i) * 3 + c] =
            static_cast<float>(relative[std::size_t(j) * width + i] * scale[c]);
  auto image = std::make_shared<const TextureImage>(width, height, std::move(rgb));
  return std::make_unique<EquirectangularEnvironment>(std::move(image), Vec3{0, 1, 0}, sun.north, Color(1),
                                                      "cie_sky");
}

const std::array kEnvironmentEntries = {
    EnvironmentEntry{"constant", "the same radiance from every direction",
                     R"({"type": "constant", "color": [0.2, 0.3, 0.5]})", make_constant},
    EnvironmentEntry{
        "cube",
        "cube map of six square images around the scene (000 §4.1.3); layout \"inside\" (what a 90° "
        "camera at the centre sees) or \"opengl\" (sky-box sets); bilinear within a face",
        R"({"type": "cube", "faces": {"+x": "sky/px.png", "-x": "sky/nx.png", "+y": "sky/py.png", "-y": "sky/ny.png", "+z": "sky/pz.png", "-z": "sky/nz.png"}, "multiplier": 1, "encoding": "auto", "layout": "inside"})",
        make_cube},
    EnvironmentEntry{
        "equirectangular",
        "latitude/longitude panorama: image centre along forward, top row up; "
        "bilinear, repeating in longitude",
        R"({"type": "equirectangular", "file": "sky.exr", "up": [0, 1, 0], "forward": [0, 0, -1], "multiplier": [1, 1, 1], "encoding": "linear"})",
        make_equirectangular},
    EnvironmentEntry{
        "cie_sky",
        "the CIE standard general sky (ISO 15469) of sky_type 1-15, its sun by place and time or "
        "sun_elevation/sun_azimuth, diffuse_illuminance lx on the horizontal",
        R"({"type": "cie_sky", "sky_type": 12, "sun_elevation": 40, "sun_azimuth": 200, "diffuse_illuminance": 15000})",
        make_cie_sky},
};

}  // namespace

std::span<const EnvironmentEntry> environment_entries() {
  return kEnvironmentEntries;
}

const EnvironmentEntry* find_environment(std::string_view name) {
  return find_entry<EnvironmentEntry>(kEnvironmentEntries, name);
}

std::unique_ptr<Environment> read_environment(const JsonNode& node, const LoadContext& context) {
  node.expect_object();
  const JsonNode type_node = node.at("type");
  const std::string type = type_node.as_string();
  const EnvironmentEntry* entry = find_environment(type);
  if (!entry)
    type_node.fail("unknown environment type \"" + type +
                   "\" (expected one of: " + entry_names<EnvironmentEntry>(kEnvironmentEntries) + ")");
  auto environment = entry->create(node, context);
  node.finish();
  return environment;
}

}  // namespace candela
