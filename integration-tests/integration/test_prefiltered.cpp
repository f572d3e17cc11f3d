// The prefiltered technique (klehm2014, peters2017 §5) against the Reference in the same run:
// every storage variant on every directional scene and on the epipole placements, the passes it
// records, its settings' validation, the two prefix-sum schemes and the spacing heuristics.
// Bars (issue 4): relative RMSE of L_in ≤ 5% with 6 moments, ≤ 8% with 4, Fourier reported; no
// NaN/Inf; no validation message. Where a bar is missed, kMissedBars says by how much and why
// (docs/PREFILTERED.md "Accuracy"); those cases assert their measured figure instead, so that they
// cannot get worse unnoticed.
// Cost (lavapipe with validation, 2 cores in CI): compiling a pipeline takes seconds, a 320x180
// frame well under a second. So the renders of a test go
// through one shared context (renderWithSharedContext; a render's result does not depend on what
// the context rendered before, which SettingsChangeBetweenFramesInFlight checks), and one test
// covers one scene or placement: its Reference is rendered once and every variant is compared with
// it, each variant's figure printed and a failure naming the variant.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "test_support.h"
#include "tyndall_effect.h"

namespace tyndall::test {
namespace {

constexpr std::uint32_t kWidth = 320;
constexpr std::uint32_t kHeight = 180;
constexpr std::uint32_t kShadowMapSize = 1024;

samples::RenderOptions options(Technique technique, const PrefilteredSettings& settings = {}) {
  samples::RenderOptions o;
  o.technique = technique;
  o.width = kWidth;
  o.height = kHeight;
  o.shadowMapSize = kShadowMapSize;
  o.prefiltered = settings;
  return o;
}

// The Reference of a scene, rendered once per process and key.
const samples::RenderResult& reference(const std::string& key, const host::Scene& scene) {
  static std::map<std::string, samples::RenderResult> cache;
  auto it = cache.find(key);
  if (it == cache.end()) it = cache.emplace(key, renderWithSharedContext(scene, options(Technique::Reference))).first;
  return it->second;
}

bool has(const std::vector<std::string>& passes, const std::string& name) {
  return std::find(passes.begin(), passes.end(), name) != passes.end();
}

bool anyStartsWith(const std::vector<std::string>& passes, const std::string& prefix) {
  return std::any_of(passes.begin(), passes.end(), [&](const std::string& p) { return p.rfind(prefix, 0) == 0; });
}

// The bar of a basis (test_support.h); Fourier has none (it is reported).
double bar(PrefilteredBasis basis) { return prefilteredBar(basis); }

// Cases measured above their bar, with the measured relative RMSE they are held to (rounded up) and
// the reason; docs/PREFILTERED.md "Accuracy" has the analysis. Not a loosened bar: each is printed
// as a miss.
struct MissedBar {
  const char* scene;
  PrefilteredBasis basis;
  double measured;
  const char* reason;
};
// None since the texel walk (window-room's 6-moment variants measured 15.0%, 5.73% and 5.45% before
// it: the moments' leak at the edges of the window beams). Kept so that a case that cannot meet its
// bar is listed with its figure and reason, not dropped.
const std::vector<MissedBar> kMissedBars = {};

const MissedBar* missedBar(const std::string& scene, PrefilteredBasis basis) {
  for (const MissedBar& m : kMissedBars) {
    if (scene == m.scene && basis == m.basis) return &m;
  }
  return nullptr;
}

struct Comparison {
  ErrorStats stats;
  samples::RenderResult result;
};

Comparison compare(const std::string& key, const host::Scene& scene, const PrefilteredSettings& settings) {
  const samples::RenderResult& ref = reference(key, scene);
  Comparison c{{}, renderWithSharedContext(scene, options(Technique::Prefiltered, settings))};
  c.stats = compareRgb(c.result.scattering, ref.scattering);
  return c;
}

void expectWithinBar(const std::string& scene, PrefilteredBasis basis, const ErrorStats& stats) {
  EXPECT_EQ(stats.nonFinite, 0u);
  EXPECT_GT(stats.meanReference, 0.0);
  if (const MissedBar* missed = missedBar(scene, basis)) {
    std::printf("[ %s ] BAR MISSED: %s measured %.2f%% against %.0f%% (%s)\n", scene.c_str(), to_string(basis),
                stats.relativeRmse * 100.0, bar(basis) * 100.0, missed->reason);
    EXPECT_LE(stats.relativeRmse, missed->measured) << describe(stats);
    EXPECT_GT(stats.relativeRmse, bar(basis)) << "the bar is met: take this case out of kMissedBars";
  } else {
    EXPECT_LE(stats.relativeRmse, bar(basis)) << to_string(basis) << ": " << describe(stats);
  }
}

const PrefilteredBasis kBases[] = {PrefilteredBasis::Moments4_64,  PrefilteredBasis::Moments4_128,
                                   PrefilteredBasis::Moments6_64,  PrefilteredBasis::Moments6_96,
                                   PrefilteredBasis::Moments6_192, PrefilteredBasis::Fourier32};

// ---------------------------------------------------------------------------------------------
// Every storage variant on every directional scene (defaults otherwise): one test per scene, the
// Reference rendered once, each variant against it.

class PrefilteredScenes : public ::testing::TestWithParam<const char*> {};

TEST_P(PrefilteredScenes, EveryVariantMatchesTheReference) {
  const char* sceneName = GetParam();
  const host::Scene scene = loadTestScene(sceneName);
  for (PrefilteredBasis basis : kBases) {
    SCOPED_TRACE(to_string(basis));
    PrefilteredSettings settings;
    settings.basis = basis;
    const Comparison c = compare(sceneName, scene, settings);
    std::printf("[ %s ] prefiltered %s vs reference: %s\n", sceneName, to_string(basis), describe(c.stats).c_str());
    EXPECT_EQ(c.result.stats.technique, Technique::Prefiltered);
    expectWithinBar(sceneName, basis, c.stats);
    expectNoValidationMessages();
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, PrefilteredScenes,
                         ::testing::Values("pillars", "fence", "forest", "window-room", "analytic-spheres",
                                           "analytic-boxes", "analytic-mixed", "gltf-tetrahedron"),
                         [](const auto& test_param) {
                           std::string name = test_param.param;
                           for (char& c : name) c = c == '-' ? '_' : c;
                           return name;
                         });

// ---------------------------------------------------------------------------------------------
// Epipole placements (analytic-mixed with the camera turned so that the light lands there): the
// pass list follows the epipole, the rectification follows the switch, the result the Reference.
// One test per placement, the Reference rendered once, each variant against it.

struct EpipoleCase {
  const char* name;
  glm::dvec2 ndc;
  bool behind;
  bool blockOnScreen;  // the epipole block (default 16 px) touches the screen
};

const PrefilteredBasis kEpipoleBases[] = {PrefilteredBasis::Moments4_64, PrefilteredBasis::Moments6_64,
                                          PrefilteredBasis::Fourier32};

class PrefilteredEpipole : public ::testing::TestWithParam<EpipoleCase> {};

TEST_P(PrefilteredEpipole, MatchesTheReferenceAndFixesUpOnlyOnScreen) {
  const EpipoleCase& e = GetParam();
  const host::Scene scene = withEpipoleAt(loadTestScene("analytic-mixed"), e.ndc, e.behind, kWidth, kHeight);
  for (PrefilteredBasis basis : kEpipoleBases) {
    SCOPED_TRACE(to_string(basis));
    PrefilteredSettings settings;
    settings.basis = basis;
    const Comparison c = compare(std::string("epipole ") + e.name, scene, settings);
    std::printf("[ epipole %s ] prefiltered %s vs reference: %s; %s\n", e.name, to_string(basis),
                describe(c.stats).c_str(), c.result.stats.techniqueNote.c_str());
    const std::vector<std::string>& passes = c.result.stats.passesRecorded;
    EXPECT_EQ(has(passes, "prefiltered_epipole_fixup"), e.blockOnScreen);
    EXPECT_EQ(has(passes, "prefiltered_epipole_fixup_args"), e.blockOnScreen);
    expectWithinBar(std::string("epipole ") + e.name, basis, c.stats);
    expectNoValidationMessages();
  }
}

const EpipoleCase kEpipoleCases[] = {
    {"centre", {0.0, 0.0}, false, true},
    {"near_corner", {-0.97, -0.95}, false, true},
    {"just_off_screen", {1.03, 0.2}, false, true},
    {"far_off_screen", {6.0, -3.0}, false, false},
    {"behind_on_screen", {0.4, 0.3}, true, true},
    {"behind_on_axis", {0.0, 0.0}, true, true},
    {"behind_off_screen", {5.0, 2.0}, true, false},
};

INSTANTIATE_TEST_SUITE_P(Placements, PrefilteredEpipole, ::testing::ValuesIn(kEpipoleCases),
                         [](const auto& test_param) { return std::string(test_param.param.name); });

// klehm2014's projective rectification where the epipole is far off screen, chosen automatically,
// against the non-linear one in the same view; the stats say which ran.
TEST(Prefiltered, ProjectiveRectificationWhereTheEpipoleIsFarOffScreen) {
  const host::Scene scene = withEpipoleAt(loadTestScene("analytic-mixed"), {6.0, -3.0}, false, kWidth, kHeight);
  PrefilteredSettings automatic;
  const Comparison a = compare("epipole far_off_screen", scene, automatic);
  ASSERT_TRUE(a.result.stats.prefiltered);
  EXPECT_EQ(a.result.stats.prefiltered->rectification, Rectification::Projective) << a.result.stats.techniqueNote;
  EXPECT_EQ(a.result.stats.prefiltered->choice, RectificationChoice::Automatic);
  EXPECT_LE(a.result.stats.prefiltered->projectiveTexelStretch, 2.0);
  PrefilteredSettings nonLinear;
  nonLinear.rectification = PrefilteredRectification::NonLinear;
  const Comparison n = compare("epipole far_off_screen", scene, nonLinear);
  ASSERT_TRUE(n.result.stats.prefiltered);
  EXPECT_EQ(n.result.stats.prefiltered->rectification, Rectification::NonLinear) << n.result.stats.techniqueNote;
  EXPECT_EQ(n.result.stats.prefiltered->choice, RectificationChoice::Requested);
  std::printf("[ epipole far_off_screen ] projective %s; non-linear %s\n", describe(a.stats).c_str(),
              describe(n.stats).c_str());
  expectWithinBar("epipole far_off_screen", automatic.basis, a.stats);
  expectWithinBar("epipole far_off_screen", nonLinear.basis, n.stats);

  // With the light in view the projective map cannot be built: a frame that asks for it runs the
  // non-linear one and says so.
  PrefilteredSettings projective;
  projective.rectification = PrefilteredRectification::Projective;
  const Comparison p = compare("analytic-mixed", loadTestScene("analytic-mixed"), projective);
  ASSERT_TRUE(p.result.stats.prefiltered);
  EXPECT_EQ(p.result.stats.prefiltered->rectification, Rectification::NonLinear) << p.result.stats.techniqueNote;
  EXPECT_EQ(p.result.stats.prefiltered->choice, RectificationChoice::ProjectiveImpossible);
  expectWithinBar("analytic-mixed", projective.basis, p.stats);
  expectNoValidationMessages();
}

// Reverse-Z and an infinite far plane (sky pixels integrate to the sky distance): the frustum
// bounds, the rays' ends and the Reference agree.
TEST(Prefiltered, DepthConventions) {
  const host::Scene scene = loadTestScene("analytic-spheres");
  for (const bool reverse : {false, true}) {
    for (const bool infinite : {false, true}) {
      SCOPED_TRACE(std::string(reverse ? "reverse-Z" : "standard") + (infinite ? ", infinite far" : ""));
      samples::RenderOptions ref = options(Technique::Reference);
      samples::RenderOptions pre = options(Technique::Prefiltered);
      for (samples::RenderOptions* o : {&ref, &pre}) {
        o->depth = reverse ? host::DepthConvention::Reverse : host::DepthConvention::Standard;
        o->infiniteFar = infinite;
      }
      const samples::RenderResult r = renderWithSharedContext(scene, ref);
      const samples::RenderResult p = renderWithSharedContext(scene, pre);
      const ErrorStats stats = compareRgb(p.scattering, r.scattering);
      std::printf("[ analytic-spheres, %s%s ] prefiltered vs reference: %s\n", reverse ? "reverse-Z" : "standard",
                  infinite ? ", infinite far" : "", describe(stats).c_str());
      expectWithinBar("analytic-spheres", PrefilteredBasis::Moments6_64, stats);
      EXPECT_EQ(compareRgb(p.transmittance, r.transmittance).relativeMax, 0.0);
    }
  }
  expectNoValidationMessages();
}

// ---------------------------------------------------------------------------------------------
// What is recorded.

TEST(Prefiltered, PassesFollowTheFrame) {
  const host::Scene scene = loadTestScene("analytic-mixed");
  samples::RenderResult r = renderWithSharedContext(scene, options(Technique::Prefiltered));
  EXPECT_EQ(r.stats.technique, Technique::Prefiltered);
  EXPECT_EQ(r.stats.passesRecorded,
            (std::vector<std::string>{"prefiltered_moment_shadow_map", "prefiltered_rectify", "prefiltered_prefix_sums",
                                      "prefiltered_evaluate", "prefiltered_epipole_fixup_args",
                                      "prefiltered_epipole_fixup", "composite", "aov_output"}));

  // Plain resampling needs no moment map; no block, no fix-up.
  PrefilteredSettings plain;
  plain.filteredResampling = false;
  plain.epipoleBlockPixels = 0;
  r = renderWithSharedContext(scene, options(Technique::Prefiltered, plain));
  EXPECT_EQ(r.stats.passesRecorded,
            (std::vector<std::string>{"prefiltered_rectify", "prefiltered_prefix_sums", "prefiltered_evaluate",
                                      "composite", "aov_output"}));

  // The epipole off screen: no fix-up pass is recorded at all.
  r = renderWithSharedContext(withEpipoleAt(scene, {6.0, -3.0}, false, kWidth, kHeight),
                              options(Technique::Prefiltered));
  EXPECT_FALSE(anyStartsWith(r.stats.passesRecorded, "prefiltered_epipole_fixup"));

  // No in-scattering (σ_s = 0, σ_a > 0): no technique runs, L_in is cleared, T is the composite's.
  host::Scene absorbing = scene;
  for (host::MediumComponent& m : absorbing.medium) {
    m.absorption += m.scattering;
    m.scattering = glm::dvec3(0.0);
  }
  r = renderWithSharedContext(absorbing, options(Technique::Prefiltered));
  EXPECT_EQ(r.stats.technique, Technique::None);
  EXPECT_EQ(r.stats.passesRecorded, (std::vector<std::string>{"scattering_clear", "composite", "aov_output"}));
  const samples::RenderResult refAbsorbing = renderWithSharedContext(absorbing, options(Technique::Reference));
  EXPECT_EQ(compareRgb(r.transmittance, refAbsorbing.transmittance).relativeMax, 0.0);
  double largest = 0.0;
  for (float v : r.scattering.pixels) largest = std::max(largest, double(std::abs(v)));
  EXPECT_EQ(largest, 0.0);
  expectNoValidationMessages();
}

// Spot and point lights are not rectified: the epipolar technique runs, and the stats say so.
TEST(Prefiltered, LocalLightsRunTheEpipolarTechnique) {
  for (const char* name : {"spot-lamp", "point"}) {
    SCOPED_TRACE(name);
    host::Scene scene = loadTestScene("spot-lamp");
    if (std::string(name) == "point") scene.light.type = host::LightType::Point;
    samples::RenderOptions o = options(Technique::Prefiltered);
    o.width = 96;
    o.height = 54;
    const samples::RenderResult r = renderWithSharedContext(scene, o);
    EXPECT_EQ(r.stats.technique, Technique::Epipolar);
    EXPECT_EQ(r.stats.requestedTechnique, Technique::Prefiltered);
    EXPECT_EQ(r.stats.techniqueChange, TechniqueChange::PrefilteredNeedsDirectionalLight) << r.stats.techniqueNote;
    EXPECT_FALSE(r.stats.prefiltered);
    EXPECT_TRUE(anyStartsWith(r.stats.passesRecorded, "epipolar_"));
    EXPECT_FALSE(anyStartsWith(r.stats.passesRecorded, "prefiltered_"));
  }
  expectNoValidationMessages();
}

// ---------------------------------------------------------------------------------------------
// Prefix sums and spacing.

double medianPass(const samples::RenderResult& r, const std::string& pass) {
  std::vector<double> ms;
  for (const FrameTimings& frame : r.timings) {
    for (const PassTiming& p : frame.passes) {
      if (p.name == pass) ms.push_back(p.milliseconds);
    }
  }
  if (ms.empty()) return -1.0;
  std::sort(ms.begin(), ms.end());
  return ms[ms.size() / 2];
}

// Row-parallel and one thread per row run the same blends in the same order: the results are
// identical. The workgroup scan merges runs of texels in another order: the same up to rounding.
// A rounding apart in a moment can move a reconstruction near the edge of the valid moment domain
// (measured: one pixel 1% off with moments4_64's 16-bit quantisation), so the bound is on the RMSE
// and the 99th percentile (a run merged at the wrong place or missed shifts whole rows' averages:
// percents). 1000 columns leave the scan's last lanes short or empty. The schemes' cost is printed
// (docs/PREFILTERED.md quotes it; lavapipe's numbers say little about a GPU's).
TEST(Prefiltered, PrefixSumSchemesAgree) {
  constexpr double kScanRmseBound = 3e-4;  // relative to the mean |L_in|
  constexpr double kScanP99Bound = 1e-3;
  const host::Scene scene = loadTestScene("pillars");
  struct Case {
    PrefilteredBasis basis;
    std::uint32_t columns;
  };
  for (const Case& c : {Case{PrefilteredBasis::Moments4_64, 2048}, Case{PrefilteredBasis::Moments6_64, 2048},
                        Case{PrefilteredBasis::Fourier32, 2048}, Case{PrefilteredBasis::Moments4_128, 1000}}) {
    PrefilteredSettings rowParallel;
    rowParallel.basis = c.basis;
    rowParallel.columns = c.columns;
    rowParallel.prefixSums = PrefixSumScheme::RowParallel;
    PrefilteredSettings threadPerRow = rowParallel;
    threadPerRow.prefixSums = PrefixSumScheme::ThreadPerRow;
    PrefilteredSettings scan = rowParallel;
    scan.prefixSums = PrefixSumScheme::WorkgroupScan;
    samples::RenderOptions a = options(Technique::Prefiltered, rowParallel);
    samples::RenderOptions b = options(Technique::Prefiltered, threadPerRow);
    samples::RenderOptions s = options(Technique::Prefiltered, scan);
    a.frames = b.frames = s.frames = 5;
    const samples::RenderResult ra = renderWithSharedContext(scene, a);
    const samples::RenderResult rb = renderWithSharedContext(scene, b);
    const samples::RenderResult rs = renderWithSharedContext(scene, s);
    EXPECT_EQ(compareRgb(ra.scattering, rb.scattering).relativeMax, 0.0) << to_string(c.basis);
    const ErrorStats scanError = compareRgb(rs.scattering, ra.scattering);
    EXPECT_EQ(scanError.nonFinite, 0u) << to_string(c.basis);
    EXPECT_LT(scanError.relativeRmse, kScanRmseBound) << to_string(c.basis) << ", " << c.columns << " columns";
    EXPECT_LT(scanError.relativeP99, kScanP99Bound) << to_string(c.basis) << ", " << c.columns << " columns";
    std::printf("[ prefix sums ] %s, %ux%u: row-parallel %.2f ms, one thread per row %.2f ms, workgroup scan %.2f ms "
                "(median of %zu frames, %s); scan against row-parallel: RMSE %.2e, p99 %.2e, max %.2e\n",
                to_string(c.basis), rowParallel.columns, rowParallel.rows, medianPass(ra, "prefiltered_prefix_sums"),
                medianPass(rb, "prefiltered_prefix_sums"), medianPass(rs, "prefiltered_prefix_sums"), ra.timings.size(),
                ra.deviceName.c_str(), scanError.relativeRmse, scanError.relativeP99, scanError.relativeMax);
  }
  expectNoValidationMessages();
}

// peters2017's mean θ and klehm2014's reference ray with one lookup, against the fastest ray with
// the re-weighting taps (the default), per scene.
TEST(Prefiltered, SpacingHeuristicsMeasured) {
  double sumSingle[2] = {0.0, 0.0};
  double sumTaps = 0.0;
  // The first four look into the light: no slice contains θ = π/2, and both heuristics pick the
  // same ray. With the light beside the view they differ.
  const std::pair<const char*, host::Scene> scenes[] = {
      {"pillars", loadTestScene("pillars")},
      {"fence", loadTestScene("fence")},
      {"forest", loadTestScene("forest")},
      {"analytic-mixed", loadTestScene("analytic-mixed")},
      {"epipole far_off_screen", withEpipoleAt(loadTestScene("analytic-mixed"), {6.0, -3.0}, false, kWidth, kHeight)},
      {"pillars, light beside", withEpipoleAt(loadTestScene("pillars"), {3.0, 0.0}, false, kWidth, kHeight)},
  };
  for (const auto& [name, scene] : scenes) {
    double single[2];
    for (int h = 0; h < 2; ++h) {
      PrefilteredSettings s;
      s.spacing = h == 0 ? PrefilteredSpacing::MeanTheta : PrefilteredSpacing::ReferenceRay;
      s.rayWeightTaps = 1;
      single[h] = compare(name, scene, s).stats.relativeRmse;
      sumSingle[h] += single[h];
    }
    const double taps = compare(name, scene, PrefilteredSettings{}).stats.relativeRmse;
    sumTaps += taps;
    std::printf("[ %s ] spacing: mean theta %.2f%%, reference ray %.2f%% (one lookup); fastest ray with 4 taps %.2f%%\n",
                name, single[0] * 100.0, single[1] * 100.0, taps * 100.0);
  }
  EXPECT_LT(sumTaps, sumSingle[0]);
  EXPECT_LT(sumTaps, sumSingle[1]);
  expectNoValidationMessages();
}

// One on/off setting for one scene and basis, defaults otherwise: both renders against the scene's
// Reference, printed as "<what>: off X%, on Y%"; the render with it on is finite and its stats say
// it ran (`ran`), the other's do not.
struct OffOn {
  Comparison off;
  Comparison on;
};

OffOn compareOffOn(const char* name, const host::Scene& scene, PrefilteredBasis basis,
                   const std::function<void(PrefilteredSettings&, bool)>& set, const char* what,
                   const std::function<bool(const PrefilteredStats&)>& ran) {
  PrefilteredSettings off;
  off.basis = basis;
  set(off, false);
  PrefilteredSettings on = off;
  set(on, true);
  OffOn r{compare(name, scene, off), compare(name, scene, on)};
  std::printf("[ %s ] %s %s: off %.2f%%, on %.2f%% relative RMSE\n", name, to_string(basis), what,
              r.off.stats.relativeRmse * 100.0, r.on.stats.relativeRmse * 100.0);
  EXPECT_EQ(r.on.stats.nonFinite, 0u);
  EXPECT_TRUE(r.on.result.stats.prefiltered && ran(*r.on.result.stats.prefiltered)) << r.on.result.stats.techniqueNote;
  EXPECT_TRUE(r.off.result.stats.prefiltered && !ran(*r.off.result.stats.prefiltered))
      << r.off.result.stats.techniqueNote;
  return r;
}

OffOn compareOffOn(const char* name, const host::Scene& scene, PrefilteredBasis basis,
                   bool PrefilteredSettings::*setting, const char* what,
                   const std::function<bool(const PrefilteredStats&)>& ran) {
  return compareOffOn(name, scene, basis, [&](PrefilteredSettings& s, bool on) { s.*setting = on; }, what, ran);
}

// The row depth bounds (shaders/prefiltered/depth_bounds.h) give rays whose row leaves no doubt
// their exact verdict instead of the reconstruction. Where every ray of a closed room is in the
// roof's shadow but for the window beams, that removes most of the moments' leak; elsewhere it may
// only remove error. Each case is printed with and without; the note says when they are on.
TEST(Prefiltered, RowDepthBoundsRemoveTheLeaks) {
  for (const char* name : {"window-room", "pillars", "forest"}) {
    const host::Scene scene = loadTestScene(name);
    for (PrefilteredBasis basis : {PrefilteredBasis::Moments4_64, PrefilteredBasis::Moments6_64,
                                   PrefilteredBasis::Fourier32}) {
      SCOPED_TRACE(std::string(name) + " " + to_string(basis));
      const OffOn r = compareOffOn(name, scene, basis, &PrefilteredSettings::depthBounds, "row depth bounds",
                                   [](const PrefilteredStats& p) { return p.rowDepthBounds; });
      EXPECT_LE(r.on.stats.relativeRmse, r.off.stats.relativeRmse * 1.001);
      // The room: its leak (several times the mean) at least halves.
      if (std::string(name) == "window-room") {
        EXPECT_LT(r.on.stats.relativeRmse, 0.5 * r.off.stats.relativeRmse);
      }
    }
  }
  expectNoValidationMessages();
}

// Segmented reconstruction (weight_taps.h tyn_segment_coefficients): each of the 4 segments between
// the lookups reconstructed on its own. Measured off -> on with the default 512 x 2048 map
// (docs/PREFILTERED.md), trimmed segments, short rays and the texel walk (the defaults) included:
// moments6_64 pillars 5.26 -> 0.60%, window-room 83.3 -> 1.95%, forest 5.75 -> 2.25%. Asserted: the segments at least halve
// pillars' and window-room's errors and do not worsen forest's for these two variants, and the note says when they run (not with one lookup).
TEST(Prefiltered, SegmentedReconstructionLowersTheError) {
  for (const char* name : {"pillars", "window-room", "forest"}) {
    const host::Scene scene = loadTestScene(name);
    for (PrefilteredBasis basis : {PrefilteredBasis::Moments4_64, PrefilteredBasis::Moments6_64}) {
      SCOPED_TRACE(std::string(name) + " " + to_string(basis));
      const OffOn r = compareOffOn(name, scene, basis, &PrefilteredSettings::segmentedReconstruction,
                                   "segmented reconstruction", [](const PrefilteredStats& p) { return p.segments > 0; });
      if (std::string(name) == "forest") {
        EXPECT_LE(r.on.stats.relativeRmse, r.off.stats.relativeRmse);
      } else {
        EXPECT_LT(r.on.stats.relativeRmse, 0.5 * r.off.stats.relativeRmse);
      }
      EXPECT_EQ(r.on.result.stats.prefiltered.value().segments, 4u);
    }
  }
  PrefilteredSettings single;
  single.rayWeightTaps = 1;
  const Comparison one = compare("pillars", loadTestScene("pillars"), single);
  EXPECT_EQ(one.result.stats.prefiltered.value().segments, 0u) << "one lookup is one segment";
  expectNoValidationMessages();
}

// Trimmed segments (depth_bounds.h tyn_depth_bounds_run_end / run_begin): the runs at both ends of a
// segment that the row's min/max tree decides count exactly, with the ray's own weights, and only
// the columns between them are reconstructed. Measured off -> on (docs/PREFILTERED.md "Trimmed
// segments", 320x180, short rays and the texel walk on): moments6_64 window-room 39.7 -> 1.95%,
// pillars 2.27 -> 0.60%, forest 4.00 -> 2.25%. Asserted: no case gets worse, window-room's error at least halves, and the note
// says when they run (not without the segments).
TEST(Prefiltered, TrimmedSegmentsLowerTheError) {
  for (const char* name : {"window-room", "pillars", "forest"}) {
    const host::Scene scene = loadTestScene(name);
    for (PrefilteredBasis basis : {PrefilteredBasis::Moments4_64, PrefilteredBasis::Moments6_64}) {
      SCOPED_TRACE(std::string(name) + " " + to_string(basis));
      const OffOn r = compareOffOn(name, scene, basis, &PrefilteredSettings::trimmedSegments, "trimmed segments",
                                   [](const PrefilteredStats& p) { return p.trimmedSegments; });
      EXPECT_LE(r.on.stats.relativeRmse, r.off.stats.relativeRmse * 1.001);
      if (std::string(name) == "window-room") {
        EXPECT_LT(r.on.stats.relativeRmse, 0.5 * r.off.stats.relativeRmse);
      }
    }
  }
  PrefilteredSettings unsegmented;
  unsegmented.segmentedReconstruction = false;
  const Comparison c = compare("pillars", loadTestScene("pillars"), unsegmented);
  EXPECT_FALSE(c.result.stats.prefiltered.value().trimmedSegments) << "only segments are trimmed";
  expectNoValidationMessages();
}

// Texel walk (depth_bounds.h "Texel walk"): the columns between a trimmed segment's runs are walked
// for up to 8 steps, a decided run or one undecided texel (its two depths) each, and only the rest is
// reconstructed. Measured off -> on (docs/PREFILTERED.md "Texel walk", 320x180): moments6_64
// window-room 15.00 -> 1.95%, pillars 1.03 -> 0.60%, forest 3.75 -> 2.25%. Asserted: no case gets
// worse, window-room's error falls below a third, and the note says when it runs (not without the
// trimmed segments, whose middle it walks).
TEST(Prefiltered, TexelWalkResolvesTheMiddleOfTrimmedSegments) {
  const PrefilteredSettings defaults;
  ASSERT_GT(defaults.texelWalkSteps, 0u) << "the walk is on by default";
  auto walk = [&](PrefilteredSettings& s, bool on) { s.texelWalkSteps = on ? defaults.texelWalkSteps : 0u; };
  for (const char* name : {"window-room", "pillars", "forest"}) {
    const host::Scene scene = loadTestScene(name);
    for (PrefilteredBasis basis : {PrefilteredBasis::Moments4_64, PrefilteredBasis::Moments6_64}) {
      SCOPED_TRACE(std::string(name) + " " + to_string(basis));
      const OffOn r = compareOffOn(name, scene, basis, walk, "texel walk", [&](const PrefilteredStats& p) {
        return p.texelWalkSteps == defaults.texelWalkSteps;
      });
      EXPECT_LE(r.on.stats.relativeRmse, r.off.stats.relativeRmse * 1.001);
      if (std::string(name) == "window-room") {
        EXPECT_LT(r.on.stats.relativeRmse, r.off.stats.relativeRmse / 3.0);
      }
    }
  }
  PrefilteredSettings untrimmed;
  untrimmed.trimmedSegments = false;
  const Comparison c = compare("pillars", loadTestScene("pillars"), untrimmed);
  EXPECT_EQ(c.result.stats.prefiltered.value().texelWalkSteps, 0u) << "only trimmed segments are walked";
  expectNoValidationMessages();
}

// Short rays (PrefilteredSettings::shortRayColumns): next to the epipole a view ray runs almost
// along the light and crosses a few texels of its row, too few for any reconstruction; those rays
// take the Reference's walk. The epipole block is a number of pixels, so it covers a smaller angle
// as the output grows; the short rays are chosen in texels, which the output size does not change.
// window-room (the epipole just above the screen, a closed room whose rays next to it are all in
// shadow), moments4_64, measured (docs/PREFILTERED.md "Short rays", texel walk on): with short rays
// 1.55% at 320x180 and 1.56% at 640x360; with the 16-px block alone 16.39% at 640x360. Asserted: with short
// rays the error at 640x360 stays within 10% of 320x180's, without them it is more than 1.5 times
// as large, and the note says when they run.
TEST(Prefiltered, ShortRaysHoldTheErrorAtEveryOutputSize) {
  const host::Scene scene = loadTestScene("window-room");
  PrefilteredSettings on;
  on.basis = PrefilteredBasis::Moments4_64;
  PrefilteredSettings off = on;
  off.shortRayColumns = 0;
  auto render = [&](Technique technique, std::uint32_t width, std::uint32_t height,
                    const PrefilteredSettings& settings) {
    samples::RenderOptions o = options(technique, settings);
    o.width = width;
    o.height = height;
    return renderWithSharedContext(scene, o);
  };
  // One Reference per size.
  const samples::RenderResult smallRef = render(Technique::Reference, kWidth, kHeight, {});
  const samples::RenderResult largeRef = render(Technique::Reference, 2 * kWidth, 2 * kHeight, {});
  auto error = [&](const samples::RenderResult& ref, const PrefilteredSettings& settings) {
    const std::uint32_t width = ref.scattering.width;
    const std::uint32_t height = ref.scattering.height;
    const samples::RenderResult r = render(Technique::Prefiltered, width, height, settings);
    const ErrorStats stats = compareRgb(r.scattering, ref.scattering);
    EXPECT_EQ(stats.nonFinite, 0u);
    EXPECT_TRUE(r.stats.prefiltered && r.stats.prefiltered->shortRayColumns == settings.shortRayColumns)
        << r.stats.techniqueNote;
    return stats.relativeRmse;
  };
  const double small = error(smallRef, on);
  const double large = error(largeRef, on);
  const double largeOff = error(largeRef, off);
  std::printf("[ window-room ] moments4_64 short rays: %ux%u %.2f%%, %ux%u %.2f%% (off: %.2f%%)\n", kWidth, kHeight,
              small * 100.0, 2 * kWidth, 2 * kHeight, large * 100.0, largeOff * 100.0);
  EXPECT_LE(large, 1.1 * small);
  EXPECT_GT(largeOff, 1.5 * large);
  expectNoValidationMessages();
}

// ---------------------------------------------------------------------------------------------
// Settings: validated per frame, and changed between frames with frames in flight.

class SettingsEffect final : public host::PostProcessEffect {
 public:
  std::unique_ptr<Context> context;
  std::vector<PrefilteredSettings> perFrame;  // cycled
  PrefilteredSettings bad;
  bool useBad = false;
  Outcome outcome;
  std::size_t frame = 0;

  bool record(VkCommandBuffer cmd, const host::PostProcessInputs& inputs, std::string&) override {
    samples::FrameStorage storage;
    FrameDesc desc = samples::makeFrameDesc(inputs, Profile::Balanced, storage);
    desc.technique = Technique::Prefiltered;
    desc.prefiltered = useBad ? &bad : &perFrame[frame++ % perFrame.size()];
    outcome = context->record(cmd, desc);
    return true;
  }
  bool resize(VkExtent2D, std::string&) override { return true; }
};

struct BadSetting {
  const char* field;
  std::function<void(PrefilteredSettings&)> mutate;
};

TEST(Prefiltered, EachBadSettingRecordsNothingAndNamesTheField) {
  const host::Scene scene = loadTestScene("analytic-mixed");
  host::RenderSettings settings;
  settings.width = 32;
  settings.height = 18;
  settings.shadowMapSize = 256;
  std::string error;
  host::Device& device = validatedDevice();
  // What the host renders without any post-process: what a rejected frame must leave.
  std::unique_ptr<host::Renderer> plainRenderer = host::Renderer::create(device, scene, settings, error);
  ASSERT_TRUE(plainRenderer) << error;
  ASSERT_TRUE(plainRenderer->renderFrame(error)) << error;
  plainRenderer->waitIdle();
  host::ImageRgba32f plain;
  ASSERT_TRUE(plainRenderer->readBackBuffer(plain, error)) << error;

  std::unique_ptr<host::Renderer> renderer = host::Renderer::create(device, scene, settings, error);
  ASSERT_TRUE(renderer) << error;
  SettingsEffect effect;
  {
    Result<std::unique_ptr<Context>> created = Context::create(samples::contextDescFor(device, settings));
    ASSERT_TRUE(created.ok()) << created.outcome().message;
    effect.context = std::move(created).value();
  }
  PrefilteredSettings small;
  small.rows = small.columns = 64;
  effect.perFrame = {small};
  renderer->addPostProcess(&effect);
  // The valid frame records and changes the picture, so that the comparison below can fail.
  ASSERT_TRUE(renderer->renderFrame(error)) << error;
  renderer->waitIdle();
  ASSERT_TRUE(effect.outcome.ok()) << effect.outcome.message;
  host::ImageRgba32f good;
  ASSERT_TRUE(renderer->readBackBuffer(good, error)) << error;
  ASSERT_GT(compareRgb(good, plain).relativeRmse, 0.01);

  const std::vector<BadSetting> cases = {
      {"prefiltered.basis", [](PrefilteredSettings& s) { s.basis = static_cast<PrefilteredBasis>(6); }},
      {"prefiltered.rectification", [](PrefilteredSettings& s) { s.rectification = static_cast<PrefilteredRectification>(3); }},
      {"prefiltered.rows", [](PrefilteredSettings& s) { s.rows = 15; }},
      {"prefiltered.rows", [](PrefilteredSettings& s) { s.rows = 4097; }},
      {"prefiltered.columns", [](PrefilteredSettings& s) { s.columns = 0; }},
      {"prefiltered.columns", [](PrefilteredSettings& s) { s.columns = 8192; }},
      {"prefiltered.spacing", [](PrefilteredSettings& s) { s.spacing = static_cast<PrefilteredSpacing>(3); }},
      {"prefiltered.rayWeightTaps", [](PrefilteredSettings& s) { s.rayWeightTaps = 0; }},
      {"prefiltered.rayWeightTaps", [](PrefilteredSettings& s) { s.rayWeightTaps = 9; }},
      {"prefiltered.rayWeightTaps", [](PrefilteredSettings& s) { s.spacing = PrefilteredSpacing::MeanTheta; }},
      {"prefiltered.prefixSums", [](PrefilteredSettings& s) { s.prefixSums = static_cast<PrefixSumScheme>(3); }},
      {"prefiltered.overestimation", [](PrefilteredSettings& s) { s.overestimation = -0.1f; }},
      {"prefiltered.overestimation", [](PrefilteredSettings& s) { s.overestimation = NAN; }},
      {"prefiltered.epipoleBlockPixels", [](PrefilteredSettings& s) { s.epipoleBlockPixels = 257; }},
      {"prefiltered.shortRayColumns", [](PrefilteredSettings& s) { s.shortRayColumns = s.columns + 1; }},
      {"prefiltered.texelWalkSteps", [](PrefilteredSettings& s) { s.texelWalkSteps = 65; }},
      {"prefiltered.resolution", [](PrefilteredSettings& s) { s.resolution = static_cast<ScatteringResolution>(3); }},
  };
  for (const BadSetting& bad : cases) {
    SCOPED_TRACE(bad.field);
    effect.bad = small;
    bad.mutate(effect.bad);
    effect.useBad = true;
    const std::uint64_t framesBefore = effect.context->stats().frameIndex;
    ASSERT_TRUE(renderer->renderFrame(error)) << error;
    renderer->waitIdle();
    EXPECT_EQ(effect.outcome.status, Status::InvalidArgument) << effect.outcome.message;
    EXPECT_EQ(effect.outcome.message.rfind(bad.field, 0), 0u) << effect.outcome.message;
    EXPECT_EQ(effect.context->stats().frameIndex, framesBefore) << "a rejected frame must not count";
    host::ImageRgba32f out;
    ASSERT_TRUE(renderer->readBackBuffer(out, error)) << error;
    EXPECT_EQ(compareRgb(out, plain).relativeMax, 0.0) << "a rejected frame must leave the back buffer alone";
    expectNoValidationMessages();
  }
  renderer->waitIdle();
}

// Sizes, bases and sets change from frame to frame while earlier frames are in flight: the maps of
// other sizes are retired, not destroyed under the GPU (synchronization validation is on), and the
// last frame equals a render that used its settings from the start.
TEST(Prefiltered, SettingsChangeBetweenFramesInFlight) {
  const host::Scene scene = loadTestScene("analytic-boxes");
  host::RenderSettings settings;
  settings.width = 64;
  settings.height = 36;
  settings.shadowMapSize = 512;
  settings.aovImages = true;
  settings.framesInFlight = 2;
  std::string error;
  host::Device& device = validatedDevice();
  std::unique_ptr<host::Renderer> renderer = host::Renderer::create(device, scene, settings, error);
  ASSERT_TRUE(renderer) << error;
  SettingsEffect effect;
  {
    Result<std::unique_ptr<Context>> created = Context::create(samples::contextDescFor(device, settings));
    ASSERT_TRUE(created.ok()) << created.outcome().message;
    effect.context = std::move(created).value();
  }
  PrefilteredSettings a, b, c;
  a.rows = 64;
  a.columns = 128;
  b.basis = PrefilteredBasis::Fourier32;
  b.rows = 96;
  b.columns = 64;
  b.filteredResampling = false;
  c.basis = PrefilteredBasis::Moments6_96;
  c.rows = 128;
  c.columns = 128;
  effect.perFrame = {a, b, c, a, c, b, c};
  renderer->addPostProcess(&effect);
  for (std::size_t i = 0; i < effect.perFrame.size(); ++i) {
    ASSERT_TRUE(renderer->renderFrame(error)) << error;
    ASSERT_TRUE(effect.outcome.ok()) << effect.outcome.message;
  }
  renderer->waitIdle();
  host::ImageRgba32f last;
  ASSERT_TRUE(renderer->readAovScattering(last, error)) << error;
  expectNoValidationMessages();

  samples::RenderOptions fresh = options(Technique::Prefiltered, c);
  fresh.width = settings.width;
  fresh.height = settings.height;
  fresh.shadowMapSize = settings.shadowMapSize;
  // A fresh context (not the shared one): what these settings give from the first frame on.
  const samples::RenderResult once = renderWithAovs(scene, fresh);
  EXPECT_EQ(compareRgb(last, once.scattering).relativeMax, 0.0);
  expectNoValidationMessages();
}

// tyndall-render --technique prefiltered --prefiltered KEY=VALUE,…: every key reaches its field;
// unknown keys and malformed values fail with a line naming them (ranges are the plugin's to check).
TEST(Prefiltered, CommandLineSettings) {
  auto parse = [](std::vector<const char*> args, samples::RenderOptions& options, std::string& error) {
    args.insert(args.begin(), "tyndall-render");
    bool help = false;
    return samples::parseCommandLine(static_cast<int>(args.size()), args.data(), options, help, error);
  };
  samples::RenderOptions o;
  std::string error;
  ASSERT_TRUE(parse({"scene.json", "--technique", "prefiltered", "--prefiltered",
                     "basis=fourier32,rectification=projective,rows=64,columns=128,filtered=0,spacing=mean-theta,"
                     "taps=1,prefix-sums=thread-per-row,beta=0.25,epipole-block=0,short-rays=5,depth-bounds=0,segments=0,"
                     "trim=0,texel-walk=3"},
                    o, error))
      << error;
  EXPECT_EQ(o.technique, Technique::Prefiltered);
  ASSERT_TRUE(o.prefiltered.has_value());
  const PrefilteredSettings& s = *o.prefiltered;
  EXPECT_EQ(s.basis, PrefilteredBasis::Fourier32);
  EXPECT_EQ(s.rectification, PrefilteredRectification::Projective);
  EXPECT_EQ(s.rows, 64u);
  EXPECT_EQ(s.columns, 128u);
  EXPECT_FALSE(s.filteredResampling);
  EXPECT_EQ(s.spacing, PrefilteredSpacing::MeanTheta);
  EXPECT_EQ(s.rayWeightTaps, 1u);
  EXPECT_EQ(s.prefixSums, PrefixSumScheme::ThreadPerRow);
  EXPECT_FALSE(s.adaptiveOverestimation);
  EXPECT_EQ(s.overestimation, 0.25f);
  EXPECT_EQ(s.epipoleBlockPixels, 0u);
  EXPECT_EQ(s.shortRayColumns, 5u);
  EXPECT_FALSE(s.depthBounds);
  EXPECT_FALSE(s.segmentedReconstruction);
  EXPECT_FALSE(s.trimmedSegments);
  EXPECT_EQ(s.texelWalkSteps, 3u);

  samples::RenderOptions adaptive;
  ASSERT_TRUE(parse({"scene.json", "--prefiltered", "beta=adaptive"}, adaptive, error)) << error;
  EXPECT_TRUE(adaptive.prefiltered->adaptiveOverestimation);

  for (const char* bad : {"bases=moments6_64", "basis=moments8", "rows=many", "beta=", "spacing=median"}) {
    samples::RenderOptions b;
    error.clear();
    EXPECT_FALSE(parse({"scene.json", "--prefiltered", bad}, b, error)) << bad;
    EXPECT_EQ(error.rfind("--prefiltered: ", 0), 0u) << error;
  }
}

}  // namespace
}  // namespace tyndall::test
