// The medium and the light of a frame, evaluated at points along a view ray. Needs `frame`.
#ifndef TYNDALL_MEDIUM_GLSL
#define TYNDALL_MEDIUM_GLSL

#include "common/phase.h"

// Σ_components σ_s · p(cos θ): the scattered fraction towards the camera, per channel.
vec3 tyn_phase_weighted_scattering(float cos_theta) {
  vec3 sum = vec3(0.0);
  for (uint c = 0u; c < frame.counts.y; ++c) {
    sum += frame.scattering[c].rgb *
           tyn_phase(frame.phase_type[c].x, frame.scattering[c].w, cos_theta);
  }
  return sum;
}

// Hermite falloff between the outer (0) and inner (1) cone; GLSL's smoothstep is undefined when
// the two edges are equal, which is a valid hard-edged spot.
float tyn_spot_falloff(float cos_angle) {
  float cos_outer = frame.light_direction.w;
  float cos_inner = frame.light_radiance.w;
  float x = clamp((cos_angle - cos_outer) / max(cos_inner - cos_outer, 1e-6), 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}

// Spot/point light: light reaching the point x, scattered towards the camera along `view_dir`
// and attenuated back to the camera over distance t: E(x) · Σσ_s p(cos θ) · e^{−σ_t t}, with
// E = I / d² · e^{−σ_t d} · falloff.
vec3 tyn_local_light_integrand(vec3 origin, vec3 view_dir, float t) {
  vec3 x = origin + t * view_dir;
  vec3 to_light = frame.light_position.xyz - x;
  float d2 = max(dot(to_light, to_light), 1e-12);
  float d = sqrt(d2);
  vec3 omega_l = to_light / d;
  float falloff = frame.counts.x == TYN_LIGHT_SPOT
                      ? tyn_spot_falloff(dot(-omega_l, frame.light_direction.xyz))
                      : 1.0;
  vec3 irradiance = frame.light_radiance.rgb * (falloff / d2) * exp(-frame.extinction.rgb * d);
  return irradiance * tyn_phase_weighted_scattering(dot(view_dir, omega_l)) *
         exp(-frame.extinction.rgb * t);
}

// ∫_a^b of the integrand above by 4-point Gauss–Legendre on pieces no longer than half the
// distance to the light, so that the 1/d² peak near the light is resolved (relative error of
// the rule on such a piece is below 1e-5 for 1/d²).
vec3 tyn_local_light_segment(vec3 origin, vec3 view_dir, float a, float b) {
  // Nodes ±x0, ±x1 and weights w0, w1 of the 4-point rule on [−1, 1].
  const float x0 = 0.3399810435848563;
  const float x1 = 0.8611363115940526;
  const float w0 = 0.6521451548625461;
  const float w1 = 0.3478548451374538;
  float t_closest = clamp(dot(frame.light_position.xyz - origin, view_dir), a, b);
  float d_near = max(length(origin + t_closest * view_dir - frame.light_position.xyz), 1e-4);
  int pieces = int(clamp(ceil((b - a) / (0.5 * d_near)), 1.0, 64.0));
  float h = (b - a) / float(pieces);
  vec3 sum = vec3(0.0);
  for (int i = 0; i < pieces; ++i) {
    float mid = a + (float(i) + 0.5) * h;
    float d0 = 0.5 * h * x0;
    float d1 = 0.5 * h * x1;
    sum += w0 * (tyn_local_light_integrand(origin, view_dir, mid - d0) +
                 tyn_local_light_integrand(origin, view_dir, mid + d0));
    sum += w1 * (tyn_local_light_integrand(origin, view_dir, mid - d1) +
                 tyn_local_light_integrand(origin, view_dir, mid + d1));
  }
  return sum * 0.5 * h;
}

#endif
