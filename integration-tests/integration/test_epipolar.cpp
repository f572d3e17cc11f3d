// The epipolar technique (first stage: every epipolar sample ray-marched with the Reference's
// walk, bilateral unwarp, fix-up) against the Reference in the same run. Directional scenes
// only so far: on spot-lamp this stage measures 5% relative RMSE (the bar is 3%), see the
// epipolar issue's notes.
#include <cmath>

#include <gtest/gtest.h>

#include "test_support.h"

namespace tyndall::test {
namespace {

constexpr std::uint32_t kWidth = 192;
constexpr std::uint32_t kHeight = 108;

samples::RenderOptions options(Technique technique) {
  samples::RenderOptions o;
  o.technique = technique;
  o.width = kWidth;
  o.height = kHeight;
  o.shadowMapSize = 1024;
  EpipolarSettings epipolar;
  epipolar.slices = 256;
  epipolar.samplesPerSlice = 128;
  o.epipolar = epipolar;
  return o;
}

struct Comparison {
  ErrorStats stats;
  samples::RenderResult epipolar;
};

Comparison compareWithReference(const host::Scene& scene) {
  const samples::RenderResult reference = renderWithAovs(scene, options(Technique::Reference));
  samples::RenderOptions o = options(Technique::Epipolar);
  o.frames = 3;  // the fix-up count of a frame is read when its slot comes round again
  Comparison c{{}, renderWithAovs(scene, o)};
  c.stats = compareRgb(c.epipolar.scattering, reference.scattering);
  return c;
}

class EpipolarScenes : public ::testing::TestWithParam<const char*> {};

TEST_P(EpipolarScenes, MatchesTheReference) {
  const Comparison c = compareWithReference(loadTestScene(GetParam()));
  std::printf("[ %s ] epipolar vs reference: %s; fixed up %.2f%% of the pixels\n", GetParam(),
              describe(c.stats).c_str(), c.epipolar.stats.fixedUpPixelFraction * 100.0);
  EXPECT_EQ(c.epipolar.stats.technique, Technique::Epipolar);
  EXPECT_EQ(c.stats.nonFinite, 0u);
  // The High profile's bar in the epipolar issue; measured 0.21–0.26% on these scenes.
  EXPECT_LE(c.stats.relativeRmse, 0.03) << describe(c.stats);
  EXPECT_GE(c.epipolar.stats.fixedUpPixelFraction, 0.0);
  EXPECT_LT(c.epipolar.stats.fixedUpPixelFraction, 0.5);
  EXPECT_EQ(c.epipolar.stats.marchedSamples, 256u * 128u);
  expectNoValidationMessages();
}

INSTANTIATE_TEST_SUITE_P(Scenes, EpipolarScenes,
                         ::testing::Values("analytic-spheres", "analytic-boxes", "analytic-mixed"),
                         [](const auto& test_param) {
                           std::string name = test_param.param;
                           for (char& c : name) c = c == '-' ? '_' : c;
                           return name;
                         });

}  // namespace
}  // namespace tyndall::test
