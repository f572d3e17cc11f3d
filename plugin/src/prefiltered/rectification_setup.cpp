#include "prefiltered/rectification_setup.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>

#include "camera.h"
#include "gpu.h"

namespace tyndall::prefiltered {

using glm::dmat4;
using glm::dvec2;
using glm::dvec3;
using glm::dvec4;

namespace {

constexpr double kPi = std::numbers::pi;

// A light axis this close to a side plane (cosine of the angle to the plane, i.e. ~1e-9 rad)
// counts as inside the frustum: the azimuth range is then within rounding of π and the full
// circle is the safe answer.
constexpr double kInsideTolerance = 1e-9;

// Inclination of direction d from z_L: atan2 keeps full precision near 0 and π.
double inclination(const dvec3& d, const dvec3& z) {
  return std::atan2(glm::length(glm::cross(z, d)), glm::dot(z, d));
}

dvec3 perpendicularPart(const dvec3& d, const dvec3& z) { return d - glm::dot(d, z) * z; }

bool insideCone(const std::array<dvec3, 4>& planes, const dvec3& d) {
  return std::all_of(planes.begin(), planes.end(),
                     [&](const dvec3& n) { return glm::dot(n, d) >= -kInsideTolerance; });
}

// The inclination interval of the frustum's view directions in slice φ: the construction of
// tyn_slice_theta_range in double (each side plane keeps one end of [0, π] up to its root).
dvec2 sliceThetaRange(const NonLinearRectification& rect, double phi) {
  const dvec3 e = std::cos(phi) * rect.axisX + std::sin(phi) * rect.axisY;
  double lo = 0.0, hi = kPi;
  for (const dvec3& n : rect.sidePlanes) {
    const double a = glm::dot(n, e), b = glm::dot(n, rect.axisZ);
    if (b > 0.0) {
      hi = std::min(hi, std::atan2(b, -a));
    } else if (b < 0.0) {
      lo = std::max(lo, std::atan2(-b, a));
    } else if (a < 0.0) {
      return dvec2(kPi, 0.0);
    }
  }
  return dvec2(lo, hi);
}

// max over the frustum's directions of sin²θ·cos φ = |dθ/dζ| (ζ = h/x): per slice, sin² is
// largest at the inclination nearest π/2; over slices, a dense scan then a golden-section
// refinement around the best sample (the function is smooth in φ; 512 samples leave the
// refinement a bracket of Δφ/256).
double maxInclinationPerDepth(const NonLinearRectification& rect) {
  auto g = [&](double phi) {
    const dvec2 range = sliceThetaRange(rect, phi);
    if (range.x > range.y) return 0.0;
    const double s = std::sin(std::clamp(0.5 * kPi, range.x, range.y));
    return std::cos(phi) * s * s;
  };
  const int samples = 512;
  const double half = 0.5 * rect.phiExtent;
  double best = -1.0, bestPhi = 0.0;
  for (int i = 0; i <= samples; ++i) {
    const double phi = -half + rect.phiExtent * i / samples;
    const double v = g(phi);
    if (v > best) {
      best = v;
      bestPhi = phi;
    }
  }
  const double step = rect.phiExtent / samples;
  double a = std::max(-half, bestPhi - step), b = std::min(half, bestPhi + step);
  const double ratio = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int it = 0; it < 60; ++it) {
    const double c = b - ratio * (b - a), d = a + ratio * (b - a);
    if (g(c) > g(d)) {
      b = d;
    } else {
      a = c;
    }
  }
  return std::max(best, g(0.5 * (a + b)));
}

gpu::vec4 f4(const dvec3& v, double w) {
  return gpu::vec4(static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z),
                   static_cast<float>(w));
}

}  // namespace

Outcome buildViewFrustum(const dmat4& view, const dmat4& projection, double skyDistance,
                         ViewFrustum& out) {
  ProjectionInfo info;
  if (Outcome o = analyzeProjection(projection, info); !o.ok()) return o;
  const double det = glm::determinant(view);
  if (!std::isfinite(det) || std::abs(det) < 1e-30) {
    return failure(Status::InvalidArgument, "camera.view is singular or not finite");
  }
  if (info.infiniteFar && !(std::isfinite(skyDistance) && skyDistance > 0.0)) {
    return failure(Status::InvalidArgument, "an infinite far plane needs a finite sky distance > 0");
  }
  const dmat4 viewToWorld = glm::inverse(view);
  const dmat4 clipToView = glm::inverse(projection);
  ViewFrustum f;
  f.position = dvec3(viewToWorld[3]);
  f.forward = glm::normalize(dvec3(viewToWorld * dvec4(0.0, 0.0, -1.0, 0.0)));
  f.up = glm::normalize(dvec3(viewToWorld * dvec4(0.0, 1.0, 0.0, 0.0)));
  f.infiniteFar = info.infiniteFar;
  f.skyDistance = info.infiniteFar ? skyDistance : 0.0;
  const dvec2 ndc[4] = {{-1.0, -1.0}, {1.0, -1.0}, {1.0, 1.0}, {-1.0, 1.0}};
  double longest = 0.0;
  for (int i = 0; i < 4; ++i) {
    const dvec4 n = clipToView * dvec4(ndc[i], info.nearNdc, 1.0);
    const dvec3 nearView = dvec3(n) / n.w;
    dvec3 farView;
    if (info.infiniteFar) {
      farView = nearView * (skyDistance / -nearView.z);
    } else {
      const dvec4 fp = clipToView * dvec4(ndc[i], info.farNdc, 1.0);
      farView = dvec3(fp) / fp.w;
    }
    f.nearCorners[i] = dvec3(viewToWorld * dvec4(nearView, 1.0));
    f.farCorners[i] = dvec3(viewToWorld * dvec4(farView, 1.0));
    longest = std::max(longest, glm::length(f.farCorners[i] - f.position));
  }
  f.maxRayLength = info.infiniteFar ? skyDistance : longest;
  out = f;
  return {};
}

NonLinearRectification computeNonLinearRectification(const ViewFrustum& frustum,
                                                     const dvec3& lightDirection) {
  NonLinearRectification rect;
  rect.origin = frustum.position;
  const dvec3 z = glm::normalize(lightDirection);
  rect.axisZ = z;

  std::array<dvec3, 4> dirs{};
  dvec3 centroid(0.0);
  for (int i = 0; i < 4; ++i) {
    dirs[i] = frustum.farCorners[i] - frustum.position;
    centroid += glm::normalize(dirs[i]);
  }
  // Side planes through the camera, oriented towards the inside (the corner directions' mean
  // is inside the convex cone, also for off-axis projections whose view axis is not).
  for (int i = 0; i < 4; ++i) {
    dvec3 n = glm::normalize(glm::cross(dirs[i], dirs[(i + 1) % 4]));
    rect.sidePlanes[i] = glm::dot(n, centroid) < 0.0 ? -n : n;
  }

  // Appendix A, special case: the light axis (either way) in the frustum.
  const bool alongLight = insideCone(rect.sidePlanes, z);     // a view ray travels with the light
  const bool intoLight = insideCone(rect.sidePlanes, -z);     // a view ray looks into the light
  rect.fullCircle = alongLight || intoLight;

  if (!rect.fullCircle) {
    // The largest pairwise azimuth angle of the projected corners; the projected frustum is a
    // convex 2D cone narrower than π (else the light axis would be in it), so that pair spans
    // it and its bisectrix is x_L.
    double widest = -1.0;
    dvec3 bisectrix(0.0);
    for (int i = 0; i < 4; ++i) {
      for (int j = i + 1; j < 4; ++j) {
        const dvec3 a = perpendicularPart(dirs[i], z);
        const dvec3 b = perpendicularPart(dirs[j], z);
        const double angle = std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
        if (angle > widest) {
          widest = angle;
          bisectrix = glm::normalize(a) + glm::normalize(b);
        }
      }
    }
    rect.axisX = glm::normalize(bisectrix);
    rect.phiExtent = widest;
  } else {
    // Any perpendicular works; the view axis' projection keeps the seam (φ = ±π) behind the
    // camera where it can be, and the camera's up serves when the axis is the light's.
    dvec3 x = perpendicularPart(frustum.forward, z);
    if (glm::length(x) < 1e-6) x = perpendicularPart(frustum.up, z);
    rect.axisX = glm::normalize(x);
    rect.phiExtent = 2.0 * kPi;
  }
  rect.axisY = glm::cross(z, rect.axisX);

  // θ extrema: corners, then critical points on the far rectangle's edges (the derivative of the
  // normalised z-coordinate along a + t·b vanishes at t = (a_z·a·b − b_z·|a|²)/(b_z·a·b − a_z·|b|²),
  // peters2017 App. A), then the inside.
  double thetaMin = kPi, thetaMax = 0.0;
  for (const dvec3& d : dirs) {
    const double t = inclination(d, z);
    thetaMin = std::min(thetaMin, t);
    thetaMax = std::max(thetaMax, t);
  }
  for (int i = 0; i < 4; ++i) {
    const dvec3 a = dirs[i];
    const dvec3 b = dirs[(i + 1) % 4] - dirs[i];
    const double az = glm::dot(a, z), bz = glm::dot(b, z), ab = glm::dot(a, b);
    const double denominator = bz * ab - az * glm::dot(b, b);
    if (denominator == 0.0) continue;
    const double t = (az * ab - bz * glm::dot(a, a)) / denominator;
    if (t > 0.0 && t < 1.0) {
      const double theta = inclination(a + t * b, z);
      thetaMin = std::min(thetaMin, theta);
      thetaMax = std::max(thetaMax, theta);
    }
  }
  if (alongLight) thetaMin = 0.0;
  if (intoLight) thetaMax = kPi;
  rect.thetaMin = thetaMin;
  rect.thetaMax = thetaMax;
  const double guard = 0.5 * static_cast<double>(gpu::TYN_RECT_THETA_GUARD) * (thetaMax - thetaMin);
  rect.thetaMinGuarded = thetaMin - guard;
  rect.thetaMaxGuarded = thetaMax + guard;

  if (frustum.infiniteFar) {
    // Cone ∩ ball: r = |p|·sin θ is largest on the sphere, at the inclination nearest π/2.
    const double nearest = std::clamp(0.5 * kPi, thetaMin, thetaMax);
    rect.rMax = frustum.skyDistance * std::sin(nearest);
  } else {
    double rMax = 0.0;
    for (const dvec3& d : dirs) rMax = std::max(rMax, glm::length(perpendicularPart(d, z)));
    rect.rMax = rMax;
  }
  return rect;
}

// The rectification parameters' std140 offsets (shaders/prefiltered/rectification.h).
static_assert(offsetof(gpu::NonLinearRectificationParams, r_max) == 12);
static_assert(offsetof(gpu::NonLinearRectificationParams, phi_extent) == 28);
static_assert(offsetof(gpu::NonLinearRectificationParams, theta_range) == 64);
static_assert(offsetof(gpu::NonLinearRectificationParams, theta_range_guarded) == 72);
static_assert(offsetof(gpu::NonLinearRectificationParams, side_planes) == 80);
static_assert(sizeof(gpu::NonLinearRectificationParams) == 144);
static_assert(offsetof(gpu::ProjectiveRectificationParams, x_near) == 64);
static_assert(offsetof(gpu::ProjectiveRectificationParams, zeta_hi) == 92);
static_assert(sizeof(gpu::ProjectiveRectificationParams) == 96);

gpu::NonLinearRectificationParams toGpu(const NonLinearRectification& rect) {
  gpu::NonLinearRectificationParams p{};
  p.origin = gpu::vec3(rect.origin);
  p.r_max = static_cast<float>(rect.rMax);
  p.axis_x = gpu::vec3(rect.axisX);
  p.phi_extent = static_cast<float>(rect.phiExtent);
  p.axis_y = gpu::vec3(rect.axisY);
  p.axis_z = gpu::vec3(rect.axisZ);
  p.theta_range = gpu::vec2(static_cast<float>(rect.thetaMin), static_cast<float>(rect.thetaMax));
  p.theta_range_guarded =
      gpu::vec2(static_cast<float>(rect.thetaMinGuarded), static_cast<float>(rect.thetaMaxGuarded));
  for (int i = 0; i < 4; ++i) p.side_planes[i] = f4(rect.sidePlanes[i], 0.0);
  return p;
}

ProjectiveRectification computeProjectiveRectification(const ViewFrustum& frustum,
                                                       const NonLinearRectification& rect) {
  ProjectiveRectification proj;
  if (rect.fullCircle) return proj;
  std::array<dvec3, 8> corners{};
  for (int i = 0; i < 4; ++i) {
    corners[i] = frustum.nearCorners[i];
    corners[4 + i] = frustum.farCorners[i];
  }
  double xNear = std::numeric_limits<double>::infinity(), xFar = 0.0;
  double etaLo = xNear, etaHi = -xNear, zetaLo = xNear, zetaHi = -xNear;
  for (const dvec3& c : corners) {
    const dvec3 q = c - rect.origin;
    const double x = glm::dot(q, rect.axisX);
    if (!(x > 0.0)) return proj;  // a corner beside or behind the camera along x_L
    const double eta = glm::dot(q, rect.axisY) / x;
    const double zeta = glm::dot(q, rect.axisZ) / x;
    xNear = std::min(xNear, x);
    xFar = std::max(xFar, x);
    etaLo = std::min(etaLo, eta);
    etaHi = std::max(etaHi, eta);
    zetaLo = std::min(zetaLo, zeta);
    zetaHi = std::max(zetaHi, zeta);
  }
  proj.constructible = true;
  proj.xNear = xNear;
  proj.xFar = xFar;
  proj.etaLo = etaLo;
  proj.etaHi = etaHi;
  proj.zetaLo = zetaLo;
  proj.zetaHi = zetaHi;
  const double guard = 0.5 * static_cast<double>(gpu::TYN_RECT_THETA_GUARD) * (zetaHi - zetaLo);
  proj.zetaLoGuarded = zetaLo - guard;
  proj.zetaHiGuarded = zetaHi + guard;

  // World → light frame (x, y, h, 1): rows x_L, y_L, z_L, translated to the camera.
  dmat4 lightView(1.0);
  const dvec3 axes[3] = {rect.axisX, rect.axisY, rect.axisZ};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) lightView[c][r] = axes[r][c];
    lightView[3][r] = -glm::dot(axes[r], rect.origin);
  }
  // Perspective along x (column-major m[col][row]): W = x; X = A·x + B so that X/W runs −1 → 1
  // from x_n to x_f; Y/W affine in η = y/x; Z/W affine in ζ = h/x.
  dmat4 p(0.0);
  p[0][0] = (xFar + xNear) / (xFar - xNear);
  p[3][0] = -2.0 * xFar * xNear / (xFar - xNear);
  p[0][1] = -(etaLo + etaHi) / (etaHi - etaLo);
  p[1][1] = 2.0 / (etaHi - etaLo);
  p[0][2] = -proj.zetaLoGuarded / (proj.zetaHiGuarded - proj.zetaLoGuarded);
  p[2][2] = 1.0 / (proj.zetaHiGuarded - proj.zetaLoGuarded);
  p[0][3] = 1.0;
  proj.worldToClip = p * lightView;
  proj.texelStretch = projectiveTexelStretch(proj, rect);
  return proj;
}

double projectiveTexelStretch(const ProjectiveRectification& proj, const NonLinearRectification& rect) {
  if (!proj.constructible) return std::numeric_limits<double>::infinity();
  // Rows: |dφ/dη| = cos²φ is 1 on the bisectrix (always a frustum slice), so the coarsest
  // projective row spans η range / Δφ non-linear rows. Depth: |dθ/dζ| = sin²θ·cos φ, largest
  // somewhere in the frustum (maxInclinationPerDepth).
  const double rows = (proj.etaHi - proj.etaLo) / rect.phiExtent;
  const double depth = (proj.zetaHi - proj.zetaLo) / (rect.thetaMax - rect.thetaMin) * maxInclinationPerDepth(rect);
  return std::max(rows, depth);
}

gpu::ProjectiveRectificationParams toGpu(const ProjectiveRectification& proj) {
  gpu::ProjectiveRectificationParams p{};
  p.world_to_clip = gpu::mat4(proj.worldToClip);
  p.x_near = static_cast<float>(proj.xNear);
  p.x_far = static_cast<float>(proj.xFar);
  p.eta_lo = static_cast<float>(proj.etaLo);
  p.eta_hi = static_cast<float>(proj.etaHi);
  p.zeta_lo_guarded = static_cast<float>(proj.zetaLoGuarded);
  p.zeta_hi_guarded = static_cast<float>(proj.zetaHiGuarded);
  p.zeta_lo = static_cast<float>(proj.zetaLo);
  p.zeta_hi = static_cast<float>(proj.zetaHi);
  return p;
}

PrefixSumExtinction choosePrefixSumExtinction(const dvec3& sigmaT, double maxRayLength) {
  PrefixSumExtinction out;
  const double lo = std::min(std::min(sigmaT.x, sigmaT.y), sigmaT.z);
  const double hi = std::max(std::max(sigmaT.x, sigmaT.y), sigmaT.z);
  out.distinctChannels = 1 + (sigmaT.y != sigmaT.x ? 1 : 0) +
                         (sigmaT.z != sigmaT.x && sigmaT.z != sigmaT.y ? 1 : 0);
  auto worst = [&](double grey) {
    double e = 0.0;
    for (int c = 0; c < 3; ++c) {
      e = std::max(e, static_cast<double>(gpu::tyn_weighted_average_max_error(
                          static_cast<float>(grey * maxRayLength), static_cast<float>(sigmaT[c] * maxRayLength))));
    }
    return e;
  };
  if (hi == lo) {
    out.sigma = lo;
    return out;
  }
  // The error against the least extinct channel grows with σ_grey and against the most extinct
  // one falls: the minimax is where they meet (bisection; 60 halvings reach double precision).
  double a = lo, b = hi;
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (a + b);
    const double toLo = gpu::tyn_weighted_average_max_error(static_cast<float>(mid * maxRayLength),
                                                            static_cast<float>(lo * maxRayLength));
    const double toHi = gpu::tyn_weighted_average_max_error(static_cast<float>(mid * maxRayLength),
                                                            static_cast<float>(hi * maxRayLength));
    (toLo < toHi ? a : b) = mid;
  }
  out.sigma = 0.5 * (a + b);
  out.greyMaxError = worst(out.sigma);
  out.perChannel = out.greyMaxError > kGreyExtinctionMaxError;
  return out;
}

}  // namespace tyndall::prefiltered
