// The rectified shadow maps of prefiltered single scattering (shaders/prefiltered/rectification.h,
// compiled as C++ from the shaders' source, and plugin/src/prefiltered/rectification_setup.h)
// against independent double-precision constructions: frusta sampled from the projection matrices,
// rectified coordinates recomputed from their definitions, brute-force searches for extrema, exact
// integrals, and the Fourier series of the step written directly as a square wave.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "vulkan_projection.h"

#include "prefiltered/rectification.h"
#include "prefiltered/rectification_setup.h"

namespace {

using namespace tyndall::gpu;
using namespace tyndall::prefiltered;
using glm::dmat4;
using glm::dvec2;
using glm::dvec3;
using glm::dvec4;

constexpr double kPi = 3.14159265358979323846;
const double kInf = std::numeric_limits<double>::infinity();

// ---------------------------------------------------------------------------------------------
// Measured worst errors, printed as one line when the binary ends.

struct Worst {
  double roundTripWorld = 0.0;      // relative to the point's distance from the camera
  double roundTripTexcoord = 0.0;   // texture-coordinate units
  double boundsOvershoot = 0.0;     // how far a frustum point lies outside the bounds (relative)
  double boundsSlack = 0.0;         // how far the closest frustum point stays from a bound (relative)
  double rowSpread = 0.0;           // spread of v and depth along one view ray (float path)
  double lightRaySpread = 0.0;      // spread of (u, v) along one light ray (float path)
  double sliceTheta = 0.0;          // per-slice θ range vs brute force (rad)
  double weightSum = 0.0;           // relative, prefix weights vs ∫ over the row
  double prefixAverage = 0.0;       // normalised prefix sums vs double
  double inscattering = 0.0;        // relative, per-pixel evaluation vs exact integral
  double greyBound = 0.0;           // tyn_weighted_average_max_error vs brute force
  double fourierSeries = 0.0;       // float basis vs double square-wave series
  double fourierAt[3] = {0, 0, 0};  // truncation error at d = 0.05, 0.1, 0.25 (M = 32)
  double gibbs = 0.0;               // overshoot / jump
  double quantised = 0.0;           // unorm8 reconstruction error
  double filtering = 0.0;           // prefiltered reconstruction vs filtered reconstructions
  double projRowSpread = 0.0;       // projective: spread of v and depth along a view ray (float)
  double projLightSpread = 0.0;     // projective: spread of (u, v) along a light ray (float)
  double projOffsetSpread = 0.0;    // projective, camera-relative form: spread along a view ray
};
Worst g_worst;

void keepMax(double& slot, double value) { slot = std::max(slot, value); }

class SummaryPrinter : public ::testing::Environment {
 public:
  void TearDown() override {
    const Worst& w = g_worst;
    std::printf(
        "[ Rectify ] worst: world round trip %.1e rel, texcoord round trip %.1e, bounds overshoot "
        "%.1e / slack %.1e rel, row spread %.1e, light-ray spread %.1e, slice theta %.1e rad, weight "
        "sum %.1e rel, prefix average %.1e, inscattering %.1e rel, grey bound %.1e, fourier series "
        "%.1e, truncation at d=0.05/0.1/0.25: %.3f/%.3f/%.3f, gibbs %.4f of the jump, unorm8 %.4f, "
        "filtering %.1e, projective row %.1e (camera-relative %.1e) / light ray %.1e\n",
        w.roundTripWorld, w.roundTripTexcoord, w.boundsOvershoot, w.boundsSlack, w.rowSpread,
        w.lightRaySpread, w.sliceTheta, w.weightSum, w.prefixAverage, w.inscattering, w.greyBound,
        w.fourierSeries, w.fourierAt[0], w.fourierAt[1], w.fourierAt[2], w.gibbs, w.quantised,
        w.filtering, w.projRowSpread, w.projOffsetSpread, w.projLightSpread);
  }
};
[[maybe_unused]] ::testing::Environment* const g_summary =
    ::testing::AddGlobalTestEnvironment(new SummaryPrinter);

// ---------------------------------------------------------------------------------------------
// Cameras and lights, in double

using tyndall::test::vulkanPerspective;

struct Camera {
  std::string name;
  dvec3 position;
  dvec3 target;
  double fovYDegrees;
  double aspect;
  double nearPlane;
  double farPlane;  // INFINITY: infinite far plane
  bool reversed;
  double sky;       // sky distance with an infinite far plane
  dmat4 view{1.0}, proj{1.0}, viewProj{1.0}, inverseViewProj{1.0};
  dvec3 forward{0.0}, up{0.0}, right{0.0};
  bool infinite() const { return std::isinf(farPlane); }
};

Camera makeCamera(std::string name, dvec3 position, dvec3 target, double fovY, double aspect,
                  double nearPlane, double farPlane, bool reversed, double sky = 1000.0) {
  Camera c{std::move(name), position, target, fovY, aspect, nearPlane, farPlane, reversed, sky};
  c.view = glm::lookAt(position, target, dvec3(0.0, 1.0, 0.0));
  c.proj = vulkanPerspective(glm::radians(fovY), aspect, nearPlane, farPlane, reversed);
  c.viewProj = c.proj * c.view;
  c.inverseViewProj = glm::inverse(c.viewProj);
  const dmat4 toWorld = glm::inverse(c.view);
  c.forward = glm::normalize(dvec3(toWorld * dvec4(0.0, 0.0, -1.0, 0.0)));
  c.up = glm::normalize(dvec3(toWorld * dvec4(0.0, 1.0, 0.0, 0.0)));
  c.right = glm::normalize(dvec3(toWorld * dvec4(1.0, 0.0, 0.0, 0.0)));
  return c;
}

std::vector<Camera> cameras() {
  const dvec3 p(3.0, 2.0, 5.0), t(-4.0, 0.5, -7.0);
  return {makeCamera("standard", p, t, 60.0, 16.0 / 9.0, 0.1, 200.0, false),
          makeCamera("reverse-Z", p, t, 60.0, 16.0 / 9.0, 0.1, 200.0, true),
          makeCamera("infinite far", p, t, 60.0, 16.0 / 9.0, 0.1, kInf, false, 800.0),
          makeCamera("reverse-Z infinite far", p, t, 60.0, 16.0 / 9.0, 0.1, kInf, true, 800.0),
          makeCamera("narrow", dvec3(-20.0, 15.0, 4.0), dvec3(0.0, 0.0, 0.0), 20.0, 1.0, 0.5, 50.0, false),
          makeCamera("wide, looking down", dvec3(0.0, 30.0, 0.0), dvec3(1.0, 0.0, -2.0), 100.0, 4.0 / 3.0, 0.05, 400.0, true)};
}

// Light directions (direction the light travels) for a camera, with the expected special case.
struct Light {
  std::string name;
  dvec3 direction;
};

std::vector<Light> lights(const Camera& c) {
  return {{"from above", glm::normalize(dvec3(0.3, -1.0, 0.45))},
          {"from the side", glm::normalize(dvec3(-0.8, -0.3, -0.5))},
          {"grazing", glm::normalize(dvec3(0.1, -0.2, 1.0))},
          {"perpendicular to the view", glm::normalize(glm::cross(c.forward, c.up) + 0.2 * c.up)},
          {"along the view (light behind)", glm::normalize(c.forward + 0.05 * c.right + 0.03 * c.up)},
          {"into the view (looking at it)", -glm::normalize(c.forward - 0.04 * c.right + 0.05 * c.up)}};
}

double nearNdc(const Camera& c) { return c.reversed ? 1.0 : 0.0; }

dvec3 unproject(const Camera& c, dvec3 ndc) {
  const dvec4 p = c.inverseViewProj * dvec4(ndc, 1.0);
  return dvec3(p) / p.w;
}

// Unit direction of the view ray through an NDC point.
dvec3 rayDirection(const Camera& c, dvec2 ndc) {
  return glm::normalize(unproject(c, dvec3(ndc, nearNdc(c))) - c.position);
}

// The end of the volume along the ray through ndc: the far plane, or the sky sphere.
dvec3 farPoint(const Camera& c, dvec2 ndc) {
  if (c.infinite()) return c.position + rayDirection(c, ndc) * c.sky;
  return unproject(c, dvec3(ndc, c.reversed ? 0.0 : 1.0));
}

// Whether a direction from the camera lies in the view frustum (its cone).
bool inFrustumCone(const Camera& c, dvec3 direction) {
  const dvec4 clip = c.viewProj * dvec4(c.position + direction, 1.0);
  return clip.w > 0.0 && std::abs(clip.x) <= clip.w && std::abs(clip.y) <= clip.w;
}

ViewFrustum frustumOf(const Camera& c) {
  ViewFrustum f;
  const tyndall::Outcome o = buildViewFrustum(c.view, c.proj, c.sky, f);
  EXPECT_TRUE(o.ok()) << c.name << ": " << o.message;
  return f;
}

// (r, φ, θ) in double from the definitions, in the rectification's light frame.
dvec3 rectifiedDouble(const NonLinearRectification& rect, dvec3 p) {
  const dvec3 q = p - rect.origin;
  const double x = glm::dot(q, rect.axisX), y = glm::dot(q, rect.axisY), h = glm::dot(q, rect.axisZ);
  const double r = std::hypot(x, y);
  return dvec3(r, std::atan2(y, x), std::atan2(r, h));
}

vec3 f3(dvec3 v) { return vec3(v); }
dvec3 d3(vec3 v) { return dvec3(v); }

// Frustum points: random (uniform in NDC and in the fraction of the way to the far end), the
// corners, a grid on the far surface, dense samples along its edges, and the light axis when it
// lies in the frustum (the interior extrema of θ).
std::vector<dvec3> frustumPoints(const Camera& c, const dvec3& lightDir, std::mt19937& rng, int randomCount) {
  std::uniform_real_distribution<double> ndc(-1.0, 1.0), frac(0.0, 1.0);
  std::vector<dvec3> pts;
  for (int i = 0; i < randomCount; ++i) {
    const dvec2 n(ndc(rng), ndc(rng));
    pts.push_back(c.position + frac(rng) * (farPoint(c, n) - c.position));
  }
  const int grid = 300;
  for (int i = 0; i <= grid; ++i) {
    for (int j = 0; j <= grid; ++j) pts.push_back(farPoint(c, dvec2(-1.0 + 2.0 * i / grid, -1.0 + 2.0 * j / grid)));
  }
  const int edge = 4000;
  for (int i = 0; i <= edge; ++i) {
    const double s = -1.0 + 2.0 * i / edge;
    for (dvec2 n : {dvec2(s, -1.0), dvec2(s, 1.0), dvec2(-1.0, s), dvec2(1.0, s)}) pts.push_back(farPoint(c, n));
  }
  for (dvec3 axis : {lightDir, -lightDir}) {
    if (inFrustumCone(c, axis)) {
      const double reach = c.infinite() ? c.sky : 10.0;
      pts.push_back(c.position + axis * reach);
    }
  }
  return pts;
}

// ---------------------------------------------------------------------------------------------
// Non-linear rectification: frame, round trips, bounds

TEST(Rectification, LightFrameIsRightHandedWithZAlongTheLight) {
  for (const Camera& c : cameras()) {
    const ViewFrustum f = frustumOf(c);
    EXPECT_NEAR(glm::length(f.position - c.position), 0.0, 1e-9) << c.name;
    for (const Light& l : lights(c)) {
      const NonLinearRectification rect = computeNonLinearRectification(f, l.direction * 3.0);
      EXPECT_LT(glm::length(rect.axisZ - l.direction), 1e-12) << c.name << " / " << l.name;
      EXPECT_NEAR(glm::length(rect.axisX), 1.0, 1e-12);
      EXPECT_NEAR(glm::dot(rect.axisX, rect.axisZ), 0.0, 1e-12);
      EXPECT_NEAR(glm::dot(rect.axisY, rect.axisZ), 0.0, 1e-12);
      EXPECT_NEAR(glm::dot(rect.axisX, rect.axisY), 0.0, 1e-12);
      EXPECT_NEAR(glm::dot(glm::cross(rect.axisX, rect.axisY), rect.axisZ), 1.0, 1e-12);
      // Depth grows along a light ray like the original shadow depth: moving with the light
      // lowers θ, raises the stored flipped inclination.
      const NonLinearRectificationParams gp = toGpu(rect);
      const dvec3 p = c.position + 20.0 * c.forward + 3.0 * c.right;
      const float d0 = tyn_rectified_depth(gp, tyn_rectified_from_world(gp, f3(p)).z);
      const float d1 = tyn_rectified_depth(gp, tyn_rectified_from_world(gp, f3(p + l.direction * 2.0)).z);
      EXPECT_GT(d1, d0) << c.name << " / " << l.name;
    }
  }
}

TEST(Rectification, RoundTripsWorldRectifiedTexcoord) {
  std::mt19937 rng(7);
  for (const Camera& c : cameras()) {
    const ViewFrustum f = frustumOf(c);
    for (const Light& l : lights(c)) {
      const NonLinearRectification rect = computeNonLinearRectification(f, l.direction);
      const NonLinearRectificationParams gp = toGpu(rect);
      std::uniform_real_distribution<double> ndc(-1.0, 1.0), frac(0.01, 1.0);
      for (int i = 0; i < 2000; ++i) {
        const dvec3 p = c.position + frac(rng) * (farPoint(c, dvec2(ndc(rng), ndc(rng))) - c.position);
        const dvec3 exact = rectifiedDouble(rect, p);
        const vec3 got = tyn_rectified_from_world(gp, f3(p));
        const double dist = glm::length(p - c.position);
        // float world coordinates carry ~6e-8 of their magnitude; angles ~that over r.
        const double scale = glm::length(p) + glm::length(c.position);
        EXPECT_NEAR(got.x, exact.x, 4e-7 * scale) << c.name << " / " << l.name;
        EXPECT_NEAR(got.z, exact.z, 4e-7 * scale / dist) << c.name << " / " << l.name;
        if (exact.x > 1e-3 * dist) {
          double dphi = std::abs(got.y - exact.y);
          dphi = std::min(dphi, 2.0 * kPi - dphi);
          EXPECT_LT(dphi, 4e-7 * scale / exact.x) << c.name << " / " << l.name;
        }
        // Back to the world, away from the light axis where h = r·cot θ is ill-conditioned.
        if (std::sin(exact.z) > 0.05) {
          const dvec3 back = d3(tyn_world_from_rectified(gp, got));
          const double err = glm::length(back - p) / dist;
          keepMax(g_worst.roundTripWorld, err);
          EXPECT_LT(err, 1e-6 * scale / dist / std::sin(exact.z)) << c.name << " / " << l.name;
        }
        // Texture coordinates and back.
        const vec3 uvd = tyn_rectified_texcoord(gp, got);
        const vec3 again = tyn_rectified_from_texcoord(gp, uvd);
        const double texErr = std::max({std::abs(double(again.x - got.x)) / rect.rMax,
                                        std::abs(double(again.y - got.y)) / rect.phiExtent,
                                        std::abs(double(again.z - got.z)) / (rect.thetaMaxGuarded - rect.thetaMinGuarded)});
        keepMax(g_worst.roundTripTexcoord, texErr);
        EXPECT_LT(texErr, 2e-6) << c.name << " / " << l.name;
      }
      // The view-ray form agrees with the point form.
      const dvec3 d = rayDirection(c, dvec2(0.3, -0.6));
      const vec3 viaRay = tyn_rectified_from_view_ray(gp, f3(d), 37.0f);
      const dvec3 exact = rectifiedDouble(rect, c.position + 37.0 * d);
      EXPECT_NEAR(viaRay.x, exact.x, 1e-4);
      EXPECT_NEAR(viaRay.y, exact.y, 1e-5);
      EXPECT_NEAR(viaRay.z, exact.z, 1e-5);
      // A light-ray point has the light ray's (r, φ).
      const dvec3 onRay = d3(tyn_light_ray_point(gp, 12.5f, 0.2f, -30.0f));
      const dvec3 back = rectifiedDouble(rect, onRay);
      EXPECT_NEAR(back.x, 12.5, 1e-4);
      EXPECT_NEAR(back.y, 0.2, 1e-5);
    }
  }
}

TEST(Rectification, BoundsContainTheFrustumAndAreTight) {
  std::mt19937 rng(11);
  const double guardFraction = 0.5 * double(TYN_RECT_THETA_GUARD) / (1.0 + double(TYN_RECT_THETA_GUARD));
  for (const Camera& c : cameras()) {
    const ViewFrustum f = frustumOf(c);
    for (const Light& l : lights(c)) {
      const std::string what = c.name + " / " + l.name;
      const NonLinearRectification rect = computeNonLinearRectification(f, l.direction);
      const NonLinearRectificationParams gp = toGpu(rect);
      const bool axisInside = inFrustumCone(c, l.direction) || inFrustumCone(c, -l.direction);
      EXPECT_EQ(rect.fullCircle, axisInside) << what;
      const std::vector<dvec3> pts = frustumPoints(c, l.direction, rng, 20000);
      double rMax = 0.0, phiLo = kInf, phiHi = -kInf, thetaLo = kInf, thetaHi = -kInf;
      for (const dvec3& p : pts) {
        const dvec3 q = rectifiedDouble(rect, p);
        rMax = std::max(rMax, q.x);
        thetaLo = std::min(thetaLo, q.z);
        thetaHi = std::max(thetaHi, q.z);
        if (q.x > 1e-9) {
          phiLo = std::min(phiLo, q.y);
          phiHi = std::max(phiHi, q.y);
        }
        // Float path: every frustum point has texture coordinates in [0, 1] and its depth inside
        // the guard band.
        // Tolerances: float rounds p and o to ~6e-8 of their magnitude, which moves r by that,
        // φ by that over r and θ by that over |p − o|.
        const vec3 uvd = tyn_rectified_texcoord(gp, tyn_rectified_from_world(gp, f3(p)));
        const double rounding = 2e-7 * (glm::length(p) + glm::length(c.position));
        const double tolU = 1e-6 + rounding / rect.rMax;
        const double tolV = 1e-6 + rounding / std::max(q.x, 1e-30) / rect.phiExtent;
        const double tolDepth = 1e-6 + rounding / std::max(glm::length(p - c.position), 1e-30) /
                                           (rect.thetaMaxGuarded - rect.thetaMinGuarded);
        EXPECT_LE(uvd.x, 1.0 + tolU) << what;
        EXPECT_GE(uvd.y, -tolV) << what;
        EXPECT_LE(uvd.y, 1.0 + tolV) << what;
        EXPECT_GE(uvd.z, guardFraction - tolDepth) << what;
        EXPECT_LE(uvd.z, 1.0 - guardFraction + tolDepth) << what;
      }
      const double thetaRange = rect.thetaMax - rect.thetaMin;
      // Contained (double): no point beyond a bound by more than rounding.
      const double overshoot = std::max({(rMax - rect.rMax) / rect.rMax, (rect.thetaMin - thetaLo) / thetaRange,
                                         (thetaHi - rect.thetaMax) / thetaRange,
                                         rect.fullCircle ? 0.0 : (phiHi - 0.5 * rect.phiExtent) / rect.phiExtent,
                                         rect.fullCircle ? 0.0 : (-0.5 * rect.phiExtent - phiLo) / rect.phiExtent});
      keepMax(g_worst.boundsOvershoot, overshoot);
      EXPECT_LT(overshoot, 1e-9) << what;
      // Tight: some point within 1e-4 (relative) of every bound.
      const double slack = std::max({(rect.rMax - rMax) / rect.rMax, (thetaLo - rect.thetaMin) / thetaRange,
                                     (rect.thetaMax - thetaHi) / thetaRange,
                                     rect.fullCircle ? 0.0 : (0.5 * rect.phiExtent - phiHi) / rect.phiExtent,
                                     rect.fullCircle ? 0.0 : (phiLo + 0.5 * rect.phiExtent) / rect.phiExtent});
      keepMax(g_worst.boundsSlack, slack);
      EXPECT_LT(slack, 1e-4) << what;
      // The guard band stretches the θ interval by 10%, centred.
      EXPECT_NEAR(rect.thetaMaxGuarded - rect.thetaMinGuarded, 1.1 * thetaRange, 1e-6 * thetaRange) << what;
      EXPECT_NEAR(rect.thetaMaxGuarded + rect.thetaMinGuarded, rect.thetaMax + rect.thetaMin, 1e-12) << what;
      if (rect.fullCircle) {
        EXPECT_DOUBLE_EQ(rect.phiExtent, 2.0 * kPi) << what;
      } else {
        EXPECT_LT(rect.phiExtent, kPi) << what;
      }
    }
  }
}

TEST(Rectification, FullCircleWhenTheLightAxisIsInTheFrustum) {
  const Camera c = makeCamera("axis", dvec3(1.0, 2.0, 3.0), dvec3(1.0, 2.0, -10.0), 60.0, 16.0 / 9.0, 0.1, 100.0, false);
  const ViewFrustum f = frustumOf(c);
  // The light travels along a view ray: θ_min = 0 (a view ray looks away from the light).
  const NonLinearRectification along = computeNonLinearRectification(f, glm::normalize(dvec3(0.2, 0.1, -1.0)));
  EXPECT_TRUE(along.fullCircle);
  EXPECT_DOUBLE_EQ(along.phiExtent, 2.0 * kPi);
  EXPECT_EQ(along.thetaMin, 0.0);
  EXPECT_LT(along.thetaMax, 0.5 * kPi);
  // The light comes towards the camera from inside the view: θ_max = π (looking into the light).
  const NonLinearRectification into = computeNonLinearRectification(f, glm::normalize(dvec3(-0.2, 0.1, 1.0)));
  EXPECT_TRUE(into.fullCircle);
  EXPECT_DOUBLE_EQ(into.phiExtent, 2.0 * kPi);
  EXPECT_EQ(into.thetaMax, kPi);
  EXPECT_GT(into.thetaMin, 0.5 * kPi);
  // The light source just outside the top of the screen (vertical half-angle 30°): not the full
  // circle, but an azimuth range close to π.
  const double psi = glm::radians(31.0);
  const NonLinearRectification outside =
      computeNonLinearRectification(f, -dvec3(0.0, std::sin(psi), -std::cos(psi)));
  EXPECT_FALSE(outside.fullCircle);
  EXPECT_GT(outside.phiExtent, 0.8 * kPi);
  EXPECT_LT(outside.phiExtent, kPi);
  EXPECT_GT(outside.thetaMax, 0.9 * kPi);
  EXPECT_LT(outside.thetaMax, kPi);
  // Every view direction's slice wraps around: the rows cover every azimuth.
  const NonLinearRectificationParams gp = toGpu(into);
  for (int i = 0; i < 64; ++i) {
    const double phi = -kPi + (i + 0.5) * 2.0 * kPi / 64.0;
    const vec2 range = tyn_slice_theta_range(gp, float(phi));
    EXPECT_LT(range.x, range.y) << phi;
    EXPECT_NEAR(range.y, kPi, 1e-6) << phi;  // every slice contains the light's own direction
  }
}

TEST(Rectification, ViewRaysAreRowsOfConstantDepthAndLightRaysTexels) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> ndc(-1.0, 1.0);
  for (const Camera& c : cameras()) {
    const ViewFrustum f = frustumOf(c);
    for (const Light& l : lights(c)) {
      const NonLinearRectification rect = computeNonLinearRectification(f, l.direction);
      const NonLinearRectificationParams gp = toGpu(rect);
      for (int i = 0; i < 200; ++i) {
        const dvec2 n(ndc(rng), ndc(rng));
        const dvec3 d = rayDirection(c, n);
        const double rayLength = glm::length(farPoint(c, n) - c.position);
        const vec2 slice = tyn_view_ray_slice(gp, f3(d));
        const float rowV = 0.5f + slice.x / gp.phi_extent;
        const float rowDepth = tyn_rectified_depth(gp, slice.y);
        const double sinTheta = std::sin(rectifiedDouble(rect, c.position + d).z);
        double spread = 0.0;
        for (int k = 1; k <= 64; ++k) {
          const double t = rayLength * std::pow(1e-3, 1.0 - k / 64.0);
          const dvec3 p = c.position + t * d;
          const vec3 uvd = tyn_rectified_texcoord(gp, tyn_rectified_from_world(gp, f3(p)));
          // Same row and depth as the direction's; u grows linearly, u = t·sin θ / r_max.
          const double scale = (glm::length(p) + glm::length(c.position)) / t;  // float rounding of p − o, relative
          double dv = std::abs(double(uvd.y - rowV));
          if (rect.fullCircle) dv = std::min(dv, 1.0 - dv);
          spread = std::max({spread, dv * sinTheta, double(std::abs(uvd.z - rowDepth))});
          EXPECT_LT(dv * sinTheta, 1e-6 * scale) << c.name << " / " << l.name;
          EXPECT_LT(std::abs(uvd.z - rowDepth), 1e-6 * scale) << c.name << " / " << l.name;
          EXPECT_NEAR(uvd.x, t * sinTheta / rect.rMax, 1e-6 * scale) << c.name << " / " << l.name;
        }
        keepMax(g_worst.rowSpread, spread);
      }
      // Light rays: every point has the texel (u, v) of the ray.
      std::uniform_real_distribution<double> radius(0.05 * rect.rMax, rect.rMax), phi(-0.5 * rect.phiExtent, 0.5 * rect.phiExtent);
      for (int i = 0; i < 100; ++i) {
        const float r = float(radius(rng)), ph = float(phi(rng));
        const vec3 first = tyn_rectified_texcoord(gp, vec3(r, ph, 1.0f));
        double previousDepth = -kInf;
        for (int k = -20; k <= 20; ++k) {
          const float h = float(k) * 0.05f * float(rect.rMax);
          const vec3 uvd = tyn_rectified_texcoord(gp, tyn_rectified_from_world(gp, tyn_light_ray_point(gp, r, ph, h)));
          const double spread = std::max(std::abs(double(uvd.x - first.x)), std::abs(double(uvd.y - first.y)));
          keepMax(g_worst.lightRaySpread, spread);
          const double magnitude = glm::length(c.position) + double(r) + std::abs(double(h));
          EXPECT_LT(spread, 1e-6 + 4e-7 * magnitude / double(r) / std::min(rect.phiExtent, 1.0))
              << c.name << " / " << l.name;
          EXPECT_GT(uvd.z, previousDepth) << "depth grows along the light";
          previousDepth = uvd.z;
        }
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Per-slice spacing Δ(v)

// The inclination interval of slice φ by brute force: directions of the half-plane, tested
// against the frustum by projection.
dvec2 sliceThetaBruteForce(const Camera& c, const NonLinearRectification& rect, double phi, int samples) {
  const dvec3 e = std::cos(phi) * rect.axisX + std::sin(phi) * rect.axisY;
  double lo = kInf, hi = -kInf;
  for (int i = 0; i <= samples; ++i) {
    const double theta = kPi * i / samples;
    const dvec3 d = std::sin(theta) * e + std::cos(theta) * rect.axisZ;
    if (inFrustumCone(c, d)) {
      lo = std::min(lo, theta);
      hi = std::max(hi, theta);
    }
  }
  return dvec2(lo, hi);
}

TEST(Rectification, SliceInclinationRangesMatchBruteForce) {
  const int samples = 200000;
  for (const Camera& c : cameras()) {
    const ViewFrustum f = frustumOf(c);
    for (const Light& l : lights(c)) {
      const NonLinearRectification rect = computeNonLinearRectification(f, l.direction);
      const NonLinearRectificationParams gp = toGpu(rect);
      for (int i = 0; i < 16; ++i) {
        const double phi = (-0.5 + (i + 0.5) / 16.0) * rect.phiExtent;
        const dvec2 brute = sliceThetaBruteForce(c, rect, phi, samples);
        const vec2 got = tyn_slice_theta_range(gp, float(phi));
        ASSERT_LE(brute.x, brute.y) << c.name << " / " << l.name << " slice " << i << " misses the frustum";
        const double err = std::max(std::abs(got.x - brute.x), std::abs(got.y - brute.y));
        keepMax(g_worst.sliceTheta, err);
        EXPECT_LT(err, kPi / samples + 1e-5) << c.name << " / " << l.name << " φ " << phi;
        // And inside the frame's bounds.
        EXPECT_GE(got.x, rect.thetaMin - 1e-5);
        EXPECT_LE(got.y, rect.thetaMax + 1e-5);
      }
    }
  }
}

TEST(Rectification, ReferenceRayChoices) {
  // klehm2014 §3.2 in terms of k = sin θ: E(k_ref) = max(k_big/k_ref, k_ref/k_small) is minimal at
  // √(k_big·k_small); the bisectrix and peters2017's mean θ agree when π/2 is outside the range.
  for (dvec2 range : {dvec2(0.3, 1.2), dvec2(1.0, 2.5), dvec2(1.9, 2.9), dvec2(0.0, 0.8), dvec2(1.2, kPi)}) {
    const vec2 fr(range);
    const double nearest = std::clamp(0.5 * kPi, range.x, range.y);
    const double farthest = std::abs(range.x - 0.5 * kPi) > std::abs(range.y - 0.5 * kPi) ? range.x : range.y;
    const double kBig = std::sin(nearest), kSmall = std::sin(farthest);
    const double optimal = tyn_reference_sin_klehm(fr, true);
    if (kSmall > 1e-6) {
      // Brute-force minimiser of E.
      double best = 0.0, bestE = kInf;
      for (int i = 0; i <= 100000; ++i) {
        const double k = kSmall + (kBig - kSmall) * i / 100000.0;
        const double e = std::max(kBig / k, k / kSmall);
        if (e < bestE) {
          bestE = e;
          best = k;
        }
      }
      EXPECT_NEAR(optimal, best, 1e-4 * best) << range.x << " " << range.y;
    } else {
      // ω_max ∥ ω_l: the optimum does not exist; the bisectrix is used.
      EXPECT_FLOAT_EQ(float(optimal), tyn_reference_sin_klehm(fr, false));
    }
    const double bisectrix = tyn_reference_sin_klehm(fr, false);
    EXPECT_NEAR(bisectrix, std::sin(0.5 * (nearest + farthest)), 1e-6);
    const double mean = tyn_reference_sin_mean_theta(fr);
    EXPECT_NEAR(mean, std::max(std::sin(0.5 * (range.x + range.y)), 1e-6), 1e-6);
    if (nearest != 0.5 * kPi) {
      EXPECT_NEAR(mean, bisectrix, 1e-6) << range.x << " " << range.y;
    }
    EXPECT_FLOAT_EQ(tyn_slice_sample_spacing(0.5f, float(bisectrix)), float(0.5 / bisectrix));
  }
}

TEST(Rectification, ReferenceRayHeuristicsMeasured) {
  // Per slice, the worst ratio E between a ray's texel spacing and the reference one, and the
  // worst visibility error it causes (tyn_weighted_average_max_error with the optical depth the
  // weights assume, σ·s·k_ray/k_ref, against the ray's own, σ·s), for peters2017's mean θ (per
  // slice and over the frustum) and klehm2014's bisectrix and optimum. The optimum minimises E.
  const char* names[4] = {"mean theta (slice)", "mean theta (frustum)", "klehm bisectrix", "klehm optimum"};
  // [0]: epipole off screen, [1]: light axis in the frustum (slices reach rays along the light).
  double worstError[2][4] = {}, worstRatio[2][4] = {};
  for (const Camera& c : cameras()) {
    const ViewFrustum f = frustumOf(c);
    const double sigma = 2.0 / f.maxRayLength;  // optical depth 2 along the longest ray
    for (const Light& l : lights(c)) {
      const NonLinearRectification rect = computeNonLinearRectification(f, l.direction);
      const NonLinearRectificationParams gp = toGpu(rect);
      const vec2 frustumRange(float(rect.thetaMin), float(rect.thetaMax));
      const int group = rect.fullCircle ? 1 : 0;
      for (int i = 0; i < 32; ++i) {
        const double phi = (-0.5 + (i + 0.5) / 32.0) * rect.phiExtent;
        const vec2 range = tyn_slice_theta_range(gp, float(phi));
        const double kRef[4] = {tyn_reference_sin_mean_theta(range), tyn_reference_sin_mean_theta(frustumRange),
                                tyn_reference_sin_klehm(range, false), tyn_reference_sin_klehm(range, true)};
        const dvec3 e = std::cos(phi) * rect.axisX + std::sin(phi) * rect.axisY;
        double ratio[4] = {0, 0, 0, 0};
        for (int j = 0; j <= 200; ++j) {
          const double theta = double(range.x) + (double(range.y) - double(range.x)) * j / 200.0;
          const double k = std::sin(theta);
          const dvec3 d = k * e + std::cos(theta) * rect.axisZ;
          if (!inFrustumCone(c, d) || k < 1e-6) continue;
          const double s = c.infinite() ? c.sky : c.farPlane / glm::dot(d, c.forward);  // to the far plane
          for (int h = 0; h < 4; ++h) {
            ratio[h] = std::max(ratio[h], std::max(k / kRef[h], kRef[h] / k));
            const double err = double(tyn_weighted_average_max_error(float(sigma * s * k / kRef[h]), float(sigma * s)));
            worstError[group][h] = std::max(worstError[group][h], err);
          }
        }
        for (int h = 0; h < 4; ++h) worstRatio[group][h] = std::max(worstRatio[group][h], ratio[h]);
        if (std::sin(double(range.x)) > 1e-3 && std::sin(double(range.y)) > 1e-3) {
          for (int h = 0; h < 3; ++h) EXPECT_LE(ratio[3], ratio[h] * (1.0 + 1e-4)) << c.name << " / " << l.name << " " << names[h];
        }
      }
    }
  }
  for (int g = 0; g < 2; ++g) {
    std::printf("[ Rectify ] reference rays, %s, optical depth 2 on the longest ray: worst spacing ratio / "
                "visibility error:", g == 0 ? "epipole off screen" : "light axis in the frustum");
    for (int h = 0; h < 4; ++h) {
      std::printf(" %s %.3g / %.3f%s", names[h], worstRatio[g][h], worstError[g][h], h < 3 ? ";" : "\n");
    }
  }
  EXPECT_LE(worstRatio[0][3], worstRatio[0][2] * (1.0 + 1e-4));
}

// ---------------------------------------------------------------------------------------------
// Prefix sums

double exactIntegral(double a, double b, double sigma) {
  if (sigma == 0.0) return b - a;
  return std::exp(-sigma * a) * -std::expm1(-sigma * (b - a)) / sigma;
}

TEST(PrefixSums, WeightsSumToTheRowIntegral) {
  const uint texels = 1024u;
  for (double spacing : {0.01, 0.37, 4.0}) {
    for (double sigma : {0.0, 1e-5, 1e-3, 0.05, 0.8, 6.0}) {
      double sum = 0.0;
      for (uint i = 0; i < texels; ++i) {
        const vec2 span = tyn_nonlinear_texel_span(i, float(spacing));
        const float w = tyn_prefix_weight(span, float(sigma));
        const double exact = exactIntegral(double(span.x), double(span.y), double(float(sigma)));
        // float rounds σ·t, so the weight carries ~1e-7 of the optical depth as relative error.
        if (exact > 1e-30) {
          EXPECT_NEAR(w / exact, 1.0, 2e-6 + 1.2e-7 * sigma * double(span.x)) << spacing << " " << sigma << " " << i;
        }
        sum += double(w);
      }
      const double row = exactIntegral(0.0, texels * spacing, sigma);
      keepMax(g_worst.weightSum, std::abs(sum / row - 1.0));
      EXPECT_NEAR(sum / row, 1.0, 1e-5) << spacing << " " << sigma;
    }
  }
  // Projective rows: spans tile the row from the camera, and the weights add up alike.
  const Camera c = makeCamera("proj", dvec3(0.0, 1.5, 0.0), dvec3(0.0, 1.5, -1.0), 60.0, 16.0 / 9.0, 0.5, 100.0, false);
  const ViewFrustum f = frustumOf(c);
  const NonLinearRectification rect = computeNonLinearRectification(f, glm::normalize(dvec3(0.2, -1.0, 0.1)));
  const ProjectiveRectification proj = computeProjectiveRectification(f, rect);
  ASSERT_TRUE(proj.constructible);
  const ProjectiveRectificationParams pp = toGpu(proj);
  for (float v : {0.0f, 0.3f, 1.0f}) {
    const float eta = tyn_projective_eta(pp, v);
    for (double sigma : {0.0, 0.01, 0.3}) {
      double sum = 0.0;
      vec2 previous(0.0f);
      for (uint i = 0; i < texels; ++i) {
        const vec2 span = tyn_projective_texel_span(pp, i, float(texels), eta, 0.8f);
        EXPECT_EQ(span.x, i == 0 ? 0.0f : previous.y) << "spans tile the row";
        previous = span;
        sum += double(tyn_prefix_weight(span, float(sigma)));
      }
      const double end = proj.xFar * std::sqrt(1.0 + double(eta) * eta) / 0.8;
      EXPECT_NEAR(double(previous.y), end, 1e-5 * end);
      const double row = exactIntegral(0.0, end, sigma);
      keepMax(g_worst.weightSum, std::abs(sum / row - 1.0));
      EXPECT_NEAR(sum / row, 1.0, 1e-5) << v << " " << sigma;
    }
  }
}

TEST(PrefixSums, NormalisedStorageDenormalisesToTheExactIntegral) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::bernoulli_distribution lit(0.6);
  const uint texels = 512u;
  const double spacing = 0.25;  // Δ(v) of the reference ray
  for (double sigma : {0.0, 0.002, 0.05, 0.4}) {
    // Values in [−1, 1] (basis values) stay in [−1, 1] when normalised, so unorm8 keeps them.
    std::vector<dvec4> values(texels);
    std::vector<double> weights(texels);
    for (uint i = 0; i < texels; ++i) {
      values[i] = dvec4(unit(rng), unit(rng), unit(rng), unit(rng));
      weights[i] = double(tyn_prefix_weight(tyn_nonlinear_texel_span(i, float(spacing)), float(sigma)));
    }
    vec4 average(0.0f);
    float weightSum = 0.0f;
    dvec4 weighted(0.0);
    double exactSum = 0.0;
    for (uint i = 0; i < texels; ++i) {
      const float w = tyn_prefix_weight(tyn_nonlinear_texel_span(i, float(spacing)), float(sigma));
      weightSum += w;
      average = tyn_prefix_blend(average, vec4(values[i]), w, weightSum);
      weighted += weights[i] * values[i];
      exactSum += weights[i];
      const dvec4 exact = weighted / exactSum;
      const double err = glm::length(dvec4(average) - exact);
      keepMax(g_worst.prefixAverage, err);
      EXPECT_LT(err, 2e-5) << sigma << " texel " << i;
      for (int k = 0; k < 4; ++k) EXPECT_LE(std::abs(average[k]), 1.0f + 1e-6f);
    }
    // A visibility row (0/1 per texel) and the per-pixel evaluation for the reference ray ending
    // on texel edges: L = factor · average · ∫_0^s e^{−σt} dt must equal factor · Σ V_j w_j.
    std::vector<float> stored(texels);
    float avg = 0.0f, sum = 0.0f;
    std::vector<double> exactPrefix(texels);
    double acc = 0.0;
    for (uint i = 0; i < texels; ++i) {
      const float v = lit(rng) ? 1.0f : 0.0f;
      const float w = tyn_prefix_weight(tyn_nonlinear_texel_span(i, float(spacing)), float(sigma));
      sum += w;
      avg = tyn_prefix_blend(vec4(avg), vec4(v), w, sum).x;
      stored[i] = avg;
      acc += double(v) * exactIntegral(i * spacing, (i + 1) * spacing, sigma);
      exactPrefix[i] = acc;
    }
    const vec3 factor(0.7f, 1.1f, 2.0f);
    for (uint i = 0; i < texels; i += 17) {
      const float u = float(i + 1) / float(texels);  // the pixel's surface at texel i's far edge
      const float lookup = tyn_prefix_lookup_u(u, float(texels));
      // Linear filtering at `lookup` (texel centres at (j + 0.5)/N) lands on texel i exactly.
      const float x = lookup * float(texels) - 0.5f;
      EXPECT_NEAR(x, float(i), 1e-3f);
      const float s = float((i + 1) * spacing);
      const vec3 l = tyn_prefiltered_inscattering(factor, vec3(stored[i]), s, vec3(float(sigma)));
      for (int ch = 0; ch < 3; ++ch) {
        const double exact = double(factor[ch]) * exactPrefix[i];
        if (exact == 0.0) {
          EXPECT_EQ(l[ch], 0.0f);
          continue;
        }
        const double rel = std::abs(double(l[ch]) / exact - 1.0);
        keepMax(g_worst.inscattering, rel);
        EXPECT_LT(rel, 2e-5) << sigma << " texel " << i;
      }
    }
  }
}

// The worst error of a weighted average over step visibilities, by brute force in double.
double averageErrorBruteForce(double a, double b) {
  auto cdf = [](double x, double tau) {  // ∫_0^τ x e^{−xt} dt / (1 − e^{−x})
    if (x == 0.0) return tau;
    return std::expm1(-x * tau) / std::expm1(-x);
  };
  double worst = 0.0;
  for (int i = 0; i <= 20000; ++i) {
    const double tau = i / 20000.0;
    worst = std::max(worst, std::abs(cdf(a, tau) - cdf(b, tau)));  // V = 1 on [0, τ] (and its complement)
  }
  return worst;
}

TEST(PrefixSums, ExtinctionMismatchErrorBound) {
  const double depths[] = {0.0, 1e-3, 0.05, 0.3, 1.0, 2.5, 8.0, 40.0};
  for (double a : depths) {
    for (double b : depths) {
      const double brute = averageErrorBruteForce(a, b);
      const double got = double(tyn_weighted_average_max_error(float(a), float(b)));
      keepMax(g_worst.greyBound, std::abs(got - brute));
      EXPECT_NEAR(got, brute, 2e-5 + 1e-4 * brute) << a << " " << b;
      EXPECT_GE(got + 2e-5, brute) << "a bound";
    }
  }
  // Random visibility patterns never exceed it.
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int n = 400;
  for (int trial = 0; trial < 200; ++trial) {
    const double a = 5.0 * unit(rng), b = 5.0 * unit(rng);
    double na = 0, nb = 0, sa = 0, sb = 0;
    for (int i = 0; i < n; ++i) {
      const double v = unit(rng) < 0.5 ? 0.0 : 1.0;
      const double wa = exactIntegral(double(i) / n, double(i + 1) / n, a);
      const double wb = exactIntegral(double(i) / n, double(i + 1) / n, b);
      na += wa * v;
      sa += wa;
      nb += wb * v;
      sb += wb;
    }
    EXPECT_LE(std::abs(na / sa - nb / sb), double(tyn_weighted_average_max_error(float(a), float(b))) + 1e-6);
  }
  // Grows with the ray length at a fixed ratio of extinctions (choosePrefixSumExtinction relies
  // on it to evaluate the longest ray only).
  for (double ratio : {1.1, 2.0, 5.7}) {
    double previous = 0.0;
    for (int i = 1; i <= 200; ++i) {
      const double depth = 0.01 * std::pow(1.05, i);
      const double e = double(tyn_weighted_average_max_error(float(depth), float(depth * ratio)));
      EXPECT_GE(e, previous - 1e-6) << ratio << " " << depth;
      previous = e;
    }
    // The limit for infinitely long rays: ρ^{−1/(ρ−1)} − ρ^{−ρ/(ρ−1)}.
    const double limit = std::pow(ratio, -1.0 / (ratio - 1.0)) - std::pow(ratio, -ratio / (ratio - 1.0));
    EXPECT_NEAR(double(tyn_weighted_average_max_error(1e4f, float(1e4 * ratio))), limit, 1e-4) << ratio;
  }
}

TEST(PrefixSums, GreyOrPerChannelExtinction) {
  // Equal channels: exact with one set.
  PrefixSumExtinction e = choosePrefixSumExtinction(dvec3(0.02), 300.0);
  EXPECT_EQ(e.distinctChannels, 1);
  EXPECT_FALSE(e.perChannel);
  EXPECT_EQ(e.greyMaxError, 0.0);
  EXPECT_DOUBLE_EQ(e.sigma, 0.02);
  // No extinction at all.
  e = choosePrefixSumExtinction(dvec3(0.0), 300.0);
  EXPECT_FALSE(e.perChannel);
  EXPECT_EQ(e.sigma, 0.0);
  // A thin, slightly coloured haze over 200 units: grey is within the threshold.
  e = choosePrefixSumExtinction(dvec3(1.0e-4, 1.2e-4, 1.5e-4), 200.0);
  EXPECT_EQ(e.distinctChannels, 3);
  EXPECT_FALSE(e.perChannel) << e.greyMaxError;
  EXPECT_GE(e.sigma, 1.0e-4);
  EXPECT_LE(e.sigma, 1.5e-4);
  // Rayleigh-like σ (ratio 5.7) in a thick medium: grey would be far off; one set per channel.
  const dvec3 rayleigh(0.058, 0.135, 0.331);
  e = choosePrefixSumExtinction(rayleigh, 50.0);
  EXPECT_TRUE(e.perChannel) << e.greyMaxError;
  // The chosen grey σ is the minimax: nudging it either way does not lower the worst error.
  auto worst = [&](double grey) {
    double w = 0.0;
    for (int ch = 0; ch < 3; ++ch) {
      w = std::max(w, double(tyn_weighted_average_max_error(float(grey * 50.0), float(rayleigh[ch] * 50.0))));
    }
    return w;
  };
  EXPECT_NEAR(worst(e.sigma), e.greyMaxError, 1e-6);
  EXPECT_GE(worst(e.sigma * 1.05), e.greyMaxError - 1e-6);
  EXPECT_GE(worst(e.sigma / 1.05), e.greyMaxError - 1e-6);
  // Two equal channels count once.
  EXPECT_EQ(choosePrefixSumExtinction(dvec3(0.1, 0.2, 0.1), 10.0).distinctChannels, 2);
  const PrefixSumExtinction haze = choosePrefixSumExtinction(dvec3(1.0e-4, 1.2e-4, 1.5e-4), 200.0);
  const PrefixSumExtinction thinRayleigh = choosePrefixSumExtinction(rayleigh, 0.5);
  std::printf("[ Rectify ] grey extinction, worst visibility error: haze (1, 1.2, 1.5)e-4 over 200: %.4f; Rayleigh-like "
              "(0.058, 0.135, 0.331) over 50: %.3f, over 0.5: %.4f (threshold %.2f)\n",
              haze.greyMaxError, e.greyMaxError, thinRayleigh.greyMaxError, kGreyExtinctionMaxError);
  EXPECT_FALSE(thinRayleigh.perChannel);
}

// ---------------------------------------------------------------------------------------------
// Fourier basis

// V ≈ ½ − Σ_{k ≤ K} (2/c_k)·sin(c_k(z_r − z_i)): the square wave written directly (not separated).
double squareWaveSeries(double zr, double zi, int harmonics) {
  double v = 0.5;
  for (int k = 1; k <= harmonics; ++k) {
    const double ck = kPi * (2 * k - 1);
    v -= 2.0 / ck * std::sin(ck * (zr - zi));
  }
  return v;
}

// The reconstruction from the header's layers, any number of layers (2 harmonics each).
double reconstructFloat(float zr, float zi, uint layers) {
  float v = 0.5f;
  for (uint l = 0; l < layers; ++l) v += dot(tyn_fourier_coefficients(zr, l), tyn_fourier_basis(zi, l));
  return double(v);
}

TEST(Fourier, BasisIsTheSquareWaveOfTheCorrectStep) {
  EXPECT_EQ(TYN_FOURIER_COEFFICIENTS, 2u * TYN_FOURIER_HARMONICS);
  EXPECT_EQ(TYN_FOURIER_COEFFICIENTS, 4u * TYN_FOURIER_LAYERS);
  EXPECT_NEAR(tyn_fourier_frequency(1u), kPi, 1e-6);
  EXPECT_NEAR(tyn_fourier_frequency(16u), 31.0 * kPi, 1e-5);
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < 20000; ++i) {
    const double zr = unit(rng), zi = unit(rng);
    const double err = std::abs(reconstructFloat(float(zr), float(zi), TYN_FOURIER_LAYERS) -
                                squareWaveSeries(double(float(zr)), double(float(zi)), 16));
    keepMax(g_worst.fourierSeries, err);
    EXPECT_LT(err, 2e-5) << zr << " " << zi;
  }
  // The sign: a sample in front of its occluder (z_r < z_i) is lit, behind it is shadowed.
  vec4 filtered[TYN_FOURIER_LAYERS];
  for (uint l = 0; l < TYN_FOURIER_LAYERS; ++l) filtered[l] = tyn_fourier_basis(0.6f, l);
  EXPECT_GT(tyn_fourier_visibility(0.2f, filtered), 0.95f);
  EXPECT_LT(tyn_fourier_visibility(0.9f, filtered), 0.05f);
  EXPECT_NEAR(tyn_fourier_visibility_unclamped(0.6f, filtered), 0.5f, 1e-5f);  // midpoint at the step
}

TEST(Fourier, ConvergesAwayFromTheStepAndOvershootsByGibbs) {
  // Error of the partial sum at distance d from the jump (and from the periodic jump at |x| = 1),
  // against the Abel-summation bound |error| ≤ (2/π) / ((2K + 1)·sin(πd)).
  const double distances[] = {0.05, 0.1, 0.25};
  for (int i = 0; i < 3; ++i) {
    const double d = distances[i];
    double worst16 = 0.0, worst32 = 0.0;
    for (int j = 0; j <= 20000; ++j) {
      const double x = d + (1.0 - 2.0 * d) * j / 20000.0;
      for (double sx : {x, -x}) {
        const double step = sx <= 0.0 ? 1.0 : 0.0;
        // z_r − z_i = sx with both in [0, 1].
        const double zi = sx > 0.0 ? 0.0 : 1.0, zr = zi + sx;
        worst16 = std::max(worst16, std::abs(reconstructFloat(float(zr), float(zi), 8u) - step));
        worst32 = std::max(worst32, std::abs(squareWaveSeries(zr, zi, 32) - step));
      }
    }
    const double bound16 = 2.0 / kPi / (33.0 * std::sin(kPi * d));
    g_worst.fourierAt[i] = worst16;
    EXPECT_LE(worst16, bound16 + 2e-5) << "d " << d;
    EXPECT_GT(worst16, 0.3 * bound16) << "the bound is of the right size";
    EXPECT_LT(worst32, 0.6 * worst16) << "M = 64 converges further at d " << d;
  }
  // Gibbs: the unclamped reconstruction overshoots the lit side by (1/π)·Si(π) − ½ ≈ 0.0895 of
  // the jump (and undershoots the shadowed side alike); clamping removes both.
  double overshoot = -kInf, undershoot = kInf;
  vec4 filtered[TYN_FOURIER_LAYERS];
  for (int j = 1; j <= 4000; ++j) {
    const double x = 0.25 * j / 4000.0;
    const float zi = 0.5f;
    for (uint l = 0; l < TYN_FOURIER_LAYERS; ++l) filtered[l] = tyn_fourier_basis(zi, l);
    overshoot = std::max(overshoot, double(tyn_fourier_visibility_unclamped(zi - float(x), filtered)) - 1.0);
    undershoot = std::min(undershoot, double(tyn_fourier_visibility_unclamped(zi + float(x), filtered)));
    EXPECT_LE(tyn_fourier_visibility(zi - float(x), filtered), 1.0f);
    EXPECT_GE(tyn_fourier_visibility(zi + float(x), filtered), 0.0f);
  }
  const double gibbs = 0.0894898722;  // (1/π)·Si(π) − ½
  g_worst.gibbs = overshoot;
  EXPECT_NEAR(overshoot, gibbs, 2e-3);
  EXPECT_NEAR(-undershoot, gibbs, 2e-3);
}

TEST(Fourier, PacksIntoUnorm8) {
  double worstQuantised = 0.0, worstBound = 0.0;
  vec4 stored[TYN_FOURIER_LAYERS];
  vec4 exact[TYN_FOURIER_LAYERS];
  for (int i = 0; i <= 2000; ++i) {
    const float zi = float(i) / 2000.0f;
    for (uint l = 0; l < TYN_FOURIER_LAYERS; ++l) {
      exact[l] = tyn_fourier_basis(zi, l);
      const vec4 packed = tyn_fourier_pack(exact[l]);
      for (int k = 0; k < 4; ++k) {
        EXPECT_GE(packed[k], 0.0f);
        EXPECT_LE(packed[k], 1.0f);
      }
      EXPECT_LT(glm::length(tyn_fourier_unpack(packed) - exact[l]), 1e-6f);
      stored[l] = tyn_fourier_unpack(glm::round(packed * 255.0f) / 255.0f);  // unorm8 round trip
    }
    for (int j = 0; j <= 50; ++j) {
      const float zr = float(j) / 50.0f;
      const double err = std::abs(double(tyn_fourier_visibility_unclamped(zr, stored) -
                                         tyn_fourier_visibility_unclamped(zr, exact)));
      // Rounding to unorm8 moves a stored value by ≤ 0.5/255, an unpacked one by ≤ 1/255.
      double bound = 0.0;
      for (uint l = 0; l < TYN_FOURIER_LAYERS; ++l) {
        const vec4 a = tyn_fourier_coefficients(zr, l);
        bound += double(std::abs(a.x) + std::abs(a.y) + std::abs(a.z) + std::abs(a.w)) / 255.0;
      }
      worstQuantised = std::max(worstQuantised, err);
      worstBound = std::max(worstBound, bound);
      EXPECT_LE(err, bound + 1e-6);
    }
  }
  g_worst.quantised = worstQuantised;
  EXPECT_LT(worstBound, 0.0085);  // the figure quoted by kGreyExtinctionMaxError
}

TEST(Fourier, NormalisedWeightedFilteringIsLinear) {
  // Prefiltering a row then reconstructing equals reconstructing every texel then averaging with
  // the same weights (before clamping): the basis is linear in the occluder's representation.
  std::mt19937 rng(17);
  std::normal_distribution<double> stepDist(0.0, 0.03);
  const uint texels = 512u;
  std::vector<double> depth(texels);
  double z = 0.5;
  for (uint i = 0; i < texels; ++i) {
    z = std::clamp(z + stepDist(rng), 0.0, 1.0);
    depth[i] = z;
  }
  const float spacing = 0.5f, sigma = 0.01f;
  vec4 average[TYN_FOURIER_LAYERS];
  for (vec4& a : average) a = vec4(0.0f);
  float weightSum = 0.0f;
  std::vector<double> w(texels);
  double worst = 0.0;
  for (uint i = 0; i < texels; ++i) {
    const float wi = tyn_prefix_weight(tyn_nonlinear_texel_span(i, spacing), sigma);
    w[i] = double(wi);
    weightSum += wi;
    for (uint l = 0; l < TYN_FOURIER_LAYERS; ++l) {
      average[l] = tyn_prefix_blend(average[l], tyn_fourier_basis(float(depth[i]), l), wi, weightSum);
    }
    if (i % 31 != 0) continue;
    for (double zr : {0.1, 0.45, 0.62, 0.9}) {
      double num = 0.0, den = 0.0;
      for (uint j = 0; j <= i; ++j) {
        num += w[j] * squareWaveSeries(zr, depth[j], 16);
        den += w[j];
      }
      const double err = std::abs(double(tyn_fourier_visibility_unclamped(float(zr), average)) - num / den);
      worst = std::max(worst, err);
      EXPECT_LT(err, 2e-4) << "texel " << i << " z_r " << zr;
    }
  }
  g_worst.filtering = worst;
}

// ---------------------------------------------------------------------------------------------
// Projective rectification

dvec3 projectiveTexcoordDouble(const ProjectiveRectification& p, dvec3 world) {
  const dvec4 clip = p.worldToClip * dvec4(world, 1.0);
  return dvec3(clip.x / clip.w * 0.5 + 0.5, clip.y / clip.w * 0.5 + 0.5, clip.z / clip.w);
}

// Camera at the origin looking down −Z (vertical half-angle 30°); a light whose source is ψ
// above the view axis (ψ = 90°: straight above, epipole at infinity; ψ < 30°: on screen).
dvec3 lightFromElevation(double psiDegrees) {
  const double psi = glm::radians(psiDegrees);
  return -dvec3(0.0, std::sin(psi), -std::cos(psi));
}

TEST(ProjectiveRectification, ViewRaysAreRowsOfConstantDepthAndLightRaysTexels) {
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> ndc(-1.0, 1.0), unit(0.0, 1.0);
  for (const Camera& c : cameras()) {
    const ViewFrustum f = frustumOf(c);
    for (const Light& l : lights(c)) {
      const std::string what = c.name + " / " + l.name;
      const NonLinearRectification rect = computeNonLinearRectification(f, l.direction);
      const ProjectiveRectification proj = computeProjectiveRectification(f, rect);
      EXPECT_EQ(proj.constructible, !rect.fullCircle) << what;
      if (!proj.constructible) {
        EXPECT_TRUE(std::isinf(proj.texelStretch));
        EXPECT_FALSE(useProjectiveRectification(proj));
        continue;
      }
      const ProjectiveRectificationParams pp = toGpu(proj);
      const double guard = 0.5 * double(TYN_RECT_THETA_GUARD) / (1.0 + double(TYN_RECT_THETA_GUARD));
      dvec3 lo(kInf), hi(-kInf);
      for (int i = 0; i < 300; ++i) {
        const dvec2 n(ndc(rng), ndc(rng));
        const dvec3 d = rayDirection(c, n);
        const double tNear = c.nearPlane / glm::dot(d, c.forward);
        const double tFar = glm::length(farPoint(c, n) - c.position);
        const dvec3 first = projectiveTexcoordDouble(proj, c.position + tNear * d);
        double spreadF = 0.0, previousU = -kInf;
        for (int k = 0; k <= 40; ++k) {
          const double t = tNear * std::pow(tFar / tNear, k / 40.0);
          const dvec3 p = c.position + t * d;
          const dvec3 uvd = projectiveTexcoordDouble(proj, p);
          EXPECT_NEAR(uvd.y, first.y, 1e-9) << what;  // one row
          EXPECT_NEAR(uvd.z, first.z, 1e-9) << what;  // constant depth
          EXPECT_GT(uvd.x, previousU) << what;        // left to right
          previousU = uvd.x;
          lo = glm::min(lo, uvd);
          hi = glm::max(hi, uvd);
          const vec3 got = tyn_projective_texcoord(pp, f3(p));
          const double scale = (glm::length(p) + glm::length(c.position)) / t;
          spreadF = std::max({spreadF, std::abs(double(got.y) - first.y), std::abs(double(got.z) - first.z)});
          EXPECT_LT(std::abs(double(got.y) - first.y), 1e-5 * scale) << what;
          EXPECT_LT(std::abs(double(got.z) - first.z), 1e-5 * scale) << what;
          // The column's light-frame x through the Möbius inverse.
          // u rounded to float moves x by du·x²(x_f − x_n)/(x_n·x_f) ≤ du·(x_f/x_n)·x.
          const double x = glm::dot(p - rect.origin, rect.axisX);
          EXPECT_NEAR(double(tyn_projective_x(pp, float(uvd.x))), x, (1e-5 + 2e-7 * proj.xFar / proj.xNear) * x) << what;
        }
        keepMax(g_worst.projRowSpread, spreadF);
        // The camera-relative form keeps float precision all along the ray, and agrees with the
        // world form where that one is precise.
        const vec3 firstOffset = tyn_projective_texcoord_from_offset(pp, f3(tNear * d));
        for (int k = 0; k <= 40; ++k) {
          const double t = tNear * std::pow(tFar / tNear, k / 40.0);
          const vec3 got = tyn_projective_texcoord_from_offset(pp, f3(t * d));
          const dvec3 exact = projectiveTexcoordDouble(proj, c.position + t * d);
          const double spread = std::max(std::abs(double(got.y - firstOffset.y)), std::abs(double(got.z - firstOffset.z)));
          keepMax(g_worst.projOffsetSpread, spread);
          EXPECT_LT(spread, 1e-6) << what;
          EXPECT_NEAR(double(got.y), exact.y, 1e-6) << what;
          EXPECT_NEAR(double(got.z), exact.z, 1e-6) << what;
          EXPECT_NEAR(double(got.x), exact.x, 1e-6 + 2e-7 * proj.xFar / proj.xNear) << what;
        }
        // The row's slice is the non-linear one: φ = atan η.
        const double phiExact = rectifiedDouble(rect, c.position + d).y;
        EXPECT_NEAR(double(tyn_projective_row_phi(pp, float(first.y))), phiExact, 1e-5) << what;
      }
      // The light frustum wraps the camera frustum: every point between the near and far planes
      // maps into [0, 1]² with its depth inside the guard band; the extremes are reached.
      EXPECT_GT(lo.x, -1e-9);
      EXPECT_LT(hi.x, 1.0 + 1e-9);
      EXPECT_GT(lo.y, -1e-9);
      EXPECT_LT(hi.y, 1.0 + 1e-9);
      EXPECT_GT(lo.z, guard - 1e-9);
      EXPECT_LT(hi.z, 1.0 - guard + 1e-9);
      for (int i = 0; i < 4; ++i) {
        for (const dvec3& corner : {f.nearCorners[i], f.farCorners[i]}) {
          const dvec3 uvd = projectiveTexcoordDouble(proj, corner);
          lo = glm::min(lo, uvd);
          hi = glm::max(hi, uvd);
        }
      }
      EXPECT_NEAR(lo.x, 0.0, 1e-9) << what;
      EXPECT_NEAR(hi.x, 1.0, 1e-9) << what;
      EXPECT_NEAR(lo.y, 0.0, 1e-9) << what;
      EXPECT_NEAR(hi.y, 1.0, 1e-9) << what;
      EXPECT_NEAR(lo.z, guard, 1e-9) << what;
      EXPECT_NEAR(hi.z, 1.0 - guard, 1e-9) << what;
      // Light rays: one texel, depth growing with the light.
      for (int i = 0; i < 100; ++i) {
        const dvec2 n(ndc(rng), ndc(rng));
        const dvec3 p = c.position + (0.2 + 0.8 * unit(rng)) * (farPoint(c, n) - c.position);
        const dvec3 a = projectiveTexcoordDouble(proj, p);
        const vec3 af = tyn_projective_texcoord(pp, f3(p));
        double previousDepth = -kInf;
        for (int k = -10; k <= 10; ++k) {
          const dvec3 q = p + l.direction * (5.0 * k);
          const dvec3 b = projectiveTexcoordDouble(proj, q);
          EXPECT_NEAR(b.x, a.x, 1e-9) << what;
          EXPECT_NEAR(b.y, a.y, 1e-9) << what;
          EXPECT_GT(b.z, previousDepth) << what;
          previousDepth = b.z;
          const vec3 bf = tyn_projective_texcoord(pp, f3(q));
          const double spread = std::max(std::abs(double(bf.x - af.x)), std::abs(double(bf.y - af.y)));
          keepMax(g_worst.projLightSpread, spread);
          EXPECT_LT(spread, 2e-5 * (1.0 + glm::length(q) / glm::length(p - c.position))) << what;
        }
      }
    }
  }
}

TEST(ProjectiveRectification, ColumnDistancesAreMoebiusNotGeometric) {
  // klehm2014 Eq. 12 assumes the distance along a ray grows by a constant factor per texel. The
  // column is u = x_f(x − x_n)/((x_f − x_n)x): x(u) = C/(u_∞ − u) is linear-fractional, and the
  // ratio of successive increments, (u_∞ − u_i)/(u_∞ − u_{i+2}) = x_{i+2}/x_i, grows from ~1 at
  // the camera's end of the row (dense columns) to large at the far end.
  const Camera c = makeCamera("proj", dvec3(0.0), dvec3(0.0, 0.0, -1.0), 60.0, 16.0 / 9.0, 0.5, 200.0, false);
  const ViewFrustum f = frustumOf(c);
  const NonLinearRectification rect = computeNonLinearRectification(f, lightFromElevation(80.0));
  const ProjectiveRectification proj = computeProjectiveRectification(f, rect);
  ASSERT_TRUE(proj.constructible);
  const ProjectiveRectificationParams pp = toGpu(proj);
  const double n = 1024.0;
  auto x = [&](double column) { return double(tyn_projective_x(pp, float(column / n))); };
  const double ratioStart = (x(2.5) - x(1.5)) / (x(1.5) - x(0.5));
  const double ratioEnd = (x(n - 0.5) - x(n - 1.5)) / (x(n - 1.5) - x(n - 2.5));
  EXPECT_NEAR(x(0.0), proj.xNear, 1e-5 * proj.xNear);
  EXPECT_NEAR(x(n), proj.xFar, 1e-4 * proj.xFar);
  // Exact ratio of increments from the Möbius form: (u_i − u_∞)/(u_{i+2} − u_∞), u_∞ = x_f/(x_f − x_n).
  const double uInf = proj.xFar / (proj.xFar - proj.xNear);
  EXPECT_NEAR(ratioStart, (0.5 / n - uInf) / (2.5 / n - uInf), 1e-3);
  EXPECT_GT(ratioEnd / ratioStart, 1.1) << "not a constant factor";
  EXPECT_NEAR(ratioEnd, (1.0 - 2.5 / n - uInf) / (1.0 - 0.5 / n - uInf), 1e-2 * ratioEnd);
}

TEST(ProjectiveRectification, CriterionSeparatesOnScreenFromFarOffScreenEpipoles) {
  const Camera c = makeCamera("criterion", dvec3(0.0), dvec3(0.0, 0.0, -1.0), 60.0, 16.0 / 9.0, 0.1, 300.0, false);
  const ViewFrustum f = frustumOf(c);
  auto stretchAt = [&](double psi) {
    const NonLinearRectification rect = computeNonLinearRectification(f, lightFromElevation(psi));
    return computeProjectiveRectification(f, rect);
  };
  // On screen (light ahead, or behind the camera shining along the view): no projective map.
  for (double psi : {0.0, 10.0, 25.0, 29.9, 150.1, 170.0, 180.0}) {
    const ProjectiveRectification p = stretchAt(psi);
    EXPECT_FALSE(p.constructible) << psi;
    EXPECT_FALSE(useProjectiveRectification(p)) << psi;
  }
  // Far off screen (the light above, perpendicular to the view axis): usable.
  const ProjectiveRectification above = stretchAt(90.0);
  EXPECT_TRUE(useProjectiveRectification(above)) << above.texelStretch;
  EXPECT_GE(above.texelStretch, 1.0);
  // Approaching the border from above, the stretch grows monotonically and without bound, and
  // the switch happens before the border.
  double previous = 0.0, switchPsi = 0.0;
  for (double psi = 90.0; psi >= 30.05; psi -= 0.05) {
    const ProjectiveRectification p = stretchAt(psi);
    ASSERT_TRUE(p.constructible) << psi;
    EXPECT_GE(p.texelStretch, previous - 1e-9) << psi;
    previous = p.texelStretch;
    if (switchPsi == 0.0 && !useProjectiveRectification(p)) switchPsi = psi;
  }
  EXPECT_GT(previous, 50.0) << "diverges at the border";
  EXPECT_GT(switchPsi, 30.5);
  // Symmetric for a light behind the camera.
  const ProjectiveRectification behind = stretchAt(180.0 - 45.0);
  EXPECT_NEAR(behind.texelStretch, stretchAt(45.0).texelStretch, 1e-9);
  // The epipole's NDC distance from the screen centre when the switch happens (cot ψ / tan 30°).
  std::printf("[ Rectify ] projective texel stretch %.2f with the light straight above; switch to non-linear "
              "at %.2f deg elevation, epipole at |y_ndc| = %.2f\n",
              above.texelStretch, switchPsi, 1.0 / std::tan(glm::radians(switchPsi)) / std::tan(glm::radians(30.0)));
}

TEST(ProjectiveRectification, TexelStretchBoundsTheTexelAngleRatio) {
  // The measure's meaning, checked by finite differences of the double matrix: at every frustum
  // direction, a projective texel spans at most `texelStretch` times the slice angle (φ) and the
  // inclination (θ) of a non-linear texel of the same map size (both maps carry the same 10%
  // depth guard), and some direction comes within 2% of it (the measure is tight). Near the
  // screen border the inclination part dominates.
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> ndc(-1.0, 1.0);
  double worstRatio = kInf;
  int depthDominated = 0;
  for (const Camera& c : cameras()) {
    const ViewFrustum f = frustumOf(c);
    for (double tilt : {0.0, 0.3, 0.6, 0.9, 0.97}) {
      // From perpendicular to the view (tilt 0) towards a light just off a corner of the screen.
      const dvec3 corner = glm::normalize(f.farCorners[2] - f.position);
      const dvec3 side = glm::normalize(glm::cross(c.forward, c.up) + 0.5 * c.up);
      const dvec3 source = glm::normalize((1.0 - tilt) * side + tilt * corner + 0.02 * (corner - c.forward));
      if (inFrustumCone(c, source)) continue;
      const NonLinearRectification rect = computeNonLinearRectification(f, -source);
      const ProjectiveRectification proj = computeProjectiveRectification(f, rect);
      ASSERT_TRUE(proj.constructible) << c.name << " tilt " << tilt;
      double rowRatio = 0.0, depthRatio = 0.0;
      for (int i = 0; i < 4000; ++i) {
        // Random directions, and the screen border where the extremes usually lie.
        const double s = ndc(rng);
        const dvec2 n = i < 2000 ? dvec2(ndc(rng), s)
                                 : (i % 4 == 0 ? dvec2(s, -1.0) : i % 4 == 1 ? dvec2(s, 1.0) : i % 4 == 2 ? dvec2(-1.0, s) : dvec2(1.0, s));
        const dvec3 d = rayDirection(c, n);
        const dvec3 angles = rectifiedDouble(rect, c.position + d);  // (r, φ, θ)
        auto at = [&](double phi, double theta) {
          const dvec3 e = std::cos(phi) * rect.axisX + std::sin(phi) * rect.axisY;
          return projectiveTexcoordDouble(proj, c.position + std::sin(theta) * e + std::cos(theta) * rect.axisZ);
        };
        const double h = 1e-6;
        const double dvdphi = (at(angles.y + h, angles.z).y - at(angles.y - h, angles.z).y) / (2.0 * h);
        const double ddepthdtheta = (at(angles.y, angles.z + h).z - at(angles.y, angles.z - h).z) / (2.0 * h);
        rowRatio = std::max(rowRatio, 1.0 / (std::abs(dvdphi) * rect.phiExtent));
        depthRatio = std::max(depthRatio, 1.0 / (std::abs(ddepthdtheta) * (rect.thetaMaxGuarded - rect.thetaMinGuarded)));
      }
      EXPECT_LE(rowRatio, proj.texelStretch * (1.0 + 1e-5)) << c.name << " tilt " << tilt;
      EXPECT_LE(depthRatio, proj.texelStretch * (1.0 + 1e-5)) << c.name << " tilt " << tilt;
      EXPECT_GE(std::max(rowRatio, depthRatio), 0.98 * proj.texelStretch) << c.name << " tilt " << tilt;
      worstRatio = std::min(worstRatio, std::max(rowRatio, depthRatio) / proj.texelStretch);
      if (depthRatio > rowRatio) ++depthDominated;
    }
  }
  EXPECT_GT(depthDominated, 0);
  std::printf("[ Rectify ] sampled projective texel-angle ratio reaches at least %.4f of the stretch measure; "
              "inclination dominates in %d cases\n", worstRatio, depthDominated);
}

}  // namespace
