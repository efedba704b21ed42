// Every accelerator answers exactly as the brute-force list (SPEC §5): on random scenes of
// spheres, triangles and mixed shapes — degenerate, coincident and transformed ones included —
// and random rays, the same nearest primitive at the same distance, and the same occlusion.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "accel/accelerator_registry.h"
#include "accel/primitive_list.h"
#include "geometry/box.h"
#include "geometry/cone.h"
#include "geometry/cylinder.h"
#include "geometry/disc.h"
#include "geometry/plane.h"
#include "geometry/polygon.h"
#include "geometry/sphere.h"
#include "geometry/torus.h"
#include "geometry/transformed_shape.h"
#include "geometry/triangle_mesh.h"
#include "math/constants.h"
#include "math/pcg32.h"

namespace candela {
namespace {

class RandomScene {
 public:
  explicit RandomScene(uint64_t seed) : rng_(seed, 7) {}

  double uniform(double lower, double upper) { return lower + (upper - lower) * rng_.next_double(); }
  Vec3 point(double extent) {
    return {uniform(-extent, extent), uniform(-extent, extent), uniform(-extent, extent)};
  }
  Vec3 direction() {
    const double z = uniform(-1, 1), phi = uniform(0, 2 * kPi), r = std::sqrt(std::max(0.0, 1 - z * z));
    return {r * std::cos(phi), r * std::sin(phi), z};
  }

  void add(std::unique_ptr<Shape> shape) {
    primitives_.push_back({shape.get(), 0, object_});
    shapes_.push_back(std::move(shape));
  }
  void next_object() { ++object_; }

  void add_spheres(int count, double extent, double radius) {
    for (int i = 0; i < count; ++i, next_object())
      add(std::make_unique<Sphere>(point(extent), uniform(0.1, 1) * radius));
  }
  // One mesh object of random triangles (some tiny, some long and thin).
  void add_triangle_soup(int count, double extent, double size) {
    auto mesh = std::make_shared<TriangleMesh>();
    for (int i = 0; i < count; ++i) {
      const Vec3 a = point(extent);
      const double scale = (i % 10 == 0) ? size * 8 : (i % 10 == 1 ? size * 1e-6 : size);
      mesh->positions.push_back(a);
      mesh->positions.push_back(a + point(scale));
      mesh->positions.push_back(a + point(scale));
      const auto base = static_cast<uint32_t>(3 * i);
      mesh->triangles.push_back({base, base + 1, base + 2});
    }
    for (auto& shape : make_triangles(mesh)) add(std::move(shape));
    next_object();
  }
  void add_mixed(int count, double extent) {
    for (int i = 0; i < count; ++i, next_object()) {
      const Vec3 c = point(extent);
      switch (i % 7) {
        case 0:
          add(std::make_unique<Box>(c, c + Vec3{uniform(0.1, 2), uniform(0.1, 2), uniform(0.1, 2)}));
          break;
        case 1:
          add(std::make_unique<Cylinder>(c, c + point(2), uniform(0.1, 0.5), i % 2 == 0));
          break;
        case 2:
          add(std::make_unique<Cone>(c, uniform(0.1, 0.6), c + point(2), uniform(0, 0.3), true));
          break;
        case 3:
          add(std::make_unique<Torus>(c, direction(), uniform(0.5, 1), uniform(0.05, 0.3)));
          break;
        case 4:
          add(std::make_unique<Disc>(c, direction(), uniform(0.2, 1), 0.0));
          break;
        case 5: {
          Vec3 u, v;
          const Vec3 n = direction();
          orthonormal_basis(n, u, v);
          add(std::make_unique<Polygon>(std::vector<Vec3>{c, c + u * 2, c + u + v, c + v * 2}));  // concave
          break;
        }
        case 6: {
          const Transform transform = Transform::translate(c) *
                                      Transform::rotate(uniform(0, 360), direction()) *
                                      Transform::scale({uniform(0.2, 2), uniform(0.2, 2), uniform(0.2, 2)});
          add(std::make_unique<TransformedShape>(std::make_unique<Sphere>(Vec3{0, 0, 0}, 1.0), transform));
          break;
        }
      }
    }
  }
  // Exact duplicates of existing primitives: coincident surfaces test the tie rule.
  void add_duplicates(int count) {
    const std::size_t existing = shapes_.size();
    for (int i = 0; i < count && existing > 0; ++i, next_object()) {
      const Shape* original = shapes_[rng_.next_uint() % existing].get();
      if (const auto* sphere = dynamic_cast<const Sphere*>(original))
        add(std::make_unique<Sphere>(sphere->center(), sphere->radius()));
      else if (const auto* triangle = dynamic_cast<const MeshTriangle*>(original))
        add(std::make_unique<MeshTriangle>(triangle->shared_mesh(), triangle->triangle_index()));
    }
  }
  void add_plane() {
    add(std::make_unique<Plane>(Vec3{0, -20, 0}, Vec3{0, 1, 0}));
    next_object();
  }

  std::vector<Ray> rays(int count, double extent) {
    std::vector<Ray> rays;
    for (int i = 0; i < count; ++i) {
      Ray ray{point(extent * 1.5), direction()};
      if (i % 5 == 0) ray.direction = normalize(point(extent * 0.5) - ray.origin);  // aimed inside
      if (i % 17 == 0) ray.direction = Vec3{0, 0, (i % 2) ? 1.0 : -1.0};            // zero components
      if (i % 13 == 0) ray.t_max = uniform(0.5, extent);                            // shadow-like
      rays.push_back(ray);
    }
    return rays;
  }
  const std::vector<Primitive>& primitives() const { return primitives_; }

 private:
  Pcg32 rng_;
  std::vector<std::unique_ptr<Shape>> shapes_;
  std::vector<Primitive> primitives_;
  uint32_t object_ = 0;
};

struct Candidate {
  std::string label;
  std::unique_ptr<Accelerator> accelerator;
};

std::vector<Candidate> every_accelerator() {
  std::vector<Candidate> candidates;
  for (const AcceleratorEntry& entry : accelerator_entries())  // bvh-fast's own tests: src/accel/bvh_test.cpp
    if (entry.exact) candidates.push_back({std::string(entry.name), create_default_accelerator(entry)});
  for (const auto kind : {BoundingVolumeKind::sphere, BoundingVolumeKind::box, BoundingVolumeKind::slabs})
    candidates.push_back(
        {"list+" + std::string(kBoundingVolumeNames.name(kind)), std::make_unique<PrimitiveList>(kind)});
  return candidates;
}

void expect_all_agree(const RandomScene& scene, const std::vector<Ray>& rays) {
  PrimitiveList reference;
  reference.build(scene.primitives());
  for (Candidate& candidate : every_accelerator()) {
    candidate.accelerator->build(scene.primitives());
    int mismatches = 0;
    for (std::size_t i = 0; i < rays.size() && mismatches < 5; ++i) {
      Intersection expected, got;
      const bool expected_hit = reference.intersect(rays[i], expected);
      const bool hit = candidate.accelerator->intersect(rays[i], got);
      bool same = expected_hit == hit;
      if (same && hit)
        same = expected.primitive == got.primitive &&
               std::fabs(expected.surface.t - got.surface.t) <= 1e-9 * std::max(1.0, expected.surface.t);
      same = same && reference.occluded(rays[i]) == candidate.accelerator->occluded(rays[i]);
      if (!same) {
        ++mismatches;
        ADD_FAILURE() << candidate.label << " ray " << i << ": list " << expected_hit << " prim "
                      << expected.primitive << " t " << expected.surface.t << ", got " << hit << " prim "
                      << got.primitive << " t " << got.surface.t;
      }
    }
  }
}

TEST(AcceleratorProperty, RandomSpheres) {
  RandomScene scene(1);
  scene.add_spheres(300, 10, 1.0);
  expect_all_agree(scene, scene.rays(3000, 10));
}

TEST(AcceleratorProperty, RandomTriangles) {
  RandomScene scene(2);
  scene.add_triangle_soup(2000, 10, 1.0);
  expect_all_agree(scene, scene.rays(3000, 10));
}

TEST(AcceleratorProperty, MixedTransformedDegenerateAndCoincident) {
  RandomScene scene(3);
  scene.add_spheres(50, 8, 1.5);
  scene.add_triangle_soup(300, 8, 1.5);
  scene.add_mixed(140, 8);
  scene.add_duplicates(60);
  scene.add_plane();
  expect_all_agree(scene, scene.rays(4000, 8));
}

TEST(AcceleratorProperty, EverythingInOnePlace) {
  RandomScene scene(4);
  for (int i = 0; i < 50; ++i) {
    scene.add(std::make_unique<Sphere>(Vec3{1, 2, 3}, 0.5));  // 50 coincident spheres
    scene.next_object();
  }
  expect_all_agree(scene, scene.rays(1000, 4));
}

TEST(AcceleratorProperty, EmptyScene) {
  RandomScene scene(5);
  expect_all_agree(scene, scene.rays(100, 4));
}

// Primitives no ray can report stay out of every structure — zero-area triangles, and
// copies of a triangle (the same corners, in other meshes or objects) that lose every tie to the
// first. 2,000 coincident copies made every ray meeting them test them all.
TEST(AcceleratorProperty, DegenerateAndRepeatedTrianglesAreLeftOut) {
  RandomScene scene(6);
  const std::vector<Vec3> corners{{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};
  for (int copy = 0; copy < 2000; ++copy) {
    auto mesh = std::make_shared<TriangleMesh>();
    mesh->positions = corners;
    mesh->triangles = {{0, 1, 2}};
    scene.add(std::make_unique<MeshTriangle>(mesh, 0));
    scene.next_object();
  }
  auto flat = std::make_shared<TriangleMesh>();
  flat->positions = {{-1, 0, 0}, {0, 0, 0}, {1, 0, 0}};
  for (int i = 0; i < 50; ++i) flat->triangles.push_back({0, 1, 2});
  for (uint32_t t = 0; t < 50; ++t) scene.add(std::make_unique<MeshTriangle>(flat, t));
  EXPECT_EQ(reportable_primitives(scene.primitives()), std::vector<uint32_t>{0});
  // Each structure is the one built over the first triangle alone.
  std::vector<Candidate> alone = every_accelerator();
  std::vector<Candidate> all = every_accelerator();
  for (std::size_t c = 0; c < all.size(); ++c) {
    alone[c].accelerator->build(std::span(scene.primitives()).first(1));
    all[c].accelerator->build(scene.primitives());
    const AcceleratorReport expected = alone[c].accelerator->report(), got = all[c].accelerator->report();
    EXPECT_EQ(got.figures, expected.figures) << all[c].label;
    EXPECT_EQ(got.bytes, expected.bytes) << all[c].label;
    Intersection hit;
    ASSERT_TRUE(all[c].accelerator->intersect(Ray{{0, 0, 2}, {0, 0, -1}}, hit)) << all[c].label;
    EXPECT_EQ(hit.primitive, 0u) << all[c].label;
  }
  expect_all_agree(scene, scene.rays(500, 2));
}

}  // namespace
}  // namespace candela
