// candela probe SCENE --method path|radiosity|meshless (--points pts.csv | --grid ...) -o out.csv
//   Irradiance and radiance at sensor points (integrators/probe.h; like Radiance's rtrace -I).
//   --grid cx,cy,cz,ux,uy,uz,vx,vy,vz  a work plane: the parallelogram corner + s·u + t·v, with
//   --grid-size NU,NV points at its cells' centres facing u × v, and --image FILE.png a
//   false-color picture of the illuminance with its scale (--scale LO,HI, --log, --contours N as
//   Radiance's falsecolor -s, -log, -cl). The summary and --json FILE give Emin, Eavg, Emax and
//   the uniformities Emin/Eavg and Emin/Emax.
#include <fmt/format.h>
#include <tbb/global_control.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <limits>
#include <optional>

#include "commands.h"
#include "false_color_options.h"
#include "integrators/method_registry.h"
#include "integrators/probe.h"
#include "io/false_color.h"
#include "io/image_writer.h"
#include "list_option.h"
#include "output_paths.h"
#include "scene_options.h"
#include "thread_limit.h"
#include "util/atomic_file.h"
#include "util/error.h"
#include "util/statistics.h"

namespace candela::cli {

namespace {

struct ProbeOptions {
  SceneOptions scene;
  std::string method = std::string(kReferenceMethod);
  std::string points_path;
  std::vector<double> grid;
  std::vector<int> grid_size{20, 20};
  std::string image;
  std::vector<double> image_scale;  // --scale lo,hi
  bool image_log = false;
  int contours = 0;
  std::string json;
  bool daylight_factor = false;
  std::string output;
  int samples = 256;
  std::optional<int64_t> seed;
  double efficacy = kDefaultLuminousEfficacy;
  int threads = 0;
  bool quiet = false;
};

std::string csv_number(double value) {
  return fmt::format("{:.9g}", value);
}

// The options alone, before anything is read: the points' source, the method, the outputs (each
// writable) and the picture's scale.
void check_probe_options(const ProbeOptions& options) {
  if (options.points_path.empty() == options.grid.empty())
    throw BadArgument("give either --points FILE or --grid cx,cy,cz,ux,uy,uz,vx,vy,vz");
  if (options.samples < 1) throw BadArgument("--samples must be >= 1");
  check_efficacy(options.efficacy);
  const MethodEntry* entry = find_method(options.method);
  if (!entry || !entry->capabilities.probe)
    throw BadArgument("--method " + options.method +
                      " cannot be probed (expected one of: " + probe_method_names() + ")");
  if (options.output.size() < 5 || options.output.substr(options.output.size() - 4) != ".csv")
    throw BadArgument("-o " + options.output + ": expected a .csv file");
  check_writable(options.output, "-o");
  if (!options.image.empty()) {
    if (options.grid.empty()) throw BadArgument("--image needs --grid (a picture of the work plane)");
    ImageFormat image_format;
    if (!image_format_for_path(options.image, image_format) || image_format != ImageFormat::png)
      throw BadArgument("--image " + options.image + ": expected a .png file");
    check_writable(options.image, "--image");
  }
  if (!options.image_scale.empty() && options.image.empty()) throw BadArgument("--scale needs --image");
  if ((options.image_log || options.contours != 0) && options.image.empty())
    throw BadArgument(options.image_log ? "--log needs --image" : "--contours needs --image");
  check_false_color_options(options.image_scale, options.image_log, options.contours, "lux");
  if (!options.json.empty()) check_writable(options.json, "--json");
}

// The points probed and what was found there, in the units written: lux, and the daylight factor
// in per cent.
struct ProbeMeasurements {
  std::vector<ProbePoint> points;
  int nu = 0, nv = 0;  // --grid-size: the work plane's points along u and v; 0 with --points
  ProbeSettings settings;
  double sky_lux = 0;    // --daylight-factor: what an unobstructed horizontal surface receives
  nlohmann::json facts;  // what the method's solution measured (probe())
  std::vector<ProbeResult> results;
  std::vector<double> illuminance;
  std::vector<double> daylight_factor;  // --daylight-factor
};

// --grid's work plane (its points row by row along v from the corner) or --points' file.
void place_points(const ProbeOptions& options, ProbeMeasurements& measurements) {
  if (options.grid.empty()) {
    measurements.points = read_probe_points(options.points_path);
    return;
  }
  if (options.grid.size() != 9) throw BadArgument("--grid expects 9 numbers: cx,cy,cz,ux,uy,uz,vx,vy,vz");
  for (const double v : options.grid)
    if (!std::isfinite(v)) throw BadArgument("--grid: every number must be finite");
  if (options.grid_size.size() != 2 || options.grid_size[0] < 1 || options.grid_size[1] < 1 ||
      int64_t(options.grid_size[0]) * options.grid_size[1] > 4'000'000)
    throw BadArgument("--grid-size expects NU,NV >= 1 (at most 4,000,000 points)");
  const Vec3 corner{options.grid[0], options.grid[1], options.grid[2]};
  const Vec3 u{options.grid[3], options.grid[4], options.grid[5]},
      v{options.grid[6], options.grid[7], options.grid[8]};
  if (!(length(cross(u, v)) > 0)) throw BadArgument("--grid: the edges u and v must span a plane");
  measurements.nu = options.grid_size[0];
  measurements.nv = options.grid_size[1];
  measurements.points = grid_probe_points(corner, u, v, measurements.nu, measurements.nv);
}

ProbeSettings probe_settings(const ProbeOptions& options, const Scene& scene) {
  ProbeSettings settings;
  settings.method = options.method;
  settings.samples = options.samples;
  settings.seed = options.seed ? uint64_t(*options.seed) : scene.render.seed;
  settings.quiet = options.quiet;
  return settings;
}

// The daylight factor, the illuminance over what an unobstructed horizontal surface
// receives from the sky (the environment), in per cent; a scene without a sky is refused before
// anything is probed. Returns that surface's illuminance in lux.
double unobstructed_sky_lux(const ProbeOptions& options, const Scene& scene) {
  if (!scene.environment)
    throw InputError({options.scene.scene_path, 0, 0, "environment"},
                     "--daylight-factor needs a sky: the scene has no environment");
  const double sky_lux = options.efficacy * luminance(unobstructed_sky_irradiance(scene));
  if (!(sky_lux > 0))
    throw InputError({options.scene.scene_path, 0, 0, "environment"},
                     "--daylight-factor: the environment gives an unobstructed horizontal surface no light");
  // A daylight factor is of the daylight alone: electric light in the scene is counted too.
  if (!scene.lights.empty() || !scene.surface_lights.empty())
    std::cerr << fmt::format(
        "candela: warning: --daylight-factor: the scene has {} light(s) and {} emissive surface(s) besides "
        "the "
        "sky, whose light the factor counts too (--set 'lights=[]' leaves the daylight alone)\n",
        scene.lights.size(), scene.surface_lights.size());
  return sky_lux;
}

// The illuminance of each point and, with --daylight-factor, its share of the sky's.
void convert_to_lux(const ProbeOptions& options, ProbeMeasurements& measurements) {
  const std::vector<ProbeResult>& results = measurements.results;
  measurements.illuminance.resize(results.size());
  for (std::size_t i = 0; i < results.size(); ++i)
    measurements.illuminance[i] = options.efficacy * luminance(results[i].irradiance);
  if (options.daylight_factor)
    for (const double lux : measurements.illuminance)
      measurements.daylight_factor.push_back(100 * lux / measurements.sky_lux);
}

// Nothing that is not finite is written (an efficacy of 1e308 once wrote a CSV of inf).
void refuse_values_not_finite(const ProbeOptions& options, const ProbeMeasurements& measurements) {
  const std::vector<ProbePoint>& points = measurements.points;
  const std::vector<double>& illuminance = measurements.illuminance;
  for (std::size_t i = 0; i < measurements.results.size(); ++i) {
    const ProbeResult& r = measurements.results[i];
    const double values[] = {
        r.irradiance.r, r.irradiance.g, r.irradiance.b, r.radiance.r,
        r.radiance.g,   r.radiance.b,   illuminance[i], options.efficacy * r.irradiance_error};
    for (const double value : values)
      if (!std::isfinite(value))
        throw std::runtime_error(
            fmt::format("point {} ({}, {}, {}): its estimate is not finite ({}); nothing written", i + 1,
                        points[i].position.x, points[i].position.y, points[i].position.z, value));
    // A faint sky under a bright light: the ratio overflows though both are finite.
    if (options.daylight_factor && !std::isfinite(measurements.daylight_factor[i]))
      throw InputError(
          {options.scene.scene_path, 0, 0, "environment"},
          fmt::format("--daylight-factor: point {} has {:g} lux under a sky that gives an unobstructed "
                      "horizontal surface {:g} lux: the ratio is beyond a double; nothing written",
                      i + 1, illuminance[i], measurements.sky_lux));
  }
}

// -o: one row a point. Streamed row by row (a 4,000,000-point grid is 600 MB of text), into a
// temporary file renamed into place.
void write_points_csv(const ProbeOptions& options, const ProbeMeasurements& measurements) {
  write_atomically(options.output, [&](const std::string& temporary) {
    std::ofstream out(temporary);
    out << "x,y,z,nx,ny,nz,irradiance_r,irradiance_g,irradiance_b,radiance_r,radiance_g,radiance_b,"
           "illuminance_lux,illuminance_error_lux"
        << (options.daylight_factor ? ",daylight_factor_percent\n" : "\n");
    for (std::size_t i = 0; i < measurements.results.size(); ++i) {
      const ProbePoint& p = measurements.points[i];
      const ProbeResult& r = measurements.results[i];
      out << fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{}", csv_number(p.position.x),
                         csv_number(p.position.y), csv_number(p.position.z), csv_number(p.normal.x),
                         csv_number(p.normal.y), csv_number(p.normal.z), csv_number(r.irradiance.r),
                         csv_number(r.irradiance.g), csv_number(r.irradiance.b), csv_number(r.radiance.r),
                         csv_number(r.radiance.g), csv_number(r.radiance.b),
                         csv_number(measurements.illuminance[i]),
                         csv_number(options.efficacy * r.irradiance_error))
          << (options.daylight_factor ? "," + csv_number(measurements.daylight_factor[i]) + "\n" : "\n");
    }
    out.close();
    if (!out) throw std::runtime_error("cannot write " + options.output);
  });
}

// --image: the work plane's illuminance in false color, with its scale.
void write_illuminance_image(const ProbeOptions& options, const ProbeMeasurements& measurements) {
  const int nu = measurements.nu, nv = measurements.nv;
  // The grid's rows run along v from the corner; the picture shows the last row at the top.
  std::vector<double> values(measurements.illuminance.size());
  double high = 0;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const double value = measurements.illuminance[std::size_t(j) * nu + i];
      values[std::size_t(nv - 1 - j) * nu + i] = value;
      if (std::isfinite(value)) high = std::max(high, value);
    }
  const FalseColorScale scale =
      false_color_scale(high, options.image_scale, options.image_log, options.contours, "lx", "illuminance");
  // Each point a square of pixels, the picture at least 240 wide (a 20×20 grid: 12×12 squares), so
  // that the scale's labels and caption fit beneath it.
  const int block = std::clamp((240 + nu - 1) / nu, 1, 32);
  std::vector<double> blocks(std::size_t(nu) * block * nv * block);
  for (int y = 0; y < nv * block; ++y)
    for (int x = 0; x < nu * block; ++x)
      blocks[std::size_t(y) * nu * block + x] = values[std::size_t(y / block) * nu + x / block];
  const Film picture = false_color_image(blocks, nu * block, nv * block, scale, ColorMap::viridis);
  write_image(picture, options.image, DisplaySettings{});
  if (!options.quiet)
    std::cout << fmt::format("illuminance scale: {} to {} lux{}{}\n", format_scale_value(scale.low),
                             format_scale_value(scale.high), scale.logarithmic ? ", logarithmic" : "",
                             scale.contours > 1 ? fmt::format(", {} contour steps", scale.contours) : "");
}

// The summary's figures, in lux (the daylight factor in per cent).
struct ProbeSummary {
  IlluminanceStatistics illuminance;
  IlluminanceStatistics daylight_factor;  // --daylight-factor
  double mean_error = 0;                  // the points' standard errors' mean
};

ProbeSummary summarize(const ProbeOptions& options, const ProbeMeasurements& measurements) {
  ProbeSummary summary;
  summary.illuminance = illuminance_statistics(measurements.illuminance);
  summary.daylight_factor = options.daylight_factor ? illuminance_statistics(measurements.daylight_factor)
                                                    : IlluminanceStatistics{};
  double error_sum = 0;
  for (const ProbeResult& result : measurements.results)
    error_sum += options.efficacy * result.irradiance_error;
  summary.mean_error = error_sum / double(measurements.results.size());
  return summary;
}

// --json.
void write_summary_json(const ProbeOptions& options, const ProbeMeasurements& measurements,
                        const ProbeSummary& summary, const Stopwatch& timer) {
  const IlluminanceStatistics& statistics = summary.illuminance;
  nlohmann::json json = {{"points", statistics.points},
                         {"method", measurements.settings.method},
                         {"samples", measurements.settings.samples},
                         {"efficacy_lm_per_w", options.efficacy},
                         {"illuminance_lux",
                          {{"min", statistics.minimum},
                           {"max", statistics.maximum},
                           {"average", statistics.average},
                           {"uniformity_min_average", statistics.uniformity_min_average},
                           {"uniformity_min_max", statistics.uniformity_min_max},
                           {"mean_standard_error", summary.mean_error}}},
                         {"seconds", timer.seconds()}};
  if (!options.grid.empty())
    json["grid"] = {{"size", {measurements.nu, measurements.nv}}, {"corner_and_edges", options.grid}};
  if (options.daylight_factor) {
    const IlluminanceStatistics& daylight = summary.daylight_factor;
    json["unobstructed_sky_illuminance_lux"] = measurements.sky_lux;
    json["daylight_factor_percent"] = {
        {"min", daylight.minimum}, {"max", daylight.maximum}, {"average", daylight.average}};
  }
  write_atomically(options.json, [&](const std::string& temporary) {
    std::ofstream out(temporary);
    out << json.dump(2) << "\n";
    out.close();
    if (!out) throw std::runtime_error("cannot write " + options.json);
  });
}

// Without --quiet: the summary on the standard output, and a warning for rays off the solution.
void print_summary(const ProbeOptions& options, const ProbeMeasurements& measurements,
                   const ProbeSummary& summary, const Stopwatch& timer) {
  const IlluminanceStatistics& statistics = summary.illuminance;
  const ProbeSettings& settings = measurements.settings;
  // The standard error falls as 1/√samples: 4× the samples halve it.
  std::cout << fmt::format(
      "probed {} points with {} ({} samples each) in {:.2f} s: illuminance Emin {:.4g}, Eavg {:.4g}, "
      "Emax {:.4g} lux (efficacy {} lm/W), uniformity Emin/Eavg {:.3f}, Emin/Emax {:.3f}; standard "
      "error {:.3g} lux on average ({:.2g} % of the mean); wrote {}\n",
      measurements.points.size(), settings.method, settings.samples, timer.seconds(), statistics.minimum,
      statistics.average, statistics.maximum, options.efficacy, statistics.uniformity_min_average,
      statistics.uniformity_min_max, summary.mean_error,
      statistics.average > 0 ? 100 * summary.mean_error / statistics.average : 0.0, options.output);
  if (options.daylight_factor) {
    const IlluminanceStatistics& daylight = summary.daylight_factor;
    std::cout << fmt::format(
        "daylight factor (of {:.4g} lux on an unobstructed horizontal surface): min {:.3g} %, average "
        "{:.3g} %, max {:.3g} %\n",
        measurements.sky_lux, daylight.minimum, daylight.average, daylight.maximum);
  }
  const nlohmann::json& facts = measurements.facts;
  if (facts.contains("rays_without_solution") && facts["rays_without_solution"].get<uint64_t>() > 0)
    std::cerr << fmt::format(
        "candela: warning: {} probe rays hit surfaces the {} solution does not cover (counted as 0)\n",
        facts["rays_without_solution"].get<uint64_t>(), settings.method);
}

int run_probe(ProbeOptions& options) {
  check_probe_options(options);
  // No output may be the scene, the points file, a file the scene reads (checked again
  // once it is loaded) or another output.
  std::vector<OutputFile> outputs{{options.output, "-o"}};
  if (!options.image.empty()) outputs.push_back({options.image, "--image"});
  if (!options.json.empty()) outputs.push_back({options.json, "--json"});
  std::vector<std::string> inputs{options.scene.scene_path, options.points_path};
  refuse_outputs_over_inputs(outputs, inputs);
  ProbeMeasurements measurements;
  place_points(options, measurements);
  std::optional<tbb::global_control> thread_limit;
  limit_threads(options.threads, thread_limit);

  Stopwatch timer;
  std::unique_ptr<Scene> scene = options.scene.load();
  inputs.insert(inputs.end(), scene->input_files.begin(), scene->input_files.end());
  refuse_outputs_over_inputs(outputs, inputs);
  for (const auto& warning : scene->warnings) std::cerr << "candela: warning: " << warning << "\n";
  measurements.settings = probe_settings(options, *scene);
  if (options.daylight_factor) measurements.sky_lux = unobstructed_sky_lux(options, *scene);
  measurements.results = probe(*scene, measurements.points, measurements.settings, &measurements.facts);
  convert_to_lux(options, measurements);
  refuse_values_not_finite(options, measurements);
  write_points_csv(options, measurements);
  if (!options.image.empty()) write_illuminance_image(options, measurements);
  const ProbeSummary summary = summarize(options, measurements);
  if (!options.json.empty()) write_summary_json(options, measurements, summary, timer);
  if (!options.quiet) print_summary(options, measurements, summary, timer);
  return 0;
}

}  // namespace

void add_probe_command(CLI::App& app, std::function<int()>& run) {
  auto options = std::make_shared<ProbeOptions>();
  CLI::App* command =
      app.add_subcommand("probe", "Irradiance and radiance at sensor points or over a work plane");
  command->add_option("scene", options->scene.scene_path, "Scene file (candela/1 JSON)")->required();
  command->add_option("--method", options->method, "Method: " + probe_method_names() + " (default path)");
  command->add_option("--points", options->points_path, "CSV of sensor points: x,y,z,nx,ny,nz per line");
  add_list_option(command, "--grid", options->grid,
                  "Work plane: corner and edges cx,cy,cz,ux,uy,uz,vx,vy,vz (normal u × v)", 9);
  add_list_option(command, "--grid-size", options->grid_size, "Points along u and v: NU,NV (default 20,20)",
                  2);
  command->add_option("--image", options->image,
                      "With --grid: a false-color PNG of the illuminance with its scale");
  add_list_option(command, "--scale", options->image_scale,
                  "With --image: the color scale's range LO,HI in lux", 2);
  command->add_flag(
      "--log", options->image_log,
      "With --image: a logarithmic color scale (default range: three decades below the maximum)");
  command->add_option("--contours", options->contours,
                      "With --image: N equal steps of the scale with iso-lines between them");
  command->add_option("--json", options->json,
                      "Summary as JSON: Emin, Emax, Eavg, uniformities Emin/Eavg and Emin/Emax");
  command->add_flag(
      "--daylight-factor", options->daylight_factor,
      "Also the daylight factor: illuminance / the sky's on an unobstructed horizontal surface (%)");
  command->add_option("-o,--output,--outfile", options->output, "Output CSV")->required();
  command->add_option("--samples,--spp", options->samples,
                      "Estimates (path) or hemisphere rays per point (default 256)");
  command->add_option("--seed", options->seed, "Random seed (default: render.seed)");
  command->add_option("--efficacy", options->efficacy,
                      "Luminous efficacy in lm/W for the lux column (default 179, Radiance's)");
  command->add_option("--threads,--nthreads", options->threads, "Worker threads (default: all cores)");
  command->add_option("--set", options->scene.overrides, "Override a scene setting: key=value")
      ->expected(1)
      ->allow_extra_args(false)
      ->take_all();
  command->add_flag("-q,--quiet", options->quiet, "No progress and no summary");
  command->callback([options, &run]() {
    run = [options]() { return run_reporting_bad_input([&] { return run_probe(*options); }); };
  });
}

}  // namespace candela::cli
