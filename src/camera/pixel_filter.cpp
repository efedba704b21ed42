#include "camera/pixel_filter.h"

#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "util/registry.h"

namespace candela {

namespace {

constexpr double kPi = std::numbers::pi;

class BoxFilter final : public PixelFilter {
 public:
  explicit BoxFilter(double radius) : PixelFilter(radius) {}
  std::string_view name() const override { return "box"; }

 private:
  double profile(double) const override { return 0.5 / radius_; }
};

// The tent (1 - |d| / radius) / radius: linear interpolation between pixel centres at radius 1.
class TriangleFilter final : public PixelFilter {
 public:
  explicit TriangleFilter(double radius) : PixelFilter(radius) {}
  std::string_view name() const override { return "triangle"; }

 private:
  double profile(double d) const override { return (1 - std::fabs(d) / radius_) / radius_; }
};

// exp(-d²/2σ²) truncated to |d| <= radius and renormalised to integrate to 1 there (000 §5.8.1:
// "weights the samples by their distance from the pixel centre").
class GaussianFilter final : public PixelFilter {
 public:
  GaussianFilter(double radius, double sigma)
      : PixelFilter(radius),
        sigma_(sigma),
        scale_(1.0 / (sigma * std::sqrt(2.0 * kPi) * std::erf(radius / (sigma * std::sqrt(2.0))))) {}
  std::string_view name() const override { return "gaussian"; }

 private:
  double profile(double d) const override { return scale_ * std::exp(-d * d / (2 * sigma_ * sigma_)); }
  double sigma_, scale_;
};

// Mitchell & Netravali (1988) with B = C = 1/3: the cubic k(x) on |x| < 2 integrates to 1; it
// is stretched to the radius: g(d) = (2 / radius) k(2 d / radius).
class MitchellFilter final : public PixelFilter {
 public:
  explicit MitchellFilter(double radius) : PixelFilter(radius) {}
  std::string_view name() const override { return "mitchell"; }

 private:
  double profile(double d) const override {
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

double sinc(double x) {
  return std::fabs(x) < 1e-8 ? 1.0 : std::sin(kPi * x) / (kPi * x);
}

// Lanczos: the sinc of the ideal low-pass filter (zeros at every other pixel centre) windowed by
// the wider sinc(d / radius) (pbrt-v4's LanczosSincFilter with tau = radius). Its integral has no
// closed form: Simpson's rule once, here, makes it integrate to 1.
class LanczosFilter final : public PixelFilter {
 public:
  explicit LanczosFilter(double radius) : PixelFilter(radius) {
    constexpr int kIntervals = 4096;  // even
    const double h = 2 * radius / kIntervals;
    double sum = windowed_sinc(-radius) + windowed_sinc(radius);
    for (int i = 1; i < kIntervals; ++i) sum += (i % 2 ? 4 : 2) * windowed_sinc(-radius + i * h);
    scale_ = 1 / (sum * h / 3);
  }
  std::string_view name() const override { return "lanczos"; }

 private:
  double windowed_sinc(double d) const { return sinc(d) * sinc(d / radius_); }
  double profile(double d) const override { return scale_ * windowed_sinc(d); }
  double scale_ = 1;
};

// The four-term Blackman-Harris window (Harris 1978: a0..a3 = 0.35875, 0.48829, 0.14128,
// 0.01168) centred on the pixel: g(d) = Σ a_k cos(kπ d / radius), whose integral over
// [-radius, radius] is 2 radius a0 (the cosines span whole periods).
class BlackmanHarrisFilter final : public PixelFilter {
 public:
  explicit BlackmanHarrisFilter(double radius) : PixelFilter(radius) {}
  std::string_view name() const override { return "blackman-harris"; }

 private:
  static constexpr double a0 = 0.35875, a1 = 0.48829, a2 = 0.14128, a3 = 0.01168;
  double profile(double d) const override {
    const double t = kPi * d / radius_;
    return (a0 + a1 * std::cos(t) + a2 * std::cos(2 * t) + a3 * std::cos(3 * t)) / (2 * radius_ * a0);
  }
};

double checked_radius(const PixelFilterParameters& parameters, double fallback) {
  const double radius = parameters.radius == 0 ? fallback : parameters.radius;
  if (!(radius > 0) || !std::isfinite(radius)) throw std::invalid_argument("filter radius must be > 0");
  // Each sample reaches the pixels within the radius: past 16 a sample would touch over a
  // thousand pixels.
  if (radius > 16) throw std::invalid_argument("filter radius must be at most 16 pixels");
  return radius;
}

const std::array kFilterEntries{
    PixelFilterEntry{"box", 0.5,
                     [](const PixelFilterParameters& p) -> std::unique_ptr<PixelFilter> {
                       return std::make_unique<BoxFilter>(checked_radius(p, 0.5));
                     }},
    PixelFilterEntry{"triangle", 1.0,
                     [](const PixelFilterParameters& p) -> std::unique_ptr<PixelFilter> {
                       return std::make_unique<TriangleFilter>(checked_radius(p, 1.0));
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
    PixelFilterEntry{"lanczos", 2.0,
                     [](const PixelFilterParameters& p) -> std::unique_ptr<PixelFilter> {
                       return std::make_unique<LanczosFilter>(checked_radius(p, 2.0));
                     }},
    PixelFilterEntry{"blackman-harris", 1.5,
                     [](const PixelFilterParameters& p) -> std::unique_ptr<PixelFilter> {
                       return std::make_unique<BlackmanHarrisFilter>(checked_radius(p, 1.5));
                     }},
};

}  // namespace

std::span<const PixelFilterEntry> pixel_filter_entries() {
  return kFilterEntries;
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
