// Scenes and rays shared by the uniform grid and octree tests: every answer of a spatial
// subdivision is compared with the brute-force list (same primitive, same t bit for bit, same
// occlusion; accelerator.h).
#pragma once

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <span>
#include <vector>

#include "accel/accelerator.h"
#include "accel/primitive_list.h"
#include "geometry/plane.h"
#include "geometry/sphere.h"
#include "geometry/triangle_mesh.h"
#include "math/constants.h"
#include "math/pcg32.h"

namespace candela::testing {

class SubdivisionScene {
 public:
  explicit SubdivisionScene(uint64_t seed) : rng_(seed, 11) {}

  double uniform(double lower, double upper) { return lower + (upper - lower) * rng_.next_double(); }
  Vec3 point(const Bounds3& region) {
    return {uniform(region.lower.x, region.upper.x), uniform(region.lower.y, region.upper.y),
            uniform(region.lower.z, region.upper.z)};
  }
  Vec3 direction() {
    const double z = uniform(-1, 1), phi = uniform(0, 2 * kPi), r = std::sqrt(std::max(0.0, 1 - z * z));
    return {r * std::cos(phi), r * std::sin(phi), z};
  }

  uint32_t add(std::unique_ptr<Shape> shape) {
    const auto index = static_cast<uint32_t>(primitives_.size());
    primitives_.push_back({shape.get(), 0, index});
    shapes_.push_back(std::move(shape));
    return index;
  }
  uint32_t add_sphere(const Vec3& center, double radius) {
    return add(std::make_unique<Sphere>(center, radius));
  }
  void add_plane(const Vec3& point, const Vec3& normal) { add(std::make_unique<Plane>(point, normal)); }
  // Every non-degenerate triangle of the mesh; returns the index of the first.
  uint32_t add_mesh(std::shared_ptr<const TriangleMesh> mesh) {
    const auto first = static_cast<uint32_t>(primitives_.size());
    for (auto& shape : make_triangles(std::move(mesh))) add(std::move(shape));
    return first;
  }
  uint32_t add_triangle(const Vec3& a, const Vec3& b, const Vec3& c) {
    auto mesh = std::make_shared<TriangleMesh>();
    mesh->positions = {a, b, c};
    mesh->triangles = {{0, 1, 2}};
    return add_mesh(mesh);
  }

  void add_random_spheres(int count, const Bounds3& region, double min_radius, double max_radius) {
    for (int i = 0; i < count; ++i) add_sphere(point(region), uniform(min_radius, max_radius));
  }
  // One mesh of independent random triangles of about the given size.
  void add_random_triangles(int count, const Bounds3& region, double size) {
    auto mesh = std::make_shared<TriangleMesh>();
    const Bounds3 corner{{-size, -size, -size}, {size, size, size}};
    for (int i = 0; i < count; ++i) {
      const Vec3 a = point(region);
      const auto base = static_cast<uint32_t>(mesh->positions.size());
      mesh->positions.insert(mesh->positions.end(), {a, a + point(corner), a + point(corner)});
      mesh->triangles.push_back({base, base + 1, base + 2});
    }
    add_mesh(mesh);
  }

  // Rays around region: origins outside (aimed into it, or at a primitive's bounds) and
  // inside; random, axis-aligned and zero-component directions; some with a finite t_max or a
  // positive t_min.
  std::vector<Ray> rays(int count, const Bounds3& region) {
    const Vec3 center = region.center();
    const double radius = std::max(1e-3, length(region.diagonal()));
    const Bounds3 around{center - Vec3{radius, radius, radius}, center + Vec3{radius, radius, radius}};
    std::vector<Ray> rays;
    for (int i = 0; i < count; ++i) {
      Ray ray;
      const bool inside = i % 3 == 1;
      ray.origin = inside ? point(region) : center + direction() * (1.5 * radius);
      switch (i % 6) {
        case 0:
          ray.direction = normalize(point(region) - ray.origin);
          break;
        case 1:
          ray.direction = direction();
          break;
        case 2: {  // along an axis, either way
          Vec3 axis{0, 0, 0};
          axis[static_cast<int>(rng_.next_uint() % 3)] = (rng_.next_uint() & 1) ? 1.0 : -1.0;
          ray.direction = axis;
          if (!inside) ray.origin = point(around);
          break;
        }
        case 3: {  // one zero component
          Vec3 d = direction();
          d[static_cast<int>(rng_.next_uint() % 3)] = 0;
          ray.direction = normalize(d);
          if (!inside) ray.origin = point(around);
          break;
        }
        case 4:
          if (!primitives_.empty()) {
            const Bounds3 bounds = primitives_[rng_.next_uint() % primitives_.size()].shape->bounds();
            ray.direction = bounds.is_finite() ? normalize(bounds.center() - ray.origin) : direction();
          } else {
            ray.direction = direction();
          }
          break;
        default:
          ray.direction = normalize(point(region) - ray.origin);
          ray.t_min = uniform(0, 0.5 * radius);
          ray.t_max = ray.t_min + uniform(0, 2 * radius);
          break;
      }
      if (!(length(ray.direction) > 0.5)) ray.direction = {1, 0, 0};
      rays.push_back(ray);
    }
    return rays;
  }

  std::span<const Primitive> primitives() const { return primitives_; }
  Pcg32& rng() { return rng_; }

 private:
  Pcg32 rng_;
  std::vector<std::unique_ptr<Shape>> shapes_;
  std::vector<Primitive> primitives_;
};

// The scenes both subdivisions are checked on; each returns the region to aim rays at.
inline Bounds3 random_spheres_scene(SubdivisionScene& scene) {
  const Bounds3 region{{-10, -10, -10}, {10, 10, 10}};
  scene.add_random_spheres(400, region, 0.1, 1.0);
  return region;
}

inline Bounds3 random_triangles_scene(SubdivisionScene& scene) {
  const Bounds3 region{{-10, -10, -10}, {10, 10, 10}};
  scene.add_random_triangles(1500, region, 1.0);
  return region;
}

// Long thin triangles crossing the whole scene (many voxels each), along the axes and slanted,
// among small spheres: hits found in one voxel often lie in a later one.
inline Bounds3 long_thin_scene(SubdivisionScene& scene) {
  const Bounds3 region{{-10, -10, -10}, {10, 10, 10}};
  for (int i = 0; i < 60; ++i) {
    const Vec3 a = scene.point(region), b = scene.point(region);
    const Vec3 side = normalize(cross(b - a, scene.direction())) * scene.uniform(0.01, 0.2);
    scene.add_triangle(a, b, a + side);
  }
  for (int i = 0; i < 30; ++i) {
    const int axis = i % 3;
    Vec3 a = scene.point(region), b = a;
    a[axis] = -10;
    b[axis] = 10;
    scene.add_triangle(a, b, b + scene.direction() * 0.05);
  }
  scene.add_random_spheres(200, region, 0.05, 0.3);
  return region;
}

// Exact duplicates (the tie rule: the lowest index wins at equal t).
inline Bounds3 coincident_scene(SubdivisionScene& scene) {
  const Bounds3 region{{-5, -5, -5}, {5, 5, 5}};
  scene.add_random_spheres(100, region, 0.2, 1.0);
  for (int i = 0; i < 40; ++i) {
    const Sphere& original =
        dynamic_cast<const Sphere&>(*scene.primitives()[scene.rng().next_uint() % 100].shape);
    scene.add_sphere(original.center(), original.radius());
  }
  auto mesh = std::make_shared<TriangleMesh>();
  for (int i = 0; i < 30; ++i) {
    const Vec3 a = scene.point(region);
    mesh->positions.insert(mesh->positions.end(), {a, a + scene.direction() * 2, a + scene.direction() * 2});
  }
  for (uint32_t i = 0; i < 30; ++i) {
    for (int copy = 0; copy < 3; ++copy) mesh->triangles.push_back({3 * i, 3 * i + 1, 3 * i + 2});
    mesh->triangles.push_back({3 * i + 2, 3 * i, 3 * i + 1});  // same triangle, other corner order
  }
  scene.add_mesh(mesh);
  scene.add_mesh(mesh);  // the same mesh twice
  return region;
}

// Everything around one point: identical and concentric spheres, tiny triangles.
inline Bounds3 one_point_scene(SubdivisionScene& scene) {
  const Vec3 center{1, 2, 3};
  for (int i = 0; i < 30; ++i) scene.add_sphere(center, 0.5);
  for (int i = 0; i < 10; ++i) scene.add_sphere(center, scene.uniform(0.1, 1));
  const Bounds3 tiny{center - Vec3{1e-9, 1e-9, 1e-9}, center + Vec3{1e-9, 1e-9, 1e-9}};
  scene.add_random_triangles(10, tiny, 1e-9);
  return {center - Vec3{1, 1, 1}, center + Vec3{1, 1, 1}};
}

// All triangles in the plane y = 0 (a zero extent along y).
inline Bounds3 flat_scene(SubdivisionScene& scene) {
  auto mesh = std::make_shared<TriangleMesh>();
  for (uint32_t i = 0; i < 800; ++i) {
    for (int k = 0; k < 3; ++k) {
      const Vec3 c{scene.uniform(-10, 10), 0, scene.uniform(-10, 10)};
      mesh->positions.push_back(k == 0 ? c : mesh->positions[3 * i] + Vec3{c.x * 0.1, 0, c.z * 0.1});
    }
    mesh->triangles.push_back({3 * i, 3 * i + 1, 3 * i + 2});
  }
  scene.add_mesh(mesh);
  return {{-10, -1, -10}, {10, 1, 10}};
}

// Spheres and triangles with planes (unbounded: tested on every ray).
inline Bounds3 planes_scene(SubdivisionScene& scene) {
  const Bounds3 region{{-10, -10, -10}, {10, 10, 10}};
  scene.add_plane({0, -8, 0}, {0, 1, 0});
  scene.add_random_spheres(200, region, 0.1, 1.0);
  scene.add_plane({0, 0, 0}, normalize(Vec3{1, 2, 3}));
  scene.add_random_triangles(300, region, 1.0);
  scene.add_plane({0, 0, 9}, {0, 0, -1});
  return region;
}

// The case of 000 §5.7.2: primitive 0, a long thin slanted triangle, lies in the voxel where a
// ray along +x (from origin(), through y = z = 0) enters the scene, but the ray hits it only at
// x = 9, many voxels later. Tiny spheres along y = z = 3 make the subdivision fine along x.
inline Ray thin_triangle_ray() {
  return {{-1, 0, 0}, {1, 0, 0}};
}
inline void thin_triangle_scene(SubdivisionScene& scene) {
  scene.add_triangle({0, 1, -1}, {0, 1, 1}, {10, -1.0 / 9.0, 0});  // plane x + 9 y = 9
  for (int i = 0; i <= 100; ++i) scene.add_sphere({0.1 * i, 3, 3}, 0.01);
}

// Builds the accelerator and compares it with the list on every ray: nearest hit (primitive and
// t exactly), occlusion over the whole ray, and occlusion up to the list's hit (strict t_max).
// Returns how many rays hit something (so a test can check it exercised hits).
inline int expect_same_as_list(Accelerator& accelerator, std::span<const Primitive> primitives,
                               std::span<const Ray> rays) {
  PrimitiveList reference;
  reference.build(primitives);
  accelerator.build(primitives);
  int hits = 0, mismatches = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const Ray& ray = rays[i];
    Intersection expected, actual;
    const bool expected_hit = reference.intersect(ray, expected);
    const bool actual_hit = accelerator.intersect(ray, actual);
    bool same = expected_hit == actual_hit;
    if (same && expected_hit)
      same = expected.primitive == actual.primitive && expected.surface.t == actual.surface.t;
    same = same && reference.occluded(ray) == accelerator.occluded(ray);
    if (expected_hit) {
      ++hits;
      Ray shorter = ray;
      shorter.t_max = expected.surface.t;
      same = same && reference.occluded(shorter) == accelerator.occluded(shorter);
    }
    if (!same && ++mismatches <= 5) {
      ADD_FAILURE() << accelerator.name() << " ray " << i << " (origin " << ray.origin << ", direction "
                    << ray.direction << ", t in (" << ray.t_min << ", " << ray.t_max << ")): list "
                    << expected_hit << " primitive " << expected.primitive << " t " << expected.surface.t
                    << "; " << accelerator.name() << " " << actual_hit << " primitive " << actual.primitive
                    << " t " << actual.surface.t;
    }
  }
  EXPECT_EQ(mismatches, 0) << "of " << rays.size() << " rays";
  return hits;
}

// Traces the rays from many threads at once against one shared accelerator; returns the number
// of rays whose nearest hit differs from the list's.
inline int mismatches_when_shared(const Accelerator& accelerator, std::span<const Primitive> primitives,
                                  const std::vector<Ray>& rays) {
  PrimitiveList list;
  list.build(primitives);
  std::vector<int> mismatches(rays.size(), 0);
  tbb::parallel_for(std::size_t{0}, rays.size(), [&](std::size_t i) {
    Intersection expected, actual;
    const bool expected_hit = list.intersect(rays[i], expected);
    const bool actual_hit = accelerator.intersect(rays[i], actual);
    mismatches[i] =
        expected_hit != actual_hit ||
        (expected_hit && (expected.primitive != actual.primitive || expected.surface.t != actual.surface.t));
  });
  return static_cast<int>(std::count(mismatches.begin(), mismatches.end(), 1));
}

// The named figure of a quality report (a test failure when it is missing).
inline double report_figure(const AcceleratorReport& report, const std::string& name) {
  for (const auto& [key, value] : report.figures)
    if (key == name) return value;
  ADD_FAILURE() << "no figure " << name;
  return 0.0;
}

}  // namespace candela::testing
