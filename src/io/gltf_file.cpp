#include "io/gltf_file.h"

#include <fmt/format.h>
#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string_view>
#include <utility>

#include "math/constants.h"
#include "util/file_extension.h"
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

// A glTF node's transform numbers, as every number of a scene file, are limited to
// kMaxSceneMagnitude (math/constants.h): beyond it squared distances lose all precision.
constexpr double kMaxNodeNumber = kMaxSceneMagnitude;
static_assert(kMaxNodeNumber == 1e16, "the messages below name it");

// tinygltf reads an optional size that is not a non-negative integer (-4, 1.5, 1e30, "8") as its
// default 0 without a word: an accessor at byteOffset -4 read its buffer from the start.
// Such a value is refused by its JSON path. (Required sizes, byteLength and count, tinygltf
// refuses itself.)
void check_optional_sizes(const GltfFile& file) {
  static constexpr std::array<std::pair<const char*, const char*>, 3> kSizes = {
      {{"accessors", "byteOffset"}, {"bufferViews", "byteOffset"}, {"bufferViews", "byteStride"}}};
  for (const auto& [array, key] : kSizes) {
    const auto objects = file.json.find(array);
    if (objects == file.json.end() || !objects->is_array()) continue;
    for (std::size_t i = 0; i < objects->size(); ++i) {
      const nlohmann::json& object = (*objects)[i];
      if (!object.is_object()) continue;
      const auto value = object.find(key);
      if (value == object.end() || value->is_number_unsigned()) continue;
      std::string found = value->dump();
      if (found.size() > 40) found = found.substr(0, 40) + "...";
      file.fail(fmt::format("{}[{}].{}: must be a non-negative integer (found {})", array, i, key, found));
    }
  }
}

// The numbers of a node's matrix, translation, rotation and scale must be finite and at most
// kMaxNodeNumber: larger ones overflowed when composed and were then called a singular matrix.
void check_node_numbers(const GltfFile& file, const tinygltf::Node& node, int index) {
  const std::array<std::pair<const char*, const std::vector<double>*>, 4> fields = {
      {{"matrix", &node.matrix},
       {"translation", &node.translation},
       {"rotation", &node.rotation},
       {"scale", &node.scale}}};
  for (const auto& [name, values] : fields)
    for (std::size_t k = 0; k < values->size(); ++k) {
      const double value = (*values)[k];
      if (!std::isfinite(value)) file.fail(fmt::format("nodes[{}].{}[{}]: must be finite", index, name, k));
      if (std::fabs(value) > kMaxNodeNumber)
        file.fail(fmt::format("nodes[{}].{}[{}]: magnitude above 1e16 is not supported (found {})", index,
                              name, k, value));
    }
  const auto& r = node.rotation;
  if (r.size() == 4 && r[0] == 0 && r[1] == 0 && r[2] == 0 && r[3] == 0)
    file.fail(fmt::format("nodes[{}].rotation: the zero quaternion [0, 0, 0, 0] is not a rotation", index));
}

Eigen::Matrix4d local_matrix(const tinygltf::Node& node) {
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

}  // namespace

void GltfFile::fail(const std::string& message) const {
  throw InputError(referenced_from, fmt::format("glTF file '{}' {}", path, message));
}

GltfFile read_gltf_file(const std::string& path, const SourceLocation& referenced_from) {
  const std::string extension = lower_case_extension(path);

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
    // The folder external buffers resolve against (tinygltf's GetBaseDir, which its header keeps
    // to its implementation).
    const std::size_t slash = path.find_last_of("/\\");
    const std::string base_dir = slash == std::string::npos ? std::string() : path.substr(0, slash);
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
  nlohmann::json json = nlohmann::json::parse(json_text.begin(), json_text.end(), nullptr, false);
  GltfFile file;
  file.path = path;
  file.referenced_from = referenced_from;
  file.model = std::move(model);
  file.json = std::move(json);
  for (const auto& line : lines_of(warning)) file.warnings.push_back(path + ": " + line);
  check_optional_sizes(file);
  return file;
}

int gltf_scene_index(const GltfFile& file, int requested) {
  const int count = static_cast<int>(file.model.scenes.size());
  if (requested >= 0) {
    if (requested >= count)
      file.fail(fmt::format("has no scene {} (it has {}{})", requested, count,
                            count == 0 ? "" : fmt::format(": 0 to {}", count - 1)));
    return requested;
  }
  if (count == 0) return -1;
  const int scene = file.model.defaultScene >= 0 ? file.model.defaultScene : 0;
  if (scene >= count) file.fail(fmt::format("names scene {}, which does not exist", scene));
  return scene;
}

std::vector<GltfNodePlacement> gltf_scene_nodes(const GltfFile& file, int scene) {
  std::vector<GltfNodePlacement> placed;
  if (scene < 0) return placed;
  const tinygltf::Model& model = file.model;
  // Depth-first over an explicit stack (a chain of nodes as deep as the file is long must not
  // overflow the call stack); a node reached twice (a cycle, or two parents) is refused.
  std::vector<bool> visited(model.nodes.size(), false);
  std::vector<std::pair<int, Eigen::Matrix4d>> stack;
  // Pushed last first, so that nodes come out in the file's order (a parent before its children).
  const std::vector<int>& roots = model.scenes[static_cast<std::size_t>(scene)].nodes;
  for (auto root = roots.rbegin(); root != roots.rend(); ++root)
    stack.emplace_back(*root, Eigen::Matrix4d::Identity());
  while (!stack.empty()) {
    const auto [index, parent] = stack.back();
    stack.pop_back();
    if (index < 0 || index >= static_cast<int>(model.nodes.size()))
      file.fail(fmt::format("refers to node {}, which does not exist", index));
    if (visited[static_cast<std::size_t>(index)])
      file.fail(fmt::format("reaches node {} twice (the nodes are not a tree)", index));
    visited[static_cast<std::size_t>(index)] = true;
    const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(index)];
    check_node_numbers(file, node, index);
    const Eigen::Matrix4d world = parent * local_matrix(node);
    // Each node's numbers are at most 1e16, but a chain of them multiplies: name the node
    // where the composed transform leaves the supported range.
    if (!world.allFinite())
      file.fail(
          fmt::format("nodes[{}]: the transform composed from the scene's root down to this node overflows "
                      "(is not finite)",
                      index));
    if (const double largest = world.cwiseAbs().maxCoeff(); largest > kMaxNodeNumber)
      file.fail(fmt::format(
          "nodes[{}]: the transform composed from the scene's root down to this node has an entry "
          "of magnitude {}, above the supported 1e16",
          index, largest));
    placed.push_back({index, world});
    for (auto child = node.children.rbegin(); child != node.children.rend(); ++child)
      stack.emplace_back(*child, world);
  }
  return placed;
}

}  // namespace candela
