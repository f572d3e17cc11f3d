#version 460
// Interpolation along the slices (yusov2013): a sample that was not ray-marched takes L_in
// linearly from its two interpolation sources (which are on its own surface: a depth break
// between them would have made a ray-marched sample).
#extension GL_GOOGLE_include_directive : require
#include "epipolar/epipolar_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

void main() {
  uvec2 id = gl_GlobalInvocationID.xy;  // x: sample, y: slice
  if (id.x >= epipolar.samples_per_slice || id.y >= epipolar.slice_count) return;
  uint source = imageLoad(interpolation_source, ivec2(id)).x;
  if (source == TYN_EPIPOLAR_NO_SOURCE) return;
  uint left = source & 0xffffu;
  uint right = source >> 16;
  if (left == id.x) return;  // ray-marched
  vec3 a = imageLoad(epipolar_scattering, ivec2(left, id.y)).rgb;
  vec3 b = imageLoad(epipolar_scattering, ivec2(right, id.y)).rgb;
  float w = float(id.x - left) / float(max(right - left, 1u));
  imageStore(epipolar_scattering, ivec2(id), vec4(mix(a, b, w), 0.0));
}
