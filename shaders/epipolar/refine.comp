#version 460
// Sample refinement (engelhardt2010 §4.2, yusov2013): along each slice, every `initial step`-th
// sample (denser near the epipole, see tyn_march_step) and the last one are ray-marched, and so
// are both samples on either side of a depth break (relative difference of view-ray length above the threshold). Every other sample is
// interpolated from the nearest ray-marched sample on each side: the interpolation source. The
// ray-marching samples are listed for the march pass, except those whose whole view ray the
// slice's min/max tree shows to be in shadow: their L_in is zero, written here, and the march never
// sees them. When the light reaches no visible point (behind a wall covering the screen) the list
// stays empty and the march's indirect dispatches run no work (DESIGN.md "Model only what the
// scene requires": the decision needs the shadow map, so it is made on the GPU).
// One thread walks one slice, so the result does not depend on a subgroup width.
#extension GL_GOOGLE_include_directive : require
#include "epipolar/epipolar_common.glsl"

int g_slice;
#define TYN_MIN_MAX_FETCH(level, index) \
  imageLoad(min_max_tree, ivec2(tyn_min_max_level_offset(int(epipolar.tree.x), level) + (index), g_slice)).xy
#include "epipolar/min_max_tree.h"
#include "epipolar/slice_ray.glsl"

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

// A ray the march walks like the Reference (slice_ray.glsl) covers less than a cell of the line:
// the level-0 nodes over its cells bound every texel that walk meets (min_max_tree.h's footprint
// guarantee), so it is dark when its depth exceeds them all. The walk computes its depths from
// the same homogeneous ray per texel; the margin of 1e-6 (a few ulps of a depth in [0, 1]) keeps
// its rounding from finding a lit sliver where this test found none.
bool tyn_degenerate_ray_in_shadow(TynSliceRay sr) {
  int sample_count = int(epipolar.tree.x);
  float end = float(sample_count);
  float a = clamp(min(sr.ray.u_begin, sr.ray.u_end), 0.0, end);
  float b = clamp(max(sr.ray.u_begin, sr.ray.u_end), a, end);
  int first = min(int(floor(a)), sample_count - 1);
  int last = max(min(int(ceil(b)) - 1, sample_count - 1), first);
  vec2 bounds = tyn_min_max_merge(TYN_MIN_MAX_FETCH(0, first >> 1), TYN_MIN_MAX_FETCH(0, last >> 1));
  return bounds.y < 1.0 && min(sr.depths.x, sr.depths.y) > bounds.y + 1e-6;
}

// Every view ray starts at the camera, so where the camera itself is lit (or outside the map) no
// ray of the slice is in shadow along its whole length and the per-sample test below, a tree walk
// per marked sample in this serial per-slice loop, is skipped: in the common open-air view it
// costs nothing. Only a gate: the test it lets through is exact on its own.
bool tyn_camera_in_shadow(vec4 origin_direction) {
  vec4 h0 = frame.world_to_shadow[0] * vec4(frame.view_to_world[3].xyz, 1.0);
  if (h0.w <= 0.0 || abs(h0.x) > h0.w || abs(h0.y) > h0.w) return false;
  float size = float(frame.counts.w);
  vec2 camera_texels = (vec2(h0.x, h0.y) / h0.w * 0.5 + 0.5) * size;
  float u = tyn_min_max_u(vec2(origin_direction.x, origin_direction.y) * size,
                          tyn_min_max_step_texels(vec2(origin_direction.z, origin_direction.w)), camera_texels);
  int sample_count = int(epipolar.tree.x);
  vec2 bounds = TYN_MIN_MAX_FETCH(0, clamp(int(floor(u)), 0, sample_count - 1) >> 1);
  return bounds.y < 1.0 && h0.z / h0.w > bounds.y;
}

// True when the march would give sample k zero: its ray is inside the map (a directional light
// lights everything outside it) and the tree finds no lit point along it (min_max_tree.h's
// tyn_min_max_ray_shadowed, on the march's own ray, slice_ray.glsl). Needs the slice's tree.
bool tyn_sample_in_shadow(uint k, uint slice, vec4 origin_direction) {
  vec4 coordinates = imageLoad(epipolar_coordinates, ivec2(k, slice));
  if (coordinates.w < 0.5) return false;  // the march writes invalid samples itself
  vec3 dir = tyn_view_direction(vec2(coordinates.x, coordinates.y));
  TynSliceRay sr = tyn_slice_ray(origin_direction, frame.view_to_world[3].xyz, dir, coordinates.z);
  if (frame.counts.x == TYN_LIGHT_DIRECTIONAL) {
    if (!sr.inside || sr.t_in > 0.0 || sr.t_out < coordinates.z) return false;
  } else if (!sr.inside) {
    return true;  // a spot light's rays outside its frustum are not lit
  }
  if (tyn_slice_ray_degenerate(sr)) return tyn_degenerate_ray_in_shadow(sr);
  return tyn_min_max_ray_shadowed(int(epipolar.tree.x), int(epipolar.tree.y), sr.ray);
}

void main() {
  uint slice = gl_GlobalInvocationID.x;
  if (slice >= epipolar.counts.x) return;
  vec4 end_points = imageLoad(slice_end_points, ivec2(slice, 0));
  uint count = tyn_slice_sample_count(end_points, tyn_output_extent(), epipolar.counts.y, epipolar.params.x,
                                      epipolar.counts.z != 0u);
  // The whole-ray shadow test needs the slice's line and tree (directional and spot lights).
  vec4 origin_direction = epipolar.tree.z != 0u ? imageLoad(slice_uv, ivec2(slice, 0))
                                                 : vec4(TYN_EPIPOLAR_INVALID_COORD);
  g_slice = int(slice);
  bool tested = tyn_slice_valid(origin_direction) && tyn_camera_in_shadow(origin_direction);
  // Forward: each sample's left source (the last ray-marched sample at or before it). A sample in
  // shadow is marked with TYN_SHADOWED_FLAG until the backward walk.
  const uint TYN_SHADOWED_FLAG = 0x80000000u;
  uint left = 0u;
  uint marched = 0u;
  uint shadowed = 0u;
  for (uint k = 0u; k < epipolar.counts.y; ++k) {
    if (k >= count) {
      imageStore(interpolation_source, ivec2(k, slice), uvec4(TYN_EPIPOLAR_NO_SOURCE));
      continue;
    }
    uint flag = 0u;
    if (tyn_marched(k, count, slice)) {
      left = k;
      if (tested && tyn_sample_in_shadow(k, slice, origin_direction)) {
        imageStore(epipolar_scattering, ivec2(k, slice), vec4(0.0));
        flag = TYN_SHADOWED_FLAG;
        ++shadowed;
      } else {
        ++marched;
      }
    }
    imageStore(interpolation_source, ivec2(k, slice), uvec4(left | flag));
  }
  // Backward: the right source (the first ray-marched sample at or after it); the slice's
  // ray-marching samples go to the march list, in one range reserved by one atomic.
  uint entry = atomicAdd(march_count, marched);
  if (shadowed > 0u) atomicAdd(march_shadowed, shadowed);
  uint right = count > 0u ? count - 1u : 0u;
  for (uint i = 0u; i < count; ++i) {
    uint k = count - 1u - i;
    uint stored = imageLoad(interpolation_source, ivec2(k, slice)).x;
    uint left_of_k = stored & ~TYN_SHADOWED_FLAG;
    if (left_of_k == k) {
      right = k;
      if ((stored & TYN_SHADOWED_FLAG) == 0u) march_samples[entry++] = k | (slice << 16);
    }
    imageStore(interpolation_source, ivec2(k, slice), uvec4(left_of_k | (right << 16)));
  }
}
