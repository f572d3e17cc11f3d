// The extremes suite (ctest label `extremes`), its medium cases: every profile on σ_t from 0 to
// 10³ per scene unit, one channel without scattering, and g at ±0.99 and 0, against the Reference
// (extremes_support.h says what is asserted).
#include <string>

#include <gtest/gtest.h>

#include "extremes_support.h"

namespace tyndall::test {
namespace {

struct MediumCase {
  const char* name;
  glm::dvec3 extinction;  // σ_t per scene unit, per channel
  double albedo;          // σ_s / σ_t
  double g;               // Henyey–Greenstein
};

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
  samples::RenderOptions o;
  o.width = 160;
  o.height = 90;
  o.shadowMapSize = 1024;
  o.frames = 3;
  expectEveryProfileWithinTwiceItsBudget(withMedium(loadTestScene("analytic-mixed"), c), o, c.name);
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
