#version 460
// The epipole block (klehm2014 Fig. 8): near the epipole view rays run almost along light rays,
// where a rectified map has the least resolution, so the pixels of the block are ray-marched one by
// one with the Reference's texel walk (the same shader code as the Reference and the epipolar
// fix-up). The transmittance was written by the evaluation; only L_in is replaced.
#extension GL_GOOGLE_include_directive : require

#include "prefiltered/prefiltered_common.glsl"
#include "reference/reference_march.glsl"

layout(local_size_x = TYN_PF_TEXEL_GROUP, local_size_y = TYN_PF_TEXEL_GROUP) in;

void main() {
  ivec2 pixel = fixup_args.rect.xy + ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, fixup_args.rect.zw))) return;
  float depth = texelFetch(depth_buffer, pixel, 0).r;
  TynViewRay ray = tyn_view_ray(uvec2(pixel), depth);
  vec3 in_scattering = tyn_reference_in_scattering(ray.origin, ray.direction, ray.surface_distance);
  imageStore(out_scattering, pixel, vec4(in_scattering, 0.0));
}
