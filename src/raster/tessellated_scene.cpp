#include "raster/tessellated_scene.h"

#include <cmath>
#include <cstdint>

#include "geometry/transformed_shape.h"

namespace candela {

TessellatedScene tessellate_scene(const Scene& scene, int segments, double crease_angle_degrees, const Bounds3& clip) {
  TessellatedScene result;
  TessellationSettings settings;
  settings.segments = segments;
  settings.clip = clip;
  for (uint32_t object_index = 0; object_index < scene.objects.size(); ++object_index) {
    const SceneObject& object = scene.objects[object_index];
    // One mesh per object, so normals are averaged across its primitives (the triangles of an
    // OBJ mesh) but never across objects that merely touch.
    TriangleMesh mesh;
    std::vector<uint32_t> source_primitive;
    for (uint32_t p = object.first_primitive; p < object.first_primitive + object.primitive_count; ++p) {
      scene.primitives[p].shape->tessellate(settings, mesh);
      source_primitive.resize(mesh.triangles.size(), p);
    }
    if (mesh.triangles.empty()) continue;
    compute_corner_normals(mesh, crease_angle_degrees);
    // The world-to-object transform of the primitive the current triangles come from.
    uint32_t placed_primitive = UINT32_MAX;
    bool transformed = false;
    Transform world_to_object;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      if (mesh.is_degenerate(t)) continue;
      const uint32_t primitive = source_primitive[t];
      if (primitive != placed_primitive) {
        placed_primitive = primitive;
        const auto* placed = dynamic_cast<const TransformedShape*>(scene.primitives[primitive].shape);
        transformed = placed != nullptr;
        world_to_object = placed ? placed->object_to_world().inverse() : Transform();
      }
      for (int k = 0; k < 3; ++k) {
        const Vec3& p = mesh.positions[mesh.triangles[t][k]];
        result.corner_positions.push_back(p);
        result.corner_object_positions.push_back(transformed ? world_to_object.point(p) : p);
        result.corner_normals.push_back(mesh.corner_normals[t][k]);
        result.corner_uvs.push_back(mesh.corner_uvs.empty() ? Vec2{} : mesh.corner_uvs[t][k]);
      }
      result.face_normals.push_back(normalize(mesh.face_cross(t)));
      result.primitives.push_back(primitive);
      result.materials.push_back(scene.primitives[primitive].material);
      result.objects.push_back(object_index);
    }
  }
  return result;
}

}  // namespace candela
