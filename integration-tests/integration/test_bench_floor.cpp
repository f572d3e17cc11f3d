// tyndall-bench's floor passes: the compute floor does the fragment floor's work (so their times
// compare like for like) and runs only where the back buffer can be a storage image.
#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

#include <gtest/gtest.h>

#include "floor_pass.h"
#include "test_support.h"

namespace tyndall::test {
namespace {

using samples::bench::FloorKind;
using samples::bench::FloorPass;

host::RenderSettings floorSettings() {
  host::RenderSettings settings;
  settings.width = 64;
  settings.height = 36;
  settings.shadowMapSize = 256;
  return settings;
}

// The back buffer after two frames with `kind`'s floor in the stack (none: the host alone).
host::ImageRgba32f renderFloor(const host::Scene& scene, const host::RenderSettings& settings,
                               std::optional<FloorKind> kind) {
  host::Device& device = validatedDevice();
  std::string error;
  std::unique_ptr<FloorPass> floor;
  if (kind) {
    floor = FloorPass::create(device, *kind, error);
    EXPECT_NE(floor, nullptr) << error;
  }
  std::unique_ptr<host::Renderer> renderer = host::Renderer::create(device, scene, settings, error);
  host::ImageRgba32f image;
  EXPECT_NE(renderer, nullptr) << error;
  if (!renderer || (kind && !floor)) return image;
  if (floor) renderer->addPostProcess(floor.get());
  for (int i = 0; i < 2; ++i) EXPECT_TRUE(renderer->renderFrame(error)) << error;
  renderer->waitIdle();
  EXPECT_TRUE(renderer->readBackBuffer(image, error)) << error;
  if (floor) {
    EXPECT_TRUE(floor->lastMilliseconds().has_value());
  }
  return image;
}

TEST(BenchFloorPass, TheComputeFloorWritesWhatTheFragmentFloorBlends) {
  const host::Scene scene = loadTestScene("pillars");
  const host::RenderSettings settings = floorSettings();
  const std::string unavailable = samples::bench::computeFloorUnavailable(validatedDevice(), settings);
  if (!unavailable.empty()) GTEST_SKIP() << unavailable;
  const host::ImageRgba32f none = renderFloor(scene, settings, std::nullopt);
  const host::ImageRgba32f fragment = renderFloor(scene, settings, FloorKind::Fragment);
  const host::ImageRgba32f compute = renderFloor(scene, settings, FloorKind::Compute);
  ASSERT_EQ(fragment.pixels.size(), none.pixels.size());
  ASSERT_EQ(compute.pixels.size(), none.pixels.size());
  double changed = 0.0, worst = 0.0;
  for (std::size_t i = 0; i < none.pixels.size(); ++i) {
    changed = std::max(changed, static_cast<double>(std::abs(fragment.pixels[i] - none.pixels[i])));
    // Half-float back buffer: the blender and the shader round differently, by about 2^-11 relative.
    const double scale = std::max(1.0, static_cast<double>(std::abs(fragment.pixels[i])));
    worst = std::max(worst, std::abs(static_cast<double>(compute.pixels[i]) - fragment.pixels[i]) / scale);
  }
  EXPECT_GT(changed, 1e-2);  // the fog did change the image, so the comparison means something
  EXPECT_LT(worst, 2e-3);
  expectNoValidationMessages();
}

// Without STORAGE usage the sweep does not measure the compute floor, and says why; a compute floor
// given such a back buffer refuses the frame instead of recording an invalid dispatch.
TEST(BenchFloorPass, TheComputeFloorNeedsAStorageBackBuffer) {
  host::RenderSettings settings = floorSettings();
  settings.storageBackBuffer = false;
  EXPECT_FALSE(samples::bench::computeFloorUnavailable(validatedDevice(), settings).empty());

  host::Device& device = validatedDevice();
  std::string error;
  std::unique_ptr<FloorPass> floor = FloorPass::create(device, FloorKind::Compute, error);
  ASSERT_NE(floor, nullptr) << error;
  std::unique_ptr<host::Renderer> renderer =
      host::Renderer::create(device, loadTestScene("pillars"), settings, error);
  ASSERT_NE(renderer, nullptr) << error;
  renderer->addPostProcess(floor.get());
  EXPECT_FALSE(renderer->renderFrame(error));
  EXPECT_NE(error.find("STORAGE"), std::string::npos) << error;
  renderer->waitIdle();
  expectNoValidationMessages();
}

}  // namespace
}  // namespace tyndall::test
