// planEpipolarFrame: the epipolar technique's per-frame decisions, without a device.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "epipolar/epipolar_plan.h"
#include "epipolar/min_max_tree.h"
#include "vulkan_projection.h"

namespace tyndall {
namespace {

constexpr VkExtent2D kExtent{320, 180};

// A camera at (0, 2, 10) looking at the origin, a light of `type` above the scene, `maps` maps of
// `mapSize`² texels (their extents are all the plan reads of them).
struct TestFrame {
  std::array<ShadowMapDesc, kMaxShadowMaps> maps{};
  MediumComponent medium;
  FrameDesc frame;

  TestFrame(LightType type, std::uint32_t mapSize) {
    const glm::mat4 view = glm::lookAt(glm::vec3(0, 2, 10), glm::vec3(0), glm::vec3(0, 1, 0));
    const glm::mat4 projection = glm::mat4(
        test::vulkanPerspective(glm::radians(60.0), double(kExtent.width) / kExtent.height, 0.1, 100.0, false));
    std::copy(glm::value_ptr(view), glm::value_ptr(view) + 16, frame.camera.view.begin());
    std::copy(glm::value_ptr(projection), glm::value_ptr(projection) + 16, frame.camera.projection.begin());
    frame.light.type = type;
    frame.light.direction = {0.3f, -1.0f, -0.2f};
    frame.light.position = {0.0f, 6.0f, 0.0f};
    for (ShadowMapDesc& map : maps) map.depth.extent = {mapSize, mapSize};
    const std::size_t count = type == LightType::Point ? 6 : 1;
    frame.shadowMaps = std::span<const ShadowMapDesc>(maps.data(), count);
    frame.medium = std::span<const MediumComponent>(&medium, 1);
  }
};

TEST(EpipolarPlan, ADirectionalLightMarchesTheTreeAndWalksBlocksInTheFixUp) {
  const TestFrame t(LightType::Directional, 2048);
  EpipolarSettings settings;
  const EpipolarFramePlan plan = planEpipolarFrame(t.frame, settings, kExtent);
  EXPECT_EQ(plan.stats.march, EpipolarMarch::MinMaxTree);
  EXPECT_EQ(plan.treeSamples, static_cast<std::uint32_t>(gpu::tyn_min_max_sample_count(2048)));
  EXPECT_EQ(plan.constants.tree_enabled, 1u);
  EXPECT_EQ(plan.colorSamples, 0u);
  const std::uint32_t side = 2048 / gpu::TYN_EPIPOLAR_SHADOW_BLOCK;
  EXPECT_EQ(plan.shadowBlocks.width, side);
  EXPECT_EQ(plan.shadowBlocks.height, side);
  EXPECT_EQ(plan.constants.shadow_block_side, side);
  // The settings reach the constants by name.
  EXPECT_EQ(plan.constants.slice_count, settings.slices);
  EXPECT_EQ(plan.constants.samples_per_slice, settings.samplesPerSlice);
  EXPECT_EQ(plan.stats.slices, settings.slices);
  EXPECT_EQ(plan.stats.samplesPerSlice, settings.samplesPerSlice);
  EXPECT_EQ(plan.constants.fixup_steps, 0u);
  EXPECT_EQ(epipolarNote(plan.stats).find("tree"), std::string::npos);

  // A fix-up in steps walks no blocks.
  settings.fixupSteps = 64;
  const EpipolarFramePlan stepped = planEpipolarFrame(t.frame, settings, kExtent);
  EXPECT_EQ(stepped.shadowBlocks.width, 0u);
  EXPECT_EQ(stepped.constants.fixup_steps, 64u);
}

TEST(EpipolarPlan, TheTreeIsOffWhenAskedAndAboveItsLargestMap) {
  EpipolarSettings off;
  off.minMaxTree = false;
  const EpipolarFramePlan a = planEpipolarFrame(TestFrame(LightType::Directional, 2048).frame, off, kExtent);
  EXPECT_EQ(a.stats.march, EpipolarMarch::CellsTreeOff);
  EXPECT_EQ(a.treeSamples, 0u);
  EXPECT_NE(epipolarNote(a.stats).find("min/max tree off"), std::string::npos);
  const EpipolarFramePlan b =
      planEpipolarFrame(TestFrame(LightType::Directional, 8192).frame, EpipolarSettings{}, kExtent);
  EXPECT_EQ(b.stats.march, EpipolarMarch::CellsMapTooLarge);
  EXPECT_EQ(b.treeSamples, 0u);
}

TEST(EpipolarPlan, APointLightWalksBlocksOfItsSixMapsAndASpotLightNone) {
  const EpipolarFramePlan point = planEpipolarFrame(TestFrame(LightType::Point, 1000).frame, EpipolarSettings{}, kExtent);
  EXPECT_EQ(point.stats.march, EpipolarMarch::PointLightBlockWalk);
  EXPECT_EQ(point.treeSamples, 0u);
  EXPECT_EQ(point.lineMaps, 0u);
  const std::uint32_t side = (1000 + gpu::TYN_EPIPOLAR_WALKED_SHADOW_BLOCK - 1) / gpu::TYN_EPIPOLAR_WALKED_SHADOW_BLOCK;
  EXPECT_EQ(point.shadowBlocks.width, side);
  EXPECT_EQ(point.shadowBlocks.height, 6 * side);

  TestFrame spot(LightType::Spot, 2048);
  spot.frame.light.direction = {0.0f, -1.0f, 0.0f};
  const EpipolarFramePlan s = planEpipolarFrame(spot.frame, EpipolarSettings{}, kExtent);
  EXPECT_EQ(s.stats.march, EpipolarMarch::MinMaxTree);
  EXPECT_EQ(s.shadowBlocks.width, 0u);
  EXPECT_EQ(s.lineMaps, 1u);
  EXPECT_EQ(s.colorSamples, 0u);
  // A light-colour texture: the march integrates in coloured chunks along the tree's samples.
  spot.frame.lightColor.image = reinterpret_cast<VkImage>(std::uintptr_t{1});
  const EpipolarFramePlan coloured = planEpipolarFrame(spot.frame, EpipolarSettings{}, kExtent);
  EXPECT_EQ(coloured.colorSamples, coloured.treeSamples);
  EXPECT_EQ(coloured.constants.colored_chunk, EpipolarSettings{}.coloredStep);
}

TEST(EpipolarPlan, CascadesMarchAlongALineAndTreePerCascade) {
  TestFrame t(LightType::Directional, 1024);
  t.frame.shadowMaps = std::span<const ShadowMapDesc>(t.maps.data(), 3);
  const EpipolarFramePlan plan = planEpipolarFrame(t.frame, EpipolarSettings{}, kExtent);
  EXPECT_EQ(plan.stats.march, EpipolarMarch::MinMaxTree);
  EXPECT_FALSE(plan.walksMaps);
  EXPECT_EQ(plan.lineMaps, 3u);
  EXPECT_EQ(plan.stats.linesPerSlice, 3u);
  EXPECT_EQ(plan.treeSamples, static_cast<std::uint32_t>(gpu::tyn_min_max_sample_count(1024)));
  EXPECT_EQ(plan.constants.tree_enabled, 1u);
  // The fix-up's blocks, when it walks texel by texel, cover every cascade.
  EpipolarSettings texelWalk;
  texelWalk.fixupSteps = 0;
  const EpipolarFramePlan walked = planEpipolarFrame(t.frame, texelWalk, kExtent);
  const std::uint32_t side = 1024 / gpu::TYN_EPIPOLAR_SHADOW_BLOCK;
  EXPECT_EQ(walked.shadowBlocks.width, side);
  EXPECT_EQ(walked.shadowBlocks.height, 3 * side);
  EXPECT_NE(epipolarNote(plan.stats).find("3 cascades"), std::string::npos) << epipolarNote(plan.stats);
  // One map is not a cascade: one line, and no word of cascades.
  t.frame.shadowMaps = std::span<const ShadowMapDesc>(t.maps.data(), 1);
  const EpipolarFramePlan one = planEpipolarFrame(t.frame, EpipolarSettings{}, kExtent);
  EXPECT_EQ(one.stats.march, EpipolarMarch::MinMaxTree);
  EXPECT_EQ(one.lineMaps, 1u);
  EXPECT_EQ(epipolarNote(one.stats).find("cascades"), std::string::npos) << epipolarNote(one.stats);
}

TEST(EpipolarPlan, TheSlicesCoverTheWholeBorderAroundAnOnScreenEpipole) {
  // The light behind the camera's target, shining towards it: its epipole lies on screen.
  TestFrame t(LightType::Directional, 1024);
  t.frame.light.direction = {0.0f, -0.2f, 1.0f};
  const EpipolarFramePlan plan = planEpipolarFrame(t.frame, EpipolarSettings{}, kExtent);
  EXPECT_EQ(plan.stats.sliceBorderFraction, 1.0f);
  EXPECT_FALSE(plan.stats.slicesFitSpotCone);
  EXPECT_FALSE(plan.stats.slicesFitOffScreenEpipole);
}

// A local light's occluders can sit next to it: by default its samples crowd towards it and the
// march step shrinks faster there than a directional light's; a density in the settings wins.
TEST(EpipolarPlan, ALocalLightGetsDenserSamplesAndStepsNextToIt) {
  const EpipolarSettings defaults;
  ASSERT_EQ(defaults.epipoleDensity, 0.0f);
  const EpipolarFramePlan sun = planEpipolarFrame(TestFrame(LightType::Directional, 1024).frame, defaults, kExtent);
  EXPECT_EQ(sun.constants.epipole_density, 1.0f);
  EXPECT_EQ(sun.stats.epipoleDensity, 1.0f);
  EXPECT_EQ(sun.constants.near_epipole_steps, gpu::TYN_EPIPOLAR_NEAR_EPIPOLE_STEPS);
  for (LightType type : {LightType::Spot, LightType::Point}) {
    const TestFrame t(type, 1024);
    const EpipolarFramePlan local = planEpipolarFrame(t.frame, defaults, kExtent);
    EXPECT_EQ(local.constants.epipole_density, gpu::TYN_EPIPOLAR_LOCAL_LIGHT_DENSITY);
    EXPECT_EQ(local.stats.epipoleDensity, gpu::TYN_EPIPOLAR_LOCAL_LIGHT_DENSITY);
    EXPECT_EQ(local.constants.near_epipole_steps, gpu::TYN_EPIPOLAR_NEAR_LOCAL_LIGHT_STEPS);
    EXPECT_GT(gpu::TYN_EPIPOLAR_NEAR_LOCAL_LIGHT_STEPS, gpu::TYN_EPIPOLAR_NEAR_EPIPOLE_STEPS);
    EpipolarSettings uniform;
    uniform.epipoleDensity = 1.0f;
    EXPECT_EQ(planEpipolarFrame(t.frame, uniform, kExtent).constants.epipole_density, 1.0f);
  }
  EpipolarSettings dense;
  dense.epipoleDensity = 3.5f;
  EXPECT_EQ(planEpipolarFrame(TestFrame(LightType::Directional, 1024).frame, dense, kExtent).constants.epipole_density,
            3.5f);
}

}  // namespace
}  // namespace tyndall
