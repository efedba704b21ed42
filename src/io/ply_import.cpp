#include "io/ply_import.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <string_view>
#include <system_error>
#include <vector>

#include "geometry/face_triangulation.h"

namespace candela {

namespace {

enum class Scalar { i8, u8, i16, u16, i32, u32, f32, f64 };
enum class Format { ascii, little_endian, big_endian };

std::optional<Scalar> scalar_named(const std::string& name) {
  if (name == "char" || name == "int8") return Scalar::i8;
  if (name == "uchar" || name == "uint8") return Scalar::u8;
  if (name == "short" || name == "int16") return Scalar::i16;
  if (name == "ushort" || name == "uint16") return Scalar::u16;
  if (name == "int" || name == "int32") return Scalar::i32;
  if (name == "uint" || name == "uint32") return Scalar::u32;
  if (name == "float" || name == "float32") return Scalar::f32;
  if (name == "double" || name == "float64") return Scalar::f64;
  return std::nullopt;
}

std::size_t size_of(Scalar type) {
  switch (type) {
    case Scalar::i8:
    case Scalar::u8:
      return 1;
    case Scalar::i16:
    case Scalar::u16:
      return 2;
    case Scalar::i32:
    case Scalar::u32:
    case Scalar::f32:
      return 4;
    case Scalar::f64:
      return 8;
  }
  return 1;
}

bool is_integer(Scalar type) {
  return type != Scalar::f32 && type != Scalar::f64;
}

struct Property {
  std::string name;
  Scalar type = Scalar::f32;  // the item type for a list
  bool list = false;
  Scalar count_type = Scalar::u8;
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
};

std::vector<std::string> words_of(const std::string& line) {
  std::istringstream in(line);
  return {std::istream_iterator<std::string>(in), std::istream_iterator<std::string>()};
}

class PlyReader {
 public:
  PlyReader(const std::string& path, const SourceLocation& referenced_from, std::string data)
      : path_(path), referenced_from_(referenced_from), data_(std::move(data)) {}

  ObjImport read() {
    read_header();
    check_counts();
    for (const Element& element : elements_) {
      if (element.name == "vertex") {
        read_vertices(element);
      } else if (element.name == "face") {
        read_faces(element);
      } else {
        skip_element(element);
      }
    }
    if (!seen_vertex_) fail_at_header("there is no vertex element");
    if (triangles_.empty()) fail_plain("has no triangles");
    return build();
  }

 private:
  // --- errors -------------------------------------------------------------------------------

  [[noreturn]] void fail_plain(const std::string& message) const {
    throw InputError(referenced_from_, fmt::format("PLY file '{}' {}", path_, message));
  }
  [[noreturn]] void fail_line(int line, const std::string& message) const {
    throw InputError(referenced_from_, fmt::format("PLY file '{}' line {}: {}", path_, line, message));
  }
  [[noreturn]] void fail_at_header(const std::string& message) const { fail_line(line_, message); }
  // In the body: the line of the last token (ASCII) or the byte offset (binary).
  [[noreturn]] void fail_here(const std::string& message) const {
    if (format_ == Format::ascii) fail_line(token_line_, message);
    throw InputError(referenced_from_, fmt::format("PLY file '{}' byte {}: {}", path_, pos_, message));
  }

  // --- header -------------------------------------------------------------------------------

  // The next header line (without its end of line), or nullopt at the end of the data.
  std::optional<std::string> header_line() {
    if (pos_ >= data_.size()) return std::nullopt;
    std::size_t end = data_.find('\n', pos_);
    if (end == std::string::npos) end = data_.size();
    std::string line = data_.substr(pos_, end - pos_);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    pos_ = std::min(end + 1, data_.size());
    ++line_;
    return line;
  }

  std::uint64_t parse_count(const std::string& text) const {
    std::uint64_t value = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size())
      fail_at_header("element count '" + text + "' is not a non-negative integer");
    return value;
  }

  Scalar parse_type(const std::string& text) const {
    const auto type = scalar_named(text);
    if (!type) fail_at_header("unknown property type '" + text + "'");
    return *type;
  }

  void read_header() {
    const auto first = header_line();
    if (!first || *first != "ply") fail_line(1, "does not start with 'ply'");
    bool have_format = false;
    while (true) {
      const auto line = header_line();
      if (!line) fail_at_header("the header has no end_header line");
      const auto words = words_of(*line);
      if (words.empty()) continue;
      const std::string& keyword = words[0];
      if (keyword == "end_header") break;
      if (keyword == "comment" || keyword == "obj_info") continue;
      if (keyword == "format") {
        if (words.size() != 3)
          fail_at_header("expected 'format <ascii|binary_little_endian|binary_big_endian> 1.0'");
        if (words[1] == "ascii")
          format_ = Format::ascii;
        else if (words[1] == "binary_little_endian")
          format_ = Format::little_endian;
        else if (words[1] == "binary_big_endian")
          format_ = Format::big_endian;
        else
          fail_at_header("unknown format '" + words[1] + "'");
        if (words[2] != "1.0" && words[2] != "1")
          fail_at_header("unsupported version '" + words[2] + "' (expected 1.0)");
        have_format = true;
      } else if (keyword == "element") {
        if (words.size() != 3) fail_at_header("expected 'element <name> <count>'");
        elements_.push_back({words[1], parse_count(words[2]), {}});
      } else if (keyword == "property") {
        if (elements_.empty()) fail_at_header("a property before any element");
        Property property;
        if (words.size() == 5 && words[1] == "list") {
          property.list = true;
          property.count_type = parse_type(words[2]);
          if (!is_integer(property.count_type)) fail_at_header("a list count type must be an integer type");
          property.type = parse_type(words[3]);
          property.name = words[4];
        } else if (words.size() == 3) {
          property.type = parse_type(words[1]);
          property.name = words[2];
        } else {
          fail_at_header("expected 'property <type> <name>' or 'property list <count type> <type> <name>'");
        }
        elements_.back().properties.push_back(property);
      } else {
        fail_at_header("unknown header keyword '" + keyword + "'");
      }
    }
    if (!have_format) fail_at_header("the header has no format line");
    ++line_;  // the body starts on the line after end_header
    token_line_ = line_;
  }

  // Refuses counts the rest of the file cannot hold, before anything is allocated: in binary
  // each element takes at least its scalars and list counts, in ASCII at least one character
  // per property.
  void check_counts() const {
    const std::uint64_t body = data_.size() - pos_;
    std::uint64_t needed = 0;
    for (const Element& element : elements_) {
      std::uint64_t minimum = 0;
      for (const Property& property : element.properties)
        minimum +=
            format_ == Format::ascii ? 1 : size_of(property.list ? property.count_type : property.type);
      if (minimum == 0 || element.count == 0) continue;
      if (element.count > body / minimum || needed + element.count * minimum > body)
        fail_plain(fmt::format("announces {} '{}' element(s), more than its {} bytes of data can hold",
                               element.count, element.name, body));
      needed += element.count * minimum;
    }
  }

  // --- body values --------------------------------------------------------------------------

  std::string_view next_token() {
    while (pos_ < data_.size() && std::isspace(static_cast<unsigned char>(data_[pos_]))) {
      if (data_[pos_] == '\n') ++line_;
      ++pos_;
    }
    token_line_ = line_;
    if (pos_ >= data_.size()) fail_here("unexpected end of file");
    const std::size_t start = pos_;
    while (pos_ < data_.size() && !std::isspace(static_cast<unsigned char>(data_[pos_]))) ++pos_;
    return std::string_view(data_).substr(start, pos_ - start);
  }

  double ascii_value(Scalar type) {
    const std::string_view token = next_token();
    const char* begin = token.data();
    const char* end = begin + token.size();
    if (is_integer(type)) {
      long long value = 0;
      const auto [stop, ec] = std::from_chars(begin, end, value);
      if (ec != std::errc() || stop != end) fail_here("'" + std::string(token) + "' is not an integer");
      return static_cast<double>(value);
    }
    double value = 0;
    if (*begin == '+') ++begin;  // from_chars takes no leading '+'
    const auto [stop, ec] = std::from_chars(begin, end, value);
    if (stop != end || (ec != std::errc() && ec != std::errc::result_out_of_range))
      fail_here("'" + std::string(token) + "' is not a number");
    if (ec == std::errc::result_out_of_range) return std::numeric_limits<double>::infinity();
    return value;
  }

  void need_bytes(std::size_t count) const {
    if (count > data_.size() - pos_)
      fail_here(fmt::format("truncated: {} more byte(s) needed, {} left", count, data_.size() - pos_));
  }

  double binary_value(Scalar type) {
    const std::size_t size = size_of(type);
    need_bytes(size);
    std::array<unsigned char, 8> bytes{};
    std::memcpy(bytes.data(), data_.data() + pos_, size);
    pos_ += size;
    if (format_ == Format::big_endian)
      std::reverse(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(size));
    switch (type) {
      case Scalar::i8: {
        std::int8_t v;
        std::memcpy(&v, bytes.data(), 1);
        return v;
      }
      case Scalar::u8:
        return bytes[0];
      case Scalar::i16: {
        std::int16_t v;
        std::memcpy(&v, bytes.data(), 2);
        return v;
      }
      case Scalar::u16: {
        std::uint16_t v;
        std::memcpy(&v, bytes.data(), 2);
        return v;
      }
      case Scalar::i32: {
        std::int32_t v;
        std::memcpy(&v, bytes.data(), 4);
        return v;
      }
      case Scalar::u32: {
        std::uint32_t v;
        std::memcpy(&v, bytes.data(), 4);
        return v;
      }
      case Scalar::f32: {
        float v;
        std::memcpy(&v, bytes.data(), 4);
        return static_cast<double>(v);
      }
      case Scalar::f64: {
        double v;
        std::memcpy(&v, bytes.data(), 8);
        return v;
      }
    }
    return 0;
  }

  double value(Scalar type) { return format_ == Format::ascii ? ascii_value(type) : binary_value(type); }

  // A list's length, checked against what is left of the file.
  std::size_t list_count(const Property& property) {
    const double count = value(property.count_type);
    if (count < 0) fail_here(fmt::format("negative list length {} for '{}'", count, property.name));
    const double item = format_ == Format::ascii ? 1.0 : static_cast<double>(size_of(property.type));
    if (count * item > static_cast<double>(data_.size() - pos_))
      fail_here(fmt::format("list '{}' of {} item(s) runs past the end of the file", property.name, count));
    return static_cast<std::size_t>(count);
  }

  void skip_property(const Property& property) {
    if (!property.list) {
      (void)value(property.type);
      return;
    }
    const std::size_t count = list_count(property);
    if (format_ == Format::ascii) {
      for (std::size_t i = 0; i < count; ++i) (void)ascii_value(property.type);
    } else {
      pos_ += count * size_of(property.type);  // list_count checked the bytes are there
    }
  }

  void skip_element(const Element& element) {
    if (element.properties.empty()) return;
    for (std::uint64_t i = 0; i < element.count; ++i)
      for (const Property& property : element.properties) skip_property(property);
  }

  // --- vertices and faces -------------------------------------------------------------------

  void read_vertices(const Element& element) {
    if (seen_vertex_) fail_plain("has more than one vertex element");
    seen_vertex_ = true;
    if (element.count > std::numeric_limits<std::uint32_t>::max())
      fail_plain(fmt::format("has {} vertices, more than 2^32 - 1", element.count));
    // Slot of each property: 0-2 position, 3-5 normal, 6-7 uv, -1 ignored.
    std::vector<int> slot(element.properties.size(), -1);
    std::array<bool, 8> present{};
    const std::array<std::vector<std::string>, 8> names = {{{"x"},
                                                            {"y"},
                                                            {"z"},
                                                            {"nx"},
                                                            {"ny"},
                                                            {"nz"},
                                                            {"u", "s", "texture_u", "texture_s"},
                                                            {"v", "t", "texture_v", "texture_t"}}};
    for (std::size_t p = 0; p < element.properties.size(); ++p) {
      const Property& property = element.properties[p];
      for (int s = 0; s < 8; ++s) {
        bool match = false;
        for (const std::string& name : names[static_cast<std::size_t>(s)])
          match = match || property.name == name;
        if (!match || present[static_cast<std::size_t>(s)]) continue;
        if (property.list) fail_plain("vertex property '" + property.name + "' is a list");
        slot[p] = s;
        present[static_cast<std::size_t>(s)] = true;
      }
    }
    if (!present[0] || !present[1] || !present[2]) fail_plain("vertex element lacks one of x, y, z");
    const bool normals = present[3] && present[4] && present[5];
    const bool uvs = present[6] && present[7];
    const auto count = static_cast<std::size_t>(element.count);
    positions_.reserve(count);
    if (normals) normals_.reserve(count);
    if (uvs) uvs_.reserve(count);
    for (std::size_t i = 0; i < count; ++i) {
      std::array<double, 8> values{};
      int first_line = 0;
      const std::size_t first_byte = pos_;
      for (std::size_t p = 0; p < element.properties.size(); ++p) {
        if (slot[p] < 0) {
          skip_property(element.properties[p]);
        } else {
          values[static_cast<std::size_t>(slot[p])] = value(element.properties[p].type);
        }
        if (p == 0) first_line = token_line_;
      }
      const auto check = [&](int from, int to, const char* what) {
        for (int k = from; k < to; ++k) {
          if (std::isfinite(values[static_cast<std::size_t>(k)])) continue;
          if (format_ == Format::ascii)
            fail_line(first_line, fmt::format("vertex {} has a non-finite {}", i, what));
          throw InputError(referenced_from_,
                           fmt::format("PLY file '{}' byte {}: vertex {} has a non-finite {}", path_,
                                       first_byte, i, what));
        }
      };
      check(0, 3, "coordinate");
      positions_.push_back({values[0], values[1], values[2]});
      if (normals) {
        check(3, 6, "normal");
        normals_.push_back({values[3], values[4], values[5]});
      }
      if (uvs) {
        check(6, 8, "texture coordinate");
        uvs_.push_back({values[6], values[7]});
      }
    }
  }

  void read_faces(const Element& element) {
    if (!seen_vertex_) fail_plain("has its face element before its vertex element");
    std::ptrdiff_t indices = -1;
    for (std::size_t p = 0; p < element.properties.size(); ++p) {
      const Property& property = element.properties[p];
      if (property.list && (property.name == "vertex_indices" || property.name == "vertex_index")) {
        indices = static_cast<std::ptrdiff_t>(p);
        break;
      }
    }
    if (indices < 0) fail_plain("face element has no list property vertex_indices (or vertex_index)");
    triangles_.reserve(static_cast<std::size_t>(element.count));
    std::vector<std::uint32_t> polygon;
    std::vector<Vec3> face_positions;
    std::vector<std::array<std::uint32_t, 3>> face_triangles;
    for (std::uint64_t f = 0; f < element.count; ++f) {
      for (std::size_t p = 0; p < element.properties.size(); ++p) {
        const Property& property = element.properties[p];
        if (static_cast<std::ptrdiff_t>(p) != indices) {
          skip_property(property);
          continue;
        }
        const std::size_t corners = list_count(property);
        polygon.clear();
        for (std::size_t c = 0; c < corners; ++c) {
          const double index = value(property.type);
          if (!(index >= 0 && index < static_cast<double>(positions_.size())) || index != std::floor(index))
            fail_here(fmt::format("face {} refers to vertex {}, but there are {} vertices (counted from 0)",
                                  f, index, positions_.size()));
          polygon.push_back(static_cast<std::uint32_t>(index));
        }
        if (polygon.size() < 3) {
          ++short_faces_;
          continue;
        }
        if (polygon.size() <= 4) {
          for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
            triangles_.push_back({polygon[0], polygon[k], polygon[k + 1]});
          continue;
        }
        // A large face is halved or ear-clipped as an OBJ face is, not fanned into
        // slivers that all overlap at its first corner.
        face_positions.clear();
        for (const std::uint32_t index : polygon) face_positions.push_back(positions_[index]);
        if (const std::string problem = triangulate_face(face_positions, face_triangles); !problem.empty())
          fail_here(fmt::format("face {}: {}", f, problem));
        for (const auto& [a, b, c] : face_triangles)
          triangles_.push_back({polygon[a], polygon[b], polygon[c]});
      }
    }
  }

  ObjImport build() {
    ObjImport result;
    result.mesh = std::make_shared<TriangleMesh>();
    TriangleMesh& mesh = *result.mesh;
    mesh.positions = std::move(positions_);
    mesh.triangles = std::move(triangles_);
    result.triangle_material.assign(mesh.triangles.size(), -1);
    if (short_faces_ > 0)
      result.warnings.push_back(
          fmt::format("{}: skipped {} face(s) with fewer than 3 vertices", path_, short_faces_));
    if (!normals_.empty()) {
      std::size_t zero = 0;
      mesh.corner_normals.reserve(mesh.triangles.size());
      for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const Vec3 cross = mesh.face_cross(t);
        const double area = length(cross);
        const Vec3 face = area > 0 && std::isfinite(area) ? cross / area : Vec3{0, 0, 0};
        std::array<Vec3, 3> corners;
        for (std::size_t c = 0; c < 3; ++c) {
          const Vec3 n = normals_[mesh.triangles[t][c]];
          const double n_length = length(n);
          if (n_length > 0 && std::isfinite(n_length)) {
            corners[c] = n / n_length;
          } else {
            corners[c] = face;
            ++zero;
          }
        }
        mesh.corner_normals.push_back(corners);
      }
      if (zero > 0)
        result.warnings.push_back(fmt::format(
            "{}: {} corner(s) with a zero-length normal use the face normal instead", path_, zero));
    }
    if (!uvs_.empty()) {
      mesh.corner_uvs.reserve(mesh.triangles.size());
      for (const auto& triangle : mesh.triangles)
        mesh.corner_uvs.push_back({uvs_[triangle[0]], uvs_[triangle[1]], uvs_[triangle[2]]});
    }
    return result;
  }

  const std::string& path_;
  const SourceLocation& referenced_from_;
  std::string data_;
  std::size_t pos_ = 0;
  int line_ = 0;        // header lines read so far, then the current body line (ASCII)
  int token_line_ = 0;  // the line of the last ASCII token
  Format format_ = Format::ascii;
  std::vector<Element> elements_;
  bool seen_vertex_ = false;
  std::vector<Vec3> positions_;
  std::vector<Vec3> normals_;
  std::vector<Vec2> uvs_;
  std::vector<std::array<std::uint32_t, 3>> triangles_;
  std::size_t short_faces_ = 0;
};

}  // namespace

ObjImport import_ply(const std::string& path, const SourceLocation& referenced_from) {
  require_mesh_file(path, "PLY", referenced_from);
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (!in) throw InputError(referenced_from, "cannot read PLY file '" + path + "'");
  PlyReader reader(path, referenced_from, bytes.str());
  return reader.read();
}

}  // namespace candela
