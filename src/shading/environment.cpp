#include "shading/environment.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "math/constants.h"
#include "math/direction.h"

namespace candela {

namespace {
constexpr const char* kFaceNames[6] = {"+x", "-x", "+y", "-y", "+z", "-z"};

// The sampling weight of a color: its luminance (Rec. 709), negative channels ignored.
double sampling_weight(const Color& c) {
  return 0.2126 * std::max(0.0, c.r) + 0.7152 * std::max(0.0, c.g) + 0.0722 * std::max(0.0, c.b);
}

// Per texel of an image (row-major from the bottom row): the largest luminance of
// multiplier × texel over the texel and its 8 neighbours (which a bilinear lookup inside the
// texel reaches), columns wrapping when wrap_x, otherwise clamped; rows always clamped.
std::vector<double> neighbourhood_luminance(const TextureImage& image, const Color& multiplier, bool wrap_x) {
  const int w = image.width(), h = image.height();
  std::vector<double> own(std::size_t(w) * std::size_t(h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) own[std::size_t(y) * w + x] = sampling_weight(multiplier * image.texel(x, y));
  std::vector<double> result(own.size());
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      double largest = 0;
      for (int dy = -1; dy <= 1; ++dy) {
        const int yy = std::clamp(y + dy, 0, h - 1);
        for (int dx = -1; dx <= 1; ++dx) {
          int xx = x + dx;
          xx = wrap_x ? (xx + w) % w : std::clamp(xx, 0, w - 1);
          largest = std::max(largest, own[std::size_t(yy) * w + xx]);
        }
      }
      result[std::size_t(y) * w + x] = largest;
    }
  }
  return result;
}

// The solid angle of the rectangle [a0, a1] × [b0, b1] on the plane at distance 1 from the eye.
double rectangle_solid_angle(double a0, double a1, double b0, double b1) {
  const auto corner = [](double a, double b) { return std::atan2(a * b, std::sqrt(a * a + b * b + 1)); };
  return corner(a1, b1) - corner(a0, b1) - corner(a1, b0) + corner(a0, b0);
}

// A unit direction uniform on the sphere.
Vec3 uniform_sphere(const Vec2& u) {
  const double z = 1 - 2 * u.x;
  const double r = 2 * std::sqrt(std::max(0.0, u.x * (1 - u.x)));
  const double phi = 2 * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// How much of the mean weight every texel gets at least (support where bilinear blur reaches
// and a little beyond; the density stays exact for what it claims).
constexpr double kWeightFloor = 1e-3;
}  // namespace

bool Environment::sample(const Vec2&, Vec3&, double&, Color&) const {
  return false;
}

double Environment::pdf(const Vec3&) const {
  return 0;
}

bool ConstantEnvironment::sample(const Vec2& u, Vec3& direction, double& density, Color& radiance) const {
  if (color_.is_black()) return false;
  direction = uniform_sphere(u);
  density = 1 / (4 * kPi);
  radiance = color_;
  return true;
}

double ConstantEnvironment::pdf(const Vec3&) const {
  return color_.is_black() ? 0 : 1 / (4 * kPi);
}

CubeMapEnvironment::CubeMapEnvironment(std::array<std::shared_ptr<const TextureImage>, 6> faces,
                                       const Color& multiplier, CubeLayout layout)
    : faces_(std::move(faces)), multiplier_(multiplier), layout_(layout) {
  for (int face = 0; face < 6; ++face)
    if (!faces_[face])
      throw std::invalid_argument(std::string("cube map face ") + kFaceNames[face] + " is missing");
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

void CubeMapEnvironment::prepare_sampling() {
  const int n = faces_[0]->width();
  std::vector<double> weights(std::size_t(6) * n * n);
  double total = 0;
  std::array<std::vector<double>, 6> face_weights;
  for (int face = 0; face < 6; ++face) {
    face_weights[face] = neighbourhood_luminance(*faces_[face], multiplier_, /*wrap_x=*/false);
    for (const double w : face_weights[face]) total += w;
  }
  if (!(total > 0) || !std::isfinite(total)) {
    distribution_ = Distribution2D();
    return;
  }
  const double floor = kWeightFloor * total / static_cast<double>(weights.size());
  for (int face = 0; face < 6; ++face) {
    for (int j = 0; j < n; ++j) {    // t cell, from the top row
      for (int i = 0; i < n; ++i) {  // s cell
        const int column = layout_ == CubeLayout::inside ? n - 1 - i : i;
        const int row = n - 1 - j;  // TextureImage rows count from the bottom
        const double a0 = 2.0 * i / n - 1, a1 = 2.0 * (i + 1) / n - 1;
        const double b0 = 2.0 * j / n - 1, b1 = 2.0 * (j + 1) / n - 1;
        weights[(std::size_t(face) * n + j) * n + i] =
            (face_weights[face][std::size_t(row) * n + column] + floor) *
            rectangle_solid_angle(a0, a1, b0, b1);
      }
    }
  }
  distribution_ = Distribution2D(weights, std::size_t(n), std::size_t(6) * n);
}

bool CubeMapEnvironment::sample(const Vec2& u, Vec3& direction, double& density, Color& radiance) const {
  Vec2 point;
  double cell_density = 0;
  if (!distribution_.sample_continuous(u, point, cell_density)) return false;
  const int face = std::min(5, static_cast<int>(point.y * 6));
  const double s = point.x, t = std::clamp(point.y * 6 - face, 0.0, 1.0);
  const double sc = 2 * s - 1, tc = 2 * t - 1;
  // The inverse of face_coordinates (OpenGL 4.6 Table 8.19) with |ma| = 1.
  Vec3 r;
  switch (face) {
    case positive_x:
      r = {1, -tc, -sc};
      break;
    case negative_x:
      r = {-1, -tc, sc};
      break;
    case positive_y:
      r = {sc, 1, tc};
      break;
    case negative_y:
      r = {sc, -1, -tc};
      break;
    case positive_z:
      r = {sc, -tc, 1};
      break;
    default:
      r = {-sc, -tc, -1};
      break;
  }
  direction = normalize(r);
  // The density of the direction as pdf() computes it (the same bits; a direction rounding
  // onto a neighbouring face or cell gets that cell's density, as it would when traced).
  density = pdf(direction);
  radiance = this->radiance(direction);
  return density > 0;
}

double CubeMapEnvironment::pdf(const Vec3& direction) const {
  if (!distribution_.can_sample()) return 0;
  const double major = std::max({std::fabs(direction.x), std::fabs(direction.y), std::fabs(direction.z)});
  if (!(major > 0) || !is_finite(direction)) return 0;
  const FaceCoordinates at = face_coordinates(direction);
  const double cell_density = distribution_.pdf({at.s, (static_cast<int>(at.face) + at.t) / 6});
  // (x, y) = (s, (face + t)/6) and (a, b) = (2s − 1, 2t − 1) on the face plane at distance 1:
  // p(a, b) = p(x, y)/24, and dω = da db / |(a, b, 1)|³.
  const double a = 2 * at.s - 1, b = 2 * at.t - 1;
  const double distance_squared = 1 + a * a + b * b;
  return cell_density / 24 * distance_squared * std::sqrt(distance_squared);
}

EquirectangularEnvironment::EquirectangularEnvironment(std::shared_ptr<const TextureImage> image,
                                                       const Vec3& up, const Vec3& forward,
                                                       const Color& multiplier, std::string_view type_name)
    : image_(std::move(image)), multiplier_(multiplier), type_name_(type_name) {
  if (!image_) throw std::invalid_argument("equirectangular environment needs an image");
  const std::optional<Vec3> up_unit = direction_of(up);
  if (!up_unit) throw std::invalid_argument("up must be a non-zero vector");
  if (!(length(forward) > 0) || !is_finite(forward))
    throw std::invalid_argument("forward must be a non-zero vector");
  up_ = *up_unit;
  // Gram-Schmidt: forward keeps only its part orthogonal to up.
  const Vec3 across = forward - dot(forward, up_) * up_;
  if (!(length(across) > 1e-9 * length(forward)))
    throw std::invalid_argument("forward must not be parallel to up");
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

void EquirectangularEnvironment::prepare_sampling() {
  const int w = image_->width(), h = image_->height();
  std::vector<double> texel_weights = neighbourhood_luminance(*image_, multiplier_, /*wrap_x=*/true);
  double total = 0;
  for (const double weight : texel_weights) total += weight;
  if (!(total > 0) || !std::isfinite(total)) {
    distribution_ = Distribution2D();
    return;
  }
  const double floor = kWeightFloor * total / static_cast<double>(texel_weights.size());
  std::vector<double> weights(std::size_t(w) * h);
  for (int j = 0; j < h; ++j) {  // v cell, from the top row
    const double sin_theta = std::sin(kPi * (j + 0.5) / h);
    const int row = h - 1 - j;
    for (int i = 0; i < w; ++i)
      weights[std::size_t(j) * w + i] = (texel_weights[std::size_t(row) * w + i] + floor) * sin_theta;
  }
  distribution_ = Distribution2D(weights, std::size_t(w), std::size_t(h));
}

bool EquirectangularEnvironment::sample(const Vec2& u, Vec3& direction, double& density,
                                        Color& radiance) const {
  Vec2 point;
  double cell_density = 0;
  if (!distribution_.sample_continuous(u, point, cell_density)) return false;
  const double theta = kPi * point.y, phi = 2 * kPi * (point.x - 0.5);
  const double sin_theta = std::sin(theta);
  direction = normalize(forward_ * (sin_theta * std::cos(phi)) + right_ * (sin_theta * std::sin(phi)) +
                        up_ * std::cos(theta));
  density = pdf(direction);
  radiance = this->radiance(direction);
  return density > 0;
}

double EquirectangularEnvironment::pdf(const Vec3& unit_direction) const {
  if (!distribution_.can_sample()) return 0;
  const double sin_theta = length(unit_direction - up_ * dot(unit_direction, up_));
  if (!(sin_theta > 0)) return 0;
  // dω = sin θ dθ dφ = 2π² sin θ du dv.
  return distribution_.pdf(panorama_coordinates(unit_direction)) / (2 * kPi * kPi * sin_theta);
}

}  // namespace candela
