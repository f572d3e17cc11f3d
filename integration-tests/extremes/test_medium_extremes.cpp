// The extremes suite (ctest label `extremes`), its medium cases: every profile on σ_t from 0 to
// 10³ per scene unit, one channel without scattering, and g at ±0.99 and 0. Each is asserted: no
// NaN/Inf, no validation message, and L_in within twice the profile's accuracy budget of the
// Reference (High 3%, Balanced 6%, Performance 8% relative RMSE; Auto: the profile it ran). Every
// case prints one "[ extremes ]" line: scripts/extremes-report.sh turns them into docs/EXTREMES.md.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "test_support.h"

namespace tyndall::test {
namespace {

struct MediumCase {
  const char* name;
  glm::dvec3 extinction;  // σ_t per scene unit, per channel
  double albedo;          // σ_s / σ_t
  double g;               // Henyey–Greenstein
};

// The profile's relative-RMSE budget (the profile issue's goals), doubled by the caller.
double budget(Profile profile) {
  switch (profile) {
    case Profile::High: return 0.02;
    case Profile::Balanced: return 0.04;
    case Profile::Performance: return 0.08;
    default: return 0.0;
  }
}

host::Scene withMedium(host::Scene scene, const MediumCase& c) {
  host::MediumComponent m;
  m.scattering = c.extinction * c.albedo;
  m.absorption = c.extinction - m.scattering;
  m.phase = host::PhaseType::HenyeyGreenstein;
  m.g = c.g;
  scene.medium = {m};
  return scene;
}

class MediumExtremes : public ::testing::TestWithParam<MediumCase> {};

TEST_P(MediumExtremes, EveryProfileStaysFiniteAndWithinTwiceItsBudget) {
  const MediumCase& c = GetParam();
  const host::Scene scene = withMedium(loadTestScene("analytic-mixed"), c);
  samples::RenderOptions o;
  o.width = 160;
  o.height = 90;
  o.shadowMapSize = 1024;
  o.frames = 3;
  o.profile = Profile::Reference;
  const samples::RenderResult reference = renderWithSharedContext(scene, o);
  const ErrorStats self = compareRgb(reference.scattering, reference.scattering);
  EXPECT_EQ(self.nonFinite, 0u) << "the Reference itself";
  const bool scatters = c.albedo > 0.0 && (c.extinction.x > 0.0 || c.extinction.y > 0.0 || c.extinction.z > 0.0);
  for (Profile profile : {Profile::High, Profile::Balanced, Profile::Performance, Profile::Auto}) {
    SCOPED_TRACE(to_string(profile));
    o.profile = profile;
    const samples::RenderResult r = renderWithSharedContext(scene, o);
    const ErrorStats s = compareRgb(r.scattering, reference.scattering);
    const ErrorStats t = compareRgb(r.transmittance, reference.transmittance);
    const Profile ran = profile == Profile::Auto ? r.stats.profileUsed : profile;
    const double bar = 2.0 * budget(ran);
    std::printf("[ extremes ] %s :: %s :: L_in %s :: T relative RMSE %.3g%%, NaN/Inf %zu\n", c.name, to_string(profile),
                scatters ? describe(s).c_str() : "zero expected", 100.0 * t.relativeRmse, t.nonFinite);
    EXPECT_EQ(s.nonFinite, 0u);
    EXPECT_EQ(t.nonFinite, 0u);
    EXPECT_LE(t.relativeRmse, 1e-5) << "T is exact per pixel in every technique";
    if (scatters) {
      EXPECT_GT(s.meanReference, 0.0);
      EXPECT_LE(s.relativeRmse, bar) << describe(s);
    } else {
      EXPECT_EQ(s.meanReference, 0.0);
      double largest = 0.0;  // of L_in's RGB (the AOV is RGBA)
      for (std::size_t i = 0; i < r.scattering.pixels.size(); ++i) {
        if (i % 4 != 3) largest = std::max(largest, double(std::abs(r.scattering.pixels[i])));
      }
      EXPECT_EQ(largest, 0.0);
    }
  }
  expectNoValidationMessages();
}

INSTANTIATE_TEST_SUITE_P(
    Media, MediumExtremes,
    ::testing::Values(MediumCase{"sigma_t_0", glm::dvec3(0.0), 0.8, 0.3},
                      MediumCase{"sigma_t_1e-6", glm::dvec3(1e-6), 0.8, 0.3},
                      MediumCase{"sigma_t_1e-3", glm::dvec3(1e-3), 0.8, 0.3},
                      MediumCase{"sigma_t_0.1", glm::dvec3(0.1), 0.8, 0.3},
                      MediumCase{"sigma_t_10", glm::dvec3(10.0), 0.8, 0.3},
                      MediumCase{"sigma_t_1e3", glm::dvec3(1e3), 0.8, 0.3},
                      MediumCase{"one_channel_zero", glm::dvec3(0.0, 0.05, 0.1), 0.8, 0.3},
                      MediumCase{"g_minus_0.99", glm::dvec3(0.05), 0.8, -0.99},
                      MediumCase{"g_0", glm::dvec3(0.05), 0.8, 0.0},
                      MediumCase{"g_0.99", glm::dvec3(0.05), 0.8, 0.99}),
    [](const auto& test_param) {
      std::string name = test_param.param.name;
      for (char& ch : name) ch = (ch == '-' || ch == '.') ? '_' : ch;
      return name;
    });

}  // namespace
}  // namespace tyndall::test
