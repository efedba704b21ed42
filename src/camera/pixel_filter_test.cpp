#include "camera/pixel_filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace candela {
namespace {

// Midpoint rule over the filter's square support.
double integral(const PixelFilter& filter, int steps = 400) {
  const double r = filter.radius(), h = 2 * r / steps;
  double sum = 0;
  for (int j = 0; j < steps; ++j)
    for (int i = 0; i < steps; ++i) sum += filter.evaluate(-r + (i + 0.5) * h, -r + (j + 0.5) * h);
  return sum * h * h;
}

TEST(PixelFilter, EachIntegratesToOneOverItsSupport) {
  for (const PixelFilterEntry& entry : pixel_filter_entries()) {
    for (const double radius : {0.5, 1.0, 2.0}) {
      const auto filter = create_pixel_filter(entry.name, {radius, 0});
      EXPECT_NEAR(integral(*filter), 1.0, 1e-4) << entry.name << " radius " << radius;
      EXPECT_EQ(filter->evaluate(radius * 1.01, 0), 0.0) << entry.name;
    }
  }
  const auto gaussian = create_pixel_filter("gaussian", {1.5, 0.3});
  EXPECT_NEAR(integral(*gaussian), 1.0, 1e-4);
}

TEST(PixelFilter, ShapesAreAsDocumented) {
  const auto box = create_pixel_filter("box", {});
  EXPECT_EQ(box->radius(), 0.5);
  EXPECT_DOUBLE_EQ(box->evaluate(0.1, -0.4), box->evaluate(0, 0));
  const auto gaussian = create_pixel_filter("gaussian", {1.5, 0.5});
  EXPECT_GT(gaussian->evaluate(0, 0), gaussian->evaluate(0.5, 0));
  EXPECT_NEAR(gaussian->evaluate_1d(0.5) / gaussian->evaluate_1d(0), std::exp(-0.5), 1e-12);
  // Mitchell-Netravali B = C = 1/3: negative lobes between radius/2 and radius.
  const auto mitchell = create_pixel_filter("mitchell", {2.0, 0});
  EXPECT_GT(mitchell->evaluate_1d(0), 0);
  EXPECT_LT(mitchell->evaluate_1d(1.5), 0);
  EXPECT_NEAR(mitchell->evaluate_1d(0), (6 - 2.0 / 3) / 6, 1e-12);
  // The tent: 1/r at the centre, half that halfway out.
  const auto triangle = create_pixel_filter("triangle", {});
  EXPECT_EQ(triangle->radius(), 1.0);
  EXPECT_DOUBLE_EQ(triangle->evaluate_1d(0), 1.0);
  EXPECT_DOUBLE_EQ(triangle->evaluate_1d(0.5), 0.5);
  // Lanczos: zero at every other pixel centre (the sinc's zeros), negative between 1 and 2.
  const auto lanczos = create_pixel_filter("lanczos", {});
  EXPECT_EQ(lanczos->radius(), 2.0);
  EXPECT_NEAR(lanczos->evaluate_1d(1.0), 0.0, 1e-12);
  EXPECT_LT(lanczos->evaluate_1d(1.5), 0);
  // Blackman-Harris: a0 + a1 + a2 + a3 = 1 at the centre, over 2 r a0; nearly zero at the edge.
  const auto blackman_harris = create_pixel_filter("blackman-harris", {2.0, 0});
  EXPECT_NEAR(blackman_harris->evaluate_1d(0), 1.0 / (2 * 2.0 * 0.35875), 1e-12);
  EXPECT_LT(blackman_harris->evaluate_1d(1.999), 1e-4);
}

TEST(PixelFilter, SupportIsHalfOpenSoTheHalfPixelBoxPartitionsTheImage) {
  const auto box = create_pixel_filter("box", {});
  EXPECT_GT(box->evaluate_1d(-0.5), 0);
  EXPECT_EQ(box->evaluate_1d(0.5), 0);  // a sample on a pixel border belongs to one pixel
}

TEST(PixelFilter, UnknownNamesAndBadParametersAreRejected) {
  EXPECT_EQ(find_pixel_filter("sinc"), nullptr);
  EXPECT_THROW(create_pixel_filter("sinc", {}), std::invalid_argument);
  EXPECT_THROW(create_pixel_filter("gaussian", {17, 0}), std::invalid_argument);
  EXPECT_THROW(create_pixel_filter("box", {-1, 0}), std::invalid_argument);
  EXPECT_THROW(create_pixel_filter("gaussian", {1, -0.5}), std::invalid_argument);
}

}  // namespace
}  // namespace candela
