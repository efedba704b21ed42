// A scene as triangles, for the rasterizer (SPEC §9) and the Gouraud display of radiosity:
// every primitive tessellated by Shape::tessellate, vertex normals averaged from the adjacent
// face normals of the same object with a crease angle (000 §3.2, §3.2.1: a real edge keeps two
// normals at its vertices), and per triangle the primitive, object and material it came from.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "geometry/triangle_mesh.h"
#include "scene/scene.h"

namespace candela {

struct TessellatedScene {
  // Corner data, three entries per triangle (triangle t owns corners 3t, 3t+1, 3t+2).
  std::vector<Vec3> corner_positions;         // world
  std::vector<Vec3> corner_object_positions;  // the shape's own coordinates (solid textures)
  std::vector<Vec3> corner_normals;           // averaged with the crease angle, unit (or zero)
  std::vector<Vec2> corner_uvs;               // the shape's parametrisation
  // Per triangle.
  std::vector<Vec3> face_normals;  // unit, counter-clockwise: the shape's geometric normal side
  std::vector<uint32_t> primitives;
  std::vector<uint32_t> materials;
  std::vector<uint32_t> objects;

  std::size_t triangle_count() const { return primitives.size(); }
};

// segments: TessellationSettings::segments; crease_angle_degrees as compute_corner_normals;
// unbounded shapes are cut by `clip`. Degenerate (zero-area) triangles are dropped.
TessellatedScene tessellate_scene(const Scene& scene, int segments, double crease_angle_degrees, const Bounds3& clip);

}  // namespace candela
