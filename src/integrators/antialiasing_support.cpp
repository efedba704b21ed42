#include "integrators/antialiasing_support.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "camera/accumulation_buffer.h"
#include "camera/sample_grid.h"
#include "integrators/method.h"
#include "scene/scene.h"
#include "util/error.h"

namespace candela {

namespace {

// The most grid samples a rasterized view keeps (24 bytes each: 3 GiB).
constexpr int64_t kMaxGridSamples = int64_t(1) << 27;

// The grid of a view over the samples it may hold.
std::optional<AntialiasingRefusal> grid_size_refusal(const AntialiasingSettings& settings,
                                                     const SampleGrid& grid, const Camera& camera,
                                                     const std::string& view) {
  const int64_t samples =
      (grid.end(camera.width()) - grid.first(0)) * (grid.end(camera.height()) - grid.first(0));
  if (samples <= kMaxGridSamples) return std::nullopt;
  const bool uniform = settings.mode == AntialiasingMode::uniform;
  return AntialiasingRefusal{
      uniform ? "aa.n" : "aa.max_level", std::to_string(uniform ? settings.n : settings.max_level),
      fmt::format("the grid of {} × {} samples it would rasterize{} is over the {} samples it may hold; "
                  "lower it",
                  grid.end(camera.width()), grid.end(camera.height()), view, kMaxGridSamples)};
}

}  // namespace

std::optional<AntialiasingRefusal> sample_grid_refusal(const AntialiasingSettings& settings,
                                                       const Scene& scene) {
  // Jittered samples are drawn in passes of the image's own size (camera/accumulation_buffer.h).
  if (drawn_in_passes(settings)) return std::nullopt;
  const SampleGrid grid = *sample_grid(settings);
  if (auto refusal = grid_size_refusal(settings, grid, *scene.camera, "")) return refusal;
  for (const NamedCamera& named : scene.cameras)
    if (auto refusal = grid_size_refusal(settings, grid, *named.camera, " for camera \"" + named.name + "\""))
      return refusal;
  return std::nullopt;
}

std::string describe_refusal(std::string_view method, const AntialiasingRefusal& refusal) {
  return fmt::format("{} cannot do {} {} ({})", method, refusal.key, refusal.value, refusal.reason);
}

bool set_samples_per_pixel(AntialiasingSettings& settings, std::string_view method, int samples) {
  const int n = static_cast<int>(std::lround(std::sqrt(double(std::max(samples, 1)))));
  if (samples < 1 || n * n != samples) {
    const int below = std::max(1, static_cast<int>(std::floor(std::sqrt(double(std::max(samples, 1))))));
    throw std::invalid_argument(fmt::format("{}: {} takes n×n samples per pixel (aa.n); use {} or {}",
                                            samples, method, below * below, (below + 1) * (below + 1)));
  }
  if (n > 64)
    throw std::invalid_argument(
        fmt::format("{}: {} takes at most 64×64 = 4096 samples per pixel (aa.n)", samples, method));
  settings.n = n;
  if (settings.mode == AntialiasingMode::uniform || settings.mode == AntialiasingMode::jittered) return false;
  settings.mode = AntialiasingMode::uniform;
  return true;
}

bool set_samples_per_pixel(Scene& scene, std::string_view method, int samples) {
  return set_samples_per_pixel(scene.antialiasing, method, samples);
}

void choose_jittered_where_possible(AntialiasingSettings& settings, const Scene& scene,
                                    const Method& method) {
  settings.mode = AntialiasingMode::jittered;
  if (method.rasterizes() || method.antialiasing_refusal(scene, settings))
    settings.mode = AntialiasingMode::uniform;
}

void choose_jittered_where_possible(Scene& scene, const Method& method) {
  choose_jittered_where_possible(scene.antialiasing, scene, method);
}

void refuse_unsupported_antialiasing(const Method& method, const Scene& scene,
                                     const AntialiasingSettings& antialiasing) {
  if (const auto refusal = method.antialiasing_refusal(scene, antialiasing))
    throw InputError({scene.source, 0, 0, refusal->key}, describe_refusal(method.name(), *refusal));
}

void refuse_unsupported_antialiasing(const Method& method, const Scene& scene) {
  refuse_unsupported_antialiasing(method, scene, scene.antialiasing);
}

}  // namespace candela
