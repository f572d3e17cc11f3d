#version 460
// Per-pixel evaluation (klehm2014 §3.1, peters2017 §5.1.1, §5.3, §5.4): one bilinear lookup of the
// prefix sums at the end of the pixel's view ray (one per prefix-sum set), the visibility averaged
// along the ray reconstructed from it, and L_in = Σσ_s p(cos θ) E · visibility · ∫_0^s e^{−σ_t t} dt.
//   - moments: dequantize, bias toward b* by α_b of the variant (§2.5), the sharp lower and upper
//     bounds of the shadow intensity (Algorithm 1: 3×3 Hankel and a quadratic for 4 moments, 4×4
//     and a cubic for 6), between them by β: the adaptive overestimation (§5.3.1) or a constant;
//   - Fourier: the clamped series ½ + Σ a_k(z_r) B̄_k (klehm2014 Eq. 9, Appendix A).
// With rayWeightTaps > 1 the lookup is K lookups along the row whose combination re-weights the
// row's prefix sums to the pixel's own ray (weight_taps.h). Segmented reconstruction (the default)
// reconstructs each of the K segments between the taps from the difference of two lookups and
// averages the K visibilities; trimmed segments (the default with the row depth bounds) count the
// runs at a segment's two ends that the row decides exactly and walk the columns between them
// (the texel walk), reconstructing only what the walk does not reach; otherwise the
// reconstruction runs once, on the combined representation. The transmittance T = e^{−σ_t s} is the composite's (exact per pixel).
// The storage variant is a specialisation constant: this pass only samples, so it needs no format qualifier.
#extension GL_GOOGLE_include_directive : require

#include "prefiltered/prefiltered_common.glsl"
#include "prefiltered/moments.h"
#include "prefiltered/weight_taps.h"
#include "common/medium.glsl"
#include "common/texel_walk.glsl"

layout(local_size_x = TYN_PIXEL_GROUP_SIZE, local_size_y = TYN_PIXEL_GROUP_SIZE) in;

layout(constant_id = 0) const uint TYN_PF_BASIS = 0u;

// The lookups of one pixel for one prefix-sum set: texture coordinates along the row (already
// shifted by tyn_prefix_lookup_u), the row coordinate, and the coefficients (summing to 1).
struct TynPfTaps {
  float u[TYN_PF_MAX_TAPS];
  float c[TYN_PF_MAX_TAPS];
  uint count;
  float v;
};

vec4 tyn_pf_fetch_a(TynPfTaps taps, float layer) {
  vec4 sum = vec4(0.0);
  for (uint k = 0u; k < taps.count; ++k) sum += taps.c[k] * texture(prefix_a, vec3(taps.u[k], taps.v, layer));
  return sum;
}

vec4 tyn_pf_fetch_b(TynPfTaps taps, float layer) {
  vec4 sum = vec4(0.0);
  for (uint k = 0u; k < taps.count; ++k) sum += taps.c[k] * texture(prefix_b, vec3(taps.u[k], taps.v, layer));
  return sum;
}

// 1 − shadow intensity along the ray for one prefix-sum set, at rectified depth `depth_ray`.
float tyn_pf_visibility(uint set, TynPfTaps taps, float depth_ray, float beta) {
  float zf = 2.0 * depth_ray - 1.0;  // signed depth of the moments
  float layer = float(set);
  vec2 bounds;
  if (TYN_PF_BASIS == TYN_PF_MOMENTS4_64) {
    vec4 b = tyn_dequantize_moments4_64(tyn_pf_fetch_a(taps, layer));
    bounds = tyn_moments4_bounds(tyn_bias_moments(b, TYN_MOMENTS4_64_B_STAR, TYN_MOMENTS4_64_ALPHA), zf);
  } else if (TYN_PF_BASIS == TYN_PF_MOMENTS4_128) {
    vec4 b = tyn_dequantize_moments4_128(tyn_pf_fetch_a(taps, layer));
    bounds = tyn_moments4_bounds(tyn_bias_moments(b, TYN_MOMENTS4_128_B_STAR, TYN_MOMENTS4_128_ALPHA), zf);
  } else if (TYN_PF_BASIS == TYN_PF_FOURIER32) {
    vec4 filtered[TYN_FOURIER_LAYERS];
    for (uint l = 0u; l < TYN_FOURIER_LAYERS; ++l) {
      filtered[l] = tyn_fourier_unpack(tyn_pf_fetch_a(taps, float(set * TYN_FOURIER_LAYERS + l)));
    }
    return tyn_fourier_visibility(depth_ray, filtered);
  } else {
    vec3 odd;
    vec3 even;
    float alpha;
    if (TYN_PF_BASIS == TYN_PF_MOMENTS6_64) {
      odd = tyn_dequantize_moments6_odd(tyn_pf_fetch_a(taps, 2.0 * layer).xyz);
      even = tyn_dequantize_moments6_even(tyn_pf_fetch_a(taps, 2.0 * layer + 1.0).xyz);
      alpha = TYN_MOMENTS6_64_ALPHA;
    } else {
      vec4 a = tyn_pf_fetch_a(taps, layer);
      vec2 b = tyn_pf_fetch_b(taps, layer).xy;
      odd = a.xyz;
      even = vec3(a.w, b);
      if (TYN_PF_BASIS == TYN_PF_MOMENTS6_96) {
        odd = tyn_dequantize_moments6_odd(odd);
        even = tyn_dequantize_moments6_even(even);
        alpha = TYN_MOMENTS6_96_ALPHA;
      } else {
        alpha = TYN_MOMENTS6_192_ALPHA;
      }
    }
    bounds = tyn_moments6_bounds(tyn_bias_moments(odd, TYN_MOMENTS6_B_STAR_ODD, alpha),
                                 tyn_bias_moments(even, TYN_MOMENTS6_B_STAR_EVEN, alpha), zf);
  }
  return 1.0 - tyn_shadow_intensity(bounds, beta);
}

// The visibility of the columns between u_a and u_b of a row (before tyn_prefix_lookup_u's shift;
// the reference's weights w_a, w_b there): the difference of the two lookups
// (tyn_segment_coefficients), reconstructed. w_a = 0 (the ray's start) reads u_b alone.
float tyn_pf_part_visibility(uint set, float v, float columns, float u_a, float u_b, float w_a, float w_b,
                             float depth_ray, float beta) {
  vec2 c = tyn_segment_coefficients(w_a, w_b);
  TynPfTaps part;
  part.v = v;
  part.count = c.y == 0.0 ? 1u : 2u;
  part.u[0] = tyn_prefix_lookup_u(u_b, columns);
  part.c[0] = c.x;
  part.u[1] = tyn_prefix_lookup_u(u_a, columns);
  part.c[1] = c.y;
  return tyn_pf_visibility(set, part, depth_ray, beta);
}

// The reference distance τ at which the row is read at u (the inverse of tyn_weight_tap_u_*).
float tyn_pf_tap_tau(float u, float reference_sin, float eta) {
  return tyn_pf_projective() ? tyn_weight_tap_tau_projective(pf.projective, u, reference_sin, eta)
                             : tyn_weight_tap_tau_nonlinear(u, reference_sin, pf.nonlinear.r_max);
}

// The visibility at depth_ray of one row's texel of the walk, whose texel bounds are `bounds`:
// their verdict where they give one, else the share of its two depths (depth_bounds.h "Texel walk").
float tyn_pf_row_texel_visibility(ivec2 texel, vec2 bounds, float depth_ray) {
  float verdict = tyn_depth_bounds_verdict(bounds, depth_ray);
  return verdict >= 0.0 ? verdict : tyn_two_depth_visibility(imageLoad(texel_depths, texel).xyz, depth_ray);
}

// One segment [u_lo, u_hi] of a row for the trimmed segments: its ends and weights, and the ray's
// pace through it (the arguments every column edge's weight needs).
struct TynPfSegment {
  float u_lo;
  float u_hi;
  float w_lo;    // the reference's weight at u_lo (0 at the ray's start)
  float w_hi;
  float own_lo;  // the pixel's own weight there (rate σκ along τ)
  float own_hi;
  float sigma;
  float own_rate;
  float reference_sin;
  float eta;
};

// The texture coordinate of the left edge of column i inside the segment, whose first and last
// columns (c_lo, c_hi) it covers only from u_lo and up to u_hi.
float tyn_pf_edge_u(TynPfSegment g, ivec2 c_lo_hi, int i, float n) {
  return i <= c_lo_hi.x ? g.u_lo : i > c_lo_hi.y ? g.u_hi : float(i) / n;
}

// The pixel's own weight W(σκ, τ) up to u, and the reference's W(σ, τ) (the prefix sums'). The
// segment's own ends keep their given weights: u = 0 is the ray's start, which the projective map
// does not put at τ = 0.
float tyn_pf_own_weight(TynPfSegment g, float u) {
  if (u == g.u_lo) return g.own_lo;
  if (u == g.u_hi) return g.own_hi;
  return tyn_prefix_weight(g.own_rate, tyn_pf_tap_tau(u, g.reference_sin, g.eta));
}

float tyn_pf_reference_weight(TynPfSegment g, float u) {
  if (u == g.u_lo) return g.w_lo;
  if (u == g.u_hi) return g.w_hi;
  return tyn_prefix_weight(g.sigma, tyn_pf_tap_tau(u, g.reference_sin, g.eta));
}

// What a trimmed segment leaves to the reconstruction: the columns [u_first, u_q] (the reference's
// weights w_first, w_q there) whose reconstructed visibility counts `own` of the pixel's weight.
// The segment's visibility is (lit + reconstructed · own) / total, or `decided` when total is 0.
struct TynPfSegmentRest {
  float lit;
  float own;
  float total;
  float decided;
  float u_first;
  float u_q;
  float w_first;
  float w_q;
  bool reconstruct;
};

// A rest with nothing to reconstruct: visibility `visibility`.
TynPfSegmentRest tyn_pf_segment_decided(float visibility) {
  TynPfSegmentRest rest;
  rest.lit = 0.0;
  rest.own = 0.0;
  rest.total = 0.0;
  rest.decided = visibility;
  rest.u_first = 0.0;
  rest.u_q = 0.0;
  rest.w_first = 0.0;
  rest.w_q = 0.0;
  rest.reconstruct = false;
  return rest;
}

// Trimmed segment (depth_bounds.h): segment [u_lo, u_hi] of a row loses the run of texels at each
// end that the row decides on its own; the runs count 0 or 1 with the pixel's own weights, and the
// columns between them are walked for up to pf.texel_walk_steps steps (depth_bounds.h "Texel walk"); what
// the walk does not reach is left to the reconstruction (the rest returned), which the caller runs
// for all segments of the pixel together.
TynPfSegmentRest tyn_pf_trimmed_segment(ivec3 rows_columns, float row_fraction, TynPfSegment g, float depth_ray) {
  int columns = rows_columns.z;
  float n = float(columns);
  int c_lo = clamp(int(floor(g.u_lo * n)), 0, columns - 1);
  int c_hi = clamp(int(floor(g.u_hi * n)), c_lo, columns - 1);
  ivec2 c_lo_hi = ivec2(c_lo, c_hi);
  // A segment whose whole prefix the row decides is that side, as the search from c_lo would find
  // after O(log N) nodes: the running bounds at c_hi say it in one read of each row.
  float prefix_side = tyn_depth_bounds_verdict(
      tyn_depth_bounds_merge(imageLoad(depth_bounds_prefix, ivec2(c_hi, rows_columns.x)).xy,
                             imageLoad(depth_bounds_prefix, ivec2(c_hi, rows_columns.y)).xy),
      depth_ray);
  if (prefix_side >= 0.0) return tyn_pf_segment_decided(prefix_side);
  float side_a = tyn_depth_bounds_verdict(tyn_depth_bounds_node(rows_columns, 0u, c_lo), depth_ray);
  int p = side_a < 0.0 ? c_lo : tyn_depth_bounds_run_end(rows_columns, c_lo, c_hi, depth_ray, side_a);
  if (p > c_hi) return tyn_pf_segment_decided(side_a);
  float side_b = tyn_depth_bounds_verdict(tyn_depth_bounds_node(rows_columns, 0u, c_hi), depth_ray);
  int q = side_b < 0.0 ? c_hi : tyn_depth_bounds_run_begin(rows_columns, p, c_hi, depth_ray, side_b);
  // The pixel's own weight of each part: the runs are exact, so their share should be the ray's,
  // not the reference's (which, slower, gives the later part of a segment too much).
  float own_p = tyn_pf_own_weight(g, tyn_pf_edge_u(g, c_lo_hi, p, n));
  float own_q = tyn_pf_own_weight(g, tyn_pf_edge_u(g, c_lo_hi, q + 1, n));
  float lit = max(side_a, 0.0) * (own_p - g.own_lo) + max(side_b, 0.0) * (g.own_hi - own_q);
  // The walk through the middle [p, q]: a step is a decided run or one undecided texel.
  int first = p;
  float own_first = own_p;
  // One loop reads one node of the two rows' tree (both rows of the lookup) per iteration: at a
  // step's first column (level 0, x = column) the merged bounds decide a run, apart they decide
  // each row of an undecided texel, whose rows are then interpolated by `row_fraction` as the
  // bilinear lookup does; inside a run the iterations are tyn_depth_bounds_run_end's, one node
  // each. Pixels that run side by side then share iterations whether they walk texels or runs.
  uint levels = tyn_depth_bounds_levels(columns);
  int i = first;             // the node read next, of `level`
  uint level = 0u;
  float run_side = -1.0;     // the side of the run being searched; −1 at a step's first column
  uint step = 0u;
  for (uint iteration = 0u; iteration < pf.texel_walk_steps * 4u * TYN_DEPTH_BOUNDS_MAX_LEVELS &&
                            step < pf.texel_walk_steps && first <= q; ++iteration) {
    int next = -1;
    float visibility = run_side;
    if (run_side >= 0.0 && ((i << level) > q || i >= tyn_depth_bounds_level_nodes(columns, level))) {
      next = q + 1;
    } else {
      int x = tyn_depth_bounds_level_offset(columns, level) + i;
      ivec2 texel0 = ivec2(x, rows_columns.x);
      ivec2 texel1 = ivec2(x, rows_columns.y);
      vec2 bounds0 = imageLoad(depth_bounds_texels, texel0).xy;
      vec2 bounds1 = imageLoad(depth_bounds_texels, texel1).xy;
      float side = tyn_depth_bounds_verdict(tyn_depth_bounds_merge(bounds0, bounds1), depth_ray);
      if (run_side < 0.0 && side < 0.0) {
        next = first + 1;
        visibility = mix(tyn_pf_row_texel_visibility(texel0, bounds0, depth_ray),
                         tyn_pf_row_texel_visibility(texel1, bounds1, depth_ray), row_fraction);
      } else if (run_side < 0.0 || side == run_side) {
        run_side = side;
        i += 1;
        while ((i & 1) == 0 && level + 1u < levels) {
          i >>= 1;
          level += 1u;
        }
      } else if (level == 0u) {
        next = i;
      } else {
        i *= 2;
        level -= 1u;
      }
    }
    if (next >= 0) {
      float own_next = next > q ? own_q : tyn_pf_own_weight(g, tyn_pf_edge_u(g, c_lo_hi, next, n));
      lit += visibility * (own_next - own_first);
      first = next;
      own_first = own_next;
      step += 1u;
      i = next;
      level = 0u;
      run_side = -1.0;
    }
  }
  TynPfSegmentRest rest = tyn_pf_segment_decided(side_a);
  rest.lit = lit;
  rest.total = g.own_hi - g.own_lo;
  if (first <= q) {
    rest.u_first = tyn_pf_edge_u(g, c_lo_hi, first, n);
    rest.u_q = tyn_pf_edge_u(g, c_lo_hi, q + 1, n);
    rest.w_first = tyn_pf_reference_weight(g, rest.u_first);
    rest.w_q = tyn_pf_reference_weight(g, rest.u_q);
    rest.own = own_q - own_first;
    rest.reconstruct = rest.w_q > rest.w_first;
  }
  return rest;
}

void main() {
  // Invocations in runs of 8 (a CPU driver's SIMD lanes; a quarter of a GPU's warp) take 4 × 2
  // pixel blocks rather than rows of 8: the closer the pixels, the more alike their rays' work.
  uint lane = gl_LocalInvocationIndex;
  uint block = lane >> 3u;
  uvec2 pixel = gl_WorkGroupID.xy * TYN_PIXEL_GROUP_SIZE +
                uvec2((block % (TYN_PIXEL_GROUP_SIZE / 4u)) * 4u + (lane & 3u),
                      (block / (TYN_PIXEL_GROUP_SIZE / 4u)) * 2u + ((lane >> 2u) & 1u));
  if (any(greaterThanEqual(pixel, frame.target_extent))) return;

  // `pixel` is the L_in target's; its ray is the output pixel's it stands for.
  uvec2 output_pixel = tyn_output_pixel(pixel);
  float depth = texelFetch(depth_buffer, ivec2(output_pixel), 0).r;
  TynViewRay ray = tyn_view_ray(output_pixel, depth);
  float s = ray.surface_distance;

  // Where the ray ends in the rectified map, and its (constant) rectified depth. Both forms take
  // the ray's direction and length, not a world position (rectification.h "Precision").
  vec3 uvd;
  if (tyn_pf_projective()) {
    uvd = tyn_projective_texcoord_from_offset(pf.projective, ray.direction * s);
  } else {
    uvd = tyn_rectified_texcoord(pf.nonlinear, tyn_rectified_from_view_ray(pf.nonlinear, ray.direction, s));
  }
  float columns = float(pf.map_columns);
  // Short rays (PrefilteredSettings::shortRayColumns): a ray ending within the first few columns
  // of its row is a handful of texels of the rectified map, too few for the reconstruction; its
  // stretch across the host's map is as short, so it takes the Reference's walk instead.
  if (uvd.x * columns < float(pf.short_ray_columns)) {
    vec3 in_scattering = tyn_reference_in_scattering(ray.origin, ray.direction, s);
    imageStore(out_scattering, ivec2(pixel), tyn_target_value(in_scattering));
    return;
  }
  float v = tyn_pf_lookup_v(uvd.y);
  float depth_ray = clamp(uvd.z, 0.0, 1.0);

  // The ray's pace through its row against the row's reference ray: κ = sin θ_ref / sin θ ≥ 1 for
  // the fastest-ray reference (rayWeightTaps > 1 requires it).
  uint tap_count = pf.ray_weight_taps;
  vec2 slice = tyn_view_ray_slice(pf.nonlinear, ray.direction);
  float reference_sin = tyn_pf_reference_sin(slice.x);
  float kappa = max(reference_sin / max(sin(slice.y), TYN_RECT_MIN_SIN), 1.0);
  float tau_end = s / kappa;
  float eta = tyn_pf_projective() ? tyn_projective_eta(pf.projective, uvd.y) : 0.0;

  vec3 to_light = -frame.light_direction;
  float beta = pf.overestimation < 0.0 ? tyn_adaptive_overestimation(to_light, -ray.direction) : pf.overestimation;
  // Rays the row's occluders decide on their own (all in front, or none) skip the reconstruction:
  // the row depth bounds (depth_bounds.h), the same for every prefix-sum set.
  float verdict = tyn_pf_depth_bounds() ? tyn_pf_depth_bounds_verdict(uvd.x, v, depth_ray) : -1.0;
  vec3 set_visibility = vec3(max(verdict, 0.0));
  bool segmented = pf.segmented != 0u;
  for (uint set = 0u; verdict < 0.0 && set < pf.prefix_sum_sets; ++set) {
    TynPfTaps taps;
    taps.v = v;
    if (tap_count <= 1u) {
      taps.count = 1u;
      taps.u[0] = tyn_prefix_lookup_u(uvd.x, columns);
      taps.c[0] = 1.0;
      set_visibility[set] = tyn_pf_visibility(set, taps, depth_ray, beta);
      continue;
    }
    // The K taps: where each reads (u, before the half-texel shift) and the reference's weight up
    // to it. Only the combined lookup needs the taps' coefficients (tyn_weight_tap, several
    // exponentials and logarithms each), so the segments take the fraction alone.
    float sigma = pf.set_extinction[set];
    float optical_depth = sigma * kappa * tau_end;
    float tap_u[TYN_PF_MAX_TAPS];
    float tap_w[TYN_PF_MAX_TAPS];
    for (uint k = 0u; k < tap_count; ++k) {
      float tau = tyn_weight_tap_fraction(optical_depth, k + 1u, tap_count) * tau_end;
      // The last tap is the ray's end itself, where the single lookup reads.
      tap_u[k] = k + 1u == tap_count ? uvd.x
                 : tyn_pf_projective() ? tyn_weight_tap_u_projective(pf.projective, tau, reference_sin, eta)
                                       : tyn_weight_tap_u_nonlinear(tau, reference_sin, pf.nonlinear.r_max);
      tap_w[k] = tyn_prefix_weight(sigma, tau);
    }
    if (!segmented) {
      float sum = 0.0;
      for (uint k = 0u; k < tap_count; ++k) {
        taps.u[k] = tyn_prefix_lookup_u(tap_u[k], columns);
        taps.c[k] = tyn_weight_tap(sigma, kappa, tau_end, k + 1u, tap_count).y;
        sum += taps.c[k];
      }
      // Σ c = 1 in exact arithmetic; the rounding that tyn_weight_tap clamps is renormalised.
      taps.count = tap_count;
      for (uint k = 0u; k < tap_count; ++k) taps.c[k] /= max(sum, 1.0e-30);
      set_visibility[set] = tyn_pf_visibility(set, taps, depth_ray, beta);
      continue;
    }
    // Segmented: each segment holds 1/K of the ray's weight and is reconstructed on its own
    // (tyn_segment_coefficients). Its occluders are the row's between two taps, so the prefix's
    // depth bounds at its end decide it when they can, whatever the segments after it hold.
    float visible = 0.0;
    bool trimmed = pf.trimmed != 0u;
    float row_fraction = fract(v * float(pf.map_rows) - 0.5);  // the second row's share (tyn_depth_bounds_texels)
    ivec3 rows_columns = ivec3(tyn_depth_bounds_texels(uvd.x, v, int(pf.map_columns), int(pf.map_rows), pf.rows_wrap != 0u).yz,
                               int(pf.map_columns));
    TynPfSegment segment;
    segment.sigma = sigma;
    segment.own_rate = sigma * kappa;
    segment.reference_sin = reference_sin;
    segment.eta = eta;
    segment.u_hi = 0.0;
    segment.w_hi = 0.0;
    segment.own_hi = 0.0;
    if (trimmed) {
      // The segments first, then the reconstructions they leave, in one loop over those alone: a
      // pixel pays for as many reconstructions as it needs, not one at every segment where some
      // pixel that runs beside it needs one.
      TynPfSegmentRest rests[TYN_PF_MAX_TAPS];
      uint pending[TYN_PF_MAX_TAPS];
      uint pending_count = 0u;
      for (uint k = 0u; k < tap_count; ++k) {
        // Segment k starts where segment k − 1 ended (the ray's start for the first).
        segment.u_lo = segment.u_hi;
        segment.w_lo = segment.w_hi;
        segment.own_lo = segment.u_lo > 0.0 ? segment.own_hi : 0.0;
        segment.u_hi = tap_u[k];
        segment.w_hi = tap_w[k];
        segment.own_hi = tyn_prefix_weight(segment.own_rate, tyn_pf_tap_tau(tap_u[k], reference_sin, eta));
        rests[k] = tyn_pf_trimmed_segment(rows_columns, row_fraction, segment, depth_ray);
        if (rests[k].reconstruct) pending[pending_count++] = k;
      }
      for (uint i = 0u; i < pending_count; ++i) {
        uint k = pending[i];
        TynPfSegmentRest rest = rests[k];
        rests[k].lit += tyn_pf_part_visibility(set, v, columns, rest.u_first, rest.u_q, rest.w_first, rest.w_q,
                                               depth_ray, beta) * rest.own;
      }
      for (uint k = 0u; k < tap_count; ++k) {
        visible += rests[k].total > 0.0 ? rests[k].lit / rests[k].total : rests[k].decided;
      }
    }
    for (uint k = 0u; !trimmed && k < tap_count; ++k) {
      float segment_verdict = tyn_pf_depth_bounds() ? tyn_pf_depth_bounds_verdict(tap_u[k], v, depth_ray) : -1.0;
      if (segment_verdict >= 0.0) {
        visible += segment_verdict;
        continue;
      }
      visible += tyn_pf_part_visibility(set, v, columns, k == 0u ? 0.0 : tap_u[k - 1u], tap_u[k],
                                        k == 0u ? 0.0 : tap_w[k - 1u], tap_w[k], depth_ray, beta);
    }
    set_visibility[set] = visible / float(tap_count);
  }
  vec3 visibility = vec3(set_visibility[pf.channel_set.x], set_visibility[pf.channel_set.y],
                         set_visibility[pf.channel_set.z]);
  vec3 radiance_factor =
      frame.light_radiance * tyn_phase_weighted_scattering(dot(ray.direction, to_light));
  vec3 in_scattering = tyn_prefiltered_inscattering(radiance_factor, visibility, s, frame.extinction);
  imageStore(out_scattering, ivec2(pixel), tyn_target_value(in_scattering));
}
