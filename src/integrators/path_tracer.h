// The path-traced reference (SPEC §12; 002 §2, the rendering equation): unidirectional path
// tracing with next-event estimation, multiple importance sampling of lights and BSDFs (power
// heuristic) and Russian roulette, in progressive passes of one sample per pixel.
//
// Units: like every Candela method the image holds π × radiance (W/m², "exitance units"), so a
// diffuse surface shows its radiosity B, an emitter its exitance E, and a ray leaving the scene
// the background/environment color — the values the local, radiosity and meshless methods show
// for the same scene. Inside, f is the physical BSDF (a white Lambert surface has 1/π), emitters
// give E, the environment its color, and a point-like light of intensity I (Ip·f_at, the
// irradiance it gives at normal incidence) contributes π·f·I·cos θ.
#pragma once

#include "integrators/light_sampler.h"
#include "integrators/method.h"
#include "integrators/pass_method.h"
#include "io/json_node.h"
#include "math/pcg32.h"
#include "sampling/sampler.h"

namespace candela {

// The scene file's "path" object (SPEC §12).
struct PathSettings {
  int spp = 64;                     // passes of one sample per pixel; 0: as many as `time` allows
  double time = 0;                  // seconds; > 0: stop after the pass that reaches it (or at spp, if set)
  int max_depth = 0;                // bounces at most; 0: unlimited (Russian roulette ends every path)
  int roulette_depth = 3;           // Russian roulette from this bounce on
  double checkpoint_interval = 60;  // seconds between checkpoints (candela render --checkpoint)
  std::string sampler = "sobol";    // sampling/sampler.h: independent, stratified, sobol
};
// Ranges checked, unknown keys refused; spp 0 needs a time limit.
PathSettings read_path_settings(const JsonNode& node);

struct PathCounts {
  RayCounts rays;
};

// The estimate of one camera ray (display units), drawing from the sampler's current sample (its
// pixel point already drawn) or from a random stream. The depth limits are path.max_depth and
// path.roulette_depth.
Color path_radiance(const Scene& scene, const PathSettings& settings, const LightSampler& lights,
                    const Ray& ray, Sampler& sampler, RayCounts& rays);
Color path_radiance(const Scene& scene, const PathSettings& settings, const LightSampler& lights,
                    const Ray& ray, Pcg32& rng, RayCounts& rays);

// The radiance a surface point with a white Lambert surface (ρ = 1) facing `normal` would
// reflect, times π: the irradiance at (point, normal) in display units (candela probe). Every
// light arriving over the hemisphere counts, by next-event estimation and BSDF sampling with MIS.
// From the sampler's current sample after its first pair (the pixel point, not used here), or
// from a random stream.
Color path_irradiance(const Scene& scene, const PathSettings& settings, const LightSampler& lights,
                      const Vec3& point, const Vec3& normal, Sampler& sampler, RayCounts& rays);
Color path_irradiance(const Scene& scene, const PathSettings& settings, const LightSampler& lights,
                      const Vec3& point, const Vec3& normal, Pcg32& rng, RayCounts& rays);

// The stream of pass `pass` at image pixel (x, y): independent of the thread and of the region
// (the independent sampler's, sampling/independent_sampler.h).
Pcg32 path_pixel_rng(uint64_t seed, uint64_t pass, uint32_t x, uint32_t y);
// The stream of pass `pass` at image point (x, y) of aa.mode "corners" and "adaptive": a lattice
// point's, independent of the thread, of the region and of which pixel asked first.
Pcg32 path_point_rng(uint64_t seed, uint64_t pass, double x, double y);

// The passes, their checkpoints and ranks are PassMethod's; the path tracer's own are the pass
// over the pixels (PathPasses), path.spp and path.time, and the settings that shape a sample.
class PathMethod final : public PassMethod {
 public:
  explicit PathMethod(const PathSettings& settings = {}) : settings_(settings) {}
  std::string_view name() const override { return "path"; }
  std::unique_ptr<PointProbe> point_probe(const Scene& scene, const ProbeSettings& settings) const override;

 protected:
  std::string pass_fingerprint() const override;
  RunLimits limits() const override;
  std::unique_ptr<PixelPasses> start_passes(const Scene& scene, const RenderRequest& request) const override;

 private:
  PathSettings settings_;
};

}  // namespace candela
