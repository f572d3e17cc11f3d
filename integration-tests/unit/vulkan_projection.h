// Test scaffolding: the Vulkan perspective matrices a host builds, in double precision.
#pragma once

#include <cmath>

#include <glm/glm.hpp>

namespace tyndall::test {

/// Clip depth [0, 1], y flipped (row 0 at the top), standard or reverse-Z, finite or infinite
/// far (f = INFINITY). Built by hand so that no GL [−1, 1] convention leaks in.
inline glm::dmat4 vulkanPerspective(double fovY, double aspect, double n, double f, bool reversed) {
  const double t = 1.0 / std::tan(fovY / 2.0);
  glm::dmat4 p(0.0);
  p[0][0] = t / aspect;
  p[1][1] = -t;
  p[2][3] = -1.0;
  const bool infinite = std::isinf(f);
  if (!reversed) {
    p[2][2] = infinite ? -1.0 : f / (n - f);
    p[3][2] = infinite ? -n : f * n / (n - f);
  } else {
    p[2][2] = infinite ? 0.0 : n / (f - n);
    p[3][2] = infinite ? n : f * n / (f - n);
  }
  return p;
}

}  // namespace tyndall::test
