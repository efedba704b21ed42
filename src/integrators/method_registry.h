// The methods by name (render.method, --method). Each entry makes its method from the method's
// own object of the scene file ("whitted": {...}; an empty object gives the defaults) and says
// what the method can give besides its image (MethodCapabilities), so that a caller can refuse an
// output the method cannot give before any work.
#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "integrators/method.h"
#include "io/json_node.h"
#include "scene/plugin_settings.h"

namespace candela {

// What a method gives besides its image, and which run options it takes.
struct MethodCapabilities {
  bool ray_trees = false;           // the ray tree of one pixel (RayTracingMethod::pixel_ray_tree)
  bool samples_per_pixel = false;   // how many samples each pixel used (RunStatistics::samples_per_pixel)
  bool solution = false;            // a view-independent solution mesh (RenderResult::solution)
  bool sites_image = false;         // the image with its sites drawn (RenderResult::sites_image)
  bool relighting = false;          // other light set-ups from the same geometry, cheaply
  bool progressive_passes = false;  // samples per pixel and a time limit (path.spp, path.time)
  bool checkpoints = false;         // checkpoint and resume (RenderRequest::checkpoint, resume)
  bool probe = false;               // irradiance at sensor points (integrators/probe.h)
  // Lights emissive surfaces by shadow rays to points sampled on them (scene/surface_light.h):
  // refuses a scene with an emissive surface that cannot be sampled (Scene::unsampled_emitters).
  bool samples_emissive_surfaces = false;
};

struct MethodEntry {
  std::string_view name;  // also the key of its settings object in the scene file
  std::string_view description;
  // How it accounts for each kind of emitter (docs/scene-format.md, "Emitters").
  std::string_view emitters;
  MethodCapabilities capabilities;
  // Reads the settings object (ranges checked, unknown keys refused: InputError) and makes the method.
  std::unique_ptr<Method> (*create)(const JsonNode& settings);
};

std::span<const MethodEntry> method_entries();
const MethodEntry* find_method(std::string_view name);
// The methods whose capabilities have `capability`, in registry order.
std::vector<std::string_view> method_names_with(bool MethodCapabilities::*capability);
std::string method_names();  // "local, whitted"

// What a render by this method lit the scene with: the scene's emitters by kind (lights by type,
// the emissive objects by name, the environment) and how the method accounts for them — in
// --stats and in candela report.
nlohmann::json emitter_facts(const Scene& scene, const MethodEntry& entry);

// The method made from the scene's settings object for it, with `overrides` applied to that object
// first ("spp=16": keys within it, as --set path.spp=16 would). An InputError when the method
// cannot honour the scene's "aa" settings (Method::antialiasing_refusal), cannot light the scene
// by one of its emitters, or refuses the scene otherwise (Method::refuse_scene), before any work.
std::unique_ptr<Method> create_method(const MethodEntry& entry, const Scene& scene,
                                      const std::vector<std::string>& overrides = {});
// The same, the "aa" settings checked being a render's own (RenderRequest::antialiasing)
// rather than the scene's.
std::unique_ptr<Method> create_method(const MethodEntry& entry, const Scene& scene,
                                      const std::vector<std::string>& overrides,
                                      const AntialiasingSettings& antialiasing);

// One section per method, for the scene loader: every method's object is checked at load time.
std::span<const SettingsSection> method_settings_sections();

}  // namespace candela
