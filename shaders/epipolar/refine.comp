#version 460
// Sample refinement (engelhardt2010 §4.2, yusov2013): along each slice, every `initial step`-th
// sample (denser near the epipole, see tyn_march_step) and the last one are ray-marched, and so
// are both samples on either side of a depth break (relative difference of view-ray length above the threshold). Every other sample is
// interpolated from the nearest ray-marched sample on each side: the interpolation source. The
// ray-marching samples are listed for the march pass (shadow_test.comp first takes out those whose
// whole ray is in shadow).
// One thread walks one slice, so the result does not depend on a subgroup width.
#extension GL_GOOGLE_include_directive : require
#include "epipolar/epipolar_common.glsl"

layout(local_size_x = TYN_EPIPOLAR_SLICE_GROUP) in;

bool tyn_depth_break(float a, float b) {
  return abs(a - b) > epipolar.refinement.x * min(a, b);
}

// The ray-marching step at sample k: the initial step, but near the epipole at most
// 1/TYN_EPIPOLAR_NEAR_EPIPOLE_STEPS of the distance to it (a power of two, so the steps nest).
// L_in of a local light grows like 1/(distance to the epipole) there and a phase lobe peaks there:
// linear interpolation of 1/r over a step Δ ≤ r/8 is off by at most Δ²/(4r²) < 0.4%, where a fixed
// step next to the light would interpolate from the light's own (unbounded) value.
uint tyn_march_step(vec2 here, vec2 next) {
  uint step = epipolar.counts.w;
  if (epipolar.epipole.z > 0.0) {
    vec2 extent = tyn_output_extent();
    float to_epipole = length((here - tyn_epipole_ndc(epipolar.epipole)) * 0.5 * extent);
    float spacing = max(length((next - here) * 0.5 * extent), 1e-6);
    uint steps = uint(clamp(to_epipole / (TYN_EPIPOLAR_NEAR_EPIPOLE_STEPS * spacing), 1.0, float(step)));
    step = min(step, 1u << findMSB(steps));
  }
  return step;
}

bool tyn_marched(uint k, uint count, uint slice) {
  if (k == 0u || k + 1u == count) return true;
  vec4 here = imageLoad(epipolar_coordinates, ivec2(k, slice));
  vec4 after = imageLoad(epipolar_coordinates, ivec2(k + 1u, slice));
  if (k % tyn_march_step(vec2(here.x, here.y), vec2(after.x, after.y)) == 0u) return true;
  float before = imageLoad(epipolar_coordinates, ivec2(k - 1u, slice)).z;
  return tyn_depth_break(before, here.z) || tyn_depth_break(here.z, after.z);
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
  // Backward: the right source (the first ray-marched sample at or after it); the slice's
  // ray-marching samples go to the march list, in one range reserved by one atomic.
  uint entry = atomicAdd(march_count, marched);
  uint right = count > 0u ? count - 1u : 0u;
  for (uint i = 0u; i < count; ++i) {
    uint k = count - 1u - i;
    uint left_of_k = imageLoad(interpolation_source, ivec2(k, slice)).x;
    if (left_of_k == k) {
      right = k;
      march_samples[entry++] = k | (slice << 16);
    }
    imageStore(interpolation_source, ivec2(k, slice), uvec4(left_of_k | (right << 16)));
  }
}
