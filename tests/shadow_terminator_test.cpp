// The shadow terminator on a smooth low-poly mesh (Hanika 2021, "Hacking the shadow
// terminator", Ray Tracing Gems II ch. 4): a coarse sphere with its true vertex normals, lit from
// the side. Where a facet faces slightly away from the light but its interpolated normal faces
// the light, the local model cut the light off at the facet (geometric N·L ≤ 0) and the path
// tracer's shadow rays hit the neighbouring facets: the terminator ran in steps along the facets,
// a jump of kd·I·0.22 at one edge here. From Hanika's lifted point (SurfaceHit::lifted_toward) the
// shadow ray decides, and the terminator follows the shading normals.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "geometry/triangle_mesh.h"
#include "integrators/scene_loading.h"
#include "math/constants.h"
#include "render_support.h"
#include "scene/scene.h"
#include "scratch_directory.h"

namespace candela {
namespace {

// A unit UV sphere of `segments` × `rings` with its exact normals (vn), its longitudes at
// (k + ½)·360°/segments from +x toward +z, so that the facet facing the camera on +z is centred on
// longitude 90°; counter-clockwise seen from outside.
std::string uv_sphere_obj(int segments, int rings) {
  std::ostringstream obj;
  obj.precision(17);
  const auto vertex = [&](double theta, double phi) {
    const Vec3 p{std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)};
    obj << "v " << p.x << ' ' << p.y << ' ' << p.z << "\nvn " << p.x << ' ' << p.y << ' ' << p.z << '\n';
  };
  vertex(0, 0);  // 1: north pole
  for (int j = 1; j < rings; ++j)
    for (int k = 0; k < segments; ++k) vertex(j * kPi / rings, (k + 0.5) * 2 * kPi / segments);
  vertex(kPi, 0);  // south pole
  const int south = 2 + (rings - 1) * segments;
  const auto index = [&](int j, int k) { return 2 + (j - 1) * segments + (k % segments); };
  const auto face = [&](int a, int b, int c) {
    obj << "f " << a << "//" << a << ' ' << b << "//" << b << ' ' << c << "//" << c << '\n';
  };
  for (int k = 0; k < segments; ++k) {
    face(1, index(1, k + 1), index(1, k));
    for (int j = 1; j + 1 < rings; ++j) {
      face(index(j, k), index(j, k + 1), index(j + 1, k));
      face(index(j, k + 1), index(j + 1, k + 1), index(j + 1, k));
    }
    face(index(rings - 1, k), index(rings - 1, k + 1), south);
  }
  return obj.str();
}

// The sphere seen along −z through an orthographic window of [−1.2, 1.2]², lit by a directional
// light from longitude −10° (slightly behind the sphere, on +x): the terminator of the smooth
// sphere is the meridian at longitude 80°, which crosses the facet spanning 67.5°–112.5°, whose
// geometric normal (at 90°) faces 10° away from the light.
std::string scene_text() {
  const double phi = -10 * kPi / 180;
  std::ostringstream text;
  text.precision(17);
  text << R"({"format": "candela/1",
    "camera": {"type": "orthographic", "eye": [0, 0, 5], "target": [0, 0, 0], "window": [-1.2, 1.2, -1.2, 1.2],
               "width": 96, "height": 8},
    "path": {"max_depth": 1, "spp": 8},
    "aa": {"mode": "none"},
    "lights": [{"type": "directional", "direction": [)"
       << -std::cos(phi) << ", 0, " << -std::sin(phi) << R"(], "intensity": 1}],
    "shapes": [{"type": "mesh", "file": "sphere.obj", "normals": "file", "material": {"kd": 0.5}}]})";
  return text.str();
}

// The largest change between neighbouring pixels of the rows through the equator's facets, inside
// the sphere's silhouette, and where the smooth sphere is dark.
struct RowProfile {
  double largest_step = 0;
  double largest_value = 0;
};
RowProfile equator_profile(const Film& film) {
  RowProfile profile;
  for (const int y : {3, 4})
    for (int x = 0; x + 1 < film.width(); ++x) {
      const double left = (x + 0.5) / film.width() * 2.4 - 1.2;  // the window's x at pixel x
      if (std::fabs(left) > 0.75 || std::fabs(left + 2.4 / film.width()) > 0.75) continue;
      profile.largest_step = std::max(profile.largest_step, std::fabs(film.at(x + 1, y).r - film.at(x, y).r));
      profile.largest_value = std::max(profile.largest_value, film.at(x, y).r);
    }
  return profile;
}

TEST(ShadowTerminator, TheLiftOnACurvedTriangleIsHanikasAndNoneOnAFlatOne) {
  // One facet of a sphere: corners on the unit sphere with their radial normals.
  auto mesh = std::make_shared<TriangleMesh>();
  const Vec3 corners[3] = {normalize(Vec3{1, 0, 0.2}), normalize(Vec3{0, 1, 0.2}),
                           normalize(Vec3{-1, -1, 0.4})};
  mesh->positions.assign(std::begin(corners), std::end(corners));
  mesh->triangles = {{0, 1, 2}};
  mesh->corner_normals = {{corners[0], corners[1], corners[2]}};
  const MeshTriangle triangle(mesh, 0);
  const Vec3 centroid = (corners[0] + corners[1] + corners[2]) / 3;
  SurfaceHit hit;
  ASSERT_TRUE(triangle.intersect(Ray{centroid * 3, -normalize(centroid), 0, kInfinity}, hit));
  ASSERT_TRUE(hit.interpolated_normal);
  // P' − P = −Σ b_i min(0, (P − V_i)·n_i) n_i with b = ⅓ each; the chord's points are under
  // every tangent plane of a sphere, so every term lifts.
  Vec3 expected;
  for (const Vec3& corner : corners)
    expected -= corner * (std::min(0.0, dot(hit.position - corner, corner)) / 3);
  EXPECT_NEAR(length(hit.terminator_lift_outside - expected), 0, 1e-12);
  EXPECT_GT(dot(hit.terminator_lift_outside, hit.geometric_normal), 0.05);
  EXPECT_EQ(hit.terminator_lift_inside, Vec3{});  // seen from inside the sphere is hollow: no lift
  EXPECT_EQ(hit.lifted_toward(hit.geometric_normal), hit.position + hit.terminator_lift_outside);
  EXPECT_EQ(hit.lifted_toward(-hit.geometric_normal), hit.position);

  // Normals equal to the face normal: a flat surface, no lift at all.
  const Vec3 face = normalize(cross(corners[1] - corners[0], corners[2] - corners[0]));
  mesh->corner_normals = {{face, face, face}};
  const MeshTriangle flat(mesh, 0);
  SurfaceHit flat_hit;
  ASSERT_TRUE(flat.intersect(Ray{centroid * 3, -normalize(centroid), 0, kInfinity}, flat_hit));
  EXPECT_NEAR(length(flat_hit.terminator_lift_outside), 0, 1e-15);
  EXPECT_NEAR(length(flat_hit.terminator_lift_inside), 0, 1e-15);
}

class ShadowTerminatorRender : public ::testing::TestWithParam<const char*> {};

TEST_P(ShadowTerminatorRender, FollowsTheShadingNormalsNotTheFacets) {
  testing::ScratchDirectory scratch("terminator");
  testing::write_file(scratch.path() / "sphere.obj", uv_sphere_obj(8, 6));
  const auto scene = load_scene_text(scene_text(), "terminator.json", scratch.path().string());
  const RowProfile profile = equator_profile(testing::render_scene(*scene, GetParam()));
  // kd·I·(N·L) of the smooth sphere changes by at most kd·I·Δx = 0.5 · 0.025 between pixels;
  // the stepped terminator jumped by kd·I·cos(77.5°) = 0.108 where the lit facet meets the dark one.
  EXPECT_GT(profile.largest_value, 0.2);  // the lit part is in the rows
  EXPECT_LT(profile.largest_step, 0.045) << GetParam();
}

// The relaxed side test lets no light in: from inside the closed smooth sphere, lit from outside by
// a light that reaches every facet's outside, every pixel stays black.
TEST_P(ShadowTerminatorRender, NoLightLeaksIntoTheClosedSmoothSphere) {
  testing::ScratchDirectory scratch("terminator");
  testing::write_file(scratch.path() / "sphere.obj", uv_sphere_obj(8, 6));
  std::string text = scene_text();
  text.replace(text.find(R"("type": "orthographic")"), 22, R"("type": "perspective", "fov": 100)");
  text.replace(text.find(R"(, "window": [-1.2, 1.2, -1.2, 1.2])"), 34, "");
  text.replace(text.find(R"("eye": [0, 0, 5])"), 16, R"("eye": [0, 0, 0.2])");
  const auto scene = load_scene_text(text, "terminator.json", scratch.path().string());
  const Film film = testing::render_scene(*scene, GetParam());
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x) ASSERT_TRUE(film.at(x, y).is_black()) << x << ", " << y;
}

INSTANTIATE_TEST_SUITE_P(Methods, ShadowTerminatorRender, ::testing::Values("local", "whitted", "path"));

}  // namespace
}  // namespace candela
