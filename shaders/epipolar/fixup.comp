#version 460
// Fix-up: pixels the unwarp could not interpolate are ray-marched with the Reference's walk (the
// brute-force path and the fix-up run the same code; a point light's lit sections come from the
// semi-analytic table instead of quadrature per texel). On a GPU one workgroup walks each pixel's
// ray together (common/split_march.glsl): there are few such pixels, and one thread each would
// leave the GPU idle while a few long walks finish. A CPU driver has no idle lanes to fill and pays
// for the split (64 partial walks, each finding its start, and the barriers between them): there a
// directional light's pixels are walked one per thread, as in the Reference (epipolar_technique.cpp,
// serialFixup, says when). The unwarp sizes the dispatch for either and caps the groups at the
// dispatch limit, so the groups stride over the rest of the list. With EpipolarSettings::fixupSteps
// the walk is replaced by that many steps per map (fixup_steps.glsl), shared by the same threads.
#extension GL_GOOGLE_include_directive : require
#include "epipolar/epipolar_common.glsl"
// The texel walk's hooks (common/texel_walk.glsl). A point light's lit sections from the
// semi-analytic table.
#define TYN_WALK_LIT_SECTIONS
// A directional light's maps (its cascades) and a point light's six crossed block by block where a
// block decides all its texels.
#define TYN_WALK_SHADOW_BLOCKS
// EpipolarSettings::fixupSteps > 0: N steps per map instead of the texel walk.
#define TYN_WALK_IN_STEPS
#include "common/split_march.glsl"
#include "epipolar/block_walk.glsl"
#include "epipolar/fixup_steps.glsl"

// Whether this frame built the blocks: a walked light's (point) before the march,
// whenever the frame has a block image; a directional light's where the unwarp found them worth
// building.
bool tyn_shadow_blocks_built() {
  return tyn_epipolar_walks_maps() ? epipolar.shadow_block_side != 0u : shadow_block_groups[0] != 0u;
}
#define TYN_SCATTERING_LUT_FETCH(texel) imageLoad(scattering_lut, texel).rgb
#define TYN_SCATTERING_LUT_FRAME
#include "epipolar/scattering_lut.h"

// One thread per pixel, or the whole workgroup per pixel.
layout(constant_id = 3) const bool TYN_FIXUP_SERIAL = false;

layout(local_size_x = TYN_SPLIT_MARCH_PARTS) in;

// L_in of a listed pixel of the L_in target; `writer`: the thread that stores it.
void fix_up(uvec2 pixel, bool writer) {
  uvec2 output_pixel = tyn_output_pixel(pixel);
  float depth = texelFetch(depth_buffer, ivec2(output_pixel), 0).r;
  TynViewRay ray = tyn_view_ray(output_pixel, depth);
  // A ray next to the epipole passes close to a local light, where in-scattering peaks as 1/b for
  // a passing distance b and the pixel outshines the frame many times over. Occluders next to the
  // lamp cut that peak finer than the steps' one verdict each resolves, so those rays take the
  // texel walk, as the Reference does; the steps serve the other listed pixels.
  bool peak = TYN_LIGHT_TYPE != TYN_LIGHT_DIRECTIONAL &&
              tyn_near_epipole(tyn_ndc_from_pixel(vec2(output_pixel) + 0.5, tyn_output_extent()),
                               epipolar.epipole_walk_radius);
  tyn_fixup_pixel_steps = peak ? 0u : epipolar.fixup_steps;
  vec3 in_scattering = TYN_FIXUP_SERIAL ? tyn_reference_in_scattering(ray.origin, ray.direction, ray.surface_distance)
                                        : tyn_split_in_scattering(ray.origin, ray.direction, ray.surface_distance);
  if (writer) imageStore(out_scattering, ivec2(pixel), tyn_target_value(in_scattering));
}

// Serial: the group's quads' flagged pixels as slots (entry · 4 + bit), and their count.
shared uint group_slots[4u * TYN_SPLIT_MARCH_PARTS];
shared uint group_pixel_count;

void main() {
  if (TYN_FIXUP_SERIAL) {
    // The group takes a quad per thread and walks their flagged pixels a thread each, so that no
    // lane idles on a quad's unflagged pixels (neighbouring lanes take neighbouring pixels).
    uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
    for (uint first = gl_WorkGroupID.x * gl_WorkGroupSize.x; first < fixup_count; first += stride) {
      if (gl_LocalInvocationIndex == 0u) group_pixel_count = 0u;
      barrier();
      uint index = first + gl_LocalInvocationIndex;
      if (index < fixup_count) {
        uint entry = fixup_quads[index];
        uint slot = atomicAdd(group_pixel_count, bitCount(entry >> 28));
        for (uint bit = 0u; bit < 4u; ++bit) {
          if (tyn_fixup_quad_flags(entry, bit)) group_slots[slot++] = index * 4u + bit;
        }
      }
      barrier();
      for (uint i = gl_LocalInvocationIndex; i < group_pixel_count; i += gl_WorkGroupSize.x) {
        uint listed = group_slots[i];
        fix_up(tyn_fixup_quad_pixel(fixup_quads[listed >> 2], listed & 3u), true);
      }
      barrier();  // the pixels read before the next quads overwrite them
    }
  } else {
    // The whole workgroup walks one pixel at a time, striding over four slots per listed quad, one
    // per pixel (skipping those the quad does not flag): the loop and the test are uniform across
    // the group (barriers inside).
    for (uint slot = gl_WorkGroupID.x; slot < 4u * fixup_count; slot += gl_NumWorkGroups.x) {
      uint entry = fixup_quads[slot >> 2];
      if (tyn_fixup_quad_flags(entry, slot & 3u)) {
        fix_up(tyn_fixup_quad_pixel(entry, slot & 3u), gl_LocalInvocationID.x == 0u);
      }
    }
  }
}
