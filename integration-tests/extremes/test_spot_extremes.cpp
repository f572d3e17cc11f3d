// The extremes suite (ctest label `extremes`), its spot-cone cases: every profile with the camera
// outside the spot light's cone (spot-lamp as it is), inside it looking out sideways, and exactly
// on its outer boundary, and a lamp inside its shade (an occluder's bounding box), as a spot light
// and as a point light. Against the
// Reference, as extremes_support.h says. At 320×180: at the suite's usual 160×90, spot-lamp from
// outside the cone misses (High 6.0%, Balanced 6.5% against bars of 4% and 8%; 7.7% and 8.1%
// before the unwarp fix described below; docs/EXTREMES.md has the command). Half of High's
// squared error there is one pixel of sky just above the hanging ball, 11 px from the light: the
// ball's shadow makes L_in fall steeply towards its silhouette, and with improved placement's
// one-pixel spacing the nearest sample above the silhouette is up to a pixel away
// (`improved-placement=0` gives 2.4%, ray-marching the pixels within 40 px of the light 0.8%).
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include <glm/gtc/constants.hpp>
#include <gtest/gtest.h>

#include "extremes_support.h"

namespace tyndall::test {
namespace {

samples::RenderOptions options() {
  samples::RenderOptions o;
  o.width = 320;
  o.height = 180;
  o.shadowMapSize = 1024;
  o.frames = 3;
  return o;
}

TEST(SpotExtremes, CameraOutsideInsideAndOnTheCone) {
  const host::Scene base = loadTestScene("spot-lamp");
  ASSERT_EQ(base.light.type, host::LightType::Spot);
  // spot-lamp's light hangs at (0, 7, 0) pointing down with a 30° outer cone: 5 units below it the
  // cone's radius is 5 tan 30°.
  const double boundary = 5.0 * std::tan(glm::radians(base.light.outerConeDegrees));
  struct Case {
    const char* name;
    glm::dvec3 position;
    glm::dvec3 target;
  };
  for (const Case& c : {Case{"camera outside the cone", base.camera.position, base.camera.target},
                        Case{"camera inside the cone", {0.5, 2.0, 0.5}, {4.0, 1.5, 4.0}},
                        Case{"camera on the cone", {boundary, 2.0, 0.0}, {-2.0, 3.0, -3.0}}}) {
    host::Scene scene = base;
    scene.camera.position = c.position;
    scene.camera.target = c.target;
    expectEveryProfileWithinTwiceItsBudget(scene, options(), c.name);
  }
}

// A lamp hanging inside its shade: a hollow box of five thin boxes, open at the bottom, one side
// shorter than the others, so that the walls cut the 60° cone on three sides (at ~49° from the
// axis) and let it out whole on the fourth. The light is inside the shade's bounding box: the
// host's shadow frustum starts at its minimum near distance (10⁻³ of its far distance), the
// walls are within 0.8 units of the light, and the beam leaves through the opening.
//
// This case found a defect of the epipolar unwarp next to a spot light, now fixed (High 5.1% →
// 3.4%, Balanced 5.3% → 3.9%, Performance 5.1% → 3.6%). On the far ground under the lamp, seen at
// a grazing angle, the view-ray length changes by 5–15% per pixel, more than the unwarp's 5%
// bilateral threshold: each pixel rejected its taps one pixel away and kept only the sample
// inside it, which improved placement's ~1-pixel spacing puts at the same sub-pixel offset (about
// 0.4 px below the centre) over many rows, so the pixel took L_in from there, where L_in changes
// by ~5% per pixel (−2% on every row). Nearer, on ground inside the beam, each sample's ray ended
// at the depth of its pixel's centre instead of at its own position (up to half a pixel's 3–5%
// change of ray length), at that same offset again, so the samples were biased alike (−0.5 to −1%
// per row); and along silhouettes a pixel with samples of its surface on one side only took the
// nearest one's value. The unwarp now tests taps against the pixel's plane in the depth buffer
// and extrapolates linearly on one-sided slices, and samples end on their pixel's plane
// (shaders/epipolar/epipolar_geometry.h, "The surface around a pixel").
// What is left is mostly the box's top face, a sliver one pixel high inside the beam where L_in
// changes by ~35% per pixel (14% low): its one sample on a slice is up to a pixel away
// (ray-marching the pixels within 80 px of the light, `epipole-radius=80`, leaves 0.06%). At the
// worst pixels the Reference agrees to 10⁻⁵ with a double-precision CPU integral of the
// radiometry; docs/EXTREMES.md has the scene as JSON and the commands.
host::Scene lampInsideItsShade() {
  host::Scene scene = loadTestScene("spot-lamp");
  // spot-lamp's ball hanging at 4.5 units would be inside the shade.
  std::erase_if(scene.objects, [](const host::Object& o) { return o.center.y > 4.0; });
  scene.light.position = {0.0, 4.0, 0.0};
  scene.light.direction = {0.0, -1.0, 0.0};
  scene.light.innerConeDegrees = 45.0;
  scene.light.outerConeDegrees = 60.0;
  scene.light.intensity = 30.0;
  // Top, ±x walls and +z wall down to y = 3.4; the −z wall only down to y = 3.7 (67° from the axis).
  for (const host::Object& wall :
       {boxObject({0.0, 4.35, 0.0}, {0.8, 0.05, 0.8}), boxObject({0.75, 3.85, 0.0}, {0.05, 0.45, 0.8}),
        boxObject({-0.75, 3.85, 0.0}, {0.05, 0.45, 0.8}), boxObject({0.0, 3.85, 0.75}, {0.7, 0.45, 0.05}),
        boxObject({0.0, 4.0, -0.75}, {0.7, 0.3, 0.05})}) {
    scene.objects.push_back(wall);
  }
  glm::dvec3 lo(1e9);
  glm::dvec3 hi(-1e9);
  for (std::size_t i = scene.objects.size() - 5; i < scene.objects.size(); ++i) {
    lo = glm::min(lo, scene.objects[i].center - scene.objects[i].halfExtents);
    hi = glm::max(hi, scene.objects[i].center + scene.objects[i].halfExtents);
  }
  EXPECT_TRUE(glm::all(glm::lessThan(lo, scene.light.position)) &&
              glm::all(glm::lessThan(scene.light.position, hi)))
      << "the light must be inside the shade's bounding box";
  return scene;
}

TEST(SpotExtremes, LightInsideAnOccludersBoundingBox) {
  expectEveryProfileWithinTwiceItsBudget(lampInsideItsShade(), options(), "spot light inside its shade");
}

// The same lamp as a point light: its six maps hold the shade's walls within 0.8 units of the light
// and the floor far below, the light leaves through the opening only. A point light's samples are
// all walked through the maps, across blocks of texels where a block decides
// (epipolar/block_walk.glsl): the walls' blocks shadow whatever lies behind them, the opening's
// blocks hold the near walls' edges and the far ground at once and are walked texel by texel.
TEST(SpotExtremes, PointLightInsideAnOccludersBoundingBox) {
  host::Scene scene = lampInsideItsShade();
  scene.light.type = host::LightType::Point;
  expectEveryProfileWithinTwiceItsBudget(scene, options(), "point light inside its shade");
}

}  // namespace
}  // namespace tyndall::test
