// settings_text: the KEY=VALUE form of the techniques' parameters that tyndall-render reads and
// tyndall-bench and docs/TRADEOFFS.md write.
#include <gtest/gtest.h>

#include "settings_text.h"

namespace tyndall::samples {
namespace {

TEST(SettingsText, DefaultsReadAsDefaults) {
  EXPECT_EQ(describe(EpipolarSettings{}), "defaults");
  EXPECT_EQ(describe(PrefilteredSettings{}), "defaults");
}

TEST(SettingsText, EveryEpipolarFieldRoundTrips) {
  EpipolarSettings s;
  s.slices = 1024;
  s.samplesPerSlice = 512;
  s.improvedSamplePlacement = false;
  s.initialSampleStep = 32;
  s.refinementThreshold = 0.07f;
  s.intensityRefinementThreshold = 0.15f;
  s.epipoleDensity = 3.5f;
  s.minMaxTree = false;
  s.maxTreeStep = 64;
  s.bilateralDepthThreshold = 0.1f;
  s.fixupWeightThreshold = 0.2f;
  s.sliceContrastThreshold = 0.15f;
  s.epipoleFixupRadius = 24.0f;
  s.epipoleFixupHeightFraction = 0.05f;
  s.fixupSteps = 48;
  s.coloredStep = 8;
  s.resolution = ScatteringResolution::Half;
  const std::string text = describe(s);
  EXPECT_EQ(text,
            "slices=1024,samples=512,improved-placement=0,initial-step=32,refinement=0.07,intensity-refinement=0.15,"
            "density=3.5,tree=0,max-tree-step=64,bilateral=0.1,fixup-weight=0.2,slice-contrast=0.15,epipole-radius=24,"
            "epipole-fraction=0.05,fixup-steps=48,colored-step=8,resolution=half");
  EpipolarSettings back;
  std::string error;
  ASSERT_TRUE(parseEpipolarSettings(text, back, error)) << error;
  EXPECT_EQ(describe(back), text);
  EXPECT_EQ(back.refinementThreshold, s.refinementThreshold);  // shortest form reads back exactly
  EXPECT_EQ(back.intensityRefinementThreshold, s.intensityRefinementThreshold);
}

TEST(SettingsText, EveryPrefilteredFieldRoundTrips) {
  PrefilteredSettings s;
  s.basis = PrefilteredBasis::Fourier32;
  s.rectification = PrefilteredRectification::Projective;
  s.rows = 256;
  s.columns = 256;
  s.filteredResampling = false;
  s.spacing = PrefilteredSpacing::MeanTheta;
  s.rayWeightTaps = 1;
  s.prefixSums = PrefixSumScheme::ThreadPerRow;
  s.overestimation = 0.25f;
  s.epipoleBlockPixels = 0;
  s.shortRayColumns = 5;
  s.depthBounds = false;
  s.segmentedReconstruction = false;
  s.trimmedSegments = false;
  s.texelWalkSteps = 3;
  s.resolution = ScatteringResolution::Quarter;
  const std::string text = describe(s);
  EXPECT_EQ(text,
            "basis=fourier32,rectification=projective,rows=256,columns=256,filtered=0,spacing=mean-theta,taps=1,"
            "prefix-sums=thread-per-row,beta=0.25,epipole-block=0,short-rays=5,depth-bounds=0,segments=0,trim=0,"
            "texel-walk=3,resolution=quarter");
  PrefilteredSettings back;
  std::string error;
  ASSERT_TRUE(parsePrefilteredSettings(text, back, error)) << error;
  EXPECT_EQ(describe(back), text);

  PrefilteredSettings adaptive;
  adaptive.adaptiveOverestimation = true;
  EXPECT_EQ(describe(adaptive), "beta=adaptive");
  ASSERT_TRUE(parsePrefilteredSettings("beta=adaptive", back, error)) << error;
  EXPECT_TRUE(back.adaptiveOverestimation);
}

TEST(SettingsText, BadTextSaysWhatIsWrong) {
  EpipolarSettings e;
  PrefilteredSettings p;
  std::string error;
  EXPECT_FALSE(parseEpipolarSettings("slices=many", e, error));
  EXPECT_EQ(error, "--epipolar: bad value for slices (got 'many')");
  EXPECT_FALSE(parseEpipolarSettings("slice=512", e, error));
  EXPECT_EQ(error.rfind("--epipolar: unknown key 'slice'", 0), 0u) << error;
  EXPECT_FALSE(parseEpipolarSettings("tree=2", e, error));
  EXPECT_FALSE(parsePrefilteredSettings("basis=moments5", p, error));
  EXPECT_EQ(error, "--prefiltered: bad value for basis (got 'moments5')");
  EXPECT_FALSE(parsePrefilteredSettings("beta=", p, error));
  EXPECT_FALSE(parseEpipolarSettings("resolution=third", e, error));
  EXPECT_EQ(error, "--epipolar: bad value for resolution (got 'third')");
  EXPECT_FALSE(parsePrefilteredSettings("resolution=2", p, error));
  EXPECT_EQ(error, "--prefiltered: bad value for resolution (got '2')");
}

}  // namespace
}  // namespace tyndall::samples
