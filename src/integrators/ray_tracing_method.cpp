#include "integrators/ray_tracing_method.h"

#include <fmt/format.h>
#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <atomic>
#include <cmath>

#include "camera/antialiasing.h"
#include "distributed/cluster.h"
#include "integrators/distributed_tiles.h"
#include "util/cancellation.h"
#include "util/progress.h"

namespace candela {

RenderResult RayTracingMethod::render(const Scene& scene, const RenderRequest& request) const {
  RenderResult output(request.region);
  Film& film = output.film;
  RunStatistics& statistics = output.statistics;
  const PixelRect region = request.region;
  const int tile = scene.render.tile_size;
  // The render's seed and aa settings, which may not be the scene's.
  const uint64_t seed = request.seed_for(scene);
  const AntialiasingSettings& antialiasing = request.antialiasing_for(scene);
  Cluster* cluster = several_ranks(request);
  // Across ranks the tiles are the larger ones handed out; rank 0 shows their progress.
  const SamplingRegion sampling{region.x0, region.y0, scene.camera->width(), scene.camera->height()};
  const int64_t tiles_total =
      cluster ? tile_count(region.width(), region.height(), kDistributedTileSize)
              : sampling_tile_count(antialiasing, sampling, region.width(), region.height(), tile);
  ProgressReporter progress("render", static_cast<uint64_t>(tiles_total), "tiles",
                            request.quiet || (cluster && !cluster->root()));
  // Counts are per thread and summed at the end; the random stream is reseeded per ray from the
  // pixel that holds the sample point, so values never depend on the thread.
  tbb::enumerable_thread_specific<TraceContext> contexts([seed] {
    TraceContext context;
    context.seed = seed;
    return context;
  });
  const RadianceFunction radiance = [&](double x, double y) {
    TraceContext& context = contexts.local();
    const auto px =
        static_cast<uint32_t>(std::clamp(static_cast<int>(std::floor(x)), 0, scene.camera->width() - 1));
    const auto py =
        static_cast<uint32_t>(std::clamp(static_cast<int>(std::floor(y)), 0, scene.camera->height() - 1));
    context.rng = pixel_rng(seed, px, py);
    ++context.counts.primary;
    return trace_primary(scene, scene.camera->generate_ray(x, y), context);
  };
  SamplingResult result;
  std::atomic<int64_t> tiles_done{0};
  bool interrupted = false;
  if (cluster) {
    // Across ranks: larger tiles, each sampled like a region of its own — every
    // sample point's value is a function of the point, so the tiles join into the same image —
    // with the per-pixel counts (--aa-map, --stats) sent along with the pixels.
    const std::size_t pixel_count = std::size_t(region.width()) * region.height();
    if (cluster->root()) {
      result.traced_per_pixel.assign(pixel_count, 0);
      result.samples_per_pixel.assign(pixel_count, 0);
    }
    const TiledRender run = render_tiles_across_ranks(
        *cluster, region,
        [&](const PixelRect& piece) {
          RenderedTile rendered{Film(piece.width(), piece.height()), {}};
          const SamplingRegion at_piece{piece.x0, piece.y0, scene.camera->width(), scene.camera->height()};
          SamplingResult sampled = sample_image(antialiasing, seed, at_piece, tile, radiance, rendered.film);
          rendered.counts = std::move(sampled.traced_per_pixel);
          rendered.counts.insert(rendered.counts.end(), sampled.samples_per_pixel.begin(),
                                 sampled.samples_per_pixel.end());
          return rendered;
        },
        film,
        [&](const PixelRect& piece, const std::vector<uint32_t>& counts) {
          const std::size_t size = std::size_t(piece.width()) * piece.height();
          for (int y = piece.y0; y < piece.y1; ++y)
            for (int x = piece.x0; x < piece.x1; ++x) {
              const std::size_t from = std::size_t(y - piece.y0) * piece.width() + (x - piece.x0);
              const std::size_t to = std::size_t(y - region.y0) * region.width() + (x - region.x0);
              result.traced_per_pixel[to] = counts[from];
              result.samples_per_pixel[to] = counts[size + from];
            }
        },
        &progress);
    tiles_done = static_cast<int64_t>(run.tiles_done);
    interrupted = run.interrupted;
    statistics.extra["distributed"] = distributed_facts(*cluster, run.tiles_by_rank, "tiles");
  } else {
    result = sample_image(antialiasing, seed, sampling, tile, radiance, film, [&] {
      tiles_done.fetch_add(1, std::memory_order_relaxed);
      progress.advance();
    });
  }
  progress.finish();
  if (interrupted || cancel_requested()) {  // Ctrl-C: the tiles not rendered are black
    statistics.extra["interrupted"] = true;
    statistics.extra["completed"] = fmt::format("{} of {} tiles", tiles_done.load(), tiles_total);
  }
  RayCounts total;
  for (const TraceContext& context : contexts) total += context.counts;
  if (cluster) sum_across_ranks(*cluster, total);
  statistics.rays += total;
  statistics.pixels += static_cast<uint64_t>(region.width()) * region.height();
  statistics.primary_per_pixel = std::move(result.traced_per_pixel);
  statistics.samples_per_pixel = std::move(result.samples_per_pixel);
  statistics.extra["antialiasing"] = std::string(kAntialiasingModeNames.name(antialiasing.mode));
  return output;
}

RayTree RayTracingMethod::pixel_ray_tree(const Scene& scene, int x, int y, Color& radiance) const {
  RayTree tree;
  TraceContext context;
  context.tree = &tree;
  context.seed = scene.render.seed;
  context.rng = pixel_rng(scene.render.seed, static_cast<uint32_t>(x), static_cast<uint32_t>(y));
  radiance = trace_primary(scene, scene.camera->generate_ray(x + 0.5, y + 0.5), context);
  return tree;
}

}  // namespace candela
