// Depth conventions detected from the projection matrix (plugin/src/camera.cpp).
#include <cmath>

#include <gtest/gtest.h>

#include "vulkan_projection.h"

#include <glm/gtc/matrix_transform.hpp>

#include "camera.h"

namespace {

using tyndall::test::vulkanPerspective;

struct Case {
  bool reversed;
  double farPlane;
};

TEST(Projection, DetectsEveryConvention) {
  for (Case c : {Case{false, 200.0}, Case{true, 200.0}, Case{false, INFINITY}, Case{true, INFINITY}}) {
    tyndall::ProjectionInfo info;
    const glm::dmat4 p = vulkanPerspective(1.0, 16.0 / 9.0, 0.1, c.farPlane, c.reversed);
    ASSERT_TRUE(tyndall::analyzeProjection(glm::dmat4(glm::mat4(p)), info).ok());
    EXPECT_EQ(info.reversed, c.reversed);
    EXPECT_EQ(info.infiniteFar, std::isinf(c.farPlane));
    EXPECT_NEAR(info.nearDistance, 0.1, 1e-6);
    if (!std::isinf(c.farPlane)) {
      EXPECT_NEAR(info.farDistance, c.farPlane, 1e-3 * c.farPlane);
    }
    EXPECT_EQ(info.farNdc, c.reversed ? 0.0f : 1.0f);
    EXPECT_EQ(info.nearNdc, c.reversed ? 1.0f : 0.0f);
  }
}

TEST(Projection, FarToNearRatios) {
  // Finite far planes up to ~4·10^6 near distances are told apart from infinity in float.
  for (double ratio : {10.0, 1e3, 1e5}) {
    for (bool reversed : {false, true}) {
      tyndall::ProjectionInfo info;
      const glm::dmat4 p = glm::dmat4(glm::mat4(vulkanPerspective(1.0, 1.0, 0.01, 0.01 * ratio, reversed)));
      ASSERT_TRUE(tyndall::analyzeProjection(p, info).ok()) << ratio;
      EXPECT_FALSE(info.infiniteFar) << ratio;
      EXPECT_NEAR(info.farDistance / (0.01 * ratio), 1.0, 0.05) << ratio << " reversed " << reversed;
    }
  }
  tyndall::ProjectionInfo info;
  ASSERT_TRUE(tyndall::analyzeProjection(glm::dmat4(glm::mat4(vulkanPerspective(1.0, 1.0, 0.01, 1e7, false))), info).ok());
  EXPECT_TRUE(info.infiniteFar);
}

TEST(Projection, RejectsBadMatrices) {
  tyndall::ProjectionInfo info;
  EXPECT_FALSE(tyndall::analyzeProjection(glm::dmat4(0.0), info).ok());  // singular
  glm::dmat4 nan = vulkanPerspective(1.0, 1.0, 0.1, 100.0, false);
  nan[0][0] = NAN;
  EXPECT_FALSE(tyndall::analyzeProjection(nan, info).ok());
  EXPECT_FALSE(tyndall::analyzeProjection(glm::dmat4(1.0), info).ok());  // orthographic
  // A standard-Z matrix built with near and far swapped is exactly a reverse-Z matrix and is
  // accepted as one; a far plane behind the camera (here far = −5) is near >= far.
  const glm::dmat4 swapped = vulkanPerspective(1.0, 1.0, 100.0, 0.1, false);
  ASSERT_TRUE(tyndall::analyzeProjection(swapped, info).ok());
  EXPECT_TRUE(info.reversed);
  EXPECT_NEAR(info.nearDistance, 0.1, 1e-9);
  EXPECT_NEAR(info.farDistance, 100.0, 1e-9);
  for (bool reversed : {false, true}) {
    const glm::dmat4 behind = vulkanPerspective(1.0, 1.0, 0.1, -5.0, reversed);
    const tyndall::Outcome o = tyndall::analyzeProjection(behind, info);
    EXPECT_FALSE(o.ok());
    EXPECT_EQ(o.status, tyndall::Status::InvalidArgument);
    EXPECT_NE(o.message.find("near >= far"), std::string::npos) << o.message;
  }
}

// A spot light's cone against the view pyramid of a camera at (0, 0, 5) looking down −z (60°
// vertical, 16:9: the horizontal half-angle is 45.7°), with each depth convention.
TEST(SpotCulling, OnlyConesWhollyOutsideOneSidePlaneMissTheView) {
  const double radians = std::acos(-1.0) / 180.0;
  for (bool reversed : {false, true}) {
    const glm::dmat4 clipToView = glm::inverse(vulkanPerspective(60.0 * radians, 16.0 / 9.0, 0.1, 100.0, reversed));
    const glm::dmat4 viewToWorld = glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 0.0, 5.0));
    auto misses = [&](glm::dvec3 position, glm::dvec3 axis, double outerDegrees) {
      return tyndall::spotConeMissesView(viewToWorld, clipToView, position, glm::normalize(axis), outerDegrees * radians);
    };
    // Behind the camera, shining away, however wide: behind the plane the view rays start from.
    EXPECT_TRUE(misses({0, 0, 9}, {0, 0, 1}, 35.0));
    EXPECT_TRUE(misses({0, 0, 9}, {0, 0, 1}, 85.0));
    // Behind, shining sideways and a little back: its edge rays run flatter than the view's edge
    // and never catch up with it. Shining sideways and forward: they cross into the view.
    EXPECT_TRUE(misses({0, 0, 9}, {1, 0, 0.2}, 40.0));
    EXPECT_FALSE(misses({0, 0, 9}, {1, 0, -1.5}, 40.0));
    // In front, shining down across the view: seen.
    EXPECT_FALSE(misses({0, 3, -5}, {0, -1, 0}, 30.0));
    // Far to the right, shining further right: misses; shining left into the view: seen.
    EXPECT_TRUE(misses({40, 0, -5}, {1, 0, 0}, 30.0));
    EXPECT_FALSE(misses({40, 0, -5}, {-1, 0, 0}, 30.0));
    // Apex in the view: seen whatever it points at.
    EXPECT_FALSE(misses({0, 0, -5}, {0, 0, 1}, 10.0));
    // Above the view shining up; and the camera itself inside a cone pointing away.
    EXPECT_TRUE(misses({0, 40, -5}, {0, 1, 0}, 20.0));
    EXPECT_FALSE(misses({0, 0, 5}, {0, 0, 1}, 20.0));
  }
}

}  // namespace
