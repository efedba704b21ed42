// Vectors, points and colors in double precision (SPEC "one floating-point type").
#pragma once

#include <algorithm>
#include <cmath>
#include <ostream>

namespace candela {

struct Vec2 {
  double x = 0, y = 0;
};

struct Vec3 {
  double x = 0, y = 0, z = 0;

  constexpr Vec3() = default;
  constexpr Vec3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}

  constexpr double operator[](int axis) const { return axis == 0 ? x : (axis == 1 ? y : z); }
  double& operator[](int axis) { return axis == 0 ? x : (axis == 1 ? y : z); }

  constexpr Vec3 operator+(const Vec3& o) const { return {x + o.x, y + o.y, z + o.z}; }
  constexpr Vec3 operator-(const Vec3& o) const { return {x - o.x, y - o.y, z - o.z}; }
  constexpr Vec3 operator-() const { return {-x, -y, -z}; }
  constexpr Vec3 operator*(double s) const { return {x * s, y * s, z * s}; }
  constexpr Vec3 operator/(double s) const { return {x / s, y / s, z / s}; }
  Vec3& operator+=(const Vec3& o) {
    x += o.x;
    y += o.y;
    z += o.z;
    return *this;
  }
  Vec3& operator-=(const Vec3& o) {
    x -= o.x;
    y -= o.y;
    z -= o.z;
    return *this;
  }
  Vec3& operator*=(double s) {
    x *= s;
    y *= s;
    z *= s;
    return *this;
  }
  constexpr bool operator==(const Vec3& o) const { return x == o.x && y == o.y && z == o.z; }
};

constexpr Vec3 operator*(double s, const Vec3& v) {
  return v * s;
}
constexpr double dot(const Vec3& a, const Vec3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
constexpr Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length_squared(const Vec3& v) {
  return dot(v, v);
}
inline double length(const Vec3& v) {
  return std::sqrt(dot(v, v));
}
inline Vec3 normalize(const Vec3& v) {
  return v / length(v);
}
inline Vec3 abs(const Vec3& v) {
  return {std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)};
}
inline Vec3 min(const Vec3& a, const Vec3& b) {
  return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}
inline Vec3 max(const Vec3& a, const Vec3& b) {
  return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}
inline int max_dimension(const Vec3& v) {
  return (v.x > v.y) ? (v.x > v.z ? 0 : 2) : (v.y > v.z ? 1 : 2);
}
inline bool is_finite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
// Flips n to lie in the hemisphere of v.
inline Vec3 face_forward(const Vec3& n, const Vec3& v) {
  return dot(n, v) < 0 ? -n : n;
}

// Builds two unit vectors orthogonal to the unit vector n (Duff et al. 2017).
inline void orthonormal_basis(const Vec3& n, Vec3& b1, Vec3& b2) {
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z);
  const double b = n.x * n.y * a;
  b1 = {1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x};
  b2 = {b, sign + n.y * n.y * a, -n.y};
}

inline std::ostream& operator<<(std::ostream& os, const Vec3& v) {
  return os << '(' << v.x << ", " << v.y << ", " << v.z << ')';
}

// Linear RGB; the unit is whatever the scene uses (SPEC §3: colors are linear RGB).
struct Color {
  double r = 0, g = 0, b = 0;

  constexpr Color() = default;
  constexpr explicit Color(double v) : r(v), g(v), b(v) {}
  constexpr Color(double r_, double g_, double b_) : r(r_), g(g_), b(b_) {}

  constexpr double operator[](int c) const { return c == 0 ? r : (c == 1 ? g : b); }
  double& operator[](int c) { return c == 0 ? r : (c == 1 ? g : b); }
  constexpr Color operator+(const Color& o) const { return {r + o.r, g + o.g, b + o.b}; }
  constexpr Color operator-(const Color& o) const { return {r - o.r, g - o.g, b - o.b}; }
  constexpr Color operator*(const Color& o) const { return {r * o.r, g * o.g, b * o.b}; }
  constexpr Color operator*(double s) const { return {r * s, g * s, b * s}; }
  constexpr Color operator/(double s) const { return {r / s, g / s, b / s}; }
  Color& operator+=(const Color& o) {
    r += o.r;
    g += o.g;
    b += o.b;
    return *this;
  }
  Color& operator*=(const Color& o) {
    r *= o.r;
    g *= o.g;
    b *= o.b;
    return *this;
  }
  Color& operator*=(double s) {
    r *= s;
    g *= s;
    b *= s;
    return *this;
  }
  constexpr bool operator==(const Color& o) const { return r == o.r && g == o.g && b == o.b; }

  double max_component() const { return std::max({r, g, b}); }
  double average() const { return (r + g + b) / 3.0; }
  bool is_black() const { return r == 0 && g == 0 && b == 0; }
};

constexpr Color operator*(double s, const Color& c) {
  return c * s;
}

inline Color min(const Color& a, const Color& b) {
  return {std::min(a.r, b.r), std::min(a.g, b.g), std::min(a.b, b.b)};
}
inline Color max(const Color& a, const Color& b) {
  return {std::max(a.r, b.r), std::max(a.g, b.g), std::max(a.b, b.b)};
}

// Rec. 709 / sRGB luminance Y of a linear color.
constexpr double luminance(const Color& c) {
  return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
}

inline std::ostream& operator<<(std::ostream& os, const Color& c) {
  return os << '[' << c.r << ", " << c.g << ", " << c.b << ']';
}

}  // namespace candela
