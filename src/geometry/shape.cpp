#include "geometry/shape.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace candela {

void Shape::tessellate(const TessellationSettings&, TriangleMesh&) const {
  throw std::logic_error("shape \"" + std::string(type_name()) + "\" cannot be tessellated");
}

bool Shape::sample_area(const Vec2&, SurfaceSample&) const {
  return false;
}

double Shape::pdf_area(const SurfaceHit&) const {
  return 0;
}

namespace {

// Area density → solid-angle density about reference: pdf_area · d² / |cos θ_light|; 0 when the
// point coincides with reference or is seen edge-on.
double area_to_solid_angle(double pdf_area, const Vec3& reference, const Vec3& position, const Vec3& normal) {
  const Vec3 to_point = position - reference;
  const double distance_squared = length_squared(to_point);
  if (!(distance_squared > 0) || !(pdf_area > 0)) return 0;
  const double cos_light = std::fabs(dot(normal, to_point)) / std::sqrt(distance_squared);
  if (!(cos_light > 0)) return 0;
  const double pdf = pdf_area * distance_squared / cos_light;
  return std::isfinite(pdf) ? pdf : 0;
}

}  // namespace

bool Shape::sample_from(const Vec3& reference, const Vec2& u, SurfaceSample& sample) const {
  if (!sample_area(u, sample)) return false;
  sample.pdf = area_to_solid_angle(sample.pdf, reference, sample.position, sample.normal);
  return sample.pdf > 0;
}

double Shape::pdf_from(const Vec3& reference, const SurfaceHit& hit) const {
  return area_to_solid_angle(pdf_area(hit), reference, hit.position, hit.geometric_normal);
}

}  // namespace candela
