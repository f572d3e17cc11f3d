// Frames in flight, timings, resize, back-buffer formats, depth conventions, and the passes a
// frame records when the medium needs less.
#include <cmath>

#include <gtest/gtest.h>

#include "test_support.h"
#include "tyndall_effect.h"

namespace tyndall::test {
namespace {

samples::RenderOptions smallOptions(std::uint32_t width = 64, std::uint32_t height = 36) {
  samples::RenderOptions options;
  options.profile = Profile::Reference;
  options.width = width;
  options.height = height;
  options.shadowMapSize = 1024;
  return options;
}

TEST(FramesInFlight, EveryFrameIsTimedAndValidationIsClean) {
  const host::Scene scene = loadTestScene("analytic-spheres");
  for (std::uint32_t inFlight : {1u, 2u, 3u}) {
    SCOPED_TRACE("frames in flight " + std::to_string(inFlight));
    samples::RenderOptions options = smallOptions();
    options.framesInFlight = inFlight;
    options.frames = 6;
    const samples::RenderResult result = renderWithAovs(scene, options);
    ASSERT_TRUE(result.stats.timestampsSupported) << "lavapipe supports timestamps";
    ASSERT_EQ(result.timings.size(), 6u);
    for (std::size_t i = 0; i < result.timings.size(); ++i) {
      const FrameTimings& t = result.timings[i];
      EXPECT_EQ(t.frameIndex, i);
      ASSERT_EQ(t.passes.size(), 3u);
      EXPECT_EQ(t.passes[0].name, "reference_scattering");
      EXPECT_EQ(t.passes[1].name, "composite");
      EXPECT_EQ(t.passes[2].name, "aov_output");
      EXPECT_GT(t.passes[0].milliseconds, 0.0);
      EXPECT_GE(t.totalMilliseconds, t.passes[0].milliseconds);
    }
    EXPECT_EQ(result.stats.frameIndex, 6u);
    expectNoValidationMessages();
  }
}

TEST(Resize, OnlyTheNewSizeIsRenderedAndStaysAccurate) {
  const host::Scene scene = loadTestScene("analytic-boxes");
  host::RenderSettings settings;
  settings.width = 48;
  settings.height = 27;
  settings.shadowMapSize = 2048;
  settings.aovImages = true;
  std::string error;
  host::Device& device = validatedDevice();
  std::unique_ptr<host::Renderer> renderer = host::Renderer::create(device, scene, settings, error);
  ASSERT_TRUE(renderer) << error;
  std::unique_ptr<samples::TyndallEffect> effect =
      samples::TyndallEffect::create(device, settings, Profile::Reference, error);
  ASSERT_TRUE(effect) << error;
  renderer->addPostProcess(effect.get());
  ASSERT_TRUE(renderer->renderFrame(error)) << error;
  ASSERT_TRUE(renderer->resize(96, 54, error)) << error;
  ASSERT_TRUE(renderer->renderFrame(error)) << error;
  ASSERT_TRUE(renderer->renderFrame(error)) << error;
  renderer->waitIdle();

  host::ImageRgba32f scattering;
  ASSERT_TRUE(renderer->readAovScattering(scattering, error)) << error;
  ASSERT_EQ(scattering.width, 96u);
  ASSERT_EQ(scattering.height, 54u);
  analytic::RgbImage reference;
  analytic::RgbImage transmittance;
  ASSERT_TRUE(analytic::renderAnalytic(scene, 96, 54, reference, transmittance, error)) << error;
  const ErrorStats stats = compareRgb(scattering, reference.rgb);
  EXPECT_LE(stats.relativeRmse, 0.02) << describe(stats);
  EXPECT_EQ(stats.nonFinite, 0u);
  expectNoValidationMessages();
}

TEST(BackBuffer, Srgb8IsCompositedInLinear) {
  const host::Scene scene = loadTestScene("analytic-mixed");
  samples::RenderOptions options = smallOptions();
  const samples::RenderResult hdr = renderWithAovs(scene, options);
  options.backBufferFormat = VK_FORMAT_B8G8R8A8_SRGB;
  const samples::RenderResult srgb = renderWithAovs(scene, options);
  ASSERT_EQ(srgb.color.pixels.size(), hdr.color.pixels.size());
  // Same scene, same composite: they differ by 8-bit sRGB quantisation (and clamping to 1).
  host::ImageRgba32f clamped = hdr.color;
  for (float& v : clamped.pixels) v = std::min(v, 1.0f);
  const ErrorStats stats = compareRgb(srgb.color, clamped);
  EXPECT_LE(stats.relativeRmse, 0.02) << describe(stats);
  expectNoValidationMessages();
}

// Reverse-Z and an infinite far plane give the same L_in as standard depth. With an infinite far
// plane the sky integrates to a fixed distance instead of the far plane, so sky pixels (told by
// their transmittance) are left out there.
TEST(DepthConventions, ReverseZAndInfiniteFarMatchStandard) {
  const host::Scene scene = loadTestScene("analytic-spheres");
  const samples::RenderResult standard = renderWithAovs(scene, smallOptions(96, 54));

  samples::RenderOptions reverse = smallOptions(96, 54);
  reverse.depth = host::DepthConvention::Reverse;
  const samples::RenderResult reversed = renderWithAovs(scene, reverse);
  const ErrorStats r = compareRgb(reversed.scattering, standard.scattering);
  EXPECT_LE(r.relativeRmse, 0.005) << describe(r);

  for (host::DepthConvention convention : {host::DepthConvention::Standard, host::DepthConvention::Reverse}) {
    samples::RenderOptions infinite = smallOptions(96, 54);
    infinite.depth = convention;
    infinite.infiniteFar = true;
    const samples::RenderResult inf = renderWithAovs(scene, infinite);
    std::vector<unsigned char> surfaces(static_cast<std::size_t>(96) * 54, 0);
    std::size_t count = 0;
    for (std::size_t i = 0; i < surfaces.size(); ++i) {
      const float a = standard.transmittance.pixels[i * 4];
      const float b = inf.transmittance.pixels[i * 4];
      surfaces[i] = std::abs(a - b) <= 1e-3f * a ? 1 : 0;
      count += surfaces[i];
    }
    EXPECT_GT(count, surfaces.size() / 2) << "most pixels of the scene show a surface";
    const ErrorStats stats = compareRgb(inf.scattering, standard.scattering, &surfaces);
    EXPECT_LE(stats.relativeRmse, 0.005) << describe(stats);
    EXPECT_EQ(stats.nonFinite, 0u);
  }
  expectNoValidationMessages();
}

// Model only what the scene requires (DESIGN.md): a vacuum records no scattering work; an
// absorbing medium that does not scatter still attenuates.
TEST(PassesRecorded, VacuumAndAbsorptionOnly) {
  host::Scene scene = loadTestScene("analytic-mixed");
  for (host::MediumComponent& c : scene.medium) {
    c.scattering = glm::dvec3(0.0);
    c.absorption = glm::dvec3(0.0);
  }
  const samples::RenderResult vacuum = renderWithAovs(scene, smallOptions());
  EXPECT_EQ(vacuum.stats.passesRecorded, std::vector<std::string>{"aov_clear"});
  EXPECT_EQ(vacuum.stats.technique, Technique::None);
  for (std::size_t i = 0; i < vacuum.scattering.pixels.size(); i += 4) {
    ASSERT_EQ(vacuum.scattering.pixels[i], 0.0f);
    ASSERT_EQ(vacuum.transmittance.pixels[i], 1.0f);
  }

  for (host::MediumComponent& c : scene.medium) c.absorption = glm::dvec3(0.05);
  const samples::RenderResult absorbing = renderWithAovs(scene, smallOptions());
  EXPECT_EQ(absorbing.stats.passesRecorded,
            (std::vector<std::string>{"reference_scattering", "composite", "aov_output"}));
  double minT = 1.0;
  for (std::size_t i = 0; i < absorbing.scattering.pixels.size(); i += 4) {
    ASSERT_EQ(absorbing.scattering.pixels[i], 0.0f);
    minT = std::min(minT, static_cast<double>(absorbing.transmittance.pixels[i]));
  }
  EXPECT_LT(minT, 0.9);
  expectNoValidationMessages();
}

TEST(Profiles, EveryProfileRunsAndSaysWhichTechnique) {
  const host::Scene scene = loadTestScene("analytic-spheres");
  for (Profile profile : {Profile::Reference, Profile::High, Profile::Balanced, Profile::Performance, Profile::Auto}) {
    samples::RenderOptions options = smallOptions(32, 18);
    options.profile = profile;
    const samples::RenderResult result = renderWithAovs(scene, options);
    EXPECT_EQ(result.stats.requestedProfile, profile);
    EXPECT_EQ(result.stats.technique, profile == Profile::Reference ? Technique::Reference : Technique::Epipolar);
    EXPECT_NE(result.stats.techniqueNote.find(profile == Profile::Reference ? "brute force" : "epipolar"),
              std::string::npos)
        << result.stats.techniqueNote;
  }
  expectNoValidationMessages();
}

}  // namespace
}  // namespace tyndall::test

namespace tyndall::test {
namespace {

// Tiny and odd output extents: every pixel is written, nothing is read out of bounds.
TEST(Extents, TinyAndOddSizes) {
  const host::Scene scene = loadTestScene("analytic-spheres");
  for (auto [w, h] : {std::pair{1u, 1u}, std::pair{3u, 7u}, std::pair{13u, 5u}}) {
    SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h));
    samples::RenderOptions options = smallOptions(w, h);
    const samples::RenderResult result = renderWithAovs(scene, options);
    ASSERT_EQ(result.scattering.width, w);
    ASSERT_EQ(result.scattering.height, h);
    analytic::RgbImage reference;
    analytic::RgbImage transmittance;
    std::string error;
    ASSERT_TRUE(analytic::renderAnalytic(scene, w, h, reference, transmittance, error)) << error;
    const ErrorStats stats = compareRgb(result.scattering, reference.rgb);
    EXPECT_EQ(stats.nonFinite, 0u);
    EXPECT_LE(stats.relativeRmse, 0.02) << describe(stats);
  }
  expectNoValidationMessages();
}

}  // namespace
}  // namespace tyndall::test
