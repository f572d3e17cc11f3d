// Every kind of invalid frame DESIGN.md lists, and every technique setting out of its range: the
// status says why, nothing is recorded (the back buffer is exactly what the host rendered), and no
// validation message appears.
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "test_support.h"
#include "tyndall_effect.h"

namespace tyndall::test {
namespace {

struct BadCase {
  std::string name;
  Status expected;
  std::function<void(FrameDesc&, samples::FrameStorage&)> mutate;
  /// When set, the message must begin with it (the name of the field at fault).
  std::string messageStart;
};

// A post-process that builds the frame an engine would, breaks it, and records it.
class BreakingEffect final : public host::PostProcessEffect {
 public:
  std::unique_ptr<Context> context;
  const BadCase* badCase = nullptr;
  Outcome outcome;

  bool record(VkCommandBuffer cmd, const host::PostProcessInputs& inputs, std::string&) override {
    samples::FrameStorage storage;
    FrameDesc frame = samples::makeFrameDesc(inputs, Profile::Reference, storage);
    if (badCase != nullptr) badCase->mutate(frame, storage);
    outcome = context->record(cmd, frame);
    return true;  // the host goes on with its frame
  }
  bool resize(VkExtent2D, std::string&) override { return true; }
};

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

std::vector<BadCase> badCases() {
  using F = FrameDesc;
  using S = samples::FrameStorage;
  const Status invalid = Status::InvalidArgument;
  return {
      {"NaN scattering", invalid, [](F&, S& s) { s.medium[0].scattering[1] = kNaN; }},
      {"Inf absorption", invalid, [](F&, S& s) { s.medium[0].absorption[0] = kInf; }},
      {"negative scattering", invalid, [](F&, S& s) { s.medium[0].scattering[2] = -0.1f; }},
      {"negative absorption", invalid, [](F&, S& s) { s.medium[0].absorption[2] = -1e-6f; }},
      {"g out of range", invalid, [](F&, S& s) {
         s.medium[0].phase = PhaseFunction::HenyeyGreenstein;
         s.medium[0].g = 1.0f;
       }},
      {"no medium component", invalid, [](F& f, S&) { f.medium = {}; }},
      {"five medium components", invalid, [](F& f, S& s) {
         s.medium.assign(5, s.medium[0]);
         f.medium = s.medium;
       }},
      {"NaN light colour", invalid, [](F& f, S&) { f.light.color[0] = kNaN; }},
      {"negative intensity", invalid, [](F& f, S&) { f.light.intensity = -1.0f; }},
      {"zero light direction", invalid, [](F& f, S&) { f.light.direction = {0.0f, 0.0f, 0.0f}; }},
      {"spot cone inner > outer", invalid, [](F& f, S&) {
         f.light.type = LightType::Spot;
         f.light.innerConeRadians = 0.5f;
         f.light.outerConeRadians = 0.4f;
       }},
      {"no shadow map", invalid, [](F& f, S&) { f.shadowMaps = {}; }},
      {"translucent layer count without layers", invalid, [](F&, S& s) { s.shadowMaps[0].translucentLayerCount = 2; },
       "shadowMaps[0].translucentLayers and translucentLayerCount go together"},
      {"translucent layers of a depth format", Status::UnsupportedFormat, [](F&, S& s) {
         s.shadowMaps[0].translucentLayers = s.shadowMaps[0].depth;
         s.shadowMaps[0].translucentLayerCount = 2;
       }, "shadowMaps[0].translucentLayers must be R32G32_SFLOAT"},
      {"nine translucent layers", invalid, [](F&, S& s) {
         s.shadowMaps[0].translucentLayers = s.shadowMaps[0].depth;
         s.shadowMaps[0].translucentLayerCount = 9;
       }, "shadowMaps[0].translucentLayerCount must be at most 8"},
      {"cascades with different translucent layer counts", invalid, [](F& f, S& s) {
         s.shadowMaps.assign(2, s.shadowMaps[0]);
         s.shadowMaps[0].viewDepthFar = 10.0f;
         s.shadowMaps[1].viewDepthNear = 10.0f;
         s.shadowMaps[1].viewDepthFar = 50.0f;
         s.shadowMaps[1].translucentLayers = s.shadowMaps[0].depth;
         s.shadowMaps[1].translucentLayerCount = 2;
         f.shadowMaps = s.shadowMaps;
       }, "shadowMaps[1].translucentLayerCount must equal shadowMaps[0]'s"},
      {"point light with one shadow map", invalid, [](F& f, S&) { f.light.type = LightType::Point; }},
      {"five cascades", invalid, [](F& f, S& s) {
         s.shadowMaps.assign(5, s.shadowMaps[0]);
         f.shadowMaps = s.shadowMaps;
       }, "shadowMaps: a directional light needs 1 to 4"},
      {"cascades that overlap", invalid, [](F& f, S& s) {
         s.shadowMaps.assign(2, s.shadowMaps[0]);
         s.shadowMaps[0].viewDepthFar = 10.0f;
         s.shadowMaps[1].viewDepthNear = 8.0f;
         s.shadowMaps[1].viewDepthFar = 50.0f;
         f.shadowMaps = s.shadowMaps;
       }, "shadowMaps[1].viewDepthNear must equal shadowMaps[0].viewDepthFar"},
      {"cascades out of order", invalid, [](F& f, S& s) {
         s.shadowMaps.assign(2, s.shadowMaps[0]);
         s.shadowMaps[0].viewDepthNear = 10.0f;
         s.shadowMaps[0].viewDepthFar = 50.0f;
         s.shadowMaps[1].viewDepthNear = 50.0f;
         s.shadowMaps[1].viewDepthFar = 10.0f;
         f.shadowMaps = s.shadowMaps;
       }, "shadowMaps[1].viewDepthNear/viewDepthFar"},
      {"cascade without a range", invalid, [](F& f, S& s) {
         s.shadowMaps.assign(3, s.shadowMaps[0]);
         f.shadowMaps = s.shadowMaps;
       }, "shadowMaps[0].viewDepthNear/viewDepthFar"},
      {"cascades on a spot light", invalid, [](F& f, S& s) {
         f.light.type = LightType::Spot;
         s.shadowMaps.assign(2, s.shadowMaps[0]);
         f.shadowMaps = s.shadowMaps;
       }, "shadowMaps: a spot light needs exactly 1"},
      {"light-colour texture with cascades", Status::UnsupportedFeature, [](F& f, S& s) {
         s.shadowMaps.assign(2, s.shadowMaps[0]);
         s.shadowMaps[0].viewDepthFar = 10.0f;
         s.shadowMaps[1].viewDepthNear = 10.0f;
         s.shadowMaps[1].viewDepthFar = 50.0f;
         f.shadowMaps = s.shadowMaps;
         f.lightColor = f.color;
       }, "lightColor: a light with cascades"},
      {"zero depth extent", invalid, [](F& f, S&) { f.depth.extent = {0, 0}; }},
      {"null depth view", invalid, [](F& f, S&) { f.depth.view = VK_NULL_HANDLE; }},
      {"null back buffer", invalid, [](F& f, S&) { f.color.image = VK_NULL_HANDLE; }},
      {"null shadow map", invalid, [](F&, S& s) { s.shadowMaps[0].depth.image = VK_NULL_HANDLE; }},
      {"mismatched back buffer size", invalid, [](F& f, S&) { f.color.extent.width += 1; }},
      {"mismatched depth size", invalid, [](F& f, S&) { f.depth.extent.height += 1; }},
      {"undefined depth layout", invalid, [](F& f, S&) { f.depth.layout = VK_IMAGE_LAYOUT_UNDEFINED; }},
      {"colour format as depth", Status::UnsupportedFormat, [](F& f, S&) { f.depth.format = VK_FORMAT_R8G8B8A8_UNORM; }},
      {"depth format as back buffer", Status::UnsupportedFormat, [](F& f, S&) { f.color.format = VK_FORMAT_D32_SFLOAT; }},
      {"non-square shadow map", invalid, [](F&, S& s) { s.shadowMaps[0].depth.extent.width /= 2; }},
      {"near >= far", invalid, [](F& f, S&) {
         // Standard-Z perspective with near 0.1 and far −5: the far plane behind the camera.
         const float n = 0.1f, fa = -5.0f;
         f.camera.projection = {1, 0, 0, 0, 0, -1, 0, 0, 0, 0, fa / (n - fa), -1, 0, 0, fa * n / (n - fa), 0};
       }},
      {"near == far", invalid, [](F& f, S&) {
         // The standard-Z formula with near = far divides by zero.
         const float n = 1.0f, fa = 1.0f;
         f.camera.projection = {1, 0, 0, 0, 0, -1, 0, 0, 0, 0, fa / (n - fa), -1, 0, 0, fa * n / (n - fa), 0};
       }},
      {"singular projection", invalid, [](F& f, S&) { f.camera.projection = Mat4{}; }},
      {"orthographic projection", invalid, [](F& f, S&) {
         f.camera.projection = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
       }},
      {"NaN view matrix", invalid, [](F& f, S&) { f.camera.view[5] = kNaN; }},
      {"singular view matrix", invalid, [](F& f, S&) { f.camera.view = Mat4{}; }},
      {"rank-deficient view matrix", invalid,
       [](F& f, S&) {
         for (int row = 0; row < 4; ++row) f.camera.view[4 + row] = f.camera.view[row];  // column 1 = column 0
       }},
      {"singular shadow matrix", invalid, [](F&, S& s) { s.shadowMaps[0].worldToShadowClip = Mat4{}; }},
      {"zero infinite-far sky distance", invalid, [](F& f, S&) {
         // Standard-Z with the far plane at infinity.
         f.camera.projection = {1, 0, 0, 0, 0, -1, 0, 0, 0, 0, -1, -1, 0, 0, -0.1f, 0};
         f.camera.infiniteFarSkyDistance = 0.0f;
       }},
      {"light-colour texture in a depth format", Status::UnsupportedFormat, [](F& f, S&) { f.lightColor = f.depth; }},
      {"light-colour texture with a null view", invalid, [](F& f, S&) {
         f.lightColor = f.color;
         f.lightColor.view = VK_NULL_HANDLE;
       }},
      {"light-colour texture for a point light", Status::UnsupportedFeature, [](F& f, S& s) {
         f.light.type = LightType::Point;
         s.shadowMaps.assign(6, s.shadowMaps[0]);
         f.shadowMaps = s.shadowMaps;
         f.lightColor = f.color;
       }},
      {"eight additional lights", invalid, [](F& f, S& s) {
         s.additionalLights.assign(kMaxLights, LightInput{f.light, f.shadowMaps, {}});
         f.additionalLights = s.additionalLights;
       }, "additionalLights holds 8"},
      {"additional light with a NaN intensity", invalid, [](F& f, S& s) {
         s.additionalLights.assign(2, LightInput{f.light, f.shadowMaps, {}});
         s.additionalLights[1].light.intensity = kNaN;
         f.additionalLights = s.additionalLights;
       }, "additionalLights[1].light.intensity"},
      {"additional point light with one shadow map", invalid, [](F& f, S& s) {
         s.additionalLights.assign(1, LightInput{f.light, f.shadowMaps, {}});
         s.additionalLights[0].light.type = LightType::Point;
         s.additionalLights[0].light.position = {0.0f, 5.0f, 0.0f};
         f.additionalLights = s.additionalLights;
       }, "additionalLights[0].shadowMaps"},
      {"additional light with a singular shadow matrix", invalid, [](F& f, S& s) {
         s.additionalShadowMaps.assign(1, {f.shadowMaps[0]});
         s.additionalShadowMaps[0][0].worldToShadowClip = Mat4{};
         s.additionalLights.assign(1, LightInput{f.light, s.additionalShadowMaps[0], {}});
         f.additionalLights = s.additionalLights;
       }, "additionalLights[0].shadowMaps[0].worldToShadowClip"},
      {"additional light's colour texture in a depth format", Status::UnsupportedFormat, [](F& f, S& s) {
         s.additionalLights.assign(1, LightInput{f.light, f.shadowMaps, f.depth});
         f.additionalLights = s.additionalLights;
       }, "additionalLights[0].lightColor"},
      {"debug view without an image", invalid, [](F& f, S&) { f.debugView = DebugView::EpipolarSamples; }},
      {"unknown debug view", invalid, [](F& f, S&) {
         f.debugView = static_cast<DebugView>(7);
         f.debugOutput = f.scatteringOutput;
       }},
      {"AOV with zero extent", invalid, [](F& f, S&) { f.scatteringOutput.extent = {0, 0}; }},
      {"zero auto budget", invalid, [](F& f, S&) { f.autoBudgetMilliseconds = 0.0f; }},
      {"unknown technique", invalid, [](F& f, S&) { f.technique = static_cast<Technique>(99); }},
      {"epipolar slices out of range", invalid, [](F& f, S&) {
         static EpipolarSettings settings;
         settings.slices = 4;
         f.technique = Technique::Epipolar;
         f.epipolar = &settings;
       }},
      {"NaN epipolar bilateral threshold", invalid, [](F& f, S&) {
         static EpipolarSettings settings;
         settings.bilateralDepthThreshold = kNaN;
         f.epipolar = &settings;
       }},
  };
}

// Every EpipolarSettings field out of its range, in a frame that asks for the epipolar technique:
// the message names the field.
std::vector<BadCase> badEpipolarSettings() {
  const std::vector<std::pair<const char*, std::function<void(EpipolarSettings&)>>> fields = {
      {"epipolar.slices", [](EpipolarSettings& s) { s.slices = 7; }},
      {"epipolar.slices", [](EpipolarSettings& s) { s.slices = 4097; }},
      {"epipolar.samplesPerSlice", [](EpipolarSettings& s) { s.samplesPerSlice = 1; }},
      {"epipolar.samplesPerSlice", [](EpipolarSettings& s) { s.samplesPerSlice = 4097; }},
      {"epipolar.epipoleDensity", [](EpipolarSettings& s) { s.epipoleDensity = 0.5f; }},
      {"epipolar.bilateralDepthThreshold", [](EpipolarSettings& s) { s.bilateralDepthThreshold = 0.0f; }},
      {"epipolar.fixupWeightThreshold", [](EpipolarSettings& s) { s.fixupWeightThreshold = 1.5f; }},
      {"epipolar.sliceContrastThreshold", [](EpipolarSettings& s) { s.sliceContrastThreshold = 0.0f; }},
      {"epipolar.sliceContrastThreshold", [](EpipolarSettings& s) { s.sliceContrastThreshold = kNaN; }},
      {"epipolar.initialSampleStep", [](EpipolarSettings& s) { s.initialSampleStep = 0; }},
      {"epipolar.refinementThreshold", [](EpipolarSettings& s) { s.refinementThreshold = -0.1f; }},
      {"epipolar.intensityRefinementThreshold", [](EpipolarSettings& s) { s.intensityRefinementThreshold = 2.0f; }},
      {"epipolar.maxTreeStep", [](EpipolarSettings& s) { s.maxTreeStep = 3; }},
      {"epipolar.maxTreeStep", [](EpipolarSettings& s) { s.maxTreeStep = 8192; }},
      {"epipolar.epipoleFixupRadius", [](EpipolarSettings& s) { s.epipoleFixupRadius = 300.0f; }},
      {"epipolar.epipoleFixupHeightFraction", [](EpipolarSettings& s) { s.epipoleFixupHeightFraction = -0.01f; }},
      {"epipolar.fixupSteps", [](EpipolarSettings& s) { s.fixupSteps = 257; }},
      {"epipolar.coloredStep", [](EpipolarSettings& s) { s.coloredStep = 0; }},
      {"epipolar.coloredStep", [](EpipolarSettings& s) { s.coloredStep = 24; }},
      {"epipolar.resolution", [](EpipolarSettings& s) { s.resolution = static_cast<ScatteringResolution>(3); }},
  };
  std::vector<BadCase> cases;
  for (const auto& [field, mutate] : fields) {
    auto settings = std::make_shared<EpipolarSettings>();
    mutate(*settings);
    cases.push_back({std::string("bad ") + field, Status::InvalidArgument,
                     [settings](FrameDesc& f, samples::FrameStorage&) {
                       f.technique = Technique::Epipolar;
                       f.epipolar = settings.get();
                     },
                     field});
  }
  return cases;
}

TEST(BadInputs, EachCaseRecordsNothingAndSaysWhy) {
  const host::Scene scene = loadTestScene("analytic-mixed");
  host::RenderSettings settings;
  settings.width = 32;
  settings.height = 18;
  settings.shadowMapSize = 256;
  settings.aovImages = true;
  std::string error;
  host::Device& device = validatedDevice();

  // What the host renders without any post-process.
  std::unique_ptr<host::Renderer> plainRenderer = host::Renderer::create(device, scene, settings, error);
  ASSERT_TRUE(plainRenderer) << error;
  ASSERT_TRUE(plainRenderer->renderFrame(error)) << error;
  plainRenderer->waitIdle();
  host::ImageRgba32f plain;
  ASSERT_TRUE(plainRenderer->readBackBuffer(plain, error)) << error;

  std::unique_ptr<host::Renderer> renderer = host::Renderer::create(device, scene, settings, error);
  ASSERT_TRUE(renderer) << error;
  BreakingEffect effect;
  {
    Result<std::unique_ptr<Context>> created = Context::create(samples::contextDescFor(device, settings));
    ASSERT_TRUE(created.ok()) << created.outcome().message;
    effect.context = std::move(created).value();
  }
  renderer->addPostProcess(&effect);

  // The unbroken frame records and changes the picture: the comparison below can fail.
  ASSERT_TRUE(renderer->renderFrame(error)) << error;
  renderer->waitIdle();
  ASSERT_TRUE(effect.outcome.ok()) << effect.outcome.message;
  host::ImageRgba32f good;
  ASSERT_TRUE(renderer->readBackBuffer(good, error)) << error;
  ASSERT_GT(compareRgb(good, plain).relativeRmse, 0.01);

  std::vector<BadCase> cases = badCases();
  for (BadCase& bad : badEpipolarSettings()) cases.push_back(std::move(bad));
  for (const BadCase& bad : cases) {
    SCOPED_TRACE(bad.name);
    effect.badCase = &bad;
    const std::uint64_t framesBefore = effect.context->stats().frameIndex;
    ASSERT_TRUE(renderer->renderFrame(error)) << error;
    renderer->waitIdle();
    EXPECT_FALSE(effect.outcome.ok());
    EXPECT_EQ(effect.outcome.status, bad.expected) << to_string(effect.outcome.status) << ": " << effect.outcome.message;
    EXPECT_FALSE(effect.outcome.message.empty());
    if (!bad.messageStart.empty()) {
      EXPECT_EQ(effect.outcome.message.rfind(bad.messageStart, 0), 0u) << effect.outcome.message;
    }
    EXPECT_EQ(effect.context->stats().frameIndex, framesBefore) << "a rejected frame must not count";
    host::ImageRgba32f out;
    ASSERT_TRUE(renderer->readBackBuffer(out, error)) << error;
    EXPECT_EQ(compareRgb(out, plain).relativeMax, 0.0) << "a rejected frame must leave the back buffer alone";
    expectNoValidationMessages();
  }
}

TEST(BadInputs, ContextCreationErrors) {
  host::RenderSettings settings;
  settings.width = 16;
  settings.height = 16;
  ContextDesc desc = samples::contextDescFor(validatedDevice(), settings);
  desc.backBufferFormat = VK_FORMAT_UNDEFINED;

  ContextDesc noDevice = desc;
  noDevice.device = VK_NULL_HANDLE;
  EXPECT_EQ(Context::create(noDevice).outcome().status, Status::InvalidArgument);
  ContextDesc zeroExtent = desc;
  zeroExtent.outputExtent = {0, 16};
  EXPECT_EQ(Context::create(zeroExtent).outcome().status, Status::InvalidArgument);
  ContextDesc tooManyFrames = desc;
  tooManyFrames.maxFramesInFlight = 9;
  EXPECT_EQ(Context::create(tooManyFrames).outcome().status, Status::InvalidArgument);
  ContextDesc badFamily = desc;
  badFamily.queueFamilyIndex = 1000;
  EXPECT_EQ(Context::create(badFamily).outcome().status, Status::InvalidArgument);
  ContextDesc badFormat = desc;
  badFormat.backBufferFormat = VK_FORMAT_D32_SFLOAT;
  EXPECT_EQ(Context::create(badFormat).outcome().status, Status::UnsupportedFormat);

  Result<std::unique_ptr<Context>> created = Context::create(desc);
  ASSERT_TRUE(created.ok()) << created.outcome().message;
  EXPECT_EQ(created.outcome().status, Status::Success);
  std::unique_ptr<Context> context = std::move(created).value();
  EXPECT_EQ(context->resize({0, 0}).status, Status::InvalidArgument);
  EXPECT_EQ(context->record(VK_NULL_HANDLE, FrameDesc{}).status, Status::InvalidArgument);
  context.reset();
  expectNoValidationMessages();
}

}  // namespace
}  // namespace tyndall::test
