// A whole glTF 2.0 scene as a candela/1 scene document (docs/import.md has the table of what each
// glTF feature becomes in each method): the scene's meshes as one "mesh" entry of the file (its
// node tree and primitives, io/gltf_import.h) whose glTF materials stand for named scene
// materials ("file_materials"), its cameras, its KHR_lights_punctual and EXT_lights_ies lights.
// The document is loaded like any scene file, so --set, the ranges and every method apply; a
// JSON scene may include it and add or override what the file lacks.
//
// Materials (glTF's metallic-roughness model, Khronos's BRDF): a layered Cook-Torrance material
// (docs/materials.md: the diffuse beneath the facets gets 1 − F at the viewing angle in the path
// tracer) with GGX facets, roughness α = roughnessFactor² (at least 1e-3), kd = baseColor ·
// (1 − metallic)·(1 − transmission) (the factor × the baseColorTexture, sRGB, over TEXCOORD_0 with
// KHR_texture_transform's offset and scale), ks = 1 − kt, Schlick F0 = mix(((ior − 1)/(ior + 1))²,
// baseColor, metallic), kt = (1 − metallic)·transmission of index KHR_materials_ior (1.5), a thin
// sheet unless KHR_materials_volume gives a thickness (then Beer's law absorption
// −ln(attenuationColor)/attenuationDistance), emission of luminance emissiveFactor ×
// KHR_materials_emissive_strength in cd/m², alphaMode BLEND a constant transparency 1 − alpha.
// The local model, Whitted and the rasterizer read the same Cook-Torrance parameters (Beckmann
// facets of the same roughness); radiosity and meshless the diffuse kd.
//
// Warnings (each prefixed with the file) for what is read but not rendered: an extension of
// extensionsUsed Candela does not support, normal, metallic-roughness and emissive textures,
// texture rotation, a second texture coordinate set, embedded images, a light's range, an
// EXT_lights_ies profile not given by a file. Errors (InputError located at referenced_from,
// naming the file and the JSON path): those of io/gltf_file.h, an extension of
// extensionsRequired Candela does not support, a light or camera of the wrong shape, an image
// file that is missing.
#pragma once

#include <Eigen/Dense>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "util/error.h"

namespace candela {

struct GltfSceneDocument {
  nlohmann::json document;  // candela/1
  std::vector<std::string> warnings;
  // The file has no camera: the document's "camera" sees the whole scene from the front, above
  // and to the right (the bounds of its POSITION accessors), as a viewer's "frame all" does.
  bool framed_camera = false;
};

// The extensions a glTF scene may require (extensionsRequired), in the order docs/import.md
// lists them.
const std::vector<std::string>& supported_gltf_extensions();

// Where the scene stands in the document's world and how its files are named (a JSON scene's
// "include"): placement moves its cameras and lights (its mesh entry is given the same transform
// by the includer); file_prefix goes before every file the document names (the glTF itself,
// images, IES profiles), which are otherwise relative to the glTF file's folder.
struct GltfPlacement {
  Eigen::Matrix4d matrix = Eigen::Matrix4d::Identity();
  std::string file_prefix;
};

// The document of scene `scene` of the file at path (-1: its default scene).
GltfSceneDocument gltf_scene_document(const std::string& path, int scene,
                                      const SourceLocation& referenced_from,
                                      const GltfPlacement& placement = {});

}  // namespace candela
