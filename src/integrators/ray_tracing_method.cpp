#include "integrators/ray_tracing_method.h"

#include <fmt/format.h>
#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <atomic>
#include <cmath>

#include "camera/antialiasing.h"

#include "util/cancellation.h"
#include "util/progress.h"

namespace candela {

void RayTracingMethod::render(const Scene& scene, const RenderRequest& request, Film& film,
                              RunStatistics& statistics) const {
  const PixelRect region = request.region;
  const int tile = scene.render.tile_size;
  const int64_t tile_count = sampling_tile_count(region.width(), region.height(), tile);
  ProgressReporter progress("render", static_cast<uint64_t>(tile_count), "tiles", request.quiet);
  // Counts are per thread and summed at the end; the random stream is reseeded per ray from the
  // pixel that holds the sample point, so values never depend on the thread.
  tbb::enumerable_thread_specific<TraceContext> contexts;
  const RadianceFunction radiance = [&](double x, double y) {
    TraceContext& context = contexts.local();
    const auto px = static_cast<uint32_t>(std::clamp(static_cast<int>(std::floor(x)), 0, scene.camera->width() - 1));
    const auto py = static_cast<uint32_t>(std::clamp(static_cast<int>(std::floor(y)), 0, scene.camera->height() - 1));
    context.rng = pixel_rng(scene.render.seed, px, py);
    ++context.counts.primary;
    return trace_primary(scene, scene.camera->generate_ray(x, y), context);
  };
  const SamplingRegion sampling{region.x0, region.y0, scene.camera->width(), scene.camera->height()};
  std::atomic<int64_t> tiles_done{0};
  SamplingResult result = sample_image(scene.antialiasing, scene.render.seed, sampling, tile, radiance, film, [&] {
    tiles_done.fetch_add(1, std::memory_order_relaxed);
    progress.advance();
  });
  progress.finish();
  if (cancel_requested()) {  // Ctrl-C: the tiles not rendered are black
    statistics.extra["interrupted"] = true;
    statistics.extra["completed"] = fmt::format("{} of {} tiles", tiles_done.load(), tile_count);
  }
  RayCounts total;
  for (const TraceContext& context : contexts) total += context.counts;
  statistics.rays += total;
  statistics.pixels += static_cast<uint64_t>(region.width()) * region.height();
  statistics.primary_per_pixel = std::move(result.traced_per_pixel);
  statistics.samples_per_pixel = std::move(result.samples_per_pixel);
  statistics.extra["antialiasing"] = antialiasing_mode_name(scene.antialiasing.mode);
}

RayTree RayTracingMethod::pixel_ray_tree(const Scene& scene, int x, int y, Color& radiance) const {
  RayTree tree;
  TraceContext context;
  context.tree = &tree;
  context.rng = pixel_rng(scene.render.seed, static_cast<uint32_t>(x), static_cast<uint32_t>(y));
  radiance = trace_primary(scene, scene.camera->generate_ray(x + 0.5, y + 0.5), context);
  return tree;
}

}  // namespace candela
