// candela info [SCENE] [--set k=v]: what the scene holds.
#include <fmt/format.h>

#include <iostream>
#include <map>

#include "commands.h"
#include "scene_options.h"
#include "shading/environment.h"
#include "util/error.h"
#include "util/statistics.h"

namespace candela::cli {

namespace {

int run_info(const SceneOptions& options) {
  const std::unique_ptr<Scene> scene = options.load();
  for (const auto& warning : scene->warnings) std::cerr << "candela: warning: " << warning << "\n";
  std::map<std::string, std::pair<int, uint64_t>> by_type;  // objects, primitives
  for (const SceneObject& object : scene->objects) {
    auto& [objects, primitives] = by_type[object.type];
    ++objects;
    primitives += object.primitive_count;
  }
  std::cout << fmt::format("scene: {}\n", scene->source);
  std::cout << fmt::format("camera: {} {}x{}\n", scene->camera->type_name(), scene->camera->width(),
                           scene->camera->height());
  for (const NamedCamera& view : scene->cameras)  // --camera NAME
    std::cout << fmt::format("camera {}: {} {}x{}\n", view.name, view.camera->type_name(),
                             view.camera->width(), view.camera->height());
  std::cout << fmt::format("objects: {}, primitives: {}\n", scene->objects.size(), scene->primitives.size());
  for (const auto& [type, counts] : by_type)
    std::cout << fmt::format("  {:<10} {:>6} object(s) {:>10} primitive(s)\n", type, counts.first,
                             counts.second);
  const uint64_t triangles = by_type.count("mesh") ? by_type["mesh"].second : 0;
  std::cout << fmt::format("triangles: {}\n",
                           triangles + (by_type.count("triangle") ? by_type["triangle"].second : 0));
  std::cout << fmt::format("lights: {} (+ ambient [{:.4g}, {:.4g}, {:.4g}])\n", scene->lights.size(),
                           scene->ambient.r, scene->ambient.g, scene->ambient.b);
  for (const auto& light : scene->lights) std::cout << "  " << light->type_name() << "\n";
  std::cout << fmt::format("materials: {}\n", scene->materials.size());
  if (scene->environment)
    std::cout << fmt::format("environment: {}\n", scene->environment->type_name());
  else
    std::cout << fmt::format("background: [{:.4g}, {:.4g}, {:.4g}]\n", scene->background.r,
                             scene->background.g, scene->background.b);
  const Bounds3& b = scene->bounds();
  std::cout << fmt::format("bounds (finite shapes): ({:.4g}, {:.4g}, {:.4g}) to ({:.4g}, {:.4g}, {:.4g})\n",
                           b.lower.x, b.lower.y, b.lower.z, b.upper.x, b.upper.y, b.upper.z);
  std::cout << fmt::format("method: {}, accelerator: {}\n", scene->render.method,
                           scene->accelerator().name());
  std::cout << fmt::format("memory: {:.1f} MiB peak resident after loading\n",
                           peak_memory_bytes() / (1024.0 * 1024.0));
  return 0;
}

}  // namespace

void add_info_command(CLI::App& app, std::function<int()>& run) {
  auto options = std::make_shared<SceneOptions>();
  CLI::App* command = app.add_subcommand("info", "Describe what a scene holds");
  command->add_option("scene", options->scene_path, "Scene file (default: the built-in scene)");
  command->add_option("--set", options->overrides, "Override a scene setting: key=value")
      ->expected(1)
      ->allow_extra_args(false)
      ->take_all();
  command->callback([options, &run]() {
    run = [options]() { return run_reporting_bad_input([&] { return run_info(*options); }); };
  });
}

}  // namespace candela::cli
