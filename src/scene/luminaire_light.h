// A luminaire of measured photometry (issue 23, item 2): a point source whose intensity in each
// direction is a photometric file's (IES LM-63 or EULUMDAT, io/photometry.h), placed in the scene
// by its position, the direction of its nadir (the photometric axis, γ = 0: where a downlight
// points) and the direction of its C0 plane; C grows counter-clockwise seen from above, looking
// along the nadir (LM-63's and EULUMDAT's type C): with the nadir −y and C0 along +x, C90 is −z.
//
// A direction ω from the luminaire has γ = angle(ω, nadir) and C = atan2(ω·c90, ω·c0); it
// carries I(γ, C) candela, which become the renderer's units by the one efficacy
// (shading/photometric_units.h) in the luminaire's colour; a point at distance d facing ω
// receives I cos θ / d². Its power, by which the path tracer chooses it, is the file's flux.
#pragma once

#include <memory>

#include "io/photometry.h"
#include "scene/light.h"

namespace candela {

class LuminaireLight final : public Light {
 public:
  // nadir and c0: non-zero, not parallel (c0 is made perpendicular to nadir); scale multiplies
  // every candela value; colour: any luminance > 0 (only its chromaticity counts).
  LuminaireLight(std::shared_ptr<const Photometry> photometry, const Vec3& position, const Vec3& nadir,
                 const Vec3& c0, double scale, const Color& colour);
  bool illuminate(const Vec3& point, LightSample& sample) const override;
  std::string_view type_name() const override { return "luminaire"; }
  Color power(double scene_radius) const override;
  // The intensity in candela toward a unit direction from the luminaire.
  double candela_toward(const Vec3& direction) const;

 private:
  std::shared_ptr<const Photometry> photometry_;
  Vec3 position_, nadir_, c0_, c90_;
  double scale_;
  Color per_candela_;  // the radiometric intensity of 1 cd of this colour
  double flux_;        // lumens, the table's × scale
};

}  // namespace candela
