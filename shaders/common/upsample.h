// Joint bilateral upsampling (Kopf et al. 2007, depth as the guide) of L_in computed at reduced
// resolution: an output pixel blends the four target pixels around it with bilinear weights, each
// times a Gaussian of how far the view-ray length of the target pixel's output pixel lies from the
// pixel's own. Across a depth break the taps on the other surface drop out; where all four are on
// other surfaces (a thin object the target missed), the one nearest in depth is taken alone.
// Shared by the composites and the L_in AOV (composite/upsample.glsl) and the unit tests.
#ifndef TYNDALL_UPSAMPLE_H
#define TYNDALL_UPSAMPLE_H

#include "common/cpp_glsl.h"

TYN_BEGIN

// Relative difference of view-ray length at which a tap's weight falls to e^-1. Ground seen at a
// grazing angle changes its ray length by several percent per output pixel, and a quarter-resolution
// tap lies up to four pixels away: a tolerance below about 0.1 would reject taps on the same surface.
TYN_CONST float TYN_UPSAMPLE_DEPTH_TOLERANCE = 0.1f;
// Below this total weight no tap is on the pixel's surface (each is then beyond about 3 tolerances).
TYN_CONST float TYN_UPSAMPLE_MIN_WEIGHT = 1e-4f;

// Where output pixel `pixel` lies in the target's pixel grid (target pixel p at output pixel
// p · stride + offset).
TYN_FUNC vec2 tyn_upsample_position(uvec2 pixel, uint stride, uint offset) {
  return (vec2(pixel) - vec2(float(offset))) / float(stride);
}

// Normalised weights of the taps at base + (0,0), (1,0), (0,1), (1,1) for a pixel at fraction `f`
// between them; `tap_distance` their view-ray lengths, `distance` the pixel's.
TYN_FUNC vec4 tyn_upsample_weights(vec2 f, vec4 tap_distance, float distance) {
  vec4 bilinear = vec4((1.0f - f.x) * (1.0f - f.y), f.x * (1.0f - f.y), (1.0f - f.x) * f.y, f.x * f.y);
  vec4 difference = abs(tap_distance - vec4(distance));
  vec4 relative = difference / (max(distance, 1e-30f) * TYN_UPSAMPLE_DEPTH_TOLERANCE);
  vec4 w = bilinear * exp(-relative * relative);
  float total = w.x + w.y + w.z + w.w;
  if (total >= TYN_UPSAMPLE_MIN_WEIGHT) return w / total;
  // The tap nearest in depth, the first of equals.
  vec4 nearest = vec4(1.0f, 0.0f, 0.0f, 0.0f);
  float best = difference.x;
  if (difference.y < best) { best = difference.y; nearest = vec4(0.0f, 1.0f, 0.0f, 0.0f); }
  if (difference.z < best) { best = difference.z; nearest = vec4(0.0f, 0.0f, 1.0f, 0.0f); }
  if (difference.w < best) { nearest = vec4(0.0f, 0.0f, 0.0f, 1.0f); }
  return nearest;
}

TYN_END

#endif
