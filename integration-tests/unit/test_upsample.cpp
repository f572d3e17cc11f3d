// The composite's joint bilateral upsample (shaders/common/upsample.h, compiled as C++) and the
// reduced L_in target's extent (technique.h).
#include <gtest/gtest.h>

#include "common/upsample.h"
#include "technique.h"

namespace tyndall {
namespace {

using gpu::tyn_upsample_position;
using gpu::tyn_upsample_weights;

TEST(Upsample, TargetPixelsStandForOneOutputPixelOfTheirBlock) {
  // Half: target pixel p at output pixel 2p + 1; quarter: 4p + 2.
  EXPECT_EQ(tyn_upsample_position(glm::uvec2(1, 1), 2, 1), glm::vec2(0.0f));
  EXPECT_EQ(tyn_upsample_position(glm::uvec2(7, 3), 2, 1), glm::vec2(3.0f, 1.0f));
  EXPECT_EQ(tyn_upsample_position(glm::uvec2(8, 4), 2, 1), glm::vec2(3.5f, 1.5f));
  EXPECT_EQ(tyn_upsample_position(glm::uvec2(10, 3), 4, 2), glm::vec2(2.0f, 0.25f));
  // Full: the identity.
  EXPECT_EQ(tyn_upsample_position(glm::uvec2(5, 9), 1, 0), glm::vec2(5.0f, 9.0f));
}

TEST(Upsample, OnOneSurfaceTheWeightsAreBilinear) {
  const glm::vec4 w = tyn_upsample_weights(glm::vec2(0.25f, 0.5f), glm::vec4(10.0f), 10.0f);
  EXPECT_FLOAT_EQ(w.x, 0.75f * 0.5f);
  EXPECT_FLOAT_EQ(w.y, 0.25f * 0.5f);
  EXPECT_FLOAT_EQ(w.z, 0.75f * 0.5f);
  EXPECT_FLOAT_EQ(w.w, 0.25f * 0.5f);
  // On its own tap's pixel the upsample returns that tap.
  EXPECT_EQ(tyn_upsample_weights(glm::vec2(0.0f), glm::vec4(10.0f, 3.0f, 50.0f, 9.0f), 10.0f),
            glm::vec4(1.0f, 0.0f, 0.0f, 0.0f));
}

TEST(Upsample, TapsOnAnotherSurfaceDropOut) {
  // Two taps on a pillar 4 units away, two on the ground behind at 40 like the pixel: the pillar's
  // taps weigh nothing, the ground's split the weight in their bilinear proportion.
  const glm::vec4 w = tyn_upsample_weights(glm::vec2(0.5f, 0.25f), glm::vec4(4.0f, 40.0f, 4.0f, 40.0f), 40.0f);
  EXPECT_LT(w.x, 1e-12f);
  EXPECT_LT(w.z, 1e-12f);
  EXPECT_NEAR(w.y, 0.75f, 1e-6f);
  EXPECT_NEAR(w.w, 0.25f, 1e-6f);
  // Ground seen at a grazing angle: ray lengths a few percent apart still blend.
  const glm::vec4 grazing = tyn_upsample_weights(glm::vec2(0.5f), glm::vec4(40.0f, 40.0f, 42.0f, 42.0f), 41.0f);
  EXPECT_GT(grazing.z, 0.2f);
  EXPECT_NEAR(grazing.x + grazing.y + grazing.z + grazing.w, 1.0f, 1e-6f);
}

TEST(Upsample, WithNoTapOnItsSurfaceAPixelTakesTheNearestInDepth) {
  // A thin pole at 5 that no target pixel landed on: every tap is the ground at 40 or the sky at
  // 1000; the ground is nearer in depth.
  const glm::vec4 w = tyn_upsample_weights(glm::vec2(0.5f), glm::vec4(1000.0f, 40.0f, 1000.0f, 40.0f), 5.0f);
  EXPECT_EQ(w, glm::vec4(0.0f, 1.0f, 0.0f, 0.0f));
}

TEST(Upsample, TheTargetCoversEveryOutputPixel) {
  EXPECT_EQ(targetExtentFor({1920, 1080}, ScatteringResolution::Full).width, 1920u);
  const VkExtent2D half = targetExtentFor({1279, 719}, ScatteringResolution::Half);
  EXPECT_EQ(half.width, 640u);
  EXPECT_EQ(half.height, 360u);
  const VkExtent2D quarter = targetExtentFor({1, 5}, ScatteringResolution::Quarter);
  EXPECT_EQ(quarter.width, 1u);
  EXPECT_EQ(quarter.height, 2u);
}

}  // namespace
}  // namespace tyndall
