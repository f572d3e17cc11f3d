#version 460
// The epipole block (klehm2014 Fig. 8): near the epipole view rays run almost along light rays,
// where a rectified map has the least resolution, so the pixels of the block are ray-marched one by
// one with the Reference's texel walk (the same shader code as the Reference and the epipolar
// fix-up). Only L_in is replaced: the composite computes T.
#extension GL_GOOGLE_include_directive : require

#include "prefiltered/prefiltered_common.glsl"
#include "common/split_march.glsl"

// One workgroup per pixel of the block sharing its ray (common/split_march.glsl): the block is
// a few thousand pixels, too few to keep a GPU busy with one long walk each.
layout(local_size_x = TYN_SPLIT_MARCH_PARTS) in;

void main() {
  ivec2 pixel = fixup_args.rect_lo + ivec2(gl_WorkGroupID.xy);
  if (any(greaterThanEqual(pixel, fixup_args.rect_hi))) return;
  uvec2 output_pixel = tyn_output_pixel(uvec2(pixel));  // the block is in L_in target pixels
  float depth = texelFetch(depth_buffer, ivec2(output_pixel), 0).r;
  TynViewRay ray = tyn_view_ray(output_pixel, depth);
  vec3 in_scattering = tyn_split_in_scattering(ray.origin, ray.direction, ray.surface_distance);
  if (gl_LocalInvocationID.x == 0u) imageStore(out_scattering, pixel, tyn_target_value(in_scattering));
}
