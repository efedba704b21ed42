// The environment as a light: the radiance arriving from infinitely far away
// (shading/environment.h: a constant sky, a cube or an equirectangular map) lights every
// method's diffuse points through shadow rays that reach nothing — the local model, the
// rasterizer, radiosity's first shot (the sky seen through openings) and meshless η — as it lights
// the path tracer's (integrators/light_sampler.h). `background` is not a light: it only colours
// rays that leave the scene (docs/scene-format.md); a uniform sky is {"type": "constant"}.
//
// The samples: samples × samples cells of [0, 1)², each point u mapped to a direction by the
// environment's own importance sampling (uniform on the sphere for a constant sky, by luminance
// for a map); sample k carries intensity L(ω) / (π · samples² · pdf(ω)), so that Σ_k intensity_k ·
// max(0, n·ω_k) estimates (1/π) ∫ L cos θ dω, the quantity a diffuse surface's kd multiplies (as
// for the area lights, area_light.h).
#pragma once

#include "math/constants.h"
#include "scene/light.h"
#include "shading/environment.h"

namespace candela {

class EnvironmentLight final : public Light {
 public:
  // Throws std::invalid_argument for samples < 1. The environment must outlive the light.
  EnvironmentLight(const Environment& environment, int samples);
  // The whole sky as the one direction its sampling gives for u = (0.5, 0.5).
  bool illuminate(const Vec3& point, LightSample& sample) const override;
  int sample_count() const override { return samples_ * samples_; }
  bool stratified() const override { return true; }
  bool illuminate_sample(const Vec3& point, int index, const Vec2& within,
                         LightSample& sample) const override;
  bool illuminate_random(const Vec3& point, const Vec2& u, LightSample& sample) const override;
  std::string_view type_name() const override { return "environment"; }
  // 4π r² times the radiance averaged over the sphere: the power a uniform sky of that radiance
  // sends into the scene's sphere.
  Color power(double scene_radius) const override {
    return mean_radiance_ * (4 * kPi * scene_radius * scene_radius);
  }
  Color emitted_radiance(const Vec3& direction) const override { return environment_.radiance(direction); }
  const Color& mean_radiance() const { return mean_radiance_; }

 private:
  bool from(const Vec2& u, int cells, LightSample& sample) const;
  const Environment& environment_;
  int samples_;
  Color mean_radiance_;
};

}  // namespace candela
