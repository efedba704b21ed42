#include "integrators/ray_tracing_method.h"

#include <tbb/parallel_for.h>

#include <mutex>

#include "util/progress.h"

namespace candela {

void RayTracingMethod::render(const Scene& scene, const RenderRequest& request, Film& film,
                              RunStatistics& statistics) const {
  const PixelRect region = request.region;
  const int tile = scene.render.tile_size;
  const int tiles_x = (region.width() + tile - 1) / tile;
  const int tiles_y = (region.height() + tile - 1) / tile;
  const int64_t tile_count = int64_t(tiles_x) * tiles_y;
  ProgressReporter progress("render", static_cast<uint64_t>(tile_count), "tiles", request.quiet);
  std::mutex merge;
  RayCounts total;
  tbb::parallel_for(int64_t(0), tile_count, [&](int64_t tile_index) {
    const int x_begin = region.x0 + static_cast<int>(tile_index % tiles_x) * tile;
    const int y_begin = region.y0 + static_cast<int>(tile_index / tiles_x) * tile;
    const int x_end = std::min(x_begin + tile, region.x1);
    const int y_end = std::min(y_begin + tile, region.y1);
    TraceContext context;
    for (int y = y_begin; y < y_end; ++y) {
      for (int x = x_begin; x < x_end; ++x) {
        context.rng = pixel_rng(scene.render.seed, static_cast<uint32_t>(x), static_cast<uint32_t>(y));
        const Ray ray = scene.camera->generate_ray(x + 0.5, y + 0.5);
        ++context.counts.primary;
        film.at(x - region.x0, y - region.y0) = trace_primary(scene, ray, context);
      }
    }
    {
      std::lock_guard lock(merge);
      total += context.counts;
    }
    progress.advance();
  });
  progress.finish();
  statistics.rays += total;
  statistics.pixels += static_cast<uint64_t>(region.width()) * region.height();
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
