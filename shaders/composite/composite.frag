#version 460
// out = in · T + L_in in one pass with dual-source blending: source 0 carries L_in (added with
// factor ONE), source 1 carries T (the destination factor SRC1_COLOR). The back buffer's alpha
// is kept. Works for any blendable format, sRGB ones included (blending happens in linear).
// T = exp(−σ_t s) comes from the depth buffer here rather than from a target a technique wrote:
// it is exact per pixel whatever the technique, and an output-sized RGBA32F target (16 bytes a
// pixel) is not needed for it.
#extension GL_GOOGLE_include_directive : require

#include "common/shared_constants.h"

layout(set = 0, binding = TYN_BINDING_FRAME, std140) uniform FrameBlock { FrameConstants frame; };
layout(set = 0, binding = TYN_BINDING_DEPTH) uniform sampler2D depth_buffer;
layout(set = 0, binding = TYN_COMPOSITE_BINDING_TARGET) uniform sampler2D in_scattering;

#include "common/view_ray.glsl"
#include "composite/upsample.glsl"

layout(location = 0, index = 0) out vec4 out_add;
layout(location = 0, index = 1) out vec4 out_multiply;

void main() {
  uvec2 pixel = uvec2(gl_FragCoord.xy);
  float depth = texelFetch(depth_buffer, ivec2(pixel), 0).r;
  out_add = vec4(tyn_upsampled_in_scattering(pixel, depth), 0.0);
  out_multiply = vec4(tyn_view_transmittance(pixel, depth), 1.0);
}
