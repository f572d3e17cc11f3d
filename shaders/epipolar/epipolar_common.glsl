// Declarations every epipolar pass shares: one descriptor set layout and the push constants.
#ifndef TYNDALL_EPIPOLAR_COMMON_GLSL
#define TYNDALL_EPIPOLAR_COMMON_GLSL

#include "common/shared_constants.h"
#include "epipolar/epipolar_constants.h"

layout(set = 0, binding = TYN_EPIPOLAR_BINDING_FRAME, std140) uniform FrameBlock { FrameConstants frame; };
#include "common/scattering_target.glsl"
layout(set = 0, binding = TYN_EPIPOLAR_BINDING_DEPTH) uniform sampler2D depth_buffer;
layout(set = 0, binding = TYN_EPIPOLAR_BINDING_SHADOW_MAPS) uniform sampler2D shadow_maps[TYN_MAX_SHADOW_MAPS];
// (entry.xy, exit.xy) per slice, NDC; TYN_EPIPOLAR_INVALID_COORD for a culled slice.
layout(set = 0, binding = TYN_EPIPOLAR_BINDING_SLICE_END_POINTS, rgba32f) uniform image2D slice_end_points;
// Per (sample, slice): NDC xy, view-ray length to the surface, 1 when the sample is valid. The slice
// setup reads what other threads of its group wrote: it defines TYN_COORDINATES_COHERENT.
#ifdef TYN_COORDINATES_COHERENT
layout(set = 0, binding = TYN_EPIPOLAR_BINDING_COORDINATES, rgba32f) coherent uniform image2D epipolar_coordinates;
#else
layout(set = 0, binding = TYN_EPIPOLAR_BINDING_COORDINATES, rgba32f) uniform image2D epipolar_coordinates;
#endif
// Per (sample, slice): L_in of the ray-marched sample.
layout(set = 0, binding = TYN_EPIPOLAR_BINDING_SAMPLE_SCATTERING, rgba32f) uniform image2D epipolar_scattering;
layout(set = 0, binding = TYN_EPIPOLAR_BINDING_OUT_SCATTERING, TYN_SCATTERING_TARGET_FORMAT) uniform image2D
    out_scattering;
// Nearest and farthest depth per block of tyn_shadow_block_size()² texels of each shadow map,
// map m's in rows [m · side, (m + 1) · side) (shadow_blocks.comp), for a directional light's fix-up
// and the march and fix-up of a light whose maps are walked (block_walk.glsl); 1 × 1 otherwise.
layout(set = 0, binding = TYN_EPIPOLAR_BINDING_SHADOW_BLOCKS, rg32f) uniform image2D shadow_blocks;

// A light whose view rays have no slice line, so that every sample walks its maps with the
// Reference's texel walk: a point light (six maps, whose frusta cut a slice's plane into pieces of
// six different lines). A directional light's cascades each have their own line per slice.
bool tyn_epipolar_walks_maps() { return frame.light_type == TYN_LIGHT_POINT; }

// The maps a slice has a line and tree in: a directional light's cascades, else map 0 (a spot
// light; a point light has none).
uint tyn_epipolar_line_maps() { return frame.light_type == TYN_LIGHT_DIRECTIONAL ? frame.shadow_map_count : 1u; }

// Texels along a block's side: a walked light's or a directional light's fix-up's.
int tyn_shadow_block_size() {
  return int(tyn_epipolar_walks_maps() ? TYN_EPIPOLAR_WALKED_SHADOW_BLOCK : TYN_EPIPOLAR_SHADOW_BLOCK);
}
// The pixels the unwarp could not interpolate, listed by 2×2 quad of the L_in target: an entry per
// quad with any, so that the list a target must hold room for is a byte a pixel. Counts first (read
// back for the stats): the quads listed, the pixels they flag.
layout(set = 0, binding = TYN_EPIPOLAR_BINDING_FIXUP_LIST, std430) buffer FixupList {
  uint fixup_count;
  uint fixup_pixel_count;
  uint fixup_quads[];
};

// A fix-up entry: the quad's x | y << 14 | its flagged pixels << 28, bit (y & 1) · 2 + (x & 1) for
// target pixel (x, y). 14 bits hold quads of targets up to 32768 pixels a side, twice the
// maxImageDimension2D of common devices.
uint tyn_fixup_quad_entry(uvec2 quad, uint mask) { return quad.x | (quad.y << 14) | (mask << 28); }
bool tyn_fixup_quad_flags(uint entry, uint bit) { return ((entry >> (28u + bit)) & 1u) != 0u; }
uvec2 tyn_fixup_quad_pixel(uint entry, uint bit) {
  return uvec2(((entry & 0x3fffu) << 1) + (bit & 1u), (((entry >> 14) & 0x3fffu) << 1) + (bit >> 1));
}
// VkDispatchIndirectCommand for the fix-up pass, then one for the shadow-map blocks pass, which
// runs (and the fix-up walks the blocks) only where the unwarp finds it worth its cost.
layout(set = 0, binding = TYN_EPIPOLAR_BINDING_FIXUP_ARGS, std430) buffer FixupArgs {
  uint fixup_groups[3];
  uint shadow_block_groups[3];
};
// Per (sample, slice): the ray-marched samples it is interpolated from, left | right << 16
// (both equal to the sample itself when it is ray-marched; TYN_EPIPOLAR_NO_SOURCE if invalid).
layout(set = 0, binding = TYN_EPIPOLAR_BINDING_INTERPOLATION_SOURCE, r32ui) uniform uimage2D interpolation_source;
// Per (slice, map): where the slice's line starts in that shadow map's UV and its unit direction
// (yusov2013 "Slice UV origin & direction"), TYN_EPIPOLAR_INVALID_COORD when tyn_slice_shadow_uv
// found none; row m for map m (a cascade, yusov2013's cascaded version; one row otherwise).
layout(set = 0, binding = TYN_EPIPOLAR_BINDING_SLICE_UV, rgba32f) uniform image2D slice_uv;
// One row per (slice, map): its 1D min/max binary tree, level after level (min_max_tree.h's
// layout), at tyn_epipolar_tree_row.
layout(set = 0, binding = TYN_EPIPOLAR_BINDING_MIN_MAX_TREE, rg16) uniform image2D min_max_tree;
// The ray-marching samples the refinement chose, sample | slice << 16, with their count (read back
// for the stats) and the VkDispatchIndirectCommands that run the passes over them: marching a
// compact list keeps every lane busy, where a thread per (sample, slice) would idle all but one in
// `initial step`. The slice setup lists [0, n0); with a tree, shadow_test.comp lists those not in
// shadow again at [n0, n1) and round 1 marches them, else round 1 marches [0, n0); round 2 (the
// samples refine_intensity.comp adds) marches what follows. Each producer's last workgroup starts
// the next range (dispatch_chain.glsl). The header is 18 words (kMarchHeaderWords in
// epipolar_technique.cpp), zeroed every frame.
layout(set = 0, binding = TYN_EPIPOLAR_BINDING_MARCH_LIST, std430) buffer MarchList {
  uint test_groups[3];     // the shadow test's dispatch (slice_setup.comp)
  uint round_groups[6];    // march round 1's dispatch, then round 2's
  uint march_count;        // entries so far
  uint march_first;        // first entry of the current round
  uint march_round_end;    // entries when the current round started (the next round's first)
  uint march_shadowed;     // samples shadow_test.comp found in shadow along their whole ray
  uint march_listed;       // the refinement's entries, which shadow_test.comp lists again (or not)
  uint groups_done[4];     // workgroups finished per producing pass (dispatch_chain.glsl)
  uint march_samples[];
};

// The light-colour texture (common/light_color.glsl); a white texel when the frame has none.
layout(set = 0, binding = TYN_EPIPOLAR_BINDING_LIGHT_COLOR) uniform sampler2D light_color;
// The spot and point lights' semi-analytic scattering table (epipolar/scattering_lut.h), built by
// scattering_lut.comp when the medium changes; a 1×1 placeholder before a local light needs it.
layout(set = 0, binding = TYN_EPIPOLAR_BINDING_SCATTERING_LUT, rgba32f) uniform image2D scattering_lut;
// One slice's prefix sums of the light-colour texture along its line (light_color_sums.h's
// layout), rebuilt every frame that has a light-colour texture; 1 × 1 otherwise.
layout(set = 0, binding = TYN_EPIPOLAR_BINDING_LIGHT_COLOR_SUMS, rgba32f) uniform image2D light_color_sums;
// The debug view (DebugView), bound only for the debug passes.
layout(set = 0, binding = TYN_EPIPOLAR_BINDING_DEBUG_IMAGE, rgba32f) uniform writeonly image2D debug_image;

layout(push_constant, std430) uniform EpipolarBlock { EpipolarConstants epipolar; };

#include "common/shadow_ray.glsl"
#include "common/view_ray.glsl"
#include "epipolar/epipolar_geometry.h"

vec2 tyn_output_extent() { return vec2(frame.output_extent); }

// Whether the output pixel centre at `ndc` lies within `radius` pixels of the epipole (on screen or
// just off it; a light at infinity has none): EpipolarConstants::epipole_block_radius for the epipole
// block, epipole_walk_radius for its part that the fix-up walks texel by texel.
bool tyn_near_epipole(vec2 ndc, float radius) {
  return epipolar.epipole.z > 1e-6 && length((ndc - tyn_epipole_ndc(epipolar.epipole)) * 0.5 * tyn_output_extent()) <= radius;
}

// The tree image's row of a slice's tree in map `map`: the slices' rows of map 0, then of map 1, ….
int tyn_epipolar_tree_row(int slice, uint map) { return int(map * epipolar.slice_count) + slice; }

// Depth of a texel of a map a slice's line runs in (the spot light's map, a cascade), 1 (no
// occluder) outside the map: min_max_tree.h's TYN_MIN_MAX_SHADOW_TEXEL.
float tyn_epipolar_shadow_texel(uint map, ivec2 texel) {
  int size = int(frame.shadow_map_size);
  if (any(lessThan(texel, ivec2(0))) || any(greaterThanEqual(texel, ivec2(size)))) return 1.0;
  return tyn_shadow_texel(map, texel);
}

// The plane of the surface at a pixel of the depth buffer (epipolar_geometry.h, "The surface around
// a pixel"): slopes per pixel along x and y. The tolerance is the bilateral threshold in both
// passes that use it, so that a sample's depth (slice_setup.comp) and the unwarp's expectation of
// it (unwarp.comp) come from the same plane.
vec2 tyn_epipolar_depth_range() {
  return vec2(min(frame.near_ndc_depth, frame.far_ndc_depth), max(frame.near_ndc_depth, frame.far_ndc_depth));
}

vec2 tyn_epipolar_depth_slopes(ivec2 pixel, float depth) {
  ivec2 last = ivec2(frame.output_extent) - 1;
  // View z from depth: the z and w rows of clip_to_view (column-major: [column][row]) at this
  // pixel's x, y. The neighbours' x, y differ, but a perspective or orthographic projection's z
  // and w rows do not depend on x, y (an oblique one's would, slightly, over three pixels).
  vec2 ndc = tyn_ndc_from_pixel(vec2(pixel) + 0.5, vec2(frame.output_extent));
  mat4 inverse = frame.clip_to_view;
  vec4 to_view_z = vec4(inverse[2][2], inverse[0][2] * ndc.x + inverse[1][2] * ndc.y + inverse[3][2],
                        inverse[2][3], inverse[0][3] * ndc.x + inverse[1][3] * ndc.y + inverse[3][3]);
  vec2 range = tyn_epipolar_depth_range();
  vec2 slopes;
  for (int a = 0; a < 2; ++a) {
    ivec2 axis = a == 0 ? ivec2(1, 0) : ivec2(0, 1);
    float lo[3];  // one, two, three pixels before along the axis
    float hi[3];  // and after
    for (int i = 0; i < 3; ++i) {
      lo[i] = texelFetch(depth_buffer, clamp(pixel - (i + 1) * axis, ivec2(0), last), 0).r;
      hi[i] = texelFetch(depth_buffer, clamp(pixel + (i + 1) * axis, ivec2(0), last), 0).r;
    }
    bvec3 before = bvec3(pixel[a] >= 1, pixel[a] >= 2, pixel[a] >= 3);
    bvec3 after = bvec3(pixel[a] + 1 <= last[a], pixel[a] + 2 <= last[a], pixel[a] + 3 <= last[a]);
    slopes[a] = tyn_depth_plane_slope(lo[2], lo[1], lo[0], depth, hi[0], hi[1], hi[2], before, after, to_view_z,
                                      range, epipolar.bilateral_depth_threshold);
  }
  return slopes;
}

// Depth-buffer value of that plane `offset` pixels from the pixel's centre.
float tyn_epipolar_depth_at(float depth, vec2 slopes, vec2 offset) {
  return tyn_depth_on_plane(depth, slopes, offset, tyn_epipolar_depth_range());
}

#endif
