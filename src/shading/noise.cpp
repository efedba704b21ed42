#include "shading/noise.h"

#include <array>
#include <cmath>
#include <cstdint>

namespace candela {

namespace {

// Perlin 2002, "Improving Noise": the permutation of 0..255 of the reference implementation.
constexpr std::array<std::uint8_t, 256> kPermutation = {
    151, 160, 137, 91,  90,  15,  131, 13,  201, 95,  96,  53,  194, 233, 7,   225, 140, 36,  103, 30,
    69,  142, 8,   99,  37,  240, 21,  10,  23,  190, 6,   148, 247, 120, 234, 75,  0,   26,  197, 62,
    94,  252, 219, 203, 117, 35,  11,  32,  57,  177, 33,  88,  237, 149, 56,  87,  174, 20,  125, 136,
    171, 168, 68,  175, 74,  165, 71,  134, 139, 48,  27,  166, 77,  146, 158, 231, 83,  111, 229, 122,
    60,  211, 133, 230, 220, 105, 92,  41,  55,  46,  245, 40,  244, 102, 143, 54,  65,  25,  63,  161,
    1,   216, 80,  73,  209, 76,  132, 187, 208, 89,  18,  169, 200, 196, 135, 130, 116, 188, 159, 86,
    164, 100, 109, 198, 173, 186, 3,   64,  52,  217, 226, 250, 124, 123, 5,   202, 38,  147, 118, 126,
    255, 82,  85,  212, 207, 206, 59,  227, 47,  16,  58,  17,  182, 189, 28,  42,  223, 183, 170, 213,
    119, 248, 152, 2,   44,  154, 163, 70,  221, 153, 101, 155, 167, 43,  172, 9,   129, 22,  39,  253,
    19,  98,  108, 110, 79,  113, 224, 232, 178, 185, 112, 104, 218, 246, 97,  228, 251, 34,  242, 193,
    238, 210, 144, 12,  191, 179, 162, 241, 81,  51,  145, 235, 249, 14,  239, 107, 49,  192, 214, 31,
    181, 199, 106, 157, 184, 84,  204, 176, 115, 121, 50,  45,  127, 4,   150, 254, 138, 236, 205, 93,
    222, 114, 67,  29,  24,  72,  243, 141, 128, 195, 78,  66,  215, 61,  156, 180};

// The table written twice, as in the reference, so that hash chains such as perm[perm[X] + Y + 1]
// (indices up to 511) need no further wrapping.
constexpr std::array<std::uint8_t, 512> kDoubledPermutation = [] {
  std::array<std::uint8_t, 512> doubled{};
  for (int i = 0; i < 512; ++i) doubled[i] = kPermutation[i & 255];
  return doubled;
}();

// Perlin 2002: the 12 vectors from the centre of a cube to its edges' midpoints, padded to 16
// (hash & 15) by repeating (1,1,0), (−1,1,0), (0,−1,1), (0,−1,−1) — the order of the reference
// grad(hash, x, y, z), entry h being the vector whose dot product with (x, y, z) it returns.
constexpr std::array<Vec3, 16> kGradients = {{
    {1, 1, 0},
    {-1, 1, 0},
    {1, -1, 0},
    {-1, -1, 0},
    {1, 0, 1},
    {-1, 0, 1},
    {1, 0, -1},
    {-1, 0, -1},
    {0, 1, 1},
    {0, -1, 1},
    {0, 1, -1},
    {0, -1, -1},
    {1, 1, 0},
    {0, -1, 1},
    {-1, 1, 0},
    {0, -1, -1},
}};

// Perlin 2002, "Improving Noise": quintic fade 6t^5 − 15t^4 + 10t^3, whose first and second
// derivatives vanish at 0 and 1 (the 1985 cubic 3t^2 − 2t^3 left second-derivative seams).
double fade(double t) {
  return t * t * t * (t * (t * 6 - 15) + 10);
}
double fade_derivative(double t) {
  return 30 * t * t * (t * (t - 2) + 1);
}

double lerp(double t, double a, double b) {
  return a + t * (b - a);
}

// floor(x) modulo 256 for an integral double `cell`, never overflowing. Below 2^62 the cast to a
// 64-bit integer is exact and & 255 is the two's-complement remainder (−1 → 255, as the
// reference's `(int)Math.floor(x) & 255`). From 2^62 up every double is a multiple of 2^10,
// hence of 256.
int wrap_lattice(double cell) {
  if (std::fabs(cell) < 0x1p62) return static_cast<int>(static_cast<std::int64_t>(cell) & 255);
  return 0;
}

struct Dual {
  double value;
  Vec3 gradient;
};

// a + t·(b − a) together with its gradient; dt is ∇t (the fade's derivative along one axis).
Dual lerp(double t, const Vec3& dt, const Dual& a, const Dual& b) {
  const double difference = b.value - a.value;
  return {a.value + t * difference, a.gradient + (b.gradient - a.gradient) * t + dt * difference};
}

template <bool kWithGradient>
NoiseSample evaluate(const Vec3& p) {
  if (!is_finite(p)) return {};
  const double cell_x = std::floor(p.x), cell_y = std::floor(p.y), cell_z = std::floor(p.z);
  const int X = wrap_lattice(cell_x), Y = wrap_lattice(cell_y), Z = wrap_lattice(cell_z);
  // The point within its unit cell, in [0, 1).
  const double x = p.x - cell_x, y = p.y - cell_y, z = p.z - cell_z;

  // The reference's hash chain: corner (i, j, k) of the cell gets perm[perm[perm[X+i]+Y+j]+Z+k].
  const auto& perm = kDoubledPermutation;
  const int A = perm[X] + Y, AA = perm[A] + Z, AB = perm[A + 1] + Z;
  const int B = perm[X + 1] + Y, BA = perm[B] + Z, BB = perm[B + 1] + Z;
  const Vec3& g000 = kGradients[perm[AA] & 15];
  const Vec3& g100 = kGradients[perm[BA] & 15];
  const Vec3& g010 = kGradients[perm[AB] & 15];
  const Vec3& g110 = kGradients[perm[BB] & 15];
  const Vec3& g001 = kGradients[perm[AA + 1] & 15];
  const Vec3& g101 = kGradients[perm[BA + 1] & 15];
  const Vec3& g011 = kGradients[perm[AB + 1] & 15];
  const Vec3& g111 = kGradients[perm[BB + 1] & 15];

  // Each corner contributes the linear ramp g · (p − corner), zero at the corner itself.
  const double n000 = dot(g000, {x, y, z});
  const double n100 = dot(g100, {x - 1, y, z});
  const double n010 = dot(g010, {x, y - 1, z});
  const double n110 = dot(g110, {x - 1, y - 1, z});
  const double n001 = dot(g001, {x, y, z - 1});
  const double n101 = dot(g101, {x - 1, y, z - 1});
  const double n011 = dot(g011, {x, y - 1, z - 1});
  const double n111 = dot(g111, {x - 1, y - 1, z - 1});

  const double u = fade(x), v = fade(y), w = fade(z);
  if constexpr (!kWithGradient) {
    // Trilinear blend by the faded coordinates, in the reference's order.
    return {lerp(w, lerp(v, lerp(u, n000, n100), lerp(u, n010, n110)),
                 lerp(v, lerp(u, n001, n101), lerp(u, n011, n111))),
            {}};
  } else {
    // The same blend carried with gradients (each ramp's gradient is its corner vector).
    const Vec3 du{fade_derivative(x), 0, 0}, dv{0, fade_derivative(y), 0}, dw{0, 0, fade_derivative(z)};
    const Dual x00 = lerp(u, du, {n000, g000}, {n100, g100});
    const Dual x10 = lerp(u, du, {n010, g010}, {n110, g110});
    const Dual x01 = lerp(u, du, {n001, g001}, {n101, g101});
    const Dual x11 = lerp(u, du, {n011, g011}, {n111, g111});
    const Dual result = lerp(w, dw, lerp(v, dv, x00, x10), lerp(v, dv, x01, x11));
    return {result.value, result.gradient};
  }
}

}  // namespace

double gradient_noise(const Vec3& p) {
  return evaluate<false>(p).value;
}

Vec3 gradient_noise_gradient(const Vec3& p) {
  return evaluate<true>(p).gradient;
}

NoiseSample gradient_noise_sample(const Vec3& p) {
  return evaluate<true>(p);
}

double fractal_noise(const Vec3& p, int octaves, double lacunarity, double gain) {
  double sum = 0, frequency = 1, amplitude = 1;
  for (int octave = 0; octave < octaves; ++octave) {
    sum += amplitude * gradient_noise(p * frequency);
    frequency *= lacunarity;
    amplitude *= gain;
  }
  return sum;
}

Vec3 fractal_noise_gradient(const Vec3& p, int octaves, double lacunarity, double gain) {
  Vec3 sum;
  double frequency = 1, amplitude = 1;
  for (int octave = 0; octave < octaves; ++octave) {
    // Chain rule: d/dp noise(f·p) = f · ∇noise(f·p).
    sum += gradient_noise_gradient(p * frequency) * (amplitude * frequency);
    frequency *= lacunarity;
    amplitude *= gain;
  }
  return sum;
}

double turbulence(const Vec3& p, int octaves, double lacunarity, double gain) {
  double sum = 0, frequency = 1, amplitude = 1;
  for (int octave = 0; octave < octaves; ++octave) {
    sum += amplitude * std::fabs(gradient_noise(p * frequency));
    frequency *= lacunarity;
    amplitude *= gain;
  }
  return sum;
}

}  // namespace candela
