#include "integrators/method_registry.h"

#include <fmt/format.h>

#include <array>
#include <string>

#include "integrators/local.h"
#include "integrators/meshless_method.h"
#include "integrators/path_tracer.h"
#include "integrators/radiosity_method.h"
#include "integrators/raster_method.h"
#include "integrators/whitted.h"
#include "radiosity/radiosity_settings.h"
#include "shading/environment.h"
#include "util/error.h"
#include "util/registry.h"

namespace candela {

namespace {

MethodCapabilities ray_tracer() {
  MethodCapabilities capabilities;
  capabilities.ray_trees = true;
  capabilities.samples_per_pixel = true;
  capabilities.samples_emissive_surfaces = true;
  return capabilities;
}

// The local model answers probe with its direct light (integrators/probe.h); whitted does not.
MethodCapabilities local() {
  MethodCapabilities capabilities = ray_tracer();
  capabilities.probe = true;
  return capabilities;
}

MethodCapabilities raster() {
  MethodCapabilities capabilities;
  capabilities.samples_emissive_surfaces = true;
  return capabilities;
}

MethodCapabilities radiosity() {
  MethodCapabilities capabilities;
  capabilities.solution = true;
  capabilities.checkpoints = true;
  capabilities.probe = true;  // integrators/probe.h
  capabilities.standalone_solution = true;
  return capabilities;
}

MethodCapabilities meshless() {
  MethodCapabilities capabilities;
  capabilities.sites_image = true;
  capabilities.relighting = true;
  capabilities.samples_emissive_surfaces = true;
  capabilities.probe = true;  // integrators/probe.h
  capabilities.standalone_solution = true;
  return capabilities;
}

MethodCapabilities path() {
  MethodCapabilities capabilities;
  capabilities.progressive_passes = true;
  capabilities.checkpoints = true;
  capabilities.probe = true;  // integrators/probe.h
  return capabilities;
}

// The path tracer's passes and time limit: --spp N passes, --time T seconds (passes without limit
// unless --spp says otherwise), --checkpoint-every its checkpoint interval.
constexpr std::array<std::string_view, 3> kPathRunLength = {"spp", "time", "checkpoint_interval"};
std::vector<std::string> path_run_limits(const RunLimitOptions& limits) {
  std::vector<std::string> overrides;
  if (limits.spp) overrides.push_back(fmt::format("spp={}", *limits.spp));
  if (limits.time) {
    overrides.push_back(fmt::format("time={}", *limits.time));
    if (!limits.spp) overrides.push_back("spp=0");
  }
  if (limits.checkpoint_every)
    overrides.push_back(fmt::format("checkpoint_interval={}", *limits.checkpoint_every));
  return overrides;
}

// Progressive radiosity goes on from a checkpoint to a lower threshold or more steps.
constexpr std::array<std::string_view, 3> kRadiosityRunLength = {"threshold", "max_steps",
                                                                 "memory_limit_mib"};

constexpr std::string_view kShadowRays =
    "shadow rays to every light, to jittered points of each emissive surface and to the environment";

const std::array kMethodEntries = {
    MethodEntry{"local", "ray casting with the local model only (001, 000 §2)", kShadowRays, local(),
                [](const JsonNode& settings) -> std::unique_ptr<Method> {
                  return std::make_unique<LocalMethod>(read_local_settings(settings));
                }},
    MethodEntry{"whitted", "recursive Whitted ray tracing (000 §5, 001)", kShadowRays, ray_tracer(),
                [](const JsonNode& settings) -> std::unique_ptr<Method> {
                  return std::make_unique<WhittedMethod>(read_whitted_settings(settings));
                }},
    MethodEntry{
        "raster", "scanline z-buffer rasterizer, flat / Gouraud / Phong / dot-product shading (000 §3)",
        "the local model's shadow rays at the shading points (dotproduct: one point per light)", raster(),
        [](const JsonNode& settings) -> std::unique_ptr<Method> {
          return std::make_unique<RasterMethod>(read_raster_settings(settings));
        }},
    MethodEntry{
        "radiosity",
        "classic radiosity: hemicube form factors, progressive refinement with substructuring (000 §6)",
        "lights and environment: the first shot (shadow rays from each element); emissive surfaces: emitters "
        "of "
        "the mesh (front side)",
        radiosity(),
        [](const JsonNode& settings) -> std::unique_ptr<Method> {
          return std::make_unique<RadiosityMethod>(read_radiosity_settings(settings));
        },
        kRadiosityRunLength},
    MethodEntry{"meshless",
                "meshless finite-element radiosity: sites, radial / normalized / Shepard bases (002)",
                "every emitter lights η by shadow rays from the sites, the emissive surfaces also by the "
                "sites' MIS-weighted cosine rays (per pixel in hybrid: shadow rays)",
                meshless(),
                [](const JsonNode& settings) -> std::unique_ptr<Method> {
                  return std::make_unique<MeshlessMethod>(read_meshless_settings(settings));
                }},
    MethodEntry{
        "path",
        "path-traced reference: next-event estimation, MIS, Russian roulette, progressive passes (SPEC §12)",
        "next-event estimation and BSDF rays with MIS, for every emitter", path(),
        [](const JsonNode& settings) -> std::unique_ptr<Method> {
          return std::make_unique<PathMethod>(read_path_settings(settings));
        },
        kPathRunLength, path_run_limits},
};

// kMethodEntries as loader sections: each method's object checked by making the method from it.
std::array<SettingsSection, kMethodEntries.size()> make_sections() {
  std::array<SettingsSection, kMethodEntries.size()> sections;
  for (std::size_t i = 0; i < kMethodEntries.size(); ++i) {
    const MethodEntry* entry = &kMethodEntries[i];
    sections[i] = {entry->name, [entry](const JsonNode& node) { entry->create(node); }};
  }
  return sections;
}

// The method made from its settings object with the overrides applied.
std::unique_ptr<Method> made_from_settings(const MethodEntry& entry, const Scene& scene,
                                           const std::vector<std::string>& overrides) {
  if (overrides.empty()) return entry.create(scene.plugin_settings.node(entry.name));
  // A document of the object alone, the overrides applied to it (errors name the assignment).
  const JsonNode original = scene.plugin_settings.node(entry.name);
  JsonDocument document =
      JsonDocument::parse(nlohmann::json{{std::string(entry.name), original.json()}}.dump(), scene.source);
  for (const std::string& assignment : overrides)
    document.apply_override(std::string(entry.name) + "." + assignment);
  const JsonNode root(document, document.root(), "");
  return entry.create(root.at(entry.name));
}

// An emitter a method cannot account for is an error naming both, never a dark image.
void refuse_unsampled_emitters(const MethodEntry& entry, const Scene& scene) {
  if (!entry.capabilities.samples_emissive_surfaces || scene.unsampled_emitters.empty()) return;
  std::string able;  // the methods that take such a surface
  for (const MethodEntry& other : kMethodEntries)
    if (!other.capabilities.samples_emissive_surfaces)
      able += (able.empty() ? "" : " or ") + std::string(other.name);
  const UnsampledEmitter& emitter = scene.unsampled_emitters.front();
  throw InputError(emitter.location, std::string(entry.name) + " cannot light the scene by the emissive " +
                                         emitter.type + " \"" + emitter.name +
                                         "\": it cannot be sampled for shadow rays (unbounded); bound it (a "
                                         "quad, a disc) or render with " +
                                         able);
}

}  // namespace

std::span<const MethodEntry> method_entries() {
  return kMethodEntries;
}

const MethodEntry* find_method(std::string_view name) {
  return find_entry<MethodEntry>(kMethodEntries, name);
}

std::string method_names() {
  return entry_names<MethodEntry>(kMethodEntries);
}

std::vector<std::string> default_comparison_methods() {
  return {"whitted", "radiosity", "meshless", std::string(kReferenceMethod)};
}

bool overrides_run_length(std::string_view assignment) {
  for (const MethodEntry& entry : kMethodEntries)
    for (const std::string_view key : entry.run_length_keys)
      if (assignment.size() > entry.name.size() + key.size() + 1 && assignment.starts_with(entry.name) &&
          assignment[entry.name.size()] == '.' && assignment.substr(entry.name.size() + 1).starts_with(key) &&
          assignment[entry.name.size() + 1 + key.size()] == '=')
        return true;
  return false;
}

std::vector<std::string> run_limit_overrides(const RunLimitOptions& limits) {
  std::vector<std::string> overrides;
  for (const MethodEntry& entry : kMethodEntries)
    if (entry.run_limit_overrides)
      for (const std::string& assignment : entry.run_limit_overrides(limits))
        overrides.push_back(std::string(entry.name) + "." + assignment);
  return overrides;
}

std::vector<std::string_view> method_names_with(bool MethodCapabilities::*capability) {
  std::vector<std::string_view> names;
  for (const MethodEntry& entry : kMethodEntries)
    if (entry.capabilities.*capability) names.push_back(entry.name);
  return names;
}

std::unique_ptr<Method> create_method(const MethodEntry& entry, const Scene& scene,
                                      const std::vector<std::string>& overrides) {
  return create_method(entry, scene, overrides, scene.antialiasing);
}

std::unique_ptr<Method> create_method(const MethodEntry& entry, const Scene& scene,
                                      const std::vector<std::string>& overrides,
                                      const AntialiasingSettings& antialiasing) {
  std::unique_ptr<Method> method = made_from_settings(entry, scene, overrides);
  refuse_unsupported_antialiasing(*method, scene, antialiasing);
  refuse_unsampled_emitters(entry, scene);
  method->refuse_scene(scene);
  return method;
}

nlohmann::json emitter_facts(const Scene& scene, const MethodEntry& entry) {
  nlohmann::json lights = nlohmann::json::object();
  for (const auto& light : scene.lights) {
    const std::string type(light->type_name());
    lights[type] = lights.value(type, 0) + 1;
  }
  nlohmann::json surfaces = nlohmann::json::array();
  for (const auto& surface : scene.surface_lights) surfaces.push_back(surface->object_name());
  for (const UnsampledEmitter& emitter : scene.unsampled_emitters) surfaces.push_back(emitter.name);
  return {{"lights", lights},
          {"emissive_surfaces", surfaces},
          {"environment", scene.environment ? nlohmann::json(std::string(scene.environment->type_name()))
                                            : nlohmann::json(nullptr)},
          {"background_lights", false},
          {"accounted_by", std::string(entry.emitters)}};
}

std::span<const SettingsSection> method_settings_sections() {
  static const std::array<SettingsSection, kMethodEntries.size()> sections = make_sections();
  return sections;
}

}  // namespace candela
