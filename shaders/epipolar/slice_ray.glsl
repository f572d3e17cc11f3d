// An epipolar sample's view ray along its slice's line in one shadow map (yusov2013 "1D min/max
// binary trees"; a cascade's stretch of the ray along that cascade's line in its cascaded
// version): every view ray of a slice projects onto that line, so the ray is described by
// the line's 1D parameter u (texel units, min_max_tree.h) and its shadow depth and view distance
// at both ends of its part inside the map. Shared by the march (march.comp) and the refinement's
// whole-ray shadow test (shadow_test.comp), so that a sample the test finds in shadow is one the march
// would have given zero to the bit. Include after epipolar/min_max_tree.h.
#ifndef TYNDALL_SLICE_RAY_GLSL
#define TYNDALL_SLICE_RAY_GLSL

#include "common/shadow_ray.glsl"

struct TynSliceRay {
  vec2 origin_texels;  // the slice line's origin and step (max-norm one texel), texel units
  vec2 step_texels;
  float t_in;          // the part of [0, s] inside the map (a directional light's square slab, a
  float t_out;         // spot light's frustum); outside it a directional light is unshadowed and a
  bool inside;         // spot light does not reach
  // Homogeneous texel coordinates of the ray, relative to the line's origin, projected on the
  // step: u = (a0 + a1 t) / (p + q t), as (a0, a1, p, q); through a projective shadow matrix u is a
  // linear-fractional function of the view distance.
  vec4 u_of_t;
  TynMinMaxRay ray;    // the part inside, when `inside`
  vec2 depths;         // its shadow depths at t_in and t_out (`ray` keeps only one when u does not move)
};

// The stretch [t0, t1] of the view ray from `origin` along unit `dir`, in shadow map `map`, on the
// slice whose line in that map's UV is origin_direction (slice_setup.comp).
TynSliceRay tyn_slice_ray(uint map, vec4 origin_direction, vec3 origin, vec3 dir, float t0, float t1) {
  float size = float(frame.shadow_map_size);
  TynSliceRay sr;
  sr.origin_texels = vec2(origin_direction.x, origin_direction.y) * size;
  sr.step_texels = tyn_min_max_step_texels(vec2(origin_direction.z, origin_direction.w));
  TynShadowRay r = tyn_shadow_ray(map, origin, dir);
  sr.t_in = t0;
  sr.t_out = t1;
  sr.inside = tyn_clip_to_shadow_map(r, sr.t_in, sr.t_out);
  sr.u_of_t = vec4(0.0);
  sr.ray = tyn_min_max_ray(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, frame.extinction);
  sr.depths = vec2(0.0);
  if (sr.inside) {
    float inv_step2 = 1.0 / dot(sr.step_texels, sr.step_texels);
    vec2 rel0 = (vec2(r.h0.x, r.h0.y) * 0.5 + 0.5 * r.h0.w) * size - r.h0.w * sr.origin_texels;
    vec2 rel1 = (vec2(r.h1.x, r.h1.y) * 0.5 + 0.5 * r.h1.w) * size - r.h1.w * sr.origin_texels;
    sr.u_of_t = vec4(dot(rel0, sr.step_texels) * inv_step2, dot(rel1, sr.step_texels) * inv_step2, r.h0.w, r.h1.w);
    vec4 h_in = r.h0 + sr.t_in * r.h1;
    vec4 h_out = r.h0 + sr.t_out * r.h1;
    float u_in = (sr.u_of_t.x + sr.u_of_t.y * sr.t_in) / h_in.w;
    float u_out = (sr.u_of_t.x + sr.u_of_t.y * sr.t_out) / h_out.w;
    sr.depths = vec2(h_in.z / h_in.w, h_out.z / h_out.w);
    sr.ray = tyn_min_max_ray(u_in, u_out, sr.depths.x, sr.depths.y, sr.t_in, sr.t_out, frame.extinction);
  }
  return sr;
}

// A ray (nearly) along the light projects onto less than one cell of the line: its 1D
// parametrisation degenerates (dt/du grows without bound, and a ray exactly along the light has an
// empty u range, which the 1D march would give no light at all), so the march walks it texel by
// texel like the Reference instead (a few texels), and the refinement never calls it shadowed from
// the tree. The sample at an on-screen epipole is one; short rays to near surfaces are others.
bool tyn_slice_ray_degenerate(TynSliceRay sr) {
  return sr.inside && abs(sr.ray.u_end - sr.ray.u_begin) < 1.0;
}

#endif
