// A rectangular Lambertian area light (direct light by shadow rays, as from point and directional
// lights): the parallelogram corner + s·edge_u + t·edge_v, s, t ∈ [0, 1], emitting
// exitance E (the same unit as a material's `emission`) from its front side (edge_u × edge_v), or
// from both sides.
//
// The irradiance it gives a point x is ∫ (E/π) cos θ_l cos θ_x / d² dA. Sampled in
// samples × samples equal cells (at the centres, or jittered per shading point): sample k at y_k carries
// intensity (E/π) cos θ_l (A/samples²) / d², so that Σ_k intensity_k · cos θ_x is the irradiance —
// the quantity the local model's diffuse term multiplies by kd, as for a point light with
// inverse-square attenuation. The light itself is not seen by camera rays (give it an emissive
// quad to show it).
#pragma once

#include "scene/light.h"

namespace candela {

class AreaLight final : public Light {
 public:
  // Throws std::invalid_argument for parallel or zero edges, or samples < 1.
  AreaLight(const Vec3& corner, const Vec3& edge_u, const Vec3& edge_v, const Color& exitance, int samples,
            bool two_sided);
  bool illuminate(const Vec3& point, LightSample& sample) const override;
  bool stratified() const override { return true; }
  bool illuminate_sample(const Vec3& point, int index, const Vec2& within,
                         LightSample& sample) const override;
  int sample_count() const override { return samples_ * samples_; }
  // A uniform point of the parallelogram carrying the whole area.
  bool illuminate_random(const Vec3& point, const Vec2& u, LightSample& sample) const override;
  std::string_view type_name() const override { return "area"; }
  Color power(double) const override { return exitance_ * (area_ * (two_sided_ ? 2 : 1)); }
  double area() const { return area_; }

 private:
  // The light from a patch of the given area centred at y.
  bool from(const Vec3& point, const Vec3& y, double patch_area, LightSample& sample) const;

  Vec3 corner_, edge_u_, edge_v_, normal_;
  Color exitance_;
  int samples_;
  bool two_sided_;
  double area_;
};

}  // namespace candela
