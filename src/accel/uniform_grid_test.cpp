#include "accel/uniform_grid.h"

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "accel/subdivision_test_support.h"

namespace candela {
namespace {

using testing::SubdivisionScene;

std::array<int, 3> formula(const Vec3& extent, double count, double density) {
  const double scale = std::cbrt(density * count / (extent.x * extent.y * extent.z));
  std::array<int, 3> resolution{};
  for (int axis = 0; axis < 3; ++axis)
    resolution[axis] = static_cast<int>(std::clamp(std::round(extent[axis] * scale), 1.0, 512.0));
  return resolution;
}

TEST(UniformGrid, ResolutionFollowsTheObjectCount) {
  EXPECT_EQ(UniformGrid::resolution_for({10, 10, 10}, 1000, 3), (std::array<int, 3>{14, 14, 14}));
  EXPECT_EQ(UniformGrid::resolution_for({4, 2, 1}, 500, 3), formula({4, 2, 1}, 500, 3));
  EXPECT_EQ(UniformGrid::resolution_for({4, 2, 1}, 500, 3), (std::array<int, 3>{23, 11, 6}));
  EXPECT_EQ(UniformGrid::resolution_for({3, 7, 5}, 12345, 0.5), formula({3, 7, 5}, 12345, 0.5));
  // Clamped to 512 per axis.
  EXPECT_EQ(UniformGrid::resolution_for({1000, 1, 1}, 1000000, 3), (std::array<int, 3>{512, 14, 14}));
  EXPECT_EQ(UniformGrid::resolution_for({1, 1, 1}, 1000000000, 3), (std::array<int, 3>{512, 512, 512}));
  // Flat, linear and point-like scenes: one voxel across a zero extent, the budget to the rest.
  EXPECT_EQ(UniformGrid::resolution_for({10, 0, 10}, 1200, 3), (std::array<int, 3>{60, 1, 60}));
  EXPECT_EQ(UniformGrid::resolution_for({10, 1e-12, 10}, 1200, 3), (std::array<int, 3>{60, 1, 60}));
  EXPECT_EQ(UniformGrid::resolution_for({5, 0, 0}, 100, 3), (std::array<int, 3>{300, 1, 1}));
  EXPECT_EQ(UniformGrid::resolution_for({0, 0, 0}, 7, 3), (std::array<int, 3>{1, 1, 1}));
  EXPECT_EQ(UniformGrid::resolution_for({1, 1, 1}, 1, 1e-6), (std::array<int, 3>{1, 1, 1}));
  EXPECT_EQ(UniformGrid::resolution_for({1, 1, 1}, 0, 3), (std::array<int, 3>{0, 0, 0}));
}

TEST(UniformGrid, BuildUsesTheBoundedPrimitiveCount) {
  SubdivisionScene scene(1);
  testing::random_spheres_scene(scene);
  scene.add_plane({0, 0, 0}, {0, 1, 0});  // unbounded: not counted
  for (double density : {0.5, 3.0, 8.0}) {
    UniformGrid grid(density);
    grid.build(scene.primitives());
    Bounds3 bounds;
    for (const Primitive& primitive : scene.primitives())
      if (primitive.shape->bounds().is_finite()) bounds.extend(primitive.shape->bounds());
    EXPECT_EQ(grid.resolution(), UniformGrid::resolution_for(bounds.diagonal(), 400, density));
    EXPECT_EQ(grid.resolution(), formula(bounds.diagonal(), 400, density));
    const double voxels = 1.0 * grid.resolution()[0] * grid.resolution()[1] * grid.resolution()[2];
    EXPECT_NEAR(voxels / (density * 400), 1.0, 0.3) << density;
  }
}

TEST(UniformGrid, EveryVoxelListsThePrimitivesOverlappingIt) {
  SubdivisionScene scene(2);
  const Bounds3 region = testing::random_triangles_scene(scene);
  UniformGrid grid;
  grid.build(scene.primitives());
  for (uint32_t index = 0; index < scene.primitives().size(); ++index) {
    const Bounds3 bounds = scene.primitives()[index].shape->bounds();
    for (int k = 0; k < 4; ++k) {  // points of the primitive's bounds
      const Vec3 p = scene.point(bounds);
      const auto voxel = grid.voxel_primitives(grid.voxel_of(p));
      EXPECT_TRUE(std::binary_search(voxel.begin(), voxel.end(), index)) << index;
    }
  }
  // And nothing else: a voxel's primitives overlap it.
  for (int k = 0; k < 200; ++k) {
    const auto cell = grid.voxel_of(scene.point(region));
    Bounds3 box;
    for (int axis = 0; axis < 3; ++axis) {
      const double size =
          (grid.grid_bounds().upper[axis] - grid.grid_bounds().lower[axis]) / grid.resolution()[axis];
      box.lower[axis] = grid.grid_bounds().lower[axis] + cell[axis] * size - 1e-9;
      box.upper[axis] = box.lower[axis] + size + 2e-9;
    }
    for (uint32_t index : grid.voxel_primitives(cell)) {
      const Bounds3 bounds = scene.primitives()[index].shape->bounds();
      EXPECT_TRUE(bounds.lower.x <= box.upper.x && bounds.upper.x >= box.lower.x &&
                  bounds.lower.y <= box.upper.y && bounds.upper.y >= box.lower.y &&
                  bounds.lower.z <= box.upper.z && bounds.upper.z >= box.lower.z);
    }
  }
}

TEST(UniformGrid, MatchesTheListOnRandomSpheres) {
  SubdivisionScene scene(3);
  const Bounds3 region = testing::random_spheres_scene(scene);
  UniformGrid grid;
  EXPECT_GT(testing::expect_same_as_list(grid, scene.primitives(), scene.rays(4000, region)), 1000);
}

TEST(UniformGrid, MatchesTheListOnRandomTriangles) {
  SubdivisionScene scene(4);
  const Bounds3 region = testing::random_triangles_scene(scene);
  UniformGrid grid;
  EXPECT_GT(testing::expect_same_as_list(grid, scene.primitives(), scene.rays(4000, region)), 1000);
}

TEST(UniformGrid, MatchesTheListOnLongThinPrimitives) {
  SubdivisionScene scene(5);
  const Bounds3 region = testing::long_thin_scene(scene);
  for (double density : {3.0, 30.0}) {
    UniformGrid grid(density);
    EXPECT_GT(testing::expect_same_as_list(grid, scene.primitives(), scene.rays(4000, region)), 500);
  }
}

TEST(UniformGrid, MatchesTheListOnCoincidentDuplicates) {
  SubdivisionScene scene(6);
  const Bounds3 region = testing::coincident_scene(scene);
  UniformGrid grid;
  EXPECT_GT(testing::expect_same_as_list(grid, scene.primitives(), scene.rays(4000, region)), 1000);
}

TEST(UniformGrid, MatchesTheListWithEverythingInOnePoint) {
  SubdivisionScene scene(7);
  const Bounds3 region = testing::one_point_scene(scene);
  UniformGrid grid;
  EXPECT_GT(testing::expect_same_as_list(grid, scene.primitives(), scene.rays(2000, region)), 500);
}

TEST(UniformGrid, MatchesTheListOnAFlatScene) {
  SubdivisionScene scene(8);
  const Bounds3 region = testing::flat_scene(scene);
  UniformGrid grid;
  std::vector<Ray> rays = scene.rays(4000, region);
  for (int i = 0; i < 300; ++i) {  // rays in the plane of the triangles (edge-on: no hit)
    const Vec3 d = scene.direction();
    rays.push_back({{scene.uniform(-12, 12), 0, scene.uniform(-12, 12)}, normalize(Vec3{d.x, 0, d.z})});
  }
  EXPECT_GT(testing::expect_same_as_list(grid, scene.primitives(), rays), 600);
  EXPECT_EQ(grid.resolution()[1], 1);
  EXPECT_NEAR(1.0 * grid.resolution()[0] * grid.resolution()[2] / (3.0 * 800), 1.0, 0.2);
}

TEST(UniformGrid, MatchesTheListWithPlanes) {
  SubdivisionScene scene(9);
  const Bounds3 region = testing::planes_scene(scene);
  UniformGrid grid;
  EXPECT_GT(testing::expect_same_as_list(grid, scene.primitives(), scene.rays(4000, region)), 2000);
}

TEST(UniformGrid, EmptyAndPlanesOnlyScenes) {
  SubdivisionScene empty(10);
  UniformGrid grid;
  const Bounds3 region{{-1, -1, -1}, {1, 1, 1}};
  EXPECT_EQ(testing::expect_same_as_list(grid, empty.primitives(), empty.rays(200, region)), 0);
  EXPECT_EQ(grid.resolution(), (std::array<int, 3>{0, 0, 0}));

  SubdivisionScene planes(11);
  planes.add_plane({0, 0, 0}, {0, 1, 0});
  planes.add_plane({0, 0, 0}, {0, 1, 0});  // coincident: index 0 wins
  planes.add_plane({0, 0.5, 0}, {1, 1, 0});
  EXPECT_GT(testing::expect_same_as_list(grid, planes.primitives(), planes.rays(1000, region)), 300);
}

// 000 §5.7.2: a hit found in a voxel but lying beyond it is not final.
TEST(UniformGrid, AHitBeyondTheCurrentVoxelWaitsForNearerPrimitives) {
  const Ray ray = testing::thin_triangle_ray();
  const Vec3 far_hit{9, 0, 0};  // where the ray meets the thin triangle (primitive 0)
  for (const double sphere_x : {-100.0, 5.0, 8.95}) {
    SubdivisionScene scene(12);
    testing::thin_triangle_scene(scene);
    const uint32_t sphere = sphere_x > -100 ? scene.add_sphere({sphere_x, 0, 0}, 0.02) : 0;
    UniformGrid grid;
    grid.build(scene.primitives());
    // The triangle is met in the voxel where the ray enters, its hit lies in a later voxel.
    double t_enter = 0, t_exit = 0;
    ASSERT_TRUE(grid.grid_bounds().intersect(ray, t_enter, t_exit));
    const auto first = grid.voxel_of(ray.at(t_enter));
    ASSERT_TRUE(
        std::binary_search(grid.voxel_primitives(first).begin(), grid.voxel_primitives(first).end(), 0u));
    ASSERT_GE(grid.voxel_of(far_hit)[0], first[0] + 5);
    if (sphere_x == 8.95) {  // the nearer primitive lies in the very voxel of the far hit
      ASSERT_EQ(grid.voxel_of({sphere_x - 0.02, 0, 0}), grid.voxel_of(far_hit));
    }

    Intersection hit;
    ASSERT_TRUE(grid.intersect(ray, hit));
    if (sphere_x > -100) {
      EXPECT_EQ(hit.primitive, sphere);
      EXPECT_NEAR(hit.surface.t, sphere_x - 0.02 + 1, 1e-12);
    } else {
      EXPECT_EQ(hit.primitive, 0u);
      EXPECT_NEAR(hit.surface.t, 10, 1e-12);
    }
    testing::expect_same_as_list(grid, scene.primitives(), std::vector<Ray>{ray});
  }
}

TEST(UniformGrid, IsSafeToShareBetweenThreads) {
  SubdivisionScene scene(13);
  const Bounds3 region = testing::long_thin_scene(scene);
  const std::vector<Ray> rays = scene.rays(20000, region);
  UniformGrid grid;
  grid.build(scene.primitives());
  EXPECT_EQ(testing::mismatches_when_shared(grid, scene.primitives(), rays), 0);
}

TEST(UniformGrid, ReportsItsFigures) {
  SubdivisionScene scene(14);
  testing::planes_scene(scene);
  UniformGrid grid;
  grid.build(scene.primitives());
  const AcceleratorReport report = grid.report();
  const auto figure = [&](const std::string& name) { return testing::report_figure(report, name); };
  EXPECT_EQ(figure("voxels"), 1.0 * grid.resolution()[0] * grid.resolution()[1] * grid.resolution()[2]);
  EXPECT_EQ(figure("unbounded"), 3);
  EXPECT_GE(figure("references"), 500);
  EXPECT_GE(figure("primitives per non-empty voxel"), 1);
  EXPECT_GT(report.bytes, 0u);
  EXPECT_THROW(UniformGrid(0.0), std::invalid_argument);
  EXPECT_THROW(UniformGrid(-1.0), std::invalid_argument);
  EXPECT_EQ(UniformGrid().name(), "grid");
}

}  // namespace
}  // namespace candela
