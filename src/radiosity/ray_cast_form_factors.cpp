#include "radiosity/ray_cast_form_factors.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "math/constants.h"
#include "math/ray.h"

namespace candela {

// ---------------------------------------------------------------------------------------------
// Elements

FormFactorElement FormFactorElement::triangle(const Vec3& p0, const Vec3& p1, const Vec3& p2) {
  FormFactorElement element;
  element.corners_ = {p0, p1, p2, Vec3{}};
  element.corner_count_ = 3;
  element.finish();
  return element;
}

FormFactorElement FormFactorElement::quad(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3) {
  FormFactorElement element;
  element.corners_ = {p0, p1, p2, p3};
  element.corner_count_ = 4;
  element.finish();
  // Planar: the fourth corner on the plane of the other three (the normal is Newell's, so
  // measure every corner's distance from the plane through the centroid).
  const Vec3 centre = element.centroid();
  for (const Vec3& corner : element.corners())
    if (std::fabs(dot(corner - centre, element.normal_)) > 1e-6 * element.diameter_)
      throw std::invalid_argument("form factor element: the quadrilateral is not planar");
  // Strictly convex: every pair of consecutive edges turns the same way as the normal.
  for (int k = 0; k < 4; ++k) {
    const Vec3 edge = element.corners_[(k + 1) % 4] - element.corners_[k];
    const Vec3 next = element.corners_[(k + 2) % 4] - element.corners_[(k + 1) % 4];
    if (!(dot(cross(edge, next), element.normal_) > 0))
      throw std::invalid_argument("form factor element: the quadrilateral is not strictly convex");
  }
  return element;
}

void FormFactorElement::finish() {
  for (const Vec3& corner : corners())
    if (!is_finite(corner)) throw std::invalid_argument("form factor element: a corner is not finite");
  // Newell's normal: Σ p_k × p_{k+1} is twice the vector area of the planar polygon (taken
  // relative to p0, which drops the terms of the first and last edges and keeps precision far
  // from the origin).
  Vec3 twice_vector_area;
  for (int k = 1; k + 1 < corner_count_; ++k)
    twice_vector_area += cross(corners_[k] - corners_[0], corners_[k + 1] - corners_[0]);
  const double twice_area = length(twice_vector_area);
  diameter_ = 0;
  for (int i = 0; i < corner_count_; ++i)
    for (int j = i + 1; j < corner_count_; ++j)
      diameter_ = std::max(diameter_, length(corners_[j] - corners_[i]));
  if (!(twice_area > 0) || !std::isfinite(twice_area))
    throw std::invalid_argument("form factor element: zero area");
  area_ = twice_area / 2;
  normal_ = twice_vector_area / twice_area;
}

Vec3 FormFactorElement::centroid() const {
  Vec3 sum;
  for (const Vec3& corner : corners()) sum += corner;
  return sum / corner_count_;
}

Vec3 FormFactorElement::point_at(double u, double v, double& area_density) const {
  if (corner_count_ == 3) {
    // Area-preserving: the square's strata map to triangle pieces of equal area.
    const double s = std::sqrt(u);
    area_density = area_;
    return corners_[0] * (1 - s) + corners_[1] * (s * (1 - v)) + corners_[2] * (s * v);
  }
  const Vec3 &p0 = corners_[0], &p1 = corners_[1], &p2 = corners_[2], &p3 = corners_[3];
  const Vec3 along_u = (p1 - p0) * (1 - v) + (p2 - p3) * v;  // ∂p/∂u
  const Vec3 along_v = (p3 - p0) * (1 - u) + (p2 - p1) * u;  // ∂p/∂v
  area_density = length(cross(along_u, along_v));
  return p0 * ((1 - u) * (1 - v)) + p1 * (u * (1 - v)) + p2 * (u * v) + p3 * ((1 - u) * v);
}

// ---------------------------------------------------------------------------------------------
// The analytic differential-area-to-polygon form factor

namespace {

Vec3 checked_unit_normal(const Vec3& normal, const char* who) {
  const double normal_length = length(normal);
  if (!(normal_length > 0) || !std::isfinite(normal_length))
    throw std::invalid_argument(std::string(who) + ": the normal must be finite and non-zero");
  return normal / normal_length;
}

void check_samples_per_side(int samples_per_side, const char* what) {
  if (samples_per_side < 1)
    throw std::invalid_argument(std::string("ray-cast form factors: ") + what + " must be at least 1, not " +
                                std::to_string(samples_per_side));
}

// Accumulates the contour integral Σ γ_k n·(a × b)/|a × b| of a polygon edge by edge, the
// corners relative to x.
class ContourSum {
 public:
  explicit ContourSum(const Vec3& n) : n_(n) {}
  // The next corner of the (clipped) polygon.
  void add_corner(const Vec3& corner) {
    if (corners_ == 0) {
      first_ = corner;
    } else {
      add_edge(previous_, corner);
    }
    previous_ = corner;
    ++corners_;
  }
  double close() {
    if (corners_ >= 2) add_edge(previous_, first_);
    return sum_;
  }

 private:
  void add_edge(const Vec3& a, const Vec3& b) {
    const Vec3 c = cross(a, b);
    const double c_length = length(c);
    // a and b on one line through x: the edge subtends no solid angle.
    if (!(c_length > 0)) return;
    // γ, the angle between a and b (atan2 keeps it accurate near 0 and π).
    const double gamma = std::atan2(c_length, dot(a, b));
    sum_ += gamma * dot(n_, c) / c_length;
  }

  Vec3 n_;
  Vec3 first_, previous_;
  int corners_ = 0;
  double sum_ = 0;
};

}  // namespace

double point_to_polygon_form_factor(const Vec3& x, const Vec3& normal, std::span<const Vec3> polygon) {
  const Vec3 n = checked_unit_normal(normal, "point-to-polygon form factor");
  const std::size_t count = polygon.size();
  if (count < 3) return 0.0;
  // Sutherland–Hodgman against the plane n·(p − x) > 0, the clipped corners fed straight into
  // the contour sum (no storage): for each edge p → q, p if inside, then the crossing if the
  // edge crosses the plane.
  ContourSum contour(n);
  for (std::size_t k = 0; k < count; ++k) {
    const Vec3 p = polygon[k] - x, q = polygon[(k + 1) % count] - x;
    const double hp = dot(n, p), hq = dot(n, q);
    const bool p_inside = hp > 0, q_inside = hq > 0;
    if (p_inside) contour.add_corner(p);
    if (p_inside != q_inside) contour.add_corner(p + (q - p) * (hp / (hp - hq)));
  }
  // Hottel and Sarofim's contour form of Lambert's polygon formula; the sum is negative when the
  // polygon winds counter-clockwise around a normal toward x (its front faces x). Surfaces are
  // one-sided: a polygon seen from behind passes nothing.
  return std::max(0.0, -contour.close()) / (2 * kPi);
}

// ---------------------------------------------------------------------------------------------
// Sampled form factors

namespace {

// The sampled integrand over the source from one point: the unoccluded weight Σ w_k and the
// visible one Σ w_k V_k, both already divided by N.
struct SampledIntegral {
  double unoccluded = 0;
  double visible = 0;
};

SampledIntegral sample_source(const Vec3& x, const Vec3& n, const FormFactorElement& source,
                              const Accelerator* visibility, const RayCastSettings& settings, Pcg32& random) {
  const int side = settings.source_samples_per_side;
  const double min_distance = settings.min_distance_fraction * source.diameter();
  const double min_distance_squared = min_distance * min_distance;
  SampledIntegral result;
  for (int i = 0; i < side; ++i) {
    for (int j = 0; j < side; ++j) {
      // One jittered sample per stratum of the unit square.
      const double u = (i + random.next_double()) / side, v = (j + random.next_double()) / side;
      double area_density = 0;
      const Vec3 y = source.point_at(u, v, area_density);
      const Vec3 d = y - x;
      const double r_squared = dot(d, d);
      // r → 0 guard: the pair is skipped (see the header).
      if (!(r_squared > min_distance_squared) || !(r_squared > 0)) continue;
      const double r = std::sqrt(r_squared);
      const Vec3 omega = d / r;
      const double cos_x = dot(n, omega);
      if (!(cos_x > 0)) continue;  // below the receiving point's horizon
      // One-sided: a source seen from behind sends nothing toward x.
      const double cos_y = -dot(source.normal(), omega);
      if (!(cos_y > 0)) continue;
      // 000 eq. 6-2: cosφ_i cosφ_j / (π R²) dA, with dA = J du dv.
      const double weight = cos_x * cos_y / (kPi * r_squared) * area_density;
      result.unoccluded += weight;
      if (visibility) {
        const double offset = settings.offset_fraction * r;
        Ray ray;
        ray.origin = x;
        ray.direction = omega;
        ray.t_min = offset;
        ray.t_max = r - offset;
        if (visibility->occluded(ray)) continue;  // 000 eq. 6-4: H = 0
      }
      result.visible += weight;
    }
  }
  const double samples = static_cast<double>(side) * side;
  result.unoccluded /= samples;
  result.visible /= samples;
  return result;
}

double point_to_element_unit_normal(const Vec3& x, const Vec3& n, const FormFactorElement& source,
                                    const Accelerator* visibility, const RayCastSettings& settings,
                                    Pcg32& random) {
  if (settings.inner_integral == InnerIntegral::sampled)
    return sample_source(x, n, source, visibility, settings, random).visible;
  const double unoccluded = point_to_polygon_form_factor(x, n, source.corners());
  if (!visibility || unoccluded == 0) return unoccluded;
  const SampledIntegral sampled = sample_source(x, n, source, visibility, settings, random);
  if (!(sampled.unoccluded > 0)) return unoccluded;  // no sample to judge by: taken as visible
  return unoccluded * (sampled.visible / sampled.unoccluded);
}

}  // namespace

double point_to_element_form_factor(const Vec3& x, const Vec3& normal, const FormFactorElement& source,
                                    const Accelerator* visibility, const RayCastSettings& settings,
                                    Pcg32& random) {
  const Vec3 n = checked_unit_normal(normal, "point-to-element form factor");
  check_samples_per_side(settings.source_samples_per_side, "source samples per side");
  return point_to_element_unit_normal(x, n, source, visibility, settings, random);
}

double element_to_element_form_factor(const FormFactorElement& from, const FormFactorElement& to,
                                      const Accelerator* visibility, const RayCastSettings& settings,
                                      Pcg32& random) {
  check_samples_per_side(settings.source_samples_per_side, "source samples per side");
  check_samples_per_side(settings.receiver_samples_per_side, "receiver samples per side");
  const int side = settings.receiver_samples_per_side;
  double sum = 0;
  for (int i = 0; i < side; ++i) {
    for (int j = 0; j < side; ++j) {
      const double u = (i + random.next_double()) / side, v = (j + random.next_double()) / side;
      double area_density = 0;
      const Vec3 x = from.point_at(u, v, area_density);
      // 000 eq. 6-4: F_ij = (1/A_i) ∫_{A_i} F_{dA_x→A_j} dA_x, with dA_x = J du dv.
      sum += area_density * point_to_element_unit_normal(x, from.normal(), to, visibility, settings, random);
    }
  }
  return sum / (static_cast<double>(side) * side * from.area());
}

}  // namespace candela
