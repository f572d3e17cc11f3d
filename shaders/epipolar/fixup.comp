#version 460
// Fix-up: pixels the unwarp could not interpolate are ray-marched with the Reference's walk (the
// brute-force path and the fix-up run the same code; a point light's lit sections come from the
// semi-analytic table instead of quadrature per texel), one workgroup per pixel sharing its ray
// (reference/split_march.glsl): there are few such pixels, and one thread each would leave a GPU
// idle while a few long walks finish. fixup_args.comp caps the groups at the dispatch limit, so a
// group takes every gl_NumWorkGroups.x-th pixel of the list.
#extension GL_GOOGLE_include_directive : require
#include "epipolar/epipolar_common.glsl"
// A point light's lit sections from the semi-analytic table (reference_march.glsl).
#define TYN_WALK_LIT_SECTIONS
#include "reference/split_march.glsl"
#define TYN_SCATTERING_LUT_FETCH(texel) imageLoad(scattering_lut, texel).rgb
#define TYN_SCATTERING_LUT_FRAME
#include "epipolar/scattering_lut.h"

layout(local_size_x = TYN_SPLIT_MARCH_PARTS) in;

void main() {
  for (uint index = gl_WorkGroupID.x; index < fixup_count; index += gl_NumWorkGroups.x) {
    uint packed = fixup_pixels[index];
    uvec2 pixel = uvec2(packed & 0xffffu, packed >> 16);
    float depth = texelFetch(depth_buffer, ivec2(pixel), 0).r;
    TynViewRay ray = tyn_view_ray(pixel, depth);
    vec3 in_scattering = tyn_split_in_scattering(ray.origin, ray.direction, ray.surface_distance);
    if (gl_LocalInvocationID.x == 0u) imageStore(out_scattering, ivec2(pixel), vec4(in_scattering, 0.0));
  }
}
