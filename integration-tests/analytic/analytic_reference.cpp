// The CPU analytic reference (see analytic_reference.h).
//
// Shadows in closed form: a point p is in shadow when the ray p + u·l (l towards the light, u > 0)
// hits an object. For a convex object K the shadowed set S(K) = {p : ∃u ≥ 0, p + u·l ∈ K} is convex
// (the Minkowski sum of K and a half-line), so it meets a view line in one interval; the shadowed
// part of a ray is the union of one interval per object.
//
// A translucent object of opacity α lets (1 − α) through each surface the light ray crosses: from a
// point of S(K) outside K two surfaces, from inside K one. Along a view line the light's
// transmittance is therefore piecewise constant, changing only at the ends of the intervals
// S(K) and K of each translucent object.
#include "analytic_reference.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace tyndall::analytic {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

struct Interval {
  double lo = -kInfinity;
  double hi = kInfinity;
  bool empty() const { return !(lo < hi); }  // single points are measure zero: treated as empty
};

constexpr Interval kEmpty{kInfinity, -kInfinity};

// Intersects `interval` with the half-line {t : alpha·t ≤ beta}. Exactly parallel constraints
// (alpha = 0) keep everything or nothing; nearly parallel ones give huge but correct bounds.
void clipHalfLine(Interval& interval, double alpha, double beta) {
  if (alpha > 0.0) {
    interval.hi = std::min(interval.hi, beta / alpha);
  } else if (alpha < 0.0) {
    interval.lo = std::max(interval.lo, beta / alpha);
  } else if (beta < 0.0) {
    interval = kEmpty;
  }
}

// {t : a·t² + 2b·t + c ≤ 0} for a ≥ 0, with the cancellation-free form of the quadratic roots.
Interval quadraticNonPositive(double a, double b, double c) {
  if (a <= 0.0) {
    Interval all;
    clipHalfLine(all, 2.0 * b, -c);
    return all;
  }
  const double discriminant = b * b - a * c;
  if (discriminant < 0.0) return kEmpty;
  const double q = -(b + std::copysign(std::sqrt(discriminant), b));
  if (q == 0.0) return kEmpty;  // b = c = 0: a double root, a single point
  const double t0 = q / a, t1 = c / q;
  return {std::min(t0, t1), std::max(t0, t1)};
}

Interval hull(const Interval& x, const Interval& y) {
  if (x.empty()) return y;
  if (y.empty()) return x;
  return {std::min(x.lo, y.lo), std::max(x.hi, y.hi)};
}

// An object with what the per-ray queries need resolved once (rotations, normalised vectors).
struct PreparedObject {
  host::ObjectType type = host::ObjectType::Box;
  glm::dvec3 centre{0.0};       // box and sphere centre; a point on a plane
  glm::dvec3 normal{0.0};       // plane
  glm::dvec3 halfExtents{0.0};  // box
  glm::dmat3 worldToLocal{1.0}; // box: Rᵀ
  double radius = 0.0;          // sphere
  double opacity = 1.0;         // below 1: translucent
};

PreparedObject prepare(const host::Object& object) {
  PreparedObject prepared;
  prepared.type = object.type;
  prepared.centre = object.type == host::ObjectType::Plane ? object.point : object.center;
  prepared.normal = object.type == host::ObjectType::Plane ? glm::normalize(object.normal) : glm::dvec3(0.0);
  prepared.halfExtents = object.halfExtents;
  prepared.worldToLocal = glm::transpose(host::rotationFromDegrees(object.rotationDegrees));
  prepared.radius = object.radius;
  prepared.opacity = object.opacity;
  return prepared;
}

// ---- first surface ----------------------------------------------------------------------------

double planeHit(const PreparedObject& plane, const glm::dvec3& o, const glm::dvec3& d) {
  const double approach = glm::dot(d, plane.normal);
  if (approach == 0.0) return kInfinity;
  const double t = glm::dot(plane.centre - o, plane.normal) / approach;
  return t > 0.0 ? t : kInfinity;
}

// The line o + t·d inside a sphere or a box: an interval of t (possibly empty).
Interval sphereChord(const PreparedObject& sphere, const glm::dvec3& o, const glm::dvec3& d) {
  const glm::dvec3 q = o - sphere.centre;
  return quadraticNonPositive(glm::dot(d, d), glm::dot(q, d), glm::dot(q, q) - sphere.radius * sphere.radius);
}

Interval boxChord(const PreparedObject& box, const glm::dvec3& o, const glm::dvec3& d) {
  const glm::dvec3 localOrigin = box.worldToLocal * (o - box.centre);
  const glm::dvec3 localDir = box.worldToLocal * d;
  Interval inside;
  for (int i = 0; i < 3; ++i) {
    // The slab −h ≤ o_i + t·d_i ≤ h as two half-lines.
    clipHalfLine(inside, localDir[i], box.halfExtents[i] - localOrigin[i]);
    clipHalfLine(inside, -localDir[i], box.halfExtents[i] + localOrigin[i]);
  }
  return inside.lo > inside.hi ? kEmpty : inside;
}

Interval objectChord(const PreparedObject& object, const glm::dvec3& o, const glm::dvec3& d) {
  switch (object.type) {
    case host::ObjectType::Sphere: return sphereChord(object, o, d);
    case host::ObjectType::Box: return boxChord(object, o, d);
    case host::ObjectType::Plane:
    case host::ObjectType::Gltf: break;
  }
  return kEmpty;
}

// The first crossing of a chord's surface with t > 0.
double chordHit(const Interval& chord) {
  if (chord.lo > chord.hi) return kInfinity;
  if (chord.lo > 0.0) return chord.lo;
  return chord.hi > 0.0 ? chord.hi : kInfinity;
}

double objectHit(const PreparedObject& object, const glm::dvec3& o, const glm::dvec3& d) {
  return object.type == host::ObjectType::Plane ? planeHit(object, o, d) : chordHit(objectChord(object, o, d));
}

// ---- shadowed intervals -----------------------------------------------------------------------

// The ray p + u·l crosses the plane iff the signed distance of p and l·n have opposite signs;
// points on the plane, and every point when l is parallel to the plane, are lit.
Interval planeShadow(const PreparedObject& plane, const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& l) {
  const double lightSide = glm::dot(l, plane.normal);
  if (lightSide == 0.0) return kEmpty;
  const double offset = glm::dot(o - plane.centre, plane.normal) * lightSide;  // < 0: shadowed
  const double slope = glm::dot(d, plane.normal) * lightSide;
  if (slope == 0.0) return offset < 0.0 ? Interval{} : kEmpty;
  Interval shadowed;
  clipHalfLine(shadowed, slope, -offset);
  return shadowed;
}

// S(sphere) = the ball ∪ the half-infinite cylinder of radius r behind it ((p − c)·l ≤ 0, distance to
// the axis c + u·l at most r): the minimum of |p − c + u·l| over u ≥ 0 is |p − c| when (p − c)·l ≥ 0
// and the distance to the axis otherwise. Both pieces are convex and their union is, so the hull of
// the two line intervals is exact.
Interval sphereShadow(const PreparedObject& sphere, const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& l) {
  const double r2 = sphere.radius * sphere.radius;
  const glm::dvec3 q = o - sphere.centre;
  const Interval ball = quadraticNonPositive(glm::dot(d, d), glm::dot(q, d), glm::dot(q, q) - r2);
  // Components perpendicular to the axis, computed as vectors: 1 − (d·l)² would cancel.
  const glm::dvec3 dPerp = d - glm::dot(d, l) * l;
  const glm::dvec3 qPerp = q - glm::dot(q, l) * l;
  Interval cylinder = quadraticNonPositive(glm::dot(dPerp, dPerp), glm::dot(qPerp, dPerp), glm::dot(qPerp, qPerp) - r2);
  clipHalfLine(cylinder, glm::dot(d, l), -glm::dot(q, l));
  return hull(ball, cylinder);
}

// S(box) along the line: {t : ∃u ≥ 0, o + t·d + u·l ∈ box} is the projection onto t of a convex
// polygon in (t, u) given by seven constraints a·t + b·u ≤ c (six slab sides and u ≥ 0).
// Fourier–Motzkin elimination of u is exact: t is feasible iff every pure-t constraint holds and
// every lower bound on u lies below every upper bound. Combining with positive multipliers instead
// of dividing by b keeps it robust when l is (nearly) parallel to a face.
Interval boxShadow(const PreparedObject& box, const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& l) {
  struct Constraint {
    double a, b, c;
  };
  const glm::dvec3 localOrigin = box.worldToLocal * (o - box.centre);
  const glm::dvec3 localDir = box.worldToLocal * d;
  const glm::dvec3 localLight = box.worldToLocal * l;
  Constraint constraints[7];
  for (int i = 0; i < 3; ++i) {
    const double h = box.halfExtents[i];
    constraints[2 * i] = {localDir[i], localLight[i], h - localOrigin[i]};
    constraints[2 * i + 1] = {-localDir[i], -localLight[i], h + localOrigin[i]};
  }
  constraints[6] = {0.0, -1.0, 0.0};  // u ≥ 0
  Interval shadowed;
  for (const Constraint& lower : constraints) {
    if (lower.b == 0.0) clipHalfLine(shadowed, lower.a, lower.c);
    if (!(lower.b < 0.0)) continue;
    for (const Constraint& upper : constraints) {
      if (!(upper.b > 0.0)) continue;
      // upper.b·(lower) + (−lower.b)·(upper) cancels u.
      clipHalfLine(shadowed, upper.b * lower.a - lower.b * upper.a, upper.b * lower.c - lower.b * upper.c);
    }
  }
  return shadowed;
}

Interval objectShadow(const PreparedObject& object, const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& l) {
  switch (object.type) {
    case host::ObjectType::Plane: return planeShadow(object, o, d, l);
    case host::ObjectType::Sphere: return sphereShadow(object, o, d, l);
    case host::ObjectType::Box: return boxShadow(object, o, d, l);
    case host::ObjectType::Gltf: break;
  }
  return kEmpty;
}

// Sorts and merges in place: overlapping or touching intervals become one.
void mergeIntervals(std::vector<Interval>& intervals) {
  std::sort(intervals.begin(), intervals.end(), [](const Interval& x, const Interval& y) { return x.lo < y.lo; });
  std::size_t kept = 0;
  for (const Interval& next : intervals) {
    if (kept > 0 && next.lo <= intervals[kept - 1].hi) {
      intervals[kept - 1].hi = std::max(intervals[kept - 1].hi, next.hi);
    } else {
      intervals[kept++] = next;
    }
  }
  intervals.resize(kept);
}

// ---- the scene as the queries see it ----------------------------------------------------------

class AnalyticScene {
 public:
  explicit AnalyticScene(const host::Scene& scene)
      : medium_(scene.medium),
        toLight_(-glm::normalize(scene.light.direction)),
        irradiance_(scene.light.color * scene.light.intensity),
        sigmaT_(extinction(scene)) {
    objects_.reserve(scene.objects.size());
    for (const host::Object& object : scene.objects) {
      (object.translucent() ? translucent_ : objects_).push_back(prepare(object));
    }
  }

  // Translucent objects are not in the depth buffer: view rays pass them.
  double firstSurface(const glm::dvec3& o, const glm::dvec3& d) const {
    double nearest = kInfinity;
    for (const PreparedObject& object : objects_) nearest = std::min(nearest, objectHit(object, o, d));
    return nearest;
  }

  // By the opaque objects, clipped to [0, tMax], merged and sorted into `out` (reused between rays
  // to avoid allocations).
  void shadowed(const glm::dvec3& o, const glm::dvec3& d, double tMax, std::vector<Interval>& out) const {
    out.clear();
    for (const PreparedObject& object : objects_) {
      Interval interval = objectShadow(object, o, d, toLight_);
      interval.lo = std::max(interval.lo, 0.0);
      interval.hi = std::min(interval.hi, tMax);
      if (!interval.empty()) out.push_back(interval);
    }
    mergeIntervals(out);
  }

  glm::dvec3 inScattering(const glm::dvec3& o, const glm::dvec3& d, double s, std::vector<Interval>& scratch) const {
    shadowed(o, d, s, scratch);
    const glm::dvec3 lit = translucent_.empty() ? litIntegral(scratch, s) : translucentLitIntegral(o, d, s, scratch);
    const double cosTheta = glm::dot(d, toLight_);
    glm::dvec3 radiance(0.0);
    for (const host::MediumComponent& component : medium_) {
      radiance += component.scattering * phase(component.phase, component.g, cosTheta);
    }
    return radiance * irradiance_ * lit;
  }

  const glm::dvec3& sigmaT() const { return sigmaT_; }

 private:
  // ∫ exp(−σ_t t) dt over [0, s] minus the shadowed intervals, per channel, summed over the lit gaps
  // (never as "all minus shadowed", which would cancel when most of the ray is in shadow).
  glm::dvec3 litIntegral(const std::vector<Interval>& shadows, double s) const {
    glm::dvec3 lit(0.0);
    double litStart = 0.0;
    for (const Interval& shadow : shadows) {
      for (int c = 0; c < 3; ++c) lit[c] += attenuatedLength(litStart, shadow.lo, sigmaT_[c]);
      litStart = shadow.hi;
    }
    for (int c = 0; c < 3; ++c) lit[c] += attenuatedLength(litStart, s, sigmaT_[c]);
    return lit;
  }

  // litIntegral with translucent occluders: [0, s] cut at every end of a translucent object's S(K)
  // and K interval, each piece weighted by the light's transmittance at its middle (constant on it).
  glm::dvec3 translucentLitIntegral(const glm::dvec3& o, const glm::dvec3& d, double s,
                                    const std::vector<Interval>& opaqueShadows) const {
    struct Crossed {
      Interval shadow, inside;
      double opacity;
    };
    std::vector<Crossed> crossed;
    std::vector<double> cuts{0.0, s};
    for (const PreparedObject& object : translucent_) {
      const Crossed c{objectShadow(object, o, d, toLight_), objectChord(object, o, d), object.opacity};
      if (c.shadow.empty()) continue;
      crossed.push_back(c);
      for (double t : {c.shadow.lo, c.shadow.hi, c.inside.lo, c.inside.hi}) {
        if (t > 0.0 && t < s) cuts.push_back(t);
      }
    }
    for (const Interval& shadow : opaqueShadows) {
      cuts.push_back(shadow.lo);
      cuts.push_back(shadow.hi);
    }
    std::sort(cuts.begin(), cuts.end());
    glm::dvec3 lit(0.0);
    for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
      const double a = cuts[i], b = cuts[i + 1];
      if (!(b > a)) continue;
      const double middle = 0.5 * (a + b);
      const bool opaque = std::any_of(opaqueShadows.begin(), opaqueShadows.end(),
                                      [&](const Interval& x) { return x.lo <= middle && middle <= x.hi; });
      if (opaque) continue;
      double transmittance = 1.0;
      for (const Crossed& c : crossed) {
        if (!(c.shadow.lo <= middle && middle <= c.shadow.hi)) continue;
        const bool inside = c.inside.lo <= middle && middle <= c.inside.hi;
        transmittance *= inside ? 1.0 - c.opacity : (1.0 - c.opacity) * (1.0 - c.opacity);
      }
      for (int c = 0; c < 3; ++c) lit[c] += transmittance * attenuatedLength(a, b, sigmaT_[c]);
    }
    return lit;
  }

  std::vector<PreparedObject> objects_;      // opaque
  std::vector<PreparedObject> translucent_;
  std::vector<host::MediumComponent> medium_;
  glm::dvec3 toLight_;
  glm::dvec3 irradiance_;
  glm::dvec3 sigmaT_;
};

glm::dvec3 cameraForward(const host::Camera& camera) {
  return glm::normalize(camera.target - camera.position);
}

double rayLength(const AnalyticScene& analytic, const host::Camera& camera, const glm::dvec3& dir) {
  const double farDistance = camera.farPlane / glm::dot(dir, cameraForward(camera));
  return std::min(analytic.firstSurface(camera.position, dir), farDistance);
}

bool checkSupported(const host::Scene& scene, std::uint32_t width, std::uint32_t height, std::string& error) {
  if (width == 0 || height == 0) {
    error = "the image size must be non-zero";
  } else if (!scene.additionalLights.empty()) {
    error = "the analytic reference supports one light only";
  } else if (scene.light.type != host::LightType::Directional) {
    error = "the analytic reference supports directional lights only";
  } else if (scene.medium.empty()) {
    error = "the scene has no medium";
  } else {
    for (const host::Object& object : scene.objects) {
      if (object.type == host::ObjectType::Gltf) error = "the analytic reference supports no glTF objects";
    }
  }
  return error.empty();
}

void resize(RgbImage& image, std::uint32_t width, std::uint32_t height) {
  image.width = width;
  image.height = height;
  image.rgb.assign(static_cast<std::size_t>(width) * height * 3, 0.0);
}

void store(RgbImage& image, std::uint32_t x, std::uint32_t y, const glm::dvec3& value) {
  const std::size_t i = (static_cast<std::size_t>(y) * image.width + x) * 3;
  image.rgb[i] = value.r;
  image.rgb[i + 1] = value.g;
  image.rgb[i + 2] = value.b;
}

}  // namespace

double phase(host::PhaseType type, double g, double cosTheta) {
  constexpr double kPi = std::numbers::pi;
  switch (type) {
    case host::PhaseType::Isotropic:
      return 1.0 / (4.0 * kPi);
    case host::PhaseType::Rayleigh:
      return 3.0 / (16.0 * kPi) * (1.0 + cosTheta * cosTheta);
    case host::PhaseType::HenyeyGreenstein:
      return (1.0 - g * g) / (4.0 * kPi * std::pow(1.0 + g * g - 2.0 * g * cosTheta, 1.5));
    case host::PhaseType::CornetteShanks:
      return 3.0 * (1.0 - g * g) / (8.0 * kPi * (2.0 + g * g)) * (1.0 + cosTheta * cosTheta) /
             std::pow(1.0 + g * g - 2.0 * g * cosTheta, 1.5);
  }
  return 0.0;
}

double attenuatedLength(double a, double b, double sigmaT) {
  if (!(b > a)) return 0.0;
  if (sigmaT == 0.0) return b - a;
  // exp(−σa)·(1 − exp(−σ(b − a)))/σ; expm1 keeps all digits when σ(b − a) is tiny.
  return std::exp(-sigmaT * a) * -std::expm1(-sigmaT * (b - a)) / sigmaT;
}

glm::dvec3 extinction(const host::Scene& scene) {
  glm::dvec3 sigmaT(0.0);
  for (const host::MediumComponent& component : scene.medium) sigmaT += component.scattering + component.absorption;
  return sigmaT;
}

glm::dvec3 cameraRayDirection(const host::Camera& camera, std::uint32_t px, std::uint32_t py,
                              std::uint32_t width, std::uint32_t height) {
  const glm::dvec3 forward = cameraForward(camera);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, camera.up));
  const glm::dvec3 trueUp = glm::cross(right, forward);
  const double tanHalfFov = std::tan(glm::radians(camera.fovYDegrees) * 0.5);
  const double aspect = static_cast<double>(width) / static_cast<double>(height);
  const double x = 2.0 * (px + 0.5) / width - 1.0;   // −1 at the left edge
  const double y = 1.0 - 2.0 * (py + 0.5) / height;  // +1 at the top edge (row 0)
  return glm::normalize(forward + right * (x * tanHalfFov * aspect) + trueUp * (y * tanHalfFov));
}

double firstSurfaceDistance(const host::Scene& scene, glm::dvec3 origin, glm::dvec3 dir) {
  return AnalyticScene(scene).firstSurface(origin, dir);
}

double viewRayLength(const host::Scene& scene, glm::dvec3 dir) {
  return rayLength(AnalyticScene(scene), scene.camera, dir);
}

std::vector<std::pair<double, double>> shadowedIntervals(const host::Scene& scene, glm::dvec3 origin,
                                                         glm::dvec3 dir, double tMax) {
  std::vector<Interval> intervals;
  AnalyticScene(scene).shadowed(origin, dir, tMax, intervals);
  std::vector<std::pair<double, double>> result;
  result.reserve(intervals.size());
  for (const Interval& interval : intervals) result.emplace_back(interval.lo, interval.hi);
  return result;
}

glm::dvec3 inScattering(const host::Scene& scene, glm::dvec3 origin, glm::dvec3 dir, double s) {
  std::vector<Interval> scratch;
  return AnalyticScene(scene).inScattering(origin, dir, s, scratch);
}

bool renderAnalytic(const host::Scene& scene, std::uint32_t width, std::uint32_t height,
                    RgbImage& scattering, RgbImage& transmittance, std::string& error) {
  error.clear();
  if (!checkSupported(scene, width, height, error)) return false;
  const AnalyticScene analytic(scene);
  resize(scattering, width, height);
  resize(transmittance, width, height);
  std::vector<Interval> scratch;
  for (std::uint32_t y = 0; y < height; ++y) {
    for (std::uint32_t x = 0; x < width; ++x) {
      const glm::dvec3 dir = cameraRayDirection(scene.camera, x, y, width, height);
      const double s = rayLength(analytic, scene.camera, dir);
      store(scattering, x, y, analytic.inScattering(scene.camera.position, dir, s, scratch));
      store(transmittance, x, y, glm::exp(-analytic.sigmaT() * s));
    }
  }
  return true;
}

}  // namespace tyndall::analytic
