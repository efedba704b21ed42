#include "scene/camera_registry.h"

#include <fmt/format.h>

#include <array>
#include <cmath>

#include "camera/orthographic_camera.h"
#include "camera/perspective_camera.h"
#include "math/constants.h"
#include "util/registry.h"

namespace candela {

namespace {

template <typename Make>
std::unique_ptr<Camera> checked(const JsonNode& node, Make make) {
  try {
    return make();
  } catch (const std::invalid_argument& e) {
    node.fail(e.what());
  }
}

std::unique_ptr<Camera> make_perspective(const JsonNode& node, int width, int height) {
  const Vec3 eye = node.vec3("eye", {0, 0, 5});
  const Vec3 target = node.vec3("target", {0, 0, 0});
  const Vec3 up = node.vec3("up", {0, 1, 0});
  // 2θ, the horizontal field of view (000 §5.2); or the vertical one (a glTF camera's yfov), the
  // horizontal then following from the image's aspect, so that a resized image keeps its height's view.
  if (node.has("fov") && node.has("vertical_fov"))
    node.at("vertical_fov").fail("give one of fov (horizontal) and vertical_fov, not both");
  double fov = node.number("fov", 60.0, {0, 180, true, true});
  if (node.has("vertical_fov")) {
    const double vertical = node.number("vertical_fov", {0, 180, true, true});
    fov = 2 * std::atan(std::tan(vertical * kPi / 360) * width / height) * 180 / kPi;
  }
  const bool mirrored = node.boolean("mirrored", false);
  return checked(node, [&] {
    return std::make_unique<PerspectiveCamera>(eye, target, up, fov, width, height, mirrored);
  });
}

std::unique_ptr<Camera> make_orthographic(const JsonNode& node, int width, int height) {
  const Vec3 eye = node.vec3("eye", {0, 0, 5});
  const Vec3 target = node.vec3("target", {0, 0, 0});
  const Vec3 up = node.vec3("up", {0, 1, 0});
  double left, right, bottom, top;
  if (const auto window = node.get("window")) {
    if (window->size() != 4) window->fail("expected [left, right, bottom, top]");
    left = window->element(0).as_number();
    right = window->element(1).as_number();
    bottom = window->element(2).as_number();
    top = window->element(3).as_number();
    if (!(right > left) || !(top > bottom)) window->fail("needs right > left and top > bottom");
  } else {
    const double window_height = node.number("window_height", 2.0, Range::positive());
    top = window_height / 2;
    bottom = -top;
    right = top * width / height;
    left = -right;
  }
  const bool mirrored = node.boolean("mirrored", false);
  return checked(node, [&] {
    return std::make_unique<OrthographicCamera>(eye, target, up, left, right, bottom, top, width, height,
                                                mirrored);
  });
}

const std::array kCameraEntries = {
    CameraEntry{
        "perspective",
        "eye, target, up, horizontal field of view fov (or vertical_fov) in degrees (000 §5.2)",
        R"({"type": "perspective", "eye": [0, 1, 5], "target": [0, 1, 0], "up": [0, 1, 0], "fov": 60, "width": 320, "height": 240})",
        make_perspective},
    CameraEntry{
        "orthographic",
        "eye, target, up and the image window [left, right, bottom, top] (or window_height) (001)",
        R"({"type": "orthographic", "eye": [0, 1, 5], "target": [0, 1, 0], "window": [-2, 2, -1.5, 1.5], "width": 320, "height": 240})",
        make_orthographic},
};

}  // namespace

std::span<const CameraEntry> camera_entries() {
  return kCameraEntries;
}

const CameraEntry* find_camera(std::string_view name) {
  return find_entry<CameraEntry>(kCameraEntries, name);
}

std::unique_ptr<Camera> read_camera(const JsonNode& node, int default_width, int default_height) {
  node.expect_object();
  const int width = node.integer("width", default_width, {1, 65536, false, false});
  const int height = node.integer("height", default_height, {1, 65536, false, false});
  // The film holds three doubles a pixel: refuse what would not fit (SPEC §15).
  constexpr double kMaxPixels = 1 << 28;  // 6 GiB of film
  if (double(width) * height > kMaxPixels)
    node.at(node.has("width") ? "width" : "height")
        .fail(fmt::format(
            "{}x{} = {} pixels needs {:.1f} GiB of film; the limit is {} pixels: lower camera.width or "
            "camera.height",
            width, height, double(width) * height, double(width) * height * 24 / (1 << 30), kMaxPixels));
  const std::string type = node.string("type", "perspective");
  const CameraEntry* entry = find_camera(type);
  if (!entry)
    node.at("type").fail("unknown camera \"" + type +
                         "\" (expected one of: " + entry_names<CameraEntry>(kCameraEntries) + ")");
  auto camera = entry->create(node, width, height);
  node.finish();
  return camera;
}

}  // namespace candela
