// A luminaire of measured photometry: a point source whose intensity in each
// direction is a photometric file's (IES LM-63 or EULUMDAT, io/photometry.h), placed in the scene
// by its position, the direction of its nadir (the photometric axis, γ = 0: where a downlight
// points) and the direction of its C0 plane; C grows counter-clockwise seen from above, looking
// along the nadir (LM-63's and EULUMDAT's type C): with the nadir −y and C0 along +x, C90 is −z.
//
// A direction ω from the luminaire has γ = angle(ω, nadir) and C = atan2(ω·c90, ω·c0); it
// carries I(γ, C) candela, which become the renderer's units by the one efficacy
// (shading/photometric_units.h) in the luminaire's colour; a point at distance d facing ω
// receives I cos θ / d². Its power, by which the path tracer chooses it, is the file's flux.
//
// An area luminaire (a "size", width along C0 and length along C90, centred on the position and
// across the nadir): the file's distribution leaves every point of that rectangle, each carrying
// I(γ, C) / (its share of the area) — a Lambertian file (I0 cos γ) over a side a is a Lambertian
// emitter of luminance I0/a² — near the luminaire the light of a large opening, not of its centre.
// Its samples × samples strata for the methods that take a light's fixed samples, one random
// point for the path tracer; no ray can hit it (as the `area` light).
#pragma once

#include <memory>

#include "io/photometry.h"
#include "scene/light.h"

namespace candela {

class LuminaireLight final : public Light {
 public:
  // nadir and c0: non-zero, not parallel (c0 is made perpendicular to nadir); scale multiplies
  // every candela value; colour: any luminance > 0 (only its chromaticity counts).
  // width (along C0), depth (along C90) >= 0 (both 0: a point); samples >= 1, per side of an area's strata.
  LuminaireLight(std::shared_ptr<const Photometry> photometry, const Vec3& position, const Vec3& nadir,
                 const Vec3& c0, double scale, const Color& colour, double width = 0, double depth = 0,
                 int samples = 1);
  bool illuminate(const Vec3& point, LightSample& sample) const override;
  int sample_count() const override { return samples_ * samples_; }
  bool stratified() const override { return true; }
  bool illuminate_sample(const Vec3& point, int index, const Vec2& within,
                         LightSample& sample) const override;
  bool illuminate_random(const Vec3& point, const Vec2& u, LightSample& sample) const override;
  std::string_view type_name() const override { return "luminaire"; }
  Color power(double scene_radius) const override;
  // The intensity in candela toward a unit direction from the luminaire.
  double candela_toward(const Vec3& direction) const;

 private:
  std::shared_ptr<const Photometry> photometry_;
  Vec3 position_, nadir_, c0_, c90_;
  double scale_;
  Color per_candela_;            // the radiometric intensity of 1 cd of this colour
  double flux_;                  // lumens, the table's × scale
  Vec3 across_c0_, across_c90_;  // the area's full edges (zero for a point)
  bool area_ = false;            // an area luminaire (else a point)
  int samples_ = 1;

  // The light from the point of the area at u ∈ [0, 1)² (the centre for a point), × share.
  bool illuminate_from(const Vec2& u, const Vec3& point, double share, LightSample& sample) const;
};

}  // namespace candela
