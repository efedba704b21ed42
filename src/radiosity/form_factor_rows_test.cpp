#include "radiosity/form_factor_rows.h"

#include <fmt/format.h>
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
  fill_element_form_factor_rows(settings, 7, mesh, all_rows(elements), all, sums, nullptr);
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
  fill_element_form_factor_rows(settings, 7, mesh, picked, some, some_sums, nullptr);
  for (const uint32_t q : picked) {
    EXPECT_TRUE(some.row(q) == all.row(q)) << "element " << q;
    EXPECT_EQ(some_sums[q], sums[q]);
  }
  EXPECT_EQ(some_sums[0], -1);  // rows not asked for are left as they are
  EXPECT_EQ(some.row(0).cwiseAbs().sum(), 0.0f);
  // The patch rows: square, each patch's own form factor 0, closed.
  Eigen::MatrixXd patch_rows(static_cast<Eigen::Index>(patches), static_cast<Eigen::Index>(patches));
  std::vector<double> patch_sums(patches);
  fill_patch_form_factor_rows(settings, 7, mesh, patch_rows, patch_sums, nullptr);
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

// A small isotropic sphere source at the centre of a closed cube — CIE
// 171:2006 case 5.8's geometry — delivers its whole flux to the walls through the element rows the
// solvers gather with: Σ_q A_q Σ_j F_qj E_j = Σ_j A_j E_j. Before: 1.02–1.03× by hemicube (the
// sphere covers a few cells of each wall element's hemicube) and 0.01 % by ray cast (the analytic
// sphere blocked its own elements' rays).
TEST(RadiosityFormFactorRows, ASmallSphereSourceInACubeDeliversItsFlux) {
  std::string shapes = testing::closed_cube_shapes(R"({"kd": 0.5})");
  shapes.pop_back();  // the closing bracket
  shapes +=
      R"(, {"type": "sphere", "center": [1, 1, 1], "radius": 0.05, "material": {"kd": 0, "emission": 1}}])";
  const auto scene = read_scene_text(
      R"({"format": "candela/1", "camera": {"eye": [1, 1, 1.9], "target": [1, 1, 0], "fov": 80, "width": 8, "height": 8}, )" +
          shapes + "}",
      "test.json", ".", {}, {});
  // The default hemicube; wall elements of 0.25 (the centroid approximation's own error is +0.5 %
  // at 0.5); the sphere at 16 segments (128 emitting patches: a quarter of the default's time —
  // the area-true mesh emits the sphere's flux at any count).
  RadiosityMeshSettings mesh_settings;
  mesh_settings.segments = 16;
  mesh_settings.patch_size = 0.5;
  mesh_settings.element_size = 0.25;
  const RadiosityMesh mesh = build_radiosity_mesh(*scene, mesh_settings);
  double emitted = 0;
  for (const RadiositySurface& patch : mesh.patches) emitted += patch.area * luminance(patch.emission);
  EXPECT_NEAR(emitted / (4 * kPi * 0.05 * 0.05), 1, 1e-9);  // area-true
  for (const RadiosityFormFactors method : {RadiosityFormFactors::hemicube, RadiosityFormFactors::ray_cast}) {
    RadiositySettings settings;
    settings.form_factors = method;
    const auto elements = mesh.elements.size(), patches = mesh.patches.size();
    ElementToPatch rows(static_cast<Eigen::Index>(elements), static_cast<Eigen::Index>(patches));
    std::vector<double> sums(elements);
    fill_element_form_factor_rows(settings, 7, mesh, all_rows(elements), rows, sums, nullptr);
    double delivered = 0;
    for (std::size_t q = 0; q < elements; ++q) {
      if (!mesh.elements[q].emission.is_black()) continue;  // a wall element
      for (std::size_t j = 0; j < patches; ++j)
        delivered += mesh.elements[q].area *
                     rows(static_cast<Eigen::Index>(q), static_cast<Eigen::Index>(j)) *
                     luminance(mesh.patches[j].emission);
    }
    EXPECT_NEAR(delivered / emitted, 1, 0.005)
        << (method == RadiosityFormFactors::hemicube ? "hemicube" : "ray cast") << ": "
        << delivered / emitted;
    RecordProperty(method == RadiosityFormFactors::hemicube ? "hemicube" : "ray-cast",
                   std::to_string(delivered / emitted));
  }
}

}  // namespace
}  // namespace candela
