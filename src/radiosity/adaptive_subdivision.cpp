#include "radiosity/adaptive_subdivision.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "radiosity/diagnostics.h"
#include "radiosity/form_factor_memory.h"

namespace candela {

std::vector<bool> elements_to_split(const RadiosityMesh& mesh, const std::vector<Color>& radiosity,
                                    const std::vector<double>& row_sums, double threshold, double min_size) {
  // Hidden elements (lying against another surface) see nothing: their darkness is no gradient.
  const auto counted = [&](std::size_t q) {
    return mesh.elements[q].emission.is_black() && row_sums[q] >= kHiddenRowSum;
  };
  const std::size_t count = mesh.elements.size();
  double largest = 0;
  for (std::size_t q = 0; q < count; ++q)
    if (counted(q)) largest = std::max({largest, radiosity[q].r, radiosity[q].g, radiosity[q].b});
  std::vector<bool> split(count, false);
  if (!(largest > 0)) return split;
  const double limit = threshold * largest;
  const auto splittable = [&](std::size_t q) { return longest_edge(mesh.elements[q]) > min_size; };
  const std::vector<std::vector<uint32_t>> neighbours = mesh.element_neighbours();
  for (std::size_t q = 0; q < count; ++q) {
    if (!counted(q)) continue;
    for (const uint32_t other : neighbours[q]) {
      if (!counted(other)) continue;
      const Color d = radiosity[q] - radiosity[other];
      if (std::max({std::fabs(d.r), std::fabs(d.g), std::fabs(d.b)}) > limit) {
        if (splittable(q)) split[q] = true;
        if (splittable(other)) split[other] = true;
      }
    }
  }
  return split;
}

std::vector<uint32_t> split_elements_keeping_rows(const Scene& scene, const RadiositySettings& settings,
                                                  const std::vector<bool>& split, RadiosityMesh& mesh,
                                                  ElementRows& rows) {
  const std::size_t patch_count = mesh.patches.size();
  const auto split_count = static_cast<std::size_t>(std::count(split.begin(), split.end(), true));
  // The new elements' rows; the others keep theirs. Both matrices are held while copying.
  const std::size_t new_count = mesh.elements.size() + split_count;
  check_form_factor_memory(
      element_rows_bytes(mesh.elements.size(), patch_count) + element_rows_bytes(new_count, patch_count),
      settings, fmt::format("adaptive subdivision to {} elements", new_count),
      "raise radiosity.subdivision_threshold or radiosity.min_element_size");
  const std::vector<uint32_t> origin = mesh.split_elements(scene, split);
  auto refined = std::make_shared<ElementToPatch>(static_cast<Eigen::Index>(mesh.elements.size()),
                                                  static_cast<Eigen::Index>(patch_count));
  std::vector<uint32_t> new_rows;
  std::vector<double> refined_sums(mesh.elements.size());
  for (std::size_t q = 0; q < origin.size(); ++q) {
    if (split[origin[q]]) {
      new_rows.push_back(static_cast<uint32_t>(q));
    } else {
      refined->row(static_cast<Eigen::Index>(q)) = rows.form_factors->row(origin[q]);
      refined_sums[q] = rows.sums[origin[q]];
    }
  }
  rows.form_factors = std::move(refined);  // the old rows freed before the new are computed
  rows.sums = std::move(refined_sums);
  return new_rows;
}

}  // namespace candela
