#include "io/solution_mesh_formats.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "camera/film.h"

namespace candela {

namespace {

// Binary bodies are assembled byte by byte in little-endian order, whatever the host's order.
void append_u32_le(std::string& bytes, uint32_t value) {
  for (int shift = 0; shift < 32; shift += 8) bytes.push_back(static_cast<char>((value >> shift) & 0xFFu));
}
void append_float_le(std::string& bytes, float value) {
  append_u32_le(bytes, std::bit_cast<uint32_t>(value));
}
void append_vec3_le(std::string& bytes, const Vec3& v) {
  for (int axis = 0; axis < 3; ++axis) append_float_le(bytes, static_cast<float>(v[axis]));
}
void append_color_le(std::string& bytes, const Color& c) {
  for (int channel = 0; channel < 3; ++channel) append_float_le(bytes, static_cast<float>(c[channel]));
}

// The vertex radiosities laid out as a one-row film, so that the display functions of
// camera/tone_map.h (exposure, out-of-range rule, sRGB) apply to them exactly as to an image.
Film vertex_film(const SolutionMesh& vertices) {
  if (vertices.radiosity.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw std::length_error("radiosity solution export: too many vertices for a display film");
  Film film(static_cast<int>(vertices.radiosity.size()), 1);
  for (std::size_t i = 0; i < vertices.radiosity.size(); ++i)
    film.at(static_cast<int>(i), 0) = vertices.radiosity[i];
  return film;
}

// PLY's face indices are `int` and glTF's are UNSIGNED_INT: both hold any count below 2^31.
void require_int_indexable(const SolutionMesh& vertices) {
  if (vertices.positions.size() > static_cast<std::size_t>(std::numeric_limits<int32_t>::max()))
    throw std::length_error("radiosity solution export: too many vertices for 32-bit indices");
}

// RFC 4648 §4 base64 with '=' padding, for the glTF data URI (glTF 2.0 specification, "Buffers and
// Buffer Views").
std::string base64_encode(const std::string& bytes) {
  static constexpr char alphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string text;
  text.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 3 <= bytes.size(); i += 3) {
    const uint32_t group = (uint32_t(uint8_t(bytes[i])) << 16) | (uint32_t(uint8_t(bytes[i + 1])) << 8) |
                           uint32_t(uint8_t(bytes[i + 2]));
    text.push_back(alphabet[(group >> 18) & 63]);
    text.push_back(alphabet[(group >> 12) & 63]);
    text.push_back(alphabet[(group >> 6) & 63]);
    text.push_back(alphabet[group & 63]);
  }
  const std::size_t remaining = bytes.size() - i;
  if (remaining > 0) {
    uint32_t group = uint32_t(uint8_t(bytes[i])) << 16;
    if (remaining == 2) group |= uint32_t(uint8_t(bytes[i + 1])) << 8;
    text.push_back(alphabet[(group >> 18) & 63]);
    text.push_back(alphabet[(group >> 12) & 63]);
    text.push_back(remaining == 2 ? alphabet[(group >> 6) & 63] : '=');
    text.push_back('=');
  }
  return text;
}

// glTF 2.0 specification, "Accessor Data Types" and the bufferView schema: the GL enums it uses.
constexpr int gltf_float = 5126;
constexpr int gltf_unsigned_int = 5125;
constexpr int gltf_array_buffer = 34962;
constexpr int gltf_element_array_buffer = 34963;
constexpr int gltf_triangles = 4;

// The writers index positions and radiosities alike, with 32-bit indices.
void require_consistent(const SolutionMesh& mesh) {
  if (mesh.radiosity.size() != mesh.positions.size())
    throw std::invalid_argument("radiosity solution export: " + std::to_string(mesh.positions.size()) +
                                " vertices but " + std::to_string(mesh.radiosity.size()) +
                                " vertex radiosities");
  require_int_indexable(mesh);
}

}  // namespace

void write_solution_ply(const SolutionMesh& vertices, const DisplaySettings& display, std::ostream& out) {
  require_consistent(vertices);
  // The same bytes the PNG output would hold for these radiosities (tone_map.h's to_display).
  const std::vector<uint8_t> display_colors = to_display(vertex_film(vertices), display);

  // PLY format: Turk, "The PLY Polygon File Format" (binary_little_endian 1.0).
  std::string text =
      "ply\n"
      "format binary_little_endian 1.0\n"
      "comment Candela radiosity solution: x y z in scene units; red green blue the display color "
      "(as in the PNG); b_r b_g b_b the linear vertex radiosity, in the units of the scene's emission\n";
  text += "element vertex " + std::to_string(vertices.positions.size()) + "\n";
  text +=
      "property float x\n"
      "property float y\n"
      "property float z\n"
      "property uchar red\n"
      "property uchar green\n"
      "property uchar blue\n"
      "property float b_r\n"
      "property float b_g\n"
      "property float b_b\n";
  text += "element face " + std::to_string(vertices.triangles.size()) + "\n";
  text +=
      "property list uchar int vertex_indices\n"
      "end_header\n";
  text.reserve(text.size() + vertices.positions.size() * 27 + vertices.triangles.size() * 13);
  for (std::size_t i = 0; i < vertices.positions.size(); ++i) {
    append_vec3_le(text, vertices.positions[i]);
    for (int channel = 0; channel < 3; ++channel)
      text.push_back(static_cast<char>(display_colors[i * 3 + channel]));
    append_color_le(text, vertices.radiosity[i]);
  }
  for (const auto& corners : vertices.triangles) {
    text.push_back(char(3));
    for (uint32_t vertex : corners) append_u32_le(text, vertex);  // < 2^31: the same bits as an int
  }
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
}

void write_solution_gltf(const SolutionMesh& vertices, const DisplaySettings& display, std::ostream& out) {
  require_consistent(vertices);
  const std::size_t vertex_count = vertices.positions.size();
  const std::size_t index_count = vertices.triangles.size() * 3;

  nlohmann::json gltf;
  gltf["asset"] = {{"version", "2.0"}, {"generator", "Candela"}};
  gltf["scene"] = 0;
  nlohmann::json scene = nlohmann::json::object();
  scene["nodes"] = nlohmann::json::array({0});
  gltf["scenes"] = nlohmann::json::array({scene});
  nlohmann::json node = nlohmann::json::object();
  node["name"] = "radiosity solution";

  // glTF requires at least one element in a buffer, a view and an accessor (byteLength ≥ 1,
  // count ≥ 1) and a mesh to have a primitive: an empty solution is a scene with one empty node.
  if (vertex_count > 0) {
    // COLOR_0: exposure as in every output, then clamped per channel (NaN to 0, as to_display does);
    // glTF 2.0 ("Meshes", COLOR_n) requires float colors in [0, 1] and linear.
    std::vector<Color> colors = expose(vertex_film(vertices), display.exposure);
    for (Color& c : colors)
      for (int channel = 0; channel < 3; ++channel) {
        const double value = std::clamp(c[channel], 0.0, 1.0);
        c[channel] = value >= 0 ? value : 0;
      }

    // One buffer of four tightly packed views; every section is a multiple of 4 bytes long, so
    // each view starts 4-aligned as glTF 2.0 ("Data Alignment") requires for float and uint32 components.
    std::string bytes;
    bytes.reserve(vertex_count * 36 + index_count * 4);
    std::array<float, 3> position_min{}, position_max{};
    position_min.fill(std::numeric_limits<float>::infinity());
    position_max.fill(-std::numeric_limits<float>::infinity());
    for (const Vec3& position : vertices.positions) {
      append_vec3_le(bytes, position);
      // min/max of the stored (float) values, which glTF 2.0 ("Accessor Bounds") requires for POSITION.
      for (int axis = 0; axis < 3; ++axis) {
        const float stored = static_cast<float>(position[axis]);
        position_min[axis] = std::min(position_min[axis], stored);
        position_max[axis] = std::max(position_max[axis], stored);
      }
    }
    const std::size_t colors_offset = bytes.size();
    for (const Color& c : colors) append_color_le(bytes, c);
    const std::size_t radiosity_offset = bytes.size();
    for (const Color& c : vertices.radiosity) append_color_le(bytes, c);
    const std::size_t indices_offset = bytes.size();
    for (const auto& corners : vertices.triangles)
      for (uint32_t vertex : corners) append_u32_le(bytes, vertex);

    const auto view = [](std::size_t offset, std::size_t length, int target) {
      return nlohmann::json{
          {"buffer", 0}, {"byteOffset", offset}, {"byteLength", length}, {"target", target}};
    };
    nlohmann::json buffer = nlohmann::json::object();
    buffer["byteLength"] = bytes.size();
    buffer["uri"] = "data:application/octet-stream;base64," + base64_encode(bytes);
    gltf["buffers"] = nlohmann::json::array({buffer});
    gltf["bufferViews"] = nlohmann::json::array({
        view(0, colors_offset, gltf_array_buffer),
        view(colors_offset, radiosity_offset - colors_offset, gltf_array_buffer),
        view(radiosity_offset, indices_offset - radiosity_offset, gltf_array_buffer),
        view(indices_offset, bytes.size() - indices_offset, gltf_element_array_buffer),
    });
    const auto vec3_accessor = [&](int buffer_view) {
      return nlohmann::json{{"bufferView", buffer_view},
                            {"componentType", gltf_float},
                            {"count", vertex_count},
                            {"type", "VEC3"}};
    };
    nlohmann::json position_accessor = vec3_accessor(0);
    position_accessor["min"] = position_min;
    position_accessor["max"] = position_max;
    gltf["accessors"] = nlohmann::json::array({
        position_accessor,
        vec3_accessor(1),
        vec3_accessor(2),
        {{"bufferView", 3}, {"componentType", gltf_unsigned_int}, {"count", index_count}, {"type", "SCALAR"}},
    });
    // Application-specific attributes must start with an underscore (glTF 2.0, "Meshes").
    nlohmann::json primitive = nlohmann::json::object();
    primitive["attributes"] = {{"POSITION", 0}, {"COLOR_0", 1}, {"_RADIOSITY", 2}};
    primitive["indices"] = 3;
    primitive["mode"] = gltf_triangles;
    nlohmann::json mesh = nlohmann::json::object();
    mesh["name"] = "radiosity solution";
    mesh["primitives"] = nlohmann::json::array({primitive});
    gltf["meshes"] = nlohmann::json::array({mesh});
    node["mesh"] = 0;
  }
  gltf["nodes"] = nlohmann::json::array({node});

  const std::string text = gltf.dump(1) + "\n";
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
}

}  // namespace candela
