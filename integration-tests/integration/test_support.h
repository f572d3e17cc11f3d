// Shared pieces of the integration tests: one validated device, scene loading, error metrics.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "analytic_reference.h"
#include "error_metrics.h"
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

/// The project's error metrics (samples/render/error_metrics.h); these check the sizes first.
using samples::ErrorStats;
using samples::describe;
ErrorStats compareRgb(const host::ImageRgba32f& measured, const std::vector<double>& referenceRgb,
                      const std::vector<unsigned char>* mask = nullptr);
ErrorStats compareRgb(const host::ImageRgba32f& measured, const host::ImageRgba32f& reference,
                      const std::vector<unsigned char>* mask = nullptr);

/// Turns the scene's camera so that the light (where its light comes from) appears at `ndc` (Vulkan
/// NDC, y down; beyond ±1 is off screen) of a `width`×`height` image, or, with `behind`, so that the
/// light is behind the camera and its mirrored epipole appears there. (The construction of
/// test_epipolar.cpp's placements, shared.)
host::Scene withEpipoleAt(host::Scene scene, glm::dvec2 ndc, bool behind, std::uint32_t width, std::uint32_t height);

/// Renders `frames` frames with the options' profile and reads the AOVs back.
samples::RenderResult renderWithAovs(const host::Scene& scene, samples::RenderOptions options);

/// renderWithAovs through one Tyndall context per process and context description (output size,
/// frames in flight, back-buffer format), created by the first render that needs it, as an engine
/// keeps one context while its scenes and settings change. The context compiles each pipeline on
/// first use (seconds per pipeline on lavapipe with validation, against well under a second for a
/// 320×180 frame), so a test that renders many times with one technique compiles its pipelines
/// once. A test about what a fresh context renders uses renderWithAovs. `stats.frameIndex` counts every frame of the shared context.
samples::RenderResult renderWithSharedContext(const host::Scene& scene, samples::RenderOptions options);

}  // namespace tyndall::test
