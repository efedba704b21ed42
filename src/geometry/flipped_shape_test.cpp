// A shape with its normals reversed ("flip_normals"), geometry/flipped_shape.h.
#include "geometry/flipped_shape.h"

#include <gtest/gtest.h>

#include <memory>

#include "geometry/quad.h"
#include "geometry/sphere.h"
#include "geometry/triangle_mesh.h"

namespace candela {
namespace {

TEST(FlippedShape, ReversesTheNormalsAndKeepsTheSurface) {
  const Sphere sphere({0, 0, 0}, 1);
  const FlippedShape flipped(std::make_unique<Sphere>(Vec3{0, 0, 0}, 1));
  // From inside, along +x: the same point, t and uv; the normal points in (toward the centre).
  Ray ray;
  ray.origin = {0.2, 0.1, 0};
  ray.direction = {1, 0, 0};
  SurfaceHit plain, turned;
  ASSERT_TRUE(sphere.intersect(ray, plain));
  ASSERT_TRUE(flipped.intersect(ray, turned));
  EXPECT_EQ(turned.t, plain.t);
  EXPECT_EQ(turned.position, plain.position);
  EXPECT_EQ(turned.uv.x, plain.uv.x);
  EXPECT_EQ(turned.uv.y, plain.uv.y);
  EXPECT_EQ(turned.geometric_normal, -plain.geometric_normal);
  EXPECT_EQ(turned.shading_normal, -plain.shading_normal);
  EXPECT_LT(dot(turned.geometric_normal, turned.position), 0);
  // Textures look the same: the object-space frame is the shape's own.
  EXPECT_EQ(turned.object_normal(), plain.object_normal());
  EXPECT_EQ(turned.object_dpdu(), plain.object_dpdu());
  EXPECT_EQ(flipped.occluded(ray), sphere.occluded(ray));
  EXPECT_EQ(flipped.bounds().lower, sphere.bounds().lower);
  EXPECT_EQ(flipped.type_name(), "sphere");
  // Area and densities unchanged; samples' normals reversed.
  EXPECT_EQ(flipped.area(), sphere.area());
  EXPECT_EQ(flipped.pdf_area(turned), sphere.pdf_area(plain));
  const Vec3 reference{0.3, -0.2, 0.1};
  EXPECT_EQ(flipped.pdf_from(reference, turned), sphere.pdf_from(reference, plain));
  SurfaceSample a, b;
  ASSERT_TRUE(sphere.sample_from(reference, {0.3, 0.7}, a));
  ASSERT_TRUE(flipped.sample_from(reference, {0.3, 0.7}, b));
  EXPECT_EQ(b.position, a.position);
  EXPECT_EQ(b.normal, -a.normal);
  EXPECT_EQ(b.pdf, a.pdf);
  ASSERT_TRUE(sphere.sample_area({0.6, 0.2}, a));
  ASSERT_TRUE(flipped.sample_area({0.6, 0.2}, b));
  EXPECT_EQ(b.normal, -a.normal);
}

TEST(FlippedShape, TessellationIsWoundTheOtherWay) {
  for (const bool curved : {false, true}) {
    std::unique_ptr<Shape> inner;
    if (curved)
      inner = std::make_unique<Sphere>(Vec3{0, 0, 0}, 1);
    else
      inner = std::make_unique<Quad>(Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 0});
    TriangleMesh plain, turned;
    inner->tessellate({}, plain);
    const FlippedShape flipped(std::move(inner));
    flipped.tessellate({}, turned);
    ASSERT_EQ(turned.triangles.size(), plain.triangles.size());
    ASSERT_EQ(turned.positions, plain.positions);
    for (std::size_t t = 0; t < plain.triangles.size(); ++t) {
      const Vec3 a = plain.face_cross(t), b = turned.face_cross(t);
      EXPECT_NEAR(length(a + b), 0, 1e-12 * (1 + length(a))) << t;
      if (!plain.corner_uvs.empty()) {  // each corner keeps its uv
        EXPECT_EQ(turned.corner_uvs[t][0].x, plain.corner_uvs[t][0].x);
        EXPECT_EQ(turned.corner_uvs[t][1].y, plain.corner_uvs[t][2].y);
      }
    }
  }
}

}  // namespace
}  // namespace candela
