// Small mesh files for the importer tests (src/io/*_import_test.cpp) and the cross-module tests
// that load them through a scene (tests/mesh_scene_test.cpp): a PLY cube and the pieces of a
// glTF unit square (its buffer, its JSON, as data URI or .glb).
#pragma once

#include <cstdint>
#include <cstring>
#include <string>

namespace candela::testing {

// A unit cube of 8 vertices and 6 quads (outward, counter-clockwise), with an extra vertex
// property, an extra element and comments.
inline constexpr const char* kAsciiCube = R"(ply
format ascii 1.0
comment made by hand
obj_info nothing
element vertex 8
property float x
property float y
property float z
property uchar confidence
element edge 1
property int vertex1
property int vertex2
element face 6
property list uchar int vertex_indices
property uchar flags
end_header
0 0 0 9
1 0 0 9
1 1 0 9
0 1 0 9
0 0 1 9
1 0 1 9
1 1 1 9
0 1 1 9
0 1
4 0 3 2 1 0
4 4 5 6 7 0
4 0 1 5 4 0
4 2 3 7 6 0
4 1 2 6 5 0
4 3 0 4 7 0
)";

inline std::string base64(const std::string& bytes) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) |
                       (static_cast<unsigned char>(bytes[i + 1]) << 8) |
                       static_cast<unsigned char>(bytes[i + 2]);
    out += {table[(v >> 18) & 63], table[(v >> 12) & 63], table[(v >> 6) & 63], table[v & 63]};
  }
  if (i + 1 == bytes.size()) {
    const unsigned v = static_cast<unsigned char>(bytes[i]) << 16;
    out += {table[(v >> 18) & 63], table[(v >> 12) & 63], '=', '='};
  } else if (i + 2 == bytes.size()) {
    const unsigned v =
        (static_cast<unsigned char>(bytes[i]) << 16) | (static_cast<unsigned char>(bytes[i + 1]) << 8);
    out += {table[(v >> 18) & 63], table[(v >> 12) & 63], table[(v >> 6) & 63], '='};
  }
  return out;
}

template <typename T>
void put(std::string& bytes, T value) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  bytes.append(raw, sizeof(T));
}

// A unit square in z = 0 (4 float positions, 48 bytes) and two triangles of uint16 indices (12).
inline std::string square_buffer(float nan_at_y = 0, std::uint16_t last_index = 3) {
  std::string bytes;
  const float corners[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int v = 0; v < 4; ++v) {
    put<float>(bytes, corners[v][0]);
    put<float>(bytes, v == 1 ? nan_at_y : corners[v][1]);
    put<float>(bytes, 0);
  }
  for (std::uint16_t i : {0, 1, 2, 0, 2}) put<std::uint16_t>(bytes, i);
  put<std::uint16_t>(bytes, last_index);
  return bytes;
}

// The JSON around a buffer of square_buffer's layout; uri empty for .glb's BIN chunk.
inline std::string square_json(const std::string& uri, const std::string& node = R"({"mesh": 0})",
                               const std::string& extra_primitive = "") {
  return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
    "nodes": [)" +
         node + R"(],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": 4})" +
         extra_primitive + R"(]}],
    "buffers": [{"byteLength": 60)" +
         (uri.empty() ? std::string() : R"(, "uri": ")" + uri + "\"") + R"(}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                    {"buffer": 0, "byteOffset": 48, "byteLength": 12}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                   "min": [0, 0, 0], "max": [1, 1, 0]},
                  {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}]})";
}

inline std::string data_uri(const std::string& bytes) {
  return "data:application/octet-stream;base64," + base64(bytes);
}

inline std::string glb(const std::string& json, const std::string& bin) {
  std::string j = json;
  while (j.size() % 4 != 0) j += ' ';
  std::string b = bin;
  while (b.size() % 4 != 0) b += '\0';
  std::string out = "glTF";
  put<std::uint32_t>(out, 2);
  put<std::uint32_t>(out, static_cast<std::uint32_t>(12 + 8 + j.size() + 8 + b.size()));
  put<std::uint32_t>(out, static_cast<std::uint32_t>(j.size()));
  out += "JSON" + j;
  put<std::uint32_t>(out, static_cast<std::uint32_t>(b.size()));
  out += std::string("BIN\0", 4) + b;
  return out;
}

}  // namespace candela::testing
