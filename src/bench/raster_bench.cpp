#include "bench/raster_bench.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "camera/perspective_camera.h"
#include "math/constants.h"
#include "raster/item_buffer.h"
#include "raster/rasterizer.h"
#include "util/statistics.h"

namespace candela {

namespace {

// Area-weighted vertex normals by index (the bench meshes share vertices between faces).
std::vector<Vec3> vertex_normals(const TriangleMesh& mesh) {
  std::vector<Vec3> normals(mesh.positions.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Vec3 face = mesh.face_cross(t);
    if (!is_finite(face)) continue;
    for (const uint32_t corner : mesh.triangles[t]) normals[corner] += face;
  }
  for (Vec3& n : normals) {
    const double n_length = length(n);
    n = n_length > 0 ? n / n_length : Vec3{0, 0, 1};
  }
  return normals;
}

// What a frame of one pass needs: the mesh, its clip-space positions and the light.
struct Frame {
  const TriangleMesh& mesh;
  const std::vector<Vec3>& normals;
  Eigen::Matrix4d clip_from_world;
  Vec3 eye;
  std::vector<Eigen::Vector4d> clip;  // per position, filled by each frame
  std::vector<float> image;           // width × height intensities of the shaded passes
  int width;

  void transform() {
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
      const Vec3& p = mesh.positions[i];
      clip[i] = clip_from_world * Eigen::Vector4d(p.x, p.y, p.z, 1);
    }
  }
  // Two-sided Lambert with a light at the eye.
  double lambert(std::size_t vertex, const Vec3& normal) const {
    const Vec3 to_light = normalize(eye - mesh.positions[vertex]);
    return std::fabs(dot(normal, to_light));
  }
};

// Draws every triangle with the corners' varyings filled by fill(corner index, vertex).
template <typename Fill, typename Shade>
void draw_mesh(Rasterizer& rasterizer, const Frame& frame, int varying_count, Fill&& fill, Shade&& shade) {
  RasterVertex corners[3];
  for (const auto& triangle : frame.mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      corners[k].clip = frame.clip[triangle[k]];
      fill(corners[k], triangle[k]);
    }
    rasterizer.draw_triangle(corners[0], corners[1], corners[2], varying_count, shade);
  }
}

// Times frames of one pass: clear() untimed, frame() timed, until enough frames and time.
template <typename Clear, typename DrawFrame, typename Statistics>
RasterPassResult time_pass(const std::string& name, uint64_t triangles, const RasterBenchOptions& options,
                           Clear&& clear, DrawFrame&& draw_frame, Statistics&& statistics) {
  RasterPassResult result;
  result.pass = name;
  clear();
  draw_frame();  // warm-up: caches, page faults of the buffers
  result.best_seconds = kInfinity;
  constexpr int kMaxFrames = 1'000'000;
  while ((result.frames < options.repeat || result.total_seconds < options.min_seconds) &&
         result.frames < kMaxFrames) {
    clear();
    const Stopwatch timer;
    draw_frame();
    const double seconds = timer.seconds();
    result.best_seconds = std::min(result.best_seconds, seconds);
    result.total_seconds += seconds;
    ++result.frames;
  }
  const RasterStatistics& frame = statistics();
  result.culled = frame.culled;
  result.clipped = frame.clipped;
  result.fragments = frame.fragments;
  result.written = frame.written;
  const double best = std::max(result.best_seconds, 1e-12);
  result.mtriangles_per_s = static_cast<double>(triangles) / best * 1e-6;
  result.mfragments_per_s = static_cast<double>(frame.written) / best * 1e-6;
  return result;
}

}  // namespace

RasterBenchReport run_raster_bench(const BenchMesh& mesh, const RasterBenchOptions& options,
                                   const std::function<void(const std::string&)>& log) {
  if (options.width < 1 || options.height < 1) throw std::invalid_argument("raster bench: size must be >= 1");
  if (!(options.fov_degrees > 0 && options.fov_degrees < 180))
    throw std::invalid_argument("raster bench: the field of view must lie in (0, 180) degrees");
  if (options.repeat < 1) throw std::invalid_argument("raster bench: repeat must be >= 1");
  if (!(options.min_seconds >= 0) || !std::isfinite(options.min_seconds))
    throw std::invalid_argument("raster bench: min_seconds must be >= 0");
  if (!mesh.mesh || mesh.bounds.empty() || !mesh.bounds.is_finite())
    throw std::invalid_argument("raster bench: the mesh has no finite bounds");
  const TriangleMesh& triangles = *mesh.mesh;

  RasterBenchReport report;
  report.mesh = mesh.name;
  report.triangles = triangles.triangles.size();
  report.width = options.width;
  report.height = options.height;
  report.fov_degrees = options.fov_degrees;

  // The bounding sphere just filling the vertical field of view.
  const Vec3 centre = mesh.bounds.center();
  const double radius = std::max(0.5 * length(mesh.bounds.diagonal()), 1e-9 * (1 + length(centre)));
  const double half_fov = degrees_to_radians(options.fov_degrees) / 2;
  const double distance = radius / std::sin(half_fov);
  report.target = centre;
  report.eye = centre + normalize(Vec3{0.6, 0.45, 1.0}) * distance;
  report.near = (distance - radius) / 2;
  report.far = 2 * (distance + radius);
  const double horizontal_fov =
      2 * std::atan(std::tan(half_fov) * options.width / options.height) * (180.0 / kPi);
  const PerspectiveCamera camera(report.eye, report.target, {0, 1, 0}, horizontal_fov, options.width,
                                 options.height);

  const std::vector<Vec3> normals = vertex_normals(triangles);
  Frame frame{
      triangles,
      normals,
      camera.view_projection(report.near, report.far),
      report.eye,
      std::vector<Eigen::Vector4d>(triangles.positions.size()),
      std::vector<float>(static_cast<std::size_t>(options.width) * static_cast<std::size_t>(options.height)),
      options.width};
  const auto say = [&](const RasterPassResult& r) {
    if (log)
      log(fmt::format("{}: {}: {:.2f} Mtriangles/s, {:.2f} Mfragments/s ({} frame(s), best {:.3f} ms)",
                      mesh.name, r.pass, r.mtriangles_per_s, r.mfragments_per_s, r.frames,
                      r.best_seconds * 1e3));
  };

  {
    ItemBuffer items(options.width, options.height);
    report.passes.push_back(time_pass(
        "item_buffer", report.triangles, options,
        [&] {
          items.clear();
          items.reset_statistics();
        },
        [&] { items.draw(frame.clip_from_world, triangles); },
        [&]() -> const RasterStatistics& { return items.statistics(); }));
    say(report.passes.back());
  }

  Rasterizer rasterizer(options.width, options.height);
  const auto clear = [&] {
    rasterizer.clear_depth();
    rasterizer.reset_statistics();
    std::fill(frame.image.begin(), frame.image.end(), 0.0f);
  };
  const auto statistics = [&]() -> const RasterStatistics& { return rasterizer.statistics(); };
  const auto no_varyings = [](RasterVertex&, uint32_t) {};
  const std::size_t width = static_cast<std::size_t>(options.width);

  report.passes.push_back(time_pass(
      "depth", report.triangles, options, clear,
      [&] {
        frame.transform();
        draw_mesh(rasterizer, frame, 0, no_varyings, [](const Fragment&) { return true; });
      },
      statistics));
  say(report.passes.back());

  std::vector<double> intensities(triangles.positions.size());
  report.passes.push_back(time_pass(
      "gouraud", report.triangles, options, clear,
      [&] {
        frame.transform();
        for (std::size_t i = 0; i < intensities.size(); ++i) intensities[i] = frame.lambert(i, normals[i]);
        draw_mesh(
            rasterizer, frame, 1,
            [&](RasterVertex& corner, uint32_t vertex) { corner.varyings[0] = intensities[vertex]; },
            [&](const Fragment& f) {
              frame.image[static_cast<std::size_t>(f.y) * width + static_cast<std::size_t>(f.x)] =
                  static_cast<float>(f.varyings[0]);
              return true;
            });
      },
      statistics));
  say(report.passes.back());

  report.passes.push_back(time_pass(
      "phong", report.triangles, options, clear,
      [&] {
        frame.transform();
        // The model per pixel needs the point too: the world position rides along (6 varyings).
        draw_mesh(
            rasterizer, frame, 6,
            [&](RasterVertex& corner, uint32_t vertex) {
              const Vec3& n = normals[vertex];
              const Vec3& p = triangles.positions[vertex];
              corner.varyings[0] = n.x;
              corner.varyings[1] = n.y;
              corner.varyings[2] = n.z;
              corner.varyings[3] = p.x;
              corner.varyings[4] = p.y;
              corner.varyings[5] = p.z;
            },
            [&](const Fragment& f) {
              const Vec3 normal{f.varyings[0], f.varyings[1], f.varyings[2]};
              const Vec3 to_light = report.eye - Vec3{f.varyings[3], f.varyings[4], f.varyings[5]};
              const double shade = std::fabs(dot(normal, to_light)) /
                                   std::sqrt(length_squared(normal) * length_squared(to_light));
              frame.image[static_cast<std::size_t>(f.y) * width + static_cast<std::size_t>(f.x)] =
                  static_cast<float>(shade);
              return true;
            });
      },
      statistics));
  say(report.passes.back());
  return report;
}

nlohmann::json RasterBenchReport::to_json() const {
  nlohmann::json json = {{"mesh", mesh},
                         {"triangles", triangles},
                         {"width", width},
                         {"height", height},
                         {"fov", fov_degrees},
                         {"eye", {eye.x, eye.y, eye.z}},
                         {"target", {target.x, target.y, target.z}},
                         {"near", near},
                         {"far", far}};
  nlohmann::json& list = json["passes"] = nlohmann::json::array();
  for (const RasterPassResult& p : passes)
    list.push_back({{"pass", p.pass},
                    {"frames", p.frames},
                    {"best_seconds", p.best_seconds},
                    {"total_seconds", p.total_seconds},
                    {"mtriangles_per_s", p.mtriangles_per_s},
                    {"mfragments_per_s", p.mfragments_per_s},
                    {"culled", p.culled},
                    {"clipped", p.clipped},
                    {"fragments", p.fragments},
                    {"written", p.written}});
  return json;
}

std::string RasterBenchReport::table() const {
  std::string text = fmt::format("mesh: {} ({} triangles), {}x{}, vertical fov {} degrees, 1 thread\n", mesh,
                                 triangles, width, height, fov_degrees);
  text += fmt::format("{:<12} {:>7} {:>10} {:>10} {:>10} {:>10} {:>10} {:>8} {:>8}\n", "pass", "frames",
                      "best ms", "Mtri/s", "Mfrag/s", "fragments", "written", "culled", "clipped");
  for (const RasterPassResult& p : passes)
    text += fmt::format("{:<12} {:>7} {:>10.3f} {:>10.2f} {:>10.2f} {:>10} {:>10} {:>8} {:>8}\n", p.pass,
                        p.frames, p.best_seconds * 1e3, p.mtriangles_per_s, p.mfragments_per_s, p.fragments,
                        p.written, p.culled, p.clipped);
  return text;
}

}  // namespace candela
