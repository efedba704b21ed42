// Form factors by ray casting (SPEC §10: "sampled area-to-differential form factors with
// visibility through the accelerator"), the alternative to and cross-check of the hemicube.
//
// From the differential area dA_x at a point x with unit normal n to a planar element A
// (000 eq. 6-2 integrated over A, eq. 6-10 with the visibility H):
//   F_{dA→A} = ∫_A cosθ_x cosθ_y / (π r²) · V(x, y) dA_y
//            ≈ (1/N) Σ_k cosθ_x cosθ_y / (π r_k²) · V(x, y_k) · J(u_k, v_k),
// over N = n × n stratified (jittered) samples (u_k, v_k) of the unit square mapped onto the
// element, J the area density of that map (J = A for a triangle, whose map is area-preserving,
// so the estimator is the familiar (A/N) Σ …; the bilinear map's |∂p/∂u × ∂p/∂v| for a
// quadrilateral). The element-to-element form factor (000 eq. 6-4) averages it over M = m × m
// stratified points x_k of the receiving element, weighted the same way:
//   F_ij = (1/A_i) ∫_{A_i} F_{dA_x→A_j} dA_x ≈ (1/(M A_i)) Σ_k J_i(u_k, v_k) F_{dA_{x_k}→A_j}.
//
// Conventions:
// - Sides: the point (and the `from` element) sees only the hemisphere its normal points into,
//   cosθ_x = max(0, n·ω); the source element is one-sided too, cosθ_y = max(0, −n_y·ω), as the
//   hemicube counts only front faces. An element's front is the side its corners run
//   counter-clockwise around (TriangleMesh's winding).
// - Visibility: V(x, y) = 1 unless `visibility->occluded` reports a hit on the open segment
//   from x to y shortened by offset_fraction · r at both ends (so that the two surfaces the
//   endpoints lie on are not hit); a null accelerator means no occluders.
// - r → 0 (elements that share an edge or touch): the integrand cosθ_x cosθ_y/(π r²) is
//   singular where x meets the source, and the plain estimator's variance is unbounded there.
//   Two inner integrals are offered (RayCastSettings::inner_integral):
//   · analytic_visibility (default): the unoccluded inner integral exactly, by
//     point_to_polygon_form_factor, times the visible fraction of the sampled integrand
//     Σ_k w_k V_k / Σ_k w_k (w_k the unoccluded sample weights). Exact without occluders (a null
//     accelerator skips the samples altogether) and bounded near shared edges; the visible
//     fraction is the only sampled part. When no sample has weight (all skipped or below the
//     horizon) the element is taken as visible.
//   · sampled: the plain estimator above; sample pairs closer than min_distance_fraction × the
//     source's diameter are skipped, which drops the integral over that small disc around x
//     (a bias of the order of min_distance_fraction for edge-sharing elements, none otherwise).
// - Determinism: every jitter comes from the Pcg32 the caller passes (a seeded stream per row or
//   per pair keeps results independent of the thread count).
#pragma once

#include <array>
#include <span>

#include "accel/accelerator.h"
#include "math/pcg32.h"
#include "math/vector.h"

namespace candela {

// A planar triangle or convex quadrilateral, as a source or a receiving element.
class FormFactorElement {
 public:
  // Throws std::invalid_argument for non-finite corners or zero area.
  static FormFactorElement triangle(const Vec3& p0, const Vec3& p1, const Vec3& p2);
  // Throws std::invalid_argument for non-finite corners, zero area, a fourth corner off the
  // plane of the first three (by more than 1e-6 of the diameter) or a quadrilateral that is
  // not strictly convex.
  static FormFactorElement quad(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3);

  std::span<const Vec3> corners() const { return {corners_.data(), static_cast<std::size_t>(corner_count_)}; }
  int corner_count() const { return corner_count_; }
  const Vec3& normal() const { return normal_; }  // unit, the front (counter-clockwise) side
  double area() const { return area_; }
  double diameter() const { return diameter_; }  // the largest corner-to-corner distance
  Vec3 centroid() const;

  // The point at (u, v) ∈ [0, 1]² of the element's parameterisation, and its area density
  // (∫ density du dv = area): a triangle (1 − √u) p0 + √u (1 − v) p1 + √u v p2 (density =
  // area); a quadrilateral bilinear, p0 at (0, 0), p1 at (1, 0), p2 at (1, 1), p3 at (0, 1).
  Vec3 point_at(double u, double v, double& area_density) const;

 private:
  FormFactorElement() = default;
  void finish();  // normal, area, diameter from the corners; throws when degenerate

  std::array<Vec3, 4> corners_{};
  int corner_count_ = 0;
  Vec3 normal_;
  double area_ = 0;
  double diameter_ = 0;
};

enum class InnerIntegral {
  analytic_visibility,  // point_to_polygon_form_factor × the sampled visible fraction
  sampled,              // (1/N) Σ cosθ_x cosθ_y / (π r²) V J, close pairs skipped
};

struct RayCastSettings {
  int source_samples_per_side = 8;    // n: N = n² stratified samples on the source element
  int receiver_samples_per_side = 4;  // m: M = m² stratified points on the receiving element
  InnerIntegral inner_integral = InnerIntegral::analytic_visibility;
  double min_distance_fraction = 1e-3;  // sample pairs closer than this × source diameter are skipped
  double offset_fraction = 1e-5;        // the visibility segment is shortened by this × r at each end
};

// The differential-area-to-polygon form factor of Lambert (1760), in the contour form of
// Hottel and Sarofim (1967):
//   F_{dA→A} = max(0, −(1/2π) Σ_k γ_k n · (R_k × R_{k+1}) / |R_k × R_{k+1}|),
// R_k = p_k − x, γ_k the angle between R_k and R_{k+1}. Exact for any simple planar polygon
// without occluders; the polygon is first clipped to the half-space above x's plane
// (n·(p − x) > 0), so that a polygon crossing the horizon counts only its visible part, and one
// on or below it counts 0. One-sided: the sum is negative when the polygon's front (its corners
// counter-clockwise) faces x, and a polygon seen from behind gives 0. normal need not be unit
// length; throws std::invalid_argument for a zero or non-finite normal.
double point_to_polygon_form_factor(const Vec3& x, const Vec3& normal, std::span<const Vec3> polygon);

// F_{dA_x→A}: from the differential area at x facing normal to the source element, with
// visibility through the accelerator (null: none). See the header comment for the estimator.
// Throws std::invalid_argument for a zero or non-finite normal or sample counts below 1.
double point_to_element_form_factor(const Vec3& x, const Vec3& normal, const FormFactorElement& source,
                                    const Accelerator* visibility, const RayCastSettings& settings,
                                    Pcg32& random);

// F_ij from element `from` (facing its normal) to element `to`, averaged over M points of
// `from`, each with the inner integral of point_to_element_form_factor. Throws like it.
double element_to_element_form_factor(const FormFactorElement& from, const FormFactorElement& to,
                                      const Accelerator* visibility, const RayCastSettings& settings,
                                      Pcg32& random);

}  // namespace candela
