// planPrefilteredFrame: the prefiltered technique's per-frame decisions, without a device.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "prefiltered/prefiltered_plan.h"
#include "vulkan_projection.h"

namespace tyndall {
namespace {

constexpr VkExtent2D kExtent{320, 180};

// A camera at (0, 2, 10) looking at the origin under a directional light travelling `direction`.
struct TestFrame {
  ShadowMapDesc map{};
  MediumComponent medium;
  FrameDesc frame;

  explicit TestFrame(Float3 direction) {
    const glm::mat4 view = glm::lookAt(glm::vec3(0, 2, 10), glm::vec3(0), glm::vec3(0, 1, 0));
    const glm::mat4 projection = glm::mat4(
        test::vulkanPerspective(glm::radians(60.0), double(kExtent.width) / kExtent.height, 0.1, 100.0, false));
    std::copy(glm::value_ptr(view), glm::value_ptr(view) + 16, frame.camera.view.begin());
    std::copy(glm::value_ptr(projection), glm::value_ptr(projection) + 16, frame.camera.projection.begin());
    frame.light.direction = direction;
    map.depth.extent = {2048, 2048};
    frame.shadowMaps = std::span<const ShadowMapDesc>(&map, 1);
    medium.scattering = {0.02f, 0.02f, 0.02f};
    medium.absorption = {0.01f, 0.01f, 0.01f};
    frame.medium = std::span<const MediumComponent>(&medium, 1);
  }
};

// Light from behind the camera's target towards it: the light axis crosses the frustum.
constexpr Float3 kIntoTheCamera{0.0f, -0.2f, 1.0f};
// Light from the side, almost horizontal across the view: the epipole far off screen.
constexpr Float3 kAcross{1.0f, -0.05f, 0.0f};

TEST(PrefilteredPlan, TheDefaultsRunEveryPerRayOptionWithOneGreySet) {
  PrefilteredFramePlan plan;
  const PrefilteredSettings settings;
  ASSERT_TRUE(planPrefilteredFrame(TestFrame(kIntoTheCamera).frame, settings, kExtent, plan).ok());
  EXPECT_EQ(plan.decisions.prefixSumSets, 1u);
  EXPECT_EQ(plan.decisions.segments, settings.rayWeightTaps);
  EXPECT_TRUE(plan.decisions.rowDepthBounds);
  EXPECT_TRUE(plan.decisions.trimmedSegments);
  EXPECT_EQ(plan.decisions.texelWalkSteps, settings.texelWalkSteps);
  EXPECT_EQ(plan.texelWalkSteps, settings.texelWalkSteps);
  EXPECT_EQ(plan.decisions.shortRayColumns, settings.shortRayColumns);
  EXPECT_EQ(plan.constants.map_columns, settings.columns);
  EXPECT_EQ(plan.constants.map_rows, settings.rows);
  EXPECT_EQ(plan.constants.prefix_sum_sets, 1u);
  EXPECT_EQ(plan.constants.host_map_size, 2048u);
  EXPECT_EQ(plan.note.rfind("; moments6_64, ", 0), 0u) << plan.note;
}

TEST(PrefilteredPlan, TheLightAxisInTheFrustumRulesOutTheProjectiveMap) {
  PrefilteredSettings projective;
  projective.rectification = PrefilteredRectification::Projective;
  PrefilteredFramePlan plan;
  ASSERT_TRUE(planPrefilteredFrame(TestFrame(kIntoTheCamera).frame, projective, kExtent, plan).ok());
  EXPECT_EQ(plan.decisions.rectification, Rectification::NonLinear);
  EXPECT_EQ(plan.decisions.choice, RectificationChoice::ProjectiveImpossible);
  EXPECT_TRUE(std::isinf(plan.decisions.projectiveTexelStretch));
  EXPECT_EQ(plan.constants.projective_map, 0u);
  // The epipole on screen: its block is ray-marched.
  EXPECT_TRUE(plan.decisions.epipoleBlockMarched);

  PrefilteredFramePlan automatic;
  ASSERT_TRUE(planPrefilteredFrame(TestFrame(kAcross).frame, PrefilteredSettings{}, kExtent, automatic).ok());
  EXPECT_EQ(automatic.decisions.choice, RectificationChoice::Automatic);
  EXPECT_EQ(automatic.decisions.rectification == Rectification::Projective,
            automatic.decisions.projectiveTexelStretch <= 2.0);
  EXPECT_EQ(automatic.constants.projective_map, automatic.decisions.rectification == Rectification::Projective ? 1u : 0u);
  EXPECT_FALSE(automatic.decisions.epipoleBlockMarched);
}

TEST(PrefilteredPlan, ChannelsOfDifferentExtinctionGetTheirOwnSetsWhereGreyWouldErr) {
  TestFrame t(kIntoTheCamera);
  t.medium.scattering = {0.02f, 0.2f, 0.02f};  // green extinguishes ten times faster; red = blue
  PrefilteredFramePlan plan;
  ASSERT_TRUE(planPrefilteredFrame(t.frame, PrefilteredSettings{}, kExtent, plan).ok());
  EXPECT_EQ(plan.decisions.prefixSumSets, 2u);
  EXPECT_EQ(plan.constants.channel_set[0], plan.constants.channel_set[2]);
  EXPECT_NE(plan.constants.channel_set[0], plan.constants.channel_set[1]);
}

TEST(PrefilteredPlan, OneLookupHasNoSegmentsAndNothingTrimmedOrWalked) {
  PrefilteredSettings single;
  single.rayWeightTaps = 1;
  PrefilteredFramePlan plan;
  ASSERT_TRUE(planPrefilteredFrame(TestFrame(kIntoTheCamera).frame, single, kExtent, plan).ok());
  EXPECT_EQ(plan.decisions.segments, 0u);
  EXPECT_FALSE(plan.decisions.trimmedSegments);
  EXPECT_EQ(plan.decisions.texelWalkSteps, 0u);
  EXPECT_EQ(plan.constants.segmented, 0u);
  EXPECT_EQ(plan.constants.texel_walk_steps, 0u);
  EXPECT_EQ(plan.note.find("segmented"), std::string::npos);
}

}  // namespace
}  // namespace tyndall
