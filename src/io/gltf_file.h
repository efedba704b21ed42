// A glTF 2.0 file read once through tinygltf (.gltf with embedded data-URI or external buffers,
// resolved against the file's folder, or binary .glb), for the mesh reader (io/gltf_import.h)
// and the whole-scene translation (io/gltf_scene.h); and its node tree walked from a scene's
// roots with each node's world transform.
//
// Errors (InputError located at referenced_from, naming the file and, where there is one, the
// JSON path): tinygltf's parse errors; an accessor or bufferView byteOffset or byteStride that is
// not a non-negative integer (tinygltf would read it as 0); node numbers (matrix, translation,
// rotation, scale) that are not finite or above 1e16, or a transform composed down the node tree
// that leaves that range; the zero quaternion; a node reached twice (not a tree); a scene or node
// that does not exist.
#pragma once

// Images are never decoded by tinygltf (the project's stb_image is compiled in texture_image.cpp):
// no stb, no external image files. These shape the header's inline code too, so every file that
// includes tinygltf does so through this header; the implementation is
// io/tinygltf_implementation.cpp.
#ifndef TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE
#endif
#ifndef TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#endif
#ifndef TINYGLTF_NO_EXTERNAL_IMAGE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#endif
#include <tiny_gltf.h>

#include <Eigen/Dense>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "util/error.h"

namespace candela {

struct GltfFile {
  std::string path;
  SourceLocation referenced_from;
  tinygltf::Model model;
  nlohmann::json json;                // the file's JSON (a .glb's first chunk), for what tinygltf drops
  std::vector<std::string> warnings;  // tinygltf's, each prefixed with the path
  // InputError at referenced_from: "glTF file 'PATH' MESSAGE".
  [[noreturn]] void fail(const std::string& message) const;
};

// Reads path (taken as given; ".glb", any case, as binary glTF). Images are not decoded: each
// keeps its uri (or bufferView), for the caller to resolve.
GltfFile read_gltf_file(const std::string& path, const SourceLocation& referenced_from);

// The scene a file shows: `requested` when it is not negative, else the file's "scene", else 0;
// -1 when the file has no scenes (then every mesh stands at the origin). Fails on a scene that
// does not exist.
int gltf_scene_index(const GltfFile& file, int requested);

struct GltfNodePlacement {
  int node = 0;
  Eigen::Matrix4d world;  // the node's local transform composed down from the scene's roots
};

// Every node of scene `scene` (gltf_scene_index), depth first from its roots in the file's order
// (a node before its children, siblings as listed), with its world transform; none when scene is -1.
std::vector<GltfNodePlacement> gltf_scene_nodes(const GltfFile& file, int scene);

}  // namespace candela
