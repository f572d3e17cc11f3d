// The Reference technique against the CPU double-precision analytic reference, and the
// composite it leaves in the back buffer.
#include <cmath>
#include <string>
#include <tuple>

#include <gtest/gtest.h>

#include "test_support.h"

namespace tyndall::test {
namespace {

constexpr std::uint32_t kWidth = 192;
constexpr std::uint32_t kHeight = 108;

samples::RenderOptions referenceOptions() {
  samples::RenderOptions options;
  options.profile = Profile::Reference;
  options.width = kWidth;
  options.height = kHeight;
  options.shadowMapSize = 2048;
  return options;
}

class ReferenceVsAnalytic : public ::testing::TestWithParam<const char*> {};

// The bar: relative RMSE of L_in ≤ 2% at a 2048² shadow map, no NaN/Inf.
TEST_P(ReferenceVsAnalytic, InScatteringAndTransmittance) {
  const host::Scene scene = loadTestScene(GetParam());
  const samples::RenderResult result = renderWithAovs(scene, referenceOptions());
  ASSERT_EQ(result.scattering.width, kWidth);
  EXPECT_EQ(result.stats.technique, Technique::Reference);

  analytic::RgbImage scattering;
  analytic::RgbImage transmittance;
  std::string error;
  ASSERT_TRUE(analytic::renderAnalytic(scene, kWidth, kHeight, scattering, transmittance, error)) << error;

  const ErrorStats lin = compareRgb(result.scattering, scattering.rgb);
  const ErrorStats t = compareRgb(result.transmittance, transmittance.rgb);
  RecordProperty("relative_rmse_percent", std::to_string(lin.relativeRmse * 100.0));
  std::printf("[ %s ] L_in: %s\n[ %s ] T:    %s\n", GetParam(), describe(lin).c_str(), GetParam(),
              describe(t).c_str());
  EXPECT_GT(lin.meanReference, 0.0) << "the scene must scatter light";
  EXPECT_EQ(lin.nonFinite, 0u);
  EXPECT_LE(lin.relativeRmse, 0.02) << describe(lin);
  // Away from silhouettes (where the tessellated and the exact shapes see different surfaces)
  // the two agree far more closely: measured p99 0.02–0.10%.
  EXPECT_LE(lin.relativeP99, 0.005) << describe(lin);
  EXPECT_EQ(t.nonFinite, 0u);
  // T = exp(−σ_t s) depends only on the depth buffer: it agrees to float precision except where
  // a tessellated silhouette and the exact shape disagree on a pixel centre (well under 1% of
  // the pixels; there the error is large, so the bound is on the 99th percentile).
  EXPECT_LE(t.relativeP99, 1e-3) << describe(t);
  expectNoValidationMessages();
}

INSTANTIATE_TEST_SUITE_P(AnalyticScenes, ReferenceVsAnalytic,
                         ::testing::Values("analytic-spheres", "analytic-boxes", "analytic-mixed"),
                         [](const auto& test_param) {
                           std::string name = test_param.param;
                           for (char& c : name) c = c == '-' ? '_' : c;
                           return name;
                         });

// out = in · T + L_in: the back buffer with the effect against the back buffer without it, on both
// paths: compute (the back buffer a storage image) and the fragment blend (no STORAGE usage). At
// reduced resolution (the epipolar technique's half and quarter targets) the L_in AOV is the
// upsampled L_in, the composite's own.
class Composite : public ::testing::TestWithParam<std::tuple<bool, ScatteringResolution>> {};

TEST_P(Composite, BackBufferIsInTimesTransmittancePlusInScattering) {
  const auto [storage, resolution] = GetParam();
  const host::Scene scene = loadTestScene("analytic-mixed");
  samples::RenderOptions options = referenceOptions();
  options.width = 64;
  options.height = 36;
  options.shadowMapSize = 512;
  options.storageBackBuffer = storage;
  if (resolution != ScatteringResolution::Full) {
    options.technique = Technique::Epipolar;
    options.epipolar = EpipolarSettings{};
    options.epipolar->resolution = resolution;
  }
  const samples::RenderResult with = renderWithAovs(scene, options);
  EXPECT_EQ(with.stats.composite, storage ? CompositePath::Compute : CompositePath::Fragment);
  EXPECT_EQ(with.stats.scatteringResolution, resolution);

  host::RenderSettings settings;
  settings.width = options.width;
  settings.height = options.height;
  settings.shadowMapSize = options.shadowMapSize;
  std::string error;
  std::unique_ptr<host::Renderer> plain = host::Renderer::create(validatedDevice(), scene, settings, error);
  ASSERT_TRUE(plain) << error;
  ASSERT_TRUE(plain->renderFrame(error)) << error;
  plain->waitIdle();
  host::ImageRgba32f in;
  ASSERT_TRUE(plain->readBackBuffer(in, error)) << error;

  host::ImageRgba32f expected = in;
  for (std::size_t i = 0; i < expected.pixels.size(); i += 4) {
    for (std::size_t c = 0; c < 3; ++c) {
      expected.pixels[i + c] = in.pixels[i + c] * with.transmittance.pixels[i + c] + with.scattering.pixels[i + c];
    }
  }
  // The back buffer is RGBA16F (11 significant bits): the blend's (or the compute pass's) result is
  // rounded once, so each value is within 2^-11 of the exact one, relative (checked with 2^-10).
  ASSERT_EQ(with.color.pixels.size(), expected.pixels.size());
  std::size_t outside = 0;
  for (std::size_t i = 0; i < expected.pixels.size(); i += 4) {
    for (std::size_t c = 0; c < 3; ++c) {
      const float e = expected.pixels[i + c];
      const float got = with.color.pixels[i + c];
      if (!(std::abs(got - e) <= std::ldexp(std::abs(e), -10) + 1e-7f)) ++outside;
    }
  }
  EXPECT_EQ(outside, 0u);
  // And the effect did change the picture.
  EXPECT_GT(compareRgb(in, expected).relativeRmse, 0.05);
  expectNoValidationMessages();
}

INSTANTIATE_TEST_SUITE_P(Paths, Composite,
                         ::testing::Combine(::testing::Bool(),
                                            ::testing::Values(ScatteringResolution::Full, ScatteringResolution::Half,
                                                              ScatteringResolution::Quarter)),
                         [](const auto& param_info) {
                           return std::string(std::get<0>(param_info.param) ? "compute_" : "fragment_") +
                                  to_string(std::get<1>(param_info.param));
                         });

}  // namespace
}  // namespace tyndall::test
