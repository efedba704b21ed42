// A luminaire's luminous intensity distribution as the photometric files give it (IES LM-63,
// io/ies_reader.h; EULUMDAT, io/eulumdat_reader.h): a table of candela values over vertical and
// horizontal angles, with the symmetry the horizontal angles imply, and the lamps' data.
//
// Symmetry (LM-63-02 §5.18, EULUMDAT's Isym), type C: one horizontal angle (0) — the same in every
// plane; horizontal angles 0 to 90 — quadrant symmetry; 0 to 180 — bilateral about the 0–180
// plane; 90 to 270 — bilateral about the 90–270 plane; up to 360 — none (past the last plane the
// table runs back to plane 0). Types A and B: horizontal angles 0 to 90 mirror to −90 to 0; −90
// to 90 none. Between the tabulated angles the intensity is bilinear in the vertical and
// horizontal angle; outside the vertical range it is 0.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace candela {

enum class PhotometricType { c = 1, b = 2, a = 3 };

struct Photometry {
  std::string format;  // "LM-63-1986", "LM-63-1991", "LM-63-1995", "LM-63-2002" or "EULUMDAT"
  // IES: ("TEST", "..."), in file order; EULUMDAT: the identification lines by their names.
  std::vector<std::pair<std::string, std::string>> keywords;
  std::string tilt;  // IES: "NONE", "INCLUDE" or the file name; EULUMDAT: the tilt angle
  int lamps = 1;
  double lumens_per_lamp = -1;  // -1: absolute photometry (the candela values are the luminaire's)
  double candela_multiplier = 1;
  PhotometricType type = PhotometricType::c;
  bool metres = true;                        // units of the luminous opening (false: feet)
  double width = 0, length = 0, height = 0;  // the luminous opening
  double ballast_factor = 1;
  double input_watts = 0;
  std::vector<double> vertical;    // degrees, increasing
  std::vector<double> horizontal;  // degrees, increasing
  // candela[h * vertical.size() + v], multiplied by candela_multiplier and ballast_factor.
  std::vector<double> candela;

  // The intensity in candela toward (vertical, horizontal) in degrees — type C: γ from the
  // nadir and the C-plane angle — with the file's symmetry and bilinear interpolation.
  double intensity(double vertical_degrees, double horizontal_degrees) const;
  // The luminous flux ∫ I dω in lumens over the whole sphere (type C: sin γ dγ dC; types A and B:
  // cos V dV dH), by the midpoint rule on quarter-degree cells.
  double flux() const;
  // The rated lumens of the lamps (lamps × lumens per lamp), or -1 for absolute photometry.
  double rated_lumens() const { return lumens_per_lamp < 0 ? -1 : lamps * lumens_per_lamp; }
};

}  // namespace candela
