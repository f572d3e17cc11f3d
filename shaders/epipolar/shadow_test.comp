#version 460
// The whole-ray shadow test (DESIGN.md "Model only what the scene requires"): before the march,
// each sample the refinement listed asks its slice's min/max trees (one per cascade) whether its
// whole view ray is in shadow; such a sample gets L_in = 0 here, exactly what the march would give
// it, and the others are listed again, after the refinement's entries, for the march. When the
// light reaches no visible point (behind a wall covering the screen) nothing is listed and the
// march's indirect dispatch runs no work: the decision needs the shadow map, so it is made on the
// GPU. One thread per listed sample, like the march (the same walk in the refinement's
// one-thread-per-slice loop cost more refinement time than it saved march time on lavapipe). The
// slice setup skips the pass when the camera is lit; the test's last workgroup starts the march
// (dispatch_chain.glsl).
#extension GL_GOOGLE_include_directive : require
#include "epipolar/epipolar_common.glsl"

int g_tree_row;  // the tree being read (tyn_epipolar_tree_row)
#define TYN_MIN_MAX_FETCH(level, index) \
  imageLoad(min_max_tree, ivec2(tyn_min_max_level_offset(int(epipolar.tree_samples), level) + (index), g_tree_row)).xy
#include "epipolar/min_max_tree.h"
#include "epipolar/slice_ray.glsl"
#include "epipolar/dispatch_chain.glsl"

layout(local_size_x = TYN_EPIPOLAR_MARCH_GROUP) in;

// A ray the march walks like the Reference (slice_ray.glsl) covers less than a cell of the line:
// the level-0 nodes over its cells bound every texel that walk meets (min_max_tree.h's footprint
// guarantee), so it is dark when its depth exceeds them all. The walk computes its depths from
// the same homogeneous ray per texel; the margin of 1e-6 (a few ulps of a depth in [0, 1]) keeps
// its rounding from finding a lit sliver where this test found none.
bool tyn_degenerate_ray_in_shadow(TynSliceRay sr) {
  int sample_count = int(epipolar.tree_samples);
  float end = float(sample_count);
  float a = clamp(min(sr.ray.u_begin, sr.ray.u_end), 0.0, end);
  float b = clamp(max(sr.ray.u_begin, sr.ray.u_end), a, end);
  int first = min(int(floor(a)), sample_count - 1);
  int last = max(min(int(ceil(b)) - 1, sample_count - 1), first);
  vec2 bounds = tyn_min_max_merge(TYN_MIN_MAX_FETCH(0, first >> 1), TYN_MIN_MAX_FETCH(0, last >> 1));
  return bounds.y < 1.0 && min(sr.depths.x, sr.depths.y) > bounds.y + 1e-6;
}

// True when the march would give the stretch [t0, t1] of the ray zero along the slice's line in
// map `map`: the stretch is inside the map (a directional light lights everything outside it) and
// the tree finds no lit point along it (min_max_tree.h's tyn_min_max_ray_shadowed, on the march's
// own ray, slice_ray.glsl). A slice without a line there is walked by the march: not decided here.
bool tyn_stretch_in_shadow(int slice, uint map, vec3 origin, vec3 dir, float t0, float t1) {
  vec4 origin_direction = imageLoad(slice_uv, ivec2(slice, map));
  if (!tyn_slice_valid(origin_direction)) return false;
  g_tree_row = tyn_epipolar_tree_row(slice, map);
  TynSliceRay sr = tyn_slice_ray(map, origin_direction, origin, dir, t0, t1);
  if (frame.light_type == TYN_LIGHT_DIRECTIONAL) {
    if (!sr.inside || sr.t_in > t0 || sr.t_out < t1) return false;
  } else if (!sr.inside) {
    return true;  // a spot light's rays outside its frustum are not lit
  }
  if (tyn_slice_ray_degenerate(sr)) return tyn_degenerate_ray_in_shadow(sr);
  // A ray whose far end may be lit is not dark: one node read saves the walk for most rays that
  // leave the camera's shadow (a safe rejection; only "dark" needs the walk's proof).
  int sample_count = int(epipolar.tree_samples);
  float u_end = clamp(sr.ray.u_end, 0.0, float(sample_count));
  vec2 end_bounds = TYN_MIN_MAX_FETCH(0, min(int(floor(u_end)), sample_count - 1) >> 1);
  if (end_bounds.y >= 1.0 || tyn_min_max_depth_at(sr.ray, u_end) <= end_bounds.y) return false;
  return tyn_min_max_ray_shadowed(sample_count, int(epipolar.tree_top_level), sr.ray);
}

// True when the march would give the sample zero: every stretch of its ray (one per cascade a
// directional light has; the whole ray otherwise) is in shadow. Needs the slice's trees.
bool tyn_sample_in_shadow(uvec2 id) {
  vec4 coordinates = imageLoad(epipolar_coordinates, ivec2(id));
  if (coordinates.w < 0.5) return false;  // the march writes invalid samples itself
  vec3 origin = frame.view_to_world[3].xyz;
  vec3 dir = tyn_view_direction(vec2(coordinates.x, coordinates.y));
  float s = coordinates.z;
  if (frame.light_type != TYN_LIGHT_DIRECTIONAL) return tyn_stretch_in_shadow(int(id.y), 0u, origin, dir, 0.0, s);
  bool any_stretch = false;
  for (uint map = 0u; map < frame.shadow_map_count; ++map) {
    vec2 stretch = tyn_cascade_stretch(map, origin, dir, s);
    if (!(stretch.y > stretch.x)) continue;
    if (!tyn_stretch_in_shadow(int(id.y), map, origin, dir, stretch.x, stretch.y)) return false;
    any_stretch = true;
  }
  return any_stretch;
}

// The kept entries are appended per workgroup: one global atomic per group, not per entry.
shared uint tyn_kept;
shared uint tyn_base;

void main() {
  if (gl_LocalInvocationIndex == 0u) tyn_kept = 0u;
  barrier();
  // The refinement's entries are [march_first, march_round_end) (slice_setup.comp).
  uint entry = march_first + gl_GlobalInvocationID.x;
  if (gl_GlobalInvocationID.x == 0u) march_listed = march_round_end;
  bool listed = entry < march_round_end;
  uint packed = listed ? march_samples[entry] : 0u;
  bool kept = false;
  if (listed) {
    uvec2 id = uvec2(packed & 0xffffu, packed >> 16);  // x: sample, y: slice
    if (tyn_sample_in_shadow(id)) {
      // Alpha 1 marks it for the samples debug view (debug_samples.comp); L_in readers take .rgb.
      imageStore(epipolar_scattering, ivec2(id), vec4(0.0, 0.0, 0.0, 1.0));
      atomicAdd(march_shadowed, 1u);
    } else {
      kept = true;
    }
  }
  uint slot = kept ? atomicAdd(tyn_kept, 1u) : 0u;
  barrier();
  if (gl_LocalInvocationIndex == 0u) tyn_base = atomicAdd(march_count, tyn_kept);
  barrier();
  if (kept) march_samples[tyn_base + slot] = packed;
  if (tyn_last_group(TYN_DONE_SHADOW_TEST)) tyn_start_march_round(0u);
}
