// The candela/1 scene format (SPEC §3, docs/scene-format.md): JSON in, Scene out.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace candela {

// Reads and validates a scene file. overrides are "dotted.path=value" (--set). plugin_sections:
// the top-level objects that plugins above the scene read (the methods' settings), each checked
// by its reader; any other unknown key is refused. Throws InputError naming file, line, column
// and JSON path for any problem. (integrators/scene_loading.h passes every method's section.)
std::unique_ptr<Scene> read_scene_file(const std::string& path, const std::vector<std::string>& overrides,
                                       std::span<const SettingsSection> plugin_sections);
// The same for text held in memory; name stands for the file in messages, base_directory
// resolves relative mesh paths.
std::unique_ptr<Scene> read_scene_text(const std::string& text, const std::string& name,
                                       const std::string& base_directory,
                                       const std::vector<std::string>& overrides,
                                       std::span<const SettingsSection> plugin_sections);
// Light set-ups for relighting (candela render --relight FILE): a JSON object
// {"frames": [{"name": "noon", "ambient": 0.1, "lights": [... as a scene's "lights" ...],
//              "materials": {"red": {"kd": [0.2, 0.6, 0.2]}}}, ...]}.
// Names (default frameN) are unique and made of letters, digits, '_' and '-'. "materials" (the
// albedo edits) gives named materials of the scene another diffuse reflectance kd for the frame;
// the names are checked against the scene when the frame is rendered (find_albedo_edit_targets).
// Throws InputError with file, line, column and JSON path.
struct AlbedoEdit {
  std::string material;
  Color kd;
  SourceLocation location;  // the material's key in the set-ups file
};
struct LightSetup {
  std::string name;
  std::vector<std::unique_ptr<Light>> lights;
  Color ambient;
  std::vector<AlbedoEdit> albedo_edits;
  // The files the frame's lights read (luminaires), inputs no output may overwrite, and
  // what its lights warn of (a sun below the horizon), as a scene's.
  std::vector<std::string> input_files;
  std::vector<std::string> warnings;
};
std::vector<LightSetup> load_light_setups(const std::string& path);
std::vector<LightSetup> load_light_setups_text(const std::string& text, const std::string& name);
// The index in scene.materials of each edit's material; InputError at the edit's location when the
// scene has no material of that name (the names it has listed).
std::vector<std::size_t> find_albedo_edit_targets(const Scene& scene, const std::vector<AlbedoEdit>& edits);

// The built-in default scene (the two-mirror scene of 000 §5.9).
std::unique_ptr<Scene> read_default_scene(const std::vector<std::string>& overrides,
                                          std::span<const SettingsSection> plugin_sections);
const std::string& default_scene_text();

}  // namespace candela
