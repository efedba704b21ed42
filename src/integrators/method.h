// A rendering method (local, whitted, raster, radiosity, meshless, path), made by the method
// registry from its settings. A method reads the Scene, never edits it, and writes no file: it
// returns its image and extras (RenderResult), and hands out its checkpoints, for the caller to
// write.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "camera/film.h"
#include "integrators/antialiasing_support.h"
#include "integrators/ray_tree.h"
#include "io/checkpoint_file.h"
#include "scene/scene.h"
#include "util/statistics.h"

namespace candela {

class Cluster;
class PointProbe;
struct ProbeSettings;
struct RadiositySolveResult;

// The pixels to render: [x0, x1) × [y0, y1) of the camera's image.
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
};

// One step of a progressive method's way to its image (candela render --error-log,
// candela report's error-against-time chart).
struct ProgressStep {
  std::string_view unit;                  // "passes", "shots", "sweeps", "iterations"
  uint64_t work = 0;                      // of them, so far
  std::optional<double> unshot_fraction;  // progressive radiosity: the unshot flux left
  // Makes the image of the state reached: the request's region, as render would return it were it
  // to stop here (progressive radiosity and meshless: the display of the solution so far).
  std::function<Film()> image;
};

struct RenderRequest {
  PixelRect region;
  bool quiet = false;
  // Extras to compute besides the image, when the method can give them (MethodCapabilities).
  bool sites_image = false;  // meshless: the image with its sites drawn (seed 002 Figure 4.7)
  // The progressive run (path; progressive radiosity; SPEC §12, §15), for methods whose
  // capabilities say checkpoints. With `checkpoint` set, the method returns its final state in
  // RenderResult::checkpoint (also when interrupted) and, when save_checkpoint is given, hands it
  // its state every checkpoint_interval seconds while work remains; the caller stores them
  // (candela render: the --checkpoint file, atomically). `resume` is a state to continue from:
  // every rank is given one, only rank 0's bytes are read (it need not be on the others' disks),
  // and errors name its source. `fingerprint` ties a checkpoint to the scene that made it (the
  // caller's part: the scene file's contents and overrides; the method adds its own settings).
  // A checkpoint is sealed bytes (io/checkpoint_file.h); only rank 0 hands checkpoints out.
  bool checkpoint = false;
  std::function<void(const Bytes& sealed)> save_checkpoint = {};
  std::optional<SealedCheckpoint> resume = {};
  std::string fingerprint = {};
  // Seconds between checkpoints; 0: the method's default (path.checkpoint_interval; 60 for
  // progressive radiosity).
  double checkpoint_interval = 0;
  // When set, a progressive method reports its steps — the path tracer after every whole pass (where
  // a caller, a test, may ask the run to stop after exactly N passes),
  // progressive radiosity after every `progress_every` shots, Gauss-Seidel after every sweep,
  // meshless after every iteration of λ — in one process (not across ranks). The time the caller
  // spends in it (making and measuring the image) is the caller's to account for. A method that
  // keeps its solution between renders (radiosity, meshless) solves afresh when it is set.
  std::function<void(const ProgressStep& step)> on_progress = {};
  uint64_t progress_every = 0;  // progressive radiosity: shots between steps; 0: 50
  // The ranks to split the work across (docs/distributed.md); null or one rank: this
  // process alone. Every rank calls render with the same scene and request; rank 0's result
  // holds the image and the checkpoints. Statistics are totals over the ranks.
  Cluster* cluster = nullptr;
  // This render's seed and anti-aliasing settings where they are not the scene's
  // (candela.render(seed=, spp=) in Python). A method reads them through seed_for and
  // antialiasing_for, never from scene.render.seed or scene.antialiasing on its render path, so
  // that a render with other values leaves the Scene as it was and renders of one Scene with
  // different values may run at once.
  std::optional<uint64_t> seed = {};
  std::optional<AntialiasingSettings> antialiasing = {};
  uint64_t seed_for(const Scene& scene) const { return seed.value_or(scene.render.seed); }
  const AntialiasingSettings& antialiasing_for(const Scene& scene) const {
    return antialiasing ? *antialiasing : scene.antialiasing;
  }
};

// What the light-dependent part of a render cost, for methods whose capabilities say relighting
// (the meshless method's direct light and iteration): a relit frame's cost on the relighting page.
struct RelightingCost {
  double lighting_seconds = 0;
  uint64_t iterations = 0;
};

// What a render gives: the image of the request's region, what the run measured, and the extras
// the method's capabilities promise. The caller decides what to write (candela render).
struct RenderResult {
  explicit RenderResult(const PixelRect& region) : film(region.width(), region.height()) {}
  Film film;
  RunStatistics statistics;
  std::optional<Film> sites_image;                       // when requested (RenderRequest::sites_image)
  std::shared_ptr<const RadiositySolveResult> solution;  // a view-independent solution (radiosity)
  std::optional<Bytes> checkpoint;           // the final state, sealed (RenderRequest::checkpoint; rank 0)
  std::optional<RelightingCost> relighting;  // what the lighting cost, when the method relights
};

// A method's view-independent solution made on its own, without an image (Method::solve_alone:
// candela bench --solve, candela.solution in Python).
struct StandaloneSolution {
  // One array of the solution, row by row: a solution mesh's "vertices" (columns 3), the meshless
  // sites' effective "area" (columns 1).
  struct Array {
    std::string name;
    std::size_t columns = 1;
    bool indices = false;  // vertex or object indices (uint32 in Python); exact in a double
    std::vector<double> values;
    std::size_t rows() const { return columns == 0 ? 0 : values.size() / columns; }
  };
  // Adds the array `name` of rows: numbers (one column), or points, colours and index triples
  // (three).
  template <class Row>
  void add(std::string name, const std::vector<Row>& rows, bool indices = false) {
    Array array{std::move(name), std::is_arithmetic_v<Row> ? 1u : 3u, indices, {}};
    array.values.reserve(rows.size() * array.columns);
    for (const Row& row : rows) {
      if constexpr (std::is_arithmetic_v<Row>)
        array.values.push_back(static_cast<double>(row));
      else
        for (int c = 0; c < 3; ++c) array.values.push_back(static_cast<double>(row[c]));
    }
    arrays.push_back(std::move(array));
  }
  std::vector<Array> arrays;
  nlohmann::json facts;  // what the solve measured: the method's facts of render --stats
  // The facts worth a column of candela bench --solve's table, in order: heading and value as shown.
  std::vector<std::pair<std::string, std::string>> columns;
};

// SPEC §15: a part of what a render will hold beyond the loaded scene, estimated before
// any work, and the setting that makes it smaller.
struct MemoryPart {
  std::string what;  // "the image", "the effective-area integration's 42,600,000 triangles"
  uint64_t bytes = 0;
  std::string setting;  // the JSON path to change ("camera.width", "meshless.effective_area")
  std::string remedy;   // how ("set it to \"thesis\"")
};

class Method {
 public:
  virtual ~Method() = default;
  virtual std::string_view name() const = 0;
  virtual RenderResult render(const Scene& scene, const RenderRequest& request) const = 0;
  // The ray tree of pixel (x, y) and its radiance, for methods whose capabilities say ray_trees;
  // the others throw std::logic_error.
  virtual RayTree pixel_ray_tree(const Scene& scene, int x, int y, Color& radiance) const;
  // Why the method cannot honour the "aa" settings `antialiasing` for the scene — its own or a
  // render's (RenderRequest::antialiasing_for) — none when it can; by default it can:
  // the path tracer and the ray tracers take every mode and filter.
  virtual std::optional<AntialiasingRefusal> antialiasing_refusal(
      const Scene& scene, const AntialiasingSettings& antialiasing) const {
    (void)scene;
    (void)antialiasing;
    return std::nullopt;
  }
  // Whether the method draws its image with the rasterizer (raster; radiosity's gouraud display):
  // candela render --spp N then gives it aa.mode "uniform", its n× grid drawn at once, rather
  // than the n² passes of "jittered" (choose_jittered_where_possible).
  virtual bool rasterizes() const { return false; }
  // Throws the InputError of a scene the method cannot render with its settings (an emitter its
  // shading cannot take), so that create_method refuses it before any work; render checks again.
  virtual void refuse_scene(const Scene& scene) const { (void)scene; }
  // What rendering the request (its region empty: the solution alone, as probe needs
  // it) will hold, part by part; by default the image (integrators/memory_estimate.h).
  virtual std::vector<MemoryPart> memory_needed(const Scene& scene, const RenderRequest& request) const;
  // What `candela probe` asks of the method (integrators/probe.h): irradiance and radiance at
  // sensor points by its own model, its solution made now when it has one; null when it cannot
  // (its capabilities do not say probe).
  virtual std::unique_ptr<PointProbe> point_probe(const Scene& scene, const ProbeSettings& settings) const;
  // Its view-independent solution, made now with the scene's seed (quiet: no progress bar), for
  // methods whose capabilities say standalone_solution; the others throw std::logic_error.
  virtual StandaloneSolution solve_alone(const Scene& scene, bool quiet) const;
};

// Throws the InputError of method.antialiasing_refusal(scene, antialiasing), naming the method,
// the setting and its value (SPEC §17: never a silent fallback).
void refuse_unsupported_antialiasing(const Method& method, const Scene& scene,
                                     const AntialiasingSettings& antialiasing);
// The same for the scene's own "aa" settings.
void refuse_unsupported_antialiasing(const Method& method, const Scene& scene);

inline RayTree Method::pixel_ray_tree(const Scene&, int, int, Color&) const {
  throw std::logic_error(std::string(name()) + " traces no ray trees");
}

inline StandaloneSolution Method::solve_alone(const Scene&, bool) const {
  throw std::logic_error(std::string(name()) + " has no view-independent solution");
}

}  // namespace candela
