// An emissive surface of any shape as a light: the primitives of
// one scene object whose material has `emission`, as the local model, the rasterizer and meshless
// η see them — shadow rays to points sampled on the surface — while the path tracer finds the
// same surfaces by their material (integrators/light_sampler.h) and radiosity meshes them as
// emitters. Emission leaves both sides of a surface with radiance E/π per unit of the material's
// `emission` E, as an area light of exitance E does (area_light.h).
//
// The samples: samples × samples cells of [0, 1)², each point u mapped to the surface by the
// shapes' own sampling from the shading point (Shape::sample_from: the cone a sphere subtends, the
// area of a quad or a triangle), a primitive of the object chosen by its area from u.x. Sample k
// carries intensity (E/π) / (samples² · P(primitive) · pdf_ω) so that Σ_k intensity_k cos θ_x is
// the irradiance ∫ (E/π) cos θ_l cos θ_x / d² dA at the point.
#pragma once

#include <string>
#include <vector>

#include "geometry/shape.h"
#include "scene/light.h"

namespace candela {

class SurfaceLight final : public Light {
 public:
  // The shapes that can be sampled (area > 0); throws std::invalid_argument when none can or
  // samples < 1.
  SurfaceLight(std::string object_name, const std::vector<const Shape*>& shapes, const Color& emission,
               int samples);
  bool illuminate(const Vec3& point, LightSample& sample) const override;
  int sample_count() const override { return samples_ * samples_; }
  bool stratified() const override { return true; }
  bool illuminate_sample(const Vec3& point, int index, const Vec2& within,
                         LightSample& sample) const override;
  bool illuminate_random(const Vec3& point, const Vec2& u, LightSample& sample) const override;
  std::string_view type_name() const override { return "surface"; }
  Color power(double) const override { return emission_ * (2 * area_); }  // both sides
  Color emitted_radiance(const Vec3&) const override { return emission_; }

  const std::string& object_name() const { return object_name_; }
  const Color& emission() const { return emission_; }
  double area() const { return area_; }
  // The shapes it samples (those of area > 0), each chosen with probability area / area().
  const std::vector<const Shape*>& shapes() const { return shapes_; }

 private:
  // The light from the point u ∈ [0, 1)² maps to, as one of `cells` equal parts of the surface.
  bool from(const Vec3& point, Vec2 u, int cells, LightSample& sample) const;

  std::string object_name_;
  std::vector<const Shape*> shapes_;
  std::vector<double> cumulative_area_;  // running sums of the shapes' areas, last = area_
  Color emission_;
  int samples_;
  double area_ = 0;
};

}  // namespace candela
