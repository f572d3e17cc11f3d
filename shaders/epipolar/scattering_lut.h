// In-scattering from a spot or point light along a lit section of a view ray, in O(1) from a
// precomputed table (yusov2013 "Solution to Inscattering Integral": point light – integral
// reformulation, look-up table, semi-analytical solution), with quadrature where the table is not
// accurate enough (the spot's penumbra, and sections whose two table values nearly cancel).
// integration-tests/unit/test_scattering_lut.cpp checks everything here against double precision.
//
// ## What is computed (DESIGN.md "Radiometry", per RGB channel, per unit of light colour·intensity)
//   S(t_a, t_b) = ∫_{t_a}^{t_b} P(cos θ) · falloff · e^{−σ_t (t + d)} / d² dt,  P = Σ_c σ_s,c p_c
// along x(t) = C + t v (|v| = 1, 0 ≤ t_a ≤ t_b), light at L, d = |L − x|, cos θ = dot(v, ω_l), ω_l the
// unit vector from x towards L. The caller multiplies by the light's colour·intensity; visibility
// is the march's business (it passes lit sections only).
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
// The table: a R32G32B32A32_SFLOAT image of TYN_SCATTERING_LUT_WIDTH × HEIGHT = 1024 × 256 texels
// (4 MiB), written by a build pass (one invocation per row calling tyn_scattering_lut_build_row,
// e.g. local_size_x = 64 and 4 groups) whenever the medium changes, read by texelFetch (the filter
// is done here, in float; any sampler, the mode is irrelevant; a storage image with imageLoad works
// too). Hardware bilinear filtering is NOT used: it interpolates with subTexelPrecisionBits of weight
// (4 guaranteed, 8 typical), an error of up to 1/32 (1/512) of the step between neighbouring
// texels, i.e. up to 3e-3 (2e-4) of Ĝ where it changes by 10% per texel, which the difference
// F(t_a) − F(t_b) multiplies by up to 7 (see TYN_SCATTERING_LUT_GUARD). Half floats would add 5e-4
// (2^-11) of rounding to every value.
//
// ## The reformulation (checked numerically in the unit test)
// t_L = dot(L − C, v) (the foot: closest point of the line to L), h = |L − C − t_L v|,
// s = t − t_L. Then cos θ = −s/d, sin θ = h/d, so s = −h cot θ, d = h / sin θ and
// t + d = t_L + h tan(θ/2); θ ∈ (0, π) grows with t, and dt / d² = dθ / h. With falloff = 1:
//   S = (1/h) ∫_{θ_a}^{θ_b} P(cos θ) e^{−σ (t_L + h tan(θ/2))} dθ = (F(t_a) − F(t_b)) / h,
//   F(t) = e^{−σ (t + d)} · Ĝ(h, θ(t)),
//   Ĝ(h, θ0) = ∫_{θ0}^{π} P(cos θ) e^{−σ h [tan(θ/2) − tan(θ0/2)]} dθ     (yusov2013's relative
// attenuation: every exponent ≤ 0, so nothing overflows however dense the medium or far the light).
// Ĝ depends on h only through k = σ h per channel.
//
// ## The table: what a texel holds
// Texel (j, i) (column j = θ node, row i = h node) holds, per channel, Q = Ĝ(h_i, θ_j) / N(k, u_j),
// u = π − θ, k = σ h, with the normaliser
//   N(k, u) = u² r(2k/u) / (u + 2k · (u/2)² / sin²(u/2)),  r(z) = (1 + z) (1 − z e^z E1(z)).
// N equals ∫_{θ0}^{π} e^{−k(tan(θ/2) − tan(θ0/2))} dθ (Ĝ for P ≡ 1) at k = 0, to O(u²) near θ = π and
// to leading order as k → ∞, and is within 20% of it elsewhere; dividing it out leaves Q ≈ a
// weighted mean of P, smooth in both coordinates. Without it Ĝ falls like u²/k near θ = π and like
// 1/k at large k, and bilinear interpolation of Ĝ itself is off by up to 100% in those cells
// (measured). Limits: Q = P(θ) on the last row (h = ∞, for channels with σ > 0) and Q = P(−1) on the
// last column (θ = π). Alpha is written 0 and unused.
//
// ## Coordinates (node i of n at coordinate i / (n − 1); rows are h, columns θ)
//   h axis: x = √κ / (1 + √κ), κ = σ_ref h / TYN_SCATTERING_LUT_K_MID, σ_ref = max channel of σ_t
//   (1 when σ_t = 0: Ĝ then does not depend on h and every row is the same); x = 1 is h = ∞. Ĝ
//   changes with log k over k ∈ [1e-2, 1e3] (phase lobes seen through the exponential), and √κ
//   spreads log k around K_MID; near k = 0 it keeps k ∝ x², which flattens the k ln k that a
//   backward lobe puts into Ĝ (HG g = −0.9, 65 rows, double: interpolation error 0.11 there with
//   x = k/(1 + k), 5e-3 with √κ).
//   θ axis: y = ln(1 + θ/c) / (2β) for θ ≤ π/2 and 1 − ln(1 + u/c) / (2β) beyond, β = ln(1 + π/(2c)),
//   c = TYN_SCATTERING_LUT_THETA_KNEE = 0.02: spacing ∝ (θ + c) near θ = 0 and ∝ (u + c) near π
//   (1.7e-4 rad at the ends, 0.045 rad in the middle), so forward lobes up to g = 0.99 (width
//   1 − g = 0.01) and backward ones are resolved alike. Chebyshev spacing (π sin²(πy/2)) had 7e-4
//   error for g = 0.99 at 1024 nodes, c = 0.05 had 3.7e-4 (measured in double, midpoints).
//   Measured error of the float table's bilinear lookup at cell centres (the unit test,
//   k = σ h ≤ 30, beyond which every contribution of the ray is below e^{−30} of the light's):
//   ≤ 1.3e-4 of Ĝ for isotropic, Rayleigh, HG g ∈ {0, 0.76}, CS 0.9 and a two-component medium;
//   5e-4 for HG g = 0.99 (its lobe seen at large k) and HG g = −0.9 (rows with k < 1e-5).
//
// ## Building (tyn_scattering_lut_build_row: one invocation per row, 1024 texels each)
// Ĝ is accumulated from θ = π down: Ĝ(θ_p) = e^{−k (τ_q − τ_p)} Ĝ(θ_q) + ∫_{θ_p}^{θ_q}, τ = tan(θ/2),
// with sub-steps per node interval (tyn_scattering_lut_build_substeps). On a sub-step, in the
// variable w = τ − τ_p, the integrand is g(w) e^{−k w} with g = P(θ) (1 + cos θ) (= 2P/(1 + τ²)); g is
// taken linear between the sub-step's ends and multiplied by e^{−k w} exactly (product trapezoid
// rule), so the phase is evaluated once per sub-step end for all three channels and a steep
// exponential (large k) costs nothing extra. The last interval, which reaches θ = π (w = ∞), is
// Ĝ = P · N (its error is O(u²) ≈ 3e-8 there). Error: ≤ 3e-5 of Ĝ against adaptive double
// quadrature (unit test, every phase). Cost: ~5400 sub-steps per row, i.e. 1.4M phase evaluations
// per medium component for the table (66 ms for two components in single-threaded C++).
//
// ## The segment (tyn_scattering_lut_segment, tyn_spot_segment)
// F(t) needs one bilinear lookup per end. The difference F(t_a) − F(t_b) keeps the table's relative
// error ε only while the two values do not nearly cancel: its error is about
// ε (F_a + F_b) / (F_a − F_b). They cancel when a section before the foot subtends a small angle at
// the light (Δθ ≈ h ℓ / (s_a s_b) near θ = 0, where Ĝ ≈ Ĝ(0) − P(0) θ: a ray passing close to the
// light, or a short or far section), for short sections generally, and where a backward lobe
// beyond θ_b dominates Ĝ. (After the foot Ĝ ∝ u ≈ h/s vanishes at π, so a small h does not cancel
// there.) The guard: where F_a − F_b < TYN_SCATTERING_LUT_GUARD · F_a in some channel, the section
// is integrated by quadrature instead (see the constant). Spot lights: inside the inner cone the
// falloff is 1 and the table applies; in the penumbra (between the cones) the exact integrand with
// the falloff is integrated by quadrature; outside the outer cone the contribution is 0.
// Measured against double quadrature of the original integral (unit test; 8 phases × 5 extinctions
// × 35 light placements × 15 sections): ≤ 1.3e-4 relative for most media, 5e-4 worst (HG −0.9).
//
// ## Quadrature (tyn_local_light_quadrature)
// In θ, where the 1/d² peak disappears: S = (1/h) ∫ P falloff e^{−σ(t + d)} dθ, by 4-point
// Gauss–Legendre on pieces taken greedily from t_a (see the function). Positions are computed from
// the section's ends through angles and foot offsets measured from them, so nothing cancels when h
// is tiny or the light far. Measured: ≤ 6e-6 relative on the same matrix, every section by
// quadrature alone; spot sections crossing the penumbra ≤ 3e-4 (the table's share).
//
// ## Float precision on a GPU
// common/phase.h takes cos θ, and float rounds cos θ near 1 by 3e-8: for HG g = 0.99 that is 7e-4
// of 1 + g² − 2g cos θ within 0.01 rad of the light. The build and the quadrature know θ (or π − θ)
// and evaluate the phase from 2 sin²(θ/2) and 2 cos²(θ/2) instead (tyn_scattering_lut_phase, the
// same formulas), to 1e-6. Vulkan guarantees the built-in sin and cos only to 2^-11 absolute and
// atan to 4096 ulp, while angles here go down to h/d and need relative accuracy: the header uses its
// own (tyn_scattering_lut_sin, _cos, _atan2: polynomials, within 1e-7 relative, unit-tested). exp
// (3 + 2|x| ulp: 1e-5 at e^{−80}), log (2^-21 absolute, only in coordinates and the normaliser),
// sqrt and division are used as built in. (Not run on a GPU here: only the C++ compilation of the
// same source was measured; glslangValidator compiles every function.)
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

#include "common/phase.h"

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
// c of the θ warp: below c the spacing is uniform, above it proportional to θ (see the header).
TYN_CONST float TYN_SCATTERING_LUT_THETA_KNEE = 0.02f;
// k = σ h at the middle row (x = ½) of the h axis.
TYN_CONST float TYN_SCATTERING_LUT_K_MID = 1.0f;
// Sub-steps of the product trapezoid rule per node interval of the build, away from θ = π (error
// ∝ 1/substeps²; 4 gives ≤ 3e-5).
TYN_CONST int TYN_SCATTERING_LUT_BUILD_SUBSTEPS = 4;
// The cancellation guard: the table is used while F_a − F_b ≥ GUARD · F_a in every channel. The
// relative error of the difference is then at most ε (2 − GUARD) / GUARD, ε the lookup's relative
// error (≤ 1.3e-4 but for the two extreme lobes): ≤ 1e-3 at GUARD = 0.25. Measured worst section
// error over a test matrix as GUARD varies: 0.05 and 0.1 → 1.4e-3 (a short section just past the
// foot inside a g = −0.9 lobe), 0.15 → 5.6e-4, 0.25 → 5.4e-4, 0.5 → 5.2e-4, while the share of
// sections sent to quadrature grows from 33% (0.05) to 47% (0.25) and 53% (0.5). It is
// conservative for the small-h case alone (unit test ScatteringLutGuard: the table alone stays
// within 1e-3 down to 1 − F_b/F_a ≈ 1e-5, then float's rounding of F takes over).
TYN_CONST float TYN_SCATTERING_LUT_GUARD = 0.25f;
// Quadrature (tyn_local_light_quadrature): a piece spans at most 1/PIECES_PER_Y of the table's y
// (a sweep 0 → π is 32 pieces of ~32 nodes), grows max(f, h) by at most FOOT_RATIO and σ_max (t + d)
// by at most PATH_PER_PIECE (e^{−2} across a piece: 4-point Gauss–Legendre integrates that
// exponential to 1e-7); at most MAX_PIECES pieces (4 integrand evaluations each).
TYN_CONST float TYN_LOCAL_LIGHT_PIECES_PER_Y = 32.0f;
TYN_CONST float TYN_LOCAL_LIGHT_FOOT_RATIO = 2.0f;
TYN_CONST float TYN_LOCAL_LIGHT_PATH_PER_PIECE = 2.0f;
TYN_CONST int TYN_LOCAL_LIGHT_MAX_PIECES = 64;
// A channel is extinguished once σ (t + d) has grown by this much since t_a: e^{−40} = 4e-18, below
// float's resolution of that channel's earlier pieces even where the phase is 1e7 times larger
// there (HG g = 0.99 across its range). Its steps then no longer limit the pieces.
TYN_CONST float TYN_LOCAL_LIGHT_EXTINCT = 40.0f;
// Smallest distance from the light to the ray that is used (scene units): a ray through the light
// has an infinite integral; 1e-18 keeps h² (1e-36) and every angle h/d (d < 1e20) normal floats, which
// GPUs would otherwise flush to 0.
TYN_CONST float TYN_LOCAL_LIGHT_MIN_H = 1e-18f;
TYN_CONST float TYN_HALF_PI = 1.57079632679490f;

// ---- sin, cos and atan2 with relative accuracy ----
// Vulkan requires of the built-ins only 2^-11 absolute accuracy for sin and cos on [−π, π] and 4096
// ulp for atan; the angles here go down to h/d ~ 1e-20 and need relative accuracy (sin θ gives
// d = h / sin θ, 2 sin²(θ/2) the phase near a lobe). These use only +, −, ×, ÷ (correctly rounded
// or within 2.5 ulp) and are within a few ulps on the ranges used; the unit test checks them.

// π/2 as a float plus its remainder, so that π/2 − x is exact to an ulp for x near π/2.
TYN_CONST float TYN_HALF_PI_HI = 1.57079637f;
TYN_CONST float TYN_HALF_PI_LO = -4.37113883e-8f;

// Taylor polynomials on [0, π/4]: the first omitted terms are x¹³/13! < 7e-12 and x¹⁴/14! < 4e-13.
TYN_FUNC float tyn_scattering_lut_sin_poly(float x) {
  float z = x * x;
  return x + x * z * (-1.0f / 6.0f + z * (1.0f / 120.0f + z * (-1.0f / 5040.0f + z * (1.0f / 362880.0f +
                      z * (-1.0f / 39916800.0f)))));
}

TYN_FUNC float tyn_scattering_lut_cos_poly(float x) {
  float z = x * x;
  return 1.0f + z * (-0.5f + z * (1.0f / 24.0f + z * (-1.0f / 720.0f + z * (1.0f / 40320.0f +
                     z * (-1.0f / 3628800.0f + z * (1.0f / 479001600.0f))))));
}

// sin x and cos x for x ∈ [0, π/2] (beyond π/4 through the complement π/2 − x).
TYN_FUNC float tyn_scattering_lut_sin(float x) {
  return x <= 0.785398163f ? tyn_scattering_lut_sin_poly(x)
                           : tyn_scattering_lut_cos_poly((TYN_HALF_PI_HI - x) + TYN_HALF_PI_LO);
}

TYN_FUNC float tyn_scattering_lut_cos(float x) {
  return x <= 0.785398163f ? tyn_scattering_lut_cos_poly(x)
                           : tyn_scattering_lut_sin_poly((TYN_HALF_PI_HI - x) + TYN_HALF_PI_LO);
}

// atan z for z ∈ [0, 1] (Cephes atanf: beyond tan(π/8), π/4 + atan((z − 1)/(z + 1)); then an odd
// polynomial of degree 9; relative error ~1e-7).
TYN_FUNC float tyn_scattering_lut_atan01(float z) {
  float offset = 0.0f;
  if (z > 0.414213562f) {
    offset = 0.785398163f;
    z = (z - 1.0f) / (z + 1.0f);
  }
  float z2 = z * z;
  return offset + ((((8.05374449538e-2f * z2 - 1.38776856032e-1f) * z2 + 1.99777106478e-1f) * z2 -
                    3.33329491539e-1f) * z2 * z + z);
}

// atan2(y, x) ∈ [0, π] for y ≥ 0: relative accuracy for small results, absolute near π/2 and π.
TYN_FUNC float tyn_scattering_lut_atan2(float y, float x) {
  float ax = abs(x);
  float lo = min(y, ax);
  float hi = max(y, ax);
  float a = hi > 0.0f ? tyn_scattering_lut_atan01(lo / hi) : 0.0f;
  if (y > ax) a = (TYN_HALF_PI_HI - a) + TYN_HALF_PI_LO;
  if (x < 0.0f) a = (2.0f * TYN_HALF_PI_HI - a) + 2.0f * TYN_HALF_PI_LO;
  return a;
}

// ---- The medium, as plain parameters (C++ tests build it; GLSL: tyn_medium_from_frame) ----

struct TynMedium {
  vec3 sigma_t;                                     // extinction per scene unit, RGB
  uint components;                                  // medium components in use
  vec4 scattering[TYN_MAX_MEDIUM_COMPONENTS];       // rgb: σ_s of a component; w: its g
  uint phase_type[TYN_MAX_MEDIUM_COMPONENTS];       // TYN_PHASE_* of a component
};

// One phase function from cos θ and the accurate 1 − cos θ and 1 + cos θ: common/phase.h's formulas
// (the unit test holds them equal), with 1 + g² − 2g cos θ built from whichever of the two is small.
// tyn_phase takes cos θ alone, and float rounds cos θ near 1 to 3e-8: for HG g = 0.99 that is 7e-4 of
// 1 + g² − 2g cos θ within 0.01 rad of the light (measured), more than the table's own error. The
// table's nodes and the quadrature's know θ (or π − θ) and pass 2 sin²(θ/2) and 2 cos²(θ/2).
TYN_FUNC float tyn_scattering_lut_phase(uint type, float g, float cos_theta, float one_minus_cos, float one_plus_cos) {
  if (type == TYN_PHASE_RAYLEIGH) return tyn_phase_rayleigh(cos_theta);
  if (type != TYN_PHASE_HENYEY_GREENSTEIN && type != TYN_PHASE_CORNETTE_SHANKS) return tyn_phase_isotropic();
  float denom = g >= 0.0f ? (1.0f - g) * (1.0f - g) + 2.0f * g * one_minus_cos
                          : (1.0f + g) * (1.0f + g) - 2.0f * g * one_plus_cos;
  float lobe = (1.0f - g * g) / (denom * sqrt(denom));
  if (type == TYN_PHASE_HENYEY_GREENSTEIN) return lobe / (4.0f * TYN_PI);
  return 3.0f / (8.0f * TYN_PI * (2.0f + g * g)) * (1.0f + cos_theta * cos_theta) * lobe;
}

// P(θ) = Σ_components σ_s · p(θ), per channel, from cos θ, 1 − cos θ and 1 + cos θ. A constant
// bound, unrolled: the table's build calls this at each of a row's 5415 sub-steps, and on lavapipe
// every loop iteration of an invocation counts against one budget of 65,535 (docs/REFERENCE.md
// "Loop budget on lavapipe").
TYN_FUNC vec3 tyn_medium_phase_scattering_precise(TynMedium m, float cos_theta, float one_minus_cos,
                                                  float one_plus_cos) {
  vec3 sum = vec3(0.0f);
  for (uint c = 0u; c < TYN_MAX_MEDIUM_COMPONENTS; ++c) {
    if (c < m.components) {
      sum += vec3(m.scattering[c]) *
             tyn_scattering_lut_phase(m.phase_type[c], m.scattering[c].w, cos_theta, one_minus_cos, one_plus_cos);
    }
  }
  return sum;
}

// P(cos θ), as common/phase.h evaluates it.
TYN_FUNC vec3 tyn_medium_phase_scattering(TynMedium m, float cos_theta) {
  return tyn_medium_phase_scattering_precise(m, cos_theta, 1.0f - cos_theta, 1.0f + cos_theta);
}

// P at the angle (θ, u = π − θ), each accurate on its own side of π/2.
TYN_FUNC vec3 tyn_medium_phase_scattering_at(TynMedium m, vec2 angle) {
  float half_sin = tyn_scattering_lut_sin(0.5f * angle.x);  // sin(θ/2)
  float half_cos = tyn_scattering_lut_sin(0.5f * angle.y);  // cos(θ/2) = sin(u/2)
  float cos_theta = angle.x <= TYN_HALF_PI ? tyn_scattering_lut_cos(angle.x) : -tyn_scattering_lut_cos(angle.y);
  return tyn_medium_phase_scattering_precise(m, cos_theta, 2.0f * half_sin * half_sin, 2.0f * half_cos * half_cos);
}

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

TYN_FUNC float tyn_scattering_lut_theta_beta() {
  return log(1.0f + TYN_HALF_PI / TYN_SCATTERING_LUT_THETA_KNEE);
}

// Column coordinate y ∈ [0, 1] of an angle given as θ and u = π − θ (both accurate: callers get
// them from atan2, never as π minus the other, which would lose u near π).
TYN_FUNC float tyn_scattering_lut_y(float theta, float u) {
  float two_beta = 2.0f * tyn_scattering_lut_theta_beta();
  if (theta <= TYN_HALF_PI) return log(1.0f + max(theta, 0.0f) / TYN_SCATTERING_LUT_THETA_KNEE) / two_beta;
  return 1.0f - log(1.0f + max(u, 0.0f) / TYN_SCATTERING_LUT_THETA_KNEE) / two_beta;
}

// (θ, u) of a column coordinate y, each computed directly on its own side of π/2.
TYN_FUNC vec2 tyn_scattering_lut_angle(float y) {
  float two_beta = 2.0f * tyn_scattering_lut_theta_beta();
  if (y <= 0.5f) {
    float theta = TYN_SCATTERING_LUT_THETA_KNEE * (exp(two_beta * y) - 1.0f);
    return vec2(theta, 2.0f * TYN_HALF_PI - theta);
  }
  float u = TYN_SCATTERING_LUT_THETA_KNEE * (exp(two_beta * (1.0f - y)) - 1.0f);
  return vec2(2.0f * TYN_HALF_PI - u, u);
}

// ---- The normaliser N(k, u) (see the header) ----

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
  float sin_half = tyn_scattering_lut_sin(half_u);
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

  // Node last − 1: the interval to π is the single sub-step Ĝ = P(θ) N(k, u) (see the header).
  vec2 angle_q = tyn_scattering_lut_angle(float(last - 1) / float(last));
  vec3 p_q = tyn_medium_phase_scattering_at(m, angle_q);
  vec3 big_g = p_q * tyn_scattering_lut_norm(k, angle_q.y);
  TYN_SCATTERING_LUT_STORE(ivec2(last - 1, row), p_q);  // Q = Ĝ / N = P there, and in the limit
  // g = P (1 + cos θ) = 2 P sin²(u/2) at the current sub-step end.
  float sin_half_q = tyn_scattering_lut_sin(0.5f * angle_q.y);
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
      float cos_half_p = tyn_scattering_lut_sin(0.5f * angle_p.y);  // cos(θ/2) = sin(u/2), accurate near π
      float cos_half_q = tyn_scattering_lut_sin(0.5f * angle_q.y);
      // W = tan(θ_q/2) − tan(θ_p/2) = sin(Δθ/2) / (cos(θ_q/2) cos(θ_p/2)), without cancellation.
      float dw = tyn_scattering_lut_sin(0.5f * step_theta) / (cos_half_p * cos_half_q);
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

// ---- The view ray relative to the light ----

struct TynLightRay {
  float t_light;  // t_L = dot(L − C, v): ray parameter of the foot, the point closest to the light
  float h;        // distance from the light to the line, ≥ TYN_LOCAL_LIGHT_MIN_H
  vec3 normal;    // unit vector from the foot towards the light (some unit vector ⊥ v if h = 0)
};

// v must be unit length. h carries float's absolute error of the whole offset, ε |L − C| (the
// integral's own sensitivity to the inputs, about |L − C| / h times theirs): nothing here can
// resolve a ray passing closer to the light than ~1e-7 |L − C|.
TYN_FUNC TynLightRay tyn_light_ray(vec3 origin, vec3 dir, vec3 light_position) {
  TynLightRay r;
  vec3 to_light = light_position - origin;
  r.t_light = dot(to_light, dir);
  vec3 across = to_light - r.t_light * dir;
  float h = length(across);
  r.h = max(h, TYN_LOCAL_LIGHT_MIN_H);
  vec3 helper = abs(dir.x) < 0.9f ? vec3(1.0f, 0.0f, 0.0f) : vec3(0.0f, 1.0f, 0.0f);
  r.normal = h > 0.0f ? across / h : normalize(cross(dir, helper));
  return r;
}

// A point of the ray, as the reformulation sees it.
struct TynLightPoint {
  float t;      // ray parameter (≥ 0)
  float s;      // t − t_L
  float d;      // distance to the light
  float theta;  // scattering angle θ = atan2(h, −s): cos θ = dot(v, ω_l)
  float u;      // π − θ = atan2(h, s), accurate where θ is near π
  float path;   // t + d: the light's path through the medium to the camera
  float foot;   // s + d = h tan(θ/2) (= path − t_L, without cancellation)
};

TYN_FUNC TynLightPoint tyn_light_point(TynLightRay r, float t) {
  TynLightPoint p;
  p.t = t;
  p.s = t - r.t_light;
  p.d = sqrt(p.s * p.s + r.h * r.h);
  p.theta = tyn_scattering_lut_atan2(r.h, -p.s);
  p.u = tyn_scattering_lut_atan2(r.h, p.s);
  p.path = t + p.d;
  // s + d cancels when s < 0: (d + s)(d − s) = h².
  p.foot = p.s >= 0.0f ? p.s + p.d : r.h * r.h / (p.d - p.s);
  return p;
}

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

// ---- The spot cone ----

struct TynSpotCone {
  float along;      // dot(v, axis), axis = the direction the light travels
  float across;     // dot(normal, axis)
  float cos_outer;  // cos of the outer half-angle (falloff 0 outside), > 0 (half-angle < 90°)
  float cos_inner;  // cos of the inner half-angle (falloff 1 inside), ≥ cos_outer
};

TYN_FUNC TynSpotCone tyn_spot_cone(TynLightRay r, vec3 dir, vec3 axis, float cos_outer, float cos_inner) {
  TynSpotCone c;
  c.along = dot(dir, axis);
  c.across = dot(r.normal, axis);
  c.cos_outer = cos_outer;
  c.cos_inner = max(cos_inner, cos_outer);
  return c;
}

// cos of the angle between the axis and the direction from the light to the point at angle θ:
// x − L = s v − h n, so dot(x − L, axis) / d = −cos θ · along − sin θ · across.
TYN_FUNC float tyn_spot_cos_angle(TynSpotCone c, float cos_theta, float sin_theta) {
  return -cos_theta * c.along - sin_theta * c.across;
}

// The spot's falloff (the Reference's tyn_spot_falloff: Hermite between the cones, a hard edge
// when they coincide).
TYN_FUNC float tyn_spot_falloff_of(TynSpotCone c, float cos_angle) {
  float x = clamp((cos_angle - c.cos_outer) / max(c.cos_inner - c.cos_outer, 1e-6f), 0.0f, 1.0f);
  return x * x * (3.0f - 2.0f * x);
}

// The ray's parameter interval inside the cone of half-angle acos(cos_half) around the axis,
// single nappe (in front of the light), clipped to [t0, t1]: vec2(begin, end), empty when
// end ≤ begin. With f(s) = s·along − h·across (= dot(x − L, axis)), the point is inside when
// f ≥ 0 and f² ≥ cos²·(s² + h²): a quadratic a s² + 2 b s + c ≥ 0 whose discriminant is
// h² cos² (along² + across² − cos²). A line meets a cone's solid nappe in one interval (a convex
// set), bounded or not; f cannot change sign inside {quadratic ≥ 0} (f = 0 makes it negative), so
// each of that set's pieces lies in one nappe.
TYN_FUNC vec2 tyn_spot_cone_interval(TynLightRay r, TynSpotCone cone, float cos_half, float t0, float t1) {
  vec2 empty = vec2(t1, t0);
  float c2 = cos_half * cos_half;
  float a = cone.along * cone.along - c2;
  float b = -cone.along * cone.across * r.h;
  float c = (cone.across * cone.across - c2) * r.h * r.h;
  float spread = cone.along * cone.along + cone.across * cone.across - c2;
  if (spread < 0.0f) return empty;  // the line misses both nappes (a < 0 then)
  float root = r.h * cos_half * sqrt(spread);
  float q = -(b + (b >= 0.0f ? root : -root));  // |q| ≥ root: the stable quadratic formula
  if (q == 0.0f) return empty;                   // tangent through the apex region
  const float unbounded = 3.0e38f;
  float near_root = c / q;
  // The other root q / a; a → 0 (the ray parallel to a generator) sends it to ±∞ with q's sign.
  float far_root = abs(a) * 1e30f > abs(q) ? q / a : (q >= 0.0f ? unbounded : -unbounded);
  float lo = min(near_root, far_root);
  float hi = max(near_root, far_root);
  float s_begin;
  float s_end;
  if (a >= 0.0f) {
    // Outside [lo, hi]: the unbounded piece the direction points into is in front of the light.
    if (cone.along > 0.0f) {
      s_begin = hi;
      s_end = unbounded;
    } else {
      s_begin = -unbounded;
      s_end = lo;
    }
  } else {
    float mid = 0.5f * lo + 0.5f * hi;
    if (mid * cone.along - r.h * cone.across < 0.0f) return empty;  // the back nappe
    s_begin = lo;
    s_end = hi;
  }
  float begin = s_begin <= -unbounded ? t0 : max(t0, r.t_light + s_begin);
  float end = s_end >= unbounded ? t1 : min(t1, r.t_light + s_end);
  return end > begin ? vec2(begin, end) : empty;
}

// ---- Quadrature of the exact integrand (penumbra, and sections the table cannot resolve) ----

// The angle between the directions of the points whose foot values (s + d = h tan(θ/2)) are f0 and
// f0 + e, e ≥ 0: (θ1 − θ0)/2 = atan(τ1) − atan(τ0) = atan(e h / (h² + f0 (f0 + e))), τ = f / h. The
// offset e is passed rather than f1: foot values carry ε f of rounding, a difference of two of them
// 1e-4 of itself on a short section far from the light (measured: it broke the pieces' tiling).
TYN_FUNC float tyn_local_light_angle_between(TynLightRay r, float f0, float e) {
  return 2.0f * tyn_scattering_lut_atan2(max(e, 0.0f) * r.h, r.h * r.h + f0 * (f0 + e));
}

// The foot value h tan(θ/2) of the angle (θ, u), from the side of π/2 where it is accurate.
TYN_FUNC float tyn_local_light_foot_of_angle(TynLightRay r, vec2 angle) {
  float half_angle = 0.5f * (angle.x <= TYN_HALF_PI ? angle.x : angle.y);
  float ratio = tyn_scattering_lut_sin(half_angle) / tyn_scattering_lut_cos(half_angle);  // tan(half_angle)
  return angle.x <= TYN_HALF_PI ? r.h * ratio : r.h / ratio;
}

// A quadrature node: the angle (θ, u = π − θ, each accurate on its own side of π/2) and the light's
// path t + d there.
struct TynLightNode {
  vec2 angle;
  float sin_theta;
  float path;
};

// The node at angle φ after a and ψ before b (φ + ψ = the section's span; both passed because each
// is accurate near its own end). θ comes from the side of π/2 where it is accurate (θ = θ_a + φ or
// u = u_b + ψ), and t = t_a + d_a sin φ / sin θ (from s = −h cot θ: s − s_a = h sin φ /
// (sin θ_a sin θ)), a sum of non-negative terms accurate to a few ulps of t itself; beyond π/2,
// sin φ = sin(θ_a + u) (φ + θ_a + u = π) keeps its precision. (Measuring from b instead,
// t_b − d_b sin ψ / sin θ, loses ε t_b: 6e-3 of e^{−σ t} at σ = 10, t_b = 1e4, measured.)
TYN_FUNC TynLightNode tyn_local_light_node(TynLightRay r, TynLightPoint a, TynLightPoint b, float phi, float psi) {
  TynLightNode n;
  if (a.theta + phi <= TYN_HALF_PI) {
    n.angle = vec2(a.theta + phi, 2.0f * TYN_HALF_PI - (a.theta + phi));
    n.sin_theta = tyn_scattering_lut_sin(n.angle.x);
  } else {
    n.angle = vec2(2.0f * TYN_HALF_PI - (b.u + psi), b.u + psi);
    n.sin_theta = tyn_scattering_lut_sin(n.angle.y);
  }
  float sin_phi = phi <= TYN_HALF_PI ? tyn_scattering_lut_sin(phi) : tyn_scattering_lut_sin(a.theta + b.u + psi);
  float t = a.t + a.d * sin_phi / n.sin_theta;
  n.path = t + r.h / n.sin_theta;
  return n;
}

// ∫_{t_a}^{t_b} P falloff e^{−σ (t + d)} / d² dt (falloff = 1 unless use_falloff) by composite
// 4-point Gauss–Legendre in θ, where it is (1/h) ∫ P falloff e^{−σ (t + d)} dθ. In the foot
// variable f = s + d = h tan(θ/2) the path is t + d = t_L + f and (1/h) dθ = 2 df / (f² + h²), so
// the integrand is smooth on a piece when (a) the piece spans at most 1/PIECES_PER_Y of the table's
// y (lobes: y is dense where they are), (b) max(f, h) grows by at most FOOT_RATIO across it (the
// Lorentzian and the speed of θ), (c) σ f grows by at most PATH_PER_PIECE (the exponential) for
// the largest σ among the channels not yet extinguished.
// Pieces are taken greedily from t_a, each as long as (a)–(c) allow; past the budget the last one
// takes the rest (only reached by sections whose far part the exponential has already wiped out).
// Requires 0 ≤ t_a; 0 when t_b ≤ t_a.
TYN_FUNC vec3 tyn_local_light_quadrature(TynMedium m, TynLightRay r, TynSpotCone cone, bool use_falloff,
                                         float ta, float tb) {
  if (!(tb > ta)) return vec3(0.0f);
  // Nodes ±x0, ±x1 and weights w0, w1 of the 4-point rule on [−1, 1].
  const float x0 = 0.3399810435848563f;
  const float x1 = 0.8611363115940526f;
  const float w0 = 0.6521451548625461f;
  const float w1 = 0.3478548451374538f;
  TynLightPoint a = tyn_light_point(r, ta);
  TynLightPoint b = tyn_light_point(r, tb);
  // Everything is measured from a in the foot offset e = f − f_a (= the growth of the path t + d):
  // its total across the section, E = ℓ + d_b − d_a = ℓ (f_a + f_b) / (d_a + d_b), without the
  // cancellation of f_b − f_a; the span and every boundary's angles φ (from a) and ψ (to b) follow
  // from offsets, so the pieces tile [0, span] exactly.
  float total = (tb - ta) * (a.foot + b.foot) / (a.d + b.d);
  float span = tyn_local_light_angle_between(r, a.foot, total);
  vec3 sum = vec3(0.0f);
  // The current piece starts at offset e0, φ0 after a and ψ0 before b.
  float e0 = 0.0f;
  float phi0 = 0.0f;
  float psi0 = span;
  float y0 = tyn_scattering_lut_y(a.theta, a.u);
  for (int i = 0; i < TYN_LOCAL_LIGHT_MAX_PIECES; ++i) {
    // (c) with the largest σ of the channels not yet extinguished since t_a.
    vec3 alive = vec3(lessThan(m.sigma_t * e0, vec3(TYN_LOCAL_LIGHT_EXTINCT)));
    vec3 sigma_alive = m.sigma_t * alive;
    float sigma_max = max(max(sigma_alive.x, sigma_alive.y), sigma_alive.z);
    // (b): f1 ≤ FOOT_RATIO max(f0, h).
    float e1 = max(a.foot + e0, r.h) * TYN_LOCAL_LIGHT_FOOT_RATIO - a.foot;
    if (sigma_max > 0.0f) e1 = min(e1, e0 + TYN_LOCAL_LIGHT_PATH_PER_PIECE / sigma_max);
    // (a): the foot value of the next y step.
    float y1 = y0 + 1.0f / TYN_LOCAL_LIGHT_PIECES_PER_Y;
    if (y1 < 1.0f) e1 = min(e1, tyn_local_light_foot_of_angle(r, tyn_scattering_lut_angle(y1)) - a.foot);
    e1 = max(e1, e0);
    bool last = e1 >= total || i == TYN_LOCAL_LIGHT_MAX_PIECES - 1;
    float phi1 = last ? span : tyn_local_light_angle_between(r, a.foot, e1);
    float psi1 = last ? 0.0f : tyn_local_light_angle_between(r, a.foot + e1, total - e1);
    // The piece's angle, from the end whose offsets are the smaller (accurate) ones.
    float half_width = 0.5f * max(phi0 <= psi1 ? phi1 - phi0 : psi0 - psi1, 0.0f);
    vec3 piece = vec3(0.0f);
    for (int n = 0; n < 4; ++n) {
      float offset = (n < 2 ? x0 : x1) * ((n & 1) == 0 ? -half_width : half_width);
      // φ = φ0 + half + offset, ψ = ψ1 + half − offset.
      TynLightNode node = tyn_local_light_node(r, a, b, phi0 + half_width + offset, psi1 + half_width - offset);
      vec3 value = tyn_medium_phase_scattering_at(m, node.angle) * exp(-m.sigma_t * node.path);
      if (use_falloff) {
        float cos_theta = node.angle.x <= TYN_HALF_PI ? tyn_scattering_lut_cos(node.angle.x) : -tyn_scattering_lut_cos(node.angle.y);
        value *= tyn_spot_falloff_of(cone, tyn_spot_cos_angle(cone, cos_theta, node.sin_theta));
      }
      piece += (n < 2 ? w0 : w1) * value;
    }
    sum += piece * half_width;
    if (last) break;
    e0 = e1;
    phi0 = phi1;
    psi0 = psi1;
    float theta1 = a.theta + phi1;
    float u1 = b.u + psi1;
    y0 = max(theta1 <= TYN_HALF_PI ? tyn_scattering_lut_y(theta1, 2.0f * TYN_HALF_PI - theta1)
                                   : tyn_scattering_lut_y(2.0f * TYN_HALF_PI - u1, u1),
             y0);
  }
  // dt / d² = dθ / h.
  return sum / r.h;
}

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

// S(t_a, t_b) for a spot light over a lit section: the table inside the inner cone, quadrature
// with the falloff in the penumbra, nothing outside the outer cone.
TYN_SCATTERING_LUT_TEMPLATE
TYN_FUNC vec3 tyn_spot_segment(TYN_SCATTERING_LUT_ACCESS TynMedium m, TynLightRay r, TynSpotCone cone,
                               float ta, float tb) {
  vec2 outer = tyn_spot_cone_interval(r, cone, cone.cos_outer, ta, tb);
  if (!(outer.y > outer.x)) return vec3(0.0f);
  vec2 inner = tyn_spot_cone_interval(r, cone, cone.cos_inner, outer.x, outer.y);
  if (!(inner.y > inner.x)) return tyn_local_light_quadrature(m, r, cone, true, outer.x, outer.y);
  return tyn_local_light_quadrature(m, r, cone, true, outer.x, inner.x) +
         tyn_scattering_lut_segment(TYN_SCATTERING_LUT_PASS m, r, inner.x, inner.y) +
         tyn_local_light_quadrature(m, r, cone, true, inner.y, outer.y);
}
#endif

TYN_END

// ---- GLSL helpers reading the global `frame` (define TYN_SCATTERING_LUT_FRAME after declaring it) ----
#if defined(TYN_SCATTERING_LUT_FRAME) && !defined(__cplusplus)
TynMedium tyn_medium_from_frame() {
  TynMedium m;
  m.sigma_t = frame.extinction.rgb;
  m.components = frame.counts.y;
  for (uint c = 0u; c < TYN_MAX_MEDIUM_COMPONENTS; ++c) {
    m.scattering[c] = frame.scattering[c];
    m.phase_type[c] = frame.phase_type[c].x;
  }
  return m;
}

TynSpotCone tyn_spot_cone_from_frame(TynLightRay r, vec3 view_dir) {
  return tyn_spot_cone(r, view_dir, frame.light_direction.xyz, frame.light_direction.w,
                       frame.light_radiance.w);
}

#if defined(TYN_SCATTERING_LUT_FETCH) && defined(TYN_WALK_LIT_SECTIONS)
// L_in from the lit section [a, b] of the view ray (origin, unit view_dir) for the frame's point
// light, colour·intensity included: the texel walk's lit sections (reference/reference_march.glsl,
// TYN_WALK_LIT_SECTIONS, which merges them for point lights only). Sections are few per ray, so
// the medium and the ray are set up per call; the march along a slice hoists them out of its loop.
vec3 tyn_point_light_lut_segment(vec3 origin, vec3 view_dir, float a, float b) {
  TynMedium m = tyn_medium_from_frame();
  TynLightRay r = tyn_light_ray(origin, view_dir, frame.light_position.xyz);
  return frame.light_radiance.rgb * tyn_scattering_lut_segment(m, r, a, b);
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
