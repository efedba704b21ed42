#include "radiosity/vertex_radiosity.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <nanoflann.hpp>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

namespace candela {

namespace {

using Edge = std::pair<uint32_t, uint32_t>;  // vertex indices, lower first

Edge make_edge(uint32_t a, uint32_t b) {
  return a < b ? Edge{a, b} : Edge{b, a};
}

// Whether `point` lies strictly inside the segment a–b (a T-junction vertex on that edge).
bool strictly_inside_segment(const Vec3& point, const Vec3& a, const Vec3& b) {
  const Vec3 along = b - a;
  const double length_squared = dot(along, along);
  if (length_squared <= 0) return false;
  const double t = dot(point - a, along) / length_squared;
  if (t <= 1e-9 || t >= 1 - 1e-9) return false;
  const Vec3 offset = point - (a + along * t);
  return dot(offset, offset) <= 1e-18 * length_squared;
}

// The vertices within a distance of a point (nanoflann's k-d tree, SPEC §16): what finds the
// T-junction vertices on an edge without scanning every vertex of its object per edge (which
// took 20 s on a 100,000-triangle mesh with open edges).
class VertexIndex {
 public:
  explicit VertexIndex(const std::vector<Vec3>& positions)
      : positions_{positions}, tree_(3, positions_, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {
    tree_.buildIndex();
  }
  // The vertices within `radius` of point (and a hair more), in increasing index order.
  void within(const Vec3& point, double radius, std::vector<uint32_t>& out) const {
    out.clear();
    if (positions_.positions.empty()) return;
    const double query[3] = {point.x, point.y, point.z};
    std::vector<std::pair<uint32_t, double>> matches;
    tree_.radiusSearch(query, radius * radius * (1 + 1e-9), matches, nanoflann::SearchParams(32, 0, false));
    for (const auto& match : matches) out.push_back(match.first);
    std::sort(out.begin(), out.end());
  }

 private:
  struct Positions {
    const std::vector<Vec3>& positions;
    std::size_t kdtree_get_point_count() const { return positions.size(); }
    double kdtree_get_pt(std::size_t index, std::size_t axis) const {
      return positions[index][static_cast<int>(axis)];
    }
    template <typename Box>
    bool kdtree_get_bbox(Box&) const {
      return false;
    }
  };
  Positions positions_;
  nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Positions>, Positions, 3, uint32_t>
      tree_;
};

}  // namespace

VertexRadiosity compute_vertex_radiosity(const std::vector<RadiositySurface>& elements,
                                         const std::vector<Color>& element_radiosity) {
  if (elements.size() != element_radiosity.size())
    throw std::invalid_argument("compute_vertex_radiosity: one radiosity per element expected");
  VertexRadiosity result;
  result.element_vertices.resize(elements.size());

  // Vertices shared by exact position within one object, between elements whose normals differ by
  // at most 45° (a crease keeps its own vertices on each side).
  const double crease_cosine = std::cos(std::acos(-1.0) / 4);
  struct Cluster {
    Vec3 normal;
    uint32_t vertex;
  };
  std::map<std::tuple<uint32_t, double, double, double>, std::vector<Cluster>> vertex_of_position;
  std::vector<std::vector<uint32_t>> elements_of_vertex;
  for (std::size_t q = 0; q < elements.size(); ++q) {
    const RadiositySurface& element = elements[q];
    for (int c = 0; c < 3; ++c) {
      const Vec3& p = element.corners[static_cast<std::size_t>(c)];
      std::vector<Cluster>& clusters = vertex_of_position[{element.object, p.x, p.y, p.z}];
      uint32_t vertex = UINT32_MAX;
      for (const Cluster& cluster : clusters)
        if (dot(cluster.normal, element.normal) >= crease_cosine) {
          vertex = cluster.vertex;
          break;
        }
      if (vertex == UINT32_MAX) {
        vertex = static_cast<uint32_t>(result.positions.size());
        clusters.push_back({element.normal, vertex});
        result.positions.push_back(p);
        result.object.push_back(element.object);
        elements_of_vertex.emplace_back();
      }
      result.element_vertices[q][static_cast<std::size_t>(c)] = vertex;
      elements_of_vertex[vertex].push_back(static_cast<uint32_t>(q));
    }
  }
  const std::size_t vertex_count = result.positions.size();

  std::map<Edge, std::vector<uint32_t>> elements_of_edge;
  for (std::size_t q = 0; q < elements.size(); ++q) {
    const auto& v = result.element_vertices[q];
    for (int c = 0; c < 3; ++c)
      elements_of_edge[make_edge(v[static_cast<std::size_t>(c)], v[static_cast<std::size_t>((c + 1) % 3)])]
          .push_back(static_cast<uint32_t>(q));
  }

  // Edges of one element only are boundary edges, unless they belong to a T-junction: an edge
  // with vertices of its surface strictly inside it, or a piece of such an edge.
  const VertexIndex vertex_index(result.positions);
  std::vector<uint32_t> near_edge;
  // A T-junction vertex on the edge a–b of a larger element, at a + t (b − a).
  struct Junction {
    uint32_t vertex, a, b;
    double t, length_squared;
  };
  std::vector<Junction> junctions;
  std::map<Edge, bool> is_boundary_edge;
  for (const auto& [edge, owners] : elements_of_edge)
    if (owners.size() == 1) is_boundary_edge[edge] = true;
  for (auto& [edge, boundary] : is_boundary_edge) {
    const Vec3& a = result.positions[edge.first];
    const Vec3& b = result.positions[edge.second];
    std::vector<uint32_t> on_edge{edge.first, edge.second};
    vertex_index.within((a + b) * 0.5, 0.5 * length(b - a), near_edge);
    for (const uint32_t v : near_edge)
      if (result.object[v] == result.object[edge.first] && strictly_inside_segment(result.positions[v], a, b))
        on_edge.push_back(v);
    if (on_edge.size() == 2) continue;
    boundary = false;
    // Without cracks, the T-junction vertices of this edge take the radiosity the
    // element holding the whole edge interpolates there (set below, after every vertex's own).
    for (std::size_t i = 2; i < on_edge.size(); ++i)
      junctions.push_back({on_edge[i], edge.first, edge.second,
                           dot(result.positions[on_edge[i]] - a, b - a) / dot(b - a, b - a),
                           dot(b - a, b - a)});
    for (std::size_t i = 2; i < on_edge.size(); ++i)
      elements_of_vertex[on_edge[i]].push_back(elements_of_edge[edge].front());
    for (std::size_t i = 0; i < on_edge.size(); ++i)
      for (std::size_t j = i + 1; j < on_edge.size(); ++j) {
        const auto piece = is_boundary_edge.find(make_edge(on_edge[i], on_edge[j]));
        if (piece != is_boundary_edge.end() && piece->first != edge) piece->second = false;
      }
  }
  result.kind.assign(vertex_count, VertexKind::interior);
  for (const auto& [edge, boundary] : is_boundary_edge)
    if (boundary) result.kind[edge.first] = result.kind[edge.second] = VertexKind::boundary;

  const auto mean_of = [&](const std::vector<uint32_t>& owners) {
    Color sum;
    for (const uint32_t q : owners) sum += element_radiosity[q];
    return owners.empty() ? Color() : sum * (1.0 / static_cast<double>(owners.size()));
  };
  // 000 §6.5: an interior vertex gets the mean of its elements.
  result.radiosity.assign(vertex_count, Color());
  for (uint32_t v = 0; v < vertex_count; ++v)
    if (result.kind[v] == VertexKind::interior) result.radiosity[v] = mean_of(elements_of_vertex[v]);

  // 000 §6.5: a boundary vertex v from the nearest interior vertex e joined to it by an edge,
  // B_v = 2 · mean(elements holding v and e) − B_e (B_1 + B_2 − B_e, or 2B_1 − B_e).
  std::vector<std::vector<uint32_t>> neighbours(vertex_count);
  for (const auto& [edge, owners] : elements_of_edge) {
    neighbours[edge.first].push_back(edge.second);
    neighbours[edge.second].push_back(edge.first);
  }
  for (uint32_t v = 0; v < vertex_count; ++v) {
    if (result.kind[v] == VertexKind::interior) continue;
    uint32_t nearest = UINT32_MAX;
    double nearest_distance = std::numeric_limits<double>::infinity();
    for (const uint32_t n : neighbours[v]) {
      if (result.kind[n] != VertexKind::interior) continue;
      const Vec3 d = result.positions[n] - result.positions[v];
      const double distance = dot(d, d);
      if (distance < nearest_distance || (distance == nearest_distance && n < nearest))
        nearest = n, nearest_distance = distance;
    }
    if (nearest == UINT32_MAX) {
      result.kind[v] = VertexKind::isolated_boundary;  // 000 §6.5, Figure 58b: no general formula
      result.radiosity[v] = mean_of(elements_of_vertex[v]);
    } else {
      result.radiosity[v] =
          mean_of(elements_of_edge[make_edge(v, nearest)]) * 2.0 - result.radiosity[nearest];
    }
  }
  for (Color& b : result.radiosity) b = max(b, Color());
  // Gouraud without cracks (SPEC §10.1): a T-junction vertex gets the radiosity interpolated along
  // the larger element's edge, which is what that element shows there; the longest edges first, so
  // that a vertex on a shorter edge that is itself a junction reads its ends' final values.
  std::stable_sort(junctions.begin(), junctions.end(),
                   [](const Junction& x, const Junction& y) { return x.length_squared > y.length_squared; });
  for (const Junction& j : junctions)
    result.radiosity[j.vertex] = result.radiosity[j.a] * (1 - j.t) + result.radiosity[j.b] * j.t;
  return result;
}

VertexRadiosity compute_vertex_radiosity(const std::vector<RadiositySurface>& elements,
                                         const std::vector<Color>& element_radiosity,
                                         const std::vector<uint8_t>& hidden) {
  if (hidden.empty()) return compute_vertex_radiosity(elements, element_radiosity);
  if (hidden.size() != elements.size() || element_radiosity.size() != elements.size())
    throw std::invalid_argument("vertex radiosity: " + std::to_string(elements.size()) + " elements, " +
                                std::to_string(element_radiosity.size()) + " radiosities and " +
                                std::to_string(hidden.size()) + " hidden flags");
  std::vector<RadiositySurface> visible;
  std::vector<Color> visible_radiosity;
  for (std::size_t q = 0; q < elements.size(); ++q)
    if (!hidden[q]) visible.push_back(elements[q]), visible_radiosity.push_back(element_radiosity[q]);
  VertexRadiosity result = compute_vertex_radiosity(visible, visible_radiosity);
  std::vector<std::array<uint32_t, 3>> visible_vertices = std::move(result.element_vertices);
  result.element_vertices.clear();
  std::size_t next_visible = 0;
  for (std::size_t q = 0; q < elements.size(); ++q) {
    if (!hidden[q]) {
      result.element_vertices.push_back(visible_vertices[next_visible++]);
      continue;
    }
    std::array<uint32_t, 3> own;
    for (std::size_t k = 0; k < 3; ++k) {
      own[k] = static_cast<uint32_t>(result.positions.size());
      result.positions.push_back(elements[q].corners[k]);
      result.object.push_back(elements[q].object);
      result.kind.push_back(VertexKind::isolated_boundary);
      result.radiosity.push_back(element_radiosity[q]);
    }
    result.element_vertices.push_back(own);
  }
  return result;
}

}  // namespace candela
