// The part of the screen border the epipolar slices are spread over (shaders/epipolar/
// epipolar_geometry.h "Slice arc"). The slices' exit points are evenly spaced along the border;
// where the epipolar planes of a whole stretch of it cannot meet the lit volume, slices there
// would sample L_in = 0, so the N slices are spread over the rest instead: a spot light's cone
// seen from outside covers a wedge of directions from the epipole (a quarter of them or less in
// the sample scenes), and an off-screen epipole leaves about half the border without a valid
// slice. Computed on the CPU per frame, conservatively: a pixel off the arc gets L_in = 0.
#pragma once

#include <glm/glm.hpp>

#include "tyndall/tyndall.h"

namespace tyndall {

struct SliceArc {
  glm::vec2 arc{0.0f};    ///< (start, length) in perimeter pixels; length = P: the whole border
  float fraction = 1.0f;  ///< length / P
  bool cone = false;      ///< the spot cone bounds the arc
  bool screen = false;    ///< exit points an off-screen epipole culls bound it
};

/// The slices' arc for a frame: `epipole` from tyn_epipole, `extent` the output in pixels (≥ 2×2).
/// The whole border when nothing bounds it: a point or directional light with the epipole on
/// screen, a spot light whose cone holds the line through the camera and the light (the camera
/// inside the cone or behind the light in it), or a lit stretch too short to resolve.
SliceArc sliceArc(const CameraDesc& camera, const LightDesc& light, glm::vec4 epipole, glm::vec2 extent);

}  // namespace tyndall
