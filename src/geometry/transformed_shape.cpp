#include "geometry/transformed_shape.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "geometry/box.h"
#include "geometry/tessellation.h"
#include "geometry/triangle_mesh.h"

namespace candela {

TransformedShape::TransformedShape(std::unique_ptr<Shape> shape, const Transform& object_to_world)
    : shape_(std::move(shape)),
      object_to_world_(object_to_world),
      world_to_object_(object_to_world.inverse()) {
  const Eigen::Matrix3d linear = object_to_world_.matrix().topLeftCorner<3, 3>();
  determinant_ = std::fabs(linear.determinant());
  const double object_area = shape_->area();
  if (!(object_area > 0)) return;
  // A similarity: MᵀM = s² I, world areas are s² = |det M|^{2/3} times the object's.
  const Eigen::Matrix3d gram = linear.transpose() * linear;
  const double scale_squared = gram.trace() / 3;
  if ((gram - scale_squared * Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() <= 1e-12 * scale_squared) {
    area_ = object_area * std::cbrt(determinant_ * determinant_);
    return;
  }
  // A box: six planar faces, each scaled by its own constant factor.
  if (const auto* box = dynamic_cast<const Box*>(shape_.get())) {
    const Vec3 e = box->upper() - box->lower();
    for (int axis = 0; axis < 3; ++axis) {
      Vec3 n;
      n[axis] = 1;
      area_ += 2 * e[(axis + 1) % 3] * e[(axis + 2) % 3] * area_scale(n);
    }
    return;
  }
  // Otherwise the mean of area_scale / object density over a midpoint grid of the unit square:
  // exact (to rounding) when the factor is constant (planar shapes), else an estimate.
  const auto grid_mean = [&](int cells, bool& constant) {
    double sum = 0, first = 0;
    int count = 0;
    constant = true;
    for (int i = 0; i < cells; ++i) {
      for (int j = 0; j < cells; ++j) {
        SurfaceSample sample;
        if (!shape_->sample_area({(i + 0.5) / cells, (j + 0.5) / cells}, sample) || !(sample.pdf > 0))
          continue;
        const double value = area_scale(sample.normal) / sample.pdf;
        if (count == 0) first = value;
        if (std::fabs(value - first) > 1e-12 * first) constant = false;
        sum += value;
        ++count;
      }
    }
    return count > 0 ? sum / count : 0.0;
  };
  bool constant = false;
  area_ = grid_mean(16, constant);
  if (!constant) area_ = grid_mean(256, constant);
}

double TransformedShape::area_scale(const Vec3& object_normal) const {
  return determinant_ * length(object_to_world_.normal(object_normal)) / length(object_normal);
}

bool TransformedShape::sample_area(const Vec2& u, SurfaceSample& sample) const {
  SurfaceSample object;
  if (!shape_->sample_area(u, object)) return false;
  const double scale = area_scale(object.normal);
  if (!(scale > 0)) return false;
  sample.position = object_to_world_.point(object.position);
  sample.normal = normalize(object_to_world_.normal(object.normal));
  sample.pdf = object.pdf / scale;
  return sample.pdf > 0 && std::isfinite(sample.pdf);
}

double TransformedShape::pdf_area(const SurfaceHit& hit) const {
  // The hit as the object-space shape reported it.
  SurfaceHit object;
  object.t = hit.t;
  object.position = hit.object_position;
  object.object_position = hit.object_position;
  object.geometric_normal = hit.object_normal();
  object.shading_normal = object.geometric_normal;
  object.uv = hit.uv;
  object.dpdu = hit.object_dpdu();
  object.dpdv = hit.object_dpdv();
  const double scale = area_scale(object.geometric_normal);
  if (!(scale > 0)) return 0;
  return shape_->pdf_area(object) / scale;
}

Ray TransformedShape::to_object(const Ray& ray, double& scale) const {
  Ray local;
  local.origin = world_to_object_.point(ray.origin);
  const Vec3 direction = world_to_object_.vector(ray.direction);
  scale = length(direction);
  local.direction = direction / scale;
  local.t_min = ray.t_min * scale;
  local.t_max = ray.t_max * scale;
  return local;
}

bool TransformedShape::intersect(const Ray& ray, SurfaceHit& hit) const {
  double scale = 1;
  const Ray local = to_object(ray, scale);
  if (!shape_->intersect(local, hit)) return false;
  hit.t /= scale;
  hit.object_position = hit.position;
  hit.position = object_to_world_.point(hit.position);
  // The object-space normal is kept before the world one replaces it (pdf_area and the
  // spherical texture mapping read it).
  hit.object_normal_ = hit.geometric_normal;
  hit.geometric_normal = normalize(object_to_world_.normal(hit.geometric_normal));
  hit.shading_normal = normalize(object_to_world_.normal(hit.shading_normal));
  hit.transformed = true;
  hit.object_dpdu_ = hit.dpdu;
  hit.object_dpdv_ = hit.dpdv;
  hit.dpdu = object_to_world_.vector(hit.dpdu);
  hit.dpdv = object_to_world_.vector(hit.dpdv);
  hit.terminator_lift_outside = object_to_world_.vector(hit.terminator_lift_outside);
  hit.terminator_lift_inside = object_to_world_.vector(hit.terminator_lift_inside);
  return true;
}

bool TransformedShape::occluded(const Ray& ray) const {
  double scale = 1;
  return shape_->occluded(to_object(ray, scale));
}

Bounds3 TransformedShape::bounds() const {
  return object_to_world_.bounds(shape_->bounds());
}

namespace {

// A corner of a triangle being clipped.
struct ClipCorner {
  Vec3 position;
  Vec2 uv;
};

// Sutherland and Hodgman 1974, "Reentrant polygon clipping": the convex polygon cut by the six
// planes of box in turn. A new point lies on the segment from the corner inside to the corner
// outside, computed in that direction whichever way the polygon runs, so the two triangles
// sharing an edge cut it at bit-identical points. uv is interpolated linearly, which is exact on
// a flat triangle whose uv is affine (a plane's).
std::vector<ClipCorner> clip_to_box(std::vector<ClipCorner> polygon, const Bounds3& box) {
  for (int axis = 0; axis < 3 && !polygon.empty(); ++axis) {
    for (const bool upper : {false, true}) {
      const double bound = upper ? box.upper[axis] : box.lower[axis];
      const auto inside = [&](const ClipCorner& c) {
        return upper ? c.position[axis] <= bound : c.position[axis] >= bound;
      };
      std::vector<ClipCorner> kept;
      for (std::size_t i = 0; i < polygon.size(); ++i) {
        const ClipCorner& current = polygon[i];
        const ClipCorner& next = polygon[(i + 1) % polygon.size()];
        if (inside(current)) kept.push_back(current);
        if (inside(current) != inside(next)) {
          const ClipCorner& in = inside(current) ? current : next;
          const ClipCorner& out = inside(current) ? next : current;
          const double s = (bound - in.position[axis]) / (out.position[axis] - in.position[axis]);
          ClipCorner cut{in.position + (out.position - in.position) * s,
                         {in.uv.x + (out.uv.x - in.uv.x) * s, in.uv.y + (out.uv.y - in.uv.y) * s}};
          cut.position[axis] = bound;  // exactly on the box
          kept.push_back(cut);
        }
      }
      polygon = std::move(kept);
    }
  }
  return polygon;
}

}  // namespace

void TransformedShape::tessellate(const TessellationSettings& settings, TriangleMesh& mesh) const {
  MeshAppender out(mesh);
  const bool unbounded = !shape_->bounds().is_finite();
  const bool clip_usable = !settings.clip.empty() && settings.clip.is_finite();
  TessellationSettings object_settings = settings;
  if (unbounded && clip_usable) object_settings.clip = world_to_object_.bounds(settings.clip);
  TriangleMesh object_mesh;
  shape_->tessellate(object_settings, object_mesh);
  object_mesh.transform(object_to_world_);

  const auto corner_uvs = [&](std::size_t t) {
    return object_mesh.corner_uvs.empty() ? kDefaultCornerUvs : object_mesh.corner_uvs[t];
  };
  if (!(unbounded && clip_usable)) {
    std::vector<uint32_t> ids(object_mesh.positions.size());
    for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = out.vertex(object_mesh.positions[i]);
    for (std::size_t t = 0; t < object_mesh.triangles.size(); ++t) {
      const auto& tri = object_mesh.triangles[t];
      out.triangle({ids[tri[0]], ids[tri[1]], ids[tri[2]]}, corner_uvs(t));
    }
    return;
  }
  for (std::size_t t = 0; t < object_mesh.triangles.size(); ++t) {
    const auto& tri = object_mesh.triangles[t];
    std::vector<ClipCorner> polygon;
    const std::array<Vec2, 3> uvs = corner_uvs(t);
    for (int k = 0; k < 3; ++k) polygon.push_back({object_mesh.positions[tri[k]], uvs[k]});
    polygon = clip_to_box(std::move(polygon), settings.clip);
    // A point made by clipping is the same vertex (the appender welds by position) as the
    // neighbouring triangle's, which is computed bit for bit the same.
    std::vector<uint32_t> ids;
    for (const ClipCorner& corner : polygon) ids.push_back(out.vertex(corner.position));
    // The clipped triangle is convex: a fan (zero-area pieces are dropped by the appender).
    for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
      out.triangle({ids[0], ids[k], ids[k + 1]}, {polygon[0].uv, polygon[k].uv, polygon[k + 1].uv});
  }
}

}  // namespace candela
