// An image region rendered across the ranks of a cluster: square tiles handed out
// dynamically (distributed/task_farm.h), each rendered whole by one rank with its threads, its
// pixels sent to rank 0 bit for bit. A pixel's value depends only on the pixel (per-pixel random
// streams, SPEC §6), so the gathered image is the single-process image.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "camera/film.h"
#include "distributed/cluster.h"
#include "integrators/method.h"
#include "util/progress.h"
#include "util/statistics.h"

namespace candela {

// The request's cluster when it has several ranks; null when this process renders alone.
inline Cluster* several_ranks(const RenderRequest& request) {
  return request.cluster && request.cluster->distributed() ? request.cluster : nullptr;
}

// The side of a distributed tile in pixels: large enough that a tile's pixels keep a rank's
// threads busy and its message is worth sending, small enough for 16 tiles a rank at 512².
inline constexpr int kDistributedTileSize = 64;

struct RenderedTile {
  Film film{0, 0};
  std::vector<uint32_t> counts;  // method-defined per-pixel counters (tile-sized arrays), or none
};

struct TiledRender {
  uint64_t tiles = 0;       // in the region
  uint64_t tiles_done = 0;  // rank 0: gathered (fewer after Ctrl-C)
  std::vector<uint64_t> tiles_by_rank;
  bool interrupted = false;  // Ctrl-C reached some rank: tiles may be missing or black (every rank agrees)
};

// The tiles of a region, row by row.
std::vector<PixelRect> distributed_tiles(const PixelRect& region, int tile_size = kDistributedTileSize);

// Every rank calls it. On rank 0 film (region-sized) receives every tile and place_counts, when
// set, each tile's counts; other ranks' film is left as it was. progress (rank 0) advances a tile
// at a time.
TiledRender render_tiles_across_ranks(
    Cluster& cluster, const PixelRect& region,
    const std::function<RenderedTile(const PixelRect& tile)>& render_tile, Film& film,
    const std::function<void(const PixelRect&, const std::vector<uint32_t>&)>& place_counts = {},
    ProgressReporter* progress = nullptr);

// A view drawn by draw(area, target) (target area-sized): on one process (cluster null or of one
// rank) the whole region at once; with several ranks in tiles across them, with the
// "distributed" facts in statistics. Every rank calls it.
void draw_across_ranks(Cluster* cluster, const PixelRect& region,
                       const std::function<void(const PixelRect& area, Film& target)>& draw, Film& film,
                       RunStatistics& statistics);

// Adds up every rank's ray counts (a collective: every rank calls it); all ranks get the total.
void sum_across_ranks(Cluster& cluster, RayCounts& rays);

// The "distributed" facts of --stats: ranks, what each did, what crossed.
nlohmann::json distributed_facts(const Cluster& cluster, const std::vector<uint64_t>& tasks_by_rank,
                                 const char* task_name);

}  // namespace candela
