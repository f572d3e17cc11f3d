// The extremes suite (ctest label `extremes`), its scene-scale cases: every profile on
// analytic-mixed with every length multiplied by 10⁻³ and by 10⁴ and the medium's coefficients
// divided by the same factor, so that the picture is the same (L_in depends on σ·t and on
// directions only). Against the Reference at that scale, as extremes_support.h says.
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "extremes_support.h"

namespace tyndall::test {
namespace {

// Every length times `s`, every coefficient per unit length divided by it. A local light's
// intensity is multiplied by s², so that E = I / d² is unchanged at every scaled point.
host::Scene scaled(host::Scene scene, double s) {
  scene.camera.position *= s;
  scene.camera.target *= s;
  scene.camera.nearPlane *= s;
  scene.camera.farPlane *= s;
  scene.light.position *= s;
  if (scene.light.type != host::LightType::Directional) scene.light.intensity *= s * s;
  for (host::MediumComponent& m : scene.medium) {
    m.scattering /= s;
    m.absorption /= s;
  }
  for (host::Object& o : scene.objects) {
    o.point *= s;
    o.center *= s;
    o.halfExtents *= s;
    o.radius *= s;
    o.translation *= s;
    o.scale *= s;
  }
  return scene;
}

samples::RenderOptions options() {
  samples::RenderOptions o;
  o.width = 160;
  o.height = 90;
  o.shadowMapSize = 1024;
  o.frames = 3;
  o.profile = Profile::Reference;
  return o;
}

// The Reference at scale `s` against the unscaled one (measured: 1.4·10⁻⁵ relative RMSE at both
// 10⁻³ and 10⁴, float rounding), then every profile against the scaled Reference.
void expectScaleInvariance(double s, const std::string& name) {
  const host::Scene base = loadTestScene("analytic-mixed");
  const host::Scene scene = scaled(base, s);
  const samples::RenderResult unscaled = renderWithSharedContext(base, options());
  // Scale 10⁴ puts the camera ~10⁵ units from the origin: the plugin's invertibility test of
  // camera.view and worldToShadowClip must not depend on units (plugin/src/frame_setup.cpp).
  const samples::RenderResult reference = renderWithSharedContext(scene, options());

  const ErrorStats e = compareRgb(reference.scattering, unscaled.scattering);
  std::printf("[ scale ] %s: the Reference against the unscaled Reference: %s\n", name.c_str(), describe(e).c_str());
  EXPECT_EQ(e.nonFinite, 0u);
  EXPECT_LE(e.relativeRmse, 1e-4) << "the same picture at another scale";
  expectEveryProfileWithinTwiceItsBudget(scene, options(), name);
}

TEST(ScaleExtremes, SceneScale1e_3) { expectScaleInvariance(1e-3, "scene scale 1e-3"); }

TEST(ScaleExtremes, SceneScale1e4) { expectScaleInvariance(1e4, "scene scale 1e4"); }

}  // namespace
}  // namespace tyndall::test
