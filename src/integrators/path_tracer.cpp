#include "integrators/path_tracer.h"

#include <fmt/format.h>
#include <tbb/blocked_range2d.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>

#include "camera/antialiasing.h"
#include "camera/pixel_filter.h"
#include "camera/splat_film.h"
#include "distributed/cluster.h"
#include "distributed/task_farm.h"
#include "integrators/distributed_tiles.h"
#include "integrators/memory_estimate.h"
#include "integrators/probe.h"
#include "math/constants.h"
#include "sampling/independent_sampler.h"
#include "sampling/multiple_importance.h"
#include "sampling/sobol_sampler.h"
#include "shading/bsdf.h"
#include "shading/bump.h"
#include "shading/fresnel.h"
#include "shading/material_bsdf.h"
#include "shading/optics.h"
#include "util/cancellation.h"
#include "util/error.h"
#include "util/hash.h"
#include "util/progress.h"

namespace candela {

PathSettings read_path_settings(const JsonNode& node) {
  PathSettings settings;
  node.expect_object();
  settings.spp = node.integer("spp", settings.spp, {0, 1 << 24, false, false});
  settings.time = node.number("time", settings.time, Range::non_negative());
  if (settings.spp == 0 && !(settings.time > 0))
    node.at("spp").fail("spp 0 (no limit) needs a time limit: path.time > 0");
  settings.max_depth = node.integer("max_depth", settings.max_depth, {0, 1024, false, false});
  settings.roulette_depth = node.integer("roulette_depth", settings.roulette_depth, {0, 1024, false, false});
  settings.checkpoint_interval =
      node.number("checkpoint_interval", settings.checkpoint_interval, {0, 1e9, true, false});
  if (const auto sampler = node.get("sampler")) {
    settings.sampler = sampler->as_string();
    const SamplerEntry* entry = find_sampler(settings.sampler);
    if (!entry)
      sampler->fail("unknown sampler \"" + settings.sampler + "\" (expected one of: " + sampler_names() +
                    ")");
    if (entry->needs_sample_count && settings.spp == 0)
      sampler->fail(
          "the \"" + settings.sampler +
          "\" sampler needs path.spp (its strata are the passes of a pixel), not spp 0 with a time");
  }
  node.finish();
  return settings;
}

namespace {

// Paths end here even when Russian roulette keeps them going (a closed mirror box).
constexpr int kDepthCap = 1024;

bool is_finite(const Color& c) {
  return std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b);
}

// A secondary ray starts off the surface on the side it leaves by (SPEC §8's offset): the side of
// `side`, its direction for a refraction and wo for a reflection (which on a smooth mesh may dip
// under the facet, from Hanika's lifted point: SurfaceHit::lifted_toward).
Vec3 offset_origin(const Scene& scene, const Vec3& position, const Vec3& geometric_normal, const Vec3& side) {
  const Vec3 outward = dot(side, geometric_normal) >= 0 ? geometric_normal : -geometric_normal;
  return position + outward * scene.ray_offset(position);
}

// The fraction of light that crosses a shadow ray (Scene::transmittance: in a scene with thin
// sheets the product of what each on the way lets through, what the BSDF's passthrough samples carry
// on average, so that next-event estimation and the path continued through a sheet estimate the
// same light).
Color shadow_transmittance(const Scene& scene, const Ray& ray, RayCounts& rays) {
  ++rays.shadow;
  return scene.transmittance(ray);
}

// What crosses from the point (leaving along L on side's side) to distance further (infinity: the
// environment). The segment stops short of its end by the offset there, so an emissive quad drawn
// where an area light is does not shadow it.
Color transmittance_toward(const Scene& scene, const Vec3& position, const Vec3& geometric_normal,
                           const Vec3& side, const Vec3& L, double distance, RayCounts& rays) {
  Ray shadow{offset_origin(scene, position, geometric_normal, side), L};
  if (std::isfinite(distance)) {
    shadow.t_max = distance - 2 * scene.ray_offset(position + L * distance);
    if (!(shadow.t_max > 0)) {
      ++rays.shadow;
      return Color(1);
    }
  }
  return shadow_transmittance(scene, shadow, rays);
}

// What crosses from the point to a point sampled on a surface: both ends are lifted off their
// surfaces (the far one toward the near side), so that a segment reaching a sphere's silhouette at
// a grazing angle does not clip the sphere just before its end.
Color transmittance_to_surface(const Scene& scene, const Vec3& position, const Vec3& geometric_normal,
                               const Vec3& side, const Vec3& target, const Vec3& target_normal,
                               RayCounts& rays) {
  const Vec3 toward = dot(target_normal, position - target) >= 0 ? target_normal : -target_normal;
  const Vec3 end = target + toward * scene.ray_offset(target);
  const Vec3 origin = offset_origin(scene, position, geometric_normal, side);
  const Vec3 segment = end - origin;
  const double distance = length(segment);
  if (!(distance > 0)) {
    ++rays.shadow;
    return Color(1);
  }
  return shadow_transmittance(scene, Ray{origin, segment / distance, 0, distance}, rays);
}

// One next-event estimate at a surface point: an emitter chosen by its power, a point or direction
// of it drawn by the emitter's own sampling (Light::illuminate_random), weighted against BSDF
// sampling (MIS) where a BSDF-sampled ray could have found it too (LightSample::pdf > 0). The
// shadow ray leaves from `from` (the hit, or a smooth mesh's lifted point) on wo's side: every
// non-delta lobe reflects.
template <class SamplerType>
Color sample_light(const Scene& scene, const LightSampler& lights, const Vec3& position, const Vec3& from,
                   const Vec3& geometric_normal, const Vec3& shading_normal, const Bsdf& bsdf, const Vec3& wo,
                   SamplerType& sampler, RayCounts& rays) {
  if (lights.empty()) return {};
  // A value is drawn only where there is a choice (the samplers' dimensions go to what varies).
  const LightSampler::Choice choice = lights.choose(lights.single() ? 0.0 : sampler.get_1d());
  const Vec2 u = sampler.get_2d();
  LightSample sample;
  if (!scene.emitter(choice.emitter).illuminate_random(position, u, sample)) return {};
  const Vec3& L = sample.direction;
  const Color f = bsdf.evaluate(wo, L);
  if (f.is_black()) return {};
  const bool on_surface = sample.normal != Vec3{};
  const Color transmittance =
      on_surface ? transmittance_to_surface(scene, from, geometric_normal, wo, position + L * sample.distance,
                                            sample.normal, rays)
                 : transmittance_toward(scene, from, geometric_normal, wo, L, sample.distance, rays);
  if (transmittance.is_black()) return {};
  // A point-like light (pdf 0): no BSDF-sampled ray can hit it, so no MIS.
  const double weight =
      sample.pdf > 0 ? power_heuristic(choice.probability * sample.pdf, bsdf.pdf(wo, L)) : 1.0;
  // The intensity is (light/π) / pdf already: π · f · intensity · cos θ / P(choice).
  return f * sample.intensity * transmittance *
         (kPi * std::fabs(dot(shading_normal, L)) * weight / choice.probability);
}

// One pass's sample of a pixel: where in the pixel (dx, dy ∈ [0, 1)) and what the path brought.
struct PassSample {
  Color value;
  double dx = 0.5, dy = 0.5;
};

// Where a path stands between bounces.
struct PathState {
  Ray ray;
  Color beta{1};
  bool specular = true;  // the last bounce was a delta (or this is the camera ray): no MIS on hits
  double bsdf_pdf = 0;   // the density the last bounce sampled ray.direction with
  Vec3 previous;         // where the last bounce happened
  double eta_scale = 1;  // Russian roulette looks at beta without the 1/η² of refractions
  int depth = 0;
  int sheets_crossed = 0;  // thin sheets the path went straight through (no vertex, no depth)
};

// Follows a path from its current ray to its end, adding what it gathers. A template on the
// sampler's type, made for each final sampler class whose values are inline (and for Sampler,
// through virtual calls, for the others): on the Cornell box with Sobol' the virtual calls,
// each returning its pair by memory, cost 3 % of the render.
template <class SamplerType>
Color continue_path(const Scene& scene, const PathSettings& settings, const LightSampler& lights,
                    PathState state, SamplerType& sampler, RayCounts& rays) {
  Color L;
  const int max_depth = settings.max_depth > 0 ? settings.max_depth : kDepthCap;
  for (;; ++state.depth) {
    Intersection hit;
    if (!scene.intersect(state.ray, hit)) {
      // The background colours what the camera sees (directly, or in mirrors and
      // through glass) and lights nothing; an environment lights the scene too.
      if (!scene.environment && !state.specular) break;
      const Color background = scene.background_along(state.ray.direction);
      if (!background.is_black()) {
        double weight = 1;
        if (!state.specular && lights.has_environment())
          weight = power_heuristic(state.bsdf_pdf, lights.environment_pdf(state.ray.direction));
        L += state.beta * background * weight;
      }
      break;
    }
    const SurfaceHit& surface = hit.surface;
    const Material& material = scene.material_of(hit);
    // Emission leaves both sides of a surface, as in the local model and the meshless method.
    if (!material.emission.is_black()) {
      double weight = 1;
      if (!state.specular) {
        const double light_pdf = lights.surface_pdf(hit.primitive, state.previous, surface);
        if (light_pdf > 0) weight = power_heuristic(state.bsdf_pdf, light_pdf);
      }
      L += state.beta * material.emission * weight;
    }
    // A thin sheet is crossed at any depth: the vertex before it estimated what lies beyond it.
    const bool sheet = material.thin && material.has_refraction();
    const bool last = state.depth >= max_depth;
    if (last && !sheet) break;

    SurfaceHit shading = surface;
    // 000 §4.2.1: the bump tilts the shading normal only.
    shading.shading_normal = bumped_normal(material.bump, surface);
    const SurfaceProperties at = material.at(shading);
    const Bsdf bsdf = make_bsdf(material, at, shading, shading.shading_normal);
    const Vec3 wo = -state.ray.direction;
    if (!last && bsdf.has_non_delta())
      L += state.beta * sample_light(scene, lights, surface.position, surface.lifted_toward(wo),
                                     surface.geometric_normal, shading.shading_normal, bsdf, wo, sampler,
                                     rays);

    // Straight on through a sheet, as the shadow rays go (Scene::transmittance): the bounce before
    // it stays the one MIS and the emitters' densities are measured from, and the depth is not
    // spent (the loop's ++ gives it back).
    const auto pass_through = [&](const Color& weight) {
      state.beta *= weight;
      ++rays.refracted;
      state.ray = Ray{offset_origin(scene, surface.position, surface.geometric_normal, -wo), -wo};
      --state.depth;
    };
    // A pane and nothing else (one thin_dielectric lobe): the path is split rather than sent one
    // way by a coin — the reflection followed as a path of its own, weighted R, and this path on
    // straight through, weighted T. The coin's extra random number broke the stratification of the
    // bounce before the pane (Sobol'): under CIE 171 5.13's clear sky a point 0.25 m from the
    // window, which sees it at 76–86°, was 1.4 % off at 4,194,304 coin-tossing paths. Only before
    // Russian roulette begins (the early bounces, where stratification counts): the branches stay
    // few, and deeper panes toss the coin (below).
    if (bsdf.lobe_count() == 1 && bsdf.lobe(0).type == LobeType::thin_dielectric &&
        state.depth < settings.roulette_depth) {
      if (++state.sheets_crossed > kMaxSheetsCrossed) break;
      const SheetColors split =
          thin_sheet(std::fabs(dot(bsdf.frame().n, wo)), bsdf.lobe(0).ior, bsdf.lobe(0).weight);
      if (!last && !split.reflectance.is_black()) {
        PathState reflected = state;
        const Vec3 mirrored = reflect(wo, bsdf.frame().n);
        if (dot(mirrored, surface.geometric_normal) * dot(wo, surface.geometric_normal) > 0) {
          reflected.beta *= split.reflectance;
          reflected.specular = true;
          reflected.bsdf_pdf = 0;
          reflected.previous = surface.position;
          reflected.ray =
              Ray{offset_origin(scene, surface.lifted_toward(wo), surface.geometric_normal, wo), mirrored};
          ++reflected.depth;
          ++rays.reflected;
          L += continue_path(scene, settings, lights, reflected, sampler, rays);
        }
      }
      if (split.transmittance.is_black()) break;
      pass_through(split.transmittance);
      continue;
    }

    BsdfSample sample;
    const double u_lobe = bsdf.lobe_count() > 1 ? sampler.get_1d() : 0.0;
    const Vec2 u = sampler.get_2d();
    if (!bsdf.sample(wo, u_lobe, u, sample) || sample.weight.is_black() || !is_finite(sample.weight)) break;
    if (sample.passthrough) {  // wi = −wo
      if (++state.sheets_crossed > kMaxSheetsCrossed) break;
      pass_through(sample.weight);
      continue;
    }
    if (last) break;
    state.beta *= sample.weight;
    state.specular = sample.delta;
    state.bsdf_pdf = sample.pdf;
    state.previous = surface.position;
    if (sample.transmission) {
      state.eta_scale *= sample.eta * sample.eta;
      ++rays.refracted;
    } else {
      ++rays.reflected;
    }
    const Vec3 leaving_side = sample.transmission ? sample.wi : wo;
    state.ray =
        Ray{offset_origin(scene, surface.lifted_toward(leaving_side), surface.geometric_normal, leaving_side),
            sample.wi};
    // Russian roulette: survive with q ≤ 0.95 proportional to the throughput, which is divided by q.
    if (state.depth + 1 >= settings.roulette_depth) {
      const double q = std::min(0.95, state.beta.max_component() * state.eta_scale);
      if (!(sampler.get_1d() < q)) break;
      state.beta = state.beta / q;
    }
  }
  return L;
}

}  // namespace

namespace {

// The state every stream of pass `pass` starts from; the stream picks the pixel or point.
uint64_t pass_state(uint64_t seed, uint64_t pass) {
  return mix64(seed * 0x9e3779b97f4a7c15ULL + pass);
}

}  // namespace

Pcg32 path_pixel_rng(uint64_t seed, uint64_t pass, uint32_t x, uint32_t y) {
  return independent_stream(seed, pass, x, y);
}

Pcg32 path_point_rng(uint64_t seed, uint64_t pass, double x, double y) {
  return Pcg32(pass_state(seed, pass), mix64(std::bit_cast<uint64_t>(x) ^ mix64(std::bit_cast<uint64_t>(y))));
}

Color path_radiance(const Scene& scene, const PathSettings& settings, const LightSampler& lights,
                    const Ray& ray, Sampler& sampler, RayCounts& rays) {
  PathState state;
  state.ray = ray;
  if (auto* sobol = dynamic_cast<SobolSampler*>(&sampler))
    return continue_path(scene, settings, lights, state, *sobol, rays);
  if (auto* independent = dynamic_cast<IndependentSampler*>(&sampler))
    return continue_path(scene, settings, lights, state, *independent, rays);
  return continue_path(scene, settings, lights, state, sampler, rays);
}

Color path_radiance(const Scene& scene, const PathSettings& settings, const LightSampler& lights,
                    const Ray& ray, Pcg32& rng, RayCounts& rays) {
  IndependentSampler sampler(rng);
  const Color L = path_radiance(scene, settings, lights, ray, sampler, rays);
  rng = sampler.stream();
  return L;
}

Color path_irradiance(const Scene& scene, const PathSettings& settings, const LightSampler& lights,
                      const Vec3& point, const Vec3& normal, Sampler& sampler, RayCounts& rays) {
  Bsdf bsdf(ShadingFrame::from_normal(normal), normal);
  BsdfLobe white;
  white.type = LobeType::lambert;
  white.weight = Color(1);
  bsdf.add(white);
  // The virtual surface faces the hemisphere of the normal: wo along it.
  Color E = sample_light(scene, lights, point, point, normal, normal, bsdf, normal, sampler, rays);
  BsdfSample sample;
  const double u_lobe = 0;  // one lobe
  const Vec2 u = sampler.get_2d();
  if (!bsdf.sample(normal, u_lobe, u, sample) || sample.weight.is_black()) return E;
  PathState state;
  state.ray = Ray{offset_origin(scene, point, normal, sample.wi), sample.wi};
  state.beta = sample.weight;
  state.specular = false;
  state.bsdf_pdf = sample.pdf;
  state.previous = point;
  state.depth = 1;
  ++rays.reflected;
  E += continue_path(scene, settings, lights, state, sampler, rays);
  return E;
}

Color path_irradiance(const Scene& scene, const PathSettings& settings, const LightSampler& lights,
                      const Vec3& point, const Vec3& normal, Pcg32& rng, RayCounts& rays) {
  IndependentSampler sampler(rng);
  const Color E =
      path_irradiance(scene, settings, lights, point, normal, static_cast<Sampler&>(sampler), rays);
  rng = sampler.stream();
  return E;
}

namespace {

// One render's passes of the path tracer: a sample of every pixel per pass, its point by aa.mode,
// splatted with aa.filter into the pixels within its reach (pbrt-v4's film).
class PathPasses final : public PixelPasses {
 public:
  PathPasses(const Scene& scene, const PathSettings& settings, const RenderRequest& request)
      : scene_(scene),
        settings_(settings),
        region_(request.region),
        seed_(request.seed_for(scene)),
        aa_(request.antialiasing_for(scene)),
        lights_(scene),
        tile_(std::max(1, scene.render.tile_size)),
        cells_(aa_.mode == AntialiasingMode::none ? 1 : aa_.n),
        lattice_passes_(aa_.mode == AntialiasingMode::corners || aa_.mode == AntialiasingMode::adaptive),
        prototype_(
            create_sampler(settings.sampler, SamplerParameters{seed_, uint64_t(std::max(settings.spp, 0))})),
        samplers_([this] { return prototype_->clone(); }),
        filter_(create_pixel_filter(aa_.filter, aa_.filter_parameters)),
        reach_(filter_reach(*filter_)),
        image_{-region_.x0, -region_.y0, scene.camera->width() - region_.x0,
               scene.camera->height() - region_.y0} {}

  bool run_pass(uint64_t pass, const PixelBox& pixels, Color* sums, double* weights,
                uint64_t& dropped) override;

  RayCounts rays() const override {
    RayCounts total;
    for (const RayCounts& c : counts_) total += c;
    return total;
  }

  void add_facts(nlohmann::json& facts) const override {
    facts["max_depth"] = settings_.max_depth;
    facts["roulette_depth"] = settings_.roulette_depth;
    facts["sampler"] = settings_.sampler;
    facts["emissive_primitives"] = lights_.emissive_primitive_count();
    facts["scene_lights"] = scene_.lights.size();
    facts["environment"] = lights_.has_environment();
    if (lights_.empty())
      facts["warning"] =
          "nothing emits light (no lights, emissive surfaces or environment; the background lights "
          "nothing): the image shows the background alone";
  }

 private:
  PassSample sample_pixel(uint64_t pass, int i, int j, RayCounts& rays, uint64_t& dropped);
  bool run_lattice_pass(uint64_t pass, const PixelBox& pixels, Color* sums, double* weights,
                        uint64_t& dropped);

  const Scene& scene_;
  const PathSettings& settings_;
  const PixelRect region_;
  const uint64_t seed_;
  const AntialiasingSettings& aa_;
  const LightSampler lights_;
  const int tile_;
  // aa.mode "jittered" and "uniform": the n × n cells a pixel's passes take in turn.
  const int cells_;
  // aa.mode "corners" and "adaptive": each pass is the camera sampler's own lattice image.
  const bool lattice_passes_;
  // path.sampler draws each pixel's samples: one sampler per thread, restarted for every pixel and
  // pass (its values depend on neither the thread nor the tile).
  const std::unique_ptr<Sampler> prototype_;
  tbb::enumerable_thread_specific<std::unique_ptr<Sampler>> samplers_;
  tbb::enumerable_thread_specific<RayCounts> counts_;
  const std::unique_ptr<PixelFilter> filter_;
  const int reach_;
  const PixelBox image_;  // the camera's image, in region coordinates
};

// A pass's sample of one pixel (i, j of the region; outside it too, for the filter's ring): a point
// of its square and the path's radiance there (a non-finite one — an exploded weight — dropped as
// zero, never allowed to poison the pixels). The point, by aa.mode: "none" uniform in the square;
// "jittered" n × n the passes take the n² cells in turn (pass k the cell k mod n²), a random point
// in each — stratified across passes; "uniform" the cells' centres in turn.
PassSample PathPasses::sample_pixel(uint64_t pass, int i, int j, RayCounts& rays, uint64_t& dropped) {
  const auto x = static_cast<uint32_t>(region_.x0 + i), y = static_cast<uint32_t>(region_.y0 + j);
  Sampler& sampler = *samplers_.local();
  sampler.start_pixel_sample(x, y, pass);
  PassSample sample;
  const Vec2 point = sampler.get_2d();
  sample.dx = point.x;
  sample.dy = point.y;
  if (cells_ > 1) {
    const auto cell = static_cast<int>(pass % uint64_t(cells_ * cells_));
    const bool centred = aa_.mode == AntialiasingMode::uniform;
    sample.dx = (cell % cells_ + (centred ? 0.5 : sample.dx)) / cells_;
    sample.dy = (cell / cells_ + (centred ? 0.5 : sample.dy)) / cells_;
  }
  ++rays.primary;
  sample.value = path_radiance(scene_, settings_, lights_,
                               scene_.camera->generate_ray(x + sample.dx, y + sample.dy), sampler, rays);
  if (!is_finite(sample.value)) {
    sample.value = Color();
    ++dropped;
  }
  return sample;
}

// aa.mode "corners" and "adaptive": each pass is the camera sampler's own lattice image
// (camera/antialiasing.h: corner rays shared with the neighbours, squares split where the contrast
// of their corners exceeds aa.threshold, leaves splatted with aa.filter), its lattice jittered
// afresh each pass when aa.jitter is set; a lattice point's path takes its random stream from the
// point and the pass, so a tile and the whole image trace the same paths. The pixel is the mean of
// its passes' images.
bool PathPasses::run_lattice_pass(uint64_t pass, const PixelBox& pixels, Color* sums, double* weights,
                                  uint64_t& dropped) {
  const SamplingRegion at{region_.x0 + pixels.x0, region_.y0 + pixels.y0, scene_.camera->width(),
                          scene_.camera->height()};
  // The pixels' own samples count as dropped: those of the ring are some other tile's own.
  const double x0 = at.x0, y0 = at.y0, x1 = at.x0 + pixels.width(), y1 = at.y0 + pixels.height();
  std::atomic<uint64_t> dropped_now{0};
  const RadianceFunction radiance = [&](double x, double y) {
    Pcg32 rng = path_point_rng(seed_, pass, x, y);
    RayCounts& rays = counts_.local();
    ++rays.primary;
    Color value = path_radiance(scene_, settings_, lights_, scene_.camera->generate_ray(x, y), rng, rays);
    if (!is_finite(value)) {
      value = Color();
      if (x >= x0 && x < x1 && y >= y0 && y < y1) ++dropped_now;
    }
    return value;
  };
  Film image(pixels.width(), pixels.height());
  sample_image(aa_, mix64(seed_ ^ mix64(pass + 0x5851f42d4c957f2dULL)), at, tile_, radiance, image);
  if (cancel_requested()) return false;  // tiles of the pass may have been skipped
  for (int j = 0; j < pixels.height(); ++j)
    for (int i = 0; i < pixels.width(); ++i) {
      const std::size_t q = std::size_t(j) * pixels.width() + i;
      sums[q] += image.at(i, j);
      weights[q] += 1;
    }
  dropped += dropped_now.load();
  return true;
}

// Every sample is splatted with the scene's aa.filter into the pixels within its reach (pbrt-v4's
// film), gathered here per pixel in a fixed order, so the image depends neither on the threads nor
// on the tiles. The pixels take their passes from the samples of the box grown by the reach
// (clipped to the image): all of them are taken before any is added.
bool PathPasses::run_pass(uint64_t pass, const PixelBox& pixels, Color* sums, double* weights,
                          uint64_t& dropped) {
  if (lattice_passes_) return run_lattice_pass(pass, pixels, sums, weights, dropped);
  const PixelBox box = pixels.grown(reach_).clipped(image_);
  std::vector<PassSample> samples(std::size_t(box.width()) * box.height());
  std::atomic<bool> cut_short{false};
  std::atomic<uint64_t> dropped_now{0};
  tbb::parallel_for(tbb::blocked_range2d<int>(box.y0, box.y1, tile_, box.x0, box.x1, tile_),
                    [&](const tbb::blocked_range2d<int>& block) {
                      if (cancel_requested()) {
                        cut_short.store(true, std::memory_order_relaxed);
                        return;
                      }
                      RayCounts& rays = counts_.local();
                      // Only the pixels' own samples count as dropped (a ring sample is some other
                      // tile's own).
                      uint64_t dropped_block = 0, ring = 0;
                      for (int j = block.rows().begin(); j < block.rows().end(); ++j)
                        for (int i = block.cols().begin(); i < block.cols().end(); ++i)
                          samples[std::size_t(j - box.y0) * box.width() + (i - box.x0)] =
                              sample_pixel(pass, i, j, rays, pixels.contains(i, j) ? dropped_block : ring);
                      dropped_now += dropped_block;
                    });
  if (cut_short.load()) return false;
  tbb::parallel_for(
      tbb::blocked_range2d<int>(pixels.y0, pixels.y1, tile_, pixels.x0, pixels.x1, tile_),
      [&](const tbb::blocked_range2d<int>& block) {
        for (int qy = block.rows().begin(); qy < block.rows().end(); ++qy)
          for (int qx = block.cols().begin(); qx < block.cols().end(); ++qx) {
            const std::size_t q = std::size_t(qy - pixels.y0) * pixels.width() + (qx - pixels.x0);
            for (int py = std::max(qy - reach_, box.y0); py < std::min(qy + reach_ + 1, box.y1); ++py)
              for (int px = std::max(qx - reach_, box.x0); px < std::min(qx + reach_ + 1, box.x1); ++px) {
                const PassSample& sample = samples[std::size_t(py - box.y0) * box.width() + (px - box.x0)];
                const double w = filter_->evaluate(sample.dx - 0.5 + (px - qx), sample.dy - 0.5 + (py - qy));
                if (w == 0) continue;
                sums[q] += sample.value * w;
                weights[q] += w;
              }
          }
      });
  dropped += dropped_now.load();
  return true;
}

}  // namespace

std::string PathMethod::pass_fingerprint() const {
  return fmt::format("max_depth={} roulette_depth={} sampler={}{}", settings_.max_depth,
                     settings_.roulette_depth, settings_.sampler,
                     find_sampler(settings_.sampler)->needs_sample_count ? fmt::format("/{}", settings_.spp)
                                                                         : std::string());
}

RunLimits PathMethod::limits() const {
  return {uint64_t(settings_.spp), "path.spp", settings_.time, settings_.checkpoint_interval};
}

std::unique_ptr<PointProbe> PathMethod::point_probe(const Scene& scene, const ProbeSettings& settings) const {
  return make_path_probe(scene, settings_, settings);
}

std::unique_ptr<PixelPasses> PathMethod::start_passes(const Scene& scene,
                                                      const RenderRequest& request) const {
  return std::make_unique<PathPasses>(scene, settings_, request);
}

}  // namespace candela
