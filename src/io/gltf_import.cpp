#include "io/gltf_import.h"

#include <fmt/format.h>
#include <sys/stat.h>

#include <Eigen/Dense>
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

#include "io/gltf_file.h"
#include "math/constants.h"
#include "math/transform.h"
#include "util/input_file.h"

namespace candela {

namespace {

// A checked window onto an accessor's elements.
struct AccessorData {
  const unsigned char* data = nullptr;
  std::size_t stride = 0;
  std::size_t count = 0;
  int component_type = 0;
};

// Every number of an OBJ vertex and a glTF position is limited to kMaxSceneMagnitude
// (math/constants.h): beyond it squared distances lose all precision.
constexpr double kMaxMagnitude = kMaxSceneMagnitude;
static_assert(kMaxMagnitude == 1e16, "the messages below name it");

class GltfReader {
 public:
  explicit GltfReader(const GltfFile& file) : file_(file), path_(file.path), model_(file.model) {}

  ObjImport read(int scene) {
    place_scene(gltf_scene_index(file_, scene));
    if (parts_.empty() || triangle_count_ == 0) fail("has no triangles (mode TRIANGLES)");
    return merge();
  }

  std::vector<std::string> warnings;

 private:
  [[noreturn]] void fail(const std::string& message) const { file_.fail(message); }

  // --- node tree ----------------------------------------------------------------------------

  void place_scene(int scene) {
    if (scene < 0) {
      for (std::size_t m = 0; m < model_.meshes.size(); ++m)
        add_mesh(static_cast<int>(m), Eigen::Matrix4d::Identity(), -1);
      return;
    }
    for (const GltfNodePlacement& placed : gltf_scene_nodes(file_, scene)) {
      const int mesh = model_.nodes[static_cast<std::size_t>(placed.node)].mesh;
      if (mesh >= 0) add_mesh(mesh, placed.world, placed.node);
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
    part.material = primitive.material;
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
      result.triangle_file_material.insert(result.triangle_file_material.end(), part.mesh.triangles.size(),
                                           part.material);
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
    int material = -1;  // the primitive's material in the file
  };

  const GltfFile& file_;
  const std::string& path_;
  const tinygltf::Model& model_;
  std::vector<Part> parts_;
  std::size_t triangle_count_ = 0;
  std::size_t replaced_normals_ = 0;
};

}  // namespace

ObjImport import_gltf(const std::string& path, const SourceLocation& referenced_from, int scene) {
  require_mesh_file(path, "glTF", referenced_from);
  const GltfFile file = read_gltf_file(path, referenced_from);
  GltfReader reader(file);
  reader.warnings = file.warnings;
  return reader.read(scene);
}

}  // namespace candela
