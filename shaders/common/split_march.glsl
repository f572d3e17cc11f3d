// One view ray's L_in walked by a whole workgroup: each of the TYN_SPLIT_MARCH_PARTS threads walks
// one equal length of the ray's stretch in the shadow map (tyn_reference_in_scattering_part,
// common/texel_walk.glsl) and the parts are summed in shared memory. For the passes that march
// only a few pixels (the epipolar fix-up, the prefiltered epipole block): one thread per pixel would
// leave a GPU nearly idle while a few long serial walks finish. The result differs from one
// thread's walk only by rounding. A CPU driver gains nothing from the split and pays for each
// part's setup and the barriers: the epipolar fix-up walks a directional light's rays whole there
// (epipolar/fixup.comp). Needs the workgroup's size to be TYN_SPLIT_MARCH_PARTS along x and is
// called by every thread of the workgroup (it synchronises them). Include the walk's hooks
// (common/texel_walk.glsl) before this file.
#ifndef TYNDALL_SPLIT_MARCH_GLSL
#define TYNDALL_SPLIT_MARCH_GLSL

#include "common/texel_walk.glsl"

shared vec3 tyn_split_march_parts[TYN_SPLIT_MARCH_PARTS];

vec3 tyn_split_in_scattering(vec3 origin, vec3 dir, float s) {
  uint part = gl_LocalInvocationID.x;
  tyn_split_march_parts[part] = tyn_reference_in_scattering_part(origin, dir, s, part, TYN_SPLIT_MARCH_PARTS);
  barrier();
  for (uint stride = TYN_SPLIT_MARCH_PARTS / 2u; stride > 0u; stride /= 2u) {
    if (part < stride) tyn_split_march_parts[part] += tyn_split_march_parts[part + stride];
    barrier();
  }
  vec3 sum = tyn_split_march_parts[0];
  // The next call's first write must wait until every thread has read the sum.
  barrier();
  return sum;
}

#endif
