// Rectified shadow maps for prefiltered single scattering (klehm2014 §3–4, peters2017 §5.1.1 and
// Appendix A): the coordinate systems in which every view ray is one row of constant depth, the
// per-row sample spacing Δ(v) and the transmittance weights of the prefix sums, the per-pixel
// evaluation, and klehm2014's Fourier basis — pure functions shared by the GPU passes and the unit
// tests. The per-frame set-up on the CPU (bounds, basis, projective matrix, the switch between the
// two rectifications, the choice of extinction for the weights) is
// plugin/src/prefiltered/rectification_setup.h.
//
// Conventions
// - Light frame (both rectifications): origin at the camera position o; z_L = the direction the
//   light TRAVELS (DESIGN.md `direction`, unit), so that along a light ray depth grows with z_L as
//   the original shadow depth does; x_L ⊥ z_L is the bisectrix of the view frustum's azimuth
//   range (klehm2014 §4.2; any perpendicular when the range is the full circle); y_L = z_L × x_L
//   (right-handed). Light-frame coordinates of p: (x, y, h) = (p − o)·(x_L, y_L, z_L).
// - Non-linear rectification (peters2017 §5.1.1): r = |(x, y)| (distance between p's light ray and
//   the camera), φ = atan2(y, x) ∈ (−π, π] (the epipolar slice; 0 on the bisectrix), θ = atan2(r, h)
//   ∈ [0, π] (inclination from z_L: the angle between the camera→p direction and the light's travel
//   direction; π − θ is the angle to the light, whose cosine is the phase function's cos θ).
//   A view ray o + t·d (|d| = 1) has constant φ and θ (they depend on d only) and r = t·sin θ, so
//   it is one row of constant depth; a light ray has constant (r, φ), i.e. one texel, and θ falls
//   along it. Stored depth is the flipped inclination π − θ (it grows with the original depth, as
//   the paper requires), normalised to the guarded inclination range [θ_min', θ_max']:
//     u = r / r_max,  v = 0.5 + φ / Δφ,  depth = (θ_max' − θ) / (θ_max' − θ_min')
//   (texture coordinates in [0, 1]; texel i of a row covers r ∈ [i, i + 1]·r_max/N_u). Δφ ≤ 2π;
//   Δφ = 2π (the light axis inside the frustum) uses the whole circle with its seam at φ = ±π,
//   v = 0 ≡ 1: sample it with repeat addressing along v. [θ_min', θ_max'] is the frustum's
//   [θ_min, θ_max] stretched by 10% (TYN_RECT_THETA_GUARD) and deliberately not clamped to [0, π],
//   so every view ray's depth stays at least 0.05/1.1 inside (0, 1) — which the Fourier basis
//   needs (see "Fourier basis"). Occluder depths outside [0, 1] are clamped (klehm2014 §4.1).
//   The inverse (r, φ, θ) → p is undefined on the light ray through the camera (r = 0).
// - Precision: a float world position far from the origin carries ~6e-8 of its magnitude as
//   error, which near the camera is a large error in direction. Per-pixel passes should use the
//   forms that take the view ray (tyn_rectified_from_view_ray, tyn_projective_texcoord_from_offset);
//   a ray's row and depth then come from its direction alone and are exactly constant.
// - Projective rectification (klehm2014 §4.2): one world → clip matrix, a perspective projection
//   ALONG x_L with the camera as its centre. With η = y/x and ζ = h/x:
//     clip.w = x;  column NDC = (x_f + x_n)/(x_f − x_n) − 2·x_f·x_n/((x_f − x_n)·x) ∈ [−1, 1];
//     row NDC = (2η − η_lo − η_hi)/(η_hi − η_lo);  depth = (ζ − ζ_lo')/(ζ_hi' − ζ_lo') ∈ [0, 1]
//   and texture coordinates (u, v) = (NDC + 1)/2 (row 0 at v = 0, as a Vulkan framebuffer). η and ζ
//   are ratios of coordinates that scale with t along a view ray, so a view ray keeps its row and
//   its depth; a light ray changes only h, so it keeps x and y: one texel. It needs x > 0 on the
//   whole frustum (the light axis outside it); see tyn_projective_texcoord.
// - Prefix sums (klehm2014 §3.1, Appendix A; peters2017 §5.1.1): along row v, texel i holds the
//   visibility representation b(i, v) of the light ray at the texel, the reference view ray of the
//   row crosses that texel over the distance interval [t_i, t_{i+1}] (tyn_nonlinear_texel_span,
//   tyn_projective_texel_span), and the stored value is the NORMALISED weighted prefix sum
//     b_Σ(i, v) = Σ_{j ≤ i} w_j·b(j, v) / Σ_{j ≤ i} w_j,   w_j = ∫_{t_j}^{t_{j+1}} e^{−σ t} dt,
//   a weighted average that keeps the range of b, so unorm8 storage works (klehm2014 App. A).
//   t_0 = 0: integration starts at the camera (DESIGN.md), also for the projective map, whose first
//   column starts at x_n > 0 — its first texel stands for the segment from the camera.
//   b_Σ(i) covers the row up to the far EDGE of texel i, so a pixel whose surface is at u_s reads
//   the prefix sums at u_s − 0.5/N_u (tyn_prefix_lookup_u) for linear filtering to return the
//   average up to u_s. De-normalisation multiplies that average by Σ w up to u_s, i.e. by
//   ∫_0^s e^{−σ_t t} dt of the pixel's own ray, computed exactly per channel:
//     L_in = Σ σ_s·p(cos θ) · E · (1 − shadow) · ∫_0^s e^{−σ_t t} dt      (tyn_prefiltered_inscattering)
//   with 1 − shadow = the reconstructed visibility average. Two approximations remain, both of the
//   same kind (the weights assume another exponential rate than the pixel's ray has), and both are
//   bounded by tyn_weighted_average_max_error:
//   * all rays of a row share the reference ray's spacing Δ(v) (peters2017's mean θ or
//     klehm2014 §3.2's reference ray), while a ray at inclination θ has Δr/sin θ;
//   * with RGB σ_t the exact weights differ per channel. Exact: one prefix-sum set per distinct
//     channel. Approximation: one grey σ for the weights and the exact per-channel ∫_0^s; its
//     worst visibility error is the bound above with optical depths σ_grey·s and σ_c·s. The CPU
//     picks per frame (choosePrefixSumExtinction). σ_t = 0 is exact everywhere (weights = lengths).
// - Fourier basis (klehm2014 §3.1, Eq. 8–9): see the derivation above tyn_fourier_basis.
#ifndef TYNDALL_RECTIFICATION_H
#define TYNDALL_RECTIFICATION_H

#include "common/phase.h"
#include "common/segment_integral.h"

TYN_BEGIN

// peters2017 §5.1.1: "The length of the interval of values for θ is stretched by 10%."
TYN_CONST float TYN_RECT_THETA_GUARD = 0.1f;
// Below this sine a reference ray is treated as parallel to the light (its texel spacing would be
// infinite); 1e-6 keeps Δ(v) = Δr/sin finite in float for any scene scale up to 1e30.
TYN_CONST float TYN_RECT_MIN_SIN = 1.0e-6f;

// klehm2014 §5: M = 32 real coefficients = 16 sine/cosine pairs, in eight RGBA8 layers.
TYN_CONST uint TYN_FOURIER_COEFFICIENTS = 32u;
TYN_CONST uint TYN_FOURIER_HARMONICS = 16u;
TYN_CONST uint TYN_FOURIER_LAYERS = 8u;

// The per-frame parameters of the non-linear rectification (std140: a vec3 and a scalar share a
// 16-byte row, so C++ places every member at the same offset; 144 bytes).
struct NonLinearRectificationParams {
  vec3 origin;               // camera position o, world
  float r_max;               // largest radius r of the map (scene units)
  vec3 axis_x;               // x_L
  float phi_extent;          // Δφ, the azimuth extent in (0, 2π]
  vec3 axis_y;               // y_L = z_L × x_L
  float pad0;
  vec3 axis_z;               // z_L, the direction the light travels
  float pad1;
  vec2 theta_range;          // θ_min, θ_max of the view frustum (peters2017 App. A)
  vec2 theta_range_guarded;  // θ_min', θ_max' with the guard band (the stored depth range)
  vec4 side_planes[4];       // inward unit normals of the view frustum's side planes (world,
                             // through o) in xyz, w 0: per-slice inclination ranges
};

// The per-frame parameters of the projective rectification (klehm2014 §4.2).
struct ProjectiveRectificationParams {
  mat4 world_to_clip;     // see the header comment; clip.w = x > 0 on the frustum
  float x_near;           // x_n, x_f: light-frame x of the map's first and last column
  float x_far;
  float eta_lo;           // the row range, η = y/x
  float eta_hi;
  float zeta_lo_guarded;  // the guarded depth range, ζ = h/x
  float zeta_hi_guarded;
  float zeta_lo;          // the unguarded one
  float zeta_hi;
};

// ---------------------------------------------------------------------------------------------
// Non-linear rectification (peters2017 §5.1.1)

// Light-frame coordinates (x, y, h) of a world point.
TYN_FUNC vec3 tyn_light_frame(NonLinearRectificationParams rect, vec3 world) {
  vec3 p = world - vec3(rect.origin);
  return vec3(dot(p, vec3(rect.axis_x)), dot(p, vec3(rect.axis_y)), dot(p, vec3(rect.axis_z)));
}

// φ of light-frame (x, y); 0 at the camera's own light ray, where atan is undefined (GLSL).
TYN_FUNC float tyn_rect_azimuth(float x, float y) {
  return (x == 0.0f && y == 0.0f) ? 0.0f : atan(y, x);
}

// (r, φ, θ) of a world point. atan2 rather than acos: full precision near θ = 0 and π.
TYN_FUNC vec3 tyn_rectified_from_world(NonLinearRectificationParams rect, vec3 world) {
  vec3 q = tyn_light_frame(rect, world);
  float r = length(vec2(q.x, q.y));
  return vec3(r, tyn_rect_azimuth(q.x, q.y), atan(r, q.z));
}

// (φ, θ) of a view direction (any length): shared by every point of the ray, so a pass can take
// the ray's row and depth from its direction and need no point on it.
TYN_FUNC vec2 tyn_view_ray_slice(NonLinearRectificationParams rect, vec3 direction) {
  float x = dot(direction, vec3(rect.axis_x));
  float y = dot(direction, vec3(rect.axis_y));
  float h = dot(direction, vec3(rect.axis_z));
  return vec2(tyn_rect_azimuth(x, y), atan(length(vec2(x, y)), h));
}

// (r, φ, θ) of the point at distance t along the unit view direction d: r = t·sin θ.
TYN_FUNC vec3 tyn_rectified_from_view_ray(NonLinearRectificationParams rect, vec3 direction,
                                          float distance) {
  vec2 slice = tyn_view_ray_slice(rect, direction);
  return vec3(distance * sin(slice.y), slice.x, slice.y);
}

// World point of (r, φ, θ), r > 0 and 0 < θ < π: h = r·cot θ.
TYN_FUNC vec3 tyn_world_from_rectified(NonLinearRectificationParams rect, vec3 r_phi_theta) {
  float r = r_phi_theta.x;
  vec3 radial = cos(r_phi_theta.y) * vec3(rect.axis_x) + sin(r_phi_theta.y) * vec3(rect.axis_y);
  float h = r * cos(r_phi_theta.z) / sin(r_phi_theta.z);
  return vec3(rect.origin) + r * radial + h * vec3(rect.axis_z);
}

// The point at light-frame height h on the light ray (r, φ): what a resampling pass projects
// into the host's shadow map to find the occluder on that light ray.
TYN_FUNC vec3 tyn_light_ray_point(NonLinearRectificationParams rect, float r, float phi, float h) {
  vec3 radial = cos(phi) * vec3(rect.axis_x) + sin(phi) * vec3(rect.axis_y);
  return vec3(rect.origin) + r * radial + h * vec3(rect.axis_z);
}

// Normalised stored depth of an inclination (the flipped inclination π − θ in the guarded
// range); unclamped: occluders outside the frustum's range give values outside [0, 1].
TYN_FUNC float tyn_rectified_depth(NonLinearRectificationParams rect, float theta) {
  return (rect.theta_range_guarded.y - theta) / (rect.theta_range_guarded.y - rect.theta_range_guarded.x);
}

TYN_FUNC float tyn_rectified_theta(NonLinearRectificationParams rect, float depth) {
  return rect.theta_range_guarded.y - depth * (rect.theta_range_guarded.y - rect.theta_range_guarded.x);
}

// (u, v, depth) of (r, φ, θ); see the header comment.
TYN_FUNC vec3 tyn_rectified_texcoord(NonLinearRectificationParams rect, vec3 r_phi_theta) {
  return vec3(r_phi_theta.x / rect.r_max, 0.5f + r_phi_theta.y / rect.phi_extent,
              tyn_rectified_depth(rect, r_phi_theta.z));
}

TYN_FUNC vec3 tyn_rectified_from_texcoord(NonLinearRectificationParams rect, vec3 uvd) {
  return vec3(uvd.x * rect.r_max, (uvd.y - 0.5f) * rect.phi_extent, tyn_rectified_theta(rect, uvd.z));
}

// ---------------------------------------------------------------------------------------------
// Per-slice sample spacing Δ(v)
//
// In slice φ, a view direction is d(θ) = sin θ·e(φ) + cos θ·z_L with e(φ) = cos φ·x_L + sin φ·y_L,
// and it crosses a texel of radial size Δr over Δr / sin θ (r = t·sin θ). klehm2014 §3.2 writes
// sin θ = k(ω) = ω·ω_l^⊥ with ω_l^⊥ = e(φ). Rows of both rectifications are slices (the projective
// row η has φ = atan η), so both use these functions.

// The inclination interval [θ_lo, θ_hi] of the view directions in slice φ: the frustum is the
// cone n_i·d ≥ 0 (four side planes); each constraint a·sin θ + b·cos θ ≥ 0 (a = n·e, b = n·z_L)
// keeps one end of [0, π] up to its root θ0 (sin θ0, cos θ0) ∝ (b, −a) when b > 0, and from its
// root ∝ (−b, a) when b < 0. θ_lo > θ_hi when the slice misses the frustum (no pixel reads it).
TYN_FUNC vec2 tyn_slice_theta_range(NonLinearRectificationParams rect, float phi) {
  vec3 e = cos(phi) * vec3(rect.axis_x) + sin(phi) * vec3(rect.axis_y);
  float lo = 0.0f;
  float hi = TYN_PI;
  for (uint i = 0u; i < 4u; ++i) {
    vec3 n = vec3(rect.side_planes[i]);
    float a = dot(n, e);
    float b = dot(n, vec3(rect.axis_z));
    if (b > 0.0f) {
      hi = min(hi, atan(b, -a));
    } else if (b < 0.0f) {
      lo = max(lo, atan(-b, a));
    } else if (a < 0.0f) {
      lo = TYN_PI;
      hi = 0.0f;
    }
  }
  return vec2(lo, hi);
}

// peters2017 §5.1.1: "the distance for the arithmetic mean of the minimal and maximal values of
// θ" — sin of the mean of the interval given: the slice's (tyn_slice_theta_range) or the frustum's
// (theta_range, the literal reading of the paper; then every row gets the same Δ).
TYN_FUNC float tyn_reference_sin_mean_theta(vec2 theta_range) {
  return max(sin(0.5f * (theta_range.x + theta_range.y)), TYN_RECT_MIN_SIN);
}

// klehm2014 §3.2: ω_min (smallest Δ) is the direction of the slice closest to ω_l^⊥ (θ nearest
// π/2), ω_max (largest Δ) the one farthest from it (the end of the interval farthest from π/2).
// optimal = false: the bisectrix of ω_min and ω_max, which the paper uses throughout; true: the
// minimiser of max(c_min⁻¹, c_max), k_ref = √(k(ω_min)·k(ω_max)), which the paper notes fails when
// ω_max ∥ ω_l (k = 0) — the bisectrix is returned then.
TYN_FUNC float tyn_reference_sin_klehm(vec2 theta_range, bool optimal) {
  float half_pi = 0.5f * TYN_PI;
  float theta_near = clamp(half_pi, theta_range.x, theta_range.y);
  float theta_far = abs(theta_range.x - half_pi) > abs(theta_range.y - half_pi) ? theta_range.x
                                                                               : theta_range.y;
  if (optimal) {
    float k = sqrt(sin(theta_near) * max(sin(theta_far), 0.0f));
    if (k > TYN_RECT_MIN_SIN) return k;
  }
  return max(sin(0.5f * (theta_near + theta_far)), TYN_RECT_MIN_SIN);
}

// Δ(v): world distance along the reference ray per texel of radial size delta_r.
TYN_FUNC float tyn_slice_sample_spacing(float delta_r, float reference_sin) {
  return delta_r / max(reference_sin, TYN_RECT_MIN_SIN);
}

// ---------------------------------------------------------------------------------------------
// Transmittance-weighted prefix sums

// Distance interval [t_i, t_{i+1}] of texel i of a non-linear row for the reference ray.
TYN_FUNC vec2 tyn_nonlinear_texel_span(uint texel, float spacing) {
  return vec2(float(texel) * spacing, float(texel + 1u) * spacing);
}

// w = ∫_{t_lo}^{t_hi} e^{−σ t} dt (peters2017's w_{u,v}, klehm2014 Eq. 11 divided by σ), in the
// cancellation-free form of segment_integral.h, exact for σ = 0 (the length).
TYN_FUNC float tyn_prefix_weight(vec2 t_span, float sigma_t) {
  float len = max(t_span.y - t_span.x, 0.0f);
  return exp(-sigma_t * t_span.x) * len * tyn_one_minus_exp_over_x(sigma_t * len);
}

// One step of the normalised prefix sum (klehm2014 Listings 1–2): the weighted average up to the
// previous texel blended with the new texel's value; weight_sum includes `weight`. Requires
// weight_sum > 0 (w_0 > 0: the first texel has positive length).
TYN_FUNC vec4 tyn_prefix_blend(vec4 average, vec4 value, float weight, float weight_sum) {
  return mix(average, value, weight / weight_sum);
}

// Where a pixel whose surface is at texture coordinate u reads the prefix sums (N texels per
// row): half a texel back, because texel i's value covers the row up to its far edge.
TYN_FUNC float tyn_prefix_lookup_u(float u, float texels) { return u - 0.5f / texels; }

// L_in of a directional light for one view ray (DESIGN.md "Radiometry", peters2017 §5.1.1):
// radiance_factor = Σ σ_s·p(cos θ)·E (per channel), visibility = the reconstructed 1 − shadow
// (per channel when there is one prefix-sum set per channel, else the same in all three),
// distance = s, the ray's length to its surface. The de-normalisation of the stored averages is
// the exact ∫_0^s e^{−σ_t t} dt of this ray.
TYN_FUNC vec3 tyn_prefiltered_inscattering(vec3 radiance_factor, vec3 visibility, float distance,
                                           vec3 sigma_t) {
  return radiance_factor * visibility * tyn_transmittance_integral(0.0f, distance, sigma_t);
}

// The largest error, over all visibility functions V ∈ [0, 1] along a ray, of a weighted average
// of V taken with weights e^{−A τ} instead of e^{−B τ} on τ ∈ [0, 1] (A, B ≥ 0: the two optical
// depths over the ray). It is the total-variation distance of the two normalised densities
// p_X(τ) = e^{−Xτ}/ome(X), ome(X) = (1 − e^{−X})/X: they cross once, at τ* = ln(ome(a)/ome(b))/(b − a)
// (a < b), the steeper one (b) is larger before it, and the worst V is the indicator of [0, τ*]:
// error = F_b(τ*) − F_a(τ*) with F_X(τ) = τ·ome(Xτ)/ome(X). Symmetric in A and B; 0 when A = B.
TYN_FUNC float tyn_weighted_average_max_error(float optical_depth_a, float optical_depth_b) {
  float a = min(optical_depth_a, optical_depth_b);
  float b = max(optical_depth_a, optical_depth_b);
  if (!(b > a)) return 0.0f;
  float ome_a = tyn_one_minus_exp_over_x(a);
  float ome_b = tyn_one_minus_exp_over_x(b);
  float tau = clamp(log(ome_a / ome_b) / (b - a), 0.0f, 1.0f);
  return max(tau * (tyn_one_minus_exp_over_x(b * tau) / ome_b -
                    tyn_one_minus_exp_over_x(a * tau) / ome_a), 0.0f);
}

// ---------------------------------------------------------------------------------------------
// Fourier basis (klehm2014 §3.1, Eq. 8–9; Annen et al. 2007)
//
// Visibility of a ray sample at normalised depth z_r against an occluder at z_i (both in [0, 1])
// is V = 1 when z_r ≤ z_i (the sample is in front of the occluder), else 0 — klehm2014 writes it
// H(z_r − z_i) with a "Heaviside" that is 1 for NEGATIVE arguments. As a function of
// x = z_r − z_i ∈ [−1, 1], V − ½ = −½·sgn(x); extended with period 2 this is an odd square wave:
//   −½·sgn(x) = −(2/π)·Σ_{k≥1} sin(c_k x)/(2k − 1) = −Σ_k (2/c_k)·sin(c_k x),  c_k = π(2k − 1)
// and sin(c_k(z_r − z_i)) = sin(c_k z_r)cos(c_k z_i) − cos(c_k z_r)sin(c_k z_i) separates it into
//   V ≈ ½ + Σ_{k=1}^{K} a_{2k−1}(z_r)·B_{2k−1}(z_i) + a_{2k}(z_r)·B_{2k}(z_i),
//   B_{2k−1} = sin(c_k z_i), B_{2k} = cos(c_k z_i), a_{2k−1} = (2/c_k)cos(c_k z_r), a_{2k} = −(2/c_k)sin(c_k z_r)
// — exactly klehm2014's Eq. 8, which is therefore right for the correct visibility. K = 16
// (M = 32). Truncation rings (Gibbs: the partial sums overshoot by ≈ 8.9% of the jump next to
// x = 0); reconstruction clamps to [0, 1] as the paper does, and no window is applied (this is the
// published baseline). The series is 2-periodic in x, so it also jumps at x = ±1 (z_r = 1 against
// an occluder at 0 gives ½): the guard band keeps ray depths off 0 and 1 for this reason.
// Layer l ∈ [0, 8) packs harmonics k = 2l + 1 and 2l + 2 as (B_{2k−1}, B_{2k}, B_{2k'−1}, B_{2k'}).
// Filtered (prefix-averaged) B stay in [−1, 1] and are stored in unorm8 as ½ + ½·B.

// c_k = π(2k − 1), k ≥ 1.
TYN_FUNC float tyn_fourier_frequency(uint k) { return TYN_PI * float(2u * k - 1u); }

// (sin c_k z, cos c_k z, sin c_k' z, cos c_k' z), k = 2·layer + 1, k' = k + 1: B(z_i) of a texel.
TYN_FUNC vec4 tyn_fourier_basis(float z, uint layer) {
  float c0 = tyn_fourier_frequency(2u * layer + 1u);
  float c1 = tyn_fourier_frequency(2u * layer + 2u);
  return vec4(sin(c0 * z), cos(c0 * z), sin(c1 * z), cos(c1 * z));
}

// a(z_r) of a view ray for the same layer.
TYN_FUNC vec4 tyn_fourier_coefficients(float z_ray, uint layer) {
  float c0 = tyn_fourier_frequency(2u * layer + 1u);
  float c1 = tyn_fourier_frequency(2u * layer + 2u);
  return vec4(2.0f / c0 * cos(c0 * z_ray), -2.0f / c0 * sin(c0 * z_ray),
              2.0f / c1 * cos(c1 * z_ray), -2.0f / c1 * sin(c1 * z_ray));
}

// unorm8 storage of filtered basis values in [−1, 1] (klehm2014 §3.3, Appendix A).
TYN_FUNC vec4 tyn_fourier_pack(vec4 filtered) { return filtered * 0.5f + 0.5f; }
TYN_FUNC vec4 tyn_fourier_unpack(vec4 stored) { return stored * 2.0f - 1.0f; }

// ½ + Σ a·B̄ over the eight layers (unpacked values), before clamping.
TYN_FUNC float tyn_fourier_visibility_unclamped(float z_ray, vec4 filtered[TYN_FOURIER_LAYERS]) {
  float v = 0.5f;
  for (uint l = 0u; l < TYN_FOURIER_LAYERS; ++l) v += dot(tyn_fourier_coefficients(z_ray, l), filtered[l]);
  return v;
}

// The filtered visibility 1 − shadow, clamped to [0, 1] (klehm2014 Appendix A).
TYN_FUNC float tyn_fourier_visibility(float z_ray, vec4 filtered[TYN_FOURIER_LAYERS]) {
  return clamp(tyn_fourier_visibility_unclamped(z_ray, filtered), 0.0f, 1.0f);
}

// ---------------------------------------------------------------------------------------------
// Projective rectification (klehm2014 §4.2)

// (u, v, depth) of a world point: the projective map's texture coordinates (see the header
// comment). Valid for points with x > 0 (in particular the whole frustum beyond the camera).
TYN_FUNC vec3 tyn_projective_texcoord(ProjectiveRectificationParams proj, vec3 world) {
  vec4 clip = proj.world_to_clip * vec4(world, 1.0f);
  return vec3(clip.x / clip.w * 0.5f + 0.5f, clip.y / clip.w * 0.5f + 0.5f, clip.z / clip.w);
}

// The same from the camera-relative offset p − o (t·d along a view ray). world_to_clip maps o to
// (B, 0, 0, 0), B = −2·x_f·x_n/(x_f − x_n) (the light view takes o to the origin, the projection
// keeps only its translation column), so clip = M·(offset, 0) + (B, 0, 0, 0): no cancellation
// against the camera's world position, which costs a float world position its precision near a
// camera far from the origin. Prefer it in per-pixel passes.
TYN_FUNC vec3 tyn_projective_texcoord_from_offset(ProjectiveRectificationParams proj, vec3 offset) {
  float xn = proj.x_near;
  float xf = proj.x_far;
  vec4 clip = proj.world_to_clip * vec4(offset, 0.0f) + vec4(-2.0f * xf * xn / (xf - xn), 0.0f, 0.0f, 0.0f);
  return vec3(clip.x / clip.w * 0.5f + 0.5f, clip.y / clip.w * 0.5f + 0.5f, clip.z / clip.w);
}

// Light-frame x of column coordinate u: the inverse of u = x_f·(x − x_n)/((x_f − x_n)·x), a
// linear-fractional (Möbius) map — so distances along a ray do NOT grow by a constant factor per
// texel, whatever klehm2014 §4.2 (Eq. 12) says; the weights use this exact map instead.
TYN_FUNC float tyn_projective_x(ProjectiveRectificationParams proj, float u) {
  float xn = proj.x_near;
  float xf = proj.x_far;
  return xn * xf / (xf - u * (xf - xn));
}

// η and φ = atan η of row coordinate v.
TYN_FUNC float tyn_projective_eta(ProjectiveRectificationParams proj, float v) {
  return mix(proj.eta_lo, proj.eta_hi, v);
}

TYN_FUNC float tyn_projective_row_phi(ProjectiveRectificationParams proj, float v) {
  return atan(tyn_projective_eta(proj, v));
}

// Distance interval of column `texel` (of `texels`) along the reference ray of the row with
// ratio eta (r = x·√(1 + η²), t = r / sin θ_ref); the first column starts at the camera.
TYN_FUNC vec2 tyn_projective_texel_span(ProjectiveRectificationParams proj, uint texel, float texels,
                                        float eta, float reference_sin) {
  float scale = sqrt(1.0f + eta * eta) / max(reference_sin, TYN_RECT_MIN_SIN);
  float t_lo = texel == 0u ? 0.0f : tyn_projective_x(proj, float(texel) / texels) * scale;
  return vec2(t_lo, tyn_projective_x(proj, float(texel + 1u) / texels) * scale);
}

TYN_END

#endif
