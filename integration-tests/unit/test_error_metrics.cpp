// The error metric every accuracy figure uses (samples/render/error_metrics.h): relative RMSE,
// 99th percentile and maximum of |L_in − reference| over the mean |reference|, NaN/Inf counted
// apart, against values computed here by hand and by a full sort.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "error_metrics.h"

namespace {

using tyndall::host::ImageRgba32f;
using tyndall::samples::compareRgb;

ImageRgba32f image(std::uint32_t width, std::uint32_t height) {
  ImageRgba32f out;
  out.width = width;
  out.height = height;
  out.pixels.assign(std::size_t(width) * height * 4, 0.0f);
  return out;
}

TEST(ErrorMetrics, PercentileAndMaximumEqualAFullSort) {
  std::mt19937 rng(99);
  std::uniform_real_distribution<float> value(0.0f, 2.0f);
  ImageRgba32f measured = image(67, 31);
  std::vector<double> reference(std::size_t(67) * 31 * 3);
  std::vector<double> errors;
  double sumSquared = 0.0, sumReference = 0.0;
  for (std::size_t i = 0; i < std::size_t(67) * 31; ++i) {
    for (std::size_t c = 0; c < 3; ++c) {
      const float m = value(rng);
      const double r = value(rng);
      measured.pixels[i * 4 + c] = m;
      reference[i * 3 + c] = r;
      errors.push_back(std::abs(double(m) - r));
      sumSquared += (double(m) - r) * (double(m) - r);
      sumReference += r;
    }
  }
  std::sort(errors.begin(), errors.end());
  const double mean = sumReference / double(errors.size());
  const auto s = compareRgb(measured, reference);
  EXPECT_EQ(s.samples, errors.size());
  EXPECT_EQ(s.nonFinite, 0u);
  EXPECT_DOUBLE_EQ(s.meanReference, mean);
  EXPECT_NEAR(s.relativeRmse, std::sqrt(sumSquared / double(errors.size())) / mean, 1e-12);
  EXPECT_EQ(s.relativeP99, errors[std::size_t(0.99 * double(errors.size() - 1))] / mean);
  EXPECT_EQ(s.relativeMax, errors.back() / mean);
}

TEST(ErrorMetrics, NonFiniteValuesAreCountedApart) {
  ImageRgba32f measured = image(2, 1);
  const std::vector<double> reference = {1.0, 1.0, 1.0, 1.0, 1.0, 1.0};
  measured.pixels = {1.5f, 1.0f, 1.0f, 0.0f, std::numeric_limits<float>::quiet_NaN(), 1.0f,
                     std::numeric_limits<float>::infinity(), 0.0f};
  const auto s = compareRgb(measured, reference);
  EXPECT_EQ(s.nonFinite, 2u);
  EXPECT_EQ(s.samples, 4u);
  EXPECT_EQ(s.relativeMax, 0.5);
  EXPECT_EQ(s.relativeRmse, 0.25);  // sqrt(0.25 / 4) over a mean reference of 1
}

}  // namespace
