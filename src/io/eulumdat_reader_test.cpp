// EULUMDAT files (io/eulumdat_reader.h): the fixed lines, cd/klm scaled by the lamps' flux and the
// conversion factor, each Isym's stored planes unfolded by Photometry's symmetry, the flux of a
// closed-form distribution, and bad files refused with their line.
#include "io/eulumdat_reader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "math/constants.h"

namespace candela {
namespace {

// A file of Mc planes every 360/Mc degrees and the given γ-angles, with `values` (one per line).
std::string ldt_file(int symmetry, int planes, const std::vector<double>& gammas,
                     const std::vector<double>& values, double lamp_flux = 2000, double conversion = 1) {
  std::string text = "Candela Lighting\n1\n" + std::to_string(symmetry) + "\n" + std::to_string(planes) +
                     "\n" + std::to_string(360.0 / planes) + "\n" + std::to_string(gammas.size()) +
                     "\n5\nREPORT-1\n"
                     "Downlight D1\nD1-100\nd1.ldt\n2026-12-03\n"
                     "200\n0\n80\n150\n0\n0\n0\n0\n0\n100\n85\n" +
                     std::to_string(conversion) + "\n0\n1\n2\nLED\n" + std::to_string(lamp_flux) +
                     "\n3000K\n1A\n24\n";
  for (int k = 0; k < 10; ++k) text += "0.5\n";
  for (int i = 0; i < planes; ++i) text += std::to_string(i * 360.0 / planes) + "\n";
  for (const double g : gammas) text += std::to_string(g) + "\n";
  for (const double v : values) text += std::to_string(v) + "\n";
  return text;
}

std::string eulumdat_error(const std::string& text) {
  try {
    parse_eulumdat(text, "lamp.ldt");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Eulumdat, ReadsTheLinesAndScalesCandelaPerKilolumen) {
  // Rotational symmetry (Isym 1): one plane; 2,000 lm of lamps, conversion factor 1.5.
  const Photometry ldt = parse_eulumdat(ldt_file(1, 24, {0, 45, 90}, {300, 200, 50}, 2000, 1.5), "d1.ldt");
  EXPECT_EQ(ldt.format, "EULUMDAT");
  EXPECT_EQ(ldt.keywords[1].second, "REPORT-1");
  EXPECT_EQ(ldt.keywords[2].second, "Downlight D1");
  EXPECT_EQ(ldt.lamps, 2);
  EXPECT_EQ(ldt.rated_lumens(), 2000);
  EXPECT_EQ(ldt.input_watts, 24);
  EXPECT_DOUBLE_EQ(ldt.length, 0.15);
  EXPECT_DOUBLE_EQ(ldt.intensity(0, 0), 300 * 2 * 1.5);
  EXPECT_DOUBLE_EQ(ldt.intensity(45, 123), 200 * 2 * 1.5);
  EXPECT_DOUBLE_EQ(ldt.intensity(67.5, 300), 125 * 2 * 1.5);
  EXPECT_EQ(ldt.intensity(135, 0), 0);
}

TEST(Eulumdat, EachSymmetryKeepsItsPlanesAndUnfoldsThem) {
  const std::vector<double> gammas = {0, 90};
  // Isym 4, Mc 4: planes C0 and C90 stored.
  const Photometry quadrant = parse_eulumdat(ldt_file(4, 4, gammas, {100, 100, 50, 50}), "q.ldt");
  EXPECT_EQ(quadrant.horizontal, (std::vector<double>{0, 90}));
  EXPECT_DOUBLE_EQ(quadrant.intensity(10, 270), quadrant.intensity(10, 90));
  EXPECT_DOUBLE_EQ(quadrant.intensity(10, 180), 200);
  // Isym 2, Mc 4: C0, C90, C180; C270 mirrors C90.
  const Photometry bilateral = parse_eulumdat(ldt_file(2, 4, gammas, {100, 100, 50, 50, 10, 10}), "b.ldt");
  EXPECT_EQ(bilateral.horizontal, (std::vector<double>{0, 90, 180}));
  EXPECT_DOUBLE_EQ(bilateral.intensity(10, 270), 100);
  EXPECT_DOUBLE_EQ(bilateral.intensity(10, 180), 20);
  // Isym 3, Mc 4: C90, C180, C270; C0 mirrors C180.
  const Photometry other = parse_eulumdat(ldt_file(3, 4, gammas, {100, 100, 50, 50, 10, 10}), "o.ldt");
  EXPECT_EQ(other.horizontal, (std::vector<double>{90, 180, 270}));
  EXPECT_DOUBLE_EQ(other.intensity(10, 0), 100);
  EXPECT_DOUBLE_EQ(other.intensity(10, 45), other.intensity(10, 135));
  // Isym 0, Mc 4: every plane; between C270 and C360 back to C0.
  const Photometry none = parse_eulumdat(ldt_file(0, 4, gammas, {100, 100, 80, 80, 60, 60, 40, 40}), "n.ldt");
  EXPECT_DOUBLE_EQ(none.intensity(10, 315), 2 * 70);
}

TEST(Eulumdat, FluxOfALambertianDownlight) {
  // I = 1000 cd/klm × cos γ for γ ≤ 90 and 0 above, 2,000 lamp lumens: π × 2,000 lm.
  std::vector<double> gammas, values;
  for (int g = 0; g <= 180; g += 1) {
    gammas.push_back(g);
    values.push_back(g <= 90 ? 1000 * std::cos(g * kPi / 180) : 0);
  }
  const Photometry ldt = parse_eulumdat(ldt_file(1, 24, gammas, values), "l.ldt");
  EXPECT_NEAR(ldt.flux(), kPi * 2000, 2e-4 * kPi * 2000);
}

TEST(Eulumdat, BadFilesNameTheLineAndWhatWasExpected) {
  EXPECT_NE(eulumdat_error("Company\n1\n").find("lamp.ldt:3: the file ends where the symmetry indicator"),
            std::string::npos)
      << eulumdat_error("Company\n1\n");
  EXPECT_NE(eulumdat_error("Company\n1\n7\n")
                .find("lamp.ldt:3: the symmetry indicator Isym (line 3) must be an integer"),
            std::string::npos);
  EXPECT_EQ(eulumdat_error(ldt_file(1, 24, {0, 90}, {1, 2})), "no error");
  EXPECT_NE(
      eulumdat_error(ldt_file(1, 24, {0, 90}, {1})).find("the file ends where the intensity at C0°, γ 90°"),
      std::string::npos)
      << eulumdat_error(ldt_file(1, 24, {0, 90}, {1}));
  // Counts the file cannot hold are refused before anything is allocated: 24 planes × 18,001.
  std::string huge = ldt_file(0, 24, {0, 90}, {1, 2});
  huge.replace(huge.find("\n2\n5\nREPORT") + 1, 1, "18001");
  EXPECT_NE(eulumdat_error(huge).find("do not fit in the rest of the file"), std::string::npos)
      << eulumdat_error(huge);
  EXPECT_NE(eulumdat_error(ldt_file(1, 24, {90, 0}, {1, 2})).find("γ-angles must increase"),
            std::string::npos);
  EXPECT_NE(eulumdat_error(ldt_file(1, 24, {0, 90}, {1, -2})).find("cannot be negative"), std::string::npos);
  EXPECT_NE(eulumdat_error(ldt_file(4, 6, {0, 90}, {1, 2, 3, 4})).find("divisible by 4"), std::string::npos);
  EXPECT_NE(
      eulumdat_error(ldt_file(1, 24, {0, 90}, {1, 2}, 0)).find("luminous flux of lamp set 1 must be > 0"),
      std::string::npos);
  // A number that is not one, with its line: line 6 is Ng.
  std::string bad = ldt_file(1, 24, {0, 90}, {1, 2});
  const std::size_t ng = bad.find("\n2\n5\n");
  bad.replace(ng + 1, 1, "two");
  EXPECT_NE(eulumdat_error(bad).find("lamp.ldt:6: \"two\" is not a number"), std::string::npos)
      << eulumdat_error(bad);
}

// Flux / 1000 × the conversion factor of two large legal numbers made every intensity
// inf; every number is held to 1e16 and each scaled intensity too, at its line.
TEST(Eulumdat, IntensitiesThatWouldOverflowAreRefusedWhereTheyAreRead) {
  const std::string products = ldt_file(1, 24, {0, 90}, {0, 1000}, 1e16, 1e12);
  EXPECT_NE(eulumdat_error(products).find("the intensity 1000 cd/klm × the lamp flux 1e+16 lm / 1000 × the "
                                          "conversion factor 1e+12 is 1e+28 cd, above 1e+16"),
            std::string::npos)
      << eulumdat_error(products);
  // The last line of the file is the value 1000.
  const int last_line = static_cast<int>(std::count(products.begin(), products.end(), '\n'));
  EXPECT_NE(eulumdat_error(products).find("lamp.ldt:" + std::to_string(last_line) + ":"), std::string::npos)
      << eulumdat_error(products);
  const std::string huge = ldt_file(1, 24, {0, 90}, {0, 1}, 2000, 1e300);
  EXPECT_NE(
      eulumdat_error(huge).find("lamp.ldt:24: the conversion factor for luminous intensities (line 24): "
                                "magnitude above 1e+16 is not supported"),
      std::string::npos)
      << eulumdat_error(huge);
}

}  // namespace
}  // namespace candela
