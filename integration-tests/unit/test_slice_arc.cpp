// The slices' border arc (plugin/src/epipolar/slice_arc.cpp, shaders/epipolar/epipolar_geometry.h
// "Slice arc"): the arc mapping and its inverse, and that the arc is conservative — every point a
// spot light's cone lights, and every valid slice an off-screen epipole leaves, lands on it — while
// being a real restriction where it should be (the test would pass with the whole border
// otherwise).
#include <cmath>
#include <random>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <gtest/gtest.h>

#include "vulkan_projection.h"

#include "epipolar/epipolar_geometry.h"
#include "epipolar/slice_arc.h"

namespace tyndall {
namespace {

using namespace gpu;
using glm::dvec3;
using glm::dvec4;

CameraDesc makeCamera(dvec3 eye, dvec3 target, glm::dvec2 extent, bool reversed) {
  CameraDesc c;
  const glm::mat4 view = glm::mat4(glm::lookAt(eye, target, dvec3(0.0, 1.0, 0.0)));
  const glm::mat4 projection =
      glm::mat4(test::vulkanPerspective(glm::radians(60.0), extent.x / extent.y, 0.1, 500.0, reversed));
  std::copy(glm::value_ptr(view), glm::value_ptr(view) + 16, c.view.begin());
  std::copy(glm::value_ptr(projection), glm::value_ptr(projection) + 16, c.projection.begin());
  return c;
}

glm::mat4 viewProjOf(const CameraDesc& c) { return glm::make_mat4(c.projection.data()) * glm::make_mat4(c.view.data()); }

vec4 epipoleOf(const CameraDesc& c, const LightDesc& light) {
  const glm::mat4 vp = viewProjOf(c);
  return light.type == LightType::Directional
             ? tyn_epipole(tyn_epipole_clip_directional(vp, glm::normalize(glm::make_vec3(light.direction.data()))))
             : tyn_epipole(tyn_epipole_clip_local(vp, glm::make_vec3(light.position.data())));
}

TEST(SliceArc, MappingAndItsInverse) {
  for (vec2 extent : {vec2(640.0f, 360.0f), vec2(37.0f, 53.0f), vec2(1920.0f, 1080.0f)}) {
    const float perimeter = tyn_border_length_pixels(extent);
    for (uint n : {2u, 64u, 1024u}) {
      // The whole border from 0 is the plain layout, bit for bit.
      const vec2 whole(0.0f, perimeter);
      for (uint i = 0; i < n; ++i) {
        EXPECT_EQ(tyn_arc_exit_point(float(i), n, whole, extent), tyn_exit_point(float(i), n, extent));
      }
      // A partial arc, one crossing the top-left corner (start + length > P), and the whole border
      // from elsewhere.
      for (vec2 arc : {vec2(0.1f * perimeter, 0.3f * perimeter), vec2(0.8f * perimeter, 0.35f * perimeter),
                       vec2(0.37f * perimeter, perimeter)}) {
        const bool isWhole = arc.y >= perimeter;
        const double spacing = isWhole ? double(perimeter) / n : double(arc.y) / (n - 1);
        for (uint i = 0; i < n; ++i) {
          const float s = tyn_arc_border_position(float(i), n, arc, extent);
          const double expected = std::fmod(double(arc.x) + i * spacing, double(perimeter));
          const double tolerance = 2e-3 * std::max(1.0, double(perimeter) / 2000.0);
          EXPECT_LT(std::min(std::abs(s - expected), perimeter - std::abs(s - expected)), tolerance) << i;
          // The exit point is on the border at that perimeter distance, and inverts to slice i.
          const vec2 x = tyn_arc_exit_point(float(i), n, arc, extent);
          const float back = tyn_border_position(x, extent);
          EXPECT_LT(std::min(std::abs(back - s), perimeter - std::abs(back - s)), tolerance) << i;
          const float c = tyn_arc_slice_coordinate(back, n, arc, extent);
          ASSERT_GE(c, 0.0f) << i;
          EXPECT_LT(std::min(std::abs(c - float(i)), float(n) - std::abs(c - float(i))), 2e-3f * float(n) / 64.0f + 1e-3f)
              << "slice " << i << " of " << n;
        }
        if (!isWhole) {
          // Off the arc: no slice. Half a spacing past either end, and the middle of the gap.
          for (double off : {double(arc.y) + 0.5 * spacing + 0.5, double(perimeter) - 0.5 * spacing - 0.5,
                             0.5 * (double(arc.y) + perimeter)}) {
            const float s = float(std::fmod(double(arc.x) + off, double(perimeter)));
            EXPECT_EQ(tyn_arc_slice_coordinate(s, n, arc, extent), -1.0f) << off;
          }
        }
      }
    }
  }
}

// Points inside a spot light's cone, seen by the camera, lie on epipolar lines that leave the
// screen on the arc (so their pixels are not zeroed); and from outside the cone the arc is a
// fraction of the border.
TEST(SliceArc, SpotConeArcHoldsEveryLitPoint) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const glm::dvec2 extent(320.0, 180.0);
  const vec2 fextent(320.0f, 180.0f);
  const uint n = 512;
  int partial = 0;
  int cases = 0;
  int checkedPoints = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const bool reversed = trial % 2 == 1;
    const dvec3 eye(u(rng) * 10.0, 2.0 + u(rng) * 2.0, 12.0 + u(rng) * 4.0);
    const CameraDesc camera = makeCamera(eye, dvec3(u(rng), u(rng), 0.0), extent, reversed);
    LightDesc light;
    light.type = LightType::Spot;
    const dvec3 position(u(rng) * 6.0, 6.0 + u(rng) * 3.0, u(rng) * 6.0);
    const dvec3 axis = glm::normalize(dvec3(u(rng) * 0.6, -1.0, u(rng) * 0.6));
    light.position = {float(position.x), float(position.y), float(position.z)};
    light.direction = {float(axis.x), float(axis.y), float(axis.z)};
    light.outerConeRadians = float(0.15 + 0.5 * (u(rng) + 1.0) * 0.5);
    light.innerConeRadians = light.outerConeRadians * 0.8f;
    const vec4 epipole = epipoleOf(camera, light);
    const SliceArc arc = sliceArc(camera, light, epipole, fextent);
    ++cases;
    if (arc.fraction < 1.0f) ++partial;
    const double cosCamera = glm::dot(glm::normalize(eye - position), axis);
    if (cosCamera >= std::cos(double(light.outerConeRadians))) {
      EXPECT_FALSE(arc.cone) << "camera inside the cone, trial " << trial;
    }
    // Random points of the cone, projected.
    const glm::dmat4 vp = glm::dmat4(viewProjOf(camera));
    const dvec3 side = glm::normalize(glm::cross(axis, dvec3(1.0, 0.0, 0.0)));
    const dvec3 side2 = glm::cross(axis, side);
    const vec4 rect = tyn_epipolar_screen_rect(fextent);
    const glm::dvec2 epipolePixel = glm::dvec2(tyn_pixel_from_ndc(tyn_epipole_ndc(epipole), fextent));
    for (int k = 0; k < 400; ++k) {
      const double angle = double(light.outerConeRadians) * std::sqrt(0.5 * (u(rng) + 1.0));
      const double around = 3.14159265358979 * u(rng);
      const dvec3 dir = std::cos(angle) * axis + std::sin(angle) * (std::cos(around) * side + std::sin(around) * side2);
      const dvec3 point = position + dir * (0.05 + 20.0 * 0.5 * (u(rng) + 1.0));
      const dvec4 clip = vp * dvec4(point, 1.0);
      if (!(clip.w > 1e-6)) continue;
      const vec2 p = vec2(float(clip.x / clip.w), float(clip.y / clip.w));
      if (p.x < rect.x || p.x > rect.z || p.y < rect.y || p.y > rect.w) continue;
      // Within a pixel of the epipole the line's direction is not defined (the fix-up block).
      if (epipole.z > 0.0f && glm::length(glm::dvec2(tyn_pixel_from_ndc(p, fextent)) - epipolePixel) < 1.0) continue;
      ++checkedPoints;
      const float c = tyn_arc_slice_coordinate_of(epipole, p, n, arc.arc, fextent);
      EXPECT_GE(c, 0.0f) << "trial " << trial << ": a lit point off the arc (" << 100.0f * arc.fraction
                         << "% of the border)";
    }
  }
  EXPECT_GT(checkedPoints, 10000);
  // Most cameras here are outside the cone: the arc is then a part of the border.
  EXPECT_GT(partial, cases / 2) << partial << " of " << cases;
}

// An off-screen epipole (directional light): every slice that would be valid on the whole border
// has its exit point on the arc, and the arc is shorter than the border; on screen it is the
// whole border.
TEST(SliceArc, OffScreenEpipoleKeepsEveryValidSlice) {
  const glm::dvec2 extent(320.0, 180.0);
  const vec2 fextent(320.0f, 180.0f);
  const CameraDesc camera = makeCamera(dvec3(0.0, 2.0, 10.0), dvec3(0.0, 2.0, 0.0), extent, false);
  int offScreen = 0;
  for (dvec3 toLight : {dvec3(0.0, 0.1, -1.0), dvec3(3.0, 0.5, -1.0), dvec3(-1.0, 2.0, -1.0), dvec3(0.0, 0.0, 1.0),
                        dvec3(1.0, -0.2, 0.3), dvec3(0.2, 0.9, -0.1), dvec3(-0.8, 0.05, -0.5)}) {
    LightDesc light;
    light.type = LightType::Directional;
    const dvec3 d = -glm::normalize(toLight);
    light.direction = {float(d.x), float(d.y), float(d.z)};
    const vec4 epipole = epipoleOf(camera, light);
    const SliceArc arc = sliceArc(camera, light, epipole, fextent);
    if (tyn_epipole_on_screen(epipole, fextent)) {
      EXPECT_EQ(arc.fraction, 1.0f);
      continue;
    }
    ++offScreen;
    EXPECT_LT(arc.fraction, 1.0f);
    EXPECT_TRUE(arc.screen);
    const uint n = 8192;
    for (uint i = 0; i < n; ++i) {
      vec4 ends;
      const vec2 exitPoint = tyn_exit_point(float(i), n, fextent);
      if (!tyn_slice_end_points(epipole, exitPoint, fextent, ends)) continue;
      EXPECT_GE(tyn_arc_slice_coordinate(tyn_border_position(exitPoint, fextent), 512u, arc.arc, fextent), 0.0f)
          << "valid exit point " << i << " of " << n << " off the arc";
    }
  }
  EXPECT_GE(offScreen, 4);
}

}  // namespace
}  // namespace tyndall
