#include "epipolar/slice_arc.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "epipolar/epipolar_geometry.h"

namespace tyndall {

namespace {

// Border positions tested per pixel of perimeter (at least this many in all), and how many of
// them the arc is widened by at each end: the lit stretch's true end lies between a tested
// position inside it and the next one outside.
constexpr double kTestsPerPixel = 1.0;
constexpr int kMinTests = 256;
constexpr int kGuardTests = 2;
// A gap this short (in tested positions) is not worth an arc: the whole border is kept.
constexpr int kMinGap = 8;
// Slack on the cone test's cosine (the float exit points against the double test).
constexpr double kConeSlack = 1.0e-4;

// The half-planes bounded by the line through the camera C and a spot light L (unit ℓ from C to
// L) that meet the light's cone: a view ray from C meets the cone only if its half-plane does,
// and every ray of one slice lies in one such half-plane (the slice's screen line minus the
// epipole is the image of the plane through C and L minus that line). Writing the axis as
// â = d·ℓ + r·m (m ⊥ ℓ, r = √(1 − d²)), the directions from L in the half-plane of unit normal
// direction n are cos φ·ℓ + sin φ·n, φ ∈ [0, π], whose largest cosine with â is
// √(d² + r²·(n·m)²) when n·m ≥ 0 and |d| otherwise. The half-plane meets the cone (half-angle α)
// iff that is ≥ cos α: n·m ≥ √(cos²α − d²)/r. When |d| ≥ cos α the line itself runs inside the
// cone and every half-plane meets it.
struct ConeWedge {
  bool bounded = false;
  glm::dvec3 camera{0.0};
  glm::dvec3 axis{0.0};   // ℓ
  glm::dvec3 middle{0.0}; // m
  double minCosine = -1.0;
};

ConeWedge coneWedge(const glm::dvec3& camera, const LightDesc& light) {
  ConeWedge w;
  const glm::dvec3 toLight = glm::dvec3(light.position[0], light.position[1], light.position[2]) - camera;
  const glm::dvec3 spotAxis(light.direction[0], light.direction[1], light.direction[2]);
  const double distance = glm::length(toLight);
  if (!(distance > 0.0) || !(glm::length(spotAxis) > 0.0)) return w;
  const glm::dvec3 l = toLight / distance;
  const glm::dvec3 a = glm::normalize(spotAxis);
  const double cosAlpha = std::cos(double(light.outerConeRadians));
  const double d = glm::dot(a, l);
  if (std::abs(d) >= cosAlpha) return w;
  const double r = std::sqrt(std::max(1.0 - d * d, 0.0));
  if (!(r > 0.0)) return w;
  w.bounded = true;
  w.camera = camera;
  w.axis = l;
  w.middle = (a - d * l) / r;
  w.minCosine = std::sqrt(std::max(cosAlpha * cosAlpha - d * d, 0.0)) / r - kConeSlack;
  return w;
}

bool inWedge(const ConeWedge& w, const glm::dvec3& rayDirection) {
  const glm::dvec3 n = rayDirection - glm::dot(rayDirection, w.axis) * w.axis;
  const double length = glm::length(n);
  if (!(length > 0.0)) return true;  // along the line through camera and light: every half-plane
  return glm::dot(n, w.middle) >= w.minCosine * length;
}

}  // namespace

SliceArc sliceArc(const CameraDesc& camera, const LightDesc& light, glm::vec4 epipole, glm::vec2 extent) {
  const double perimeter = gpu::tyn_border_length_pixels(extent);
  SliceArc whole;
  whole.arc = gpu::tyn_whole_border_arc(extent);

  const glm::dmat4 view = glm::dmat4(glm::make_mat4(camera.view.data()));
  const glm::dmat4 projection = glm::dmat4(glm::make_mat4(camera.projection.data()));
  const glm::dmat4 clipToWorld = glm::inverse(projection * view);
  const glm::dvec3 eye = glm::dvec3(glm::inverse(view)[3]);
  const ConeWedge wedge = light.type == LightType::Spot ? coneWedge(eye, light) : ConeWedge{};
  const bool epipoleOnScreen = gpu::tyn_epipole_on_screen(epipole, extent);
  if (!wedge.bounded && epipoleOnScreen) return whole;

  const int tests = std::max(kMinTests, static_cast<int>(std::ceil(perimeter * kTestsPerPixel)));
  const double step = perimeter / tests;
  std::vector<char> lit(tests);
  bool anyCone = false;
  bool anyScreen = false;
  int litCount = 0;
  for (int i = 0; i < tests; ++i) {
    const glm::vec2 exitPoint = gpu::tyn_border_point(static_cast<float>(i * step), extent);
    glm::vec4 ends;
    const bool onScreen = gpu::tyn_slice_end_points(epipole, exitPoint, extent, ends);
    bool inCone = true;
    if (wedge.bounded) {
      // Depth 0.5 lies between the near and the far plane for every depth convention.
      const glm::dvec4 h = clipToWorld * glm::dvec4(exitPoint.x, exitPoint.y, 0.5, 1.0);
      inCone = inWedge(wedge, glm::dvec3(h) / h.w - eye);
    }
    anyScreen |= !onScreen;
    anyCone |= onScreen && !inCone;
    lit[i] = onScreen && inCone;
    litCount += lit[i];
  }
  if (litCount == 0 || litCount == tests) return whole;

  // The longest cyclic run of unlit positions; the arc is the rest, widened by the guard.
  int bestStart = 0;
  int bestLength = 0;
  int first = 0;
  while (!lit[first]) ++first;  // a lit position: runs are found after it, cyclically
  for (int k = 1, run = 0; k <= tests; ++k) {
    const int i = (first + k) % tests;
    if (!lit[i]) {
      ++run;
      if (run > bestLength) {
        bestLength = run;
        bestStart = (i - run + 1 + tests) % tests;
      }
    } else {
      run = 0;
    }
  }
  if (bestLength - 2 * kGuardTests < kMinGap) return whole;

  SliceArc result;
  const int arcStart = (bestStart + bestLength - kGuardTests) % tests;  // first lit position − guard
  const int arcTests = tests - bestLength + 2 * kGuardTests - 1;
  result.arc = glm::vec2(static_cast<float>(arcStart * step), static_cast<float>(arcTests * step));
  result.fraction = static_cast<float>(arcTests * step / perimeter);
  result.cone = anyCone;
  result.screen = anyScreen;
  return result;
}

}  // namespace tyndall
