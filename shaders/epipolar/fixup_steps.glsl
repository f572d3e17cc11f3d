// The epipolar fix-up's stepped march (EpipolarSettings::fixupSteps > 0), yusov2013's fix-up
// "using fewer steps": the ray's stretch in a shadow map is cut into N steps of equal length in the
// map (along its projected line's main axis), and each step takes its verdict from the one texel
// under its middle. Equal in the map, not in t: a directional light's map is affine in t, so there
// the two are the same; a local light's projection moves fastest where the ray passes the light,
// where its in-scattering peaks (1/d²), and steps equal in t would put one or two verdicts across
// that whole peak.
// Within a step, its texel's depth is compared with the ray exactly (tyn_texel_lit_part, the
// Reference's test), so a step whose texel is an occluder the ray passes behind part-way is lit up
// to the crossing. What the stepped march cannot see is any other texel the step crosses: an
// occluder narrower than a step may be missed, or one under the middle taken for the whole step.
// A directional light's lit parts are integrated in closed form, a local light's as below. A pixel
// then costs N texel reads instead of one per texel its ray crosses (about the map's side: the
// fix-up's pixels sit at depth breaks, and their rays mostly cross the whole map).
// This is the texel walk's TYN_WALK_IN_STEPS hook (common/texel_walk.glsl).
#ifndef TYNDALL_FIXUP_STEPS_GLSL
#define TYNDALL_FIXUP_STEPS_GLSL

#include "common/texel_walk.glsl"

// The steps of the pixel being fixed up: EpipolarSettings::fixupSteps, or 0 (the texel walk) where
// fixup.comp finds that steps cannot follow the pixel's in-scattering.
uint tyn_fixup_pixel_steps = 0u;
uint tyn_walk_steps() { return tyn_fixup_pixel_steps; }

// Where step `i` of `steps` begins on [t0, t1] (i = steps: t1): where the ray's clip coordinate
// along `axis` has gone i/steps of the way from c0 to c1; i/steps of [t0, t1] instead when the ray
// moves less than a texel in the map (`moves` false). Clamped, so that rounding keeps the steps in
// order and inside [t0, t1].
float tyn_step_end(TynShadowRay r, float t0, float t1, uint i, uint steps, int axis, float c0, float c1,
                   bool moves) {
  if (i == 0u) return t0;
  if (i >= steps) return t1;
  float f = float(i) / float(steps);
  float t = moves ? tyn_edge_crossing(r.h0[axis], r.h1[axis], r.h0.w, r.h1.w, mix(c0, c1, f)) : mix(t0, t1, f);
  return clamp(t, t0, t1);
}

vec3 tyn_step_shadow_map(uint map, vec3 origin, vec3 dir, float t0, float t1, uint part, uint parts,
                         bool directional) {
  TynShadowRay r = tyn_shadow_ray(map, origin, dir);
  int size = int(frame.shadow_map_size);
  uint steps = tyn_walk_steps();
  // The projected line's main axis in the map, and its clip coordinate at both ends: step i ends
  // where the ray's coordinate on that axis has gone i/N of the way (tyn_edge_crossing solves the
  // linear-fractional projection for t). A line shorter than a texel steps equally in t.
  vec4 h_begin = r.h0 + t0 * r.h1;
  vec4 h_end = r.h0 + t1 * r.h1;
  vec2 c0 = h_begin.xy / h_begin.w;
  vec2 c1 = h_end.xy / h_end.w;
  int axis = abs(c1.x - c0.x) >= abs(c1.y - c0.y) ? 0 : 1;
  bool moves = abs(c1[axis] - c0[axis]) * 0.5 * float(size) >= 1.0;
  vec4 cuts = directional ? vec4(0.0) : tyn_local_light_cuts(origin, dir);
  TynLocalLightRay local_ray = tyn_local_light_ray(origin, dir);
  // A point light's consecutive lit parts are merged into runs and each run integrated from the
  // semi-analytic table, as the texel walk's sections (common/texel_walk.glsl TYN_WALK_LIT_SECTIONS).
  // A spot light's (or a coloured light's) lit parts take the quadrature one step at a time: over a
  // merged run that passes the light, its 64 pieces cannot follow the 1/d² peak.
  bool sections = TYN_LIGHT_TYPE == TYN_LIGHT_POINT && !tyn_has_light_color();
  vec2 run = vec2(t0);  // the lit run being merged: [x, y), empty while y ≤ x
  vec3 sum = vec3(0.0);
  for (uint i = part * steps / parts; i < (part + 1u) * steps / parts; ++i) {
    // The same expression for a step's start and the previous step's end, so that a run's parts
    // join exactly; the first step starts at t0, the last ends at t1.
    float a = tyn_step_end(r, t0, t1, i, steps, axis, c0[axis], c1[axis], moves);
    float b = tyn_step_end(r, t0, t1, i + 1u, steps, axis, c0[axis], c1[axis], moves);
    vec4 h = r.h0 + (0.5 * (a + b)) * r.h1;
    ivec2 texel = clamp(tyn_clip_texel(h, float(size)), ivec2(0), ivec2(size - 1));
    vec2 lit = tyn_texel_lit_part(r, tyn_shadow_texel(map, texel), a, b);
    if (lit.y <= lit.x) continue;
    if (directional) {
      // As the texel walk: a light-colour texture filtered at the lit part's middle.
      sum += tyn_light_color_at(origin + dir * (0.5 * (lit.x + lit.y))) *
             tyn_transmittance_integral(lit.x, lit.y, frame.extinction);
    } else if (sections) {
      if (lit.x != run.y) {
        if (run.y > run.x) sum += tyn_point_light_lut_segment(origin, dir, run.x, run.y);
        run.x = lit.x;
      }
      run.y = lit.y;
    } else {
      sum += tyn_local_light_segment_cut(local_ray, cuts, lit.x, lit.y, false);
    }
  }
  if (sections && run.y > run.x) sum += tyn_point_light_lut_segment(origin, dir, run.x, run.y);
  return sum;
}

#endif
