#include "shading/procedural_textures.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>

#include "math/constants.h"
#include "shading/noise.h"

namespace candela {

namespace {

[[noreturn]] void reject(const std::string& what) {
  throw std::invalid_argument(what);
}

void require_finite(double value, const char* name) {
  if (!std::isfinite(value)) reject(std::string(name) + " must be a finite number");
}

void require_positive(double value, const char* name) {
  if (!(std::isfinite(value) && value > 0)) reject(std::string(name) + " must be a finite number > 0");
}

void require_non_negative(double value, const char* name) {
  if (!(std::isfinite(value) && value >= 0)) reject(std::string(name) + " must be a finite number >= 0");
}

void require_finite(const Color& color, const char* name) {
  if (!(std::isfinite(color.r) && std::isfinite(color.g) && std::isfinite(color.b)))
    reject(std::string(name) + " must have finite components");
}

void require_octaves(int octaves) {
  if (octaves < 1 || octaves > kMaxOctaves)
    reject("octaves must be in [1, " + std::to_string(kMaxOctaves) + "] (found " + std::to_string(octaves) +
           ")");
}

void require_mapping(const TextureMapping* mapping) {
  if (mapping == nullptr) reject("a 2D texture needs a mapping");
}

// Hermite step from 0 at edge0 to 1 at edge1 (GLSL smoothstep), flat at both ends.
double smoothstep(double edge0, double edge1, double x) {
  const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

Color mix(const Color& a, const Color& b, double t) {
  return a + (b - a) * t;
}

}  // namespace

int floor_parity(double x) {
  const double cell = std::floor(x);
  // NaN fails the comparison; from 2^62 up every double is a multiple of 2^10 (even).
  if (!(std::fabs(cell) < 0x1p62)) return 0;
  // Two's complement & 1 gives the parity of negative integers too (−1 → 1, −2 → 0).
  return static_cast<int>(static_cast<std::int64_t>(cell) & 1);
}

// --- Checkerboard2DTexture ---------------------------------------------------------------------

Checkerboard2DTexture::Checkerboard2DTexture(const Color& even, const Color& odd,
                                             std::shared_ptr<const TextureMapping> mapping)
    : Texture2D(mapping), even_(even), odd_(odd) {
  require_mapping(mapping.get());
  require_finite(even, "even");
  require_finite(odd, "odd");
}

Color Checkerboard2DTexture::lookup(const Vec2& uv) const {
  // floor(u) + floor(v) is even exactly when the two floors have the same parity.
  return floor_parity(uv.x) == floor_parity(uv.y) ? even_ : odd_;
}

// --- WoodTexture -------------------------------------------------------------------------------

WoodTexture::WoodTexture(const WoodParameters& parameters, const Transform& texture_from_object)
    : SolidTexture(texture_from_object), parameters_(parameters) {
  require_finite(parameters.light, "light");
  require_finite(parameters.dark, "dark");
  require_positive(parameters.ring_frequency, "ring_frequency");
  require_non_negative(parameters.turbulence, "turbulence");
  require_positive(parameters.noise_scale, "noise_scale");
  require_octaves(parameters.octaves);
}

double WoodTexture::darkness(const Vec3& p) const {
  const double radius = std::sqrt(p.x * p.x + p.y * p.y);
  double phase = radius * parameters_.ring_frequency;
  // With no turbulence the rings are exact circles: skip the noise (and keep them exactly periodic).
  if (parameters_.turbulence > 0)
    phase += parameters_.turbulence * fractal_noise(p * parameters_.noise_scale, parameters_.octaves);
  const double ring = phase - std::floor(phase);  // in [0, 1): the position within one year
  // Light early wood, then a late-wood band (about a quarter of the ring) that fades out before
  // the ring ends, so the profile is continuous across ring boundaries.
  return smoothstep(0.60, 0.85, ring) - smoothstep(0.93, 1.00, ring);
}

Color WoodTexture::at(const Vec3& p) const {
  return mix(parameters_.light, parameters_.dark, darkness(p));
}

// --- MarbleTexture -----------------------------------------------------------------------------

MarbleTexture::MarbleTexture(const MarbleParameters& parameters, const Transform& texture_from_object)
    : SolidTexture(texture_from_object), parameters_(parameters) {
  require_finite(parameters.base, "base");
  require_finite(parameters.vein, "vein");
  require_positive(parameters.frequency, "frequency");
  require_non_negative(parameters.turbulence, "turbulence");
  require_positive(parameters.noise_scale, "noise_scale");
  require_octaves(parameters.octaves);
  require_positive(parameters.sharpness, "sharpness");
}

double MarbleTexture::vein_weight(const Vec3& p) const {
  double phase = parameters_.frequency * p.x;
  if (parameters_.turbulence > 0)
    phase += parameters_.turbulence * turbulence(p * parameters_.noise_scale, parameters_.octaves);
  // Perlin 1985: the marble is a sine of x whose phase the turbulence bends into veins.
  // 0.5 + 0.5·sin lies in [0, 1] exactly (both products and the sum are exact at ±1).
  const double value = 0.5 + 0.5 * std::sin(phase);
  return std::pow(value, parameters_.sharpness);
}

Color MarbleTexture::at(const Vec3& p) const {
  return mix(parameters_.base, parameters_.vein, vein_weight(p));
}

// --- NoiseTexture ------------------------------------------------------------------------------

NoiseTexture::NoiseTexture(const NoiseParameters& parameters, const Transform& texture_from_object)
    : SolidTexture(texture_from_object), parameters_(parameters) {
  if (parameters.mode != NoiseMode::fbm && parameters.mode != NoiseMode::turbulence)
    reject("mode must be fbm or turbulence");
  require_octaves(parameters.octaves);
  require_positive(parameters.lacunarity, "lacunarity");
  require_positive(parameters.gain, "gain");
  require_finite(parameters.amplitude, "amplitude");
  require_finite(parameters.offset, "offset");
  require_positive(parameters.scale, "scale");
}

double NoiseTexture::value(const Vec3& p) const {
  const Vec3 q = p * parameters_.scale;
  const double noise =
      parameters_.mode == NoiseMode::fbm
          ? 0.5 + 0.5 * fractal_noise(q, parameters_.octaves, parameters_.lacunarity, parameters_.gain)
          : turbulence(q, parameters_.octaves, parameters_.lacunarity, parameters_.gain);
  return parameters_.offset + parameters_.amplitude * noise;
}

// --- WavesTexture ------------------------------------------------------------------------------

WavesTexture::WavesTexture(std::vector<Wave> waves, std::shared_ptr<const TextureMapping> mapping)
    : Texture2D(mapping), waves_(std::move(waves)) {
  require_mapping(mapping.get());
  if (waves_.empty()) reject("waves needs at least one wave");
  for (const Wave& wave : waves_) {
    require_finite(wave.amplitude, "wave amplitude");
    require_finite(wave.frequency.x, "wave frequency");
    require_finite(wave.frequency.y, "wave frequency");
    require_finite(wave.phase, "wave phase");
    if (wave.frequency.x == 0 && wave.frequency.y == 0)
      reject("wave frequency must not be [0, 0] (a constant is not a wave)");
  }
}

double WavesTexture::value(const Vec2& uv) const {
  double sum = 0;
  for (const Wave& wave : waves_)
    sum +=
        wave.amplitude * std::sin(2 * kPi * (wave.frequency.x * uv.x + wave.frequency.y * uv.y) + wave.phase);
  return sum;
}

}  // namespace candela
