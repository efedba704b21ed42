// candela bench [MESH] [--sphere N | --terrain N] [--accel NAME...] [--threads N...] [--json FILE]
//               [--seed S] [--eye X Y Z] [--lookat X Y Z] [--fov DEG] [--light X Y Z]
//               [--width W] [--height H] [--rays N] [--repeat R] [--min-time S] [--dump DIR] [--quiet]
// candela bench --raster [MESH.obj ...] [--sphere N] [--terrain N] [--width W] [--height H] [--fov DEG]
//               [--repeat R] [--min-time S] [--json FILE] [--quiet]
// candela bench --solve METHOD [SCENE.json] [--set key=value]... [--threads N...] [--json FILE] [--quiet]
// Reproducible ray-set throughput (SPEC §14) with the ray sets and checksums of
// shared/BENCH-RAYS.md. "embree" is Embree's own triangle test (the reference speed).
// --raster measures the scanline rasterizer instead (bench/raster_bench.h): every mesh given,
// or every .obj of ../shared/models (from the current directory) when none is.
// --solve makes a method's view-independent solution of a scene (Method::solve_alone) once per
// thread count (default: one run with every core) and reports the
// method's facts — a table of the columns it chooses, all of them in the JSON — and the process's
// peak resident memory; SCENE defaults to the built-in default scene, as for render.
#include <fmt/format.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <optional>
#include <string>
#include <thread>

#include "bench/bench_runner.h"
#include "bench/raster_bench.h"
#include "commands.h"
#include "integrators/method_registry.h"
#include "integrators/scene_loading.h"
#include "list_option.h"
#include "output_paths.h"
#include "util/atomic_file.h"
#include "util/error.h"
#include "util/file_extension.h"
#include "util/statistics.h"

namespace candela::cli {

namespace {

struct BenchCommandOptions {
  std::vector<std::string> inputs;  // the positional arguments
  std::string mesh_path;            // the one input of a ray-set bench
  std::optional<uint64_t> sphere;
  std::optional<uint64_t> terrain;
  std::vector<std::string> accelerators;
  std::vector<int> threads;
  std::string json_path;
  uint64_t seed = 1;
  std::vector<double> eye, lookat, light;
  double fov = 45.0;
  int width = 1024;
  int height = 1024;
  uint64_t rays = 0;
  int repeat = 3;
  double min_time = 0.5;
  std::string dump_directory;
  bool quiet = false;
  bool raster = false;
  std::string solve_method;            // --solve METHOD
  std::vector<std::string> overrides;  // --set key=value (scene files)
  // Whether the option was on the command line (the raster bench has its own defaults).
  bool width_given = false, height_given = false, min_time_given = false;
  bool fov_given = false, repeat_given = false, seed_given = false;
};

// Where `candela bench --raster` looks for meshes when none is given (as
// scripts/run-benchmarks.sh does, from the repository root).
constexpr const char* kDefaultModelDirectory = "../shared/models";

constexpr uint64_t kMaxTriangles = 50'000'000;
constexpr uint64_t kMaxRays = uint64_t{1} << 26;

std::optional<Vec3> point(const std::vector<double>& xyz, const char* option) {
  if (xyz.empty()) return std::nullopt;
  const Vec3 p{xyz[0], xyz[1], xyz[2]};
  if (!is_finite(p)) throw BadArgument(fmt::format("{} must be three finite numbers", option));
  return p;
}

BenchMesh load_mesh(const BenchCommandOptions& options) {
  const int sources = !options.mesh_path.empty() + options.sphere.has_value() + options.terrain.has_value();
  if (sources != 1) throw BadArgument("give exactly one of MESH, --sphere N or --terrain N");
  if (options.sphere) {
    if (*options.sphere < 1 || *options.sphere > kMaxTriangles)
      throw BadArgument(fmt::format("--sphere N must lie in [1, {}]", kMaxTriangles));
    return bench_sphere(*options.sphere);
  }
  if (options.terrain) {
    if (*options.terrain < 1 || *options.terrain > kMaxTriangles)
      throw BadArgument(fmt::format("--terrain N must lie in [1, {}]", kMaxTriangles));
    return bench_terrain(*options.terrain);
  }
  return read_bench_obj(options.mesh_path);
}

BenchOptions bench_options(const BenchCommandOptions& options) {
  BenchOptions bench;
  bench.accelerator_settings = options.overrides;
  const std::vector<std::string> known = bench_accelerator_names();
  for (const std::string& name : options.accelerators) {
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      std::string list;
      for (const std::string& n : known) list += (list.empty() ? "" : ", ") + n;
      throw BadArgument("--accel " + name + ": unknown accelerator (expected one of: " + list + ")");
    }
    if (std::find(bench.accelerators.begin(), bench.accelerators.end(), name) == bench.accelerators.end())
      bench.accelerators.push_back(name);
  }
  if (!options.threads.empty()) {
    bench.threads.clear();
    for (const int threads : options.threads) {
      if (threads < 1 || threads > 1024) throw BadArgument("--threads values must lie in [1, 1024]");
      if (std::find(bench.threads.begin(), bench.threads.end(), threads) == bench.threads.end())
        bench.threads.push_back(threads);
    }
  }
  if (options.width < 1 || options.height < 1) throw BadArgument("--width and --height must be >= 1");
  if (static_cast<uint64_t>(options.width) * static_cast<uint64_t>(options.height) > kMaxRays)
    throw BadArgument(fmt::format("--width x --height must be at most {} rays", kMaxRays));
  if (options.rays > kMaxRays) throw BadArgument(fmt::format("--rays must be at most {}", kMaxRays));
  if (!(options.fov > 0 && options.fov < 180)) throw BadArgument("--fov must lie in (0, 180) degrees");
  if (options.repeat < 1) throw BadArgument("--repeat must be >= 1");
  if (!(options.min_time >= 0) || !std::isfinite(options.min_time))
    throw BadArgument("--min-time must be >= 0");
  bench.rays.eye = point(options.eye, "--eye");
  bench.rays.lookat = point(options.lookat, "--lookat");
  bench.rays.light = point(options.light, "--light");
  bench.rays.fov_degrees = options.fov;
  bench.rays.width = options.width;
  bench.rays.height = options.height;
  bench.rays.incoherent_rays = options.rays;
  bench.rays.seed = options.seed;
  bench.repeat = options.repeat;
  bench.min_seconds = options.min_time;
  bench.dump_directory = options.dump_directory;
  return bench;
}

// Writes --json (when given) atomically.
int write_json(const nlohmann::json& json, const BenchCommandOptions& options) {
  if (!options.json_path.empty()) {
    const std::string text = json.dump(2) + "\n";
    write_atomically(options.json_path, [&](const std::string& temporary) {
      std::ofstream out(temporary);
      out << text;
      out.close();
      if (!out) throw std::runtime_error("cannot write " + options.json_path);
    });
  }
  return 0;
}

// Prints the table and writes --json.
int finish_bench(const BenchReport& report, const BenchCommandOptions& options) {
  std::cout << report.table();
  return write_json(report.to_json(), options);
}

// --json must not be one of the files the scene reads (its meshes, textures, luminaires).
void refuse_json_over_scene_files(const BenchCommandOptions& options, const Scene& scene) {
  if (!options.json_path.empty())
    refuse_outputs_over_inputs({{options.json_path, "--json"}}, scene.input_files);
}

bool is_scene_file(const std::string& path) {
  return path.size() > 5 && path.compare(path.size() - 5, 5, ".json") == 0;
}

// What --solve loads: a scene file, or a glTF or pbrt-v4 file read as a scene (docs/import.md).
bool is_any_scene_file(const std::string& path) {
  const std::string extension = lower_case_extension(path);
  return extension == ".json" || extension == ".gltf" || extension == ".glb" || extension == ".pbrt";
}

// The meshes of --raster: the files given, the generated ones, else every .obj of the models
// directory in name order.
std::vector<BenchMesh> raster_meshes(const BenchCommandOptions& options) {
  std::vector<std::string> paths = options.inputs;
  for (const std::string& path : paths)
    if (is_scene_file(path)) throw BadArgument("--raster measures meshes (.obj), not scene files: " + path);
  std::vector<BenchMesh> meshes;
  if (paths.empty() && !options.sphere && !options.terrain) {
    std::error_code error;
    for (const auto& entry : std::filesystem::directory_iterator(kDefaultModelDirectory, error))
      if (entry.is_regular_file() && entry.path().extension() == ".obj")
        paths.push_back(entry.path().string());
    std::sort(paths.begin(), paths.end());
    if (paths.empty())
      throw BadArgument(
          fmt::format("--raster: no MESH given and no .obj file in {} (run from the repository root "
                      "or pass the meshes)",
                      kDefaultModelDirectory));
  }
  // The meshes found in the models folder are inputs too.
  if (!options.json_path.empty()) refuse_outputs_over_inputs({{options.json_path, "--json"}}, paths);
  for (const std::string& path : paths) {
    meshes.push_back(read_bench_obj(path));
    if (meshes.back().skipped_faces > 0)
      std::cerr << fmt::format("candela: warning: {}: {} face(s) with an out-of-range index skipped\n",
                               meshes.back().name, meshes.back().skipped_faces);
  }
  if (options.sphere) {
    if (*options.sphere < 1 || *options.sphere > kMaxTriangles)
      throw BadArgument(fmt::format("--sphere N must lie in [1, {}]", kMaxTriangles));
    meshes.push_back(bench_sphere(*options.sphere));
  }
  if (options.terrain) {
    if (*options.terrain < 1 || *options.terrain > kMaxTriangles)
      throw BadArgument(fmt::format("--terrain N must lie in [1, {}]", kMaxTriangles));
    meshes.push_back(bench_terrain(*options.terrain));
  }
  return meshes;
}

int run_raster_bench_command(const BenchCommandOptions& options) {
  // The options of the ray sets do not apply to the rasterizer.
  if (!options.accelerators.empty() || !options.threads.empty() || !options.eye.empty() ||
      !options.lookat.empty() || !options.light.empty() || options.rays != 0 ||
      !options.dump_directory.empty())
    throw BadArgument(
        "--raster takes MESH files, --sphere, --terrain, --width, --height, --fov, --repeat, "
        "--min-time, --json and --quiet only");
  RasterBenchOptions raster;
  if (options.width_given) raster.width = options.width;
  if (options.height_given) raster.height = options.height;
  if (raster.width < 1 || raster.height < 1) throw BadArgument("--width and --height must be >= 1");
  if (static_cast<uint64_t>(raster.width) * static_cast<uint64_t>(raster.height) > kMaxRays)
    throw BadArgument(fmt::format("--width x --height must be at most {} pixels", kMaxRays));
  if (!(options.fov > 0 && options.fov < 180)) throw BadArgument("--fov must lie in (0, 180) degrees");
  raster.fov_degrees = options.fov;
  if (options.repeat < 1) throw BadArgument("--repeat must be >= 1");
  raster.repeat = options.repeat;
  if (options.min_time_given) {
    if (!(options.min_time >= 0) || !std::isfinite(options.min_time))
      throw BadArgument("--min-time must be >= 0");
    raster.min_seconds = options.min_time;
  }
  const auto log = [&](const std::string& line) {
    if (!options.quiet) std::cerr << "candela: bench: " << line << "\n";
  };
  nlohmann::json reports = nlohmann::json::array();
  for (const BenchMesh& mesh : raster_meshes(options)) {
    const RasterBenchReport report = run_raster_bench(mesh, raster, log);
    std::cout << report.table() << "\n";
    reports.push_back(report.to_json());
  }
  return write_json({{"raster", reports}}, options);
}

// The machine, for the JSON of --solve: the CPU's model name (Linux) and hardware threads.
nlohmann::json machine_facts() {
  std::string model = "unknown";
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);) {
    if (line.rfind("model name", 0) != 0) continue;
    const std::size_t colon = line.find(':');
    if (colon != std::string::npos) model = line.substr(line.find_first_not_of(" \t", colon + 1));
    break;
  }
  return {{"cpu", model}, {"hardware_threads", std::thread::hardware_concurrency()}};
}

// The method --solve names, made from the scene's settings as render makes it (refusing what it
// cannot do before any work).
std::unique_ptr<Method> solving_method(const std::string& name, const Scene& scene) {
  const MethodEntry* entry = find_method(name);
  if (!entry || !entry->capabilities.standalone_solution)
    throw BadArgument(
        fmt::format("--solve: '{}' has no view-independent solution to measure (expected one of {})", name,
                    fmt::join(method_names_with(&MethodCapabilities::standalone_solution), ", ")));
  return create_method(*entry, scene);
}

// A line of --solve's table: each cell right-aligned in its column's width.
std::string solve_table_line(const std::vector<std::string>& cells, const std::vector<std::size_t>& widths) {
  std::string line;
  for (std::size_t i = 0; i < cells.size(); ++i)
    line += fmt::format("{}{:>{}}", i == 0 ? "" : " ", cells[i], widths[i]);
  return line;
}

// --solve: solve one scene file once per thread count, a table row and the method's facts per run.
int run_solve_bench_command(const BenchCommandOptions& options) {
  const std::string& name = options.solve_method;
  if (options.raster) throw BadArgument("give one of --raster and --solve");
  if (!options.accelerators.empty() || !options.eye.empty() || !options.lookat.empty() ||
      !options.light.empty() || options.rays != 0 || !options.dump_directory.empty() || options.sphere ||
      options.terrain || options.width_given || options.height_given || options.min_time_given ||
      options.fov_given || options.repeat_given || options.seed_given)
    throw BadArgument("--solve takes METHOD, SCENE, --set, --threads, --json and --quiet only");
  if (options.inputs.size() > 1) throw BadArgument("--solve takes at most one SCENE");
  const std::string scene_path = options.inputs.empty() ? std::string() : options.inputs.front();
  if (!scene_path.empty() && !is_any_scene_file(scene_path))
    throw BadArgument("--solve measures a scene (.json, .gltf, .glb or .pbrt), not " + scene_path);
  std::vector<int> thread_counts;
  for (const int threads : options.threads) {
    if (threads < 1 || threads > 1024) throw BadArgument("--threads values must lie in [1, 1024]");
    if (std::find(thread_counts.begin(), thread_counts.end(), threads) == thread_counts.end())
      thread_counts.push_back(threads);
  }
  if (thread_counts.empty())
    thread_counts.push_back(
        static_cast<int>(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism)));

  const std::unique_ptr<Scene> scene = scene_path.empty() ? load_default_scene(options.overrides)
                                                          : load_scene_file(scene_path, options.overrides);
  refuse_json_over_scene_files(options, *scene);
  for (const auto& warning : scene->warnings) std::cerr << "candela: warning: " << warning << "\n";
  const std::unique_ptr<Method> method = solving_method(name, *scene);
  nlohmann::json runs = nlohmann::json::array();
  std::cout << fmt::format("scene: {}\n", scene_path.empty() ? "(built-in default)" : scene_path);
  std::vector<std::size_t> widths;
  for (const int threads : thread_counts) {
    if (!options.quiet) std::cerr << fmt::format("candela: bench: {}, {} thread(s)\n", name, threads);
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                    static_cast<std::size_t>(threads));
    Stopwatch total;
    StandaloneSolution solution = method->solve_alone(*scene, options.quiet);
    nlohmann::json& facts = solution.facts;
    facts["total_seconds"] = total.seconds();
    facts["threads"] = threads;
    // The process's peak so far: with several thread counts, the largest run's up to this one.
    const double peak_mib = static_cast<double>(peak_memory_bytes()) / 1048576.0;
    facts["peak_memory_mib"] = peak_mib;
    std::vector<std::pair<std::string, std::string>> cells{{"threads", std::to_string(threads)}};
    cells.insert(cells.end(), solution.columns.begin(), solution.columns.end());
    cells.emplace_back("peak MiB", fmt::format("{:.1f}", peak_mib));
    // The table: the thread count, the method's columns and the peak memory, each column as wide
    // as its heading or its first value.
    std::vector<std::string> headings, values;
    for (const auto& [heading, value] : cells) {
      headings.push_back(heading);
      values.push_back(value);
    }
    if (widths.empty()) {
      for (std::size_t i = 0; i < cells.size(); ++i)
        widths.push_back(std::max(headings[i].size(), values[i].size()));
      std::cout << solve_table_line(headings, widths) << "\n";
    }
    std::cout << solve_table_line(values, widths) << "\n";
    runs.push_back(std::move(facts));
  }
  return write_json({{name,
                      {{"scene", scene_path.empty() ? "(built-in default)" : scene_path},
                       {"overrides", options.overrides},
                       {"machine", machine_facts()},
                       {"runs", runs}}}},
                    options);
}

int run_bench_command(const BenchCommandOptions& given) {
  // --json is checked before any work, against the meshes and scene given (a scene's own
  // files again once it is loaded, refuse_json_over_scene_files).
  if (!given.json_path.empty()) {
    check_writable(given.json_path, "--json");
    refuse_outputs_over_inputs({{given.json_path, "--json"}}, given.inputs);
  }
  if (!given.solve_method.empty()) return run_solve_bench_command(given);
  if (given.raster) return run_raster_bench_command(given);
  if (given.inputs.size() > 1) throw BadArgument("give exactly one of MESH, --sphere N or --terrain N");
  BenchCommandOptions options = given;
  if (!given.inputs.empty()) options.mesh_path = given.inputs.front();
  BenchOptions bench = bench_options(options);
  // --dump's files are outputs too, checked against --json and the mesh.
  if (!options.dump_directory.empty()) {
    std::vector<OutputFile> outputs;
    if (!options.json_path.empty()) outputs.push_back({options.json_path, "--json"});
    std::vector<std::string> sets{"primary", "incoherent"};
    for (const std::string& name : bench_accelerator_names()) sets.push_back("shadow-" + name);
    for (const std::string& set : sets)
      outputs.push_back(
          {(std::filesystem::path(options.dump_directory) / (set + ".rays")).string(), "--dump"});
    refuse_outputs_over_inputs(outputs, {options.mesh_path});
  }
  const auto log = [&](const std::string& line) {
    if (!options.quiet) std::cerr << "candela: bench: " << line << "\n";
  };
  if (is_scene_file(options.mesh_path)) {
    // A scene: its primitives as the loader makes them, rays from the bounds of its bounded
    // shapes; Embree's native triangle mode does not apply.
    if (options.sphere || options.terrain)
      throw BadArgument("give exactly one of MESH, --sphere N or --terrain N");
    const std::unique_ptr<Scene> scene = load_scene_file(options.mesh_path);
    refuse_json_over_scene_files(options, *scene);
    if (bench.accelerators.empty())
      for (const std::string& name : bench_accelerator_names())
        if (name != "embree") bench.accelerators.push_back(name);
    if (std::find(bench.accelerators.begin(), bench.accelerators.end(), "embree") != bench.accelerators.end())
      throw BadArgument("--accel embree measures Embree's own triangles: use embree-exact for a scene");
    const BenchScene primitives(scene->primitives);
    const BenchReport report = run_bench(
        BenchInput{options.mesh_path, scene->bounds(), scene->primitives.size(), &primitives}, bench, log);
    return finish_bench(report, options);
  }
  const BenchMesh mesh = load_mesh(options);
  if (mesh.skipped_faces > 0)
    std::cerr << fmt::format("candela: warning: {}: {} face(s) with an out-of-range index skipped\n",
                             mesh.name, mesh.skipped_faces);
  const BenchView view = resolve_view(mesh.bounds, bench.rays);
  const Vec3 forward = view.lookat - view.eye;
  if (!(length(cross(forward, Vec3{0, 1, 0})) > 0))
    throw BadArgument("--eye and --lookat must differ and the view must not be vertical");
  return finish_bench(run_bench(mesh, bench, log), options);
}

}  // namespace

void add_bench_command(CLI::App& app, std::function<int()>& run) {
  auto options = std::make_shared<BenchCommandOptions>();
  CLI::App* command =
      app.add_subcommand("bench", "Ray-set throughput and checksums per accelerator (shared/BENCH-RAYS.md)");
  command->add_option(
      "mesh", options->inputs,
      "Wavefront OBJ mesh (only v and f lines are read) or a scene file (.json); with --raster, "
      "any number of meshes (default: every .obj of ../shared/models)");
  command->add_flag(
      "--raster", options->raster,
      "Measure the scanline rasterizer (item buffer, depth, Gouraud, Phong passes) instead of rays");
  command->add_option(
      "--solve", options->solve_method,
      "Make METHOD's view-independent solution of SCENE (default: the built-in scene) once per "
      "--threads count and report its facts, times and memory (methods: " +
          [] {
            const auto names = method_names_with(&MethodCapabilities::standalone_solution);
            return fmt::format("{}", fmt::join(names, ", "));
          }() +
          ")");
  // One key=value per --set, as for render.
  command
      ->add_option("--set", options->overrides,
                   "--solve: override a scene setting (KEY=VALUE, as for render); rays: an accelerator's "
                   "setting, e.g. bvh.isa=sse")
      ->expected(1)
      ->allow_extra_args(false)
      ->take_all();
  command->add_option("--sphere", options->sphere, "Generated UV sphere of about N triangles");
  command->add_option("--terrain", options->terrain, "Generated height field of about N triangles");
  add_list_option(command, "--accel", options->accelerators,
                  "Accelerators (default: every registered one); embree = Embree's own triangle test, "
                  "embree-exact = Embree with Candela's tests");
  add_list_option(command, "--threads,--nthreads", options->threads,
                  "Thread counts to run (default: 1 2; --solve: every core)");
  command->add_option("--json", options->json_path, "Write the results as JSON");
  command->add_option("--seed", options->seed, "Seed of the incoherent rays (default 1)");
  add_list_option(command, "--eye", options->eye, "Camera position X,Y,Z (default: from the bounds)", 3);
  add_list_option(command, "--lookat", options->lookat, "Camera target X,Y,Z (default: the bounds' centre)",
                  3);
  command->add_option("--fov", options->fov, "Vertical field of view in degrees (default 45)");
  add_list_option(command, "--light", options->light,
                  "Point light X,Y,Z of the shadow rays (default: from the bounds)", 3);
  command->add_option("--width", options->width,
                      "Primary rays per row (default 1024; --raster: image width, 1024)");
  command->add_option("--height", options->height,
                      "Rows of primary rays (default 1024; --raster: image height, 768)");
  command->add_option("--rays", options->rays, "Incoherent rays (default: width x height)");
  command->add_option("--repeat", options->repeat, "Timed repetitions (default 3)");
  command->add_option(
      "--min-time", options->min_time,
      "Stop repeating once the timed repetitions took this many seconds (default 0.5; --raster: "
      "repeat until they took at least this long, default 1)");
  command->add_option("--dump", options->dump_directory, "Write the ray sets to this directory");
  command->add_flag("-q,--quiet", options->quiet, "No progress lines");
  command->callback([options, command, &run]() {
    options->width_given = command->count("--width") > 0;
    options->height_given = command->count("--height") > 0;
    options->min_time_given = command->count("--min-time") > 0;
    options->fov_given = command->count("--fov") > 0;
    options->repeat_given = command->count("--repeat") > 0;
    options->seed_given = command->count("--seed") > 0;
    run = [options]() { return run_reporting_bad_input([&] { return run_bench_command(*options); }); };
  });
}

}  // namespace candela::cli
