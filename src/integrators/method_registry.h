// The methods by name (render.method, --method). Each entry makes its method from the method's
// own object of the scene file ("whitted": {...}; an empty object gives the defaults) and says
// what the method can give besides its image (MethodCapabilities), so that a caller can refuse an
// output the method cannot give before any work.
#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
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
  bool ray_trees = false;            // the ray tree of one pixel (RayTracingMethod::pixel_ray_tree)
  bool samples_per_pixel = false;    // how many samples each pixel used (RunStatistics::samples_per_pixel)
  bool solution = false;             // a view-independent solution mesh (RenderResult::solution)
  bool sites_image = false;          // the image with its sites drawn (RenderResult::sites_image)
  bool relighting = false;           // other light set-ups from the same geometry, cheaply
  bool progressive_passes = false;   // samples per pixel and a time limit (path.spp, path.time)
  bool checkpoints = false;          // checkpoint and resume (RenderRequest::checkpoint, resume)
  bool probe = false;                // irradiance at sensor points (integrators/probe.h)
  bool standalone_solution = false;  // its solution without an image (Method::solve_alone)
  // Lights emissive surfaces by shadow rays to points sampled on them (scene/surface_light.h):
  // refuses a scene with an emissive surface that cannot be sampled (Scene::unsampled_emitters).
  bool samples_emissive_surfaces = false;
};

// The command line's run limits (candela render --spp, --time, --checkpoint-every).
struct RunLimitOptions {
  std::optional<int> spp;
  std::optional<double> time;
  std::optional<double> checkpoint_every;
};

struct MethodEntry {
  std::string_view name;  // also the key of its settings object in the scene file
  std::string_view description;
  // How it accounts for each kind of emitter (docs/scene-format.md, "Emitters").
  std::string_view emitters;
  MethodCapabilities capabilities;
  // Reads the settings object (ranges checked, unknown keys refused: InputError) and makes the method.
  std::unique_ptr<Method> (*create)(const JsonNode& settings);
  // The keys of its settings object that say only how far to run (path.spp, radiosity.threshold):
  // a checkpoint made with other values still resumes, so a caller's fingerprint leaves them out.
  std::span<const std::string_view> run_length_keys = {};
  // Its settings for the command line's run limits, as keys within its object ("spp=16"); null:
  // it takes none of them.
  std::vector<std::string> (*run_limit_overrides)(const RunLimitOptions& limits) = nullptr;
};

// The reference the other methods are measured against (SPEC §12: the path tracer): candela
// probe's default, candela report's reference.
inline constexpr std::string_view kReferenceMethod = "path";

// The methods candela report compares by default: one of each family (recursive ray tracing, the
// two diffuse solutions) and the reference.
std::vector<std::string> default_comparison_methods();

std::span<const MethodEntry> method_entries();
const MethodEntry* find_method(std::string_view name);
// The methods whose capabilities have `capability`, in registry order.
std::vector<std::string_view> method_names_with(bool MethodCapabilities::*capability);
std::string method_names();  // "local, whitted"

// Whether an override ("path.spp=16") sets a key that says only how far its method runs.
bool overrides_run_length(std::string_view assignment);
// The overrides ("path.spp=16") the command line's run limits make, for every method that takes
// them.
std::vector<std::string> run_limit_overrides(const RunLimitOptions& limits);

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
