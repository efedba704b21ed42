// A file name's extension as readers choose by it: "scene.GLTF" → ".gltf" (with the dot, lower case;
// empty when there is none).
#pragma once

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>

namespace candela {

inline std::string lower_case_extension(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

}  // namespace candela
