// IES LM-63 photometric files (io/ies_reader.h, io/photometry.h): the header and numbers of each format, the
// candela multiplier and ballast factor, bilinear interpolation, every type C symmetry, the
// luminous flux of distributions with a closed form, and bad files refused with line and column.
#include "io/ies_reader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "math/constants.h"

namespace candela {
namespace {

// A type C file: `horizontal` and `vertical` angles, and the candela rows (one per horizontal).
std::string type_c_file(const std::string& vertical, int vertical_count, const std::string& horizontal,
                        int horizontal_count, const std::string& values,
                        const std::string& header = "IESNA:LM-63-2002\n[TEST] t\nTILT=NONE\n") {
  return header + "1 -1 1 " + std::to_string(vertical_count) + " " + std::to_string(horizontal_count) +
         " 1 2 0 0 0\n1 1 0\n" + vertical + "\n" + horizontal + "\n" + values + "\n";
}

std::string ies_error(const std::string& text) {
  try {
    parse_ies(text, "lamp.ies");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Ies, Reads2002HeaderKeywordsMultiplierAndBallastFactor) {
  const std::string text =
      "IESNA:LM-63-2002\r\n[TEST] 12345\r\n[MANUFAC] Candela Lighting\r\n[MORE] second line\r\n"
      "TILT=NONE\r\n2 1500 2.5 3 1 1 2 0.6 1.2 0.1\r\n0.9 1 72\r\n0 45 90\r\n0\r\n100, 80, 20\r\n";
  const Photometry ies = parse_ies(text, "lamp.ies");
  EXPECT_EQ(ies.format, "LM-63-2002");
  ASSERT_EQ(ies.keywords.size(), 3u);
  EXPECT_EQ(ies.keywords[1].first, "MANUFAC");
  EXPECT_EQ(ies.keywords[1].second, "Candela Lighting");
  EXPECT_EQ(ies.tilt, "NONE");
  EXPECT_EQ(ies.lamps, 2);
  EXPECT_EQ(ies.rated_lumens(), 3000);
  EXPECT_EQ(ies.type, PhotometricType::c);
  EXPECT_TRUE(ies.metres);
  EXPECT_EQ(ies.length, 1.2);
  EXPECT_EQ(ies.input_watts, 72);
  // Multiplier 2.5 and ballast factor 0.9 applied; rotational symmetry.
  EXPECT_DOUBLE_EQ(ies.intensity(0, 0), 225);
  EXPECT_DOUBLE_EQ(ies.intensity(45, 137), 180);
  EXPECT_DOUBLE_EQ(ies.intensity(22.5, 300), 202.5);  // halfway between 225 and 180
  EXPECT_DOUBLE_EQ(ies.intensity(90, 10), 45);
  EXPECT_EQ(ies.intensity(120, 0), 0);  // above the last vertical angle: nothing
}

TEST(Ies, OlderFormatsAndTiltDataAreRead) {
  const std::string v1986 = type_c_file("0 90", 2, "0", 1, "10 5", "Some lamp, 1986\nTILT=NONE\n");
  EXPECT_EQ(parse_ies(v1986, "a.ies").format, "LM-63-1986");
  EXPECT_DOUBLE_EQ(parse_ies(v1986, "a.ies").intensity(45, 0), 7.5);
  const std::string v1991 = type_c_file("0 90", 2, "0", 1, "10 5", "IESNA91\n[TEST] x\nTILT=NONE\n");
  EXPECT_EQ(parse_ies(v1991, "a.ies").format, "LM-63-1991");
  // TILT=INCLUDE: geometry, 3 angles and 3 factors, read past (not applied).
  const std::string tilted =
      type_c_file("0 90", 2, "0", 1, "10 5", "IESNA:LM-63-1995\nTILT=INCLUDE\n1\n3\n0 45 90\n1 0.95 0.9\n");
  const Photometry ies = parse_ies(tilted, "a.ies");
  EXPECT_EQ(ies.format, "LM-63-1995");
  EXPECT_EQ(ies.tilt, "INCLUDE");
  EXPECT_DOUBLE_EQ(ies.intensity(0, 0), 10);
}

TEST(Ies, TypeCSymmetriesFoldEveryPlaneOntoTheTable) {
  // Quadrant symmetry (0 to 90): planes 0, 45, 90 with intensities 30, 20, 10 at every γ.
  const Photometry quadrant = parse_ies(type_c_file("0 90", 2, "0 45 90", 3, "30 30 20 20 10 10"), "q.ies");
  for (const double c : {30.0, 150.0, 210.0, 330.0, -30.0, 390.0})
    EXPECT_DOUBLE_EQ(quadrant.intensity(40, c), quadrant.intensity(40, 30)) << c;
  EXPECT_DOUBLE_EQ(quadrant.intensity(40, 30), 30 - 10 * 30.0 / 45);
  EXPECT_DOUBLE_EQ(quadrant.intensity(40, 180), 30);
  // Bilateral about 0–180: C and 360 − C agree, C and 180 − C do not.
  const Photometry bilateral = parse_ies(type_c_file("0 90", 2, "0 90 180", 3, "30 30 20 20 10 10"), "b.ies");
  EXPECT_DOUBLE_EQ(bilateral.intensity(10, 200), bilateral.intensity(10, 160));
  EXPECT_DOUBLE_EQ(bilateral.intensity(10, 160), 10 + 10 * 20.0 / 90);
  EXPECT_NE(bilateral.intensity(10, 20), bilateral.intensity(10, 160));
  // Bilateral about 90–270 (LM-63-1995): C and 180 − C agree.
  const Photometry other = parse_ies(type_c_file("0 90", 2, "90 180 270", 3, "30 30 20 20 10 10"), "o.ies");
  EXPECT_DOUBLE_EQ(other.intensity(10, 45), other.intensity(10, 135));
  EXPECT_DOUBLE_EQ(other.intensity(10, 300), other.intensity(10, 240));
  EXPECT_DOUBLE_EQ(other.intensity(10, 90), 30);
  // No symmetry, last plane 270: between 270 and 360 the table runs back to plane 0.
  const Photometry full =
      parse_ies(type_c_file("0 90", 2, "0 90 180 270", 4, "40 40 30 30 20 20 10 10"), "f.ies");
  EXPECT_DOUBLE_EQ(full.intensity(5, 315), 25);
  EXPECT_DOUBLE_EQ(full.intensity(5, 135), 25);
  EXPECT_DOUBLE_EQ(full.intensity(5, 45), 35);
}

TEST(Ies, FluxOfIsotropicAndLambertianDistributions) {
  // 1000 cd everywhere: 4π × 1000 lm.
  const Photometry isotropic =
      parse_ies(type_c_file("0 45 90 135 180", 5, "0", 1, "1000 1000 1000 1000 1000"), "i.ies");
  EXPECT_NEAR(isotropic.flux(), 4 * kPi * 1000, 1e-6 * 4 * kPi * 1000);
  // A Lambertian downlight, I = 1000 cos γ tabulated every degree to 90: π × 1000 lm (the table's
  // linear pieces under the cosine lose a few parts in 10⁵).
  std::string angles, values;
  for (int g = 0; g <= 90; ++g) {
    angles += std::to_string(g) + " ";
    values += std::to_string(1000 * std::cos(g * kPi / 180)) + " ";
  }
  const Photometry lambertian = parse_ies(type_c_file(angles, 91, "0 90", 2, values + values), "l.ies");
  EXPECT_NEAR(lambertian.flux(), kPi * 1000, 2e-4 * kPi * 1000);
  EXPECT_NEAR(lambertian.intensity(60, 45), 500, 0.1);
}

TEST(Ies, BadFilesNameTheLineColumnAndWhatWasExpected) {
  EXPECT_NE(ies_error("IESNA:LM-63-2002\n[TEST] x\n1 2 3\n").find("lamp.ies:3: no TILT= line"),
            std::string::npos);
  EXPECT_NE(ies_error(type_c_file("0 9O", 2, "0", 1, "1 2")).find("lamp.ies:6:3: \"9O\" is not a number"),
            std::string::npos)
      << ies_error(type_c_file("0 9O", 2, "0", 1, "1 2"));
  EXPECT_NE(ies_error(type_c_file("0 90", 2, "0", 1, "1")).find("the file ends where the candela value"),
            std::string::npos);
  EXPECT_NE(ies_error(type_c_file("90 0", 2, "0", 1, "1 2")).find("vertical angles must increase"),
            std::string::npos);
  EXPECT_NE(ies_error(type_c_file("0 190", 2, "0", 1, "1 2")).find("outside 0° to 180°"), std::string::npos);
  EXPECT_NE(ies_error(type_c_file("0 90", 2, "0 45", 2, "1 2 3 4")).find("none of LM-63's symmetries"),
            std::string::npos);
  EXPECT_NE(ies_error(type_c_file("0 90", 2, "0", 1, "1 -2")).find("cannot be negative"), std::string::npos);
  // Counts that the file cannot hold are refused before anything is allocated.
  const std::string huge = "TILT=NONE\n1 -1 1 100000 100000 1 2 0 0 0\n1 1 0\n0 90\n";
  EXPECT_NE(ies_error(huge).find("do not fit in the rest of the file"), std::string::npos) << ies_error(huge);
  EXPECT_NE(
      ies_error("TILT=NONE\n1 -1 0 2 1 1 2 0 0 0\n").find("lamp.ies:2:6: the candela multiplier must be > 0"),
      std::string::npos)
      << ies_error("TILT=NONE\n1 -1 0 2 1 1 2 0 0 0\n");
  EXPECT_NE(ies_error("TILT=NONE\n1 -1 1 2 1 4 2 0 0 0\n").find("photometric type"), std::string::npos);
}

// A candela multiplier × ballast factor of two large legal-looking numbers made every
// intensity inf (NaN where a value was 0); every number is held to the scene file's 1e16, and each
// scaled value too, at its line and column.
TEST(Ies, IntensitiesThatWouldOverflowAreRefusedWhereTheyAreRead) {
  const std::string header = "IESNA:LM-63-2002\n[TEST] t\nTILT=NONE\n";
  const std::string products = header + "1 -1 1e10 2 1 1 2 0 0 0\n1e10 1 0\n0 90\n0\n0 1000\n";
  EXPECT_NE(
      ies_error(products).find("lamp.ies:8:3: the candela value 1000 × the candela multiplier 1e+10 × the "
                               "ballast factor 1e+10 is 1e+23 cd, above 1e+16"),
      std::string::npos)
      << ies_error(products);
  const std::string huge = header + "1 -1 1e300 2 1 1 2 0 0 0\n1e300 1 0\n0 90\n0\n0 1000\n";
  EXPECT_NE(
      ies_error(huge).find("lamp.ies:4:6: the candela multiplier: magnitude above 1e+16 is not supported "
                           "(found 1e+300)"),
      std::string::npos)
      << ies_error(huge);
  const std::string value = header + "1 -1 1 2 1 1 2 0 0 0\n1 1 0\n0 90\n0\n1e17 0\n";
  EXPECT_NE(
      ies_error(value).find("lamp.ies:8:1: the candela value at vertical angle 0°, horizontal 0°: magnitude "
                            "above 1e+16"),
      std::string::npos)
      << ies_error(value);
  // At the limit the table is read, its intensities and flux finite.
  const Photometry at_limit = parse_ies(header + "1 -1 1e8 2 1 1 2 0 0 0\n1e8 1 0\n0 90\n0\n0 1\n", "t.ies");
  EXPECT_EQ(at_limit.intensity(90, 0), 1e16);
  EXPECT_TRUE(std::isfinite(at_limit.flux()));
}

}  // namespace
}  // namespace candela
