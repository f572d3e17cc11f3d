// The medium and the light of a frame, evaluated at points along a view ray. Needs `frame` and
// `light_color` (common/light_color.glsl).
#ifndef TYNDALL_MEDIUM_GLSL
#define TYNDALL_MEDIUM_GLSL

#include "common/gauss_legendre.h"
#include "common/light_color.glsl"
#include "common/phase.h"

// The frame's light type (TYN_LIGHT_*), a specialisation constant: each pass that integrates light
// is built once per light type, so that it carries only its light's code. On a CPU driver
// (lavapipe) a uniform branch still costs both sides, and the spot's extra code in the same
// pipeline was measured to change a point light's result: taken then for a miscompile of
// unexecuted code, it fits lavapipe's loop budget, which loops under a branch not taken spend too
// (docs/REFERENCE.md "Loop budget on lavapipe").
layout(constant_id = 7) const uint TYN_LIGHT_TYPE = TYN_LIGHT_DIRECTIONAL;

// Σ_components σ_s · p(cos θ): the scattered fraction towards the camera, per channel. The loop's
// bound is a constant so that the compiler unrolls it: on lavapipe all loop iterations of one
// invocation share a budget of 65,535 (docs/REFERENCE.md "Loop budget on lavapipe"), and this runs
// at every quadrature node of a texel walk.
vec3 tyn_phase_weighted_scattering(float cos_theta) {
  vec3 sum = vec3(0.0);
  for (uint c = 0u; c < TYN_MAX_MEDIUM_COMPONENTS; ++c) {
    if (c < frame.medium_component_count) {
      sum += frame.medium[c].scattering *
             tyn_phase(frame.medium[c].phase_type, frame.medium[c].g, cos_theta);
    }
  }
  return sum;
}

// Hermite falloff between the outer (0) and inner (1) cone; GLSL's smoothstep is undefined when
// the two edges are equal, which is a valid hard-edged spot.
float tyn_spot_falloff(float cos_angle) {
  float cos_outer = frame.cos_outer_cone;
  float cos_inner = frame.cos_inner_cone;
  float x = clamp((cos_angle - cos_outer) / max(cos_inner - cos_outer, 1e-6), 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}

// What a local light's integrand needs of a view ray origin + t·dir, computed once per ray: the
// quadratures below evaluate it at hundreds of nodes on a coloured spot light's rays, where
// recomputing the light vector and the colour texture's projection from the point at each node
// would cost a quarter of the march (docs/EPIPOLAR.md "Coloured shafts").
struct TynLocalLightRay {
  vec3 dir;
  vec3 to_light;    // light position − origin
  vec4 clip;        // the origin in shadow map 0's clip space (the light-colour texture)
  vec4 clip_step;   // dir there (w component included: a spot's projection is perspective)
  // Whether the integrand takes the light-colour texture at each node: with one bound, unless the
  // caller multiplies the integral by a mean colour itself (the epipolar march's chunks).
  bool colored;
};

TynLocalLightRay tyn_local_light_ray(vec3 origin, vec3 dir) {
  TynLocalLightRay ray;
  ray.dir = dir;
  ray.to_light = frame.light_position - origin;
  ray.clip = frame.world_to_shadow[0] * vec4(origin, 1.0);
  ray.clip_step = frame.world_to_shadow[0] * vec4(dir, 0.0);
  ray.colored = tyn_has_light_color();
  return ray;
}

// Spot/point light: light reaching the point at t, scattered towards the camera along the ray and
// attenuated back to the camera over distance t: E(x) · Σσ_s p(cos θ) · e^{−σ_t t}, with
// E = I / d² · e^{−σ_t d} · falloff (one exponential for both paths, d + t).
vec3 tyn_local_light_integrand(TynLocalLightRay ray, float t) {
  vec3 to_light = ray.to_light - t * ray.dir;
  float d2 = max(dot(to_light, to_light), 1e-12);
  float d = sqrt(d2);
  vec3 omega_l = to_light / d;
  float falloff = TYN_LIGHT_TYPE == TYN_LIGHT_SPOT
                      ? tyn_spot_falloff(dot(-omega_l, frame.light_direction))
                      : 1.0;
  // A light-colour texture filters the light at every quadrature node: next to a spot light the
  // integrand peaks within a texel, where one colour per segment would be off.
  vec3 color = ray.colored ? tyn_light_color_clip(ray.clip + t * ray.clip_step) : vec3(1.0);
  return frame.light_radiance * color * (falloff / d2) *
         tyn_phase_weighted_scattering(dot(ray.dir, omega_l)) * exp(-frame.extinction * (d + t));
}

// ∫_a^b of the integrand above by the 4-point Gauss–Legendre rule on pieces no longer than half
// the distance to the light (common/gauss_legendre.h), so that the 1/d² peak near the light is
// resolved (relative error for 1/d² below 1.2·10⁻⁷). Needs a < b and a segment on which the
// integrand is smooth (tyn_local_light_segment_cut splits one at the spot cones first).
// `pairwise` (a constant at every call site): the loop takes one pair of symmetric nodes per
// iteration instead of all four: faster where a coloured spot light's march inlines this at
// several call sites of its loop, for the same L_in to the bit (docs/EPIPOLAR.md "Coloured
// shafts"). It costs two iterations of lavapipe's loop budget per piece instead of one
// (docs/REFERENCE.md "Loop budget on lavapipe"), which a texel walk past a point light with 4096²
// maps cannot spare: the Reference and the fix-up keep four nodes per iteration.
vec3 tyn_local_light_piece(TynLocalLightRay ray, float a, float b, const bool pairwise) {
  float t_closest = clamp(dot(ray.to_light, ray.dir), a, b);
  float d_near = max(length(t_closest * ray.dir - ray.to_light), 1e-4);
  int pieces = tyn_local_light_pieces(b - a, d_near);
  float h = (b - a) / float(pieces);
  float d0 = 0.5 * h * TYN_GAUSS4_X0;
  float d1 = 0.5 * h * TYN_GAUSS4_X1;
  vec3 sum = vec3(0.0);
  // The exit test at the end: one iteration of lavapipe's loop budget per pass, not two.
  if (pairwise) {
    for (int i = 0;;) {
      bool outer = (i & 1) == 1;
      float mid = a + (float(i >> 1) + 0.5) * h;
      float offset = outer ? d1 : d0;
      sum += (outer ? TYN_GAUSS4_W1 : TYN_GAUSS4_W0) *
             (tyn_local_light_integrand(ray, mid - offset) + tyn_local_light_integrand(ray, mid + offset));
      if (++i >= 2 * pieces) break;
    }
  } else {
    float mid = a + 0.5 * h;
    for (int i = 0;;) {
      sum += TYN_GAUSS4_W0 * (tyn_local_light_integrand(ray, mid - d0) + tyn_local_light_integrand(ray, mid + d0));
      sum += TYN_GAUSS4_W1 * (tyn_local_light_integrand(ray, mid - d1) + tyn_local_light_integrand(ray, mid + d1));
      if (++i >= pieces) break;
      mid = a + (float(i) + 0.5) * h;
    }
  }
  return sum * 0.5 * h;
}

// Roots of A t² + B t + C = 0 without cancellation; 1e30 for a missing root (beyond any ray, and
// no NaN, which a driver's fast maths may not keep).
vec2 tyn_quadratic_roots(float A, float B, float C) {
  const float none = 1e30;
  if (abs(A) <= 1e-12 * (abs(B) + abs(C))) return vec2(abs(B) > 0.0 ? -C / B : none, none);
  float disc = B * B - 4.0 * A * C;
  if (disc < 0.0) return vec2(none);
  float q = -0.5 * (B + (B >= 0.0 ? 1.0 : -1.0) * sqrt(disc));
  return vec2(q / A, q != 0.0 ? C / q : none);
}

// Where the ray origin + t·dir crosses the cone of half-angle acos(cos_angle) around the spot's
// axis (either nappe: a crossing of the back one is only an extra split). Solved around the ray's
// closest approach to the light, t_L + s: the coefficients then scale with that distance h rather
// than with the distance to the camera, which in float cancelled down to a few digits for rays
// passing near the light (the roots moved by more than the penumbra).
vec2 tyn_spot_cone_crossings(vec3 origin, vec3 dir, float cos_angle) {
  vec3 axis = frame.light_direction;
  float t_l = dot(frame.light_position - origin, dir);
  vec3 w = origin + t_l * dir - frame.light_position;  // ⟂ dir, |w| = h
  float wa = dot(w, axis);
  float va = dot(dir, axis);
  float c2 = cos_angle * cos_angle;
  vec2 s = tyn_quadratic_roots(va * va - c2, 2.0 * wa * va, wa * wa - c2 * dot(w, w));
  return vec2(s.x < 1e29 ? t_l + s.x : s.x, s.y < 1e29 ? t_l + s.y : s.y);
}

// Where a local light's integrand has kinks along the ray: a spot's smoothstep falloff at the
// inner and the outer cone (a quadrature across one is off by up to the whole penumbra), sorted;
// 1e30 for a cone the ray misses and for a point light. They depend on the ray only, so a march
// that integrates many parts of one ray computes them once.
vec4 tyn_local_light_cuts(vec3 origin, vec3 view_dir) {
  if (TYN_LIGHT_TYPE != TYN_LIGHT_SPOT) return vec4(1e30);
  vec4 c = vec4(tyn_spot_cone_crossings(origin, view_dir, frame.cos_outer_cone),
                tyn_spot_cone_crossings(origin, view_dir, frame.cos_inner_cone));
  // A sorting network.
  c = vec4(min(c.x, c.y), max(c.x, c.y), min(c.z, c.w), max(c.z, c.w));
  c = vec4(min(c.x, c.z), min(c.y, c.w), max(c.x, c.z), max(c.y, c.w));  // (lowest, ?, ?, highest)
  return vec4(c.x, min(c.y, c.z), max(c.y, c.z), c.w);
}

// ∫_a^b of a local light's in-scattering, the spot's falloff included: cut at the ray's kinks
// (`cuts`, tyn_local_light_cuts), each smooth span by tyn_local_light_piece. Only the spans that
// [a, b] overlaps are visited, one when no kink falls inside it: a march's short parts seldom
// hold one, and a CPU driver runs a branch for all lanes when any takes it, so five spans tested
// one by one cost five quadratures per part (stained-glass, lavapipe: see docs/EPIPOLAR.md).
vec3 tyn_local_light_segment_cut(TynLocalLightRay ray, vec4 cuts, float a, float b, const bool pairwise) {
  vec3 sum = vec3(0.0);
  float lo = a;
  // At most the four kinks split [a, b]: five spans.
  for (int span = 0; span < 5 && lo < b; ++span) {
    vec4 ahead = mix(vec4(b), cuts, greaterThan(cuts, vec4(lo)));
    float hi = min(min(min(ahead.x, ahead.y), min(ahead.z, ahead.w)), b);
    sum += tyn_local_light_piece(ray, lo, hi, pairwise);
    lo = hi;
  }
  return sum;
}

#endif
