#version 460
// Fix-up: pixels the unwarp could not interpolate are ray-marched one by one with the
// Reference's walk (the brute-force path and the fix-up run the same code).
#extension GL_GOOGLE_include_directive : require
#include "epipolar/epipolar_common.glsl"
#include "reference/reference_march.glsl"

layout(local_size_x = TYN_EPIPOLAR_FIXUP_GROUP) in;

void main() {
  uint index = gl_GlobalInvocationID.x;
  if (index >= fixup_count) return;
  uint packed = fixup_pixels[index];
  uvec2 pixel = uvec2(packed & 0xffffu, packed >> 16);
  float depth = texelFetch(depth_buffer, ivec2(pixel), 0).r;
  TynViewRay ray = tyn_view_ray(pixel, depth);
  vec3 in_scattering = tyn_reference_in_scattering(ray.origin, ray.direction, ray.surface_distance);
  imageStore(out_scattering, ivec2(pixel), vec4(in_scattering, 0.0));
}
