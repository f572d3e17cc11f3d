// Re-weighting the prefix sums of a row to one view ray (shared by the evaluation pass and the
// unit test integration-tests/unit/test_weight_taps.cpp).
//
// The prefix sums of a row are weighted for its reference ray: texel j at reference distance
// τ ∈ [τ_j, τ_{j+1}] has weight ∫ e^{−σ τ} dτ (rectification.h). A view ray of the row crosses the
// same texels κ times as slowly, κ = sin θ_ref / sin θ (its distance is t = κ τ, both rectified
// maps; rectification.h "Per-slice sample spacing"), so its own weights are ∫ κ e^{−σ κ τ} dτ: a
// faster exponential. With one lookup (klehm2014, peters2017) the pixel uses the reference's weights
// as they are; the error grows with κ (up to 1/sin θ near the epipole) and with the ray's optical
// depth σ s (tyn_weighted_average_max_error).
//
// Here the ray's weights are approximated by the reference's times a step function g that is
// constant on K segments [τ_{k−1}, τ_k] of the ray's extent [0, τ_end] in the row, g_k chosen so
// that each segment gets exactly its own weight under the ray's exponential. With the unnormalised
// prefix sums P(τ) = A(τ)·W(τ) (A: the stored normalised average up to τ, W(τ) = ∫_0^τ e^{−σ u} du):
//   Σ_k g_k (P(τ_k) − P(τ_{k−1})) = Σ_k W(τ_k)(g_k − g_{k+1}) A(τ_k),   g_{K+1} = 0,
// divided by the ray's total weight ∫_0^{τ_end} κ e^{−σ κ τ} dτ: the ray's weighted average is a
// combination Σ c_k A(τ_k) of K lookups with Σ c_k = 1. The segments hold equal shares of the ray's
// weight (quantiles of its truncated exponential), so each lookup matters equally.
//   - κ ≥ 1 makes g decreasing, so every c_k ≥ 0: the combination is a convex combination of stored
//     representations, itself a valid one (moments stay in the moment domain). This is why the
//     taps need the slice's fastest ray as reference (klehm2014's ω_min, sin θ largest), which no
//     ray of the slice outruns.
//   - K = 1 is the single lookup at τ_end; κ = 1 or σ = 0 give c_K = 1 (the reference is exact).
//   - The error left is the reference's shape inside each segment: it vanishes as K grows.
#ifndef TYNDALL_WEIGHT_TAPS_H
#define TYNDALL_WEIGHT_TAPS_H

#include "common/cpp_glsl.h"
#include "common/segment_integral.h"
#include "prefiltered/rectification.h"

TYN_BEGIN

TYN_CONST uint TYN_PF_MAX_TAPS = 8u;

// −ln(1 − y) / y for y ∈ [0, 1), accurate as y → 0. Directly, 1 − y rounds to u with an absolute
// error of 2⁻²⁵, which is a relative error of 3e-8 / y in −ln(1 − y). Dividing by 1 − u instead of y
// (exact for u ∈ [½, 1], Sterbenz) pairs the logarithm with the u it was taken of (Goldberg, "What
// every computer scientist should know about floating-point arithmetic", Thm. 4's log1p trick).
TYN_FUNC float tyn_neg_log1m_over_y(float y) {
  float u = 1.0f - y;
  if (u == 1.0f) return 1.0f;
  return -log(u) / (1.0f - u);
}

// W(τ) = ∫_0^τ e^{−σ u} du: the reference ray's weight up to τ, by which a stored prefix average is
// de-normalised (the prefix sums' own weights, rectification.h).
TYN_FUNC float tyn_prefix_weight(float sigma, float tau) { return tau * tyn_one_minus_exp_over_x(sigma * tau); }

// Where the k-th of `taps` segments ends, as a fraction of τ_end: the q = k/taps quantile of the ray's
// weight, whose optical depth over its whole extent is x = σ κ τ_end = σ s. F(q) = −ln(1 − q(1 − e^{−x}))/x.
TYN_FUNC float tyn_weight_tap_fraction(float optical_depth, uint k, uint taps) {
  if (k >= taps) return 1.0f;
  float q = float(k) / float(taps);
  float y = q * optical_depth * tyn_one_minus_exp_over_x(optical_depth);
  return q * tyn_one_minus_exp_over_x(optical_depth) * tyn_neg_log1m_over_y(y);
}

// g_k of segment k ∈ [1, taps] (0 beyond the last): the ray's weight of the segment over the
// reference's, the ray's weight being total / taps by construction.
TYN_FUNC float tyn_weight_tap_ratio(float sigma, float optical_depth, float tau_end, uint k, uint taps) {
  if (k > taps) return 0.0f;
  float lo = tau_end * tyn_weight_tap_fraction(optical_depth, k - 1u, taps);
  float hi = tau_end * tyn_weight_tap_fraction(optical_depth, k, taps);
  float len = max(hi - lo, 0.0f);
  float reference = exp(-sigma * lo) * len * tyn_one_minus_exp_over_x(sigma * len);
  // The ray's total weight in reference units: ∫_0^{τ_end} κ e^{−σκτ} dτ = κ τ_end ome(x); the κ
  // cancels against the one in the normalisation of tyn_weight_tap.
  float ray = tau_end * tyn_one_minus_exp_over_x(optical_depth) / float(taps);
  return reference > 0.0f ? ray / reference : 0.0f;
}

// Tap k ∈ [1, taps]: (where, as a fraction of τ_end; coefficient c_k). sigma: the extinction of the
// prefix weights (per scene unit); kappa ≥ 1: the ray's distance per reference distance; tau_end:
// the reference distance at the ray's end (s / κ). taps = 1, a zero-length ray, or κ = 1 within
// rounding return the single lookup (1, 1) for k = 1.
TYN_FUNC vec2 tyn_weight_tap(float sigma, float kappa, float tau_end, uint k, uint taps) {
  float optical_depth = sigma * kappa * tau_end;
  if (taps <= 1u || !(tau_end > 0.0f)) return vec2(1.0f, k == taps ? 1.0f : 0.0f);
  float fraction = tyn_weight_tap_fraction(optical_depth, k, taps);
  float tau = tau_end * fraction;
  float w = tyn_prefix_weight(sigma, tau);  // W(τ_k)
  float g = tyn_weight_tap_ratio(sigma, optical_depth, tau_end, k, taps);
  float g_next = tyn_weight_tap_ratio(sigma, optical_depth, tau_end, k + 1u, taps);
  float total = tau_end * tyn_one_minus_exp_over_x(optical_depth);
  // g decreases for κ ≥ 1; rounding may leave a difference of either sign next to κ = 1.
  return vec2(fraction, max(w * (g - g_next), 0.0f) / total);
}

// Segmented reconstruction: the representation of segment k alone, (P(τ_k) − P(τ_{k−1})) / ΔW, is
// the combination c.x·A(τ_k) + c.y·A(τ_{k−1}) of two lookups with c.x + c.y = 1 (so it holds for
// stored values too, every stored channel being affine in the representation; storage_variants.glsl).
// c.y ≤ 0: a difference, not a convex combination, so rounding of the stored averages is amplified
// by W(τ_k)/ΔW and the result may leave the moment domain by that much (the variant's bias toward b*
// and the bounds' pivot clamp absorb it; measured in docs/PREFILTERED.md). w_lo = 0 (the ray's first
// segment) or a segment of no weight returns the lookup at τ_k alone: c = (1, 0).
// Every segment holds 1/K of the ray's weight (tyn_weight_tap_fraction) and g_k = (total/K)/ΔW_k,
// so Σ_k (1/K)·segment_k is exactly Σ_k c_k A(τ_k) of tyn_weight_tap: the same linear average. The
// difference is where the non-linear reconstruction runs: once per segment, on a distribution of
// occluders from a quarter of the ray rather than all of it (test_weight_taps.cpp checks the identity).
TYN_FUNC vec2 tyn_segment_coefficients(float w_lo, float w_hi) {
  if (!(w_lo > 0.0f) || !(w_hi > w_lo)) return vec2(1.0f, 0.0f);
  float inv = 1.0f / (w_hi - w_lo);
  return vec2(w_hi * inv, -w_lo * inv);
}

// Where a tap at reference distance τ reads along its row. Both rectifications measure distance
// from the camera's light ray: the reference ray is at r = τ·sin θ_ref there (rectification.h,
// "Per-slice sample spacing"), and so is every ray of the row at its own t = κ τ.
// Non-linear map: u = r / r_max.
TYN_FUNC float tyn_weight_tap_u_nonlinear(float tau, float reference_sin, float r_max) {
  return tau * reference_sin / r_max;
}

// Projective map: the column of light-frame x = r / √(1 + η²) (η = y/x of the row), the inverse of
// tyn_projective_x: u = x_f (x − x_n) / ((x_f − x_n) x). Below x_n (between the camera and the
// frustum's nearest corner) u < 0, which the lookup clamps to the first column.
TYN_FUNC float tyn_weight_tap_u_projective(ProjectiveRectificationParams proj, float tau, float reference_sin,
                                           float eta) {
  float x = tau * reference_sin / sqrt(1.0f + eta * eta);
  float xn = proj.x_near;
  float xf = proj.x_far;
  return xf * (x - xn) / ((xf - xn) * max(x, 1.0e-30f));
}

// The inverses: the reference distance τ at which a row is read at u (trimmed segments end at
// column edges, depth_bounds.h).
TYN_FUNC float tyn_weight_tap_tau_nonlinear(float u, float reference_sin, float r_max) {
  return u * r_max / reference_sin;
}

TYN_FUNC float tyn_weight_tap_tau_projective(ProjectiveRectificationParams proj, float u, float reference_sin,
                                             float eta) {
  return tyn_projective_x(proj, u) * sqrt(1.0f + eta * eta) / reference_sin;
}

TYN_END

#endif
