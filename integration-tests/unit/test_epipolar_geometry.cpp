// The epipolar geometry (shaders/epipolar/epipolar_geometry.h), compiled as C++ from the shaders'
// source, against independent double-precision constructions of the same quantities: projections
// with double matrices, line/rectangle clipping and perimeter coordinates written again here,
// brute-force sampling of segments and rays.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "vulkan_projection.h"

#include "epipolar/epipolar_geometry.h"

namespace {

using namespace tyndall::gpu;
using glm::dmat4;
using glm::dvec2;
using glm::dvec3;
using glm::dvec4;

// ---------------------------------------------------------------------------------------------
// Double-precision scaffolding

using tyndall::test::vulkanPerspective;

struct View {
  dvec3 position;
  dmat4 viewProj;
  dmat4 inverse;
  double nearNdc;
  dvec2 extent;
};

View makeView(dvec3 position, dvec3 target, dvec2 extent, bool reversed = false,
              double farPlane = 200.0) {
  View v;
  v.position = position;
  v.viewProj = vulkanPerspective(glm::radians(60.0), extent.x / extent.y, 0.1, farPlane, reversed) *
               glm::lookAt(position, target, dvec3(0.0, 1.0, 0.0));
  v.inverse = glm::inverse(v.viewProj);
  v.nearNdc = reversed ? 1.0 : 0.0;
  v.extent = extent;
  return v;
}

// Unit world direction of the view ray through an NDC point.
dvec3 rayThrough(const View& v, dvec2 ndc) {
  const dvec4 p = v.inverse * dvec4(ndc, v.nearNdc, 1.0);
  return glm::normalize(dvec3(p) / p.w - v.position);
}

vec2 f2(dvec2 v) { return vec2(v); }
vec3 f3(dvec3 v) { return vec3(v); }
dvec2 d2(vec2 v) { return dvec2(v); }

struct Rect {
  dvec2 lo, hi;
};
// The sample rectangle [−1 + 1/W, 1 − 1/W] × [−1 + 1/H, 1 − 1/H], rounded to float as the shaders
// hold it: the float pixel centres on the border must lie exactly on the reference's border, or a
// line grazing an edge (slope 1e-4) would cross it somewhere else.
Rect sampleRect(dvec2 extent) {
  const vec2 e = f2(extent);
  return {dvec2(vec2(0.5f) / e * 2.0f - 1.0f), dvec2((e - 0.5f) / e * 2.0f - 1.0f)};
}

// Interval of origin + t·dir inside the rectangle; empty when .x > .y.
dvec2 clipLine(dvec2 origin, dvec2 dir, const Rect& r) {
  double t0 = -std::numeric_limits<double>::infinity();
  double t1 = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 2; ++a) {
    if (dir[a] == 0.0) {
      if (origin[a] < r.lo[a] || origin[a] > r.hi[a]) return dvec2(1.0, -1.0);
      continue;
    }
    const double ta = (r.lo[a] - origin[a]) / dir[a];
    const double tb = (r.hi[a] - origin[a]) / dir[a];
    t0 = std::max(t0, std::min(ta, tb));
    t1 = std::min(t1, std::max(ta, tb));
  }
  return dvec2(t0, t1);
}

// Perimeter distance in pixels of a border point, clockwise from the top-left corner.
double perimeterPixels(dvec2 b, dvec2 extent) {
  const dvec2 q = (b + 1.0) * 0.5 * extent - 0.5;  // pixels from the top-left pixel centre
  const dvec2 size = extent - 1.0;
  const double dTop = std::abs(q.y), dRight = std::abs(size.x - q.x);
  const double dBottom = std::abs(size.y - q.y), dLeft = std::abs(q.x);
  const double m = std::min(std::min(dTop, dRight), std::min(dBottom, dLeft));
  // The top-left corner is 0 from both of its edges.
  if (q.x < 1e-3 && std::abs(q.y) < 1e-3) return 0.0;
  if (m == dTop) return q.x;
  if (m == dRight) return size.x + q.y;
  if (m == dBottom) return size.x + size.y + (size.x - q.x);
  return 2.0 * size.x + size.y + (size.y - q.y);
}

double perimeterTotal(dvec2 extent) { return 2.0 * (extent.x - 1.0 + extent.y - 1.0); }

// Circular distance between two slice coordinates.
double sliceDistance(double a, double b, double n) {
  const double d = std::fmod(std::abs(a - b), n);
  return std::min(d, n - d);
}

// An epipole in double: homogeneous (x, y, w) of the light, as projected.
struct Epipole {
  dvec3 h;  // clip x, y, w
  bool finite() const { return std::abs(h.z) > 1e-12; }
  dvec2 ndc() const { return dvec2(h) / h.z; }
};

// The visible part of the segment from the epipole to `exit` (the half-line towards `exit` from
// the point at infinity when the epipole is there), in the rectangle: [entry, end] as line
// parameters of exit + s·(exit − epipole direction); returns the length in pixels (0 if none).
double visibleSegmentPixels(const Epipole& e, dvec2 exit, dvec2 extent, dvec2* entry) {
  const Rect r = sampleRect(extent);
  dvec2 dir;
  double sEpipole;
  if (e.finite()) {
    dir = exit - e.ndc();
    sEpipole = -1.0;
  } else {
    dir = -dvec2(e.h) * (e.h.z < 0.0 ? -1.0 : 1.0);
    sEpipole = -std::numeric_limits<double>::infinity();
  }
  const dvec2 range = clipLine(exit, dir, r);
  const double s0 = std::max(range.x, sEpipole);
  const double s1 = std::min(range.y, 0.0);
  if (entry != nullptr) *entry = exit + dir * s0;
  if (!(s1 > s0)) return 0.0;
  return (s1 - s0) * glm::length(dir * extent * 0.5);
}

// The screen cases of the issue, for a camera at the origin looking down −Z: the epipole NDC
// wanted and whether the light is behind the camera.
struct EpipoleCase {
  std::string name;
  dvec2 ndc;
  bool behind;
};

std::vector<EpipoleCase> epipoleCases() {
  return {{"centre", {0.0, 0.0}, false},
          {"near corner", {0.93, -0.88}, false},
          {"just off screen", {1.03, 0.31}, false},
          {"just off a corner", {-1.02, 1.05}, false},
          {"far off screen", {6.5, -4.25}, false},
          {"very far off screen", {-2500.0, 1300.0}, false},
          {"behind, on screen", {0.3, 0.2}, true},
          {"behind, off screen", {-2.4, 0.7}, true},
          {"behind, far off screen", {40.0, 35.0}, true},
          {"on view axis, front", {0.0, 0.0}, false},
          {"on view axis, behind", {0.0, 0.0}, true}};
}

// A directional light putting the epipole at c.ndc (mirrored when behind): the light comes from
// the direction of the view ray through that point, or travels along it when behind.
dvec3 lightDirFor(const View& v, const EpipoleCase& c) {
  const dvec3 towardsLight = rayThrough(v, c.ndc);
  return c.behind ? towardsLight : -towardsLight;
}

vec4 epipoleOf(const View& v, dvec3 lightDir) {
  return tyn_epipole(tyn_epipole_clip_directional(mat4(v.viewProj), f3(lightDir)));
}

// The light directions of every case plus the ones with the epipole at (or near) infinity: the
// light in the camera's plane, exactly and with a tiny forward or backward tilt.
struct LightCase {
  std::string name;
  dvec3 lightDir;
};

std::vector<LightCase> lightCases(const View& v, const dvec3& right, const dvec3& forward) {
  std::vector<LightCase> cases;
  for (const EpipoleCase& c : epipoleCases()) cases.push_back({c.name, lightDirFor(v, c)});
  cases.push_back({"at infinity (light in the camera plane)", -glm::normalize(right * 0.8 + dvec3(0, 0.6, 0))});
  cases.push_back({"near infinity, front", -glm::normalize(right + forward * 1e-4)});
  cases.push_back({"near infinity, behind", -glm::normalize(right - forward * 1e-4 + dvec3(0, 0.3, 0))});
  return cases;
}

const dvec3 kCameraRight(1.0, 0.0, 0.0);
const dvec3 kCameraForward(0.0, 0.0, -1.0);

View defaultView(dvec2 extent, bool reversed = false, double farPlane = 200.0) {
  return makeView(dvec3(0.0), kCameraForward, extent, reversed, farPlane);
}

// ---------------------------------------------------------------------------------------------
// Epipole

TEST(EpipolarGeometry, EpipoleMatchesDoubleProjection) {
  const dvec2 extent(1280.0, 720.0);
  for (bool reversed : {false, true}) {
    for (double farPlane : {200.0, std::numeric_limits<double>::infinity()}) {
      // An oblique camera, so that no coordinate is trivially zero.
      const View v = makeView(dvec3(3.0, 2.0, 5.0), dvec3(-4.0, 0.5, -7.0), extent, reversed, farPlane);
      for (const EpipoleCase& c : epipoleCases()) {
        const dvec3 lightDir = lightDirFor(v, c);
        const vec4 e = epipoleOf(v, lightDir);
        const dvec4 clip = v.viewProj * dvec4(-lightDir, 0.0);
        const dvec2 ndc = dvec2(clip) / clip.w;
        EXPECT_NEAR(ndc.x, c.ndc.x, 1e-9 * (1.0 + std::abs(c.ndc.x))) << c.name;  // the scaffold
        EXPECT_EQ(tyn_epipole_behind(e), c.behind) << c.name;
        EXPECT_EQ(e.w, c.behind ? -1.0f : 1.0f) << c.name;
        EXPECT_GT(e.z, 0.0f) << c.name;
        EXPECT_NEAR(glm::length(vec3(e)), 1.0f, 1e-6f) << c.name;
        // The homogeneous epipole (what the slices use): float matrices make a near-infinite
        // epipole's NDC uncertain, not its direction.
        const double side = clip.w < 0.0 ? -1.0 : 1.0;
        const dvec3 h = glm::normalize(dvec3(clip.x, clip.y, clip.w) * side);
        EXPECT_LT(glm::length(dvec3(vec3(e)) - h), 1e-6) << c.name;
        const dvec2 got = d2(tyn_epipole_ndc(e));
        if (glm::length(ndc) < 10.0) {
          EXPECT_LT(glm::length(got - ndc), 2e-6 * (1.0 + glm::length(ndc))) << c.name;
        }
        const Rect r = sampleRect(extent);
        const bool inside = ndc.x >= r.lo.x && ndc.x <= r.hi.x && ndc.y >= r.lo.y && ndc.y <= r.hi.y;
        EXPECT_EQ(tyn_epipole_on_screen(e, f2(extent)), inside) << c.name;
      }
      // A local light: the same point seen through a position instead of a direction.
      for (const EpipoleCase& c : epipoleCases()) {
        const dvec3 dir = rayThrough(v, c.ndc);
        const dvec3 lightPos = v.position + (c.behind ? -dir : dir) * 37.0;
        const vec4 e = tyn_epipole(tyn_epipole_clip_local(mat4(v.viewProj), f3(lightPos)));
        EXPECT_EQ(tyn_epipole_behind(e), c.behind) << c.name;
        const dvec4 clip = v.viewProj * dvec4(lightPos, 1.0);
        const dvec3 h = glm::normalize(dvec3(clip.x, clip.y, clip.w) * (clip.w < 0.0 ? -1.0 : 1.0));
        EXPECT_LT(glm::length(dvec3(vec3(e)) - h), 2e-6) << c.name;
        if (glm::length(c.ndc) < 10.0) {
          EXPECT_LT(glm::length(d2(tyn_epipole_ndc(e)) - c.ndc), 2e-5 * (1.0 + glm::length(c.ndc))) << c.name;
        }
      }
    }
  }
}

TEST(EpipolarGeometry, EpipoleOnTheViewAxis) {
  const View v = defaultView(dvec2(640.0, 360.0));
  // In front: the light comes from straight ahead; behind: it shines along the view direction.
  const vec4 front = epipoleOf(v, -kCameraForward);
  EXPECT_EQ(front, vec4(0.0f, 0.0f, 1.0f, 1.0f));
  EXPECT_TRUE(tyn_epipole_on_screen(front, vec2(640.0f, 360.0f)));
  const vec4 behind = epipoleOf(v, kCameraForward);
  EXPECT_EQ(behind, vec4(0.0f, 0.0f, 1.0f, -1.0f));
  EXPECT_TRUE(tyn_epipole_behind(behind));
  EXPECT_TRUE(tyn_epipole_on_screen(behind, vec2(640.0f, 360.0f)));
  // A local light on the axis, in front and behind.
  const vec4 local = tyn_epipole(tyn_epipole_clip_local(mat4(v.viewProj), vec3(0.0f, 0.0f, -5.0f)));
  EXPECT_NEAR(glm::length(tyn_epipole_ndc(local)), 0.0f, 1e-7f);
  EXPECT_EQ(local.w, 1.0f);
  const vec4 localBehind = tyn_epipole(tyn_epipole_clip_local(mat4(v.viewProj), vec3(0.0f, 0.0f, 5.0f)));
  EXPECT_NEAR(glm::length(tyn_epipole_ndc(localBehind)), 0.0f, 1e-7f);
  EXPECT_EQ(localBehind.w, -1.0f);
}

TEST(EpipolarGeometry, EpipoleAtInfinityAndDegenerate) {
  const View v = defaultView(dvec2(640.0, 360.0));
  // Light in the camera plane (perpendicular to the view axis): clip w = 0, the epipole is a
  // direction; the epipolar lines are parallel to the light's screen direction.
  const dvec3 lightDir = -glm::normalize(dvec3(0.8, 0.6, 0.0));
  const vec4 e = epipoleOf(v, lightDir);
  EXPECT_NEAR(e.z, 0.0f, 1e-7f);
  EXPECT_FALSE(tyn_epipole_on_screen(e, vec2(640.0f, 360.0f)));
  const dvec4 clip = v.viewProj * dvec4(-lightDir, 0.0);
  const dvec2 screenDir = glm::normalize(dvec2(clip));
  EXPECT_LT(glm::length(d2(vec2(e)) - screenDir), 1e-6);
  // Every epipolar line runs away from the point at infinity, i.e. along −screenDir.
  for (dvec2 p : {dvec2(0.0), dvec2(0.7, -0.4), dvec2(-0.99, 0.99)}) {
    const dvec2 d = glm::normalize(d2(tyn_epipolar_direction(e, f2(p))));
    EXPECT_LT(glm::length(d + screenDir), 1e-6);
  }
  // Light at the camera position: degenerate, taken at the screen centre.
  const vec4 atCamera = tyn_epipole(tyn_epipole_clip_local(mat4(v.viewProj), vec3(0.0f)));
  EXPECT_EQ(atCamera, vec4(0.0f, 0.0f, 1.0f, 0.0f));
  EXPECT_FALSE(tyn_epipole_behind(atCamera));
  // An orthographic camera with the light along its axis: also degenerate.
  const mat4 ortho = mat4(glm::orthoRH_ZO(-4.0, 4.0, -3.0, 3.0, 0.1, 100.0));
  EXPECT_EQ(tyn_epipole(tyn_epipole_clip_directional(ortho, vec3(0.0f, 0.0f, -1.0f))),
            vec4(0.0f, 0.0f, 1.0f, 0.0f));
}

// ---------------------------------------------------------------------------------------------
// Exit points

TEST(EpipolarGeometry, ExitPointsOnTheShrunkBorderEvenlyClockwise) {
  for (dvec2 extent : {dvec2(640.0, 360.0), dvec2(37.0, 53.0), dvec2(2.0, 2.0), dvec2(1920.0, 1080.0)}) {
    const Rect r = sampleRect(extent);
    const double perimeter = perimeterTotal(extent);
    EXPECT_DOUBLE_EQ(tyn_border_length_pixels(f2(extent)), perimeter);
    const dvec4 rect = dvec4(tyn_epipolar_screen_rect(f2(extent)));
    EXPECT_LT(glm::length(rect - dvec4(1.0 / extent - 1.0, 1.0 - 1.0 / extent)), 1e-7);
    // Pixel centres are on or inside it: the first and last are its corners.
    EXPECT_EQ(tyn_ndc_from_pixel(vec2(0.5f), f2(extent)), vec2(rect));
    EXPECT_EQ(tyn_ndc_from_pixel(f2(extent) - 0.5f, f2(extent)), vec2(rect.z, rect.w));
    for (uint n : {1u, 7u, 64u, 100u, 1024u}) {
      const double spacing = perimeter / n;
      double previous = -1.0;
      for (uint i = 0; i < n; ++i) {
        const dvec2 x = d2(tyn_exit_point(float(i), n, f2(extent)));
        // On the sample rectangle: inside it, and on one of its edges.
        const double tol = 1e-6;
        EXPECT_TRUE(x.x >= r.lo.x - tol && x.x <= r.hi.x + tol && x.y >= r.lo.y - tol && x.y <= r.hi.y + tol)
            << i;
        const double edgeDistance = std::min(std::min(std::abs(x.x - r.lo.x), std::abs(x.x - r.hi.x)),
                                              std::min(std::abs(x.y - r.lo.y), std::abs(x.y - r.hi.y)));
        EXPECT_LT(edgeDistance, 1e-6) << "extent " << extent.x << " n " << n << " slice " << i;
        // In order, clockwise from the top-left corner, evenly spaced by length in pixels.
        const double s = perimeterPixels(x, extent);
        EXPECT_NEAR(s, i * spacing, 2e-4 * std::max(1.0, extent.x / 640.0)) << i;
        EXPECT_GT(s, previous) << i;
        previous = s;
        // The inverse gives back the slice index.
        EXPECT_LT(sliceDistance(tyn_border_slice_coordinate(f2(x), n, f2(extent)), i, n), 1e-3) << i;
      }
      // Slice 0 sits on the top-left corner; a quarter of the perimeter ahead (by length) the
      // exit is on the top edge when it is wider than tall, on the right edge at W − 1 pixels.
      EXPECT_LT(glm::length(d2(tyn_exit_point(0.0f, n, f2(extent))) - r.lo), 1e-7);
      const float onRight = static_cast<float>((extent.x - 1.0 + 0.5 * (extent.y - 1.0)) / perimeter * n);
      const dvec2 right = d2(tyn_exit_point(onRight, n, f2(extent)));
      EXPECT_NEAR(right.x, r.hi.x, 1e-7);
      EXPECT_NEAR(right.y, 0.5 * (r.lo.y + r.hi.y), 1e-4);
      const float onBottom = static_cast<float>((1.5 * (extent.x - 1.0) + (extent.y - 1.0)) / perimeter * n);
      const dvec2 bottom = d2(tyn_exit_point(onBottom, n, f2(extent)));
      EXPECT_NEAR(bottom.y, r.hi.y, 1e-7);
      EXPECT_NEAR(bottom.x, 0.5 * (r.lo.x + r.hi.x), 1e-4);
      // Continuous slice N is slice 0 again (the seam).
      EXPECT_LT(glm::length(d2(tyn_exit_point(float(n), n, f2(extent))) - r.lo), 1e-6);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Slice end points

TEST(EpipolarGeometry, SliceEndPointsMatchDoubleClippingAndCulledSlicesMissTheScreen) {
  for (dvec2 extent : {dvec2(640.0, 360.0), dvec2(37.0, 53.0)}) {
    const View v = defaultView(extent);
    const vec2 fextent = f2(extent);
    const Rect r = sampleRect(extent);
    for (const LightCase& lc : lightCases(v, kCameraRight, kCameraForward)) {
      const vec4 e = epipoleOf(v, lc.lightDir);
      const dvec4 clip = v.viewProj * dvec4(-lc.lightDir, 0.0);
      const Epipole ref{dvec3(clip.x, clip.y, clip.w)};
      const bool onScreen = tyn_epipole_on_screen(e, fextent);
      int valid = 0;
      const uint n = 256;
      for (uint i = 0; i < n; ++i) {
        const vec2 exit = tyn_exit_point(float(i), n, fextent);
        vec4 ends;
        const bool ok = tyn_slice_end_points(e, exit, fextent, ends);
        EXPECT_EQ(ok, tyn_slice_valid(ends)) << lc.name << " slice " << i;
        dvec2 entryRef;
        const double visible = visibleSegmentPixels(ref, d2(exit), extent, &entryRef);
        if (onScreen) {
          // Every slice starts at the epipole.
          EXPECT_TRUE(ok) << lc.name << " slice " << i;
          EXPECT_LT(glm::length(d2(vec2(ends)) - ref.ndc()), 1e-6) << lc.name;
        } else if (visible > TYN_EPIPOLAR_MIN_SLICE_PIXELS + 1e-3) {
          EXPECT_TRUE(ok) << lc.name << " slice " << i << " visible " << visible;
          if (ok) {
            // The entry is the double-precision first crossing, the exit is untouched.
            EXPECT_LT(glm::length(d2(vec2(ends)) - entryRef), 1e-4) << lc.name << " slice " << i;
            EXPECT_EQ(vec2(ends.z, ends.w), exit);
          }
        } else if (visible < TYN_EPIPOLAR_MIN_SLICE_PIXELS - 1e-3) {
          EXPECT_FALSE(ok) << lc.name << " slice " << i << " visible " << visible;
        }
        if (ok) ++valid;
        if (!ok) {
          EXPECT_EQ(ends, vec4(TYN_EPIPOLAR_INVALID_COORD));
          // Brute force: walk the segment from the epipole (or from far along the direction it
          // comes from) to the exit point; what lies in the sample rectangle spans under the
          // culling threshold.
          const dvec2 x = d2(exit);
          const dvec2 start = ref.finite() ? ref.ndc() : x + dvec2(ref.h) * (ref.h.z < 0.0 ? -1e4 : 1e4);
          double first = -1.0, last = -1.0;
          const int steps = 200000;
          for (int k = 0; k <= steps; ++k) {
            const double t = static_cast<double>(k) / steps;
            const dvec2 p = start + (x - start) * t;
            if (p.x > r.lo.x && p.x < r.hi.x && p.y > r.lo.y && p.y < r.hi.y) {
              if (first < 0.0) first = t;
              last = t;
            }
          }
          const double spanPixels =
              first < 0.0 ? 0.0 : (last - first) * glm::length((x - start) * extent * 0.5);
          const double stepPixels = glm::length((x - start) * extent * 0.5) / steps;
          EXPECT_LE(spanPixels, TYN_EPIPOLAR_MIN_SLICE_PIXELS + 2.0 * stepPixels + 1e-3)
              << lc.name << " slice " << i;
        }
      }
      if (onScreen) {
        EXPECT_EQ(valid, static_cast<int>(n)) << lc.name;
      }
      EXPECT_GT(valid, 0) << lc.name;  // every case sees its shafts somewhere
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Inverse (unwarp)

// The slice coordinate of a pixel computed independently in double.
// Where the line from the epipole through p leaves the sample rectangle, beyond p.
dvec2 referenceBorderPoint(const Epipole& e, dvec2 p, dvec2 extent) {
  const dvec2 dir = e.finite() ? (p - e.ndc()) : -dvec2(e.h) * (e.h.z < 0.0 ? -1.0 : 1.0);
  const double t = clipLine(p, dir, sampleRect(extent)).y;
  return p + dir * std::max(t, 0.0);
}

double referenceSliceCoordinate(const Epipole& e, dvec2 p, uint n, dvec2 extent) {
  const dvec2 b = referenceBorderPoint(e, p, extent);
  double c = perimeterPixels(b, extent) / perimeterTotal(extent) * n;
  return c >= n ? c - n : c;
}

struct Coverage {
  int pixels = 0;
  int roundTrips = 0;
};

void checkCoverage(const View& v, const LightCase& lc, dvec2 extent, uint n, int stride, Coverage& stats) {
  const vec2 fextent = f2(extent);
  const vec4 e = epipoleOf(v, lc.lightDir);
  const dvec4 clip = v.viewProj * dvec4(-lc.lightDir, 0.0);
  const Epipole ref{dvec3(clip.x, clip.y, clip.w)};
  const double spacingNdc = 2.0 * perimeterTotal(extent) / n / std::min(extent.x, extent.y);
  int failures = 0;
  for (int py = 0; py < static_cast<int>(extent.y) && failures < 5; py += stride) {
    for (int px = 0; px < static_cast<int>(extent.x) && failures < 5; px += stride) {
      const vec2 p = tyn_ndc_from_pixel(vec2(float(px), float(py)) + 0.5f, fextent);
      const dvec2 pd = d2(p);
      ++stats.pixels;
      const float c = tyn_slice_coordinate(e, p, n, fextent);
      const bool nearEpipole = ref.finite() && glm::length(pd - ref.ndc()) < 1e-3;
      bool ok = c >= 0.0f && c < float(n);
      std::string why;
      // The line epipole → pixel reaches the border at the slice coordinate the double
      // construction finds (between the exit points of the two slices around it).
      if (!nearEpipole) {
        // The float epipole's rounding (~1e-6 NDC) turns the line by ~1e-6/|p − epipole|; at
        // the border, 2 NDC away, that moves the exit by that times the slices per NDC unit.
        const double angle = ref.finite() ? 2e-6 / glm::length(pd - ref.ndc()) : 0.0;
        const double tolerance = 2e-3 + 2.0 * angle * n / perimeterTotal(extent) * std::max(extent.x, extent.y) * 0.5;
        if (!(sliceDistance(c, referenceSliceCoordinate(ref, pd, n, extent), n) < tolerance)) {
          ok = false;
          why += " slice coordinate;";
        }
      }
      // Round trip through the continuous slice: its end points, the pixel's fraction along it,
      // back to a screen position.
      vec4 ends;
      if (tyn_slice_end_points(e, tyn_exit_point(c, n, fextent), fextent, ends)) {
        const float u = tyn_slice_fraction(ends, p);
        const dvec2 back = d2(vec2(ends)) + (d2(vec2(ends.z, ends.w)) - d2(vec2(ends))) * double(u);
        // On the slice's line, and within 1e-4 NDC of its visible segment.
        const double outside = std::max(0.0, std::max(-double(u), double(u) - 1.0)) *
                               glm::length(d2(vec2(ends.z, ends.w)) - d2(vec2(ends)));
        if (!(glm::length(back - pd) < 1e-4 && outside < 1e-4)) {
          ok = false;
          why += " round trip u " + std::to_string(u) + " error " + std::to_string(glm::length(back - pd)) + ";";
        }
        ++stats.roundTrips;
      } else {
        // Only a pixel on the border, on a line that merely grazes the screen, may lie on a culled
        // slice (e.g. the corner pixel nearest an off-screen epipole).
        const double visible = visibleSegmentPixels(ref, referenceBorderPoint(ref, pd, extent), extent, nullptr);
        if (!(visible < TYN_EPIPOLAR_MIN_SLICE_PIXELS + 1e-2)) {
          ok = false;
          why += " culled slice with visible " + std::to_string(visible) + ";";
        }
        const Rect r = sampleRect(extent);
        ok &= std::abs(pd.x - r.lo.x) < 1e-6 || std::abs(pd.x - r.hi.x) < 1e-6 ||
              std::abs(pd.y - r.lo.y) < 1e-6 || std::abs(pd.y - r.hi.y) < 1e-6;
      }
      // Covered: one of the two discrete slices around it is valid and has a sample position
      // within one exit spacing of it. A pixel exactly on an exit point (fract(c) = 0 up to
      // rounding) is on that slice, which may be a culled grazing line (a screen corner seen
      // along an edge): then the slice on its other side covers it, so both sides count.
      const uvec2 pair = tyn_slice_pair(c, n);
      ok &= pair.x < n && pair.y == (pair.x + 1u) % n;
      std::vector<uint> candidates = {pair.x, pair.y};
      const double nearest = std::round(double(c));
      if (std::abs(double(c) - nearest) < 1e-3) {
        candidates.push_back((static_cast<uint>(nearest) + n - 1u) % n);
        candidates.push_back(static_cast<uint>(nearest) % n);
      }
      bool covered = false;
      for (uint s : candidates) {
        vec4 se;
        if (!tyn_slice_end_points(e, tyn_exit_point(float(s), n, fextent), fextent, se)) continue;
        // The unwarp pass clamps to the slice's samples: its nearest sample position is what counts
        // (a pixel in a screen corner lies beyond both exit points around it).
        const double u = std::clamp(double(tyn_slice_fraction(se, p)), 0.0, 1.0);
        const dvec2 a = d2(vec2(se)), b = d2(vec2(se.z, se.w));
        const dvec2 foot = a + (b - a) * u;
        if (glm::length(foot - pd) <= spacingNdc + 1e-6) covered = true;
      }
      ok &= covered;
      if (!ok) {
        ++failures;
        ADD_FAILURE() << lc.name << " extent " << extent.x << "x" << extent.y << " n " << n << " pixel ("
                      << px << ", " << py << ") c " << c << " ref "
                      << referenceSliceCoordinate(ref, pd, n, extent) << " covered " << covered << why;
      }
    }
  }
}

TEST(EpipolarGeometry, EveryPixelCentreIsCoveredAndRoundTrips) {
  Coverage stats;
  for (dvec2 extent : {dvec2(64.0, 36.0), dvec2(37.0, 53.0), dvec2(640.0, 360.0)}) {
    const View v = defaultView(extent);
    const int stride = extent.x > 100.0 ? 7 : 1;
    for (const LightCase& lc : lightCases(v, kCameraRight, kCameraForward)) {
      for (uint n : {16u, 64u, 100u, 512u}) checkCoverage(v, lc, extent, n, stride, stats);
    }
  }
  // The round trip really ran (the culled-slice branch is for a handful of border pixels).
  EXPECT_GT(stats.roundTrips, stats.pixels * 99 / 100);
}

TEST(EpipolarGeometry, SliceCoordinateWrapsAtTheSeam) {
  const dvec2 extent(64.0, 36.0);
  const vec2 fextent = f2(extent);
  const uint n = 64;
  // Epipole at the screen centre: pixels just below the top-left corner on the left edge are
  // between the last slice and slice 0.
  const vec4 e = vec4(0.0f, 0.0f, 1.0f, 1.0f);
  const vec2 p = tyn_ndc_from_pixel(vec2(0.5f, 1.5f), fextent);
  const float c = tyn_slice_coordinate(e, p, n, fextent);
  EXPECT_GT(c, float(n - 1u));
  EXPECT_LT(c, float(n));
  EXPECT_EQ(tyn_slice_pair(c, n), uvec2(n - 1u, 0u));
  // Just right of the corner on the top edge: slice 0 and 1.
  const float c2 = tyn_slice_coordinate(e, tyn_ndc_from_pixel(vec2(1.5f, 0.5f), fextent), n, fextent);
  EXPECT_EQ(tyn_slice_pair(c2, n), uvec2(0u, 1u));
  // At the epipole itself a slice is still returned, and the pixel sits at its entry.
  const float c3 = tyn_slice_coordinate(e, vec2(0.0f), n, fextent);
  EXPECT_TRUE(c3 >= 0.0f && c3 < float(n));
  vec4 ends;
  ASSERT_TRUE(tyn_slice_end_points(e, tyn_exit_point(c3, n, fextent), fextent, ends));
  EXPECT_NEAR(tyn_slice_fraction(ends, vec2(0.0f)), 0.0f, 1e-7f);
}

// ---------------------------------------------------------------------------------------------
// Sample placement

double referenceFraction(double t, double density) {
  const double rho = std::clamp(density, 1.0, 1000.0);
  const double b = (rho - 1.0) / (rho + 1.0);
  return t - b * t * (1.0 - t);
}

TEST(EpipolarGeometry, SamplePlacementHitsBothEndsAndIsMonotonic) {
  const vec4 ends(-0.31f, 0.77f, 0.998f, -0.42f);
  for (uint count : {2u, 3u, 17u, 256u, 1024u}) {
    for (float density : {1.0f, 1.5f, 4.0f, 16.0f, 0.5f}) {
      EXPECT_EQ(tyn_sample_position(ends, 0.0f, count, density), vec2(ends));
      EXPECT_EQ(tyn_sample_position(ends, float(count - 1u), count, density), vec2(ends.z, ends.w));
      EXPECT_EQ(tyn_sample_fraction(float(count - 1u), count, density), 1.0f);
      double previousFraction = -1.0, previousDistance = -1.0;
      for (uint k = 0; k < count; ++k) {
        const double t = static_cast<double>(k) / (count - 1u);
        const double f = tyn_sample_fraction(float(k), count, density);
        EXPECT_NEAR(f, referenceFraction(t, density), 2e-7) << count << " " << density << " " << k;
        EXPECT_GT(f, previousFraction);
        previousFraction = f;
        const dvec2 pos = d2(tyn_sample_position(ends, float(k), count, density));
        const double distance = glm::length(pos - d2(vec2(ends)));
        EXPECT_GE(distance, previousDistance - 1e-7);
        previousDistance = distance;
        // On the segment.
        const dvec2 expected = d2(vec2(ends)) + (d2(vec2(ends.z, ends.w)) - d2(vec2(ends))) * f;
        EXPECT_LT(glm::length(pos - expected), 1e-6);
      }
    }
  }
  // The density factor is the ratio of the last spacing to the first (uniform: 1).
  for (float density : {1.0f, 2.0f, 8.0f, 100.0f}) {
    const uint count = 4097;
    const double first = tyn_sample_fraction(1.0f, count, density) - tyn_sample_fraction(0.0f, count, density);
    const double last = tyn_sample_fraction(float(count - 1u), count, density) -
                        tyn_sample_fraction(float(count - 2u), count, density);
    EXPECT_NEAR(last / first, density, 2e-2 * density) << density;
  }
  // Fewer than two samples: everything at the entry.
  EXPECT_EQ(tyn_sample_position(ends, 0.0f, 1u, 1.0f), vec2(ends));
}

TEST(EpipolarGeometry, SampleCoordinateInvertsSamplePlacement) {
  const vec4 ends(0.1f, -0.2f, -0.9f, 0.95f);
  for (uint count : {2u, 33u, 512u, 1024u}) {
    for (float density : {1.0f, 2.0f, 10.0f, 1000.0f}) {
      for (double k = 0.0; k <= count - 1.0; k += (count - 1.0) / 97.0) {
        const vec2 pos = tyn_sample_position(ends, static_cast<float>(k), count, density);
        const float u = tyn_slice_fraction(ends, pos);
        EXPECT_NEAR(tyn_sample_coordinate(u, count, density), k, 2e-6 * count + 1e-4)
            << count << " " << density;
      }
      EXPECT_EQ(tyn_sample_coordinate(0.0f, count, density), 0.0f);
      EXPECT_NEAR(tyn_sample_coordinate(1.0f, count, density), count - 1.0, 1e-6 * count);
      EXPECT_EQ(tyn_sample_coordinate(-0.5f, count, density), 0.0f);  // clamped
    }
  }
}

TEST(EpipolarGeometry, ImprovedPlacementSpacesShortSlicesOnePixelApart) {
  const dvec2 extent(1280.0, 720.0);
  const vec2 fextent = f2(extent);
  const uint maxSamples = 256;
  for (double lengthPixels : {0.3, 5.3, 37.0, 150.0, 255.0, 600.0}) {
    for (float density : {1.0f, 3.0f}) {
      // A slanted slice of the given length in pixels.
      const dvec2 dirPixels = glm::normalize(dvec2(3.0, 1.0)) * lengthPixels;
      const dvec2 entry(-0.2, 0.1);
      const dvec2 exit = entry + dirPixels * 2.0 / extent;
      const vec4 ends(f2(entry), f2(exit));
      const uint count = tyn_slice_sample_count(ends, fextent, maxSamples, density, true);
      const double b = (density - 1.0) / (density + 1.0);
      const double expected = std::clamp(std::ceil(lengthPixels * (1.0 + b)) + 1.0, 2.0, double(maxSamples));
      EXPECT_NEAR(count, expected, 1.0) << lengthPixels;  // ceil at a float boundary
      double largest = 0.0;
      for (uint k = 1; k < count; ++k) {
        const dvec2 a = d2(tyn_sample_position(ends, float(k - 1u), count, density));
        const dvec2 c = d2(tyn_sample_position(ends, float(k), count, density));
        largest = std::max(largest, glm::length((c - a) * extent * 0.5));
      }
      EXPECT_LT(glm::length(d2(tyn_sample_position(ends, float(count - 1u), count, density)) - exit), 1e-6);
      if (count < maxSamples) {
        // Short slice: the largest spacing is one pixel, or just under (≈ 1 pixel apart).
        EXPECT_LE(largest, 1.0 + 1e-4) << lengthPixels;
        if (lengthPixels >= 5.0) {
          EXPECT_GT(largest, 0.8) << lengthPixels;
        }
      } else {
        // Long slice: all the samples, spaced more than a pixel.
        EXPECT_EQ(count, maxSamples);
        EXPECT_GT(largest, 1.0) << lengthPixels;
      }
      EXPECT_EQ(tyn_slice_sample_count(ends, fextent, maxSamples, density, false), maxSamples);
    }
  }
  EXPECT_EQ(tyn_slice_sample_count(vec4(TYN_EPIPOLAR_INVALID_COORD), fextent, maxSamples, 1.0f, true), 0u);
  EXPECT_EQ(tyn_slice_sample_count(vec4(TYN_EPIPOLAR_INVALID_COORD), fextent, maxSamples, 1.0f, false), 0u);
}

// ---------------------------------------------------------------------------------------------
// The surface around a pixel (depth-buffer planes)

// A camera 1.7 above the ground y = 0 looking towards the horizon, as D32 depth values of the
// ground and of walls facing the camera (fronto-parallel, at a view distance), built in double
// from the projection and rounded to float as the depth buffer holds them.
struct DepthScene {
  dvec2 extent;
  dmat4 projection;
  dmat4 view;
  vec4 toViewZ(dvec2 pixel) const {  // as tyn_epipolar_depth_slopes builds it
    const dmat4 m = glm::inverse(projection);
    const dvec2 ndc = (pixel + 0.5) / extent * 2.0 - 1.0;
    return vec4(dvec4(m[2][2], m[0][2] * ndc.x + m[1][2] * ndc.y + m[3][2], m[2][3],
                      m[0][3] * ndc.x + m[1][3] * ndc.y + m[3][3]));
  }
  double projectedDepth(double viewZ) const {
    const dvec4 c = projection * dvec4(0.0, 0.0, viewZ, 1.0);
    return std::clamp(c.z / c.w, 0.0, 1.0);
  }
  // Depth of the ground at a (fractional) pixel position, in double.
  double ground(dvec2 pixel) const {
    const dmat4 inverse = glm::inverse(projection * view);
    const dvec2 ndc = (pixel + 0.5) / extent * 2.0 - 1.0;
    const dvec4 a = inverse * dvec4(ndc, 0.5, 1.0);
    const dvec3 eye = dvec3(glm::inverse(view)[3]);
    const dvec3 dir = glm::normalize(dvec3(a) / a.w - eye);
    const dvec3 hit = eye + dir * (-eye.y / dir.y);
    const dvec4 c = projection * view * dvec4(hit, 1.0);
    return c.z / c.w;
  }
  // Depth of a wall facing the camera at view distance `distance`.
  float wall(double distance) const { return float(projectedDepth(-distance)); }
};

DepthScene depthScene(bool reversed, double farPlane) {
  const dvec2 extent(640.0, 360.0);
  return {extent, vulkanPerspective(glm::radians(60.0), extent.x / extent.y, 0.1, farPlane, reversed),
          glm::lookAt(dvec3(0.0, 1.7, 0.0), dvec3(0.0, 1.5, -20.0), dvec3(0.0, 1.0, 0.0))};
}

// tyn_depth_plane_slope on seven depths in a row (three before the pixel, the pixel, three after),
// all on screen unless `onScreen` says otherwise (pixels before, after the pixel).
float planeSlope(const std::array<float, 7>& d, const vec4& toViewZ, float tolerance, glm::ivec2 onScreen = {3, 3}) {
  const bvec3 before(onScreen.x >= 1, onScreen.x >= 2, onScreen.x >= 3);
  const bvec3 after(onScreen.y >= 1, onScreen.y >= 2, onScreen.y >= 3);
  return tyn_depth_plane_slope(d[0], d[1], d[2], d[3], d[4], d[5], d[6], before, after, toViewZ, vec2(0.0f, 1.0f),
                               tolerance);
}

TEST(EpipolarGeometry, DepthPlaneSlopeFollowsPlanesAndStopsAtSilhouettes) {
  const float tolerance = 0.05f;  // EpipolarSettings::bilateralDepthThreshold's default
  const vec2 range(0.0f, 1.0f);   // [min, max] of the near and far planes' depths, any convention
  for (const bool reversed : {false, true}) {
    for (const double farPlane : {80.0, std::numeric_limits<double>::infinity()}) {
      const DepthScene scene = depthScene(reversed, farPlane);
      const std::string name = std::string(reversed ? "reverse-Z" : "standard") + (std::isinf(farPlane) ? ", infinite" : "");
      // Ground at a grazing angle, from 7 to 43 units away (its ray length changes by up to 10%
      // per pixel): the central difference, and the plane through a pixel gives the ground's depth
      // between pixel centres, in view z to float precision.
      for (const double row : {190.0, 200.0, 220.0, 260.0}) {
        const dvec2 p(300.0, row);
        const vec4 toZ = scene.toViewZ(p);
        auto ground = [&](double dy) { return float(scene.ground(p + dvec2(0.0, dy))); };
        const std::array<float, 7> column{ground(-3), ground(-2), ground(-1), ground(0), ground(1), ground(2), ground(3)};
        const float slope = planeSlope(column, toZ, tolerance);
        const double central = 0.5 * (double(ground(1)) - double(ground(-1)));
        EXPECT_NE(slope, 0.0f) << name << " " << row;
        EXPECT_NEAR(slope, central, 1e-6 * std::abs(central)) << name << " " << row;
        for (const double offset : {-0.5, 0.5, 1.0}) {
          const double exact = tyn_depth_view_z(float(scene.ground(p + dvec2(0.0, offset))), toZ);
          const double onPlane =
              tyn_depth_view_z(tyn_depth_on_plane(ground(0), vec2(0.0f, slope), vec2(0.0f, float(offset)), range), toZ);
          EXPECT_NEAR(onPlane, exact, 2e-4 * std::abs(exact)) << name << " " << row << " " << offset;
        }
        // A silhouette below the pixel (a wall 3 units away): the ground's one-sided slope above
        // the pixel, and the wall's own (flat) slope on the wall's side.
        const float wall = scene.wall(3.0);
        const double above = double(ground(0)) - double(ground(-1));
        EXPECT_NEAR(planeSlope({ground(-3), ground(-2), ground(-1), ground(0), wall, wall, wall}, toZ, tolerance), above,
                    1e-6 * std::abs(above))
            << name << " " << row;
        EXPECT_EQ(planeSlope({ground(-2), ground(-1), ground(0), wall, wall, wall, wall}, toZ, tolerance), 0.0f);
        // A sliver one pixel wide (the wall at the pixel only): no plane.
        EXPECT_EQ(planeSlope({ground(-3), ground(-2), ground(-1), wall, ground(1), ground(2), ground(3)}, toZ, tolerance),
                  0.0f);
        // Off the screen's edge: the side that is there with enough pixels, or nothing.
        EXPECT_NEAR(planeSlope(column, toZ, tolerance, {3, 0}), above, 1e-6 * std::abs(above));
        EXPECT_EQ(planeSlope(column, toZ, tolerance, {2, 0}), 0.0f);
        EXPECT_NEAR(planeSlope(column, toZ, tolerance, {2, 1}), central, 1e-6 * std::abs(central));
        EXPECT_EQ(planeSlope(column, toZ, tolerance, {1, 1}), 0.0f);
      }
      const vec4 toZ = scene.toViewZ(dvec2(300.0, 150.0));
      // A crease (a ridge): the pixel is on two planes, neither continuing through it: no plane.
      const float ridge = scene.wall(10.0);
      const float step = ridge - scene.wall(10.3);
      EXPECT_EQ(planeSlope({ridge - 3.0f * step, ridge - 2.0f * step, ridge - step, ridge, ridge - step,
                            ridge - 2.0f * step, ridge - 3.0f * step},
                           toZ, tolerance),
                0.0f);
      // Thin trunks before a far background, forest at 640x360 (distances halved to stay within
      // the far plane): a pixel of one trunk after two others, the three nearly collinear in depth
      // (their 1/z steps agree within 2%) but not with the trunk before them: no plane.
      EXPECT_EQ(planeSlope({scene.wall(9.0), scene.wall(27.99), scene.wall(20.79), scene.wall(16.59), scene.wall(39.06),
                            scene.wall(39.06), scene.wall(39.06)},
                           toZ, tolerance),
                0.0f);
      // A pixel of sky beside a silhouette: the sky's flat plane, not the one through the silhouette.
      const float sky = reversed ? 0.0f : 1.0f;
      EXPECT_EQ(planeSlope({scene.wall(20.0), scene.wall(20.0), scene.wall(20.0), sky, sky, sky, sky}, toZ, tolerance),
                0.0f);
      // The plane is kept within the depth range: past the horizon it ends at the far plane.
      EXPECT_EQ(tyn_depth_on_plane(0.5f, vec2(0.0f, 1.0f), vec2(0.0f, 2.0f), range), range.y);
      EXPECT_EQ(tyn_depth_on_plane(0.5f, vec2(0.0f, -1.0f), vec2(0.0f, 2.0f), range), range.x);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Slice in shadow-map UV

dvec2 shadowUv(const dmat4& m, dvec3 p, double* w = nullptr) {
  const dvec4 c = m * dvec4(p, 1.0);
  if (w != nullptr) *w = c.w;
  return dvec2(c) / c.w * 0.5 + 0.5;
}

glm::dmat4 lookAlong(dvec3 eye, dvec3 forward) {
  const dvec3 up = std::abs(forward.y) < 0.99 ? dvec3(0.0, 1.0, 0.0) : dvec3(1.0, 0.0, 0.0);
  return glm::lookAt(eye, eye + forward, up);
}

// Checks the slices of a view against brute-force projections of their view rays.
// inRegion: whether a world point is in the region the slice is bounded by (and its image).
template <typename InRegion>
void checkShadowSlices(const View& v, const dmat4& shadow, const vec4& e, const vec3& cone,
                       InRegion inRegion, const std::string& name, bool expectCameraOrigin,
                       int* validSlices, int* reachingSlices) {
  const uint n = 32;
  const vec2 fextent = f2(v.extent);
  for (uint i = 0; i < n; ++i) {
    vec4 ends;
    if (!tyn_slice_end_points(e, tyn_exit_point(float(i), n, fextent), fextent, ends)) continue;
    const dvec3 exitRay = rayThrough(v, d2(vec2(ends.z, ends.w)));
    vec4 od;
    float uvLength = -1.0f;
    const bool ok = tyn_slice_shadow_uv(mat4(shadow), f3(v.position), f3(exitRay), cone, od, uvLength);
    const dvec2 origin = d2(vec2(od)), dir = d2(vec2(od.z, od.w));
    if (ok) {
      ++*validSlices;
      EXPECT_NEAR(glm::length(dir), 1.0, 1e-6) << name << " slice " << i;
      EXPECT_GE(uvLength, 0.0f);
    }
    bool anyInRegion = false;
    for (int r = 0; r <= 8; ++r) {
      // Rays through points of the slice, entry to exit.
      const dvec2 p = d2(vec2(ends)) + (d2(vec2(ends.z, ends.w)) - d2(vec2(ends))) * (r / 8.0);
      const dvec3 ray = rayThrough(v, p);
      double previous = -std::numeric_limits<double>::infinity();
      bool wasIn = false;
      double tPrev = 0.0;
      for (int k = 0; k <= 4000; ++k) {
        const double t = k == 0 ? 0.0 : 1e-3 * std::pow(1.0025, k);  // up to ~22000 units
        const dvec3 x = v.position + ray * t;
        double w;
        const dvec2 uv = shadowUv(shadow, x, &w);
        const bool in = w > 0.0 && inRegion(x, uv);
        if (in && !ok) {
          ADD_FAILURE() << name << " slice " << i << ": culled but ray " << r << " reaches the region at t " << t;
          return;
        }
        if (in && ok) {
          anyInRegion = true;
          // On the slice's line, moving along its direction, inside [origin, origin + length].
          const dvec2 rel = uv - origin;
          const double along = glm::dot(rel, dir);
          EXPECT_LT(std::abs(rel.x * dir.y - rel.y * dir.x), 2e-4) << name << " slice " << i << " ray " << r;
          EXPECT_GE(along, previous - 1e-6) << name << " slice " << i << " ray " << r;
          EXPECT_GE(along, -2e-4) << name << " slice " << i << " ray " << r;
          EXPECT_LE(along, uvLength + 2e-4) << name << " slice " << i << " ray " << r;
          previous = along;
          if (!wasIn) {
            // Where the ray enters the region (bisection in double): it projects to the origin.
            double lo = tPrev, hi = t;
            if (k > 0) {
              for (int it = 0; it < 80; ++it) {
                const double mid = 0.5 * (lo + hi);
                double wm;
                const dvec3 xm = v.position + ray * mid;
                const dvec2 uvm = shadowUv(shadow, xm, &wm);
                ((wm > 0.0 && inRegion(xm, uvm)) ? hi : lo) = mid;
              }
            }
            const dvec2 entryUv = shadowUv(shadow, v.position + ray * hi);
            EXPECT_LT(glm::length(entryUv - origin), 2e-4)
                << name << " slice " << i << " ray " << r << " enters at t " << hi;
          }
        }
        wasIn = in;
        tPrev = t;
      }
    }
    if (ok && expectCameraOrigin) {
      EXPECT_LT(glm::length(origin - shadowUv(shadow, v.position)), 1e-5) << name << " slice " << i;
    }
    // Valid is conservative (a slice looking away from the cone may be valid although no ray
    // reaches it); culled is exact (checked above). Count the slices that do reach.
    if (ok && anyInRegion) ++*reachingSlices;
  }
}

TEST(EpipolarGeometry, ShadowSliceDirectionalMatchesBruteForceProjection) {
  const dvec2 extent(640.0, 360.0);
  for (dvec3 lightDir : {glm::normalize(dvec3(0.3, -1.0, 0.45)), glm::normalize(dvec3(-0.8, -0.3, -0.5)),
                         glm::normalize(dvec3(0.1, -0.2, 1.0))}) {
    // An orthographic light box around the scene, as the host fits it (light view z = −distance).
    const dmat4 lightView = lookAlong(-lightDir * 60.0, lightDir);
    const dmat4 shadow = glm::orthoRH_ZO(-40.0, 40.0, -40.0, 40.0, 1.0, 150.0) * lightView;
    const View v = makeView(dvec3(2.0, 3.0, 4.0), dvec3(-5.0, 0.0, -8.0), extent);
    const vec4 e = epipoleOf(v, lightDir);
    auto inMap = [](const dvec3&, const dvec2& uv) {
      return uv.x >= 0.0 && uv.x <= 1.0 && uv.y >= 0.0 && uv.y <= 1.0;
    };
    int valid = 0, reaching = 0;
    checkShadowSlices(v, shadow, e, vec3(0.0f), inMap, "directional", true, &valid, &reaching);
    EXPECT_GT(reaching, 0);
  }
}

struct Spot {
  dvec3 position, axis;
  double outerRadians;
  dmat4 shadow;
};

Spot makeSpot(dvec3 position, dvec3 axis, double outerDegrees) {
  Spot s{position, glm::normalize(axis), glm::radians(outerDegrees), dmat4(1.0)};
  // As the host stub builds it: a symmetric frustum 5° wider than the cone, clip depth [0, 1].
  const double fov = 2.0 * glm::radians(outerDegrees + 5.0);
  s.shadow = glm::perspectiveRH_ZO(fov, 1.0, 0.05, 500.0) * lookAlong(position, s.axis);
  return s;
}

TEST(EpipolarGeometry, SpotConeImageIsACircle) {
  const Spot s = makeSpot(dvec3(1.0, 9.0, -2.0), dvec3(0.2, -1.0, 0.1), 28.0);
  const vec3 cone = tyn_spot_cone_uv(mat4(s.shadow), f3(s.position), f3(s.axis), std::cos(static_cast<float>(s.outerRadians)));
  const dvec3 u = glm::normalize(glm::cross(s.axis, dvec3(0.0, 0.0, 1.0)));
  const dvec3 w = glm::cross(s.axis, u);
  for (int k = 0; k < 16; ++k) {
    const double phi = k * 2.0 * M_PI / 16.0;
    for (double dist : {0.5, 3.0, 40.0}) {
      const dvec3 onCone = s.position + dist * (s.axis + std::tan(s.outerRadians) * (std::cos(phi) * u + std::sin(phi) * w));
      const dvec2 uv = shadowUv(s.shadow, onCone);
      EXPECT_NEAR(glm::length(uv - d2(vec2(cone))), cone.z, 1e-5);
    }
  }
  EXPECT_LT(glm::length(d2(vec2(cone)) - dvec2(0.5)), 1e-6);
}

TEST(EpipolarGeometry, ShadowSliceSpotMatchesBruteForceProjection) {
  const dvec2 extent(640.0, 360.0);
  const Spot s = makeSpot(dvec3(0.0, 10.0, 0.0), dvec3(0.15, -1.0, 0.05), 30.0);
  const vec3 cone = tyn_spot_cone_uv(mat4(s.shadow), f3(s.position), f3(s.axis), std::cos(static_cast<float>(s.outerRadians)));
  const double cosOuter = std::cos(s.outerRadians);
  auto inCone = [&](const dvec3& x, const dvec2&) {
    const dvec3 d = x - s.position;
    return glm::dot(d, s.axis) >= cosOuter * glm::length(d);
  };
  struct CameraCase {
    std::string name;
    dvec3 position, target;
    bool insideCone;
  };
  const CameraCase cases[] = {
      {"camera inside the cone", {0.5, 2.0, 0.3}, {4.0, 0.0, -3.0}, true},
      {"camera inside, looking at the light", {1.0, 1.0, 1.0}, {0.0, 10.0, 0.0}, true},
      {"camera outside, in front of the light", {14.0, 1.5, 3.0}, {0.0, 0.0, 0.0}, false},
      {"camera outside, light behind it", {3.0, 9.0, 0.0}, {4.0, 8.0, 0.0}, false},
      {"camera behind the light's plane", {2.0, 16.0, -3.0}, {0.0, 0.0, 0.0}, false},
      {"camera behind the light, looking away", {-1.0, 14.0, 2.0}, {-6.0, 12.0, 9.0}, false},
  };
  for (const CameraCase& cc : cases) {
    const View v = makeView(cc.position, cc.target, extent);
    ASSERT_EQ(inCone(cc.position, dvec2(0.0)), cc.insideCone) << cc.name;
    const vec4 e = tyn_epipole(tyn_epipole_clip_local(mat4(v.viewProj), f3(s.position)));
    int valid = 0, reaching = 0;
    checkShadowSlices(v, s.shadow, e, cone, inCone, cc.name, cc.insideCone, &valid, &reaching);
    if (cc.name != "camera behind the light, looking away") {
      EXPECT_GT(reaching, 0) << cc.name;
    }
    if (cc.insideCone) {
      EXPECT_EQ(reaching, valid) << cc.name;  // from inside the cone every ray starts lit
    }
  }
}

TEST(EpipolarGeometry, ShadowSliceDegenerateCases) {
  const Spot s = makeSpot(dvec3(0.0, 10.0, 0.0), dvec3(0.0, -1.0, 0.0), 30.0);
  vec4 od;
  float len = 0.0f;
  // Camera at the light position: no epipolar plane.
  EXPECT_FALSE(tyn_slice_shadow_uv(mat4(s.shadow), f3(s.position), vec3(0.3f, -1.0f, 0.2f), vec3(0.5f, 0.5f, 0.3f), od, len));
  EXPECT_EQ(od, vec4(TYN_EPIPOLAR_INVALID_COORD));
  // Exit ray pointing straight at the light.
  EXPECT_FALSE(tyn_slice_shadow_uv(mat4(s.shadow), vec3(0.0f, 2.0f, 0.0f), vec3(0.0f, 1.0f, 0.0f), vec3(0.5f, 0.5f, 0.3f), od, len));
  // Directional: an exit ray along the light direction.
  const dvec3 lightDir(0.0, -1.0, 0.0);
  const dmat4 shadow = glm::orthoRH_ZO(-40.0, 40.0, -40.0, 40.0, 1.0, 150.0) * lookAlong(-lightDir * 60.0, lightDir);
  EXPECT_FALSE(tyn_slice_shadow_uv(mat4(shadow), vec3(1.0f, 2.0f, 3.0f), vec3(0.0f, 1.0f, 0.0f), vec3(0.0f), od, len));
  // A slice whose line misses the cone entirely.
  EXPECT_FALSE(tyn_slice_shadow_uv(mat4(s.shadow), vec3(30.0f, 2.0f, 0.0f), vec3(0.0f, 0.0f, 1.0f), vec3(0.5f, 0.5f, 0.1f), od, len));
}

}  // namespace
