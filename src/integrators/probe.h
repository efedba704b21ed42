// `candela probe` (SPEC "Product surface"): irradiance and radiance at given points
// and normals, by the path tracer, classic radiosity, the meshless method or the local model —
// Radiance's rtrace -I for lighting designers' sensor points and work planes.
//
// At a sensor point x facing n:
//   irradiance E = ∫ L(x, ω) cos θ dω over n's hemisphere (W/m² in the scene's units), found
//     path       as the light a white Lambert surface at x would reflect (next-event estimation
//                and BSDF sampling with MIS, whole paths), averaged over `samples` estimates;
//     radiosity, meshless   ∫ (B/π) cos θ dω with B the solution's exitance at each ray's hit (the
//                background's value where it leaves), by `samples` stratified cosine-distributed
//                rays and as many points on the emissive surfaces, combined by MIS; plus, for the
//                meshless method, the direct light of the scene's point/spot/directional/area
//                lights at x with shadows (rays never hit them);
//     local      the direct light alone: every emitter's samples (lights, the jittered samples
//                of the emissive surfaces, the environment) with opaque shadows, as the local
//                model lights a white diffuse point (scene/direct_irradiance.h); deterministic;
//   radiance L = the radiance arriving at x from direction n (looking along n, what a luminance
//     meter at x aimed along n reads): B/π at the hit of the ray from x along n.
// The sensor is not part of the scene: it shadows nothing, and rays leave x offset along n.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "integrators/method_registry.h"
#include "integrators/solution_field.h"
#include "scene/scene.h"
#include "shading/photometric_units.h"
#include "util/statistics.h"

namespace candela {

struct PathSettings;

struct ProbePoint {
  Vec3 position;
  Vec3 normal;  // unit
};

// What a lighting designer reads off a work plane (EN 12464-1, CIE 171's tables, DIALux's and
// Relux's results): the minimum, maximum and average illuminance over its points and the
// uniformities U0 = Emin/Eavg and Ud = Emin/Emax (0 where the average or the maximum is 0).
struct IlluminanceStatistics {
  std::size_t points = 0;
  double minimum = 0, maximum = 0, average = 0;
  double uniformity_min_average = 0, uniformity_min_max = 0;
};
// Throws std::invalid_argument for no values or a non-finite one.
IlluminanceStatistics illuminance_statistics(const std::vector<double>& illuminance);

// The irradiance (W/m²) an unobstructed horizontal surface facing up (+y) receives from the
// scene's environment — a daylight factor's denominator (interior illuminance /
// unobstructed horizontal sky illuminance) — by 512 × 512 stratified cosine-distributed
// directions; black without an environment.
Color unobstructed_sky_irradiance(const Scene& scene);

struct ProbeResult {
  Color irradiance;  // W/m²
  Color radiance;    // W/(m²·sr)
  // The estimated standard error (1σ) of the irradiance's luminance, W/m²: the spread of the
  // samples' luminances over √samples (256 samples give 2–4 % noise; this says how many
  // to ask for). The radiosity and meshless solutions' own errors are not in it, only their
  // gathering's.
  double irradiance_error = 0;
};

struct ProbeSettings {
  std::string method = std::string(kReferenceMethod);  // one whose capabilities say probe
  int samples = 256;  // estimates per point (path) or hemisphere rays (the others)
  uint64_t seed = 0;
  bool quiet = true;
};

// What a method offers `candela probe` (Method::point_probe): the irradiance and radiance at
// sensor points by its own model. Thread-safe.
class PointProbe {
 public:
  virtual ~PointProbe() = default;
  // Point `index` of those probed (its random streams are the index's).
  virtual ProbeResult probe(const ProbePoint& point, std::size_t index, RayCounts& rays) const = 0;
  // What the probe measured besides the rays (the field's rays that found no solution).
  virtual void add_facts(nlohmann::json& facts) const { (void)facts; }
};

// The answers above, for the methods to offer: the path tracer's whole paths with its settings;
// the local model's direct light; a view-independent solution gathered over the hemisphere.
std::unique_ptr<PointProbe> make_path_probe(const Scene& scene, const PathSettings& path,
                                            const ProbeSettings& settings);
std::unique_ptr<PointProbe> make_local_probe(const Scene& scene, const ProbeSettings& settings);
std::unique_ptr<PointProbe> make_field_probe(const Scene& scene, std::unique_ptr<SolutionField> field,
                                             const ProbeSettings& settings);

// The methods probe() answers for.
// "local, radiosity, meshless, path": the methods whose capabilities say probe.
std::string probe_method_names();

// By the point probe the method offers (Method::point_probe), made from its settings object of the
// scene; throws std::invalid_argument for a method that offers none. Fills facts (when not null) with what
// the solution measured and how many rays found no solution (off the radiosity mesh, no site near).
std::vector<ProbeResult> probe(const Scene& scene, const std::vector<ProbePoint>& points,
                               const ProbeSettings& settings, nlohmann::json* facts = nullptr);

// Points from a CSV file: one "x,y,z,nx,ny,nz" per line; blank lines and lines starting with '#'
// are skipped, as is a first line naming the columns. Throws InputError (file, line, column) for
// anything else: a missing or extra value, a number that does not parse or is not finite, a zero
// normal. Normals are normalised.
std::vector<ProbePoint> read_probe_points(const std::string& path);

// A work plane: nu × nv points at the centres of the cells of the parallelogram corner + s·u + t·v
// (s, t ∈ [0, 1]), row by row (t outer), all facing normalize(u × v).
std::vector<ProbePoint> grid_probe_points(const Vec3& corner, const Vec3& u, const Vec3& v, int nu, int nv);

// Illuminance in lux from irradiance in W/m²: efficacy × luminance, the one conversion of
// shading/photometric_units.h (Radiance's 179 lm/W), which photometric lights use too.
inline constexpr double kDefaultLuminousEfficacy = kLuminousEfficacy;

}  // namespace candela
