// Several lights: one additional light's L_in (its technique's target) added to the frame's L_in
// target, texel by texel, at the targets' resolution. Each target has its technique's format
// (common/scattering_target.glsl): the includer defines TYN_LIGHT_SUM_FORMAT (the frame's) and
// TYN_LIGHT_FORMAT (the light's).
#ifndef TYNDALL_LIGHT_SUM_GLSL
#define TYNDALL_LIGHT_SUM_GLSL

#include "common/shared_constants.h"

layout(local_size_x = TYN_PIXEL_GROUP_SIZE, local_size_y = TYN_PIXEL_GROUP_SIZE) in;

layout(set = 0, binding = TYN_LIGHT_SUM_BINDING_SUM, TYN_LIGHT_SUM_FORMAT) uniform image2D sum;
layout(set = 0, binding = TYN_LIGHT_SUM_BINDING_LIGHT, TYN_LIGHT_FORMAT) uniform readonly image2D light;

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, imageSize(sum)))) return;
  imageStore(sum, texel, imageLoad(sum, texel) + imageLoad(light, texel));
}

#endif
