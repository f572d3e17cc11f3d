// Frames in flight, timings, resize, back-buffer formats, depth conventions, and the passes a
// frame records when the medium needs less.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "test_support.h"
#include "profiles.h"
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
      // The render copies the AOVs in its last frame only (the frames before run as an engine's).
      const bool last = i + 1 == result.timings.size();
      ASSERT_EQ(t.passes.size(), last ? 3u : 2u);
      EXPECT_EQ(t.passes[0].name, "reference_scattering");
      EXPECT_EQ(t.passes[1].name, "composite");
      if (last) {
        EXPECT_EQ(t.passes[2].name, "aov_output");
      }
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
// absorbing medium that does not scatter runs no technique either (L_in is cleared) and still
// attenuates.
TEST(PassesRecorded, VacuumAndAbsorptionOnly) {
  host::Scene scene = loadTestScene("analytic-mixed");
  for (host::MediumComponent& c : scene.medium) {
    c.scattering = glm::dvec3(0.0);
    c.absorption = glm::dvec3(0.0);
  }
  const samples::RenderResult vacuum = renderWithAovs(scene, smallOptions());
  EXPECT_EQ(vacuum.stats.passesRecorded, std::vector<std::string>{"aov_clear"});
  EXPECT_EQ(vacuum.stats.technique, Technique::None);
  EXPECT_EQ(vacuum.stats.composite, CompositePath::None);
  EXPECT_EQ(vacuum.stats.dispatches, 0u);  // the AOVs are cleared, nothing computed
  EXPECT_GT(vacuum.stats.barriers, 0u);
  for (std::size_t i = 0; i < vacuum.scattering.pixels.size(); i += 4) {
    ASSERT_EQ(vacuum.scattering.pixels[i], 0.0f);
    ASSERT_EQ(vacuum.transmittance.pixels[i], 1.0f);
  }

  for (host::MediumComponent& c : scene.medium) c.absorption = glm::dvec3(0.05);
  const samples::RenderResult absorbing = renderWithAovs(scene, smallOptions());
  EXPECT_EQ(absorbing.stats.passesRecorded,
            (std::vector<std::string>{"scattering_clear", "composite", "aov_output"}));
  EXPECT_EQ(absorbing.stats.technique, Technique::None);
  EXPECT_EQ(absorbing.stats.techniqueChange, TechniqueChange::NothingScatters) << absorbing.stats.techniqueNote;
  // T's AOV pass, and the composite where it runs in compute.
  EXPECT_EQ(absorbing.stats.dispatches, absorbing.stats.composite == CompositePath::Compute ? 2u : 1u);
  double minT = 1.0;
  for (std::size_t i = 0; i < absorbing.scattering.pixels.size(); i += 4) {
    ASSERT_EQ(absorbing.scattering.pixels[i], 0.0f);
    minT = std::min(minT, static_cast<double>(absorbing.transmittance.pixels[i]));
  }
  EXPECT_LT(minT, 0.9);
  expectNoValidationMessages();
}

// Stats::dispatches and Stats::barriers count what a frame recorded: the Reference is one dispatch
// (plus T's AOV pass and a compute composite), the epipolar profiles a chain of passes whose every
// dispatch follows a barrier. For a directional light the chain is short enough that launches and
// barriers do not set a GPU's time: with the composite (either path) and without the AOVs' pass,
// Performance records at most 8 dispatches, High and Balanced at most 12.
TEST(Profiles, StatsCountTheDispatchesAndBarriersRecorded) {
  const host::Scene scene = loadTestScene("analytic-spheres");
  for (Profile profile : {Profile::Reference, Profile::High, Profile::Balanced, Profile::Performance}) {
    samples::RenderOptions options = smallOptions(32, 18);
    options.profile = profile;
    const samples::RenderResult r = renderWithAovs(scene, options);
    const std::uint32_t composite = r.stats.composite == CompositePath::Compute ? 1u : 0u;
    const auto& passes = r.stats.passesRecorded;
    const auto aov = static_cast<std::uint32_t>(std::count(passes.begin(), passes.end(), "aov_output"));
    // The AOVs' pass dispatches T, and L_in where the target is not full-float at full resolution
    // (its AOV is then written into a full-float image first).
    const bool linThroughAovImage = r.stats.scatteringFormat != VK_FORMAT_R32G32B32A32_SFLOAT ||
                                    r.stats.scatteringResolution != ScatteringResolution::Full;
    const std::uint32_t aovDispatches = aov * (linThroughAovImage ? 2u : 1u);
    const std::uint32_t effect =
        r.stats.dispatches - aovDispatches + (r.stats.composite == CompositePath::Fragment ? 1u : 0u);
    std::printf("[ passes ] %s: %u dispatches, %u barriers, composite %s; the effect's passes: %u\n",
                to_string(profile), r.stats.dispatches, r.stats.barriers, to_string(r.stats.composite), effect);
    EXPECT_EQ(aov, 1u);
    if (profile == Profile::Reference) {
      EXPECT_EQ(r.stats.dispatches, 2u + composite);
    } else {
      EXPECT_GT(r.stats.dispatches, 4u + composite) << to_string(profile);
      EXPECT_LE(effect, profile == Profile::Performance ? 8u : 12u) << to_string(profile);
    }
    EXPECT_GE(r.stats.barriers, r.stats.dispatches) << to_string(profile);
  }
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
    EXPECT_EQ(result.stats.requestedTechnique, result.stats.technique);
    EXPECT_EQ(result.stats.techniqueChange, TechniqueChange::None);
    EXPECT_FALSE(result.stats.techniqueSetByFrame);
    EXPECT_FALSE(result.stats.techniqueNote.empty());
  }
  expectNoValidationMessages();
}

// The profile table has a row per kind of light (plugin/src/profiles.h): a spot or point light runs
// the local row, a directional light the directional one, and the stats say which settings ran.
TEST(Profiles, EachKindOfLightRunsItsOwnRow) {
  host::Scene scene = loadTestScene("spot-lamp");
  for (const auto& [type, row] : {std::pair{host::LightType::Spot, LightClass::Local},
                                  std::pair{host::LightType::Point, LightClass::Local},
                                  std::pair{host::LightType::Directional, LightClass::Directional}}) {
    scene.light.type = type;
    for (Profile profile : {Profile::High, Profile::Balanced, Profile::Performance}) {
      samples::RenderOptions options = smallOptions(32, 18);
      options.profile = profile;
      const samples::RenderResult result = renderWithAovs(scene, options);
      EXPECT_EQ(result.stats.technique, Technique::Epipolar);
      ASSERT_TRUE(result.stats.epipolar);
      const EpipolarSettings& expected = profileChoice(profile, row).epipolar;
      EXPECT_EQ(result.stats.epipolar->slices, expected.slices) << to_string(profile) << ": " << result.stats.techniqueNote;
      EXPECT_EQ(result.stats.epipolar->samplesPerSlice, expected.samplesPerSlice) << to_string(profile);
    }
  }
  expectNoValidationMessages();
}

// Switches the profile (and now and then the technique) of the effect it wraps every frame, and
// keeps what each frame asked for and what ran.
class SwitchingEffect final : public host::PostProcessEffect {
 public:
  struct Frame {
    Profile profile;
    Technique technique;  // asked for: None lets the profile decide
    Stats stats;
  };
  explicit SwitchingEffect(samples::TyndallEffect& inner) : inner_(inner) {}

  bool record(VkCommandBuffer cmd, const host::PostProcessInputs& inputs, std::string& error) override {
    static constexpr Profile kCycle[] = {Profile::High, Profile::Reference, Profile::Balanced, Profile::Performance,
                                         Profile::Auto};
    const std::size_t n = frames.size();
    const Frame frame{kCycle[n % std::size(kCycle)], n % 7 == 6 ? Technique::Prefiltered : Technique::None, {}};
    inner_.setProfile(frame.profile);
    inner_.setTechnique(frame.technique);
    if (!inner_.record(cmd, inputs, error)) return false;
    frames.push_back(frame);
    frames.back().stats = inner_.context().stats();
    return true;
  }
  bool resize(VkExtent2D extent, std::string& error) override { return inner_.resize(extent, error); }

  std::vector<Frame> frames;

 private:
  samples::TyndallEffect& inner_;
};

// Run-time switching: the profile changes every frame for 100 frames, two frames in flight, one
// context whose pipelines were all built at creation. No frame compiles a pipeline (the context
// would say so through its callback), every frame runs what its profile or technique names, and
// synchronization validation sees nothing, and after the first lap nothing is allocated (the
// sample textures of each profile are kept and reused while other profiles' frames are in flight).
// A renderer of analytic-spheres at 64×36 (256² map, two frames in flight) and a Tyndall effect for
// it, not yet in its post-process stack.
struct SmallFrames {
  host::RenderSettings settings;
  std::unique_ptr<host::Renderer> renderer;
  std::unique_ptr<samples::TyndallEffect> effect;
};

SmallFrames smallFrames(PipelineCreation pipelines) {
  SmallFrames s;
  s.settings.width = 64;
  s.settings.height = 36;
  s.settings.shadowMapSize = 256;
  s.settings.framesInFlight = 2;
  std::string error;
  host::Device& device = validatedDevice();
  s.renderer = host::Renderer::create(device, loadTestScene("analytic-spheres"), s.settings, error);
  EXPECT_TRUE(s.renderer) << error;
  s.effect = samples::TyndallEffect::create(device, s.settings, Profile::Balanced, error, pipelines);
  EXPECT_TRUE(s.effect) << error;
  return s;
}

TEST(Profiles, SwitchingEveryFrameCompilesNothingAndStaysValid) {
  SmallFrames small = smallFrames(PipelineCreation::AtCreate);
  ASSERT_TRUE(small.renderer && small.effect);
  host::Renderer* renderer = small.renderer.get();
  samples::TyndallEffect* effect = small.effect.get();
  std::string error;
  SwitchingEffect switching(*effect);
  renderer->addPostProcess(&switching);
  for (int frame = 0; frame < 100; ++frame) ASSERT_TRUE(renderer->renderFrame(error)) << "frame " << frame << ": " << error;
  renderer->waitIdle();

  ASSERT_EQ(switching.frames.size(), 100u);
  for (std::size_t i = 0; i < switching.frames.size(); ++i) {
    const SwitchingEffect::Frame& f = switching.frames[i];
    SCOPED_TRACE("frame " + std::to_string(i) + ", " + to_string(f.profile));
    EXPECT_EQ(f.stats.frameIndex, i + 1);
    EXPECT_EQ(f.stats.requestedProfile, f.profile);
    const Technique expected = f.technique != Technique::None ? f.technique
                               : f.profile == Profile::Reference ? Technique::Reference
                                                                 : Technique::Epipolar;
    EXPECT_EQ(f.stats.technique, expected) << f.stats.techniqueNote;
  }
  for (const std::string& message : effect->messages()) {
    EXPECT_EQ(message.find("compiled during record"), std::string::npos) << message;
  }
  // Once every profile and the prefiltered technique have run (the first 7 frames), nothing more is
  // allocated or freed: each profile's textures are kept and reused.
  const std::uint64_t settled = switching.frames[7].stats.deviceMemoryBytes;
  EXPECT_GT(settled, 0u);
  for (std::size_t i = 7; i < switching.frames.size(); ++i) {
    EXPECT_EQ(switching.frames[i].stats.deviceMemoryBytes, settled) << "frame " << i;
  }
  expectNoValidationMessages();
}

// Textures a technique retired (a new parameter's size) are released by the frames that follow,
// whichever technique runs them: a context that stops running the prefiltered technique after
// changing its map size does not keep the old maps.
TEST(Profiles, RetiredTexturesAreReleasedWhicheverTechniqueRuns) {
  SmallFrames small = smallFrames(PipelineCreation::OnFirstUse);
  ASSERT_TRUE(small.renderer && small.effect);
  host::Renderer* renderer = small.renderer.get();
  samples::TyndallEffect* effect = small.effect.get();
  std::string error;
  renderer->addPostProcess(effect);
  effect->setTechnique(Technique::Prefiltered);
  PrefilteredSettings maps;
  maps.rows = maps.columns = 64;
  effect->setPrefilteredSettings(maps);
  ASSERT_TRUE(renderer->renderFrame(error)) << error;
  maps.rows = maps.columns = 128;  // retires the 64 × 64 maps
  effect->setPrefilteredSettings(maps);
  ASSERT_TRUE(renderer->renderFrame(error)) << error;
  const std::uint64_t held = effect->context().stats().deviceMemoryBytes;
  effect->setTechnique(Technique::Reference);
  for (std::uint32_t frame = 0; frame <= small.settings.framesInFlight; ++frame) {
    ASSERT_TRUE(renderer->renderFrame(error)) << error;
  }
  renderer->waitIdle();
  EXPECT_EQ(effect->context().stats().technique, Technique::Reference);
  EXPECT_LT(effect->context().stats().deviceMemoryBytes, held);
  expectNoValidationMessages();
}

// Profile::Auto against the plugin's own timestamps: budgets that force each profile. One context
// throughout (Auto keeps what it measured when the budget changes, as in an engine). An unbounded
// budget must climb to High and a budget no frame fits must end on Performance; on the way down Auto
// measures High and Balanced itself, and the third budget lies between those two estimates, so that
// Auto must settle on Balanced. The middle budget comes from Auto's own estimates, not from separate
// runs: lavapipe's frame times drift by 20-40% between runs on a shared machine, and the spec is
// the most accurate profile whose time *as Auto measured it* fits.
TEST(Profiles, AutoFitsTheBudget) {
  // pillars at 160×90 with a 4096² map: the min/max trees and the march dominate, and High has
  // twice Balanced's slices (1.6-2.5x the time on lavapipe; at 320×180 with a 2048² map the costs
  // per pixel leave 1.45-1.6x).
  const host::Scene scene = loadTestScene("pillars");
  samples::RenderOptions o = smallOptions(160, 90);
  o.shadowMapSize = 4096;
  // Each profile's pipelines run once first: lavapipe builds a shader's machine code at its first
  // dispatch, inside the GPU timestamps, and Auto's first Balanced frames would carry that cost.
  o.frames = 3;
  for (Profile p : {Profile::High, Profile::Balanced, Profile::Performance}) {
    o.profile = p;
    renderWithSharedContext(scene, o);
  }
  o.profile = Profile::Auto;
  o.frames = 40;
  AutoEstimates estimates;
  const auto estimateOf = [&](Profile p) {
    return p == Profile::High ? estimates.high : p == Profile::Balanced ? estimates.balanced : estimates.performance;
  };
  auto run = [&](double budget, Profile expected) {
    o.autoBudgetMilliseconds = static_cast<float>(budget);
    const samples::RenderResult r = renderWithSharedContext(scene, o);
    estimates = r.stats.autoEstimateMilliseconds;
    std::printf("[ auto ] budget %.3g ms -> %s: %s; estimates high %.3g, balanced %.3g, performance %.3g ms\n",
                budget, to_string(r.stats.profileUsed), r.stats.techniqueNote.c_str(), estimates.high.value_or(-1.0),
                estimates.balanced.value_or(-1.0), estimates.performance.value_or(-1.0));
    EXPECT_EQ(r.stats.requestedProfile, Profile::Auto);
    EXPECT_EQ(r.stats.profileUsed, expected) << "budget " << budget << " ms: " << r.stats.techniqueNote;
    // The profile it runs has been measured under Auto, and the stats say so.
    ASSERT_TRUE(estimateOf(expected).has_value());
    EXPECT_GT(*estimateOf(expected), 0.0);
  };
  // The estimates are the context's own timestamps of a few frames each; on a CPU driver another
  // test on the other core can inflate one profile's window (CI measured Balanced 43.7 ms, then
  // 53.2 ms, in one run), so the pair is measured again, at most twice, while it does not show
  // High clearly dearer (below). Every run's assertions hold each time.
  double high = 0.0;
  double balanced = 0.0;
  for (int attempt = 0; attempt < 3 && !(high > 1.3 * balanced && balanced > 0.0); ++attempt) {
    if (attempt > 0) std::printf("[ auto ] high %.3g ms vs balanced %.3g ms: measured again\n", high, balanced);
    run(1e6, Profile::High);
    run(1e-3, Profile::Performance);
    high = estimates.high.value_or(0.0);
    balanced = estimates.balanced.value_or(0.0);
  }
  ASSERT_GT(balanced, 0.0) << "Auto passed Balanced on its way down without measuring it";
  // The middle budget needs High clearly dearer than Balanced. Auto climbs back to a profile it
  // measured within 80% of the budget (AutoProfile::kClimbShare), and 80% of this budget lies
  // between the two estimates, so from Performance it must climb to Balanced and no further
  // whatever the ratio; once there, Balanced's new frames must fit the budget, which is
  // sqrt(High / Balanced) / 0.8 times its estimate: at least 1.43x with the ratio asserted here.
  // (Measured 1.6-2.0x in one context on lavapipe; the ratio of the slice counts is 2.)
  ASSERT_GT(high, 1.3 * balanced);
  const double middle = std::sqrt(high * balanced) / 0.8;
  run(middle, Profile::Balanced);
  EXPECT_LE(estimates.balanced.value_or(1e30), middle) << "Balanced, measured again, no longer fits";
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
