// The CPU analytic reference against independent brute-force computations: phase normalisation by
// quadrature, shadowed intervals by point sampling with shadow rays, the lit integral by numerical
// quadrature with brute-force visibility, and the camera ray convention.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "analytic_reference.h"
#include "tyndall_host/scene.h"

namespace tyndall::analytic {
namespace {

using host::PhaseType;
using Intervals = std::vector<std::pair<double, double>>;

const std::filesystem::path kScenesDir = TYNDALL_SCENES_DIR;
constexpr double kPi = std::numbers::pi;
constexpr double kInfinity = std::numeric_limits<double>::infinity();
const char* const kAnalyticScenes[] = {"analytic-spheres.json", "analytic-boxes.json", "analytic-mixed.json"};

host::Scene loadSample(const char* name) {
  host::SceneLoadResult result = host::loadScene(kScenesDir / name);
  EXPECT_TRUE(result.scene.has_value()) << name << ": " << result.error;
  return result.scene.value_or(host::Scene{});
}

// ---- independent brute force ------------------------------------------------------------------

// Does the ray p + u·l, u > 0, hit the object? Plain textbook intersections, written apart from the
// reference's closed-form shadow volumes.
bool shadowRayHitsPlane(const host::Object& plane, const glm::dvec3& p, const glm::dvec3& l) {
  const double denominator = glm::dot(l, plane.normal);
  if (denominator == 0.0) return false;
  return glm::dot(plane.point - p, plane.normal) / denominator > 0.0;
}

bool shadowRayHitsSphere(const host::Object& sphere, const glm::dvec3& p, const glm::dvec3& l) {
  const glm::dvec3 q = p - sphere.center;
  const double c = glm::dot(q, q) - sphere.radius * sphere.radius;
  if (c <= 0.0) return true;  // inside
  const double b = glm::dot(q, l);
  const double discriminant = b * b - c;
  return discriminant >= 0.0 && -b + std::sqrt(discriminant) > 0.0;
}

bool shadowRayHitsBox(const host::Object& box, const glm::dmat3& toLocal, const glm::dvec3& p, const glm::dvec3& l) {
  const glm::dvec3 o = toLocal * (p - box.center);
  const glm::dvec3 d = toLocal * l;
  double uMin = 0.0, uMax = kInfinity;
  for (int i = 0; i < 3; ++i) {
    if (d[i] == 0.0) {
      if (std::abs(o[i]) > box.halfExtents[i]) return false;
      continue;
    }
    const double u0 = (-box.halfExtents[i] - o[i]) / d[i];
    const double u1 = (box.halfExtents[i] - o[i]) / d[i];
    uMin = std::max(uMin, std::min(u0, u1));
    uMax = std::min(uMax, std::max(u0, u1));
  }
  return uMin <= uMax;
}

// A point is in shadow when its shadow ray towards the light hits any object.
class BruteForceShadows {
 public:
  explicit BruteForceShadows(const host::Scene& scene) : scene_(scene), toLight_(-scene.light.direction) {
    for (const host::Object& object : scene.objects) {
      toLocal_.push_back(glm::transpose(host::rotationFromDegrees(object.rotationDegrees)));
    }
  }

  bool inShadow(const glm::dvec3& p) const {
    for (std::size_t i = 0; i < scene_.objects.size(); ++i) {
      const host::Object& object = scene_.objects[i];
      const bool hit = object.type == host::ObjectType::Plane    ? shadowRayHitsPlane(object, p, toLight_)
                       : object.type == host::ObjectType::Sphere ? shadowRayHitsSphere(object, p, toLight_)
                                                                 : shadowRayHitsBox(object, toLocal_[i], p, toLight_);
      if (hit) return true;
    }
    return false;
  }

 private:
  const host::Scene& scene_;
  glm::dvec3 toLight_;
  std::vector<glm::dmat3> toLocal_;
};

bool insideIntervals(const Intervals& intervals, double t) {
  return std::any_of(intervals.begin(), intervals.end(), [t](const auto& i) { return t >= i.first && t <= i.second; });
}

double distanceToEndpoint(const Intervals& intervals, double t) {
  double nearest = kInfinity;
  for (const auto& [lo, hi] : intervals) nearest = std::min({nearest, std::abs(t - lo), std::abs(t - hi)});
  return nearest;
}

// ∫ V(t)·exp(−σ t) dt over [0, s] per channel. V is sampled on a grid of `cells`; where it changes
// inside a cell the transition is located by bisection, and exp is integrated by Simpson's rule on
// each constant piece (a numerical integral, independent of the reference's closed form).
glm::dvec3 litIntegralByQuadrature(const host::Scene& scene, const glm::dvec3& o, const glm::dvec3& d, double s,
                                   const glm::dvec3& sigmaT, int cells) {
  const BruteForceShadows shadows(scene);
  const auto visible = [&](double t) { return !shadows.inShadow(o + t * d); };
  const auto simpson = [&](double a, double b) {
    glm::dvec3 sum(0.0);
    constexpr int kPanels = 8;
    const double h = (b - a) / kPanels;
    for (int i = 0; i <= kPanels; ++i) {
      const double weight = (i == 0 || i == kPanels) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
      sum += weight * glm::exp(-sigmaT * (a + i * h));
    }
    return sum * (h / 3.0);
  };
  glm::dvec3 total(0.0);
  const double step = s / cells;
  for (int cell = 0; cell < cells; ++cell) {
    const double a = cell * step, b = cell == cells - 1 ? s : (cell + 1) * step;
    const bool visibleA = visible(a), visibleB = visible(b);
    if (visibleA == visibleB) {
      if (visibleA) total += simpson(a, b);
      continue;
    }
    double lo = a, hi = b;  // visible(lo) == visibleA, visible(hi) == visibleB
    for (int i = 0; i < 60; ++i) {
      const double mid = 0.5 * (lo + hi);
      (visible(mid) == visibleA ? lo : hi) = mid;
    }
    total += visibleA ? simpson(a, lo) : simpson(hi, b);
  }
  return total;
}

glm::dvec3 inScatteringByQuadrature(const host::Scene& scene, const glm::dvec3& o, const glm::dvec3& d, double s,
                                    int cells) {
  const glm::dvec3 lit = litIntegralByQuadrature(scene, o, d, s, extinction(scene), cells);
  const double cosTheta = glm::dot(d, -scene.light.direction);
  glm::dvec3 coefficient(0.0);
  for (const host::MediumComponent& c : scene.medium) coefficient += c.scattering * phase(c.phase, c.g, cosTheta);
  return coefficient * scene.light.color * scene.light.intensity * lit;
}

struct TestRay {
  glm::dvec3 origin;
  glm::dvec3 dir;
  double length;
};

glm::dvec3 randomDirection(std::mt19937& rng) {
  std::normal_distribution<double> normal;
  glm::dvec3 v;
  do {
    v = {normal(rng), normal(rng), normal(rng)};
  } while (glm::length(v) < 1e-6);
  return glm::normalize(v);
}

// Camera rays through random pixels, random rays from inside the scene's region, and degenerate
// directions: along the light, against it, along the world axes.
std::vector<TestRay> testRays(const host::Scene& scene, unsigned seed, int cameraRays, int freeRays) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::uint32_t> px(0, 319), py(0, 179);
  std::uniform_real_distribution<double> x(-10, 10), y(0.2, 10), z(-15, 10);
  std::vector<TestRay> rays;
  for (int i = 0; i < cameraRays; ++i) {
    const glm::dvec3 dir = cameraRayDirection(scene.camera, px(rng), py(rng), 320, 180);
    rays.push_back({scene.camera.position, dir, viewRayLength(scene, dir)});
  }
  for (int i = 0; i < freeRays; ++i) rays.push_back({{x(rng), y(rng), z(rng)}, randomDirection(rng), 40.0});
  const glm::dvec3 l = -scene.light.direction;
  for (const glm::dvec3& dir : {l, -l, glm::dvec3(1, 0, 0), glm::dvec3(0, 0, -1), glm::dvec3(0, -1, 0)}) {
    rays.push_back({{x(rng), y(rng), z(rng)}, dir, 40.0});
  }
  return rays;
}

// ---- phase functions --------------------------------------------------------------------------

// 2π ∫_{−1}^{1} f(μ) dμ by composite Simpson; fine enough for the g = ±0.9 peaks (width ~ (1−|g|)²).
template <typename F>
double sphereIntegral(F&& f) {
  constexpr int kPanels = 200000;
  const double h = 2.0 / kPanels;
  double sum = 0.0;
  for (int i = 0; i <= kPanels; ++i) {
    const double weight = (i == 0 || i == kPanels) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
    sum += weight * f(-1.0 + i * h);
  }
  return 2.0 * kPi * sum * h / 3.0;
}

TEST(Phase, EveryTypeIsNormalisedOverTheSphere) {
  for (PhaseType type : {PhaseType::Isotropic, PhaseType::Rayleigh, PhaseType::HenyeyGreenstein, PhaseType::CornetteShanks}) {
    for (double g : {-0.9, -0.5, 0.0, 0.3, 0.9}) {
      SCOPED_TRACE(testing::Message() << "type " << static_cast<int>(type) << ", g " << g);
      EXPECT_NEAR(sphereIntegral([&](double mu) { return phase(type, g, mu); }), 1.0, 1e-8);
    }
  }
}

TEST(Phase, MeanCosinesMatchTheirClosedForms) {
  // Henyey–Greenstein's mean cosine is g by construction; Cornette–Shanks's is 3g(4 + g²)/(5(2 + g²)).
  for (double g : {-0.9, -0.4, 0.2, 0.75, 0.9}) {
    SCOPED_TRACE(g);
    EXPECT_NEAR(sphereIntegral([&](double mu) { return mu * phase(PhaseType::HenyeyGreenstein, g, mu); }), g, 1e-8);
    EXPECT_NEAR(sphereIntegral([&](double mu) { return mu * phase(PhaseType::CornetteShanks, g, mu); }),
                3.0 * g * (4.0 + g * g) / (5.0 * (2.0 + g * g)), 1e-8);
  }
  EXPECT_NEAR(sphereIntegral([](double mu) { return mu * phase(PhaseType::Rayleigh, 0.0, mu); }), 0.0, 1e-12);
}

TEST(Phase, ReducesToTheSimplerLobes) {
  for (double mu : {-1.0, -0.6, 0.0, 0.3, 1.0}) {
    SCOPED_TRACE(mu);
    EXPECT_DOUBLE_EQ(phase(PhaseType::Isotropic, 0.7, mu), 1.0 / (4.0 * kPi));  // g is ignored
    EXPECT_NEAR(phase(PhaseType::HenyeyGreenstein, 0.0, mu), 1.0 / (4.0 * kPi), 1e-15);
    // Cornette–Shanks at g = 0: 3/(8π·2)·(1 + μ²) = Rayleigh.
    EXPECT_NEAR(phase(PhaseType::CornetteShanks, 0.0, mu), 3.0 / (16.0 * kPi) * (1.0 + mu * mu), 1e-15);
    EXPECT_NEAR(phase(PhaseType::Rayleigh, 0.0, mu), 3.0 / (16.0 * kPi) * (1.0 + mu * mu), 1e-15);
    // g → −g mirrors the lobe.
    EXPECT_NEAR(phase(PhaseType::HenyeyGreenstein, 0.6, mu), phase(PhaseType::HenyeyGreenstein, -0.6, -mu), 1e-14);
  }
  // Forward peak (looking into the light) of Henyey–Greenstein: (1 + g)/(4π(1 − g)²).
  const double g = 0.8;
  EXPECT_NEAR(phase(PhaseType::HenyeyGreenstein, g, 1.0), (1.0 + g) / (4.0 * kPi * (1.0 - g) * (1.0 - g)), 1e-12);
  EXPECT_GT(phase(PhaseType::CornetteShanks, g, 1.0), phase(PhaseType::CornetteShanks, g, -1.0));
}

// ---- camera rays ------------------------------------------------------------------------------

host::Camera testCamera() {
  host::Camera camera;
  camera.position = {1, 2, 3};
  camera.target = {-2, 3, -5};
  camera.up = {0, 1, 0};
  camera.fovYDegrees = 50;
  return camera;
}

TEST(CameraRays, CentrePixelOfAnOddImageLooksAtTheTarget) {
  const host::Camera camera = testCamera();
  const glm::dvec3 forward = glm::normalize(camera.target - camera.position);
  for (auto [w, h] : {std::pair<std::uint32_t, std::uint32_t>{5, 3}, {161, 91}, {1, 1}}) {
    const glm::dvec3 dir = cameraRayDirection(camera, w / 2, h / 2, w, h);
    EXPECT_NEAR(glm::length(dir - forward), 0.0, 1e-14) << w << "x" << h;
  }
}

TEST(CameraRays, RowZeroLooksUpColumnZeroLooksLeftAtTheHalfPixelAngles) {
  const host::Camera camera = testCamera();
  const glm::dvec3 forward = glm::normalize(camera.target - camera.position);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, camera.up));
  const glm::dvec3 up = glm::cross(right, forward);
  const std::uint32_t w = 9, h = 5;
  const double tanHalf = std::tan(glm::radians(camera.fovYDegrees) / 2.0);
  const glm::dvec3 top = cameraRayDirection(camera, w / 2, 0, w, h);
  EXPECT_GT(glm::dot(top, up), 0.0);
  // Pixel centres at half-integers: row 0's centre is half a pixel below the top edge.
  EXPECT_NEAR(glm::dot(top, up) / glm::dot(top, forward), (1.0 - 1.0 / h) * tanHalf, 1e-14);
  EXPECT_NEAR(glm::dot(top, right), 0.0, 1e-14);
  const glm::dvec3 left = cameraRayDirection(camera, 0, h / 2, w, h);
  EXPECT_LT(glm::dot(left, right), 0.0);
  EXPECT_NEAR(glm::dot(left, right) / glm::dot(left, forward), -(1.0 - 1.0 / w) * tanHalf * w / h, 1e-14);
  const glm::dvec3 bottomRight = cameraRayDirection(camera, w - 1, h - 1, w, h);
  EXPECT_LT(glm::dot(bottomRight, up), 0.0);
  EXPECT_GT(glm::dot(bottomRight, right), 0.0);
  EXPECT_NEAR(glm::length(bottomRight), 1.0, 1e-15);
}

// ---- first surface and ray length -------------------------------------------------------------

host::Scene emptyScene() {
  host::Scene scene;
  scene.light.direction = {0, -1, 0};
  scene.medium = {host::MediumComponent{glm::dvec3(0.05), glm::dvec3(0.01), PhaseType::Isotropic, 0.0}};
  return scene;
}

host::Object sphereAt(glm::dvec3 centre, double radius) {
  host::Object o;
  o.type = host::ObjectType::Sphere;
  o.center = centre;
  o.radius = radius;
  return o;
}

host::Object boxAt(glm::dvec3 centre, glm::dvec3 halfExtents, glm::dvec3 rotation = glm::dvec3(0.0)) {
  host::Object o;
  o.type = host::ObjectType::Box;
  o.center = centre;
  o.halfExtents = halfExtents;
  o.rotationDegrees = rotation;
  return o;
}

host::Object planeAt(glm::dvec3 point, glm::dvec3 normal) {
  host::Object o;
  o.type = host::ObjectType::Plane;
  o.point = point;
  o.normal = glm::normalize(normal);
  return o;
}

TEST(FirstSurface, KnownDistances) {
  host::Scene scene = emptyScene();
  const glm::dvec3 origin(0.0), ahead(0, 0, -1);
  EXPECT_EQ(firstSurfaceDistance(scene, origin, ahead), kInfinity);
  scene.objects = {sphereAt({0, 0, -10}, 2)};
  EXPECT_NEAR(firstSurfaceDistance(scene, origin, ahead), 8.0, 1e-12);
  EXPECT_NEAR(firstSurfaceDistance(scene, {0, 0, -10}, ahead), 2.0, 1e-12);  // from inside: the exit
  EXPECT_EQ(firstSurfaceDistance(scene, origin, {0, 0, 1}), kInfinity);      // behind the ray
  scene.objects = {boxAt({0, 0, -10}, {1, 1, 1}, {0, 45, 0})};
  EXPECT_NEAR(firstSurfaceDistance(scene, origin, ahead), 10.0 - std::sqrt(2.0), 1e-12);  // an edge faces us
  EXPECT_EQ(firstSurfaceDistance(scene, {0, 1.5, 0}, ahead), kInfinity);  // parallel to the top face, above it
  scene.objects = {planeAt({0, -1, 0}, {0, 1, 0}), sphereAt({0, 0, -10}, 2)};
  EXPECT_NEAR(firstSurfaceDistance(scene, origin, glm::normalize(glm::dvec3(0, -1, -1))), std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(firstSurfaceDistance(scene, origin, ahead), 8.0, 1e-12);  // nearest of several
}

TEST(FirstSurface, RaysWithoutASurfaceOrBeyondFarEndAtTheFarPlane) {
  host::Scene scene = emptyScene();
  scene.camera = testCamera();
  scene.camera.farPlane = 30.0;
  const glm::dvec3 forward = glm::normalize(scene.camera.target - scene.camera.position);
  const glm::dvec3 dir = cameraRayDirection(scene.camera, 0, 0, 16, 9);
  EXPECT_NEAR(viewRayLength(scene, dir), 30.0 / glm::dot(dir, forward), 1e-12);
  scene.objects = {sphereAt(scene.camera.position + 20.0 * forward, 1.0)};
  EXPECT_NEAR(viewRayLength(scene, forward), 19.0, 1e-12);
  scene.objects = {sphereAt(scene.camera.position + 40.0 * forward, 1.0)};
  EXPECT_NEAR(viewRayLength(scene, forward), 30.0, 1e-12);
}

// ---- shadowed intervals -----------------------------------------------------------------------

void expectIntervals(const Intervals& actual, const Intervals& expected) {
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t i = 0; i < actual.size(); ++i) {
    EXPECT_NEAR(actual[i].first, expected[i].first, 1e-12);
    EXPECT_NEAR(actual[i].second, expected[i].second, 1e-12);
  }
}

TEST(ShadowedIntervals, DegenerateDirectionsHaveKnownAnswers) {
  host::Scene scene = emptyScene();  // light travels −y: l = +y
  scene.objects = {boxAt({0, 0, 0}, {1, 1, 1})};
  const double r2 = std::sqrt(2.0);
  // View ray along l, under the box: shadowed until it leaves the box's top face.
  expectIntervals(shadowedIntervals(scene, {0, -5, 0}, {0, 1, 0}, 10), {{0, 6}});
  // View ray against l, from above: shadowed from the top face on.
  expectIntervals(shadowedIntervals(scene, {0, 5, 0}, {0, -1, 0}, 10), {{4, 10}});
  // Parallel to two box faces, crossing below the box.
  expectIntervals(shadowedIntervals(scene, {-5, -3, 0}, {1, 0, 0}, 10), {{4, 6}});
  expectIntervals(shadowedIntervals(scene, {-5, 1.5, 0}, {1, 0, 0}, 10), {});  // above it: lit
  scene.objects = {boxAt({0, 0, 0}, {1, 1, 1}, {0, 45, 0})};  // a diamond footprint
  expectIntervals(shadowedIntervals(scene, {-5, -3, 0}, {1, 0, 0}, 10), {{5 - r2, 5 + r2}});

  scene.objects = {sphereAt({0, 0, 0}, 1)};
  expectIntervals(shadowedIntervals(scene, {0.5, -5, 0}, {0, 1, 0}, 10), {{0, 5 + std::sqrt(0.75)}});
  expectIntervals(shadowedIntervals(scene, {2, -5, 0}, {0, 1, 0}, 10), {});
  expectIntervals(shadowedIntervals(scene, {-5, -3, 0.6}, {1, 0, 0}, 10), {{5 - 0.8, 5 + 0.8}});  // the cylinder

  scene.objects = {planeAt({0, 0, 0}, {0, 1, 0})};
  expectIntervals(shadowedIntervals(scene, {0, 5, 0}, {0, -1, 0}, 10), {{5, 10}});  // below the ground
  expectIntervals(shadowedIntervals(scene, {0, 5, 0}, {1, 0, 0}, 10), {});          // parallel, above it
  scene.objects = {planeAt({0, 0, 0}, {1, 0, 0})};  // parallel to the light: shadows nothing
  expectIntervals(shadowedIntervals(scene, {-5, 5, 0}, glm::normalize(glm::dvec3(1, -1, 0)), 20), {});

  // Overlapping shadows merge; the result is clipped to [0, tMax].
  scene.objects = {boxAt({0, 3, 0}, {1, 1, 1}), sphereAt({1.5, 3, 0}, 1)};
  expectIntervals(shadowedIntervals(scene, {-5, 0, 0}, {1, 0, 0}, 6), {{4, 6}});
}

TEST(ShadowedIntervals, MatchBruteForcePointSamplingInEveryAnalyticScene) {
  for (const char* name : kAnalyticScenes) {
    SCOPED_TRACE(name);
    const host::Scene scene = loadSample(name);
    const BruteForceShadows bruteForce(scene);
    int shadowedSamples = 0, litSamples = 0;
    for (const TestRay& ray : testRays(scene, 7, 60, 60)) {
      const Intervals intervals = shadowedIntervals(scene, ray.origin, ray.dir, ray.length);
      for (std::size_t i = 0; i < intervals.size(); ++i) {
        EXPECT_LT(intervals[i].first, intervals[i].second);
        EXPECT_GE(intervals[i].first, 0.0);
        EXPECT_LE(intervals[i].second, ray.length);
        if (i > 0) {
          EXPECT_GT(intervals[i].first, intervals[i - 1].second);  // merged and sorted
        }
      }
      constexpr int kSamples = 2000;
      for (int k = 0; k < kSamples; ++k) {
        const double t = ray.length * (k + 0.5) / kSamples;
        if (distanceToEndpoint(intervals, t) < 1e-7) continue;  // on a shadow boundary
        const bool shadowed = bruteForce.inShadow(ray.origin + t * ray.dir);
        ASSERT_EQ(insideIntervals(intervals, t), shadowed)
            << "t = " << t << " on the ray from (" << ray.origin.x << ", " << ray.origin.y << ", " << ray.origin.z
            << ") along (" << ray.dir.x << ", " << ray.dir.y << ", " << ray.dir.z << ")";
        (shadowed ? shadowedSamples : litSamples) += 1;
      }
    }
    // The test means something only if both cases occur often.
    EXPECT_GT(shadowedSamples, 10000);
    EXPECT_GT(litSamples, 10000);
  }
}

// ---- the lit integral -------------------------------------------------------------------------

TEST(InScattering, MatchesQuadratureWithBruteForceVisibility) {
  for (const char* name : kAnalyticScenes) {
    SCOPED_TRACE(name);
    const host::Scene scene = loadSample(name);
    for (const TestRay& ray : testRays(scene, 11, 12, 12)) {
      const glm::dvec3 reference = inScattering(scene, ray.origin, ray.dir, ray.length);
      const glm::dvec3 quadrature = inScatteringByQuadrature(scene, ray.origin, ray.dir, ray.length, 2000);
      // Relative to the unshadowed value, so that rays almost entirely in shadow are judged fairly.
      host::Scene unshadowed = scene;
      unshadowed.objects.clear();
      const glm::dvec3 unoccluded = inScattering(unshadowed, ray.origin, ray.dir, ray.length);
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(reference[c], quadrature[c], 1e-6 * unoccluded[c])
            << "channel " << c << " along (" << ray.dir.x << ", " << ray.dir.y << ", " << ray.dir.z << ")";
        EXPECT_GE(reference[c], 0.0);
        EXPECT_LE(reference[c], unoccluded[c] * (1.0 + 1e-12));
      }
    }
  }
}

TEST(InScattering, AttenuatedLengthIsStableAsExtinctionVanishes) {
  EXPECT_EQ(attenuatedLength(2.0, 7.5, 0.0), 5.5);  // exactly
  EXPECT_NEAR(attenuatedLength(2.0, 7.5, 1e-9), 5.5, 5.5 * 1e-8);
  EXPECT_NEAR(attenuatedLength(2.0, 7.5, 1e-9) / attenuatedLength(2.0, 7.5, 0.0), 1.0, 1e-8);
  EXPECT_LT(attenuatedLength(2.0, 7.5, 1e-9), 5.5);
  EXPECT_NEAR(attenuatedLength(0.0, 1000.0, 50.0), 1.0 / 50.0, 1e-15);
  EXPECT_EQ(attenuatedLength(30.0, 100.0, 50.0), 0.0);  // exp(−1500) underflows to 0, not NaN
  EXPECT_EQ(attenuatedLength(5.0, 5.0, 0.3), 0.0);
  EXPECT_EQ(attenuatedLength(6.0, 5.0, 0.3), 0.0);
  // Against the closed form where it is well conditioned.
  EXPECT_NEAR(attenuatedLength(1.0, 4.0, 0.5), (std::exp(-0.5) - std::exp(-2.0)) / 0.5, 1e-15);
}

TEST(InScattering, ZeroExtinctionLimitGivesTheLitLength) {
  // σ_s = 1e-9, σ_a = 0: L_in/(σ_s·p·E) tends to the lit length s − Σ shadowed lengths.
  for (double sigma : {1e-9, 0.0}) {
    host::Scene scene = loadSample("analytic-spheres.json");
    scene.medium = {host::MediumComponent{glm::dvec3(sigma), glm::dvec3(0.0), PhaseType::Isotropic, 0.0}};
    // A ray from the camera through the middle row that is partly in shadow.
    glm::dvec3 dir(0.0);
    double s = 0.0;
    Intervals shadows;
    for (std::uint32_t x = 0; x < 320 && (shadows.empty() || shadows.front().first == 0.0); ++x) {
      dir = cameraRayDirection(scene.camera, x, 90, 320, 180);
      s = viewRayLength(scene, dir);
      shadows = shadowedIntervals(scene, scene.camera.position, dir, s);
    }
    ASSERT_FALSE(shadows.empty());
    ASSERT_GT(shadows.front().first, 0.0);
    double litLength = s;
    for (const auto& [lo, hi] : shadows) litLength -= hi - lo;
    const glm::dvec3 l = inScattering(scene, scene.camera.position, dir, s);
    const double scale = sigma / (4.0 * kPi) * scene.light.intensity;
    if (sigma == 0.0) {
      EXPECT_EQ(l, glm::dvec3(0.0));
    } else {
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(l[c] / (scale * scene.light.color[c]), litLength, 1e-7 * litLength);
    }
  }
}

// ---- translucent occluders --------------------------------------------------------------------

// Whether p lies inside a sphere or a box.
bool insideObject(const host::Object& object, const glm::dvec3& p) {
  if (object.type == host::ObjectType::Sphere) return glm::length(p - object.center) < object.radius;
  const glm::dvec3 local = glm::transpose(host::rotationFromDegrees(object.rotationDegrees)) * (p - object.center);
  return glm::all(glm::lessThan(glm::abs(local), object.halfExtents));
}

// The light's transmittance at p, along its own light ray: 0 when an opaque object is hit; per
// translucent object, (1 − α) for each surface crossed, one from inside, two when the ray hits it
// from outside (found with firstSurfaceDistance on the object alone, made opaque).
double lightTransmittance(const host::Scene& scene, const glm::dvec3& p) {
  const glm::dvec3 toLight = -glm::normalize(scene.light.direction);
  double transmittance = 1.0;
  for (const host::Object& object : scene.objects) {
    host::Scene single = scene;
    single.objects = {object};
    single.objects[0].opacity = 1.0;
    const bool hit = std::isfinite(firstSurfaceDistance(single, p, toLight));
    if (!object.translucent()) {
      if (hit) return 0.0;
      continue;
    }
    const int crossings = insideObject(object, p) ? 1 : hit ? 2 : 0;
    transmittance *= std::pow(1.0 - object.opacity, crossings);
  }
  return transmittance;
}

// The exact translucent integral against midpoint quadrature of the light's transmittance at each
// point (a different construction: light rays, not intervals along the view ray), on camera rays
// of analytic-glass.json: stacked panes, a ball and a box, some rays passing through them.
TEST(InScattering, TranslucentOccludersMatchQuadratureAlongTheLightRays) {
  const host::Scene scene = loadSample("analytic-glass.json");
  host::Scene unshadowed = scene;
  unshadowed.objects.clear();
  const glm::dvec3 sigmaT = extinction(scene);
  int partlyTranslucent = 0;
  for (std::uint32_t y = 0; y < 9; ++y) {
    for (std::uint32_t x = 0; x < 16; ++x) {
      const glm::dvec3 dir = cameraRayDirection(scene.camera, x, y, 16, 9);
      const double s = viewRayLength(scene, dir);
      const glm::dvec3 exact = inScattering(scene, scene.camera.position, dir, s);
      const glm::dvec3 unoccluded = inScattering(unshadowed, scene.camera.position, dir, s);
      constexpr int kSteps = 4000;
      const double h = s / kSteps;
      glm::dvec3 sum(0.0);
      bool translucentSeen = false;
      for (int i = 0; i < kSteps; ++i) {
        const double t = (i + 0.5) * h;
        const double transmittance = lightTransmittance(scene, scene.camera.position + t * dir);
        translucentSeen = translucentSeen || (transmittance > 0.0 && transmittance < 1.0);
        sum += transmittance * glm::exp(-sigmaT * t) * h;
      }
      partlyTranslucent += translucentSeen ? 1 : 0;
      for (int c = 0; c < 3; ++c) {
        // The unshadowed value per unit of ∫ e^{−σ_t t} dt turns the quadrature into radiance.
        const double quadrature = sum[c] * unoccluded[c] / attenuatedLength(0.0, s, sigmaT[c]);
        EXPECT_NEAR(exact[c], quadrature, 2e-3 * unoccluded[c]) << "pixel (" << x << ", " << y << ") channel " << c;
      }
    }
  }
  EXPECT_GT(partlyTranslucent, 20) << "enough rays must pass through translucent shadows";
}

TEST(InScattering, TranslucentObjectsAreNotInTheDepthBuffer) {
  host::Scene scene = loadSample("analytic-glass.json");
  // A ray from the camera straight through the smoke ball: its surface is no hit.
  const host::Object& ball = scene.objects[7];
  ASSERT_EQ(ball.type, host::ObjectType::Sphere);
  const glm::dvec3 dir = glm::normalize(ball.center - scene.camera.position);
  const double through = firstSurfaceDistance(scene, scene.camera.position, dir);
  scene.objects[7].opacity = 1.0;
  const double opaque = firstSurfaceDistance(scene, scene.camera.position, dir);
  EXPECT_NEAR(opaque, glm::length(ball.center - scene.camera.position) - ball.radius, 1e-9);
  EXPECT_GT(through, opaque + 2.0 * ball.radius - 1e-9);
}

// ---- whole images -----------------------------------------------------------------------------

TEST(RenderAnalytic, PixelsAreThePerRayQueries) {
  const host::Scene scene = loadSample("analytic-mixed.json");
  RgbImage scattering, transmittance;
  std::string error;
  ASSERT_TRUE(renderAnalytic(scene, 33, 19, scattering, transmittance, error)) << error;
  ASSERT_EQ(scattering.rgb.size(), 33u * 19u * 3u);
  ASSERT_EQ(transmittance.width, 33u);
  const glm::dvec3 sigmaT = extinction(scene);
  for (auto [x, y] : {std::pair<std::uint32_t, std::uint32_t>{0, 0}, {16, 9}, {32, 18}, {5, 14}}) {
    const glm::dvec3 dir = cameraRayDirection(scene.camera, x, y, 33, 19);
    const double s = viewRayLength(scene, dir);
    const glm::dvec3 expected = inScattering(scene, scene.camera.position, dir, s);
    for (int c = 0; c < 3; ++c) {
      EXPECT_DOUBLE_EQ(scattering.at(x, y)[c], expected[c]);
      EXPECT_DOUBLE_EQ(transmittance.at(x, y)[c], std::exp(-sigmaT[c] * s));
    }
  }
  // Row 0 looks at the sky: its transmittance is that of the far plane.
  const glm::dvec3 top = cameraRayDirection(scene.camera, 16, 0, 33, 19);
  const double farLength = scene.camera.farPlane / glm::dot(top, glm::normalize(scene.camera.target - scene.camera.position));
  EXPECT_NEAR(transmittance.at(16, 0).r, std::exp(-sigmaT.r * farLength), 1e-15);
}

TEST(RenderAnalytic, RejectsUnsupportedScenes) {
  RgbImage scattering, transmittance;
  std::string error;
  EXPECT_FALSE(renderAnalytic(loadSample("spot-lamp.json"), 16, 9, scattering, transmittance, error));
  EXPECT_NE(error.find("directional"), std::string::npos) << error;
  EXPECT_FALSE(renderAnalytic(loadSample("gltf-tetrahedron.json"), 16, 9, scattering, transmittance, error));
  EXPECT_NE(error.find("glTF"), std::string::npos) << error;
  // A second light, even a directional one, would be ignored: refused instead.
  host::Scene twoSuns = loadSample("analytic-spheres.json");
  twoSuns.additionalLights.push_back(twoSuns.light);
  error.clear();
  EXPECT_FALSE(renderAnalytic(twoSuns, 16, 9, scattering, transmittance, error));
  EXPECT_NE(error.find("one light"), std::string::npos) << error;
  EXPECT_FALSE(renderAnalytic(loadSample("analytic-spheres.json"), 0, 9, scattering, transmittance, error));
  EXPECT_FALSE(error.empty());
}

// The oracle runs in CI on 2 cores: well under a second for 320×180 (about 0.05 s measured in a
// Release build); unoptimised and sanitizer builds get a loose bound.
#ifdef NDEBUG
constexpr double kRenderBudgetSeconds = 1.0;
#else
constexpr double kRenderBudgetSeconds = 30.0;
#endif

TEST(RenderAnalytic, AnalyticScenesShowShaftsAndRenderQuickly) {
  for (const char* name : kAnalyticScenes) {
    SCOPED_TRACE(name);
    const host::Scene scene = loadSample(name);
    RgbImage scattering, transmittance;
    std::string error;
    const auto start = std::chrono::steady_clock::now();
    ASSERT_TRUE(renderAnalytic(scene, 320, 180, scattering, transmittance, error)) << error;
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_LT(seconds, kRenderBudgetSeconds);
    // Light shafts: many camera rays are partly shadowed by a finite object, and not all pixels are
    // alike (the test scenes would be useless otherwise).
    host::Scene withoutGround = scene;
    std::erase_if(withoutGround.objects, [](const host::Object& o) { return o.type == host::ObjectType::Plane; });
    int partlyShadowed = 0;
    for (std::uint32_t y = 0; y < 180; y += 4) {
      for (std::uint32_t x = 0; x < 320; x += 4) {
        const glm::dvec3 dir = cameraRayDirection(scene.camera, x, y, 320, 180);
        const double s = viewRayLength(scene, dir);
        const Intervals shadows = shadowedIntervals(withoutGround, scene.camera.position, dir, s);
        double shadowed = 0.0;
        for (const auto& [lo, hi] : shadows) shadowed += hi - lo;
        if (shadowed > 0.05 * s && shadowed < 0.95 * s) ++partlyShadowed;
      }
    }
    EXPECT_GT(partlyShadowed, 80 * 45 / 10) << "fewer than 10% of the rays cross a shaft";
    const auto [minIt, maxIt] = std::minmax_element(scattering.rgb.begin(), scattering.rgb.end());
    EXPECT_GT(*maxIt, 2.0 * *minIt);
  }
}

}  // namespace
}  // namespace tyndall::analytic
