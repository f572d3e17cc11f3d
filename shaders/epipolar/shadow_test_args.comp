#version 460
// Starts the shadow test (shadow_test.comp) over the refinement's entries, or skips it: every view
// ray starts at the camera, so where the camera is lit no ray is in shadow along its whole length.
// Then the test's dispatch is zero groups and the march's round starts at the refinement's
// entries themselves (march_args.comp starts the round at march_round_end, left at 0), so an
// open-air view pays nothing for the test. Only a gate: shadow_test.comp is exact on its own.
#extension GL_GOOGLE_include_directive : require
#include "epipolar/epipolar_common.glsl"
#define TYN_MIN_MAX_SHADOW_TEXEL(texel) tyn_epipolar_shadow_texel(texel)
#include "epipolar/min_max_tree.h"

layout(local_size_x = 1) in;

// The camera in shadow on the 2×2 texel block around it (the footprint of a 1D cell there); a
// camera outside the map counts as lit.
bool tyn_camera_in_shadow_map() {
  vec4 h0 = frame.world_to_shadow[0] * vec4(frame.view_to_world[3].xyz, 1.0);
  if (h0.w <= 0.0 || abs(h0.x) > h0.w || abs(h0.y) > h0.w) return false;
  vec2 camera_texels = (vec2(h0.x, h0.y) / h0.w * 0.5 + 0.5) * float(frame.shadow_map_size);
  ivec2 t = tyn_min_max_footprint_origin(camera_texels);
  vec2 bounds = tyn_min_max_footprint_bounds(vec4(tyn_epipolar_shadow_texel(t), tyn_epipolar_shadow_texel(t + ivec2(1, 0)),
                                                  tyn_epipolar_shadow_texel(t + ivec2(0, 1)),
                                                  tyn_epipolar_shadow_texel(t + ivec2(1, 1))));
  return bounds.y < 1.0 && h0.z / h0.w > bounds.y;
}

void main() {
  bool test = tyn_camera_in_shadow_map();
  march_first = 0u;
  march_round_end = test ? march_count : 0u;
  march_groups[0] = test ? (march_count + TYN_EPIPOLAR_MARCH_GROUP - 1u) / TYN_EPIPOLAR_MARCH_GROUP : 0u;
  march_groups[1] = 1u;
  march_groups[2] = 1u;
}
