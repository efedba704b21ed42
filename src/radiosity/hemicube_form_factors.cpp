#include "radiosity/hemicube_form_factors.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "raster/hemicube_views.h"

namespace candela {

void FormFactorGeometry::validate() const {
  mesh.validate();
  if (element_of_triangle.size() != mesh.triangles.size())
    throw std::invalid_argument("form factor geometry: " + std::to_string(element_of_triangle.size()) +
                                " element ids for " + std::to_string(mesh.triangles.size()) + " triangles");
  if (element_count >= kBackFace)
    throw std::invalid_argument("form factor geometry: " + std::to_string(element_count) +
                                " elements; at most " + std::to_string(kBackFace - 1));
  for (std::size_t t = 0; t < element_of_triangle.size(); ++t)
    if (element_of_triangle[t] >= element_count)
      throw std::invalid_argument("form factor geometry: triangle " + std::to_string(t) +
                                  " belongs to element " + std::to_string(element_of_triangle[t]) + " of " +
                                  std::to_string(element_count));
}

namespace {

std::shared_ptr<const DeltaFormFactors> checked_table(std::shared_ptr<const DeltaFormFactors> table) {
  if (!table) throw std::invalid_argument("hemicube form factors: no delta form factor table");
  return table;
}

double checked_near_fraction(double near_fraction) {
  if (!(near_fraction > 0 && near_fraction < 1))
    throw std::invalid_argument("hemicube form factors: the near plane fraction must lie in (0, 1)");
  return near_fraction;
}

}  // namespace

HemicubeFormFactors::HemicubeFormFactors(int resolution, double near_fraction)
    : HemicubeFormFactors(std::make_shared<const DeltaFormFactors>(resolution), near_fraction) {}

HemicubeFormFactors::HemicubeFormFactors(std::shared_ptr<const DeltaFormFactors> delta_form_factors,
                                         double near_fraction)
    : delta_form_factors_(checked_table(std::move(delta_form_factors))),
      near_fraction_(checked_near_fraction(near_fraction)),
      top_items_(delta_form_factors_->resolution(), delta_form_factors_->resolution()),
      side_items_(delta_form_factors_->resolution(), delta_form_factors_->resolution()),
      delta_row_(static_cast<std::size_t>(delta_form_factors_->resolution())) {
  // raster/hemicube_views.h: on a side face the directions above the surface are the upper
  // half of the image rows.
  side_items_.set_region(0, 0, resolution(), delta_form_factors_->side_rows());
}

void HemicubeFormFactors::compute_row(const FormFactorGeometry& geometry, const Vec3& center,
                                      const Vec3& normal, const Vec3& tangent, uint32_t source_element,
                                      std::vector<double>& row) {
  if (!is_finite(center)) throw std::invalid_argument("hemicube form factors: the centre must be finite");
  const double normal_length = length(normal);
  if (!(normal_length > 0) || !std::isfinite(normal_length))
    throw std::invalid_argument("hemicube form factors: the normal must be finite and non-zero");
  const Vec3 n = normal / normal_length;
  const TriangleMesh& mesh = geometry.mesh;
  if (geometry.element_of_triangle.size() != mesh.triangles.size())
    throw std::invalid_argument(
        "hemicube form factors: " + std::to_string(geometry.element_of_triangle.size()) +
        " element ids for " + std::to_string(mesh.triangles.size()) + " triangles");
  row.assign(geometry.element_count, 0.0);

  // The corners relative to the centre (the view matrices are then built at the origin, and
  // nearby geometry keeps its precision), their heights above the plane through the centre,
  // and the largest distance, which scales the near and far planes.
  const std::size_t corner_count = mesh.positions.size();
  visible_.positions.resize(corner_count);
  corner_heights_.resize(corner_count);
  double reach_squared = 0;
  for (std::size_t i = 0; i < corner_count; ++i) {
    const Vec3 d = mesh.positions[i] - center;
    visible_.positions[i] = d;
    corner_heights_[i] = dot(d, n);
    reach_squared = std::max(reach_squared, dot(d, d));
  }
  // The triangles that may be seen: not the source's, not entirely on or below the plane.
  visible_.triangles.clear();
  visible_elements_.clear();
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const uint32_t element = geometry.element_of_triangle[t];
    const auto& corner = mesh.triangles[t];
    if (element >= geometry.element_count || element >= kBackFace || corner[0] >= corner_count ||
        corner[1] >= corner_count || corner[2] >= corner_count)
      throw std::invalid_argument("hemicube form factors: triangle " + std::to_string(t) +
                                  " has an element id or a corner index out of range");
    if (element == source_element) continue;
    if (std::max({corner_heights_[corner[0]], corner_heights_[corner[1]], corner_heights_[corner[2]]}) <= 0)
      continue;
    // Surfaces are one-sided (000 §6.2: a patch emits and reflects from its front): a triangle
    // whose back faces the point still hides what lies behind it, but passes no energy.
    const Vec3& a = visible_.positions[corner[0]];
    const Vec3 front = cross(visible_.positions[corner[1]] - a, visible_.positions[corner[2]] - a);
    const bool seen_from_front = dot(front, a) < 0;
    // A two-sided surface's back: its twin, facing the point, is drawn in its place (the two
    // would otherwise fight over the same cells).
    if (!seen_from_front && t < geometry.hidden_from_behind.size() && geometry.hidden_from_behind[t])
      continue;
    visible_.triangles.push_back(corner);
    visible_elements_.push_back(seen_from_front ? element : kBackFace);
  }
  const double reach = std::sqrt(reach_squared);
  if (visible_.triangles.empty() || !(reach > 0) || !std::isfinite(reach)) return;

  // Near: a small fraction of the scene's size seen from the centre, so that the patch in the
  // plane through the centre is never drawn; far: beyond every corner.
  const double near = near_fraction_ * reach, far = 2 * reach;
  const int resolution = this->resolution();
  for (const HemicubeFace face : kHemicubeFaces) {
    ItemBuffer& items = face == HemicubeFace::top ? top_items_ : side_items_;
    items.clear();
    items.draw(hemicube_view_projection(Vec3{}, n, tangent, face, near, far), visible_, visible_elements_);
    triangles_drawn_ += visible_.triangles.size();
    // 000 §6.4: F_j = Σ ΔF_q over the cells q where element j is the nearest.
    accumulate(items, face, face == HemicubeFace::top ? resolution : delta_form_factors_->side_rows(),
               row.data());
  }
}

std::vector<double> HemicubeFormFactors::row(const FormFactorGeometry& geometry, const Vec3& center,
                                             const Vec3& normal, const Vec3& tangent,
                                             uint32_t source_element) {
  std::vector<double> result;
  compute_row(geometry, center, normal, tangent, source_element, result);
  return result;
}

void HemicubeFormFactors::accumulate(const ItemBuffer& items, HemicubeFace face, int rows, double* row_out) {
  const int resolution = this->resolution();
  const uint32_t* ids = items.ids().data();
  double* delta = delta_row_.data();
  uint64_t covered = 0;
  for (int image_row = 0; image_row < rows; ++image_row) {
    delta_form_factors_->expand_row(face, image_row, delta);
    const uint32_t* id_row = ids + static_cast<std::size_t>(image_row) * static_cast<std::size_t>(resolution);
    for (int column = 0; column < resolution; ++column) {
      const uint32_t id = id_row[column];
      if (id < kBackFace) {  // neither background nor a back face
        row_out[id] += delta[column];
        ++covered;
      }
    }
  }
  cells_covered_ += covered;
}

double row_sum(std::span<const double> row) {
  double sum = 0;
  for (const double value : row) sum += value;
  return sum;
}

}  // namespace candela
