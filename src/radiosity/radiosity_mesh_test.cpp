#include "radiosity/radiosity_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "raster/tessellated_scene.h"
#include "scene/scene_loader.h"

namespace candela {
namespace {

std::unique_ptr<Scene> scene_with(const std::string& shapes) {
  return read_scene_text(
      R"({"format": "candela/1", "camera": {"eye": [0, 0, 20], "target": [0, 0, 0], "fov": 40, "width": 8, "height": 8}, "shapes": )" +
          shapes + "}",
      "test.json", ".", {}, {});
}

// Sizes, areas and the element → patch mapping of any mesh.
void expect_consistent(const RadiosityMesh& mesh) {
  ASSERT_EQ(mesh.first_element.size(), mesh.patches.size() + 1);
  ASSERT_EQ(mesh.patch_of_element.size(), mesh.elements.size());
  EXPECT_EQ(mesh.first_element.front(), 0u);
  EXPECT_EQ(mesh.first_element.back(), mesh.elements.size());
  for (std::size_t p = 0; p < mesh.patches.size(); ++p) {
    EXPECT_LE(longest_edge(mesh.patches[p]), mesh.patch_size * (1 + 1e-12));
    double element_area = 0;
    for (uint32_t e = mesh.first_element[p]; e < mesh.first_element[p + 1]; ++e) {
      EXPECT_EQ(mesh.patch_of_element[e], p);
      EXPECT_LE(longest_edge(mesh.elements[e]), mesh.element_size * (1 + 1e-12));
      EXPECT_EQ(mesh.elements[e].primitive, mesh.patches[p].primitive);
      EXPECT_NEAR(length(mesh.elements[e].normal), 1, 1e-12);
      EXPECT_GT(dot(mesh.elements[e].normal, mesh.patches[p].normal), 1 - 1e-9);  // same plane, same side
      element_area += mesh.elements[e].area;
    }
    EXPECT_NEAR(element_area, mesh.patches[p].area, 1e-12 * mesh.patches[p].area);
  }
  EXPECT_NO_THROW(mesh.element_geometry.validate());
  EXPECT_NO_THROW(mesh.patch_geometry.validate());
  EXPECT_EQ(mesh.element_geometry.element_count, mesh.elements.size());
  EXPECT_EQ(mesh.patch_geometry.element_count, mesh.patches.size());
  std::size_t listed = 0;
  for (const auto& list : mesh.elements_of_primitive) listed += list.size();
  EXPECT_EQ(listed, mesh.elements.size());
}

TEST(RadiosityMesh, BoxAreaIsExactAndEveryPieceWithinItsBound) {
  const auto scene = scene_with(R"([{"type": "box", "min": [0, 0, 0], "max": [2, 3, 4]}])");
  RadiosityMeshSettings settings;
  settings.patch_size = 1;
  settings.element_size = 0.4;
  const RadiosityMesh mesh = build_radiosity_mesh(*scene, settings);
  expect_consistent(mesh);
  EXPECT_NEAR(mesh.patch_area(), 52, 1e-12);  // 2·(2·3 + 2·4 + 3·4)
  EXPECT_NEAR(mesh.element_area(), 52, 1e-12);
  EXPECT_GT(mesh.elements.size(), mesh.patches.size());
  // Outward normals: every centroid + normal lies outside the box.
  for (const auto& element : mesh.elements) {
    const Vec3 outside = element.centroid + element.normal * 0.01;
    EXPECT_TRUE(outside.x < 0 || outside.x > 2 || outside.y < 0 || outside.y > 3 || outside.z < 0 ||
                outside.z > 4);
  }
  // The element found at an element's centroid is that element.
  for (uint32_t e = 0; e < mesh.elements.size(); ++e) {
    EXPECT_EQ(mesh.element_at(mesh.elements[e].primitive, mesh.elements[e].centroid), e);
  }
}

TEST(RadiosityMesh, DefaultSizesFollowTheSceneSize) {
  const auto scene = scene_with(R"([{"type": "box", "min": [0, 0, 0], "max": [2, 3, 6]}])");
  const RadiosityMesh mesh = build_radiosity_mesh(*scene, {});
  EXPECT_NEAR(mesh.patch_size, 7.0 / 8, 1e-12);  // the diagonal √(4 + 9 + 36) = 7
  EXPECT_NEAR(mesh.element_size, 7.0 / 16, 1e-12);
  expect_consistent(mesh);
}

// The tessellation is area-true, so the mesh's area is the sphere's own 4πr² (it was
// the inscribed polyhedron's, 0.97 of it at 12 segments).
TEST(RadiosityMesh, SphereAreaIsTheTessellatedAreaAndTheSpheresOwn) {
  const auto scene = scene_with(R"([{"type": "sphere", "center": [1, 0, 0], "radius": 2}])");
  RadiosityMeshSettings settings;
  settings.segments = 12;
  settings.patch_size = 0.9;
  const RadiosityMesh mesh = build_radiosity_mesh(*scene, settings);
  expect_consistent(mesh);
  TessellationRequest request;
  request.max_segments = 12;
  request.clip = scene->bounds();
  const TessellatedScene triangles = tessellate_scene(*scene, request);
  double tessellated_area = 0;
  for (std::size_t t = 0; t < triangles.triangle_count(); ++t) {
    const Vec3* p = &triangles.corner_positions[3 * t];
    tessellated_area += 0.5 * length(cross(p[1] - p[0], p[2] - p[0]));
  }
  EXPECT_NEAR(mesh.patch_area(), tessellated_area, 1e-9);
  EXPECT_NEAR(mesh.element_area(), tessellated_area, 1e-9);
  EXPECT_NEAR(mesh.patch_area() / (4 * kPi * 4), 1, 1e-9);
}

TEST(RadiosityMesh, ElementAtFindsTheElementUnderAPointOfACurvedSurface) {
  // Points of the true sphere lie just off its (area-true) triangles: the element found is the one
  // the point projects into, whose centroid lies within an element size of it, never one on the
  // far side.
  const auto scene = scene_with(R"([{"type": "sphere", "center": [0, 0, 0], "radius": 1}])");
  RadiosityMeshSettings settings;
  settings.segments = 16;
  settings.patch_size = 0.5;
  const RadiosityMesh mesh = build_radiosity_mesh(*scene, settings);
  for (int k = 0; k < 50; ++k) {
    const double theta = 0.1 + 2.9 * k / 49.0, phi = 0.7 * k;
    const Vec3 point{std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)};
    const uint32_t element = mesh.element_at(0, point);
    ASSERT_LT(element, mesh.elements.size());
    EXPECT_LT(length(mesh.elements[element].centroid - point), mesh.element_size);
    EXPECT_GT(dot(mesh.elements[element].normal, point), 0.9);
  }
  EXPECT_EQ(mesh.element_at(7, {0, 0, 0}), UINT32_MAX);  // no such primitive
}

TEST(RadiosityMesh, PlanesAreCutByTheClipBox) {
  const auto scene = scene_with(R"([{"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0]}])");
  RadiosityMeshSettings settings;
  settings.clip = {{-1, -1, -2}, {1, 1, 2}};
  settings.patch_size = 0.5;
  const RadiosityMesh mesh = build_radiosity_mesh(*scene, settings);
  expect_consistent(mesh);
  EXPECT_NEAR(mesh.patch_area(), 8, 1e-12);  // the 2 × 4 rectangle inside the box
  for (const auto& patch : mesh.patches) EXPECT_NEAR(patch.normal.y, 1, 1e-12);
  // Without a clip box nothing bounds the plane.
  EXPECT_THROW(build_radiosity_mesh(*scene, {}), std::invalid_argument);
}

TEST(RadiosityMesh, ReflectanceAndEmissionComeFromTheMaterials) {
  const auto scene = scene_with(R"([
      {"type": "quad", "corner": [0, 0, 0], "edge_u": [1, 0, 0], "edge_v": [0, 1, 0], "material": {"kd": [0.2, 0.4, 0.6], "emission": [1, 2, 3]}},
      {"type": "quad", "corner": [0, 0, 1], "edge_u": [1, 0, 0], "edge_v": [0, 1, 0],
       "material": {"kd": {"type": "checker2d", "even": [0.1, 0.1, 0.1], "odd": [0.9, 0.9, 0.9], "mapping": {"type": "uv", "scale": [2, 1]}}}},
      {"type": "quad", "corner": [0, 0, 2], "edge_u": [1, 0, 0], "edge_v": [0, 1, 0], "material": {"kd": 1.5}}])");
  RadiosityMeshSettings settings;
  settings.patch_size = 0.3;
  const RadiosityMesh mesh = build_radiosity_mesh(*scene, settings);
  expect_consistent(mesh);
  bool saw_dark = false, saw_light = false;
  for (const auto& element : mesh.elements) {
    if (element.primitive == 0) {
      EXPECT_EQ(element.reflectance.r, 0.2);
      EXPECT_EQ(element.reflectance.b, 0.6);
      EXPECT_EQ(element.emission.g, 2);
    } else if (element.primitive == 1) {
      EXPECT_TRUE(element.emission.is_black());
      // The checker in u: ρ follows the element's centroid.
      EXPECT_TRUE(element.reflectance.r == 0.1 || element.reflectance.r == 0.9);
      saw_dark |= element.reflectance.r == 0.1;
      saw_light |= element.reflectance.r == 0.9;
    } else {
      EXPECT_EQ(element.reflectance.r, 1);  // clamped to a physical reflectance
    }
  }
  EXPECT_TRUE(saw_dark);
  EXPECT_TRUE(saw_light);
  EXPECT_NO_THROW(mesh.element_system().validate(mesh.patches.size()));
  EXPECT_NO_THROW(mesh.patch_system().validate());
}

TEST(RadiosityMesh, BadSettingsAreRefused) {
  const auto scene = scene_with(R"([{"type": "box", "min": [0, 0, 0], "max": [1, 1, 1]}])");
  RadiosityMeshSettings settings;
  settings.segments = 2;
  EXPECT_THROW(build_radiosity_mesh(*scene, settings), std::invalid_argument);
  settings = {};
  settings.patch_size = 0.1;
  settings.element_size = 0.2;
  EXPECT_THROW(build_radiosity_mesh(*scene, settings), std::invalid_argument);
  settings = {};
  settings.patch_size = -1;
  EXPECT_THROW(build_radiosity_mesh(*scene, settings), std::invalid_argument);
}

TEST(RadiosityMesh, NeighboursShareEdgesWithinOneSurfaceAndAreSymmetric) {
  // A unit quad meshed into 8 elements (two triangles, each bisected twice), and a box beside it.
  const auto scene =
      scene_with(R"([{"type": "quad", "corner": [0, 0, 0], "edge_u": [1, 0, 0], "edge_v": [0, 1, 0]},
                                    {"type": "box", "min": [2, 0, 0], "max": [3, 1, 1]}])");
  RadiosityMeshSettings settings;
  settings.patch_size = 1.5;
  settings.element_size = 0.75;
  RadiosityMesh mesh = build_radiosity_mesh(*scene, settings);
  const auto neighbours = mesh.element_neighbours();
  ASSERT_EQ(neighbours.size(), mesh.elements.size());
  for (uint32_t q = 0; q < neighbours.size(); ++q) {
    for (const uint32_t other : neighbours[q]) {
      EXPECT_NE(other, q);
      EXPECT_EQ(mesh.elements[other].object, mesh.elements[q].object);
      EXPECT_GT(dot(mesh.elements[other].normal, mesh.elements[q].normal), 0.7);  // never across a crease
      EXPECT_TRUE(std::binary_search(neighbours[other].begin(), neighbours[other].end(), q));
    }
  }
  // In a triangulated square every element has at least one and at most three edge neighbours.
  for (uint32_t q = 0; q < mesh.elements.size(); ++q) {
    if (mesh.elements[q].object != 0) continue;
    EXPECT_GE(neighbours[q].size(), 1u);
    EXPECT_LE(neighbours[q].size(), 3u);
  }
  // Split one element of the quad: across the T-junction its halves still neighbour the old
  // neighbours that touch them, and the areas still add up.
  const uint32_t split_one = mesh.elements_of_primitive[0].front();
  const std::vector<uint32_t> before = neighbours[split_one];
  std::vector<bool> split(mesh.elements.size(), false);
  split[split_one] = true;
  const double area_before = mesh.element_area();
  const std::size_t count_before = mesh.elements.size();
  const std::vector<uint32_t> origin = mesh.split_elements(*scene, split);
  ASSERT_EQ(origin.size(), count_before + 1);
  ASSERT_EQ(mesh.elements.size(), count_before + 1);
  EXPECT_NEAR(mesh.element_area(), area_before, 1e-12);
  expect_consistent(mesh);
  const auto after = mesh.element_neighbours();
  std::vector<uint32_t> halves;
  for (uint32_t q = 0; q < origin.size(); ++q)
    if (origin[q] == split_one) halves.push_back(q);
  ASSERT_EQ(halves.size(), 2u);
  // The halves neighbour each other, and between them they touch every old neighbour.
  EXPECT_TRUE(std::binary_search(after[halves[0]].begin(), after[halves[0]].end(), halves[1]));
  for (const uint32_t old_neighbour : before) {
    uint32_t renumbered = 0;
    while (origin[renumbered] != old_neighbour) ++renumbered;
    const bool touches = std::binary_search(after[halves[0]].begin(), after[halves[0]].end(), renumbered) ||
                         std::binary_search(after[halves[1]].begin(), after[halves[1]].end(), renumbered);
    EXPECT_TRUE(touches) << "old neighbour " << old_neighbour;
  }
  EXPECT_THROW(mesh.split_elements(*scene, std::vector<bool>(3, false)), std::invalid_argument);
}

// SPEC §10's remedy for light leaks: surfaces cut where other objects meet them, so that no
// floor element straddles the footprint of a box standing on it.
TEST(RadiosityMesh, SplitAtContactsCutsTheFloorAlongABoxFootprint) {
  const auto scene =
      scene_with(R"([{"type": "quad", "corner": [0, 0, 0], "edge_u": [4, 0, 0], "edge_v": [0, 4, 0]},
                                    {"type": "box", "min": [1.3, 1.1, 0], "max": [2.45, 2.7, 1]}])");
  RadiosityMeshSettings settings;
  settings.patch_size = 1;
  settings.element_size = 0.5;
  // Elements partly inside and partly outside the footprint [1.3, 2.45] × [1.1, 2.7]: sampled at
  // the centroid and halfway from it to each corner.
  const auto straddling = [](const RadiosityMesh& mesh) {
    std::size_t count = 0;
    for (const RadiositySurface& element : mesh.elements) {
      if (element.object != 0) continue;
      bool inside = false, outside = false;
      for (const Vec3& corner : element.corners)
        for (const Vec3& p : {element.centroid, (element.centroid + corner) * 0.5}) {
          const bool in = p.x > 1.3 && p.x < 2.45 && p.y > 1.1 && p.y < 2.7;
          inside |= in;
          outside |= !in;
        }
      count += inside && outside;
    }
    return count;
  };
  const RadiosityMesh plain = build_radiosity_mesh(*scene, settings);
  EXPECT_GT(straddling(plain), 0u);
  settings.split_at_contacts = true;
  const RadiosityMesh cut = build_radiosity_mesh(*scene, settings);
  expect_consistent(cut);
  EXPECT_EQ(straddling(cut), 0u);
  // Nothing is lost or added: the floor still has area 16 and the box 2·(1.15·1.6 + 1.15 + 1.6).
  double floor = 0, box = 0;
  for (const RadiositySurface& patch : cut.patches) (patch.object == 0 ? floor : box) += patch.area;
  EXPECT_NEAR(floor, 16, 1e-9);
  EXPECT_NEAR(box, 2 * (1.15 * 1.6 + 1.15 + 1.6), 1e-9);
  // The box's own faces are cut only where the floor meets them: along their bottom edges, which
  // they already have, so they gain nothing beyond bisection.
  std::size_t plain_box = 0, cut_box = 0;
  for (const RadiositySurface& patch : plain.patches) plain_box += patch.object == 1;
  for (const RadiositySurface& patch : cut.patches) cut_box += patch.object == 1;
  EXPECT_EQ(cut_box, plain_box);
}

// element_at looks near the point through the element grid; the answer must be the brute-force
// nearest element of the primitive (ties to the lowest index), near and far from the surface.
TEST(RadiosityMesh, ElementAtMatchesTheNearestElementFoundByScanning) {
  const auto scene = scene_with(R"([{"type": "sphere", "center": [0, 0, 0], "radius": 1.5},
                                    {"type": "quad", "corner": [-3, -3, -2], "edge_u": [6, 0, 0], "edge_v": [0, 6, 0]}])");
  RadiosityMeshSettings settings;
  settings.patch_size = 0.8;
  settings.element_size = 0.3;
  settings.segments = 24;
  const RadiosityMesh mesh = build_radiosity_mesh(*scene, settings);
  uint64_t state = 12345;
  const auto next = [&] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(state >> 11) / 9007199254740992.0;
  };
  // The same mesh without its grid answers by scanning every element of the primitive.
  RadiosityMesh scan_only = mesh;
  scan_only.element_grid = SurfaceGrid();
  for (int trial = 0; trial < 2000; ++trial) {
    const uint32_t primitive = trial % 2;
    // Points on and off the surfaces, some far away (the grid's fallback).
    const double spread = trial % 10 == 0 ? 40 : 4;
    const Vec3 point{(next() - 0.5) * spread, (next() - 0.5) * spread, (next() - 0.5) * spread};
    uint32_t expected = scan_only.element_at(primitive, point);
    ASSERT_NE(expected, UINT32_MAX);
    // Off the mesh (beyond the elements' box by more than a cell): no element.
    const double reach = mesh.element_grid.cell_size();
    const Bounds3& box = mesh.element_grid.bounds();
    for (int axis = 0; axis < 3; ++axis)
      if (point[axis] < box.lower[axis] - reach || point[axis] > box.upper[axis] + reach)
        expected = UINT32_MAX;
    EXPECT_EQ(mesh.element_at(primitive, point), expected) << trial;
  }
}

// The contact cuts stay near the contact: a cylinder standing through a floor cuts the floor
// around its footprint only, not along lines running across the whole floor.
TEST(RadiosityMesh, ContactCutsStayNearTheContact) {
  const auto scene =
      scene_with(R"([{"type": "quad", "corner": [-5, -5, 0], "edge_u": [10, 0, 0], "edge_v": [0, 10, 0]},
                                    {"type": "cylinder", "base": [0.3, 0.2, -1], "cap": [0.3, 0.2, 2], "radius": 1}])");
  RadiosityMeshSettings settings;
  settings.patch_size = 1;
  settings.element_size = 1;
  settings.segments = 32;
  const RadiosityMesh plain = build_radiosity_mesh(*scene, settings);
  settings.split_at_contacts = true;
  const RadiosityMesh cut = build_radiosity_mesh(*scene, settings);
  expect_consistent(cut);
  const auto far_floor = [](const RadiosityMesh& mesh) {
    std::size_t count = 0;
    for (const RadiositySurface& element : mesh.elements)
      if (element.object == 0 && std::hypot(element.centroid.x - 0.3, element.centroid.y - 0.2) > 3) ++count;
    return count;
  };
  EXPECT_EQ(far_floor(cut), far_floor(plain));
  std::size_t floor_plain = 0, floor_cut = 0;
  for (const RadiositySurface& element : plain.elements) floor_plain += element.object == 0;
  for (const RadiositySurface& element : cut.elements) floor_cut += element.object == 0;
  EXPECT_GT(floor_cut, floor_plain);      // cut around the footprint
  EXPECT_LT(floor_cut, 4 * floor_plain);  // and not everywhere
  // No floor element straddles the circle of the cylinder's 32 facets (up to their sagitta).
  for (const RadiositySurface& element : cut.elements) {
    if (element.object != 0) continue;
    bool inside = false, outside = false;
    for (const Vec3& corner : element.corners)
      for (const Vec3& p : {element.centroid, (element.centroid + corner) * 0.5}) {
        const double r = std::hypot(p.x - 0.3, p.y - 0.2);
        inside |= r < 1 - 0.01;
        outside |= r > 1 + 1e-9;
      }
    EXPECT_FALSE(inside && outside);
  }
}

}  // namespace
}  // namespace candela
