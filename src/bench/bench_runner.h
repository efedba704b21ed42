// `candela bench` as a library (SPEC §14, shared/BENCH-RAYS.md): for each accelerator and thread
// count, build (time and report().bytes), then for each ray set one untimed warm-up pass and
// timed repetitions traced in parallel over the rays (TBB), and the checksums summed
// sequentially in ray order afterwards: hits, sum_t (double) and sum_prim (the triangle ids of
// the hits). The checksums do not depend on the thread count.
//
// Ray sets: "primary" and "incoherent" (nearest hit), "shadow" (any hit; built from the
// primary hits of the accelerator being measured), "incoherent_occlusion" (any hit).
// Accelerators: every registered name; "embree" is Embree in native_triangles mode (its own
// float triangle test, the reference speed) and "embree-exact" Embree with Candela's tests.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "accel/accelerator.h"
#include "bench/bench_mesh.h"
#include "bench/ray_sets.h"

namespace candela {

// The bench scene: one MeshTriangle primitive per non-degenerate triangle (make_triangles, in
// triangle order) and the triangle id of each primitive.
class BenchScene {
 public:
  explicit BenchScene(std::shared_ptr<const TriangleMesh> mesh);
  // A scene's primitives (they must outlive this); the id of a primitive is its index.
  explicit BenchScene(std::span<const Primitive> primitives);
  std::span<const Primitive> primitives() const { return primitives_; }
  uint32_t triangle_id(uint32_t primitive) const { return triangle_ids_[primitive]; }
  std::size_t skipped_degenerate() const { return skipped_degenerate_; }
  // Copies of an earlier triangle (make_triangles' merged_duplicates), left out like the
  // degenerate ones: the first copy wins every tie, so no hit changes.
  std::size_t merged_duplicates() const { return merged_duplicates_; }

 private:
  std::vector<std::unique_ptr<Shape>> shapes_;
  std::vector<Primitive> primitives_;
  std::vector<uint32_t> triangle_ids_;
  std::size_t skipped_degenerate_ = 0;
  std::size_t merged_duplicates_ = 0;
};

enum class RayQuery { nearest, any };

// Per ray: the hit distance (+inf: no hit; 0 for an occluded any-hit ray) and the primitive
// index (kNoHit: none, and always for any-hit rays).
struct TraceResults {
  static constexpr uint32_t kNoHit = 0xFFFFFFFFu;
  std::vector<double> t;
  std::vector<uint32_t> primitive;
};

struct Checksums {
  uint64_t hits = 0;
  double sum_t = 0;
  uint64_t sum_prim = 0;
};

// Traces every ray in parallel with TBB (as many threads as the calling arena allows).
void trace_rays(const Accelerator& accelerator, std::span<const BenchRay> rays, RayQuery query,
                TraceResults& results);
// Sequential, in ray order: hits, sum of t and sum of triangle ids (nearest-hit rays only).
Checksums checksums(const TraceResults& results, const BenchScene& scene, RayQuery query);

// The names `candela bench --accel` accepts: the registry's, and "embree-exact" with Embree.
std::vector<std::string> bench_accelerator_names();
// nullptr for an unknown name; "embree" is native_triangles mode. settings: "NAME.key=value"
// assignments (--set); those for NAME are read by the accelerator's registry entry, as a
// scene's "NAME" object would be (unknown keys and bad values refused, naming the assignment).
std::unique_ptr<Accelerator> make_bench_accelerator(std::string_view name,
                                                    const std::vector<std::string>& settings = {});

struct BenchOptions {
  std::vector<std::string> accelerators;          // empty: every registered accelerator
  std::vector<std::string> accelerator_settings;  // --set NAME.key=value (see make_bench_accelerator)
  std::vector<int> threads{1, 2};
  RaySetOptions rays;
  int repeat = 3;              // timed repetitions
  double min_seconds = 0.5;    // ...fewer once the timed ones took this long (a slow accelerator runs once)
  std::string dump_directory;  // when set, the ray sets are written there (see write_ray_dump)
};

struct BenchResult {
  std::string accel;
  std::string set;
  int threads = 0;
  uint64_t rays = 0;
  int repetitions = 0;
  double seconds = 0;  // of the timed repetitions
  double mrays_per_s = 0;
  Checksums checksums;
};

struct BenchBuild {
  std::string accel;
  int threads = 0;
  double seconds = 0;
  uint64_t bytes = 0;
};

struct BenchReport {
  std::string mesh;
  uint64_t triangles = 0;
  std::vector<BenchResult> results;
  std::vector<BenchBuild> builds;
  std::vector<std::pair<std::string, std::string>> quality;  // accel, report().text()

  // {"mesh", "triangles", "results": [{accel, set, threads, rays, mrays_per_s, hits, sum_t,
  // sum_prim}], "builds": [{accel, threads, seconds, bytes}]}
  nlohmann::json to_json() const;
  // The table of results (with the ratio to Embree when it ran), builds and quality reports.
  std::string table() const;
};

// What is measured: its name, the bounds the ray sets are made from, and its primitives.
struct BenchInput {
  std::string name;
  Bounds3 bounds;
  uint64_t triangles = 0;  // triangles of a mesh, primitives of a scene
  const BenchScene* scene = nullptr;
};

// Throws std::invalid_argument for an unknown accelerator name or bad options.
BenchReport run_bench(const BenchMesh& mesh, const BenchOptions& options,
                      const std::function<void(const std::string&)>& log = {});
// The same for any primitives (a scene file): "embree" (native triangles) does not apply.
BenchReport run_bench(const BenchInput& input, const BenchOptions& options,
                      const std::function<void(const std::string&)>& log = {});

// Writes the rays to directory/<set>.rays as packed little-endian float32 records (origin xyz,
// direction xyz, tnear, tfar: 32 bytes a ray), atomically.
void write_ray_dump(const std::string& directory, const std::string& set, std::span<const BenchRay> rays);

}  // namespace candela
