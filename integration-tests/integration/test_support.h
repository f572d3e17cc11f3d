// Shared pieces of the integration tests: one validated device, scene loading, error metrics.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "analytic_reference.h"
#include "render_job.h"
#include "tyndall_host/renderer.h"
#include "tyndall_host/scene.h"

namespace tyndall::test {

/// The device every integration test uses: lavapipe (TYNDALL_DEVICE) with the Khronos validation
/// layer and synchronization validation. Created once per process.
host::Device& validatedDevice();

/// Fails the current test if the device reported any validation message since the last call.
void expectNoValidationMessages();

host::Scene loadTestScene(const std::string& name);  ///< samples/scenes/<name>.json

/// The error metrics of the project (README "Accuracy"): relative RMSE = RMSE / mean |reference|;
/// p99 and max of |error| / mean |reference|; count of NaN/Inf in the measured image.
struct ErrorStats {
  double relativeRmse = 0.0;
  double relativeP99 = 0.0;
  double relativeMax = 0.0;
  double meanReference = 0.0;
  std::size_t nonFinite = 0;
  std::size_t samples = 0;
};
/// RGB of a float RGBA image against a reference RGB image, optionally only where mask[i] != 0.
ErrorStats compareRgb(const host::ImageRgba32f& measured, const std::vector<double>& referenceRgb,
                      const std::vector<unsigned char>* mask = nullptr);
ErrorStats compareRgb(const host::ImageRgba32f& measured, const host::ImageRgba32f& reference,
                      const std::vector<unsigned char>* mask = nullptr);
std::string describe(const ErrorStats& stats);

/// Renders `frames` frames with the options' profile and reads the AOVs back.
samples::RenderResult renderWithAovs(const host::Scene& scene, samples::RenderOptions options);

}  // namespace tyndall::test
