#include "radiosity/adaptive_subdivision.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "radiosity/diagnostics.h"
#include "radiosity/solvers.h"
#include "scene/scene_loader.h"

namespace candela {
namespace {

// A 4 × 4 square in z = 0 (one object), meshed into patches of 2 and elements of 1.
struct Square {
  std::unique_ptr<Scene> scene;
  RadiosityMesh mesh;
};

Square square() {
  Square result;
  result.scene = read_scene_text(
      R"({"format": "candela/1", "camera": {"eye": [2, 2, 10], "target": [2, 2, 0], "fov": 40, "width": 8, "height": 8},
          "shapes": [{"type": "quad", "corner": [0, 0, 0], "edge_u": [4, 0, 0], "edge_v": [0, 4, 0], "material": {"kd": 0.5}}]})",
      "test.json", ".", {}, {});
  RadiosityMeshSettings settings;
  settings.patch_size = 2;
  settings.element_size = 1;
  result.mesh = build_radiosity_mesh(*result.scene, settings);
  return result;
}

TEST(RadiosityAdaptiveSubdivision, SplitsBothNeighboursOfASteepStepAndNothingElse) {
  const Square s = square();
  const std::size_t count = s.mesh.elements.size();
  ASSERT_GT(count, 4u);
  std::vector<Color> radiosity(count, Color(1.0));
  radiosity[0] = Color(2.0, 1.0, 1.0);  // a step of 1 in red, half the largest radiosity
  const std::vector<double> sums(count, 1.0);
  const std::vector<std::vector<uint32_t>> neighbours = s.mesh.element_neighbours();
  const std::vector<bool> split = elements_to_split(s.mesh, radiosity, sums, 0.4, 0.0);
  EXPECT_TRUE(split[0]);
  for (std::size_t q = 1; q < count; ++q) {
    const bool neighbour = std::binary_search(neighbours[0].begin(), neighbours[0].end(), q);
    EXPECT_EQ(split[q], neighbour) << "element " << q;
  }
  // A threshold above the step: nothing to split.
  const std::vector<bool> gentle = elements_to_split(s.mesh, radiosity, sums, 0.6, 0.0);
  EXPECT_EQ(std::count(gentle.begin(), gentle.end(), true), 0);
  // Elements at the smallest size are not split.
  const std::vector<bool> small =
      elements_to_split(s.mesh, radiosity, sums, 0.4, longest_edge(s.mesh.elements[0]));
  EXPECT_EQ(std::count(small.begin(), small.end(), true), 0);
  // A hidden element (its row sees nothing) is not compared: its darkness is no gradient.
  std::vector<double> hidden_first = sums;
  hidden_first[0] = 0.5 * kHiddenRowSum;
  const std::vector<bool> hidden = elements_to_split(s.mesh, radiosity, hidden_first, 0.4, 0.0);
  EXPECT_EQ(std::count(hidden.begin(), hidden.end(), true), 0);
}

TEST(RadiosityAdaptiveSubdivision, SplittingCarriesTheRowsOfTheElementsThatStay) {
  Square s = square();
  const std::size_t count = s.mesh.elements.size(), patches = s.mesh.patches.size();
  ElementRows rows{
      std::make_shared<ElementToPatch>(static_cast<Eigen::Index>(count), static_cast<Eigen::Index>(patches)),
      std::vector<double>(count)};
  for (std::size_t q = 0; q < count; ++q) {
    for (std::size_t j = 0; j < patches; ++j)
      (*rows.form_factors)(static_cast<Eigen::Index>(q), static_cast<Eigen::Index>(j)) =
          static_cast<float>(q * 100 + j);
    rows.sums[q] = static_cast<double>(q);
  }
  std::vector<bool> split(count, false);
  split[1] = split[count - 1] = true;
  const RadiositySettings settings;
  const std::vector<uint32_t> new_rows = split_elements_keeping_rows(*s.scene, settings, split, s.mesh, rows);
  ASSERT_EQ(s.mesh.elements.size(), count + 2);
  ASSERT_EQ(new_rows.size(), 4u);  // two halves each
  ASSERT_EQ(static_cast<std::size_t>(rows.form_factors->rows()), count + 2);
  ASSERT_EQ(rows.sums.size(), count + 2);
  // Every element that stayed has its old row and sum: the old index is the row's first value / 100.
  std::vector<bool> seen(count, false);
  for (std::size_t q = 0; q < count + 2; ++q) {
    if (std::find(new_rows.begin(), new_rows.end(), q) != new_rows.end()) continue;
    const double old = rows.sums[q];
    ASSERT_LT(old, static_cast<double>(count));
    seen[static_cast<std::size_t>(old)] = true;
    for (std::size_t j = 0; j < patches; ++j)
      EXPECT_EQ((*rows.form_factors)(static_cast<Eigen::Index>(q), static_cast<Eigen::Index>(j)),
                static_cast<float>(old * 100 + static_cast<double>(j)));
  }
  for (std::size_t q = 0; q < count; ++q) EXPECT_EQ(seen[q], !split[q]) << "old element " << q;
  // Refused when the old and the new rows together exceed the limit.
  RadiositySettings tight;
  tight.memory_limit_mib = 1e-6;
  std::vector<bool> again(s.mesh.elements.size(), false);
  again[0] = true;
  EXPECT_THROW(split_elements_keeping_rows(*s.scene, tight, again, s.mesh, rows), SolverMemoryError);
  EXPECT_EQ(s.mesh.elements.size(), count + 2);  // refused before splitting
}

}  // namespace
}  // namespace candela
