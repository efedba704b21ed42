// Issue 9 item 2, the furnace: inside a closed diffuse enclosure of albedo ρ whose walls emit E,
// every surface shows E/(1 − ρ) (SPEC §13) — the path tracer within 1 % by a Student's t-test,
// and every other method that can render it (radiosity, meshless). Local, Whitted and the raster
// method have no interreflection, so they cannot.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "closed_cube.h"
#include "integrators/scene_loading.h"
#include "render_support.h"

namespace candela {
namespace {

// ρ per channel and E: E/(1 − ρ) = (2, 3.333…, 5).
const Color kAlbedo(0.5, 0.7, 0.8);
const Color kExpected(2.0, 1.0 / 0.3, 5.0);

std::string material_json() {
  return R"({"kd": [0.5, 0.7, 0.8], "emission": 1})";
}

// The camera at the centre of a closed sphere of radius 2.
std::unique_ptr<Scene> sphere_furnace(const std::string& method, const std::string& settings) {
  return load_scene_text(R"({"format": "candela/1",
    "camera": {"eye": [0.1, 0.2, 0], "target": [0, 0, -1], "fov": 70, "width": 16, "height": 16},
    "render": {"method": ")" +
                             method + R"("}, )" + settings + R"(
    "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 2, "material": )" +
                             material_json() + R"(}]})",
                         "sphere-furnace.json", ".");
}

// The camera inside a closed cube of six quads facing in (classic radiosity's patches are one-sided).
std::unique_ptr<Scene> cube_furnace(const std::string& method, const std::string& settings) {
  return load_scene_text(R"({"format": "candela/1",
    "camera": {"eye": [1, 1.1, 1.7], "target": [0.9, 0.8, 0], "fov": 80, "width": 16, "height": 16},
    "render": {"method": ")" +
                             method + R"("}, )" + settings + testing::closed_cube_shapes(material_json()) +
                             "}",
                         "cube-furnace.json", ".");
}

// Student's t-test of H0: the pixels' mean is `expected`, at the 1 % level (two-sided), plus the
// issue's 1 % bound on the mean itself. Every pixel is an independent estimate (its own random
// stream), n = 256 pixels: t_{0.995, 255} = 2.596.
void expect_furnace_mean(const Film& film, int channel, double expected, const std::string& label) {
  const auto n = static_cast<double>(film.width() * film.height());
  double sum = 0, sum_squares = 0;
  for (const Color& c : film.pixels()) {
    sum += c[channel];
    sum_squares += c[channel] * c[channel];
  }
  const double mean = sum / n;
  const double variance = std::max(0.0, (sum_squares - n * mean * mean) / (n - 1));
  // A floor of 1e-6 relative: an estimator without variance (one bounce, area sampling) still
  // carries the ray offsets' bias of ~1e-7.
  const double standard_error = std::sqrt(variance / n) + 1e-6 * expected;
  const double t = standard_error > 0 ? (mean - expected) / standard_error : 0;
  EXPECT_LT(std::fabs(t), 2.596) << label << " channel " << channel << ": mean " << mean << " ± "
                                 << standard_error;
  EXPECT_LT(std::fabs(mean - expected), 0.01 * expected)
      << label << " channel " << channel << ": mean " << mean;
}

TEST(Furnace, PathTracerGivesEOverOneMinusRhoInASphere) {
  const auto scene = sphere_furnace("path", R"("path": {"spp": 32},)");
  RunStatistics statistics;
  const Film film = testing::render_scene(*scene, "path", 2, statistics);
  for (int c = 0; c < 3; ++c) expect_furnace_mean(film, c, kExpected[c], "path, sphere");
  EXPECT_EQ(statistics.extra["path"]["spp"], 32);
}

TEST(Furnace, PathTracerGivesEOverOneMinusRhoInACube) {
  // ρ = 0.8 makes long paths: Russian roulette's variance needs more samples than the sphere.
  const auto scene = cube_furnace("path", R"("path": {"spp": 128},)");
  const Film film = testing::render_scene(*scene, "path", 2);
  for (int c = 0; c < 3; ++c) expect_furnace_mean(film, c, kExpected[c], "path, cube");
}

// Without next-event estimation paying its way the furnace would still converge; with MIS
// weights that do not sum to one it would not. Bounces limited to 1: E + ρE exactly in the mean.
TEST(Furnace, OneBounceGivesEPlusRhoE) {
  const auto scene = sphere_furnace("path", R"("path": {"spp": 32, "max_depth": 1},)");
  const Film film = testing::render_scene(*scene, "path", 2);
  for (int c = 0; c < 3; ++c) expect_furnace_mean(film, c, 1 + kAlbedo[c], "path, one bounce");
}

TEST(Furnace, RadiosityGivesEOverOneMinusRhoInACube) {
  for (const std::string form_factors : {"hemicube", "ray-cast"}) {
    const auto scene = cube_furnace(
        "radiosity",
        R"("radiosity": {"solver": "gauss-seidel", "threshold": 1e-6, "patch_size": 0.5, "form_factors": ")" +
            form_factors + R"("},)");
    const Film film = testing::render_scene(*scene, "radiosity", 2);
    for (const Color& pixel : film.pixels())
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(pixel[c], kExpected[c], 0.01 * kExpected[c]) << form_factors;
  }
}

TEST(Furnace, MeshlessGivesEOverOneMinusRhoInASphere) {
  // The radial basis cannot: it is no partition of unity (Σφ ≈ 1.4, docs/methods/meshless.md), so
  // a constant field comes out scaled — the thesis's reason for the normalized basis.
  for (const std::string basis : {"normalized", "shepard"}) {
    const auto scene = sphere_furnace(
        "meshless", R"("meshless": {"basis": ")" + basis + R"(", "spacing": 0.3, "grid": 24, "rounds": 6},)");
    const Film film = testing::render_scene(*scene, "meshless", 2);
    // Not 1 %: the effective areas are integrated over the tessellated sphere, a few tenths of a
    // percent short, so the rows of S sum to s ≈ 0.996 and B = E/(1 − ρs) falls short by
    // ρ(1 − s)/(1 − ρ) — 1.5 % at ρ = 0.8 (measured 2.3 % at spacing 0.3, 1.5 % at 0.2).
    const double tolerance = 0.03;
    for (const Color& pixel : film.pixels())
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(pixel[c], kExpected[c], tolerance * kExpected[c]) << basis;
  }
}

}  // namespace
}  // namespace candela
