#version 460
// Several lights: one additional light's L_in (its technique's target) added to the frame's L_in
// target, texel by texel, at the targets' resolution.
#extension GL_GOOGLE_include_directive : require

#include "common/shared_constants.h"

layout(local_size_x = TYN_PIXEL_GROUP_SIZE, local_size_y = TYN_PIXEL_GROUP_SIZE) in;

layout(set = 0, binding = TYN_LIGHT_SUM_BINDING_SUM, rgba32f) uniform image2D sum;
layout(set = 0, binding = TYN_LIGHT_SUM_BINDING_LIGHT, rgba32f) uniform readonly image2D light;

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, imageSize(sum)))) return;
  imageStore(sum, texel, imageLoad(sum, texel) + imageLoad(light, texel));
}
