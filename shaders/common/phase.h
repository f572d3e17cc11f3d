// Phase functions, normalised over the sphere (DESIGN.md "Radiometry"). cos_theta is
// dot(view direction, direction towards the light), so g > 0 peaks when looking into the light.
#ifndef TYNDALL_PHASE_H
#define TYNDALL_PHASE_H

#include "common/shared_constants.h"

TYN_BEGIN

TYN_CONST float TYN_PI = 3.14159265358979f;

TYN_FUNC float tyn_phase_isotropic() { return 1.0f / (4.0f * TYN_PI); }

TYN_FUNC float tyn_phase_rayleigh(float cos_theta) {
  return 3.0f / (16.0f * TYN_PI) * (1.0f + cos_theta * cos_theta);
}

// 1 + g² − 2g·cos θ as a sum of non-negative terms, so that it keeps float's relative precision
// where a strong lobe peaks (g → ±1, cos θ → ±1) instead of cancelling to a few digits.
TYN_FUNC float tyn_phase_denominator(float cos_theta, float g) {
  return g >= 0.0f ? (1.0f - g) * (1.0f - g) + 2.0f * g * (1.0f - cos_theta)
                   : (1.0f + g) * (1.0f + g) - 2.0f * g * (1.0f + cos_theta);
}

TYN_FUNC float tyn_phase_henyey_greenstein(float cos_theta, float g) {
  float denom = tyn_phase_denominator(cos_theta, g);
  return (1.0f - g * g) / (4.0f * TYN_PI * denom * sqrt(denom));
}

TYN_FUNC float tyn_phase_cornette_shanks(float cos_theta, float g) {
  float denom = tyn_phase_denominator(cos_theta, g);
  return 3.0f * (1.0f - g * g) / (8.0f * TYN_PI * (2.0f + g * g)) *
         (1.0f + cos_theta * cos_theta) / (denom * sqrt(denom));
}

TYN_FUNC float tyn_phase(uint type, float g, float cos_theta) {
  if (type == TYN_PHASE_RAYLEIGH) return tyn_phase_rayleigh(cos_theta);
  if (type == TYN_PHASE_HENYEY_GREENSTEIN) return tyn_phase_henyey_greenstein(cos_theta, g);
  if (type == TYN_PHASE_CORNETTE_SHANKS) return tyn_phase_cornette_shanks(cos_theta, g);
  return tyn_phase_isotropic();
}

TYN_END

#endif
