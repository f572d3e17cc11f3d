// sin, cos and atan2 with relative accuracy, for the local-light integrals. Vulkan requires of the
// built-ins only 2^-11 absolute accuracy for sin and cos on [−π, π] and 4096 ulp for atan, while
// angles there go down to h/d ~ 1e-20 and need relative accuracy (sin θ gives d = h / sin θ,
// 2 sin²(θ/2) the phase near a lobe). These use only +, −, ×, ÷ and are within a few ulps on the
// ranges used (integration-tests/unit/test_scattering_lut.cpp checks them).
#ifndef TYNDALL_PRECISE_TRIG_H
#define TYNDALL_PRECISE_TRIG_H

#include "common/cpp_glsl.h"

TYN_BEGIN

TYN_CONST float TYN_HALF_PI = 1.57079632679490f;

// π/2 as a float plus its remainder, so that π/2 − x is exact to an ulp for x near π/2.
TYN_CONST float TYN_HALF_PI_HI = 1.57079637f;
TYN_CONST float TYN_HALF_PI_LO = -4.37113883e-8f;

// Taylor polynomials on [0, π/4]: the first omitted terms are x¹³/13! < 7e-12 and x¹⁴/14! < 4e-13.
TYN_FUNC float tyn_precise_sin_poly(float x) {
  float z = x * x;
  return x + x * z * (-1.0f / 6.0f + z * (1.0f / 120.0f + z * (-1.0f / 5040.0f + z * (1.0f / 362880.0f +
                      z * (-1.0f / 39916800.0f)))));
}

TYN_FUNC float tyn_precise_cos_poly(float x) {
  float z = x * x;
  return 1.0f + z * (-0.5f + z * (1.0f / 24.0f + z * (-1.0f / 720.0f + z * (1.0f / 40320.0f +
                     z * (-1.0f / 3628800.0f + z * (1.0f / 479001600.0f))))));
}

// sin x and cos x for x ∈ [0, π/2] (beyond π/4 through the complement π/2 − x).
TYN_FUNC float tyn_precise_sin(float x) {
  return x <= 0.785398163f ? tyn_precise_sin_poly(x)
                           : tyn_precise_cos_poly((TYN_HALF_PI_HI - x) + TYN_HALF_PI_LO);
}

TYN_FUNC float tyn_precise_cos(float x) {
  return x <= 0.785398163f ? tyn_precise_cos_poly(x)
                           : tyn_precise_sin_poly((TYN_HALF_PI_HI - x) + TYN_HALF_PI_LO);
}

// atan z for z ∈ [0, 1] (Cephes atanf: beyond tan(π/8), π/4 + atan((z − 1)/(z + 1)); then an odd
// polynomial of degree 9; relative error ~1e-7).
TYN_FUNC float tyn_precise_atan01(float z) {
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
TYN_FUNC float tyn_precise_atan2(float y, float x) {
  float ax = abs(x);
  float lo = min(y, ax);
  float hi = max(y, ax);
  float a = hi > 0.0f ? tyn_precise_atan01(lo / hi) : 0.0f;
  if (y > ax) a = (TYN_HALF_PI_HI - a) + TYN_HALF_PI_LO;
  if (x < 0.0f) a = (2.0f * TYN_HALF_PI_HI - a) + 2.0f * TYN_HALF_PI_LO;
  return a;
}
TYN_END

#endif
