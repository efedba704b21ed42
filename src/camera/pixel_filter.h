// Pixel reconstruction filters (000 §5.8.1; pbrt-v4's filters): box, triangle, Gaussian,
// Mitchell-Netravali, Lanczos (windowed sinc) and Blackman-Harris, found by name in a registry.
// Each is separable, f(dx, dy) = g(dx) g(dy), over the square -radius <= dx, dy < radius, and
// integrates to 1 over it. sample_image (camera/antialiasing.h) splats every sample into each
// pixel whose centre lies within the radius with weight f(sample - centre) and divides each pixel
// by its weight sum (camera/splat_film.h), so a filter wider than a pixel spreads a sample across
// pixels: a real reconstruction filter, not a reweighting of the pixel's own samples.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <string_view>

namespace candela {

struct PixelFilterParameters {
  double radius = 0;  // in pixels; 0: the filter's default
  double sigma = 0;   // gaussian only; 0: the default (radius / 3)
};

class PixelFilter {
 public:
  virtual ~PixelFilter() = default;
  virtual std::string_view name() const = 0;
  double radius() const { return radius_; }
  // The weight of a sample (dx, dy) pixels from the pixel centre; 0 outside the support
  // [-radius, radius)² (half-open, so that the box of radius 0.5 gives each sample to one pixel).
  double evaluate(double dx, double dy) const { return evaluate_1d(dx) * evaluate_1d(dy); }
  double evaluate_1d(double d) const { return d >= -radius_ && d < radius_ ? profile(d) : 0.0; }

 protected:
  explicit PixelFilter(double radius) : radius_(radius) {}
  // g(d) for -radius <= d < radius.
  virtual double profile(double d) const = 0;
  double radius_;
};

struct PixelFilterEntry {
  const char* name;
  double default_radius;
  // Throws std::invalid_argument for parameters out of range.
  std::unique_ptr<PixelFilter> (*create)(const PixelFilterParameters& parameters);
};

std::span<const PixelFilterEntry> pixel_filter_entries();
const PixelFilterEntry* find_pixel_filter(std::string_view name);  // nullptr when unknown
std::string pixel_filter_names();
// Throws std::invalid_argument for an unknown name or bad parameters.
std::unique_ptr<PixelFilter> create_pixel_filter(std::string_view name,
                                                 const PixelFilterParameters& parameters);

}  // namespace candela
