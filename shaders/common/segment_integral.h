// Closed-form integrals along a view ray in a homogeneous medium.
#ifndef TYNDALL_SEGMENT_INTEGRAL_H
#define TYNDALL_SEGMENT_INTEGRAL_H

#include "common/shared_constants.h"

TYN_BEGIN

// (1 − e^{−x}) / x for x ≥ 0, accurate as x → 0 where the direct form cancels. Below 1e-2 the
// series 1 − x/2 + x²/6 − x³/24 is used: its truncation error x⁴/120 < 1e-10 there, and above
// it 1 − e^{−x} has lost at most two of float's seven digits.
TYN_FUNC float tyn_one_minus_exp_over_x(float x) {
  if (x < 1e-2f) return 1.0f - x * (0.5f - x * (1.0f / 6.0f - x * (1.0f / 24.0f)));
  return (1.0f - exp(-x)) / x;
}

// ∫_a^b e^{−σ t} dt = e^{−σ a} · (b − a) · (1 − e^{−σ (b − a)}) / (σ (b − a)), per channel,
// exact for σ = 0 (the limit b − a). Requires 0 ≤ a ≤ b.
TYN_FUNC vec3 tyn_transmittance_integral(float a, float b, vec3 sigma_t) {
  float len = max(b - a, 0.0f);
  vec3 x = sigma_t * len;
  vec3 ratio = vec3(tyn_one_minus_exp_over_x(x.x), tyn_one_minus_exp_over_x(x.y),
                    tyn_one_minus_exp_over_x(x.z));
  return exp(-sigma_t * a) * len * ratio;
}

TYN_END

#endif
