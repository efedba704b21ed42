// Closed-form configuration factors from J. R. Howell, "A Catalog of Radiation Heat Transfer
// Configuration Factors" (3rd ed., 2010; entries named by title, with the catalogue's numbers where
// they are the well-known ones): what the form factors of the radiosity method (000 §6.2–6.4) are
// tested and validated against (radiosity/form_factors_test.cpp, validate/form_factor_validation.h).
#pragma once

#include <cmath>

#include "math/constants.h"

namespace candela {

// C-11, "identical, parallel, directly opposed rectangles" a × b at distance c, X = a/c, Y = b/c:
// F = 2/(πXY) { ln[(1+X²)(1+Y²)/(1+X²+Y²)]^½ + X√(1+Y²) atan(X/√(1+Y²))
//               + Y√(1+X²) atan(Y/√(1+X²)) − X atan X − Y atan Y }.
inline double parallel_rectangles(double X, double Y) {
  return 2 / (kPi * X * Y) *
         (0.5 * std::log((1 + X * X) * (1 + Y * Y) / (1 + X * X + Y * Y)) +
          X * std::sqrt(1 + Y * Y) * std::atan(X / std::sqrt(1 + Y * Y)) +
          Y * std::sqrt(1 + X * X) * std::atan(Y / std::sqrt(1 + X * X)) - X * std::atan(X) -
          Y * std::atan(Y));
}

// C-14, "two finite rectangles of the same length, having one common edge, at an angle of 90°":
// from rectangle 1 (width w) to rectangle 2 (height h), common edge l, W = w/l, H = h/l:
// F_12 = 1/(πW) ( W atan(1/W) + H atan(1/H) − √(H²+W²) atan(1/√(H²+W²))
//        + ¼ ln{ (1+W²)(1+H²)/(1+W²+H²) · [W²(1+W²+H²)/((1+W²)(W²+H²))]^{W²}
//                · [H²(1+H²+W²)/((1+H²)(H²+W²))]^{H²} } ).
inline double perpendicular_rectangles(double W, double H) {
  const double W2 = W * W, H2 = H * H;
  const double log_term = std::log((1 + W2) * (1 + H2) / (1 + W2 + H2)) +
                          W2 * std::log(W2 * (1 + W2 + H2) / ((1 + W2) * (W2 + H2))) +
                          H2 * std::log(H2 * (1 + H2 + W2) / ((1 + H2) * (H2 + W2)));
  return (W * std::atan(1 / W) + H * std::atan(1 / H) -
          std::sqrt(H2 + W2) * std::atan(1 / std::sqrt(H2 + W2)) + 0.25 * log_term) /
         (kPi * W);
}

// C-41, "disk to parallel coaxial disk": radii r1 (from), r2 (to), distance h, R = r/h,
// X = 1 + (1 + R2²)/R1²: F_12 = ½ [X − √(X² − 4 (r2/r1)²)].
inline double coaxial_discs(double r1, double r2, double h) {
  const double R1 = r1 / h, R2 = r2 / h;
  const double X = 1 + (1 + R2 * R2) / (R1 * R1);
  return 0.5 * (X - std::sqrt(X * X - 4 * (r2 / r1) * (r2 / r1)));
}

// "Plane element to a parallel coaxial disk" of radius r at distance h: F = r²/(h² + r²).
inline double point_to_coaxial_disc(double r, double h) {
  return r * r / (h * h + r * r);
}

// "Plane element to a parallel rectangle" a × b at distance c, the element's normal through a
// corner of it, A = a/c, B = b/c:
// F = 1/(2π) [A/√(1+A²) atan(B/√(1+A²)) + B/√(1+B²) atan(A/√(1+B²))].
inline double point_to_parallel_rectangle_corner(double a, double b, double c) {
  const double A = a / c, B = b / c;
  return (A / std::sqrt(1 + A * A) * std::atan(B / std::sqrt(1 + A * A)) +
          B / std::sqrt(1 + B * B) * std::atan(A / std::sqrt(1 + B * B))) /
         (2 * kPi);
}

// "Differential planar element to a sphere", the element facing the sphere's centre at distance h
// from it: F = (r/h)².
inline double point_to_sphere(double r, double h) {
  return (r / h) * (r / h);
}

// "Sphere to a coaxial disk" of radius a whose centre is h from the sphere's centre, facing it:
// F = ½ (1 − 1/√(1 + (a/h)²)).
inline double sphere_to_coaxial_disc(double a, double h) {
  return 0.5 * (1 - 1 / std::sqrt(1 + (a / h) * (a / h)));
}

}  // namespace candela
