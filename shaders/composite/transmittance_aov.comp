#version 460
// The T AOV (FrameDesc::transmittanceOutput): exp(−σ_t s) per pixel, the composite's own factor
// (common/view_ray.glsl), written to a storage image that is then copied to the host's image.
#extension GL_GOOGLE_include_directive : require

#include "common/shared_constants.h"

layout(local_size_x = TYN_PIXEL_GROUP_SIZE, local_size_y = TYN_PIXEL_GROUP_SIZE) in;

layout(set = 0, binding = TYN_BINDING_FRAME, std140) uniform FrameBlock { FrameConstants frame; };
layout(set = 0, binding = TYN_BINDING_DEPTH) uniform sampler2D depth_buffer;
layout(set = 0, binding = TYN_COMPOSITE_BINDING_TARGET, rgba32f) uniform writeonly image2D out_transmittance;

#include "common/view_ray.glsl"

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(pixel, frame.output_extent))) return;
  float depth = texelFetch(depth_buffer, ivec2(pixel), 0).r;
  imageStore(out_transmittance, ivec2(pixel), vec4(tyn_view_transmittance(pixel, depth), 1.0));
}
