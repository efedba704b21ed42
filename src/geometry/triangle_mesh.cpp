#include "geometry/triangle_mesh.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

#include "geometry/tessellation.h"
#include "math/constants.h"
#include "util/hash.h"

// The watertight test relies on every edge function a*b - c*d being rounded term by term:
// rounding is monotone, so the computed sign is then the exact sign or zero, and two triangles
// sharing an edge see exactly opposite values. A fused multiply-add would break both.
#if defined(__clang__)
#pragma clang fp contract(off)
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

namespace candela {

namespace {

bool is_finite(const Vec2& v) {
  return std::isfinite(v.x) && std::isfinite(v.y);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// TriangleMesh

void TriangleMesh::validate() const {
  for (std::size_t i = 0; i < positions.size(); ++i) {
    if (!candela::is_finite(positions[i]))
      throw std::invalid_argument("mesh position " + std::to_string(i) + " is not finite");
  }
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    for (uint32_t index : triangles[t]) {
      if (index >= positions.size())
        throw std::invalid_argument("triangle " + std::to_string(t) + " refers to vertex " +
                                    std::to_string(index) + " but the mesh has " +
                                    std::to_string(positions.size()) + " vertices");
    }
  }
  if (!corner_normals.empty() && corner_normals.size() != triangles.size())
    throw std::invalid_argument("mesh has " + std::to_string(corner_normals.size()) +
                                " corner normal triples for " + std::to_string(triangles.size()) +
                                " triangles");
  if (!corner_uvs.empty() && corner_uvs.size() != triangles.size())
    throw std::invalid_argument("mesh has " + std::to_string(corner_uvs.size()) + " corner uv triples for " +
                                std::to_string(triangles.size()) + " triangles");
  for (std::size_t t = 0; t < corner_normals.size(); ++t) {
    for (const Vec3& n : corner_normals[t]) {
      if (!candela::is_finite(n))
        throw std::invalid_argument("corner normal of triangle " + std::to_string(t) + " is not finite");
    }
  }
  for (std::size_t t = 0; t < corner_uvs.size(); ++t) {
    for (const Vec2& uv : corner_uvs[t]) {
      if (!is_finite(uv))
        throw std::invalid_argument("corner uv of triangle " + std::to_string(t) + " is not finite");
    }
  }
}

Vec3 TriangleMesh::face_cross(std::size_t triangle) const {
  const auto& tri = triangles[triangle];
  const Vec3& p0 = positions[tri[0]];
  return cross(positions[tri[1]] - p0, positions[tri[2]] - p0);
}

bool TriangleMesh::is_degenerate(std::size_t triangle) const {
  const Vec3 c = face_cross(triangle);
  return !(length_squared(c) > 0) || !candela::is_finite(c);
}

Bounds3 TriangleMesh::bounds() const {
  Bounds3 result;
  for (const auto& tri : triangles)
    for (uint32_t index : tri) result.extend(positions[index]);
  return result;
}

Bounds3 TriangleMesh::triangle_bounds(std::size_t triangle) const {
  Bounds3 result;
  for (uint32_t index : triangles[triangle]) result.extend(positions[index]);
  return result;
}

void TriangleMesh::transform(const Transform& object_to_world) {
  for (Vec3& p : positions) p = object_to_world.point(p);
  for (auto& corners : corner_normals) {
    for (Vec3& n : corners) {
      const Vec3 transformed = object_to_world.normal(n);
      const double len = length(transformed);
      n = len > 0 ? transformed / len : Vec3{};
    }
  }
  // A mirroring transform turns counter-clockwise corners clockwise: swap two corners so that
  // cross(p1 - p0, p2 - p0) follows the transformed normals.
  if (object_to_world.matrix().topLeftCorner<3, 3>().determinant() < 0) {
    for (auto& tri : triangles) std::swap(tri[1], tri[2]);
    for (auto& corners : corner_normals) std::swap(corners[1], corners[2]);
    for (auto& corners : corner_uvs) std::swap(corners[1], corners[2]);
  }
}

// ---------------------------------------------------------------------------------------------
// Smooth normals

void compute_corner_normals(TriangleMesh& mesh, double crease_angle_degrees) {
  if (!(crease_angle_degrees >= 0)) throw std::invalid_argument("crease angle must be >= 0 degrees");
  mesh.validate();
  const bool smooth_everything = crease_angle_degrees >= 180;
  const double cos_crease = std::cos(degrees_to_radians(std::min(crease_angle_degrees, 180.0)));

  // Weld by exact position (-0 and +0 compare equal, as they should).
  std::map<std::array<double, 3>, uint32_t> ids;
  std::vector<uint32_t> welded(mesh.positions.size());
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const Vec3& p = mesh.positions[i];
    const auto [it, inserted] =
        ids.emplace(std::array<double, 3>{p.x, p.y, p.z}, static_cast<uint32_t>(ids.size()));
    welded[i] = it->second;
  }

  const std::size_t triangle_count = mesh.triangles.size();
  std::vector<Vec3> area_normal(triangle_count);  // 2 * area * unit normal
  std::vector<Vec3> unit_normal(triangle_count);
  std::vector<bool> degenerate(triangle_count);
  for (std::size_t t = 0; t < triangle_count; ++t) {
    degenerate[t] = mesh.is_degenerate(t);
    if (degenerate[t]) continue;
    area_normal[t] = mesh.face_cross(t);
    unit_normal[t] = normalize(area_normal[t]);
  }

  // Triangles around each welded vertex (compressed rows). A non-degenerate triangle has three
  // distinct welded corners, so it appears at most once per vertex.
  std::vector<std::size_t> row_start(ids.size() + 1, 0);
  for (std::size_t t = 0; t < triangle_count; ++t) {
    if (degenerate[t]) continue;
    for (uint32_t index : mesh.triangles[t]) ++row_start[welded[index] + 1];
  }
  for (std::size_t v = 0; v < ids.size(); ++v) row_start[v + 1] += row_start[v];
  std::vector<uint32_t> around(row_start.back());
  std::vector<std::size_t> fill(row_start.begin(), row_start.end() - 1);
  for (std::size_t t = 0; t < triangle_count; ++t) {
    if (degenerate[t]) continue;
    for (uint32_t index : mesh.triangles[t]) around[fill[welded[index]]++] = static_cast<uint32_t>(t);
  }

  mesh.corner_normals.assign(triangle_count, {Vec3{}, Vec3{}, Vec3{}});
  for (std::size_t t = 0; t < triangle_count; ++t) {
    if (degenerate[t]) continue;
    const Vec3& own = unit_normal[t];
    for (int corner = 0; corner < 3; ++corner) {
      const uint32_t vertex = welded[mesh.triangles[t][corner]];
      Vec3 sum;
      for (std::size_t k = row_start[vertex]; k < row_start[vertex + 1]; ++k) {
        const uint32_t other = around[k];
        if (other == t || smooth_everything || dot(own, unit_normal[other]) >= cos_crease)
          sum += area_normal[other];
      }
      // Opposite faces can cancel (a two-sided sheet smoothed at 180 degrees): keep the face's
      // own normal rather than a zero or reversed one.
      const double len = length(sum);
      mesh.corner_normals[t][corner] = (len > 0 && dot(sum, own) > 0) ? sum / len : own;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// The watertight test

bool WatertightRay::edges(const Vec3& p0, const Vec3& p1, const Vec3& p2, double& u, double& v, double& w,
                          double& det) const {
  // Vertices relative to the ray origin, sheared.
  const Vec3 a = p0 - origin;
  const Vec3 b = p1 - origin;
  const Vec3 c = p2 - origin;
  const double ax = a[kx] - sx * a[kz];
  const double ay = a[ky] - sy * a[kz];
  const double bx = b[kx] - sx * b[kz];
  const double by = b[ky] - sy * b[kz];
  const double cx = c[kx] - sx * c[kz];
  const double cy = c[ky] - sy * c[kz];

  // Edge functions: u weights p0 (edge p1-p2), v weights p1, w weights p2.
  u = cx * by - cy * bx;
  v = ax * cy - ay * cx;
  w = bx * ay - by * ax;
  // The paper's fallback to higher precision when the ray passes (numerically) through an edge.
  if (u == 0 || v == 0 || w == 0) {
    using Long = long double;
    u = static_cast<double>(Long(cx) * Long(by) - Long(cy) * Long(bx));
    v = static_cast<double>(Long(ax) * Long(cy) - Long(ay) * Long(cx));
    w = static_cast<double>(Long(bx) * Long(ay) - Long(by) * Long(ax));
  }
  if ((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0)) return false;
  det = u + v + w;
  return det != 0;
}

bool WatertightRay::distance(const Vec3& p0, const Vec3& p1, const Vec3& p2, double& t) const {
  double u, v, w, det;
  if (!edges(p0, p1, p2, u, v, w, det)) return false;
  const double az = sz * (p0[kz] - origin[kz]);
  const double bz = sz * (p1[kz] - origin[kz]);
  const double cz = sz * (p2[kz] - origin[kz]);
  t = (u * az + v * bz + w * cz) / det;
  return t > t_min && t < t_max;
}

bool WatertightRay::intersect(const Vec3& p0, const Vec3& p1, const Vec3& p2,
                              TriangleIntersection& result) const {
  double u, v, w, det;
  if (!edges(p0, p1, p2, u, v, w, det)) return false;
  const double az = sz * (p0[kz] - origin[kz]);
  const double bz = sz * (p1[kz] - origin[kz]);
  const double cz = sz * (p2[kz] - origin[kz]);
  const double t = (u * az + v * bz + w * cz) / det;
  if (!(t > t_min && t < t_max)) return false;

  result.t = t;
  result.b0 = u / det;
  result.b1 = v / det;
  result.b2 = w / det;
  return true;
}

bool intersect_triangle(const Ray& ray, const Vec3& p0, const Vec3& p1, const Vec3& p2,
                        TriangleIntersection& result) {
  return WatertightRay(ray).intersect(p0, p1, p2, result);
}

// ---------------------------------------------------------------------------------------------
// MeshTriangle

MeshTriangle::MeshTriangle(std::shared_ptr<const TriangleMesh> mesh, uint32_t triangle_index)
    : mesh_(std::move(mesh)), index_(triangle_index), degenerate_(true) {
  if (!mesh_) throw std::invalid_argument("triangle needs a mesh");
  if (index_ >= mesh_->triangles.size())
    throw std::invalid_argument("triangle index " + std::to_string(index_) +
                                " is out of range (the mesh has " + std::to_string(mesh_->triangles.size()) +
                                " triangles)");
  for (uint32_t index : mesh_->triangles[index_]) {
    if (index >= mesh_->positions.size())
      throw std::invalid_argument("triangle " + std::to_string(index_) + " refers to vertex " +
                                  std::to_string(index) + " but the mesh has " +
                                  std::to_string(mesh_->positions.size()) + " vertices");
  }
  if (!mesh_->corner_normals.empty() && mesh_->corner_normals.size() != mesh_->triangles.size())
    throw std::invalid_argument("mesh corner normals do not match its triangles");
  if (!mesh_->corner_uvs.empty() && mesh_->corner_uvs.size() != mesh_->triangles.size())
    throw std::invalid_argument("mesh corner uvs do not match its triangles");
  degenerate_ = mesh_->is_degenerate(index_);
}

void fill_triangle_hit(const TriangleMesh& mesh, std::size_t triangle, const Vec3& p0, const Vec3& p1,
                       const Vec3& p2, const TriangleIntersection& found, SurfaceHit& hit) {
  hit.t = found.t;
  hit.position = p0 * found.b0 + p1 * found.b1 + p2 * found.b2;
  hit.object_position = hit.position;
  const Vec3 normal = normalize(cross(p1 - p0, p2 - p0));
  hit.geometric_normal = normal;

  hit.shading_normal = normal;
  if (!mesh.corner_normals.empty()) {
    const auto& n = mesh.corner_normals[triangle];
    const Vec3 interpolated = n[0] * found.b0 + n[1] * found.b1 + n[2] * found.b2;
    const double len = length(interpolated);
    if (len > 0 && std::isfinite(len)) {
      hit.shading_normal = interpolated / len;
      hit.interpolated_normal = true;
      // Hanika 2021: P' = P − Σ b_i min(0, (P − V_i)·n_i) n_i, P moved above each vertex's tangent
      // plane it lies under (none where the surface is flat or hollow); the inside's with −n_i.
      const double b[3] = {found.b0, found.b1, found.b2};
      const Vec3 corners[3] = {p0, p1, p2};
      for (int i = 0; i < 3; ++i) {
        const double height = dot(hit.position - corners[i], n[i]);
        hit.terminator_lift_outside -= n[i] * (b[i] * std::min(0.0, height));
        hit.terminator_lift_inside -= n[i] * (b[i] * std::max(0.0, height));
      }
      // Vertex normals against the winding: their outside is the geometric normal's inside.
      if (dot(interpolated, normal) < 0) std::swap(hit.terminator_lift_outside, hit.terminator_lift_inside);
    }
  }

  // pbrt: solve [dp02 dp12] = [dpdu dpdv] [duv02 duv12] for the uv parameterisation.
  const Vec3 dp02 = p0 - p2;
  const Vec3 dp12 = p1 - p2;
  bool degenerate_uv;
  if (mesh.corner_uvs.empty()) {
    // kDefaultCornerUvs, (0, 0), (1, 0), (1, 1), in the general code below: duv02 = (-1, -1),
    // duv12 = (0, -1), uv_det = 1 and its inverse 1. Its products by 1 and -1 and its division are
    // exact, so what is left gives the same bits (the products by 0 stay: they make the -0 and
    // NaN the general code makes), for a fifth of the instructions of this function, which runs
    // once per nearest hit of every accelerator.
    hit.uv = {(0.0 * found.b0 + found.b1) + found.b2, (0.0 * found.b0 + 0.0 * found.b1) + found.b2};
    hit.dpdu = -dp02 - -dp12;
    hit.dpdv = -dp12 - dp02 * 0.0;
    degenerate_uv = false;
  } else {
    const auto& uv = mesh.corner_uvs[triangle];
    hit.uv = {uv[0].x * found.b0 + uv[1].x * found.b1 + uv[2].x * found.b2,
              uv[0].y * found.b0 + uv[1].y * found.b1 + uv[2].y * found.b2};
    const Vec2 duv02{uv[0].x - uv[2].x, uv[0].y - uv[2].y};
    const Vec2 duv12{uv[1].x - uv[2].x, uv[1].y - uv[2].y};
    const double uv_det = duv02.x * duv12.y - duv02.y * duv12.x;
    degenerate_uv = !(std::fabs(uv_det) >= 1e-9);
    if (!degenerate_uv) {
      const double inverse = 1.0 / uv_det;
      hit.dpdu = (dp02 * duv12.y - dp12 * duv02.y) * inverse;
      hit.dpdv = (dp12 * duv02.x - dp02 * duv12.x) * inverse;
    }
  }
  if (!degenerate_uv) {
    const Vec3 n = cross(hit.dpdu, hit.dpdv);
    degenerate_uv = !(length_squared(n) > 0) || !candela::is_finite(n);
  }
  if (degenerate_uv) orthonormal_basis(normal, hit.dpdu, hit.dpdv);
}

bool MeshTriangle::intersect(const Ray& ray, SurfaceHit& hit) const {
  if (degenerate_) return false;
  const auto& tri = mesh_->triangles[index_];
  const Vec3& p0 = mesh_->positions[tri[0]];
  const Vec3& p1 = mesh_->positions[tri[1]];
  const Vec3& p2 = mesh_->positions[tri[2]];
  TriangleIntersection found;
  if (!intersect_triangle(ray, p0, p1, p2, found)) return false;

  fill_triangle_hit(*mesh_, index_, p0, p1, p2, found, hit);
  return true;
}

bool MeshTriangle::occluded(const Ray& ray) const {
  if (degenerate_) return false;
  const auto& tri = mesh_->triangles[index_];
  TriangleIntersection found;
  return intersect_triangle(ray, mesh_->positions[tri[0]], mesh_->positions[tri[1]], mesh_->positions[tri[2]],
                            found);
}

Bounds3 MeshTriangle::bounds() const {
  return mesh_->triangle_bounds(index_);
}

void MeshTriangle::tessellate(const TessellationSettings&, TriangleMesh& mesh) const {
  // Copied before appending: mesh may be the very mesh this triangle belongs to.
  const auto& tri = mesh_->triangles[index_];
  const std::array<Vec3, 3> corners{mesh_->positions[tri[0]], mesh_->positions[tri[1]],
                                    mesh_->positions[tri[2]]};
  const std::array<Vec2, 3> uvs = mesh_->corner_uvs.empty() ? kDefaultCornerUvs : mesh_->corner_uvs[index_];
  MeshAppender out(mesh);
  out.triangle({out.vertex(corners[0]), out.vertex(corners[1]), out.vertex(corners[2])}, uvs);
}

double MeshTriangle::area() const {
  if (degenerate_) return 0;
  return 0.5 * length(mesh_->face_cross(index_));
}

bool MeshTriangle::sample_area(const Vec2& u, SurfaceSample& sample) const {
  const double triangle_area = area();
  if (!(triangle_area > 0)) return false;
  const auto& tri = mesh_->triangles[index_];
  const Vec3& p0 = mesh_->positions[tri[0]];
  const Vec3& p1 = mesh_->positions[tri[1]];
  const Vec3& p2 = mesh_->positions[tri[2]];
  const double root = std::sqrt(u.x);
  const double b0 = 1 - root, b1 = u.y * root;
  sample.position = p0 * b0 + p1 * b1 + p2 * (1 - b0 - b1);
  sample.normal = normalize(cross(p1 - p0, p2 - p0));  // as fill_triangle_hit
  sample.pdf = 1 / triangle_area;
  return true;
}

double MeshTriangle::pdf_area(const SurfaceHit&) const {
  const double triangle_area = area();
  return triangle_area > 0 ? 1 / triangle_area : 0;
}

std::vector<bool> repeated_triangles(const TriangleMesh& mesh) {
  const std::size_t count = mesh.triangles.size();
  // Each triangle's corners from its least corner on (the same cyclic order), -0 read as +0.
  using Key = std::array<double, 9>;
  const auto key_of = [&](std::size_t t) {
    std::array<Vec3, 3> corners;
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = mesh.positions[mesh.triangles[t][k]];
      corners[k] = {p.x + 0.0, p.y + 0.0, p.z + 0.0};
    }
    const auto less = [](const Vec3& a, const Vec3& b) {
      return a.x != b.x ? a.x < b.x : a.y != b.y ? a.y < b.y : a.z < b.z;
    };
    int first = 0;
    for (int k = 1; k < 3; ++k)
      if (less(corners[k], corners[first])) first = k;
    Key key;
    for (int k = 0; k < 3; ++k)
      for (int axis = 0; axis < 3; ++axis) key[3 * k + axis] = corners[(first + k) % 3][axis];
    return key;
  };
  const auto hash_of = [](const Key& key) {
    uint64_t hash = 0;
    for (double value : key) hash = mix64(hash ^ std::bit_cast<uint64_t>(value));
    return hash;
  };
  // Sorted by hash, then index: in a run of equal hashes the lowest index of each key comes first.
  std::vector<std::pair<uint64_t, uint32_t>> order;
  order.reserve(count);
  for (std::size_t t = 0; t < count; ++t)
    if (!mesh.is_degenerate(t)) order.push_back({hash_of(key_of(t)), static_cast<uint32_t>(t)});
  std::sort(order.begin(), order.end());
  std::vector<bool> repeated(count, false);
  std::vector<std::pair<Key, uint32_t>> kept;  // the distinct keys of the current run
  for (std::size_t begin = 0; begin < order.size();) {
    std::size_t end = begin + 1;
    while (end < order.size() && order[end].first == order[begin].first) ++end;
    if (end - begin > 1) {
      kept.clear();
      for (std::size_t i = begin; i < end; ++i) {
        const Key key = key_of(order[i].second);
        const bool seen =
            std::any_of(kept.begin(), kept.end(), [&](const auto& k) { return k.first == key; });
        if (seen)
          repeated[order[i].second] = true;
        else
          kept.push_back({key, order[i].second});
      }
    }
    begin = end;
  }
  return repeated;
}

std::vector<std::unique_ptr<Shape>> make_triangles(std::shared_ptr<const TriangleMesh> mesh,
                                                   std::size_t* skipped_degenerate,
                                                   std::size_t* merged_duplicates) {
  if (!mesh) throw std::invalid_argument("make_triangles needs a mesh");
  mesh->validate();
  std::vector<std::unique_ptr<Shape>> shapes;
  shapes.reserve(mesh->triangles.size());
  std::size_t skipped = 0, merged = 0;
  const std::vector<bool> repeated = merged_duplicates ? repeated_triangles(*mesh) : std::vector<bool>();
  for (std::size_t t = 0; t < mesh->triangles.size(); ++t) {
    if (mesh->is_degenerate(t)) {
      ++skipped;
      continue;
    }
    if (!repeated.empty() && repeated[t]) {
      ++merged;
      continue;
    }
    shapes.push_back(std::make_unique<MeshTriangle>(mesh, static_cast<uint32_t>(t)));
  }
  if (skipped_degenerate) *skipped_degenerate = skipped;
  if (merged_duplicates) *merged_duplicates = merged;
  return shapes;
}

}  // namespace candela
