// candela report SCENE [--methods M,M,...] -o DIR [--reference-spp N | --reference FILE] [--spp N]
//                     [--equal-time] [--set k=v]... [--threads N] [-q]
// The cross-method report (SPEC §13): the scene rendered by each method, every image measured
// against a path-traced reference, written to DIR as index.html (self-contained, relative image
// paths), report.json and the images (validate/cross_method_report.h). See docs/report.md.
#include <fmt/format.h>
#include <tbb/global_control.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "commands.h"
#include "image_arguments.h"
#include "integrators/method_registry.h"
#include "list_option.h"
#include "output_paths.h"
#include "scene/scene.h"
#include "scene_options.h"
#include "shading/photometric_units.h"
#include "util/input_file.h"
#include "validate/cross_method_report.h"
#include "validate/image_comparison.h"

namespace candela::cli {

namespace {

struct ReportOptions {
  SceneOptions scene;
  std::vector<std::string> methods = default_comparison_methods();
  std::string output;
  int reference_spp = 1024;
  std::string reference;
  std::string error_mask;  // the convergence chart's pixels
  std::optional<int> spp;
  bool equal_time = false;
  bool luminance = false;  // errors in cd/m²
  int threads = 0;
  bool quiet = false;
};

void check_methods(const std::vector<std::string>& methods) {
  for (auto name = methods.begin(); name != methods.end(); ++name) {
    if (name->empty()) throw BadArgument("--methods: empty method name");
    if (!find_method(*name))
      throw BadArgument("--methods: unknown method \"" + *name + "\" (expected one of: " + method_names() +
                        ")");
    if (std::find(methods.begin(), name, *name) != name)
      throw BadArgument("--methods: " + *name + " is named twice");
  }
}

// DIR is created when missing; it must be a folder that accepts new files.
void prepare_directory(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code error;
  if (fs::exists(path, error) && !fs::is_directory(path, error))
    throw BadArgument("-o " + path + " is a file, not a folder");
  if (!fs::exists(path, error)) {
    fs::create_directories(path, error);
    if (error) throw BadArgument("-o " + path + ": cannot create the folder (" + error.message() + ")");
  }
  if (::access(path.c_str(), W_OK) != 0) throw BadArgument("-o " + path + ": the folder is not writable");
}

int run_report(ReportOptions& options) {
  check_methods(options.methods);
  const std::vector<std::string>& methods = options.methods;
  if (options.reference_spp < 1) throw BadArgument("--reference-spp must be >= 1");
  if (options.spp && *options.spp < 1) throw BadArgument("--spp must be >= 1");
  if (options.output.empty()) throw BadArgument("-o DIR is required");
  if (!std::filesystem::is_regular_file(options.scene.scene_path))
    throw BadArgument("SCENE " + options.scene.scene_path + ": no such file");
  std::optional<LinearImage> reference;
  if (!options.reference.empty()) {
    reference = read_image_argument(options.reference, "--reference");
    if (reference->srgb_decoded)
      throw BadArgument("--reference " + options.reference +
                        ": an 8-bit (sRGB) image; the reference must be linear (.exr or .pfm)");
  }
  std::optional<tbb::global_control> thread_limit;
  if (options.threads > 0)
    thread_limit.emplace(tbb::global_control::max_allowed_parallelism,
                         static_cast<std::size_t>(options.threads));
  const int threads =
      static_cast<int>(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));

  std::unique_ptr<Scene> scene = options.scene.load();
  for (const auto& warning : scene->warnings) std::cerr << "candela: warning: " << warning << "\n";

  CrossMethodOptions settings;
  settings.methods = methods;
  settings.output_directory = options.output;
  settings.reference_spp = options.reference_spp;
  if (reference) {
    check_image_size(reference->film, "--reference", options.reference, scene->camera->width(),
                     scene->camera->height(), "the scene's image");
    settings.reference_image = exposure_undone(reference->film, scene->display.exposure);
    settings.reference_file = options.reference;
  }
  if (!options.error_mask.empty())
    settings.convergence_mask = read_mask_argument(options.error_mask, "--error-mask", scene->camera->width(),
                                                   scene->camera->height(), "the scene's image");
  settings.path_spp = options.spp;
  settings.equal_time = options.equal_time;
  settings.luminance_efficacy = options.luminance ? kLuminousEfficacy : 0;
  settings.quiet = options.quiet;
  settings.scene_path = options.scene.scene_path;
  settings.scene_text = read_input_file(options.scene.scene_path, "the scene file");
  settings.overrides = options.scene.overrides;
  settings.threads = threads;
  if (!options.quiet)
    settings.log = [](const std::string& line) { std::cerr << "candela: report: " << line << "\n"; };

  // No file the report writes may be an input of the run (a texture beside the scene in DIR).
  std::vector<OutputFile> outputs;
  for (const std::string& name : cross_method_report_files(settings))
    outputs.push_back({(std::filesystem::path(options.output) / name).string(), "-o"});
  std::vector<std::string> inputs = scene->input_files;
  inputs.push_back(options.scene.scene_path);
  inputs.push_back(options.error_mask);
  inputs.push_back(options.reference);
  refuse_outputs_over_inputs(outputs, inputs);
  prepare_directory(options.output);
  const CrossMethodReport report = run_cross_method_report(*scene, settings);

  if (!options.quiet) {
    std::cerr << fmt::format(
        "candela: report: wrote {}/index.html ({} methods against {})\n", options.output,
        report.entries.size(),
        report.reference_rendered ? fmt::format("path at {} spp", report.reference_spp) : options.reference);
    std::cerr << fmt::format("  {:<34} {:>9} {:>11} {:>11} {:>9}\n", "method", "time (s)", "RMSE", "rel. MSE",
                             "PSNR");
    for (const CrossMethodEntry& entry : report.entries)
      std::cerr << fmt::format("  {:<34} {:>9.3f} {:>11.4g} {:>11.4g} {:>9.2f}\n", entry.label, entry.seconds,
                               entry.errors.rmse, entry.errors.relative_mse, entry.errors.psnr);
  }
  return 0;
}

}  // namespace

void add_report_command(CLI::App& app, std::function<int()>& run) {
  auto options = std::make_shared<ReportOptions>();
  CLI::App* command = app.add_subcommand(
      "report",
      "Render a scene with several methods and write an HTML report of their errors against a path-traced "
      "reference");
  command->add_option("scene", options->scene.scene_path, "Scene file (candela/1 JSON)")->required();
  add_list_option(
      command, "--methods", options->methods,
      "Methods to compare (default whitted,radiosity,meshless,path; any of: " + method_names() + ")");
  command
      ->add_option("-o,--output,--outfile", options->output,
                   "Folder for index.html, report.json and the images (created)")
      ->required();
  auto* reference_spp = command->add_option("--reference-spp", options->reference_spp,
                                            "Samples per pixel of the path-traced reference (default 1024)");
  command
      ->add_option(
          "--reference", options->reference,
          "Use this linear image (.exr or .pfm, the scene's size) as the reference instead of rendering one")
      ->excludes(reference_spp);
  command->add_option("--spp", options->spp,
                      "Samples per pixel of the \"path\" entry (default: the scene's path.spp)");
  command->add_option("--error-mask", options->error_mask,
                      "Measure the error-against-time chart over the pixels the mask image (white) includes");
  command->add_flag("--luminance", options->luminance,
                    "Measure the errors in luminance, cd/m² (179 lm/W × Y / π) instead of linear RGB");
  command->add_flag("--equal-time", options->equal_time,
                    "Also render path limited to each other method's render time, and report its errors");
  command
      ->add_option("--set", options->scene.overrides,
                   "Override a scene setting: key=value, e.g. camera.width=640")
      ->expected(1)
      ->allow_extra_args(false)
      ->take_all();
  command->add_option("--threads,--nthreads", options->threads, "Worker threads (default: all cores)");
  command->add_flag("-q,--quiet", options->quiet, "No progress and no summary");
  command->callback([options, &run]() {
    run = [options]() { return run_reporting_bad_input([&] { return run_report(*options); }); };
  });
}

}  // namespace candela::cli
