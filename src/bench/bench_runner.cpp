#include "bench/bench_runner.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "accel/accelerator_registry.h"
#include "io/json_document.h"
#include "io/json_node.h"
#include "util/atomic_file.h"
#include "util/registry.h"
#include "util/statistics.h"
#ifdef CANDELA_HAVE_EMBREE
#include "accel/embree_accelerator.h"
#endif

namespace candela {

BenchScene::BenchScene(std::shared_ptr<const TriangleMesh> mesh) {
  shapes_ = make_triangles(std::move(mesh), &skipped_degenerate_, &merged_duplicates_);
  primitives_.reserve(shapes_.size());
  triangle_ids_.reserve(shapes_.size());
  for (const auto& shape : shapes_) {
    primitives_.push_back(Primitive{shape.get(), 0, 0});
    // make_triangles leaves degenerate and repeated triangles out: the id is the triangle's, not
    // the index.
    triangle_ids_.push_back(static_cast<const MeshTriangle&>(*shape).triangle_index());
  }
}

BenchScene::BenchScene(std::span<const Primitive> primitives)
    : primitives_(primitives.begin(), primitives.end()) {
  triangle_ids_.resize(primitives_.size());
  for (uint32_t i = 0; i < triangle_ids_.size(); ++i) triangle_ids_[i] = i;
}

void trace_rays(const Accelerator& accelerator, std::span<const BenchRay> rays, RayQuery query,
                TraceResults& results) {
  results.t.resize(rays.size());
  results.primitive.resize(rays.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), 256),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      Intersection intersection;
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        const Ray ray = to_ray(rays[i]);
                        if (query == RayQuery::nearest) {
                          if (accelerator.intersect(ray, intersection)) {
                            results.t[i] = intersection.surface.t;
                            results.primitive[i] = intersection.primitive;
                          } else {
                            results.t[i] = kInfinity;
                            results.primitive[i] = TraceResults::kNoHit;
                          }
                        } else {
                          results.t[i] = accelerator.occluded(ray) ? 0.0 : kInfinity;
                          results.primitive[i] = TraceResults::kNoHit;
                        }
                      }
                    });
}

Checksums checksums(const TraceResults& results, const BenchScene& scene, RayQuery query) {
  Checksums sums;
  for (std::size_t i = 0; i < results.t.size(); ++i) {
    if (!std::isfinite(results.t[i])) continue;
    ++sums.hits;
    if (query == RayQuery::nearest) {
      sums.sum_t += results.t[i];
      sums.sum_prim += scene.triangle_id(results.primitive[i]);
    }
  }
  return sums;
}

std::vector<std::string> bench_accelerator_names() {
  std::vector<std::string> names;
  for (const AcceleratorEntry& entry : accelerator_entries()) names.emplace_back(entry.name);
#ifdef CANDELA_HAVE_EMBREE
  names.emplace_back("embree-exact");
#endif
  return names;
}

std::unique_ptr<Accelerator> make_bench_accelerator(std::string_view name,
                                                    const std::vector<std::string>& settings) {
  if (!settings.empty()) {
    JsonDocument document = JsonDocument::parse("{}", "--set");
    for (const std::string& assignment : settings) document.apply_override(assignment);
    for (const auto& [key, value] : document.root().items()) {
      if (!find_accelerator(key))
        throw InputError(document.locate(key), "no accelerator named " + key + " (expected one of: " +
                                                   entry_names(accelerator_entries()) + ")");
    }
    const AcceleratorEntry* entry = find_accelerator(name);
    if (entry && document.root().contains(std::string(name)))
      return entry->create(JsonNode(document, document.root()[std::string(name)], std::string(name)),
                           BoundingVolumeKind::none);
  }
#ifdef CANDELA_HAVE_EMBREE
  if (name == "embree") return std::make_unique<EmbreeAccelerator>(EmbreeAccelerator::Mode::native_triangles);
  if (name == "embree-exact") return std::make_unique<EmbreeAccelerator>(EmbreeAccelerator::Mode::exact);
#endif
  const AcceleratorEntry* entry = find_accelerator(name);
  return entry ? create_default_accelerator(*entry) : nullptr;
}

void write_ray_dump(const std::string& directory, const std::string& set, std::span<const BenchRay> rays) {
  static_assert(sizeof(BenchRay) == 32 && std::endian::native == std::endian::little,
                "the dump format is packed little-endian float32");
  const std::string path = (std::filesystem::path(directory) / (set + ".rays")).string();
  write_atomically(path, [&](const std::string& temporary) {
    std::ofstream out(temporary, std::ios::binary);
    out.write(reinterpret_cast<const char*>(rays.data()), static_cast<std::streamsize>(rays.size_bytes()));
    out.close();
    if (!out) throw std::runtime_error("cannot write " + path);
  });
}

namespace {

struct RaySet {
  std::string name;
  RayQuery query;
  std::span<const BenchRay> rays;
};

BenchResult time_set(const Accelerator& accelerator, const BenchScene& scene, const RaySet& set,
                     const BenchOptions& options, int threads, TraceResults& results) {
  BenchResult result;
  result.accel = std::string(accelerator.name());
  result.set = set.name;
  result.threads = threads;
  result.rays = set.rays.size();
  trace_rays(accelerator, set.rays, set.query, results);  // warm-up, untimed
  Stopwatch timer;
  do {
    trace_rays(accelerator, set.rays, set.query, results);
    ++result.repetitions;
    result.seconds = timer.seconds();
  } while (result.repetitions < options.repeat && result.seconds < options.min_seconds);
  if (result.seconds > 0)
    result.mrays_per_s = static_cast<double>(result.rays) * result.repetitions / result.seconds / 1e6;
  result.checksums = checksums(results, scene, set.query);
  return result;
}

void write_dump_index(const std::string& directory, const BenchInput& mesh, const RaySetOptions& options,
                      const nlohmann::json& sets) {
  const BenchView view = resolve_view(mesh.bounds, options);
  const auto vec = [](const Vec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); };
  nlohmann::json index = {
      {"format", "packed little-endian float32 records: origin xyz, direction xyz, tnear, tfar (32 bytes)"},
      {"mesh", mesh.name},
      {"triangles", mesh.triangles},
      {"bounds", {vec(mesh.bounds.lower), vec(mesh.bounds.upper)}},
      {"eye", vec(view.eye)},
      {"lookat", vec(view.lookat)},
      {"light", vec(view.light)},
      {"fov", options.fov_degrees},
      {"width", options.width},
      {"height", options.height},
      {"seed", options.seed},
      {"sets", sets}};
  const std::string path = (std::filesystem::path(directory) / "rays.json").string();
  const std::string text = index.dump(2) + "\n";
  write_atomically(path, [&](const std::string& temporary) {
    std::ofstream out(temporary);
    out << text;
    out.close();
    if (!out) throw std::runtime_error("cannot write " + path);
  });
}

}  // namespace

BenchReport run_bench(const BenchMesh& mesh, const BenchOptions& options,
                      const std::function<void(const std::string&)>& log) {
  const BenchScene scene(mesh.mesh);
  if (scene.skipped_degenerate() > 0 && log)
    log(fmt::format("{} degenerate triangle(s) are never hit (they keep their ids)",
                    scene.skipped_degenerate()));
  if (scene.merged_duplicates() > 0 && log)
    log(fmt::format("{} duplicate triangle(s) merged into their first copy (they keep their ids)",
                    scene.merged_duplicates()));
  return run_bench(BenchInput{mesh.name, mesh.bounds, mesh.mesh->triangles.size(), &scene}, options, log);
}

BenchReport run_bench(const BenchInput& mesh, const BenchOptions& options,
                      const std::function<void(const std::string&)>& log) {
  const auto say = [&](const std::string& line) {
    if (log) log(line);
  };
  std::vector<std::string> names = options.accelerators;
  if (names.empty())
    for (const AcceleratorEntry& entry : accelerator_entries()) names.emplace_back(entry.name);
  for (const std::string& name : names)
    if (!make_bench_accelerator(name, options.accelerator_settings))
      throw std::invalid_argument("unknown accelerator \"" + name + "\" (expected one of: " + [] {
        std::string list;
        for (const std::string& n : bench_accelerator_names()) list += (list.empty() ? "" : ", ") + n;
        return list;
      }() + ")");
  if (options.threads.empty()) throw std::invalid_argument("no thread count");
  for (const int threads : options.threads)
    if (threads < 1) throw std::invalid_argument("thread counts must be >= 1");
  if (options.repeat < 1) throw std::invalid_argument("--repeat must be >= 1");

  BenchReport report;
  report.mesh = mesh.name;
  report.triangles = mesh.triangles;
  const BenchScene& scene = *mesh.scene;

  const std::vector<BenchRay> primary = primary_rays(mesh.bounds, options.rays);
  const uint64_t incoherent_count = options.rays.incoherent_rays > 0
                                        ? options.rays.incoherent_rays
                                        : static_cast<uint64_t>(options.rays.width) * options.rays.height;
  const std::vector<BenchRay> incoherent = incoherent_rays(mesh.bounds, incoherent_count, options.rays.seed);
  nlohmann::json dumped = nlohmann::json::object();
  if (!options.dump_directory.empty()) {
    std::filesystem::create_directories(options.dump_directory);
    write_ray_dump(options.dump_directory, "primary", primary);
    write_ray_dump(options.dump_directory, "incoherent", incoherent);
    dumped["primary"] = {{"file", "primary.rays"}, {"rays", primary.size()}, {"query", "intersect"}};
    dumped["incoherent"] = {{"file", "incoherent.rays"}, {"rays", incoherent.size()}, {"query", "intersect"}};
    dumped["incoherent_occlusion"] = {
        {"file", "incoherent.rays"}, {"rays", incoherent.size()}, {"query", "occluded"}};
  }

  TraceResults primary_results, results;
  for (const int threads : options.threads) {
    tbb::global_control allow(tbb::global_control::max_allowed_parallelism,
                              static_cast<std::size_t>(threads));
    tbb::task_arena arena(threads);
    for (const std::string& name : names) {
      arena.execute([&] {
        std::unique_ptr<Accelerator> accelerator = make_bench_accelerator(name, options.accelerator_settings);
        Stopwatch build_timer;
        accelerator->build(scene.primitives());
        const double build_seconds = build_timer.seconds();
        const AcceleratorReport quality = accelerator->report();
        report.builds.push_back({name, threads, build_seconds, quality.bytes});
        say(fmt::format("{}, {} thread(s): built in {:.3f} s, {:.2f} MiB", name, threads, build_seconds,
                        quality.bytes / (1024.0 * 1024.0)));
        const auto known = std::find_if(report.quality.begin(), report.quality.end(),
                                        [&](const auto& entry) { return entry.first == name; });
        if (known == report.quality.end()) {
          report.quality.emplace_back(name, quality.text());
          for (const std::string& warning : quality.warnings) say("warning: " + warning);
        }

        const auto record = [&](BenchResult result) {
          result.accel = name;
          say(fmt::format("{} {} {} thread(s): {:.3f} Mrays/s ({} repetition(s), {:.2f} s)", name, result.set,
                          threads, result.mrays_per_s, result.repetitions, result.seconds));
          report.results.push_back(std::move(result));
        };
        record(time_set(*accelerator, scene, {"primary", RayQuery::nearest, primary}, options, threads,
                        primary_results));
        record(time_set(*accelerator, scene, {"incoherent", RayQuery::nearest, incoherent}, options, threads,
                        results));
        const std::vector<BenchRay> shadow =
            shadow_rays(mesh.bounds, options.rays, primary, primary_results.t);
        if (!options.dump_directory.empty() && threads == options.threads.front()) {
          const std::string set = "shadow-" + name;
          write_ray_dump(options.dump_directory, set, shadow);
          dumped[set] = {{"file", set + ".rays"}, {"rays", shadow.size()}, {"query", "occluded"}};
        }
        record(time_set(*accelerator, scene, {"shadow", RayQuery::any, shadow}, options, threads, results));
        record(time_set(*accelerator, scene, {"incoherent_occlusion", RayQuery::any, incoherent}, options,
                        threads, results));
      });
    }
  }
  if (!options.dump_directory.empty()) write_dump_index(options.dump_directory, mesh, options.rays, dumped);
  return report;
}

nlohmann::json BenchReport::to_json() const {
  nlohmann::json json = {{"mesh", mesh}, {"triangles", triangles}};
  nlohmann::json& result_list = json["results"] = nlohmann::json::array();
  for (const BenchResult& r : results)
    result_list.push_back({{"accel", r.accel},
                           {"set", r.set},
                           {"threads", r.threads},
                           {"rays", r.rays},
                           {"mrays_per_s", r.mrays_per_s},
                           {"hits", r.checksums.hits},
                           {"sum_t", r.checksums.sum_t},
                           {"sum_prim", r.checksums.sum_prim}});
  nlohmann::json& build_list = json["builds"] = nlohmann::json::array();
  for (const BenchBuild& b : builds)
    build_list.push_back(
        {{"accel", b.accel}, {"threads", b.threads}, {"seconds", b.seconds}, {"bytes", b.bytes}});
  return json;
}

std::string BenchReport::table() const {
  std::string text = fmt::format("mesh: {} ({} triangles)\n", mesh, triangles);
  text += fmt::format("{:<14} {:<21} {:>7} {:>9} {:>10} {:>9} {:>20} {:>14} {:>9}\n", "accel", "set",
                      "threads", "rays", "Mrays/s", "hits", "sum_t", "sum_prim", "/embree");
  // Grouped by set and thread count so that accelerators sit next to each other.
  std::vector<const BenchResult*> order;
  for (const BenchResult& r : results) order.push_back(&r);
  const auto set_rank = [](const std::string& set) {
    static const std::array<std::string_view, 4> kSets = {"primary", "incoherent", "shadow",
                                                          "incoherent_occlusion"};
    return std::find(kSets.begin(), kSets.end(), set) - kSets.begin();
  };
  std::stable_sort(order.begin(), order.end(), [&](const BenchResult* a, const BenchResult* b) {
    if (set_rank(a->set) != set_rank(b->set)) return set_rank(a->set) < set_rank(b->set);
    return a->threads < b->threads;
  });
  for (const BenchResult* r : order) {
    std::string ratio = "-";
    for (const BenchResult& e : results)
      if (e.accel == "embree" && e.set == r->set && e.threads == r->threads && e.mrays_per_s > 0)
        ratio = fmt::format("{:.3f}", r->mrays_per_s / e.mrays_per_s);
    text += fmt::format("{:<14} {:<21} {:>7} {:>9} {:>10.3f} {:>9} {:>20.12g} {:>14} {:>9}\n", r->accel,
                        r->set, r->threads, r->rays, r->mrays_per_s, r->checksums.hits, r->checksums.sum_t,
                        r->checksums.sum_prim, ratio);
  }
  text += fmt::format("\n{:<14} {:>7} {:>10} {:>12}\n", "build", "threads", "seconds", "MiB");
  for (const BenchBuild& b : builds)
    text += fmt::format("{:<14} {:>7} {:>10.4f} {:>12.3f}\n", b.accel, b.threads, b.seconds,
                        b.bytes / (1024.0 * 1024.0));
  text += "\n";
  for (const auto& [name, quality] : quality) text += fmt::format("{}: {}\n", name, quality);
  return text;
}

}  // namespace candela
