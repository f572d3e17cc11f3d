#include "camera.h"

#include <cmath>

#include "gpu.h"

namespace tyndall {

// A perspective projection maps view distance d (= −z_view) to depth ndc(d) = A + B / d with
// A = −P22 / k, B = P32 / k and k = −P23 (column-major P[col][row]): standard Z has B < 0,
// reverse-Z B > 0. The far plane is at infinity when the limit A equals the far value (1 for
// standard, 0 for reverse). A float matrix stores A to 2^-24 relative, so |A − far| below 2^-22
// means infinite: such a far plane is more than ~4·10^6 near distances away.
Outcome analyzeProjection(const glm::dmat4& p, ProjectionInfo& out) {
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) {
      if (!std::isfinite(p[c][r])) return failure(Status::InvalidArgument, "camera.projection has a NaN or Inf entry");
    }
  }
  const double det = glm::determinant(p);
  if (!std::isfinite(det) || std::abs(det) < 1e-30) {
    return failure(Status::InvalidArgument, "camera.projection is singular");
  }
  const double k = -p[2][3];
  if (p[0][3] != 0.0 || p[1][3] != 0.0 || p[3][3] != 0.0 || !(k > 0.0)) {
    return failure(Status::InvalidArgument,
                   "camera.projection is not a perspective projection looking down -Z (w_clip must be -z_view)");
  }
  const double a = -p[2][2] / k;
  const double b = p[3][2] / k;
  if (b == 0.0) return failure(Status::InvalidArgument, "camera.projection maps every depth to one value");
  constexpr double kInfiniteTolerance = 1.0 / (1 << 22);

  out.reversed = b > 0.0;
  if (!out.reversed) {
    out.nearNdc = 0.0f;
    out.farNdc = 1.0f;
    out.nearDistance = a != 0.0 ? -b / a : 0.0;
    out.infiniteFar = std::abs(a - 1.0) <= kInfiniteTolerance;
    out.farDistance = out.infiniteFar ? INFINITY : b / (1.0 - a);
    if (!(a > 0.0)) return failure(Status::InvalidArgument, "camera.projection has near <= 0");
  } else {
    out.nearNdc = 1.0f;
    out.farNdc = 0.0f;
    out.nearDistance = b / (1.0 - a);
    out.infiniteFar = std::abs(a) <= kInfiniteTolerance;
    out.farDistance = out.infiniteFar ? INFINITY : -b / a;
    if (!(a < 1.0)) return failure(Status::InvalidArgument, "camera.projection has near <= 0");
  }
  if (!(out.nearDistance > 0.0) || !std::isfinite(out.nearDistance)) {
    return failure(Status::InvalidArgument, "camera.projection has near <= 0");
  }
  if (!out.infiniteFar && !(out.farDistance > out.nearDistance)) {
    return failure(Status::InvalidArgument, "camera.projection has near >= far");
  }
  return {};
}

bool spotConeMissesView(const glm::dmat4& viewToWorld, const glm::dmat4& clipToView, const glm::dvec3& position,
                        const glm::dvec3& axis, double outerCone) {
  // The image's four corner rays in view space (any depth of the ray will do: the planes pass
  // through the camera).
  glm::dvec3 corner[4];
  const double xs[4] = {-1.0, 1.0, 1.0, -1.0};
  const double ys[4] = {-1.0, -1.0, 1.0, 1.0};
  for (int i = 0; i < 4; ++i) {
    const glm::dvec4 v = clipToView * glm::dvec4(xs[i], ys[i], 0.5, 1.0);
    corner[i] = glm::dvec3(v) / v.w;
  }
  const glm::dvec3 camera = glm::dvec3(viewToWorld * glm::dvec4(0.0, 0.0, 0.0, 1.0));
  const glm::dmat3 normalToWorld = glm::transpose(glm::inverse(glm::dmat3(viewToWorld)));
  const glm::dvec3 centre = corner[0] + corner[1] + corner[2] + corner[3];
  // The four side planes, and the plane through the camera facing the view (rays start there).
  for (int i = 0; i < 5; ++i) {
    glm::dvec3 inward = i == 4 ? centre : glm::cross(corner[i], corner[(i + 1) % 4]);
    if (glm::dot(inward, centre) < 0.0) inward = -inward;
    const glm::dvec3 n = normalToWorld * inward;
    const double length = glm::length(n);
    if (!(length > 0.0)) continue;
    // Outside the plane: the apex behind it and every direction of the cone leading further out
    // (the angle between the inward normal and the axis at least π/2 + the half-angle).
    if (glm::dot(n, position - camera) < 0.0 && glm::dot(n / length, axis) <= -std::sin(outerCone)) return true;
  }
  return false;
}

}  // namespace tyndall
