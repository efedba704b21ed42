#include "io/obj_import.h"

#include <fmt/format.h>
#include <tiny_obj_loader.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <span>
#include <sstream>
#include <string_view>
#include <system_error>

#include "geometry/face_triangulation.h"
#include "math/bounds.h"
#include "math/constants.h"
#include "util/input_file.h"

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

// What the pre-scan of the OBJ text found: the line of each face tinyobjloader keeps (three
// corners or more), in file order, or a problem it reads wrongly without a word.
struct ObjScan {
  std::vector<int> face_lines;
  // The corners of each of those faces: tinyobjloader keeps a face's count in 8 bits (a face of
  // 100,000 corners reads as 160), its indices all.
  std::vector<std::size_t> face_corners;
  std::string problem;  // "line N: ..." or ""
};

bool obj_space(char c) {
  return c == ' ' || c == '\t';
}

// One pass over the text with tinyobjloader's own line breaks ("\n", "\r\n", "\r") and
// statement tests, for what it reads silently wrong:
// - a vertex coordinate that is not a finite number (nan, inf, 1e400): read as 0;
// - an index of an f, l or p statement beyond the 32-bit range (atoi saturates, and the
//   saturated value read as -1 is "the last vertex"), or a negative (relative) one reaching
//   before the first vertex, normal or texture coordinate.
ObjScan scan_obj(std::string_view text) {
  ObjScan scan;
  std::size_t vertices = 0, normals = 0, texcoords = 0;
  int line_number = 0;
  std::size_t position = 0;
  while (position < text.size()) {
    std::size_t end = text.find_first_of("\r\n", position);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(position, end - position);
    position = end + (end + 1 < text.size() && text[end] == '\r' && text[end + 1] == '\n' ? 2 : 1);
    ++line_number;
    line = line.substr(0, line.find('\0'));  // tinyobjloader stops a statement there
    std::size_t at = 0;
    while (at < line.size() && obj_space(line[at])) ++at;
    if (at + 1 >= line.size()) continue;
    const char kind = line[at];
    const std::string located = "line " + std::to_string(line_number) + ": ";
    if (kind == 'v' && line[at + 1] == 't' && at + 2 < line.size() && obj_space(line[at + 2])) {
      ++texcoords;
    } else if (kind == 'v' && line[at + 1] == 'n' && at + 2 < line.size() && obj_space(line[at + 2])) {
      ++normals;
    } else if (kind == 'v' && obj_space(line[at + 1])) {
      ++vertices;
      std::istringstream tokens{std::string(line.substr(at + 1))};
      std::string token;
      for (int k = 0; k < 3 && tokens >> token; ++k) {
        const double value = std::strtod(token.c_str(), nullptr);
        if (!std::isfinite(value)) {
          scan.problem =
              located + "vertex " + std::to_string(vertices) + ": '" + token + "' is a non-finite coordinate";
          return scan;
        }
      }
    } else if ((kind == 'f' || kind == 'l' || kind == 'p') && obj_space(line[at + 1])) {
      std::size_t corners = 0;
      std::size_t i = at + 2;
      while (i < line.size()) {
        while (i < line.size() && (obj_space(line[i]) || line[i] == '\r')) ++i;
        if (i >= line.size()) break;
        const std::size_t token_end = line.find_first_of(" \t\r", i);
        const std::string_view token =
            line.substr(i, token_end == std::string_view::npos ? line.npos : token_end - i);
        i += token.size();
        ++corners;
        // v, v/vt, v//vn, v/vt/vn: each part as tinyobjloader's atoi reads it.
        std::size_t part_start = 0;
        for (int part = 0; part < 3 && part_start <= token.size(); ++part) {
          std::size_t slash = token.find('/', part_start);
          if (slash == std::string_view::npos) slash = token.size();
          std::string_view digits = token.substr(part_start, slash - part_start);
          part_start = slash + 1;
          const bool negative = !digits.empty() && digits.front() == '-';
          if (!digits.empty() && (digits.front() == '-' || digits.front() == '+')) digits.remove_prefix(1);
          std::size_t count = 0;
          while (count < digits.size() && std::isdigit(static_cast<unsigned char>(digits[count]))) ++count;
          if (count == 0) continue;
          digits = digits.substr(0, count);
          const char* what = part == 0 ? "vertex" : part == 1 ? "texture coordinate" : "normal";
          const std::size_t before = part == 0 ? vertices : part == 1 ? texcoords : normals;
          uint64_t value = 0;
          const auto [last, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
          (void)last;
          const uint64_t limit = negative ? uint64_t{2147483648u} : uint64_t{2147483647u};
          if (error != std::errc() || value > limit) {
            scan.problem = located + "index '" + std::string(token) + "': " + what +
                           " index beyond the 32-bit integer range (face index out of range)";
            return scan;
          }
          if (negative && value > before) {
            scan.problem = located + "index '" + std::string(token) + "' refers back to " + what + " -" +
                           std::to_string(value) + " but only " + std::to_string(before) +
                           " precede it (face index out of range)";
            return scan;
          }
        }
      }
      if (kind == 'f' && corners >= 3) {
        scan.face_lines.push_back(line_number);
        scan.face_corners.push_back(corners);
      }
    }
  }
  return scan;
}

// tinyobjloader opens the files of mtllib itself, and blocked in open() on a FIFO or read
// /dev/zero until memory ran out: each is read here, as a regular file of bounded
// size, and handed over as text. A missing file stays a warning, as before; any other problem
// is kept to be thrown once tinyobjloader returns.
class BoundedMaterialReader final : public tinyobj::MaterialReader {
 public:
  explicit BoundedMaterialReader(std::string directory) : directory_(std::move(directory)) {}

  bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* material_map, std::string* warning,
                  std::string* error) override {
    const std::string path = (std::filesystem::path(directory_) / name).string();
    const std::string what = "material file " + quoted(path);
    std::error_code ec;
    if (!std::filesystem::exists(std::filesystem::status(path, ec))) {
      if (warning) *warning += "material file " + quoted(name) + " not found in '" + directory_ + "'\n";
      return false;
    }
    std::string text;
    try {
      text = read_input_file(path, what, kLargeInputLimit);
    } catch (const InputError& e) {
      if (problem_.empty()) problem_ = e.message();
      return false;
    }
    std::istringstream in(text);
    tinyobj::LoadMtl(material_map, materials, &in, warning, error);
    return true;
  }

  const std::string& problem() const { return problem_; }

 private:
  std::string directory_;
  std::string problem_;
};

// The OBJ file being imported, for its errors: each is located where the scene refers to it.
struct ObjSource {
  const std::string& path;
  const SourceLocation& referenced_from;

  InputError fail(const std::string& message) const { return InputError(referenced_from, message); }
};

// The OBJ file's text, read as a regular file of bounded size (as each MTL file is, by
// BoundedMaterialReader).
std::string read_obj_text(const ObjSource& source) {
  std::string text;
  try {
    text = read_input_file(source.path, "OBJ file " + quoted(source.path), kLargeInputLimit);
  } catch (const InputError& e) {
    throw source.fail(e.message());
  }
  return text;
}

// What tinyobjloader read, and its errors one per line.
struct ParsedObj {
  std::string directory;  // the OBJ file's: its MTL files and textures are looked up there
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warning_text;
  std::vector<std::string> errors;
};

// tinyobjloader's reading of text, with the MTL files through BoundedMaterialReader; what it cannot
// read is thrown, with the line when its message names one.
ParsedObj parse_obj(const ObjSource& source, std::string text) {
  const std::string& path = source.path;
  ParsedObj obj;
  obj.directory = std::filesystem::path(path).parent_path().string();
  if (obj.directory.empty()) obj.directory = ".";
  BoundedMaterialReader material_reader(obj.directory);
  std::string error_text;
  std::istringstream stream(text);
  text = {};
  // Polygons are triangulated by gather_triangles (triangulate_face), not by tinyobjloader.
  const bool parsed = tinyobj::LoadObj(&obj.attrib, &obj.shapes, &obj.materials, &obj.warning_text,
                                       &error_text, &stream, &material_reader,
                                       /*triangulate=*/false, /*default_vcols_fallback=*/false);
  if (!material_reader.problem().empty())
    throw source.fail("OBJ file " + quoted(path) + ": " + material_reader.problem());
  obj.errors = split_lines(error_text);
  if (!parsed) {
    const std::string message = obj.errors.empty() ? "unknown error" : join(obj.errors);
    const int line = line_number_in(message);
    std::string where = "OBJ file " + quoted(path);
    if (line > 0) where += " line " + std::to_string(line);
    throw source.fail("cannot read " + where + ": " + message);
  }
  return obj;
}

// tinyobjloader's warnings and errors into warnings, each prefixed and once (a missing material
// repeats); returns whether one of them was about an index out of range. tinyobjloader only
// warns about out-of-range indices; the faces are checked one by one (check_face_indices), with
// better messages, so this is the fallback.
bool collect_warnings(const ParsedObj& obj, const std::string& prefix, std::vector<std::string>& warnings) {
  bool index_out_of_range = false;
  std::vector<std::string> lines = split_lines(obj.warning_text);
  lines.insert(lines.end(), obj.errors.begin(), obj.errors.end());
  for (const std::string& line : lines) {
    if (line.find("out of bounds") != std::string::npos ||
        line.find("invalid vertex index") != std::string::npos) {
      index_out_of_range = true;
      continue;
    }
    const std::string warning = prefix + line;
    if (std::find(warnings.begin(), warnings.end(), warning) == warnings.end()) warnings.push_back(warning);
  }
  return index_out_of_range;
}

void read_positions(const ObjSource& source, const tinyobj::attrib_t& attrib, TriangleMesh& mesh) {
  const std::string& path = source.path;
  const std::size_t vertex_count = attrib.vertices.size() / 3;
  mesh.positions.reserve(vertex_count);
  for (std::size_t i = 0; i < vertex_count; ++i) {
    const Vec3 p{static_cast<double>(attrib.vertices[3 * i]), static_cast<double>(attrib.vertices[3 * i + 1]),
                 static_cast<double>(attrib.vertices[3 * i + 2])};
    if (!is_finite(p))
      throw source.fail("OBJ file " + quoted(path) + ": vertex " + std::to_string(i + 1) +
                        " has a non-finite coordinate");
    // The scene file's limit (io/json_node.cpp): beyond it squared distances lose all
    // precision and ray offsets stop working.
    const double magnitude = std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
    static_assert(kMaxSceneMagnitude == 1e16, "the message below names it");
    if (magnitude > kMaxSceneMagnitude)
      throw source.fail("OBJ file " + quoted(path) + ": vertex " + std::to_string(i + 1) +
                        ": magnitude above 1e16 is not supported (found " + fmt::format("{}", magnitude) +
                        ")");
    mesh.positions.push_back(p);
  }
}

// Whether the pre-scan saw the same faces in the same order (their counts agree with
// tinyobjloader's 8-bit ones, and the corners add up): then it gives each face's line and its
// true corner count.
bool scan_matches(const ObjScan& scan, const std::vector<tinyobj::shape_t>& shapes) {
  std::size_t face_total = 0, index_total = 0, scan_total = 0;
  for (const tinyobj::shape_t& shape : shapes) {
    face_total += shape.mesh.num_face_vertices.size();
    index_total += shape.mesh.indices.size();
  }
  bool lines_known = face_total == scan.face_lines.size();
  for (std::size_t face = 0, shape = 0, in_shape = 0; lines_known && face < face_total; ++face, ++in_shape) {
    while (in_shape >= shapes[shape].mesh.num_face_vertices.size()) {
      ++shape;
      in_shape = 0;
    }
    lines_known = scan.face_corners[face] % 256 == shapes[shape].mesh.num_face_vertices[in_shape];
    scan_total += scan.face_corners[face];
  }
  return lines_known && scan_total == index_total;
}

// Every index of a face's corners refers to a vertex, normal or texture coordinate of the file;
// describe_face() names the face in the error.
template <typename DescribeFace>
void check_face_indices(const ObjSource& source, const tinyobj::attrib_t& attrib,
                        std::span<const tinyobj::index_t> indices, const DescribeFace& describe_face) {
  const std::size_t vertex_count = attrib.vertices.size() / 3;
  const std::size_t normal_count = attrib.normals.size() / 3;
  const std::size_t texcoord_count = attrib.texcoords.size() / 2;
  for (const tinyobj::index_t& index : indices) {
    if (index.vertex_index < 0 || static_cast<std::size_t>(index.vertex_index) >= vertex_count)
      throw source.fail(describe_face() + " refers to vertex " +
                        std::to_string(static_cast<long long>(index.vertex_index) + 1) +
                        " but the file has " + std::to_string(vertex_count) +
                        " vertices (face index out of range)");
    if (index.normal_index != -1 &&
        (index.normal_index < 0 || static_cast<std::size_t>(index.normal_index) >= normal_count))
      throw source.fail(describe_face() + " refers to normal " +
                        std::to_string(static_cast<long long>(index.normal_index) + 1) +
                        " but the file has " + std::to_string(normal_count) +
                        " normals (face index out of range)");
    if (index.texcoord_index != -1 &&
        (index.texcoord_index < 0 || static_cast<std::size_t>(index.texcoord_index) >= texcoord_count))
      throw source.fail(describe_face() + " refers to texture coordinate " +
                        std::to_string(static_cast<long long>(index.texcoord_index) + 1) +
                        " but the file has " + std::to_string(texcoord_count) +
                        " texture coordinates (face index out of range)");
  }
}

using TriangleCorners = std::array<tinyobj::index_t, 3>;

// Gather the triangles with their attribute indices; check every index. Each face is triangulated
// (triangulate_face) over the mesh's positions; each triangle's material goes to triangle_material.
std::vector<TriangleCorners> gather_triangles(const ObjSource& source, const ParsedObj& obj,
                                              const ObjScan& scan, const TriangleMesh& mesh,
                                              std::vector<int>& triangle_material) {
  const std::string& path = source.path;
  std::vector<TriangleCorners> corners;
  std::size_t face_number = 0;
  // The pre-scan gives each face's line and its true corner count when it saw the same faces.
  const bool lines_known = scan_matches(scan, obj.shapes);
  std::vector<Vec3> face_positions;
  std::vector<std::array<uint32_t, 3>> face_triangles;
  for (const tinyobj::shape_t& shape : obj.shapes) {
    const tinyobj::mesh_t& shape_mesh = shape.mesh;
    std::size_t offset = 0;
    for (std::size_t face = 0; face < shape_mesh.num_face_vertices.size(); ++face) {
      ++face_number;
      const std::size_t count =
          lines_known ? scan.face_corners[face_number - 1] : shape_mesh.num_face_vertices[face];
      if (offset + count > shape_mesh.indices.size())
        throw source.fail("OBJ file " + quoted(path) + ": inconsistent face data");
      const auto describe_face = [&] {
        return "OBJ file " + quoted(path) +
               (lines_known ? " line " + std::to_string(scan.face_lines[face_number - 1]) : std::string()) +
               ": face " + std::to_string(face_number) +
               (shape.name.empty() ? std::string() : " (object '" + shape.name + "')");
      };
      check_face_indices(source, obj.attrib,
                         std::span<const tinyobj::index_t>(shape_mesh.indices).subspan(offset, count),
                         describe_face);
      int material = face < shape_mesh.material_ids.size() ? shape_mesh.material_ids[face] : -1;
      if (material < 0 || static_cast<std::size_t>(material) >= obj.materials.size()) material = -1;
      face_positions.clear();
      for (std::size_t k = 0; k < count; ++k)
        face_positions.push_back(
            mesh.positions[static_cast<std::size_t>(shape_mesh.indices[offset + k].vertex_index)]);
      if (const std::string problem = triangulate_face(face_positions, face_triangles); !problem.empty())
        throw source.fail(describe_face() + " is " + problem);
      for (const auto& [a, b, c] : face_triangles) {
        corners.push_back(
            {shape_mesh.indices[offset + a], shape_mesh.indices[offset + b], shape_mesh.indices[offset + c]});
        triangle_material.push_back(material);
      }
      offset += count;
    }
  }
  return corners;
}

// Which of the triangles' corners have a normal, and which a texture coordinate.
struct CornerAttributes {
  bool all_normals = true;
  bool any_normals = false;
  bool all_uvs = true;
  bool any_uvs = false;
};

CornerAttributes add_triangles(const std::vector<TriangleCorners>& corners, TriangleMesh& mesh) {
  CornerAttributes present;
  mesh.triangles.reserve(corners.size());
  for (const auto& triangle : corners) {
    mesh.triangles.push_back({static_cast<uint32_t>(triangle[0].vertex_index),
                              static_cast<uint32_t>(triangle[1].vertex_index),
                              static_cast<uint32_t>(triangle[2].vertex_index)});
    for (const tinyobj::index_t& index : triangle) {
      present.any_normals = present.any_normals || index.normal_index >= 0;
      present.all_normals = present.all_normals && index.normal_index >= 0;
      present.any_uvs = present.any_uvs || index.texcoord_index >= 0;
      present.all_uvs = present.all_uvs && index.texcoord_index >= 0;
    }
  }
  return present;
}

// Every corner's normal, unit length; a zero-length one replaced by the face normal (with a warning).
void add_corner_normals(const ObjSource& source, const tinyobj::attrib_t& attrib,
                        const std::vector<TriangleCorners>& corners, const std::string& prefix,
                        TriangleMesh& mesh, std::vector<std::string>& warnings) {
  std::size_t replaced = 0;
  mesh.corner_normals.reserve(corners.size());
  for (std::size_t t = 0; t < corners.size(); ++t) {
    std::array<Vec3, 3> normals;
    for (int k = 0; k < 3; ++k) {
      const auto n = static_cast<std::size_t>(corners[t][k].normal_index);
      const Vec3 value{static_cast<double>(attrib.normals[3 * n]),
                       static_cast<double>(attrib.normals[3 * n + 1]),
                       static_cast<double>(attrib.normals[3 * n + 2])};
      if (!is_finite(value))
        throw source.fail("OBJ file " + quoted(source.path) + ": normal " + std::to_string(n + 1) +
                          " has a non-finite coordinate");
      const double len = length(value);
      if (len > 0 && std::isfinite(len)) {
        normals[k] = value / len;
      } else {
        const Vec3 face = mesh.face_cross(t);
        normals[k] = length_squared(face) > 0 ? normalize(face) : Vec3{};
        ++replaced;
      }
    }
    mesh.corner_normals.push_back(normals);
  }
  if (replaced > 0)
    warnings.push_back(prefix + std::to_string(replaced) +
                       " zero-length vertex normal(s) replaced by the face normal");
}

// Every corner's texture coordinate; a triangle without them all gets the default per-triangle uvs.
void add_corner_uvs(const ObjSource& source, const tinyobj::attrib_t& attrib,
                    const std::vector<TriangleCorners>& corners, TriangleMesh& mesh) {
  constexpr std::array<Vec2, 3> kDefault{Vec2{0, 0}, Vec2{1, 0}, Vec2{1, 1}};
  mesh.corner_uvs.reserve(corners.size());
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
          throw source.fail("OBJ file " + quoted(source.path) + ": texture coordinate " +
                            std::to_string(n + 1) + " is not finite");
      }
    }
    mesh.corner_uvs.push_back(uvs);
  }
}

// An MTL material as the scene's materials take it, its texture resolved against directory.
ImportedMaterial import_material(const ObjSource& source, const tinyobj::material_t& material_source,
                                 const std::string& directory) {
  const std::string& path = source.path;
  ImportedMaterial material;
  material.name = material_source.name;
  material.ka = to_color(material_source.ambient);
  material.kd = to_color(material_source.diffuse);
  material.ke = to_color(material_source.emission);
  material.ks = to_color(material_source.specular).average();
  material.shininess = static_cast<double>(material_source.shininess);
  material.kt = std::clamp(1.0 - static_cast<double>(material_source.dissolve), 0.0, 1.0);
  material.ior = static_cast<double>(material_source.ior);
  if (!material_source.diffuse_texname.empty()) {
    const std::filesystem::path texture(material_source.diffuse_texname);
    material.diffuse_texture =
        texture.is_absolute() ? texture.string() : (std::filesystem::path(directory) / texture).string();
  }
  if (!finite_color(material.ka) || !finite_color(material.kd) || !finite_color(material.ke) ||
      !std::isfinite(material.ks) || !std::isfinite(material.shininess) || !std::isfinite(material.ior) ||
      std::isnan(material.kt))
    throw source.fail("OBJ file " + quoted(path) + ": material '" + material_source.name +
                      "' has a non-finite value");
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
    throw source.fail("OBJ file " + quoted(path) + ": material '" + material_source.name + "': " + problem);
  return material;
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
  require_mesh_file(path, "OBJ", referenced_from);
  const ObjSource source{path, referenced_from};
  std::string text = read_obj_text(source);
  const ObjScan scan = scan_obj(text);
  if (!scan.problem.empty()) throw source.fail("OBJ file " + quoted(path) + " " + scan.problem);
  const ParsedObj obj = parse_obj(source, std::move(text));

  ObjImport result;
  const std::string prefix = path + ": ";
  const bool index_out_of_range = collect_warnings(obj, prefix, result.warnings);
  auto mesh = std::make_shared<TriangleMesh>();
  read_positions(source, obj.attrib, *mesh);
  const std::vector<TriangleCorners> corners =
      gather_triangles(source, obj, scan, *mesh, result.triangle_material);
  if (index_out_of_range)
    throw source.fail("OBJ file " + quoted(path) +
                      ": a face refers to a vertex, normal or texture coordinate that does not exist "
                      "(face index out of range)");
  if (corners.empty()) throw source.fail("OBJ file " + quoted(path) + " has no triangles");

  const CornerAttributes present = add_triangles(corners, *mesh);
  if (present.all_normals) {
    add_corner_normals(source, obj.attrib, corners, prefix, *mesh, result.warnings);
  } else if (present.any_normals) {
    result.warnings.push_back(prefix +
                              "some faces have vertex normals and some do not; using flat "
                              "normals for the whole mesh");
  }
  if (present.any_uvs) {
    if (!present.all_uvs)
      result.warnings.push_back(prefix +
                                "some faces have texture coordinates and some do not; the "
                                "others get the default per-triangle uvs");
    add_corner_uvs(source, obj.attrib, corners, *mesh);
  }
  for (const tinyobj::material_t& material_source : obj.materials)
    result.materials.push_back(import_material(source, material_source, obj.directory));
  result.mesh = std::move(mesh);
  return result;
}

}  // namespace candela
