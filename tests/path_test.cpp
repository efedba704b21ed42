// The path-traced reference (SPEC §12) against analytic values, across thread
// counts, and through a checkpoint.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "integrators/light_sampler.h"
#include "integrators/pass_checkpoint.h"
#include "integrators/path_tracer.h"
#include "integrators/scene_loading.h"
#include "radiosity/configuration_factors.h"
#include "render_support.h"
#include "scratch_directory.h"
#include "shading/bsdf.h"
#include "shading/fresnel.h"

namespace candela {
namespace {

std::unique_ptr<Scene> path_scene(const std::string& body) {
  return load_scene_text(R"({"format": "candela/1", )" + body + "}", "path-test.json", ".");
}

// The mean of n independent estimates and its standard error.
struct Estimate {
  Color mean, error;
};

template <typename Sample>
Estimate estimate(int n, Sample sample) {
  Color sum, squares;
  for (int i = 0; i < n; ++i) {
    const Color v = sample(i);
    sum += v;
    squares += v * v;
  }
  Estimate e;
  e.mean = sum / n;
  for (int c = 0; c < 3; ++c)
    e.error[c] = std::sqrt(std::max(0.0, squares[c] / n - e.mean[c] * e.mean[c]) / (n - 1));
  return e;
}

// Irradiance at (point, normal) by path_irradiance, n independent streams.
Estimate irradiance(const Scene& scene, const Vec3& point, const Vec3& normal, int n,
                    const PathSettings& settings = {}) {
  const LightSampler lights(scene);
  RayCounts rays;
  return estimate(n, [&](int i) {
    Pcg32 rng = path_pixel_rng(7, static_cast<uint64_t>(i), 0, 0);
    return path_irradiance(scene, settings, lights, point, normal, rng, rays);
  });
}

void expect_estimate(const Estimate& e, double expected, const std::string& label) {
  for (int c = 0; c < 3; ++c) {
    // Four standard errors (a false alarm once in 16,000 runs; the streams are fixed anyway)
    // and a 1 % bound.
    EXPECT_NEAR(e.mean[c], expected, 4 * e.error[c] + 1e-12) << label;
    EXPECT_NEAR(e.mean[c], expected, 0.01 * expected) << label;
  }
}

// A point one unit below the centre of an emitting unit square (E = 3, facing down): the
// irradiance is E × the point-to-area form factor, 4 corner rectangles of 0.5 × 0.5.
TEST(PathTracer, IrradianceUnderAnEmittingSquareIsEmissionTimesTheFormFactor) {
  const auto scene = path_scene(
      R"("camera": {"eye": [0, -3, 0], "target": [0, 0, 0], "up": [0, 0, 1], "width": 4, "height": 4},
    "shapes": [{"type": "quad", "corner": [-0.5, 1, -0.5], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1],
                "material": {"kd": 0, "emission": 3}}])");
  const double expected = 3 * 4 * point_to_parallel_rectangle_corner(0.5, 0.5, 1);  // 3 × 0.23946
  expect_estimate(irradiance(*scene, {0, 0, 0}, {0, 1, 0}, 4000), expected, "square");
}

// The same square as two mesh triangles, and as a unit quad placed by a transform (rotated and
// scaled): the emitter sampling of mesh triangles and transformed shapes gives the same irradiance.
TEST(PathTracer, TrianglesAndTransformedQuadsEmitLikeTheSquare) {
  const double expected = 3 * 4 * point_to_parallel_rectangle_corner(0.5, 0.5, 1);
  const auto triangles = path_scene(
      R"("camera": {"eye": [0, -3, 0], "target": [0, 0, 0], "up": [0, 0, 1], "width": 4, "height": 4},
    "materials": {"lamp": {"kd": 0, "emission": 3}},
    "shapes": [{"type": "triangle", "vertices": [[-0.5, 1, -0.5], [0.5, 1, -0.5], [0.5, 1, 0.5]], "material": "lamp"},
               {"type": "triangle", "vertices": [[-0.5, 1, -0.5], [0.5, 1, 0.5], [-0.5, 1, 0.5]], "material": "lamp"}])");
  expect_estimate(irradiance(*triangles, {0, 0, 0}, {0, 1, 0}, 4000), expected, "triangles");
  const auto transformed = path_scene(
      R"("camera": {"eye": [0, -3, 0], "target": [0, 0, 0], "up": [0, 0, 1], "width": 4, "height": 4},
    "shapes": [{"type": "quad", "corner": [0, 0, 0], "edge_u": [1, 0, 0], "edge_v": [0, 1, 0],
                "transform": [{"scale": [2, 0.5, 1]}, {"translate": [-1, -0.25, 0]}, {"rotate": {"angle": 90, "axis": [1, 0, 0]}},
                              {"translate": [0, 1, 0]}],
                "material": {"kd": 0, "emission": 3}}])");
  // A 2 × 0.5 rectangle one unit up, centred: 4 corner rectangles of 1 × 0.25.
  expect_estimate(irradiance(*transformed, {0, 0, 0}, {0, 1, 0}, 4000),
                  3 * 4 * point_to_parallel_rectangle_corner(1, 0.25, 1), "transformed quad");
}

// Coaxial disc of radius r at height h: F = r²/(h² + r²); a sphere of radius r whose centre lies
// at distance d on the normal: F = (r/d)².
TEST(PathTracer, IrradianceFromADiscAndASphereMatchesTheirFormFactors) {
  const auto disc = path_scene(
      R"("camera": {"eye": [0, -3, 0], "target": [0, 0, 0], "up": [0, 0, 1], "width": 4, "height": 4},
    "shapes": [{"type": "disc", "center": [0, 2, 0], "normal": [0, -1, 0], "radius": 1.5,
                "material": {"kd": 0, "emission": 2}}])");
  expect_estimate(irradiance(*disc, {0, 0, 0}, {0, 1, 0}, 4000), 2 * 2.25 / (4 + 2.25), "disc");
  const auto sphere = path_scene(
      R"("camera": {"eye": [0, -3, 0], "target": [0, 0, 0], "up": [0, 0, 1], "width": 4, "height": 4},
    "shapes": [{"type": "sphere", "center": [0, 3, 0], "radius": 1, "material": {"kd": 0, "emission": 2}}])");
  expect_estimate(irradiance(*sphere, {0, 0, 0}, {0, 1, 0}, 4000), 2.0 / 9.0, "sphere");
}

// Under a uniform sky of 1 an unoccluded point facing up receives irradiance 1 (display units:
// the sky's value), and a floor of ρ = 0.5 shows 0.5.
TEST(PathTracer, UniformSkyGivesUnitIrradianceAndTheFloorItsAlbedo) {
  const auto scene =
      path_scene(R"("camera": {"eye": [0, 3, 0], "target": [0, 0, 0], "up": [0, 0, -1], "fov": 40,
      "width": 16, "height": 16},
    "environment": {"type": "constant", "color": [1, 1, 1]}, "path": {"spp": 16},
    "shapes": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": {"kd": 0.5}}])");
  expect_estimate(irradiance(*scene, {0, 0.5, 0}, {0, 1, 0}, 2000), 1.0, "sky");
  const Film film = testing::render_scene(*scene, "path");
  const Estimate floor = estimate(film.width() * film.height(), [&](int i) { return film.pixels()[i]; });
  expect_estimate(floor, 0.5, "floor");
}

// CIE 171 5.12/5.13's glazing: a thin pane (`"thin": true`, kt its transmissivity)
// reflects R(θ) and lets T(θ) through without bending it (shading/fresnel.h). Under a uniform sky
// of 1 over a black ground a point below a pane receives 2 ∫ T(c) c dc; below two panes, whose
// light also bounces between them, 2 ∫ T² / (1 − R²) c dc — here two of CIE 171's 6 mm clear glass
// (n = 1.52, transmissivity 0.95712), which absorbs. The pane is crossed at any depth: with
// max_depth 1 the light through it is all still there. Without the ground (the sky all round) a
// lossless pane vanishes: what it reflects of the sky below makes up for what it keeps from above.
TEST(PathTracer, ThinPanesPassTheirFresnelTransmittanceOfTheSky) {
  double single = 0, two = 0;
  constexpr int kSteps = 20000;
  for (int k = 0; k < kSteps; ++k) {
    const double c = (k + 0.5) / kSteps;
    single += 2 * thin_sheet(c, 1.5).transmittance * c / kSteps;
    const SheetSplit glass = thin_sheet(c, 1.52, 0.95712);
    const double R = glass.reflectance, T = glass.transmittance;
    two += 2 * T * T / (1 - R * R) * c / kSteps;
  }
  // A clear pane's diffuse (hemispherical) transmittance: 0.85 at n = 1.5, 0.92 at normal incidence.
  EXPECT_NEAR(single, 0.851, 0.001);
  EXPECT_LT(two, 0.8 * single);
  const std::string pane = R"({"type": "plane", "point": [0, 1, 0], "normal": [0, 1, 0],
      "material": {"kd": 0, "kt": 1, "ior": 1.5, "thin": true}})";
  const std::string glass = R"("material": {"kd": 0, "kt": 0.95712, "ior": 1.52, "thin": true}})";
  const std::string sky = R"("camera": {"eye": [0, 3, 0], "target": [0, 0, 0], "up": [0, 0, -1]},
    "environment": {"type": "constant", "color": [1, 1, 1]}, )";
  const std::string ground =
      R"({"type": "plane", "point": [0, -0.5, 0], "normal": [0, 1, 0], "material": {"kd": 0}}, )";
  expect_estimate(irradiance(*path_scene(sky + R"("shapes": [)" + pane + "]"), {0, 0, 0}, {0, 1, 0}, 4000),
                  1.0, "no ground");
  const auto one_pane = path_scene(sky + R"("shapes": [)" + ground + pane + "]");
  expect_estimate(irradiance(*one_pane, {0, 0, 0}, {0, 1, 0}, 16000), single, "one pane");
  PathSettings one_bounce;
  one_bounce.max_depth = 1;
  expect_estimate(irradiance(*one_pane, {0, 0, 0}, {0, 1, 0}, 16000, one_bounce), single, "max_depth 1");
  const auto two_panes = path_scene(
      sky + R"("shapes": [)" + ground + R"({"type": "plane", "point": [0, 1, 0], "normal": [0, 1, 0], )" +
      glass + R"(, {"type": "plane", "point": [0, 1.2, 0], "normal": [0, -1, 0], )" + glass + "]");
  expect_estimate(irradiance(*two_panes, {0, 0, 0}, {0, 1, 0}, 16000), two, "two panes");
}

// Emitters are chosen in proportion to their power. Eleven point lights at the
// same distance and angle from a point — one of intensity 100, ten of 1 — give it irradiance in
// proportion to their power, so choosing by power makes every estimate the exact sum (no noise),
// where a uniform choice would give a relative standard deviation of 2.8 per sample.
TEST(PathTracer, ChoosingEmittersByPowerRemovesTheNoiseOfOneBrightAndManyDimLights) {
  std::string lights;
  for (int i = 0; i < 11; ++i) {
    const double angle = 2 * kPi * i / 11;
    lights += (i ? ", " : "") + std::string(R"({"type": "point", "position": [)") +
              std::to_string(std::cos(angle)) + ", 1, " + std::to_string(std::sin(angle)) +
              "], \"intensity\": " + (i == 0 ? "100" : "1") + "}";
  }
  const auto scene = path_scene(R"("camera": {"eye": [0, 3, 3], "target": [0, 0, 0], "width": 4, "height": 4},
    "lights": [)" + lights + "]");
  const LightSampler sampler(*scene);
  EXPECT_NEAR(sampler.probability(0), 100.0 / 110.0, 1e-12);
  EXPECT_NEAR(sampler.probability(1), 1.0 / 110.0, 1e-12);
  const Estimate e = irradiance(*scene, {0, 0, 0}, {0, 1, 0}, 400);
  // A point light's intensity is the irradiance it gives at normal incidence (path_tracer.h):
  // E = Σ I cos θ, cos θ = 1/√2.
  const double expected = 110 / std::sqrt(2.0);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(e.mean[c], expected, 1e-6 * expected);
    EXPECT_LT(e.error[c], 1e-6 * expected);
  }
}

// One rule for every method: the background colours rays that leave the scene from the
// camera (directly, in mirrors, through glass) and lights nothing. Under a white background the
// same floor is black, while a mirror shows the background.
TEST(PathTracer, TheBackgroundLightsNothingButIsSeenInMirrors) {
  const auto floor_only =
      path_scene(R"("camera": {"eye": [0, 3, 0], "target": [0, 0, 0], "up": [0, 0, -1], "fov": 40,
      "width": 8, "height": 8},
    "background": [1, 1, 1], "path": {"spp": 4},
    "shapes": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": {"kd": 0.5}}])");
  const Film dark = testing::render_scene(*floor_only, "path");
  for (const Color& pixel : dark.pixels()) ASSERT_EQ(pixel, Color(0));
  const auto mirror =
      path_scene(R"("camera": {"eye": [0, 3, 0], "target": [0, 0, 0], "up": [0, 0, -1], "fov": 40,
      "width": 8, "height": 8},
    "background": [0.25, 0.5, 1], "path": {"spp": 4},
    "shapes": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": {"kd": 0, "kr": 1}}])");
  const Film seen = testing::render_scene(*mirror, "path");
  for (const Color& pixel : seen.pixels()) {
    EXPECT_NEAR(pixel.r, 0.25, 1e-9);
    EXPECT_NEAR(pixel.b, 1.0, 1e-9);
  }
}

// Under the latitude-longitude sky of scenes/textures/sky.exr, the irradiance of a point facing up
// (or tilted) is ∫ L cos θ dω over its hemisphere, L = the map's value / π (the map holds display
// units, π × radiance, as the background color does) — here by a dense midpoint quadrature of the
// map's own radiance(), against the path tracer's importance-sampled environment with MIS.
TEST(PathTracer, IrradianceUnderAnEnvironmentMapMatchesQuadrature) {
  const auto scene = load_scene_text(R"({"format": "candela/1",
    "camera": {"eye": [0, 0, 3], "target": [0, 0, 0], "width": 4, "height": 4},
    "environment": {"type": "equirectangular", "file": "textures/sky.exr", "up": [0, 1, 0], "forward": [0, 0, -1]},
    "shapes": [{"type": "sphere", "center": [0, -100, 0], "radius": 1, "material": {"kd": 0.5}}]})",
                                     "sky.json", CANDELA_SOURCE_DIR "/scenes");
  for (const Vec3 normal : {Vec3{0, 1, 0}, normalize(Vec3{1, 1, 0.3})}) {
    const ShadingFrame frame = ShadingFrame::from_normal(normal);
    Color exact;
    const int n = 400;  // θ × φ cells
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const double theta = (i + 0.5) / n * kPi / 2, phi = (j + 0.5) / n * 2 * kPi;
        const Vec3 local{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
        exact += scene->background_along(frame.to_world(local)) *
                 (std::cos(theta) * std::sin(theta) * (kPi / 2 / n) * (2 * kPi / n) / kPi);
      }
    const Estimate e = irradiance(*scene, {0, 0, 0}, normal, 20000);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(e.mean[c], exact[c], 4 * e.error[c] + 1e-4 * exact[c]) << c;
      EXPECT_NEAR(e.mean[c], exact[c], 0.01 * exact[c]) << c;
    }
  }
}

// A lossless mirror or glass sphere in a uniform environment is invisible: every path carries the
// environment's value back (the dielectric's 1/η² in and η² out cancel). Without Russian roulette
// (which is unbiased but not exact) every path's weight is exactly 1.
TEST(PathTracer, MirrorAndGlassSpheresVanishInAUniformEnvironment) {
  for (const std::string material : {R"({"kd": 0, "kr": 1})", R"({"kd": 0, "kt": 1, "ior": 1.5})"}) {
    const auto scene = path_scene(R"("camera": {"eye": [0, 0, 4], "target": [0, 0, 0], "fov": 35, "width": 12,
        "height": 12}, "background": [0.7, 0.7, 0.7], "path": {"spp": 8, "roulette_depth": 64},
      "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": )" +
                                  material + "}]");
    const Film film = testing::render_scene(*scene, "path");
    for (const Color& pixel : film.pixels())
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(pixel[c], 0.7, 0.7 * 0.01) << material;
  }
}

// Direct light from a directional light on a diffuse floor seen straight down by an orthographic
// camera: next-event estimation gives kd·I·cos θ exactly, the local model's value.
TEST(PathTracer, DirectLightOnADiffuseFloorEqualsTheLocalModel) {
  const auto scene = path_scene(R"("camera": {"type": "orthographic", "eye": [0, 5, 0], "target": [0, 0, 0],
      "up": [0, 0, -1], "width": 8, "height": 8, "window_height": 2},
    "path": {"spp": 4}, "ambient": 0,
    "lights": [{"type": "directional", "direction": [1, -2, 0.5], "intensity": [1.5, 1, 0.5]}],
    "shapes": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": {"kd": [0.6, 0.5, 0.4]}}])");
  const Film path = testing::render_scene(*scene, "path");
  const Film local = testing::render_scene(*scene, "local");
  for (std::size_t i = 0; i < path.pixels().size(); ++i)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(path.pixels()[i][c], local.pixels()[i][c], 1e-9);
}

std::unique_ptr<Scene> small_box(int spp, const std::string& sampler = "independent") {
  return path_scene(
      R"("camera": {"eye": [0.5, 0.5, 2], "target": [0.5, 0.5, 0], "fov": 60, "width": 12, "height": 10},
    "path": {"spp": )" +
      std::to_string(spp) + R"(, "sampler": ")" + sampler + R"("},
    "lights": [{"type": "point", "position": [0.3, 0.8, 0.6], "intensity": 1}],
    "shapes": [
      {"type": "quad", "corner": [0, 0, 0], "edge_u": [1, 0, 0], "edge_v": [0, 1, 0], "material": {"kd": 0.7}},
      {"type": "quad", "corner": [0, 0, 0], "edge_u": [0, 0, 1], "edge_v": [1, 0, 0], "material": {"kd": [0.7, 0.2, 0.2]}},
      {"type": "quad", "corner": [0, 1, 0], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1], "material": {"kd": 0, "emission": 0.5}},
      {"type": "sphere", "center": [0.6, 0.3, 0.4], "radius": 0.2, "material": {"kd": 0.2, "ks": 0.5, "n": 30}},
      {"type": "sphere", "center": [0.3, 0.25, 0.5], "radius": 0.15, "material": {"kd": 0, "kt": 1, "ior": 1.5}}])");
}

const char* const kSamplers[] = {"independent", "stratified", "sobol"};

TEST(PathTracer, ImagesDoNotDependOnTheThreadCount) {
  for (const char* sampler : kSamplers) {
    SCOPED_TRACE(sampler);
    const auto scene = small_box(4, sampler);
    const Film one = testing::render_scene(*scene, "path", 1);
    const Film two = testing::render_scene(*scene, "path", 2);
    for (std::size_t i = 0; i < one.pixels().size(); ++i) ASSERT_EQ(one.pixels()[i], two.pixels()[i]) << i;
  }
}

// Each sampler's image at 16 spp against a 1024-spp reference; the samplers that
// stratify have less error, and all converge to the same image (no bias).
TEST(PathTracer, StratifyingSamplersHaveLessErrorAndNoBias) {
  const Film reference = testing::render_scene(*small_box(1024, "sobol"), "path");
  const auto mse = [&](const Film& film) {
    double sum = 0;
    for (std::size_t i = 0; i < film.pixels().size(); ++i)
      for (int c = 0; c < 3; ++c) sum += std::pow(film.pixels()[i][c] - reference.pixels()[i][c], 2);
    return sum / double(3 * film.pixels().size());
  };
  const auto mean = [](const Film& film) {
    double sum = 0;
    for (const Color& c : film.pixels()) sum += c.r + c.g + c.b;
    return sum / double(film.pixels().size());
  };
  const double independent = mse(testing::render_scene(*small_box(16, "independent"), "path"));
  const double stratified = mse(testing::render_scene(*small_box(16, "stratified"), "path"));
  const double sobol = mse(testing::render_scene(*small_box(16, "sobol"), "path"));
  EXPECT_LT(stratified, 0.9 * independent) << stratified << " " << independent;
  EXPECT_LT(sobol, 0.8 * independent) << sobol << " " << independent;
  // The image means of 1024 independent passes and of the Sobol' reference agree within noise.
  EXPECT_NEAR(mean(testing::render_scene(*small_box(1024, "independent"), "path")) / mean(reference), 1,
              0.01);
}

TEST(PathTracer, TheSamplerIsCheckedByName) {
  const auto error = [](const std::string& path) {
    try {
      (void)path_scene(R"("camera": {"eye": [0, 0, 3], "target": [0, 0, 0], "width": 4, "height": 4},
        "render": {"method": "path"}, "path": )" +
                       path);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error(R"({"sampler": "halton"})")
                .find("path.sampler: unknown sampler \"halton\" (expected one of: "
                      "independent, stratified, sobol)"),
            std::string::npos)
      << error(R"({"sampler": "halton"})");
  EXPECT_NE(error(R"({"spp": 0, "time": 1, "sampler": "stratified"})").find("needs path.spp"),
            std::string::npos);
}

TEST(PathTracer, ResumingACheckpointGivesTheUninterruptedImage) {
  // The method hands its final state out (RenderResult::checkpoint) and continues from it
  // (RenderRequest::resume); it writes no file.
  const auto render = [&](int spp, bool checkpoint, const std::optional<Bytes>& resume) {
    const auto scene = small_box(spp);
    const auto method = create_method(*find_method("path"), *scene);
    RenderRequest request{{0, 0, scene->camera->width(), scene->camera->height()}, true};
    request.checkpoint = checkpoint;
    if (resume) request.resume = SealedCheckpoint{"box.checkpoint", *resume};
    request.fingerprint = "box";
    return method->render(*scene, request);
  };
  const RenderResult uninterrupted = render(7, false, std::nullopt);
  EXPECT_FALSE(uninterrupted.checkpoint);
  const RenderResult first = render(3, true, std::nullopt);
  ASSERT_TRUE(first.checkpoint);
  EXPECT_EQ(unseal_pass_checkpoint("path", {"first", *first.checkpoint}).passes, 3u);
  const RenderResult resumed = render(7, true, *first.checkpoint);
  for (std::size_t i = 0; i < resumed.film.pixels().size(); ++i)
    ASSERT_EQ(resumed.film.pixels()[i], uninterrupted.film.pixels()[i]) << i;
  ASSERT_TRUE(resumed.checkpoint);
  EXPECT_EQ(unseal_pass_checkpoint("path", {"resumed", *resumed.checkpoint}).passes, 7u);
  EXPECT_EQ(resumed.statistics.extra["path"]["resumed_from_spp"], 3);
  // Another scene's state is refused, naming where it came from.
  try {
    const auto scene = small_box(7);
    RenderRequest request{{0, 0, scene->camera->width(), scene->camera->height()}, true};
    request.resume = SealedCheckpoint{"box.checkpoint", *first.checkpoint};
    request.fingerprint = "another box";
    (void)create_method(*find_method("path"), *scene)->render(*scene, request);
    ADD_FAILURE() << "another scene's checkpoint was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.location().file, "box.checkpoint");
    EXPECT_NE(e.message().find("another scene"), std::string::npos) << e.message();
  }
}

// One film: the path tracer's samples are splatted with the scene's filter (Σ w·L / Σ w
// across pixels); a checkpoint holds both sums, so resuming still gives the uninterrupted image,
// and a crop's pixels are the whole image's (its ring of pixels is sampled too).
TEST(PathTracer, FilteredPassesResumeAndCropToTheWholeImage) {
  const auto render = [&](int spp, const PixelRect& region, bool checkpoint,
                          const std::optional<Bytes>& resume) {
    const auto scene = small_box(spp);
    scene->antialiasing.filter = "gaussian";
    scene->antialiasing.filter_parameters.radius = 1.5;
    const auto method = create_method(*find_method("path"), *scene);
    RenderRequest request{region, true};
    request.checkpoint = checkpoint;
    if (resume) request.resume = SealedCheckpoint{"box.checkpoint", *resume};
    request.fingerprint = "box";
    return method->render(*scene, request);
  };
  const auto whole_region = [&] {
    const auto scene = small_box(1);
    return PixelRect{0, 0, scene->camera->width(), scene->camera->height()};
  }();
  const RenderResult whole = render(5, whole_region, false, std::nullopt);
  const RenderResult part = render(2, whole_region, true, std::nullopt);
  ASSERT_TRUE(part.checkpoint);
  const RenderResult resumed = render(5, whole_region, false, *part.checkpoint);
  for (std::size_t i = 0; i < whole.film.pixels().size(); ++i)
    ASSERT_EQ(resumed.film.pixels()[i], whole.film.pixels()[i]) << i;
  // The filter really spreads: the box gives another image.
  const auto box_scene = small_box(5);
  const Film box = testing::render_scene(*box_scene, "path");
  EXPECT_NE(std::memcmp(box.pixels().data(), whole.film.pixels().data(), box.pixels().size() * sizeof(Color)),
            0);
  const PixelRect crop{3, 2, 9, 7};
  const RenderResult cropped = render(5, crop, false, std::nullopt);
  for (int y = crop.y0; y < crop.y1; ++y)
    for (int x = crop.x0; x < crop.x1; ++x)
      ASSERT_EQ(cropped.film.at(x - crop.x0, y - crop.y0), whole.film.at(x, y)) << x << ", " << y;
}

// The aa settings for every method: "corners" and "adaptive" passes are the camera sampler's lattice
// images (Figure 49's setting: adaptive, jittered lattice, Gaussian). The image does not depend on
// the thread count, a crop's pixels are the whole image's, a resumed run gives the uninterrupted
// image, and the passes converge to what jittered passes converge to.
TEST(PathTracer, LatticePassesAreDeterministicCropAndResumeAndConverge) {
  const auto adaptive_box = [](int spp, AntialiasingMode mode) {
    auto scene = small_box(spp);
    scene->antialiasing.mode = mode;
    scene->antialiasing.jitter = true;
    scene->antialiasing.filter = "gaussian";
    return scene;
  };
  const auto render = [&](const Scene& scene, const PixelRect& region, bool checkpoint,
                          const std::optional<Bytes>& resume) {
    const auto method = create_method(*find_method("path"), scene);
    RenderRequest request{region, true};
    request.checkpoint = checkpoint;
    if (resume) request.resume = SealedCheckpoint{"box.checkpoint", *resume};
    request.fingerprint = "box";
    return method->render(scene, request);
  };
  for (const AntialiasingMode mode : {AntialiasingMode::corners, AntialiasingMode::adaptive}) {
    SCOPED_TRACE(std::string(kAntialiasingModeNames.name(mode)));
    const auto scene = adaptive_box(4, mode);
    const PixelRect whole{0, 0, scene->camera->width(), scene->camera->height()};
    const Film one = testing::render_scene(*scene, "path", 1);
    const Film two = testing::render_scene(*scene, "path", 2);
    for (std::size_t i = 0; i < one.pixels().size(); ++i) ASSERT_EQ(one.pixels()[i], two.pixels()[i]) << i;
    const PixelRect crop{3, 2, 9, 7};
    const RenderResult cropped = render(*scene, crop, false, std::nullopt);
    for (int y = crop.y0; y < crop.y1; ++y)
      for (int x = crop.x0; x < crop.x1; ++x)
        ASSERT_EQ(cropped.film.at(x - crop.x0, y - crop.y0), two.at(x, y)) << x << ", " << y;
    const RenderResult part = render(*adaptive_box(2, mode), whole, true, std::nullopt);
    ASSERT_TRUE(part.checkpoint);
    const RenderResult resumed = render(*scene, whole, false, *part.checkpoint);
    for (std::size_t i = 0; i < one.pixels().size(); ++i)
      ASSERT_EQ(resumed.film.pixels()[i], one.pixels()[i]) << i;
  }
  // The adaptive image's mean and the jittered one's agree within their noise (both 64 passes);
  // adaptive subdivides where corners differ, so it traces more rays than the corners alone.
  const auto mean_of = [](const Film& film) {
    double sum = 0;
    for (const Color& c : film.pixels()) sum += luminance(c);
    return sum / double(film.pixels().size());
  };
  RunStatistics adaptive_rays, jittered_rays;
  const Film adaptive =
      testing::render_scene(*adaptive_box(64, AntialiasingMode::adaptive), "path", 2, adaptive_rays);
  const Film jittered =
      testing::render_scene(*adaptive_box(64, AntialiasingMode::jittered), "path", 2, jittered_rays);
  EXPECT_NEAR(mean_of(adaptive) / mean_of(jittered), 1.0, 0.03);
  const auto corner_rays = uint64_t(64) * (12 + 1) * (10 + 1);
  EXPECT_GT(adaptive_rays.rays.primary, corner_rays);
  EXPECT_EQ(jittered_rays.rays.primary, uint64_t(64) * 12 * 10);
}

// With every sampler, a run stopped after 3 of 7 passes (the checkpoint handed out then)
// resumes into the uninterrupted image, byte for byte; a stratified checkpoint made for another
// spp is refused (its strata are the passes).
TEST(PathTracer, EverySamplerResumesIntoTheUninterruptedImage) {
  for (const char* sampler : kSamplers) {
    SCOPED_TRACE(sampler);
    const auto scene = small_box(7, sampler);
    const auto method = create_method(*find_method("path"), *scene, {"checkpoint_interval=1e-9"});
    RenderRequest request{{0, 0, scene->camera->width(), scene->camera->height()}, true};
    request.fingerprint = "box";
    request.checkpoint = true;
    std::optional<Bytes> after_three;
    request.save_checkpoint = [&](const Bytes& sealed) {
      if (unseal_pass_checkpoint("path", {"saved", sealed}).passes == 3) after_three = sealed;
    };
    const RenderResult uninterrupted = method->render(*scene, request);
    ASSERT_TRUE(after_three);
    RenderRequest again{{0, 0, scene->camera->width(), scene->camera->height()}, true};
    again.fingerprint = "box";
    again.resume = SealedCheckpoint{"box.checkpoint", *after_three};
    const RenderResult resumed = create_method(*find_method("path"), *scene)->render(*scene, again);
    for (std::size_t i = 0; i < resumed.film.pixels().size(); ++i)
      ASSERT_EQ(resumed.film.pixels()[i], uninterrupted.film.pixels()[i]) << i;
    const auto other_spp = small_box(9, sampler);
    RenderRequest longer{{0, 0, other_spp->camera->width(), other_spp->camera->height()}, true};
    longer.fingerprint = "box";
    longer.resume = again.resume;
    if (std::string(sampler) == "stratified") {
      EXPECT_THROW(create_method(*find_method("path"), *other_spp)->render(*other_spp, longer), InputError);
    } else {
      EXPECT_NO_THROW(create_method(*find_method("path"), *other_spp)->render(*other_spp, longer));
    }
  }
}

// "--checkpoint FILE every N seconds": with an interval shorter than a pass, a checkpoint is handed
// out after every pass but the last, and the final state is returned at the end.
TEST(PathTracer, CheckpointsAreHandedOutEveryIntervalAndAtTheEnd) {
  auto scene = small_box(4);
  const auto method = create_method(*find_method("path"), *scene, {"checkpoint_interval=1e-9"});
  RenderRequest request{{0, 0, scene->camera->width(), scene->camera->height()}, true};
  request.checkpoint = true;
  std::vector<uint64_t> saved_passes;
  request.save_checkpoint = [&](const Bytes& sealed) {
    saved_passes.push_back(unseal_pass_checkpoint("path", {"saved", sealed}).passes);
  };
  const RenderResult result = method->render(*scene, request);
  EXPECT_EQ(saved_passes, (std::vector<uint64_t>{1, 2, 3}));
  ASSERT_TRUE(result.checkpoint);
  EXPECT_EQ(unseal_pass_checkpoint("path", {"final", *result.checkpoint}).passes, 4u);
  EXPECT_EQ(result.statistics.extra["path"]["checkpoints_written"],
            4);  // after passes 1, 2, 3 and at the end
}

TEST(PathCheckpoint, RoundTripsExactlyAndRefusesDamage) {
  const testing::ScratchDirectory directory("path-checkpoint");
  const std::string file = (directory.path() / "c.checkpoint").string();
  PassCheckpoint written;
  written.fingerprint = "scene 1";
  written.region = {2, 3, 4, 5};
  written.passes = 9;
  written.seconds = 1.25;
  written.rays.primary = 36;
  written.sums = {Color(0.1, 1e-300, 3), Color(1.0 / 3), Color(7, 8, 9), Color(-0.0, 2, 5e300)};
  written.weights = {9, 9.5, 1.0 / 7, 0};
  write_checkpoint_file(file, seal_pass_checkpoint("path", written));
  const PassCheckpoint read = unseal_pass_checkpoint("path", read_checkpoint_file(file));
  EXPECT_EQ(read.fingerprint, written.fingerprint);
  EXPECT_EQ(read.passes, 9u);
  EXPECT_EQ(read.rays.primary, 36u);
  EXPECT_EQ(read.region.x1, 4);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(read.sums[i], written.sums[i]);
  EXPECT_EQ(read.weights, written.weights);
  // Truncated, or one byte changed: refused with the file's name.
  std::string bytes;
  {
    std::ifstream in(file, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  // The format the path tracer has written since the filter weights: older files still resume.
  EXPECT_EQ(bytes.rfind("CANDELA-PATH-CHECKPOINT 2\n", 0), 0u);
  // Another pass method's checkpoint is not the path tracer's.
  EXPECT_THROW((void)unseal_pass_checkpoint("toy", read_checkpoint_file(file)), InputError);
  const auto expect_refused = [&](const std::string& damaged, const std::string& why) {
    std::ofstream(file, std::ios::binary | std::ios::trunc) << damaged;
    try {
      (void)unseal_pass_checkpoint("path", read_checkpoint_file(file));
      ADD_FAILURE() << why << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("c.checkpoint"), std::string::npos) << e.what();
    }
  };
  expect_refused(bytes.substr(0, bytes.size() - 9), "a truncated file");
  std::string flipped = bytes;
  flipped[flipped.size() / 2] ^= 0x10;
  expect_refused(flipped, "a changed byte");
  expect_refused("P6\n", "another file");
}

// Path tracing with an end: inside a closed sphere of albedo exactly 1 lit by a point,
// with `max_depth` 0 (no limit), every path survives Russian roulette with q = min(0.95, beta),
// so roulette alone ends it after 20 bounces on average; with roulette held off until bounce
// 1024 none escapes or dies, and the hard cap of 1024 bounces ends every one: exactly 1024
// reflected rays per primary ray, and the render finishes (a hang fails by the test's timeout).
TEST(PathTracer, AClosedWhiteEnclosureWithoutADepthLimitEndsEveryPath) {
  const auto enclosure = [](int roulette_depth) {
    return path_scene(R"("camera": {"eye": [0, 0, 0], "target": [0, 0, -1], "up": [0, 1, 0], "width": 4,
      "height": 3}, "render": {"method": "path"},
      "path": {"spp": 2, "max_depth": 0, "roulette_depth": )" +
                      std::to_string(roulette_depth) + R"(},
      "materials": {"white": {"kd": [1, 1, 1]}},
      "lights": [{"type": "point", "position": [0.2, 0.3, 0], "intensity": [1, 1, 1]}],
      "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 2, "material": "white"}])");
  };
  RunStatistics capped;
  const Film film = testing::render_scene(*enclosure(1024), "path", 2, capped);
  EXPECT_EQ(capped.rays.primary, 2u * 4 * 3);
  EXPECT_EQ(capped.rays.reflected, capped.rays.primary * 1024);
  for (const Color& c : film.pixels()) EXPECT_TRUE(std::isfinite(c.r) && c.r > 0) << c.r;
  RunStatistics roulette;
  testing::render_scene(*enclosure(3), "path", 2, roulette);
  const double bounces = double(roulette.rays.reflected) / double(roulette.rays.primary);
  EXPECT_GT(bounces, 5);
  EXPECT_LT(bounces, 60);  // 1 / (1 − 0.95) = 20 after the first three
}

}  // namespace
}  // namespace candela
