// The maths of prefiltered single scattering with moments (peters2017 §2 and §5), shared by the
// shaders and the unit tests (integration-tests/unit/test_moments.cpp, which checks every function
// against double precision and prints the worst errors it measures).
//
// ## Pipeline of one texel / one pixel
//   store:  z = tyn_signed_depth(d)  →  b = tyn_moments4(z) | tyn_moments6_odd/even(z)
//           → average (filters, prefix sums; any non-negative weights)  →  tyn_quantize_*
//   shade:  tyn_dequantize_*  →  tyn_bias_moments(b, b*, α_b) of the same variant
//           → tyn_moments4_bounds | tyn_moments6_bounds (lower and upper bound of the shadow
//             intensity Z(z < z_f))  →  tyn_shadow_intensity(bounds, tyn_adaptive_overestimation)
//   filtered resampling (§5.2): canonical b1..b3 → tyn_two_depths_from_moments → two depths and
//           weights, re-projected and turned into moments again.
// The storage variants, their transforms, b* and α_b are tabled in prefiltered/moment_constants.h.
//
// ## Conventions
// Moments are canonical (E[z^j] of the signed depth) unless the name says quantized; b0 = 1 is
// implicit. Four moments are vec4(b1, b2, b3, b4); six are split by parity as Θ6* and the two
// textures split them: odd = vec3(b1, b3, b5), even = vec3(b2, b4, b6). Polynomial coefficients
// are in ascending order: q = (q0, q1, q2[, q3]) means q0 + q1 z + q2 z² [+ q3 z³]. Roots are
// returned homogeneous, z = x / w, because one of them legitimately runs off to infinity when the
// leading coefficient vanishes (§5.4.1, |q3| ≪ 1); w = 0 is a root at infinity.
#ifndef TYNDALL_MOMENTS_H
#define TYNDALL_MOMENTS_H

#include "common/cpp_glsl.h"
#include "prefiltered/moment_constants.h"

TYN_BEGIN

// ---- Depth and moments ------------------------------------------------------------------------

// Depth in [0, 1] (near → far) to the signed depth in [−1, 1] (§2.3): of all affine remappings it
// maximises the determinant of the induced moment transform, i.e. the precision left after
// rounding (1024 × that of [0, 1] for four moments).
TYN_FUNC float tyn_signed_depth(float depth01) { return 2.0f * depth01 - 1.0f; }

TYN_FUNC vec4 tyn_moments4(float z) {
  float z2 = z * z;
  return vec4(z, z2, z2 * z, z2 * z2);
}

TYN_FUNC vec3 tyn_moments6_odd(float z) {
  float z2 = z * z;
  return vec3(z, z2 * z, z2 * z2 * z);
}

TYN_FUNC vec3 tyn_moments6_even(float z) {
  float z2 = z * z;
  return vec3(z2, z2 * z2, z2 * z2 * z2);
}

// ---- Storage ----------------------------------------------------------------------------------

// 4 moments in 64 bits: Θ4* (§2.4) maps the moments of any depth distribution on [−1, 1] into
// [0, 1]⁴ for RGBA16_UNORM, spending the 16 bits where the moment curve lives.
TYN_FUNC vec4 tyn_quantize_moments4_64(vec4 b) {
  vec2 odd = TYN_THETA4_ODD * vec2(b.x, b.z) + TYN_THETA4_ODD_OFFSET;
  vec2 even = TYN_THETA4_EVEN * vec2(b.y, b.w);
  return vec4(odd.x, even.x, odd.y, even.y);
}

TYN_FUNC vec4 tyn_dequantize_moments4_64(vec4 stored) {
  vec2 odd = TYN_THETA4_ODD_INVERSE * (vec2(stored.x, stored.z) - TYN_THETA4_ODD_OFFSET);
  vec2 even = TYN_THETA4_EVEN_INVERSE * vec2(stored.y, stored.w);
  return vec4(odd.x, even.x, odd.y, even.y);
}

// 4 moments in 128 bits (RGBA32F) and 6 moments in 192 bits store canonical moments: in float a
// transform adds no precision, it would have to be undone in float before Algorithm 1 (§2.3).
// These two keep the call sites uniform across variants.
TYN_FUNC vec4 tyn_quantize_moments4_128(vec4 b) { return b; }
TYN_FUNC vec4 tyn_dequantize_moments4_128(vec4 stored) { return stored; }

// 6 moments in 64 bits (two RGB10 textures) or 96 bits (16-bit channels): Θ6* (§5.4.3) acts on
// odd and even moments separately, one texture each; every channel lies in [0, 1].
TYN_FUNC vec3 tyn_quantize_moments6_odd(vec3 b_odd) {
  return TYN_THETA6_ODD * b_odd + TYN_THETA6_ODD_OFFSET;
}

TYN_FUNC vec3 tyn_quantize_moments6_even(vec3 b_even) {
  return TYN_THETA6_EVEN * b_even + TYN_THETA6_EVEN_OFFSET;
}

TYN_FUNC vec3 tyn_dequantize_moments6_odd(vec3 stored_odd) {
  return TYN_THETA6_ODD_INVERSE * (stored_odd - TYN_THETA6_ODD_OFFSET);
}

TYN_FUNC vec3 tyn_dequantize_moments6_even(vec3 stored_even) {
  return TYN_THETA6_EVEN_INVERSE * (stored_even - TYN_THETA6_EVEN_OFFSET);
}

// Worst-case biasing (§2.5): b' = (1 − α_b) b + α_b b*, with b* and α_b of the storage variant.
// b' is the moment vector of the mixture (1 − α_b) Z + α_b Z*, strictly inside the valid domain
// even for distributions on its boundary (one or two depths), and stays so under rounding errors
// up to α_b times the distance of b* to the boundary. The price: the bounds may move by up to α_b.
// b0 needs no biasing since b0 = b*_0 = 1.
TYN_FUNC vec4 tyn_bias_moments(vec4 b, vec4 b_star, float alpha) { return mix(b, b_star, alpha); }
TYN_FUNC vec3 tyn_bias_moments(vec3 b, vec3 b_star, float alpha) { return mix(b, b_star, alpha); }

// ---- Polynomial roots -------------------------------------------------------------------------

// Roots of q0 + q1 z + q2 z² with real roots: x / w, the root of smaller magnitude first.
// Citardauq pairing: t = −(q1 + sign(q1) √disc) / 2 never cancels, and the two roots are q0 / t and
// t / q2, so neither is a difference of nearly equal numbers; q2 = 0 gives w.y = 0 (a root at
// infinity), not a division by zero. disc < 0 only from rounding next to a double root: clamped.
TYN_FUNC void tyn_solve_quadratic(vec3 q, TYN_INOUT(vec2) x, TYN_INOUT(vec2) w) {
  float root_disc = sqrt(max(q.y * q.y - 4.0f * q.x * q.z, 0.0f));
  float t = -0.5f * (q.y + (q.y >= 0.0f ? root_disc : -root_disc));
  x = vec2(q.x, t);
  w = vec2(t, q.z);
}

TYN_CONST float TYN_HALF_SQRT3 = 0.8660254037844386f;

// The two extreme roots t of the depressed cubic t³ + 3 c t + d = 0 (three real roots, c ≤ 0),
// by the trigonometric method: t_k = 2 √−c cos(θ + 2πk/3) with 3θ = atan2(√(−4c³ − d²), −d).
// Returns (t_0, t_1), the largest and the smallest. √(−4c³ − d²) = |a| √Δ for the cubic's
// leading coefficient a and discriminant Δ; a √Δ is passed in, as it is cheaper than the
// difference of cubes and does not cancel.
TYN_FUNC vec2 tyn_depressed_cubic_extremes(float c, float d, float a_root_disc) {
  float theta = atan(abs(a_root_disc), -d) / 3.0f;
  float scale = 2.0f * sqrt(max(-c, 0.0f));
  float cos_theta = cos(theta);
  return scale * vec2(cos_theta, -0.5f * cos_theta - TYN_HALF_SQRT3 * sin(theta));
}

// Roots of q0 + q1 z + q2 z² + q3 z³ with three real roots, after Blinn ("How to Solve a Cubic
// Equation, Part 5: Back to Numerics", IEEE CG&A 27(3), 2007), returned as x / w in the order
// (smallest magnitude, middle, largest magnitude). In Blinn's form A x³ + 3B x² + 3C x + D with Hessian
// δ = (AC − B², AD − BC, BD − C²) and discriminant Δ = 4 δ1 δ3 − δ2² ≥ 0:
//   - the root of largest magnitude comes from t = A z + B, which depresses the cubic to
//     t³ + 3 δ1 t + (A δ2 − 2 B δ1) = 0; z = (t − B) / A, so A = q3 → 0 gives w = 0, a root
//     at infinity, instead of cancellation;
//   - the root of smallest magnitude comes from the reversed cubic in u = 1 / z, s = D u + C,
//     s³ + 3 δ3 s + (D δ2 − 2 C δ3) = 0; z = D / (s − C), accurate as z → 0;
//   - the middle one from the cubic divided by the other two (Blinn's E, F, G).
// Each extreme root takes the extreme t whose distance to B (to C) is largest. peters2017 §5.4.1
// computes all three roots with one branch; the two-branch form costs a second atan/sin/cos but
// stays accurate where one branch cancels (|q3| ≪ 1 for the A branch, a root near 0 for the D
// branch; the unit test MomentRoots.Cubic* covers both and double roots). q is first scaled to
// max |q_j| = 1: Δ is quartic in q, and q = B⁻¹ v(z_f) grows like 1 / α_b.
TYN_FUNC void tyn_solve_cubic(vec4 q, TYN_INOUT(vec3) x, TYN_INOUT(vec3) w) {
  q /= max(max(abs(q.x), abs(q.y)), max(abs(q.z), abs(q.w)));
  float A = q.w;
  float B = q.z / 3.0f;
  float C = q.y / 3.0f;
  float D = q.x;
  vec3 delta = vec3(A * C - B * B, A * D - B * C, B * D - C * C);
  float root_disc = sqrt(max(4.0f * delta.x * delta.z - delta.y * delta.y, 0.0f));

  vec2 t = tyn_depressed_cubic_extremes(delta.x, A * delta.y - 2.0f * B * delta.x, A * root_disc);
  float t_large = (t.x + t.y > 2.0f * B) ? t.x : t.y;
  vec2 largest = vec2(t_large - B, A);

  vec2 s = tyn_depressed_cubic_extremes(delta.z, D * delta.y - 2.0f * C * delta.z, D * root_disc);
  float s_small = (s.x + s.y > 2.0f * C) ? s.x : s.y;
  vec2 smallest = vec2(D, s_small - C);

  // (w_l z − x_l)(w_s z − x_s) = E z² + F z + G; the cubic divided by it leaves (w_m z − x_m).
  float E = largest.y * smallest.y;
  float F = -largest.x * smallest.y - largest.y * smallest.x;
  float G = largest.x * smallest.x;
  vec2 middle = vec2(C * F - B * G, C * E - B * F);

  x = vec3(smallest.x, middle.x, largest.x);
  w = vec3(smallest.y, middle.y, largest.y);
}

// ---- Algorithm 1: sharp bounds of the shadow intensity (§2.2.1, §5.3, §5.4) -------------------
// For moments b and a fragment depth z_f, the depth distributions matching b give shadow
// intensities Z(z < z_f) in [lower, upper]. Both bounds come from the one distribution matching b
// that has an atom at z_f (weight w0) and m/2 others at the roots z_l of
// q(z) = v(z)ᵀ B(b)⁻¹ v(z_f), v(z) = (1, z, …, z^{m/2}) and B(b) the Hankel matrix (b_{j+k}):
// lower = Σ_{z_l < z_f} w_l and upper = lower + w0 (§5.3).
//   - B = L D Lᵀ (the Cholesky factorisation without square roots); y = L⁻¹ v(z_f) and
//     q = L⁻ᵀ D⁻¹ y.
//   - w0 = 1 / (v(z_f)ᵀ B⁻¹ v(z_f)) = 1 / Σ y_k² / D_k: B = Σ w_l v(z_l) v(z_l)ᵀ and q(z_l) = 0
//     for l ≥ 1 give B q = w0 q(z_f) v(z_f), while B q = v(z_f). A sum of positive terms: no
//     cancellation, however close b is to the boundary.
//   - Σ_l v_l w_l for indicator values v_l is E_b[p] for the polynomial p interpolating (z_l, v_l)
//     (the weights solve a Vandermonde system, §5.4.2); p in Newton form from divided differences.
//     The root of largest magnitude is the last node, homogeneous: it only ever appears as
//     1 / (z_3 − z_k) = w / (x − z_k w), so a root at infinity (w = 0) contributes nothing, as
//     its weight, 0, says.
// Requires B(b) positive definite: biased moments (tyn_bias_moments). Returns vec2(lower, upper),
// clamped to [0, 1] against rounding only.

// Divided difference (f_b − f_a) / (z_b − z_a), zero where f_b = f_a: the interpolated indicator
// is flat there, and rounding may have merged the two nodes (0 / 0 otherwise).
TYN_FUNC float tyn_divided_difference(float f_a, float f_b, float z_a, float z_b) {
  return f_b == f_a ? 0.0f : (f_b - f_a) / (z_b - z_a);
}

// The same with z_b = x_b / w_b homogeneous (w_b = 0 at infinity).
TYN_FUNC float tyn_divided_difference_h(float f_a, float f_b, float z_a, vec2 z_b) {
  return f_b == f_a ? 0.0f : (f_b - f_a) * z_b.y / (z_b.x - z_a * z_b.y);
}

// 1 when the homogeneous root x / w lies in front of z_f. x/w < z_f ⇔ (x − z_f w) w < 0; false
// for a root at infinity, whose weight is 0 anyway.
TYN_FUNC float tyn_in_front(vec2 root, float zf) {
  return (root.x - zf * root.y) * root.y < 0.0f ? 1.0f : 0.0f;
}

// A pivot D_k of L D Lᵀ is b_{2k} minus terms of the same size, so float32 knows it only to
// about half an ulp of b_{2k} (2⁻²⁴ b_{2k}), the resolution of b_{2k} itself. Biased moments
// keep D_k ≥ α_b D_k(b*) in exact arithmetic, but with α_b = 3e-7 (4 moments in float32) that is
// below this resolution and rounding can return 0 or less. Such a pivot is clamped to the
// resolution: the reconstruction then stays a valid (positive definite) one instead of dividing
// by zero.
TYN_CONST float TYN_FLOAT_UNIT_ROUNDOFF = 5.9604645e-8f;  // 2⁻²⁴
TYN_FUNC float tyn_hankel_pivot(float pivot, float diagonal) {
  return max(pivot, TYN_FLOAT_UNIT_ROUNDOFF * diagonal);
}

// 4 moments b = (b1, b2, b3, b4): 3×3 Hankel matrix, quadratic.
TYN_FUNC vec2 tyn_moments4_bounds(vec4 b, float zf) {
  float d1 = tyn_hankel_pivot(b.y - b.x * b.x, b.y);
  float l21 = (b.z - b.x * b.y) / d1;
  float d2 = tyn_hankel_pivot(b.w - b.y * b.y - l21 * l21 * d1, b.w);

  float y1 = zf - b.x;
  float y2 = zf * zf - b.y - l21 * y1;
  float w0 = 1.0f / (1.0f + y1 * y1 / d1 + y2 * y2 / d2);

  float q2 = y2 / d2;
  float q1 = y1 / d1 - l21 * q2;
  float q0 = 1.0f - b.x * q1 - b.y * q2;
  vec2 x;
  vec2 w;
  tyn_solve_quadratic(vec3(q0, q1, q2), x, w);

  // Nodes z0 = z_f, z1 (finite), z2 = x.y / w.y; values 0, [z1 < z_f], [z2 < z_f].
  float z1 = x.x / w.x;
  float v1 = z1 < zf ? 1.0f : 0.0f;
  float v2 = tyn_in_front(vec2(x.y, w.y), zf);
  float f01 = tyn_divided_difference(0.0f, v1, zf, z1);
  float f12 = tyn_divided_difference_h(v1, v2, z1, vec2(x.y, w.y));
  float f012 = tyn_divided_difference_h(f01, f12, zf, vec2(x.y, w.y));
  // E_b[f01 (z − z0) + f012 (z − z0)(z − z1)]
  float lower = f01 * (b.x - zf) + f012 * (b.y - (zf + z1) * b.x + zf * z1);
  lower = clamp(lower, 0.0f, 1.0f);
  return vec2(lower, min(lower + w0, 1.0f));
}

// 6 moments, odd = (b1, b3, b5), even = (b2, b4, b6): 4×4 Hankel matrix, cubic (§5.4).
TYN_FUNC vec2 tyn_moments6_bounds(vec3 b_odd, vec3 b_even, float zf) {
  float b1 = b_odd.x;
  float b2 = b_even.x;
  float b3 = b_odd.y;
  float b4 = b_even.y;
  float b5 = b_odd.z;
  float b6 = b_even.z;
  float d1 = tyn_hankel_pivot(b2 - b1 * b1, b2);
  float l21 = (b3 - b1 * b2) / d1;
  float l31 = (b4 - b1 * b3) / d1;
  float d2 = tyn_hankel_pivot(b4 - b2 * b2 - l21 * l21 * d1, b4);
  float l32 = (b5 - b2 * b3 - l21 * l31 * d1) / d2;
  float d3 = tyn_hankel_pivot(b6 - b3 * b3 - l31 * l31 * d1 - l32 * l32 * d2, b6);

  float y1 = zf - b1;
  float y2 = zf * zf - b2 - l21 * y1;
  float y3 = zf * zf * zf - b3 - l31 * y1 - l32 * y2;
  float w0 = 1.0f / (1.0f + y1 * y1 / d1 + y2 * y2 / d2 + y3 * y3 / d3);

  float q3 = y3 / d3;
  float q2 = y2 / d2 - l32 * q3;
  float q1 = y1 / d1 - l21 * q2 - l31 * q3;
  float q0 = 1.0f - b1 * q1 - b2 * q2 - b3 * q3;
  vec3 x;
  vec3 w;
  tyn_solve_cubic(vec4(q0, q1, q2, q3), x, w);

  // Nodes z0 = z_f, z1, z2 (finite), z3 = x.z / w.z; values 0, [z_l < z_f].
  vec2 z3 = vec2(x.z, w.z);
  float z1 = x.x / w.x;
  float z2 = x.y / w.y;
  float v1 = z1 < zf ? 1.0f : 0.0f;
  float v2 = z2 < zf ? 1.0f : 0.0f;
  float v3 = tyn_in_front(z3, zf);
  float f01 = tyn_divided_difference(0.0f, v1, zf, z1);
  float f12 = tyn_divided_difference(v1, v2, z1, z2);
  float f23 = tyn_divided_difference_h(v2, v3, z2, z3);
  float f012 = tyn_divided_difference(f01, f12, zf, z2);
  float f123 = tyn_divided_difference_h(f12, f23, z1, z3);
  float f0123 = tyn_divided_difference_h(f012, f123, zf, z3);
  // p(z) = f01 (z − z0) + f012 (z − z0)(z − z1) + f0123 (z − z0)(z − z1)(z − z2), expanded into
  // ascending coefficients by Horner steps (§5.4.2), then E_b[p] = dot(p, (1, b1, b2, b3)).
  vec4 p = vec4(f012 - f0123 * z2, f0123, 0.0f, 0.0f);
  p = vec4(f01 - p.x * z1, p.x - p.y * z1, p.y, 0.0f);
  p = vec4(-p.x * zf, p.x - p.y * zf, p.y - p.z * zf, p.z);
  float lower = clamp(dot(p, vec4(1.0f, b1, b2, b3)), 0.0f, 1.0f);
  return vec2(lower, min(lower + w0, 1.0f));
}

// ---- Adaptive overestimation (§5.3.1) ---------------------------------------------------------

// β = (1 + ω_lᵀ ω_p) / 2 with ω_l the unit direction towards the light and ω_p the unit direction
// from the scattering point towards the camera. β = 0 looking straight into the light (ω_p = −ω_l),
// where the rectified depth is minimal and any overestimated visibility leaks light; β = 1
// looking away from it, where underestimation would leave no scattering at all. In Tyndall's
// terms (DESIGN.md "Radiometry") ω_p = −v, so β = (1 − cos θ) / 2.
TYN_FUNC float tyn_adaptive_overestimation(vec3 omega_l, vec3 omega_p) {
  return 0.5f + 0.5f * dot(omega_l, omega_p);
}

// Shadow intensity between the bounds: β = 0 takes the upper bound (single scattering
// underestimated), β = 1 the lower one (overestimated); §5.4.2 writes it as visibility
// Σ_{z_l ≥ z_f} w_l + β w0 = 1 − (lower + (1 − β) w0).
TYN_FUNC float tyn_shadow_intensity(vec2 bounds, float beta) {
  return mix(bounds.y, bounds.x, beta);
}

// ---- Algorithm 2: two depths from b1, b2, b3 (§5.2, Appendix B) --------------------------------
// Returns (z1, z2, w1, w2) with w1 δ_{z1} + w2 δ_{z2} matching b0 = 1, b1, b2, b3 for canonical
// b = (b1, b2, b3); z1 is the depth of larger weight. σ² = b2 − b1² ≤ 0 (one depth, or rounding) falls
// back to δ_{b1}, as the paper prescribes: (b1, b1, 1, 0).
// The paper's steps (with the minus signs the text lost: q2 = b2 − b1², q1 = b1 b2 − b3,
// q0 = −b1 q1 − b2 q2, roots of q2 z² + q1 z + q0, w2 = (b1 − z1) / (z2 − z1)) are run after the
// affine change z = b1 + σ x, under which they are invariant. It maps the moments to (1, 0, 1, γ)
// with the skewness γ = μ3 / σ³, μ3 = b3 − 3 b1 b2 + 2 b1³, so q = (−1, −γ, 1): the roots solve
// x² − γ x − 1 = 0, their product is −1, and the weights become 1 / (1 + x²) (mean 0, variance 1).
// Done in float on the raw moments instead, q0 cancels, and when σ² is small (a 64-bit moment map
// read back, one surface plus noise) w2 = (b1 − z1) / (z2 − z1) divides two rounding-sized
// numbers: the returned distribution then missed b2, b3 by up to 1 % of their size. Here the only
// cancellations are in σ² and μ3 themselves, i.e. in the input. γ stays far from overflow:
// σ² > 0 computed in float is at least about u b2 (u = 2⁻²⁴), so |γ| ≲ 1e12.
TYN_FUNC vec4 tyn_two_depths_from_moments(vec3 b) {
  float variance = b.y - b.x * b.x;
  if (!(variance > 0.0f)) return vec4(b.x, b.x, 1.0f, 0.0f);
  float sigma = sqrt(variance);
  float mu3 = b.z - b.x * (3.0f * b.y - 2.0f * b.x * b.x);
  float gamma = mu3 / (variance * sigma);
  // Root of larger magnitude without cancellation, the other one from the product −1.
  float x_far = 0.5f * gamma + (gamma >= 0.0f ? 1.0f : -1.0f) * sqrt(0.25f * gamma * gamma + 1.0f);
  float x_near = -1.0f / x_far;
  float w_far = 1.0f / (1.0f + x_far * x_far);
  return vec4(b.x + sigma * x_near, b.x + sigma * x_far, 1.0f - w_far, w_far);
}

TYN_END

#endif
