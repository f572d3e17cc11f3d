// The power of two the half-float L_in target holds L_in times (plugin/src/frame_setup.cpp,
// scatteringTargetScale): the reciprocal of the frame's typical L_in, E · σ_s · ℓ / 4π.
#include <cmath>

#include <gtest/gtest.h>

#include "frame_setup.h"

namespace tyndall {
namespace {

// A camera at the origin and a light 10 units in front of it.
LightSetup lightWith(LightType type, float radiance) {
  LightSetup l;
  l.light.type = type;
  l.constants.view_to_world = glm::mat4(1.0f);
  l.constants.light_position = glm::vec3(0.0f, 0.0f, -10.0f);
  l.constants.light_radiance = glm::vec3(radiance);
  return l;
}

// The lights in a medium of σ_s `scattering` and σ_t `extinction`, the far plane at 100.
FrameSetup frameOf(std::initializer_list<LightSetup> lights, float scattering = 0.01f, float extinction = 0.01f) {
  FrameSetup setup;
  setup.projection.nearDistance = 0.1;
  setup.projection.farDistance = 100.0;
  setup.scattering = glm::vec3(scattering);
  setup.extinction = glm::vec3(extinction);
  setup.lights = lights;
  return setup;
}

TEST(TargetScale, ThePowerOfTwoNearestTheTypicalInScatteringsReciprocal) {
  // Directional: 1 · 0.01 · min(1/0.01, far 100) / 4π = 0.0796 ≈ 2^-3.65: 2^4.
  EXPECT_EQ(scatteringTargetScale(frameOf({lightWith(LightType::Directional, 1.0f)})), 16.0f);
  // A dense medium: the path is 1/σ_t, 0.1 here: 1 · 1 · 0.1 / 4π ≈ 2^-6.97: 2^7.
  EXPECT_EQ(scatteringTargetScale(frameOf({lightWith(LightType::Directional, 1.0f)}, 1.0f, 10.0f)), 128.0f);
  // A spot light 10 units away: I/d² · σ_s · min(1/σ_t, d) / 4π = 0.01 · 100 · 0.01 · 10 / 4π ≈ 2^-6.97.
  EXPECT_EQ(scatteringTargetScale(frameOf({lightWith(LightType::Spot, 100.0f)})), 128.0f);
  // The lights' units: 2^20 times brighter, 2^-20 times the scale.
  EXPECT_EQ(scatteringTargetScale(frameOf({lightWith(LightType::Directional, std::ldexp(1.0f, 20))})),
            std::ldexp(16.0f, -20));
}

TEST(TargetScale, TheBrightestLightThatRunsDecides) {
  LightSetup off = lightWith(LightType::Directional, 1e6f);
  off.skipped = LightSkipped::OutsideView;
  const LightSetup dim = lightWith(LightType::Directional, 1.0f);
  const LightSetup bright = lightWith(LightType::Spot, 1e5f);  // 1000 · 2^-6.97 ≈ 2^3
  EXPECT_EQ(scatteringTargetScale(frameOf({off, dim})), 16.0f);
  EXPECT_EQ(scatteringTargetScale(frameOf({dim, bright})), 0.125f);
  // Nothing runs, or nothing scatters: L_in as it is.
  EXPECT_EQ(scatteringTargetScale(frameOf({off})), 1.0f);
  EXPECT_EQ(scatteringTargetScale(frameOf({dim}, 0.0f)), 1.0f);
  // Within float's range whatever the estimate.
  EXPECT_EQ(scatteringTargetScale(frameOf({lightWith(LightType::Directional, 1e38f)}, 1e30f, 1e-30f)),
            std::ldexp(1.0f, -64));
}

}  // namespace
}  // namespace tyndall
