// In-scattering from a spot or point light along a lit section of a view ray by quadrature of the
// exact integrand, S(t_a, t_b) = ∫ P(cos θ) · falloff · e^{−σ_t (t + d)} / d² dt (per RGB channel,
// per unit of light colour·intensity; DESIGN.md "Radiometry"), and the medium's phase evaluated
// precisely near a lobe. The epipolar scattering table (epipolar/scattering_lut.h) calls it where
// the table is not accurate enough. Derivation and accuracy: docs/derivations/scattering-lut.md.
#ifndef TYNDALL_LOCAL_LIGHT_INTEGRAL_H
#define TYNDALL_LOCAL_LIGHT_INTEGRAL_H

#include "common/phase.h"
#include "common/precise_trig.h"
#include "common/light_ray.h"
#include "common/spot_cone.h"

TYN_BEGIN

// c of the θ warp: below c the spacing is uniform, above it proportional to θ. The scattering
// table's columns follow this warp, and the quadrature sizes its pieces by it.
TYN_CONST float TYN_SCATTERING_LUT_THETA_KNEE = 0.02f;
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
TYN_FUNC float tyn_phase_precise(uint type, float g, float cos_theta, float one_minus_cos, float one_plus_cos) {
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
             tyn_phase_precise(m.phase_type[c], m.scattering[c].w, cos_theta, one_minus_cos, one_plus_cos);
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
  float half_sin = tyn_precise_sin(0.5f * angle.x);  // sin(θ/2)
  float half_cos = tyn_precise_sin(0.5f * angle.y);  // cos(θ/2) = sin(u/2)
  float cos_theta = angle.x <= TYN_HALF_PI ? tyn_precise_cos(angle.x) : -tyn_precise_cos(angle.y);
  return tyn_medium_phase_scattering_precise(m, cos_theta, 2.0f * half_sin * half_sin, 2.0f * half_cos * half_cos);
}

// ---- The θ warp (the scattering table's column coordinate) ----

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

// ---- Quadrature of the exact integrand (penumbra, and sections the table cannot resolve) ----

// The angle between the directions of the points whose foot values (s + d = h tan(θ/2)) are f0 and
// f0 + e, e ≥ 0: (θ1 − θ0)/2 = atan(τ1) − atan(τ0) = atan(e h / (h² + f0 (f0 + e))), τ = f / h. The
// offset e is passed rather than f1: foot values carry ε f of rounding, a difference of two of them
// 1e-4 of itself on a short section far from the light, enough to break the pieces' tiling.
TYN_FUNC float tyn_local_light_angle_between(TynLightRay r, float f0, float e) {
  return 2.0f * tyn_precise_atan2(max(e, 0.0f) * r.h, r.h * r.h + f0 * (f0 + e));
}

// The foot value h tan(θ/2) of the angle (θ, u), from the side of π/2 where it is accurate.
TYN_FUNC float tyn_local_light_foot_of_angle(TynLightRay r, vec2 angle) {
  float half_angle = 0.5f * (angle.x <= TYN_HALF_PI ? angle.x : angle.y);
  float ratio = tyn_precise_sin(half_angle) / tyn_precise_cos(half_angle);  // tan(half_angle)
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
    n.sin_theta = tyn_precise_sin(n.angle.x);
  } else {
    n.angle = vec2(2.0f * TYN_HALF_PI - (b.u + psi), b.u + psi);
    n.sin_theta = tyn_precise_sin(n.angle.y);
  }
  float sin_phi = phi <= TYN_HALF_PI ? tyn_precise_sin(phi) : tyn_precise_sin(a.theta + b.u + psi);
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
        float cos_theta = node.angle.x <= TYN_HALF_PI ? tyn_precise_cos(node.angle.x) : -tyn_precise_cos(node.angle.y);
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
TYN_END

#endif
