// Warps from the unit square [0,1)² to the domains the renderer samples, each with its density
// (with respect to area on the disc/triangle, solid angle on the sphere) and its inverse, so that
// tests can check warp(inverse(x)) = x and a χ² test can compare samples with the density
// (SPEC "Architecture": src/sampling, shared by anti-aliasing, BSDFs, path tracing and meshless).
// Local frame convention: z is the axis (the normal), directions are unit vectors.
#pragma once

#include "math/vector.h"

namespace candela {

// Shirley–Chiu concentric map onto the unit disc (area preserving: density 1/π).
Vec2 square_to_uniform_disc_concentric(const Vec2& u);
Vec2 uniform_disc_concentric_to_square(const Vec2& p);
inline double uniform_disc_pdf() {
  return 1.0 / 3.14159265358979323846;
}

// Uniform on the unit sphere (density 1/(4π)) and on the upper hemisphere z ≥ 0 (1/(2π)).
Vec3 square_to_uniform_sphere(const Vec2& u);
Vec2 uniform_sphere_to_square(const Vec3& direction);
double uniform_sphere_pdf();
Vec3 square_to_uniform_hemisphere(const Vec2& u);
Vec2 uniform_hemisphere_to_square(const Vec3& direction);
double uniform_hemisphere_pdf(const Vec3& direction);  // 0 below the horizon

// Cosine-weighted upper hemisphere (Malley: the concentric disc lifted): density cos θ/π.
Vec3 square_to_cosine_hemisphere(const Vec2& u);
Vec2 cosine_hemisphere_to_square(const Vec3& direction);
double cosine_hemisphere_pdf(const Vec3& direction);  // 0 below the horizon

// Uniform inside the cone of directions within angle acos(cos_max) of +z: 1/(2π(1 − cos_max)).
Vec3 square_to_uniform_cone(const Vec2& u, double cos_max);
Vec2 uniform_cone_to_square(const Vec3& direction, double cos_max);
double uniform_cone_pdf(const Vec3& direction, double cos_max);  // 0 outside the cone

// Power-cosine lobe about +z: density (n + 1)/(2π)·cos^n θ (the normalized Phong lobe).
Vec3 square_to_power_cosine(const Vec2& u, double exponent);
Vec2 power_cosine_to_square(const Vec3& direction, double exponent);
double power_cosine_pdf(const Vec3& direction, double exponent);  // 0 below the horizon

// Uniform on a triangle: barycentrics (b0, b1), b2 = 1 − b0 − b1 (area density 1/area).
Vec2 square_to_uniform_triangle(const Vec2& u);
Vec2 uniform_triangle_to_square(const Vec2& barycentric);

// Bilinear densities on [0, 1]² (pbrt-v4's SampleBilinear; Hart et al. 2020, "Practical product
// sampling by fitting and composing warps"): density proportional to the bilinear interpolation
// of the corner weights w = {w(0,0), w(1,0), w(0,1), w(1,1)} (non-negative, not all zero), the
// second coordinate drawn from its marginal, the first from the conditional; the inverse maps a
// point back. sample_linear is the 1D case on [0, 1] with weights a at 0 and b at 1.
double sample_linear(double u, double a, double b);
double linear_to_square(double x, double a, double b);
Vec2 square_to_bilinear(const Vec2& u, const double (&w)[4]);
Vec2 bilinear_to_square(const Vec2& p, const double (&w)[4]);
double bilinear_pdf(const Vec2& p, const double (&w)[4]);

// Microfacet normals m about +z distributed as D(m)·cos θ_m (the density of m in solid angle),
// for the Beckmann and GGX (Trowbridge–Reitz) distributions of roughness α.
Vec3 square_to_beckmann(const Vec2& u, double alpha);
Vec2 beckmann_to_square(const Vec3& m, double alpha);
double beckmann_pdf(const Vec3& m, double alpha);
Vec3 square_to_ggx(const Vec2& u, double alpha);
Vec2 ggx_to_square(const Vec3& m, double alpha);
double ggx_pdf(const Vec3& m, double alpha);

}  // namespace candela
