#include "radiosity/radiosity_mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "math/constants.h"
#include "raster/tessellated_scene.h"
#include "scene/scene.h"
#include "shading/material.h"

namespace candela {
namespace {

// The most elements a mesh may have (classic radiosity's scale is 10⁴; 2²⁴ leaves room and still fits).
constexpr uint64_t kMaxElements = uint64_t{1} << 24;

// 000 §6.7.1: patches (and elements) by binary subdivision. Longest-edge bisection: the
// longest edge (k, k+1) is halved at m and the triangle becomes (k, m, k+2) and (m, k+1, k+2),
// both with the original winding. Every split halves the area, and the longest edge of the
// descendants shrinks geometrically (Rivara's bisection), so the recursion ends; the pieces tile
// the triangle exactly.
void bisect(const CornerTriangle& triangle, double max_edge, std::vector<CornerTriangle>& out) {
  int longest = 0;
  double longest_length = -1;
  for (int k = 0; k < 3; ++k) {
    const double edge = length(triangle[(k + 1) % 3].position - triangle[k].position);
    if (edge > longest_length) {
      longest_length = edge;
      longest = k;
    }
  }
  if (longest_length <= max_edge) {
    out.push_back(triangle);
    return;
  }
  const MeshCorner& a = triangle[longest];
  const MeshCorner& b = triangle[(longest + 1) % 3];
  const MeshCorner& c = triangle[(longest + 2) % 3];
  const MeshCorner m = midpoint(a, b);
  bisect({a, m, c}, max_edge, out);
  bisect({m, b, c}, max_edge, out);
}

}  // namespace

MeshCorner midpoint(const MeshCorner& a, const MeshCorner& b) {
  return {(a.position + b.position) * 0.5, (a.object_position + b.object_position) * 0.5,
          Vec2{(a.uv.x + b.uv.x) * 0.5, (a.uv.y + b.uv.y) * 0.5}};
}

RadiositySurface make_radiosity_surface(const Scene& scene, const CornerTriangle& triangle,
                                        uint32_t primitive) {
  RadiositySurface surface;
  for (int k = 0; k < 3; ++k) surface.corners[k] = triangle[k].position;
  const Vec3 face_cross =
      cross(triangle[1].position - triangle[0].position, triangle[2].position - triangle[0].position);
  surface.area = 0.5 * length(face_cross);
  surface.normal = normalize(face_cross);
  surface.centroid = (triangle[0].position + triangle[1].position + triangle[2].position) / 3.0;
  surface.primitive = primitive;
  surface.object = scene.primitives[primitive].object;
  surface.material = scene.primitives[primitive].material;
  surface.two_sided = scene.objects[surface.object].two_sided;

  SurfaceHit hit;
  hit.position = surface.centroid;
  hit.geometric_normal = surface.normal;
  hit.shading_normal = surface.normal;
  hit.object_position =
      (triangle[0].object_position + triangle[1].object_position + triangle[2].object_position) / 3.0;
  hit.uv = Vec2{(triangle[0].uv.x + triangle[1].uv.x + triangle[2].uv.x) / 3.0,
                (triangle[0].uv.y + triangle[1].uv.y + triangle[2].uv.y) / 3.0};
  // Any tangent frame in the surface (only bump mapping reads it, and ρ does not depend on it).
  hit.dpdu = normalize(triangle[1].position - triangle[0].position);
  hit.dpdv = cross(surface.normal, hit.dpdu);
  const Material& material = scene.materials[surface.material];
  const SurfaceProperties properties = material.at(hit);
  surface.reflectance = properties.diffuse_albedo();
  surface.emission = material.emission;
  return surface;
}

namespace {

FormFactorGeometry geometry_of(const std::vector<RadiositySurface>& surfaces) {
  FormFactorGeometry geometry;
  geometry.mesh.positions.reserve(3 * surfaces.size());
  for (uint32_t i = 0; i < surfaces.size(); ++i) {
    const auto first = static_cast<uint32_t>(geometry.mesh.positions.size());
    for (const Vec3& corner : surfaces[i].corners) geometry.mesh.positions.push_back(corner);
    geometry.mesh.triangles.push_back({first, first + 1, first + 2});
    geometry.element_of_triangle.push_back(i);
    geometry.hidden_from_behind.push_back(surfaces[i].two_sided ? 1 : 0);
  }
  geometry.element_count = static_cast<uint32_t>(surfaces.size());
  return geometry;
}

RadiositySystem system_of(const std::vector<RadiositySurface>& surfaces) {
  RadiositySystem system;
  for (const RadiositySurface& surface : surfaces) {
    system.areas.push_back(surface.area);
    system.reflectance.push_back(surface.reflectance);
    system.emission.push_back(surface.emission + surface.first_shot);
  }
  return system;
}

// The point of triangle (a, b, c) closest to p (Ericson, Real-Time Collision Detection §5.1.5).
Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denominator = 1 / (va + vb + vc);
  return a + ab * (vb * denominator) + ac * (vc * denominator);
}

// The fraction of the segment a + t·direction, t ∈ [0, 1], inside a counter-clockwise triangle
// (clipped to the three edges' half-planes); 0 when it misses.
double segment_inside(const std::array<Vec2, 3>& corners, const Vec2& a, const Vec2& direction) {
  double t0 = 0, t1 = 1;
  for (int k = 0; k < 3 && t0 <= t1; ++k) {
    const Vec2 e0 = corners[static_cast<std::size_t>(k)], e1 = corners[static_cast<std::size_t>((k + 1) % 3)];
    const Vec2 edge{e1.x - e0.x, e1.y - e0.y};
    // Inside: to the left of each counter-clockwise edge.
    const double start = edge.x * (a.y - e0.y) - edge.y * (a.x - e0.x);
    const double change = edge.x * direction.y - edge.y * direction.x;
    if (std::fabs(change) < 1e-300) {
      if (start < 0) return 0;
      continue;
    }
    const double t_edge = -start / change;
    if (change > 0)
      t0 = std::max(t0, t_edge);
    else
      t1 = std::min(t1, t_edge);
  }
  return std::max(0.0, t1 - t0);
}

// Where surfaces meet (SPEC §10: the remedy for the light and shadow leaks of 000 §6.5.1): every
// triangle (a patch) is cut along the lines where a cutter — a triangle of another object — meets
// or crosses its plane inside it: a box standing on the floor cuts the floor's patches along its
// footprint, so that no patch or element straddles the contact, half lit and half hidden. The
// patches are cut, not the surfaces they come from, so that a cut runs at most across one patch.
//
// A cut is the infinite line through the contact segment, in the triangle's plane; the pieces on
// either side (halves of a convex polygon, fanned into triangles with the original winding) carry
// positions, object positions and uvs interpolated linearly along the cut edges.
void cut_at_contacts(const Scene& scene, std::vector<CornerTriangle>& triangles,
                     std::vector<uint32_t>& primitives, const std::vector<CornerTriangle>& cutters,
                     const std::vector<uint32_t>& cutter_primitives, double tolerance) {
  const std::size_t count = triangles.size();
  const auto box_of = [](const CornerTriangle& triangle) {
    Bounds3 box;
    for (const MeshCorner& corner : triangle) box.extend(corner.position);
    return box;
  };
  // The cutters that may touch each triangle: boxes overlapping within the tolerance, found
  // through a grid of the cutters (walking them sorted by their lowest x from the first
  // took 16 s for the dragon's 100,000), taken in the order of their lowest x (the cuts' order).
  std::vector<Bounds3> cutter_boxes(cutters.size());
  std::vector<RadiositySurface> cutter_surfaces(cutters.size());
  for (std::size_t c = 0; c < cutters.size(); ++c) {
    cutter_boxes[c] = box_of(cutters[c]);
    for (int k = 0; k < 3; ++k) cutter_surfaces[c].corners[k] = cutters[c][k].position;
  }
  std::vector<std::size_t> by_x(cutters.size());
  for (std::size_t c = 0; c < cutters.size(); ++c) by_x[c] = c;
  std::sort(by_x.begin(), by_x.end(),
            [&](std::size_t a, std::size_t b) { return cutter_boxes[a].lower.x < cutter_boxes[b].lower.x; });
  std::vector<std::size_t> rank(cutters.size());
  for (std::size_t i = 0; i < by_x.size(); ++i) rank[by_x[i]] = i;
  const SurfaceGrid grid(cutter_surfaces, tolerance);
  std::vector<std::vector<std::size_t>> touching(count);
  for (std::size_t t = 0; t < count; ++t) {
    const Bounds3 box = box_of(triangles[t]);
    const uint32_t object = scene.primitives[primitives[t]].object;
    std::vector<std::size_t>& list = touching[t];
    grid.for_each_near(box, [&](uint32_t c) {
      const Bounds3& other = cutter_boxes[c];
      if (other.upper.x < box.lower.x - tolerance || other.lower.x > box.upper.x + tolerance ||
          other.lower.y > box.upper.y + tolerance || box.lower.y > other.upper.y + tolerance ||
          other.lower.z > box.upper.z + tolerance || box.lower.z > other.upper.z + tolerance)
        return;
      if (scene.primitives[cutter_primitives[c]].object == object) return;
      list.push_back(c);
    });
    std::sort(list.begin(), list.end(), [&](std::size_t a, std::size_t b) { return rank[a] < rank[b]; });
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  std::vector<CornerTriangle> result;
  std::vector<uint32_t> result_primitives;
  for (std::size_t t = 0; t < count; ++t) {
    const CornerTriangle& triangle = triangles[t];
    const Vec3 origin = triangle[0].position;
    const Vec3 face = cross(triangle[1].position - origin, triangle[2].position - origin);
    std::vector<CornerTriangle> pieces{triangle};
    if (!(length(face) > 0) || touching[t].empty()) {
      result.push_back(triangle);
      result_primitives.push_back(primitives[t]);
      continue;
    }
    const Vec3 n = normalize(face);
    const Vec3 axis_u = normalize(triangle[1].position - origin), axis_v = cross(n, axis_u);
    const auto plane_coordinates = [&](const Vec3& p) {
      return Vec2{dot(p - origin, axis_u), dot(p - origin, axis_v)};
    };
    std::array<Vec2, 3> corners2;
    for (int k = 0; k < 3; ++k) corners2[k] = plane_coordinates(triangle[k].position);
    for (const std::size_t other : touching[t]) {
      // The other triangle's crossing of this plane: the points where its edges meet the plane.
      std::array<double, 3> height;
      for (int k = 0; k < 3; ++k) height[k] = dot(cutters[other][k].position - origin, n);
      const double highest = std::max({height[0], height[1], height[2]}),
                   lowest = std::min({height[0], height[1], height[2]});
      if (lowest > tolerance || highest < -tolerance) continue;    // wholly on one side
      if (highest <= tolerance && lowest >= -tolerance) continue;  // coplanar: no line
      std::vector<Vec2> crossing;
      for (int k = 0; k < 3; ++k) {
        const Vec3& p = cutters[other][k].position;
        const Vec3& q = cutters[other][(k + 1) % 3].position;
        const double hp = height[k], hq = height[(k + 1) % 3];
        if (std::fabs(hp) <= tolerance)
          crossing.push_back(plane_coordinates(p));
        else if ((hp > tolerance && hq < -tolerance) || (hp < -tolerance && hq > tolerance))
          crossing.push_back(plane_coordinates(p + (q - p) * (hp / (hp - hq))));
      }
      if (crossing.size() < 2) continue;
      Vec2 a = crossing[0], b = crossing[1];
      for (const Vec2& c : crossing)  // the two farthest apart
        if (std::hypot(c.x - a.x, c.y - a.y) > std::hypot(b.x - a.x, b.y - a.y)) b = c;
      const Vec2 direction{b.x - a.x, b.y - a.y};
      const double segment_length = std::hypot(direction.x, direction.y);
      if (!(segment_length > tolerance)) continue;
      // Does the segment reach the triangle's interior?
      if (!(segment_inside(corners2, a, direction) * segment_length > tolerance)) continue;
      // Cut every piece the segment crosses by the line through a and b (a piece is convex, so
      // the cut runs across it); pieces the segment does not reach stay whole, so the cut does
      // not run on across the rest of the surface.
      std::vector<CornerTriangle> cut;
      for (const CornerTriangle& piece : pieces) {
        const std::array<Vec2, 3> piece2{plane_coordinates(piece[0].position),
                                         plane_coordinates(piece[1].position),
                                         plane_coordinates(piece[2].position)};
        if (!(segment_inside(piece2, a, direction) * segment_length > tolerance)) {
          cut.push_back(piece);
          continue;
        }
        std::array<double, 3> side;
        for (int k = 0; k < 3; ++k) {
          const Vec2 p = plane_coordinates(piece[k].position);
          side[k] = (direction.x * (p.y - a.y) - direction.y * (p.x - a.x)) / segment_length;
          if (std::fabs(side[k]) <= tolerance) side[k] = 0;
        }
        if (!(std::max({side[0], side[1], side[2]}) > 0 && std::min({side[0], side[1], side[2]}) < 0)) {
          cut.push_back(piece);
          continue;
        }
        for (const double sign : {1.0, -1.0}) {
          // Sutherland–Hodgman against sign·side ≥ 0, then a fan.
          std::vector<MeshCorner> polygon;
          for (int k = 0; k < 3; ++k) {
            const int next = (k + 1) % 3;
            const double sp = sign * side[k], sq = sign * side[next];
            if (sp >= 0) polygon.push_back(piece[k]);
            if ((sp > 0 && sq < 0) || (sp < 0 && sq > 0)) {
              const double f = sp / (sp - sq);
              const MeshCorner& p = piece[k];
              const MeshCorner& q = piece[next];
              polygon.push_back({p.position + (q.position - p.position) * f,
                                 p.object_position + (q.object_position - p.object_position) * f,
                                 Vec2{p.uv.x + (q.uv.x - p.uv.x) * f, p.uv.y + (q.uv.y - p.uv.y) * f}});
            }
          }
          for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
            cut.push_back({polygon[0], polygon[k], polygon[k + 1]});
        }
      }
      pieces = std::move(cut);
    }
    for (const CornerTriangle& piece : pieces) {
      result.push_back(piece);
      result_primitives.push_back(primitives[t]);
    }
  }
  triangles = std::move(result);
  primitives = std::move(result_primitives);
}

}  // namespace

RadiositySystem RadiosityMesh::patch_system() const {
  return system_of(patches);
}
ElementSystem RadiosityMesh::element_system() const {
  RadiositySystem surfaces = system_of(elements);
  return {{patch_of_element.begin(), patch_of_element.end()},
          std::move(surfaces.areas),
          std::move(surfaces.reflectance),
          std::move(surfaces.emission)};
}

double RadiosityMesh::patch_area() const {
  double sum = 0;
  for (const auto& patch : patches) sum += patch.area;
  return sum;
}

double RadiosityMesh::element_area() const {
  double sum = 0;
  for (const auto& element : elements) sum += element.area;
  return sum;
}

uint32_t RadiosityMesh::element_at(uint32_t primitive, const Vec3& point, const Vec3& toward) const {
  if (primitive >= elements_of_primitive.size()) return UINT32_MAX;
  uint32_t best = UINT32_MAX;
  double best_distance = std::numeric_limits<double>::infinity();
  bool best_faces = false;
  // Twins of a two-sided surface are the same triangle wound both ways: their distances agree to
  // rounding (the corners in another order), far inside this.
  const double twin_tolerance = 1e-12 * (element_size * element_size + length_squared(point));
  // The nearest element, ties to the lowest index (the same answer in any visiting order); among
  // a two-sided surface's twins, the one facing `toward`.
  const auto consider = [&](uint32_t e) {
    if (elements[e].primitive != primitive) return;
    const auto& corners = elements[e].corners;
    const double distance =
        length_squared(point - closest_point_on_triangle(point, corners[0], corners[1], corners[2]));
    const bool faces = elements[e].two_sided && dot(elements[e].normal, toward) > 0;
    const bool twins = elements[e].two_sided && best != UINT32_MAX && elements[best].two_sided &&
                       std::fabs(distance - best_distance) <= twin_tolerance;
    const bool better = twins ? (faces != best_faces ? faces : e < best)
                              : (distance < best_distance || (distance == best_distance && e < best));
    if (better) {
      best_distance = distance;
      best = e;
      best_faces = faces;
    }
  };
  // Near the point first: every element within `reach` of it overlaps the box of that half-width
  // around it, so a nearest element found within that distance is the nearest of all. The reach
  // grows from the smallest cell to the largest (the point lies on an element nearly always).
  if (!element_grid.empty()) {
    const double largest = element_grid.cell_size();
    for (double reach = element_grid.smallest_cell_size();; reach = std::min(4 * reach, largest)) {
      Bounds3 around;
      around.extend(point - Vec3(reach, reach, reach));
      around.extend(point + Vec3(reach, reach, reach));
      element_grid.for_each_near(around, consider);
      if (best != UINT32_MAX && best_distance <= reach * reach) return best;
      if (reach >= largest) break;
    }
    // Farther than a cell from the mesh's box: off the mesh (an unbounded plane beyond where
    // it was cut), not a point of any element.
    const Bounds3& mesh_box = element_grid.bounds();
    for (int axis = 0; axis < 3; ++axis)
      if (point[axis] < mesh_box.lower[axis] - largest || point[axis] > mesh_box.upper[axis] + largest)
        return UINT32_MAX;
  }
  for (const uint32_t e : elements_of_primitive[primitive]) consider(e);  // far from every element
  return best;
}

std::vector<std::vector<uint32_t>> RadiosityMesh::element_neighbours() const {
  const std::size_t count = elements.size();
  std::vector<std::vector<uint32_t>> neighbours(count);
  if (count == 0) return neighbours;
  Bounds3 bounds;
  double largest_edge = 0;
  for (const RadiositySurface& element : elements)
    for (int k = 0; k < 3; ++k) {
      bounds.extend(element.corners[k]);
      largest_edge = std::max(largest_edge, length(element.corners[(k + 1) % 3] - element.corners[k]));
    }
  const double tolerance = 1e-7 * std::max(largest_edge, length(bounds.diagonal()) * 1e-3);
  const SurfaceGrid grid(elements, tolerance);  // touching elements share a cell
  // How many corners of a lie on the boundary of b (within the tolerance).
  const auto corners_on_boundary = [&](const RadiositySurface& a, const RadiositySurface& b) {
    int on = 0;
    for (const Vec3& p : a.corners)
      for (int k = 0; k < 3; ++k) {
        const Vec3 start = b.corners[k], edge = b.corners[(k + 1) % 3] - start;
        const double t = std::clamp(dot(p - start, edge) / std::max(dot(edge, edge), 1e-300), 0.0, 1.0);
        if (length(p - (start + edge * t)) <= tolerance) {
          ++on;
          break;
        }
      }
    return on;
  };
  const double crease_cosine = std::cos(kPi / 4);
  for (uint32_t q = 0; q < count; ++q) {
    std::vector<uint32_t>& list = neighbours[q];
    Bounds3 box;
    for (const Vec3& corner : elements[q].corners) box.extend(corner);
    grid.for_each_near(box, [&](uint32_t other) {
      if (other == q || elements[other].object != elements[q].object) return;
      if (dot(elements[other].normal, elements[q].normal) < crease_cosine) return;
      // A shared piece of edge: two corners of one lie on the other's boundary.
      if (corners_on_boundary(elements[q], elements[other]) >= 2 ||
          corners_on_boundary(elements[other], elements[q]) >= 2)
        list.push_back(other);
    });
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return neighbours;
}

std::vector<uint32_t> RadiosityMesh::split_elements(const Scene& scene, const std::vector<bool>& split) {
  if (split.size() != elements.size())
    throw std::invalid_argument("radiosity mesh: " + std::to_string(split.size()) + " split flags for " +
                                std::to_string(elements.size()) + " elements");
  std::vector<RadiositySurface> new_elements;
  std::vector<uint32_t> new_patch_of_element, origin;
  std::vector<std::array<Vec3, 3>> new_object_corners;
  std::vector<std::array<Vec2, 3>> new_uvs;
  std::vector<uint32_t> new_first_element{0};
  for (std::size_t p = 0; p + 1 < first_element.size(); ++p) {
    for (uint32_t q = first_element[p]; q < first_element[p + 1]; ++q) {
      CornerTriangle triangle;
      for (int k = 0; k < 3; ++k)
        triangle[k] = {elements[q].corners[k], element_object_corners[q][k], element_uvs[q][k]};
      std::vector<CornerTriangle> pieces;
      if (split[q]) {
        // One bisection: a zero max_edge would recurse to the bottom, so halve by hand.
        int longest = 0;
        double longest_length = -1;
        for (int k = 0; k < 3; ++k) {
          const double edge = length(triangle[(k + 1) % 3].position - triangle[k].position);
          if (edge > longest_length) longest_length = edge, longest = k;
        }
        const MeshCorner& a = triangle[longest];
        const MeshCorner& b = triangle[(longest + 1) % 3];
        const MeshCorner& c = triangle[(longest + 2) % 3];
        const MeshCorner m = midpoint(a, b);
        pieces = {{a, m, c}, {m, b, c}};
      } else {
        pieces = {triangle};
      }
      for (const CornerTriangle& piece : pieces) {
        new_elements.push_back(split[q] ? make_radiosity_surface(scene, piece, elements[q].primitive)
                                        : elements[q]);
        new_patch_of_element.push_back(static_cast<uint32_t>(p));
        new_object_corners.push_back(
            {piece[0].object_position, piece[1].object_position, piece[2].object_position});
        new_uvs.push_back({piece[0].uv, piece[1].uv, piece[2].uv});
        origin.push_back(q);
      }
    }
    new_first_element.push_back(static_cast<uint32_t>(new_elements.size()));
  }
  elements = std::move(new_elements);
  patch_of_element = std::move(new_patch_of_element);
  element_object_corners = std::move(new_object_corners);
  element_uvs = std::move(new_uvs);
  first_element = std::move(new_first_element);
  for (auto& list : elements_of_primitive) list.clear();
  for (uint32_t q = 0; q < elements.size(); ++q) elements_of_primitive[elements[q].primitive].push_back(q);
  element_geometry = geometry_of(elements);
  element_grid = SurfaceGrid(elements, 0);
  return origin;
}

namespace {

// The sizes a mesh is built with, checked, and the scene's triangles before any split.
struct MeshStart : RadiosityInput {
  double patch_size = 0, element_size = 0;
};

MeshStart start_mesh(const Scene& scene, const RadiosityMeshSettings& settings) {
  if (!(settings.patch_size >= 0) || !std::isfinite(settings.patch_size) || !(settings.element_size >= 0) ||
      !std::isfinite(settings.element_size)) {
    throw std::invalid_argument("radiosity mesh: patch_size and element_size must be finite and >= 0");
  }
  MeshStart start;
  static_cast<RadiosityInput&>(start) = radiosity_input(scene, settings);
  start.patch_size = settings.patch_size > 0 ? settings.patch_size : start.scene_size / 8;
  start.element_size = settings.element_size > 0 ? settings.element_size : start.patch_size / 2;
  if (!(start.patch_size > 0)) throw std::invalid_argument("radiosity mesh: the scene has zero size");
  if (start.element_size > start.patch_size) {
    throw std::invalid_argument("radiosity mesh: element_size " + std::to_string(start.element_size) +
                                " exceeds patch_size " + std::to_string(start.patch_size));
  }
  return start;
}

double total_area(const std::vector<CornerTriangle>& triangles) {
  double area = 0;
  for (const CornerTriangle& t : triangles)
    area += 0.5 * length(cross(t[1].position - t[0].position, t[2].position - t[0].position));
  return area;
}

}  // namespace

RadiosityInput radiosity_input(const Scene& scene, const RadiosityMeshSettings& settings) {
  if (settings.segments < 3) {
    throw std::invalid_argument("radiosity mesh: segments " + std::to_string(settings.segments) +
                                " (must be >= 3)");
  }
  const Bounds3 clip = settings.clip.empty() ? scene.bounds() : settings.clip;
  if (clip.empty() || !clip.is_finite()) {
    throw std::invalid_argument(
        "radiosity mesh: the scene has no bounded shape and no clip box (where planes end)");
  }
  RadiosityInput input;
  input.scene_size = length(clip.diagonal());
  TessellationRequest request;
  request.max_segments = settings.segments;
  request.chord_tolerance = settings.chord_fraction * input.scene_size;
  request.clip = clip;
  const TessellatedScene tessellated = tessellate_scene(scene, request);
  input.triangles.resize(tessellated.triangle_count());
  input.primitives.assign(tessellated.primitives.begin(), tessellated.primitives.end());
  for (std::size_t t = 0; t < input.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      input.triangles[t][k] = {tessellated.corner_positions[3 * t + k],
                               tessellated.corner_object_positions[3 * t + k],
                               tessellated.corner_uvs[3 * t + k]};
  // A two-sided object's triangles again, wound the other way (its back side).
  const std::size_t one_sided = input.triangles.size();
  for (std::size_t t = 0; t < one_sided; ++t) {
    if (!scene.objects[tessellated.objects[t]].two_sided) continue;
    CornerTriangle back = input.triangles[t];
    std::swap(back[1], back[2]);
    input.triangles.push_back(back);
    input.primitives.push_back(input.primitives[t]);
  }
  return input;
}

RadiosityInput split_input_at_contacts(const Scene& scene, const RadiosityInput& input, double patch_size) {
  RadiosityInput split;
  split.scene_size = input.scene_size;
  for (std::size_t t = 0; t < input.triangles.size(); ++t) {
    bisect(input.triangles[t], patch_size, split.triangles);
    split.primitives.resize(split.triangles.size(), input.primitives[t]);
  }
  cut_at_contacts(scene, split.triangles, split.primitives, input.triangles, input.primitives,
                  1e-9 * input.scene_size);
  return split;
}

RadiosityMesh assemble_radiosity_mesh(std::vector<RadiositySurface> patches,
                                      std::vector<RadiositySurface> elements, std::vector<uint32_t> first,
                                      std::vector<std::array<Vec3, 3>> object_corners,
                                      std::vector<std::array<Vec2, 3>> uvs, std::size_t primitive_count) {
  RadiosityMesh mesh;
  mesh.patches = std::move(patches);
  mesh.elements = std::move(elements);
  mesh.first_element = std::move(first);
  mesh.element_object_corners = std::move(object_corners);
  mesh.element_uvs = std::move(uvs);
  mesh.patch_of_element.resize(mesh.elements.size());
  for (std::size_t p = 0; p + 1 < mesh.first_element.size(); ++p)
    for (uint32_t q = mesh.first_element[p]; q < mesh.first_element[p + 1]; ++q)
      mesh.patch_of_element[q] = static_cast<uint32_t>(p);
  mesh.elements_of_primitive.resize(primitive_count);
  for (uint32_t q = 0; q < mesh.elements.size(); ++q)
    mesh.elements_of_primitive[mesh.elements[q].primitive].push_back(q);
  for (const RadiositySurface& patch : mesh.patches)
    mesh.patch_size = std::max(mesh.patch_size, longest_edge(patch));
  for (const RadiositySurface& element : mesh.elements)
    mesh.element_size = std::max(mesh.element_size, longest_edge(element));
  mesh.element_geometry = geometry_of(mesh.elements);
  mesh.patch_geometry = geometry_of(mesh.patches);
  mesh.element_grid = SurfaceGrid(mesh.elements, 0);
  return mesh;
}

RadiosityMeshEstimate estimate_radiosity_mesh(const Scene& scene, const RadiosityMeshSettings& settings) {
  const MeshStart start = start_mesh(scene, settings);
  // No triangle whose longest edge is at most s is larger than the equilateral one, √3/4 s².
  const double area = total_area(start.triangles), largest = std::sqrt(3.0) / 4;
  RadiosityMeshEstimate estimate;
  estimate.patches = std::max(static_cast<double>(start.triangles.size()),
                              area / (largest * start.patch_size * start.patch_size));
  estimate.elements = std::max(estimate.patches, area / (largest * start.element_size * start.element_size));
  return estimate;
}

RadiosityMesh build_radiosity_mesh(const Scene& scene, const RadiosityMeshSettings& settings) {
  MeshStart start = start_mesh(scene, settings);
  const double scene_size = start.scene_size;
  RadiosityMesh result;
  result.patch_size = start.patch_size;
  result.element_size = start.element_size;
  std::vector<CornerTriangle>& triangles = start.triangles;
  std::vector<uint32_t>& primitives = start.primitives;
  // Elements bound the work: refuse a mesh far beyond what any solver could keep (a right
  // triangle with legs s/√2 has area s²/4, the smallest bisection keeps).
  const double estimated_elements =
      total_area(triangles) / (0.25 * result.element_size * result.element_size);
  if (estimated_elements > kMaxElements)
    throw std::invalid_argument(
        "radiosity mesh: about " + std::to_string(static_cast<uint64_t>(estimated_elements)) +
        " elements of size " + std::to_string(result.element_size) + " (at most " +
        std::to_string(kMaxElements) + "); raise radiosity.element_size and radiosity.patch_size");

  // Patches: each triangle bisected to patch_size, then cut where other objects meet it.
  std::vector<CornerTriangle> patches;
  std::vector<uint32_t> patch_primitives;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    bisect(triangles[t], result.patch_size, patches);
    patch_primitives.resize(patches.size(), primitives[t]);
  }
  if (settings.split_at_contacts)
    cut_at_contacts(scene, patches, patch_primitives, triangles, primitives, 1e-9 * scene_size);

  result.elements_of_primitive.resize(scene.primitives.size());
  result.first_element.push_back(0);
  std::vector<CornerTriangle> element_pieces;
  for (std::size_t p = 0; p < patches.size(); ++p) {
    const uint32_t primitive = patch_primitives[p];
    const CornerTriangle& patch = patches[p];
    const auto patch_index = static_cast<uint32_t>(result.patches.size());
    result.patches.push_back(make_radiosity_surface(scene, patch, primitive));
    element_pieces.clear();
    bisect(patch, result.element_size, element_pieces);  // 000 §6.7.1: elements within patches
    for (const CornerTriangle& element : element_pieces) {
      result.elements_of_primitive[primitive].push_back(static_cast<uint32_t>(result.elements.size()));
      result.elements.push_back(make_radiosity_surface(scene, element, primitive));
      result.patch_of_element.push_back(patch_index);
      result.element_object_corners.push_back(
          {element[0].object_position, element[1].object_position, element[2].object_position});
      result.element_uvs.push_back({element[0].uv, element[1].uv, element[2].uv});
    }
    result.first_element.push_back(static_cast<uint32_t>(result.elements.size()));
  }
  if (result.patches.empty()) throw std::invalid_argument("radiosity mesh: the scene has no surface to mesh");
  result.element_geometry = geometry_of(result.elements);
  result.patch_geometry = geometry_of(result.patches);
  result.element_grid = SurfaceGrid(result.elements, 0);
  return result;
}

}  // namespace candela
