#include "accel/octree.h"

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <stdexcept>

#include "accel/subdivision_test_support.h"

namespace candela {
namespace {

using testing::SubdivisionScene;

// Nodes split only while they hold more than K primitives and lie above depth D; internal nodes
// have 8 children one level deeper; leaves hold their primitives in ascending order.
void expect_respects(const Octree& octree, int max_primitives, int max_depth) {
  const auto& nodes = octree.nodes();
  ASSERT_FALSE(nodes.empty());
  EXPECT_EQ(nodes[0].depth, 0);
  for (const Octree::Node& node : nodes) {
    EXPECT_LE(node.depth, max_depth);
    if (node.leaf) {
      const auto primitives = octree.leaf_primitives(node);
      EXPECT_TRUE(std::is_sorted(primitives.begin(), primitives.end()));
      EXPECT_EQ(std::adjacent_find(primitives.begin(), primitives.end()), primitives.end());
      continue;
    }
    EXPECT_GT(node.count, static_cast<uint32_t>(max_primitives));
    EXPECT_LT(node.depth, max_depth);
    ASSERT_LE(node.first + 8, nodes.size());
    uint32_t references = 0, non_empty = 0, full = 0;
    for (uint32_t child = 0; child < 8; ++child) {
      const Octree::Node& next = nodes[node.first + child];
      EXPECT_EQ(next.depth, node.depth + 1);
      references += next.count;
      non_empty += next.count > 0;
      full += next.count == node.count;
    }
    // The guard: few duplicates, and the cut separates something.
    EXPECT_LE(references, Octree::kMaxDuplication * node.count);
    EXPECT_FALSE(non_empty >= 2 && full == non_empty);
  }
}

TEST(Octree, RespectsMaxPrimitivesAndMaxDepth) {
  SubdivisionScene scene(1);
  const Bounds3 region{{0, 0, 0}, {1, 1, 1}};
  scene.add_random_spheres(2000, region, 1e-5, 1e-4);
  // A dense but separable cluster: it reaches depth D with more than K primitives.
  const Bounds3 cluster{{0.3001, 0.3001, 0.3001}, {0.3002, 0.3002, 0.3002}};
  scene.add_random_spheres(40, cluster, 1e-9, 2e-9);
  for (const auto& [max_primitives, max_depth] :
       {std::pair{8, 10}, {1, 6}, {4, 3}, {0, 2}, {20, 32}, {8, 0}}) {
    Octree octree(max_primitives, max_depth);
    octree.build(scene.primitives());
    expect_respects(octree, max_primitives, max_depth);
    int deepest = 0;
    for (const Octree::Node& node : octree.nodes()) {
      deepest = std::max<int>(deepest, node.depth);
      // With primitives this small (to depth 10), a leaf holds more than K only at depth D.
      if (max_depth <= 10 && node.leaf && node.count > static_cast<uint32_t>(max_primitives)) {
        EXPECT_EQ(node.depth, max_depth);
      }
    }
    if (max_depth <= 10) {
      EXPECT_EQ(deepest, max_depth) << max_primitives << " " << max_depth;
    }
    // Every primitive is in the leaf around its centre, and only primitives overlapping it.
    for (uint32_t index = 0; index < scene.primitives().size(); index += 7) {
      Bounds3 box;
      const auto& leaf = octree.leaf_at(scene.primitives()[index].shape->bounds().center(), &box);
      const auto primitives = octree.leaf_primitives(leaf);
      EXPECT_TRUE(std::binary_search(primitives.begin(), primitives.end(), index));
      for (uint32_t other : primitives) {
        const Bounds3 bounds = scene.primitives()[other].shape->bounds();
        const double slack = 1e-5;
        EXPECT_TRUE(bounds.lower.x <= box.upper.x + slack && bounds.upper.x >= box.lower.x - slack &&
                    bounds.lower.y <= box.upper.y + slack && bounds.upper.y >= box.lower.y - slack &&
                    bounds.lower.z <= box.upper.z + slack && bounds.upper.z >= box.lower.z - slack);
      }
    }
  }
  EXPECT_THROW(Octree(-1, 10), std::invalid_argument);
  EXPECT_THROW(Octree(8, -1), std::invalid_argument);
  EXPECT_THROW(Octree(8, 33), std::invalid_argument);
}

TEST(Octree, StopsCuttingWhatCannotBeSeparated) {
  // Identical spheres: every child meeting one meets all, so the root stays a leaf.
  SubdivisionScene same(2);
  for (int i = 0; i < 50; ++i) same.add_sphere({1, 2, 3}, 0.5);
  Octree octree;
  octree.build(same.primitives());
  EXPECT_EQ(octree.nodes().size(), 1u);
  EXPECT_EQ(octree.nodes()[0].count, 50u);

  // Large triangles overlapping everything, among small spheres: the tree stays small.
  SubdivisionScene large(3);
  const Bounds3 region{{-10, -10, -10}, {10, 10, 10}};
  for (int i = 0; i < 40; ++i)
    large.add_triangle(large.point(region), large.point(region), large.point(region));
  large.add_random_spheres(3000, region, 0.01, 0.05);
  Octree deep(1, 32);
  EXPECT_GT(testing::expect_same_as_list(deep, large.primitives(), large.rays(3000, region)), 1000);
  expect_respects(deep, 1, 32);
  EXPECT_LT(deep.nodes().size(), 200000u);
}

struct Settings {
  int max_primitives, max_depth;
};
const Settings kSettings[] = {{8, 10}, {1, 32}, {2, 4}, {100, 10}};

TEST(Octree, MatchesTheListOnRandomSpheres) {
  SubdivisionScene scene(4);
  const Bounds3 region = testing::random_spheres_scene(scene);
  for (const Settings& settings : kSettings) {
    Octree octree(settings.max_primitives, settings.max_depth);
    EXPECT_GT(testing::expect_same_as_list(octree, scene.primitives(), scene.rays(3000, region)), 800);
  }
}

TEST(Octree, MatchesTheListOnRandomTriangles) {
  SubdivisionScene scene(5);
  const Bounds3 region = testing::random_triangles_scene(scene);
  for (const Settings& settings : kSettings) {
    Octree octree(settings.max_primitives, settings.max_depth);
    EXPECT_GT(testing::expect_same_as_list(octree, scene.primitives(), scene.rays(3000, region)), 800);
  }
}

TEST(Octree, MatchesTheListOnLongThinPrimitives) {
  SubdivisionScene scene(6);
  const Bounds3 region = testing::long_thin_scene(scene);
  for (const Settings& settings : kSettings) {
    Octree octree(settings.max_primitives, settings.max_depth);
    EXPECT_GT(testing::expect_same_as_list(octree, scene.primitives(), scene.rays(3000, region)), 400);
  }
}

TEST(Octree, MatchesTheListOnCoincidentDuplicates) {
  SubdivisionScene scene(7);
  const Bounds3 region = testing::coincident_scene(scene);
  for (const Settings& settings : kSettings) {
    Octree octree(settings.max_primitives, settings.max_depth);
    EXPECT_GT(testing::expect_same_as_list(octree, scene.primitives(), scene.rays(3000, region)), 800);
  }
}

TEST(Octree, MatchesTheListWithEverythingInOnePoint) {
  SubdivisionScene scene(8);
  const Bounds3 region = testing::one_point_scene(scene);
  for (const Settings& settings : kSettings) {
    Octree octree(settings.max_primitives, settings.max_depth);
    EXPECT_GT(testing::expect_same_as_list(octree, scene.primitives(), scene.rays(2000, region)), 400);
  }
}

TEST(Octree, MatchesTheListOnAFlatScene) {
  SubdivisionScene scene(9);
  const Bounds3 region = testing::flat_scene(scene);
  std::vector<Ray> rays = scene.rays(3000, region);
  for (int i = 0; i < 300; ++i) {  // rays in the plane of the triangles (edge-on: no hit)
    const Vec3 d = scene.direction();
    rays.push_back({{scene.uniform(-12, 12), 0, scene.uniform(-12, 12)}, normalize(Vec3{d.x, 0, d.z})});
  }
  for (const Settings& settings : kSettings) {
    Octree octree(settings.max_primitives, settings.max_depth);
    EXPECT_GT(testing::expect_same_as_list(octree, scene.primitives(), rays), 500);
    expect_respects(octree, settings.max_primitives, settings.max_depth);
  }
}

TEST(Octree, MatchesTheListWithPlanes) {
  SubdivisionScene scene(10);
  const Bounds3 region = testing::planes_scene(scene);
  for (const Settings& settings : kSettings) {
    Octree octree(settings.max_primitives, settings.max_depth);
    EXPECT_GT(testing::expect_same_as_list(octree, scene.primitives(), scene.rays(3000, region)), 1500);
  }
}

TEST(Octree, EmptyAndPlanesOnlyScenes) {
  SubdivisionScene empty(11);
  Octree octree;
  const Bounds3 region{{-1, -1, -1}, {1, 1, 1}};
  EXPECT_EQ(testing::expect_same_as_list(octree, empty.primitives(), empty.rays(200, region)), 0);
  EXPECT_TRUE(octree.nodes().empty());

  SubdivisionScene planes(12);
  planes.add_plane({0, 0, 0}, {0, 1, 0});
  planes.add_plane({0, 0, 0}, {0, 1, 0});  // coincident: index 0 wins
  planes.add_plane({0, 0.5, 0}, {1, 1, 0});
  EXPECT_GT(testing::expect_same_as_list(octree, planes.primitives(), planes.rays(1000, region)), 300);
}

// 000 §5.7.2: a hit found in a leaf but lying beyond it is not final.
TEST(Octree, AHitBeyondTheCurrentLeafWaitsForNearerPrimitives) {
  const Ray ray = testing::thin_triangle_ray();
  const Vec3 far_hit{9, 0, 0};  // where the ray meets the thin triangle (primitive 0)
  for (const double sphere_x : {-100.0, 5.0, 8.95}) {
    SubdivisionScene scene(13);
    testing::thin_triangle_scene(scene);
    const uint32_t sphere = sphere_x > -100 ? scene.add_sphere({sphere_x, 0, 0}, 0.02) : 0;
    Octree octree(2, 10);
    octree.build(scene.primitives());
    // The triangle is in the leaf where the ray enters; its hit lies in another leaf.
    double t_enter = 0, t_exit = 0;
    ASSERT_TRUE(octree.root_bounds().intersect(ray, t_enter, t_exit));
    const Octree::Node& first = octree.leaf_at(ray.at(t_enter));
    const auto primitives = octree.leaf_primitives(first);
    ASSERT_TRUE(std::binary_search(primitives.begin(), primitives.end(), 0u));
    ASSERT_NE(&first, &octree.leaf_at(far_hit));
    if (sphere_x == 8.95) {  // the nearer primitive lies in the very leaf of the far hit
      ASSERT_EQ(&octree.leaf_at({sphere_x - 0.02, 0, 0}), &octree.leaf_at(far_hit));
    }

    Intersection hit;
    ASSERT_TRUE(octree.intersect(ray, hit));
    if (sphere_x > -100) {
      EXPECT_EQ(hit.primitive, sphere);
      EXPECT_NEAR(hit.surface.t, sphere_x - 0.02 + 1, 1e-12);
    } else {
      EXPECT_EQ(hit.primitive, 0u);
      EXPECT_NEAR(hit.surface.t, 10, 1e-12);
    }
    testing::expect_same_as_list(octree, scene.primitives(), std::vector<Ray>{ray});
  }
}

TEST(Octree, IsSafeToShareBetweenThreads) {
  SubdivisionScene scene(14);
  const Bounds3 region = testing::long_thin_scene(scene);
  const std::vector<Ray> rays = scene.rays(20000, region);
  Octree octree;
  octree.build(scene.primitives());
  EXPECT_EQ(testing::mismatches_when_shared(octree, scene.primitives(), rays), 0);
}

TEST(Octree, ReportsItsFigures) {
  SubdivisionScene scene(15);
  testing::planes_scene(scene);
  Octree octree;
  octree.build(scene.primitives());
  const AcceleratorReport report = octree.report();
  const auto figure = [&](const std::string& name) { return testing::report_figure(report, name); };
  EXPECT_EQ(figure("nodes"), static_cast<double>(octree.nodes().size()));
  EXPECT_GT(figure("leaves"), 8);
  EXPECT_LE(figure("max depth"), 10);
  EXPECT_EQ(figure("unbounded"), 3);
  EXPECT_GE(figure("references"), 500);
  EXPECT_GE(figure("primitives per non-empty leaf"), 1);
  EXPECT_GT(report.bytes, 0u);
  EXPECT_EQ(Octree().name(), "octree");
}

}  // namespace
}  // namespace candela
