// Cascaded shadow maps of a directional light (ShadowMapDesc::viewDepthNear/viewDepthFar) on
// samples/scenes/colonnade.json, a 300 m avenue of pillars seen from eye height: the Reference
// against the CPU analytic reference, no seam where one cascade hands over to the next, a smooth
// change of L_in as the camera moves across the boundaries, and every profile within its bar
// against the Reference with the same cascades.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "report.h"
#include "test_support.h"
#include "tyndall_effect.h"

namespace tyndall::test {
namespace {

constexpr std::uint32_t kWidth = 192;
constexpr std::uint32_t kHeight = 108;

samples::RenderOptions cascadeOptions(Profile profile, std::uint32_t cascades, std::uint32_t mapSize) {
  samples::RenderOptions options;
  options.profile = profile;
  options.width = kWidth;
  options.height = kHeight;
  options.shadowMapSize = mapSize;
  options.cascades = cascades;
  return options;
}

// The analytic L_in of every pixel.
analytic::RgbImage analyticScattering(const host::Scene& scene) {
  analytic::RgbImage scattering;
  analytic::RgbImage transmittance;
  std::string error;
  EXPECT_TRUE(analytic::renderAnalytic(scene, kWidth, kHeight, scattering, transmittance, error)) << error;
  return scattering;
}

double sceneBar(Profile profile) { return samples::bench::profileGoal(profile)->maxSceneRelativeRmse; }

// Four cascades of 1024² against the analytic answer, beside one map of 1024² and one of 2048²
// fitted to the casters (printed: on a colonnade under a low sun the single map's window is a
// narrow strip, its texels a few centimetres across the light, finer than the far cascades').
TEST(Cascades, FourCascadesMeetTheReferenceBarOnALongView) {
  const host::Scene scene = loadTestScene("colonnade");
  const analytic::RgbImage exact = analyticScattering(scene);
  const samples::RenderResult four = renderWithSharedContext(scene, cascadeOptions(Profile::Reference, 4, 1024));
  const samples::RenderResult fine = renderWithSharedContext(scene, cascadeOptions(Profile::Reference, 4, 4096));
  const samples::RenderResult one = renderWithSharedContext(scene, cascadeOptions(Profile::Reference, 1, 1024));
  const samples::RenderResult one2048 = renderWithSharedContext(scene, cascadeOptions(Profile::Reference, 1, 2048));
  EXPECT_EQ(four.stats.technique, Technique::Reference);
  const ErrorStats e4 = compareRgb(four.scattering, exact.rgb);
  const ErrorStats e4fine = compareRgb(fine.scattering, exact.rgb);
  const ErrorStats e1 = compareRgb(one.scattering, exact.rgb);
  const ErrorStats e1x2048 = compareRgb(one2048.scattering, exact.rgb);
  std::printf("[ colonnade ] 4 cascades of 1024^2: %s\n[ colonnade ] 4 cascades of 4096^2: %s\n"
              "[ colonnade ] 1 map of 1024^2:      %s\n[ colonnade ] 1 map of 2048^2:      %s\n",
              describe(e4).c_str(), describe(e4fine).c_str(), describe(e1).c_str(), describe(e1x2048).c_str());
  EXPECT_GT(e4.meanReference, 0.0);
  EXPECT_EQ(e4.nonFinite, 0u);
  EXPECT_LE(e4.relativeRmse, 0.02) << describe(e4);  // the Reference's bar on the analytic scenes
  // The cascades converge on the analytic answer as their maps grow, and four of them do better
  // than one map of the same size.
  EXPECT_LT(e4fine.relativeRmse, 0.5 * e4.relativeRmse) << describe(e4fine);
  EXPECT_LT(e4.relativeRmse, e1.relativeRmse);
  expectNoValidationMessages();
}

// Renders the Reference with the frame's one map handed over as four cascades of that same map
// (each a stretch of view depths), or as it is.
class SplitMapEffect final : public host::PostProcessEffect {
 public:
  std::unique_ptr<Context> context;
  bool split = false;
  Outcome outcome;

  bool record(VkCommandBuffer cmd, const host::PostProcessInputs& inputs, std::string&) override {
    samples::FrameStorage storage;
    FrameDesc frame = samples::makeFrameDesc(inputs, Profile::Reference, storage);
    if (split) {
      const std::vector<float> ends = {6.0f, 17.5f, 60.0f, 1000.0f};
      storage.shadowMaps.assign(ends.size(), storage.shadowMaps[0]);
      for (std::size_t i = 0; i < ends.size(); ++i) {
        storage.shadowMaps[i].viewDepthNear = i == 0 ? 0.0f : ends[i - 1];
        storage.shadowMaps[i].viewDepthFar = ends[i];
      }
      frame.shadowMaps = storage.shadowMaps;
    }
    outcome = context->record(cmd, frame);
    return true;
  }
  bool resize(VkExtent2D, std::string&) override { return true; }
};

// A seam at a cascade boundary would come from the handover: a stretch of the ray walked twice or
// not at all, or its ends lit differently. With every cascade the same map, the cascaded walk must
// give the single map's L_in up to float rounding (a few more integrals summed), whatever the
// maps' resolution: the boundaries alone cost nothing.
TEST(Cascades, NoSeamWhereOneCascadeHandsOverToTheNext) {
  const host::Scene scene = loadTestScene("colonnade");
  host::RenderSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.shadowMapSize = 1024;
  settings.cascades = 1;
  settings.aovImages = true;
  std::string error;
  host::Device& device = validatedDevice();
  std::unique_ptr<host::Renderer> renderer = host::Renderer::create(device, scene, settings, error);
  ASSERT_TRUE(renderer) << error;
  SplitMapEffect effect;
  {
    Result<std::unique_ptr<Context>> created = Context::create(samples::contextDescFor(device, settings));
    ASSERT_TRUE(created.ok()) << created.outcome().message;
    effect.context = std::move(created).value();
  }
  renderer->addPostProcess(&effect);
  host::ImageRgba32f whole, split;
  for (bool cascades : {false, true}) {
    effect.split = cascades;
    ASSERT_TRUE(renderer->renderFrame(error)) << error;
    renderer->waitIdle();
    ASSERT_TRUE(effect.outcome.ok()) << effect.outcome.message;
    ASSERT_TRUE(renderer->readAovScattering(cascades ? split : whole, error)) << error;
  }
  const ErrorStats e = compareRgb(split, whole);
  std::printf("[ colonnade ] one map as four cascades against the map: %s\n", describe(e).c_str());
  EXPECT_GT(e.meanReference, 0.0);
  EXPECT_EQ(e.nonFinite, 0u);
  EXPECT_LE(e.relativeMax, 1e-4) << describe(e);
  expectNoValidationMessages();
}

// The largest flicker between consecutive frames as the camera walks 12 m down the avenue in steps
// of 1.5 m, with `cascades` maps of `mapSize`²: RMS of (ΔL_in − Δanalytic) over the analytic mean,
// the change of L_in that the analytic answer does not make.
double worstFlicker(const host::Scene& scene, std::uint32_t cascades, std::uint32_t mapSize) {
  std::vector<double> previous;
  std::vector<double> previousExact;
  double worst = 0.0;
  for (int step = 0; step <= 8; ++step) {
    const glm::dvec3 shift(0.0, 0.0, -1.5 * step);
    host::Scene moved = scene;
    moved.camera.position += shift;
    moved.camera.target += shift;
    const analytic::RgbImage exact = analyticScattering(moved);
    const samples::RenderResult frame =
        renderWithSharedContext(moved, cascadeOptions(Profile::Reference, cascades, mapSize));
    std::vector<double> current(frame.scattering.pixels.size() / 4 * 3);
    for (std::size_t p = 0; p < current.size() / 3; ++p) {
      for (std::size_t c = 0; c < 3; ++c) current[p * 3 + c] = frame.scattering.pixels[p * 4 + c];
    }
    if (!previous.empty()) {
      double mean = 0.0, flicker = 0.0;
      for (std::size_t i = 0; i < current.size(); ++i) {
        mean += std::abs(exact.rgb[i]);
        const double d = (current[i] - previous[i]) - (exact.rgb[i] - previousExact[i]);
        flicker += d * d;
      }
      mean /= double(current.size());
      worst = std::max(worst, std::sqrt(flicker / double(current.size())) / mean);
    }
    previous = current;
    previousExact = exact.rgb;
  }
  return worst;
}

// Pillars and their shadows cross every cascade boundary as the camera walks. The cascades' texels
// stay fixed in the world (texel-snapped), so L_in flickers no more than with one map of the
// cascades' size, which the host refits to the view every frame.
TEST(Cascades, CameraMotionAcrossTheBoundariesChangesLinSmoothly) {
  const host::Scene scene = loadTestScene("colonnade");
  const double cascades = worstFlicker(scene, 4, 1024);
  const double one = worstFlicker(scene, 1, 1024);
  std::printf("[ colonnade ] worst flicker over 8 steps: 4 cascades of 1024^2 %.3f%%, 1 map of 1024^2 %.3f%%\n",
              100.0 * cascades, 100.0 * one);
  EXPECT_LE(cascades, one);
  EXPECT_LE(cascades, 0.03);
  expectNoValidationMessages();
}

TEST(Cascades, EachProfileIsWithinItsBarAgainstTheReference) {
  const host::Scene scene = loadTestScene("colonnade");
  const samples::RenderResult reference = renderWithSharedContext(scene, cascadeOptions(Profile::Reference, 4, 1024));
  for (Profile profile : {Profile::High, Profile::Balanced, Profile::Performance}) {
    SCOPED_TRACE(to_string(profile));
    const samples::RenderResult result = renderWithSharedContext(scene, cascadeOptions(profile, 4, 1024));
    ASSERT_EQ(result.stats.technique, Technique::Epipolar);
    ASSERT_TRUE(result.stats.epipolar.has_value());
    EXPECT_EQ(result.stats.epipolar->march, EpipolarMarch::MinMaxTree) << result.stats.techniqueNote;
    EXPECT_EQ(result.stats.epipolar->linesPerSlice, 4u) << result.stats.techniqueNote;
    const ErrorStats e = compareRgb(result.scattering, reference.scattering);
    std::printf("[ colonnade ] %s: %s\n", to_string(profile), describe(e).c_str());
    EXPECT_EQ(e.nonFinite, 0u);
    EXPECT_LT(e.relativeRmse, sceneBar(profile)) << describe(e);
  }
  // The prefiltered technique rectifies one map: epipolar runs, and says why.
  samples::RenderOptions prefiltered = cascadeOptions(Profile::Balanced, 4, 1024);
  prefiltered.technique = Technique::Prefiltered;
  const samples::RenderResult changed = renderWithSharedContext(scene, prefiltered);
  EXPECT_EQ(changed.stats.technique, Technique::Epipolar);
  EXPECT_EQ(changed.stats.techniqueChange, TechniqueChange::PrefilteredNeedsOneShadowMap);
  expectNoValidationMessages();
}

}  // namespace
}  // namespace tyndall::test
