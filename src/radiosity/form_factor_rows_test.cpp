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

// Issue 20, Howell's catalogue through the method's own mesh at its default settings (32
// segments, patches of the scene's size / 8), hemicube and ray cast: a differential area facing a
// sphere (F = (r/h)², a 0.01 square for the point) and a sphere to a coaxial disc facing it
// (F = ½(1 − 1/√(1 + (a/h)²))). Before: the inscribed tessellation of 16 segments gave −2.5 % and
// −3 %, and ray casting 0 (the analytic sphere blocked every ray from its own elements); area-true
// at 16 segments, +1.0 % (the sphere's 16-gon silhouette seen along its pole is larger than the
// mean projected area), at 32 within 0.25 %.
struct CurvedCase {
  std::string name;
  std::string shapes;  // two objects
  double expected;     // F from object `from` to the other
  uint32_t from;
};

double mesh_form_factor(const CurvedCase& c, RadiosityFormFactors method) {
  const auto scene = read_scene_text(
      R"({"format": "candela/1", "camera": {"eye": [5, 0, 0], "target": [0, 0, 0], "width": 8, "height": 8},
        "materials": {"grey": {"kd": 0.5}}, "shapes": [)" +
          c.shapes + "]}",
      "test.json", ".", {}, {});
  RadiositySettings settings;
  settings.form_factors = method;
  const RadiosityMesh mesh = build_radiosity_mesh(*scene, RadiosityMeshSettings{});
  const auto patches = static_cast<Eigen::Index>(mesh.patches.size());
  Eigen::MatrixXd rows(patches, patches);
  std::vector<double> sums(mesh.patches.size());
  fill_patch_form_factor_rows(settings, 7, mesh, rows, sums, nullptr);
  // F from the object: its patches' rows toward the other object, weighted by area (000 eq. 6-4).
  double weighted = 0, area = 0;
  for (Eigen::Index i = 0; i < patches; ++i) {
    const RadiositySurface& from = mesh.patches[static_cast<std::size_t>(i)];
    if (from.object != c.from) continue;
    double to_other = 0;
    for (Eigen::Index j = 0; j < patches; ++j)
      if (mesh.patches[static_cast<std::size_t>(j)].object != c.from) to_other += rows(i, j);
    weighted += from.area * to_other;
    area += from.area;
  }
  return weighted / area;
}

TEST(RadiosityFormFactorRows, CurvedSurfacesMatchHowellAtDefaultSettings) {
  const std::string sphere = R"({"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "grey"}, )";
  const double h = 3, a = 1.5;
  // C-41, coaxial discs of radii r1 = r2 = 1 at distance 1: F = (X − √(X² − 4 R2²/R1²)) / 2 with
  // R = r/h, X = 1 + (1 + R2²)/R1².
  const double X = 1 + (1 + 1.0) / 1.0;
  const std::vector<CurvedCase> cases{
      {"point to sphere",
       sphere +
           R"({"type": "quad", "corner": [-0.005, -0.005, 3], "edge_u": [0, 0.01, 0], "edge_v": [0.01, 0, 0], "material": "grey"})",
       1 / (h * h), 1},
      {"sphere to disc",
       sphere +
           R"({"type": "disc", "center": [0, 0, 3], "normal": [0, 0, -1], "radius": 1.5, "material": "grey"})",
       0.5 * (1 - 1 / std::sqrt(1 + (a / h) * (a / h))), 0},
      {"coaxial discs",
       R"({"type": "disc", "center": [0, 0, 0], "normal": [0, 0, 1], "radius": 1, "material": "grey"},
          {"type": "disc", "center": [0, 0, 1], "normal": [0, 0, -1], "radius": 1, "material": "grey"})",
       0.5 * (X - std::sqrt(X * X - 4)), 0}};
  for (const RadiosityFormFactors method : {RadiosityFormFactors::hemicube, RadiosityFormFactors::ray_cast})
    for (const CurvedCase& c : cases) {
      const double computed = mesh_form_factor(c, method);
      EXPECT_NEAR(computed / c.expected, 1, 0.005)
          << (method == RadiosityFormFactors::hemicube ? "hemicube, " : "ray cast, ") << c.name << ": "
          << computed << " against " << c.expected;
      RecordProperty(
          std::string(method == RadiosityFormFactors::hemicube ? "hemicube " : "ray-cast ") + c.name,
          std::to_string(computed / c.expected - 1));
    }
}

// Issue 20, items 1 and 4: a small isotropic sphere source at the centre of a closed cube — CIE
// 171:2006 case 5.8's geometry — delivers its whole flux to the walls through the element rows the
// solvers gather with: Σ_q A_q Σ_j F_qj E_j = Σ_j A_j E_j. Before: 1.02–1.03× by hemicube (the
// sphere covers a few cells of each wall element's hemicube) and 0.01 % by ray cast (the analytic
// sphere blocked its own elements' rays).
// Issue 20, item 1: a cylinder receiver got 18 % of the hemicube's value by ray casting (its
// elements' rays blocked by the analytic cylinder); the two now agree. No closed form for a
// sphere to a parallel cylinder's side: the cross-check, within 1 %.
TEST(RadiosityFormFactorRows, HemicubeAndRayCastAgreeOnACylinderReceiver) {
  const CurvedCase cylinder{"sphere to cylinder",
                            R"({"type": "sphere", "center": [0, 0, 0], "radius": 0.5, "material": "grey"},
         {"type": "cylinder", "base": [2, -1, 0], "cap": [2, 1, 0], "radius": 0.5, "material": "grey"})",
                            0, 0};
  const double hemicube = mesh_form_factor(cylinder, RadiosityFormFactors::hemicube);
  const double ray_cast = mesh_form_factor(cylinder, RadiosityFormFactors::ray_cast);
  EXPECT_GT(hemicube, 0.02);
  EXPECT_NEAR(ray_cast / hemicube, 1, 0.01) << ray_cast << " against " << hemicube;
  RecordProperty("hemicube", fmt::format("{:.9g}", hemicube));
  RecordProperty("ray-cast", fmt::format("{:.9g}", ray_cast));
}

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
