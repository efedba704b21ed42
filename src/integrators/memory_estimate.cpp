#include "integrators/memory_estimate.h"

#include <fmt/format.h>

#include <algorithm>
#include <utility>

#include "util/memory.h"

namespace candela {

namespace {

std::string mebibytes(uint64_t bytes) {
  return fmt::format("{:.1f} MiB", static_cast<double>(bytes) / 1048576.0);
}

}  // namespace

uint64_t film_bytes(const PixelRect& region, int copies) {
  const uint64_t pixels = static_cast<uint64_t>(std::max(region.width(), 0)) *
                          static_cast<uint64_t>(std::max(region.height(), 0));
  return pixels * sizeof(Color) * static_cast<uint64_t>(copies);
}

MemoryPart image_memory_part(std::string what, uint64_t bytes) {
  return {std::move(what), bytes, "camera.width",
          "lower camera.width and camera.height, or render a part (--crop)"};
}

// The image and its exposed copy for writing.
std::vector<MemoryPart> Method::memory_needed(const Scene&, const RenderRequest& request) const {
  return {image_memory_part("the image", film_bytes(request.region, 2))};
}

void refuse_beyond_memory_limit(const Method& method, const Scene& scene, const RenderRequest& request) {
  std::vector<MemoryPart> parts = method.memory_needed(scene, request);
  uint64_t total = 0;
  for (const MemoryPart& part : parts) total += part.bytes;
  const uint64_t limit = memory_limit_bytes(scene.render.memory_limit_mib);
  if (total <= limit) return;
  std::stable_sort(parts.begin(), parts.end(),
                   [](const MemoryPart& a, const MemoryPart& b) { return a.bytes > b.bytes; });
  std::string listed;
  for (const MemoryPart& part : parts)
    listed += fmt::format("{}{} {}", listed.empty() ? "" : ", ", part.what, mebibytes(part.bytes));
  const MemoryPart& largest = parts.front();
  const bool scene_sets_limit = !scene.render.memory_limit_location.file.empty();
  const std::string allowed =
      scene_sets_limit ? fmt::format("the {} render.memory_limit_mib allows", mebibytes(limit))
                       : fmt::format("the {} allowed (half the machine's memory; render.memory_limit_mib)",
                                     mebibytes(limit));
  const SourceLocation where = scene_sets_limit ? scene.render.memory_limit_location
                                                : SourceLocation{scene.source, 0, 0, largest.setting};
  throw InputError(
      where, fmt::format("{} would hold {} ({}), more than {}; {}: {} (or raise "
                         "render.memory_limit_mib)",
                         method.name(), mebibytes(total), listed, allowed, largest.setting, largest.remedy));
}

}  // namespace candela
