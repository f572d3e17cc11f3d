// What the host's projection matrix says about depth: standard or reverse-Z, finite or infinite
// far plane, and the near/far distances. Detected from the matrix alone (DESIGN.md).
#pragma once

#include <glm/glm.hpp>

#include "tyndall/tyndall.h"

namespace tyndall {

struct ProjectionInfo {
  bool reversed = false;      ///< near maps to depth 1, far to 0
  bool infiniteFar = false;   ///< far plane at infinity
  double nearDistance = 0.0;  ///< scene units along the view axis
  double farDistance = 0.0;   ///< scene units; +inf when infiniteFar
  float nearNdc = 0.0f;       ///< depth-buffer value at the near plane
  float farNdc = 1.0f;        ///< depth-buffer value at the far plane (the sky's clear value)
};

/// Analyses a perspective projection with clip depth [0, 1]. Fails (InvalidArgument) for
/// non-finite, singular, non-perspective matrices and for near ≤ 0 or near ≥ far.
Outcome analyzeProjection(const glm::dmat4& projection, ProjectionInfo& out);

/// Whether a spot light's cone (apex `position`, unit `axis`, half-angle `outerCone` < π/2) lies
/// wholly outside one side plane of the view pyramid (the camera's rays through the four edges of
/// the image) or behind the camera, so that no view ray crosses it. Conservative: false whenever
/// no single plane separates them.
bool spotConeMissesView(const glm::dmat4& viewToWorld, const glm::dmat4& clipToView, const glm::dvec3& position,
                        const glm::dvec3& axis, double outerCone);

}  // namespace tyndall
