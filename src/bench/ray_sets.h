// The ray sets of `candela bench` exactly as shared/BENCH-RAYS.md defines them: primary rays of
// a pinhole camera looking at the bounds, incoherent rays from a splitmix64 stream, shadow rays
// from primary hits to a point light, and the incoherent rays again as occlusion queries.
// Every formula is evaluated in double and each ray is stored rounded to float32 (BenchRay),
// then widened to a candela::Ray for tracing, so that a float32 program (Embree) traces the
// very same rays.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "math/bounds.h"
#include "math/ray.h"

namespace candela {

struct BenchRay {
  float origin[3];
  float direction[3];
  float t_near;
  float t_far;
};

// x rounded to the nearest float32, as a double. Out of line on purpose: GCC 12.2 at -O2/-O3
// vectorises adjacent `(double)(float)a, (double)(float)b` pairs and drops the rounding
// (seen in this build), so every double-to-float-to-double round trip goes through here.
double round_to_float32(double x);

// The float ray as a double one (exact: every float is a double).
Ray to_ray(const BenchRay& ray);

// BENCH-RAYS "Incoherent rays": next() and uniform() of the splitmix64 generator.
class SplitMix64 {
 public:
  explicit SplitMix64(uint64_t seed) : state_(seed) {}
  uint64_t next() {
    state_ += 0x9E3779B97F4A7C15ull;
    uint64_t z = state_;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

 private:
  uint64_t state_;
};

// What the command line may override; the rest follows from the bounds.
struct RaySetOptions {
  std::optional<Vec3> eye;     // default C + 0.8·D·normalize(0.6, 0.45, 1.0)
  std::optional<Vec3> lookat;  // default C
  std::optional<Vec3> light;   // default C + D·(0.3, 1.0, 0.5)
  double fov_degrees = 45.0;   // vertical
  int width = 1024;
  int height = 1024;
  uint64_t incoherent_rays = 0;  // 0: width × height
  uint64_t seed = 1;
};

// The camera and light after defaults: C = bounds centre, D = |bmax - bmin|.
struct BenchView {
  Vec3 eye;
  Vec3 lookat;
  Vec3 light;
  double diagonal = 0;  // D
};
BenchView resolve_view(const Bounds3& bounds, const RaySetOptions& options);

// Ray index y·W + x, y = 0 the top row.
std::vector<BenchRay> primary_rays(const Bounds3& bounds, const RaySetOptions& options);
std::vector<BenchRay> incoherent_rays(const Bounds3& bounds, uint64_t count, uint64_t seed);
// One ray per primary ray with a hit, in index order; hit_t[i] is the hit distance of
// primary[i] (+inf or NaN: no hit).
std::vector<BenchRay> shadow_rays(const Bounds3& bounds, const RaySetOptions& options,
                                  std::span<const BenchRay> primary, std::span<const double> hit_t);

}  // namespace candela
