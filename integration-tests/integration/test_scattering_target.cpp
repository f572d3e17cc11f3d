// The L_in target's format (plugin/src/technique.h): half floats for the approximate techniques,
// full floats for the Reference; the AOVs are full floats either way.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

#include <gtest/gtest.h>

#include "test_support.h"

namespace tyndall::test {
namespace {

constexpr std::uint32_t kWidth = 160;
constexpr std::uint32_t kHeight = 90;

samples::RenderOptions smallOptions(Technique technique, Profile profile = Profile::High) {
  samples::RenderOptions options;
  options.profile = profile;
  options.technique = technique;
  options.width = kWidth;
  options.height = kHeight;
  options.pipelineCreation = PipelineCreation::OnFirstUse;
  return options;
}

// Whether a float has no more significant bits than a half float (a half float times a power of
// two: the target's value unscaled, FrameConstants::target_scale).
bool hasHalfPrecision(float value) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, &value, sizeof(bits));
  return (bits & 0x1fffu) == 0;  // float's 23 fraction bits less half's 10
}

// Each technique reports the format it wrote, and the L_in AOV is that target's content: every
// value of an approximate technique's AOV has a half float's precision, the Reference's do not;
// ContextTuning::fullFloatTargets gives the approximate techniques full floats.
TEST(ScatteringTarget, TheApproximateTechniquesWriteHalfFloatsTheReferenceFullFloats) {
  const host::Scene scene = loadTestScene("pillars");
  for (bool fullFloat : {false, true}) {
    for (Technique technique : {Technique::Reference, Technique::Epipolar, Technique::Prefiltered}) {
      samples::RenderOptions options = smallOptions(technique);
      options.fullFloatTargets = fullFloat;
      const samples::RenderResult result = renderWithAovs(scene, options);
      ASSERT_EQ(result.stats.technique, technique);
      const bool half = technique != Technique::Reference && !fullFloat;
      const std::string name = std::string(to_string(technique)) + (fullFloat ? ", full-float targets" : "");
      EXPECT_EQ(result.stats.scatteringFormat, half ? VK_FORMAT_R16G16B16A16_SFLOAT : VK_FORMAT_R32G32B32A32_SFLOAT)
          << name;
      std::size_t halves = 0, values = 0;
      for (std::size_t i = 0; i < result.scattering.pixels.size(); i += 4) {
        for (std::size_t c = 0; c < 3; ++c) {
          const float v = result.scattering.pixels[i + c];
          if (v == 0.0f) continue;
          ++values;
          halves += hasHalfPrecision(v) ? 1 : 0;
        }
      }
      ASSERT_GT(values, result.scattering.pixels.size() / 8) << name;
      if (half) {
        EXPECT_EQ(halves, values) << name;
      } else {
        EXPECT_LT(halves, values / 10) << name;
      }
    }
  }
  expectNoValidationMessages();
}

// The half-float target holds L_in scaled by a power of two chosen from the lights and the medium,
// so that its precision does not depend on the units of the lights' intensities: a light 2⁴⁰ times
// brighter or dimmer gives L_in exactly 2⁴⁰ times larger or smaller, bit for bit. Unscaled, the
// brighter frame would saturate at 65504 and the dimmer one flush to zero.
TEST(ScatteringTarget, TheTargetScaleKeepsHalfFloatsExactInAnyUnits) {
  const host::Scene scene = loadTestScene("spot-lamp");
  const samples::RenderOptions options = smallOptions(Technique::None, Profile::High);
  const samples::RenderResult unit = renderWithAovs(scene, options);
  ASSERT_EQ(unit.stats.technique, Technique::Epipolar);
  ASSERT_EQ(unit.stats.scatteringFormat, VK_FORMAT_R16G16B16A16_SFLOAT);
  ASSERT_GT(*std::max_element(unit.scattering.pixels.begin(), unit.scattering.pixels.end()), 0.0f);
  for (int exponent : {40, -40}) {
    host::Scene scaled = scene;
    scaled.light.intensity = std::ldexp(scene.light.intensity, exponent);
    const samples::RenderResult result = renderWithAovs(scaled, options);
    std::size_t differing = 0;
    for (std::size_t i = 0; i < unit.scattering.pixels.size(); i += 4) {
      for (std::size_t c = 0; c < 3; ++c) {
        differing += result.scattering.pixels[i + c] != std::ldexp(unit.scattering.pixels[i + c], exponent) ? 1 : 0;
      }
    }
    EXPECT_EQ(differing, 0u) << "intensity times 2^" << exponent;
  }
  expectNoValidationMessages();
}

}  // namespace
}  // namespace tyndall::test
