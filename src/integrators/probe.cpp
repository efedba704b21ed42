#include "integrators/probe.h"

#include <fmt/format.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "integrators/light_sampler.h"
#include "integrators/method_registry.h"
#include "integrators/path_tracer.h"
#include "integrators/solution_field.h"
#include "math/constants.h"
#include "math/direction.h"
#include "sampling/multiple_importance.h"
#include "sampling/sampler.h"
#include "sampling/warps.h"
#include "scene/direct_irradiance.h"
#include "shading/bsdf.h"
#include "util/error.h"
#include "util/input_file.h"
#include "util/progress.h"

namespace candela {

Color unobstructed_sky_irradiance(const Scene& scene) {
  if (!scene.environment) return {};
  // An environment value C is π × its radiance (a constant C gives irradiance C): the irradiance
  // ∫ (C/π) cos θ dω is the mean of C over cosine-distributed directions.
  constexpr int kCells = 512;
  Color sum;
  for (int i = 0; i < kCells; ++i)
    for (int j = 0; j < kCells; ++j) {
      const Vec3 local = square_to_cosine_hemisphere({(i + 0.5) / kCells, (j + 0.5) / kCells});
      sum += scene.environment->radiance(Vec3{local.x, local.z, local.y});  // z up → y up
    }
  return sum / (double(kCells) * kCells);
}

IlluminanceStatistics illuminance_statistics(const std::vector<double>& illuminance) {
  if (illuminance.empty()) throw std::invalid_argument("illuminance statistics of no points");
  IlluminanceStatistics statistics;
  statistics.points = illuminance.size();
  statistics.minimum = std::numeric_limits<double>::infinity();
  statistics.maximum = -std::numeric_limits<double>::infinity();
  double sum = 0;
  for (const double value : illuminance) {
    if (!std::isfinite(value)) throw std::invalid_argument("illuminance statistics of a non-finite value");
    statistics.minimum = std::min(statistics.minimum, value);
    statistics.maximum = std::max(statistics.maximum, value);
    sum += value;
  }
  statistics.average = sum / double(illuminance.size());
  if (statistics.average > 0) statistics.uniformity_min_average = statistics.minimum / statistics.average;
  if (statistics.maximum > 0) statistics.uniformity_min_max = statistics.minimum / statistics.maximum;
  return statistics;
}

namespace {

// The mean of n samples' luminances and its standard error from their sum and sum of squares.
double standard_error(double sum, double sum_of_squares, int n) {
  if (n < 2) return 0;
  const double mean = sum / n;
  return std::sqrt(std::max(0.0, (sum_of_squares - n * mean * mean) / (double(n - 1) * n)));
}

// The probe's samples apart from the image pixels' (a seed of its own; PCG32 drops the sequence's
// top bit, so a flag there would not do).
constexpr uint64_t kProbeSeed = 0x50524f4245ULL;  // "PROBE"

// Probe point `index` as the pixel (x, y) its samples are keyed by: its low and high 32 bits.
uint32_t point_x(std::size_t index) {
  return static_cast<uint32_t>(index & 0xffffffffu);
}
uint32_t point_y(std::size_t index) {
  return static_cast<uint32_t>(uint64_t(index) >> 32);
}

// The stream of the gathering rays at probe point `index` (radiosity, meshless).
Pcg32 probe_rng(uint64_t seed, uint64_t sample, std::size_t index) {
  return path_pixel_rng(seed ^ kProbeSeed, sample, point_x(index), point_y(index));
}

Vec3 sensor_origin(const Scene& scene, const ProbePoint& point) {
  return point.position + point.normal * scene.ray_offset(point.position);
}

// Sample s of point `index` from the scene's path.sampler (Sobol' by default: the first light
// sample and the first bounce stratified over the point's samples, so daylight openings
// converge as the image's pixels do), the point's number standing for the pixel, and seeded apart
// from the image's pixels (kProbeSeed).
ProbeResult probe_path(const Scene& scene, const PathSettings& path, const LightSampler& lights,
                       const ProbePoint& point, std::size_t index, const ProbeSettings& settings,
                       Sampler& sampler, RayCounts& rays) {
  Color irradiance, radiance;
  double sum = 0, sum_of_squares = 0;
  const Ray look{sensor_origin(scene, point), point.normal};
  for (int s = 0; s < settings.samples; ++s) {
    sampler.start_pixel_sample(point_x(index), point_y(index), uint64_t(s));
    sampler.get_2d();  // the pixel point: no pixel here
    const Color sample = path_irradiance(scene, path, lights, point.position, point.normal, sampler, rays);
    irradiance += sample;
    sum += luminance(sample);
    sum_of_squares += luminance(sample) * luminance(sample);
    radiance += path_radiance(scene, path, lights, look, sampler, rays);
  }
  // path_irradiance is in display units already irradiance; path_radiance is π × radiance.
  return {irradiance / settings.samples, radiance / (settings.samples * kPi),
          standard_error(sum, sum_of_squares, settings.samples)};
}

// E = ∫ (B/π) cos θ dω by two strategies combined with MIS (the power heuristic): k × k stratified
// cosine-distributed rays (density cos θ/π), and as many points drawn on the emissive surfaces by
// the path tracer's light sampler (a small lamp is otherwise found by few rays). A point on an
// emitter counts only when the ray toward it hits that primitive first.
ProbeResult probe_field(const Scene& scene, const SolutionField& field, const LightSampler& lights,
                        const ProbePoint& point, std::size_t index, const ProbeSettings& settings,
                        uint64_t& uncovered, RayCounts& rays) {
  const ShadingFrame frame = ShadingFrame::from_normal(point.normal);
  const Vec3 origin = sensor_origin(scene, point);
  // The exitance the ray sees (the environment's where it leaves: the background lights nothing)
  // and the hit's primitive — through window panes, times what they let through (the solutions
  // take a pane as a black patch: what it reflects is not counted).
  const auto seen = [&](const Ray& ray, Intersection& hit, bool& found) {
    Color through;
    found = scene.intersect_past_sheets(ray, hit, through);
    if (!found) return scene.sky_along(ray.direction) * through;
    if (through.is_black()) return Color();
    Color b;
    if (field.exitance(ray, hit, b)) return b * through;
    ++uncovered;
    return Color();
  };
  // The density the light strategy gives the direction toward hit.
  const auto light_pdf = [&](const Intersection& hit) {
    return lights.surface_pdf(hit.primitive, point.position, hit.surface);
  };
  const int k = std::max(1, static_cast<int>(std::ceil(std::sqrt(double(settings.samples)))));
  const int n = k * k;
  Pcg32 rng = probe_rng(settings.seed, 0, index);
  // Sample s's part of the estimate, both strategies' (the k × k cosine strata, then the light
  // points): their spread gives the standard error.
  std::vector<Color> parts(static_cast<std::size_t>(n));
  for (int j = 0; j < k; ++j)
    for (int i = 0; i < k; ++i) {
      const Vec2 u{(i + rng.next_double()) / k, (j + rng.next_double()) / k};
      const Vec3 local = square_to_cosine_hemisphere(u);
      const Vec3 direction = normalize(frame.to_world(local));
      ++rays.reflected;
      Intersection hit;
      bool found = false;
      const Color b = seen(Ray{origin, direction}, hit, found);
      const double p_cosine = cosine_hemisphere_pdf(local);
      const double weight = found ? power_heuristic(p_cosine, light_pdf(hit)) : 1.0;
      // (B/π)·cos/pdf with pdf = cos/π: B.
      parts[std::size_t(j) * k + i] += b * weight;
    }
  if (!lights.empty())
    for (int s = 0; s < n; ++s) {
      const LightSampler::Choice choice = lights.choose(rng.next_double());
      const Vec2 u{rng.next_double(), rng.next_double()};
      if (!scene.is_surface_emitter(choice.emitter)) continue;  // only surfaces carry a solution
      LightSample sample;
      if (!scene.emitter(choice.emitter).illuminate_random(point.position, u, sample) || !(sample.pdf > 0))
        continue;
      const Vec3 target = point.position + sample.direction * sample.distance;
      const Vec3 direction = normalize(target - origin);
      const double cosine = dot(direction, point.normal);
      if (!(cosine > 0)) continue;
      ++rays.shadow;
      Intersection hit;
      bool found = false;
      const Color b = seen(Ray{origin, direction}, hit, found);
      // Hidden (something nearer than the sampled point), or missed by rounding.
      if (!found ||
          length(hit.surface.position - target) > 2 * scene.ray_offset(target) + 1e-9 * sample.distance)
        continue;
      const double p_light = light_pdf(hit);
      if (!(p_light > 0)) continue;
      const double weight = power_heuristic(p_light, cosine * kInvPi);
      parts[s] += b * (kInvPi * cosine * weight / p_light);
    }
  Color sum;
  double luminance_sum = 0, luminance_squares = 0;
  for (const Color& part : parts) {
    sum += part;
    luminance_sum += luminance(part);
    luminance_squares += luminance(part) * luminance(part);
  }
  const Color irradiance = sum / double(n) + field.direct_irradiance(point.position, point.normal);
  ++rays.primary;
  Intersection hit;
  bool found = false;
  const Color radiance = seen(Ray{origin, point.normal}, hit, found) / kPi;
  return {irradiance, radiance, standard_error(luminance_sum, luminance_squares, n)};
}

// The local model's answer (CIE 171's direct cases): the irradiance straight from
// every emitter — lights, emissive surfaces (their jittered samples) and the environment — with
// opaque shadows, scene/direct_irradiance.h's sum; no interreflection. Deterministic: no samples.
ProbeResult probe_local(const Scene& scene, const ProbePoint& point, const ProbeSettings& settings,
                        RayCounts& rays) {
  const StratumJitter jitter{true, settings.seed};
  ProbeResult result;
  result.irradiance = direct_irradiance(scene, point.position, point.normal, EmitterSet::everything, jitter);
  ++rays.primary;
  Intersection hit;
  const Ray look{sensor_origin(scene, point), point.normal};
  result.radiance =
      (scene.intersect(look, hit) ? scene.material_of(hit).emission : scene.sky_along(look.direction)) / kPi;
  return result;
}

[[noreturn]] void fail(const std::string& path, int line, int column, const std::string& message) {
  throw InputError({path, line, column, {}}, message);
}

}  // namespace

std::string probe_method_names() {
  std::string names;
  for (const std::string_view name : method_names_with(&MethodCapabilities::probe))
    names += (names.empty() ? "" : ", ") + std::string(name);
  return names;
}

namespace {

// The path tracer's answer: path.sampler's samples, one sampler per thread.
class PathProbe final : public PointProbe {
 public:
  PathProbe(const Scene& scene, const PathSettings& path, const ProbeSettings& settings)
      : scene_(scene),
        path_(path),
        settings_(settings),
        lights_(scene),
        prototype_(create_sampler(path.sampler,
                                  SamplerParameters{settings.seed ^ kProbeSeed, uint64_t(settings.samples)})),
        samplers_([this] { return prototype_->clone(); }) {}
  ProbeResult probe(const ProbePoint& point, std::size_t index, RayCounts& rays) const override {
    return probe_path(scene_, path_, lights_, point, index, settings_, *samplers_.local(), rays);
  }

 private:
  const Scene& scene_;
  const PathSettings path_;
  const ProbeSettings settings_;
  const LightSampler lights_;
  const std::unique_ptr<Sampler> prototype_;
  mutable tbb::enumerable_thread_specific<std::unique_ptr<Sampler>> samplers_;
};

class LocalProbe final : public PointProbe {
 public:
  LocalProbe(const Scene& scene, const ProbeSettings& settings) : scene_(scene), settings_(settings) {}
  ProbeResult probe(const ProbePoint& point, std::size_t, RayCounts& rays) const override {
    return probe_local(scene_, point, settings_, rays);
  }

 private:
  const Scene& scene_;
  const ProbeSettings settings_;
};

// A view-independent solution's answer, gathered over the hemisphere (probe_field).
class FieldProbe final : public PointProbe {
 public:
  FieldProbe(const Scene& scene, std::unique_ptr<SolutionField> field, const ProbeSettings& settings)
      : scene_(scene), field_(std::move(field)), settings_(settings), lights_(scene) {}
  ProbeResult probe(const ProbePoint& point, std::size_t index, RayCounts& rays) const override {
    return probe_field(scene_, *field_, lights_, point, index, settings_, uncovered_.local(), rays);
  }
  void add_facts(nlohmann::json& facts) const override {
    uint64_t missing = 0;
    for (const uint64_t m : uncovered_) missing += m;
    facts["rays_without_solution"] = missing;
  }

 private:
  const Scene& scene_;
  const std::unique_ptr<SolutionField> field_;
  const ProbeSettings settings_;
  const LightSampler lights_;
  mutable tbb::enumerable_thread_specific<uint64_t> uncovered_;
};

}  // namespace

std::unique_ptr<PointProbe> make_path_probe(const Scene& scene, const PathSettings& path,
                                            const ProbeSettings& settings) {
  return std::make_unique<PathProbe>(scene, path, settings);
}

std::unique_ptr<PointProbe> make_local_probe(const Scene& scene, const ProbeSettings& settings) {
  return std::make_unique<LocalProbe>(scene, settings);
}

std::unique_ptr<PointProbe> make_field_probe(const Scene& scene, std::unique_ptr<SolutionField> field,
                                             const ProbeSettings& settings) {
  return std::make_unique<FieldProbe>(scene, std::move(field), settings);
}

std::unique_ptr<PointProbe> Method::point_probe(const Scene&, const ProbeSettings&) const {
  return nullptr;
}

std::vector<ProbeResult> probe(const Scene& scene, const std::vector<ProbePoint>& points,
                               const ProbeSettings& settings, nlohmann::json* facts) {
  if (settings.samples < 1) throw std::invalid_argument("probe: samples must be >= 1");
  // The method answers for itself, with its own settings as its reader reads them.
  const MethodEntry* entry = find_method(settings.method);
  const std::unique_ptr<Method> method =
      entry && entry->capabilities.probe ? entry->create(scene.plugin_settings.node(entry->name)) : nullptr;
  const std::unique_ptr<PointProbe> prober = method ? method->point_probe(scene, settings) : nullptr;
  if (!prober)
    throw std::invalid_argument("probe: method \"" + settings.method +
                                "\" cannot be probed (expected one of: " + probe_method_names() + ")");
  std::vector<ProbeResult> results(points.size());
  tbb::enumerable_thread_specific<RayCounts> counts;
  ProgressReporter progress("probe", points.size(), "points", settings.quiet);
  tbb::parallel_for(std::size_t(0), points.size(), [&](std::size_t i) {
    results[i] = prober->probe(points[i], i, counts.local());
    progress.advance();
  });
  progress.finish();
  if (facts) {
    RayCounts rays;
    for (const RayCounts& c : counts) rays += c;
    (*facts)["method"] = settings.method;
    (*facts)["points"] = points.size();
    (*facts)["samples"] = settings.samples;
    (*facts)["rays"] = rays.total();
    prober->add_facts(*facts);
  }
  return results;
}

std::vector<ProbePoint> read_probe_points(const std::string& path) {
  // A regular file of bounded size only.
  std::istringstream in(read_input_file(path, "the points file"));
  std::vector<ProbePoint> points;
  std::string line;
  int line_number = 0;
  bool first = true;
  while (std::getline(in, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::size_t start = line.find_first_not_of(" \t");
    if (start == std::string::npos || line[start] == '#') continue;
    const bool header = first && line.find_first_of("0123456789") == std::string::npos;
    first = false;
    if (header) continue;  // "x,y,z,nx,ny,nz"
    double values[6];
    std::size_t at = 0;
    for (int k = 0; k < 6; ++k) {
      const std::size_t comma = line.find(',', at);
      if (k < 5 && comma == std::string::npos)
        fail(path, line_number, int(line.size()) + 1,
             fmt::format("expected 6 values x,y,z,nx,ny,nz, found {}", k + 1));
      if (k == 5 && comma != std::string::npos)
        fail(path, line_number, int(comma) + 1, "more than 6 values (expected x,y,z,nx,ny,nz)");
      const std::string field = line.substr(at, k < 5 ? comma - at : std::string::npos);
      const int column = int(at) + 1;
      std::size_t used = 0;
      try {
        values[k] = std::stod(field, &used);
      } catch (const std::out_of_range&) {
        fail(path, line_number, column, "\"" + field + "\" is out of the range of a double");
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0 || field.find_first_not_of(" \t", used) != std::string::npos)
        fail(path, line_number, column, "\"" + field + "\" is not a number");
      if (!std::isfinite(values[k])) fail(path, line_number, column, "the value must be finite");
      at = comma + 1;
    }
    // Each value is finite: only (0, 0, 0) has no direction ((1e200, 1e200, 0) has one).
    const std::optional<Vec3> normal = direction_of({values[3], values[4], values[5]});
    if (!normal) fail(path, line_number, 1, "the normal (nx,ny,nz) must not be zero");
    points.push_back({{values[0], values[1], values[2]}, *normal});
  }
  if (points.empty()) fail(path, line_number, 0, "no points (expected lines x,y,z,nx,ny,nz)");
  return points;
}

std::vector<ProbePoint> grid_probe_points(const Vec3& corner, const Vec3& u, const Vec3& v, int nu, int nv) {
  const Vec3 normal = normalize(cross(u, v));
  std::vector<ProbePoint> points;
  points.reserve(std::size_t(nu) * nv);
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i)
      points.push_back({corner + u * ((i + 0.5) / nu) + v * ((j + 0.5) / nv), normal});
  return points;
}

}  // namespace candela
