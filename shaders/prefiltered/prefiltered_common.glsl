// Declarations every prefiltered pass shares: one descriptor set layout (the storage images, whose
// format qualifiers depend on the storage variant, are declared by storage_variants.glsl) and the
// helpers that map texels of the rectified map to light rays.
#ifndef TYNDALL_PREFILTERED_COMMON_GLSL
#define TYNDALL_PREFILTERED_COMMON_GLSL

#include "common/shared_constants.h"
#include "prefiltered/prefiltered_constants.h"
#include "prefiltered/depth_bounds.h"

layout(set = 0, binding = TYN_PF_BINDING_FRAME, std140) uniform FrameBlock { FrameConstants frame; };
#include "common/scattering_target.glsl"
layout(set = 0, binding = TYN_PF_BINDING_DEPTH) uniform sampler2D depth_buffer;
layout(set = 0, binding = TYN_PF_BINDING_SHADOW_MAPS) uniform sampler2D shadow_maps[TYN_MAX_SHADOW_MAPS];
layout(set = 0, binding = TYN_PF_BINDING_CONSTANTS, std140) uniform PrefilteredBlock { PrefilteredConstants pf; };
layout(set = 0, binding = TYN_PF_BINDING_OUT_SCATTERING, TYN_SCATTERING_TARGET_FORMAT) uniform image2D out_scattering;
// The light-colour texture (common/light_color.glsl), read by the epipole block's Reference walk.
layout(set = 0, binding = TYN_PF_BINDING_LIGHT_COLOR) uniform sampler2D light_color;
// Four moments of the host's signed depth, Θ4*-quantized (RGBA16_UNORM), bilinear, clamped to the edge.
layout(set = 0, binding = TYN_PF_BINDING_MOMENT_MAP) uniform sampler2D moment_shadow_map;
// TYN_PF_BINDING_MOMENT_MAP_STORAGE: the moment map as a storage image (moment_shadow_map.comp).
// The rectified map, one or two images (nearest: texelFetch only).
layout(set = 0, binding = TYN_PF_BINDING_RECTIFIED_A) uniform sampler2DArray rectified_a;
layout(set = 0, binding = TYN_PF_BINDING_RECTIFIED_B) uniform sampler2DArray rectified_b;
// TYN_PF_BINDING_RECTIFIED_*_STORAGE: the rectified map as storage images (storage_variants.glsl).
// The prefix sums: bilinear, clamped along rows (u), repeating across them (v) for the full
// circle; a map that does not wrap clamps v itself (tyn_pf_lookup_v).
layout(set = 0, binding = TYN_PF_BINDING_PREFIX_A) uniform sampler2DArray prefix_a;
layout(set = 0, binding = TYN_PF_BINDING_PREFIX_B) uniform sampler2DArray prefix_b;
// TYN_PF_BINDING_PREFIX_*_STORAGE: the prefix sums as storage images (storage_variants.glsl).
layout(set = 0, binding = TYN_PF_BINDING_FIXUP_ARGS, std430) buffer FixupBlock { PrefilteredFixupArgs fixup_args; };
// Row depth bounds (depth_bounds.h), RG16_UNORM: each rectified texel's smallest and largest
// occluder depth (written by the rectification) followed by the levels of the row's min/max tree,
// and their running min and max along the row (both written by the prefix-sum pass, read by the
// evaluation). 1 × 1 placeholders when off.
layout(set = 0, binding = TYN_PF_BINDING_DEPTH_BOUNDS_TEXELS, rg16) uniform coherent image2D depth_bounds_texels;
layout(set = 0, binding = TYN_PF_BINDING_DEPTH_BOUNDS_PREFIX, rg16) uniform image2D depth_bounds_prefix;
// The texel walk's depths (depth_bounds.h "Texel walk"), RGBA16_UNORM: each rectified texel's two
// rectified depths and the second's weight (the distribution its representation holds), written by
// the rectification and read by the evaluation. 1 × 1 placeholder when off.
layout(set = 0, binding = TYN_PF_BINDING_TEXEL_DEPTHS, rgba16) uniform image2D texel_depths;

#include "common/view_ray.glsl"

NonLinearRectificationParams tyn_pf_rect() { return pf.nonlinear; }
ProjectiveRectificationParams tyn_pf_proj() { return pf.projective; }
bool tyn_pf_projective() { return pf.projective_map != 0u; }

// Camera-relative offset of the light ray through the centre of a rectified texel (texture
// coordinates tc), at light-frame height h = 0, and the ray's radial coordinate in the map's
// terms: r for the non-linear map, x for the projective one (both > 0 at texel centres).
vec3 tyn_pf_light_ray_offset(vec2 tc, out float radial) {
  if (tyn_pf_projective()) {
    float x = tyn_projective_x(pf.projective, tc.x);
    float eta = tyn_projective_eta(pf.projective, tc.y);
    radial = x;
    return x * pf.nonlinear.axis_x + (eta * x) * pf.nonlinear.axis_y;
  }
  float r = tc.x * pf.nonlinear.r_max;
  float phi = (tc.y - 0.5) * pf.nonlinear.phi_extent;
  radial = r;
  return r * (cos(phi) * pf.nonlinear.axis_x + sin(phi) * pf.nonlinear.axis_y);
}

// Normalised rectified depth of the point at light-frame height h on that light ray, clamped to
// [0, 1] (klehm2014 §4.1: occluders outside the frustum's range keep their effect).
float tyn_pf_rectified_depth(float radial, float h) {
  if (tyn_pf_projective()) {
    return clamp((h / radial - pf.projective.zeta_lo_guarded) / (pf.projective.zeta_hi_guarded - pf.projective.zeta_lo_guarded), 0.0, 1.0);
  }
  return clamp(tyn_rectified_depth(pf.nonlinear, atan(radial, h)), 0.0, 1.0);
}

// The slice (epipolar plane) of a row: its azimuth φ and, for the projective map, η = tan φ.
float tyn_pf_row_phi(float v) {
  if (tyn_pf_projective()) return tyn_projective_row_phi(pf.projective, v);
  return (v - 0.5) * pf.nonlinear.phi_extent;
}

// The sine of the reference ray of a slice (the setting's heuristic), from the slice's own
// inclination range; a slice that misses the frustum (no pixel reads it) takes the frustum's.
float tyn_pf_reference_sin(float phi) {
  vec2 range = tyn_slice_theta_range(pf.nonlinear, phi);
  if (range.x > range.y) range = pf.nonlinear.theta_range;
  if (pf.spacing == TYN_PF_SPACING_REFERENCE_RAY) return tyn_reference_sin_klehm(range, false);
  // The slice's fastest ray: the inclination nearest π/2 (klehm2014 §3.2's ω_min).
  if (pf.spacing == TYN_PF_SPACING_FASTEST_RAY) return max(sin(clamp(0.5 * TYN_PI, range.x, range.y)), TYN_RECT_MIN_SIN);
  return tyn_reference_sin_mean_theta(range);
}

// Row coordinate of a lookup: a map that does not wrap is clamped to its first and last rows'
// centres (the sampler repeats along v for the full circle).
float tyn_pf_lookup_v(float v) {
  if (pf.rows_wrap != 0u) return v;
  float half_texel = 0.5 / float(pf.map_rows);
  return clamp(v, half_texel, 1.0 - half_texel);
}

// pf.depth_bounds: the row depth bounds are built and read (PrefilteredSettings::depthBounds).
bool tyn_pf_depth_bounds() { return pf.depth_bounds != 0u; }

// pf.texel_walk_steps: steps of the texel walk per trimmed segment (PrefilteredSettings::texelWalkSteps).
bool tyn_pf_texel_walk() { return pf.texel_walk_steps != 0u; }

// A node of the min/max tree of the two rows (row0, row1, N) a lookup reads (depth_bounds.h).
vec2 tyn_depth_bounds_node(ivec3 rows_columns, uint level, int index) {
  int x = tyn_depth_bounds_level_offset(rows_columns.z, level) + index;
  return tyn_depth_bounds_merge(imageLoad(depth_bounds_texels, ivec2(x, rows_columns.x)).xy,
                                imageLoad(depth_bounds_texels, ivec2(x, rows_columns.y)).xy);
}

// The verdict of the row's occluders on a whole view ray ending at (u, v) with rectified depth
// depth_ray: 0 in shadow, 1 lit, −1 for the reconstruction (depth_bounds.h).
float tyn_pf_depth_bounds_verdict(float u, float v, float depth_ray) {
  ivec3 t = tyn_depth_bounds_texels(u, v, int(pf.map_columns), int(pf.map_rows), pf.rows_wrap != 0u);
  vec2 bounds = tyn_depth_bounds_merge(imageLoad(depth_bounds_prefix, t.xy).xy,
                                       imageLoad(depth_bounds_prefix, t.xz).xy);
  return tyn_depth_bounds_verdict(bounds, depth_ray);
}

#endif
