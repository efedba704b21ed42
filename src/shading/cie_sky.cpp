#include "shading/cie_sky.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "math/constants.h"

namespace candela {

namespace {

struct Gradation {
  double a, b;
};
struct Indicatrix {
  double c, d, e;
};
// ISO 15469:2004 Table 1: gradation groups I–VI and indicatrix groups 1–6.
constexpr Gradation kGradation[6] = {{4.0, -0.70},  {1.1, -0.8},   {0.0, -1.0},
                                     {-1.0, -0.55}, {-1.0, -0.32}, {-1.0, -0.15}};
constexpr Indicatrix kIndicatrix[6] = {{0, -1.0, 0},     {2, -1.5, 0.15},  {5, -2.5, 0.30},
                                       {10, -3.0, 0.45}, {16, -3.0, 0.30}, {24, -2.8, 0.15}};
// The fifteen types as (gradation, indicatrix) group numbers.
constexpr int kTypes[15][2] = {{1, 1}, {1, 2}, {2, 1}, {2, 2}, {3, 1}, {3, 2}, {3, 3}, {3, 4},
                               {4, 2}, {4, 3}, {4, 4}, {5, 4}, {5, 5}, {6, 5}, {6, 6}};

double gradation(const Gradation& g, double zenith) {
  const double cos_z = std::cos(zenith);
  return cos_z > 0 ? 1 + g.a * std::exp(g.b / cos_z) : 1.0;
}

double indicatrix(const Indicatrix& i, double chi) {
  const double cos_chi = std::cos(chi);
  return 1 + i.c * (std::exp(i.d * chi) - std::exp(i.d * kPi / 2)) + i.e * cos_chi * cos_chi;
}

}  // namespace

double cie_sky_relative_luminance(int type, double zenith, double to_sun, double sun_zenith) {
  if (type < 1 || type > 15)
    throw std::invalid_argument("CIE sky type " + std::to_string(type) + " (expected 1 to 15)");
  const Gradation& g = kGradation[kTypes[type - 1][0] - 1];
  const Indicatrix& i = kIndicatrix[kTypes[type - 1][1] - 1];
  return indicatrix(i, to_sun) * gradation(g, zenith) / (indicatrix(i, sun_zenith) * gradation(g, 0));
}

}  // namespace candela
