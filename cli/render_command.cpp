// candela render [SCENE] [-o FILE] [--method M] [--threads N] [--seed S] [--set k=v]...
//                [--stats FILE.json] [--quiet] [--crop x0,y0,x1,y1 | --pixelbounds x0,x1,y0,y1 |
//                --cropwindow x0,x1,y0,y1] [--spp N] [--pixel X,Y]
//                [--error-reference REF --error-log FILE.csv [--error-mask MASK] [--error-every N]]
//                [--aa-map FILE.png] [--camera NAME[,NAME...]]... [--export-solution FILE]
//                [--show-sites FILE.png] [--relight LIGHTS.json]
#include <fmt/format.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <optional>

#include "commands.h"
#include "distributed/cluster.h"
#include "image_arguments.h"
#include "integrators/antialiasing_support.h"
#include "integrators/memory_estimate.h"
#include "integrators/method_registry.h"
#include "io/checkpoint_file.h"
#include "io/image_writer.h"
#include "list_option.h"
#include "output_paths.h"
#include "radiosity/solution_export.h"
#include "scene/scene_loader.h"
#include "scene_options.h"
#include "thread_limit.h"
#include "util/atomic_file.h"
#include "util/cancellation.h"
#include "util/error.h"
#include "util/hash.h"
#include "util/input_file.h"
#include "validate/convergence_log.h"
#include "validate/image_comparison.h"
#include "validate/relight_page.h"

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
  std::vector<int> crop;            // x0,y0,x1,y1
  std::vector<int> pixel_bounds;    // pbrt's --pixelbounds x0,x1,y0,y1
  std::vector<double> crop_window;  // pbrt's --cropwindow x0,x1,y0,y1, fractions of the image
  std::vector<int> pixel;
  std::vector<std::string> cameras;  // --camera values in the order given, each NAME or NAME,NAME...
  std::string export_solution;
  std::string show_sites;
  std::string relight;
  std::string relight_page;  // the relighting page
  // The path tracer's progressive run (SPEC §12).
  std::optional<int> spp;
  std::optional<double> time;
  std::string checkpoint;
  std::optional<double> checkpoint_every;
  std::string resume;
  // The convergence log against a reference.
  std::string error_reference, error_mask, error_log;
  std::optional<int> error_every;
};

// What ties a checkpoint (path tracing, progressive radiosity) to this run: the scene file's
// bytes, the bytes of every file it referenced (meshes, textures, maps) and the --set overrides,
// except those that only say how long to go on (each method's run-length keys, which may change
// between a run and its continuation: MethodEntry::run_length_keys) or how to find the hits
// (render.accelerator: every accelerator gives the same hits).
std::string scene_fingerprint(const SceneOptions& options, const Scene& scene) {
  // The files were read (and checked) by the loader; read again here the same safe way.
  const auto file_text = [](const std::string& path) {
    return read_input_file(path, "an input of the scene", kLargeInputLimit);
  };
  const std::string text = options.scene_path.empty() ? default_scene_text() : file_text(options.scene_path);
  std::string referenced;
  for (const std::string& file : scene.input_files)
    referenced += fmt::format("{:016x}", fnv1a_64(file_text(file)));
  std::string overrides;
  for (const std::string& o : options.overrides) {
    const bool irrelevant = o.rfind("render.accelerator=", 0) == 0 || overrides_run_length(o);
    if (!irrelevant) overrides += o + "\n";
  }
  return fmt::format("scene {:016x} files {:016x} overrides {:016x}", fnv1a_64(text), fnv1a_64(referenced),
                     fnv1a_64(overrides));
}

// The pixels to render, y = 0 the top row: --crop x0,y0,x1,y1, pbrt's --pixelbounds x0,x1,y0,y1
// (the same pixels, pbrt's order) or --cropwindow x0,x1,y0,y1 in fractions of the image, which
// pbrt-v4 turns into pixels by rounding each edge up (⌈width·x0⌉ … ⌈width·x1⌉).
PixelRect region_of(const RenderOptions& options, const Camera& camera) {
  const int width = camera.width(), height = camera.height();
  PixelRect region{0, 0, width, height};
  std::string option, order;
  if (!options.crop.empty()) {
    const std::vector<int>& c = options.crop;
    region = {c[0], c[1], c[2], c[3]};
    option = fmt::format("--crop {},{},{},{}", c[0], c[1], c[2], c[3]);
    order = "x0,y0,x1,y1";
  } else if (!options.pixel_bounds.empty()) {
    const std::vector<int>& b = options.pixel_bounds;
    region = {b[0], b[2], b[1], b[3]};
    option = fmt::format("--pixelbounds {},{},{},{}", b[0], b[1], b[2], b[3]);
    order = "x0,x1,y0,y1";
  } else if (!options.crop_window.empty()) {
    const std::vector<double>& w = options.crop_window;
    option = fmt::format("--cropwindow {:g},{:g},{:g},{:g}", w[0], w[1], w[2], w[3]);
    if (!(0 <= w[0] && w[0] < w[1] && w[1] <= 1 && 0 <= w[2] && w[2] < w[3] && w[3] <= 1))
      throw BadArgument(option +
                        " must satisfy 0 <= x0 < x1 <= 1 and 0 <= y0 < y1 <= 1 (fractions of the image)");
    const auto edge = [](double fraction, int size) { return static_cast<int>(std::ceil(fraction * size)); };
    region = {edge(w[0], width), edge(w[2], height), edge(w[1], width), edge(w[3], height)};
    if (region.x0 >= region.x1 || region.y0 >= region.y1)
      throw BadArgument(fmt::format("{} holds no pixel of the {}x{} image", option, width, height));
    return region;
  } else {
    return region;
  }
  if (region.x0 < 0 || region.y0 < 0 || region.x1 > width || region.y1 > height || region.x0 >= region.x1 ||
      region.y0 >= region.y1)
    throw BadArgument(fmt::format("{} must satisfy 0 <= x0 < x1 <= {} and 0 <= y0 < y1 <= {} ({})", option,
                                  width, height, order));
  return region;
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

// One image to render: the scene's "camera" ("default") or one of its named cameras.
struct View {
  std::string name;
  std::unique_ptr<Camera>* named_camera = nullptr;  // the slot in Scene::cameras; null: "default"
  const Camera& camera(const Scene& scene) const { return named_camera ? **named_camera : *scene.camera; }
};

// Makes a view's camera the one methods render through (Scene::camera) for as long as it lives:
// the pointers are swapped, and swapped back on the way out, errors included.
class CurrentCamera {
 public:
  CurrentCamera(Scene& scene, const View& view) : scene_(scene), named_camera_(view.named_camera) {
    if (named_camera_) std::swap(scene_.camera, *named_camera_);
  }
  ~CurrentCamera() {
    if (named_camera_) std::swap(scene_.camera, *named_camera_);
  }
  CurrentCamera(const CurrentCamera&) = delete;
  CurrentCamera& operator=(const CurrentCamera&) = delete;

 private:
  Scene& scene_;
  std::unique_ptr<Camera>* named_camera_;
};

std::string camera_names(const Scene& scene) {
  std::string names = "default";
  for (const auto& named : scene.cameras) names += ", " + named.name;
  return names + (scene.cameras.empty() ? "" : " or all");
}

// --camera: names in the order given (each once); "default" is the "camera" object, "all" every
// named camera. None given: the "camera" object.
std::vector<View> select_views(const std::vector<std::string>& requested, Scene& scene) {
  std::vector<View> views;
  const auto add = [&](View view) {
    const bool seen =
        std::any_of(views.begin(), views.end(), [&](const View& v) { return v.name == view.name; });
    if (!seen) views.push_back(std::move(view));
  };
  for (const std::string& name : requested) {
    if (name.empty()) throw BadArgument("--camera: empty camera name");
    if (name == "default") {
      add({"default", nullptr});
    } else if (name == "all") {
      if (scene.cameras.empty())
        throw BadArgument("--camera all: the scene has no named cameras (no \"cameras\" array)");
      for (auto& named : scene.cameras) add({named.name, &named.camera});
    } else {
      const auto found = std::find_if(scene.cameras.begin(), scene.cameras.end(),
                                      [&](const NamedCamera& named) { return named.name == name; });
      if (found == scene.cameras.end())
        throw BadArgument("--camera " + name + ": unknown camera (expected one of: " + camera_names(scene) +
                          ")");
      add({found->name, &found->camera});
    }
  }
  if (views.empty()) views.push_back({"default", nullptr});
  return views;
}

// With several views each output gets the camera's name: out.png → out-front.png.
// out.png → out-NAME.png (empty stays empty).
std::string path_with_suffix(const std::string& path, const std::string& name) {
  if (path.empty()) return path;
  const std::filesystem::path original(path);
  return (original.parent_path() / (original.stem().string() + "-" + name + original.extension().string()))
      .string();
}

std::string path_for_view(const std::string& path, const View& view, std::size_t view_count) {
  return view_count == 1 ? path : path_with_suffix(path, view.name);
}

void write_statistics(const RunStatistics& statistics, const std::string& path) {
  write_text_atomically(path, statistics.to_json().dump(2) + "\n");
}

// After Ctrl-C, once the image in progress (and its statistics) is written: says what it holds,
// where the checkpoint is, and what was skipped. Returns the exit status.
int report_interrupted(const RunStatistics& statistics, const std::string& output, std::size_t skipped) {
  const nlohmann::json& extra = statistics.extra;
  const bool partial = extra.value("interrupted", false);
  std::string message = partial ? "interrupted: partial result" : "interrupted: finished result";
  if (partial && extra.contains("completed") && extra["completed"].is_string())
    message += " (" + extra["completed"].get<std::string>() + ")";
  message += " written to " + output;
  if (extra.contains("checkpoint") && extra["checkpoint"].is_string())
    message += "; checkpoint " + extra["checkpoint"].get<std::string>() + " (continue with --resume " +
               extra["checkpoint"].get<std::string>() + ")";
  if (skipped > 0) message += fmt::format("; {} more image{} not rendered", skipped, skipped == 1 ? "" : "s");
  std::cerr << "candela: " << message << "\n";
  return kInterruptedExitCode;
}

// Ctrl-C between images: nothing of the next one is begun.
int report_interrupted_before(std::size_t skipped, const char* what) {
  std::cerr << fmt::format("candela: interrupted: {} more {}{} not rendered\n", skipped, what,
                           skipped == 1 ? "" : "s");
  return kInterruptedExitCode;
}

// An image with pixels that are not finite (or beyond a float for .exr/.pfm) comes from
// legal values whose product overflowed: bad input — the scene's — refused before anything of the
// image is written.
void refuse_unwritable_image(const Film& film, const std::string& output, const Scene& scene) {
  ImageFormat format = ImageFormat::png;
  image_format_for_path(output, format);
  if (const std::string problem = non_finite_image_problem(film, format, scene.display.exposure);
      !problem.empty())
    throw InputError({scene.source, 0, 0, {}}, problem);
}

// The files a run of several images (views, relight frames) has written, so that a
// failure in one image says which images are complete, what of the failing one was written and
// what was not rendered — each file is whole (written atomically), but a set can be unfinished.
struct WrittenImages {
  std::vector<std::string> finished;  // "out-a.png (camera a)"; each with all of its files
  std::vector<std::string> current;   // the files of the image in progress written so far

  void wrote(const std::string& path) { current.push_back(path); }
  void finish(const std::string& image) {
    finished.push_back(image);
    current.clear();
  }
  // Printed before the error itself (rethrown by the caller): only when there was more than one image.
  void report_failure(const std::string& image, std::size_t not_rendered, std::size_t images) const {
    if (images <= 1) return;
    const auto join = [](const std::vector<std::string>& items) {
      std::string text;
      for (const std::string& item : items) text += (text.empty() ? "" : ", ") + item;
      return text;
    };
    std::string message = "candela: " + image + " failed (the error follows)";
    message +=
        finished.empty() ? "; no image was finished before it" : "; finished before it: " + join(finished);
    if (!current.empty()) message += "; of " + image + " only " + join(current) + " was written";
    if (not_rendered > 0)
      message += fmt::format("; {} more image{} not rendered", not_rendered, not_rendered == 1 ? "" : "s");
    std::cerr << message << "\n";
  }
};

// "--export-solution needs --method radiosity (the method is whitted)": the methods that can, from
// their capabilities.
[[noreturn]] void refuse_option(const std::string& option_needs, bool MethodCapabilities::*capability,
                                const MethodEntry& entry) {
  const std::vector<std::string_view> able = method_names_with(capability);
  std::string names;
  for (std::size_t i = 0; i < able.size(); ++i)
    names += (i == 0 ? "" : i + 1 == able.size() ? " or " : ", ") + std::string(able[i]);
  throw BadArgument(option_needs + " --method " + names + " (the method is " + std::string(entry.name) + ")");
}

int print_pixel_ray_trees(const RenderOptions& options, Scene& scene, const std::vector<View>& views,
                          const Method& method) {
  for (const View& view : views) {
    const Camera& camera = view.camera(scene);
    if (options.pixel.size() != 2 || options.pixel[0] < 0 || options.pixel[1] < 0 ||
        options.pixel[0] >= camera.width() || options.pixel[1] >= camera.height())
      throw BadArgument(fmt::format("--pixel X,Y must lie in the {}x{} image{}", camera.width(),
                                    camera.height(),
                                    views.size() > 1 ? " of camera " + view.name : std::string()));
  }
  for (const View& view : views) {
    const CurrentCamera current(scene, view);
    Color radiance;
    const RayTree tree = method.pixel_ray_tree(scene, options.pixel[0], options.pixel[1], radiance);
    if (views.size() > 1) std::cout << "camera " << view.name << ":\n";
    std::cout << fmt::format("pixel ({}, {}) with method {}: radiance [{:.6g}, {:.6g}, {:.6g}]\n",
                             options.pixel[0], options.pixel[1], method.name(), radiance.r, radiance.g,
                             radiance.b)
              << tree.to_text();
  }
  return 0;
}

// One image of `method`: its figures are added to `statistics` (after any phases already there),
// with the thread count and the render's time.
RenderResult timed_render(const Method& method, const Scene& scene, const RenderRequest& request, int threads,
                          RunStatistics& statistics) {
  Stopwatch render_timer;
  RenderResult result = method.render(scene, request);
  statistics.threads = threads;
  statistics.absorb(std::move(result.statistics));
  statistics.add_phase("render", render_timer.seconds());
  return result;
}

// Everything a render needs, checked and loaded before the first image is begun.
struct RenderJob {
  std::optional<tbb::global_control> thread_limit;
  int threads = 0;
  std::vector<LightSetup> relight_frames;
  double load_seconds = 0, build_seconds = 0;
  std::unique_ptr<Scene> scene;
  const MethodEntry* entry = nullptr;
  std::vector<View> views;
  std::unique_ptr<Method> method;
  std::vector<PixelRect> regions;
  std::string fingerprint;
  std::optional<ConvergenceLog> convergence;  // --error-log
  std::vector<RelightPageFrame> page_frames;  // --relight-page: every frame written, in order
  nlohmann::json precomputation;              // --relight-page: the first render's meshless facts
};

// A relight frame's albedo edits — each named material's kd replaced by the frame's
// constant, and put back by undo() or at the latest when the frame's scope ends (an exception).
class AlbedoEditsInPlace {
 public:
  AlbedoEditsInPlace(Scene& scene, const std::vector<AlbedoEdit>& edits) : scene_(scene) {
    const std::vector<std::size_t> targets = find_albedo_edit_targets(scene, edits);
    for (std::size_t e = 0; e < targets.size(); ++e) {
      Material& material = scene.materials[targets[e]];
      kept_.emplace_back(targets[e], material.kd);
      material.kd = constant_texture(edits[e].kd);
      material.prepare();
    }
  }
  AlbedoEditsInPlace(const AlbedoEditsInPlace&) = delete;
  AlbedoEditsInPlace& operator=(const AlbedoEditsInPlace&) = delete;
  ~AlbedoEditsInPlace() { undo(); }
  void undo() {
    // In reverse, so that a material named twice gets its own kd back.
    for (auto kept = kept_.rbegin(); kept != kept_.rend(); ++kept) {
      Material& material = scene_.materials[kept->first];
      material.kd = kept->second;
      material.prepare();
    }
    kept_.clear();
  }

 private:
  Scene& scene_;
  std::vector<std::pair<std::size_t, std::shared_ptr<const Texture>>> kept_;
};

// The relighting page's line for a frame just rendered (rank 0).
RelightPageFrame relight_page_frame(const std::string& name, const std::string& image,
                                    const std::string& page,
                                    const std::vector<std::unique_ptr<Light>>& lights, const Color& ambient,
                                    const std::optional<RelightingCost>& cost, double seconds) {
  RelightPageFrame frame;
  frame.name = name;
  const std::filesystem::path folder = std::filesystem::absolute(page).parent_path();
  frame.image = std::filesystem::absolute(image).lexically_relative(folder).generic_string();
  std::map<std::string, int> kinds;
  for (const auto& light : lights) ++kinds[std::string(light->type_name())];
  for (const auto& [kind, count] : kinds)
    frame.lights += (frame.lights.empty() ? "" : ", ") + fmt::format("{} {}", count, kind);
  if (!ambient.is_black()) frame.lights += frame.lights.empty() ? "ambient" : " and ambient";
  if (frame.lights.empty()) frame.lights = "emissive surfaces only";
  if (cost) {
    frame.lighting_seconds = cost->lighting_seconds;
    frame.iterations = static_cast<int>(cost->iterations);
  }
  frame.frame_seconds = seconds;
  return frame;
}

// --error-reference, --error-mask: the reference in the units the method's film holds (the
// scene's film.exposure, which render -o applied to it, undone) and the mask, both the size of the
// image rendered. Throws BadArgument.
ConvergenceLog convergence_log_for(const RenderOptions& options, const MethodEntry& entry, const Scene& scene,
                                   const PixelRect& region) {
  const LinearImage reference =
      read_image_argument(options.error_reference, "--error-reference " + options.error_reference);
  if (reference.srgb_decoded)
    throw BadArgument(
        "--error-reference " + options.error_reference +
        ": an 8-bit display image is no linear reference; use one render wrote as .exr, .pfm or .hdr");
  check_image_size(reference.film, "--error-reference", options.error_reference, region.width(),
                   region.height(), "the image rendered");
  std::vector<uint8_t> mask;
  if (!options.error_mask.empty())
    mask = read_mask_argument(options.error_mask, "--error-mask", region.width(), region.height(),
                              "the image rendered");
  return ConvergenceLog(std::string(entry.name), exposure_undone(reference.film, scene.display.exposure),
                        std::move(mask));
}

// Every file the run writes: each checked writable as it is named (on the rank that writes), and
// all of them checked against the run's inputs once the scene is loaded.
class RunOutputs {
 public:
  explicit RunOutputs(bool writes_outputs) : writes_outputs_(writes_outputs) {}
  void check_writable(const std::string& path, const char* option) {
    if (writes_outputs_) cli::check_writable(path, option);
    files_.push_back({path, option});
  }
  bool written_here() const { return writes_outputs_; }
  const std::vector<OutputFile>& files() const { return files_; }

 private:
  bool writes_outputs_;
  std::vector<OutputFile> files_;
};

// -o (named after the scene when not given), --seed and the files written besides the image: each
// format known, each file writable. Returns the format of -o.
ImageFormat check_output_options(RenderOptions& options, RunOutputs& outputs) {
  if (options.output.empty()) options.output = default_output(options);
  ImageFormat format;
  if (!image_format_for_path(options.output, format))
    throw BadArgument("-o " + options.output + ": unsupported extension (expected " + kImageExtensions + ")");
  if (options.seed && (*options.seed < 0 || *options.seed > (int64_t(1) << 53)))
    throw BadArgument("--seed must be in [0, 2^53]");
  outputs.check_writable(options.output, "-o");
  if (!options.stats_path.empty()) outputs.check_writable(options.stats_path, "--stats");
  if (!options.aa_map_path.empty()) {
    ImageFormat map_format;
    if (!image_format_for_path(options.aa_map_path, map_format) || map_format != ImageFormat::png)
      throw BadArgument("--aa-map " + options.aa_map_path + ": expected a .png file");
    outputs.check_writable(options.aa_map_path, "--aa-map");
  }
  if (!options.show_sites.empty()) {
    ImageFormat sites_format;
    if (!image_format_for_path(options.show_sites, sites_format))
      throw BadArgument("--show-sites " + options.show_sites + ": unsupported extension (expected " +
                        kImageExtensions + ")");
    outputs.check_writable(options.show_sites, "--show-sites");
  }
  if (!options.export_solution.empty()) {
    SolutionFormat solution_format;
    if (!solution_format_for_path(options.export_solution, solution_format))
      throw BadArgument("--export-solution " + options.export_solution +
                        ": unsupported extension (expected .csv, .ply or .gltf)");
    outputs.check_writable(options.export_solution, "--export-solution");
  }
  return format;
}

// How long the run goes on (--spp, --time, --checkpoint-every: settings of the methods that take
// them), --accel, --checkpoint, the convergence log's options and the checkpoint to resume.
void check_run_options(RenderOptions& options, RunOutputs& outputs) {
  if (!options.accelerator.empty())
    options.scene.overrides.push_back("render.accelerator=" + options.accelerator);
  if (options.spp && (*options.spp < 1 || *options.spp > (1 << 24)))
    throw BadArgument("--spp must be in [1, 16777216]");
  if (options.time && (!(*options.time > 0) || !std::isfinite(*options.time)))
    throw BadArgument("--time must be a number of seconds > 0");
  if (options.checkpoint_every && !(*options.checkpoint_every > 0))
    throw BadArgument("--checkpoint-every must be a number of seconds > 0");
  // The methods that take them say which of their settings the run limits set (the registry).
  for (std::string& assignment : run_limit_overrides({options.spp, options.time, options.checkpoint_every}))
    options.scene.overrides.push_back(std::move(assignment));
  if (!options.checkpoint.empty()) outputs.check_writable(options.checkpoint, "--checkpoint");
  const bool logs_error = !options.error_log.empty();
  if (logs_error != !options.error_reference.empty())
    throw BadArgument(
        "--error-log and --error-reference go together (the log measures against the reference)");
  if (!logs_error && (!options.error_mask.empty() || options.error_every))
    throw BadArgument("--error-mask and --error-every need --error-log and --error-reference");
  if (options.error_every && *options.error_every < 1) throw BadArgument("--error-every must be at least 1");
  if (logs_error) outputs.check_writable(options.error_log, "--error-log");
  if (logs_error && world_cluster().distributed())
    throw BadArgument("--error-log runs in one process (start it without mpirun)");
  // Rank 0 alone reads the checkpoint: it need not be on the other ranks' disks.
  // A folder or a FIFO is named as what it is, not "no such file".
  if (!options.resume.empty() && outputs.written_here()) {
    std::error_code error;
    if (!std::filesystem::exists(options.resume, error))
      throw BadArgument("--resume " + options.resume + ": no such checkpoint file");
    if (const std::string problem = input_file_problem(options.resume, "the checkpoint", kLargeInputLimit);
        !problem.empty())
      throw BadArgument("--resume " + options.resume + ": " + problem);
  }
}

// Loads the scene (printing its warnings and the relight frames'), with --method and --seed in
// place, and finds its method.
void load_scene_and_method(const RenderOptions& options, RenderJob& job) {
  Stopwatch load_timer;
  job.scene = options.scene.load();
  Scene& scene = *job.scene;
  job.build_seconds = scene.accelerator_build_seconds();
  job.load_seconds = load_timer.seconds() - job.build_seconds;
  for (const auto& warning : scene.warnings) std::cerr << "candela: warning: " << warning << "\n";
  // A frame's warnings as the scene's (a sun below the horizon rendered black unannounced).
  for (const LightSetup& frame : job.relight_frames)
    for (const auto& warning : frame.warnings)
      std::cerr << fmt::format("candela: warning: {}: frame {}: {}\n", options.relight, frame.name, warning);
  if (!options.method.empty()) {
    scene.render.method = options.method;
    scene.render.method_location = {"--method", 0, 0, {}};
  }
  if (options.seed) scene.render.seed = static_cast<uint64_t>(*options.seed);
  job.entry = find_method(scene.render.method);
  if (!job.entry) {
    SourceLocation where = scene.render.method_location;
    if (where.file.empty()) where = {scene.source, 0, 0, "render.method"};
    throw InputError(
        where, "unknown method \"" + scene.render.method + "\" (expected one of: " + method_names() + ")");
  }
}

// An output the method cannot give would be silently missing: refused before any work. Also sets
// --spp as the anti-aliasing samples of a method without passes; returns true when their mode is
// left to choose_jittered_where_possible once the method is made.
bool check_options_against_method(const RenderOptions& options, RenderJob& job) {
  const MethodEntry& entry = *job.entry;
  const MethodCapabilities& can = entry.capabilities;
  if (!options.export_solution.empty() && !can.solution)
    refuse_option("--export-solution needs", &MethodCapabilities::solution, entry);
  if (!options.show_sites.empty() && !can.sites_image)
    refuse_option("--show-sites needs", &MethodCapabilities::sites_image, entry);
  if (options.time && !can.progressive_passes)
    refuse_option("--time needs", &MethodCapabilities::progressive_passes, entry);
  // --spp for the other methods: their anti-aliasing samples (pbrt's --spp).
  bool choose_mode = false;
  if (options.spp && !can.progressive_passes) try {
      choose_mode = set_samples_per_pixel(*job.scene, entry.name, *options.spp);
    } catch (const std::invalid_argument& e) {
      throw BadArgument(std::string("--spp ") + e.what());
    }
  const bool checkpoint_options =
      !options.checkpoint.empty() || options.checkpoint_every || !options.resume.empty();
  if (checkpoint_options && !can.checkpoints)
    refuse_option("--checkpoint, --checkpoint-every and --resume need", &MethodCapabilities::checkpoints,
                  entry);
  if (!job.relight_frames.empty() && !can.relighting)
    refuse_option("--relight needs", &MethodCapabilities::relighting, entry);
  return choose_mode;
}

// --relight-page, and each relight frame's materials and files, before any work.
void check_relight_outputs(const RenderOptions& options, const RenderJob& job, ImageFormat format,
                           RunOutputs& outputs) {
  if (!options.relight_page.empty()) {
    if (job.relight_frames.empty()) throw BadArgument("--relight-page needs --relight");
    if (format != ImageFormat::png)
      throw BadArgument("--relight-page shows the frames in a browser: -o must name a .png, not " +
                        options.output);
    if (std::filesystem::path(options.relight_page).extension() != ".html")
      throw BadArgument("--relight-page " + options.relight_page + ": expected a .html file");
    outputs.check_writable(options.relight_page, "--relight-page");
  }
  for (const LightSetup& frame : job.relight_frames) {
    find_albedo_edit_targets(*job.scene, frame.albedo_edits);  // every material named, before any work
    outputs.check_writable(path_with_suffix(options.output, frame.name), "-o");
    if (!options.stats_path.empty())
      outputs.check_writable(path_with_suffix(options.stats_path, frame.name), "--stats");
  }
}

// Every view's region and outputs are checked before the first image is rendered.
void check_views(const RenderOptions& options, RenderJob& job, RunOutputs& outputs) {
  const std::vector<View>& views = job.views;
  Scene& scene = *job.scene;
  for (const View& view : views) {
    try {
      job.regions.push_back(region_of(options, view.camera(scene)));
    } catch (const BadArgument& e) {
      if (views.size() == 1) throw;
      throw BadArgument(std::string(e.what()) + " (camera " + view.name + ")");
    }
    {  // What the method would hold for this view, against render.memory_limit_mib.
      const CurrentCamera current(scene, view);
      RenderRequest request;
      request.region = job.regions.back();
      refuse_beyond_memory_limit(*job.method, scene, request);
    }
    outputs.check_writable(path_for_view(options.output, view, views.size()), "-o");
    if (!options.stats_path.empty())
      outputs.check_writable(path_for_view(options.stats_path, view, views.size()), "--stats");
    if (!options.aa_map_path.empty())
      outputs.check_writable(path_for_view(options.aa_map_path, view, views.size()), "--aa-map");
    if (!options.show_sites.empty())
      outputs.check_writable(path_for_view(options.show_sites, view, views.size()), "--show-sites");
    if (!options.checkpoint.empty())
      outputs.check_writable(path_for_view(options.checkpoint, view, views.size()), "--checkpoint");
  }
}

// Every file the run reads: the scene and the files it references, --relight and its frames'
// luminaire files, the convergence log's reference and mask, and the checkpoint resumed.
std::vector<std::string> run_inputs(const RenderOptions& options, const RenderJob& job) {
  std::vector<std::string> inputs = job.scene->input_files;
  inputs.push_back(options.scene.scene_path);
  inputs.push_back(options.relight);
  inputs.push_back(options.error_reference);
  inputs.push_back(options.error_mask);
  for (const LightSetup& frame : job.relight_frames)  // the frames' luminaire files
    inputs.insert(inputs.end(), frame.input_files.begin(), frame.input_files.end());
  // Resuming from the checkpoint it goes on writing is how a run continues (read whole first).
  std::error_code error;
  if (!options.resume.empty() && !(options.resume == options.checkpoint ||
                                   std::filesystem::equivalent(options.resume, options.checkpoint, error)))
    inputs.push_back(options.resume);
  return inputs;
}

// Checks the options, loads the scene and makes the method; throws on bad input. Ranks other
// than 0 check no outputs: only rank 0 writes.
void prepare_render(RenderOptions& options, RenderJob& job, bool writes_outputs) {
  // Fail before the work, not after it: every output must be writable.
  RunOutputs outputs(writes_outputs);
  const ImageFormat format = check_output_options(options, outputs);
  // 002 §5.3: light set-ups rendered from one geometry; read (and refused) before anything else.
  if (!options.relight.empty()) job.relight_frames = load_light_setups(options.relight);
  limit_threads(options.threads, job.thread_limit);  // lives as long as the job
  job.threads =
      static_cast<int>(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));

  check_run_options(options, outputs);
  load_scene_and_method(options, job);
  const bool choose_mode = check_options_against_method(options, job);
  job.views = select_views(options.cameras, *job.scene);
  if (!options.resume.empty() && job.views.size() != 1)
    throw BadArgument("--resume continues one camera's image, not " + std::to_string(job.views.size()));
  if (!job.relight_frames.empty() && job.views.size() != 1)
    throw BadArgument("--relight renders one camera, not " + std::to_string(job.views.size()));
  check_relight_outputs(options, job, format, outputs);
  // One method object renders every view, so what it keeps between renders (a radiosity
  // solution) is computed once.
  const MethodEntry& entry = *job.entry;
  job.method = create_method(entry, *job.scene);
  if (choose_mode) choose_jittered_where_possible(*job.scene, *job.method);
  const MethodCapabilities& can = entry.capabilities;
  if (!options.aa_map_path.empty() && !can.samples_per_pixel)
    refuse_option("--aa-map needs", &MethodCapabilities::samples_per_pixel, entry);
  if (!options.pixel.empty()) {  // printed instead of rendering: checked here, printed by the caller
    if (!can.ray_trees) refuse_option("--pixel needs", &MethodCapabilities::ray_trees, entry);
    return;
  }

  check_views(options, job, outputs);
  if (!options.error_log.empty()) {
    if (job.views.size() != 1 || !job.relight_frames.empty())
      throw BadArgument("--error-log measures one image: one camera and no --relight");
    job.convergence = convergence_log_for(options, entry, *job.scene, job.regions.front());
  }
  // No output may be an input of the run, nor two outputs one file.
  if (writes_outputs) refuse_outputs_over_inputs(outputs.files(), run_inputs(options, job));
  job.fingerprint = can.checkpoints ? scene_fingerprint(options.scene, *job.scene) : std::string();
}

// Distributed runs: every rank prepares the same job; then they agree, so that a rank
// whose set-up failed does not leave the others waiting for it. An error on rank 0 is reported by
// rank 0 alone (the others had the same input); an error only elsewhere is reported by that rank.
void prepare_everywhere(RenderOptions& options, RenderJob& job, Cluster& cluster) {
  std::exception_ptr error;
  try {
    prepare_render(options, job, cluster.root());
  } catch (...) {
    if (!cluster.distributed()) throw;
    error = std::current_exception();
  }
  if (!cluster.distributed() || cluster.all(!error)) return;
  Bytes root_failed(1, std::byte{cluster.root() && error ? uint8_t{1} : uint8_t{0}});
  cluster.broadcast(root_failed);
  if (cluster.root()) {
    if (error) std::rethrow_exception(error);
    print_error("another rank could not set up the render (its error is above)");
    throw PeerFailure(2);
  }
  if (error && root_failed[0] == std::byte{0}) {
    try {
      std::rethrow_exception(error);
    } catch (const std::exception& e) {
      std::cerr << fmt::format("candela: error (rank {}): {}\n", cluster.rank(), e.what());
    }
  }
  throw PeerFailure(2);
}

// Rank 0, after the last frame: the relighting page, with the precomputation the first render
// reported (its meshless facts) and every frame written.
void write_relight_page(const RenderOptions& options, const RenderJob& job) {
  const nlohmann::json& m = job.precomputation;
  RelightPage page;
  page.title = "Relighting " + job.scene->source + " (meshless radiosity)";
  page.facts = {
      {"sites", fmt::format("{}", m.value("sites", 0))},
      {"transport", fmt::format("{} ({} levels)", m.value("transport", std::string("flat")),
                                m.value("hierarchy_levels", 1))},
      {"entries of S", fmt::format("{} ({} cluster links, {:.1f} MiB)", m.value("transfer_entries", 0),
                                   m.value("cluster_links", 0), m.value("transfer_memory_mib", 0.0))},
      {"precomputation (s)",
       fmt::format("{:.2f}: sites {:.2f}, effective areas {:.2f}, hierarchy {:.2f}, S {:.2f}",
                   m.value("sampling_seconds", 0.0) + m.value("area_seconds", 0.0) +
                       m.value("hierarchy_seconds", 0.0) + m.value("transfer_seconds", 0.0),
                   m.value("sampling_seconds", 0.0), m.value("area_seconds", 0.0),
                   m.value("hierarchy_seconds", 0.0), m.value("transfer_seconds", 0.0))},
      {"frames", fmt::format("{}", job.page_frames.size())}};
  page.frames = job.page_frames;
  write_text_atomically(options.relight_page, relight_page_html(page));
  if (!options.quiet)
    std::cerr << fmt::format("candela: wrote {} ({} frames)\n", options.relight_page, page.frames.size());
}

// Renders a prepared job's images one at a time, the views and then the relight frames: every rank
// renders each image, rank 0 writes its files and notes them in `written`. Each image's step returns
// the exit status when the run ends with it (interrupted), nothing when the next image follows.
class ImageRenderer {
 public:
  ImageRenderer(const RenderOptions& options, RenderJob& job, Cluster& cluster, WrittenImages& written)
      : options_(options),
        job_(job),
        scene_(*job.scene),
        method_(*job.method),
        cluster_(cluster),
        root_(cluster.root()),
        written_(written) {}

  std::optional<int> render_view(std::size_t v);
  std::optional<int> render_frame(std::size_t f);

 private:
  // With several ranks they stop together: Ctrl-C on any of them counts (a collective).
  bool interrupted() const { return cancelled_anywhere(cluster_); }
  RenderRequest view_request(const View& view, const PixelRect& region, const std::string& checkpoint_path);
  void write_view_files(const View& view, std::size_t v, const RenderResult& result,
                        const std::string& output, const std::string& checkpoint_path,
                        RunStatistics& statistics);
  void write_convergence_log(const Film& film, RunStatistics& statistics);
  void describe_view(const View& view, const std::string& output, const Film& film,
                     RunStatistics& statistics) const;
  std::string write_frame(const LightSetup& frame, const RenderResult& result, const Stopwatch& frame_timer,
                          RunStatistics& statistics);

  const RenderOptions& options_;
  RenderJob& job_;
  Scene& scene_;
  const Method& method_;
  Cluster& cluster_;
  const bool root_;
  WrittenImages& written_;
};

std::optional<int> ImageRenderer::render_view(std::size_t v) {
  const std::vector<View>& views = job_.views;
  const View& view = views[v];
  if (interrupted())
    return root_ ? report_interrupted_before(views.size() - v, "view") : kInterruptedExitCode;
  const std::string output = path_for_view(options_.output, view, views.size());
  const std::string stats_path = path_for_view(options_.stats_path, view, views.size());
  const CurrentCamera current(scene_, view);
  const std::string checkpoint_path =
      options_.checkpoint.empty() ? std::string() : path_for_view(options_.checkpoint, view, views.size());
  const RenderRequest request = view_request(view, job_.regions[v], checkpoint_path);
  RunStatistics statistics;
  // Loading and building are done once, before the first view: they count in its statistics
  // alone, so the views' total_seconds add up to the run's.
  if (v == 0) {
    statistics.add_phase("load", job_.load_seconds);
    statistics.add_phase("build", job_.build_seconds);
  }
  const Stopwatch view_timer;
  const RenderResult result = timed_render(method_, scene_, request, job_.threads, statistics);
  // A method's warning about its result (the path tracer: nothing emits light).
  const auto& method_facts = statistics.extra[std::string(method_.name())];
  if (root_ && method_facts.is_object() && method_facts.contains("warning"))
    std::cerr << "candela: warning: " << method_facts["warning"].get<std::string>() << "\n";
  if (!root_) {  // rank 0 holds the image and writes everything
    if (interrupted()) return kInterruptedExitCode;
    return std::nullopt;
  }

  write_view_files(view, v, result, output, checkpoint_path, statistics);
  describe_view(view, output, result.film, statistics);
  if (!options_.relight_page.empty())
    job_.page_frames.push_back(relight_page_frame("scene", output, options_.relight_page, scene_.lights,
                                                  scene_.ambient, result.relighting, view_timer.seconds()));
  if (!options_.relight_page.empty())
    job_.precomputation = statistics.extra.value(std::string(method_.name()), nlohmann::json());
  if (!stats_path.empty()) write_statistics(statistics, stats_path);
  written_.finish(output + " (camera " + view.name + ")");
  if (interrupted())
    return report_interrupted(statistics, output, views.size() - v - 1 + job_.relight_frames.size());
  return std::nullopt;
}

RenderRequest ImageRenderer::view_request(const View& view, const PixelRect& region,
                                          const std::string& checkpoint_path) {
  RenderRequest request;
  request.region = region;
  request.quiet = options_.quiet;
  request.sites_image = !options_.show_sites.empty();
  // The method hands out its checkpoints; rank 0 writes them and alone reads the one resumed.
  request.checkpoint = !checkpoint_path.empty();
  if (request.checkpoint && root_)
    request.save_checkpoint = [checkpoint_path](const Bytes& sealed) {
      write_checkpoint_file(checkpoint_path, sealed);
    };
  if (!options_.resume.empty())
    request.resume = root_ ? read_checkpoint_file(options_.resume) : SealedCheckpoint{options_.resume, {}};
  // A view-independent solution (radiosity) is the same for every view; an image is not.
  const std::string& fingerprint = job_.fingerprint;
  request.fingerprint =
      job_.entry->capabilities.solution ? fingerprint : fingerprint + " camera " + view.name;
  if (options_.checkpoint_every) request.checkpoint_interval = *options_.checkpoint_every;
  request.cluster = &cluster_;
  if (job_.convergence) {
    job_.convergence->start();
    request.on_progress = job_.convergence->observer();
    if (options_.error_every) request.progress_every = static_cast<uint64_t>(*options_.error_every);
  }
  return request;
}

// Rank 0: the view's image and every file the method gave with it, each noted in `written_` once
// written and named in the statistics.
void ImageRenderer::write_view_files(const View& view, std::size_t v, const RenderResult& result,
                                     const std::string& output, const std::string& checkpoint_path,
                                     RunStatistics& statistics) {
  const Film& film = result.film;
  const std::size_t view_count = job_.views.size();
  refuse_unwritable_image(film, output, scene_);
  Stopwatch write_timer;
  if (result.checkpoint) {
    write_checkpoint_file(checkpoint_path, *result.checkpoint);
    written_.wrote(checkpoint_path);
    statistics.extra["checkpoint"] = checkpoint_path;
  }
  write_image(film, output, scene_.display);
  written_.wrote(output);
  if (job_.convergence) write_convergence_log(film, statistics);
  const std::string aa_map_path = path_for_view(options_.aa_map_path, view, view_count);
  if (!aa_map_path.empty()) {
    write_aa_map(statistics, film.width(), film.height(), aa_map_path);
    written_.wrote(aa_map_path);
  }
  nlohmann::json& method_facts_out = statistics.extra[std::string(method_.name())];
  if (result.sites_image) {
    const std::string sites_path = path_for_view(options_.show_sites, view, view_count);
    write_image(*result.sites_image, sites_path, scene_.display);
    written_.wrote(sites_path);
    method_facts_out["sites_image"] = sites_path;
  }
  // The solution is the same for every view: written once, with the first.
  if (v == 0 && !options_.export_solution.empty() && result.solution) {
    export_solution(*result.solution, options_.export_solution, scene_.display);
    written_.wrote(options_.export_solution);
    method_facts_out["exported_to"] = options_.export_solution;
  }
  statistics.add_phase("write", write_timer.seconds());
}

// --error-log: the final image's row ends the log, which is written whole.
void ImageRenderer::write_convergence_log(const Film& film, RunStatistics& statistics) {
  ConvergenceLog& convergence = *job_.convergence;
  convergence.finish(film);
  write_text_atomically(options_.error_log, convergence_csv(convergence.rows()));
  written_.wrote(options_.error_log);
  const ConvergenceRow& last = convergence.rows().back();
  statistics.extra["error_log"] = {{"file", options_.error_log},
                                   {"rows", convergence.rows().size()},
                                   {"final_rmse", last.rmse},
                                   {"final_relative_mse", last.relative_mse},
                                   {"log_seconds", convergence.overhead_seconds()}};
}

// The view's facts in its statistics, and its summary printed (without --quiet).
void ImageRenderer::describe_view(const View& view, const std::string& output, const Film& film,
                                  RunStatistics& statistics) const {
  statistics.extra["scene"] = scene_.source;
  statistics.extra["camera"] = view.name;
  statistics.extra["method"] = std::string(method_.name());
  statistics.extra["emitters"] = emitter_facts(scene_, *job_.entry);
  statistics.extra["output"] = output;
  statistics.extra["image"] = {{"width", film.width()}, {"height", film.height()}};
  statistics.extra["primitives"] = scene_.primitives.size();
  statistics.extra["accelerator"] = std::string(scene_.accelerator().name());
  statistics.extra["seed"] = scene_.render.seed;
  if (!options_.quiet)
    std::cerr << fmt::format("candela: wrote {} ({}x{}, {}{})\n", output, film.width(), film.height(),
                             method_.name(), job_.views.size() > 1 ? ", camera " + view.name : std::string())
              << statistics.summary();
  statistics.extra["ranks"] = cluster_.size();
}

std::optional<int> ImageRenderer::render_frame(std::size_t f) {
  std::vector<LightSetup>& frames = job_.relight_frames;
  LightSetup& frame = frames[f];
  if (interrupted())
    return root_ ? report_interrupted_before(frames.size() - f, "frame") : kInterruptedExitCode;
  std::swap(scene_.lights, frame.lights);
  std::swap(scene_.ambient, frame.ambient);
  // The frame's albedo edits, undone when the frame ends however it ends (the
  // geometry and S are reused).
  AlbedoEditsInPlace edits(scene_, frame.albedo_edits);
  const CurrentCamera current(scene_, job_.views.front());
  RenderRequest request;
  request.region = job_.regions.front();
  request.quiet = options_.quiet;
  request.cluster = &cluster_;
  Stopwatch frame_timer;
  RunStatistics statistics;
  const RenderResult result = timed_render(method_, scene_, request, job_.threads, statistics);
  edits.undo();
  std::swap(scene_.lights, frame.lights);
  std::swap(scene_.ambient, frame.ambient);
  if (!root_) {
    if (interrupted()) return kInterruptedExitCode;
    return std::nullopt;
  }
  const std::string output = write_frame(frame, result, frame_timer, statistics);
  written_.finish(output + " (frame " + frame.name + ")");
  if (interrupted()) return report_interrupted(statistics, output, frames.size() - f - 1);
  return std::nullopt;
}

// Rank 0: the frame's image, its statistics and its line of the relighting page. Returns the image's
// path.
std::string ImageRenderer::write_frame(const LightSetup& frame, const RenderResult& result,
                                       const Stopwatch& frame_timer, RunStatistics& statistics) {
  const Film& film = result.film;
  const std::string output = path_with_suffix(options_.output, frame.name);
  refuse_unwritable_image(film, output, scene_);
  Stopwatch write_timer;
  write_image(film, output, scene_.display);
  written_.wrote(output);
  statistics.add_phase("write", write_timer.seconds());
  statistics.extra["scene"] = scene_.source;
  statistics.extra["relight_frame"] = frame.name;
  statistics.extra["method"] = std::string(method_.name());
  statistics.extra["output"] = output;
  if (!options_.quiet)
    std::cerr << fmt::format("candela: relit frame {} in {:.3f} s (lighting {:.3f} s), wrote {}\n",
                             frame.name, frame_timer.seconds(),
                             result.relighting ? result.relighting->lighting_seconds : 0.0, output);
  if (!options_.stats_path.empty())
    write_statistics(statistics, path_with_suffix(options_.stats_path, frame.name));
  if (!options_.relight_page.empty()) {
    // The frame's lights are back in `frame`.
    job_.page_frames.push_back(relight_page_frame(frame.name, output, options_.relight_page, frame.lights,
                                                  frame.ambient, result.relighting, frame_timer.seconds()));
  }
  return output;
}

// Renders every view and relight frame of a prepared job; rank 0 writes. Returns the exit status.
int render_views(const RenderOptions& options, RenderJob& job, Cluster& cluster) {
  // SPEC §15: from here on Ctrl-C (or SIGTERM) stops the method early; what it finished is written
  // as usual, the views and frames after it are skipped, and the exit status is 130. A second
  // Ctrl-C ends the process at once.
  install_interrupt_handler();
  const bool root = cluster.root();
  const std::size_t view_count = job.views.size(), frame_count = job.relight_frames.size();
  WrittenImages written;
  ImageRenderer renderer(options, job, cluster, written);
  for (std::size_t v = 0; v < view_count; ++v) {
    try {
      if (const std::optional<int> status = renderer.render_view(v)) return *status;
    } catch (...) {
      if (root)
        written.report_failure("camera " + job.views[v].name, view_count - v - 1 + frame_count,
                               view_count + frame_count);
      throw;
    }
  }

  // Relighting: each frame's lights in place of the scene's, the same method object, so the
  // meshless geometry (sites, areas, transfer matrix) is reused and only η and λ are redone.
  for (std::size_t f = 0; f < frame_count; ++f) {
    try {
      if (const std::optional<int> status = renderer.render_frame(f)) return *status;
    } catch (...) {
      if (root)
        written.report_failure("frame " + job.relight_frames[f].name, frame_count - f - 1,
                               view_count + frame_count);
      throw;
    }
  }
  if (root && !options.relight_page.empty()) write_relight_page(options, job);
  return 0;
}

// Bad input found by some ranks once they render together (not agreed by all) would leave the
// others waiting: it ends every rank.
[[noreturn]] void end_every_rank(const Cluster& cluster, const std::exception& error) {
  std::cerr << fmt::format("candela: error (rank {}): {}\n", cluster.rank(), error.what());
  abort_all_ranks(2);
}

int run_render(RenderOptions& options) {
  Cluster& cluster = world_cluster();
  // Only rank 0 prints progress and summaries and writes files.
  if (!cluster.root()) options.quiet = true;
  RenderJob job;
  prepare_everywhere(options, job, cluster);
  if (!options.pixel.empty())
    return cluster.root() ? print_pixel_ray_trees(options, *job.scene, job.views, *job.method) : 0;
  if (!cluster.distributed()) return render_views(options, job, cluster);
  try {
    return render_views(options, job, cluster);
  } catch (const InputError& e) {
    if (cluster.failure_agreed()) throw;
    end_every_rank(cluster, e);
  } catch (const BadArgument& e) {
    if (cluster.failure_agreed()) throw;
    end_every_rank(cluster, e);
  }
}

}  // namespace

void add_render_command(CLI::App& app, std::function<int()>& run) {
  auto options = std::make_shared<RenderOptions>();
  CLI::App* command =
      app.add_subcommand("render", "Render a scene (the built-in default scene without SCENE)");
  command->add_option("scene", options->scene.scene_path, "Scene file (candela/1 JSON)");
  command->add_option("-o,--output,--outfile", options->output,
                      "Output image: .png (sRGB 8-bit), .exr or .pfm (linear float), .hdr (Radiance RGBE)");
  command->add_option("--method", options->method, "Rendering method: " + method_names());
  command->add_option("--accel", options->accelerator,
                      "Acceleration structure (default: render.accelerator)");
  command->add_option("--threads,--nthreads", options->threads, "Worker threads (default: all cores)");
  command->add_option("--seed", options->seed, "Random seed (default: render.seed)");
  // One key=value per --set, repeated as often as needed, so SCENE may follow.
  command
      ->add_option("--set", options->scene.overrides,
                   "Override a scene setting: key=value, e.g. camera.width=640")
      ->expected(1)
      ->allow_extra_args(false)
      ->take_all();
  command->add_option("--stats", options->stats_path, "Write run statistics as JSON");
  command->add_option("--aa-map", options->aa_map_path,
                      "Write a PNG whose grey levels show the samples each pixel used (white: the most)");
  command->add_flag("-q,--quiet", options->quiet, "No progress and no summary");
  CLI::Option* crop =
      add_list_option(command, "--crop", options->crop,
                      "Render only pixels x0,y0 (inclusive) to x1,y1 (exclusive); y = 0 is the top row", 4);
  CLI::Option* pixel_bounds = add_list_option(command, "--pixelbounds", options->pixel_bounds,
                                              "pbrt's form of --crop: x0,x1,y0,y1", 4);
  add_list_option(
      command, "--cropwindow", options->crop_window,
      "Render only the part x0,x1,y0,y1 of the image, in fractions in [0, 1] (pbrt's --cropwindow)", 4)
      ->excludes(crop)
      ->excludes(pixel_bounds);
  crop->excludes(pixel_bounds);
  add_list_option(command, "--pixel", options->pixel, "Print the ray tree of pixel X,Y instead of rendering",
                  2);
  command
      ->add_option(
          "--camera", options->cameras,
          "Render the named camera(s) of the scene's \"cameras\": NAME, a comma-separated list, or "
          "all; default is the \"camera\" object. Several: one image each, -o out.png -> out-NAME.png")
      ->delimiter(',')
      ->expected(1)
      ->allow_extra_args(false)
      ->take_all();
  command->add_option("--export-solution", options->export_solution,
                      "radiosity: also write the solution (.csv, .ply or .gltf)");
  command->add_option(
      "--relight", options->relight,
      "meshless: also render each light set-up of FILE ({\"frames\": [{\"name\", \"lights\"}]}) from the "
      "same sites and transfer matrix, -o out.png -> out-NAME.png");
  command->add_option(
      "--relight-page", options->relight_page,
      "meshless, with --relight: also write an HTML page with every frame, a slider over them and "
      "their times (-o must be a .png)");
  command->add_option("--show-sites", options->show_sites,
                      "meshless: also write the image with the element centres (sites) drawn over it");
  command->add_option(
      "--spp", options->spp,
      "Samples per pixel: path's passes (setting path.spp); every other method n×n anti-aliasing "
      "samples (aa.n; aa.mode \"jittered\", or \"uniform\" where the method rasterizes, unless the "
      "scene's is one of them)");
  command->add_option(
      "--time", options->time,
      "path: render passes for this many seconds (setting path.time; with --spp, whichever comes first)");
  command->add_option(
      "--checkpoint", options->checkpoint,
      "path: write the progressive state to FILE every --checkpoint-every seconds and at the end");
  command->add_option("--checkpoint-every", options->checkpoint_every,
                      "path: seconds between checkpoints (setting path.checkpoint_interval, default 60)");
  command->add_option(
      "--resume", options->resume,
      "path: continue from a checkpoint of the same scene and settings (to --spp / --time more)");
  command->add_option("--error-reference", options->error_reference,
                      "A linear reference image (.exr, .pfm, .hdr as render writes it) for --error-log");
  command->add_option("--error-mask", options->error_mask,
                      "With --error-log: measure only the pixels the mask image (white) includes");
  command->add_option(
      "--error-log", options->error_log,
      "Write the error against --error-reference (RMSE, relMSE) and the time at every step: "
      "path passes, radiosity shots or sweeps, meshless iterations, and the final image (CSV)");
  command->add_option("--error-every", options->error_every,
                      "With --error-log and progressive radiosity: shots between rows (default 50)");
  command->callback([options, &run]() {
    run = [options]() { return run_reporting_bad_input([&] { return run_render(*options); }); };
  });
}

}  // namespace candela::cli
