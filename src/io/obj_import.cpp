#include "io/obj_import.h"

#include <fmt/format.h>
#include <tiny_obj_loader.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

namespace candela {

namespace {

std::string quoted(const std::string& path) {
  return "'" + path + "'";
}

// tinyobjloader's messages, one per line, trimmed; empty lines (and the stray "." it writes
// after "Degenerated face found") dropped.
std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(start, end - start);
    const auto not_space = [](unsigned char ch) { return !std::isspace(ch); };
    line.erase(line.begin(), std::find_if(line.begin(), line.end(), not_space));
    line.erase(std::find_if(line.rbegin(), line.rend(), not_space).base(), line.end());
    if (!line.empty() && line != ".") lines.push_back(line);
    start = end + 1;
  }
  return lines;
}

std::string join(const std::vector<std::string>& lines) {
  std::string result;
  for (const std::string& line : lines) {
    if (!result.empty()) result += "; ";
    result += line;
  }
  return result;
}

// The first "line N" in a tinyobjloader message, or 0.
int line_number_in(const std::string& text) {
  std::size_t at = 0;
  while ((at = text.find("line ", at)) != std::string::npos) {
    at += 5;
    int value = 0;
    std::size_t digits = 0;
    while (at + digits < text.size() && std::isdigit(static_cast<unsigned char>(text[at + digits])) &&
           digits < 9) {
      value = value * 10 + (text[at + digits] - '0');
      ++digits;
    }
    if (digits > 0) return value;
  }
  return 0;
}

Color to_color(const tinyobj::real_t* values) {
  return {static_cast<double>(values[0]), static_cast<double>(values[1]), static_cast<double>(values[2])};
}

bool finite_color(const Color& c) {
  return std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b);
}

// tinyobjloader reads "nan" and "inf" in a vertex as 0 without a word: the first vertex
// coordinate that is not a finite number (nan, inf, 1e400), as "vertex N (line L): 'text'", or "".
std::string first_non_finite_vertex(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::size_t line_number = 0, vertex = 0;
  while (std::getline(in, line)) {
    ++line_number;
    std::size_t at = line.find_first_not_of(" \t");
    if (at == std::string::npos || line[at] != 'v' || at + 1 >= line.size() ||
        (line[at + 1] != ' ' && line[at + 1] != '\t'))
      continue;
    ++vertex;
    std::istringstream tokens(line.substr(at + 1));
    std::string token;
    for (int k = 0; k < 3 && tokens >> token; ++k) {
      const double value = std::strtod(token.c_str(), nullptr);
      if (!std::isfinite(value))
        return "vertex " + std::to_string(vertex) + " (line " + std::to_string(line_number) + "): '" + token +
               "'";
    }
  }
  return "";
}

}  // namespace

void require_mesh_file(const std::string& path, const std::string& format,
                       const SourceLocation& referenced_from) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status))
    throw InputError(referenced_from, format + " file " + quoted(path) + " not found");
  if (!std::filesystem::is_regular_file(status))
    throw InputError(referenced_from, format + " file " + quoted(path) + " is not a regular file");
}

ObjImport import_obj(const std::string& path, const SourceLocation& referenced_from) {
  const auto fail = [&](const std::string& message) -> InputError {
    return InputError(referenced_from, message);
  };

  require_mesh_file(path, "OBJ", referenced_from);

  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  std::string directory = std::filesystem::path(path).parent_path().string();
  config.mtl_search_path = directory.empty() ? std::string(".") : directory;

  tinyobj::ObjReader reader;
  const bool parsed = reader.ParseFromFile(path, config);
  const std::vector<std::string> errors = split_lines(reader.Error());
  if (!parsed) {
    const std::string text = errors.empty() ? "unknown error" : join(errors);
    const int line = line_number_in(text);
    std::string where = "OBJ file " + quoted(path);
    if (line > 0) where += " line " + std::to_string(line);
    throw fail("cannot read " + where + ": " + text);
  }

  ObjImport result;
  const std::string prefix = path + ": ";
  // tinyobjloader only warns about out-of-range indices (and drops quads that have them); the
  // faces it kept are checked one by one below, with better messages, so this is the fallback.
  bool index_out_of_range = false;
  std::vector<std::string> warnings = split_lines(reader.Warning());
  warnings.insert(warnings.end(), errors.begin(), errors.end());
  for (const std::string& line : warnings) {
    if (line.find("out of bounds") != std::string::npos ||
        line.find("invalid vertex index") != std::string::npos) {
      index_out_of_range = true;
      continue;
    }
    const std::string warning = prefix + line;  // once each: a missing material repeats
    if (std::find(result.warnings.begin(), result.warnings.end(), warning) == result.warnings.end())
      result.warnings.push_back(warning);
  }

  if (const std::string bad = first_non_finite_vertex(path); !bad.empty())
    throw fail("OBJ file " + quoted(path) + ": " + bad + " has a non-finite coordinate");

  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  auto mesh = std::make_shared<TriangleMesh>();

  const std::size_t vertex_count = attrib.vertices.size() / 3;
  mesh->positions.reserve(vertex_count);
  for (std::size_t i = 0; i < vertex_count; ++i) {
    const Vec3 p{static_cast<double>(attrib.vertices[3 * i]), static_cast<double>(attrib.vertices[3 * i + 1]),
                 static_cast<double>(attrib.vertices[3 * i + 2])};
    if (!is_finite(p))
      throw fail("OBJ file " + quoted(path) + ": vertex " + std::to_string(i + 1) +
                 " has a non-finite coordinate");
    // The scene file's limit (io/json_node.cpp): beyond it squared distances lose all
    // precision and ray offsets stop working.
    const double magnitude = std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
    if (magnitude > 1e16)
      throw fail("OBJ file " + quoted(path) + ": vertex " + std::to_string(i + 1) +
                 ": magnitude above 1e16 is not supported (found " + fmt::format("{}", magnitude) + ")");
    mesh->positions.push_back(p);
  }
  const std::size_t normal_count = attrib.normals.size() / 3;
  const std::size_t texcoord_count = attrib.texcoords.size() / 2;

  // Gather the triangles with their attribute indices; check every index.
  std::vector<std::array<tinyobj::index_t, 3>> corners;
  std::size_t face_number = 0;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const tinyobj::mesh_t& shape_mesh = shape.mesh;
    std::size_t offset = 0;
    for (std::size_t face = 0; face < shape_mesh.num_face_vertices.size(); ++face) {
      const std::size_t count = shape_mesh.num_face_vertices[face];
      ++face_number;
      if (offset + count > shape_mesh.indices.size())
        throw fail("OBJ file " + quoted(path) + ": inconsistent face data");
      const auto describe_face = [&] {
        return "OBJ file " + quoted(path) + ": triangle " + std::to_string(face_number) +
               (shape.name.empty() ? std::string() : " (object '" + shape.name + "')");
      };
      for (std::size_t k = 0; k < count; ++k) {
        const tinyobj::index_t& index = shape_mesh.indices[offset + k];
        if (index.vertex_index < 0 || static_cast<std::size_t>(index.vertex_index) >= vertex_count)
          throw fail(describe_face() + " refers to vertex " +
                     std::to_string(static_cast<long long>(index.vertex_index) + 1) + " but the file has " +
                     std::to_string(vertex_count) + " vertices (face index out of range)");
        if (index.normal_index != -1 &&
            (index.normal_index < 0 || static_cast<std::size_t>(index.normal_index) >= normal_count))
          throw fail(describe_face() + " refers to normal " +
                     std::to_string(static_cast<long long>(index.normal_index) + 1) + " but the file has " +
                     std::to_string(normal_count) + " normals (face index out of range)");
        if (index.texcoord_index != -1 &&
            (index.texcoord_index < 0 || static_cast<std::size_t>(index.texcoord_index) >= texcoord_count))
          throw fail(describe_face() + " refers to texture coordinate " +
                     std::to_string(static_cast<long long>(index.texcoord_index) + 1) + " but the file has " +
                     std::to_string(texcoord_count) + " texture coordinates (face index out of range)");
      }
      int material = face < shape_mesh.material_ids.size() ? shape_mesh.material_ids[face] : -1;
      if (material < 0 || static_cast<std::size_t>(material) >= reader.GetMaterials().size()) material = -1;
      // tinyobjloader has triangulated already; a fan covers anything it left as a polygon.
      for (std::size_t k = 1; k + 1 < count; ++k) {
        corners.push_back(
            {shape_mesh.indices[offset], shape_mesh.indices[offset + k], shape_mesh.indices[offset + k + 1]});
        result.triangle_material.push_back(material);
      }
      offset += count;
    }
  }
  if (index_out_of_range)
    throw fail("OBJ file " + quoted(path) +
               ": a face refers to a vertex, normal or texture coordinate that does not exist "
               "(face index out of range)");
  if (corners.empty()) throw fail("OBJ file " + quoted(path) + " has no triangles");

  mesh->triangles.reserve(corners.size());
  bool all_normals = true;
  bool any_normals = false;
  bool all_uvs = true;
  bool any_uvs = false;
  for (const auto& triangle : corners) {
    mesh->triangles.push_back({static_cast<uint32_t>(triangle[0].vertex_index),
                               static_cast<uint32_t>(triangle[1].vertex_index),
                               static_cast<uint32_t>(triangle[2].vertex_index)});
    for (const tinyobj::index_t& index : triangle) {
      any_normals = any_normals || index.normal_index >= 0;
      all_normals = all_normals && index.normal_index >= 0;
      any_uvs = any_uvs || index.texcoord_index >= 0;
      all_uvs = all_uvs && index.texcoord_index >= 0;
    }
  }

  if (all_normals) {
    std::size_t replaced = 0;
    mesh->corner_normals.reserve(corners.size());
    for (std::size_t t = 0; t < corners.size(); ++t) {
      std::array<Vec3, 3> normals;
      for (int k = 0; k < 3; ++k) {
        const auto n = static_cast<std::size_t>(corners[t][k].normal_index);
        const Vec3 value{static_cast<double>(attrib.normals[3 * n]),
                         static_cast<double>(attrib.normals[3 * n + 1]),
                         static_cast<double>(attrib.normals[3 * n + 2])};
        if (!is_finite(value))
          throw fail("OBJ file " + quoted(path) + ": normal " + std::to_string(n + 1) +
                     " has a non-finite coordinate");
        const double len = length(value);
        if (len > 0 && std::isfinite(len)) {
          normals[k] = value / len;
        } else {
          const Vec3 face = mesh->face_cross(t);
          normals[k] = length_squared(face) > 0 ? normalize(face) : Vec3{};
          ++replaced;
        }
      }
      mesh->corner_normals.push_back(normals);
    }
    if (replaced > 0)
      result.warnings.push_back(prefix + std::to_string(replaced) +
                                " zero-length vertex normal(s) replaced by the face normal");
  } else if (any_normals) {
    result.warnings.push_back(prefix +
                              "some faces have vertex normals and some do not; using flat "
                              "normals for the whole mesh");
  }

  if (any_uvs) {
    if (!all_uvs)
      result.warnings.push_back(prefix +
                                "some faces have texture coordinates and some do not; the "
                                "others get the default per-triangle uvs");
    constexpr std::array<Vec2, 3> kDefault{Vec2{0, 0}, Vec2{1, 0}, Vec2{1, 1}};
    mesh->corner_uvs.reserve(corners.size());
    for (const auto& triangle : corners) {
      std::array<Vec2, 3> uvs = kDefault;
      const bool has_all = std::all_of(triangle.begin(), triangle.end(),
                                       [](const tinyobj::index_t& i) { return i.texcoord_index >= 0; });
      if (has_all) {
        for (int k = 0; k < 3; ++k) {
          const auto n = static_cast<std::size_t>(triangle[k].texcoord_index);
          uvs[k] = {static_cast<double>(attrib.texcoords[2 * n]),
                    static_cast<double>(attrib.texcoords[2 * n + 1])};
          if (!std::isfinite(uvs[k].x) || !std::isfinite(uvs[k].y))
            throw fail("OBJ file " + quoted(path) + ": texture coordinate " + std::to_string(n + 1) +
                       " is not finite");
        }
      }
      mesh->corner_uvs.push_back(uvs);
    }
  }

  for (const tinyobj::material_t& source : reader.GetMaterials()) {
    ImportedMaterial material;
    material.name = source.name;
    material.ka = to_color(source.ambient);
    material.kd = to_color(source.diffuse);
    material.ke = to_color(source.emission);
    material.ks = to_color(source.specular).average();
    material.shininess = static_cast<double>(source.shininess);
    material.kt = std::clamp(1.0 - static_cast<double>(source.dissolve), 0.0, 1.0);
    material.ior = static_cast<double>(source.ior);
    if (!source.diffuse_texname.empty()) {
      const std::filesystem::path texture(source.diffuse_texname);
      material.diffuse_texture = texture.is_absolute()
                                     ? texture.string()
                                     : (std::filesystem::path(config.mtl_search_path) / texture).string();
    }
    if (!finite_color(material.ka) || !finite_color(material.kd) || !finite_color(material.ke) ||
        !std::isfinite(material.ks) || !std::isfinite(material.shininess) || !std::isfinite(material.ior) ||
        std::isnan(material.kt))
      throw fail("OBJ file " + quoted(path) + ": material '" + source.name + "' has a non-finite value");
    // The ranges a scene file's materials must respect (scene/material_registry.cpp).
    const auto non_negative = [](const Color& c) { return c.r >= 0 && c.g >= 0 && c.b >= 0; };
    std::string problem;
    if (!non_negative(material.ka) || !non_negative(material.kd) || !non_negative(material.ke)) {
      problem = "Ka, Kd and Ke must be >= 0";
    } else if (material.ks < 0) {
      problem = "Ks must be >= 0";
    } else if (material.shininess < 0) {
      problem = "Ns must be >= 0";
    } else if (!(material.ior > 0)) {
      problem = "Ni must be > 0";
    }
    if (!problem.empty())
      throw fail("OBJ file " + quoted(path) + ": material '" + source.name + "': " + problem);
    result.materials.push_back(std::move(material));
  }

  result.mesh = std::move(mesh);
  return result;
}

}  // namespace candela
