// State shared by the scene loader and the registries' factories while one file loads.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "math/transform.h"
#include "shading/material.h"

namespace candela {

struct LoadContext {
  std::filesystem::path base_directory;  // relative mesh and texture paths start here
  std::vector<Material>* materials = nullptr;
  std::vector<std::string>* warnings = nullptr;
  // Every file resolved (meshes, textures, environment maps), in order: Scene::input_files.
  std::vector<std::string>* input_files = nullptr;

  std::filesystem::path resolve(const std::string& file) const {
    const std::filesystem::path path(file);
    std::filesystem::path resolved = path.is_absolute() ? path : base_directory / path;
    if (input_files) input_files->push_back(resolved.string());
    return resolved;
  }
  uint32_t add_material(Material material) {
    materials->push_back(std::move(material));
    return static_cast<uint32_t>(materials->size() - 1);
  }
};

}  // namespace candela
