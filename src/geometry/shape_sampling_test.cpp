// Sampling points on shapes for area emitters (SPEC §12, Shape::sample_area / sample_from):
// for every shape, sampled points lie on the surface where intersect finds them, with the normal
// intersect reports; area() is the analytic area; the area density integrates to 1 (the mean of
// 1/pdf is the area, and finite differences of the sampling map give 1/pdf pointwise);
// sample_from's solid-angle density equals pdf_from at the hit found by tracing toward the
// sample, and integrates to the solid angle the surface covers (counted with multiplicity:
// E[1/pdf] = ∫ (crossings along ω) dω, estimated independently by uniform directions).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "geometry/box.h"
#include "geometry/cone.h"
#include "geometry/cylinder.h"
#include "geometry/disc.h"
#include "geometry/plane.h"
#include "geometry/polygon.h"
#include "geometry/quad.h"
#include "geometry/sphere.h"
#include "geometry/torus.h"
#include "geometry/transformed_shape.h"
#include "geometry/triangle_mesh.h"
#include "math/constants.h"
#include "math/pcg32.h"

namespace candela {
namespace {

Vec3 uniform_direction(Pcg32& rng) {
  const double u = rng.next_double(), v = rng.next_double();
  const double z = 1 - 2 * u;
  const double r = 2 * std::sqrt(u * (1 - u));
  const double phi = 2 * kPi * v;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// Mean and standard error of a running sum.
struct Mean {
  double sum = 0, sum_squares = 0;
  int count = 0;
  void add(double x) {
    sum += x;
    sum_squares += x * x;
    ++count;
  }
  double mean() const { return sum / count; }
  double error() const {
    const double m = mean();
    return std::sqrt(std::max(0.0, sum_squares / count - m * m) / count);
  }
};

// How many times the ray from origin along direction crosses the surface.
int crossings(const Shape& shape, const Vec3& origin, const Vec3& direction, double size) {
  Ray ray{origin, direction, 0, kInfinity};
  SurfaceHit hit;
  int count = 0;
  while (count < 16 && shape.intersect(ray, hit)) {
    ++count;
    ray.t_min = hit.t + 1e-7 * size;
  }
  return count;
}

struct Check {
  double area;                    // the analytic area (or the estimate to compare with)
  double area_tolerance = 1e-12;  // relative
  bool uniform = true;            // every sample has pdf 1/area
  double size = 1;                // the shape's scale, for tolerances
  std::vector<Vec3> references;   // points to sample from
  bool cone_sampled = false;      // sample_from sees one layer only (the sphere from outside)
};

void check_shape(const Shape& shape, const Check& check, uint64_t seed) {
  SCOPED_TRACE(std::string(shape.type_name()));
  const double size = check.size;
  EXPECT_NEAR(shape.area(), check.area, check.area_tolerance * check.area);
  Pcg32 rng(seed, 7);

  // Points on the surface, normals as intersect reports them, pdf_area at the hit.
  Mean inverse_pdf;
  for (int i = 0; i < 4000; ++i) {
    const Vec2 u{rng.next_double(), rng.next_double()};
    SurfaceSample sample;
    ASSERT_TRUE(shape.sample_area(u, sample));
    ASSERT_GT(sample.pdf, 0);
    EXPECT_NEAR(length(sample.normal), 1, 1e-12);
    if (check.uniform) {
      EXPECT_NEAR(sample.pdf * check.area, 1, check.area_tolerance + 1e-12);
    }
    inverse_pdf.add(1 / sample.pdf);
    const Ray ray{sample.position + sample.normal * (1e-6 * size), -sample.normal, 0, kInfinity};
    SurfaceHit hit;
    ASSERT_TRUE(shape.intersect(ray, hit)) << "sample " << i << " at " << sample.position;
    EXPECT_NEAR(length(hit.position - sample.position), 0, 1e-9 * size) << "sample " << i;
    EXPECT_GT(dot(hit.geometric_normal, sample.normal), 1 - 1e-9)
        << "sample " << i << " at " << sample.position;
    EXPECT_NEAR(shape.pdf_area(hit) / sample.pdf, 1, 1e-7) << "sample " << i;
  }
  // ∫ pdf dA = 1: the mean of 1/pdf is the area.
  EXPECT_NEAR(inverse_pdf.mean(), check.area, 4 * inverse_pdf.error() + 1e-9 * check.area);

  // Pointwise: |∂p/∂u × ∂p/∂v| = 1/pdf (the unit square has density 1), by forward differences.
  int compared = 0;
  for (int i = 0; i < 300; ++i) {
    const Vec2 u{0.01 + 0.98 * rng.next_double(), 0.01 + 0.98 * rng.next_double()};
    const double h = 1e-7;
    SurfaceSample s0, s1, s2;
    ASSERT_TRUE(shape.sample_area(u, s0));
    ASSERT_TRUE(shape.sample_area({u.x + h, u.y}, s1));
    ASSERT_TRUE(shape.sample_area({u.x, u.y + h}, s2));
    // Straddling a part boundary or a kink of the map: not comparable.
    if (length(s1.normal - s0.normal) > 1e-4 || length(s2.normal - s0.normal) > 1e-4) continue;
    if (length(s1.position - s0.position) > 1e-4 * size || length(s2.position - s0.position) > 1e-4 * size)
      continue;
    const double jacobian = length(cross(s1.position - s0.position, s2.position - s0.position)) / (h * h);
    if (jacobian * s0.pdf < 1e-3) continue;  // a degenerate point of the map (a pole, a centre)
    EXPECT_NEAR(jacobian * s0.pdf, 1, 2e-4) << "u = " << u.x << ", " << u.y;
    ++compared;
  }
  EXPECT_GT(compared, 200);

  for (const Vec3& reference : check.references) {
    SCOPED_TRACE(::testing::Message() << "from " << reference);
    Mean solid_angle;  // E[1/pdf] over sample_from
    int matched = 0;
    for (int i = 0; i < 20000; ++i) {
      const Vec2 u{rng.next_double(), rng.next_double()};
      SurfaceSample sample;
      if (!shape.sample_from(reference, u, sample)) {
        solid_angle.add(0);
        continue;
      }
      ASSERT_GT(sample.pdf, 0);
      solid_angle.add(1 / sample.pdf);
      const Vec3 to_point = sample.position - reference;
      const Ray ray{reference, normalize(to_point), 0, kInfinity};
      SurfaceHit hit;
      if (!shape.intersect(ray, hit)) continue;                            // grazing
      if (length(hit.position - sample.position) > 1e-7 * size) continue;  // behind a nearer layer
      ++matched;
      // The hit and the sample differ by rounding, which the 1/cos of a grazing view amplifies.
      const double cos_light = std::fabs(dot(sample.normal, ray.direction));
      EXPECT_NEAR(shape.pdf_from(reference, hit) / sample.pdf, 1, 1e-8 + 1e-8 / cos_light) << "sample " << i;
    }
    EXPECT_GT(matched, check.cone_sampled ? 19900 : 2000);
    // The solid angle independently: uniform directions, counting every layer crossed (or the
    // first only for cone sampling).
    Mean covered;
    for (int i = 0; i < 40000; ++i) {
      const int count = crossings(shape, reference, uniform_direction(rng), size);
      covered.add(4 * kPi * (check.cone_sampled ? std::min(count, 1) : count));
    }
    EXPECT_NEAR(solid_angle.mean(), covered.mean(),
                4 * std::hypot(solid_angle.error(), covered.error()) + 1e-9);
  }
}

TEST(ShapeSampling, Sphere) {
  const Sphere sphere({1, 2, 3}, 1.5);
  check_shape(sphere, {4 * kPi * 2.25, 1e-12, true, 1.5, {{4, 2, 3}, {1, 2, 3.2}, {-3, 5, 9}}, true}, 1);
  // From outside the cone is sampled with the analytic solid angle 2π(1 − cos θ_max), and
  // from inside or on the sphere area sampling (all checked above with the matching count).
  for (const Vec3& reference : {Vec3{4, 2, 3}, Vec3{1, 2, 3 + 1.5 * (1 + 1e-8)}, Vec3{1e4, -3e4, 2e4}}) {
    const double d = length(reference - sphere.center());
    const double cos_max = std::sqrt(1 - 2.25 / (d * d));
    Pcg32 rng(3, 4);
    int hits = 0;
    for (int i = 0; i < 2000; ++i) {
      SurfaceSample sample;
      ASSERT_TRUE(sphere.sample_from(reference, {rng.next_double(), rng.next_double()}, sample));
      EXPECT_NEAR(1 / sample.pdf, 2 * kPi * (1 - cos_max), 1e-9 * (1 - cos_max) + 1e-12);
      // On the sphere, on the near side, inside the cone.
      EXPECT_NEAR(length(sample.position - sphere.center()), 1.5, 1e-12 * std::max(1.0, d));
      EXPECT_LE(dot(sample.normal, sample.position - reference), 1e-9 * d);
      SurfaceHit hit;
      const Vec3 direction = normalize(sample.position - reference);
      if (sphere.intersect({reference, direction, 0, kInfinity}, hit) &&
          length(hit.position - sample.position) < 1e-9 * d) {
        ++hits;
        EXPECT_EQ(sphere.pdf_from(reference, hit), sample.pdf);  // bit for bit (MIS)
      }
    }
    EXPECT_GE(hits, 1990);
  }
  // A shading point on the sphere (as intersect computes it, possibly an ulp outside) is
  // sampled by area: the points are spread over the sphere, not gathered at the reference.
  Pcg32 rng(9, 9);
  for (int i = 0; i < 200; ++i) {
    const Vec3 direction = uniform_direction(rng);
    SurfaceHit on;
    ASSERT_TRUE(sphere.intersect({sphere.center(), direction, 0, kInfinity}, on));
    SurfaceSample sample;
    ASSERT_TRUE(sphere.sample_from(on.position, {rng.next_double(), rng.next_double()}, sample));
    const Vec3 to_point = sample.position - on.position;
    const double d2 = length_squared(to_point);
    EXPECT_NEAR(sample.pdf, d2 / (sphere.area() * std::fabs(dot(sample.normal, to_point)) / std::sqrt(d2)),
                1e-9 * sample.pdf);
  }
}

TEST(ShapeSampling, QuadAndMeshTriangle) {
  const Quad quad({1, 0, 0}, {2, 0, 0.5}, {1, 1, 0});
  check_shape(quad,
              {length(cross(Vec3{2, 0, 0.5}, Vec3{1, 1, 0})),
               1e-12,
               true,
               2,
               {{2, 0.5, 2}, {2, 0.5, -1}, {8, 1, 0.3}, {1.05, 0.02, 0.1}, {2.5, 0.5, 0.3}}},
              2);

  auto mesh = std::make_shared<TriangleMesh>();
  mesh->positions = {{0, 0, 0}, {2, 0.3, 0}, {0.5, 1.5, 1}};
  mesh->triangles = {{0, 1, 2}};
  const MeshTriangle triangle(mesh, 0);
  const double area = 0.5 * length(cross(mesh->positions[1], mesh->positions[2]));
  check_shape(triangle, {area, 1e-12, true, 2, {{0.5, 0.5, 3}, {1, 1, -2}}}, 3);

  auto degenerate = std::make_shared<TriangleMesh>();
  degenerate->positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  degenerate->triangles = {{0, 1, 2}};
  const MeshTriangle flat(degenerate, 0);
  SurfaceSample sample;
  EXPECT_EQ(flat.area(), 0);
  EXPECT_FALSE(flat.sample_area({0.5, 0.5}, sample));
}

// Quad::sample_from weights (u, v) by the solid-angle density at the corners: from a point
// close to a corner the estimate of the solid angle (the mean of 1/pdf) is far less noisy than
// with uniform area sampling (Shape::sample_from); beside the middle of an edge, where the
// density peaks between two corners, the bilinear fit is no better than uniform and not much
// worse; from far away the two are the same.
TEST(ShapeSampling, QuadSeenFromNearbyIsSampledCloseToItsSolidAngle) {
  const Quad quad({0, 0, 0}, {2, 0, 0}, {0, 0, 2});  // normal -y; both sides are sampled alike
  const auto spread = [&](const Vec3& reference, bool by_area) {
    Pcg32 rng(5, 9);
    Mean inverse_pdf;
    for (int i = 0; i < 20000; ++i) {
      const Vec2 u{rng.next_double(), rng.next_double()};
      SurfaceSample sample;
      const bool ok =
          by_area ? quad.Shape::sample_from(reference, u, sample) : quad.sample_from(reference, u, sample);
      inverse_pdf.add(ok ? 1 / sample.pdf : 0.0);
    }
    return inverse_pdf;
  };
  const auto ratio = [&](const Vec3& reference) {
    SCOPED_TRACE(::testing::Message() << "from " << reference);
    const Mean warped = spread(reference, false), uniform = spread(reference, true);
    EXPECT_NEAR(warped.mean(), uniform.mean(), 4 * std::hypot(warped.error(), uniform.error()));
    return warped.error() / uniform.error();
  };
  EXPECT_LT(ratio({0.3, 0.4, 0.2}), 0.6);
  EXPECT_LT(ratio({2.1, -0.3, 1.9}), 0.6);
  EXPECT_LT(ratio({-0.2, 0.5, 1}), 1.1);
  EXPECT_NEAR(ratio({1, 40, 1}), 1, 0.02);
}

TEST(ShapeSampling, DiscAndAnnulus) {
  const Disc disc({1, -1, 2}, {1, 2, 2}, 2);
  check_shape(disc, {4 * kPi, 1e-12, true, 2, {{3, 3, 5}, {0, -2, 0}}}, 4);
  const Disc annulus({0, 0, 0}, {0, 0, 1}, 2, 0.7);
  check_shape(annulus, {kPi * (4 - 0.49), 1e-12, true, 2, {{0, 0, 1}, {3, 1, -1}}}, 5);
}

TEST(ShapeSampling, ConcavePolygon) {
  // An L in a tilted plane: the unit square [0,2]² minus [1,2]², area 3, rotated about x.
  const double c = std::cos(0.4), s = std::sin(0.4);
  const auto place = [&](double x, double y) { return Vec3{x, y * c, y * s + 1}; };
  const Polygon polygon({place(0, 0), place(2, 0), place(2, 1), place(1, 1), place(1, 2), place(0, 2)});
  check_shape(polygon, {3, 1e-12, true, 2, {place(1.5, 1.5) + Vec3{0, -s, c} * 0.5, {4, -1, 3}}}, 6);
}

TEST(ShapeSampling, Box) {
  const Box box({-1, 0, 2}, {1, 3, 2.5});
  check_shape(box, {2 * (2 * 3 + 3 * 0.5 + 0.5 * 2), 1e-12, true, 3, {{3, 4, 5}, {0, 1, 2.2}}}, 7);
}

TEST(ShapeSampling, CylinderCappedAndOpen) {
  const Vec3 base{1, 0, 0}, cap{1, 2, 1};
  const double h = length(cap - base), r = 0.6;
  const Cylinder capped(base, cap, r);
  check_shape(capped, {2 * kPi * r * h + 2 * kPi * r * r, 1e-12, true, 2, {{3, 1, 2}, {1, 1, 0.5}}}, 8);
  const Cylinder open(base, cap, r, false);
  check_shape(open, {2 * kPi * r * h, 1e-12, true, 2, {{3, 1, 2}, {1, 1, 0.5}}}, 9);
}

TEST(ShapeSampling, ConesTruncatedAndPointed) {
  const Vec3 base{0, 0, 0}, cap{0.5, 0.5, 2};
  const double h = length(cap - base);
  const Cone truncated(base, 1.0, cap, 0.4);
  const double side = kPi * 1.4 * std::hypot(h, 0.6);
  check_shape(truncated, {side + kPi * (1 + 0.16), 1e-12, true, 2, {{3, 0, 1}, {0.2, 0.2, 1}}}, 10);
  const Cone pointed(base, 0, cap, 0.8, false);  // apex at the base, open
  check_shape(pointed, {kPi * 0.8 * std::hypot(h, 0.8), 1e-12, true, 2, {{3, 0, 1}, {0.4, 0.4, 1.8}}}, 11);
  const Cone widening(base, 0.3, cap, 1.1);
  check_shape(widening, {kPi * 1.4 * std::hypot(h, 0.8) + kPi * (0.09 + 1.21), 1e-12, true, 2, {{-2, 1, 3}}},
              12);
}

TEST(ShapeSampling, Torus) {
  const Torus torus({1, 1, 0}, {0.3, 1, 0.2}, 2, 0.5);
  check_shape(torus, {4 * kPi * kPi * 2 * 0.5, 1e-12, true, 2.5, {{6, 1, 0}, {1, 1, 0}, {1, 3, 0.5}}}, 13);
  const Torus horn({0, 0, 0}, {0, 0, 1}, 1, 1);
  check_shape(horn, {4 * kPi * kPi, 1e-12, true, 2, {{4, 0, 1}}}, 14);
  // A spindle torus is not sampled (documented in torus.h).
  const Torus spindle({0, 0, 0}, {0, 0, 1}, 1, 1.5);
  SurfaceSample sample;
  EXPECT_EQ(spindle.area(), 0);
  EXPECT_FALSE(spindle.sample_area({0.5, 0.5}, sample));
}

TEST(ShapeSampling, PlaneCannotBeSampled) {
  const Plane plane({0, 0, 0}, {0, 0, 1});
  SurfaceSample sample;
  EXPECT_EQ(plane.area(), 0);
  EXPECT_FALSE(plane.sample_area({0.5, 0.5}, sample));
  EXPECT_FALSE(plane.sample_from({0, 0, 1}, {0.5, 0.5}, sample));
  SurfaceHit hit;
  ASSERT_TRUE(plane.intersect({{0, 0, 1}, {0, 0, -1}, 0, kInfinity}, hit));
  EXPECT_EQ(plane.pdf_area(hit), 0);
  EXPECT_EQ(plane.pdf_from({0, 0, 1}, hit), 0);
}

Transform skew() {
  return Transform::translate({0.5, -1, 2}) * Transform::rotate(35, {1, 2, 0.5}) *
         Transform::scale({2, 0.5, 1.3}) * Transform::rotate(-20, {0, 1, 1});
}

TEST(ShapeSampling, TransformedPlanarShapesAreExact) {
  const Transform m = skew();
  const Vec3 eu{2, 0, 0.5}, ev{1, 1, 0};
  const TransformedShape quad(std::make_unique<Quad>(Vec3{1, 0, 0}, eu, ev), m);
  check_shape(quad, {length(cross(m.vector(eu), m.vector(ev))), 1e-12, true, 3, {{2, 0.5, 5}, {-3, 1, 1}}},
              20);

  // A mirroring transform keeps the normals intersect reports.
  const Transform mirror = Transform::scale({-1, 1.5, 1}) * Transform::rotate(10, {1, 0, 0});
  const TransformedShape disc(std::make_unique<Disc>(Vec3{0, 0, 0}, Vec3{0, 0.3, 1}, 1), mirror);
  const Vec3 n = normalize(Vec3{0, 0.3, 1});
  const double scale =
      std::fabs(mirror.matrix().topLeftCorner<3, 3>().determinant()) * length(mirror.normal(n));
  check_shape(disc, {kPi * scale, 1e-12, true, 1.5, {{0.2, 0.5, 2}}}, 21);

  // A box under shear: six parallelograms.
  const Vec3 lower{-1, 0, 2}, upper{1, 3, 2.5};
  const TransformedShape box(std::make_unique<Box>(lower, upper), m);
  const Vec3 e = upper - lower;
  double area = 0;
  for (int axis = 0; axis < 3; ++axis) {
    Vec3 a, b;
    a[(axis + 1) % 3] = e[(axis + 1) % 3];
    b[(axis + 2) % 3] = e[(axis + 2) % 3];
    area += 2 * length(cross(m.vector(a), m.vector(b)));
  }
  check_shape(box, {area, 1e-12, false, 6, {{10, 3, 2}, m.point((lower + upper) * 0.5)}}, 22);
}

TEST(ShapeSampling, TransformedCurvedShapes) {
  // A similarity: exact area.
  const Transform similar =
      Transform::translate({1, 2, 3}) * Transform::rotate(40, {1, 1, 0}) * Transform::scale({1.5, 1.5, 1.5});
  const TransformedShape cylinder(std::make_unique<Cylinder>(Vec3{0, 0, 0}, Vec3{0, 0, 1}, 0.5), similar);
  check_shape(cylinder, {2.25 * (2 * kPi * 0.5 + 2 * kPi * 0.25), 1e-12, true, 2, {{4, 2, 3}}}, 30);
  const TransformedShape torus(std::make_unique<Torus>(Vec3{0, 0, 0}, Vec3{0, 0, 1}, 1, 0.3), similar);
  check_shape(torus, {2.25 * 4 * kPi * kPi * 0.3, 1e-12, true, 2, {{5, 2, 3}, {1, 2, 3}}}, 31);

  // Non-uniform scale and rotation: the density follows the local area scale; area() is an
  // estimate, compared with a long Monte Carlo mean of 1/pdf.
  const Transform m = skew();
  for (int shape_kind = 0; shape_kind < 3; ++shape_kind) {
    std::unique_ptr<Shape> object;
    if (shape_kind == 0) object = std::make_unique<Sphere>(Vec3{0, 0, 0}, 1);
    if (shape_kind == 1) object = std::make_unique<Cylinder>(Vec3{0, 0, 0}, Vec3{0, 0, 1}, 0.5);
    if (shape_kind == 2) object = std::make_unique<Torus>(Vec3{0, 0, 0}, Vec3{0, 1, 0}, 1, 0.4);
    const TransformedShape shape(std::move(object), m);
    Pcg32 rng(40 + shape_kind, 1);
    Mean inverse_pdf;
    for (int i = 0; i < 100000; ++i) {
      SurfaceSample sample;
      ASSERT_TRUE(shape.sample_area({rng.next_double(), rng.next_double()}, sample));
      inverse_pdf.add(1 / sample.pdf);
    }
    EXPECT_NEAR(shape.area(), inverse_pdf.mean(), 4 * inverse_pdf.error() + 1e-4 * shape.area())
        << shape_kind;
    check_shape(shape, {shape.area(), 1e-12, false, 3, {m.point({3, 0, 0}), m.point({0, 0, 0.5})}},
                50 + shape_kind);
  }
}

}  // namespace
}  // namespace candela
