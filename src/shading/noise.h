// Gradient noise for procedural textures and bump mapping (SPEC §7: "wood, marble from gradient
// noise"; 000 §4.2.1: a normal perturbed by a noise height gives a rough surface).
//
// gradient_noise is Ken Perlin's improved noise (SIGGRAPH 2002, "Improving Noise"), value for
// value the same as his reference ImprovedNoise.java: the fixed 256-entry permutation, the 12
// cube-edge gradients (padded to 16), the quintic fade 6t^5 − 15t^4 + 10t^3. It is zero at every
// integer lattice point, lies in about [−1, 1], and is C1 (continuous, with continuous first
// derivatives), so a bump map built on it shows no creases along cell faces.
//
// All functions are pure: the same input gives the same bits on every thread and, since the
// build uses ISO C++ (no floating-point contraction), on every platform. Any coordinate may be
// huge (the lattice index wraps modulo 256 without overflow); a NaN or infinite coordinate gives
// 0 (and a zero gradient).
#pragma once

#include "math/vector.h"

namespace candela {

// The noise value with its analytic gradient, from one walk over the lattice cell.
struct NoiseSample {
  double value = 0;
  Vec3 gradient;
};

double gradient_noise(const Vec3& p);
// ∇ gradient_noise at p, exact (not finite differences): for bump mapping.
Vec3 gradient_noise_gradient(const Vec3& p);
NoiseSample gradient_noise_sample(const Vec3& p);

// Fractional Brownian motion: Σ_{i<octaves} gain^i · noise(lacunarity^i · p). One octave is
// gradient_noise itself; the default (2, 0.5) doubles the frequency and halves the amplitude at
// each octave, so the sum stays within about ±(2 − 2^(1−octaves)). octaves < 1 gives 0.
double fractal_noise(const Vec3& p, int octaves, double lacunarity = 2, double gain = 0.5);
// ∇ fractal_noise: Σ gain^i · lacunarity^i · ∇noise(lacunarity^i · p).
Vec3 fractal_noise_gradient(const Vec3& p, int octaves, double lacunarity = 2, double gain = 0.5);

// Perlin 1985 ("An Image Synthesizer"): Σ_{i<octaves} gain^i · |noise(lacunarity^i · p)|, ≥ 0.
// The absolute value folds each octave into sharp creases (marble veins, flames); it is only C0
// there, so it has no gradient function.
double turbulence(const Vec3& p, int octaves, double lacunarity = 2, double gain = 0.5);

}  // namespace candela
