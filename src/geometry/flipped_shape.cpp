#include "geometry/flipped_shape.h"

#include <utility>

#include "geometry/triangle_mesh.h"

namespace candela {

namespace {

// The hit as the inner shape reported it (its densities may read the normal).
SurfaceHit unflipped(const SurfaceHit& hit) {
  SurfaceHit inner = hit;
  inner.geometric_normal = -hit.geometric_normal;
  inner.shading_normal = -hit.shading_normal;
  return inner;
}

}  // namespace

FlippedShape::FlippedShape(std::unique_ptr<Shape> shape) : shape_(std::move(shape)) {}

bool FlippedShape::intersect(const Ray& ray, SurfaceHit& hit) const {
  if (!shape_->intersect(ray, hit)) return false;
  // The object-space frame stays the shape's own (textures look the same flipped or not).
  if (!hit.transformed) {
    hit.object_dpdu_ = hit.dpdu;
    hit.object_dpdv_ = hit.dpdv;
    hit.object_normal_ = hit.geometric_normal;
    hit.transformed = true;
  }
  hit.geometric_normal = -hit.geometric_normal;
  hit.shading_normal = -hit.shading_normal;
  return true;
}

void FlippedShape::tessellate(const TessellationSettings& settings, TriangleMesh& mesh) const {
  const std::size_t first = mesh.triangles.size();
  shape_->tessellate(settings, mesh);
  for (std::size_t t = first; t < mesh.triangles.size(); ++t) {
    std::swap(mesh.triangles[t][1], mesh.triangles[t][2]);
    if (t < mesh.corner_uvs.size()) std::swap(mesh.corner_uvs[t][1], mesh.corner_uvs[t][2]);
    if (t < mesh.corner_normals.size()) {
      std::swap(mesh.corner_normals[t][1], mesh.corner_normals[t][2]);
      for (Vec3& normal : mesh.corner_normals[t]) normal = -normal;
    }
  }
}

bool FlippedShape::sample_area(const Vec2& u, SurfaceSample& sample) const {
  if (!shape_->sample_area(u, sample)) return false;
  sample.normal = -sample.normal;
  return true;
}

double FlippedShape::pdf_area(const SurfaceHit& hit) const {
  return shape_->pdf_area(unflipped(hit));
}

bool FlippedShape::sample_from(const Vec3& reference, const Vec2& u, SurfaceSample& sample) const {
  if (!shape_->sample_from(reference, u, sample)) return false;
  sample.normal = -sample.normal;
  return true;
}

double FlippedShape::pdf_from(const Vec3& reference, const SurfaceHit& hit) const {
  return shape_->pdf_from(reference, unflipped(hit));
}

}  // namespace candela
