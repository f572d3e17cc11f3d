#include "error_metrics.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <sstream>

namespace tyndall::samples {

namespace {

ErrorStats compare(const host::ImageRgba32f& measured, auto reference, std::size_t pixelCount,
                   const std::vector<unsigned char>* mask) {
  ErrorStats stats;
  std::vector<double> errors;
  double sumSquared = 0.0;
  double sumReference = 0.0;
  for (std::size_t i = 0; i < pixelCount; ++i) {
    if (mask != nullptr && (*mask)[i] == 0) continue;
    for (std::size_t c = 0; c < 3; ++c) {
      const double m = measured.pixels[i * 4 + c];
      const double r = reference(i, c);
      if (!std::isfinite(m)) {
        ++stats.nonFinite;
        continue;
      }
      const double e = m - r;
      sumSquared += e * e;
      sumReference += std::abs(r);
      errors.push_back(std::abs(e));
    }
  }
  stats.samples = errors.size();
  if (errors.empty()) return stats;
  stats.meanReference = sumReference / static_cast<double>(errors.size());
  const double scale = stats.meanReference > 0.0 ? stats.meanReference : 1.0;
  stats.relativeRmse = std::sqrt(sumSquared / static_cast<double>(errors.size())) / scale;
  // The same order statistic a full sort would give, in linear time (a 4096×2160 image has 26M).
  const auto p99 = errors.begin() + static_cast<std::ptrdiff_t>(0.99 * static_cast<double>(errors.size() - 1));
  std::nth_element(errors.begin(), p99, errors.end());
  stats.relativeP99 = *p99 / scale;
  stats.relativeMax = *std::max_element(p99, errors.end()) / scale;
  return stats;
}

}  // namespace

ErrorStats compareRgb(const host::ImageRgba32f& measured, const std::vector<double>& referenceRgb,
                      const std::vector<unsigned char>* mask) {
  const std::size_t pixels = static_cast<std::size_t>(measured.width) * measured.height;
  return compare(measured, [&](std::size_t i, std::size_t c) { return referenceRgb[i * 3 + c]; }, pixels, mask);
}

ErrorStats compareRgb(const host::ImageRgba32f& measured, const host::ImageRgba32f& reference,
                      const std::vector<unsigned char>* mask) {
  const std::size_t pixels = static_cast<std::size_t>(measured.width) * measured.height;
  return compare(
      measured, [&](std::size_t i, std::size_t c) { return static_cast<double>(reference.pixels[i * 4 + c]); },
      pixels, mask);
}

std::string describe(const ErrorStats& s) {
  std::ostringstream out;
  out << "relative RMSE " << s.relativeRmse * 100.0 << "%, p99 " << s.relativeP99 * 100.0 << "%, max "
      << s.relativeMax * 100.0 << "%, NaN/Inf " << s.nonFinite << ", mean |ref| " << s.meanReference << " over "
      << s.samples << " values";
  return out.str();
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace tyndall::samples
