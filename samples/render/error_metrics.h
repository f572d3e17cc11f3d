// The project's accuracy metrics (README "Accuracy"), shared by the tests, tyndall-compare and the
// benchmark: relative RMSE = RMSE / mean |reference| over the RGB values; p99 and max of
// |error| / mean |reference|; the count of NaN/Inf values in the measured image (left out of the
// other metrics).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "tyndall_host/renderer.h"

namespace tyndall::samples {

struct ErrorStats {
  double relativeRmse = 0.0;
  double relativeP99 = 0.0;
  double relativeMax = 0.0;
  double meanReference = 0.0;
  std::size_t nonFinite = 0;
  std::size_t samples = 0;
};

/// RGB of a float RGBA image against a reference RGB image (3 doubles per pixel), optionally only
/// where mask[i] != 0. The sizes must match (the caller checks).
ErrorStats compareRgb(const host::ImageRgba32f& measured, const std::vector<double>& referenceRgb,
                      const std::vector<unsigned char>* mask = nullptr);
/// RGB of two float RGBA images of the same size.
ErrorStats compareRgb(const host::ImageRgba32f& measured, const host::ImageRgba32f& reference,
                      const std::vector<unsigned char>* mask = nullptr);

/// The median of the values (the mean of the middle two for an even count); 0 for none. Timings
/// are reported as medians over frames (tyndall-render's JSON, tyndall-bench).
double median(std::vector<double> values);

/// "relative RMSE …%, p99 …%, max …%, NaN/Inf n, mean |ref| … over n values".
std::string describe(const ErrorStats& stats);

}  // namespace tyndall::samples
