#include "radiosity/form_factor_rows.h"

#include <gtest/gtest.h>

#include <string>

#include "closed_cube.h"
#include "scene/scene_loader.h"

namespace candela {
namespace {

// A closed cube [0, 2]³ of six quads facing inward.
std::unique_ptr<Scene> closed_cube() {
  return read_scene_text(
      R"({"format": "candela/1", "camera": {"eye": [1, 1, 1.9], "target": [1, 1, 0], "fov": 80, "width": 8, "height": 8}, )" +
          testing::closed_cube_shapes(R"({"kd": 0.6})") + "}",
      "test.json", ".", {}, {});
}

RadiosityMesh cube_mesh(const Scene& scene) {
  RadiosityMeshSettings settings;
  settings.patch_size = 1;
  settings.element_size = 0.5;
  return build_radiosity_mesh(scene, settings);
}

void expect_closed_rows(RadiosityFormFactors method) {
  const auto scene = closed_cube();
  const RadiosityMesh mesh = cube_mesh(*scene);
  RadiositySettings settings;
  settings.form_factors = method;
  settings.hemicube_resolution = 60;
  settings.ray_cast_samples = 3;
  const auto elements = mesh.elements.size(), patches = mesh.patches.size();
  ElementToPatch all(static_cast<Eigen::Index>(elements), static_cast<Eigen::Index>(patches));
  std::vector<double> sums(elements);
  fill_element_form_factor_rows(*scene, settings, 7, mesh, all_rows(elements), all, sums, nullptr);
  for (std::size_t q = 0; q < elements; ++q) {
    // 000 eq. 6-6 in a closed cube; nothing to the element's own patch.
    EXPECT_NEAR(sums[q], 1, 0.01) << "element " << q;
    EXPECT_NEAR(all.row(static_cast<Eigen::Index>(q)).cast<double>().sum(), sums[q], 1e-5);
    EXPECT_EQ(all(static_cast<Eigen::Index>(q), mesh.patch_of_element[q]), 0.0f);
  }
  // A row computed alone is the same row: each row by one thread into its own place, with its own
  // random stream.
  ElementToPatch some =
      ElementToPatch::Zero(static_cast<Eigen::Index>(elements), static_cast<Eigen::Index>(patches));
  std::vector<double> some_sums(elements, -1);
  const std::vector<uint32_t> picked{3, static_cast<uint32_t>(elements - 1)};
  fill_element_form_factor_rows(*scene, settings, 7, mesh, picked, some, some_sums, nullptr);
  for (const uint32_t q : picked) {
    EXPECT_TRUE(some.row(q) == all.row(q)) << "element " << q;
    EXPECT_EQ(some_sums[q], sums[q]);
  }
  EXPECT_EQ(some_sums[0], -1);  // rows not asked for are left as they are
  EXPECT_EQ(some.row(0).cwiseAbs().sum(), 0.0f);
  // The patch rows: square, each patch's own form factor 0, closed.
  Eigen::MatrixXd patch_rows(static_cast<Eigen::Index>(patches), static_cast<Eigen::Index>(patches));
  std::vector<double> patch_sums(patches);
  fill_patch_form_factor_rows(*scene, settings, 7, mesh, patch_rows, patch_sums, nullptr);
  for (std::size_t i = 0; i < patches; ++i) {
    EXPECT_NEAR(patch_sums[i], 1, 0.01) << "patch " << i;
    EXPECT_EQ(patch_rows(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i)), 0.0);
  }
}

TEST(RadiosityFormFactorRows, HemicubeRowsOfAClosedCubeSumToOne) {
  expect_closed_rows(RadiosityFormFactors::hemicube);
}

TEST(RadiosityFormFactorRows, RayCastRowsOfAClosedCubeSumToOne) {
  expect_closed_rows(RadiosityFormFactors::ray_cast);
}

}  // namespace
}  // namespace candela
