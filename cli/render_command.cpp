// candela render [SCENE] [-o FILE] [--method M] [--threads N] [--seed S] [--set k=v]...
//                [--stats FILE.json] [--quiet] [--crop x0,y0,x1,y1] [--pixel X,Y]
//                [--aa-map FILE.png]
#include <fmt/format.h>
#include <unistd.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>

#include "commands.h"
#include "integrators/method_registry.h"
#include "integrators/ray_tracing_method.h"
#include "io/image_writer.h"
#include "scene_options.h"
#include "util/atomic_file.h"
#include "util/error.h"

namespace candela::cli {

namespace {

struct RenderOptions {
  SceneOptions scene;
  std::string output;
  std::string method;
  std::string accelerator;
  int threads = 0;
  std::optional<int64_t> seed;
  std::string stats_path;
  std::string aa_map_path;
  bool quiet = false;
  std::vector<int> crop;
  std::vector<int> pixel;
};

PixelRect region_of(const RenderOptions& options, const Camera& camera) {
  PixelRect region{0, 0, camera.width(), camera.height()};
  if (options.crop.empty()) return region;
  if (options.crop.size() != 4) throw BadArgument("--crop expects x0,y0,x1,y1");
  region = {options.crop[0], options.crop[1], options.crop[2], options.crop[3]};
  if (region.x0 < 0 || region.y0 < 0 || region.x1 > camera.width() || region.y1 > camera.height() ||
      region.x0 >= region.x1 || region.y0 >= region.y1)
    throw BadArgument(fmt::format("--crop {},{},{},{} must satisfy 0 <= x0 < x1 <= {} and 0 <= y0 < y1 <= {}",
                                  region.x0, region.y0, region.x1, region.y1, camera.width(), camera.height()));
  return region;
}

// The file's folder must exist and accept new files (outputs are renamed into place there).
void check_writable(const std::string& path, const char* option) {
  namespace fs = std::filesystem;
  const fs::path parent = fs::path(path).parent_path().empty() ? fs::path(".") : fs::path(path).parent_path();
  std::error_code error;
  if (!fs::is_directory(parent, error))
    throw BadArgument(std::string(option) + " " + path + ": the folder " + parent.string() + " does not exist");
  if (::access(parent.c_str(), W_OK) != 0)
    throw BadArgument(std::string(option) + " " + path + ": the folder " + parent.string() + " is not writable");
  if (fs::is_directory(path, error)) throw BadArgument(std::string(option) + " " + path + " is a folder");
}

// --aa-map: grey levels proportional to the samples each pixel used, white the most used (a
// pixel of one sample in an image of one sample per pixel is white too).
void write_aa_map(const RunStatistics& statistics, int width, int height, const std::string& path) {
  if (statistics.samples_per_pixel.size() != std::size_t(width) * height)
    throw BadArgument("--aa-map needs a ray-tracing method (local or whitted)");
  uint32_t most = 1;
  for (const uint32_t count : statistics.samples_per_pixel) most = std::max(most, count);
  Film map(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      map.at(x, y) = Color(double(statistics.samples_per_pixel[std::size_t(y) * width + x]) / most);
  DisplaySettings display;
  display.srgb = false;
  write_image(map, path, display);
}

std::string default_output(const RenderOptions& options) {
  if (options.scene.scene_path.empty()) return "candela-default.png";
  return std::filesystem::path(options.scene.scene_path).stem().string() + ".png";
}

int run_render(RenderOptions& options) {
  Stopwatch total;
  RunStatistics statistics;
  if (options.output.empty()) options.output = default_output(options);
  ImageFormat format;
  if (!image_format_for_path(options.output, format))
    throw BadArgument("-o " + options.output + ": unsupported extension (expected .png, .exr or .pfm)");
  if (options.threads < 0) throw BadArgument("--threads must be >= 0 (0: all cores)");
  if (options.seed && (*options.seed < 0 || *options.seed > (int64_t(1) << 53)))
    throw BadArgument("--seed must be in [0, 2^53]");
  // Fail before the work, not after it: both outputs must be writable.
  check_writable(options.output, "-o");
  if (!options.stats_path.empty()) check_writable(options.stats_path, "--stats");
  if (!options.aa_map_path.empty()) {
    ImageFormat map_format;
    if (!image_format_for_path(options.aa_map_path, map_format) || map_format != ImageFormat::png)
      throw BadArgument("--aa-map " + options.aa_map_path + ": expected a .png file");
    check_writable(options.aa_map_path, "--aa-map");
  }
  std::optional<tbb::global_control> thread_limit;
  if (options.threads > 0)
    thread_limit.emplace(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(options.threads));
  statistics.threads = static_cast<int>(
      tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));

  if (!options.accelerator.empty()) options.scene.overrides.push_back("render.accelerator=" + options.accelerator);
  Stopwatch load_timer;
  std::unique_ptr<Scene> scene = options.scene.load();
  const double build_seconds = scene->accelerator_build_seconds();
  statistics.add_phase("load", load_timer.seconds() - build_seconds);
  statistics.add_phase("build", build_seconds);
  for (const auto& warning : scene->warnings) std::cerr << "candela: warning: " << warning << "\n";
  if (!options.method.empty()) {
    scene->render.method = options.method;
    scene->render.method_location = {"--method", 0, 0, {}};
  }
  if (options.seed) scene->render.seed = static_cast<uint64_t>(*options.seed);
  const MethodEntry* entry = find_method(scene->render.method);
  if (!entry) {
    SourceLocation where = scene->render.method_location;
    if (where.file.empty()) where = {scene->source, 0, 0, "render.method"};
    throw InputError(where, "unknown method \"" + scene->render.method + "\" (expected one of: " +
                                method_names() + ")");
  }
  const std::unique_ptr<Method> method = entry->create();
  const Camera& camera = *scene->camera;

  if (!options.pixel.empty()) {
    if (options.pixel.size() != 2 || options.pixel[0] < 0 || options.pixel[1] < 0 ||
        options.pixel[0] >= camera.width() || options.pixel[1] >= camera.height())
      throw BadArgument(fmt::format("--pixel X,Y must lie in the {}x{} image", camera.width(), camera.height()));
    const auto* tracer = dynamic_cast<const RayTracingMethod*>(method.get());
    if (!tracer) throw BadArgument("--pixel needs a ray-tracing method (local or whitted)");
    Color radiance;
    const RayTree tree = tracer->pixel_ray_tree(*scene, options.pixel[0], options.pixel[1], radiance);
    std::cout << fmt::format("pixel ({}, {}) with method {}: radiance [{:.6g}, {:.6g}, {:.6g}]\n",
                             options.pixel[0], options.pixel[1], method->name(), radiance.r, radiance.g,
                             radiance.b)
              << tree.to_text();
    return 0;
  }

  const PixelRect region = region_of(options, camera);
  Film film(region.width(), region.height());
  Stopwatch render_timer;
  method->render(*scene, {region, options.quiet}, film, statistics);
  statistics.add_phase("render", render_timer.seconds());

  Stopwatch write_timer;
  write_image(film, options.output, scene->display);
  if (!options.aa_map_path.empty()) write_aa_map(statistics, film.width(), film.height(), options.aa_map_path);
  statistics.add_phase("write", write_timer.seconds());

  statistics.extra["scene"] = scene->source;
  statistics.extra["method"] = std::string(method->name());
  statistics.extra["output"] = options.output;
  statistics.extra["image"] = {{"width", film.width()}, {"height", film.height()}};
  statistics.extra["primitives"] = scene->primitives.size();
  statistics.extra["accelerator"] = std::string(scene->accelerator().name());
  statistics.extra["seed"] = scene->render.seed;
  if (!options.quiet)
    std::cerr << fmt::format("candela: wrote {} ({}x{}, {})\n", options.output, film.width(), film.height(),
                             method->name())
              << statistics.summary();
  if (!options.stats_path.empty()) {
    const std::string text = statistics.to_json().dump(2) + "\n";
    write_atomically(options.stats_path, [&](const std::string& temporary) {
      std::ofstream out(temporary);
      out << text;
      out.close();
      if (!out) throw std::runtime_error("cannot write " + options.stats_path);
    });
  }
  return 0;
}

}  // namespace

void add_render_command(CLI::App& app, std::function<int()>& run) {
  auto options = std::make_shared<RenderOptions>();
  CLI::App* command = app.add_subcommand("render", "Render a scene (the built-in default scene without SCENE)");
  command->add_option("scene", options->scene.scene_path, "Scene file (candela/1 JSON)");
  command->add_option("-o,--output", options->output, "Output image: .png (sRGB 8-bit), .exr or .pfm (linear float)");
  command->add_option("--method", options->method, "Rendering method: " + method_names());
  command->add_option("--accel", options->accelerator, "Acceleration structure (default: render.accelerator)");
  command->add_option("--threads", options->threads, "Worker threads (default: all cores)");
  command->add_option("--seed", options->seed, "Random seed (default: render.seed)");
  // One key=value per --set, repeated as often as needed, so SCENE may follow.
  command->add_option("--set", options->scene.overrides, "Override a scene setting: key=value, e.g. camera.width=640")
      ->expected(1)
      ->allow_extra_args(false)
      ->take_all();
  command->add_option("--stats", options->stats_path, "Write run statistics as JSON");
  command->add_option("--aa-map", options->aa_map_path,
                      "Write a PNG whose grey levels show the samples each pixel used (white: the most)");
  command->add_flag("-q,--quiet", options->quiet, "No progress and no summary");
  command->add_option("--crop", options->crop, "Render only pixels x0,y0 (inclusive) to x1,y1 (exclusive)")
      ->delimiter(',')->expected(4);
  command->add_option("--pixel", options->pixel, "Print the ray tree of pixel X,Y instead of rendering")
      ->delimiter(',')->expected(2);
  command->callback([options, &run]() {
    run = [options]() { return run_reporting_bad_input([&] { return run_render(*options); }); };
  });
}

}  // namespace candela::cli
