// Environment maps: the radiance arriving from infinitely far away along a direction, seen by
// rays that leave the scene (background and reflections; 000 §4.1.3, SPEC §7). Created by name
// in scene/environment_registry.
#pragma once

#include <array>
#include <memory>
#include <string_view>

#include "math/vector.h"
#include "sampling/piecewise_constant.h"
#include "shading/texture_image.h"

namespace candela {

class Environment {
 public:
  virtual ~Environment() = default;
  // The radiance seen looking along the unit direction (away from the scene).
  virtual Color radiance(const Vec3& unit_direction) const = 0;
  virtual std::string_view type_name() const = 0;

  // Importance sampling for the path tracer's next-event estimation (SPEC §12): a unit
  // direction (away from the scene) with its solid-angle density, roughly proportional to the
  // radiance (a piecewise-constant distribution over the map's texels; uniform on the sphere for
  // a constant color). Sets radiance to radiance(direction). False when nothing can be sampled
  // (a black map).
  virtual bool sample(const Vec2& u, Vec3& direction, double& pdf, Color& radiance) const;
  // The density sample() draws the unit direction with (must match it exactly: MIS).
  virtual double pdf(const Vec3& unit_direction) const;
  // Call once after construction (Scene::prepare does): builds the sampling distribution.
  // Until then the image maps sample nothing (sample false, pdf 0).
  virtual void prepare_sampling() {}
};

// The same color in every direction.
class ConstantEnvironment final : public Environment {
 public:
  explicit ConstantEnvironment(const Color& color) : color_(color) {}
  Color radiance(const Vec3&) const override { return color_; }
  std::string_view type_name() const override { return "constant"; }
  const Color& color() const { return color_; }
  // Uniform on the sphere (1/(4π)); nothing for black.
  bool sample(const Vec2& u, Vec3& direction, double& pdf, Color& radiance) const override;
  double pdf(const Vec3& unit_direction) const override;

 private:
  Color color_;
};

// A cube of six square images around the scene (000 §4.1.3). Two layouts of the face images:
//
// CubeLayout::inside (the default): each face is what a 90° camera at the centre photographs
// looking along the face's axis, the image's top row up — with up = +y for the ±x and ±z
// faces, up = −z looking along +y and up = +z looking along −y (the camera's right is
// forward × up). Six renders of a scene from its centre with those cameras are a cube map that
// gives the same scene back (tested).
//
// CubeLayout::opengl: the OpenGL cube-map convention (OpenGL 4.6 core §8.13, Table 8.19), in
// which common sky-box sets ("posx.jpg" … "negz.jpg") are stored. It is the inside view
// mirrored left to right (OpenGL's cube maps are defined in a left-handed frame, which is why
// three.js flips x for them).
//
// The face is the one of the direction r's major axis (largest |component|; on a tie x before
// y before z, so a direction exactly on an edge or corner always picks the same face). With ma
// the major component, the OpenGL face coordinates are
//   face  sc    tc    ma
//   +x    −rz   −ry   rx
//   −x    +rz   −ry   rx
//   +y    +rx   +rz   ry
//   −y    +rx   −rz   ry
//   +z    +rx   −ry   rz
//   −z    −rx   −ry   rz
//   s = (sc/|ma| + 1)/2 (s = 0 the image's left column, 1 its right column),
//   t = (tc/|ma| + 1)/2 (t = 0 the image's TOP row as stored in the file, 1 its bottom row),
// and the inside layout reads column 1 − s instead of s.
//
// Lookups are bilinear, clamped to the edge texels within a face (no blending across faces).
enum class CubeLayout { inside, opengl };

class CubeMapEnvironment final : public Environment {
 public:
  enum Face { positive_x, negative_x, positive_y, negative_y, positive_z, negative_z };

  // faces in the order +x, −x, +y, −y, +z, −z. Throws std::invalid_argument when one is null,
  // not square, or not the size of the others.
  CubeMapEnvironment(std::array<std::shared_ptr<const TextureImage>, 6> faces, const Color& multiplier,
                     CubeLayout layout = CubeLayout::inside);

  // Black for a zero or non-finite direction.
  Color radiance(const Vec3& direction) const override;
  std::string_view type_name() const override { return "cube"; }

  struct FaceCoordinates {
    Face face;
    double s, t;  // as in the OpenGL table above: t = 0 at the image's top row
  };
  // The face and (s, t) a direction looks up (needs not be unit length, must be non-zero).
  static FaceCoordinates face_coordinates(const Vec3& direction);

  // Sampling (SPEC §12): a texel of the six faces with probability ∝ weight × its solid angle
  // (weight: the largest luminance among the texel and its 8 neighbours on the face, which the
  // bilinear lookup reaches, plus 1e-3 of the mean so the density is positive everywhere), then
  // a point uniform on the texel's face rectangle, pushed out to the sphere. The density is
  // exact: p(texel)/(texel face area) · |P|³ for P the point on the face plane at distance 1.
  bool sample(const Vec2& u, Vec3& direction, double& pdf, Color& radiance) const override;
  double pdf(const Vec3& unit_direction) const override;
  void prepare_sampling() override;

 private:
  std::array<std::shared_ptr<const TextureImage>, 6> faces_;
  Color multiplier_;
  CubeLayout layout_;
  // Columns along s, rows along (face + t) / 6 (t from the top row); empty until prepared.
  Distribution2D distribution_;
};

// A latitude/longitude panorama (the common "lat-long" or equirectangular HDRI): the image's
// width spans 360° of longitude, its height 180° of latitude. With up and forward made an
// orthonormal pair (forward loses its component along up) and right = forward × up (the right
// of a camera looking along forward with up up, as the perspective camera's X = G × U):
//   u = 0.5 + atan2(d·right, d·forward) / (2π)   (u = 0 the left column, 1 the right column)
//   v = acos(d·up) / π                            (v = 0 the TOP row, 1 the bottom row)
// so forward is the centre of the image, up its top row, −up its bottom row, right is at
// u = 0.75, left at u = 0.25, and behind (−forward) at the left/right edge, where the lookup
// blends the last and first columns. Bilinear, repeating in u, clamped in v.
class EquirectangularEnvironment final : public Environment {
 public:
  // Throws std::invalid_argument for a null image, a zero up or forward, or parallel ones.
  // type_name: "equirectangular", or the name of what was baked into the panorama ("cie_sky").
  EquirectangularEnvironment(std::shared_ptr<const TextureImage> image, const Vec3& up, const Vec3& forward,
                             const Color& multiplier, std::string_view type_name = "equirectangular");

  Color radiance(const Vec3& unit_direction) const override;
  std::string_view type_name() const override { return type_name_; }

  // (u, v) as in the comment above (v from the top row); for a unit direction.
  Vec2 panorama_coordinates(const Vec3& unit_direction) const;

  // Sampling (SPEC §12, pbrt's infinite area light): a piecewise-constant density over (u, v)
  // with one cell a texel, weight ∝ (the largest luminance among the texel and its neighbours,
  // plus 1e-3 of the mean) × sin θ at the row's centre; the solid-angle density is
  // p(u, v) / (2π² sin θ), exact.
  bool sample(const Vec2& u, Vec3& direction, double& pdf, Color& radiance) const override;
  double pdf(const Vec3& unit_direction) const override;
  void prepare_sampling() override;

 private:
  std::shared_ptr<const TextureImage> image_;
  Vec3 up_, forward_, right_;
  Color multiplier_;
  std::string_view type_name_;  // a literal
  // Columns along u, rows along v (from the top row); empty until prepared.
  Distribution2D distribution_;
};

}  // namespace candela
