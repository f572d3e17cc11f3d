#version 460
// Sample refinement (engelhardt2010 §4.2, yusov2013): along each slice, every `initial step`-th
// sample and the last one are ray-marched, and so are both samples on either side of a depth
// break (relative difference of view-ray length above the threshold). Every other sample is
// interpolated from the nearest ray-marched sample on each side: the interpolation source.
// One thread walks one slice, so the result does not depend on a subgroup width.
#extension GL_GOOGLE_include_directive : require
#include "epipolar/epipolar_common.glsl"

layout(local_size_x = TYN_EPIPOLAR_SLICE_GROUP) in;

bool tyn_depth_break(float a, float b) {
  return abs(a - b) > epipolar.refinement.x * min(a, b);
}

bool tyn_marched(uint k, uint count, uint slice) {
  if (k % epipolar.counts.w == 0u || k + 1u == count) return true;
  float here = imageLoad(epipolar_coordinates, ivec2(k, slice)).z;
  float before = imageLoad(epipolar_coordinates, ivec2(k - 1u, slice)).z;
  float after = imageLoad(epipolar_coordinates, ivec2(k + 1u, slice)).z;
  return tyn_depth_break(before, here) || tyn_depth_break(here, after);
}

void main() {
  uint slice = gl_GlobalInvocationID.x;
  if (slice >= epipolar.counts.x) return;
  vec4 end_points = imageLoad(slice_end_points, ivec2(slice, 0));
  uint count = tyn_slice_sample_count(end_points, tyn_output_extent(), epipolar.counts.y, epipolar.params.x,
                                      epipolar.counts.z != 0u);
  // Forward: each sample's left source (the last ray-marched sample at or before it).
  uint left = 0u;
  uint marched = 0u;
  for (uint k = 0u; k < epipolar.counts.y; ++k) {
    if (k >= count) {
      imageStore(interpolation_source, ivec2(k, slice), uvec4(TYN_EPIPOLAR_NO_SOURCE));
      continue;
    }
    if (tyn_marched(k, count, slice)) {
      left = k;
      ++marched;
    }
    imageStore(interpolation_source, ivec2(k, slice), uvec4(left));
  }
  // Backward: the right source (the first ray-marched sample at or after it).
  uint right = count > 0u ? count - 1u : 0u;
  for (uint i = 0u; i < count; ++i) {
    uint k = count - 1u - i;
    uint left_of_k = imageLoad(interpolation_source, ivec2(k, slice)).x;
    if (left_of_k == k) right = k;
    imageStore(interpolation_source, ivec2(k, slice), uvec4(left_of_k | (right << 16)));
  }
  atomicAdd(marched_count, marched);
}
