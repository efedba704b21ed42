#include "raster/item_buffer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "camera/perspective_camera.h"
#include "geometry/triangle_mesh.h"
#include "math/constants.h"
#include "math/pcg32.h"
#include "raster/hemicube_views.h"

namespace candela {
namespace {

double ndc_depth(const Eigen::Matrix4d& clip_from_world, const Vec3& p) {
  const Eigen::Vector4d clip = clip_from_world * Eigen::Vector4d(p.x, p.y, p.z, 1);
  return clip.z() / clip.w();
}

TEST(ItemBuffer, StartsEmptyAndKeepsTheNearestId) {
  const PerspectiveCamera camera({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 50, 64, 48);
  const Eigen::Matrix4d clip_from_world = camera.view_projection(0.1, 50);
  ItemBuffer items(64, 48);
  EXPECT_EQ(items.at(0, 0), ItemBuffer::kNoItem);
  EXPECT_EQ(items.depth_at(63, 47), kInfinity);
  // A far triangle behind a near one, drawn far-first and near-first into two buffers.
  const Vec3 far[3] = {{-3, -3, -2}, {3, -3, -2}, {0, 3, -2}};
  const Vec3 near[3] = {{-1, -1, 1}, {1, -1, 1}, {0, 1, 1}};
  ItemBuffer other(64, 48);
  items.draw(clip_from_world, far[0], far[1], far[2], 7);
  items.draw(clip_from_world, near[0], near[1], near[2], 3);
  other.draw(clip_from_world, near[0], near[1], near[2], 3);
  other.draw(clip_from_world, far[0], far[1], far[2], 7);
  EXPECT_EQ(items.ids(), other.ids());
  EXPECT_EQ(items.at(32, 24), 3u);  // the centre: the near triangle
  EXPECT_EQ(items.at(32, 44), 7u);  // below the near one's base: the far triangle
  EXPECT_EQ(items.at(0, 0), ItemBuffer::kNoItem);
  // The depth is the ndc depth of what the pixel's ray hits.
  const Ray ray = camera.generate_ray(32.5, 24.5);
  const Vec3 hit = ray.at((1 - ray.origin.z) / ray.direction.z);  // the plane z = 1
  EXPECT_NEAR(items.depth_at(32, 24), ndc_depth(clip_from_world, hit), 1e-12);
  EXPECT_EQ(items.statistics().triangles, 2u);
  items.clear();
  EXPECT_EQ(items.at(32, 24), ItemBuffer::kNoItem);
  EXPECT_EQ(items.depth_at(32, 24), kInfinity);
}

// A cube [-1, 1]³ of 12 triangles (both windings are drawn, so orientation does not matter).
TriangleMesh cube() {
  TriangleMesh mesh;
  for (int i = 0; i < 8; ++i)
    mesh.positions.push_back({(i & 1) ? 1.0 : -1.0, (i & 2) ? 1.0 : -1.0, (i & 4) ? 1.0 : -1.0});
  const int quads[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1},
                           {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
  for (const auto& q : quads) {
    mesh.triangles.push_back(
        {static_cast<uint32_t>(q[0]), static_cast<uint32_t>(q[1]), static_cast<uint32_t>(q[2])});
    mesh.triangles.push_back(
        {static_cast<uint32_t>(q[0]), static_cast<uint32_t>(q[2]), static_cast<uint32_t>(q[3])});
  }
  return mesh;
}

TEST(ItemBuffer, MeshIdsAreTheTrianglesARayCasterSees) {
  // A cube and a tilted quad through it, from an oblique camera: at every pixel the id is the
  // triangle whose hit is nearest along the pixel's ray.
  TriangleMesh mesh = cube();
  const uint32_t base = static_cast<uint32_t>(mesh.positions.size());
  mesh.positions.insert(mesh.positions.end(),
                        {{-2.2, -0.3, -1.9}, {2.1, 0.4, -2.3}, {1.8, 0.9, 2.4}, {-2.4, 0.1, 2.2}});
  mesh.triangles.push_back({base, base + 1, base + 2});
  mesh.triangles.push_back({base, base + 2, base + 3});
  const PerspectiveCamera camera({3.1, 2.3, 4.2}, {0.1, -0.2, 0}, {0, 1, 0}, 55, 96, 72);
  const Eigen::Matrix4d clip_from_world = camera.view_projection(0.5, 30);
  for (const bool with_ids : {false, true}) {
    std::vector<uint32_t> ids(mesh.triangles.size());
    for (std::size_t i = 0; i < ids.size(); ++i)
      ids[i] = with_ids ? static_cast<uint32_t>(100 + 3 * i) : static_cast<uint32_t>(i);
    ItemBuffer items(96, 72);
    if (with_ids)
      items.draw(clip_from_world, mesh, ids);
    else
      items.draw(clip_from_world, mesh);
    int seen = 0;
    for (int y = 0; y < 72; ++y)
      for (int x = 0; x < 96; ++x) {
        const Ray ray = camera.generate_ray(x + 0.5, y + 0.5);
        double nearest = kInfinity;
        uint32_t expected = ItemBuffer::kNoItem;
        for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
          TriangleIntersection hit;
          const auto& c = mesh.triangles[t];
          if (intersect_triangle(ray, mesh.positions[c[0]], mesh.positions[c[1]], mesh.positions[c[2]],
                                 hit) &&
              hit.t < nearest) {
            nearest = hit.t;
            expected = ids[t];
          }
        }
        ASSERT_EQ(items.at(x, y), expected) << "pixel " << x << "," << y;
        seen += expected != ItemBuffer::kNoItem;
      }
    EXPECT_GT(seen, 96 * 72 / 4);
    EXPECT_EQ(items.statistics().triangles, mesh.triangles.size());
  }
  ItemBuffer items(8, 8);
  const std::vector<uint32_t> too_few(3, 0);
  EXPECT_THROW(items.draw(clip_from_world, mesh, too_few), std::invalid_argument);
}

TEST(ItemBuffer, RegionLimitsDrawing) {
  const PerspectiveCamera camera({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 60, 32, 32);
  const Eigen::Matrix4d clip_from_world = camera.view_projection(0.1, 50);
  ItemBuffer full(32, 32), part(32, 32);
  part.set_region(4, 10, 20, 16);
  for (ItemBuffer* items : {&full, &part}) {
    items->draw(clip_from_world, {-4, -4, 0}, {4, -4, 0}, {4, 4, 0}, 1);
    items->draw(clip_from_world, {-4, -4, 0}, {4, 4, 0}, {-4, 4, 0}, 2);
  }
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      const bool inside = x >= 4 && x < 20 && y >= 10 && y < 16;
      EXPECT_EQ(part.at(x, y), inside ? full.at(x, y) : ItemBuffer::kNoItem) << x << "," << y;
      EXPECT_NE(full.at(x, y), ItemBuffer::kNoItem);
    }
  EXPECT_THROW(part.set_region(0, 0, 33, 32), std::invalid_argument);
  EXPECT_THROW(full.at(32, 0), std::out_of_range);
  EXPECT_THROW(full.at(0, -1), std::out_of_range);
  EXPECT_THROW(ItemBuffer(0, 3), std::invalid_argument);
}

// Whether direction d is seen by the face: inside its square frustum and, for a side face, in
// the upper half of its image (ndc y > 0) — the part a hemicube uses.
bool face_sees(const Eigen::Matrix4d& clip_from_world, const Vec3& center, const Vec3& d, HemicubeFace face) {
  const Vec3 p = center + d;
  const Eigen::Vector4d clip = clip_from_world * Eigen::Vector4d(p.x, p.y, p.z, 1);
  const double w = clip.w();
  if (!(w > 0) || std::fabs(clip.x()) > w || std::fabs(clip.y()) > w || std::fabs(clip.z()) > w) return false;
  return face == HemicubeFace::top || clip.y() > 0;
}

TEST(Hemicube, FacesLookAlongTheDocumentedAxes) {
  const Vec3 center{0.4, -1.2, 2.5};
  const Vec3 normal = normalize(Vec3{0.3, 1, -0.2});
  const Vec3 hint{1, 0.2, 0.1};  // made perpendicular to the normal
  const HemicubeFaceAxes top = hemicube_face_axes(normal, hint, HemicubeFace::top);
  EXPECT_NEAR(length(top.forward - normal), 0, 1e-15);
  EXPECT_NEAR(dot(top.up, normal), 0, 1e-15);
  EXPECT_NEAR(length(top.up - normalize(hint - normal * dot(hint, normal))), 0,
              1e-15);  // t: the hint, orthogonalised
  const Vec3 t = top.up, b = top.right;
  EXPECT_NEAR(length(cross(normal, t) - b), 0, 1e-15);  // b = n × t
  const struct {
    HemicubeFace face;
    Vec3 forward, right, up;
  } expected[] = {{HemicubeFace::top, normal, b, t},
                  {HemicubeFace::front, t, -b, normal},
                  {HemicubeFace::back, -t, b, normal},
                  {HemicubeFace::right, b, t, normal},
                  {HemicubeFace::left, -b, -t, normal}};
  const int size = 64;
  for (const auto& e : expected) {
    const HemicubeFaceAxes axes = hemicube_face_axes(normal, hint, e.face);
    EXPECT_NEAR(length(axes.forward - e.forward), 0, 1e-15);
    EXPECT_NEAR(length(axes.right - e.right), 0, 1e-15);
    EXPECT_NEAR(length(axes.up - e.up), 0, 1e-15);
    EXPECT_NEAR(length(cross(axes.forward, axes.up) - axes.right), 0, 1e-15);  // right = forward × up
    const Eigen::Matrix4d m = hemicube_view_projection(center, normal, hint, e.face, 0.01, 100);
    const auto ndc = [&](const Vec3& d) {
      const Vec3 p = center + d;
      const Eigen::Vector4d clip = m * Eigen::Vector4d(p.x, p.y, p.z, 1);
      return Eigen::Vector3d(clip.x() / clip.w(), clip.y() / clip.w(), clip.z() / clip.w());
    };
    // The face's own direction lands at the image centre; 45° toward right / up at the edges.
    EXPECT_NEAR(ndc(e.forward * 2).x(), 0, 1e-12);
    EXPECT_NEAR(ndc(e.forward * 2).y(), 0, 1e-12);
    EXPECT_NEAR(ndc(e.forward + e.right * 0.5).x(), 0.5, 1e-12);
    EXPECT_NEAR(ndc(e.forward + e.up * 0.5).y(), 0.5, 1e-12);
    EXPECT_NEAR(ndc(e.forward + e.right + e.up).x(), 1, 1e-12);
    EXPECT_NEAR(ndc(e.forward + e.right + e.up).y(), 1, 1e-12);
    EXPECT_NEAR(ndc(e.forward * 0.01).z(), -1, 1e-9);
    EXPECT_NEAR(ndc(e.forward * 100).z(), 1, 1e-9);
    if (e.face != HemicubeFace::top) {
      // Above the surface: the upper half of the image rows (y < size/2).
      const double row = (1 - ndc(e.forward + normal * 0.3).y()) / 2 * size;
      EXPECT_LT(row, size / 2.0);
      const double row_below = (1 - ndc(e.forward - normal * 0.3).y()) / 2 * size;
      EXPECT_GT(row_below, size / 2.0);
    }
  }
  // A point straight along the normal lands at the centre of the top face's image.
  ItemBuffer items(size, size);
  const Vec3 ahead = center + normal * 3;
  items.draw(hemicube_view_projection(center, normal, hint, HemicubeFace::top, 0.01, 100),
             ahead - t * 0.3 - b * 0.3, ahead + t * 0.3 - b * 0.3, ahead + b * 0.3, 5);
  EXPECT_EQ(items.at(size / 2, size / 2), 5u);
  EXPECT_EQ(items.at(size / 2 - 1, size / 2 - 1), 5u);
  EXPECT_EQ(items.at(0, 0), ItemBuffer::kNoItem);
}

TEST(Hemicube, FiveFacesCoverTheHemisphereExactlyOnce) {
  const Vec3 center{1, 2, 3};
  Pcg32 random(17, 4);
  for (int frame = 0; frame < 4; ++frame) {
    const Vec3 normal{2 * random.next_double() - 1, 2 * random.next_double() - 1,
                      2 * random.next_double() - 1};
    const Vec3 hint =
        frame == 3 ? normal * 2 : Vec3{random.next_double(), 1, random.next_double()};  // 3: degenerate hint
    Eigen::Matrix4d matrices[5];
    for (int f = 0; f < 5; ++f)
      matrices[f] = hemicube_view_projection(center, normal, hint, kHemicubeFaces[f], 1e-3, 10);
    const Vec3 n = normalize(normal);
    for (int sample = 0; sample < 20000; ++sample) {
      // Uniform on the sphere.
      const double z = 1 - 2 * random.next_double(), phi = 2 * kPi * random.next_double();
      const double r = std::sqrt(std::max(0.0, 1 - z * z));
      const Vec3 d{r * std::cos(phi), r * std::sin(phi), z};
      int seen_by = 0;
      for (int f = 0; f < 5; ++f) seen_by += face_sees(matrices[f], center, d, kHemicubeFaces[f]);
      if (dot(d, n) > 1e-9) {
        ASSERT_EQ(seen_by, 1) << "direction " << d << " above the surface";
      } else if (dot(d, n) < -1e-9) {
        ASSERT_EQ(seen_by, 0) << "direction " << d << " below the surface";
      }
    }
  }
}

TEST(Hemicube, DeltaFormFactorsOfTheUsedCellsSumToOne) {
  // 000 §6.4.1: ΔF = cos φ_i cos φ_q / (π r²) ΔA per cell. Summed over the top face and the upper
  // halves of the side faces (cells located through the projection matrices), it is 1.
  const int size = 100;  // cells per face edge; the cube has edge 2
  const Vec3 center{0.5, 0.5, 0.5}, normal = normalize(Vec3{-1, 2, 0.5}), hint{0, 0, 1};
  double sum = 0;
  const double cell_area = (2.0 / size) * (2.0 / size);
  for (const HemicubeFace face : kHemicubeFaces) {
    const HemicubeFaceAxes axes = hemicube_face_axes(normal, hint, face);
    const Eigen::Matrix4d m = hemicube_view_projection(center, normal, hint, face, 0.01, 10);
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const double ndc_x = 2 * (x + 0.5) / size - 1, ndc_y = 1 - 2 * (y + 0.5) / size;
        const Vec3 cell = axes.forward + axes.right * ndc_x + axes.up * ndc_y;  // on the cube
        const Vec3 p = center + cell;
        const Eigen::Vector4d clip = m * Eigen::Vector4d(p.x, p.y, p.z, 1);
        ASSERT_NEAR(clip.x() / clip.w(), ndc_x, 1e-12);
        ASSERT_NEAR(clip.y() / clip.w(), ndc_y, 1e-12);
        if (face != HemicubeFace::top && y >= size / 2) continue;  // below the surface
        const double r2 = length_squared(cell);
        const double cos_i = dot(cell, normal) / std::sqrt(r2), cos_q = 1 / std::sqrt(r2);
        ASSERT_GT(cos_i, 0);
        sum += cos_i * cos_q / (kPi * r2) * cell_area;
      }
  }
  EXPECT_NEAR(sum, 1, 2e-4);
}

TEST(Hemicube, ItemBufferOfASideFaceSeesTheFloorBelowAndTheCeilingAbove) {
  // A floor below the surface point and a ceiling above it, both far wider than the far plane
  // (so clipped at near and far): side faces see the ceiling in every row of their upper halves
  // and the floor in every row of their lower halves.
  const Vec3 center{0, 0, 0}, normal{0, 0, 1}, hint{1, 0, 0};
  const int size = 32;
  for (const HemicubeFace face : kHemicubeFaces) {
    const Eigen::Matrix4d m = hemicube_view_projection(center, normal, hint, face, 0.01, 1000);
    ItemBuffer items(size, size);
    const double extent = 500;
    items.draw(m, {-extent, -extent, -0.5}, {extent, -extent, -0.5}, {extent, extent, -0.5}, 1);
    items.draw(m, {-extent, -extent, -0.5}, {extent, extent, -0.5}, {-extent, extent, -0.5}, 1);
    items.draw(m, {-extent, -extent, 0.5}, {extent, -extent, 0.5}, {extent, extent, 0.5}, 2);
    items.draw(m, {-extent, -extent, 0.5}, {extent, extent, 0.5}, {-extent, extent, 0.5}, 2);
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const uint32_t id = items.at(x, y);
        if (face == HemicubeFace::top) {
          EXPECT_EQ(id, 2u) << x << "," << y;
        } else if (y < size / 2) {
          EXPECT_EQ(id, 2u) << "face " << static_cast<int>(face) << " " << x << "," << y;
        } else {
          EXPECT_EQ(id, 1u) << "face " << static_cast<int>(face) << " " << x << "," << y;
        }
      }
  }
}

TEST(Hemicube, RejectsBadInput) {
  EXPECT_THROW(hemicube_view_projection({0, 0, 0}, {0, 0, 0}, {1, 0, 0}, HemicubeFace::top, 0.1, 1),
               std::invalid_argument);
  EXPECT_THROW(hemicube_view_projection({0, 0, 0}, {0, 0, 1}, {1, 0, 0}, HemicubeFace::top, 0, 1),
               std::invalid_argument);
  EXPECT_THROW(hemicube_view_projection({0, 0, 0}, {0, 0, 1}, {1, 0, 0}, HemicubeFace::top, 2, 1),
               std::invalid_argument);
  // A hint along the normal (or zero) gives way to some perpendicular tangent.
  for (const Vec3 hint : {Vec3{0, 0, 3}, Vec3{0, 0, 0}}) {
    const HemicubeFaceAxes axes = hemicube_face_axes({0, 0, 2}, hint, HemicubeFace::top);
    EXPECT_NEAR(dot(axes.up, Vec3{0, 0, 1}), 0, 1e-15);
    EXPECT_NEAR(length(axes.up), 1, 1e-15);
  }
}

}  // namespace
}  // namespace candela
