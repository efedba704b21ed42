#include "shading/environment.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "math/constants.h"

namespace candela {

namespace {
constexpr const char* kFaceNames[6] = {"+x", "-x", "+y", "-y", "+z", "-z"};
}  // namespace

CubeMapEnvironment::CubeMapEnvironment(std::array<std::shared_ptr<const TextureImage>, 6> faces,
                                       const Color& multiplier, CubeLayout layout)
    : faces_(std::move(faces)), multiplier_(multiplier), layout_(layout) {
  for (int face = 0; face < 6; ++face)
    if (!faces_[face]) throw std::invalid_argument(std::string("cube map face ") + kFaceNames[face] + " is missing");
  const int size = faces_[0]->width();
  for (int face = 0; face < 6; ++face) {
    const TextureImage& image = *faces_[face];
    const std::string dimensions = std::to_string(image.width()) + "×" + std::to_string(image.height());
    if (image.width() != image.height())
      throw std::invalid_argument(std::string("cube map face ") + kFaceNames[face] + " is " + dimensions +
                                  "; faces must be square");
    if (image.width() != size)
      throw std::invalid_argument(std::string("cube map face ") + kFaceNames[face] + " is " + dimensions +
                                  " but +x is " + std::to_string(size) + "×" + std::to_string(size) +
                                  "; all six faces must be the same size");
  }
}

CubeMapEnvironment::FaceCoordinates CubeMapEnvironment::face_coordinates(const Vec3& r) {
  const double ax = std::fabs(r.x), ay = std::fabs(r.y), az = std::fabs(r.z);
  Face face;
  double sc, tc, ma;
  // OpenGL 4.6 Table 8.19; ties go to x, then y, so every direction has exactly one face.
  if (ax >= ay && ax >= az) {
    face = r.x >= 0 ? positive_x : negative_x;
    sc = r.x >= 0 ? -r.z : r.z;
    tc = -r.y;
    ma = ax;
  } else if (ay >= az) {
    face = r.y >= 0 ? positive_y : negative_y;
    sc = r.x;
    tc = r.y >= 0 ? r.z : -r.z;
    ma = ay;
  } else {
    face = r.z >= 0 ? positive_z : negative_z;
    sc = r.z >= 0 ? r.x : -r.x;
    tc = -r.y;
    ma = az;
  }
  return {face, (sc / ma + 1) / 2, (tc / ma + 1) / 2};
}

Color CubeMapEnvironment::radiance(const Vec3& direction) const {
  const double major = std::max({std::fabs(direction.x), std::fabs(direction.y), std::fabs(direction.z)});
  if (!(major > 0) || !is_finite(direction)) return Color(0);
  const FaceCoordinates at = face_coordinates(direction);
  // TextureImage's v runs up from the bottom row; the cube map's t runs down from the top row.
  const double column = layout_ == CubeLayout::inside ? 1 - at.s : at.s;
  return multiplier_ * faces_[at.face]->bilinear({column, 1 - at.t}, WrapMode::clamp);
}

EquirectangularEnvironment::EquirectangularEnvironment(std::shared_ptr<const TextureImage> image, const Vec3& up,
                                                       const Vec3& forward, const Color& multiplier)
    : image_(std::move(image)), multiplier_(multiplier) {
  if (!image_) throw std::invalid_argument("equirectangular environment needs an image");
  if (!(length(up) > 0) || !is_finite(up)) throw std::invalid_argument("up must be a non-zero vector");
  if (!(length(forward) > 0) || !is_finite(forward)) throw std::invalid_argument("forward must be a non-zero vector");
  up_ = normalize(up);
  // Gram-Schmidt: forward keeps only its part orthogonal to up.
  const Vec3 across = forward - dot(forward, up_) * up_;
  if (!(length(across) > 1e-9 * length(forward))) throw std::invalid_argument("forward must not be parallel to up");
  forward_ = normalize(across);
  right_ = cross(forward_, up_);
}

Vec2 EquirectangularEnvironment::panorama_coordinates(const Vec3& d) const {
  const double u = 0.5 + std::atan2(dot(d, right_), dot(d, forward_)) / (2 * kPi);
  const double v = std::acos(std::clamp(dot(d, up_), -1.0, 1.0)) / kPi;
  return {u, v};
}

Color EquirectangularEnvironment::radiance(const Vec3& unit_direction) const {
  const Vec2 uv = panorama_coordinates(unit_direction);
  // v counts from the top row; TextureImage's from the bottom row.
  return multiplier_ * image_->bilinear({uv.x, 1 - uv.y}, WrapMode::repeat, WrapMode::clamp);
}

}  // namespace candela
