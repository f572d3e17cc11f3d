// The extremes suite (ctest label `extremes`), its view cases: every profile with the epipole at
// the screen centre, a corner, on an edge, one pixel off screen, far off screen, behind the camera
// and exactly on the view axis in front and behind; reverse-Z and an infinite far plane; near/far
// ratios of 10⁻⁴ and 10⁻⁶; output extents of 1×1, 3×7 and 4096×2160; sky-only and surface-only
// frames and a surface at the near plane. Against the Reference, as extremes_support.h says.
#include <string>

#include <gtest/gtest.h>

#include "extremes_support.h"

namespace tyndall::test {
namespace {

constexpr std::uint32_t kWidth = 160;
constexpr std::uint32_t kHeight = 90;

samples::RenderOptions options(std::uint32_t width = kWidth, std::uint32_t height = kHeight) {
  samples::RenderOptions o;
  o.width = width;
  o.height = height;
  o.shadowMapSize = 1024;
  o.frames = 3;
  return o;
}

struct EpipoleCase {
  const char* name;
  glm::dvec2 ndc;
  bool behind;
};

class EpipoleExtremes : public ::testing::TestWithParam<EpipoleCase> {};

TEST_P(EpipoleExtremes, EveryProfileStaysFiniteAndWithinTwiceItsBudget) {
  const EpipoleCase& e = GetParam();
  const host::Scene scene = withEpipoleAt(loadTestScene("analytic-mixed"), e.ndc, e.behind, kWidth, kHeight);
  expectEveryProfileWithinTwiceItsBudget(scene, options(), std::string("epipole ") + e.name);
}

INSTANTIATE_TEST_SUITE_P(
    Placements, EpipoleExtremes,
    ::testing::Values(EpipoleCase{"centre_on_axis", {0.0, 0.0}, false}, EpipoleCase{"corner", {-1.0, -1.0}, false},
                      EpipoleCase{"edge", {1.0, 0.3}, false},
                      // One pixel beyond the right edge: NDC 1 + 2/width.
                      EpipoleCase{"one_pixel_off", {1.0 + 2.0 / kWidth, 0.2}, false},
                      EpipoleCase{"far_off", {40.0, -25.0}, false}, EpipoleCase{"behind", {0.4, 0.3}, true},
                      EpipoleCase{"behind_on_axis", {0.0, 0.0}, true}),
    [](const auto& test_param) { return std::string(test_param.param.name); });

TEST(ViewExtremes, DepthConventions) {
  const host::Scene scene = loadTestScene("analytic-spheres");
  for (const auto& [name, reverse, infinite] : {std::tuple{"reverse-Z", true, false},
                                                std::tuple{"infinite far", false, true},
                                                std::tuple{"reverse-Z, infinite far", true, true}}) {
    samples::RenderOptions o = options();
    o.depth = reverse ? host::DepthConvention::Reverse : host::DepthConvention::Standard;
    o.infiniteFar = infinite;
    expectEveryProfileWithinTwiceItsBudget(scene, o, name);
  }
}

TEST(ViewExtremes, NearFarRatios) {
  for (const auto& [name, nearPlane, farPlane] : {std::tuple{"near/far 1e-4", 0.01, 100.0},
                                                  std::tuple{"near/far 1e-6", 1e-4, 100.0}}) {
    host::Scene scene = loadTestScene("analytic-spheres");
    scene.camera.nearPlane = nearPlane;
    scene.camera.farPlane = farPlane;
    expectEveryProfileWithinTwiceItsBudget(scene, options(), name);
  }
}

TEST(ViewExtremes, TinyExtents) {
  const host::Scene scene = loadTestScene("analytic-spheres");
  expectEveryProfileWithinTwiceItsBudget(scene, options(1, 1), "extent 1x1");
  expectEveryProfileWithinTwiceItsBudget(scene, options(3, 7), "extent 3x7");
}

// The largest extent the issue asks for, 4096×2160 (8.8 M pixels, 615 times the suite's 160×90),
// with a 64² shadow map: on lavapipe the Reference's cost is pixels × shadow-map texels walked per
// ray, and 64² caps the walk at ~130 texels (its frame takes ~4 s on 2 cores, ~8 s at 256²,
// minutes at 1024²); the techniques' cost at this extent is in the pixels (unwarp, fix-up,
// composite), not in the map. The image does not depend on the frame count (the suite's three
// frames are for stats read back a frame later), so one frame per profile, and one frame in
// flight (half the host's 4K images). Measured: ~50 s for the case on 2 cores, ~30 s of it the
// five renders (host frame and AOV readback included) and ~18 s the error metrics over 26.5 M
// values (each sorts them for the p99). The 64² map's own extremes are ShadowMapExtremes'.
TEST(ViewExtremes, Extent4096x2160) {
  samples::RenderOptions o = options(4096, 2160);
  o.shadowMapSize = 64;
  o.frames = 1;
  o.framesInFlight = 1;
  expectEveryProfileWithinTwiceItsBudget(loadTestScene("analytic-spheres"), o, "extent 4096x2160");
}

// analytic-mixed with the camera turned: straight up (every pixel is sky, integrated to the far
// plane), straight down from close above the ground (every pixel is surface), and down onto the
// ground from just beyond the near plane (the nearest surface at 1.5 near distances).
TEST(ViewExtremes, SkyOnlySurfaceOnlyAndNearPlane) {
  const host::Scene base = loadTestScene("analytic-mixed");
  struct Case {
    const char* name;
    glm::dvec3 position;
    glm::dvec3 target;
    glm::dvec3 up;
  };
  const double nearPlane = base.camera.nearPlane;
  for (const Case& c : {Case{"sky only", {-2.0, 3.0, 12.0}, {-2.0, 10.0, 12.0}, {0.0, 0.0, -1.0}},
                        Case{"surface only", {-4.0, 1.0, 8.0}, {-4.0, 0.0, 8.0}, {0.0, 0.0, -1.0}},
                        Case{"surface at the near plane", {-4.0, 1.5 * nearPlane, 8.0}, {-4.0, 0.0, 8.0},
                             {0.0, 0.0, -1.0}}}) {
    host::Scene scene = base;
    scene.camera.position = c.position;
    scene.camera.target = c.target;
    scene.camera.up = c.up;
    expectEveryProfileWithinTwiceItsBudget(scene, options(), c.name);
  }
}

}  // namespace
}  // namespace tyndall::test
