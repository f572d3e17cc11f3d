// selectTechnique: the request runs unless a design fallback applies, and each fallback is named.
#include <gtest/gtest.h>

#include "technique_selection.h"

namespace tyndall {
namespace {

TechniqueRequest request(Technique technique, LightType light = LightType::Directional) {
  TechniqueRequest r;
  r.requested = technique;
  r.light = light;
  r.extent = {64, 36};
  return r;
}

TEST(TechniqueSelection, TheRequestRunsWhenNothingPreventsIt) {
  for (Technique t : {Technique::Reference, Technique::Epipolar, Technique::Prefiltered}) {
    const TechniqueSelection s = selectTechnique(request(t));
    EXPECT_EQ(s.technique, t) << to_string(t);
    EXPECT_EQ(s.change, TechniqueChange::None);
  }
  for (LightType light : {LightType::Spot, LightType::Point}) {
    EXPECT_EQ(selectTechnique(request(Technique::Epipolar, light)).technique, Technique::Epipolar);
    EXPECT_EQ(selectTechnique(request(Technique::Reference, light)).technique, Technique::Reference);
  }
}

TEST(TechniqueSelection, PrefilteredFallsBackToEpipolarForLocalLightsAndLightColour) {
  for (LightType light : {LightType::Spot, LightType::Point}) {
    const TechniqueSelection s = selectTechnique(request(Technique::Prefiltered, light));
    EXPECT_EQ(s.technique, Technique::Epipolar);
    EXPECT_EQ(s.change, TechniqueChange::PrefilteredNeedsDirectionalLight);
  }
  TechniqueRequest coloured = request(Technique::Prefiltered);
  coloured.hasLightColor = true;
  const TechniqueSelection s = selectTechnique(coloured);
  EXPECT_EQ(s.technique, Technique::Epipolar);
  EXPECT_EQ(s.change, TechniqueChange::PrefilteredHasNoLightColor);
  coloured.requested = Technique::Epipolar;
  EXPECT_EQ(selectTechnique(coloured).change, TechniqueChange::None);

  TechniqueRequest cascades = request(Technique::Prefiltered);
  cascades.cascades = true;
  EXPECT_EQ(selectTechnique(cascades).technique, Technique::Epipolar);
  EXPECT_EQ(selectTechnique(cascades).change, TechniqueChange::PrefilteredNeedsOneShadowMap);
  for (Technique t : {Technique::Reference, Technique::Epipolar}) {
    cascades.requested = t;
    EXPECT_EQ(selectTechnique(cascades).technique, t);
    EXPECT_EQ(selectTechnique(cascades).change, TechniqueChange::None);
  }
}

TEST(TechniqueSelection, OutputsUnderTwoByTwoRunTheReferenceInsteadOfEpipolar) {
  for (VkExtent2D extent : {VkExtent2D{1, 1}, VkExtent2D{1, 64}, VkExtent2D{64, 1}}) {
    TechniqueRequest r = request(Technique::Epipolar);
    r.extent = extent;
    const TechniqueSelection s = selectTechnique(r);
    EXPECT_EQ(s.technique, Technique::Reference);
    EXPECT_EQ(s.change, TechniqueChange::EpipolarNeeds2x2);
    // A prefiltered request for a spot light on such an output falls back twice: the last names it.
    r.requested = Technique::Prefiltered;
    r.light = LightType::Spot;
    EXPECT_EQ(selectTechnique(r).technique, Technique::Reference);
    EXPECT_EQ(selectTechnique(r).change, TechniqueChange::EpipolarNeeds2x2);
  }
  TechniqueRequest two = request(Technique::Epipolar);
  two.extent = {2, 2};
  EXPECT_EQ(selectTechnique(two).technique, Technique::Epipolar);
}

TEST(TechniqueSelection, NothingScattersRunsNoTechnique) {
  for (Technique t : {Technique::Reference, Technique::Epipolar, Technique::Prefiltered}) {
    TechniqueRequest r = request(t, LightType::Spot);
    r.scatters = false;
    const TechniqueSelection s = selectTechnique(r);
    EXPECT_EQ(s.technique, Technique::None);
    EXPECT_EQ(s.change, TechniqueChange::NothingScatters);
  }
}

TEST(TechniqueSelection, EveryChangeHasANoteAndAName) {
  EXPECT_STREQ(techniqueChangeNote(TechniqueChange::None), "");
  for (TechniqueChange c : {TechniqueChange::NoExtinction, TechniqueChange::NothingScatters,
                            TechniqueChange::PrefilteredNeedsDirectionalLight,
                            TechniqueChange::PrefilteredHasNoLightColor, TechniqueChange::EpipolarNeeds2x2}) {
    EXPECT_STRNE(techniqueChangeNote(c), "");
    EXPECT_STRNE(to_string(c), "unknown");
  }
}

// lavapipe's 65,535 loop iterations per invocation (docs/REFERENCE.md "Loop budget on lavapipe"):
// a point light's walk is measured within it up to 4096² maps; a directional light's takes one
// iteration per texel edge, up to 2·N per cascade; a spot light's two.
TEST(TechniqueSelection, WalksThatCanOverrunTheCpuLoopBudget) {
  EXPECT_FALSE(walkCanOverrunCpuLoopBudget(LightType::Point, 6, 4096));
  EXPECT_TRUE(walkCanOverrunCpuLoopBudget(LightType::Point, 6, 4104));
  EXPECT_FALSE(walkCanOverrunCpuLoopBudget(LightType::Directional, 1, 16384));
  EXPECT_FALSE(walkCanOverrunCpuLoopBudget(LightType::Directional, 4, 4096));
  EXPECT_FALSE(walkCanOverrunCpuLoopBudget(LightType::Directional, 4, 8191));
  EXPECT_TRUE(walkCanOverrunCpuLoopBudget(LightType::Directional, 4, 8192));
  EXPECT_TRUE(walkCanOverrunCpuLoopBudget(LightType::Directional, 2, 16384));
  EXPECT_FALSE(walkCanOverrunCpuLoopBudget(LightType::Spot, 1, 8192));
  EXPECT_TRUE(walkCanOverrunCpuLoopBudget(LightType::Spot, 1, 16384));
  // Four translucent layers (five read): a spot or point light's step costs 12 iterations, a
  // directional light's 6.
  EXPECT_FALSE(walkCanOverrunCpuLoopBudget(LightType::Spot, 1, 2048, 4));
  EXPECT_TRUE(walkCanOverrunCpuLoopBudget(LightType::Spot, 1, 4096, 4));
  EXPECT_FALSE(walkCanOverrunCpuLoopBudget(LightType::Point, 6, 512, 4));
  EXPECT_TRUE(walkCanOverrunCpuLoopBudget(LightType::Point, 6, 1024, 4));
  EXPECT_FALSE(walkCanOverrunCpuLoopBudget(LightType::Directional, 1, 4096, 4));
  EXPECT_TRUE(walkCanOverrunCpuLoopBudget(LightType::Directional, 1, 8192, 4));
  EXPECT_FALSE(walkCanOverrunCpuLoopBudget(LightType::Directional, 4, 1024, 4));
  EXPECT_TRUE(walkCanOverrunCpuLoopBudget(LightType::Directional, 4, 2048, 4));
}

}  // namespace
}  // namespace tyndall
