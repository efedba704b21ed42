// Pixel reconstruction filters (000 §5.8.1): box, Gaussian and Mitchell-Netravali, found by name
// in a registry. Each is separable, f(dx, dy) = g(dx) g(dy), over the square |dx|, |dy| <= radius,
// and integrates to 1 over it. The anti-aliasing modes that take several samples inside a pixel
// weight them by f(offset from the pixel centre), normalised over the pixel's own samples.
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
  // The weight of a sample (dx, dy) pixels from the pixel centre; 0 outside the support.
  double evaluate(double dx, double dy) const { return evaluate_1d(dx) * evaluate_1d(dy); }
  virtual double evaluate_1d(double d) const = 0;

 protected:
  explicit PixelFilter(double radius) : radius_(radius) {}
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
