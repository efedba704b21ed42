// Procedural textures (SPEC §7: checkerboard, wood, marble from gradient noise; sine waves and
// noise as bump heights, 000 §4.2.1). The 2D ones read the (u, v) of a TextureMapping, whose
// scale and offset do the tiling; the solid ones read the shape's own coordinates through an
// optional texture_from_object Transform that places, turns and scales the pattern.
//
// Every constructor checks its parameters and throws std::invalid_argument, naming the
// parameter, for NaN or infinite values, non-positive frequencies and scales, octaves outside
// [1, kMaxOctaves], an empty wave list or a missing mapping.
#pragma once

#include <memory>
#include <string_view>
#include <vector>

#include "math/transform.h"
#include "math/vector.h"
#include "shading/texture.h"

namespace candela {

// Beyond 16 octaves of a lacunarity-2 sum the finest one is 2^-15 of the first in scale: finer
// than any pixel footprint and below double-precision rounding of the coarsest at unit scale.
inline constexpr int kMaxOctaves = 16;

// The parity (0 or 1) of floor(x), defined for every double: a NaN or infinite x gives 0, and so
// does |x| ≥ 2^62, where every double is an even integer. Checkerboards use it instead of a cast
// of floor(x) to an integer, which is undefined behaviour for huge values.
int floor_parity(double x);

// A checkerboard over (u, v) with cells of size 1 (the mapping's scale sets how many repeat):
// color `even` where floor(u) + floor(v) is even, `odd` elsewhere. Cells are half-open
// [i, i + 1): a point on an edge or corner belongs to the cell above and to the right of it, so
// (0, 0) is `even` and (1, 0), (0, 1) are `odd`.
class Checkerboard2DTexture final : public Texture2D {
 public:
  Checkerboard2DTexture(const Color& even, const Color& odd, std::shared_ptr<const TextureMapping> mapping);
  Color lookup(const Vec2& uv) const override;
  std::string_view type_name() const override { return "checker2d"; }

 private:
  Color even_, odd_;
};

// Wood: concentric rings about the texture-space z axis (the trunk), their phase disturbed by
// fBm so they wander like growth rings (after Perlin 1985 and Peachey, "Texturing & Modeling"):
//   r    = sqrt(x² + y²)
//   ring = frac(r · ring_frequency + turbulence · fractal_noise(p · noise_scale, octaves))
//   dark = smoothstep(0.60, 0.85, ring) − smoothstep(0.93, 1.00, ring)
//   color = light + dark · (dark_color − light)
// The profile `dark` is 0 through the light early wood, rises to 1 in a late-wood band about a
// quarter of a ring wide and falls back before the ring ends, so it is continuous (and smooth)
// across ring boundaries and the color is always a convex combination of `light` and `dark`.
struct WoodParameters {
  Color light{0.78, 0.56, 0.33};
  Color dark{0.42, 0.24, 0.11};
  double ring_frequency = 4;  // rings per unit of radius
  double turbulence = 0.4;    // amplitude of the phase perturbation, in rings (≥ 0)
  double noise_scale = 1.5;   // frequency of the perturbing noise
  int octaves = 3;
};

class WoodTexture final : public SolidTexture {
 public:
  explicit WoodTexture(const WoodParameters& parameters, const Transform& texture_from_object = {});
  Color at(const Vec3& p) const override;
  // The profile `dark` above, in [0, 1], at a texture-space point.
  double darkness(const Vec3& p) const;
  std::string_view type_name() const override { return "wood"; }
  const WoodParameters& parameters() const { return parameters_; }

 private:
  WoodParameters parameters_;
};

// Marble: Perlin's 1985 sine of turbulence ("An Image Synthesizer", the marble vase): veins are
// the layers x = const of a sine, bent by turbulence:
//   value  = 0.5 + 0.5 · sin(frequency · x + turbulence · turbulence_noise(p · noise_scale, octaves))
//   color = base + value^sharpness · (vein − base)
// (turbulence_noise being noise.h's turbulence()), so value 0 is `base`, value 1 is `vein`, and a
// sharpness above 1 narrows the veins.
struct MarbleParameters {
  Color base{0.92, 0.91, 0.88};
  Color vein{0.25, 0.25, 0.30};
  double frequency = 6;    // radians of the sine per unit of x (period 2π / frequency)
  double turbulence = 4;   // amplitude of the turbulence added to the sine's phase (≥ 0)
  double noise_scale = 2;  // frequency of the turbulence
  int octaves = 5;
  double sharpness = 3;  // exponent on the value (> 0)
};

class MarbleTexture final : public SolidTexture {
 public:
  explicit MarbleTexture(const MarbleParameters& parameters, const Transform& texture_from_object = {});
  Color at(const Vec3& p) const override;
  // value^sharpness above, in [0, 1]: the weight of `vein` at a texture-space point.
  double vein_weight(const Vec3& p) const;
  std::string_view type_name() const override { return "marble"; }
  const MarbleParameters& parameters() const { return parameters_; }

 private:
  MarbleParameters parameters_;
};

// A grey value from noise, for bump heights and for modulating material parameters:
//   fbm:        value = offset + amplitude · (0.5 + 0.5 · fractal_noise(scale · p, …))
//   turbulence: value = offset + amplitude · turbulence(scale · p, …)
// where … is (octaves, lacunarity, gain).
// fbm is centred on offset + amplitude/2 (the noise has mean 0); turbulence() is ≥ 0, so the
// turbulence mode never goes below offset for a positive amplitude. Neither is clamped: several octaves can
// take fbm a little outside [0, 1].
enum class NoiseMode { fbm, turbulence };

struct NoiseParameters {
  NoiseMode mode = NoiseMode::fbm;
  int octaves = 4;
  double lacunarity = 2;  // frequency ratio between octaves (> 0)
  double gain = 0.5;      // amplitude ratio between octaves (> 0)
  double amplitude = 1;
  double offset = 0;
  double scale = 1;  // frequency multiplier on p (> 0)
};

class NoiseTexture final : public SolidTexture {
 public:
  explicit NoiseTexture(const NoiseParameters& parameters, const Transform& texture_from_object = {});
  Color at(const Vec3& p) const override { return Color(value(p)); }
  double value(const Vec3& p) const;
  std::string_view type_name() const override { return "noise"; }
  const NoiseParameters& parameters() const { return parameters_; }

 private:
  NoiseParameters parameters_;
};

// Sine waves over (u, v) for bump mapping (000 §4.2.1: "a surface can look wavy if we perturb
// the normal with a sine function"), a grey value
//   value(u, v) = Σ_i amplitude_i · sin(2π (frequency_i.x · u + frequency_i.y · v) + phase_i).
// A wave's frequency is a vector in cycles per unit of (u, v): its direction is the direction of
// travel, so components may be negative, but not both zero.
struct Wave {
  double amplitude = 1;
  Vec2 frequency{1, 0};  // cycles per unit of u and of v
  double phase = 0;      // radians
};

class WavesTexture final : public Texture2D {
 public:
  WavesTexture(std::vector<Wave> waves, std::shared_ptr<const TextureMapping> mapping);
  Color lookup(const Vec2& uv) const override { return Color(value(uv)); }
  double value(const Vec2& uv) const;
  std::string_view type_name() const override { return "waves"; }
  const std::vector<Wave>& waves() const { return waves_; }

 private:
  std::vector<Wave> waves_;
};

}  // namespace candela
