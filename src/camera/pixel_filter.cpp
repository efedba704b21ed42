#include "camera/pixel_filter.h"

#include <array>
#include <cmath>
#include <stdexcept>

#include "util/registry.h"

namespace candela {

namespace {

class BoxFilter final : public PixelFilter {
 public:
  explicit BoxFilter(double radius) : PixelFilter(radius) {}
  std::string_view name() const override { return "box"; }
  double evaluate_1d(double d) const override { return std::fabs(d) <= radius_ ? 0.5 / radius_ : 0.0; }
};

// exp(-d²/2σ²) truncated to |d| <= radius and renormalised to integrate to 1 there.
class GaussianFilter final : public PixelFilter {
 public:
  GaussianFilter(double radius, double sigma)
      : PixelFilter(radius),
        sigma_(sigma),
        scale_(1.0 / (sigma * std::sqrt(2.0 * M_PI) * std::erf(radius / (sigma * std::sqrt(2.0))))) {}
  std::string_view name() const override { return "gaussian"; }
  double evaluate_1d(double d) const override {
    if (std::fabs(d) > radius_) return 0.0;
    return scale_ * std::exp(-d * d / (2 * sigma_ * sigma_));
  }

 private:
  double sigma_, scale_;
};

// Mitchell & Netravali (1988) with B = C = 1/3: the cubic k(x) on |x| < 2 integrates to 1; it
// is stretched to the radius: g(d) = (2 / radius) k(2 d / radius).
class MitchellFilter final : public PixelFilter {
 public:
  explicit MitchellFilter(double radius) : PixelFilter(radius) {}
  std::string_view name() const override { return "mitchell"; }
  double evaluate_1d(double d) const override {
    const double x = std::fabs(2 * d / radius_);
    constexpr double b = 1.0 / 3.0, c = 1.0 / 3.0;
    double k = 0;
    if (x < 1)
      k = ((12 - 9 * b - 6 * c) * x * x * x + (-18 + 12 * b + 6 * c) * x * x + (6 - 2 * b)) / 6;
    else if (x < 2)
      k = ((-b - 6 * c) * x * x * x + (6 * b + 30 * c) * x * x + (-12 * b - 48 * c) * x + (8 * b + 24 * c)) /
          6;
    return k * 2 / radius_;
  }
};

double checked_radius(const PixelFilterParameters& parameters, double fallback) {
  const double radius = parameters.radius == 0 ? fallback : parameters.radius;
  if (!(radius > 0) || !std::isfinite(radius)) throw std::invalid_argument("filter radius must be > 0");
  return radius;
}

const std::array kEntries{
    PixelFilterEntry{"box", 0.5,
                     [](const PixelFilterParameters& p) -> std::unique_ptr<PixelFilter> {
                       return std::make_unique<BoxFilter>(checked_radius(p, 0.5));
                     }},
    PixelFilterEntry{"gaussian", 1.5,
                     [](const PixelFilterParameters& p) -> std::unique_ptr<PixelFilter> {
                       const double radius = checked_radius(p, 1.5);
                       const double sigma = p.sigma == 0 ? radius / 3 : p.sigma;
                       if (!(sigma > 0) || !std::isfinite(sigma))
                         throw std::invalid_argument("filter sigma must be > 0");
                       return std::make_unique<GaussianFilter>(radius, sigma);
                     }},
    PixelFilterEntry{"mitchell", 2.0,
                     [](const PixelFilterParameters& p) -> std::unique_ptr<PixelFilter> {
                       return std::make_unique<MitchellFilter>(checked_radius(p, 2.0));
                     }},
};

}  // namespace

std::span<const PixelFilterEntry> pixel_filter_entries() {
  return kEntries;
}

const PixelFilterEntry* find_pixel_filter(std::string_view name) {
  return find_entry(pixel_filter_entries(), name);
}

std::string pixel_filter_names() {
  return entry_names(pixel_filter_entries());
}

std::unique_ptr<PixelFilter> create_pixel_filter(std::string_view name,
                                                 const PixelFilterParameters& parameters) {
  const PixelFilterEntry* entry = find_pixel_filter(name);
  if (!entry)
    throw std::invalid_argument("unknown filter \"" + std::string(name) +
                                "\" (expected one of: " + pixel_filter_names() + ")");
  return entry->create(parameters);
}

}  // namespace candela
