// Real roots of polynomials up to degree four (the torus needs the quartic).
#pragma once

namespace candela {

// Each solver writes the real roots of a_n x^n + ... + a_0 = 0 in ascending order and returns
// how many there are. Roots are counted with multiplicity where it is detected (a zero
// discriminant gives two equal roots); a vanishing leading coefficient falls back to the lower
// degree. An identically zero polynomial reports no roots.
int solve_quadratic(double a2, double a1, double a0, double roots[2]);
int solve_cubic(double a3, double a2, double a1, double a0, double roots[3]);
// Descartes' factorisation through the resolvent cubic, then every root polished by Newton
// steps on the original polynomial. Near-double roots (a tangent ray) are kept as two roots.
int solve_quartic(double a4, double a3, double a2, double a1, double a0, double roots[4]);

}  // namespace candela
