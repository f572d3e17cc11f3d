// The extremes suite (ctest label `extremes`), its spot-cone cases: every profile with the camera
// outside the spot light's cone (spot-lamp as it is), inside it looking out sideways, and exactly
// on its outer boundary, and a lamp inside its shade (an occluder's bounding box), as a spot light
// and as a point light, against the Reference as extremes_support.h says. At 320×180 rather than
// the suite's 160×90: there the hanging ball's silhouette, where L_in falls steeply, is a pixel or
// two from the light, closer than a sample spacing can follow.
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
// The far ground under the lamp is seen at a grazing angle, where the view-ray length changes by
// more than the unwarp's bilateral threshold per pixel, and the box's top face is a sliver one
// pixel high inside the beam: the case holds the unwarp's test of taps against the pixel's plane
// and samples whose rays end at their own position (epipolar_geometry.h, "The surface around a
// pixel"). docs/EXTREMES.md has the scene as JSON and the commands.
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
