#include "io/gltf_import.h"

#include <fmt/format.h>
#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

// tinygltf's implementation lives here. Images are never decoded (the project's stb_image is
// compiled in texture_image.cpp, and glTF materials are not imported): no stb, no external
// image files, and a loader callback that keeps nothing.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include "math/constants.h"
#include "math/transform.h"
#include "util/input_file.h"

namespace candela {

namespace {

bool ignore_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*,
                  int, void*) {
  return true;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(start, end - start);
    while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.pop_back();
    if (!line.empty()) lines.push_back(line);
    start = end + 1;
  }
  return lines;
}

// A checked window onto an accessor's elements.
struct AccessorData {
  const unsigned char* data = nullptr;
  std::size_t stride = 0;
  std::size_t count = 0;
  int component_type = 0;
};

// The JSON of a .glb: its first chunk (tinygltf has checked the header and the chunk sizes).
std::string_view glb_json_chunk(const std::string& bytes) {
  const auto u32_at = [&](std::size_t at) {
    std::uint32_t value = 0;
    for (std::size_t k = 0; k < 4; ++k)
      value |= std::uint32_t(static_cast<unsigned char>(bytes[at + k])) << (8 * k);
    return value;
  };
  if (bytes.size() < 20) return {};
  const std::size_t length = u32_at(12);
  return length <= bytes.size() - 20 ? std::string_view(bytes).substr(20, length) : std::string_view();
}

// Every number of a scene file, an OBJ vertex and a glTF node's transform or position is limited
// to kMaxSceneMagnitude (math/constants.h): beyond it squared distances lose all precision.
constexpr double kMaxMagnitude = kMaxSceneMagnitude;
static_assert(kMaxMagnitude == 1e16, "the messages below name it");

class GltfReader {
 public:
  GltfReader(const std::string& path, const SourceLocation& referenced_from, tinygltf::Model model,
             const nlohmann::json& json)
      : path_(path), referenced_from_(referenced_from), model_(std::move(model)), json_(json) {}

  ObjImport read() {
    check_optional_sizes();
    place_scene();
    if (parts_.empty() || triangle_count_ == 0) fail("has no triangles (mode TRIANGLES)");
    return merge();
  }

  std::vector<std::string> warnings;

 private:
  [[noreturn]] void fail(const std::string& message) const {
    throw InputError(referenced_from_, fmt::format("glTF file '{}' {}", path_, message));
  }

  // tinygltf reads an optional size that is not a non-negative integer (-4, 1.5, 1e30, "8") as its
  // default 0 without a word: an accessor at byteOffset -4 read its buffer from the start.
  // Such a value is refused by its JSON path. (Required sizes, byteLength and count, tinygltf
  // refuses itself.)
  void check_optional_sizes() const {
    static constexpr std::array<std::pair<const char*, const char*>, 3> kSizes = {
        {{"accessors", "byteOffset"}, {"bufferViews", "byteOffset"}, {"bufferViews", "byteStride"}}};
    for (const auto& [array, key] : kSizes) {
      const auto objects = json_.find(array);
      if (objects == json_.end() || !objects->is_array()) continue;
      for (std::size_t i = 0; i < objects->size(); ++i) {
        const nlohmann::json& object = (*objects)[i];
        if (!object.is_object()) continue;
        const auto value = object.find(key);
        if (value == object.end() || value->is_number_unsigned()) continue;
        std::string found = value->dump();
        if (found.size() > 40) found = found.substr(0, 40) + "...";
        fail(fmt::format("{}[{}].{}: must be a non-negative integer (found {})", array, i, key, found));
      }
    }
  }

  // --- node tree ----------------------------------------------------------------------------

  // The numbers of a node's matrix, translation, rotation and scale must be finite and at most
  // kMaxMagnitude: larger ones overflowed when composed and were then called a singular matrix.
  void check_node_numbers(const tinygltf::Node& node, int index) const {
    const std::array<std::pair<const char*, const std::vector<double>*>, 4> fields = {
        {{"matrix", &node.matrix},
         {"translation", &node.translation},
         {"rotation", &node.rotation},
         {"scale", &node.scale}}};
    for (const auto& [name, values] : fields)
      for (std::size_t k = 0; k < values->size(); ++k) {
        const double value = (*values)[k];
        if (!std::isfinite(value)) fail(fmt::format("nodes[{}].{}[{}]: must be finite", index, name, k));
        if (std::fabs(value) > kMaxMagnitude)
          fail(fmt::format("nodes[{}].{}[{}]: magnitude above 1e16 is not supported (found {})", index, name,
                           k, value));
      }
    const auto& r = node.rotation;
    if (r.size() == 4 && r[0] == 0 && r[1] == 0 && r[2] == 0 && r[3] == 0)
      fail(fmt::format("nodes[{}].rotation: the zero quaternion [0, 0, 0, 0] is not a rotation", index));
  }

  static Eigen::Matrix4d local_matrix(const tinygltf::Node& node) {
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    if (node.matrix.size() == 16) {
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) m(r, c) = node.matrix[static_cast<std::size_t>(c * 4 + r)];
      return m;
    }
    Eigen::Matrix4d t = Eigen::Matrix4d::Identity();
    if (node.translation.size() == 3)
      for (int k = 0; k < 3; ++k) t(k, 3) = node.translation[static_cast<std::size_t>(k)];
    Eigen::Matrix4d r = Eigen::Matrix4d::Identity();
    if (node.rotation.size() == 4) {
      Eigen::Quaterniond q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
      // Components so small that their squares underflow (1e-200) still name a rotation: scale
      // them up first (check_node_numbers refused the zero quaternion; 1e16 cannot overflow).
      if (!(q.coeffs().squaredNorm() >= std::numeric_limits<double>::min()))
        q.coeffs() /= q.coeffs().cwiseAbs().maxCoeff();
      q.normalize();
      r.topLeftCorner<3, 3>() = q.toRotationMatrix();
    }
    Eigen::Matrix4d s = Eigen::Matrix4d::Identity();
    if (node.scale.size() == 3)
      for (int k = 0; k < 3; ++k) s(k, k) = node.scale[static_cast<std::size_t>(k)];
    return t * r * s;
  }

  void place_scene() {
    if (model_.scenes.empty()) {
      for (std::size_t m = 0; m < model_.meshes.size(); ++m)
        add_mesh(static_cast<int>(m), Eigen::Matrix4d::Identity(), -1);
      return;
    }
    const int scene = model_.defaultScene >= 0 ? model_.defaultScene : 0;
    if (scene >= static_cast<int>(model_.scenes.size()))
      fail(fmt::format("names scene {}, which does not exist", scene));
    // Depth-first over an explicit stack (a chain of nodes as deep as the file is long must not
    // overflow the call stack); a node reached twice (a cycle, or two parents) is refused.
    std::vector<bool> visited(model_.nodes.size(), false);
    std::vector<std::pair<int, Eigen::Matrix4d>> stack;
    for (const int root : model_.scenes[static_cast<std::size_t>(scene)].nodes)
      stack.emplace_back(root, Eigen::Matrix4d::Identity());
    while (!stack.empty()) {
      const auto [index, parent] = stack.back();
      stack.pop_back();
      if (index < 0 || index >= static_cast<int>(model_.nodes.size()))
        fail(fmt::format("refers to node {}, which does not exist", index));
      if (visited[static_cast<std::size_t>(index)])
        fail(fmt::format("reaches node {} twice (the nodes are not a tree)", index));
      visited[static_cast<std::size_t>(index)] = true;
      const tinygltf::Node& node = model_.nodes[static_cast<std::size_t>(index)];
      check_node_numbers(node, index);
      const Eigen::Matrix4d world = parent * local_matrix(node);
      // Each node's numbers are at most 1e16, but a chain of them multiplies: name the node
      // where the composed transform leaves the supported range.
      if (!world.allFinite())
        fail(
            fmt::format("nodes[{}]: the transform composed from the scene's root down to this node overflows "
                        "(is not finite)",
                        index));
      if (const double largest = world.cwiseAbs().maxCoeff(); largest > kMaxMagnitude)
        fail(fmt::format(
            "nodes[{}]: the transform composed from the scene's root down to this node has an entry "
            "of magnitude {}, above the supported 1e16",
            index, largest));
      if (node.mesh >= 0) add_mesh(node.mesh, world, index);
      for (const int child : node.children) stack.emplace_back(child, world);
    }
  }

  // --- accessors ----------------------------------------------------------------------------

  AccessorData accessor(int index, int type, const std::vector<int>& component_types,
                        const std::string& what) const {
    if (index < 0 || index >= static_cast<int>(model_.accessors.size()))
      fail(fmt::format("{}: accessor {} does not exist", what, index));
    const tinygltf::Accessor& a = model_.accessors[static_cast<std::size_t>(index)];
    if (a.sparse.isSparse) fail(fmt::format("{}: accessor {} is sparse (not supported)", what, index));
    if (a.type != type) fail(fmt::format("{}: accessor {} has the wrong type", what, index));
    if (std::find(component_types.begin(), component_types.end(), a.componentType) == component_types.end())
      fail(fmt::format("{}: accessor {} has an unsupported component type {}", what, index, a.componentType));
    if (a.bufferView < 0 || a.bufferView >= static_cast<int>(model_.bufferViews.size()))
      fail(fmt::format("{}: accessor {} has no valid bufferView", what, index));
    const tinygltf::BufferView& view = model_.bufferViews[static_cast<std::size_t>(a.bufferView)];
    if (view.buffer < 0 || view.buffer >= static_cast<int>(model_.buffers.size()))
      fail(fmt::format("{}: bufferView {} has no valid buffer", what, a.bufferView));
    const std::vector<unsigned char>& buffer = model_.buffers[static_cast<std::size_t>(view.buffer)].data;
    const int component_size = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType));
    const int components = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
    if (component_size <= 0 || components <= 0)
      fail(fmt::format("{}: accessor {} is malformed", what, index));
    const std::size_t element =
        static_cast<std::size_t>(component_size) * static_cast<std::size_t>(components);
    const std::string view_path = fmt::format("bufferViews[{}]", a.bufferView);
    const std::string accessor_path = fmt::format("accessors[{}]", index);
    // tinygltf has refused a byteStride that is not a multiple of 4 in [4, 252].
    const std::size_t stride = view.byteStride > 0 ? view.byteStride : element;
    if (stride < element)
      fail(fmt::format("{}: {}.byteStride: {} is less than the {} bytes of an element of accessor {}", what,
                       view_path, stride, element, index));
    // All sizes are checked against the buffer before any product is formed, so none overflows.
    if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset)
      fail(fmt::format("{}: {}: byteOffset {} + byteLength {} is past the end of buffer {} ({} bytes)", what,
                       view_path, view.byteOffset, view.byteLength, view.buffer, buffer.size()));
    if (a.byteOffset > view.byteLength)
      fail(fmt::format("{}: {}.byteOffset: {} is past the end of bufferView {} ({} bytes)", what,
                       accessor_path, a.byteOffset, a.bufferView, view.byteLength));
    if (a.count > view.byteLength ||
        (a.count > 0 && stride * (a.count - 1) + element > view.byteLength - a.byteOffset))
      fail(fmt::format(
          "{}: {}.count: {} elements of {} bytes, {} bytes apart from byteOffset {}, do not fit in "
          "bufferView {} ({} bytes)",
          what, accessor_path, a.count, element, stride, a.byteOffset, a.bufferView, view.byteLength));
    return {buffer.data() + view.byteOffset + a.byteOffset, stride, a.count, a.componentType};
  }

  static float float_at(const AccessorData& data, std::size_t i, std::size_t k) {
    float value = 0;
    std::memcpy(&value, data.data + i * data.stride + k * sizeof(float), sizeof(float));
    return value;
  }

  static std::uint32_t index_at(const AccessorData& data, std::size_t i) {
    const unsigned char* at = data.data + i * data.stride;
    switch (data.component_type) {
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return *at;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        std::uint16_t v;
        std::memcpy(&v, at, 2);
        return v;
      }
      default: {
        std::uint32_t v;
        std::memcpy(&v, at, 4);
        return v;
      }
    }
  }

  // --- primitives ---------------------------------------------------------------------------

  void add_mesh(int mesh_index, const Eigen::Matrix4d& world, int node) {
    if (mesh_index < 0 || mesh_index >= static_cast<int>(model_.meshes.size()))
      fail(fmt::format("node {} refers to mesh {}, which does not exist", node, mesh_index));
    const tinygltf::Mesh& mesh = model_.meshes[static_cast<std::size_t>(mesh_index)];
    for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
      const std::string name = fmt::format("mesh {} primitive {}", mesh_index, p);
      const tinygltf::Primitive& primitive = mesh.primitives[p];
      if (primitive.mode != TINYGLTF_MODE_TRIANGLES) {
        warnings.push_back(
            fmt::format("{}: {} has mode {} (not TRIANGLES); skipped", path_, name, primitive.mode));
        continue;
      }
      add_primitive(primitive, name, world, node);
    }
  }

  void add_primitive(const tinygltf::Primitive& primitive, const std::string& name,
                     const Eigen::Matrix4d& world, int node) {
    const auto attribute = [&](const char* key) {
      const auto found = primitive.attributes.find(key);
      return found == primitive.attributes.end() ? -1 : found->second;
    };
    const int position_index = attribute("POSITION");
    if (position_index < 0) fail(name + " has no POSITION");
    const AccessorData positions =
        accessor(position_index, TINYGLTF_TYPE_VEC3, {TINYGLTF_COMPONENT_TYPE_FLOAT}, name + " POSITION");
    if (positions.count > std::numeric_limits<std::uint32_t>::max()) fail(name + " has too many vertices");
    Part part;
    part.mesh.positions.reserve(positions.count);
    for (std::size_t i = 0; i < positions.count; ++i) {
      const Vec3 p{float_at(positions, i, 0), float_at(positions, i, 1), float_at(positions, i, 2)};
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        fail(fmt::format("{}: vertex {} has a non-finite position", name, i));
      if (const double largest = std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
          largest > kMaxMagnitude)
        fail(
            fmt::format("{}: vertex {}: magnitude above 1e16 is not supported (found {})", name, i, largest));
      part.mesh.positions.push_back(p);
    }
    if (primitive.indices >= 0) {
      const AccessorData indices =
          accessor(primitive.indices, TINYGLTF_TYPE_SCALAR,
                   {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                    TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT},
                   name + " indices");
      part.mesh.triangles.reserve(indices.count / 3);
      for (std::size_t i = 0; i + 2 < indices.count; i += 3) {
        std::array<std::uint32_t, 3> triangle{};
        for (std::size_t c = 0; c < 3; ++c) {
          triangle[c] = index_at(indices, i + c);
          if (triangle[c] >= positions.count)
            fail(fmt::format("{}: index {} refers to vertex {}, but there are {}", name, i + c, triangle[c],
                             positions.count));
        }
        part.mesh.triangles.push_back(triangle);
      }
    } else {
      for (std::size_t i = 0; i + 2 < positions.count; i += 3)
        part.mesh.triangles.push_back({static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(i + 1),
                                       static_cast<std::uint32_t>(i + 2)});
    }
    const int normal_index = attribute("NORMAL");
    if (normal_index >= 0) {
      const AccessorData normals =
          accessor(normal_index, TINYGLTF_TYPE_VEC3, {TINYGLTF_COMPONENT_TYPE_FLOAT}, name + " NORMAL");
      if (normals.count != positions.count) fail(name + ": NORMAL and POSITION have different counts");
      part.has_normals = true;
      for (std::size_t t = 0; t < part.mesh.triangles.size(); ++t) {
        const Vec3 cross = part.mesh.face_cross(t);
        const double area = length(cross);
        const Vec3 face = area > 0 && std::isfinite(area) ? cross / area : Vec3{0, 0, 0};
        std::array<Vec3, 3> corners;
        for (std::size_t c = 0; c < 3; ++c) {
          const std::size_t v = part.mesh.triangles[t][c];
          const Vec3 n{float_at(normals, v, 0), float_at(normals, v, 1), float_at(normals, v, 2)};
          const double n_length = length(n);
          if (n_length > 0 && std::isfinite(n_length)) {
            corners[c] = n / n_length;
          } else {
            corners[c] = face;
            ++replaced_normals_;
          }
        }
        part.mesh.corner_normals.push_back(corners);
      }
    }
    const int uv_index = attribute("TEXCOORD_0");
    if (uv_index >= 0) {
      const AccessorData uvs =
          accessor(uv_index, TINYGLTF_TYPE_VEC2, {TINYGLTF_COMPONENT_TYPE_FLOAT}, name + " TEXCOORD_0");
      if (uvs.count != positions.count) fail(name + ": TEXCOORD_0 and POSITION have different counts");
      for (const auto& triangle : part.mesh.triangles) {
        std::array<Vec2, 3> corners;
        for (std::size_t c = 0; c < 3; ++c) {
          const double u = float_at(uvs, triangle[c], 0);
          const double v = float_at(uvs, triangle[c], 1);
          if (!std::isfinite(u) || !std::isfinite(v))
            fail(fmt::format("{}: vertex {} has a non-finite TEXCOORD_0", name, triangle[c]));
          corners[c] = {u, 1.0 - v};
        }
        part.mesh.corner_uvs.push_back(corners);
      }
    }
    if (!world.isIdentity()) {
      try {
        part.mesh.transform(Transform::from_matrix(world));
      } catch (const std::invalid_argument& e) {
        fail(fmt::format("nodes[{}]: transform: {}", node, e.what()));
      }
    }
    triangle_count_ += part.mesh.triangles.size();
    parts_.push_back(std::move(part));
  }

  // --- merge --------------------------------------------------------------------------------

  ObjImport merge() {
    ObjImport result;
    result.mesh = std::make_shared<TriangleMesh>();
    TriangleMesh& mesh = *result.mesh;
    const bool all_normals =
        std::all_of(parts_.begin(), parts_.end(), [](const Part& p) { return p.has_normals; });
    const bool any_uvs =
        std::any_of(parts_.begin(), parts_.end(), [](const Part& p) { return !p.mesh.corner_uvs.empty(); });
    const bool any_normals =
        std::any_of(parts_.begin(), parts_.end(), [](const Part& p) { return p.has_normals; });
    if (any_normals && !all_normals)
      warnings.push_back(fmt::format("{}: some primitives have no NORMAL; the mesh is left flat", path_));
    if (all_normals && replaced_normals_ > 0)
      warnings.push_back(fmt::format("{}: {} corner(s) with a zero-length normal use the face normal instead",
                                     path_, replaced_normals_));
    for (const Part& part : parts_) {
      if (mesh.positions.size() + part.mesh.positions.size() > std::numeric_limits<std::uint32_t>::max())
        fail("has too many vertices");
      const auto offset = static_cast<std::uint32_t>(mesh.positions.size());
      mesh.positions.insert(mesh.positions.end(), part.mesh.positions.begin(), part.mesh.positions.end());
      for (const auto& t : part.mesh.triangles)
        mesh.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
      if (all_normals)
        mesh.corner_normals.insert(mesh.corner_normals.end(), part.mesh.corner_normals.begin(),
                                   part.mesh.corner_normals.end());
      if (any_uvs) {
        if (part.mesh.corner_uvs.empty()) {
          mesh.corner_uvs.insert(mesh.corner_uvs.end(), part.mesh.triangles.size(), kDefaultCornerUvs);
        } else {
          mesh.corner_uvs.insert(mesh.corner_uvs.end(), part.mesh.corner_uvs.begin(),
                                 part.mesh.corner_uvs.end());
        }
      }
    }
    result.triangle_material.assign(mesh.triangles.size(), -1);
    result.warnings = std::move(warnings);
    return result;
  }

  struct Part {
    TriangleMesh mesh;
    bool has_normals = false;
  };

  const std::string& path_;
  const SourceLocation& referenced_from_;
  tinygltf::Model model_;
  const nlohmann::json& json_;  // the file's JSON, for what tinygltf does not keep
  std::vector<Part> parts_;
  std::size_t triangle_count_ = 0;
  std::size_t replaced_normals_ = 0;
};

}  // namespace

ObjImport import_gltf(const std::string& path, const SourceLocation& referenced_from) {
  require_mesh_file(path, "glTF", referenced_from);
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });

  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(ignore_image, nullptr);
  // The file and its external buffers are read only when they are regular files of at
  // most 4 GiB (a FIFO buffer blocked in open(), /dev/zero was read until memory ran out).
  tinygltf::FsCallbacks callbacks{};
  // tinygltf's own FileExists opens the file, which blocks on a FIFO: stat it instead.
  callbacks.FileExists = [](const std::string& file, void*) {
    struct stat status {};
    return ::stat(file.c_str(), &status) == 0;
  };
  callbacks.ExpandFilePath = tinygltf::ExpandFilePath;
  callbacks.WriteWholeFile = tinygltf::WriteWholeFile;
  callbacks.ReadWholeFile = [](std::vector<unsigned char>* out, std::string* err, const std::string& file,
                               void* user_data) {
    const std::string problem = input_file_problem(file, "'" + file + "'", kLargeInputLimit);
    if (!problem.empty()) {
      if (err) *err += problem + "\n";
      return false;
    }
    return tinygltf::ReadWholeFile(out, err, file, user_data);
  };
  callbacks.user_data = nullptr;
  loader.SetFsCallbacks(callbacks);
  // The file is read here, once, so that its JSON can be checked where tinygltf is silent.
  std::string bytes;
  try {
    bytes = read_input_file(path, "the glTF file", std::numeric_limits<unsigned int>::max());
  } catch (const InputError& e) {
    throw InputError(referenced_from, "cannot read glTF file '" + path + "': " + e.message());
  }
  const bool binary = extension == ".glb";
  tinygltf::Model model;
  std::string error, warning;
  bool loaded = false;
  try {
    const std::string base_dir = tinygltf::GetBaseDir(path);
    const auto size = static_cast<unsigned int>(bytes.size());
    loaded = binary ? loader.LoadBinaryFromMemory(&model, &error, &warning,
                                                  reinterpret_cast<const unsigned char*>(bytes.data()), size,
                                                  base_dir)
                    : loader.LoadASCIIFromString(&model, &error, &warning, bytes.data(), size, base_dir);
  } catch (const std::exception& e) {  // the JSON library may throw on malformed input
    error = e.what();
    loaded = false;
  }
  if (!loaded) {
    const auto lines = lines_of(error);
    std::string text;
    for (const auto& line : lines) text += (text.empty() ? "" : "; ") + line;
    throw InputError(referenced_from,
                     "cannot read glTF file '" + path + "': " + (text.empty() ? "unknown error" : text));
  }
  const std::string_view json_text = binary ? glb_json_chunk(bytes) : std::string_view(bytes);
  const nlohmann::json json = nlohmann::json::parse(json_text.begin(), json_text.end(), nullptr, false);
  GltfReader reader(path, referenced_from, std::move(model), json);
  for (const auto& line : lines_of(warning)) reader.warnings.push_back(path + ": " + line);
  return reader.read();
}

}  // namespace candela
