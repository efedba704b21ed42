// The sphere-over-disc validation of seed 002 chapter 7 (SPEC §13): a Lambertian sphere of radius r
// whose centre is h above a Lambertian disc of radius R, lit by a distant light on the vertical axis,
// solved twice —
//
//   * the reference: the radiosity equations reduced by the axial symmetry to functions B(α) of the
//     sphere's latitude and D(u) of the distance from the disc's centre (002 eqs. 7.3–7.4), by the
//     thesis's quadrature (§7.2): m latitude rings α_i = (i − ½)π/m − π/2, n disc rings
//     u_j = (j − ½)R/n, k azimuths τ_s = (s − ½)2π/k, and the Jacobi iteration λ ← η + Rλ;
//   * the meshless finite-element method (integrators/meshless_method.h) on the same scene built
//     from JSON, one solve per basis and site spacing Δ, interpolated at the reference's points.
//
// Units: radiosity (exitance) B, as the meshless method uses (radiance is B/π). The exchange, derived
// afresh (the printed eqs. 7.1–7.11 have slips — SPEC §13):
//
//   B(α_i) = B*(α_i) + β Σ_j D̄(u_j) Σ_s F(p(α_i, 0), q(u_j, τ_s)) u_j σ_u σ_τ
//   D(u_j) = D*(u_j) + δ Σ_i B̄(α_i) Σ_s F(q(u_j, 0), p(α_i, τ_s)) r² cos α_i σ_α σ_τ
//
// with F = cos θ_p cos θ_q / (π d²), σ_u = R/n, σ_α = π/m, σ_τ = 2π/k; the sphere's area element is
// r² cos α dα dτ and the disc's u du dτ. No visibility term is needed: disc–disc and sphere–sphere
// exchange vanish (flat; convex: (p' − p)·n_p = r(n_p·n_p' − 1) ≤ 0), and a segment from a sphere
// point p leaving on the outside of its tangent plane never re-enters the ball, so whenever both
// cosines are positive the two points see each other (the thesis's remark after eq. 7.2).
//
// Direct light (002 eqs. 7.5–7.6), from a light of irradiance μ travelling straight down:
// B*(α) = β μ max(0, sin α), D*(u) = δ μ for r ≤ u ≤ R (the sphere's shadow is the disc u < r).
// D̄ and B̄ are what the rings send: the same but with the direct term averaged over each ring's cell
// (by area). For n = 100 and R/r = 8 the node u_13 = 5 lies exactly on the shadow edge; the thesis's
// pointwise D*(u_13) = δμ would make the whole cell [4.8, 5.2] lit and bias the sphere's indirect
// light; the cell average (51 % lit) does not. (ReferenceSettings::average_direct turns it off.)
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "meshless/meshless_basis.h"

namespace candela {

struct SphereDiscScene {
  double sphere_radius = 5;    // r
  double disc_radius = 40;     // R
  double height = 20;          // h: the sphere's centre above the disc
  double sphere_albedo = 0.9;  // β
  double disc_albedo = 0.9;    // δ
  double light = 0.9;          // μ: the irradiance of the light on a surface facing it
};

struct ReferenceSettings {
  int disc_rings = 100;        // n
  int sphere_rings = 100;      // m
  int azimuths = 100;          // k
  int iterations = 100;        // of λ ← η + Rλ (Jacobi, as the thesis's eq. 5.8)
  bool average_direct = true;  // the direct term the rings send: averaged over each cell (see above)
};

// The direct exitance at a point (eqs. 7.5–7.6).
double reference_disc_direct(const SphereDiscScene& scene, double u);
double reference_sphere_direct(const SphereDiscScene& scene, double alpha);

class ReferenceSolution {
 public:
  ReferenceSolution(const SphereDiscScene& scene, const ReferenceSettings& settings);

  const SphereDiscScene& scene() const { return scene_; }
  const ReferenceSettings& settings() const { return settings_; }
  // The nodes and the solution there: direct (pointwise, eqs. 7.5–7.6) and total = direct + indirect.
  std::vector<double> u, disc_direct, disc_total;          // n disc rings
  std::vector<double> alpha, sphere_direct, sphere_total;  // m sphere rings, α in radians
  double last_change = 0;  // the largest change of the last iteration, over the largest total

  // The total at any point (Nyström: the direct term plus the quadrature of what the converged
  // rings send); at a node, the same as the node's total.
  double disc_at(double u) const;
  double sphere_at(double alpha) const;
  // The form factor from a disc point at u to the whole sphere (the quadrature of F r² cos α dα dτ);
  // analytically r² h / (h² + u²)^{3/2}.
  double disc_to_sphere_factor(double u) const;

 private:
  double disc_indirect(double u) const;
  double sphere_indirect(double alpha) const;

  SphereDiscScene scene_;
  ReferenceSettings settings_;
  std::vector<double> disc_sent_, sphere_sent_;  // D̄_j, B̄_i
};

struct FeSettings {
  BasisKind basis = BasisKind::normalized;
  double spacing = 3;              // Δ
  std::string transport = "flat";  // or "hierarchical" (meshless.transport)
  int grid = 256;                  // camera rays per side (an orthographic camera over the disc, from above)
  int rounds = 8;                  // rounds of secondary rays
  int azimuths = 100;              // points per ring for the azimuth mean
};

// The scene as candela/1 JSON (y up: disc in y = 0, sphere centre at y = h, light along −y).
std::string sphere_disc_scene_json(const SphereDiscScene& scene, const FeSettings& settings);

struct FeCurves {
  // At the reference's nodes: the mean over `azimuths` points of each ring, and the value at
  // azimuth 0 (the meridian in the scene's x–y half-plane x > 0).
  std::vector<double> disc_mean, disc_meridian, disc_direct_mean;
  std::vector<double> sphere_mean, sphere_meridian, sphere_direct_mean;
  std::size_t sites = 0, disc_sites = 0, sphere_sites = 0;
  std::size_t uncovered = 0;  // sample points no element reaches (counted as 0)
  bool converged = false;
  double seconds = 0;
  double precompute_seconds = 0;  // sites, effective areas, hierarchy and S (what relighting reuses)
  std::size_t entries = 0;        // S's
};

FeCurves solve_fe(const SphereDiscScene& scene, const FeSettings& settings, const std::vector<double>& u,
                  const std::vector<double>& alpha);

// Errors of a curve pair (FE − reference) over the disc nodes and the sphere nodes together, each
// node counting once: RMS and largest absolute value, and both over the reference's largest total.
struct CurveErrors {
  double rms = 0, max = 0, rms_relative = 0, max_relative = 0;
};
CurveErrors curve_errors(const std::vector<double>& disc_fe, const std::vector<double>& disc_reference,
                         const std::vector<double>& sphere_fe, const std::vector<double>& sphere_reference);

// The whole validation (`candela validate sphere-disc`): the reference, the refined reference
// (n = m = k = 4× — its values at the reference's nodes show that the reference has converged),
// and the FE solutions for the three bases at Δ = 3 and Δ = 1, written to directory:
// reference_disc.csv, reference_sphere.csv, fe_<basis>_delta<Δ>_disc.csv / _sphere.csv,
// errors.json and PNG plots; and the normalized basis's flat and hierarchical transport at
// several spacings, each with its precomputation seconds and RMS error (transport.csv, errors.json's
// "transport": the hierarchical one's error at equal precomputation time). quick (for tests): a disc of
// radius 15, n = m = k = 30, a 64² camera grid. Every file is written atomically; progress lines go to log
// when not null. Returns errors.json's content.
struct SphereDiscRun {
  bool quick = false;
  bool refine = true;  // also solve the refined reference
};
nlohmann::json run_sphere_disc_validation(const std::string& directory, const SphereDiscRun& run,
                                          std::ostream* log = nullptr);

}  // namespace candela
