#version 460
// The L_in AOV (FrameDesc::scatteringOutput) of a frame whose L_in target is at reduced
// resolution or in half floats: every output pixel's L_in as the composite added it
// (composite/upsample.glsl), into a full-resolution, full-float storage image that is then copied
// to the host's image. It binds like the compute
// composite, the output in the back buffer's place.
#extension GL_GOOGLE_include_directive : require

#include "common/shared_constants.h"

layout(local_size_x = TYN_PIXEL_GROUP_SIZE, local_size_y = TYN_PIXEL_GROUP_SIZE) in;

layout(set = 0, binding = TYN_BINDING_FRAME, std140) uniform FrameBlock { FrameConstants frame; };
layout(set = 0, binding = TYN_BINDING_DEPTH) uniform sampler2D depth_buffer;
layout(set = 0, binding = TYN_COMPOSITE_BINDING_TARGET) uniform sampler2D in_scattering;
layout(set = 0, binding = TYN_COMPOSITE_BINDING_COLOR, rgba32f) uniform writeonly image2D out_scattering;

#include "common/view_ray.glsl"
#include "composite/upsample.glsl"

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(pixel, frame.output_extent))) return;
  float depth = texelFetch(depth_buffer, ivec2(pixel), 0).r;
  imageStore(out_scattering, ivec2(pixel), vec4(tyn_upsampled_in_scattering(pixel, depth), 0.0));
}
