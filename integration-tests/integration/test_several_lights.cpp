// Several lights in one frame (FrameDesc::additionalLights) on samples/scenes/street-dusk.json, a
// sun and three spot lamps: L_in is the sum of the lights' single-light frames, each profile stays
// within its bar against the Reference, and a light that can reach no visible point records
// nothing.
#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "report.h"
#include "test_support.h"

namespace tyndall::test {
namespace {

constexpr std::uint32_t kWidth = 192;
constexpr std::uint32_t kHeight = 108;
// The sum of single-light frames against the frame of all lights: float rounding of the additions
// (the Reference's full-float targets), or half-float rounding of each light's target and of each
// addition (the approximate techniques' RGBA16F targets: up to 2⁻¹¹ relative each).
constexpr double kSumTolerance = 1e-5;
constexpr double kHalfSumTolerance = 1e-3;

samples::RenderOptions smallOptions(Technique technique, Profile profile = Profile::Balanced) {
  samples::RenderOptions options;
  options.profile = profile;
  options.technique = technique;
  options.width = kWidth;
  options.height = kHeight;
  options.shadowMapSize = 0;  // each light's own size (the lamps' 1024², the sun's 2048²)
  return options;
}

std::size_t lightCount(const host::Scene& scene) { return 1 + scene.additionalLights.size(); }

// The scene lit by its light `index` alone (0: Scene::light).
host::Scene onlyLight(const host::Scene& scene, std::size_t index) {
  host::Scene single = scene;
  if (index > 0) single.light = scene.additionalLights[index - 1];
  single.additionalLights.clear();
  return single;
}

// The per-pixel RGB sum of every light's single-light L_in.
std::vector<double> sumOfSingleLights(const host::Scene& scene, const samples::RenderOptions& options) {
  std::vector<double> sum(std::size_t(kWidth) * kHeight * 3, 0.0);
  for (std::size_t i = 0; i < lightCount(scene); ++i) {
    const samples::RenderResult single = renderWithSharedContext(onlyLight(scene, i), options);
    EXPECT_EQ(single.stats.lights.size(), 1u);
    for (std::size_t p = 0; p < sum.size() / 3; ++p) {
      for (std::size_t c = 0; c < 3; ++c) sum[p * 3 + c] += single.scattering.pixels[p * 4 + c];
    }
  }
  return sum;
}

// Passes named `name` whichever light they belong to ("lightI/name" in a frame of several lights).
std::size_t countPasses(const Stats& stats, const std::string& name) {
  return static_cast<std::size_t>(std::count_if(stats.passesRecorded.begin(), stats.passesRecorded.end(),
                                                [&](const std::string& pass) {
                                                  return pass == name || (pass.size() > name.size() + 1 &&
                                                                          pass.ends_with("/" + name));
                                                }));
}

double sceneBar(Profile profile) { return samples::bench::profileGoal(profile)->maxSceneRelativeRmse; }

TEST(SeveralLights, TheReferenceIsTheSumOfSingleLightFrames) {
  const host::Scene scene = loadTestScene("street-dusk");
  ASSERT_EQ(lightCount(scene), 4u);
  const samples::RenderOptions options = smallOptions(Technique::Reference);
  const samples::RenderResult all = renderWithSharedContext(scene, options);
  const ErrorStats e = compareRgb(all.scattering, sumOfSingleLights(scene, options));
  EXPECT_EQ(e.nonFinite, 0u);
  EXPECT_LT(e.relativeRmse, kSumTolerance) << describe(e);
  EXPECT_GT(e.meanReference, 0.0);
  // Every light ran the Reference into its own target, added by three light sums; one composite.
  ASSERT_EQ(all.stats.lights.size(), 4u);
  EXPECT_EQ(all.stats.lights[0].type, LightType::Directional);
  for (const LightStats& light : all.stats.lights) {
    EXPECT_EQ(light.technique, Technique::Reference);
    EXPECT_EQ(light.skipped, LightSkipped::No);
  }
  EXPECT_EQ(countPasses(all.stats, "reference_scattering"), 4u);
  EXPECT_EQ(countPasses(all.stats, "light_sum"), 3u);
  EXPECT_EQ(countPasses(all.stats, "composite"), 1u);
  // Each light's passes carry its index, so that their timings say whose they are; the shared
  // composite has none.
  for (const char* pass : {"light0/reference_scattering", "light3/reference_scattering", "light3/light_sum",
                           "composite"}) {
    EXPECT_NE(std::find(all.stats.passesRecorded.begin(), all.stats.passesRecorded.end(), pass),
              all.stats.passesRecorded.end())
        << pass;
  }
  ASSERT_FALSE(all.timings.empty());
  EXPECT_NE(std::find_if(all.timings.back().passes.begin(), all.timings.back().passes.end(),
                         [](const PassTiming& p) { return p.name == "light2/reference_scattering"; }),
            all.timings.back().passes.end());
  expectNoValidationMessages();
}

TEST(SeveralLights, EachProfileIsWithinItsBarAndHighIsTheSumOfItsLights) {
  const host::Scene scene = loadTestScene("street-dusk");
  const samples::RenderResult reference = renderWithSharedContext(scene, smallOptions(Technique::Reference));
  for (Profile profile : {Profile::High, Profile::Balanced, Profile::Performance}) {
    const samples::RenderOptions options = smallOptions(Technique::None, profile);
    const samples::RenderResult all = renderWithSharedContext(scene, options);
    const ErrorStats e = compareRgb(all.scattering, reference.scattering);
    EXPECT_EQ(e.nonFinite, 0u) << to_string(profile);
    EXPECT_LT(e.relativeRmse, sceneBar(profile)) << to_string(profile) << ": " << describe(e);
    ASSERT_EQ(all.stats.lights.size(), 4u);
    // The sun runs the directional row, the lamps the local one (every row is epipolar).
    for (const LightStats& light : all.stats.lights) EXPECT_EQ(light.technique, Technique::Epipolar);
    EXPECT_EQ(countPasses(all.stats, "light_sum"), 3u);
    if (profile == Profile::High) {
      // Each light's technique runs as it would alone: the frame is the sum of the single-light frames.
      const ErrorStats sum = compareRgb(all.scattering, sumOfSingleLights(scene, options));
      EXPECT_LT(sum.relativeRmse, kHalfSumTolerance) << describe(sum);
    }
  }
  expectNoValidationMessages();
}

TEST(SeveralLights, LightsThatReachNoVisiblePointRecordNothing) {
  const host::Scene scene = loadTestScene("street-dusk");
  host::Scene more = scene;
  // A spot light behind the camera shining away from the view, and a lamp switched off.
  host::Light away = scene.additionalLights[0];
  away.position = scene.camera.position + glm::dvec3(0.0, 0.0, 4.0);
  away.direction = glm::normalize(scene.camera.position - scene.camera.target);
  host::Light off = scene.additionalLights[1];
  off.intensity = 0.0;
  more.additionalLights.push_back(away);
  more.additionalLights.push_back(off);
  samples::RenderOptions options = smallOptions(Technique::None, Profile::Balanced);
  // The stats are the last frame's: the second, after a first that may build each lamp's
  // scattering table (once per light and medium).
  options.frames = 2;
  const samples::RenderResult base = renderWithSharedContext(scene, options);
  const samples::RenderResult extended = renderWithSharedContext(more, options);
  ASSERT_EQ(extended.stats.lights.size(), 6u);
  EXPECT_EQ(extended.stats.lights[4].skipped, LightSkipped::OutsideView);
  EXPECT_EQ(extended.stats.lights[4].technique, Technique::None);
  EXPECT_EQ(extended.stats.lights[5].skipped, LightSkipped::Off);
  EXPECT_EQ(countPasses(extended.stats, "light_sum"), countPasses(base.stats, "light_sum"));
  EXPECT_EQ(extended.stats.dispatches, base.stats.dispatches);
  const ErrorStats e = compareRgb(extended.scattering, base.scattering);
  EXPECT_EQ(e.relativeMax, 0.0) << describe(e);

  // Alone, the light behind the camera leaves nothing to compute: L_in is cleared.
  const samples::RenderResult alone = renderWithSharedContext(onlyLight(more, 4), options);
  EXPECT_EQ(alone.stats.technique, Technique::None);
  EXPECT_EQ(alone.stats.techniqueChange, TechniqueChange::NothingScatters);
  ASSERT_EQ(alone.stats.lights.size(), 1u);
  EXPECT_EQ(alone.stats.lights[0].skipped, LightSkipped::OutsideView);
  EXPECT_EQ(countPasses(alone.stats, "scattering_clear"), 1u);
  EXPECT_EQ(*std::max_element(alone.scattering.pixels.begin(), alone.scattering.pixels.end()), 0.0f);
  expectNoValidationMessages();
}

}  // namespace
}  // namespace tyndall::test
