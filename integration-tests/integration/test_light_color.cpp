// The light-colour texture (stained glass, FrameDesc::lightColor): its colour multiplies the light
// where the light reaches, so a constant texture scales L_in channel by channel in every technique;
// a spot light is used because every point it lights lies inside its map's square (outside the
// square a directional light is unfiltered, by contract).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <gtest/gtest.h>

#include "test_support.h"

namespace tyndall::test {
namespace {

// An 8×8 PNG of one sRGB colour, and that colour decoded to linear (the R8G8B8A8_SRGB texture's).
struct ConstantTexture {
  std::filesystem::path path;
  glm::dvec3 linear;
};

double srgbToLinear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

ConstantTexture writeConstantTexture(const std::string& name, std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  ConstantTexture t{std::filesystem::temp_directory_path() / name, {}};
  std::vector<std::uint8_t> rgba;
  for (int i = 0; i < 64; ++i) rgba.insert(rgba.end(), {r, g, b, 255});
  std::string error;
  EXPECT_TRUE(host::writePng(t.path.string(), 8, 8, rgba, error)) << error;
  t.linear = {srgbToLinear(r / 255.0), srgbToLinear(g / 255.0), srgbToLinear(b / 255.0)};
  return t;
}

TEST(LightColor, ConstantColourScalesEveryTechnique) {
  const ConstantTexture texture = writeConstantTexture("tyndall-test-light-colour.png", 255, 140, 60);
  host::Scene scene = loadTestScene("spot-lamp");
  for (Technique technique : {Technique::Reference, Technique::Epipolar}) {
    samples::RenderOptions o;
    o.width = 128;
    o.height = 72;
    o.shadowMapSize = 512;
    o.technique = technique;
    o.fullFloatTargets = true;  // the two results compared below half-float rounding
    scene.light.colorTexture.clear();
    const samples::RenderResult white = renderWithAovs(scene, o);
    scene.light.colorTexture = texture.path;
    const samples::RenderResult colored = renderWithAovs(scene, o);
    // The uncoloured result times one factor per channel: the texture's colour as the GPU decodes
    // it (8-bit sRGB decoding may differ from the exact curve by a few 1e-4).
    glm::dvec3 sumColored(0.0), sumWhite(0.0);
    for (std::size_t i = 0; i < white.scattering.pixels.size(); ++i) {
      if (i % 4 == 3) continue;
      sumColored[int(i % 4)] += colored.scattering.pixels[i];
      sumWhite[int(i % 4)] += white.scattering.pixels[i];
    }
    const glm::dvec3 factor = sumColored / sumWhite;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(factor[c], texture.linear[c], 2e-3) << "channel " << c;
    host::ImageRgba32f expected = white.scattering;
    for (std::size_t i = 0; i < expected.pixels.size(); ++i) {
      if (i % 4 != 3) expected.pixels[i] *= float(factor[int(i % 4)]);
    }
    const ErrorStats s = compareRgb(colored.scattering, expected);
    std::printf("[ %s ] constant light colour vs colour x white: %s\n", to_string(technique), describe(s).c_str());
    EXPECT_EQ(colored.stats.technique, technique);
    EXPECT_GT(s.meanReference, 0.0);
    EXPECT_EQ(s.nonFinite, 0u);
    // Float rounding only: the coloured march integrates chunk by chunk where the white one merges
    // lit cells. (Relative to the mean |L_in|, which the spot's peak exceeds ~1000-fold here.)
    EXPECT_LE(s.relativeRmse, 1e-4) << to_string(technique) << ": " << describe(s);
    EXPECT_LE(s.relativeMax, 1e-2) << to_string(technique) << ": " << describe(s);
    // And the colour did change the result (the texture was bound and sampled).
    EXPECT_GT(compareRgb(colored.scattering, white.scattering).relativeRmse, 0.1);
  }
  expectNoValidationMessages();
  std::filesystem::remove(texture.path);
}

// The coloured march (light_color_sums.h): lit sections in chunks of coloredStep cells, each
// uncoloured times its mean colour from the slices' prefix sums, against chunks of one cell
// (yusov2013's fine step, one colour per cell) and against the Reference, for the sun and for the
// lamp behind the rose window. The chunks may only move L_in by the colour's covariance with the
// integrand inside them (the attenuation, the lamp's fall-off), far below the technique's own error.
struct ChunkCase {
  const char* scene;
  double maxChange;  // relative RMSE of the chunks against the fine step (measured: sun 4.4e-7, lamp 3.7e-3)
};

class LightColorChunks : public ::testing::TestWithParam<ChunkCase> {};

TEST_P(LightColorChunks, MatchTheFineStep) {
  const ChunkCase& c = GetParam();
  const host::Scene scene = loadTestScene(c.scene);
  samples::RenderOptions o;
  o.width = 160;
  o.height = 90;
  o.shadowMapSize = 1024;
  o.technique = Technique::Reference;
  const samples::RenderResult reference = renderWithAovs(scene, o);
  o.technique = Technique::Epipolar;
  o.fullFloatTargets = true;  // the chunks compared with the fine step below half-float rounding
  o.epipolar = EpipolarSettings{};
  o.epipolar->coloredStep = 1;
  const samples::RenderResult fine = renderWithAovs(scene, o);
  o.epipolar->coloredStep = EpipolarSettings{}.coloredStep;
  const samples::RenderResult chunked = renderWithAovs(scene, o);
  const ErrorStats fineError = compareRgb(fine.scattering, reference.scattering);
  const ErrorStats chunkedError = compareRgb(chunked.scattering, reference.scattering);
  const ErrorStats change = compareRgb(chunked.scattering, fine.scattering);
  std::printf("[ %s ] fine step vs reference: %s; chunks of %u vs reference: %s; chunks vs fine step: %s\n", c.scene,
              describe(fineError).c_str(), EpipolarSettings{}.coloredStep, describe(chunkedError).c_str(),
              describe(change).c_str());
  for (const samples::RenderResult* r : {&fine, &chunked}) {
    EXPECT_EQ(r->stats.technique, Technique::Epipolar);
    ASSERT_TRUE(r->stats.epipolar);
    EXPECT_GT(r->stats.epipolar->coloredChunkCells, 0u);
  }
  EXPECT_EQ(chunkedError.nonFinite, 0u);
  EXPECT_GT(chunkedError.meanReference, 0.0);
  EXPECT_LE(chunkedError.relativeRmse, 0.04) << describe(chunkedError);  // Balanced's goal
  EXPECT_LE(change.relativeRmse, c.maxChange) << describe(change);
  EXPECT_LE(chunkedError.relativeRmse, fineError.relativeRmse + c.maxChange);
  expectNoValidationMessages();
}

INSTANTIATE_TEST_SUITE_P(Lights, LightColorChunks,
                         ::testing::Values(ChunkCase{"stained-glass-sun", 1e-4}, ChunkCase{"stained-glass", 5e-3}),
                         [](const auto& test_param) {
                           std::string name = test_param.param.scene;
                           for (char& ch : name) ch = ch == '-' ? '_' : ch;
                           return name;
                         });

}  // namespace
}  // namespace tyndall::test
