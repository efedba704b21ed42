// State shared by the scene loader and the registries' factories while one file loads.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "io/json_node.h"
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
  // The scene's named materials (its "materials" object), by name.
  const std::map<std::string, uint32_t>* named_materials = nullptr;

  uint32_t add_material(Material material) {
    materials->push_back(std::move(material));
    return static_cast<uint32_t>(materials->size() - 1);
  }
  // The named material `name` (a string node) stands for; fails at the node naming the ones defined.
  uint32_t named_material(const JsonNode& name) const {
    const std::string wanted = name.as_string();
    if (named_materials) {
      const auto found = named_materials->find(wanted);
      if (found != named_materials->end()) return found->second;
    }
    std::string known;
    if (named_materials)
      for (const auto& [key, index] : *named_materials) known += (known.empty() ? "" : ", ") + key;
    name.fail("unknown material \"" + wanted + "\"" +
              (known.empty() ? std::string(" (no materials are defined)") : " (defined: " + known + ")"));
  }
};

}  // namespace candela
