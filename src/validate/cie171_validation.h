// `candela validate cie171` (docs/validation/cie171.md): the analytical test
// cases of CIE 171:2006 ("Test cases to assess the accuracy of lighting computer programs",
// section 5) that candela/1 can express, each built as a scene from its geometry, probed by every
// method that can answer it (integrators/probe.h: path, radiosity, meshless; the direct cases by
// local too) and compared point by point with a reference derived here from the geometry:
//
//   5.2   a point source of Lambertian intensity I(γ) = I0 cos γ (an IES LM-63 file) over a
//         black floor and a black wall: E = I(γ) cos θ / d²;
//   5.3   a square source of luminance L in the ceiling of a black room, points on the floor and a
//         wall: E = π L F, F Lambert's point-to-polygon factor;
//   5.4   a directional source (the sun, normal illuminance E_n) through a roof opening of a black
//         room: E = E_n sin α in the sunlit patch, 0 outside it;
//   5.5   the directional transmittance of clear glass: the sun through a horizontal pane of the
//         report's 6 mm clear glass at incidences 0–85° (quick: 0° and 60°), sensors beyond it
//         facing the sun and facing up: E = E_n τ(θ) cos(the sensor's angle to the sun);
//   5.6   a sunlit diffuse wall (reflectance ρ, uniform illuminance E_w), seen from sensors not
//         lit by the sun: E = ρ E_w F(sensor → the part of the wall above its horizon);
//   5.7   the same with a black internal obstruction between sensors and wall: F of the wall less
//         the obstruction's projection on it from each sensor (the case whose printed Table 19 is
//         wrong, CIE 171 errata: derived here, never copied);
//   5.8   an isotropic source of flux Φ at the centre of a cube of reflectance ρ (each ρ of the
//         table): the floor's mean indirect illuminance Φ ρ / (A (1 − ρ)), A the cube's area
//         (every reflected lumen lands on a surface; by symmetry each face gets a sixth);
//   5.9   the sky component under a roof opening, CIE overcast (type 1) and clear (type 12) skies;
//   5.10  the sky component under a facade opening, both skies: SC = ∫ L cos θ dω over the
//         opening / the unobstructed horizontal illuminance, both by quadrature of the CIE
//         standard general sky's luminance (shading/cie_sky.h);
//   5.11  5.10 with a black external obstruction outside the window: the quadrature leaves out
//         the directions that meet it;
//   5.12  5.9 and 5.13 5.10 with the opening glazed with the report's 6 mm clear glass (a thin
//         sheet, n = 1.52, transmissivity 0.95712: 0.87881 through at normal incidence): the
//         quadrature weighs each direction by the glass's transmittance τ(θ) (shading/fresnel.h)
//         — the daylight factor, the black room reflecting nothing. The report's fifth-degree
//         polynomial fit of τ (cie171_clear_glass_curve) gives a second reference, within 1 % of
//         the first (its fit is poorest at grazing incidence).
//
// What is expressed is Candela's reading of each case (dimensions, points, sources are chosen here
// and listed on the docs page); the report's own tables were not at hand, so no printed value is
// compared. Targets: 1 % at every point for path, 2 % for radiosity; meshless and
// local are held to 2 %. A point whose reference is 0 (outside the sun patch) is measured
// against the case's largest reference.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "integrators/probe.h"

namespace candela {

struct Cie171Case {
  std::string id;               // "5.8 rho 0.5"
  std::string title;            // "diffuse inter-reflections in a cube"
  std::string scene;            // candela/1 JSON
  std::string directory = ".";  // where the scene's files are (the Lambertian IES file of 5.2)
  std::vector<ProbePoint> points;
  std::vector<double> reference;  // lux at each point (the direct part alone when mean_indirect)
  std::vector<std::string> methods;
  // 5.8: the one compared value is the mean over the points of (computed − reference), against
  // mean_indirect_reference.
  bool mean_indirect = false;
  double mean_indirect_reference = 0;
  // The daylight cases: the unobstructed horizontal illuminance the sky component is over (0: an
  // illuminance case).
  double unobstructed_illuminance = 0;
  // 5.12, 5.13: the opening is glazed (a thin pane), and the reference with
  // the report's polynomial for the glass's transmittance instead of the exact one.
  bool glazed = false;
  // 5.11 reflected: the obstruction reflects the sky into the window (the path tracer's light
  // comes by a bounce outside: more samples too).
  bool reflecting_obstruction = false;
  std::vector<double> reference_report_curve;
};

// CIE 171's transmittance of 6 mm clear glass at incidence cos θ: the report's fifth-degree
// polynomial (Tregenza and Sharples, Daylighting Algorithms, 2.34), 0.87881 at normal incidence.
double cie171_clear_glass_curve(double cos_theta);

struct Cie171Run {
  bool quick = false;  // fewer points' samples and a coarser radiosity mesh (CI: under a minute)
  std::vector<std::string> only_methods;  // empty: every method of each case
  // Empty: every case; else the case numbers to run ("5.11": each of its variants).
  std::vector<std::string> only_cases;
  // Settings of every case's scene, as render's --set ("radiosity.solver=hierarchical": the
  // hierarchical solver passes every case too, as Gauss-Seidel, the cases' own, does).
  std::vector<std::string> overrides;
};

// Throws the InputError of an override the cases' scenes refuse (an unknown key, a value out of
// range), before any case is built or written.
void check_cie171_overrides(const Cie171Run& run);

// The cases, with the files they need (the Lambertian IES file) written into out_dir.
std::vector<Cie171Case> cie171_cases(const std::string& out_dir, const Cie171Run& run);

// The numbers of the cases built ("5.2", …, "5.13"), in order.
std::vector<std::string> cie171_case_numbers();

// The probe settings of a method for a case (samples per point: 65,536, under the sky openings
// 262,144; for the path tracer 1,048,576 behind 5.11's reflecting obstruction; quick 1,024).
ProbeSettings cie171_probe_settings(const Cie171Case& test, const std::string& method, const Cie171Run& run);

// The largest error a method may show at a point: 0.01 for path, 0.02 for the others.
double cie171_tolerance(const std::string& method);

// One method's answer for one case: the relative error at each point (or of the mean indirect).
struct Cie171Result {
  std::string case_id, method;
  std::vector<double> computed;  // lux at each point
  std::vector<double> errors;    // relative errors of the compared values
  std::vector<double> noise;     // their estimated standard errors (probe's), relative
  double largest_error = 0;      // the largest |error|
  bool passed = false;
  double seconds = 0;
};
Cie171Result run_cie171_case(const Cie171Case& test, const std::string& method, const Cie171Run& run);

// Everything into out_dir: cie171.csv (every point), summary.csv (a line per case and method:
// the largest error, the tolerance, pass), results.json, and a plot per case
// (cie171-<case>.png: reference and every method's lux against the point's number). Returns
// results.json's content; progress lines to log when given.
nlohmann::json run_cie171_validation(const std::string& out_dir, const Cie171Run& run, std::ostream* log);

}  // namespace candela
