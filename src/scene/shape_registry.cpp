#include "scene/shape_registry.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <filesystem>

#include "geometry/box.h"
#include "geometry/cone.h"
#include "geometry/cylinder.h"
#include "geometry/disc.h"
#include "geometry/plane.h"
#include "geometry/polygon.h"
#include "geometry/quad.h"
#include "geometry/sphere.h"
#include "geometry/torus.h"
#include "geometry/triangle_mesh.h"
#include "io/gltf_import.h"
#include "io/obj_import.h"
#include "io/ply_import.h"
#include "shading/image_texture.h"
#include "util/file_extension.h"
#include "util/registry.h"

namespace candela {

namespace {

// Constructors validate their arguments; their message is reported at the entry.
template <typename Make>
ShapeBuild one_shape(const JsonNode& node, Make make) {
  ShapeBuild build;
  try {
    build.shapes.push_back(make());
  } catch (const std::invalid_argument& e) {
    node.fail(e.what());
  }
  build.materials.push_back(-1);
  return build;
}

ShapeBuild make_sphere(const JsonNode& node, const Transform&, LoadContext&) {
  const Vec3 center = node.vec3("center", {0, 0, 0});
  const double radius = node.number("radius", 1.0, Range::positive());
  return one_shape(node, [&] { return std::make_unique<Sphere>(center, radius); });
}

ShapeBuild make_plane(const JsonNode& node, const Transform&, LoadContext&) {
  const Vec3 point = node.vec3("point", {0, 0, 0});
  const Vec3 normal = node.vec3("normal", {0, 1, 0});
  return one_shape(node, [&] { return std::make_unique<Plane>(point, normal); });
}

ShapeBuild make_disc(const JsonNode& node, const Transform&, LoadContext&) {
  const Vec3 center = node.vec3("center", {0, 0, 0});
  const Vec3 normal = node.vec3("normal", {0, 1, 0});
  const double radius = node.number("radius", 1.0, Range::positive());
  const double inner = node.number("inner_radius", 0.0, Range::non_negative());
  return one_shape(node, [&] { return std::make_unique<Disc>(center, normal, radius, inner); });
}

ShapeBuild make_quad(const JsonNode& node, const Transform&, LoadContext&) {
  const Vec3 corner = node.vec3("corner");
  const Vec3 edge_u = node.vec3("edge_u");
  const Vec3 edge_v = node.vec3("edge_v");
  return one_shape(node, [&] { return std::make_unique<Quad>(corner, edge_u, edge_v); });
}

std::vector<Vec3> read_vertices(const JsonNode& node, std::size_t minimum, std::size_t maximum) {
  const JsonNode list = node.at("vertices");
  const std::size_t count = list.size();
  if (count < minimum || count > maximum)
    list.fail(minimum == maximum ? fmt::format("expected {} vertices, found {}", minimum, count)
                                 : fmt::format("expected at least {} vertices, found {}", minimum, count));
  std::vector<Vec3> vertices;
  for (std::size_t i = 0; i < count; ++i) vertices.push_back(list.element(i).as_vec3());
  return vertices;
}

ShapeBuild make_polygon(const JsonNode& node, const Transform&, LoadContext&) {
  const auto vertices = read_vertices(node, 3, std::size_t(-1));
  return one_shape(node, [&] { return std::make_unique<Polygon>(vertices); });
}

// Transforms the mesh into the world and makes its triangles; failures (coordinates that
// overflow under the transform) are reported at the entry.
std::vector<std::unique_ptr<Shape>> placed_triangles(const JsonNode& node,
                                                     const std::shared_ptr<TriangleMesh>& mesh,
                                                     const Transform& transform, std::size_t& skipped,
                                                     std::size_t* merged = nullptr) {
  try {
    mesh->transform(transform);
    return make_triangles(mesh, &skipped, merged);
  } catch (const std::invalid_argument& e) {
    node.fail(e.what());
  }
}

ShapeBuild triangles_of(const JsonNode& node, std::shared_ptr<TriangleMesh> mesh, const Transform& transform,
                        LoadContext& context) {
  std::size_t skipped = 0;
  ShapeBuild build;
  build.shapes = placed_triangles(node, mesh, transform, skipped);
  build.materials.assign(build.shapes.size(), -1);
  build.transform_applied = true;
  // A zero-area (or overflowing) triangle is skipped, not refused (SPEC §15): the entry stays,
  // with no primitive.
  if (skipped > 0)
    context.warnings->push_back(fmt::format("{}: skipped {} degenerate triangle(s) (zero area)",
                                            node.location().describe(), skipped));
  return build;
}

ShapeBuild make_triangle(const JsonNode& node, const Transform& transform, LoadContext& context) {
  const auto vertices = read_vertices(node, 3, 3);
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->positions = vertices;
  mesh->triangles.push_back({0, 1, 2});
  return triangles_of(node, mesh, transform, context);
}

ShapeBuild make_box(const JsonNode& node, const Transform&, LoadContext&) {
  const Vec3 lower = node.vec3("min", {-1, -1, -1});
  const Vec3 upper = node.vec3("max", {1, 1, 1});
  return one_shape(node, [&] { return std::make_unique<Box>(lower, upper); });
}

ShapeBuild make_cylinder(const JsonNode& node, const Transform&, LoadContext&) {
  const Vec3 base = node.vec3("base", {0, 0, 0});
  const Vec3 cap = node.vec3("cap", {0, 1, 0});
  const double radius = node.number("radius", 1.0, Range::positive());
  const bool capped = node.boolean("capped", true);
  return one_shape(node, [&] { return std::make_unique<Cylinder>(base, cap, radius, capped); });
}

ShapeBuild make_cone(const JsonNode& node, const Transform&, LoadContext&) {
  const Vec3 base = node.vec3("base", {0, 0, 0});
  const double base_radius = node.number("base_radius", 1.0, Range::non_negative());
  const Vec3 cap = node.vec3("cap", {0, 1, 0});
  const double cap_radius = node.number("cap_radius", 0.0, Range::non_negative());
  const bool capped = node.boolean("capped", true);
  return one_shape(node, [&] { return std::make_unique<Cone>(base, base_radius, cap, cap_radius, capped); });
}

ShapeBuild make_torus(const JsonNode& node, const Transform&, LoadContext&) {
  const Vec3 center = node.vec3("center", {0, 0, 0});
  const Vec3 axis = node.vec3("axis", {0, 1, 0});
  const double major = node.number("major_radius", 1.0, Range::positive());
  const double minor = node.number("minor_radius", 0.25, Range::positive());
  return one_shape(node, [&] { return std::make_unique<Torus>(center, axis, major, minor); });
}

ShapeBuild make_mesh(const JsonNode& node, const Transform& transform, LoadContext& context) {
  const JsonNode file = node.at("file");
  const std::string path = context.resolve(file.as_string()).string();
  const std::string normals = node.choice("normals", "flat", {"flat", "smooth", "file"});
  const double crease = node.number("crease_angle", 180.0, {0, 180, false, false});
  // glTF only: the scene of the file to read (default its own), and the scene materials its
  // materials stand for, by their index in the file (null: the entry's material).
  const int gltf_scene = node.integer("scene", -1, {0, 1e9, false, false});
  const std::optional<JsonNode> file_materials = node.get("file_materials");
  // The reader by file extension (any case); all three return the same ObjImport result.
  const std::string extension = lower_case_extension(path);
  ObjImport imported;
  if (extension == ".obj") {
    imported = import_obj(path, file.location());
  } else if (extension == ".ply") {
    imported = import_ply(path, file.location());
  } else if (extension == ".gltf" || extension == ".glb") {
    imported = import_gltf(path, file.location(), gltf_scene);
  } else {
    file.fail(fmt::format("'{}': unknown mesh file extension '{}' (expected .obj, .ply, .gltf or .glb)", path,
                          extension));
  }
  if (extension != ".gltf" && extension != ".glb")
    for (const char* key : {"scene", "file_materials"})
      if (node.has(key)) node.at(key).fail("is for glTF files (their scenes and numbered materials)");
  std::vector<int> by_file_index;  // file_materials: the scene material of each of the file's
  if (file_materials) {
    for (std::size_t k = 0; k < file_materials->size(); ++k) {
      const JsonNode name = file_materials->element(k);
      by_file_index.push_back(name.json().is_null() ? -1 : static_cast<int>(context.named_material(name)));
    }
  }
  for (const auto& warning : imported.warnings) context.warnings->push_back(warning);
  if (normals == "flat") {
    imported.mesh->corner_normals.clear();
  } else if (normals == "smooth") {
    compute_corner_normals(*imported.mesh, crease);
  } else if (imported.mesh->corner_normals.empty()) {
    node.at("normals").fail(extension == ".obj" ? "the OBJ file has no vertex normals (vn) on every face"
                                                : "the mesh file has no vertex normals");
  }
  // MTL materials become scene materials; triangles without one use the entry's material.
  std::vector<int> material_index;
  for (const ImportedMaterial& m : imported.materials) {
    Material material;
    material.name = m.name;
    material.kd = constant_texture(m.kd);
    if (!m.diffuse_texture.empty()) {
      // MTL map_Kd: an image over the OBJ's texture coordinates (vt), multiplied by Kd as the
      // MTL format specifies.
      try {
        auto image = std::make_shared<const TextureImage>(TextureImage::load(m.diffuse_texture));
        material.kd = std::make_shared<ImageTexture>(std::move(image), WrapMode::repeat, m.kd,
                                                     std::make_shared<ParametricMapping>());
      } catch (const std::runtime_error& e) {
        file.fail(fmt::format("material '{}' (map_Kd): {}", m.name, e.what()));
      }
    }
    material.ka = constant_texture(m.ka);
    material.ks = constant_texture(m.ks);
    material.shininess = constant_texture(std::max(1.0, m.shininess));
    material.kt = constant_texture(m.kt);
    material.ior = constant_texture(m.ior);
    material_index.push_back(static_cast<int>(context.add_material(std::move(material))));
  }
  // Degenerate triangles are dropped by make_triangles, so map materials by the surviving
  // triangles' indices.
  ShapeBuild build;
  std::size_t skipped = 0, merged = 0;
  build.shapes = placed_triangles(node, imported.mesh, transform, skipped, &merged);
  build.transform_applied = true;
  for (const auto& shape : build.shapes) {
    const auto& triangle = static_cast<const MeshTriangle&>(*shape);
    if (file_materials) {
      const int in_file = imported.triangle_file_material[triangle.triangle_index()];
      if (in_file >= static_cast<int>(by_file_index.size()))
        file_materials->fail(fmt::format("names {} material(s), but the file's triangles use material {}",
                                         by_file_index.size(), in_file));
      build.materials.push_back(in_file >= 0 ? by_file_index[std::size_t(in_file)] : -1);
      continue;
    }
    const int source = imported.triangle_material[triangle.triangle_index()];
    build.materials.push_back(source >= 0 ? material_index[source] : -1);
  }
  if (skipped > 0)
    context.warnings->push_back(
        fmt::format("{}: {}: skipped {} degenerate triangle(s)", node.location().describe(), path, skipped));
  // Copies of one triangle are one surface; each copy cost every ray that met it a test.
  if (merged > 0)
    context.warnings->push_back(
        fmt::format("{}: {}: merged {} duplicate triangle(s) (the same corners as an "
                    "earlier triangle, in the same order)",
                    node.location().describe(), path, merged));
  if (build.shapes.empty()) file.fail(path + ": every triangle is degenerate (zero area)");
  return build;
}

const std::array kShapeEntries = {
    ShapeEntry{"sphere", "centre and radius (000 §5.6.1)",
               R"({"type": "sphere", "center": [0, 1, 0], "radius": 1})", make_sphere},
    ShapeEntry{"plane", "infinite plane through a point with a normal",
               R"({"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0]})", make_plane},
    ShapeEntry{
        "disc", "disc or annulus: centre, normal, radius, inner_radius",
        R"({"type": "disc", "center": [0, 0, 0], "normal": [0, 1, 0], "radius": 2, "inner_radius": 0.5})",
        make_disc},
    ShapeEntry{"quad", "parallelogram corner + u·edge_u + v·edge_v, (u, v) in [0, 1]² its own uv",
               R"({"type": "quad", "corner": [-1, 0, -1], "edge_u": [2, 0, 0], "edge_v": [0, 0, 2]})",
               make_quad},
    ShapeEntry{
        "polygon", "planar polygon, convex or not (000 §5.6.2)",
        R"({"type": "polygon", "vertices": [[0, 0, 0], [2, 0, 0], [2, 1, 0], [1, 1, 0], [1, 2, 0], [0, 2, 0]]})",
        make_polygon},
    ShapeEntry{"triangle", "one triangle (watertight test)",
               R"({"type": "triangle", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]]})", make_triangle},
    ShapeEntry{"box", "axis-aligned box from min to max (use a transform to turn it)",
               R"({"type": "box", "min": [-1, 0, -1], "max": [1, 2, 1]})", make_box},
    ShapeEntry{"cylinder", "from base to cap with a radius; capped or open",
               R"({"type": "cylinder", "base": [0, 0, 0], "cap": [0, 2, 0], "radius": 0.5, "capped": true})",
               make_cylinder},
    ShapeEntry{
        "cone", "truncated cone from base (base_radius) to cap (cap_radius); capped or open",
        R"({"type": "cone", "base": [0, 0, 0], "base_radius": 1, "cap": [0, 2, 0], "cap_radius": 0, "capped": true})",
        make_cone},
    ShapeEntry{
        "torus", "centre, axis, major and minor radius (quartic)",
        R"({"type": "torus", "center": [0, 0, 0], "axis": [0, 1, 0], "major_radius": 1, "minor_radius": 0.25})",
        make_torus},
    ShapeEntry{
        "mesh",
        "OBJ (+MTL), PLY or glTF 2.0 triangle mesh; normals flat, smooth (crease_angle) or from the file",
        R"({"type": "mesh", "file": "meshes/cube.obj", "normals": "smooth", "crease_angle": 60})", make_mesh},
};

}  // namespace

std::span<const ShapeEntry> shape_entries() {
  return kShapeEntries;
}

const ShapeEntry* find_shape(std::string_view name) {
  return find_entry<ShapeEntry>(kShapeEntries, name);
}

}  // namespace candela
