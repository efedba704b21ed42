#include "integrators/distributed_tiles.h"

#include <algorithm>

#include "distributed/task_farm.h"
#include "util/cancellation.h"

namespace candela {

std::vector<PixelRect> distributed_tiles(const PixelRect& region, int tile_size) {
  std::vector<PixelRect> tiles;
  for (int y = region.y0; y < region.y1; y += tile_size)
    for (int x = region.x0; x < region.x1; x += tile_size)
      tiles.push_back({x, y, std::min(x + tile_size, region.x1), std::min(y + tile_size, region.y1)});
  return tiles;
}

TiledRender render_tiles_across_ranks(
    Cluster& cluster, const PixelRect& region,
    const std::function<RenderedTile(const PixelRect& tile)>& render_tile, Film& film,
    const std::function<void(const PixelRect&, const std::vector<uint32_t>&)>& place_counts,
    ProgressReporter* progress) {
  const std::vector<PixelRect> tiles = distributed_tiles(region);
  TaskFarm farm;
  farm.task_count = tiles.size();
  farm.work = [&](std::size_t task, std::span<const std::byte>) {
    const RenderedTile rendered = render_tile(tiles[task]);
    ByteWriter writer;
    writer.put_array(rendered.film.pixels());
    writer.put_array(rendered.counts);
    return writer.take();
  };
  farm.collect = [&](std::size_t task, Bytes result) {
    const PixelRect& tile = tiles[task];
    ByteReader reader(result);
    const std::vector<Color> pixels = reader.get_array<Color>();
    const std::vector<uint32_t> counts = reader.get_array<uint32_t>();
    if (pixels.size() != std::size_t(tile.width()) * tile.height())
      throw std::runtime_error("distributed tile of the wrong size");
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x)
        film.at(x - region.x0, y - region.y0) =
            pixels[std::size_t(y - tile.y0) * tile.width() + (x - tile.x0)];
    if (place_counts) place_counts(tile, counts);
    if (progress) progress->advance();
  };
  farm.stop = [] { return cancel_requested(); };
  const TaskFarmReport report = run_task_farm(cluster, farm);
  TiledRender result;
  result.tiles = tiles.size();
  result.tiles_done = report.tasks_done;
  result.tiles_by_rank = report.tasks_by_rank;
  result.interrupted = cancelled_anywhere(cluster);
  return result;
}

void draw_across_ranks(Cluster* cluster, const PixelRect& region,
                       const std::function<void(const PixelRect& area, Film& target)>& draw, Film& film,
                       RunStatistics& statistics) {
  if (!cluster || !cluster->distributed()) return draw(region, film);
  const TiledRender run = render_tiles_across_ranks(
      *cluster, region,
      [&](const PixelRect& tile) {
        RenderedTile rendered{Film(tile.width(), tile.height()), {}};
        draw(tile, rendered.film);
        return rendered;
      },
      film);
  statistics.extra["distributed"] = distributed_facts(*cluster, run.tiles_by_rank, "tiles");
}

void sum_across_ranks(Cluster& cluster, RayCounts& rays) {
  std::vector<uint64_t> counts{rays.primary, rays.shadow, rays.reflected, rays.refracted};
  cluster.sum(counts);
  rays = {counts[0], counts[1], counts[2], counts[3]};
}

nlohmann::json distributed_facts(const Cluster& cluster, const std::vector<uint64_t>& tasks_by_rank,
                                 const char* task_name) {
  const CommunicationVolume& volume = cluster.volume();
  return {{"ranks", cluster.size()},
          {std::string(task_name) + "_by_rank", tasks_by_rank},
          {"rank0_messages_sent", volume.messages_sent},
          {"rank0_bytes_sent", volume.bytes_sent},
          {"rank0_messages_received", volume.messages_received},
          {"rank0_bytes_received", volume.bytes_received},
          {"collectives", volume.collectives},
          {"collective_bytes", volume.collective_bytes},
          {"rank0_waiting_seconds", volume.waiting_seconds}};
}

}  // namespace candela
