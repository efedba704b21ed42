// The form-factor and furnace validation (SPEC §13; docs/validation/form-factors.md):
//
//   * Howell's closed forms (radiosity/configuration_factors.h) through the radiosity method's own
//     mesh and form-factor rows — parallel rectangles (C-11), perpendicular rectangles with a
//     common edge (C-14), coaxial discs (C-41), a point to a coaxial disc, a point to a sphere and
//     a sphere to a coaxial disc — at the default settings and refined (patches and elements
//     halved, segments and the hemicube's resolution doubled each time: twice for the squares,
//     once for the curved cases, whose finest meshes would take hours), hemicube and ray cast;
//   * the furnace: a closed box of six glowing walls (E = 1, reflectance ρ = 0.5, 0.9, 0.95), where
//     every surface shows E/(1 − ρ), rendered by every method that sees interreflection —
//     radiosity (hemicube, ray cast), meshless (each basis) and the path tracer.
//
// One scene text per case (candela/1 JSON), the method's registry entry and its settings as a
// user's file would give them: what is validated is what `candela render` does.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "radiosity/radiosity_settings.h"

namespace candela {

struct HowellCase {
  std::string name;       // "coaxial discs"
  std::string catalogue;  // "C-41", or "" when the catalogue gives the entry no well-known number
  std::string shapes;     // the two objects, a "shapes" array's members
  unsigned from = 0;      // the object the factor is from (0 or 1)
  double expected = 0;    // F from it to the other
};

// The six cases, each in a scene of unit size (distances and radii of about 1).
std::vector<HowellCase> howell_cases();

// F from the case's `from` object to the other by the radiosity method's mesh and patch rows
// (000 eq. 6-4: the area-weighted mean of its patches' rows toward the other object) at
// refinement `level` (0: the defaults; each level halves the patch size and doubles segments and
// hemicube resolution).
double radiosity_form_factor(const HowellCase& howell, RadiosityFormFactors method, int level);

// The furnace's scene for a method ("radiosity-hemicube", "radiosity-ray-cast",
// "meshless-normalized", "meshless-shepard", "meshless-radial", "path") and reflectance.
struct FurnaceResult {
  std::string method;
  double albedo = 0;
  double expected = 0;       // E/(1 − ρ)
  double mean = 0;           // over the image's pixels (green channel)
  double largest_error = 0;  // the largest |pixel − expected| / expected
  double seconds = 0;
};
std::vector<std::string> furnace_methods();
FurnaceResult run_furnace(const std::string& method, double albedo, bool quick);

struct FormFactorRun {
  bool quick = false;  // one refinement fewer per case, and fewer sites and samples in the furnace
};

// Everything into out_dir (form_factors.csv, furnace.csv, results.json, convergence_flat.png,
// convergence_curved.png); returns results.json's content. Progress lines to log when given.
nlohmann::json run_form_factor_validation(const std::string& out_dir, const FormFactorRun& run,
                                          std::ostream* log);

}  // namespace candela
