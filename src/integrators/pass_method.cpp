#include "integrators/pass_method.h"

#include <fmt/format.h>

#include <algorithm>
#include <utility>

#include "distributed/task_farm.h"
#include "integrators/distributed_tiles.h"
#include "integrators/memory_estimate.h"
#include "integrators/pass_checkpoint.h"
#include "io/byte_stream.h"
#include "util/cancellation.h"

namespace candela {
namespace {

// The pixels' sums (sums, weights: the region's, row by row) of the tile t, and back.
void put_tile(ByteWriter& writer, const PassCheckpoint& state, const PixelRect& t, int width) {
  for (int j = t.y0; j < t.y1; ++j)
    for (int i = t.x0; i < t.x1; ++i) {
      writer.put(state.sums[std::size_t(j) * width + i]);
      writer.put(state.weights[std::size_t(j) * width + i]);
    }
}

// Rounds of passes across ranks: in a round every tile goes to some rank with its sums so far,
// which adds the round's passes pixel by pixel in pass order — the very additions one process
// makes — and sends the sums back. Rank 0 decides each round (how many passes, or stop: the
// limit reached, time up, Ctrl-C), keeps the sums and hands out the checkpoints. A round cut
// short is dropped, so the sums always hold whole passes. Returns the "distributed" facts.
nlohmann::json passes_across_ranks(ProgressiveRun& run, PixelPasses& passes, PassCheckpoint& state,
                                   const std::function<Film()>& image, const std::function<Bytes()>& seal,
                                   bool& interrupted, uint64_t& dropped) {
  Cluster& cluster = *run.cluster();
  const int width = state.region.width(), height = state.region.height();
  const uint64_t last_pass = run.limits().steps > 0 ? run.limits().steps : UINT64_MAX;
  const std::vector<PixelRect> tiles = distributed_tiles({0, 0, width, height});
  std::vector<uint64_t> tiles_by_rank(static_cast<std::size_t>(cluster.size()), 0);
  uint64_t passes_per_round = 1, rounds = 0;
  for (;;) {
    // The plan of the next round, from rank 0: its first pass and pass count (0: stop).
    ByteWriter plan_writer;
    const bool cancelled = cancelled_anywhere(cluster);  // Ctrl-C on any rank stops all
    if (cluster.root()) {
      uint64_t count = 0;
      if (cancelled)
        interrupted = true;
      else if (run.more_steps(state.passes))
        count = std::min(passes_per_round, last_pass - state.passes);
      plan_writer.put<uint64_t>(state.passes);
      plan_writer.put<uint64_t>(count);
    }
    Bytes plan = plan_writer.take();
    cluster.broadcast(plan);
    ByteReader plan_reader(plan);
    const auto round_first = plan_reader.get<uint64_t>(), round_count = plan_reader.get<uint64_t>();
    if (round_count == 0) break;
    Stopwatch round_time;
    std::vector<Color> round_sums = cluster.root() ? state.sums : std::vector<Color>();
    std::vector<double> round_weights = cluster.root() ? state.weights : std::vector<double>();
    bool whole = true;
    uint64_t round_dropped = 0;
    TaskFarm farm;
    farm.task_count = tiles.size();
    farm.input = [&](std::size_t task) {
      ByteWriter writer;
      put_tile(writer, state, tiles[task], width);
      return writer.take();
    };
    farm.work = [&](std::size_t task, std::span<const std::byte> input) {
      const PixelRect& t = tiles[task];
      const PixelBox pixels{t.x0, t.y0, t.x1, t.y1};
      std::vector<Color> sums(std::size_t(t.width()) * t.height());
      std::vector<double> weights(sums.size());
      ByteReader reader(input);
      for (std::size_t k = 0; k < sums.size(); ++k) {
        sums[k] = reader.get<Color>();
        weights[k] = reader.get<double>();
      }
      uint64_t tile_dropped = 0;
      bool cut_short = false;
      for (uint64_t pass = round_first; pass < round_first + round_count; ++pass) {
        // The tile samples the ring its filter reaches too: a ring pixel's sample is a function of
        // the pixel and the pass, the same as the tile that owns it takes, so the tiles join into
        // one image.
        if (cancel_requested() || !passes.run_pass(pass, pixels, sums.data(), weights.data(), tile_dropped)) {
          cut_short = true;
          break;
        }
      }
      ByteWriter writer;
      writer.put<uint8_t>(cut_short ? 0 : 1);
      writer.put<uint64_t>(tile_dropped);
      writer.put_array(sums);
      writer.put_array(weights);
      return writer.take();
    };
    farm.collect = [&](std::size_t task, Bytes result) {
      const PixelRect& t = tiles[task];
      ByteReader reader(result);
      if (reader.get<uint8_t>() == 0) whole = false;
      round_dropped += reader.get<uint64_t>();
      const std::vector<Color> sums = reader.get_array<Color>();
      const std::vector<double> weights = reader.get_array<double>();
      for (int j = t.y0; j < t.y1; ++j)
        for (int i = t.x0; i < t.x1; ++i) {
          round_sums[std::size_t(j) * width + i] = sums[std::size_t(j - t.y0) * t.width() + (i - t.x0)];
          round_weights[std::size_t(j) * width + i] = weights[std::size_t(j - t.y0) * t.width() + (i - t.x0)];
        }
    };
    farm.stop = [] { return cancel_requested(); };
    const TaskFarmReport report = run_task_farm(cluster, farm);
    ++rounds;
    if (!cluster.root()) continue;
    for (std::size_t r = 0; r < report.tasks_by_rank.size(); ++r) tiles_by_rank[r] += report.tasks_by_rank[r];
    if (report.tasks_done < tiles.size() || !whole) {  // Ctrl-C during the round: dropped
      interrupted = true;
      continue;  // the next plan says stop
    }
    state.sums.swap(round_sums);
    state.weights.swap(round_weights);
    dropped += round_dropped;
    for (uint64_t pass = 0; pass < round_count; ++pass) run.step_done(++state.passes, image);
    // Rounds of a second for every 200,000 pixels (1 to 30 s): each round sends every tile's sums
    // out and back (48 bytes a pixel), which stays near 1 % of the round on 10 Gb/s; no longer
    // than the time left or the checkpoint interval allow. The image does not depend on it.
    const double per_pass = round_time.seconds() / double(round_count);
    double budget = std::clamp(double(width) * height / 2e5, 1.0, 30.0);
    if (run.limits().seconds > 0) budget = std::min(budget, run.limits().seconds - run.seconds());
    if (run.request().checkpoint) budget = std::min(budget, run.limits().checkpoint_interval);
    passes_per_round =
        per_pass > 0 ? std::clamp<uint64_t>(static_cast<uint64_t>(budget / per_pass), 1, 256) : 256;
    if (state.passes < last_pass) run.checkpoints().between_steps(seal);
  }
  nlohmann::json distributed = distributed_facts(cluster, tiles_by_rank, "tiles");
  distributed["rounds"] = rounds;
  return distributed;
}

}  // namespace

std::vector<MemoryPart> PassMethod::memory_needed(const Scene&, const RenderRequest& request) const {
  const PixelRect& region = request.region;
  // A Color and a double a pixel for the sums and weights, again in a checkpoint; the image and a
  // pass's (RenderResult, the pass image).
  const uint64_t pixels = film_bytes(region, 1) / sizeof(Color);
  return {image_memory_part("the image, a pass's, the running sums and weights and their checkpoint",
                            film_bytes(region, 4) + 2 * pixels * sizeof(double))};
}

RenderResult PassMethod::render(const Scene& scene, const RenderRequest& request) const {
  RenderResult output(request.region);
  const PixelRect region = request.region;
  const int width = region.width(), height = region.height();
  // Everything besides the scene file that changes a sample: a checkpoint made with other values
  // cannot be continued.
  ProgressiveRun run(
      request,
      fmt::format("{}|{} {} seed={} image={}x{}", request.fingerprint, name(), pass_fingerprint(),
                  request.seed_for(scene), scene.camera->width(), scene.camera->height()),
      limits());
  PassCheckpoint state;
  state.fingerprint = run.fingerprint();
  state.region = region;
  state.sums.assign(std::size_t(width) * height, Color());
  state.weights.assign(std::size_t(width) * height, 0.0);
  // Only rank 0 reads the checkpoint: the others are given sums with each tile.
  const std::function<PassCheckpoint(const SealedCheckpoint&)> unseal = [&](const SealedCheckpoint& sealed) {
    return unseal_pass_checkpoint(name(), sealed);
  };
  const std::function<void(const PassCheckpoint&, const SourceLocation&)> check =
      [&](const PassCheckpoint& resumed, const SourceLocation& where) {
        const PixelRect& r = resumed.region;
        if (r.x0 != region.x0 || r.y0 != region.y0 || r.x1 != region.x1 || r.y1 != region.y1)
          throw InputError(
              where, fmt::format("the checkpoint covers pixels [{},{})×[{},{}), not [{},{})×[{},{})", r.x0,
                                 r.x1, r.y0, r.y1, region.x0, region.x1, region.y0, region.y1));
        if (run.limits().steps > 0 && resumed.passes > run.limits().steps)
          throw InputError(where,
                           fmt::format("the checkpoint already holds {} samples per pixel, more than {} = {}",
                                       resumed.passes, run.limits().steps_setting, run.limits().steps));
      };
  if (std::optional<PassCheckpoint> resumed = run.resume(unseal, check, false)) state = std::move(*resumed);
  const double seconds_before = state.seconds;
  const std::unique_ptr<PixelPasses> passes = start_passes(scene, request);
  run.start(state.passes, name(), "passes", "spp");

  // Σ w·L / Σ w (with the box of half a pixel Σ w is the pass count).
  const auto film_of_passes = [&](Film& target) {
    for (int j = 0; j < height; ++j)
      for (int i = 0; i < width; ++i) {
        const std::size_t k = std::size_t(j) * width + i;
        target.at(i, j) = state.weights[k] > 1e-12 ? state.sums[k] * (1.0 / state.weights[k]) : Color();
      }
  };
  const std::function<Film()> image = [&] {
    Film film(width, height);
    film_of_passes(film);
    return film;
  };
  const std::function<Bytes()> seal = [&] {
    PassCheckpoint snapshot{state.fingerprint, state.region, state.passes, seconds_before + run.seconds(),
                            state.rays,        state.sums,   state.weights};
    snapshot.rays += passes->rays();
    return seal_pass_checkpoint(name(), snapshot);
  };
  bool interrupted = false;
  uint64_t dropped = 0;
  if (run.cluster()) {
    output.statistics.extra["distributed"] =
        passes_across_ranks(run, *passes, state, image, seal, interrupted, dropped);
  } else {
    // A pass's samples are all taken before any is added to the sums: a pass cut short by Ctrl-C
    // is dropped, so the sums (and the checkpoint) always hold whole passes.
    const PixelBox pixels{0, 0, width, height};
    while (run.more_steps(state.passes)) {
      if (cancel_requested() ||
          !passes->run_pass(state.passes, pixels, state.sums.data(), state.weights.data(), dropped)) {
        interrupted = true;
        break;
      }
      run.step_done(++state.passes, image);
      if (run.more_steps(state.passes)) run.checkpoints().between_steps(seal);
    }
  }
  run.finish_progress();
  run.checkpoints().finish(seal);  // a later run can go on from it
  output.checkpoint = run.checkpoints().take_final();
  film_of_passes(output.film);

  RayCounts rays = passes->rays();
  if (run.cluster()) sum_across_ranks(*run.cluster(), rays);
  output.statistics.rays += rays;
  output.statistics.pixels += uint64_t(width) * height;
  nlohmann::json facts;
  passes->add_facts(facts);
  facts["dropped_samples"] = dropped;
  run.report(state.passes, seconds_before, interrupted, facts, output.statistics);
  output.statistics.extra[std::string(name())] = std::move(facts);
  return output;
}

}  // namespace candela
