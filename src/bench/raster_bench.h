// `candela bench --raster`: throughput of the scanline z-buffer rasterizer (SPEC §9, §14) on a
// mesh framed by a perspective camera. Single-threaded: one rasterizer draws one frame.
//
// Framing: the bounding sphere of the mesh's bounds (centre C, radius R = half the diagonal)
// seen from C + d·normalize(0.6, 0.45, 1.0) (BENCH-RAYS.md's eye direction) with up (0, 1, 0),
// at the distance d = R / sin(fov/2) where it just fills the vertical field of view; near =
// (d − R)/2 and far = 2(d + R), so no triangle is cut by a depth plane. Default 1024×768, vertical
// fov 45°.
//
// Passes, each drawing every triangle of the mesh into a cleared buffer (both windings):
// - item_buffer: ItemBuffer::draw of the whole mesh, one id per triangle (the hemicube's use);
// - depth:       the depth test alone (no varyings, every passing fragment written);
// - gouraud:     000 §3.2: one intensity per vertex (two-sided Lambert of the vertex normal with
//                a head light, computed in the frame), interpolated into a float image;
// - phong:       000 §3.3: the vertex normal and position (6 varyings) interpolated and the
//                model (the same Lambert term) evaluated per pixel.
// A frame transforms every vertex to clip space and draws; clearing is not timed. After one
// untimed warm-up frame, frames are timed until at least `repeat` were drawn and together they
// took at least `min_seconds`; the best frame gives triangles/s and written fragments/s.
#pragma once

#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench/bench_mesh.h"
#include "math/vector.h"

namespace candela {

struct RasterBenchOptions {
  int width = 1024;
  int height = 768;
  double fov_degrees = 45.0;  // vertical
  int repeat = 3;             // at least this many timed frames per pass
  double min_seconds = 1.0;   // ...and at least this long in all
};

struct RasterPassResult {
  std::string pass;
  int frames = 0;            // timed
  double best_seconds = 0;   // the fastest timed frame
  double total_seconds = 0;  // all timed frames
  double mtriangles_per_s = 0;
  double mfragments_per_s = 0;  // written fragments (pixels) per second of the best frame
  // One frame's RasterStatistics (the same every frame).
  uint64_t culled = 0, clipped = 0, fragments = 0, written = 0;
};

struct RasterBenchReport {
  std::string mesh;
  uint64_t triangles = 0;
  int width = 0, height = 0;
  double fov_degrees = 0;
  Vec3 eye, target;
  double near = 0, far = 0;
  std::vector<RasterPassResult> passes;

  // {"mesh", "triangles", "width", "height", "fov", "eye", "target", "near", "far",
  //  "passes": [{pass, frames, best_seconds, total_seconds, mtriangles_per_s, mfragments_per_s,
  //  culled, clipped, fragments, written}]}
  nlohmann::json to_json() const;
  std::string table() const;
};

// Throws std::invalid_argument for bad options (size below 1, fov outside (0, 180), repeat
// below 1, negative or non-finite min_seconds) or a mesh with empty or non-finite bounds.
RasterBenchReport run_raster_bench(const BenchMesh& mesh, const RasterBenchOptions& options,
                                   const std::function<void(const std::string&)>& log = {});

}  // namespace candela
