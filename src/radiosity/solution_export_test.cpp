// Tests of the radiosity solution exports (radiosity/solution_export.h): every file is parsed back
// and compared value by value with a three-element solution built by hand.
#include "radiosity/solution_export.h"

#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "scratch_directory.h"

namespace candela {
namespace {

RadiositySurface triangle(const Vec3& a, const Vec3& b, const Vec3& c, uint32_t object,
                          const Color& reflectance, const Color& emission) {
  RadiositySurface s;
  s.corners = {a, b, c};
  s.area = 0.5 * length(cross(b - a, c - a));
  s.centroid = (a + b + c) * (1.0 / 3);
  s.normal = normalize(cross(b - a, c - a));
  s.object = object;
  s.reflectance = reflectance;
  s.emission = emission;
  return s;
}

// Element radiosities: B0 and B2 exceed 1 in one channel, so clamping and exposure show.
const Color b0(2, 0.5, 0.25), b1(0.1, 0.2, 0.3), b2(4, 0.1, 0);

// A unit square in z = 0 split along its diagonal (object 0, patch 0: elements 0 and 1) and an
// emitting triangle in x = 2 facing +x (object 1, patch 1: element 2). Values are chosen to need
// all 17 significant digits (1/3, 0.1 + 0.2) or an extreme exponent (1e-300).
RadiositySolveResult three_element_solution() {
  RadiositySolveResult solution;
  solution.mesh.elements = {
      triangle({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, 0, Color(0.1, 0.5, 0.7), Color(0)),
      triangle({0, 0, 0}, {1, 1, 0}, {0, 1, 0}, 0, Color(0.8, 0.2, 1.0 / 3), Color(0)),
      triangle({2, 0, 0}, {2, 1, 0}, {2, 0, 1}, 1, Color(0.25, 0.25, 0.25),
               Color(0.1 + 0.2, 1e-300, 123456789.125)),
  };
  solution.mesh.patch_of_element = {0, 0, 1};
  solution.element_radiosity = {b0, b1, b2};
  return solution;
}

// The vertex radiosity at corner k of element e, by hand: the square has no interior vertex, so
// every vertex is an isolated boundary vertex and takes the mean of the elements holding it
// (radiosity/vertex_radiosity.h); the diagonal's ends are shared by elements 0 and 1.
Color expected_vertex_radiosity(std::size_t element, std::size_t corner) {
  const Color shared = (b0 + b1) * 0.5;
  const std::array<std::array<Color, 3>, 3> table = {
      {{shared, b0, shared}, {shared, shared, b1}, {b2, b2, b2}}};
  return table[element][corner];
}
constexpr std::size_t expected_vertex_count = 7;  // 4 of the square + 3 of the triangle

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (std::size_t end; (end = text.find(separator, start)) != std::string::npos; start = end + 1)
    parts.push_back(text.substr(start, end - start));
  parts.push_back(text.substr(start));
  return parts;
}

double parse_double(const std::string& text) {
  double value = std::numeric_limits<double>::quiet_NaN();
  const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
  EXPECT_TRUE(result.ec == std::errc() && result.ptr == text.data() + text.size())
      << "not a number: " << text;
  return value;
}

// Little-endian readers, independent of the host's byte order.
uint32_t read_u32_le(const std::string& bytes, std::size_t offset) {
  uint32_t value = 0;
  for (int i = 3; i >= 0; --i) value = (value << 8) | uint8_t(bytes.at(offset + i));
  return value;
}
float read_float_le(const std::string& bytes, std::size_t offset) {
  return std::bit_cast<float>(read_u32_le(bytes, offset));
}

// RFC 4648 base64, strict: rejects characters outside the alphabet and bad padding.
std::string base64_decode(const std::string& text) {
  const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  if (text.size() % 4 != 0) throw std::invalid_argument("base64 length not a multiple of 4");
  std::string bytes;
  for (std::size_t i = 0; i < text.size(); i += 4) {
    uint32_t group = 0;
    int padding = 0;
    for (std::size_t k = 0; k < 4; ++k) {
      const char c = text[i + k];
      uint32_t sextet = 0;
      if (c == '=' && i + 4 == text.size() && k >= 2) {
        ++padding;
      } else {
        const auto position = alphabet.find(c);
        if (position == std::string::npos || padding > 0) throw std::invalid_argument("bad base64");
        sextet = static_cast<uint32_t>(position);
      }
      group = (group << 6) | sextet;
    }
    bytes.push_back(char(group >> 16));
    if (padding < 2) bytes.push_back(char((group >> 8) & 0xFF));
    if (padding < 1) bytes.push_back(char(group & 0xFF));
  }
  return bytes;
}

// sRGB transfer curve (IEC 61966-2-1) written out here, not taken from camera/tone_map.h.
uint8_t srgb_byte(double linear) {
  const double clamped = std::min(std::max(linear, 0.0), 1.0);
  const double encoded = clamped <= 0.0031308 ? 12.92 * clamped : 1.055 * std::pow(clamped, 1 / 2.4) - 0.055;
  return static_cast<uint8_t>(std::lround(encoded * 255));
}

std::string csv_text(const RadiositySolveResult& solution) {
  std::ostringstream out;
  write_solution_csv(solution, out);
  return out.str();
}
std::string ply_bytes(const RadiositySolveResult& solution, const DisplaySettings& display) {
  std::ostringstream out(std::ios::binary);
  write_solution_ply(solution, display, out);
  return out.str();
}
std::string gltf_text(const RadiositySolveResult& solution, const DisplaySettings& display) {
  std::ostringstream out;
  write_solution_gltf(solution, display, out);
  return out.str();
}
std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

const std::string csv_header = "id,patch,area,cx,cy,cz,nx,ny,nz,e_r,e_g,e_b,rho_r,rho_g,rho_b,b_r,b_g,b_b";

// ---- CSV -------------------------------------------------------------------------------------

TEST(SolutionExport, CsvRoundTripsEveryColumnOfEveryElementExactly) {
  const RadiositySolveResult solution = three_element_solution();
  const std::string text = csv_text(solution);
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.back(), '\n');
  EXPECT_EQ(text.find('\r'), std::string::npos);
  std::vector<std::string> lines = split(text, '\n');
  ASSERT_EQ(lines.back(), "");  // after the last '\n'
  lines.pop_back();
  ASSERT_EQ(lines.size(), 1 + solution.mesh.elements.size());
  EXPECT_EQ(lines[0], csv_header);

  for (std::size_t id = 0; id < solution.mesh.elements.size(); ++id) {
    SCOPED_TRACE("element " + std::to_string(id));
    const RadiositySurface& element = solution.mesh.elements[id];
    const Color& b = solution.element_radiosity[id];
    const std::vector<std::string> fields = split(lines[1 + id], ',');
    ASSERT_EQ(fields.size(), 18u);
    EXPECT_EQ(fields[0], std::to_string(id));
    EXPECT_EQ(fields[1], std::to_string(solution.mesh.patch_of_element[id]));
    const std::array<double, 16> expected = {element.area,
                                             element.centroid.x,
                                             element.centroid.y,
                                             element.centroid.z,
                                             element.normal.x,
                                             element.normal.y,
                                             element.normal.z,
                                             element.emission.r,
                                             element.emission.g,
                                             element.emission.b,
                                             element.reflectance.r,
                                             element.reflectance.g,
                                             element.reflectance.b,
                                             b.r,
                                             b.g,
                                             b.b};
    for (std::size_t column = 0; column < expected.size(); ++column)
      EXPECT_EQ(parse_double(fields[2 + column]), expected[column])
          << "column " << lines[0] << " #" << 2 + column;
  }
  // The values that need every digit come out as the shortest text that reads back exactly.
  EXPECT_EQ(split(lines[3], ',')[9], "0.30000000000000004");  // e_r = 0.1 + 0.2
  EXPECT_EQ(split(lines[3], ',')[10], "1e-300");
  EXPECT_EQ(split(lines[1], ',')[3], "0.6666666666666666");  // cx = 2/3
  EXPECT_EQ(lines[3],
            "2,1,0.5,2,0.3333333333333333,0.3333333333333333,1,0,0,0.30000000000000004,1e-300,"
            "123456789.125,0.25,0.25,0.25,4,0.1,0");
}

// ---- PLY -------------------------------------------------------------------------------------

struct PlyVertex {
  std::array<float, 3> position;
  std::array<uint8_t, 3> color;
  std::array<float, 3> radiosity;
};
struct PlyFile {
  std::vector<std::string> header;  // lines up to and including end_header
  std::vector<PlyVertex> vertices;
  std::vector<std::array<int32_t, 3>> faces;
};

// Parses the exact layout the header promises; fails the test on any deviation.
PlyFile parse_ply(const std::string& bytes) {
  PlyFile ply;
  std::size_t offset = 0;
  while (ply.header.empty() || ply.header.back() != "end_header") {
    const std::size_t end = bytes.find('\n', offset);
    if (end == std::string::npos) throw std::runtime_error("PLY header not terminated");
    ply.header.push_back(bytes.substr(offset, end - offset));
    offset = end + 1;
  }
  std::size_t vertex_count = 0, face_count = 0;
  for (const std::string& line : ply.header) {
    if (line.rfind("element vertex ", 0) == 0) vertex_count = std::stoul(line.substr(15));
    if (line.rfind("element face ", 0) == 0) face_count = std::stoul(line.substr(13));
  }
  constexpr std::size_t vertex_bytes = 3 * 4 + 3 + 3 * 4, face_bytes = 1 + 3 * 4;
  if (bytes.size() - offset != vertex_count * vertex_bytes + face_count * face_bytes)
    throw std::runtime_error("PLY body size does not match the header");
  for (std::size_t i = 0; i < vertex_count; ++i, offset += vertex_bytes) {
    PlyVertex v;
    for (int k = 0; k < 3; ++k) {
      v.position[k] = read_float_le(bytes, offset + 4 * k);
      v.color[k] = uint8_t(bytes[offset + 12 + k]);
      v.radiosity[k] = read_float_le(bytes, offset + 15 + 4 * k);
    }
    ply.vertices.push_back(v);
  }
  for (std::size_t i = 0; i < face_count; ++i, offset += face_bytes) {
    if (uint8_t(bytes[offset]) != 3) throw std::runtime_error("PLY face is not a triangle");
    std::array<int32_t, 3> face;
    for (int k = 0; k < 3; ++k) face[k] = static_cast<int32_t>(read_u32_le(bytes, offset + 1 + 4 * k));
    ply.faces.push_back(face);
  }
  return ply;
}

std::vector<std::string> expected_ply_header(std::size_t vertices, std::size_t faces) {
  return {"ply",
          "format binary_little_endian 1.0",
          "",  // the comment, checked apart
          "element vertex " + std::to_string(vertices),
          "property float x",
          "property float y",
          "property float z",
          "property uchar red",
          "property uchar green",
          "property uchar blue",
          "property float b_r",
          "property float b_g",
          "property float b_b",
          "element face " + std::to_string(faces),
          "property list uchar int vertex_indices",
          "end_header"};
}

void expect_ply_header(std::vector<std::string> header, std::size_t vertices, std::size_t faces) {
  ASSERT_EQ(header.size(), 16u);
  EXPECT_EQ(header[2].rfind("comment Candela", 0), 0u) << header[2];
  EXPECT_NE(header[2].find("scene units"), std::string::npos) << header[2];
  header[2] = "";
  EXPECT_EQ(header, expected_ply_header(vertices, faces));
}

TEST(SolutionExport, PlyCarriesVerticesRadiositiesDisplayColorsAndFaces) {
  const RadiositySolveResult solution = three_element_solution();
  const PlyFile ply = parse_ply(ply_bytes(solution, DisplaySettings{}));
  expect_ply_header(ply.header, expected_vertex_count, 3);
  ASSERT_EQ(ply.vertices.size(), expected_vertex_count);
  ASSERT_EQ(ply.faces.size(), 3u);

  std::vector<bool> seen(expected_vertex_count, false);
  for (std::size_t e = 0; e < 3; ++e)
    for (std::size_t k = 0; k < 3; ++k) {
      SCOPED_TRACE("element " + std::to_string(e) + " corner " + std::to_string(k));
      const int32_t index = ply.faces[e][k];
      ASSERT_GE(index, 0);
      ASSERT_LT(index, int32_t(expected_vertex_count));
      seen[index] = true;
      const PlyVertex& v = ply.vertices[index];
      const Vec3& corner = solution.mesh.elements[e].corners[k];
      const Color b = expected_vertex_radiosity(e, k);
      for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(v.position[c], static_cast<float>(corner[c]));
        EXPECT_EQ(v.radiosity[c], static_cast<float>(b[c]));
        EXPECT_EQ(v.color[c], srgb_byte(b[c]));  // exposure 0, clamp, sRGB
      }
    }
  for (std::size_t i = 0; i < expected_vertex_count; ++i) EXPECT_TRUE(seen[i]) << "vertex " << i << " unused";
  // The diagonal's ends are one vertex each within object 0; object 1 shares none with it.
  EXPECT_EQ(ply.faces[0][0], ply.faces[1][0]);
  EXPECT_EQ(ply.faces[0][2], ply.faces[1][1]);
  // Worked by hand: B2 = (4, 0.1, 0) → (255, round(255 · 0.3492), 0); B0 = (2, 0.5, 0.25) → sRGB
  // 0.7354 and 0.5371 of 255.
  EXPECT_EQ(ply.vertices[ply.faces[2][0]].color, (std::array<uint8_t, 3>{255, 89, 0}));
  EXPECT_EQ(ply.vertices[ply.faces[0][1]].color, (std::array<uint8_t, 3>{255, 188, 137}));
}

TEST(SolutionExport, PlyColorsFollowExposureAndTheOutOfRangeRule) {
  const RadiositySolveResult solution = three_element_solution();
  DisplaySettings display;
  display.exposure = -1;                     // × 1/2: the largest value, B2's red 4, becomes 2
  display.out_of_range = OutOfRange::scale;  // the whole set divided by that 2
  const PlyFile ply = parse_ply(ply_bytes(solution, display));
  ASSERT_EQ(ply.faces.size(), 3u);
  for (std::size_t e = 0; e < 3; ++e)
    for (std::size_t k = 0; k < 3; ++k) {
      const PlyVertex& v = ply.vertices[ply.faces[e][k]];
      const Color b = expected_vertex_radiosity(e, k);
      for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(v.color[c], srgb_byte(b[c] * 0.5 / 2)) << "element " << e << " corner " << k;
        EXPECT_EQ(v.radiosity[c], static_cast<float>(b[c]));  // the floats stay unexposed
      }
    }
  EXPECT_EQ(ply.vertices[ply.faces[2][0]].color, (std::array<uint8_t, 3>{255, srgb_byte(0.025), 0}));

  display.srgb = false;  // linear 8-bit
  const PlyFile linear = parse_ply(ply_bytes(solution, display));
  EXPECT_EQ(linear.vertices[linear.faces[0][1]].color,
            (std::array<uint8_t, 3>{128, 32, 16}));  // B0 / 4 = (0.5, 0.125, 0.0625) × 255, rounded
}

// ---- glTF ------------------------------------------------------------------------------------

std::vector<float> read_float_accessor(const nlohmann::json& gltf, const std::string& buffer,
                                       int accessor_index) {
  const nlohmann::json& accessor = gltf.at("accessors").at(accessor_index);
  EXPECT_EQ(accessor.at("componentType"), 5126);  // FLOAT
  EXPECT_EQ(accessor.at("type"), "VEC3");
  const nlohmann::json& view = gltf.at("bufferViews").at(accessor.at("bufferView").get<int>());
  EXPECT_EQ(view.at("target"), 34962);  // ARRAY_BUFFER
  const std::size_t count = accessor.at("count").get<std::size_t>();
  const std::size_t start =
      view.at("byteOffset").get<std::size_t>() + accessor.value("byteOffset", std::size_t(0));
  EXPECT_GE(view.at("byteLength").get<std::size_t>(), count * 12);
  std::vector<float> values;
  for (std::size_t i = 0; i < count * 3; ++i) values.push_back(read_float_le(buffer, start + 4 * i));
  return values;
}

TEST(SolutionExport, GltfCarriesPositionsClampedColorsRadiositiesAndIndices) {
  const RadiositySolveResult solution = three_element_solution();
  DisplaySettings display;
  display.exposure = -1;
  const nlohmann::json gltf = nlohmann::json::parse(gltf_text(solution, display));

  EXPECT_EQ(gltf.at("asset").at("version"), "2.0");
  EXPECT_EQ(gltf.at("asset").at("generator"), "Candela");
  EXPECT_EQ(gltf.at("scene"), 0);
  EXPECT_EQ(gltf.at("scenes").at(0).at("nodes"), nlohmann::json::array({0}));
  EXPECT_EQ(gltf.at("nodes").at(0).at("mesh"), 0);
  ASSERT_EQ(gltf.at("meshes").size(), 1u);
  ASSERT_EQ(gltf.at("meshes").at(0).at("primitives").size(), 1u);
  const nlohmann::json& primitive = gltf.at("meshes").at(0).at("primitives").at(0);
  EXPECT_EQ(primitive.at("mode"), 4);  // TRIANGLES
  const nlohmann::json& attributes = primitive.at("attributes");
  ASSERT_EQ(attributes.size(), 3u);

  // One buffer, embedded.
  ASSERT_EQ(gltf.at("buffers").size(), 1u);
  const std::string uri = gltf.at("buffers").at(0).at("uri").get<std::string>();
  const std::string prefix = "data:application/octet-stream;base64,";
  ASSERT_EQ(uri.rfind(prefix, 0), 0u);
  const std::string buffer = base64_decode(uri.substr(prefix.size()));
  EXPECT_EQ(gltf.at("buffers").at(0).at("byteLength"), buffer.size());
  for (const nlohmann::json& view : gltf.at("bufferViews")) {
    EXPECT_EQ(view.at("buffer"), 0);
    EXPECT_EQ(view.at("byteOffset").get<std::size_t>() % 4, 0u);
    EXPECT_LE(view.at("byteOffset").get<std::size_t>() + view.at("byteLength").get<std::size_t>(),
              buffer.size());
  }

  const int position_accessor = attributes.at("POSITION").get<int>();
  const std::vector<float> positions = read_float_accessor(gltf, buffer, position_accessor);
  const std::vector<float> colors = read_float_accessor(gltf, buffer, attributes.at("COLOR_0").get<int>());
  const std::vector<float> radiosities =
      read_float_accessor(gltf, buffer, attributes.at("_RADIOSITY").get<int>());
  ASSERT_EQ(positions.size(), expected_vertex_count * 3);
  ASSERT_EQ(colors.size(), expected_vertex_count * 3);
  ASSERT_EQ(radiosities.size(), expected_vertex_count * 3);
  EXPECT_EQ(gltf.at("accessors").at(position_accessor).at("min"), nlohmann::json::array({0.0, 0.0, 0.0}));
  EXPECT_EQ(gltf.at("accessors").at(position_accessor).at("max"), nlohmann::json::array({2.0, 1.0, 1.0}));

  const nlohmann::json& index_accessor = gltf.at("accessors").at(primitive.at("indices").get<int>());
  EXPECT_EQ(index_accessor.at("componentType"), 5125);  // UNSIGNED_INT
  EXPECT_EQ(index_accessor.at("type"), "SCALAR");
  ASSERT_EQ(index_accessor.at("count"), 9);
  const nlohmann::json& index_view = gltf.at("bufferViews").at(index_accessor.at("bufferView").get<int>());
  EXPECT_EQ(index_view.at("target"), 34963);  // ELEMENT_ARRAY_BUFFER
  const std::size_t index_start =
      index_view.at("byteOffset").get<std::size_t>() + index_accessor.value("byteOffset", std::size_t(0));

  for (std::size_t e = 0; e < 3; ++e)
    for (std::size_t k = 0; k < 3; ++k) {
      SCOPED_TRACE("element " + std::to_string(e) + " corner " + std::to_string(k));
      const uint32_t vertex = read_u32_le(buffer, index_start + 4 * (3 * e + k));
      ASSERT_LT(vertex, expected_vertex_count);
      const Vec3& corner = solution.mesh.elements[e].corners[k];
      const Color b = expected_vertex_radiosity(e, k);
      for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(positions[3 * vertex + c], static_cast<float>(corner[c]));
        EXPECT_EQ(radiosities[3 * vertex + c], static_cast<float>(b[c]));  // neither exposed nor clamped
        EXPECT_EQ(colors[3 * vertex + c], static_cast<float>(std::min(b[c] * 0.5, 1.0)));
      }
    }
  // B2 = (4, 0.1, 0) at exposure −1: (2, 0.05, 0) clamped to (1, 0.05, 0); _RADIOSITY keeps 4.
  const uint32_t b2_vertex = read_u32_le(buffer, index_start + 4 * 6);
  EXPECT_EQ(colors[3 * b2_vertex], 1.0f);
  EXPECT_EQ(colors[3 * b2_vertex + 1], 0.05f);
  EXPECT_EQ(radiosities[3 * b2_vertex], 4.0f);
}

// ---- Empty solution --------------------------------------------------------------------------

TEST(SolutionExport, EmptySolutionWritesValidEmptyFiles) {
  const RadiositySolveResult empty;
  EXPECT_EQ(csv_text(empty), csv_header + "\n");

  const std::string ply = ply_bytes(empty, DisplaySettings{});
  const PlyFile parsed = parse_ply(ply);
  expect_ply_header(parsed.header, 0, 0);
  EXPECT_TRUE(parsed.vertices.empty());
  EXPECT_EQ(ply.substr(ply.size() - 11), "end_header\n");  // no body

  // glTF forbids empty buffers, accessors and meshes: a scene with one empty node remains.
  const nlohmann::json gltf = nlohmann::json::parse(gltf_text(empty, DisplaySettings{}));
  EXPECT_EQ(gltf.at("asset").at("version"), "2.0");
  EXPECT_EQ(gltf.at("scenes").at(0).at("nodes"), nlohmann::json::array({0}));
  ASSERT_EQ(gltf.at("nodes").size(), 1u);
  EXPECT_FALSE(gltf.at("nodes").at(0).contains("mesh"));
  for (const char* absent : {"buffers", "bufferViews", "accessors", "meshes"})
    EXPECT_FALSE(gltf.contains(absent)) << absent;
}

TEST(SolutionExport, MismatchedSolutionArraysAreRejected) {
  RadiositySolveResult solution = three_element_solution();
  solution.element_radiosity.pop_back();
  EXPECT_THROW(csv_text(solution), std::invalid_argument);
  solution = three_element_solution();
  solution.mesh.patch_of_element.clear();
  EXPECT_THROW(ply_bytes(solution, DisplaySettings{}), std::invalid_argument);
  EXPECT_THROW(gltf_text(solution, DisplaySettings{}), std::invalid_argument);
}

// ---- export_solution -------------------------------------------------------------------------

TEST(SolutionExport, FormatForPathIsChosenByCaseInsensitiveExtension) {
  SolutionFormat format = SolutionFormat::gltf;
  ASSERT_TRUE(solution_format_for_path("out/solution.csv", format));
  EXPECT_EQ(format, SolutionFormat::csv);
  ASSERT_TRUE(solution_format_for_path("solution.PLY", format));
  EXPECT_EQ(format, SolutionFormat::ply);
  ASSERT_TRUE(solution_format_for_path("a.b/solution.GlTf", format));
  EXPECT_EQ(format, SolutionFormat::gltf);
  for (const char* other :
       {"solution.glb", "solution.obj", "solution", "csv", "dir.csv/solution", "solution.csv.gz"})
    EXPECT_FALSE(solution_format_for_path(other, format)) << other;
}

TEST(SolutionExport, ExportWritesEachFormatByItsExtension) {
  const candela::testing::ScratchDirectory scratch("candela-solution-export");
  const RadiositySolveResult solution = three_element_solution();
  DisplaySettings display;
  display.exposure = 0.5;
  const std::array<std::pair<std::string, std::string>, 6> cases = {{
      {"solution.csv", csv_text(solution)},
      {"solution.ply", ply_bytes(solution, display)},
      {"solution.gltf", gltf_text(solution, display)},
      {"UPPER.CSV", csv_text(solution)},
      {"UPPER.PLY", ply_bytes(solution, display)},
      {"Mixed.glTF", gltf_text(solution, display)},
  }};
  for (const auto& [name, expected] : cases) {
    const std::filesystem::path path = scratch.path() / name;
    export_solution(solution, path.string(), display);
    EXPECT_EQ(read_file(path), expected) << name;
  }
  // Written through a temporary file renamed into place: nothing else is left behind.
  std::size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(scratch.path())) {
    ++files;
    EXPECT_NE(entry.path().filename().string().rfind(".tmp-", 0), 0u) << entry.path();
  }
  EXPECT_EQ(files, cases.size());
}

TEST(SolutionExport, ExportReplacesAnExistingFile) {
  const candela::testing::ScratchDirectory scratch("candela-solution-export");
  const std::filesystem::path path = scratch.path() / "solution.csv";
  std::ofstream(path) << "stale contents that are longer than the header of an empty solution's CSV\n";
  export_solution(RadiositySolveResult{}, path.string(), DisplaySettings{});
  EXPECT_EQ(read_file(path), csv_header + "\n");
}

TEST(SolutionExport, EmptySolutionExportsToEveryFormat) {
  const candela::testing::ScratchDirectory scratch("candela-solution-export");
  const RadiositySolveResult empty;
  for (const char* name : {"empty.csv", "empty.ply", "empty.gltf"}) {
    const std::filesystem::path path = scratch.path() / name;
    export_solution(empty, path.string(), DisplaySettings{});
    EXPECT_TRUE(std::filesystem::is_regular_file(path)) << name;
    EXPECT_GT(std::filesystem::file_size(path), 0u) << name;
  }
}

TEST(SolutionExport, UnknownExtensionThrowsNamingPathAndFormatsAndWritesNothing) {
  const candela::testing::ScratchDirectory scratch("candela-solution-export");
  for (const char* name : {"solution.obj", "solution"}) {
    const std::string path = (scratch.path() / name).string();
    try {
      export_solution(three_element_solution(), path, DisplaySettings{});
      ADD_FAILURE() << "no exception for " << path;
    } catch (const std::runtime_error& error) {
      const std::string message = error.what();
      EXPECT_NE(message.find(path), std::string::npos) << message;
      for (const char* extension : {".csv", ".ply", ".gltf"})
        EXPECT_NE(message.find(extension), std::string::npos) << message;
    }
  }
  EXPECT_TRUE(std::filesystem::is_empty(scratch.path()));
}

TEST(SolutionExport, UnwritablePathThrowsNamingIt) {
  const candela::testing::ScratchDirectory scratch("candela-solution-export");
  const std::filesystem::path missing_directory = scratch.path() / "does-not-exist";
  for (const char* name : {"solution.csv", "solution.ply", "solution.gltf"}) {
    const std::string path = (missing_directory / name).string();
    try {
      export_solution(three_element_solution(), path, DisplaySettings{});
      ADD_FAILURE() << "no exception for " << path;
    } catch (const std::runtime_error& error) {
      EXPECT_NE(std::string(error.what()).find(path), std::string::npos) << error.what();
    }
  }
  EXPECT_FALSE(std::filesystem::exists(missing_directory));
  EXPECT_TRUE(std::filesystem::is_empty(scratch.path()));
}

}  // namespace
}  // namespace candela
