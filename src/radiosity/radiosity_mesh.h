// The radiosity mesh of a scene (000 §6.7.1 substructuring, SPEC §10): every primitive
// tessellated into triangles (Shape::tessellate through tessellate_scene; planes cut by a clip
// box), each triangle split by longest-edge bisection until no edge is longer than patch_size —
// the patches, which shoot light — and each patch split the same way until no edge is longer
// than element_size — the elements, which receive it. A patch is the union of its elements, so
// their areas add up exactly.
//
// Every patch and element is one triangle, wound counter-clockwise about the shape's geometric
// normal (outward for closed shapes), with the diffuse reflectance ρ = kd and the emitted exitance
// E of its material at its centroid (000 eq. 6-7's ρ_i and E_i).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "math/bounds.h"
#include "math/vector.h"
#include "radiosity/hemicube_form_factors.h"
#include "radiosity/radiosity_system.h"
#include "radiosity/surface_grid.h"

namespace candela {

class Scene;

struct RadiosityMeshSettings {
  int segments = 32;  // divisions of a full turn of a curved shape (≥ 3)
  // > 0: each curved shape gets the fewest segments, at most `segments`, whose chords
  // stray at most this fraction of the scene size from its surface (raster/tessellated_scene.h).
  double chord_fraction = 0;
  double patch_size = 0;    // the longest patch edge; 0: the scene size / 8
  double element_size = 0;  // the longest element edge; 0: patch_size / 2 (≤ patch_size)
  // Cut every surface along the lines where other objects meet it before meshing (the remedy
  // for light and shadow leaks, SPEC §10), so that no patch straddles a contact.
  bool split_at_contacts = false;
  // Where planes are cut; empty: the bounds of the bounded shapes (the scene size is the length
  // of this box's diagonal).
  Bounds3 clip;
};

// One patch or element: a triangle of the mesh.
struct RadiositySurface {
  std::array<Vec3, 3> corners;  // world, counter-clockwise about normal
  double area = 0;
  Vec3 centroid;
  Vec3 normal;  // unit
  uint32_t primitive = 0, object = 0, material = 0;
  // Its object is two-sided (SceneObject::two_sided): the mesh holds a twin on the other side,
  // wound the other way, and this one is not drawn where its back would be seen.
  bool two_sided = false;
  Color reflectance;  // ρ = kd at the centroid, clamped to [0, 1]
  Color emission;     // E of the material
  // ρ times the direct light of the scene's lights (point, spot, directional, area) on the
  // surface, averaged over it: radiosity's first shot (first_shot.h); the solvers' source term is
  // emission + first_shot.
  Color first_shot;
};

// The length of the surface's longest edge (the adaptive subdivision's size).
inline double longest_edge(const RadiositySurface& surface) {
  const auto& c = surface.corners;
  return std::max({length(c[1] - c[0]), length(c[2] - c[1]), length(c[0] - c[2])});
}

struct RadiosityMesh {
  std::vector<RadiositySurface> patches;
  std::vector<RadiositySurface> elements;
  // Patch p's elements are first_element[p] … first_element[p + 1] − 1 (size patches + 1).
  std::vector<uint32_t> first_element;
  std::vector<uint32_t> patch_of_element;  // one per element
  // The elements of each primitive of the scene (for finding the element a ray hits).
  std::vector<std::vector<uint32_t>> elements_of_primitive;
  // The hemicube's geometry: one triangle per element (id = element index), and per patch.
  FormFactorGeometry element_geometry;
  FormFactorGeometry patch_geometry;
  double patch_size = 0, element_size = 0;  // the bounds used
  // Per element: its corners in object space and their uvs (where textures are looked up when
  // an element is split again).
  std::vector<std::array<Vec3, 3>> element_object_corners;
  std::vector<std::array<Vec2, 3>> element_uvs;
  // The elements by place, for element_at (rebuilt with the elements).
  SurfaceGrid element_grid;

  // The patches as a radiosity system (areas, ρ, E), and the elements as the receivers of a
  // substructured system (their patches, areas, ρ, E; 000 §6.7.1); E is each surface's emission
  // plus its first shot.
  RadiositySystem patch_system() const;
  ElementSystem element_system() const;
  double patch_area() const;    // Σ patch areas
  double element_area() const;  // Σ element areas
  // The element of primitive `primitive` nearest the world point (the one containing it for
  // flat shapes; for curved ones the triangle closest to the true surface point); UINT32_MAX
  // when the primitive has no elements, or when the point lies farther than the grid's cell size
  // (the longest element edge) outside the box of all elements — off the mesh, like the part of
  // an unbounded plane beyond its clip box.
  // toward (a direction from the point to whoever looks: −ray direction; zero for none) chooses
  // between a two-sided surface's twins, which are as near: the one it faces.
  uint32_t element_at(uint32_t primitive, const Vec3& point, const Vec3& toward = Vec3()) const;

  // The neighbours of every element (000 §6.7.2): the elements of the same object that share a
  // piece of an edge with it (also across the T-junctions that splitting leaves) and whose
  // normals differ by at most 45° (a crease, like a box's edge, separates two surfaces).
  // Symmetric, sorted, without the element itself.
  std::vector<std::vector<uint32_t>> element_neighbours() const;

  // 000 §6.7.2: splits every element q with split[q] once by longest-edge bisection (ρ and E
  // evaluated again at the halves' centroids); the elements stay grouped patch by patch and the
  // geometry is rebuilt. Returns, for each new element, the index of the old element it is or
  // was cut from. Throws std::invalid_argument unless split has one entry per element.
  std::vector<uint32_t> split_elements(const Scene& scene, const std::vector<bool>& split);
};

// A corner carried through subdivision: world and object positions and the uv, all interpolated
// linearly along an edge (textures are looked up again where a surface is split).
struct MeshCorner {
  Vec3 position, object_position;
  Vec2 uv;
};
using CornerTriangle = std::array<MeshCorner, 3>;

MeshCorner midpoint(const MeshCorner& a, const MeshCorner& b);

// A surface of the mesh from its corners: area, centroid, normal, and ρ, E of the material
// evaluated at the centroid (000 eq. 6-7's ρ_i and E_i taken constant over the surface).
RadiositySurface make_radiosity_surface(const Scene& scene, const CornerTriangle& triangle,
                                        uint32_t primitive);

// The scene's surfaces as radiosity sees them before any split: every primitive tessellated
// (settings.segments; planes cut by the clip box) and a two-sided object's triangles again, wound
// the other way; scene_size is the clip box's diagonal. Throws like build_radiosity_mesh for
// bad settings or a scene without bounds.
struct RadiosityInput {
  double scene_size = 0;
  std::vector<CornerTriangle> triangles;
  std::vector<uint32_t> primitives;  // one per triangle
};
RadiosityInput radiosity_input(const Scene& scene, const RadiosityMeshSettings& settings);

// The remedy for light and shadow leaks (split_at_contacts) on radiosity_input's triangles: each is
// bisected until no edge is longer than patch_size, then cut along the lines where other objects
// meet it (as build_radiosity_mesh cuts its patches), so that no piece straddles a contact.
RadiosityInput split_input_at_contacts(const Scene& scene, const RadiosityInput& input, double patch_size);

// A mesh from surfaces made elsewhere (hierarchical radiosity's input triangles and the leaves of
// their quadtrees): patches[p]'s elements are elements[first[p]] … elements[first[p + 1] − 1]; the
// lookup structures (elements_of_primitive, geometry, grid) are built. patch_size and element_size
// are the longest patch and element edges.
RadiosityMesh assemble_radiosity_mesh(std::vector<RadiositySurface> patches,
                                      std::vector<RadiositySurface> elements, std::vector<uint32_t> first,
                                      std::vector<std::array<Vec3, 3>> object_corners,
                                      std::vector<std::array<Vec2, 3>> uvs, std::size_t primitive_count);

// The fewest patches and elements build_radiosity_mesh can make with these settings (the
// tessellated area over the largest triangle whose longest edge is the bound), found by
// tessellating only: what memory checks read before the mesh is built. Throws like
// build_radiosity_mesh for bad settings.
struct RadiosityMeshEstimate {
  double patches = 0, elements = 0;
};
RadiosityMeshEstimate estimate_radiosity_mesh(const Scene& scene, const RadiosityMeshSettings& settings);

// Builds the mesh of a prepared scene. Throws std::invalid_argument for segments < 3, a negative
// or non-finite size, element_size > patch_size, a scene with no surface, a scene whose bounds
// (and clip box) are empty, or sizes that would make more than 2²⁴ elements (named in the message).
RadiosityMesh build_radiosity_mesh(const Scene& scene, const RadiosityMeshSettings& settings);

}  // namespace candela
