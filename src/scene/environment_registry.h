// Environment maps by name (SPEC §7, 000 §4.1.3), and the reading of image files that image
// textures share with them.
//
//   {"type": "constant", "color": [r, g, b]}
//   {"type": "cube", "faces": {"+x": "px.png", "-x": "nx.png", "+y": "py.png", "-y": "ny.png",
//                              "+z": "pz.png", "-z": "nz.png"},
//    "multiplier": 1 | [r, g, b], "encoding": "auto" | "srgb" | "linear"}
//   {"type": "equirectangular", "file": "sky.exr", "up": [0, 1, 0], "forward": [0, 0, -1],
//    "multiplier": 1 | [r, g, b], "encoding": "auto" | "srgb" | "linear"}
//
// File names are relative to the scene file. The conventions (which way a cube face or a
// panorama faces) are in shading/environment.h.
#pragma once

#include <memory>
#include <span>
#include <string_view>

#include "io/json_node.h"
#include "scene/load_context.h"
#include "shading/environment.h"
#include "shading/texture_image.h"

namespace candela {

struct EnvironmentEntry {
  std::string_view name;
  std::string_view description;
  std::string_view example;  // a complete JSON object that read_environment accepts
  std::unique_ptr<Environment> (*create)(const JsonNode& node, const LoadContext& context);
};

std::span<const EnvironmentEntry> environment_entries();
const EnvironmentEntry* find_environment(std::string_view name);

// An environment object with a "type"; fails (InputError with file, line, column and JSON
// path) on an unknown type, a bad value, an unreadable image or an unknown key.
std::unique_ptr<Environment> read_environment(const JsonNode& node, const LoadContext& context);

// The optional "encoding" member of owner: "auto" (default), "srgb" or "linear".
ColorEncoding read_color_encoding(const JsonNode& owner);
// The optional "wrap" member of owner: "repeat" (default), "clamp" or "mirror".
WrapMode read_wrap_mode(const JsonNode& owner);

// The image named by file_node (a string, relative to the scene file), decoded with encoding.
// Failures are reported on file_node with the reason. A file already loaded with the same
// encoding (same canonical path, modification time and size) and still in use is shared, not
// read again: the cache holds weak references, so images go away with the last scene using them.
std::shared_ptr<const TextureImage> load_texture_image(const JsonNode& file_node, const LoadContext& context,
                                                       ColorEncoding encoding);

}  // namespace candela
