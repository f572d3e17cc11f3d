// Spot and point lights: the Reference against a double-precision quadrature of the radiometry
// (DESIGN.md) in a scene whose only occluder is the ground, which shadows nothing above it. With
// 4096² maps too: a ray passing the light crosses thousands of texels in each map, and on lavapipe
// the loops of one shader invocation share 65,535 iterations in all (docs/REFERENCE.md "Loop
// budget on lavapipe"); when the walk spent more than that, the rays near the light came out too
// dark. And the lamp scenes' view of their light (spot-lamp's; point-lamp's as a point light), at
// every pixel: one of point-lamp's rays runs through a 90° map along a row towards its vanishing
// point, where the walk once took an edge's crossing behind the light's plane for one already
// passed and dropped the rest of the map (tyn_edge_crossing).
#include <cmath>

#include <gtest/gtest.h>

#include "test_support.h"

namespace tyndall::test {
namespace {

constexpr std::uint32_t kWidth = 96;
constexpr std::uint32_t kHeight = 54;

host::Scene localLightScene(host::LightType type, std::uint32_t shadowMapSize) {
  host::Scene scene;
  scene.camera.position = {0.0, 2.0, 9.0};
  scene.camera.target = {0.0, 1.5, 0.0};
  scene.camera.fovYDegrees = 60.0;
  scene.camera.nearPlane = 0.1;
  scene.camera.farPlane = 40.0;
  scene.light.type = type;
  scene.light.position = type == host::LightType::Spot ? glm::dvec3(0.5, 6.0, 0.0) : glm::dvec3(0.5, 3.0, 1.0);
  scene.light.direction = glm::normalize(glm::dvec3(0.1, -1.0, 0.05));
  scene.light.color = {1.0, 0.9, 0.8};
  scene.light.intensity = 40.0;
  scene.light.innerConeDegrees = 20.0;
  scene.light.outerConeDegrees = 30.0;
  host::MediumComponent fog;
  fog.scattering = {0.05, 0.06, 0.07};
  fog.absorption = {0.01, 0.01, 0.01};
  fog.phase = host::PhaseType::HenyeyGreenstein;
  fog.g = 0.4;
  scene.medium = {fog};
  host::Object ground;
  ground.type = host::ObjectType::Plane;
  ground.point = {0.0, 0.0, 0.0};
  ground.normal = {0.0, 1.0, 0.0};
  scene.objects = {ground};
  scene.shadowMapSize = shadowMapSize;
  return scene;
}

// samples/scenes/spot-lamp.json's (and point-lamp.json's) camera, light and medium over the ground
// alone.
host::Scene lampView(host::LightType type, std::uint32_t shadowMapSize) {
  host::Scene scene = localLightScene(type, shadowMapSize);
  scene.camera.position = {9.0, 2.5, 11.0};
  scene.camera.target = {0.0, 3.0, 0.0};
  scene.camera.farPlane = 80.0;
  scene.light.position = {0.0, 7.0, 0.0};
  scene.light.direction = {0.0, -1.0, 0.0};
  scene.light.color = {1.0, 0.9, 0.75};
  scene.light.intensity = 60.0;
  scene.medium[0].scattering = {0.04, 0.04, 0.04};
  scene.medium[0].absorption = {0.004, 0.004, 0.004};
  scene.medium[0].g = 0.2;
  return scene;
}

double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / std::max(e1 - e0, 1e-12), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// L_in along one view ray by composite Simpson in double.
glm::dvec3 quadrature(const host::Scene& scene, const glm::dvec3& origin, const glm::dvec3& dir, double s) {
  const host::Light& light = scene.light;
  const host::MediumComponent& m = scene.medium[0];
  const glm::dvec3 sigmaT = m.scattering + m.absorption;
  auto integrand = [&](double t) {
    const glm::dvec3 x = origin + t * dir;
    const glm::dvec3 toLight = light.position - x;
    const double d2 = glm::dot(toLight, toLight);
    const double d = std::sqrt(d2);
    const glm::dvec3 omega = toLight / d;
    double falloff = 1.0;
    if (light.type == host::LightType::Spot) {
      falloff = smoothstep(std::cos(glm::radians(light.outerConeDegrees)),
                           std::cos(glm::radians(light.innerConeDegrees)), glm::dot(-omega, light.direction));
    }
    const double phase = analytic::phase(m.phase, m.g, glm::dot(dir, omega));
    return light.color * light.intensity * falloff / d2 * glm::exp(-sigmaT * d) * m.scattering * phase *
           glm::exp(-sigmaT * t);
  };
  const int n = 20000;
  const double h = s / n;
  glm::dvec3 sum = integrand(0.0) + integrand(s);
  for (int i = 1; i < n; ++i) sum += (i % 2 == 1 ? 4.0 : 2.0) * integrand(i * h);
  return sum * h / 3.0;
}

struct LocalLightCase {
  host::LightType type;
  std::uint32_t shadowMapSize;
  bool lampView = false;  // lampView's scene, every pixel (else every third in x and y)
};

class LocalLights : public ::testing::TestWithParam<LocalLightCase> {};

TEST_P(LocalLights, ReferenceMatchesQuadrature) {
  const host::Scene scene = GetParam().lampView ? lampView(GetParam().type, GetParam().shadowMapSize)
                                               : localLightScene(GetParam().type, GetParam().shadowMapSize);
  const std::uint32_t stride = GetParam().lampView ? 1 : 3;
  samples::RenderOptions options;
  options.profile = Profile::Reference;
  options.width = kWidth;
  options.height = kHeight;
  const samples::RenderResult result = renderWithAovs(scene, options);
  ASSERT_EQ(result.scattering.width, kWidth);

  // Reference values at the sampled pixels; the mask selects them in the GPU image.
  std::vector<double> reference(static_cast<std::size_t>(kWidth) * kHeight * 3, 0.0);
  std::vector<unsigned char> mask(static_cast<std::size_t>(kWidth) * kHeight, 0);
  const glm::dvec3 forward = glm::normalize(scene.camera.target - scene.camera.position);
  for (std::uint32_t y = stride / 2; y < kHeight; y += stride) {
    for (std::uint32_t x = stride / 2; x < kWidth; x += stride) {
      const glm::dvec3 dir = analytic::cameraRayDirection(scene.camera, x, y, kWidth, kHeight);
      double s = scene.camera.farPlane / glm::dot(dir, forward);
      if (dir.y < 0.0) s = std::min(s, -scene.camera.position.y / dir.y);
      const glm::dvec3 lin = quadrature(scene, scene.camera.position, dir, s);
      const std::size_t i = static_cast<std::size_t>(y) * kWidth + x;
      mask[i] = 1;
      for (int c = 0; c < 3; ++c) reference[i * 3 + c] = lin[c];
    }
  }
  const ErrorStats stats = compareRgb(result.scattering, reference, &mask);
  std::printf("[ %s light%s, %u^2 maps ] L_in: %s\n", GetParam().type == host::LightType::Spot ? "spot" : "point",
              GetParam().lampView ? " (the lamp scenes' view)" : "", GetParam().shadowMapSize, describe(stats).c_str());
  // The pixel farthest from the quadrature (red), to say where an error sits.
  std::size_t worst = 0;
  double worstError = -1.0;
  for (std::size_t i = 0; i < mask.size(); ++i) {
    const double error = mask[i] ? std::abs(result.scattering.pixels[i * 4] - reference[i * 3]) : -1.0;
    if (error > worstError) worstError = error, worst = i;
  }
  std::printf("  worst pixel (%zu, %zu): red %.6g, quadrature %.6g\n", worst % kWidth, worst / kWidth,
              double(result.scattering.pixels[worst * 4]), reference[worst * 3]);
  EXPECT_GT(stats.meanReference, 0.0);
  EXPECT_EQ(stats.nonFinite, 0u);
  // Measured on lavapipe: 0.012% (spot) and 0.006% (point) with 1024² maps, 0.009% and 0.002%
  // with 4096² (144% for the point light while the walk overran the loop budget); the bound keeps
  // a margin.
  EXPECT_LE(stats.relativeRmse, 0.002) << describe(stats);
  expectNoValidationMessages();
}

// Above 4096² a point light's walk can overrun lavapipe's loop budget: the stats say so on a CPU
// driver (and only there, and only above).
TEST(LocalLightsOnCpuDrivers, StatsSayWhenAPointLightsWalkCanOverrunTheLoopBudget) {
  samples::RenderOptions options;
  options.profile = Profile::Reference;
  options.width = 16;
  options.height = 9;
  const samples::RenderResult within = renderWithAovs(localLightScene(host::LightType::Point, 4096), options);
  const samples::RenderResult above = renderWithAovs(localLightScene(host::LightType::Point, 4104), options);
  EXPECT_FALSE(within.stats.walkOverCpuLoopLimit) << within.stats.techniqueNote;
  EXPECT_EQ(above.stats.walkOverCpuLoopLimit, above.cpuDevice)
      << above.deviceName << ": " << above.stats.techniqueNote;
  expectNoValidationMessages();
}

INSTANTIATE_TEST_SUITE_P(SpotAndPoint, LocalLights,
                         ::testing::Values(LocalLightCase{host::LightType::Spot, 1024},
                                           LocalLightCase{host::LightType::Point, 1024},
                                           LocalLightCase{host::LightType::Spot, 4096},
                                           LocalLightCase{host::LightType::Point, 4096},
                                           LocalLightCase{host::LightType::Spot, 1024, true},
                                           LocalLightCase{host::LightType::Point, 1024, true}),
                         [](const auto& test_param) -> std::string {
                           const bool spot = test_param.param.type == host::LightType::Spot;
                           if (test_param.param.lampView) return spot ? "spot_lamp_view" : "point_lamp_view";
                           if (test_param.param.shadowMapSize == 1024) return spot ? "spot" : "point";
                           return spot ? "spot_4096" : "point_4096";
                         });

}  // namespace
}  // namespace tyndall::test
