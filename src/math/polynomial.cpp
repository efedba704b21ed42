#include "math/polynomial.h"

#include <algorithm>
#include <cmath>

#include "math/constants.h"

namespace candela {
namespace {

// Roots of the monic x^2 + b x + c with the cancellation-free formula. A discriminant that is
// negative only by rounding (relative to the size of the terms, given by tolerance) counts as a
// double root.
int monic_quadratic(double b, double c, double tolerance, double roots[2]) {
  const double half_b = 0.5 * b;
  double discriminant = half_b * half_b - c;
  if (discriminant < 0) {
    if (discriminant < -tolerance * std::max(half_b * half_b, std::fabs(c))) return 0;
    discriminant = 0;
  }
  const double q = -(half_b + std::copysign(std::sqrt(discriminant), half_b));
  if (q == 0) {  // b = c = 0
    roots[0] = roots[1] = 0;
    return 2;
  }
  roots[0] = q;
  roots[1] = c / q;
  if (roots[0] > roots[1]) std::swap(roots[0], roots[1]);
  return 2;
}

// Newton steps on the polynomial with coefficients[0..degree] (highest first), kept only while
// they reduce the residual.
void polish(const double* coefficients, int degree, double& x) {
  for (int step = 0; step < 3; ++step) {
    double value = coefficients[0];
    double derivative = 0;
    for (int i = 1; i <= degree; ++i) {
      derivative = derivative * x + value;
      value = value * x + coefficients[i];
    }
    if (value == 0 || derivative == 0) return;
    const double next = x - value / derivative;
    double next_value = coefficients[0];
    for (int i = 1; i <= degree; ++i) next_value = next_value * next + coefficients[i];
    if (!(std::fabs(next_value) < std::fabs(value))) return;
    x = next;
  }
}

}  // namespace

int solve_quadratic(double a2, double a1, double a0, double roots[2]) {
  if (a2 == 0) {
    if (a1 == 0) return 0;
    roots[0] = -a0 / a1;
    return 1;
  }
  return monic_quadratic(a1 / a2, a0 / a2, 0.0, roots);
}

int solve_cubic(double a3, double a2, double a1, double a0, double roots[3]) {
  if (a3 == 0) return solve_quadratic(a2, a1, a0, roots);
  const double b = a2 / a3, c = a1 / a3, d = a0 / a3;
  // Depressed cubic y^3 + p y + q = 0 with x = y - b/3.
  const double shift = b / 3;
  const double p = c - b * shift;
  const double q = (2.0 / 27.0) * b * b * b - b * c / 3 + d;
  const double half_q = 0.5 * q;
  const double third_p = p / 3;
  const double discriminant = half_q * half_q + third_p * third_p * third_p;
  int count = 0;
  if (discriminant > 0) {
    // One real root (Cardano), in the form without cancellation: u v = -p/3.
    const double u = -std::copysign(std::cbrt(std::fabs(half_q) + std::sqrt(discriminant)), q);
    roots[0] = (u == 0 ? 0.0 : u - third_p / u) - shift;
    count = 1;
  } else if (p == 0) {
    roots[0] = roots[1] = roots[2] = -shift;  // triple root
    count = 3;
  } else {
    // Three real roots (the trigonometric form).
    const double m = 2 * std::sqrt(-third_p);
    const double theta = std::acos(std::clamp(3 * q / (p * m), -1.0, 1.0)) / 3;
    for (int k = 0; k < 3; ++k) roots[k] = m * std::cos(theta - 2 * kPi * k / 3) - shift;
    count = 3;
  }
  const double monic[4] = {1, b, c, d};
  for (int i = 0; i < count; ++i) polish(monic, 3, roots[i]);
  std::sort(roots, roots + count);
  return count;
}

int solve_quartic(double a4, double a3, double a2, double a1, double a0, double roots[4]) {
  if (a4 == 0) return solve_cubic(a3, a2, a1, a0, roots);
  const double b = a3 / a4, c = a2 / a4, d = a1 / a4, e = a0 / a4;
  // Depressed quartic y^4 + p y^2 + q y + r = 0 with x = y - b/4.
  const double shift = b / 4;
  const double b2 = b * b;
  const double p = c - 0.375 * b2;
  const double q = d - 0.5 * b * c + 0.125 * b2 * b;
  const double r = e - 0.25 * b * d + b2 * c / 16 - 3 * b2 * b2 / 256;
  // Descartes: y^4 + p y^2 + q y + r = (y^2 + s y + u)(y^2 - s y + v) with m = s^2 the largest
  // root of the resolvent m^3 + 2p m^2 + (p^2 - 4r) m - q^2 = 0 (positive whenever q != 0).
  double cubic_roots[3];
  const int cubic_count = solve_cubic(1, 2 * p, p * p - 4 * r, -q * q, cubic_roots);
  const double m = cubic_roots[cubic_count - 1];
  constexpr double kTolerance = 1e-12;
  int count = 0;
  if (m > 0 && q != 0) {
    const double s = std::sqrt(m);
    const double u = 0.5 * (p + m - q / s);
    const double v = 0.5 * (p + m + q / s);
    count += monic_quadratic(s, u, kTolerance, roots + count);
    count += monic_quadratic(-s, v, kTolerance, roots + count);
  } else {
    // Biquadratic: z^2 + p z + r = 0 with z = y^2.
    double z[2];
    const int z_count = monic_quadratic(p, r, kTolerance, z);
    for (int i = 0; i < z_count; ++i) {
      if (z[i] < 0) continue;
      const double y = std::sqrt(z[i]);
      roots[count++] = -y;
      roots[count++] = y;
    }
  }
  const double monic[5] = {1, b, c, d, e};
  for (int i = 0; i < count; ++i) {
    roots[i] -= shift;
    polish(monic, 4, roots[i]);
  }
  std::sort(roots, roots + count);
  return count;
}

}  // namespace candela
