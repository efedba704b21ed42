#include "raster/tessellated_scene.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>

#include "geometry/flipped_shape.h"
#include "geometry/plane.h"
#include "geometry/transformed_shape.h"
#include "math/constants.h"

namespace candela {

namespace {

// The plane a shape is (directly or transformed), in world space; false for other shapes.
bool world_plane(const Shape& shape, Vec3& point, Vec3& normal) {
  if (const auto* plane = dynamic_cast<const Plane*>(&shape)) {
    point = plane->point();
    normal = plane->normal();
    return true;
  }
  if (const auto* flipped = dynamic_cast<const FlippedShape*>(&shape)) {
    if (!world_plane(flipped->shape(), point, normal)) return false;
    normal = -normal;
    return true;
  }
  if (const auto* placed = dynamic_cast<const TransformedShape*>(&shape)) {
    Vec3 inner_point, inner_normal;
    if (!world_plane(placed->shape(), inner_point, inner_normal)) return false;
    point = placed->object_to_world().point(inner_point);
    normal = normalize(placed->object_to_world().normal(inner_normal));
    return true;
  }
  return false;
}

// The fewest segments a chord tolerance gives a curved shape: a sphere of six longitudes and three
// latitudes (24 triangles).
constexpr double kMinChordSegments = 6;

// Segments for a bounded shape: by the chord tolerance when there is one, else about one pixel per
// edge around its outline on screen.
int segments_for(const Shape& shape, const TessellationRequest& request) {
  if (request.chord_tolerance > 0) {
    // The fewest segments whose chords stray at most the tolerance from a circle of the
    // shape's radius (half its box's middle extent: a sphere's, a cylinder's or a disc's radius),
    // sagitta r (1 − cos(π/N)) ≤ tolerance.
    const Bounds3 box = shape.bounds();
    if (!box.is_finite()) return request.max_segments;
    std::array<double, 3> extent{box.diagonal().x, box.diagonal().y, box.diagonal().z};
    std::sort(extent.begin(), extent.end());
    const double radius = 0.5 * extent[1];
    const double cap = std::max(request.max_segments, 3);
    if (!(radius > request.chord_tolerance)) return static_cast<int>(std::min(kMinChordSegments, cap));
    const double needed = std::ceil(kPi / std::acos(1 - request.chord_tolerance / radius));
    return static_cast<int>(std::clamp(needed, std::min(kMinChordSegments, cap), cap));
  }
  if (!request.has_view) return request.max_segments;
  const Bounds3 b = shape.bounds();
  if (!b.is_finite()) return request.max_segments;
  const Vec3 center = (b.lower + b.upper) * 0.5;
  const double radius = 0.5 * length(b.diagonal());
  const Eigen::Vector4d clip = request.clip_from_world * Eigen::Vector4d(center.x, center.y, center.z, 1);
  const double w = clip.w();
  // Eye inside or near the bounding sphere (perspective w is the depth): the finest.
  if (!(w > radius) && request.clip_from_world(3, 3) == 0) return request.max_segments;
  const double pixels_per_unit =
      std::fabs(request.clip_from_world(0, 0)) * 0.5 * request.image_width / std::max(w, 1e-300);
  const double outline_pixels = 2 * kPi * radius * pixels_per_unit;
  if (!std::isfinite(outline_pixels)) return request.max_segments;
  return static_cast<int>(
      std::clamp(std::ceil(outline_pixels), 8.0, double(std::max(request.max_segments, 3))));
}

// Splits the triangles [first, end) of mesh in halves across their longest edge while that edge
// is longer than a tenth of its distance to the eye (the screen size of the triangle), with
// corner uvs interpolated. A plane's few huge triangles become a mesh fine near the eye.
void refine_toward(TriangleMesh& mesh, std::size_t first, const Vec3& eye) {
  constexpr int kMaxLevels = 20;
  struct Pending {
    std::array<uint32_t, 3> triangle;
    std::array<Vec2, 3> uvs;
    int level;
  };
  std::vector<Pending> stack;
  for (std::size_t t = first; t < mesh.triangles.size(); ++t)
    stack.push_back({mesh.triangles[t], mesh.corner_uvs[t], 0});
  mesh.triangles.resize(first);
  mesh.corner_uvs.resize(first);
  while (!stack.empty()) {
    const Pending p = stack.back();
    stack.pop_back();
    int longest = 0;
    double longest_length = -1;
    for (int k = 0; k < 3; ++k) {
      const double l = length(mesh.positions[p.triangle[(k + 1) % 3]] - mesh.positions[p.triangle[k]]);
      if (l > longest_length) longest_length = l, longest = k;
    }
    const Vec3 a = mesh.positions[p.triangle[longest]], b = mesh.positions[p.triangle[(longest + 1) % 3]];
    const Vec3 middle = (a + b) * 0.5;
    if (p.level >= kMaxLevels || !(longest_length > 0.1 * length(middle - eye))) {
      mesh.triangles.push_back(p.triangle);
      mesh.corner_uvs.push_back(p.uvs);
      continue;
    }
    const auto m = static_cast<uint32_t>(mesh.positions.size());
    mesh.positions.push_back(middle);
    const int k0 = longest, k1 = (longest + 1) % 3, k2 = (longest + 2) % 3;
    const Vec2 uv_middle{(p.uvs[k0].x + p.uvs[k1].x) * 0.5, (p.uvs[k0].y + p.uvs[k1].y) * 0.5};
    // (k0, m, k2) and (m, k1, k2) keep the winding.
    Pending first_half{{p.triangle[k0], m, p.triangle[k2]}, {p.uvs[k0], uv_middle, p.uvs[k2]}, p.level + 1};
    Pending second_half{{m, p.triangle[k1], p.triangle[k2]}, {uv_middle, p.uvs[k1], p.uvs[k2]}, p.level + 1};
    stack.push_back(first_half);
    stack.push_back(second_half);
  }
}

// Appends the primitive's triangles for the request to mesh: curved shapes by their segments, a
// plane refined toward the eye when there is a view. (Degenerate triangles are left in: the caller
// drops them.)
void append_primitive(const Shape& shape, const TessellationRequest& request, TessellationSettings& settings,
                      TriangleMesh& mesh) {
  settings.segments = segments_for(shape, request);
  const std::size_t first = mesh.triangles.size();
  shape.tessellate(settings, mesh);
  Vec3 point, normal;
  if (request.has_view && first < mesh.triangles.size() && world_plane(shape, point, normal))
    refine_toward(mesh, first, request.eye);
}

}  // namespace

Bounds3 raster_clip_box(const Scene& scene, const Vec3& eye, double margin) {
  Bounds3 reach = scene.bounds();
  reach.extend(eye);
  for (const Primitive& primitive : scene.primitives) {
    Vec3 point, normal;
    if (!primitive.shape->bounds().is_finite() && world_plane(*primitive.shape, point, normal))
      reach.extend(eye - normal * dot(eye - point, normal));  // the plane's point nearest the eye
  }
  const double size = std::max(length(reach.diagonal()), 1e-9 * std::max(1.0, length(eye)));
  const Vec3 middle = (reach.lower + reach.upper) * 0.5;
  const Vec3 half{margin * size, margin * size, margin * size};
  return {middle - half, middle + half};
}

std::size_t tessellated_triangle_count(const Scene& scene, const TessellationRequest& request) {
  // In parallel over the primitives (the 10,584 spheres of scenes/sphere-field-10584.json are 42
  // million triangles at 64 segments: seconds), each chunk's mesh reused; a sum of integers, so the
  // count is the same for every thread count.
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, scene.primitives.size(), 64), std::size_t{0},
      [&](const tbb::blocked_range<std::size_t>& range, std::size_t count) {
        TessellationSettings settings;
        settings.clip = request.clip;
        TriangleMesh mesh;
        for (std::size_t p = range.begin(); p < range.end(); ++p) {
          mesh.positions.clear();
          mesh.triangles.clear();
          mesh.corner_normals.clear();
          mesh.corner_uvs.clear();
          append_primitive(*scene.primitives[p].shape, request, settings, mesh);
          for (std::size_t t = 0; t < mesh.triangles.size(); ++t) count += !mesh.is_degenerate(t);
        }
        return count;
      },
      std::plus<>());
}

TessellatedScene tessellate_scene(const Scene& scene, const TessellationRequest& request) {
  TessellatedScene result;
  TessellationSettings settings;
  settings.clip = request.clip;
  for (uint32_t object_index = 0; object_index < scene.objects.size(); ++object_index) {
    const SceneObject& object = scene.objects[object_index];
    // One mesh per object, so normals are averaged across its primitives (the triangles of an
    // OBJ mesh) but never across objects that merely touch.
    TriangleMesh mesh;
    std::vector<uint32_t> source_primitive;
    for (uint32_t p = object.first_primitive; p < object.first_primitive + object.primitive_count; ++p) {
      append_primitive(*scene.primitives[p].shape, request, settings, mesh);
      source_primitive.resize(mesh.triangles.size(), p);
    }
    if (mesh.triangles.empty()) continue;
    compute_corner_normals(mesh, request.crease_angle_degrees);
    // The world-to-object transform of the primitive the current triangles come from.
    uint32_t placed_primitive = UINT32_MAX;
    bool transformed = false;
    const MeshTriangle* mesh_triangle = nullptr;
    Transform world_to_object;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      if (mesh.is_degenerate(t)) continue;
      const uint32_t primitive = source_primitive[t];
      if (primitive != placed_primitive) {
        placed_primitive = primitive;
        const Shape* shape = scene.primitives[primitive].shape;
        const auto* placed = dynamic_cast<const TransformedShape*>(shape);
        transformed = placed != nullptr;
        world_to_object = placed ? placed->object_to_world().inverse() : Transform();
        mesh_triangle = dynamic_cast<const MeshTriangle*>(shape);
      }
      const Vec3 face_normal = normalize(mesh.face_cross(t));
      for (int k = 0; k < 3; ++k) {
        const Vec3& p = mesh.positions[mesh.triangles[t][k]];
        result.corner_positions.push_back(p);
        result.corner_object_positions.push_back(transformed ? world_to_object.point(p) : p);
        Vec3 n = mesh.corner_normals[t][k];
        if (mesh_triangle) {
          // A triangle mesh keeps the normals the scene gave it: smooth (with its own crease
          // angle), from the file, or flat — as the ray tracer shades it.
          const TriangleMesh& source = mesh_triangle->mesh();
          n = source.corner_normals.empty() ? face_normal
                                            : source.corner_normals[mesh_triangle->triangle_index()][k];
        }
        result.corner_normals.push_back(n);
        result.corner_uvs.push_back(mesh.corner_uvs.empty() ? Vec2{} : mesh.corner_uvs[t][k]);
      }
      result.face_normals.push_back(face_normal);
      result.primitives.push_back(primitive);
      result.materials.push_back(scene.primitives[primitive].material);
      result.objects.push_back(object_index);
    }
  }
  return result;
}

}  // namespace candela
