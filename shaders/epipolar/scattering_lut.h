// In-scattering from a spot or point light along a lit section of a view ray, in O(1) from a
// precomputed table (yusov2013 "Solution to Inscattering Integral": point light – integral
// reformulation, look-up table, semi-analytical solution), with quadrature
// (common/local_light_integral.h) where the table is not accurate enough (the spot's penumbra, and
// sections whose two table values nearly cancel). What the table holds, its coordinates, its build
// and its accuracy: docs/derivations/scattering-lut.md. integration-tests/unit/test_scattering_lut.cpp
// checks everything here against double precision.
//
// ## Calling convention (a march shader)
//   per invocation:   TynMedium m = tyn_medium_from_frame();             (or built by hand)
//   per view ray:     TynLightRay r = tyn_light_ray(origin, view_dir, light_position);
//                     TynSpotCone cone = tyn_spot_cone(r, view_dir, light_direction, cos_outer, cos_inner);
//   per lit section [a, b] (view distances from the camera, a ≥ 0):
//                     L_in += light_radiance.rgb * (spot ? tyn_spot_segment(m, r, cone, a, b)
//                                                        : tyn_scattering_lut_segment(m, r, a, b));
// (tyn_point_light_lut_segment does it from `frame` for a point light's section.) Sections that touch
// should be merged first (as min_max_tree.h's accumulator does): one call per maximal lit interval.
// The table: a R32G32B32A32_SFLOAT image of TYN_SCATTERING_LUT_WIDTH × HEIGHT texels, written by
// a build pass (one invocation per row calling tyn_scattering_lut_build_row) whenever the medium
// changes, read by texelFetch or imageLoad: the bilinear filter is done here, in float (hardware
// filtering's few bits of weight would be too coarse).
//
// ## Accessors (GLSL has no pointers): define before including, as needed
//   TYN_SCATTERING_LUT_FETCH(texel)         vec3: RGB of the table texel ivec2(column, row)
//   TYN_SCATTERING_LUT_STORE(texel, value)  writes vec3 value to the table texel (build pass)
// Only the functions whose accessors are defined are compiled. In C++ each of these functions is a
// template whose first parameter is an accessor object with `vec3 fetch(ivec2) const` or
// `void store(ivec2, vec3) const`; the arguments after it are the same in both languages.
// Example (march pass, on one line):
//   #define TYN_SCATTERING_LUT_FETCH(texel) texelFetch(scattering_lut, texel, 0).rgb
// and (build pass):
//   #define TYN_SCATTERING_LUT_STORE(texel, value) imageStore(scattering_lut_image, texel, vec4(value, 0.0))
//   ... if (row < TYN_SCATTERING_LUT_HEIGHT) tyn_scattering_lut_build_row(row, tyn_medium_from_frame());
// GLSL helpers reading the global `frame` are compiled when TYN_SCATTERING_LUT_FRAME is defined.
#ifndef TYNDALL_SCATTERING_LUT_H
#define TYNDALL_SCATTERING_LUT_H

#include "common/local_light_integral.h"

#ifdef __cplusplus
#define TYN_SCATTERING_LUT_TEMPLATE template <class TynAccess>
#define TYN_SCATTERING_LUT_ACCESS const TynAccess &tyn_access,
#define TYN_SCATTERING_LUT_PASS tyn_access,
#define TYN_SCATTERING_LUT_FETCH(texel) tyn_access.fetch(texel)
#define TYN_SCATTERING_LUT_STORE(texel, value) tyn_access.store(texel, value)
#else
#define TYN_SCATTERING_LUT_TEMPLATE
#define TYN_SCATTERING_LUT_ACCESS
#define TYN_SCATTERING_LUT_PASS
#endif

TYN_BEGIN

// ---- Constants ----

// Table size: with the warps below, 1024 θ nodes keep the θ interpolation error ≤ 1.5e-4 (512: 6e-4)
// and 256 h nodes the h one ≤ 4e-4 for k ≤ 30 (measured in double; halving either quadruples it).
TYN_CONST int TYN_SCATTERING_LUT_WIDTH = 1024;
TYN_CONST int TYN_SCATTERING_LUT_HEIGHT = 256;
// k = σ h at the middle row (x = ½) of the h axis.
TYN_CONST float TYN_SCATTERING_LUT_K_MID = 1.0f;
// Sub-steps of the product trapezoid rule per node interval of the build, away from θ = π (error
// ∝ 1/substeps²; 4 gives ≤ 3e-5).
TYN_CONST int TYN_SCATTERING_LUT_BUILD_SUBSTEPS = 4;
// The cancellation guard: the table is used while F_a − F_b ≥ GUARD · F_a in every channel. The
// relative error of the difference is then at most ε (2 − GUARD) / GUARD, ε the lookup's relative
// error: ≤ 1e-3 at 0.25 (docs/derivations/scattering-lut.md "The segment" for how it was chosen).
TYN_CONST float TYN_SCATTERING_LUT_GUARD = 0.25f;

// σ_ref: the h axis is scaled by the largest extinction; 1 when there is none (Ĝ then does not
// depend on h and every row is the same).
TYN_FUNC float tyn_scattering_lut_sigma_ref(vec3 sigma_t) {
  float s = max(max(sigma_t.x, sigma_t.y), sigma_t.z);
  return s > 0.0f ? s : 1.0f;
}

// ---- Coordinates ----

// Row coordinate x ∈ [0, 1] of k_ref = σ_ref h (x = 1: h = ∞).
TYN_FUNC float tyn_scattering_lut_x(float k_ref) {
  float root = sqrt(max(k_ref, 0.0f) / TYN_SCATTERING_LUT_K_MID);
  return root / (1.0f + root);
}

// k_ref of a row coordinate x < 1.
TYN_FUNC float tyn_scattering_lut_k(float x) {
  float root = x / (1.0f - x);
  return TYN_SCATTERING_LUT_K_MID * root * root;
}

// ---- The normaliser N(k, u) (docs/derivations/scattering-lut.md "What a texel holds") ----

// r(z) = (1 + z) ψ(z), ψ(z) = 1 − z e^z E1(z) = ∫_0^∞ e^{−z y} / (1 + y)² dy, from Abramowitz &
// Stegun 5.1.53 (z < 1, error 2e-7) and 5.1.56 (z ≥ 1, error 2e-8), written in v = 1/z so that a
// huge z neither overflows nor cancels. r is only a normaliser (the same one builds and reads the
// table), so these errors do not reach the result; what matters is that r is smooth and carries
// the z ln z of the exact function (it removes the k ln k of Ĝ near k = 0).
TYN_FUNC float tyn_scattering_lut_r_small(float z) {
  float e1 = -log(max(z, 1e-30f)) +
             (-0.57721566f + z * (0.99999193f + z * (-0.24991055f + z * (0.05519968f +
              z * (-0.00976004f + z * 0.00107857f)))));
  return (1.0f + z) * (1.0f - z * exp(z) * e1);
}

TYN_FUNC float tyn_scattering_lut_r_large(float v) {
  // z e^z E1(z) = (z⁴ + a1 z³ + a2 z² + a3 z + a4) / (z⁴ + b1 z³ + b2 z² + b3 z + b4), so
  // ψ = 1 − that = ((b1 − a1) z³ + (b2 − a2) z² + (b3 − a3) z + (b4 − a4)) / (...), here in v = 1/z
  // with the differences precomputed. b1 − a1 = 0.9999936 is taken as 1, so that r(∞) = 1 exactly
  // (the table's limits Q = P at h = ∞ and θ = π rest on it); this moves r by < 3e-7 at z = 1.
  const float b1 = 9.5733223454f, b2 = 25.6329561486f, b3 = 21.0996530827f, b4 = 3.9584969228f;
  const float c2 = 7.5739391756f, c3 = 12.4648921902f, c4 = 3.6907231885f;  // b_i − a_i
  float den = 1.0f + v * (b1 + v * (b2 + v * (b3 + v * b4)));
  float num = 1.0f + v * (c2 + v * (c3 + v * c4));
  return (1.0f + v) * num / den;
}

// N for one channel; u > 0 (N = 0 at u = 0).
TYN_FUNC float tyn_scattering_lut_norm1(float k, float u) {
  if (u <= 0.0f) return 0.0f;
  float r = 2.0f * k < u ? tyn_scattering_lut_r_small(2.0f * k / u) : tyn_scattering_lut_r_large(u / (2.0f * k));
  float half_u = 0.5f * u;
  float sin_half = tyn_precise_sin(half_u);
  float shape = half_u * half_u / (sin_half * sin_half);  // (u/2)² / sin²(u/2) ∈ [1, π²/4]
  return u * u * r / (u + 2.0f * k * shape);
}

TYN_FUNC vec3 tyn_scattering_lut_norm(vec3 k, float u) {
  return vec3(tyn_scattering_lut_norm1(k.x, u), tyn_scattering_lut_norm1(k.y, u),
              tyn_scattering_lut_norm1(k.z, u));
}

// ---- Small exact-exponential helpers ----

// (1 − e^{−x}) / x, x ≥ 0 (series below 1e-2: truncation x⁴/120 < 1e-10).
TYN_FUNC float tyn_scattering_lut_e1(float x) {
  if (x < 1e-2f) return 1.0f - x * (0.5f - x * (1.0f / 6.0f - x * (1.0f / 24.0f)));
  return (1.0f - exp(-x)) / x;
}

// (1 − e^{−x} (1 + x)) / x², x ≥ 0 = ∫_0^1 s e^{−x s} ds (series below 0.1: truncation
// x⁵/5040 < 2e-9; the direct form loses 1e-7 / x² there).
TYN_FUNC float tyn_scattering_lut_e2(float x) {
  if (x < 0.1f) return 0.5f - x * (1.0f / 3.0f - x * (1.0f / 8.0f - x * (1.0f / 30.0f - x * (1.0f / 144.0f))));
  return (1.0f - exp(-x) * (1.0f + x)) / (x * x);
}

// ---- Building the table ----

// Sub-steps for the node interval `from_end` intervals before θ = π. Near π the nodes are evenly
// spaced in u, so the interval [J, J + 1]·δ has Δu/u = 1/J, and there g ∝ 1/τ² is far from linear
// in w: the relative error of Ĝ from the trapezoid is about 1/(2 S² J) (measured 3e-3 at J = 9 with
// S = 4). S = NEAR_PI / √J keeps it below 1e-4 for ~1300 extra sub-steps per row (5415 in all).
TYN_CONST float TYN_SCATTERING_LUT_BUILD_NEAR_PI = 71.0f;
TYN_FUNC int tyn_scattering_lut_build_substeps(int from_end) {
  return max(TYN_SCATTERING_LUT_BUILD_SUBSTEPS,
             int(ceil(TYN_SCATTERING_LUT_BUILD_NEAR_PI / sqrt(float(from_end)))));
}

#if defined(TYN_SCATTERING_LUT_STORE)
// Writes row `row` (h node) of the table for medium m: TYN_SCATTERING_LUT_WIDTH texels.
TYN_SCATTERING_LUT_TEMPLATE
TYN_FUNC void tyn_scattering_lut_build_row(TYN_SCATTERING_LUT_ACCESS int row, TynMedium m) {
  const int last = TYN_SCATTERING_LUT_WIDTH - 1;
  float x = float(row) / float(TYN_SCATTERING_LUT_HEIGHT - 1);
  bool infinite = row >= TYN_SCATTERING_LUT_HEIGHT - 1;  // h = ∞
  float h = infinite ? 0.0f : tyn_scattering_lut_k(x) / tyn_scattering_lut_sigma_ref(m.sigma_t);
  // h = ∞: channels with σ > 0 take the limit Q = P(θ); channels with σ = 0 keep k = 0.
  vec3 k = infinite ? vec3(0.0f) : m.sigma_t * h;
  vec3 limit_mask = infinite ? vec3(greaterThan(m.sigma_t, vec3(0.0f))) : vec3(0.0f);

  // θ = π: Q = P(−1) (the limit of Ĝ / N for every k).
  vec3 p_pi = tyn_medium_phase_scattering(m, -1.0f);
  TYN_SCATTERING_LUT_STORE(ivec2(last, row), p_pi);

  // Node last − 1: the interval to π is the single sub-step Ĝ = P(θ) N(k, u) (docs/derivations/scattering-lut.md "Building").
  vec2 angle_q = tyn_scattering_lut_angle(float(last - 1) / float(last));
  vec3 p_q = tyn_medium_phase_scattering_at(m, angle_q);
  vec3 big_g = p_q * tyn_scattering_lut_norm(k, angle_q.y);
  TYN_SCATTERING_LUT_STORE(ivec2(last - 1, row), p_q);  // Q = Ĝ / N = P there, and in the limit
  // g = P (1 + cos θ) = 2 P sin²(u/2) at the current sub-step end.
  float sin_half_q = tyn_precise_sin(0.5f * angle_q.y);
  vec3 g_q = p_q * (2.0f * sin_half_q * sin_half_q);

  for (int j = last - 2; j >= 0; --j) {
    vec2 angle_node = tyn_scattering_lut_angle(float(j) / float(last));
    // The interval's width, from whichever of θ and u is accurate on this side.
    float width = angle_node.x <= TYN_HALF_PI ? angle_q.x - angle_node.x : angle_node.y - angle_q.y;
    int substeps = tyn_scattering_lut_build_substeps(last - j);
    float sub = width / float(substeps);
    for (int i = substeps - 1; i >= 0; --i) {
      vec2 angle_p = i == 0 ? angle_node : vec2(angle_q.x - sub, angle_q.y + sub);
      float step_theta = i == 0 ? (angle_p.x <= TYN_HALF_PI ? angle_q.x - angle_p.x : angle_p.y - angle_q.y)
                                : sub;
      float cos_half_p = tyn_precise_sin(0.5f * angle_p.y);  // cos(θ/2) = sin(u/2), accurate near π
      float cos_half_q = tyn_precise_sin(0.5f * angle_q.y);
      // W = tan(θ_q/2) − tan(θ_p/2) = sin(Δθ/2) / (cos(θ_q/2) cos(θ_p/2)), without cancellation.
      float dw = tyn_precise_sin(0.5f * step_theta) / (cos_half_p * cos_half_q);
      vec3 p_p = tyn_medium_phase_scattering_at(m, angle_p);
      vec3 g_p = p_p * (2.0f * cos_half_p * cos_half_p);
      vec3 kw = k * dw;
      vec3 e1 = vec3(tyn_scattering_lut_e1(kw.x), tyn_scattering_lut_e1(kw.y), tyn_scattering_lut_e1(kw.z));
      vec3 e2 = vec3(tyn_scattering_lut_e2(kw.x), tyn_scattering_lut_e2(kw.y), tyn_scattering_lut_e2(kw.z));
      // ∫_0^W (g_p (1 − w/W) + g_q w/W) e^{−k w} dw = W [g_p (E1 − E2) + g_q E2].
      big_g = exp(-kw) * big_g + dw * (g_p * (e1 - e2) + g_q * e2);
      angle_q = angle_p;
      g_q = g_p;
      if (i == 0) {
        vec3 q = big_g / tyn_scattering_lut_norm(k, angle_p.y);
        TYN_SCATTERING_LUT_STORE(ivec2(j, row), mix(q, p_p, limit_mask));
      }
    }
  }
}
#endif

// ---- Reading the table ----

#if defined(TYN_SCATTERING_LUT_FETCH)
// Q at table coordinates (x, y) ∈ [0, 1]², bilinear between the four nodes around it, in float.
TYN_SCATTERING_LUT_TEMPLATE
TYN_FUNC vec3 tyn_scattering_lut_lookup(TYN_SCATTERING_LUT_ACCESS float x, float y) {
  float fx = clamp(x, 0.0f, 1.0f) * float(TYN_SCATTERING_LUT_HEIGHT - 1);
  float fy = clamp(y, 0.0f, 1.0f) * float(TYN_SCATTERING_LUT_WIDTH - 1);
  int i = min(int(fx), TYN_SCATTERING_LUT_HEIGHT - 2);
  int j = min(int(fy), TYN_SCATTERING_LUT_WIDTH - 2);
  float wx = fx - float(i);
  float wy = fy - float(j);
  vec3 low = mix(TYN_SCATTERING_LUT_FETCH(ivec2(j, i)), TYN_SCATTERING_LUT_FETCH(ivec2(j + 1, i)), wy);
  vec3 high = mix(TYN_SCATTERING_LUT_FETCH(ivec2(j, i + 1)), TYN_SCATTERING_LUT_FETCH(ivec2(j + 1, i + 1)), wy);
  return mix(low, high, wx);
}

// Ĝ(h, θ(t)) from the table: Q · N(σ h, u).
TYN_SCATTERING_LUT_TEMPLATE
TYN_FUNC vec3 tyn_scattering_lut_g(TYN_SCATTERING_LUT_ACCESS TynMedium m, TynLightRay r, TynLightPoint p) {
  float x = tyn_scattering_lut_x(tyn_scattering_lut_sigma_ref(m.sigma_t) * r.h);
  vec3 q = tyn_scattering_lut_lookup(TYN_SCATTERING_LUT_PASS x, tyn_scattering_lut_y(p.theta, p.u));
  return q * tyn_scattering_lut_norm(m.sigma_t * r.h, p.u);
}

// F(t) = e^{−σ (t + d)} Ĝ(h, θ(t)) = h ∫_t^∞ P e^{−σ(t' + d')} / d'² dt' (falloff 1). Exponent ≤ 0.
TYN_SCATTERING_LUT_TEMPLATE
TYN_FUNC vec3 tyn_scattering_lut_tail(TYN_SCATTERING_LUT_ACCESS TynMedium m, TynLightRay r, TynLightPoint p) {
  return exp(-m.sigma_t * p.path) * tyn_scattering_lut_g(TYN_SCATTERING_LUT_PASS m, r, p);
}
#endif

// ---- Segments ----

#if defined(TYN_SCATTERING_LUT_FETCH)
// S(t_a, t_b) with falloff 1 (point light, inside a spot's inner cone): the table's difference
// (F(t_a) − F(t_b)) / h, or quadrature where it would cancel (F_a − F_b < guard · F_a in a
// channel); guard < 0 never falls back (tests measure what the guard buys).
TYN_SCATTERING_LUT_TEMPLATE
TYN_FUNC vec3 tyn_scattering_lut_segment_guarded(TYN_SCATTERING_LUT_ACCESS TynMedium m, TynLightRay r,
                                                 float ta, float tb, float guard) {
  if (!(tb > ta)) return vec3(0.0f);
  vec3 fa = tyn_scattering_lut_tail(TYN_SCATTERING_LUT_PASS m, r, tyn_light_point(r, ta));
  vec3 fb = tyn_scattering_lut_tail(TYN_SCATTERING_LUT_PASS m, r, tyn_light_point(r, tb));
  vec3 diff = fa - fb;
  if (guard >= 0.0f && any(lessThan(diff, guard * fa))) {
    TynSpotCone none;
    none.along = 0.0f;
    none.across = 0.0f;
    none.cos_outer = 0.0f;
    none.cos_inner = 1.0f;
    return tyn_local_light_quadrature(m, r, none, false, ta, tb);
  }
  return diff / r.h;
}

// S(t_a, t_b) for a point light (falloff 1) over a lit section, 0 ≤ t_a ≤ t_b.
TYN_SCATTERING_LUT_TEMPLATE
TYN_FUNC vec3 tyn_scattering_lut_segment(TYN_SCATTERING_LUT_ACCESS TynMedium m, TynLightRay r, float ta, float tb) {
  return tyn_scattering_lut_segment_guarded(TYN_SCATTERING_LUT_PASS m, r, ta, tb, TYN_SCATTERING_LUT_GUARD);
}

// A view ray's intervals inside the spot's outer and inner cones, whole (a cone meets a line in
// one interval): clipping them to a section gives what tyn_spot_cone_interval gives for it, so a
// march computes them once per ray instead of twice per lit section.
struct TynSpotRay {
  vec2 outer;
  vec2 inner;
};

TYN_FUNC TynSpotRay tyn_spot_ray(TynLightRay r, TynSpotCone cone) {
  const float unbounded = 3.0e38f;
  TynSpotRay s;
  s.outer = tyn_spot_cone_interval(r, cone, cone.cos_outer, -unbounded, unbounded);
  s.inner = tyn_spot_cone_interval(r, cone, cone.cos_inner, -unbounded, unbounded);
  return s;
}

// S(t_a, t_b) for a spot light over a lit section, given its ray's cone intervals: the table inside
// the inner cone, quadrature with the falloff in the penumbra, nothing outside the outer cone.
TYN_SCATTERING_LUT_TEMPLATE
TYN_FUNC vec3 tyn_spot_ray_segment(TYN_SCATTERING_LUT_ACCESS TynMedium m, TynLightRay r, TynSpotCone cone,
                                   TynSpotRay spot, float ta, float tb) {
  vec2 outer = vec2(max(ta, spot.outer.x), min(tb, spot.outer.y));
  if (!(outer.y > outer.x)) return vec3(0.0f);
  vec2 inner = vec2(max(outer.x, spot.inner.x), min(outer.y, spot.inner.y));
  bool has_inner = inner.y > inner.x;
  // The penumbra's pieces before and after the inner cone (the whole section without one), each
  // integrated only when not empty, in one loop: most lit sections lie inside the inner cone and
  // run no quadrature, and where SIMD lanes run both sides of a branch (a CPU driver) the lanes
  // share one loop instead of three calls.
  vec2 before = has_inner ? vec2(outer.x, inner.x) : outer;
  vec2 after = has_inner ? vec2(inner.y, outer.y) : vec2(0.0f);
  bool needs_before = before.y > before.x;
  int count = (needs_before ? 1 : 0) + (after.y > after.x ? 1 : 0);
  vec3 q_before = vec3(0.0f);
  vec3 q_after = vec3(0.0f);
  for (int i = 0; i < count; ++i) {
    bool is_before = i == 0 && needs_before;
    vec2 piece = is_before ? before : after;
    vec3 q = tyn_local_light_quadrature(m, r, cone, true, piece.x, piece.y);
    if (is_before) {
      q_before = q;
    } else {
      q_after = q;
    }
  }
  if (!has_inner) return q_before;
  return q_before + tyn_scattering_lut_segment(TYN_SCATTERING_LUT_PASS m, r, inner.x, inner.y) + q_after;
}

// The same, the cone intervals found for this section alone.
TYN_SCATTERING_LUT_TEMPLATE
TYN_FUNC vec3 tyn_spot_segment(TYN_SCATTERING_LUT_ACCESS TynMedium m, TynLightRay r, TynSpotCone cone,
                               float ta, float tb) {
  return tyn_spot_ray_segment(TYN_SCATTERING_LUT_PASS m, r, cone, tyn_spot_ray(r, cone), ta, tb);
}
#endif

TYN_END

// ---- GLSL helpers reading the global `frame` (define TYN_SCATTERING_LUT_FRAME after declaring it) ----
#if defined(TYN_SCATTERING_LUT_FRAME) && !defined(__cplusplus)
TynMedium tyn_medium_from_frame() {
  TynMedium m;
  m.sigma_t = frame.extinction;
  m.components = frame.medium_component_count;
  for (uint c = 0u; c < TYN_MAX_MEDIUM_COMPONENTS; ++c) {
    m.scattering[c] = vec4(frame.medium[c].scattering, frame.medium[c].g);
    m.phase_type[c] = frame.medium[c].phase_type;
  }
  return m;
}

TynSpotCone tyn_spot_cone_from_frame(TynLightRay r, vec3 view_dir) {
  return tyn_spot_cone(r, view_dir, frame.light_direction, frame.cos_outer_cone,
                       frame.cos_inner_cone);
}

#if defined(TYN_SCATTERING_LUT_FETCH) && defined(TYN_WALK_LIT_SECTIONS)
// L_in from the lit section [a, b] of the view ray (origin, unit view_dir) for the frame's point
// light, colour·intensity included: the texel walk's lit sections (common/texel_walk.glsl,
// TYN_WALK_LIT_SECTIONS, which merges them for point lights only). Sections are few per ray, so
// the medium and the ray are set up per call; the march along a slice hoists them out of its loop.
vec3 tyn_point_light_lut_segment(vec3 origin, vec3 view_dir, float a, float b) {
  TynMedium m = tyn_medium_from_frame();
  TynLightRay r = tyn_light_ray(origin, view_dir, frame.light_position);
  return frame.light_radiance * tyn_scattering_lut_segment(m, r, a, b);
}
#endif
#endif

#ifdef __cplusplus
#undef TYN_SCATTERING_LUT_FETCH
#undef TYN_SCATTERING_LUT_STORE
#endif
#undef TYN_SCATTERING_LUT_TEMPLATE
#undef TYN_SCATTERING_LUT_ACCESS
#undef TYN_SCATTERING_LUT_PASS

#endif
